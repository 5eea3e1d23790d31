/* simd_wide16_walk.h - the AVX-512 level's walks (raster stage, tile
 * worker threads): which walk a triangle's part in a tile takes, a box
 * covered whole in rows of sixteen, tiny triangles in a function of their
 * own, the textured instances, and the SR_SIMD_INSTANCE that makes this
 * level's raster_name from them.  Included by simd_kernel.h in its
 * AVX-512 instance only, before raster_as, which the walks call; the
 * stamps they draw are simd_wide16.h's. */

/* Defined after this file, in simd_kernel.h; the walks below call it. */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(raster_as)(const sr_draw_state *ds, const sr_tri *t,
                                                    const sr_edges *ed,
                                                    int rx0, int ry0, int rx1, int ry1,
                                                    sr_frag_stats *st, sr_shading shading,
                                                    sr_depth_mode dmode, sr_walk_flags walk);

/* A box the triangle covers whole (a large triangle over most of its
 * tiles): no blocks and no coverage test, each row in spans of sixteen,
 * one load and one store each for depth and color.  Apart from
 * raster_as, whose code it would otherwise grow: inline there it cost
 * spot and teapot 2%. */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(raster_inside_as)(const sr_draw_state *ds,
                                                           const sr_tri *t, const sr_edges *ed,
                                                           int rx0, int ry0,
                                                           int rx1, int ry1, sr_frag_stats *st,
                                                           sr_shading shading,
                                                           sr_depth_mode dmode,
                                                           sr_walk_flags walk)
{
    bool narrow = walk & SR_WALK_NARROW;
    SR_SIMD_FN(w16_lanes) wl;
    SR_SIMD_FN(w16_make)(t, shading, &wl);
    int64_t sx[3], sy[3];
    sr__pixel_steps(t, sx, sy);
    __m512d lx8[3], nb8[3];
    __m512i nb32[3], off16[3];
    SR_SIMD_FN(w16_edge_lanes)(ed, sx, lx8, nb8, nb32);
    SR_SIMD_FN(n16_offsets)(sx, sy, 16, off16);
    double r[3];
    uint32_t r32[3];
    SR_SIMD_FN(edges_at)(ed, rx0, ry0, r, r32);
    for (int py = ry0; py < ry1; py++) {
        double rs[3] = { r[0], r[1], r[2] };
        uint32_t rs32[3] = { r32[0], r32[1], r32[2] };
        for (int gx = rx0; gx < rx1; gx += 16) {
            unsigned valid = rx1 - gx >= 16 ? 0xffffu : (1u << (rx1 - gx)) - 1;
            __m512d e[3][2];
            __m512i n[3];
            if (narrow) {
                SR_SIMD_FN(n16_edges)(rs32, off16, n);
            } else {
                for (int i = 0; i < 3; i++) {
                    e[i][0] = _mm512_add_pd(_mm512_set1_pd(rs[i]), lx8[i]);
                    e[i][1] = _mm512_add_pd(_mm512_set1_pd(rs[i] + 8.0 * (double)sx[i]), lx8[i]);
                }
            }
            SR_SIMD_FN(stamp16)(ds, t, gx, py, e[0], e[1], e[2], n, (__mmask16)valid, true, nb8,
                                nb32, &wl, st, shading, dmode, SR_STAMP_16X1, walk);
            for (int i = 0; i < 3; i++) {
                rs[i] += 16.0 * (double)sx[i];
                rs32[i] += 16u * (uint32_t)sx[i];
            }
        }
        for (int i = 0; i < 3; i++) {
            r[i] += (double)sy[i];
            r32[i] += (uint32_t)sy[i];
        }
    }
}

/* Which walk a triangle's part in a tile takes: a box of at least half a
 * tile each way that it covers whole by whole rows, the rest by
 * raster_as; both with 32-bit edge lanes where the box's values fit.
 * (Testing smaller boxes for it cost spot and teapot 2%: few of their
 * triangles cover a box whole.) */
SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(raster_dispatch)(const sr_draw_state *ds,
                                                          const sr_tri *t, int rx0, int ry0,
                                                          int rx1, int ry1, sr_frag_stats *st,
                                                          sr_shading shading, sr_depth_mode dmode)
{
    sr_edges ed;
    sr__tri_edges(t, &ed);
    bool narrow = t->fits32 || sr__rect_fits32(&ed, rx0, ry0, rx1, ry1);
    if (rx1 - rx0 >= SR_TILE_SIZE / 2 && ry1 - ry0 >= SR_TILE_SIZE / 2) {
        int64_t sx[3], sy[3];
        sr__pixel_steps(t, sx, sy);
        if (sr__rect_inside(&ed, rx0, ry0, rx1, ry1, sx, sy)) {
            if (narrow) {
                SR_SIMD_FN(raster_inside_as)(ds, t, &ed, rx0, ry0, rx1, ry1, st, shading, dmode,
                                             SR_WALK_NARROW);
            } else {
                SR_SIMD_FN(raster_inside_as)(ds, t, &ed, rx0, ry0, rx1, ry1, st, shading, dmode,
                                             SR_WALK_PLAIN);
            }
            return;
        }
    }
    if (narrow) {
        SR_SIMD_FN(raster_as)(ds, t, &ed, rx0, ry0, rx1, ry1, st, shading, dmode, SR_WALK_NARROW);
    } else {
        SR_SIMD_FN(raster_as)(ds, t, &ed, rx0, ry0, rx1, ry1, st, shading, dmode, SR_WALK_PLAIN);
    }
}

/* Tiny triangles (simd_tiny.h) and the rest in functions of their own,
 * so the tiny path keeps its constants in registers: inside the other
 * walks' function it paid their stack frame and spills. */
#define SR_SIMD_INSTANCE(name, shading, dmode)                                         \
    SR_SIMD_TARGET static __attribute__((noinline)) void SR_SIMD_FN(                   \
        tiny_##name)(const sr_draw_state *ds, const sr_tri *t, int rx0, int ry0,       \
                     int rx1, int ry1, sr_frag_stats *st)                              \
    {                                                                                  \
        if (rx1 - rx0 <= 4) {                                                          \
            SR_SIMD_FN(raster_tiny)(ds, t, rx0, ry0, rx1, ry1, st, shading, dmode,     \
                                    SR_STAMP_4X4);                                     \
        } else {                                                                       \
            SR_SIMD_FN(raster_tiny)(ds, t, rx0, ry0, rx1, ry1, st, shading, dmode,     \
                                    SR_STAMP_8X2);                                     \
        }                                                                              \
    }                                                                                  \
    SR_SIMD_TARGET static __attribute__((noinline)) void SR_SIMD_FN(                   \
        walk_##name)(const sr_draw_state *ds, const sr_tri *t, int rx0, int ry0,       \
                     int rx1, int ry1, sr_frag_stats *st)                              \
    {                                                                                  \
        SR_SIMD_FN(raster_dispatch)(ds, t, rx0, ry0, rx1, ry1, st, shading, dmode);    \
    }                                                                                  \
    SR_SIMD_TARGET static void SR_SIMD_FN(raster_##name)(                              \
        const sr_draw_state *ds, const sr_tri *t, int rx0, int ry0, int rx1, int ry1,  \
        sr_frag_stats *st)                                                             \
    {                                                                                  \
        if (t->fits32 && rx1 - rx0 <= 8 && ry1 - ry0 <= 2 * SR_BLOCK_SIZE) {           \
            SR_SIMD_FN(tiny_##name)(ds, t, rx0, ry0, rx1, ry1, st);                    \
        } else {                                                                       \
            SR_SIMD_FN(walk_##name)(ds, t, rx0, ry0, rx1, ry1, st);                    \
        }                                                                              \
    }

/* UNLIT or GOURAUD color modulated by a texture (simd_tex.h). */
SR_SIMD_TARGET static void SR_SIMD_FN(raster_tex_less)(const sr_draw_state *ds, const sr_tri *t,
                                                       int rx0, int ry0, int rx1, int ry1,
                                                       sr_frag_stats *st)
{
    sr_edges ed;
    sr__tri_edges(t, &ed);
    SR_SIMD_FN(raster_as)(ds, t, &ed, rx0, ry0, rx1, ry1, st, SR_SHADING_UNLIT, SR_DEPTH_MODE_LESS,
                          SR_WALK_TEXTURED);
}

SR_SIMD_TARGET static void SR_SIMD_FN(raster_tex_off)(const sr_draw_state *ds, const sr_tri *t,
                                                      int rx0, int ry0, int rx1, int ry1,
                                                      sr_frag_stats *st)
{
    sr_edges ed;
    sr__tri_edges(t, &ed);
    SR_SIMD_FN(raster_as)(ds, t, &ed, rx0, ry0, rx1, ry1, st, SR_SHADING_UNLIT, SR_DEPTH_MODE_OFF,
                          SR_WALK_TEXTURED);
}
