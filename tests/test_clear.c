/* test_clear.c - deferred clears.  A clear marks tiles; reading the
 * pixels writes the clear color into the tiles nobody drew and remembers
 * them as clean, so a later clear to the same color leaves them alone.
 * Whatever mix of clears, draws, 2D drawing, resolves and downsamples
 * comes in between, every read must give the pixels of a model image
 * built without clean tiles. */
#include "sr_test.h"
#include "softrast.h"
#include "target/framebuffer.h"
#include "raster/fixed.h"

#include <stdlib.h>
#include <string.h>

/* 3 x 3 tiles, the last column and row partial. */
enum { W = 2 * SR_TILE_SIZE + 22, H = 2 * SR_TILE_SIZE + 12 };

static int pending_color_tiles(const sr_framebuffer *fb)
{
    int n = 0;
    for (int t = 0; t < fb->tiles_x * fb->tiles_y; t++) {
        n += (fb->tile_pending[t] & SR_TILE_PENDING_COLOR) != 0;
    }
    return n;
}

/* One triangle given in window pixels, unlit in `rgb`, no depth test (it
 * covers what was there, as the 2D operations do). */
static sr_result draw_tri(sr_context *ctx, sr_framebuffer *fb, const float xy[6], const float rgb[3])
{
    int w = sr_framebuffer_width(fb), h = sr_framebuffer_height(fb);
    float pos[9];
    for (int i = 0; i < 3; i++) {
        pos[i * 3 + 0] = xy[i * 2] / (w * 0.5f) - 1.0f;
        pos[i * 3 + 1] = 1.0f - xy[i * 2 + 1] / (h * 0.5f);
        pos[i * 3 + 2] = 0.0f;
    }
    sr_state st = { .shading = SR_SHADING_UNLIT, .depth_test = SR_OFF,
                    .material = { .diffuse = { rgb[0], rgb[1], rgb[2] } } };
    return sr_draw(ctx, fb, &st, &(sr_draw_desc){ .positions = pos, .vertex_count = 3 });
}

/* The elision itself: after a read, clearing to the same color leaves
 * the undrawn tiles clean (nothing pending), a drawn tile pending, and a
 * different color makes every tile pending again. */
SR_TEST(clearing_to_the_same_color_leaves_clean_tiles_alone)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 2 }, &ctx) == SR_OK);
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &fb) ==
            SR_OK);
    const sr_clear_desc blue = { .color = { 0, 0, 1, 1 }, .depth = 1 };
    const sr_clear_desc red = { .color = { 1, 0, 0, 1 }, .depth = 1 };
    REQUIRE(sr_clear(ctx, fb, &blue) == SR_OK);
    CHECK_EQ(pending_color_tiles(fb), 9);
    sr_framebuffer_pixels(fb);
    CHECK_EQ(pending_color_tiles(fb), 0);
    REQUIRE(sr_clear(ctx, fb, &blue) == SR_OK);
    CHECK_EQ(pending_color_tiles(fb), 0);
    /* A triangle inside the first tile: only that tile needs clearing. */
    const float xy[6] = { 2, 2, 40, 5, 8, 50 }, green[3] = { 0, 1, 0 };
    REQUIRE(draw_tri(ctx, fb, xy, green) == SR_OK);
    REQUIRE(sr_clear(ctx, fb, &blue) == SR_OK);
    CHECK_EQ(pending_color_tiles(fb), 1);
    const uint8_t *px = sr_framebuffer_pixels(fb);
    int not_blue = 0;
    for (int p = 0; p < W * H; p++) {
        not_blue += px[p * 4] != 0 || px[p * 4 + 1] != 0 || px[p * 4 + 2] != 255;
    }
    CHECK_EQ(not_blue, 0);
    REQUIRE(sr_clear(ctx, fb, &red) == SR_OK);
    CHECK_EQ(pending_color_tiles(fb), 9);
    px = sr_framebuffer_pixels(fb);
    CHECK(px[0] == 255 && px[2] == 0 && px[(W * H - 1) * 4] == 255);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

/* The operations the random sequences are made of. */
typedef struct clear_world {
    sr_context *ctx;
    sr_framebuffer *ms;      /* a 4-sample source for sr_resolve */
    sr_framebuffer *big;     /* a 2x source for sr_downsample */
    sr_framebuffer *one;     /* a single-sample source for sr_resolve (a copy) */
} clear_world;

static const sr_clear_desc world_colors[2] = {
    { .color = { 0.2f, 0.4f, 0.6f, 1 }, .depth = 1 },
    { .color = { 1, 1, 0, 1 }, .depth = 1 },
};

/* A rectangle of pixels written with sr_write_pixels: corners from
 * arg[0..3] kept inside the framebuffer, a pattern from the position and
 * arg[6], rows `stride` bytes apart with a gap after each. */
static void write_rect(clear_world *w, sr_framebuffer *fb, const float *arg)
{
    int x0 = (int)arg[0], y0 = (int)arg[1], x1 = (int)arg[2], y1 = (int)arg[3];
    x0 = x0 < 0 ? 0 : x0 >= W ? W - 1 : x0;
    x1 = x1 < 0 ? 0 : x1 >= W ? W - 1 : x1;
    y0 = y0 < 0 ? 0 : y0 >= H ? H - 1 : y0;
    y1 = y1 < 0 ? 0 : y1 >= H ? H - 1 : y1;
    int x = x0 < x1 ? x0 : x1, y = y0 < y1 ? y0 : y1;
    int rw = abs(x1 - x0) + 1, rh = abs(y1 - y0) + 1;
    size_t stride = (size_t)rw * 4 + 12;
    uint8_t *px = malloc(stride * (size_t)rh);
    REQUIRE(px);
    for (int j = 0; j < rh; j++) {
        for (int i = 0; i < rw; i++) {
            uint8_t *p = px + (size_t)j * stride + (size_t)i * 4;
            p[0] = (uint8_t)(i * 7 + j);
            p[1] = (uint8_t)(j * 13);
            p[2] = (uint8_t)(arg[6] * 255.0f);
            p[3] = 255;
        }
    }
    CHECK(sr_write_pixels(w->ctx, fb, x, y, rw, rh, px, stride) == SR_OK);
    free(px);
}

/* Operation `op` (a clear to either color, a triangle, a 2D line, a
 * resolve of either source, a downsample into fb, or pixels written) with
 * its random arguments. */
static void apply(clear_world *w, sr_framebuffer *fb, int op, const float *arg)
{
    switch (op) {
    case 0:
    case 1:
        CHECK(sr_clear(w->ctx, fb, &world_colors[op]) == SR_OK);
        break;
    case 2:
        CHECK(draw_tri(w->ctx, fb, arg, arg + 6) == SR_OK);
        break;
    case 3:
        CHECK(sr_draw_line(w->ctx, fb, (sr_point2){ arg[0], arg[1] }, (sr_point2){ arg[2], arg[3] },
                           (sr_rgba){ 255, 0, 255, 255 }, NULL) == SR_OK);
        break;
    case 4:
        CHECK(sr_resolve(w->ctx, w->ms, fb) == SR_OK);
        break;
    case 5:
        CHECK(sr_downsample(w->ctx, w->big, fb, SR_RESAMPLE_BOX) == SR_OK);
        break;
    case 6:
        CHECK(sr_resolve(w->ctx, w->one, fb) == SR_OK);
        break;
    case 7:
        write_rect(w, fb, arg);
        break;
    default:
        break;
    }
}

/* What `op` does to the model image, found without any clean tile: the
 * operation on two fresh framebuffers cleared to two different colors
 * and read once; a pixel equal in both was written, with that value. */
static void apply_to_model(clear_world *w, uint32_t *model, int op, const float *arg)
{
    if (op <= 1) {
        uint8_t c[4];
        for (int k = 0; k < 4; k++) {
            c[k] = (uint8_t)(world_colors[op].color[k] * 255.0f + 0.5f);
        }
        uint32_t v;
        memcpy(&v, c, 4);
        for (int p = 0; p < W * H; p++) {
            model[p] = v;
        }
        return;
    }
    const uint32_t *img[2];
    sr_framebuffer *fresh[2] = { NULL, NULL };
    for (int i = 0; i < 2; i++) {
        REQUIRE(sr_make_framebuffer(w->ctx, &(sr_framebuffer_desc){ .width = W, .height = H },
                                    &fresh[i]) == SR_OK);
        CHECK(sr_clear(w->ctx, fresh[i], &(sr_clear_desc){ .color = { 0, 0, (float)i, 0 } }) ==
              SR_OK);
        apply(w, fresh[i], op, arg);
        img[i] = (const uint32_t *)sr_framebuffer_pixels(fresh[i]);
    }
    for (int p = 0; p < W * H; p++) {
        if (img[0][p] == img[1][p]) {
            model[p] = img[0][p];
        }
    }
    sr_destroy_framebuffer(w->ctx, fresh[0]);
    sr_destroy_framebuffer(w->ctx, fresh[1]);
}

/* Fixed seed: sequences of random operations (each drawn from `ops`) on a
 * framebuffer read after every one (so its tiles keep turning clean),
 * each read compared with a model image that never relies on a clean
 * tile. */
static void run_sequences(const int *ops, int nops, unsigned seed)
{
    clear_world w = { 0 };
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 2 }, &w.ctx) == SR_OK);
    REQUIRE(sr_make_framebuffer(w.ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                                               .samples = 4 }, &w.ms) == SR_OK);
    REQUIRE(sr_make_framebuffer(w.ctx, &(sr_framebuffer_desc){ .width = 2 * W, .height = 2 * H },
                                &w.big) == SR_OK);
    REQUIRE(sr_make_framebuffer(w.ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &w.one)
            == SR_OK);
    uint32_t *model = malloc(sizeof(uint32_t) * W * H);
    REQUIRE(model);
    srand(seed);
    for (int seq = 0; seq < 40 && !sr_test_failed_now(); seq++) {
        sr_framebuffer *fb = NULL;
        REQUIRE(sr_make_framebuffer(w.ctx, &(sr_framebuffer_desc){ .width = W, .height = H },
                                    &fb) == SR_OK);
        memset(model, 0, sizeof(uint32_t) * W * H); /* a new framebuffer is transparent black */
        /* The sources: cleared to one of the two colors, sometimes with a
         * triangle in one corner (so most of their tiles are clear). */
        const float corner[9] = { 3, 3, 60, 10, 10, 55, 1, 0, 0 };
        sr_clear(w.ctx, w.ms, &world_colors[0]);
        sr_clear(w.ctx, w.big, &world_colors[1]);
        sr_clear(w.ctx, w.one, &world_colors[seq / 2 % 2]);
        if (seq % 2) {
            CHECK(draw_tri(w.ctx, w.ms, corner, corner + 6) == SR_OK);
            CHECK(draw_tri(w.ctx, w.big, corner, corner + 6) == SR_OK);
            CHECK(draw_tri(w.ctx, w.one, corner, corner + 6) == SR_OK);
        }
        for (int step = 0; step < 16 && !sr_test_failed_now(); step++) {
            int op = ops[rand() % nops];
            float arg[9];
            for (int i = 0; i < 6; i++) {
                arg[i] = (float)(rand() % (i % 2 ? H + 40 : W + 40)) - 20.0f;
            }
            for (int i = 6; i < 9; i++) {
                arg[i] = (float)(rand() % 256) / 255.0f;
            }
            apply(&w, fb, op, arg);
            apply_to_model(&w, model, op, arg);
            const uint32_t *px = (const uint32_t *)sr_framebuffer_pixels(fb);
            int differ = 0;
            for (int p = 0; p < W * H; p++) {
                differ += px[p] != model[p];
            }
            if (differ) {
                sr_test_fail(__FILE__, __LINE__, "sequence %d step %d (operation %d): %d pixels "
                             "differ from the model", seq, step, op, differ);
            }
        }
        sr_destroy_framebuffer(w.ctx, fb);
    }
    free(model);
    sr_destroy_framebuffer(w.ctx, w.ms);
    sr_destroy_framebuffer(w.ctx, w.big);
    sr_destroy_framebuffer(w.ctx, w.one);
    sr_destroy_context(w.ctx);
}

/* Clears twice as often as each other operation, so that a clear to the
 * color a tile already holds often follows something drawn on it. */
SR_TEST(pixels_follow_every_operation_after_reads)
{
    static const int ops[9] = { 0, 1, 0, 1, 2, 3, 4, 5, 6 };
    run_sequences(ops, 9, 7);
}

/* sr_write_pixels among them: the tiles it writes must not be taken for
 * clean or for holding their base color outside what was drawn, and a
 * clear pending there must still reach the rest of the tile. */
SR_TEST(written_pixels_follow_every_operation_after_reads)
{
    static const int ops[11] = { 0, 1, 0, 1, 2, 3, 4, 5, 6, 7, 7 };
    run_sequences(ops, 11, 17);
}

/* sr_write_pixels gives back exactly what it was given, inside its
 * rectangle only (the rest keeps a clear still pending when it was
 * called), from rows with a gap between them, and on 1 and 4 samples;
 * a clear after it, to the color the tiles held, clears it. */
SR_TEST(written_pixels_read_back_exactly)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 2 }, &ctx) == SR_OK);
    enum { RX = SR_TILE_SIZE - 5, RY = 3, RW = 17, RH = SR_TILE_SIZE + 2, GAP = 20 };
    static uint8_t in[RH][RW * 4 + GAP], out[W * H * 4];
    for (int y = 0; y < RH; y++) {
        for (int x = 0; x < RW * 4; x++) {
            in[y][x] = (uint8_t)(x * 31 + y * 7 + 1);
        }
    }
    const sr_clear_desc teal = { .color = { 0, 0.5f, 0.5f, 1 }, .depth = 1 };
    for (int samples = 1; samples <= 4; samples += 3) {
        sr_framebuffer *fb = NULL;
        REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                                                 .samples = samples }, &fb) ==
                SR_OK);
        REQUIRE(sr_clear(ctx, fb, &teal) == SR_OK);
        const uint8_t want_bg[4] = { 0, 128, 128, 255 };
        for (int pass = 0; pass < 2; pass++) {
            /* Pass 1 writes over tiles a read has left clean. */
            REQUIRE(sr_write_pixels(ctx, fb, RX, RY, RW, RH, &in[0][0], sizeof in[0]) == SR_OK);
            REQUIRE(sr_read_pixels(ctx, fb, 0, 0, W, H, out, (size_t)W * 4) == SR_OK);
            int wrong = 0;
            for (int y = 0; y < H; y++) {
                for (int x = 0; x < W; x++) {
                    bool inside = x >= RX && x < RX + RW && y >= RY && y < RY + RH;
                    const uint8_t *want = inside ? &in[y - RY][(x - RX) * 4] : want_bg;
                    wrong += memcmp(&out[((size_t)y * W + x) * 4], want, 4) != 0;
                }
            }
            CHECK_EQ(wrong, 0);
        }
        REQUIRE(sr_clear(ctx, fb, &teal) == SR_OK);
        REQUIRE(sr_read_pixels(ctx, fb, 0, 0, W, H, out, (size_t)W * 4) == SR_OK);
        int not_teal = 0;
        for (int p = 0; p < W * H; p++) {
            not_teal += memcmp(&out[(size_t)p * 4], want_bg, 4) != 0;
        }
        CHECK_EQ(not_teal, 0);
        sr_destroy_framebuffer(ctx, fb);
    }
    sr_destroy_context(ctx);
}

/* ---- clears of the drawn rectangle only --------------------------------- */

/* The framebuffers of the drawn-rectangle test: `fb` clears as the library
 * does; `ref` forgets every tile's base before each operation, so each of
 * its clears writes whole tiles, as every clear did before. */
static void forget_bases(sr_framebuffer *fb)
{
    for (int t = 0; t < fb->tiles_x * fb->tiles_y; t++) {
        fb->tile_pending[t] &= (uint8_t)~SR_TILE_BASE_ALL;
    }
}

/* A small triangle around (x, y) at depth z, depth-tested (LESS) and
 * written, the stencil replaced by `ref` where it passes. */
static sr_result draw_small(sr_context *ctx, sr_framebuffer *fb, float x, float y, float z,
                            const float rgb[3], uint8_t ref)
{
    int w = sr_framebuffer_width(fb), h = sr_framebuffer_height(fb);
    const float xy[6] = { x, y, x + 9, y + 2, x + 3, y + 7 };
    float pos[9];
    for (int i = 0; i < 3; i++) {
        pos[i * 3 + 0] = xy[i * 2] / (w * 0.5f) - 1.0f;
        pos[i * 3 + 1] = 1.0f - xy[i * 2 + 1] / (h * 0.5f);
        pos[i * 3 + 2] = z;
    }
    sr_state st = { .shading = SR_SHADING_UNLIT, .cull = SR_CULL_NONE,
                    .material = { .diffuse = { rgb[0], rgb[1], rgb[2] } } };
    if (sr_framebuffer_has_stencil(fb)) {
        st.stencil = (sr_stencil){ .enabled = true,
                                   .front = { .ref = ref, .pass = SR_STENCIL_REPLACE } };
    }
    return sr_draw(ctx, fb, &st, &(sr_draw_desc){ .positions = pos, .vertex_count = 3 });
}

/* Fixed seed: small depth-tested triangles with clears in between - the
 * same values again (only the drawn rectangles are written), other
 * values (whole tiles), one component at a time - and a 2D line now and
 * then, on 1 and 4 samples with a stencil buffer; after every step the
 * color, depth and stencil read the same as from `ref`. */
SR_TEST(clears_of_the_drawn_rectangle_give_whole_clears_bytes)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 2 }, &ctx) == SR_OK);
    uint8_t *pa = malloc((size_t)W * H * 4), *pb = malloc((size_t)W * H * 4);
    float *da = malloc(sizeof(float) * W * H), *db = malloc(sizeof(float) * W * H);
    REQUIRE(pa && pb && da && db);
    const sr_clear_desc clears[5] = {
        { .color = { 0.2f, 0.4f, 0.6f, 1 }, .depth = 1, .stencil = 0 },
        { .color = { 0.2f, 0.4f, 0.6f, 1 }, .depth = 1, .stencil = 0 },
        { .color = { 1, 1, 0, 1 }, .depth_action = SR_ACTION_CLEAR, .depth = 0.75f,
          .stencil_action = SR_ACTION_CLEAR, .stencil = 9 },
        { .color = { 0.2f, 0.4f, 0.6f, 1 }, .depth_action = SR_ACTION_KEEP,
          .stencil_action = SR_ACTION_KEEP },
        { .depth = 1, .color_action = SR_ACTION_KEEP, .stencil = 0 },
    };
    srand(11);
    for (int samples = 1; samples <= 4; samples += 3) {
        sr_framebuffer *fb = NULL, *ref = NULL;
        sr_framebuffer_desc desc = { .width = W, .height = H, .samples = samples,
                                     .stencil = true };
        REQUIRE(sr_make_framebuffer(ctx, &desc, &fb) == SR_OK);
        REQUIRE(sr_make_framebuffer(ctx, &desc, &ref) == SR_OK);
        for (int step = 0; step < 400 && !sr_test_failed_now(); step++) {
            int op = rand() % 10;
            float x = (float)(rand() % (W - 8)), y = (float)(rand() % (H - 8));
            float z = (float)(rand() % 200) / 100.0f - 1.0f;
            const float rgb[3] = { (float)(rand() % 256) / 255.0f, 0.5f, 0.25f };
            uint8_t sref = (uint8_t)(1 + rand() % 200);
            sr_framebuffer *both[2] = { fb, ref };
            for (int i = 0; i < 2; i++) {
                if (i == 1) {
                    forget_bases(ref);
                }
                if (op < 5) {
                    CHECK(sr_clear(ctx, both[i], &clears[op]) == SR_OK);
                } else if (op < 9 || samples > 1) {
                    CHECK(draw_small(ctx, both[i], x, y, z, rgb, sref) == SR_OK);
                } else {
                    CHECK(sr_draw_line(ctx, both[i], (sr_point2){ x, y },
                                       (sr_point2){ x + 30, y + 5 }, (sr_rgba){ 255, 0, 255, 255 },
                                       NULL) == SR_OK);
                }
            }
            /* Reading only now and then lets pending clears pile up. */
            if (rand() % 3) {
                continue;
            }
            REQUIRE(sr_read_pixels(ctx, fb, 0, 0, W, H, pa, (size_t)W * 4) == SR_OK);
            REQUIRE(sr_read_pixels(ctx, ref, 0, 0, W, H, pb, (size_t)W * 4) == SR_OK);
            CHECK(memcmp(pa, pb, (size_t)W * H * 4) == 0);
            REQUIRE(sr_read_depth(ctx, fb, 0, 0, W, H, da, W) == SR_OK);
            REQUIRE(sr_read_depth(ctx, ref, 0, 0, W, H, db, W) == SR_OK);
            CHECK(memcmp(da, db, sizeof(float) * W * H) == 0);
            REQUIRE(sr_read_stencil(ctx, fb, 0, 0, W, H, pa, W) == SR_OK);
            REQUIRE(sr_read_stencil(ctx, ref, 0, 0, W, H, pb, W) == SR_OK);
            CHECK(memcmp(pa, pb, (size_t)W * H) == 0);
            if (sr_test_failed_now()) {
                sr_test_fail(__FILE__, __LINE__, "%d samples, step %d (operation %d)", samples,
                             step, op);
            }
        }
        sr_destroy_framebuffer(ctx, fb);
        sr_destroy_framebuffer(ctx, ref);
    }
    free(pa);
    free(pb);
    free(da);
    free(db);
    sr_destroy_context(ctx);
}

/* What the memo saves: after a small triangle, a clear to the same values
 * writes its box, not the tile - seen as a pixel outside the box that is
 * left alone (overwritten behind the library's back, it keeps that
 * value), while one inside is cleared. */
SR_TEST(a_clear_to_the_same_values_writes_only_the_drawn_rectangle)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &fb) ==
            SR_OK);
    const sr_clear_desc grey = { .color = { 0.5f, 0.5f, 0.5f, 1 }, .depth = 1 };
    const float rgb[3] = { 1, 0, 0 };
    REQUIRE(sr_clear(ctx, fb, &grey) == SR_OK);
    REQUIRE(draw_small(ctx, fb, 20, 20, 0, rgb, 0) == SR_OK);
    const uint32_t *px = (const uint32_t *)sr_framebuffer_pixels(fb);
    uint32_t clear = px[0];
    REQUIRE(px[22 * W + 23] != clear);            /* inside the triangle */
    const sr_tile_memo *m = &fb->tile_memo[0];
    CHECK(m->x0 <= 20 && m->y0 <= 20 && m->x1 >= 29 && m->y1 >= 27 && m->x1 <= 40 &&
          m->y1 <= 40);
    fb->color[100 * W + 100] = 0x12345678u;     /* outside the box, same tile */
    fb->color[22 * W + 23] = 0x12345678u;       /* inside it */
    REQUIRE(sr_clear(ctx, fb, &grey) == SR_OK);
    REQUIRE(draw_small(ctx, fb, 60, 60, 0, rgb, 0) == SR_OK);
    px = (const uint32_t *)sr_framebuffer_pixels(fb);
    CHECK_EQ(px[100 * W + 100], 0x12345678u);
    CHECK_EQ(px[22 * W + 23], clear);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}
