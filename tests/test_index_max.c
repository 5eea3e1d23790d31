/* test_index_max.c - geometry/index_max.c, the largest index of a range
 * (the draw's check that every index names a vertex), against one plain
 * loop: each index type, the portable loop and the AVX2 one (where the CPU
 * has it), ranges of every length up to past a few vector steps with
 * every start, the largest value at every place, the type's own maximum
 * (an unsigned compare, not a signed one), and, through sr_draw, an index
 * out of range deep inside a long list; sr__index_range, the smallest
 * and largest together, against plain loops. */
#include "sr_test.h"
#include "pipeline.h"
#include "softrast.h"

#include <stdlib.h>
#include <string.h>

/* The reference: one running maximum. */
static uint32_t plain_max(sr_index_type type, const void *ix, size_t begin, size_t end)
{
    uint32_t m = 0;
    for (size_t i = begin; i < end; i++) {
        uint32_t v = type == SR_INDEX_U8    ? ((const uint8_t *)ix)[i]
                     : type == SR_INDEX_U16 ? ((const uint16_t *)ix)[i]
                                            : ((const uint32_t *)ix)[i];
        m = v > m ? v : m;
    }
    return m;
}

static uint64_t next(uint64_t *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return *s >> 33;
}

static void put(sr_index_type type, void *ix, size_t i, uint32_t v)
{
    switch (type) {
    case SR_INDEX_U8:  ((uint8_t *)ix)[i] = (uint8_t)v; break;
    case SR_INDEX_U16: ((uint16_t *)ix)[i] = (uint16_t)v; break;
    default:           ((uint32_t *)ix)[i] = v; break;
    }
}

static bool have_avx2(void)
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2");
#else
    return false;
#endif
}

enum { N = 300 };   /* past four AVX2 steps of 32-bit indices (128) twice */

SR_TEST(index_max_equals_one_running_maximum)
{
    static const sr_index_type types[] = { SR_INDEX_U8, SR_INDEX_U16, SR_INDEX_U32 };
    static const uint32_t top[] = { 0xffu, 0xffffu, 0xffffffffu };
    bool ways[2] = { false, have_avx2() };
    uint64_t seed = 20261124;
    uint32_t buf[N];
    for (int w = 0; w < (ways[1] ? 2 : 1); w++) {
        for (int k = 0; k < 3; k++) {
            sr_index_type type = types[k];
            /* Random values below the type's maximum, then each place in
             * turn takes a larger one: every start and length sees it. */
            for (size_t i = 0; i < N; i++) {
                put(type, buf, i, (uint32_t)(next(&seed) % (top[k] / 2)));
            }
            for (size_t begin = 0; begin < 40; begin++) {
                for (size_t end = begin; end <= N; end++) {
                    uint32_t want = plain_max(type, buf, begin, end);
                    uint32_t got = sr__index_max(type, buf, begin, end, ways[w]);
                    if (got != want) {
                        sr_test_fail(__FILE__, __LINE__,
                                     "type %d avx2 %d [%zu, %zu): %u, want %u", (int)type, w,
                                     begin, end, got, want);
                        return;
                    }
                }
            }
            uint32_t saved[N];
            memcpy(saved, buf, sizeof buf);
            for (size_t at = 0; at < N; at++) {
                for (int big = 0; big < 2; big++) {
                    memcpy(buf, saved, sizeof buf);
                    uint32_t v = big ? top[k] : top[k] / 2 + (uint32_t)at % 7;
                    put(type, buf, at, v);
                    CHECK_EQ(sr__index_max(type, buf, 0, N, ways[w]), v);
                    CHECK_EQ(sr__index_max(type, buf, at, at + 1, ways[w]), v);
                    /* A range that stops just short of it does not see it. */
                    CHECK_EQ(sr__index_max(type, buf, 0, at, ways[w]), plain_max(type, buf, 0, at));
                }
            }
            memcpy(buf, saved, sizeof buf);
        }
        CHECK_EQ(sr__index_max(SR_INDEX_NONE, buf, 0, N, ways[w]), 0);
    }
}

/* Through sr_draw: a list of 1,500 indices with one out of range at each
 * of a few places, the vector loop's body and its tail included, is
 * refused with that place named; in range, the draw goes ahead. */
SR_TEST(an_index_out_of_range_deep_in_a_long_list_is_named)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 2 }, &ctx) == SR_OK);
    sr_framebuffer *fb;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 32, .height = 32 }, &fb) ==
            SR_OK);
    const float pos[9] = { -1, -1, 0, 1, -1, 0, 0, 1, 0 };
    enum { COUNT = 1500 };
    uint32_t *ix32 = malloc(COUNT * sizeof *ix32);
    uint16_t *ix16 = malloc(COUNT * sizeof *ix16);
    REQUIRE(ix32 && ix16);
    static const size_t places[] = { 0, 31, 32, 777, 1497, 1499 };
    for (size_t p = 0; p < sizeof places / sizeof places[0]; p++) {
        for (int wide = 0; wide < 2; wide++) {
            for (size_t i = 0; i < COUNT; i++) {
                ix32[i] = (uint32_t)(i % 3);
                ix16[i] = (uint16_t)(i % 3);
            }
            if (wide) {
                ix32[places[p]] = 3;
            } else {
                ix16[places[p]] = 3;
            }
            sr_draw_desc d = { .positions = pos, .vertex_count = 3,
                               .indices = wide ? (const void *)ix32 : (const void *)ix16,
                               .index_type = wide ? SR_INDEX_U32 : SR_INDEX_U16,
                               .index_count = COUNT };
            sr_state st = { .material = { .diffuse = { 1, 0, 0 } } };
            CHECK_EQ(sr_draw(ctx, fb, &st, &d), SR_INVALID_ARG);
            char want[64];
            snprintf(want, sizeof want, "indices[%zu] = 3", places[p]);
            CHECK_STR_CONTAINS(sr_context_error(ctx), want);
            if (wide) {
                ix32[places[p]] = 2;
            } else {
                ix16[places[p]] = 2;
            }
            CHECK_EQ(sr_draw(ctx, fb, &st, &d), SR_OK);
        }
    }
    free(ix32);
    free(ix16);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

/* sr__index_range, the smallest and largest together, against plain
 * loops: each type, every length up to N, the extremes at every place. */
SR_TEST(index_range_equals_plain_minimum_and_maximum)
{
    static const sr_index_type types[] = { SR_INDEX_U8, SR_INDEX_U16, SR_INDEX_U32 };
    static const uint32_t top[] = { 0xffu, 0xffffu, 0xffffffffu };
    uint64_t seed = 20261128;
    uint32_t buf[N];
    for (int k = 0; k < 3; k++) {
        for (size_t i = 0; i < N; i++) {
            put(types[k], buf, i, 1 + (uint32_t)(next(&seed) % (top[k] - 1)));
        }
        for (size_t count = 0; count <= N; count++) {
            uint32_t lo, hi, want_lo = count ? top[k] : 0;
            for (size_t i = 0; i < count; i++) {
                uint32_t v = types[k] == SR_INDEX_U8    ? ((const uint8_t *)buf)[i]
                             : types[k] == SR_INDEX_U16 ? ((const uint16_t *)buf)[i]
                                                        : buf[i];
                want_lo = v < want_lo ? v : want_lo;
            }
            sr__index_range(types[k], buf, count, &lo, &hi);
            CHECK_EQ(lo, want_lo);
            CHECK_EQ(hi, plain_max(types[k], buf, 0, count));
        }
        for (size_t at = 0; at < N; at += 13) {
            uint32_t saved = types[k] == SR_INDEX_U32 ? buf[at] : 0;
            uint32_t lo, hi;
            put(types[k], buf, at, 0);
            sr__index_range(types[k], buf, N, &lo, &hi);
            CHECK_EQ(lo, 0);
            put(types[k], buf, at, top[k]);
            sr__index_range(types[k], buf, N, &lo, &hi);
            CHECK_EQ(hi, top[k]);
            put(types[k], buf, at, saved ? saved : 1);
        }
    }
}
