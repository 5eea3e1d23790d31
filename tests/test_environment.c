/* test_environment.c - image-based light: a uniform environment gives
 * irradiance and prefiltered radiance equal to its radiance; the BRDF
 * table against a Monte Carlo estimate of the directional albedo and
 * within energy; the SH irradiance against brute-force integration; the
 * rotation and intensity; identical results for any thread count; the
 * build's tables equal to what the library computes at run time; bad
 * input and allocation failures; and pictures of the built-in studio, its
 * specular levels and spheres lit by it (tests/out/environment_*.png). */
#include "softrast.h"
#include "softrast_io.h"
#include "failing_alloc.h"
#include "fragment/environment.h"
#include "sr_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static sr_context *make_ctx(int threads)
{
    sr_context *ctx = NULL;
    sr_result r = sr_make_context(&(sr_context_desc){ .threads = threads }, &ctx);
    return r == SR_OK ? ctx : NULL;
}

static unsigned rng = 2024;
static double drand(void)
{
    rng = rng * 1664525u + 1013904223u;
    return ((rng >> 8) + 0.5) / (double)(1u << 24);
}

/* A direction spread over the sphere (fixed seed). */
static void random_direction(float d[3])
{
    double z = 2.0 * drand() - 1.0, phi = 2.0 * M_PI * drand(), s = sqrt(1.0 - z * z);
    d[0] = (float)(s * cos(phi));
    d[1] = (float)(s * sin(phi));
    d[2] = (float)z;
}

/* An equirectangular image filled by f(direction through the pixel centre). */
static float *make_image(int w, int h, float (*f)(const double d[3]))
{
    float *p = malloc((size_t)w * h * 3 * sizeof *p);
    for (int j = 0; j < h; j++) {
        for (int i = 0; i < w; i++) {
            double phi = (i + 0.5) / w * 2.0 * M_PI - M_PI, theta = (j + 0.5) / h * M_PI;
            double d[3] = { sin(theta) * cos(phi), cos(theta), sin(theta) * sin(phi) };
            float v = f(d);
            for (int c = 0; c < 3; c++) {
                p[((size_t)j * w + i) * 3 + c] = v;
            }
        }
    }
    return p;
}

static float white(const double d[3])
{
    (void)d;
    return 1.0f;
}

SR_TEST(uniform_white_environment_gives_one_everywhere)
{
    sr_context *ctx = make_ctx(2);
    float *img = make_image(64, 32, white);
    sr_environment *env = NULL;
    REQUIRE(sr_make_environment(ctx, &(sr_environment_desc){ .pixels = img, .width = 64,
                                                             .height = 32 },
                                &env) == SR_OK);
    float worst_irr = 0, worst_spec = 0;
    for (int n = 0; n < 500; n++) {
        float d[3], c[3];
        random_direction(d);
        sr_environment_irradiance(env, d, c);
        for (int k = 0; k < 3; k++) {
            worst_irr = fmaxf(worst_irr, fabsf(c[k] - 1.0f));
        }
        for (int r = 0; r <= 20; r++) {
            sr_environment_specular(env, d, r / 20.0f, c);
            for (int k = 0; k < 3; k++) {
                worst_spec = fmaxf(worst_spec, fabsf(c[k] - 1.0f));
            }
        }
    }
    CHECK_NEAR(worst_irr, 0.0, 1e-3);
    CHECK_NEAR(worst_spec, 0.0, 1e-4);
    sr_destroy_environment(ctx, env);
    free(img);
    sr_destroy_context(ctx);
}

/* ---- the BRDF table ---------------------------------------------------- */

/* The directional albedo of the specular BRDF, D Vis F (N.L) over the
 * hemisphere, for F0 = 1 (scale + bias) and F0 = 0 (bias), estimated with
 * cosine-weighted directions on a jittered grid (fixed seed). */
static void albedo_monte_carlo(double nv, double roughness, double *sum, double *bias)
{
    enum { N = 400 };
    double alpha = roughness * roughness, a2 = alpha * alpha;
    double v[3] = { sqrt(1 - nv * nv), 0, nv };
    double s = 0, b = 0;
    for (int i = 0; i < N; i++) {
        for (int j = 0; j < N; j++) {
            double e1 = (i + drand()) / N, e2 = (j + drand()) / N;
            double r = sqrt(e1), phi = 2 * M_PI * e2;
            double l[3] = { r * cos(phi), r * sin(phi), sqrt(1 - e1) };
            double nl = l[2];
            double h[3] = { l[0] + v[0], l[1] + v[1], l[2] + v[2] };
            double hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
            double nh = h[2] / hl, vh = (v[0] * h[0] + v[1] * h[1] + v[2] * h[2]) / hl;
            double q = nh * nh * (a2 - 1) + 1;
            double D = a2 / (M_PI * q * q);
            double vis = 0.5 / (nl * sqrt(nv * nv * (1 - a2) + a2) + nv * sqrt(nl * nl * (1 - a2) + a2));
            double fc = pow(1 - vh, 5);
            /* pdf = N.L / pi, so f N.L / pdf = pi f */
            s += M_PI * D * vis;
            b += M_PI * D * vis * fc;
        }
    }
    *sum = s / ((double)N * N);
    *bias = b / ((double)N * N);
}

SR_TEST(brdf_table_matches_a_monte_carlo_directional_albedo)
{
    /* Roughness from 0.3: below it the lobe is too narrow for this plain
     * estimator; roughness 0 is checked exactly below. */
    static const double rough[] = { 0.3, 0.5, 0.7, 1.0 };
    static const double nvs[] = { 0.15, 0.4, 0.7, 0.95 };
    for (size_t i = 0; i < sizeof rough / sizeof rough[0]; i++) {
        for (size_t j = 0; j < sizeof nvs / sizeof nvs[0]; j++) {
            double sum, bias;
            albedo_monte_carlo(nvs[j], rough[i], &sum, &bias);
            float t[2];
            sr_brdf_table((float)nvs[j], (float)rough[i], t);
            CHECK_NEAR(t[0] + t[1], sum, 0.02);
            CHECK_NEAR(t[1], bias, 0.01);
        }
    }
    /* At roughness 1 (alpha 1) D is 1/pi and Vis 1 / (2 (N.L + N.V)), so
     * the albedo is the integral of mu / (mu + N.V) over mu in [0, 1]:
     * 1 - N.V ln(1 + 1 / N.V).  Near grazing the sampled estimate and the
     * bilinear table both err most (1.3% at N.V = 0.1). */
    for (int j = 1; j <= 10; j++) {
        double nv = j / 10.0;
        float t[2];
        sr_brdf_table((float)nv, 1.0f, t);
        CHECK_NEAR(t[0] + t[1], 1 - nv * log(1 + 1 / nv), nv < 0.15 ? 0.015 : 5e-3);
    }
    /* A mirror reflects everything, with Schlick's Fresnel at N.V. */
    for (int j = 0; j <= 8; j++) {
        float nv = 0.2f + 0.1f * j, t[2];
        sr_brdf_table(nv, 0.0f, t);
        CHECK_NEAR(t[0] + t[1], 1.0, 1e-3);
        CHECK_NEAR(t[1], pow(1 - nv, 5), 0.01);
    }
}

SR_TEST(brdf_table_never_creates_energy)
{
    float worst = 0;
    for (int i = 0; i <= 100; i++) {
        for (int j = 0; j <= 100; j++) {
            float t[2];
            sr_brdf_table(i / 100.0f, j / 100.0f, t);
            CHECK(t[0] >= 0 && t[1] >= 0);
            worst = fmaxf(worst, t[0] + t[1]);
        }
    }
    /* every node sums to 1 at most; between nodes only the rounding of
     * the bilinear weights may add to that */
    CHECK(worst <= 1.0f + 1e-6f);
    /* The 4-lane form reads the same table. */
    float nv[4] = { 0.1f, 0.5f, 0.77f, 1.0f }, r[4] = { 0.9f, 0.0f, 0.33f, 0.5f };
    float scale[4], bias[4];
    sr_brdf_table4(nv, r, scale, bias);
    for (int i = 0; i < 4; i++) {
        float t[2];
        sr_brdf_table(nv[i], r[i], t);
        CHECK(scale[i] == t[0] && bias[i] == t[1]);
    }
}

/* ---- irradiance -------------------------------------------------------- */

/* E / pi at n by summing every texel of the image with its solid angle. */
static double brute_irradiance(const float *img, int w, int h, const float n[3])
{
    double e = 0;
    for (int j = 0; j < h; j++) {
        double t0 = M_PI * j / h, t1 = M_PI * (j + 1) / h;
        double omega = 2 * M_PI / w * (cos(t0) - cos(t1));
        for (int i = 0; i < w; i++) {
            double phi = (i + 0.5) / w * 2.0 * M_PI - M_PI, theta = (j + 0.5) / h * M_PI;
            double d[3] = { sin(theta) * cos(phi), cos(theta), sin(theta) * sin(phi) };
            double c = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
            if (c > 0) {
                e += img[((size_t)j * w + i) * 3] * c * omega;
            }
        }
    }
    return e / M_PI;
}

static float half_sky(const double d[3])
{
    return d[1] > 0 ? 1.0f : 0.0f;
}

/* Linear and quadratic in the direction: exactly what 9 SH hold. */
static float smooth_sky(const double d[3])
{
    return (float)(1.0 + 0.5 * d[1] + 0.3 * d[0] + 0.4 * d[0] * d[2] + 0.2 * d[1] * d[1]);
}

static void check_sh_against_brute_force(float (*f)(const double d[3]), double tol)
{
    enum { W = 256, H = 128 };
    sr_context *ctx = make_ctx(1);
    float *img = make_image(W, H, f);
    sr_environment *env = NULL;
    REQUIRE(sr_make_environment(ctx, &(sr_environment_desc){ .pixels = img, .width = W,
                                                             .height = H },
                                &env) == SR_OK);
    double worst = 0;
    for (int n = 0; n < 60; n++) {
        float d[3], c[3];
        random_direction(d);
        sr_environment_irradiance(env, d, c);
        worst = fmax(worst, fabs(c[0] - brute_irradiance(img, W, H, d)));
        CHECK(c[0] == c[1] && c[1] == c[2]);
    }
    CHECK_NEAR(worst, 0.0, tol);
    sr_destroy_environment(ctx, env);
    free(img);
    sr_destroy_context(ctx);
}

SR_TEST(sh_irradiance_of_a_quadratic_sky_is_exact)
{
    /* Irradiance of a quadratic radiance lies wholly in the 9 terms: what
     * differs is the SH mip's box filter and float sums. */
    check_sh_against_brute_force(smooth_sky, 5e-3);
}

SR_TEST(sh_irradiance_of_a_half_white_sky_is_close)
{
    /* A step at the horizon: 9 terms leave a ringing of a few percent
     * (Ramamoorthi and Hanrahan's bound for the clamped cosine). */
    check_sh_against_brute_force(half_sky, 0.05);
}

/* ---- rotation, intensity, threads -------------------------------------- */

/* A bright patch around +X (the image's centre) on black. */
static float patch_at_plus_x(const double d[3])
{
    return d[0] > 0.95 ? 10.0f : 0.0f;
}

SR_TEST(rotation_moves_a_feature_about_plus_y)
{
    enum { W = 128, H = 64 };
    sr_context *ctx = make_ctx(1);
    float *img = make_image(W, H, patch_at_plus_x);
    const float px[3] = { 1, 0, 0 }, mz[3] = { 0, 0, -1 }, pz[3] = { 0, 0, 1 };
    for (int rotated = 0; rotated < 2; rotated++) {
        sr_environment *env = NULL;
        sr_environment_desc desc = { .pixels = img, .width = W, .height = H,
                                     .rotation = rotated ? (float)M_PI / 2 : 0 };
        REQUIRE(sr_make_environment(ctx, &desc, &env) == SR_OK);
        float a[3], b[3], c[3];
        sr_environment_background(env, rotated ? mz : px, 0, a);
        sr_environment_background(env, rotated ? px : mz, 0, b);
        sr_environment_background(env, pz, 0, c);
        CHECK_NEAR(a[0], 10.0, 1e-3);
        CHECK_EQ(b[0], 0);
        CHECK_EQ(c[0], 0);
        sr_environment_irradiance(env, rotated ? mz : px, a);
        sr_environment_irradiance(env, rotated ? px : mz, b);
        CHECK(a[0] > 4 * b[0] + 0.01f);
        sr_destroy_environment(ctx, env);
    }
    free(img);
    sr_destroy_context(ctx);
}

SR_TEST(intensity_scales_every_query)
{
    sr_context *ctx = make_ctx(1);
    sr_environment *one = NULL, *two = NULL;
    REQUIRE(sr_make_environment(ctx, &(sr_environment_desc){0}, &one) == SR_OK);
    REQUIRE(sr_make_environment(ctx, &(sr_environment_desc){ .intensity = 2 }, &two) == SR_OK);
    for (int n = 0; n < 50; n++) {
        float d[3], a[3], b[3];
        random_direction(d);
        sr_environment_irradiance(one, d, a);
        sr_environment_irradiance(two, d, b);
        CHECK_NEAR(b[0], 2 * a[0], 1e-4 * a[0] + 1e-6);
        sr_environment_specular(one, d, 0.37f, a);
        sr_environment_specular(two, d, 0.37f, b);
        CHECK_NEAR(b[1], 2 * a[1], 1e-4 * a[1] + 1e-6);
    }
    sr_destroy_environment(ctx, one);
    sr_destroy_environment(ctx, two);
    sr_destroy_context(ctx);
}

SR_TEST(same_results_for_any_thread_count)
{
    sr_context *c1 = make_ctx(1), *c2 = make_ctx(2);
    float *img = make_image(200, 100, smooth_sky);
    sr_environment_desc desc = { .pixels = img, .width = 200, .height = 100, .rotation = 1 };
    for (int builtin = 0; builtin < 2; builtin++) {
        sr_environment *a = NULL, *b = NULL;
        REQUIRE(sr_make_environment(c1, builtin ? NULL : &desc, &a) == SR_OK);
        REQUIRE(sr_make_environment(c2, builtin ? NULL : &desc, &b) == SR_OK);
        int differ = 0;
        for (int n = 0; n < 300; n++) {
            float d[3], x[3], y[3];
            random_direction(d);
            float r = (float)drand();
            sr_environment_specular(a, d, r, x);
            sr_environment_specular(b, d, r, y);
            differ += memcmp(x, y, sizeof x) != 0;
            sr_environment_irradiance(a, d, x);
            sr_environment_irradiance(b, d, y);
            differ += memcmp(x, y, sizeof x) != 0;
        }
        CHECK_EQ(differ, 0);
        sr_destroy_environment(c1, a);
        sr_destroy_environment(c2, b);
    }
    free(img);
    sr_destroy_context(c1);
    sr_destroy_context(c2);
}

SR_TEST(four_lane_queries_equal_the_single_ones)
{
    /* Bit for bit, on random directions and roughnesses and on the edge
     * cases: axes, signed zeros, a zero vector, huge, tiny, infinite and
     * NaN components, roughness outside [0, 1] and NaN. */
    static const float special[][4] = {
        { 1, 0, 0, 0 }, { -1, 0, 0, 1 }, { 0, 1, 0, 0.2f }, { 0, -1, 0, 0.4f },
        { 0, 0, 1, 0.5f }, { 0, 0, -1, 0.99f }, { -0.0f, 0.0f, -1, 0 }, { -1, -0.0f, 0.0f, 0.3f },
        { 0, 0, 0, 0.5f }, { 1e30f, 1e30f, 0, 0.1f }, { 1e-30f, -1e-30f, 1e-30f, 0.7f },
        { INFINITY, 0, 1, 0.6f }, { NAN, 0, 1, 0.6f }, { 0.3f, 0.4f, 0.5f, -2 },
        { 0.3f, -0.4f, 0.5f, 7 }, { -0.3f, 0.4f, -0.5f, NAN },
    };
    sr_context *ctx = make_ctx(1);
    float *img = make_image(64, 32, smooth_sky);
    sr_environment *envs[3] = { NULL, NULL, NULL };
    REQUIRE(sr_make_environment(ctx, NULL, &envs[0]) == SR_OK);
    REQUIRE(sr_make_environment(ctx, &(sr_environment_desc){ .pixels = img, .width = 64,
                                                             .height = 32, .rotation = 2.5f },
                                &envs[1]) == SR_OK);
    REQUIRE(sr_make_environment(ctx, &(sr_environment_desc){ .rotation = -1 }, &envs[2]) == SR_OK);
    int differ = 0;
    for (int e = 0; e < 3; e++) {
        for (int n = 0; n < 2000; n++) {
            sr_vec3x4 d, irr, spec;
            float rough[4];
            for (int i = 0; i < 4; i++) {
                int k = (n * 4 + i) % 64;
                if (n < 8 && k < (int)(sizeof special / sizeof special[0])) {
                    d.x[i] = special[k][0];
                    d.y[i] = special[k][1];
                    d.z[i] = special[k][2];
                    rough[i] = special[k][3];
                } else {
                    float v[3];
                    random_direction(v);
                    d.x[i] = v[0] * 3;
                    d.y[i] = v[1] * 3;
                    d.z[i] = v[2] * 3;
                    rough[i] = (float)drand();
                }
            }
            sr_environment_irradiance4(envs[e], &d, &irr);
            sr_environment_specular4(envs[e], &d, rough, &spec);
            for (int i = 0; i < 4; i++) {
                float v[3] = { d.x[i], d.y[i], d.z[i] }, a[3], b[3];
                sr_environment_irradiance(envs[e], v, a);
                sr_environment_specular(envs[e], v, rough[i], b);
                float la[3] = { irr.x[i], irr.y[i], irr.z[i] };
                float lb[3] = { spec.x[i], spec.y[i], spec.z[i] };
                differ += memcmp(a, la, sizeof a) != 0 || memcmp(b, lb, sizeof b) != 0;
                differ += !(isfinite(b[0]) && b[0] >= 0 && isfinite(a[0]) && a[0] >= 0);
            }
        }
        sr_destroy_environment(ctx, envs[e]);
    }
    CHECK_EQ(differ, 0);
    free(img);
    sr_destroy_context(ctx);
}

/* ---- the built-in studio ----------------------------------------------- */

/* The tables the build computed (tools/ibl_tables.c) are the bytes the
 * library's functions give here: the BRDF table row by row, and the
 * studio's levels and SH those of sr_make_environment given the studio's
 * own image; so is the built-in studio's environment, at intensity 1. */
SR_TEST(builtin_tables_equal_the_runtime_computation)
{
    int rows_differ = 0;
    for (int row = 0; row < SR__BRDF_TABLE_SIZE; row++) {
        float t[SR__BRDF_TABLE_SIZE][2];
        sr__brdf_table_row(row, t);
        rows_differ += memcmp(t, sr__brdf_builtin[row], sizeof t) != 0;
    }
    CHECK_EQ(rows_differ, 0);

    sr_context *ctx = make_ctx(2);
    sr__equirect img = { SR__STUDIO_WIDTH, SR__STUDIO_HEIGHT,
                         malloc(sizeof(float) * 3 * SR__STUDIO_WIDTH * SR__STUDIO_HEIGHT) };
    REQUIRE(img.rgb);
    sr__studio_rows(&img, 0, img.h);
    sr_environment *from_image = NULL, *builtin = NULL;
    REQUIRE(sr_make_environment(ctx, &(sr_environment_desc){ .pixels = img.rgb, .width = img.w,
                                                             .height = img.h }, &from_image) == SR_OK);
    REQUIRE(sr_make_environment(ctx, NULL, &builtin) == SR_OK);
    for (int k = 1; k < SR_ENVIRONMENT_LEVELS; k++) {
        const sr__equirect *a = &from_image->level[k], *b = &builtin->level[k];
        REQUIRE(a->w == b->w && a->h == b->h && a->w == sr__level_width(SR__STUDIO_WIDTH, k));
        size_t n = (size_t)a->w * a->h;
        int differ = memcmp(a->rgb, b->rgb, n * 3 * sizeof(float)) != 0;
        for (size_t i = 0; i < n; i++) {
            differ += a->rgb[3 * i + 1] != sr__studio_builtin_levels[k][i];
        }
        CHECK_EQ(differ, 0);
    }
    CHECK(memcmp(from_image->sh, builtin->sh, sizeof builtin->sh) == 0);
    for (int k = 0; k < 9; k++) {
        CHECK(builtin->sh[k][2] == sr__studio_builtin_sh[k]);
    }
    sr_destroy_environment(ctx, from_image);
    sr_destroy_environment(ctx, builtin);
    free(img.rgb);
    sr_destroy_context(ctx);
}

/* The environment seen through an equirectangular W x H grid at `blur`,
 * tone mapped to RGBA8 rows of out. */
static void render_equirect(sr_context *ctx, const sr_environment *env, float blur, int w, int h,
                            uint8_t *out, size_t out_stride)
{
    float *f = malloc((size_t)w * h * 3 * sizeof *f);
    for (int j = 0; j < h; j++) {
        for (int i = 0; i < w; i++) {
            double phi = (i + 0.5) / w * 2.0 * M_PI - M_PI, theta = (j + 0.5) / h * M_PI;
            float d[3] = { (float)(sin(theta) * cos(phi)), (float)cos(theta),
                           (float)(sin(theta) * sin(phi)) };
            sr_environment_background(env, d, blur, f + ((size_t)j * w + i) * 3);
        }
    }
    sr_tonemap(ctx, f, w, h, 0, out, out_stride, &(sr_tonemap_desc){ .channels = 3 });
    free(f);
}

SR_TEST(builtin_studio_is_a_neutral_lit_room)
{
    sr_context *ctx = make_ctx(2);
    sr_environment *env = NULL;
    REQUIRE(sr_make_environment(ctx, &(sr_environment_desc){0}, &env) == SR_OK);
    const float up[3] = { 0, 1, 0 }, down[3] = { 0, -1, 0 }, front[3] = { 0, 0, 1 };
    float u[3], dn[3], f[3];
    sr_environment_irradiance(env, up, u);
    sr_environment_irradiance(env, down, dn);
    sr_environment_irradiance(env, front, f);
    /* Colourless; lit from above more than from the floor; a white
     * Lambertian surface facing up or the camera comes out light, not
     * blown out. */
    CHECK(u[0] == u[1] && u[1] == u[2]);
    CHECK(u[0] > 1.5f * dn[0]);
    CHECK(u[0] > 0.7f && u[0] < 1.6f);
    CHECK(f[0] > 0.5f && f[0] < 1.3f);
    CHECK(dn[0] > 0.15f);

    /* The picture of each level, one above the other, to look at. */
    enum { W = 256, H = 128, LEVELS = SR_ENVIRONMENT_LEVELS };
    uint8_t *rgba = malloc((size_t)W * H * LEVELS * 4);
    for (int k = 0; k < LEVELS; k++) {
        render_equirect(ctx, env, (float)k / (LEVELS - 1), W, H, rgba + (size_t)k * W * H * 4,
                        W * 4);
    }
    char path[512];
    snprintf(path, sizeof path, "%s/environment_studio_levels.png", sr_test_out_dir());
    sr_io_error err;
    CHECK(sr_write_png(path, W, H * LEVELS, rgba, W * 4, NULL, &err) == SR_OK);
    free(rgba);
    sr_destroy_environment(ctx, env);
    sr_destroy_context(ctx);
}

/* The split sum of docs/ibl.md for a sphere's point with normal n seen
 * along -Z (v = +Z), in linear RGB. */
static void shade(const sr_environment *env, const float n[3], const float base[3],
                  float metallic, float roughness, float out[3])
{
    float nv = n[2] > 1e-4f ? n[2] : 1e-4f;
    float r[3] = { 2 * nv * n[0], 2 * nv * n[1], 2 * nv * n[2] - 1 };
    float e[3], l[3], ab[2];
    sr_environment_irradiance(env, n, e);
    sr_environment_specular(env, r, roughness, l);
    sr_brdf_table(nv, roughness, ab);
    for (int c = 0; c < 3; c++) {
        float f0 = 0.04f + (base[c] - 0.04f) * metallic;
        float es = f0 * ab[0] + ab[1];
        out[c] = (1 - es) * base[c] * (1 - metallic) * e[c] + es * l[c];
    }
}

SR_TEST(builtin_studio_lights_spheres_from_above)
{
    /* Rows: white dielectric, white metal, gold; roughness 0 .. 1 left to
     * right, on the blurred background (tests/out/environment_spheres.png). */
    enum { S = 64, COLS = 6, ROWS = 3, W = S * COLS, H = S * ROWS };
    static const float base[ROWS][3] = { { 1, 1, 1 }, { 1, 1, 1 }, { 1.0f, 0.766f, 0.336f } };
    static const float metal[ROWS] = { 0, 1, 1 };
    sr_context *ctx = make_ctx(2);
    sr_environment *env = NULL;
    REQUIRE(sr_make_environment(ctx, NULL, &env) == SR_OK);
    float *f = malloc((size_t)W * H * 3 * sizeof *f);
    float top_minus_bottom = 0;
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            int row = y / S, col = x / S;
            float sx = ((x % S) + 0.5f) / S * 2 - 1, sy = 1 - ((y % S) + 0.5f) / S * 2;
            float *o = f + ((size_t)y * W + x) * 3;
            float r2 = (sx * sx + sy * sy) / 0.9f / 0.9f;
            if (r2 >= 1) {
                float d[3] = { (x - W / 2.0f) / W, (H / 2.0f - y) / W, -1 };
                sr_environment_background(env, d, 0.6f, o);
                continue;
            }
            float n[3] = { sx / 0.9f, sy / 0.9f, sqrtf(1 - r2) };
            shade(env, n, base[row], metal[row], (float)col / (COLS - 1), o);
            if (row == 1 && col == 0 && (x % S) == S / 2) {
                top_minus_bottom += sy > 0 ? o[0] : -o[0];
            }
        }
    }
    /* A mirror sphere shows the bright ceiling above and the floor below. */
    CHECK(top_minus_bottom > 0);
    uint8_t *rgba = malloc((size_t)W * H * 4);
    REQUIRE(sr_tonemap(ctx, f, W, H, 0, rgba, 0, &(sr_tonemap_desc){ .channels = 3 }) == SR_OK);
    char path[512];
    snprintf(path, sizeof path, "%s/environment_spheres.png", sr_test_out_dir());
    sr_io_error err;
    CHECK(sr_write_png(path, W, H, rgba, W * 4, NULL, &err) == SR_OK);
    free(rgba);
    free(f);
    sr_destroy_environment(ctx, env);
    sr_destroy_context(ctx);
}

/* ---- bad input --------------------------------------------------------- */

SR_TEST(bad_descriptions_are_refused)
{
    sr_context *ctx = make_ctx(1);
    sr_environment *env = (sr_environment *)&env;
    float px[4 * 2 * 3];
    for (int i = 0; i < 24; i++) {
        px[i] = 1;
    }
    CHECK_EQ(sr_make_environment(NULL, NULL, &env), SR_INVALID_ARG);
    CHECK_EQ(sr_make_environment(ctx, NULL, NULL), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "out is NULL");
    CHECK_EQ(sr_make_environment(ctx, &(sr_environment_desc){ .width = 4, .height = 2 }, &env),
             SR_INVALID_ARG);
    CHECK(env == NULL);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "pixels is NULL");
    CHECK_EQ(sr_make_environment(ctx, &(sr_environment_desc){ .pixels = px, .height = 2 }, &env),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "width");
    CHECK_EQ(sr_make_environment(ctx, &(sr_environment_desc){ .pixels = px, .width = 4,
                                                              .height = -2 },
                                 &env),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "height");
    CHECK_EQ(sr_make_environment(ctx, &(sr_environment_desc){ .pixels = px, .width = 40000,
                                                              .height = 2 },
                                 &env),
             SR_TOO_LARGE);
    CHECK_EQ(sr_make_environment(ctx, &(sr_environment_desc){ .pixels = px, .width = 30000,
                                                              .height = 30000 },
                                 &env),
             SR_TOO_LARGE);
    const float bad[] = { NAN, -1.0f, INFINITY, -0.0001f };
    for (size_t b = 0; b < sizeof bad / sizeof bad[0]; b++) {
        px[7] = bad[b];
        CHECK_EQ(sr_make_environment(ctx, &(sr_environment_desc){ .pixels = px, .width = 4,
                                                                  .height = 2 },
                                     &env),
                 SR_INVALID_ARG);
        CHECK_STR_CONTAINS(sr_context_error(ctx), "pixel (2, 0) channel 1");
    }
    px[7] = 1;
    /* The first bad row is named whichever thread finds which. */
    sr_context *ctx2 = make_ctx(2);
    enum { BW = 8, BH = 64 };
    float *big = make_image(BW, BH, white);
    big[(40 * BW + 3) * 3 + 2] = -5;
    big[(9 * BW + 5) * 3 + 0] = NAN;
    big[(60 * BW + 1) * 3 + 1] = INFINITY;
    CHECK_EQ(sr_make_environment(ctx2, &(sr_environment_desc){ .pixels = big, .width = BW,
                                                               .height = BH },
                                 &env),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx2), "pixel (5, 9) channel 0 is nan");
    free(big);
    sr_destroy_context(ctx2);
    CHECK_EQ(sr_make_environment(ctx, &(sr_environment_desc){ .intensity = -1 }, &env),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "intensity");
    CHECK_EQ(sr_make_environment(ctx, &(sr_environment_desc){ .intensity = NAN }, &env),
             SR_INVALID_ARG);
    CHECK_EQ(sr_make_environment(ctx, &(sr_environment_desc){ .rotation = INFINITY }, &env),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "rotation");
    CHECK(env == NULL);
    /* A tiny image is fine. */
    CHECK_EQ(sr_make_environment(ctx, &(sr_environment_desc){ .pixels = px, .width = 1,
                                                              .height = 1 },
                                 &env),
             SR_OK);
    sr_destroy_environment(ctx, env);
    /* Queries on NULL give black, and NULL outputs are ignored. */
    float d[3] = { 0, 1, 0 }, c[3] = { 9, 9, 9 };
    sr_environment_irradiance(NULL, d, c);
    CHECK(c[0] == 0 && c[1] == 0 && c[2] == 0);
    c[0] = 9;
    sr_environment_specular(NULL, d, 0.5f, c);
    CHECK(c[0] == 0);
    sr_environment_specular(NULL, d, 0.5f, NULL);
    sr_brdf_table(0.5f, 0.5f, NULL);
    sr_destroy_environment(ctx, NULL);
    sr_destroy_context(ctx);
}

SR_TEST(sizes_past_the_limits_are_refused_before_any_allocation)
{
    failing f = { .fail_at = -1 };
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){
        .threads = 1, .allocator = { fail_alloc, fail_free, &f } }, &ctx) == SR_OK);
    long before = f.count;
    float px[3] = { 1, 1, 1 };
    static const int sizes[][2] = { { SR_ENVIRONMENT_MAX_SIDE + 1, 1 },
                                    { 1, SR_ENVIRONMENT_MAX_SIDE + 1 },
                                    { 1 << 14, 1 << 14 },
                                    { 0x7fffffff, 0x7fffffff } };
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        sr_environment *env = NULL;
        sr_environment_desc d = { .pixels = px, .width = sizes[i][0], .height = sizes[i][1] };
        CHECK_EQ(sr_make_environment(ctx, &d, &env), SR_TOO_LARGE);
        CHECK(env == NULL);
    }
    CHECK_EQ(f.count, before);
    sr_destroy_context(ctx);
}

SR_TEST(every_allocation_failure_is_reported_cleanly)
{
    float *img = make_image(64, 32, smooth_sky);
    for (int builtin = 0; builtin < 2; builtin++) {
        for (long fail_at = 0;; fail_at++) {
            failing f = { .fail_at = fail_at };
            sr_context *ctx = NULL;
            sr_result r = sr_make_context(&(sr_context_desc){
                .threads = 1, .allocator = { fail_alloc, fail_free, &f } }, &ctx);
            if (r != SR_OK) {
                continue;
            }
            sr_environment *env = NULL;
            r = sr_make_environment(ctx, builtin ? NULL : &(sr_environment_desc){
                .pixels = img, .width = 64, .height = 32 }, &env);
            sr_destroy_environment(ctx, env);
            sr_destroy_context(ctx);
            CHECK_EQ(f.live, 0);
            if (f.failed == 0) {
                CHECK_EQ(r, SR_OK);
                break;
            }
            CHECK_EQ(r, SR_OUT_OF_MEMORY);
        }
    }
    free(img);
}
