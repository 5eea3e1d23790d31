/* texture.c - textures: creation with a mip chain, and sampling with
 * nearest, bilinear and trilinear filtering and three wrap modes (fragment
 * stage).  Textures are read-only once made; tile workers sample them
 * concurrently. */
#include "fragment/texture.h"
#include "context.h"
#include "rows.h"

#include <math.h>
#include <string.h>

/* sRGB transfer functions (IEC 61966-2-1). */
static float srgb_to_linear(float c)
{
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

static float linear_to_srgb(float c)
{
    return c <= 0.0031308f ? c * 12.92f : 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
}

static uint8_t to_byte(float v)
{
    v = v > 0.0f ? v : 0.0f;
    v = v < 1.0f ? v : 1.0f;
    return (uint8_t)(v * 255.0f + 0.5f);
}

/* Level k+1 from level k: each texel the average of the 2x2 block above it
 * (a box filter; an odd last row or column repeats its edge). */
static void downsample(const sr_texture *t, int k, uint8_t *dst)
{
    int w = t->width[k], h = t->height[k];
    int nw = t->width[k + 1], nh = t->height[k + 1];
    const uint8_t *src = t->texels[k];
    for (int y = 0; y < nh; y++) {
        for (int x = 0; x < nw; x++) {
            int x0 = 2 * x < w ? 2 * x : w - 1, x1 = 2 * x + 1 < w ? 2 * x + 1 : w - 1;
            int y0 = 2 * y < h ? 2 * y : h - 1, y1 = 2 * y + 1 < h ? 2 * y + 1 : h - 1;
            const uint8_t *p[4] = { src + ((size_t)y0 * w + x0) * 4, src + ((size_t)y0 * w + x1) * 4,
                                    src + ((size_t)y1 * w + x0) * 4, src + ((size_t)y1 * w + x1) * 4 };
            for (int c = 0; c < 4; c++) {
                float sum = 0.0f;
                /* The decode tables hold srgb_to_linear(i / 255) (or i / 255):
                 * the same values as calling it, without a powf each. */
                const float *value = c < 3 ? t->color_value : t->alpha_value;
                for (int i = 0; i < 4; i++) {
                    sum += value[p[i][c]];
                }
                float avg = sum * 0.25f;
                dst[((size_t)y * nw + x) * 4 + c] = to_byte((t->srgb && c < 3) ? linear_to_srgb(avg) : avg);
            }
        }
    }
}

sr_result sr_make_texture(sr_context *ctx, const sr_texture_desc *desc, sr_texture **out)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_make_texture: ctx is NULL");
    }
    if (!out || !desc) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_make_texture: %s is NULL", out ? "desc" : "out");
    }
    *out = NULL;
    if (desc->width < 1 || desc->height < 1 || desc->width > SR_TEXTURE_MAX_SIZE ||
        desc->height > SR_TEXTURE_MAX_SIZE) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_texture_desc.%s must be 1..%d (got %d)",
                        (desc->width < 1 || desc->width > SR_TEXTURE_MAX_SIZE) ? "width" : "height",
                        SR_TEXTURE_MAX_SIZE,
                        (desc->width < 1 || desc->width > SR_TEXTURE_MAX_SIZE) ? desc->width
                                                                                : desc->height);
    }
    if (!desc->pixels) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_texture_desc.pixels is NULL");
    }
    size_t stride = desc->stride ? desc->stride : (size_t)desc->width * 4;
    if (stride < (size_t)desc->width * 4) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_texture_desc.stride %zu < 4 * width", stride);
    }
    if (!sr__rows_fit(desc->pixels, (size_t)desc->height, stride, (size_t)desc->width * 4)) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_texture_desc: %d rows of stride %zu run past the end of memory",
                        desc->height, stride);
    }
    sr_texture *t = sr__calloc(ctx, 1, sizeof *t);
    if (!t) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_make_texture: out of memory");
    }
    t->srgb = desc->srgb;
    for (int i = 0; i < 256; i++) {
        float v = i / 255.0f;
        t->color_value[i] = t->srgb ? srgb_to_linear(v) : v;
        t->alpha_value[i] = v;
    }
    int w = desc->width, h = desc->height;
    for (int k = 0; k < SR_TEXTURE_MAX_LEVELS; k++) {
        t->width[k] = w;
        t->height[k] = h;
        t->texels[k] = sr__alloc(ctx, (size_t)w * (size_t)h * 4);
        if (!t->texels[k]) {
            sr_destroy_texture(ctx, t);
            return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_make_texture: out of memory for %dx%d", w, h);
        }
        t->levels = k + 1;
        if (k == 0) {
            for (int y = 0; y < h; y++) {
                memcpy(t->texels[0] + (size_t)y * w * 4, desc->pixels + (size_t)y * stride,
                       (size_t)w * 4);
            }
        } else {
            downsample(t, k - 1, t->texels[k]);
        }
        if (w == 1 && h == 1) {
            break;
        }
        w = w > 1 ? w / 2 : 1;
        h = h > 1 ? h / 2 : 1;
    }
    *out = t;
    sr__ok(ctx);
    return SR_OK;
}

void sr_destroy_texture(sr_context *ctx, sr_texture *t)
{
    if (!ctx || !t) {
        return;
    }
    for (int k = 0; k < t->levels; k++) {
        sr__free(ctx, t->texels[k]);
    }
    sr__free(ctx, t);
}

int sr_texture_levels(const sr_texture *t)
{
    return t ? t->levels : 0;
}

static void fetch(const sr_texture *t, int k, int x, int y, float out[4])
{
    const uint8_t *p = t->texels[k] + ((size_t)y * t->width[k] + x) * 4;
    out[0] = t->color_value[p[0]];
    out[1] = t->color_value[p[1]];
    out[2] = t->color_value[p[2]];
    out[3] = t->alpha_value[p[3]];
}

/* Texel space: u in [0, 1] spans the width with texel centres at
 * (i + 1/2) / w; v = 0 is the bottom row, so the row index runs down from
 * the top as 1 - v. */
static void sample_level(const sr_texture *t, int k, bool linear, sr_texture_wrap wu,
                         sr_texture_wrap wv, float u, float v, float out[4])
{
    int w = t->width[k], h = t->height[k];
    /* Far outside [0, 1] the fraction has no precision left anyway; the
     * clamp keeps the conversions to int defined. */
    float x = u * (float)w, y = (1.0f - v) * (float)h;
    /* fmaxf/fminf as comparisons (u, v are finite here, so no NaN): the
     * same values without two library calls per coordinate. */
    x = x > -1e7f ? x : -1e7f;
    x = x < 1e7f ? x : 1e7f;
    y = y > -1e7f ? y : -1e7f;
    y = y < 1e7f ? y : 1e7f;
    if (!linear) {
        int xi = sr__texture_wrap((int)floorf(x), w, wu), yi = sr__texture_wrap((int)floorf(y), h, wv);
        fetch(t, k, xi, yi, out);
        return;
    }
    x -= 0.5f;
    y -= 0.5f;
    float fx = floorf(x), fy = floorf(y);
    float ax = x - fx, ay = y - fy;
    int x0 = sr__texture_wrap((int)fx, w, wu), x1 = sr__texture_wrap((int)fx + 1, w, wu);
    int y0 = sr__texture_wrap((int)fy, h, wv), y1 = sr__texture_wrap((int)fy + 1, h, wv);
    float p00[4], p10[4], p01[4], p11[4];
    fetch(t, k, x0, y0, p00);
    fetch(t, k, x1, y0, p10);
    fetch(t, k, x0, y1, p01);
    fetch(t, k, x1, y1, p11);
    for (int c = 0; c < 4; c++) {
        float top = p00[c] + ax * (p10[c] - p00[c]);
        float bottom = p01[c] + ax * (p11[c] - p01[c]);
        out[c] = top + ay * (bottom - top);
    }
}

float sr__texture_lod(const sr_texture *t, float dudx, float dvdx, float dudy, float dvdy)
{
    float w = (float)t->width[0], h = (float)t->height[0];
    float ax = dudx * w, bx = dvdx * h, ay = dudy * w, by = dvdy * h;
    return sr__texture_lod_rho2(fmaxf(ax * ax + bx * bx, ay * ay + by * by));
}

float sr__texture_lod_rho2(float rho2)
{
    /* log2(rho) = log2(rho^2) / 2; rho <= 1 (magnification) is level 0. */
    return rho2 > 1.0f ? 0.5f * log2f(rho2) : 0.0f;
}

void sr__texture_sample_linear(const sr_texture *t, sr_texture_filter filter, sr_texture_wrap wu,
                               sr_texture_wrap wv, float u, float v, float lod, float out[4])
{
    if (!isfinite(u) || !isfinite(v)) {
        u = 0.0f;
        v = 0.0f;
    }
    if (filter == SR_FILTER_TRILINEAR && t->levels > 1 && lod > 0.0f) {
        float maxl = (float)(t->levels - 1);
        float l = lod < maxl ? lod : maxl;
        int k0 = (int)floorf(l);
        int k1 = k0 + 1 < t->levels ? k0 + 1 : k0;
        float f = l - (float)k0;
        float a[4], b[4];
        sample_level(t, k0, true, wu, wv, u, v, a);
        sample_level(t, k1, true, wu, wv, u, v, b);
        for (int c = 0; c < 4; c++) {
            out[c] = a[c] + f * (b[c] - a[c]);
        }
    } else {
        sample_level(t, 0, filter != SR_FILTER_NEAREST, wu, wv, u, v, out);
    }
}

void sr__texture_sample(const sr_texture *t, sr_texture_filter filter, sr_texture_wrap wu,
                        sr_texture_wrap wv, float u, float v, float lod, float out[4])
{
    sr__texture_sample_linear(t, filter, wu, wv, u, v, lod, out);
    if (t->srgb) {
        for (int c = 0; c < 3; c++) {
            out[c] = linear_to_srgb(out[c] > 0.0f ? out[c] : 0.0f);
        }
    }
}
