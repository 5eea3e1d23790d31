/* setup.c - triangle setup (raster stage): divide by w, viewport S, snap to
 * 8 sub-pixel bits, facing and culling from the snapped signed area, the
 * three integer edge functions with the top-left fill rule folded in as a
 * bias, the bounding box, the depth plane and polygon offset.  Produces the
 * sr_tri the rasterizers consume.  Any thread; no shared state. */
#include "pipeline.h"
#include "fragment/depth.h"

#include <math.h>
#include <string.h>

/* Clamp to the fixed-point range (clipping already keeps vertices inside
 * the guard band; the clamp only absorbs rounding at the band's edge), then
 * round to nearest even.  Adding and subtracting 1.5 x 2^52 rounds any
 * |s| < 2^51 to an integer in the default rounding mode, exactly as
 * nearbyint would, without the library call baseline x86-64 makes for it
 * (two per vertex). */
static int32_t snap_q8(double v)
{
    const double lim = (double)SR_GUARD_BAND_MAX * SR_SUBPIXEL_ONE;
    const double magic = 6755399441055744.0; /* 1.5 x 2^52 */
    double s = v * SR_SUBPIXEL_ONE;
    s = s > lim ? lim : s;
    s = s < -lim ? -lim : s;
    s = (s + magic) - magic;
    return (int32_t)s;
}

/* One fixed operation order (RASTER_RULES 1.2), in double, one rounding
 * at the snap: the same clip position always gives the same q8 value. */
void sr__project(const sr_draw_state *ds, const float pos[4], int32_t *x_q8, int32_t *y_q8,
                 double *z, float *inv_w)
{
    double iw = 1.0 / pos[3];
    double xn = pos[0] * iw, yn = pos[1] * iw, zn = pos[2] * iw;
    *x_q8 = snap_q8(ds->vp_ox + ds->vp_px * xn);
    *y_q8 = snap_q8(ds->vp_oy - ds->vp_py * yn);
    *z = ds->vp_zs * zn + ds->vp_zb;
    *inv_w = (float)iw;
}

void sr__window_vertex(const sr_draw_state *ds, const sr_clip_vertex *v, sr_window_vertex *out)
{
    sr__project(ds, v->pos, &out->x_q8, &out->y_q8, &out->z, &out->inv_w);
    out->vary = v->vary;
}


/* y points down.  With area2 > 0 the interior has E > 0.  A top edge is
 * horizontal and runs toward +x; a left edge runs upward (dy < 0).  Samples
 * exactly on a top or left edge are inside, on any other edge outside. */
static bool is_top_left(int64_t dx, int64_t dy)
{
    return dy < 0 || (dy == 0 && dx > 0);
}

/* Polygon offset o = factor m + units r, with the slope m of the triangle's
 * snapped plane (RASTER_RULES 5.3), in depth-range units.  Applied to the
 * triangle's fill, or to its outline or vertices in the other polygon
 * modes, each enabled separately. */
double sr__polygon_offset(const sr_draw_state *ds, const sr_window_vertex *v0,
                          const sr_window_vertex *v1, const sr_window_vertex *v2,
                          sr_polygon_mode mode)
{
    bool on = mode == SR_POLYGON_LINE ? ds->offset_line
            : mode == SR_POLYGON_POINT ? ds->offset_point : ds->offset_on;
    if (!on) {
        return 0.0;
    }
    int64_t area2 = sr__area2(v0, v1, v2);
    if (area2 == 0) {
        return 0.0;
    }
    double dx1 = v1->x_q8 - v0->x_q8, dy1 = v1->y_q8 - v0->y_q8;
    double dx2 = v2->x_q8 - v0->x_q8, dy2 = v2->y_q8 - v0->y_q8;
    double dz1 = v1->z - v0->z, dz2 = v2->z - v0->z;
    double dzdx = (dz1 * dy2 - dz2 * dy1) * SR_SUBPIXEL_ONE / (double)area2;
    double dzdy = (dx1 * dz2 - dx2 * dz1) * SR_SUBPIXEL_ONE / (double)area2;
    double m = fmax(fabs(dzdx), fabs(dzdy));
    double maxz = fmax(fabs(v0->z), fmax(fabs(v1->z), fabs(v2->z)));
    double r = sr__depth_r(ds->depth_bits, maxz);
    double o = ds->offset_factor * m + ds->offset_units * r;
    if (ds->offset_clamp > 0.0) {
        o = fmin(o, ds->offset_clamp);
    } else if (ds->offset_clamp < 0.0) {
        o = fmax(o, ds->offset_clamp);
    }
    return o;
}

bool sr__setup_triangle(const sr_draw_state *ds, const sr_window_vertex *w0,
                        const sr_window_vertex *w1, const sr_window_vertex *w2,
                        bool front, int ninterp, const float flat[4], sr_tri *t)
{
    return sr__setup_triangle_offset(ds, w0, w1, w2, NAN, front, ninterp, flat, t);
}

bool sr__setup_triangle_offset(const sr_draw_state *ds, const sr_window_vertex *w0,
                               const sr_window_vertex *w1, const sr_window_vertex *w2,
                               double offset, bool front, int ninterp, const float flat[4],
                               sr_tri *t)
{
    const sr_window_vertex *v[3] = { w0, w1, w2 };
    int64_t area2 = sr__area2(w0, w1, w2);
    if (area2 == 0) {
        return false;
    }
    /* Coverage needs area2 > 0: swap v1 and v2 (their attributes go with
     * them, so barycentric weights still pair with the right values). */
    if (area2 < 0) {
        v[1] = w2;
        v[2] = w1;
        area2 = -area2;
    }
    t->area2 = area2;
    t->front = front;

    int32_t minx = INT32_MAX, miny = INT32_MAX, maxx = INT32_MIN, maxy = INT32_MIN;
    for (int i = 0; i < 3; i++) {
        t->x[i] = v[i]->x_q8;
        t->y[i] = v[i]->y_q8;
        minx = t->x[i] < minx ? t->x[i] : minx;
        maxx = t->x[i] > maxx ? t->x[i] : maxx;
        miny = t->y[i] < miny ? t->y[i] : miny;
        maxy = t->y[i] > maxy ? t->y[i] : maxy;
    }
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
    t->h.kind = SR_KIND_TRIANGLE;
    t->h.x0 = x0 > ds->rect_x0 ? x0 : ds->rect_x0;
    t->h.y0 = y0 > ds->rect_y0 ? y0 : ds->rect_y0;
    t->h.x1 = x1 < ds->rect_x1 ? x1 : ds->rect_x1;
    t->h.y1 = y1 < ds->rect_y1 ? y1 : ds->rect_y1;
    if (t->h.x0 >= t->h.x1 || t->h.y0 >= t->h.y1) {
        return false;
    }

    /* Edge i runs from vertex i+1 to vertex i+2 and is opposite vertex i:
     * E_i(p) = (b.x - a.x)(p.y - a.y) - (b.y - a.y)(p.x - a.x). */
    for (int i = 0; i < 3; i++) {
        int a = (i + 1) % 3, b = (i + 2) % 3;
        int64_t dx = (int64_t)t->x[b] - t->x[a];
        int64_t dy = (int64_t)t->y[b] - t->y[a];
        t->a[i] = -dy;
        t->b[i] = dx;
        t->c[i] = dy * t->x[a] - dx * t->y[a];
        t->bias[i] = is_top_left(dx, dy) ? 0 : -1;
    }

    /* Depth: linear in screen space (RASTER_RULES 4.1). */
    double z[3] = { v[0]->z, v[1]->z, v[2]->z };
    /* NaN: the fill's own offset; otherwise the caller's (the quads that
     * stand for multisampled lines carry their line's). */
    if (isnan(offset)) {
        offset = sr__polygon_offset(ds, v[0], v[1], v[2], SR_POLYGON_FILL);
    }
    /* The depth plane, in buffer units so the fragment stage only adds,
     * clamps and rounds. */
    double scale = ds->depth_scale;
    t->z0 = (z[0] + offset) * scale;
    /* Interpolated depths lie between the vertex depths up to rounding of
     * a few ulps; a margin of 1e-9 of the scale is far larger. */
    double zlo = fmin(z[0], fmin(z[1], z[2])) + offset, zhi = fmax(z[0], fmax(z[1], z[2])) + offset;
    t->z_inside = zlo * scale > ds->zq_min + 1e-9 * scale && zhi * scale < ds->zq_max - 1e-9 * scale;
    double per_area = scale / (double)area2;
    t->dz1 = (z[1] - z[0]) * per_area;
    t->dz2 = (z[2] - z[0]) * per_area;

    for (int i = 0; i < 3; i++) {
        t->w[i] = ds->perspective ? v[i]->inv_w : 1.0f;
    }
    t->ninterp = ninterp;
    for (int k = 0; k < ninterp; k++) {
        float a0 = v[0]->vary[k];
        t->vary[k] = a0;
        t->vary[ninterp + k] = v[1]->vary[k] - a0;
        t->vary[2 * ninterp + k] = v[2]->vary[k] - a0;
    }
    if (flat) {
        memcpy(t->flat, flat, sizeof t->flat);
    }
    return true;
}
