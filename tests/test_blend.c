/* test_blend.c - blending with every GL factor and equation against the
 * formula, the color write mask, the scissor rectangle (triangles, lines,
 * points), and order-dependent blending that stays the same bytes for any
 * thread count. */
#include "raster_util.h"
#include "raster/fixed.h"

static const float SRC[4] = { 0.8f, 0.4f, 0.2f, 0.6f };
static const float DST[4] = { 0.2f, 0.5f, 0.9f, 0.3f };
static const float K[4] = { 0.25f, 0.5f, 0.75f, 0.4f };

static double factor(sr_blend_factor f, const double *s, const double *d, int ch)
{
    switch (f) {
    case SR_BLEND_ZERO: return 0;
    case SR_BLEND_ONE: return 1;
    case SR_BLEND_SRC_COLOR: return s[ch];
    case SR_BLEND_ONE_MINUS_SRC_COLOR: return 1 - s[ch];
    case SR_BLEND_SRC_ALPHA: return s[3];
    case SR_BLEND_ONE_MINUS_SRC_ALPHA: return 1 - s[3];
    case SR_BLEND_DST_ALPHA: return d[3];
    case SR_BLEND_ONE_MINUS_DST_ALPHA: return 1 - d[3];
    case SR_BLEND_DST_COLOR: return d[ch];
    case SR_BLEND_ONE_MINUS_DST_COLOR: return 1 - d[ch];
    case SR_BLEND_CONSTANT_COLOR: return K[ch];
    case SR_BLEND_ONE_MINUS_CONSTANT_COLOR: return 1 - K[ch];
    case SR_BLEND_CONSTANT_ALPHA: return K[3];
    case SR_BLEND_ONE_MINUS_CONSTANT_ALPHA: return 1 - K[3];
    case SR_BLEND_SRC_ALPHA_SATURATE: return ch == 3 ? 1 : (s[3] < 1 - d[3] ? s[3] : 1 - d[3]);
    default: return 1;
    }
}

/* Full-target quad of color SRC over a target cleared to DST. */
static void draw_over(rt_target *t, const sr_state *st)
{
    sr_clear(t->ctx, t->fb, &(sr_clear_desc){ .color = { DST[0], DST[1], DST[2], DST[3] } });
    float pos[12] = { -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0 };
    float col[16];
    for (int i = 0; i < 4; i++) {
        memcpy(&col[i * 4], SRC, sizeof SRC);
    }
    uint32_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    sr_state s = *st;
    s.shading = SR_SHADING_UNLIT;
    CHECK_EQ(sr_draw(t->ctx, t->fb, &s, &(sr_draw_desc){ .positions = pos, .colors = col,
                                                        .vertex_count = 4, .indices = idx,
                                                        .index_type = SR_INDEX_U32,
                                                        .index_count = 6 }), SR_OK);
}

SR_TEST(every_blend_factor_and_equation_follows_the_formula)
{
    rt_target t = rt_make(8, 8, 1);
    /* The source color enters blending as it is; the destination is what
     * the target holds, the clear color's bytes. */
    double s[4], d[4];
    for (int c = 0; c < 4; c++) {
        s[c] = SRC[c];
        d[c] = floor(DST[c] * 255 + 0.5) / 255;
    }
    long checked = 0;
    for (int f = SR_BLEND_ZERO; f <= SR_BLEND_SRC_ALPHA_SATURATE; f++) {
        for (int g = SR_BLEND_ZERO; g <= SR_BLEND_SRC_ALPHA_SATURATE; g++) {
            for (int op = SR_BLEND_ADD; op <= SR_BLEND_MAX; op++) {
                sr_state st = { .blend = { .enabled = true, .src_rgb = f, .src_alpha = f,
                                           .dst_rgb = g, .dst_alpha = g, .op_rgb = op,
                                           .op_alpha = op,
                                           .constant = { K[0], K[1], K[2], K[3] } } };
                draw_over(&t, &st);
                const uint8_t *px = sr_framebuffer_pixels(t.fb) + (3 * 8 + 3) * 4;
                for (int c = 0; c < 4; c++) {
                    double fs = factor(f, s, d, c), fd = factor(g, s, d, c), v;
                    switch (op) {
                    case SR_BLEND_SUBTRACT: v = s[c] * fs - d[c] * fd; break;
                    case SR_BLEND_REVERSE_SUBTRACT: v = d[c] * fd - s[c] * fs; break;
                    case SR_BLEND_MIN: v = s[c] < d[c] ? s[c] : d[c]; break;
                    case SR_BLEND_MAX: v = s[c] > d[c] ? s[c] : d[c]; break;
                    default: v = s[c] * fs + d[c] * fd; break;
                    }
                    v = v < 0 ? 0 : v > 1 ? 1 : v;
                    CHECK_NEAR(px[c], v * 255.0, 1.0);
                    checked++;
                }
            }
        }
    }
    CHECK_EQ(checked, 15 * 15 * 5 * 4);
    rt_free(&t);
}

SR_TEST(color_mask_keeps_masked_channels)
{
    rt_target t = rt_make(8, 8, 1);
    for (int m = 0; m < 16; m++) {
        /* m: the channels left untouched, bit c = channel c */
        sr_state st = { .color_mask = m == 15 ? SR_COLOR_MASK_NONE
                                              : (sr_color_mask)(SR_COLOR_MASK_RGBA & ~m) };
        draw_over(&t, &st);
        const uint8_t *px = sr_framebuffer_pixels(t.fb);
        for (int c = 0; c < 4; c++) {
            double want = (m >> c) & 1 ? DST[c] : SRC[c];
            CHECK_NEAR(px[c], want * 255.0, 0.51);
        }
    }
    rt_free(&t);
}

SR_TEST(scissor_bounds_every_primitive)
{
    rt_target t = rt_make(32, 32, 2);
    sr_state st = { .scissor = { .enabled = true, .x = 5, .y = 7, .width = 11, .height = 9 },
                    .point_size = 40, .line_width = 40 };
    const sr_primitive prims[] = { SR_PRIM_TRIANGLES, SR_PRIM_LINES, SR_PRIM_POINTS };
    for (int p = 0; p < 3; p++) {
        rt_clear(&t);
        float pos[9] = { -1, -1, 0, 3, -1, 0, -1, 3, 0 };
        if (prims[p] != SR_PRIM_TRIANGLES) {
            pos[0] = -1; pos[1] = 0; pos[3] = 1; pos[4] = 0; /* a line across / a point at (-1,0) */
            pos[6] = 0; pos[7] = 0;
        }
        sr_state s = st;
        s.shading = SR_SHADING_UNLIT;
        s.material = (sr_material){ .diffuse = { 1, 1, 1 } };
        REQUIRE(sr_draw(t.ctx, t.fb, &s, &(sr_draw_desc){ .primitive = prims[p], .positions = pos,
                                                         .vertex_count = 3 }) == SR_OK);
        uint8_t m[32 * 32];
        rt_mask(&t, m);
        int inside = 0;
        for (int y = 0; y < 32; y++) {
            for (int x = 0; x < 32; x++) {
                bool in = x >= 5 && x < 16 && y >= 7 && y < 16;
                if (!in) {
                    CHECK_EQ(m[y * 32 + x], 0);
                }
                inside += in && m[y * 32 + x];
            }
        }
        CHECK(inside > 0);
    }
    rt_free(&t);
}

/* Overlapping translucent triangles: the result depends on order, and the
 * tile bins keep submission order whatever the thread count. */
SR_TEST(blending_is_the_same_bytes_for_any_thread_count)
{
    enum { N = 300 };
    static double xy[N * 6];
    static float col[N * 12];
    sr_rng rng = { 0xb1e };
    for (int i = 0; i < N * 3; i++) {
        xy[i * 2] = sr_rng_range(&rng, -10, 2 * SR_TILE_SIZE + 10);
        xy[i * 2 + 1] = sr_rng_range(&rng, -10, 2 * SR_TILE_SIZE + 10);
        for (int c = 0; c < 4; c++) {
            col[i * 4 + c] = (float)sr_rng_unit(&rng);
        }
    }
    uint8_t *first = NULL;
    for (int threads = 1; threads <= 4; threads += 3) {
        rt_target t = rt_make(2 * SR_TILE_SIZE, 2 * SR_TILE_SIZE, threads); /* 2 x 2 tiles */
        rt_clear(&t);
        float *pos = malloc(sizeof(float) * 9 * N);
        for (int i = 0; i < N * 3; i++) {
            pos[i * 3] = rt_ndc_x(&t, xy[i * 2]);
            pos[i * 3 + 1] = rt_ndc_y(&t, xy[i * 2 + 1]);
            pos[i * 3 + 2] = 0;
        }
        sr_state st = { .shading = SR_SHADING_UNLIT,
                        .blend = { .enabled = true, .src_rgb = SR_BLEND_SRC_ALPHA,
                                   .dst_rgb = SR_BLEND_ONE_MINUS_SRC_ALPHA } };
        REQUIRE(sr_draw(t.ctx, t.fb, &st, &(sr_draw_desc){ .positions = pos, .colors = col,
                                                          .vertex_count = N * 3 }) == SR_OK);
        free(pos);
        const uint8_t *px = sr_framebuffer_pixels(t.fb);
        if (!first) {
            first = malloc(128 * 128 * 4);
            memcpy(first, px, 128 * 128 * 4);
        } else {
            CHECK(memcmp(first, px, 128 * 128 * 4) == 0);
        }
        rt_free(&t);
    }
    free(first);
}
