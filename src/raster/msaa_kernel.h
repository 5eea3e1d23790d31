/* msaa_kernel.h - the four-sample MSAA fast path (raster stage, tile
 * workers): one pixel's four samples in the four lanes of a vector, for
 * the common state - depth LESS with writes on a D16/D24 buffer, no
 * stencil, no blending or masks, no alpha to coverage.  Included twice by
 * msaa.c on x86, for AVX2 and for the baseline instruction set, and once
 * on AArch64, for NEON, with SR_SIMD_FN naming the copies.
 *
 * Exactness: edge values are integers below 2^53, exact in double lanes,
 * so a sample's value u + offset is the scalar path's int64 sum; depth
 * repeats sr__tri_depth's operations in order (no FMA), and the samples
 * are four consecutive words of the depth and color buffers
 * (framebuffer.h), so the test and the writes are one load and one
 * select each.  The bytes equal the generic per-sample path's, which the
 * tests check. */

SR_SIMD_TARGET SR_INLINE v4l SR_SIMD_FN(ms4_sel)(v4l m, v4l a, v4l b) { return (m & a) | (~m & b); }

typedef struct SR_SIMD_FN(ms4) {
    const sr_draw_state *ds;
    const sr_tri *t;
    sr_frag_stats *st;
    v4d so[3];             /* per edge: the four samples' offsets from the centre */
    v4d nbias[3];          /* -bias: covered iff e >= -bias */
    v4d z0, dz1, dz2, zmin, zmax;
} SR_SIMD_FN(ms4);

SR_SIMD_TARGET SR_INLINE void SR_SIMD_FN(ms4_pixel)(void *arg, int px, int py, const int64_t *u,
                                                    bool inside)
{
    const SR_SIMD_FN(ms4) *k = arg;
    const sr_draw_state *ds = k->ds;
    v4d e[3];
    for (int i = 0; i < 3; i++) {
        e[i] = (double)u[i] + k->so[i];
    }
    v4l cov = { -1, -1, -1, -1 };
    if (!inside) {
        cov = (e[0] >= k->nbias[0]) & (e[1] >= k->nbias[1]) & (e[2] >= k->nbias[2]);
        if (!(cov[0] | cov[1] | cov[2] | cov[3])) {
            return;
        }
    }
    v4d z = k->z0 + e[1] * k->dz1 + e[2] * k->dz2;
    if (!k->t->z_inside) {
        z = (v4d)SR_SIMD_FN(ms4_sel)((v4l)(z >= k->zmin), (v4l)z, (v4l)k->zmin);
        z = (v4d)SR_SIMD_FN(ms4_sel)((v4l)(z <= k->zmax), (v4l)z, (v4l)k->zmax);
    }
    /* Non-negative and below 2^24: truncation is the scalar (uint32_t) cast. */
    v4i q = __builtin_convertvector(z + 0.5, v4i);
    size_t base = ((size_t)py * (size_t)ds->fb->width + (size_t)px) * 4;
    v4i pass = sr__depth_less4(ds->fb, base, q, __builtin_convertvector(cov, v4i));
    if (!(pass[0] | pass[1] | pass[2] | pass[3])) {
        return;
    }
    /* Shading once per pixel, at its centre. */
    float c[4];
    shade_centre(ds, k->t, u, c);
    uint8_t rgba[4];
    for (int j = 0; j < 4; j++) {
        rgba[j] = sr__unorm8(c[j]);
    }
    int32_t packed;
    memcpy(&packed, rgba, sizeof packed);
    uint32_t *cp = &ds->fb->color[base];
    v4i old;
    memcpy(&old, cp, sizeof old);
    v4i out = (pass & packed) | (~pass & old);
    memcpy(cp, &out, sizeof out);
    k->st->fragments += (uint64_t)(-(pass[0] + pass[1] + pass[2] + pass[3]));
}

SR_SIMD_TARGET static void SR_SIMD_FN(raster_ms4)(const sr_draw_state *ds, const sr_tri *t,
                                                  int rx0, int ry0, int rx1, int ry1,
                                                  sr_frag_stats *st)
{
    SR_SIMD_FN(ms4) k = { .ds = ds, .t = t, .st = st };
    for (int i = 0; i < 3; i++) {
        for (int s = 0; s < 4; s++) {
            k.so[i][s] = (double)((int64_t)t->a[i] * ds->sample_off[s][0] +
                                  (int64_t)t->b[i] * ds->sample_off[s][1]);
            k.nbias[i][s] = (double)-sr__tri_bias(t, i);
        }
    }
    k.z0 = (v4d){ t->z0, t->z0, t->z0, t->z0 };
    k.dz1 = (v4d){ t->dz1, t->dz1, t->dz1, t->dz1 };
    k.dz2 = (v4d){ t->dz2, t->dz2, t->dz2, t->dz2 };
    k.zmin = (v4d){ ds->zq_min, ds->zq_min, ds->zq_min, ds->zq_min };
    k.zmax = (v4d){ ds->zq_max, ds->zq_max, ds->zq_max, ds->zq_max };
    sr__msaa_walk(ds, t, rx0, ry0, rx1, ry1, &k, SR_SIMD_FN(ms4_pixel));
}
