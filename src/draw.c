/* draw.c - sr_draw, the pipeline's driver: validate (draw_validate.c),
 * resolve the state (draw_state.c), run the vertex stage, then batch by
 * batch the front end (geometry/assembly.c: assemble, clip, set up, bin)
 * and the tiles (parallel/bin.c).  Application thread; both fan out to
 * the context's pool. */
#include "context.h"
#include "geometry/assembly.h"
#include "parallel/bin.h"
#include "scratch.h"

#include <string.h>

/* The largest of indices [begin, end) of an indexed draw
 * (geometry/index_max.c).  Run by the vertex stage's jobs, each over its
 * share: the indices come from memory, and one pass over the bunny's
 * 208,353 on the application thread alone took 3% of a two-thread frame. */
static uint32_t max_index(const sr_draw_state *ds, const sr_draw_desc *d, size_t begin,
                          size_t end)
{
    return sr__index_max(d->index_type, d->indices, begin, end, ds->index_avx2);
}

/* Indices out of range are an error before anything is drawn: given the
 * largest index, name the first one out of range. */
static sr_result check_indices(sr_context *ctx, const sr_draw_desc *d, uint32_t max)
{
    if (d->index_type == SR_INDEX_NONE || d->index_count == 0 || max < d->vertex_count) {
        return SR_OK;
    }
    for (size_t i = 0; i < d->index_count; i++) {
        uint32_t ix = sr__index_at(d, i);
        if (ix >= d->vertex_count) {
            return sr__fail(ctx, SR_INVALID_ARG,
                            "sr_draw_desc.indices[%zu] = %u is out of range (vertex_count %zu)",
                            i, ix, d->vertex_count);
        }
    }
    return SR_OK;
}

typedef struct vertex_job {
    const sr_draw_state *ds;
    const sr_draw_desc *d;
    const sr_mat4 *mvp, *mv, *nm;
    sr_scratch *s;
    size_t base, span;  /* vertices [base, base + span), at post[0 ..] */
    size_t per_job, jobs;
    bool find_max;      /* the indices' maximum is not known yet */
    uint32_t max_index[SR_MAX_THREADS]; /* per thread, over its jobs' shares of the indices */
} vertex_job;

static void run_vertex_stage(void *arg, int job, int thread)
{
    vertex_job *vj = arg;
    const sr_draw_desc *d = vj->d;
    size_t at = (size_t)job * vj->per_job;
    size_t count = vj->span - at < vj->per_job ? vj->span - at : vj->per_job;
    sr__vertex_stage(vj->ds, d, vj->mvp, vj->mv, vj->nm, vj->base + at, count, vj->s->post + at,
                     vj->s->vary + at * (size_t)vj->ds->nvary);
    if (!vj->find_max) {
        return;
    }
    /* The vertex stage reads no index, so the check can wait for it. */
    uint32_t m = max_index(vj->ds, d, d->index_count * (size_t)job / vj->jobs,
                           d->index_count * ((size_t)job + 1) / vj->jobs);
    vj->max_index[thread] = m > vj->max_index[thread] ? m : vj->max_index[thread];
}

/* Cut primitives [begin, end) into the chunks: one equal share per thread
 * (the pool runs share t's chunks on thread t first), each share cut
 * into chunks of decreasing size, 4 : 3 : 2 : 1, so that what a thread that
 * is done early takes from the end of another's share is small - the
 * cost of a mesh's triangles varies along it (the bunny's first half,
 * mostly facing the camera, takes 1.7 times its second half to set up). */
static void split_batch(sr_scratch *s, size_t begin, size_t end, int threads, int chunks)
{
    _Static_assert(SR_CHUNKS_PER_THREAD == 4, "the weights below are for four chunks");
    static const unsigned quarters[] = { 0, 4, 7, 9, 10 }, whole[] = { 0, 10 };
    int per_thread = chunks / threads; /* 1 (one thread) or SR_CHUNKS_PER_THREAD */
    const unsigned *cum = per_thread == 1 ? whole : quarters;
    size_t n = end - begin;
    for (int ci = 0; ci < chunks; ci++) {
        size_t t = (size_t)(ci / per_thread), k = (size_t)(ci % per_thread);
        size_t lo = begin + n * t / (size_t)threads, hi = begin + n * (t + 1) / (size_t)threads;
        s->chunks[ci].prim_begin = lo + (hi - lo) * cum[k] / 10;
        s->chunks[ci].prim_end = lo + (hi - lo) * cum[k + 1] / 10;
    }
}

sr_result sr_draw(sr_context *ctx, sr_framebuffer *fb, const sr_state *state,
                  const sr_draw_desc *d)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_draw: ctx is NULL");
    }
    memset(&ctx->last_draw, 0, sizeof ctx->last_draw);
    sr_result r = sr__draw_validate(ctx, fb, state, d);
    if (r != SR_OK) {
        return r;
    }
    if (state->visibility == SR_VISIBILITY_PAINTER) {
        return sr__draw_painter(ctx, fb, state, d);
    }
    size_t count = d->index_type == SR_INDEX_NONE ? d->vertex_count : d->index_count;

    sr_draw_state ds;
    sr__resolve_draw_state(fb, state, d->view, d->projection, ctx->simd, &ds);

    size_t prims = 0;
    switch (d->primitive) {
    case SR_PRIM_TRIANGLE_STRIP:
    case SR_PRIM_TRIANGLE_FAN: prims = count >= 3 ? count - 2 : 0; break;
    case SR_PRIM_LINES:        prims = count / 2; break;
    case SR_PRIM_LINE_STRIP:   prims = count >= 2 ? count - 1 : 0; break;
    case SR_PRIM_LINE_LOOP:    prims = count >= 3 ? count : (count == 2 ? 1 : 0); break;
    case SR_PRIM_POINTS:       prims = count; break;
    default:                   prims = count / 3; break;
    }
    /* Without indices, lists of triangles, lines or points use each vertex
     * once: the front end's chunks run the vertex stage for their own
     * primitives (sr__run_front_end) and the whole-draw arrays are not used. */
    size_t verts_per_prim = 0;
    if (d->index_type == SR_INDEX_NONE) {
        switch (d->primitive) {
        case SR_PRIM_DEFAULT:
        case SR_PRIM_TRIANGLES: verts_per_prim = 3; break;
        case SR_PRIM_LINES:     verts_per_prim = 2; break;
        case SR_PRIM_POINTS:    verts_per_prim = 1; break;
        default:                break;
        }
    }
    bool fused = verts_per_prim != 0;
    /* A context on a fixed budget (the caller's arena, or the embedded
     * profile) draws an indexed mesh through a window of its vertices
     * (geometry/assembly.c), so its scratch does not grow with the mesh;
     * such a context has one thread. */
#ifdef SR_EMBEDDED
    bool bounded = true;
#else
    bool bounded = ctx->arena != NULL;
#endif
    size_t window = 0;
    if (!fused && bounded) {
        window = d->vertex_count < SR_VERTEX_WINDOW ? d->vertex_count : SR_VERTEX_WINDOW;
    }
    /* A draw with fewer indices than vertices uses part of its array at
     * most - a glTF part, one node's mesh of a scene's: the vertex stage
     * shades only the range its indices span, found first on this thread.
     * That pass costs less than the vertices it could spare (an index is
     * a load and two compares, a vertex a transform and often lighting);
     * a draw with more indices than vertices (a whole mesh, which names
     * each vertex about six times) keeps the pass fused with the vertex
     * stage, so its cost stays within a few times its indices either way. */
    size_t base = 0, span = d->vertex_count;
    bool ranged = !fused && !window && d->index_type != SR_INDEX_NONE &&
                  d->index_count < d->vertex_count;
    uint32_t range_max = 0;
    if (ranged) {
        uint32_t lo;
        sr__index_range(d->index_type, d->indices, d->index_count, &lo, &range_max);
        if (d->index_count > 0 && range_max < d->vertex_count) {
            base = lo;
            span = (size_t)range_max - lo + 1;
        }
    }
    /* More chunks than threads evens out uneven clipping and culling: the
     * bunny's first quarter of triangles takes four times as long to set up
     * as its last (culled backs), and with two chunks a thread the pool's
     * stealing could not even that out. */
    int chunks = ctx->threads == 1 ? 1 : ctx->threads * SR_CHUNKS_PER_THREAD;
    /* A draw of a few primitives (a glTF node's part, an instance) takes a
     * single chunk, set up on this thread: waking the pool and binning
     * chunks * tiles counters cost more than its front end.  The tile jobs
     * read the chunks in submission order, so the cut changes no pixel. */
    if (prims < SR_SMALL_DRAW_PRIMS) {
        chunks = 1;
    }
    sr_scratch *s = ctx->scratch;
    size_t post_count = fused ? 0 : (window ? window : span);
    if (!sr__scratch_reserve(&ctx->allocator, s, post_count, ds.nvary,
                             (size_t)ds.tiles_x * ds.tiles_y, chunks)) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_draw: out of memory for %zu vertices",
                        post_count);
    }
    sr__ok(ctx);
    if (prims == 0 || ds.rect_x0 >= ds.rect_x1 || ds.rect_y0 >= ds.rect_y1 ||
        d->vertex_count == 0) {
        /* Nothing to draw, but the indices are still checked. */
        return check_indices(ctx, d, ranged ? range_max : max_index(&ds, d, 0, d->index_count));
    }

    /* M = P E M_O, and the normal matrix from E M_O. */
    sr_mat4 mo = d->model ? *d->model : sr_mat4_identity();
    sr_mat4 e = d->view ? *d->view : sr_mat4_identity();
    sr_mat4 p = d->projection ? *d->projection : sr_mat4_identity();
    sr_mat4 mv = sr_mat4_mul(&e, &mo);
    sr_mat4 mvp = sr_mat4_mul(&p, &mv);
    sr_mat4 nm;
    if (!sr_normal_matrix(&mv, &nm)) {
        nm = mv; /* singular model-view (a flattening scale): best effort */
    }
    if (window) {
        sr_result ri = check_indices(ctx, d, max_index(&ds, d, 0, d->index_count));
        if (ri != SR_OK) {
            return ri;
        }
        s->window_lo = s->window_hi = 0;
    } else if (ranged && range_max >= d->vertex_count) {
        return check_indices(ctx, d, range_max);
    } else if (!fused) {
        /* Blocks of at most 4096 vertices, a multiple of the thread count
         * of them: the pool gives each thread a contiguous share of the
         * blocks, as it does the front end's chunks, and a mesh's
         * triangles mostly use vertices near their own place in the
         * order, so a chunk mostly reads vertices its own core shaded.
         * Up to 8 blocks a thread as long as each has 256 vertices, so
         * that a caller whose workers are still waking takes over the
         * blocks of theirs they have not started. */
        size_t threads = (size_t)ctx->threads;
        size_t jobs = (span + 4095) / 4096;
        size_t fine = span / 256 < threads * 8 ? span / 256 : threads * 8;
        jobs = jobs > fine ? jobs : fine;
        /* One job (run on this thread, no wake-up) for fewer than 512. */
        jobs = jobs > 1 ? (jobs + threads - 1) / threads * threads : 1;
        vertex_job vj = { &ds, d, &mvp, &mv, &nm, s, base, span, (span + jobs - 1) / jobs, 0,
                          !ranged, { 0 } };
        vj.jobs = (span + vj.per_job - 1) / vj.per_job;
        sr__pool_run(ctx->pool, run_vertex_stage, &vj, (int)vj.jobs);
        uint32_t m = range_max;
        for (int t = 0; t < ctx->threads && !ranged; t++) {
            m = vj.max_index[t] > m ? vj.max_index[t] : m;
        }
        sr_result ri = check_indices(ctx, d, m);
        if (ri != SR_OK) {
            return ri;
        }
        ctx->last_draw.vertices_shaded = span;
    }

    memset(s->stats, 0, sizeof s->stats);
    /* Filled triangles only: records of a triangle's size (sr__record_size). */
    bool triangle_prims = d->primitive == SR_PRIM_DEFAULT || d->primitive == SR_PRIM_TRIANGLES ||
                          d->primitive == SR_PRIM_TRIANGLE_STRIP ||
                          d->primitive == SR_PRIM_TRIANGLE_FAN;
    bool triangles_only = triangle_prims && ds.mode_front == SR_POLYGON_FILL &&
                          ds.mode_back == SR_POLYGON_FILL;
    size_t record_size =
        sr__record_size(ds.ninterp, ds.shading == SR_SHADING_FLAT, triangles_only);
    sr_front_end fe = { ctx, &ds, d, record_size, chunks, fused, ctx->threads > 1,
                     verts_per_prim, window, base, &mvp, &mv, &nm };
    bool oom = false;
    /* Equal batches of at most the context's batch size, so no batch is a
     * sliver. */
    size_t batches = (prims + ctx->batch_prims - 1) / ctx->batch_prims;
    size_t batch_size = (prims + batches - 1) / batches;
    for (size_t begin = 0; begin < prims && !oom; begin += batch_size) {
        size_t end = prims - begin < batch_size ? prims : begin + batch_size;
        split_batch(s, begin, end, chunks == 1 ? 1 : ctx->threads, chunks);
        sr__pool_run(ctx->pool, sr__run_front_end, &fe, chunks);
        sr__bin_rasterize(ctx, &ds, chunks, fe.tri_size);
        for (int ci = 0; ci < chunks; ci++) {
            sr_chunk *c = &s->chunks[ci];
            sr_draw_info *in = &c->info;
            ctx->last_draw.triangles_in += in->triangles_in;
            ctx->last_draw.triangles_clipped += in->triangles_clipped;
            ctx->last_draw.triangles_culled += in->triangles_culled;
            ctx->last_draw.triangles_drawn += in->triangles_drawn;
            ctx->last_draw.vertices_shaded += in->vertices_shaded;
            memset(in, 0, sizeof *in);
            oom |= c->out_of_memory;
            c->out_of_memory = false;
        }
    }
    for (int i = 0; i < SR_MAX_THREADS; i++) {
        ctx->last_draw.fragments += s->stats[i].fragments;
    }
    if (oom) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY,
                        "sr_draw: out of memory while setting up triangles (the draw is incomplete)");
    }
    return SR_OK;
}
