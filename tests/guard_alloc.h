/* guard_alloc.h - an allocator that ends every block at an unmapped page
 * (single thread), so a read or write past a buffer's end faults at once,
 * in any build and without a sanitizer; vector loads whose extra lanes are
 * masked off do not fault, so this catches only lanes really used.  Plug it
 * in as (sr_allocator){ guard_alloc, guard_free, &g }, or make a context
 * on it with guard_context, where the platform has mmap
 * (GUARD_ALLOC_WORKS; define _DEFAULT_SOURCE before any header). */
#ifndef SR_GUARD_ALLOC_H
#define SR_GUARD_ALLOC_H

#include "softrast.h"

#include <stddef.h>
#include <stdint.h>

#if defined(__unix__) && !defined(__EMSCRIPTEN__)
#include <sys/mman.h>
#include <unistd.h>
#define GUARD_ALLOC_WORKS 1

enum { GUARD_BLOCKS = 256 };

typedef struct guard {
    struct { void *user, *base; size_t length; } block[GUARD_BLOCKS];
    int live;
} guard;

static inline void *guard_alloc(size_t size, void *user)
{
    guard *g = user;
    size_t page = (size_t)sysconf(_SC_PAGESIZE);
    /* 64-byte aligned, as the default allocator is: a block whose size is
     * a multiple of 64 ends exactly at the guard page. */
    size_t body = (size + 63) & ~(size_t)63;
    size_t mapped = (body + page - 1) / page * page;
    int slot = 0;
    while (slot < GUARD_BLOCKS && g->block[slot].base) {
        slot++;
    }
    if (slot == GUARD_BLOCKS) {
        return NULL;
    }
    uint8_t *base = mmap(NULL, mapped + page, PROT_READ | PROT_WRITE,
                         MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (base == MAP_FAILED) {
        return NULL;
    }
    if (mprotect(base + mapped, page, PROT_NONE) != 0) {
        munmap(base, mapped + page);
        return NULL;
    }
    void *p = base + mapped - body;
    g->block[slot].user = p;
    g->block[slot].base = base;
    g->block[slot].length = mapped + page;
    g->live++;
    return p;
}

static inline void guard_free(void *ptr, void *user)
{
    guard *g = user;
    for (int i = 0; ptr && i < GUARD_BLOCKS; i++) {
        if (g->block[i].user == ptr) {
            munmap(g->block[i].base, g->block[i].length);
            g->block[i].base = g->block[i].user = NULL;
            g->live--;
            return;
        }
    }
}

/* A single-threaded context at SIMD level `level` whose every block ends
 * at a guard page. */
static inline sr_result guard_context(guard *g, int level, sr_context **out)
{
    return sr_make_context(&(sr_context_desc){ .threads = 1, .simd = (sr_simd_level)level,
                                               .allocator = { guard_alloc, guard_free, g } },
                           out);
}
#endif

#endif
