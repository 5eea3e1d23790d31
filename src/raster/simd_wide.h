/* simd_wide.h - one row of an 8x8 block, eight pixels at a time (raster
 * stage, tile worker threads).  Included by simd_kernel.h in its AVX2
 * instance only: the half-space kernel's block walk hands it every row
 * of a block that spans the full eight pixels, which is nearly every row
 * of a large triangle.  Small triangles keep the four-wide groups, whose
 * narrower lanes waste less on a triangle's ragged edges.  The AVX-512
 * instance includes it too, for the helpers its sixteen-lane stamps
 * (simd_wide16.h) share.
 *
 * Exactness, as in quad(): edge values are integers held in double lanes;
 * each lane repeats the scalar fragment stage's operations in the same
 * order, one half of the row per 4-lane double vector where doubles are
 * needed (edges, depth) and all eight lanes at once in float. */

SR_SIMD_TARGET SR_INLINE __m256 SR_SIMD_FN(wide_f)(v4f lo)
{
    return _mm256_set_m128((__m128)lo, (__m128)lo);
}

/* Two halves' exact edge values, converted to float once (one rounding,
 * as the scalar (float)e). */
SR_SIMD_TARGET SR_INLINE __m256 SR_SIMD_FN(wide_cvt)(v4d lo, v4d hi)
{
    return _mm256_set_m128(_mm256_cvtpd_ps((__m256d)hi), _mm256_cvtpd_ps((__m256d)lo));
}

/* sr__unorm8 on eight pixels, packed r,g,b,a per pixel.  min(1, v) keeps
 * NaN, truncation sends NaN and negatives below zero, and the max with 0
 * takes them to 0: the scalar form and pack_rgba's saturating packs agree. */
SR_SIMD_TARGET SR_INLINE __m256i SR_SIMD_FN(wide_pack)(const __m256 c[4])
{
    const __m256 one = _mm256_set1_ps(1.0f), k255 = _mm256_set1_ps(255.0f);
    const __m256 half = _mm256_set1_ps(0.5f);
    __m256i q[4];
    for (int ch = 0; ch < 4; ch++) {
        __m256 v = _mm256_min_ps(one, c[ch]);
        q[ch] = _mm256_max_epi32(_mm256_cvttps_epi32(_mm256_add_ps(_mm256_mul_ps(v, k255), half)),
                                 _mm256_setzero_si256());
    }
    return _mm256_or_si256(_mm256_or_si256(q[0], _mm256_slli_epi32(q[1], 8)),
                           _mm256_or_si256(_mm256_slli_epi32(q[2], 16),
                                           _mm256_slli_epi32(q[3], 24)));
}

/* depth_lanes.h's sr__depth_less4 on eight samples from element idx:
 * the lanes of m (all ones or zero) whose q is below the stored value
 * write it; returns them.  D16's samples are zero-extended into the
 * lanes and narrowed back. */
SR_SIMD_TARGET SR_INLINE __m256i SR_SIMD_FN(depth_less8)(sr_framebuffer *fb, size_t idx,
                                                         __m256i q, __m256i m)
{
    if (fb->depth16) {
        __m128i *p = (__m128i *)((uint16_t *)fb->depth + idx);
        __m256i old = _mm256_cvtepu16_epi32(_mm_loadu_si128(p));
        m = _mm256_and_si256(m, _mm256_cmpgt_epi32(old, q));
        __m256i d = _mm256_blendv_epi8(old, q, m);
        /* Every lane is below 2^16: the unsigned saturation keeps it. */
        _mm_storeu_si128(p, _mm_packus_epi32(_mm256_castsi256_si128(d),
                                             _mm256_extracti128_si256(d, 1)));
        return m;
    }
    __m256i *p = (__m256i *)((uint32_t *)fb->depth + idx);
    __m256i old = _mm256_loadu_si256(p);
    m = _mm256_and_si256(m, _mm256_cmpgt_epi32(old, q));
    _mm256_storeu_si256(p, _mm256_blendv_epi8(old, q, m));
    return m;
}

/* Pixels gx .. gx+7 of row py; e*[0] holds lanes 0-3 and e*[1] lanes 4-7
 * (unbiased edge values).  `inside`: the block lies wholly inside the
 * triangle, so no lane needs its coverage test.  Unlit/Gouraud color or
 * flat shading; depth off or LESS on a D16/D24 buffer. */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(row8)(const sr_draw_state *ds, const sr_tri *t, int gx,
                                               int py, const v4d e0[2], const v4d e1[2],
                                               const v4d e2[2], bool inside, const v4d nbias[3],
                                               const SR_SIMD_FN(tri_lanes) *k, sr_frag_stats *st,
                                               sr_shading shading, sr_depth_mode dmode)
{
    const __m256i lane_bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    int bits = 255;
    if (!inside) {
        /* Covered iff e >= -bias, as in quad(). */
        v4l lo = (e0[0] >= nbias[0]) & (e1[0] >= nbias[1]) & (e2[0] >= nbias[2]);
        v4l hi = (e0[1] >= nbias[0]) & (e1[1] >= nbias[1]) & (e2[1] >= nbias[2]);
        bits = _mm256_movemask_pd((__m256d)lo) | _mm256_movemask_pd((__m256d)hi) << 4;
        if (!bits) {
            return;
        }
    }
    sr_framebuffer *fb = ds->fb;
    size_t idx = (size_t)py * (size_t)fb->width + (size_t)gx;
    __m256i m = _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(bits), lane_bit), lane_bit);

    if (dmode == SR_DEPTH_MODE_LESS) {
        __m128i qh[2];
        for (int h = 0; h < 2; h++) {
            v4d z = k->z0 + e1[h] * k->dz1 + e2[h] * k->dz2;
            if (!t->z_inside) {
                v4d zmin = { ds->zq_min, ds->zq_min, ds->zq_min, ds->zq_min };
                v4d zmax = { ds->zq_max, ds->zq_max, ds->zq_max, ds->zq_max };
                z = SR_SIMD_FN(sel_d)(z >= zmin, z, zmin);
                z = SR_SIMD_FN(sel_d)(z <= zmax, z, zmax);
            }
            qh[h] = _mm256_cvttpd_epi32((__m256d)(z + 0.5)); /* < 2^24: fits int32 */
        }
        __m256i q = _mm256_set_m128i(qh[1], qh[0]);
        m = SR_SIMD_FN(depth_less8)(fb, idx, q, m);
        bits = _mm256_movemask_ps(_mm256_castsi256_ps(m));
        if (!bits) {
            return;
        }
    }

    __m256i rgba;
    if (shading == SR_SHADING_FLAT) {
        uint32_t c = 0;
        for (int ch = 0; ch < 4; ch++) {
            c |= (uint32_t)sr__unorm8(sr__tri_flat(t)[ch]) << (8 * ch);
        }
        rgba = _mm256_set1_epi32((int)c);
    } else {
        /* sr__bary and sr__interp on eight lanes. */
        __m256 q0 = _mm256_mul_ps(SR_SIMD_FN(wide_cvt)(e0[0], e0[1]), SR_SIMD_FN(wide_f)(k->w[0]));
        __m256 q1 = _mm256_mul_ps(SR_SIMD_FN(wide_cvt)(e1[0], e1[1]), SR_SIMD_FN(wide_f)(k->w[1]));
        __m256 q2 = _mm256_mul_ps(SR_SIMD_FN(wide_cvt)(e2[0], e2[1]), SR_SIMD_FN(wide_f)(k->w[2]));
        __m256 s = _mm256_add_ps(_mm256_add_ps(q0, q1), q2);
        /* s != 0 ? 1/s : 0, with NaN taking the division as in C. */
        __m256 nz = _mm256_cmp_ps(s, _mm256_setzero_ps(), _CMP_NEQ_UQ);
        __m256 inv = _mm256_and_ps(nz, _mm256_div_ps(_mm256_set1_ps(1.0f), s));
        __m256 l1 = _mm256_mul_ps(q1, inv), l2 = _mm256_mul_ps(q2, inv);
        __m256 c[4];
        for (int ch = 0; ch < 4; ch++) {
            c[ch] = _mm256_add_ps(
                _mm256_add_ps(SR_SIMD_FN(wide_f)(k->c0[ch]),
                              _mm256_mul_ps(l1, SR_SIMD_FN(wide_f)(k->c1[ch]))),
                _mm256_mul_ps(l2, SR_SIMD_FN(wide_f)(k->c2[ch])));
        }
        rgba = SR_SIMD_FN(wide_pack)(c);
    }
    __m256i *dst = (__m256i *)&fb->color[idx];
    if (bits == 255) {
        _mm256_storeu_si256(dst, rgba);
    } else {
        _mm256_storeu_si256(dst, _mm256_blendv_epi8(_mm256_loadu_si256(dst), rgba, m));
    }
    st->fragments += (uint64_t)__builtin_popcount((unsigned)bits);
}
