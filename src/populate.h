/* populate.h - fault in a block's pages before it is written, shared by
 * the library (mesh normals) and softrast_io (model arrays).  A static
 * inline function rather than an internal symbol: the two shared libraries
 * export only the public API, so softrast_io cannot call into libsoftrast's
 * internals. */
#ifndef SR_POPULATE_H
#define SR_POPULATE_H

/* MADV_POPULATE_WRITE and MAP_ANONYMOUS are not POSIX: without glibc's
 * default names this would quietly compile to nothing. */
#ifndef _DEFAULT_SOURCE
#error "define _DEFAULT_SOURCE before the first #include to use populate.h"
#endif

#include <stddef.h>
#include <stdint.h>
#include <sys/mman.h>
#include <unistd.h>

#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23       /* Linux 5.14; older kernels say EINVAL */
#endif

/* Fault in at once the pages lying wholly inside [p, p + bytes) of a
 * block about to be written (MADV_POPULATE_WRITE), for malloc'd blocks of
 * SR_POPULATE_MIN bytes and more: on the development VM a page faulted in
 * on first touch costs several times one of a batch (alloc.c).  A no-op
 * for smaller blocks and where the kernel cannot. */
#define SR_POPULATE_MIN ((size_t)64 << 10)

static inline void sr__populate(void *p, size_t bytes)
{
#if defined(MAP_ANONYMOUS)
    if (!p || bytes < SR_POPULATE_MIN) {
        return;
    }
    uintptr_t page = (uintptr_t)sysconf(_SC_PAGESIZE);
    uintptr_t start = ((uintptr_t)p + page - 1) & ~(page - 1);
    uintptr_t end = ((uintptr_t)p + bytes) & ~(page - 1);
    if (end > start) {
        (void)madvise((void *)start, end - start, MADV_POPULATE_WRITE);  /* EINVAL before 5.14 */
    }
#else
    (void)p;
    (void)bytes;
#endif
}

#endif
