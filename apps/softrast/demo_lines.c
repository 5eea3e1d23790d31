/* demo_lines.c - `softrast demo lines`: a star of lines at every angle,
 * drawn with each line algorithm of sr_draw_line side by side and
 * magnified so the pixels show: naive and incremental DDA, midpoint
 * (Bresenham), Xiaolin Wu, exact area coverage, and wide aliased lines
 * with each cap. */
#include "cli.h"
#include "demo.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#define PANEL 48           /* logical pixels per panel side */
#define COLS 4
#define ROWS 2
#define GAP 12             /* output pixels between panels */
#define LABEL_H 28         /* output pixels above each panel for its label */
#define RAYS 24

typedef struct panel {
    const char *label;
    sr_line_desc desc;
    double radius;
} panel;

static const panel panels[COLS * ROWS] = {
    { "DDA, naive", { .algorithm = SR_LINE_DDA_NAIVE }, 21.0 },
    { "DDA, incremental", { .algorithm = SR_LINE_DDA_INCREMENTAL }, 21.0 },
    { "midpoint (Bresenham)", { .algorithm = SR_LINE_BRESENHAM }, 21.0 },
    { "Xiaolin Wu", { .algorithm = SR_LINE_WU }, 21.0 },
    { "area, width 1", { .algorithm = SR_LINE_AREA, .width = 1.0 }, 21.0 },
    { "area, width 2.5, round", { .algorithm = SR_LINE_AREA, .width = 2.5,
                                  .cap = SR_LINE_CAP_ROUND }, 18.0 },
    { "wide 3, butt", { .algorithm = SR_LINE_WIDE, .width = 3 }, 18.0 },
    { "wide 3, round", { .algorithm = SR_LINE_WIDE, .width = 3, .cap = SR_LINE_CAP_ROUND },
      18.0 },
};

/* The star: RAYS lines from just off the panel's centre pixel outwards,
 * each at its own angle; the wide and thick ones use fewer rays so the
 * rays stay apart. */
static sr_result draw_star(sr_context *ctx, sr_framebuffer *fb, const panel *p)
{
    const sr_point2 c = { PANEL / 2.0, PANEL / 2.0 };
    const sr_rgba ink = { 1.0f, 0.93f, 0.75f, 1.0f };
    int rays = p->radius < 20.0 ? RAYS / 2 : RAYS;
    for (int i = 0; i < rays; i++) {
        double t = 2.0 * 3.14159265358979323846 * (i + 0.25) / rays;
        sr_point2 a = { c.x + 4.0 * cos(t), c.y + 4.0 * sin(t) };
        sr_point2 b = { c.x + p->radius * cos(t), c.y + p->radius * sin(t) };
        sr_result r = sr_draw_line(ctx, fb, a, b, ink, &p->desc);
        if (r != SR_OK) {
            return r;
        }
    }
    return SR_OK;
}

int demo_lines(sr_context *ctx, const demo_args *args, sr_framebuffer **out)
{
    const int scale = args->scale > 0 ? args->scale : 6;
    const int cell = PANEL * scale;
    const int width = COLS * cell + (COLS + 1) * GAP;
    const int height = ROWS * (cell + LABEL_H) + (ROWS + 1) * GAP;
    sr_framebuffer *big = NULL, *small = NULL;
    if (demo_check_image("lines", scale, width, height) != EXIT_OK) {
        return EXIT_USAGE;
    }
    if (sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = width, .height = height,
                                                         .depth_format = SR_DEPTH_NONE }, &big) != SR_OK ||
        sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = PANEL, .height = PANEL,
                                                         .depth_format = SR_DEPTH_NONE }, &small) != SR_OK) {
        cli_error("demo lines: %s", sr_context_error(ctx));
        sr_destroy_framebuffer(ctx, big);
        return EXIT_FAILURE_RUN;
    }
    sr_clear(ctx, big, &(sr_clear_desc){ .color = { 0.93f, 0.93f, 0.93f, 1 } });
    static const uint8_t grid[4] = { 44, 48, 56, 255 };
    /* Labels at twice the font size when they all fit their panels,
     * else at 1, cut short if even that is too wide (tiny --scale). */
    int ts = 2;
    for (int n = 0; n < COLS * ROWS; n++) {
        ts = sr_text_width(panels[n].label, 2) <= cell ? ts : 1;
    }
    for (int n = 0; n < COLS * ROWS; n++) {
        const panel *p = &panels[n];
        int ox = GAP + (n % COLS) * (cell + GAP);
        int oy = GAP + (n / COLS) * (cell + LABEL_H + GAP);
        char label[64];
        snprintf(label, sizeof label, "%s", p->label);
        while (sr_text_width(label, ts) > cell && strlen(label) > 1) {
            label[strlen(label) - 1] = '\0';
        }
        sr_draw_text(ctx, big, ox, oy + LABEL_H - 8 * ts - 6, ts, label,
                     (sr_rgba){ 0.1f, 0.1f, 0.12f, 1 });
        oy += LABEL_H;
        sr_clear(ctx, small, &(sr_clear_desc){ .color = { 0.08f, 0.09f, 0.11f, 1 } });
        /* Magnify: each pixel a scale x scale block, with a one-pixel grid
         * line on its top and left edges when the blocks are big enough. */
        sr_result r = draw_star(ctx, small, p);
        if (r == SR_OK) {
            r = demo_magnify(ctx, big, ox, oy, small, scale, grid);
        }
        if (r != SR_OK) {
            cli_error("demo lines: %s", sr_context_error(ctx)[0] ? sr_context_error(ctx)
                                                                 : sr_result_text(r));
            sr_destroy_framebuffer(ctx, small);
            sr_destroy_framebuffer(ctx, big);
            return EXIT_FAILURE_RUN;
        }
    }
    sr_destroy_framebuffer(ctx, small);
    *out = big;
    return EXIT_OK;
}
