/* vertex.c - the vertex stage (geometry): object coordinates to clip space
 * with M = P E M_O, normals to eye space with the inverse transpose of E M_O
 * (renormalized), per-vertex lighting for Gouraud, and the varyings each
 * shading model interpolates.  Reads the caller's arrays; writes
 * sr_clip_vertex records.  Any thread (it touches only its own range). */
#include "pipeline.h"

#include <math.h>
#include <string.h>

static const float *element(const float *base, size_t stride, size_t count, size_t i)
{
    size_t step = stride ? stride : count * sizeof(float);
    return (const float *)((const char *)base + i * step);
}

/* Two-sided lighting: turn the normal n toward the viewer at eye-space
 * position eye (toward +z under an orthographic projection). */
static void face_viewer(const sr_draw_state *ds, const float eye[3], float n[3])
{
    float vdir[3] = { 0, 0, 1 };
    if (ds->local_viewer) {
        vdir[0] = -eye[0];
        vdir[1] = -eye[1];
        vdir[2] = -eye[2];
    }
    if (n[0] * vdir[0] + n[1] * vdir[1] + n[2] * vdir[2] < 0.0f) {
        n[0] = -n[0];
        n[1] = -n[1];
        n[2] = -n[2];
    }
}

static void transform_point(const sr_mat4 *m, const float p[4], float out[4])
{
    const float *a = m->m;
    for (int r = 0; r < 4; r++) {
        out[r] = a[r] * p[0] + a[4 + r] * p[1] + a[8 + r] * p[2] + a[12 + r] * p[3];
    }
}

static void normal_to_eye(const sr_mat4 *nm, const float n[3], float out[3])
{
    const float *a = nm->m;
    float x = a[0] * n[0] + a[4] * n[1] + a[8] * n[2];
    float y = a[1] * n[0] + a[5] * n[1] + a[9] * n[2];
    float z = a[2] * n[0] + a[6] * n[1] + a[10] * n[2];
    /* The inverse transpose keeps normals perpendicular but not unit
     * length: renormalize. */
    float len = sqrtf(x * x + y * y + z * z);
    float s = len > 0.0f ? 1.0f / len : 0.0f;
    out[0] = x * s;
    out[1] = y * s;
    out[2] = z * s;
}

/* The clip outcode of a transformed vertex, and for a vertex inside every
 * plane its window position: divided and snapped once, here (the
 * post-transform cache). */
static void classify(const sr_draw_state *ds, sr_vertex_post *v)
{
    if (!(isfinite(v->pos[0]) && isfinite(v->pos[1]) && isfinite(v->pos[2]) &&
          isfinite(v->pos[3]))) {
        v->outcode = SR_OUTCODE_NONFINITE;
        return;
    }
    v->outcode = sr__clip_outcode(ds, v->pos);
    if (v->outcode == 0) {
        sr__project(ds, v->pos, &v->x_q8, &v->y_q8, &v->z, &v->inv_w);
    }
}

/* The programmable vertex stage: the vertex shader gets the arrays at
 * the vertex and writes the clip position and the varyings. */
static void program_stage(const sr_draw_state *ds, const sr_draw_desc *d, size_t first,
                          size_t count, sr_vertex_post *post, float *vary_out)
{
    const sr_program *pr = ds->program;
    int psize = d->position_size ? d->position_size : 3;
    int csize = d->color_size ? d->color_size : 4;
    int gsize = d->generic_size ? d->generic_size : 4;
    for (size_t i = first; i < first + count; i++) {
        sr_vertex_input in = { .index = (uint32_t)i, .position = { 0, 0, 0, 1 },
                               .color = { 0, 0, 0, 1 }, .generic = { 0, 0, 0, 1 } };
        memcpy(in.position, element(d->positions, d->position_stride, (size_t)psize, i),
               (size_t)psize * sizeof(float));
        in.has_normal = d->normals != NULL;
        in.has_color = d->colors != NULL;
        in.has_texcoord = d->texcoords != NULL;
        in.has_generic = d->generic != NULL;
        if (d->normals) {
            memcpy(in.normal, element(d->normals, d->normal_stride, 3, i), sizeof in.normal);
        }
        if (d->colors) {
            memcpy(in.color, element(d->colors, d->color_stride, (size_t)csize, i),
                   (size_t)csize * sizeof(float));
        }
        if (d->texcoords) {
            memcpy(in.texcoord, element(d->texcoords, d->texcoord_stride, 2, i),
                   sizeof in.texcoord);
        }
        if (d->generic) {
            memcpy(in.generic, element(d->generic, d->generic_stride, (size_t)gsize, i),
                   (size_t)gsize * sizeof(float));
        }
        sr_vertex_post *v = &post[i];
        float *vary = vary_out + i * (size_t)ds->nvary;
        float clip[4] = { 0, 0, 0, 1 };
        pr->vertex(pr->uniforms, &in, clip, vary);
        memcpy(v->pos, clip, sizeof clip);
        classify(ds, v);
    }
}

/* One vertex of a built-in model: the clip position and the model's
 * varyings (pipeline.h's layouts).  color: RGBA, or NULL for the
 * material's; normal, texcoord, generic: NULL when absent (generic is
 * already widened to four components). */
void sr__vertex_shade(const sr_draw_state *ds, const float obj[4], const float *normal,
                      const float *color_in, const float *texcoord, const float *generic,
                      const sr_mat4 *mvp, const sr_mat4 *mv, const sr_mat4 *nm, float clip[4],
                      float *vary)
{
    bool need_eye = ds->shading == SR_SHADING_FLAT || ds->shading == SR_SHADING_PHONG ||
                    ds->shading == SR_SHADING_GOURAUD;
    bool need_normal = ds->shading == SR_SHADING_PHONG || ds->shading == SR_SHADING_GOURAUD ||
                       ds->shading == SR_SHADING_NORMALS;
    bool need_color = ds->shading != SR_SHADING_NORMALS && ds->shading != SR_SHADING_DEPTH;
    transform_point(mvp, obj, clip);

    float eye[4] = { 0, 0, 0, 1 }, n[3] = { 0, 0, 1 }, color[4];
    if (need_eye) {
        transform_point(mv, obj, eye);
        if (eye[3] != 1.0f && eye[3] != 0.0f) {
            eye[0] /= eye[3];
            eye[1] /= eye[3];
            eye[2] /= eye[3];
        }
    }
    if (need_normal && normal) {
        normal_to_eye(nm, normal, n);
    }
    if (need_color) {
        if (ds->use_vertex_color && color_in) {
            color[0] = color_in[0];
            color[1] = color_in[1];
            color[2] = color_in[2];
            color[3] = color_in[3] * ds->diffuse[3];
        } else {
            color[0] = ds->diffuse[0];
            color[1] = ds->diffuse[1];
            color[2] = ds->diffuse[2];
            color[3] = ds->diffuse[3];
        }
    }

    if (ds->uv_index >= 0 && texcoord) {
        vary[ds->uv_index] = texcoord[0];
        vary[ds->uv_index + 1] = texcoord[1];
    }
    switch (ds->shading) {
    case SR_SHADING_UNLIT:
        for (int k = 0; k < 4; k++) {
            vary[SR_VARY_COLOR + k] = color[k];
        }
        break;
    case SR_SHADING_GOURAUD: {
        /* Gouraud: light once per vertex; the rasterizer interpolates the
         * resulting colors.  Two-sided: light the side that faces the eye. */
        if (ds->two_sided) {
            face_viewer(ds, eye, n);
        }
        sr__light(ds, n, eye, color, &vary[SR_VARY_COLOR]);
        break;
    }
    case SR_SHADING_FLAT:
        for (int k = 0; k < 3; k++) {
            vary[SR_VARY_FLAT_EYE + k] = eye[k];
        }
        for (int k = 0; k < 4; k++) {
            vary[SR_VARY_FLAT_COLOR + k] = color[k];
        }
        break;
    case SR_SHADING_PHONG:
        for (int k = 0; k < 3; k++) {
            vary[SR_VARY_PHONG_NORMAL + k] = n[k];
            vary[SR_VARY_PHONG_EYE + k] = eye[k];
        }
        for (int k = 0; k < 4; k++) {
            vary[SR_VARY_PHONG_COLOR + k] = color[k];
        }
        break;
    case SR_SHADING_DEPTH:
        vary[SR_VARY_DEPTH_W] = clip[3];
        break;
    case SR_SHADING_ATTRIBUTE:
        memcpy(&vary[SR_VARY_ATTRIBUTE], generic, 4 * sizeof(float));
        break;
    case SR_SHADING_NORMALS:
        for (int k = 0; k < 3; k++) {
            vary[SR_VARY_NORMAL + k] = n[k];
        }
        break;
    default:
        break;
    }
}

void sr__vertex_stage(const sr_draw_state *ds, const sr_draw_desc *d,
                      const sr_mat4 *mvp, const sr_mat4 *mv, const sr_mat4 *nm,
                      size_t first, size_t count, sr_vertex_post *post, float *vary_out)
{
    if (ds->program) {
        program_stage(ds, d, first, count, post, vary_out);
        return;
    }
    int psize = d->position_size ? d->position_size : 3;
    int csize = d->color_size ? d->color_size : 4;
    int gsize = d->generic_size ? d->generic_size : 4;
    for (size_t i = first; i < first + count; i++) {
        sr_vertex_post *v = &post[i];
        float *vary = vary_out + i * (size_t)ds->nvary;
        const float *p = element(d->positions, d->position_stride, (size_t)psize, i);
        float obj[4] = { p[0], p[1], p[2], psize == 4 ? p[3] : 1.0f };
        float color[4], generic[4];
        const float *cp = NULL, *gp = NULL;
        if (d->colors) {
            const float *c = element(d->colors, d->color_stride, (size_t)csize, i);
            color[0] = c[0];
            color[1] = c[1];
            color[2] = c[2];
            color[3] = csize == 4 ? c[3] : 1.0f;
            cp = color;
        }
        if (ds->shading == SR_SHADING_ATTRIBUTE) {
            /* Missing components read as 0, alpha as 1; one component
             * is shown as gray. */
            const float *g = element(d->generic, d->generic_stride, (size_t)gsize, i);
            float out[4] = { g[0], gsize > 1 ? g[1] : (gsize == 1 ? g[0] : 0.0f),
                             gsize > 2 ? g[2] : (gsize == 1 ? g[0] : 0.0f),
                             gsize > 3 ? g[3] : 1.0f };
            memcpy(generic, out, sizeof out);
            gp = generic;
        }
        sr__vertex_shade(ds, obj, d->normals ? element(d->normals, d->normal_stride, 3, i) : NULL,
                         cp, d->texcoords ? element(d->texcoords, d->texcoord_stride, 2, i) : NULL,
                         gp, mvp, mv, nm, v->pos, vary);
        classify(ds, v);
    }
}

/* Flat shading: one color per triangle, lit with the face normal (for a
 * triangle, Newell's method reduces to the cross product of two edges) at
 * the provoking vertex, whose color it takes. */
void sr__flat_color(const sr_draw_state *ds, const float *v0, const float *v1,
                    const float *v2, const float *pv, float out[4])
{
    const float *p0 = &v0[SR_VARY_FLAT_EYE];
    const float *p1 = &v1[SR_VARY_FLAT_EYE];
    const float *p2 = &v2[SR_VARY_FLAT_EYE];
    float e1[3] = { p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2] };
    float e2[3] = { p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2] };
    float n[3] = { e1[1] * e2[2] - e1[2] * e2[1],
                   e1[2] * e2[0] - e1[0] * e2[2],
                   e1[0] * e2[1] - e1[1] * e2[0] };
    float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len > 0.0f) {
        n[0] /= len;
        n[1] /= len;
        n[2] /= len;
    }
    const float *eye = &pv[SR_VARY_FLAT_EYE];
    if (ds->two_sided) {
        face_viewer(ds, eye, n);
    }
    sr__light(ds, n, eye, &pv[SR_VARY_FLAT_COLOR], out);
}
