/* simd_wide16.h - sixteen pixels at a time, the AVX-512 level's stamps
 * (raster stage, tile worker threads): two rows of a block, a 4 x 4 or
 * 8 x 2 stamp of a small triangle, or sixteen pixels of a row, with
 * edge values in double halves or, where they fit, in 32-bit lanes.
 * Included by simd_kernel.h in its AVX-512 instance only, after
 * simd_wide.h, before raster_as, which walks these stamps; with the
 * textured stamps (simd_tex.h) and the tiny triangles' set-up
 * (simd_tiny.h).  simd_wide16_walk.h holds this level's walks.
 *
 * Exactness, as in simd_wide.h: every lane repeats the scalar fragment
 * stage's operations in the same order. */

/* Sixteen pixels at once (the AVX-512 instance): two rows of a block, or
 * a 4 x 4 stamp of a tiny triangle.  Doubles take two 8-lane registers,
 * floats one 16-lane register; a mask register carries coverage and the
 * depth test to masked stores, so no lane outside the triangle or behind
 * the depth buffer is written. */
/* Both rows' exact edge values to float, one rounding each. */
SR_SIMD_TARGET SR_INLINE __m512 SR_SIMD_FN(w16_cvt)(__m512d row0, __m512d row1)
{
    return _mm512_insertf32x8(_mm512_castps256_ps512(_mm512_cvtpd_ps(row0)),
                              _mm512_cvtpd_ps(row1), 1);
}

/* sr__unorm8 on one channel of sixteen lanes, as wide_pack: min keeps
 * NaN, truncation sends it below zero, the max takes it to 0. */
SR_SIMD_TARGET SR_INLINE __m512i SR_SIMD_FN(w16_unorm8)(__m512 c)
{
    __m512 v = _mm512_min_ps(_mm512_set1_ps(1.0f), c);
    return _mm512_max_epi32(_mm512_cvttps_epi32(_mm512_add_ps(
                                _mm512_mul_ps(v, _mm512_set1_ps(255.0f)), _mm512_set1_ps(0.5f))),
                            _mm512_setzero_si512());
}

/* A triangle's constants in sixteen lanes, made once per triangle.  A
 * color channel equal at the three vertices (alpha, nearly always) is
 * c0 + l1 0 + l2 0 = c0 wherever l1 and l2 are finite, so its byte is
 * packed here once (`fixed`) and only the `varying` channels are
 * interpolated per pixel. */
typedef struct SR_SIMD_FN(w16_lanes) {
    __m512 w[3], c0[4], c1[4], c2[4];
    __m512d z0, dz1, dz2;
    __m512i fixed;
    unsigned varying;      /* bit ch: channel ch differs between vertices */
} SR_SIMD_FN(w16_lanes);

SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(w16_make)(const sr_tri *t, sr_shading shading,
                                                   SR_SIMD_FN(w16_lanes) *o)
{
    /* From the record itself rather than the four-lane tri_lanes, which
     * the sixteen-lane paths would otherwise make for nothing. */
    o->z0 = _mm512_set1_pd(t->z0);
    o->dz1 = _mm512_set1_pd(t->dz1);
    o->dz2 = _mm512_set1_pd(t->dz2);
    for (int i = 0; i < 3; i++) {
        o->w[i] = _mm512_set1_ps(t->w[i]);
    }
    uint32_t fixed = 0;
    o->varying = 0;
    for (int ch = 0; ch < 4 && shading != SR_SHADING_PHONG; ch++) {
        if (shading == SR_SHADING_FLAT) {
            fixed |= (uint32_t)sr__unorm8(sr__tri_flat(t)[ch]) << (8 * ch);
            continue;
        }
        int n = t->ninterp;
        float c0 = t->vary[SR_VARY_COLOR + ch], c1 = t->vary[n + SR_VARY_COLOR + ch];
        float c2 = t->vary[2 * n + SR_VARY_COLOR + ch];
        if (c1 == 0.0f && c2 == 0.0f) {
            fixed |= (uint32_t)sr__unorm8(c0) << (8 * ch);
        } else {
            o->varying |= 1u << ch;
            o->c0[ch] = _mm512_set1_ps(c0);
            o->c1[ch] = _mm512_set1_ps(c1);
            o->c2[ch] = _mm512_set1_ps(c2);
        }
    }
    o->fixed = _mm512_set1_epi32((int)fixed);
}

/* sr__bary on sixteen lanes: the weights l1, l2 of vertices 1 and 2,
 * from the edge values as floats (f_i = (float)e_i, one rounding). */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(w16_bary_f)(const SR_SIMD_FN(w16_lanes) *k, __m512 f0,
                                                     __m512 f1, __m512 f2, __m512 *l1,
                                                     __m512 *l2)
{
    __m512 q0 = _mm512_mul_ps(f0, k->w[0]);
    __m512 q1 = _mm512_mul_ps(f1, k->w[1]);
    __m512 q2 = _mm512_mul_ps(f2, k->w[2]);
    __m512 s = _mm512_add_ps(_mm512_add_ps(q0, q1), q2);
    /* s != 0 ? 1/s : 0, with NaN taking the division as in C. */
    __mmask16 nz = _mm512_cmp_ps_mask(s, _mm512_setzero_ps(), _CMP_NEQ_UQ);
    __m512 inv = _mm512_maskz_div_ps(nz, _mm512_set1_ps(1.0f), s);
    *l1 = _mm512_mul_ps(q1, inv);
    *l2 = _mm512_mul_ps(q2, inv);
}

/* The same from edge values in double halves. */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(w16_bary)(const SR_SIMD_FN(w16_lanes) *k,
                                                   const __m512d e0[2], const __m512d e1[2],
                                                   const __m512d e2[2], __m512 *l1, __m512 *l2)
{
    SR_SIMD_FN(w16_bary_f)(k, SR_SIMD_FN(w16_cvt)(e0[0], e0[1]), SR_SIMD_FN(w16_cvt)(e1[0], e1[1]),
                           SR_SIMD_FN(w16_cvt)(e2[0], e2[1]), l1, l2);
}

/* A stamp of sixteen pixels: 8 x 2 (lanes 0-7 row py, 8-15 row py + 1),
 * 4 x 4 for tiny triangles (lanes 4r .. 4r + 3 row py + r), or 16 x 1
 * for a box the triangle covers whole (lanes 0-15 row py). */
typedef enum sr_stamp { SR_STAMP_8X2, SR_STAMP_4X4, SR_STAMP_16X1 } sr_stamp;

/* The stamp's elements of a buffer (width `pitch`, `size`-byte elements:
 * rows_avx512.h) at `base` = pixel (gx, py), which is always inside the
 * buffer; a row without an enabled lane is never addressed (it uses row
 * 0's address and loads or stores nothing there). */
SR_SIMD_TARGET SR_INLINE __m512i SR_SIMD_FN(stamp_load)(const void *buf, int size, size_t base,
                                                        size_t pitch, __mmask16 m, sr_stamp shape)
{
    if (shape == SR_STAMP_16X1) {
        return sr__row16_load(buf, size, base, m);
    }
    if (shape == SR_STAMP_8X2) {
        size_t b1 = m >> 8 ? base + pitch : base;
        return _mm512_inserti64x4(
            _mm512_castsi256_si512(sr__row8_load(buf, size, base, (__mmask8)m)),
            sr__row8_load(buf, size, b1, (__mmask8)(m >> 8)), 1);
    }
    /* Row r's lanes.  A row without lanes loads nothing, from row 0's
     * address (a row below the framebuffer's is never formed); chosen by
     * arithmetic, not a branch: a tiny triangle's rows vary at random,
     * and a branch per row mispredicted.  The insert positions must be
     * literal constants. */
    __m128i row[4];
    for (int r = 0; r < 4; r++) {
        __mmask8 mr = (__mmask8)((m >> (4 * r)) & 0xf);
        size_t at = base + ((size_t)r * pitch & -(size_t)(mr != 0));
        row[r] = sr__row4_load(buf, size, at, mr);
    }
    __m512i v = _mm512_castsi128_si512(row[0]);
    v = _mm512_inserti32x4(v, row[1], 1);
    v = _mm512_inserti32x4(v, row[2], 2);
    return _mm512_inserti32x4(v, row[3], 3);
}

SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(stamp_store)(void *buf, int size, size_t base,
                                                      size_t pitch, __mmask16 m, __m512i v,
                                                      sr_stamp shape)
{
    if (shape == SR_STAMP_16X1) {
        sr__row16_store(buf, size, base, m, v);
        return;
    }
    if (shape == SR_STAMP_8X2) {
        sr__row8_store(buf, size, base, (__mmask8)m, _mm512_castsi512_si256(v));
        if (m >> 8) {
            sr__row8_store(buf, size, base + pitch, (__mmask8)(m >> 8),
                           _mm512_extracti64x4_epi64(v, 1));
        }
        return;
    }
    __m128i row[4] = { _mm512_castsi512_si128(v), _mm512_extracti32x4_epi32(v, 1),
                       _mm512_extracti32x4_epi32(v, 2), _mm512_extracti32x4_epi32(v, 3) };
    for (int r = 0; r < 4; r++) {
        __mmask8 mr = (__mmask8)((m >> (4 * r)) & 0xf);
        size_t at = base + ((size_t)r * pitch & -(size_t)(mr != 0)); /* as in stamp_load */
        sr__row4_store(buf, size, at, mr, row[r]);
    }
}

/* Sixteen 32-bit edge values as double halves (lanes 0-7, 8-15), exact. */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(w16_halves)(__m512i e, __m512d h[2])
{
    h[0] = _mm512_cvtepi32_pd(_mm512_castsi512_si256(e));
    h[1] = _mm512_cvtepi32_pd(_mm512_extracti64x4_epi64(e, 1));
}

/* A stamp's depths in buffer units, from the depth plane at edge values
 * e1, e2 (double halves: lanes 0-7, 8-15): clamped to the depth range
 * unless the triangle lies inside it (z_inside), rounded. */
SR_SIMD_TARGET SR_INLINE __m512i SR_SIMD_FN(w16_zq)(const sr_draw_state *ds, const sr_tri *t,
                                                    const __m512d e1[2], const __m512d e2[2],
                                                    const SR_SIMD_FN(w16_lanes) *k)
{
    __m256i q[2];
    for (int h = 0; h < 2; h++) {
        __m512d z = _mm512_add_pd(
            _mm512_add_pd(k->z0, _mm512_mul_pd(e1[h], k->dz1)), _mm512_mul_pd(e2[h], k->dz2));
        if (!t->z_inside) {
            __m512d zmin = _mm512_set1_pd(ds->zq_min), zmax = _mm512_set1_pd(ds->zq_max);
            z = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(z, zmin, _CMP_GE_OQ), zmin, z);
            z = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(z, zmax, _CMP_LE_OQ), zmax, z);
        }
        q[h] = _mm512_cvttpd_epi32(_mm512_add_pd(z, _mm512_set1_pd(0.5)));
    }
    return _mm512_inserti64x4(_mm512_castsi256_si512(q[0]), q[1], 1);
}

/* The depth test of a stamp's lanes m (depth written where it passes),
 * the depth plane at edge values e1, e2 (double halves: lanes 0-7, 8-15):
 * the lanes still to be shaded, 0 for none.  Rows without an enabled
 * lane are never addressed (stamp_load). */
SR_SIMD_TARGET SR_INLINE __mmask16 SR_SIMD_FN(w16_depth)(const sr_draw_state *ds, const sr_tri *t,
                                                         size_t idx, __mmask16 m,
                                                         const __m512d e1[2], const __m512d e2[2],
                                                         const SR_SIMD_FN(w16_lanes) *k,
                                                         sr_depth_mode dmode, sr_stamp shape)
{
    if (dmode != SR_DEPTH_MODE_LESS) {
        return m;
    }
    sr_framebuffer *fb = ds->fb;
    size_t pitch = (size_t)fb->width;
    __m512i qz = SR_SIMD_FN(w16_zq)(ds, t, e1, e2, k);
    __m512i old = SR_SIMD_FN(stamp_load)(fb->depth, sr__depth_size(fb), idx, pitch, m, shape);
    m = _mm512_mask_cmplt_epi32_mask(m, qz, old);
    if (m) {
        SR_SIMD_FN(stamp_store)(fb->depth, sr__depth_size(fb), idx, pitch, m, qz, shape);
    }
    return m;
}

/* Coverage and the depth test of a stamp whose edge values are in double
 * halves (e*[h]: lanes 8h .. 8h + 7): the lanes still to be shaded, 0
 * for none.  `valid` masks the lanes inside the span being drawn: no
 * other lane's memory is read or written, so a span may start anywhere
 * and run past its tile or the framebuffer (a lane-masked load or store
 * touches only its enabled lanes).  Without a row py + 1, its lanes are
 * off. */
SR_SIMD_TARGET SR_INLINE __mmask16 SR_SIMD_FN(w16_test)(const sr_draw_state *ds, const sr_tri *t,
                                                        size_t idx, const __m512d e0[2],
                                                        const __m512d e1[2], const __m512d e2[2],
                                                        __mmask16 valid, bool inside,
                                                        const __m512d nb[3],
                                                        const SR_SIMD_FN(w16_lanes) *k,
                                                        sr_depth_mode dmode, sr_stamp shape)
{
    __mmask16 m = valid;
    if (!inside) {
        /* Covered iff e >= -bias, as in quad(). */
        __mmask8 r[2];
        for (int h = 0; h < 2; h++) {
            r[h] = _mm512_cmp_pd_mask(e0[h], nb[0], _CMP_GE_OQ) &
                   _mm512_cmp_pd_mask(e1[h], nb[1], _CMP_GE_OQ) &
                   _mm512_cmp_pd_mask(e2[h], nb[2], _CMP_GE_OQ);
        }
        m &= (__mmask16)(r[0] | r[1] << 8);
        if (!m) {
            return 0;
        }
    }
    return SR_SIMD_FN(w16_depth)(ds, t, idx, m, e1, e2, k, dmode, shape);
}

/* PHONG on sixteen lanes, as quad() does it on four: sr__bary's weights
 * l1, l2 give the ten varyings (v0 + l1 d1 + l2 d2), the normal is
 * renormalized (and turned for a back face lit on both sides), and
 * sr__light lights it (light16, the lane body of light_lanes.h);
 * sr__unorm8 packs the result. */
SR_SIMD_TARGET SR_INLINE __m512i SR_SIMD_FN(w16_phong)(const sr_draw_state *ds, const sr_tri *t,
                                                       __m512 l1, __m512 l2)
{
    int n = t->ninterp;
    v16f a = (v16f)l1, b = (v16f)l2;
    v16f vv[10];
    for (int j = 0; j < 10; j++) {
        vv[j] = t->vary[j] + a * t->vary[n + j] + b * t->vary[2 * n + j];
    }
    const v16f zero = { 0 };
    const v16f *vn = &vv[SR_VARY_PHONG_NORMAL];
    v16f len = v16_sqrt(vn[0] * vn[0] + vn[1] * vn[1] + vn[2] * vn[2]);
    v16f sc = v16_sel(len > zero, 1.0f / len, zero);
    if (ds->two_sided && !t->front) {
        sc = -sc;
    }
    v16f nn[3] = { vn[0] * sc, vn[1] * sc, vn[2] * sc };
    v16f c[4];
    light16(ds, nn, &vv[SR_VARY_PHONG_EYE], &vv[SR_VARY_PHONG_COLOR], c);
    __m512i rgba = _mm512_setzero_si512();
    for (int ch = 0; ch < 4; ch++) {
        rgba = _mm512_or_si512(rgba, _mm512_sll_epi32(SR_SIMD_FN(w16_unorm8)((__m512)c[ch]),
                                                      _mm_cvtsi32_si128(8 * ch)));
    }
    return rgba;
}

/* A stamp's colors, packed r,g,b,a per lane, with the weights l1, l2 of
 * vertices 1 and 2 (w16_bary). */
SR_SIMD_TARGET SR_INLINE __m512i SR_SIMD_FN(w16_color)(const sr_draw_state *ds, const sr_tri *t,
                                                       __m512 l1, __m512 l2,
                                                       const SR_SIMD_FN(w16_lanes) *k,
                                                       sr_shading shading)
{
    __m512i rgba = k->fixed;
    if (shading == SR_SHADING_PHONG) {
        rgba = SR_SIMD_FN(w16_phong)(ds, t, l1, l2);
    } else if (k->varying) {
        __m512i var = _mm512_setzero_si512();
        for (int ch = 0; ch < 4; ch++) {
            if (k->varying >> ch & 1) {
                __m512 c = _mm512_add_ps(_mm512_add_ps(k->c0[ch], _mm512_mul_ps(l1, k->c1[ch])),
                                         _mm512_mul_ps(l2, k->c2[ch]));
                var = _mm512_or_si512(var, _mm512_sll_epi32(SR_SIMD_FN(w16_unorm8)(c),
                                                             _mm_cvtsi32_si128(8 * ch)));
            }
        }
        rgba = var;
        if (k->varying != 0xf) {
            /* Where l1 or l2 is infinite or NaN a constant channel is NaN
             * too, which packs to 0: those lanes get no fixed byte. */
            __mmask16 bad = _mm512_fpclass_ps_mask(l1, 0x99) | _mm512_fpclass_ps_mask(l2, 0x99);
            rgba = _mm512_mask_or_epi32(var, (__mmask16)~bad, var, k->fixed);
        }
    }
    return rgba;
}

/* Shade and store the lanes m of a stamp at idx (w16_color). */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(w16_shade)(const sr_draw_state *ds, const sr_tri *t,
                                                    size_t idx, __mmask16 m, __m512 l1, __m512 l2,
                                                    const SR_SIMD_FN(w16_lanes) *k,
                                                    sr_frag_stats *st, sr_shading shading,
                                                    sr_stamp shape)
{
    sr_framebuffer *fb = ds->fb;
    __m512i rgba = SR_SIMD_FN(w16_color)(ds, t, l1, l2, k, shading);
    SR_SIMD_FN(stamp_store)(fb->color, 4, idx, (size_t)fb->width, m, rgba, shape);
    st->fragments += (uint64_t)__builtin_popcount((unsigned)m);
}

/* The sixteen pixels of a stamp at (gx, py); e*[h] holds lanes 8h .. 8h + 7
 * (w16_test says which lanes). */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(rows16)(const sr_draw_state *ds, const sr_tri *t, int gx,
                                                 int py, const __m512d e0[2], const __m512d e1[2],
                                                 const __m512d e2[2], __mmask16 valid,
                                                 bool inside, const __m512d nb[3],
                                                 const SR_SIMD_FN(w16_lanes) *k, sr_frag_stats *st,
                                                 sr_shading shading, sr_depth_mode dmode,
                                                 sr_stamp shape)
{
    size_t idx = (size_t)py * (size_t)ds->fb->width + (size_t)gx;
    __mmask16 m = SR_SIMD_FN(w16_test)(ds, t, idx, e0, e1, e2, valid, inside, nb, k, dmode, shape);
    if (!m) {
        return;
    }
    __m512 l1 = _mm512_setzero_ps(), l2 = _mm512_setzero_ps();
    if (k->varying || shading == SR_SHADING_PHONG) {
        SR_SIMD_FN(w16_bary)(k, e0, e1, e2, &l1, &l2);
    }
    SR_SIMD_FN(w16_shade)(ds, t, idx, m, l1, l2, k, st, shading, shape);
}

/* The same with the edge values in sixteen 32-bit lanes, for a triangle
 * whose values inside the box being drawn all fit (sr__rect_fits32):
 * one compare an edge instead of two, and one conversion to float
 * instead of two and a merge.  Lanes outside `valid` may have wrapped;
 * they are never used.  The depth plane still takes doubles (exact). */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(rows16_n)(const sr_draw_state *ds, const sr_tri *t, int gx,
                                                   int py, const __m512i e[3], __mmask16 valid,
                                                   bool inside, const __m512i nb[3],
                                                   const SR_SIMD_FN(w16_lanes) *k,
                                                   sr_frag_stats *st, sr_shading shading,
                                                   sr_depth_mode dmode, sr_stamp shape)
{
    size_t idx = (size_t)py * (size_t)ds->fb->width + (size_t)gx;
    __mmask16 m = valid;
    if (!inside) {
        /* Covered iff e >= -bias, as in quad(). */
        m = _mm512_mask_cmpge_epi32_mask(m, e[0], nb[0]);
        m = _mm512_mask_cmpge_epi32_mask(m, e[1], nb[1]);
        m = _mm512_mask_cmpge_epi32_mask(m, e[2], nb[2]);
        if (!m) {
            return;
        }
    }
    if (dmode == SR_DEPTH_MODE_LESS) {
        __m512d e1[2], e2[2];
        SR_SIMD_FN(w16_halves)(e[1], e1);
        SR_SIMD_FN(w16_halves)(e[2], e2);
        m = SR_SIMD_FN(w16_depth)(ds, t, idx, m, e1, e2, k, dmode, shape);
        if (!m) {
            return;
        }
    }
    __m512 l1 = _mm512_setzero_ps(), l2 = _mm512_setzero_ps();
    if (k->varying || shading == SR_SHADING_PHONG) {
        SR_SIMD_FN(w16_bary_f)(k, _mm512_cvtepi32_ps(e[0]), _mm512_cvtepi32_ps(e[1]),
                               _mm512_cvtepi32_ps(e[2]), &l1, &l2);
    }
    SR_SIMD_FN(w16_shade)(ds, t, idx, m, l1, l2, k, st, shading, shape);
}

#include "raster/simd_tex.h"
#include "raster/simd_tiny.h"

/* An 8 x 2 stamp's exact edge values: r[i] at the top row's first pixel,
 * the next row sy[i] further, lanes lx8[i] apart. */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(w16_edges)(const double r[3], const int64_t sy[3],
                                                    const __m512d lx8[3], __m512d e0[2],
                                                    __m512d e1[2], __m512d e2[2])
{
    __m512d *e[3] = { e0, e1, e2 };
    for (int i = 0; i < 3; i++) {
        e[i][0] = _mm512_add_pd(_mm512_set1_pd(r[i]), lx8[i]);
        e[i][1] = _mm512_add_pd(_mm512_set1_pd(r[i] + (double)sy[i]), lx8[i]);
    }
}

/* A stamp, plain or textured (SR_WALK_TEXTURED, a constant at each
 * instance), with its edge values in 32-bit lanes (n, nb32) under
 * SR_WALK_NARROW, else in double halves (e0 .. e2, nb). */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(stamp16)(const sr_draw_state *ds, const sr_tri *t, int gx,
                                                  int py, const __m512d e0[2], const __m512d e1[2],
                                                  const __m512d e2[2], const __m512i n[3],
                                                  __mmask16 valid, bool inside,
                                                  const __m512d nb[3], const __m512i nb32[3],
                                                  const SR_SIMD_FN(w16_lanes) *k,
                                                  sr_frag_stats *st, sr_shading shading,
                                                  sr_depth_mode dmode, sr_stamp shape,
                                                  sr_walk_flags walk)
{
    bool tex = walk & SR_WALK_TEXTURED, narrow = walk & SR_WALK_NARROW;
    if (narrow) {
        SR_SIMD_FN(rows16_n)(ds, t, gx, py, n, valid, inside, nb32, k, st, shading, dmode, shape);
    } else if (tex) {
        SR_SIMD_FN(rows16_tex)(ds, t, gx, py, e0, e1, e2, valid, inside, nb, k, st, dmode, shape);
    } else {
        SR_SIMD_FN(rows16)(ds, t, gx, py, e0, e1, e2, valid, inside, nb, k, st, shading, dmode,
                           shape);
    }
}

/* A stamp's 32-bit edge values: the value r[i] at its corner pixel plus
 * each lane's offset, modulo 2^32 (so a corner outside the box may wrap;
 * the lanes inside it come out exact, sr__rect_fits32). */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(n16_edges)(const uint32_t r[3], const __m512i off[3],
                                                   __m512i n[3])
{
    for (int i = 0; i < 3; i++) {
        n[i] = _mm512_add_epi32(_mm512_set1_epi32((int32_t)r[i]), off[i]);
    }
}

/* Each lane's offset from the stamp's corner pixel in 32-bit lanes, for
 * a stamp `cols` pixels wide (16, 8 or 4; lane l is pixel (l % cols,
 * l / cols)): x a + y b per edge, modulo 2^32. */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(n16_offsets)(const int64_t sx[3], const int64_t sy[3],
                                                     int cols, __m512i off[3])
{
    const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    int shift = cols == 16 ? 4 : cols == 8 ? 3 : 2;
    __m512i x = _mm512_and_si512(lane, _mm512_set1_epi32(cols - 1));
    __m512i y = _mm512_srli_epi32(lane, (unsigned)shift);
    for (int i = 0; i < 3; i++) {
        __m512i a = _mm512_set1_epi32((int32_t)(uint32_t)sx[i]);
        __m512i b = _mm512_set1_epi32((int32_t)(uint32_t)sy[i]);
        off[i] = _mm512_add_epi32(_mm512_mullo_epi32(x, a), _mm512_mullo_epi32(y, b));
    }
}

/* The sixteen-lane walks' per-triangle lanes: lane offsets 0..7 pixel
 * steps in double (exact: small integers), and the coverage bounds -bias
 * in double and in 32-bit lanes. */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(w16_edge_lanes)(const sr_edges *ed, const int64_t sx[3],
                                                        __m512d lx8[3], __m512d nb8[3],
                                                        __m512i nb32[3])
{
    const __m512d steps = _mm512_setr_pd(0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0);
    for (int i = 0; i < 3; i++) {
        lx8[i] = _mm512_mul_pd(_mm512_set1_pd((double)sx[i]), steps);
        nb8[i] = _mm512_set1_pd(-(double)ed->bias[i]);
        nb32[i] = _mm512_set1_epi32((int32_t)-ed->bias[i]);
    }
}

/* The three (unbiased) edge values at pixel (x, y)'s centre, in double
 * (exact) and modulo 2^32. */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(edges_at)(const sr_edges *ed, int x, int y, double r[3],
                                                  uint32_t r32[3])
{
    int64_t xc = sr__centre_q8(x), yc = sr__centre_q8(y);
    for (int i = 0; i < 3; i++) {
        int64_t v = sr__edge_at(ed, i, xc, yc);
        r[i] = (double)v;
        r32[i] = (uint32_t)v;
    }
}
