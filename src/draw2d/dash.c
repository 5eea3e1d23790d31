/* dash.c - draw2d stage: dashed paths, as SVG's stroke-dasharray and
 * stroke-dashoffset.  Consumes a flattened path and produces a path of
 * its dashes, each an open subpath that is then stroked as any path is,
 * so caps and joins apply per dash.  The pattern restarts at every
 * subpath; on a closed subpath the closing segment is dashed too, and a
 * dash running over the start point continues into the first one (one
 * dash, joined, no caps there).  The SVG reader dashes through this too.
 * Same threading as path.c. */
#include "context.h"

#include <math.h>
#include <stdbool.h>

/* The most points a dashed path may take: sr_path's own limit. */
#define MAX_DASH_POINTS (1 << 26)

double sr_path_length(const sr_path *path)
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
            len += hypot(b.x - a.x, b.y - a.y);
        }
        start += n;
    }
    return len;
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
    sr_result r;
} dasher;

static void emit(dasher *d, sr_point2 p, bool start)
{
    if (d->r == SR_OK && !d->held) {
        d->r = start ? sr_path_move_to(d->out, p.x, p.y) : sr_path_line_to(d->out, p.x, p.y);
    }
}

/* Walk a to b: points of the dashes into out. */
static void walk(dasher *d, sr_point2 a, sr_point2 b)
{
    double len = hypot(b.x - a.x, b.y - a.y), at = 0;
    while (d->r == SR_OK) {
        double step = fmin(d->left, len - at);
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
        if (at >= len && d->left > 0) {
            return;
        }
    }
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
                               double offset, sr_path *out)
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
        dasher d = { .out = out, .dash = dash, .n = n, .index = 0, .left = dash[0] };
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
        if (d.drawing) {
            emit(&d, p[0], true);
        }
        walk_subpath(&d, p, count, closed);
        if (held && d.r == SR_OK) {
            /* still held: the dash went all the way round */
            if (!d.drawing || d.held) {
                d.held = false;
                emit(&d, p[0], true);
            }
            const double first[2] = { head, INFINITY };
            dasher h = { .out = out, .dash = first, .n = 2, .left = head, .drawing = true };
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
    static const char fn[] = "sr_path_dash";
    if (!ctx) {
        return SR_INVALID_ARG;
    }
    if (!path || !out || (!dashes && count != 0)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %s is NULL", fn,
                        !path ? "path" : !out ? "out" : "dashes");
    }
    if (out == path) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: out must not be path itself", fn);
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
        double pieces = sr_path_length(path) / period * n + poly.contour_count;
        double points = poly.point_count + 2 * pieces + sr_path_polygon(out).point_count;
        if (!(points <= MAX_DASH_POINTS)) {
            return sr__fail(ctx, SR_TOO_LARGE,
                            "%s: a pattern of period %g along a path of length %g makes about "
                            "%.0f dashes, beyond a path's %d points",
                            fn, period, sr_path_length(path), pieces, MAX_DASH_POINTS);
        }
        r = dash_subpaths(path, dash, n, period, offset, out);
    }
    if (r != SR_OK) {
        return sr__fail(ctx, r, "%s: the dashes do not fit in out (%s)", fn, sr_result_text(r));
    }
    sr__ok(ctx);
    return SR_OK;
}
