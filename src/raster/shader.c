/* shader.c - triangles, lines and points through a program's fragment
 * shader (raster and fragment stages, tile workers).
 *
 * Triangles go by 2x2 quads: the quad's four lanes are interpolated from
 * the exact edge values at their pixel centres (helper lanes outside the
 * triangle too, so lane differences are derivatives), the shader runs once
 * per quad, and each lane's color goes to its pixel's surviving samples.
 * A program whose lanes are independent gets full calls instead: the
 * triangle's surviving fragments, quad after quad, four to a call (each
 * lane interpolated as its own, so the same bits as in its quad).
 * Depth and stencil are tested before the shader (early, so hidden
 * fragments cost no shading) unless the program writes depth or may
 * discard, or alpha to coverage needs the shaded alpha: then after it,
 * as the GL order of operations says. */
#include "fragment/msaa_ops.h"
#include "raster/depth_lanes.h"
#include "raster/msaa_walk.h"
#include "simd_types.h"

#include <string.h>

typedef struct quad_job {
    const sr_draw_state *ds;
    const sr_tri *t;
    sr_frag_stats *st;
    bool early;                   /* tests before shading */
    bool writes_color;            /* some channel is written (a masked write keeps every byte) */
    int64_t so[16][3];            /* sample offsets of the edge values */
    int64_t bias[3];              /* the edges' top-left bias */
    int64_t reach[3];             /* bias plus the largest sample offset: an edge value
                                   * below -reach at a pixel centre covers none of its samples */
    int64_t corner[3];            /* reach plus the largest lane offset: the same for a quad */
    int64_t centre[3];            /* bias plus the one sample's offset (test1) */
    float inv_area;               /* for screen-space (noperspective) weights */
    int64_t lane[4][3];           /* quad lane i's edge values less lane 0's */
    bool test4;                   /* early and the state of test4: the vector test */
    bool test1;                   /* the same state with one sample: test_pixels */
    v4d so4[2];                   /* so[0..3][1] and so[0..3][2] as double lanes */
    bool pack;                    /* early and independent lanes: fragments gather in lanes */
    int packed;                   /* lanes gathered so far */
    int px, py;                   /* the first gathered lane's pixel */
    int64_t pu[4][3];             /* the gathered lanes' edge values, */
    size_t pbase[4];              /* first samples */
    unsigned pcover[4];           /* and surviving samples */
} quad_job;

/* A mask of four lanes (each 0 or -1) as the bits 0..3 of a sample mask. */
static unsigned lane_bits(v4i m)
{
    return (unsigned)(m[0] & 1) | (unsigned)(m[1] & 2) | (unsigned)(m[2] & 4) |
           (unsigned)(m[3] & 8);
}

/* The early depth test of one pixel's four samples at once, for the state
 * msaa_kernel.h covers (four samples, LESS with writes on a D16 or D24
 * buffer, no stencil): sr__test_tri_samples' operations lane by lane -
 * edge values are integers below 2^53, exact in doubles, depth is
 * sr__tri_depth's sum in its order (no FMA), clamped and rounded as
 * sr__quantize_depth does - so the same depth words and the same mask;
 * the four depth words are consecutive (framebuffer.h). */
/* sr__tri_depth at four points, clamped as sr__quantize_depth clamps
 * (NaN to the minimum). */
static v4d depth4(const sr_draw_state *ds, const sr_tri *t, v4d e1, v4d e2)
{
    v4d z = t->z0 + e1 * t->dz1 + e2 * t->dz2;
    v4d lo = { ds->zq_min, ds->zq_min, ds->zq_min, ds->zq_min };
    v4d hi = { ds->zq_max, ds->zq_max, ds->zq_max, ds->zq_max };
    v4l above = z >= lo;
    z = (v4d)((above & (v4l)z) | (~above & (v4l)lo));
    v4l below = z <= hi;
    return (v4d)((below & (v4l)z) | (~below & (v4l)hi));
}

static unsigned test4(const quad_job *j, size_t base, const int64_t u[3], unsigned cover)
{
    const sr_draw_state *ds = j->ds;
    v4d z = depth4(ds, j->t, (double)u[1] + j->so4[0], (double)u[2] + j->so4[1]);
    /* Non-negative and below 2^24: truncation is the scalar (uint32_t) cast. */
    v4i q = __builtin_convertvector(z + 0.5, v4i);
    v4i lanes = { (int32_t)(cover & 1u), (int32_t)(cover >> 1 & 1u), (int32_t)(cover >> 2 & 1u),
                  (int32_t)(cover >> 3 & 1u) };
    return lane_bits(sr__depth_less4(ds->fb, base, q, lanes != 0));
}

/* test4 for a quad's four pixels of one sample each, the covered ones
 * (cover[i] 1 or 0, left at 1 where the pixel passed): their depth samples
 * are two pairs of rows apart, so read and written lane by lane. */
static unsigned test_pixels(const quad_job *j, const size_t base[4], const int64_t u[4][3],
                            unsigned cover[4])
{
    v4d e1 = { (double)u[0][1], (double)u[1][1], (double)u[2][1], (double)u[3][1] };
    v4d e2 = { (double)u[0][2], (double)u[1][2], (double)u[2][2], (double)u[3][2] };
    v4d z = depth4(j->ds, j->t, e1 + j->so4[0], e2 + j->so4[1]);
    v4i q = __builtin_convertvector(z + 0.5, v4i);
    v4i d = sr__depth_gather4(j->ds->fb, base, cover), lanes;
    for (int i = 0; i < 4; i++) {
        lanes[i] = -(int32_t)cover[i];
    }
    v4i pass = lanes & (q < d);
    sr__depth_scatter4(j->ds->fb, base, pass, q);
    for (int i = 0; i < 4; i++) {
        cover[i] = (unsigned)pass[i] & 1u;
    }
    return lane_bits(pass);
}

/* The number of set bits of a sample mask (at most 16 samples), without
 * the library call __builtin_popcount becomes on the baseline build. */
static unsigned count16(unsigned x)
{
    x = x - ((x >> 1) & 0x5555u);
    x = (x & 0x3333u) + ((x >> 2) & 0x3333u);
    x = (x + (x >> 4)) & 0x0f0fu;
    return (x + (x >> 8)) & 0x1fu;
}

/* Varyings and depth of the four lanes from their unbiased centre
 * values u: sr__bary and sr__interp with the lanes in vectors - the same
 * operations in the same order, so the same bits as one lane at a time. */
static void interpolate_quad(const quad_job *j, const int64_t u[4][3], sr_fragment_quad *q)
{
    const sr_draw_state *ds = j->ds;
    const sr_tri *t = j->t;
    v4f e[3];
    for (int k = 0; k < 3; k++) {
        e[k] = (v4f){ (float)u[0][k], (float)u[1][k], (float)u[2][k], (float)u[3][k] };
    }
    v4f q0 = e[0] * t->w[0], q1 = e[1] * t->w[1], q2 = e[2] * t->w[2];
    v4f sum = q0 + q1 + q2;
    /* 1 / sum, and 0 where the sum is 0 (divided as 1 there). */
    v4i nonzero = sum != 0.0f;
    v4f divisor = (v4f)((nonzero & (v4i)sum) | (~nonzero & (v4i)(v4f){ 1, 1, 1, 1 }));
    v4f inv = (v4f)(nonzero & (v4i)(1.0f / divisor));
    v4f l1 = q1 * inv, l2 = q2 * inv;
    v4f s1 = e[1] * j->inv_area, s2 = e[2] * j->inv_area;
    int n = t->ninterp;
    const float *v0 = t->vary, *d1 = &t->vary[n], *d2 = &t->vary[2 * n];
    if (!ds->noperspective_mask) {
        for (int k = 0; k < n; k++) {
            v4f r = v0[k] + l1 * d1[k] + l2 * d2[k];
            memcpy(q->varyings[k], &r, sizeof r);
        }
    }
    for (int k = 0; k < n && ds->noperspective_mask; k++) {
        bool linear = (ds->noperspective_mask >> k) & 1;
        v4f a = linear ? s1 : l1, b = linear ? s2 : l2;
        v4f r = v0[k] + a * d1[k] + b * d2[k];
        memcpy(q->varyings[k], &r, sizeof r);
    }
    v4d z = depth4(ds, t, (v4d){ (double)u[0][1], (double)u[1][1], (double)u[2][1], (double)u[3][1] },
                   (v4d){ (double)u[0][2], (double)u[1][2], (double)u[2][2], (double)u[3][2] });
    v4f zf = __builtin_convertvector(z / ds->depth_scale, v4f);
    memcpy(q->z, &zf, sizeof zf);
}

/* The colors of the lanes `live` to their samples `cover`, which passed
 * the tests, without blending: sr__write_samples' conversion (sr__unorm8)
 * in vectors, channel by channel. */
static void write_lanes(const quad_job *j, const sr_fragment_quad *q, unsigned live,
                        const size_t base[4], const unsigned cover[4])
{
    v4i code[4];
    for (int c = 0; c < 4; c++) {
        v4f v;
        memcpy(&v, q->color[c], sizeof v);
        v = (v4f)((v > 0.0f) & (v4i)v);                          /* NaN to 0 */
        v4i below = v < 1.0f;
        v = (v4f)((below & (v4i)v) | (~below & (v4i)(v4f){ 1, 1, 1, 1 }));
        code[c] = __builtin_convertvector(v * 255.0f + 0.5f, v4i);
    }
    uint32_t *color = j->ds->fb->color;
    bool one = j->ds->samples == 1;   /* cover[i] is 1 */
    for (int i = 0; i < 4; i++) {
        if (!(live >> i & 1) || !cover[i]) {
            continue;
        }
        if (j->writes_color) {
            uint8_t out[4] = { (uint8_t)code[0][i], (uint8_t)code[1][i], (uint8_t)code[2][i],
                               (uint8_t)code[3][i] };
            uint32_t packed;
            memcpy(&packed, out, sizeof packed);
            if (one) {
                color[base[i]] = packed;
            }
            for (unsigned m = one ? 0u : cover[i]; m; m &= m - 1) {
                color[base[i] + (size_t)__builtin_ctz(m)] = packed;
            }
        }
        j->st->fragments += one ? 1u : count16(cover[i]);
    }
}

/* The program on the lanes `live` (the rest helpers) with edge values u,
 * then each surviving lane's color to its pixel's samples: cover (the
 * early tests' survivors, else the covered samples, tested here).  u is
 * a pointer, not u[4][3]: GCC takes an array parameter's bound as an
 * access size and misreads the packed lanes' rows as one. */
static void shade_lanes(const quad_job *j, int x, int y, unsigned live, const int64_t (*u)[3],
                        const size_t base[4], const unsigned cover[4])
{
    const sr_draw_state *ds = j->ds;
    const sr_tri *t = j->t;
    sr_fragment_quad q;
    q.mask = live;
    q.x = x;
    q.y = y;
    q.front = t->front;
    q.discard = 0;
    interpolate_quad(j, u, &q);
    for (int i = 0; i < 4; i++) {
        q.color[0][i] = q.color[1][i] = q.color[2][i] = 0.0f;
        q.color[3][i] = 1.0f;
    }
    ds->program->fragment(ds->program->uniforms, &q);
    live &= ~q.discard;
    if (j->early && !ds->blending) {
        write_lanes(j, &q, live, base, cover);
        return;
    }
    for (int i = 0; i < 4; i++) {
        if (!(live >> i & 1)) {
            continue;
        }
        float c[4] = { q.color[0][i], q.color[1][i], q.color[2][i], q.color[3][i] };
        unsigned pass = cover[i];
        if (!j->early) {
            if (ds->alpha_to_coverage) {
                pass &= sr__alpha_coverage(c[3], ds->samples);
            }
            double zs = (double)q.z[i] * ds->depth_scale;
            pass = pass ? sr__test_tri_samples(ds, t, base[i], u[i], (const int64_t(*)[3])j->so,
                                               pass, ds->program->writes_depth ? &zs : NULL)
                        : 0;
        }
        if (pass) {
            if (j->writes_color) {
                sr__write_samples(ds, base[i], pass, c, &ds->blend);
            }
            j->st->fragments += count16(pass);
        }
    }
}

/* The gathered fragments as one call; lanes not filled repeat lane 0
 * (finite inputs for the helpers). */
static void flush_packed(quad_job *j)
{
    int n = j->packed;
    for (int k = n; k < 4; k++) {
        memcpy(j->pu[k], j->pu[0], sizeof j->pu[k]);
    }
    shade_lanes(j, j->px, j->py, (1u << n) - 1u, (const int64_t(*)[3])j->pu, j->pbase,
                j->pcover);
    j->packed = 0;
}

static void quad_fn(void *arg, int qx, int qy, const int64_t *u00, bool inside, const int rect[4])
{
    quad_job *j = arg;
    const sr_draw_state *ds = j->ds;
    const sr_tri *t = j->t;
    int n = ds->samples;
    unsigned all = (1u << n) - 1u;
    /* Most quads of a small triangle's blocks hold none of it: the edge
     * values are linear, so the largest over the four lane centres is at
     * one corner, and a quad beyond any edge's reach is skipped before
     * its samples are tested (the same coverage, found sooner). */
    if ((u00[0] + j->corner[0]) < 0 || (u00[1] + j->corner[1]) < 0 ||
        (u00[2] + j->corner[2]) < 0) {
        return;
    }
    int64_t u[4][3];
    unsigned cover[4] = { 0, 0, 0, 0 }, live = 0;
    if (j->test1) {
        /* One sample per pixel, without branches: the lanes inside the
         * block's part (its columns, then its rows), then each one's edges. */
        unsigned part = (qx >= rect[0] ? 5u : 0u) | (qx + 1 < rect[2] ? 10u : 0u);
        part &= (qy >= rect[1] ? 3u : 0u) | (qy + 1 < rect[3] ? 12u : 0u);
        for (int i = 0; i < 4; i++) {
            for (int e = 0; e < 3; e++) {
                u[i][e] = u00[e] + j->lane[i][e];
            }
            bool covered = inside || ((u[i][0] + j->centre[0]) | (u[i][1] + j->centre[1]) |
                                      (u[i][2] + j->centre[2])) >= 0;
            cover[i] = (part >> i & 1u) & (unsigned)covered;
        }
    }
    for (int i = 0; i < 4 && !j->test1; i++) {
        int px = qx + (i & 1), py = qy + (i >> 1);
        for (int e = 0; e < 3; e++) {
            u[i][e] = u00[e] + j->lane[i][e];
        }
        if (px < rect[0] || px >= rect[2] || py < rect[1] || py >= rect[3]) {
            continue;
        }
        unsigned m = all;
        if (!inside) {
            m = 0;
            /* A lane beyond an edge's reach covers none of its samples. */
            bool beyond = ((u[i][0] + j->reach[0]) | (u[i][1] + j->reach[1]) |
                           (u[i][2] + j->reach[2])) < 0;
            for (int s = 0; s < n && !beyond; s++) {
                if (((u[i][0] + j->so[s][0] + j->bias[0]) | (u[i][1] + j->so[s][1] + j->bias[1]) |
                     (u[i][2] + j->so[s][2] + j->bias[2])) >= 0) {
                    m |= 1u << s;
                }
            }
        }
        cover[i] = m;
    }
    size_t width = (size_t)ds->fb->width;
    size_t base[4];
    base[0] = ((size_t)qy * width + (size_t)qx) * (size_t)n;
    base[1] = base[0] + (size_t)n;
    base[2] = base[0] + width * (size_t)n;
    base[3] = base[2] + (size_t)n;
    for (int i = 0; i < 4 && !j->test1; i++) {
        if (cover[i] && j->test4) {
            cover[i] = test4(j, base[i], u[i], cover[i]);
        } else if (cover[i] && j->early) {
            cover[i] = sr__test_tri_samples(ds, t, base[i], u[i], (const int64_t(*)[3])j->so,
                                            cover[i], NULL);
        }
        live |= cover[i] ? 1u << i : 0u;
    }
    if (j->test1 && (cover[0] | cover[1] | cover[2] | cover[3])) {
        live = test_pixels(j, base, (const int64_t(*)[3])u, cover);
    }
    if (!live) {
        return;
    }
    if (!j->pack) {
        shade_lanes(j, qx, qy, live, (const int64_t(*)[3])u, base, cover);
        return;
    }
    for (int i = 0; i < 4; i++) {
        if (!(live >> i & 1)) {
            continue;
        }
        int k = j->packed++;
        if (k == 0) {
            j->px = qx + (i & 1);
            j->py = qy + (i >> 1);
        }
        memcpy(j->pu[k], u[i], sizeof j->pu[k]);
        j->pbase[k] = base[i];
        j->pcover[k] = cover[i];
        if (k == 3) {
            flush_packed(j);
        }
    }
}

void sr__raster_shader(const sr_draw_state *ds, const sr_tri *t, int rx0, int ry0, int rx1,
                       int ry1, sr_frag_stats *st)
{
    /* Field by field rather than by an initializer, which would zero
     * all sixteen samples' offsets where only ds->samples are read: for
     * a triangle of a pixel or less that store is a large part of its
     * cost here. */
    quad_job j;
    j.ds = ds;
    j.t = t;
    j.st = st;
    j.writes_color = (ds->write_mask[0] | ds->write_mask[1] | ds->write_mask[2] |
                      ds->write_mask[3]) != 0;
    j.early = !ds->program->writes_depth && !ds->program->may_discard && !ds->alpha_to_coverage;
    sr_edges ed;
    sr__tri_edges(t, &ed);
    j.inv_area = 1.0f / (float)(ed.c[0] + ed.c[1] + ed.c[2]);   /* area2 */
    memcpy(j.bias, ed.bias, sizeof j.bias);
    for (int i = 0; i < 3; i++) {
        j.reach[i] = INT64_MIN;
    }
    for (int s = 0; s < ds->samples; s++) {
        for (int i = 0; i < 3; i++) {
            j.so[s][i] = (int64_t)t->a[i] * ds->sample_off[s][0] + (int64_t)t->b[i] * ds->sample_off[s][1];
            j.reach[i] = j.so[s][i] > j.reach[i] ? j.so[s][i] : j.reach[i];
        }
    }
    for (int i = 0; i < 3; i++) {
        j.reach[i] += j.bias[i];
        j.corner[i] = j.reach[i] + ((int64_t)(t->a[i] > 0 ? t->a[i] : 0) +
                                    (t->b[i] > 0 ? t->b[i] : 0)) * SR_SUBPIXEL_ONE;
        j.centre[i] = j.so[0][i] + j.bias[i];
    }
    for (int i = 0; i < 4; i++) {
        for (int e = 0; e < 3; e++) {
            j.lane[i][e] = ((int64_t)t->a[e] * (i & 1) + (int64_t)t->b[e] * (i >> 1)) * SR_SUBPIXEL_ONE;
        }
    }
    j.test4 = j.early && !ds->stencil_test &&
              ds->depth_mode == SR_DEPTH_MODE_LESS && ds->depth_bits >= 1 && ds->depth_bits <= 24;
    j.test1 = j.test4 && ds->samples == 1;
    j.test4 = j.test4 && ds->samples == 4;
    for (int s = 0; s < 4 && (j.test4 || j.test1); s++) {
        /* One sample: its offsets in every lane. */
        j.so4[0][s] = (double)j.so[j.test1 ? 0 : s][1];
        j.so4[1][s] = (double)j.so[j.test1 ? 0 : s][2];
    }
    j.pack = j.early && ds->program->independent_lanes;
    j.packed = 0;
    sr__quad_walk(ds, t, rx0, ry0, rx1, ry1, &j, quad_fn);
    if (j.packed) {
        flush_packed(&j);
    }
}

bool sr__program_shade_one(const sr_draw_state *ds, const float *v, bool front, int px, int py,
                           double *z, float c[4])
{
    sr_fragment_quad q;
    memset(&q, 0, sizeof q);
    q.mask = 1;
    q.x = px;
    q.y = py;
    q.front = front;
    for (int k = 0; k < ds->ninterp; k++) {
        q.varyings[k][0] = q.varyings[k][1] = q.varyings[k][2] = q.varyings[k][3] = v[k];
    }
    q.z[0] = q.z[1] = q.z[2] = q.z[3] = (float)(*z / ds->depth_scale);
    q.color[3][0] = 1.0f;
    ds->program->fragment(ds->program->uniforms, &q);
    if (q.discard & 1) {
        return false;
    }
    for (int k = 0; k < 4; k++) {
        c[k] = q.color[k][0];
    }
    if (ds->program->writes_depth) {
        *z = (double)q.z[0] * ds->depth_scale;
    }
    return true;
}
