/* test_demo3d.c - the 3D pipeline demos end to end: `softrast demo
 * gouraud-highlight | perspective | zfight | normals | viewport | clip |
 * painter | orientation | depth-range`
 * through the CLI, each image compared with tests/ref/demo_NAME.png, and
 * each phenomenon measured in the panels where the demo draws it (the
 * layouts are shared with the demos through demo3d_layout.h).
 *
 * Tolerance of the reference comparison: a channel may be off by 2 and
 * at most 0.5% of the pixels may differ.  On one machine the output is
 * bit-exact; the slack absorbs libm differences (sin, cos, tan, pow in
 * the lighting and the sRGB-free overlays).  SR_UPDATE_REFS=1 rewrites
 * the references; a failing comparison writes NAME.actual.png and
 * NAME.diff.png to the build's tests/out. */
#include "../apps/softrast/demo3d_layout.h"
#include "image_compare.h"
#include "softrast_io.h"
#include "sr_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct image {
    int w, h;
    uint8_t *px;
} image;

/* Render `demo` with the CLI at its default scale and compare it with
 * its reference (unless it is `clip`: test_demo2d.c compares that one, at
 * --scale 4 like the other 2D demos, and the 3D section is the same at
 * any scale); the image is returned for the phenomenon checks (px NULL
 * if it could not be made). */
static image render_demo(const char *demo)
{
    bool compare = strcmp(demo, "clip") != 0;
    image im = { 0, 0, NULL };
    char out[1024], name[64];
    snprintf(name, sizeof name, "demo_%s", demo);
    for (char *c = name; *c; c++) {
        *c = *c == '-' ? '_' : *c;
    }
    snprintf(out, sizeof out, "%s/%s%s.png", sr_test_out_dir(), name, compare ? "" : "_3d");
    int status = sr_test_run_cli((const char *[]){ "demo", demo, "-o", out, NULL });
    CHECK_EQ(status, 0);
    if (status != 0) {
        return im;
    }
    sr_io_error err;
    if (sr_read_png(out, NULL, &im.w, &im.h, &im.px, &err) != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "reading %s: %s", out, err.message);
        im.px = NULL;
        return im;
    }
    if (compare) {
        sr_test_check_image(name, im.px, im.w, im.h, 2, (long)im.w * im.h / 200);
    }
    return im;
}

/* A panel of a demo image: its top-left output pixel and size. */
typedef struct panel {
    const image *im;
    int x0, y0, w, h;
} panel;

static panel cell(const image *im, demo3d_layout l, int top, int index)
{
    panel p = { im, 0, 0, l.cell_w, l.cell_h };
    demo3d_cell_origin(l, 1, top, index, &p.x0, &p.y0);
    return p;
}

static const uint8_t *at(const panel *p, int x, int y)
{
    return p->im->px + 4 * ((size_t)(p->y0 + y) * (size_t)p->im->w + (size_t)(p->x0 + x));
}

static int luma(const uint8_t *c)
{
    return (2 * c[0] + 5 * c[1] + c[2]) / 8;
}

static int peak_luma(const panel *p)
{
    int best = 0;
    for (int y = 0; y < p->h; y++) {
        for (int x = 0; x < p->w; x++) {
            int l = luma(at(p, x, y));
            best = l > best ? l : best;
        }
    }
    return best;
}

/* Pixels whose every channel is at least `lo` (white-ish highlight). */
static long count_bright(const panel *p, int lo)
{
    long n = 0;
    for (int y = 0; y < p->h; y++) {
        for (int x = 0; x < p->w; x++) {
            const uint8_t *c = at(p, x, y);
            n += c[0] >= lo && c[1] >= lo && c[2] >= lo;
        }
    }
    return n;
}

static double mean_abs_diff(const panel *a, const panel *b)
{
    double sum = 0;
    for (int y = 0; y < a->h; y++) {
        for (int x = 0; x < a->w; x++) {
            for (int k = 0; k < 3; k++) {
                sum += abs((int)at(a, x, y)[k] - (int)at(b, x, y)[k]);
            }
        }
    }
    return sum / (3.0 * a->w * a->h);
}

SR_TEST(demo_gouraud_highlight_phong_catches_what_gouraud_misses)
{
    image im = render_demo("gouraud-highlight");
    REQUIRE(im.px);
    demo3d_layout l = DEMO3D_LAYOUT_GOURAUD;
    panel g_int = cell(&im, l, 0, 0), p_int = cell(&im, l, 0, 1);
    panel g_vtx = cell(&im, l, 0, 2), p_vtx = cell(&im, l, 0, 3);
    /* Interior highlight: Gouraud interpolates four dull corners and
     * shows no highlight at all; Phong lights the pixels under it. */
    long g = count_bright(&g_int, 200), p = count_bright(&p_int, 200);
    CHECK(g < 20);
    CHECK(p > 150);
    CHECK(peak_luma(&p_int) - peak_luma(&g_int) >= 25);
    /* Vertex highlight: Gouraud smears the vertex's full brightness over
     * the triangles around it (a blob twice the size), Phong keeps the
     * small round spot. */
    long gb = count_bright(&g_vtx, 200), pb = count_bright(&p_vtx, 200);
    CHECK(pb > 150);
    CHECK(gb > 3 * pb / 2);
    free(im.px);
}

/* Rows, from the bottom of column x, where the luma crosses 128. */
static int crossings(const panel *p, int x, int *rows, int max)
{
    int n = 0;
    for (int y = p->h - 2; y >= 0 && n < max; y--) {
        if ((luma(at(p, x, y)) >= 128) != (luma(at(p, x, y + 1)) >= 128)) {
            rows[n++] = y;
        }
    }
    return n;
}

/* In the gradient panel's centre column: the row of the white midpoint
 * line (the first white run from the bottom) and the row where the color
 * turns from more red than blue to more blue than red. */
static void gradient_rows(const panel *p, int *line_row, int *half_row)
{
    int x = p->w / 2;
    *line_row = *half_row = -1;
    bool on_floor = false;
    for (int y = p->h - 1; y >= 0; y--) {
        const uint8_t *c = at(p, x, y);
        bool white = c[0] > 200 && c[1] > 200 && c[2] > 200;
        if (white) {
            if (*line_row < 0) {
                *line_row = y;
            }
            continue;
        }
        if (c[0] > c[2] + 60) {
            on_floor = true;
        } else if (on_floor && *half_row < 0 && c[0] <= c[2]) {
            *half_row = y;
        }
    }
}

SR_TEST(demo_perspective_affine_differs_from_perspective_correct)
{
    image im = render_demo("perspective");
    REQUIRE(im.px);
    demo3d_layout l = DEMO3D_LAYOUT_PERSPECTIVE;
    panel ca = cell(&im, l, 0, 0), cp = cell(&im, l, 0, 1);
    panel ga = cell(&im, l, 0, 2), gp = cell(&im, l, 0, 3);
    /* Checker: the squares' edges sit at other rows.  Away from the
     * centre line (the triangles' shared diagonal passes nearby) count the
     * crossings of a column and compare them. */
    int ra[64], rp[64];
    int x = ca.w / 2 + 40;
    int na = crossings(&ca, x, ra, 64), np = crossings(&cp, x, rp, 64);
    CHECK(na >= 6 && np >= 6);
    int moved = 0;
    for (int i = 0; i < na && i < np; i++) {
        moved += abs(ra[i] - rp[i]) >= 3;
    }
    CHECK(moved >= 3);
    CHECK(mean_abs_diff(&ca, &cp) > 10);
    /* Gradient: perspective-correct puts the half-way color on the
     * world-space midpoint line, screen-space interpolation far from it. */
    int line_a, half_a, line_p, half_p;
    gradient_rows(&ga, &line_a, &half_a);
    gradient_rows(&gp, &line_p, &half_p);
    CHECK(line_a > 0 && line_p > 0 && half_a > 0 && half_p > 0);
    CHECK(abs(half_p - line_p) <= 4);
    CHECK(half_a - line_p >= 15);
    free(im.px);
}

/* Floor pixels of each floor color: orange (the top surface, right) and
 * blue (the lower surface showing through: z-fighting). */
static void count_floors(const panel *p, long *orange, long *blue)
{
    *orange = *blue = 0;
    for (int y = 0; y < p->h; y++) {
        for (int x = 0; x < p->w; x++) {
            const uint8_t *c = at(p, x, y);
            *orange += c[0] > c[2] + 60;
            *blue += c[2] > c[0] + 60;
        }
    }
}

SR_TEST(demo_zfight_d16_fights_reversed_z_and_offset_do_not)
{
    image im = render_demo("zfight");
    REQUIRE(im.px);
    demo3d_layout l = DEMO3D_LAYOUT_ZFIGHT;
    long o, b;
    /* Rows D16, D24, D32F, D32F reversed-Z, D16 + offset; columns
     * far/near 10^2, 10^4, 10^6. */
    panel d16_1e4 = cell(&im, l, 0, 1);
    count_floors(&d16_1e4, &o, &b);
    CHECK(o > (o + b) / 10);
    CHECK(b > (o + b) / 10);
    panel d16_1e2 = cell(&im, l, 0, 0);
    count_floors(&d16_1e2, &o, &b);
    CHECK(b < (o + b) / 50);
    panel d24_1e6 = cell(&im, l, 0, 5);
    count_floors(&d24_1e6, &o, &b);
    CHECK(b > (o + b) / 20);
    for (int col = 0; col < 3; col++) {
        panel rev = cell(&im, l, 0, 9 + col), off = cell(&im, l, 0, 12 + col);
        count_floors(&rev, &o, &b);
        CHECK(o > 5000);
        CHECK(b <= (o + b) / 1000);
        count_floors(&off, &o, &b);
        CHECK(o > 5000);
        CHECK(b <= (o + b) / 1000);
    }
    free(im.px);
}

SR_TEST(demo_normals_wrong_and_right_normals_shade_differently)
{
    image im = render_demo("normals");
    REQUIRE(im.px);
    demo3d_layout l = DEMO3D_LAYOUT_NORMALS;
    panel lit_m = cell(&im, l, 0, 0), lit_t = cell(&im, l, 0, 1);
    panel col_m = cell(&im, l, 0, 2), col_t = cell(&im, l, 0, 3);
    CHECK(mean_abs_diff(&lit_m, &lit_t) > 6);
    CHECK(mean_abs_diff(&col_m, &col_t) > 6);
    /* Same positions: the same pixels are covered (background dark in
     * both, up to the whiskers, which differ in direction). */
    long both_bg = 0, one_bg = 0;
    for (int y = 0; y < lit_m.h; y++) {
        for (int x = 0; x < lit_m.w; x++) {
            bool a = luma(at(&lit_m, x, y)) < 30, c = luma(at(&lit_t, x, y)) < 30;
            both_bg += a && c;
            one_bg += a != c;
        }
    }
    CHECK(both_bg > 0);
    /* The whiskers alone differ: a seventh of the shared background
     * (5,959 pixels against 43,392).  Shifting one panel by 4 pixels
     * adds the mesh's outline and fails this. */
    CHECK(6 * one_bg < both_bg);
    free(im.px);
}

/* Bounding box of the red sphere's pixels: width / height. */
static double sphere_aspect(const panel *p)
{
    int x0 = p->w, x1 = -1, y0 = p->h, y1 = -1;
    for (int y = 0; y < p->h; y++) {
        for (int x = 0; x < p->w; x++) {
            const uint8_t *c = at(p, x, y);
            if (c[0] > 60 && c[0] > 2 * c[1] && c[0] > 2 * c[2]) {
                x0 = x < x0 ? x : x0;
                x1 = x > x1 ? x : x1;
                y0 = y < y0 ? y : y0;
                y1 = y > y1 ? y : y1;
            }
        }
    }
    if (x1 < x0) {
        return 0;
    }
    return (double)(x1 - x0 + 1) / (double)(y1 - y0 + 1);
}

SR_TEST(demo_viewport_sphere_stays_round_only_when_aspect_is_kept)
{
    image im = render_demo("viewport");
    REQUIRE(im.px);
    demo3d_layout l = DEMO3D_LAYOUT_VIEWPORT;
    double a[6];
    for (int i = 0; i < 6; i++) {
        panel p = cell(&im, l, 0, i);
        a[i] = sphere_aspect(&p);
    }
    CHECK(a[0] > 1.5);                 /* wide, stretched: squashed flat */
    CHECK(a[3] > 0 && a[3] < 1 / 1.5); /* tall, stretched: squeezed thin */
    for (int i = 1; i < 6; i++) {
        if (i != 3) {
            CHECK_NEAR(a[i], 1.0, 0.08);
        }
    }
    free(im.px);
}

SR_TEST(demo_clip_3d_section_shows_clip_generated_edges)
{
    image im = render_demo("clip");
    REQUIRE(im.px);
    demo3d_layout l = DEMO3D_LAYOUT_CLIP;
    int top = im.h - demo3d_grid_height(l, 1);
    REQUIRE(top > 0);
    panel scene = cell(&im, l, top, 0), lines = cell(&im, l, top, 1), full = cell(&im, l, top, 2);
    long covered = 0, outlined = 0, red = 0;
    for (int y = 0; y < scene.h; y++) {
        for (int x = 0; x < scene.w; x++) {
            covered += luma(at(&scene, x, y)) > 40;
            outlined += luma(at(&lines, x, y)) > 40;
            const uint8_t *c = at(&full, x, y);
            red += c[0] > 200 && c[1] < 110 && c[2] < 110;
        }
    }
    CHECK(covered > scene.w * scene.h / 2);      /* the scene fills most of the view */
    CHECK(outlined > 500 && outlined < covered / 4);
    CHECK(red > 400);                            /* edges on the near, far and side planes */
    free(im.px);
}

/* Render `demo` into *im and point p[0 .. n) at its first n panels;
 * false when it could not be rendered. */
static bool render_panels(const char *demo, demo3d_layout l, image *im, panel *p, int n)
{
    *im = render_demo(demo);
    for (int i = 0; im->px && i < n; i++) {
        p[i] = cell(im, l, 0, i);
    }
    return im->px != NULL;
}

/* Where the painter's panel differs from the z-buffer's, and how: pixels
 * where `want` holds of the z-buffer's color and the painter's. */
typedef bool (*pixel_pair)(const uint8_t *zbuf, const uint8_t *painter, int x, int w);

static void count_differences(const panel *zb, const panel *pa, pixel_pair want, long *differ,
                              long *as_wanted)
{
    *differ = *as_wanted = 0;
    for (int y = 0; y < zb->h; y++) {
        for (int x = 0; x < zb->w; x++) {
            const uint8_t *a = at(zb, x, y), *b = at(pa, x, y);
            if (memcmp(a, b, 3) != 0) {
                ++*differ;
                *as_wanted += want(a, b, x, zb->w);
            }
        }
    }
}

/* Cyclic overlap: only red (the pencil that should be on top at the top
 * corner) turned blue (the last pencil, painted over it). */
static bool red_became_blue(const uint8_t *zb, const uint8_t *pa, int x, int w)
{
    (void)x;
    (void)w;
    return zb[0] > zb[2] && pa[2] > pa[0];
}

/* Interpenetration: only the green that comes out of the red triangle on
 * the left turned red (green passes through red 2 pixels right of the
 * panel's middle). */
static bool green_became_red_on_the_left(const uint8_t *zb, const uint8_t *pa, int x, int w)
{
    return zb[1] > zb[0] && pa[0] > pa[1] && x < w / 2 + 4;
}

SR_TEST(demo_painter_fails_where_the_z_buffer_does_not)
{
    image im;
    panel p[4];
    REQUIRE(render_panels("painter", DEMO3D_LAYOUT_PAINTER, &im, p, 4));
    long differ, wanted;
    count_differences(&p[0], &p[1], red_became_blue, &differ, &wanted);
    printf("painter demo, cyclic: %ld pixels differ, %ld red -> blue\n", differ, wanted);
    CHECK(differ > 300);
    CHECK_EQ(wanted, differ);
    count_differences(&p[2], &p[3], green_became_red_on_the_left, &differ, &wanted);
    printf("painter demo, interpenetrating: %ld pixels differ, %ld green -> red on the left\n",
           differ, wanted);
    CHECK(differ > 300);
    CHECK_EQ(wanted, differ);
    free(im.px);
}

/* Mean channel difference between the 0-degree panel and the panel
 * turned by `deg`, sampled back through the turn, over the square's
 * inside (points at least 4 pixels from its edges). */
static double turned_difference(const panel *upright, const panel *turned, double deg)
{
    double c = cos(deg * 3.14159265358979 / 180.0), s = sin(deg * 3.14159265358979 / 180.0);
    double cx = upright->w / 2.0, cy = upright->h / 2.0;
    double half = 0.85 * (cx < cy ? cx : cy) / sqrt(2.0) - 4.0; /* the demo's square, inset */
    double sum = 0;
    long n = 0;
    for (int y = 0; y < upright->h; y++) {
        for (int x = 0; x < upright->w; x++) {
            double ux = x + 0.5 - cx, uy = y + 0.5 - cy;
            if (fabs(ux) > half || fabs(uy) > half) {
                continue;
            }
            int tx = (int)floor(cx + c * ux - s * uy), ty = (int)floor(cy + s * ux + c * uy);
            for (int k = 0; k < 3; k++) {
                sum += abs((int)at(upright, x, y)[k] - (int)at(turned, tx, ty)[k]);
            }
            n += 3;
        }
    }
    return n ? sum / (double)n : 1e9;
}

SR_TEST(demo_orientation_only_triangles_turn_with_the_square)
{
    image im;
    panel p[6];
    REQUIRE(render_panels("orientation", DEMO3D_LAYOUT_ORIENTATION, &im, p, 6));
    const double turn[3] = { 0, 30, 45 };
    for (int t = 1; t < 3; t++) {
        double scan = turned_difference(&p[0], &p[t], turn[t]);
        double tri = turned_difference(&p[3], &p[3 + t], turn[t]);
        printf("orientation demo, %g deg: scan lines differ by %.2f, triangles by %.2f\n",
               turn[t], scan, tri);
        CHECK(scan > 20.0);
        CHECK(tri < 3.0);
    }
    free(im.px);
}

/* Range 0.25,0.75 holds the depths of range 0,1 halved and moved up a
 * quarter (the cleared background stays 1); 1,0 with LESS shows the blue
 * sphere through the red one; the marker behind the red sphere shows in
 * front in its own range. */
SR_TEST(demo_depth_range_maps_inverts_and_splits_depth)
{
    image im;
    panel p[4];
    REQUIRE(render_panels("depth-range", DEMO3D_LAYOUT_DEPTH_RANGE, &im, p, 4));
    long covered = 0, off = 0, through = 0, marker = 0;
    for (int y = 0; y < p[0].h; y++) {
        for (int x = 0; x < p[0].w; x++) {
            int g0 = at(&p[0], x, y)[0], g1 = at(&p[1], x, y)[0];
            if (g0 == 255) {
                off += g1 != 255;
            } else {
                covered++;
                off += abs(4 * g1 - (255 + 2 * g0)) > 6; /* g1 = 63.75 + g0 / 2, +-1.5 */
            }
            const uint8_t *inv = at(&p[2], x, y), *split = at(&p[3], x, y);
            through += inv[2] > inv[0] + 40 && split[0] > split[2] + 40;
            marker += split[0] > 150 && split[1] > 150 && split[2] < 100;
        }
    }
    printf("depth-range demo: %ld covered, %ld off the mapping, %ld blue through red, "
           "%ld marker pixels\n", covered, off, through, marker);
    CHECK(covered > 5000);
    CHECK_EQ(off, 0);
    CHECK(through > 500);
    CHECK(marker > 200);
    free(im.px);
}

/* --scale takes 1..32, but most 3D demos' pages pass the framebuffer's
 * 8192 a side well before 32: refused as bad usage (exit 2) with the
 * largest scale that fits, before any file is written, not a failed run
 * (exit 1) with the library's message about sr_framebuffer_desc.width. */
SR_TEST(demo_scale_too_large_for_the_page_is_refused)
{
    static const char *const demos[] = { "gouraud-highlight", "perspective", "zfight", "normals",
                                         "viewport", "aa", "painter", "orientation",
                                         "depth-range" };
    for (size_t i = 0; i < sizeof demos / sizeof demos[0]; i++) {
        char out[1024];
        snprintf(out, sizeof out, "%s/demo_too_large.png", sr_test_out_dir());
        remove(out);
        int status = sr_test_run_cli((const char *[]){ "demo", demos[i], "--scale", "32", "-o",
                                                       out, NULL });
        if (status != 2) {
            sr_test_fail(__FILE__, __LINE__, "demo %s --scale 32: exit %d, not 2", demos[i],
                         status);
        }
        FILE *f = fopen(out, "rb");
        CHECK(f == NULL);   /* nothing written */
        if (f) {
            fclose(f);
        }
    }
}

/* An empty -o is bad usage (exit 2), not a failed run. */
SR_TEST(demo_empty_output_name_is_refused)
{
    CHECK_EQ(sr_test_run_cli((const char *[]){ "demo", "lines", "-o", "", NULL }), 2);
}
