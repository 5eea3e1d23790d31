/* vertex_wide.c - the Gouraud vertex stage sixteen vertices at a time
 * (geometry, AVX-512): vertex.c's gouraud_stage, whose lanes are four
 * vertices, with every step of a vertex in the lanes - the clip and eye
 * positions, the normal to eye space, two-sided facing, the surface color
 * and the lighting (light_lanes_body.h) - where gouraud_stage does all but
 * the lighting one vertex at a time.  The vertices' inputs are gathered
 * straight into lanes (a structure of arrays), so sixteen vertices cost
 * about what four did.
 *
 * Exactness: each lane repeats sr__vertex_shade's operations in the same
 * order (transform_point's column sums, eye_position's division,
 * normal_to_eye's renormalization, face_viewer's test), without FMA
 * (-ffp-contract=off), and a scalar branch becomes a select with the same
 * comparison, NaN included: the same bits as the scalar stage.  The
 * caller classifies the positions (classify_block) as for every stage. */
#include "pipeline.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>

/* The inlined helpers pass 64-byte vectors; GCC notes the ABI difference,
 * which cannot matter for inlined statics. */
#pragma GCC diagnostic ignored "-Wpsabi"

#define SR_WIDE __attribute__((target("avx2,avx512f,avx512dq,avx512bw,avx512vl")))
#define SR_WIDE_INLINE static inline __attribute__((always_inline)) SR_WIDE

typedef float v16f __attribute__((vector_size(64)));
typedef int32_t v16i __attribute__((vector_size(64)));

SR_WIDE_INLINE v16f v16_sel(v16i m, v16f a, v16f b)
{
    return (v16f)((m & (v16i)a) | (~m & (v16i)b));
}

/* Correctly rounded, as sqrtf. */
SR_WIDE_INLINE v16f v16_sqrt(v16f x)
{
    return (v16f)_mm512_sqrt_ps((__m512)x);
}

#define SR_LL_F v16f
#define SR_LL_I v16i
#define SR_LL_SEL v16_sel
#define SR_LL_SQRT v16_sqrt
#define SR_LL_NAME light16
#define SR_LL_TARGET SR_WIDE
#include "fragment/light_lanes_body.h"

/* An attribute array: `step` bytes from one vertex's element to the
 * next (element() in vertex.c), and its first element in the draw. */
typedef struct lanes_src {
    const char *base;
    size_t step;
} lanes_src;

static lanes_src source(const void *array, size_t stride, size_t count, size_t first)
{
    size_t step = stride ? stride : count * sizeof(float);
    return (lanes_src){ (const char *)array + first * step, step };
}

/* Component c of the group's sixteen elements; `off` holds each lane's
 * byte offset from the group's first element (past the draw's last
 * vertex a lane repeats it, so nothing outside the arrays is read). */
SR_WIDE_INLINE v16f gather(const char *group, __m512i off, int c)
{
    return (v16f)_mm512_i32gather_ps(off, group + c * sizeof(float), 1);
}

/* transform_point's lane r of m p, for sixteen points p (x, y, z, w):
 * m[r] x + m[4 + r] y + m[8 + r] z + m[12 + r] w, summed in that order. */
SR_WIDE_INLINE void transform16(const sr_mat4 *m, const v16f p[4], v16f out[4])
{
    for (int r = 0; r < 4; r++) {
        out[r] = m->m[r] * p[0] + m->m[4 + r] * p[1] + m->m[8 + r] * p[2] + m->m[12 + r] * p[3];
    }
}

/* Sixteen vertices from `g` (n of them real) of the draw's vertices
 * `first` on: clip positions into post[].pos, lit colors and texture
 * coordinates into vary. */
SR_WIDE static void group16(const sr_draw_state *ds, const sr_draw_desc *d, const sr_mat4 *mvp,
                            const sr_mat4 *mv, const sr_mat4 *nm, size_t first, size_t g,
                            int n, sr_vertex_post *post, float *vary_out)
{
    const v16f zero = { 0 }, one = zero + 1.0f;
    const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    const __m512i clamped = _mm512_min_epi32(lane, _mm512_set1_epi32(n - 1));

    /* vertex_position: w = 1 for three components. */
    int psize = d->position_size ? d->position_size : 3;
    lanes_src ps = source(d->positions, d->position_stride, (size_t)psize, first + g);
    __m512i poff = _mm512_mullo_epi32(clamped, _mm512_set1_epi32((int32_t)ps.step));
    v16f obj[4] = { gather(ps.base, poff, 0), gather(ps.base, poff, 1), gather(ps.base, poff, 2),
                    psize == 4 ? gather(ps.base, poff, 3) : one };
    v16f clip[4], eye[4];
    transform16(mvp, obj, clip);

    /* eye_position: divided by w unless w is 1 or 0 (NaN divides). */
    transform16(mv, obj, eye);
    v16i divide = (eye[3] != one) & (eye[3] != zero);
    for (int k = 0; k < 3; k++) {
        eye[k] = v16_sel(divide, eye[k] / eye[3], eye[k]);
    }

    /* normal_to_eye, or (0, 0, 1) without normals. */
    v16f nrm[3] = { zero, zero, one };
    if (d->normals) {
        lanes_src ns = source(d->normals, d->normal_stride, 3, first + g);
        __m512i noff = _mm512_mullo_epi32(clamped, _mm512_set1_epi32((int32_t)ns.step));
        v16f in[3] = { gather(ns.base, noff, 0), gather(ns.base, noff, 1),
                       gather(ns.base, noff, 2) };
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
            for (int k = 0; k < 3; k++) {
                vdir[k] = -eye[k];
            }
        }
        v16i away = nrm[0] * vdir[0] + nrm[1] * vdir[1] + nrm[2] * vdir[2] < zero;
        for (int k = 0; k < 3; k++) {
            nrm[k] = v16_sel(away, -nrm[k], nrm[k]);
        }
    }

    /* surface_color: the vertex color with the material's alpha, or the
     * material's diffuse color. */
    v16f dif[4];
    if (ds->use_vertex_color && d->colors) {
        int csize = d->color_size ? d->color_size : 4;
        lanes_src cs = source(d->colors, d->color_stride, (size_t)csize, first + g);
        __m512i coff = _mm512_mullo_epi32(clamped, _mm512_set1_epi32((int32_t)cs.step));
        for (int k = 0; k < 3; k++) {
            dif[k] = gather(cs.base, coff, k);
        }
        dif[3] = (csize == 4 ? gather(cs.base, coff, 3) : one) * ds->diffuse[3];
    } else {
        for (int k = 0; k < 4; k++) {
            dif[k] = zero + ds->diffuse[k];
        }
    }

    v16f lit[4];
    light16(ds, nrm, eye, dif, lit);

    /* Back to one record per vertex. */
    size_t nv = (size_t)ds->nvary;
    for (int k = 0; k < n; k++) {
        sr_vertex_post *v = &post[g + (size_t)k];
        float *vary = vary_out + (g + (size_t)k) * nv;
        for (int j = 0; j < 4; j++) {
            v->pos[j] = clip[j][k];
            vary[SR_VARY_COLOR + j] = lit[j][k];
        }
    }
    if (ds->uv_index >= 0 && d->texcoords) {
        lanes_src ts = source(d->texcoords, d->texcoord_stride, 2, first + g);
        for (int k = 0; k < n; k++) {
            const float *t = (const float *)(ts.base + (size_t)k * ts.step);
            float *vary = vary_out + (g + (size_t)k) * nv;
            vary[ds->uv_index] = t[0];
            vary[ds->uv_index + 1] = t[1];
        }
    }
}

/* The gathers take 32-bit byte offsets: sixteen elements must lie within
 * 2^31 bytes of the group's first. */
static bool offsets_fit(const void *array, size_t stride, size_t count)
{
    size_t step = stride ? stride : count * sizeof(float);
    return !array || step <= (size_t)INT32_MAX / 16;
}

bool sr__gouraud_stage16(const sr_draw_state *ds, const sr_draw_desc *d, const sr_mat4 *mvp,
                         const sr_mat4 *mv, const sr_mat4 *nm, size_t first, size_t count,
                         sr_vertex_post *post, float *vary_out)
{
    int psize = d->position_size ? d->position_size : 3;
    int csize = d->color_size ? d->color_size : 4;
    if (!offsets_fit(d->positions, d->position_stride, (size_t)psize) ||
        !offsets_fit(d->normals, d->normal_stride, 3) ||
        !offsets_fit(d->colors, d->color_stride, (size_t)csize)) {
        return false;
    }
    for (size_t g = 0; g < count; g += 16) {
        int n = count - g < 16 ? (int)(count - g) : 16;
        group16(ds, d, mvp, mv, nm, first, g, n, post, vary_out);
    }
    return true;
}

#else

bool sr__gouraud_stage16(const sr_draw_state *ds, const sr_draw_desc *d, const sr_mat4 *mvp,
                         const sr_mat4 *mv, const sr_mat4 *nm, size_t first, size_t count,
                         sr_vertex_post *post, float *vary_out)
{
    (void)ds, (void)d, (void)mvp, (void)mv, (void)nm, (void)first, (void)count, (void)post;
    (void)vary_out;
    return false;
}

#endif
