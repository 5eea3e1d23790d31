/* bin.h - binning set-up triangles into 128x128 screen tiles and the back
 * end's tile jobs (parallel stage).  Each front-end chunk sorts its own
 * triangles into per-tile bins (a counting sort, so a bin keeps submission
 * order); a tile job then walks the chunks in order.  A tile's pixels
 * belong to exactly one job, so the result is the same bytes for any
 * thread count. */
#ifndef SR_BIN_H
#define SR_BIN_H

#include "pipeline.h"
#include "scratch.h"

/* A record's tiles for binning, a byte each: columns tx0, tx1 in bits 0-15
 * and rows ty0, ty1 in bits 16-31 (inclusive); SR_TILE_BOX_WALK for an
 * aliased line, whose tiles binning walks from the record itself. */
#define SR_TILE_BOX_WALK UINT32_MAX
_Static_assert(SR_MAX_FRAMEBUFFER_SIZE / SR_TILE_SIZE < 255, "a tile box never equals SR_TILE_BOX_WALK");

static inline uint32_t sr__tile_box(const sr_prim_head *p)
{
    if (p->kind == SR_KIND_LINE && !((const sr_line *)p)->smooth) {
        return SR_TILE_BOX_WALK;
    }
    uint32_t tx0 = (uint32_t)(p->x0 >> SR_TILE_ORDER), tx1 = (uint32_t)((p->x1 - 1) >> SR_TILE_ORDER);
    uint32_t ty0 = (uint32_t)(p->y0 >> SR_TILE_ORDER), ty1 = (uint32_t)((p->y1 - 1) >> SR_TILE_ORDER);
    return tx0 | tx1 << 8 | ty0 << 16 | ty1 << 24;
}

/* Sort chunk c's triangles into its bins (front-end worker); `shared`:
 * more than one thread draws, so the tile jobs read its records on every
 * core, which lets a scattered chunk be copied in tile order.  false when
 * the refs array could not grow. */
bool sr__bin_chunk(sr_context *ctx, const sr_draw_state *ds, sr_chunk *c, size_t tri_size,
                   bool shared);

/* Rasterize every tile that the first `chunks` chunks touched. */
void sr__bin_rasterize(sr_context *ctx, const sr_draw_state *ds, int chunks, size_t tri_size);

#endif
