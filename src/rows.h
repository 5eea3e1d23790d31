/* rows.h - whether a caller's image of `rows` rows, `stride` bytes apart,
 * the last `row_bytes` long, can be addressed from `base`: the span
 * (rows - 1) * stride + row_bytes must fit in size_t, in PTRDIFF_MAX (no
 * object is larger: C's pointer differences within it must be
 * representable) and must not run past the top of the address space.  A stride too large for that describes a
 * buffer that cannot exist, and stepping by it would wrap the pointer onto
 * memory the caller never gave.  Any thread.  Internal to the library. */
#ifndef SR_ROWS_H
#define SR_ROWS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

static inline bool sr__rows_fit(const void *base, size_t rows, size_t stride, size_t row_bytes)
{
    if (rows == 0) {
        return true;
    }
    if (stride != 0 && rows - 1 > (SIZE_MAX - row_bytes) / stride) {
        return false;
    }
    size_t span = (rows - 1) * stride + row_bytes;
    return span <= (size_t)PTRDIFF_MAX && span <= UINTPTR_MAX - (uintptr_t)base;
}

#endif
