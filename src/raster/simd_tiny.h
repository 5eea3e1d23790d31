/* simd_tiny.h - tiny triangles in 4 x 4 stamps, set up in 32-bit lanes
 * straight from the record (raster stage, tile worker threads).  Included
 * by simd_kernel.h in its AVX-512 instance only, after simd_wide.h, whose
 * stamp arithmetic it shares.
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

/* Edge i's value at q8 point (X, Y) modulo 2^32: a_i (X - X_i) + b_i (Y - Y_i)
 * with (X_i, Y_i) a vertex on edge i - vertex 0 for edges 1 and 2, vertex 1
 * = vertex 0 + (b_2, -a_2) for edge 0 (as sr__tri_c). */
SR_SIMD_TARGET SR_INLINE uint32_t SR_SIMD_FN(tiny_edge)(const sr_tri *t, int i, uint32_t X,
                                                       uint32_t Y)
{
    uint32_t xi = (uint32_t)t->x0_q8, yi = (uint32_t)t->y0_q8;
    if (i == 0) {
        xi += (uint32_t)t->b[2];
        yi -= (uint32_t)t->a[2];
    }
    return (uint32_t)t->a[i] * (X - xi) + (uint32_t)t->b[i] * (Y - yi);
}

/* A stamp's rows of a buffer: row r starts at at[r] (4 x 4: four rows
 * of four lanes; 8 x 2: two of eight).  A row the box lacks, whose lanes
 * are off, gets the address of its last row, so no address below the
 * framebuffer is formed. */
SR_SIMD_TARGET SR_INLINE __m512i SR_SIMD_FN(tiny_load)(const uint32_t *buf, const size_t at[4],
                                                      __mmask16 m, sr_stamp shape)
{
    if (shape == SR_STAMP_8X2) {
        return _mm512_inserti64x4(
            _mm512_castsi256_si512(_mm256_maskz_loadu_epi32((__mmask8)m, &buf[at[0]])),
            _mm256_maskz_loadu_epi32((__mmask8)(m >> 8), &buf[at[1]]), 1);
    }
    __m512i v = _mm512_castsi128_si512(_mm_maskz_loadu_epi32((__mmask8)m, &buf[at[0]]));
    v = _mm512_inserti32x4(v, _mm_maskz_loadu_epi32((__mmask8)(m >> 4), &buf[at[1]]), 1);
    v = _mm512_inserti32x4(v, _mm_maskz_loadu_epi32((__mmask8)(m >> 8), &buf[at[2]]), 2);
    return _mm512_inserti32x4(v, _mm_maskz_loadu_epi32((__mmask8)(m >> 12), &buf[at[3]]), 3);
}

SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(tiny_store)(uint32_t *buf, const size_t at[4],
                                                    __mmask16 m, __m512i v, sr_stamp shape)
{
    if (shape == SR_STAMP_8X2) {
        _mm256_mask_storeu_epi32(&buf[at[0]], (__mmask8)m, _mm512_castsi512_si256(v));
        _mm256_mask_storeu_epi32(&buf[at[1]], (__mmask8)(m >> 8), _mm512_extracti64x4_epi64(v, 1));
        return;
    }
    _mm_mask_storeu_epi32(&buf[at[0]], (__mmask8)m, _mm512_castsi512_si128(v));
    _mm_mask_storeu_epi32(&buf[at[1]], (__mmask8)(m >> 4), _mm512_extracti32x4_epi32(v, 1));
    _mm_mask_storeu_epi32(&buf[at[2]], (__mmask8)(m >> 8), _mm512_extracti32x4_epi32(v, 2));
    _mm_mask_storeu_epi32(&buf[at[3]], (__mmask8)(m >> 12), _mm512_extracti32x4_epi32(v, 3));
}

/* The box [rx0, rx1) x [ry0, ry1) of a record with fits32, in stamps from
 * its top-left pixel: 4 x 4 for a box at most 4 pixels wide (lane 4 r + c
 * is pixel (rx0 + c, py + r)), else 8 x 2 for one at most 8 wide (lane
 * 8 r + c).  Its own constants rather than w16_lanes: every color channel
 * is interpolated (alpha too: v0 + l1 0 + l2 0 is what the scalar stage
 * computes), which costs a stamp less than w16_make's test of each
 * channel costs a triangle. */
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
    uint32_t X = (uint32_t)sr__centre_q8(rx0), Y = (uint32_t)sr__centre_q8(ry0);
    uint32_t corner[3];
    __m512i off[3], nb[3];
    for (int i = 0; i < 3; i++) {
        corner[i] = SR_SIMD_FN(tiny_edge)(t, i, X, Y);
        /* Lane (c, r) lies c pixel steps a and r steps b from the corner. */
        __m512i a = _mm512_set1_epi32((int32_t)((uint32_t)t->a[i] * SR_SUBPIXEL_ONE));
        __m512i b = _mm512_set1_epi32((int32_t)((uint32_t)t->b[i] * SR_SUBPIXEL_ONE));
        off[i] = _mm512_add_epi32(_mm512_mullo_epi32(col, a), _mm512_mullo_epi32(row, b));
        /* Covered iff e >= -bias (1 off a top or left edge, else 0). */
        nb[i] = _mm512_set1_epi32(-sr__tri_bias(t, i));
    }
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
        __m512i e[3];
        __mmask16 m = (__mmask16)valid;
        for (int i = 0; i < 3; i++) {
            e[i] = _mm512_add_epi32(_mm512_set1_epi32((int32_t)corner[i]), off[i]);
            m = _mm512_mask_cmpge_epi32_mask(m, e[i], nb[i]);
            corner[i] += (uint32_t)rows * (uint32_t)t->b[i] * SR_SUBPIXEL_ONE;
        }
        if (!m) {
            continue;
        }
        if (dmode == SR_DEPTH_MODE_LESS) {
            __m512d e1[2], e2[2];
            SR_SIMD_FN(w16_halves)(e[1], e1);
            SR_SIMD_FN(w16_halves)(e[2], e2);
            __m512i qz = SR_SIMD_FN(w16_zq)(ds, t, e1, e2, &k);
            __m512i old = SR_SIMD_FN(tiny_load)(fb->depth, at, m, shape);
            m = _mm512_mask_cmplt_epi32_mask(m, qz, old);
            if (!m) {
                continue;
            }
            SR_SIMD_FN(tiny_store)(fb->depth, at, m, qz, shape);
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
                    __m512 c = _mm512_add_ps(
                        _mm512_add_ps(_mm512_set1_ps(v[0]), _mm512_mul_ps(l1, _mm512_set1_ps(v[n]))),
                        _mm512_mul_ps(l2, _mm512_set1_ps(v[2 * n])));
                    rgba = _mm512_or_si512(rgba, _mm512_slli_epi32(SR_SIMD_FN(w16_unorm8)(c),
                                                                    (unsigned)(8 * ch)));
                }
            } else {
                rgba = SR_SIMD_FN(w16_phong)(ds, t, l1, l2);
            }
        }
        SR_SIMD_FN(tiny_store)(fb->color, at, m, rgba, shape);
        st->fragments += (uint64_t)__builtin_popcount((unsigned)m);
    }
}
