/* texture.h - texture storage and sampling (fragment stage; read-only
 * after creation, so any tile worker may sample concurrently). */
#ifndef SR_TEXTURE_H
#define SR_TEXTURE_H

#include "softrast.h"

#define SR_TEXTURE_MAX_SIZE 16384
#define SR_TEXTURE_MAX_LEVELS 15   /* 16384 -> 1 */

struct sr_texture {
    int levels;
    int width[SR_TEXTURE_MAX_LEVELS], height[SR_TEXTURE_MAX_LEVELS];
    uint8_t *texels[SR_TEXTURE_MAX_LEVELS];   /* RGBA8 rows, row 0 at the top */
    bool srgb;
    /* A byte's value in [0, 1] for the color channels (decoded from sRGB
     * when srgb) and for alpha: exactly what the division (and powf)
     * would give, looked up instead of computed for every texel fetched. */
    float color_value[256], alpha_value[256];
};

/* Texel index along one axis of n texels under a wrap mode (the scalar
 * sampler's, and the vector kernel's for coordinates outside the image). */
static inline int sr__texture_wrap(int i, int n, sr_texture_wrap mode)
{
    /* Inside the image every mode is the identity: no division for the
     * common case. */
    if (i >= 0 && i < n) {
        return i;
    }
    switch (mode) {
    case SR_WRAP_CLAMP:
        return i < 0 ? 0 : i >= n ? n - 1 : i;
    case SR_WRAP_MIRROR: {
        int period = 2 * n;
        int m = i % period;
        m = m < 0 ? m + period : m;
        return m < n ? m : period - 1 - m;
    }
    default: {
        int m = i % n;
        return m < 0 ? m + n : m;
    }
    }
}

/* Filtered texel at (u, v) for a level of detail lod = log2 of the texels
 * per pixel at level 0; rgba in [0, 1].  An sRGB texture is filtered in
 * linear light and its colour encoded back to sRGB, the fixed-function
 * texture's contract; sr__texture_sample_linear leaves it linear, as a
 * shader working in linear light wants it. */
void sr__texture_sample_linear(const sr_texture *t, sr_texture_filter filter, sr_texture_wrap wu,
                               sr_texture_wrap wv, float u, float v, float lod, float out[4]);
void sr__texture_sample(const sr_texture *t, sr_texture_filter filter, sr_texture_wrap wu,
                        sr_texture_wrap wv, float u, float v, float lod, float out[4]);

/* Level of detail from the texture-coordinate derivatives along x and y
 * (texture units per pixel): log2 of the larger footprint side in texels. */
float sr__texture_lod(const sr_texture *t, float dudx, float dvdx, float dudy, float dvdy);
/* Its last step, from rho^2 = the larger squared footprint in texels
 * (the vector kernel computes rho^2 in lanes, then calls this). */
float sr__texture_lod_rho2(float rho2);

/* A slot's KHR_texture_transform (already in sr_texture's frame, v up) as
 * u' = xf[0] u + xf[1] v + xf[2], v' = xf[3] u + xf[4] v + xf[5]:
 * uv' = T(offset) R(rotation) S(scale) uv, R counter-clockwise
 * (texture_slot.c; the PBR program and sr_texture_slot_uv share it). */
void sr__texture_slot_matrix(const sr_texture_slot *slot, float xf[6]);

#endif
