/* simd_kernel.h - the half-space rasterizer, several pixels at a time
 * (raster stage, tile worker threads).  A template included three times
 * by triangle_simd.c - compiled for AVX-512 (sixteen-lane stamps and
 * walks: simd_wide16.h, simd_wide16_walk.h), for AVX2 (eight-lane block
 * rows, simd_wide.h) and for the baseline instruction set (four-lane
 * groups) - with SR_SIMD_FN naming the copies (f_avx512, f_avx2, f_base).
 * Written with GCC/Clang vector extensions and intrinsics, so one source
 * serves all three; on AArch64 the four-lane copy is the only one (f_neon),
 * with SR_SIMD_NEON taking its two x86 helpers, bits and pack_rgba, from
 * unorm8_neon.h.  The AVX-512 paths that branch off raster_as stay in
 * line under #ifdef SR_SIMD_WIDE16: moved into functions, they change the
 * AVX-512 instances' generated code.
 *
 * Exactness: edge values are integers below 2^53, so holding them in
 * double lanes is exact; the AVX-512 copy holds them in 32-bit lanes
 * where every value in the box fits (sr__rect_fits32).  Every
 * floating-point step repeats the scalar fragment stage's operations in
 * the same order (no FMA: the build uses -ffp-contract=off), so the bytes
 * equal those of the reference rasterizers.  Covers the common states:
 * depth off or LESS with writes on a D16/D24 buffer, and UNLIT, GOURAUD,
 * FLAT or PHONG (whole-number shininess) shading, textured color in the
 * AVX-512 copy; triangle.c sends everything else down the scalar path. */

SR_SIMD_TARGET SR_INLINE v4l SR_SIMD_FN(sel_l)(v4l m, v4l a, v4l b) { return (m & a) | (~m & b); }
SR_SIMD_TARGET SR_INLINE v4i SR_SIMD_FN(sel_i)(v4i m, v4i a, v4i b) { return (m & a) | (~m & b); }

SR_SIMD_TARGET SR_INLINE v4f SR_SIMD_FN(sel_f)(v4i m, v4f a, v4f b)
{
    return (v4f)SR_SIMD_FN(sel_i)(m, (v4i)a, (v4i)b);
}

SR_SIMD_TARGET SR_INLINE v4d SR_SIMD_FN(sel_d)(v4l m, v4d a, v4d b)
{
    return (v4d)SR_SIMD_FN(sel_l)(m, (v4l)a, (v4l)b);
}

/* One bit per lane of a mask (lane 0 = bit 0). */
SR_SIMD_TARGET SR_INLINE int SR_SIMD_FN(bits)(v4i m)
{
#ifdef SR_SIMD_NEON
    return sr__neon_bits(m);
#else
    return _mm_movemask_ps((__m128)m);
#endif
}

/* sr__unorm8 on four pixels' r, g, b, a, packed into r,g,b,a bytes per
 * pixel.  Equal to the scalar form for every input: min(1, v) keeps NaN
 * (min returns its second operand then), truncation sends NaN and
 * negatives to values the saturating packs turn into 0, and anything
 * above 1 became exactly 255. */
SR_SIMD_TARGET SR_INLINE v4i SR_SIMD_FN(pack_rgba)(const v4f c[4])
{
#ifdef SR_SIMD_NEON
    return sr__neon_pack4_unorm8(c);
#else
    const __m128 one = _mm_set1_ps(1.0f);
    __m128i q[4];
    for (int k = 0; k < 4; k++) {
        __m128 v = _mm_min_ps(one, (__m128)c[k]);
        q[k] = _mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(v, _mm_set1_ps(255.0f)),
                                           _mm_set1_ps(0.5f)));
    }
    /* Bytes R0..3 B0..3 G0..3 A0..3, then interleave to R G B A per pixel. */
    __m128i x = _mm_packus_epi16(_mm_packs_epi32(q[0], q[2]), _mm_packs_epi32(q[1], q[3]));
    __m128i y = _mm_unpacklo_epi8(x, _mm_srli_si128(x, 8));
    return (v4i)_mm_unpacklo_epi16(y, _mm_srli_si128(y, 8));
#endif
}

/* A triangle's constants as lanes, made once per triangle rather than
 * broadcast in every group: depth plane, perspective weights, and the
 * color planes (v0, v1 - v0, v2 - v0 per channel). */
typedef struct SR_SIMD_FN(tri_lanes) {
    v4d z0, dz1, dz2;
    v4f w[3];
    v4f c0[4], c1[4], c2[4];
} SR_SIMD_FN(tri_lanes);

SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(make_lanes)(const sr_tri *t, SR_SIMD_FN(tri_lanes) *k)
{
    k->z0 = (v4d){ t->z0, t->z0, t->z0, t->z0 };
    k->dz1 = (v4d){ t->dz1, t->dz1, t->dz1, t->dz1 };
    k->dz2 = (v4d){ t->dz2, t->dz2, t->dz2, t->dz2 };
    for (int i = 0; i < 3; i++) {
        k->w[i] = (v4f){ t->w[i], t->w[i], t->w[i], t->w[i] };
    }
    int n = t->ninterp;
    for (int c = 0; c < 4 && c < n; c++) {
        float a = t->vary[SR_VARY_COLOR + c], b = t->vary[n + SR_VARY_COLOR + c];
        float d = t->vary[2 * n + SR_VARY_COLOR + c];
        k->c0[c] = (v4f){ a, a, a, a };
        k->c1[c] = (v4f){ b, b, b, b };
        k->c2[c] = (v4f){ d, d, d, d };
    }
}

/* Four pixels (gx .. gx+3, row py) with unbiased edge values e0..e2;
 * `valid` masks the lanes inside the span being drawn. */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(quad)(const sr_draw_state *ds, const sr_tri *t, int gx,
                                               int py, v4d e0, v4d e1, v4d e2, v4i valid,
                                               bool inside, const v4d nbias[3],
                                               const SR_SIMD_FN(tri_lanes) *k, sr_frag_stats *st,
                                               sr_shading shading, sr_depth_mode dmode)
{
    /* Covered iff e + bias >= 0, i.e. e >= -bias (exact: e is an integer).
     * In a block wholly inside the triangle only the span limits apply. */
    v4i m = valid;
    if (!inside) {
        m &= __builtin_convertvector((e0 >= nbias[0]) & (e1 >= nbias[1]) & (e2 >= nbias[2]), v4i);
    }
    if (!SR_SIMD_FN(bits)(m)) {
        return;
    }
    sr_framebuffer *fb = ds->fb;
    size_t idx = (size_t)py * (size_t)fb->width + (size_t)gx;

    if (dmode == SR_DEPTH_MODE_LESS) {
        v4d z = k->z0 + e1 * k->dz1 + e2 * k->dz2;
        if (!t->z_inside) {
            v4d zmin = { ds->zq_min, ds->zq_min, ds->zq_min, ds->zq_min };
            v4d zmax = { ds->zq_max, ds->zq_max, ds->zq_max, ds->zq_max };
            z = SR_SIMD_FN(sel_d)(z >= zmin, z, zmin);
            z = SR_SIMD_FN(sel_d)(z <= zmax, z, zmax);
        }
        v4i q = __builtin_convertvector(z + 0.5, v4i);   /* < 2^24: fits int32 */
        m = sr__depth_less4(fb, idx, q, m);
        if (!SR_SIMD_FN(bits)(m)) {
            return;
        }
    }

    v4i rgba;
    if (shading == SR_SHADING_PHONG) {
        /* sr__bary, then sr__shade_vary's Phong case. */
        v4f q0 = __builtin_convertvector(e0, v4f) * k->w[0];
        v4f q1 = __builtin_convertvector(e1, v4f) * k->w[1];
        v4f q2 = __builtin_convertvector(e2, v4f) * k->w[2];
        v4f s = q0 + q1 + q2;
        const v4f fzero = { 0, 0, 0, 0 };
        v4f inv = SR_SIMD_FN(sel_f)(s != fzero, 1.0f / s, fzero);
        v4f l1 = q1 * inv, l2 = q2 * inv;
        int n = t->ninterp;
        v4f vv[10];
        for (int j = 0; j < 10; j++) {
            vv[j] = t->vary[j] + l1 * t->vary[n + j] + l2 * t->vary[2 * n + j];
        }
        const v4f *vn = &vv[SR_VARY_PHONG_NORMAL];
        v4f len = sr__v4_sqrt(vn[0] * vn[0] + vn[1] * vn[1] + vn[2] * vn[2]);
        v4f sc = SR_SIMD_FN(sel_f)(len > fzero, 1.0f / len, fzero);
        if (ds->two_sided && !t->front) {
            sc = -sc;
        }
        v4f nn[3] = { vn[0] * sc, vn[1] * sc, vn[2] * sc };
        v4f c[4];
        sr__light_lanes(ds, nn, &vv[SR_VARY_PHONG_EYE], &vv[SR_VARY_PHONG_COLOR], c);
        rgba = SR_SIMD_FN(pack_rgba)(c);
    } else if (shading == SR_SHADING_FLAT) {
        v4i c[4];
        for (int ch = 0; ch < 4; ch++) {
            uint8_t b = sr__unorm8(sr__tri_flat(t)[ch]);
            c[ch] = (v4i){ b, b, b, b };
        }
        rgba = c[0] | c[1] << 8 | c[2] << 16 | c[3] << 24;
    } else {
        /* sr__bary and sr__interp, lane by lane. */
        v4f q0 = __builtin_convertvector(e0, v4f) * k->w[0];
        v4f q1 = __builtin_convertvector(e1, v4f) * k->w[1];
        v4f q2 = __builtin_convertvector(e2, v4f) * k->w[2];
        v4f s = q0 + q1 + q2;
        const v4f fzero = { 0, 0, 0, 0 };
        v4f inv = SR_SIMD_FN(sel_f)(s != fzero, 1.0f / s, fzero);
        v4f l1 = q1 * inv, l2 = q2 * inv;
        v4f c[4];
        for (int ch = 0; ch < 4; ch++) {
            c[ch] = k->c0[ch] + l1 * k->c1[ch] + l2 * k->c2[ch];
        }
        rgba = SR_SIMD_FN(pack_rgba)(c);
    }
    int lanes = SR_SIMD_FN(bits)(m);
    if (lanes == 15) {
        memcpy(&fb->color[idx], &rgba, sizeof rgba);    /* all four written */
    } else {
        v4i oldc;
        memcpy(&oldc, &fb->color[idx], sizeof oldc);
        v4i nc = SR_SIMD_FN(sel_i)(m, rgba, oldc);
        memcpy(&fb->color[idx], &nc, sizeof nc);
    }
    st->fragments += (uint64_t)__builtin_popcount((unsigned)lanes);
}

#ifdef SR_SIMD_WIDE
#include "raster/simd_wide.h"
#endif
/* The AVX-512 level's stamps and walks (its SR_SIMD_INSTANCE among
 * them); at the other levels SR_SIMD_INSTANCE makes raster_name straight
 * from raster_as. */
#ifdef SR_SIMD_WIDE16
#include "raster/rows_avx512.h"
#include "raster/simd_wide16.h"
#include "raster/simd_wide16_walk.h"
#else
#define SR_SIMD_INSTANCE(name, shading, dmode)                                         \
    SR_SIMD_TARGET static void SR_SIMD_FN(raster_##name)(                              \
        const sr_draw_state *ds, const sr_tri *t, int rx0, int ry0, int rx1, int ry1,  \
        sr_frag_stats *st)                                                             \
    {                                                                                  \
        sr_edges ed;                                                                   \
        sr__tri_edges(t, &ed);                                                         \
        SR_SIMD_FN(raster_as)(ds, t, &ed, rx0, ry0, rx1, ry1, st, shading, dmode,      \
                              SR_WALK_PLAIN);                                          \
    }
#endif

SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(raster_as)(const sr_draw_state *ds, const sr_tri *t,
                                                    const sr_edges *ed,
                                                    int rx0, int ry0, int rx1, int ry1,
                                                    sr_frag_stats *st, sr_shading shading,
                                                    sr_depth_mode dmode, sr_walk_flags walk)
{
    /* Textured instances and 32-bit edge lanes exist in the AVX-512
     * build only. */
    bool tex = walk & SR_WALK_TEXTURED, narrow = walk & SR_WALK_NARROW;
    (void)tex;
    (void)narrow;
    int64_t sx[3], sy[3];
    sr__pixel_steps(t, sx, sy);
    /* Lane offsets: 0..3 pixel steps, exact in double. */
    v4d lx[3];
    for (int i = 0; i < 3; i++) {
        double s = (double)sx[i];
        lx[i] = (v4d){ 0.0, s, 2.0 * s, 3.0 * s };
    }
    const v4i lane = { 0, 1, 2, 3 };
    int fbw = ds->fb->width;
    v4d nbias[3], g4[3];
    for (int i = 0; i < 3; i++) {
        double nb = -(double)ed->bias[i], g = 4.0 * (double)sx[i];
        nbias[i] = (v4d){ nb, nb, nb, nb };
        g4[i] = (v4d){ g, g, g, g };
    }
    const v4i all = { -1, -1, -1, -1 };
#ifdef SR_SIMD_WIDE16 /* in line: in a struct or a function, the AVX-512 code changes */
    __m512d lx8[3], nb8[3];
    __m512i nb32[3], off82[3], off44[3];
    SR_SIMD_FN(w16_edge_lanes)(ed, sx, lx8, nb8, nb32);
    /* The 32-bit lanes' offsets in an 8 x 2 stamp and a 4 x 4 one, made
     * once a call: made in each walk instead, spot and the bunny were
     * slower. */
    SR_SIMD_FN(n16_offsets)(sx, sy, 8, off82);
    SR_SIMD_FN(n16_offsets)(sx, sy, 4, off44);
#endif
    SR_SIMD_FN(tri_lanes) lanes;
    SR_SIMD_FN(make_lanes)(t, &lanes);
#ifdef SR_SIMD_WIDE16 /* apart from the block above: merged, the AVX-512 code changes */
    SR_SIMD_FN(w16_lanes) wl;
    SR_SIMD_FN(w16_make)(t, shading, &wl);
#endif

#ifdef SR_SIMD_WIDE16 /* in line: even as always_inline functions, the AVX-512 code changes */
    if (rx1 - rx0 <= 4 && ry1 - ry0 <= 2 * SR_BLOCK_SIZE) {
        /* Tiny triangles: the bounding box in 4 x 4 stamps, lane (x, y)
         * at offset x a + y b from the stamp's corner. */
        const __m512d col = _mm512_setr_pd(0, 1, 2, 3, 0, 1, 2, 3);
        const __m512d row = _mm512_setr_pd(0, 0, 0, 0, 1, 1, 1, 1);
        __m512d off[2][3];
        for (int i = 0; i < 3; i++) {
            /* Small integers: every product and sum is exact. */
            __m512d a = _mm512_set1_pd((double)sx[i]), b = _mm512_set1_pd((double)sy[i]);
            __m512d top = _mm512_add_pd(_mm512_mul_pd(a, col), _mm512_mul_pd(b, row));
            off[0][i] = top;
            off[1][i] = _mm512_add_pd(top, _mm512_add_pd(b, b));
        }
        unsigned cols = (1u << (rx1 - rx0)) - 1;
        for (int py = ry0; py < ry1; py += 4) {
            unsigned valid = 0;
            for (int r = 0; r < 4 && py + r < ry1; r++) {
                valid |= cols << (4 * r);
            }
            __m512d e[3][2];
            __m512i n[3];
            double corner_d[3];
            uint32_t corner[3];
            SR_SIMD_FN(edges_at)(ed, rx0, py, corner_d, corner);
            if (!narrow) {
                for (int i = 0; i < 3; i++) {
                    __m512d c = _mm512_set1_pd(corner_d[i]);
                    e[i][0] = _mm512_add_pd(c, off[0][i]);
                    e[i][1] = _mm512_add_pd(c, off[1][i]);
                }
            }
            if (narrow) {
                SR_SIMD_FN(n16_edges)(corner, off44, n);
            }
            SR_SIMD_FN(stamp16)(ds, t, rx0, py, e[0], e[1], e[2], n, (__mmask16)valid, false, nb8,
                                nb32, &wl, st, shading, dmode, SR_STAMP_4X4, walk);
        }
        return;
    }
    if (rx1 - rx0 <= 2 * SR_BLOCK_SIZE && ry1 - ry0 <= 2 * SR_BLOCK_SIZE) {
        /* Small triangles: the bounding box by pairs of rows, in spans of
         * eight from its left edge; masked lanes leave the rest alone. */
        double r[3];
        uint32_t r32[3];
        SR_SIMD_FN(edges_at)(ed, rx0, ry0, r, r32);
        for (int py = ry0; py < ry1; py += 2) {
            __mmask16 rows = py + 1 < ry1 ? 0xffff : 0x00ff;
            double rs[3] = { r[0], r[1], r[2] };
            uint32_t rs32[3] = { r32[0], r32[1], r32[2] };
            for (int gx = rx0; gx < rx1; gx += 8) {
                unsigned span = rx1 - gx >= 8 ? 0xffu : (1u << (rx1 - gx)) - 1;
                __m512d e0[2], e1[2], e2[2];
                __m512i n[3];
                if (narrow) {
                    SR_SIMD_FN(n16_edges)(rs32, off82, n);
                } else {
                    SR_SIMD_FN(w16_edges)(rs, sy, lx8, e0, e1, e2);
                }
                SR_SIMD_FN(stamp16)(ds, t, gx, py, e0, e1, e2, n, rows & (span | span << 8),
                                    false, nb8, nb32, &wl, st, shading, dmode, SR_STAMP_8X2, walk);
                for (int i = 0; i < 3; i++) {
                    rs[i] += 8.0 * (double)sx[i];
                    rs32[i] += 8u * (uint32_t)sx[i];
                }
            }
            for (int i = 0; i < 3; i++) {
                r[i] += 2.0 * (double)sy[i];
                r32[i] += 2u * (uint32_t)sy[i];
            }
        }
        return;
    }
#endif
    /* Small triangles (most of a detailed mesh): walk the bounding box in
     * rows of four-pixel groups, stepping the exact double edge values,
     * with no block classification.  Groups start on multiples of four so
     * they never straddle a tile (another thread's pixels); lanes outside
     * the box are masked, and the last group must end inside the row. */
    int gx_start = rx0 & ~3;
    if (rx1 - rx0 <= 2 * SR_BLOCK_SIZE && ry1 - ry0 <= 2 * SR_BLOCK_SIZE &&
        ((rx1 + 3) & ~3) <= fbw) {
        int64_t xc = sr__centre_q8(gx_start), yc = sr__centre_q8(ry0);
        double r0 = (double)sr__edge_at(ed, 0, xc, yc);
        double r1 = (double)sr__edge_at(ed, 1, xc, yc);
        double r2 = (double)sr__edge_at(ed, 2, xc, yc);
        double gx0 = 4.0 * (double)sx[0], gx1 = 4.0 * (double)sx[1], gx2 = 4.0 * (double)sx[2];
        for (int py = ry0; py < ry1; py++) {
            v4d e0 = r0 + lx[0], e1 = r1 + lx[1], e2 = r2 + lx[2];
            for (int gx = gx_start; gx < rx1; gx += 4) {
                v4i px = lane + gx;
                v4i valid = (px >= rx0) & (px < rx1);
                SR_SIMD_FN(quad)(ds, t, gx, py, e0, e1, e2, valid, false, nbias, &lanes, st,
                                 shading, dmode);
                e0 += gx0;
                e1 += gx1;
                e2 += gx2;
            }
            r0 += (double)sy[0];
            r1 += (double)sy[1];
            r2 += (double)sy[2];
        }
        return;
    }

    int bx_start = rx0 & ~(SR_BLOCK_SIZE - 1);
    int by_start = ry0 & ~(SR_BLOCK_SIZE - 1);
    bool all_inside = sr__rect_inside(ed, rx0, ry0, rx1, ry1, sx, sy);

    for (int by = by_start; by < ry1; by += SR_BLOCK_SIZE) {
        for (int bx = bx_start; bx < rx1; bx += SR_BLOCK_SIZE) {
            int64_t e[3];
            bool inside = true;
            if (all_inside) {
                for (int i = 0; i < 3; i++) {
                    e[i] = sr__edge_at(ed, i, sr__centre_q8(bx), sr__centre_q8(by)) +
                           ed->bias[i];
                }
            } else if (!sr__block_classify(ed, bx, by, sx, sy, e, &inside)) {
                continue;
            }
            int px0 = bx > rx0 ? bx : rx0, px1 = bx + SR_BLOCK_SIZE < rx1 ? bx + SR_BLOCK_SIZE : rx1;
            int py0 = by > ry0 ? by : ry0, py1 = by + SR_BLOCK_SIZE < ry1 ? by + SR_BLOCK_SIZE : ry1;
            /* Edge values step exactly in double lanes: by 256 b per row,
             * by 4 x 256 a per group of four pixels. */
            double r[3];
            for (int i = 0; i < 3; i++) {
                r[i] = (double)(e[i] - ed->bias[i] + sy[i] * (py0 - by));
            }
            bool full_width = px0 == bx && px1 == bx + SR_BLOCK_SIZE;
#if defined(SR_SIMD_WIDE16) /* in line, as the small-triangle walks above */
            {
                /* The block's rows in pairs, sixteen lanes, with the span
                 * [px0, px1) and the rows that exist as the lane mask. */
                unsigned span = (0xffu >> (SR_BLOCK_SIZE - (px1 - bx))) & (0xffu << (px0 - bx));
                uint32_t r32[3]; /* narrow: r modulo 2^32 */
                for (int i = 0; i < 3; i++) {
                    r32[i] = (uint32_t)(e[i] - ed->bias[i] + sy[i] * (py0 - by));
                }
                for (int py = py0; py < py1; py += 2) {
                    unsigned valid = py + 1 < py1 ? span | span << 8 : span;
                    __m512d e0[2], e1[2], e2[2];
                    __m512i n[3];
                    if (narrow) {
                        SR_SIMD_FN(n16_edges)(r32, off82, n);
                    } else {
                        SR_SIMD_FN(w16_edges)(r, sy, lx8, e0, e1, e2);
                    }
                    SR_SIMD_FN(stamp16)(ds, t, bx, py, e0, e1, e2, n, (__mmask16)valid, inside,
                                        nb8, nb32, &wl, st, shading, dmode, SR_STAMP_8X2, walk);
                    for (int i = 0; i < 3; i++) {
                        r[i] += 2.0 * (double)sy[i];
                        r32[i] += 2u * (uint32_t)sy[i];
                    }
                }
                continue;
            }
#elif defined(SR_SIMD_WIDE)
            if (full_width && shading != SR_SHADING_PHONG) {
                /* Whole rows of the block: eight lanes at once. */
                for (int py = py0; py < py1; py++) {
                    v4d e0[2] = { r[0] + lx[0], r[0] + lx[0] + g4[0] };
                    v4d e1[2] = { r[1] + lx[1], r[1] + lx[1] + g4[1] };
                    v4d e2[2] = { r[2] + lx[2], r[2] + lx[2] + g4[2] };
                    SR_SIMD_FN(row8)(ds, t, bx, py, e0, e1, e2, inside, nbias, &lanes, st,
                                     shading, dmode);
                    for (int i = 0; i < 3; i++) {
                        r[i] += (double)sy[i];
                    }
                }
                continue;
            }
#endif
            for (int py = py0; py < py1; py++) {
                v4d e0 = r[0] + lx[0], e1 = r[1] + lx[1], e2 = r[2] + lx[2];
                for (int gx = bx; gx < px1; gx += 4) {
                    if (gx + 4 <= px0) {
                        e0 += g4[0];
                        e1 += g4[1];
                        e2 += g4[2];
                        continue;
                    }
                    if (gx + 4 > fbw) {
                        /* The lanes would run past the row: finish the
                         * span one pixel at a time. */
                        int64_t dy = py - by;
                        for (int px = gx > px0 ? gx : px0; px < px1; px++) {
                            int64_t dx = px - bx;
                            int64_t r0 = e[0] - ed->bias[0] + sy[0] * dy + sx[0] * dx;
                            int64_t r1 = e[1] - ed->bias[1] + sy[1] * dy + sx[1] * dx;
                            int64_t r2 = e[2] - ed->bias[2] + sy[2] * dy + sx[2] * dx;
                            if (((r0 + ed->bias[0]) | (r1 + ed->bias[1]) | (r2 + ed->bias[2])) >= 0) {
                                sr__fragment_as(ds, t, px, py, r0, r1, r2, st, shading, dmode);
                            }
                        }
                        break;
                    }
                    v4i valid = all;
                    if (!full_width) {
                        v4i pxl = lane + gx;
                        valid = (pxl >= px0) & (pxl < px1);
                    }
                    SR_SIMD_FN(quad)(ds, t, gx, py, e0, e1, e2, valid, inside, nbias, &lanes,
                                     st, shading, dmode);
                    e0 += g4[0];
                    e1 += g4[1];
                    e2 += g4[2];
                }
                for (int i = 0; i < 3; i++) {
                    r[i] += (double)sy[i];
                }
            }
        }
    }
}

/* SR_SIMD_INSTANCE(name, ...) defines raster_name (and, at the AVX-512
 * level, its tiny_name and walk_name halves); SR_SIMD_FN suffixes each
 * with the level, so raster_unlit_less_avx512 is raster_unlit_less below. */
SR_SIMD_INSTANCE(unlit_off, SR_SHADING_UNLIT, SR_DEPTH_MODE_OFF)
SR_SIMD_INSTANCE(unlit_less, SR_SHADING_UNLIT, SR_DEPTH_MODE_LESS)
SR_SIMD_INSTANCE(flat_off, SR_SHADING_FLAT, SR_DEPTH_MODE_OFF)
SR_SIMD_INSTANCE(flat_less, SR_SHADING_FLAT, SR_DEPTH_MODE_LESS)
SR_SIMD_INSTANCE(phong_off, SR_SHADING_PHONG, SR_DEPTH_MODE_OFF)
SR_SIMD_INSTANCE(phong_less, SR_SHADING_PHONG, SR_DEPTH_MODE_LESS)
#undef SR_SIMD_INSTANCE


/* The kernel for a state, or NULL when this path does not cover it. */
static sr_raster_fn SR_SIMD_FN(select)(const sr_draw_state *ds)
{
    if (ds->blending) {
        return NULL; /* blending and masks take the scalar path */
    }
    bool depth_ok = ds->depth_mode == SR_DEPTH_MODE_OFF ||
                    (ds->depth_mode == SR_DEPTH_MODE_LESS && ds->depth_bits >= 1 &&
                     ds->depth_bits <= 24);
    if (!depth_ok) {
        return NULL;
    }
    bool less = ds->depth_mode == SR_DEPTH_MODE_LESS;
    if (ds->texture) {
        /* Textured color in the AVX-512 instance; the other textured
         * models and instances take the scalar path. */
#ifdef SR_SIMD_WIDE16 /* a hook function here reorders this function's blocks */
        if (sr__color_varying_shading(ds->shading)) {
            return less ? SR_SIMD_FN(raster_tex_less) : SR_SIMD_FN(raster_tex_off);
        }
#endif
        return NULL;
    }
    if (sr__color_varying_shading(ds->shading)) {
        return less ? SR_SIMD_FN(raster_unlit_less)
                    : SR_SIMD_FN(raster_unlit_off);
    }
    switch (ds->shading) {
    case SR_SHADING_FLAT:
        return less ? SR_SIMD_FN(raster_flat_less)
                    : SR_SIMD_FN(raster_flat_off);
    case SR_SHADING_PHONG:
        /* powf has no lane-exact vector twin: whole-number shininess only. */
        if (ds->shininess_int < 0) {
            return NULL;
        }
        return less ? SR_SIMD_FN(raster_phong_less)
                    : SR_SIMD_FN(raster_phong_off);
    default:
        return NULL;
    }
}
