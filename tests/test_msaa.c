/* test_msaa.c - multisampling: the standard sample positions, per-sample
 * coverage against an independent int64 reference of the top-left rule at
 * each sample, watertight meshes per sample, the box resolve, lines and
 * points per sample, alpha to coverage, and that the per-sample path with
 * one sample gives the fast path's bytes. */
#include "raster_util.h"
#include "target/framebuffer.h"
#include "raster/fixed.h"

#include <stdlib.h>
#include <string.h>

/* docs/raster-rules.md §9.1, Vulkan's standardSampleLocations in sixteenths of a
 * pixel from the upper-left corner, written out from the spec table. */
static const int vk2[2][2] = { { 12, 12 }, { 4, 4 } };
static const int vk4[4][2] = { { 6, 2 }, { 14, 6 }, { 2, 10 }, { 10, 14 } };
static const int vk8[8][2] = { { 9, 5 }, { 7, 11 }, { 13, 9 }, { 5, 3 },
                               { 3, 13 }, { 1, 7 }, { 11, 15 }, { 15, 1 } };
static const int vk16[16][2] = { { 9, 9 }, { 7, 5 }, { 5, 10 }, { 12, 7 }, { 3, 6 }, { 10, 13 },
                                 { 13, 11 }, { 11, 3 }, { 6, 14 }, { 8, 1 }, { 4, 2 }, { 2, 12 },
                                 { 0, 8 }, { 15, 4 }, { 14, 15 }, { 1, 0 } };

static const int (*vk_table(int n))[2]
{
    return n == 2 ? vk2 : n == 4 ? vk4 : n == 8 ? vk8 : vk16;
}

SR_TEST(sample_positions_are_the_standard_ones)
{
    static const int counts[] = { 2, 4, 8, 16 };
    for (int c = 0; c < 4; c++) {
        int n = counts[c];
        for (int s = 0; s < n; s++) {
            float x = -1, y = -1;
            CHECK_EQ(sr_sample_position(n, s, &x, &y), SR_OK);
            CHECK_NEAR(x, vk_table(n)[s][0] / 16.0, 0);
            CHECK_NEAR(y, vk_table(n)[s][1] / 16.0, 0);
        }
        CHECK_EQ(sr_sample_position(n, n, &(float){ 0 }, &(float){ 0 }), SR_INVALID_ARG);
    }
    float x, y;
    CHECK_EQ(sr_sample_position(1, 0, &x, &y), SR_OK);
    CHECK(x == 0.5f && y == 0.5f);
    CHECK_EQ(sr_sample_position(3, 0, &x, &y), SR_INVALID_ARG);
}

SR_TEST(framebuffer_rejects_bad_sample_counts)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(NULL, &ctx) == SR_OK);
    sr_framebuffer *fb = (sr_framebuffer *)1;
    CHECK_EQ(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 8, .height = 8,
                                                             .samples = 3 }, &fb), SR_INVALID_ARG);
    CHECK(fb == NULL);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "samples");
    CHECK_EQ(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 8, .height = 8,
                                                             .samples = 32 }, &fb), SR_INVALID_ARG);
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 8, .height = 8,
                                                            .samples = 4 }, &fb) == SR_OK);
    CHECK_EQ(sr_framebuffer_samples(fb), 4);
    /* 2D drawing and SSAA's downsample want single-sampled images. */
    CHECK_EQ(sr_draw_text(ctx, fb, 0, 0, 1, "x", (sr_rgba){ 1, 1, 1, 1 }), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "multisampled");
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

/* Per-sample coverage of one triangle by the top-left rule, at the
 * table's positions: out[pixel * n + s]. */
static void ref_cover_samples(const double *xy, int w, int h, int n, uint8_t *out)
{
    int64_t x[3], y[3];
    for (int i = 0; i < 3; i++) {
        x[i] = ref_snap(xy[i * 2]);
        y[i] = ref_snap(xy[i * 2 + 1]);
    }
    memset(out, 0, (size_t)w * h * n);
    int64_t area2 = ref_edge(x[0], y[0], x[1], y[1], x[2], y[2]);
    if (area2 == 0) {
        return;
    }
    if (area2 < 0) {
        int64_t tx = x[1], ty = y[1];
        x[1] = x[2], y[1] = y[2];
        x[2] = tx, y[2] = ty;
    }
    const int (*pos)[2] = vk_table(n);
    for (int py = 0; py < h; py++) {
        for (int px = 0; px < w; px++) {
            for (int s = 0; s < n; s++) {
                int64_t sx = px * 256 + pos[s][0] * 16, sy = py * 256 + pos[s][1] * 16;
                bool in = true;
                for (int i = 0; i < 3; i++) {
                    int a = i, b = (i + 1) % 3;
                    int64_t dx = x[b] - x[a], dy = y[b] - y[a];
                    bool tl = dy < 0 || (dy == 0 && dx > 0);
                    in &= ref_edge(x[a], y[a], x[b], y[b], sx, sy) + (tl ? 1 : 0) > 0;
                }
                out[((size_t)py * w + px) * n + s] = in;
            }
        }
    }
}

static sr_framebuffer *make_ms(sr_context *ctx, int w, int h, int n, sr_depth_format depth)
{
    sr_framebuffer *fb = NULL;
    sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = w, .height = h, .samples = n,
                                                    .depth_format = depth, .stencil = true }, &fb);
    return fb;
}

static sr_result draw_window_tris(sr_context *ctx, sr_framebuffer *fb, const double *xy, int ntri,
                                  const sr_state *st)
{
    int w = sr_framebuffer_width(fb), h = sr_framebuffer_height(fb);
    float *pos = malloc(sizeof(float) * 9 * (size_t)ntri);
    for (int i = 0; i < ntri * 3; i++) {
        pos[i * 3 + 0] = (float)(xy[i * 2] / (w * 0.5) - 1.0);
        pos[i * 3 + 1] = (float)(1.0 - xy[i * 2 + 1] / (h * 0.5));
        pos[i * 3 + 2] = 0.0f;
    }
    sr_result r = sr_draw(ctx, fb, st, &(sr_draw_desc){ .positions = pos,
                                                        .vertex_count = (size_t)ntri * 3 });
    free(pos);
    return r;
}

/* Random triangles on the 1/256 grid, snapped exactly; every sample of
 * every pixel is compared with the reference, for 2, 4, 8 and 16
 * samples and each rasterizer choice. */
SR_TEST(per_sample_coverage_matches_the_reference)
{
    enum { W = 32, H = 32 };
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    static const int counts[] = { 2, 4, 8, 16 };
    sr_rng rng = { 0x5eed05a1u };
    uint8_t *ref = malloc(W * H * 16);
    int mismatches = 0, covered = 0;
    for (int c = 0; c < 4; c++) {
        int n = counts[c];
        sr_framebuffer *fb = make_ms(ctx, W, H, n, SR_DEPTH_NONE);
        REQUIRE(fb);
        for (int iter = 0; iter < 300; iter++) {
            double xy[6];
            for (int k = 0; k < 6; k++) {
                /* Small and large, often with vertices on sample rows. */
                double v = sr_rng_range(&rng, -4, W + 4);
                xy[k] = (iter & 1) ? floor(v * 16) / 16 : floor(v * 256) / 256;
            }
            sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
            sr_state st = { .shading = SR_SHADING_UNLIT, .material = { .diffuse = { 1, 1, 1 } },
                            .rasterizer = (sr_rasterizer)(1 + iter % 3) };
            REQUIRE(draw_window_tris(ctx, fb, xy, 1, &st) == SR_OK);
            sr__fb_resolve(fb, SR_TILE_PENDING_COLOR);  /* the pending clear, into the samples */
            ref_cover_samples(xy, W, H, n, ref);
            for (int i = 0; i < W * H * n; i++) {
                bool got = (fb->color[i] & 0xff) != 0;
                mismatches += got != (ref[i] != 0);
                covered += ref[i];
            }
        }
        sr_destroy_framebuffer(ctx, fb);
    }
    CHECK_EQ(mismatches, 0);
    CHECK(covered > 100000);
    free(ref);
    sr_destroy_context(ctx);
}

/* A fan and a grid of triangles sharing edges, added up per sample with
 * ONE + ONE blending: every sample inside is counted exactly once. */
SR_TEST(shared_edges_cover_each_sample_once)
{
    enum { W = 64, H = 64, N = 4 };
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 2 }, &ctx) == SR_OK);
    sr_framebuffer *fb = make_ms(ctx, W, H, N, SR_DEPTH_NONE);
    REQUIRE(fb);
    sr_rng rng = { 77 };
    for (int iter = 0; iter < 20; iter++) {
        /* A fan around a random centre covering a random convex polygon. */
        enum { K = 24 };
        double cx = sr_rng_range(&rng, 20, 44), cy = sr_rng_range(&rng, 20, 44);
        double xy[K * 6];
        double r0 = sr_rng_range(&rng, 8, 18), phase = sr_rng_range(&rng, 0, 1);
        for (int k = 0; k < K; k++) {
            double a0 = (k + phase) * 2 * M_PI / K, a1 = (k + 1 + phase) * 2 * M_PI / K;
            double p[6] = { cx, cy, cx + r0 * cos(a0), cy + r0 * sin(a0), cx + r0 * cos(a1),
                            cy + r0 * sin(a1) };
            for (int j = 0; j < 6; j++) {
                xy[k * 6 + j] = floor(p[j] * 256) / 256;
            }
        }
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
        sr_state st = { .shading = SR_SHADING_UNLIT,
                        .material = { .diffuse = { 1 / 255.0f, 1 / 255.0f, 1 / 255.0f } },
                        .blend = { .enabled = true, .src_rgb = SR_BLEND_ONE,
                                   .dst_rgb = SR_BLEND_ONE } };
        REQUIRE(draw_window_tris(ctx, fb, xy, K, &st) == SR_OK);
        sr__fb_resolve(fb, SR_TILE_PENDING_COLOR);  /* the pending clear, into the samples */
        int twice = 0, once = 0;
        for (int i = 0; i < W * H * N; i++) {
            int v = (int)(fb->color[i] & 0xff);
            twice += v > 1;
            once += v == 1;
        }
        CHECK_EQ(twice, 0);
        /* The polygon's area in samples, roughly: nothing went missing. */
        double area = 0.5 * K * r0 * r0 * sin(2 * M_PI / K) * N;
        CHECK_NEAR(once, area, area * 0.05 + 40);
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(resolve_is_the_rounded_box_average)
{
    enum { W = 37, H = 3 };
    sr_context *ctx;
    REQUIRE(sr_make_context(NULL, &ctx) == SR_OK);
    static const int counts[] = { 2, 4, 8, 16 };
    for (int c = 0; c < 4; c++) {
        int n = counts[c];
        sr_framebuffer *fb = make_ms(ctx, W, H, n, SR_DEPTH_NONE), *out = NULL;
        REQUIRE(fb);
        REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H },
                                    &out) == SR_OK);
        sr__fb_resolve(fb, SR_TILE_PENDING_COLOR);  /* the pending clear, into the samples */
        sr_rng rng = { 3 + (uint64_t)n };
        for (int i = 0; i < W * H * n; i++) {
            fb->color[i] = (uint32_t)sr_rng_next(&rng);
        }
        /* Pixels whose samples agree, and all-255 extremes. */
        for (int p = 0; p < W * H; p += 3) {
            for (int s = 1; s < n; s++) {
                fb->color[p * n + s] = p % 2 ? 0xffffffffu : fb->color[p * n];
            }
        }
        REQUIRE(sr_resolve(ctx, fb, out) == SR_OK);
        const uint8_t *a = sr_framebuffer_pixels(out), *b = sr_framebuffer_pixels(fb);
        for (int p = 0; p < W * H; p++) {
            for (int ch = 0; ch < 4; ch++) {
                unsigned sum = 0;
                for (int s = 0; s < n; s++) {
                    sum += (fb->color[p * n + s] >> (8 * ch)) & 0xff;
                }
                unsigned want = (sum + (unsigned)n / 2) / (unsigned)n;
                CHECK_EQ(a[p * 4 + ch], want);
                CHECK_EQ(b[p * 4 + ch], want);
            }
        }
        /* Wrong size or a multisampled destination are refused. */
        CHECK_EQ(sr_resolve(ctx, out, fb), SR_INVALID_ARG);
        sr_destroy_framebuffer(ctx, out);
        sr_destroy_framebuffer(ctx, fb);
    }
    sr_destroy_context(ctx);
}

/* Tiles nobody drew since the source's clear resolve to its clear color,
 * whatever the destination held or had pending, and the destination stays
 * a framebuffer like any other: read out, drawn on, resolved into again. */
SR_TEST(resolve_of_undrawn_tiles_is_the_sources_clear_color)
{
    /* 3 x 2 tiles, the last ones partial. */
    enum { W = 2 * SR_TILE_SIZE + 22, H = SR_TILE_SIZE + 6 };
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 2 }, &ctx) == SR_OK);
    sr_framebuffer *ms = make_ms(ctx, W, H, 4, SR_DEPTH_NONE), *out = NULL;
    REQUIRE(ms);
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &out) ==
            SR_OK);
    /* The destination: cleared to one color and drawn on all over, then
     * cleared to another and left pending. */
    const double full[] = { -10, -10, 400, -10, -10, 400 };
    sr_state st = { .shading = SR_SHADING_UNLIT };
    REQUIRE(sr_clear(ctx, out, &(sr_clear_desc){ .color = { 0, 0, 1, 1 } }) == SR_OK);
    REQUIRE(draw_window_tris(ctx, out, full, 1, &st) == SR_OK);
    REQUIRE(sr_clear(ctx, out, &(sr_clear_desc){ .color = { 0, 1, 0, 1 } }) == SR_OK);
    /* The source: cleared red, one small triangle in the first tile only. */
    const double small[] = { 2, 2, 30, 4, 6, 40 };
    REQUIRE(sr_clear(ctx, ms, &(sr_clear_desc){ .color = { 1, 0, 0, 1 } }) == SR_OK);
    REQUIRE(draw_window_tris(ctx, ms, small, 1, &st) == SR_OK);
    for (int round = 0; round < 2; round++) {
        REQUIRE(sr_resolve(ctx, ms, out) == SR_OK);
        const uint8_t *a = sr_framebuffer_pixels(out), *b = sr_framebuffer_pixels(ms);
        int wrong = 0, red = 0;
        for (int p = 0; p < W * H; p++) {
            wrong += memcmp(&a[p * 4], &b[p * 4], 4) != 0;
            red += a[p * 4] == 255 && a[p * 4 + 1] == 0 && a[p * 4 + 2] == 0 && a[p * 4 + 3] == 255;
        }
        CHECK_EQ(wrong, 0);
        CHECK(red > W * H - 64 * 64); /* every tile but the first is all clear color */
        /* Drawing on the destination over the cleared tiles starts from
         * the resolved clear color. */
        REQUIRE(draw_window_tris(ctx, out, small, 1, &st) == SR_OK);
        a = sr_framebuffer_pixels(out);
        CHECK(a[(H - 1) * W * 4 + (W - 1) * 4] == 255 && a[(H - 1) * W * 4 + (W - 1) * 4 + 1] == 0);
    }
    sr_destroy_framebuffer(ctx, out);
    sr_destroy_framebuffer(ctx, ms);
    sr_destroy_context(ctx);
}

/* Depth per sample: two triangles crossing inside a pixel split its
 * samples by their own depths, not the centre's. */
SR_TEST(depth_is_tested_per_sample)
{
    enum { W = 16, H = 16, N = 16 };
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb = make_ms(ctx, W, H, N, SR_DEPTH_D32F);
    REQUIRE(fb);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 }, .depth = 1 });
    /* Two full-screen quads whose depth planes cross at x = 8 exactly:
     * red rises left to right, green falls. */
    float pos[2][18];
    for (int q = 0; q < 2; q++) {
        float zl = q ? 0.5f : -0.5f, zr = -zl;
        float v[6][3] = { { -1, -1, zl }, { 1, -1, zr }, { 1, 1, zr },
                          { -1, -1, zl }, { 1, 1, zr }, { -1, 1, zl } };
        memcpy(pos[q], v, sizeof v);
        sr_state st = { .shading = SR_SHADING_UNLIT,
                        .material = { .diffuse = { q ? 0.0f : 1.0f, q ? 1.0f : 0.0f, 0 } } };
        REQUIRE(sr_draw(ctx, fb, &st, &(sr_draw_desc){ .positions = pos[q], .vertex_count = 6 })
                == SR_OK);
    }
    sr__fb_resolve(fb, SR_TILE_PENDING_COLOR);  /* the pending clear, into the samples */
    /* In pixel column 7 (x in [7, 8)) every sample is left of the
     * crossing: red is nearer.  In column 8, green. */
    for (int y = 0; y < H; y++) {
        for (int s = 0; s < N; s++) {
            uint32_t l = fb->color[((size_t)y * W + 7) * N + s], r = fb->color[((size_t)y * W + 8) * N + s];
            CHECK_EQ(l & 0xffff, 0x00ff);
            /* A sample exactly on x = 8 ties, and LESS keeps the red. */
            CHECK_EQ(r & 0xffff, vk16[s][0] == 0 ? 0x00ff : 0xff00);
        }
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

/* The per-sample path with one sample (here: the stencil test, always
 * passing) gives the same bytes as the fast path, shading and depth
 * included. */
SR_TEST(per_sample_path_with_one_sample_equals_the_fast_path)
{
    enum { W = 96, H = 80, T = 400 };
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 2 }, &ctx) == SR_OK);
    sr_framebuffer *a = make_ms(ctx, W, H, 1, SR_DEPTH_D24), *b = make_ms(ctx, W, H, 1, SR_DEPTH_D24);
    REQUIRE(a && b);
    sr_rng rng = { 99 };
    float *pos = malloc(sizeof(float) * 9 * T), *col = malloc(sizeof(float) * 12 * T);
    for (int i = 0; i < 3 * T; i++) {
        pos[i * 3 + 0] = (float)sr_rng_range(&rng, -1.2, 1.2);
        pos[i * 3 + 1] = (float)sr_rng_range(&rng, -1.2, 1.2);
        pos[i * 3 + 2] = (float)sr_rng_range(&rng, -1, 1);
        for (int k = 0; k < 4; k++) {
            col[i * 4 + k] = (float)sr_rng_unit(&rng);
        }
    }
    sr_draw_desc d = { .positions = pos, .vertex_count = 3 * T, .colors = col };
    sr_clear_desc cl = { .color = { 0.1f, 0.2f, 0.3f, 1 }, .depth = 1 };
    sr_clear(ctx, a, &cl);
    sr_clear(ctx, b, &cl);
    sr_state st = { .shading = SR_SHADING_UNLIT };
    REQUIRE(sr_draw(ctx, a, &st, &d) == SR_OK);
    st.stencil.enabled = true;
    REQUIRE(sr_draw(ctx, b, &st, &d) == SR_OK);
    CHECK(memcmp(sr_framebuffer_pixels(a), sr_framebuffer_pixels(b), (size_t)W * H * 4) == 0);
    float *da = malloc(sizeof(float) * W * H), *db = malloc(sizeof(float) * W * H);
    sr_read_depth(ctx, a, 0, 0, W, H, da, W);
    sr_read_depth(ctx, b, 0, 0, W, H, db, W);
    CHECK(memcmp(da, db, sizeof(float) * W * H) == 0);
    free(da);
    free(db);
    free(pos);
    free(col);
    sr_destroy_framebuffer(ctx, a);
    sr_destroy_framebuffer(ctx, b);
    sr_destroy_context(ctx);
}

/* Lines become rectangles of their width, points squares (or discs),
 * covered per sample by the same rule. */
SR_TEST(lines_and_points_are_covered_per_sample)
{
    enum { W = 32, H = 32, N = 4 };
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb = make_ms(ctx, W, H, N, SR_DEPTH_NONE);
    REQUIRE(fb);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
    /* A horizontal line along y = 10.5 from x = 2 to x = 20, width 1: the
     * rectangle [2, 20] x [10, 11] covers every sample of row 10 in pixels
     * 2..19 and nothing else. */
    float line[6] = { 2.0f / 16 - 1, 1 - 10.5f / 16, 0, 20.0f / 16 - 1, 1 - 10.5f / 16, 0 };
    sr_state st = { .shading = SR_SHADING_UNLIT, .material = { .diffuse = { 1, 1, 1 } } };
    REQUIRE(sr_draw(ctx, fb, &st, &(sr_draw_desc){ .primitive = SR_PRIM_LINES,
                                                   .positions = line, .vertex_count = 2 }) == SR_OK);
    /* A point of size 2 at (26, 26): the square [25, 27)^2. */
    float pt[3] = { 26.0f / 16 - 1, 1 - 26.0f / 16, 0 };
    st.point_size = 2;
    REQUIRE(sr_draw(ctx, fb, &st, &(sr_draw_desc){ .primitive = SR_PRIM_POINTS,
                                                   .positions = pt, .vertex_count = 1 }) == SR_OK);
    const uint8_t *px = sr_framebuffer_pixels(fb);
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            bool in_line = y == 10 && x >= 2 && x < 20;
            bool in_point = x >= 25 && x < 27 && y >= 25 && y < 27;
            CHECK_EQ(px[(y * W + x) * 4], (in_line || in_point) ? 255 : 0);
        }
    }
    /* A diagonal line: its resolved pixels take partial values (antialiased). */
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
    float diag[6] = { -0.9f, -0.7f, 0, 0.8f, 0.9f, 0 };
    st.point_size = 0;
    REQUIRE(sr_draw(ctx, fb, &st, &(sr_draw_desc){ .primitive = SR_PRIM_LINES,
                                                   .positions = diag, .vertex_count = 2 }) == SR_OK);
    px = sr_framebuffer_pixels(fb);
    int partial = 0;
    long total = 0;
    for (int i = 0; i < W * H; i++) {
        partial += px[i * 4] > 0 && px[i * 4] < 255;
        total += px[i * 4];
    }
    CHECK(partial > 20);
    /* The total intensity is the rectangle's area (length x width 1) in
     * pixels, up to sampling error. */
    double len = hypot((0.8 + 0.9) * 16, (0.9 + 0.7) * 16);
    CHECK_NEAR(total / 255.0, len, len * 0.08);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

/* Draws window-space points (x, y pairs) through a viewport of 256 x 256
 * at the origin, which maps q8 coordinates exactly whatever the
 * framebuffer's size: x_ndc = x / 128 - 1.  With `triangle` the three
 * points are a triangle's corners in polygon mode POINT instead. */
static sr_result draw_points(sr_context *ctx, sr_framebuffer *fb, const double *xy, int n,
                             bool triangle, const sr_state *extra)
{
    float *pos = malloc(sizeof(float) * 3 * (size_t)n);
    for (int i = 0; i < n; i++) {
        pos[i * 3 + 0] = (float)(xy[i * 2] / 128.0 - 1.0);
        pos[i * 3 + 1] = (float)(1.0 - xy[i * 2 + 1] / 128.0);
        pos[i * 3 + 2] = 0.0f;
    }
    sr_state st = *extra;
    st.viewport = (sr_viewport){ 0, 0, 256, 256 };
    st.shading = SR_SHADING_UNLIT;
    st.material = (sr_material){ .diffuse = { 1, 1, 1 } };
    if (triangle) {
        st.polygon_mode_front = st.polygon_mode_back = SR_POLYGON_POINT;
    }
    sr_result r = sr_draw(ctx, fb, &st,
                          &(sr_draw_desc){ .primitive = triangle ? SR_PRIM_TRIANGLES
                                                                 : SR_PRIM_POINTS,
                                           .positions = pos, .vertex_count = (size_t)n });
    /* The pending clear, into the samples that were not drawn. */
    sr__fb_resolve(fb, SR_TILE_PENDING_COLOR);
    free(pos);
    return r;
}

/* Sample s of pixel i drawn (red channel set), after draw_points. */
static bool sample_on(const sr_framebuffer *fb, int i, int s)
{
    return (fb->color[(size_t)i * (size_t)fb->samples + (size_t)s] & 0xff) != 0;
}

/* ceil(a / 256) */
static int64_t ceil256(int64_t a)
{
    return a >= 0 ? (a + 255) / 256 : -((-a) / 256);
}

/* docs/raster-rules.md §8 and §9.2: a multisampled point covers the samples inside
 * its square, whether or not the square holds a pixel centre, and
 * whether or not the pixel centres it holds lie inside the framebuffer
 * and the scissor. */
SR_TEST(msaa_points_cover_samples_without_a_pixel_centre)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    /* Size 0.75 at (1, 1): the square [0.625, 1.375)^2 holds no centre,
     * but sample 3 of pixel (0, 0), at (0.625, 0.875), and sample 2 of
     * pixel (1, 0), at (1.125, 0.625). */
    sr_framebuffer *fb = make_ms(ctx, 4, 4, 4, SR_DEPTH_NONE);
    REQUIRE(fb);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
    REQUIRE(draw_points(ctx, fb, (const double[]){ 1.0, 1.0 }, 1, false,
                        &(sr_state){ .point_size = 0.75f }) == SR_OK);
    for (int i = 0; i < 16; i++) {
        for (int s = 0; s < 4; s++) {
            CHECK_EQ(sample_on(fb, i, s), (i == 0 && s == 3) || (i == 1 && s == 2));
        }
    }
    CHECK_EQ(sr_last_draw_info(ctx).fragments, 2);
    sr_destroy_framebuffer(ctx, fb);
    /* Size 1 at (4.25, 1): the square [3.75, 4.75) x [0.5, 1.5) holds the
     * centres of pixels 4 (past a 4-wide framebuffer, or past a scissor at
     * x < 4) and sample 1 of pixel (3, 1), at (3.875, 1.375). */
    for (int scissored = 0; scissored < 2; scissored++) {
        int w = scissored ? 64 : 4;
        fb = make_ms(ctx, w, 4, 4, SR_DEPTH_NONE);
        REQUIRE(fb);
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
        sr_state st = { .point_size = 1 };
        if (scissored) {
            st.scissor = (sr_scissor){ true, 0, 0, 4, 4 };
        }
        REQUIRE(draw_points(ctx, fb, (const double[]){ 4.25, 1.0 }, 1, false, &st) == SR_OK);
        for (int i = 0; i < w * 4; i++) {
            for (int s = 0; s < 4; s++) {
                CHECK_EQ(sample_on(fb, i, s), i == 1 * w + 3 && s == 1);
            }
        }
        CHECK_EQ(sr_last_draw_info(ctx).fragments, 1);
        sr_destroy_framebuffer(ctx, fb);
    }
    sr_destroy_context(ctx);
}

/* Every sample of points against the rule, written from docs/raster-rules.md §8 and
 * 8.2: a square [c - h, c + h) on both axes, or with round or smooth
 * points the open disc of radius h (GL drops smoothing under
 * multisampling), h = size / 2 on the 1/256 grid.  Points, and triangles
 * in polygon mode POINT, mostly small and near the tile borders at 128 or
 * the framebuffer's edges, so that many hold no pixel centre, or none
 * inside, and many straddle two tiles; 1 and 3 threads. */
SR_TEST(msaa_points_match_the_per_sample_rule)
{
    enum { W = 136, H = 136, N = 3 };
    static const int counts[] = { 2, 4, 8, 16 };
    sr_context *ctx[2];
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx[0]) == SR_OK);
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 3 }, &ctx[1]) == SR_OK);
    sr_rng rng = { 0x90175 };
    static uint8_t want[W * H * 16];
    long bad = 0, covered = 0, pointless = 0;
    for (int it = 0; it < 480; it++) {
        int n = counts[it % 4];
        sr_context *c = ctx[(it / 4) % 2];
        sr_framebuffer *fb = make_ms(c, W, H, n, SR_DEPTH_NONE);
        REQUIRE(fb);
        sr_clear(c, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
        /* Sizes on the 1/128 grid, so that h is a whole number of q8. */
        double size = (it % 5 == 0 ? sr_rng_int(&rng, 1, 128 * 12) : sr_rng_int(&rng, 1, 128 * 2))
                      / 128.0;
        bool round = it % 3 == 1, smooth = it % 3 == 2, triangle = (it / 8) % 2 == 1;
        double xy[2 * N];
        for (int k = 0; k < N; k++) {
            static const double near[] = { 0, 128, 136 };
            for (int a = 0; a < 2; a++) {
                double v = sr_rng_int(&rng, 0, 1) ? near[sr_rng_int(&rng, 0, 2)] + sr_rng_range(&rng, -2, 2)
                                                  : sr_rng_range(&rng, -2, 138);
                xy[k * 2 + a] = floor(v * 256) / 256;
            }
        }
        if (triangle) {
            int64_t ex = ref_snap(xy[2]) - ref_snap(xy[0]), ey = ref_snap(xy[3]) - ref_snap(xy[1]);
            int64_t fx = ref_snap(xy[4]) - ref_snap(xy[0]), fy = ref_snap(xy[5]) - ref_snap(xy[1]);
            if (ex * fy - ey * fx == 0) {
                sr_destroy_framebuffer(c, fb);
                continue; /* no area: polygon mode draws nothing */
            }
        }
        sr_state st = { .point_size = (float)size, .round_points = round, .smooth_points = smooth };
        REQUIRE(draw_points(c, fb, xy, N, triangle, &st) == SR_OK);
        int64_t h = (int64_t)(size * 128);
        const int (*pos)[2] = vk_table(n);
        for (int k = 0; k < N; k++) {
            /* The pixels whose centre lies in [c - h, c + h), inside the
             * framebuffer. */
            int64_t cx = ref_snap(xy[k * 2]), cy = ref_snap(xy[k * 2 + 1]);
            int64_t x0 = ceil256(cx - h - 128), x1 = ceil256(cx + h - 128);
            int64_t y0 = ceil256(cy - h - 128), y1 = ceil256(cy + h - 128);
            x0 = x0 > 0 ? x0 : 0, y0 = y0 > 0 ? y0 : 0;
            x1 = x1 < W ? x1 : W, y1 = y1 < H ? y1 : H;
            pointless += x0 >= x1 || y0 >= y1;
        }
        /* Each point's samples, over the pixels its square meets. */
        memset(want, 0, (size_t)W * H * n);
        for (int k = 0; k < N; k++) {
            int64_t cx = ref_snap(xy[k * 2]), cy = ref_snap(xy[k * 2 + 1]);
            for (int64_t py = (cy - h) / 256 - 1; py <= (cy + h) / 256 + 1; py++) {
                for (int64_t px = (cx - h) / 256 - 1; px <= (cx + h) / 256 + 1; px++) {
                    if (px < 0 || px >= W || py < 0 || py >= H) {
                        continue;
                    }
                    for (int s = 0; s < n; s++) {
                        int64_t dx = px * 256 + pos[s][0] * 16 - cx;
                        int64_t dy = py * 256 + pos[s][1] * 16 - cy;
                        want[(py * W + px) * n + s] |= round || smooth
                                                           ? dx * dx + dy * dy < h * h
                                                           : dx >= -h && dx < h && dy >= -h && dy < h;
                    }
                }
            }
        }
        for (int i = 0; i < W * H * n; i++) {
            bad += sample_on(fb, i / n, i % n) != want[i];
            covered += want[i];
        }
        sr_destroy_framebuffer(c, fb);
    }
    CHECK_EQ(bad, 0);
    CHECK(covered > 10000);
    CHECK(pointless > 100);  /* squares holding no pixel centre inside the framebuffer */
    sr_destroy_context(ctx[0]);
    sr_destroy_context(ctx[1]);
}

/* A scissor only trims: with it the samples inside its rectangle are
 * those drawn without it, and outside it nothing is drawn.  Points of any
 * size, square, round or smooth, and polygon mode POINT, 1 to 16 samples
 * (single-sampled smooth points' ramp reaches past their square), centres
 * anywhere in and around the framebuffer. */
SR_TEST(scissor_does_not_change_points_inside_it)
{
    enum { W = 150, H = 140, N = 30 };
    static const int counts[] = { 1, 2, 4, 8, 16 };
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 2 }, &ctx) == SR_OK);
    sr_rng rng = { 0x5c155 };
    long bad = 0, drawn = 0;
    for (int it = 0; it < 150; it++) {
        int n = counts[it % 5];
        double xy[2 * N];
        for (int k = 0; k < 2 * N; k++) {
            xy[k] = floor(sr_rng_range(&rng, -4, (k % 2 ? H : W) + 4) * 256) / 256;
        }
        bool triangle = it % 4 == 3;
        sr_state st = { .point_size = (float)(sr_rng_int(&rng, 0, 3) ? sr_rng_range(&rng, 0.1, 2)
                                                                     : sr_rng_range(&rng, 2, 12)),
                        .round_points = it % 3 == 1, .smooth_points = it % 3 == 2 };
        sr_scissor sc = { true, sr_rng_int(&rng, -3, W - 1), sr_rng_int(&rng, -3, H - 1),
                          sr_rng_int(&rng, 1, 20), sr_rng_int(&rng, 1, 20) };
        uint32_t *plain = NULL;
        for (int pass = 0; pass < 2; pass++) {
            sr_framebuffer *fb = make_ms(ctx, W, H, n, SR_DEPTH_NONE);
            REQUIRE(fb);
            sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
            sr_state s = st;
            if (pass == 1) {
                s.scissor = sc;
            }
            REQUIRE(draw_points(ctx, fb, xy, N, triangle, &s) == SR_OK);
            size_t count = (size_t)W * H * n;
            if (pass == 0) {
                plain = malloc(count * sizeof(uint32_t));
                memcpy(plain, fb->color, count * sizeof(uint32_t));
            } else {
                for (int y = 0; y < H; y++) {
                    for (int x = 0; x < W; x++) {
                        bool in = x >= sc.x && x < sc.x + sc.width && y >= sc.y &&
                                  y < sc.y + sc.height;
                        for (int k = 0; k < n; k++) {
                            size_t i = ((size_t)y * W + x) * n + k;
                            bad += fb->color[i] != (in ? plain[i] : 0u);
                            drawn += in && plain[i] != 0;
                        }
                    }
                }
            }
            sr_destroy_framebuffer(ctx, fb);
        }
        free(plain);
    }
    CHECK_EQ(bad, 0);
    CHECK(drawn > 1000);
    sr_destroy_context(ctx);
}

SR_TEST(alpha_to_coverage_keeps_that_share_of_the_samples)
{
    enum { W = 8, H = 8 };
    sr_context *ctx;
    REQUIRE(sr_make_context(NULL, &ctx) == SR_OK);
    static const int counts[] = { 2, 4, 8, 16 };
    for (int c = 0; c < 4; c++) {
        int n = counts[c];
        sr_framebuffer *fb = make_ms(ctx, W, H, n, SR_DEPTH_NONE);
        REQUIRE(fb);
        for (int k = 0; k <= n; k++) {
            sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
            float quad[18] = { -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, -1, 0, 1, 1, 0, -1, 1, 0 };
            sr_state st = { .shading = SR_SHADING_UNLIT, .alpha_to_coverage = true,
                            .material = { .diffuse = { 1, 1, 1 }, .opacity = 0 } };
            st.material.opacity = (float)k / (float)n;
            if (k == 0) {
                st.material.opacity = 0.01f;  /* 0 would mean the default, 1 */
            }
            REQUIRE(sr_draw(ctx, fb, &st, &(sr_draw_desc){ .positions = quad, .vertex_count = 6 })
                    == SR_OK);
            sr__fb_resolve(fb, SR_TILE_PENDING_COLOR);  /* the pending clear, into the samples */
            for (int p = 0; p < W * H; p++) {
                int on = 0;
                for (int s = 0; s < n; s++) {
                    on += (fb->color[p * n + s] & 0xff) != 0;
                }
                CHECK_EQ(on, k);
            }
        }
        sr_destroy_framebuffer(ctx, fb);
    }
    sr_destroy_context(ctx);
}

/* The same multisampled, blended scene on 1, 2, 3 and 8 threads. */
SR_TEST(multisampled_blending_is_deterministic_across_threads)
{
    enum { W = 3 * SR_TILE_SIZE + 8, H = 2 * SR_TILE_SIZE + 22, T = 3000 }; /* 4 x 3 tiles */
    sr_rng rng = { 1234 };
    float *pos = malloc(sizeof(float) * 9 * T), *col = malloc(sizeof(float) * 12 * T);
    for (int i = 0; i < 3 * T; i++) {
        pos[i * 3 + 0] = (float)sr_rng_range(&rng, -1.1, 1.1);
        pos[i * 3 + 1] = (float)sr_rng_range(&rng, -1.1, 1.1);
        pos[i * 3 + 2] = (float)sr_rng_range(&rng, -1, 1);
        for (int k = 0; k < 4; k++) {
            col[i * 4 + k] = (float)sr_rng_unit(&rng);
        }
    }
    uint8_t *first = NULL;
    static const int threads[] = { 1, 2, 3, 8 };
    for (int ti = 0; ti < 4; ti++) {
        sr_context *ctx;
        REQUIRE(sr_make_context(&(sr_context_desc){ .threads = threads[ti] }, &ctx) == SR_OK);
        sr_framebuffer *fb = make_ms(ctx, W, H, 8, SR_DEPTH_D24);
        REQUIRE(fb);
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 }, .depth = 1 });
        sr_state st = { .shading = SR_SHADING_UNLIT, .depth_func = SR_LEQUAL,
                        .blend = { .enabled = true, .src_rgb = SR_BLEND_SRC_ALPHA,
                                   .dst_rgb = SR_BLEND_ONE_MINUS_SRC_ALPHA } };
        REQUIRE(sr_draw(ctx, fb, &st, &(sr_draw_desc){ .positions = pos, .vertex_count = 3 * T,
                                                       .colors = col }) == SR_OK);
        size_t bytes = (size_t)W * H * 8 * 4;
        if (!first) {
            first = malloc(bytes);
            memcpy(first, fb->color, bytes);
        } else {
            CHECK(memcmp(first, fb->color, bytes) == 0);
        }
        sr_destroy_framebuffer(ctx, fb);
        sr_destroy_context(ctx);
    }
    free(first);
    free(pos);
    free(col);
}

/* The four-sample vector kernels (four pixels at a time with AVX-512, one
 * pixel with SR_SIMD=avx2 and with the baseline build, SR_SIMD=base)
 * against the generic per-sample path, which the stencil test (always
 * passing) selects: every sample's color and depth equal, with colors
 * outside [0, 1] and flat shading too. */
SR_TEST(four_sample_kernel_equals_the_generic_path)
{
    enum { W = 160, H = 120, T = 1500 };
    sr_rng rng = { 4242 };
    float *pos = malloc(sizeof(float) * 9 * T), *col = malloc(sizeof(float) * 12 * T);
    for (int i = 0; i < 3 * T; i++) {
        pos[i * 3 + 0] = (float)sr_rng_range(&rng, -1.2, 1.2);
        pos[i * 3 + 1] = (float)sr_rng_range(&rng, -1.2, 1.2);
        pos[i * 3 + 2] = (float)sr_rng_range(&rng, -1.1, 1.1);  /* some beyond near/far */
        for (int k = 0; k < 4; k++) {
            col[i * 4 + k] = (float)sr_rng_range(&rng, -0.3, 1.3);
        }
    }
    sr_draw_desc d = { .positions = pos, .vertex_count = 3 * T, .colors = col };
    static const char *const simd[] = { "", "avx2", "base" };
    static const sr_depth_format formats[] = { SR_DEPTH_D16, SR_DEPTH_D24 };
    unsigned drawn = 0; /* (level, shading) pairs already drawn */
    for (int v = 0; v < 6; v++) {
        setenv("SR_SIMD", simd[v % 3], 1);
        /* A level the CPU caps to one already drawn runs the same kernel
         * again (on aarch64 all three are NEON): skipped. */
        sr_context *probe;
        REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &probe) == SR_OK);
        unsigned bit = 1u << ((int)sr_context_simd(probe) + 8 * (v / 3));
        sr_destroy_context(probe);
        if (drawn & bit) {
            continue;
        }
        drawn |= bit;
        for (int f = 0; f < 2; f++) {
            sr_context *ctx;
            REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 2 }, &ctx) == SR_OK);
            sr_framebuffer *a = make_ms(ctx, W, H, 4, formats[f]);
            sr_framebuffer *b = make_ms(ctx, W, H, 4, formats[f]);
            REQUIRE(a && b);
            sr_clear_desc cl = { .color = { 0.2f, 0.1f, 0, 1 }, .depth = 1 };
            sr_clear(ctx, a, &cl);
            sr_clear(ctx, b, &cl);
            sr_state st = { .shading = v < 3 ? SR_SHADING_UNLIT : SR_SHADING_FLAT };
            REQUIRE(sr_draw(ctx, a, &st, &d) == SR_OK);
            uint64_t frags = sr_last_draw_info(ctx).fragments;
            st.stencil.enabled = true;
            REQUIRE(sr_draw(ctx, b, &st, &d) == SR_OK);
            CHECK_EQ(sr_last_draw_info(ctx).fragments, frags);
            sr__fb_resolve(a, SR_TILE_PENDING_COLOR | SR_TILE_PENDING_DEPTH);
            sr__fb_resolve(b, SR_TILE_PENDING_COLOR | SR_TILE_PENDING_DEPTH);
            size_t n = (size_t)W * H * 4;
            CHECK(memcmp(a->color, b->color, n * 4) == 0);
            CHECK(memcmp(a->depth, b->depth, n * (size_t)sr__depth_size(a)) == 0);
            sr_destroy_framebuffer(ctx, a);
            sr_destroy_framebuffer(ctx, b);
            sr_destroy_context(ctx);
        }
    }
    unsetenv("SR_SIMD");
    free(pos);
    free(col);
}
