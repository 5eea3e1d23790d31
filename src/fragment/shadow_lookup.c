/* shadow_lookup.c - the shadow map's lookup (fragment stage, called from
 * shaders): a world-space point, moved along its normal, to the light's
 * texel space, then percentage-closer filtering over a box of the map.
 * Reads the map only: any number of threads at once, between draws.
 * Every lane is the same arithmetic in the same order, so a point's
 * visibility does not depend on the call, the lane or the thread. */
#include "fragment/shadow.h"
#include "error.h"
#include "fragment/light_lanes.h"   /* sr__v4_sel, sr__v4_sqrt */

#include <math.h>
#include <string.h>

/* The filter box spans at most 2 x SR_SHADOW_MAX_RADIUS texels, so it
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

/* Four points (SoA: x, y, z lanes) taken to the map: texel u, v and
 * window depth in out[0..2], and in out[3..5] how far each of those moves
 * for a normal offset of one texel.  Lane-wise IEEE operations only, so a
 * point gives the same bits in any lane. */
static void to_map(const sr_shadow_map *sm, const float *pos, const float *n, v4f out[6])
{
    v4f x, y, z;
    memcpy(&x, pos, sizeof x), memcpy(&y, pos + 4, sizeof y), memcpy(&z, pos + 8, sizeof z);
    const float (*m)[4] = sm->to_map;
    for (int r = 0; r < 3; r++) {
        out[r] = m[r][0] * x + m[r][1] * y + m[r][2] * z + m[r][3];
        out[3 + r] = (v4f){ 0 };
    }
    if (!n) {
        return;
    }
    v4f nx, ny, nz;
    memcpy(&nx, n, sizeof nx), memcpy(&ny, n + 4, sizeof ny), memcpy(&nz, n + 8, sizeof nz);
    v4f len2 = nx * nx + ny * ny + nz * nz;
    /* The move is along the unit normal, times the sine of its angle to
     * the light (why: visibility()); a zero or non-finite normal does not
     * move the point. */
    v4i ok = (len2 > 0.0f) & (len2 < INFINITY);
    sr_vec3 l = sm->toward_light;
    /* sin t / |n| = sqrt(|n|^2 - (n.l)^2) / |n|^2: one root, one divide. */
    v4f nl = nx * l.x + ny * l.y + nz * l.z;
    v4f s2 = len2 - nl * nl;
    v4f s = sr__v4_sqrt(sr__v4_sel(s2 > 0.0f, s2, (v4f){ 0 }));
    v4f k = sr__v4_sel(ok, s * sm->texel_size / sr__v4_sel(ok, len2, (v4f){ 1, 1, 1, 1 }), (v4f){ 0 });
    nx *= k, ny *= k, nz *= k;
    for (int r = 0; r < 3; r++) {
        out[3 + r] = m[r][0] * nx + m[r][1] * ny + m[r][2] * nz;
    }
}

/* Percentage-closer soft shadows' first step: the mean depth of the
 * blockers (texels nearer the light than the point) on a 4 x 4 grid over
 * the widest region that could hold one, and from it the penumbra's
 * half-width, (receiver - blocker distance) x tan(light radius), in
 * texels, within [filter_radius, SR_SHADOW_MAX_RADIUS]. */
static float penumbra_radius(const sr_shadow_map *sm, float u, float v, uint32_t zq)
{
    float per_texel = sm->depth_extent * sm->light_tan / sm->texel_size;
    float lo = sm->filter_radius;
    /* A blocker lies between the near plane and the point. */
    float rs = minf(maxf((float)zq * (1.0f / 16777215.0f) * per_texel, lo), SR_SHADOW_MAX_RADIUS);
    /* No texel of the region nearer than the point: no blocker, which the
     * grid below would find too. */
    if (block_verdict(sm, zq, floor_int(u - rs), floor_int(v - rs), floor_int(u + rs),
                      floor_int(v + rs)) == 1) {
        return lo;
    }
    int size = sm->size;
    uint64_t sum = 0;
    int count = 0;
    for (int b = 0; b < 4; b++) {
        int j = floor_int(v + rs * (0.5f * (float)b - 0.75f));
        for (int a = 0; a < 4; a++) {
            int i = floor_int(u + rs * (0.5f * (float)a - 0.75f));
            if (i >= 0 && j >= 0 && i < size && j < size) {
                uint32_t d = sm->depth[(size_t)j * (size_t)size + (size_t)i];
                if (d < zq) {
                    sum += d;
                    count++;
                }
            }
        }
    }
    if (count == 0) {
        return lo;
    }
    float gap = (float)(zq - (uint32_t)(sum / (uint64_t)count)) * (1.0f / 16777215.0f);
    return minf(maxf(gap * per_texel, lo), SR_SHADOW_MAX_RADIUS);
}

/* The filtered visibility of a point at texel (u, v), window depth w,
 * which a normal offset of one texel moves by (du, dv, dw). */
static float visibility(const sr_shadow_map *sm, float u, float v, float w, float du, float dv,
                        float dw)
{
    float r = sm->filter_radius;
    int size = sm->size;
    /* Far outside the map, or not finite: nothing drawn there.  (The
     * bound keeps every texel index below within int.) */
    if (!(fabsf(u) < 1e7f && fabsf(v) < 1e7f && isfinite(w))) {
        return 1.0f;
    }
    if (sm->light_tan > 0.0f) {
        float d0 = sm->normal_offset + 1.5f * r;
        r = penumbra_radius(sm, u + d0 * du, v + d0 * dv, depth_q24(w + d0 * dw));
    }
    /* Outer taps lie up to (r + 1/2) sqrt 2 texels from the point; on a
     * plane at angle t to the light their depth differs by that distance
     * times tan t, which a move of d along the normal (d / cos t along the
     * light) outruns when d exceeds the distance times sin t. */
    float move = sm->normal_offset + 1.5f * r;
    u += move * du, v += move * dv, w += move * dw;
    if (!(u + r > 0.0f && v + r > 0.0f && u - r < (float)size && v - r < (float)size)) {
        return 1.0f;   /* outside the map */
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

/* The four lanes of a fragment quad usually lie within a texel or two of
 * each other: one block test over the union of their filter boxes, with
 * the nearest and farthest of their depths, settles them all at once
 * when they are all lit or all in shadow.  Then each lane's own test
 * would have said the same, so the values equal visibility()'s; -1 when
 * the lanes must go one by one.  With a light of some size the radius is
 * not known yet: the union takes the widest filter, and the point at both
 * ends of the normal offsets that radius range gives (the move is linear
 * in the offset, so every offset's point lies between them). */
static float quad_verdict(const sr_shadow_map *sm, const float *pos, const v4f m[6])
{
    float r = sm->light_tan > 0.0f ? SR_SHADOW_MAX_RADIUS : sm->filter_radius;
    float moves[2] = { sm->normal_offset + 1.5f * sm->filter_radius, sm->normal_offset + 1.5f * r };
    int ends = moves[1] != moves[0] ? 2 : 1;
    int i0 = INT32_MAX, j0 = INT32_MAX, i1 = INT32_MIN, j1 = INT32_MIN;
    uint32_t zlo = UINT32_MAX, zhi = 0;
    for (int i = 0; i < 4; i++) {
        if (!(finite_point(pos[i], pos[4 + i], pos[8 + i]) && fabsf(m[0][i]) < 1e7f &&
              fabsf(m[1][i]) < 1e7f && isfinite(m[2][i]))) {
            return -1.0f;
        }
        for (int e = 0; e < ends; e++) {
            /* As visibility() moves the point. */
            float u = m[0][i] + moves[e] * m[3][i];
            float v = m[1][i] + moves[e] * m[4][i];
            float w = m[2][i] + moves[e] * m[5][i];
            int a = floor_int(u - r), b = floor_int(v - r), c = floor_int(u + r), d = floor_int(v + r);
            i0 = a < i0 ? a : i0, j0 = b < j0 ? b : j0;
            i1 = c > i1 ? c : i1, j1 = d > j1 ? d : j1;
            uint32_t zq = depth_q24(w);
            zlo = zq < zlo ? zq : zlo, zhi = zq > zhi ? zq : zhi;
        }
    }
    int size = sm->size;
    if (i1 < 0 || j1 < 0 || i0 >= size || j0 >= size) {
        return 1.0f;   /* all four off the map */
    }
    /* A union too wide (lanes far apart) costs more blocks than it saves. */
    if (i1 - i0 > 4 * SR_SHADOW_BLOCK_SIZE || j1 - j0 > 4 * SR_SHADOW_BLOCK_SIZE) {
        return -1.0f;
    }
    if (block_verdict(sm, zhi, i0, j0, i1, j1) == 1) {
        return 1.0f;
    }
    return block_verdict(sm, zlo, i0, j0, i1, j1) == 0 ? 0.0f : -1.0f;
}

/* The message for a lookup given a NULL sm, pos or out. */
static sr_result lookup_null(const sr_shadow_map *sm, const float *pos, const char *fn)
{
    return sr__fail(NULL, SR_INVALID_ARG, "%s: %s is NULL", fn,
                    !sm ? "sm" : !pos ? "pos" : "out");
}

sr_result sr_shadow_visibility(const sr_shadow_map *sm, const float pos[3], const float normal[3],
                               float *out)
{
    if (!sm || !pos || !out) {
        return lookup_null(sm, pos, "sr_shadow_visibility");
    }
    /* Lane 0 of the four-lane path, the others copies of it. */
    float p[12], n[12];
    for (int c = 0; c < 3; c++) {
        for (int i = 0; i < 4; i++) {
            p[4 * c + i] = pos[c];
            n[4 * c + i] = normal ? normal[c] : 0.0f;
        }
    }
    v4f m[6];
    to_map(sm, p, normal ? n : NULL, m);
    *out = finite_point(pos[0], pos[1], pos[2])
           ? visibility(sm, m[0][0], m[1][0], m[2][0], m[3][0], m[4][0], m[5][0]) : 1.0f;
    return SR_OK;
}

sr_result sr_shadow_visibility4(const sr_shadow_map *sm, const float *pos, const float *normal,
                                float out[4])
{
    if (!sm || !pos || !out) {
        return lookup_null(sm, pos, "sr_shadow_visibility4");
    }
    v4f m[6];
    to_map(sm, pos, normal, m);
    float quad = quad_verdict(sm, pos, m);
    for (int i = 0; i < 4; i++) {
        out[i] = quad >= 0.0f ? quad
                 : finite_point(pos[i], pos[4 + i], pos[8 + i])
                 ? visibility(sm, m[0][i], m[1][i], m[2][i], m[3][i], m[4][i], m[5][i]) : 1.0f;
    }
    return SR_OK;
}
