/* shapes2d.c - the 2D shape benchmark (bench), modelled on Blend2D's
 * bl_bench: batches of rectangles, polygons of 10, 20 and 40 random
 * vertices (nonzero) and closed cubic curves, 8 to 256 px, at random
 * places on a 512x600 canvas, painted solid (random colors, alpha 0.5-1),
 * with a linear or with a radial gradient over each shape's bounding box,
 * or with a pattern (a 16 px tile of three colors repeated over the
 * canvas), antialiased.  softrast renders each batch twice: as one SVG
 * document (sr_render_svg: parsing, flattening, coverage and paint, as
 * `softrast svg` does), and through its API (sr_fill_path_paint, shape by
 * shape on a canvas cleared per frame); cairo draws the same shapes
 * through its API, frame by frame in the same run.  Main thread; each
 * batch is made once. */
#include "shapes2d.h"

#include "softrast_io.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifdef SR_HAVE_CAIRO
#include <cairo.h>
#endif

#define CANVAS_W 512
#define CANVAS_H 600
#define MAX_VERTS 40
#define MAX_SHAPES 1000
/* Shapes per batch: MAX_SHAPES, fewer for large sizes so a batch's
 * bounding boxes stay within the SVG renderer's fill-work budget. */
#define BATCH_PIXELS 10000000
/* Timed frames per case at most: 120 cases make a long run already. */
#define MAX_FRAMES 5

typedef enum shape_kind { SHAPE_RECT, SHAPE_POLY, SHAPE_CURVE } shape_kind;
typedef enum paint_kind { PAINT_SOLID, PAINT_LINEAR, PAINT_RADIAL, PAINT_PATTERN } paint_kind;

static const struct { const char *name; shape_kind kind; int verts; } shapes[] = {
    { "rect", SHAPE_RECT, 4 },   { "poly10", SHAPE_POLY, 10 }, { "poly20", SHAPE_POLY, 20 },
    { "poly40", SHAPE_POLY, 40 }, { "curves", SHAPE_CURVE, 13 },
};
static const char *const paint_names[] = { "solid", "linear", "radial", "pattern" };
#define PAINT_COUNT 4
static const int sizes[] = { 8, 16, 32, 64, 128, 256 };
/* The gradients' stops, shared by both renderers. */
static const double stops[3][4] = { { 0, 0.9, 0.2, 0.1 }, { 0.5, 0.2, 0.7, 0.9 },
                                    { 1, 1.0, 0.9, 0.2 } };
/* The pattern's tile: a square of the first color, its top left and
 * bottom right quarters in the others (x, y, size, r, g, b). */
#define TILE 16
static const int tile_rects[3][6] = { { 0, 0, 16, 230, 200, 60 }, { 0, 0, 8, 40, 90, 200 },
                                      { 8, 8, 8, 200, 40, 90 } };

/* One shape: its points (a rectangle's corners, a polygon's vertices, or
 * a start point and four cubic segments for a curve) and its color. */
typedef struct shape {
    double x[MAX_VERTS], y[MAX_VERTS];
    double r, g, b, a;
} shape;

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static double rng_unit(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ULL) >> 11) / 9007199254740992.0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static void make_batch(shape *sh, int count, shape_kind kind, int verts, int size, uint64_t *rng)
{
    for (int i = 0; i < count; i++) {
        shape *s = &sh[i];
        double ox = rng_unit(rng) * (CANVAS_W - size), oy = rng_unit(rng) * (CANVAS_H - size);
        if (kind == SHAPE_RECT) {
            s->x[0] = ox;
            s->y[0] = oy;
        } else {
            for (int k = 0; k < verts; k++) {
                s->x[k] = ox + rng_unit(rng) * size;
                s->y[k] = oy + rng_unit(rng) * size;
            }
        }
        s->r = rng_unit(rng);
        s->g = rng_unit(rng);
        s->b = rng_unit(rng);
        s->a = 0.5 + 0.5 * rng_unit(rng);
    }
}

/* Append printf output to a growing buffer; false when out of memory. */
typedef struct text { char *p; size_t len, cap; } text;

static bool put(text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static bool put(text *t, const char *fmt, ...)
{
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        int n = vsnprintf(t->p ? t->p + t->len : NULL, t->p ? t->cap - t->len : 0, fmt, ap);
        va_end(ap);
        if (n < 0) {
            return false;
        }
        if (t->p && t->len + (size_t)n < t->cap) {
            t->len += (size_t)n;
            return true;
        }
        size_t cap = (t->cap + (size_t)n + 1) * 2;
        char *p = realloc(t->p, cap);
        if (!p) {
            return false;
        }
        t->p = p;
        t->cap = cap;
    }
}

static bool svg_stops(text *t)
{
    bool ok = true;
    for (int k = 0; k < 3; k++) {
        ok = ok && put(t, "<stop offset='%g' stop-color='rgb(%d,%d,%d)'/>", stops[k][0],
                       (int)(stops[k][1] * 255 + 0.5), (int)(stops[k][2] * 255 + 0.5),
                       (int)(stops[k][3] * 255 + 0.5));
    }
    return ok;
}

static bool svg_tile(text *t)
{
    bool ok = put(t, "<pattern id='p' width='%d' height='%d' patternUnits='userSpaceOnUse'>",
                  TILE, TILE);
    for (int k = 0; ok && k < 3; k++) {
        const int *q = tile_rects[k];
        ok = put(t, "<rect x='%d' y='%d' width='%d' height='%d' fill='rgb(%d,%d,%d)'/>", q[0],
                 q[1], q[2], q[2], q[3], q[4], q[5]);
    }
    return ok && put(t, "</pattern>");
}

/* The batch as an SVG document; the gradients use objectBoundingBox
 * units (the default), so one definition paints every shape's box; the
 * pattern is in user space, one tile grid over the canvas. */
static bool batch_svg(text *t, const shape *sh, int count, shape_kind kind, int verts, int size,
                      paint_kind paint)
{
    bool ok = put(t, "<svg xmlns='http://www.w3.org/2000/svg' width='%d' height='%d'><defs>"
                     "<linearGradient id='l'>", CANVAS_W, CANVAS_H) &&
              svg_stops(t) && put(t, "</linearGradient><radialGradient id='r'>") &&
              svg_stops(t) && put(t, "</radialGradient>") && svg_tile(t) &&
              put(t, "</defs>\n");
    for (int i = 0; ok && i < count; i++) {
        const shape *s = &sh[i];
        if (kind == SHAPE_RECT) {
            ok = put(t, "<rect x='%.3f' y='%.3f' width='%d' height='%d'", s->x[0], s->y[0], size,
                     size);
        } else if (kind == SHAPE_POLY) {
            ok = put(t, "<polygon points='");
            for (int k = 0; ok && k < verts; k++) {
                ok = put(t, "%.3f,%.3f ", s->x[k], s->y[k]);
            }
            ok = ok && put(t, "'");
        } else {
            ok = put(t, "<path d='M%.3f,%.3f C", s->x[0], s->y[0]);
            for (int k = 1; ok && k < verts; k++) {
                ok = put(t, " %.3f,%.3f", s->x[k], s->y[k]);
            }
            ok = ok && put(t, " Z'");
        }
        if (ok && paint == PAINT_SOLID) {
            ok = put(t, " fill='rgb(%d,%d,%d)' fill-opacity='%.3f'/>\n", (int)(s->r * 255 + 0.5),
                     (int)(s->g * 255 + 0.5), (int)(s->b * 255 + 0.5), s->a);
        } else if (ok) {
            ok = put(t, " fill='url(#%c)'/>\n", "slrp"[paint]);
        }
    }
    return ok && put(t, "</svg>\n");
}

#ifdef SR_HAVE_CAIRO
static void cairo_shape(cairo_t *cr, const shape *s, shape_kind kind, int verts, int size)
{
    if (kind == SHAPE_RECT) {
        cairo_rectangle(cr, s->x[0], s->y[0], size, size);
        return;
    }
    cairo_move_to(cr, s->x[0], s->y[0]);
    if (kind == SHAPE_POLY) {
        for (int k = 1; k < verts; k++) {
            cairo_line_to(cr, s->x[k], s->y[k]);
        }
    } else {
        for (int k = 1; k + 2 < verts; k += 3) {
            cairo_curve_to(cr, s->x[k], s->y[k], s->x[k + 1], s->y[k + 1], s->x[k + 2],
                           s->y[k + 2]);
        }
    }
    cairo_close_path(cr);
}

/* The pattern's tile as a repeating cairo pattern, made once per batch as
 * an application keeps its textures. */
static cairo_pattern_t *cairo_tile(void)
{
    cairo_surface_t *s = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, TILE, TILE);
    cairo_t *cr = cairo_create(s);
    for (int k = 0; k < 3; k++) {
        const int *q = tile_rects[k];
        cairo_rectangle(cr, q[0], q[1], q[2], q[2]);
        cairo_set_source_rgb(cr, q[3] / 255.0, q[4] / 255.0, q[5] / 255.0);
        cairo_fill(cr);
    }
    cairo_destroy(cr);
    cairo_pattern_t *p = cairo_pattern_create_for_surface(s);
    cairo_pattern_set_extend(p, CAIRO_EXTEND_REPEAT);
    cairo_surface_destroy(s);
    return p;
}

static void cairo_batch(cairo_t *cr, const shape *sh, int count, shape_kind kind, int verts,
                        int size, paint_kind paint, cairo_pattern_t *tile)
{
    cairo_set_operator(cr, CAIRO_OPERATOR_CLEAR);
    cairo_paint(cr);
    cairo_set_operator(cr, CAIRO_OPERATOR_OVER);
    for (int i = 0; i < count; i++) {
        const shape *s = &sh[i];
        cairo_shape(cr, s, kind, verts, size);
        if (paint == PAINT_SOLID) {
            cairo_set_source_rgba(cr, s->r, s->g, s->b, s->a);
            cairo_fill(cr);
            continue;
        }
        if (paint == PAINT_PATTERN) {
            cairo_set_source(cr, tile);
            cairo_fill(cr);
            continue;
        }
        /* The gradient over the unit square, mapped onto the shape's box. */
        double x0, y0, x1, y1;
        cairo_path_extents(cr, &x0, &y0, &x1, &y1);
        cairo_pattern_t *p = paint == PAINT_LINEAR
                                 ? cairo_pattern_create_linear(0, 0, 1, 0)
                                 : cairo_pattern_create_radial(0.5, 0.5, 0, 0.5, 0.5, 0.5);
        for (int k = 0; k < 3; k++) {
            cairo_pattern_add_color_stop_rgb(p, stops[k][0], stops[k][1], stops[k][2],
                                             stops[k][3]);
        }
        cairo_matrix_t m;
        cairo_matrix_init(&m, x1 - x0 > 0 ? x1 - x0 : 1, 0, 0, y1 - y0 > 0 ? y1 - y0 : 1, x0,
                          y0);
        cairo_matrix_invert(&m);
        cairo_pattern_set_matrix(p, &m);
        cairo_set_source(cr, p);
        cairo_fill(cr);
        cairo_pattern_destroy(p);
    }
}
#endif

/* The shape as a path (a curve: a start point and cubic segments). */
static sr_result api_shape(sr_path *path, const shape *s, shape_kind kind, int verts, int size)
{
    sr_path_clear(path);
    sr_result r = sr_path_move_to(path, s->x[0], s->y[0]);
    if (kind == SHAPE_RECT) {
        double x = s->x[0], y = s->y[0];
        r = r ? r : sr_path_line_to(path, x + size, y);
        r = r ? r : sr_path_line_to(path, x + size, y + size);
        r = r ? r : sr_path_line_to(path, x, y + size);
    }
    for (int k = 1; kind == SHAPE_POLY && k < verts; k++) {
        r = r ? r : sr_path_line_to(path, s->x[k], s->y[k]);
    }
    for (int k = 1; kind == SHAPE_CURVE && k + 2 < verts; k += 3) {
        r = r ? r : sr_path_cubic_to(path, s->x[k], s->y[k], s->x[k + 1], s->y[k + 1],
                                     s->x[k + 2], s->y[k + 2]);
    }
    return r ? r : sr_path_close(path);
}

/* The batch through softrast's API on fb, cleared first: each shape's
 * path built and filled with its paint, the gradients over the unit
 * square mapped onto the flattened shape's box (objectBoundingBox, as the
 * document says), the pattern's tile (made once per batch, as an
 * application keeps its images) repeated over the canvas. */
static sr_result api_batch(sr_context *ctx, sr_framebuffer *fb, sr_path *path, const shape *sh,
                           int count, shape_kind kind, int verts, int size, paint_kind paint,
                           const uint8_t *tile)
{
    sr_gradient_stop st[3];
    for (int k = 0; k < 3; k++) {
        st[k] = (sr_gradient_stop){ stops[k][0], { (float)stops[k][1], (float)stops[k][2],
                                                   (float)stops[k][3], 1 } };
    }
    sr_result r = sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
    const sr_fill_desc desc = { .antialias = SR_AA_AREA };
    for (int i = 0; r == SR_OK && i < count; i++) {
        const shape *s = &sh[i];
        r = api_shape(path, s, kind, verts, size);
        sr_affine2 box = { 1, 0, 0, 1, 0, 0 };
        sr_paint p = { .kind = SR_PAINT_COLOR,
                       .color = { (float)s->r, (float)s->g, (float)s->b, (float)s->a } };
        if (paint == PAINT_LINEAR || paint == PAINT_RADIAL) {
            sr_polygon2 poly = sr_path_polygon(path);
            double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
            for (int k = 0; k < poly.point_count; k++) {
                x0 = fmin(x0, poly.points[k].x);
                x1 = fmax(x1, poly.points[k].x);
                y0 = fmin(y0, poly.points[k].y);
                y1 = fmax(y1, poly.points[k].y);
            }
            box = (sr_affine2){ x1 - x0 > 0 ? x1 - x0 : 1, 0, 0, y1 - y0 > 0 ? y1 - y0 : 1, x0, y0 };
            p = paint == PAINT_LINEAR
                    ? (sr_paint){ .kind = SR_PAINT_LINEAR_GRADIENT, .x2 = 1 }
                    : (sr_paint){ .kind = SR_PAINT_RADIAL_GRADIENT, .cx = 0.5, .cy = 0.5,
                                  .r = 0.5 };
            p.stops = st;
            p.stop_count = 3;
            p.transform = &box;
        } else if (paint == PAINT_PATTERN) {
            p = (sr_paint){ .kind = SR_PAINT_PATTERN, .image = tile, .image_width = TILE,
                            .image_height = TILE };
        }
        r = r ? r : sr_fill_path_paint(ctx, fb, path, &p, &desc);
    }
    return r;
}

/* The pattern's tile as RGBA8, the document's rects painted into it. */
static void api_tile(uint8_t *px)
{
    for (int y = 0; y < TILE; y++) {
        for (int x = 0; x < TILE; x++) {
            for (int k = 2; k >= 0; k--) {
                const int *q = tile_rects[k];
                if (x >= q[0] && x < q[0] + q[2] && y >= q[1] && y < q[1] + q[2]) {
                    uint8_t c[4] = { (uint8_t)q[3], (uint8_t)q[4], (uint8_t)q[5], 255 };
                    memcpy(px + (y * TILE + x) * 4, c, 4);
                    break;
                }
            }
        }
    }
}

/* Times one batch on the three renderers, alternating; false on failure. */
static bool run_case(sr_context *ctx, int frames, bool compare, const char *svg, size_t len,
                     const shape *sh, int count, int si, int size, paint_kind paint,
                     double *ms, double *api_ms, double *cr_ms, double *log_ratio,
                     double *log_api_ratio)
{
    sr_framebuffer *canvas = NULL;
    sr_path *path = NULL;
    static uint8_t tile_px[TILE * TILE * 4];
    api_tile(tile_px);
    if (sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = CANVAS_W, .height = CANVAS_H,
                                                         .depth_format = SR_DEPTH_NONE },
                            &canvas) != SR_OK ||
        sr_make_path(ctx, 0, &path) != SR_OK) {
        fprintf(stderr, "softrast-bench: shapes2d: %s\n", sr_context_error(ctx));
        sr_destroy_framebuffer(ctx, canvas);
        return false;
    }
#ifdef SR_HAVE_CAIRO
    cairo_surface_t *surface = compare ? cairo_image_surface_create(CAIRO_FORMAT_ARGB32,
                                                                    CANVAS_W, CANVAS_H)
                                       : NULL;
    cairo_t *cr = surface ? cairo_create(surface) : NULL;
    cairo_pattern_t *tile = surface ? cairo_tile() : NULL;
#else
    (void)compare;
    (void)cr_ms;
    (void)log_ratio;
    (void)log_api_ratio;
#endif
    sr_svg_desc desc = { .name = "shapes2d" };
    for (int f = -1; f < frames; f++) {
        double t0 = now_ms();
        sr_framebuffer *fb = NULL;
        sr_io_error err;
        if (sr_render_svg(ctx, svg, len, &desc, &fb, NULL, &err) != SR_OK) {
            fprintf(stderr, "softrast-bench: shapes2d %s %d: %s\n", shapes[si].name, size,
                    err.message);
#ifdef SR_HAVE_CAIRO
            cairo_pattern_destroy(tile);
            cairo_destroy(cr);
            cairo_surface_destroy(surface);
#endif
            sr_destroy_path(ctx, path);
            sr_destroy_framebuffer(ctx, canvas);
            return false;
        }
        sr_framebuffer_pixels(fb);
        sr_destroy_framebuffer(ctx, fb);
        if (f >= 0) {
            ms[f] = now_ms() - t0;
        }
        double a0 = now_ms();
        if (api_batch(ctx, canvas, path, sh, count, shapes[si].kind, shapes[si].verts, size,
                      paint, tile_px) != SR_OK) {
            fprintf(stderr, "softrast-bench: shapes2d %s %d: %s\n", shapes[si].name, size,
                    sr_context_error(ctx));
            frames = f < 0 ? 0 : f; /* report nothing more of this case */
            break;
        }
        sr_framebuffer_pixels(canvas);
        if (f >= 0) {
            api_ms[f] = now_ms() - a0;
        }
#ifdef SR_HAVE_CAIRO
        if (cr) {
            double c0 = now_ms();
            cairo_batch(cr, sh, count, shapes[si].kind, shapes[si].verts, size, paint, tile);
            cairo_surface_flush(surface);
            if (f >= 0) {
                cr_ms[f] = now_ms() - c0;
            }
        }
#endif
    }
    sr_destroy_path(ctx, path);
    sr_destroy_framebuffer(ctx, canvas);
    bool ok = frames > 0;
    if (!ok) {
        frames = 1; /* the buffers below are released, nothing printed */
    }
    qsort(ms, (size_t)frames, sizeof *ms, cmp_double);
    qsort(api_ms, (size_t)frames, sizeof *api_ms, cmp_double);
    if (ok) {
        printf("scene=shapes2d shape=%s size=%d paint=%s shapes=%d renderer=softrast frames=%d "
               "median_ms=%.3f min_ms=%.3f\n"
               "scene=shapes2d shape=%s size=%d paint=%s shapes=%d renderer=softrast-api "
               "frames=%d median_ms=%.3f min_ms=%.3f\n",
               shapes[si].name, size, paint_names[paint], count, frames, ms[frames / 2], ms[0],
               shapes[si].name, size, paint_names[paint], count, frames, api_ms[frames / 2],
               api_ms[0]);
    }
#ifdef SR_HAVE_CAIRO
    if (cr && ok) {
        qsort(cr_ms, (size_t)frames, sizeof *cr_ms, cmp_double);
        double ratio = cr_ms[frames / 2] / ms[frames / 2];
        double api_ratio = cr_ms[frames / 2] / api_ms[frames / 2];
        printf("scene=shapes2d shape=%s size=%d paint=%s shapes=%d renderer=cairo frames=%d "
               "median_ms=%.3f min_ms=%.3f\n"
               "scene=shapes2d shape=%s size=%d paint=%s ratio=%.3f api_ratio=%.3f\n",
               shapes[si].name, size, paint_names[paint], count, frames, cr_ms[frames / 2],
               cr_ms[0], shapes[si].name, size, paint_names[paint], ratio, api_ratio);
        *log_ratio += log(ratio);
        *log_api_ratio += log(api_ratio);
    }
    if (cr) {
        cairo_pattern_destroy(tile);
        cairo_destroy(cr);
        cairo_surface_destroy(surface);
    }
#endif
    fflush(stdout);
    return ok;
}

/* The items of a comma-separated list among names[0..n) as a bit set (bit
 * k: names[k]); 0 after a message naming the option when an item is
 * unknown or the list empty. */
static unsigned name_set(const char *opt, const char *list, const char *const *names, int n)
{
    unsigned set = 0;
    for (const char *s = list; *s;) {
        size_t len = strcspn(s, ",");
        int k = 0;
        while (k < n && !(strlen(names[k]) == len && strncmp(s, names[k], len) == 0)) {
            k++;
        }
        if (k == n) {
            fprintf(stderr, "softrast-bench: %s: unknown item '%.*s' (expected", opt, (int)len,
                    s);
            for (int i = 0; i < n; i++) {
                fprintf(stderr, "%s%s", i ? ", " : " ", names[i]);
            }
            fprintf(stderr, ")\n");
            return 0;
        }
        set |= 1u << k;
        s += len + (s[len] == ',');
    }
    if (set == 0) {
        fprintf(stderr, "softrast-bench: %s: empty list\n", opt);
    }
    return set;
}

static const char *const shape_names[] = { "rect", "poly10", "poly20", "poly40", "curves" };
static const char *const size_names[] = { "8", "16", "32", "64", "128", "256" };
_Static_assert(sizeof shape_names / sizeof shape_names[0] == sizeof shapes / sizeof shapes[0],
               "a name per shape");
_Static_assert(sizeof size_names / sizeof size_names[0] == sizeof sizes / sizeof sizes[0],
               "a name per size");

unsigned bench_shapes2d_paints(const char *list)
{
    return name_set("--paint", list, paint_names, PAINT_COUNT);
}

unsigned bench_shapes2d_shapes(const char *list)
{
    return name_set("--shape", list, shape_names, (int)(sizeof shape_names / sizeof *shape_names));
}

unsigned bench_shapes2d_sizes(const char *list)
{
    return name_set("--shape-size", list, size_names, (int)(sizeof size_names / sizeof *size_names));
}

bool bench_shapes2d(sr_context *ctx, int frames, bool compare, const shapes2d_cases *only)
{
    unsigned paint_set = only->paints ? bench_shapes2d_paints(only->paints) : ~0u;
    unsigned shape_set = only->shapes ? bench_shapes2d_shapes(only->shapes) : ~0u;
    unsigned size_set = only->sizes ? bench_shapes2d_sizes(only->sizes) : ~0u;
    frames = frames > MAX_FRAMES ? MAX_FRAMES : frames;
    shape *sh = malloc(sizeof *sh * MAX_SHAPES);
    double *ms = calloc((size_t)frames, sizeof *ms), *cr_ms = calloc((size_t)frames, sizeof *ms);
    double *api_ms = calloc((size_t)frames, sizeof *ms);
    text t = { 0 };
    bool ok = sh && ms && cr_ms && api_ms;
    if (!ok) {
        fprintf(stderr, "softrast-bench: shapes2d: out of memory\n");
    }
#ifndef SR_HAVE_CAIRO
    if (compare) {
        fprintf(stderr, "softrast-bench: shapes2d: cairo comparison skipped (install "
                        "libcairo2-dev and rebuild)\n");
    }
#endif
    if (ok && !sr_io_have_svg()) {
        fprintf(stderr, "softrast-bench: shapes2d: this build reads no SVG (install libexpat1-dev)\n");
        ok = false;
    }
    double log_ratio = 0, log_api_ratio = 0;
    int cases = 0;
    uint64_t rng = 0x5ba9e2d1;
    for (int si = 0; ok && si < (int)(sizeof shapes / sizeof shapes[0]); si++) {
        for (int zi = 0; ok && zi < (int)(sizeof sizes / sizeof sizes[0]); zi++) {
            int size = sizes[zi];
            int count = BATCH_PIXELS / (size * size);
            count = count > MAX_SHAPES ? MAX_SHAPES : count;
            make_batch(sh, count, shapes[si].kind, shapes[si].verts, size, &rng);
            for (int p = PAINT_SOLID; ok && p < PAINT_COUNT; p++) {
                if (!(paint_set & 1u << p) || !(shape_set & 1u << si) || !(size_set & 1u << zi)) {
                    continue; /* the batch was still made: the others stay the same */
                }
                t.len = 0;
                ok = batch_svg(&t, sh, count, shapes[si].kind, shapes[si].verts, size,
                               (paint_kind)p);
                if (!ok) {
                    fprintf(stderr, "softrast-bench: shapes2d: out of memory\n");
                    break;
                }
                ok = run_case(ctx, frames, compare, t.p, t.len, sh, count, si, size,
                              (paint_kind)p, ms, api_ms, cr_ms, &log_ratio, &log_api_ratio);
                cases++;
            }
        }
    }
#ifdef SR_HAVE_CAIRO
    if (ok && compare && cases > 0) {
        printf("scene=shapes2d cases=%d geomean_ratio=%.3f geomean_api_ratio=%.3f\n", cases,
               exp(log_ratio / cases), exp(log_api_ratio / cases));
    }
#endif
    free(sh);
    free(ms);
    free(cr_ms);
    free(api_ms);
    free(t.p);
    return ok;
}
