/* test_index_range.c - an indexed draw with fewer indices than vertices
 * shades only the range its indices span (sr_draw_info.vertices_shaded):
 * 3 indices out of 100,000 vertices shade 3; and draws of subranges of a
 * large random array give the same pixels as the same draws of compacted
 * copies of the vertices they use (each shading, list and strip, lines,
 * 8-, 16- and 32-bit indices, interleaved arrays), for 1, 2 and 3 threads;
 * an index past the array in such a draw is still named.  Fixed seeds. */
#include "sr_test.h"
#include "softrast.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { W = 64, H = 48 };

static uint32_t next(uint64_t *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (uint32_t)(*s >> 33);
}

static float uni(uint64_t *s, float lo, float hi)
{
    return lo + (hi - lo) * (float)next(s) / 2147483648.0f;
}

/* Vertices interleaved: position 3, normal 3, color 4, texcoord 2. */
enum { STRIDE = 12 };

static float *random_vertices(size_t n, uint64_t *seed)
{
    float *v = malloc(n * STRIDE * sizeof *v);
    if (!v) {
        return NULL;
    }
    for (size_t i = 0; i < n; i++) {
        float *p = v + i * STRIDE;
        for (int k = 0; k < 3; k++) {
            p[k] = uni(seed, -1.2f, 1.2f);       /* some outside: clipped */
            p[3 + k] = uni(seed, -1.0f, 1.0f);
        }
        p[2] = uni(seed, -0.9f, 0.9f);
        for (int k = 0; k < 4; k++) {
            p[6 + k] = uni(seed, 0.0f, 1.0f);
        }
        p[10] = uni(seed, 0.0f, 1.0f);
        p[11] = uni(seed, 0.0f, 1.0f);
    }
    return v;
}

static sr_draw_desc vertices_desc(const float *v, size_t n)
{
    size_t stride = STRIDE * sizeof(float);
    return (sr_draw_desc){ .vertex_count = n, .positions = v, .position_stride = stride,
                           .normals = v + 3, .normal_stride = stride, .colors = v + 6,
                           .color_stride = stride, .texcoords = v + 10,
                           .texcoord_stride = stride, .generic = v + 6, .generic_size = 3,
                           .generic_stride = stride };
}

/* n random vertices, a two-thread context and a framebuffer of it. */
typedef struct fixture {
    float *v;
    sr_context *ctx;
    sr_framebuffer *fb;
} fixture;

static bool fixture_make(fixture *f, size_t n, uint64_t seed)
{
    *f = (fixture){ random_vertices(n, &seed), NULL, NULL };
    return f->v && sr_make_context(&(sr_context_desc){ .threads = 2 }, &f->ctx) == SR_OK &&
           sr_make_framebuffer(f->ctx, &(sr_framebuffer_desc){ .width = W, .height = H },
                               &f->fb) == SR_OK;
}

static void fixture_free(fixture *f)
{
    sr_destroy_framebuffer(f->ctx, f->fb);
    sr_destroy_context(f->ctx);
    free(f->v);
}

SR_TEST(three_indices_of_a_hundred_thousand_vertices_shade_three)
{
    enum { N = 100000 };
    fixture f;
    REQUIRE(fixture_make(&f, N, 20261128));
    sr_context *ctx = f.ctx;
    sr_framebuffer *fb = f.fb;
    const uint32_t ix[3] = { 61234, 61236, 61235 };
    sr_draw_desc d = vertices_desc(f.v, N);
    d.indices = ix;
    d.index_type = SR_INDEX_U32;
    d.index_count = 3;
    for (int s = 0; s < 2; s++) {
        sr_state st = { .shading = s ? SR_SHADING_GOURAUD : SR_SHADING_UNLIT };
        CHECK_EQ(sr_draw(ctx, fb, &st, &d), SR_OK);
        CHECK_EQ(sr_last_draw_info(ctx).vertices_shaded, 3);
        CHECK_EQ(sr_last_draw_info(ctx).triangles_in, 1);
    }
    /* A whole mesh (more indices than vertices) shades its array once. */
    uint32_t *all = malloc(3 * N * sizeof *all);
    REQUIRE(all);
    for (size_t i = 0; i < 3 * (size_t)N; i++) {
        all[i] = (uint32_t)((i * 7919u) % N);
    }
    d.indices = all;
    d.index_count = 3 * (size_t)N;
    CHECK_EQ(sr_draw(ctx, fb, &(sr_state){ 0 }, &d), SR_OK);
    CHECK_EQ(sr_last_draw_info(ctx).vertices_shaded, N);
    free(all);
    /* Without indices, a list shades its vertices once. */
    d.indices = NULL;
    d.index_type = SR_INDEX_NONE;
    d.index_count = 0;
    d.vertex_count = 300;
    CHECK_EQ(sr_draw(ctx, fb, &(sr_state){ 0 }, &d), SR_OK);
    CHECK_EQ(sr_last_draw_info(ctx).vertices_shaded, 300);
    fixture_free(&f);
}

SR_TEST(an_index_past_the_array_in_a_short_list_is_named)
{
    enum { N = 1000 };
    fixture f;
    REQUIRE(fixture_make(&f, N, 7));
    sr_context *ctx = f.ctx;
    sr_framebuffer *fb = f.fb;
    uint16_t ix[6] = { 5, 6, 7, 8, 9, 10 };
    sr_draw_desc d = vertices_desc(f.v, N);
    d.indices = ix;
    d.index_type = SR_INDEX_U16;
    d.index_count = 6;
    ix[4] = N;
    CHECK_EQ(sr_draw(ctx, fb, &(sr_state){ 0 }, &d), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "indices[4] = 1000");
    CHECK_EQ(sr_last_draw_info(ctx).vertices_shaded, 0);
    ix[4] = N - 1;
    CHECK_EQ(sr_draw(ctx, fb, &(sr_state){ 0 }, &d), SR_OK);
    CHECK_EQ(sr_last_draw_info(ctx).vertices_shaded, N - 5);
    fixture_free(&f);
}

static void put(sr_index_type type, void *ix, size_t i, uint32_t value)
{
    switch (type) {
    case SR_INDEX_U8:  ((uint8_t *)ix)[i] = (uint8_t)value; break;
    case SR_INDEX_U16: ((uint16_t *)ix)[i] = (uint16_t)value; break;
    default:           ((uint32_t *)ix)[i] = value; break;
    }
}

/* Clears, draws d under st and copies the color and depth out. */
static void render(sr_context *ctx, const sr_state *st, const sr_draw_desc *d, uint8_t *color,
                   float *depth)
{
    sr_framebuffer *fb;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &fb) ==
            SR_OK);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.1f, 0.1f, 0.1f, 1 }, .depth = 1.0f });
    CHECK_EQ(sr_draw(ctx, fb, st, d), SR_OK);
    memcpy(color, sr_framebuffer_pixels(fb), (size_t)W * H * 4);
    CHECK_EQ(sr_read_depth(ctx, fb, 0, 0, W, H, depth, W), SR_OK);
    sr_destroy_framebuffer(ctx, fb);
}

SR_TEST(subrange_draws_equal_draws_of_compacted_copies)
{
    enum { N = 20000, DRAWS = 48, MAX_INDICES = 600 };
    uint64_t seed = 424242;
    float *v = random_vertices(N, &seed);
    float *packed = malloc(N * STRIDE * sizeof *packed);
    uint32_t *ix = malloc(MAX_INDICES * sizeof *ix);
    uint8_t *a = malloc(W * H * 4), *b = malloc(W * H * 4);
    float *za = malloc(W * H * sizeof *za), *zb = malloc(W * H * sizeof *zb);
    REQUIRE(v && packed && ix && a && b && za && zb);
    static const sr_shading shadings[] = { SR_SHADING_UNLIT, SR_SHADING_GOURAUD,
                                           SR_SHADING_FLAT, SR_SHADING_PHONG,
                                           SR_SHADING_ATTRIBUTE };
    static const sr_primitive prims[] = { SR_PRIM_TRIANGLES, SR_PRIM_TRIANGLE_STRIP,
                                          SR_PRIM_LINES };
    static const sr_index_type types[] = { SR_INDEX_U8, SR_INDEX_U16, SR_INDEX_U32 };
    sr_context *ctx[3];
    for (int t = 0; t < 3; t++) {
        REQUIRE(sr_make_context(&(sr_context_desc){ .threads = t + 1 }, &ctx[t]) == SR_OK);
    }
    sr_mat4 proj = sr_perspective(1.0f, (float)W / H, 0.5f, 10.0f, false);
    sr_mat4 view = sr_mat4_translate(0.0f, 0.0f, -2.5f);
    int drawn = 0;
    for (int k = 0; k < DRAWS; k++) {
        /* A run of at most `span` vertices somewhere in the array (inside
         * what an 8-bit index reaches for U8), used at random. */
        sr_index_type type = types[k % 3];
        size_t span = 8 + next(&seed) % (type == SR_INDEX_U8 ? 240 : 400);
        size_t limit = type == SR_INDEX_U8 ? 256 : type == SR_INDEX_U16 ? 65536 : N;
        limit = limit < N ? limit : N;
        size_t lo = next(&seed) % (limit - span);
        size_t count = 3 * (1 + next(&seed) % (MAX_INDICES / 3));
        for (size_t i = 0; i < count; i++) {
            ix[i] = (uint32_t)(lo + next(&seed) % span);
        }
        /* The compacted copy: the vertices of [min, max] moved to 0. */
        uint32_t mn = ix[0], mx = ix[0];
        for (size_t i = 1; i < count; i++) {
            mn = ix[i] < mn ? ix[i] : mn;
            mx = ix[i] > mx ? ix[i] : mx;
        }
        memcpy(packed, v + (size_t)mn * STRIDE, ((size_t)mx - mn + 1) * STRIDE * sizeof(float));
        void *ixa = malloc(count * sizeof(uint32_t)), *ixb = malloc(count * sizeof(uint32_t));
        REQUIRE(ixa && ixb);
        for (size_t i = 0; i < count; i++) {
            put(type, ixa, i, ix[i]);
            put(type, ixb, i, ix[i] - mn);
        }
        sr_draw_desc whole = vertices_desc(v, N);
        sr_draw_desc part = vertices_desc(packed, (size_t)mx - mn + 1);
        whole.primitive = part.primitive = prims[k % 3 == 0 ? (k / 3) % 3 : 0];
        whole.indices = ixa;
        part.indices = ixb;
        whole.index_type = part.index_type = type;
        whole.index_count = part.index_count = count;
        whole.projection = part.projection = &proj;
        whole.view = part.view = &view;
        sr_state st = { .shading = shadings[k % 5], .cull = SR_CULL_NONE,
                        .two_sided = k % 2 == 1, .depth_test = SR_ON };
        uint8_t first[W * H * 4];
        for (int t = 0; t < 3; t++) {
            render(ctx[t], &st, &part, b, zb);
            render(ctx[t], &st, &whole, a, za);
            CHECK_EQ(sr_last_draw_info(ctx[t]).vertices_shaded, mx - mn + 1);
            if (memcmp(a, b, (size_t)W * H * 4) != 0 ||
                memcmp(za, zb, (size_t)W * H * sizeof *za) != 0) {
                sr_test_fail(__FILE__, __LINE__,
                             "draw %d (%zu indices of [%u, %u], shading %d, type %d, "
                             "%d threads): the subrange and its copy differ",
                             k, count, mn, mx, (int)st.shading, (int)type, t + 1);
            }
            if (t == 0) {
                memcpy(first, a, sizeof first);
            } else if (memcmp(first, a, sizeof first) != 0) {
                sr_test_fail(__FILE__, __LINE__, "draw %d: %d threads differ from one", k,
                             t + 1);
            }
        }
        /* Something was drawn, so the comparison saw pixels. */
        for (size_t i = 0; i < (size_t)W * H * 4; i += 4) {
            if (memcmp(a + i, "\x1a\x1a\x1a", 3) != 0) {
                drawn++;
                break;
            }
        }
        free(ixa);
        free(ixb);
    }
    CHECK(drawn > DRAWS * 3 / 4);
    for (int t = 0; t < 3; t++) {
        sr_destroy_context(ctx[t]);
    }
    free(v);
    free(packed);
    free(ix);
    free(a);
    free(b);
    free(za);
    free(zb);
}
