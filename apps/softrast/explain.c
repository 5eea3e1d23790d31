/* explain.c - `softrast explain ALGORITHM [options]`: parses the primitive
 * and the outputs, runs one algorithm's steps (explain_*.c) and writes them
 * as numbered PNG frames and/or a contact sheet of all of them. */
#include "batch_anim.h"
#include "cli.h"
#include "explain.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_GRID 256
#define SHEET_GAP 8
#define WEBP_FRAME_MS 1500   /* long enough to read a caption */

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
      "             rule on ties, coverage (or --rasterizer's steps)" },
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
    { "wu", EX_LINE, explain_wu,
      { .kind = EX_LINE, .pts = { { 1.3, 2.4 }, { 14.2, 7.7 } }, .count = 2 }, 16, 10, 32,
      "Xiaolin Wu's antialiased line: per column the intersection,\n"
      "             the two pixels straddling it and their weights" },
    { "aaline", EX_LINE, explain_aaline,
      { .kind = EX_LINE, .pts = { { 1.3, 2.4 }, { 14.2, 7.7 } }, .count = 2, .line_width = 1 },
      16, 10, 32,
      "softrast's antialiased line (sr_draw's smooth lines): each\n"
      "             pixel's distance to the segment and its coverage\n"
      "             (--width)" },
    { "area", EX_LINE, explain_area,
      { .kind = EX_LINE, .pts = { { 1.3, 2.4 }, { 14.2, 7.7 } }, .count = 2, .line_width = 1,
        .line_cap = SR_LINE_CAP_BUTT }, 16, 10, 32,
      "unweighted area sampling (SR_LINE_AREA): each pixel's\n"
      "             area covered by the line's rectangle, row by row\n"
      "             (--width, --cap)" },
    { "zbuffer", EX_TRIANGLES, explain_zbuffer,
      { .kind = EX_TRIANGLES, .pts = { { 1.5, 1.5 }, { 12.5, 3.5 }, { 3.5, 10.5 },
                                       { 11.5, 0.5 }, { 12.5, 10.5 }, { 2.5, 6.5 } },
        .z = { 0.25, 0.25, 0.75, 0.5, 0.125, 0.5 }, .count = 6 }, 14, 11, 40,
      "two triangles through the z-buffer: the quantized depth at\n"
      "             each covered pixel and the depth test" },
    { "perspective", EX_TRIANGLE, explain_perspective,
      { .kind = EX_TRIANGLE, .pts = { { 1.5, 1.5 }, { 14.5, 4.5 }, { 2.5, 11.5 } },
        .z = { 1, 4, 1 }, .count = 3, .row = 5 }, 16, 13, 32,
      "perspective-correct versus affine interpolation along one\n"
      "             span (--w, --row, --interpolation)" },
    { "fillpoly", EX_TRIANGLE, explain_fillpoly,
      { .kind = EX_TRIANGLE, .pts = { { 6.5, 0.7 }, { 14.3, 6.6 }, { 1.4, 10.6 } },
        .z = { 1, 0.2, 0.55 }, .count = 3 }, 16, 12, 32,
      "FillPoly/FillSpan: x by 1/m and the intensity by dI along\n"
      "             the edges and each span, split at the middle vertex" },
    { "interpolation", EX_TRIANGLE, explain_interpolation,
      { .kind = EX_TRIANGLE, .pts = { { 6.5, 0.7 }, { 14.3, 6.6 }, { 1.4, 10.6 } },
        .z = { 1, 0.2, 0.55 }, .count = 3 }, 16, 12, 32,
      "a vertex value over a triangle three ways: bilinear,\n"
      "             the plane equation, barycentric coordinates (--method)" },
    { "circle", EX_CIRCLE, explain_circle,
      { .kind = EX_CIRCLE, .pts = { { 7.3, 6.6 } }, .z = { 5.4 }, .count = 1 }, 15, 14, 36,
      "the midpoint circle: its decision variable at the pixel\n"
      "             centres each row walks, stepped by forward differences" },
    { "forward-differencing", EX_CUBIC, explain_fwdiff,
      { .kind = EX_CUBIC, .pts = { { 1.5, 10.5 }, { 3.5, 0.5 }, { 11.5, 1.5 }, { 14.5, 9.5 } },
        .z = { 0.25 }, .count = 4 }, 16, 12, 32,
      "a cubic Bezier flattened by forward differences: each\n"
      "             point by three additions (--cubic, --tolerance)" },
    { "floodfill", EX_POLYGON, explain_floodfill,
      { .kind = EX_POLYGON, .pts = { { 1.5, 1.5 }, { 13.5, 1.5 }, { 13.5, 10.5 }, { 10.5, 10.5 },
                                     { 7.5, 4.5 }, { 4.5, 10.5 }, { 1.5, 10.5 } }, .count = 7,
        .seed = { 3, 3 } }, 16, 12, 32,
      "flood fill inside a polygon's outline: run by run from a\n"
      "             stack of seeds (--seed, --connectivity 4|8)" },
    { "clip4d", EX_CLIP_TRIANGLE, explain_clip4d,
      { .kind = EX_CLIP_TRIANGLE, .count = 3,
        .clip = { { -0.9, -0.7, 0.2, 1 }, { 2.2, 0.2, 0.6, 1.5 }, { 0.5, 1.4, -1.6, -0.8 } } },
      16, 12, 32,
      "a triangle clipped in 4D against the six planes of the\n"
      "             view volume, before the divide (--clip-triangle)" },
    { "transform", EX_OBJECT_TRIANGLE, explain_transform,
      { .kind = EX_OBJECT_TRIANGLE, .count = 3,
        .pts = { { -1, -0.8 }, { 1.2, -0.5 }, { 0.1, 1 } }, .z = { 0, 0.3, -0.2 },
        .view = { .rotate = 30, .translate = { 0.5, 0, 0 }, .eye = { 0.8, 0.9, 2.7 },
                  .target = { 0.5, 0, 0 }, .up = { 0, 1, 0 }, .fov = 45,
                  .near_far = { 1, 10 } } }, 20, 12, 28,
      "the viewing pipeline S P E M_O: a triangle's vertices in\n"
      "             object, world, eye, clip, NDC and window coordinates" },
    { "gouraud", EX_TRIANGLE, explain_gouraud,
      { .kind = EX_TRIANGLE, .pts = { { 1.5, 1.5 }, { 14.5, 3.5 }, { 4.5, 11.5 } }, .count = 3,
        .highlight = { 7.2, 5.6 }, .shininess = 40 }, 16, 13, 32,
      "Gouraud versus Phong shading of a triangle whose specular\n"
      "             highlight falls inside it (--highlight, --shininess)" },
    { "zfight", EX_TRIANGLES, explain_zfight,
      { .kind = EX_TRIANGLES, .pts = { { 0.5, 0.5 }, { 13.5, 1.5 }, { 2.5, 10.5 },
                                       { 3.2, 2.3 }, { 12.6, 3.4 }, { 4.3, 9.6 } },
        .z = { 0.4, 0.4, 0.41, 0.401623187, 0.401993, 0.408948312 }, .count = 6,
        .offset = { -1, -1 } }, 14, 11, 40,
      "two nearly coplanar triangles fighting in a 16-bit z-buffer,\n"
      "             then the fix by polygon offset (--offset)" },
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
        const char *name = algorithms[i].name;
        fprintf(f, strlen(name) > 10 ? "  %s\n             %s\n" : "  %-10s %s\n", name,
                algorithms[i].summary);
    }
    fprintf(f,
            "\n"
            "primitive (window coordinates in pixels, y down; each algorithm has an\n"
            "example it uses when none is given):\n"
            "  --triangle X0,Y0,X1,Y1,X2,Y2\n"
            "  --polygon X,Y,X,Y,...      3 to %d vertices\n"
            "  --line X0,Y0,X1,Y1\n"
            "  --width W                  aaline, area: the line's width in pixels, 0.0625\n"
            "                             to 64 (default 1)\n"
            "  --cap butt|square|round    area: the line's ends, at A and B (butt, the\n"
            "                             default), w/2 past them or half disks\n"
            "  --circle CX,CY,R           circle: centre and radius (R at most 4096)\n"
            "  --cubic X0,Y0,...,X3,Y3    forward-differencing: a cubic Bezier's four\n"
            "                             control points\n"
            "  --seed X,Y                 floodfill: the seed pixel (default: the example's,\n"
            "                             or the grid's middle)\n"
            "  --connectivity 4|8         floodfill: neighbours across edges (4, the\n"
            "                             default) or corners too (8)\n"
            "  --clip-triangle X,Y,Z,W,X,Y,Z,W,X,Y,Z,W\n"
            "                             clip4d: a triangle in clip space (before the\n"
            "                             divide; the viewport is the grid less a fifth on\n"
            "                             each side)\n"
            "  --object X0,Y0,Z0,X1,Y1,Z1,X2,Y2,Z2\n"
            "                             transform: the triangle in object coordinates\n"
            "  --rotate DEG               transform: M_O's rotation about y, degrees\n"
            "                             (default 30), before\n"
            "  --translate X,Y,Z          transform: M_O's translation (default 0.5,0,0)\n"
            "  --eye X,Y,Z                transform: the camera's eye (default 0.8,0.9,2.7)\n"
            "  --target X,Y,Z             transform: the point it looks at (default 0.5,0,0)\n"
            "  --up X,Y,Z                 transform: the view-up vector (default 0,1,0)\n"
            "  --projection perspective|orthographic\n"
            "                             transform: P (default perspective)\n"
            "  --fov DEG                  transform: the field of view across the viewport's\n"
            "                             smaller side, 1 to 170 (default 45); orthographic:\n"
            "                             the box as tall at the target\n"
            "  --near-far N,F             transform: the near and far planes' distances,\n"
            "                             0 < N < F (default 1,10)\n"
            "  --aspect fit|stretch       transform: keep the aspect ratio (fit, the\n"
            "                             default: the other field of view derived from the\n"
            "                             viewport's width/height) or stretch NDC's square\n"
            "                             over the viewport\n"
            "  --offset FACTOR,UNITS      zfight: the second triangle's polygon offset,\n"
            "                             each in -64..64 (default -1,-1: pulled forward)\n"
            "  --highlight X,Y            gouraud: where the point light's highlight peaks\n"
            "                             (default: the example's, or the triangle's\n"
            "                             centroid)\n"
            "  --shininess N              gouraud: the Blinn-Phong exponent, 1 to 1000\n"
            "                             (default 40)\n"
            "  --tolerance T              forward-differencing: how far the chords may stray\n"
            "                             from the curve, pixels (default 0.25; at most 64\n"
            "                             steps)\n"
            "  --triangles X,Y,Z,...      zbuffer, zfight: two triangles, 18 numbers, Z the\n"
            "                             window depth of each vertex in 0..1 (0 near)\n"
            "  --window XMIN,YMIN,XMAX,YMAX\n"
            "                             clip: the clip window\n"
            "  --samples N                msaa: 2, 4 (the default), 8 or 16 per pixel\n"
            "  --w W0,W1,W2               perspective: each vertex's eye distance (its\n"
            "                             clip-space w), 1/64 to 1024 (default 1,1,1)\n"
            "  --row Y                    perspective: the span's scanline (default: the\n"
            "                             triangle's middle)\n"
            "  --intensity IA,IB,IC       fillpoly, interpolation: the intensity at each\n"
            "                             vertex, 0..1 (default 1,0.2,0.55)\n"
            "  --method M                 interpolation: the method whose steps to show,\n"
            "                             all (the default), bilinear (along the edges,\n"
            "                             then the spans), plane (I = a x + b y + c,\n"
            "                             stepped) or barycentric (the edge functions'\n"
            "                             weights)\n"
            "  --rasterizer R             triangle: whose steps to show, halfspace (edge\n"
            "                             functions, the default), scanline (edge walking)\n"
            "                             or barycentric (the bounding box's weights)\n"
            "  --interpolation M          perspective: what the last step draws, the whole\n"
            "                             triangle perspective-correct (the default),\n"
            "                             affine (SR_INTERP_AFFINE) or by FillPoly/FillSpan's\n"
            "                             screen-space increments (fillspan)\n"
            "  --fill-rule evenodd|nonzero\n"
            "                             scanline, clip: inside by parity (the default)\n"
            "                             or by winding number\n"
            "\n"
            "view:\n"
            "  --grid WxH                 pixels shown (from 1x1 to %dx%d)\n"
            "  --zoom N                   frame pixels per pixel, 4 to 64; the grid times\n"
            "                             the zoom at most 4096 a side, all the frames\n"
            "                             at most 1 GiB\n"
            "\n"
            "output (at least one):\n"
            "  -o, --output DIR|PATTERN   one PNG per step: DIR/frame-001.png, ..., or a\n"
            "                             PATTERN with one %%d, e.g. out/step-%%02d.png\n"
            "                             (the directories are made if missing)\n"
            "  --sheet FILE.png           all the steps on one captioned contact sheet,\n"
            "                             three to a row, at most %d pixels a side\n"
            "  --webp FILE.webp           all the steps as one animated WebP, 1.5 s each\n"
            "                             (needs a build with libwebp)\n",
            EX_MAX_POINTS, MAX_GRID, MAX_GRID, SR_MAX_FRAMEBUFFER_SIZE);
}

/* "x,y,x,y,..." (dims 2) or "x,y,z,..." (dims 3) into pts and z; false
 * after one line naming the option. */
static bool parse_points(const char *opt, const char *s, int dims, int min, int max,
                         const char *form, ex_primitive *prim)
{
    double v[3 * EX_MAX_POINTS];
    int n = 0;
    const char *p = s;
    for (;;) {
        char *end;
        errno = 0;
        double d = strtod(p, &end);
        if (errno || end == p || !isfinite(d) || fabs(d) > 16384 || n == dims * max) {
            break;
        }
        v[n++] = d;
        if (*end == 0) {
            if (n % dims == 0 && n / dims >= min) {
                prim->count = n / dims;
                for (int i = 0; i < prim->count; i++) {
                    prim->pts[i] = (sr_point2){ v[dims * i], v[dims * i + 1] };
                    prim->z[i] = dims == 3 ? v[dims * i + 2] : 0;
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
    if (form) {
        cli_error("%s: expected %d numbers %s in -16384..16384 (got '%s')", opt, dims * min,
                  form, s);
    } else {
        cli_error("%s: expected %d to %d X,Y pairs in -16384..16384 (got '%s')", opt, min, max,
                  s);
    }
    return false;
}

/* Two triangles with a window depth in [0, 1] at each vertex. */
static bool parse_depths(const char *opt, const char *s, ex_primitive *prim)
{
    if (!parse_points(opt, s, 3, 6, 6, "X,Y,Z,...", prim)) {
        return false;
    }
    for (int i = 0; i < 6; i++) {
        if (!(prim->z[i] >= 0 && prim->z[i] <= 1)) {
            cli_error("%s: each Z is a window depth in 0..1 (got '%s')", opt, s);
            return false;
        }
    }
    return true;
}

/* Three points x, y, z, w: 12 numbers through the 2D parser, as six
 * pairs. */
static bool parse_clip(const char *opt, const char *s, ex_primitive *prim)
{
    ex_primitive p = { 0 };
    if (!parse_points(opt, s, 2, 6, 6, "X,Y,Z,W,X,Y,Z,W,X,Y,Z,W", &p)) {
        return false;
    }
    for (int i = 0; i < 3; i++) {
        double v[4] = { p.pts[2 * i].x, p.pts[2 * i].y, p.pts[2 * i + 1].x, p.pts[2 * i + 1].y };
        memcpy(prim->clip[i], v, sizeof v);
    }
    prim->count = 3;
    return true;
}

static bool parse_radius(const char *opt, const char *s, double r)
{
    if (r < 0 || r > 4096) {
        cli_error("%s: expected CX,CY,R with R in 0..4096 (got '%s')", opt, s);
        return false;
    }
    return true;
}

/* Three numbers in lo..hi, one per vertex, into out; a message gives the
 * form of --help and this range. */
static bool parse_three(const char *opt, const char *s, const char *form, double lo, double hi,
                        double out[3])
{
    const char *p = s;
    for (int k = 0; k < 3; k++) {
        char *end;
        errno = 0;
        double v = strtod(p, &end);
        if (errno || end == p || !(v >= lo && v <= hi) || *end != (k < 2 ? ',' : '\0')) {
            cli_error("%s: expected three numbers %s, each in %g..%g (got '%s')", opt, form, lo,
                      hi, s);
            return false;
        }
        out[k] = v;
        p = end + 1;
    }
    return true;
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

/* Frame i's file (from 0) of -o `out`; false after one line. */
static bool frame_path(const char *out, int i, char *path, size_t size)
{
    bool is_dir;
    frame_pattern(out, &is_dir);
    int n = is_dir ? snprintf(path, size, "%s/frame-%03d.png", out, i + 1)
                   : snprintf(path, size, out, i + 1);
    if (n < 0 || (size_t)n >= size) {
        cli_error("explain: -o: the file name is too long");
        return false;
    }
    return true;
}

/* No output replaces another of the same run: --sheet or --webp naming a
 * frame of -o, or each other, would leave one of them missing.  false
 * after one line, before anything is written. */
static bool outputs_distinct(int frames, const char *out, const char *sheet, const char *webp)
{
    const char *opts[2] = { "--sheet", "--webp" }, *files[2] = { sheet, webp };
    if (sheet && webp && cli_same_output(sheet, webp)) {
        cli_error("explain: --webp: '%s' is also --sheet; choose another file", webp);
        return false;
    }
    for (int i = 0; out && i < frames; i++) {
        char path[4096];
        if (!frame_path(out, i, path, sizeof path)) {
            return false;
        }
        for (int k = 0; k < 2; k++) {
            if (files[k] && cli_same_output(files[k], path)) {
                cli_error("explain: %s: '%s' is also frame %d of -o; choose another file",
                          opts[k], files[k], i + 1);
                return false;
            }
        }
    }
    return true;
}

static bool write_frames(const ex_canvas *c, const char *out)
{
    for (int i = 0; i < c->frame_count; i++) {
        char path[4096];
        if (!frame_path(out, i, path, sizeof path)) {
            return false;
        }
        /* The directory, or a pattern's, is made if missing. */
        sr_io_error err;
        if (!cli_make_parents(path, &err)) {
            cli_error("explain: -o: %s", err.message);
            return false;
        }
        if (!write_png(path, c->width, c->height, c->frames[i])) {
            return false;
        }
    }
    return true;
}

/* The contact sheet's layout: the frames side by side, at most three to a
 * row, in step order. */
static void sheet_size(const ex_canvas *c, int *cols, int64_t *w, int64_t *h)
{
    *cols = c->frame_count < 3 ? c->frame_count : 3;
    int rows = (c->frame_count + *cols - 1) / *cols;
    *w = (int64_t)*cols * c->width + (*cols + 1) * SHEET_GAP;
    *h = (int64_t)rows * c->height + (rows + 1) * SHEET_GAP;
}

/* A sheet the framebuffer cannot hold is refused before any file is
 * written: the frames of -o would otherwise be left without their sheet. */
static bool sheet_fits(const ex_canvas *c)
{
    int cols;
    int64_t w, h;
    sheet_size(c, &cols, &w, &h);
    if (w > SR_MAX_FRAMEBUFFER_SIZE || h > SR_MAX_FRAMEBUFFER_SIZE) {
        cli_error("explain: --sheet: %d frames of %dx%d make a %lldx%lld sheet, over %d a side: "
                  "make --grid or --zoom smaller, or use -o", c->frame_count, c->width, c->height,
                  (long long)w, (long long)h, SR_MAX_FRAMEBUFFER_SIZE);
        return false;
    }
    return true;
}

static bool write_sheet(const ex_canvas *c, const char *path)
{
    int cols;
    int64_t w64, h64;
    sheet_size(c, &cols, &w64, &h64);
    int w = (int)w64, h = (int)h64;
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

/* The frames as one animated WebP, each shown WEBP_FRAME_MS, the last
 * twice as long before it loops. */
static bool write_webp(const ex_canvas *c, const char *path)
{
    char why[600];
    batch_anim *anim = batch_anim_start(c->width, c->height, false, why, sizeof why);
    bool ok = anim != NULL;
    for (int i = 0; i < c->frame_count && ok; i++) {
        ok = batch_anim_add(anim, c->frames[i], i * WEBP_FRAME_MS, why, sizeof why);
    }
    sr_io_error err;
    if (ok && !batch_anim_write(anim, path, (c->frame_count + 1) * WEBP_FRAME_MS, &err)) {
        snprintf(why, sizeof why, "%s", err.message);
        ok = false;
    }
    batch_anim_free(anim);
    if (!ok) {
        cli_error("explain: --webp: %s", why);
    }
    return ok;
}

/* The options that only some algorithms take, and which: given to
 * another, one would be ignored without a word (`explain triangle
 * --samples 8` drew no samples). */
static const struct {
    const char *option, *algorithms[3];
} option_owners[] = {
    { "--fill-rule", { "scanline", "clip" } },
    { "--window", { "clip" } },
    { "--samples", { "msaa" } },
    { "--w", { "perspective" } },
    { "--row", { "perspective" } },
    { "--interpolation", { "perspective" } },
    { "--intensity", { "fillpoly", "interpolation" } },
    { "--method", { "interpolation" } },
    { "--rasterizer", { "triangle" } },
    { "--tolerance", { "forward-differencing" } },
    { "--seed", { "floodfill" } },
    { "--connectivity", { "floodfill" } },
    { "--rotate", { "transform" } },
    { "--translate", { "transform" } },
    { "--eye", { "transform" } },
    { "--target", { "transform" } },
    { "--up", { "transform" } },
    { "--projection", { "transform" } },
    { "--fov", { "transform" } },
    { "--near-far", { "transform" } },
    { "--aspect", { "transform" } },
    { "--highlight", { "gouraud" } },
    { "--offset", { "zfight" } },
    { "--shininess", { "gouraud" } },
    { "--width", { "aaline", "area" } },
    { "--cap", { "area" } },
};

/* Whether algorithm `name` takes option `a`; false after one line. */
static bool option_applies(const char *name, const char *a)
{
    for (size_t i = 0; i < sizeof option_owners / sizeof option_owners[0]; i++) {
        if (strcmp(a, option_owners[i].option) != 0) {
            continue;
        }
        const char *const *owners = option_owners[i].algorithms;
        for (int k = 0; k < 3 && owners[k]; k++) {
            if (strcmp(name, owners[k]) == 0) {
                return true;
            }
        }
        cli_error("explain %s: %s is for '%s'%s%s%s", name, a, owners[0],
                  owners[1] ? " and '" : "", owners[1] ? owners[1] : "", owners[1] ? "'" : "");
        return false;
    }
    return true;
}

static const char *kind_option(ex_kind k)
{
    return k == EX_TRIANGLE ? "--triangle" : k == EX_POLYGON ? "--polygon"
         : k == EX_TRIANGLES ? "--triangles" : k == EX_CIRCLE ? "--circle"
         : k == EX_CUBIC ? "--cubic" : k == EX_CLIP_TRIANGLE ? "--clip-triangle"
         : k == EX_OBJECT_TRIANGLE ? "--object" : "--line";
}

int cmd_explain(int argc, char **argv)
{
    if (argc >= 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
        usage(stdout);
        return EXIT_OK;
    }
    bool ended = false;
    int first = argc >= 2 && cli_arg(argv[1], &ended) == CLI_ARG_END ? 2 : 1;
    if (first >= argc || cli_arg(argv[first], &ended) != CLI_ARG_OPERAND) {
        usage(stderr);
        return EXIT_USAGE;
    }
    const char *name = argv[first];
    const algorithm *alg = NULL;
    for (size_t i = 0; i < sizeof algorithms / sizeof algorithms[0]; i++) {
        if (strcmp(name, algorithms[i].name) == 0) {
            alg = &algorithms[i];
        }
    }
    if (!alg) {
        cli_error("explain: unknown algorithm '%s' (try 'softrast explain --help')", name);
        return EXIT_USAGE;
    }
    ex_primitive prim = alg->example;
    ex_view view = alg->example.view;
    sr_fill_rule rule = SR_EVENODD;
    ex_primitive window = { .count = 0 };
    bool prim_given = false;
    double per_vertex[3];
    bool per_vertex_given = false;
    int row = -1;
    double tolerance = 0;
    int seed[2] = { 0, 0 }, connectivity = 4;
    double highlight[2] = { 0, 0 }, shininess = 0, offset[2] = { 0, 0 }, line_width = 0;
    sr_line_cap line_cap = SR_LINE_CAP_BUTT;
    bool offset_given = false;
    bool highlight_given = false;
    bool seed_given = false;
    int samples = 4;
    sr_rasterizer rasterizer = SR_RASTER_HALFSPACE;
    ex_interp interpolation = EX_INTERP_PERSPECTIVE;
    ex_method method = EX_METHOD_ALL;
    int grid_w = 0, grid_h = 0, zoom = 0;
    const char *out = NULL, *sheet = NULL, *webp = NULL;
    for (int i = first + 1; i < argc; i++) {
        const char *a = argv[i];
        cli_arg_kind kind = cli_arg(a, &ended);
        if (kind == CLI_ARG_END) {
            continue;
        } else if (kind == CLI_ARG_OPERAND) {
            cli_error("explain: takes one ALGORITHM, then options (got '%s' too)", a);
            return EXIT_USAGE;
        }
        cli_opt opt;
        cli_split_option(a, &opt);
        int help = cli_help_option(&opt, usage);
        if (help >= 0) {
            return help;
        }
        const char *given = a;
        a = opt.name;
        if (!opt.value && i + 1 >= argc) {
            cli_error("explain: %s: needs a value (try 'softrast explain --help')", a);
            return EXIT_USAGE;
        }
        if (!option_applies(alg->name, a)) {
            return EXIT_USAGE;
        }
        const char *v = cli_option_value(&opt, argc, argv, &i);
        bool ok = true;
        if ((strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0 || strcmp(a, "--sheet") == 0 ||
             strcmp(a, "--webp") == 0) && !cli_check_output_name(a, v)) {
            return EXIT_USAGE;
        }
        ex_primitive p = { 0 };
        if (strcmp(a, "--triangle") == 0 || strcmp(a, "--polygon") == 0 ||
            strcmp(a, "--line") == 0 || strcmp(a, "--triangles") == 0 ||
            strcmp(a, "--circle") == 0 || strcmp(a, "--cubic") == 0 ||
            strcmp(a, "--clip-triangle") == 0 || strcmp(a, "--object") == 0) {
            p.kind = strcmp(a, "--triangles") == 0 ? EX_TRIANGLES
                   : strcmp(a, "--object") == 0    ? EX_OBJECT_TRIANGLE
                   : strcmp(a, "--circle") == 0    ? EX_CIRCLE
                   : strcmp(a, "--cubic") == 0     ? EX_CUBIC
                   : strcmp(a, "--clip-triangle") == 0 ? EX_CLIP_TRIANGLE
                   : a[2] == 't' ? EX_TRIANGLE : a[2] == 'p' ? EX_POLYGON : EX_LINE;
            if (p.kind != alg->kind) {
                cli_error("explain %s: takes %s, not %s", alg->name, kind_option(alg->kind), a);
                return EXIT_USAGE;
            }
            ok = p.kind == EX_TRIANGLE  ? parse_points(a, v, 2, 3, 3, "X0,Y0,X1,Y1,X2,Y2", &p)
               : p.kind == EX_LINE      ? parse_points(a, v, 2, 2, 2, "X0,Y0,X1,Y1", &p)
               : p.kind == EX_TRIANGLES ? parse_depths(a, v, &p)
               : p.kind == EX_CUBIC     ? parse_points(a, v, 2, 4, 4, "X0,Y0,...,X3,Y3", &p)
               : p.kind == EX_CLIP_TRIANGLE ? parse_clip(a, v, &p)
               : p.kind == EX_OBJECT_TRIANGLE
                   ? parse_points(a, v, 3, 3, 3, "X0,Y0,Z0,X1,Y1,Z1,X2,Y2,Z2", &p)
               : p.kind == EX_CIRCLE    ? parse_points(a, v, 3, 1, 1, "CX,CY,R", &p) &&
                                              parse_radius(a, v, p.z[0])
                                        : parse_points(a, v, 2, 3, EX_MAX_POINTS, NULL, &p);
            prim = p;
            prim_given = true;
        } else if (strcmp(a, "--fill-rule") == 0) {
            static const char *const rules[] = { "evenodd", "nonzero", NULL };
            int k;
            ok = parse_choice(a, v, rules, &k);
            rule = k == 0 ? SR_EVENODD : SR_NONZERO;
        } else if (strcmp(a, "--rasterizer") == 0 || strcmp(a, "--interpolation") == 0) {
            static const char *const rasterizers[] = { "halfspace", "scanline", "barycentric",
                                                       NULL };
            static const char *const interpolations[] = { "perspective", "affine", "fillspan",
                                                          NULL };
            bool r = a[2] == 'r';
            int k;
            ok = parse_choice(a, v, r ? rasterizers : interpolations, &k);
            if (r) {
                rasterizer = (sr_rasterizer)(SR_RASTER_HALFSPACE + k);
            } else {
                interpolation = (ex_interp)k;
            }
        } else if (strcmp(a, "--method") == 0) {
            static const char *const methods[] = { "all", "bilinear", "plane", "barycentric",
                                                   NULL };
            int k = 0;
            ok = parse_choice(a, v, methods, &k);
            method = (ex_method)k;
        } else if (strcmp(a, "--eye") == 0 || strcmp(a, "--target") == 0 ||
                   strcmp(a, "--up") == 0 || strcmp(a, "--translate") == 0) {
            ex_primitive vp = { 0 };
            ok = parse_points(a, v, 3, 1, 1, "X,Y,Z", &vp);
            double *to = a[2] == 'e' ? view.eye : a[2] == 'u' ? view.up
                       : a[3] == 'a' ? view.target : view.translate;
            to[0] = vp.pts[0].x;
            to[1] = vp.pts[0].y;
            to[2] = vp.z[0];
        } else if (strcmp(a, "--highlight") == 0) {
            ex_primitive hp = { 0 };
            ok = parse_points(a, v, 2, 1, 1, "X,Y", &hp);
            highlight[0] = hp.pts[0].x;
            highlight[1] = hp.pts[0].y;
            highlight_given = true;
        } else if (strcmp(a, "--offset") == 0) {
            ex_primitive op = { 0 };
            ok = parse_points(a, v, 2, 1, 1, "FACTOR,UNITS", &op);
            offset[0] = op.pts[0].x;
            offset[1] = op.pts[0].y;
            if (ok && !(fabs(offset[0]) <= 64 && fabs(offset[1]) <= 64)) {
                cli_error("%s: expected FACTOR,UNITS, each in -64..64 (got '%s')", a, v);
                ok = false;
            }
            offset_given = true;
        } else if (strcmp(a, "--shininess") == 0 || strcmp(a, "--rotate") == 0 ||
                   strcmp(a, "--fov") == 0) {
            float f = 0;
            ok = a[2] == 's'   ? parse_float(a, v, 1, 1000, &f)
               : a[2] == 'r' ? parse_float(a, v, -360, 360, &f) : parse_float(a, v, 1, 170, &f);
            *(a[2] == 's' ? &shininess : a[2] == 'r' ? &view.rotate : &view.fov) = f;
        } else if (strcmp(a, "--width") == 0) {
            float f = 0;
            ok = parse_float(a, v, 0.0625f, 64, &f);
            line_width = f;
        } else if (strcmp(a, "--cap") == 0) {
            static const char *const caps[] = { "butt", "square", "round", NULL };
            int k = 0;
            ok = parse_choice(a, v, caps, &k);
            line_cap = (sr_line_cap)(SR_LINE_CAP_BUTT + k);
        } else if (strcmp(a, "--near-far") == 0) {
            ex_primitive np = { 0 };
            ok = parse_points(a, v, 2, 1, 1, "N,F", &np);
            if (ok && !(np.pts[0].x > 0 && np.pts[0].y > np.pts[0].x)) {
                cli_error("%s: expected N,F with 0 < N < F (got '%s')", a, v);
                ok = false;
            }
            view.near_far[0] = np.pts[0].x;
            view.near_far[1] = np.pts[0].y;
        } else if (strcmp(a, "--projection") == 0 || strcmp(a, "--aspect") == 0) {
            static const char *const projections[] = { "perspective", "orthographic", NULL };
            static const char *const aspects[] = { "fit", "stretch", NULL };
            bool proj = a[2] == 'p';
            int k = 0;
            ok = parse_choice(a, v, proj ? projections : aspects, &k);
            *(proj ? &view.orthographic : &view.stretch) = k == 1;
        } else if (strcmp(a, "--window") == 0) {
            ex_primitive wp = { 0 };
            ok = parse_points(a, v, 2, 2, 2, "XMIN,YMIN,XMAX,YMAX", &wp);
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
        } else if (strcmp(a, "--w") == 0 || strcmp(a, "--intensity") == 0) {
            bool w = a[2] == 'w';
            ok = w ? parse_three(a, v, "W0,W1,W2", 1.0 / 64, 1024, per_vertex)
                   : parse_three(a, v, "IA,IB,IC", 0, 1, per_vertex);
            per_vertex_given = true;
        } else if (strcmp(a, "--tolerance") == 0) {
            char *end;
            tolerance = strtod(v, &end);
            if (*end || end == v || !(tolerance >= 0.001 && tolerance <= 100)) {
                cli_error("%s: expected a number of pixels in 0.001..100 (got '%s')", a, v);
                ok = false;
            }
        } else if (strcmp(a, "--seed") == 0) {
            ex_primitive sp = { 0 };
            ok = parse_points(a, v, 2, 1, 1, "X,Y", &sp);
            seed[0] = (int)floor(sp.pts[0].x);
            seed[1] = (int)floor(sp.pts[0].y);
            seed_given = true;
        } else if (strcmp(a, "--connectivity") == 0) {
            ok = parse_int(a, v, 4, 8, &connectivity);
            if (ok && connectivity != 4 && connectivity != 8) {
                cli_error("%s: expected 4 or 8 (got '%s')", a, v);
                ok = false;
            }
        } else if (strcmp(a, "--row") == 0) {
            ok = parse_int(a, v, 0, MAX_GRID - 1, &row);
        } else if (strcmp(a, "--grid") == 0) {
            ok = parse_size_max(a, v, MAX_GRID, &grid_w, &grid_h);
        } else if (strcmp(a, "--zoom") == 0) {
            ok = parse_int(a, v, 4, 64, &zoom);
        } else if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
            bool is_dir;
            out = v;
            if (!frame_pattern(v, &is_dir)) {
                cli_error("%s: a directory, or a file name with one %%d (got '%s')", a, v);
                ok = false;
            } else if (!is_dir) {
                ok = cli_check_image_name(a, v, true);
            }
        } else if (strcmp(a, "--webp") == 0) {
            webp = v;
            if (!batch_anim_available()) {
                cli_message("%s: cannot write animated WebP (softrast was built without libwebp; "
                            "install libwebp-dev and rebuild)", v);
                ok = false;
            } else if (!batch_anim_is_webp_name(v)) {
                cli_error("%s: '%s': an animation is a WebP (name it .webp)", a, v);
                ok = false;
            }
        } else if (strcmp(a, "--sheet") == 0) {
            sheet = v;
            ok = cli_check_image_name(a, v, true);
        } else {
            cli_error("explain: unknown option '%s' (try 'softrast explain --help')", given);
            return EXIT_USAGE;
        }
        if (!ok) {
            return EXIT_USAGE;
        }
    }
    if (!out && !sheet && !webp) {
        cli_error("explain: no output: give -o DIR, --sheet FILE.png and/or --webp FILE.webp");
        return EXIT_USAGE;
    }
    prim.rule = rule;
    prim.samples = samples;
    prim.rasterizer = rasterizer;
    prim.interpolation = interpolation;
    prim.method = method;
    if (per_vertex_given) {
        memcpy(prim.z, per_vertex, sizeof per_vertex);
    } else if (prim_given && alg->kind == EX_TRIANGLE) {   /* the example's values */
        memcpy(prim.z, alg->run == explain_perspective ? (double[3]){ 1, 1, 1 } : alg->example.z,
               sizeof per_vertex);
    }
    prim.connectivity = connectivity;
    prim.view = view;
    if (alg->run == explain_zfight) {
        memcpy(prim.offset, offset_given ? offset : alg->example.offset, sizeof offset);
    }
    if (alg->run == explain_gouraud) {
        prim.shininess = shininess > 0 ? shininess : alg->example.shininess;
        if (highlight_given) {
            memcpy(prim.highlight, highlight, sizeof highlight);
        } else if (prim_given) {   /* the centroid */
            prim.highlight[0] = (prim.pts[0].x + prim.pts[1].x + prim.pts[2].x) / 3;
            prim.highlight[1] = (prim.pts[0].y + prim.pts[1].y + prim.pts[2].y) / 3;
        }
    }
    if (alg->run == explain_aaline || alg->run == explain_area) {
        prim.line_width = line_width > 0 ? line_width : alg->example.line_width;
        prim.line_cap = line_cap;
    }
    if (seed_given) {
        prim.seed[0] = seed[0];
        prim.seed[1] = seed[1];
    } else if (prim_given) {
        prim.seed[0] = (grid_w ? grid_w : alg->grid_w) / 2;
        prim.seed[1] = (grid_h ? grid_h : alg->grid_h) / 2;
    }
    if (alg->kind == EX_CUBIC) {
        prim.z[0] = tolerance > 0 ? tolerance : alg->example.z[0];
    }
    if (alg->run == explain_perspective) {
        prim.row = row >= 0 ? row : prim_given ? -1 : prim.row;
    }
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
    if (alg->run == explain_floodfill &&
        (prim.seed[0] < 0 || prim.seed[1] < 0 || prim.seed[0] >= grid_w || prim.seed[1] >= grid_h)) {
        cli_error("explain floodfill: --seed: (%d, %d) is outside the %dx%d grid", prim.seed[0],
                  prim.seed[1], grid_w, grid_h);
        return EXIT_USAGE;
    }
    char why[300];
    if (alg->run == explain_transform && !ex_transform_check(&prim, grid_w, grid_h, why,
                                                             sizeof why)) {
        cli_error("explain transform: %s", why);
        return EXIT_USAGE;
    }
    if ((int64_t)grid_w * zoom > 4096 || (int64_t)grid_h * zoom > 4096) {
        cli_error("explain: the grid times the zoom is over 4096 frame pixels: "
                  "make --grid or --zoom smaller");
        return EXIT_USAGE;
    }

    sr_context *ctx = NULL;
    sr_set_last_error(NULL);
    sr_result r = sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx);
    if (r != SR_OK) {
        cli_error("explain: cannot make a context: %s", cli_why(r));
        return EXIT_FAILURE_RUN;
    }
    ex_canvas c;
    int status = EXIT_OK;
    /* the scan-line fill lists its edge table in a caption */
    int lines = alg->run == explain_scanline ? 8 + prim.count : alg->run == explain_fillpoly ||
                                                                     alg->run == explain_fwdiff ||
                                                                     alg->run == explain_clip4d ? 9
              : alg->run == explain_transform ? 10 : 7;
    sr_result run = SR_OK;
    bool made = ex_canvas_init(&c, ctx, grid_w, grid_h, zoom, lines) == SR_OK &&
                (run = alg->run(&c, &prim)) == SR_OK;
    if (made && c.caption_needed > lines) {
        /* A caption longer than the room kept for it (a narrow grid wraps
         * it into more lines) would be cut off: the steps again, with room
         * for the longest.  The frames are all one size, for the sheet. */
        lines = c.caption_needed;
        ex_canvas_free(&c);
        made = ex_canvas_init(&c, ctx, grid_w, grid_h, zoom, lines) == SR_OK &&
               (run = alg->run(&c, &prim)) == SR_OK;
    }
    if (!made) {
        if (c.too_many) {
            cli_error("explain %s: the frames would take over %zu MiB: make --grid or --zoom "
                      "smaller", alg->name, EX_MAX_FRAME_BYTES >> 20);
            status = EXIT_USAGE;
        } else if (alg->run == explain_fwdiff && run == SR_TOO_LARGE) {
            cli_error("explain %s: the curve needs more than 64 steps at this tolerance: "
                      "give a larger --tolerance", alg->name);
            status = EXIT_USAGE;
        } else {
            cli_error("explain %s: %s", alg->name,
                      sr_context_error(ctx)[0] ? sr_context_error(ctx) : sr_result_text(c.error));
            status = EXIT_FAILURE_RUN;
        }
    } else if ((sheet && !sheet_fits(&c)) || !outputs_distinct(c.frame_count, out, sheet, webp)) {
        status = EXIT_USAGE;
    } else if ((out && !write_frames(&c, out)) || (sheet && !write_sheet(&c, sheet)) ||
               (webp && !write_webp(&c, webp))) {
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
