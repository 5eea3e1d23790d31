/* context.c - context creation (its settings resolved once: allocator,
 * threads, vector level, the pool and scratch memory), error messages and
 * result strings.  Called from the application thread only. */
/* _SC_NPROCESSORS_ONLN is not POSIX: ask glibc for it. */
#define _DEFAULT_SOURCE 1
#include "context.h"
#include "arena.h"
#include "parallel/pool.h"
#include "scratch.h"
#include "raster/triangle_simd.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stdint.h>
#include <unistd.h>

static const char *result_names[] = {
#define SR__X(name, text) "SR_" #name,
    SR_RESULT_LIST(SR__X)
#undef SR__X
};
static const char *result_texts[] = {
#define SR__X(name, text) text,
    SR_RESULT_LIST(SR__X)
#undef SR__X
};

const char *sr_result_name(sr_result r)
{
    return (unsigned)r < SR_RESULT_COUNT ? result_names[r] : "SR_UNKNOWN";
}

const char *sr_result_text(sr_result r)
{
    return (unsigned)r < SR_RESULT_COUNT ? result_texts[r] : "unknown result";
}


size_t sr_context_arena_peak(const sr_context *ctx)
{
    return ctx ? sr__arena_peak(ctx->arena) : 0;
}

int sr_context_threads(const sr_context *ctx)
{
    return ctx ? ctx->threads : 0;
}

sr_simd_level sr_context_simd(const sr_context *ctx)
{
    return ctx ? ctx->simd : SR_SIMD_OFF;
}

sr_result sr_run_jobs(sr_context *ctx, sr_job_fn fn, void *arg, int count)
{
    if (!fn) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_run_jobs: fn is NULL");
    }
    if (count < 0) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_run_jobs: count %d is negative", count);
    }
    if (!ctx) {
        sr__pool_run(NULL, fn, arg, count);
        return SR_OK;
    }
    sr__pool_run(ctx->pool, fn, arg, count);
    sr__ok(ctx);
    return SR_OK;
}

sr_draw_info sr_last_draw_info(const sr_context *ctx)
{
    sr_draw_info none = {0};
    return ctx ? ctx->last_draw : none;
}

/* SR_SIMD_DEFAULT means: the SR_SIMD environment variable, else the
 * widest level; either way capped by what the CPU runs. */
static sr_simd_level resolve_simd(sr_simd_level requested)
{
    if (requested == SR_SIMD_DEFAULT) {
        static const struct { const char *name; sr_simd_level level; } names[] = {
            { "off", SR_SIMD_OFF }, { "base", SR_SIMD_BASE }, { "avx2", SR_SIMD_AVX2 },
            { "avx512", SR_SIMD_AVX512 },
        };
        const char *env = getenv("SR_SIMD");
        requested = SR_SIMD_AVX512;
        for (size_t i = 0; env && i < sizeof names / sizeof names[0]; i++) {
            if (strcmp(env, names[i].name) == 0) {
                requested = names[i].level;
            }
        }
    }
    sr_simd_level cpu = sr__simd_cpu_level();
    return requested < cpu ? requested : cpu;
}

/* 0 threads means: the SR_THREADS environment variable, else one per CPU. */
static int resolve_threads(int requested)
{
    if (requested > 0) {
        return requested;
    }
    const char *env = getenv("SR_THREADS");
    if (env && *env) {
        char *end;
        long n = strtol(env, &end, 10);
        if (*end == 0 && n >= 1 && n <= SR_MAX_THREADS) {
            return (int)n;
        }
    }
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    if (cpus < 1) {
        cpus = 1;
    }
    return cpus > SR_MAX_THREADS ? SR_MAX_THREADS : (int)cpus;
}

sr_result sr_make_context(const sr_context_desc *desc, sr_context **out)
{
    if (!out) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_make_context: out is NULL");
    }
    *out = NULL;
    sr_context_desc d = desc ? *desc : (sr_context_desc){0};
    /* No context yet to hold a message: they go to sr_last_error alone. */
    if ((d.allocator.alloc == NULL) != (d.allocator.free == NULL)) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_context_desc.allocator has %s but no %s",
                        d.allocator.alloc ? "alloc" : "free", d.allocator.alloc ? "free" : "alloc");
    }
    if (d.threads < 0 || d.threads > SR_MAX_THREADS) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_context_desc.threads must be in 0..%d (got %d)",
                        SR_MAX_THREADS, d.threads);
    }
    if (d.simd < SR_SIMD_DEFAULT || d.simd > SR_SIMD_AVX512) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_context_desc.simd %d is not an sr_simd_level",
                        (int)d.simd);
    }
    if (d.batch_primitives != 0 &&
        (d.batch_primitives < SR_BATCH_MIN || d.batch_primitives > SR_BATCH_MAX)) {
        return sr__fail(NULL, SR_INVALID_ARG,
                        "sr_context_desc.batch_primitives must be 0 or in %d..%d (got %d)",
                        SR_BATCH_MIN, SR_BATCH_MAX, d.batch_primitives);
    }
    sr_arena *arena = NULL;
    if (d.arena) {
        if (d.allocator.alloc || d.threads > 1) {
            /* An arena is the only memory, on one thread. */
            return sr__fail(NULL, SR_INVALID_ARG, "sr_context_desc.arena excludes %s",
                            d.allocator.alloc ? "an allocator" : "threads > 1");
        }
        if (d.arena_size > UINTPTR_MAX - (uintptr_t)d.arena) {
            return sr__fail(NULL, SR_INVALID_ARG,
                            "sr_context_desc.arena_size %zu runs past the end of memory",
                            d.arena_size);
        }
        arena = sr__arena_init(d.arena, d.arena_size, &d.allocator);
        if (!arena) {
            return sr__fail(NULL, SR_OUT_OF_MEMORY,
                            "sr_context_desc.arena_size %zu is too small for a context",
                            d.arena_size);
        }
        d.threads = 1;
    } else if (d.arena_size) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_context_desc.arena_size %zu without an arena",
                        d.arena_size);
    }
    if (!d.allocator.alloc) {
        d.allocator = sr__default_allocator();
    }
    sr_context *ctx = d.allocator.alloc(sizeof *ctx, d.allocator.user);
    if (!ctx) {
        return sr__fail(NULL, SR_OUT_OF_MEMORY, "sr_make_context: out of memory");
    }
    memset(ctx, 0, sizeof *ctx);
    ctx->allocator = d.allocator;
    ctx->arena = arena;
    ctx->threads = resolve_threads(d.threads);
    ctx->simd = resolve_simd(d.simd);
    ctx->batch_prims = d.batch_primitives ? (size_t)d.batch_primitives : SR_BATCH_DEFAULT;
    ctx->oct.budget = d.radiance_cache_bytes ? d.radiance_cache_bytes : SR_RADIANCE_CACHE_DEFAULT;

    ctx->scratch = sr__scratch_create(&ctx->allocator);
    if (!ctx->scratch) {
        sr_destroy_context(ctx);
        return sr__fail(NULL, SR_OUT_OF_MEMORY, "sr_make_context: out of memory");
    }
    if (ctx->threads > 1) {
        int threads = ctx->threads;
        sr_result r = sr__pool_create(&ctx->allocator, threads, &ctx->pool);
        if (r != SR_OK) {
            sr_destroy_context(ctx);
            return sr__fail(NULL, r, "sr_make_context: cannot start %d threads: %s", threads,
                            sr_result_text(r));
        }
    }
    *out = ctx;
    return SR_OK;
}

void sr_destroy_context(sr_context *ctx)
{
    if (!ctx) {
        return;
    }
    sr__pool_destroy(&ctx->allocator, ctx->pool);
    sr__scratch_destroy(&ctx->allocator, ctx->scratch);
    sr__free(ctx, ctx->gradient);
    sr__oct_cache_free(ctx);
    ctx->allocator.free(ctx, ctx->allocator.user);
}
