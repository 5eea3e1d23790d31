/* line.c - lines in the 3D pipeline (raster stage, tile workers): a
 * set-up segment (line_setup.c) rasterized within one tile.  Points are in
 * point.c.
 *
 * Lines follow the diamond-exit rule in its exact closed form
 * (docs/raster-rules.md §7.1): with endpoints snapped to 1/256 px, an x-major
 * segment covers, in each column whose centre it spans, the pixel holding
 * the segment's point at that centre (a boundary point goes to the smaller
 * minor index, Direct3D's tie rule); the start pixel is added when the
 * start lies in its diamond, and the end pixel is removed when the end
 * lies in its diamond (half-open).  So the pixels do not depend on the
 * direction except for which end is left open, line strips join without
 * gaps or double pixels, and everything is integer arithmetic.  Wide lines
 * are OpenGL's: the segment moved by -(width - 1)/2 along the minor axis,
 * and a run of `width` pixels toward +minor from each of its pixels.
 *
 * Work is done where it is cheapest.  Setup finds, once per segment, the
 * columns, the DDA of their pixels, the two diamonds' pixels and the tiles
 * the pixels reach (binning puts the segment in those only, not in its
 * whole bounding box).  Each tile solves for the columns whose pixel falls
 * inside it and walks just those.  line_fragment through
 * sr__fragment_vary is the reference fragment path; common states take a
 * fast path (one pixel wide, plain color write, depth off or LESS) with
 * the same operations, four columns at a time with AVX2 for the
 * commonest, and test_lines_fast.c holds both to the reference. */
#include "fragment/msaa_ops.h"
#include "raster/smooth_line.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#elif defined(__aarch64__) && defined(__ARM_NEON) && defined(__BYTE_ORDER__) && \
    __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
#define SR_LINE_NEON 1
#include "raster/unorm8_neon.h"
#endif

#define H SR_SUBPIXEL_HALF
#define S SR_SUBPIXEL_ONE

/* 1 / |b - a|^2 (q8^2), the projection's scale: the reference's
 * expression, per tile rather than stored, to keep the record small. */
static double inv_len2(const sr_line *l)
{
    int64_t dx = (int64_t)l->xb - l->xa, dy = (int64_t)l->yb - l->ya;
    return 1.0 / ((double)dx * dx + (double)dy * dy);
}

typedef struct line_ctx {
    const sr_draw_state *ds;
    const sr_line *l;
    int rx0, ry0, rx1, ry1;
    bool xmajor;
    sr_frag_stats *st;
    double inv_len2;                  /* 1 / |b - a|^2 in q8^2 */
    bool equal_w;                     /* both ends share 1/w: interpolation is affine */
} line_ctx;

/* One path pixel's fragments: project its centre onto the segment for t,
 * then depth linear in t and varyings perspective-correct (docs/raster-rules.md
 * §5.5).  A wide line's path is the segment moved by -(width - 1)/2 along
 * the minor axis and each of its pixels starts a run of `width` toward
 * +minor (setup_walk in line_setup.c); the run's centre, (width - 1)/2
 * past the path pixel's, is projected onto the unmoved segment, which is
 * the path pixel's centre projected onto the moved one.  With width 1 it
 * is the pixel's own centre. */
static void line_fragment(const line_ctx *lc, int px, int py)
{
    const sr_line *l = lc->l;
    int64_t run_q8 = (int64_t)(l->width - 1) * H; /* the run's centre past the path pixel's */
    double cx = (double)px * S + H - l->xa, cy = (double)py * S + H - l->ya;
    if (lc->xmajor) {
        cy += (double)run_q8;
    } else {
        cx += (double)run_q8;
    }
    for (int k = 0; k < l->width; k++) {
        int qx = lc->xmajor ? px : px + k;
        int qy = lc->xmajor ? py + k : py;
        if (qx < lc->rx0 || qx >= lc->rx1 || qy < lc->ry0 || qy >= lc->ry1) {
            continue;
        }
        double t = (cx * (l->xb - l->xa) + cy * (l->yb - l->ya)) * lc->inv_len2;
        t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
        double z = l->za + t * (l->zb - l->za);
        float v[SR_MAX_VARYINGS];
        int n = l->ninterp;
        if (lc->equal_w) {
            /* Equal 1/w at both ends: perspective-correct is the lerp. */
            float tf = (float)t;
            for (int i = 0; i < n; i++) {
                v[i] = l->vary[i] + tf * (l->vary[n + i] - l->vary[i]);
            }
        } else {
            float qa = (float)(1.0 - t) * l->wa, qb = (float)t * l->wb;
            float inv = qa + qb != 0.0f ? 1.0f / (qa + qb) : 0.0f;
            for (int i = 0; i < n; i++) {
                v[i] = (qa * l->vary[i] + qb * l->vary[n + i]) * inv;
            }
        }
        sr__fragment_vary(lc->ds, qx, qy, z, v, l->flat, l->front, 1.0f, lc->st);
    }
}

/* Antialiased line: sr__smooth_line_walk's pixels (smooth_line.h), each
 * shaded with its coverage as alpha. */
typedef struct smooth_ctx {
    const sr_draw_state *ds;
    const sr_line *l;
    sr_frag_stats *st;
} smooth_ctx;

static inline void smooth_fragment(void *user, const sr_line_pixel_info *p)
{
    const smooth_ctx *sc = user;
    const sr_line *l = sc->l;
    int n = l->ninterp;
    double t = p->t;
    double z = l->za + t * (l->zb - l->za);
    float v[SR_MAX_VARYINGS];
    float qa = (float)(1.0 - t) * l->wa, qb = (float)t * l->wb;
    float inv = qa + qb != 0.0f ? 1.0f / (qa + qb) : 0.0f;
    for (int i = 0; i < n; i++) {
        v[i] = (qa * l->vary[i] + qb * l->vary[n + i]) * inv;
    }
    sr__fragment_vary(sc->ds, p->x, p->y, z, v, l->flat, l->front, p->coverage, sc->st);
}

static void raster_smooth_line(const sr_draw_state *ds, const sr_line *l, int rx0, int ry0,
                               int rx1, int ry1, sr_frag_stats *st)
{
    smooth_ctx sc = { ds, l, st };
    sr__smooth_line_walk(l->xa, l->ya, l->xb, l->yb, l->half_width, rx0, ry0, rx1, ry1,
                         smooth_fragment, &sc);
}

/* The columns of [klo, khi] whose path pixel lies in [vlo, vhi] on the
 * minor axis.  The pixel v(k) = floor(N(k) / d) is monotonic in k, so they
 * form one range [*ka, *kb], found in integers by solving
 * vlo d <= n0 + m dn <= (vhi + 1) d - 1 for m = k - k0, rather than by
 * walking every column of the tile and rejecting most of them. */
static bool column_range(const sr_line *l, int64_t klo, int64_t khi, int64_t vlo, int64_t vhi,
                         int64_t *ka, int64_t *kb)
{
    int64_t mlo = (klo > l->k0 ? klo : l->k0) - l->k0;
    int64_t mhi = (khi < l->k1 ? khi : l->k1) - l->k0;
    int64_t lo = vlo * l->d - l->n0, hi = (vhi + 1) * l->d - 1 - l->n0; /* m dn in [lo, hi] */
    if (l->dn > 0) {
        int64_t a = sr__ceil_div(lo, l->dn), b = sr__floor_div(hi, l->dn);
        mlo = a > mlo ? a : mlo;
        mhi = b < mhi ? b : mhi;
    } else if (l->dn < 0) {
        int64_t a = sr__ceil_div(-hi, -l->dn), b = sr__floor_div(-lo, -l->dn);
        mlo = a > mlo ? a : mlo;
        mhi = b < mhi ? b : mhi;
    } else if (lo > 0 || hi < 0) {
        return false;
    }
    *ka = l->k0 + mlo;
    *kb = l->k0 + mhi;
    return mlo <= mhi;
}

/* The reference walk: every path pixel of columns [ka, kb] and the
 * off-path start pixel through line_fragment, which clips the runs of
 * wide lines to the rectangle and shades through sr__fragment_vary. */
static void walk_generic(const line_ctx *lc, int64_t ka, int64_t kb)
{
    const sr_line *l = lc->l;
    bool xmajor = l->xmajor;
    sr_dda dda;
    sr__dda_init(&dda, l->n0 + (ka - l->k0) * l->dn, l->d, l->dn);
    for (int64_t k = ka; k <= kb; k++, sr__dda_step(&dda)) {
        int64_t j = dda.q;
        if (k == l->end_u && j == l->end_v) {
            continue; /* half-open: the end's own pixel is not drawn */
        }
        line_fragment(lc, xmajor ? (int)k : (int)j, xmajor ? (int)j : (int)k);
    }
    if (l->start_extra) {
        line_fragment(lc, xmajor ? l->start_u : l->start_v, xmajor ? l->start_v : l->start_u);
    }
}

/* ---- the fast path ----
 * One pixel wide, no program, texture, stencil, blending or color mask,
 * depth off or LESS, and a color that is the interpolated rgba (UNLIT,
 * GOURAUD, ATTRIBUTE) or the line's flat color: what line_fragment and
 * sr__fragment_vary do for that state, with the per-line constants
 * hoisted and the four channels in one vector.  Every floating-point
 * operation is the reference's, in its order (the build uses
 * -ffp-contract=off), so the bytes are the same; test_lines_fast.c holds
 * it to the reference. */

/* sr__unorm8 on r, g, b, a, packed as the framebuffer's bytes.  With SSE2
 * as in the triangle kernels: min(1, v) keeps NaN (min returns its second
 * operand then), truncation sends NaN and negatives to values the
 * saturating packs turn into 0, and anything above 1 became 255.  With
 * NEON on AArch64 as unorm8_neon.h says. */
static inline uint32_t pack_unorm8(v4f c)
{
#if defined(__SSE2__) && defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    __m128 v = _mm_min_ps(_mm_set1_ps(1.0f), (__m128)c);
    __m128i q = _mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(v, _mm_set1_ps(255.0f)),
                                            _mm_set1_ps(0.5f)));
    q = _mm_packs_epi32(q, q);
    return (uint32_t)_mm_cvtsi128_si32(_mm_packus_epi16(q, q));
#elif defined(SR_LINE_NEON)
    return sr__neon_pack_unorm8(c);
#else
    uint8_t out[4];
    for (int k = 0; k < 4; k++) {
        out[k] = sr__unorm8(c[k]);
    }
    uint32_t packed;
    memcpy(&packed, out, sizeof packed);
    return packed;
#endif
}

typedef enum line_color {
    LINE_COLOR_FLAT,        /* the line's flat color, packed once */
    LINE_COLOR_LERP,        /* equal 1/w at both ends: the lerp */
    LINE_COLOR_PERSPECTIVE, /* perspective-correct */
} line_color;

typedef struct fast_line {
    const sr_draw_state *ds;
    const sr_line *l;
    uint32_t *color;
    sr_framebuffer *fb;             /* its depth: sr__depth_at */
    size_t step_u, step_v;          /* buffer elements per column and per minor pixel */
    int64_t au, av, du, dv;         /* q8 start and direction on the major, minor axes */
    double dz;                      /* zb - za */
    double inv_len2;                /* 1 / |b - a|^2 in q8^2 */
    v4f va, vb, dvary;         /* the ends' rgba, and b - a */
    uint32_t flat;                  /* LINE_COLOR_FLAT: the packed color */
} fast_line;

/* Does the fast path draw this line exactly as the reference would? */
static bool line_is_fast(const sr_draw_state *ds, const sr_line *l)
{
    if (l->width != 1 || ds->program || ds->texture || ds->stencil_test || ds->blending ||
        ds->blend.enabled || ds->samples != 1 || ds->depth_mode == SR_DEPTH_MODE_GENERIC) {
        return false;
    }
    return ds->shading == SR_SHADING_FLAT ||
           (sr__color_varying_shading(ds->shading) && l->ninterp >= 4);
}

/* One pixel at buffer element idx whose centre c gives the projection's
 * numerator num = (c - a) . (b - a) in q8^2: line_fragment's t, depth and
 * color, and sr__fragment_vary's test and write.  The reference forms num
 * in doubles, but each of its terms is an integer below 2^48 (|c - a| <
 * 2^24 and |b - a| < 2^23 in q8 inside the guard band), so every step
 * there is exact; num in int64 is the same number, (double)num the same
 * double, and t the same product. */
SR_INLINE int fast_pixel(const fast_line *f, size_t idx, int64_t num, line_color mode,
                         bool less)
{
    const sr_line *l = f->l;
    double t = (double)num * f->inv_len2;
    /* The reference's clamp t < 0 ? 0 : t > 1 ? 1 : t, written as max
     * then min (maxsd, minsd): the same for every t but NaN and -0, and t
     * is neither (num is a finite integer, so num = 0 gives +0). */
    t = t > 0.0 ? t : 0.0;
    t = t < 1.0 ? t : 1.0;
    if (less) {
        double z = l->za + t * f->dz;
        uint32_t q = sr__quantize_depth(f->ds, &z);
        if (!(q < sr__depth_at(f->fb, idx))) {
            return 0;
        }
        sr__depth_put(f->fb, idx, q);
    }
    uint32_t packed = f->flat;
    if (mode == LINE_COLOR_LERP) {
        float tf = (float)t;
        packed = pack_unorm8(f->va + tf * f->dvary);
    } else if (mode == LINE_COLOR_PERSPECTIVE) {
        float qa = (float)(1.0 - t) * l->wa, qb = (float)t * l->wb;
        float inv = qa + qb != 0.0f ? 1.0f / (qa + qb) : 0.0f;
        packed = pack_unorm8((qa * f->va + qb * f->vb) * inv);
    }
    f->color[idx] = packed;
    return 1;
}

/* The projection's numerator at the centre of pixel (u, v). */
static int64_t centre_num(const fast_line *f, int64_t u, int64_t v)
{
    return (u * S + H - f->au) * f->du + (v * S + H - f->av) * f->dv;
}

/* The path pixels of columns [ka, kb] (all inside the rectangle).  The
 * DDA steps the pixel's minor index with Bresenham's error term (the
 * remainder), and with it the buffer element and the exact numerator, by
 * integer adds. */
SR_INLINE uint64_t walk_columns_as(const fast_line *f, int64_t ka, int64_t kb, line_color mode,
                                   bool less)
{
    const sr_line *l = f->l;
    /* |dn| <= d (|slope| <= 1), so the DDA's whole step is -1, 0 or 1. */
    int64_t d = l->d, dn = l->dn;
    int64_t dq = dn >= d ? 1 : dn < 0 ? -1 : 0, dr = dn - dq * d;
    int64_t n = l->n0 + (ka - l->k0) * dn;
    int64_t j = sr__floor_div(n, d), rem = n - j * d;
    int64_t num = centre_num(f, ka, j);
    size_t idx = (size_t)ka * f->step_u + (size_t)j * f->step_v;
    int64_t num_u = S * f->du + dq * (S * f->dv), num_v = S * f->dv;
    size_t idx_u = f->step_u + (size_t)dq * f->step_v, idx_v = f->step_v;
    /* The end's pixel, when on the path, is its column's pixel: skipping
     * that column leaves it open (half-open). */
    int64_t skip = l->end_u;
    uint64_t frags = 0;
    for (int64_t k = ka; k <= kb; k++) {
        if (k != skip) {
            frags += fast_pixel(f, idx, num, mode, less);
        }
        rem += dr;
        num += num_u;
        idx += idx_u;
        if (rem >= d) {
            rem -= d;
            num += num_v;
            idx += idx_v;
        }
    }
    return frags;
}

/* The off-path start pixel, drawn after the path when inside the
 * rectangle r (see sr__raster_line). */
SR_INLINE uint64_t start_pixel_as(const fast_line *f, const int r[4], line_color mode,
                                  bool less)
{
    const sr_line *l = f->l;
    if (l->start_extra && l->start_u >= r[0] && l->start_u < r[1] && l->start_v >= r[2] &&
        l->start_v < r[3]) {
        return fast_pixel(f, (size_t)l->start_u * f->step_u + (size_t)l->start_v * f->step_v,
                          centre_num(f, l->start_u, l->start_v), mode, less);
    }
    return 0;
}

/* The fragments written: the path, then the start pixel (the
 * reference's order). */
SR_INLINE uint64_t walk_fast_as(const fast_line *f, int64_t ka, int64_t kb, const int r[4],
                                line_color mode, bool less)
{
    uint64_t frags = walk_columns_as(f, ka, kb, mode, less);
    return frags + start_pixel_as(f, r, mode, less);
}

/* ---- four columns at a time (AVX2) ----
 * The commonest state (interpolated color, equal 1/w, depth off) takes
 * four columns per step when the CPU has AVX2.  Each column's pixel comes
 * from the closed form instead of the DDA, so lanes need no start-up and
 * a range splits freely: j = floor(N / d) with N = n0 + (k - k0) dn.  In
 * double lanes N (< 2^48) and d (< 2^31) are exact, and so is the floor of
 * their rounded quotient: an exact integer quotient is representable and
 * comes out exactly, and any other lies at least 1/d > 2^-31 from an
 * integer, farther than the rounding (half an ulp of |j| < 2^21) can move
 * it.  The projection's numerator, a sum of integer products below 2^48,
 * and the buffer element (< 2^29) are exact too.  t, its float, the color
 * and its packing then repeat the scalar path lane by lane. */
#if defined(__GNUC__) && defined(__SSE2__) && (defined(__x86_64__) || defined(__i386__)) && \
    defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
#define SR_LINE_AVX2 1
#include <immintrin.h>

/* sr__unorm8 on four pixels' r, g, b, a lanes, packed per pixel: the
 * triangle kernels' packing (see pack_unorm8 for why it is the same). */
SR_INLINE __m128i pack4_unorm8(const __m128 c[4])
{
    __m128i q[4];
    for (int k = 0; k < 4; k++) {
        __m128 v = _mm_min_ps(_mm_set1_ps(1.0f), c[k]);
        q[k] = _mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(v, _mm_set1_ps(255.0f)),
                                           _mm_set1_ps(0.5f)));
    }
    /* Bytes R0..3 B0..3 G0..3 A0..3, then interleaved to R G B A per pixel. */
    __m128i x = _mm_packus_epi16(_mm_packs_epi32(q[0], q[2]), _mm_packs_epi32(q[1], q[3]));
    __m128i y = _mm_unpacklo_epi8(x, _mm_srli_si128(x, 8));
    return _mm_unpacklo_epi16(y, _mm_srli_si128(y, 8));
}

/* Columns [ka, kb], every one drawn (the caller leaves out the end's). */
__attribute__((target("avx2"))) static uint64_t walk_lerp_avx2(const fast_line *f, int64_t ka,
                                                                int64_t kb)
{
    const sr_line *l = f->l;
    const __m256d n0 = _mm256_set1_pd((double)l->n0), dn = _mm256_set1_pd((double)l->dn);
    const __m256d d = _mm256_set1_pd((double)l->d), k0 = _mm256_set1_pd((double)l->k0);
    /* num = (k S + H - a_u) du + (j S + H - a_v) dv = a + k b + j c */
    const __m256d a = _mm256_set1_pd((double)((H - f->au) * f->du + (H - f->av) * f->dv));
    const __m256d b = _mm256_set1_pd((double)(S * f->du)), c = _mm256_set1_pd((double)(S * f->dv));
    const __m256d su = _mm256_set1_pd((double)f->step_u), sv = _mm256_set1_pd((double)f->step_v);
    const __m256d inv = _mm256_set1_pd(f->inv_len2);
    const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
    __m128 va[4], dva[4];
    for (int ch = 0; ch < 4; ch++) {
        va[ch] = _mm_set1_ps(f->va[ch]);
        dva[ch] = _mm_set1_ps(f->dvary[ch]);
    }
    __m256d k = _mm256_add_pd(_mm256_set1_pd((double)ka), _mm256_setr_pd(0, 1, 2, 3));
    for (int64_t kk = ka; kk <= kb; kk += 4) {
        __m256d nn = _mm256_add_pd(n0, _mm256_mul_pd(_mm256_sub_pd(k, k0), dn));
        __m256d j = _mm256_floor_pd(_mm256_div_pd(nn, d));
        __m256d num = _mm256_add_pd(_mm256_add_pd(a, _mm256_mul_pd(k, b)), _mm256_mul_pd(j, c));
        /* max then min, as fast_pixel (t is never NaN or -0). */
        __m256d t = _mm256_min_pd(_mm256_max_pd(_mm256_mul_pd(num, inv), zero), one);
        __m128 tf = _mm256_cvtpd_ps(t);
        __m128 col[4];
        for (int ch = 0; ch < 4; ch++) {
            col[ch] = _mm_add_ps(va[ch], _mm_mul_ps(tf, dva[ch]));
        }
        uint32_t px[4], idx[4];
        _mm_storeu_si128((__m128i *)px, pack4_unorm8(col));
        _mm_storeu_si128((__m128i *)idx, _mm256_cvttpd_epi32(_mm256_add_pd(
                                              _mm256_mul_pd(k, su), _mm256_mul_pd(j, sv))));
        int lanes = kb - kk < 3 ? (int)(kb - kk + 1) : 4;
        for (int i = 0; i < lanes; i++) {
            f->color[idx[i]] = px[i];
        }
        k = _mm256_add_pd(k, _mm256_set1_pd(4.0));
    }
    return kb >= ka ? (uint64_t)(kb - ka + 1) : 0;
}

/* The columns [ka, kb] but the end's (half-open), then the start pixel. */
static uint64_t walk_lerp_x4(const fast_line *f, int64_t ka, int64_t kb, const int r[4])
{
    int64_t skip = f->l->end_u;
    uint64_t frags;
    if (skip >= ka && skip <= kb) {
        frags = walk_lerp_avx2(f, ka, skip - 1) + walk_lerp_avx2(f, skip + 1, kb);
    } else {
        frags = walk_lerp_avx2(f, ka, kb);
    }
    return frags + start_pixel_as(f, r, LINE_COLOR_LERP, false);
}
#endif

/* r: the rectangle as major [r[0], r[1]) and minor [r[2], r[3]). */
static void walk_fast(const sr_draw_state *ds, const sr_line *l, int64_t ka, int64_t kb,
                      const int r[4], sr_frag_stats *st)
{
    sr_framebuffer *fb = ds->fb;
    size_t width = (size_t)fb->width;
    fast_line f = { .ds = ds, .l = l, .color = fb->color, .fb = fb };
    f.step_u = l->xmajor ? 1 : width;
    f.step_v = l->xmajor ? width : 1;
    f.au = l->xmajor ? l->xa : l->ya;
    f.av = l->xmajor ? l->ya : l->xa;
    f.du = (int64_t)(l->xmajor ? l->xb : l->yb) - f.au;
    f.dv = (int64_t)(l->xmajor ? l->yb : l->xb) - f.av;
    f.dz = l->zb - l->za;
    f.inv_len2 = inv_len2(l);
    line_color mode = LINE_COLOR_FLAT;
    if (ds->shading == SR_SHADING_FLAT) {
        memcpy(&f.va, l->flat, sizeof f.va);
        f.flat = pack_unorm8(f.va);
    } else {
        int n = l->ninterp;
        memcpy(&f.va, &l->vary[SR_VARY_COLOR], sizeof f.va);
        memcpy(&f.vb, &l->vary[n + SR_VARY_COLOR], sizeof f.vb);
        f.dvary = f.vb - f.va;
        mode = l->wa == l->wb ? LINE_COLOR_LERP : LINE_COLOR_PERSPECTIVE;
    }
    /* Instances per color mode and depth mode: the branches fold away. */
    bool less = ds->depth_mode == SR_DEPTH_MODE_LESS;
    uint64_t frags;
    switch (mode) {
    case LINE_COLOR_FLAT:
        frags = less ? walk_fast_as(&f, ka, kb, r, LINE_COLOR_FLAT, true)
                     : walk_fast_as(&f, ka, kb, r, LINE_COLOR_FLAT, false);
        break;
    case LINE_COLOR_LERP:
#ifdef SR_LINE_AVX2
        if (!less && ds->simd >= SR_SIMD_AVX2) {
            frags = walk_lerp_x4(&f, ka, kb, r);
            break;
        }
#endif
        frags = less ? walk_fast_as(&f, ka, kb, r, LINE_COLOR_LERP, true)
                     : walk_fast_as(&f, ka, kb, r, LINE_COLOR_LERP, false);
        break;
    default:
        frags = less ? walk_fast_as(&f, ka, kb, r, LINE_COLOR_PERSPECTIVE, true)
                     : walk_fast_as(&f, ka, kb, r, LINE_COLOR_PERSPECTIVE, false);
        break;
    }
    st->fragments += frags;
}

void sr__raster_line(const sr_draw_state *ds, const sr_line *l, int rx0, int ry0, int rx1,
                     int ry1, sr_frag_stats *st)
{
    /* A tile's records lie scattered through the chunk, so each visit
     * starts with cache misses.  Ask for the record's later lines now:
     * the varyings' place depends on ninterp, and loading them would
     * otherwise wait for the first line's miss before starting its own. */
    for (size_t off = 64; off < offsetof(sr_line, vary) + 2 * 4 * sizeof(float); off += 64) {
        __builtin_prefetch((const char *)l + off);
    }
    if (l->smooth) {
        raster_smooth_line(ds, l, rx0, ry0, rx1, ry1, st);
        return;
    }
    bool xmajor = l->xmajor;
    /* The rectangle as major [r[0], r[1]) and minor [r[2], r[3]). */
    int r[4] = { xmajor ? rx0 : ry0, xmajor ? rx1 : ry1, xmajor ? ry0 : rx0, xmajor ? ry1 : rx1 };
    /* Columns inside the rectangle whose path pixel, or some pixel of its
     * run of width - 1 more toward +minor, falls inside it. */
    int64_t ka, kb;
    if (!column_range(l, r[0], r[1] - 1, r[2] - (l->width - 1), r[3] - 1, &ka, &kb)) {
        ka = 0;
        kb = -1;
    }
    if (line_is_fast(ds, l)) {
        walk_fast(ds, l, ka, kb, r, st);
        return;
    }
    line_ctx lc = { ds, l, rx0, ry0, rx1, ry1, xmajor, st, inv_len2(l), l->wa == l->wb };
    walk_generic(&lc, ka, kb);
}
