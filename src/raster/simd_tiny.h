/* simd_tiny.h - tiny triangles in 4 x 4 stamps, set up in 32-bit lanes
 * straight from the record (raster stage, tile worker threads).  Included
 * by simd_wide16.h (simd_kernel.h's AVX-512 instance only), whose stamp
 * arithmetic it shares.
 *
 * A triangle of a few pixels (the bench's `small`, a distant mesh) draws
 * one or two stamps, so what it costs is the set-up around them: the
 * 64-bit edge functions (sr_edges), the lane constants of every walk
 * raster_as might take, and per row of each buffer access an address
 * chosen by that access's own mask - about 590 instructions for a single
 * stamp.  Here the edge values come from the record's a, b and vertex 0
 * in 32-bit arithmetic modulo 2^32, and the rows' addresses are chosen
 * once per stamp from the box alone.
 *
 * Exactness: for a record with fits32, every edge value at a pixel centre
 * inside the triangle's bounding box fits in 32 bits; the arithmetic
 * modulo 2^32 gives that value wherever it fits, so every lane inside the
 * box holds the exact edge value (lanes outside it may wrap and are never
 * enabled).  From there the stamp repeats rows16_n's operations. */

/* The three edges' a, b, top-left bounds and values at q8 point (X, Y)
 * in lanes 0-2 (lane 3 is not used).  Edge i's value modulo 2^32 is
 * a_i (X - X_i) + b_i (Y - Y_i) with (X_i, Y_i) a vertex on edge i -
 * vertex 0 for edges 1 and 2, vertex 1 = vertex 0 + (b_2, -a_2) for edge 0
 * (as sr__tri_c) - and a pixel is covered iff e_i >= nb_i = -bias_i: 0 on
 * a top or left edge, else 1 (sr__tri_bias: a top or left edge has
 * a > 0, or a = 0 and b > 0). */
typedef struct SR_SIMD_FN(tiny_edges) {
    __m128i a, b, nb, at;
} SR_SIMD_FN(tiny_edges);

SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(tiny_setup)(const sr_tri *t, uint32_t X, uint32_t Y,
                                                    SR_SIMD_FN(tiny_edges) *o)
{
    _Static_assert(offsetof(sr_tri, b) == offsetof(sr_tri, a) + 12 &&
                       offsetof(sr_tri, x0_q8) == offsetof(sr_tri, b) + 12,
                   "a, b and vertex 0 lie one after the other: 16-byte loads stay inside");
    __m128i a = _mm_loadu_si128((const __m128i *)t->a);   /* a0 a1 a2 b0 */
    __m128i b = _mm_loadu_si128((const __m128i *)t->b);   /* b0 b1 b2 x0 */
    __m128i zero = _mm_setzero_si128();
    __m128i flat_b = _mm_and_si128(_mm_cmpeq_epi32(a, zero), _mm_cmpgt_epi32(b, zero));
    __m128i top_left = _mm_or_si128(_mm_cmpgt_epi32(a, zero), flat_b);
    o->nb = _mm_add_epi32(_mm_set1_epi32(1), top_left);   /* the mask is -1 where top-left */
    uint32_t dx = X - (uint32_t)t->x0_q8, dy = Y - (uint32_t)t->y0_q8;
    __m128i px = _mm_setr_epi32((int32_t)(dx - (uint32_t)t->b[2]), (int32_t)dx, (int32_t)dx, 0);
    __m128i py = _mm_setr_epi32((int32_t)(dy + (uint32_t)t->a[2]), (int32_t)dy, (int32_t)dy, 0);
    o->at = _mm_add_epi32(_mm_mullo_epi32(a, px), _mm_mullo_epi32(b, py));
    o->a = a;
    o->b = b;
}

/* Lane i of v in all sixteen lanes. */
#define SR_TINY_LANE(v, i) _mm512_broadcastd_epi32(_mm_shuffle_epi32((v), (i) * 0x55))

/* A stamp's rows of a buffer of `size`-byte elements (rows_avx512.h):
 * row r starts at at[r] (4 x 4: four rows of four lanes; 8 x 2: two of
 * eight).  A row the box lacks, whose lanes are off, gets the address of
 * its last row, so no address below the framebuffer is formed. */
SR_SIMD_TARGET SR_INLINE __m512i SR_SIMD_FN(tiny_load)(const void *buf, int size,
                                                      const size_t at[4], __mmask16 m,
                                                      sr_stamp shape)
{
    if (shape == SR_STAMP_8X2) {
        return _mm512_inserti64x4(
            _mm512_castsi256_si512(sr__row8_load(buf, size, at[0], (__mmask8)m)),
            sr__row8_load(buf, size, at[1], (__mmask8)(m >> 8)), 1);
    }
    __m512i v = _mm512_castsi128_si512(sr__row4_load(buf, size, at[0], (__mmask8)m));
    v = _mm512_inserti32x4(v, sr__row4_load(buf, size, at[1], (__mmask8)(m >> 4)), 1);
    v = _mm512_inserti32x4(v, sr__row4_load(buf, size, at[2], (__mmask8)(m >> 8)), 2);
    return _mm512_inserti32x4(v, sr__row4_load(buf, size, at[3], (__mmask8)(m >> 12)), 3);
}

SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(tiny_store)(void *buf, int size, const size_t at[4],
                                                    __mmask16 m, __m512i v, sr_stamp shape)
{
    if (shape == SR_STAMP_8X2) {
        sr__row8_store(buf, size, at[0], (__mmask8)m, _mm512_castsi512_si256(v));
        sr__row8_store(buf, size, at[1], (__mmask8)(m >> 8), _mm512_extracti64x4_epi64(v, 1));
        return;
    }
    sr__row4_store(buf, size, at[0], (__mmask8)m, _mm512_castsi512_si128(v));
    sr__row4_store(buf, size, at[1], (__mmask8)(m >> 4), _mm512_extracti32x4_epi32(v, 1));
    sr__row4_store(buf, size, at[2], (__mmask8)(m >> 8), _mm512_extracti32x4_epi32(v, 2));
    sr__row4_store(buf, size, at[3], (__mmask8)(m >> 12), _mm512_extracti32x4_epi32(v, 3));
}

/* The box [rx0, rx1) x [ry0, ry1) of a record with fits32, in stamps from
 * its top-left pixel: 4 x 4 for a box at most 4 pixels wide (lane 4 r + c
 * is pixel (rx0 + c, py + r)), else 8 x 2 for one at most 8 wide (lane
 * 8 r + c).  Every color channel is interpolated (alpha too: v0 + l1 0 +
 * l2 0 is what the scalar stage computes), which costs a stamp less than
 * w16_make's test of each channel costs a triangle.  Its own loop rather
 * than w16_make and w16_color with every channel varying: with those, GCC
 * keeps the twelve color constants in registers and spills others for
 * them (the compiled tiny function 516 -> 597 instructions); here it
 * broadcasts each from the record where it is used (small 1.017, bunny
 * 1.012 with the shared ones, six alternating rounds). */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(raster_tiny)(const sr_draw_state *ds, const sr_tri *t,
                                                     int rx0, int ry0, int rx1, int ry1,
                                                     sr_frag_stats *st, sr_shading shading,
                                                     sr_depth_mode dmode, sr_stamp shape)
{
    SR_SIMD_FN(w16_lanes) k;
    k.z0 = _mm512_set1_pd(t->z0);
    k.dz1 = _mm512_set1_pd(t->dz1);
    k.dz2 = _mm512_set1_pd(t->dz2);
    for (int i = 0; i < 3; i++) {
        k.w[i] = _mm512_set1_ps(t->w[i]);
    }
    bool gouraud = shading != SR_SHADING_FLAT && shading != SR_SHADING_PHONG;
    __m512i flat = _mm512_setzero_si512();
    if (shading == SR_SHADING_FLAT) {
        uint32_t c = 0;
        for (int ch = 0; ch < 4; ch++) {
            c |= (uint32_t)sr__unorm8(sr__tri_flat(t)[ch]) << (8 * ch);
        }
        flat = _mm512_set1_epi32((int)c);
    }
    bool wide = shape == SR_STAMP_8X2;
    const int rows = wide ? 2 : 4;
    const __m512i col = wide ? _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 0, 1, 2, 3, 4, 5, 6, 7)
                             : _mm512_setr_epi32(0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3);
    const __m512i row = wide ? _mm512_setr_epi32(0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1)
                             : _mm512_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3);
    SR_SIMD_FN(tiny_edges) te;
    SR_SIMD_FN(tiny_setup)(t, (uint32_t)sr__centre_q8(rx0), (uint32_t)sr__centre_q8(ry0), &te);
    /* A pixel step is 256 q8 units: lane (c, r) lies 256 (c a + r b) from
     * the corner, and the next stamp rows 256 rows b below. */
    __m128i sa = _mm_slli_epi32(te.a, 8), sb = _mm_slli_epi32(te.b, 8);
    __m128i corner = te.at, down = _mm_mullo_epi32(sb, _mm_set1_epi32(rows));
    __m512i off[3], nb[3];
    off[0] = _mm512_add_epi32(_mm512_mullo_epi32(col, SR_TINY_LANE(sa, 0)),
                              _mm512_mullo_epi32(row, SR_TINY_LANE(sb, 0)));
    off[1] = _mm512_add_epi32(_mm512_mullo_epi32(col, SR_TINY_LANE(sa, 1)),
                              _mm512_mullo_epi32(row, SR_TINY_LANE(sb, 1)));
    off[2] = _mm512_add_epi32(_mm512_mullo_epi32(col, SR_TINY_LANE(sa, 2)),
                              _mm512_mullo_epi32(row, SR_TINY_LANE(sb, 2)));
    nb[0] = SR_TINY_LANE(te.nb, 0);
    nb[1] = SR_TINY_LANE(te.nb, 1);
    nb[2] = SR_TINY_LANE(te.nb, 2);
    sr_framebuffer *fb = ds->fb;
    size_t pitch = (size_t)fb->width;
    /* The box's columns in each row of a stamp. */
    unsigned cols = (1u << (rx1 - rx0)) - 1;
    unsigned cols_rows = wide ? cols * 0x101u : cols * 0x1111u;
    for (int py = ry0; py < ry1; py += rows) {
        int last = ry1 - py < rows ? ry1 - py - 1 : rows - 1;
        unsigned valid = cols_rows & (0xffffu >> (16 / rows * (rows - 1 - last)));
        size_t idx = (size_t)py * pitch + (size_t)rx0, at[4];
        for (int r = 0; r < rows; r++) {
            /* With min, not a branch: the boxes' heights vary at random. */
            at[r] = idx + (size_t)(r < last ? r : last) * pitch;
        }
        __m512i e[3] = { _mm512_add_epi32(SR_TINY_LANE(corner, 0), off[0]),
                         _mm512_add_epi32(SR_TINY_LANE(corner, 1), off[1]),
                         _mm512_add_epi32(SR_TINY_LANE(corner, 2), off[2]) };
        corner = _mm_add_epi32(corner, down);
        __mmask16 m = (__mmask16)valid;
        for (int i = 0; i < 3; i++) {
            m = _mm512_mask_cmpge_epi32_mask(m, e[i], nb[i]);
        }
        if (!m) {
            continue;
        }
        if (dmode == SR_DEPTH_MODE_LESS) {
            __m512d e1[2], e2[2];
            SR_SIMD_FN(w16_halves)(e[1], e1);
            SR_SIMD_FN(w16_halves)(e[2], e2);
            __m512i qz = SR_SIMD_FN(w16_zq)(ds, t, e1, e2, &k);
            __m512i old = SR_SIMD_FN(tiny_load)(fb->depth, sr__depth_size(fb), at, m, shape);
            m = _mm512_mask_cmplt_epi32_mask(m, qz, old);
            if (!m) {
                continue;
            }
            SR_SIMD_FN(tiny_store)(fb->depth, sr__depth_size(fb), at, m, qz, shape);
        }
        __m512i rgba = flat;
        if (shading != SR_SHADING_FLAT) {
            __m512 l1, l2;
            SR_SIMD_FN(w16_bary_f)(&k, _mm512_cvtepi32_ps(e[0]), _mm512_cvtepi32_ps(e[1]),
                                   _mm512_cvtepi32_ps(e[2]), &l1, &l2);
            if (gouraud) {
                /* w16_color's channels, all four. */
                int n = t->ninterp;
                for (int ch = 0; ch < 4; ch++) {
                    const float *v = &t->vary[SR_VARY_COLOR + ch];
                    __m512 c1 = _mm512_mul_ps(l1, _mm512_set1_ps(v[n]));
                    __m512 c = _mm512_add_ps(_mm512_add_ps(_mm512_set1_ps(v[0]), c1),
                                             _mm512_mul_ps(l2, _mm512_set1_ps(v[2 * n])));
                    rgba = _mm512_or_si512(rgba, _mm512_slli_epi32(SR_SIMD_FN(w16_unorm8)(c),
                                                                    (unsigned)(8 * ch)));
                }
            } else {
                rgba = SR_SIMD_FN(w16_phong)(ds, t, l1, l2);
            }
        }
        SR_SIMD_FN(tiny_store)(fb->color, 4, at, m, rgba, shape);
        st->fragments += (uint64_t)__builtin_popcount((unsigned)m);
    }
}
