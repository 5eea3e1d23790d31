/* context.h - the sr_context: allocator, error message, per-draw scratch
 * memory kept across draws (so a frame never faults fresh pages back in),
 * and the tile thread pool.  Internal to the library. */
#ifndef SR_CONTEXT_H
#define SR_CONTEXT_H

#include "softrast.h"
#include "alloc.h"
#include "error.h"
#include "fragment/oct_cache.h"

#include <stdarg.h>

struct sr_pool;
struct sr_scratch;
struct sr__gradient;

struct sr_context {
    sr_allocator allocator;
    struct sr_arena *arena;        /* sr_context_desc.arena's, or NULL */
    int threads;
    sr_simd_level simd;        /* resolved once by sr_make_context; every draw follows it */
    size_t batch_prims;        /* sr_context_desc.batch_primitives, resolved */
    struct sr_pool *pool;          /* NULL when threads == 1 */
    struct sr_scratch *scratch;    /* draw-call working memory, grown on demand */
    struct sr__gradient *gradient; /* the last painted fill's gradient (paint_api.c) */
    /* Maps the pbr programs made with this context share, kept after their
     * programs (fragment/oct_cache.h): a scene's draws make a program
     * each, mostly of a few materials, and building a map is 4096 queries
     * of the environment. */
    sr__oct_cache oct;
    sr_draw_info last_draw;
    char error[256];
};

/* The context's allocator (alloc.h). */
static inline void *sr__alloc(sr_context *ctx, size_t size)
{
    return sr__mem_alloc(&ctx->allocator, size);
}
static inline void *sr__calloc(sr_context *ctx, size_t count, size_t size)
{
    return sr__mem_calloc(&ctx->allocator, count, size);
}
static inline void sr__free(sr_context *ctx, void *ptr)
{
    sr__mem_free(&ctx->allocator, ptr);
}
static inline void *sr__alloc_large(sr_context *ctx, size_t size)
{
    return sr__mem_alloc_large(&ctx->allocator, size);
}

/* A success clears ctx's message (sr__fail, error.h, sets it). */
void sr__ok(sr_context *ctx);

#endif
