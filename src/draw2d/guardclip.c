/* guardclip.c - draw2d stage, setup: a polygon with points beyond the
 * converters' fixed-point budget (SR_MAX_COORD2D) is cut to a guard
 * rectangle, the window grown by GUARD_MARGIN pixels, before it is
 * snapped.  Consumes a validated sr_polygon2 of finite points, produces a
 * new one on ctx.  Runs on the caller's thread.
 *
 * Sutherland-Hodgman on each closed contour against a convex region keeps
 * the winding number of every point inside the region: what it drops is an
 * outside run of the contour closed by a chord along a clip line, a loop
 * that lies wholly outside and so winds around no inside point.  Each new
 * point is computed once and shared by the kept segment and the chord, so
 * the loop closes exactly in floating point too.  The chords lie on the
 * guard lines, GUARD_MARGIN pixels outside the window, where no converter
 * (aliased, area or supersampled) writes a pixel. */
#include "context.h"
#include "draw2d/polyfill.h"

/* A cut edge ends on a guard line at a point rounded to 1/256 px, which
 * turns it by about (distance / GUARD_MARGIN) / 512 px in the window: far
 * out, that is a hair no aliased sample has been seen to cross
 * (tests/test_draw2d_guard.c).  The guard stays within the budget, and so
 * does every window (sr_polygon_coverage refuses one reaching past it):
 * a guard line held at the budget's edge lies on or beyond the window's. */
#define GUARD_MARGIN 131072.0

static double clamp_budget(double v)
{
    return v < -SR_MAX_COORD2D ? -SR_MAX_COORD2D : v > SR_MAX_COORD2D ? SR_MAX_COORD2D : v;
}

sr_result sr__guard_clip(sr_context *ctx, const char *fn, const sr_polygon2 *poly,
                         sr__window win, sr_polygon2 *out)
{
    const double bound[4] = {
        clamp_budget(win.x0 - GUARD_MARGIN), clamp_budget(win.y1 + GUARD_MARGIN),
        clamp_budget(win.x1 + GUARD_MARGIN), clamp_budget(win.y0 - GUARD_MARGIN),
    };
    static const int axis[4] = { 0, 1, 0, 1 };
    static const double sign[4] = { +1, -1, -1, +1 };
    int contours = poly->contour_counts ? poly->contour_count : 1;
    *out = (sr_polygon2){0};
    sr__clip_scratch sc = { 0 };
    long long cap_out = 0, total = 0;
    sr_point2 *res = NULL;
    int *counts = sr__alloc(ctx, (size_t)(contours > 0 ? contours : 1) * sizeof *counts);
    sr_result r = counts ? SR_OK : SR_OUT_OF_MEMORY;
    for (int c = 0, at = 0; r == SR_OK && c < contours; c++) {
        int n = poly->contour_counts ? poly->contour_counts[c] : poly->point_count, m = n;
        if (!sr__clip_reserve(ctx, &sc.a, &sc.cap_a, n + 1LL)) {
            r = SR_OUT_OF_MEMORY;
            break;
        }
        for (int i = 0; i < n; i++) {
            sc.a[i] = poly->points[at + i];
        }
        at += n;
        for (int k = 0; k < 4 && r == SR_OK; k++) {
            r = sr__clip_axis_stage(ctx, &sc, axis[k], bound[k], sign[k], &m) ? SR_OK
                                                                               : SR_OUT_OF_MEMORY;
        }
        if (r != SR_OK) {
            break;
        }
        if (total + m > INT32_MAX) {
            r = SR_TOO_LARGE;
            break;
        }
        if (total + m > cap_out) {
            long long cap = (total + m) * 2;
            sr_point2 *grown = sr__alloc(ctx, (size_t)cap * sizeof *grown);
            if (!grown) {
                r = SR_OUT_OF_MEMORY;
                break;
            }
            for (long long i = 0; i < total; i++) {
                grown[i] = res[i];
            }
            sr__free(ctx, res);
            res = grown;
            cap_out = cap;
        }
        for (int i = 0; i < m; i++) {
            res[total + i] = sc.a[i];
        }
        total += m;
        counts[c] = m;
    }
    sr__free(ctx, sc.a);
    sr__free(ctx, sc.b);
    if (r != SR_OK) {
        sr__free(ctx, counts);
        sr__free(ctx, res);
        return sr__fail(ctx, r, r == SR_TOO_LARGE
                                    ? "%s: the polygon cut to the guard band passes 2^31 points"
                                    : "%s: no memory to cut the polygon to the guard band", fn);
    }
    *out = (sr_polygon2){ res, (int)total, counts, contours };
    return SR_OK;
}
