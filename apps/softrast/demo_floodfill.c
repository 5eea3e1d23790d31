/* demo_floodfill.c - `softrast demo floodfill`: region filling from a
 * seed, magnified.  The image is a diamond drawn as a one-pixel staircase
 * (its pixels touch only diagonally), with a few blue pixels and a patch
 * of light gray inside.  A 4-connected flood fill stays inside; an
 * 8-connected one leaks out through the diagonal gaps, because the
 * background pixels on either side of a staircase step are diagonal
 * neighbours.  Boundary fill (until the red boundary) paints over the blue
 * pixels, flood fill (only the seed's color) goes around them; a color
 * tolerance lets the flood take in the gray patch too. */
#include "cli.h"
#include "demo.h"
#include "demo2d.h"

#define PANEL 36

static const sr_rgba PAPER = { 0.93f, 0.93f, 0.9f, 1 };
static const sr_rgba RED = { 0.85f, 0.12f, 0.1f, 1 };
static const sr_rgba BLUE = { 0.15f, 0.3f, 0.85f, 1 };
static const sr_rgba GRAY = { 0.8f, 0.8f, 0.78f, 1 };
static const sr_rgba FILL = { 0.98f, 0.78f, 0.2f, 1 };
static const sr_point2 SEED = { 17.5, 17.5 };

static void put(sr_context *ctx, sr_framebuffer *fb, int x, int y, sr_rgba c)
{
    sr_point2 q[4] = { { x, y }, { x + 1, y }, { x + 1, y + 1 }, { x, y + 1 } };
    sr_fill_polygon(ctx, fb, &(sr_polygon2){ q, 4, NULL, 0 }, c, NULL);
}

static void draw_image(sr_context *ctx, sr_framebuffer *fb)
{
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { PAPER.r, PAPER.g, PAPER.b, 1 } });
    /* The diamond |x - 17| + |y - 17| = 14 as four staircases. */
    for (int k = 0; k < 14; k++) {
        put(ctx, fb, 17 + k, 3 + k, RED);
        put(ctx, fb, 31 - k, 17 + k, RED);
        put(ctx, fb, 17 - k, 31 - k, RED);
        put(ctx, fb, 3 + k, 17 - k, RED);
    }
    /* Blue pixels inside, and a gray patch (a 4x4 checker of two grays). */
    int blue[6][2] = { { 14, 12 }, { 20, 13 }, { 12, 19 }, { 22, 21 }, { 17, 24 }, { 18, 10 } };
    for (int i = 0; i < 6; i++) {
        put(ctx, fb, blue[i][0], blue[i][1], BLUE);
    }
    for (int y = 0; y < 5; y++) {
        for (int x = 0; x < 5; x++) {
            if ((x + y) % 2 == 0) {
                put(ctx, fb, 19 + x, 16 + y, GRAY);
            }
        }
    }
}

typedef struct panel_spec {
    const char *label;
    int kind;             /* 0 the image, 1 flood, 2 boundary */
    sr_region_fill_desc desc;
} panel_spec;

static const panel_spec panels[6] = {
    { "image, seed (dot)", 0, { 0 } },
    { "flood, 4-connected", 1, { SR_CONNECT_4, 0 } },
    { "flood, 8: leaks", 1, { SR_CONNECT_8, 0 } },
    { "boundary, 4-conn.", 2, { SR_CONNECT_4, 0 } },
    { "boundary, 8: leaks", 2, { SR_CONNECT_8, 0 } },
    { "flood 4, tolerance 40", 1, { SR_CONNECT_4, 40 } },
};

int demo_floodfill(sr_context *ctx, const demo_args *args, sr_framebuffer **out)
{
    demo2d d;
    int scale = args->scale > 0 ? args->scale : 7;
    int status = demo2d_begin(&d, ctx, "floodfill", 3, 2, PANEL, PANEL, scale);
    if (status != EXIT_OK) {
        return status;
    }
    for (int i = 0; i < 6; i++) {
        const panel_spec *p = &panels[i];
        draw_image(ctx, d.panel);
        sr_result r = SR_OK;
        if (p->kind == 1) {
            r = sr_flood_fill(ctx, d.panel, (int)SEED.x, (int)SEED.y, FILL, &p->desc, NULL);
        } else if (p->kind == 2) {
            r = sr_boundary_fill(ctx, d.panel, (int)SEED.x, (int)SEED.y, FILL, RED, &p->desc, NULL);
        }
        if (r != SR_OK) {
            return demo2d_fail(&d);
        }
        demo2d_blit(&d, i, p->label);
        demo2d_dot(&d, i, SEED, scale * 0.3, (sr_rgba){ 0.1f, 0.1f, 0.1f, 1 });
    }
    return demo2d_finish(&d, out);
}
