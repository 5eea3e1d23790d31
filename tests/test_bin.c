/* test_bin.c - binning a chunk's primitives into tiles (parallel/bin.c):
 * each tile's refs list exactly the primitives whose tile box covers it,
 * in submission order, and a chunk is marked scattered - its tile jobs
 * prefetch pixels - when most primitives start over a tile away from the
 * one before, and only then; a scattered chunk of records streamed out to
 * memory is copied in tile order when its primitives lie mostly in one
 * tile; a chunk's bins span only the tiles from the first to the last its
 * primitives reach, whatever the counters outside hold; and the streaming
 * copy of a record (scratch.h) writes exactly its bytes. */
#include "sr_test.h"
#include "context.h"
#include "parallel/bin.h"
#include "softrast.h"

#include <stdlib.h>
#include <string.h>

enum { TILES_X = 30, TILES_Y = 17, PRIMS = 2000 };

static uint32_t box(int tx0, int tx1, int ty0, int ty1)
{
    return (uint32_t)tx0 | (uint32_t)tx1 << 8 | (uint32_t)ty0 << 16 | (uint32_t)ty1 << 24;
}

static uint32_t next_random(uint64_t *s)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (uint32_t)(*s >> 33);
}

typedef struct bin_flags {
    bool scattered, in_tile_order;
} bin_flags;

enum { RECORD = 128 };

/* Bin `boxes` as one chunk whose records (RECORD bytes, each filled with
 * its own number) went out by streaming stores or not.  Check every
 * tile's bin against the boxes - its refs, or in a chunk in tile order
 * its copies of the records - and return the chunk's flags. */
static bin_flags bin_and_check(const uint32_t *boxes, uint32_t n, bool streamed)
{
    bin_flags f = { false, false };
    sr_context *ctx = NULL;
    if (sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) != SR_OK) {
        CHECK(!"sr_make_context");
        return f;
    }
    sr_draw_state ds = { 0 };
    ds.tiles_x = TILES_X;
    ds.tiles_y = TILES_Y;
    sr_chunk c = { 0 };
    c.tile_box = (uint32_t *)boxes;
    c.tri_count = n;
    c.bin_start = malloc((TILES_X * TILES_Y + 1) * sizeof(uint32_t));
    c.tris = aligned_alloc(64, (size_t)n * RECORD);
    bool ok = c.bin_start && c.tris;
    if (c.bin_start) {
        /* What an earlier draw's bins may have left: binning sets the
         * counters of the tiles it spans and no others. */
        memset(c.bin_start, 0xa5, (TILES_X * TILES_Y + 1) * sizeof(uint32_t));
    }
    for (uint32_t i = 0; ok && i < n; i++) {
        for (int w = 0; w < RECORD / 4; w++) {
            memcpy(c.tris + (size_t)i * RECORD + 4 * w, &i, 4);
        }
    }
    ok = ok && sr__bin_chunk(ctx, &ds, &c, RECORD, streamed);
    CHECK(ok);
    CHECK(c.bin_lo <= c.bin_hi && c.bin_hi <= TILES_X * TILES_Y);
    for (int tile = 0; ok && tile < TILES_X * TILES_Y; tile++) {
        int tx = tile % TILES_X, ty = tile / TILES_X;
        /* Outside the span a bin is empty (parallel/bin.c reads none). */
        bool spanned = (uint32_t)tile >= c.bin_lo && (uint32_t)tile < c.bin_hi;
        uint32_t r = spanned ? c.bin_start[tile] : 0;
        uint32_t end = spanned ? c.bin_start[tile + 1] : 0;
        for (uint32_t i = 0; i < n; i++) {
            uint32_t b = boxes[i];
            bool covers = tx >= (int)(b & 0xff) && tx <= (int)(b >> 8 & 0xff) &&
                          ty >= (int)(b >> 16 & 0xff) && ty <= (int)(b >> 24);
            if (covers) {
                /* The next of this tile, in submission order. */
                CHECK(r < end);
                if (c.in_tile_order) {
                    CHECK(memcmp(c.ordered + (size_t)r * RECORD, c.tris + (size_t)i * RECORD,
                                 RECORD) == 0);
                } else {
                    CHECK(c.refs[r] == i);
                }
                r++;
            }
        }
        CHECK_EQ(r, end);
    }
    f.scattered = c.scattered;
    f.in_tile_order = c.in_tile_order;
    sr__free(ctx, c.refs);
    sr__free(ctx, c.ordered);
    free(c.tris);
    free(c.bin_start);
    sr_destroy_context(ctx);
    return f;
}

/* Random boxes of one tile, every `wide`-th (0: none) two tiles wide. */
static void random_boxes(uint32_t *boxes, int n, uint64_t seed, int wide)
{
    for (int i = 0; i < n; i++) {
        int tx = (int)(next_random(&seed) % (TILES_X - 1)), ty = (int)(next_random(&seed) % TILES_Y);
        boxes[i] = box(tx, tx + (wide && i % wide == 0), ty, ty);
    }
}

SR_TEST(a_mesh_walk_is_not_scattered)
{
    /* Neighbouring primitives: each starts in the tile of the one before
     * or the next one over, now and then spanning two tiles. */
    static uint32_t boxes[PRIMS];
    uint64_t s = 7;
    int tx = 10, ty = 8;
    for (int i = 0; i < PRIMS; i++) {
        tx += (int)(next_random(&s) % 3) - 1;
        ty += (int)(next_random(&s) % 3) - 1;
        tx = tx < 0 ? 0 : tx > TILES_X - 2 ? TILES_X - 2 : tx;
        ty = ty < 0 ? 0 : ty > TILES_Y - 2 ? TILES_Y - 2 : ty;
        int wide = next_random(&s) % 4 == 0;
        boxes[i] = box(tx, tx + wide, ty, ty);
    }
    CHECK(!bin_and_check(boxes, PRIMS, false).scattered);
    /* Streamed out or not, a mesh's chunk keeps its refs. */
    CHECK(!bin_and_check(boxes, PRIMS, true).in_tile_order);
}

SR_TEST(random_small_primitives_are_scattered)
{
    static uint32_t boxes[PRIMS];
    random_boxes(boxes, PRIMS, 11, 0);
    bin_flags f = bin_and_check(boxes, PRIMS, false);
    CHECK(f.scattered);
    CHECK(!f.in_tile_order); /* on one thread the records are in cache */
}

/* A scattered chunk whose records went out to memory is copied in tile
 * order when its primitives lie mostly in one tile - at most a quarter
 * more copies than primitives - and keeps its refs otherwise. */
SR_TEST(scattered_streamed_chunks_are_copied_in_tile_order)
{
    static uint32_t boxes[PRIMS];
    random_boxes(boxes, PRIMS, 13, 0);
    CHECK(bin_and_check(boxes, PRIMS, true).in_tile_order);
    random_boxes(boxes, PRIMS, 17, 4); /* a quarter two tiles wide: 1.25 copies each */
    CHECK(bin_and_check(boxes, PRIMS, true).in_tile_order);
    random_boxes(boxes, PRIMS, 19, 3); /* a third */
    bin_flags f = bin_and_check(boxes, PRIMS, true);
    CHECK(f.scattered);
    CHECK(!f.in_tile_order);
}

/* A few primitives in one corner of the target (a small draw's) span
 * the tiles from their first to their last in row order, and no more;
 * none span nothing. */
SR_TEST(bins_span_the_tiles_the_primitives_reach)
{
    uint32_t boxes[3] = { box(7, 8, 3, 3), box(4, 5, 4, 5), box(9, 9, 2, 2) };
    sr_chunk c = { 0 };
    c.tile_box = boxes;
    c.tri_count = 3;
    c.bin_start = calloc(TILES_X * TILES_Y + 1, sizeof(uint32_t));
    REQUIRE(c.bin_start);
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_draw_state ds = { 0 };
    ds.tiles_x = TILES_X;
    ds.tiles_y = TILES_Y;
    CHECK(sr__bin_chunk(ctx, &ds, &c, RECORD, false));
    CHECK_EQ(c.bin_lo, 2 * TILES_X + 9);
    CHECK_EQ(c.bin_hi, 5 * TILES_X + 5 + 1);
    CHECK_EQ(c.bin_start[c.bin_hi] - c.bin_start[c.bin_lo], 2 + 4 + 1);
    c.tri_count = 0;
    CHECK(sr__bin_chunk(ctx, &ds, &c, RECORD, false));
    CHECK_EQ(c.bin_lo, c.bin_hi);
    sr__free(ctx, c.refs);
    free(c.bin_start);
    sr_destroy_context(ctx);
    /* The primitives in the span, placed where their boxes say. */
    bin_and_check(boxes, 3, false);
}

/* sr__stream_record writes exactly the record's bytes, whatever the
 * destination's alignment (16-byte streaming stores where it allows them,
 * memcpy elsewhere) and the record's size. */
SR_TEST(stream_record_copies_exactly_the_record)
{
    enum { MAX = 256, PAD = 64 };
    static _Alignas(64) uint8_t src[MAX], dst[PAD + MAX + PAD];
    for (int i = 0; i < MAX; i++) {
        src[i] = (uint8_t)(i * 7 + 1);
    }
    for (size_t size = 16; size <= MAX; size += 16) {
        for (size_t at = PAD - 16; at <= PAD + 16; at += 4) {
            memset(dst, 0xee, sizeof dst);
            sr__stream_record(dst + at, src, size);
            sr__stream_fence();
            CHECK(memcmp(dst + at, src, size) == 0);
            for (size_t k = 0; k < sizeof dst; k++) {
                if (k < at || k >= at + size) {
                    CHECK_EQ(dst[k], 0xee);
                }
            }
        }
    }
}

/* Two tiles far apart: primitive i goes to the other one than i - 1
 * (a far jump) unless i is a multiple of 4 other than `extra`. */
static void alternate(uint32_t *boxes, int n, int extra)
{
    int other = 0;
    for (int i = 0; i < n; i++) {
        if (i > 0 && (i % 4 != 0 || i == extra)) {
            other ^= 1;
        }
        boxes[i] = other ? box(25, 25, 14, 14) : box(2, 2, 2, 2);
    }
}

SR_TEST(scattered_means_more_than_three_quarters_far)
{
    /* 1,500 far jumps among 2,000 primitives: exactly three quarters. */
    static uint32_t boxes[PRIMS];
    alternate(boxes, PRIMS, -1);
    CHECK(!bin_and_check(boxes, PRIMS, false).scattered);
    /* One more. */
    alternate(boxes, PRIMS, 4);
    CHECK(bin_and_check(boxes, PRIMS, false).scattered);
}

/* The records a chunk stores: a filled triangle with four varyings in two
 * cache lines, FLAT's color after its varyings, and room for a line or a
 * point wherever a draw may make them. */
SR_TEST(record_sizes_follow_the_kinds_a_draw_makes)
{
    CHECK_EQ(sr__record_size(4, false, true), 128);
    CHECK_EQ(sr__record_size(4, true, true), 144);
    CHECK_EQ(sr__record_size(0, true, true), 96);
    for (int n = 0; n <= SR_MAX_VARYINGS; n++) {
        size_t tri = offsetof(sr_tri, vary) + sizeof(float) * (size_t)(3 * n);
        size_t line = offsetof(sr_line, vary) + sizeof(float) * (size_t)(2 * n);
        size_t point = offsetof(sr_point, vary) + sizeof(float) * (size_t)n;
        size_t only = sr__record_size(n, false, true), any = sr__record_size(n, false, false);
        CHECK(only >= tri && only < tri + 16 && only % 16 == 0);
        CHECK(any >= tri && any >= line && any >= point && any % 16 == 0);
        CHECK(sr__record_size(n, true, true) >= tri + 4 * sizeof(float));
    }
}
