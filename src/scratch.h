/* scratch.h - a draw call's working memory, owned by the context and kept
 * across draws: post-transform vertices (the draw's, or a window of them),
 * and per front-end chunk its
 * set-up triangles and tile bins.  Grown on demand, never shrunk until the
 * context is destroyed, so steady-state frames allocate nothing. */
#ifndef SR_SCRATCH_H
#define SR_SCRATCH_H

#include "pipeline.h"
#include "parallel/pool.h"

#include <stdint.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

/* Primitives per batch (sr_context_desc.batch_primitives): the front end
 * sets up a batch in parallel chunks, the back end rasterizes it, then the
 * next batch follows.  This bounds memory for any draw size while keeping
 * submission order.  The default, 98,304, takes a mesh of up to that many
 * triangles (the bunny, 69,451) through the tiles in one pass: 32,768 took
 * three, and each pass reloads every tile's color and depth (bunny 10%,
 * a million small triangles 16%, 4x MSAA 7% slower, for about 35 MB less
 * scratch at the bunny's size). */
#define SR_CHUNKS_PER_THREAD 4
/* Vertices in the window a context on a fixed budget draws an indexed
 * mesh through (sr_front_end.window): 128 hold a few rows of a patch or
 * grid mesh, whose triangles use vertices near their own place in the
 * order, in 10 KiB for Phong's 80 bytes a vertex. */
#define SR_VERTEX_WINDOW 128
#define SR_MAX_CHUNKS (SR_CHUNKS_PER_THREAD * SR_MAX_THREADS)
/* Draws of fewer primitives are set up as one chunk by the calling thread
 * (sr_draw): their front end, some 500 instructions a triangle, costs
 * less than waking the pool's workers for it. */
#define SR_SMALL_DRAW_PRIMS 64

/* One front-end chunk: a contiguous range of primitives, the triangles it
 * set up (records of tri_size bytes) and its bins by counting sort -
 * bin_start[tile] .. bin_start[tile + 1] index refs[], which holds triangle
 * numbers in submission order, or, when the chunk is in tile order, the
 * copies of its records in ordered[] (sr__bin_chunk). */
/* Each chunk is written by one front-end worker per batch, bumping its
 * counters per triangle: aligned to a cache line of its own so two
 * workers never share one (false sharing doubled the front end's time on
 * two threads). */
typedef struct sr_chunk {
    _Alignas(64) size_t prim_begin, prim_end;
    uint8_t *tris;
    size_t tri_bytes;          /* capacity of tris */
    uint32_t tri_count;
    /* Per record, the tiles it covers (sr__tile_box), written beside the
     * record so that binning need not read the records back. */
    uint32_t *tile_box;
    size_t box_cap;
    uint32_t *refs;
    size_t ref_cap;
    uint32_t *bin_start;       /* tile_cap + 1, valid from bin_lo to bin_hi */
    /* The tiles, in row order, from the first to one past the last that
     * the chunk's primitives reach (sr__bin_chunk): bins outside are empty,
     * whatever bin_start holds there. */
    uint32_t bin_lo, bin_hi;
    bool scattered;            /* few neighbours share a tile (sr__bin_chunk) */
    bool in_tile_order;        /* the tile jobs read ordered[], not refs[] */
    /* This batch's records went out by streaming stores (sr__run_front_end). */
    bool stream;
    uint8_t *ordered;
    size_t ordered_bytes;      /* capacity of ordered */
    sr_draw_info info;
    bool out_of_memory;
} sr_chunk;

typedef struct sr_scratch {
    sr_vertex_post *post;
    float *vary;               /* the draw's nvary per vertex */
    size_t vert_cap;           /* capacity of post, in vertices */
    size_t vary_cap;           /* capacity of vary, in floats */
    /* Drawing through a vertex window (sr_front_end.window): post and vary
     * hold vertices [window_lo, window_hi). */
    size_t window_lo, window_hi;

    sr_chunk chunks[SR_MAX_CHUNKS];
    size_t tile_cap;
    uint32_t *active_tiles;

    sr_frag_stats stats[SR_MAX_THREADS];
} sr_scratch;

sr_scratch *sr__scratch_create(const sr_allocator *a);
void sr__scratch_destroy(const sr_allocator *a, sr_scratch *s);
/* Room for `count` vertices of `nvary` varyings and `tiles` tiles in
 * `chunks` chunks. */
bool sr__scratch_reserve(const sr_allocator *a, sr_scratch *s, size_t count, int nvary,
                         size_t tiles, int chunks);
/* Grow a chunk's triangle store to hold `records` of `size` bytes, and its
 * tile boxes to one per record the store can hold (called
 * from front-end workers: the allocator must be thread-safe). */
bool sr__chunk_reserve_tris(const sr_allocator *a, sr_chunk *c, size_t records, size_t size);
bool sr__chunk_reserve_refs(const sr_allocator *a, sr_chunk *c, size_t refs);
/* Room for `bytes` of records copied in tile order. */
bool sr__chunk_reserve_ordered(const sr_allocator *a, sr_chunk *c, size_t bytes);

/* Copy a record set up on the stack to its place in the chunk with
 * non-temporal stores, when more than one thread draws (but for a chunk
 * copied in tile order the batch before: sr__run_front_end).  The tile
 * jobs of the last batch read the chunk's records on every core; a plain
 * store to such a line must first take it back from the other core's
 * cache, which on the development VM doubled the front end's time
 * on two threads (a prefetch for writing did not help).  A streaming
 * store claims the line without reading it.  `size` is a multiple of 16;
 * a destination that is not 16-byte aligned (a caller's allocator) takes
 * memcpy. */
static inline void sr__stream_record(void *dst, const void *src, size_t size)
{
#if defined(__SSE2__)
    if (((uintptr_t)dst & 15) == 0) {
        for (size_t o = 0; o < size; o += 16) {
            _mm_stream_si128((__m128i *)((char *)dst + o),
                             _mm_loadu_si128((const __m128i *)((const char *)src + o)));
        }
        return;
    }
#endif
    memcpy(dst, src, size);
}

/* Streaming stores are weakly ordered: fence them before another thread
 * reads the records. */
static inline void sr__stream_fence(void)
{
#if defined(__SSE2__)
    _mm_sfence();
#endif
}

#endif
