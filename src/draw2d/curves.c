/* curves.c - draw2d stage: curves.  Midpoint ellipses and circles
 * (aliased, outline or filled), implicit regions F(x, y) < 0 from a
 * callback (aliased or antialiased by F / |grad F|), and the flattening of
 * quadratic and cubic Beziers by forward differencing and of SVG
 * elliptical arcs.  Consumes curve parameters, produces pixels or point
 * lists.  Caller's thread only. */
#include "context.h"
#include "draw2d/arc.h"
#include "draw2d/paint.h"
#include "math/wide.h"

#include <math.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* 128-bit integers for the ellipse decision variable (math/wide.h): with
 * centre and radii in q8 below 2^27, (x - cx)^2 < 2^56 and ry^2 < 2^54,
 * so every term of F stays below 2^111. */
typedef sr_i128 i128;

#define Q8_ONE 256
#define MAX_FLATTEN_STEPS (1 << 16)

static int64_t floor_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    if ((a % b != 0) && (a < 0)) {
        q--;
    }
    return q;
}

/* ---- midpoint ellipse ---------------------------------------------------- */

typedef struct ellipse_q8 {
    int64_t cx, cy;   /* centre, q8 */
    int64_t a, b;     /* F = a dx^2 + b dy^2 - c, a = ry^2, b = rx^2, c = rx^2 ry^2 */
    i128 c;
} ellipse_q8;

/* The decision variable at pixel (i, j)'s centre, with dx of that centre. */
typedef struct decision {
    i128 f;
    int64_t dx;
} decision;

static decision decide(const ellipse_q8 *e, int64_t i, int64_t j)
{
    int64_t dx = i * Q8_ONE + Q8_ONE / 2 - e->cx, dy = j * Q8_ONE + Q8_ONE / 2 - e->cy;
    decision d = { sr__wide_sub(sr__wide_add(sr__wide_mul(e->a, dx * dx), sr__wide_mul(e->b, dy * dy)), e->c), dx };
    return d;
}

/* Forward differences in x: F(dx + 256) - F(dx) = a (512 dx + 65536). */
static void step_right(const ellipse_q8 *e, decision *d)
{
    d->f = sr__wide_add(d->f, sr__wide_mul(e->a, 2 * Q8_ONE * d->dx + Q8_ONE * Q8_ONE));
    d->dx += Q8_ONE;
}

static void step_left(const ellipse_q8 *e, decision *d)
{
    d->dx -= Q8_ONE;
    d->f = sr__wide_sub(d->f, sr__wide_mul(e->a, 2 * Q8_ONE * d->dx + Q8_ONE * Q8_ONE));
}

/* Inside pixels of row j: lo..hi (false when none).  Walks from the
 * previous row's ends (hint_lo/hi; the span is an interval around the
 * centre column ic), so the whole ellipse costs O(perimeter) steps. */
static bool ellipse_row(const ellipse_q8 *e, int64_t j, int64_t ic, bool have_hint,
                        int64_t hint_lo, int64_t hint_hi, int64_t *lo, int64_t *hi)
{
    decision centre = decide(e, ic, j);
    if (!sr__wide_negative(centre.f)) {
        return false;
    }
    int64_t i = have_hint && hint_lo < ic ? hint_lo : ic;
    decision d = decide(e, i, j);
    if (sr__wide_negative(d.f)) {
        for (;;) { /* extend left while the next pixel is inside */
            decision t = d;
            step_left(e, &t);
            if (!sr__wide_negative(t.f)) {
                break;
            }
            d = t;
            i--;
        }
    } else {
        while (!sr__wide_negative(d.f)) {
            step_right(e, &d);
            i++;
        }
    }
    *lo = i;
    i = have_hint && hint_hi > ic ? hint_hi : ic;
    d = decide(e, i, j);
    if (sr__wide_negative(d.f)) {
        for (;;) {
            decision t = d;
            step_right(e, &t);
            if (!sr__wide_negative(t.f)) {
                break;
            }
            d = t;
            i++;
        }
    } else {
        while (!sr__wide_negative(d.f)) {
            step_left(e, &d);
            i--;
        }
    }
    *hi = i;
    return true;
}

typedef struct row_span { bool any; int64_t lo, hi; } row_span;

static void paint_clipped(const sr__paint *p, sr_framebuffer *fb, int64_t y, int64_t x0,
                          int64_t x1 /* inclusive */)
{
    if (y < 0 || y >= fb->height) {
        return;
    }
    if (x0 < 0) {
        x0 = 0;
    }
    if (x1 >= fb->width) {
        x1 = fb->width - 1;
    }
    if (x0 <= x1) {
        sr__paint_span(p, fb, (int)y, (int)x0, (int)x1 + 1);
    }
}

/* Outline pixels of row `cur`: its span minus the pixels whose four
 * neighbours are all inside, i.e. minus [max(lo)+.., min(hi)-..] of the
 * rows above and below, shrunk by one at each end. */
static void paint_outline_row(const sr__paint *p, sr_framebuffer *fb, int64_t y,
                              const row_span *up, const row_span *cur, const row_span *down)
{
    if (!cur->any) {
        return;
    }
    if (!up->any || !down->any) {
        paint_clipped(p, fb, y, cur->lo, cur->hi);
        return;
    }
    int64_t in_lo = cur->lo + 1, in_hi = cur->hi - 1;
    int64_t l = up->lo > down->lo ? up->lo : down->lo;
    int64_t r = up->hi < down->hi ? up->hi : down->hi;
    if (l > in_lo) {
        in_lo = l;
    }
    if (r < in_hi) {
        in_hi = r;
    }
    if (in_lo > in_hi) {
        paint_clipped(p, fb, y, cur->lo, cur->hi);
        return;
    }
    paint_clipped(p, fb, y, cur->lo, in_lo - 1);
    paint_clipped(p, fb, y, in_hi + 1, cur->hi);
}

static bool coord_ok(double v)
{
    return isfinite(v) && fabs(v) <= SR_MAX_COORD2D;
}

sr_result sr_draw_ellipse(sr_context *ctx, sr_framebuffer *fb, double cx, double cy, double rx,
                          double ry, sr_rgba color, bool filled)
{
    static const char fn[] = "sr_draw_ellipse";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_draw_ellipse: ctx is NULL");
    }
    if (!fb) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: fb is NULL", fn);
    }
    if (!coord_ok(cx) || !coord_ok(cy)) {
        return sr__fail(ctx, isfinite(cx) && isfinite(cy) ? SR_TOO_LARGE : SR_INVALID_ARG,
                        "%s: centre (%g, %g) must be finite and within +-%g", fn, cx, cy,
                        SR_MAX_COORD2D);
    }
    if (!(rx >= 0) || !(ry >= 0) || !coord_ok(rx) || !coord_ok(ry)) {
        return sr__fail(ctx, isfinite(rx) && isfinite(ry) && rx >= 0 && ry >= 0
                                 ? SR_TOO_LARGE : SR_INVALID_ARG,
                        "%s: radii (%g, %g) must be in 0..%g", fn, rx, ry, SR_MAX_COORD2D);
    }
    sr__paint paint;
    if (!sr__paint_init(&paint, color, false)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: color is not finite", fn);
    }
    sr_result r2d = sr__fb_begin_2d(ctx, fn, fb);
    if (r2d != SR_OK) {
        return r2d;
    }
    int64_t rxq = (int64_t)nearbyint(rx * Q8_ONE), ryq = (int64_t)nearbyint(ry * Q8_ONE);
    ellipse_q8 e = { (int64_t)nearbyint(cx * Q8_ONE), (int64_t)nearbyint(cy * Q8_ONE),
                     ryq * ryq, rxq * rxq, sr__wide_mul(rxq * rxq, ryq * ryq) };
    /* The pixel whose centre is nearest the ellipse centre in x. */
    int64_t ic = floor_div(e.cx, Q8_ONE);
    /* Rows that can hold inside pixels, with one more above and below for
     * the outline's neighbour test; clipped to the framebuffer +-1. */
    int64_t j0 = floor_div(e.cy - ryq, Q8_ONE) - 1, j1 = floor_div(e.cy + ryq, Q8_ONE) + 1;
    if (j0 < -1) {
        j0 = -1;
    }
    if (j1 > fb->height) {
        j1 = fb->height;
    }
    row_span rows[3] = { { false, 0, 0 }, { false, 0, 0 }, { false, 0, 0 } };
    bool have_hint = false;
    int64_t hint_lo = ic, hint_hi = ic;
    for (int64_t j = j0; j <= j1 + 1; j++) {
        row_span next = { false, 0, 0 };
        if (j <= j1) {
            next.any = ellipse_row(&e, j, ic, have_hint, hint_lo, hint_hi, &next.lo, &next.hi);
            if (next.any) {
                have_hint = true;
                hint_lo = next.lo;
                hint_hi = next.hi;
            }
        }
        rows[0] = rows[1];
        rows[1] = rows[2];
        rows[2] = next;
        /* rows[1] is row j - 1 */
        if (filled) {
            if (rows[1].any) {
                paint_clipped(&paint, fb, j - 1, rows[1].lo, rows[1].hi);
            }
        } else {
            paint_outline_row(&paint, fb, j - 1, &rows[0], &rows[1], &rows[2]);
        }
    }
    sr__ok(ctx);
    return SR_OK;
}

sr_result sr_draw_circle(sr_context *ctx, sr_framebuffer *fb, double cx, double cy, double r,
                         sr_rgba color, bool filled)
{
    return sr_draw_ellipse(ctx, fb, cx, cy, r, r, color, filled);
}

/* ---- implicit regions -------------------------------------------------------- */

sr_result sr_fill_implicit(sr_context *ctx, sr_framebuffer *fb, const sr_implicit_desc *desc,
                           sr_rgba color)
{
    static const char fn[] = "sr_fill_implicit";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_fill_implicit: ctx is NULL");
    }
    if (!fb || !desc || !desc->f) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %s is NULL", fn,
                        !fb ? "fb" : !desc ? "desc" : "sr_implicit_desc.f");
    }
    double bx0 = desc->x0, by0 = desc->y0, bx1 = desc->x1, by1 = desc->y1;
    if (bx0 == 0 && by0 == 0 && bx1 == 0 && by1 == 0) {
        bx1 = fb->width;
        by1 = fb->height;
    }
    if (!isfinite(bx0) || !isfinite(by0) || !isfinite(bx1) || !isfinite(by1)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_implicit_desc box is not finite", fn);
    }
    sr__paint paint;
    if (!sr__paint_init(&paint, color, desc->linear_light)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: color is not finite", fn);
    }
    sr_result r2d = sr__fb_begin_2d(ctx, fn, fb);
    if (r2d != SR_OK) {
        return r2d;
    }
    /* Pixels whose centres lie in the box, clipped to the framebuffer. */
    double fx0 = fmax(ceil(bx0 - 0.5), 0), fy0 = fmax(ceil(by0 - 0.5), 0);
    double fx1 = fmin(ceil(bx1 - 0.5), fb->width), fy1 = fmin(ceil(by1 - 0.5), fb->height);
    for (int y = (int)fy0; y < (int)fy1; y++) {
        uint32_t *row = fb->color + (size_t)y * (size_t)fb->width;
        for (int x = (int)fx0; x < (int)fx1; x++) {
            double px = x + 0.5, py = y + 0.5;
            if (!desc->antialias) {
                double f = desc->f(desc->user, px, py, NULL);
                if (f < 0) {
                    sr__paint_pixel(&paint, &row[x], 255);
                }
                continue;
            }
            double g[2] = { NAN, NAN };
            double f = desc->f(desc->user, px, py, g);
            if (!isfinite(f)) {
                continue;
            }
            if (!isfinite(g[0]) || !isfinite(g[1])) {
                const double h = 0.25;
                g[0] = (desc->f(desc->user, px + h, py, NULL) -
                        desc->f(desc->user, px - h, py, NULL)) / (2 * h);
                g[1] = (desc->f(desc->user, px, py + h, NULL) -
                        desc->f(desc->user, px, py - h, NULL)) / (2 * h);
            }
            double len = hypot(g[0], g[1]);
            double cov;
            if (len > 0 && isfinite(len)) {
                /* -F/|grad F| is the signed distance into the region to
                 * first order; a pixel is a unit box around its centre. */
                cov = 0.5 - f / len;
                cov = cov < 0 ? 0 : cov > 1 ? 1 : cov;
            } else {
                cov = f < 0 ? 1 : 0;
            }
            sr__paint_pixel(&paint, &row[x], (unsigned)(cov * 255.0 + 0.5));
        }
    }
    sr__ok(ctx);
    return SR_OK;
}

/* ---- flattening ------------------------------------------------------------ */

static bool point_ok(sr_point2 p)
{
    return isfinite(p.x) && isfinite(p.y);
}

static sr_result check_flatten(sr_context *ctx, const char *fn, double tolerance, sr_point2 *out,
                               int capacity, int *out_count)
{
    if (!out_count) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: out_count is NULL", fn);
    }
    *out_count = 0;
    if (capacity < 0 || (capacity > 0 && !out)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: out is NULL or capacity < 0", fn);
    }
    if (!(tolerance > 0) || !isfinite(tolerance)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: tolerance must be > 0 (got %g)", fn, tolerance);
    }
    return SR_OK;
}

/* Steps so that the chord error |B''|max h^2 / 8 stays within tolerance. */
static int steps_for(double second_derivative_max, double tolerance)
{
    double n = ceil(sqrt(second_derivative_max / (8.0 * tolerance)));
    if (!(n >= 1)) {
        return 1;
    }
    return n > MAX_FLATTEN_STEPS ? MAX_FLATTEN_STEPS : (int)n;
}

static sr_result flatten_done(sr_context *ctx, const char *fn, int n, int capacity)
{
    if (n > capacity) {
        return sr__fail(ctx, SR_TOO_LARGE, "%s: needs %d points, capacity is %d", fn, n, capacity);
    }
    sr__ok(ctx);
    return SR_OK;
}

sr_result sr_flatten_quadratic(sr_context *ctx, sr_point2 p0, sr_point2 p1, sr_point2 p2,
                               double tolerance, sr_point2 *out, int capacity, int *out_count)
{
    static const char fn[] = "sr_flatten_quadratic";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_flatten_quadratic: ctx is NULL");
    }
    sr_result r = check_flatten(ctx, fn, tolerance, out, capacity, out_count);
    if (r != SR_OK) {
        return r;
    }
    if (!point_ok(p0) || !point_ok(p1) || !point_ok(p2)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: a control point is not finite", fn);
    }
    /* B(t) = A t^2 + B t + C;  B'' = 2 A. */
    double ax = p0.x - 2 * p1.x + p2.x, ay = p0.y - 2 * p1.y + p2.y;
    double bx = 2 * (p1.x - p0.x), by = 2 * (p1.y - p0.y);
    int n = steps_for(2 * hypot(ax, ay), tolerance);
    *out_count = n;
    if (n > capacity) {
        return flatten_done(ctx, fn, n, capacity);
    }
    /* Forward differences with step h: first difference A h^2 + B h,
     * second difference 2 A h^2 (constant). */
    double h = 1.0 / n;
    double x = p0.x, y = p0.y;
    double dx = ax * h * h + bx * h, dy = ay * h * h + by * h;
    double ddx = 2 * ax * h * h, ddy = 2 * ay * h * h;
    for (int i = 0; i < n - 1; i++) {
        x += dx;
        y += dy;
        dx += ddx;
        dy += ddy;
        out[i] = (sr_point2){ x, y };
    }
    out[n - 1] = p2;
    return flatten_done(ctx, fn, n, capacity);
}

sr_result sr_flatten_cubic(sr_context *ctx, sr_point2 p0, sr_point2 p1, sr_point2 p2,
                           sr_point2 p3, double tolerance, sr_point2 *out, int capacity,
                           int *out_count)
{
    static const char fn[] = "sr_flatten_cubic";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_flatten_cubic: ctx is NULL");
    }
    sr_result r = check_flatten(ctx, fn, tolerance, out, capacity, out_count);
    if (r != SR_OK) {
        return r;
    }
    if (!point_ok(p0) || !point_ok(p1) || !point_ok(p2) || !point_ok(p3)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: a control point is not finite", fn);
    }
    /* B(t) = A t^3 + B t^2 + C t + D.  B'' = 6 A t + 2 B is linear in t,
     * so |B''| peaks at an end: 6 |p0 - 2 p1 + p2| or 6 |p1 - 2 p2 + p3|. */
    double ax = -p0.x + 3 * p1.x - 3 * p2.x + p3.x, ay = -p0.y + 3 * p1.y - 3 * p2.y + p3.y;
    double bx = 3 * p0.x - 6 * p1.x + 3 * p2.x, by = 3 * p0.y - 6 * p1.y + 3 * p2.y;
    double cx = 3 * (p1.x - p0.x), cy = 3 * (p1.y - p0.y);
    double m0 = 6 * hypot(p0.x - 2 * p1.x + p2.x, p0.y - 2 * p1.y + p2.y);
    double m1 = 6 * hypot(p1.x - 2 * p2.x + p3.x, p1.y - 2 * p2.y + p3.y);
    int n = steps_for(m0 > m1 ? m0 : m1, tolerance);
    *out_count = n;
    if (n > capacity) {
        return flatten_done(ctx, fn, n, capacity);
    }
    double h = 1.0 / n, h2 = h * h, h3 = h2 * h;
    double x = p0.x, y = p0.y;
    double dx = ax * h3 + bx * h2 + cx * h, dy = ay * h3 + by * h2 + cy * h;
    double ddx = 6 * ax * h3 + 2 * bx * h2, ddy = 6 * ay * h3 + 2 * by * h2;
    double dddx = 6 * ax * h3, dddy = 6 * ay * h3;
    for (int i = 0; i < n - 1; i++) {
        x += dx;
        y += dy;
        dx += ddx;
        dy += ddy;
        ddx += dddx;
        ddy += dddy;
        out[i] = (sr_point2){ x, y };
    }
    out[n - 1] = p3;
    return flatten_done(ctx, fn, n, capacity);
}

static double vec_angle(double ux, double uy, double vx, double vy)
{
    return atan2(ux * vy - uy * vx, ux * vx + uy * vy);
}

sr_result sr_flatten_arc(sr_context *ctx, sr_point2 from, double rx, double ry,
                         double rotation_deg, bool large_arc, bool sweep, sr_point2 to,
                         double tolerance, sr_point2 *out, int capacity, int *out_count)
{
    static const char fn[] = "sr_flatten_arc";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_flatten_arc: ctx is NULL");
    }
    sr_result r = check_flatten(ctx, fn, tolerance, out, capacity, out_count);
    if (r != SR_OK) {
        return r;
    }
    if (!point_ok(from) || !point_ok(to) || !isfinite(rx) || !isfinite(ry) ||
        !isfinite(rotation_deg)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: an argument is not finite", fn);
    }
    sr__arc arc;
    switch (sr__arc_centre(from, rx, ry, rotation_deg, large_arc, sweep, to, &arc)) {
    case SR__ARC_OMITTED:
        return flatten_done(ctx, fn, 0, capacity);
    case SR__ARC_LINE:
        *out_count = 1;
        if (capacity >= 1) {
            out[0] = to;
        }
        return flatten_done(ctx, fn, 1, capacity);
    case SR__ARC_FAR_ENDS:
        return sr__fail(ctx, SR_TOO_LARGE, "%s: end points too far apart", fn);
    case SR__ARC_FAR_CENTRE:
        return sr__fail(ctx, SR_TOO_LARGE, "%s: radii (%g, %g) put the centre beyond range", fn,
                        fabs(rx), fabs(ry));
    case SR__ARC_CURVED:
        break;
    }
    int n = sr__arc_steps(&arc, arc.dtheta, tolerance);
    *out_count = n;
    if (n <= capacity) {
        sr__arc_points(&arc, arc.theta1, arc.dtheta, n, to, out);
    }
    return flatten_done(ctx, fn, n, capacity);
}

sr__arc_kind sr__arc_centre(sr_point2 from, double rx, double ry, double rotation_deg,
                            bool large_arc, bool sweep, sr_point2 to, sr__arc *arc)
{
    rx = fabs(rx);
    ry = fabs(ry);
    if ((from.x == to.x && from.y == to.y)) {
        return SR__ARC_OMITTED;
    }
    if (rx == 0 || ry == 0) {
        return SR__ARC_LINE;
    }
    double phi = rotation_deg * M_PI / 180.0, cphi = cos(phi), sphi = sin(phi);
    double mx = from.x / 2 - to.x / 2, my = from.y / 2 - to.y / 2;
    double half_chord = hypot(mx, my);
    int k_exp = 0;
    (void)frexp(half_chord, &k_exp);
    double k = ldexp(1, k_exp);
    if (!(half_chord > 0) || !isfinite(half_chord) || !isfinite(k)) {
        return SR__ARC_FAR_ENDS;
    }
    mx /= k;
    my /= k;
    /* Normalized radii within 1e-60..1e60: their products of four stay
     * finite and normal.  An arc 1e60 times wider than its chord is a
     * straight line at any tolerance, and one 1e60 times narrower is
     * scaled up to the chord below anyway (F.6.6). */
    rx = fmin(fmax(rx / k, 1e-60), 1e60);
    ry = fmin(fmax(ry / k, 1e-60), 1e60);
    double x1p = cphi * mx + sphi * my, y1p = -sphi * mx + cphi * my;
    double lambda = (x1p * x1p) / (rx * rx) + (y1p * y1p) / (ry * ry);
    if (lambda > 1) { /* F.6.6: radii too small, scale them up */
        double s = sqrt(lambda);
        rx *= s;
        ry *= s;
    }
    double num = rx * rx * ry * ry - rx * rx * y1p * y1p - ry * ry * x1p * x1p;
    double den = rx * rx * y1p * y1p + ry * ry * x1p * x1p;
    double coef = den > 0 && num > 0 ? sqrt(num / den) : 0;
    if (large_arc == sweep) {
        coef = -coef;
    }
    double cxp = coef * rx * y1p / ry, cyp = -coef * ry * x1p / rx;
    double ux = (x1p - cxp) / rx, uy = (y1p - cyp) / ry;
    double vx = (-x1p - cxp) / rx, vy = (-y1p - cyp) / ry;
    /* Back to the caller's scale. */
    cxp *= k;
    cyp *= k;
    rx *= k;
    ry *= k;
    double ccx = cphi * cxp - sphi * cyp + (from.x / 2 + to.x / 2);
    double ccy = sphi * cxp + cphi * cyp + (from.y / 2 + to.y / 2);
    if (!isfinite(ccx) || !isfinite(ccy) || !isfinite(rx) || !isfinite(ry)) {
        return SR__ARC_FAR_CENTRE;
    }
    double theta1 = vec_angle(1, 0, ux, uy);
    double dtheta = vec_angle(ux, uy, vx, vy);
    if (!sweep && dtheta > 0) {
        dtheta -= 2 * M_PI;
    } else if (sweep && dtheta < 0) {
        dtheta += 2 * M_PI;
    }
    *arc = (sr__arc){ ccx, ccy, rx, ry, cphi, sphi, theta1, dtheta };
    return SR__ARC_CURVED;
}

int sr__arc_steps(const sr__arc *arc, double dtheta, double tolerance)
{
    /* Segments: a chord of angle a on radius R strays R (1 - cos(a/2)). */
    double rmax = arc->rx > arc->ry ? arc->rx : arc->ry;
    double a = tolerance >= rmax ? M_PI / 2 : 2 * acos(1 - tolerance / rmax);
    if (!(a > 0)) {
        /* R above 1e16 tolerances: 1 - x rounds to 1 and acos gives 0
         * (0/0 steps for dtheta = 0).  acos(1 - x) = sqrt(2 x) to first
         * order; still 0 when x underflows, hence the fallback below. */
        a = 2 * sqrt(2 * (tolerance / rmax));
    }
    double steps = a > 0 ? ceil(fabs(dtheta) / a) : MAX_FLATTEN_STEPS;
    if (!(steps >= 1)) { /* also NaN */
        steps = 1;
    }
    if (steps > MAX_FLATTEN_STEPS) {
        steps = MAX_FLATTEN_STEPS;
    }
    return (int)steps;
}

sr_point2 sr__arc_point(const sr__arc *arc, double t)
{
    double ex = arc->rx * cos(t), ey = arc->ry * sin(t);
    return (sr_point2){ arc->cphi * ex - arc->sphi * ey + arc->cx,
                        arc->sphi * ex + arc->cphi * ey + arc->cy };
}

void sr__arc_points(const sr__arc *arc, double t0, double dtheta, int n, sr_point2 to,
                    sr_point2 *out)
{
    for (int i = 1; i < n; i++) {
        out[i - 1] = sr__arc_point(arc, t0 + dtheta * i / n);
    }
    out[n - 1] = to;
}
