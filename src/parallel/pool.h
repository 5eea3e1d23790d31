/* pool.h - the tile thread pool (parallel stage).  Created with the
 * context; sr__pool_run hands out job indices 0..count-1 to the calling
 * thread and the workers and returns when all are done.  Thread t first
 * runs the t-th contiguous share of the jobs in order, then helps with the
 * others' (pool.c).  Jobs must be independent (tiles write disjoint
 * pixels). */
#ifndef SR_POOL_H
#define SR_POOL_H

#include "softrast.h"

/* The embedded profile has no threads: one chunk set and one set of
 * per-thread records in the draw scratch instead of 64. */
#ifdef SR_EMBEDDED
#define SR_MAX_THREADS 1
#else
#define SR_MAX_THREADS 64
#endif

typedef struct sr_pool sr_pool;
/* fn(arg, job, thread) - thread is 0 for the caller, 1..n-1 for workers. */
typedef void (*sr_pool_fn)(void *arg, int job, int thread);

/* The pool's memory comes from `a`, which must outlive it. */
sr_result sr__pool_create(const sr_allocator *a, int threads, sr_pool **out);
void sr__pool_destroy(const sr_allocator *a, sr_pool *pool);
/* With pool == NULL, runs every job on the calling thread. */
void sr__pool_run(sr_pool *pool, sr_pool_fn fn, void *arg, int count);

#endif
