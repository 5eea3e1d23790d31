/* pool_inline.c - the tile pool without threads (parallel stage), for the
 * embedded profile (SR_EMBEDDED, docs/portability.md): every job runs on
 * the calling thread, in order.  Built instead of pool.c. */
#include "parallel/pool.h"

sr_result sr__pool_create(const sr_allocator *a, int threads, sr_pool **out)
{
    (void)a;
    *out = NULL;
    return threads > 1 ? SR_INVALID_ARG : SR_OK;
}

void sr__pool_destroy(const sr_allocator *a, sr_pool *pool)
{
    (void)a;
    (void)pool;
}

void sr__pool_run(sr_pool *pool, sr_pool_fn fn, void *arg, int count)
{
    (void)pool;
    for (int i = 0; i < count; i++) {
        fn(arg, i, 0);
    }
}
