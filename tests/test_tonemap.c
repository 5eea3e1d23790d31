/* test_tonemap.c - sr_tonemap and its curves: the properties each
 * operator promises (PBR Neutral's pass-through below its compression
 * start, hue, bound and monotonicity; ACES's zero and monotonicity), the
 * exposure as a power of two, the sRGB encode against its formula at every
 * 8-bit boundary, the NaN/inf policy, thread identity and validation. */
#include "softrast.h"
#include "sr_test.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static sr_context *make_ctx(int threads)
{
    sr_context *ctx = NULL;
    sr_result r = sr_make_context(&(sr_context_desc){ .threads = threads }, &ctx);
    return r == SR_OK ? ctx : NULL;
}

/* The definition, computed another way than the library does: the sRGB
 * OETF in long double, and the code the count of half-steps it reaches. */
static int srgb_ref(double x)
{
    long double v = x;
    if (!(v > 0)) {
        return 0;
    }
    long double s = v <= 0.0031308L ? 12.92L * v : 1.055L * powl(v, 1.0L / 2.4L) - 0.055L;
    int code = 0;
    while (code < 255 && s * 255.0L >= code + 0.5L) {
        code++;
    }
    return code;
}

static unsigned rng = 12345;
static float frand(float lo, float hi)
{
    rng = rng * 1664525u + 1013904223u;
    return lo + (hi - lo) * (float)(rng >> 8) / (float)(1u << 24);
}

/* One RGB colour through sr_tonemap (a 1x1 image) as bytes. */
static void tonemap1(sr_context *ctx, const float rgb[3], sr_tonemap_op op, float ev,
                     uint8_t out[4])
{
    sr_tonemap_desc d = { .op = op, .exposure = ev, .channels = 3 };
    sr_result r = sr_tonemap(ctx, rgb, 1, 1, 0, out, 0, &d);
    if (r != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "sr_tonemap: %s", sr_context_error(ctx));
    }
}

SR_TEST(pbr_neutral_passes_colours_below_its_compression_start)
{
    /* Below peak 0.76 (after the offset) the curve only subtracts the
     * offset: 0.04 when the smallest channel is 0.08 or more, x - 6.25 x^2
     * below that.  The bytes are then the encode of exactly that. */
    sr_context *ctx = make_ctx(1);
    REQUIRE(ctx);
    int checked = 0;
    for (int i = 0; i < 20000; i++) {
        float in[3] = { frand(0, 0.8f), frand(0, 0.8f), frand(0, 0.8f) };
        if (i % 4 == 0) {
            in[i % 3] = frand(0, 0.08f); /* the smooth-offset branch */
        }
        float x = fminf(in[0], fminf(in[1], in[2]));
        float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
        float want[3] = { in[0] - offset, in[1] - offset, in[2] - offset };
        if (fmaxf(want[0], fmaxf(want[1], want[2])) >= 0.76f) {
            continue;
        }
        float got[3];
        REQUIRE(sr_tonemap_rgb(SR_TONEMAP_PBR_NEUTRAL, in, got) == SR_OK);
        uint8_t px[4];
        tonemap1(ctx, in, SR_TONEMAP_DEFAULT, 0.0f, px);
        for (int c = 0; c < 3; c++) {
            if (got[c] != want[c] || px[c] != srgb_ref(want[c])) {
                sr_test_fail(__FILE__, __LINE__, "in %g %g %g channel %d: %.9g (byte %d), want %.9g",
                             in[0], in[1], in[2], c, got[c], px[c], want[c]);
                i = 1 << 30;
                break;
            }
        }
        checked++;
    }
    CHECK(checked > 10000);
    /* A base colour lit to colour + 0.04 (a dielectric's Fresnel) comes
     * back as itself. */
    float base[3] = { 0.5f, 0.25f, 0.125f }, lit[3], got[3];
    for (int c = 0; c < 3; c++) {
        lit[c] = base[c] + 0.04f;
    }
    sr_tonemap_rgb(SR_TONEMAP_PBR_NEUTRAL, lit, got);
    for (int c = 0; c < 3; c++) {
        CHECK_NEAR(got[c], base[c], 1e-6);
    }
    sr_destroy_context(ctx);
}

/* HSV hue in [0, 6) (the sextant and its fraction). */
static double hue(const float c[3])
{
    double mx = fmax(c[0], fmax(c[1], c[2])), mn = fmin(c[0], fmin(c[1], c[2]));
    double d = mx - mn;
    double h;
    if (mx == c[0]) {
        h = (c[1] - c[2]) / d;
    } else if (mx == c[1]) {
        h = 2.0 + (c[2] - c[0]) / d;
    } else {
        h = 4.0 + (c[0] - c[1]) / d;
    }
    return h < 0 ? h + 6.0 : h;
}

SR_TEST(pbr_neutral_keeps_hue_and_stays_below_one)
{
    for (int i = 0; i < 20000; i++) {
        float scale = powf(10.0f, frand(-1.0f, 4.0f));
        float in[3] = { frand(0, 1) * scale, frand(0, 1) * scale, frand(0, 1) * scale }, out[3];
        REQUIRE(sr_tonemap_rgb(SR_TONEMAP_PBR_NEUTRAL, in, out) == SR_OK);
        for (int c = 0; c < 3; c++) {
            if (!(out[c] >= 0.0f && out[c] < 1.0f)) {
                sr_test_fail(__FILE__, __LINE__, "in %g %g %g: channel %d = %.9g", in[0], in[1],
                             in[2], c, out[c]);
                return;
            }
        }
        /* Hue is defined where the input is clearly chromatic; the output's
         * spread may shrink to a few ulps at high desaturation. */
        double in_spread = fmax(in[0], fmax(in[1], in[2])) - fmin(in[0], fmin(in[1], in[2]));
        double out_spread = fmax(out[0], fmax(out[1], out[2])) - fmin(out[0], fmin(out[1], out[2]));
        if (in_spread < 0.05 * scale || out_spread < 1e-3) {
            continue;
        }
        double dh = fabs(hue(in) - hue(out));
        dh = fmin(dh, 6.0 - dh);
        if (dh > 1e-3) {
            sr_test_fail(__FILE__, __LINE__, "in %g %g %g: hue %.6f -> %.6f", in[0], in[1],
                         in[2], hue(in), hue(out));
            return;
        }
    }
    /* Very bright light is white at the top, not past it. */
    float sun[3] = { 1e6f, 1e6f, 1e6f }, out[3];
    sr_tonemap_rgb(SR_TONEMAP_PBR_NEUTRAL, sun, out);
    CHECK(out[0] <= 1.0f && out[0] > 0.999f);
}

/* Each channel of op(k c) never decreases as k grows along a ramp. */
static void check_monotonic(sr_tonemap_op op, const float c[3], int line)
{
    float prev[3] = { -1, -1, -1 };
    for (int i = 0; i <= 4000; i++) {
        float k = i < 2000 ? i / 1000.0f : 2.0f * powf(1.002f, (float)(i - 2000));
        float in[3] = { k * c[0], k * c[1], k * c[2] }, out[3];
        sr_tonemap_rgb(op, in, out);
        for (int ch = 0; ch < 3; ch++) {
            if (out[ch] < prev[ch] - 1e-6f) {
                sr_test_fail(__FILE__, line, "op %d colour %g %g %g at k = %g: channel %d %.9g < %.9g",
                             (int)op, c[0], c[1], c[2], k, ch, out[ch], prev[ch]);
                return;
            }
            prev[ch] = out[ch];
        }
    }
}

SR_TEST(curves_are_monotonic_along_ramps)
{
    const float colours[][3] = { { 1, 1, 1 }, { 1, 0.5f, 0.25f }, { 0.1f, 0.2f, 1 },
                                 { 0, 1, 0 }, { 0.9f, 0.9f, 0.05f } };
    for (int i = 0; i < 5; i++) {
        check_monotonic(SR_TONEMAP_PBR_NEUTRAL, colours[i], __LINE__);
        check_monotonic(SR_TONEMAP_ACES, colours[i], __LINE__);
        check_monotonic(SR_TONEMAP_NONE, colours[i], __LINE__);
    }
}

SR_TEST(aces_black_is_black_and_highlights_saturate)
{
    float zero[3] = { 0, 0, 0 }, out[3];
    REQUIRE(sr_tonemap_rgb(SR_TONEMAP_ACES, zero, out) == SR_OK);
    CHECK(out[0] == 0.0f && out[1] == 0.0f && out[2] == 0.0f);
    /* Mid grey (0.18) lands near the middle of the display range and a
     * very bright grey at white. */
    float grey[3] = { 0.18f, 0.18f, 0.18f }, bright[3] = { 1e4f, 1e4f, 1e4f };
    sr_tonemap_rgb(SR_TONEMAP_ACES, grey, out);
    CHECK(out[0] > 0.1f && out[0] < 0.4f);
    CHECK_NEAR(out[0], out[1], 2e-3);
    sr_tonemap_rgb(SR_TONEMAP_ACES, bright, out);
    CHECK(out[0] == 1.0f && out[1] == 1.0f && out[2] == 1.0f);
}

SR_TEST(one_ev_is_a_doubling)
{
    sr_context *ctx = make_ctx(1);
    REQUIRE(ctx);
    enum { N = 4096 };
    float *a = malloc(N * 3 * sizeof(float)), *b = malloc(N * 3 * sizeof(float));
    uint8_t *pa = malloc(N * 4), *pb = malloc(N * 4);
    for (int i = 0; i < N * 3; i++) {
        a[i] = frand(0, 4);
    }
    const struct { float ev, factor; } cases[] = { { 1, 2 }, { -3, 0.125f }, { 5, 32 } };
    for (int op = SR_TONEMAP_DEFAULT; op <= SR_TONEMAP_NONE; op++) {
        for (int k = 0; k < 3; k++) {
            for (int i = 0; i < N * 3; i++) {
                b[i] = a[i] * cases[k].factor;
            }
            sr_tonemap_desc da = { .op = op, .exposure = cases[k].ev, .channels = 3 };
            sr_tonemap_desc db = { .op = op, .channels = 3 };
            REQUIRE(sr_tonemap(ctx, a, N, 1, 0, pa, 0, &da) == SR_OK);
            REQUIRE(sr_tonemap(ctx, b, N, 1, 0, pb, 0, &db) == SR_OK);
            CHECK(memcmp(pa, pb, N * 4) == 0);
        }
    }
    /* And the exposure does something: +1 EV brightens a mid grey. */
    float grey[3] = { 0.18f, 0.18f, 0.18f };
    uint8_t g0[4], g1[4];
    tonemap1(ctx, grey, SR_TONEMAP_DEFAULT, 0, g0);
    tonemap1(ctx, grey, SR_TONEMAP_DEFAULT, 1, g1);
    CHECK(g1[0] > g0[0]);
    free(a);
    free(b);
    free(pa);
    free(pb);
    sr_destroy_context(ctx);
}

SR_TEST(srgb_encode_matches_the_formula_at_every_code_boundary)
{
    /* For each code k, the linear value where the formula crosses k + 0.5
     * (inverted in double), and floats within 4 ulps either side of it:
     * sr_srgb_encode8 and the image path (op NONE, the table) must give
     * the formula's code for each. */
    sr_context *ctx = make_ctx(1);
    REQUIRE(ctx);
    enum { PER = 9, N = 255 * PER };
    float *in = malloc(N * 3 * sizeof(float));
    uint8_t *out = malloc(N * 4);
    int n = 0;
    for (int k = 0; k < 255; k++) {
        double s = (k + 0.5) / 255.0;
        double b = s <= 0.04045 ? s / 12.92 : pow((s + 0.055) / 1.055, 2.4);
        float f = (float)b;
        for (int i = 0; i < 4; i++) {
            f = nextafterf(f, 0.0f);
        }
        for (int i = 0; i < PER; i++, f = nextafterf(f, 2.0f)) {
            in[3 * n] = in[3 * n + 1] = in[3 * n + 2] = f;
            n++;
        }
    }
    REQUIRE(sr_tonemap(ctx, in, N, 1, 0, out, 0,
                       &(sr_tonemap_desc){ .op = SR_TONEMAP_NONE, .channels = 3 }) == SR_OK);
    int bad = 0, crossings = 0;
    for (int i = 0; i < N && bad < 5; i++) {
        int want = srgb_ref(in[3 * i]);
        if (out[4 * i] != want || sr_srgb_encode8(in[3 * i]) != want) {
            sr_test_fail(__FILE__, __LINE__, "%.9g: table %d, encode8 %d, formula %d",
                         in[3 * i], out[4 * i], sr_srgb_encode8(in[3 * i]), want);
            bad++;
        }
        crossings += i % PER > 0 && srgb_ref(in[3 * i]) != srgb_ref(in[3 * i - 3]);
    }
    CHECK_EQ(crossings, 255); /* each window holds its boundary */
    /* The ends and the specials. */
    CHECK_EQ(sr_srgb_encode8(0.0f), 0);
    CHECK_EQ(sr_srgb_encode8(1.0f), 255);
    CHECK_EQ(sr_srgb_encode8(NAN), 0);
    CHECK_EQ(sr_srgb_encode8(-1.0f), 0);
    CHECK_EQ(sr_srgb_encode8(INFINITY), 255);
    free(in);
    free(out);
    sr_destroy_context(ctx);
}

SR_TEST(nan_inf_and_alpha_policy)
{
    sr_context *ctx = make_ctx(1);
    REQUIRE(ctx);
    const float px[4][4] = { { NAN, 0.5f, -2.0f, 0.5f },
                             { INFINITY, INFINITY, INFINITY, NAN },
                             { FLT_MAX, 0, 0, 2.0f },
                             { 0.2f, 0.2f, 0.2f, -1.0f } };
    for (int op = SR_TONEMAP_DEFAULT; op <= SR_TONEMAP_NONE; op++) {
        uint8_t out[16];
        REQUIRE(sr_tonemap(ctx, &px[0][0], 4, 1, 0, out, 0, &(sr_tonemap_desc){ .op = op }) ==
                SR_OK);
        /* NaN and -2 are black, the same as 0 there. */
        const float clean[3] = { 0, 0.5f, 0 };
        uint8_t ref[4];
        tonemap1(ctx, clean, op, 0, ref);
        CHECK(memcmp(out, ref, 3) == 0);
        CHECK_EQ(out[3], 128);
        /* +inf is white; alpha NaN -> 0, 2 -> 255, -1 -> 0. */
        CHECK(out[4] == 255 && out[5] == 255 && out[6] == 255);
        CHECK_EQ(out[7], 0);
        CHECK_EQ(out[11], 255);
        CHECK_EQ(out[15], 0);
    }
    sr_destroy_context(ctx);
}

SR_TEST(strides_channels_and_threads)
{
    /* 3 channels, 4 channels with alpha 1 and a padded source stride and a
     * padded output give the same colour bytes; 1 and 3 threads the same
     * image. */
    int w = 37, h = 53;
    size_t n = (size_t)w * h;
    float *rgb = malloc(n * 3 * sizeof(float));
    float *rgba = malloc((size_t)(w * 4 + 3) * h * sizeof(float));
    for (size_t i = 0; i < n; i++) {
        for (int c = 0; c < 3; c++) {
            rgb[3 * i + c] = frand(0, 3);
        }
    }
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            float *q = rgba + (size_t)y * (w * 4 + 3) + 4 * x;
            memcpy(q, rgb + 3 * ((size_t)y * w + x), 3 * sizeof(float));
            q[3] = 1.0f;
        }
    }
    uint8_t *a = malloc(n * 4), *b = malloc((size_t)(w * 4 + 8) * h), *c = malloc(n * 4);
    sr_context *one = make_ctx(1), *three = make_ctx(3);
    REQUIRE(one && three);
    for (int op = SR_TONEMAP_DEFAULT; op <= SR_TONEMAP_NONE; op++) {
        REQUIRE(sr_tonemap(one, rgb, w, h, 0, a, 0,
                           &(sr_tonemap_desc){ .op = op, .channels = 3, .exposure = 0.5f }) ==
                SR_OK);
        REQUIRE(sr_tonemap(three, rgba, w, h, (size_t)(w * 4 + 3) * sizeof(float), b,
                           (size_t)w * 4 + 8, &(sr_tonemap_desc){ .op = op, .exposure = 0.5f }) ==
                SR_OK);
        REQUIRE(sr_tonemap(three, rgb, w, h, 0, c, 0,
                           &(sr_tonemap_desc){ .op = op, .channels = 3, .exposure = 0.5f }) ==
                SR_OK);
        CHECK(memcmp(a, c, n * 4) == 0);
        for (int y = 0; y < h; y++) {
            CHECK(memcmp(a + (size_t)y * w * 4, b + (size_t)y * (w * 4 + 8), (size_t)w * 4) == 0);
        }
        CHECK_EQ(a[3], 255);
    }
    sr_destroy_context(one);
    sr_destroy_context(three);
    free(rgb);
    free(rgba);
    free(a);
    free(b);
    free(c);
}

SR_TEST(tonemap_validates_its_arguments)
{
    sr_context *ctx = make_ctx(1);
    REQUIRE(ctx);
    float px[8] = { 0 };
    uint8_t out[8];
    CHECK(sr_tonemap(NULL, px, 1, 1, 0, out, 0, NULL) == SR_INVALID_ARG);
    CHECK(sr_tonemap(ctx, NULL, 1, 1, 0, out, 0, NULL) == SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_tonemap: pixels is NULL");
    CHECK(sr_tonemap(ctx, px, 1, 1, 0, NULL, 0, NULL) == SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_tonemap: out is NULL");
    CHECK(sr_tonemap(ctx, px, 0, 1, 0, out, 0, NULL) == SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "size 0x1");
    CHECK(sr_tonemap(ctx, px, 1, -1, 0, out, 0, NULL) == SR_INVALID_ARG);
    CHECK(sr_tonemap(ctx, px, 1, 1, 0, out, 0, &(sr_tonemap_desc){ .channels = 2 }) ==
          SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_tonemap_desc.channels 2 must be 3 or 4");
    CHECK(sr_tonemap(ctx, px, 1, 1, 0, out, 0, &(sr_tonemap_desc){ .op = (sr_tonemap_op)9 }) ==
          SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_tonemap_desc.op 9");
    CHECK(sr_tonemap(ctx, px, 1, 1, 0, out, 0, &(sr_tonemap_desc){ .exposure = NAN }) ==
          SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_tonemap_desc.exposure nan");
    CHECK(sr_tonemap(ctx, px, 1, 1, 0, out, 0, &(sr_tonemap_desc){ .exposure = 65 }) ==
          SR_INVALID_ARG);
    CHECK(sr_tonemap(ctx, px, 2, 1, 31, out, 0, NULL) == SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "stride 31 must be a multiple of 4 and at least 32");
    CHECK(sr_tonemap(ctx, px, 2, 1, 30, out, 0, NULL) == SR_INVALID_ARG);
    CHECK(sr_tonemap(ctx, px, 2, 1, 0, out, 7, NULL) == SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "out_stride 7 is less than 8 bytes");
    CHECK(sr_tonemap(ctx, px, 1, 1 << 30, SIZE_MAX / 8 * 4, out, 0, NULL) == SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "does not fit in memory");
    /* out must not overlap pixels (rows run on several threads): in
     * place, or out starting inside the floats, is refused. */
    float img[16 * 4] = { 0 };
    CHECK(sr_tonemap(ctx, img, 4, 4, 0, (uint8_t *)img, 0, NULL) == SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sr_tonemap: out overlaps pixels");
    CHECK(sr_tonemap(ctx, img, 2, 2, 0, (uint8_t *)(img + 15), 0, NULL) == SR_INVALID_ARG);
    CHECK(sr_tonemap(ctx, img + 2, 2, 2, 0, (uint8_t *)img, 0, NULL) == SR_INVALID_ARG);
    CHECK(sr_tonemap(ctx, img, 2, 2, 0, (uint8_t *)(img + 16), 0, NULL) == SR_OK);
    /* The bounds themselves are accepted, and a success clears the message. */
    CHECK(sr_tonemap(ctx, px, 2, 1, 32, out, 8,
                     &(sr_tonemap_desc){ .exposure = -64, .op = SR_TONEMAP_ACES }) == SR_OK);
    CHECK(sr_context_error(ctx)[0] == 0);
    float rgb[3] = { 0 };
    CHECK(sr_tonemap_rgb((sr_tonemap_op)4, rgb, rgb) == SR_INVALID_ARG);
    CHECK(sr_tonemap_rgb(SR_TONEMAP_NONE, NULL, rgb) == SR_INVALID_ARG);
    CHECK(sr_tonemap_rgb(SR_TONEMAP_NONE, rgb, NULL) == SR_INVALID_ARG);
    sr_destroy_context(ctx);
}
