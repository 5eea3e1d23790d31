/* test_context_env.c - SR_SIMD and SR_THREADS are read once, by
 * sr_make_context, and only for a sr_context_desc field left at 0: a field
 * set overrides the variable, the variable set after the context is made
 * changes nothing, and every draw's kernels follow the context's level. */
#include "sr_test.h"
#include "context.h"
#include "pipeline.h"

#include <stdlib.h>

static sr_simd_level level_of(const sr_context_desc *d)
{
    sr_context *ctx = NULL;
    CHECK_EQ(sr_make_context(d, &ctx), SR_OK);
    sr_simd_level l = ctx ? sr_context_simd(ctx) : SR_SIMD_DEFAULT;
    sr_destroy_context(ctx);
    return l;
}

static sr_simd_level capped(sr_simd_level l, sr_simd_level widest)
{
    return l < widest ? l : widest;
}

/* The widest level this CPU runs: what an AVX-512 request is capped to. */
static sr_simd_level widest_level(void)
{
    unsetenv("SR_SIMD");
    return level_of(&(sr_context_desc){ .threads = 1, .simd = SR_SIMD_AVX512 });
}

SR_TEST(simd_env_var_is_honoured_when_the_field_is_zero)
{
    sr_simd_level widest = widest_level();
    CHECK(widest != SR_SIMD_DEFAULT);
    CHECK_EQ(level_of(&(sr_context_desc){ .threads = 1 }), widest);
    static const struct { const char *env; sr_simd_level level; } cases[] = {
        { "off", SR_SIMD_OFF }, { "base", SR_SIMD_BASE }, { "avx2", SR_SIMD_AVX2 },
        { "avx512", SR_SIMD_AVX512 }, { "no-such-level", SR_SIMD_AVX512 },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        setenv("SR_SIMD", cases[i].env, 1);
        CHECK_EQ(level_of(&(sr_context_desc){ .threads = 1 }), capped(cases[i].level, widest));
    }
    unsetenv("SR_SIMD");
}

SR_TEST(simd_field_overrides_the_env_var)
{
    sr_simd_level widest = widest_level();
    setenv("SR_SIMD", "off", 1);
    for (sr_simd_level l = SR_SIMD_OFF; l <= SR_SIMD_AVX512; l++) {
        CHECK_EQ(level_of(&(sr_context_desc){ .threads = 1, .simd = l }), capped(l, widest));
    }
    setenv("SR_SIMD", "avx512", 1);
    CHECK_EQ(level_of(&(sr_context_desc){ .threads = 1, .simd = SR_SIMD_OFF }), SR_SIMD_OFF);
    unsetenv("SR_SIMD");
}

SR_TEST(simd_field_out_of_range_is_rejected)
{
    sr_context *ctx = NULL;
    CHECK_EQ(sr_make_context(&(sr_context_desc){ .simd = (sr_simd_level)(SR_SIMD_AVX512 + 1) },
                             &ctx),
             SR_INVALID_ARG);
    CHECK(ctx == NULL);
    CHECK_EQ(sr_make_context(&(sr_context_desc){ .simd = (sr_simd_level)-1 }, &ctx),
             SR_INVALID_ARG);
}

/* The level is the context's: setting the variable later changes neither
 * the context's level nor the kernels its draws resolve. */
SR_TEST(simd_env_var_is_read_once_per_context)
{
    sr_simd_level widest = widest_level();
    setenv("SR_SIMD", "off", 1);
    sr_context *off;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &off) == SR_OK);
    unsetenv("SR_SIMD");
    sr_context *wide;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &wide) == SR_OK);
    setenv("SR_SIMD", "off", 1);
    CHECK_EQ(sr_context_simd(off), SR_SIMD_OFF);
    CHECK_EQ(sr_context_simd(wide), widest);

    sr_framebuffer *fb;
    REQUIRE(sr_make_framebuffer(wide, &(sr_framebuffer_desc){ .width = 8, .height = 8 }, &fb) ==
            SR_OK);
    sr_state st = { .shading = SR_SHADING_GOURAUD };
    sr_draw_state ds;
    sr__resolve_draw_state(fb, &st, NULL, NULL, off->simd, &ds);
    CHECK(ds.raster_tri == sr__raster_halfspace_select(&ds));  /* the scalar instance */
    sr__resolve_draw_state(fb, &st, NULL, NULL, wide->simd, &ds);
    CHECK_EQ(ds.raster_tri != sr__raster_halfspace_select(&ds), widest != SR_SIMD_OFF);
    sr_destroy_framebuffer(wide, fb);
    sr_destroy_context(off);
    sr_destroy_context(wide);
    unsetenv("SR_SIMD");
}

SR_TEST(threads_field_overrides_the_env_var)
{
    setenv("SR_THREADS", "3", 1);
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){0}, &ctx) == SR_OK);
    CHECK_EQ(sr_context_threads(ctx), 3);
    sr_destroy_context(ctx);
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 2 }, &ctx) == SR_OK);
    CHECK_EQ(sr_context_threads(ctx), 2);
    sr_destroy_context(ctx);
    unsetenv("SR_THREADS");
}
