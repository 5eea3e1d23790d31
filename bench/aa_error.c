/* aa_error.c - how far an antialiased image is from the ideal one at the
 * silhouette: softrast-aa-error REF.png K IMAGE.png...
 *
 * REF.png is the same scene rendered K times wider and taller without
 * antialiasing; averaging each K x K block of it gives the reference image
 * (K = 16: 256 samples per pixel).  The edge pixels are those whose block
 * holds both background samples (the colour of REF's corner pixel) and
 * model samples: where antialiasing acts on a silhouette.  For each IMAGE
 * it prints the root mean square and the largest channel error on those
 * pixels, in 0..255 levels. */
#include "softrast_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: softrast-aa-error REF.png K IMAGE.png...\n");
        return 2;
    }
    int k = atoi(argv[2]);
    int rw, rh;
    uint8_t *ref;
    sr_io_error err;
    if (k < 1 || sr_read_png(argv[1], NULL, &rw, &rh, &ref, &err) != SR_OK) {
        fprintf(stderr, "%s\n", k < 1 ? "K must be a positive integer" : err.message);
        return 2;
    }
    int w = rw / k, h = rh / k;
    if (w * k != rw || h * k != rh) {
        fprintf(stderr, "%s: %dx%d is not a multiple of %d\n", argv[1], rw, rh, k);
        return 2;
    }
    /* The block averages, and which blocks are edges. */
    double *avg = calloc((size_t)w * h * 3, sizeof *avg);
    unsigned char *edge = calloc((size_t)w * h, 1);
    if (!avg || !edge) {
        fprintf(stderr, "out of memory\n");
        return 1;
    }
    const uint8_t *bg = ref;
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            int n_bg = 0;
            double sum[3] = { 0, 0, 0 };
            for (int sy = 0; sy < k; sy++) {
                for (int sx = 0; sx < k; sx++) {
                    const uint8_t *p = &ref[(((size_t)y * k + sy) * rw + (size_t)x * k + sx) * 4];
                    n_bg += memcmp(p, bg, 3) == 0;
                    for (int c = 0; c < 3; c++) {
                        sum[c] += p[c];
                    }
                }
            }
            for (int c = 0; c < 3; c++) {
                avg[((size_t)y * w + x) * 3 + c] = sum[c] / (k * k);
            }
            edge[(size_t)y * w + x] = n_bg > 0 && n_bg < k * k;
        }
    }
    free(ref);
    for (int i = 3; i < argc; i++) {
        int iw, ih;
        uint8_t *img;
        if (sr_read_png(argv[i], NULL, &iw, &ih, &img, &err) != SR_OK) {
            fprintf(stderr, "%s\n", err.message);
            return 2;
        }
        if (iw != w || ih != h) {
            fprintf(stderr, "%s: %dx%d, the reference is %dx%d\n", argv[i], iw, ih, w, h);
            return 2;
        }
        double se = 0.0, worst = 0.0;
        long n = 0;
        for (size_t p = 0; p < (size_t)w * h; p++) {
            if (!edge[p]) {
                continue;
            }
            for (int c = 0; c < 3; c++) {
                double d = img[p * 4 + c] - avg[p * 3 + c];
                se += d * d;
                worst = fmax(worst, fabs(d));
            }
            n++;
        }
        printf("%s: edge_pixels=%ld rms=%.2f max=%.0f\n", argv[i], n, n ? sqrt(se / (3.0 * n)) : 0.0,
               worst);
        free(img);
    }
    free(avg);
    free(edge);
    return 0;
}
