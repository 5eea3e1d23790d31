/* pool.c - a fixed set of worker threads that sleep on a condition variable
 * between batches of tile jobs (parallel stage).  The calling thread works
 * too, so `threads` counts it. */
#include "parallel/pool.h"
#include "context.h"

#include <pthread.h>
#include <stdatomic.h>

struct sr_pool {
    int threads;
    pthread_t *workers;
    int started;
    pthread_mutex_t lock;
    pthread_cond_t wake, done;
    uint64_t generation;    /* bumped per batch; workers wait for a change */
    bool quit;
    /* The current batch. */
    sr_pool_fn fn;
    void *arg;
    int count;
    atomic_int next;
    int busy;               /* workers still inside the batch */
};

typedef struct worker_arg {
    sr_pool *pool;
    int index;
} worker_arg;

static void run_jobs(sr_pool *p, int thread)
{
    for (;;) {
        int job = atomic_fetch_add_explicit(&p->next, 1, memory_order_relaxed);
        if (job >= p->count) {
            return;
        }
        p->fn(p->arg, job, thread);
    }
}

static void *worker_main(void *arg)
{
    sr_pool *p = ((worker_arg *)arg)->pool;
    int index = ((worker_arg *)arg)->index;
    uint64_t seen = 0;
    pthread_mutex_lock(&p->lock);
    for (;;) {
        while (!p->quit && p->generation == seen) {
            pthread_cond_wait(&p->wake, &p->lock);
        }
        if (p->quit) {
            break;
        }
        seen = p->generation;
        pthread_mutex_unlock(&p->lock);
        run_jobs(p, index);
        pthread_mutex_lock(&p->lock);
        if (--p->busy == 0) {
            pthread_cond_signal(&p->done);
        }
    }
    pthread_mutex_unlock(&p->lock);
    return NULL;
}

/* The worker args live right after the pool in one allocation. */
sr_result sr__pool_create(sr_context *ctx, int threads, sr_pool **out)
{
    *out = NULL;
    size_t bytes = sizeof(sr_pool) + (size_t)threads * (sizeof(pthread_t) + sizeof(worker_arg));
    sr_pool *p = sr__calloc(ctx, 1, bytes);
    if (!p) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_make_context: out of memory for the thread pool");
    }
    p->threads = threads;
    p->workers = (pthread_t *)(p + 1);
    worker_arg *args = (worker_arg *)(p->workers + threads);
    pthread_mutex_init(&p->lock, NULL);
    pthread_cond_init(&p->wake, NULL);
    pthread_cond_init(&p->done, NULL);
    atomic_init(&p->next, 0);
    for (int i = 1; i < threads; i++) {
        args[i] = (worker_arg){ p, i };
        if (pthread_create(&p->workers[i], NULL, worker_main, &args[i]) != 0) {
            sr__pool_destroy(ctx, p);
            return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_make_context: cannot start thread %d", i);
        }
        p->started = i;
    }
    *out = p;
    return SR_OK;
}

void sr__pool_destroy(sr_context *ctx, sr_pool *p)
{
    if (!p) {
        return;
    }
    pthread_mutex_lock(&p->lock);
    p->quit = true;
    pthread_cond_broadcast(&p->wake);
    pthread_mutex_unlock(&p->lock);
    for (int i = 1; i <= p->started; i++) {
        pthread_join(p->workers[i], NULL);
    }
    pthread_mutex_destroy(&p->lock);
    pthread_cond_destroy(&p->wake);
    pthread_cond_destroy(&p->done);
    sr__free(ctx, p);
}

void sr__pool_run(sr_pool *p, sr_pool_fn fn, void *arg, int count)
{
    if (count <= 0) {
        return;
    }
    if (!p || count == 1) {
        for (int i = 0; i < count; i++) {
            fn(arg, i, 0);
        }
        return;
    }
    pthread_mutex_lock(&p->lock);
    p->fn = fn;
    p->arg = arg;
    p->count = count;
    atomic_store(&p->next, 0);
    p->busy = p->started;
    p->generation++;
    pthread_cond_broadcast(&p->wake);
    pthread_mutex_unlock(&p->lock);

    run_jobs(p, 0);

    pthread_mutex_lock(&p->lock);
    while (p->busy > 0) {
        pthread_cond_wait(&p->done, &p->lock);
    }
    pthread_mutex_unlock(&p->lock);
}
