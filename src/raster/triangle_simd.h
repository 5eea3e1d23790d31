/* triangle_simd.h - choosing the vector kernels of the half-space
 * rasterizer by the context's level (sr_context_desc.simd or SR_SIMD):
 * off forces the scalar loop, base the baseline (SSE2) build. */
#ifndef SR_TRIANGLE_SIMD_H
#define SR_TRIANGLE_SIMD_H

#include "pipeline.h"

/* The vector kernel for this draw's state, or NULL if none applies. */
sr_raster_fn sr__raster_simd_select(const sr_draw_state *ds);
/* The widest level this CPU runs (SR_SIMD_OFF in a build without the
 * kernels); sr_make_context caps the context's level by it. */
sr_simd_level sr__simd_cpu_level(void);

#endif
