/* pbr_lanes.h - the PBR program's four-lane arithmetic (fragment stage):
 * min, max, clamps, dot products and correctly rounded reciprocals on
 * v4f, shared by pbr.c and the material extensions' lobes
 * (pbr_clearcoat.c, pbr_sheen.c).  Pure; any thread.  Every includer is
 * compiled with -fno-math-errno so sqrtf becomes one instruction. */
#ifndef SR_PBR_LANES_H
#define SR_PBR_LANES_H

#include "fragment/environment.h"
#include "fragment/light_lanes.h"

#include <string.h>

#define PI_F          3.14159265358979f
#define MIN_ROUGHNESS 0.05f     /* a perfect mirror has no highlight from a point light */

/* min and max as comparisons: one instruction each, where fminf and
 * fmaxf are library calls that stop the lane loops from vectorizing. */
static inline float min_f(float a, float b)
{
    return a < b ? a : b;
}

static inline float max_f(float a, float b)
{
    return a > b ? a : b;
}

static inline float clamp01(float a)
{
    return min_f(max_f(a, 0.0f), 1.0f);
}

static inline v4f load(const float a[4])
{
    v4f v;
    memcpy(&v, a, sizeof v);
    return v;
}

static inline void store(float a[4], v4f v)
{
    memcpy(a, &v, sizeof v);
}

static inline void load3(v4f v[3], const float a[][4])
{
    for (int k = 0; k < 3; k++) {
        v[k] = load(a[k]);
    }
}

static inline v4f dot3(const v4f a[3], const v4f b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* a < b ? a : b and a > b ? a : b lane by lane, NaN and zeros' signs
 * included: exactly what minps and maxps compute, one instruction where
 * the select is three. */
static inline v4f vmin(v4f a, v4f b)
{
#if defined(__SSE__)
    return (v4f)_mm_min_ps((__m128)a, (__m128)b);
#else
    return sr__v4_sel(a < b, a, b);
#endif
}

static inline v4f vmax(v4f a, v4f b)
{
#if defined(__SSE__)
    return (v4f)_mm_max_ps((__m128)a, (__m128)b);
#else
    return sr__v4_sel(a > b, a, b);
#endif
}

/* 1 / sqrt(x) and 1 / x, correctly rounded (sqrtps, divps): the SSE
 * estimates would be quicker but differ between CPU vendors, and the same
 * scene must give the same bytes on every machine. */
static inline v4f rsqrt_nr(v4f x)
{
    return 1.0f / sr__v4_sqrt(x);
}

static inline v4f rcp_nr(v4f x)
{
    return 1.0f / x;
}

/* NaN goes to lo. */
static inline v4f vclamp(v4f a, float lo, float hi)
{
    return vmin(vmax(a, lo - (v4f){ 0 }), hi - (v4f){ 0 });
}

/* The split sum's scale and bias of F0 (Es = F0 A + F90 B), read
 * bilinearly from the table the build integrated for this very BRDF
 * (brdf_integrate.c) rather than from an analytic fit of another
 * renderer's: the multiple-scattering terms take 1 - (A + B) as what
 * single scattering loses, so A + B must be this lobe's own albedo.  rc
 * is the roughness clamped to 0..1. */
static inline void split_sum(v4f rc, v4f nv, v4f *sa, v4f *sb)
{
    float r[4], n[4], a[4], b[4];
    store(r, rc);
    store(n, nv);
    sr__brdf_lookup4(n, r, a, b);
    *sa = load(a);
    *sb = load(b);
}

#endif
