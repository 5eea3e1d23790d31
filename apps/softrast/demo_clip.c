/* demo_clip.c - `softrast demo clip`: Sutherland-Hodgman polygon
 * clipping, one clip edge at a time, magnified.  A concave star sticks out
 * of every side of the clip rectangle; each panel shows the polygon after
 * clipping against one more edge (left, bottom, right, top), filled by the
 * edge-table fill, with its vertices.  The edge just used is drawn red and
 * the polygon before that stage faintly.  The last panel clips the same
 * star against a convex hexagon.
 *
 * Under them, the same algorithm in 3D: triangles clipped against the
 * planes of the view volume in homogeneous clip space (demo_clip3d.c). */
#include "cli.h"
#include "demo.h"
#include "demo2d.h"
#include "demo3d.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define PANEL_W 48
#define PANEL_H 36
#define MAX_PTS 64

static const sr_rgba BG = { 0.08f, 0.09f, 0.11f, 1 };
static const sr_rgba INK = { 0.45f, 0.75f, 0.5f, 1 };
static const sr_rgba LINE = { 0.98f, 0.86f, 0.45f, 1 };
static const sr_rgba FAINT = { 0.6f, 0.6f, 0.65f, 0.45f };
static const sr_rgba WINDOW = { 0.55f, 0.6f, 0.7f, 1 };
static const sr_rgba ACTIVE = { 0.95f, 0.25f, 0.2f, 1 };

typedef struct stages {
    sr_point2 pts[8][MAX_PTS];
    int count[8];
    int n;
} stages;

static void keep_stage(void *user, int edge, const sr_point2 *poly, int count)
{
    stages *s = user;
    if (edge < 8 && count <= MAX_PTS) {
        memcpy(s->pts[edge], poly, (size_t)count * sizeof *poly);
        s->count[edge] = count;
        s->n = edge + 1;
    }
}

static int star(sr_point2 *p)
{
    for (int k = 0; k < 12; k++) {
        double a = 0.3 + k * M_PI / 6, r = k % 2 ? 7.5 : 16.5;
        p[k] = (sr_point2){ 24.6 + r * cos(a), 17.7 + r * sin(a) };
    }
    return 12;
}

/* The polygon's pixels in the panel (edge-table fill, nonzero). */
static void draw_polygon(demo2d *d, const sr_point2 *p, int n)
{
    sr_fill_polygon(d->ctx, d->panel, &(sr_polygon2){ p, n, NULL, 0 }, INK, NULL);
}

static void overlay_polygon(demo2d *d, int cell, const sr_point2 *p, int n)
{
    demo2d_outline(d, cell, p, n, true, LINE, 2.0);
    for (int i = 0; i < n; i++) {
        demo2d_dot(d, cell, p[i], 3.5, LINE);
    }
}

static int clip2d_section(sr_context *ctx, const demo_args *args, sr_framebuffer **out)
{
    demo2d d;
    int scale = args->scale > 0 ? args->scale : 6;
    int status = demo2d_begin(&d, ctx, "clip", 3, 2, PANEL_W, PANEL_H, scale);
    if (status != EXIT_OK) {
        return status;
    }
    sr_point2 subject[12], result[MAX_PTS];
    int n = star(subject), m = 0;
    const double x0 = 11, y0 = 8, x1 = 38, y1 = 27;
    sr_point2 rect[4] = { { x0, y0 }, { x1, y0 }, { x1, y1 }, { x0, y1 } };
    stages st = { .n = 0 };
    if (sr_clip_polygon_rect(ctx, subject, n, x0, y0, x1, y1,
                             &(sr_polygon_clip_desc){ keep_stage, &st }, result, MAX_PTS,
                             &m) != SR_OK || st.n != 4) {
        return demo2d_fail(&d);
    }
    /* The clip edges in the order used: left, bottom, right, top. */
    const char *names[4] = { "left", "bottom", "right", "top" };
    sr_point2 edges[4][2] = { { { x0, 0 }, { x0, PANEL_H } }, { { 0, y1 }, { PANEL_W, y1 } },
                              { { x1, 0 }, { x1, PANEL_H } }, { { 0, y0 }, { PANEL_W, y0 } } };
    char label[64];
    for (int cell = 0; cell < 5; cell++) {
        const sr_point2 *p = cell == 0 ? subject : st.pts[cell - 1];
        int count = cell == 0 ? n : st.count[cell - 1];
        demo2d_clear_panel(&d, BG);
        draw_polygon(&d, p, count);
        if (cell == 0) {
            snprintf(label, sizeof label, "input: %d vertices", count);
        } else {
            snprintf(label, sizeof label, "clip %s: %d", names[cell - 1], count);
        }
        demo2d_blit(&d, cell, label);
        demo2d_outline(&d, cell, rect, 4, true, WINDOW, 1.5);
        if (cell > 0) {
            const sr_point2 *prev = cell == 1 ? subject : st.pts[cell - 2];
            int prev_n = cell == 1 ? n : st.count[cell - 2];
            demo2d_outline(&d, cell, prev, prev_n, true, FAINT, 1.5);
            demo2d_outline(&d, cell, edges[cell - 1], 2, false, ACTIVE, 3.0);
        }
        overlay_polygon(&d, cell, p, count);
    }
    /* A convex window: a hexagon, its edges in order. */
    sr_point2 hex[6], hres[MAX_PTS];
    for (int k = 0; k < 6; k++) {
        double a = k * M_PI / 3;
        hex[k] = (sr_point2){ 24.5 + 12.5 * cos(a), 17.7 + 11.5 * sin(a) };
    }
    int hm = 0;
    if (sr_clip_polygon_convex(ctx, subject, n, hex, 6, NULL, hres, MAX_PTS, &hm) != SR_OK) {
        return demo2d_fail(&d);
    }
    demo2d_clear_panel(&d, BG);
    draw_polygon(&d, hres, hm);
    snprintf(label, sizeof label, "convex window: %d", hm);
    demo2d_blit(&d, 5, label);
    demo2d_outline(&d, 5, subject, n, true, FAINT, 1.5);
    demo2d_outline(&d, 5, hex, 6, true, WINDOW, 1.5);
    overlay_polygon(&d, 5, hres, hm);
    return demo2d_finish(&d, out);
}

/* The 2D panels on top, a title, then the 3D section, left-aligned on
 * the page color; the 3D section is not magnified by --scale. */
int demo_clip(sr_context *ctx, const demo_args *args, sr_framebuffer **out)
{
    sr_framebuffer *top = NULL, *bottom = NULL, *page = NULL;
    int status = clip2d_section(ctx, args, &top);
    if (status == EXIT_OK) {
        status = demo_clip3d_section(ctx, &bottom);
    }
    if (status != EXIT_OK) {
        sr_destroy_framebuffer(ctx, top);
        return status;
    }
    const int title_h = 28;
    int tw = sr_framebuffer_width(top), th = sr_framebuffer_height(top);
    int bw = sr_framebuffer_width(bottom), bh = sr_framebuffer_height(bottom);
    if (sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = tw > bw ? tw : bw,
                                                         .height = th + title_h + bh,
                                                         .depth_format = SR_DEPTH_NONE },
                            &page) != SR_OK) {
        cli_error("demo clip: %s", sr_context_error(ctx));
        status = EXIT_FAILURE_RUN;
    } else {
        sr_clear(ctx, page, &(sr_clear_desc){ .color = { 0.93f, 0.93f, 0.93f, 1 } });
        sr_result r = demo_paste(ctx, page, top, 0, 0);
        if (r == SR_OK) {
            r = demo_paste(ctx, page, bottom, 0, th + title_h);
        }
        if (r == SR_OK) {
            sr_draw_text(ctx, page, 12, th + title_h - 16, 2, "3D: clipping in clip space",
                         (sr_rgba){ 0.1f, 0.1f, 0.12f, 1 });
            *out = page;
        } else {
            cli_error("demo clip: %s", sr_context_error(ctx));
            sr_destroy_framebuffer(ctx, page);
            status = EXIT_FAILURE_RUN;
        }
    }
    sr_destroy_framebuffer(ctx, top);
    sr_destroy_framebuffer(ctx, bottom);
    return status;
}
