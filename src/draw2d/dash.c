/* dash.c - draw2d stage: dashed paths, as SVG's stroke-dasharray and
 * stroke-dashoffset.  Consumes a flattened path and produces a path of
 * its dashes, each an open subpath that is then stroked as any path is,
 * so caps and joins apply per dash.  The pattern restarts at every
 * subpath; on a closed subpath the closing segment is dashed too, and a
 * dash running over the start point continues into the first one (one
 * dash, joined, no caps there).  The SVG reader dashes through this too.
 * Same threading as path.c. */
#include "context.h"
#include "draw2d/pathcull.h"

#include <math.h>
#include <stdbool.h>

/* The most points a dashed path may take: sr_path's own limit. */
#define MAX_DASH_POINTS (1 << 26)

/* The part [*s0, *s1] of the segment a-b, as lengths along it, that the
 * cull region holds when cull is set (Liang-Barsky on the mapped
 * segment); all of it without one.  *s0 > *s1 when none is. */
static void span_within(const sr_path_view *cull, sr_point2 a, sr_point2 b, double len, double *s0,
                        double *s1)
{
    double t0 = 0, t1 = 1;
    if (cull) {
        const double *m = cull->m;
        double ax = m[0] * a.x + m[2] * a.y + m[4], ay = m[1] * a.x + m[3] * a.y + m[5];
        double bx = m[0] * b.x + m[2] * b.y + m[4], by = m[1] * b.x + m[3] * b.y + m[5];
        const double from[4] = { ax, -ax, ay, -ay }, delta[4] = { bx - ax, ax - bx, by - ay, ay - by };
        const double bound[4] = { cull->x1, -cull->x0, cull->y1, -cull->y0 };
        for (int k = 0; k < 4; k++) {
            /* from + t delta <= bound */
            if (delta[k] == 0) {
                if (!(from[k] <= bound[k])) {
                    t0 = 1, t1 = 0;
                }
            } else {
                double t = (bound[k] - from[k]) / delta[k];
                if (delta[k] > 0) {
                    t1 = fmin(t1, t);
                } else {
                    t0 = fmax(t0, t);
                }
            }
        }
    }
    *s0 = t0 * len;
    *s1 = t0 <= t1 ? t1 * len : -1;
}

double sr_path_length_in_view(const sr_path *path, const sr_path_view *cull)
{
    if (!path) {
        return 0;
    }
    sr_polygon2 poly = sr_path_polygon(path);
    double len = 0;
    int start = 0;
    for (int c = 0; c < poly.contour_count; c++) {
        int n = poly.contour_counts[c];
        int segs = sr_path_subpath_closed(path, c) ? n : n - 1;
        for (int i = 0; i < segs; i++) {
            sr_point2 a = poly.points[start + i], b = poly.points[start + (i + 1) % n];
            double l = hypot(b.x - a.x, b.y - a.y), s0, s1;
            span_within(cull, a, b, l, &s0, &s1);
            len += s1 > s0 ? s1 - s0 : 0;
        }
        start += n;
    }
    return len;
}

double sr_path_length(const sr_path *path)
{
    return sr_path_length_in_view(path, NULL);
}

/* The dash walk along one subpath. */
typedef struct dasher {
    sr_path *out;
    const double *dash;
    int n;
    int index;                /* the current dash or gap */
    double left;              /* of it still to go */
    bool drawing;             /* inside a dash, whose subpath is open in out */
    bool held;                /* the first dash of a closed subpath: drawn last */
    bool broken;              /* the dash drawn was cut at the cull region */
    const sr_path_view *cull;     /* NULL: every dash is drawn */
    sr_result r;
} dasher;

static void emit(dasher *d, sr_point2 p, bool start)
{
    if (d->r == SR_OK && !d->held) {
        d->r = start ? sr_path_move_to(d->out, p.x, p.y) : sr_path_line_to(d->out, p.x, p.y);
    }
}

/* Whether p lies within cull's region (always without one): a dash that
 * starts outside starts where the path enters instead. */
static bool within(const sr_path_view *cull, sr_point2 p)
{
    if (!cull) {
        return true;
    }
    const double *m = cull->m;
    double x = m[0] * p.x + m[2] * p.y + m[4], y = m[1] * p.x + m[3] * p.y + m[5];
    return x >= cull->x0 && x <= cull->x1 && y >= cull->y0 && y <= cull->y1;
}

/* The pattern moved on by len without drawing: outside the cull region. */
static void skip(dasher *d, double len)
{
    if (!(len > 0)) {
        return;
    }
    if (len >= d->left) {
        len -= d->left;
        d->left = 0;
        /* whole periods at once: fmod is exact */
        double period = 0;
        for (int i = 0; i < d->n; i++) {
            period += d->dash[i];
        }
        if (isfinite(period)) {
            len = fmod(len, period);
        }
        while (d->r == SR_OK) {
            d->held = false;
            d->index = (d->index + 1) % d->n;
            d->left = d->dash[d->index];
            if (len < d->left || (len == d->left && len > 0)) {
                break;
            }
            len -= d->left;
        }
        d->drawing = d->index % 2 == 0;
    }
    d->left -= len;
    d->broken = true;
}

/* Walk a to b from at to end (lengths along it): points of the dashes
 * into out. */
static void walk_span(dasher *d, sr_point2 a, sr_point2 b, double len, double at, double end)
{
    if (d->broken) {
        /* a dash cut at the region goes on from where the segment enters */
        d->broken = false;
        if (d->drawing) {
            emit(d, (sr_point2){ a.x + (b.x - a.x) * (len > 0 ? at / len : 0),
                                 a.y + (b.y - a.y) * (len > 0 ? at / len : 0) }, true);
        }
    }
    while (d->r == SR_OK) {
        double step = fmin(d->left, end - at);
        at += step;
        d->left -= step;
        sr_point2 p = { a.x + (b.x - a.x) * (len > 0 ? at / len : 1),
                        a.y + (b.y - a.y) * (len > 0 ? at / len : 1) };
        if (d->drawing) {
            emit(d, p, false);
        }
        if (d->left > 0) {
            return; /* the segment ends inside this dash or gap */
        }
        d->held = false;
        d->index = (d->index + 1) % d->n;
        d->left = d->dash[d->index];
        d->drawing = d->index % 2 == 0;
        if (d->drawing) {
            emit(d, p, true);
        }
        if (at >= end && d->left > 0) {
            return;
        }
    }
}

/* Walk a to b: the part within the cull region drawn, the rest skipped. */
static void walk(dasher *d, sr_point2 a, sr_point2 b)
{
    double len = hypot(b.x - a.x, b.y - a.y), s0, s1;
    span_within(d->cull, a, b, len, &s0, &s1);
    if (!(s1 >= s0)) {
        skip(d, len);
        return;
    }
    skip(d, s0);
    walk_span(d, a, b, len, s0, s1);
    skip(d, len - s1);
}

/* Walk the subpath p[0..count) (closed: back to p[0]) with d. */
static void walk_subpath(dasher *d, const sr_point2 *p, int count, bool closed)
{
    int segs = closed ? count : count - 1;
    for (int i = 0; i < segs && d->r == SR_OK; i++) {
        walk(d, p[i], p[(i + 1) % count]);
    }
}

/* out gets a copy of in's subpaths (a pattern that draws everything). */
static sr_result copy_path(const sr_path *in, sr_path *out)
{
    sr_polygon2 poly = sr_path_polygon(in);
    sr_result r = SR_OK;
    for (int c = 0, at = 0; r == SR_OK && c < poly.contour_count; at += poly.contour_counts[c++]) {
        for (int i = 0; r == SR_OK && i < poly.contour_counts[c]; i++) {
            sr_point2 p = poly.points[at + i];
            r = i == 0 ? sr_path_move_to(out, p.x, p.y) : sr_path_line_to(out, p.x, p.y);
        }
        if (r == SR_OK && sr_path_subpath_closed(in, c)) {
            r = sr_path_close(out);
        }
    }
    return r;
}

/* The dashes of every subpath of in into out; dash[0..n) even, their sum
 * `period` > 0, the work bounded by the caller. */
static sr_result dash_subpaths(const sr_path *in, const double *dash, int n, double period,
                               double offset, const sr_path_view *cull, sr_path *out)
{
    sr_polygon2 poly = sr_path_polygon(in);
    offset = fmod(offset, period);
    if (offset < 0) {
        offset += period;
    }
    int start = 0;
    for (int c = 0; c < poly.contour_count; c++) {
        const sr_point2 *p = poly.points + start;
        int count = poly.contour_counts[c];
        bool closed = sr_path_subpath_closed(in, c);
        start += count;
        /* Where the pattern stands at the subpath's start. */
        dasher d = { .out = out, .dash = dash, .n = n, .index = 0, .left = dash[0], .cull = cull };
        double skip = offset;
        while (skip > d.left || (skip == d.left && skip > 0)) {
            skip -= d.left;
            d.index = (d.index + 1) % n;
            d.left = dash[d.index];
        }
        d.left -= skip;
        d.drawing = d.index % 2 == 0;
        /* On a closed subpath a dash at the start is drawn after the walk,
         * as the end of the last dash when that one reaches the start. */
        bool held = d.held = closed && d.drawing;
        double head = d.left;
        bool start_within = within(cull, p[0]);
        d.broken = !start_within;
        if (d.drawing && start_within) {
            emit(&d, p[0], true);
        }
        walk_subpath(&d, p, count, closed);
        if (held && d.r == SR_OK) {
            /* still held: the dash went all the way round */
            /* a last dash cut at the region does not go on into the first */
            bool broken = d.broken;
            if (!d.drawing || d.held) {
                d.held = false;
                broken = !start_within;
                if (start_within) {
                    emit(&d, p[0], true);
                }
            }
            const double first[2] = { head, INFINITY };
            dasher h = { .out = out, .dash = first, .n = 2, .left = head, .drawing = true,
                         .broken = broken, .cull = cull };
            walk_subpath(&h, p, count, true);
            d.r = h.r;
        }
        if (d.r != SR_OK) {
            return d.r;
        }
    }
    return SR_OK;
}

sr_result sr_path_dash(sr_context *ctx, const sr_path *path, const double *dashes, int count,
                       double offset, sr_path *out)
{
    return sr_path_dash_in_view(ctx, path, dashes, count, offset, NULL, out);
}

sr_result sr_path_dash_in_view(sr_context *ctx, const sr_path *path, const double *dashes,
                               int count, double offset, const sr_path_view *cull, sr_path *out)
{
    static const char fn[] = "sr_path_dash";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_path_dash_in_view: ctx is NULL");
    }
    if (!path || !out || (!dashes && count != 0)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %s is NULL", fn,
                        !path ? "path" : !out ? "out" : "dashes");
    }
    if (out == path) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: out must not be path itself", fn);
    }
    if (cull && !sr__path_view_valid(cull)) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "%s: the view needs a finite m and a rectangle x0 <= x1, y0 <= y1", fn);
    }
    if (count < 0 || count > SR_MAX_DASHES) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: count must be 0 .. %d (got %d)", fn,
                        SR_MAX_DASHES, count);
    }
    if (!isfinite(offset)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: offset must be finite (got %g)", fn, offset);
    }
    /* An odd list is repeated once to make an even one (SVG). */
    double dash[2 * SR_MAX_DASHES], period = 0;
    int n = count % 2 ? 2 * count : count;
    for (int i = 0; i < n; i++) {
        dash[i] = dashes[i % count];
        if (!(dash[i] >= 0) || !isfinite(dash[i])) {
            return sr__fail(ctx, SR_INVALID_ARG, "%s: dashes[%d] must be finite and >= 0 (got %g)",
                            fn, i % count, dash[i]);
        }
        period += dash[i];
    }
    sr_result r;
    if (!(period > 0)) {
        r = copy_path(path, out); /* no list or all zero: solid, as SVG draws it */
    } else {
        /* Each dash is a subpath of at most its segments' points plus its
         * two ends: refused before any is cut when they would not fit. */
        sr_polygon2 poly = sr_path_polygon(path);
        double len = sr_path_length_in_view(path, cull);
        double pieces = len / period * n + poly.contour_count;
        /* where the region cuts, a dash starts again: a point of the path
         * each, and its start */
        double points = (cull ? 3 : 1) * (double)poly.point_count + 2 * pieces +
                        sr_path_polygon(out).point_count;
        if (!(points <= MAX_DASH_POINTS)) {
            return sr__fail(ctx, SR_TOO_LARGE,
                            "%s: a pattern of period %g along a path of length %g makes about "
                            "%.0f dashes, beyond a path's %d points",
                            fn, period, len, pieces, MAX_DASH_POINTS);
        }
        r = dash_subpaths(path, dash, n, period, offset, cull, out);
    }
    if (r != SR_OK) {
        return sr__fail(ctx, r, "%s: the dashes do not fit in out (%s)", fn, sr_result_text(r));
    }
    sr__ok(ctx);
    return SR_OK;
}
