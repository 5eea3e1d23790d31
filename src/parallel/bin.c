/* bin.c - tile binning per front-end chunk, and the back end's tile jobs
 * (parallel stage). */
#include "parallel/bin.h"
#include "context.h"

#include <string.h>

static int tile_lo(int p) { return p >> SR_TILE_ORDER; }
static int tile_hi(int p_exclusive) { return (p_exclusive - 1) >> SR_TILE_ORDER; }

static const sr_prim_head *prim_at(const sr_chunk *c, uint32_t i, size_t size)
{
    return (const sr_prim_head *)(c->tris + (size_t)i * size);
}

bool sr__bin_chunk(sr_context *ctx, const sr_draw_state *ds, sr_chunk *c, size_t tri_size)
{
    size_t tiles = (size_t)ds->tiles_x * ds->tiles_y;
    uint32_t *start = c->bin_start;
    memset(start, 0, (tiles + 1) * sizeof(uint32_t));
    /* Count into start[tile + 1], prefix-sum, then place in order. */
    size_t total = 0;
    for (uint32_t i = 0; i < c->tri_count; i++) {
        const sr_prim_head *t = prim_at(c, i, tri_size);
        for (int ty = tile_lo(t->y0); ty <= tile_hi(t->y1); ty++) {
            for (int tx = tile_lo(t->x0); tx <= tile_hi(t->x1); tx++) {
                start[(size_t)ty * ds->tiles_x + tx + 1]++;
                total++;
            }
        }
    }
    if (total > UINT32_MAX || !sr__chunk_reserve_refs(ctx, c, total)) {
        memset(start, 0, (tiles + 1) * sizeof(uint32_t));
        return false;
    }
    for (size_t k = 0; k < tiles; k++) {
        start[k + 1] += start[k];
    }
    /* Fill using start[tile] as a cursor, then shift back. */
    for (uint32_t i = 0; i < c->tri_count; i++) {
        const sr_prim_head *t = prim_at(c, i, tri_size);
        for (int ty = tile_lo(t->y0); ty <= tile_hi(t->y1); ty++) {
            for (int tx = tile_lo(t->x0); tx <= tile_hi(t->x1); tx++) {
                c->refs[start[(size_t)ty * ds->tiles_x + tx]++] = i;
            }
        }
    }
    for (size_t k = tiles; k > 0; k--) {
        start[k] = start[k - 1];
    }
    start[0] = 0;
    return true;
}

typedef struct tile_job {
    sr_context *ctx;
    const sr_draw_state *ds;
    int chunks;
    size_t tri_size;
} tile_job;

static void run_tile(void *arg, int job, int thread)
{
    const tile_job *tj = arg;
    const sr_draw_state *ds = tj->ds;
    sr_scratch *s = tj->ctx->scratch;
    uint32_t tile = s->active_tiles[job];
    int tx = (int)(tile % (uint32_t)ds->tiles_x), ty = (int)(tile / (uint32_t)ds->tiles_x);
    int x0 = tx << SR_TILE_ORDER, y0 = ty << SR_TILE_ORDER;
    int x1 = x0 + SR_TILE_SIZE, y1 = y0 + SR_TILE_SIZE;
    sr_frag_stats *st = &s->stats[thread];

    sr__tile_resolve(ds->fb, (int)tile);
    for (int ci = 0; ci < tj->chunks; ci++) {
        const sr_chunk *c = &s->chunks[ci];
        for (uint32_t r = c->bin_start[tile]; r < c->bin_start[tile + 1]; r++) {
            const sr_prim_head *p = prim_at(c, c->refs[r], tj->tri_size);
            int rx0 = p->x0 > x0 ? p->x0 : x0, rx1 = p->x1 < x1 ? p->x1 : x1;
            int ry0 = p->y0 > y0 ? p->y0 : y0, ry1 = p->y1 < y1 ? p->y1 : y1;
            if (p->kind == SR_KIND_LINE) {
                sr__raster_line(ds, (const sr_line *)p, rx0, ry0, rx1, ry1, st);
                continue;
            }
            if (p->kind == SR_KIND_POINT) {
                sr__raster_point(ds, (const sr_point *)p, rx0, ry0, rx1, ry1, st);
                continue;
            }
            const sr_tri *t = (const sr_tri *)p;
            if (ds->per_sample) {
                sr__raster_sample(ds, t, rx0, ry0, rx1, ry1, st);
                continue;
            }
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
}

void sr__bin_rasterize(sr_context *ctx, const sr_draw_state *ds, int chunks, size_t tri_size)
{
    sr_scratch *s = ctx->scratch;
    uint32_t tiles = (uint32_t)(ds->tiles_x * ds->tiles_y), active = 0;
    for (uint32_t k = 0; k < tiles; k++) {
        for (int ci = 0; ci < chunks; ci++) {
            const sr_chunk *c = &s->chunks[ci];
            if (c->bin_start[k + 1] != c->bin_start[k]) {
                s->active_tiles[active++] = k;
                break;
            }
        }
    }
    tile_job tj = { ctx, ds, chunks, tri_size };
    sr__pool_run(ctx->pool, run_tile, &tj, (int)active);
}
