/* polygon_offset.c - polygon offset (raster stage): the depth offset of a
 * triangle's fill, outline or vertices from its snapped plane's slope and
 * the depth format's resolution.  Consumes window vertices, produces an
 * offset in depth-range units for setup (setup_tri.h, line_setup.c).  Any
 * thread; no shared state. */
#include "pipeline.h"
#include "fragment/depth.h"

#include <math.h>

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
