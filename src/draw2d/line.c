/* line.c - draw2d stage: aliased 2D lines and sr_draw_line.  Consumes a
 * segment in pixel coordinates snapped to 1/256 px ("q8"), produces one
 * pixel per major step through a plot callback: the naive and incremental
 * DDA, the midpoint/Bresenham line as the exact diamond-exit closed form
 * of docs/raster-rules.md §7.1 (with the integer fast path for endpoints on pixel
 * centres), and wide lines.  Runs on the caller's thread.
 *
 * Conventions: y down; pixel (x, y) covers [x, x+1) x [y, y+1), centre
 * (x+1/2, y+1/2) = q8 (256x + 128).  x-major iff |dx| >= |dy|; (u, v) are
 * the (major, minor) coordinates, k and j the (major, minor) pixel
 * indices.  A minor coordinate v that falls exactly on a pixel boundary
 * belongs to the smaller index: j = ceil(v) - 1 (the D3D tie rule). */
#include "draw2d/line.h"
#include "context.h"
#include "draw2d/paint.h"
#include "target/framebuffer.h"
#include "math/wide.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef sr_i128 i128;   /* math/wide.h */

#define S ((int64_t)256)   /* q8: sub-pixel steps per pixel */
#define H ((int64_t)128)   /* half a pixel */

/* floor(a / b) and ceil(a / b) for b > 0. */
static int64_t floor_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}
static int64_t ceil_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    return (a % b != 0 && a > 0) ? q + 1 : q;
}
/* a / b rounded to nearest, halves up, for b != 0. */
static i128 round_div128(i128 a, int64_t b)
{
    if (b < 0) {
        a = sr__wide_neg(a);
        b = -b;
    }
    return sr__wide_floor_div(sr__wide_add(sr__wide_mul64(a, 2), sr__wide(b)), 2 * b);
}
static int64_t max64(int64_t a, int64_t b) { return a > b ? a : b; }
static int64_t min64(int64_t a, int64_t b) { return a < b ? a : b; }

int64_t sr__line_snap_q8(double v)
{
    return (int64_t)llrint(v * 256.0);   /* default rounding: to nearest even */
}

/* ---- the line in major/minor coordinates ------------------------------------ */

typedef struct uv_line {
    bool xmaj;
    int64_t au, av, bu, bv;    /* q8: start a, end b */
} uv_line;

static uv_line to_uv(const sr__line_q8 *l)
{
    int64_t dx = l->bx - l->ax, dy = l->by - l->ay;
    uv_line m;
    /* |dx| == |dy| is x-major (GL, VK, D3D and dEQP agree). */
    m.xmaj = llabs(dx) >= llabs(dy);
    m.au = m.xmaj ? l->ax : l->ay;
    m.av = m.xmaj ? l->ay : l->ax;
    m.bu = m.xmaj ? l->bx : l->by;
    m.bv = m.xmaj ? l->by : l->bx;
    return m;
}

/* Receives (major, minor) pixel indices. */
typedef void (*emit_fn)(void *user, int64_t k, int64_t j);

/* Major indices worth visiting: those of the clipper's part of the line
 * inside the clip rectangle grown by `margin` px, plus 2 steps each side
 * for the clipper's rounding, within the rectangle's major range.  The
 * pixels themselves are computed from the original endpoints, so this
 * range only has to be conservative. */
static bool visible_major(const sr__line_q8 *l, bool xmaj, sr__irect clip, double margin,
                          sr_line_clipper clipper, int64_t *lo, int64_t *hi)
{
    int64_t clo = xmaj ? clip.x0 : clip.y0, chi = (int64_t)(xmaj ? clip.x1 : clip.y1) - 1;
    if (clip.x1 <= clip.x0 || clip.y1 <= clip.y0) {
        return false;
    }
    if (clipper == SR__LINE_CLIP_NONE) {
        *lo = clo;
        *hi = chi;
        return true;
    }
    sr_point2 a = { (double)l->ax / 256.0, (double)l->ay / 256.0 };
    sr_point2 b = { (double)l->bx / 256.0, (double)l->by / 256.0 };
    if (!sr__clip_line(clipper, clip.x0 - margin, clip.y0 - margin, clip.x1 + margin,
                       clip.y1 + margin, &a, &b)) {
        return false;
    }
    double ua = xmaj ? a.x : a.y, ub = xmaj ? b.x : b.y;
    *lo = max64((int64_t)floor(fmin(ua, ub)) - 2, clo);
    *hi = min64((int64_t)floor(fmax(ua, ub)) + 2, chi);
    return *lo <= *hi;
}

/* ---- midpoint / Bresenham: the exact closed form ----------------------------- */

/* Does pixel q own the point p under the diamond rule?  The diamond is
 * |dx| + |dy| < 1/2 around q's centre; of its boundary it owns the lower
 * edges and the bottom corner (y down), and for y-major lines also the
 * right corner (D3D). */
static bool in_diamond(int64_t px, int64_t py, int64_t qx, int64_t qy, bool xmaj)
{
    int64_t dx = px - (qx * S + H), dy = py - (qy * S + H);
    int64_t d = llabs(dx) + llabs(dy);
    return d < H || (d == H && (dy > 0 || (!xmaj && dx == H && dy == 0)));
}

/* The pixel whose diamond owns p, if any (at most one does). */
static bool diamond_pixel(int64_t px, int64_t py, bool xmaj, int64_t *qx, int64_t *qy)
{
    int64_t fx = floor_div(px, S), fy = floor_div(py, S);
    for (int oy = -1; oy <= 1; oy++) {
        for (int ox = -1; ox <= 1; ox++) {
            if (in_diamond(px, py, fx + ox, fy + oy, xmaj)) {
                *qx = fx + ox;
                *qy = fy + oy;
                return true;
            }
        }
    }
    return false;
}

/* The pixels of the line a->b with major index in [klo, khi]: for each
 * column k whose centre c lies in [min u, max u], the pixel where the
 * line crosses the centre line u = c, j = ceil(v(c)) - 1; plus the pixel
 * whose diamond owns the start (the line exits it); minus the pixel whose
 * diamond owns the end (half-open).  Exact integer arithmetic: v(c) =
 * num / (den S) with num = a_v den + (c - a_u) dv', den = |du|. */
static void closed_form(const sr__line_q8 *l, int64_t klo, int64_t khi, emit_fn emit, void *user)
{
    if (l->ax == l->bx && l->ay == l->by) {
        return;
    }
    uv_line m = to_uv(l);
    int64_t sx, sy, ex, ey;
    bool has_s = diamond_pixel(l->ax, l->ay, m.xmaj, &sx, &sy);
    bool has_e = diamond_pixel(l->bx, l->by, m.xmaj, &ex, &ey);
    int64_t sk = m.xmaj ? sx : sy, sj = m.xmaj ? sy : sx;
    int64_t ek = m.xmaj ? ex : ey, ej = m.xmaj ? ey : ex;
    if (has_s && has_e && sk == ek && sj == ej) {
        has_s = false;   /* both ends in one diamond: added, then removed */
    }
    int64_t du = m.bu - m.au, dv = m.bv - m.av;
    int64_t den = du < 0 ? -du : du, dvn = du < 0 ? -dv : dv;
    int64_t k0 = ceil_div(min64(m.au, m.bu) - H, S), k1 = floor_div(max64(m.au, m.bu) - H, S);
    int64_t ka = max64(k0, klo), kb = min64(k1, khi);
    bool start_emitted = false;
    if (ka <= kb) {
        /* v(c) = num / D with D = den S; keep num = q D + r, 0 <= r < D.
         * Per column num grows by S dv', and |S dv'| <= D (|dv| <= |du|),
         * so one correction step keeps r in range. */
        const int64_t D = den * S, step = S * dvn;
        i128 num = sr__wide_add(sr__wide_mul(m.av, den), sr__wide_mul(ka * S + H - m.au, dvn));
        int64_t q = sr__wide_low(sr__wide_floor_div(num, D));
        int64_t r = sr__wide_low(sr__wide_sub(num, sr__wide_mul(q, D)));
        for (int64_t k = ka; k <= kb; k++) {
            int64_t j = q + (r != 0) - 1;          /* ceil(v) - 1 */
            if (!(has_e && k == ek && j == ej)) {
                emit(user, k, j);
            }
            if (has_s && k == sk && j == sj) {
                start_emitted = true;
            }
            r += step;
            if (r >= D) {
                r -= D;
                q++;
            } else if (r < 0) {
                r += D;
                q--;
            }
        }
    }
    if (has_s && !start_emitted && sk >= klo && sk <= khi) {
        emit(user, sk, sj);
    }
}

/* ---- plotting helpers ---------------------------------------------------------- */

typedef struct thin_ctx {
    bool xmaj;
    sr__irect clip;
    sr__plot_fn plot;
    void *user;
} thin_ctx;

static void emit_thin(void *user, int64_t k, int64_t j)
{
    const thin_ctx *t = user;
    int64_t x = t->xmaj ? k : j, y = t->xmaj ? j : k;
    if (x >= t->clip.x0 && x < t->clip.x1 && y >= t->clip.y0 && y < t->clip.y1) {
        t->plot(t->user, (int)x, (int)y, 1.0f);
    }
}

/* ---- midpoint / Bresenham: the integer fast path ------------------------------- */

static bool on_centre(int64_t v_q8)
{
    return floor_div(v_q8 - H, S) * S == v_q8 - H;
}

/* The textbook midpoint algorithm for endpoints on pixel centres, in all
 * eight octants: canonicalize so the major coordinate increases, reflect
 * the minor axis by s = sign(dv), then the decision variable
 * d = 2 F(midpoint) starts at 2dy - dx and grows by 2dy (step E) or
 * 2(dy - dx) (step NE).  An exact tie (d == 0: the midpoint is on the
 * line) goes to the smaller minor index, like the closed form: E when
 * s > 0, NE when s < 0.  The original end pixel is left out. */
static bool bresenham_centres(const sr__line_q8 *l, int64_t klo, int64_t khi, emit_fn emit,
                              void *user)
{
    if (!on_centre(l->ax) || !on_centre(l->ay) || !on_centre(l->bx) || !on_centre(l->by)) {
        return false;
    }
    if (l->ax == l->bx && l->ay == l->by) {
        return true;
    }
    uv_line m = to_uv(l);
    int64_t u0 = (m.au - H) / S, v0 = (m.av - H) / S, u1 = (m.bu - H) / S, v1 = (m.bv - H) / S;
    const int64_t end_k = u1;                     /* the pixel left out */
    if (u0 > u1) {
        int64_t t = u0; u0 = u1; u1 = t;
        t = v0; v0 = v1; v1 = t;
    }
    const int64_t dx = u1 - u0, dy = llabs(v1 - v0), s = v1 < v0 ? -1 : 1;
    int64_t ka = max64(u0, klo), kb = min64(u1, khi);
    if (ka > kb) {
        return true;
    }
    /* Enter at column ka (clipping): i = rows stepped so far, d = the
     * decision for column ka + 1, both from the closed form
     * i = round(n dy / dx) with the tie rule, n = ka - u0. */
    int64_t n = ka - u0;
    i128 t2 = sr__wide_add(sr__wide_mul64(sr__wide_mul(2, n), dy), sr__wide(dx));
    int64_t i = s > 0 ? sr__wide_low(sr__wide_ceil_div(t2, 2 * dx)) - 1
                      : sr__wide_low(sr__wide_floor_div(t2, 2 * dx));
    int64_t d = sr__wide_low(sr__wide_sub(sr__wide_mul64(sr__wide_mul(2, dy), n + 1),
                                          sr__wide_mul(dx, 2 * i + 1)));
    const int64_t dE = 2 * dy, dNE = 2 * (dy - dx);
    for (int64_t k = ka; k <= kb; k++) {
        if (k != end_k) {
            emit(user, k, v0 + s * i);
        }
        if (s > 0 ? d > 0 : d >= 0) {   /* NE: step the minor axis */
            i++;
            d += dNE;
        } else {                        /* E */
            d += dE;
        }
    }
    return true;
}

bool sr__line_bresenham_centres(const sr__line_q8 *l, sr__irect clip, sr_line_clipper clipper,
                                sr__plot_fn plot, void *user)
{
    uv_line m = to_uv(l);
    thin_ctx t = { m.xmaj, clip, plot, user };
    int64_t lo, hi;
    if (!on_centre(l->ax) || !on_centre(l->ay) || !on_centre(l->bx) || !on_centre(l->by)) {
        return false;
    }
    if (visible_major(l, m.xmaj, clip, 1.0, clipper, &lo, &hi)) {
        bresenham_centres(l, lo, hi, emit_thin, &t);
    }
    return true;
}

void sr__line_bresenham(const sr__line_q8 *l, sr__irect clip, sr_line_clipper clipper,
                        bool closed_form_only, sr__plot_fn plot, void *user)
{
    uv_line m = to_uv(l);
    thin_ctx t = { m.xmaj, clip, plot, user };
    int64_t lo, hi;
    if (!visible_major(l, m.xmaj, clip, 1.0, clipper, &lo, &hi)) {
        return;
    }
    if (closed_form_only || !bresenham_centres(l, lo, hi, emit_thin, &t)) {
        closed_form(l, lo, hi, emit_thin, &t);
    }
}

/* ---- DDA ------------------------------------------------------------------------- */

void sr__line_dda(const sr__line_q8 *l, bool incremental, sr__irect clip,
                  sr_line_clipper clipper, sr__plot_fn plot, void *user)
{
    if (l->ax == l->bx && l->ay == l->by) {
        return;
    }
    uv_line m = to_uv(l);
    thin_ctx t = { m.xmaj, clip, plot, user };
    int64_t du = m.bu - m.au, dv = m.bv - m.av;
    /* Steps whose centre c is in the half-open range [a_u, b_u) along
     * the direction of travel. */
    int64_t k0, k1;
    if (du > 0) {
        k0 = ceil_div(m.au - H, S);
        k1 = ceil_div(m.bu - H, S) - 1;
    } else {
        k0 = floor_div(m.bu - H, S) + 1;
        k1 = floor_div(m.au - H, S);
    }
    int64_t lo, hi;
    if (k0 > k1 || !visible_major(l, m.xmaj, clip, 1.0, clipper, &lo, &hi)) {
        return;
    }
    int64_t ka = max64(k0, lo), kb = min64(k1, hi);
    if (!incremental) {
        /* The line equation evaluated per column: v = v_a + m (u - u_a) at each centre,
         * rounded to the nearest pixel: floor(v) with centres at +1/2. */
        const double slope = (double)dv / (double)du;
        const double ua = (double)m.au / 256.0, va = (double)m.av / 256.0;
        for (int64_t k = ka; k <= kb; k++) {
            double v = va + slope * ((double)k + 0.5 - ua);
            emit_thin(&t, k, (int64_t)floor(v));
        }
        return;
    }
    /* Incremental: v += m per step, in fixed point with 32 fraction bits
     * (units of 2^-32 px), so entering at a clipped step is exact:
     * v_k = v_first + n m.  v_first = v at the first centre, rounded once;
     * m is rounded once; their error then grows by at most 2^-33 px per
     * step, which is the DDA's accumulated rounding. */
    const int64_t first = du > 0 ? k0 : k1;
    /* per step of travel */
    const i128 inc = round_div128(sr__wide_mul(dv, (int64_t)1 << 32), du > 0 ? du : -du);
    const i128 v_first = sr__wide_add(
        sr__wide_mul(m.av, 1 << 24),
        round_div128(sr__wide_mul64(sr__wide_mul(first * S + H - m.au, dv), 1 << 24), du));
    const i128 inc_k = du > 0 ? inc : sr__wide_neg(inc);       /* per +1 in k */
    i128 v = sr__wide_add(v_first, sr__wide_mul64(inc_k, ka - first));
    for (int64_t k = ka; k <= kb; k++) {
        emit_thin(&t, k, sr__wide_low(sr__wide_floor_div(v, (int64_t)1 << 32)));
        v = sr__wide_add(v, inc_k);
    }
}

/* ---- wide aliased lines --------------------------------------------------------- */

typedef struct wide_ctx {
    bool xmaj;
    int w;
    sr__irect clip;
    sr__plot_fn plot;
    void *user;
} wide_ctx;

#define WIDE_MAX 1024

/* Round caps: the runs of a cap's box, per major index. */
typedef struct cap_runs {
    int64_t k0;
    int n;
    int64_t j[2 * (WIDE_MAX + 4)];   /* first minor index of up to 2 runs */
    uint8_t count[WIDE_MAX + 4];
} cap_runs;

static void emit_run(void *user, int64_t k, int64_t j)
{
    const wide_ctx *c = user;
    int64_t mlo = c->xmaj ? c->clip.y0 : c->clip.x0, mhi = c->xmaj ? c->clip.y1 : c->clip.x1;
    int64_t klo = c->xmaj ? c->clip.x0 : c->clip.y0, khi = c->xmaj ? c->clip.x1 : c->clip.y1;
    if (k < klo || k >= khi) {
        return;
    }
    int64_t j0 = max64(j, mlo), j1 = min64(j + c->w, mhi);
    for (int64_t i = j0; i < j1; i++) {
        c->plot(c->user, (int)(c->xmaj ? k : i), (int)(c->xmaj ? i : k), 1.0f);
    }
}

static void record_run(void *user, int64_t k, int64_t j)
{
    cap_runs *c = user;
    int64_t i = k - c->k0;
    if (i >= 0 && i < c->n && c->count[i] < 2) {
        c->j[2 * i + c->count[i]++] = j;
    }
}

static bool in_disk(int64_t x, int64_t y, int64_t px, int64_t py, int64_t r_q8)
{
    int64_t dx = x * S + H - px, dy = y * S + H - py;
    return dx * dx + dy * dy <= r_q8 * r_q8;
}

/* Round cap at p: the pixels with centres in the disk of radius w/2
 * that the runs (offset line `off`) and the first cap did not draw. */
static void round_cap(const wide_ctx *c, const sr__line_q8 *off, bool has_line, int64_t px, int64_t py,
                      const int64_t *other)
{
    const int64_t r = (int64_t)c->w * H;       /* w/2 in q8 */
    int64_t x0 = max64(floor_div(px - r, S) - 1, c->clip.x0);
    int64_t x1 = min64(floor_div(px + r, S) + 1, (int64_t)c->clip.x1 - 1);
    int64_t y0 = max64(floor_div(py - r, S) - 1, c->clip.y0);
    int64_t y1 = min64(floor_div(py + r, S) + 1, (int64_t)c->clip.y1 - 1);
    if (x0 > x1 || y0 > y1) {
        return;
    }
    cap_runs runs;
    runs.k0 = c->xmaj ? x0 : y0;
    runs.n = (int)((c->xmaj ? x1 - x0 : y1 - y0) + 1);
    memset(runs.count, 0, sizeof runs.count);
    if (has_line) {
        closed_form(off, runs.k0, runs.k0 + runs.n - 1, record_run, &runs);
    }
    for (int64_t y = y0; y <= y1; y++) {
        for (int64_t x = x0; x <= x1; x++) {
            if (!in_disk(x, y, px, py, r) || (other && in_disk(x, y, other[0], other[1], r))) {
                continue;
            }
            int64_t k = c->xmaj ? x : y, j = c->xmaj ? y : x, i = k - runs.k0;
            bool in_run = false;
            for (int n = 0; n < runs.count[i]; n++) {
                in_run |= j >= runs.j[2 * i + n] && j < runs.j[2 * i + n] + c->w;
            }
            if (!in_run) {
                c->plot(c->user, (int)x, (int)y, 1.0f);
            }
        }
    }
}

void sr__line_wide(const sr__line_q8 *l, int w, sr_line_cap cap, sr__irect clip,
                   sr_line_clipper clipper, sr__plot_fn plot, void *user)
{
    if (w < 1) {
        w = 1;
    }
    if (w > WIDE_MAX) {
        w = WIDE_MAX;
    }
    if (clip.x1 <= clip.x0 || clip.y1 <= clip.y0) {
        return;
    }
    sr__line_q8 e = *l;
    bool point = l->ax == l->bx && l->ay == l->by;
    if (point) {
        if (cap == SR_LINE_CAP_SQUARE) {
            /* No direction: the w x w square of pixel centres around the
             * point, half-open like a span. */
            int64_t hw = (int64_t)w * H;
            for (int64_t y = ceil_div(l->ay - hw - H, S); y < ceil_div(l->ay + hw - H, S); y++) {
                for (int64_t x = ceil_div(l->ax - hw - H, S); x < ceil_div(l->ax + hw - H, S); x++) {
                    if (x >= clip.x0 && x < clip.x1 && y >= clip.y0 && y < clip.y1) {
                        plot(user, (int)x, (int)y, 1.0f);
                    }
                }
            }
        } else if (cap == SR_LINE_CAP_ROUND) {
            wide_ctx c = { true, w, clip, plot, user };
            round_cap(&c, l, false, l->ax, l->ay, NULL);
        }
        return;
    }
    if (cap == SR_LINE_CAP_SQUARE) {
        /* Extend by w/2 along the line, then snap again. */
        double dx = (double)(l->bx - l->ax), dy = (double)(l->by - l->ay);
        double t = (double)w * 128.0 / hypot(dx, dy);
        e.ax = l->ax - (int64_t)llrint(dx * t);
        e.ay = l->ay - (int64_t)llrint(dy * t);
        e.bx = l->bx + (int64_t)llrint(dx * t);
        e.by = l->by + (int64_t)llrint(dy * t);
    }
    uv_line m = to_uv(&e);
    /* GL wide lines: offset by -(w-1)/2 along the minor axis, exact in q8. */
    sr__line_q8 off = e;
    int64_t shift = (int64_t)(w - 1) * H;
    if (m.xmaj) {
        off.ay -= shift;
        off.by -= shift;
    } else {
        off.ax -= shift;
        off.bx -= shift;
    }
    wide_ctx c = { m.xmaj, w, clip, plot, user };
    int64_t lo, hi;
    if (visible_major(&e, m.xmaj, clip, (double)w + 2.0, clipper, &lo, &hi)) {
        closed_form(&off, lo, hi, emit_run, &c);
    }
    if (cap == SR_LINE_CAP_ROUND) {
        round_cap(&c, &off, true, l->ax, l->ay, NULL);
        const int64_t first[2] = { l->ax, l->ay };
        round_cap(&c, &off, true, l->bx, l->by, first);
    }
}

/* ---- sr_draw_line ------------------------------------------------------------------ */

typedef struct fb_plot {
    sr_framebuffer *fb;
    sr__paint paint;
} fb_plot;

static void plot_fb(void *user, int x, int y, float coverage)
{
    fb_plot *p = user;
    unsigned cov = coverage >= 1.0f ? 255u : (unsigned)(coverage * 255.0f + 0.5f);
    sr__paint_pixel(&p->paint, &p->fb->color[(size_t)y * (size_t)p->fb->width + (size_t)x], cov);
}

static const char *point_name(int i)
{
    static const char *names[4] = { "a.x", "a.y", "b.x", "b.y" };
    return names[i];
}

/* The checks and defaults sr_draw_line and sr_line_steps share: the
 * points and *d (desc with its defaults resolved), errors reported as
 * `fname`'s. */
static sr_result check_line(sr_context *ctx, const char *fname, sr_point2 a, sr_point2 b,
                            const sr_line_desc *desc, sr_line_desc *out)
{
    sr_line_desc d = desc ? *desc : (sr_line_desc){ 0 };
    const double coords[4] = { a.x, a.y, b.x, b.y };
    for (int i = 0; i < 4; i++) {
        if (!isfinite(coords[i])) {
            return sr__fail(ctx, SR_INVALID_ARG, "%s: %s is not finite", fname, point_name(i));
        }
        if (fabs(coords[i]) > SR__LINE_MAX_COORD) {
            return sr__fail(ctx, SR_TOO_LARGE, "%s: |%s| = %g exceeds %g px", fname,
                            point_name(i), fabs(coords[i]), SR__LINE_MAX_COORD);
        }
    }
    if (d.algorithm == SR_LINE_DEFAULT) {
        d.algorithm = SR_LINE_BRESENHAM;
    }
    if (d.algorithm < SR_LINE_DDA_NAIVE || d.algorithm > SR_LINE_WIDE) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_line_desc.algorithm %d is not an algorithm",
                        (int)d.algorithm);
    }
    if (d.cap == SR_LINE_CAP_DEFAULT) {
        d.cap = SR_LINE_CAP_BUTT;
    }
    if (d.cap < SR_LINE_CAP_BUTT || d.cap > SR_LINE_CAP_ROUND) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_line_desc.cap %d is not a cap", (int)d.cap);
    }
    if (d.clipper == SR_LINE_CLIP_DEFAULT) {
        d.clipper = SR_LINE_CLIP_LIANG_BARSKY;
    }
    if (d.clipper < SR_LINE_CLIP_COHEN_SUTHERLAND || d.clipper > SR_LINE_CLIP_LIANG_BARSKY) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_line_desc.clipper %d is not a clipper",
                        (int)d.clipper);
    }
    if (d.width == 0.0) {
        d.width = 1.0;
    }
    double max_width = d.algorithm == SR_LINE_WIDE ? WIDE_MAX + 0.49 : 4096.0;
    if (!(d.width > 0.0 && d.width <= max_width)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_line_desc.width must be in (0, %g] (got %g)",
                        d.algorithm == SR_LINE_WIDE ? (double)WIDE_MAX : 4096.0, d.width);
    }
    *out = d;
    return SR_OK;
}

sr_result sr_draw_line(sr_context *ctx, sr_framebuffer *fb, sr_point2 a, sr_point2 b,
                       sr_rgba color, const sr_line_desc *desc)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_draw_line: ctx is NULL");
    }
    if (!fb) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_draw_line: fb is NULL");
    }
    sr_line_desc d = { 0 };
    sr_result r = check_line(ctx, "sr_draw_line", a, b, desc, &d);
    if (r != SR_OK) {
        return r;
    }
    fb_plot p = { .fb = fb };
    if (!sr__paint_init(&p.paint, color, true)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_draw_line: color is not finite");
    }
    sr_result r2d = sr__fb_begin_2d(ctx, "sr_draw_line", fb);
    if (r2d != SR_OK) {
        return r2d;
    }
    sr__irect clip = { 0, 0, fb->width, fb->height };
    sr__line_q8 q = { sr__line_snap_q8(a.x), sr__line_snap_q8(a.y),
                      sr__line_snap_q8(b.x), sr__line_snap_q8(b.y) };
    switch (d.algorithm) {
    case SR_LINE_DDA_NAIVE:
        sr__line_dda(&q, false, clip, d.clipper, plot_fb, &p);
        break;
    case SR_LINE_DDA_INCREMENTAL:
        sr__line_dda(&q, true, clip, d.clipper, plot_fb, &p);
        break;
    case SR_LINE_WU:
        sr__line_wu(a, b, clip, d.clipper, plot_fb, &p);
        break;
    case SR_LINE_AREA:
        sr__line_area(a, b, d.width, d.cap, clip, d.clipper, plot_fb, &p);
        break;
    case SR_LINE_WIDE: {
        int w = (int)floor(d.width + 0.5);
        sr__line_wide(&q, w < 1 ? 1 : w, d.cap, clip, d.clipper, plot_fb, &p);
        break;
    }
    default:
        sr__line_bresenham(&q, clip, d.clipper, false, plot_fb, &p);
        break;
    }
    sr__ok(ctx);
    return SR_OK;
}

sr_result sr_line_steps(sr_context *ctx, int width, int height, sr_point2 a, sr_point2 b,
                        const sr_line_desc *desc, sr_line_step_fn fn, void *user)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_line_steps: ctx is NULL");
    }
    if (!fn) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_line_steps: fn is NULL");
    }
    if (width <= 0 || height <= 0) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_line_steps: width and height must be > 0 "
                        "(got %d x %d)", width, height);
    }
    sr_line_desc d = { 0 };
    sr_result r = check_line(ctx, "sr_line_steps", a, b, desc, &d);
    if (r != SR_OK) {
        return r;
    }
    if (d.algorithm != SR_LINE_WU) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_line_steps: sr_line_desc.algorithm %d has no "
                        "steps (only SR_LINE_WU)", (int)d.algorithm);
    }
    sr__line_wu_steps(a, b, (sr__irect){ 0, 0, width, height }, d.clipper, fn, user);
    sr__ok(ctx);
    return SR_OK;
}

sr_result sr_line_area_pixels(sr_context *ctx, int width, int height, sr_point2 a, sr_point2 b,
                              const sr_line_desc *desc, sr_line_area_fn fn, void *user)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_line_area_pixels: ctx is NULL");
    }
    if (!fn) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_line_area_pixels: fn is NULL");
    }
    if (width <= 0 || height <= 0) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_line_area_pixels: width and height must be "
                        "> 0 (got %d x %d)", width, height);
    }
    sr_line_desc d = { 0 };
    sr_result r = check_line(ctx, "sr_line_area_pixels", a, b, desc, &d);
    if (r != SR_OK) {
        return r;
    }
    if (d.algorithm != SR_LINE_AREA) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_line_area_pixels: sr_line_desc.algorithm %d "
                        "is not SR_LINE_AREA", (int)d.algorithm);
    }
    sr_point2 *strip = sr__alloc(ctx, SR__LINE_AREA_STRIP_MAX * sizeof *strip);
    if (!strip) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_line_area_pixels: out of memory");
    }
    sr__line_area_cells(a, b, d.width, d.cap, (sr__irect){ 0, 0, width, height }, d.clipper, fn,
                        user, strip);
    sr__free(ctx, strip);
    sr__ok(ctx);
    return SR_OK;
}
