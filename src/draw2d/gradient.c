/* gradient.c - draw2d stage: the gradient paints, linear and radial,
 * evaluated a row at a time (spread pad, reflect, repeat; a radial
 * gradient's focal circle as the two-circle cone of SVG 2), their colors
 * from a table filled as the pixels ask for it.  Used by paint_fill.c on
 * the caller's thread. */
#include "draw2d/paint_fill.h"

#include <math.h>
#include <string.h>

/* Pixels of a radial gradient's span worked out together, so that the
 * loop that finds their t runs in vector lanes. */
#define RADIAL_BATCH 64

/* t of n pixels of a radial gradient from (pdx, pdy), the first centre
 * less the focal point, stepping (sx, sy): NAN where the cone does not
 * reach (the pixel is left unpainted).  Circles (f + t (c - f),
 * fr + t (r - fr)): the largest t with a circle through the point and a
 * radius >= 0, a root of a t^2 - 2 b t + c = 0. */
static void radial_parameters(const sr__gradient *g, double pdx, double pdy, double sx,
                              double sy, int n, double *t)
{
    double cdx = g->cx - g->fx, cdy = g->cy - g->fy, dr = g->r - g->fr;
    double a = cdx * cdx + cdy * cdy - dr * dr, frdr = g->fr * dr, fr2 = g->fr * g->fr;
    if (fabs(a) < 1e-12) {
        /* The focal circle touches the end circle: one root. */
        for (int i = 0; i < n; i++) {
            double x = pdx + sx * i, y = pdy + sy * i;
            double b = x * cdx + y * cdy + frdr, c = x * x + y * y - fr2, u = c / (2 * b);
            t[i] = fabs(b) >= 1e-12 && g->fr + u * dr >= 0 ? u : NAN;
        }
        return;
    }
    double ia = 1 / a;
    for (int i = 0; i < n; i++) {
        double x = pdx + sx * i, y = pdy + sy * i;
        double b = x * cdx + y * cdy + frdr, c = x * x + y * y - fr2;
        double disc = b * b - a * c, sq = sqrt(disc > 0 ? disc : 0);
        double r0 = (b + sq) * ia, r1 = (b - sq) * ia;
        double hi = r0 > r1 ? r0 : r1, lo = r0 > r1 ? r1 : r0;
        double u = g->fr + hi * dr >= 0 ? hi : g->fr + lo * dr >= 0 ? lo : NAN;
        t[i] = disc < 0 ? NAN : u;
    }
}

/* t mapped into [0, 1] by the spread method. */
static double spread(sr_gradient_spread s, double t)
{
    switch (s) {
    case SR_SPREAD_REPEAT:
        return t - floor(t);
    case SR_SPREAD_REFLECT: {
        double u = fmod(fabs(t), 2);
        return u > 1 ? 2 - u : u;
    }
    default:
        return t < 0 ? 0 : t > 1 ? 1 : t;
    }
}

/* The first stop with an offset above t (n_stops if none): t lies
 * between it and the one before. */
static int stop_above(const sr__gradient *g, double t)
{
    int i = 0;
    while (i < g->n_stops && !(t < g->offset[i])) {
        i++;
    }
    return i;
}

/* The color of t on the piece that ends at stop i (stop_above): flat
 * before the first stop and after the last, else mixed linearly. */
static sr_rgba piece_color(const sr__gradient *g, int i, double t)
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

static uint32_t pack(sr_rgba c)
{
    uint8_t b[4] = { sr__paint_unorm8(c.r), sr__paint_unorm8(c.g), sr__paint_unorm8(c.b), sr__paint_unorm8(c.a) };
    uint32_t v;
    memcpy(&v, b, sizeof v);
    return v;
}

/* The exact color of a spread t, quantized. */
static uint32_t exact_color(const sr__gradient *g, double t)
{
    return pack(piece_color(g, stop_above(g, t), t));
}

/* Whether the piece ending at stop i (stop_above) changes a channel by
 * less than 0.98 codes across a cell: then the color of the cell's centre
 * is within 0.49 codes of every color of the cell. */
static bool piece_is_flat(const sr__gradient *g, int i)
{
    if (i == 0 || i == g->n_stops) {
        return true;
    }
    sr_rgba a = g->color[i - 1], b = g->color[i];
    float d[4] = { b.r - a.r, b.g - a.g, b.b - a.b, b.a - a.a }, m = 0;
    for (int k = 0; k < 4; k++) {
        float v = d[k] < 0 ? -d[k] : d[k];
        m = v > m ? v : m;
    }
    double span = g->offset[i] - g->offset[i - 1];
    return m * 255.0 < 0.98 * span * SR__GRADIENT_LUT;
}

/* Fill cell k of the table: the color of its centre when every color of
 * the cell is within half a code of it, else mark it for pixels alone. */
static void fill_cell(sr__gradient *g, int k)
{
    if (k == SR__GRADIENT_LUT) {
        g->lut[k] = exact_color(g, 1.0);
        g->lut_state[k] = 1;
        return;
    }
    double t0 = (double)k / SR__GRADIENT_LUT, t1 = (double)(k + 1) / SR__GRADIENT_LUT;
    int i = stop_above(g, t0);
    /* A stop inside the cell bends or breaks the color there. */
    if ((i < g->n_stops && g->offset[i] < t1) || !piece_is_flat(g, i)) {
        g->lut_state[k] = 2;
        return;
    }
    g->lut[k] = pack(piece_color(g, i, (k + 0.5) / SR__GRADIENT_LUT));
    g->lut_state[k] = 1;
}

/* The color of an unspread t (transparent where it is not finite). */
static inline uint32_t color_of(sr__gradient *g, double t)
{
    if (!isfinite(t)) {
        return 0;
    }
    t = spread(g->spread, t);
    int k = t >= 1 ? SR__GRADIENT_LUT : (int)(t * SR__GRADIENT_LUT);
    if (g->lut_state[k] == 1) {
        return g->lut[k];
    }
    if (g->lut_state[k] == 0) {
        fill_cell(g, k);
    }
    return g->lut_state[k] == 1 ? g->lut[k] : exact_color(g, t);
}

bool sr__gradient_span(void *paint, int x, int y, int n, uint32_t *out)
{
    sr__gradient *g = paint;
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
    for (int i = 0; i < n; i += RADIAL_BATCH) {
        double t[RADIAL_BATCH];
        int k = n - i < RADIAL_BATCH ? n - i : RADIAL_BATCH;
        radial_parameters(g, gx0 + m[0] * i - g->fx, gy0 + m[1] * i - g->fy, m[0], m[1], k, t);
        for (int j = 0; j < k; j++) {
            out[i + j] = color_of(g, t[j]);
        }
    }
    return false;
}
