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
 * are OpenGL's: a run of `width` pixels across the minor axis per step. */
#include "fragment/sample.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define H SR_SUBPIXEL_HALF
#define S SR_SUBPIXEL_ONE

static int clampi(int64_t v, int lo, int hi)
{
    return v < lo ? lo : v > hi ? hi : (int)v;
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

/* Is p (q8) inside the diamond of pixel (qx, qy), with Direct3D's boundary
 * ownership: the lower edges and bottom corner belong to it, and for a
 * y-major line also the right corner (y points down, so "lower" is +y). */
static bool in_diamond(int64_t x, int64_t y, int qx, int qy, bool xmajor)
{
    int64_t dx = x - ((int64_t)qx * S + H), dy = y - ((int64_t)qy * S + H);
    int64_t d = llabs(dx) + llabs(dy);
    return d < H || (d == H && (dy > 0 || (!xmajor && dx == H && dy == 0)));
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

void sr__raster_line(const sr_draw_state *ds, const sr_line *l, int rx0, int ry0, int rx1,
                     int ry1, sr_frag_stats *st)
{
    if (l->smooth) {
        raster_smooth_line(ds, l, rx0, ry0, rx1, ry1, st);
        return;
    }
    int64_t dx = (int64_t)l->xb - l->xa, dy = (int64_t)l->yb - l->ya;
    line_ctx lc = { ds, l, rx0, ry0, rx1, ry1, llabs(dx) >= llabs(dy), st,
                    1.0 / ((double)dx * dx + (double)dy * dy), l->wa == l->wb };
    bool xmajor = lc.xmajor;
    int pad = l->width / 2 + 1;
    /* Columns whose centre lies within the segment's major extent, limited
     * to those that can reach this rectangle. */
    int64_t au = xmajor ? l->xa : l->ya, bu = xmajor ? l->xb : l->yb;
    int64_t lo = au < bu ? au : bu, hi = au ^ bu ^ lo;
    int64_t k0 = sr__ceil_div(lo - H, S), k1 = sr__floor_div(hi - H, S);
    int64_t r0 = (xmajor ? rx0 : ry0) - pad, r1 = (xmajor ? rx1 : ry1) + pad;
    k0 = k0 > r0 ? k0 : r0;
    k1 = k1 < r1 ? k1 : r1;

    /* The start diamond's pixel, and the end's (excluded). */
    int sx = (int)sr__floor_div(l->xa, S), sy = (int)sr__floor_div(l->ya, S);
    int ex = (int)sr__floor_div(l->xb, S), ey = (int)sr__floor_div(l->yb, S);
    bool start_in = false, end_in = false;
    int start_px = 0, start_py = 0, end_px = 0, end_py = 0;
    /* Candidates: the pixels whose closed squares can hold the point, the
     * one it lies in and its left and upper neighbours (a point on a pixel
     * boundary).  At most one diamond owns a point. */
    for (int cy = 0; cy < 2; cy++) {
        for (int cx = 0; cx < 2; cx++) {
            int qx = sx - cx, qy = sy - cy;
            if (!start_in && in_diamond(l->xa, l->ya, qx, qy, xmajor)) {
                start_in = true;
                start_px = qx;
                start_py = qy;
            }
            int rx = ex - cx, ry = ey - cy;
            if (!end_in && in_diamond(l->xb, l->yb, rx, ry, xmajor)) {
                end_in = true;
                end_px = rx;
                end_py = ry;
            }
        }
    }

    /* The minor coordinate at column centre c is num/den with
     * num = a_v (b_u - a_u) + (c - a_u)(b_v - a_v), den = b_u - a_u (made
     * positive); the column's pixel is j = ceil(num / 256 den) - 1 =
     * floor((num - 1) / 256 den), a point on a pixel boundary going to the
     * smaller index.  num grows by 256 (b_v - a_v) per column: a DDA. */
    int64_t av = xmajor ? l->ya : l->xa, bv = xmajor ? l->yb : l->xb;
    int64_t den = bu - au, sign = den < 0 ? -1 : 1;
    int64_t num0 = av * (bu - au) + (k0 * S + H - au) * (bv - av);
    sr_dda dda;
    sr__dda_init(&dda, sign * num0 - 1, sign * den * S, sign * S * (bv - av));

    bool start_done = false;
    for (int64_t k = k0; k <= k1; k++, sr__dda_step(&dda)) {
        int64_t j = dda.q;
        if (j < INT32_MIN + 1 || j > INT32_MAX - 1) {
            continue;
        }
        int px = xmajor ? (int)k : (int)j, py = xmajor ? (int)j : (int)k;
        if (end_in && px == end_px && py == end_py) {
            continue; /* half-open: the end's own pixel is not drawn */
        }
        if (start_in && px == start_px && py == start_py) {
            start_done = true;
        }
        line_fragment(&lc, px, py);
    }
    if (start_in && !start_done && !(end_in && start_px == end_px && start_py == end_py)) {
        line_fragment(&lc, start_px, start_py);
    }
}
