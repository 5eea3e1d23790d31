/* polyclip.c - draw2d stage: Sutherland-Hodgman polygon clipping against
 * a rectangle or a convex window.  Consumes a polygon (sr_point2 list),
 * produces the clipped polygon and, on request, the polygon after each
 * clip edge.  Pure computation on the caller's thread; the framebuffer is
 * not involved. */
#include "context.h"
#include "draw2d/polyfill.h"

#include <math.h>
#include <string.h>

/* One clip edge as a half-plane: inside where dist(p) >= 0.  For the
 * rectangle the distance is an exact coordinate difference. */
typedef struct half_plane {
    int axis;           /* 0: x, 1: y, -1: general line */
    double bound;       /* axis: the coordinate of the edge */
    double sign;        /* axis: +1 keeps >= bound, -1 keeps <= bound */
    sr_point2 a, b;     /* general: the edge a -> b; orient * cross >= 0 inside */
    double orient;
} half_plane;

static double hp_dist(const half_plane *h, sr_point2 p)
{
    if (h->axis >= 0) {
        return h->sign * ((h->axis ? p.y : p.x) - h->bound);
    }
    return h->orient * ((h->b.x - h->a.x) * (p.y - h->a.y) - (h->b.y - h->a.y) * (p.x - h->a.x));
}

/* The point where segment inside -> outside crosses the clip edge, from
 * the inside point (so shared edges clip identically in either direction). */
static sr_point2 hp_intersect(const half_plane *h, sr_point2 in, double d_in, sr_point2 out,
                              double d_out)
{
    double t = d_in / (d_in - d_out);
    sr_point2 p = { in.x + t * (out.x - in.x), in.y + t * (out.y - in.y) };
    if (h->axis == 0) {
        p.x = h->bound;
    } else if (h->axis == 1) {
        p.y = h->bound;
    }
    return p;
}

/* One Sutherland-Hodgman stage: the four cases for each edge (s, p). */
static int clip_stage(const half_plane *h, const sr_point2 *in, int n, sr_point2 *out)
{
    int m = 0;
    if (n == 0) {
        return 0;
    }
    sr_point2 s = in[n - 1];
    double ds = hp_dist(h, s);
    for (int i = 0; i < n; i++) {
        sr_point2 p = in[i];
        double dp = hp_dist(h, p);
        bool s_in = ds >= 0, p_in = dp >= 0;
        if (s_in && p_in) {                 /* case 1: inside, inside */
            out[m++] = p;
        } else if (s_in) {                  /* case 2: inside, outside */
            out[m++] = hp_intersect(h, s, ds, p, dp);
        } else if (p_in) {                  /* case 4: outside, inside */
            out[m++] = hp_intersect(h, p, dp, s, ds);
            out[m++] = p;
        }                                   /* case 3: outside, outside: nothing */
        s = p;
        ds = dp;
    }
    return m;
}

#define MAX_CLIP_POINTS (1 << 26)

bool sr__clip_reserve(sr_context *ctx, sr_point2 **buf, long long *cap, long long need)
{
    if (need <= *cap) {
        return true;
    }
    sr__free(ctx, *buf);
    *buf = sr__alloc(ctx, (size_t)need * sizeof **buf);
    *cap = *buf ? need : 0;
    return *buf != NULL;
}

/* One stage from s->a (n points) through s->b, which has room for need
 * points made first; the result is s->a again.  False when out of memory. */
static bool stage_swap(sr_context *ctx, const half_plane *h, sr__clip_scratch *s, int *n,
                       long long need)
{
    if (!sr__clip_reserve(ctx, &s->b, &s->cap_b, need)) {
        return false;
    }
    *n = clip_stage(h, s->a, *n, s->b);
    sr__clip_scratch t = *s;
    *s = (sr__clip_scratch){ t.b, t.a, t.cap_b, t.cap_a };
    return true;
}

bool sr__clip_axis_stage(sr_context *ctx, sr__clip_scratch *s, int axis, double bound,
                         double sign, int *n)
{
    half_plane h = { .axis = axis, .bound = bound, .sign = sign };
    /* One point per edge kept or leaving, two per edge entering; entries
     * pair with exits, so at most 3/2 n. */
    return stage_swap(ctx, &h, s, n, 3LL * *n / 2 + 2);
}

static sr_result clip_run(sr_context *ctx, const char *fn, const sr_point2 *in, int count,
                          const half_plane *planes, int n_planes,
                          const sr_polygon_clip_desc *desc, sr_point2 *out, int capacity,
                          int *out_count)
{
    sr__clip_scratch s = { 0 };
    sr_result r = SR_OK;
    if (!sr__clip_reserve(ctx, &s.a, &s.cap_a, count + 1LL)) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "%s: no memory for %d points", fn, count);
    }
    if (count) {
        memcpy(s.a, in, (size_t)count * sizeof *s.a);
    }
    int n = count;
    for (int k = 0; k < n_planes && r == SR_OK; k++) {
        /* A stage emits at most 2 points per input edge. */
        long long need = 2LL * n + 1;
        if (need > MAX_CLIP_POINTS) {
            r = sr__fail(ctx, SR_TOO_LARGE, "%s: clipped polygon exceeds %d points", fn,
                         MAX_CLIP_POINTS);
            break;
        }
        if (!stage_swap(ctx, &planes[k], &s, &n, need)) {
            r = sr__fail(ctx, SR_OUT_OF_MEMORY, "%s: no memory for %lld points", fn, need);
            break;
        }
        if (desc && desc->on_stage) {
            desc->on_stage(desc->user, k, s.a, n);
        }
    }
    if (r == SR_OK) {
        *out_count = n;
        if (n > capacity) {
            r = sr__fail(ctx, SR_TOO_LARGE,
                         "%s: the clipped polygon has %d points, capacity is %d", fn, n, capacity);
        } else {
            if (n) {
                memcpy(out, s.a, (size_t)n * sizeof *out);
            }
            sr__ok(ctx);
        }
    }
    sr__free(ctx, s.a);
    sr__free(ctx, s.b);
    return r;
}

static sr_result check_polygon(sr_context *ctx, const char *fn, const char *what,
                               const sr_point2 *p, int n)
{
    if (n < 0 || (n > 0 && !p)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %s is NULL or its count < 0", fn, what);
    }
    if (n > (1 << 24)) {
        return sr__fail(ctx, SR_TOO_LARGE, "%s: %s has more than 2^24 points", fn, what);
    }
    for (int i = 0; i < n; i++) {
        if (!isfinite(p[i].x) || !isfinite(p[i].y)) {
            return sr__fail(ctx, SR_INVALID_ARG, "%s: %s[%d] is not finite", fn, what, i);
        }
    }
    return SR_OK;
}

static sr_result check_out(sr_context *ctx, const char *fn, sr_point2 *out, int capacity,
                           int *out_count)
{
    if (!out_count) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: out_count is NULL", fn);
    }
    *out_count = 0;
    if (capacity < 0 || (capacity > 0 && !out)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: out is NULL or capacity < 0", fn);
    }
    return SR_OK;
}

sr_result sr_clip_polygon_rect(sr_context *ctx, const sr_point2 *in, int count, double xmin,
                               double ymin, double xmax, double ymax,
                               const sr_polygon_clip_desc *desc, sr_point2 *out, int capacity,
                               int *out_count)
{
    static const char fn[] = "sr_clip_polygon_rect";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_clip_polygon_rect: ctx is NULL");
    }
    sr_result r = check_out(ctx, fn, out, capacity, out_count);
    if (r == SR_OK) {
        r = check_polygon(ctx, fn, "in", in, count);
    }
    if (r != SR_OK) {
        return r;
    }
    if (!isfinite(xmin) || !isfinite(ymin) || !isfinite(xmax) || !isfinite(ymax) ||
        !(xmin <= xmax) || !(ymin <= ymax)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: the rectangle needs finite xmin <= xmax and "
                        "ymin <= ymax", fn);
    }
    /* The textbook order: left, bottom, right, top (bottom = y max, y down). */
    half_plane planes[4] = {
        { .axis = 0, .bound = xmin, .sign = +1 },
        { .axis = 1, .bound = ymax, .sign = -1 },
        { .axis = 0, .bound = xmax, .sign = -1 },
        { .axis = 1, .bound = ymin, .sign = +1 },
    };
    return clip_run(ctx, fn, in, count, planes, 4, desc, out, capacity, out_count);
}

sr_result sr_clip_polygon_convex(sr_context *ctx, const sr_point2 *in, int count,
                                 const sr_point2 *window, int window_count,
                                 const sr_polygon_clip_desc *desc, sr_point2 *out, int capacity,
                                 int *out_count)
{
    static const char fn[] = "sr_clip_polygon_convex";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_clip_polygon_convex: ctx is NULL");
    }
    sr_result r = check_out(ctx, fn, out, capacity, out_count);
    if (r == SR_OK) {
        r = check_polygon(ctx, fn, "in", in, count);
    }
    if (r == SR_OK) {
        r = check_polygon(ctx, fn, "window", window, window_count);
    }
    if (r != SR_OK) {
        return r;
    }
    if (window_count < 3) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: the window needs at least 3 points", fn);
    }
    if (window_count > 4096) {
        return sr__fail(ctx, SR_TOO_LARGE, "%s: the window has more than 4096 edges", fn);
    }
    /* Orientation from the signed area; convex means no turn against it. */
    double area2 = 0;
    for (int i = 0; i < window_count; i++) {
        sr_point2 a = window[i], b = window[(i + 1) % window_count];
        area2 += a.x * b.y - b.x * a.y;
    }
    if (area2 == 0) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: the window has zero area", fn);
    }
    double orient = area2 > 0 ? 1.0 : -1.0;
    for (int i = 0; i < window_count; i++) {
        sr_point2 a = window[i], b = window[(i + 1) % window_count];
        sr_point2 c = window[(i + 2) % window_count];
        double turn = (b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x);
        if (turn * orient < 0) {
            return sr__fail(ctx, SR_INVALID_ARG, "%s: the window is not convex at point %d", fn,
                            (i + 1) % window_count);
        }
    }
    half_plane *planes = sr__alloc(ctx, (size_t)window_count * sizeof *planes);
    if (!planes) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "%s: no memory", fn);
    }
    for (int i = 0; i < window_count; i++) {
        planes[i] = (half_plane){ .axis = -1, .a = window[i], .b = window[(i + 1) % window_count],
                                  .orient = orient };
    }
    r = clip_run(ctx, fn, in, count, planes, window_count, desc, out, capacity, out_count);
    sr__free(ctx, planes);
    return r;
}
