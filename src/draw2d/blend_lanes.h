/* blend_lanes.h - draw2d stage, internal to paint.c: the flat-color
 * blend of sr__paint_pixel (without linear light) on BL_LANES pixels at
 * once, in GCC/Clang vector extensions.  Included once per width with
 * BL_LANES, the types BL_F (float lanes), BL_I (their masks), BL_U
 * (packed pixels), BL_WIDEN(ptr) (BL_LANES coverage bytes loaded as
 * BL_U), BL_FN(name), BL_INLINE
 * (which carries the target attribute of the width), BL_ALL(mask) and
 * BL_ANY(mask) (true when every lane, any lane, of a BL_I mask is set)
 * defined, and BL_TABLE_ROW (the table's whole blocks at this width,
 * where it has them); it undefines them at its end.  The same
 * float operations in the same order as the scalar blend, lane by lane:
 * the same bytes at every width. */

BL_INLINE BL_F BL_FN(splat)(float v)
{
    return (BL_F){ 0 } + v;
}

BL_INLINE BL_F BL_FN(select)(BL_I m, BL_F a, BL_F b)
{
    return (BL_F)((m & (BL_I)a) | (~m & (BL_I)b));
}

BL_INLINE BL_F BL_FN(channel)(BL_U px, int k)
{
    return __builtin_convertvector((px >> CHANNEL_SHIFT(k)) & 0xff, BL_F);
}

/* sr__unorm8 lane by lane, placed at channel k. */
BL_INLINE BL_U BL_FN(unorm8)(BL_F v, int k)
{
    BL_I inside = (v > 0.0f) & (v < 1.0f);
    BL_F safe = BL_FN(select)(inside, v, BL_FN(splat)(0.0f));
    BL_U q = (BL_U)__builtin_convertvector(safe * 255.0f + 0.5f, BL_I);
    q = ((BL_U)inside & q) | ((BL_U)(v >= 1.0f) & 255);
    return q << CHANNEL_SHIFT(k);
}

/* sr__paint_pixel on the pixels d with coverages c (0..255).  Both blends
 * (over an opaque and over a translucent pixel) are computed and each
 * lane keeps its own; lanes that keep no quotient divide by 1. */
BL_INLINE BL_U BL_FN(blend)(const sr__paint *p, BL_U d, BL_U c)
{
    BL_F zero = BL_FN(splat)(0.0f);
    BL_F a = BL_FN(splat)(p->alpha) * __builtin_convertvector(c, BL_F) * (1.0f / 255.0f);
    BL_I full = ((BL_I)(c >= 255) & (p->alpha >= 1.0f ? -1 : 0)) | (a >= 1.0f);
    BL_I none = (BL_I)(c == 0) | (a <= 0.0f);
    BL_F da = BL_FN(channel)(d, 3) * (1.0f / 255.0f), keep = 1.0f - a, oa = a + da * keep;
    BL_I translucent = (BL_I)(((d >> CHANNEL_SHIFT(3)) & 0xff) < 255), pos = oa > 0.0f;
    if (BL_ANY(translucent)) { /* over opaque pixels only, no lane divides */
        BL_F div = BL_FN(select)(pos, oa, BL_FN(splat)(1.0f));
        keep = BL_FN(select)(translucent, BL_FN(select)(pos, da * keep / div, zero), keep);
        a = BL_FN(select)(translucent, BL_FN(select)(pos, a / div, zero), a);
    }
    BL_U out = BL_FN(unorm8)(oa, 3);
    for (int k = 0; k < 3; k++) {
        BL_F v = (BL_FN(splat)((float)p->rgba[k]) * a + BL_FN(channel)(d, k) * keep) *
                 (1.0f / 255.0f);
        out |= BL_FN(unorm8)(v, k);
    }
    out = ((BL_U)none & d) | (~(BL_U)none & out);
    return ((BL_U)full & p->packed) | (~(BL_U)full & out);
}

#ifdef BL_TABLE_ROW
/* Whether m's table of the blend over opaque pixels at full coverage is
 * there, making it (from the lanes' blend of the grey pixels (v, v, v,
 * 255)) once the fill has met SR__BLEND_TABLE_AFTER such pixels: a small
 * fill never pays for it. */
BL_INLINE bool BL_FN(table_ready)(const sr__paint *p, sr__blend_memo *m)
{
    if (m->table_wait == SR__BLEND_TABLE_NEVER) {
        return false;
    }
    if (m->table_wait >= 0) {
        m->table_wait -= BL_LANES;
        if (m->table_wait >= 0) {
            return false;
        }
        for (int v = 0; v < 256; v += BL_LANES) {
            BL_U d;
            for (int j = 0; j < BL_LANES; j++) {
                uint32_t g = (uint32_t)(v + j);
                d[j] = g << CHANNEL_SHIFT(0) | g << CHANNEL_SHIFT(1) | g << CHANNEL_SHIFT(2) |
                       255u << CHANNEL_SHIFT(3);
            }
            d = BL_FN(blend)(p, d, (BL_U){ 0 } + 255);
            for (int j = 0; j < BL_LANES; j++) {
                for (int k = 0; k < 3; k++) {
                    m->table[k][v + j] = (uint8_t)(d[j] >> CHANNEL_SHIFT(k));
                }
            }
            m->table_alpha = (uint8_t)ALPHA_BYTE(d[0]);
        }
    }
    return true;
}
#endif

/* The whole blocks of dst[0..n), BL_LANES pixels each; returns how many
 * pixels were blended.  A block of one pixel and one coverage takes the
 * last result when they are the last pair (*in, *last_cov -> *out) and
 * the memo's otherwise; a run of blocks of opaque pixels at full coverage
 * takes the memo's table (BL_TABLE_ROW) once it is there; any other block
 * takes the lanes' blend.  m may be NULL (no memo, no table). */
BL_INLINE int BL_FN(blend_row)(const sr__paint *p, sr__blend_memo *m, uint32_t *dst,
                               const uint8_t *cov, int n, uint32_t *in, unsigned *last_cov,
                               uint32_t *out)
{
    int i = 0;
    while (i + BL_LANES <= n) {
        BL_U d, c = (BL_U){ 0 } + 255;
        memcpy(&d, dst + i, sizeof d);
        if (cov) {
            c = BL_WIDEN(cov + i);
        }
        BL_I same = (BL_I)(d == (BL_U){ 0 } + d[0]) & (BL_I)(c == (BL_U){ 0 } + c[0]);
#ifdef BL_TABLE_ROW
        if (!BL_ALL(same) && m && BL_ALL((BL_I)(c == 255) & (BL_I)(ALPHA_BYTE(d) == 255)) &&
            BL_FN(table_ready)(p, m)) {
            i += BL_TABLE_ROW(m, dst + i, cov ? cov + i : NULL, n - i);
            continue;
        }
#endif
        if (BL_ALL(same)) {
            if (d[0] != *in || c[0] != *last_cov) {
                *in = d[0];
                *last_cov = c[0];
                *out = memo_blend(p, m, *in, *last_cov);
            }
            d = (BL_U){ 0 } + *out;
        } else {
            d = BL_FN(blend)(p, d, c);
        }
        memcpy(dst + i, &d, sizeof d);
        i += BL_LANES;
    }
    return i;
}

#undef BL_LANES
#undef BL_F
#undef BL_I
#undef BL_U
#undef BL_WIDEN
#undef BL_FN
#undef BL_INLINE
#undef BL_ALL
#undef BL_ANY
#undef BL_TABLE_ROW
