/* paint.h - draw2d stage, internal: how the 2D calls put color into a
 * framebuffer.  Consumes a straight-alpha sr_rgba and per-pixel coverage
 * (0..255), produces RGBA8 pixels blended source-over.  Shared by every
 * file in src/draw2d; the calls run on the caller's thread only. */
#ifndef SR_DRAW2D_PAINT_H
#define SR_DRAW2D_PAINT_H

#include "softrast.h"
#include "target/framebuffer.h"

#include <limits.h>
#include <stdbool.h>
#include <stdint.h>

typedef struct sr__paint {
    uint8_t rgba[4];     /* the color quantized to RGBA8 */
    uint32_t packed;     /* rgba[] in framebuffer memory order */
    float alpha;         /* color.a clamped to [0, 1] */
    float linear[3];     /* r, g, b decoded from sRGB (set with linear_light only) */
    bool linear_light;   /* blend in linear light: decode, mix, encode */
    bool wide;           /* rows 16 pixels at a time (AVX-512: fb->wide_stores); init: false */
} sr__paint;

/* False when a component is not finite (the caller reports which call). */
bool sr__paint_init(sr__paint *p, sr_rgba color, bool linear_light);

/* Recent blends of one paint: a blend is a pure function of the pixel
 * and the coverage, and a fill meets the same few pairs row after row (its
 * inside over an empty or flat background).  Direct-mapped by a hash of
 * the pair; for one paint only. */
#define SR__BLEND_MEMO_BITS 6
#define SR__BLEND_MEMO (1 << SR__BLEND_MEMO_BITS)
/* Over an opaque pixel at full coverage each channel of the blend is a
 * function of that channel's byte alone (the color, its alpha and the
 * destination's alpha are fixed), so a fill that meets many such pixels
 * tabulates the blend of the 256 grey opaque pixels once and looks the
 * channels up (at the AVX-512 level, with VBMI): the same bytes, from
 * the blend itself. */
#ifndef SR__BLEND_TABLE_AFTER
#define SR__BLEND_TABLE_AFTER 256 /* such pixels blended before the table is made */
#endif
#define SR__BLEND_TABLE_NEVER INT_MAX /* table_wait where no table is used */
typedef struct sr__blend_memo {
    uint32_t in[SR__BLEND_MEMO], out[SR__BLEND_MEMO];
    uint16_t cov[SR__BLEND_MEMO]; /* 256: an empty slot */
    int table_wait;               /* such pixels still to blend; < 0: table[] is made */
    uint8_t table_alpha;          /* the result's alpha there */
    _Alignas(64) uint8_t table[3][256]; /* channel k of the blend over (v, v, v, 255) */
} sr__blend_memo;

void sr__blend_memo_init(sr__blend_memo *m);

/* Blend `p` over the pixel with coverage cov (0..255). */
void sr__paint_pixel(const sr__paint *p, uint32_t *dst, unsigned cov);
/* Blend `p` over dst[0..n) with coverage cov[i], or full coverage when
 * cov is NULL: the bytes of sr__paint_pixel on each, faster. */
void sr__paint_row(const sr__paint *p, uint32_t *dst, const uint8_t *cov, int n);
/* sr__paint_row with the results kept in m (initialized for p) from one
 * call to the next (m NULL: none kept): the same bytes. */
void sr__paint_row_memo(const sr__paint *p, sr__blend_memo *m, uint32_t *dst, const uint8_t *cov,
                        int n);
/* Blend pixels x0..x1-1 of row y with full coverage (the span is
 * already clipped to the framebuffer). */
void sr__paint_span(const sr__paint *p, sr_framebuffer *fb, int y, int x0, int x1);

/* Blend one straight-alpha RGBA color (floats in [0, 1]) over a pixel. */
void sr__blend_rgba(uint32_t *dst, const float rgba[4]);

/* sRGB transfer functions on [0, 1]. */
float sr__srgb_to_linear(float c);
float sr__linear_to_srgb(float c);

uint32_t sr__pack_rgba8(const uint8_t rgba[4]);
uint8_t  sr__unorm8(float v);

#endif
