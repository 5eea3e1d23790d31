/* framebuffer.c - creating, clearing and reading render targets (target
 * stage).  Called from the application thread. */
#include "target/framebuffer.h"
#include "context.h"
#include "parallel/pool.h"
#include "fragment/depth.h"
#include "raster/fixed.h"
#include "pipeline.h"
#include "rows.h"

#include <math.h>
#include <string.h>
#ifdef __SSE2__
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

sr_result sr_make_framebuffer(sr_context *ctx, const sr_framebuffer_desc *desc,
                              sr_framebuffer **out)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_make_framebuffer: ctx is NULL");
    }
    if (!out) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_make_framebuffer: out is NULL");
    }
    *out = NULL;
    if (!desc) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_make_framebuffer: desc is NULL");
    }
    if (desc->width <= 0 || desc->height <= 0) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_framebuffer_desc.%s must be > 0 (got %d)",
                        desc->width <= 0 ? "width" : "height",
                        desc->width <= 0 ? desc->width : desc->height);
    }
    if (desc->width > SR_MAX_FRAMEBUFFER_SIZE || desc->height > SR_MAX_FRAMEBUFFER_SIZE) {
        bool w = desc->width > SR_MAX_FRAMEBUFFER_SIZE;
        return sr__fail(ctx, SR_TOO_LARGE,
                        "sr_framebuffer_desc.%s %d exceeds the maximum %d",
                        w ? "width" : "height", w ? desc->width : desc->height,
                        SR_MAX_FRAMEBUFFER_SIZE);
    }
    int samples = desc->samples == 0 ? 1 : desc->samples;
    if (!sr__sample_offsets(samples)) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_framebuffer_desc.samples must be 0, 1, 2, 4, 8 or 16 (got %d)",
                        desc->samples);
    }
    int bits;
    sr_depth_format fmt = desc->depth_format == SR_DEPTH_DEFAULT ? SR_DEPTH_D24 : desc->depth_format;
    switch (fmt) {
    case SR_DEPTH_NONE: bits = -1; break;
    case SR_DEPTH_D16:  bits = 16; break;
    case SR_DEPTH_D24:  bits = 24; break;
    case SR_DEPTH_D32:  bits = 32; break;
    case SR_DEPTH_D32F: bits = 0;  break;
    default:
        return sr__fail(ctx, SR_INVALID_ARG, "sr_framebuffer_desc.depth_format %d is not a format",
                        (int)desc->depth_format);
    }

    sr_framebuffer *fb = sr__calloc(ctx, 1, sizeof *fb);
    if (!fb) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_make_framebuffer: out of memory");
    }
    size_t pixels = (size_t)desc->width * (size_t)desc->height;
    size_t n = pixels * (size_t)samples;
    fb->width = desc->width;
    fb->height = desc->height;
    fb->row0 = 0;
    fb->row1 = desc->height;
    fb->samples = samples;
    fb->wide_stores = ctx->simd == SR_SIMD_AVX512;
    fb->depth_format = fmt;
    fb->depth_bits = bits < 0 ? 0 : bits;
    fb->depth16 = fmt == SR_DEPTH_D16;
    fb->tiles_x = (desc->width + SR_TILE_SIZE - 1) >> SR_TILE_ORDER;
    fb->tiles_y = (desc->height + SR_TILE_SIZE - 1) >> SR_TILE_ORDER;
    fb->tile_pending = sr__calloc(ctx, (size_t)fb->tiles_x * fb->tiles_y, 1);
    fb->tile_memo = fb->tile_pending ? sr__calloc(ctx, (size_t)fb->tiles_x * fb->tiles_y,
                                                  sizeof *fb->tile_memo)
                                     : NULL;
    /* Nothing is written here: every tile starts with a pending clear to
     * transparent black and the far depth, carried out when the tile is
     * first drawn or read. */
    fb->color = fb->tile_memo ? sr__alloc_large(ctx, n * sizeof(uint32_t)) : NULL;
    if (fb->color && bits >= 0) {
        fb->depth = sr__alloc_large(ctx, n * (size_t)sr__depth_size(fb));
    }
    if (fb->color && desc->stencil) {
        fb->stencil = sr__alloc_large(ctx, n);
    }
    if (fb->color && samples > 1) {
        fb->resolved = sr__alloc_large(ctx, pixels * sizeof(uint32_t));
    }
    if (fb->tile_pending) {
        fb->clear_color = 0;
        fb->clear_depth = bits >= 0 ? sr__depth_quantize(1.0, fb->depth_bits) : 0;
        fb->clear_stencil = 0;
        memset(fb->tile_pending, SR_TILE_PENDING_COLOR | (bits >= 0 ? SR_TILE_PENDING_DEPTH : 0) |
                                 (desc->stencil ? SR_TILE_PENDING_STENCIL : 0),
               (size_t)fb->tiles_x * fb->tiles_y);
    }
    if (!fb->color || (bits >= 0 && !fb->depth) || (desc->stencil && !fb->stencil) ||
        (samples > 1 && !fb->resolved)) {
        sr_destroy_framebuffer(ctx, fb);
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_make_framebuffer: out of memory for %dx%d",
                        desc->width, desc->height);
    }
    *out = fb;
    sr__ok(ctx);
    return SR_OK;
}

void sr_destroy_framebuffer(sr_context *ctx, sr_framebuffer *fb)
{
    if (!ctx || !fb) {
        return;
    }
    sr__free(ctx, fb->color);
    sr__free(ctx, fb->depth);
    sr__free(ctx, fb->stencil);
    sr__free(ctx, fb->resolved);
    sr__free(ctx, fb->tile_pending);
    sr__free(ctx, fb->tile_memo);
    sr__free(ctx, fb);
}

/* n words of value v from p.  A tile's row is 256 bytes; the baseline
 * build's 16-byte stores made clearing tiles a tenth of a mesh's frame
 * on one thread, so at the AVX-512 level (the context's, which the CPU
 * runs: fb->wide_stores) the rows go in 64-byte stores, the same
 * words. */
#if defined(__x86_64__) && defined(__GNUC__)
SR_TARGET_AVX512 static void fill_words_avx512(uint32_t *p, uint32_t v, size_t n)
{
    __m512i w = _mm512_set1_epi32((int)v);
    size_t i = 0;
    for (; i + 16 <= n; i += 16) {
        _mm512_storeu_si512(p + i, w);
    }
    if (i < n) {
        _mm512_mask_storeu_epi32(p + i, (__mmask16)((1u << (n - i)) - 1), w);
    }
}
#endif

static void fill_words(uint32_t *p, uint32_t v, size_t n, bool wide)
{
#if defined(__x86_64__) && defined(__GNUC__)
    if (wide) {
        fill_words_avx512(p, v, n);
        return;
    }
#else
    (void)wide;
#endif
    for (size_t i = 0; i < n; i++) {
        p[i] = v;
    }
}

static void fill_halves(uint16_t *p, uint16_t v, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        p[i] = v;
    }
}

/* Fill [x0, x1) x [y0, y1) of one component (`size`-byte values: color
 * and depth words, D16's halves, stencil bytes) with v, a row of samples
 * at a time. */
static void fill_rect(const sr_framebuffer *fb, void *mem, int size, uint32_t v,
                      int x0, int y0, int x1, int y1, bool wide)
{
    /* A row of the rectangle is one run of samples in memory
     * (framebuffer.h). */
    size_t ns = (size_t)fb->samples;
    size_t run = x1 > x0 ? (size_t)(x1 - x0) * ns : 0;
    for (int y = y0; y < y1 && run; y++) {
        size_t first = ((size_t)y * fb->width + (size_t)x0) * ns;
        if (size == 4) {
            fill_words((uint32_t *)mem + first, v, run, wide);
        } else if (size == 2) {
            fill_halves((uint16_t *)mem + first, (uint16_t)v, run);
        } else {
            memset((uint8_t *)mem + first, (int)v, run);
        }
    }
}

/* Write the clear values of the `pending` components into a tile, in
 * 64-byte stores if `wide` (the AVX-512 level: fb->wide_stores).  Where
 * a component's base is the value being cleared to, only the tile's drawn
 * rectangle is written (SR_TILE_BASE_COLOR); otherwise the whole tile,
 * which makes that value its base.  Returns the tile's flags with the
 * base bits brought up to date; the drawn rectangle is emptied once every
 * component the framebuffer has is clear. */
static unsigned clear_tile(sr_framebuffer *fb, int tile, unsigned pending, bool wide)
{
    int tx = tile % fb->tiles_x, ty = tile / fb->tiles_x;
    int x0 = tx << SR_TILE_ORDER, y0 = ty << SR_TILE_ORDER;
    int x1 = x0 + SR_TILE_SIZE < fb->width ? x0 + SR_TILE_SIZE : fb->width;
    int y1 = y0 + SR_TILE_SIZE < fb->height ? y0 + SR_TILE_SIZE : fb->height;
    sr_tile_memo *m = &fb->tile_memo[tile];
    int dx0 = x0 + m->x0, dy0 = y0 + m->y0;
    int dx1 = x0 + m->x1 < x1 ? x0 + m->x1 : x1, dy1 = y0 + m->y1 < y1 ? y0 + m->y1 : y1;
    /* Only the rows in memory (a band's). */
    y0 = y0 > fb->row0 ? y0 : fb->row0;
    y1 = y1 < fb->row1 ? y1 : fb->row1;
    dy0 = dy0 > fb->row0 ? dy0 : fb->row0;
    dy1 = dy1 < fb->row1 ? dy1 : fb->row1;
    unsigned flags = fb->tile_pending[tile];
    struct {
        unsigned pending, base;
        void *mem;
        int size;
        uint32_t value, *memo;
    } part[3] = {
        { SR_TILE_PENDING_COLOR, SR_TILE_BASE_COLOR, fb->color, 4, fb->clear_color, &m->color },
        { SR_TILE_PENDING_DEPTH, SR_TILE_BASE_DEPTH, fb->depth, sr__depth_size(fb), fb->clear_depth,
          &m->depth },
        { SR_TILE_PENDING_STENCIL, SR_TILE_BASE_STENCIL, fb->stencil, 1, fb->clear_stencil,
          &m->stencil },
    };
    unsigned present = 0, cleared = 0;
    for (int k = 0; k < 3; k++) {
        if (!part[k].mem) {
            continue;   /* the framebuffer has no such buffer */
        }
        present |= part[k].pending;
        if (!(pending & part[k].pending)) {
            continue;
        }
        cleared |= part[k].pending;
        if ((flags & part[k].base) && *part[k].memo == part[k].value) {
            fill_rect(fb, part[k].mem, part[k].size, part[k].value, dx0, dy0, dx1, dy1, wide);
            continue;
        }
        fill_rect(fb, part[k].mem, part[k].size, part[k].value, x0, y0, x1, y1, wide);
        *part[k].memo = part[k].value;
        flags |= part[k].base;
    }
    if (cleared == present) {
        m->x0 = m->y0 = m->x1 = m->y1 = 0;
    }
    return flags & SR_TILE_BASE_ALL;
}

void sr__tile_resolve(sr_framebuffer *fb, int tile, bool wide)
{
    unsigned flags = fb->tile_pending[tile];
    if (!(flags & (SR_TILE_PENDING_ALL | SR_TILE_CLEAN_COLOR))) {
        return;
    }
    fb->tile_pending[tile] = (uint8_t)clear_tile(fb, tile, flags & SR_TILE_PENDING_ALL, wide);
}

_Static_assert(SR_TILE_SIZE <= UINT8_MAX, "a tile's drawn rectangle is kept in uint8_t");

void sr__tile_drawn(sr_framebuffer *fb, int tile, int x0, int y0, int x1, int y1)
{
    if (x0 >= x1 || y0 >= y1) {
        return;
    }
    int ox = (tile % fb->tiles_x) << SR_TILE_ORDER, oy = (tile / fb->tiles_x) << SR_TILE_ORDER;
    sr_tile_memo *m = &fb->tile_memo[tile];
    x0 -= ox;
    x1 -= ox;
    y0 -= oy;
    y1 -= oy;
    if (m->x0 < m->x1) {
        x0 = m->x0 < x0 ? m->x0 : x0;
        y0 = m->y0 < y0 ? m->y0 : y0;
        x1 = m->x1 > x1 ? m->x1 : x1;
        y1 = m->y1 > y1 ? m->y1 : y1;
    }
    m->x0 = (uint8_t)x0;
    m->y0 = (uint8_t)y0;
    m->x1 = (uint8_t)x1;
    m->y1 = (uint8_t)y1;
}

void sr__fb_resolve(sr_framebuffer *fb, unsigned components)
{
    bool wide = fb->wide_stores;
    int tiles = fb->tiles_x * fb->tiles_y;
    for (int t = 0; t < tiles; t++) {
        unsigned pending = fb->tile_pending[t];
        if (pending & components) {
            unsigned base = clear_tile(fb, t, pending & SR_TILE_PENDING_ALL, wide);
            fb->tile_pending[t] = (uint8_t)(base | (pending & SR_TILE_PENDING_COLOR
                                                        ? SR_TILE_CLEAN_COLOR
                                                        : pending & SR_TILE_CLEAN_COLOR));
        }
    }
}

/* Clear the flags `bits` of every tile. */
static void drop_tile_flags(sr_framebuffer *fb, unsigned bits)
{
    int tiles = fb->tiles_x * fb->tiles_y;
    for (int t = 0; t < tiles; t++) {
        fb->tile_pending[t] &= (uint8_t)~bits;
    }
}

/* Whether any tile has one of the flags `bits`, eight tiles a step: the
 * 2D fills call sr__fb_begin_write once per shape, and after the first
 * one nothing is left to resolve or drop. */
static bool any_tile_flags(const sr_framebuffer *fb, unsigned bits)
{
    size_t tiles = (size_t)fb->tiles_x * (size_t)fb->tiles_y, t = 0;
    uint64_t seen = 0;
    for (; t + 8 <= tiles; t += 8) {
        uint64_t eight;
        memcpy(&eight, fb->tile_pending + t, sizeof eight);
        seen |= eight;
    }
    for (; t < tiles; t++) {
        seen |= fb->tile_pending[t];
    }
    return (seen & (UINT64_C(0x0101010101010101) * (uint8_t)bits)) != 0;
}

void sr__fb_begin_write(sr_framebuffer *fb)
{
    if (!any_tile_flags(fb, SR_TILE_PENDING_COLOR | SR_TILE_COLOR_FROM_CLEARS)) {
        return;
    }
    sr__fb_resolve(fb, SR_TILE_PENDING_COLOR);
    drop_tile_flags(fb, SR_TILE_COLOR_FROM_CLEARS);
}

sr_result sr__fb_begin_2d(sr_context *ctx, const char *fn, sr_framebuffer *fb)
{
    if (fb->samples > 1) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "%s: the framebuffer is multisampled; 2D drawing needs a single-sampled "
                        "one (sr_resolve into it first)", fn);
    }
    if (sr__fb_is_band(fb)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: 2D drawing needs a whole framebuffer, "
                        "not a band of sr_render_bands", fn);
    }
    sr__fb_begin_write(fb);
    return SR_OK;
}

int sr_framebuffer_width(const sr_framebuffer *fb) { return fb ? fb->width : 0; }
int sr_framebuffer_height(const sr_framebuffer *fb) { return fb ? fb->height : 0; }
sr_depth_format sr_framebuffer_depth_format(const sr_framebuffer *fb)
{
    return fb ? fb->depth_format : SR_DEPTH_NONE;
}
int sr_framebuffer_samples(const sr_framebuffer *fb) { return fb ? fb->samples : 0; }
bool sr_framebuffer_has_stencil(const sr_framebuffer *fb) { return fb && fb->stencil; }

/* D3D's standard patterns in 1/16 px from the centre, times 16 (q8). */
#define P(x, y) { (int8_t)(16 * (x)), (int8_t)(16 * (y)) }
static const int8_t offsets_1[1][2] = { P(0, 0) };
static const int8_t offsets_2[2][2] = { P(4, 4), P(-4, -4) };
static const int8_t offsets_4[4][2] = { P(-2, -6), P(6, -2), P(-6, 2), P(2, 6) };
static const int8_t offsets_8[8][2] = {
    P(1, -3), P(-1, 3), P(5, 1), P(-3, -5), P(-5, 5), P(-7, -1), P(3, 7), P(7, -7),
};
static const int8_t offsets_16[16][2] = {
    P(1, 1), P(-1, -3), P(-3, 2), P(4, -1), P(-5, -2), P(2, 5), P(5, 3), P(3, -5),
    P(-2, 6), P(0, -7), P(-4, -6), P(-6, 4), P(-8, 0), P(7, -4), P(6, 7), P(-7, -8),
};
#undef P

const int8_t (*sr__sample_offsets(int samples))[2]
{
    switch (samples) {
    case 1:  return offsets_1;
    case 2:  return offsets_2;
    case 4:  return offsets_4;
    case 8:  return offsets_8;
    case 16: return offsets_16;
    default: return NULL;
    }
}

sr_result sr_sample_position(int samples, int index, float *x, float *y)
{
    const int8_t (*off)[2] = sr__sample_offsets(samples);
    if (!x || !y) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_sample_position: %s is NULL", x ? "y" : "x");
    }
    if (!off) {
        return sr__fail(NULL, SR_INVALID_ARG,
                        "sr_sample_position: samples %d must be 1, 2, 4, 8 or 16", samples);
    }
    if (index < 0 || index >= samples) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_sample_position: index %d is not in 0..%d",
                        index, samples - 1);
    }
    *x = (float)(128 + off[index][0]) / 256.0f;
    *y = (float)(128 + off[index][1]) / 256.0f;
    return SR_OK;
}

/* The box resolve of one tile into dst (single-sampled, same size): each
 * channel (sum + n/2) / n, the rounded average (docs/raster-rules.md §9.3).  A tile
 * whose clear is still pending resolves to the clear color without
 * touching its samples, and a pixel whose samples agree (every pixel
 * inside a triangle) is copied: most of a frame costs one compare per
 * sample. */
#ifdef __SSE2__
/* One pixel's four samples (16 bytes): copied when they agree, else the
 * rounded channel sums (s0 + s2) + (s1 + s3), (sum + 2) >> 2, in 16-bit
 * lanes - exact, the sums stay below 1021. */
static uint32_t resolve4(const uint32_t *s)
{
    __m128i v = _mm_loadu_si128((const __m128i *)s);
    if (_mm_movemask_epi8(_mm_cmpeq_epi32(v, _mm_shuffle_epi32(v, 0))) == 0xffff) {
        return s[0];
    }
    __m128i zero = _mm_setzero_si128();
    __m128i sum = _mm_add_epi16(_mm_unpacklo_epi8(v, zero), _mm_unpackhi_epi8(v, zero));
    sum = _mm_add_epi16(sum, _mm_srli_si128(sum, 8));
    sum = _mm_srli_epi16(_mm_add_epi16(sum, _mm_set1_epi16(2)), 2);
    return (uint32_t)_mm_cvtsi128_si32(_mm_packus_epi16(sum, sum));
}
#endif

#if defined(__x86_64__) && defined(__SSE2__)
#define SR_HAVE_WIDE_RESOLVE 1
#include <immintrin.h>

/* Four pixels' sixteen samples in one AVX-512 register, n pixels of a row
 * in groups of four (the rest left to the caller): copied where all four
 * pixels' samples agree, else resolve4's sums for all four at once - the
 * bytes widened to 16 bits, each pixel's samples added in pairs across
 * the register's 64- and 128-bit halves, rounded and packed back. */
SR_TARGET_AVX512 static int resolve_row4_avx512(const uint32_t *s, uint32_t *d, int n)
{
    const __m512i first = _mm512_setr_epi32(0, 0, 0, 0, 4, 4, 4, 4, 8, 8, 8, 8, 12, 12, 12, 12);
    const __m512i gather = _mm512_setr_epi32(0, 4, 8, 12, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0);
    const __m512i pixels = _mm512_setr_epi32(0, 8, 2, 10, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0);
    int x = 0;
    for (; x + 4 <= n; x += 4) {
        __m512i v = _mm512_loadu_si512(&s[x * 4]);
        __m512i out;
        if (_mm512_cmpeq_epi32_mask(v, _mm512_permutexvar_epi32(first, v)) == 0xffff) {
            out = _mm512_permutexvar_epi32(gather, v);
        } else {
            __m512i r[2];
            for (int h = 0; h < 2; h++) {
                /* Pixels 2h and 2h + 1: 16 words each, sample k at 4k. */
                __m512i w = _mm512_cvtepu8_epi16(h ? _mm512_extracti64x4_epi64(v, 1)
                                                   : _mm512_castsi512_si256(v));
                w = _mm512_add_epi16(w, _mm512_shuffle_epi32(w, _MM_PERM_BADC));
                w = _mm512_add_epi16(w, _mm512_shuffle_i64x2(w, w, _MM_SHUFFLE(2, 3, 0, 1)));
                r[h] = _mm512_srli_epi16(_mm512_add_epi16(w, _mm512_set1_epi16(2)), 2);
            }
            /* Pixel 0 lands in dword 0, 1 in dword 8, 2 in dword 2, 3 in 10. */
            out = _mm512_permutexvar_epi32(pixels, _mm512_packus_epi16(r[0], r[1]));
        }
        _mm_storeu_si128((__m128i *)&d[x], _mm512_castsi512_si128(out));
    }
    return x;
}
#endif

static void resolve_tile(const sr_framebuffer *src, uint32_t *dst, int tile, bool wide)
{
    int n = src->samples;
    size_t w = (size_t)src->width;
    int tx = tile % src->tiles_x, ty = tile / src->tiles_x;
    int x0 = tx << SR_TILE_ORDER, y0 = ty << SR_TILE_ORDER;
    int x1 = x0 + SR_TILE_SIZE < src->width ? x0 + SR_TILE_SIZE : src->width;
    int y1 = y0 + SR_TILE_SIZE < src->height ? y0 + SR_TILE_SIZE : src->height;
    y0 = y0 > src->row0 ? y0 : src->row0;
    y1 = y1 < src->row1 ? y1 : src->row1;
    bool pending = src->tile_pending[tile] & SR_TILE_PENDING_COLOR;
    for (int y = y0; y < y1; y++) {
        int x = x0;
#ifdef SR_HAVE_WIDE_RESOLVE
        if (wide && n == 4 && !pending) {
            size_t p = (size_t)y * w + (size_t)x0;
            x += resolve_row4_avx512(&src->color[p * 4], &dst[p], x1 - x0);
        }
#else
        (void)wide;
#endif
        for (; x < x1; x++) {
            size_t p = (size_t)y * w + (size_t)x;
            if (pending) {
                dst[p] = src->clear_color;
                continue;
            }
            const uint32_t *s = &src->color[p * (size_t)n];
#ifdef __SSE2__
            if (n == 4) {
                dst[p] = resolve4(s);
                continue;
            }
#endif
            uint32_t diff = 0;
            for (int i = 1; i < n; i++) {
                diff |= s[i] ^ s[0];
            }
            if (!diff) {
                dst[p] = s[0];
                continue;
            }
            unsigned sum[4] = { 0, 0, 0, 0 };
            for (int i = 0; i < n; i++) {
                for (int c = 0; c < 4; c++) {
                    sum[c] += (s[i] >> (8 * c)) & 0xffu;
                }
            }
            uint32_t out = 0;
            for (int c = 0; c < 4; c++) {
                out |= ((sum[c] + (unsigned)n / 2) / (unsigned)n) << (8 * c);
            }
            dst[p] = out;
        }
    }
}

typedef struct resolve_job {
    const sr_framebuffer *src;
    uint32_t *dst;
    sr_framebuffer *dst_fb;    /* NULL: dst is a plain image */
    bool wide;                 /* the AVX-512 rows */
} resolve_job;

static void run_resolve(void *arg, int job, int thread)
{
    (void)thread;
    const resolve_job *j = arg;
    /* A tile nobody drew since the clear resolves to the clear color: a
     * framebuffer destination takes it as its own deferred clear rather
     * than 16 KiB of stores. */
    if (j->dst_fb && (j->src->tile_pending[job] & SR_TILE_PENDING_COLOR)) {
        /* A destination tile already clean in that color stays as it is. */
        if (!(j->dst_fb->tile_pending[job] & SR_TILE_CLEAN_COLOR)) {
            j->dst_fb->tile_pending[job] |= SR_TILE_PENDING_COLOR;
        }
        return;
    }
    if (j->dst_fb) {
        j->dst_fb->tile_pending[job] &=
            (uint8_t)~(SR_TILE_PENDING_COLOR | SR_TILE_COLOR_FROM_CLEARS);
    }
    resolve_tile(j->src, j->dst, job, j->wide);
}

/* Resolve every tile into dst_fb's color, or into the image dst when
 * dst_fb is NULL, on the context's threads when there is one. */
static void resolve_all(sr_context *ctx, const sr_framebuffer *src, sr_framebuffer *dst_fb,
                        uint32_t *dst)
{
    resolve_job j = { src, dst_fb ? dst_fb->color : dst, dst_fb,
                      src->wide_stores };
    if (dst_fb && dst_fb->clear_color != src->clear_color) {
        drop_tile_flags(dst_fb, SR_TILE_CLEAN_COLOR); /* they hold the old clear color */
        dst_fb->clear_color = src->clear_color;
    }
    sr__pool_run(ctx ? ctx->pool : NULL, run_resolve, &j, src->tiles_x * src->tiles_y);
}

/* Reading resolves deferred clears (and multisampled pixels): logically the
 * framebuffer is unchanged, so the read functions keep their const
 * parameter. */
const uint32_t *sr__fb_color_image(const sr_framebuffer *fb)
{
    if (fb->samples == 1) {
        sr__fb_resolve((sr_framebuffer *)fb, SR_TILE_PENDING_COLOR);
        return fb->color;
    }
    resolve_all(NULL, fb, NULL, fb->resolved);
    return fb->resolved;
}

const uint8_t *sr_framebuffer_pixels(const sr_framebuffer *fb)
{
    if (!fb || sr__fb_is_band(fb)) {
        return NULL;
    }
    return (const uint8_t *)sr__fb_color_image(fb);
}

sr_result sr_resolve(sr_context *ctx, const sr_framebuffer *src, sr_framebuffer *dst)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_resolve: ctx is NULL");
    }
    if (!src || !dst) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_resolve: %s is NULL", src ? "dst" : "src");
    }
    if (dst->samples != 1 || src->width != dst->width || src->height != dst->height) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_resolve: the destination must be single-sampled and %dx%d "
                        "(got %d samples, %dx%d)", src->width, src->height, dst->samples,
                        dst->width, dst->height);
    }
    if (sr__fb_is_band(src) || sr__fb_is_band(dst)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_resolve: not on a band of sr_render_bands");
    }
    if (src == dst) {
        sr__fb_resolve(dst, SR_TILE_PENDING_COLOR);
        sr__ok(ctx);
        return SR_OK;
    }
    /* Every destination pixel is written (or, for the source's cleared
     * tiles, cleared again): its pending color clears are moot.  A
     * multisampled source's jobs settle each destination tile's flags. */
    if (src->samples == 1) {
        drop_tile_flags(dst, SR_TILE_PENDING_COLOR | SR_TILE_COLOR_FROM_CLEARS);
        sr__fb_resolve((sr_framebuffer *)src, SR_TILE_PENDING_COLOR);
        memcpy(dst->color, src->color, (size_t)src->width * src->height * sizeof(uint32_t));
    } else {
        resolve_all(ctx, src, dst, NULL);
    }
    sr__ok(ctx);
    return SR_OK;
}

static uint8_t unorm8(float v)
{
    if (!(v > 0.0f)) {
        return 0;
    }
    if (v >= 1.0f) {
        return 255;
    }
    return (uint8_t)(v * 255.0f + 0.5f);
}

sr_result sr_clear(sr_context *ctx, sr_framebuffer *fb, const sr_clear_desc *desc)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_clear: ctx is NULL");
    }
    if (!fb || !desc) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_clear: %s is NULL", fb ? "desc" : "fb");
    }
    for (int c = 0; c < 4; c++) {
        if (!isfinite(desc->color[c])) {
            return sr__fail(ctx, SR_INVALID_ARG, "sr_clear_desc.color[%d] is not finite", c);
        }
    }
    if ((unsigned)desc->color_action > SR_ACTION_KEEP ||
        (unsigned)desc->depth_action > SR_ACTION_KEEP ||
        (unsigned)desc->stencil_action > SR_ACTION_KEEP) {
        const char *field = (unsigned)desc->color_action > SR_ACTION_KEEP ? "color_action"
                            : (unsigned)desc->depth_action > SR_ACTION_KEEP ? "depth_action"
                                                                             : "stencil_action";
        return sr__fail(ctx, SR_INVALID_ARG, "sr_clear_desc.%s is not an sr_clear_action", field);
    }
    if (!(desc->depth >= 0.0f && desc->depth <= 1.0f)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_clear_desc.depth must be in [0, 1] (got %g)",
                        (double)desc->depth);
    }
    /* The default actions clear to fixed values; a value they would drop is
     * most likely a forgotten SR_ACTION_CLEAR. */
    if (desc->depth_action == SR_ACTION_DEFAULT && desc->depth != 0.0f && desc->depth != 1.0f) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_clear_desc.depth %g needs depth_action = SR_ACTION_CLEAR "
                        "(the default action clears to 1)", (double)desc->depth);
    }
    if (desc->stencil_action == SR_ACTION_DEFAULT && desc->stencil != 0) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_clear_desc.stencil %d needs stencil_action = SR_ACTION_CLEAR "
                        "(the default action clears to 0)", desc->stencil);
    }
    float depth = desc->depth_action == SR_ACTION_CLEAR ? desc->depth : 1.0f;
    uint8_t stencil = desc->stencil_action == SR_ACTION_CLEAR ? desc->stencil : 0;
    unsigned pending = 0;
    bool same_color = false;
    if (desc->color_action != SR_ACTION_KEEP) {
        uint8_t rgba[4] = { unorm8(desc->color[0]), unorm8(desc->color[1]),
                            unorm8(desc->color[2]), unorm8(desc->color[3]) };
        uint32_t color;
        memcpy(&color, rgba, sizeof color);
        same_color = color == fb->clear_color;
        fb->clear_color = color;
        pending |= SR_TILE_PENDING_COLOR;
    }
    if (desc->depth_action != SR_ACTION_KEEP && fb->depth) {
        fb->clear_depth = sr__depth_quantize(depth, fb->depth_bits);
        pending |= SR_TILE_PENDING_DEPTH;
    }
    if (desc->stencil_action != SR_ACTION_KEEP && fb->stencil) {
        fb->clear_stencil = stencil;
        pending |= SR_TILE_PENDING_STENCIL;
    }
    int tiles = fb->tiles_x * fb->tiles_y;
    for (int t = 0; t < tiles; t++) {
        unsigned p = fb->tile_pending[t], add = pending;
        if ((p & SR_TILE_CLEAN_COLOR) && same_color) {
            add &= ~SR_TILE_PENDING_COLOR; /* already this color */
        }
        if (add & SR_TILE_PENDING_COLOR) {
            p &= ~SR_TILE_CLEAN_COLOR;
        }
        fb->tile_pending[t] = (uint8_t)(p | add);
    }
    sr__ok(ctx);
    return SR_OK;
}

/* `pixels` is the caller's buffer, named `pixels_name` in messages. */
static sr_result check_rect(sr_context *ctx, const char *fn, const sr_framebuffer *fb,
                            int x, int y, int w, int h, const void *pixels,
                            const char *pixels_name)
{
    if (!fb || !pixels) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %s is NULL", fn, fb ? pixels_name : "fb");
    }
    if (x < 0 || y < 0 || w <= 0 || h <= 0 || x > fb->width - w || y > fb->height - h) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "%s: rectangle (%d, %d, %d x %d) is not inside the %dx%d framebuffer",
                        fn, x, y, w, h, fb->width, fb->height);
    }
    if (y < fb->row0 || y + h > fb->row1) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "%s: rows %d .. %d are not all in the band (rows %d .. %d)",
                        fn, y, y + h - 1, fb->row0, fb->row1 - 1);
    }
    return SR_OK;
}

/* The arguments of sr_read_pixels and sr_write_pixels: a rectangle inside
 * fb and RGBA8 rows of at least 4 * w bytes. */
static sr_result check_rgba_rect(sr_context *ctx, const char *fn, const sr_framebuffer *fb,
                                 int x, int y, int w, int h, const void *pixels,
                                 const char *pixels_name, size_t stride)
{
    sr_result r = check_rect(ctx, fn, fb, x, y, w, h, pixels, pixels_name);
    if (r == SR_OK && stride < (size_t)w * 4) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: stride %zu < 4 * width", fn, stride);
    }
    if (r == SR_OK && !sr__rows_fit(pixels, (size_t)h, stride, (size_t)w * 4)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %d rows of stride %zu run past the end of memory",
                        fn, h, stride);
    }
    return r;
}

sr_result sr_read_pixels(sr_context *ctx, const sr_framebuffer *fb,
                         int x, int y, int w, int h, uint8_t *out, size_t stride)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_read_pixels: ctx is NULL");
    }
    sr_result r = check_rgba_rect(ctx, "sr_read_pixels", fb, x, y, w, h, out, "out", stride);
    if (r != SR_OK) {
        return r;
    }
    const uint32_t *image = sr__fb_color_image(fb);
    for (int row = 0; row < h; row++) {
        memcpy(out + (size_t)row * stride, image + (size_t)(y + row) * fb->width + x,
               (size_t)w * 4);
    }
    sr__ok(ctx);
    return SR_OK;
}

sr_result sr_write_pixels(sr_context *ctx, sr_framebuffer *fb, int x, int y, int w, int h,
                          const uint8_t *rgba, size_t stride)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_write_pixels: ctx is NULL");
    }
    sr_result r = check_rgba_rect(ctx, "sr_write_pixels", fb, x, y, w, h, rgba, "rgba", stride);
    if (r != SR_OK) {
        return r;
    }
    /* The source may be the framebuffer's own pixels (sr_framebuffer_pixels
     * of a single-sampled one is its color buffer): rows copied in place
     * would then read rows already overwritten, so such a source is read
     * from a copy. */
    size_t row_bytes = (size_t)w * 4, span = (size_t)(h - 1) * stride + row_bytes;
    size_t row_words = (size_t)fb->width * (size_t)fb->samples;
    const uint8_t *image = (const uint8_t *)(fb->color + (size_t)fb->row0 * row_words);
    size_t image_bytes = (size_t)(fb->row1 - fb->row0) * row_words * 4;
    uint8_t *copy = NULL;
    if ((uintptr_t)rgba < (uintptr_t)image + image_bytes &&
        (uintptr_t)image < (uintptr_t)rgba + span) {
        copy = sr__alloc(ctx, row_bytes * (size_t)h);
        if (!copy) {
            return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_write_pixels: out of memory");
        }
        for (int row = 0; row < h; row++) {
            memcpy(copy + (size_t)row * row_bytes, rgba + (size_t)row * stride, row_bytes);
        }
        rgba = copy;
        stride = row_bytes;
    }
    /* The tiles under the rectangle: their pending clears are carried out
     * first (the rest of each tile still gets the cleared values), they no
     * longer hold only the clear color, and the rectangle joins what was
     * drawn on them, so a later clear to their base color rewrites it. */
    bool wide = fb->wide_stores;
    int tx0 = x >> SR_TILE_ORDER, tx1 = (x + w - 1) >> SR_TILE_ORDER;
    int ty0 = y >> SR_TILE_ORDER, ty1 = (y + h - 1) >> SR_TILE_ORDER;
    for (int ty = ty0; ty <= ty1; ty++) {
        for (int tx = tx0; tx <= tx1; tx++) {
            int t = ty * fb->tiles_x + tx;
            unsigned flags = fb->tile_pending[t];
            if (flags & SR_TILE_PENDING_ALL) {
                flags = clear_tile(fb, t, flags & SR_TILE_PENDING_ALL, wide);
            }
            fb->tile_pending[t] = (uint8_t)(flags & ~SR_TILE_CLEAN_COLOR);
            int cx0 = tx << SR_TILE_ORDER, cy0 = ty << SR_TILE_ORDER;
            int cx1 = cx0 + SR_TILE_SIZE, cy1 = cy0 + SR_TILE_SIZE;
            sr__tile_drawn(fb, t, x > cx0 ? x : cx0, y > cy0 ? y : cy0,
                           x + w < cx1 ? x + w : cx1, y + h < cy1 ? y + h : cy1);
        }
    }
    /* Multisampled: every sample of a pixel takes its value, so the
     * resolved image reads back exactly what was written. */
    size_t ns = (size_t)fb->samples;
    for (int row = 0; row < h; row++) {
        const uint8_t *src = rgba + (size_t)row * stride;
        uint32_t *dst = fb->color + ((size_t)(y + row) * (size_t)fb->width + (size_t)x) * ns;
        if (ns == 1) {
            memcpy(dst, src, (size_t)w * 4);
            continue;
        }
        for (int col = 0; col < w; col++) {
            uint32_t v;
            memcpy(&v, src + (size_t)col * 4, 4);
            for (size_t k = 0; k < ns; k++) {
                dst[(size_t)col * ns + k] = v;
            }
        }
    }
    sr__free(ctx, copy);
    sr__ok(ctx);
    return SR_OK;
}

sr_result sr_read_depth(sr_context *ctx, const sr_framebuffer *fb,
                        int x, int y, int w, int h, float *out, size_t stride)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_read_depth: ctx is NULL");
    }
    sr_result r = check_rect(ctx, "sr_read_depth", fb, x, y, w, h, out, "out");
    if (r != SR_OK) {
        return r;
    }
    if (!fb->depth) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_read_depth: the framebuffer has no depth buffer");
    }
    if (stride < (size_t)w) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_read_depth: stride %zu < width", stride);
    }
    if (stride > SIZE_MAX / sizeof(float) ||
        !sr__rows_fit(out, (size_t)h, stride * sizeof(float), (size_t)w * sizeof(float))) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_read_depth: %d rows of stride %zu floats run past the end of memory",
                        h, stride);
    }
    sr__fb_resolve((sr_framebuffer *)fb, SR_TILE_PENDING_DEPTH);
    for (int row = 0; row < h; row++) {
        for (int col = 0; col < w; col++) {
            /* Multisampled: sample 0's depth. */
            size_t px = (size_t)(y + row) * fb->width + x + col;
            uint32_t q = sr__depth_at(fb, px * (size_t)fb->samples);
            out[(size_t)row * stride + col] = (float)sr__depth_dequantize(q, fb->depth_bits);
        }
    }
    sr__ok(ctx);
    return SR_OK;
}

sr_result sr_read_stencil(sr_context *ctx, const sr_framebuffer *fb,
                          int x, int y, int w, int h, uint8_t *out, size_t stride)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_read_stencil: ctx is NULL");
    }
    sr_result r = check_rect(ctx, "sr_read_stencil", fb, x, y, w, h, out, "out");
    if (r != SR_OK) {
        return r;
    }
    if (!fb->stencil) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_read_stencil: the framebuffer has no stencil buffer");
    }
    if (stride < (size_t)w) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_read_stencil: stride %zu < width", stride);
    }
    if (!sr__rows_fit(out, (size_t)h, stride, (size_t)w)) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_read_stencil: %d rows of stride %zu run past the end of memory", h,
                        stride);
    }
    sr__fb_resolve((sr_framebuffer *)fb, SR_TILE_PENDING_STENCIL);
    for (int row = 0; row < h; row++) {
        for (int col = 0; col < w; col++) {
            size_t px = (size_t)(y + row) * fb->width + x + col;
            out[(size_t)row * stride + col] = fb->stencil[px * (size_t)fb->samples];
        }
    }
    sr__ok(ctx);
    return SR_OK;
}
