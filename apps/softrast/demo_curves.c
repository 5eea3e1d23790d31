/* demo_curves.c - `softrast demo curves`: the curve and stroke tools of
 * the 2D toolkit, magnified.  Midpoint circles (exact at the octant
 * joins for any centre and radius) and filled ellipses; a cubic Bezier
 * flattened by forward differencing (its control polygon, the chord
 * points, and the stroked result); stroke joins (miter, round, bevel) and
 * caps (butt, round, square) with the centre line drawn over them; and an
 * implicit curve (a superellipse) antialiased from F and its gradient. */
#include "cli.h"
#include "demo.h"
#include "demo2d.h"

#include <math.h>

#define PANEL 48

static const sr_rgba BG = { 0.08f, 0.09f, 0.11f, 1 };
static const sr_rgba INK = { 0.98f, 0.86f, 0.45f, 1 };
static const sr_rgba INK2 = { 0.45f, 0.75f, 0.5f, 1 };
static const sr_rgba LINE = { 0.2f, 0.65f, 1.0f, 1 };
static const sr_rgba FAINT = { 0.6f, 0.6f, 0.65f, 0.7f };

static double superellipse(void *user, double x, double y, double grad[2])
{
    (void)user;
    double u = (x - 24) / 19, v = (y - 24) / 13;
    if (grad) {
        grad[0] = 4 * u * u * u / 19;
        grad[1] = 4 * v * v * v / 13;
    }
    return u * u * u * u + v * v * v * v - 1;
}

static sr_path *polyline(sr_context *ctx, const sr_point2 *p, int n)
{
    sr_path *path = NULL;
    if (sr_make_path(ctx, 0.05, &path) != SR_OK) {
        return NULL;
    }
    sr_path_move_to(path, p[0].x, p[0].y);
    for (int i = 1; i < n; i++) {
        sr_path_line_to(path, p[i].x, p[i].y);
    }
    return path;
}

int demo_curves(sr_context *ctx, const demo_args *args, sr_framebuffer **out)
{
    demo2d d;
    int scale = args->scale > 0 ? args->scale : 5;
    int status = demo2d_begin(&d, ctx, "curves", 3, 2, PANEL, PANEL, scale);
    if (status != EXIT_OK) {
        return status;
    }
    sr_result r = SR_OK;

    /* 0: midpoint circles, concentric about a point off the pixel grid. */
    demo2d_clear_panel(&d, BG);
    for (int k = 0; k < 5 && r == SR_OK; k++) {
        r = sr_draw_circle(ctx, d.panel, 23.7, 24.2, 4.3 + 4.6 * k, k % 2 ? INK2 : INK, false);
    }
    if (r != SR_OK) {
        return demo2d_fail(&d);
    }
    demo2d_blit(&d, 0, "midpoint circles");

    /* 1: filled ellipses, and their outlines. */
    demo2d_clear_panel(&d, BG);
    r = sr_draw_ellipse(ctx, d.panel, 24.5, 14.5, 20, 9, INK, true);
    if (r == SR_OK) {
        r = sr_draw_ellipse(ctx, d.panel, 17.2, 33.6, 12.4, 11.1, INK2, true);
    }
    if (r == SR_OK) {
        r = sr_draw_ellipse(ctx, d.panel, 36, 33, 7, 13.5, INK, false);
    }
    if (r != SR_OK) {
        return demo2d_fail(&d);
    }
    demo2d_blit(&d, 1, "midpoint ellipses");

    /* 2: a cubic Bezier by forward differences, coarse tolerance so the
     * chords show. */
    sr_point2 cp[4] = { { 4, 42 }, { 8, 2 }, { 42, 6 }, { 44, 40 } };
    sr_point2 flat[65];
    int n = 0;
    flat[0] = cp[0];
    r = sr_flatten_cubic(ctx, cp[0], cp[1], cp[2], cp[3], 0.4, flat + 1, 64, &n);
    if (r != SR_OK) {
        return demo2d_fail(&d);
    }
    demo2d_clear_panel(&d, BG);
    sr_path *curve = polyline(ctx, flat, n + 1);
    if (!curve) {
        return demo2d_fail(&d);
    }
    r = sr_stroke_path(ctx, d.panel, curve, INK, &(sr_stroke_desc){ .width = 1.2 });
    sr_destroy_path(ctx, curve);
    if (r != SR_OK) {
        return demo2d_fail(&d);
    }
    demo2d_blit(&d, 2, "cubic, forward diff.");
    demo2d_outline(&d, 2, cp, 4, false, FAINT, 1.0);
    for (int i = 0; i < 4; i++) {
        demo2d_dot(&d, 2, cp[i], 3.0, FAINT);
    }
    demo2d_outline(&d, 2, flat, n + 1, false, LINE, 1.5);
    for (int i = 0; i <= n; i++) {
        demo2d_dot(&d, 2, flat[i], 2.5, LINE);
    }

    /* 3: joins (miter, round, bevel) on the same zigzag. */
    demo2d_clear_panel(&d, BG);
    const sr_stroke_join joins[3] = { SR_STROKE_JOIN_MITER, SR_STROKE_JOIN_ROUND,
                                      SR_STROKE_JOIN_BEVEL };
    sr_point2 zig[3][4];
    for (int j = 0; j < 3; j++) {
        double y = 10 + 14 * j;
        sr_point2 z[4] = { { 5, y + 6 }, { 17, y - 4 }, { 29, y + 6 }, { 43, y - 3 } };
        for (int i = 0; i < 4; i++) {
            zig[j][i] = z[i];
        }
        sr_path *p = polyline(ctx, z, 4);
        if (!p) {
            return demo2d_fail(&d);
        }
        r = sr_stroke_path(ctx, d.panel, p, j % 2 ? INK2 : INK,
                           &(sr_stroke_desc){ .width = 5, .join = joins[j],
                                              .antialias = SR_AA_AREA });
        sr_destroy_path(ctx, p);
        if (r != SR_OK) {
            return demo2d_fail(&d);
        }
    }
    demo2d_blit(&d, 3, "miter, round, bevel");
    for (int j = 0; j < 3; j++) {
        demo2d_outline(&d, 3, zig[j], 4, false, LINE, 1.5);
    }

    /* 4: caps (butt, round, square). */
    demo2d_clear_panel(&d, BG);
    const sr_stroke_cap caps[3] = { SR_STROKE_CAP_BUTT, SR_STROKE_CAP_ROUND,
                                    SR_STROKE_CAP_SQUARE };
    sr_point2 seg[3][2];
    for (int j = 0; j < 3; j++) {
        double y = 9 + 13 * j;
        sr_point2 s[2] = { { 12, y }, { 35, y + 6 } };
        seg[j][0] = s[0];
        seg[j][1] = s[1];
        sr_path *p = polyline(ctx, s, 2);
        if (!p) {
            return demo2d_fail(&d);
        }
        r = sr_stroke_path(ctx, d.panel, p, j % 2 ? INK2 : INK,
                           &(sr_stroke_desc){ .width = 7, .cap = caps[j],
                                              .antialias = SR_AA_AREA });
        sr_destroy_path(ctx, p);
        if (r != SR_OK) {
            return demo2d_fail(&d);
        }
    }
    demo2d_blit(&d, 4, "butt, round, square");
    for (int j = 0; j < 3; j++) {
        demo2d_outline(&d, 4, seg[j], 2, false, LINE, 1.5);
        demo2d_dot(&d, 4, seg[j][0], 2.5, LINE);
        demo2d_dot(&d, 4, seg[j][1], 2.5, LINE);
    }

    /* 5: an implicit region F < 0, antialiased by F / |grad F|. */
    demo2d_clear_panel(&d, BG);
    r = sr_fill_implicit(ctx, d.panel, &(sr_implicit_desc){ .f = superellipse, .antialias = true },
                         INK);
    if (r != SR_OK) {
        return demo2d_fail(&d);
    }
    demo2d_blit(&d, 5, "implicit F<0, AA");
    return demo2d_finish(&d, out);
}
