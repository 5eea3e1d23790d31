/* simd_tex.h - textured stamps of sixteen pixels (raster stage, tile
 * worker threads): the AVX-512 instance's rows16 for UNLIT and GOURAUD
 * color modulated by a texture.  Included by simd_kernel.h after
 * simd_wide.h, in its AVX-512 instance only.
 *
 * The lanes do what the scalar fragment stage does per pixel, in the same
 * order: coverage and depth as rows16; sr__bary at the pixel and, for
 * trilinear filtering, one pixel to the right and one below (edge values
 * stepped exactly by a and b); sr__interp of the color and of u, v.  The
 * level of detail (its fmaxf and log2f) and the texel fetch and filter are
 * then sr__texture_lod and sr__texture_sample themselves, called for each
 * covered lane, and the lanes modulate and pack as sr__write_color does.
 * So every byte is the scalar path's; what the lanes save is the per-pixel
 * setup around the sampler. */

/* Attribute `ch` of the triangle at weights l1, l2 (sr__interp). */
SR_SIMD_TARGET SR_INLINE __m512 SR_SIMD_FN(w16_interp)(const sr_tri *t, int ch, __m512 l1,
                                                       __m512 l2)
{
    int n = t->ninterp;
    return _mm512_add_ps(_mm512_add_ps(_mm512_set1_ps(t->vary[ch]),
                                       _mm512_mul_ps(l1, _mm512_set1_ps(t->vary[n + ch]))),
                         _mm512_mul_ps(l2, _mm512_set1_ps(t->vary[2 * n + ch])));
}

/* Edge values one step away: e + d[i] for edge i (exact in double). */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(w16_step)(const __m512d e[2], double d, __m512d out[2])
{
    out[0] = _mm512_add_pd(e[0], _mm512_set1_pd(d));
    out[1] = _mm512_add_pd(e[1], _mm512_set1_pd(d));
}

SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(rows16_tex)(const sr_draw_state *ds, const sr_tri *t,
                                                     int gx, int py, const __m512d e0[2],
                                                     const __m512d e1[2], const __m512d e2[2],
                                                     __mmask16 valid, bool inside,
                                                     const __m512d nb[3],
                                                     const SR_SIMD_FN(w16_lanes) *k,
                                                     sr_frag_stats *st, sr_depth_mode dmode,
                                                     sr_stamp shape)
{
    sr_framebuffer *fb = ds->fb;
    size_t pitch = (size_t)fb->width, idx = (size_t)py * pitch + (size_t)gx;
    __mmask16 m = SR_SIMD_FN(w16_test)(ds, t, idx, e0, e1, e2, valid, inside, nb, k, dmode, shape);
    if (!m) {
        return;
    }

    /* sr__shade_as: the weights, the color and u, v at the pixel. */
    __m512 l1, l2;
    SR_SIMD_FN(w16_bary)(k, e0, e1, e2, &l1, &l2);
    int ui = ds->uv_index;
    __m512 c[4];
    for (int ch = 0; ch < 4; ch++) {
        c[ch] = SR_SIMD_FN(w16_interp)(t, SR_VARY_COLOR + ch, l1, l2);
    }
    float u[16], v[16], lod[16];
    __m512 uu = SR_SIMD_FN(w16_interp)(t, ui, l1, l2), vv = SR_SIMD_FN(w16_interp)(t, ui + 1, l1, l2);
    _mm512_storeu_ps(u, uu);
    _mm512_storeu_ps(v, vv);
    const sr_texture *tex = ds->texture;
    unsigned lanes = m;
    if (ds->texture_filter == SR_FILTER_TRILINEAR) {
        /* The derivatives by the same exact interpolation one pixel to
         * the right (edge values + a * 256) and one below (+ b * 256). */
        float d[4][16];
        for (int dir = 0; dir < 2; dir++) {
            const int64_t *ab = dir ? t->b : t->a;
            __m512d s0[2], s1[2], s2[2];
            SR_SIMD_FN(w16_step)(e0, (double)(ab[0] * SR_SUBPIXEL_ONE), s0);
            SR_SIMD_FN(w16_step)(e1, (double)(ab[1] * SR_SUBPIXEL_ONE), s1);
            SR_SIMD_FN(w16_step)(e2, (double)(ab[2] * SR_SUBPIXEL_ONE), s2);
            __m512 m1, m2;
            SR_SIMD_FN(w16_bary)(k, s0, s1, s2, &m1, &m2);
            _mm512_storeu_ps(d[2 * dir], _mm512_sub_ps(SR_SIMD_FN(w16_interp)(t, ui, m1, m2), uu));
            _mm512_storeu_ps(d[2 * dir + 1],
                             _mm512_sub_ps(SR_SIMD_FN(w16_interp)(t, ui + 1, m1, m2), vv));
        }
        for (unsigned b = lanes; b; b &= b - 1) {
            int i = __builtin_ctz(b);
            lod[i] = sr__texture_lod(tex, d[0][i], d[1][i], d[2][i], d[3][i]);
        }
    } else {
        for (unsigned b = lanes; b; b &= b - 1) {
            lod[__builtin_ctz(b)] = 0.0f;
        }
    }
    /* The texels, lane by lane, as four channel rows; lanes not covered
     * keep 1 (their colors are not stored). */
    float texel[4][16];
    for (int ch = 0; ch < 4; ch++) {
        _mm512_storeu_ps(texel[ch], _mm512_set1_ps(1.0f));
    }
    for (unsigned b = lanes; b; b &= b - 1) {
        int i = __builtin_ctz(b);
        float out[4];
        sr__texture_sample(tex, ds->texture_filter, ds->wrap_u, ds->wrap_v, u[i], v[i], lod[i],
                           out);
        for (int ch = 0; ch < 4; ch++) {
            texel[ch][i] = out[ch];
        }
    }
    /* sr__modulate, then sr__unorm8 and the packing of rows16. */
    __m512i rgba = _mm512_setzero_si512();
    for (int ch = 0; ch < 4; ch++) {
        __m512 mod = _mm512_mul_ps(c[ch], _mm512_loadu_ps(texel[ch]));
        rgba = _mm512_or_si512(rgba, _mm512_sll_epi32(SR_SIMD_FN(w16_unorm8)(mod),
                                                      _mm_cvtsi32_si128(8 * ch)));
    }
    SR_SIMD_FN(stamp_store)(fb->color, idx, pitch, m, rgba, shape);
    st->fragments += (uint64_t)__builtin_popcount(lanes);
}
