/* failing_alloc.h - an allocator for fault-injection tests (single
 * thread): counts allocations, refuses number fail_at (from 0), and counts
 * the blocks still live, so a test can fail every allocation of a call in
 * turn and check that nothing leaked.  Plug it in as
 * (sr_allocator){ fail_alloc, fail_free, &f }. */
#ifndef SR_FAILING_ALLOC_H
#define SR_FAILING_ALLOC_H

#include <stdlib.h>

typedef struct failing {
    long count;      /* allocations so far */
    long fail_at;    /* this one fails; -1: none */
    long live;       /* blocks not yet freed */
    long failed;     /* allocations refused */
} failing;

static inline void *fail_alloc(size_t size, void *user)
{
    failing *f = user;
    if (f->count++ == f->fail_at) {
        f->failed++;
        return NULL;
    }
    void *p = malloc(size);
    f->live += p != NULL;
    return p;
}

static inline void fail_free(void *ptr, void *user)
{
    failing *f = user;
    if (ptr) {
        f->live--;
        free(ptr);
    }
}

#endif
