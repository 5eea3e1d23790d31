/*
 * face_lanes.h - the visibility pass's first look at its faces, eight at
 * a time in AVX2 lanes (included by visibility.c, which calls it where
 * the draw state's SIMD level allows and no vertex is outside a clip
 * plane).  Most faces of a dense mesh cover no pixel centre or face
 * away: here their vertices' window positions are gathered, and their
 * boxes of pixel centres, snapped areas and culling, and for a box of at
 * most 2 x 2 centres the edge test at each centre, are worked out one
 * face a lane, so that only the faces these leave go through the scalar
 * code, which decides their coverage exactly.
 *
 * Exactness: the lanes only drop a face the scalar code would drop.  The
 * box is find_candidates's (the smallest ceiling and largest floor of
 * the vertices' positions less half a pixel, as setup's).  For a face
 * less than 2^14 across (64 pixels), its snapped area and its edge
 * values at its box's centres are differences of products below 2^30,
 * exact in int32 lanes; a larger face is left to the scalar code.  A
 * face is dropped for no centre in the closed half-planes of its three
 * edges, which the fill rule and the depth test only narrow.
 */
#if defined(__x86_64__) && defined(__GNUC__)
#define SR_PY_FACE_LANES 1

#include <immintrin.h>

/* The window positions are gathered by a 32-bit index in int32 units:
 * vertex v's x at 4 v. */
_Static_assert(sizeof(window_vertex) == 4 * sizeof(int32_t), "window_vertex is 16 bytes");
#define FACE_LANES_MAX_VERTICES ((size_t)1 << 29)

/* Vertex c of faces f .. f + 7 of instance u, numbered from `base`. */
__attribute__((target("avx2"))) static inline __m256i lane_vertices(const geometry_uniforms *u,
                                                                    size_t f, int c,
                                                                    uint32_t base)
{
    const __m256i stride = _mm256_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21);
    __m256i v;
    if (u->faces64) {
        /* Indices below the vertex count: their low halves. */
        const long long *p = (const long long *)u->faces + 3 * f + c;
        const __m256i low = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
        __m256i a = _mm256_i32gather_epi64(p, _mm256_castsi256_si128(stride), 8);
        __m256i b = _mm256_i32gather_epi64(p, _mm256_extracti128_si256(stride, 1), 8);
        v = _mm256_permute2x128_si256(_mm256_permutevar8x32_epi32(a, low),
                                      _mm256_permutevar8x32_epi32(b, low), 0x20);
    } else {
        v = _mm256_i32gather_epi32((const int *)u->faces + 3 * f + c, stride, 4);
    }
    return _mm256_add_epi32(v, _mm256_set1_epi32((int)base));
}

/* The lanes of an int32 comparison as eight bits. */
__attribute__((target("avx2"))) static inline unsigned lane_bits(__m256i m)
{
    return (unsigned)_mm256_movemask_ps(_mm256_castsi256_ps(m));
}

/* Faces [lo, hi) of instance `inst`, none with a vertex outside a clip
 * plane: those that may cover a pixel centre, into out[] as
 * find_candidates writes them (which takes the last hi - lo mod 8); their
 * number. */
__attribute__((target("avx2"))) static long find_candidates_lanes(const vis_job *j, size_t inst,
                                                                   size_t lo, size_t hi,
                                                                   candidate *out)
{
    const sr_draw_state *ds = j->ds;
    const geometry_uniforms *u = &j->u[inst];
    size_t first = j->first_face[inst];
    uint32_t base = (uint32_t)j->first_vertex[inst];
    const __m256i half = _mm256_set1_epi32(SR_SUBPIXEL_HALF), one = _mm256_set1_epi32(1);
    const __m256i two = _mm256_set1_epi32(2), zero = _mm256_setzero_si256();
    const __m256i rx0 = _mm256_set1_epi32(ds->rect_x0 > INT16_MIN ? ds->rect_x0 : INT16_MIN);
    const __m256i ry0 = _mm256_set1_epi32(ds->rect_y0 > INT16_MIN ? ds->rect_y0 : INT16_MIN);
    const __m256i rx1 = _mm256_set1_epi32(ds->rect_x1 < INT16_MAX ? ds->rect_x1 : INT16_MAX);
    const __m256i ry1 = _mm256_set1_epi32(ds->rect_y1 < INT16_MAX ? ds->rect_y1 : INT16_MAX);
    int cull_sign = u->cull_sign;
    long n = 0;
    size_t g = lo;
    for (; g + 8 <= hi; g += 8) {
        __m256i V[3], X[3], Y[3];
        for (int c = 0; c < 3; c++) {
            V[c] = lane_vertices(u, g - first, c, base);
            __m256i at = _mm256_slli_epi32(V[c], 2);
            X[c] = _mm256_i32gather_epi32((const int *)j->win, at, 4);
            Y[c] = _mm256_i32gather_epi32((const int *)j->win + 1, at, 4);
        }
        /* The box: sr__ceil_q8(min - half) = -((half - min) >> 8) and
         * sr__floor_q8(max - half) + 1, trimmed to the drawing rectangle. */
        __m256i minx = _mm256_min_epi32(X[0], _mm256_min_epi32(X[1], X[2]));
        __m256i maxx = _mm256_max_epi32(X[0], _mm256_max_epi32(X[1], X[2]));
        __m256i miny = _mm256_min_epi32(Y[0], _mm256_min_epi32(Y[1], Y[2]));
        __m256i maxy = _mm256_max_epi32(Y[0], _mm256_max_epi32(Y[1], Y[2]));
        __m256i x0 = _mm256_sub_epi32(zero, _mm256_srai_epi32(_mm256_sub_epi32(half, minx),
                                                              SR_SUBPIXEL_BITS));
        __m256i y0 = _mm256_sub_epi32(zero, _mm256_srai_epi32(_mm256_sub_epi32(half, miny),
                                                              SR_SUBPIXEL_BITS));
        __m256i x1 = _mm256_add_epi32(_mm256_srai_epi32(_mm256_sub_epi32(maxx, half),
                                                        SR_SUBPIXEL_BITS), one);
        __m256i y1 = _mm256_add_epi32(_mm256_srai_epi32(_mm256_sub_epi32(maxy, half),
                                                        SR_SUBPIXEL_BITS), one);
        x0 = _mm256_max_epi32(x0, rx0);
        y0 = _mm256_max_epi32(y0, ry0);
        x1 = _mm256_min_epi32(x1, rx1);
        y1 = _mm256_min_epi32(y1, ry1);
        __m256i w = _mm256_sub_epi32(x1, x0), h = _mm256_sub_epi32(y1, y0);
        unsigned keep = lane_bits(_mm256_and_si256(_mm256_cmpgt_epi32(w, zero),
                                                   _mm256_cmpgt_epi32(h, zero)));
        if (keep == 0) {
            continue;
        }
        /* The box's centres that are tested here, and the boxes too large
         * for that, kept for the scalar code. */
        unsigned wide = lane_bits(_mm256_cmpgt_epi32(w, one));
        unsigned tall = lane_bits(_mm256_cmpgt_epi32(h, one));
        unsigned large = lane_bits(_mm256_or_si256(_mm256_cmpgt_epi32(w, two),
                                                   _mm256_cmpgt_epi32(h, two)));
        /* Faces less than 2^14 across in x and y, whose snapped area
         * and edge values at the box's centres (at most a pixel outside
         * it) are below 2^30 and exact in int32 lanes; the others are
         * left to the scalar code. */
        __m256i across = _mm256_max_epi32(_mm256_sub_epi32(maxx, minx),
                                          _mm256_sub_epi32(maxy, miny));
        unsigned near = lane_bits(_mm256_cmpgt_epi32(_mm256_set1_epi32(1 << 14), across));
        /* Edge i, from vertex i + 1 to vertex i + 2: b - a. */
        __m256i ex[3], ey[3];
        for (int i = 0; i < 3; i++) {
            ex[i] = _mm256_sub_epi32(X[(i + 2) % 3], X[(i + 1) % 3]);
            ey[i] = _mm256_sub_epi32(Y[(i + 2) % 3], Y[(i + 1) % 3]);
        }
        /* sr__area2, (x1 - x0)(y2 - y0) - (y1 - y0)(x2 - x0), from edge
         * 2 (v0 to v1) and edge 1 (v2 to v0). */
        __m256i area = _mm256_sub_epi32(_mm256_mullo_epi32(ey[2], ex[1]),
                                        _mm256_mullo_epi32(ex[2], ey[1]));
        unsigned pos = lane_bits(_mm256_cmpgt_epi32(area, zero));
        unsigned neg = lane_bits(_mm256_cmpgt_epi32(zero, area));
        /* Culled as faces_job culls: no area, or area2 * cull_sign > 0.
         * Neighbouring faces of a mesh mostly face the same way, so
         * eight culled at once are common and the branch predictable. */
        unsigned culled = ~(pos | neg) | (cull_sign > 0 ? pos : cull_sign < 0 ? neg : 0u);
        keep &= ~near | ~culled;
        if (keep == 0) {
            continue;
        }
        /* may_pass's edge values, turned to the face's winding, at the
         * box's first centre, a pixel right and a pixel down. */
        __m256i cx = _mm256_add_epi32(_mm256_slli_epi32(x0, SR_SUBPIXEL_BITS), half);
        __m256i cy = _mm256_add_epi32(_mm256_slli_epi32(y0, SR_SUBPIXEL_BITS), half);
        __m256i in[4];
        for (int c = 0; c < 4; c++) {
            in[c] = _mm256_set1_epi32(-1);
        }
        for (int i = 0; i < 3; i++) {
            __m256i dx = _mm256_sign_epi32(ex[i], area), dy = _mm256_sign_epi32(ey[i], area);
            __m256i a = i == 2 ? X[0] : X[i + 1], b = i == 2 ? Y[0] : Y[i + 1];
            __m256i e = _mm256_sub_epi32(_mm256_mullo_epi32(dx, _mm256_sub_epi32(cy, b)),
                                         _mm256_mullo_epi32(dy, _mm256_sub_epi32(cx, a)));
            __m256i right = _mm256_slli_epi32(dy, SR_SUBPIXEL_BITS);
            __m256i down = _mm256_slli_epi32(dx, SR_SUBPIXEL_BITS);
            __m256i at[4] = { e, _mm256_sub_epi32(e, right), _mm256_add_epi32(e, down),
                              _mm256_sub_epi32(_mm256_add_epi32(e, down), right) };
            for (int c = 0; c < 4; c++) {
                in[c] = _mm256_and_si256(in[c], _mm256_cmpgt_epi32(at[c], _mm256_set1_epi32(-1)));
            }
        }
        unsigned hit = lane_bits(in[0]) | (lane_bits(in[1]) & wide) | (lane_bits(in[2]) & tall) |
                       (lane_bits(in[3]) & wide & tall);
        keep &= ~near | large | hit;
        if (keep == 0) {
            continue;
        }
        int32_t lane[7][8];
        _mm256_storeu_si256((__m256i *)lane[0], V[0]);
        _mm256_storeu_si256((__m256i *)lane[1], V[1]);
        _mm256_storeu_si256((__m256i *)lane[2], V[2]);
        _mm256_storeu_si256((__m256i *)lane[3], x0);
        _mm256_storeu_si256((__m256i *)lane[4], x1);
        _mm256_storeu_si256((__m256i *)lane[5], y0);
        _mm256_storeu_si256((__m256i *)lane[6], y1);
        for (; keep; keep &= keep - 1) {
            int l = __builtin_ctz(keep);
            out[n++] = (candidate){ (uint32_t)(g + (size_t)l),
                                    { (uint32_t)lane[0][l], (uint32_t)lane[1][l],
                                      (uint32_t)lane[2][l] },
                                    (int16_t)lane[3][l], (int16_t)lane[4][l],
                                    (int16_t)lane[5][l], (int16_t)lane[6][l] };
        }
    }
    return n + find_candidates(j, inst, g, hi, false, out + n);
}
#endif
