/* fragment.h - the per-sample fragment stage, inline so every rasterizer
 * shares one definition: depth from the screen-space plane, quantize, depth
 * test (before shading: nothing here writes depth from a shader), shade,
 * write.  Called from tile workers; each tile is touched by one thread. */
#ifndef SR_FRAGMENT_H
#define SR_FRAGMENT_H

#include "pipeline.h"
#include "fragment/depth.h"

#include <math.h>
#include <string.h>

static inline uint8_t sr__unorm8(float v)
{
    if (!(v > 0.0f)) {
        return 0;
    }
    if (v >= 1.0f) {
        return 255;
    }
    return (uint8_t)(v * 255.0f + 0.5f);
}

/* Perspective-correct barycentrics from the exact integer edge values
 * (RASTER_RULES 4.4): q_i = e_i / w_i, normalized.  Affine mode drops the
 * 1/w factor, which is exactly screen-space interpolation. */
static inline void sr__bary(const sr_draw_state *ds, const sr_tri *t,
                            int64_t e0, int64_t e1, int64_t e2, float l[3])
{
    double q0 = (double)e0, q1 = (double)e1, q2 = (double)e2;
    if (ds->perspective) {
        q0 *= t->inv_w[0];
        q1 *= t->inv_w[1];
        q2 *= t->inv_w[2];
    }
    double s = q0 + q1 + q2;
    double inv = s != 0.0 ? 1.0 / s : 0.0;
    l[0] = (float)(q0 * inv);
    l[1] = (float)(q1 * inv);
    l[2] = (float)(q2 * inv);
}

static inline float sr__interp(const sr_tri *t, const float l[3], int k)
{
    return l[0] * t->vary[0][k] + l[1] * t->vary[1][k] + l[2] * t->vary[2][k];
}

static inline double sr__tri_depth(const sr_tri *t, int64_t e1, int64_t e2)
{
    return t->z0 + (double)e1 * t->dz1 + (double)e2 * t->dz2;
}

static inline void sr__shade(const sr_draw_state *ds, const sr_tri *t, double z,
                             int64_t e0, int64_t e1, int64_t e2, float c[4])
{
    float l[3];
    switch (ds->shading) {
    case SR_SHADING_FLAT:
        memcpy(c, t->flat, 4 * sizeof(float));
        return;
    case SR_SHADING_DEPTH:
        c[0] = c[1] = c[2] = (float)z;
        c[3] = 1.0f;
        return;
    case SR_SHADING_PHONG: {
        /* Phong: interpolate the normal, renormalize, light per pixel. */
        sr__bary(ds, t, e0, e1, e2, l);
        float n[3], eye[3], diffuse[4];
        for (int k = 0; k < 3; k++) {
            n[k] = sr__interp(t, l, SR_VARY_PHONG_NORMAL + k);
            eye[k] = sr__interp(t, l, SR_VARY_PHONG_EYE + k);
        }
        for (int k = 0; k < 4; k++) {
            diffuse[k] = sr__interp(t, l, SR_VARY_PHONG_COLOR + k);
        }
        float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        float s = len > 0.0f ? 1.0f / len : 0.0f;
        if (ds->two_sided && !t->front) {
            s = -s;
        }
        n[0] *= s;
        n[1] *= s;
        n[2] *= s;
        sr__light(ds, n, eye, diffuse, c);
        return;
    }
    case SR_SHADING_NORMALS: {
        sr__bary(ds, t, e0, e1, e2, l);
        float n[3];
        for (int k = 0; k < 3; k++) {
            n[k] = sr__interp(t, l, SR_VARY_NORMAL + k);
        }
        float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        float s = len > 0.0f ? 0.5f / len : 0.0f;
        for (int k = 0; k < 3; k++) {
            c[k] = n[k] * s + 0.5f;
        }
        c[3] = 1.0f;
        return;
    }
    default: /* UNLIT and GOURAUD: interpolate the color */
        sr__bary(ds, t, e0, e1, e2, l);
        for (int k = 0; k < 4; k++) {
            c[k] = sr__interp(t, l, SR_VARY_COLOR + k);
        }
        return;
    }
}

/* One sample at pixel (px, py) with unbiased edge values e0, e1, e2. */
static inline void sr__fragment(const sr_draw_state *ds, const sr_tri *t, int px, int py,
                                int64_t e0, int64_t e1, int64_t e2, sr_frag_stats *st)
{
    sr_framebuffer *fb = ds->fb;
    size_t idx = (size_t)py * (size_t)fb->width + (size_t)px;
    double z = sr__tri_depth(t, e1, e2);
    /* Clamp to the depth range after offset, then quantize once. */
    if (z < ds->depth_min) {
        z = ds->depth_min;
    }
    if (z > ds->depth_max) {
        z = ds->depth_max;
    }
    if (fb->depth) {
        uint32_t q = sr__depth_quantize(z, ds->depth_bits);
        if (ds->depth_test && !sr__depth_pass(ds->depth_func, q, fb->depth[idx])) {
            return;
        }
        if (ds->depth_write) {
            fb->depth[idx] = q;
        }
    }
    float c[4];
    sr__shade(ds, t, z, e0, e1, e2, c);
    uint8_t rgba[4] = { sr__unorm8(c[0]), sr__unorm8(c[1]), sr__unorm8(c[2]), sr__unorm8(c[3]) };
    memcpy(&fb->color[idx], rgba, 4);
    st->fragments++;
}

#endif
