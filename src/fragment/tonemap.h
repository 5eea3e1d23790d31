/* tonemap.h - the tone curves and the exact sRGB encode table, shared by
 * sr_tonemap (whole images) and the PBR program (per fragment).  The table
 * is built once and read-only after, so any thread may look codes up. */
#ifndef SR_TONEMAP_H
#define SR_TONEMAP_H

#include "softrast.h"

#include <string.h>

/* One colour through a tone curve: negatives and NaN are black, out in [0, 1]. */
void sr__tone_curve(sr_tonemap_op op, const float in[3], float out[3]);

/* step[k]: the smallest float whose code is above k, found from the
 * inverse OETF and nudged by ulps until the formula agrees.  first[i]:
 * the code of the smallest float whose bits, shifted right by
 * SR_SRGB_BUCKET_SHIFT, are i.  A bucket spans 1/128 of an octave, over which the
 * code rises by less than one, so the code of x is first[bucket] plus at
 * most one step - equal to srgb_code_exact for every float, without a pow
 * per channel. */
#define SR_SRGB_BUCKET_SHIFT 16
#define SR_SRGB_BUCKETS      ((0x3F800000u >> SR_SRGB_BUCKET_SHIFT) + 1) /* up to 1.0f */

typedef struct srgb_table {
    float step[255];
    uint8_t first[SR_SRGB_BUCKETS];
} srgb_table;

void sr__srgb_table_init(srgb_table *t);
/* One table for the process, built on first use (thread-safe). */
const srgb_table *sr__srgb_table(void);

static inline uint8_t sr__srgb_code(const srgb_table *t, float x)
{
    if (!(x > 0.0f)) {
        return 0;
    }
    if (x >= 1.0f) {
        return 255;
    }
    uint32_t bits;
    memcpy(&bits, &x, sizeof bits);
    int code = t->first[bits >> SR_SRGB_BUCKET_SHIFT];
    code += code < 255 && x >= t->step[code];
    return (uint8_t)code;
}

#endif
