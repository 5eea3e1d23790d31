/* demo_fill.c - `softrast demo fill`: the scan-line polygon fill (edge
 * table + active edge table) under the two fill rules, magnified.  A
 * self-intersecting pentagram (winding number 2 in the middle: a hole
 * under even-odd parity, filled under nonzero) and a square with a square
 * hole wound the same way (a hole only under even-odd) or the opposite
 * way (a hole under both); below, the star antialiased by exact area
 * coverage and by 4x4 supersampling.  The polygon outline is drawn over
 * the pixels: a pixel is filled when its centre is inside. */
#include "cli.h"
#include "demo.h"
#include "demo2d.h"

#include <math.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define PANEL 40

static const sr_rgba BG = { 0.08f, 0.09f, 0.11f, 1 };
static const sr_rgba INK = { 0.98f, 0.86f, 0.45f, 1 };
static const sr_rgba LINE = { 0.2f, 0.65f, 1.0f, 1 };

typedef struct shape {
    sr_point2 pts[12];
    int counts[2];
    int contours;
} shape;

static shape pentagram(void)
{
    shape s = { .counts = { 5 }, .contours = 1 };
    for (int k = 0; k < 5; k++) {
        double a = -M_PI / 2 + k * 4 * M_PI / 5;
        s.pts[k] = (sr_point2){ 20.2 + 17.5 * cos(a), 21.3 + 17.5 * sin(a) };
    }
    return s;
}

/* Outer square clockwise on screen; the hole the same way or reversed. */
static shape square_with_hole(bool reversed)
{
    shape s = { .counts = { 4, 4 }, .contours = 2 };
    sr_point2 outer[4] = { { 4.3, 4.6 }, { 35.6, 4.6 }, { 35.6, 35.4 }, { 4.3, 35.4 } };
    sr_point2 inner[4] = { { 13.4, 12.7 }, { 27.2, 12.7 }, { 27.2, 27.3 }, { 13.4, 27.3 } };
    for (int k = 0; k < 4; k++) {
        s.pts[k] = outer[k];
        s.pts[4 + k] = inner[reversed ? 3 - k : k];
    }
    return s;
}

typedef struct panel_spec {
    const char *label;
    int shape;           /* 0 star, 1 same-way hole, 2 reversed hole */
    sr_fill_desc fill;
} panel_spec;

static const panel_spec panels[8] = {
    { "even-odd: star", 0, { .rule = SR_EVENODD } },
    { "nonzero: star", 0, { .rule = SR_NONZERO } },
    { "even-odd: hole", 1, { .rule = SR_EVENODD } },
    { "nonzero: hole", 1, { .rule = SR_NONZERO } },
    { "area AA, even-odd", 0, { .rule = SR_EVENODD, .antialias = SR_AA_AREA } },
    { "area AA, nonzero", 0, { .rule = SR_NONZERO, .antialias = SR_AA_AREA } },
    { "4x4 samples, nonzero", 0, { .rule = SR_NONZERO, .antialias = SR_AA_SUPERSAMPLE,
                                   .samples = 4 } },
    { "nonzero: reversed", 2, { .rule = SR_NONZERO } },
};

int demo_fill(sr_context *ctx, const demo_args *args, sr_framebuffer **out)
{
    demo2d d;
    int scale = args->scale > 0 ? args->scale : 6;
    int status = demo2d_begin(&d, ctx, "fill", 4, 2, PANEL, PANEL, scale);
    if (status != EXIT_OK) {
        return status;
    }
    for (int i = 0; i < 8; i++) {
        const panel_spec *p = &panels[i];
        shape s = p->shape == 0 ? pentagram() : square_with_hole(p->shape == 2);
        int n = s.counts[0] + (s.contours > 1 ? s.counts[1] : 0);
        demo2d_clear_panel(&d, BG);
        if (sr_fill_polygon(ctx, d.panel, &(sr_polygon2){ s.pts, n, s.counts, s.contours }, INK,
                            &p->fill) != SR_OK) {
            return demo2d_fail(&d);
        }
        demo2d_blit(&d, i, p->label);
        int start = 0;
        for (int c = 0; c < s.contours; c++) {
            demo2d_outline(&d, i, s.pts + start, s.counts[c], true, LINE, 2.0);
            demo2d_dot(&d, i, s.pts[start], 4.0, LINE); /* where each contour starts */
            start += s.counts[c];
        }
    }
    return demo2d_finish(&d, out);
}
