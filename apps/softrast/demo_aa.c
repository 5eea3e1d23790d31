/* demo_aa.c - `softrast demo aa`: aliasing and three cures for it
 * (a pixel is an area, not a point; sampling it once at its centre
 * turns an edge into a staircase and thin features into broken dashes).
 *
 * Every shape panel draws the same two shapes into a small image,
 * magnified with nearest-neighbour so each pixel is a block: a star of
 * SPOKES thin wedges (every other sector of a fan of triangles, the
 * classic aliasing test: near the centre the wedges are thinner than a
 * pixel) and a square turned 10 degrees (shallow edges, long stairs).
 * Light ink on a dark ground, unlit, so a pixel's gray level is its
 * coverage and nothing else.
 *
 * Panels (row-major, DEMO3D_LAYOUT_AA):
 *   row 0: no AA - one sample at the pixel centre: two levels only;
 *          MSAA 4x, 8x, 16x - sr_framebuffer_desc.samples at the standard
 *          positions, shaded once per pixel, read back resolved (the box
 *          average of the samples): at most n + 1 levels, k/n covered;
 *   row 1: exact area - the same shapes through the 2D filler's exact-area
 *          coverage (sr_fill_polygon, SR_AA_AREA): the box-filtered
 *          truth the others approximate;
 *          the 4x, 8x and 16x sample positions (sr_sample_position) in one
 *          magnified pixel, under the MSAA panel that uses them: a 1/16 px
 *          grid, the centre cross, sample i labelled i (4x and 8x);
 *   row 2: SSAA - the shapes drawn at 4 x 4 the size (16 samples per
 *          pixel on a regular grid) and reduced by sr_downsample with
 *          each reconstruction filter: box (unweighted area sampling),
 *          tent, gaussian (weighted, softer) and mitchell (negative lobes:
 *          sharper, a faint ring).
 * A faint pixel grid is drawn over the shape panels (between blocks, so
 * the block centres keep the panel's colors for tests/test_demo_aa.c). */
#include "cli.h"
#include "demo.h"
#include "demo3d.h"

#include <math.h>
#include <stdio.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define SPOKES 24         /* wedges of the star */
#define SSAA_K 4          /* supersampling factor per axis */
#define STAR_R 15.6       /* panel pixels */
#define SQUARE_HALF 10.2
#define SQUARE_TURN_DEG 10.0

#define VERTS (3 * SPOKES + 6)      /* triangle corners: wedges, two for the square */
#define POINTS (3 * SPOKES + 4)     /* 2D polygon: one contour per wedge, the square */

static const sr_rgba BG = { 0.09f, 0.10f, 0.13f, 1 };
static const sr_rgba INK = { 1.0f, 0.86f, 0.42f, 1 };
static const sr_rgba GRID = { 0, 0, 0, 0.25f };          /* blended over the blocks */
static const sr_rgba PIXEL_FACE = { 0.17f, 0.19f, 0.24f, 1 };
static const sr_rgba SUBGRID = { 0.25f, 0.28f, 0.34f, 1 };
static const sr_rgba CENTRE = { 0.45f, 0.72f, 1.0f, 1 };
static const sr_rgba NUMBER = { 0.75f, 0.78f, 0.84f, 1 };

typedef struct shapes {
    float xyz[VERTS * 3];          /* sr_draw: triangles in panel pixels, z = 0 */
    sr_point2 pts[POINTS];         /* sr_fill_polygon: the same outlines */
    int counts[SPOKES + 1];
} shapes;

/* Star centre and square centre are off the pixel grid on purpose: a
 * symmetric placement would hide some of the aliasing. */
static void make_shapes(int w, int h, shapes *s)
{
    double cx = STAR_R + 2.3, cy = h * 0.5 + 0.2;
    int v = 0, p = 0;
    for (int k = 0; k < SPOKES; k++) {
        double a0 = 2 * M_PI * k / SPOKES + 0.05, a1 = a0 + M_PI / SPOKES;
        /* counter-clockwise on screen (y down): centre, then a1, then a0 */
        sr_point2 tri[3] = { { cx, cy }, { cx + STAR_R * cos(a1), cy + STAR_R * sin(a1) },
                             { cx + STAR_R * cos(a0), cy + STAR_R * sin(a0) } };
        for (int i = 0; i < 3; i++) {
            s->pts[p++] = tri[i];
        }
        s->counts[k] = 3;
    }
    double qx = w - SQUARE_HALF * 1.16 - 3.4, qy = h * 0.5 - 0.3;
    double t = SQUARE_TURN_DEG * M_PI / 180, c = cos(t), sn = sin(t);
    static const double corner[4][2] = { { -1, -1 }, { -1, 1 }, { 1, 1 }, { 1, -1 } };
    for (int i = 0; i < 4; i++) {
        double x = corner[i][0] * SQUARE_HALF, y = corner[i][1] * SQUARE_HALF;
        s->pts[p++] = (sr_point2){ qx + c * x - sn * y, qy + sn * x + c * y };
    }
    s->counts[SPOKES] = 4;
    /* Triangles: the wedges as they are, the square as two halves. */
    for (int i = 0; i < 3 * SPOKES; i++) {
        s->xyz[v++] = (float)s->pts[i].x;
        s->xyz[v++] = (float)s->pts[i].y;
        s->xyz[v++] = 0;
    }
    static const int halves[6] = { 0, 1, 2, 0, 2, 3 };
    for (int i = 0; i < 6; i++) {
        const sr_point2 *q = &s->pts[3 * SPOKES + halves[i]];
        s->xyz[v++] = (float)q->x;
        s->xyz[v++] = (float)q->y;
        s->xyz[v++] = 0;
    }
}

/* Draw the shapes into fb.  The orthographic projection maps panel pixels
 * (y down) onto the whole framebuffer, so an SSAA framebuffer k times the
 * size gets the same shapes k times larger. */
static sr_result draw_shapes(sr_context *ctx, sr_framebuffer *fb, const shapes *s, int w, int h)
{
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { BG.r, BG.g, BG.b, 1 } });
    sr_mat4 proj = sr_ortho(0, (float)w, (float)h, 0, -1, 1, false);
    sr_state st = { .shading = SR_SHADING_UNLIT,
                    .material.diffuse = { INK.r, INK.g, INK.b } };
    return sr_draw(ctx, fb, &st, &(sr_draw_desc){ .positions = s->xyz, .vertex_count = VERTS,
                                                  .projection = &proj });
}

/* One polygon call for all the contours: the wedges meet at the centre,
 * and separate calls would blend their partial coverages there
 * (1 - (1-a)(1-b) instead of a + b). */
static sr_result fill_exact(sr_context *ctx, sr_framebuffer *fb, const shapes *s)
{
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { BG.r, BG.g, BG.b, 1 } });
    sr_polygon2 poly = { s->pts, POINTS, s->counts, SPOKES + 1 };
    return sr_fill_polygon(ctx, fb, &poly, INK,
                           &(sr_fill_desc){ .rule = SR_NONZERO, .antialias = SR_AA_AREA });
}

static void fill_rect(sr_context *ctx, sr_framebuffer *fb, double x0, double y0, double x1,
                      double y1, sr_rgba color)
{
    sr_point2 r[4] = { { x0, y0 }, { x1, y0 }, { x1, y1 }, { x0, y1 } };
    sr_fill_polygon(ctx, fb, &(sr_polygon2){ r, 4, NULL, 0 }, color, NULL);
}

/* One-pixel lines on the top and left edge of every block but the first,
 * aliased (whole output pixels). */
static void pixel_grid(demo3d *d, int index)
{
    int ox, oy, s = d->scale;
    if (s < 4) {
        return;
    }
    demo3d_cell_origin(d->layout, s, 0, index, &ox, &oy);
    int cw = d->layout.cell_w * s, ch = d->layout.cell_h * s;
    for (int x = 1; x < d->layout.cell_w; x++) {
        fill_rect(d->ctx, d->out, ox + x * s, oy, ox + x * s + 1, oy + ch, GRID);
    }
    for (int y = 1; y < d->layout.cell_h; y++) {
        fill_rect(d->ctx, d->out, ox, oy + y * s, ox + cw, oy + y * s + 1, GRID);
    }
}

static void dot(sr_context *ctx, sr_framebuffer *fb, double x, double y, double r, sr_rgba color)
{
    sr_path *path = NULL;
    if (sr_make_path(ctx, 0.05, &path) != SR_OK) {
        return;
    }
    sr_path_move_to(path, x - r, y);
    sr_path_arc_to(path, r, r, 0, false, true, x + r, y);
    sr_path_arc_to(path, r, r, 0, false, true, x - r, y);
    sr_path_close(path);
    sr_fill_path(ctx, fb, path, color, &(sr_fill_desc){ .antialias = SR_AA_AREA });
    sr_destroy_path(ctx, path);
}

/* One pixel magnified to most of the cell: the 1/16 px lattice every
 * standard position lies on, the centre (where the single sample of the
 * no-AA panel is) as a cross, and the samples as dots, numbered when they
 * leave room for it (4x and 8x at the default magnification). */
static void sample_positions(demo3d *d, int index, int samples)
{
    int ox, oy, s = d->scale;
    demo3d_cell_origin(d->layout, s, 0, index, &ox, &oy);
    int cw = d->layout.cell_w * s, ch = d->layout.cell_h * s;
    double size = ch - 20.0, step = size / 16;
    double x0 = ox + floor((cw - size) / 2), y0 = oy + 10;
    fill_rect(d->ctx, d->out, x0, y0, x0 + size, y0 + size, PIXEL_FACE);
    for (int i = 1; i < 16 && step >= 4; i++) {
        double t = floor(i * step);
        if (i == 8) {
            continue;
        }
        fill_rect(d->ctx, d->out, x0 + t, y0, x0 + t + 1, y0 + size, SUBGRID);
        fill_rect(d->ctx, d->out, x0, y0 + t, x0 + size, y0 + t + 1, SUBGRID);
    }
    double c = floor(8 * step), arm = fmin(7, floor(0.7 * step));
    fill_rect(d->ctx, d->out, x0 + c - arm, y0 + c, x0 + c + arm + 1, y0 + c + 1, CENTRE);
    fill_rect(d->ctx, d->out, x0 + c, y0 + c - arm, x0 + c + 1, y0 + c + arm + 1, CENTRE);
    for (int i = 0; i < samples; i++) {
        float sx, sy;
        if (sr_sample_position(samples, i, &sx, &sy) != SR_OK) {
            return;
        }
        /* the dot's centre on the lattice line's pixel, + 0.5 */
        double px = x0 + floor(sx * 16 * step) + 0.5, py = y0 + floor(sy * 16 * step) + 0.5;
        double r = fmin(3.5, 0.35 * step); /* small magnifications: keep dots apart */
        dot(d->ctx, d->out, px, py, r + 1, BG);
        dot(d->ctx, d->out, px, py, r, INK);
        if (samples <= 8 && step >= 6) {
            char num[12];
            snprintf(num, sizeof num, "%d", i);
            sr_draw_text(d->ctx, d->out, (int)px + 6, (int)py - 10, 1, num, NUMBER);
        }
    }
}

int demo_aa(sr_context *ctx, const demo_args *args, sr_framebuffer **out)
{
    enum { NO_AA, MSAA4, MSAA8, MSAA16, EXACT, POS4, POS8, POS16, BOX, TENT, GAUSS, MITCHELL,
           PANELS };
    static const char *const labels[PANELS] = {
        "no AA (1 sample)", "MSAA 4x", "MSAA 8x", "MSAA 16x",
        "exact area (2D)", "4x sample positions", "8x sample positions", "16x sample positions",
        "SSAA 4x4 box", "SSAA 4x4 tent", "SSAA 4x4 gaussian", "SSAA 4x4 mitchell",
    };
    static const sr_resample_filter filters[4] = { SR_RESAMPLE_BOX, SR_RESAMPLE_TENT,
                                                   SR_RESAMPLE_GAUSSIAN,
                                                   SR_RESAMPLE_MITCHELL };
    demo3d_layout l = DEMO3D_LAYOUT_AA;
    demo3d d;
    int status = demo3d_begin(&d, ctx, "aa", l, args->scale > 0 ? args->scale : DEMO3D_AA_SCALE,
                              labels, PANELS);
    if (status != EXIT_OK) {
        return status;
    }
    static shapes sh;
    make_shapes(l.cell_w, l.cell_h, &sh);
    for (int i = 0; i < PANELS; i++) {
        sr_framebuffer *fb = NULL, *big = NULL;
        int samples = i == MSAA4 ? 4 : i == MSAA8 ? 8 : i == MSAA16 ? 16 : 1;
        sr_result r = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){
                                              .width = l.cell_w, .height = l.cell_h,
                                              .depth_format = SR_DEPTH_NONE,
                                              .samples = samples }, &fb);
        if (r == SR_OK && i >= BOX) {
            r = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){
                                        .width = SSAA_K * l.cell_w, .height = SSAA_K * l.cell_h,
                                        .depth_format = SR_DEPTH_NONE }, &big);
            if (r == SR_OK) {
                r = draw_shapes(ctx, big, &sh, l.cell_w, l.cell_h);
            }
            if (r == SR_OK) {
                r = sr_downsample(ctx, big, fb, filters[i - BOX]);
            }
        } else if (r == SR_OK && i == EXACT) {
            r = fill_exact(ctx, fb, &sh);
        } else if (r == SR_OK && i >= POS4 && i <= POS16) {
            sr_clear(ctx, fb, &(sr_clear_desc){ .color = { BG.r, BG.g, BG.b, 1 } });
        } else if (r == SR_OK) {
            r = draw_shapes(ctx, fb, &sh, l.cell_w, l.cell_h); /* no AA and MSAA */
        }
        if (r != SR_OK) {
            sr_destroy_framebuffer(ctx, big);
            sr_destroy_framebuffer(ctx, fb);
            return demo3d_fail(&d);
        }
        /* demo3d_blit reads sr_framebuffer_pixels: the MSAA panels resolved */
        demo3d_blit(&d, i, fb, labels[i]);
        if (i >= POS4 && i <= POS16) {
            sample_positions(&d, i, 4 << (i - POS4));
        } else {
            pixel_grid(&d, i);
        }
        sr_destroy_framebuffer(ctx, big);
        sr_destroy_framebuffer(ctx, fb);
    }
    return demo3d_finish(&d, out);
}
