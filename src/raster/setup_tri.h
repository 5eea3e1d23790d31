/* setup_tri.h - the body of triangle setup (raster stage), inline so the
 * front end's common case (geometry/assembly.c: a triangle inside every
 * clip plane) sets up without a call, and setup.c's entry points share it.  Produces
 * the sr_tri the rasterizers consume.  Any thread; no shared state. */
#ifndef SR_SETUP_TRI_H
#define SR_SETUP_TRI_H

#include "pipeline.h"

#include <math.h>
#include <string.h>

/* The smaller and larger of two depths as minsd and maxsd give them (the
 * second operand when they compare equal), which is also what fmin and
 * fmax return for the finite depths of set-up vertices - without the
 * library calls. */
static inline double sr__min_d(double a, double b) { return a < b ? a : b; }
static inline double sr__max_d(double a, double b) { return a > b ? a : b; }

/* sr__setup_triangle_offset once the snapped area2 = sr__area2(w0, w1, w2)
 * is known and non-zero.  Always inlined: the front end's common case
 * calls it directly, and a constant ninterp unrolls the varyings. */
static inline __attribute__((always_inline)) bool
sr__setup_tri(const sr_draw_state *ds, const sr_window_vertex *w0, const sr_window_vertex *w1,
              const sr_window_vertex *w2, int64_t area2, double offset, bool front, int ninterp,
              const float flat[4], sr_tri *t)
{
    const sr_window_vertex *v[3] = { w0, w1, w2 };
    /* Coverage needs area2 > 0: swap v1 and v2 (their attributes go with
     * them, so barycentric weights still pair with the right values). */
    if (area2 < 0) {
        v[1] = w2;
        v[2] = w1;
        area2 = -area2;
    }

    int32_t x[3] = { v[0]->x_q8, v[1]->x_q8, v[2]->x_q8 };
    int32_t y[3] = { v[0]->y_q8, v[1]->y_q8, v[2]->y_q8 };
    int32_t minx = x[0] < x[1] ? x[0] : x[1], maxx = x[0] < x[1] ? x[1] : x[0];
    int32_t miny = y[0] < y[1] ? y[0] : y[1], maxy = y[0] < y[1] ? y[1] : y[0];
    minx = x[2] < minx ? x[2] : minx;
    maxx = x[2] > maxx ? x[2] : maxx;
    miny = y[2] < miny ? y[2] : miny;
    maxy = y[2] > maxy ? y[2] : maxy;
    /* Pixels whose centre 256 p + 128 lies in [min, max]; multisampled,
     * pixels whose square [256 p, 256 p + 256) meets it. */
    int x0, x1, y0, y1;
    if (ds->samples > 1) {
        x0 = (int)sr__floor_q8(minx);
        x1 = (int)sr__floor_q8(maxx) + 1;
        y0 = (int)sr__floor_q8(miny);
        y1 = (int)sr__floor_q8(maxy) + 1;
    } else {
        x0 = (int)sr__ceil_q8((int64_t)minx - SR_SUBPIXEL_HALF);
        x1 = (int)sr__floor_q8((int64_t)maxx - SR_SUBPIXEL_HALF) + 1;
        y0 = (int)sr__ceil_q8((int64_t)miny - SR_SUBPIXEL_HALF);
        y1 = (int)sr__floor_q8((int64_t)maxy - SR_SUBPIXEL_HALF) + 1;
    }
    x0 = x0 > ds->rect_x0 ? x0 : ds->rect_x0;
    y0 = y0 > ds->rect_y0 ? y0 : ds->rect_y0;
    x1 = x1 < ds->rect_x1 ? x1 : ds->rect_x1;
    y1 = y1 < ds->rect_y1 ? y1 : ds->rect_y1;
    /* A tiny triangle between pixel centres covers nothing: out before
     * any of the record is written. */
    if (x0 >= x1 || y0 >= y1) {
        return false;
    }
    t->h.kind = SR_KIND_TRIANGLE;
    t->h.x0 = x0;
    t->h.y0 = y0;
    t->h.x1 = x1;
    t->h.y1 = y1;
    t->front = front;

    /* Edge i runs from vertex i+1 to vertex i+2 and is opposite vertex i:
     * E_i(p) = (b.x - a.x)(p.y - a.y) - (b.y - a.y)(p.x - a.x). */
    for (int i = 0; i < 3; i++) {
        int a = (i + 1) % 3, b = (i + 2) % 3;
        int64_t dx = (int64_t)x[b] - x[a];
        int64_t dy = (int64_t)y[b] - y[a];
        t->a[i] = (int32_t)-dy;   /* |dy|, |dx| < 2^23 (fixed.h) */
        t->b[i] = (int32_t)dx;
    }
    /* c_i = dy x_a - dx y_a and the top-left bias (sr__is_top_left) are
     * rebuilt from these where needed (sr__tri_c, sr__tri_bias). */
    t->x0_q8 = x[0];
    t->y0_q8 = y[0];

    /* E_i(p) is twice the signed area of the triangle p makes with edge
     * i, so wherever p lies within a box that holds the edge, |E_i(p)| is
     * at most that box's area.  The pixel centres the kernels visit lie
     * within the vertex spans, widened by half a pixel each way when
     * multisampled: |E_i| <= (span_x + 256)(span_y + 256) there.  Small
     * triangles thus skip the per-tile check of their box
     * (sr__rect_fits32), which was a tenth of the kernel's time for the
     * bench's `small`.  The spans are held below 2^24 so the product
     * cannot overflow (a held one already fails the test), with selects
     * rather than branches. */
    int64_t span_x = (int64_t)maxx - minx + SR_SUBPIXEL_ONE;
    int64_t span_y = (int64_t)maxy - miny + SR_SUBPIXEL_ONE;
    const int64_t held = (int64_t)1 << 24;
    span_x = span_x < held ? span_x : held;
    span_y = span_y < held ? span_y : held;
    t->fits32 = span_x * span_y <= INT32_MAX - 1;

    /* Depth: linear in screen space (docs/raster-rules.md §5.2). */
    double z[3] = { v[0]->z, v[1]->z, v[2]->z };
    /* NaN: the fill's own offset (0 when it is off); otherwise the
     * caller's (the quads that stand for multisampled lines carry their
     * line's). */
    if (isnan(offset)) {
        offset = ds->offset_on ? sr__polygon_offset(ds, v[0], v[1], v[2], SR_POLYGON_FILL) : 0.0;
    }
    /* The depth plane, in buffer units so the fragment stage only adds,
     * clamps and rounds. */
    double scale = ds->depth_scale;
    t->z0 = (z[0] + offset) * scale;
    /* Interpolated depths lie between the vertex depths up to rounding of
     * a few ulps; a margin of 1e-9 of the scale is far larger. */
    double zlo = sr__min_d(z[0], sr__min_d(z[1], z[2])) + offset;
    double zhi = sr__max_d(z[0], sr__max_d(z[1], z[2])) + offset;
    t->z_inside = (zlo * scale > ds->zq_min + 1e-9 * scale) &
                  (zhi * scale < ds->zq_max - 1e-9 * scale);
    double per_area = scale / (double)area2;
    t->dz1 = (z[1] - z[0]) * per_area;
    t->dz2 = (z[2] - z[0]) * per_area;

    for (int i = 0; i < 3; i++) {
        t->w[i] = ds->perspective ? v[i]->inv_w : 1.0f;
    }
    t->ninterp = ninterp;
    /* Four varyings at a time where they fill a vector: the same
     * subtractions, lane by lane. */
    int k = 0;
    for (; k + 4 <= ninterp; k += 4) {
        v4f a0, a1, a2;
        memcpy(&a0, &v[0]->vary[k], sizeof a0);
        memcpy(&a1, &v[1]->vary[k], sizeof a1);
        memcpy(&a2, &v[2]->vary[k], sizeof a2);
        a1 -= a0;
        a2 -= a0;
        memcpy(&t->vary[k], &a0, sizeof a0);
        memcpy(&t->vary[ninterp + k], &a1, sizeof a1);
        memcpy(&t->vary[2 * ninterp + k], &a2, sizeof a2);
    }
    for (; k < ninterp; k++) {
        float a0 = v[0]->vary[k];
        t->vary[k] = a0;
        t->vary[ninterp + k] = v[1]->vary[k] - a0;
        t->vary[2 * ninterp + k] = v[2]->vary[k] - a0;
    }
    if (flat && ds->shading == SR_SHADING_FLAT) {
        memcpy(&t->vary[3 * ninterp], flat, 4 * sizeof(float)); /* sr__tri_flat */
    }
    return true;
}

#endif
