/* vertex.c - the vertex stage (geometry): object coordinates to clip space
 * with M = P E M_O, normals to eye space with the inverse transpose of E M_O
 * (renormalized), per-vertex lighting for Gouraud, and the varyings each
 * shading model interpolates.  Reads the caller's arrays; writes
 * sr_clip_vertex records.  Any thread (it touches only its own range). */
#include "pipeline.h"
#include "fragment/light_lanes.h"

#include <math.h>
#include <string.h>
#include <stddef.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

static const float *element(const float *base, size_t stride, size_t count, size_t i)
{
    return (const float *)((const char *)base + i * sr__attr_step(stride, count));
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

/* out = m p, column by column: lane r computes m[r] p0 + m[4 + r] p1 +
 * m[8 + r] p2 + m[12 + r] p3 in that order, the scalar expression's, so
 * the four lanes give the scalar bytes (no FMA: -ffp-contract=off). */
static void transform_point(const sr_mat4 *m, const float p[4], float out[4])
{
    v4f c0, c1, c2, c3;
    memcpy(&c0, &m->m[0], sizeof c0);
    memcpy(&c1, &m->m[4], sizeof c1);
    memcpy(&c2, &m->m[8], sizeof c2);
    memcpy(&c3, &m->m[12], sizeof c3);
    v4f r = c0 * p[0] + c1 * p[1] + c2 * p[2] + c3 * p[3];
    memcpy(out, &r, sizeof r);
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
 * post-transform cache).  `k` holds the state's plane coefficients. */
static void classify(const sr_draw_state *ds, const sr_clip_planes *k, sr_vertex_post *v)
{
    if (!(isfinite(v->pos[0]) && isfinite(v->pos[1]) && isfinite(v->pos[2]) &&
          isfinite(v->pos[3]))) {
        v->outcode = SR_OUTCODE_NONFINITE;
        return;
    }
    v->outcode = sr__clip_outcode_with(k, v->pos);
    if (v->outcode == 0) {
        sr__project(ds, v->pos, &v->x_q8, &v->y_q8, &v->z, &v->inv_w);
    }
}

#if defined(__SSE2__)
/* Bits of the outcode, as two 64-bit lanes, where a plane's outside mask
 * is set. */
static inline __m128i plane_bit(__m128d outside, int plane)
{
    return _mm_and_si128(_mm_castpd_si128(outside), _mm_set1_epi64x(1ll << plane));
}

/* classify's constants, each in both lanes, made once per block. */
typedef struct classify_lanes {
    __m128d px, py, left_w, right_w, top_w, bottom_w, eps;
    __m128d ox, oy, vpx, vpy, zs, zb, one, subpixel, lim, neg_lim, magic;
    bool zero_to_one;
} classify_lanes;

static void make_lanes(const sr_draw_state *ds, const sr_clip_planes *k, classify_lanes *c)
{
    const double lim = (double)SR_GUARD_BAND_MAX * SR_SUBPIXEL_ONE;
    *c = (classify_lanes){
        _mm_set1_pd(k->px), _mm_set1_pd(k->py), _mm_set1_pd(k->left_w),
        _mm_set1_pd(k->right_w), _mm_set1_pd(k->top_w), _mm_set1_pd(k->bottom_w),
        _mm_set1_pd(SR_CLIP_W_EPSILON),
        _mm_set1_pd(ds->vp_ox), _mm_set1_pd(ds->vp_oy), _mm_set1_pd(ds->vp_px),
        _mm_set1_pd(ds->vp_py), _mm_set1_pd(ds->vp_zs), _mm_set1_pd(ds->vp_zb),
        _mm_set1_pd(1.0), _mm_set1_pd(SR_SUBPIXEL_ONE), _mm_set1_pd(lim), _mm_set1_pd(-lim),
        _mm_set1_pd(6755399441055744.0), /* 1.5 x 2^52, as sr__snap_q8 */
        k->zero_to_one,
    };
}

/* classify for two vertices whose x, y, z, w are the lanes of xd .. wd:
 * sr__clip_outcode_with's and sr__project's operations, lane by lane in
 * the same order (oy - py yn included), so the same bits and values.
 * The window position is computed for both and is only meaningful where
 * the outcode is 0, as in classify. */
static inline void classify2(const classify_lanes *k, __m128d xd, __m128d yd, __m128d zd,
                             __m128d wd, sr_vertex_post *v)
{
    const __m128d zero = _mm_setzero_pd();
    __m128d near = k->zero_to_one ? zd : _mm_add_pd(zd, wd);
    __m128d pxx = _mm_mul_pd(k->px, xd);
    __m128d pyy = _mm_mul_pd(k->py, yd);
    __m128d dw = _mm_sub_pd(wd, k->eps);
    __m128d dl = _mm_sub_pd(pxx, _mm_mul_pd(k->left_w, wd));
    __m128d dr = _mm_sub_pd(_mm_mul_pd(k->right_w, wd), pxx);
    __m128d dt = _mm_sub_pd(_mm_mul_pd(k->top_w, wd), pyy);
    __m128d db = _mm_sub_pd(pyy, _mm_mul_pd(k->bottom_w, wd));
    __m128i code = plane_bit(_mm_cmpnge_pd(dw, zero), SR_PLANE_W);
    code = _mm_or_si128(code, plane_bit(_mm_cmpnge_pd(near, zero), SR_PLANE_NEAR));
    code = _mm_or_si128(code, plane_bit(_mm_cmpnge_pd(_mm_sub_pd(wd, zd), zero), SR_PLANE_FAR));
    code = _mm_or_si128(code, plane_bit(_mm_cmpnge_pd(dl, zero), SR_PLANE_LEFT));
    code = _mm_or_si128(code, plane_bit(_mm_cmpnge_pd(dr, zero), SR_PLANE_RIGHT));
    code = _mm_or_si128(code, plane_bit(_mm_cmpnge_pd(dt, zero), SR_PLANE_TOP));
    code = _mm_or_si128(code, plane_bit(_mm_cmpnge_pd(db, zero), SR_PLANE_BOTTOM));
    v[0].outcode = (unsigned)_mm_cvtsi128_si32(code);
    v[1].outcode = (unsigned)_mm_cvtsi128_si32(_mm_unpackhi_epi64(code, code));
    if (v[0].outcode != 0 && v[1].outcode != 0) {
        return;
    }

    /* sr__project and sr__snap_q8; min and max clamp as its selects do
     * for every value they can meet here (inside the planes, finite). */
    __m128d iw = _mm_div_pd(k->one, wd);
    __m128d xn = _mm_mul_pd(xd, iw), yn = _mm_mul_pd(yd, iw), zn = _mm_mul_pd(zd, iw);
    __m128d sx = _mm_add_pd(k->ox, _mm_mul_pd(k->vpx, xn));
    __m128d sy = _mm_sub_pd(k->oy, _mm_mul_pd(k->vpy, yn));
    sx = _mm_mul_pd(sx, k->subpixel);
    sy = _mm_mul_pd(sy, k->subpixel);
    sx = _mm_max_pd(_mm_min_pd(sx, k->lim), k->neg_lim);
    sy = _mm_max_pd(_mm_min_pd(sy, k->lim), k->neg_lim);
    sx = _mm_sub_pd(_mm_add_pd(sx, k->magic), k->magic);
    sy = _mm_sub_pd(_mm_add_pd(sy, k->magic), k->magic);
    __m128i q = _mm_unpacklo_epi32(_mm_cvttpd_epi32(sx), _mm_cvttpd_epi32(sy));
    __m128d z = _mm_add_pd(_mm_mul_pd(k->zs, zn), k->zb);
    __m128 fw = _mm_cvtpd_ps(iw);
    _Static_assert(offsetof(sr_vertex_post, y_q8) == offsetof(sr_vertex_post, x_q8) + 4,
                   "x_q8, y_q8 are stored as one pair");
    _mm_storel_epi64((__m128i *)(void *)&v[0].x_q8, q);
    _mm_storel_epi64((__m128i *)(void *)&v[1].x_q8, _mm_unpackhi_epi64(q, q));
    _mm_storel_pd(&v[0].z, z);
    _mm_storeh_pd(&v[1].z, z);
    _mm_store_ss(&v[0].inv_w, fw);
    _mm_store_ss(&v[1].inv_w, _mm_shuffle_ps(fw, fw, 1));
}
#endif

/* classify for post[0 .. count), four at a time where SSE2 is there. */
static void classify_block(const sr_draw_state *ds, sr_vertex_post *post, size_t count)
{
    if (ds->vertex_lanes16 && sr__classify16(ds, post, count)) {
        return;
    }
    sr_clip_planes k;
    sr__clip_planes(ds, &k);
    size_t i = 0;
#if defined(__SSE2__)
    const __m128i inf = _mm_set1_epi32(0x7f800000);
    classify_lanes lanes;
    make_lanes(ds, &k, &lanes);
    for (; i + 4 <= count; i += 4) {
        sr_vertex_post *v = &post[i];
        __m128 x = _mm_loadu_ps(v[0].pos), y = _mm_loadu_ps(v[1].pos);
        __m128 z = _mm_loadu_ps(v[2].pos), w = _mm_loadu_ps(v[3].pos);
        /* Any infinite or NaN coordinate (exponent all ones): one at a time. */
        __m128i e = _mm_or_si128(
            _mm_or_si128(_mm_cmpeq_epi32(_mm_and_si128(_mm_castps_si128(x), inf), inf),
                         _mm_cmpeq_epi32(_mm_and_si128(_mm_castps_si128(y), inf), inf)),
            _mm_or_si128(_mm_cmpeq_epi32(_mm_and_si128(_mm_castps_si128(z), inf), inf),
                         _mm_cmpeq_epi32(_mm_and_si128(_mm_castps_si128(w), inf), inf)));
        if (_mm_movemask_epi8(e)) {
            for (int j = 0; j < 4; j++) {
                classify(ds, &k, &v[j]);
            }
            continue;
        }
        _MM_TRANSPOSE4_PS(x, y, z, w);
        classify2(&lanes, _mm_cvtps_pd(x), _mm_cvtps_pd(y), _mm_cvtps_pd(z), _mm_cvtps_pd(w),
                  &v[0]);
        classify2(&lanes, _mm_cvtps_pd(_mm_movehl_ps(x, x)), _mm_cvtps_pd(_mm_movehl_ps(y, y)),
                  _mm_cvtps_pd(_mm_movehl_ps(z, z)), _mm_cvtps_pd(_mm_movehl_ps(w, w)), &v[2]);
    }
#endif
    for (; i < count; i++) {
        classify(ds, &k, &post[i]);
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
    /* Filled once: each vertex overwrites only its index and the
     * components its arrays have, so the absent ones keep their defaults
     * (the shader gets a const pointer and cannot change them). */
    sr_vertex_input in = { .position = { 0, 0, 0, 1 }, .color = { 0, 0, 0, 1 },
                           .generic = { 0, 0, 0, 1 }, .has_normal = d->normals != NULL,
                           .has_color = d->colors != NULL, .has_texcoord = d->texcoords != NULL,
                           .has_generic = d->generic != NULL };
    for (size_t i = first; i < first + count; i++) {
        in.index = (uint32_t)i;
        const float *pos = element(d->positions, d->position_stride, (size_t)psize, i);
        /* Three components, the usual count, as a fixed-size copy the
         * compiler inlines rather than a call to memcpy a vertex. */
        if (psize == 3) {
            memcpy(in.position, pos, 3 * sizeof(float));
        } else {
            memcpy(in.position, pos, (size_t)psize * sizeof(float));
        }
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
        sr_vertex_post *v = &post[i - first];
        float *vary = vary_out + (i - first) * (size_t)ds->nvary;
        float clip[4] = { 0, 0, 0, 1 };
        pr->vertex(pr->uniforms, &in, clip, vary);
        memcpy(v->pos, clip, sizeof clip);
    }
    classify_block(ds, post, count);
}

/* Vertex i's object position, w = 1 when it has three components. */
static void vertex_position(const sr_draw_desc *d, size_t i, float obj[4])
{
    int psize = d->position_size ? d->position_size : 3;
    const float *p = element(d->positions, d->position_stride, (size_t)psize, i);
    obj[0] = p[0];
    obj[1] = p[1];
    obj[2] = p[2];
    obj[3] = psize == 4 ? p[3] : 1.0f;
}

/* Vertex i's RGBA color, alpha 1 when it has three components; NULL
 * when the draw has no colors. */
static const float *vertex_color(const sr_draw_desc *d, size_t i, float rgba[4])
{
    if (!d->colors) {
        return NULL;
    }
    int csize = d->color_size ? d->color_size : 4;
    const float *c = element(d->colors, d->color_stride, (size_t)csize, i);
    rgba[0] = c[0];
    rgba[1] = c[1];
    rgba[2] = c[2];
    rgba[3] = csize == 4 ? c[3] : 1.0f;
    return rgba;
}

/* The eye-space position E M_O obj, divided by its w. */
static void eye_position(const sr_mat4 *mv, const float obj[4], float eye[4])
{
    transform_point(mv, obj, eye);
    if (eye[3] != 1.0f && eye[3] != 0.0f) {
        eye[0] /= eye[3];
        eye[1] /= eye[3];
        eye[2] /= eye[3];
    }
}

/* The surface color lighting starts from: the vertex color (NULL: none)
 * with the material's alpha, or the material's diffuse color. */
static void surface_color(const sr_draw_state *ds, const float *color_in, float color[4])
{
    if (ds->use_vertex_color && color_in) {
        color[0] = color_in[0];
        color[1] = color_in[1];
        color[2] = color_in[2];
        color[3] = color_in[3] * ds->diffuse[3];
    } else {
        memcpy(color, ds->diffuse, 4 * sizeof(float));
    }
}

/* One vertex of a built-in model: the clip position and the model's
 * varyings (raster/records.h's layouts).  color: RGBA, or NULL for the
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
        eye_position(mv, obj, eye);
    }
    if (need_normal && normal) {
        normal_to_eye(nm, normal, n);
    }
    if (need_color) {
        surface_color(ds, color_in, color);
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

/* UNLIT: the clip position and the color, nothing else - the common case
 * of large synthetic draws, so without sr__vertex_shade's per-vertex
 * decisions.  The same operations as sr__vertex_shade's UNLIT case. */
static void unlit_stage(const sr_draw_state *ds, const sr_draw_desc *d, const sr_mat4 *mvp,
                        size_t first, size_t count, sr_vertex_post *post, float *vary_out)
{
    int psize = d->position_size ? d->position_size : 3;
    int csize = d->color_size ? d->color_size : 4;
    size_t pstep = sr__attr_step(d->position_stride, (size_t)psize);
    size_t cstep = sr__attr_step(d->color_stride, (size_t)csize);
    size_t tstep = sr__attr_step(d->texcoord_stride, 2);
    size_t nv = (size_t)ds->nvary;
    const char *pos = (const char *)d->positions + first * pstep;
    const char *col = d->colors ? (const char *)d->colors + first * cstep : NULL;
    const char *tex = ds->uv_index >= 0 && d->texcoords
                          ? (const char *)d->texcoords + first * tstep : NULL;
    bool vertex_color = ds->use_vertex_color && col;
    float alpha = ds->diffuse[3];
    for (size_t i = 0; i < count; i++) {
        sr_vertex_post *v = &post[i];
        float *vary = vary_out + i * nv;
        const float *p = (const float *)(pos + i * pstep);
        float obj[4] = { p[0], p[1], p[2], psize == 4 ? p[3] : 1.0f };
        transform_point(mvp, obj, v->pos);
        if (vertex_color) {
            const float *c = (const float *)(col + i * cstep);
            vary[SR_VARY_COLOR + 0] = c[0];
            vary[SR_VARY_COLOR + 1] = c[1];
            vary[SR_VARY_COLOR + 2] = c[2];
            vary[SR_VARY_COLOR + 3] = (csize == 4 ? c[3] : 1.0f) * alpha;
        } else {
            memcpy(&vary[SR_VARY_COLOR], ds->diffuse, 4 * sizeof(float));
        }
        if (tex) {
            const float *t = (const float *)(tex + i * tstep);
            vary[ds->uv_index] = t[0];
            vary[ds->uv_index + 1] = t[1];
        }
    }
    classify_block(ds, post, count);
}

/* GOURAUD with whole-number shininess (the common lit mesh): what
 * sr__vertex_shade does, with the lighting - most of a lit vertex's cost -
 * done for four vertices at once by sr__light_lanes, which gives
 * sr__light's bytes.  A last group of fewer than four repeats its last
 * vertex in the spare lanes. */
static void gouraud_stage(const sr_draw_state *ds, const sr_draw_desc *d, const sr_mat4 *mvp,
                          const sr_mat4 *mv, const sr_mat4 *nm, size_t first, size_t count,
                          sr_vertex_post *post, float *vary_out)
{
    size_t nv = (size_t)ds->nvary;
    for (size_t g = 0; g < count; g += 4) {
        /* The four vertices' inputs to lighting, vertex by vertex; made
         * into lanes below from scalars (storing lanes one by one and
         * loading the vector would stall on store forwarding). */
        float n4[4][3], eye4[4][3], dif4[4][4];
        for (int k = 0; k < 4; k++) {
            size_t i = g + (size_t)k < count ? g + (size_t)k : count - 1;
            float obj[4], e[4], nk[3] = { 0, 0, 1 }, rgba[4];
            vertex_position(d, first + i, obj);
            transform_point(mvp, obj, post[i].pos);
            eye_position(mv, obj, e);
            if (d->normals) {
                normal_to_eye(nm, element(d->normals, d->normal_stride, 3, first + i), nk);
            }
            if (ds->two_sided) {
                face_viewer(ds, e, nk);
            }
            surface_color(ds, vertex_color(d, first + i, rgba), dif4[k]);
            memcpy(n4[k], nk, sizeof n4[k]);
            memcpy(eye4[k], e, sizeof eye4[k]);
            if (ds->uv_index >= 0 && d->texcoords) {
                const float *t = element(d->texcoords, d->texcoord_stride, 2, first + i);
                vary_out[i * nv + (size_t)ds->uv_index] = t[0];
                vary_out[i * nv + (size_t)ds->uv_index + 1] = t[1];
            }
        }
        v4f n[3], eye[3], dif[4], lit[4];
        for (int j = 0; j < 3; j++) {
            n[j] = (v4f){ n4[0][j], n4[1][j], n4[2][j], n4[3][j] };
            eye[j] = (v4f){ eye4[0][j], eye4[1][j], eye4[2][j], eye4[3][j] };
        }
        for (int j = 0; j < 4; j++) {
            dif[j] = (v4f){ dif4[0][j], dif4[1][j], dif4[2][j], dif4[3][j] };
        }
        sr__light_lanes(ds, n, eye, dif, lit);
        for (int k = 0; k < 4 && g + (size_t)k < count; k++) {
            float *vary = vary_out + (g + (size_t)k) * nv;
            for (int j = 0; j < 4; j++) {
                vary[SR_VARY_COLOR + j] = lit[j][k];
            }
        }
    }
    classify_block(ds, post, count);
}

void sr__vertex_stage(const sr_draw_state *ds, const sr_draw_desc *d,
                      const sr_mat4 *mvp, const sr_mat4 *mv, const sr_mat4 *nm,
                      size_t first, size_t count, sr_vertex_post *post, float *vary_out)
{
    if (ds->program) {
        program_stage(ds, d, first, count, post, vary_out);
        return;
    }
    if (ds->vertex_lanes16 && sr__vertex_stage16(ds, d, mvp, mv, nm, first, count, post, vary_out)) {
        return;
    }
    if (ds->shading == SR_SHADING_UNLIT) {
        unlit_stage(ds, d, mvp, first, count, post, vary_out);
        return;
    }
    if (ds->shading == SR_SHADING_GOURAUD && ds->shininess_int >= 0 && ds->light_lanes) {
        gouraud_stage(ds, d, mvp, mv, nm, first, count, post, vary_out);
        return;
    }
    int gsize = d->generic_size ? d->generic_size : 4;
    for (size_t i = first; i < first + count; i++) {
        sr_vertex_post *v = &post[i - first];
        float *vary = vary_out + (i - first) * (size_t)ds->nvary;
        float obj[4], color[4], generic[4];
        vertex_position(d, i, obj);
        const float *cp = vertex_color(d, i, color), *gp = NULL;
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
    }
    classify_block(ds, post, count);
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
