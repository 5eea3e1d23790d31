/* test_blur.c - sr_blur_image: the exact kernel and the three box blurs
 * against a direct Gaussian sum, conservation of the total away from the
 * edges, the identity at sigma 0, the edge modes and the validation. */
#include "sr_test.h"
#include "softrast.h"

#include <math.h>
#include <stdlib.h>

#define W 64
#define H 48

static double total(const float *p, int n)
{
    double s = 0;
    for (int i = 0; i < n; i++) {
        s += p[i];
    }
    return s;
}

SR_TEST(blur_keeps_the_total_away_from_the_edges)
{
    static const double sigmas[] = { 0.5, 1.3, 2.0, 3.7, 6.0 };
    for (size_t k = 0; k < sizeof sigmas / sizeof sigmas[0]; k++) {
        static float img[W * H];
        sr_rng rng = { 1234 + k };
        for (int i = 0; i < W * H; i++) {
            int x = i % W, y = i / W;
            /* content well inside: 3 sigma + the box sizes stay in */
            img[i] = x >= 24 && x < 40 && y >= 18 && y < 30 ? (float)sr_rng_unit(&rng) : 0.0f;
        }
        double before = total(img, W * H);
        CHECK_EQ(sr_blur_image(sr_test_ctx(), img, W, H, 1,
                               &(sr_blur_desc){ .sigma_x = sigmas[k], .sigma_y = sigmas[k] }),
                 SR_OK);
        CHECK_NEAR(total(img, W * H), before, 1e-3 * before);
    }
}

SR_TEST(blur_of_sigma_zero_is_the_identity)
{
    static float img[W * H * 4], orig[W * H * 4];
    sr_rng rng = { 7 };
    for (int i = 0; i < W * H * 4; i++) {
        img[i] = orig[i] = (float)sr_rng_unit(&rng);
    }
    CHECK_EQ(sr_blur_image(sr_test_ctx(), img, W, H, 4, &(sr_blur_desc){ 0 }), SR_OK);
    for (int i = 0; i < W * H * 4; i++) {
        CHECK_EQ(img[i], orig[i]);
    }
    /* sigma_x only: columns stay as they are, a constant row stays constant */
    for (int i = 0; i < W * H; i++) {
        img[i] = (float)(i / W);
    }
    CHECK_EQ(sr_blur_image(sr_test_ctx(), img, W, H, 1,
                           &(sr_blur_desc){ .sigma_x = 3, .edge = SR_BLUR_EDGE_DUPLICATE }),
             SR_OK);
    for (int i = 0; i < W * H; i++) {
        CHECK_NEAR(img[i], (float)(i / W), 1e-4);
    }
}

/* An impulse blurred is the kernel: the exact one below sigma 2, and
 * within a few percent of the Gaussian of the box blurs above. */
SR_TEST(blur_of_an_impulse_is_a_gaussian)
{
    static const double sigmas[] = { 0.8, 1.9, 2.5, 5.0 };
    for (size_t k = 0; k < sizeof sigmas / sizeof sigmas[0]; k++) {
        double s = sigmas[k];
        static float img[W];
        for (int i = 0; i < W; i++) {
            img[i] = i == W / 2 ? 1.0f : 0.0f;
        }
        CHECK_EQ(sr_blur_image(sr_test_ctx(), img, W, 1, 1, &(sr_blur_desc){ .sigma_x = s }),
                 SR_OK);
        double peak = 1 / (sqrt(2 * M_PI) * s);
        double tol = s < 2 ? 0.02 * peak : 0.08 * peak;
        for (int i = 0; i < W; i++) {
            double d = i - W / 2, g = peak * exp(-d * d / (2 * s * s));
            if (s < 2 && fabs(d) > ceil(3 * s)) {
                g = 0;
            }
            CHECK_NEAR(img[i], g, tol);
        }
        CHECK_NEAR(total(img, W), 1.0, 1e-4);
    }
}

SR_TEST(blur_edge_modes_extend_the_image)
{
    static float img[W];
    /* a constant line: duplicate and wrap keep it, none darkens its ends */
    for (int e = SR_BLUR_EDGE_NONE; e <= SR_BLUR_EDGE_WRAP; e++) {
        for (int i = 0; i < W; i++) {
            img[i] = 0.5f;
        }
        CHECK_EQ(sr_blur_image(sr_test_ctx(), img, W, 1, 1,
                               &(sr_blur_desc){ .sigma_x = 4, .edge = (sr_blur_edge)e }),
                 SR_OK);
        if (e == SR_BLUR_EDGE_NONE) {
            CHECK(img[0] < 0.35f);
            CHECK_NEAR(img[W / 2], 0.5, 1e-5);
        } else {
            CHECK_NEAR(img[0], 0.5, 1e-5);
            CHECK_NEAR(img[W - 1], 0.5, 1e-5);
        }
    }
    /* wrap: a value at the right end reaches the left one */
    for (int i = 0; i < W; i++) {
        img[i] = i == W - 1 ? 1.0f : 0.0f;
    }
    CHECK_EQ(sr_blur_image(sr_test_ctx(), img, W, 1, 1,
                           &(sr_blur_desc){ .sigma_x = 1, .edge = SR_BLUR_EDGE_WRAP }),
             SR_OK);
    CHECK_NEAR(img[0], img[W - 2], 1e-6);
    CHECK(img[0] > 0.2f);
}

SR_TEST(blur_of_a_huge_sigma_is_the_mean_and_ends)
{
    static float img[W];
    for (int i = 0; i < W; i++) {
        img[i] = (float)i;
    }
    CHECK_EQ(sr_blur_image(sr_test_ctx(), img, W, 1, 1,
                           &(sr_blur_desc){ .sigma_x = 1e12, .edge = SR_BLUR_EDGE_WRAP }),
             SR_OK);
    CHECK_NEAR(img[5], (W - 1) / 2.0, 0.5);
}

SR_TEST(blur_validates_its_arguments)
{
    float img[4] = { 0 };
    sr_context *ctx = sr_test_ctx();
    CHECK_EQ(sr_blur_image(NULL, img, 2, 2, 1, &(sr_blur_desc){ 0 }), SR_INVALID_ARG);
    CHECK_EQ(sr_blur_image(ctx, NULL, 2, 2, 1, &(sr_blur_desc){ 0 }), SR_INVALID_ARG);
    CHECK_EQ(sr_blur_image(ctx, img, 2, 2, 1, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_blur_image(ctx, img, 0, 2, 1, &(sr_blur_desc){ 0 }), SR_INVALID_ARG);
    CHECK_EQ(sr_blur_image(ctx, img, 2, 2, 5, &(sr_blur_desc){ 0 }), SR_INVALID_ARG);
    CHECK_EQ(sr_blur_image(ctx, img, 2, 2, 1, &(sr_blur_desc){ .sigma_x = -1 }), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "sigma_x");
    CHECK_EQ(sr_blur_image(ctx, img, 2, 2, 1, &(sr_blur_desc){ .sigma_y = NAN }), SR_INVALID_ARG);
    CHECK_EQ(sr_blur_image(ctx, img, 2, 2, 1, &(sr_blur_desc){ .edge = (sr_blur_edge)9 }),
             SR_INVALID_ARG);
}
