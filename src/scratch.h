/* scratch.h - a draw call's working memory, owned by the context and kept
 * across draws: transformed vertices, the current batch of set-up triangles
 * and their tile bins.  Grown on demand, never shrunk until the context is
 * destroyed, so steady-state frames allocate nothing. */
#ifndef SR_SCRATCH_H
#define SR_SCRATCH_H

#include "pipeline.h"
#include "parallel/pool.h"

/* Triangles per batch, and tile references per batch: when either fills,
 * the batch is rasterized and the front end carries on.  This bounds memory
 * for any draw size while keeping submission order. */
#define SR_BATCH_TRIS 8192
#define SR_BATCH_REFS (1u << 20)

typedef struct sr_scratch {
    sr_clip_vertex *verts;
    size_t vert_cap;

    sr_tri *tris;              /* SR_BATCH_TRIS */
    uint32_t tri_count;
    uint64_t ref_count;        /* tile references of the batch so far */

    /* Bins by counting sort: bin_start[tile] .. bin_start[tile+1] in refs. */
    uint32_t *bin_start;       /* tile_cap + 1 */
    uint32_t *bin_fill;        /* tile_cap */
    uint32_t *refs;            /* SR_BATCH_REFS */
    size_t tile_cap;
    uint32_t *active_tiles;    /* tiles with a non-empty bin */

    sr_frag_stats stats[SR_MAX_THREADS];
} sr_scratch;

sr_scratch *sr__scratch_create(sr_context *ctx);
void sr__scratch_destroy(sr_context *ctx, sr_scratch *s);
/* Make room for `count` vertices and `tiles` tiles; false when out of memory. */
bool sr__scratch_reserve(sr_context *ctx, sr_scratch *s, size_t count, size_t tiles);

#endif
