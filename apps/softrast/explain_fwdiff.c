/* explain_fwdiff.c - `softrast explain forward-differencing`: a cubic
 * Bezier flattened by forward differences, as sr_flatten_cubic does it.
 * B(t) = a t^3 + b t^2 + c t + P0 is a polynomial; with step h = 1/n its
 * first difference B(t + h) - B(t) is a quadratic, the second a line and
 * the third the constant 6 a h^3, so each new point costs three additions
 * and no multiplication: P += d1, d1 += d2, d2 += d3.  n is the least that
 * keeps the chords within the tolerance of the curve, by the bound
 * |B''|max h^2 / 8.  The chords are then drawn as lines (sr_draw_line). */
#include "explain.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_STEPS 64   /* one frame each */

static const sr_rgba CONTROL = { 0.60f, 0.62f, 0.66f, 1 };

/* The curve at t, for the fine outline drawn beside the chords. */
static sr_point2 bezier(const sr_point2 *p, double t)
{
    double s = 1 - t;
    double a = s * s * s, b = 3 * s * s * t, c = 3 * s * t * t, d = t * t * t;
    return (sr_point2){ a * p[0].x + b * p[1].x + c * p[2].x + d * p[3].x,
                        a * p[0].y + b * p[1].y + c * p[2].y + d * p[3].y };
}

static void backdrop(ex_canvas *c, const sr_point2 *p)
{
    ex_outline(c, p, 4, false, CONTROL, 1);
    sr_point2 fine[65];
    for (int i = 0; i <= 64; i++) {
        fine[i] = bezier(p, i / 64.0);
    }
    ex_outline(c, fine, 65, false, EX_HILITE, 1);
    for (int i = 0; i < 4; i++) {
        char name[8];
        snprintf(name, sizeof name, "P%d", i);
        ex_dot(c, p[i], 3, CONTROL);
        ex_label(c, p[i], name, CONTROL);
    }
}

sr_result explain_fwdiff(ex_canvas *c, const ex_primitive *prim)
{
    const sr_point2 *p = prim->pts;
    double tol = prim->z[0];
    double ax = -p[0].x + 3 * p[1].x - 3 * p[2].x + p[3].x;
    double ay = -p[0].y + 3 * p[1].y - 3 * p[2].y + p[3].y;
    double bx = 3 * p[0].x - 6 * p[1].x + 3 * p[2].x, by = 3 * p[0].y - 6 * p[1].y + 3 * p[2].y;
    double cx = 3 * (p[1].x - p[0].x), cy = 3 * (p[1].y - p[0].y);
    /* B'' = 6 a t + 2 b is linear in t: |B''| peaks at an end */
    double m0 = 6 * hypot(p[0].x - 2 * p[1].x + p[2].x, p[0].y - 2 * p[1].y + p[2].y);
    double m1 = 6 * hypot(p[1].x - 2 * p[2].x + p[3].x, p[1].y - 2 * p[2].y + p[3].y);
    double m = m0 > m1 ? m0 : m1;
    double nd = ceil(sqrt(m / (8.0 * tol)));
    int n = nd >= 1 ? (int)fmin(nd, MAX_STEPS + 1) : 1;
    if (n > MAX_STEPS) {
        return SR_TOO_LARGE;
    }
    double h = 1.0 / n, h2 = h * h, h3 = h2 * h;
    double x = p[0].x, y = p[0].y;
    double dx = ax * h3 + bx * h2 + cx * h, dy = ay * h3 + by * h2 + cy * h;
    double ddx = 6 * ax * h3 + 2 * bx * h2, ddy = 6 * ay * h3 + 2 * by * h2;
    double dddx = 6 * ax * h3, dddy = 6 * ay * h3;
    sr_point2 pts[MAX_STEPS + 1] = { p[0] };
    char cap[800];

    ex_begin(c);
    backdrop(c, p);
    char steps[200];
    if (m > 0) {
        snprintf(steps, sizeof steps,
                 "|B''| peaks at an end: %.2f; chords within %g px need n = ceil(sqrt(%.2f / (8 "
                 "x %g))) = %d step%s of h = 1/%d.", m, tol, m, tol, n, n == 1 ? "" : "s", n);
    } else {
        /* the bound gives 0 steps; one chord is the whole (straight) curve */
        snprintf(steps, sizeof steps,
                 "|B''| = 0: a straight segment, traced at an even pace, so one chord is exact: "
                 "n = 1 step of h = 1/1.");
    }
    snprintf(cap, sizeof cap,
             "1. A cubic Bezier (pink; grey: its control polygon) as a polynomial B(t) = a t^3 + "
             "b t^2 + c t + P0: a = (%.2f, %.2f), b = (%.2f, %.2f), c = (%.2f, %.2f). %s Start: "
             "d1 = a h^3 + b h^2 + c h = (%.3f, %.3f), d2 = 6 a h^3 + 2 b h^2 = (%.3f, %.3f), "
             "d3 = 6 a h^3 = (%.4f, %.4f).",
             ax, ay, bx, by, cx, cy, steps, dx, dy, ddx, ddy, dddx, dddy);
    ex_end(c, cap);

    for (int i = 1; i <= n; i++) {
        double px = x + dx, py = y + dy;
        bool last = i == n;
        /* the last point is P3 itself, not the sum */
        pts[i] = last ? p[3] : (sr_point2){ px, py };
        ex_begin(c);
        backdrop(c, p);
        ex_outline(c, pts, i + 1, false, EX_INK, 2);
        for (int k = 0; k <= i; k++) {
            ex_dot(c, pts[k], k == i ? 5 : 3, EX_INK);
        }
        if (last) {
            snprintf(cap, sizeof cap,
                     "%d. Step %d, the last: the sum gives (%.4f, %.4f), P3 is (%g, %g); the "
                     "point is taken as P3 itself, so rounding in the sums cannot move the end.",
                     c->frame_count + 1, i, px, py, p[3].x, p[3].y);
        } else {
            snprintf(cap, sizeof cap,
                     "%d. Step %d, t = %d/%d: P += d1 gives (%.3f, %.3f); then d1 += d2 = "
                     "(%.3f, %.3f), d2 += d3 = (%.3f, %.3f). Three additions per point, no "
                     "multiplication.",
                     c->frame_count + 1, i, i, n, px, py, dx + ddx, dy + ddy, ddx + dddx,
                     ddy + dddy);
        }
        ex_end(c, cap);
        x = px;
        y = py;
        dx += ddx;
        dy += ddy;
        ddx += dddx;
        ddy += dddy;
    }

    uint8_t *mask = malloc((size_t)c->grid_w * (size_t)c->grid_h);
    if (!mask) {
        return SR_OUT_OF_MEMORY;
    }
    sr_result r = ex_polyline_pixels(c, pts, n + 1, false, mask);
    ex_begin(c);
    for (int yy = 0; yy < c->grid_h; yy++) {
        for (int xx = 0; xx < c->grid_w; xx++) {
            if (mask[yy * c->grid_w + xx]) {
                ex_cell(c, xx, yy, EX_INK);
            }
        }
    }
    ex_outline(c, pts, n + 1, false, EX_EDGE, 1);
    snprintf(cap, sizeof cap,
             "%d. The %d chord%s drawn as lines (sr_draw_line, each leaving out its end pixel so "
             "they join without doubling): what sr_flatten_cubic's points give at 1x.",
             c->frame_count + 1, n, n == 1 ? "" : "s");
    ex_end(c, cap);
    free(mask);
    return r != SR_OK ? r : c->error;
}
