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

sr_result sr__fail(sr_context *ctx, sr_result code, const char *fmt, ...)
{
    if (ctx) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(ctx->error, sizeof ctx->error, fmt, ap);
        va_end(ap);
    }
    return code;
}

void sr__ok(sr_context *ctx)
{
    ctx->error[0] = 0;
}

const char *sr_context_error(const sr_context *ctx)
{
    return ctx ? ctx->error : "sr_context is NULL";
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
        return SR_INVALID_ARG;
    }
    *out = NULL;
    sr_context_desc d = desc ? *desc : (sr_context_desc){0};
    if ((d.allocator.alloc == NULL) != (d.allocator.free == NULL)) {
        return SR_INVALID_ARG; /* half an allocator: no context to hold a message */
    }
    if (d.threads < 0 || d.threads > SR_MAX_THREADS) {
        return SR_INVALID_ARG;
    }
    if (d.simd < SR_SIMD_DEFAULT || d.simd > SR_SIMD_AVX512) {
        return SR_INVALID_ARG;
    }
    if (d.batch_primitives != 0 &&
        (d.batch_primitives < SR_BATCH_MIN || d.batch_primitives > SR_BATCH_MAX)) {
        return SR_INVALID_ARG;
    }
    sr_arena *arena = NULL;
    if (d.arena) {
        if (d.allocator.alloc || d.threads > 1) {
            return SR_INVALID_ARG; /* an arena is the only memory, on one thread */
        }
        if (d.arena_size > UINTPTR_MAX - (uintptr_t)d.arena) {
            return SR_INVALID_ARG; /* it would run past the end of memory */
        }
        arena = sr__arena_init(d.arena, d.arena_size, &d.allocator);
        if (!arena) {
            return SR_OUT_OF_MEMORY;
        }
        d.threads = 1;
    } else if (d.arena_size) {
        return SR_INVALID_ARG;
    }
    if (!d.allocator.alloc) {
        d.allocator = sr__default_allocator();
    }
    sr_context *ctx = d.allocator.alloc(sizeof *ctx, d.allocator.user);
    if (!ctx) {
        return SR_OUT_OF_MEMORY;
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
        return SR_OUT_OF_MEMORY;
    }
    if (ctx->threads > 1) {
        sr_result r = sr__pool_create(&ctx->allocator, ctx->threads, &ctx->pool);
        if (r != SR_OK) {
            sr_destroy_context(ctx);
            return r;
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
