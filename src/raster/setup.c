/* setup.c - triangle setup (raster stage): divide by w, viewport S, snap to
 * 8 sub-pixel bits, facing and culling from the snapped signed area, the
 * three integer edge functions with the top-left fill rule folded in as a
 * bias, the bounding box, the depth plane with its polygon offset
 * (polygon_offset.c).  Produces the sr_tri the rasterizers consume.  Any thread; no shared state. */
#include "raster/setup_tri.h"

#include <math.h>
#include <string.h>

void sr__window_vertex(const sr_draw_state *ds, const sr_clip_vertex *v, sr_window_vertex *out)
{
    sr__project(ds, v->pos, &out->x_q8, &out->y_q8, &out->z, &out->inv_w);
    out->vary = v->vary;
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
