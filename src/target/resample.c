/* resample.c - supersampling's resolve (target stage): a k-times larger
 * image filtered down to the output size with a reconstruction filter.
 * The filter is separable: weights are computed once per output column and
 * row, then applied as a horizontal pass into a float buffer and a vertical
 * pass into the destination.  Application thread. */
#include "context.h"
#include "target/framebuffer.h"

#include <math.h>
#include <string.h>

static double filter_radius(sr_resample_filter f)
{
    switch (f) {
    case SR_RESAMPLE_TENT:     return 1.0;
    case SR_RESAMPLE_GAUSSIAN: return 1.5;
    case SR_RESAMPLE_MITCHELL: return 2.0;
    default:                   return 0.5;
    }
}

/* Weight at distance x (destination pixels) from the output pixel's centre. */
static double filter_weight(sr_resample_filter f, double x)
{
    x = fabs(x);
    switch (f) {
    case SR_RESAMPLE_TENT:
        return x < 1.0 ? 1.0 - x : 0.0;
    case SR_RESAMPLE_GAUSSIAN:
        return x < 1.5 ? exp(-2.0 * x * x) : 0.0;   /* sigma = 1/2 */
    case SR_RESAMPLE_MITCHELL: {
        const double b = 1.0 / 3.0, c = 1.0 / 3.0;
        if (x < 1.0) {
            return ((12 - 9 * b - 6 * c) * x * x * x + (-18 + 12 * b + 6 * c) * x * x +
                    (6 - 2 * b)) / 6.0;
        }
        if (x < 2.0) {
            return ((-b - 6 * c) * x * x * x + (6 * b + 30 * c) * x * x +
                    (-12 * b - 48 * c) * x + (8 * b + 24 * c)) / 6.0;
        }
        return 0.0;
    }
    default:
        return x < 0.5 ? 1.0 : 0.0;   /* box: the source samples inside the pixel */
    }
}

/* For each of n output pixels along an axis of k n samples: the first
 * sample index, the tap count and normalized weights (taps per pixel fixed). */
typedef struct axis_taps {
    int taps;
    int *first;
    float *w;
} axis_taps;

static bool make_taps(sr_context *ctx, sr_resample_filter f, int n, int k, axis_taps *a)
{
    double r = filter_radius(f);
    a->taps = (int)ceil(2.0 * r * k) + 1;
    a->first = sr__calloc(ctx, (size_t)n, sizeof(int));
    a->w = sr__calloc(ctx, (size_t)n * (size_t)a->taps, sizeof(float));
    if (!a->first || !a->w) {
        return false;
    }
    for (int i = 0; i < n; i++) {
        double centre = (i + 0.5) * k;              /* in samples */
        int s0 = (int)floor(centre - r * k);
        a->first[i] = s0;
        double sum = 0.0;
        for (int t = 0; t < a->taps; t++) {
            double d = (s0 + t + 0.5 - centre) / k; /* destination pixels */
            double w = filter_weight(f, d);
            a->w[(size_t)i * a->taps + t] = (float)w;
            sum += w;
        }
        for (int t = 0; t < a->taps; t++) {
            a->w[(size_t)i * a->taps + t] = (float)(a->w[(size_t)i * a->taps + t] / sum);
        }
    }
    return true;
}

static int clampi(int v, int lo, int hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

sr_result sr_downsample(sr_context *ctx, const sr_framebuffer *src, sr_framebuffer *dst,
                        sr_resample_filter filter)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_downsample: ctx is NULL");
    }
    if (!src || !dst) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_downsample: %s is NULL", src ? "dst" : "src");
    }
    if (src->samples > 1 || dst->samples > 1) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_downsample: multisampled framebuffers are resolved with sr_resolve");
    }
    if (sr__fb_is_band(src) || sr__fb_is_band(dst)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_downsample: not on a band of sr_render_bands");
    }
    if ((unsigned)filter > SR_RESAMPLE_MITCHELL) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_downsample: filter %d is not a filter", (int)filter);
    }
    int k = src->width / dst->width;
    if (k < 1 || k > 16 || src->width != k * dst->width || src->height != k * dst->height) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_downsample: the source (%dx%d) must be k times the destination "
                        "(%dx%d), k = 1..16", src->width, src->height, dst->width, dst->height);
    }
    if (filter == SR_RESAMPLE_DEFAULT) {
        filter = SR_RESAMPLE_BOX;
    }
    sr__fb_resolve((sr_framebuffer *)src, SR_TILE_PENDING_COLOR);
    sr__fb_begin_write(dst);

    axis_taps ax = { 0 }, ay = { 0 };
    int W = dst->width, H = dst->height, SW = src->width, SH = src->height;
    float *rows = NULL;
    bool ok = make_taps(ctx, filter, W, k, &ax) && make_taps(ctx, filter, H, k, &ay);
    if (ok) {
        /* Horizontal pass: every source row, filtered to W columns. */
        rows = sr__calloc(ctx, (size_t)SH * (size_t)W * 4, sizeof(float));
        ok = rows != NULL;
    }
    if (ok) {
        const uint8_t *sp = (const uint8_t *)src->color;
        for (int y = 0; y < SH; y++) {
            for (int x = 0; x < W; x++) {
                float acc[4] = { 0, 0, 0, 0 };
                for (int t = 0; t < ax.taps; t++) {
                    int sx = clampi(ax.first[x] + t, 0, SW - 1);
                    float w = ax.w[(size_t)x * ax.taps + t];
                    const uint8_t *p = sp + ((size_t)y * SW + sx) * 4;
                    for (int c = 0; c < 4; c++) {
                        acc[c] += w * p[c];
                    }
                }
                memcpy(&rows[((size_t)y * W + x) * 4], acc, sizeof acc);
            }
        }
        /* Vertical pass into the destination, rounded and clamped (the
         * Mitchell filter's negative lobes can overshoot). */
        uint8_t *dp = (uint8_t *)dst->color;
        for (int y = 0; y < H; y++) {
            for (int x = 0; x < W; x++) {
                float acc[4] = { 0, 0, 0, 0 };
                for (int t = 0; t < ay.taps; t++) {
                    int sy = clampi(ay.first[y] + t, 0, SH - 1);
                    float w = ay.w[(size_t)y * ay.taps + t];
                    const float *p = &rows[((size_t)sy * W + x) * 4];
                    for (int c = 0; c < 4; c++) {
                        acc[c] += w * p[c];
                    }
                }
                for (int c = 0; c < 4; c++) {
                    float v = acc[c] + 0.5f;
                    dp[((size_t)y * W + x) * 4 + c] = (uint8_t)(v < 0.0f ? 0.0f : v > 255.0f ? 255.0f : v);
                }
            }
        }
    }
    sr__free(ctx, rows);
    sr__free(ctx, ax.first);
    sr__free(ctx, ax.w);
    sr__free(ctx, ay.first);
    sr__free(ctx, ay.w);
    if (!ok) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_downsample: out of memory");
    }
    sr__ok(ctx);
    return SR_OK;
}
