/* pool.c - a fixed set of worker threads for the front-end chunks and the
 * tile jobs (parallel stage).  The calling thread works too, so `threads`
 * counts it.
 *
 * A draw hands the pool several short batches in a row (vertex stage, then
 * front end and tiles per batch of primitives), each lasting about a
 * millisecond.  Waking a sleeping thread through a condition variable can
 * take a good part of that on a virtual machine, so a worker that finished
 * a batch first spins briefly, watching the batch counter, and only then
 * sleeps; the caller likewise spins before sleeping on the batch's end.
 *
 * A worker joins a batch only while it is open, and the caller waits only
 * for the workers that joined: when the caller has taken every job itself
 * (a worker still waking from sleep, a batch of a few jobs), it closes the
 * batch and goes on at once rather than waiting out the wake-up, and the
 * late worker finds the batch closed. */
#include "parallel/pool.h"
#include "alloc.h"

#include <pthread.h>
#include <stdatomic.h>

/* Polling before falling back to sleep: 20,000 pauses take about 360 us
 * on the development machine (AMD family 26; a pause is some 18 ns). */
#define SR_POOL_SPIN 20000

/* The batch word: the batch's generation in the high 32 bits, OPEN while
 * workers may join, and the count of workers inside it in the low bits. */
#define BATCH_OPEN ((uint_fast64_t)1 << 31)
#define BATCH_ACTIVE ((uint_fast64_t)BATCH_OPEN - 1)
#define BATCH_GEN(v) ((uint32_t)((v) >> 32))

struct sr_pool {
    int threads;
    pthread_t *workers;
    int started;
    pthread_mutex_t lock;
    pthread_cond_t wake, done;
    atomic_uint_fast64_t batch;
    atomic_bool quit;
    /* The current batch, written before it opens. */
    sr_pool_fn fn;
    void *arg;
    /* Per thread, the jobs it owns this batch: front (next to run, low 32
     * bits) and end (high 32 bits), 64 bytes apart so that no two share a
     * cache line. */
    struct {
        atomic_uint_fast64_t range;
        char pad[64 - sizeof(atomic_uint_fast64_t)];
    } own[SR_MAX_THREADS];
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

#define RANGE(front, end) ((uint_fast64_t)(front) | (uint_fast64_t)(end) << 32)

/* The owner takes its range's first job; a thief its last. */
static int take(sr_pool *p, int owner, bool steal)
{
    atomic_uint_fast64_t *r = &p->own[owner].range;
    uint_fast64_t v = atomic_load_explicit(r, memory_order_relaxed);
    for (;;) {
        uint32_t front = (uint32_t)v, end = (uint32_t)(v >> 32);
        if (front >= end) {
            return -1;
        }
        uint_fast64_t next = steal ? RANGE(front, end - 1) : RANGE(front + 1, end);
        if (atomic_compare_exchange_weak_explicit(r, &v, next, memory_order_relaxed,
                                                  memory_order_relaxed)) {
            return (int)(steal ? end - 1 : front);
        }
    }
}

/* Thread t owns the t-th contiguous share of the jobs and runs it in
 * order; then it takes the last jobs of the others.  Consecutive batches
 * with the same job layout (the tiles of one frame and the next, a mesh's
 * vertex blocks and the primitives that use them) so run mostly on the
 * same core and find their data in its cache: on the development VM a
 * line that was written on the other core costs several times a local
 * one. */
static void run_jobs(sr_pool *p, int thread)
{
    int job;
    while ((job = take(p, thread, false)) >= 0) {
        p->fn(p->arg, job, thread);
    }
    for (int k = 1; k < p->threads; k++) {
        int victim = (thread + k) % p->threads;
        while ((job = take(p, victim, true)) >= 0) {
            p->fn(p->arg, job, thread);
        }
    }
}

/* Join the open batch after generation `seen`: true with the worker
 * counted in it, false when there is none to join (yet, or any more). */
static bool join(sr_pool *p, uint32_t *seen)
{
    uint_fast64_t v = atomic_load_explicit(&p->batch, memory_order_acquire);
    while (BATCH_GEN(v) != *seen) {
        if (!(v & BATCH_OPEN)) {
            *seen = BATCH_GEN(v); /* closed before this worker came: skip it */
            return false;
        }
        if (atomic_compare_exchange_weak_explicit(&p->batch, &v, v + 1, memory_order_acquire,
                                                  memory_order_acquire)) {
            *seen = BATCH_GEN(v);
            return true;
        }
    }
    return false;
}

static bool batch_waiting(sr_pool *p, uint32_t seen)
{
    uint_fast64_t v = atomic_load_explicit(&p->batch, memory_order_relaxed);
    return BATCH_GEN(v) != seen && (v & BATCH_OPEN);
}

static void *worker_main(void *arg)
{
    sr_pool *p = ((worker_arg *)arg)->pool;
    int index = ((worker_arg *)arg)->index;
    uint32_t seen = 0;
    for (;;) {
        for (int i = 0; i < SR_POOL_SPIN && !batch_waiting(p, seen) && !atomic_load(&p->quit);
             i++) {
            cpu_relax();
        }
        if (!batch_waiting(p, seen)) {
            pthread_mutex_lock(&p->lock);
            while (!atomic_load(&p->quit) && !batch_waiting(p, seen)) {
                pthread_cond_wait(&p->wake, &p->lock);
            }
            pthread_mutex_unlock(&p->lock);
        }
        if (atomic_load(&p->quit)) {
            break;
        }
        if (!join(p, &seen)) {
            continue;
        }
        run_jobs(p, index);

        /* The last worker out tells the caller, under the lock so the
         * wake-up cannot slip between its check and its wait. */
        uint_fast64_t left = atomic_fetch_sub_explicit(&p->batch, 1, memory_order_release) - 1;
        if ((left & BATCH_ACTIVE) == 0) {
            pthread_mutex_lock(&p->lock);
            pthread_cond_signal(&p->done);
            pthread_mutex_unlock(&p->lock);
        }
    }
    return NULL;
}

/* The worker args live right after the pool in one allocation.  Failures
 * carry no message: sr_make_context, the only caller, then has no
 * context to keep one on. */
sr_result sr__pool_create(const sr_allocator *a, int threads, sr_pool **out)
{
    *out = NULL;
    size_t bytes = sizeof(sr_pool) + (size_t)threads * (sizeof(pthread_t) + sizeof(worker_arg));
    sr_pool *p = sr__mem_calloc(a, 1, bytes);
    if (!p) {
        return SR_OUT_OF_MEMORY;
    }
    p->threads = threads;
    p->workers = (pthread_t *)(p + 1);
    worker_arg *args = (worker_arg *)(p->workers + threads);
    pthread_mutex_init(&p->lock, NULL);
    pthread_cond_init(&p->wake, NULL);
    pthread_cond_init(&p->done, NULL);
    atomic_init(&p->batch, 0);
    atomic_init(&p->quit, false);
    for (int i = 0; i < SR_MAX_THREADS; i++) {
        atomic_init(&p->own[i].range, 0);
    }
    for (int i = 1; i < threads; i++) {
        args[i] = (worker_arg){ p, i };
        if (pthread_create(&p->workers[i], NULL, worker_main, &args[i]) != 0) {
            sr__pool_destroy(a, p);
            return SR_OUT_OF_MEMORY;
        }
        p->started = i;
    }
    *out = p;
    return SR_OK;
}

void sr__pool_destroy(const sr_allocator *a, sr_pool *p)
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
    sr__mem_free(a, p);
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
    /* No worker is inside a batch here (the last one closed empty), so
     * the batch's fields are the caller's to write until it opens. */
    p->fn = fn;
    p->arg = arg;
    for (int t = 0; t < p->threads; t++) {
        uint32_t lo = (uint32_t)((int64_t)count * t / p->threads);
        uint32_t hi = (uint32_t)((int64_t)count * (t + 1) / p->threads);
        atomic_store_explicit(&p->own[t].range, RANGE(lo, hi), memory_order_relaxed);
    }
    uint32_t gen = BATCH_GEN(atomic_load_explicit(&p->batch, memory_order_relaxed)) + 1;
    pthread_mutex_lock(&p->lock);
    atomic_store_explicit(&p->batch, (uint_fast64_t)gen << 32 | BATCH_OPEN, memory_order_release);
    pthread_cond_broadcast(&p->wake);
    pthread_mutex_unlock(&p->lock);

    run_jobs(p, 0);

    /* Every job is taken: close the batch once no worker is inside it. */
    uint_fast64_t open = (uint_fast64_t)gen << 32 | BATCH_OPEN;
    for (int i = 0; i < SR_POOL_SPIN; i++) {
        uint_fast64_t v = open;
        if (atomic_compare_exchange_weak_explicit(&p->batch, &v, (uint_fast64_t)gen << 32,
                                                  memory_order_acquire, memory_order_relaxed)) {
            return;
        }
        cpu_relax();
    }
    pthread_mutex_lock(&p->lock);
    for (;;) {
        uint_fast64_t v = open;
        if (atomic_compare_exchange_strong_explicit(&p->batch, &v, (uint_fast64_t)gen << 32,
                                                    memory_order_acquire, memory_order_relaxed)) {
            break;
        }
        pthread_cond_wait(&p->done, &p->lock);
    }
    pthread_mutex_unlock(&p->lock);
}
