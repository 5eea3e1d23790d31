/* arena.c - an sr_allocator inside one block of memory the caller gives
 * (sr_context_desc.arena), for systems without malloc: first fit over
 * blocks laid end to end, neighbouring free blocks merged as the search
 * passes them, and the high-water mark recorded.  Not locked: a context
 * with an arena has one thread. */
#include "arena.h"

#include <stdint.h>
#include <string.h>

/* Headers and blocks are this many bytes apart, as the default
 * allocator's blocks (the vector kernels' stores like 64-byte lines). */
#define ALIGN 64u

typedef struct block {
    size_t size;                /* bytes after the header, a multiple of ALIGN */
    size_t free;                /* 1 when free */
    uint8_t pad[ALIGN - 2 * sizeof(size_t)];
} block;
_Static_assert(sizeof(block) == ALIGN, "a block header is one alignment unit");

struct sr_arena {
    uint8_t *first;             /* the first block's header */
    uint8_t *end;               /* just past the last block; free space follows */
    uint8_t *limit;             /* the end of the caller's memory */
    uint8_t *start;             /* the caller's memory */
    size_t peak;                /* the most bytes from start ever in use */
    uint8_t pad[ALIGN - 5 * sizeof(void *)];
};
_Static_assert(sizeof(struct sr_arena) == ALIGN, "the arena's record is one alignment unit");

static block *next_of(block *b)
{
    return (block *)((uint8_t *)(b + 1) + b->size);
}

static void *arena_alloc(size_t size, void *user)
{
    sr_arena *a = user;
    if (size > (size_t)(a->limit - a->start)) {
        return NULL;
    }
    size = (size + ALIGN - 1) & ~(size_t)(ALIGN - 1);
    block *b = (block *)a->first;
    while ((uint8_t *)b < a->end) {
        if (b->free) {
            /* Merge the free blocks that follow; a free run at the end
             * gives its memory back to the free space. */
            block *n = next_of(b);
            while ((uint8_t *)n < a->end && n->free) {
                b->size += sizeof(block) + n->size;
                n = next_of(b);
            }
            if ((uint8_t *)n >= a->end) {
                a->end = (uint8_t *)b;
                break;
            }
            if (b->size >= size) {
                if (b->size >= size + 2 * sizeof(block)) {
                    block *rest = (block *)((uint8_t *)(b + 1) + size);
                    rest->size = b->size - size - sizeof(block);
                    rest->free = 1;
                    b->size = size;
                }
                b->free = 0;
                return b + 1;
            }
        }
        b = next_of(b);
    }
    if ((size_t)(a->limit - a->end) < sizeof(block) + size) {
        return NULL;
    }
    b = (block *)a->end;
    b->size = size;
    b->free = 0;
    a->end = (uint8_t *)(b + 1) + size;
    size_t used = (size_t)(a->end - a->start);
    a->peak = used > a->peak ? used : a->peak;
    return b + 1;
}

static void arena_free(void *ptr, void *user)
{
    sr_arena *a = user;
    block *b = (block *)ptr - 1;
    b->free = 1;
    if ((uint8_t *)next_of(b) == a->end) {
        a->end = (uint8_t *)b;
    }
}

sr_arena *sr__arena_init(void *memory, size_t size, sr_allocator *out)
{
    uintptr_t p = (uintptr_t)memory, aligned = (p + ALIGN - 1) & ~(uintptr_t)(ALIGN - 1);
    if (!memory || size < aligned - p + 2 * ALIGN) {
        return NULL;
    }
    sr_arena *a = (sr_arena *)aligned;
    memset(a, 0, sizeof *a);
    a->start = memory;
    a->limit = (uint8_t *)memory + size;
    a->first = a->end = (uint8_t *)(a + 1);
    a->peak = (size_t)(a->end - a->start);
    *out = (sr_allocator){ .alloc = arena_alloc, .free = arena_free, .user = a };
    return a;
}

size_t sr__arena_peak(const sr_arena *a)
{
    return a ? a->peak : 0;
}
