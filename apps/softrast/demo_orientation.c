/* demo_orientation.c - `softrast demo orientation`: only triangles
 * interpolate independently of orientation.
 *
 * A square with red at two opposite corners and blue at the other two,
 * turned by 0, 30 and 45 degrees.  Top row: its colors interpolated by
 * scan lines (sr_fill_polygon_gouraud: along the edges to each scan
 * line's crossings, then along the span), which for more than three
 * vertices depends on how the polygon lies on the scan lines - at 0
 * degrees the centre is the mean of all four corners, at 45 the mean of
 * the left and right ones, so the picture changes as the square turns.
 * Bottom row: the same square as two triangles (sr_fill_triangle_gouraud,
 * split along the red diagonal): a triangle's interpolation is the
 * unique linear function through its three corners, so each picture is
 * the first one turned.
 *
 * Panels (row-major): scan lines at 0, 30, 45 degrees; two triangles at
 * 0, 30, 45 degrees.  Point-sampled (colors at pixel centres). */
#include "cli.h"
#include "demo.h"
#include "demo3d.h"

#include <math.h>

#define TURNS 3
static const float turn_deg[TURNS] = { 0.0f, 30.0f, 45.0f };

static sr_result draw_panel(sr_context *ctx, sr_framebuffer *fb, float deg, bool triangles)
{
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.07f, 0.08f, 0.1f, 1 }, .depth = 1 });
    const sr_rgba red = { 0.95f, 0.15f, 0.1f, 1 }, blue = { 0.1f, 0.3f, 1.0f, 1 };
    const sr_rgba colors[4] = { red, blue, red, blue };
    float cx = (float)sr_framebuffer_width(fb) / 2, cy = (float)sr_framebuffer_height(fb) / 2;
    float r = 0.85f * (cx < cy ? cx : cy), a0 = deg * 3.14159265f / 180.0f; /* centre to corner */
    sr_point2 v[4];
    for (int k = 0; k < 4; k++) {
        float a = a0 + 0.78539816f + 1.5707963f * (float)k; /* corners of an upright square */
        v[k] = (sr_point2){ cx + r * cosf(a), cy + r * sinf(a) };
    }
    if (!triangles) {
        sr_polygon2 poly = { .points = v, .point_count = 4 };
        return sr_fill_polygon_gouraud(ctx, fb, &poly, colors, SR_FILL_RULE_DEFAULT);
    }
    const sr_point2 t0[3] = { v[0], v[1], v[2] }, t1[3] = { v[0], v[2], v[3] };
    const sr_rgba c0[3] = { red, blue, red }, c1[3] = { red, red, blue };
    sr_result res = sr_fill_triangle_gouraud(ctx, fb, t0, c0);
    return res != SR_OK ? res : sr_fill_triangle_gouraud(ctx, fb, t1, c1);
}

int demo_orientation(sr_context *ctx, const demo_args *args, sr_framebuffer **out)
{
    static const char *const labels[2 * TURNS] = {
        "scan lines, 0 deg",   "scan lines, 30 deg",   "scan lines, 45 deg",
        "2 triangles, 0 deg", "2 triangles, 30 deg", "2 triangles, 45 deg",
    };
    demo3d d;
    int status = demo3d_begin(&d, ctx, "orientation", DEMO3D_LAYOUT_ORIENTATION, args->scale,
                              labels, 2 * TURNS);
    if (status != EXIT_OK) {
        return status;
    }
    sr_framebuffer *fb = NULL;
    if (demo3d_panel(&d, SR_DEPTH_NONE, &fb) != SR_OK) {
        return demo3d_fail(&d);
    }
    for (int i = 0; i < 2 * TURNS; i++) {
        if (draw_panel(ctx, fb, turn_deg[i % TURNS], i >= TURNS) != SR_OK) {
            sr_destroy_framebuffer(ctx, fb);
            return demo3d_fail(&d);
        }
        demo3d_blit(&d, i, fb, labels[i]);
    }
    sr_destroy_framebuffer(ctx, fb);
    return demo3d_finish(&d, out);
}
