/* demo_depth_range.c - `softrast demo depth-range`: the depth range
 * (sr_state.depth_near, depth_far; glDepthRange) maps NDC z onto window
 * depths [near, far], clamped to [0, 1].
 *
 * A red sphere in front of a blue one, and a yellow marker placed behind
 * the red sphere.  Top row: the depth buffer as gray (black 0, white 1;
 * the background is the cleared 1) with the range 0,1 and with 0.25,0.75,
 * where the same scene uses only the middle half of the values.  Bottom
 * row: the range 1,0 with the usual LESS test keeps the farthest surface
 * (the blue sphere shows through the red one); and the range split as an
 * overlay would use it - the marker drawn in 0,0.05 and the spheres in
 * 0.05,1 - so the marker is in front wherever it lies in the scene.
 *
 * Panels (row-major): depth 0,1; depth 0.25,0.75; color 1,0 with LESS;
 * color with the marker in its own range.  Point-sampled (one sample at
 * each pixel centre). */
#include "cli.h"
#include "demo.h"
#include "demo3d.h"

#include <stdlib.h>

#define STACKS 16
#define SLICES 24

typedef struct sphere_mesh {
    float pos[3 * DEMO3D_SPHERE_VERTICES(STACKS, SLICES)];
    float nrm[3 * DEMO3D_SPHERE_VERTICES(STACKS, SLICES)];
    uint32_t idx[DEMO3D_SPHERE_INDICES(STACKS, SLICES)];
} sphere_mesh;

/* One sphere (radius r at c, color rgb) into fb with the given range
 * and depth test. */
static sr_result draw_sphere(sr_context *ctx, sr_framebuffer *fb, const sphere_mesh *m,
                             sr_vec3 c, float r, sr_vec3 rgb, float near, float far,
                             sr_depth_func func)
{
    float aspect = (float)sr_framebuffer_width(fb) / (float)sr_framebuffer_height(fb);
    sr_mat4 proj = sr_perspective(0.7f, aspect, 2.0f, 12.0f, false);
    sr_mat4 model = sr_mat4_translate(c.x, c.y, c.z), s = sr_mat4_scale(r, r, r);
    model = sr_mat4_mul(&model, &s);
    sr_state st = {
        .shading = SR_SHADING_GOURAUD, .depth_range = SR_DEPTH_RANGE_SET, .depth_near = near,
        .depth_far = far, .depth_func = func,
        .ambient = { 0.25f, 0.25f, 0.25f },
        .material = { .diffuse = rgb },
        .lights[0] = { .type = SR_LIGHT_DIRECTIONAL, .vector = { -0.4f, -0.6f, -0.7f } },
    };
    return sr_draw(ctx, fb, &st,
                   &(sr_draw_desc){ .positions = m->pos, .normals = m->nrm,
                                    .vertex_count = DEMO3D_SPHERE_VERTICES(STACKS, SLICES),
                                    .indices = m->idx, .index_type = SR_INDEX_U32,
                                    .index_count = DEMO3D_SPHERE_INDICES(STACKS, SLICES),
                                    .model = &model, .projection = &proj });
}

/* The scene, the spheres in [near, far] and the marker in [mnear, mfar]. */
static sr_result draw_scene(sr_context *ctx, sr_framebuffer *fb, const sphere_mesh *m, float near,
                            float far, float mnear, float mfar, sr_depth_func func)
{
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.07f, 0.08f, 0.1f, 1 },
                                        .depth_action = SR_ACTION_CLEAR,
                                        .depth = func == SR_LESS ? 1.0f : 0.0f });
    sr_result r = draw_sphere(ctx, fb, m, (sr_vec3){ -0.45f, 0, -5 }, 1.0f,
                              (sr_vec3){ 0.9f, 0.25f, 0.2f }, near, far, func);
    if (r == SR_OK) {
        r = draw_sphere(ctx, fb, m, (sr_vec3){ 0.9f, 0.2f, -7.5f }, 1.5f,
                        (sr_vec3){ 0.25f, 0.45f, 1.0f }, near, far, func);
    }
    if (r == SR_OK) {
        r = draw_sphere(ctx, fb, m, (sr_vec3){ -0.8f, 0.35f, -6.8f }, 0.35f,
                        (sr_vec3){ 1.0f, 0.9f, 0.2f }, mnear, mfar, func);
    }
    return r;
}

/* The depth buffer as gray, written over the panel's colors. */
static sr_result depth_as_gray(sr_context *ctx, sr_framebuffer *fb)
{
    int w = sr_framebuffer_width(fb), h = sr_framebuffer_height(fb);
    float *z = malloc(sizeof *z * (size_t)w * (size_t)h);
    uint8_t *px = malloc((size_t)w * (size_t)h * 4);
    sr_result r = z && px ? sr_read_depth(ctx, fb, 0, 0, w, h, z, (size_t)w) : SR_OUT_OF_MEMORY;
    if (r == SR_OK) {
        for (size_t i = 0; i < (size_t)w * (size_t)h; i++) {
            uint8_t g = (uint8_t)(z[i] * 255.0f + 0.5f);
            px[4 * i] = px[4 * i + 1] = px[4 * i + 2] = g;
            px[4 * i + 3] = 255;
        }
        r = sr_write_pixels(ctx, fb, 0, 0, w, h, px, (size_t)w * 4);
    }
    free(z);
    free(px);
    return r;
}

int demo_depth_range(sr_context *ctx, const demo_args *args, sr_framebuffer **out)
{
    static const char *const labels[4] = {
        "depth, range 0,1", "depth, range 0.25,0.75",
        "range 1,0, test LESS", "marker in 0,0.05, spheres 0.05,1",
    };
    demo3d d;
    int status = demo3d_begin(&d, ctx, "depth-range", DEMO3D_LAYOUT_DEPTH_RANGE, args->scale,
                              labels, 4);
    if (status != EXIT_OK) {
        return status;
    }
    sr_framebuffer *fb = NULL;
    sphere_mesh *m = malloc(sizeof *m);
    if (!m || demo3d_panel(&d, SR_DEPTH_D24, &fb) != SR_OK) {
        free(m);
        return demo3d_fail(&d);
    }
    demo3d_sphere(STACKS, SLICES, m->pos, m->nrm, m->idx);
    sr_result r = draw_scene(ctx, fb, m, 0, 1, 0, 1, SR_LESS);
    r = r == SR_OK ? depth_as_gray(ctx, fb) : r;
    demo3d_blit(&d, 0, fb, labels[0]);
    r = r == SR_OK ? draw_scene(ctx, fb, m, 0.25f, 0.75f, 0.25f, 0.75f, SR_LESS) : r;
    r = r == SR_OK ? depth_as_gray(ctx, fb) : r;
    demo3d_blit(&d, 1, fb, labels[1]);
    r = r == SR_OK ? draw_scene(ctx, fb, m, 1, 0, 1, 0, SR_LESS) : r;
    demo3d_blit(&d, 2, fb, labels[2]);
    r = r == SR_OK ? draw_scene(ctx, fb, m, 0.05f, 1, 0, 0.05f, SR_LESS) : r;
    demo3d_blit(&d, 3, fb, labels[3]);
    sr_destroy_framebuffer(ctx, fb);
    free(m);
    return r == SR_OK ? demo3d_finish(&d, out) : demo3d_fail(&d);
}
