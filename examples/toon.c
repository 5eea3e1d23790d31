/* toon.c - a toon (cel) shader through softrast's programmable stages:
 * the Utah teapot lit in three flat bands with a rim of ink where the
 * surface turns away from the viewer.  Writes toon.png (or argv[1]).
 *
 * The vertex shader transforms the position with the matrices in the
 * uniforms and passes the eye-space normal and position as varyings; the
 * fragment shader quantizes the diffuse term, per fragment, four
 * fragments (a 2x2 quad) per call.  docs/shaders.md walks through it. */
#include "softrast.h"
#include "softrast_io.h"

#include <math.h>
#include <stdio.h>

typedef struct toon_uniforms {
    sr_mat4 mvp, mv, normal_matrix;
    float light[3];             /* unit vector to the light, eye space */
    float base[3];              /* the surface color */
} toon_uniforms;

/* Varyings: 0..2 eye-space normal, 3..5 eye-space position. */
static void toon_vertex(const void *uniforms, const sr_vertex_input *in, float clip[4],
                        float *vary)
{
    const toon_uniforms *u = uniforms;
    sr_vec4 p = { in->position[0], in->position[1], in->position[2], 1.0f };
    sr_vec4 c = sr_mat4_mul_vec4(&u->mvp, p);
    sr_vec4 e = sr_mat4_mul_vec4(&u->mv, p);
    sr_vec4 n = sr_mat4_mul_vec4(&u->normal_matrix,
                                 (sr_vec4){ in->normal[0], in->normal[1], in->normal[2], 0 });
    clip[0] = c.x, clip[1] = c.y, clip[2] = c.z, clip[3] = c.w;
    vary[0] = n.x, vary[1] = n.y, vary[2] = n.z;
    vary[3] = e.x, vary[4] = e.y, vary[5] = e.z;
}

static void toon_fragment(const void *uniforms, sr_fragment_quad *q)
{
    const toon_uniforms *u = uniforms;
    for (int i = 0; i < 4; i++) {
        float n[3] = { q->varyings[0][i], q->varyings[1][i], q->varyings[2][i] };
        float v[3] = { -q->varyings[3][i], -q->varyings[4][i], -q->varyings[5][i] };
        float nl = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        float vl = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        float ndotl = (n[0] * u->light[0] + n[1] * u->light[1] + n[2] * u->light[2]) / nl;
        float ndotv = (n[0] * v[0] + n[1] * v[1] + n[2] * v[2]) / (nl * vl);
        /* Three bands instead of a smooth ramp. */
        float band = ndotl > 0.6f ? 1.0f : ndotl > 0.2f ? 0.65f : 0.35f;
        /* Ink where the surface grazes the line of sight. */
        if (ndotv < 0.25f) {
            band = 0.05f;
        }
        for (int k = 0; k < 3; k++) {
            q->color[k][i] = u->base[k] * band;
        }
        q->color[3][i] = 1.0f;
    }
}

int main(int argc, char **argv)
{
    const char *out = argc > 1 ? argv[1] : "toon.png";
    enum { W = 640, H = 480 };
    sr_context *ctx = NULL;
    sr_framebuffer *fb = NULL;
    sr_mesh teapot = { 0 };
    sr_result r = sr_make_context(NULL, &ctx);
    if (r == SR_OK) {
        r = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                                            .samples = 4 }, &fb);
    }
    if (r == SR_OK) {
        r = sr_make_teapot(ctx, 8, &teapot);
    }
    if (r != SR_OK) {
        fprintf(stderr, "toon: %s\n", ctx ? sr_context_error(ctx) : sr_result_text(r));
        return 1;
    }

    sr_mat4 view = sr_look_at((sr_vec3){ 3.0f, 3.6f, 8.5f }, (sr_vec3){ 0.2f, 1.2f, 0 },
                              (sr_vec3){ 0, 1, 0 });
    sr_mat4 proj = sr_perspective(0.7f, (float)W / H, 0.5f, 50.0f, false);
    toon_uniforms u = { .mv = view, .light = { 0.48f, 0.8f, 0.36f }, .base = { 1.0f, 0.55f, 0.2f } };
    u.mvp = sr_mat4_mul(&proj, &view);
    sr_normal_matrix(&view, &u.normal_matrix);
    sr_program toon = { .vertex = toon_vertex, .fragment = toon_fragment, .uniforms = &u,
                        .varying_count = 6 };

    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.93f, 0.93f, 0.9f, 1 } });
    r = sr_draw(ctx, fb, &(sr_state){ .program = &toon, .cull = SR_CULL_NONE },
                &(sr_draw_desc){ .positions = teapot.positions, .normals = teapot.normals,
                                 .vertex_count = teapot.vertex_count, .indices = teapot.indices,
                                 .index_type = SR_INDEX_U32,
                                 .index_count = teapot.triangle_count * 3 });
    sr_io_error err;
    if (r == SR_OK) {
        r = sr_write_png(out, W, H, sr_framebuffer_pixels(fb), W * 4, NULL, &err);
        if (r != SR_OK) {
            fprintf(stderr, "toon: %s\n", err.message);
        }
    } else {
        fprintf(stderr, "toon: %s\n", sr_context_error(ctx));
    }
    sr_destroy_mesh(ctx, &teapot);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
    return r == SR_OK ? 0 : 1;
}
