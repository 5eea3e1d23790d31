/* line.c - lines and points in the 3D pipeline (raster stage): setup of a
 * clipped segment or point into a binned record, and rasterization within
 * one tile.  Runs setup on front-end workers and rasterization on tile
 * workers; no shared state.
 *
 * Lines follow the diamond-exit rule in its exact closed form
 * (RASTER_RULES 6.1-6.2): with endpoints snapped to 1/256 px, an x-major
 * segment covers, in each column whose centre it spans, the pixel holding
 * the segment's point at that centre (a boundary point goes to the smaller
 * minor index, Direct3D's tie rule); the start pixel is added when the
 * start lies in its diamond, and the end pixel is removed when the end
 * lies in its diamond (half-open).  So the pixels do not depend on the
 * direction except for which end is left open, line strips join without
 * gaps or double pixels, and everything is integer arithmetic.  Wide lines
 * are OpenGL's: a run of `width` pixels across the minor axis per step.
 *
 * Work is done where it is cheapest.  Setup finds, once per segment, the
 * columns, the DDA of their pixels, the two diamonds' pixels and the tiles
 * the pixels reach (binning puts the segment in those only, not in its
 * whole bounding box).  Each tile solves for the columns whose pixel falls
 * inside it and walks just those.  line_fragment through
 * sr__fragment_vary is the reference fragment path; common states take a
 * fast path (one pixel wide, plain color write, depth off or LESS) with
 * the same operations, four columns at a time with AVX2 for the
 * commonest, and test_lines_fast.c holds both to the reference. */
#include "fragment/sample.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#define H SR_SUBPIXEL_HALF
#define S SR_SUBPIXEL_ONE

static int clampi(int64_t v, int lo, int hi)
{
    return v < lo ? lo : v > hi ? hi : (int)v;
}

/* The pixel whose diamond owns point (x, y) (q8), if any.  A pixel's
 * diamond is |dx| + |dy| < H around its centre, with Direct3D's boundary
 * ownership: the lower edges and bottom corner belong to it, and for a
 * y-major line also the right corner (y points down, so "lower" is +y).
 * Candidates: the pixel P whose square holds the point and P's left and
 * upper neighbours (whose closed squares share its left and top edges),
 * decided from the offset (dx, dy) to P's centre, both in [-H, H).  A
 * diamond's interior lies inside its own square, so only P can hold the
 * point strictly inside; on P's diamond's boundary P owns it when dy > 0;
 * P's left corner is the left neighbour's right corner (owned for y-major
 * lines), its top corner the upper neighbour's bottom corner (owned).  Any
 * other point is in no diamond, so at most one diamond owns a point. */
static bool diamond_owner(int64_t x, int64_t y, bool xmajor, int *qx, int *qy)
{
    int64_t px = sr__floor_div(x, S), py = sr__floor_div(y, S);
    int64_t dx = x - (px * S + H), dy = y - (py * S + H);
    int64_t d = llabs(dx) + llabs(dy);
    *qx = (int)px;
    *qy = (int)py;
    if (d < H || (d == H && dy > 0)) {
        return true;
    }
    if (dx == -H && dy == 0 && !xmajor) {
        *qx = (int)px - 1;
        return true;
    }
    if (dx == 0 && dy == -H) {
        *qy = (int)py - 1;
        return true;
    }
    return false;
}

/* Column k's pixel on the minor axis (see sr_line). */
static int64_t minor_at(const sr_line *l, int64_t k)
{
    return sr__floor_div(l->n0 + (k - l->k0) * l->dn, l->d);
}

/* The aliased walk's constants, once per line rather than once per tile
 * it touches: the columns, the DDA of their pixels, and the pixels whose
 * diamonds own the two ends. */
static void setup_walk(sr_line *l)
{
    int64_t dx = (int64_t)l->xb - l->xa, dy = (int64_t)l->yb - l->ya;
    bool xmajor = llabs(dx) >= llabs(dy);
    l->xmajor = xmajor;
    /* Columns whose centre lies within the segment's major extent. */
    int64_t au = xmajor ? l->xa : l->ya, bu = xmajor ? l->xb : l->yb;
    int64_t av = xmajor ? l->ya : l->xa, bv = xmajor ? l->yb : l->xb;
    int64_t lo = au < bu ? au : bu, hi = au ^ bu ^ lo;
    int64_t k0 = sr__ceil_div(lo - H, S), k1 = sr__floor_div(hi - H, S);
    /* The minor coordinate at column centre c is num/den with
     * num = a_v (b_u - a_u) + (c - a_u)(b_v - a_v), den = b_u - a_u (made
     * positive); the column's pixel is j = ceil(num / 256 den) - 1 =
     * floor((num - 1) / 256 den), a point on a pixel boundary going to the
     * smaller index.  num grows by 256 (b_v - a_v) per column: a DDA. */
    int64_t den = bu - au, sign = den < 0 ? -1 : 1;
    l->k0 = (int16_t)k0;
    l->k1 = (int16_t)k1;
    l->n0 = sign * (av * den + (k0 * S + H - au) * (bv - av)) - 1;
    l->d = sign * den * S;
    l->dn = sign * S * (bv - av);

    /* The start diamond's pixel is drawn (the line exits it), the end's
     * is not (half-open).  Either may lie on the column path or beside
     * it; only an off-path start pixel needs a pixel of its own. */
    int sx, sy, ex, ey;
    bool start_in = diamond_owner(l->xa, l->ya, xmajor, &sx, &sy);
    bool end_in = diamond_owner(l->xb, l->yb, xmajor, &ex, &ey);
    int su = xmajor ? sx : sy, sv = xmajor ? sy : sx;
    int eu = xmajor ? ex : ey, ev = xmajor ? ey : ex;
    bool start_on_path = start_in && su >= k0 && su <= k1 && minor_at(l, su) == sv;
    bool end_on_path = end_in && eu >= k0 && eu <= k1 && minor_at(l, eu) == ev;
    bool start_is_end = start_in && end_in && sx == ex && sy == ey;
    l->start_extra = start_in && !start_on_path && !start_is_end;
    l->start_u = (int16_t)su;
    l->start_v = (int16_t)sv;
    l->end_u = (int16_t)(end_on_path ? eu : INT16_MIN);
    l->end_v = (int16_t)ev;
}

/* 1 / |b - a|^2 (q8^2), the projection's scale: the reference's
 * expression, per tile rather than stored, to keep the record small. */
static double inv_len2(const sr_line *l)
{
    int64_t dx = (int64_t)l->xb - l->xa, dy = (int64_t)l->yb - l->ya;
    return 1.0 / ((double)dx * dx + (double)dy * dy);
}

/* ---- binning: the tiles a line's pixels reach ---- */

bool sr__line_span(const sr_line *l, int u0, int u1, int *v0, int *v1)
{
    int64_t lo = INT64_MAX, hi = INT64_MIN;
    int64_t a = u0 > l->k0 ? u0 : l->k0, b = u1 < l->k1 ? u1 : l->k1;
    if (a <= b) {
        /* v(k) is monotonic: its extremes are at the ends. */
        int64_t va = minor_at(l, a), vb = minor_at(l, b);
        lo = va < vb ? va : vb;
        hi = va ^ vb ^ lo;
    }
    if (l->start_extra && l->start_u >= u0 && l->start_u <= u1) {
        lo = l->start_v < lo ? l->start_v : lo;
        hi = l->start_v > hi ? l->start_v : hi;
    }
    if (lo > hi) {
        return false;
    }
    /* A wide line's run reaches (width - 1) / 2 pixels below its path
     * pixel and the rest above it. */
    int below = (l->width - 1) / 2;
    *v0 = (int)lo - below;
    *v1 = (int)hi + (l->width - 1 - below);
    return true;
}

/* The bounding box as major [b[0], b[1]) and minor [b[2], b[3]). */
static void box_uv(const sr_line *l, int b[4])
{
    bool x = l->xmajor;
    b[0] = x ? l->h.x0 : l->h.y0;
    b[1] = x ? l->h.x1 : l->h.y1;
    b[2] = x ? l->h.y0 : l->h.x0;
    b[3] = x ? l->h.y1 : l->h.x1;
}

void sr__line_tile_columns(const sr_line *l, int *tu0, int *tu1)
{
    int b[4];
    box_uv(l, b);
    /* Every pixel (runs included) lies in the path's columns or the
     * start pixel's. */
    int u0 = l->k0, u1 = l->k1;
    if (l->start_extra) {
        u0 = l->start_u < u0 ? l->start_u : u0;
        u1 = l->start_u > u1 ? l->start_u : u1;
    }
    u0 = u0 > b[0] ? u0 : b[0];
    u1 = u1 < b[1] - 1 ? u1 : b[1] - 1;
    *tu0 = u0 >> SR_TILE_ORDER;
    *tu1 = u0 <= u1 ? u1 >> SR_TILE_ORDER : *tu0 - 1;
}

bool sr__line_tile_rows(const sr_line *l, int tu, int *tv0, int *tv1)
{
    int b[4];
    box_uv(l, b);
    int u0 = tu << SR_TILE_ORDER, u1 = u0 + SR_TILE_SIZE - 1;
    u0 = u0 > b[0] ? u0 : b[0];
    u1 = u1 < b[1] - 1 ? u1 : b[1] - 1;
    int v0, v1;
    if (u0 > u1 || !sr__line_span(l, u0, u1, &v0, &v1)) {
        return false;
    }
    v0 = v0 > b[2] ? v0 : b[2];
    v1 = v1 < b[3] - 1 ? v1 : b[3] - 1;
    *tv0 = v0 >> SR_TILE_ORDER;
    *tv1 = v1 >> SR_TILE_ORDER;
    return v0 <= v1;
}

/* The tile rows of each tile column, for binning, when the line spans at
 * most SR_LINE_BIN_COLUMNS of them (bin_count above that otherwise). */
static void setup_bins(sr_line *l)
{
    int tu0, tu1;
    sr__line_tile_columns(l, &tu0, &tu1);
    int n = tu1 >= tu0 ? tu1 - tu0 + 1 : 0;
    if (n > SR_LINE_BIN_COLUMNS) {
        l->bin_count = SR_LINE_BIN_COLUMNS + 1;
        return;
    }
    l->bin_count = (uint8_t)n;
    l->bin_tu0 = (uint8_t)(n > 0 ? tu0 : 0);
    for (int i = 0; i < n; i++) {
        int tv0, tv1;
        if (!sr__line_tile_rows(l, tu0 + i, &tv0, &tv1)) {
            tv0 = 1; /* empty */
            tv1 = 0;
        }
        l->bin_rows[2 * i] = (uint8_t)tv0;
        l->bin_rows[2 * i + 1] = (uint8_t)tv1;
    }
}

bool sr__setup_line(const sr_draw_state *ds, const sr_window_vertex *a, const sr_window_vertex *b,
                    double offset, bool front, int ninterp, const float flat[4], sr_line *l)
{
    if (a->x_q8 == b->x_q8 && a->y_q8 == b->y_q8) {
        return false;
    }
    l->h.kind = SR_KIND_LINE;
    l->xa = a->x_q8;
    l->ya = a->y_q8;
    l->xb = b->x_q8;
    l->yb = b->y_q8;
    l->width = ds->line_width;
    l->smooth = ds->smooth_lines;
    l->half_width = (float)(ds->smooth_width * 0.5);
    /* Bounding box of every pixel the line (and its wide runs, or its
     * antialiasing ramp) can touch: the segment's box widened by half the
     * width plus one pixel. */
    int pad = (l->smooth ? (int)ceil(l->half_width) : l->width / 2) + 1;
    int64_t minx = a->x_q8 < b->x_q8 ? a->x_q8 : b->x_q8, maxx = a->x_q8 ^ b->x_q8 ^ minx;
    int64_t miny = a->y_q8 < b->y_q8 ? a->y_q8 : b->y_q8, maxy = a->y_q8 ^ b->y_q8 ^ miny;
    int x0 = (int)sr__floor_div(minx, S) - pad, x1 = (int)sr__floor_div(maxx, S) + pad + 1;
    int y0 = (int)sr__floor_div(miny, S) - pad, y1 = (int)sr__floor_div(maxy, S) + pad + 1;
    l->h.x0 = x0 > ds->rect_x0 ? x0 : ds->rect_x0;
    l->h.y0 = y0 > ds->rect_y0 ? y0 : ds->rect_y0;
    l->h.x1 = x1 < ds->rect_x1 ? x1 : ds->rect_x1;
    l->h.y1 = y1 < ds->rect_y1 ? y1 : ds->rect_y1;
    if (l->h.x0 >= l->h.x1 || l->h.y0 >= l->h.y1) {
        return false;
    }
    l->front = front;
    l->ninterp = ninterp;
    l->za = (a->z + offset) * ds->depth_scale;
    l->zb = (b->z + offset) * ds->depth_scale;
    l->wa = ds->perspective ? a->inv_w : 1.0f;
    l->wb = ds->perspective ? b->inv_w : 1.0f;
    if (ninterp > 0) {
        memcpy(l->vary, a->vary, (size_t)ninterp * sizeof(float));
        memcpy(l->vary + ninterp, b->vary, (size_t)ninterp * sizeof(float));
    }
    if (flat) {
        memcpy(l->flat, flat, sizeof l->flat);
    }
    if (!l->smooth) {
        setup_walk(l);
        setup_bins(l);
    }
    return true;
}

bool sr__setup_point(const sr_draw_state *ds, const sr_window_vertex *v, double offset,
                     bool front, int ninterp, const float flat[4], sr_point *p)
{
    /* The square's edges snap to q8; a pixel is covered when its centre
     * lies in [lo, hi) on both axes (the top-left rule for a square). */
    int64_t half = (int64_t)nearbyint(ds->point_size * (S / 2));
    int64_t lox = v->x_q8 - half, hix = v->x_q8 + half;
    int64_t loy = v->y_q8 - half, hiy = v->y_q8 + half;
    int64_t x0 = sr__ceil_div(lox - H, S), x1 = sr__ceil_div(hix - H, S);
    int64_t y0 = sr__ceil_div(loy - H, S), y1 = sr__ceil_div(hiy - H, S);
    p->h.kind = SR_KIND_POINT;
    p->h.x0 = clampi(x0, ds->rect_x0, ds->rect_x1);
    p->h.x1 = clampi(x1, ds->rect_x0, ds->rect_x1);
    p->h.y0 = clampi(y0, ds->rect_y0, ds->rect_y1);
    p->h.y1 = clampi(y1, ds->rect_y0, ds->rect_y1);
    if (p->h.x0 >= p->h.x1 || p->h.y0 >= p->h.y1) {
        return false;
    }
    p->cx = v->x_q8;
    p->cy = v->y_q8;
    p->half = (int32_t)half;
    p->radius2 = ds->round_points ? half * half : 0;
    p->smooth_radius = ds->smooth_points ? (float)(ds->point_size * 0.5) : 0.0f;
    if (ds->samples > 1) {
        /* Multisampled: the samples inside the square or disc decide
         * (smooth points become discs, as GL ignores smoothing under
         * multisampling); the box holds every pixel whose square meets
         * [lo, hi). */
        p->radius2 = ds->round_points || ds->smooth_points ? half * half : 0;
        p->smooth_radius = 0.0f;
        p->h.x0 = clampi(sr__floor_div(lox, S), ds->rect_x0, ds->rect_x1);
        p->h.x1 = clampi(sr__floor_div(hix - 1, S) + 1, ds->rect_x0, ds->rect_x1);
        p->h.y0 = clampi(sr__floor_div(loy, S), ds->rect_y0, ds->rect_y1);
        p->h.y1 = clampi(sr__floor_div(hiy - 1, S) + 1, ds->rect_y0, ds->rect_y1);
        if (p->h.x0 >= p->h.x1 || p->h.y0 >= p->h.y1) {
            return false;
        }
    }
    if (p->smooth_radius > 0.0f) {
        /* The ramp reaches half a pixel past the radius. */
        int64_t reach = half + H;
        p->h.x0 = clampi(sr__ceil_div(v->x_q8 - reach - H, S), ds->rect_x0, ds->rect_x1);
        p->h.x1 = clampi(sr__floor_div(v->x_q8 + reach - H, S) + 1, ds->rect_x0, ds->rect_x1);
        p->h.y0 = clampi(sr__ceil_div(v->y_q8 - reach - H, S), ds->rect_y0, ds->rect_y1);
        p->h.y1 = clampi(sr__floor_div(v->y_q8 + reach - H, S) + 1, ds->rect_y0, ds->rect_y1);
        if (p->h.x0 >= p->h.x1 || p->h.y0 >= p->h.y1) {
            return false;
        }
    }
    p->z = (v->z + offset) * ds->depth_scale;
    p->front = front;
    p->ninterp = ninterp;
    if (ninterp > 0) {
        memcpy(p->vary, v->vary, (size_t)ninterp * sizeof(float));
    }
    if (flat) {
        memcpy(p->flat, flat, sizeof p->flat);
    }
    return true;
}

/* A multisampled point: each sample inside the half-open square
 * [c - half, c + half) or strictly inside the disc, in exact integers;
 * one depth and one shading for the pixel. */
static void raster_point_samples(const sr_draw_state *ds, const sr_point *p, int rx0, int ry0,
                                 int rx1, int ry1, sr_frag_stats *st)
{
    size_t n = (size_t)ds->samples;
    bool late = ds->program && (ds->program->writes_depth || ds->program->may_discard);
    for (int py = ry0; py < ry1; py++) {
        for (int px = rx0; px < rx1; px++) {
            size_t base = ((size_t)py * (size_t)ds->fb->width + (size_t)px) * n;
            double z = p->z;
            float c[4];
            if (late && !sr__program_shade_one(ds, p->vary, p->front, px, py, &z, c)) {
                continue;
            }
            uint32_t q = sr__quantize_depth(ds, &z);
            unsigned pass = 0;
            for (size_t s = 0; s < n; s++) {
                int64_t dx = sr__centre_q8(px) + ds->sample_off[s][0] - p->cx;
                int64_t dy = sr__centre_q8(py) + ds->sample_off[s][1] - p->cy;
                bool in = p->radius2 ? dx * dx + dy * dy < p->radius2
                                     : dx >= -p->half && dx < p->half && dy >= -p->half &&
                                           dy < p->half;
                if (in && sr__sample_test(ds, base + s, q, p->front, true)) {
                    pass |= 1u << s;
                }
            }
            if (pass) {
                if (ds->program && !late) {
                    (void)sr__program_shade_one(ds, p->vary, p->front, px, py, &z, c);
                } else if (!ds->program) {
                    sr__shade_vary(ds, p->vary, p->flat, p->front, z, 0.0f, c, ds->shading);
                }
                sr__write_samples(ds, base, pass, c, &ds->blend);
                st->fragments += (uint64_t)__builtin_popcount(pass);
            }
        }
    }
}

void sr__raster_point(const sr_draw_state *ds, const sr_point *p, int rx0, int ry0, int rx1,
                      int ry1, sr_frag_stats *st)
{
    if (ds->samples > 1) {
        raster_point_samples(ds, p, rx0, ry0, rx1, ry1, st);
        return;
    }
    for (int py = ry0; py < ry1; py++) {
        for (int px = rx0; px < rx1; px++) {
            if (p->radius2) {
                /* A disc: the pixel centre strictly inside the circle,
                 * decided in exact integers. */
                int64_t dx = sr__centre_q8(px) - p->cx, dy = sr__centre_q8(py) - p->cy;
                if (dx * dx + dy * dy >= p->radius2) {
                    continue;
                }
            }
            float coverage = 1.0f;
            if (p->smooth_radius > 0.0f) {
                /* A one-pixel ramp across the disc's edge. */
                double dx = (sr__centre_q8(px) - p->cx) / (double)S;
                double dy = (sr__centre_q8(py) - p->cy) / (double)S;
                double c = p->smooth_radius + 0.5 - sqrt(dx * dx + dy * dy);
                if (c <= 0.0) {
                    continue;
                }
                coverage = c < 1.0 ? (float)c : 1.0f;
            }
            sr__fragment_vary(ds, px, py, p->z, p->vary, p->flat, p->front, coverage, st);
        }
    }
}

typedef struct line_ctx {
    const sr_draw_state *ds;
    const sr_line *l;
    int rx0, ry0, rx1, ry1;
    bool xmajor;
    sr_frag_stats *st;
    double inv_len2;                  /* 1 / |b - a|^2 in q8^2 */
    bool equal_w;                     /* both ends share 1/w: interpolation is affine */
} line_ctx;

/* One covered pixel: project its centre onto the segment for t, then depth
 * linear in t and varyings perspective-correct (RASTER_RULES 4.1). */
static void line_fragment(const line_ctx *lc, int px, int py)
{
    const sr_line *l = lc->l;
    for (int k = 0; k < l->width; k++) {
        /* Wide lines: a run across the minor axis, centred on the pixel. */
        int off = k - (l->width - 1) / 2;
        int qx = lc->xmajor ? px : px + off;
        int qy = lc->xmajor ? py + off : py;
        if (qx < lc->rx0 || qx >= lc->rx1 || qy < lc->ry0 || qy >= lc->ry1) {
            continue;
        }
        double cx = (double)px * S + H - l->xa, cy = (double)py * S + H - l->ya;
        double t = (cx * (l->xb - l->xa) + cy * (l->yb - l->ya)) * lc->inv_len2;
        t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
        double z = l->za + t * (l->zb - l->za);
        float v[SR_MAX_VARYINGS];
        int n = l->ninterp;
        if (lc->equal_w) {
            /* Equal 1/w at both ends: perspective-correct is the lerp. */
            float tf = (float)t;
            for (int i = 0; i < n; i++) {
                v[i] = l->vary[i] + tf * (l->vary[n + i] - l->vary[i]);
            }
        } else {
            float qa = (float)(1.0 - t) * l->wa, qb = (float)t * l->wb;
            float inv = qa + qb != 0.0f ? 1.0f / (qa + qb) : 0.0f;
            for (int i = 0; i < n; i++) {
                v[i] = (qa * l->vary[i] + qb * l->vary[n + i]) * inv;
            }
        }
        sr__fragment_vary(lc->ds, qx, qy, z, v, l->flat, l->front, 1.0f, lc->st);
    }
}

/* Antialiased line: every pixel whose centre lies within half the width
 * plus half a pixel of the segment, with coverage falling linearly over the
 * last pixel (a box filter across the edge); round ends come from clamping
 * the projection to the segment.  Walks, per major-axis column, only the
 * rows the line can reach. */
static void raster_smooth_line(const sr_draw_state *ds, const sr_line *l, int rx0, int ry0,
                               int rx1, int ry1, sr_frag_stats *st)
{
    double ax = l->xa / (double)S, ay = l->ya / (double)S;
    double dx = (l->xb - l->xa) / (double)S, dy = (l->yb - l->ya) / (double)S;
    double len2 = dx * dx + dy * dy;
    bool xmajor = fabs(dx) >= fabs(dy);
    double reach = l->half_width + 0.5;
    int n = l->ninterp;
    int k0 = xmajor ? rx0 : ry0, k1 = xmajor ? rx1 : ry1;
    for (int k = k0; k < k1; k++) {
        /* The band of minor rows within reach at this column's centre. */
        double c = k + 0.5;
        double t_c = xmajor ? (dx != 0.0 ? (c - ax) / dx : 0.0) : (dy != 0.0 ? (c - ay) / dy : 0.0);
        t_c = t_c < 0.0 ? 0.0 : t_c > 1.0 ? 1.0 : t_c;
        double minor = xmajor ? ay + t_c * dy : ax + t_c * dx;
        double slope = xmajor ? (dx != 0.0 ? fabs(dy / dx) : 0.0) : (dy != 0.0 ? fabs(dx / dy) : 0.0);
        double span = reach * sqrt(1.0 + slope * slope) + 1.0;
        int j0 = (int)floor(minor - span), j1 = (int)ceil(minor + span);
        int lo = xmajor ? ry0 : rx0, hi = xmajor ? ry1 : rx1;
        j0 = j0 > lo ? j0 : lo;
        j1 = j1 < hi ? j1 : hi;
        for (int j = j0; j < j1; j++) {
            int px = xmajor ? k : j, py = xmajor ? j : k;
            double cx = px + 0.5 - ax, cy = py + 0.5 - ay;
            double t = len2 > 0.0 ? (cx * dx + cy * dy) / len2 : 0.0;
            t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
            double ex = cx - t * dx, ey = cy - t * dy;
            double cov = reach - sqrt(ex * ex + ey * ey);
            if (cov <= 0.0) {
                continue;
            }
            double z = l->za + t * (l->zb - l->za);
            float v[SR_MAX_VARYINGS];
            float qa = (float)(1.0 - t) * l->wa, qb = (float)t * l->wb;
            float inv = qa + qb != 0.0f ? 1.0f / (qa + qb) : 0.0f;
            for (int i = 0; i < n; i++) {
                v[i] = (qa * l->vary[i] + qb * l->vary[n + i]) * inv;
            }
            sr__fragment_vary(ds, px, py, z, v, l->flat, l->front, cov < 1.0 ? (float)cov : 1.0f,
                              st);
        }
    }
}

/* The columns of [klo, khi] whose path pixel lies in [vlo, vhi] on the
 * minor axis.  The pixel v(k) = floor(N(k) / d) is monotonic in k, so they
 * form one range [*ka, *kb], found in integers by solving
 * vlo d <= n0 + m dn <= (vhi + 1) d - 1 for m = k - k0, rather than by
 * walking every column of the tile and rejecting most of them. */
static bool column_range(const sr_line *l, int64_t klo, int64_t khi, int64_t vlo, int64_t vhi,
                         int64_t *ka, int64_t *kb)
{
    int64_t mlo = (klo > l->k0 ? klo : l->k0) - l->k0;
    int64_t mhi = (khi < l->k1 ? khi : l->k1) - l->k0;
    int64_t lo = vlo * l->d - l->n0, hi = (vhi + 1) * l->d - 1 - l->n0; /* m dn in [lo, hi] */
    if (l->dn > 0) {
        int64_t a = sr__ceil_div(lo, l->dn), b = sr__floor_div(hi, l->dn);
        mlo = a > mlo ? a : mlo;
        mhi = b < mhi ? b : mhi;
    } else if (l->dn < 0) {
        int64_t a = sr__ceil_div(-hi, -l->dn), b = sr__floor_div(-lo, -l->dn);
        mlo = a > mlo ? a : mlo;
        mhi = b < mhi ? b : mhi;
    } else if (lo > 0 || hi < 0) {
        return false;
    }
    *ka = l->k0 + mlo;
    *kb = l->k0 + mhi;
    return mlo <= mhi;
}

/* The reference walk: every path pixel of columns [ka, kb] and the
 * off-path start pixel through line_fragment, which clips the runs of
 * wide lines to the rectangle and shades through sr__fragment_vary. */
static void walk_generic(const line_ctx *lc, int64_t ka, int64_t kb)
{
    const sr_line *l = lc->l;
    bool xmajor = l->xmajor;
    sr_dda dda;
    sr__dda_init(&dda, l->n0 + (ka - l->k0) * l->dn, l->d, l->dn);
    for (int64_t k = ka; k <= kb; k++, sr__dda_step(&dda)) {
        int64_t j = dda.q;
        if (k == l->end_u && j == l->end_v) {
            continue; /* half-open: the end's own pixel is not drawn */
        }
        line_fragment(lc, xmajor ? (int)k : (int)j, xmajor ? (int)j : (int)k);
    }
    if (l->start_extra) {
        line_fragment(lc, xmajor ? l->start_u : l->start_v, xmajor ? l->start_v : l->start_u);
    }
}

/* ---- the fast path ----
 * One pixel wide, no program, texture, stencil, blending or color mask,
 * depth off or LESS, and a color that is the interpolated rgba (UNLIT,
 * GOURAUD, ATTRIBUTE) or the line's flat color: what line_fragment and
 * sr__fragment_vary do for that state, with the per-line constants
 * hoisted and the four channels in one vector.  Every floating-point
 * operation is the reference's, in its order (the build uses
 * -ffp-contract=off), so the bytes are the same; test_lines_fast.c holds
 * it to the reference. */

typedef float line_v4f __attribute__((vector_size(16)));

/* sr__unorm8 on r, g, b, a, packed as the framebuffer's bytes.  With SSE2
 * as in the triangle kernels: min(1, v) keeps NaN (min returns its second
 * operand then), truncation sends NaN and negatives to values the
 * saturating packs turn into 0, and anything above 1 became 255. */
static inline uint32_t pack_unorm8(line_v4f c)
{
#if defined(__SSE2__) && defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    __m128 v = _mm_min_ps(_mm_set1_ps(1.0f), (__m128)c);
    __m128i q = _mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(v, _mm_set1_ps(255.0f)),
                                            _mm_set1_ps(0.5f)));
    q = _mm_packs_epi32(q, q);
    return (uint32_t)_mm_cvtsi128_si32(_mm_packus_epi16(q, q));
#else
    uint8_t out[4];
    for (int k = 0; k < 4; k++) {
        out[k] = sr__unorm8(c[k]);
    }
    uint32_t packed;
    memcpy(&packed, out, sizeof packed);
    return packed;
#endif
}

typedef enum line_color {
    LINE_COLOR_FLAT,        /* the line's flat color, packed once */
    LINE_COLOR_LERP,        /* equal 1/w at both ends: the lerp */
    LINE_COLOR_PERSPECTIVE, /* perspective-correct */
} line_color;

typedef struct fast_line {
    const sr_draw_state *ds;
    const sr_line *l;
    uint32_t *color, *depth;
    size_t step_u, step_v;          /* buffer elements per column and per minor pixel */
    int64_t au, av, du, dv;         /* q8 start and direction on the major, minor axes */
    double dz;                      /* zb - za */
    double inv_len2;                /* 1 / |b - a|^2 in q8^2 */
    line_v4f va, vb, dvary;         /* the ends' rgba, and b - a */
    uint32_t flat;                  /* LINE_COLOR_FLAT: the packed color */
} fast_line;

/* Does the fast path draw this line exactly as the reference would? */
static bool line_is_fast(const sr_draw_state *ds, const sr_line *l)
{
    if (l->width != 1 || ds->program || ds->texture || ds->stencil_test || ds->blending ||
        ds->blend.enabled || ds->samples != 1 || ds->depth_mode == SR_DEPTH_MODE_GENERIC) {
        return false;
    }
    switch (ds->shading) {
    case SR_SHADING_FLAT:
        return true;
    case SR_SHADING_UNLIT:
    case SR_SHADING_GOURAUD:
    case SR_SHADING_ATTRIBUTE:
        return l->ninterp >= 4;
    default:
        return false;
    }
}

/* One pixel at buffer element idx whose centre c gives the projection's
 * numerator num = (c - a) . (b - a) in q8^2: line_fragment's t, depth and
 * color, and sr__fragment_vary's test and write.  The reference forms num
 * in doubles, but each of its terms is an integer below 2^48 (|c - a| <
 * 2^24 and |b - a| < 2^23 in q8 inside the guard band), so every step
 * there is exact; num in int64 is the same number, (double)num the same
 * double, and t the same product. */
SR_INLINE int fast_pixel(const fast_line *f, size_t idx, int64_t num, line_color mode,
                         bool less)
{
    const sr_line *l = f->l;
    double t = (double)num * f->inv_len2;
    /* The reference's clamp t < 0 ? 0 : t > 1 ? 1 : t, written as max
     * then min (maxsd, minsd): the same for every t but NaN and -0, and t
     * is neither (num is a finite integer, so num = 0 gives +0). */
    t = t > 0.0 ? t : 0.0;
    t = t < 1.0 ? t : 1.0;
    if (less) {
        double z = l->za + t * f->dz;
        uint32_t q = sr__quantize_depth(f->ds, &z);
        if (!(q < f->depth[idx])) {
            return 0;
        }
        f->depth[idx] = q;
    }
    uint32_t packed = f->flat;
    if (mode == LINE_COLOR_LERP) {
        float tf = (float)t;
        packed = pack_unorm8(f->va + tf * f->dvary);
    } else if (mode == LINE_COLOR_PERSPECTIVE) {
        float qa = (float)(1.0 - t) * l->wa, qb = (float)t * l->wb;
        float inv = qa + qb != 0.0f ? 1.0f / (qa + qb) : 0.0f;
        packed = pack_unorm8((qa * f->va + qb * f->vb) * inv);
    }
    f->color[idx] = packed;
    return 1;
}

/* The projection's numerator at the centre of pixel (u, v). */
static int64_t centre_num(const fast_line *f, int64_t u, int64_t v)
{
    return (u * S + H - f->au) * f->du + (v * S + H - f->av) * f->dv;
}

/* The path pixels of columns [ka, kb] (all inside the rectangle).  The
 * DDA steps the pixel's minor index with Bresenham's error term (the
 * remainder), and with it the buffer element and the exact numerator, by
 * integer adds. */
SR_INLINE uint64_t walk_columns_as(const fast_line *f, int64_t ka, int64_t kb, line_color mode,
                                   bool less)
{
    const sr_line *l = f->l;
    /* |dn| <= d (|slope| <= 1), so the DDA's whole step is -1, 0 or 1. */
    int64_t d = l->d, dn = l->dn;
    int64_t dq = dn >= d ? 1 : dn < 0 ? -1 : 0, dr = dn - dq * d;
    int64_t n = l->n0 + (ka - l->k0) * dn;
    int64_t j = sr__floor_div(n, d), rem = n - j * d;
    int64_t num = centre_num(f, ka, j);
    size_t idx = (size_t)ka * f->step_u + (size_t)j * f->step_v;
    int64_t num_u = S * f->du + dq * (S * f->dv), num_v = S * f->dv;
    size_t idx_u = f->step_u + (size_t)dq * f->step_v, idx_v = f->step_v;
    /* The end's pixel, when on the path, is its column's pixel: skipping
     * that column leaves it open (half-open). */
    int64_t skip = l->end_u;
    uint64_t frags = 0;
    for (int64_t k = ka; k <= kb; k++) {
        if (k != skip) {
            frags += fast_pixel(f, idx, num, mode, less);
        }
        rem += dr;
        num += num_u;
        idx += idx_u;
        if (rem >= d) {
            rem -= d;
            num += num_v;
            idx += idx_v;
        }
    }
    return frags;
}

/* The off-path start pixel, drawn after the path when inside the
 * rectangle r (see sr__raster_line). */
SR_INLINE uint64_t start_pixel_as(const fast_line *f, const int r[4], line_color mode,
                                  bool less)
{
    const sr_line *l = f->l;
    if (l->start_extra && l->start_u >= r[0] && l->start_u < r[1] && l->start_v >= r[2] &&
        l->start_v < r[3]) {
        return fast_pixel(f, (size_t)l->start_u * f->step_u + (size_t)l->start_v * f->step_v,
                          centre_num(f, l->start_u, l->start_v), mode, less);
    }
    return 0;
}

/* The fragments written: the path, then the start pixel (the
 * reference's order). */
SR_INLINE uint64_t walk_fast_as(const fast_line *f, int64_t ka, int64_t kb, const int r[4],
                                line_color mode, bool less)
{
    uint64_t frags = walk_columns_as(f, ka, kb, mode, less);
    return frags + start_pixel_as(f, r, mode, less);
}

/* ---- four columns at a time (AVX2) ----
 * The commonest state (interpolated color, equal 1/w, depth off) takes
 * four columns per step when the CPU has AVX2.  Each column's pixel comes
 * from the closed form instead of the DDA, so lanes need no start-up and
 * a range splits freely: j = floor(N / d) with N = n0 + (k - k0) dn.  In
 * double lanes N (< 2^48) and d (< 2^31) are exact, and so is the floor of
 * their rounded quotient: an exact integer quotient is representable and
 * comes out exactly, and any other lies at least 1/d > 2^-31 from an
 * integer, farther than the rounding (half an ulp of |j| < 2^21) can move
 * it.  The projection's numerator, a sum of integer products below 2^48,
 * and the buffer element (< 2^29) are exact too.  t, its float, the color
 * and its packing then repeat the scalar path lane by lane. */
#if defined(__GNUC__) && defined(__SSE2__) && (defined(__x86_64__) || defined(__i386__)) && \
    defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
#define SR_LINE_AVX2 1
#include <immintrin.h>

/* Whether the AVX2 walk runs: the CPU has AVX2 and SR_SIMD does not cap
 * the vector kernels below it.  Read once, at the first line drawn
 * (per call it would cost a getenv per line and tile). */
static bool line_avx2(void)
{
    static int cached = -1;
    int v = __atomic_load_n(&cached, __ATOMIC_RELAXED);
    if (v < 0) {
        v = sr__simd_level() >= SR_SIMD_AVX2;
        __atomic_store_n(&cached, v, __ATOMIC_RELAXED);
    }
    return v;
}

/* sr__unorm8 on four pixels' r, g, b, a lanes, packed per pixel: the
 * triangle kernels' packing (see pack_unorm8 for why it is the same). */
SR_INLINE __m128i pack4_unorm8(const __m128 c[4])
{
    __m128i q[4];
    for (int k = 0; k < 4; k++) {
        __m128 v = _mm_min_ps(_mm_set1_ps(1.0f), c[k]);
        q[k] = _mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(v, _mm_set1_ps(255.0f)),
                                           _mm_set1_ps(0.5f)));
    }
    /* Bytes R0..3 B0..3 G0..3 A0..3, then interleaved to R G B A per pixel. */
    __m128i x = _mm_packus_epi16(_mm_packs_epi32(q[0], q[2]), _mm_packs_epi32(q[1], q[3]));
    __m128i y = _mm_unpacklo_epi8(x, _mm_srli_si128(x, 8));
    return _mm_unpacklo_epi16(y, _mm_srli_si128(y, 8));
}

/* Columns [ka, kb], every one drawn (the caller leaves out the end's). */
__attribute__((target("avx2"))) static uint64_t walk_lerp_avx2(const fast_line *f, int64_t ka,
                                                                int64_t kb)
{
    const sr_line *l = f->l;
    const __m256d n0 = _mm256_set1_pd((double)l->n0), dn = _mm256_set1_pd((double)l->dn);
    const __m256d d = _mm256_set1_pd((double)l->d), k0 = _mm256_set1_pd((double)l->k0);
    /* num = (k S + H - a_u) du + (j S + H - a_v) dv = a + k b + j c */
    const __m256d a = _mm256_set1_pd((double)((H - f->au) * f->du + (H - f->av) * f->dv));
    const __m256d b = _mm256_set1_pd((double)(S * f->du)), c = _mm256_set1_pd((double)(S * f->dv));
    const __m256d su = _mm256_set1_pd((double)f->step_u), sv = _mm256_set1_pd((double)f->step_v);
    const __m256d inv = _mm256_set1_pd(f->inv_len2);
    const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
    __m128 va[4], dva[4];
    for (int ch = 0; ch < 4; ch++) {
        va[ch] = _mm_set1_ps(f->va[ch]);
        dva[ch] = _mm_set1_ps(f->dvary[ch]);
    }
    __m256d k = _mm256_add_pd(_mm256_set1_pd((double)ka), _mm256_setr_pd(0, 1, 2, 3));
    for (int64_t kk = ka; kk <= kb; kk += 4) {
        __m256d nn = _mm256_add_pd(n0, _mm256_mul_pd(_mm256_sub_pd(k, k0), dn));
        __m256d j = _mm256_floor_pd(_mm256_div_pd(nn, d));
        __m256d num = _mm256_add_pd(_mm256_add_pd(a, _mm256_mul_pd(k, b)), _mm256_mul_pd(j, c));
        /* max then min, as fast_pixel (t is never NaN or -0). */
        __m256d t = _mm256_min_pd(_mm256_max_pd(_mm256_mul_pd(num, inv), zero), one);
        __m128 tf = _mm256_cvtpd_ps(t);
        __m128 col[4];
        for (int ch = 0; ch < 4; ch++) {
            col[ch] = _mm_add_ps(va[ch], _mm_mul_ps(tf, dva[ch]));
        }
        uint32_t px[4], idx[4];
        _mm_storeu_si128((__m128i *)px, pack4_unorm8(col));
        _mm_storeu_si128((__m128i *)idx, _mm256_cvttpd_epi32(_mm256_add_pd(
                                              _mm256_mul_pd(k, su), _mm256_mul_pd(j, sv))));
        int lanes = kb - kk < 3 ? (int)(kb - kk + 1) : 4;
        for (int i = 0; i < lanes; i++) {
            f->color[idx[i]] = px[i];
        }
        k = _mm256_add_pd(k, _mm256_set1_pd(4.0));
    }
    return kb >= ka ? (uint64_t)(kb - ka + 1) : 0;
}

/* The columns [ka, kb] but the end's (half-open), then the start pixel. */
static uint64_t walk_lerp_x4(const fast_line *f, int64_t ka, int64_t kb, const int r[4])
{
    int64_t skip = f->l->end_u;
    uint64_t frags;
    if (skip >= ka && skip <= kb) {
        frags = walk_lerp_avx2(f, ka, skip - 1) + walk_lerp_avx2(f, skip + 1, kb);
    } else {
        frags = walk_lerp_avx2(f, ka, kb);
    }
    return frags + start_pixel_as(f, r, LINE_COLOR_LERP, false);
}
#endif

/* r: the rectangle as major [r[0], r[1]) and minor [r[2], r[3]). */
static void walk_fast(const sr_draw_state *ds, const sr_line *l, int64_t ka, int64_t kb,
                      const int r[4], sr_frag_stats *st)
{
    sr_framebuffer *fb = ds->fb;
    size_t width = (size_t)fb->width;
    fast_line f = { .ds = ds, .l = l, .color = fb->color, .depth = fb->depth };
    f.step_u = l->xmajor ? 1 : width;
    f.step_v = l->xmajor ? width : 1;
    f.au = l->xmajor ? l->xa : l->ya;
    f.av = l->xmajor ? l->ya : l->xa;
    f.du = (int64_t)(l->xmajor ? l->xb : l->yb) - f.au;
    f.dv = (int64_t)(l->xmajor ? l->yb : l->xb) - f.av;
    f.dz = l->zb - l->za;
    f.inv_len2 = inv_len2(l);
    line_color mode = LINE_COLOR_FLAT;
    if (ds->shading == SR_SHADING_FLAT) {
        memcpy(&f.va, l->flat, sizeof f.va);
        f.flat = pack_unorm8(f.va);
    } else {
        int n = l->ninterp;
        memcpy(&f.va, &l->vary[SR_VARY_COLOR], sizeof f.va);
        memcpy(&f.vb, &l->vary[n + SR_VARY_COLOR], sizeof f.vb);
        f.dvary = f.vb - f.va;
        mode = l->wa == l->wb ? LINE_COLOR_LERP : LINE_COLOR_PERSPECTIVE;
    }
    /* Instances per color mode and depth mode: the branches fold away. */
    bool less = ds->depth_mode == SR_DEPTH_MODE_LESS;
    uint64_t frags;
    switch (mode) {
    case LINE_COLOR_FLAT:
        frags = less ? walk_fast_as(&f, ka, kb, r, LINE_COLOR_FLAT, true)
                     : walk_fast_as(&f, ka, kb, r, LINE_COLOR_FLAT, false);
        break;
    case LINE_COLOR_LERP:
#ifdef SR_LINE_AVX2
        if (!less && line_avx2()) {
            frags = walk_lerp_x4(&f, ka, kb, r);
            break;
        }
#endif
        frags = less ? walk_fast_as(&f, ka, kb, r, LINE_COLOR_LERP, true)
                     : walk_fast_as(&f, ka, kb, r, LINE_COLOR_LERP, false);
        break;
    default:
        frags = less ? walk_fast_as(&f, ka, kb, r, LINE_COLOR_PERSPECTIVE, true)
                     : walk_fast_as(&f, ka, kb, r, LINE_COLOR_PERSPECTIVE, false);
        break;
    }
    st->fragments += frags;
}

void sr__raster_line(const sr_draw_state *ds, const sr_line *l, int rx0, int ry0, int rx1,
                     int ry1, sr_frag_stats *st)
{
    /* A tile's records lie scattered through the chunk, so each visit
     * starts with cache misses.  Ask for the record's later lines now:
     * the varyings' place depends on ninterp, and loading them would
     * otherwise wait for the first line's miss before starting its own. */
    for (size_t off = 64; off < offsetof(sr_line, vary) + 2 * 4 * sizeof(float); off += 64) {
        __builtin_prefetch((const char *)l + off);
    }
    if (l->smooth) {
        raster_smooth_line(ds, l, rx0, ry0, rx1, ry1, st);
        return;
    }
    bool xmajor = l->xmajor;
    /* The rectangle as major [r[0], r[1]) and minor [r[2], r[3]). */
    int r[4] = { xmajor ? rx0 : ry0, xmajor ? rx1 : ry1, xmajor ? ry0 : rx0, xmajor ? ry1 : rx1 };
    /* Columns inside the rectangle whose path pixel, or some pixel of its
     * run across the minor axis, falls inside it. */
    int below = (l->width - 1) / 2, above = l->width - 1 - below;
    int64_t ka, kb;
    if (!column_range(l, r[0], r[1] - 1, r[2] - above, r[3] - 1 + below, &ka, &kb)) {
        ka = 0;
        kb = -1;
    }
    if (line_is_fast(ds, l)) {
        walk_fast(ds, l, ka, kb, r, st);
        return;
    }
    line_ctx lc = { ds, l, rx0, ry0, rx1, ry1, xmajor, st, inv_len2(l), l->wa == l->wb };
    walk_generic(&lc, ka, kb);
}
