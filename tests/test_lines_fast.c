/* test_lines_fast.c - the shortcuts of the aliased line path held to what
 * they replace: the fast fragment path (one pixel wide, no blending,
 * depth off or LESS, the interpolated or flat color) against the generic
 * sr__fragment_vary path, which a blend state equal to replace forces;
 * and the per-line tile binning and per-tile column ranges against the
 * closed form of the diamond-exit rule (docs/raster-rules.md §7.1), across tile
 * borders and at 1, 2 and 3 threads. */
#include "raster_util.h"
#include "raster/fixed.h"
#include "line_ref.h"

enum { FW = 8 * SR_TILE_SIZE, FH = 4 * SR_TILE_SIZE }; /* 8 x 4 tiles */

static const sr_blend blend_replace = {
    .enabled = true, .src_rgb = SR_BLEND_ONE, .dst_rgb = SR_BLEND_ZERO,
    .src_alpha = SR_BLEND_ONE, .dst_alpha = SR_BLEND_ZERO,
    .op_rgb = SR_BLEND_ADD, .op_alpha = SR_BLEND_ADD,
};

static double q8r(sr_rng *r, double lo, double hi)
{
    return floor(sr_rng_range(r, lo, hi) * 256.0) / 256.0;
}

/* ---- fast path against the generic path ---- */

typedef struct fast_case {
    const char *name;
    sr_shading shading;
    sr_depth_format depth;
    bool depth_off;
    bool perspective;   /* clip w != 1: the perspective-correct color */
    int threads;
    bool scissor;
} fast_case;

typedef struct line_set {
    int n;              /* vertices */
    float *pos, *color, *normal;
} line_set;

/* Random segments over the framebuffer and past its edges, depths that
 * cross the near and far planes, colors outside [0, 1] (the clamp). */
static line_set make_lines(uint64_t seed, int count, bool perspective)
{
    sr_rng rng = { seed };
    line_set s = { count * 2, malloc(sizeof(float) * 4 * (size_t)count * 2),
                   malloc(sizeof(float) * 4 * (size_t)count * 2),
                   malloc(sizeof(float) * 3 * (size_t)count * 2) };
    for (int i = 0; i < s.n; i++) {
        double x = sr_rng_range(&rng, -40, FW + 40), y = sr_rng_range(&rng, -40, FH + 40);
        if (i % 2 && sr_rng_int(&rng, 0, 3)) {
            /* Mostly 10-200 px from its start, like the bench scene. */
            double len = sr_rng_range(&rng, 0.5, 200), a = sr_rng_range(&rng, 0, 2 * M_PI);
            x = s.pos[(i - 1) * 4 + 0] + len * cos(a);
            y = s.pos[(i - 1) * 4 + 1] + len * sin(a);
        }
        double w = perspective ? sr_rng_range(&rng, 0.5, 2.0) : 1.0;
        float *p = &s.pos[i * 4];
        p[0] = (float)x; /* window coordinates for now, see below */
        p[1] = (float)y;
        p[2] = (float)(sr_rng_range(&rng, -1.1, 1.1) * w);
        p[3] = (float)w;
        for (int k = 0; k < 4; k++) {
            s.color[i * 4 + k] = (float)sr_rng_range(&rng, -0.2, 1.2);
        }
        for (int k = 0; k < 3; k++) {
            s.normal[i * 3 + k] = (float)sr_rng_range(&rng, -1, 1);
        }
    }
    for (int i = 0; i < s.n; i++) {
        float *p = &s.pos[i * 4];
        p[0] = (float)((p[0] / (FW * 0.5) - 1.0) * p[3]);
        p[1] = (float)((1.0 - p[1] / (FH * 0.5)) * p[3]);
    }
    return s;
}

static void free_lines(line_set *s)
{
    free(s->pos);
    free(s->color);
    free(s->normal);
}

/* Draw the set with case c, the generic path forced or not, and read back
 * color and depth. */
static void render_case(const fast_case *c, const line_set *s, bool generic, uint8_t *rgba,
                        float *depth)
{
    sr_context *ctx;
    sr_framebuffer *fb;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = c->threads }, &ctx) == SR_OK);
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = FW, .height = FH,
                                                            .depth_format = c->depth },
                                &fb) == SR_OK);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.1f, 0.2f, 0.3f, 0.4f }, .depth = 1 });
    sr_state st = {
        .shading = c->shading,
        .depth_test = c->depth_off ? SR_OFF : SR_ON,
        .depth_write = c->depth_off ? SR_OFF : SR_ON,
        .ambient = { 0.3f, 0.3f, 0.3f },
        .lights = { { .type = SR_LIGHT_DIRECTIONAL, .vector = { 0.3f, -0.5f, -1 } } },
        .material = { .diffuse = { 0.9f, 0.7f, 0.5f } },
    };
    if (c->scissor) {
        st.scissor = (sr_scissor){ .enabled = true, .x = 37, .y = 29, .width = 300, .height = 150 };
    }
    if (generic) {
        st.blend = blend_replace;
    }
    sr_draw_desc d = { .primitive = SR_PRIM_LINES, .vertex_count = (size_t)s->n,
                       .positions = s->pos, .position_size = 4, .colors = s->color,
                       .color_size = 4 };
    if (c->shading == SR_SHADING_GOURAUD || c->shading == SR_SHADING_FLAT) {
        d.normals = s->normal;
    }
    REQUIRE(sr_draw(ctx, fb, &st, &d) == SR_OK);
    REQUIRE(sr_read_pixels(ctx, fb, 0, 0, FW, FH, rgba, FW * 4) == SR_OK);
    if (c->depth != SR_DEPTH_NONE) {
        REQUIRE(sr_read_depth(ctx, fb, 0, 0, FW, FH, depth, FW) == SR_OK);
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(fast_line_path_matches_the_generic_path)
{
    static const fast_case cases[] = {
        { "unlit, no depth", SR_SHADING_UNLIT, SR_DEPTH_NONE, true, false, 1, false },
        { "unlit, depth off", SR_SHADING_UNLIT, SR_DEPTH_D24, true, false, 2, false },
        { "unlit, D24 LESS", SR_SHADING_UNLIT, SR_DEPTH_D24, false, false, 3, false },
        { "unlit, D16 LESS, w", SR_SHADING_UNLIT, SR_DEPTH_D16, false, true, 2, false },
        { "unlit, D32F LESS", SR_SHADING_UNLIT, SR_DEPTH_D32F, false, false, 1, true },
        { "unlit, w, scissor", SR_SHADING_UNLIT, SR_DEPTH_NONE, true, true, 3, true },
        { "gouraud, D24 LESS, w", SR_SHADING_GOURAUD, SR_DEPTH_D24, false, true, 2, false },
        { "flat, D24 LESS", SR_SHADING_FLAT, SR_DEPTH_D24, false, false, 2, false },
        { "flat, w, no depth", SR_SHADING_FLAT, SR_DEPTH_NONE, true, true, 1, true },
    };
    size_t px = (size_t)FW * FH;
    uint8_t *fast = malloc(px * 4), *ref = malloc(px * 4);
    float *zfast = malloc(px * sizeof(float)), *zref = malloc(px * sizeof(float));
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const fast_case *c = &cases[i];
        line_set s = make_lines(0xfa57 + i, 3000, c->perspective);
        memset(zfast, 0, px * sizeof(float));
        memset(zref, 0, px * sizeof(float));
        render_case(c, &s, false, fast, zfast);
        render_case(c, &s, true, ref, zref);
        long drawn = 0, differ = 0;
        for (size_t k = 0; k < px; k++) {
            drawn += memcmp(&fast[k * 4], (const uint8_t[]){ 26, 51, 77, 102 }, 4) != 0;
            differ += memcmp(&fast[k * 4], &ref[k * 4], 4) != 0 || zfast[k] != zref[k];
        }
        if (differ) {
            sr_test_fail(__FILE__, __LINE__, "%s: %ld pixels differ", c->name, differ);
        }
        CHECK(drawn > 20000); /* the lines were drawn */
        free_lines(&s);
    }
    free(fast);
    free(ref);
    free(zfast);
    free(zref);
}

/* ---- binning and column ranges against the closed form ---- */

static bool owner(int64_t x, int64_t y, bool xmaj, int64_t *qx, int64_t *qy)
{
    int64_t fx = x >> 8, fy = y >> 8;
    for (int64_t j = fy - 1; j <= fy + 1; j++) {
        for (int64_t i = fx - 1; i <= fx + 1; i++) {
            if (lr_diamond_owns(x, y, i, j, xmaj)) {
                *qx = i;
                *qy = j;
                return true;
            }
        }
    }
    return false;
}

/* One more hit on every pixel of the segment (q8 endpoints), wide lines
 * as GL's (docs/raster-rules.md §7.2): the segment moved by -(width - 1)/2 along
 * the minor axis, and a run of `width` toward +minor from each pixel of
 * it: the columns' pixels plus the start's diamond pixel minus the end's,
 * each with its run, clipped to the rectangle [x0, x1) x [y0, y1). */
static void ref_hits(int64_t ax, int64_t ay, int64_t bx, int64_t by, int width, const int clip[4],
                     uint8_t *hits)
{
    if (ax == bx && ay == by) {
        return;
    }
    bool xmaj = llabs(bx - ax) >= llabs(by - ay);
    int64_t shift = (int64_t)(width - 1) * 128;
    if (xmaj) {
        ay -= shift;
        by -= shift;
    } else {
        ax -= shift;
        bx -= shift;
    }
    int64_t au = xmaj ? ax : ay, av = xmaj ? ay : ax, bu = xmaj ? bx : by, bv = xmaj ? by : bx;
    int64_t lo = au < bu ? au : bu, hi = au < bu ? bu : au;
    enum { MAXP = 4096 };
    static int64_t pu[MAXP], pv[MAXP];
    int np = 0;
    for (int64_t k = (lo >> 8) - 1; k <= (hi >> 8) + 1; k++) {
        int64_t c = k * 256 + 128;
        if (c < lo || c > hi) {
            continue;
        }
        pu[np] = k;
        pv[np++] = lr_column_pixel(au, av, bu, bv, c);
    }
    int64_t sx, sy, ex, ey;
    bool start = owner(ax, ay, xmaj, &sx, &sy), end = owner(bx, by, xmaj, &ex, &ey);
    if (start) {
        bool on_path = false;
        for (int i = 0; i < np; i++) {
            on_path |= pu[i] == (xmaj ? sx : sy) && pv[i] == (xmaj ? sy : sx);
        }
        if (!on_path) {
            pu[np] = xmaj ? sx : sy;
            pv[np++] = xmaj ? sy : sx;
        }
    }
    for (int i = 0; i < np; i++) {
        int64_t x = xmaj ? pu[i] : pv[i], y = xmaj ? pv[i] : pu[i];
        if (end && x == ex && y == ey) {
            continue; /* half-open */
        }
        for (int o = 0; o < width; o++) {
            int64_t qx = xmaj ? x : x + o, qy = xmaj ? y + o : y;
            if (qx >= clip[0] && qx < clip[1] && qy >= clip[2] && qy < clip[3]) {
                hits[qy * FW + qx]++;
            }
        }
    }
}

/* Endpoints on the 1/256 grid (exact through the NDC mapping), inside and
 * past the framebuffer, from a point to long diagonals that cross many
 * tile borders; some on pixel centres and pixel edges. */
static void random_segment(sr_rng *rng, double xy[4])
{
    int kind = sr_rng_int(rng, 0, 3);
    for (int k = 0; k < 2; k++) {
        double x, y;
        if (kind == 3) {
            x = sr_rng_int(rng, -4, FW + 4) + (sr_rng_int(rng, 0, 1) ? 0.0 : 0.5);
            y = sr_rng_int(rng, -4, FH + 4) + (sr_rng_int(rng, 0, 1) ? 0.0 : 0.5);
        } else {
            x = q8r(rng, -30, FW + 30);
            y = q8r(rng, -30, FH + 30);
        }
        if (k == 1 && kind == 1) {
            /* Short: within a few pixels of the start, near a tile corner. */
            x = xy[0] + q8r(rng, -6, 6);
            y = xy[1] + q8r(rng, -6, 6);
        }
        xy[k * 2] = x;
        xy[k * 2 + 1] = y;
    }
    if (kind == 1) {
        /* Move the short segment onto a tile corner. */
        enum { T = SR_TILE_SIZE };
        double cx = T * sr_rng_int(rng, 1, FW / T - 1) - xy[0] + q8r(rng, -2, 2);
        double cy = T * sr_rng_int(rng, 1, FH / T - 1) - xy[1] + q8r(rng, -2, 2);
        for (int k = 0; k < 2; k++) {
            xy[k * 2] += cx;
            xy[k * 2 + 1] += cy;
        }
    }
}

static void draw_segments(rt_target *t, const double *xy, int nseg, int width, bool count,
                          const int clip[4])
{
    float *pos = malloc(sizeof(float) * 3 * 2 * (size_t)nseg);
    for (int i = 0; i < nseg * 2; i++) {
        pos[i * 3 + 0] = rt_ndc_x(t, xy[i * 2 + 0]);
        pos[i * 3 + 1] = rt_ndc_y(t, xy[i * 2 + 1]);
        pos[i * 3 + 2] = 0.0f;
    }
    /* Counting: each line adds 1/255 (generic path); else white, the fast
     * path when one pixel wide. */
    float v = count ? 1.0f / 255.0f : 1.0f;
    sr_state st = { .shading = SR_SHADING_UNLIT, .line_width = (float)width,
                    .material = { .diffuse = { v, v, v }, .vertex_color = SR_OFF } };
    if (count) {
        st.blend = (sr_blend){ .enabled = true, .src_rgb = SR_BLEND_ONE, .dst_rgb = SR_BLEND_ONE,
                               .src_alpha = SR_BLEND_ONE, .dst_alpha = SR_BLEND_ONE };
    }
    if (clip[0] != 0 || clip[1] != FW || clip[2] != 0 || clip[3] != FH) {
        st.scissor = (sr_scissor){ .enabled = true, .x = clip[0], .y = clip[2],
                                   .width = clip[1] - clip[0], .height = clip[3] - clip[2] };
    }
    REQUIRE(sr_draw(t->ctx, t->fb, &st,
                    &(sr_draw_desc){ .primitive = SR_PRIM_LINES, .positions = pos,
                                     .vertex_count = (size_t)nseg * 2 }) == SR_OK);
    free(pos);
}

SR_TEST(line_binning_reaches_every_pixel)
{
    static const int clips[2][4] = { { 0, FW, 0, FH }, { 45, 397, 13, 230 } };
    size_t px = (size_t)FW * FH;
    uint8_t *want = malloc(px), *got = malloc(px);
    enum { SINGLE = 120, BATCH = 1500 };
    double *xy = malloc(sizeof(double) * 4 * BATCH);
    long bad_single = 0, bad_batch = 0;
    for (int threads = 1; threads <= 3; threads++) {
        rt_target t = rt_make(FW, FH, threads);
        for (int width = 1; width <= 4; width++) {
            for (int ci = 0; ci < 2; ci++) {
                const int *clip = clips[ci];
                sr_rng rng = { 0xb1 + (uint64_t)(threads * 16 + width * 4 + ci) };
                /* One segment per draw, compared as a mask. */
                for (int i = 0; i < SINGLE; i++) {
                    random_segment(&rng, xy);
                    rt_clear(&t);
                    draw_segments(&t, xy, 1, width, false, clip);
                    rt_mask(&t, got);
                    memset(want, 0, px);
                    ref_hits((int64_t)(xy[0] * 256), (int64_t)(xy[1] * 256),
                             (int64_t)(xy[2] * 256), (int64_t)(xy[3] * 256), width, clip, want);
                    for (size_t k = 0; k < px; k++) {
                        want[k] = want[k] != 0;
                    }
                    bad_single += memcmp(got, want, px) != 0;
                }
                /* Many segments in one draw (a chunk per front-end job,
                 * so bins merge across chunks), counted: no pixel
                 * missed, none drawn twice. */
                for (int i = 0; i < BATCH; i++) {
                    random_segment(&rng, &xy[i * 4]);
                }
                rt_clear(&t);
                draw_segments(&t, xy, BATCH, width, true, clip);
                const uint8_t *rgba = sr_framebuffer_pixels(t.fb);
                memset(want, 0, px);
                for (int i = 0; i < BATCH; i++) {
                    const double *s = &xy[i * 4];
                    ref_hits((int64_t)(s[0] * 256), (int64_t)(s[1] * 256), (int64_t)(s[2] * 256),
                             (int64_t)(s[3] * 256), width, clip, want);
                }
                for (size_t k = 0; k < px; k++) {
                    got[k] = rgba[k * 4];
                }
                bad_batch += memcmp(got, want, px) != 0;
            }
        }
        rt_free(&t);
    }
    CHECK_EQ(bad_single, 0);
    CHECK_EQ(bad_batch, 0);
    free(want);
    free(got);
    free(xy);
}
