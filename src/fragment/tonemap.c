/* tonemap.c - tone mapping (the last step of the fragment stage's output):
 * linear-light float RGB(A) pixels, scaled by an exposure, through a tone
 * curve to display-linear [0, 1], then the sRGB transfer function to RGBA8.
 * Bands of rows run on the context's threads; every pixel is computed on
 * its own, so the bytes do not depend on the thread count.
 */
#include "context.h"
#include "fragment/tonemap.h"
#include "parallel/pool.h"

#include <float.h>
#include <math.h>
#include <pthread.h>
#include <string.h>

#define MAX_EXPOSURE 64.0f      /* EV either way: 2^64 keeps every float finite or flushed */
#define BAND_ROWS    16         /* rows a thread job */

/* Khronos PBR Neutral (KhronosGroup/ToneMapping, PBR_Neutral): below
 * start_compression the colour only loses the offset that undoes a
 * dielectric's 4% Fresnel reflection (smoothly shrunk towards black), so
 * base colours lit by a white furnace come out as themselves; above it
 * the peak channel is compressed towards 1 and the colour desaturated
 * towards the new peak.  Both steps keep the hue. */
static void pbr_neutral(const float in[3], float out[3])
{
    const float start_compression = 0.8f - 0.04f;
    const float desaturation = 0.15f;
    float x = fminf(in[0], fminf(in[1], in[2]));
    float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
    float c[3] = { in[0] - offset, in[1] - offset, in[2] - offset };
    float peak = fmaxf(c[0], fmaxf(c[1], c[2]));
    if (peak < start_compression) {
        memcpy(out, c, sizeof c);
        return;
    }
    const float d = 1.0f - start_compression;
    float new_peak = 1.0f - d * d / (peak + d - start_compression);
    float g = 1.0f - 1.0f / (desaturation * (peak - new_peak) + 1.0f);
    for (int i = 0; i < 3; i++) {
        float v = c[i] * (new_peak / peak);
        out[i] = v + (new_peak - v) * g;
    }
}

/* ACES filmic: Stephen Hill's fit of the ACES reference rendering and
 * output transforms (RRT + ODT) for sRGB displays - sRGB to the ACES AP1
 * working space (with the RRT's saturation), a rational fit of the
 * RRT+ODT curve per channel, back to sRGB.  The input is first divided by
 * 0.6, as three.js's ACESFilmicToneMapping does, so that a scene exposed
 * for the other operators is not darkened by the fit's toe. */
static void aces_hill(const float in[3], float out[3])
{
    static const float to_ap1[3][3] = {
        { 0.59719f, 0.35458f, 0.04823f },
        { 0.07600f, 0.90834f, 0.01566f },
        { 0.02840f, 0.13383f, 0.83777f },
    };
    static const float from_ap1[3][3] = {
        { 1.60475f, -0.53108f, -0.07367f },
        { -0.10208f, 1.10813f, -0.00605f },
        { -0.00327f, -0.07276f, 1.07602f },
    };
    float v[3], f[3];
    for (int i = 0; i < 3; i++) {
        v[i] = (to_ap1[i][0] * in[0] + to_ap1[i][1] * in[1] + to_ap1[i][2] * in[2]) / 0.6f;
    }
    for (int i = 0; i < 3; i++) {
        /* Past 1e18 the curve is flat in float; the bound keeps v * v finite. */
        float u = fminf(v[i], 1e18f);
        float a = u * (u + 0.0245786f) - 0.000090537f;
        float b = u * (0.983729f * u + 0.4329510f) + 0.238081f;
        f[i] = a / b;
    }
    for (int i = 0; i < 3; i++) {
        float o = from_ap1[i][0] * f[0] + from_ap1[i][1] * f[1] + from_ap1[i][2] * f[2];
        out[i] = fminf(fmaxf(o, 0.0f), 1.0f);
    }
}

/* The input policy: NaN and negatives are black, +inf the largest float
 * (so it maps like any very bright value instead of spreading NaN). */
static float sanitize(float v)
{
    return v > 0.0f ? fminf(v, FLT_MAX) : 0.0f;
}

void sr__tone_curve(sr_tonemap_op op, const float in[3], float out[3])
{
    float c[3] = { sanitize(in[0]), sanitize(in[1]), sanitize(in[2]) };
    switch (op) {
    case SR_TONEMAP_ACES:
        aces_hill(c, out);
        break;
    case SR_TONEMAP_NONE:
        for (int i = 0; i < 3; i++) {
            out[i] = fminf(c[i], 1.0f);
        }
        break;
    default:
        pbr_neutral(c, out);
        break;
    }
}

sr_result sr_tonemap_rgb(sr_tonemap_op op, const float in[3], float out[3])
{
    if (!in || !out) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_tonemap_rgb: %s is NULL", in ? "out" : "in");
    }
    if ((unsigned)op > SR_TONEMAP_NONE) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_tonemap_rgb: op %d is not an operator", (int)op);
    }
    sr__tone_curve(op, in, out);
    return SR_OK;
}

/* ---- sRGB encode -------------------------------------------------------- */

/* The sRGB OETF (IEC 61966-2-1) in double, rounded to nearest 8-bit code:
 * the definition the table below reproduces for every float. */
static int srgb_code_exact(double x)
{
    if (!(x > 0.0)) {
        return 0;
    }
    if (x >= 1.0) {
        return 255;
    }
    double s = x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
    return (int)floor(s * 255.0 + 0.5);
}

void sr__srgb_table_init(srgb_table *t)
{
    for (int k = 0; k < 255; k++) {
        double s = (k + 0.5) / 255.0;
        double b = s <= 0.04045 ? s / 12.92 : pow((s + 0.055) / 1.055, 2.4);
        float f = (float)b;
        while (srgb_code_exact(f) > k) {
            f = nextafterf(f, 0.0f);
        }
        while (srgb_code_exact(f) <= k) {
            f = nextafterf(f, 2.0f);
        }
        t->step[k] = f;
    }
    int code = 0;
    for (uint32_t i = 0; i < SR_SRGB_BUCKETS; i++) {
        uint32_t bits = i << SR_SRGB_BUCKET_SHIFT;
        float x;
        memcpy(&x, &bits, sizeof x);
        while (code < 255 && x >= t->step[code]) {
            code++;
        }
        t->first[i] = (uint8_t)code;
    }
}

static srgb_table shared_table;
static pthread_once_t shared_once = PTHREAD_ONCE_INIT;

static void shared_table_init(void)
{
    sr__srgb_table_init(&shared_table);
}

const srgb_table *sr__srgb_table(void)
{
    pthread_once(&shared_once, shared_table_init);
    return &shared_table;
}

uint8_t sr_srgb_encode8(float linear)
{
    return (uint8_t)srgb_code_exact(linear);
}

/* ---- images ------------------------------------------------------------- */

typedef struct tonemap_job {
    const uint8_t *src;
    size_t stride;
    uint8_t *dst;
    size_t out_stride;
    int width, height, channels;
    float scale;
    sr_tonemap_op op;
    srgb_table srgb;
} tonemap_job;

static void tonemap_band(void *arg, int job, int thread)
{
    (void)thread;
    const tonemap_job *j = arg;
    int y1 = (job + 1) * BAND_ROWS < j->height ? (job + 1) * BAND_ROWS : j->height;
    for (int y = job * BAND_ROWS; y < y1; y++) {
        const float *s = (const float *)(j->src + (size_t)y * j->stride);
        uint8_t *d = j->dst + (size_t)y * j->out_stride;
        for (int x = 0; x < j->width; x++, s += j->channels, d += 4) {
            float c[3] = { s[0] * j->scale, s[1] * j->scale, s[2] * j->scale }, m[3];
            sr__tone_curve(j->op, c, m);
            for (int i = 0; i < 3; i++) {
                d[i] = sr__srgb_code(&j->srgb, m[i]);
            }
            /* Alpha is coverage, not light: clamped and scaled, not encoded. */
            float a = j->channels == 4 ? s[3] : 1.0f;
            a = a > 0.0f ? fminf(a, 1.0f) : 0.0f;
            d[3] = (uint8_t)(a * 255.0f + 0.5f);
        }
    }
}

sr_result sr_tonemap(sr_context *ctx, const float *pixels, int width, int height, size_t stride,
                     uint8_t *out, size_t out_stride, const sr_tonemap_desc *desc)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_tonemap: ctx is NULL");
    }
    sr_tonemap_desc d = desc ? *desc : (sr_tonemap_desc){ 0 };
    if (!pixels || !out) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_tonemap: %s is NULL", pixels ? "out" : "pixels");
    }
    if (width < 1 || height < 1) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_tonemap: size %dx%d must be at least 1x1", width,
                        height);
    }
    int channels = d.channels ? d.channels : 4;
    if (channels != 3 && channels != 4) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_tonemap_desc.channels %d must be 3 or 4",
                        d.channels);
    }
    if ((unsigned)d.op > SR_TONEMAP_NONE) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_tonemap_desc.op %d is not an operator",
                        (int)d.op);
    }
    if (!(fabsf(d.exposure) <= MAX_EXPOSURE)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_tonemap_desc.exposure %g is not in -%g..%g EV",
                        (double)d.exposure, (double)MAX_EXPOSURE, (double)MAX_EXPOSURE);
    }
    size_t row_bytes = (size_t)width * (size_t)channels * sizeof(float);
    if (stride == 0) {
        stride = row_bytes;
    }
    if (out_stride == 0) {
        out_stride = 4 * (size_t)width;
    }
    if (stride < row_bytes || stride % sizeof(float) != 0) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_tonemap: stride %zu must be a multiple of 4 and at least %zu bytes",
                        stride, row_bytes);
    }
    if (out_stride < 4 * (size_t)width) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_tonemap: out_stride %zu is less than %zu bytes",
                        out_stride, 4 * (size_t)width);
    }
    if ((size_t)(height - 1) > (SIZE_MAX - row_bytes) / stride ||
        (size_t)(height - 1) > (SIZE_MAX - 4 * (size_t)width) / out_stride) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_tonemap: the image does not fit in memory");
    }
    /* Rows run on several threads at once: an out overlapping pixels would
     * be written while other rows still read it. */
    size_t in_span = (size_t)(height - 1) * stride + row_bytes;
    size_t out_span = (size_t)(height - 1) * out_stride + 4 * (size_t)width;
    if ((uintptr_t)out < (uintptr_t)pixels + in_span &&
        (uintptr_t)pixels < (uintptr_t)out + out_span) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_tonemap: out overlaps pixels");
    }
    tonemap_job *j = sr__alloc(ctx, sizeof *j);
    if (!j) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_tonemap: out of memory");
    }
    *j = (tonemap_job){
        .src = (const uint8_t *)pixels,
        .stride = stride,
        .dst = out,
        .out_stride = out_stride,
        .width = width,
        .height = height,
        .channels = channels,
        .scale = (float)exp2((double)d.exposure),
        .op = d.op == SR_TONEMAP_DEFAULT ? SR_TONEMAP_PBR_NEUTRAL : d.op,
    };
    sr__srgb_table_init(&j->srgb);
    sr__pool_run(ctx->pool, tonemap_band, j, (height + BAND_ROWS - 1) / BAND_ROWS);
    sr__free(ctx, j);
    sr__ok(ctx);
    return SR_OK;
}
