/* triangle_simd.h - choosing the vector kernels of the half-space
 * rasterizer.  SR_SIMD=off in the environment forces the scalar loop,
 * SR_SIMD=base the baseline (SSE2) build of the kernels. */
#ifndef SR_TRIANGLE_SIMD_H
#define SR_TRIANGLE_SIMD_H

#include "pipeline.h"

/* The vector kernel for this draw's state, or NULL if none applies. */
sr_raster_fn sr__raster_simd_select(const sr_draw_state *ds);
const char *sr__raster_simd_name(void);

#endif
