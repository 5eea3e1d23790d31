/* test_depth.c - the depth buffer: the eight compare functions and
 * depth_write = SR_OFF, quantization for D16/D24/D32/D32F against integer math,
 * sr_read_depth, the depth range and depth_zero_to_one, and polygon offset
 * (z-fighting without it, a deterministic winner with it, units as exactly
 * one step, the slope term and the clamp).  Fixed seeds. */
#define _DEFAULT_SOURCE /* MAP_ANONYMOUS, for guard_alloc.h */
#include "guard_alloc.h"
#include "sr_test.h"
#include "softrast.h"
#include "fragment/depth.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const sr_depth_format formats[] = { SR_DEPTH_D16, SR_DEPTH_D24, SR_DEPTH_D32, SR_DEPTH_D32F };
static const int format_bits[] = { 16, 24, 32, 0 };
static const char *format_names[] = { "D16", "D24", "D32", "D32F" };

typedef struct target {
    sr_context *ctx;
    sr_framebuffer *fb;
    int w, h, bits;
} target;

static target target_make(int w, int h, int fi)
{
    target t = { NULL, NULL, w, h, format_bits[fi] };
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &t.ctx);
    sr_make_framebuffer(t.ctx, &(sr_framebuffer_desc){ .width = w, .height = h,
                                                      .depth_format = formats[fi] }, &t.fb);
    return t;
}

static void target_free(target *t)
{
    sr_destroy_framebuffer(t->ctx, t->fb);
    sr_destroy_context(t->ctx);
}

static void target_clear(target *t, float depth)
{
    sr_clear(t->ctx, t->fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 },
                                             .depth_action = SR_ACTION_CLEAR, .depth = depth });
}

/* A full-screen quad with z_ndc = z0 + zx x_ndc + zy y_ndc, in one color. */
static sr_result draw_quad(target *t, const sr_state *st, double z0, double zx, double zy,
                           const float rgb[3])
{
    const float c[4][2] = { { -1, -1 }, { 1, -1 }, { 1, 1 }, { -1, 1 } };
    const int idx[6] = { 0, 1, 2, 0, 2, 3 };
    float pos[18], col[24];
    for (int i = 0; i < 6; i++) {
        const float *p = c[idx[i]];
        pos[i * 3 + 0] = p[0];
        pos[i * 3 + 1] = p[1];
        pos[i * 3 + 2] = (float)(z0 + zx * p[0] + zy * p[1]);
        col[i * 4 + 0] = rgb[0];
        col[i * 4 + 1] = rgb[1];
        col[i * 4 + 2] = rgb[2];
        col[i * 4 + 3] = 1;
    }
    return sr_draw(t->ctx, t->fb, st, &(sr_draw_desc){ .positions = pos, .vertex_count = 6,
                                                      .colors = col });
}

static const float WHITE[3] = { 1, 1, 1 };
static const float RED[3] = { 1, 0, 0 };
static const float GREEN[3] = { 0, 1, 0 };

static int count_color(const target *t, const float rgb[3])
{
    const uint8_t *px = sr_framebuffer_pixels(t->fb);
    int n = 0;
    for (int i = 0; i < t->w * t->h; i++) {
        n += px[i * 4] == (rgb[0] > 0 ? 255 : 0) && px[i * 4 + 1] == (rgb[1] > 0 ? 255 : 0) &&
             px[i * 4 + 2] == (rgb[2] > 0 ? 255 : 0);
    }
    return n;
}

/* The float sr_read_depth must return for quantized value q. */
static float dq(uint32_t q, int bits) { return (float)sr__depth_dequantize(q, bits); }

static bool ref_pass(sr_depth_func f, uint32_t in, uint32_t stored)
{
    switch (f) {
    case SR_NEVER:    return false;
    case SR_LESS:     return in < stored;
    case SR_EQUAL:    return in == stored;
    case SR_LEQUAL:   return in <= stored;
    case SR_GREATER:  return in > stored;
    case SR_NOTEQUAL: return in != stored;
    case SR_GEQUAL:   return in >= stored;
    case SR_ALWAYS:   return true;
    default:          return false;
    }
}

/* ---- compare functions --------------------------------------------------- */

SR_TEST(each_depth_function_passes_and_writes_as_specified)
{
    const double zw[3] = { 0.25, 0.5, 0.75 };   /* less, equal, greater than 0.5 */
    for (int fi = 0; fi < 4; fi++) {
        target t = target_make(16, 16, fi);
        uint32_t stored = sr__depth_quantize(0.5, t.bits);
        for (int f = SR_NEVER; f <= SR_ALWAYS; f++) {
            for (int k = 0; k < 3; k++) {
                for (int nowrite = 0; nowrite <= 1; nowrite++) {
                    target_clear(&t, 0.5f);
                    sr_state st = { .depth_func = (sr_depth_func)f, .depth_write = nowrite ? SR_OFF : SR_ON };
                    REQUIRE(draw_quad(&t, &st, 2 * zw[k] - 1, 0, 0, WHITE) == SR_OK);
                    uint32_t in = sr__depth_quantize(zw[k], t.bits);
                    bool pass = ref_pass((sr_depth_func)f, in, stored);
                    CHECK_EQ(count_color(&t, WHITE), pass ? 256 : 0);
                    CHECK_EQ(sr_last_draw_info(t.ctx).fragments, pass ? 256 : 0);
                    float d[256];
                    REQUIRE(sr_read_depth(t.ctx, t.fb, 0, 0, 16, 16, d, 16) == SR_OK);
                    float want = dq(pass && !nowrite ? in : stored, t.bits);
                    int bad = 0;
                    for (int i = 0; i < 256; i++) {
                        bad += d[i] != want;
                    }
                    if (bad) {
                        fprintf(stderr, "%s func %d z %g nowrite %d\n", format_names[fi], f, zw[k], nowrite);
                    }
                    CHECK_EQ(bad, 0);
                }
            }
        }
        target_free(&t);
    }
}

/* A slanted quad, z from 0.25 (left edge) to 0.75 (right edge), over 0.5:
 * LESS passes exactly on the left half, GREATER on the right half. */
SR_TEST(depth_test_is_per_pixel_on_a_slanted_quad)
{
    for (int fi = 0; fi < 4; fi++) {
        target t = target_make(16, 8, fi);
        const sr_depth_func funcs[] = { SR_LESS, SR_GREATER, SR_LEQUAL, SR_GEQUAL };
        for (int k = 0; k < 4; k++) {
            target_clear(&t, 0.5f);
            sr_state st = { .depth_func = funcs[k] };
            REQUIRE(draw_quad(&t, &st, 0.0, 0.5, 0.0, WHITE) == SR_OK);
            const uint8_t *px = sr_framebuffer_pixels(t.fb);
            int bad = 0;
            for (int y = 0; y < 8; y++) {
                for (int x = 0; x < 16; x++) {
                    bool left = x < 8;  /* z(x) = 0.25 + (x + 0.5)/32 never equals 0.5 */
                    bool want = (funcs[k] == SR_LESS || funcs[k] == SR_LEQUAL) ? left : !left;
                    bad += (px[(y * 16 + x) * 4] == 255) != want;
                }
            }
            CHECK_EQ(bad, 0);
        }
        target_free(&t);
    }
}

SR_TEST(depth_test_off_draws_everything_even_with_never)
{
    target t = target_make(8, 8, 1);
    target_clear(&t, 0.0f);
    sr_state st = { .depth_test = SR_OFF, .depth_func = SR_NEVER };
    REQUIRE(draw_quad(&t, &st, 0.5, 0, 0, WHITE) == SR_OK);
    CHECK_EQ(count_color(&t, WHITE), 64);
    target_free(&t);
    /* Without a depth buffer there is no test at all. */
    sr_context *ctx;
    sr_framebuffer *fb;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 8, .height = 8,
                                                            .depth_format = SR_DEPTH_NONE }, &fb) == SR_OK);
    target n = { ctx, fb, 8, 8, 0 };
    sr_state never = { .depth_func = SR_NEVER };
    REQUIRE(draw_quad(&n, &never, 0.5, 0, 0, WHITE) == SR_OK);
    CHECK_EQ(count_color(&n, WHITE), 64);
    float d;
    CHECK_EQ(sr_read_depth(ctx, fb, 0, 0, 1, 1, &d, 1), SR_INVALID_ARG);
    target_free(&n);
}

/* ---- quantization ------------------------------------------------------- */

/* floor(k (2^n - 1) / 2^m + 1/2) in integers: (2 k M + 2^m) >> (m + 1). */
static uint32_t int_quantize(uint64_t k, int m, int n)
{
    uint64_t M = (n == 32) ? 0xffffffffull : ((1ull << n) - 1);
    return (uint32_t)((2 * k * M + (1ull << m)) >> (m + 1));
}

SR_TEST(quantize_matches_integer_math_on_exact_binary_fractions)
{
    sr_rng rng = { 0xd3b7 };
    const int ns[3] = { 16, 24, 32 };
    for (int i = 0; i < 3; i++) {
        int n = ns[i];
        uint64_t M = (n == 32) ? 0xffffffffull : ((1ull << n) - 1);
        /* m <= 21 keeps k M < 2^53: z M is then exact in double. */
        for (int m = 0; m <= 21; m++) {
            for (int it = 0; it < 300; it++) {
                uint64_t k = m == 0 ? (uint64_t)(it & 1) : sr_rng_next(&rng) % ((1ull << m) + 1);
                double z = ldexp((double)k, -m);
                CHECK_EQ(sr__depth_quantize(z, n), int_quantize(k, m, n));
            }
        }
        CHECK_EQ(sr__depth_quantize(0.0, n), 0);
        CHECK_EQ(sr__depth_quantize(1.0, n), M);
        CHECK_EQ(sr__depth_quantize(-0.25, n), 0);     /* clamped */
        CHECK_EQ(sr__depth_quantize(3.0, n), M);
        CHECK_EQ(sr__depth_quantize(NAN, n), 0);
        CHECK_EQ(sr__depth_quantize(-0.0, n), 0);
        /* Exact integers after scaling map exactly: k / M -> k. */
        for (int it = 0; it < 1000; it++) {
            uint64_t k = sr_rng_next(&rng) % (M + 1);
            CHECK_EQ(sr__depth_quantize((double)k / (double)M, n), k);
            CHECK(dq((uint32_t)k, n) == (float)((double)k / (double)M));
        }
    }
    /* Ties at .5 round up: z M = j + 1/2 exactly. */
    CHECK_EQ(sr__depth_quantize(0.5, 16), 32768);      /* 32767.5 */
    CHECK_EQ(sr__depth_quantize(0.5, 24), 8388608);    /* 8388607.5 */
    CHECK_EQ(sr__depth_quantize(0.5, 32), 2147483648u);
    CHECK_EQ(sr__depth_quantize(1.5 / 65535.0, 16), 2);
    CHECK_EQ(sr__depth_quantize(0.25, 16), 16384);     /* 16383.75 */
    CHECK_EQ(sr__depth_quantize(0.125, 16), 8192);     /* 8191.875 */
    /* D32F stores the float's bits, clamped to [0, 1]. */
    const double fz[] = { 0.0, 1.0, 0.5, 0.1, 1.0 / 3.0, 1e-30, 0.999999 };
    for (int i = 0; i < 7; i++) {
        float f = (float)fz[i];
        uint32_t bits;
        memcpy(&bits, &f, sizeof bits);
        CHECK_EQ(sr__depth_quantize(fz[i], 0), bits);
        CHECK(dq(bits, 0) == f);
    }
    float one = 1.0f;
    uint32_t one_bits;
    memcpy(&one_bits, &one, sizeof one_bits);
    CHECK_EQ(sr__depth_quantize(2.0, 0), one_bits);
    CHECK_EQ(sr__depth_quantize(-1.0, 0), 0);
    /* Quantized values order like the depths (for the unsigned compare). */
    for (int b = 0; b <= 32; b += 8) {
        int bits = b == 8 ? 16 : b;
        uint32_t prev = 0;
        for (int i = 0; i <= 1000; i++) {
            uint32_t q = sr__depth_quantize(i / 1000.0, bits);
            CHECK(q >= prev);
            prev = q;
        }
    }
}

/* Through the pipeline: a flat quad at z = k/2^m stores the quantized value
 * and sr_read_depth returns it dequantized. */
SR_TEST(drawn_depth_is_quantized_once_and_read_back_dequantized)
{
    sr_rng rng = { 0x9e7 };
    for (int fi = 0; fi < 4; fi++) {
        target t = target_make(8, 8, fi);
        for (int it = 0; it < 200; it++) {
            int m = sr_rng_int(&rng, 1, 20);
            uint64_t k = sr_rng_next(&rng) % (1ull << m);
            double zw = ldexp((double)k, -m);
            target_clear(&t, 1.0f);
            sr_state st = { .depth_func = SR_ALWAYS };
            REQUIRE(draw_quad(&t, &st, 2 * zw - 1, 0, 0, WHITE) == SR_OK);
            float d[64];
            REQUIRE(sr_read_depth(t.ctx, t.fb, 0, 0, 8, 8, d, 8) == SR_OK);
            uint32_t q = t.bits ? int_quantize(k, m, t.bits) : sr__depth_quantize(zw, 0);
            int bad = 0;
            for (int i = 0; i < 64; i++) {
                bad += d[i] != dq(q, t.bits);
            }
            CHECK_EQ(bad, 0);
        }
        /* Cleared depth reads back dequantized too. */
        const float cd[] = { 0.0f, 1.0f, 0.3f, 0.7f };
        for (int i = 0; i < 4; i++) {
            target_clear(&t, cd[i]);
            float d[4];
            REQUIRE(sr_read_depth(t.ctx, t.fb, 3, 3, 2, 2, d, 2) == SR_OK);
            CHECK(d[0] == dq(sr__depth_quantize(cd[i], t.bits), t.bits));
            double step = t.bits ? 0.5 / ((t.bits == 32) ? 4294967295.0 : (double)((1u << t.bits) - 1)) : 0;
            CHECK_NEAR(d[3], cd[i], step + 1e-7);
        }
        target_free(&t);
    }
}

/* ---- depth range --------------------------------------------------------- */

SR_TEST(depth_range_and_zero_to_one_map_ndc_depth)
{
    /* SET: the range [n, f] given; DEFAULT: [0, 1] */
    enum { SET = SR_DEPTH_RANGE_SET, DEFAULT = SR_DEPTH_RANGE_DEFAULT };
    struct { int mode; float n, f; bool z01; double zndc, want; } cases[] = {
        { SET, 0.2f, 0.6f, false, 0.0, 0.4 },
        { SET, 0.2f, 0.6f, false, -1.0, 0.2 },
        { SET, 0.2f, 0.6f, false, 1.0, 0.6 },
        { SET, 0.8f, 0.2f, false, -1.0, 0.8 },   /* reversed range */
        { SET, 0.8f, 0.2f, false, 0.5, 0.35 },
        { DEFAULT, 0.0f, 0.0f, false, -0.5, 0.25 },
        { DEFAULT, 0.0f, 0.0f, true, 0.5, 0.5 },
        { DEFAULT, 0.0f, 0.0f, true, 0.0, 0.0 },
        { SET, 0.25f, 0.75f, true, 0.5, 0.5 },
        { SET, 0.25f, 0.75f, true, 1.0, 0.75 },
        { SET, 0.6f, 0.2f, true, 0.25, 0.5 },
        { SET, 0.0f, 0.0f, false, -0.5, 0.0 },   /* [0, 0]: a range of zero width */
        { SET, 0.0f, 0.0f, true, 0.75, 0.0 },
        { SET, 0.5f, 0.5f, false, 0.9, 0.5 },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        for (int fi = 0; fi < 4; fi++) {
            target t = target_make(8, 8, fi);
            target_clear(&t, 1.0f);
            sr_state st = { .depth_range = (sr_depth_range_mode)cases[i].mode,
                            .depth_near = cases[i].n, .depth_far = cases[i].f,
                            .depth_zero_to_one = cases[i].z01, .depth_func = SR_ALWAYS };
            REQUIRE(draw_quad(&t, &st, cases[i].zndc, 0, 0, WHITE) == SR_OK);
            CHECK_EQ(count_color(&t, WHITE), 64);
            float d[64];
            REQUIRE(sr_read_depth(t.ctx, t.fb, 0, 0, 8, 8, d, 8) == SR_OK);
            double tol = (t.bits == 16 ? 1.0 / 65535 : 1e-6);
            CHECK_NEAR(d[0], cases[i].want, tol);
            CHECK_NEAR(d[63], cases[i].want, tol);
            target_free(&t);
        }
    }
    /* z_ndc = -0.5 is in front of the near plane in the D3D convention
     * (clip z in [0, w]): nothing is drawn. */
    target t = target_make(8, 8, 1);
    target_clear(&t, 1.0f);
    sr_state z01 = { .depth_zero_to_one = true, .depth_func = SR_ALWAYS };
    REQUIRE(draw_quad(&t, &z01, -0.5, 0, 0, WHITE) == SR_OK);
    CHECK_EQ(count_color(&t, WHITE), 0);
    /* A quad half in front of the near plane: half the pixels. */
    REQUIRE(draw_quad(&t, &z01, 0.0, 0.5, 0, WHITE) == SR_OK);
    CHECK_EQ(count_color(&t, WHITE), 32);
    target_free(&t);
}

/* Depths a sloped full-screen quad writes under the range [n, f]. */
static void range_depths(int fi, float n, float f, float *d)
{
    target t = target_make(16, 16, fi);
    target_clear(&t, 0.5f);
    sr_state st = { .depth_range = SR_DEPTH_RANGE_SET, .depth_near = n, .depth_far = f,
                    .depth_func = SR_ALWAYS };
    CHECK_EQ(draw_quad(&t, &st, 0.1, 0.6, -0.3, WHITE), SR_OK);
    CHECK_EQ(count_color(&t, WHITE), 16 * 16);
    REQUIRE(sr_read_depth(t.ctx, t.fb, 0, 0, 16, 16, d, 16) == SR_OK);
    target_free(&t);
}

SR_TEST(depth_range_out_of_0_1_is_clamped_as_gl_does)
{
    static float want[16 * 16], got[16 * 16];
    for (int fi = 0; fi < 4; fi++) {
        range_depths(fi, 0.0f, 1.0f, want);
        /* The quad's depth varies, so equal buffers say something. */
        CHECK(want[0] != want[15] && want[0] != want[16 * 15]);
        range_depths(fi, -1.0f, 2.0f, got);
        CHECK(memcmp(want, got, sizeof want) == 0);
        range_depths(fi, -INFINITY, INFINITY, got);
        CHECK(memcmp(want, got, sizeof want) == 0);
        /* Reversed, clamped the same way: [1, 0], depth inverted. */
        range_depths(fi, 1.0f, 0.0f, want);
        range_depths(fi, 3.0f, -0.5f, got);
        CHECK(memcmp(want, got, sizeof want) == 0);
        /* One end out: [0.25, 1]. */
        range_depths(fi, 0.25f, 1.0f, want);
        range_depths(fi, 0.25f, 7.0f, got);
        CHECK(memcmp(want, got, sizeof want) == 0);
    }
}

/* ---- polygon offset ------------------------------------------------------- */

enum { PW = 64, PH = 64 };

/* The plane both surfaces lie on: z_ndc = A + B x + C y, steep in x. */
static double plane_z(double x, double y) { return -0.2 + 0.55 * x + 0.12 * y; }

/* Surface 1: a quad on off-grid corners as two triangles.  Surface 2: a
 * fan of 7 triangles around an off-grid centre.  Both cover the screen;
 * their vertices snap differently, so their interpolated depths differ by
 * a fraction of the slope - more than a D16 step. */
static int surface(int which, float *pos)
{
    int n = 0;
    if (which == 0) {
        const double q[4][2] = { { -1.30713, -1.21393 }, { 1.17131, -1.44172 },
                                 { 1.33911, 1.28713 }, { -1.22571, 1.19313 } };
        const int idx[6] = { 0, 1, 2, 0, 2, 3 };
        for (int i = 0; i < 6; i++, n++) {
            pos[n * 3] = (float)q[idx[i]][0];
            pos[n * 3 + 1] = (float)q[idx[i]][1];
        }
    } else {
        const double cx = 0.07313, cy = -0.04931;
        double ring[8][2];
        for (int k = 0; k < 7; k++) {
            double a = 0.3131 + k * 2 * M_PI / 7;
            ring[k][0] = cx + 2.1377 * cos(a);
            ring[k][1] = cy + 2.0519 * sin(a);
        }
        ring[7][0] = ring[0][0];
        ring[7][1] = ring[0][1];
        for (int k = 0; k < 7; k++) {
            const double *v[3] = { (const double[]){ cx, cy }, ring[k], ring[k + 1] };
            for (int j = 0; j < 3; j++, n++) {
                pos[n * 3] = (float)v[j][0];
                pos[n * 3 + 1] = (float)v[j][1];
            }
        }
    }
    for (int i = 0; i < n; i++) {
        pos[i * 3 + 2] = (float)plane_z(pos[i * 3], pos[i * 3 + 1]);
    }
    return n;
}

static sr_result draw_surface(target *t, int which, const sr_state *st, const float rgb[3])
{
    float pos[21 * 3], col[21 * 4];
    int n = surface(which, pos);
    for (int i = 0; i < n; i++) {
        col[i * 4] = rgb[0];
        col[i * 4 + 1] = rgb[1];
        col[i * 4 + 2] = rgb[2];
        col[i * 4 + 3] = 1;
    }
    return sr_draw(t->ctx, t->fb, st, &(sr_draw_desc){ .positions = pos, .vertex_count = (size_t)n,
                                                      .colors = col });
}

SR_TEST(coplanar_surfaces_z_fight_without_offset)
{
    for (int fi = 0; fi < 4; fi++) {
        target t = target_make(PW, PH, fi);
        target_clear(&t, 1.0f);
        sr_state st = { .depth_func = SR_LESS };
        REQUIRE(draw_surface(&t, 0, &st, RED) == SR_OK);
        CHECK_EQ(count_color(&t, RED), PW * PH);
        REQUIRE(draw_surface(&t, 1, &st, GREEN) == SR_OK);
        int wins = count_color(&t, GREEN), loses = count_color(&t, RED);
        CHECK_EQ(wins + loses, PW * PH);
        /* Both outcomes occur: the classic z-fighting pattern (in every
         * format: the snap error is worth more than a D16 step). */
        CHECK(wins > 0);
        CHECK(loses > 0);
        target_free(&t);
    }
}

/* Offset the first surface back (factor 1, units 1), or the second one
 * forward (factor -1, units -1): the second wins every pixel, in every
 * format.  The surfaces differ by at most slope x snap error (< m/128), so
 * m + r separates them by more than one quantization step. */
SR_TEST(polygon_offset_makes_one_surface_win_everywhere)
{
    for (int fi = 0; fi < 4; fi++) {
        for (int variant = 0; variant < 2; variant++) {
            target t = target_make(PW, PH, fi);
            target_clear(&t, 1.0f);
            sr_state first = { .depth_func = SR_LESS };
            sr_state second = { .depth_func = SR_LESS };
            if (variant == 0) {
                first.offset = (sr_polygon_offset){ .factor = 1, .units = 1, .fill = true };
            } else {
                second.offset = (sr_polygon_offset){ .factor = -1, .units = -1, .fill = true };
            }
            REQUIRE(draw_surface(&t, 0, &first, RED) == SR_OK);
            REQUIRE(draw_surface(&t, 1, &second, GREEN) == SR_OK);
            int mismatches = PW * PH - count_color(&t, GREEN);
            if (mismatches) {
                fprintf(stderr, "%s variant %d: %d pixels lost\n", format_names[fi], variant, mismatches);
            }
            CHECK_EQ(mismatches, 0);
            /* The same order with the offset on the wrong surface: the
             * second loses everywhere. */
            target_clear(&t, 1.0f);
            sr_state plain = { .depth_func = SR_LESS };
            sr_state pushed = { .depth_func = SR_LESS,
                                .offset = { .factor = 1, .units = 1, .fill = true } };
            REQUIRE(draw_surface(&t, 0, &plain, RED) == SR_OK);
            REQUIRE(draw_surface(&t, 1, &pushed, GREEN) == SR_OK);
            CHECK_EQ(count_color(&t, RED), PW * PH);
            target_free(&t);
        }
    }
}

/* units = 1 is exactly one step of the format at z = 0.5: a later draw at
 * z = 0.5 with units 1 is EQUAL to it, with units 0 or 2 it is not. */
SR_TEST(offset_units_are_one_step_of_the_format)
{
    for (int fi = 0; fi < 4; fi++) {
        target t = target_make(8, 8, fi);
        target_clear(&t, 1.0f);
        sr_state st = { .depth_func = SR_ALWAYS, .offset = { .units = 1, .fill = true } };
        REQUIRE(draw_quad(&t, &st, 0.0, 0, 0, WHITE) == SR_OK);
        const float units[3] = { 0, 1, 2 };
        for (int k = 0; k < 3; k++) {
            const float col[3] = { 0, 1, 0 };
            sr_state eq = { .depth_func = SR_EQUAL, .depth_write = SR_OFF,
                            .offset = { .units = units[k], .fill = true } };
            REQUIRE(draw_quad(&t, &eq, 0.0, 0, 0, col) == SR_OK);
            CHECK_EQ(count_color(&t, GREEN), k == 1 ? 64 : 0);
            target_clear(&t, 1.0f);
            REQUIRE(draw_quad(&t, &st, 0.0, 0, 0, WHITE) == SR_OK);
        }
        /* And the stored value is the next representable one. */
        if (t.bits != 32) {
            float d;
            REQUIRE(sr_read_depth(t.ctx, t.fb, 4, 4, 1, 1, &d, 1) == SR_OK);
            CHECK(d == dq(sr__depth_quantize(0.5, t.bits) + 1, t.bits));
        }
        /* Without .fill the offset is ignored. */
        target_clear(&t, 1.0f);
        sr_state off = { .depth_func = SR_ALWAYS, .offset = { .factor = 5, .units = 1000 } };
        REQUIRE(draw_quad(&t, &off, 0.0, 0, 0, WHITE) == SR_OK);
        float d;
        REQUIRE(sr_read_depth(t.ctx, t.fb, 0, 0, 1, 1, &d, 1) == SR_OK);
        CHECK(d == dq(sr__depth_quantize(0.5, t.bits), t.bits));
        target_free(&t);
    }
}

/* The slope term: z_w = 0.25 + x_ndc/4 rises 1/128 per pixel across a
 * 64-wide target (exact vertices), so factor 2 adds 2/128. */
SR_TEST(offset_factor_scales_the_depth_slope)
{
    target t = target_make(64, 8, 1); /* D24 */
    const double factors[] = { 2.0, -3.0, 0.5 };
    for (int k = 0; k < 3; k++) {
        target_clear(&t, 1.0f);
        sr_state st = { .depth_func = SR_ALWAYS, .offset = { .factor = (float)factors[k], .fill = true } };
        REQUIRE(draw_quad(&t, &st, -0.25, 0.5, 0.0, WHITE) == SR_OK);
        float d[64];
        REQUIRE(sr_read_depth(t.ctx, t.fb, 0, 3, 64, 1, d, 64) == SR_OK);
        int bad = 0;
        for (int x = 0; x < 64; x++) {
            double z = 0.375 + 0.25 * ((x + 0.5) / 32.0 - 1.0) + factors[k] / 128.0;
            z = z < 0 ? 0 : z > 1 ? 1 : z;
            bad += fabs(d[x] - z) > 1.0 / 16777215 + 1e-7;
        }
        CHECK_EQ(bad, 0);
    }
    target_free(&t);
}

/* clamp > 0 limits a positive offset, clamp < 0 a negative one; a clamp of
 * the other sign does nothing.  The result stays in the depth range. */
SR_TEST(offset_clamp_limits_the_offset)
{
    const double r16 = 1.0 / 65535;
    struct { float units, clamp; bool clamped; } cases[] = {
        { 100, 0, false },
        { 100, 5e-4f, true },
        { 100, -5e-4f, false },
        { -100, -5e-4f, true },
        { -100, 5e-4f, false },
        { -100, 0, false },
        { 100, 1.0f, false },       /* a clamp larger than the offset */
    };
    target t = target_make(8, 8, 0); /* D16 */
    for (int i = 0; i < (int)(sizeof cases / sizeof cases[0]); i++) {
        target_clear(&t, 1.0f);
        sr_state st = { .depth_func = SR_ALWAYS,
                        .offset = { .units = cases[i].units, .clamp = cases[i].clamp, .fill = true } };
        REQUIRE(draw_quad(&t, &st, 0.0, 0, 0, WHITE) == SR_OK);
        float d;
        REQUIRE(sr_read_depth(t.ctx, t.fb, 2, 5, 1, 1, &d, 1) == SR_OK);
        double z = 0.5 + (cases[i].clamped ? (double)cases[i].clamp : cases[i].units * r16);
        CHECK(d == dq(sr__depth_quantize(z, 16), 16));
        CHECK(fabs(d - 0.5) > 4e-4);
    }
    /* Pushed past the end of the depth range: clamped to it. */
    target_clear(&t, 1.0f);
    sr_state far = { .depth_range = SR_DEPTH_RANGE_SET, .depth_near = 0.2f, .depth_far = 0.6f,
                     .depth_func = SR_ALWAYS,
                     .offset = { .units = 10000, .fill = true } };
    REQUIRE(draw_quad(&t, &far, 0.9, 0, 0, WHITE) == SR_OK);
    float d;
    REQUIRE(sr_read_depth(t.ctx, t.fb, 0, 0, 1, 1, &d, 1) == SR_OK);
    CHECK(d == dq(sr__depth_quantize(0.6f, 16), 16));
    sr_state near = { .depth_range = SR_DEPTH_RANGE_SET, .depth_near = 0.2f, .depth_far = 0.6f,
                      .depth_func = SR_ALWAYS,
                      .offset = { .units = -10000, .fill = true } };
    REQUIRE(draw_quad(&t, &near, -0.9, 0, 0, WHITE) == SR_OK);
    REQUIRE(sr_read_depth(t.ctx, t.fb, 0, 0, 1, 1, &d, 1) == SR_OK);
    CHECK(d == dq(sr__depth_quantize(0.2f, 16), 16));
    target_free(&t);
}

/* ---- D16 storage ---------------------------------------------------------- */

/* The high-water mark of a context in an arena that makes a w x h
 * framebuffer of `samples` samples with depth format f: the context's
 * own memory plus the framebuffer's; 0 if either could not be made. */
static size_t framebuffer_arena_peak(int w, int h, sr_depth_format f, int samples)
{
    size_t size = (size_t)4 << 20, peak = 0;
    void *arena = malloc(size);
    sr_context *ctx = NULL;
    if (arena && sr_make_context(&(sr_context_desc){ .arena = arena, .arena_size = size },
                                 &ctx) == SR_OK) {
        sr_framebuffer *fb = NULL;
        if (sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = w, .height = h,
                                                            .depth_format = f,
                                                            .samples = samples }, &fb) == SR_OK) {
            peak = sr_context_arena_peak(ctx);
            sr_destroy_framebuffer(ctx, fb);
        }
        sr_destroy_context(ctx);
    }
    free(arena);
    return peak;
}

SR_TEST(d16_keeps_two_bytes_a_sample_and_the_other_formats_four)
{
    /* 64 x 32 samples: every buffer a whole number of the arena's 64-byte
     * blocks (each with a header block of its own), so the difference of
     * two formats is that of their depth buffers exactly. */
    enum { W = 64, H = 32 };
    for (int samples = 1; samples <= 4; samples *= 4) {
        size_t n = (size_t)W * H * (size_t)samples;
        size_t none = framebuffer_arena_peak(W, H, SR_DEPTH_NONE, samples);
        size_t d16 = framebuffer_arena_peak(W, H, SR_DEPTH_D16, samples);
        size_t d24 = framebuffer_arena_peak(W, H, SR_DEPTH_D24, samples);
        REQUIRE(none > 0);
        CHECK(d16 - none >= 2 * n && d16 - none < 4 * n);
        CHECK_EQ(d24 - d16, 2 * n);
        CHECK_EQ(framebuffer_arena_peak(W, H, SR_DEPTH_D32, samples), d24);
        CHECK_EQ(framebuffer_arena_peak(W, H, SR_DEPTH_D32F, samples), d24);
    }
}

/* Window depth of the quad z_ndc = z0 + zx x + zy y at a point of pixel
 * (px, py) (offset sx, sy in [0, 1) from its upper-left corner). */
static double quad_window_depth(const double z[3], int px, int py, float sx, float sy, int w,
                                int h)
{
    double x = 2.0 * (px + sx) / w - 1.0, y = 1.0 - 2.0 * (py + sy) / h;
    return (z[0] + z[1] * x + z[2] * y + 1.0) / 2.0;
}

/* Every path that tests and writes depth - each vector level the CPU
 * runs, each rasterizer, one sample and four - on a D16 buffer: depth
 * reads back as k / 65535, within a step of the nearer of two crossing
 * slanted quads (each pixel 500 steps from its neighbour, so a lane
 * stored in the wrong place shows), in the color of the nearer one; and
 * a flat quad a fifth of a step nearer than what is stored fails LESS,
 * being equal in 16 bits, while one four fifths of a step nearer passes.
 * Every path's image is the first one's with as many samples. */
SR_TEST(d16_buffer_holds_sixteen_bit_steps_on_every_path)
{
    enum { W = 64, H = 48 };
    const double M = 65535.0;
    const double green[3] = { -0.2, 0.5, 0.1 }, red[3] = { -0.1, -0.5, 0.05 };
    static uint8_t first[2][W * H * 4];    /* per sample count */
    static float d[W * H];
    bool have_first[2] = { false, false };
    int paths = 0;
    for (int level = SR_SIMD_OFF; level <= SR_SIMD_AVX512; level++) {
        for (int rast = SR_RASTER_HALFSPACE; rast <= SR_RASTER_BARYCENTRIC; rast++) {
            for (int samples = 1; samples <= 4; samples *= 4) {
                target t = { NULL, NULL, W, H, 16 };
                REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1,
                                                            .simd = (sr_simd_level)level },
                                        &t.ctx) == SR_OK);
                REQUIRE(sr_make_framebuffer(t.ctx, &(sr_framebuffer_desc){
                    .width = W, .height = H, .depth_format = SR_DEPTH_D16,
                    .samples = samples }, &t.fb) == SR_OK);
                float sx = 0.5f, sy = 0.5f;  /* read_depth reads sample 0 */
                REQUIRE(sr_sample_position(samples, 0, &sx, &sy) == SR_OK);
                sr_state st = { .rasterizer = (sr_rasterizer)rast };
                target_clear(&t, 1.0f);
                REQUIRE(draw_quad(&t, &st, green[0], green[1], green[2], GREEN) == SR_OK);
                REQUIRE(draw_quad(&t, &st, red[0], red[1], red[2], RED) == SR_OK);
                REQUIRE(sr_read_depth(t.ctx, t.fb, 0, 0, W, H, d, W) == SR_OK);
                const uint8_t *px = sr_framebuffer_pixels(t.fb);
                int off_step = 0, off_plane = 0, wrong_color = 0;
                for (int y = 0; y < H; y++) {
                    for (int x = 0; x < W; x++) {
                        int i = y * W + x;
                        double k = floor(d[i] * M + 0.5);
                        off_step += d[i] != (float)(k / M);
                        double zg = quad_window_depth(green, x, y, sx, sy, W, H) * M;
                        double zr = quad_window_depth(red, x, y, sx, sy, W, H) * M;
                        off_plane += fabs(k - (zg < zr ? zg : zr)) > 1.0;
                        /* The color at the pixel's centre, where it is
                         * shaded: away from the crossing, the nearer. */
                        double cg = quad_window_depth(green, x, y, 0.5f, 0.5f, W, H) * M;
                        double cr = quad_window_depth(red, x, y, 0.5f, 0.5f, W, H) * M;
                        if (fabs(cg - cr) > 600.0) {
                            bool g = px[4 * i + 1] == 255 && px[4 * i] == 0;
                            bool r = px[4 * i] == 255 && px[4 * i + 1] == 0;
                            wrong_color += cg < cr ? !g : !r;
                        }
                    }
                }
                CHECK_EQ(off_step, 0);
                CHECK_EQ(off_plane, 0);
                CHECK_EQ(wrong_color, 0);
                int fi = samples > 1;
                if (!have_first[fi]) {
                    memcpy(first[fi], px, sizeof first[fi]);
                    have_first[fi] = true;
                } else if (memcmp(first[fi], px, sizeof first[fi]) != 0) {
                    sr_test_fail(__FILE__, __LINE__, "SIMD level %d, rasterizer %d, %d samples: "
                                 "not the first path's image", level, rast, samples);
                }
                /* Ties at 16 bits: k + 1/5 stored as k, k - 1/5 equal to it. */
                const double k = 40000.0;
                target_clear(&t, 1.0f);
                REQUIRE(draw_quad(&t, &st, 2.0 * (k + 0.2) / M - 1.0, 0, 0, GREEN) == SR_OK);
                REQUIRE(draw_quad(&t, &st, 2.0 * (k - 0.2) / M - 1.0, 0, 0, RED) == SR_OK);
                CHECK_EQ(count_color(&t, GREEN), W * H);
                REQUIRE(draw_quad(&t, &st, 2.0 * (k - 0.8) / M - 1.0, 0, 0, WHITE) == SR_OK);
                CHECK_EQ(count_color(&t, WHITE), W * H);
                REQUIRE(sr_read_depth(t.ctx, t.fb, 0, 0, W, H, d, W) == SR_OK);
                int not_k1 = 0;
                for (int i = 0; i < W * H; i++) {
                    not_k1 += d[i] != dq((uint32_t)k - 1, 16);
                }
                CHECK_EQ(not_k1, 0);
                target_free(&t);
                paths++;
            }
        }
    }
    CHECK_EQ(paths, 4 * 3 * 2);
}

/* Small triangles over the whole of small framebuffers, each buffer ending
 * at an unmapped page (guard_alloc.h): no path reads or writes a lane past
 * the last row.  AVX-512's four-lane 16-bit load once took eight mask bits
 * and read four samples past a D16 buffer's end (found by fuzz_draw).
 * Every level's image and depth are the scalar path's. */
SR_TEST(no_path_touches_a_sample_past_a_small_buffer)
{
#ifndef GUARD_ALLOC_WORKS
    SKIP("no mmap here to put a guard page after a buffer");
#else
    /* Each D16 buffer a multiple of 64 bytes, to end at the page. */
    static const int sizes[][2] = { { 16, 8 }, { 8, 4 }, { 32, 2 }, { 2, 16 }, { 1, 32 },
                                    { 3, 32 } };
    enum { SIZES = sizeof sizes / sizeof sizes[0] };
    enum { MAX = 128 };
    static guard g;
    static uint8_t first[MAX * 4];
    static float depth_first[MAX], d[MAX];
    int runs = 0;
    for (int si = 0; si < SIZES; si++) {
        int w = sizes[si][0], h = sizes[si][1];
        for (int fi = 0; fi < 2; fi++) {    /* D16 and D24 */
            for (int samples = 1; samples <= 4; samples *= 4) {
                for (int level = SR_SIMD_OFF; level <= SR_SIMD_AVX512; level++) {
                    sr_context *ctx = NULL;
                    sr_framebuffer *fb = NULL;
                    REQUIRE(guard_context(&g, level, &ctx) == SR_OK);
                    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){
                        .width = w, .height = h, .depth_format = formats[fi],
                        .samples = samples }, &fb) == SR_OK);
                    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 },
                                                        .depth_action = SR_ACTION_CLEAR,
                                                        .depth = 1.0f });
                    /* Two layers of 3-pixel triangles, the second nearer on
                     * alternate cells, so depth is read, tested and written. */
                    for (int layer = 0; layer < 2; layer++) {
                        for (int cy = 0; cy < h; cy += 2) {
                            for (int cx = 0; cx < w; cx += 2) {
                                float x0 = 2.0f * (float)(cx - 0.5) / (float)w - 1.0f;
                                float x1 = 2.0f * (float)(cx + 2.5) / (float)w - 1.0f;
                                float y0 = 1.0f - 2.0f * (float)(cy - 0.5) / (float)h;
                                float y1 = 1.0f - 2.0f * (float)(cy + 2.5) / (float)h;
                                float z = layer ? (((cx + cy) & 2) ? -0.5f : 0.5f) : 0.1f;
                                float pos[18] = { x0, y0, z, x1, y0, z, x0, y1, z,
                                                  x1, y0, z, x1, y1, z, x0, y1, z };
                                float col[24];
                                for (int i = 0; i < 6; i++) {
                                    col[4 * i] = (float)layer;
                                    col[4 * i + 1] = (float)((cx * 7 + cy * 3) % 16) / 15.0f;
                                    col[4 * i + 2] = (float)(i < 3);
                                    col[4 * i + 3] = 1;
                                }
                                REQUIRE(sr_draw(ctx, fb, &(sr_state){ 0 },
                                                &(sr_draw_desc){ .positions = pos,
                                                                 .vertex_count = 6,
                                                                 .colors = col }) == SR_OK);
                            }
                        }
                    }
                    REQUIRE(sr_read_depth(ctx, fb, 0, 0, w, h, d, w) == SR_OK);
                    const uint8_t *px = sr_framebuffer_pixels(fb);
                    if (level == SR_SIMD_OFF) {
                        memcpy(first, px, (size_t)w * h * 4);
                        memcpy(depth_first, d, (size_t)w * h * sizeof *d);
                    } else if (memcmp(first, px, (size_t)w * h * 4) != 0 ||
                               memcmp(depth_first, d, (size_t)w * h * sizeof *d) != 0) {
                        sr_test_fail(__FILE__, __LINE__, "%dx%d %s, %d samples, SIMD level "
                                     "%d: not the scalar path's image", w, h,
                                     format_names[fi], samples, level);
                    }
                    sr_destroy_framebuffer(ctx, fb);
                    sr_destroy_context(ctx);
                    runs++;
                }
            }
        }
    }
    CHECK_EQ(g.live, 0);
    CHECK_EQ(runs, SIZES * 2 * 2 * (SR_SIMD_AVX512 - SR_SIMD_OFF + 1));
#endif
}
