/* alloc.h - memory through an sr_allocator (the context's, passed by
 * whoever owns the memory: the context, the pool, the scratch arenas), so
 * that the layers below the context need not know it.  Any thread.
 * Internal to the library. */
#ifndef SR_ALLOC_H
#define SR_ALLOC_H

#include "softrast.h"

/* The allocator a context uses when its desc leaves it zero. */
sr_allocator sr__default_allocator(void);

void *sr__mem_alloc(const sr_allocator *a, size_t size);
/* Overflow-checked and zeroed. */
void *sr__mem_calloc(const sr_allocator *a, size_t count, size_t size);
void  sr__mem_free(const sr_allocator *a, void *ptr);
/* A large buffer that will be written soon: ask the kernel for
 * transparent huge pages over it, so filling it takes a few page faults
 * instead of thousands (a no-op where unsupported). */
void *sr__mem_alloc_large(const sr_allocator *a, size_t size);

#endif
