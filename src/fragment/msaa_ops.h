/* msaa_ops.h - the per-sample fragment operations (fragment stage): the
 * stencil test and its update, the depth test, and the write of one
 * shaded color to the samples of a pixel that passed.  Multisampled
 * targets and the stencil test go through here; the single-sample fast
 * paths of fragment.h stay free of both.  Called from tile workers; each
 * tile is touched by one thread.
 *
 * Order (GL 4.6 17.3, Vulkan's fragment operations): alpha to coverage,
 * then per sample the stencil test, the depth test, the stencil update
 * chosen by their outcome, the depth write; shading runs once per pixel
 * (at its centre) when any sample survived, and its color is written to
 * exactly the surviving samples. */
#ifndef SR_MSAA_OPS_H
#define SR_MSAA_OPS_H

#include "fragment/fragment.h"

/* glStencilFunc: (ref & mask) FUNC (stored & mask). */
SR_INLINE bool sr__stencil_pass(const sr_stencil_face *f, uint8_t stored)
{
    return sr__depth_pass(f->func, (uint32_t)(f->ref & f->read_mask),
                          (uint32_t)(stored & f->read_mask));
}

/* glStencilOp on the stored value. */
SR_INLINE uint8_t sr__stencil_op(sr_stencil_op op, uint8_t v, uint8_t ref)
{
    switch (op) {
    case SR_STENCIL_ZERO:      return 0;
    case SR_STENCIL_REPLACE:   return ref;
    case SR_STENCIL_INCR:      return v == 255 ? 255 : (uint8_t)(v + 1);
    case SR_STENCIL_DECR:      return v == 0 ? 0 : (uint8_t)(v - 1);
    case SR_STENCIL_INVERT:    return (uint8_t)~v;
    case SR_STENCIL_INCR_WRAP: return (uint8_t)(v + 1);
    case SR_STENCIL_DECR_WRAP: return (uint8_t)(v - 1);
    default:                   return v;    /* KEEP */
    }
}

/* The tests of one sample (element i of the framebuffer's arrays) with
 * quantized depth q.  write_depth is false for the partly covered pixels
 * of antialiased lines and points.  True when the sample survives. */
SR_INLINE bool sr__sample_test(const sr_draw_state *ds, size_t i, uint32_t q, bool front,
                               bool write_depth)
{
    sr_framebuffer *fb = ds->fb;
    bool has_depth = ds->depth_mode != SR_DEPTH_MODE_OFF;
    bool depth_ok = !has_depth || !ds->depth_test ||
                    sr__depth_pass(ds->depth_func, q, sr__depth_at(fb, i));
    if (ds->stencil_test) {
        const sr_stencil_face *f = &ds->stencil[front ? 0 : 1];
        uint8_t s = fb->stencil[i];
        bool stencil_ok = sr__stencil_pass(f, s);
        sr_stencil_op op = !stencil_ok ? f->fail : !depth_ok ? f->depth_fail : f->pass;
        uint8_t v = sr__stencil_op(op, s, f->ref);
        fb->stencil[i] = (uint8_t)((v & f->write_mask) | (s & ~f->write_mask));
        depth_ok = depth_ok && stencil_ok;
    }
    if (!depth_ok) {
        return false;
    }
    if (has_depth && ds->depth_write && write_depth) {
        sr__depth_put(fb, i, q);
    }
    return true;
}

/* The tests of a triangle's samples `mask` in the pixel whose first
 * sample is element `base`: each at its own depth from the plane (u: the
 * centre's unbiased edge values, so[s]: sample s's offsets from them), or
 * all at the depth a fragment shader wrote (shader_z, buffer units).
 * Returns the samples that survive. */
SR_INLINE unsigned sr__test_tri_samples(const sr_draw_state *ds, const sr_tri *t, size_t base,
                                        const int64_t u[3], const int64_t (*so)[3],
                                        unsigned mask, const double *shader_z)
{
    uint32_t q_shader = 0;
    if (shader_z) {
        double z = *shader_z;
        q_shader = sr__quantize_depth(ds, &z);
    }
    unsigned pass = 0;
    for (unsigned m = mask; m; m &= m - 1) {
        int s = __builtin_ctz(m);
        uint32_t q = q_shader;
        if (!shader_z && ds->depth_mode != SR_DEPTH_MODE_OFF) {
            double z = sr__tri_depth(t, u[1] + so[s][1], u[2] + so[s][2]);
            q = sr__quantize_depth(ds, &z);
        }
        if (sr__sample_test(ds, base + (size_t)s, q, t->front, true)) {
            pass |= 1u << s;
        }
    }
    return pass;
}

/* Alpha to coverage: the first round(alpha x n) samples, a fixed pattern
 * so that the result does not depend on threads or order. */
SR_INLINE unsigned sr__alpha_coverage(float alpha, int n)
{
    float a = alpha > 0.0f ? (alpha < 1.0f ? alpha : 1.0f) : 0.0f;
    int k = (int)(a * (float)n + 0.5f);
    return k >= 32 ? ~0u : (1u << k) - 1u;
}

/* One shaded color to the samples `pass` of the pixel whose first sample
 * is element `base`: converted once when nothing blends. */
SR_INLINE void sr__write_samples(const sr_draw_state *ds, size_t base, unsigned pass,
                                 const float c[4], const sr_blend *b)
{
    if (!b->enabled && !ds->blending) {
        uint8_t out[4];
        for (int k = 0; k < 4; k++) {
            out[k] = sr__unorm8(c[k]);
        }
        uint32_t packed;
        memcpy(&packed, out, sizeof packed);
        for (unsigned m = pass; m; m &= m - 1) {
            ds->fb->color[base + (size_t)__builtin_ctz(m)] = packed;
        }
        return;
    }
    for (unsigned m = pass; m; m &= m - 1) {
        sr__write_color_as(ds, base + (size_t)__builtin_ctz(m), c, b);
    }
}

/* A line or point sample on a single-sampled target: depth already
 * interpolated (buffer units, before the clamp), varyings already
 * interpolated.  Same depth and stencil rules as triangles.  coverage < 1
 * (antialiased lines and points) blends the color source-over with
 * alpha = coverage x the color's alpha, and leaves depth unwritten so the
 * pixel stays open to what lies behind its uncovered part. */
static inline void sr__fragment_vary(const sr_draw_state *ds, int px, int py, double z,
                                     const float *v, const float flat[4], bool front,
                                     float coverage, sr_frag_stats *st)
{
    size_t idx = (size_t)py * (size_t)ds->fb->width + (size_t)px;
    float c[4];
    /* A program that writes depth or discards runs before the tests. */
    bool late = ds->program && (ds->program->writes_depth || ds->program->may_discard);
    if (late && !sr__program_shade_one(ds, v, front, px, py, &z, c)) {
        return;
    }
    uint32_t q = sr__quantize_depth(ds, &z);
    if (!sr__sample_test(ds, idx, q, front, coverage >= 1.0f)) {
        return;
    }
    if (ds->program && !late) {
        (void)sr__program_shade_one(ds, v, front, px, py, &z, c);
    } else if (!ds->program) {
        sr__shade_vary(ds, v, flat, front, z, 0.0f, c, ds->shading);
    }
    if (coverage < 1.0f) {
        /* Coverage scales alpha; the draw's blend state decides, or else
         * source-over. */
        c[3] = (c[3] > 0.0f ? (c[3] < 1.0f ? c[3] : 1.0f) : 0.0f) * coverage;
        sr__write_color_as(ds, idx, c, ds->blend.enabled ? &ds->blend : &sr__source_over);
    } else {
        sr__write_color(ds, idx, c);
    }
    st->fragments++;
}

#endif
