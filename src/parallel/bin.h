/* bin.h - binning set-up triangles into 64x64 screen tiles and the back
 * end's tile jobs (parallel stage).  Each front-end chunk sorts its own
 * triangles into per-tile bins (a counting sort, so a bin keeps submission
 * order); a tile job then walks the chunks in order.  A tile's pixels
 * belong to exactly one job, so the result is the same bytes for any
 * thread count. */
#ifndef SR_BIN_H
#define SR_BIN_H

#include "pipeline.h"
#include "scratch.h"

/* Sort chunk c's triangles into its bins (front-end worker).  false when
 * the refs array could not grow. */
bool sr__bin_chunk(sr_context *ctx, const sr_draw_state *ds, sr_chunk *c, size_t tri_size);

/* Rasterize every tile that the first `chunks` chunks touched. */
void sr__bin_rasterize(sr_context *ctx, const sr_draw_state *ds, int chunks, size_t tri_size);

#endif
