/* path.c - draw2d stage: paths and strokes.  Consumes path commands
 * (lines, Beziers, SVG arcs), flattens them as they arrive, and produces
 * either a fill (every subpath closed, through the polygon fill) or a
 * stroke: the outline polygon of quadrilaterals per segment plus join and
 * cap pieces, all wound the same way and filled nonzero, so overlaps
 * merge.  A path and the context it was made on belong to one thread. */
#include "draw2d/polyfill.h"

#include "context.h"
#include "draw2d/arc.h"
#include "draw2d/paint.h"
#include "draw2d/pathcull.h"

#include <math.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define MAX_PATH_POINTS (1 << 26)

struct sr_path {
    sr_context *ctx;
    double tolerance;
    sr_point2 *pts;
    int n, cap;
    int *counts;          /* points per subpath */
    uint8_t *closed;      /* per subpath */
    int nc, ccap;
    int closed_cap;       /* closed[]'s capacity, ccap once grown */
    bool in_subpath;      /* the last subpath takes further points */
    bool has_current;
    sr_point2 current, start;
    sr_path_view view;    /* sr_path_cull_curves */
    bool cull;
};

/* ---- building ------------------------------------------------------------- */

sr_result sr_make_path(sr_context *ctx, double tolerance, sr_path **out)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_make_path: ctx is NULL");
    }
    if (!out) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_make_path: out is NULL");
    }
    *out = NULL;
    if (tolerance == 0) {
        tolerance = 0.1;
    }
    if (!(tolerance > 0) || !isfinite(tolerance)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_make_path: tolerance must be >= 0 (got %g)",
                        tolerance);
    }
    sr_path *p = sr__calloc(ctx, 1, sizeof *p);
    if (!p) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_make_path: no memory");
    }
    p->ctx = ctx;
    p->tolerance = tolerance;
    *out = p;
    sr__ok(ctx);
    return SR_OK;
}

void sr_destroy_path(sr_context *ctx, sr_path *path)
{
    if (!ctx || !path) {
        return;
    }
    sr__free(ctx, path->pts);
    sr__free(ctx, path->counts);
    sr__free(ctx, path->closed);
    sr__free(ctx, path);
}

void sr_path_clear(sr_path *path)
{
    if (path) {
        path->n = path->nc = 0;
        path->in_subpath = path->has_current = false;
        path->cull = false;
    }
}

static bool grow(sr_context *ctx, void **buf, int *cap, int need, size_t elem)
{
    if (need <= *cap) {
        return true;
    }
    int c = *cap ? *cap : 64;
    while (c < need) {
        c *= 2;
    }
    void *b = sr__alloc(ctx, (size_t)c * elem);
    if (!b) {
        return false;
    }
    if (*buf) {
        memcpy(b, *buf, (size_t)*cap * elem);
    }
    sr__free(ctx, *buf);
    *buf = b;
    *cap = c;
    return true;
}

static sr_result begin_subpath(sr_path *p, sr_point2 at)
{
    if (!grow(p->ctx, (void **)&p->counts, &p->ccap, p->nc + 1, sizeof *p->counts)) {
        return sr__fail(p->ctx, SR_OUT_OF_MEMORY, "sr_path: no memory");
    }
    /* closed[] grows with counts[]: same capacity. */
    if (p->closed_cap < p->ccap) {
        uint8_t *closed = sr__alloc(p->ctx, (size_t)p->ccap);
        if (!closed) {
            return sr__fail(p->ctx, SR_OUT_OF_MEMORY, "sr_path: no memory");
        }
        if (p->closed) {
            memcpy(closed, p->closed, (size_t)p->nc);
        }
        sr__free(p->ctx, p->closed);
        p->closed = closed;
        p->closed_cap = p->ccap;
    }
    p->counts[p->nc] = 0;
    p->closed[p->nc] = 0;
    p->nc++;
    p->in_subpath = true;
    p->start = at;
    p->current = at;
    p->has_current = true;
    if (p->n + 1 > MAX_PATH_POINTS ||
        !grow(p->ctx, (void **)&p->pts, &p->cap, p->n + 1, sizeof *p->pts)) {
        return sr__fail(p->ctx, SR_OUT_OF_MEMORY, "sr_path: no memory for more points");
    }
    p->pts[p->n++] = at;
    p->counts[p->nc - 1]++;
    return SR_OK;
}

/* Append points to the current subpath (starting one at the current
 * point after a close). */
static sr_result append(sr_path *p, const sr_point2 *pts, int n)
{
    if (n == 0) {
        sr__ok(p->ctx);
        return SR_OK;
    }
    if (!p->in_subpath) {
        sr_result r = begin_subpath(p, p->has_current ? p->current : pts[0]);
        if (r != SR_OK) {
            return r;
        }
    }
    if ((long long)p->n + n > MAX_PATH_POINTS ||
        !grow(p->ctx, (void **)&p->pts, &p->cap, p->n + n, sizeof *p->pts)) {
        return sr__fail(p->ctx, SR_OUT_OF_MEMORY, "sr_path: no memory for more points");
    }
    memcpy(p->pts + p->n, pts, (size_t)n * sizeof *pts);
    p->n += n;
    p->counts[p->nc - 1] += n;
    if (n > 0) {
        p->current = pts[n - 1];
    }
    sr__ok(p->ctx);
    return SR_OK;
}

static bool finite2(double a, double b)
{
    return isfinite(a) && isfinite(b);
}

sr_result sr_path_move_to(sr_path *path, double x, double y)
{
    if (!path) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_path_move_to: path is NULL");
    }
    if (!finite2(x, y)) {
        return sr__fail(path->ctx, SR_INVALID_ARG, "sr_path_move_to: point is not finite");
    }
    sr_result r = begin_subpath(path, (sr_point2){ x, y });
    if (r == SR_OK) {
        sr__ok(path->ctx);
    }
    return r;
}

sr_result sr_path_line_to(sr_path *path, double x, double y)
{
    if (!path) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_path_line_to: path is NULL");
    }
    if (!finite2(x, y)) {
        return sr__fail(path->ctx, SR_INVALID_ARG, "sr_path_line_to: point is not finite");
    }
    sr_point2 pt = { x, y };
    return append(path, &pt, 1);
}

/* Flatten into a temporary buffer sized by a first call, then append. */
typedef sr_result (*flatten_fn)(sr_path *p, sr_point2 from, sr_point2 *out, int cap, int *n,
                                const void *args);

/* args[0..1] is also the start point when the path has no current one. */
static sr_result flatten_append(sr_path *p, flatten_fn fn, const void *args)
{
    const double *a = args;
    sr_point2 from = p->has_current ? p->current : (sr_point2){ a[0], a[1] };
    sr_point2 small[64];
    int n = 0;
    sr_result r = fn(p, from, small, 64, &n, args);
    if (r == SR_OK) {
        return append(p, small, n);
    }
    if (r != SR_TOO_LARGE) {
        return r;
    }
    sr_point2 *big = sr__alloc(p->ctx, (size_t)n * sizeof *big);
    if (!big) {
        return sr__fail(p->ctx, SR_OUT_OF_MEMORY, "sr_path: no memory for %d points", n);
    }
    r = fn(p, from, big, n, &n, args);
    if (r == SR_OK) {
        r = append(p, big, n);
    }
    sr__free(p->ctx, big);
    return r;
}

static sr_result quad_fn(sr_path *p, sr_point2 from, sr_point2 *out, int cap, int *n,
                         const void *args)
{
    const double *a = args;
    return sr_flatten_quadratic(p->ctx, from, (sr_point2){ a[0], a[1] }, (sr_point2){ a[2], a[3] },
                                p->tolerance, out, cap, n);
}

static sr_result cubic_fn(sr_path *p, sr_point2 from, sr_point2 *out, int cap, int *n,
                          const void *args)
{
    const double *a = args;
    return sr_flatten_cubic(p->ctx, from, (sr_point2){ a[0], a[1] }, (sr_point2){ a[2], a[3] },
                            (sr_point2){ a[4], a[5] }, p->tolerance, out, cap, n);
}

static sr_result arc_fn(sr_path *p, sr_point2 from, sr_point2 *out, int cap, int *n,
                        const void *args)
{
    const double *a = args;
    return sr_flatten_arc(p->ctx, from, a[2], a[3], a[4], a[5] != 0, a[6] != 0,
                          (sr_point2){ a[0], a[1] }, p->tolerance, out, cap, n);
}

/* ---- culling curves far outside ------------------------------------------- */

sr_result sr_path_cull_curves(sr_path *path, const sr_path_view *view)
{
    if (!path) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_path_cull_curves: path is NULL");
    }
    if (view && !sr__path_view_valid(view)) {
        return sr__fail(path->ctx, SR_INVALID_ARG, "sr_path_cull_curves: the view needs a finite "
                        "m and a rectangle x0 <= x1, y0 <= y1");
    }
    path->cull = view != NULL;
    if (view) {
        path->view = *view;
    }
    sr__ok(path->ctx);
    return SR_OK;
}

/* A piece this small in device pixels is flattened even when it crosses
 * the rectangle's edge: cutting it further saves no points. */
#define CULL_SMALL 4096.0
#define CULL_DEPTH 64

/* Where the control points c[0..n) lie, mapped: bit k set when every one
 * is beyond side k of the view's rectangle; *inside when all are within it; *extent
 * the larger side of their box. */
static int cull_sides(const sr_path *p, const sr_point2 *c, int n, bool *inside, double *extent)
{
    const double *m = p->view.m;
    int all = 15, any = 0;
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (int i = 0; i < n; i++) {
        double x = m[0] * c[i].x + m[2] * c[i].y + m[4], y = m[1] * c[i].x + m[3] * c[i].y + m[5];
        int out = (x < p->view.x0) | (x > p->view.x1) << 1 | (y < p->view.y0) << 2 |
                  (y > p->view.y1) << 3;
        all &= out;
        any |= out;
        /* Comparisons, not fmin/fmax: GCC 12's aarch64 vectorizer fails
         * (an internal compiler error) on this loop's fmin/fmax reduction.
         * A NaN is passed over either way. */
        x0 = x < x0 ? x : x0, x1 = x > x1 ? x : x1;
        y0 = y < y0 ? y : y0, y1 = y > y1 ? y : y1;
    }
    *inside = any == 0;
    *extent = fmax(x1 - x0, y1 - y0);
    return all;
}

/* The curve with control points c[0..n) (n = 3 or 4, c[0] the current
 * point): pieces wholly outside as lines, the rest flattened.  A curve
 * outside may be drawn as any path outside with the same ends: the fill's
 * winding and the stroke's pixels within the rectangle do not change. */
static sr_result cull_curve(sr_path *p, const sr_point2 *c, int n, int depth)
{
    bool inside;
    double extent;
    if (cull_sides(p, c, n, &inside, &extent) != 0) {
        return append(p, &c[n - 1], 1);
    }
    if (inside || extent <= CULL_SMALL || depth == 0) {
        double a[6] = { c[1].x, c[1].y, c[2].x, c[2].y, c[n - 1].x, c[n - 1].y };
        return flatten_append(p, n == 3 ? quad_fn : cubic_fn, a);
    }
    /* de Casteljau at t = 1/2: left[] and right[] share the middle point */
    sr_point2 w[4], left[4], right[4];
    memcpy(w, c, (size_t)n * sizeof *w);
    for (int k = 0; k < n; k++) {
        left[k] = w[0];
        right[n - 1 - k] = w[n - 1 - k];
        for (int i = 0; i + 1 < n - k; i++) {
            w[i] = (sr_point2){ (w[i].x + w[i + 1].x) / 2, (w[i].y + w[i + 1].y) / 2 };
        }
    }
    sr_result r = cull_curve(p, left, n, depth - 1);
    return r == SR_OK ? cull_curve(p, right, n, depth - 1) : r;
}

/* A Bezier segment from the current point through c[0..n-1), culled when
 * the path asks for it and has a current point. */
static sr_result curve_to(sr_path *p, const sr_point2 *c, int n, flatten_fn fn, const double *a)
{
    if (!p->cull || !p->has_current) {
        return flatten_append(p, fn, a);
    }
    sr_point2 all[4] = { p->current };
    memcpy(all + 1, c, (size_t)(n - 1) * sizeof *c);
    return cull_curve(p, all, n, CULL_DEPTH);
}

sr_result sr_path_quad_to(sr_path *path, double x1, double y1, double x, double y)
{
    if (!path) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_path_quad_to: path is NULL");
    }
    double a[4] = { x1, y1, x, y };
    return curve_to(path, (const sr_point2[]){ { x1, y1 }, { x, y } }, 3, quad_fn, a);
}

sr_result sr_path_cubic_to(sr_path *path, double x1, double y1, double x2, double y2,
                           double x, double y)
{
    if (!path) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_path_cubic_to: path is NULL");
    }
    double a[6] = { x1, y1, x2, y2, x, y };
    return curve_to(path, (const sr_point2[]){ { x1, y1 }, { x2, y2 }, { x, y } }, 4, cubic_fn,
                    a);
}

/* A piece of an arc: from angle t0 over dt to the point `to`. */
typedef struct arc_piece {
    const sr__arc *arc;
    double t0, dt;
    sr_point2 to;
} arc_piece;

static sr_result arc_piece_fn(sr_path *p, sr_point2 from, sr_point2 *out, int cap, int *n,
                              const void *args)
{
    const arc_piece *a = args;
    (void)from;
    *n = sr__arc_steps(a->arc, a->dt, p->tolerance);
    if (*n > cap) {
        return SR_TOO_LARGE;
    }
    sr__arc_points(a->arc, a->t0, a->dt, *n, a->to, out);
    return SR_OK;
}

/* The triangle holding an arc piece of at most a quarter turn: its ends
 * and where their tangents meet (on the circle's image at the middle
 * angle, 1 / cos(dt / 2) times as far out). */
static void arc_hull(const sr__arc *arc, double t0, double dt, sr_point2 *c)
{
    sr__arc out = *arc;
    out.rx /= cos(dt / 2);
    out.ry /= cos(dt / 2);
    c[0] = sr__arc_point(arc, t0);
    c[1] = sr__arc_point(&out, t0 + dt / 2);
    c[2] = sr__arc_point(arc, t0 + dt);
}

/* An arc piece as cull_curve does a Bezier: outside as a line, halved
 * (by angle) while it crosses the rectangle's edge and is large. */
static sr_result cull_arc(sr_path *p, const arc_piece *a, int depth)
{
    sr_point2 c[3];
    arc_hull(a->arc, a->t0, a->dt, c);
    bool inside;
    double extent;
    if (cull_sides(p, c, 3, &inside, &extent) != 0) {
        return append(p, &a->to, 1);
    }
    if (inside || extent <= CULL_SMALL || depth == 0) {
        return flatten_append(p, arc_piece_fn, a);
    }
    double half = a->dt / 2;
    arc_piece first = { a->arc, a->t0, half, sr__arc_point(a->arc, a->t0 + half) };
    arc_piece second = { a->arc, a->t0 + half, half, a->to };
    sr_result r = cull_arc(p, &first, depth - 1);
    return r == SR_OK ? cull_arc(p, &second, depth - 1) : r;
}

sr_result sr_path_arc_to(sr_path *path, double rx, double ry, double rotation_deg,
                         bool large_arc, bool sweep, double x, double y)
{
    if (!path) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_path_arc_to: path is NULL");
    }
    /* args[0..1] is the end point (also the start when there is no
     * current point, which makes the arc empty). */
    double a[7] = { x, y, rx, ry, rotation_deg, large_arc, sweep };
    sr__arc arc;
    if (!path->cull || !path->has_current || !finite2(x, y) || !finite2(rx, ry) ||
        !isfinite(rotation_deg) ||
        sr__arc_centre(path->current, rx, ry, rotation_deg, large_arc, sweep,
                       (sr_point2){ x, y }, &arc) != SR__ARC_CURVED) {
        return flatten_append(path, arc_fn, a);
    }
    /* Quarter turns at most, each in its triangle.  An arc wholly inside,
     * or small, is flattened in one run: the points drawn without a view. */
    int quarters = (int)fmin(fmax(ceil(fabs(arc.dtheta) / (M_PI / 2)), 1), 4);
    sr_point2 hull[12], to = { x, y };
    for (int i = 0; i < quarters; i++) {
        arc_hull(&arc, arc.theta1 + arc.dtheta * i / quarters, arc.dtheta / quarters, hull + 3 * i);
    }
    bool inside;
    double extent;
    if (cull_sides(path, hull, 3 * quarters, &inside, &extent) != 0) {
        return append(path, &to, 1);
    }
    if (inside || extent <= CULL_SMALL) {
        return flatten_append(path, arc_fn, a);
    }
    sr_result r = SR_OK;
    for (int i = 0; r == SR_OK && i < quarters; i++) {
        double t0 = arc.theta1 + arc.dtheta * i / quarters, dt = arc.dtheta / quarters;
        arc_piece q = { &arc, t0, dt, i + 1 < quarters ? sr__arc_point(&arc, t0 + dt) : to };
        r = cull_arc(path, &q, CULL_DEPTH);
    }
    return r;
}

sr_result sr_path_close(sr_path *path)
{
    if (!path) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_path_close: path is NULL");
    }
    if (path->in_subpath) {
        path->closed[path->nc - 1] = 1;
        path->in_subpath = false;
        path->current = path->start;
    }
    sr__ok(path->ctx);
    return SR_OK;
}

sr_polygon2 sr_path_polygon(const sr_path *path)
{
    if (!path) {
        return (sr_polygon2){ NULL, 0, NULL, 0 };
    }
    return (sr_polygon2){ path->pts, path->n, path->counts, path->nc };
}

bool sr_path_subpath_closed(const sr_path *path, int i)
{
    return path && i >= 0 && i < path->nc && path->closed[i] != 0;
}

sr_result sr_fill_path(sr_context *ctx, sr_framebuffer *fb, const sr_path *path, sr_rgba color,
                       const sr_fill_desc *desc)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_fill_path: ctx is NULL");
    }
    if (!path) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_fill_path: path is NULL");
    }
    sr_polygon2 poly = sr_path_polygon(path);
    return sr_fill_polygon(ctx, fb, &poly, color, desc);
}

/* ---- stroking ------------------------------------------------------------- */

typedef struct outline {
    sr_context *ctx;
    sr_point2 *pts;
    int n, cap;
    int *counts;
    int nc, ccap;
    bool failed;
} outline;

/* Add one piece, wound with positive signed area (zero-area pieces are
 * dropped), so the nonzero fill of all pieces is their union. */
static void add_piece(outline *o, const sr_point2 *p, int n)
{
    double a2 = 0;
    for (int i = 0; i < n; i++) {
        const sr_point2 *a = &p[i], *b = &p[(i + 1) % n];
        a2 += a->x * b->y - b->x * a->y;
    }
    if (!(a2 != 0) || o->failed) {
        return;
    }
    if (!grow(o->ctx, (void **)&o->pts, &o->cap, o->n + n, sizeof *o->pts) ||
        !grow(o->ctx, (void **)&o->counts, &o->ccap, o->nc + 1, sizeof *o->counts)) {
        o->failed = true;
        return;
    }
    for (int i = 0; i < n; i++) {
        o->pts[o->n + i] = a2 > 0 ? p[i] : p[n - 1 - i];
    }
    o->n += n;
    o->counts[o->nc++] = n;
}

/* Points of a whole circle of radius r within tol: 8 .. 4096. */
static int disc_steps(double r, double tol)
{
    double a = tol >= r ? M_PI / 2 : 2 * acos(1 - tol / r);
    if (!(a > 0)) {
        /* r above 1e16 tolerances: 1 - x rounds to 1 and acos gives 0 (an
         * infinite step count, undefined as an int).  acos(1 - x) =
         * sqrt(2 x) to first order. */
        a = 2 * sqrt(2 * (tol / r));
    }
    double steps = a > 0 ? ceil(2 * M_PI / a) : 4096;
    return steps > 4096 ? 4096 : steps < 8 ? 8 : (int)steps;
}

static void add_disc(outline *o, sr_point2 c, double r, double tol)
{
    int n = disc_steps(r, tol);
    sr_point2 pts[4096];
    for (int i = 0; i < n; i++) {
        double t = 2 * M_PI * i / n;
        /* vertices on a circle of radius r / cos(pi / n): the polygon then
         * contains the disc instead of cutting it */
        double rr = r / cos(M_PI / n);
        pts[i] = (sr_point2){ c.x + rr * cos(t), c.y + rr * sin(t) };
    }
    add_piece(o, pts, n);
}

static sr_point2 pt_add(sr_point2 a, double s, sr_point2 d)
{
    return (sr_point2){ a.x + s * d.x, a.y + s * d.y };
}

static void add_cap(outline *o, sr_point2 p, sr_point2 d /* outward */, double hw,
                    sr_stroke_cap cap, double tol)
{
    if (cap == SR_STROKE_CAP_ROUND) {
        add_disc(o, p, hw, tol);
    } else if (cap == SR_STROKE_CAP_SQUARE) {
        sr_point2 n = { -d.y, d.x };
        sr_point2 q[4] = { pt_add(p, hw, n), pt_add(pt_add(p, hw, n), hw, d),
                           pt_add(pt_add(p, -hw, n), hw, d), pt_add(p, -hw, n) };
        add_piece(o, q, 4);
    }
}

static void add_join(outline *o, sr_point2 p, sr_point2 d0, sr_point2 d1, double hw,
                     const sr_stroke_desc *d, double tol)
{
    double cross = d0.x * d1.y - d0.y * d1.x, dot = d0.x * d1.x + d0.y * d1.y;
    if (fabs(cross) < 1e-12 && dot > 0) {
        return; /* straight on: the segment quads already meet */
    }
    /* The outer side is away from the turn: n = d rotated +90 degrees lies
     * on the side the path turns to when cross > 0. */
    double s = cross > 0 ? -1.0 : 1.0;
    sr_point2 n0 = { -d0.y, d0.x }, n1 = { -d1.y, d1.x };
    sr_point2 a = pt_add(p, s * hw, n0), b = pt_add(p, s * hw, n1);
    if (d->join == SR_STROKE_JOIN_ROUND) {
        /* The sector between the two outer edges only: a whole disc would
         * stand out past the butt end of a segment shorter than hw (the
         * short pieces a dash ends on). */
        double turn = atan2(cross, dot), a0 = atan2(s * n0.y, s * n0.x);
        double step = 2 * M_PI / disc_steps(hw, tol);
        int n = (int)ceil(fabs(turn) / step);
        n = n < 1 ? 1 : n > 2048 ? 2048 : n;
        double rr = hw / cos(fabs(turn) / n / 2);
        sr_point2 q[2051];
        q[0] = p;
        q[1] = a;
        for (int i = 1; i < n; i++) {
            double t = a0 + turn * i / n;
            q[i + 1] = (sr_point2){ p.x + rr * cos(t), p.y + rr * sin(t) };
        }
        q[n + 1] = b;
        add_piece(o, q, n + 2);
        return;
    }
    if (d->join == SR_STROKE_JOIN_MITER) {
        /* miter length / width = 1 / sin(theta / 2), theta the angle between
         * the segments = 1 / cos(phi / 2), phi the turning angle */
        double c = sqrt((1 + dot) / 2);
        if (c > 0 && 1 / c <= d->miter_limit) {
            sr_point2 bis = { n0.x + n1.x, n0.y + n1.y };
            double len = hypot(bis.x, bis.y);
            if (len > 0) {
                sr_point2 m = pt_add(p, s * hw / c / len, bis);
                sr_point2 q[4] = { p, a, m, b };
                add_piece(o, q, 4);
                return;
            }
        }
    }
    sr_point2 t[3] = { p, a, b }; /* bevel */
    add_piece(o, t, 3);
}

static sr_point2 unit(sr_point2 a, sr_point2 b)
{
    double dx = b.x - a.x, dy = b.y - a.y, l = hypot(dx, dy);
    return (sr_point2){ dx / l, dy / l };
}

static void stroke_subpath(outline *o, const sr_point2 *in, int n_in, bool closed,
                           const sr_stroke_desc *d, double tol)
{
    double hw = d->width / 2;
    /* Drop repeated points (zero-length segments have no direction). */
    sr_point2 *p = sr__alloc(o->ctx, (size_t)(n_in > 0 ? n_in : 1) * sizeof *p);
    if (!p) {
        o->failed = true;
        return;
    }
    int n = 0;
    for (int i = 0; i < n_in; i++) {
        if (n == 0 || in[i].x != p[n - 1].x || in[i].y != p[n - 1].y) {
            p[n++] = in[i];
        }
    }
    if (closed && n > 1 && p[n - 1].x == p[0].x && p[n - 1].y == p[0].y) {
        n--;
    }
    if (n == 1) {
        /* A zero-length subpath: round and square caps still draw a dot. */
        if (n_in > 1 || closed) {
            add_cap(o, p[0], (sr_point2){ 1, 0 }, hw, d->cap, tol);
            if (d->cap == SR_STROKE_CAP_SQUARE) {
                add_cap(o, p[0], (sr_point2){ -1, 0 }, hw, d->cap, tol);
            }
        }
        sr__free(o->ctx, p);
        return;
    }
    if (n < 2) {
        sr__free(o->ctx, p);
        return;
    }
    int segs = closed ? n : n - 1;
    for (int i = 0; i < segs; i++) {
        sr_point2 a = p[i], b = p[(i + 1) % n], u = unit(a, b), nn = { -u.y, u.x };
        sr_point2 q[4] = { pt_add(a, hw, nn), pt_add(b, hw, nn), pt_add(b, -hw, nn),
                           pt_add(a, -hw, nn) };
        add_piece(o, q, 4);
    }
    for (int i = closed ? 0 : 1; i < (closed ? n : n - 1); i++) {
        sr_point2 prev = p[(i + n - 1) % n], cur = p[i], next = p[(i + 1) % n];
        add_join(o, cur, unit(prev, cur), unit(cur, next), hw, d, tol);
    }
    if (!closed) {
        sr_point2 u0 = unit(p[1], p[0]), u1 = unit(p[n - 2], p[n - 1]);
        add_cap(o, p[0], u0, hw, d->cap, tol);
        add_cap(o, p[n - 1], u1, hw, d->cap, tol);
    }
    sr__free(o->ctx, p);
}

static sr_result stroke_desc_defaults(sr_context *ctx, const char *fn, const sr_stroke_desc *in,
                                      sr_stroke_desc *out)
{
    *out = in ? *in : (sr_stroke_desc){0};
    if (out->width == 0) {
        out->width = 1;
    }
    if (!(out->width > 0) || !isfinite(out->width)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_stroke_desc.width must be >= 0 (got %g)", fn,
                        out->width);
    }
    if (out->join == SR_STROKE_JOIN_DEFAULT) {
        out->join = SR_STROKE_JOIN_MITER;
    }
    if (out->join < SR_STROKE_JOIN_MITER || out->join > SR_STROKE_JOIN_BEVEL) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_stroke_desc.join %d is invalid", fn,
                        (int)out->join);
    }
    if (out->cap == SR_STROKE_CAP_DEFAULT) {
        out->cap = SR_STROKE_CAP_BUTT;
    }
    if (out->cap < SR_STROKE_CAP_BUTT || out->cap > SR_STROKE_CAP_SQUARE) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_stroke_desc.cap %d is invalid", fn,
                        (int)out->cap);
    }
    if (out->miter_limit == 0) {
        out->miter_limit = 4;
    }
    if (!(out->miter_limit >= 1) || !isfinite(out->miter_limit)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_stroke_desc.miter_limit must be >= 1 (got %g)",
                        fn, out->miter_limit);
    }
    return SR_OK;
}

sr_result sr_make_stroke_outline(sr_context *ctx, const sr_path *path,
                                 const sr_stroke_desc *desc, sr_polygon2 *out)
{
    static const char fn[] = "sr_make_stroke_outline";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_make_stroke_outline: ctx is NULL");
    }
    if (!path || !out) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %s is NULL", fn, path ? "out" : "path");
    }
    *out = (sr_polygon2){ NULL, 0, NULL, 0 };
    sr_stroke_desc d;
    sr_result r = stroke_desc_defaults(ctx, fn, desc, &d);
    if (r != SR_OK) {
        return r;
    }
    outline o = { .ctx = ctx };
    int start = 0;
    for (int c = 0; c < path->nc; c++) {
        stroke_subpath(&o, path->pts + start, path->counts[c], path->closed[c] != 0, &d,
                       path->tolerance);
        start += path->counts[c];
    }
    if (o.failed) {
        sr__free(ctx, o.pts);
        sr__free(ctx, o.counts);
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "%s: no memory for the outline", fn);
    }
    *out = (sr_polygon2){ o.pts, o.n, o.counts, o.nc };
    sr__ok(ctx);
    return SR_OK;
}

void sr_destroy_stroke_outline(sr_context *ctx, sr_polygon2 *polygon)
{
    if (!ctx || !polygon) {
        return;
    }
    sr__free(ctx, (void *)polygon->points);
    sr__free(ctx, (void *)polygon->contour_counts);
    *polygon = (sr_polygon2){ NULL, 0, NULL, 0 };
}

sr_result sr_stroke_path(sr_context *ctx, sr_framebuffer *fb, const sr_path *path,
                         sr_rgba color, const sr_stroke_desc *desc)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_stroke_path: ctx is NULL");
    }
    if (!fb) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_stroke_path: fb is NULL");
    }
    sr_polygon2 poly;
    sr_result r = sr_make_stroke_outline(ctx, path, desc, &poly);
    if (r != SR_OK) {
        return r;
    }
    const sr_stroke_desc *d = desc;
    sr_fill_desc f = { SR_NONZERO, d ? d->antialias : SR_AA_DEFAULT, d ? d->samples : 0,
                       d ? d->linear_light : false };
    r = sr_fill_polygon(ctx, fb, &poly, color, &f);
    sr_destroy_stroke_outline(ctx, &poly);
    return r;
}
