/* paint.c - draw2d stage: source-over blending of a flat color with
 * coverage into RGBA8 pixels, optionally in linear light.  Called by every
 * 2D fill; pure functions of their arguments, safe from any thread that
 * owns the framebuffer. */
#include "draw2d/paint.h"

#include "simd_types.h"

#include <math.h>
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif
#include <string.h>

/* Where channel k (memory order: r, g, b, a) sits in a packed pixel. */
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
#define CHANNEL_SHIFT(k) (24 - 8 * (k))
#else
#define CHANNEL_SHIFT(k) (8 * (k))
#endif

uint8_t sr__unorm8(float v)
{
    if (!(v > 0.0f)) {
        return 0;
    }
    if (v >= 1.0f) {
        return 255;
    }
    return (uint8_t)(v * 255.0f + 0.5f);
}

uint32_t sr__pack_rgba8(const uint8_t rgba[4])
{
    uint32_t v;
    memcpy(&v, rgba, sizeof v);
    return v;
}

float sr__srgb_to_linear(float c)
{
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

float sr__linear_to_srgb(float c)
{
    if (!(c > 0.0f)) {
        return 0.0f;
    }
    if (c >= 1.0f) {
        return 1.0f;
    }
    return c <= 0.0031308f ? c * 12.92f : 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
}

bool sr__paint_init(sr__paint *p, sr_rgba color, bool linear_light)
{
    float c[4] = { color.r, color.g, color.b, color.a };
    for (int i = 0; i < 4; i++) {
        if (!isfinite(c[i])) {
            return false;
        }
        p->rgba[i] = sr__unorm8(c[i]);
    }
    p->packed = sr__pack_rgba8(p->rgba);
    p->alpha = c[3] < 0.0f ? 0.0f : c[3] > 1.0f ? 1.0f : c[3];
    for (int i = 0; i < 3 && linear_light; i++) {
        p->linear[i] = sr__srgb_to_linear(p->rgba[i] / 255.0f);
    }
    p->linear_light = linear_light;
    p->wide = false;
    return true;
}

void sr__paint_pixel(const sr__paint *p, uint32_t *dst, unsigned cov)
{
    if (cov == 0) {
        return;
    }
    /* Effective opacity: color alpha times coverage. */
    if (cov >= 255 && p->alpha >= 1.0f) {
        *dst = p->packed;
        return;
    }
    float a = p->alpha * (float)cov * (1.0f / 255.0f);
    if (a >= 1.0f) {
        *dst = p->packed;
        return;
    }
    if (a <= 0.0f) {
        return;
    }
    uint8_t d[4];
    memcpy(d, dst, sizeof d);
    if (d[3] == 0 && !p->linear_light) {
        /* Over an empty pixel the blend below has oa = a, so a / oa = 1
         * and keep 0 exactly: the color at alpha a, undivided. */
        memcpy(d, p->rgba, 3);
        d[3] = sr__unorm8(a);
        memcpy(dst, d, sizeof d);
        return;
    }
    /* Straight alpha: the destination's color counts by its own alpha, and
     * the sum is divided by the result's alpha.  Over an opaque pixel both
     * are 1 and the plain mix below is the same operator. */
    float da = d[3] * (1.0f / 255.0f), keep = 1.0f - a, oa = a + da * keep;
    if (d[3] < 255) {
        keep = oa > 0.0f ? da * keep / oa : 0.0f;
        a = oa > 0.0f ? a / oa : 0.0f;
    }
    if (p->linear_light) {
        for (int i = 0; i < 3; i++) {
            float dl = sr__srgb_to_linear(d[i] / 255.0f);
            d[i] = sr__unorm8(sr__linear_to_srgb(p->linear[i] * a + dl * keep));
        }
    } else {
        for (int i = 0; i < 3; i++) {
            d[i] = sr__unorm8((p->rgba[i] * a + d[i] * keep) * (1.0f / 255.0f));
        }
    }
    /* Source-over alpha: a + d.a (1 - a). */
    d[3] = sr__unorm8(oa);
    memcpy(dst, d, sizeof d);
}

void sr__blend_memo_init(sr__blend_memo *m)
{
    for (int i = 0; i < SR__BLEND_MEMO; i++) {
        m->cov[i] = 256;
    }
    /* Only the 16-pixel blend with VBMI's byte permutes uses the table:
     * elsewhere looking three bytes up per pixel is no faster than the
     * lanes' blend. */
#if defined(__x86_64__) && defined(__GNUC__)
    m->table_wait = __builtin_cpu_supports("avx512vbmi") ? SR__BLEND_TABLE_AFTER
                                                       : SR__BLEND_TABLE_NEVER;
#else
    m->table_wait = SR__BLEND_TABLE_NEVER;
#endif
}

/* sr__paint_pixel's result for the pixel d at coverage c, from the memo
 * when the pair is there (its slot keeps the last pair that hashed to it). */
static inline uint32_t memo_blend(const sr__paint *p, sr__blend_memo *m, uint32_t d, unsigned c)
{
    if (!m) {
        sr__paint_pixel(p, &d, c);
        return d;
    }
    unsigned h = (d * 0x9e3779b1u ^ c * 0x85ebca6bu) >> (32 - SR__BLEND_MEMO_BITS);
    if (m->in[h] != d || m->cov[h] != c) {
        uint32_t v = d;
        sr__paint_pixel(p, &v, c);
        m->in[h] = d;
        m->cov[h] = (uint16_t)c;
        m->out[h] = v;
    }
    return m->out[h];
}

#define ALPHA_BYTE(px) (((px) >> CHANNEL_SHIFT(3)) & 0xffu)

#if defined(__x86_64__) && defined(__GNUC__)
/* The whole blocks of opaque pixels at full coverage from the start of
 * dst[0..n) through m's table (made), 16 pixels at a time: VBMI's byte
 * permutes look 64 channel bytes up in a 128-byte half of a table at
 * once, the byte's top bit picks the half.  Returns how many pixels. */
__attribute__((target("avx2,avx512f,avx512bw,avx512vl,avx512vbmi")))
static int table_row_vbmi(const sr__blend_memo *m, uint32_t *dst, const uint8_t *cov, int n)
{
    __m512i t[3][4];
    for (int k = 0; k < 3; k++) {
        for (int q = 0; q < 4; q++) {
            t[k][q] = _mm512_load_si512((const void *)(m->table[k] + 64 * q));
        }
    }
    const __mmask64 channel[3] = { 0x1111111111111111ull, 0x2222222222222222ull,
                                   0x4444444444444444ull };
    const __m512i alpha_mask = _mm512_set1_epi32((int)0xff000000u);
    const __m512i alpha = _mm512_set1_epi32((int)((uint32_t)m->table_alpha << 24));
    int i = 0;
    for (; i + 16 <= n; i += 16) {
        __m512i d = _mm512_loadu_si512((const void *)(dst + i));
        if (cov && _mm_cmpeq_epi8_mask(_mm_loadu_si128((const __m128i *)(const void *)(cov + i)),
                                       _mm_set1_epi8(-1)) != 0xffff) {
            break;
        }
        if (_mm512_cmpeq_epi32_mask(_mm512_and_si512(d, alpha_mask), alpha_mask) != 0xffff) {
            break;
        }
        __mmask64 high = _mm512_movepi8_mask(d);
        __m512i out = alpha;
        for (int k = 0; k < 3; k++) {
            __m512i lo = _mm512_permutex2var_epi8(t[k][0], d, t[k][1]);
            __m512i hi = _mm512_permutex2var_epi8(t[k][2], d, t[k][3]);
            out = _mm512_mask_mov_epi8(out, channel[k], _mm512_mask_blend_epi8(high, lo, hi));
        }
        _mm512_storeu_si512((void *)(dst + i), out);
    }
    return i;
}
#endif

typedef uint32_t v4u __attribute__((vector_size(16)));
typedef uint8_t v4b __attribute__((vector_size(4)));

/* One bit per set lane of a mask. */
static inline unsigned lane_bits4(v4i m)
{
#if defined(__SSE2__)
    return (unsigned)_mm_movemask_ps((__m128)m);
#else
    return (m[0] & 1u) | (m[1] & 2u) | (m[2] & 4u) | (m[3] & 8u);
#endif
}

#define BL_LANES 4
#define BL_F v4f
#define BL_I v4i
#define BL_U v4u
#if defined(__SSE2__)
/* __builtin_convertvector on bytes compiles to a byte at a time here. */
static inline v4u widen4(const uint8_t *cov)
{
    int32_t w;
    memcpy(&w, cov, sizeof w);
    __m128i z = _mm_setzero_si128();
    return (v4u)_mm_unpacklo_epi16(_mm_unpacklo_epi8(_mm_cvtsi32_si128(w), z), z);
}
#define BL_WIDEN(ptr) widen4(ptr)
#else
#define BL_WIDEN(ptr) __extension__({ \
    v4b b_; \
    memcpy(&b_, (ptr), sizeof b_); \
    __builtin_convertvector(b_, v4u); \
})
#endif
#define BL_FN(name) name##4
#define BL_INLINE static inline
#define BL_ALL(m) (lane_bits4(m) == 15)
#define BL_ANY(m) (lane_bits4(m) != 0)
#include "draw2d/blend_lanes.h"

#if defined(__x86_64__) && defined(__GNUC__)
typedef uint32_t v16u __attribute__((vector_size(64)));
#define BL_LANES 16
#define BL_F v16f
#define BL_I v16i
#define BL_U v16u
#define BL_WIDEN(ptr) \
    ((v16u)_mm512_cvtepu8_epi32(_mm_loadu_si128((const __m128i *)(const void *)(ptr))))
#define BL_FN(name) name##16
#define BL_INLINE static inline __attribute__((always_inline)) SR_TARGET_AVX512
#define BL_ALL(m) (_mm512_movepi32_mask((__m512i)(m)) == 0xffff)
#define BL_ANY(m) (_mm512_movepi32_mask((__m512i)(m)) != 0)
#define BL_TABLE_ROW table_row_vbmi
#include "draw2d/blend_lanes.h"

SR_TARGET_AVX512 static int blend_row_avx512(const sr__paint *p, sr__blend_memo *m,
                                             uint32_t *dst, const uint8_t *cov, int n,
                                             uint32_t *in, unsigned *last_cov, uint32_t *out)
{
    return blend_row16(p, m, dst, cov, n, in, last_cov, out);
}
#endif

void sr__paint_row_memo(const sr__paint *p, sr__blend_memo *m, uint32_t *dst, const uint8_t *cov,
                        int n)
{
    if (!cov && p->alpha >= 1.0f) {
        for (int i = 0; i < n; i++) {
            dst[i] = p->packed;
        }
        return;
    }
    /* A blend is a pure function of the pixel and the coverage, and runs
     * of equal pairs are common (a shape's inside over an empty or flat
     * background), so the last result is reused, and a new pair's result
     * comes from the memo when the fill met it before (in an earlier row):
     * the same bytes, one blend per pair.  A translucent color without
     * linear light takes whole blocks of 16 pixels (at the AVX-512 level),
     * then of 4, through the lanes' blend (blend_lanes.h) first.  An
     * opaque color blends only where the coverage is partial (an edge):
     * there the scalar blend is as fast, and wide float lanes would slow
     * the clock for the code around them. */
    uint32_t in = 0, out = 0;
    unsigned last_cov = 256;
    int i = 0;
    if (!p->linear_light && p->alpha < 1.0f) {
#if defined(__x86_64__) && defined(__GNUC__)
        if (p->wide) {
            i = blend_row_avx512(p, m, dst, cov, n, &in, &last_cov, &out);
        }
#endif
        i += blend_row4(p, m, dst + i, cov ? cov + i : NULL, n - i, &in, &last_cov, &out);
    }
    for (; i < n; i++) {
        unsigned c = cov ? cov[i] : 255;
        if (c != last_cov || dst[i] != in) {
            in = dst[i];
            last_cov = c;
            out = memo_blend(p, m, in, c);
        }
        dst[i] = out;
    }
}

void sr__paint_row(const sr__paint *p, uint32_t *dst, const uint8_t *cov, int n)
{
    sr__paint_row_memo(p, NULL, dst, cov, n);
}

void sr__paint_span(const sr__paint *p, sr_framebuffer *fb, int y, int x0, int x1)
{
    sr__paint_row(p, fb->color + (size_t)y * (size_t)fb->width + x0, NULL, x1 - x0);
}

void sr__blend_rgba(uint32_t *dst, const float rgba[4])
{
    float a = rgba[3] < 0.0f ? 0.0f : rgba[3] > 1.0f ? 1.0f : rgba[3];
    uint8_t d[4];
    memcpy(d, dst, sizeof d);
    /* Straight alpha, as sr__paint_pixel. */
    float da = d[3] * (1.0f / 255.0f), keep = 1.0f - a, oa = a + da * keep;
    if (d[3] < 255) {
        keep = oa > 0.0f ? da * keep / oa : 0.0f;
        a = oa > 0.0f ? a / oa : 0.0f;
    }
    for (int i = 0; i < 3; i++) {
        d[i] = sr__unorm8(rgba[i] * a + d[i] * (1.0f / 255.0f) * keep);
    }
    d[3] = sr__unorm8(oa);
    memcpy(dst, d, sizeof d);
}
