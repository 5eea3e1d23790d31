/* svg_gradient.c - the SVG reader's paint servers (src/io): linear and
 * radial gradients evaluated per pixel (spread pad, reflect, repeat; a
 * radial gradient's focal circle as the two-circle cone of SVG 2).  Pure
 * functions of their arguments; used by svg.c. */
#include "io/svg.h"

#include <math.h>

/* The gradient parameter t of a point in gradient space; false where a
 * radial gradient's cone does not reach (the pixel is left unpainted). */
static bool parameter(const svg_gradient *g, double x, double y, double *t)
{
    if (!g->radial) {
        double dx = g->x2 - g->x1, dy = g->y2 - g->y1, len2 = dx * dx + dy * dy;
        *t = len2 > 0 ? ((x - g->x1) * dx + (y - g->y1) * dy) / len2 : 0;
        return true;
    }
    /* Circles (f + t (c - f), fr + t (r - fr)); the largest t with a
     * circle through the point and a radius >= 0. */
    double cdx = g->cx - g->fx, cdy = g->cy - g->fy, dr = g->r - g->fr;
    double pdx = x - g->fx, pdy = y - g->fy;
    double a = cdx * cdx + cdy * cdy - dr * dr;
    double b = pdx * cdx + pdy * cdy + g->fr * dr;
    double c = pdx * pdx + pdy * pdy - g->fr * g->fr;
    if (fabs(a) < 1e-12) {
        if (fabs(b) < 1e-12) {
            return false;
        }
        *t = c / (2 * b);
        return g->fr + *t * dr >= 0;
    }
    double disc = b * b - a * c;
    if (disc < 0) {
        return false;
    }
    double sq = sqrt(disc), t0 = (b + sq) / a, t1 = (b - sq) / a;
    if (t0 < t1) {
        double s = t0;
        t0 = t1;
        t1 = s;
    }
    if (g->fr + t0 * dr >= 0) {
        *t = t0;
        return true;
    }
    if (g->fr + t1 * dr >= 0) {
        *t = t1;
        return true;
    }
    return false;
}

static double spread(svg_spread s, double t)
{
    switch (s) {
    case SVG_SPREAD_REPEAT:
        return t - floor(t);
    case SVG_SPREAD_REFLECT: {
        double u = fmod(fabs(t), 2);
        return u > 1 ? 2 - u : u;
    }
    default:
        return t < 0 ? 0 : t > 1 ? 1 : t;
    }
}

static sr_rgba color_at(const svg_gradient *g, double t)
{
    if (t <= g->offset[0]) {
        return g->color[0];
    }
    for (int i = 1; i < g->n_stops; i++) {
        if (t < g->offset[i]) {
            double span = g->offset[i] - g->offset[i - 1];
            float u = span > 0 ? (float)((t - g->offset[i - 1]) / span) : 1.0f;
            sr_rgba a = g->color[i - 1], b = g->color[i];
            return (sr_rgba){ a.r + (b.r - a.r) * u, a.g + (b.g - a.g) * u, a.b + (b.b - a.b) * u,
                              a.a + (b.a - a.a) * u };
        }
    }
    return g->color[g->n_stops - 1];
}

sr_rgba svg_gradient_at(const svg_gradient *g, double x, double y)
{
    const double *m = g->inv;
    double gx = m[0] * x + m[2] * y + m[4], gy = m[1] * x + m[3] * y + m[5], t;
    if (!parameter(g, gx, gy, &t) || !isfinite(t)) {
        return (sr_rgba){ 0, 0, 0, 0 };
    }
    return color_at(g, spread(g->spread, t));
}

sr_rgba svg_gradient_paint(const void *g, double x, double y)
{
    return svg_gradient_at(g, x, y);
}
