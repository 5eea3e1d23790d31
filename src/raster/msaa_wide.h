/* msaa_wide.h - the four-sample MSAA fast path, four pixels at a time
 * (raster stage, tile workers; AVX-512 only): the sixteen samples of four
 * neighbouring pixels of a block row in the sixteen lanes of a vector,
 * and the four pixels' shading (at their centres) in four float lanes.
 * Included once by msaa.c, for the state msaa_kernel.h covers when
 * the shading is the interpolated vertex color or flat and no texture is
 * bound; msaa_kernel.h's one-pixel form serves the others.
 *
 * Exactness: as msaa_kernel.h for coverage and depth - a sample's edge
 * value is the pixel's exact integer value plus its offset, held in a
 * double lane - and as simd_kernel.h's quad() for the shading: sr__bary
 * and sr__interp's float operations in order, lane by lane.  The pixels'
 * samples are consecutive elements (framebuffer.h), so the four pixels
 * are sixteen consecutive elements of each buffer (rows_avx512.h). */

typedef struct ms16 {
    const sr_draw_state *ds;
    const sr_tri *t;
    sr_frag_stats *st;
    __m512d off[2][3];     /* per edge: lane (pixel p, sample s)'s offset from pixel 0's centre */
    __m512d nbias[3];      /* -bias: covered iff e >= -bias */
    __m512d z0, dz1, dz2, zmin, zmax;
    __m256d pix[3];        /* per edge: pixel p's offset from pixel 0's centre, p = 0..3 */
    __m128 w[3], c0[4], c1[4], c2[4];
    uint32_t flat;         /* FLAT: the packed color */
} ms16;

SR_TARGET_AVX512
static inline __m128i ms16_shade(const ms16 *k, const __m256d e[3])
{
    if (k->ds->shading == SR_SHADING_FLAT) {
        return _mm_set1_epi32((int)k->flat);
    }
    /* sr__bary, then sr__interp, per pixel lane. */
    __m128 q0 = _mm_mul_ps(_mm256_cvtpd_ps(e[0]), k->w[0]);
    __m128 q1 = _mm_mul_ps(_mm256_cvtpd_ps(e[1]), k->w[1]);
    __m128 q2 = _mm_mul_ps(_mm256_cvtpd_ps(e[2]), k->w[2]);
    __m128 s = _mm_add_ps(_mm_add_ps(q0, q1), q2);
    __mmask8 nz = _mm_cmp_ps_mask(s, _mm_setzero_ps(), _CMP_NEQ_UQ);
    __m128 inv = _mm_maskz_div_ps(nz, _mm_set1_ps(1.0f), s);
    __m128 l1 = _mm_mul_ps(q1, inv), l2 = _mm_mul_ps(q2, inv);
    __m128i q[4];
    for (int ch = 0; ch < 4; ch++) {
        __m128 c = _mm_add_ps(_mm_add_ps(k->c0[ch], _mm_mul_ps(l1, k->c1[ch])),
                              _mm_mul_ps(l2, k->c2[ch]));
        /* sr__unorm8: min keeps NaN, truncation sends it below zero. */
        c = _mm_min_ps(_mm_set1_ps(1.0f), c);
        q[ch] = _mm_max_epi32(_mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(c, _mm_set1_ps(255.0f)),
                                                          _mm_set1_ps(0.5f))),
                              _mm_setzero_si128());
    }
    return _mm_or_si128(_mm_or_si128(q[0], _mm_slli_epi32(q[1], 8)),
                        _mm_or_si128(_mm_slli_epi32(q[2], 16), _mm_slli_epi32(q[3], 24)));
}

/* Pixels px .. px + n - 1 of row py (n <= 4), with pixel px's unbiased
 * centre edge values u[]. */
SR_TARGET_AVX512
static inline void ms16_pixels(const ms16 *k, int px, int py, const int64_t u[3], int n,
                               bool inside)
{
    const sr_draw_state *ds = k->ds;
    __mmask16 m = (__mmask16)((1u << (4 * n)) - 1); /* the n pixels' sample lanes */
    __m512d e[2][3];
    for (int h = 0; h < 2; h++) {
        for (int i = 0; i < 3; i++) {
            e[h][i] = _mm512_add_pd(_mm512_set1_pd((double)u[i]), k->off[h][i]);
        }
    }
    if (!inside) {
        __mmask8 c[2];
        for (int h = 0; h < 2; h++) {
            c[h] = _mm512_cmp_pd_mask(e[h][0], k->nbias[0], _CMP_GE_OQ) &
                   _mm512_cmp_pd_mask(e[h][1], k->nbias[1], _CMP_GE_OQ) &
                   _mm512_cmp_pd_mask(e[h][2], k->nbias[2], _CMP_GE_OQ);
        }
        m &= (__mmask16)(c[0] | c[1] << 8);
        if (!m) {
            return;
        }
    }
    __m256i q[2];
    for (int h = 0; h < 2; h++) {
        __m512d z = _mm512_add_pd(_mm512_add_pd(k->z0, _mm512_mul_pd(e[h][1], k->dz1)),
                                  _mm512_mul_pd(e[h][2], k->dz2));
        if (!k->t->z_inside) {
            z = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(z, k->zmin, _CMP_GE_OQ), k->zmin, z);
            z = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(z, k->zmax, _CMP_LE_OQ), k->zmax, z);
        }
        q[h] = _mm512_cvttpd_epi32(_mm512_add_pd(z, _mm512_set1_pd(0.5)));
    }
    __m512i qz = _mm512_inserti64x4(_mm512_castsi256_si512(q[0]), q[1], 1);
    size_t base = ((size_t)py * (size_t)ds->fb->width + (size_t)px) * 4;
    sr_framebuffer *fb = ds->fb;
    m = _mm512_mask_cmplt_epi32_mask(m, qz, sr__row16_load(fb->depth, sr__depth_size(fb), base, m));
    if (!m) {
        return;
    }
    sr__row16_store(fb->depth, sr__depth_size(fb), base, m, qz);
    /* Shading once per pixel, at its centre. */
    __m256d centre[3];
    for (int i = 0; i < 3; i++) {
        centre[i] = _mm256_add_pd(_mm256_set1_pd((double)u[i]), k->pix[i]);
    }
    __m128i rgba = ms16_shade(k, centre);
    __m512i spread = _mm512_permutexvar_epi32(
        _mm512_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3),
        _mm512_castsi128_si512(rgba));
    _mm512_mask_storeu_epi32(&ds->fb->color[base], m, spread);
    k->st->fragments += (uint64_t)__builtin_popcount((unsigned)m);
}

/* A block's part rect (msaa_walk.h): each row in groups of four pixels. */
SR_TARGET_AVX512
static inline void ms16_block(void *arg, const sr_block_steps *bs, const int rect[4],
                              const int64_t *u0, bool inside)
{
    const ms16 *k = arg;
    for (int py = rect[1]; py < rect[3]; py++) {
        for (int px = rect[0]; px < rect[2]; px += 4) {
            int n = rect[2] - px < 4 ? rect[2] - px : 4;
            int64_t u[3];
            for (int i = 0; i < 3; i++) {
                u[i] = u0[i] + bs->sx[i] * (px - rect[0]) + bs->sy[i] * (py - rect[1]);
            }
            ms16_pixels(k, px, py, u, n, inside);
        }
    }
}

SR_TARGET_AVX512
static void raster_ms16(const sr_draw_state *ds, const sr_tri *t, int rx0, int ry0, int rx1,
                        int ry1, sr_frag_stats *st)
{
    ms16 k;                /* every field set below: zeroing it all cost a rep stos */
    k.ds = ds;
    k.t = t;
    k.st = st;
    k.flat = 0;
    /* Lane p * 4 + s: pixel p's step plus sample s's offset, built in
     * registers (small integers: every product and sum is exact). */
    __m512d sox = _mm512_setzero_pd(), soy = _mm512_setzero_pd();
    for (int s = 0; s < 4; s++) {
        sox[s] = sox[s + 4] = ds->sample_off[s][0];
        soy[s] = soy[s + 4] = ds->sample_off[s][1];
    }
    const __m512d pix01 = _mm512_setr_pd(0, 0, 0, 0, 1, 1, 1, 1);
    for (int i = 0; i < 3; i++) {
        __m512d av = _mm512_set1_pd((double)t->a[i]), bv = _mm512_set1_pd((double)t->b[i]);
        __m512d step = _mm512_mul_pd(av, _mm512_set1_pd((double)SR_SUBPIXEL_ONE));
        __m512d first = _mm512_add_pd(_mm512_mul_pd(step, pix01),
                                      _mm512_add_pd(_mm512_mul_pd(av, sox),
                                                    _mm512_mul_pd(bv, soy)));
        k.off[0][i] = first;
        k.off[1][i] = _mm512_add_pd(first, _mm512_add_pd(step, step));
        k.nbias[i] = _mm512_set1_pd((double)-sr__tri_bias(t, i));
        double a = (double)((int64_t)t->a[i] * SR_SUBPIXEL_ONE);
        k.pix[i] = _mm256_setr_pd(0.0, a, 2.0 * a, 3.0 * a);
        k.w[i] = _mm_set1_ps(t->w[i]);
    }
    k.z0 = _mm512_set1_pd(t->z0);
    k.dz1 = _mm512_set1_pd(t->dz1);
    k.dz2 = _mm512_set1_pd(t->dz2);
    k.zmin = _mm512_set1_pd(ds->zq_min);
    k.zmax = _mm512_set1_pd(ds->zq_max);
    if (ds->shading == SR_SHADING_FLAT) {
        for (int ch = 0; ch < 4; ch++) {
            k.flat |= (uint32_t)sr__unorm8(sr__tri_flat(t)[ch]) << (8 * ch);
        }
    } else {
        int n = t->ninterp;
        for (int ch = 0; ch < 4; ch++) {
            bool has = ch < n;
            k.c0[ch] = _mm_set1_ps(has ? t->vary[SR_VARY_COLOR + ch] : 0.0f);
            k.c1[ch] = _mm_set1_ps(has ? t->vary[n + SR_VARY_COLOR + ch] : 0.0f);
            k.c2[ch] = _mm_set1_ps(has ? t->vary[2 * n + SR_VARY_COLOR + ch] : 0.0f);
        }
    }
    sr__block_walk(ds, t, rx0, ry0, rx1, ry1, &k, ms16_block);
}
