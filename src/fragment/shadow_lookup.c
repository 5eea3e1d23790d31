/* shadow_lookup.c - the shadow map's lookup (fragment stage, called from
 * shaders): a world-space point, moved along its normal, to the light's
 * texel space, then percentage-closer filtering over a box of the map.
 * Reads the map only: any number of threads at once, between draws.
 * Every lane is the same arithmetic in the same order, so a point's
 * visibility does not depend on the call, the lane or the thread. */
#include "fragment/shadow.h"
#include "fragment/light_lanes.h"   /* sr__v4_sel, sr__v4_sqrt */

#include <math.h>
#include <string.h>

/* The filter box spans at most 2 x 8 texels (MAX_FILTER_RADIUS), so it
 * touches at most 18 texels a row. */
#define MAX_TAPS 18

/* The receiver's depth quantized as the D24 buffer stores it
 * (fragment/depth.h): clamped, then k = floor(z (2^24 - 1) + 1/2).  NaN
 * was turned away before. */
static uint32_t depth_q24(float z)
{
    double d = z > 0.0f ? (z < 1.0f ? (double)z : 1.0) : 0.0;
    return (uint32_t)(d * 16777215.0 + 0.5);   /* truncation is floor: d >= 0 */
}

static float maxf(float a, float b)
{
    return a > b ? a : b;
}

static float minf(float a, float b)
{
    return a < b ? a : b;
}

/* floorf for |x| < 2^31, without a library call (SSE2 has no floor). */
static int floor_int(float x)
{
    int i = (int)x;
    return (float)i > x ? i - 1 : i;
}

/* Weights of the n texels from i0 on that a box [c - r, c + r] (texel
 * edges at integers) overlaps: each the overlapped length, so they slide
 * continuously with c. */
static void box_weights(float c, float r, int i0, int n, float w[MAX_TAPS])
{
    float a = c - r, b = c + r;
    for (int k = 0; k < n; k++) {
        w[k] = minf((float)(i0 + k + 1), b) - maxf((float)(i0 + k), a);
    }
}

/* Every texel of [i0, i1] x [j0, j1] that lies on the map compares the
 * same way with zq: 1 all pass (lit), 0 all fail, -1 mixed or unknown.
 * Texels off the map pass, so a box reaching past the edge is never all
 * failing. */
static int block_verdict(const sr_shadow_map *sm, uint32_t zq, int i0, int j0, int i1, int j1)
{
    int size = sm->size;
    bool off = i0 < 0 || j0 < 0 || i1 >= size || j1 >= size;
    int bx0 = (i0 > 0 ? i0 : 0) >> SR_SHADOW_BLOCK_ORDER;
    int by0 = (j0 > 0 ? j0 : 0) >> SR_SHADOW_BLOCK_ORDER;
    int bx1 = (i1 < size ? i1 : size - 1) >> SR_SHADOW_BLOCK_ORDER;
    int by1 = (j1 < size ? j1 : size - 1) >> SR_SHADOW_BLOCK_ORDER;
    uint32_t lo = UINT32_MAX, hi = 0;
    for (int by = by0; by <= by1; by++) {
        for (int bx = bx0; bx <= bx1; bx++) {
            size_t b = (size_t)by * (size_t)sm->blocks + (size_t)bx;
            lo = sm->block_min[b] < lo ? sm->block_min[b] : lo;
            hi = sm->block_max[b] > hi ? sm->block_max[b] : hi;
        }
    }
    if (zq <= lo) {
        return 1;
    }
    return zq > hi && !off ? 0 : -1;
}

/* Four points (SoA: x, y, z lanes) moved along their normals (SoA, or
 * NULL) and taken to the map: texel u, v and window depth.  Lane-wise
 * IEEE operations only, so a point gives the same bits in any lane. */
static void to_map(const sr_shadow_map *sm, const float *pos, const float *n, v4f out[3])
{
    v4f x, y, z;
    memcpy(&x, pos, sizeof x), memcpy(&y, pos + 4, sizeof y), memcpy(&z, pos + 8, sizeof z);
    if (n) {
        v4f nx, ny, nz;
        memcpy(&nx, n, sizeof nx), memcpy(&ny, n + 4, sizeof ny), memcpy(&nz, n + 8, sizeof nz);
        v4f len2 = nx * nx + ny * ny + nz * nz;
        /* Outer taps lie up to (r + 1/2) sqrt 2 texels from the point; on
         * a plane at angle t to the light their depth differs by that
         * distance times tan t, which a move of d along the normal (d /
         * cos t along the light) outruns when d exceeds the distance
         * times sin t.  A zero or non-finite normal does not move it. */
        v4i ok = (len2 > 0.0f) & (len2 < INFINITY);
        v4f inv_len = 1.0f / sr__v4_sqrt(sr__v4_sel(ok, len2, (v4f){ 1, 1, 1, 1 }));
        sr_vec3 l = sm->toward_light;
        v4f c = (nx * l.x + ny * l.y + nz * l.z) * inv_len;
        v4f sin2 = 1.0f - c * c;
        v4f s = sr__v4_sqrt(sr__v4_sel(sin2 > 0.0f, sin2, (v4f){ 0 }));
        float k = (sm->normal_offset + 1.5f * sm->filter_radius) * sm->texel_size;
        v4f d = sr__v4_sel(ok, s * k * inv_len, (v4f){ 0 });
        x += nx * d, y += ny * d, z += nz * d;
    }
    const float (*m)[4] = sm->to_map;
    for (int r = 0; r < 3; r++) {
        out[r] = m[r][0] * x + m[r][1] * y + m[r][2] * z + m[r][3];
    }
}

/* The filtered visibility of a point at texel (u, v), window depth w. */
static float visibility(const sr_shadow_map *sm, float u, float v, float w)
{
    float r = sm->filter_radius;
    int size = sm->size;
    if (!(u + r > 0.0f && v + r > 0.0f && u - r < (float)size && v - r < (float)size)) {
        return 1.0f;   /* outside the map, or not finite: nothing drawn there */
    }
    uint32_t zq = depth_q24(w);
    int i0 = floor_int(u - r), i1 = floor_int(u + r);
    int j0 = floor_int(v - r), j1 = floor_int(v + r);
    int verdict = block_verdict(sm, zq, i0, j0, i1, j1);
    if (verdict >= 0) {
        return (float)verdict;
    }
    float wx[MAX_TAPS], wy[MAX_TAPS];
    int nx = i1 - i0 + 1, ny = j1 - j0 + 1;
    box_weights(u, r, i0, nx, wx);
    box_weights(v, r, j0, ny, wy);
    /* Lit and total weight summed alike, so a box that passes everywhere
     * gives exactly 1, as the block test does. */
    float lit = 0.0f, total = 0.0f;
    for (int b = 0; b < ny; b++) {
        int j = j0 + b;
        const uint32_t *d = j >= 0 && j < size ? sm->depth + (size_t)j * (size_t)size : NULL;
        float row = 0.0f, all = 0.0f;
        for (int a = 0; a < nx; a++) {
            int i = i0 + a;
            /* Off the map's edge counts as lit; on it, lit where the
             * nearest occluder is no nearer than the point. */
            bool pass = !d || i < 0 || i >= size || zq <= d[i];
            row += pass ? wx[a] : 0.0f;
            all += wx[a];
        }
        lit += wy[b] * row;
        total += wy[b] * all;
    }
    return minf(lit / total, 1.0f);
}

static bool finite_point(float x, float y, float z)
{
    return isfinite(x) && isfinite(y) && isfinite(z);
}

sr_result sr_shadow_visibility(const sr_shadow_map *sm, const float pos[3], const float normal[3],
                               float *out)
{
    if (!sm || !pos || !out) {
        return SR_INVALID_ARG;
    }
    /* Lane 0 of the four-lane path, the others copies of it. */
    float p[12], n[12];
    for (int c = 0; c < 3; c++) {
        for (int i = 0; i < 4; i++) {
            p[4 * c + i] = pos[c];
            n[4 * c + i] = normal ? normal[c] : 0.0f;
        }
    }
    v4f m[3];
    to_map(sm, p, normal ? n : NULL, m);
    *out = finite_point(pos[0], pos[1], pos[2]) ? visibility(sm, m[0][0], m[1][0], m[2][0]) : 1.0f;
    return SR_OK;
}

sr_result sr_shadow_visibility4(const sr_shadow_map *sm, const float *pos, const float *normal,
                                float out[4])
{
    if (!sm || !pos || !out) {
        return SR_INVALID_ARG;
    }
    v4f m[3];
    to_map(sm, pos, normal, m);
    for (int i = 0; i < 4; i++) {
        out[i] = finite_point(pos[i], pos[4 + i], pos[8 + i])
                 ? visibility(sm, m[0][i], m[1][i], m[2][i]) : 1.0f;
    }
    return SR_OK;
}
