/* polyfill.c - the 2D fill benchmark (bench): a self-intersecting polygon of
 * 10,000 random vertices in a 2048x2048 image, nonzero rule, filled by
 * sr_fill_polygon aliased (edge table and active edge table) or with exact
 * area coverage, and by cairo with the same path, rule and antialiasing
 * when the build found it.  Main thread; the polygon is made once. */
#include "polyfill.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifdef SR_HAVE_CAIRO
#include <cairo.h>
#endif

#define SIZE 2048
#define EDGES 10000

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static void print_line(const char *scene, const char *renderer, int threads, int frames,
                       double *ms)
{
    qsort(ms, (size_t)frames, sizeof *ms, cmp_double);
    double med = ms[frames / 2];
    printf("scene=%s renderer=%s size=%dx%d threads=%d frames=%d median_ms=%.3f min_ms=%.3f "
           "mtri_s=0 mpix_s=%.4g\n",
           scene, renderer, SIZE, SIZE, threads, frames, med, ms[0],
           (double)SIZE * SIZE / (med / 1e3) / 1e6);
    fflush(stdout);
}

bool bench_polyfill(sr_context *ctx, int threads, int frames, bool compare, bool antialias,
                    const char *scene)
{
    sr_point2 *pts = malloc(sizeof *pts * EDGES);
    double *sr_ms = calloc((size_t)frames, sizeof *sr_ms);
    double *cr_ms = calloc((size_t)frames, sizeof *cr_ms);
    sr_framebuffer *fb = NULL;
    bool ok = pts && sr_ms && cr_ms &&
              sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = SIZE, .height = SIZE,
                                                              .depth_format = SR_DEPTH_NONE },
                                  &fb) == SR_OK;
    if (!ok) {
        fprintf(stderr, "softrast-bench: %s: out of memory\n", scene);
        goto done;
    }
    uint64_t rng = 0x9017f111;
    for (int i = 0; i < EDGES; i++) {
        rng ^= rng >> 12;
        rng ^= rng << 25;
        rng ^= rng >> 27;
        uint64_t r = rng * 2685821657736338717ULL;
        pts[i].x = (double)(r & 0xffffff) / 0xffffff * SIZE;
        pts[i].y = (double)((r >> 24) & 0xffffff) / 0xffffff * SIZE;
    }
    sr_polygon2 poly = { .points = pts, .point_count = EDGES };
    sr_fill_desc desc = { .rule = SR_NONZERO, .antialias = antialias ? SR_AA_AREA : SR_AA_NONE };
    sr_rgba color = { 0.9f, 0.6f, 0.2f, 1.0f };

#ifdef SR_HAVE_CAIRO
    cairo_surface_t *surface = NULL;
    cairo_t *cr = NULL;
    if (compare) {
        surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, SIZE, SIZE);
        cr = cairo_create(surface);
        cairo_set_fill_rule(cr, CAIRO_FILL_RULE_WINDING);
        cairo_set_antialias(cr, antialias ? CAIRO_ANTIALIAS_DEFAULT : CAIRO_ANTIALIAS_NONE);
    }
#else
    if (compare) {
        fprintf(stderr, "softrast-bench: %s: cairo comparison skipped (install libcairo2-dev "
                        "and rebuild)\n", scene);
    }
#endif
    for (int f = -2; f < frames; f++) {
        double t0 = now_ms();
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
        if (sr_fill_polygon(ctx, fb, &poly, color, &desc) != SR_OK) {
            fprintf(stderr, "softrast-bench: %s: %s\n", scene, sr_context_error(ctx));
            ok = false;
            break;
        }
        sr_framebuffer_pixels(fb); /* the frame is done when every pixel is in memory */
        double t1 = now_ms();
        if (f >= 0) {
            sr_ms[f] = t1 - t0;
        }
#ifdef SR_HAVE_CAIRO
        if (cr) {
            double c0 = now_ms();
            cairo_set_source_rgb(cr, 0, 0, 0);
            cairo_paint(cr);
            cairo_set_source_rgb(cr, 0.9, 0.6, 0.2);
            cairo_move_to(cr, pts[0].x, pts[0].y);
            for (int i = 1; i < EDGES; i++) {
                cairo_line_to(cr, pts[i].x, pts[i].y);
            }
            cairo_close_path(cr);
            cairo_fill(cr);
            cairo_surface_flush(surface);
            if (f >= 0) {
                cr_ms[f] = now_ms() - c0;
            }
        }
#endif
    }
    if (ok) {
        print_line(scene, "softrast", threads, frames, sr_ms);
#ifdef SR_HAVE_CAIRO
        if (cr) {
            double sr_med = sr_ms[frames / 2];
            print_line(scene, "cairo", 1, frames, cr_ms);
            printf("scene=%s size=%dx%d threads=%d ratio=%.3f\n", scene, SIZE, SIZE, threads,
                   cr_ms[frames / 2] / sr_med);
            fflush(stdout);
        }
#endif
    }
#ifdef SR_HAVE_CAIRO
    if (cr) {
        cairo_destroy(cr);
        cairo_surface_destroy(surface);
    }
#endif
done:
    sr_destroy_framebuffer(ctx, fb);
    free(pts);
    free(sr_ms);
    free(cr_ms);
    return ok;
}
