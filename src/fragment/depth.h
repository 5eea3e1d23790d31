/* depth.h - depth quantization and the eight compare functions (fragment
 * stage; any thread).  docs/raster-rules.md §6.1: clamp to [0, 1], then once per
 * sample q = floor(z (2^n - 1) + 0.5) in double for UNORM formats (exact for
 * n <= 32: the product keeps >= 21 fractional bits), or round to float32 for
 * D32F.  The test compares quantized values, as Direct3D specifies. */
#ifndef SR_DEPTH_H
#define SR_DEPTH_H

#include "softrast.h"

#include <math.h>
#include <string.h>

static inline uint32_t sr__depth_quantize(double z, int bits)
{
    /* Written so that NaN lands on 0 and -0 on +0. */
    if (!(z > 0.0)) {
        z = 0.0;
    }
    if (z > 1.0) {
        z = 1.0;
    }
    if (bits == 0) {
        float f = (float)z;
        uint32_t u;
        memcpy(&u, &f, sizeof u);
        return u;
    }
    double max = (double)((bits == 32) ? 0xffffffffu : ((1u << bits) - 1u));
    return (uint32_t)floor(z * max + 0.5);
}

static inline double sr__depth_dequantize(uint32_t q, int bits)
{
    if (bits == 0) {
        float f;
        memcpy(&f, &q, sizeof f);
        return f;
    }
    double max = (double)((bits == 32) ? 0xffffffffu : ((1u << bits) - 1u));
    return q / max;
}

/* Polygon offset's r: the smallest resolvable difference of the format
 * (1/(2^n - 1) for UNORM; for float, 2^(e - 23) where e is the exponent of the
 * largest |z| of the primitive). */
static inline double sr__depth_r(int bits, double max_abs_z)
{
    if (bits == 0) {
        int e;
        frexp(max_abs_z > 0.0 ? max_abs_z : 1.0, &e);
        return ldexp(1.0, (e - 1) - 23);
    }
    double max = (double)((bits == 32) ? 0xffffffffu : ((1u << bits) - 1u));
    return 1.0 / max;
}

static inline bool sr__depth_pass(sr_depth_func f, uint32_t incoming, uint32_t stored)
{
    switch (f) {
    case SR_NEVER:    return false;
    case SR_LESS:     return incoming < stored;
    case SR_EQUAL:    return incoming == stored;
    case SR_LEQUAL:   return incoming <= stored;
    case SR_GREATER:  return incoming > stored;
    case SR_NOTEQUAL: return incoming != stored;
    case SR_GEQUAL:   return incoming >= stored;
    case SR_ALWAYS:   return true;
    default:          return incoming < stored;
    }
}

#endif
