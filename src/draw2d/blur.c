/* blur.c - draw2d stage: Gaussian blur of a float image (sr_blur_image).
 * Consumes premultiplied float pixels of 1 to 4 channels, produces them
 * blurred in place: rows, then columns.  Below a deviation of 2 pixels
 * the exact sampled Gaussian (3 deviations each side, normalized); from
 * 2 up, the three box blurs of SVG's feGaussianBlur, each a difference of
 * a running sum, so the cost does not grow with the deviation.  Caller's
 * thread only. */
#include "context.h"

#include <math.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Deviations from this up use the box blurs (SVG 1.1, feGaussianBlur). */
#define BOX_FROM_SIGMA 2.0
/* Columns are blurred this many at a time, gathered into contiguous
 * lines: walking a column down the image one row stride at a time
 * misses the cache on every pixel. */
#define COLUMN_BLOCK 16
/* Larger deviations blur no further than this: every pixel of the widest
 * image already averages the whole line; the cap keeps box sizes in int. */
#define MAX_SIGMA 1e6

typedef struct line {
    const float *src;      /* n values, `step` floats apart */
    size_t step;
    int n;
    double *sum;           /* sum[k] = src[0] + ... + src[k - 1], n + 1 of them */
    sr_blur_edge edge;
} line;

/* The sum of the extended line's values at indices below k (k may be
 * outside 0..n): what lies beyond the ends follows the edge mode. */
static double sum_below(const line *l, long long k)
{
    long long n = l->n;
    if (k >= 0 && k <= n) {
        return l->sum[k];
    }
    switch (l->edge) {
    case SR_BLUR_EDGE_DUPLICATE:
        return k < 0 ? (double)k * l->src[0]
                     : l->sum[n] + (double)(k - n) * l->src[(size_t)(n - 1) * l->step];
    case SR_BLUR_EDGE_WRAP: {
        long long q = k >= 0 ? k / n : -((-k + n - 1) / n);
        return (double)q * l->sum[n] + l->sum[k - q * n];
    }
    default:
        return k < 0 ? 0 : l->sum[n];
    }
}

static float value_at(const line *l, long long k)
{
    long long n = l->n;
    if (k < 0 || k >= n) {
        switch (l->edge) {
        case SR_BLUR_EDGE_DUPLICATE: k = k < 0 ? 0 : n - 1; break;
        case SR_BLUR_EDGE_WRAP: k = ((k % n) + n) % n; break;
        default: return 0;
        }
    }
    return l->src[(size_t)k * l->step];
}

static void prefix_sums(line *l)
{
    double s = 0;
    l->sum[0] = 0;
    for (int i = 0; i < l->n; i++) {
        s += l->src[(size_t)i * l->step];
        l->sum[i + 1] = s;
    }
}

/* One box of d values: out[i] = mean of in[i - lo .. i + d - 1 - lo]. */
static void box(line *l, float *out, long long d, long long lo)
{
    prefix_sums(l);
    /* [a, b): both ends of the box on the line, its sums read directly;
     * the ends past the line's ends follow the edge mode */
    long long n = l->n, a = lo < 0 ? 0 : lo > n ? n : lo, b = n - d + lo + 1;
    b = b < a ? a : b > n ? n : b;
    const double *sum = l->sum;
    for (long long i = 0; i < a; i++) {
        out[i] = (float)((sum_below(l, i - lo + d) - sum_below(l, i - lo)) / (double)d);
    }
    for (long long i = a; i < b; i++) {
        out[i] = (float)((sum[i - lo + d] - sum[i - lo]) / (double)d);
    }
    for (long long i = b; i < n; i++) {
        out[i] = (float)((sum_below(l, i - lo + d) - sum_below(l, i - lo)) / (double)d);
    }
}

/* The line blurred into tmp (n floats), then copied back over it. */
static void blur_line(line *l, float *out, float *tmp, double sigma, const float *kernel, int radius)
{
    int n = l->n;
    if (sigma < BOX_FROM_SIGMA) {
        for (int i = 0; i < n; i++) {
            double s = 0;
            for (int k = -radius; k <= radius; k++) {
                s += kernel[k + radius] * value_at(l, (long long)i + k);
            }
            tmp[i] = (float)s;
        }
    } else {
        /* d from SVG 1.1: three boxes of d when d is odd; else two of d,
         * centred half a pixel left then right, and one of d + 1. */
        long long d = (long long)floor(sigma * 3 * sqrt(2 * M_PI) / 4 + 0.5);
        line t = *l;
        bool odd = d % 2 == 1;
        box(l, tmp, d, d / 2);
        t.src = tmp;
        t.step = 1;
        box(&t, out, d, odd ? d / 2 : d / 2 - 1);
        t.src = out;
        box(&t, tmp, odd ? d : d + 1, d / 2);
    }
    for (int i = 0; i < n; i++) {
        ((float *)l->src)[(size_t)i * l->step] = tmp[i];
    }
}

sr_result sr_blur_image(sr_context *ctx, float *pixels, int width, int height, int channels,
                        const sr_blur_desc *desc)
{
    static const char fn[] = "sr_blur_image";
    if (!ctx) {
        return SR_INVALID_ARG;
    }
    if (!pixels || !desc) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %s is NULL", fn, pixels ? "desc" : "pixels");
    }
    if (width <= 0 || height <= 0) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: size %d x %d is not positive", fn, width,
                        height);
    }
    if (channels < 1 || channels > 4) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: channels %d is not 1 to 4", fn, channels);
    }
    double sig[2] = { desc->sigma_x, desc->sigma_y };
    for (int a = 0; a < 2; a++) {
        if (!(sig[a] >= 0) || isinf(sig[a])) {
            return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_blur_desc.sigma_%c %g is not >= 0", fn,
                            "xy"[a], sig[a]);
        }
        sig[a] = fmin(sig[a], MAX_SIGMA);
    }
    if ((unsigned)desc->edge > SR_BLUR_EDGE_WRAP) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_blur_desc.edge %d is unknown", fn,
                        (int)desc->edge);
    }
    int longest = width > height ? width : height;
    double *sum = sr__alloc(ctx, ((size_t)longest + 1) * sizeof *sum);
    float *tmp = sr__alloc(ctx, (size_t)longest * 2 * sizeof *tmp);
    float *block = sr__alloc(ctx, (size_t)COLUMN_BLOCK * (size_t)channels * (size_t)height *
                                      sizeof *block);
    if (!sum || !tmp || !block) {
        sr__free(ctx, sum);
        sr__free(ctx, tmp);
        sr__free(ctx, block);
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "%s: out of memory", fn);
    }
    for (int a = 0; a < 2; a++) {
        double s = sig[a];
        if (s <= 0) {
            continue; /* no blur along this axis */
        }
        float kernel[2 * 6 + 1];
        int radius = 0;
        if (s < BOX_FROM_SIGMA) {
            radius = (int)ceil(3 * s);
            double total = 0;
            for (int k = -radius; k <= radius; k++) {
                total += kernel[k + radius] = (float)exp(-(double)k * k / (2 * s * s));
            }
            for (int k = 0; k <= 2 * radius; k++) {
                kernel[k] = (float)(kernel[k] / total);
            }
        }
        if (a == 0) {
            for (int y = 0; y < height; y++) {
                for (int c = 0; c < channels; c++) {
                    line l = { .src = pixels + (size_t)y * (size_t)width * (size_t)channels +
                                      (size_t)c,
                               .step = (size_t)channels, .n = width, .sum = sum,
                               .edge = desc->edge };
                    blur_line(&l, tmp + longest, tmp, s, kernel, radius);
                }
            }
            continue;
        }
        size_t h = (size_t)height;
        for (int x0 = 0; x0 < width; x0 += COLUMN_BLOCK) {
            /* values k = column * channels + channel of the block, each a line of h */
            size_t k_n = (size_t)(width - x0 < COLUMN_BLOCK ? width - x0 : COLUMN_BLOCK) *
                         (size_t)channels;
            for (size_t y = 0; y < h; y++) {
                const float *row = pixels + (y * (size_t)width + (size_t)x0) * (size_t)channels;
                for (size_t k = 0; k < k_n; k++) {
                    block[k * h + y] = row[k];
                }
            }
            for (size_t k = 0; k < k_n; k++) {
                line l = { .src = block + k * h, .step = 1, .n = height, .sum = sum,
                           .edge = desc->edge };
                blur_line(&l, tmp + longest, tmp, s, kernel, radius);
            }
            for (size_t y = 0; y < h; y++) {
                float *row = pixels + (y * (size_t)width + (size_t)x0) * (size_t)channels;
                for (size_t k = 0; k < k_n; k++) {
                    row[k] = block[k * h + y];
                }
            }
        }
    }
    sr__free(ctx, sum);
    sr__free(ctx, tmp);
    sr__free(ctx, block);
    sr__ok(ctx);
    return SR_OK;
}
