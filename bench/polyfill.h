/* polyfill.h - the 2D fill benchmark: one 10,000-edge random polygon
 * filled at 2048x2048 by softrast's edge-table filler (aliased) or its
 * exact-area antialiasing, and, when the build found cairo, by cairo in the
 * same run, alternating. */
#ifndef SR_BENCH_POLYFILL_H
#define SR_BENCH_POLYFILL_H

#include "softrast.h"

/* Prints the result lines; returns false on failure (after a message). */
bool bench_polyfill(sr_context *ctx, int threads, int frames, bool compare, bool antialias,
                    const char *scene);

#endif
