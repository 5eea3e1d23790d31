/* simd_tex.h - textured stamps of sixteen pixels (raster stage, tile
 * worker threads): the AVX-512 instance's rows16 for UNLIT and GOURAUD
 * color modulated by a texture.  Included by simd_wide16.h, in
 * simd_kernel.h's AVX-512 instance only.
 *
 * The lanes do what the scalar fragment stage does per pixel, in the same
 * order: coverage and depth as rows16; sr__bary at the pixel and, for
 * trilinear filtering, one pixel to the right and one below (edge values
 * stepped exactly by a and b); sr__interp of the color and of u, v; the
 * level of detail as sr__texture_lod, its footprint in lanes and its
 * log2f lane by lane (it has no lane-exact vector twin).  The sampler is texture.c's
 * restated on lanes - clamp, floor, wrap, gathered texels turned to
 * floats by the same division the texture's tables hold, the bilinear and
 * trilinear blends in the same order - when the lanes can go together (a
 * linear texture, every lane between the same two mip levels); otherwise
 * sr__texture_sample runs lane by lane.  Either way the bytes are the
 * scalar path's (tests/test_properties.c). */

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

/* Texel indices along one axis under a wrap mode: the identity inside
 * the image; lanes outside it take sr__texture_wrap one by one. */
SR_SIMD_TARGET SR_INLINE __m512i SR_SIMD_FN(w16_wrap)(__m512i i, int n, sr_texture_wrap mode,
                                                      __mmask16 m)
{
    __mmask16 out = _mm512_mask_cmplt_epi32_mask(m, i, _mm512_setzero_si512()) |
                    _mm512_mask_cmpge_epi32_mask(m, i, _mm512_set1_epi32(n));
    if (!out) {
        return i;
    }
    int32_t lane[16];
    _mm512_storeu_si512(lane, i);
    for (unsigned b = out; b; b &= b - 1) {
        int k = __builtin_ctz(b);
        lane[k] = sr__texture_wrap(lane[k], n, mode);
    }
    return _mm512_loadu_si512(lane);
}

/* The four channels of the texels at (x, y) of level k: byte / 255 as
 * the linear texture's color_value and alpha_value hold it. */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(w16_fetch)(const sr_texture *t, int k, __m512i x,
                                                    __m512i y, __mmask16 m, __m512 out[4])
{
    __m512i idx = _mm512_add_epi32(_mm512_mullo_epi32(y, _mm512_set1_epi32(t->width[k])), x);
    __m512i px = _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), m, idx,
                                             (const int *)(const void *)t->texels[k], 4);
    const __m512 k255 = _mm512_set1_ps(255.0f);
    for (int ch = 0; ch < 4; ch++) {
        __m512i b = _mm512_and_si512(_mm512_srli_epi32(px, 8 * ch), _mm512_set1_epi32(0xff));
        out[ch] = _mm512_div_ps(_mm512_cvtepi32_ps(b), k255);
    }
}

/* sample_level (texture.c) on sixteen lanes, all at level k. */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(w16_level)(const sr_texture *t, int k, bool linear,
                                                    sr_texture_wrap wu, sr_texture_wrap wv,
                                                    __m512 u, __m512 v, __mmask16 m,
                                                    __m512 out[4])
{
    int w = t->width[k], h = t->height[k];
    __m512 x = _mm512_mul_ps(u, _mm512_set1_ps((float)w));
    __m512 y = _mm512_mul_ps(_mm512_sub_ps(_mm512_set1_ps(1.0f), v), _mm512_set1_ps((float)h));
    x = _mm512_min_ps(_mm512_max_ps(x, _mm512_set1_ps(-1e7f)), _mm512_set1_ps(1e7f));
    y = _mm512_min_ps(_mm512_max_ps(y, _mm512_set1_ps(-1e7f)), _mm512_set1_ps(1e7f));
    if (!linear) {
        __m512i xi = _mm512_cvttps_epi32(_mm512_roundscale_ps(x, _MM_FROUND_TO_NEG_INF));
        __m512i yi = _mm512_cvttps_epi32(_mm512_roundscale_ps(y, _MM_FROUND_TO_NEG_INF));
        SR_SIMD_FN(w16_fetch)(t, k, SR_SIMD_FN(w16_wrap)(xi, w, wu, m),
                              SR_SIMD_FN(w16_wrap)(yi, h, wv, m), m, out);
        return;
    }
    x = _mm512_sub_ps(x, _mm512_set1_ps(0.5f));
    y = _mm512_sub_ps(y, _mm512_set1_ps(0.5f));
    __m512 fx = _mm512_roundscale_ps(x, _MM_FROUND_TO_NEG_INF);
    __m512 fy = _mm512_roundscale_ps(y, _MM_FROUND_TO_NEG_INF);
    __m512 ax = _mm512_sub_ps(x, fx), ay = _mm512_sub_ps(y, fy);
    __m512i ix = _mm512_cvttps_epi32(fx), iy = _mm512_cvttps_epi32(fy);
    __m512i one = _mm512_set1_epi32(1);
    __m512i x0 = SR_SIMD_FN(w16_wrap)(ix, w, wu, m);
    __m512i x1 = SR_SIMD_FN(w16_wrap)(_mm512_add_epi32(ix, one), w, wu, m);
    __m512i y0 = SR_SIMD_FN(w16_wrap)(iy, h, wv, m);
    __m512i y1 = SR_SIMD_FN(w16_wrap)(_mm512_add_epi32(iy, one), h, wv, m);
    __m512 p00[4], p10[4], p01[4], p11[4];
    SR_SIMD_FN(w16_fetch)(t, k, x0, y0, m, p00);
    SR_SIMD_FN(w16_fetch)(t, k, x1, y0, m, p10);
    SR_SIMD_FN(w16_fetch)(t, k, x0, y1, m, p01);
    SR_SIMD_FN(w16_fetch)(t, k, x1, y1, m, p11);
    for (int ch = 0; ch < 4; ch++) {
        __m512 top = _mm512_add_ps(p00[ch], _mm512_mul_ps(ax, _mm512_sub_ps(p10[ch], p00[ch])));
        __m512 bottom = _mm512_add_ps(p01[ch], _mm512_mul_ps(ax, _mm512_sub_ps(p11[ch], p01[ch])));
        out[ch] = _mm512_add_ps(top, _mm512_mul_ps(ay, _mm512_sub_ps(bottom, top)));
    }
}

/* sr__texture_sample on the lanes m, when they can go together: a linear
 * (not sRGB) texture, and under trilinear filtering every lane between
 * the same two levels (or every lane at level 0).  False leaves it to the
 * scalar sampler, lane by lane. */
SR_SIMD_TARGET SR_INLINE bool SR_SIMD_FN(w16_sample)(const sr_draw_state *ds, __m512 u, __m512 v,
                                                     const float lod[16], __mmask16 m,
                                                     __m512 out[4])
{
    const sr_texture *t = ds->texture;
    if (t->srgb) {
        return false;
    }
    /* Coordinates that are not finite sample at (0, 0). */
    __mmask16 bad = _mm512_fpclass_ps_mask(u, 0x99) | _mm512_fpclass_ps_mask(v, 0x99);
    u = _mm512_maskz_mov_ps((__mmask16)~bad, u);
    v = _mm512_maskz_mov_ps((__mmask16)~bad, v);
    bool linear = ds->texture_filter != SR_FILTER_NEAREST;
    if (ds->texture_filter != SR_FILTER_TRILINEAR || t->levels == 1) {
        SR_SIMD_FN(w16_level)(t, 0, linear, ds->wrap_u, ds->wrap_v, u, v, m, out);
        return true;
    }
    __m512 l = _mm512_loadu_ps(lod);
    __mmask16 minified = _mm512_mask_cmp_ps_mask(m, l, _mm512_setzero_ps(), _CMP_GT_OQ);
    if (!minified) {
        SR_SIMD_FN(w16_level)(t, 0, true, ds->wrap_u, ds->wrap_v, u, v, m, out);
        return true;
    }
    if (minified != m) {
        return false;
    }
    l = _mm512_min_ps(l, _mm512_set1_ps((float)(t->levels - 1)));
    __m512 fl = _mm512_roundscale_ps(l, _MM_FROUND_TO_NEG_INF);
    int k0 = (int)fl[__builtin_ctz(m)];
    if (_mm512_mask_cmpneq_ps_mask(m, fl, _mm512_set1_ps((float)k0))) {
        return false;
    }
    int k1 = k0 + 1 < t->levels ? k0 + 1 : k0;
    __m512 f = _mm512_sub_ps(l, fl);
    __m512 a[4], b[4];
    SR_SIMD_FN(w16_level)(t, k0, true, ds->wrap_u, ds->wrap_v, u, v, m, a);
    SR_SIMD_FN(w16_level)(t, k1, true, ds->wrap_u, ds->wrap_v, u, v, m, b);
    for (int ch = 0; ch < 4; ch++) {
        out[ch] = _mm512_add_ps(a[ch], _mm512_mul_ps(f, _mm512_sub_ps(b[ch], a[ch])));
    }
    return true;
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
    float lod[16] = { 0 };
    __m512 uu = SR_SIMD_FN(w16_interp)(t, ui, l1, l2), vv = SR_SIMD_FN(w16_interp)(t, ui + 1, l1, l2);
    const sr_texture *tex = ds->texture;
    unsigned lanes = m;
    if (ds->texture_filter == SR_FILTER_TRILINEAR) {
        /* The derivatives by the same exact interpolation one pixel to
         * the right (edge values + a * 256) and one below (+ b * 256). */
        float d[4][16];
        for (int dir = 0; dir < 2; dir++) {
            const int32_t *ab = dir ? t->b : t->a;
            __m512d s0[2], s1[2], s2[2];
            SR_SIMD_FN(w16_step)(e0, (double)((int64_t)ab[0] * SR_SUBPIXEL_ONE), s0);
            SR_SIMD_FN(w16_step)(e1, (double)((int64_t)ab[1] * SR_SUBPIXEL_ONE), s1);
            SR_SIMD_FN(w16_step)(e2, (double)((int64_t)ab[2] * SR_SUBPIXEL_ONE), s2);
            __m512 m1, m2;
            SR_SIMD_FN(w16_bary)(k, s0, s1, s2, &m1, &m2);
            _mm512_storeu_ps(d[2 * dir], _mm512_sub_ps(SR_SIMD_FN(w16_interp)(t, ui, m1, m2), uu));
            _mm512_storeu_ps(d[2 * dir + 1],
                             _mm512_sub_ps(SR_SIMD_FN(w16_interp)(t, ui + 1, m1, m2), vv));
        }
        /* sr__texture_lod up to rho^2 in lanes: the same products and
         * sums; max returns its second operand where either is NaN, and
         * fmaxf the one that is not NaN. */
        __m512 w = _mm512_set1_ps((float)tex->width[0]), h = _mm512_set1_ps((float)tex->height[0]);
        __m512 ax = _mm512_mul_ps(_mm512_loadu_ps(d[0]), w);
        __m512 bx = _mm512_mul_ps(_mm512_loadu_ps(d[1]), h);
        __m512 ay = _mm512_mul_ps(_mm512_loadu_ps(d[2]), w);
        __m512 by = _mm512_mul_ps(_mm512_loadu_ps(d[3]), h);
        __m512 rx = _mm512_add_ps(_mm512_mul_ps(ax, ax), _mm512_mul_ps(bx, bx));
        __m512 ry = _mm512_add_ps(_mm512_mul_ps(ay, ay), _mm512_mul_ps(by, by));
        __m512 rho2 = _mm512_max_ps(rx, ry);
        rho2 = _mm512_mask_mov_ps(rho2, _mm512_cmp_ps_mask(ry, ry, _CMP_UNORD_Q), rx);
        /* The logarithm lane by lane (log2f has no lane-exact vector
         * twin), only where the texture is minified. */
        float r2[16];
        _mm512_storeu_ps(r2, rho2);
        unsigned minified = lanes & _mm512_cmp_ps_mask(rho2, _mm512_set1_ps(1.0f), _CMP_GT_OQ);
        for (unsigned b = minified; b; b &= b - 1) {
            int i = __builtin_ctz(b);
            lod[i] = sr__texture_lod_rho2(r2[i]);
        }
    }
    /* The texels: all lanes at once when they can go together, else lane
     * by lane (lanes not covered keep 1; their colors are not stored). */
    __m512 texel[4];
    if (!SR_SIMD_FN(w16_sample)(ds, uu, vv, lod, m, texel)) {
        float u[16], v[16], tl[4][16];
        _mm512_storeu_ps(u, uu);
        _mm512_storeu_ps(v, vv);
        for (int ch = 0; ch < 4; ch++) {
            _mm512_storeu_ps(tl[ch], _mm512_set1_ps(1.0f));
        }
        for (unsigned b = lanes; b; b &= b - 1) {
            int i = __builtin_ctz(b);
            float out[4];
            sr__texture_sample(tex, ds->texture_filter, ds->wrap_u, ds->wrap_v, u[i], v[i],
                               lod[i], out);
            for (int ch = 0; ch < 4; ch++) {
                tl[ch][i] = out[ch];
            }
        }
        for (int ch = 0; ch < 4; ch++) {
            texel[ch] = _mm512_loadu_ps(tl[ch]);
        }
    }
    /* sr__modulate, then sr__unorm8 and the packing of rows16. */
    __m512i rgba = _mm512_setzero_si512();
    for (int ch = 0; ch < 4; ch++) {
        __m512 mod = _mm512_mul_ps(c[ch], texel[ch]);
        rgba = _mm512_or_si512(rgba, _mm512_sll_epi32(SR_SIMD_FN(w16_unorm8)(mod),
                                                      _mm_cvtsi32_si128(8 * ch)));
    }
    SR_SIMD_FN(stamp_store)(fb->color, 4, idx, pitch, m, rgba, shape);
    st->fragments += (uint64_t)__builtin_popcount(lanes);
}
