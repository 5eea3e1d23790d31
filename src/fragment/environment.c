/* environment.c - image-based light (fragment stage, docs/ibl.md): makes
 * an sr_environment from an equirectangular image (validation, the source
 * and its mips, the irradiance SH, the specular levels on the context's
 * threads) or from the built-in studio's tables, prefiltered at build
 * time, and answers the shaders' per-fragment queries, which only read it
 * and may run on any thread.
 */
#include "context.h"
#include "fragment/environment.h"

#include <float.h>
#include <limits.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <stdatomic.h>
#include <string.h>

#define BAND_ROWS    4
#define COPY_ROWS    16         /* rows a job when copying or halving an image */

typedef struct prefilter_job {
    int level, row0, row1;
} prefilter_job;

typedef struct prefilter_work {
    sr_environment *env;
    const sr__equirect *mip;
    sr__spec_plan plans[SR_ENVIRONMENT_LEVELS];
    prefilter_job *jobs;
    float intensity;
    const float *pixels;        /* the caller's image */
    atomic_int first_bad_row;   /* INT_MAX, or the first row holding a bad value */
    const sr__equirect *half_src;
    sr__equirect *half_dst;
} prefilter_work;

static int band_end(int job, int rows, int h)
{
    return (job + 1) * rows < h ? (job + 1) * rows : h;
}

/* Rows of the caller's image into level 0, times the intensity, noting
 * the first row that holds a negative, infinite or NaN value. */
static void copy_job(void *arg, int job, int thread)
{
    (void)thread;
    prefilter_work *w = arg;
    sr__equirect *e = &w->env->level[0];
    int row1 = band_end(job, COPY_ROWS, e->h);
    const float scale = w->intensity;
    for (int j = job * COPY_ROWS; j < row1; j++) {
        size_t n = (size_t)e->w * 3, at = (size_t)j * n;
        const float *restrict src = w->pixels + at;
        float *restrict dst = e->rgb + at;
        /* written so that the compiler vectorizes it: an OR of compares,
         * no early exit */
        int bad = 0;
        for (size_t i = 0; i < n; i++) {
            float v = src[i];
            bad |= (v < 0.0f) | (v != v) | (v > FLT_MAX);
            dst[i] = v * scale;
        }
        if (bad) {
            int seen = atomic_load(&w->first_bad_row);
            while (j < seen && !atomic_compare_exchange_weak(&w->first_bad_row, &seen, j)) {
            }
            return;
        }
    }
}

static void halve_job(void *arg, int job, int thread)
{
    (void)thread;
    prefilter_work *w = arg;
    sr__equirect_halve(w->half_src, w->half_dst, job * COPY_ROWS,
                       band_end(job, COPY_ROWS, w->half_dst->h));
}

static void resample_job(void *arg, int job, int thread)
{
    (void)thread;
    prefilter_work *w = arg;
    sr__equirect_resample(w->half_src, w->half_dst, job * COPY_ROWS,
                          band_end(job, COPY_ROWS, w->half_dst->h));
}

static void level_job(void *arg, int job, int thread)
{
    (void)thread;
    prefilter_work *w = arg;
    const prefilter_job *j = &w->jobs[job];
    sr__prefilter_rows(w->mip, &w->plans[j->level], &w->env->level[j->level], j->row0, j->row1);
}

static sr_result validate(sr_context *ctx, const sr_environment_desc *d)
{
    if (!isfinite(d->intensity) || d->intensity < 0.0f) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_environment_desc.intensity must be finite and >= 0 (got %g)",
                        (double)d->intensity);
    }
    if (!isfinite(d->rotation)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_environment_desc.rotation must be finite");
    }
    if (!d->pixels) {
        if (d->width != 0 || d->height != 0) {
            return sr__fail(ctx, SR_INVALID_ARG,
                            "sr_environment_desc.pixels is NULL but the size is %dx%d",
                            d->width, d->height);
        }
        return SR_OK;
    }
    if (d->width < 1 || d->height < 1) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_environment_desc.%s must be >= 1 (got %d)",
                        d->width < 1 ? "width" : "height", d->width < 1 ? d->width : d->height);
    }
    if (d->width > SR_ENVIRONMENT_MAX_SIDE || d->height > SR_ENVIRONMENT_MAX_SIDE ||
        (size_t)d->width * (size_t)d->height > SR_ENVIRONMENT_MAX_PIXELS) {
        return sr__fail(ctx, SR_TOO_LARGE,
                        "sr_environment_desc: %dx%d exceeds %d a side or %zu pixels", d->width,
                        d->height, SR_ENVIRONMENT_MAX_SIDE, SR_ENVIRONMENT_MAX_PIXELS);
    }
    return SR_OK;
}

static float *alloc_image(sr_context *ctx, sr__equirect *e, int w, int h)
{
    e->w = w;
    e->h = h;
    e->rgb = sr__alloc_large(ctx, (size_t)w * (size_t)h * 3 * sizeof(float));
    return e->rgb;
}

/* The specular levels from the source's mips, then the mips freed. */
static sr_result prefilter(sr_context *ctx, prefilter_work *w)
{
    sr_environment *env = w->env;
    const sr__equirect *src = &env->level[0];
    int base = sr__mip_base_width(src->w);
    sr__equirect mip[SR__ENV_MAX_MIPS] = { *src };
    /* mip[0] is the source itself when it is the base's size; a resampled
     * one need not be wider than the widest mip a level reads (a 32768 x 1
     * image must not make a 32768 x 16384 one) */
    bool resampled = src->w != base || src->h != base / 2;
    if (resampled && base > 2 * SR__SPLIT_MAX) {
        base = 2 * SR__SPLIT_MAX;
    }
    int mips = sr__mip_count(base);
    sr_result r = SR_OK;
    if (resampled) {
        if (!alloc_image(ctx, &mip[0], base, base / 2)) {
            return SR_OUT_OF_MEMORY;
        }
        w->half_src = src;
        w->half_dst = &mip[0];
        sr_run_jobs(ctx, resample_job, w, (mip[0].h + COPY_ROWS - 1) / COPY_ROWS);
    }
    for (int m = 1; m < mips; m++) {
        src = &mip[m - 1];
        if (!alloc_image(ctx, &mip[m], src->w / 2, src->h / 2)) {
            mips = m;
            r = SR_OUT_OF_MEMORY;
            goto done;
        }
        w->half_src = src;
        w->half_dst = &mip[m];
        sr_run_jobs(ctx, halve_job, w, (mip[m].h + COPY_ROWS - 1) / COPY_ROWS);
    }
    sr__irradiance_sh(&mip[sr__sh_mip(mip[0].w, mips)], env->sh);

    int jobs = 0;
    for (int k = 1; k < SR_ENVIRONMENT_LEVELS; k++) {
        int lw = sr__level_width(env->level[0].w, k);
        if (!alloc_image(ctx, &env->level[k], lw, lw / 2)) {
            r = SR_OUT_OF_MEMORY;
            goto done;
        }
        jobs += (lw / 2 + BAND_ROWS - 1) / BAND_ROWS;
        sr__specular_plan((float)k / (SR_ENVIRONMENT_LEVELS - 1), mip, mips, &w->plans[k]);
        w->plans[k].simd = sr_context_simd(ctx);
    }
    w->jobs = sr__alloc(ctx, (size_t)jobs * sizeof *w->jobs);
    if (!w->jobs) {
        r = SR_OUT_OF_MEMORY;
        goto done;
    }
    int n = 0;
    for (int k = 1; k < SR_ENVIRONMENT_LEVELS; k++) {
        for (int row = 0; row < env->level[k].h; row += BAND_ROWS) {
            int row1 = row + BAND_ROWS < env->level[k].h ? row + BAND_ROWS : env->level[k].h;
            w->jobs[n++] = (prefilter_job){ k, row, row1 };
        }
    }
    w->mip = mip;
    sr_run_jobs(ctx, level_job, w, n);
    sr__free(ctx, w->jobs);
done:
    for (int m = resampled ? 0 : 1; m < mips; m++) {
        sr__free(ctx, mip[m].rgb);
    }
    return r;
}

/* The caller's image, checked and times the intensity, then prefiltered. */
static sr_result from_image(sr_context *ctx, const sr_environment_desc *d, float intensity,
                            sr_environment *env)
{
    int sw = d->width, sh = d->height;
    prefilter_work *w = sr__calloc(ctx, 1, sizeof *w);
    if (!w || !alloc_image(ctx, &env->level[0], sw, sh)) {
        sr__free(ctx, w);
        return sr__fail(ctx, SR_OUT_OF_MEMORY,
                        "sr_make_environment: out of memory for a %dx%d environment", sw, sh);
    }
    w->env = env;
    w->intensity = intensity;
    w->pixels = d->pixels;
    atomic_init(&w->first_bad_row, INT_MAX);
    sr_run_jobs(ctx, copy_job, w, (sh + COPY_ROWS - 1) / COPY_ROWS);
    int row = atomic_load(&w->first_bad_row);
    if (row != INT_MAX) {
        const float *p = d->pixels + (size_t)row * sw * 3;
        int i = 0;
        while (p[i] >= 0.0f && p[i] <= FLT_MAX) {
            i++;
        }
        sr__free(ctx, w);
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_environment_desc.pixels: pixel (%d, %d) channel %d is %g; "
                        "radiance must be finite and >= 0",
                        i / 3, row, i % 3, (double)p[i]);
    }
    sr_result r = prefilter(ctx, w);
    sr__free(ctx, w);
    if (r != SR_OK) {
        return sr__fail(ctx, r, "sr_make_environment: out of memory for a %dx%d environment",
                        sw, sh);
    }
    return SR_OK;
}

/* The built-in studio: its levels and SH prefiltered at build time, times
 * the intensity (prefiltering is linear, so scaling after it is scaling
 * the source, to the rounding); level 0 stays its function. */
static sr_result from_studio(sr_context *ctx, float intensity, sr_environment *env)
{
    env->studio_intensity = intensity;
    for (int k = 1; k < SR_ENVIRONMENT_LEVELS; k++) {
        int lw = sr__level_width(SR__STUDIO_WIDTH, k);
        if (!alloc_image(ctx, &env->level[k], lw, lw / 2)) {
            return sr__fail(ctx, SR_OUT_OF_MEMORY,
                            "sr_make_environment: out of memory for the built-in studio");
        }
        const float *src = sr__studio_builtin_levels[k];
        float *dst = env->level[k].rgb;
        for (size_t i = 0; i < (size_t)lw * (size_t)(lw / 2); i++) {
            float v = src[i] * intensity;
            dst[3 * i] = dst[3 * i + 1] = dst[3 * i + 2] = v;
        }
    }
    for (int k = 0; k < 9; k++) {
        env->sh[k][0] = env->sh[k][1] = env->sh[k][2] = sr__studio_builtin_sh[k] * intensity;
    }
    return SR_OK;
}

sr_result sr_make_environment(sr_context *ctx, const sr_environment_desc *desc,
                              sr_environment **out)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_make_environment: ctx is NULL");
    }
    if (!out) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_make_environment: out is NULL");
    }
    *out = NULL;
    sr_environment_desc d = desc ? *desc : (sr_environment_desc){ 0 };
    sr_result r = validate(ctx, &d);
    if (r != SR_OK) {
        return r;
    }
    sr_environment *env = sr__calloc(ctx, 1, sizeof *env);
    if (!env) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_make_environment: out of memory");
    }
    static atomic_uint_fast64_t serials = 1;
    env->serial = (uint64_t)atomic_fetch_add(&serials, 1);
    float intensity = d.intensity == 0.0f ? 1.0f : d.intensity;
    env->cos_rot = cosf(d.rotation);
    env->sin_rot = sinf(d.rotation);
    r = d.pixels ? from_image(ctx, &d, intensity, env) : from_studio(ctx, intensity, env);
    if (r != SR_OK) {
        sr_destroy_environment(ctx, env);
        return r;
    }
    *out = env;
    sr__ok(ctx);
    return SR_OK;
}

void sr_destroy_environment(sr_context *ctx, sr_environment *env)
{
    if (!ctx || !env) {
        return;
    }
    /* Its maps in this context's cache are never asked for again. */
    sr__oct_cache_forget(ctx, env->serial);
    for (int k = 0; k < SR_ENVIRONMENT_LEVELS; k++) {
        sr__free(ctx, env->level[k].rgb);
    }
    sr__free(ctx, env);
}

/* ---- queries ----------------------------------------------------------- */

/* The queries' arithmetic is written per lane without branches, so that
 * the 4-lane forms' loops vectorize; a scalar query runs the same code
 * on one lane, and IEEE arithmetic (no contraction, no reassociation)
 * makes both give the same floats.  Only the texel reads are per lane. */

/* A world direction to a unit direction in the image's frame; zero,
 * infinite or NaN gives +Y. */
static inline void to_image(const sr_environment *env, float x, float y, float z, float *dx,
                            float *dy, float *dz)
{
    float len2 = x * x + y * y + z * z;
    int ok = (len2 > 0.0f) & (len2 < INFINITY);
    float s = 1.0f / sqrtf(ok ? len2 : 1.0f);
    x = ok ? x * s : 0.0f;
    y = ok ? y * s : 1.0f;
    z = ok ? z * s : 0.0f;
    *dx = x * env->cos_rot - z * env->sin_rot;
    *dy = y;
    *dz = x * env->sin_rot + z * env->cos_rot;
}

static inline float clamp01(float x)
{
    return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f;  /* NaN -> 0 */
}

/* The lane-wise part of a specular query: the image direction, its
 * equirectangular (u, t) and the level coordinate f = roughness * 5. */
typedef struct spec_lanes {
    float dx[4], dy[4], dz[4], u[4], t[4], f[4];
} spec_lanes;

static inline void spec_lane(const sr_environment *env, spec_lanes *q, int i, float x, float y,
                             float z, float roughness)
{
    to_image(env, x, y, z, &q->dx[i], &q->dy[i], &q->dz[i]);
    q->u[i] = 0.5f + sr__atan2(q->dz[i], q->dx[i]) * (0.5f / SR__PI);
    q->t[i] = sr__acos(q->dy[i]) * (1.0f / SR__PI);
    q->f[i] = clamp01(roughness) * (SR_ENVIRONMENT_LEVELS - 1);
}

#if defined(__SSE2__)
/* spec_lane on four lanes at once, operation for operation (the same
 * IEEE additions, products, quotients and square roots in the same
 * order, ternaries as masks), so every float is the one spec_lane gives. */
static inline __m128 select4(__m128 mask, __m128 a, __m128 b)
{
    return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b));
}

static inline void spec_lanes4(const sr_environment *env, spec_lanes *q, const sr_vec3x4 *dir,
                               const float roughness[4])
{
    const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
    const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
    const __m128 sign = _mm_castsi128_ps(_mm_set1_epi32((int)0x80000000u));
    __m128 x = _mm_loadu_ps(dir->x), y = _mm_loadu_ps(dir->y), z = _mm_loadu_ps(dir->z);
    /* to_image */
    __m128 len2 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(x, x), _mm_mul_ps(y, y)), _mm_mul_ps(z, z));
    __m128 ok = _mm_and_ps(_mm_cmpgt_ps(len2, zero), _mm_cmplt_ps(len2, _mm_set1_ps(INFINITY)));
    __m128 s = _mm_div_ps(one, _mm_sqrt_ps(select4(ok, len2, one)));
    x = select4(ok, _mm_mul_ps(x, s), zero);
    y = select4(ok, _mm_mul_ps(y, s), one);
    z = select4(ok, _mm_mul_ps(z, s), zero);
    __m128 c = _mm_set1_ps(env->cos_rot), sn = _mm_set1_ps(env->sin_rot);
    __m128 dx = _mm_sub_ps(_mm_mul_ps(x, c), _mm_mul_ps(z, sn));
    __m128 dz = _mm_add_ps(_mm_mul_ps(x, sn), _mm_mul_ps(z, c));
    _mm_storeu_ps(q->dx, dx);
    _mm_storeu_ps(q->dy, y);
    _mm_storeu_ps(q->dz, dz);
    /* sr__atan2(dz, dx) */
    __m128 ax = _mm_and_ps(dx, abs_mask), ay = _mm_and_ps(dz, abs_mask);
    __m128 gt = _mm_cmpgt_ps(ax, ay);
    __m128 mx = select4(gt, ax, ay), mn = select4(gt, ay, ax);
    __m128 r = _mm_div_ps(mn, select4(_mm_cmpgt_ps(mx, zero), mx, one));
    __m128 r2 = _mm_mul_ps(r, r);
    __m128 p = _mm_mul_ps(r2, _mm_set1_ps(0.02083510f));
    p = _mm_mul_ps(r2, _mm_add_ps(_mm_set1_ps(-0.08513300f), p));
    p = _mm_mul_ps(r2, _mm_add_ps(_mm_set1_ps(0.18014100f), p));
    p = _mm_mul_ps(r2, _mm_add_ps(_mm_set1_ps(-0.33029950f), p));
    __m128 a = _mm_mul_ps(r, _mm_add_ps(_mm_set1_ps(0.99986602f), p));
    a = select4(_mm_cmpgt_ps(ay, ax), _mm_sub_ps(_mm_set1_ps(0.5f * SR__PI), a), a);
    a = select4(_mm_cmplt_ps(dx, zero), _mm_sub_ps(_mm_set1_ps(SR__PI), a), a);
    a = select4(_mm_cmplt_ps(dz, zero), _mm_xor_ps(a, sign), a);
    _mm_storeu_ps(q->u, _mm_add_ps(_mm_set1_ps(0.5f), _mm_mul_ps(a, _mm_set1_ps(0.5f / SR__PI))));
    /* sr__acos(dy) */
    __m128 ey = _mm_and_ps(y, abs_mask);
    ey = select4(_mm_cmplt_ps(ey, one), ey, one);
    __m128 h = _mm_set1_ps(-0.0012624911f);
    h = _mm_add_ps(_mm_mul_ps(h, ey), _mm_set1_ps(0.0066700901f));
    h = _mm_sub_ps(_mm_mul_ps(h, ey), _mm_set1_ps(0.0170881256f));
    h = _mm_add_ps(_mm_mul_ps(h, ey), _mm_set1_ps(0.0308918810f));
    h = _mm_sub_ps(_mm_mul_ps(h, ey), _mm_set1_ps(0.0501743046f));
    h = _mm_add_ps(_mm_mul_ps(h, ey), _mm_set1_ps(0.0889789874f));
    h = _mm_sub_ps(_mm_mul_ps(h, ey), _mm_set1_ps(0.2145988016f));
    h = _mm_add_ps(_mm_mul_ps(h, ey), _mm_set1_ps(1.5707963050f));
    __m128 ac = _mm_mul_ps(_mm_sqrt_ps(_mm_sub_ps(one, ey)), h);
    ac = select4(_mm_cmplt_ps(y, zero), _mm_sub_ps(_mm_set1_ps(SR__PI), ac), ac);
    _mm_storeu_ps(q->t, _mm_mul_ps(ac, _mm_set1_ps(1.0f / SR__PI)));
    /* clamp01(roughness) * levels */
    __m128 rg = _mm_loadu_ps(roughness);
    rg = select4(_mm_cmpgt_ps(rg, zero), select4(_mm_cmplt_ps(rg, one), rg, one), zero);
    _mm_storeu_ps(q->f, _mm_mul_ps(rg, _mm_set1_ps((float)(SR_ENVIRONMENT_LEVELS - 1))));
}
#endif

/* Lane i's texel reads: linear between the two levels around f. */
static inline void spec_read(const sr_environment *env, const spec_lanes *q, int i, float out[3])
{
    float f = q->f[i], u = q->u[i], t = q->t[i];
    int k = (int)f;
    k = k < SR_ENVIRONMENT_LEVELS - 1 ? k : SR_ENVIRONMENT_LEVELS - 2;
    float a = f - (float)k;
    const sr__equirect *e0 = &env->level[k], *e1 = &env->level[k + 1];
    float c0[3] = { 0, 0, 0 }, c1[3] = { 0, 0, 0 };
    if (a < 1.0f && k == 0 && env->studio_intensity > 0.0f) {
        float d[3] = { q->dx[i], q->dy[i], q->dz[i] };
        c0[0] = c0[1] = c0[2] = env->studio_intensity * sr__studio_radiance(d);
    } else if (a < 1.0f) {
        sr__equirect_bilinear(e0, u * e0->w, t * e0->h, c0);
    }
    if (a > 0.0f) {
        sr__equirect_bilinear(e1, u * e1->w, t * e1->h, c1);
    }
    for (int c = 0; c < 3; c++) {
        out[c] = c0[c] + a * (c1[c] - c0[c]);
    }
}

void sr_environment_irradiance(const sr_environment *env, const float normal[3], float out[3])
{
    if (!out) {
        return;
    }
    if (!env || !normal) {
        out[0] = out[1] = out[2] = 0.0f;
        return;
    }
    float d[3];
    to_image(env, normal[0], normal[1], normal[2], &d[0], &d[1], &d[2]);
    sr__irradiance_eval(env->sh, d, out);
}

void sr_environment_irradiance4(const sr_environment *env, const sr_vec3x4 *normal,
                                sr_vec3x4 *out)
{
    if (!out) {
        return;
    }
    if (!env || !normal) {
        memset(out, 0, sizeof *out);
        return;
    }
    sr_vec3x4 d;
    for (int i = 0; i < 4; i++) {
        to_image(env, normal->x[i], normal->y[i], normal->z[i], &d.x[i], &d.y[i], &d.z[i]);
    }
    sr__irradiance_eval4(env->sh, &d, out);
}

void sr_environment_specular(const sr_environment *env, const float dir[3], float roughness,
                             float out[3])
{
    if (!out) {
        return;
    }
    if (!env || !dir) {
        out[0] = out[1] = out[2] = 0.0f;
        return;
    }
    spec_lanes q;
    spec_lane(env, &q, 0, dir[0], dir[1], dir[2], roughness);
    spec_read(env, &q, 0, out);
}

void sr_environment_specular4(const sr_environment *env, const sr_vec3x4 *dir,
                              const float roughness[4], sr_vec3x4 *out)
{
    if (!out) {
        return;
    }
    if (!env || !dir || !roughness) {
        memset(out, 0, sizeof *out);
        return;
    }
    spec_lanes q;
#if defined(__SSE2__)
    spec_lanes4(env, &q, dir, roughness);
#else
    for (int i = 0; i < 4; i++) {
        spec_lane(env, &q, i, dir->x[i], dir->y[i], dir->z[i], roughness[i]);
    }
#endif
    for (int i = 0; i < 4; i++) {
        float c[3];
        spec_read(env, &q, i, c);
        out->x[i] = c[0];
        out->y[i] = c[1];
        out->z[i] = c[2];
    }
}

void sr_environment_background(const sr_environment *env, const float dir[3], float blur,
                               float out[3])
{
    sr_environment_specular(env, dir, blur, out);
}
