/* demo_normals.c - `softrast demo normals`: why normals are transformed
 * by the inverse transpose M^-T of the modelling matrix
 * (a normal N and a tangent P must stay perpendicular, (QN)^T (MP) = 0,
 * which gives Q = (M^-1)^T).
 *
 * A unit sphere scaled non-uniformly (an ellipsoid: 1.9 x 0.75 x 1) and
 * tilted.  Transforming its normals by M itself stretches them along the
 * long axis - the same way the surface is stretched - so they lean away
 * from the surface: the shading comes out as if the ellipsoid were rounder
 * than it is, the highlight slides and the terminator is in the wrong
 * place.  The yellow whiskers show the normals used at the vertices on the
 * silhouette: on the right they stand perpendicular to the outline.
 *
 * The library always does the right thing: given sr_draw_desc.model = M
 * it transforms normals by the inverse transpose of E * M_O's upper 3x3
 * (sr_normal_matrix).  So the right-hand panels simply pass M, and the
 * wrong left-hand panels are made here in the demo: the positions are
 * pre-transformed by M on the CPU, the normals by M too (renormalized),
 * and both drawn with an identity model matrix.
 *
 * Panels (row-major): Phong-lit by M (wrong), by M^-T (right); the
 * eye-space normals as colors (SR_SHADING_NORMALS) by M, by M^-T. */
#include "cli.h"
#include "demo.h"
#include "demo3d.h"

#include <stdint.h>
#include <stdio.h>

#define STACKS 24
#define SLICES 48
#define NV DEMO3D_SPHERE_VERTICES(STACKS, SLICES)
#define NI DEMO3D_SPHERE_INDICES(STACKS, SLICES)
#define WHISKER 0.4f

static const sr_vec3 EYE = { 0, 0.6f, 5 };

typedef struct scene {
    float pos[3 * NV], nrm[3 * NV];          /* the unit sphere, object space */
    float pos_m[3 * NV], nrm_m[3 * NV];      /* pre-transformed by M, normals by M (wrong) */
    uint32_t idx[NI];
    sr_mat4 model;                           /* M = R S */
    sr_mat4 normal_matrix;                   /* M^-T, for the whiskers */
} scene;

static sr_vec3 mul3(const sr_mat4 *m, const float *v, float w)
{
    sr_vec4 r = sr_mat4_mul_vec4(m, (sr_vec4){ v[0], v[1], v[2], w });
    return (sr_vec3){ r.x, r.y, r.z };
}

static void build(scene *s)
{
    demo3d_sphere(STACKS, SLICES, s->pos, s->nrm, s->idx);
    sr_mat4 scale = sr_mat4_scale(1.9f, 0.75f, 1.0f);
    sr_mat4 tilt = sr_mat4_rotate(0.6f, (sr_vec3){ 0, 0, 1 });
    sr_mat4 turn = sr_mat4_rotate(-0.45f, (sr_vec3){ 0, 1, 0 });
    sr_mat4 rot = sr_mat4_mul(&turn, &tilt);
    s->model = sr_mat4_mul(&rot, &scale);
    sr_normal_matrix(&s->model, &s->normal_matrix);
    for (int i = 0; i < NV; i++) {
        sr_vec3 p = mul3(&s->model, s->pos + 3 * i, 1);
        /* the mistake: a normal is not a point or a tangent, M is not its
         * transform */
        sr_vec3 n = sr_vec3_normalize(mul3(&s->model, s->nrm + 3 * i, 0));
        float pp[3] = { p.x, p.y, p.z }, nn[3] = { n.x, n.y, n.z };
        for (int k = 0; k < 3; k++) {
            s->pos_m[3 * i + k] = pp[k];
            s->nrm_m[3 * i + k] = nn[k];
        }
    }
}

static sr_result draw_panel(sr_context *ctx, sr_framebuffer *fb, const scene *s, bool right,
                            sr_shading shading)
{
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.07f, 0.08f, 0.1f, 1 }, .depth = 1 });
    float aspect = (float)sr_framebuffer_width(fb) / (float)sr_framebuffer_height(fb);
    sr_mat4 view = sr_look_at(EYE, (sr_vec3){ 0, 0, 0 }, (sr_vec3){ 0, 1, 0 });
    sr_mat4 proj = sr_perspective(0.7f, aspect, 1, 20, false);
    sr_state st = {
        .shading = shading,
        .cull = SR_CULL_BACK,
        .ambient = { 0.1f, 0.1f, 0.1f },
        .material = { .diffuse = { 0.85f, 0.55f, 0.3f }, .specular = { 0.7f, 0.7f, 0.7f },
                      .shininess = 40 },
        .lights[0] = { .type = SR_LIGHT_DIRECTIONAL, .vector = { 0.8f, -0.7f, -1 } },
    };
    sr_draw_desc draw = { .vertex_count = NV, .indices = s->idx, .index_type = SR_INDEX_U32,
                          .index_count = NI, .view = &view, .projection = &proj };
    if (right) {
        draw.positions = s->pos;
        draw.normals = s->nrm;
        draw.model = &s->model; /* the library applies M^-T to the normals */
    } else {
        draw.positions = s->pos_m;
        draw.normals = s->nrm_m;
    }
    sr_result r = sr_draw(ctx, fb, &st, &draw);
    if (r != SR_OK) {
        return r;
    }
    /* Whiskers: the normal each panel used, at the vertices on the
     * silhouette (where the right normal is perpendicular to the line of
     * sight, so it lies in the image plane and its angle to the outline
     * shows), from the surface outwards. */
    float lines[2 * 3 * NV];
    size_t n = 0;
    for (int v = 0; v < NV; v++) {
        const float *p = s->pos_m + 3 * v;
        sr_vec3 good = sr_vec3_normalize(mul3(&s->normal_matrix, s->nrm + 3 * v, 0));
        sr_vec3 sight = sr_vec3_normalize(sr_vec3_sub((sr_vec3){ p[0], p[1], p[2] }, EYE));
        float facing = sr_vec3_dot(good, sight);
        if (v % 2 != 0 || facing < -0.1f || facing > 0.1f) {
            continue;
        }
        sr_vec3 nv = right ? good : (sr_vec3){ s->nrm_m[3 * v], s->nrm_m[3 * v + 1],
                                               s->nrm_m[3 * v + 2] };
        float seg[6] = { p[0], p[1], p[2], p[0] + WHISKER * nv.x, p[1] + WHISKER * nv.y,
                         p[2] + WHISKER * nv.z };
        for (int k = 0; k < 6; k++) {
            lines[n++] = seg[k];
        }
    }
    sr_state wst = { .shading = SR_SHADING_UNLIT, .material.diffuse = { 1.0f, 0.9f, 0.2f },
                     .depth_func = SR_LEQUAL, .smooth_lines = true, .line_width = 1.5f };
    return sr_draw(ctx, fb, &wst, &(sr_draw_desc){ .primitive = SR_PRIM_LINES,
                                                   .positions = lines, .vertex_count = n / 3,
                                                   .view = &view, .projection = &proj });
}

int demo_normals(sr_context *ctx, const demo_args *args, sr_framebuffer **out)
{
    static const char *const labels[4] = {
        "lit: by M (wrong)", "lit: by M^-T (right)", "as color: by M", "as color: by M^-T",
    };
    static scene s; /* ~50 KB of vertices: not on the stack */
    build(&s);
    demo3d d;
    int status = demo3d_begin(&d, ctx, "normals", DEMO3D_LAYOUT_NORMALS, args->scale, labels, 4);
    if (status != EXIT_OK) {
        return status;
    }
    sr_framebuffer *fb = NULL;
    if (demo3d_panel(&d, SR_DEPTH_D24, &fb) != SR_OK) {
        return demo3d_fail(&d);
    }
    for (int i = 0; i < 4; i++) {
        if (draw_panel(ctx, fb, &s, i % 2 == 1, i < 2 ? SR_SHADING_PHONG : SR_SHADING_NORMALS) !=
            SR_OK) {
            sr_destroy_framebuffer(ctx, fb);
            return demo3d_fail(&d);
        }
        demo3d_blit(&d, i, fb, labels[i]);
    }
    sr_destroy_framebuffer(ctx, fb);
    return demo3d_finish(&d, out);
}
