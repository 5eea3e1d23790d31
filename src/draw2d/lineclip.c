/* lineclip.c - draw2d stage: clipping a segment to an axis-aligned
 * rectangle, by Cohen-Sutherland (region outcodes) and Liang-Barsky
 * (parametric p_k t <= q_k).  Consumes doubles, produces the visible part.
 * Used by every line rasterizer to bound the steps it visits; public for
 * other callers.  Pure functions: any thread. */
#include "draw2d/line.h"

#include <float.h>
#include <math.h>

static bool finite_input(sr_point2 rmin, sr_point2 rmax, const sr_point2 *a, const sr_point2 *b)
{
    return isfinite(rmin.x) && isfinite(rmin.y) && isfinite(rmax.x) && isfinite(rmax.y) &&
           isfinite(a->x) && isfinite(a->y) && isfinite(b->x) && isfinite(b->y) &&
           rmin.x <= rmax.x && rmin.y <= rmax.y;
}

/* ---- Cohen-Sutherland ----------------------------------------------------- */

enum { OUT_LEFT = 1, OUT_RIGHT = 2, OUT_TOP = 4, OUT_BOTTOM = 8 };   /* y down: top = ymin */

static unsigned outcode(sr_point2 rmin, sr_point2 rmax, sr_point2 p)
{
    unsigned c = 0;
    if (p.x < rmin.x) {
        c |= OUT_LEFT;
    } else if (p.x > rmax.x) {
        c |= OUT_RIGHT;
    }
    if (p.y < rmin.y) {
        c |= OUT_TOP;
    } else if (p.y > rmax.y) {
        c |= OUT_BOTTOM;
    }
    return c;
}

static bool cohen_sutherland(sr_point2 rmin, sr_point2 rmax, sr_point2 *a, sr_point2 *b)
{
    sr_point2 p = *a, q = *b;
    const sr_point2 o = *a;                          /* the original line: o + t d */
    const double dx = b->x - a->x, dy = b->y - a->y;
    unsigned cp = outcode(rmin, rmax, p), cq = outcode(rmin, rmax, q);
    /* Each pass moves one outside endpoint onto the boundary line of one
     * of its outcode bits.  The new point's coordinate on that axis is set
     * exactly, so that bit clears; rounding in the other coordinate can
     * set at most the other axis's bit, so 8 passes always suffice. */
    for (int pass = 0; pass < 8; pass++) {
        if ((cp | cq) == 0) {
            *a = p;
            *b = q;
            return true;
        }
        if (cp & cq) {
            return false;   /* both beyond the same boundary: trivial reject */
        }
        unsigned c = cp ? cp : cq;
        sr_point2 r;
        /* Intersections are computed from the original line, not from the
         * already moved endpoint, so rounding errors do not accumulate. */
        if (c & OUT_LEFT) {
            r.x = rmin.x;
            r.y = o.y + dy * ((rmin.x - o.x) / dx);
        } else if (c & OUT_RIGHT) {
            r.x = rmax.x;
            r.y = o.y + dy * ((rmax.x - o.x) / dx);
        } else if (c & OUT_TOP) {
            r.y = rmin.y;
            r.x = o.x + dx * ((rmin.y - o.y) / dy);
        } else {
            r.y = rmax.y;
            r.x = o.x + dx * ((rmax.y - o.y) / dy);
        }
        /* Rounding must not push the point just outside the other axis. */
        if (c & (OUT_LEFT | OUT_RIGHT)) {
            r.y = r.y < rmin.y && r.y > rmin.y - 1e-9 * (1 + fabs(rmin.y)) ? rmin.y : r.y;
            r.y = r.y > rmax.y && r.y < rmax.y + 1e-9 * (1 + fabs(rmax.y)) ? rmax.y : r.y;
        } else {
            r.x = r.x < rmin.x && r.x > rmin.x - 1e-9 * (1 + fabs(rmin.x)) ? rmin.x : r.x;
            r.x = r.x > rmax.x && r.x < rmax.x + 1e-9 * (1 + fabs(rmax.x)) ? rmax.x : r.x;
        }
        if (c == cp) {
            p = r;
            cp = outcode(rmin, rmax, p);
        } else {
            q = r;
            cq = outcode(rmin, rmax, q);
        }
    }
    return false;
}

/* ---- Liang-Barsky ----------------------------------------------------------- */

/* One boundary p t <= q: p < 0 enters, p > 0 leaves, p == 0 parallel. */
static bool lb_edge(double p, double q, double *t0, double *t1)
{
    if (p == 0.0) {
        return q >= 0.0;
    }
    double t = q / p;
    if (p < 0.0) {
        if (t > *t1) {
            return false;
        }
        if (t > *t0) {
            *t0 = t;
        }
    } else {
        if (t < *t0) {
            return false;
        }
        if (t < *t1) {
            *t1 = t;
        }
    }
    return true;
}

static bool liang_barsky(sr_point2 rmin, sr_point2 rmax, sr_point2 *a, sr_point2 *b)
{
    double dx = b->x - a->x, dy = b->y - a->y;
    double t0 = 0.0, t1 = 1.0;
    if (!lb_edge(-dx, a->x - rmin.x, &t0, &t1) || !lb_edge(dx, rmax.x - a->x, &t0, &t1) ||
        !lb_edge(-dy, a->y - rmin.y, &t0, &t1) || !lb_edge(dy, rmax.y - a->y, &t0, &t1)) {
        return false;
    }
    sr_point2 p = *a;
    /* Untouched ends keep their exact coordinates. */
    if (t1 < 1.0) {
        b->x = p.x + t1 * dx;
        b->y = p.y + t1 * dy;
    }
    if (t0 > 0.0) {
        a->x = p.x + t0 * dx;
        a->y = p.y + t0 * dy;
    }
    return true;
}

/* ---- both, for any finite input -------------------------------------------- */

typedef bool (*clip_fn)(sr_point2 rmin, sr_point2 rmax, sr_point2 *a, sr_point2 *b);

/* The clippers subtract coordinates (b - a, rmax - a), which overflows to
 * infinity, and then NaN, once they pass DBL_MAX / 2.  Past DBL_MAX / 4
 * everything is scaled by 1/4 (exact, a power of two) and back, and an end
 * that still comes out non-finite fails the clip with the points left. */
static bool clip_finite(clip_fn clip, sr_point2 rmin, sr_point2 rmax, sr_point2 *a, sr_point2 *b)
{
    if (!a || !b || !finite_input(rmin, rmax, a, b)) {
        return false;
    }
    double big = fmax(fmax(fmax(fabs(rmin.x), fabs(rmin.y)), fmax(fabs(rmax.x), fabs(rmax.y))),
                      fmax(fmax(fabs(a->x), fabs(a->y)), fmax(fabs(b->x), fabs(b->y))));
    double k = big > DBL_MAX / 4 ? 0.25 : 1.0;
    sr_point2 p = { a->x * k, a->y * k }, q = { b->x * k, b->y * k };
    if (!clip((sr_point2){ rmin.x * k, rmin.y * k }, (sr_point2){ rmax.x * k, rmax.y * k }, &p,
              &q)) {
        return false;
    }
    p = (sr_point2){ p.x / k, p.y / k };
    q = (sr_point2){ q.x / k, q.y / k };
    if (!isfinite(p.x) || !isfinite(p.y) || !isfinite(q.x) || !isfinite(q.y)) {
        return false;
    }
    *a = p;
    *b = q;
    return true;
}

bool sr_clip_line_cohen_sutherland(sr_point2 rmin, sr_point2 rmax, sr_point2 *a, sr_point2 *b)
{
    return clip_finite(cohen_sutherland, rmin, rmax, a, b);
}

bool sr_clip_line_liang_barsky(sr_point2 rmin, sr_point2 rmax, sr_point2 *a, sr_point2 *b)
{
    return clip_finite(liang_barsky, rmin, rmax, a, b);
}

bool sr__clip_line(sr_line_clipper clipper, double xmin, double ymin, double xmax, double ymax,
                   sr_point2 *a, sr_point2 *b)
{
    sr_point2 rmin = { xmin, ymin }, rmax = { xmax, ymax };
    if (clipper == SR__LINE_CLIP_NONE) {
        return isfinite(a->x) && isfinite(a->y) && isfinite(b->x) && isfinite(b->y);
    }
    if (clipper == SR_LINE_CLIP_COHEN_SUTHERLAND) {
        return sr_clip_line_cohen_sutherland(rmin, rmax, a, b);
    }
    return sr_clip_line_liang_barsky(rmin, rmax, a, b);
}
