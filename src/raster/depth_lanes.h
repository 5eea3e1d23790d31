/* depth_lanes.h - depth samples in 32-bit lanes (raster stage, tile
 * worker threads).  The vector kernels compare and blend depth as 32-bit
 * lanes whatever the buffer's width: these load D16's 16-bit samples
 * zero-extended and store them narrowed (the values are below 2^16, so
 * nothing is lost), and the other formats' words as they are
 * (framebuffer.h), testing the width once for a group of lanes.  Plain
 * vector extensions: every instruction set's kernels inline them. */
#ifndef SR_DEPTH_LANES_H
#define SR_DEPTH_LANES_H

#include "simd_types.h"
#include "target/framebuffer.h"

#include <string.h>

typedef uint16_t sr_v4h __attribute__((vector_size(8)));

/* The LESS test of four consecutive samples from element i: where a lane
 * of `on` (all ones or zero) holds a q below the stored value, q replaces
 * it; returns the lanes that passed.  The four are written back either
 * way, behind one test of the width. */
static inline __attribute__((always_inline)) v4i sr__depth_less4(sr_framebuffer *fb, size_t i,
                                                                 v4i q, v4i on)
{
    if (fb->depth16) {
        uint16_t *p = (uint16_t *)fb->depth + i;
        sr_v4h h;
        memcpy(&h, p, sizeof h);
        v4i d = __builtin_convertvector(h, v4i);
        v4i pass = on & (q < d);
        h = __builtin_convertvector((pass & q) | (~pass & d), sr_v4h);
        memcpy(p, &h, sizeof h);
        return pass;
    }
    uint32_t *p = (uint32_t *)fb->depth + i;
    v4i d;
    memcpy(&d, p, sizeof d);
    v4i pass = on & (q < d);
    d = (pass & q) | (~pass & d);
    memcpy(p, &d, sizeof d);
    return pass;
}

/* The samples at[i] of the lanes with on[i] set, the others 0, and the
 * store of q's lanes where pass is set: four pixels of one sample, rows
 * apart.  One test of the width for the four. */
static inline __attribute__((always_inline)) v4i sr__depth_gather4(const sr_framebuffer *fb,
                                                                   const size_t at[4],
                                                                   const unsigned on[4])
{
    v4i d;
    if (fb->depth16) {
        const uint16_t *p = fb->depth;
        for (int i = 0; i < 4; i++) {
            d[i] = on[i] ? (int32_t)p[at[i]] : 0;
        }
    } else {
        const uint32_t *p = fb->depth;
        for (int i = 0; i < 4; i++) {
            d[i] = on[i] ? (int32_t)p[at[i]] : 0;
        }
    }
    return d;
}

static inline __attribute__((always_inline)) void sr__depth_scatter4(sr_framebuffer *fb,
                                                                     const size_t at[4], v4i pass,
                                                                     v4i q)
{
    if (fb->depth16) {
        uint16_t *p = fb->depth;
        for (int i = 0; i < 4; i++) {
            if (pass[i]) {
                p[at[i]] = (uint16_t)q[i];
            }
        }
    } else {
        uint32_t *p = fb->depth;
        for (int i = 0; i < 4; i++) {
            if (pass[i]) {
                p[at[i]] = (uint32_t)q[i];
            }
        }
    }
}

#endif
