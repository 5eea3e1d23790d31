/* fragment.h - the per-sample fragment stage, inline so every rasterizer
 * shares one definition: depth from the screen-space plane, quantize, depth
 * test (before shading: nothing here writes depth from a shader), shade,
 * write.  Called from tile workers; each tile is touched by one thread. */
#ifndef SR_FRAGMENT_H
#define SR_FRAGMENT_H

#include "pipeline.h"
#include "fragment/depth.h"
#include "fragment/texture.h"

#include <math.h>
#include <string.h>

#define SR_INLINE static inline __attribute__((always_inline))

/* Float in [0, 1] to 8 bits, rounded; NaN goes to 0.  Branch-free: the
 * comparisons compile to min/max. */
SR_INLINE uint8_t sr__unorm8(float v)
{
    v = v > 0.0f ? v : 0.0f;
    v = v < 1.0f ? v : 1.0f;
    return (uint8_t)(v * 255.0f + 0.5f);
}

/* Perspective-correct barycentrics from the exact integer edge values
 * (docs/raster-rules.md §5.1): q_i = e_i / w_i, normalized.  In affine mode setup
 * set every w_i to 1, which is exactly screen-space interpolation.  Float
 * is ample here: e_i is exact, the weights need ~1e-6. */
static inline void sr__bary(const sr_draw_state *ds, const sr_tri *t,
                            int64_t e0, int64_t e1, int64_t e2, float l[3])
{
    (void)ds;
    float q0 = (float)e0 * t->w[0];
    float q1 = (float)e1 * t->w[1];
    float q2 = (float)e2 * t->w[2];
    float s = q0 + q1 + q2;
    float inv = s != 0.0f ? 1.0f / s : 0.0f;
    l[0] = q0 * inv;
    l[1] = q1 * inv;
    l[2] = q2 * inv;
}

/* Attribute k at weights l: v0 + l1 (v1 - v0) + l2 (v2 - v0). */
static inline float sr__interp(const sr_tri *t, const float l[3], int k)
{
    int n = t->ninterp;
    return t->vary[k] + l[1] * t->vary[n + k] + l[2] * t->vary[2 * n + k];
}

/* Depth in buffer units at a sample, from the exact edge values. */
static inline double sr__tri_depth(const sr_tri *t, int64_t e1, int64_t e2)
{
    return t->z0 + (double)e1 * t->dz1 + (double)e2 * t->dz2;
}

/* Clamp to the depth range after offset (*z keeps the clamped value), then
 * quantize once (docs/raster-rules.md §6.1): round half up for UNORM (z >= 0 here,
 * so truncation is floor), the float's bits for D32F. */
SR_INLINE uint32_t sr__quantize_depth(const sr_draw_state *ds, double *z)
{
    double v = *z >= ds->zq_min ? *z : ds->zq_min;
    v = v <= ds->zq_max ? v : ds->zq_max;
    *z = v;
    if (ds->depth_bits) {
        return (uint32_t)(v + 0.5);
    }
    float f = (float)v;
    uint32_t q;
    memcpy(&q, &f, sizeof q);
    return q;
}

/* Shade from interpolated varyings v (the layout of the shading model,
 * raster/records.h), the primitive's flat color and facing, and the depth z in
 * buffer units.  Triangles, lines and points all end here. */
/* One blend factor for channel k (0..2 color, 3 alpha). */
SR_INLINE float sr__blend_factor(sr_blend_factor f, const float s[4], const float d[4],
                                 const float k[4], int ch)
{
    switch (f) {
    case SR_BLEND_ZERO:                     return 0.0f;
    case SR_BLEND_SRC_COLOR:                return s[ch];
    case SR_BLEND_ONE_MINUS_SRC_COLOR:      return 1.0f - s[ch];
    case SR_BLEND_SRC_ALPHA:                return s[3];
    case SR_BLEND_ONE_MINUS_SRC_ALPHA:      return 1.0f - s[3];
    case SR_BLEND_DST_ALPHA:                return d[3];
    case SR_BLEND_ONE_MINUS_DST_ALPHA:      return 1.0f - d[3];
    case SR_BLEND_DST_COLOR:                return d[ch];
    case SR_BLEND_ONE_MINUS_DST_COLOR:      return 1.0f - d[ch];
    case SR_BLEND_CONSTANT_COLOR:           return k[ch];
    case SR_BLEND_ONE_MINUS_CONSTANT_COLOR: return 1.0f - k[ch];
    case SR_BLEND_CONSTANT_ALPHA:           return k[3];
    case SR_BLEND_ONE_MINUS_CONSTANT_ALPHA: return 1.0f - k[3];
    case SR_BLEND_SRC_ALPHA_SATURATE: {
        float m = 1.0f - d[3];
        return ch == 3 ? 1.0f : (s[3] < m ? s[3] : m);
    }
    default:                                return 1.0f;  /* ONE */
    }
}

SR_INLINE float sr__blend_op(sr_blend_op op, float s, float fs, float d, float fd)
{
    switch (op) {
    case SR_BLEND_SUBTRACT:         return s * fs - d * fd;
    case SR_BLEND_REVERSE_SUBTRACT: return d * fd - s * fs;
    case SR_BLEND_MIN:              return s < d ? s : d;
    case SR_BLEND_MAX:              return s > d ? s : d;
    default:                        return s * fs + d * fd;
    }
}

/* The color write: straight, or through the blend state b and the write
 * mask.  Color is clamped to [0, 1] before blending, as for UNORM targets. */
SR_INLINE void sr__write_color_as(const sr_draw_state *ds, size_t idx, const float c[4],
                                  const sr_blend *b)
{
    sr_framebuffer *fb = ds->fb;
    uint8_t out[4];
    if (!b->enabled && !ds->blending) {
        for (int k = 0; k < 4; k++) {
            out[k] = sr__unorm8(c[k]);
        }
        memcpy(&fb->color[idx], out, sizeof out);
        return;
    }
    uint8_t dst8[4];
    memcpy(dst8, &fb->color[idx], sizeof dst8);
    float s[4], d[4];
    for (int k = 0; k < 4; k++) {
        s[k] = c[k] > 0.0f ? (c[k] < 1.0f ? c[k] : 1.0f) : 0.0f;
        d[k] = dst8[k] / 255.0f;
    }
    for (int k = 0; k < 4; k++) {
        float v = s[k];
        if (b->enabled) {
            sr_blend_factor fs = k < 3 ? b->src_rgb : b->src_alpha;
            sr_blend_factor fd = k < 3 ? b->dst_rgb : b->dst_alpha;
            v = sr__blend_op(k < 3 ? b->op_rgb : b->op_alpha, s[k],
                             sr__blend_factor(fs, s, d, b->constant, k), d[k],
                             sr__blend_factor(fd, s, d, b->constant, k));
        }
        out[k] = (uint8_t)((sr__unorm8(v) & ds->write_mask[k]) | (dst8[k] & ~ds->write_mask[k]));
    }
    memcpy(&fb->color[idx], out, sizeof out);
}

SR_INLINE void sr__write_color(const sr_draw_state *ds, size_t idx, const float c[4])
{
    sr__write_color_as(ds, idx, c, &ds->blend);
}

/* Antialiased lines and points without a blend state of their own blend
 * their coverage source-over. */
static const sr_blend sr__source_over = {
    .enabled = true, .src_rgb = SR_BLEND_SRC_ALPHA, .dst_rgb = SR_BLEND_ONE_MINUS_SRC_ALPHA,
    .src_alpha = SR_BLEND_ONE, .dst_alpha = SR_BLEND_ONE_MINUS_SRC_ALPHA,
    .op_rgb = SR_BLEND_ADD, .op_alpha = SR_BLEND_ADD,
};

SR_INLINE void sr__modulate(float c[4], const float tex[4])
{
    for (int k = 0; k < 4; k++) {
        c[k] *= tex[k];
    }
}

SR_INLINE void sr__shade_vary(const sr_draw_state *ds, const float *v, const float flat[4],
                              bool front, double z, float lod, float c[4], sr_shading shading)
{
    float tex[4] = { 1, 1, 1, 1 };
    if (ds->texture) {
        sr__texture_sample(ds->texture, ds->texture_filter, ds->wrap_u, ds->wrap_v,
                           v[ds->uv_index], v[ds->uv_index + 1], lod, tex);
    }
    switch (shading) {
    case SR_SHADING_FLAT:
        memcpy(c, flat, 4 * sizeof(float));
        if (ds->texture) {
            sr__modulate(c, tex);
        }
        return;
    case SR_SHADING_DEPTH:
        if (ds->depth_vis_linear) {
            c[0] = c[1] = c[2] = (v[SR_VARY_DEPTH_W] - ds->depth_vis_near) * ds->depth_vis_scale;
        } else {
            c[0] = c[1] = c[2] = (float)(z / ds->depth_scale);
        }
        c[3] = 1.0f;
        return;
    case SR_SHADING_PHONG: {
        /* Phong: the interpolated normal, renormalized, lit per pixel. */
        const float *vn = &v[SR_VARY_PHONG_NORMAL];
        float len = sqrtf(vn[0] * vn[0] + vn[1] * vn[1] + vn[2] * vn[2]);
        float s = len > 0.0f ? 1.0f / len : 0.0f;
        if (ds->two_sided && !front) {
            s = -s;
        }
        float n[3] = { vn[0] * s, vn[1] * s, vn[2] * s };
        float diffuse[4];
        memcpy(diffuse, &v[SR_VARY_PHONG_COLOR], sizeof diffuse);
        if (ds->texture) {
            sr__modulate(diffuse, tex);
        }
        sr__light(ds, n, &v[SR_VARY_PHONG_EYE], diffuse, c);
        return;
    }
    case SR_SHADING_NORMALS: {
        const float *vn = &v[SR_VARY_NORMAL];
        float len = sqrtf(vn[0] * vn[0] + vn[1] * vn[1] + vn[2] * vn[2]);
        float s = len > 0.0f ? 0.5f / len : 0.0f;
        for (int k = 0; k < 3; k++) {
            c[k] = vn[k] * s + 0.5f;
        }
        c[3] = 1.0f;
        return;
    }
    default: /* UNLIT, GOURAUD, ATTRIBUTE: the interpolated color */
        memcpy(c, &v[SR_VARY_COLOR], 4 * sizeof(float));
        if (ds->texture) {
            sr__modulate(c, tex);
        }
        return;
    }
}

SR_INLINE void sr__shade_as(const sr_draw_state *ds, const sr_tri *t, double z,
                            int64_t e0, int64_t e1, int64_t e2, float c[4], sr_shading shading)
{
    float v[SR_MAX_VARYINGS];
    float lod = 0.0f;
    if (t->ninterp > 0 && !(shading == SR_SHADING_DEPTH && !ds->depth_vis_linear)) {
        float l[3];
        sr__bary(ds, t, e0, e1, e2, l);
        for (int k = 0; k < t->ninterp; k++) {
            v[k] = sr__interp(t, l, k);
        }
        if (ds->texture && ds->texture_filter == SR_FILTER_TRILINEAR) {
            /* Level of detail from the texture coordinates one pixel to the
             * right and one below, by the same exact interpolation. */
            int ui = ds->uv_index;
            float lx[3], ly[3];
            sr__bary(ds, t, e0 + (int64_t)t->a[0] * SR_SUBPIXEL_ONE,
                     e1 + (int64_t)t->a[1] * SR_SUBPIXEL_ONE,
                     e2 + (int64_t)t->a[2] * SR_SUBPIXEL_ONE, lx);
            sr__bary(ds, t, e0 + (int64_t)t->b[0] * SR_SUBPIXEL_ONE,
                     e1 + (int64_t)t->b[1] * SR_SUBPIXEL_ONE,
                     e2 + (int64_t)t->b[2] * SR_SUBPIXEL_ONE, ly);
            float u = v[ui], vv = v[ui + 1];
            lod = sr__texture_lod(ds->texture, sr__interp(t, lx, ui) - u,
                                  sr__interp(t, lx, ui + 1) - vv, sr__interp(t, ly, ui) - u,
                                  sr__interp(t, ly, ui + 1) - vv);
        }
    }
    sr__shade_vary(ds, v, sr__tri_flat(t), t->front, z, lod, c, shading);
}

static inline void sr__shade(const sr_draw_state *ds, const sr_tri *t, double z,
                             int64_t e0, int64_t e1, int64_t e2, float c[4])
{
    sr__shade_as(ds, t, z, e0, e1, e2, c, ds->shading);
}

/* One sample at pixel (px, py) with unbiased edge values e0, e1, e2, for a
 * shading model and depth mode that the caller may pass as constants: the
 * fast rasterizer instantiates this per combination (the compiler drops
 * the switches), the reference rasterizers pass the draw's values.  Both
 * run the same operations in the same order, so the bytes agree. */
SR_INLINE void sr__fragment_as(const sr_draw_state *ds, const sr_tri *t, int px, int py,
                               int64_t e0, int64_t e1, int64_t e2, sr_frag_stats *st,
                               sr_shading shading, sr_depth_mode dmode)
{
    sr_framebuffer *fb = ds->fb;
    size_t idx = (size_t)py * (size_t)fb->width + (size_t)px;
    double z = 0.0;
    uint32_t q = 0;
    if (dmode != SR_DEPTH_MODE_OFF || shading == SR_SHADING_DEPTH) {
        z = sr__tri_depth(t, e1, e2);
        q = sr__quantize_depth(ds, &z);
    }
    if (dmode != SR_DEPTH_MODE_OFF) {
        uint32_t d = sr__depth_at(fb, idx);
        if (dmode == SR_DEPTH_MODE_LESS) {
            if (!(q < d)) {
                return;
            }
            sr__depth_put(fb, idx, q);
        } else {
            if (ds->depth_test && !sr__depth_pass(ds->depth_func, q, d)) {
                return;
            }
            if (ds->depth_write) {
                sr__depth_put(fb, idx, q);
            }
        }
    }
    float c[4];
    sr__shade_as(ds, t, z, e0, e1, e2, c, shading);
    sr__write_color(ds, idx, c);
    st->fragments++;
}

static inline void sr__fragment(const sr_draw_state *ds, const sr_tri *t, int px, int py,
                                int64_t e0, int64_t e1, int64_t e2, sr_frag_stats *st)
{
    sr__fragment_as(ds, t, px, py, e0, e1, e2, st, ds->shading, ds->depth_mode);
}

#endif
