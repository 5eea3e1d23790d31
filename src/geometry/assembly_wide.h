/* assembly_wide.h - assembly and setup of sixteen triangles at a time
 * (geometry stage, front-end workers, AVX-512 only).  Included by
 * assembly.c, whose triangle() it stands in for on a list of triangles
 * without indices in the common state (sr_draw_state.triangles16: filled,
 * four interpolated varyings, no flat varyings or FLAT shading, one
 * sample, no polygon offset).
 *
 * A million triangles of a few pixels each spend as much in the front end
 * as in the kernel, and triangle() with sr__setup_tri took about 400
 * instructions for each (stepped with gdb), mostly moving one triangle's
 * values between registers and the stack.  Here the outcodes, the snapped
 * area, facing and culling, the bounding box, the edge coefficients, the
 * 32-bit check and the depth plane are worked out in sixteen lanes, one
 * triangle a lane, and each record is then written from those lanes in
 * submission order.  A triangle with a vertex outside a clip plane (or
 * not finite) goes through triangle() at its place in the order.
 *
 * Exactness: the same operations as sr__setup_tri, lane by lane.  The
 * snapped area, an int64 there, is a difference of two products of
 * coordinate differences below 2^24 (fixed.h), so below 2^49 and exact in
 * double here; min and max of depths are minpd and maxpd, which return
 * their second operand unless the first is smaller (larger), as sr__min_d
 * and sr__max_d do. */

/* The byte offsets from `post` of the field at byte `at` of vertex v of
 * each of sixteen triangles whose vertices follow one another. */
SR_TARGET_AVX512 static inline __m512i wide_offsets(int v, size_t at)
{
    const __m512i tri = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    __m512i vertex = _mm512_add_epi32(_mm512_mullo_epi32(tri, _mm512_set1_epi32(3)),
                                      _mm512_set1_epi32(v));
    __m512i size = _mm512_set1_epi32((int)sizeof(sr_vertex_post));
    return _mm512_add_epi32(_mm512_mullo_epi32(vertex, size), _mm512_set1_epi32((int)at));
}

/* One 32-bit field (at byte `at` of sr_vertex_post) of vertex v of the
 * sixteen triangles. */
SR_TARGET_AVX512 static inline __m512i wide_field(const sr_vertex_post *post, int v, size_t at)
{
    return _mm512_i32gather_epi32(wide_offsets(v, at), post, 1);
}

/* The depths of vertex v of the sixteen triangles, in two halves. */
SR_TARGET_AVX512 static inline void wide_depth(const sr_vertex_post *post, int v, __m512d z[2])
{
    __m512i at = wide_offsets(v, offsetof(sr_vertex_post, z));
    z[0] = _mm512_i32gather_pd(_mm512_castsi512_si256(at), post, 1);
    z[1] = _mm512_i32gather_pd(_mm512_extracti64x4_epi64(at, 1), post, 1);
}

/* Sixteen int32 lanes as two halves of doubles (exact). */
SR_TARGET_AVX512 static inline void wide_to_d(__m512i v, __m512d d[2])
{
    d[0] = _mm512_cvtepi32_pd(_mm512_castsi512_si256(v));
    d[1] = _mm512_cvtepi32_pd(_mm512_extracti64x4_epi64(v, 1));
}

/* What the lanes leave for each triangle's record, lane l of each field. */
typedef struct wide_tris {
    int32_t x0[16], y0[16], x1[16], y1[16];
    int32_t a[3][16], b[3][16], vx[16], vy[16];
    float w[3][16];
    double z0[16], dz1[16], dz2[16];
    unsigned culled, drawn, front, z_inside, fits32, swapped, clipped;
} wide_tris;

/* Triangles first / 3 .. first / 3 + 15 of a list without indices: their
 * vertices are first .. first + 47, in vs. */
SR_TARGET_AVX512 static void triangles16(const sr_front_end *fe, sr_chunk *c,
                                         const sr_vertex_src *vs, uint32_t first)
{
    const sr_draw_state *ds = fe->ds;
    const sr_vertex_post *post = vs->post + (first - vs->base);
    wide_tris o;

    __m512i oc = _mm512_or_si512(
        _mm512_or_si512(wide_field(post, 0, offsetof(sr_vertex_post, outcode)),
                        wide_field(post, 1, offsetof(sr_vertex_post, outcode))),
        wide_field(post, 2, offsetof(sr_vertex_post, outcode)));
    __mmask16 inside = _mm512_cmpeq_epi32_mask(oc, _mm512_setzero_si512());
    o.clipped = (unsigned)(__mmask16)~inside;
    __m512i X[3], Y[3];
    __m512 IW[3];
    __m512d Z[3][2];
    for (int v = 0; v < 3; v++) {
        X[v] = wide_field(post, v, offsetof(sr_vertex_post, x_q8));
        Y[v] = wide_field(post, v, offsetof(sr_vertex_post, y_q8));
        IW[v] = _mm512_castsi512_ps(wide_field(post, v, offsetof(sr_vertex_post, inv_w)));
        wide_depth(post, v, Z[v]);
    }

    /* sr__area2: (x1 - x0)(y2 - y0) - (y1 - y0)(x2 - x0). */
    __m512d dx1[2], dy2[2], dy1[2], dx2[2];
    wide_to_d(_mm512_sub_epi32(X[1], X[0]), dx1);
    wide_to_d(_mm512_sub_epi32(Y[2], Y[0]), dy2);
    wide_to_d(_mm512_sub_epi32(Y[1], Y[0]), dy1);
    wide_to_d(_mm512_sub_epi32(X[2], X[0]), dx2);
    __m512d area[2];
    __mmask16 neg = 0, pos = 0;
    for (int h = 0; h < 2; h++) {
        area[h] = _mm512_sub_pd(_mm512_mul_pd(dx1[h], dy2[h]), _mm512_mul_pd(dy1[h], dx2[h]));
        neg |= (__mmask16)(_mm512_cmp_pd_mask(area[h], _mm512_setzero_pd(), _CMP_LT_OQ) << 8 * h);
        pos |= (__mmask16)(_mm512_cmp_pd_mask(area[h], _mm512_setzero_pd(), _CMP_GT_OQ) << 8 * h);
        area[h] = _mm512_abs_pd(area[h]);
    }
    /* facing_front and is_culled. */
    __mmask16 front = ds->front_ccw ? neg : pos;
    __mmask16 culled = (__mmask16)~(neg | pos);
    switch (ds->cull) {
    case SR_CULL_BACK:           culled |= (__mmask16)~front; break;
    case SR_CULL_FRONT:          culled |= front; break;
    case SR_CULL_FRONT_AND_BACK: culled = 0xffff; break;
    default:                     break;
    }
    o.culled = inside & culled;
    o.front = front;

    /* Coverage needs area2 > 0: swap vertices 1 and 2 where it is not. */
    o.swapped = neg;
    __m512i x1 = _mm512_mask_blend_epi32(neg, X[1], X[2]);
    __m512i x2 = _mm512_mask_blend_epi32(neg, X[2], X[1]);
    __m512i y1 = _mm512_mask_blend_epi32(neg, Y[1], Y[2]);
    __m512i y2 = _mm512_mask_blend_epi32(neg, Y[2], Y[1]);
    X[1] = x1, X[2] = x2, Y[1] = y1, Y[2] = y2;
    __m512 w1 = _mm512_mask_blend_ps(neg, IW[1], IW[2]);
    __m512 w2 = _mm512_mask_blend_ps(neg, IW[2], IW[1]);
    IW[1] = w1, IW[2] = w2;
    for (int h = 0; h < 2; h++) {
        __mmask8 n = (__mmask8)(neg >> 8 * h);
        __m512d z1 = _mm512_mask_blend_pd(n, Z[1][h], Z[2][h]);
        __m512d z2 = _mm512_mask_blend_pd(n, Z[2][h], Z[1][h]);
        Z[1][h] = z1, Z[2][h] = z2;
    }

    /* The bounding box of pixel centres, trimmed to the drawing rectangle. */
    __m512i minx = _mm512_min_epi32(X[0], _mm512_min_epi32(X[1], X[2]));
    __m512i maxx = _mm512_max_epi32(X[0], _mm512_max_epi32(X[1], X[2]));
    __m512i miny = _mm512_min_epi32(Y[0], _mm512_min_epi32(Y[1], Y[2]));
    __m512i maxy = _mm512_max_epi32(Y[0], _mm512_max_epi32(Y[1], Y[2]));
    const __m512i half = _mm512_set1_epi32(SR_SUBPIXEL_HALF), one = _mm512_set1_epi32(1);
    /* sr__ceil_q8(min - 128) = -((128 - min) >> 8), sr__floor_q8(max - 128) + 1. */
    const __m512i izero = _mm512_setzero_si512();
    const unsigned q8 = SR_SUBPIXEL_BITS;
    __m512i bx0 = _mm512_sub_epi32(izero, _mm512_srai_epi32(_mm512_sub_epi32(half, minx), q8));
    __m512i by0 = _mm512_sub_epi32(izero, _mm512_srai_epi32(_mm512_sub_epi32(half, miny), q8));
    __m512i bx1 = _mm512_add_epi32(_mm512_srai_epi32(_mm512_sub_epi32(maxx, half), q8), one);
    __m512i by1 = _mm512_add_epi32(_mm512_srai_epi32(_mm512_sub_epi32(maxy, half), q8), one);
    bx0 = _mm512_max_epi32(bx0, _mm512_set1_epi32(ds->rect_x0));
    by0 = _mm512_max_epi32(by0, _mm512_set1_epi32(ds->rect_y0));
    bx1 = _mm512_min_epi32(bx1, _mm512_set1_epi32(ds->rect_x1));
    by1 = _mm512_min_epi32(by1, _mm512_set1_epi32(ds->rect_y1));
    __mmask16 box = _mm512_cmplt_epi32_mask(bx0, bx1) & _mm512_cmplt_epi32_mask(by0, by1);
    o.drawn = inside & ~culled & box;
    _mm512_storeu_si512(o.x0, bx0);
    _mm512_storeu_si512(o.y0, by0);
    _mm512_storeu_si512(o.x1, bx1);
    _mm512_storeu_si512(o.y1, by1);

    /* Edge i from vertex i + 1 to i + 2: a = -(dy), b = dx. */
    for (int i = 0; i < 3; i++) {
        int p = (i + 1) % 3, q = (i + 2) % 3;
        _mm512_storeu_si512(o.a[i], _mm512_sub_epi32(Y[p], Y[q]));
        _mm512_storeu_si512(o.b[i], _mm512_sub_epi32(X[q], X[p]));
    }
    _mm512_storeu_si512(o.vx, X[0]);
    _mm512_storeu_si512(o.vy, Y[0]);

    /* fits32: the spans (each held below 2^24) multiply to at most
     * INT32_MAX - 1; their product, below 2^48, is exact in double. */
    const __m512i held = _mm512_set1_epi32(1 << 24), unit = _mm512_set1_epi32(SR_SUBPIXEL_ONE);
    __m512d sx[2], sy[2];
    wide_to_d(_mm512_min_epi32(_mm512_add_epi32(_mm512_sub_epi32(maxx, minx), unit), held), sx);
    wide_to_d(_mm512_min_epi32(_mm512_add_epi32(_mm512_sub_epi32(maxy, miny), unit), held), sy);
    __mmask16 fits = 0;
    for (int h = 0; h < 2; h++) {
        fits |= (__mmask16)(_mm512_cmp_pd_mask(_mm512_mul_pd(sx[h], sy[h]),
                                               _mm512_set1_pd((double)(INT32_MAX - 1)), _CMP_LE_OQ)
                            << 8 * h);
    }
    o.fits32 = fits;

    /* The depth plane in buffer units, no polygon offset (offset 0). */
    double scale = ds->depth_scale;
    const __m512d vscale = _mm512_set1_pd(scale), zero = _mm512_setzero_pd();
    const __m512d lo = _mm512_set1_pd(ds->zq_min + 1e-9 * scale);
    const __m512d hi = _mm512_set1_pd(ds->zq_max - 1e-9 * scale);
    __mmask16 zin = 0;
    for (int h = 0; h < 2; h++) {
        __m512d z0 = _mm512_mul_pd(_mm512_add_pd(Z[0][h], zero), vscale);
        __m512d zlo = _mm512_add_pd(_mm512_min_pd(Z[0][h], _mm512_min_pd(Z[1][h], Z[2][h])), zero);
        __m512d zhi = _mm512_add_pd(_mm512_max_pd(Z[0][h], _mm512_max_pd(Z[1][h], Z[2][h])), zero);
        zin |= (__mmask16)((_mm512_cmp_pd_mask(_mm512_mul_pd(zlo, vscale), lo, _CMP_GT_OQ) &
                            _mm512_cmp_pd_mask(_mm512_mul_pd(zhi, vscale), hi, _CMP_LT_OQ))
                           << 8 * h);
        __m512d per_area = _mm512_div_pd(vscale, area[h]);
        _mm512_storeu_pd(&o.z0[8 * h], z0);
        _mm512_storeu_pd(&o.dz1[8 * h], _mm512_mul_pd(_mm512_sub_pd(Z[1][h], Z[0][h]), per_area));
        _mm512_storeu_pd(&o.dz2[8 * h], _mm512_mul_pd(_mm512_sub_pd(Z[2][h], Z[0][h]), per_area));
    }
    o.z_inside = zin;
    for (int v = 0; v < 3; v++) {
        _mm512_storeu_ps(o.w[v], ds->perspective ? IW[v] : _mm512_set1_ps(1.0f));
    }

    /* The records, in submission order. */
    size_t nv = (size_t)ds->nvary;
    bool last = ds->provoking_last;
    for (int l = 0; l < 16; l++) {
        if (c->out_of_memory) {
            return;
        }
        uint32_t i0 = first + 3 * (uint32_t)l;
        if (o.clipped >> l & 1) {
            triangle(fe, c, vs, i0, i0 + 1, i0 + 2, last ? i0 + 2 : i0);
            continue;
        }
        c->info.triangles_in++;
        if (o.culled >> l & 1) {
            c->info.triangles_culled++;
            continue;
        }
        if (!(o.drawn >> l & 1)) {
            continue; /* between pixel centres: setup finds nothing to draw */
        }
        sr_tri *rec = next_record(fe, c);
        if (!rec) {
            return;
        }
        record_buf buf;
        sr_tri *t = c->stream ? &buf.tri : rec;
        t->h.kind = SR_KIND_TRIANGLE;
        t->h.x0 = (int16_t)o.x0[l];
        t->h.y0 = (int16_t)o.y0[l];
        t->h.x1 = (int16_t)o.x1[l];
        t->h.y1 = (int16_t)o.y1[l];
        t->ninterp = 4;
        t->front = o.front >> l & 1;
        t->z_inside = o.z_inside >> l & 1;
        t->fits32 = o.fits32 >> l & 1;
        for (int i = 0; i < 3; i++) {
            t->a[i] = o.a[i][l];
            t->b[i] = o.b[i][l];
            t->w[i] = o.w[i][l];
        }
        t->x0_q8 = o.vx[l];
        t->y0_q8 = o.vy[l];
        t->z0 = o.z0[l];
        t->dz1 = o.dz1[l];
        t->dz2 = o.dz2[l];
        /* The varyings of vertex 0 and the differences to vertices 1 and
         * 2, as sr__setup_tri's four-lane step. */
        const float *v0 = vs->vary + (i0 - vs->base) * nv;
        const float *v1 = v0 + nv, *v2 = v0 + 2 * nv;
        if (o.swapped >> l & 1) {
            const float *s = v1;
            v1 = v2;
            v2 = s;
        }
        __m128 a0 = _mm_loadu_ps(v0);
        _mm_storeu_ps(&t->vary[0], a0);
        _mm_storeu_ps(&t->vary[4], _mm_sub_ps(_mm_loadu_ps(v1), a0));
        _mm_storeu_ps(&t->vary[8], _mm_sub_ps(_mm_loadu_ps(v2), a0));
        if (c->stream) {
            sr__stream_record(rec, t, fe->tri_size);
        }
        keep_record(c, &t->h);
        c->info.triangles_drawn++;
    }
}
