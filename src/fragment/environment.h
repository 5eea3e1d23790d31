/* environment.h - image-based light, shared by the files that make an
 * environment (environment.c, environment_prefilter.c,
 * environment_studio.c), the BRDF table (brdf_table.c, brdf_integrate.c)
 * and the build's table generator (tools/ibl_tables.c): equirectangular
 * images of linear RGB, sampled bilinearly with fast polynomial
 * arc functions.  Internal to the library; every function here is pure and
 * may run on any thread. */
#ifndef SR_FRAGMENT_ENVIRONMENT_H
#define SR_FRAGMENT_ENVIRONMENT_H

#include "softrast.h"

#include <math.h>

#define SR__PI_D 3.14159265358979323846
#define SR__PI ((float)SR__PI_D)

/* An equirectangular image: w x h pixels of 3 floats, row 0 at +Y. */
typedef struct sr__equirect {
    int w, h;
    float *rgb;
} sr__equirect;

/* Mips of the source, each texel the mean over its solid angle, down to
 * SR__MIP_MIN_WIDTH wide; the first is the source itself when it is
 * sr__mip_base_width x half that, else the source resampled to that size
 * (at most 2 * SR__SPLIT_MAX wide). */
#define SR__ENV_MAX_MIPS    16
#define SR__MIP_MIN_WIDTH   8
/* The SH are projected from the first mip at most this wide. */
#define SR__SH_MAX_WIDTH    64
/* The widest specular level (the first, for a source twice as wide). */
#define SR__LEVEL_MAX_WIDTH 256
/* The narrowest: a GGX lobe of roughness 0.2 spans a few degrees, a
 * texel of a 256-wide image 1.4. */
#define SR__LEVEL_MIN_WIDTH 32
/* The built-in studio's source image: soft enough that this resolution
 * holds all of it. */
#define SR__STUDIO_WIDTH    256
#define SR__STUDIO_HEIGHT   128

/* The first mip's width for a source w wide: a power of two (the levels'
 * and the mips' widths then divide each other), at most w, at least 64. */
static inline int sr__mip_base_width(int w)
{
    int b = 64;
    while (b <= w / 2 && b < (1 << 30)) {
        b *= 2;
    }
    return b;
}

/* How many mips a first mip w pixels wide has, itself included. */
static inline int sr__mip_count(int w)
{
    int mips = 1;
    while (mips < SR__ENV_MAX_MIPS && w > SR__MIP_MIN_WIDTH) {
        w /= 2;
        mips++;
    }
    return mips;
}

/* The mip the SH are projected from, of `mips` of a source w wide. */
static inline int sr__sh_mip(int w, int mips)
{
    int m = 0;
    while (m + 1 < mips && (w >> m) > SR__SH_MAX_WIDTH) {
        m++;
    }
    return m;
}

/* The width of specular level k >= 1 (its height is half of it) for a
 * source w wide: half the first mip's, at most SR__LEVEL_MAX_WIDTH, each
 * next level half as wide, down to SR__LEVEL_MIN_WIDTH. */
static inline int sr__level_width(int w, int k)
{
    int b = sr__mip_base_width(w) / 2;
    int first = b < SR__LEVEL_MAX_WIDTH ? b : SR__LEVEL_MAX_WIDTH;
    int lw = first >> (k - 1);
    return lw > SR__LEVEL_MIN_WIDTH ? lw : SR__LEVEL_MIN_WIDTH;
}

struct sr_environment {
    /* level[0] is the source (times the intensity; none for the built-in
     * studio); level[k] the radiance prefiltered for roughness
     * k / (SR_ENVIRONMENT_LEVELS - 1). */
    sr__equirect level[SR_ENVIRONMENT_LEVELS];
    float sh[9][3];             /* irradiance / pi, Lambert-convolved, in image space */
    float cos_rot, sin_rot;     /* world -> image: rotation by -desc.rotation about +Y */
    /* The built-in studio's level 0 is its function, sharp at any size,
     * times this intensity; 0 for an image. */
    float studio_intensity;
    /* Different for every environment the process makes (from 1): what
     * caches of maps made from it key on, where an address may be reused. */
    uint64_t serial;
};

/* atan(x) for |x| <= 1: Abramowitz and Stegun 4.4.49-style odd
 * polynomial, absolute error below 1e-5 rad (a texel of a 32768-wide
 * image is 2e-4 rad). */
static inline float sr__atan_unit(float x)
{
    float x2 = x * x;
    return x * (0.99986602f +
                x2 * (-0.33029950f + x2 * (0.18014100f + x2 * (-0.08513300f + x2 * 0.02083510f))));
}

static inline float sr__atan2(float y, float x)
{
    float ax = fabsf(x), ay = fabsf(y);
    float mx = ax > ay ? ax : ay, mn = ax > ay ? ay : ax;
    /* select, then divide: a division under a condition keeps the
     * compiler from vectorizing the lanes */
    float a = sr__atan_unit(mn / (mx > 0.0f ? mx : 1.0f));
    a = ay > ax ? 0.5f * SR__PI - a : a;
    a = x < 0.0f ? SR__PI - a : a;
    return y < 0.0f ? -a : a;
}

/* acos(x) for x in [-1, 1]: A&S 4.4.46, error below 2e-8 rad before rounding. */
static inline float sr__acos(float x)
{
    float ax = fabsf(x);
    ax = ax < 1.0f ? ax : 1.0f;
    float p = -0.0012624911f;
    p = p * ax + 0.0066700901f;
    p = p * ax - 0.0170881256f;
    p = p * ax + 0.0308918810f;
    p = p * ax - 0.0501743046f;
    p = p * ax + 0.0889789874f;
    p = p * ax - 0.2145988016f;
    p = p * ax + 1.5707963050f;
    float r = sqrtf(1.0f - ax) * p;
    return x < 0.0f ? SR__PI - r : r;
}

/* Bilinear sample at pixel coordinates (px, py): wraps in x, clamps in y. */
static inline void sr__equirect_bilinear(const sr__equirect *e, float px, float py, float out[3])
{
    float fx = px - 0.5f, fy = py - 0.5f;
    float x0f = floorf(fx), y0f = floorf(fy);
    float ax = fx - x0f, ay = fy - y0f;
    /* px in [0, w] (u in [0, 1]) puts x0 in [-1, w - 1]; other callers'
     * px may lie anywhere */
    int x0 = (int)x0f;
    if (x0 < -1 || x0 >= e->w) {
        x0 %= e->w;
    }
    x0 = x0 < 0 ? x0 + e->w : x0;
    int x1 = x0 + 1 == e->w ? 0 : x0 + 1;
    int y0 = (int)y0f, y1 = y0 + 1;
    y0 = y0 < 0 ? 0 : (y0 >= e->h ? e->h - 1 : y0);
    y1 = y1 < 0 ? 0 : (y1 >= e->h ? e->h - 1 : y1);
    const float *r0 = e->rgb + (size_t)y0 * e->w * 3, *r1 = e->rgb + (size_t)y1 * e->w * 3;
    float w00 = (1 - ax) * (1 - ay), w10 = ax * (1 - ay), w01 = (1 - ax) * ay, w11 = ax * ay;
    for (int c = 0; c < 3; c++) {
        out[c] = w00 * r0[x0 * 3 + c] + w10 * r0[x1 * 3 + c] + w01 * r1[x0 * 3 + c] +
                 w11 * r1[x1 * 3 + c];
    }
}

/* The unit direction through the centre of pixel (i, j) of a w x h image. */
static inline void sr__equirect_direction(int i, int j, int w, int h, float d[3])
{
    float phi = ((float)i + 0.5f) / (float)w * 2.0f * SR__PI - SR__PI;
    float theta = ((float)j + 0.5f) / (float)h * SR__PI;
    float st = sinf(theta);
    d[0] = st * cosf(phi);
    d[1] = cosf(theta);
    d[2] = st * sinf(phi);
}

/* The built-in neutral studio (environment_studio.c): its radiance in a
 * unit direction, and rows [row0, row1) of it as a w x h image. */
float sr__studio_radiance(const float d[3]);
void sr__studio_rows(sr__equirect *e, int row0, int row1);

/* environment_prefilter.c: the 9 Lambert-convolved SH coefficients
 * (divided by pi) of an image, and their value at a unit direction. */
void sr__irradiance_sh(const sr__equirect *e, float sh[9][3]);
void sr__irradiance_eval(const float sh[9][3], const float d[3], float out[3]);
void sr__irradiance_eval4(const float sh[9][3], const sr_vec3x4 *d, sr_vec3x4 *out);
/* Rows [row0, row1) of dst, src resampled to dst's size: each texel the
 * mean of src over its solid angle. */
void sr__equirect_resample(const sr__equirect *src, sr__equirect *dst, int row0, int row1);
/* The same for dst exactly half of src each way: 2 x 2 texels, the rows
 * weighed by their solid angles. */
void sr__equirect_halve(const sr__equirect *src, sr__equirect *dst, int row0, int row1);

/* A specular level is the source convolved with the GGX lobe, summed
 * over mip texels by scales: the lobe's core within `radius` of R on a
 * fine mip, then rings out to twice each radius on mips four times
 * coarser, the last (radius infinite) out to the horizon; smooth windows
 * split the lobe between them.  SR__PREFILTER_TEXELS: the core's mip's
 * texels at most this times alpha apart; SR__PREFILTER_RING: a scale's
 * radius in texels of its mip. */
#define SR__SPEC_SCALES      6
#define SR__PREFILTER_TEXELS 0.35f
#define SR__PREFILTER_RING   8.0f
/* The widest mip a level reads: its core's for roughness 0.2 (texels 0.35
 * alpha = 0.014 apart need 512 columns). */
#define SR__SPLIT_MAX        512
typedef struct sr__spec_plan {
    float a2;                   /* alpha^2 */
    /* the instruction set of its sums: SR_SIMD_BASE from sr__specular_plan,
     * the context's by sr_make_environment; the same floats at any */
    sr_simd_level simd;
    int scales;
    struct {
        int mip;
        float radius;
    } scale[SR__SPEC_SCALES];
} sr__spec_plan;
/* The scales of the level for `roughness` from `mips` mips. */
void sr__specular_plan(float roughness, const sr__equirect *mip, int mips, sr__spec_plan *p);
/* Rows [row0, row1) of a specular level from the source's mips. */
void sr__prefilter_rows(const sr__equirect *mip, const sr__spec_plan *p, sr__equirect *dst,
                        int row0, int row1);

/* The split-sum BRDF table: SR__BRDF_TABLE_SIZE nodes along N.V and
 * along roughness, each the (scale, bias) of F0; row `row` (one
 * roughness) computed by GGX importance sampling (brdf_integrate.c). */
#define SR__BRDF_TABLE_SIZE 32
void sr__brdf_table_row(int row, float out[SR__BRDF_TABLE_SIZE][2]);
/* The table read bilinearly on four lanes, inputs clamped to 0..1 (NaN
 * to 0), unchecked: the PBR program's split sum (brdf_table.c). */
void sr__brdf_lookup4(const float n_dot_v[4], const float roughness[4], float scale[4],
                      float bias[4]);

/* Computed at build time (ibl_tables.c, written by tools/ibl_tables.c
 * with the functions above): the BRDF table, [roughness][n_dot_v]; the
 * built-in studio prefiltered at intensity 1, one channel a texel (it is
 * grey), each specular level k >= 1 sr__level_width(SR__STUDIO_WIDTH, k)
 * wide (level 0 is NULL: the studio's own function), and its irradiance
 * SH, one channel each. */
extern const float sr__brdf_builtin[SR__BRDF_TABLE_SIZE][SR__BRDF_TABLE_SIZE][2];
extern const float *const sr__studio_builtin_levels[SR_ENVIRONMENT_LEVELS];
extern const float sr__studio_builtin_sh[9];

/* GGX sampling for the BRDF table (brdf_integrate.c): the half vector of
 * the 2D point (e1, e2) in [0, 1)^2 for alpha, in tangent space (z along N). */
static inline void sr__ggx_half_vector(float e1, float e2, float alpha, float h[3])
{
    float a2 = alpha * alpha;
    float cos_t = sqrtf((1.0f - e2) / (1.0f + (a2 - 1.0f) * e2));
    float sin_t = sqrtf(fmaxf(0.0f, 1.0f - cos_t * cos_t));
    float phi = 2.0f * SR__PI * e1;
    h[0] = sin_t * cosf(phi);
    h[1] = sin_t * sinf(phi);
    h[2] = cos_t;
}

/* Van der Corput's radical inverse in base 2: the Hammersley set's second
 * coordinate. */
static inline float sr__radical_inverse(unsigned bits)
{
    bits = (bits << 16) | (bits >> 16);
    bits = ((bits & 0x55555555u) << 1) | ((bits & 0xAAAAAAAAu) >> 1);
    bits = ((bits & 0x33333333u) << 2) | ((bits & 0xCCCCCCCCu) >> 2);
    bits = ((bits & 0x0F0F0F0Fu) << 4) | ((bits & 0xF0F0F0F0u) >> 4);
    bits = ((bits & 0x00FF00FFu) << 8) | ((bits & 0xFF00FF00u) >> 8);
    return (float)bits * 2.3283064365386963e-10f;
}

#endif
