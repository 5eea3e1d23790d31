/* line_setup.c - a clipped segment into a binned record (raster stage,
 * front-end workers): the diamond-exit rule's closed form (docs/raster-rules.md
 * §7.1, see line.c) solved once per segment - the columns the segment
 * spans, the DDA of their pixels, the start's and end's diamond pixels -
 * and the tiles its pixels reach, so binning puts the segment only in
 * those, not in its whole bounding box. */
#include "fragment/msaa_ops.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define H SR_SUBPIXEL_HALF
#define S SR_SUBPIXEL_ONE

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
 * diamonds own the two ends.  A wide line's are those of its path: the
 * segment moved by -(width - 1)/2 px along the minor axis, (width - 1)
 * half pixels, exact in q8 (GL's wide lines, docs/raster-rules.md §7.2); each path
 * pixel then starts a run of `width` pixels toward +minor.  For an odd
 * width that is the one-pixel line's pixel with (width - 1)/2 on each
 * side; for an even width the run's extra pixel is on the side where the
 * line passes the column centre, not always below it. */
static void setup_walk(sr_line *l)
{
    int64_t dx = (int64_t)l->xb - l->xa, dy = (int64_t)l->yb - l->ya;
    bool xmajor = llabs(dx) >= llabs(dy);
    l->xmajor = xmajor;
    int64_t shift = (int64_t)(l->width - 1) * H;
    int64_t xa = l->xa - (xmajor ? 0 : shift), xb = l->xb - (xmajor ? 0 : shift);
    int64_t ya = l->ya - (xmajor ? shift : 0), yb = l->yb - (xmajor ? shift : 0);
    /* Columns whose centre lies within the segment's major extent. */
    int64_t au = xmajor ? xa : ya, bu = xmajor ? xb : yb;
    int64_t av = xmajor ? ya : xa, bv = xmajor ? yb : xb;
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
    bool start_in = diamond_owner(xa, ya, xmajor, &sx, &sy);
    bool end_in = diamond_owner(xb, yb, xmajor, &ex, &ey);
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
    /* A wide line's run starts at its path pixel and reaches width - 1
     * pixels toward +minor (see setup_walk). */
    *v0 = (int)lo;
    *v1 = (int)hi + (l->width - 1);
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
