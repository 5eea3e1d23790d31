/* context.c - context creation, the allocator hooks, error messages and
 * result strings.  Called from the application thread only. */
/* MAP_ANONYMOUS and MAP_POPULATE are not POSIX: ask glibc for them. */
#define _DEFAULT_SOURCE 1
#include "context.h"
#include "parallel/pool.h"
#include "scratch.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stdint.h>
#include <sys/mman.h>
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

/* The default allocator.  Framebuffers and draw scratch are large and
 * written at once; faulting their pages in one by one costs far more than
 * the writes (16 MiB: 45 ms of faults against 14 ms when the kernel maps
 * them in one go, measured on the development VM).  So blocks of 1 MiB and
 * more are mapped with MAP_POPULATE; smaller ones come from malloc.  A
 * 64-byte header records which, keeping 64-byte alignment. */
#define SR_BIG_BLOCK ((size_t)1 << 20)
#define SR_HEADER 64

static void *default_alloc(size_t size, void *user)
{
    (void)user;
    if (size > SIZE_MAX - SR_HEADER) {
        return NULL;
    }
    size_t total = size + SR_HEADER;
    uint8_t *base;
#if defined(MAP_ANONYMOUS) && defined(MAP_POPULATE)
    if (size >= SR_BIG_BLOCK) {
        void *m = mmap(NULL, total, PROT_READ | PROT_WRITE,
                       MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
        if (m == MAP_FAILED) {
            return NULL;
        }
        base = m;
        memcpy(base, &total, sizeof total);
        base[sizeof total] = 1;
        return base + SR_HEADER;
    }
#endif
    if (posix_memalign((void **)&base, SR_HEADER, total) != 0) {
        return NULL;
    }
    memcpy(base, &total, sizeof total);
    base[sizeof total] = 0;
    return base + SR_HEADER;
}

static void default_free(void *ptr, void *user)
{
    (void)user;
    uint8_t *base = (uint8_t *)ptr - SR_HEADER;
    size_t total;
    memcpy(&total, base, sizeof total);
#if defined(MAP_ANONYMOUS) && defined(MAP_POPULATE)
    if (base[sizeof total]) {
        munmap(base, total);
        return;
    }
#endif
    free(base);
}

void *sr__alloc(sr_context *ctx, size_t size)
{
    return ctx->allocator.alloc(size ? size : 1, ctx->allocator.user);
}

void *sr__calloc(sr_context *ctx, size_t count, size_t size)
{
    size_t bytes;
    if (__builtin_mul_overflow(count, size, &bytes)) {
        return NULL;
    }
    void *p = sr__alloc(ctx, bytes);
    if (p) {
        memset(p, 0, bytes);
    }
    return p;
}

void *sr__alloc_large(sr_context *ctx, size_t size)
{
    void *p = sr__alloc(ctx, size);
#if defined(MADV_HUGEPAGE) && defined(SR_TRY_HUGEPAGES)
    /* Only whole 2 MiB-aligned stretches can become huge pages. */
    const uintptr_t huge = (uintptr_t)2 << 20;
    if (p && size >= 2 * huge) {
        uintptr_t start = ((uintptr_t)p + huge - 1) & ~(huge - 1);
        uintptr_t end = ((uintptr_t)p + size) & ~(huge - 1);
        if (end > start) {
            madvise((void *)start, end - start, MADV_HUGEPAGE);
        }
    }
#endif
    return p;
}

void sr__free(sr_context *ctx, void *ptr)
{
    if (ptr) {
        ctx->allocator.free(ptr, ctx->allocator.user);
    }
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

int sr_context_threads(const sr_context *ctx)
{
    return ctx ? ctx->threads : 0;
}

sr_draw_info sr_last_draw_info(const sr_context *ctx)
{
    sr_draw_info none = {0};
    return ctx ? ctx->last_draw : none;
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
    if (!d.allocator.alloc) {
        d.allocator.alloc = default_alloc;
        d.allocator.free = default_free;
    }
    sr_context *ctx = d.allocator.alloc(sizeof *ctx, d.allocator.user);
    if (!ctx) {
        return SR_OUT_OF_MEMORY;
    }
    memset(ctx, 0, sizeof *ctx);
    ctx->allocator = d.allocator;
    ctx->threads = resolve_threads(d.threads);

    ctx->scratch = sr__scratch_create(ctx);
    if (!ctx->scratch) {
        sr_destroy_context(ctx);
        return SR_OUT_OF_MEMORY;
    }
    if (ctx->threads > 1) {
        sr_result r = sr__pool_create(ctx, ctx->threads, &ctx->pool);
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
    sr__pool_destroy(ctx, ctx->pool);
    sr__scratch_destroy(ctx, ctx->scratch);
    ctx->allocator.free(ctx, ctx->allocator.user);
}
