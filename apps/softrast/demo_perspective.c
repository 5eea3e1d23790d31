/* demo_perspective.c - `softrast demo perspective`: why attributes must
 * not be interpolated in screen space ("screen space color
 * interpolation": the perspective transformation does not preserve
 * distances, so interpolating before and after it gives different
 * results).
 *
 * One floor rectangle of two triangles recedes from the eye.  Top row: a
 * checkerboard texture (sr_make_texture, trilinear).  Interpolated
 * linearly in screen space (SR_INTERP_AFFINE) the texture coordinates
 * bend at the triangles' shared diagonal and the rows of squares do not
 * shrink with distance; perspective-correctly (interpolating u/w, v/w and
 * 1/w, then dividing) the lines stay straight.  Bottom row: a color
 * gradient from the near edge (orange) to the far edge (blue); the white
 * line marks the world-space midpoint, where the color must be the
 * half-way mix.  Screen-space interpolation puts the half-way color at the
 * middle of the *image* of the rectangle instead, much too far away.
 *
 * Panels (row-major): checker affine, checker perspective, gradient
 * affine, gradient perspective. */
#include "cli.h"
#include "demo.h"
#include "demo3d.h"

#include <stdint.h>
#include <stdio.h>

/* The floor: x in [-HX, HX] on y = 0, from z = Z_NEAR to z = Z_FAR. */
#define HX 1.0f
#define Z_NEAR 0.0f
#define Z_FAR (-4.8f)
#define CELLS_X 5.0f  /* checker squares across; 0.4 x 0.4 world units each */
#define TEX 64        /* texture side: 2 x 2 squares of 32 texels */

static const sr_vec3 NEAR_COLOR = { 1.0f, 0.45f, 0.1f };
static const sr_vec3 FAR_COLOR = { 0.1f, 0.4f, 1.0f };

static sr_result make_checker(sr_context *ctx, sr_texture **out)
{
    static uint8_t px[TEX * TEX * 4];
    for (int y = 0; y < TEX; y++) {
        for (int x = 0; x < TEX; x++) {
            bool light = ((x / (TEX / 2)) ^ (y / (TEX / 2))) & 1;
            uint8_t *p = px + 4 * (y * TEX + x);
            p[0] = light ? 236 : 40;
            p[1] = light ? 226 : 46;
            p[2] = light ? 200 : 58;
            p[3] = 255;
        }
    }
    return sr_make_texture(ctx, &(sr_texture_desc){ .width = TEX, .height = TEX, .pixels = px },
                           out);
}

static sr_result draw_panel(sr_context *ctx, sr_framebuffer *fb, const sr_texture *checker,
                            sr_interpolation interp)
{
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.07f, 0.08f, 0.1f, 1 }, .depth = 1 });
    float aspect = (float)sr_framebuffer_width(fb) / (float)sr_framebuffer_height(fb);
    sr_mat4 view = sr_look_at((sr_vec3){ 0, 1.3f, 2.4f }, (sr_vec3){ 0, -0.3f, -1.9f },
                              (sr_vec3){ 0, 1, 0 });
    sr_mat4 proj = sr_perspective(0.5f, aspect, 0.2f, 20.0f, false);
    float depth = Z_NEAR - Z_FAR, reps_u = CELLS_X / 2, reps_v = reps_u * depth / (2 * HX);
    const float pos[12] = { -HX, 0, Z_NEAR, HX, 0, Z_NEAR, HX, 0, Z_FAR, -HX, 0, Z_FAR };
    const float uv[8] = { 0, 0, reps_u, 0, reps_u, reps_v, 0, reps_v };
    const float rgb[12] = { NEAR_COLOR.x, NEAR_COLOR.y, NEAR_COLOR.z,
                            NEAR_COLOR.x, NEAR_COLOR.y, NEAR_COLOR.z,
                            FAR_COLOR.x,  FAR_COLOR.y,  FAR_COLOR.z,
                            FAR_COLOR.x,  FAR_COLOR.y,  FAR_COLOR.z };
    const uint8_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    sr_draw_desc draw = { .positions = pos, .vertex_count = 4, .indices = idx,
                          .index_type = SR_INDEX_U8, .index_count = 6, .view = &view,
                          .projection = &proj };
    sr_state st = { .shading = SR_SHADING_UNLIT, .interpolation = interp };
    if (checker) {
        draw.texcoords = uv;
        st.texture = checker;
        st.material.diffuse = (sr_vec3){ 1, 1, 1 };
        return sr_draw(ctx, fb, &st, &draw);
    }
    draw.colors = rgb;
    draw.color_size = 3;
    sr_result r = sr_draw(ctx, fb, &st, &draw);
    if (r != SR_OK) {
        return r;
    }
    /* The world-space midpoint of the gradient, as a line on the floor. */
    float zm = 0.5f * (Z_NEAR + Z_FAR);
    const float mid[6] = { -HX, 0, zm, HX, 0, zm };
    sr_state line = { .shading = SR_SHADING_UNLIT, .material.diffuse = { 1, 1, 1 },
                      .depth_test = SR_OFF, .line_width = 2 };
    r = sr_draw(ctx, fb, &line, &(sr_draw_desc){ .primitive = SR_PRIM_LINES,
                                                 .positions = mid, .vertex_count = 2,
                                                 .view = &view, .projection = &proj });
    if (r != SR_OK) {
        return r;
    }
    sr_point2 at;
    if (demo3d_project(&proj, &view, 0, 0, (float)sr_framebuffer_width(fb),
                       (float)sr_framebuffer_height(fb), (sr_vec3){ 0, 0, zm }, &at)) {
        const char *text = "world-space midpoint";
        sr_draw_text(ctx, fb, (int)at.x - sr_text_width(text, 1) / 2, (int)at.y - 13, 1, text,
                     (sr_rgba){ 1, 1, 1, 1 });
    }
    return SR_OK;
}

int demo_perspective(sr_context *ctx, const demo_args *args, sr_framebuffer **out)
{
    static const char *const labels[4] = {
        "checker: affine", "checker: perspective", "gradient: affine", "gradient: perspective",
    };
    demo3d d;
    int status = demo3d_begin(&d, ctx, "perspective", DEMO3D_LAYOUT_PERSPECTIVE, args->scale,
                              labels, 4);
    if (status != EXIT_OK) {
        return status;
    }
    sr_framebuffer *fb = NULL;
    sr_texture *checker = NULL;
    if (demo3d_panel(&d, SR_DEPTH_D24, &fb) != SR_OK || make_checker(ctx, &checker) != SR_OK) {
        sr_destroy_framebuffer(ctx, fb);
        return demo3d_fail(&d);
    }
    for (int i = 0; i < 4; i++) {
        sr_interpolation interp = i % 2 ? SR_INTERP_PERSPECTIVE : SR_INTERP_AFFINE;
        if (draw_panel(ctx, fb, i < 2 ? checker : NULL, interp) != SR_OK) {
            sr_destroy_texture(ctx, checker);
            sr_destroy_framebuffer(ctx, fb);
            return demo3d_fail(&d);
        }
        demo3d_blit(&d, i, fb, labels[i]);
    }
    sr_destroy_texture(ctx, checker);
    sr_destroy_framebuffer(ctx, fb);
    return demo3d_finish(&d, out);
}
