/* bin.h - binning set-up triangles into 64x64 screen tiles and rasterizing
 * the bins (parallel stage).  The front end appends triangles to the
 * context's batch; sr__bin_flush sorts their tile references into per-tile
 * bins (a counting sort, so each bin keeps submission order) and runs one
 * job per non-empty tile on the pool.  A tile's pixels belong to exactly
 * one job, so the result is the same bytes for any thread count. */
#ifndef SR_BIN_H
#define SR_BIN_H

#include "pipeline.h"

typedef struct sr_binner {
    sr_context *ctx;
    const sr_draw_state *ds;
    int tiles_x, tiles_y;
} sr_binner;

/* The next free triangle slot of the batch (flushing first if full). */
sr_tri *sr__bin_next(sr_binner *b);
/* Commit the triangle just written to the slot from sr__bin_next. */
void sr__bin_commit(sr_binner *b);
void sr__bin_flush(sr_binner *b);

#endif
