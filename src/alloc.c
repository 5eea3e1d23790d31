/* alloc.c - memory through an sr_allocator: the default allocator (malloc
 * for small blocks, populated mappings for large ones), overflow-checked
 * zeroed blocks, and the page hints for blocks about to be written.
 * Called from any thread; the allocator must be thread-safe (softrast.h). */
/* MAP_ANONYMOUS and MAP_POPULATE are not POSIX: ask glibc for them. */
#define _DEFAULT_SOURCE 1
#include "alloc.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

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

sr_allocator sr__default_allocator(void)
{
    return (sr_allocator){ .alloc = default_alloc, .free = default_free };
}

void *sr__mem_alloc(const sr_allocator *a, size_t size)
{
    return a->alloc(size ? size : 1, a->user);
}

void *sr__mem_calloc(const sr_allocator *a, size_t count, size_t size)
{
    size_t bytes;
    if (__builtin_mul_overflow(count, size, &bytes)) {
        return NULL;
    }
    void *p = sr__mem_alloc(a, bytes);
    if (p) {
        memset(p, 0, bytes);
    }
    return p;
}

void *sr__mem_alloc_large(const sr_allocator *a, size_t size)
{
    void *p = sr__mem_alloc(a, size);
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

void sr__mem_free(const sr_allocator *a, void *ptr)
{
    if (ptr) {
        a->free(ptr, a->user);
    }
}
