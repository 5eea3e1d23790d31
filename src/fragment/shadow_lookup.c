/* shadow_lookup.c - the shadow map's lookup (fragment stage, called from
 * shaders): a world-space point, moved along its normal, to the light's
 * texel space, then percentage-closer filtering over a box of the map.
 * Reads the map only: any number of threads at once, between draws.
 * Every lane is the same arithmetic in the same order, so a point's
 * visibility does not depend on the call, the lane or the thread. */
#include "fragment/shadow.h"

#include <math.h>
#include <string.h>

/* The filter box spans at most 2 x 8 texels (MAX_FILTER_RADIUS), so it
 * touches at most 18 texels a row. */
#define MAX_TAPS 18

static uint32_t depth_bits(float z)
{
    /* Clamped as the rasterizer clamps depth before storing it (NaN was
     * turned away before). */
    z = z > 0.0f ? (z < 1.0f ? z : 1.0f) : 0.0f;
    uint32_t u;
    memcpy(&u, &z, sizeof u);
    return u;
}

/* Weights of the texels a box [c - r, c + r] (texel edges at integers)
 * overlaps, first texel *first: each the overlapped length over 2r, so
 * they sum to 1 and slide continuously with c. */
static int box_weights(float c, float r, int *first, float w[MAX_TAPS])
{
    float a = c - r, b = c + r;
    int i0 = (int)floorf(a), i1 = (int)floorf(b);
    int n = i1 - i0 + 1;
    float inv = 0.5f / r;
    for (int k = 0; k < n; k++) {
        float lo = fmaxf((float)(i0 + k), a), hi = fminf((float)(i0 + k + 1), b);
        w[k] = (hi - lo) * inv;
    }
    *first = i0;
    return n;
}

static float visibility(const sr_shadow_map *sm, float x, float y, float z, const float *n, int stride)
{
    if (!(isfinite(x) && isfinite(y) && isfinite(z))) {
        return 1.0f;
    }
    if (n) {
        float nx = n[0], ny = n[stride], nz = n[2 * stride];
        float len2 = nx * nx + ny * ny + nz * nz;
        if (len2 > 0.0f && isfinite(len2)) {
            /* Outer taps lie up to (r + 1/2) sqrt 2 texels from the point;
             * on a plane at angle t to the light their depth differs by
             * that distance times tan t, which a move of d along the
             * normal (d / cos t along the light) outruns when d exceeds
             * the distance times sin t. */
            float inv_len = 1.0f / sqrtf(len2);
            sr_vec3 l = sm->toward_light;
            float c = (nx * l.x + ny * l.y + nz * l.z) * inv_len;
            float s = sqrtf(fmaxf(0.0f, 1.0f - c * c));
            float d = s * (sm->normal_offset + 1.5f * sm->filter_radius) * sm->texel_size * inv_len;
            x += nx * d, y += ny * d, z += nz * d;
        }
    }
    const float (*m)[4] = sm->to_map;
    float u = m[0][0] * x + m[0][1] * y + m[0][2] * z + m[0][3];
    float v = m[1][0] * x + m[1][1] * y + m[1][2] * z + m[1][3];
    uint32_t zq = depth_bits(m[2][0] * x + m[2][1] * y + m[2][2] * z + m[2][3]);
    float r = sm->filter_radius;
    int size = sm->size;
    if (!(u + r > 0.0f && v + r > 0.0f && u - r < (float)size && v - r < (float)size)) {
        return 1.0f;   /* outside the map: nothing drawn there */
    }
    float wx[MAX_TAPS], wy[MAX_TAPS];
    int i0, j0;
    int nx = box_weights(u, r, &i0, wx);
    int ny = box_weights(v, r, &j0, wy);
    float lit = 0.0f;
    for (int b = 0; b < ny; b++) {
        int j = j0 + b;
        float row = 0.0f;
        if (j < 0 || j >= size) {
            row = 1.0f;
        } else {
            const uint32_t *d = sm->depth + (size_t)j * (size_t)size;
            for (int a = 0; a < nx; a++) {
                int i = i0 + a;
                /* Off the map's edge counts as lit; on it, lit where the
                 * nearest occluder is no nearer than the point. */
                bool pass = i < 0 || i >= size || zq <= d[i];
                row += pass ? wx[a] : 0.0f;
            }
        }
        lit += wy[b] * row;
    }
    return fminf(fmaxf(lit, 0.0f), 1.0f);
}

sr_result sr_shadow_visibility(const sr_shadow_map *sm, const float pos[3], const float normal[3],
                               float *out)
{
    if (!sm || !pos || !out) {
        return SR_INVALID_ARG;
    }
    *out = visibility(sm, pos[0], pos[1], pos[2], normal, 1);
    return SR_OK;
}

sr_result sr_shadow_visibility4(const sr_shadow_map *sm, const float *pos, const float *normal,
                                float out[4])
{
    if (!sm || !pos || !out) {
        return SR_INVALID_ARG;
    }
    for (int i = 0; i < 4; i++) {
        out[i] = visibility(sm, pos[i], pos[4 + i], pos[8 + i], normal ? normal + i : NULL, 4);
    }
    return SR_OK;
}
