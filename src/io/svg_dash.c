/* svg_dash.c - the SVG reader's dashed strokes (stroke-dasharray,
 * stroke-dashoffset): the flattened path is cut into dashes, each an open
 * subpath that is then stroked as any path is, so caps and joins apply
 * per dash.  The pattern restarts at every subpath; on a closed subpath
 * the closing segment is dashed too, and a dash running over the start
 * point continues into the first one (one dash, joined, no caps there). */
#include "io/svg.h"

#include <math.h>
#include <stdlib.h>

double svg_path_length(const sr_path *path)
{
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

sr_result svg_dash_path(const sr_path *in, const double *dash, int n, double offset,
                        sr_path *out)
{
    sr_polygon2 poly = sr_path_polygon(in);
    double period = 0;
    for (int i = 0; i < n; i++) {
        period += dash[i];
    }
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
