/* light_lanes.h - sr__light (shade.c) on four lanes at once, for the
 * vertex stage's Gouraud lighting (vertex.c) and the Phong vector kernel
 * (simd_kernel.h).  Written with GCC/Clang vector extensions: SSE on x86,
 * whatever the compiler makes of them elsewhere.
 *
 * Exactness: each lane performs the scalar function's operations in the
 * same order (no FMA: the build uses -ffp-contract=off), and where the
 * scalar code skips a light (`continue`) the lane keeps its sums through
 * a select, with the same comparisons, NaN included: the scalar code goes
 * on when n.l is NaN (it tests n.l <= 0), so the lanes test !(n.l <= 0).
 * Whole-number shininess only (ds->shininess_int >= 0): powf has no
 * lane-exact vector twin. */
#ifndef SR_LIGHT_LANES_H
#define SR_LIGHT_LANES_H

#include "pipeline.h"

#include <math.h>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif

typedef float sr_v4f __attribute__((vector_size(16)));
typedef int32_t sr_v4i __attribute__((vector_size(16)));

static inline __attribute__((always_inline)) sr_v4f sr__v4_sel(sr_v4i m, sr_v4f a, sr_v4f b)
{
    return (sr_v4f)((m & (sr_v4i)a) | (~m & (sr_v4i)b));
}

/* Correctly rounded, as sqrtf. */
static inline __attribute__((always_inline)) sr_v4f sr__v4_sqrt(sr_v4f x)
{
#if defined(__SSE__)
    return (sr_v4f)_mm_sqrt_ps((__m128)x);
#else
    sr_v4f r;
    for (int k = 0; k < 4; k++) {
        r[k] = sqrtf(x[k]);
    }
    return r;
#endif
}

/* out = sr__light(ds, n, eye, dif) lane by lane; n, eye and dif are the
 * lanes' components (x, y, z; r, g, b, a). */
static inline __attribute__((always_inline)) void
sr__light_lanes(const sr_draw_state *ds, const sr_v4f n[3], const sr_v4f eye[3],
                const sr_v4f dif[4], sr_v4f out[4])
{
    const sr_v4f zero = { 0, 0, 0, 0 };
    sr_v4f r = ds->ambient[0] * dif[0], g = ds->ambient[1] * dif[1], b = ds->ambient[2] * dif[2];
    sr_v4f v[3] = { zero, zero, zero + 1.0f };
    if (ds->local_viewer) {
        sr_v4f len = sr__v4_sqrt(eye[0] * eye[0] + eye[1] * eye[1] + eye[2] * eye[2]);
        sr_v4i ok = len > zero;
        for (int k = 0; k < 3; k++) {
            v[k] = sr__v4_sel(ok, -eye[k] / len, v[k]);
        }
    }
    bool spec = ds->specular[0] > 0.0f || ds->specular[1] > 0.0f || ds->specular[2] > 0.0f;
    for (int i = 0; i < ds->light_count; i++) {
        const sr_light_eye *lt = &ds->lights[i];
        sr_v4f l[3];
        sr_v4i use = { -1, -1, -1, -1 };
        if (lt->point) {
            for (int k = 0; k < 3; k++) {
                l[k] = lt->vec[k] - eye[k];
            }
            sr_v4f len = sr__v4_sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
            use = len > zero;
            for (int k = 0; k < 3; k++) {
                l[k] = l[k] / len;
            }
        } else {
            for (int k = 0; k < 3; k++) {
                l[k] = zero + lt->vec[k];
            }
        }
        sr_v4f ndotl = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
        use &= ~(ndotl <= zero);
        sr_v4f kd = ndotl;
        r = sr__v4_sel(use, r + lt->color[0] * dif[0] * kd, r);
        g = sr__v4_sel(use, g + lt->color[1] * dif[1] * kd, g);
        b = sr__v4_sel(use, b + lt->color[2] * dif[2] * kd, b);
        if (spec) {
            sr_v4f h[3] = { l[0] + v[0], l[1] + v[1], l[2] + v[2] };
            sr_v4f hl = sr__v4_sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
            sr_v4i hs = use & (hl > zero);
            sr_v4f ndoth = (n[0] * h[0] + n[1] * h[1] + n[2] * h[2]) / hl;
            hs &= ndoth > zero;
            sr_v4f x = ndoth, p = zero + 1.0f;
            for (int e = ds->shininess_int; e; e >>= 1) {
                if (e & 1) {
                    p *= x;
                }
                x *= x;
            }
            r = sr__v4_sel(hs, r + lt->color[0] * ds->specular[0] * p, r);
            g = sr__v4_sel(hs, g + lt->color[1] * ds->specular[1] * p, g);
            b = sr__v4_sel(hs, b + lt->color[2] * ds->specular[2] * p, b);
        }
    }
    out[0] = r;
    out[1] = g;
    out[2] = b;
    out[3] = dif[3];
}

#endif
