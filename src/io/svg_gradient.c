/* svg_gradient.c - the SVG reader's paint servers (src/io): linear and
 * radial gradients evaluated a row at a time (spread pad, reflect,
 * repeat; a radial gradient's focal circle as the two-circle cone of SVG
 * 2), their colors from a table filled as the pixels ask for it.  Used
 * by svg_fill.c on the thread that renders the document. */
#include "io/svg.h"

#include <math.h>
#include <string.h>

/* A radial gradient's parameter t at a point (pdx, pdy) from the focal
 * centre in gradient space; false where the cone does not reach (the
 * pixel is left unpainted).  Circles (f + t (c - f), fr + t (r - fr)):
 * the largest t with a circle through the point and a radius >= 0. */
static bool radial_parameter(const svg_gradient *g, double a, double pdx, double pdy, double *t)
{
    double cdx = g->cx - g->fx, cdy = g->cy - g->fy, dr = g->r - g->fr;
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

/* t mapped into [0, 1] by the spread method. */
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

/* The first stop with an offset above t (n_stops if none): t lies
 * between it and the one before. */
static int stop_above(const svg_gradient *g, double t)
{
    int i = 0;
    while (i < g->n_stops && !(t < g->offset[i])) {
        i++;
    }
    return i;
}

/* The color of t on the piece that ends at stop i (stop_above): flat
 * before the first stop and after the last, else mixed linearly. */
static sr_rgba piece_color(const svg_gradient *g, int i, double t)
{
    if (i == 0 || t <= g->offset[0]) {
        return g->color[0];
    }
    if (i == g->n_stops) {
        return g->color[g->n_stops - 1];
    }
    double span = g->offset[i] - g->offset[i - 1];
    float u = span > 0 ? (float)((t - g->offset[i - 1]) / span) : 1.0f;
    sr_rgba a = g->color[i - 1], b = g->color[i];
    return (sr_rgba){ a.r + (b.r - a.r) * u, a.g + (b.g - a.g) * u, a.b + (b.b - a.b) * u,
                      a.a + (b.a - a.a) * u };
}

static uint8_t unorm8(float v)
{
    return !(v > 0.0f) ? 0 : v >= 1.0f ? 255 : (uint8_t)(v * 255.0f + 0.5f);
}

static uint32_t pack(sr_rgba c)
{
    uint8_t b[4] = { unorm8(c.r), unorm8(c.g), unorm8(c.b), unorm8(c.a) };
    uint32_t v;
    memcpy(&v, b, sizeof v);
    return v;
}

/* The exact color of a spread t, quantized. */
static uint32_t exact_color(const svg_gradient *g, double t)
{
    return pack(piece_color(g, stop_above(g, t), t));
}

/* How far, in codes, a channel of the cell's color c strays from the
 * cell's ends a and b (the color is linear between them). */
static float stray(sr_rgba c, sr_rgba a, sr_rgba b)
{
    float d[8] = { c.r - a.r, c.g - a.g, c.b - a.b, c.a - a.a,
                   c.r - b.r, c.g - b.g, c.b - b.b, c.a - b.a };
    float m = 0;
    for (int k = 0; k < 8; k++) {
        m = fmaxf(m, fabsf(d[k]));
    }
    return m * 255.0f;
}

/* Fill cell k of the table: the color of its centre when every color of
 * the cell is within half a code of it, else mark it for pixels alone. */
static void fill_cell(svg_gradient *g, int k)
{
    if (k == SVG_GRADIENT_LUT) {
        g->lut[k] = exact_color(g, 1.0);
        g->lut_state[k] = 1;
        return;
    }
    double t0 = (double)k / SVG_GRADIENT_LUT, t1 = (double)(k + 1) / SVG_GRADIENT_LUT;
    double tm = (k + 0.5) / SVG_GRADIENT_LUT;
    int i = stop_above(g, t0);
    /* A stop inside the cell bends or breaks the color there. */
    if (i < g->n_stops && g->offset[i] < t1) {
        g->lut_state[k] = 2;
        return;
    }
    sr_rgba c = piece_color(g, i, tm);
    bool flat = stray(c, piece_color(g, i, t0), piece_color(g, i, t1)) <= 0.5f;
    g->lut[k] = pack(c);
    g->lut_state[k] = flat ? 1 : 2;
}

/* The color of an unspread t (transparent where it is not finite). */
static uint32_t color_of(svg_gradient *g, double t)
{
    if (!isfinite(t)) {
        return 0;
    }
    t = spread(g->spread, t);
    int k = t >= 1 ? SVG_GRADIENT_LUT : (int)(t * SVG_GRADIENT_LUT);
    if (g->lut_state[k] == 0) {
        fill_cell(g, k);
    }
    return g->lut_state[k] == 1 ? g->lut[k] : exact_color(g, t);
}

bool svg_gradient_span(void *paint, int x, int y, int n, uint32_t *out)
{
    svg_gradient *g = paint;
    const double *m = g->inv;
    /* Gradient space is affine in the pixel: from the first centre each
     * pixel steps by (m[0], m[1]), computed from the start, not summed. */
    double px = x + 0.5, py = y + 0.5;
    double gx0 = m[0] * px + m[2] * py + m[4], gy0 = m[1] * px + m[3] * py + m[5];
    if (!g->radial) {
        double dx = g->x2 - g->x1, dy = g->y2 - g->y1, len2 = dx * dx + dy * dy;
        double t0 = len2 > 0 ? ((gx0 - g->x1) * dx + (gy0 - g->y1) * dy) / len2 : 0;
        double dt = len2 > 0 ? (m[0] * dx + m[1] * dy) / len2 : 0;
        for (int i = 0; i < n; i++) {
            out[i] = color_of(g, t0 + dt * i);
        }
        /* t0 takes nothing from y when each product with py is a zero
         * (gx0 free of y, or gx weighed by 0; the same for gy). */
        return (m[2] == 0 || dx == 0) && (m[3] == 0 || dy == 0);
    }
    double cdx = g->cx - g->fx, cdy = g->cy - g->fy, dr = g->r - g->fr;
    double a = cdx * cdx + cdy * cdy - dr * dr;
    for (int i = 0; i < n; i++) {
        double t;
        bool on = radial_parameter(g, a, gx0 + m[0] * i - g->fx, gy0 + m[1] * i - g->fy, &t);
        out[i] = on ? color_of(g, t) : 0;
    }
    return false;
}
