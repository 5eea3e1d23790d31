/* pool.c - a fixed set of worker threads for the front-end chunks and the
 * tile jobs (parallel stage).  The calling thread works too, so `threads`
 * counts it.
 *
 * A draw hands the pool several short batches in a row (vertex stage, then
 * front end and tiles per batch of primitives), each lasting about a
 * millisecond.  Waking a sleeping thread through a condition variable can
 * take a good part of that on a virtual machine, so a worker that finished
 * a batch first spins briefly, watching the batch counter, and only then
 * sleeps; the caller likewise spins before sleeping on the batch's end. */
#include "parallel/pool.h"
#include "context.h"

#include <pthread.h>
#include <stdatomic.h>

/* About 50-100 microseconds of polling before falling back to sleep. */
#define SR_POOL_SPIN 20000

struct sr_pool {
    int threads;
    pthread_t *workers;
    int started;
    pthread_mutex_t lock;
    pthread_cond_t wake, done;
    atomic_uint_fast64_t generation; /* bumped per batch; workers wait for a change */
    atomic_bool quit;
    /* The current batch. */
    sr_pool_fn fn;
    void *arg;
    int count;
    atomic_int next;
    atomic_int busy;                 /* workers still inside the batch */
};

typedef struct worker_arg {
    sr_pool *pool;
    int index;
} worker_arg;

static void cpu_relax(void)
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
}

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
    uint_fast64_t seen = 0;
    for (;;) {
        for (int i = 0; i < SR_POOL_SPIN && atomic_load(&p->generation) == seen &&
                        !atomic_load(&p->quit); i++) {
            cpu_relax();
        }
        pthread_mutex_lock(&p->lock);
        while (!atomic_load(&p->quit) && atomic_load(&p->generation) == seen) {
            pthread_cond_wait(&p->wake, &p->lock);
        }
        if (atomic_load(&p->quit)) {
            pthread_mutex_unlock(&p->lock);
            break;
        }
        seen = atomic_load(&p->generation);
        pthread_mutex_unlock(&p->lock);

        run_jobs(p, index);

        /* The last worker out tells the caller, under the lock so the
         * wake-up cannot slip between its check and its wait. */
        if (atomic_fetch_sub(&p->busy, 1) == 1) {
            pthread_mutex_lock(&p->lock);
            pthread_cond_signal(&p->done);
            pthread_mutex_unlock(&p->lock);
        }
    }
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
    atomic_init(&p->generation, 0);
    atomic_init(&p->quit, false);
    atomic_init(&p->next, 0);
    atomic_init(&p->busy, 0);
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
    atomic_store(&p->quit, true);
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
    atomic_store(&p->busy, p->started);
    atomic_fetch_add(&p->generation, 1);
    pthread_cond_broadcast(&p->wake);
    pthread_mutex_unlock(&p->lock);

    run_jobs(p, 0);

    for (int i = 0; i < SR_POOL_SPIN && atomic_load(&p->busy) > 0; i++) {
        cpu_relax();
    }
    pthread_mutex_lock(&p->lock);
    while (atomic_load(&p->busy) > 0) {
        pthread_cond_wait(&p->done, &p->lock);
    }
    pthread_mutex_unlock(&p->lock);
}
