/* environment_prefilter.c - image-based light's precomputation (fragment
 * stage, docs/ibl.md): an environment image's diffuse irradiance as
 * spherical harmonics, and its radiance convolved with the GGX lobe of
 * each roughness level under the split sum's N = V = R assumption.
 * Called by sr_make_environment, and by the build for the built-in studio
 * (tools/ibl_tables.c); the levels are written by bands of rows on the
 * context's threads, each texel on its own, so the floats do not depend
 * on the thread count.
 */
#include "fragment/environment.h"
#include "simd_types.h"

#include <assert.h>
#include <string.h>

/* ---- irradiance -------------------------------------------------------- */

/* Real spherical harmonics up to order 2 at a unit direction. */
static void sh_basis(const float d[3], float y[9])
{
    float x = d[0], yy = d[1], z = d[2];
    y[0] = 0.282095f;
    y[1] = 0.488603f * yy;
    y[2] = 0.488603f * z;
    y[3] = 0.488603f * x;
    y[4] = 1.092548f * x * yy;
    y[5] = 1.092548f * yy * z;
    y[6] = 0.315392f * (3.0f * z * z - 1.0f);
    y[7] = 1.092548f * x * z;
    y[8] = 0.546274f * (x * x - yy * yy);
}

void sr__irradiance_sh(const sr__equirect *e, float sh[9][3])
{
    double acc[9][3] = { { 0 } };
    for (int j = 0; j < e->h; j++) {
        /* the exact solid angle of a texel of this row */
        double t0 = SR__PI_D * j / e->h, t1 = SR__PI_D * (j + 1) / e->h;
        double d_omega = 2.0 * SR__PI_D / e->w * (cos(t0) - cos(t1));
        const float *p = e->rgb + (size_t)j * e->w * 3;
        for (int i = 0; i < e->w; i++) {
            float d[3], y[9];
            sr__equirect_direction(i, j, e->w, e->h, d);
            sh_basis(d, y);
            for (int k = 0; k < 9; k++) {
                for (int c = 0; c < 3; c++) {
                    acc[k][c] += d_omega * y[k] * p[3 * i + c];
                }
            }
        }
    }
    /* Ramamoorthi and Hanrahan's convolution with the clamped cosine,
     * A_l = pi, 2 pi / 3, pi / 4, then divided by pi for E / pi. */
    static const float band_scale[9] = { 1.0f,        2.0f / 3.0f, 2.0f / 3.0f,
                                         2.0f / 3.0f, 0.25f,       0.25f,
                                         0.25f,       0.25f,       0.25f };
    for (int k = 0; k < 9; k++) {
        for (int c = 0; c < 3; c++) {
            sh[k][c] = (float)acc[k][c] * band_scale[k];
        }
    }
}

/* sh_basis's terms summed, branch-free per lane: the 4-lane loop
 * vectorizes and a single lane gives the same floats. */
static inline float sh_sum(const float sh[9][3], int c, float x, float y, float z)
{
    float v = sh[0][c] * 0.282095f;
    v += sh[1][c] * (0.488603f * y);
    v += sh[2][c] * (0.488603f * z);
    v += sh[3][c] * (0.488603f * x);
    v += sh[4][c] * (1.092548f * x * y);
    v += sh[5][c] * (1.092548f * y * z);
    v += sh[6][c] * (0.315392f * (3.0f * z * z - 1.0f));
    v += sh[7][c] * (1.092548f * x * z);
    v += sh[8][c] * (0.546274f * (x * x - y * y));
    /* a high-contrast image's truncated series can dip below zero */
    return v > 0.0f ? v : 0.0f;
}

void sr__irradiance_eval(const float sh[9][3], const float d[3], float out[3])
{
    for (int c = 0; c < 3; c++) {
        out[c] = sh_sum(sh, c, d[0], d[1], d[2]);
    }
}

void sr__irradiance_eval4(const float sh[9][3], const sr_vec3x4 *d, sr_vec3x4 *out)
{
    for (int i = 0; i < 4; i++) {
        out->x[i] = sh_sum(sh, 0, d->x[i], d->y[i], d->z[i]);
    }
    for (int i = 0; i < 4; i++) {
        out->y[i] = sh_sum(sh, 1, d->x[i], d->y[i], d->z[i]);
    }
    for (int i = 0; i < 4; i++) {
        out->z[i] = sh_sum(sh, 2, d->x[i], d->y[i], d->z[i]);
    }
}

/* ---- source mips ------------------------------------------------------- */

/* The solid angle of the rows of an h-row image between t0 and t1 (rows,
 * fractional), per unit of u: the mips and the prefilter weigh texels by
 * it, since a polar row covers far less of the sphere than the equator's. */
static double band_omega(double t0, double t1, int h)
{
    return cos(SR__PI_D * t0 / h) - cos(SR__PI_D * t1 / h);
}

/* min and max as comparisons, for coordinates (never NaN): fmin and
 * fmax are library calls. */
static inline double min_d(double a, double b)
{
    return a < b ? a : b;
}

static inline double max_d(double a, double b)
{
    return a > b ? a : b;
}

void sr__equirect_resample(const sr__equirect *src, sr__equirect *dst, int row0, int row1)
{
    /* A row's sums side by side, source row by source row, so that each
     * row's solid angle is computed once a level row rather than once a
     * texel; each texel still sums its source texels row by row. */
    assert(dst->w <= 2 * SR__SPLIT_MAX);
    double acc[2 * SR__SPLIT_MAX][4];
    double sx = (double)src->w / dst->w, sy = (double)src->h / dst->h;
    for (int j = row0; j < row1; j++) {
        double t0 = j * sy, t1 = (j + 1) * sy;
        memset(acc, 0, sizeof(acc[0]) * (size_t)dst->w);
        for (int y = (int)t0; y < src->h && y < t1; y++) {
            double wy = band_omega(max_d(t0, y), min_d(t1, y + 1), src->h);
            const float *r = src->rgb + (size_t)y * src->w * 3;
            for (int i = 0; i < dst->w; i++) {
                double u0 = i * sx, u1 = (i + 1) * sx, *a = acc[i];
                for (int x = (int)u0; x < src->w && x < u1; x++) {
                    double wt = wy * (min_d(u1, x + 1) - max_d(u0, x));
                    for (int c = 0; c < 3; c++) {
                        a[c] += wt * r[3 * x + c];
                    }
                    a[3] += wt;
                }
            }
        }
        float *o = dst->rgb + (size_t)j * dst->w * 3;
        for (int i = 0; i < dst->w; i++) {
            for (int c = 0; c < 3; c++) {
                o[3 * i + c] = (float)(acc[i][c] / acc[i][3]);
            }
        }
    }
}

void sr__equirect_halve(const sr__equirect *src, sr__equirect *dst, int row0, int row1)
{
    assert(src->w == 2 * dst->w && src->h == 2 * dst->h);
    for (int j = row0; j < row1; j++) {
        /* each texel the mean over its solid angle: the two source rows
         * weighed by theirs */
        double o0 = band_omega(2 * j, 2 * j + 1, src->h), o1 = band_omega(2 * j + 1, 2 * j + 2, src->h);
        float w0 = (float)(0.5 * o0 / (o0 + o1)), w1 = (float)(0.5 * o1 / (o0 + o1));
        const float *r0 = src->rgb + (size_t)(2 * j) * src->w * 3;
        const float *r1 = r0 + (size_t)src->w * 3;
        float *o = dst->rgb + (size_t)j * dst->w * 3;
        for (int i = 0; i < dst->w; i++) {
            for (int c = 0; c < 3; c++) {
                o[3 * i + c] = w0 * (r0[6 * i + c] + r0[6 * i + 3 + c]) +
                               w1 * (r1[6 * i + c] + r1[6 * i + 3 + c]);
            }
        }
    }
}

/* ---- specular levels --------------------------------------------------- */

/* The angle between two texel centres of mip m: what its texels resolve. */
static float texel_angle(const sr__equirect *m)
{
    return SR__PI / (float)m->h;
}

void sr__specular_plan(float roughness, const sr__equirect *mip, int mips, sr__spec_plan *p)
{
    float alpha = roughness * roughness;
    p->a2 = alpha * alpha;
    p->simd = SR_SIMD_BASE;
    /* The lobe's core (half its peak within about 1.3 alpha of R) on the
     * coarsest mip that resolves it, but never coarser than 128 x 64;
     * then wider and wider rings of the long GGX tail, each on a mip four
     * times coarser, but for a wide lobe never coarser than 128 x 64: a
     * texel's radiance counts at its centre, and a small bright source's
     * weight must not move much across one, even where N.L falls to 0. */
    float fine = fminf(SR__PREFILTER_TEXELS * alpha, SR__PI / 64.0f);
    int m = 0;
    while (m + 1 < mips && (texel_angle(&mip[m + 1]) <= fine || mip[m].w > SR__SPLIT_MAX)) {
        m++;
    }
    /* A narrow lobe's far tail is faint even at the horizon (for roughness
     * 0.4 under 0.3% of its peak at 90 degrees): coarser rings there. */
    float coarsest = alpha < 0.2f ? SR__PI / 16.0f : SR__PI / 64.0f;
    int n = 0;
    for (;;) {
        float radius = SR__PREFILTER_RING * texel_angle(&mip[m]);
        int next = m + 2 < mips ? m + 2 : mips - 1;
        while (next > m && texel_angle(&mip[next]) > coarsest) {
            next--;
        }
        p->scale[n].mip = m;
        /* N.L is 0 at a quarter turn: a window reaching that far is the
         * last */
        bool last = 2.0f * radius >= 0.5f * SR__PI || next == m || n + 1 == SR__SPEC_SCALES;
        p->scale[n].radius = last ? INFINITY : radius;
        n++;
        if (last) {
            break;
        }
        m = next;
    }
    p->scales = n;
}

/* 1 within `radius` of R, 0 beyond twice it, smooth between: the scales'
 * windows, which add up to 1 everywhere. */
static float window(float theta, float radius)
{
    if (theta <= radius) {
        return 1.0f;
    }
    float x = (theta - radius) / radius;
    return x >= 1.0f ? 0.0f : 1.0f - x * x * (3.0f - 2.0f * x);
}

/* A scale's window() as a function of the cosine of the angle: beyond
 * the cosines of 0.999 radius and of 2.002 radius it is 1 or 0 whatever
 * acosf's rounding (below 1e-6 of the angle), so the arc cosine is
 * needed only between them, for the same floats. */
typedef struct {
    float radius;
    double one, zero;   /* c above `one`: 1; below `zero`: 0 */
} cos_window;

static cos_window make_cos_window(float radius)
{
    cos_window w = { radius, -2.0, -2.0 };
    if (isfinite(radius)) {
        w.one = cos(0.999 * radius);
        if (2.002 * radius < SR__PI_D) {
            w.zero = cos(2.002 * radius);
        }
    }
    return w;
}

static float window_cos(float c, const cos_window *w)
{
    if (c > w->one) {
        return 1.0f;
    }
    if (c < w->zero) {
        return 0.0f;
    }
    return window(acosf(fminf(c, 1.0f)), w->radius);
}

/* Source row `row` (w texels) as `step` rows of its columns r, r + step,
 * ..., each twice over (2 * count texels, count = w / step), so that the
 * texels from column x on are one run: rows[x % step] + 3 * (x / step). */
static void split_row(const float *restrict row, int w, int step, float *restrict rows)
{
    int count = w / step;
    size_t half = (size_t)3 * count;
    for (int r = 0; r < step; r++) {
        float *o = rows + (size_t)r * 2 * half;
        if (step == 1) {
            memcpy(o, row, sizeof(float) * half);
        } else {
            for (int q = 0; q < count; q++) {
                memcpy(o + 3 * q, row + 3 * (r + step * q), sizeof(float) * 3);
            }
        }
        memcpy(o + half, o, sizeof(float) * half);
    }
}

#define PF_RUNS_FN     add_runs
#define PF_RUNS_TARGET
#define PF_RUNS_V      v4f
#include "fragment/prefilter_runs.h"
#undef PF_RUNS_FN
#undef PF_RUNS_TARGET
#undef PF_RUNS_V

#if defined(__x86_64__) || defined(__i386__)
#define PF_RUNS_FN     add_runs_avx2
#define PF_RUNS_TARGET __attribute__((target("avx2")))
#define PF_RUNS_V      v8f
#include "fragment/prefilter_runs.h"
#undef PF_RUNS_FN
#undef PF_RUNS_TARGET
#undef PF_RUNS_V
#endif

static void add_runs_at(sr_simd_level simd, float *restrict o, int n, const float *restrict w,
                        const float *const *restrict src, int runs)
{
#if defined(__x86_64__) || defined(__i386__)
    if (simd >= SR_SIMD_AVX2) {
        add_runs_avx2(o, n, w, src, runs);
        return;
    }
#endif
    (void)simd;
    add_runs(o, n, w, src, runs);
}

void sr__prefilter_rows(const sr__equirect *mip, const sr__spec_plan *p, sr__equirect *dst,
                        int row0, int row1)
{
    assert(dst->w <= SR__LEVEL_MAX_WIDTH);
    float sum[SR__LEVEL_MAX_WIDTH * 3], part[SR__LEVEL_MAX_WIDTH * 3];
    float split[SR__SPLIT_MAX * 6];
    double wsum[SR__LEVEL_MAX_WIDTH], phase_w[SR__LEVEL_MAX_WIDTH];
    /* a row's runs: their weights and where they start */
    float run_w[SR__SPLIT_MAX];
    const float *run_src[SR__SPLIT_MAX];
    /* cos of the longitude from texel ph of a level row to source column
     * x, [s][ph * w + x]: the same for every row */
    static_assert(SR__LEVEL_MAX_WIDTH <= SR__SPLIT_MAX, "a scale's cosines fit its table");
    double cos_dphi[SR__SPEC_SCALES][SR__SPLIT_MAX];
    /* where in split_row's rows the run of source column x starts */
    int run_at[SR__SPEC_SCALES][SR__SPLIT_MAX];
    for (int s = 0; s < p->scales; s++) {
        const sr__equirect *m = &mip[p->scale[s].mip];
        assert(m->w <= SR__SPLIT_MAX);
        int phases = dst->w > m->w ? dst->w / m->w : 1;
        int step = m->w > dst->w ? m->w / dst->w : 1, count = dst->w / phases;
        for (int x = 0; x < m->w; x++) {
            run_at[s][x] = (x % step) * 6 * count + 3 * (x / step);
        }
        for (int ph = 0; ph < phases; ph++) {
            for (int x = 0; x < m->w; x++) {
                double d = 2.0 * SR__PI_D * ((x + 0.5) / m->w - (ph + 0.5) / dst->w);
                cos_dphi[s][ph * m->w + x] = cos(d);
            }
        }
    }
    const float a2 = p->a2;
    for (int j = row0; j < row1; j++) {
        /* Texels of a row differ only by a rotation about +Y, and the
         * widths of the level and of the mips are powers of two: a source
         * texel weighs in texel i of the row what the texel `step` columns
         * on weighs in texel i + `phases`.  So each source texel's weight
         * is computed once a phase and added along the whole row. */
        memset(sum, 0, sizeof(float) * 3 * (size_t)dst->w);
        memset(wsum, 0, sizeof(double) * (size_t)dst->w);
        double theta_n = SR__PI_D * (j + 0.5) / dst->h;
        double cn = cos(theta_n), sn = sin(theta_n);
        for (int s = 0; s < p->scales; s++) {
            const sr__equirect *m = &mip[p->scale[s].mip];
            float radius = p->scale[s].radius;
            cos_window outer_w = make_cos_window(radius),
                       inner_w = make_cos_window(s > 0 ? p->scale[s - 1].radius : 0.0f);
            /* beyond 90 degrees N.L is negative: nothing */
            double reach = fmin(2.0 * radius, 0.5 * SR__PI_D);
            double cos_reach = cos(reach);
            int phases = dst->w > m->w ? dst->w / m->w : 1;
            int step = m->w > dst->w ? m->w / dst->w : 1;
            int count = dst->w / phases;
            memset(phase_w, 0, sizeof(double) * (size_t)phases);
            /* part: texel q * phases + ph of the row at 3 * (ph * count + q) */
            memset(part, 0, sizeof(float) * 3 * (size_t)dst->w);
            for (int y = 0; y < m->h; y++) {
                double theta = SR__PI_D * (y + 0.5) / m->h;
                if (fabs(theta - theta_n) > reach) {
                    continue;
                }
                double ct = cos(theta), st = sin(theta);
                /* the columns within `reach` of N: cos(dphi) >= k */
                double k = (cos_reach - cn * ct) / (sn * st);
                double dphi = k <= -1.0 ? SR__PI_D : acos(fmin(k, 1.0));
                int half = (int)(dphi / (2.0 * SR__PI_D) * m->w) + 2;
                float omega = (float)(2.0 * SR__PI_D / m->w * band_omega(y, y + 1, m->h));
                int split_done = 0;
                for (int ph = 0; ph < phases; ph++) {
                    /* the source column nearest texel ph of the level row */
                    double centre = (ph + 0.5) / dst->w * m->w - 0.5;
                    int x0 = (int)floor(centre) - half, x1 = (int)floor(centre) + 1 + half;
                    if (x1 - x0 + 1 >= m->w) {
                        x0 = 0;
                        x1 = m->w - 1;
                    }
                    const double *cos_d = cos_dphi[s] + (size_t)ph * m->w;
                    int runs = 0;
                    for (int xx = x0; xx <= x1; xx++) {
                        int x = xx < 0 ? xx + m->w : (xx >= m->w ? xx - m->w : xx);
                        float c = (float)(cn * ct + sn * st * cos_d[x]);
                        if (c <= (float)cos_reach || c <= 0.0f) {
                            continue;
                        }
                        float piece = window_cos(c, &outer_w) -
                                      (s > 0 ? window_cos(c, &inner_w) : 0.0f);
                        /* GGX D of the half vector; with N = V, (N.H)^2 = (1 + N.L) / 2 */
                        float q = 0.5f * (1.0f + c) * (a2 - 1.0f) + 1.0f;
                        float wt = omega * piece * a2 / (SR__PI * q * q) * c;
                        if (wt <= 0.0f) {
                            continue;
                        }
                        if (!split_done) {
                            split_row(m->rgb + (size_t)y * m->w * 3, m->w, step, split);
                            split_done = 1;
                        }
                        phase_w[ph] += wt;
                        /* its share in every texel of the row: one run */
                        run_w[runs] = wt;
                        run_src[runs++] = split + run_at[s][x];
                    }
                    add_runs_at(p->simd, part + (size_t)ph * 3 * count, 3 * count, run_w, run_src,
                                runs);
                }
            }
            for (int i = 0; i < dst->w; i++) {
                int ph = i % phases, q = i / phases;
                wsum[i] += phase_w[ph];
                for (int c = 0; c < 3; c++) {
                    sum[3 * i + c] += part[3 * (ph * count + q) + c];
                }
            }
        }
        float *o = dst->rgb + (size_t)j * dst->w * 3;
        for (int i = 0; i < dst->w; i++) {
            float inv = (float)(1.0 / wsum[i]);
            for (int c = 0; c < 3; c++) {
                o[3 * i + c] = sum[3 * i + c] * inv;
            }
        }
    }
}
