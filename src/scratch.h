/* scratch.h - a draw call's working memory, owned by the context and kept
 * across draws: post-transform vertices, and per front-end chunk its
 * set-up triangles and tile bins.  Grown on demand, never shrunk until the
 * context is destroyed, so steady-state frames allocate nothing. */
#ifndef SR_SCRATCH_H
#define SR_SCRATCH_H

#include "pipeline.h"
#include "parallel/pool.h"

/* Primitives per batch (sr_context_desc.batch_primitives): the front end
 * sets up a batch in parallel chunks, the back end rasterizes it, then the
 * next batch follows.  This bounds memory for any draw size while keeping
 * submission order.  The default, 98,304, takes a mesh of up to that many
 * triangles (the bunny, 69,451) through the tiles in one pass: 32,768 took
 * three, and each pass reloads every tile's color and depth (bunny 10%,
 * a million small triangles 16%, 4x MSAA 7% slower, for about 35 MB less
 * scratch at the bunny's size). */
#define SR_MAX_CHUNKS (2 * SR_MAX_THREADS)

/* One front-end chunk: a contiguous range of primitives, the triangles it
 * set up (records of tri_size bytes) and its bins by counting sort -
 * bin_start[tile] .. bin_start[tile + 1] index refs[], which holds triangle
 * numbers in submission order. */
/* Each chunk is written by one front-end worker per batch, bumping its
 * counters per triangle: aligned to a cache line of its own so two
 * workers never share one (false sharing doubled the front end's time on
 * two threads). */
typedef struct sr_chunk {
    _Alignas(64) size_t prim_begin, prim_end;
    uint8_t *tris;
    size_t tri_bytes;          /* capacity of tris */
    uint32_t tri_count;
    uint32_t *refs;
    size_t ref_cap;
    uint32_t *bin_start;       /* tile_cap + 1 */
    sr_draw_info info;
    bool out_of_memory;
} sr_chunk;

typedef struct sr_scratch {
    sr_vertex_post *post;
    float *vary;               /* SR_MAX_VARYINGS per vertex at most */
    size_t vert_cap;

    sr_chunk chunks[SR_MAX_CHUNKS];
    size_t tile_cap;
    uint32_t *active_tiles;

    sr_frag_stats stats[SR_MAX_THREADS];
} sr_scratch;

sr_scratch *sr__scratch_create(sr_context *ctx);
void sr__scratch_destroy(sr_context *ctx, sr_scratch *s);
/* Room for `count` vertices and `tiles` tiles in `chunks` chunks. */
bool sr__scratch_reserve(sr_context *ctx, sr_scratch *s, size_t count, size_t tiles, int chunks);
/* Grow a chunk's triangle store to hold `records` of `size` bytes (called
 * from front-end workers: the allocator must be thread-safe). */
bool sr__chunk_reserve_tris(sr_context *ctx, sr_chunk *c, size_t records, size_t size);
bool sr__chunk_reserve_refs(sr_context *ctx, sr_chunk *c, size_t refs);

#endif
