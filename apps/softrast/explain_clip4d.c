/* explain_clip4d.c - `softrast explain clip4d`: a triangle clipped in
 * homogeneous clip space, before the perspective divide, against the six
 * planes of the view volume -w <= x, y, z <= w.  Each plane is a
 * half-space d(c) >= 0 that is linear in the 4D point c = (x, y, z, w):
 * near w + z, far w - z, left w + x, right w - x, bottom w + y, top w - y.
 * Sutherland-Hodgman clips the polygon against one plane after another;
 * a new vertex is I = in + t (out - in) with t = d_in / (d_in - d_out),
 * computed in 4D, where the plane is flat (after the divide a point
 * behind the eye lands on the wrong side: its w is negative).  Near and
 * far first: together they give w >= 0, so every polygon after them can
 * be projected.  The result is divided by w and mapped onto the viewport
 * (NDC -1..1 across it), fanned into triangles and covered by the edge
 * functions with the top-left rule, as the pipeline draws it. */
#include "explain.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define MAX_VERTS 16   /* a triangle gains at most one vertex per plane */

typedef struct vec4 { double v[4]; } vec4;

static const char *const PLANE_NAME[6] = { "near", "far", "left", "right", "bottom", "top" };
static const char *const PLANE_EQ[6] = { "w + z", "w - z", "w + x", "w - x", "w + y", "w - y" };
static const sr_rgba OUTSIDE = { 0.93f, 0.88f, 0.88f, 1 };
static const sr_rgba BEFORE = { 0.62f, 0.64f, 0.68f, 1 };

static double dist(int plane, const vec4 *c)
{
    double s = plane % 2 ? -1 : 1;
    return c->v[3] + s * c->v[plane < 2 ? 2 : plane < 4 ? 0 : 1];
}

/* The viewport: the grid less a fifth on each side, so that what the
 * side planes cut away stays in sight (the test draws with the same). */
static void viewport(const ex_canvas *c, double vp[4])
{
    vp[0] = c->grid_w / 5;
    vp[1] = c->grid_h / 5;
    vp[2] = c->grid_w - 2 * (c->grid_w / 5);
    vp[3] = c->grid_h - 2 * (c->grid_h / 5);
}

/* The divide and the viewport: NDC -1..1 across it, y up. */
static sr_point2 project(const ex_canvas *c, const vec4 *p)
{
    double w = p->v[3], vp[4];
    viewport(c, vp);
    return (sr_point2){ vp[0] + vp[2] * 0.5 * (1 + p->v[0] / w),
                        vp[1] + vp[3] * 0.5 * (1 - p->v[1] / w) };
}

static void draw_viewport(ex_canvas *c)
{
    double vp[4];
    viewport(c, vp);
    sr_point2 r[4] = { { vp[0], vp[1] }, { vp[0] + vp[2], vp[1] }, { vp[0] + vp[2], vp[1] + vp[3] },
                       { vp[0], vp[1] + vp[3] } };
    ex_outline(c, r, 4, true, EX_EDGE, 1);
}

/* One Sutherland-Hodgman stage; the new vertices' indices go to made[]. */
static int clip_plane(int plane, const vec4 *in, int n, vec4 *out, int *made, int *nmade)
{
    int m = 0;
    *nmade = 0;
    for (int i = 0; i < n; i++) {
        const vec4 *s = &in[(i + n - 1) % n], *p = &in[i];
        double ds = dist(plane, s), dp = dist(plane, p);
        if ((ds >= 0) != (dp >= 0)) {
            const vec4 *a = ds >= 0 ? s : p, *b = ds >= 0 ? p : s;   /* from the inside one */
            double da = ds >= 0 ? ds : dp, db = ds >= 0 ? dp : ds;
            double t = da / (da - db);
            for (int k = 0; k < 4; k++) {
                out[m].v[k] = a->v[k] + t * (b->v[k] - a->v[k]);
            }
            made[(*nmade)++] = m++;
        }
        if (dp >= 0) {
            out[m++] = *p;
        }
    }
    return m;
}

static bool projectable(const vec4 *p, int n)
{
    for (int i = 0; i < n; i++) {
        if (!(p[i].v[3] > 0)) {
            return false;
        }
    }
    return true;
}

/* Whether the point is near enough the grid to draw (a w near 0 sends
 * it towards infinity). */
static bool drawable(const ex_canvas *c, sr_point2 q)
{
    return fabs(q.x) < 16 * c->grid_w + 64 && fabs(q.y) < 16 * c->grid_h + 64;
}

static void outline(ex_canvas *c, const vec4 *p, int n, sr_rgba color, double width)
{
    sr_point2 q[MAX_VERTS];
    for (int i = 0; i < n; i++) {
        q[i] = project(c, &p[i]);
        if (!drawable(c, q[i])) {
            return;
        }
    }
    ex_outline(c, q, n, true, color, width);
}

/* The outside of a side plane, shaded on the grid (its edge: NDC +-1). */
static void shade_outside(ex_canvas *c, int plane)
{
    double vp[4];
    viewport(c, vp);
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            double nx = (x + 0.5 - vp[0]) / vp[2] * 2 - 1, ny = 1 - (y + 0.5 - vp[1]) / vp[3] * 2;
            double v = plane < 4 ? nx : ny;
            bool out = plane % 2 ? v > 1 : v < -1;
            if (out) {
                ex_cell(c, x, y, OUTSIDE);
            }
        }
    }
}

static int fmt_vertices(char *buf, size_t size, int plane, const vec4 *p, int n)
{
    int len = 0;
    for (int i = 0; i < n && len < (int)size; i++) {
        double d = dist(plane, &p[i]);
        len += snprintf(buf + len, size - (size_t)len, "%s%.2f%s", i ? ", " : "", d,
                        d >= 0 ? "" : " out");
    }
    return len;
}

sr_result explain_clip4d(ex_canvas *c, const ex_primitive *prim)
{
    vec4 poly[MAX_VERTS], next[MAX_VERTS];
    int n = 3;
    for (int i = 0; i < 3; i++) {
        poly[i] = (vec4){ { prim->clip[i][0], prim->clip[i][1], prim->clip[i][2],
                            prim->clip[i][3] } };
    }
    char cap[1200];

    ex_begin(c);
    draw_viewport(c);
    bool naive = projectable(poly, 3);
    int behind = 0;
    for (int i = 0; i < 3; i++) {
        behind += poly[i].v[3] <= 0;
    }
    if (behind < 3) {
        /* the divide applied to every vertex, as if there were no clipping */
        vec4 shown[3];
        for (int i = 0; i < 3; i++) {
            shown[i] = poly[i];
            shown[i].v[3] = poly[i].v[3] != 0 ? poly[i].v[3] : 1e-9;
        }
        outline(c, shown, 3, naive ? EX_INK : EX_BAD, 2);
        for (int i = 0; i < 3; i++) {
            char label[48];
            snprintf(label, sizeof label, "V%d w=%g", i, poly[i].v[3]);
            if (drawable(c, project(c, &shown[i]))) {
                ex_label(c, project(c, &shown[i]), label, EX_EDGE);
            }
        }
    }
    snprintf(cap, sizeof cap,
             "1. A triangle in clip space, V0 = (%g, %g, %g, %g), V1 = (%g, %g, %g, %g), V2 = (%g, "
             "%g, %g, %g). The view volume is -w <= x, y, z <= w: after the divide, x/w and y/w in "
             "-1..1 fill the viewport. "
             "(The frame: the viewport.) %s",
             poly[0].v[0], poly[0].v[1], poly[0].v[2], poly[0].v[3], poly[1].v[0], poly[1].v[1],
             poly[1].v[2], poly[1].v[3], poly[2].v[0], poly[2].v[1], poly[2].v[2], poly[2].v[3],
             naive ? "Every w > 0: divided, it lands as drawn."
                   : "Some w <= 0: divided without clipping (red), such a vertex lands on the "
                     "wrong side, its sign lost. So clip first, in 4D.");
    ex_end(c, cap);

    for (int plane = 0; plane < 6 && n > 0; plane++) {
        int made[MAX_VERTS], nmade;
        char ds[300];
        fmt_vertices(ds, sizeof ds, plane, poly, n);
        int m = clip_plane(plane, poly, n, next, made, &nmade);
        ex_begin(c);
        if (plane >= 2) {
            shade_outside(c, plane);
        }
        draw_viewport(c);
        if (projectable(poly, n)) {
            outline(c, poly, n, BEFORE, 1.5);
        }
        bool shown = m > 0 && projectable(next, m);
        if (shown) {
            outline(c, next, m, EX_INK, 2.5);
            for (int k = 0; k < nmade; k++) {
                if (drawable(c, project(c, &next[made[k]]))) {
                    ex_dot(c, project(c, &next[made[k]]), 5, EX_HILITE);
                }
            }
        }
        snprintf(cap, sizeof cap,
                 "%d. Clip against %s, %s >= 0. Its value at the %d vertices: %s. %d intersection%s "
                 "I = in + t (out - in), t = d_in / (d_in - d_out), in 4D (pink); %d vertices "
                 "left.%s%s",
                 c->frame_count + 1, PLANE_NAME[plane], PLANE_EQ[plane], n, ds, nmade,
                 nmade == 1 ? "" : "s", m,
                 plane < 2 ? " Near and far bound z: their planes do not show on the grid." : "",
                 m > 0 && !shown ? " (Some w still <= 0: not drawn yet.)" : "");
        ex_end(c, cap);
        memcpy(poly, next, sizeof next[0] * (size_t)m);
        n = m;
    }

    /* the pixels: the clipped polygon divided, fanned, covered */
    ex_begin(c);
    int covered = 0;
    for (int k = 1; k + 1 < n; k++) {
        ex_primitive tri = { .kind = EX_TRIANGLE, .count = 3 };
        tri.pts[0] = project(c, &poly[0]);
        tri.pts[1] = project(c, &poly[k]);
        tri.pts[2] = project(c, &poly[k + 1]);
        if (!drawable(c, tri.pts[0]) || !drawable(c, tri.pts[1]) || !drawable(c, tri.pts[2])) {
            continue;   /* w = 0 at the eye: x = y = 0 there, no area on the grid */
        }
        ex_tri t;
        ex_tri_setup(&t, &tri);
        if (t.area2 == 0) {
            continue;
        }
        for (int y = 0; y < c->grid_h; y++) {
            for (int x = 0; x < c->grid_w; x++) {
                if (ex_tri_covers(&t, (int64_t)x * 256 + 128, (int64_t)y * 256 + 128)) {
                    ex_cell(c, x, y, EX_INK);
                    covered++;
                }
            }
        }
    }
    if (n > 0) {
        outline(c, poly, n, EX_EDGE, 1);
    }
    /* near and far leave w >= |z|: w = 0 only where x = y = z = 0 too,
     * at the eye, and a triangle through it covers nothing */
    bool at_eye = false;
    for (int k = 0; k < n; k++) {
        at_eye |= !(poly[k].v[3] > 0);
    }
    int fans = n > 2 ? n - 2 : 0;
    char what[400];
    if (n < 3) {
        snprintf(what, sizeof what, "Nothing with area is left after clipping (%d vertices)", n);
    } else {
        snprintf(what, sizeof what,
                 "The clipped polygon (%d vertices, all w %s) divided by w, mapped onto the grid "
                 "and fanned into %d triangle%s, each covered by its edge functions with the "
                 "top-left rule", n, at_eye ? ">= 0; w = 0 only at the eye, where nothing is "
                 "covered" : "> 0", fans, fans == 1 ? "" : "s");
    }
    snprintf(cap, sizeof cap,
             "%d. %s: %d pixel%s, what sr_draw draws for the triangle (which clips only near, "
             "far and w > 0 in clip space and trims x and y exactly to the viewport as it "
             "rasterizes).",
             c->frame_count + 1, what, covered, covered == 1 ? "" : "s");
    ex_end(c, cap);
    return c->error;
}
