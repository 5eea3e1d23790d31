/* checker.c - a procedural checkerboard through softrast's programmable
 * stages: a floor plane receding to the horizon whose squares are
 * computed per fragment from the interpolated world position, filtered by
 * the quad's screen-space derivatives so the far squares fade to gray
 * instead of aliasing.  Writes checker.png (or argv[1]).
 *
 * The fragment shader runs on a 2x2 quad: lane differences of a varying
 * are its derivatives (docs/shaders.md), which is what makes the
 * filtering possible without any texture. */
#include "softrast.h"
#include "softrast_io.h"

#include <math.h>
#include <stdio.h>

typedef struct checker_uniforms {
    sr_mat4 mvp;
    float squares_per_unit;
} checker_uniforms;

/* Varyings: 0, 1 the world x and z, scaled to squares. */
static void checker_vertex(const void *uniforms, const sr_vertex_input *in, float clip[4],
                           float *vary)
{
    const checker_uniforms *u = uniforms;
    sr_vec4 c = sr_mat4_mul_vec4(&u->mvp, (sr_vec4){ in->position[0], in->position[1],
                                                     in->position[2], 1.0f });
    clip[0] = c.x, clip[1] = c.y, clip[2] = c.z, clip[3] = c.w;
    vary[0] = in->position[0] * u->squares_per_unit;
    vary[1] = in->position[2] * u->squares_per_unit;
}

/* The box-filtered checker: the integral of the square wave over a
 * footprint of width w around x, in closed form. */
static float filtered_square(float x, float w)
{
    float h = 0.5f * w;
    float a = x - h, b = x + h;
    /* Integral of the 0/1 square wave of period 2 from 0 to t. */
    float ia = floorf(a * 0.5f) + fmaxf(a - 2.0f * floorf(a * 0.5f) - 1.0f, 0.0f);
    float ib = floorf(b * 0.5f) + fmaxf(b - 2.0f * floorf(b * 0.5f) - 1.0f, 0.0f);
    return (ib - ia) / w;
}

static void checker_fragment(const void *uniforms, sr_fragment_quad *q)
{
    (void)uniforms;
    /* Derivatives from the quad: one footprint for its four lanes. */
    float dx = fabsf(q->varyings[0][1] - q->varyings[0][0]) +
               fabsf(q->varyings[0][2] - q->varyings[0][0]);
    float dz = fabsf(q->varyings[1][1] - q->varyings[1][0]) +
               fabsf(q->varyings[1][2] - q->varyings[1][0]);
    float wx = fmaxf(dx, 1e-4f), wz = fmaxf(dz, 1e-4f);
    for (int i = 0; i < 4; i++) {
        float sx = filtered_square(q->varyings[0][i], wx);
        float sz = filtered_square(q->varyings[1][i], wz);
        /* XOR of the two square waves, kept in [0, 1] as a blend. */
        float t = sx + sz - 2.0f * sx * sz;
        float dark[3] = { 0.16f, 0.2f, 0.3f }, light[3] = { 0.92f, 0.88f, 0.78f };
        for (int k = 0; k < 3; k++) {
            q->color[k][i] = dark[k] + (light[k] - dark[k]) * t;
        }
        q->color[3][i] = 1.0f;
    }
}

int main(int argc, char **argv)
{
    const char *out = argc > 1 ? argv[1] : "checker.png";
    enum { W = 640, H = 360 };
    sr_context *ctx = NULL;
    sr_framebuffer *fb = NULL;
    sr_result r = sr_make_context(NULL, &ctx);
    if (r == SR_OK) {
        r = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &fb);
    }
    if (r != SR_OK) {
        fprintf(stderr, "checker: %s\n", ctx ? sr_context_error(ctx) : sr_result_text(r));
        return 1;
    }
    /* A floor 400 units deep, two triangles. */
    const float floor_xyz[] = { -200, 0, 5, 200, 0, 5, 200, 0, -395,
                                -200, 0, 5, 200, 0, -395, -200, 0, -395 };
    sr_mat4 view = sr_look_at((sr_vec3){ 0, 1.5f, 4 }, (sr_vec3){ 0, 0.9f, -6 },
                              (sr_vec3){ 0, 1, 0 });
    sr_mat4 proj = sr_perspective(0.9f, (float)W / H, 0.1f, 500.0f, false);
    checker_uniforms u = { .squares_per_unit = 1.0f };
    u.mvp = sr_mat4_mul(&proj, &view);
    sr_program checker = { .vertex = checker_vertex, .fragment = checker_fragment,
                           .uniforms = &u, .varying_count = 2 };

    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.55f, 0.7f, 0.85f, 1 } });
    r = sr_draw(ctx, fb, &(sr_state){ .program = &checker },
                &(sr_draw_desc){ .positions = floor_xyz, .vertex_count = 6 });
    sr_io_error err;
    if (r == SR_OK) {
        r = sr_write_png(out, W, H, sr_framebuffer_pixels(fb), W * 4, NULL, &err);
        if (r != SR_OK) {
            fprintf(stderr, "checker: %s\n", err.message);
        }
    } else {
        fprintf(stderr, "checker: %s\n", sr_context_error(ctx));
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
    return r == SR_OK ? 0 : 1;
}
