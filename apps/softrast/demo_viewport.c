/* demo_viewport.c - `softrast demo viewport`: the aspect ratio
 * (the viewport matrix S maps NDC -1..1 onto the viewport's width
 * and height; the picture keeps its aspect ratio only if the (1,1) and
 * (2,2) entries of S are equal, or if the projection compensates).
 *
 * One scene - a red sphere and a blue cube - in a wide viewport (top row)
 * and a tall one (bottom row), the viewport rectangle outlined on grey:
 *   stretched     - a projection made for a square (aspect 1): S scales x
 *                   and y differently and the sphere becomes an ellipse;
 *   square NDC    - the first strategy: map NDC into a square
 *                   viewport of the smaller dimension, centred; round,
 *                   but the rest of the viewport stays unused;
 *   fov from w, h - the second: derive the x and y fields of view from
 *                   the viewport's width and height (sr_perspective with
 *                   aspect = w/h, and sr_fit_fovy so the wanted field of
 *                   view spans the *smaller* dimension - in the tall
 *                   viewport the vertical one grows): round and filling.
 *
 * Panels (row-major): wide stretched, wide square NDC, wide fov from w,h,
 * then the same for the tall viewport. */
#include "cli.h"
#include "demo.h"
#include "demo3d.h"

#include <stdint.h>
#include <stdio.h>

#define STACKS 20
#define SLICES 40
#define NV DEMO3D_SPHERE_VERTICES(STACKS, SLICES)
#define NI DEMO3D_SPHERE_INDICES(STACKS, SLICES)
#define FOV 0.72f   /* field of view across the smaller dimension, radians */

typedef struct scene {
    float sphere_pos[3 * NV], sphere_nrm[3 * NV];
    uint32_t sphere_idx[NI];
    float cube_pos[72], cube_nrm[72];
    uint8_t cube_idx[36];
} scene;

/* A cube [-1, 1]^3, four vertices per face with the face's normal. */
static void make_cube(scene *s)
{
    static const float axes[6][3] = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 },
                                      { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 } };
    for (int f = 0; f < 6; f++) {
        const float *n = axes[f];
        /* two tangents t1, t2 with t1 x t2 = n, so the corners below wind
         * counter-clockwise seen from outside */
        float t1[3] = { 0, 0, 0 };
        t1[(f / 2 + 1) % 3] = 1;
        float t2[3] = { n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2],
                        n[0] * t1[1] - n[1] * t1[0] };
        static const float corners[4][2] = { { -1, -1 }, { 1, -1 }, { 1, 1 }, { -1, 1 } };
        for (int c = 0; c < 4; c++) {
            int v = f * 4 + c;
            for (int k = 0; k < 3; k++) {
                s->cube_pos[3 * v + k] = n[k] + corners[c][0] * t1[k] + corners[c][1] * t2[k];
                s->cube_nrm[3 * v + k] = n[k];
            }
        }
        uint8_t q[6] = { 0, 1, 2, 0, 2, 3 };
        for (int k = 0; k < 6; k++) {
            s->cube_idx[f * 6 + k] = (uint8_t)(f * 4 + q[k]);
        }
    }
}

typedef enum strategy { STRETCHED, SQUARE_NDC, FIT_FOV } strategy;

static sr_result draw_scene(sr_context *ctx, sr_framebuffer *fb, const scene *s,
                            sr_viewport vp, const sr_mat4 *proj)
{
    sr_mat4 view = sr_look_at((sr_vec3){ 0, 1.4f, 5 }, (sr_vec3){ 0, 0, 0 }, (sr_vec3){ 0, 1, 0 });
    sr_state st = {
        .viewport = vp,
        .shading = SR_SHADING_PHONG,
        .cull = SR_CULL_BACK,
        .ambient = { 0.12f, 0.12f, 0.12f },
        .material = { .diffuse = { 0.85f, 0.12f, 0.1f }, .specular = { 0.6f, 0.6f, 0.6f },
                      .shininess = 50 },
        .lights[0] = { .type = SR_LIGHT_DIRECTIONAL, .vector = { 0.6f, -0.8f, -0.7f } },
    };
    sr_mat4 m_sphere = sr_mat4_translate(-0.95f, 0, 0);
    sr_result r = sr_draw(ctx, fb, &st, &(sr_draw_desc){
        .positions = s->sphere_pos, .normals = s->sphere_nrm, .vertex_count = NV,
        .indices = s->sphere_idx, .index_type = SR_INDEX_U32, .index_count = NI,
        .model = &m_sphere, .view = &view, .projection = proj });
    if (r != SR_OK) {
        return r;
    }
    sr_mat4 t = sr_mat4_translate(1.0f, -0.1f, 0), rot = sr_mat4_rotate(0.55f, (sr_vec3){ 0, 1, 0 });
    sr_mat4 sc = sr_mat4_scale(0.55f, 0.55f, 0.55f);
    sr_mat4 tr = sr_mat4_mul(&t, &rot);
    sr_mat4 m_cube = sr_mat4_mul(&tr, &sc);
    st.material.diffuse = (sr_vec3){ 0.2f, 0.4f, 0.9f };
    return sr_draw(ctx, fb, &st, &(sr_draw_desc){
        .positions = s->cube_pos, .normals = s->cube_nrm, .vertex_count = 24,
        .indices = s->cube_idx, .index_type = SR_INDEX_U8, .index_count = 36,
        .model = &m_cube, .view = &view, .projection = proj });
}

static void fill_rect(sr_context *ctx, sr_framebuffer *fb, sr_viewport r, sr_rgba color)
{
    sr_point2 p[4] = { { r.x, r.y }, { r.x + r.width, r.y }, { r.x + r.width, r.y + r.height },
                       { r.x, r.y + r.height } };
    sr_fill_polygon(ctx, fb, &(sr_polygon2){ p, 4, NULL, 0 }, color, NULL);
}

static sr_result draw_panel(sr_context *ctx, sr_framebuffer *fb, const scene *s, bool wide,
                            strategy how)
{
    int pw = sr_framebuffer_width(fb), ph = sr_framebuffer_height(fb);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.36f, 0.37f, 0.4f, 1 }, .depth = 1 });
    int w = wide ? 216 : 100, h = wide ? 108 : 190;
    sr_viewport vp = { (pw - w) / 2, (ph - h) / 2, w, h };
    const sr_rgba bg = { 0.07f, 0.08f, 0.1f, 1 }, unused = { 0.2f, 0.21f, 0.24f, 1 };
    sr_mat4 proj;
    sr_viewport draw_vp = vp;
    if (how == STRETCHED) {
        fill_rect(ctx, fb, vp, bg);
        proj = sr_perspective(FOV, 1.0f, 1, 20, false);
    } else if (how == SQUARE_NDC) {
        fill_rect(ctx, fb, vp, unused);
        int side = w < h ? w : h;
        draw_vp = (sr_viewport){ vp.x + (w - side) / 2, vp.y + (h - side) / 2, side, side };
        fill_rect(ctx, fb, draw_vp, bg);
        proj = sr_perspective(FOV, 1.0f, 1, 20, false);
    } else {
        fill_rect(ctx, fb, vp, bg);
        proj = sr_perspective(sr_fit_fovy(FOV, w, h), (float)w / (float)h, 1, 20, false);
    }
    sr_result r = draw_scene(ctx, fb, s, draw_vp, &proj);
    if (r != SR_OK) {
        return r;
    }
    /* The viewport's outline, just outside it. */
    sr_path *path = NULL;
    r = sr_make_path(ctx, 0.1, &path);
    if (r != SR_OK) {
        return r;
    }
    sr_path_move_to(path, vp.x - 0.5, vp.y - 0.5);
    sr_path_line_to(path, vp.x + w + 0.5, vp.y - 0.5);
    sr_path_line_to(path, vp.x + w + 0.5, vp.y + h + 0.5);
    sr_path_line_to(path, vp.x - 0.5, vp.y + h + 0.5);
    sr_path_close(path);
    r = sr_stroke_path(ctx, fb, path, (sr_rgba){ 0.95f, 0.85f, 0.4f, 1 },
                       &(sr_stroke_desc){ .width = 1 });
    sr_destroy_path(ctx, path);
    if (r != SR_OK) {
        return r;
    }
    char size[32];
    snprintf(size, sizeof size, "%dx%d", w, h);
    return sr_draw_text(ctx, fb, vp.x, vp.y - 11, 1, size, (sr_rgba){ 0.95f, 0.85f, 0.4f, 1 });
}

int demo_viewport(sr_context *ctx, const demo_args *args, sr_framebuffer **out)
{
    static const char *const labels[6] = {
        "wide: stretched", "wide: square NDC", "wide: fov from w,h",
        "tall: stretched", "tall: square NDC", "tall: fov from w,h",
    };
    static scene s;
    demo3d_sphere(STACKS, SLICES, s.sphere_pos, s.sphere_nrm, s.sphere_idx);
    for (int i = 0; i < 3 * NV; i++) {
        s.sphere_pos[i] *= 0.8f;
    }
    make_cube(&s);
    demo3d d;
    int status = demo3d_begin(&d, ctx, "viewport", DEMO3D_LAYOUT_VIEWPORT, args->scale, labels,
                              6);
    if (status != EXIT_OK) {
        return status;
    }
    sr_framebuffer *fb = NULL;
    if (demo3d_panel(&d, SR_DEPTH_D24, &fb) != SR_OK) {
        return demo3d_fail(&d);
    }
    for (int i = 0; i < 6; i++) {
        if (draw_panel(ctx, fb, &s, i < 3, (strategy)(i % 3)) != SR_OK) {
            sr_destroy_framebuffer(ctx, fb);
            return demo3d_fail(&d);
        }
        demo3d_blit(&d, i, fb, labels[i]);
    }
    sr_destroy_framebuffer(ctx, fb);
    return demo3d_finish(&d, out);
}
