/* setup.c - triangle setup (raster stage): divide by w, viewport S, snap to
 * 8 sub-pixel bits, facing and culling from the snapped signed area, the
 * three integer edge functions with the top-left fill rule folded in as a
 * bias, the bounding box, the depth plane and polygon offset.  Produces the
 * sr_tri the rasterizers consume.  Any thread; no shared state. */
#include "raster/setup_tri.h"
#include "fragment/depth.h"

#include <math.h>
#include <string.h>

void sr__window_vertex(const sr_draw_state *ds, const sr_clip_vertex *v, sr_window_vertex *out)
{
    sr__project(ds, v->pos, &out->x_q8, &out->y_q8, &out->z, &out->inv_w);
    out->vary = v->vary;
}


/* Polygon offset o = factor m + units r, with the slope m of the triangle's
 * snapped plane (docs/raster-rules.md §6.4), in depth-range units.  Applied to the
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
    int64_t area2 = sr__area2(w0, w1, w2);
    if (area2 == 0) {
        return false;
    }
    return sr__setup_tri(ds, w0, w1, w2, area2, offset, front, ninterp, flat, t);
}
