/* arc.h - internal: an SVG elliptical arc in centre form, shared by its
 * flattening (curves.c) and by the paths that cull arcs far outside a
 * view piece by piece (path.c). */
#ifndef SR_DRAW2D_ARC_H
#define SR_DRAW2D_ARC_H

#include "softrast.h"

/* The point at angle t: centre + rotation (cphi, sphi) of (rx cos t,
 * ry sin t); the arc runs from theta1 over dtheta (signed). */
typedef struct sr__arc {
    double cx, cy, rx, ry, cphi, sphi;
    double theta1, dtheta;
} sr__arc;

typedef enum sr__arc_kind {
    SR__ARC_CURVED,     /* *arc holds it */
    SR__ARC_OMITTED,    /* from == to: SVG draws nothing */
    SR__ARC_LINE,       /* a zero radius: a line to the end point */
    SR__ARC_FAR_ENDS,   /* the end points too far apart for doubles */
    SR__ARC_FAR_CENTRE, /* the radii put the centre beyond doubles */
} sr__arc_kind;

/* SVG 1.1 F.6.5 for finite arguments (absolute radii, F.6.6's scaling). */
sr__arc_kind sr__arc_centre(sr_point2 from, double rx, double ry, double rotation_deg,
                            bool large_arc, bool sweep, sr_point2 to, sr__arc *arc);
/* Chords for dtheta radians of the arc within tolerance, 1 .. 2^16. */
int sr__arc_steps(const sr__arc *arc, double dtheta, double tolerance);
/* The n points after angle t0 at steps of dtheta / n, the last one `to`. */
void sr__arc_points(const sr__arc *arc, double t0, double dtheta, int n, sr_point2 to,
                    sr_point2 *out);
/* The point at angle t. */
sr_point2 sr__arc_point(const sr__arc *arc, double t);

#endif
