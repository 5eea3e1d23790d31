/* arena.h - an sr_allocator inside caller-given memory
 * (sr_context_desc.arena).  One thread.  Internal to the library. */
#ifndef SR_ARENA_H
#define SR_ARENA_H

#include "softrast.h"

typedef struct sr_arena sr_arena;

/* Lays an arena out in [memory, memory + size) and sets *out to allocate
 * from it; NULL when the memory cannot hold even its bookkeeping. */
sr_arena *sr__arena_init(void *memory, size_t size, sr_allocator *out);
/* The most bytes from the start of the memory ever in use. */
size_t sr__arena_peak(const sr_arena *a);

#endif
