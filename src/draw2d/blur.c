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
/* Columns are blurred this many at a time, side by side: each line's
 * running sum waits on the addition before it, so lines summed together
 * keep the adder busy, and a row's span of them is contiguous. */
#define COLUMN_BLOCK 16
/* Larger deviations blur no further than this: every pixel of the widest
 * image already averages the whole line; the cap keeps box sizes in int. */
#define MAX_SIGMA 1e6

/* `lanes` lines side by side: value i of lane j at src[i * step + j]. */
typedef struct lines {
    const float *src;
    size_t step;
    int n, lanes;
    double *sum;           /* sum[k * lanes + j]: lane j's values below k, n + 1 of them */
    sr_blur_edge edge;
} lines;

/* The sum of lane j's extended values at indices below k (k may be
 * outside 0..n): what lies beyond the ends follows the edge mode. */
static double sum_below(const lines *l, int j, long long k)
{
    long long n = l->n;
    const double *sum = l->sum + j;
    size_t L = (size_t)l->lanes;
    if (k >= 0 && k <= n) {
        return sum[(size_t)k * L];
    }
    switch (l->edge) {
    case SR_BLUR_EDGE_DUPLICATE:
        return k < 0 ? (double)k * l->src[j]
                     : sum[(size_t)n * L] + (double)(k - n) * l->src[(size_t)(n - 1) * l->step + j];
    case SR_BLUR_EDGE_WRAP: {
        long long q = k >= 0 ? k / n : -((-k + n - 1) / n);
        return (double)q * sum[(size_t)n * L] + sum[(size_t)(k - q * n) * L];
    }
    default:
        return k < 0 ? 0 : sum[(size_t)n * L];
    }
}

static float value_at(const lines *l, int j, long long k)
{
    long long n = l->n;
    if (k < 0 || k >= n) {
        switch (l->edge) {
        case SR_BLUR_EDGE_DUPLICATE: k = k < 0 ? 0 : n - 1; break;
        case SR_BLUR_EDGE_WRAP: k = ((k % n) + n) % n; break;
        default: return 0;
        }
    }
    return l->src[(size_t)k * l->step + j];
}

/* Each lane's running sum, the lanes side by side. */
static void prefix_sums(lines *l)
{
    size_t L = (size_t)l->lanes;
    double *sum = l->sum;
    for (size_t j = 0; j < L; j++) {
        sum[j] = 0;
    }
    for (int i = 0; i < l->n; i++) {
        const float *v = l->src + (size_t)i * l->step;
        double *prev = sum + (size_t)i * L, *next = prev + L;
        for (size_t j = 0; j < L; j++) {
            next[j] = prev[j] + v[j];
        }
    }
}

/* One box of d values: out[i] = mean of in[i - lo .. i + d - 1 - lo],
 * out laid out as the lanes (i * lanes + j). */
static void box(lines *l, float *out, long long d, long long lo)
{
    prefix_sums(l);
    /* [a, b): both ends of the box on the line, its sums read directly;
     * the ends past the line's ends follow the edge mode */
    long long n = l->n, a = lo < 0 ? 0 : lo > n ? n : lo, b = n - d + lo + 1;
    b = b < a ? a : b > n ? n : b;
    int L = l->lanes;
    const double *sum = l->sum;
    for (long long i = 0; i < n; i++) {
        float *o = out + (size_t)i * (size_t)L;
        if (i >= a && i < b) {
            const double *hi = sum + (size_t)(i - lo + d) * (size_t)L;
            const double *low = sum + (size_t)(i - lo) * (size_t)L;
            for (int j = 0; j < L; j++) {
                o[j] = (float)((hi[j] - low[j]) / (double)d);
            }
            continue;
        }
        for (int j = 0; j < L; j++) {
            o[j] = (float)((sum_below(l, j, i - lo + d) - sum_below(l, j, i - lo)) / (double)d);
        }
    }
}

/* The lines blurred into tmp (n x lanes floats), then copied back over
 * them; out is n x lanes floats of scratch. */
static void blur_lines(lines *l, float *out, float *tmp, double sigma, const float *kernel,
                       int radius)
{
    int n = l->n, L = l->lanes;
    if (sigma < BOX_FROM_SIGMA) {
        for (int i = 0; i < n; i++) {
            float *o = tmp + (size_t)i * (size_t)L;
            if (i >= radius && i + radius < n) {
                /* the whole kernel on the line: the taps read directly,
                 * all lanes at once, each lane summed in the same order
                 * as at the ends */
                double acc[4 * COLUMN_BLOCK];
                for (int j = 0; j < L; j++) {
                    acc[j] = 0;
                }
                const float *v = l->src + (size_t)(i - radius) * l->step;
                for (int k = 0; k <= 2 * radius; k++, v += l->step) {
                    float w = kernel[k];
                    for (int j = 0; j < L; j++) {
                        acc[j] += w * v[j];
                    }
                }
                for (int j = 0; j < L; j++) {
                    o[j] = (float)acc[j];
                }
                continue;
            }
            for (int j = 0; j < L; j++) {
                double s = 0;
                for (int k = -radius; k <= radius; k++) {
                    s += kernel[k + radius] * value_at(l, j, (long long)i + k);
                }
                o[j] = (float)s;
            }
        }
    } else {
        /* d from SVG 1.1: three boxes of d when d is odd; else two of d,
         * centred half a pixel left then right, and one of d + 1. */
        long long d = (long long)floor(sigma * 3 * sqrt(2 * M_PI) / 4 + 0.5);
        lines t = *l;
        bool odd = d % 2 == 1;
        box(l, tmp, d, d / 2);
        t.src = tmp;
        t.step = (size_t)L;
        box(&t, out, d, odd ? d / 2 : d / 2 - 1);
        t.src = out;
        box(&t, tmp, odd ? d : d + 1, d / 2);
    }
    for (int i = 0; i < n; i++) {
        memcpy((float *)l->src + (size_t)i * l->step, tmp + (size_t)i * (size_t)L,
               (size_t)L * sizeof *tmp);
    }
}

sr_result sr_blur_image(sr_context *ctx, float *pixels, int width, int height, int channels,
                        const sr_blur_desc *desc)
{
    static const char fn[] = "sr_blur_image";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_blur_image: ctx is NULL");
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
    /* rows: a row's channels side by side; columns: COLUMN_BLOCK columns' */
    size_t lanes = (size_t)COLUMN_BLOCK * (size_t)channels;
    double *sum = sr__alloc(ctx, ((size_t)longest + 1) * lanes * sizeof *sum);
    float *tmp = sr__alloc(ctx, (size_t)longest * lanes * 2 * sizeof *tmp);
    if (!sum || !tmp) {
        sr__free(ctx, sum);
        sr__free(ctx, tmp);
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
                lines l = { .src = pixels + (size_t)y * (size_t)width * (size_t)channels,
                            .step = (size_t)channels, .n = width, .lanes = channels,
                            .sum = sum, .edge = desc->edge };
                blur_lines(&l, tmp + (size_t)longest * lanes, tmp, s, kernel, radius);
            }
            continue;
        }
        for (int x0 = 0; x0 < width; x0 += COLUMN_BLOCK) {
            int cols = width - x0 < COLUMN_BLOCK ? width - x0 : COLUMN_BLOCK;
            lines l = { .src = pixels + (size_t)x0 * (size_t)channels,
                        .step = (size_t)width * (size_t)channels, .n = height,
                        .lanes = cols * channels, .sum = sum, .edge = desc->edge };
            blur_lines(&l, tmp + (size_t)longest * lanes, tmp, s, kernel, radius);
        }
    }
    sr__free(ctx, sum);
    sr__free(ctx, tmp);
    sr__ok(ctx);
    return SR_OK;
}
