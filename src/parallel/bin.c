/* bin.c - tile binning and the back end's tile jobs (parallel stage). */
#include "parallel/bin.h"
#include "context.h"
#include "scratch.h"

#include <string.h>

static int tile_lo(int p) { return p >> SR_TILE_ORDER; }
static int tile_hi(int p_exclusive) { return (p_exclusive - 1) >> SR_TILE_ORDER; }

static uint64_t tri_tile_refs(const sr_tri *t)
{
    return (uint64_t)(tile_hi(t->x1) - tile_lo(t->x0) + 1) *
           (uint64_t)(tile_hi(t->y1) - tile_lo(t->y0) + 1);
}

sr_tri *sr__bin_next(sr_binner *b)
{
    sr_scratch *s = b->ctx->scratch;
    if (s->tri_count == SR_BATCH_TRIS) {
        sr__bin_flush(b);
    }
    return &s->tris[s->tri_count];
}

void sr__bin_commit(sr_binner *b)
{
    sr_scratch *s = b->ctx->scratch;
    uint64_t refs = tri_tile_refs(&s->tris[s->tri_count]);
    /* A single triangle never needs more refs than there are tiles, which
     * SR_BATCH_REFS exceeds (128 x 128 tiles at 8192^2). */
    if (s->ref_count + refs > SR_BATCH_REFS) {
        /* Move the new triangle to slot 0 of the next batch. */
        sr_tri t = s->tris[s->tri_count];
        sr__bin_flush(b);
        s->tris[0] = t;
    }
    s->ref_count += refs;
    s->tri_count++;
}

typedef struct tile_job {
    const sr_binner *b;
    const sr_scratch *s;
} tile_job;

static void run_tile(void *arg, int job, int thread)
{
    const tile_job *tj = arg;
    const sr_scratch *s = tj->s;
    const sr_draw_state *ds = tj->b->ds;
    uint32_t tile = s->active_tiles[job];
    int tx = (int)(tile % (uint32_t)tj->b->tiles_x), ty = (int)(tile / (uint32_t)tj->b->tiles_x);
    int x0 = tx << SR_TILE_ORDER, y0 = ty << SR_TILE_ORDER;
    int x1 = x0 + SR_TILE_SIZE, y1 = y0 + SR_TILE_SIZE;
    sr_frag_stats *st = &tj->b->ctx->scratch->stats[thread];

    for (uint32_t r = s->bin_start[tile]; r < s->bin_start[tile + 1]; r++) {
        const sr_tri *t = &s->tris[s->refs[r]];
        int rx0 = t->x0 > x0 ? t->x0 : x0, rx1 = t->x1 < x1 ? t->x1 : x1;
        int ry0 = t->y0 > y0 ? t->y0 : y0, ry1 = t->y1 < y1 ? t->y1 : y1;
        switch (ds->rasterizer) {
        case SR_RASTER_SCANLINE:
            sr__raster_scanline(ds, t, rx0, ry0, rx1, ry1, st);
            break;
        case SR_RASTER_BARYCENTRIC:
            sr__raster_barycentric(ds, t, rx0, ry0, rx1, ry1, st);
            break;
        default:
            sr__raster_halfspace(ds, t, rx0, ry0, rx1, ry1, st);
            break;
        }
    }
}

void sr__bin_flush(sr_binner *b)
{
    sr_scratch *s = b->ctx->scratch;
    if (s->tri_count == 0) {
        return;
    }
    size_t tiles = (size_t)b->tiles_x * (size_t)b->tiles_y;
    memset(s->bin_fill, 0, tiles * sizeof(uint32_t));

    /* Counting sort: count refs per tile, prefix-sum, then place triangle
     * indices in submission order. */
    for (uint32_t i = 0; i < s->tri_count; i++) {
        const sr_tri *t = &s->tris[i];
        for (int ty = tile_lo(t->y0); ty <= tile_hi(t->y1); ty++) {
            for (int tx = tile_lo(t->x0); tx <= tile_hi(t->x1); tx++) {
                s->bin_fill[(size_t)ty * b->tiles_x + tx]++;
            }
        }
    }
    uint32_t sum = 0, active = 0;
    for (size_t k = 0; k < tiles; k++) {
        s->bin_start[k] = sum;
        sum += s->bin_fill[k];
        if (s->bin_fill[k]) {
            s->active_tiles[active++] = (uint32_t)k;
        }
        s->bin_fill[k] = s->bin_start[k];
    }
    s->bin_start[tiles] = sum;
    for (uint32_t i = 0; i < s->tri_count; i++) {
        const sr_tri *t = &s->tris[i];
        for (int ty = tile_lo(t->y0); ty <= tile_hi(t->y1); ty++) {
            for (int tx = tile_lo(t->x0); tx <= tile_hi(t->x1); tx++) {
                s->refs[s->bin_fill[(size_t)ty * b->tiles_x + tx]++] = i;
            }
        }
    }

    tile_job tj = { b, s };
    sr__pool_run(b->ctx->pool, run_tile, &tj, (int)active);
    s->tri_count = 0;
    s->ref_count = 0;
}
