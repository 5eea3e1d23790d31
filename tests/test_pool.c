/* test_pool.c - the thread pool hands out every job of a batch exactly
 * once, whoever runs it: each thread first runs its own contiguous share
 * in order, then takes the last jobs of the others (pool.c). */
#include "sr_test.h"
#include "context.h"
#include "parallel/pool.h"
#include "softrast.h"

#include <stdatomic.h>
#include <stdlib.h>
#include <time.h>

enum { MAX_JOBS = 5000 };

typedef struct batch {
    atomic_int runs[MAX_JOBS];
    atomic_int bad_thread;
    int threads;
    /* Per thread, the last job it ran from its own share, to see that a
     * share runs in order. */
    int last_own[SR_MAX_THREADS];
    int count;
    atomic_int out_of_order;
} batch;

static void job(void *arg, int j, int thread)
{
    batch *b = arg;
    atomic_fetch_add(&b->runs[j], 1);
    if (thread < 0 || thread >= b->threads) {
        atomic_store(&b->bad_thread, 1);
        return;
    }
    /* Jobs of the thread's own share come first and in increasing order;
     * stolen jobs come from the others' shares. */
    int lo = (int)((long long)b->count * thread / b->threads);
    int hi = (int)((long long)b->count * (thread + 1) / b->threads);
    if (j >= lo && j < hi) {
        if (j <= b->last_own[thread]) {
            atomic_store(&b->out_of_order, 1);
        }
        b->last_own[thread] = j;
    }
}

/* Ready b for a batch of n jobs on `threads` threads: runs[0..n) zeroed. */
static void start_batch(batch *b, int threads, int n)
{
    for (int j = 0; j < n; j++) {
        atomic_store(&b->runs[j], 0);
    }
    for (int t = 0; t < SR_MAX_THREADS; t++) {
        b->last_own[t] = -1;
    }
    atomic_store(&b->bad_thread, 0);
    atomic_store(&b->out_of_order, 0);
    b->threads = threads;
    b->count = n;
}

SR_TEST(every_job_runs_once_at_any_thread_count)
{
    static const int threads[] = { 1, 2, 3, 5, 8 };
    static const int counts[] = { 0, 1, 2, 3, 7, 8, 9, 64, 1000, MAX_JOBS };
    static batch b;
    for (size_t ti = 0; ti < sizeof threads / sizeof *threads; ti++) {
        sr_context *ctx = NULL;
        REQUIRE(sr_make_context(&(sr_context_desc){ .threads = threads[ti] }, &ctx) == SR_OK);
        CHECK_EQ(sr_context_threads(ctx), threads[ti]);
        /* Many batches in a row: a worker still leaving one batch must not
         * take jobs of the next. */
        for (int rep = 0; rep < 50; rep++) {
            for (size_t ci = 0; ci < sizeof counts / sizeof *counts; ci++) {
                int n = counts[ci];
                start_batch(&b, threads[ti], n);
                for (int j = n; j < MAX_JOBS; j++) {
                    atomic_store(&b.runs[j], 0);
                }
                sr__pool_run(ctx->pool, job, &b, n);
                int wrong = 0;
                for (int j = 0; j < MAX_JOBS; j++) {
                    wrong += atomic_load(&b.runs[j]) != (j < n ? 1 : 0);
                }
                CHECK_EQ(wrong, 0);
                CHECK_EQ(atomic_load(&b.bad_thread), 0);
                CHECK_EQ(atomic_load(&b.out_of_order), 0);
                if (sr_test_failed_now()) {
                    sr_destroy_context(ctx);
                    return;
                }
            }
        }
        sr_destroy_context(ctx);
    }
}

/* Batches handed to workers asleep (the pause between them outlasts the
 * workers' spinning): the caller may take every job before a worker wakes
 * and close the batch without it; the late worker must then sit that
 * batch out and still join the next.  Every job runs exactly once. */
SR_TEST(batches_for_sleeping_workers_run_every_job_once)
{
    static batch b;
    for (int threads = 2; threads <= 3; threads++) {
        sr_context *ctx = NULL;
        REQUIRE(sr_make_context(&(sr_context_desc){ .threads = threads }, &ctx) == SR_OK);
        for (int rep = 0; rep < 40; rep++) {
            int n = 1 + rep % 5;
            start_batch(&b, threads, n);
            if (rep % 2) {
                nanosleep(&(struct timespec){ 0, 2000000 }, NULL); /* 2 ms: workers asleep */
            }
            sr__pool_run(ctx->pool, job, &b, n);
            int wrong = 0;
            for (int j = 0; j < n; j++) {
                wrong += atomic_load(&b.runs[j]) != 1;
            }
            CHECK_EQ(wrong, 0);
            CHECK_EQ(atomic_load(&b.bad_thread), 0);
            CHECK_EQ(atomic_load(&b.out_of_order), 0);
        }
        sr_destroy_context(ctx);
    }
}

/* sr_run_jobs, the pool as the public API offers it: every job once on the
 * context's threads, or on the caller alone without a context; a NULL
 * function or a negative count is refused and named. */
SR_TEST(run_jobs_runs_every_job_once_and_checks_its_arguments)
{
    static batch b;
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 3 }, &ctx) == SR_OK);
    for (int with_ctx = 0; with_ctx <= 1; with_ctx++) {
        int n = 500;
        start_batch(&b, with_ctx ? 3 : 1, n);
        CHECK_EQ(sr_run_jobs(with_ctx ? ctx : NULL, job, &b, n), SR_OK);
        int wrong = 0;
        for (int j = 0; j < n; j++) {
            wrong += atomic_load(&b.runs[j]) != 1;
        }
        CHECK_EQ(wrong, 0);
        CHECK_EQ(atomic_load(&b.bad_thread), 0);
    }
    CHECK_EQ(sr_run_jobs(ctx, NULL, &b, 4), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "fn");
    CHECK_EQ(sr_run_jobs(ctx, job, &b, -1), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "count");
    CHECK_EQ(sr_run_jobs(NULL, NULL, &b, 4), SR_INVALID_ARG);
    sr_destroy_context(ctx);
}
