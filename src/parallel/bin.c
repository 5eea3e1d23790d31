/* bin.c - tile binning per front-end chunk, and the back end's tile jobs
 * (parallel stage). */
#include "parallel/bin.h"
#include "context.h"

#include <string.h>


static const sr_prim_head *prim_at(const sr_chunk *c, uint32_t i, size_t size)
{
    return (const sr_prim_head *)(c->tris + (size_t)i * size);
}

/* Where binning puts primitive i at place `at` of a tile's bin: its
 * number in refs[], or, in a chunk in tile order, a copy of its record in
 * ordered[]. */
typedef struct placer {
    const sr_chunk *c;
    size_t size;
    bool ordered;              /* c->in_tile_order */
} placer;

static inline void place(const placer *pl, uint32_t at, uint32_t i)
{
    const sr_chunk *c = pl->c;
    if (pl->ordered) {
        sr__stream_record(c->ordered + (size_t)at * pl->size, prim_at(c, i, pl->size), pl->size);
    } else {
        c->refs[at] = i;
    }
}

/* An aliased line goes only into the tiles its pixels reach, not every
 * tile of its bounding box (a long diagonal touches about half of them):
 * tile column by tile column along its major axis, the tile rows its
 * pixels take there - listed by setup for lines of up to
 * SR_LINE_BIN_COLUMNS tile columns, else asked of line.c.  Counts into
 * start[tile + 1] when pl is NULL, else places i at start[tile]. */
static size_t bin_line(const sr_draw_state *ds, const sr_line *l, uint32_t *start,
                       const placer *pl, uint32_t i)
{
    bool listed = l->bin_count <= SR_LINE_BIN_COLUMNS;
    int tu0 = l->bin_tu0, tu1 = tu0 + l->bin_count - 1;
    if (!listed) {
        sr__line_tile_columns(l, &tu0, &tu1);
    }
    size_t n = 0;
    for (int tu = tu0; tu <= tu1; tu++) {
        int tv0, tv1;
        if (listed) {
            tv0 = l->bin_rows[2 * (tu - tu0)];
            tv1 = l->bin_rows[2 * (tu - tu0) + 1];
        } else if (!sr__line_tile_rows(l, tu, &tv0, &tv1)) {
            continue;
        }
        for (int tv = tv0; tv <= tv1; tv++) {
            size_t tile = l->xmajor ? (size_t)tv * ds->tiles_x + tu : (size_t)tu * ds->tiles_x + tv;
            if (pl) {
                place(pl, start[tile]++, i);
            } else {
                start[tile + 1]++;
            }
            n++;
        }
    }
    return n;
}

bool sr__bin_chunk(sr_context *ctx, const sr_draw_state *ds, sr_chunk *c, size_t tri_size,
                   bool shared)
{
    size_t tiles = (size_t)ds->tiles_x * ds->tiles_y;
    uint32_t *start = c->bin_start;
    size_t tiles_x = (size_t)ds->tiles_x;
    const uint32_t *box = c->tile_box;
    /* The bins from the first tile the primitives reach to the last, in
     * row order: a small draw's binning then costs its own tiles, not
     * the target's (a node of a few triangles among 1280x720's 60 tiles). */
    size_t lo = c->tri_count ? tiles : 0, hi = 0;
    for (uint32_t i = 0; i < c->tri_count; i++) {
        if (box[i] == SR_TILE_BOX_WALK) {
            lo = 0;
            hi = tiles;
            break;
        }
        size_t first = (size_t)(box[i] >> 16 & 0xff) * tiles_x + (box[i] & 0xff);
        size_t last = (size_t)(box[i] >> 24) * tiles_x + (box[i] >> 8 & 0xff);
        lo = first < lo ? first : lo;
        hi = last + 1 > hi ? last + 1 : hi;
    }
    c->bin_lo = (uint32_t)lo;
    c->bin_hi = (uint32_t)hi;
    memset(start + lo, 0, (hi - lo + 1) * sizeof(uint32_t));
    /* Count into start[tile + 1], prefix-sum, then place in order.  Most
     * primitives lie in one tile: one step, no loops. */
    size_t total = 0;
    uint32_t far = 0;     /* primitives starting over a tile away from the one before */
    for (uint32_t i = 0; i < c->tri_count; i++) {
        if (i > 0) {
            int dx = (int)(box[i] & 0xff) - (int)(box[i - 1] & 0xff);
            int dy = (int)(box[i] >> 16 & 0xff) - (int)(box[i - 1] >> 16 & 0xff);
            far += dx < -1 || dx > 1 || dy < -1 || dy > 1;
        }
        if (box[i] == SR_TILE_BOX_WALK) {
            total += bin_line(ds, (const sr_line *)prim_at(c, i, tri_size), start, NULL, i);
            continue;
        }
        int tx0 = box[i] & 0xff, tx1 = box[i] >> 8 & 0xff;
        int ty0 = box[i] >> 16 & 0xff, ty1 = box[i] >> 24;
        uint32_t *row = start + 1 + (size_t)ty0 * tiles_x;
        if (tx0 == tx1 && ty0 == ty1) {
            row[tx0]++;
            total++;
            continue;
        }
        for (int ty = ty0; ty <= ty1; ty++, row += tiles_x) {
            for (int tx = tx0; tx <= tx1; tx++) {
                row[tx]++;
            }
        }
        total += (size_t)(tx1 - tx0 + 1) * (size_t)(ty1 - ty0 + 1);
    }
    /* Scattered primitives (run_tile prefetches their pixels): in the
     * bench's `small` 98% of them start over a tile away from the one
     * before; in the meshes (the bunny's order jumps about too) 2-51%. */
    c->scattered = far > c->tri_count / 4 * 3;
    /* A tile job reads its records in submission order, each from a
     * different place in the chunk.  Streamed out to memory, or in
     * another core's cache (more than one thread), a scattered chunk's
     * records arrive one miss at a time: on two threads the bench's
     * `small` spent a quarter of its time in the tile jobs waiting for
     * them.  So such a chunk, when its primitives mostly lie in one tile,
     * is copied in tile order: the copy reads the records in the order
     * they were written, and each tile job reads its own one after the
     * other (small 90 -> 80 ms on two threads).  A primitive is copied
     * once per tile it covers, hence "mostly in one tile".  On one
     * thread, where the core that reads the records wrote them with plain
     * stores, the copy measured level: it would only double the records'
     * memory. */
    c->in_tile_order = shared && c->scattered && total <= c->tri_count + c->tri_count / 4 &&
                       total <= SIZE_MAX / tri_size &&
                       sr__chunk_reserve_ordered(&ctx->allocator, c, total * tri_size);
    if (total > UINT32_MAX || (!c->in_tile_order && !sr__chunk_reserve_refs(&ctx->allocator, c, total))) {
        c->bin_lo = c->bin_hi = 0;
        c->in_tile_order = false;
        return false;
    }
    for (size_t k = lo; k < hi; k++) {
        start[k + 1] += start[k];
    }
    /* Fill using start[tile] as a cursor, then shift back. */
    placer pl = { c, tri_size, c->in_tile_order };
    for (uint32_t i = 0; i < c->tri_count; i++) {
        if (box[i] == SR_TILE_BOX_WALK) {
            bin_line(ds, (const sr_line *)prim_at(c, i, tri_size), start, &pl, i);
            continue;
        }
        int tx0 = box[i] & 0xff, tx1 = box[i] >> 8 & 0xff;
        int ty0 = box[i] >> 16 & 0xff, ty1 = box[i] >> 24;
        uint32_t *row = start + (size_t)ty0 * tiles_x;
        if (tx0 == tx1 && ty0 == ty1) {
            place(&pl, row[tx0]++, i);
            continue;
        }
        for (int ty = ty0; ty <= ty1; ty++, row += tiles_x) {
            for (int tx = tx0; tx <= tx1; tx++) {
                place(&pl, row[tx]++, i);
            }
        }
    }
    if (c->in_tile_order) {
        sr__stream_fence();
    }
    for (size_t k = hi; k > lo; k--) {
        start[k] = start[k - 1];
    }
    start[lo] = 0;
    return true;
}

/* Record number r of a tile's bin in chunk c (bin_start[tile] <= r <
 * bin_start[tile + 1]); `ordered`: c->in_tile_order. */
static inline const sr_prim_head *binned(const sr_chunk *c, uint32_t r, size_t size,
                                         bool ordered)
{
    if (ordered) {
        return (const sr_prim_head *)(c->ordered + (size_t)r * size);
    }
    return prim_at(c, c->refs[r], size);
}

#define SR_PREFETCH_AHEAD 4

/* Refs ahead whose pixels are prefetched, and the size up to which a
 * record counts as a small triangle for it (pixels). */
#define SR_PIXEL_PREFETCH_AHEAD 2
#define SR_PIXEL_PREFETCH_MAX   8

/* A tile's color and depth (128 KiB) do not fit in L1 beside the records
 * streaming through, and small triangles scattered over the tile (the
 * bench's `small`) stall on every one's depth load: on 1 thread a quarter
 * of the kernel's time.  So in a scattered chunk (sr__bin_chunk) the lines
 * under the small triangle `ahead` are fetched while an earlier one is
 * drawn.  A mesh's next triangle lies beside the last ones, whose lines
 * are in cache already: there the prefetch only cost time (bunny +4%).
 * Always inlined: GCC counts a prefetch as no effect, so a call of this
 * function would be dropped. */
static inline __attribute__((always_inline)) void
prefetch_pixels(const sr_framebuffer *fb, const sr_prim_head *ahead, int x0, int y0, int x1,
                int y1)
{
    int qx0 = ahead->x0 > x0 ? ahead->x0 : x0, qx1 = ahead->x1 < x1 ? ahead->x1 : x1;
    int qy0 = ahead->y0 > y0 ? ahead->y0 : y0, qy1 = ahead->y1 < y1 ? ahead->y1 : y1;
    if (qx0 >= qx1 || qy1 - qy0 > SR_PIXEL_PREFETCH_MAX || qx1 - qx0 > SR_PIXEL_PREFETCH_MAX) {
        return;
    }
    /* A pixel's samples are consecutive elements (framebuffer.h). */
    size_t ns = (size_t)fb->samples, w = (size_t)fb->width;
    for (int y = qy0; y < qy1; y++) {
        size_t first = ((size_t)y * w + (size_t)qx0) * ns;
        size_t last = ((size_t)y * w + (size_t)qx1) * ns - 1;
        __builtin_prefetch(&fb->color[first], 1);
        __builtin_prefetch(&fb->color[last], 1);
        if (fb->depth) {
            const char *d = fb->depth;
            __builtin_prefetch(d + first * (size_t)sr__depth_size(fb), 1);
            __builtin_prefetch(d + last * (size_t)sr__depth_size(fb), 1);
        }
    }
}

typedef struct tile_job {
    sr_context *ctx;
    const sr_draw_state *ds;
    int chunks;
    size_t tri_size;
} tile_job;

/* The tile's part of the drawing rectangle. */
typedef struct tile_rect {
    int x0, y0, x1, y1;
} tile_rect;

/* Draw chunk c's bin of one tile, in submission order.  Always inlined
 * with `ordered` constant (c->in_tile_order), so each way of reading the
 * records gets its own loop. */
static inline __attribute__((always_inline)) void
draw_bin(const tile_job *tj, const sr_chunk *c, uint32_t tile, tile_rect b, sr_frag_stats *st,
         tile_rect *drawn, bool ordered)
{
    if (tile < c->bin_lo || tile >= c->bin_hi) {
        return;
    }
    const sr_draw_state *ds = tj->ds;
    size_t size = tj->tri_size;
    uint32_t end = c->bin_start[tile + 1];
    for (uint32_t r = c->bin_start[tile]; r < end; r++) {
        /* A tile's records lie scattered through the chunk, and on more
         * than one thread they were streamed out to memory (scratch.h) or
         * sit in another core's cache:
         * fetch the whole record a few refs ahead while this one is
         * drawn.  In tile order they lie one after the other, and the
         * hardware's prefetcher helps too. */
        if (r + SR_PREFETCH_AHEAD < end) {
            const char *ahead = (const char *)binned(c, r + SR_PREFETCH_AHEAD, size, ordered);
            for (size_t o = 0; o < size; o += 64) {
                __builtin_prefetch(ahead + o);
            }
            __builtin_prefetch(ahead + size - 1);
        }
        const sr_prim_head *p = binned(c, r, size, ordered);
        if (c->scattered && r + SR_PIXEL_PREFETCH_AHEAD < end) {
            prefetch_pixels(ds->fb, binned(c, r + SR_PIXEL_PREFETCH_AHEAD, size, ordered), b.x0,
                            b.y0, b.x1, b.y1);
        }
        int rx0 = p->x0 > b.x0 ? p->x0 : b.x0, rx1 = p->x1 < b.x1 ? p->x1 : b.x1;
        int ry0 = p->y0 > b.y0 ? p->y0 : b.y0, ry1 = p->y1 < b.y1 ? p->y1 : b.y1;
        /* What the rasterizers may write: the next clear writes no more
         * of the tile than this (sr__tile_drawn). */
        drawn->x0 = rx0 < drawn->x0 ? rx0 : drawn->x0;
        drawn->y0 = ry0 < drawn->y0 ? ry0 : drawn->y0;
        drawn->x1 = rx1 > drawn->x1 ? rx1 : drawn->x1;
        drawn->y1 = ry1 > drawn->y1 ? ry1 : drawn->y1;
        if (p->kind == SR_KIND_LINE) {
            sr__raster_line(ds, (const sr_line *)p, rx0, ry0, rx1, ry1, st);
            continue;
        }
        if (p->kind == SR_KIND_POINT) {
            sr__raster_point(ds, (const sr_point *)p, rx0, ry0, rx1, ry1, st);
            continue;
        }
        ds->raster_tri(ds, (const sr_tri *)p, rx0, ry0, rx1, ry1, st);
    }
}

static void run_tile(void *arg, int job, int thread)
{
    const tile_job *tj = arg;
    const sr_draw_state *ds = tj->ds;
    sr_scratch *s = tj->ctx->scratch;
    uint32_t tile = s->active_tiles[job];
    int tx = (int)(tile % (uint32_t)ds->tiles_x), ty = (int)(tile / (uint32_t)ds->tiles_x);
    int x0 = tx << SR_TILE_ORDER, y0 = ty << SR_TILE_ORDER;
    tile_rect b = { x0, y0, x0 + SR_TILE_SIZE, y0 + SR_TILE_SIZE };
    sr_frag_stats *st = &s->stats[thread];

    sr__tile_resolve(ds->fb, (int)tile, ds->wide_stores);
    tile_rect drawn = { b.x1, b.y1, b.x0, b.y0 };   /* empty */
    for (int ci = 0; ci < tj->chunks; ci++) {
        const sr_chunk *c = &s->chunks[ci];
        if (c->in_tile_order) {
            draw_bin(tj, c, tile, b, st, &drawn, true);
        } else {
            draw_bin(tj, c, tile, b, st, &drawn, false);
        }
    }
    sr__tile_drawn(ds->fb, (int)tile, drawn.x0, drawn.y0, drawn.x1, drawn.y1);
}

void sr__bin_rasterize(sr_context *ctx, const sr_draw_state *ds, int chunks, size_t tri_size)
{
    sr_scratch *s = ctx->scratch;
    uint32_t lo = UINT32_MAX, hi = 0, active = 0;
    for (int ci = 0; ci < chunks; ci++) {
        const sr_chunk *c = &s->chunks[ci];
        if (c->bin_lo < c->bin_hi) {
            lo = c->bin_lo < lo ? c->bin_lo : lo;
            hi = c->bin_hi > hi ? c->bin_hi : hi;
        }
    }
    for (uint32_t k = lo; k < hi; k++) {
        for (int ci = 0; ci < chunks; ci++) {
            const sr_chunk *c = &s->chunks[ci];
            if (k >= c->bin_lo && k < c->bin_hi && c->bin_start[k + 1] != c->bin_start[k]) {
                s->active_tiles[active++] = k;
                break;
            }
        }
    }
    tile_job tj = { ctx, ds, chunks, tri_size };
    sr__pool_run(ctx->pool, run_tile, &tj, (int)active);
}
