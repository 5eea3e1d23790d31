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

#include <math.h>

/* Far enough outside every window that a clipped edge keeps its direction
 * through the window to well below 1/256 px (its end moves by a rounding
 * of the guard line's distance), near enough that a window at the far end
 * of the budget still has room around it. */
#define GUARD_MARGIN 131072.0

static double clamp_budget(double v)
{
    return v < -SR_MAX_COORD2D ? -SR_MAX_COORD2D : v > SR_MAX_COORD2D ? SR_MAX_COORD2D : v;
}

/* Make *buf hold at least `need` points (its contents need not survive). */
static bool reserve(sr_context *ctx, sr_point2 **buf, long long *cap, long long need)
{
    if (need <= *cap) {
        return true;
    }
    sr__free(ctx, *buf);
    *buf = sr__alloc(ctx, (size_t)need * sizeof **buf);
    *cap = *buf ? need : 0;
    return *buf != NULL;
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
    long long cap_out = 0, cap_a = 0, cap_b = 0, total = 0;
    sr_point2 *res = NULL, *a = NULL, *b = NULL;
    int *counts = sr__alloc(ctx, (size_t)(contours > 0 ? contours : 1) * sizeof *counts);
    sr_result r = counts ? SR_OK : SR_OUT_OF_MEMORY;
    for (int c = 0, at = 0; r == SR_OK && c < contours; c++) {
        int n = poly->contour_counts ? poly->contour_counts[c] : poly->point_count;
        if (!reserve(ctx, &a, &cap_a, n + 1LL)) {
            r = SR_OUT_OF_MEMORY;
            break;
        }
        for (int i = 0; i < n; i++) {
            a[i] = poly->points[at + i];
        }
        at += n;
        int m = n;
        for (int k = 0; k < 4 && r == SR_OK; k++) {
            /* A stage emits one point per edge kept or leaving and two per
             * edge entering; entries pair with exits, so at most 3/2 m. */
            if (!reserve(ctx, &b, &cap_b, 3LL * m / 2 + 2)) {
                r = SR_OUT_OF_MEMORY;
                break;
            }
            m = sr__clip_axis_stage(axis[k], bound[k], sign[k], a, m, b);
            sr_point2 *t = a;
            a = b;
            b = t;
            long long tc = cap_a;
            cap_a = cap_b;
            cap_b = tc;
        }
        if (r != SR_OK) {
            break;
        }
        if (total + m > INT32_MAX) {
            sr__free(ctx, counts);
            sr__free(ctx, res);
            sr__free(ctx, a);
            sr__free(ctx, b);
            return sr__fail(ctx, SR_TOO_LARGE, "%s: the polygon cut to the guard band has more "
                            "than 2^31 points", fn);
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
            res[total + i] = a[i];
        }
        total += m;
        counts[c] = m;
    }
    sr__free(ctx, a);
    sr__free(ctx, b);
    if (r != SR_OK) {
        sr__free(ctx, counts);
        sr__free(ctx, res);
        return sr__fail(ctx, r, "%s: no memory to cut the polygon to the guard band", fn);
    }
    *out = (sr_polygon2){ res, (int)total, counts, contours };
    return SR_OK;
}
