/*
 * visibility.c - the geometry outputs through a visibility buffer: every
 * face rasterized for its depth and index alone (no vertex program,
 * varyings, set-up records, bins or fragment program), then each covered
 * pixel resolved from the index of its visible face by
 * sr_py_shade_pixel.  Runs without the GIL, on the render set's context's
 * threads.
 *
 * The coverage and the depth test are the general pass's, computed by the
 * library's own inline functions under the draw state sr_draw resolves
 * for the geometry program: each vertex classified against the clip
 * planes and snapped (sr__clip_outcode_with, sr__project) from the same
 * clip position, each face set up by sr__setup_tri, and each covered
 * pixel centre's depth sr__tri_depth quantized by sr__quantize_depth and
 * tested GREATER against the faces before it.  A face crossing a clip
 * plane makes the caller draw the view the general way instead.
 *
 * A draw in order keeps at each pixel the first of the faces with the
 * greatest depth.  Each pixel's word here is (depth << 32 | ~face), face
 * numbering the faces of all instances in draw order, raised to each
 * face's word by an atomic maximum: the same winner, whatever the order
 * in which the threads get to the faces, so the bytes do not depend on
 * the number of threads or on their timing.  Most faces of a dense mesh
 * cover no pixel centre: they are dropped from their vertices' spans of
 * pixel centres before anything else is read, and a small face is tested
 * against its box's centres before it is set up.  Where the CPU has AVX2
 * the faces are first looked at eight at a time (face_lanes.h), which
 * leaves the scalar code only the faces that may cover a centre.
 */
#include "geometry.h"

#include "context.h"
#include "draw_state.h"
#include "fragment/fragment.h"
#include "parallel/pool.h"
#include "pipeline.h"
#include "raster/setup_tri.h"

#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

/* Faces and rows in a job: jobs small enough for the pool's threads to
 * even out the work between them. */
enum { FACES_PER_JOB = 4096, ROWS_PER_JOB = 16 };
/* Boxes of at most this many pixel centres are tested by may_pass before
 * setup. */
enum { SMALL_BOX = 4 };
/* Faces whose boxes are tested before any is set up; vertices
 * classified together. */
enum { CANDIDATE_BLOCK = 256, CLASSIFY_BLOCK = 256 };
/* Candidates between a prefetch and the candidate's set-up. */
enum { PREFETCH_AHEAD = 8 };

/* A vertex's snapped window position (zeros for a vertex outside a clip
 * plane, whose outcode says so). */
typedef struct window_vertex {
    int32_t x_q8, y_q8;
    double z;
} window_vertex;

/* The pixel centres a vertex's own box spans, [x0, x1) x [y0, y1) (empty
 * when it lies between centres): setup's box of a face is the smallest
 * of the x0, y0 and the largest of the x1, y1 of its vertices (rounding
 * up or down is monotonic), so a face covering no centre is found from
 * these 8 bytes a vertex, before its window positions are read. */
typedef struct centre_span {
    int16_t x0, x1, y0, y1;
} centre_span;

typedef struct vis_job {
    const sr_draw_state *ds;
    const geometry_uniforms *u;
    size_t count;
    const size_t *first_vertex, *first_face;   /* count + 1 each: prefix sums */
    window_vertex *win;
    centre_span *span;
    uint32_t *outcode;
    int vertex_jobs, face_jobs, height, width;
    bool lanes;                  /* faces first looked at in AVX2 lanes */
    size_t pixels;
    _Atomic uint64_t *word;      /* per pixel: depth << 32 | ~face, 0 for none */
    atomic_bool outside;         /* some vertex is outside a clip plane */
    atomic_bool crosses;         /* some face crosses a clip plane */
} vis_job;

/* The instance holding global index i of a prefix-sum array `first`. */
static size_t instance_of(const size_t *first, size_t count, size_t i)
{
    size_t lo = 0, hi = count;
    while (hi - lo > 1) {
        size_t mid = (lo + hi) / 2;
        if (first[mid] <= i) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return lo;
}

/* Vertices [lo, hi) of the draw, those of instance u from `base`: seen
 * from the camera (sr_py_view_vertices_to, the camera table filled and
 * the clip positions written straight into the block's records; the
 * clip table is left to the general pass), then classified and snapped
 * as the vertex stage does (vertex.c's classify, sixteen at a time where
 * the draw state says the CPU can, with the same values), a block at a
 * time.  True when one is outside a clip plane. */
static bool classify_vertices(const vis_job *j, const geometry_uniforms *u, size_t base, size_t lo,
                              size_t hi)
{
    const sr_draw_state *ds = j->ds;
    sr_clip_planes k;
    sr__clip_planes(ds, &k);
    sr_vertex_post post[CLASSIFY_BLOCK];
    bool outside = false;
    for (size_t b = lo; b < hi; b += CLASSIFY_BLOCK) {
        size_t n = hi - b < CLASSIFY_BLOCK ? hi - b : CLASSIFY_BLOCK;
        sr_py_view_vertices_to(u, b - base, b - base + n, ds->simd >= SR_SIMD_AVX2, post[0].pos,
                               sizeof post[0]);
        if (!(ds->vertex_lanes16 && sr__classify16(ds, post, n))) {
            for (size_t i = 0; i < n; i++) {
                const float *pos = post[i].pos;
                post[i].outcode = SR_OUTCODE_NONFINITE;
                if (isfinite(pos[0]) && isfinite(pos[1]) && isfinite(pos[2]) && isfinite(pos[3])) {
                    post[i].outcode = sr__clip_outcode_with(&k, pos);
                }
                if (post[i].outcode == 0) {
                    sr__project(ds, pos, &post[i].x_q8, &post[i].y_q8, &post[i].z,
                                &post[i].inv_w);
                }
            }
        }
        for (size_t i = 0; i < n; i++) {
            size_t v = b + i;
            j->outcode[v] = post[i].outcode;
            window_vertex *w = &j->win[v];
            if (post[i].outcode != 0) {
                outside = true;
                *w = (window_vertex){ 0, 0, 0.0 };
            } else {
                *w = (window_vertex){ post[i].x_q8, post[i].y_q8, post[i].z };
            }
            /* setup_tri.h's single-sample box, of this vertex alone. */
            j->span[v] = (centre_span){
                (int16_t)sr__ceil_q8((int64_t)w->x_q8 - SR_SUBPIXEL_HALF),
                (int16_t)(sr__floor_q8((int64_t)w->x_q8 - SR_SUBPIXEL_HALF) + 1),
                (int16_t)sr__ceil_q8((int64_t)w->y_q8 - SR_SUBPIXEL_HALF),
                (int16_t)(sr__floor_q8((int64_t)w->y_q8 - SR_SUBPIXEL_HALF) + 1),
            };
        }
    }
    return outside;
}

/* The draw's vertices in equal shares. */
static void classify_job(void *arg, int job, int thread)
{
    (void)thread;
    vis_job *j = arg;
    size_t total = j->first_vertex[j->count];
    size_t lo = total * (size_t)job / (size_t)j->vertex_jobs;
    size_t hi = total * (size_t)(job + 1) / (size_t)j->vertex_jobs;
    bool outside = false;
    for (size_t inst = instance_of(j->first_vertex, j->count, lo), v = lo; v < hi; inst++) {
        const geometry_uniforms *u = &j->u[inst];
        size_t base = j->first_vertex[inst];
        size_t end = j->first_vertex[inst + 1] < hi ? j->first_vertex[inst + 1] : hi;
        outside |= classify_vertices(j, u, base, v, end);
        v = end;
    }
    if (outside) {
        atomic_store_explicit(&j->outside, true, memory_order_relaxed);
    }
}

static inline int min3(int a, int b, int c)
{
    int m = a < b ? a : b;
    return m < c ? m : c;
}

static inline int max3(int a, int b, int c)
{
    int m = a > b ? a : b;
    return m > c ? m : c;
}

/* The depth-buffer value of a pixel's word. */
static inline uint32_t word_depth(uint64_t w)
{
    return (uint32_t)(w >> 32);
}

/* The covered pixel centres of one set-up face, g of the draw, where it
 * passes the depth test: greater than the depth there, or equal and
 * drawn before the face that has it. */
static void raster_face(const sr_draw_state *ds, const sr_tri *t, uint32_t g, int width,
                        _Atomic uint64_t *word)
{
    sr_edges ed;
    sr__tri_edges(t, &ed);
    for (int y = t->h.y0; y < t->h.y1; y++) {
        int64_t Y = sr__centre_q8(y);
        size_t row = (size_t)y * (size_t)width;
        for (int x = t->h.x0; x < t->h.x1; x++) {
            int64_t X = sr__centre_q8(x);
            int64_t e0 = sr__edge_at(&ed, 0, X, Y), e1 = sr__edge_at(&ed, 1, X, Y);
            int64_t e2 = sr__edge_at(&ed, 2, X, Y);
            if (((e0 + ed.bias[0]) | (e1 + ed.bias[1]) | (e2 + ed.bias[2])) < 0) {
                continue;
            }
            double z = sr__tri_depth(t, e1, e2);
            uint32_t q = sr__quantize_depth(ds, &z);
            if (q == 0) {
                continue;   /* not greater than the cleared depth */
            }
            uint64_t mine = (uint64_t)q << 32 | (uint32_t)~g;
            _Atomic uint64_t *w = &word[row + (size_t)x];
            uint64_t cur = atomic_load_explicit(w, memory_order_relaxed);
            while (mine > cur &&
                   !atomic_compare_exchange_weak_explicit(w, &cur, mine, memory_order_relaxed,
                                                          memory_order_relaxed)) {
            }
        }
    }
}

/* Whether some pixel centre of the box [x0, x1) x [y0, y1) may be
 * covered by the face and pass the depth test: a necessary condition,
 * cheaper than setup, which decides.  Covered centres lie in the closed
 * half-planes of the three edges (the fill rule only removes some on
 * the edges), and their depth, the plane through the vertex depths at
 * barycentric weights in [0, 1], exceeds the largest vertex depth only
 * by rounding (a few units in the last place of 1; setup_tri.h's
 * z_inside takes the same 1e-9 margin), so a centre whose stored depth
 * is greater than that bound, quantized, cannot pass (equal still can,
 * for a face drawn before the one there). */
static bool may_pass(const sr_draw_state *ds, const sr_window_vertex w[3], int64_t area2, int x0,
                     int y0, int x1, int y1, int width, _Atomic uint64_t *word)
{
    int64_t sign = area2 > 0 ? 1 : -1;
    int64_t dx[3], dy[3];
    for (int i = 0; i < 3; i++) {
        const sr_window_vertex *a = &w[(i + 1) % 3], *b = &w[(i + 2) % 3];
        dx[i] = sign * ((int64_t)b->x_q8 - a->x_q8);
        dy[i] = sign * ((int64_t)b->y_q8 - a->y_q8);
    }
    double zhi = sr__max_d(w[0].z, sr__max_d(w[1].z, w[2].z)) + 1e-9;
    uint32_t bound = sr__quantize_depth(ds, &zhi);
    for (int y = y0; y < y1; y++) {
        int64_t Y = sr__centre_q8(y);
        for (int x = x0; x < x1; x++) {
            int64_t X = sr__centre_q8(x);
            bool inside = true;
            for (int i = 0; i < 3; i++) {
                const sr_window_vertex *a = &w[(i + 1) % 3];
                inside &= dx[i] * (Y - a->y_q8) - dy[i] * (X - a->x_q8) >= 0;
            }
            _Atomic uint64_t *at = &word[(size_t)y * (size_t)width + (size_t)x];
            if (inside && bound >= word_depth(atomic_load_explicit(at, memory_order_relaxed))) {
                return true;
            }
        }
    }
    return false;
}

/* A face whose box holds a pixel centre: its index in the draw, its
 * vertices' (in the classified arrays) and its box. */
typedef struct candidate {
    uint32_t g, v[3];
    int16_t x0, x1, y0, y1;
} candidate;

/* Faces [lo, hi) of instance `inst` whose box holds a pixel centre, into
 * out[]; their number, or -1 when one crosses a clip plane.  Without
 * branches on the box test (whose outcome a dense mesh makes random):
 * each face is written and kept by the count's step. */
static long find_candidates(const vis_job *j, size_t inst, size_t lo, size_t hi, bool outside,
                            candidate *out)
{
    const sr_draw_state *ds = j->ds;
    const geometry_uniforms *u = &j->u[inst];
    size_t first = j->first_face[inst], base = j->first_vertex[inst];
    long n = 0;
    for (size_t g = lo; g < hi; g++) {
        size_t f = g - first;
        uint32_t v0 = (uint32_t)(base + sr_py_face_index(u, 3 * f));
        uint32_t v1 = (uint32_t)(base + sr_py_face_index(u, 3 * f + 1));
        uint32_t v2 = (uint32_t)(base + sr_py_face_index(u, 3 * f + 2));
        bool keep = true;
        if (outside) {
            uint32_t c0 = j->outcode[v0], c1 = j->outcode[v1], c2 = j->outcode[v2];
            /* Discarded, or outside one plane: drawn by neither pass. */
            keep = !(((c0 | c1 | c2) & SR_OUTCODE_NONFINITE) || (c0 & c1 & c2));
            if (keep && (c0 | c1 | c2) != 0) {
                return -1;
            }
        }
        const centre_span *s0 = &j->span[v0], *s1 = &j->span[v1], *s2 = &j->span[v2];
        int x0 = max3(min3(s0->x0, s1->x0, s2->x0), ds->rect_x0, INT16_MIN);
        int x1 = min3(max3(s0->x1, s1->x1, s2->x1), ds->rect_x1, INT16_MAX);
        int y0 = max3(min3(s0->y0, s1->y0, s2->y0), ds->rect_y0, INT16_MIN);
        int y1 = min3(max3(s0->y1, s1->y1, s2->y1), ds->rect_y1, INT16_MAX);
        out[n] = (candidate){ (uint32_t)g, { v0, v1, v2 }, (int16_t)x0, (int16_t)x1,
                              (int16_t)y0, (int16_t)y1 };
        /* No pixel centre in its box: setup would find none. */
        n += keep & (x0 < x1) & (y0 < y1);
    }
    return n;
}

#include "face_lanes.h"

/* Faces [FACES_PER_JOB job, ...) of the draw: the front end's triangle()
 * (assembly.c) for faces inside every clip plane, then setup and the
 * depth test. */
static void faces_job(void *arg, int job, int thread)
{
    (void)thread;
    vis_job *j = arg;
    const sr_draw_state *ds = j->ds;
    bool outside = atomic_load_explicit(&j->outside, memory_order_relaxed);
    size_t total = j->first_face[j->count];
    size_t lo = (size_t)job * FACES_PER_JOB;
    size_t hi = lo + FACES_PER_JOB < total ? lo + FACES_PER_JOB : total;
    candidate cand[CANDIDATE_BLOCK];
    for (size_t inst = instance_of(j->first_face, j->count, lo), g = lo; g < hi;) {
        while (g >= j->first_face[inst + 1]) {
            inst++;
        }
        size_t end = j->first_face[inst + 1] < hi ? j->first_face[inst + 1] : hi;
        end = end - g > CANDIDATE_BLOCK ? g + CANDIDATE_BLOCK : end;
#ifdef SR_PY_FACE_LANES
        long n = j->lanes && !outside ? find_candidates_lanes(j, inst, g, end, cand)
                                      : find_candidates(j, inst, g, end, outside, cand);
#else
        long n = find_candidates(j, inst, g, end, outside, cand);
#endif
        int64_t cull_sign = j->u[inst].cull_sign;
        if (n < 0) {
            atomic_store_explicit(&j->crosses, true, memory_order_relaxed);
            return;
        }
        g = end;
        for (long i = 0; i < n; i++) {
            const candidate *c = &cand[i];
            /* What a later candidate reads, asked for ahead: its window
             * vertices and its box's first pixel word. */
            if (i + PREFETCH_AHEAD < n) {
                const candidate *ahead = &cand[i + PREFETCH_AHEAD];
                for (int k = 0; k < 3; k++) {
                    __builtin_prefetch(&j->win[ahead->v[k]]);
                }
                __builtin_prefetch(&j->word[(size_t)ahead->y0 * (size_t)j->width + ahead->x0]);
            }
            const window_vertex *p0 = &j->win[c->v[0]], *p1 = &j->win[c->v[1]];
            const window_vertex *p2 = &j->win[c->v[2]];
            sr_window_vertex w[3] = {
                { p0->x_q8, p0->y_q8, p0->z, 1.0f, NULL },
                { p1->x_q8, p1->y_q8, p1->z, 1.0f, NULL },
                { p2->x_q8, p2->y_q8, p2->z, 1.0f, NULL },
            };
            int64_t area2 = sr__area2(&w[0], &w[1], &w[2]);
            /* Culled as assembly.c culls: by the snapped area's sign. */
            if (area2 == 0 || area2 * cull_sign > 0 ||
                ((c->x1 - c->x0) * (c->y1 - c->y0) <= SMALL_BOX &&
                 !may_pass(ds, w, area2, c->x0, c->y0, c->x1, c->y1, j->width, j->word))) {
                continue;
            }
            sr_tri t;
            if (sr__setup_tri(ds, &w[0], &w[1], &w[2], area2, NAN, true, 0, NULL, &t)) {
                raster_face(ds, &t, c->g, j->width, j->word);
            }
        }
    }
}

/* Rows of the image: each covered pixel resolved from its word, which
 * is cleared for the next view; the runs of pixels that no face passed
 * filled a run at a time. */
static void resolve_job(void *arg, int job, int thread)
{
    (void)thread;
    vis_job *j = arg;
    int y1 = (job + 1) * ROWS_PER_JOB < j->height ? (job + 1) * ROWS_PER_JOB : j->height;
    for (int y = job * ROWS_PER_JOB; y < y1; y++) {
        _Atomic uint64_t *row = &j->word[(size_t)y * (size_t)j->width];
        for (int x = 0; x < j->width;) {
            int run = x;
            while (run < j->width && atomic_load_explicit(&row[run], memory_order_relaxed) == 0) {
                run++;
            }
            sr_py_background_run(j->u, (size_t)y * (size_t)j->width + (size_t)x,
                                 (size_t)(run - x));
            for (x = run; x < j->width; x++) {
                uint64_t w = atomic_load_explicit(&row[x], memory_order_relaxed);
                if (w == 0) {
                    break;
                }
                atomic_store_explicit(&row[x], 0, memory_order_relaxed);
                uint32_t q = word_depth(w), g = ~(uint32_t)w;
                size_t inst = instance_of(j->first_face, j->count, g);
                float z;
                memcpy(&z, &q, sizeof z);   /* the float depth buffer's value */
                sr_py_shade_pixel(&j->u[inst], g - j->first_face[inst], x, y, z);
            }
        }
    }
}

sr_result sr_py_visibility_pass(sr_py_render_set *set, const geometry_uniforms *u, size_t count,
                                bool *done)
{
    *done = false;
    if (count == 0) {
        return SR_OK;   /* nothing to draw: the general pass fills the outputs */
    }
    sr_context *ctx = set->ctx;
    sr_framebuffer *fb = set->fb;
    /* The general pass's draw state, as sr_draw resolves it. */
    sr_program prog = { .varying_count = 1 };
    prog.modes[0] = SR_VARYING_FLAT;
    sr_state st = sr_py_geometry_state(&prog, 0);   /* culled per instance */
    sr_draw_state ds;
    sr__resolve_draw_state(fb, &st, NULL, NULL, ctx->simd, &ds);
    if (ds.samples != 1 || ds.depth_bits != 0 || ds.depth_scale != 1.0) {
        return SR_OK;
    }
    size_t *first = malloc(2 * (count + 1) * sizeof *first);
    if (!first) {
        return SR_OUT_OF_MEMORY;
    }
    vis_job j = { .ds = &ds, .u = u, .count = count, .first_vertex = first,
                  .first_face = first + count + 1, .width = fb->width, .height = fb->height };
    first[0] = first[count + 1] = 0;
    for (size_t i = 0; i < count; i++) {
        first[i + 1] = first[i] + u[i].vertices_count;
        first[count + 2 + i] = first[count + 1 + i] + u[i].faces_count;
    }
    size_t faces = j.first_face[count], vertices = j.first_vertex[count];
    if (faces >= UINT32_MAX || vertices > UINT32_MAX) {
        free(first);
        return SR_OK;   /* indices beyond 32 bits (and ~face 0 is the word of none) */
    }
    j.vertex_jobs = ctx->threads > 0 ? ctx->threads : 1;
#ifdef SR_PY_FACE_LANES
    j.lanes = ds.simd >= SR_SIMD_AVX2 && vertices < FACE_LANES_MAX_VERTICES;
#endif
    j.face_jobs = (int)((faces + FACES_PER_JOB - 1) / FACES_PER_JOB);
    j.pixels = (size_t)j.width * (size_t)j.height;
    /* The pixels' words first, so that those left cleared by the last
     * view's resolve stay where they are (but for those past this view's
     * pixels, which its vertex arrays overwrite). */
    size_t bytes = j.pixels * sizeof(uint64_t) +
                   vertices * (sizeof(window_vertex) + sizeof(centre_span) + sizeof(uint32_t));
    if (set->visibility_bytes < bytes) {
        void *grown = realloc(set->visibility, bytes);
        if (!grown) {
            free(first);
            return SR_OUT_OF_MEMORY;
        }
        set->visibility = grown;
        set->visibility_bytes = bytes;
    }
    j.word = set->visibility;
    if (set->visibility_cleared < j.pixels) {
        memset(j.word + set->visibility_cleared, 0,
               (j.pixels - set->visibility_cleared) * sizeof(uint64_t));
    }
    set->visibility_cleared = j.pixels;
    j.win = (window_vertex *)(j.word + j.pixels);
    j.span = (centre_span *)(j.win + vertices);
    j.outcode = (uint32_t *)(j.span + vertices);
    atomic_init(&j.outside, false);
    atomic_init(&j.crosses, false);
    sr__pool_run(ctx->pool, classify_job, &j, j.vertex_jobs);
    sr__pool_run(ctx->pool, faces_job, &j, j.face_jobs);
    if (atomic_load(&j.crosses)) {
        set->visibility_cleared = 0;   /* words left behind */
    } else {
        sr__pool_run(ctx->pool, resolve_job, &j, (j.height + ROWS_PER_JOB - 1) / ROWS_PER_JOB);
        *done = true;
    }
    free(first);
    return SR_OK;
}
