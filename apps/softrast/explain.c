/* explain.c - `softrast explain ALGORITHM [options]`: parses the primitive
 * and the outputs, runs one algorithm's steps (explain_*.c) and writes them
 * as numbered PNG frames and/or a contact sheet of all of them. */
#include "cli.h"
#include "explain.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define MAX_GRID 256
#define SHEET_GAP 8

typedef struct algorithm {
    const char *name;
    ex_kind kind;                /* the primitive it takes */
    ex_algorithm_fn run;
    ex_primitive example;        /* used when no primitive is given */
    int grid_w, grid_h, zoom;    /* defaults that fit the example */
    const char *summary;
} algorithm;

static const algorithm algorithms[] = {
    { "triangle", EX_TRIANGLE, explain_triangle,
      { .kind = EX_TRIANGLE, .pts = { { 2.5, 1.5 }, { 12.5, 1.5 }, { 4.5, 11.5 } }, .count = 3 }, 15, 13, 32,
      "edge functions E0..E2 at each pixel centre, the top-left\n"
      "             rule on ties, coverage" },
    { "msaa", EX_TRIANGLE, explain_msaa,
      { .kind = EX_TRIANGLE, .pts = { { 1.3, 1.2 }, { 10.6, 3.4 }, { 3.2, 8.7 } }, .count = 3 },
      12, 10, 40, "the triangle's coverage per sample and the resolve (--samples)" },
    { "scanline", EX_POLYGON, explain_scanline,
      { .kind = EX_POLYGON, .pts = { { 1.3, 1.4 }, { 7.0, 4.5 }, { 13.7, 1.4 }, { 10.5, 10.5 },
                                     { 3.5, 10.5 }, { 1.3, 6.5 } }, .count = 6 }, 16, 12, 32,
      "the polygon fill's edge table, then the active edge table,\n"
      "             parity and spans on each scanline" },
    { "clip", EX_POLYGON, explain_clip,
      { .kind = EX_POLYGON, .pts = { { 1.2, 5.3 }, { 7.5, 0.6 }, { 15.2, 4.4 }, { 11.3, 11.5 },
                                     { 6.2, 7.4 }, { 4.1, 11.2 } }, .count = 6,
        .window = { 3, 2, 13, 10 } }, 16, 12, 32,
      "Sutherland-Hodgman against a window, after each clip edge" },
    { "bresenham", EX_LINE, explain_bresenham,
      { .kind = EX_LINE, .pts = { { 1.5, 2.5 }, { 13.5, 7.5 } }, .count = 2 }, 16, 10, 32,
      "the midpoint line's decision variable at each step (ends on\n"
      "             pixel centres, x.5,y.5)" },
    { "dda", EX_LINE, explain_dda,
      { .kind = EX_LINE, .pts = { { 1.2, 2.7 }, { 14.6, 8.1 } }, .count = 2 }, 16, 10, 32,
      "the incremental DDA: the minor coordinate stepped by the slope" },
};

static void usage(FILE *f)
{
    fprintf(f,
            "usage: softrast explain ALGORITHM [options]\n"
            "\n"
            "Draw the steps of one primitive through one algorithm, on a magnified\n"
            "pixel grid with captions, all drawn by softrast.  The last step shows\n"
            "exactly the pixels the library draws for that primitive.\n"
            "\n"
            "algorithms:\n");
    for (size_t i = 0; i < sizeof algorithms / sizeof algorithms[0]; i++) {
        fprintf(f, "  %-10s %s\n", algorithms[i].name, algorithms[i].summary);
    }
    fprintf(f,
            "\n"
            "primitive (window coordinates in pixels, y down; each algorithm has an\n"
            "example it uses when none is given):\n"
            "  --triangle X0,Y0,X1,Y1,X2,Y2\n"
            "  --polygon X,Y,X,Y,...      3 to %d vertices\n"
            "  --line X0,Y0,X1,Y1\n"
            "  --window XMIN,YMIN,XMAX,YMAX\n"
            "                             clip: the clip window\n"
            "  --samples N                msaa: 2, 4 (the default), 8 or 16 per pixel\n"
            "  --fill-rule evenodd|nonzero\n"
            "                             polygons: inside by parity (the default) or by\n"
            "                             winding number\n"
            "\n"
            "view:\n"
            "  --grid WxH                 pixels shown (from 1x1 to %dx%d)\n"
            "  --zoom N                   frame pixels per pixel, 4 to 64; the grid times\n"
            "                             the zoom at most 4096 a side, all the frames\n"
            "                             at most 1 GiB\n"
            "\n"
            "output (at least one):\n"
            "  -o DIR | -o PATTERN        one PNG per step: DIR/frame-001.png, ... (DIR is\n"
            "                             made if missing), or a PATTERN with one %%d,\n"
            "                             e.g. out/step-%%02d.png\n"
            "  --sheet FILE.png           all the steps on one captioned contact sheet\n",
            EX_MAX_POINTS, MAX_GRID, MAX_GRID);
}

/* "x,y,x,y,..." into pts; false after one line naming the option. */
static bool parse_points(const char *opt, const char *s, int min, int max, bool exact,
                         ex_primitive *prim)
{
    double v[2 * EX_MAX_POINTS];
    int n = 0;
    const char *p = s;
    for (;;) {
        char *end;
        errno = 0;
        double d = strtod(p, &end);
        if (errno || end == p || !isfinite(d) || fabs(d) > 16384 || n == 2 * max) {
            break;
        }
        v[n++] = d;
        if (*end == 0) {
            if (n % 2 == 0 && n / 2 >= min) {
                prim->count = n / 2;
                for (int i = 0; i < prim->count; i++) {
                    prim->pts[i] = (sr_point2){ v[2 * i], v[2 * i + 1] };
                }
                return true;
            }
            break;
        }
        if (*end != ',') {
            break;
        }
        p = end + 1;
    }
    if (exact) {
        cli_error("%s: expected %d numbers X,Y,... in -16384..16384 (got '%s')", opt, 2 * min, s);
    } else {
        cli_error("%s: expected %d to %d X,Y pairs in -16384..16384 (got '%s')", opt, min, max, s);
    }
    return false;
}

/* A frame file name: a pattern with one %d (flags and width allowed), or
 * a directory. */
static bool frame_pattern(const char *out, bool *is_dir)
{
    const char *pc = strchr(out, '%');
    if (!pc) {
        *is_dir = true;
        return true;
    }
    const char *q = pc + 1;
    while (*q >= '0' && *q <= '9') {
        q++;
    }
    *is_dir = false;
    return *q == 'd' && q - pc <= 4 && !strchr(q, '%');
}

static bool write_png(const char *path, int w, int h, const uint8_t *px)
{
    sr_io_error err;
    if (cli_write_image(path, w, h, px, &(cli_image_options){ .png_level = -1 }, &err) != SR_OK) {
        cli_error("explain: %s", err.message);
        return false;
    }
    return true;
}

static bool write_frames(const ex_canvas *c, const char *out)
{
    bool is_dir;
    frame_pattern(out, &is_dir);
    if (is_dir && mkdir(out, 0777) != 0 && errno != EEXIST) {
        cli_error("explain: -o: cannot make directory '%s': %s", out, strerror(errno));
        return false;
    }
    for (int i = 0; i < c->frame_count; i++) {
        char path[4096];
        int n = is_dir ? snprintf(path, sizeof path, "%s/frame-%03d.png", out, i + 1)
                       : snprintf(path, sizeof path, out, i + 1);
        if (n < 0 || n >= (int)sizeof path) {
            cli_error("explain: -o: the file name is too long");
            return false;
        }
        if (!write_png(path, c->width, c->height, c->frames[i])) {
            return false;
        }
    }
    return true;
}

/* The frames side by side, at most three to a row, in step order. */
static bool write_sheet(const ex_canvas *c, const char *path)
{
    int cols = c->frame_count < 3 ? c->frame_count : 3;
    int rows = (c->frame_count + cols - 1) / cols;
    int w = cols * c->width + (cols + 1) * SHEET_GAP;
    int h = rows * c->height + (rows + 1) * SHEET_GAP;
    sr_framebuffer *fb = NULL;
    if (sr_make_framebuffer(c->ctx, &(sr_framebuffer_desc){ .width = w, .height = h,
                                                            .depth_format = SR_DEPTH_NONE },
                            &fb) != SR_OK) {
        cli_error("explain: --sheet: %s", sr_context_error(c->ctx));
        return false;
    }
    sr_clear(c->ctx, fb, &(sr_clear_desc){ .color = { 0.55f, 0.57f, 0.6f, 1 } });
    sr_result r = SR_OK;
    for (int i = 0; i < c->frame_count && r == SR_OK; i++) {
        int x = SHEET_GAP + (i % cols) * (c->width + SHEET_GAP);
        int y = SHEET_GAP + (i / cols) * (c->height + SHEET_GAP);
        r = sr_write_pixels(c->ctx, fb, x, y, c->width, c->height, c->frames[i],
                            (size_t)c->width * 4);
    }
    bool ok = r == SR_OK;
    if (!ok) {
        cli_error("explain: --sheet: %s", sr_context_error(c->ctx));
    } else {
        ok = write_png(path, w, h, sr_framebuffer_pixels(fb));
    }
    sr_destroy_framebuffer(c->ctx, fb);
    return ok;
}

static const char *kind_option(ex_kind k)
{
    return k == EX_TRIANGLE ? "--triangle" : k == EX_POLYGON ? "--polygon" : "--line";
}

int cmd_explain(int argc, char **argv)
{
    if (argc >= 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
        usage(stdout);
        return EXIT_OK;
    }
    if (argc < 2 || argv[1][0] == '-') {
        usage(stderr);
        return EXIT_USAGE;
    }
    const algorithm *alg = NULL;
    for (size_t i = 0; i < sizeof algorithms / sizeof algorithms[0]; i++) {
        if (strcmp(argv[1], algorithms[i].name) == 0) {
            alg = &algorithms[i];
        }
    }
    if (!alg) {
        cli_error("explain: unknown algorithm '%s' (try 'softrast explain --help')", argv[1]);
        return EXIT_USAGE;
    }
    ex_primitive prim = alg->example;
    sr_fill_rule rule = SR_EVENODD;
    ex_primitive window = { .count = 0 };
    bool prim_given = false;
    int samples = 4;
    int grid_w = 0, grid_h = 0, zoom = 0;
    const char *out = NULL, *sheet = NULL;
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            return EXIT_OK;
        }
        if (i + 1 >= argc) {
            cli_error("explain: %s: needs a value (try 'softrast explain --help')", a);
            return EXIT_USAGE;
        }
        const char *v = argv[++i];
        bool ok = true;
        ex_primitive p = { 0 };
        if (strcmp(a, "--triangle") == 0 || strcmp(a, "--polygon") == 0 ||
            strcmp(a, "--line") == 0) {
            p.kind = a[2] == 't' ? EX_TRIANGLE : a[2] == 'p' ? EX_POLYGON : EX_LINE;
            if (p.kind != alg->kind) {
                cli_error("explain %s: takes %s, not %s", alg->name, kind_option(alg->kind), a);
                return EXIT_USAGE;
            }
            ok = p.kind == EX_TRIANGLE ? parse_points(a, v, 3, 3, true, &p)
               : p.kind == EX_LINE     ? parse_points(a, v, 2, 2, true, &p)
                                       : parse_points(a, v, 3, EX_MAX_POINTS, false, &p);
            prim = p;
            prim_given = true;
        } else if (strcmp(a, "--fill-rule") == 0) {
            static const char *const rules[] = { "evenodd", "nonzero", NULL };
            int k;
            ok = parse_choice(a, v, rules, &k);
            rule = k == 0 ? SR_EVENODD : SR_NONZERO;
        } else if (strcmp(a, "--window") == 0) {
            ex_primitive wp = { 0 };
            ok = parse_points(a, v, 2, 2, true, &wp);
            if (ok && (wp.pts[0].x >= wp.pts[1].x || wp.pts[0].y >= wp.pts[1].y)) {
                cli_error("%s: expected XMIN,YMIN,XMAX,YMAX with XMIN < XMAX and YMIN < YMAX "
                          "(got '%s')", a, v);
                ok = false;
            }
            window = wp;
        } else if (strcmp(a, "--samples") == 0) {
            ok = parse_int(a, v, 2, 16, &samples);
            if (ok && (samples & (samples - 1)) != 0) {
                cli_error("%s: expected 2, 4, 8 or 16 (got '%s')", a, v);
                ok = false;
            }
        } else if (strcmp(a, "--grid") == 0) {
            ok = parse_size(a, v, &grid_w, &grid_h);
            if (ok && (grid_w > MAX_GRID || grid_h > MAX_GRID)) {
                cli_error("%s: at most %dx%d (got '%s')", a, MAX_GRID, MAX_GRID, v);
                ok = false;
            }
        } else if (strcmp(a, "--zoom") == 0) {
            ok = parse_int(a, v, 4, 64, &zoom);
        } else if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
            bool is_dir;
            out = v;
            if (!frame_pattern(v, &is_dir)) {
                cli_error("%s: a directory, or a file name with one %%d (got '%s')", a, v);
                ok = false;
            }
        } else if (strcmp(a, "--sheet") == 0) {
            sheet = v;
        } else {
            cli_error("explain: unknown option '%s' (try 'softrast explain --help')", a);
            return EXIT_USAGE;
        }
        if (!ok) {
            return EXIT_USAGE;
        }
    }
    if (!out && !sheet) {
        cli_error("explain: no output: give -o DIR and/or --sheet FILE.png");
        return EXIT_USAGE;
    }
    prim.rule = rule;
    prim.samples = samples;
    if (alg->run == explain_bresenham && !ex_line_on_centres(&prim)) {
        cli_error("explain bresenham: --line: the midpoint algorithm takes ends on pixel "
                  "centres (x.5,y.5); 'softrast explain dda' takes any");
        return EXIT_USAGE;
    }
    grid_w = grid_w ? grid_w : alg->grid_w;
    grid_h = grid_h ? grid_h : alg->grid_h;
    zoom = zoom ? zoom : alg->zoom;
    if (window.count == 2) {
        double w[4] = { window.pts[0].x, window.pts[0].y, window.pts[1].x, window.pts[1].y };
        memcpy(prim.window, w, sizeof w);
    } else if (prim_given) {   /* the middle of the grid */
        double w[4] = { grid_w / 4, grid_h / 4, grid_w - grid_w / 4, grid_h - grid_h / 4 };
        memcpy(prim.window, w, sizeof w);
    }
    if ((int64_t)grid_w * zoom > 4096 || (int64_t)grid_h * zoom > 4096) {
        cli_error("explain: the grid times the zoom is over 4096 frame pixels: "
                  "make --grid or --zoom smaller");
        return EXIT_USAGE;
    }

    sr_context *ctx = NULL;
    if (sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) != SR_OK) {
        cli_error("explain: cannot make a context");
        return EXIT_FAILURE_RUN;
    }
    ex_canvas c;
    int status = EXIT_OK;
    /* the scan-line fill lists its edge table in a caption */
    int lines = alg->run == explain_scanline ? 8 + prim.count : 7;
    if (ex_canvas_init(&c, ctx, grid_w, grid_h, zoom, lines) != SR_OK || alg->run(&c, &prim) != SR_OK) {
        if (c.too_many) {
            cli_error("explain %s: the frames would take over %zu MiB: make --grid or --zoom "
                      "smaller", alg->name, EX_MAX_FRAME_BYTES >> 20);
            status = EXIT_USAGE;
        } else {
            cli_error("explain %s: %s", alg->name,
                      sr_context_error(ctx)[0] ? sr_context_error(ctx) : sr_result_text(c.error));
            status = EXIT_FAILURE_RUN;
        }
    } else if ((out && !write_frames(&c, out)) || (sheet && !write_sheet(&c, sheet))) {
        status = EXIT_FAILURE_RUN;
    }
    ex_canvas_free(&c);
    sr_destroy_context(ctx);
    return status;
}

bool explain_algorithm(int i, const char **name, const char **summary, ex_primitive *example,
                       int *grid_w, int *grid_h, int *zoom)
{
    if (i < 0 || (size_t)i >= sizeof algorithms / sizeof algorithms[0]) {
        return false;
    }
    const algorithm *a = &algorithms[i];
    *name = a->name;
    *summary = a->summary;
    *example = a->example;
    *grid_w = a->grid_w;
    *grid_h = a->grid_h;
    *zoom = a->zoom;
    return true;
}
