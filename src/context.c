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
 * the writes.  Measured on the development VM for 16 MiB: 45 ms faulted
 * page by page; 3-8 ms mapped with MAP_POPULATE plus 8-24 ms for the first
 * write; 1-2 ms populated as transparent huge pages plus under 1 ms for
 * the first write (rarely ~50 ms when the kernel must compact memory
 * first).  So blocks of 4 MiB and more are mapped 2 MiB-aligned, marked
 * MADV_HUGEPAGE and populated with MADV_POPULATE_WRITE; blocks of 1 MiB
 * and more are mapped with MAP_POPULATE; smaller ones come from malloc.  A
 * 64-byte header before the block records how to free it. */
#define SR_BIG_BLOCK ((size_t)1 << 20)
#define SR_HUGE_BLOCK ((size_t)4 << 20)
#define SR_HUGE_PAGE ((size_t)2 << 20)
#define SR_HEADER 64
#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23       /* Linux 5.14; older kernels say EINVAL */
#endif

typedef struct block_header {
    void *base;                      /* what mmap or malloc returned */
    size_t length;                   /* mapped bytes, 0 for malloc */
} block_header;

static void *default_alloc(size_t size, void *user)
{
    (void)user;
    if (size > SIZE_MAX - SR_HEADER - SR_HUGE_PAGE) {
        return NULL;
    }
    uint8_t *block;
    block_header h = { NULL, 0 };
#if defined(MAP_ANONYMOUS) && defined(MAP_POPULATE)
    if (size >= SR_HUGE_BLOCK) {
        /* Room for the header before a 2 MiB-aligned block. */
        size_t length = size + SR_HUGE_PAGE + SR_HEADER;
        void *m = mmap(NULL, length, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (m == MAP_FAILED) {
            return NULL;
        }
        block = (uint8_t *)(((uintptr_t)m + SR_HEADER + SR_HUGE_PAGE - 1) & ~(SR_HUGE_PAGE - 1));
#ifdef MADV_HUGEPAGE
        madvise(block, size, MADV_HUGEPAGE);
#endif
        /* Only the block: the alignment slack around it is never touched,
         * and populating it cost up to 2 MiB of small pages a block. */
        if (madvise(block, size, MADV_POPULATE_WRITE) != 0) {
            /* An older kernel: pages arrive on first touch instead. */
        }
        h = (block_header){ m, length };
    } else if (size >= SR_BIG_BLOCK) {
        size_t length = size + SR_HEADER;
        void *m = mmap(NULL, length, PROT_READ | PROT_WRITE,
                       MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
        if (m == MAP_FAILED) {
            return NULL;
        }
        block = (uint8_t *)m + SR_HEADER;
        h = (block_header){ m, length };
    } else
#endif
    {
        void *m;
        if (posix_memalign(&m, SR_HEADER, size + SR_HEADER) != 0) {
            return NULL;
        }
        block = (uint8_t *)m + SR_HEADER;
        h = (block_header){ m, 0 };
    }
    memcpy(block - SR_HEADER, &h, sizeof h);
    return block;
}

static void default_free(void *ptr, void *user)
{
    (void)user;
    block_header h;
    memcpy(&h, (uint8_t *)ptr - SR_HEADER, sizeof h);
#if defined(MAP_ANONYMOUS) && defined(MAP_POPULATE)
    if (h.length) {
        munmap(h.base, h.length);
        return;
    }
#endif
    free(h.base);
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
    if (d.batch_primitives != 0 &&
        (d.batch_primitives < SR_BATCH_MIN || d.batch_primitives > SR_BATCH_MAX)) {
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
    ctx->batch_prims = d.batch_primitives ? (size_t)d.batch_primitives : SR_BATCH_DEFAULT;

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
