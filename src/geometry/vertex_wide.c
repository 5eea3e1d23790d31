/* vertex_wide.c - the Gouraud vertex stage sixteen vertices at a time
 * (geometry, AVX-512): vertex.c's gouraud_stage (whose lanes are four
 * vertices, and only for the lighting) with every step of a vertex in the
 * lanes - the clip and eye positions, the normal to eye space, two-sided
 * facing, the surface color, the lighting (light_lanes_body.h), and
 * classify's clip outcode, divide by w, viewport S and snap, in eight
 * double lanes at a time.  The vertices' inputs are gathered straight
 * into lanes (a structure of arrays), so sixteen vertices cost about what
 * four did; packed positions and normals of a full group are loaded and
 * permuted instead (gather3: the bunny's vertex stage 9.0% -> 7.5% of a
 * one-thread frame's samples).
 *
 * Not UNLIT: its vertices are a position and a color read once from
 * memory, and gathering them (1 million triangles, the bench's `small`)
 * measured slower than unlit_stage's plain loads.  Its classification,
 * though, and every other stage's, runs here sixteen at a time
 * (sr__classify16): the clip positions, already in the cache, are
 * transposed into lanes four at a time (small 147.9 -> 134.7 ms on one
 * thread, against vertex.c's two-lane classify2).
 *
 * Exactness: each lane repeats sr__vertex_shade's operations in the same
 * order (transform_point's column sums, eye_position's division,
 * normal_to_eye's renormalization, face_viewer's test), without FMA
 * (-ffp-contract=off), and a scalar branch becomes a select with the same
 * comparison, NaN included: the same bits as the scalar stage, outcodes
 * and window positions included. */
#include "pipeline.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include "fragment/light_lanes16.h"   /* v16f, v16i, v16_sel, v16_sqrt, light16 */

#define SR_WIDE_INLINE static inline __attribute__((always_inline)) SR_TARGET_AVX512

/* An attribute array: `step` bytes from one vertex's element to the
 * next (element() in vertex.c), and its first element in the draw. */
typedef struct lanes_src {
    const char *base;
    size_t step;
} lanes_src;

static lanes_src source(const void *array, size_t stride, size_t count, size_t first)
{
    size_t step = sr__attr_step(stride, count);
    return (lanes_src){ (const char *)array + first * step, step };
}

/* Component c of the group's sixteen elements; `off` holds each lane's
 * byte offset from the group's first element (past the draw's last
 * vertex a lane repeats it, so nothing outside the arrays is read). */
SR_WIDE_INLINE v16f gather(const char *group, __m512i off, int c)
{
    return (v16f)_mm512_i32gather_ps(off, group + c * sizeof(float), 1);
}

/* Components 0-2 of the group's sixteen elements, lane i element i.  A
 * full group of a packed three-float array (positions, normals) lies in
 * 48 consecutive floats: three loads, and two permutes a component pick
 * lane i's float 3 i + c out of them, far fewer cycles than a gather's
 * sixteen loads.  The same floats either way. */
SR_WIDE_INLINE void gather3(const lanes_src *src, __m512i off, int n, v16f out[3])
{
    if (n < 16 || src->step != 3 * sizeof(float)) {
        for (int c = 0; c < 3; c++) {
            out[c] = gather(src->base, off, c);
        }
        return;
    }
    const float *f = (const float *)(const void *)src->base;
    __m512 a = _mm512_loadu_ps(f), b = _mm512_loadu_ps(f + 16), c3 = _mm512_loadu_ps(f + 32);
    for (int c = 0; c < 3; c++) {
        /* Lanes with 3 i + c < 32 from a and b (indices 0-31), then the
         * rest from c3 (index 16 + 3 i + c - 32 in the second permute's
         * numbering, where 0-15 keep the first permute's lanes). */
        int ab[16], rest[16];
        for (int i = 0; i < 16; i++) {
            int at = 3 * i + c;
            ab[i] = at < 32 ? at : 0;
            rest[i] = at < 32 ? i : 16 + at - 32;
        }
        __m512 lo = _mm512_permutex2var_ps(a, _mm512_loadu_si512(ab), b);
        out[c] = (v16f)_mm512_permutex2var_ps(lo, _mm512_loadu_si512(rest), c3);
    }
}

/* transform_point's lane r of m p, for sixteen points p (x, y, z, w):
 * m[r] x + m[4 + r] y + m[8 + r] z + m[12 + r] w, summed in that order. */
SR_WIDE_INLINE void transform16(const sr_mat4 *m, const v16f p[4], v16f out[4])
{
    for (int r = 0; r < 4; r++) {
        out[r] = m->m[r] * p[0] + m->m[4 + r] * p[1] + m->m[8 + r] * p[2] + m->m[12 + r] * p[3];
    }
}

/* Each lane's byte offset in an array of `step`-byte elements (see
 * gather). */
SR_WIDE_INLINE __m512i offsets(__m512i clamped, size_t step)
{
    return _mm512_mullo_epi32(clamped, _mm512_set1_epi32((int32_t)step));
}

/* vertex_position for the group: w = 1 for three components. */
SR_WIDE_INLINE void positions16(const sr_draw_desc *d, size_t at, int n, __m512i clamped,
                                v16f obj[4])
{
    int psize = d->position_size ? d->position_size : 3;
    lanes_src ps = source(d->positions, d->position_stride, (size_t)psize, at);
    __m512i off = offsets(clamped, ps.step);
    gather3(&ps, off, n, obj);
    obj[3] = psize == 4 ? gather(ps.base, off, 3) : (v16f){ 0 } + 1.0f;
}

/* surface_color for the group: the vertex color (alpha 1 for three
 * components) with the material's alpha, or the material's diffuse color. */
SR_WIDE_INLINE void surface16(const sr_draw_state *ds, const sr_draw_desc *d, size_t at,
                              __m512i clamped, v16f dif[4])
{
    const v16f zero = { 0 };
    if (ds->use_vertex_color && d->colors) {
        int csize = d->color_size ? d->color_size : 4;
        lanes_src cs = source(d->colors, d->color_stride, (size_t)csize, at);
        __m512i off = offsets(clamped, cs.step);
        for (int k = 0; k < 3; k++) {
            dif[k] = gather(cs.base, off, k);
        }
        dif[3] = (csize == 4 ? gather(cs.base, off, 3) : zero + 1.0f) * ds->diffuse[3];
    } else {
        for (int k = 0; k < 4; k++) {
            dif[k] = zero + ds->diffuse[k];
        }
    }
}

/* classify's constants (vertex.c), each in eight double lanes. */
typedef struct classify8 {
    __m512d px, py, left_w, right_w, top_w, bottom_w;
    __m512d ox, oy, vpx, vpy, zs, zb;
    bool zero_to_one;
} classify8;

SR_TARGET_AVX512 static void make_classify8(const sr_draw_state *ds, classify8 *c)
{
    sr_clip_planes k;
    sr__clip_planes(ds, &k);
    *c = (classify8){
        _mm512_set1_pd(k.px), _mm512_set1_pd(k.py), _mm512_set1_pd(k.left_w),
        _mm512_set1_pd(k.right_w), _mm512_set1_pd(k.top_w), _mm512_set1_pd(k.bottom_w),
        _mm512_set1_pd(ds->vp_ox), _mm512_set1_pd(ds->vp_oy), _mm512_set1_pd(ds->vp_px),
        _mm512_set1_pd(ds->vp_py), _mm512_set1_pd(ds->vp_zs), _mm512_set1_pd(ds->vp_zb),
        k.zero_to_one,
    };
}

/* The outcode's bit for `plane` in the lanes whose distance d is not
 * >= 0 (NaN included), as sr__clip_outcode_with's !(d >= 0.0). */
SR_WIDE_INLINE __m256i plane_bit8(__m256i code, __m512d d, int plane)
{
    __mmask8 out = _mm512_cmp_pd_mask(d, _mm512_setzero_pd(), _CMP_NGE_UQ);
    return _mm256_mask_or_epi32(code, out, code, _mm256_set1_epi32(1 << plane));
}

/* sr__snap_q8 on eight lanes: min and max clamp as its selects do for
 * the values met here (inside the planes: finite), and 1.5 x 2^52 rounds
 * to nearest even. */
SR_WIDE_INLINE __m256i snap8(__m512d v)
{
    const double lim = (double)SR_GUARD_BAND_MAX * SR_SUBPIXEL_ONE;
    const __m512d magic = _mm512_set1_pd(6755399441055744.0);
    __m512d s = _mm512_mul_pd(v, _mm512_set1_pd(SR_SUBPIXEL_ONE));
    s = _mm512_max_pd(_mm512_min_pd(s, _mm512_set1_pd(lim)), _mm512_set1_pd(-lim));
    s = _mm512_sub_pd(_mm512_add_pd(s, magic), magic);
    return _mm512_cvttpd_epi32(s);
}

/* classify for eight vertices, lanes h*8 .. h*8 + 7 of the group's clip
 * positions: sr__clip_outcode_with's and sr__project's operations in the
 * same order, in double.  The window position is computed in every lane
 * and only meaningful where the outcode is 0, as in classify. */
SR_WIDE_INLINE void classify_half(const classify8 *k, const v16f clip[4], int h, uint32_t code[8],
                                  int32_t xq[8], int32_t yq[8], double z[8], float inv_w[8])
{
    __m512d c[4];
    for (int j = 0; j < 4; j++) {
        __m256 half = h ? _mm512_extractf32x8_ps((__m512)clip[j], 1)
                        : _mm512_castps512_ps256((__m512)clip[j]);
        c[j] = _mm512_cvtps_pd(half);
    }
    __m512d x = c[0], y = c[1], zc = c[2], w = c[3];
    __m512d near = k->zero_to_one ? zc : _mm512_add_pd(zc, w);
    __m512d pxx = _mm512_mul_pd(k->px, x), pyy = _mm512_mul_pd(k->py, y);
    __m256i oc = _mm256_setzero_si256();
    oc = plane_bit8(oc, _mm512_sub_pd(w, _mm512_set1_pd(SR_CLIP_W_EPSILON)), SR_PLANE_W);
    oc = plane_bit8(oc, near, SR_PLANE_NEAR);
    oc = plane_bit8(oc, _mm512_sub_pd(w, zc), SR_PLANE_FAR);
    oc = plane_bit8(oc, _mm512_sub_pd(pxx, _mm512_mul_pd(k->left_w, w)), SR_PLANE_LEFT);
    oc = plane_bit8(oc, _mm512_sub_pd(_mm512_mul_pd(k->right_w, w), pxx), SR_PLANE_RIGHT);
    oc = plane_bit8(oc, _mm512_sub_pd(_mm512_mul_pd(k->top_w, w), pyy), SR_PLANE_TOP);
    oc = plane_bit8(oc, _mm512_sub_pd(pyy, _mm512_mul_pd(k->bottom_w, w)), SR_PLANE_BOTTOM);
    _mm256_storeu_si256((__m256i *)(void *)code, oc);

    __m512d iw = _mm512_div_pd(_mm512_set1_pd(1.0), w);
    __m512d xn = _mm512_mul_pd(x, iw), yn = _mm512_mul_pd(y, iw), zn = _mm512_mul_pd(zc, iw);
    _mm256_storeu_si256((__m256i *)(void *)xq,
                        snap8(_mm512_add_pd(k->ox, _mm512_mul_pd(k->vpx, xn))));
    _mm256_storeu_si256((__m256i *)(void *)yq,
                        snap8(_mm512_sub_pd(k->oy, _mm512_mul_pd(k->vpy, yn))));
    _mm512_storeu_pd(z, _mm512_add_pd(_mm512_mul_pd(k->zs, zn), k->zb));
    _mm256_storeu_ps(inv_w, _mm512_cvtpd_ps(iw));
}

/* The group's n vertex records: clip positions and their classification
 * (vertex.c's classify): a vertex with an infinite or NaN coordinate is
 * SR_OUTCODE_NONFINITE. */
SR_WIDE_INLINE void finish16(const classify8 *k, const v16f clip[4], int n, sr_vertex_post *post)
{
    __mmask16 bad = 0;
    for (int j = 0; j < 4; j++) {
        bad |= _mm512_fpclass_ps_mask((__m512)clip[j], 0x99); /* NaN, +Inf, -Inf */
    }
    uint32_t code[16];
    int32_t xq[16], yq[16];
    double z[16];
    float inv_w[16];
    for (int h = 0; h < 2 && h * 8 < n; h++) {
        classify_half(k, clip, h, &code[h * 8], &xq[h * 8], &yq[h * 8], &z[h * 8], &inv_w[h * 8]);
    }
    for (int i = 0; i < n; i++) {
        sr_vertex_post *v = &post[i];
        for (int j = 0; j < 4; j++) {
            v->pos[j] = clip[j][i];
        }
        v->outcode = bad >> i & 1 ? SR_OUTCODE_NONFINITE : code[i];
        v->x_q8 = xq[i];
        v->y_q8 = yq[i];
        v->z = z[i];
        v->inv_w = inv_w[i];
    }
}

/* The texture coordinates of the group's n vertices, copied. */
static void texcoords16(const sr_draw_state *ds, const sr_draw_desc *d, size_t at, int n,
                        float *vary)
{
    if (ds->uv_index < 0 || !d->texcoords) {
        return;
    }
    lanes_src ts = source(d->texcoords, d->texcoord_stride, 2, at);
    for (int k = 0; k < n; k++) {
        const float *t = (const float *)(ts.base + (size_t)k * ts.step);
        vary[(size_t)k * (size_t)ds->nvary + (size_t)ds->uv_index] = t[0];
        vary[(size_t)k * (size_t)ds->nvary + (size_t)ds->uv_index + 1] = t[1];
    }
}

/* The group's n colors into the varyings. */
SR_WIDE_INLINE void colors16(const sr_draw_state *ds, const v16f rgba[4], int n, float *vary)
{
    for (int k = 0; k < n; k++) {
        for (int j = 0; j < 4; j++) {
            vary[(size_t)k * (size_t)ds->nvary + SR_VARY_COLOR + (size_t)j] = rgba[j][k];
        }
    }
}

/* Lane k of a group starting at vertex `at` of n reads element
 * min(k, n - 1): the spare lanes repeat the last vertex. */
SR_WIDE_INLINE __m512i clamped_lanes(int n)
{
    const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    return _mm512_min_epi32(lane, _mm512_set1_epi32(n - 1));
}

/* gouraud_stage for the n (<= 16) vertices from `at`: the clip position,
 * and the color lit at the eye-space position and normal. */
SR_TARGET_AVX512 static void gouraud16(const sr_draw_state *ds, const sr_draw_desc *d,
                                       const sr_mat4 *mvp, const sr_mat4 *mv, const sr_mat4 *nm,
                                       const classify8 *k, size_t at, int n,
                                       sr_vertex_post *post, float *vary)
{
    const v16f zero = { 0 }, one = zero + 1.0f;
    __m512i clamped = clamped_lanes(n);
    v16f obj[4], clip[4], eye[4];
    positions16(d, at, n, clamped, obj);
    transform16(mvp, obj, clip);

    /* eye_position: divided by w unless w is 1 or 0 (NaN divides). */
    transform16(mv, obj, eye);
    v16i divide = (eye[3] != one) & (eye[3] != zero);
    for (int j = 0; j < 3; j++) {
        eye[j] = v16_sel(divide, eye[j] / eye[3], eye[j]);
    }

    /* normal_to_eye, or (0, 0, 1) without normals. */
    v16f nrm[3] = { zero, zero, one };
    if (d->normals) {
        lanes_src ns = source(d->normals, d->normal_stride, 3, at);
        __m512i off = offsets(clamped, ns.step);
        v16f in[3];
        gather3(&ns, off, n, in);
        const float *a = nm->m;
        v16f x = a[0] * in[0] + a[4] * in[1] + a[8] * in[2];
        v16f y = a[1] * in[0] + a[5] * in[1] + a[9] * in[2];
        v16f z = a[2] * in[0] + a[6] * in[1] + a[10] * in[2];
        v16f len = v16_sqrt(x * x + y * y + z * z);
        v16f s = v16_sel(len > zero, one / len, zero);
        nrm[0] = x * s;
        nrm[1] = y * s;
        nrm[2] = z * s;
    }

    /* face_viewer: the normal turned toward the viewer. */
    if (ds->two_sided) {
        v16f vdir[3] = { zero, zero, one };
        if (ds->local_viewer) {
            for (int j = 0; j < 3; j++) {
                vdir[j] = -eye[j];
            }
        }
        v16i away = nrm[0] * vdir[0] + nrm[1] * vdir[1] + nrm[2] * vdir[2] < zero;
        for (int j = 0; j < 3; j++) {
            nrm[j] = v16_sel(away, -nrm[j], nrm[j]);
        }
    }

    v16f dif[4], lit[4];
    surface16(ds, d, at, clamped, dif);
    light16(ds, nrm, eye, dif, lit);
    finish16(k, clip, n, post);
    colors16(ds, lit, n, vary);
    texcoords16(ds, d, at, n, vary);
}

/* The gathers take 32-bit byte offsets: sixteen elements must lie within
 * 2^31 bytes of the group's first. */
static bool offsets_fit(const void *array, size_t stride, size_t count)
{
    return !array || sr__attr_step(stride, count) <= (size_t)INT32_MAX / 16;
}

static bool arrays_fit(const sr_draw_desc *d)
{
    int psize = d->position_size ? d->position_size : 3;
    int csize = d->color_size ? d->color_size : 4;
    return offsets_fit(d->positions, d->position_stride, (size_t)psize) &&
           offsets_fit(d->normals, d->normal_stride, 3) &&
           offsets_fit(d->colors, d->color_stride, (size_t)csize) &&
           offsets_fit(d->texcoords, d->texcoord_stride, 2);
}

SR_TARGET_AVX512 bool sr__vertex_stage16(const sr_draw_state *ds, const sr_draw_desc *d,
                                         const sr_mat4 *mvp, const sr_mat4 *mv, const sr_mat4 *nm,
                                         size_t first, size_t count, sr_vertex_post *post,
                                         float *vary)
{
    if (ds->program || ds->shading != SR_SHADING_GOURAUD || ds->shininess_int < 0 ||
        !arrays_fit(d)) {
        return false;
    }
    classify8 k;
    make_classify8(ds, &k);
    size_t nv = (size_t)ds->nvary;
    for (size_t g = 0; g < count; g += 16) {
        int n = count - g < 16 ? (int)(count - g) : 16;
        gouraud16(ds, d, mvp, mv, nm, &k, first + g, n, &post[g], vary + g * nv);
    }
    return true;
}

/* The clip positions of post[0 .. n) (n <= 16) as lanes: each 128-bit
 * quarter of r[j] holds vertex 4 q + j, and a 4 x 4 transpose within
 * the quarters turns them into x, y, z, w with lane i vertex i.  Lanes
 * past n repeat the last vertex. */
SR_WIDE_INLINE void clip_lanes(const sr_vertex_post *post, int n, v16f clip[4])
{
    __m512 r[4];
    for (int j = 0; j < 4; j++) {
        __m128 q[4];
        for (int k = 0; k < 4; k++) {
            int i = 4 * k + j < n ? 4 * k + j : n - 1;
            q[k] = _mm_loadu_ps(post[i].pos);
        }
        __m512 v = _mm512_castps128_ps512(q[0]);
        v = _mm512_insertf32x4(v, q[1], 1);
        v = _mm512_insertf32x4(v, q[2], 2);
        r[j] = _mm512_insertf32x4(v, q[3], 3);
    }
    __m512 t0 = _mm512_unpacklo_ps(r[0], r[1]), t1 = _mm512_unpackhi_ps(r[0], r[1]);
    __m512 t2 = _mm512_unpacklo_ps(r[2], r[3]), t3 = _mm512_unpackhi_ps(r[2], r[3]);
    clip[0] = (v16f)_mm512_shuffle_ps(t0, t2, 0x44);
    clip[1] = (v16f)_mm512_shuffle_ps(t0, t2, 0xee);
    clip[2] = (v16f)_mm512_shuffle_ps(t1, t3, 0x44);
    clip[3] = (v16f)_mm512_shuffle_ps(t1, t3, 0xee);
}

SR_TARGET_AVX512 bool sr__classify16(const sr_draw_state *ds, sr_vertex_post *post, size_t count)
{
    classify8 k;
    make_classify8(ds, &k);
    for (size_t g = 0; g < count; g += 16) {
        int n = count - g < 16 ? (int)(count - g) : 16;
        v16f clip[4];
        clip_lanes(&post[g], n, clip);
        finish16(&k, clip, n, &post[g]);
    }
    return true;
}

#else

bool sr__classify16(const sr_draw_state *ds, sr_vertex_post *post, size_t count)
{
    (void)ds, (void)post, (void)count;
    return false;
}

bool sr__vertex_stage16(const sr_draw_state *ds, const sr_draw_desc *d, const sr_mat4 *mvp,
                        const sr_mat4 *mv, const sr_mat4 *nm, size_t first, size_t count,
                        sr_vertex_post *post, float *vary)
{
    (void)ds, (void)d, (void)mvp, (void)mv, (void)nm, (void)first, (void)count, (void)post;
    (void)vary;
    return false;
}

#endif
