/* test_lines3d.c - lines, points and polygon modes in the 3D pipeline:
 * diamond-exit pixels against an independent implementation of the
 * closed form (docs/raster-rules.md §7.1), strips without gaps or doubles, polygon
 * modes against the equivalent line loops, square points with half-open
 * edges, clipping, and hidden-line depth with polygon offset. */
#include "raster_util.h"
#include "line_ref.h"

enum { W = 64, H = 64 };

static sr_result draw_prims(rt_target *t, sr_primitive prim, const double *xy, int n,
                            const sr_state *extra)
{
    float *pos = malloc(sizeof(float) * 3 * (size_t)n);
    for (int i = 0; i < n; i++) {
        pos[i * 3 + 0] = rt_ndc_x(t, xy[i * 2 + 0]);
        pos[i * 3 + 1] = rt_ndc_y(t, xy[i * 2 + 1]);
        pos[i * 3 + 2] = 0.0f;
    }
    sr_state st = extra ? *extra : (sr_state){0};
    st.shading = SR_SHADING_UNLIT;
    st.material = (sr_material){ .diffuse = { 1, 1, 1 } };
    sr_result r = sr_draw(t->ctx, t->fb, &st,
                          &(sr_draw_desc){ .primitive = prim, .positions = pos,
                                           .vertex_count = (size_t)n });
    free(pos);
    return r;
}

/* ---- the closed form, written from docs/raster-rules.md §7.1 ---- */

static int64_t snapq(double v) { return (int64_t)nearbyint(v * 256.0); }

static void ref_line(const double a[2], const double b[2], uint8_t *mask)
{
    memset(mask, 0, W * H);
    int64_t ax = snapq(a[0]), ay = snapq(a[1]), bx = snapq(b[0]), by = snapq(b[1]);
    if (ax == bx && ay == by) {
        return;
    }
    bool xmaj = llabs(bx - ax) >= llabs(by - ay);
    int64_t au = xmaj ? ax : ay, av = xmaj ? ay : ax, bu = xmaj ? bx : by, bv = xmaj ? by : bx;
    int64_t lo = au < bu ? au : bu, hi = au < bu ? bu : au;
    for (int k = -2; k < (xmaj ? W : H) + 2; k++) {
        int64_t c = k * 256 + 128;
        if (c < lo || c > hi) {
            continue;
        }
        int64_t j = lr_column_pixel(au, av, bu, bv, c);
        int px = xmaj ? k : (int)j, py = xmaj ? (int)j : k;
        if (px >= 0 && px < W && py >= 0 && py < H) {
            mask[py * W + px] = 1;
        }
    }
    for (int qy = -1; qy <= H; qy++) {
        for (int qx = -1; qx <= W; qx++) {
            bool in_range = qx >= 0 && qx < W && qy >= 0 && qy < H;
            if (in_range && lr_diamond_owns(ax, ay, qx, qy, xmaj)) {
                mask[qy * W + qx] = 1;
            }
        }
    }
    for (int qy = 0; qy < H; qy++) {
        for (int qx = 0; qx < W; qx++) {
            if (lr_diamond_owns(bx, by, qx, qy, xmaj)) {
                mask[qy * W + qx] = 0;
            }
        }
    }
}

static double q8r(sr_rng *r, double lo, double hi)
{
    return floor(sr_rng_range(r, lo, hi) * 256.0) / 256.0;
}

SR_TEST(line_pixels_match_the_closed_form)
{
    rt_target t = rt_make(W, H, 1);
    uint8_t got[W * H], want[W * H];
    sr_rng rng = { 0x11ee };
    long bad = 0;
    for (int it = 0; it < 4000; it++) {
        double xy[4];
        int kind = it % 3;
        for (int k = 0; k < 4; k++) {
            xy[k] = kind == 0 ? q8r(&rng, -8, 72)
                  : kind == 1 ? sr_rng_int(&rng, 0, 63) + 0.5       /* pixel centres */
                              : sr_rng_int(&rng, 0, 64) + (sr_rng_int(&rng, 0, 1) ? 0.0 : 0.5);
        }
        rt_clear(&t);
        REQUIRE(draw_prims(&t, SR_PRIM_LINES, xy, 2, NULL) == SR_OK);
        rt_mask(&t, got);
        ref_line(xy, xy + 2, want);
        bad += memcmp(got, want, sizeof got) != 0;
    }
    CHECK_EQ(bad, 0);
    rt_free(&t);
}

/* Reversing a segment changes only which end pixel is left open. */
SR_TEST(line_direction_changes_only_the_open_end)
{
    rt_target t = rt_make(W, H, 1);
    uint8_t ab[W * H], ba[W * H];
    sr_rng rng = { 0xd1 };
    long bad = 0;
    for (int it = 0; it < 2000; it++) {
        double xy[4] = { q8r(&rng, 2, 62), q8r(&rng, 2, 62), q8r(&rng, 2, 62), q8r(&rng, 2, 62) };
        double yx[4] = { xy[2], xy[3], xy[0], xy[1] };
        rt_clear(&t);
        draw_prims(&t, SR_PRIM_LINES, xy, 2, NULL);
        rt_mask(&t, ab);
        rt_clear(&t);
        draw_prims(&t, SR_PRIM_LINES, yx, 2, NULL);
        rt_mask(&t, ba);
        int diff = 0;
        for (int i = 0; i < W * H; i++) {
            diff += ab[i] != ba[i];
        }
        bad += diff > 2;
    }
    CHECK_EQ(bad, 0);
    rt_free(&t);
}

/* A strip drawn segment by segment: no pixel twice, and consecutive pixels
 * 8-connected (no gaps) along the whole strip. */
SR_TEST(line_strips_join_without_gaps_or_double_pixels)
{
    rt_target t = rt_make(W, H, 1);
    uint8_t m[W * H];
    static int count[W * H];
    sr_rng rng = { 0x5791 };
    for (int it = 0; it < 200; it++) {
        enum { N = 12 };
        double xy[N * 2];
        for (int k = 0; k < N * 2; k++) {
            xy[k] = q8r(&rng, 4, 60);
        }
        memset(count, 0, sizeof count);
        for (int s = 0; s + 1 < N; s++) {
            rt_clear(&t);
            draw_prims(&t, SR_PRIM_LINES, xy + s * 2, 2, NULL);
            rt_mask(&t, m);
            for (int i = 0; i < W * H; i++) {
                count[i] += m[i];
            }
        }
        /* Drawn as one strip, the image equals the union. */
        rt_clear(&t);
        REQUIRE(draw_prims(&t, SR_PRIM_LINE_STRIP, xy, N, NULL) == SR_OK);
        rt_mask(&t, m);
        for (int i = 0; i < W * H; i++) {
            CHECK_EQ(m[i], count[i] > 0);
        }
    }
    /* A straight strip split at arbitrary points: exactly the pixels of the
     * whole line, each once. */
    for (int it = 0; it < 500; it++) {
        double a[2] = { q8r(&rng, 2, 20), q8r(&rng, 2, 62) }, b[2] = { q8r(&rng, 44, 62), 0 };
        b[1] = q8r(&rng, 2, 62);
        double xy[6] = { a[0], a[1], 0, 0, b[0], b[1] };
        /* Split at a point exactly on the segment (an endpoint on the 1/256
         * grid reached by a rational t with a power-of-two denominator). */
        xy[2] = a[0] + (b[0] - a[0]) * 0.5;
        xy[3] = a[1] + (b[1] - a[1]) * 0.5;
        if (xy[2] * 256 != floor(xy[2] * 256) || xy[3] * 256 != floor(xy[3] * 256)) {
            continue;
        }
        memset(count, 0, sizeof count);
        for (int s = 0; s < 2; s++) {
            rt_clear(&t);
            draw_prims(&t, SR_PRIM_LINES, xy + s * 2, 2, NULL);
            rt_mask(&t, m);
            for (int i = 0; i < W * H; i++) {
                count[i] += m[i];
            }
        }
        /* Every pixel at most once, and the union is 8-connected from one
         * end to the other: flood it from a's pixel and reach b's run. */
        int total = 0;
        for (int i = 0; i < W * H; i++) {
            CHECK(count[i] <= 1);
            total += count[i] > 0;
        }
        int stack[W * H], top = 0, seen = 0;
        uint8_t vis[W * H] = { 0 };
        int start = -1;
        for (int i = 0; i < W * H && start < 0; i++) {
            start = count[i] ? i : -1;
        }
        if (start >= 0) {
            stack[top++] = start;
            vis[start] = 1;
            while (top) {
                int p = stack[--top];
                seen++;
                for (int dy = -1; dy <= 1; dy++) {
                    for (int dx = -1; dx <= 1; dx++) {
                        int x = p % W + dx, y = p / W + dy;
                        if (x >= 0 && x < W && y >= 0 && y < H && count[y * W + x] &&
                            !vis[y * W + x]) {
                            vis[y * W + x] = 1;
                            stack[top++] = y * W + x;
                        }
                    }
                }
            }
        }
        CHECK_EQ(seen, total); /* no gap where the two segments meet */
    }
    rt_free(&t);
}

SR_TEST(polygon_mode_line_draws_the_triangle_outline)
{
    rt_target t = rt_make(W, H, 1);
    uint8_t loop[W * H], mode[W * H];
    sr_rng rng = { 0xabc };
    for (int it = 0; it < 300; it++) {
        double xy[6];
        for (int k = 0; k < 6; k++) {
            xy[k] = q8r(&rng, 2, 62);
        }
        rt_clear(&t);
        draw_prims(&t, SR_PRIM_LINE_LOOP, xy, 3, NULL);
        rt_mask(&t, loop);
        rt_clear(&t);
        sr_state st = { .polygon_mode_front = SR_POLYGON_LINE, .polygon_mode_back = SR_POLYGON_LINE };
        draw_prims(&t, SR_PRIM_TRIANGLES, xy, 3, &st);
        rt_mask(&t, mode);
        /* Zero-area triangles draw nothing in any mode. */
        int64_t x0 = snapq(xy[0]), y0 = snapq(xy[1]), x1 = snapq(xy[2]), y1 = snapq(xy[3]);
        int64_t x2 = snapq(xy[4]), y2 = snapq(xy[5]);
        if ((x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0) == 0) {
            continue;
        }
        CHECK(memcmp(loop, mode, sizeof loop) == 0);
    }
    /* Culling applies before the polygon mode. */
    double ccw[6] = { 10.5, 50.5, 50.5, 50.5, 30.5, 10.5 }; /* counter-clockwise on screen */
    rt_clear(&t);
    sr_state st = { .polygon_mode_front = SR_POLYGON_LINE, .polygon_mode_back = SR_POLYGON_LINE,
                    .cull = SR_CULL_FRONT };
    draw_prims(&t, SR_PRIM_TRIANGLES, ccw, 3, &st);
    rt_mask(&t, mode);
    int n = 0;
    for (int i = 0; i < W * H; i++) {
        n += mode[i];
    }
    CHECK_EQ(n, 0);
    rt_free(&t);
}

static int count_mask(const uint8_t *m)
{
    int n = 0;
    for (int i = 0; i < W * H; i++) {
        n += m[i];
    }
    return n;
}

SR_TEST(points_are_squares_with_half_open_edges)
{
    rt_target t = rt_make(W, H, 1);
    uint8_t m[W * H];
    struct { double x, y; float size; int want; } cases[] = {
        { 10.5, 10.5, 1, 1 },   /* a pixel centre: that pixel */
        { 10.5, 10.5, 3, 9 },
        { 10.0, 10.0, 2, 4 },   /* on a corner: the 2x2 around it */
        { 10.0, 10.0, 1, 1 },   /* [9.5, 10.5): centre 9.5 in, 10.5 out */
        { 10.25, 10.75, 4, 16 },
        { 0.0, 0.0, 2, 1 },     /* trimmed by the framebuffer */
    };
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        rt_clear(&t);
        double xy[2] = { cases[i].x, cases[i].y };
        sr_state st = { .point_size = cases[i].size };
        REQUIRE(draw_prims(&t, SR_PRIM_POINTS, xy, 1, &st) == SR_OK);
        rt_mask(&t, m);
        CHECK_EQ(count_mask(m), cases[i].want);
    }
    /* Polygon mode POINT: one point per corner. */
    rt_clear(&t);
    double tri[6] = { 10.5, 10.5, 40.5, 12.5, 20.5, 40.5 };
    sr_state st = { .polygon_mode_front = SR_POLYGON_POINT, .polygon_mode_back = SR_POLYGON_POINT };
    draw_prims(&t, SR_PRIM_TRIANGLES, tri, 3, &st);
    rt_mask(&t, m);
    CHECK_EQ(count_mask(m), 3);
    CHECK(m[10 * W + 10] && m[12 * W + 40] && m[40 * W + 20]);
    rt_free(&t);
}

SR_TEST(round_points_cover_the_pixel_centres_inside_the_disc)
{
    rt_target t = rt_make(W, H, 1);
    uint8_t m[W * H];
    sr_rng rng = { 0x9017 };
    for (int it = 0; it < 200; it++) {
        double cx = q8r(&rng, 8, 56), cy = q8r(&rng, 8, 56);
        float size = (float)sr_rng_range(&rng, 1.0, 14.0);
        rt_clear(&t);
        double xy[2] = { cx, cy };
        sr_state st = { .point_size = size, .round_points = true };
        REQUIRE(draw_prims(&t, SR_PRIM_POINTS, xy, 1, &st) == SR_OK);
        rt_mask(&t, m);
        /* Reference: radius snapped to 1/256 as the pipeline does. */
        int64_t half = (int64_t)nearbyint(size * 128.0);
        int64_t qx = snapq(cx), qy = snapq(cy);
        for (int y = 0; y < H; y++) {
            for (int x = 0; x < W; x++) {
                int64_t dx = x * 256 + 128 - qx, dy = y * 256 + 128 - qy;
                CHECK_EQ(m[y * W + x], dx * dx + dy * dy < half * half);
            }
        }
    }
    rt_free(&t);
}

static double total_red(const rt_target *t)
{
    const uint8_t *px = sr_framebuffer_pixels(t->fb);
    double sum = 0.0;
    for (int i = 0; i < W * H; i++) {
        sum += px[i * 4] / 255.0;
    }
    return sum;
}

/* Antialiased lines and points: the coverage summed over the pixels equals
 * the integral of the one-pixel ramp, within 2% (pixel sampling).  Across a
 * straight edge the ramp integrates to the exact area; around a circle of
 * radius r it gives pi r^2 + pi/12, so a disc and the two round ends of a
 * line carry that small excess. */
SR_TEST(smooth_lines_and_points_cover_their_area)
{
    rt_target t = rt_make(W, H, 1);
    sr_rng rng = { 0x5300 };
    for (int it = 0; it < 40; it++) {
        double a[2] = { q8r(&rng, 10, 54), q8r(&rng, 10, 54) }, b[2];
        double len;
        do {
            b[0] = q8r(&rng, 10, 54);
            b[1] = q8r(&rng, 10, 54);
            len = hypot(b[0] - a[0], b[1] - a[1]);
        } while (len < 15.0);
        float width = (float)sr_rng_range(&rng, 1.0, 5.0);
        double xy[4] = { a[0], a[1], b[0], b[1] };
        rt_clear(&t);
        sr_state st = { .line_width = width, .smooth_lines = true };
        REQUIRE(draw_prims(&t, SR_PRIM_LINES, xy, 2, &st) == SR_OK);
        double want = len * width + M_PI * width * width / 4.0 + M_PI / 12.0;
        CHECK_NEAR(total_red(&t) / want, 1.0, 0.02);
    }
    for (int it = 0; it < 40; it++) {
        double xy[2] = { q8r(&rng, 16, 48), q8r(&rng, 16, 48) };
        float size = (float)sr_rng_range(&rng, 3.0, 20.0);
        rt_clear(&t);
        sr_state st = { .point_size = size, .smooth_points = true };
        REQUIRE(draw_prims(&t, SR_PRIM_POINTS, xy, 1, &st) == SR_OK);
        CHECK_NEAR(total_red(&t) / (M_PI * size * size / 4.0 + M_PI / 12.0), 1.0, 0.02);
    }
    rt_free(&t);
}

typedef struct smooth_cov {
    int cov8[W * H];          /* -1: no pixel */
    int pixels, bad_order;
    int last_major;
} smooth_cov;

static void smooth_collect(void *user, const sr_line_pixel_info *p)
{
    smooth_cov *s = user;
    CHECK(p->x >= 0 && p->x < W && p->y >= 0 && p->y < H);
    CHECK_EQ(p->major, p->y_major ? p->y : p->x);
    CHECK(p->coverage > 0.0f && p->coverage <= 1.0f);
    CHECK(p->t >= 0.0 && p->t <= 1.0);
    double want = p->reach - p->distance;
    CHECK_NEAR(p->coverage, want < 1.0 ? want : 1.0, 1e-6);
    s->bad_order += p->major < s->last_major;
    s->last_major = p->major;
    int i = p->y * W + p->x;
    CHECK_EQ(s->cov8[i], -1);   /* each pixel once */
    s->cov8[i] = (int)lroundf(p->coverage * 255.0f);
    s->pixels++;
}

/* sr_smooth_line_pixels (what `softrast explain aaline` shows) against
 * sr_draw's smooth lines, white on black: each pixel it gives is the
 * fragment sr_draw blends with that coverage as alpha (within one 8-bit
 * step), and no other pixel is touched.  Random lines of every
 * direction, ends at 1/256 px inside the framebuffer, widths 0.5..6. */
SR_TEST(smooth_line_pixels_are_what_sr_draw_blends)
{
    rt_target t = rt_make(W, H, 1);
    sr_rng rng = { 0x5a11 };
    static smooth_cov s;
    int octants[8] = { 0 }, total = 0;
    for (int it = 0; it < 400; it++) {
        double xy[4] = { q8r(&rng, 2, 62), q8r(&rng, 2, 62), 0, 0 };
        double len = sr_rng_range(&rng, 0.3, 40), ang = sr_rng_range(&rng, 0, 2 * M_PI);
        xy[2] = floor((xy[0] + len * cos(ang)) * 256.0) / 256.0;
        xy[3] = floor((xy[1] + len * sin(ang)) * 256.0) / 256.0;
        if (xy[2] < 0 || xy[2] >= W || xy[3] < 0 || xy[3] >= H) {
            continue;
        }
        double dx = xy[2] - xy[0], dy = xy[3] - xy[1];
        octants[(dx < 0) * 4 + (dy < 0) * 2 + (fabs(dy) > fabs(dx))]++;
        float width = it % 4 == 0 ? 1.0f : (float)sr_rng_range(&rng, 0.5, 6.0);
        for (int i = 0; i < W * H; i++) {
            s.cov8[i] = -1;
        }
        s.pixels = s.bad_order = 0;
        s.last_major = -1000;
        REQUIRE(sr_smooth_line_pixels(t.ctx, W, H, (sr_point2){ xy[0], xy[1] },
                                      (sr_point2){ xy[2], xy[3] }, width, smooth_collect,
                                      &s) == SR_OK);
        CHECK_EQ(s.bad_order, 0);
        rt_clear(&t);
        sr_state st = { .line_width = width, .smooth_lines = true };
        REQUIRE(draw_prims(&t, SR_PRIM_LINES, xy, 2, &st) == SR_OK);
        const uint8_t *px = sr_framebuffer_pixels(t.fb);
        int bad = 0;
        for (int i = 0; i < W * H; i++) {
            int want = s.cov8[i] < 0 ? 0 : s.cov8[i];
            bad += abs(px[4 * i] - want) > 1 || (s.cov8[i] < 0 && px[4 * i] != 0);
        }
        if (bad) {
            printf("line %g,%g -> %g,%g width %g: %d pixels differ\n", xy[0], xy[1], xy[2],
                   xy[3], (double)width, bad);
        }
        CHECK_EQ(bad, 0);
        total += s.pixels;
    }
    for (int o = 0; o < 8; o++) {
        CHECK(octants[o] > 10);
    }
    CHECK(total > 10000);
    rt_free(&t);
}

static void count_pixel(void *user, const sr_line_pixel_info *p)
{
    (void)p;
    (*(int *)user)++;
}

SR_TEST(smooth_line_pixels_refuses_bad_input)
{
    rt_target t = rt_make(W, H, 1);
    int n = 0;
    sr_point2 a = { 3, 4 }, b = { 20, 9 };
    CHECK_EQ(sr_smooth_line_pixels(NULL, W, H, a, b, 1, count_pixel, &n), SR_INVALID_ARG);
    CHECK_EQ(sr_smooth_line_pixels(t.ctx, W, H, a, b, 1, NULL, &n), SR_INVALID_ARG);
    CHECK_EQ(sr_smooth_line_pixels(t.ctx, 0, H, a, b, 1, count_pixel, &n), SR_INVALID_ARG);
    CHECK_EQ(sr_smooth_line_pixels(t.ctx, W, H, (sr_point2){ NAN, 0 }, b, 1, count_pixel, &n),
             SR_INVALID_ARG);
    CHECK_EQ(sr_smooth_line_pixels(t.ctx, W, H, a, b, 65, count_pixel, &n), SR_INVALID_ARG);
    CHECK_EQ(sr_smooth_line_pixels(t.ctx, W, H, a, b, -1, count_pixel, &n), SR_INVALID_ARG);
    CHECK_EQ(n, 0);
    CHECK_EQ(sr_smooth_line_pixels(t.ctx, W, H, a, a, 1, count_pixel, &n), SR_OK);
    CHECK_EQ(n, 0);   /* a = b: nothing, as sr_draw */
    CHECK_EQ(sr_smooth_line_pixels(t.ctx, W, H, a, b, 0, count_pixel, &n), SR_OK);
    CHECK(n > 17 * 2);
    rt_free(&t);
}

/* A smooth point's ramp reaches half a pixel past its radius: one of
 * size 0.5 at (10, 10) holds no pixel centre in its square, yet the four
 * centres around it lie 0.707 px away, within 0.25 + 0.5, and take a
 * little coverage; so do pixels with a ramp inside a scissor that holds
 * none of the square's centres. */
SR_TEST(small_smooth_points_keep_their_ramp)
{
    rt_target t = rt_make(W, H, 1);
    uint8_t m[W * H];
    for (int scissored = 0; scissored < 2; scissored++) {
        rt_clear(&t);
        double xy[2] = { 10.0, 10.0 };
        sr_state st = { .point_size = 0.5f, .smooth_points = true };
        if (scissored) {
            /* Square [8.75, 11.25): centres 9.5 and 10.5, right of the
             * scissor; the ramp, to 1.75 px, reaches centres (8.5, 9.5)
             * and (8.5, 10.5), 1.58 px away. */
            st.point_size = 2.5f;
            st.scissor = (sr_scissor){ true, 0, 0, 9, 64 };
        }
        REQUIRE(draw_prims(&t, SR_PRIM_POINTS, xy, 1, &st) == SR_OK);
        rt_mask(&t, m);
        for (int y = 0; y < H; y++) {
            for (int x = 0; x < W; x++) {
                bool want = scissored ? x == 8 && y >= 9 && y <= 10
                                      : (x == 9 || x == 10) && (y == 9 || y == 10);
                CHECK_EQ(m[y * W + x], want);
            }
        }
    }
    rt_free(&t);
}

/* Partly covered pixels of a smooth line leave depth alone; fully
 * covered ones write it. */
SR_TEST(smooth_lines_write_depth_only_where_fully_covered)
{
    sr_context *ctx;
    sr_framebuffer *fb;
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                                    .depth_format = SR_DEPTH_D24 }, &fb);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 }, .depth = 1 });
    float pos[6] = { -0.8f, -0.3f, 0.0f, 0.8f, 0.4f, 0.0f };
    sr_state st = { .shading = SR_SHADING_UNLIT, .material = { .diffuse = { 1, 1, 1 } },
                    .line_width = 3, .smooth_lines = true };
    REQUIRE(sr_draw(ctx, fb, &st, &(sr_draw_desc){ .primitive = SR_PRIM_LINES,
                                                  .positions = pos, .vertex_count = 2 }) == SR_OK);
    const uint8_t *px = sr_framebuffer_pixels(fb);
    float depth[W * H];
    REQUIRE(sr_read_depth(ctx, fb, 0, 0, W, H, depth, W) == SR_OK);
    int full = 0, partial = 0;
    for (int i = 0; i < W * H; i++) {
        if (px[i * 4] == 255) {
            full++;
            CHECK(depth[i] < 1.0f);
        } else if (px[i * 4] > 0) {
            partial++;
            CHECK(depth[i] == 1.0f);
        }
    }
    CHECK(full > 30);
    CHECK(partial > 30);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(wide_lines_are_runs_across_the_minor_axis)
{
    rt_target t = rt_make(W, H, 1);
    uint8_t m[W * H];
    double xy[4] = { 5.5, 20.5, 55.5, 30.5 }; /* x-major */
    for (int width = 1; width <= 5; width++) {
        rt_clear(&t);
        sr_state st = { .line_width = (float)width };
        draw_prims(&t, SR_PRIM_LINES, xy, 2, &st);
        rt_mask(&t, m);
        for (int x = 6; x < 55; x++) {
            int n = 0;
            for (int y = 0; y < H; y++) {
                n += m[y * W + x];
            }
            CHECK_EQ(n, width);
        }
    }
    rt_free(&t);
}

/* GL's wide lines (docs/raster-rules.md §7.2, GL 14.5.2.2), written from the rule:
 * round the width to w, translate the segment by -(w - 1)/2 along the
 * minor axis (exact in q8: (w - 1) half pixels), rasterize that segment
 * one pixel wide by the closed form, and widen each of its pixels into a
 * run of w toward +minor.  The runs are clipped only to the framebuffer,
 * so path pixels up to w above or left of it still count. */
static void ref_wide_line(const double a[2], const double b[2], int w, uint8_t *mask)
{
    memset(mask, 0, W * H);
    int64_t ax = snapq(a[0]), ay = snapq(a[1]), bx = snapq(b[0]), by = snapq(b[1]);
    if (ax == bx && ay == by) {
        return;
    }
    bool xmaj = llabs(bx - ax) >= llabs(by - ay);
    int64_t shift = (int64_t)(w - 1) * 128;
    if (xmaj) {
        ay -= shift;
        by -= shift;
    } else {
        ax -= shift;
        bx -= shift;
    }
    enum { P = 8 }; /* margin around the framebuffer, > the widest run */
    static uint8_t path[(W + 2 * P) * (H + 2 * P)];
    memset(path, 0, sizeof path);
    int64_t au = xmaj ? ax : ay, av = xmaj ? ay : ax, bu = xmaj ? bx : by, bv = xmaj ? by : bx;
    int64_t lo = au < bu ? au : bu, hi = au < bu ? bu : au;
    for (int k = -P; k < (xmaj ? W : H) + P; k++) {
        int64_t c = k * 256 + 128;
        if (c < lo || c > hi) {
            continue;
        }
        int64_t j = lr_column_pixel(au, av, bu, bv, c);
        int64_t px = xmaj ? k : j, py = xmaj ? j : k;
        if (px >= -P && px < W + P && py >= -P && py < H + P) {
            path[(py + P) * (W + 2 * P) + px + P] = 1;
        }
    }
    for (int qy = -P; qy < H + P; qy++) {
        for (int qx = -P; qx < W + P; qx++) {
            if (lr_diamond_owns(ax, ay, qx, qy, xmaj)) {
                path[(qy + P) * (W + 2 * P) + qx + P] = 1;
            }
        }
    }
    for (int qy = -P; qy < H + P; qy++) {
        for (int qx = -P; qx < W + P; qx++) {
            if (lr_diamond_owns(bx, by, qx, qy, xmaj)) {
                path[(qy + P) * (W + 2 * P) + qx + P] = 0;
            }
        }
    }
    for (int qy = -P; qy < H + P; qy++) {
        for (int qx = -P; qx < W + P; qx++) {
            if (!path[(qy + P) * (W + 2 * P) + qx + P]) {
                continue;
            }
            for (int i = 0; i < w; i++) {
                int x = xmaj ? qx : qx + i, y = xmaj ? qy + i : qy;
                if (x >= 0 && x < W && y >= 0 && y < H) {
                    mask[y * W + x] = 1;
                }
            }
        }
    }
}

/* The exact pixels of wide lines, even widths included: against the
 * reference above, and against the 2D SR_LINE_WIDE, which follows the same
 * rule on the same conventions (y down, centres at +1/2, endpoints snapped
 * to 1/256 with round-to-nearest-even, the D3D diamond ties).  The
 * endpoints are on the 1/256 grid and the viewport maps them exactly.
 * Half the lines are x-major, half y-major; some reach off the
 * framebuffer. */
SR_TEST(wide_lines_match_the_gl_rule_at_every_width)
{
    rt_target t = rt_make(W, H, 1);
    uint8_t got[W * H], want[W * H], flat[W * H];
    sr_rng rng = { 0x3d1e };
    long bad[6] = { 0 }, bad2d[6] = { 0 }, lines[6] = { 0 };
    for (int it = 0; it < 1500; it++) {
        int w = 1 + it % 5;
        double u0 = q8r(&rng, -6, 70), u1 = q8r(&rng, -6, 70);
        double v0 = q8r(&rng, -4, 68), v1 = v0 + (u1 - u0) * sr_rng_range(&rng, -1.0, 1.0);
        v1 = floor(v1 * 256.0) / 256.0;
        bool xmaj = (it / 5) % 2 == 0;
        double xy[4] = { xmaj ? u0 : v0, xmaj ? v0 : u0, xmaj ? u1 : v1, xmaj ? v1 : u1 };
        rt_clear(&t);
        sr_state st = { .line_width = (float)w };
        REQUIRE(draw_prims(&t, SR_PRIM_LINES, xy, 2, &st) == SR_OK);
        rt_mask(&t, got);
        ref_wide_line(xy, xy + 2, w, want);
        rt_clear(&t);
        REQUIRE(sr_draw_line(t.ctx, t.fb, (sr_point2){ xy[0], xy[1] }, (sr_point2){ xy[2], xy[3] },
                             (sr_rgba){ 1, 1, 1, 1 },
                             &(sr_line_desc){ .algorithm = SR_LINE_WIDE, .width = w }) == SR_OK);
        rt_mask(&t, flat);
        lines[w]++;
        bad[w] += memcmp(got, want, sizeof got) != 0;
        bad2d[w] += memcmp(flat, want, sizeof flat) != 0;
    }
    for (int w = 1; w <= 5; w++) {
        CHECK_EQ(lines[w], 300);
        CHECK_EQ(bad[w], 0);
        CHECK_EQ(bad2d[w], 0);
    }
    rt_free(&t);
}

/* Lines far outside the screen are clipped at the guard band and still
 * cross the framebuffer as one unbroken run. */
SR_TEST(huge_lines_are_clipped_and_stay_continuous)
{
    rt_target t = rt_make(W, H, 1);
    uint8_t m[W * H];
    double xy[4] = { -1e6, 20.25, 1e6, 40.75 };
    rt_clear(&t);
    float pos[6] = { (float)(xy[0] / 32 - 1), (float)(1 - xy[1] / 32), 0,
                     (float)(xy[2] / 32 - 1), (float)(1 - xy[3] / 32), 0 };
    sr_state st = { .shading = SR_SHADING_UNLIT, .material = { .diffuse = { 1, 1, 1 } } };
    REQUIRE(sr_draw(t.ctx, t.fb, &st, &(sr_draw_desc){ .primitive = SR_PRIM_LINES,
                                                      .positions = pos, .vertex_count = 2 }) == SR_OK);
    rt_mask(&t, m);
    for (int x = 0; x < W; x++) {
        int n = 0;
        for (int y = 0; y < H; y++) {
            n += m[y * W + x];
        }
        CHECK_EQ(n, 1);
    }
    rt_free(&t);
}

/* The depth of a face's outline equals the face's own depth at the same
 * pixels, up to the half pixel a line pixel's centre may sit off the edge
 * (bounded by the face's depth slope); with polygon offset on the fill the
 * face moves back by exactly the offset and the outline lies in front. */
SR_TEST(outline_depth_matches_the_face_depth)
{
    sr_context *ctx;
    sr_framebuffer *face, *line;
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    sr_framebuffer_desc fd = { .width = W, .height = H, .depth_format = SR_DEPTH_D32F };
    sr_make_framebuffer(ctx, &fd, &face);
    sr_make_framebuffer(ctx, &fd, &line);
    sr_mat4 view = sr_look_at((sr_vec3){ 0.3f, 0.4f, 3 }, (sr_vec3){ 0, 0, 0 }, (sr_vec3){ 0, 1, 0 });
    sr_mat4 proj = sr_perspective(0.9f, 1.0f, 0.5f, 10.0f, false);
    float pos[9] = { -1, -1, -0.3f, 1, -0.8f, 0.3f, 0.1f, 1, -0.2f };
    sr_draw_desc d = { .positions = pos, .vertex_count = 3, .view = &view, .projection = &proj };
    float zf[W * H], zl[W * H], zo[W * H];
    for (int pass = 0; pass < 2; pass++) {
        sr_clear(ctx, face, &(sr_clear_desc){ .depth = 1 });
        sr_clear(ctx, line, &(sr_clear_desc){ .depth = 1 });
        sr_state fill = { .shading = SR_SHADING_UNLIT, .depth_func = SR_ALWAYS };
        if (pass == 1) {
            fill.offset = (sr_polygon_offset){ .factor = 1, .units = 1, .fill = true };
        }
        REQUIRE(sr_draw(ctx, face, &fill, &d) == SR_OK);
        sr_state outline = { .shading = SR_SHADING_UNLIT, .depth_func = SR_ALWAYS,
                             .polygon_mode_front = SR_POLYGON_LINE,
                             .polygon_mode_back = SR_POLYGON_LINE };
        REQUIRE(sr_draw(ctx, line, &outline, &d) == SR_OK);
        REQUIRE(sr_read_depth(ctx, face, 0, 0, W, H, pass ? zo : zf, W) == SR_OK);
        REQUIRE(sr_read_depth(ctx, line, 0, 0, W, H, zl, W) == SR_OK);
    }
    /* The face's largest depth change per pixel, from neighbouring pixels. */
    double slope = 0.0;
    for (int y = 0; y + 1 < H; y++) {
        for (int x = 0; x + 1 < W; x++) {
            int i = y * W + x;
            if (zf[i] < 1 && zf[i + 1] < 1 && zf[i + W] < 1) {
                slope = fmax(slope, fmax(fabs(zf[i + 1] - zf[i]), fabs(zf[i + W] - zf[i])));
            }
        }
    }
    REQUIRE(slope > 0);
    int compared = 0;
    for (int i = 0; i < W * H; i++) {
        if (zl[i] < 1 && zf[i] < 1) {
            CHECK(fabs(zl[i] - zf[i]) <= 0.5 * slope + 1e-6);   /* same surface */
            CHECK(zo[i] > zf[i]);                                /* offset pushes the face back */
            CHECK(zl[i] < zo[i]);                                /* and the outline wins */
            compared++;
        }
    }
    CHECK(compared > 30);   /* about half the outline lies over the face */
    sr_destroy_framebuffer(ctx, face);
    sr_destroy_framebuffer(ctx, line);
    sr_destroy_context(ctx);
}

/* Hidden-line rendering: a face filled with polygon offset, then its
 * outline with LEQUAL: every outline pixel of a front face passes. */
SR_TEST(outline_over_an_offset_face_passes_the_depth_test)
{
    sr_context *ctx;
    sr_framebuffer *fb;
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                                    .depth_format = SR_DEPTH_D24 }, &fb);
    sr_mat4 view = sr_look_at((sr_vec3){ 0.3f, 0.4f, 3 }, (sr_vec3){ 0, 0, 0 }, (sr_vec3){ 0, 1, 0 });
    sr_mat4 proj = sr_perspective(0.9f, 1.0f, 0.5f, 10.0f, false);
    /* A tilted quad, counter-clockwise toward the camera. */
    float pos[12] = { -1, -1, -0.3f, 1, -1, 0.3f, 1, 1, -0.2f, -1, 1, 0.1f };
    uint32_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    for (int with_offset = 0; with_offset < 2; with_offset++) {
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 }, .depth = 1 });
        sr_state fill = { .shading = SR_SHADING_UNLIT, .material = { .diffuse = { 0.2f, 0.2f, 0.2f } } };
        if (with_offset) {
            fill.offset = (sr_polygon_offset){ .factor = 1, .units = 1, .fill = true };
        }
        sr_draw_desc d = { .positions = pos, .vertex_count = 4, .indices = idx,
                           .index_type = SR_INDEX_U32, .index_count = 6, .view = &view,
                           .projection = &proj };
        REQUIRE(sr_draw(ctx, fb, &fill, &d) == SR_OK);
        sr_state lines = { .shading = SR_SHADING_UNLIT, .material = { .diffuse = { 1, 1, 1 } },
                           .polygon_mode_front = SR_POLYGON_LINE, .depth_func = SR_LEQUAL };
        REQUIRE(sr_draw(ctx, fb, &lines, &d) == SR_OK);
        uint8_t tested[W * H], all[W * H];
        const uint8_t *px = sr_framebuffer_pixels(fb);
        for (int i = 0; i < W * H; i++) {
            tested[i] = px[i * 4] == 255;
        }
        /* The same outline with no depth test: every pixel it covers. */
        lines.depth_test = SR_OFF;
        REQUIRE(sr_draw(ctx, fb, &lines, &d) == SR_OK);
        px = sr_framebuffer_pixels(fb);
        int n_all = 0, missing = 0;
        for (int i = 0; i < W * H; i++) {
            all[i] = px[i * 4] == 255;
            n_all += all[i];
            missing += all[i] && !tested[i];
        }
        REQUIRE(n_all > 100);
        if (with_offset) {
            CHECK_EQ(missing, 0);   /* no stitching: the face never hides its outline */
        }
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}
