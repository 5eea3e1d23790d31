/* paint.c - filling 2D paths with more than a color (docs/draw2d.md,
 * "Paint"): a disc with a reflected linear gradient, a shape with a
 * radial gradient whose focal point is off its centre, and a star with a
 * rotated checker pattern at 80% opacity, all antialiased.  Writes
 * paint.png (or argv[1]). */
#include "softrast.h"
#include "softrast_io.h"

#include <math.h>
#include <stdio.h>

enum { W = 400, H = 140, TILE = 8 };
static const double pi = 3.14159265358979323846;

static sr_result fill(sr_context *ctx, sr_framebuffer *fb, const sr_path *path,
                      const sr_paint *paint)
{
    return sr_fill_path_paint(ctx, fb, path, paint, &(sr_fill_desc){ .antialias = SR_AA_AREA });
}

static sr_result draw(sr_context *ctx, sr_framebuffer *fb, sr_path *p)
{
    const sr_gradient_stop stops[] = { { 0, { 0.1f, 0.3f, 0.8f, 1 } },
                                       { 0.5, { 1, 0.8f, 0.1f, 1 } },
                                       { 1, { 0.8f, 0.1f, 0.2f, 1 } } };
    /* A disc; the gradient runs from (30, 40) to (60, 60), then back. */
    sr_path_move_to(p, 110, 70);
    sr_path_arc_to(p, 50, 50, 0, true, false, 10, 70);
    sr_path_arc_to(p, 50, 50, 0, true, false, 110, 70);
    sr_path_close(p);
    sr_paint linear = { .kind = SR_PAINT_LINEAR_GRADIENT, .x1 = 30, .y1 = 40, .x2 = 60,
                        .y2 = 60, .stops = stops, .stop_count = 3, .spread = SR_SPREAD_REFLECT };
    sr_result r = fill(ctx, fb, p, &linear);

    /* A square with a curved bottom; t = 0 on a circle of radius 4 around
     * the focal point (170, 50), t = 1 on the end circle around (195, 70). */
    sr_path_clear(p);
    sr_path_move_to(p, 140, 20);
    sr_path_line_to(p, 250, 20);
    sr_path_line_to(p, 250, 120);
    sr_path_cubic_to(p, 200, 135, 160, 110, 140, 120);
    sr_path_close(p);
    sr_point2 focal = { 170, 50 };
    sr_paint radial = { .kind = SR_PAINT_RADIAL_GRADIENT, .cx = 195, .cy = 70, .r = 60,
                        .focal = &focal, .fr = 4, .stops = stops, .stop_count = 3 };
    r = r ? r : fill(ctx, fb, p, &radial);

    /* A five-pointed star around (330, 75) with an 8 x 8 checker tile,
     * turned 30 degrees and doubled: a texel is 2 px a side. */
    uint8_t tile[TILE * TILE * 4];
    for (int y = 0; y < TILE; y++) {
        for (int x = 0; x < TILE; x++) {
            uint8_t *t = tile + (y * TILE + x) * 4;
            int dark = (x < TILE / 2) != (y < TILE / 2);
            t[0] = dark ? 30 : 240;
            t[1] = dark ? 140 : 240;
            t[2] = dark ? 60 : 220;
            t[3] = 255;
        }
    }
    sr_path_clear(p);
    for (int i = 0; i < 10; i++) {
        double a = -pi / 2 + i * pi / 5, radius = i % 2 ? 25 : 62;
        double x = 330 + radius * cos(a), y = 75 + radius * sin(a);
        (i == 0 ? sr_path_move_to : sr_path_line_to)(p, x, y);
    }
    sr_path_close(p);
    double c = 2 * cos(pi / 6), s = 2 * sin(pi / 6);
    sr_affine2 turn = { c, s, -s, c, 330, 75 }; /* tile texels -> pixels */
    sr_paint pattern = { .kind = SR_PAINT_PATTERN, .image = tile, .image_width = TILE,
                         .image_height = TILE, .transform = &turn, .opacity = 0.8f };
    return r ? r : fill(ctx, fb, p, &pattern);
}

int main(int argc, char **argv)
{
    const char *out = argc > 1 ? argv[1] : "paint.png";
    sr_context *ctx = NULL;
    sr_framebuffer *fb = NULL;
    sr_path *path = NULL;
    sr_result r = sr_make_context(NULL, &ctx);
    if (r == SR_OK) {
        r = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &fb);
    }
    if (r == SR_OK) {
        r = sr_make_path(ctx, 0, &path);
    }
    if (r == SR_OK) {
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 1, 1, 1, 1 } });
        r = draw(ctx, fb, path);
    }
    if (r != SR_OK) {
        fprintf(stderr, "paint: %s\n", ctx ? sr_context_error(ctx) : sr_result_text(r));
    } else {
        sr_io_error err;
        r = sr_write_png(out, W, H, sr_framebuffer_pixels(fb), W * 4, NULL, &err);
        if (r != SR_OK) {
            fprintf(stderr, "paint: %s\n", err.message);
        }
    }
    sr_destroy_path(ctx, path);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
    return r == SR_OK ? 0 : 1;
}
