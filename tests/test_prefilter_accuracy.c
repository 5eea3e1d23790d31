/* test_prefilter_accuracy.c - the image-based light's prefiltered specular
 * radiance against a brute-force reference: the split sum's prefiltered
 * radiance (Karis 2013, N = V = R) of direction r at roughness rho is
 *
 *     sum L(l) D(h) (r.l) dOmega / sum D(h) (r.l) dOmega,  h = (l + r) / |l + r|,
 *
 * summed in double precision over every texel of the full-resolution
 * image, each at its centre with its exact solid angle, D the GGX
 * distribution of alpha = rho^2.  Two environments: three.js-compare's
 * sky.hdr (tools/threejs-compare/make-assets.mjs: soft overhead box, warm
 * key box, horizon, floor) and a hard case, a small sun 500 times the sky
 * over a bright horizon band.  The levels (roughness 0.2 ... 1) must be
 * within the tolerances below of the reference in every tested direction
 * and channel (docs/ibl.md: what is left is the levels' own resolution,
 * read bilinearly: the sun's peak at 0.2, straight down past the band at
 * 0.8 and 1); between levels a query blends two of them linearly, tested
 * for the sky, whose features are wider than the lobes.  Roughness 0 is
 * the mirror: the source itself. */
#include "softrast.h"
#include "sr_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* The largest relative difference allowed at the levels (roughness 0.2,
 * 0.4, 0.6, 0.8, 1) and, for the sky, between them (0.25, 0.5, 0.75). */
static const double sky_level_tol[5] = { 0.02, 0.025, 0.04, 0.04, 0.04 };
static const double sky_between_tol[3] = { 0.045, 0.09, 0.03 };
static const double sun_level_tol[5] = { 0.09, 0.08, 0.03, 0.13, 0.22 };

typedef void (*radiance_fn)(const double d[3], double out[3]);

static double box(const double d[3], const double c[3], double size)
{
    double dot = d[0] * c[0] + d[1] * c[1] + d[2] * c[2];
    double v = (dot - cos(size)) / 0.02;
    return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v);
}

static void normalize(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= l;
    v[1] /= l;
    v[2] /= l;
}

/* make-assets.mjs's sky(), before its RGBE rounding. */
static void sky(const double d[3], double out[3])
{
    static const double top[3] = { 0, 1, 0 };
    double key[3] = { -1, 0.8, 0.6 };
    normalize(key);
    double up = d[1];
    if (up >= 0) {
        out[0] = 0.3 + 0.1 * up;
        out[1] = 0.33 + 0.15 * up;
        out[2] = 0.38 + 0.25 * up;
    } else {
        out[0] = 0.1 + 0.06 * (1 + up);
        out[1] = 0.09 + 0.06 * (1 + up);
        out[2] = 0.08 + 0.06 * (1 + up);
    }
    double t = box(d, top, 0.35) * 2.5, k = box(d, key, 0.25) * 5;
    out[0] += t + k * 1.0;
    out[1] += t + k * 0.9;
    out[2] += t + k * 0.75;
}

static const double sun_dir[3] = { 0.48, 0.36, -0.8 };   /* unit */

/* A dim blue sky, a dark floor, a bright band 2.3 degrees high along the
 * horizon and a warm sun 2.3 degrees across, 500 times the sky. */
static void sun_and_band(const double d[3], double out[3])
{
    double up = d[1];
    double base = up >= 0 ? 0.2 + 0.2 * up : 0.05;
    out[0] = base;
    out[1] = base * 1.1;
    out[2] = base * 1.4;
    if (fabs(up) < 0.02) {
        out[0] += 4.0;
        out[1] += 3.0;
        out[2] += 2.0;
    }
    double c = d[0] * sun_dir[0] + d[1] * sun_dir[1] + d[2] * sun_dir[2];
    if (c > cos(0.02)) {
        out[0] += 500.0;
        out[1] += 450.0;
        out[2] += 380.0;
    }
}

static void texel_direction(int i, int j, int w, int h, double d[3])
{
    double phi = (i + 0.5) / w * 2.0 * M_PI - M_PI, theta = (j + 0.5) / h * M_PI;
    d[0] = sin(theta) * cos(phi);
    d[1] = cos(theta);
    d[2] = sin(theta) * sin(phi);
}

static float *make_image(int w, int h, radiance_fn f)
{
    float *p = malloc((size_t)w * h * 3 * sizeof *p);
    for (int j = 0; j < h; j++) {
        for (int i = 0; i < w; i++) {
            double d[3], v[3];
            texel_direction(i, j, w, h, d);
            f(d, v);
            for (int c = 0; c < 3; c++) {
                p[((size_t)j * w + i) * 3 + c] = (float)v[c];
            }
        }
    }
    return p;
}

/* The prefiltered radiance of unit direction r at roughness rho, summed
 * over every texel. */
static void reference(const float *img, int w, int h, const double r[3], double rho,
                      double out[3])
{
    double a2 = rho * rho * rho * rho, acc[3] = { 0, 0, 0 }, wsum = 0;
    for (int j = 0; j < h; j++) {
        double omega = 2.0 * M_PI / w * (cos(M_PI * j / h) - cos(M_PI * (j + 1) / h));
        for (int i = 0; i < w; i++) {
            double l[3];
            texel_direction(i, j, w, h, l);
            double rl = r[0] * l[0] + r[1] * l[1] + r[2] * l[2];
            if (rl <= 0.0) {
                continue;
            }
            /* with N = V: (N.H)^2 = (1 + N.L) / 2 */
            double q = (1.0 + rl) / 2.0 * (a2 - 1.0) + 1.0;
            double wt = omega * a2 / (M_PI * q * q) * rl;
            const float *p = img + ((size_t)j * w + i) * 3;
            for (int c = 0; c < 3; c++) {
                acc[c] += wt * p[c];
            }
            wsum += wt;
        }
    }
    for (int c = 0; c < 3; c++) {
        out[c] = acc[c] / wsum;
    }
}

/* The directions tested: the axes, the eight diagonals, the camera's
 * (+Z, what a surface facing a default camera reflects), and for the sun
 * environment its sun, near it, and along and just off the horizon. */
static int test_directions(double dirs[][3], bool with_sun)
{
    static const double fixed[][3] = {
        { 1, 0, 0 },  { -1, 0, 0 }, { 0, 1, 0 },   { 0, -1, 0 },  { 0, 0, 1 },
        { 0, 0, -1 }, { 1, 1, 1 },  { 1, 1, -1 },  { 1, -1, 1 },  { 1, -1, -1 },
        { -1, 1, 1 }, { -1, 1, -1 }, { -1, -1, 1 }, { -1, -1, -1 }, { 0.3, 0.1, 0.95 },
        { -0.8, 0.6, 0.3 }, { -0.2, 0.97, 0.1 },
    };
    int n = 0;
    for (size_t k = 0; k < sizeof fixed / sizeof fixed[0]; k++, n++) {
        for (int c = 0; c < 3; c++) {
            dirs[n][c] = fixed[k][c];
        }
    }
    if (with_sun) {
        static const double near[][3] = {
            { 0.48, 0.36, -0.8 }, { 0.5, 0.4, -0.78 }, { 0.4, 0.2, -0.85 },  { 0.2, 0.36, -0.9 },
            { 0.6, 0.03, -0.8 },  { 0.9, 0.0, 0.3 },   { -0.5, 0.08, 0.85 }, { 0.3, -0.1, -0.95 },
        };
        for (size_t k = 0; k < sizeof near / sizeof near[0]; k++, n++) {
            for (int c = 0; c < 3; c++) {
                dirs[n][c] = near[k][c];
            }
        }
    }
    for (int k = 0; k < n; k++) {
        normalize(dirs[k]);
    }
    return n;
}

/* The largest relative difference between the environment's prefiltered
 * radiance and the reference over the test directions at rho. */
static double worst_error(const sr_environment *env, const float *img, int w, int h, double rho,
                          bool with_sun, double *lo, double *hi)
{
    double dirs[32][3];
    int n = test_directions(dirs, with_sun);
    double worst = 0.0;
    *lo = INFINITY;
    *hi = -INFINITY;
    for (int k = 0; k < n; k++) {
        double ref[3];
        reference(img, w, h, dirs[k], rho, ref);
        float d[3] = { (float)dirs[k][0], (float)dirs[k][1], (float)dirs[k][2] }, got[3];
        sr_environment_specular(env, d, (float)rho, got);
        for (int c = 0; c < 3; c++) {
            double ratio = got[c] / ref[c];
            *lo = fmin(*lo, ratio);
            *hi = fmax(*hi, ratio);
            worst = fmax(worst, fabs(ratio - 1.0));
        }
    }
    return worst;
}

/* WebAssembly has one thread. */
#if defined(__EMSCRIPTEN__)
#define PREFILTER_THREADS 1
#else
#define PREFILTER_THREADS 2
#endif

static void check_environment(const char *name, radiance_fn f, int w, int h, bool with_sun,
                              const double *level_tol, const double *between_tol)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = PREFILTER_THREADS }, &ctx) == SR_OK);
    float *img = make_image(w, h, f);
    REQUIRE(img);
    sr_environment *env = NULL;
    REQUIRE(sr_make_environment(ctx, &(sr_environment_desc){ .pixels = img, .width = w, .height = h },
                                &env) == SR_OK);
    /* the mirror reads the source: texel centres give the texels */
    int mirror_off = 0;
    for (int k = 0; k < 64; k++) {
        int i = (k * 37 + 5) % w, j = (k * 11 + 3) % h;
        double d[3];
        texel_direction(i, j, w, h, d);
        float dir[3] = { (float)d[0], (float)d[1], (float)d[2] }, got[3];
        sr_environment_specular(env, dir, 0.0f, got);
        const float *p = img + ((size_t)j * w + i) * 3;
        for (int c = 0; c < 3; c++) {
            mirror_off += fabsf(got[c] - p[c]) > 1e-3f * p[c];
        }
    }
    CHECK_EQ(mirror_off, 0);
    static const double levels[] = { 0.2, 0.4, 0.6, 0.8, 1.0 };
    static const double between[] = { 0.25, 0.5, 0.75 };
    for (int pass = 0; pass < 2; pass++) {
        const double *rho = pass ? between : levels;
        int count = pass ? 3 : 5;
        if (pass && !between_tol) {
            break;
        }
        for (int k = 0; k < count; k++) {
            double lo, hi;
            double err = worst_error(env, img, w, h, rho[k], with_sun, &lo, &hi);
            printf("%s roughness %.2f: prefiltered / reference %.3f .. %.3f\n", name, rho[k], lo,
                   hi);
            CHECK(err <= (pass ? between_tol[k] : level_tol[k]));
        }
    }
    sr_destroy_environment(ctx, env);
    sr_destroy_context(ctx);
    free(img);
}

SR_TEST(sky_levels_match_the_brute_force_integral)
{
    check_environment("sky.hdr", sky, 256, 128, false, sky_level_tol, sky_between_tol);
}

SR_TEST(sun_and_horizon_band_levels_match_the_brute_force_integral)
{
    check_environment("sun and band", sun_and_band, 512, 256, true, sun_level_tol, NULL);
}
