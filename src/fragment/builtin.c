/* builtin.c - the built-in shading models as programs (fragment stage):
 * unlit, flat, Gouraud, Phong, normals and depth, textured or not,
 * written against the public vertex- and fragment-shader interface.
 *
 * They call the same per-vertex code (sr__vertex_shade) and the same
 * per-fragment code (sr__shade_vary) as the fixed-function paths, with
 * the state resolved once into the uniforms, so a draw through them gives
 * the built-in pixels: exactly for unlit, Gouraud, Phong, normals and
 * depth; flat shading and trilinear filtering differ within rounding,
 * because a program takes the face normal and the level of detail from
 * the quad's lane differences where the fixed path uses the triangle's
 * vertices and exact per-pixel steps.  sr_draw keeps its specialized fast
 * paths for the built-in models; these programs are the same models in
 * the programmable form, for users to start from and for tests. */
#include "fragment/fragment.h"
#include "context.h"
#include "pipeline.h"

#include <math.h>
#include <string.h>

struct sr_builtin {
    sr_program program;
    sr_draw_state ds;                 /* the shading half (sr__resolve_shading) */
    sr_mat4 mvp, mv, nm;
};

static void builtin_vs(const void *uniforms, const sr_vertex_input *in, float clip[4],
                       float *vary)
{
    const sr_builtin *b = uniforms;
    const sr_draw_state *ds = &b->ds;
    sr__vertex_shade(ds, in->position, in->has_normal ? in->normal : NULL,
                     in->has_color ? in->color : NULL, in->has_texcoord ? in->texcoord : NULL,
                     in->generic, &b->mvp, &b->mv, &b->nm, clip, vary);
    if (ds->shading == SR_SHADING_FLAT) {
        /* A smooth copy of the eye position after the model's varyings:
         * its lane differences give the face normal. */
        memcpy(&vary[ds->nvary], &vary[SR_VARY_FLAT_EYE], 3 * sizeof(float));
    }
}

/* Flat shading in a quad: the face normal from the smooth eye position's
 * lane differences (its screen-space derivatives), facing the viewer as
 * the triangle's own normal does, lit at the provoking vertex's eye
 * position with its color (flat varyings), as sr__flat_color lights. */
static void flat_color(const sr_draw_state *ds, const sr_fragment_quad *q, float out[4])
{
    float dx[3], dy[3], eye[3];
    for (int k = 0; k < 3; k++) {
        const float *e = q->varyings[ds->nvary + k];
        dx[k] = e[1] - e[0];
        dy[k] = e[2] - e[0];
        eye[k] = q->varyings[SR_VARY_FLAT_EYE + k][0];
    }
    /* Screen y points down: dx x dy points away from the viewer. */
    float n[3] = { dy[1] * dx[2] - dy[2] * dx[1], dy[2] * dx[0] - dy[0] * dx[2],
                   dy[0] * dx[1] - dy[1] * dx[0] };
    float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len > 0.0f) {
        for (int k = 0; k < 3; k++) {
            n[k] /= len;
        }
    }
    if (!q->front && ds->two_sided) {
        /* sr__flat_color turns the normal toward the viewer for two-sided
         * lighting; the derivative normal already faces it. */
    } else if (!q->front) {
        for (int k = 0; k < 3; k++) {
            n[k] = -n[k];
        }
    }
    float color[4];
    for (int k = 0; k < 4; k++) {
        color[k] = q->varyings[SR_VARY_FLAT_COLOR + k][0];
    }
    sr__light(ds, n, eye, color, out);
}

static void builtin_fs(const void *uniforms, sr_fragment_quad *q)
{
    const sr_builtin *b = uniforms;
    const sr_draw_state *ds = &b->ds;
    float flat[4] = { 0, 0, 0, 1 };
    if (ds->shading == SR_SHADING_FLAT) {
        flat_color(ds, q, flat);
    }
    float lod = 0.0f;
    if (ds->texture && ds->texture_filter == SR_FILTER_TRILINEAR) {
        const float (*u)[4] = &q->varyings[ds->uv_index];
        lod = sr__texture_lod(ds->texture, u[0][1] - u[0][0], u[1][1] - u[1][0],
                              u[0][2] - u[0][0], u[1][2] - u[1][0]);
    }
    for (int i = 0; i < 4; i++) {
        float v[SR_MAX_VARYINGS], c[4];
        for (int k = 0; k < ds->nvary; k++) {
            v[k] = q->varyings[k][i];
        }
        sr__shade_vary(ds, v, flat, q->front, q->z[i], lod, c, ds->shading);
        for (int k = 0; k < 4; k++) {
            q->color[k][i] = c[k];
        }
    }
}

sr_result sr_make_builtin_program(sr_context *ctx, const sr_state *state, const sr_mat4 *model,
                                  const sr_mat4 *view, const sr_mat4 *projection,
                                  sr_builtin **out)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_make_builtin_program: ctx is NULL");
    }
    if (!state || !out) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_make_builtin_program: %s is NULL",
                        state ? "out" : "state");
    }
    *out = NULL;
    if (state->program) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_make_builtin_program: the state already has a program");
    }
    if ((unsigned)state->shading > SR_SHADING_DEPTH) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_make_builtin_program: shading %d has no program form",
                        (int)state->shading);
    }
    const sr_mat4 *mats[3] = { model, view, projection };
    static const char *const names[3] = { "model", "view", "projection" };
    for (int i = 0; i < 3; i++) {
        for (int k = 0; mats[i] && k < 16; k++) {
            if (!isfinite(mats[i]->m[k])) {
                return sr__fail(ctx, SR_INVALID_ARG,
                                "sr_make_builtin_program: %s has a NaN or infinite entry",
                                names[i]);
            }
        }
    }
    /* The state is checked as sr_draw checks it: what the program bakes
     * in (lights, material, texture modes) is read by every fragment. */
    sr_result valid = sr__draw_validate_state(
        ctx, state, &(sr_draw_desc){ .model = model, .view = view, .projection = projection });
    if (valid != SR_OK) {
        return valid;
    }
    sr_builtin *b = sr__calloc(ctx, 1, sizeof *b);
    if (!b) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_make_builtin_program: out of memory");
    }
    sr__resolve_shading(state, view, projection, &b->ds);
    /* Depth arrives in [0, 1] window units: DEPTH shading shows it as is. */
    b->ds.depth_scale = 1.0;
    sr_mat4 mo = model ? *model : sr_mat4_identity();
    sr_mat4 e = view ? *view : sr_mat4_identity();
    sr_mat4 p = projection ? *projection : sr_mat4_identity();
    b->mv = sr_mat4_mul(&e, &mo);
    b->mvp = sr_mat4_mul(&p, &b->mv);
    if (!sr_normal_matrix(&b->mv, &b->nm)) {
        b->nm = b->mv;
    }
    sr_program *pr = &b->program;
    pr->vertex = builtin_vs;
    pr->fragment = builtin_fs;
    pr->uniforms = b;
    pr->varying_count = b->ds.nvary;
    if (b->ds.shading == SR_SHADING_FLAT) {
        /* The provoking vertex's eye position and color, and a smooth
         * copy of the eye position for the face normal. */
        for (int k = 0; k < 7; k++) {
            pr->modes[k] = SR_VARYING_FLAT;
        }
        pr->varying_count += 3;
    }
    if (state->interpolation == SR_INTERP_AFFINE) {
        for (int k = 0; k < pr->varying_count; k++) {
            if (pr->modes[k] == SR_VARYING_SMOOTH) {
                pr->modes[k] = SR_VARYING_NOPERSPECTIVE;
            }
        }
    }
    *out = b;
    sr__ok(ctx);
    return SR_OK;
}

const sr_program *sr_builtin_program(const sr_builtin *b)
{
    return b ? &b->program : NULL;
}

void sr_destroy_builtin_program(sr_context *ctx, sr_builtin *b)
{
    if (ctx && b) {
        sr__free(ctx, b);
    }
}
