/* line_aa.c - draw2d stage: antialiased 2D lines.  Consumes a segment in
 * pixel coordinates (doubles), produces pixels with a coverage weight
 * through a plot callback: Xiaolin Wu's two pixels per major step, and
 * the exact area of the line's rectangle (with its caps) inside each
 * pixel square ("unweighted area sampling").  sr_draw_line blends the
 * weights in linear light.  Runs on the caller's thread. */
#include "draw2d/line.h"

#include <math.h>
#include <stdint.h>

#define PI 3.14159265358979323846

/* ---- Xiaolin Wu ---------------------------------------------------------------- */

typedef struct wu_ctx {
    bool steep;
    double gradient;
    sr__irect clip;
    sr_line_step_fn step;
    void *user;
} wu_ctx;

/* Column k's step: the two pixels straddling v, weighted by their
 * distance (the nearer one gets more) times the column's weight.  v has
 * pixel centres at integers here.  A pixel is drawn when its weight is
 * above 0 and it lies inside the clip rectangle. */
static void wu_pair(const wu_ctx *w, double k, double v, double weight, bool first, bool last)
{
    double j = floor(v), f = v - j;
    sr_line_step_info s = { .y_major = w->steep, .first_end = first, .last_end = last,
                            .major = (int)k, .gradient = w->gradient, .intersection = v + 0.5,
                            .weight = weight };
    const double c[2] = { (1.0 - f) * weight, f * weight };
    for (int i = 0; i < 2; i++) {
        double x = w->steep ? j + i : k, y = w->steep ? k : j + i;
        s.x[i] = (int)x;
        s.y[i] = (int)y;
        s.coverage[i] = (float)(c[i] > 1.0 ? 1.0 : c[i] < 0.0 ? 0.0 : c[i]);
        s.drawn[i] = c[i] > 0.0 && x >= w->clip.x0 && x < w->clip.x1 && y >= w->clip.y0 &&
                     y < w->clip.y1;
    }
    w->step(w->user, &s);
}

void sr__line_wu_steps(sr_point2 a, sr_point2 b, sr__irect clip, sr_line_clipper clipper,
                       sr_line_step_fn step, void *user)
{
    if ((a.x == b.x && a.y == b.y) || clip.x1 <= clip.x0 || clip.y1 <= clip.y0) {
        return;
    }
    sr_point2 ca = a, cb = b;
    if (!sr__clip_line(clipper, clip.x0 - 2.0, clip.y0 - 2.0, clip.x1 + 2.0, clip.y1 + 2.0,
                       &ca, &cb)) {
        return;
    }
    /* Wu's formulation puts pixel centres at integers: shift by -1/2. */
    double x0 = a.x - 0.5, y0 = a.y - 0.5, x1 = b.x - 0.5, y1 = b.y - 0.5;
    wu_ctx w = { fabs(y1 - y0) > fabs(x1 - x0), 0.0, clip, step, user };
    double lo = w.steep ? fmin(ca.y, cb.y) : fmin(ca.x, cb.x);
    double hi = w.steep ? fmax(ca.y, cb.y) : fmax(ca.x, cb.x);
    if (w.steep) {
        double t = x0; x0 = y0; y0 = t;
        t = x1; x1 = y1; y1 = t;
    }
    if (x0 > x1) {
        double t = x0; x0 = x1; x1 = t;
        t = y0; y0 = y1; y1 = t;
    }
    const double g = (y1 - y0) / (x1 - x0);      /* gradient, |g| <= 1 */
    w.gradient = g;
    /* First end: its column gets the weight of the part of the column
     * the line covers (gap); the second end likewise. */
    const double xa = floor(x0 + 0.5), ya = y0 + g * (xa - x0);
    const double xb = floor(x1 + 0.5), yb = y1 + g * (xb - x1);
    const double gap_a = 1.0 - (x0 + 0.5 - xa), gap_b = x1 + 0.5 - xb;
    if (xa == xb) {
        wu_pair(&w, xa, ya + g * (0.5 * (x0 + x1) - xa), x1 - x0, true, true);
        return;
    }
    /* The steps in order of the major index; each column has its own
     * pixels, so the order does not change what is drawn. */
    wu_pair(&w, xa, ya, gap_a, true, false);
    /* Interior columns, only the visible ones.  v is computed from the
     * first end at each column (not accumulated), so the pixels do not
     * depend on where the visible part starts. */
    double k0 = fmax(xa + 1.0, floor(lo) - 3.0), k1 = fmin(xb - 1.0, floor(hi) + 3.0);
    for (double k = k0; k <= k1; k += 1.0) {
        wu_pair(&w, k, ya + g * (k - xa), 1.0, false, false);
    }
    wu_pair(&w, xb, yb, gap_b, false, true);
}

typedef struct wu_plot_ctx {
    sr__plot_fn plot;
    void *user;
} wu_plot_ctx;

static void wu_plot_step(void *user, const sr_line_step_info *s)
{
    const wu_plot_ctx *p = user;
    for (int i = 0; i < 2; i++) {
        if (s->drawn[i]) {
            p->plot(p->user, s->x[i], s->y[i], s->coverage[i]);
        }
    }
}

void sr__line_wu(sr_point2 a, sr_point2 b, sr__irect clip, sr_line_clipper clipper,
                 sr__plot_fn plot, void *user)
{
    wu_plot_ctx p = { plot, user };
    sr__line_wu_steps(a, b, clip, clipper, wu_plot_step, &p);
}

/* ---- exact area coverage ------------------------------------------------------- */

/* Round caps are polygons whose chords stay within 1/1024 px of the
 * circle (at most ARC_MAX segments per half circle). */
#define ARC_MAX 512
#define POLY_MAX (2 * (ARC_MAX + 1) + 8)
_Static_assert(POLY_MAX <= SR__LINE_AREA_STRIP_MAX, "a strip fits the cells' buffer");

typedef struct poly { int n; double x[POLY_MAX], y[POLY_MAX]; } poly;
_Static_assert(sizeof(poly) < 20000, "polygons live on the stack");

static void poly_add(poly *p, double x, double y)
{
    if (p->n < POLY_MAX) {
        p->x[p->n] = x;
        p->y[p->n] = y;
        p->n++;
    }
}

/* Sutherland-Hodgman against one axis-aligned half-plane:
 * keep coord >= bound (keep_greater) or coord <= bound. */
static void clip_half(const poly *in, poly *out, bool y_axis, double bound, bool keep_greater)
{
    out->n = 0;
    for (int i = 0; i < in->n; i++) {
        int k = i + 1 == in->n ? 0 : i + 1;
        double ci = y_axis ? in->y[i] : in->x[i], ck = y_axis ? in->y[k] : in->x[k];
        bool ini = keep_greater ? ci >= bound : ci <= bound;
        bool ink = keep_greater ? ck >= bound : ck <= bound;
        if (ini) {
            poly_add(out, in->x[i], in->y[i]);
        }
        if (ini != ink) {
            double t = (bound - ci) / (ck - ci);
            double x = in->x[i] + t * (in->x[k] - in->x[i]);
            double y = in->y[i] + t * (in->y[k] - in->y[i]);
            /* The crossing lies exactly on the bound. */
            if (y_axis) {
                y = bound;
            } else {
                x = bound;
            }
            poly_add(out, x, y);
        }
    }
}

/* |area| by the shoelace formula, relative to (ox, oy) for precision. */
static double poly_area(const poly *p, double ox, double oy)
{
    double s = 0.0;
    for (int i = 0; i < p->n; i++) {
        int k = i + 1 == p->n ? 0 : i + 1;
        s += (p->x[i] - ox) * (p->y[k] - oy) - (p->x[k] - ox) * (p->y[i] - oy);
    }
    return fabs(s) * 0.5;
}

/* The area of the part of `strip` left of x = bound (tmp: scratch). */
static double area_left_of(const poly *strip, double bound, double oy, poly *tmp)
{
    clip_half(strip, tmp, false, bound, false);
    return tmp->n < 3 ? 0.0 : poly_area(tmp, bound, oy);
}

/* How fill_convex_area hands out its pixels: each with its areas and its
 * row's strip (cell, strip: SR__LINE_AREA_STRIP_MAX points), or only the
 * drawn ones' coverage (plot, when cell is NULL): sr_draw_line's. */
typedef struct area_out {
    sr_line_area_fn cell;
    sr__plot_fn plot;
    void *user;
    sr_point2 *strip;
} area_out;

/* Every pixel of the clip rectangle the convex polygon's bounding box
 * touches, row by row, with the exact area of polygon ∩ pixel square:
 * cut the polygon into the row's strip; a pixel's area is then
 * A(x + 1) - A(x), where A(x) is the area of the strip left of x (one cut
 * per pixel instead of two). */
static void fill_convex_area(const poly *p, sr__irect clip, const area_out *out)
{
    if (p->n < 3) {
        return;
    }
    double ymin = p->y[0], ymax = p->y[0];
    for (int i = 1; i < p->n; i++) {
        ymin = fmin(ymin, p->y[i]);
        ymax = fmax(ymax, p->y[i]);
    }
    double r0 = fmax(floor(ymin), clip.y0), r1 = fmin(ceil(ymax) - 1.0, clip.y1 - 1.0);
    poly tmp, strip;
    for (double y = r0; y <= r1; y += 1.0) {
        clip_half(p, &tmp, true, y, true);
        clip_half(&tmp, &strip, true, y + 1.0, false);
        if (strip.n < 3) {
            continue;
        }
        double xmin = strip.x[0], xmax = strip.x[0];
        for (int i = 1; i < strip.n; i++) {
            xmin = fmin(xmin, strip.x[i]);
            xmax = fmax(xmax, strip.x[i]);
        }
        if (out->cell) {
            for (int i = 0; i < strip.n; i++) {
                out->strip[i] = (sr_point2){ strip.x[i], strip.y[i] };
            }
        }
        double c0 = fmax(floor(xmin), clip.x0), c1 = fmin(ceil(xmax) - 1.0, clip.x1 - 1.0);
        double left = c0 > xmin ? area_left_of(&strip, c0, y, &tmp) : 0.0;
        for (double x = c0; x <= c1; x += 1.0) {
            double next = area_left_of(&strip, x + 1.0, y, &tmp);
            double area = next - left;
            /* Below 1e-9 px^2 is rounding noise of the subtraction. */
            bool drawn = area > 1e-9;
            float coverage = drawn ? (float)(area > 1.0 ? 1.0 : area) : 0.0f;
            if (out->cell) {
                out->cell(out->user, &(sr_line_area_info){ .x = (int)x, .y = (int)y,
                                                           .left = left, .right = next,
                                                           .area = area, .coverage = coverage,
                                                           .drawn = drawn, .strip = out->strip,
                                                           .strip_count = strip.n });
            } else if (drawn) {
                out->plot(out->user, (int)x, (int)y, coverage);
            }
            left = next;
        }
    }
}

static int arc_segments(double r)
{
    const double tol = 1.0 / 1024.0;
    if (r <= tol) {
        return 2;
    }
    double n = ceil(PI / (2.0 * acos(1.0 - tol / r)));
    return n < 2.0 ? 2 : n > ARC_MAX ? ARC_MAX : (int)n;
}

/* Half circle of radius r around c from direction (nx, ny) to (-nx, -ny),
 * bulging towards (dx, dy); the end points are not added. */
static void add_arc(poly *p, double cx, double cy, double r, double nx, double ny,
                    double dx, double dy)
{
    int n = arc_segments(r);
    for (int i = 1; i < n; i++) {
        double t = PI * i / n, c = cos(t), s = sin(t);
        poly_add(p, cx + r * (c * nx + s * dx), cy + r * (c * ny + s * dy));
    }
}

static void line_area(sr_point2 a, sr_point2 b, double width, sr_line_cap cap, sr__irect clip,
                      sr_line_clipper clipper, const area_out *out)
{
    if (clip.x1 <= clip.x0 || clip.y1 <= clip.y0 || !(width > 0.0)) {
        return;
    }
    const double h = 0.5 * width;
    double dx = b.x - a.x, dy = b.y - a.y, len = hypot(dx, dy);
    poly p = { 0 };
    if (len == 0.0) {
        if (cap == SR_LINE_CAP_SQUARE) {           /* no direction: axis-aligned */
            poly_add(&p, a.x - h, a.y - h);
            poly_add(&p, a.x + h, a.y - h);
            poly_add(&p, a.x + h, a.y + h);
            poly_add(&p, a.x - h, a.y + h);
        } else if (cap == SR_LINE_CAP_ROUND) {
            poly_add(&p, a.x + h, a.y);
            add_arc(&p, a.x, a.y, h, 1.0, 0.0, 0.0, 1.0);
            poly_add(&p, a.x - h, a.y);
            add_arc(&p, a.x, a.y, h, -1.0, 0.0, 0.0, -1.0);
        }
        fill_convex_area(&p, clip, out);
        return;
    }
    dx /= len;
    dy /= len;
    const double nx = -dy, ny = dx;                /* unit normal */
    /* Clip first: the rectangle reaches at most h + w/2 past the segment,
     * so the segment clipped to the clip rectangle grown by width + 2
     * loses nothing visible.  An end moved by the clipper is far
     * outside, so its cap does not matter: it becomes butt. */
    sr_point2 ca = a, cb = b;
    double m = width + 2.0;
    if (!sr__clip_line(clipper, clip.x0 - m, clip.y0 - m, clip.x1 + m, clip.y1 + m, &ca, &cb)) {
        return;
    }
    sr_line_cap cap_a = (ca.x == a.x && ca.y == a.y) ? cap : SR_LINE_CAP_BUTT;
    sr_line_cap cap_b = (cb.x == b.x && cb.y == b.y) ? cap : SR_LINE_CAP_BUTT;
    if (cap_a == SR_LINE_CAP_SQUARE) {
        ca.x -= h * dx;
        ca.y -= h * dy;
    }
    if (cap_b == SR_LINE_CAP_SQUARE) {
        cb.x += h * dx;
        cb.y += h * dy;
    }
    poly_add(&p, ca.x + h * nx, ca.y + h * ny);
    poly_add(&p, cb.x + h * nx, cb.y + h * ny);
    if (cap_b == SR_LINE_CAP_ROUND) {
        add_arc(&p, cb.x, cb.y, h, nx, ny, dx, dy);
    }
    poly_add(&p, cb.x - h * nx, cb.y - h * ny);
    poly_add(&p, ca.x - h * nx, ca.y - h * ny);
    if (cap_a == SR_LINE_CAP_ROUND) {
        add_arc(&p, ca.x, ca.y, h, -nx, -ny, -dx, -dy);
    }
    fill_convex_area(&p, clip, out);
}

void sr__line_area_cells(sr_point2 a, sr_point2 b, double width, sr_line_cap cap,
                         sr__irect clip, sr_line_clipper clipper, sr_line_area_fn cell,
                         void *user, sr_point2 *strip)
{
    line_area(a, b, width, cap, clip, clipper,
              &(area_out){ .cell = cell, .user = user, .strip = strip });
}

void sr__line_area(sr_point2 a, sr_point2 b, double width, sr_line_cap cap, sr__irect clip,
                   sr_line_clipper clipper, sr__plot_fn plot, void *user)
{
    line_area(a, b, width, cap, clip, clipper, &(area_out){ .plot = plot, .user = user });
}
