/* test_explain.c - `softrast explain`: every algorithm's last frame shows,
 * cell for cell, the pixels the library draws for the same primitive at
 * 1x.  The frames are read back as PNGs; a cell counts as drawn when any
 * of its pixels is the frame's fill blue: the edges, marks and labels
 * drawn over the cells are black or grey, and blended over white they stay
 * grey, so blue shows only where a cell was filled. */
#define _XOPEN_SOURCE 700   /* nftw */
#include "image_compare.h"
#include "raster_util.h"
#include "softrast_io.h"
#include "sr_test.h"

#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define ZOOM 8
#define MARGIN 16   /* the grid's top-left corner in a frame (docs/explain.md) */
#define GRID 16
#ifdef SR_CLI_PATH
#define NEEDS_CLI() (void)0
#else
#define NEEDS_CLI() SKIP("the softrast tool is not part of this build")
#endif
#define FAILF(...) sr_test_fail(__FILE__, __LINE__, __VA_ARGS__)

static bool is_fill_blue(const uint8_t *p)
{
    return p[2] > p[0] + 100 && p[2] > p[1] + 60;
}

/* zbuffer's first triangle, drawn orange */
static bool is_fill_orange(const uint8_t *p)
{
    return p[0] > p[2] + 100 && p[0] > p[1] + 60;
}

/* The cells of the last frame-NNN.png of dir with a pixel that `is_fill`
 * takes for the fill; the frame's number, or 0. */
static int last_frame_colour(const char *dir, bool (*is_fill)(const uint8_t *), uint8_t *cells)
{
    char path[1200];
    int last = 0;
    for (int i = 1; i < 100; i++) {
        struct stat st;
        snprintf(path, sizeof path, "%s/frame-%03d.png", dir, i);
        if (stat(path, &st) != 0) {
            break;
        }
        last = i;
    }
    if (last == 0) {
        return 0;
    }
    snprintf(path, sizeof path, "%s/frame-%03d.png", dir, last);
    int w, h;
    uint8_t *px = NULL;
    sr_io_error err;
    if (sr_read_png(path, NULL, &w, &h, &px, &err) != SR_OK) {
        FAILF("%s", err.message);
        return 0;
    }
    for (int cy = 0; cy < GRID; cy++) {
        for (int cx = 0; cx < GRID; cx++) {
            int blue = 0;
            for (int y = 1; y < ZOOM; y++) {
                for (int x = 1; x < ZOOM; x++) {
                    int fx = MARGIN + cx * ZOOM + x, fy = MARGIN + cy * ZOOM + y;
                    blue += fx < w && fy < h && is_fill(px + ((size_t)fy * w + fx) * 4);
                }
            }
            cells[cy * GRID + cx] = blue > 0;
        }
    }
    free(px);
    return last;
}

/* The cells drawn in the frame blue in the last frame of dir. */
static int last_frame_cells(const char *dir, uint8_t *cells)
{
    return last_frame_colour(dir, is_fill_blue, cells);
}

/* The commonest colour inside each cell of frame `frame` of dir, RGB,
 * for a frame drawn at `zoom`. */
static bool frame_cell_colours_at(const char *dir, int frame, int zoom, uint8_t *rgb)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/frame-%03d.png", dir, frame);
    int w, h;
    uint8_t *px = NULL;
    if (sr_read_png(path, NULL, &w, &h, &px, NULL) != SR_OK) {
        FAILF("cannot read %s", path);
        return false;
    }
    uint32_t *seen = malloc((size_t)(zoom - 1) * (zoom - 1) * sizeof *seen);
    int *count = malloc((size_t)(zoom - 1) * (zoom - 1) * sizeof *count);
    if (!seen || !count) {
        FAILF("out of memory");
        free(seen);
        free(count);
        free(px);
        return false;
    }
    for (int cy = 0; cy < GRID; cy++) {
        for (int cx = 0; cx < GRID; cx++) {
            int n = 0, best = 0;
            for (int y = 1; y < zoom; y++) {   /* inside the grid lines */
                for (int x = 1; x < zoom; x++) {
                    const uint8_t *p = px + ((size_t)(MARGIN + cy * zoom + y) * w + MARGIN +
                                             cx * zoom + x) * 4;
                    uint32_t c = (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2];
                    int i = 0;
                    while (i < n && seen[i] != c) {
                        i++;
                    }
                    if (i == n) {
                        seen[n] = c;
                        count[n++] = 0;
                    }
                    count[i]++;
                    best = count[i] > count[best] ? i : best;
                }
            }
            uint8_t *o = rgb + (cy * GRID + cx) * 3;
            o[0] = (uint8_t)(seen[best] >> 16);
            o[1] = (uint8_t)(seen[best] >> 8);
            o[2] = (uint8_t)seen[best];
        }
    }
    free(seen);
    free(count);
    free(px);
    return true;
}

static bool frame_cell_colours(const char *dir, int frame, uint8_t *rgb)
{
    return frame_cell_colours_at(dir, frame, ZOOM, rgb);
}

/* The covered samples of each cell of the last frame of `dir` (an
 * msaa explanation with n samples): the cell's commonest colour is the
 * fill blue over white in k/n, as the resolve rounds it. */
static bool last_frame_samples(const char *dir, int n, uint8_t *k_out)
{
    uint8_t rgb[GRID * GRID * 3];
    if (!frame_cell_colours(dir, 3, rgb)) {
        return false;
    }
    for (int i = 0; i < GRID * GRID; i++) {
        k_out[i] = (uint8_t)lround((255.0 - rgb[i * 3]) * n / (255.0 - 51.0));
    }
    return true;
}

/* The tool on one primitive at the tests' grid and zoom, with one more
 * option (opt NULL: none). */
static int run_explain_with(const char *algorithm, const char *prim_opt, const char *prim,
                            const char *opt, const char *value, const char *dir)
{
    char grid[16], zoom[8];
    snprintf(grid, sizeof grid, "%dx%d", GRID, GRID);
    snprintf(zoom, sizeof zoom, "%d", ZOOM);
    const char *args[] = { "explain", algorithm, prim_opt, prim, "--grid", grid, "--zoom", zoom,
                           "-o", dir, opt, value, NULL };
    return sr_test_run_cli(args);
}

static int run_explain_rule(const char *algorithm, const char *prim_opt, const char *prim,
                            const char *rule, const char *dir)
{
    return run_explain_with(algorithm, prim_opt, prim, rule ? "--fill-rule" : NULL, rule, dir);
}

static int run_explain(const char *algorithm, const char *prim_opt, const char *prim,
                       const char *dir)
{
    return run_explain_rule(algorithm, prim_opt, prim, NULL, dir);
}

/* Count the cells that differ from want; report them once (what NULL:
 * the caller judges the count). */
static int compare_cells(const uint8_t *cells, const uint8_t *want, const char *what)
{
    int diff = 0;
    for (int i = 0; i < GRID * GRID; i++) {
        diff += cells[i] != want[i];
    }
    if (diff && what) {
        FAILF("%s: %d cells differ", what, diff);
    }
    return diff;
}

/* The pixels the library drew into t against a last frame's cells: how
 * many differ (compare_cells); the pixels drawn are added to *drawn. */
static int compare_with_target(const rt_target *t, const uint8_t *cells, const char *what,
                               int *drawn)
{
    uint8_t want[GRID * GRID];
    rt_mask(t, want);
    for (int i = 0; i < GRID * GRID; i++) {
        *drawn += want[i];
    }
    return compare_cells(cells, want, what);
}

/* An empty directory for one run's frames: the frames of an earlier run
 * with more steps would pass for this run's last. */
static const char *out_dir(const char *name, char *buf, size_t n)
{
    snprintf(buf, n, "%s/explain_%s", sr_test_out_dir(), name);
    mkdir(buf, 0777);
    for (int i = 1; i < 100; i++) {
        char path[1200];
        snprintf(path, sizeof path, "%s/frame-%03d.png", buf, i);
        remove(path);
    }
    return buf;
}

SR_TEST(triangle_last_frame_is_what_sr_draw_covers)
{
    NEEDS_CLI();
    /* the example (ties on a top, a left and a right edge), then random
     * triangles of either winding with vertices on the half-pixel grid,
     * so that many pixel centres fall exactly on edges; each explained by
     * the steps of each rasterizer (--rasterizer) and held to every one
     * of sr_draw's */
    static const char *const rasterizers[] = { "halfspace", "scanline", "barycentric" };
    int steps[3] = { 0, 0, 0 };
    sr_rng rng = { 39 };
    rt_target t = rt_make(GRID, GRID, 1);
    int drawn_total = 0;
    for (int k = 0; k < 24; k++) {
        double v[6] = { 2.5, 1.5, 12.5, 1.5, 4.5, 11.5 };
        if (k > 0) {
            for (int i = 0; i < 6; i++) {
                v[i] = sr_rng_int(&rng, -4, 2 * GRID + 4) * 0.5 + (k % 3 == 0 ? 0.125 : 0);
            }
        }
        char prim[256], dir[1024], name[48];
        snprintf(prim, sizeof prim, "%g,%g,%g,%g,%g,%g", v[0], v[1], v[2], v[3], v[4], v[5]);
        for (int e = 0; e < 3; e++) {
            snprintf(name, sizeof name, "triangle_%02d_%s", k, rasterizers[e]);
            out_dir(name, dir, sizeof dir);
            REQUIRE(run_explain_with("triangle", "--triangle", prim, "--rasterizer",
                                     rasterizers[e], dir) == 0);
            uint8_t cells[GRID * GRID];
            int last = last_frame_cells(dir, cells);
            REQUIRE(last >= 2);
            steps[e] += last;
            for (int r = SR_RASTER_HALFSPACE; r <= SR_RASTER_BARYCENTRIC; r++) {
                rt_clear(&t);
                REQUIRE(rt_draw_tris(&t, v, 1, NULL, (sr_rasterizer)r) == SR_OK);
                char what[300];
                snprintf(what, sizeof what, "triangle %s explained %s, rasterizer %d", prim,
                         rasterizers[e], r);
                compare_with_target(&t, cells, what, &drawn_total);
            }
        }
    }
    CHECK(drawn_total > 9 * 500);   /* the triangles do cover pixels */
    /* the three explain different steps */
    CHECK(steps[0] != steps[1] && steps[1] != steps[2] && steps[0] != steps[2]);
    rt_free(&t);
}

SR_TEST(scanline_last_frame_is_what_sr_fill_polygon_fills)
{
    NEEDS_CLI();
    /* the example (a horizontal edge, a vertex on a sample height, a
     * notch), then random polygons, self-intersecting ones too, with
     * vertices on the half-pixel grid so crossings fall on pixel centres
     * and vertices on sample heights; under both fill rules */
    sr_rng rng = { 3939 };
    int drawn_total = 0;
    for (int k = 0; k < 24; k++) {
        sr_point2 v[8] = { { 1.3, 1.4 }, { 7.0, 4.5 }, { 13.7, 1.4 }, { 10.5, 10.5 },
                           { 3.5, 10.5 }, { 1.3, 6.5 } };
        int n = 6;
        if (k > 1) {
            n = sr_rng_int(&rng, 3, 8);
            for (int i = 0; i < n; i++) {
                v[i].x = sr_rng_int(&rng, -4, 2 * GRID + 4) * 0.5 + (k % 4 == 0 ? 0.3 : 0);
                v[i].y = sr_rng_int(&rng, -4, 2 * GRID + 4) * 0.5;
            }
        }
        char prim[512] = "", dir[1024], name[32];
        for (int i = 0; i < n; i++) {
            size_t len = strlen(prim);
            snprintf(prim + len, sizeof prim - len, "%s%g,%g", i ? "," : "", v[i].x, v[i].y);
        }
        sr_fill_rule rule = k % 2 ? SR_NONZERO : SR_EVENODD;
        snprintf(name, sizeof name, "scanline_%02d", k);
        out_dir(name, dir, sizeof dir);
        REQUIRE(run_explain_rule("scanline", "--polygon", prim,
                                 rule == SR_EVENODD ? "evenodd" : "nonzero", dir) == 0);
        uint8_t cells[GRID * GRID], want[GRID * GRID];
        REQUIRE(last_frame_cells(dir, cells) >= 2);
        REQUIRE(sr_polygon_coverage(sr_test_ctx(), &(sr_polygon2){ v, n, NULL, 0 },
                                    &(sr_fill_desc){ .rule = rule }, 0, 0, GRID, GRID, want,
                                    GRID) == SR_OK);
        for (int i = 0; i < GRID * GRID; i++) {
            want[i] = want[i] != 0;
            drawn_total += want[i];
        }
        char what[600];
        snprintf(what, sizeof what, "polygon %s, %s", prim,
                 rule == SR_EVENODD ? "even-odd" : "nonzero");
        compare_cells(cells, want, what);
    }
    CHECK(drawn_total > 500);
}

SR_TEST(clip_last_frame_is_the_fill_of_the_clipped_polygon)
{
    NEEDS_CLI();
    /* random polygons against integer windows: no pixel centre is on the
     * window's border, so the clipped polygon fills exactly the pixels of
     * the whole polygon whose centres are inside the window */
    sr_rng rng = { 3940 };
    int drawn_total = 0;
    for (int k = 0; k < 16; k++) {
        sr_point2 v[8];
        int n = sr_rng_int(&rng, 3, 8);
        for (int i = 0; i < n; i++) {
            v[i].x = sr_rng_int(&rng, -16, (GRID + 2) * 8) / 8.0 + 0.3;
            v[i].y = sr_rng_int(&rng, -16, (GRID + 2) * 8) / 8.0 + 0.3;
        }
        int w[4] = { sr_rng_int(&rng, 0, 6), sr_rng_int(&rng, 0, 6), sr_rng_int(&rng, 9, GRID),
                     sr_rng_int(&rng, 9, GRID) };
        char prim[512] = "", win[64], dir[1024], name[32], grid[16], zoom[8];
        for (int i = 0; i < n; i++) {
            size_t len = strlen(prim);
            snprintf(prim + len, sizeof prim - len, "%s%g,%g", i ? "," : "", v[i].x, v[i].y);
        }
        snprintf(win, sizeof win, "%d,%d,%d,%d", w[0], w[1], w[2], w[3]);
        snprintf(name, sizeof name, "clip_%02d", k);
        snprintf(grid, sizeof grid, "%dx%d", GRID, GRID);
        snprintf(zoom, sizeof zoom, "%d", ZOOM);
        sr_fill_rule rule = k % 2 ? SR_NONZERO : SR_EVENODD;
        out_dir(name, dir, sizeof dir);
        REQUIRE(sr_test_run_cli((const char *[]){ "explain", "clip", "--polygon", prim,
                                                  "--window", win, "--grid", grid, "--zoom",
                                                  zoom, "--fill-rule",
                                                  rule == SR_EVENODD ? "evenodd" : "nonzero",
                                                  "-o", dir, NULL }) == 0);
        uint8_t cells[GRID * GRID], want[GRID * GRID];
        REQUIRE(last_frame_cells(dir, cells) >= 2);
        REQUIRE(sr_polygon_coverage(sr_test_ctx(), &(sr_polygon2){ v, n, NULL, 0 },
                                    &(sr_fill_desc){ .rule = rule }, 0, 0, GRID, GRID, want,
                                    GRID) == SR_OK);
        for (int y = 0; y < GRID; y++) {
            for (int x = 0; x < GRID; x++) {
                bool in = x >= w[0] && x < w[2] && y >= w[1] && y < w[3];
                want[y * GRID + x] = want[y * GRID + x] && in;
                drawn_total += want[y * GRID + x];
            }
        }
        char what[600];
        snprintf(what, sizeof what, "polygon %s clipped to %s", prim, win);
        compare_cells(cells, want, what);
    }
    CHECK(drawn_total > 300);
}

SR_TEST(msaa_last_frame_is_what_a_multisampled_sr_draw_resolves)
{
    NEEDS_CLI();
    sr_rng rng = { 4039 };
    for (int k = 0; k < 16; k++) {
        int n = 2 << (k % 4);
        double v[6];
        for (int i = 0; i < 6; i++) {
            v[i] = sr_rng_int(&rng, -16, (GRID + 2) * 16) / 16.0;
        }
        char prim[256], dir[1024], name[32], ns[8];
        snprintf(prim, sizeof prim, "%g,%g,%g,%g,%g,%g", v[0], v[1], v[2], v[3], v[4], v[5]);
        snprintf(name, sizeof name, "msaa_%02d", k);
        snprintf(ns, sizeof ns, "%d", n);
        out_dir(name, dir, sizeof dir);
        REQUIRE(run_explain_with("msaa", "--triangle", prim, "--samples", ns, dir) == 0);
        uint8_t cells[GRID * GRID], want[GRID * GRID];
        REQUIRE(last_frame_samples(dir, n, cells));
        rt_target t = { sr_test_ctx(), NULL, GRID, GRID };
        REQUIRE(sr_make_framebuffer(t.ctx, &(sr_framebuffer_desc){ .width = GRID,
                                                                   .height = GRID,
                                                                   .samples = n },
                                    &t.fb) == SR_OK);
        rt_clear(&t);
        REQUIRE(rt_draw_tris(&t, v, 1, NULL, SR_RASTER_HALFSPACE) == SR_OK);
        const uint8_t *px = sr_framebuffer_pixels(t.fb);
        int partial = 0;
        for (int i = 0; i < GRID * GRID; i++) {
            want[i] = (uint8_t)lround(px[i * 4] * n / 255.0);
            partial += want[i] > 0 && want[i] < n;
        }
        sr_destroy_framebuffer(t.ctx, t.fb);
        char what[300];
        snprintf(what, sizeof what, "msaa %d, triangle %s", n, prim);
        compare_cells(cells, want, what);
        CHECK(partial > 0 || want[0] == want[GRID * GRID - 1]);
    }
}

SR_TEST(zbuffer_last_frame_is_what_sr_draw_leaves_with_a_depth_test)
{
    NEEDS_CLI();
    /* two triangles with depths on the 1/64 grid (exact in float, so the
     * window depth sr_draw sees is the one given), A drawn red then B blue
     * into a 16-bit depth buffer; the last frame shows A's pixels orange
     * and B's blue.  Every fourth pair is at one depth: B's ties with A
     * fail the LESS test. */
    sr_rng rng = { 4139 };
    rt_target t = rt_make(GRID, GRID, 1);
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_framebuffer(t.ctx, &(sr_framebuffer_desc){ .width = GRID, .height = GRID,
                                                              .depth_format = SR_DEPTH_D16 },
                                &fb) == SR_OK);
    int both = 0;
    for (int k = 0; k < 16; k++) {
        double v[18];
        char prim[512] = "", dir[1024], name[32];
        for (int i = 0; i < 6; i++) {
            v[3 * i] = sr_rng_int(&rng, -4, 2 * GRID + 4) * 0.5;
            v[3 * i + 1] = sr_rng_int(&rng, -4, 2 * GRID + 4) * 0.5;
            v[3 * i + 2] = k % 4 == 0 ? 0.5 : sr_rng_int(&rng, 0, 64) / 64.0;
            size_t len = strlen(prim);
            snprintf(prim + len, sizeof prim - len, "%s%g,%g,%g", i ? "," : "", v[3 * i],
                     v[3 * i + 1], v[3 * i + 2]);
        }
        snprintf(name, sizeof name, "zbuffer_%02d", k);
        out_dir(name, dir, sizeof dir);
        REQUIRE(run_explain("zbuffer", "--triangles", prim, dir) == 0);
        uint8_t blue[GRID * GRID], orange[GRID * GRID];
        REQUIRE(last_frame_cells(dir, blue) >= 3);
        REQUIRE(last_frame_colour(dir, is_fill_orange, orange) >= 3);

        float pos[18], col[24];
        for (int i = 0; i < 6; i++) {
            pos[3 * i] = rt_ndc_x(&t, v[3 * i]);
            pos[3 * i + 1] = rt_ndc_y(&t, v[3 * i + 1]);
            pos[3 * i + 2] = (float)v[3 * i + 2];
            float *c = col + 4 * i;
            c[0] = i < 3;
            c[1] = 0;
            c[2] = i >= 3;
            c[3] = 1;
        }
        sr_clear(t.ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
        sr_state st = { .shading = SR_SHADING_UNLIT, .depth_zero_to_one = true,
                        .material = { .diffuse = { 1, 1, 1 } } };
        REQUIRE(sr_draw(t.ctx, fb, &st, &(sr_draw_desc){ .positions = pos, .vertex_count = 6,
                                                         .colors = col, .color_size = 4 })
                == SR_OK);
        const uint8_t *px = sr_framebuffer_pixels(fb);
        uint8_t want_a[GRID * GRID], want_b[GRID * GRID];
        int na = 0, nb = 0;
        for (int i = 0; i < GRID * GRID; i++) {
            want_a[i] = px[i * 4] > 128;
            want_b[i] = px[i * 4 + 2] > 128;
            na += want_a[i];
            nb += want_b[i];
        }
        both += na > 0 && nb > 0;
        char what[600];
        snprintf(what, sizeof what, "zbuffer %s: A", prim);
        compare_cells(orange, want_a, what);
        snprintf(what, sizeof what, "zbuffer %s: B", prim);
        compare_cells(blue, want_b, what);
    }
    CHECK(both >= 8);   /* most pairs leave pixels of both */
    sr_destroy_framebuffer(t.ctx, fb);
    rt_free(&t);
}

SR_TEST(perspective_last_frame_is_what_sr_draw_interpolates)
{
    NEEDS_CLI();
    /* random triangles with w in 1/2..4 (powers of two: x w / w is exact
     * in float, so sr_draw snaps the vertices where they were given), red,
     * green and blue at the vertices; the cells of the last frame hold
     * sr_draw's colours, perspective-correct or (--interpolation affine)
     * affine, or sr_fill_gouraud's FillPoly/FillSpan (fillspan), within
     * one step of rounding; and FillSpan's are affine's within two */
    static const char *const interps[] = { "perspective", "affine", "fillspan" };
    sr_rng rng = { 4239 };
    rt_target t = rt_make(GRID, GRID, 1);
    int interps_differ = 0;
    for (int k = 0; k < 16; k++) {
        double v[6], w[3];
        for (int i = 0; i < 6; i++) {
            v[i] = sr_rng_int(&rng, -4, 2 * GRID + 4) * 0.5;
        }
        for (int i = 0; i < 3; i++) {
            w[i] = ldexp(1.0, sr_rng_int(&rng, -1, 2));
        }
        char prim[256], ws[64], dir[1024], name[32];
        snprintf(prim, sizeof prim, "%g,%g,%g,%g,%g,%g", v[0], v[1], v[2], v[3], v[4], v[5]);
        snprintf(ws, sizeof ws, "%g,%g,%g", w[0], w[1], w[2]);
        snprintf(name, sizeof name, "perspective_%02d", k);
        out_dir(name, dir, sizeof dir);
        int e = k % 3;
        char grid[16], zoom[8];
        snprintf(grid, sizeof grid, "%dx%d", GRID, GRID);
        snprintf(zoom, sizeof zoom, "%d", ZOOM);
        REQUIRE(sr_test_run_cli((const char *[]){ "explain", "perspective", "--triangle", prim,
                                                  "--w", ws, "--interpolation", interps[e],
                                                  "--grid", grid, "--zoom", zoom, "-o", dir,
                                                  NULL }) == 0);
        uint8_t got[GRID * GRID * 3], other[GRID * GRID * 3];
        REQUIRE(frame_cell_colours(dir, 5, got));
        REQUIRE(frame_cell_colours(dir, 4, other));
        float pos[12], col[12] = { 1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1 };
        for (int i = 0; i < 3; i++) {
            pos[4 * i] = rt_ndc_x(&t, v[2 * i]) * (float)w[i];
            pos[4 * i + 1] = rt_ndc_y(&t, v[2 * i + 1]) * (float)w[i];
            pos[4 * i + 2] = 0;
            pos[4 * i + 3] = (float)w[i];
        }
        sr_clear(t.ctx, t.fb, &(sr_clear_desc){ .color = { 1, 1, 1, 1 } });
        sr_state st = { .shading = SR_SHADING_UNLIT, .material = { .diffuse = { 1, 1, 1 } },
                        .interpolation = e == 0 ? SR_INTERP_PERSPECTIVE : SR_INTERP_AFFINE };
        REQUIRE(sr_draw(t.ctx, t.fb, &st, &(sr_draw_desc){ .positions = pos, .position_size = 4,
                                                           .vertex_count = 3, .colors = col,
                                                           .color_size = 4 }) == SR_OK);
        uint8_t affine_px[GRID * GRID * 4];
        memcpy(affine_px, sr_framebuffer_pixels(t.fb), sizeof affine_px);
        if (e == 2) {
            sr_point2 pv[3];
            sr_rgba pc[3];
            for (int i = 0; i < 3; i++) {
                pv[i] = (sr_point2){ v[2 * i], v[2 * i + 1] };
                pc[i] = (sr_rgba){ col[4 * i], col[4 * i + 1], col[4 * i + 2], 1 };
            }
            sr_clear(t.ctx, t.fb, &(sr_clear_desc){ .color = { 1, 1, 1, 1 } });
            REQUIRE(sr_fill_gouraud(t.ctx, t.fb, &(sr_polygon2){ pv, 3, NULL, 0 }, pc,
                                    &(sr_gouraud_desc){ .method = SR_GOURAUD_INCREMENTAL })
                    == SR_OK);
            /* covered by both, FillSpan's colours are affine's */
            const uint8_t *g = sr_framebuffer_pixels(t.fb);
            int far = 0;
            for (int i = 0; i < GRID * GRID * 4; i += 4) {
                bool both = memcmp(g + i, "\xff\xff\xff", 3) != 0 &&
                            memcmp(affine_px + i, "\xff\xff\xff", 3) != 0;
                for (int ch = 0; ch < 3; ch++) {
                    far += both && abs(g[i + ch] - affine_px[i + ch]) > 2;
                }
            }
            if (far) {
                FAILF("perspective %s: %d channels of FillSpan are not affine's", prim, far);
            }
        }
        const uint8_t *px = sr_framebuffer_pixels(t.fb);
        int bad = 0;
        for (int i = 0; i < GRID * GRID; i++) {
            int worst = 0, off_other = 0;
            for (int ch = 0; ch < 3; ch++) {
                int d = abs(got[i * 3 + ch] - px[i * 4 + ch]);
                worst = d > worst ? d : worst;
                d = abs(other[i * 3 + ch] - px[i * 4 + ch]);
                off_other = d > off_other ? d : off_other;
            }
            bad += worst > 1;
            interps_differ += off_other > 8;
        }
        if (bad) {
            FAILF("perspective %s, w %s, %s: %d cells differ", prim, ws, interps[e], bad);
        }
    }
    CHECK(interps_differ > 50);   /* the two interpolations do differ */
    rt_free(&t);
}

SR_TEST(fillpoly_last_frame_is_what_the_incremental_gouraud_fill_draws)
{
    NEEDS_CLI();
    /* random triangles, flat tops and bottoms among them (half-pixel
     * grid), with random intensities: the cells of the last frame hold
     * sr_fill_gouraud's SR_GOURAUD_INCREMENTAL grey within one step */
    sr_rng rng = { 4339 };
    rt_target t = rt_make(GRID, GRID, 1);
    int covered = 0;
    for (int k = 0; k < 16; k++) {
        sr_point2 v[3];
        double in[3];
        for (int i = 0; i < 3; i++) {
            v[i].x = sr_rng_int(&rng, -4, 2 * GRID + 4) * 0.5 + (k % 2 ? 0.3 : 0);
            v[i].y = sr_rng_int(&rng, -4, 2 * GRID + 4) * 0.5;
            in[i] = sr_rng_int(&rng, 0, 100) / 100.0;
        }
        char prim[256], is[64], dir[1024], name[32];
        snprintf(prim, sizeof prim, "%g,%g,%g,%g,%g,%g", v[0].x, v[0].y, v[1].x, v[1].y, v[2].x,
                 v[2].y);
        snprintf(is, sizeof is, "%g,%g,%g", in[0], in[1], in[2]);
        snprintf(name, sizeof name, "fillpoly_%02d", k);
        out_dir(name, dir, sizeof dir);
        REQUIRE(run_explain_with("fillpoly", "--triangle", prim, "--intensity", is, dir) == 0);
        uint8_t cells[GRID * GRID], got[GRID * GRID * 3];
        int last = last_frame_cells(dir, cells);
        REQUIRE(last >= 2);
        REQUIRE(frame_cell_colours(dir, last, got));
        sr_rgba col[3];
        for (int i = 0; i < 3; i++) {
            col[i] = (sr_rgba){ (float)in[i], (float)in[i], (float)in[i], 1 };
        }
        sr_clear(t.ctx, t.fb, &(sr_clear_desc){ .color = { 1, 1, 1, 1 } });
        REQUIRE(sr_fill_gouraud(t.ctx, t.fb, &(sr_polygon2){ v, 3, NULL, 0 }, col,
                                &(sr_gouraud_desc){ .method = SR_GOURAUD_INCREMENTAL })
                == SR_OK);
        uint8_t mask[GRID * GRID];
        REQUIRE(sr_polygon_coverage(t.ctx, &(sr_polygon2){ v, 3, NULL, 0 }, NULL, 0, 0, GRID,
                                    GRID, mask, GRID) == SR_OK);
        const uint8_t *px = sr_framebuffer_pixels(t.fb);
        int bad = 0;
        for (int i = 0; i < GRID * GRID; i++) {
            covered += mask[i] != 0;
            for (int ch = 0; ch < 3; ch++) {
                bad += abs(got[i * 3 + ch] - px[i * 4 + ch]) > 1;
            }
        }
        if (bad) {
            FAILF("fillpoly %s, I %s: %d channels differ", prim, is, bad);
        }
    }
    CHECK(covered > 300);
    rt_free(&t);
}

SR_TEST(circle_last_frame_is_what_sr_draw_circle_draws)
{
    NEEDS_CLI();
    /* centres and radii on the 1/8 grid (many centres exactly on a
     * circle), some circles past the grid's edges */
    sr_rng rng = { 4439 };
    rt_target t = rt_make(GRID, GRID, 1);
    int drawn_total = 0;
    for (int k = 0; k < 20; k++) {
        double cx = sr_rng_int(&rng, -16, (GRID + 2) * 8) / 8.0;
        double cy = sr_rng_int(&rng, -16, (GRID + 2) * 8) / 8.0;
        double r = sr_rng_int(&rng, 0, 12 * 8) / 8.0;
        char prim[128], dir[1024], name[32];
        snprintf(prim, sizeof prim, "%g,%g,%g", cx, cy, r);
        snprintf(name, sizeof name, "circle_%02d", k);
        out_dir(name, dir, sizeof dir);
        REQUIRE(run_explain("circle", "--circle", prim, dir) == 0);
        uint8_t cells[GRID * GRID];
        REQUIRE(last_frame_cells(dir, cells) >= 1);
        rt_clear(&t);
        REQUIRE(sr_draw_circle(t.ctx, t.fb, cx, cy, r, (sr_rgba){ 1, 1, 1, 1 }, false) == SR_OK);
        char what[200];
        snprintf(what, sizeof what, "circle %s", prim);
        compare_with_target(&t, cells, what, &drawn_total);
    }
    CHECK(drawn_total > 150);
    rt_free(&t);
}

SR_TEST(forward_differencing_last_frame_is_what_the_flattened_cubic_draws)
{
    NEEDS_CLI();
    /* random cubics and tolerances: the last frame's cells are the lines
     * sr_draw_line draws through sr_flatten_cubic's points */
    sr_rng rng = { 4539 };
    rt_target t = rt_make(GRID, GRID, 1);
    int drawn_total = 0;
    for (int k = 0; k < 16; k++) {
        sr_point2 p[4];
        for (int i = 0; i < 4; i++) {
            p[i] = (sr_point2){ sr_rng_int(&rng, 0, GRID * 8) / 8.0,
                                sr_rng_int(&rng, 0, GRID * 8) / 8.0 };
        }
        double tol = k % 2 ? 0.25 : 1.0;
        char prim[256], ts[16], dir[1024], name[40];
        snprintf(prim, sizeof prim, "%g,%g,%g,%g,%g,%g,%g,%g", p[0].x, p[0].y, p[1].x, p[1].y,
                 p[2].x, p[2].y, p[3].x, p[3].y);
        snprintf(ts, sizeof ts, "%g", tol);
        snprintf(name, sizeof name, "fwdiff_%02d", k);
        out_dir(name, dir, sizeof dir);
        REQUIRE(run_explain_with("forward-differencing", "--cubic", prim, "--tolerance", ts, dir)
                == 0);
        uint8_t cells[GRID * GRID];
        REQUIRE(last_frame_cells(dir, cells) >= 3);
        sr_point2 pts[65] = { p[0] };
        int n = 0;
        REQUIRE(sr_flatten_cubic(t.ctx, p[0], p[1], p[2], p[3], tol, pts + 1, 64, &n) == SR_OK);
        rt_clear(&t);
        for (int i = 0; i < n; i++) {
            REQUIRE(sr_draw_line(t.ctx, t.fb, pts[i], pts[i + 1], (sr_rgba){ 1, 1, 1, 1 }, NULL)
                    == SR_OK);
        }
        char what[300];
        snprintf(what, sizeof what, "cubic %s, tolerance %g", prim, tol);
        compare_with_target(&t, cells, what, &drawn_total);
    }
    CHECK(drawn_total > 150);
    rt_free(&t);
}

SR_TEST(floodfill_last_frame_is_what_sr_flood_fill_recolours)
{
    NEEDS_CLI();
    /* random polygon outlines drawn with sr_draw_line, random seeds (on
     * the outline now and then), 4- and 8-connected */
    sr_rng rng = { 4639 };
    rt_target t = rt_make(GRID, GRID, 1);
    int drawn_total = 0, differ_4_8 = 0;
    for (int k = 0; k < 16; k++) {
        sr_point2 v[8];
        int n = sr_rng_int(&rng, 3, 8);
        char prim[512] = "", seed[32], dir[1024], name[32];
        for (int i = 0; i < n; i++) {
            v[i] = (sr_point2){ sr_rng_int(&rng, 0, GRID - 1) + 0.5,
                                sr_rng_int(&rng, 0, GRID - 1) + 0.5 };
            size_t len = strlen(prim);
            snprintf(prim + len, sizeof prim - len, "%s%g,%g", i ? "," : "", v[i].x, v[i].y);
        }
        int sx = sr_rng_int(&rng, 0, GRID - 1), sy = sr_rng_int(&rng, 0, GRID - 1);
        snprintf(seed, sizeof seed, "%d,%d", sx, sy);
        int got_n[2] = { 0, 0 };
        for (int conn = 4; conn <= 8; conn += 4) {
            snprintf(name, sizeof name, "floodfill_%02d_%d", k, conn);
            out_dir(name, dir, sizeof dir);
            char grid[16], zoom[8];
            snprintf(grid, sizeof grid, "%dx%d", GRID, GRID);
            snprintf(zoom, sizeof zoom, "%d", ZOOM);
            REQUIRE(sr_test_run_cli((const char *[]){ "explain", "floodfill", "--polygon", prim,
                                                      "--seed", seed, "--connectivity",
                                                      conn == 4 ? "4" : "8", "--grid", grid,
                                                      "--zoom", zoom, "-o", dir, NULL }) == 0);
            uint8_t cells[GRID * GRID], want[GRID * GRID];
            REQUIRE(last_frame_cells(dir, cells) >= 2);
            sr_clear(t.ctx, t.fb, &(sr_clear_desc){ .color = { 1, 1, 1, 1 } });
            for (int i = 0; i < n; i++) {
                REQUIRE(sr_draw_line(t.ctx, t.fb, v[i], v[(i + 1) % n], (sr_rgba){ 0, 0, 0, 1 },
                                     NULL) == SR_OK);
            }
            REQUIRE(sr_flood_fill(t.ctx, t.fb, sx, sy, (sr_rgba){ 0, 0, 1, 1 },
                                  &(sr_region_fill_desc){ .connectivity = conn == 4
                                                              ? SR_CONNECT_4 : SR_CONNECT_8 },
                                  NULL) == SR_OK);
            const uint8_t *px = sr_framebuffer_pixels(t.fb);
            for (int i = 0; i < GRID * GRID; i++) {
                want[i] = px[i * 4 + 2] == 255 && px[i * 4] == 0;
                got_n[conn / 8] += want[i];
            }
            drawn_total += got_n[conn / 8];
            char what[600];
            snprintf(what, sizeof what, "floodfill %s from %s, %d-connected", prim, seed, conn);
            compare_cells(cells, want, what);
        }
        differ_4_8 += got_n[0] != got_n[1];
    }
    CHECK(drawn_total > 500);
    CHECK(differ_4_8 > 0);   /* 8-connected fills leak through diagonal steps */
    rt_free(&t);
}

SR_TEST(clip4d_last_frame_is_what_sr_draw_draws_for_the_clip_space_triangle)
{
    NEEDS_CLI();
    /* random clip-space triangles, a vertex behind the eye (w < 0) or
     * past the near or far plane in most, drawn by sr_draw into the same
     * viewport (the grid less a fifth on each side).  The new vertices are
     * rounded differently (sr_draw's intersections are float), so a pixel
     * centre within that rounding of an edge may differ: at most 3 cells
     * in all the triangles. */
    sr_rng rng = { 4739 };
    rt_target t = rt_make(GRID, GRID, 1);
    int drawn_total = 0, diff_total = 0, clipped = 0;
    for (int k = 0; k < 24; k++) {
        float pos[12];
        char prim[512] = "", dir[1024], name[32];
        for (int i = 0; i < 12; i++) {
            pos[i] = (float)(sr_rng_int(&rng, -24, 24) / 8.0);
            if (i % 4 == 3 && i != 11) {
                pos[i] = (float)(sr_rng_int(&rng, 4, 24) / 8.0);   /* w > 0 for two of them */
            }
            size_t len = strlen(prim);
            snprintf(prim + len, sizeof prim - len, "%s%g", i ? "," : "", pos[i]);
        }
        for (int i = 0; i < 3; i++) {
            clipped += !(pos[4 * i + 3] > 0 && fabsf(pos[4 * i + 2]) <= pos[4 * i + 3]);
        }
        snprintf(name, sizeof name, "clip4d_%02d", k);
        out_dir(name, dir, sizeof dir);
        REQUIRE(run_explain("clip4d", "--clip-triangle", prim, dir) == 0);
        uint8_t cells[GRID * GRID];
        REQUIRE(last_frame_cells(dir, cells) >= 2);
        rt_clear(&t);
        int v0 = GRID / 5, vs = GRID - 2 * (GRID / 5);
        sr_state st = { .shading = SR_SHADING_UNLIT, .material = { .diffuse = { 1, 1, 1 } },
                        .viewport = { v0, v0, vs, vs } };
        REQUIRE(sr_draw(t.ctx, t.fb, &st, &(sr_draw_desc){ .positions = pos, .position_size = 4,
                                                           .vertex_count = 3 }) == SR_OK);
        diff_total += compare_with_target(&t, cells, NULL, &drawn_total);
    }
    CHECK(diff_total <= 3);
    CHECK(drawn_total > 200);
    CHECK(clipped > 10);   /* near, far or w clipping was needed */
    rt_free(&t);
}

/* Lines in every octant: k = 0 is the algorithm's example. */
static void check_lines(const char *algorithm, sr_line_algorithm alg, bool centres)
{
    sr_rng rng = { alg * 77u };
    rt_target t = rt_make(GRID, GRID, 1);
    int drawn_total = 0;
    for (int k = 0; k < 24; k++) {
        double v[4];
        for (int i = 0; i < 4; i++) {
            v[i] = centres ? sr_rng_int(&rng, -2, GRID + 1) + 0.5
                           : sr_rng_int(&rng, -16, (GRID + 4) * 8) / 8.0;
        }
        char prim[128], dir[1024], name[40];
        snprintf(prim, sizeof prim, "%g,%g,%g,%g", v[0], v[1], v[2], v[3]);
        snprintf(name, sizeof name, "%s_%02d", algorithm, k);
        out_dir(name, dir, sizeof dir);
        REQUIRE(run_explain(algorithm, "--line", prim, dir) == 0);
        uint8_t cells[GRID * GRID];
        REQUIRE(last_frame_cells(dir, cells) >= 2);
        rt_clear(&t);
        REQUIRE(sr_draw_line(t.ctx, t.fb, (sr_point2){ v[0], v[1] }, (sr_point2){ v[2], v[3] },
                             (sr_rgba){ 1, 1, 1, 1 },
                             &(sr_line_desc){ .algorithm = alg }) == SR_OK);
        char what[200];
        snprintf(what, sizeof what, "%s line %s", algorithm, prim);
        compare_with_target(&t, cells, what, &drawn_total);
    }
    CHECK(drawn_total > 150);
    rt_free(&t);
}

SR_TEST(bresenham_last_frame_is_what_sr_draw_line_draws)
{
    NEEDS_CLI();
    check_lines("bresenham", SR_LINE_BRESENHAM, true);
}

SR_TEST(dda_last_frame_is_what_sr_draw_line_draws)
{
    NEEDS_CLI();
    check_lines("dda", SR_LINE_DDA_INCREMENTAL, false);
}

/* wu's last frame, cell for cell, is sr_draw_line's SR_LINE_WU line: the
 * fill blue over white, each cell exactly its pixel's colour.  Random
 * lines in every direction, ends at 1/8 px, some off the grid. */
SR_TEST(wu_last_frame_is_what_sr_draw_line_draws)
{
    NEEDS_CLI();
    sr_rng rng = { 0x3au };
    rt_target t = rt_make(GRID, GRID, 1);
    int drawn = 0;
    for (int k = 0; k < 16; k++) {
        double v[4];
        for (int i = 0; i < 4; i++) {
            v[i] = sr_rng_int(&rng, -16, (GRID + 2) * 8) / 8.0;
        }
        char prim[128], dir[1024], name[40];
        snprintf(prim, sizeof prim, "%g,%g,%g,%g", v[0], v[1], v[2], v[3]);
        snprintf(name, sizeof name, "wu_%02d", k);
        out_dir(name, dir, sizeof dir);
        REQUIRE(run_explain("wu", "--line", prim, dir) == 0);
        uint8_t cells[GRID * GRID], rgb[GRID * GRID * 3];
        int last = last_frame_cells(dir, cells);
        REQUIRE(last >= 2);
        REQUIRE(frame_cell_colours(dir, last, rgb));
        sr_clear(t.ctx, t.fb, &(sr_clear_desc){ .color = { 1, 1, 1, 1 } });
        REQUIRE(sr_draw_line(t.ctx, t.fb, (sr_point2){ v[0], v[1] }, (sr_point2){ v[2], v[3] },
                             (sr_rgba){ 0.20f, 0.45f, 0.85f, 1 },
                             &(sr_line_desc){ .algorithm = SR_LINE_WU }) == SR_OK);
        const uint8_t *px = sr_framebuffer_pixels(t.fb);
        int diff = 0;
        for (int i = 0; i < GRID * GRID; i++) {
            diff += memcmp(px + 4 * i, rgb + 3 * i, 3) != 0;
            drawn += px[4 * i] != 255;
        }
        if (diff) {
            FAILF("wu line %s: %d cells differ", prim, diff);
        }
    }
    CHECK(drawn > 100);
    rt_free(&t);
}

/* area's frames against sr_draw_line's SR_LINE_AREA line, the fill blue
 * over white: the last frame cell for cell exactly its pixels, and the
 * frame before it, whose cells are the areas sr_line_area_pixels handed
 * out, within one 8-bit step of them.  Random lines in every direction,
 * ends at 1/8 px, some off the grid, of widths from half a pixel to 4.5
 * and each cap; at zoom 24, where the rectangle's outline, the segment
 * and its labels leave each cell's fill its commonest colour. */
SR_TEST(area_frames_are_what_sr_draw_line_draws)
{
    NEEDS_CLI();
    static const char *const widths[] = { "0.5", "1", "1.7", "3", "4.5" };
    static const char *const caps[] = { "butt", "square", "round" };
    sr_rng rng = { 0xa4eau };
    rt_target t = rt_make(GRID, GRID, 1);
    int drawn = 0;
    for (int k = 0; k < 24; k++) {
        double v[4];
        for (int i = 0; i < 4; i++) {
            v[i] = sr_rng_int(&rng, -16, (GRID + 2) * 8) / 8.0;
        }
        const char *width = widths[k % 5], *cap = caps[k % 3];
        char prim[128], dir[1024], name[40], grid[16];
        snprintf(prim, sizeof prim, "%g,%g,%g,%g", v[0], v[1], v[2], v[3]);
        snprintf(name, sizeof name, "area_%02d", k);
        snprintf(grid, sizeof grid, "%dx%d", GRID, GRID);
        out_dir(name, dir, sizeof dir);
        REQUIRE(sr_test_run_cli((const char *[]){ "explain", "area", "--line", prim, "--width",
                                                  width, "--cap", cap, "--grid", grid, "--zoom",
                                                  "24", "-o", dir, NULL }) == 0);
        uint8_t cells[GRID * GRID], last_rgb[GRID * GRID * 3], areas_rgb[GRID * GRID * 3];
        int last = last_frame_cells(dir, cells);   /* its number; the cells are zoom 8's */
        REQUIRE(last >= 2);
        REQUIRE(frame_cell_colours_at(dir, last, 24, last_rgb));
        REQUIRE(frame_cell_colours_at(dir, last - 1, 24, areas_rgb));
        sr_clear(t.ctx, t.fb, &(sr_clear_desc){ .color = { 1, 1, 1, 1 } });
        sr_line_cap c = (sr_line_cap)(SR_LINE_CAP_BUTT + k % 3);
        REQUIRE(sr_draw_line(t.ctx, t.fb, (sr_point2){ v[0], v[1] }, (sr_point2){ v[2], v[3] },
                             (sr_rgba){ 0.20f, 0.45f, 0.85f, 1 },
                             &(sr_line_desc){ .algorithm = SR_LINE_AREA,
                                              .width = strtod(width, NULL), .cap = c }) == SR_OK);
        const uint8_t *px = sr_framebuffer_pixels(t.fb);
        int diff = 0, areas_diff = 0;
        for (int i = 0; i < GRID * GRID; i++) {
            diff += memcmp(px + 4 * i, last_rgb + 3 * i, 3) != 0;
            for (int ch = 0; ch < 3; ch++) {
                areas_diff += abs(px[4 * i + ch] - areas_rgb[3 * i + ch]) > 1;
            }
            drawn += px[4 * i] != 255;
        }
        if (diff || areas_diff) {
            FAILF("area --line %s --width %s --cap %s: %d cells of the last frame, %d channels "
                  "of the areas differ", prim, width, cap, diff, areas_diff);
        }
    }
    CHECK(drawn > 500);
    rt_free(&t);
}

SR_TEST(explain_refuses_bad_input)
{
    NEEDS_CLI();
    char dir[1024];
    out_dir("bad", dir, sizeof dir);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "nosuch", "-o", dir, NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "triangle", NULL }), 2);
    CHECK_EQ(run_explain("triangle", "--triangle", "1,2,3,4,5", dir), 2);
    CHECK_EQ(run_explain("triangle", "--line", "1,2,3,4", dir), 2);
    CHECK_EQ(run_explain("circle", "--circle", "4,4,-1", dir), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "forward-differencing", "--tolerance",
                                               "0.001", "-o", dir, NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "triangle", "--w", "1,2,3", "-o", dir,
                                               NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "fillpoly", "--intensity", "0,2,1",
                                               "-o", dir, NULL }), 2);
    CHECK_EQ(run_explain("zbuffer", "--triangles", "1,1,0,5,1,0,1,5,0,9,9,0,5,9,0,9,5,1.5", dir),
             2);
    CHECK_EQ(run_explain("scanline", "--polygon", "1,2,3,4", dir), 2);
    CHECK_EQ(run_explain("bresenham", "--line", "1.5,2.5,7,3.5", dir), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "msaa", "--samples", "3", "-o", dir,
                                               NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "clip", "--window", "5,1,2,8", "-o",
                                               dir, NULL }), 2);
    CHECK_EQ(run_explain_rule("scanline", "--polygon", "1,2,3,4,5,6", "odd", dir), 2);
    CHECK_EQ(run_explain_with("triangle", "--triangle", "1,1,9,1,1,9", "--rasterizer", "wu", dir),
             2);
    CHECK_EQ(run_explain_with("msaa", "--triangle", "1,1,9,1,1,9", "--rasterizer", "scanline",
                              dir), 2);
    CHECK_EQ(run_explain_with("perspective", "--triangle", "1,1,9,1,1,9", "--interpolation",
                              "flat", dir), 2);
    CHECK_EQ(run_explain_with("triangle", "--triangle", "1,1,9,1,1,9", "--interpolation",
                              "affine", dir), 2);
    CHECK_EQ(run_explain_with("fillpoly", "--triangle", "1,1,9,1,1,9", "--interpolation",
                              "affine", dir), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "triangle", "--zoom", "3", "-o", dir,
                                               NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "triangle", "-o", "a%s%d", NULL }), 2);
    /* an empty name: -o "" wrote the frames to /frame-001.png ..., and
     * --sheet "" failed as a run (exit 1) */
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "triangle", "-o", "", NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "triangle", "--sheet", "", NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "triangle", "--webp", "", NULL }), 2);
    /* transform: no camera frame, a vertex before the near plane, values
     * out of range */
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "transform", "--eye", "0.5,0,0",
                                               "-o", dir, NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "transform", "--up", "0,0,1", "--eye",
                                               "0.5,0,3", "-o", dir, NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "transform", "--near-far", "3,10",
                                               "-o", dir, NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "transform", "--near-far", "2,1",
                                               "-o", dir, NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "transform", "--fov", "0", "-o", dir,
                                               NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "transform", "--aspect", "wide", "-o",
                                               dir, NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "transform", "--object",
                                               "1,2,3,4,5,6,7,8", "-o", dir, NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "transform", "--triangle",
                                               "1,1,9,1,1,9", "-o", dir, NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "zfight", "--offset", "-1,-100", "-o",
                                               dir, NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "gouraud", "--shininess", "0", "-o",
                                               dir, NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "gouraud", "--highlight", "1", "-o",
                                               dir, NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "area", "--cap", "flat", "-o", dir,
                                               NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "area", "--width", "0", "-o", dir,
                                               NULL }), 2);
    static const char *const bad_widths[] = { "0", "-1", "64.5", "1px", "nan", "" };
    for (size_t i = 0; i < sizeof bad_widths / sizeof bad_widths[0]; i++) {
        CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "aaline", "--width", bad_widths[i],
                                                   "-o", dir, NULL }), 2);
    }
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "--help", NULL }), 0);
}

static int remove_entry(const char *path, const struct stat *st, int type, struct FTW *ftw)
{
    (void)st, (void)type, (void)ftw;
    return remove(path);
}

/* docs/explain.md's `-o steps/line-%02d.png` in a fresh directory: a
 * pattern's directories are made like -o DIR's, nested ones too. */
SR_TEST(output_directories_are_made_for_a_pattern_and_a_dir)
{
    NEEDS_CLI();
    char base[1024], pattern[1200], dir[1200], first[1300];
    snprintf(base, sizeof base, "%s/explain_mkdir", sr_test_out_dir());
    nftw(base, remove_entry, 16, FTW_DEPTH | FTW_PHYS);   /* an earlier run's */
    snprintf(pattern, sizeof pattern, "%s/steps/line-%%02d.png", base);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "bresenham", "--line",
                                               "1.5,2.5,13.5,7.5", "-o", pattern, NULL }), 0);
    snprintf(first, sizeof first, "%s/steps/line-01.png", base);
    CHECK(access(first, R_OK) == 0);
    snprintf(dir, sizeof dir, "%s/a/b", base);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "dda", "--output", dir, NULL }), 0);
    snprintf(first, sizeof first, "%s/a/b/frame-001.png", base);
    CHECK(access(first, R_OK) == 0);
}

/* A grid and zoom within their limits whose sheet is over the framebuffer's
 * 8192 a side: refused as bad usage before anything is written, not a
 * failed run that leaves the frames of -o behind. */
SR_TEST(sheet_too_large_is_refused_before_any_file)
{
    NEEDS_CLI();
    char dir[1024], frames[1200], sheet[1200];
    snprintf(dir, sizeof dir, "%s/explain_big_sheet", sr_test_out_dir());
    nftw(dir, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
    REQUIRE(mkdir(dir, 0777) == 0);
    snprintf(frames, sizeof frames, "%s/frames", dir);
    snprintf(sheet, sizeof sheet, "%s/sheet.png", dir);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "triangle", "--grid", "256x64",
                                               "--zoom", "16", "-o", frames, "--sheet", sheet,
                                               NULL }), 2);
    CHECK(access(frames, F_OK) != 0);
    CHECK(access(sheet, F_OK) != 0);
}

/* A --sheet (or --webp) that names a frame of -o, by any spelling, or
 * names the other, is refused before anything is written: the sheet
 * replaced frame 2 of the same run. */
SR_TEST(sheet_over_a_frame_of_the_same_run_is_refused)
{
    NEEDS_CLI();
    char dir[1024], frames[1200], first[1300], sheet[1300];
    snprintf(dir, sizeof dir, "%s/explain_sheet_frame", sr_test_out_dir());
    nftw(dir, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
    REQUIRE(mkdir(dir, 0777) == 0);
    snprintf(frames, sizeof frames, "%s/frames", dir);
    snprintf(first, sizeof first, "%s/frame-001.png", frames);
    const char *sheets[] = { "%s/frames/frame-002.png", "%s//frames//frame-003.png" };
    for (int k = 0; k < 2; k++) {
        snprintf(sheet, sizeof sheet, sheets[k], dir);
        CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "dda", "-o", frames, "--sheet",
                                                   sheet, NULL }), 2);
        CHECK(access(frames, F_OK) != 0);
        /* the frames there already (an earlier run's) */
        CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "dda", "-o", frames, NULL }), 0);
        CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "dda", "-o", frames, "--sheet",
                                                   sheet, NULL }), 2);
        int w = 0, h = 0;
        uint8_t *px = NULL;
        CHECK(sr_read_png(sheet, NULL, &w, &h, &px, NULL) == SR_OK);
        int fw = 0, fh = 0;
        uint8_t *fpx = NULL;
        CHECK(sr_read_png(first, NULL, &fw, &fh, &fpx, NULL) == SR_OK);
        CHECK(w == fw && h == fh);   /* still a frame, not a sheet */
        free(px);
        free(fpx);
        nftw(frames, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
    }
    snprintf(sheet, sizeof sheet, "%s/pattern-%%d.png", dir);
    snprintf(first, sizeof first, "%s/./pattern-4.png", dir);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "dda", "-o", sheet, "--sheet", first,
                                               NULL }), 2);
    CHECK(access(first, F_OK) != 0);
    snprintf(sheet, sizeof sheet, "%s/sheet.png", dir);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "dda", "-o", frames, "--sheet", sheet,
                                               NULL }), 0);
    CHECK(access(first, F_OK) != 0);
}

/* clip4d's first frame divides a w <= 0 vertex without clipping, which
 * lands below the grid: its red edges and its label stop above the
 * caption band (16 + 12 x 16 + 16 - 8 = 216 frame pixels down) instead
 * of crossing the words. */
SR_TEST(clip4d_first_frame_keeps_the_caption_clear)
{
    NEEDS_CLI();
    char dir[1024], first[1200];
    out_dir("clip4d_caption", dir, sizeof dir);
    REQUIRE(sr_test_run_cli((const char *[]){ "explain", "clip4d", "--grid", "16x12", "--zoom",
                                              "16", "-o", dir, NULL }) == 0);
    snprintf(first, sizeof first, "%s/frame-001.png", dir);
    int w, h;
    uint8_t *px = NULL;
    REQUIRE(sr_read_png(first, NULL, &w, &h, &px, NULL) == SR_OK);
    int red_above = 0, red_in_band = 0;
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const uint8_t *p = px + ((size_t)y * w + x) * 4;
            bool red = p[0] > 150 && p[1] < 90 && p[2] < 90;
            red_above += red && y < 216;
            red_in_band += red && y >= 216;
        }
    }
    CHECK(red_above > 0);   /* the naive divide is drawn */
    CHECK_EQ(red_in_band, 0);
    free(px);
}

SR_TEST(webp_is_an_animation_of_every_frame)
{
    NEEDS_CLI();
    char dir[1024], path[1200];
    out_dir("webp", dir, sizeof dir);
    snprintf(path, sizeof path, "%s/circle.webp", dir);
    remove(path);
    int rc = sr_test_run_cli((const char *[]){ "explain", "circle", "--webp", path, NULL });
    if (rc == 2) {
        SKIP("this build has no libwebp");
    }
    REQUIRE(rc == 0);
    /* a WebP under another name (a viewer would take out.png for a PNG) is
     * refused, as render --animate refuses it */
    char png[1200];
    snprintf(png, sizeof png, "%s/circle.png", dir);
    remove(png);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "circle", "--webp", png, NULL }), 2);
    CHECK(access(png, F_OK) != 0);
    FILE *f = fopen(path, "rb");
    REQUIRE(f != NULL);
    static uint8_t buf[1 << 20];
    size_t n = fread(buf, 1, sizeof buf, f);
    fclose(f);
    REQUIRE(n > 64);
    CHECK(memcmp(buf, "RIFF", 4) == 0 && memcmp(buf + 8, "WEBP", 4) == 0);
    /* one ANMF chunk per frame: the example circle has 13 */
    int frames = 0;
    for (size_t i = 12; i + 4 <= n; i++) {
        frames += memcmp(buf + i, "ANMF", 4) == 0;
    }
    CHECK_EQ(frames, 13);
}

SR_TEST(sheet_holds_every_frame)
{
    NEEDS_CLI();
    char dir[1024], sheet[1200];
    out_dir("sheet", dir, sizeof dir);
    snprintf(sheet, sizeof sheet, "%s/sheet.png", dir);
    REQUIRE(sr_test_run_cli((const char *[]){ "explain", "triangle", "-o", dir, "--sheet", sheet,
                                              NULL }) == 0);
    int fw, fh, sw, sh;
    uint8_t *f = NULL, *s = NULL;
    char first[1200];
    snprintf(first, sizeof first, "%s/frame-001.png", dir);
    REQUIRE(sr_read_png(first, NULL, &fw, &fh, &f, NULL) == SR_OK);
    REQUIRE(sr_read_png(sheet, NULL, &sw, &sh, &s, NULL) == SR_OK);
    uint8_t cells[GRID * GRID];
    int frames = last_frame_cells(dir, cells);
    CHECK(frames >= 5);
    /* three frames to a row; the first frame at (8, 8), byte for byte */
    CHECK(sw > 3 * fw && sh > ((frames + 2) / 3) * fh);
    int diff = 0;
    for (int y = 0; y < fh && sw > fw + 8 && sh > fh + 8; y++) {
        diff += memcmp(s + ((size_t)(y + 8) * sw + 8) * 4, f + (size_t)y * fw * 4,
                       (size_t)fw * 4) != 0;
    }
    CHECK_EQ(diff, 0);
    free(f);
    free(s);
}

/* Primitives far off the grid (coordinates reach 16384 pixels, times a
 * zoom of up to 64 in frame pixels) are drawn, cut to the frame, instead
 * of failing in the 2D filler beyond its range. */
SR_TEST(primitives_far_off_the_grid_are_drawn)
{
    NEEDS_CLI();
    static const char *const runs[][3] = {
        { "triangle", "--triangle", "-16000,-16000,16000,0,0,16000" },
        { "msaa", "--triangle", "-16000,-16000,16000,0,0,16000" },
        { "perspective", "--triangle", "-16000,-16000,16000,0,0,16000" },
        { "fillpoly", "--triangle", "-16000,-16000,16000,0,0,16000" },
        { "zbuffer", "--triangles",
          "-16000,-16000,0.5,16000,0,0.5,0,16000,0.5,-16000,-16000,0.4,16000,0,0.4,0,16000,0.6" },
        { "scanline", "--polygon", "-16000,-16000,16000,0,0,16000" },
        { "clip", "--polygon", "-16000,-16000,16000,0,0,16000" },
        { "floodfill", "--polygon", "-16000,-16000,16000,0,0,16000" },
        { "circle", "--circle", "4,4,4096" },
        { "forward-differencing", "--cubic", "-16000,0,16000,0,-16000,8,16000,8" },
        { "bresenham", "--line", "-300.5,0.5,300.5,1.5" },
        { "dda", "--line", "-300,0.5,300,1.5" },
    };
    for (size_t i = 0; i < sizeof runs / sizeof runs[0]; i++) {
        char dir[1024];
        out_dir("far", dir, sizeof dir);
        bool cubic = strcmp(runs[i][0], "forward-differencing") == 0;
        int rc = sr_test_run_cli((const char *[]){ "explain", runs[i][0], runs[i][1], runs[i][2],
                                                   "--grid", "8x8", "--zoom", "64", "-o", dir,
                                                   cubic ? "--tolerance" : NULL, "100", NULL });
        if (rc != 0) {
            FAILF("explain %s %s %s at zoom 64: exit %d", runs[i][0], runs[i][1], runs[i][2], rc);
        }
    }
}

/* docs/explain.md's forward-differencing example: frame 1's caption
 * (the set-up of d1, d2 and d3) takes ten lines at the default view and
 * ends with d3's value on the tenth, which a canvas with room for nine
 * cut off.  The grid is 12 x 32 frame pixels under a 16-pixel margin, the
 * caption starts 16 below it, a line every 20 frame pixels (text scale 2,
 * 7 pixels tall at 2x). */
SR_TEST(long_captions_are_not_cut_off)
{
    NEEDS_CLI();
    char dir[1024], first[1200];
    out_dir("caption", dir, sizeof dir);
    REQUIRE(sr_test_run_cli((const char *[]){ "explain", "forward-differencing", "-o", dir,
                                              NULL }) == 0);
    snprintf(first, sizeof first, "%s/frame-001.png", dir);
    int w, h;
    uint8_t *px = NULL;
    REQUIRE(sr_read_png(first, NULL, &w, &h, &px, NULL) == SR_OK);
    int top = MARGIN + 12 * 32 + MARGIN + 9 * 20, text = 0;
    for (int y = top; y < top + 14 && y < h; y++) {
        for (int x = 0; x < w; x++) {
            const uint8_t *p = px + ((size_t)y * w + x) * 4;
            text += p[0] < 60 && p[1] < 60 && p[2] < 60;
        }
    }
    CHECK(text > 20);   /* the tenth line is drawn */
    CHECK(h >= top + 14 + MARGIN);
    free(px);
}

/* An option the algorithm does not take is refused, not ignored: a
 * student's `explain triangle --samples 8` drew one sample per pixel
 * without a word. */
SR_TEST(options_of_another_algorithm_are_refused)
{
    NEEDS_CLI();
    char dir[1024];
    out_dir("not_mine", dir, sizeof dir);
    static const char *const runs[][3] = {
        { "triangle", "--samples", "8" },       { "msaa", "--fill-rule", "nonzero" },
        { "floodfill", "--fill-rule", "nonzero" }, { "scanline", "--window", "1,1,5,5" },
        { "triangle", "--row", "3" },           { "dda", "--tolerance", "0.5" },
        { "scanline", "--seed", "3,3" },        { "clip", "--connectivity", "8" },
        { "msaa", "--w", "1,2,3" },             { "perspective", "--intensity", "0,1,0" },
        { "triangle", "--eye", "1,2,3" },       { "clip4d", "--projection", "orthographic" },
        { "perspective", "--highlight", "3,3" }, { "transform", "--shininess", "8" },
        { "zbuffer", "--offset", "-1,-1" },     { "wu", "--width", "2" },
        { "aaline", "--cap", "round" },
    };
    for (size_t i = 0; i < sizeof runs / sizeof runs[0]; i++) {
        int rc = sr_test_run_cli((const char *[]){ "explain", runs[i][0], runs[i][1], runs[i][2],
                                                   "-o", dir, NULL });
        if (rc != 2) {
            FAILF("explain %s %s %s: exit %d, not 2", runs[i][0], runs[i][1], runs[i][2], rc);
        }
    }
    /* and the owners take them */
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "clip", "--fill-rule", "nonzero",
                                               "--window", "2,2,12,9", "-o", dir, NULL }), 0);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "floodfill", "--seed", "3,3",
                                               "--connectivity", "8", "-o", dir, NULL }), 0);
}

/* scanline's edge table frame names each edge in pink.  At the edge's
 * first crossing the name sat on the name of the vertex the edge starts
 * at (the example's e0 and e5 over V0, e1 and e2 over V2, e4 over V5);
 * the vertex names' boxes are now free of pink.  The example's view:
 * zoom 32, text at twice the font's size, a label 5 frame pixels right
 * of its point and 19 above. */
SR_TEST(scanline_edge_names_leave_the_vertex_names_readable)
{
    NEEDS_CLI();
    char dir[1024], path[1200];
    out_dir("scanline_labels", dir, sizeof dir);
    REQUIRE(sr_test_run_cli((const char *[]){ "explain", "scanline", "-o", dir, NULL }) == 0);
    snprintf(path, sizeof path, "%s/frame-002.png", dir);
    int w, h;
    uint8_t *px = NULL;
    REQUIRE(sr_read_png(path, NULL, &w, &h, &px, NULL) == SR_OK);
    static const double vertices[][2] = { { 1.3, 1.4 }, { 13.7, 1.4 }, { 1.3, 6.5 } };
    for (int v = 0; v < 3; v++) {
        int x0 = (int)(MARGIN + vertices[v][0] * 32) + 5;
        int y0 = (int)(MARGIN + vertices[v][1] * 32) - 19;
        int pink = 0;
        for (int y = y0; y < y0 + 14; y++) {
            for (int x = x0; x < x0 + 24 && x < w; x++) {
                const uint8_t *p = px + ((size_t)y * w + x) * 4;
                pink += p[0] > 180 && p[1] < 140 && p[2] > 90 && p[2] < 200;
            }
        }
        if (pink) {
            FAILF("vertex %d's name has %d pink pixels over it", v, pink);
        }
    }
    free(px);
}

/* A zero-length line's ends get one name, "A=B": "A" and "B" were drawn
 * over each other.  bresenham's view: zoom 32, text at twice the font's
 * size (12 frame pixels a character), a label 5 right of its point and
 * 19 above; the "B" of "A=B" is the third character. */
SR_TEST(line_ends_on_one_point_share_a_name)
{
    NEEDS_CLI();
    char dir[1024], path[1200];
    out_dir("zero_line", dir, sizeof dir);
    REQUIRE(sr_test_run_cli((const char *[]){ "explain", "bresenham", "--line", "1.5,1.5,1.5,1.5",
                                              "-o", dir, NULL }) == 0);
    snprintf(path, sizeof path, "%s/frame-001.png", dir);
    int w, h;
    uint8_t *px = NULL;
    REQUIRE(sr_read_png(path, NULL, &w, &h, &px, NULL) == SR_OK);
    int x0 = MARGIN + 48 + 5 + 24, y0 = MARGIN + 48 - 19, dark = 0;
    for (int y = y0; y < y0 + 14; y++) {
        for (int x = x0; x < x0 + 10; x++) {
            const uint8_t *p = px + ((size_t)y * w + x) * 4;
            dark += p[0] < 80 && p[1] < 80 && p[2] < 80;
        }
    }
    CHECK(dark > 10);
    free(px);
}

/* Two labels at one point (a polygon with a repeated vertex) are drawn
 * one under the other instead of over each other.  scanline's view at
 * zoom 32, text at twice the font's size: V1 = V2 = (9, 1) puts V1's
 * name at (16 + 288 + 5, 16 + 32 - 19) and V2's, 7 x 2 + 4 below it. */
SR_TEST(labels_at_one_point_are_stacked)
{
    NEEDS_CLI();
    char dir[1024], path[1200];
    out_dir("stacked_labels", dir, sizeof dir);
    REQUIRE(sr_test_run_cli((const char *[]){ "explain", "scanline", "--polygon",
                                              "1,1,9,1,9,1,9,9,1,9", "-o", dir, NULL }) == 0);
    snprintf(path, sizeof path, "%s/frame-001.png", dir);
    int w, h;
    uint8_t *px = NULL;
    REQUIRE(sr_read_png(path, NULL, &w, &h, &px, NULL) == SR_OK);
    int x0 = MARGIN + 288 + 5, y0 = MARGIN + 32 - 19 + 14 + 4, dark = 0;
    for (int y = y0; y < y0 + 14; y++) {
        for (int x = x0; x < x0 + 24; x++) {
            const uint8_t *p = px + ((size_t)y * w + x) * 4;
            dark += p[0] < 80 && p[1] < 80 && p[2] < 80;
        }
    }
    CHECK(dark > 10);   /* V2's name, below V1's */
    free(px);
}

/* Whether the caption of the frame at `path` reads `text`: the text drawn
 * as the canvas draws it (from x = 16, at caption_y = 16 + grid_h x zoom
 * + 16, a line every 10 x scale pixels, wrapped at the last space that
 * fits the frame's width) and compared with the frame, dark pixel for
 * dark pixel, over the caption band. */
static bool caption_reads(const char *path, int grid_h, int zoom, int scale, const char *text)
{
    int w, h;
    uint8_t *px = NULL;
    if (sr_read_png(path, NULL, &w, &h, &px, NULL) != SR_OK) {
        return false;
    }
    rt_target t = rt_make(w, h, 1);
    sr_clear(t.ctx, t.fb, &(sr_clear_desc){ .color = { 1, 1, 1, 1 } });
    int top = MARGIN + grid_h * zoom + MARGIN, max_chars = (w - 2 * MARGIN) / (6 * scale);
    const char *p = text;
    for (int line = 0; *p; line++) {
        int n = 0, cut = -1;
        while (p[n] && n < max_chars) {
            cut = p[n] == ' ' ? n : cut;
            n++;
        }
        if (p[n] && p[n] != ' ' && cut > 0) {
            n = cut;
        }
        char buf[256];
        snprintf(buf, sizeof buf, "%.*s", n, p);
        sr_draw_text(t.ctx, t.fb, MARGIN, top + line * 10 * scale, scale, buf,
                     (sr_rgba){ 0, 0, 0, 1 });
        p += n;
        while (*p == ' ') {
            p++;
        }
    }
    const uint8_t *want = sr_framebuffer_pixels(t.fb);
    int diff = 0;
    for (size_t i = (size_t)(top - 4) * w; i < (size_t)w * h; i++) {
        bool a = px[i * 4] < 80 && px[i * 4 + 1] < 80 && px[i * 4 + 2] < 80;
        diff += a != (want[i * 4] < 80);
    }
    rt_free(&t);
    free(px);
    return diff == 0;
}

/* Run `softrast explain` with args (NULL-terminated, at most 12) and
 * -o a fresh directory named `name`, then check that the caption of
 * frame `frame` reads `text` at the algorithm's default view (zoom 32,
 * text at twice the font's size, `grid_h` rows). */
static void expect_caption(const char *name, const char *const *args, int frame, int grid_h,
                           const char *text)
{
    char dir[1024], path[1200];
    out_dir(name, dir, sizeof dir);
    const char *argv[16] = { "explain" };
    int n = 1;
    while (args[n - 1] && n < 13) {
        argv[n] = args[n - 1];
        n++;
    }
    argv[n++] = "-o";
    argv[n++] = dir;
    argv[n] = NULL;
    if (sr_test_run_cli(argv) != 0) {
        FAILF("%s: explain %s failed", name, args[0]);
        return;
    }
    snprintf(path, sizeof path, "%s/frame-%03d.png", dir, frame);
    if (!caption_reads(path, grid_h, 32, 2, text)) {
        FAILF("%s: frame %d's caption does not read \"%s\"", name, frame, text);
    }
}

/* clip4d's last caption said "all w > 0" of a polygon whose vertices
 * all have w = 0 (a triangle at the eye, which near and far keep), and
 * "1 triangles". */
SR_TEST(clip4d_last_caption_says_w_may_be_zero_at_the_eye)
{
    NEEDS_CLI();
    expect_caption("clip4d_eye",
                   (const char *[]){ "clip4d", "--clip-triangle", "0,0,0,0,0,0,0,0,0,0,0,0",
                                     NULL },
                   8, 12,
                   "8. The clipped polygon (3 vertices, all w >= 0; w = 0 only at the eye, "
                   "where nothing is covered) divided by w, mapped onto the grid and fanned "
                   "into 1 triangle, each covered by its edge functions with the top-left "
                   "rule: 0 pixels, what sr_draw draws for the triangle (which clips only "
                   "near, far and w > 0 in clip space and trims x and y exactly to the "
                   "viewport as it rasterizes).");
}

/* bresenham's tie read "d = 0 = 0 (M on the line: ...)": the example's
 * step 7 (its view: 16 x 10 at zoom 32); step 2 for the other form. */
SR_TEST(bresenham_tie_caption_reads_once)
{
    NEEDS_CLI();
    const char *const args[] = { "bresenham", NULL };
    expect_caption("bresenham_tie", args, 7, 10,
                   "7. Plot (6, 4). d = 0 (M on the line: the smaller index): step E, "
                   "d + 10 = 10.");
    expect_caption("bresenham_less", args, 2, 10,
                   "2. Plot (1, 2). d = -2 < 0: step E, d + 10 = 8.");
}

/* aaline's last frame against sr_draw's smooth line of line_width (as
 * --width gives it), the fill blue over white: each cell within one 8-bit
 * step of its pixel, every pixel sr_draw leaves white an empty cell.
 * Random lines with ends at 1/8 px inside the grid (sr_draw clips a line
 * that leaves the framebuffer, which moves its snapped end).  The pixels
 * drawn are added to *drawn. */
static void check_aaline_last_frames(uint32_t seed, const char *width, int *drawn)
{
    sr_rng rng = { seed };
    rt_target t = rt_make(GRID, GRID, 1);
    for (int k = 0; k < 16; k++) {
        double v[4];
        for (int i = 0; i < 4; i++) {
            v[i] = sr_rng_int(&rng, 4, (GRID - 1) * 8 + 4) / 8.0;
        }
        char prim[128], dir[1024], name[40];
        snprintf(prim, sizeof prim, "%g,%g,%g,%g", v[0], v[1], v[2], v[3]);
        snprintf(name, sizeof name, "aaline_w%s_%02d", width, k);
        out_dir(name, dir, sizeof dir);
        REQUIRE(run_explain_with("aaline", "--line", prim, "--width", width, dir) == 0);
        uint8_t cells[GRID * GRID], rgb[GRID * GRID * 3];
        int last = last_frame_cells(dir, cells);
        REQUIRE(last >= 2);
        REQUIRE(frame_cell_colours(dir, last, rgb));
        sr_clear(t.ctx, t.fb, &(sr_clear_desc){ .color = { 1, 1, 1, 1 } });
        float pos[6] = { rt_ndc_x(&t, v[0]), rt_ndc_y(&t, v[1]), 0,
                         rt_ndc_x(&t, v[2]), rt_ndc_y(&t, v[3]), 0 };
        sr_state st = { .shading = SR_SHADING_UNLIT, .smooth_lines = true,
                        .line_width = strtof(width, NULL),
                        .material = { .diffuse = { 0.20f, 0.45f, 0.85f } } };
        REQUIRE(sr_draw(t.ctx, t.fb, &st, &(sr_draw_desc){ .primitive = SR_PRIM_LINES,
                                                           .positions = pos,
                                                           .vertex_count = 2 }) == SR_OK);
        const uint8_t *px = sr_framebuffer_pixels(t.fb);
        int diff = 0;
        for (int i = 0; i < GRID * GRID; i++) {
            for (int ch = 0; ch < 3; ch++) {
                diff += abs(px[4 * i + ch] - rgb[3 * i + ch]) > 1;
            }
            *drawn += px[4 * i] != 255;
        }
        if (diff) {
            FAILF("aaline --line %s --width %s: %d channels differ", prim, width, diff);
        }
    }
    rt_free(&t);
}

SR_TEST(aaline_last_frame_is_what_sr_draw_draws)
{
    NEEDS_CLI();
    int drawn = 0;
    check_aaline_last_frames(0xaa11u, "1", &drawn);
    CHECK(drawn > 200);
}

/* --width: the explained line is sr_draw's of that width, thinner than a
 * pixel, wider, and of a width whose edges fall between pixel centres;
 * the same lines at each width. */
SR_TEST(aaline_width_is_sr_draws_line_width)
{
    NEEDS_CLI();
    static const char *const widths[] = { "0.5", "2.5", "3.3", "6" };
    int drawn[4] = { 0 };
    for (int i = 0; i < 4; i++) {
        check_aaline_last_frames(0xaa12u, widths[i], &drawn[i]);
    }
    /* a wider line covers more: the width reached the walk */
    CHECK(drawn[0] > 100);
    for (int i = 1; i < 4; i++) {
        CHECK(drawn[i] > drawn[i - 1]);
    }
}

/* area's row frames give each pixel's area as A(x + 1) - A(x): the
 * example's row y = 3. */
SR_TEST(area_caption_gives_each_pixels_area)
{
    NEEDS_CLI();
    expect_caption("area_row", (const char *[]){ "area", NULL }, 4, 10,
                   "4. Row y = 3: the rectangle cut to the strip 3 <= y <= 4 (pink), A(x) its "
                   "area left of x; 6 pixels, each covering A(x + 1) - A(x) of its square. "
                   "x = 1: 0.063 - 0.000 = 0.063; x = 2: 0.497 - 0.063 = 0.434; x = 3: 1.338 - "
                   "0.497 = 0.841; x = 4: 2.163 - 1.338 = 0.825; x = 5: 2.578 - 2.163 = 0.415; "
                   "x = 6: 2.631 - 2.578 = 0.053.");
    /* the areas sum to the rectangle's: none of it is off the grid */
    expect_caption("area_sum", (const char *[]){ "area", NULL }, 10, 10,
                   "10. The areas: the fraction of each pixel's square the rectangle covers, 35 "
                   "pixels, exactly (the notes' count of a finer grid's subpixels inside only "
                   "approximates them). Unweighted: equal areas give equal intensities wherever "
                   "they lie in the pixel. They sum to 13.946 px^2, the rectangle's area w |AB| "
                   "= 13.946.");
}

/* The example's first end: the gap and the two weights it scales. */
SR_TEST(wu_first_end_caption_gives_the_gap_and_weights)
{
    NEEDS_CLI();
    expect_caption("wu_first_end", (const char *[]){ "wu", NULL }, 2, 10,
                   "2. First end, column x = 1: the line covers 0.7000 of the column (the "
                   "gap), so both weights are scaled by it. At the centre x = 1.5 the line is "
                   "at y = 2.4822. It lies between the centres y = 1.5 and 2.5, f = 0.9822 "
                   "past the first: (1, 1) gets gap x (1 - f) = 0.0125, (1, 2) gets gap x f "
                   "= 0.6875.");
    expect_caption("wu_row", (const char *[]){ "wu", "--line", "3.7,0.2,8.1,9.6", NULL }, 5, 10,
                   "5. Row y = 3: intersection x = 5.2447 at the centre y = 3.5 (the previous "
                   "one + gradient 0.4681). It lies between the centres x = 4.5 and 5.5, f = "
                   "0.7447 past the first: (4, 3) gets (1 - f) = 0.2553, (5, 3) gets f = "
                   "0.7447.");
}

/* aaline's distances and coverages, in the example's column x = 5. */
SR_TEST(aaline_caption_gives_distances_and_coverage)
{
    NEEDS_CLI();
    expect_caption("aaline_column", (const char *[]){ "aaline", NULL }, 7, 10,
                   "7. Column x = 5: 2 pixels within the reach 1, coverage = reach - d. y = 3: "
                   "d = 0.577, coverage 0.423; y = 4: d = 0.348, coverage 0.652.");
}

/* A column of a line wider than its caption can list: the caption ended
 * mid-list without a word; it now says how many pixels it leaves out.  A
 * horizontal line 30 wide through row 12, column x = 5: rows 0 to 24 at
 * d = |y - 12|, each listed while the caption has room. */
SR_TEST(aaline_wide_column_caption_counts_what_it_leaves_out)
{
    NEEDS_CLI();
    char text[1000];
    int len = snprintf(text, sizeof text, "7. Column x = 5: 25 pixels within the reach 15.5, "
                       "coverage = reach - d. ");
    int y = 0;
    for (; y < 25 && len < 900 - 80; y++) {
        double d = abs(y - 12);
        len += snprintf(text + len, sizeof text - (size_t)len,
                        "y = %d: d = %.3f, coverage %.3f -> 1%s", y, d, 15.5 - d,
                        y < 24 ? "; " : ".");
    }
    REQUIRE(y < 25);
    snprintf(text + len, sizeof text - (size_t)len, "and %d more.", 25 - y);
    expect_caption("aaline_wide", (const char *[]){ "aaline", "--line", "0.5,12.5,10.5,12.5",
                                                    "--width", "30", "--grid", "16x25", NULL },
                   7, 25, text);
}

/* perspective's frame 3 compares the two interpolations along the span;
 * it said "steps unevenly: at x = 0 it is 0.000, 0.000 affine" for a
 * --row that misses the triangle, and "unevenly" when every w is equal
 * (the default for a triangle given without --w). */
SR_TEST(perspective_caption_fits_the_span)
{
    NEEDS_CLI();
    expect_caption("persp_row", (const char *[]){ "perspective", "--row", "12", NULL }, 3, 13,
                   "3. Perspective-correct: the weights of the 3D point are li / wi, "
                   "normalized (interpolate colour/w and 1/w on the screen, divide per "
                   "pixel). Scanline 12 covers no pixel of the triangle: nothing to compare "
                   "(give --row 2 to 10).");
    expect_caption("persp_equal_w",
                   (const char *[]){ "perspective", "--triangle", "1.5,1.5,14.5,4.5,2.5,11.5",
                                     "--row", "5", NULL },
                   3, 13,
                   "3. Perspective-correct: the weights of the 3D point are li / wi, "
                   "normalized (interpolate colour/w and 1/w on the screen, divide per "
                   "pixel). With every w equal the two agree: at x = 2 both are 0.047. "
                   "Perspective matters only when the vertices' w differ (--w).");
}

/* fillpoly on three vertices in one row: every edge is horizontal, and
 * the first caption printed AC's increments as "inf" and "-inf". */
SR_TEST(fillpoly_flat_triangle_has_no_increments)
{
    NEEDS_CLI();
    expect_caption("fillpoly_flat", (const char *[]){ "fillpoly", "--triangle", "1,5,14,5,7,5",
                                                      NULL },
                   1, 12,
                   "1. FillPoly: A, B, C sorted by y, an intensity I at each. Per scanline "
                   "along each edge: dX_AC = -, dI_AC = -; dX_AB = -, dI_AB = -; dX_BC = -, "
                   "dI_BC = - (1/m and dI/dy; a horizontal edge crosses no scanline). Above "
                   "B, AC runs beside AB; below B, beside BC.");
}

/* forward-differencing on a straight, evenly traced cubic (|B''| = 0):
 * the caption claimed ceil(sqrt(0.00 / (8 x 0.25))) = 1 and spoke of
 * "1 steps" and "The 1 chords". */
SR_TEST(fwdiff_straight_cubic_takes_one_step)
{
    NEEDS_CLI();
    const char *const args[] = { "forward-differencing", "--cubic", "1,1,5,4,9,7,13,10", NULL };
    expect_caption("fwdiff_straight", args, 1, 12,
                   "1. A cubic Bezier (pink; grey: its control polygon) as a polynomial "
                   "B(t) = a t^3 + b t^2 + c t + P0: a = (0.00, 0.00), b = (0.00, 0.00), "
                   "c = (12.00, 9.00). |B''| = 0: a straight segment, traced at an even "
                   "pace, so one chord is exact: n = 1 step of h = 1/1. Start: d1 = a h^3 "
                   "+ b h^2 + c h = (12.000, 9.000), d2 = 6 a h^3 + 2 b h^2 = (0.000, "
                   "0.000), d3 = 6 a h^3 = (0.0000, 0.0000).");
    expect_caption("fwdiff_straight_chord", args, 3, 12,
                   "3. The 1 chord drawn as lines (sr_draw_line, each leaving out its end "
                   "pixel so they join without doubling): what sr_flatten_cubic's points "
                   "give at 1x.");
}

/* The numbers in zbuffer's cells stay whole: a failed test's cross keeps
 * above its q, and the vertices' labels keep off the rows of numbers
 * under them.  Every cell holds q = 32768 here (both triangles at z 0.5;
 * A covers the grid, B ties and fails everywhere), so each cell's text
 * band must hold exactly the pixels of "32768" in the text's colour:
 * red in frame 3, white in frame 4.  A cross, a label or its ground over
 * the band would add or take pixels of that colour. */
SR_TEST(zbuffer_numbers_are_not_covered_by_crosses_or_labels)
{
    NEEDS_CLI();
    enum { Z = 40, GW = 14, GH = 11, BAND = 10 };
    char dir[1024];
    out_dir("zbuffer_text", dir, sizeof dir);
    const char *args[] = { "explain", "zbuffer", "--grid", "14x11", "--zoom", "40", "--triangles",
                           "0,0,0.5,40,0,0.5,0,40,0.5,3,2,0.5,12,4.5,0.5,5,9.5,0.5", "-o", dir,
                           NULL };
    REQUIRE(sr_test_run_cli(args) == 0);

    /* "32768" as the explain canvas writes it: the font at scale 1 */
    const sr_rgba colours[2] = { { 0.85f, 0.15f, 0.10f, 1 }, { 1, 1, 1, 1 } };
    rt_target t = rt_make(40, 10, 1);
    uint8_t want[2][3];
    int glyph = 0;
    for (int k = 0; k < 2; k++) {
        sr_clear(t.ctx, t.fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
        REQUIRE(sr_draw_text(t.ctx, t.fb, 1, 1, 1, "32768", colours[k]) == SR_OK);
        const uint8_t *px = sr_framebuffer_pixels(t.fb);
        glyph = 0;
        for (int i = 0; i < 40 * 10; i++) {
            if (px[4 * i] || px[4 * i + 1] || px[4 * i + 2]) {
                memcpy(want[k], px + 4 * i, 3);
                glyph++;
            }
        }
    }
    rt_free(&t);
    REQUIRE(glyph > 20);

    for (int frame = 3; frame <= 4; frame++) {
        char path[1200];
        snprintf(path, sizeof path, "%s/frame-%03d.png", dir, frame);
        int w, h;
        uint8_t *px = NULL;
        REQUIRE(sr_read_png(path, NULL, &w, &h, &px, NULL) == SR_OK);
        const uint8_t *c = want[frame - 3];
        int whole = 0, bad = 0;
        for (int cy = 0; cy < GH; cy++) {
            for (int cx = 0; cx < GW; cx++) {
                int n = 0;
                for (int y = Z - BAND; y < Z; y++) {
                    for (int x = 1; x < Z; x++) {
                        const uint8_t *p =
                            px + ((size_t)(MARGIN + cy * Z + y) * w + MARGIN + cx * Z + x) * 4;
                        n += memcmp(p, c, 3) == 0;
                    }
                }
                /* frame 3 numbers only B's cells; frame 4 every cell */
                if (n == glyph) {
                    whole++;
                } else if (n != 0 || frame == 4) {
                    if (bad++ < 4) {
                        FAILF("frame %d, cell (%d, %d): %d pixels of the number's colour in its "
                              "text band, not %d", frame, cx, cy, n, glyph);
                    }
                }
            }
        }
        printf("frame %d: %d whole numbers, %d covered\n", frame, whole, bad);
        CHECK(whole >= (frame == 3 ? 20 : GW * GH));
        CHECK_EQ(bad, 0);
        free(px);
    }
}

/* floodfill's seeds are numbered at twice the font's size, in white on a
 * disc centred in the seed's cell: within the disc the first frame's one
 * seed, "1", has exactly the glyph's white pixels, centred. */
SR_TEST(floodfill_seed_numbers_are_large_and_centred)
{
    NEEDS_CLI();
    enum { Z = 32, SX = 7, SY = 4 };
    char dir[1024];
    out_dir("floodfill_seed", dir, sizeof dir);
    const char *args[] = { "explain", "floodfill", "--polygon", "1.5,1.5,13.5,1.5,7.5,10.5",
                           "--seed", "7,4", "--grid", "16x12", "--zoom", "32", "-o", dir, NULL };
    REQUIRE(sr_test_run_cli(args) == 0);
    rt_target t = rt_make(20, 20, 1);
    sr_clear(t.ctx, t.fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    REQUIRE(sr_draw_text(t.ctx, t.fb, 1, 1, 2, "1", (sr_rgba){ 1, 1, 1, 1 }) == SR_OK);
    int glyph = 0;
    for (int i = 0; i < 20 * 20; i++) {
        glyph += sr_framebuffer_pixels(t.fb)[4 * i] == 255;
    }
    rt_free(&t);

    char path[1200];
    snprintf(path, sizeof path, "%s/frame-001.png", dir);
    int w, h;
    uint8_t *px = NULL;
    REQUIRE(sr_read_png(path, NULL, &w, &h, &px, NULL) == SR_OK);
    int n = 0, x0 = Z, x1 = -1, y0 = Z, y1 = -1;
    for (int y = 1; y < Z; y++) {
        for (int x = 1; x < Z; x++) {
            const uint8_t *p = px + ((size_t)(MARGIN + SY * Z + y) * w + MARGIN + SX * Z + x) * 4;
            double dx = x + 0.5 - Z / 2.0, dy = y + 0.5 - Z / 2.0;
            /* within the disc (the cell around it is white too) */
            if (dx * dx + dy * dy < 11 * 11 && p[0] == 255 && p[1] == 255 && p[2] == 255) {
                n++;
                x0 = x < x0 ? x : x0, x1 = x > x1 ? x : x1;
                y0 = y < y0 ? y : y0, y1 = y > y1 ? y : y1;
            }
        }
    }
    free(px);
    CHECK_EQ(n, glyph);
    printf("seed 1: %d white pixels in x %d..%d, y %d..%d of the cell\n", n, x0, x1, y0, y1);
    CHECK(abs(x0 + x1 + 1 - Z) <= 2 && abs(y0 + y1 + 1 - Z) <= 2);
}

/* How many frames a run wrote into dir (frame-001.png, ...). */
static int frame_files(const char *dir)
{
    char path[1200];
    int n = 0;
    do {
        snprintf(path, sizeof path, "%s/frame-%03d.png", dir, ++n);
    } while (access(path, F_OK) == 0);
    return n - 1;
}

/* A line crossing the grid from ends far off it made one frame per step
 * (and gave up after 512 steps, so a line coming in from 2000 pixels away
 * showed none of its pixels): the steps off the grid are now one frame on
 * each side, and the last frame is still what sr_draw_line draws. */
static void check_far_line(const char *algorithm, sr_line_algorithm alg, const char *prim,
                           sr_point2 a, sr_point2 b)
{
    char dir[1024], name[40];
    snprintf(name, sizeof name, "%s_far", algorithm);
    out_dir(name, dir, sizeof dir);
    REQUIRE(run_explain(algorithm, "--line", prim, dir) == 0);
    /* the first frame, a run before the grid, GRID steps, a run after, the last */
    int frames = 1 + 1 + GRID + 1 + 1;
    CHECK_EQ(frame_files(dir), frames);
    uint8_t cells[GRID * GRID];
    REQUIRE(last_frame_cells(dir, cells) == frames);
    rt_target t = rt_make(GRID, GRID, 1);
    rt_clear(&t);
    REQUIRE(sr_draw_line(t.ctx, t.fb, a, b, (sr_rgba){ 1, 1, 1, 1 },
                         &(sr_line_desc){ .algorithm = alg }) == SR_OK);
    int drawn = 0;
    compare_with_target(&t, cells, name, &drawn);
    CHECK_EQ(drawn, GRID);
    rt_free(&t);
}

SR_TEST(line_steps_off_the_grid_are_one_frame)
{
    NEEDS_CLI();
    check_far_line("bresenham", SR_LINE_BRESENHAM, "-2000.5,3.5,2000.5,12.5",
                   (sr_point2){ -2000.5, 3.5 }, (sr_point2){ 2000.5, 12.5 });
    check_far_line("dda", SR_LINE_DDA_INCREMENTAL, "-2000.25,3.7,2000.5,12.1",
                   (sr_point2){ -2000.25, 3.7 }, (sr_point2){ 2000.5, 12.1 });
    /* the run's caption names its steps, pixels and the values at both
     * ends (what the frames of those steps said) */
    expect_caption("dda_far_caption",
                   (const char *[]){ "dda", "--line", "-2000.5,0.5,10.5,5.5", NULL }, 2, 10,
                   "2. Steps 1 to 2001: pixels (-2001, 0) to (-1, 5) off the grid, not shown "
                   "(y = 0.5000 first, y = 5.4727 last).");
}

/* The same for the circle's rows and the scan-line fill's scanlines: a
 * row whose pixels are all off the grid joins the off-grid rows beside it
 * in one frame (they made a frame each, empty). */
SR_TEST(rows_off_the_grid_are_one_frame)
{
    NEEDS_CLI();
    char dir[1024];
    out_dir("circle_far", dir, sizeof dir);
    REQUIRE(run_explain("circle", "--circle", "-300,5,250", dir) == 0);
    CHECK_EQ(frame_files(dir), 3);   /* the circle, rows 0 to 15, the outline */
    out_dir("scanline_far", dir, sizeof dir);
    REQUIRE(run_explain("scanline", "--polygon", "-300,0.5,6,5.5,-300,11.5,-600,6", dir) == 0);
    /* the polygon, the edge table, y=0..4, y=5, y=6..10, the fill */
    CHECK_EQ(frame_files(dir), 6);
    uint8_t cells[GRID * GRID], want[GRID * GRID] = { 0 };
    REQUIRE(last_frame_cells(dir, cells) == 6);
    for (int x = 0; x < 6; x++) {
        want[5 * GRID + x] = 1;
    }
    compare_cells(cells, want, "scanline far");
    expect_caption("scanline_far_caption",
                   (const char *[]){ "scanline", "--polygon", "-300,0.5,6,5.5,-300,11.5,-600,6",
                                     NULL },
                   5, 12,
                   "5. Scanlines y=6 to 10: their crossings and spans are off the grid, not "
                   "shown. From the ET: e2. Ended: e3.");
}

/* The example of `algorithm` on one sheet at `zoom`, against
 * tests/ref/explain_ALGORITHM.png: text and antialiased marks, so 2
 * levels a channel and 1 pixel in 200 may differ (a diff image is
 * written when more do). */
static void check_example_sheet(const char *algorithm, const char *zoom)
{
    char dir[1024], path[1200], name[64];
    snprintf(name, sizeof name, "%s_sheet", algorithm);
    out_dir(name, dir, sizeof dir);
    snprintf(path, sizeof path, "%s/sheet.png", dir);
    REQUIRE(sr_test_run_cli((const char *[]){ "explain", algorithm, "--zoom", zoom, "--sheet",
                                              path, NULL }) == 0);
    int w, h;
    uint8_t *px = NULL;
    REQUIRE(sr_read_png(path, NULL, &w, &h, &px, NULL) == SR_OK);
    snprintf(name, sizeof name, "explain_%s", algorithm);
    sr_test_check_image(name, px, w, h, 2, (long)w * h / 200);
    free(px);
}

/* ---- transform: the viewing pipeline S P E M_O ---- */

typedef struct tr_case {
    double obj[9], rotate, translate[3], eye[3], target[3], fov;
    bool ortho, stretch;
} tr_case;

static sr_vec3 tr_vec(const double v[3])
{
    return sr_vec3_make((float)v[0], (float)v[1], (float)v[2]);
}

/* The case's M_O, E and P from the library's functions, for a gw x gh
 * viewport (near 1, far 10, explain's defaults). */
static void tr_matrices(const tr_case *k, int gw, int gh, sr_mat4 *model, sr_mat4 *view,
                        sr_mat4 *proj)
{
    const double pi = 3.14159265358979323846;
    sr_mat4 r = sr_mat4_rotate((float)(k->rotate * pi / 180), sr_vec3_make(0, 1, 0));
    sr_mat4 t = sr_mat4_translate((float)k->translate[0], (float)k->translate[1],
                                  (float)k->translate[2]);
    *model = sr_mat4_mul(&t, &r);
    sr_vec3 eye = tr_vec(k->eye), target = tr_vec(k->target);
    *view = sr_look_at(eye, target, sr_vec3_make(0, 1, 0));
    double fov = k->fov * pi / 180, aspect = (double)gw / gh;
    if (k->ortho) {
        double base = sr_vec3_length(sr_vec3_sub(target, eye)) * tan(fov / 2);
        double hw = k->stretch || gw < gh ? base : base * aspect;
        double hh = k->stretch || gw >= gh ? base : base / aspect;
        *proj = sr_ortho((float)-hw, (float)hw, (float)-hh, (float)hh, 1, 10, false);
    } else {
        *proj = sr_perspective(k->stretch ? (float)fov : sr_fit_fovy((float)fov, gw, gh),
                               k->stretch ? 1.0f : (float)aspect, 1, 10, false);
    }
}

/* Run explain transform on the case into dir; the exit status. */
static int tr_run(const tr_case *k, const char *grid, const char *zoom, const char *dir)
{
    char obj[300] = "", rot[32], tr[96], eye[96], target[96], fov[32];
    for (int i = 0; i < 9; i++) {
        size_t len = strlen(obj);
        snprintf(obj + len, sizeof obj - len, "%s%.17g", i ? "," : "", k->obj[i]);
    }
    snprintf(rot, sizeof rot, "%.17g", k->rotate);
    snprintf(tr, sizeof tr, "%.17g,%.17g,%.17g", k->translate[0], k->translate[1],
             k->translate[2]);
    snprintf(eye, sizeof eye, "%.17g,%.17g,%.17g", k->eye[0], k->eye[1], k->eye[2]);
    snprintf(target, sizeof target, "%.17g,%.17g,%.17g", k->target[0], k->target[1],
             k->target[2]);
    snprintf(fov, sizeof fov, "%.17g", k->fov);
    const char *args[] = { "explain", "transform", "--object", obj, "--rotate", rot,
                           "--translate", tr, "--eye", eye, "--target", target, "--fov", fov,
                           "--projection", k->ortho ? "orthographic" : "perspective",
                           "--aspect", k->stretch ? "stretch" : "fit", "--grid", grid,
                           "--zoom", zoom, "-o", dir, NULL };
    return sr_test_run_cli(args);
}

/* The window-stage caption with the test's own numbers. */
static void tr_window_caption(char *buf, size_t size, int gw, int gh, const int64_t x_q8[3],
                              const int64_t y_q8[3])
{
    int len = snprintf(buf, size,
                       "6. The viewport matrix S maps NDC -1..1 onto the pixel extents of the "
                       "%dx%d viewport, x_S = %d/2 (x + 1), y_S = %d/2 (1 - y) (y down), z_S = "
                       "(z + 1)/2: S = [%d 0 0 %d; 0 -%d 0 %d; 0 0 0.5 0.5; 0 0 0 1]. Window "
                       "coordinates, snapped to 1/256 pixel: ",
                       gw, gh, gw, gh, gw / 2, gw / 2, gh / 2, gh / 2);
    for (int i = 0; i < 3; i++) {
        len += snprintf(buf + len, size - (size_t)len, "%sV%d = (%.4f, %.4f)", i ? ", " : "", i,
                        x_q8[i] / 256.0, y_q8[i] / 256.0);
    }
    snprintf(buf + len, size - (size_t)len, ".");
}

SR_TEST(transform_last_frame_is_what_sr_draw_draws_with_the_matrices)
{
    NEEDS_CLI();
    /* random triangles, rotations, translations and cameras, both
     * projections and both aspect strategies: the last frame is, cell for
     * cell, what sr_draw draws for the object-space triangle with M_O, E
     * and P; the window positions the test computes as the vertex stage
     * does (P (E M_O) v in float, the divide and S in double, snapped)
     * give the same pixels drawn directly, and frame 6 shows them */
    sr_rng rng = { 9301 };
    rt_target t = rt_make(GRID, GRID, 1);
    int drawn_total = 0, shown = 0, refused = 0;
    for (int k = 0; k < 24; k++) {
        tr_case c = { .rotate = sr_rng_int(&rng, -12, 12) * 15, .fov = sr_rng_int(&rng, 30, 80),
                      .ortho = k % 2 == 1, .stretch = k % 4 >= 2 };
        for (int i = 0; i < 9; i++) {
            c.obj[i] = sr_rng_int(&rng, -12, 12) / 8.0;
        }
        for (int i = 0; i < 3; i++) {
            c.translate[i] = sr_rng_int(&rng, -4, 4) / 8.0;
            c.target[i] = sr_rng_int(&rng, -4, 4) / 8.0;
            c.eye[i] = sr_rng_int(&rng, -16, 16) / 8.0;
        }
        c.eye[2] = sr_rng_int(&rng, 24, 40) / 8.0;
        char dir[1024], name[32], grid[16], path[1200];
        snprintf(name, sizeof name, "transform_%02d", k);
        snprintf(grid, sizeof grid, "%dx%d", GRID, GRID);
        out_dir(name, dir, sizeof dir);
        int rc = tr_run(&c, grid, "8", dir);
        if (rc == 2) {
            refused++;   /* a vertex before the near plane */
            continue;
        }
        REQUIRE(rc == 0);
        uint8_t cells[GRID * GRID];
        REQUIRE(last_frame_cells(dir, cells) == 7);

        sr_mat4 model, view, proj;
        tr_matrices(&c, GRID, GRID, &model, &view, &proj);
        float pos[9];
        for (int i = 0; i < 9; i++) {
            pos[i] = (float)c.obj[i];
        }
        rt_clear(&t);
        sr_state st = { .shading = SR_SHADING_UNLIT, .material = { .diffuse = { 1, 1, 1 } } };
        REQUIRE(sr_draw(t.ctx, t.fb, &st, &(sr_draw_desc){ .positions = pos, .vertex_count = 3,
                                                           .model = &model, .view = &view,
                                                           .projection = &proj }) == SR_OK);
        char what[64];
        snprintf(what, sizeof what, "transform case %d", k);
        compare_with_target(&t, cells, what, &drawn_total);

        sr_mat4 mv = sr_mat4_mul(&view, &model), mvp = sr_mat4_mul(&proj, &mv);
        int64_t x_q8[3], y_q8[3];
        double xy[6];
        for (int i = 0; i < 3; i++) {
            sr_vec4 cl = sr_mat4_mul_vec4(&mvp, (sr_vec4){ pos[3 * i], pos[3 * i + 1],
                                                           pos[3 * i + 2], 1 });
            double iw = 1.0 / cl.w;
            x_q8[i] = ref_snap(GRID * 0.5 + GRID * 0.5 * (cl.x * iw));
            y_q8[i] = ref_snap(GRID * 0.5 - GRID * 0.5 * (cl.y * iw));
            xy[2 * i] = x_q8[i] / 256.0;
            xy[2 * i + 1] = y_q8[i] / 256.0;
        }
        rt_clear(&t);
        REQUIRE(rt_draw_tris(&t, xy, 1, NULL, SR_RASTER_HALFSPACE) == SR_OK);
        snprintf(what, sizeof what, "transform case %d, window positions", k);
        compare_with_target(&t, cells, what, &drawn_total);

        char text[600];
        tr_window_caption(text, sizeof text, GRID, GRID, x_q8, y_q8);
        snprintf(path, sizeof path, "%s/frame-006.png", dir);
        if (!caption_reads(path, GRID, 8, 1, text)) {
            FAILF("transform case %d: frame 6 does not read \"%s\"", k, text);
        }
        shown++;
    }
    CHECK(shown >= 16);
    CHECK(drawn_total > 2 * 16 * 20);
    rt_free(&t);
    (void)refused;
}

/* The example's frames on one sheet, against tests/ref/explain_transform.png
 * (text and antialiased marks: 2 levels a channel, 1 pixel in 200). */
SR_TEST(transform_example_sheet_matches_reference)
{
    NEEDS_CLI();
    check_example_sheet("transform", "12");
}

/* A wide viewport: with --aspect fit the projection's aspect is the
 * viewport's, so a square in front of the camera covers a square of
 * pixels; with stretch, NDC's square is stretched over the viewport. */
SR_TEST(transform_aspect_fit_keeps_a_square_square)
{
    NEEDS_CLI();
    for (int stretch = 0; stretch < 2; stretch++) {
        char dir[1024];
        out_dir(stretch ? "transform_stretch" : "transform_fit", dir, sizeof dir);
        /* a right triangle, half of a 1 x 1 square, face on */
        tr_case c = { .obj = { -0.5, -0.5, 0, 0.5, -0.5, 0, -0.5, 0.5, 0 },
                      .eye = { 0, 0, 2 }, .fov = 40, .stretch = stretch == 1 };
        REQUIRE(tr_run(&c, "16x8", "8", dir) == 0);
        uint8_t cells[GRID * GRID];
        REQUIRE(last_frame_cells(dir, cells) == 7);
        int x0 = GRID, x1 = -1, y0 = GRID, y1 = -1;
        for (int y = 0; y < 8; y++) {
            for (int x = 0; x < 16; x++) {
                if (cells[y * GRID + x]) {
                    x0 = x < x0 ? x : x0;
                    x1 = x > x1 ? x : x1;
                    y0 = y < y0 ? y : y0;
                    y1 = y > y1 ? y : y1;
                }
            }
        }
        int w = x1 - x0 + 1, h = y1 - y0 + 1;
        if (stretch) {
            CHECK(w >= 2 * h - 1);   /* stretched by 16/8 */
        } else {
            CHECK(abs(w - h) <= 1);
        }
    }
}

/* ---- gouraud: Gouraud versus Phong, the highlight inside ---- */

/* explain gouraud's scene (docs/explain.md): the triangle at z = 0 in
 * window coordinates under an orthographic P, N = +z, a grey material,
 * a point light 8 pixels above the highlight. */
static sr_result gouraud_draw(rt_target *t, const double *xy, const double hl[2],
                              double shininess, sr_shading shading, bool points, int vertex)
{
    sr_mat4 proj = sr_ortho(0, (float)t->w, (float)t->h, 0, -64, 64, false);
    sr_state st = { .shading = shading, .ambient = { 0.2f, 0.2f, 0.2f }, .point_size = 2,
                    .material = { .diffuse = { 0.35f, 0.35f, 0.35f },
                                  .specular = { 0.55f, 0.55f, 0.55f },
                                  .shininess = (float)shininess },
                    .lights[0] = { .type = SR_LIGHT_POINT,
                                   .vector = { (float)hl[0], (float)hl[1], 8 } } };
    float pos[9], nrm[9] = { 0, 0, 1, 0, 0, 1, 0, 0, 1 };
    for (int i = 0; i < 3; i++) {
        int k = points ? vertex : i;
        pos[3 * i] = (float)xy[2 * k];
        pos[3 * i + 1] = (float)xy[2 * k + 1];
        pos[3 * i + 2] = 0;
    }
    sr_clear(t->ctx, t->fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
    return sr_draw(t->ctx, t->fb, &st,
                   &(sr_draw_desc){ .positions = pos, .normals = nrm,
                                    .vertex_count = points ? 1 : 3,
                                    .primitive = points ? SR_PRIM_POINTS : SR_PRIM_TRIANGLES,
                                    .projection = &proj });
}

/* Blinn-Phong by hand, in double: the intensity at (x, y), 0..1. */
static double gouraud_model(double x, double y, const double hl[2], double n)
{
    double l[3] = { hl[0] - x, hl[1] - y, 8 }, len = sqrt(l[0] * l[0] + l[1] * l[1] + 64);
    double ndotl = 8 / len, h[3] = { l[0] / len, l[1] / len, ndotl + 1 };
    double ndoth = h[2] / sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    return 0.2 * 0.35 + 0.35 * ndotl + 0.55 * pow(ndoth, n);
}

/* Frame `frame`'s cells against the pixels in t: white where nothing was
 * drawn, the pixel's grey where it was; cells within a cell of a vertex
 * or the highlight (their dots cover them) are not judged.  The cells
 * that differ by more than one level. */
static int gouraud_compare(const char *dir, int frame, const rt_target *t, const double *xy,
                           const double hl[2], int *drawn)
{
    uint8_t rgb[GRID * GRID * 3];
    if (!frame_cell_colours(dir, frame, rgb)) {
        return GRID * GRID;
    }
    const uint8_t *px = sr_framebuffer_pixels(t->fb);
    int bad = 0;
    for (int y = 0; y < GRID; y++) {
        for (int x = 0; x < GRID; x++) {
            bool marked = fabs(x + 0.5 - hl[0]) < 1.5 && fabs(y + 0.5 - hl[1]) < 1.5;
            for (int i = 0; i < 3; i++) {
                marked |= fabs(x + 0.5 - xy[2 * i]) < 1.5 && fabs(y + 0.5 - xy[2 * i + 1]) < 1.5;
            }
            const uint8_t *p = px + 4 * (y * GRID + x), *c = rgb + 3 * (y * GRID + x);
            int want = p[3] ? p[0] : 255;
            *drawn += p[3] != 0;
            if (!marked && (abs(c[0] - want) > 1 || abs(c[1] - want) > 1 || abs(c[2] - want) > 1)) {
                bad++;
            }
        }
    }
    return bad;
}

SR_TEST(gouraud_frames_are_what_sr_draw_shades)
{
    NEEDS_CLI();
    /* the example, then random triangles with the highlight at their
     * centroid: frame 4 is sr_draw's Gouraud pixels, the last frame its
     * Phong pixels; frame 2 reads the vertex intensities, which are the
     * vertices drawn as points and Blinn-Phong's value there; Gouraud
     * never exceeds them and Phong finds the highlight they miss */
    sr_rng rng = { 5417 };
    rt_target t = rt_make(GRID, GRID, 1);
    int drawn = 0, missed = 0;
    for (int k = 0; k < 12; k++) {
        double xy[6] = { 1.5, 1.5, 14.5, 3.5, 4.5, 11.5 }, hl[2] = { 7.2, 5.6 };
        double n = k == 0 ? 40 : sr_rng_int(&rng, 10, 120);
        if (k > 0) {
            for (int i = 0; i < 6; i++) {
                xy[i] = sr_rng_int(&rng, 0, 4 * GRID) * 0.25;
            }
            hl[0] = (xy[0] + xy[2] + xy[4]) / 3;
            hl[1] = (xy[1] + xy[3] + xy[5]) / 3;
        }
        char prim[200], shin[16], dir[1024], name[32], path[1200];
        snprintf(prim, sizeof prim, "%g,%g,%g,%g,%g,%g", xy[0], xy[1], xy[2], xy[3], xy[4], xy[5]);
        snprintf(shin, sizeof shin, "%g", n);
        snprintf(name, sizeof name, "gouraud_%02d", k);
        out_dir(name, dir, sizeof dir);
        if (k == 0) {
            REQUIRE(sr_test_run_cli((const char *[]){ "explain", "gouraud", "--grid", "16x16",
                                                      "--zoom", "8", "-o", dir, NULL }) == 0);
        } else {
            REQUIRE(run_explain_with("gouraud", "--triangle", prim, "--shininess", shin, dir) == 0);
        }
        int vi[3], vmax = 0;
        for (int i = 0; i < 3; i++) {
            REQUIRE(gouraud_draw(&t, xy, hl, n, SR_SHADING_GOURAUD, true, i) == SR_OK);
            const uint8_t *px = sr_framebuffer_pixels(t.fb);
            vi[i] = -1;
            for (int p = 0; p < GRID * GRID && vi[i] < 0; p++) {
                vi[i] = px[4 * p + 3] ? px[4 * p] : -1;
            }
            double want = gouraud_model(xy[2 * i], xy[2 * i + 1], hl, n) * 255;
            if (fabs(vi[i] - want) > 1) {
                FAILF("case %d: V%d's intensity %d, Blinn-Phong gives %.2f", k, i, vi[i], want);
            }
            vmax = vi[i] > vmax ? vi[i] : vmax;
        }
        char text[200];
        snprintf(text, sizeof text,
                 "2. Gouraud lights the vertices only: I = %d at V0, %d at V1, %d at V2 (of 255).",
                 vi[0], vi[1], vi[2]);
        snprintf(path, sizeof path, "%s/frame-002.png", dir);
        if (!caption_reads(path, GRID, ZOOM, 1, text)) {
            FAILF("case %d: frame 2 does not read \"%s\"", k, text);
        }
        REQUIRE(gouraud_draw(&t, xy, hl, n, SR_SHADING_GOURAUD, false, 0) == SR_OK);
        int gmax = 0;
        for (int p = 0; p < GRID * GRID; p++) {
            const uint8_t *px = sr_framebuffer_pixels(t.fb) + 4 * p;
            gmax = px[3] && px[0] > gmax ? px[0] : gmax;
        }
        CHECK(gmax <= vmax + 1);   /* a convex combination of the vertices */
        int bad = gouraud_compare(dir, 4, &t, xy, hl, &drawn);
        if (bad) {
            FAILF("case %d: %d cells of frame 4 are not sr_draw's Gouraud pixels", k, bad);
        }
        REQUIRE(gouraud_draw(&t, xy, hl, n, SR_SHADING_PHONG, false, 0) == SR_OK);
        int pmax = 0;
        for (int p = 0; p < GRID * GRID; p++) {
            const uint8_t *px = sr_framebuffer_pixels(t.fb) + 4 * p;
            pmax = px[3] && px[0] > pmax ? px[0] : pmax;
        }
        missed += pmax > gmax + 40;
        bad = gouraud_compare(dir, 6, &t, xy, hl, &drawn);
        if (bad) {
            FAILF("case %d: %d cells of the last frame are not sr_draw's Phong pixels", k, bad);
        }
        struct stat st;
        snprintf(path, sizeof path, "%s/frame-007.png", dir);
        CHECK(stat(path, &st) != 0);   /* frame 6 is the last */
    }
    CHECK(drawn > 12 * 2 * 20);
    CHECK(missed >= 6);   /* the highlight is inside the triangle, far from its vertices */
    rt_free(&t);
}

/* The example's frames on one sheet, against tests/ref/explain_gouraud.png
 * (2 levels a channel, 1 pixel in 200). */
SR_TEST(gouraud_example_sheet_matches_reference)
{
    NEEDS_CLI();
    check_example_sheet("gouraud", "16");
}

/* ---- zfight: near-coplanar triangles and polygon offset ---- */

/* Triangle t (0: A, 1: B) of xyz (x, y, z a vertex) drawn alone or, both,
 * A then B, as explain zfight draws them: D16 buffer cleared to 1, LESS,
 * B offset by (factor, units) when `offset`; A red, B blue. */
static sr_result zfight_draw(sr_context *ctx, sr_framebuffer *fb, const double *xyz, int t,
                             bool both, bool offset, const double off[2])
{
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 }, .depth = 1 });
    sr_result r = SR_OK;
    for (int k = both ? 0 : t; k <= (both ? 1 : t) && r == SR_OK; k++) {
        float pos[9];
        for (int i = 0; i < 3; i++) {
            const double *v = xyz + 9 * k + 3 * i;
            pos[3 * i] = (float)(2 * v[0] / GRID - 1);
            pos[3 * i + 1] = (float)(1 - 2 * v[1] / GRID);
            pos[3 * i + 2] = (float)(2 * v[2] - 1);
        }
        sr_state st = { .shading = SR_SHADING_UNLIT,
                        .material = { .diffuse = { k == 0 ? 1.0f : 0.0f, 0, k == 1 ? 1.0f : 0 } } };
        if (k == 1 && offset) {
            st.offset = (sr_polygon_offset){ .factor = (float)off[0], .units = (float)off[1],
                                             .fill = true };
        }
        r = sr_draw(ctx, fb, &st, &(sr_draw_desc){ .positions = pos, .vertex_count = 3 });
    }
    return r;
}

/* The q of each pixel drawn in fb, else -1. */
static void zfight_q(sr_context *ctx, sr_framebuffer *fb, int64_t *q)
{
    float d[GRID * GRID];
    sr_read_depth(ctx, fb, 0, 0, GRID, GRID, d, GRID);
    const uint8_t *px = sr_framebuffer_pixels(fb);
    for (int i = 0; i < GRID * GRID; i++) {
        q[i] = px[4 * i + 3] ? (int64_t)llround(d[i] * 65535.0) : -1;
    }
}

/* Frame `frame`'s cells against fb's pixels: orange where A shows, blue
 * where B does, white where nothing; the cells that differ.  A cell
 * whose commonest colour is none of these is under a label (its light
 * ground) and not judged; at most 16 such. */
static int zfight_compare(const char *dir, int frame, sr_framebuffer *fb, int *b_cells)
{
    uint8_t rgb[GRID * GRID * 3];
    if (!frame_cell_colours(dir, frame, rgb)) {
        return GRID * GRID;
    }
    const uint8_t *px = sr_framebuffer_pixels(fb);
    int bad = 0, unjudged = 0;
    for (int i = 0; i < GRID * GRID; i++) {
        const uint8_t *p = px + 4 * i, *c = rgb + 3 * i;
        int want = !p[3] ? 0 : p[2] ? 2 : 1;
        int got = is_fill_orange(c) ? 1 : is_fill_blue(c) ? 2
                : c[0] == 255 && c[1] == 255 && c[2] == 255 ? 0 : -1;
        unjudged += got < 0;
        bad += got >= 0 && want != got;
        *b_cells += want == 2;
    }
    return unjudged > 16 ? GRID * GRID : bad;
}

SR_TEST(zfight_frames_are_what_sr_draw_leaves_with_and_without_offset)
{
    NEEDS_CLI();
    /* the example, then random triangles B whose depths are A's plane
     * there plus less than a D16 step: frames 4 and 6 are, cell for cell,
     * what sr_draw leaves for A then B without and with the offset; frame
     * 5 reads B's slope m and the offset o (the library's formula) and
     * the passes and fails of B's offset q against A's, read back */
    sr_rng rng = { 7907 };
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = GRID, .height = GRID,
                                                             .depth_format = SR_DEPTH_D16 },
                                &fb) == SR_OK);
    int fights = 0, b_total = 0, cases = 0;
    for (int k = 0; k < 24; k++) {
        double xyz[18] = { 0.5, 0.5, 0.4, 13.5, 1.5, 0.4, 2.5, 10.5, 0.41,
                           3.2, 2.3, 0.401623187, 12.6, 3.4, 0.401993, 4.3, 9.6, 0.408948312 };
        double off[2] = { -1, -1 };
        if (k > 0) {
            for (int i = 0; i < 18; i++) {
                xyz[i] = i % 3 == 2 ? sr_rng_int(&rng, 20, 80) / 100.0
                                    : sr_rng_int(&rng, 0, 4 * GRID) * 0.25;
            }
            /* B on A's plane z = a x + b y + c, give or take a step */
            double x1 = xyz[3] - xyz[0], y1 = xyz[4] - xyz[1], z1 = xyz[5] - xyz[2];
            double x2 = xyz[6] - xyz[0], y2 = xyz[7] - xyz[1], z2 = xyz[8] - xyz[2];
            double det = x1 * y2 - x2 * y1;
            if (fabs(det) < 4) {
                continue;
            }
            double a = (z1 * y2 - z2 * y1) / det, b = (x1 * z2 - x2 * z1) / det;
            for (int i = 3; i < 6; i++) {
                double *v = xyz + 3 * i;
                v[2] = xyz[2] + a * (v[0] - xyz[0]) + b * (v[1] - xyz[1]) +
                       sr_rng_int(&rng, -10, 10) / 1e6;
                if (!(v[2] >= 0 && v[2] <= 1)) {
                    det = 0;   /* the plane leaves the depth range there */
                }
            }
            if (det == 0) {
                continue;
            }
            off[0] = sr_rng_int(&rng, -2, 0);
            off[1] = sr_rng_int(&rng, -4, -1);
        }
        char tris[600] = "", offs[32], dir[1024], name[32], path[1200];
        for (int i = 0; i < 18; i++) {
            size_t len = strlen(tris);
            snprintf(tris + len, sizeof tris - len, "%s%.17g", i ? "," : "", xyz[i]);
        }
        snprintf(offs, sizeof offs, "%g,%g", off[0], off[1]);
        snprintf(name, sizeof name, "zfight_%02d", k);
        out_dir(name, dir, sizeof dir);
        REQUIRE(run_explain_with("zfight", "--triangles", tris, "--offset", offs, dir) == 0);

        int64_t qa[GRID * GRID], qb[GRID * GRID];
        REQUIRE(zfight_draw(ctx, fb, xyz, 0, false, false, off) == SR_OK);
        zfight_q(ctx, fb, qa);
        REQUIRE(zfight_draw(ctx, fb, xyz, 1, false, false, off) == SR_OK);
        zfight_q(ctx, fb, qb);
        int fails = 0;
        for (int i = 0; i < GRID * GRID; i++) {
            fails += qb[i] >= 0 && qa[i] >= 0 && qb[i] >= qa[i];
        }
        fights += fails > 0;
        cases++;
        REQUIRE(zfight_draw(ctx, fb, xyz, 1, false, true, off) == SR_OK);
        zfight_q(ctx, fb, qb);
        int pass = 0, fail = 0;
        for (int i = 0; i < GRID * GRID; i++) {
            if (qb[i] >= 0) {
                bool p = qa[i] < 0 || qb[i] < qa[i];
                pass += p;
                fail += !p;
            }
        }
        REQUIRE(zfight_draw(ctx, fb, xyz, 0, true, false, off) == SR_OK);
        int bad = zfight_compare(dir, 4, fb, &b_total);
        if (bad) {
            FAILF("zfight case %d: %d cells of frame 4 are not sr_draw's", k, bad);
        }
        REQUIRE(zfight_draw(ctx, fb, xyz, 0, true, true, off) == SR_OK);
        bad = zfight_compare(dir, 6, fb, &b_total);
        if (bad) {
            FAILF("zfight case %d: %d cells of the last frame are not sr_draw's", k, bad);
        }
        snprintf(path, sizeof path, "%s/frame-007.png", dir);
        struct stat st;
        CHECK(stat(path, &st) != 0);

        /* m from B's snapped vertices (docs/raster-rules.md 6.4) */
        double x[3], y[3], z[3];
        for (int i = 0; i < 3; i++) {
            x[i] = (double)ref_snap(xyz[9 + 3 * i]);
            y[i] = (double)ref_snap(xyz[10 + 3 * i]);
            z[i] = xyz[11 + 3 * i];
        }
        double area2 = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
        double dzdx = ((z[1] - z[0]) * (y[2] - y[0]) - (z[2] - z[0]) * (y[1] - y[0])) * 256 / area2;
        double dzdy = ((x[1] - x[0]) * (z[2] - z[0]) - (x[2] - x[0]) * (z[1] - z[0])) * 256 / area2;
        double m = area2 ? fmax(fabs(dzdx), fabs(dzdy)) : 0, o = off[0] * m + off[1] / 65535.0;
        char text[600];
        snprintf(text, sizeof text,
                 "5. Polygon offset on B: o = factor m + units r with m = max(|dz/dx|, |dz/dy|) = "
                 "%.3g, B's depth slope per pixel, and r = 1/65535, the buffer's step: o = %g x "
                 "%.3g + %g x 1/65535 = %.3g (%.3g steps), added to B's depth before the test. "
                 "%d pass, %d fail.",
                 m, off[0], m, off[1], o, o * 65535, pass, fail);
        snprintf(path, sizeof path, "%s/frame-005.png", dir);
        if (!caption_reads(path, GRID, ZOOM, 1, text)) {
            FAILF("zfight case %d: frame 5 does not read \"%s\"", k, text);
        }
    }
    CHECK(cases >= 8);
    CHECK(fights >= cases / 2);   /* B loses pixels to A without the offset */
    CHECK(b_total > 100);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

/* The example's frames on one sheet, against tests/ref/explain_zfight.png
 * (2 levels a channel, 1 pixel in 200). */
SR_TEST(zfight_example_sheet_matches_reference)
{
    NEEDS_CLI();
    check_example_sheet("zfight", "20");
}

/* The example's frames on one sheet, against tests/ref/explain_wu.png
 * (2 levels a channel, 1 pixel in 200). */
SR_TEST(wu_example_sheet_matches_reference)
{
    NEEDS_CLI();
    check_example_sheet("wu", "16");
}

/* The example's frames on one sheet, against tests/ref/explain_aaline.png
 * (2 levels a channel, 1 pixel in 200). */
SR_TEST(aaline_example_sheet_matches_reference)
{
    NEEDS_CLI();
    check_example_sheet("aaline", "16");
}

/* The example's frames on one sheet, against tests/ref/explain_area.png
 * (2 levels a channel, 1 pixel in 200). */
SR_TEST(area_example_sheet_matches_reference)
{
    NEEDS_CLI();
    check_example_sheet("area", "16");
}

/* How many frame-NNN.png files dir holds. */
static int frame_count(const char *dir)
{
    int n = 0;
    for (int i = 1; i < 100; i++) {
        char path[1200];
        struct stat st;
        snprintf(path, sizeof path, "%s/frame-%03d.png", dir, i);
        if (stat(path, &st) != 0) {
            break;
        }
        n = i;
    }
    return n;
}

/* interpolation: the triangle, each method's frames (bilinear's edges
 * and spans, the plane, barycentric's weights and values), the library's
 * pixels; the first caption names what --method chose. */
SR_TEST(interpolation_frames_follow_the_method)
{
    NEEDS_CLI();
    static const struct { const char *method; int frames; const char *shown; } runs[] = {
        { "all", 7, "all three" },
        { "bilinear", 4, "bilinear (--method bilinear)" },
        { "plane", 3, "the plane equation (--method plane)" },
        { "barycentric", 4, "barycentric coordinates (--method barycentric)" },
    };
    for (size_t i = 0; i < sizeof runs / sizeof runs[0]; i++) {
        char dir[1024], name[64], path[1200], text[600];
        snprintf(name, sizeof name, "interp_%s", runs[i].method);
        out_dir(name, dir, sizeof dir);
        REQUIRE(sr_test_run_cli((const char *[]){ "explain", "interpolation", "--method",
                                                  runs[i].method, "-o", dir, NULL }) == 0);
        CHECK_EQ(frame_count(dir), runs[i].frames);
        snprintf(path, sizeof path, "%s/frame-001.png", dir);
        snprintf(text, sizeof text,
                 "1. A triangle with a value at each vertex, here an intensity I (a colour "
                 "channel; depth and texture coordinates are interpolated alike), snapped to "
                 "1/256 pixel. Three methods give I at each covered pixel centre, one linear "
                 "function of x and y on a triangle: bilinear (scan-line), the plane equation "
                 "and barycentric coordinates. Shown: %s.",
                 runs[i].shown);
        if (!caption_reads(path, 12, 32, 2, text)) {
            FAILF("interpolation --method %s: frame 1's caption does not read \"%s\"",
                  runs[i].method, text);
        }
    }
    char dir[1024];
    out_dir("interp_bad", dir, sizeof dir);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "interpolation", "--method", "gouraud",
                                               "-o", dir, NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "fillpoly", "--method", "plane",
                                               "-o", dir, NULL }), 2);
}

/* The example's plane frame states the coefficients solved from the
 * vertices (6.5,0.7) I=1, (14.3,6.6) I=0.2, (1.4,10.6) I=0.55. */
SR_TEST(interpolation_plane_caption_gives_the_coefficients)
{
    NEEDS_CLI();
    expect_caption("interp_plane", (const char *[]){ "interpolation", "--method", "plane", NULL },
                   2, 12,
                   "2. The plane equation I(x, y) = a x + b y + c, solved from the three "
                   "vertices (Cramer's rule, twice the area 107.357 as the determinant): "
                   "a = -0.04905, b = -0.07071, c = 1.3683. At the centre (1.5, 1.5) I = "
                   "1.1886; then +a per pixel along a row and +b from one row's start (pink) "
                   "to the next: two additions, no division, per pixel.");
}

/* interpolation's last frame holds sr_draw's pixels for the triangle with
 * the vertex values as a colour attribute (screen space): random
 * triangles on the half-pixel grid, cell for cell, within one step. */
SR_TEST(interpolation_last_frame_is_what_sr_draw_draws)
{
    NEEDS_CLI();
    sr_rng rng = { 4417 };
    rt_target t = rt_make(GRID, GRID, 1);
    int covered = 0;
    for (int k = 0; k < 8; k++) {
        double v[6], in[3];
        for (int i = 0; i < 6; i++) {
            v[i] = sr_rng_int(&rng, -4, 2 * GRID + 4) * 0.5;
        }
        for (int i = 0; i < 3; i++) {
            in[i] = sr_rng_int(&rng, 0, 100) / 100.0;
        }
        char prim[256], is[64], dir[1024], name[32];
        snprintf(prim, sizeof prim, "%g,%g,%g,%g,%g,%g", v[0], v[1], v[2], v[3], v[4], v[5]);
        snprintf(is, sizeof is, "%g,%g,%g", in[0], in[1], in[2]);
        snprintf(name, sizeof name, "interp_%02d", k);
        out_dir(name, dir, sizeof dir);
        REQUIRE(run_explain_with("interpolation", "--triangle", prim, "--intensity", is, dir)
                == 0);
        int last = frame_count(dir);
        REQUIRE(last == 7);
        uint8_t got[GRID * GRID * 3];
        REQUIRE(frame_cell_colours(dir, last, got));
        float pos[9], col[12];
        for (int i = 0; i < 3; i++) {
            pos[3 * i] = rt_ndc_x(&t, v[2 * i]);
            pos[3 * i + 1] = rt_ndc_y(&t, v[2 * i + 1]);
            pos[3 * i + 2] = 0;
            col[4 * i] = col[4 * i + 1] = col[4 * i + 2] = (float)in[i];
            col[4 * i + 3] = 1;
        }
        /* the frame's empty cells are white: so is the target */
        sr_clear(t.ctx, t.fb, &(sr_clear_desc){ .color = { 1, 1, 1, 1 } });
        sr_state st = { .shading = SR_SHADING_UNLIT, .material = { .diffuse = { 1, 1, 1 } },
                        .interpolation = SR_INTERP_AFFINE };
        REQUIRE(sr_draw(t.ctx, t.fb, &st, &(sr_draw_desc){ .positions = pos, .vertex_count = 3,
                                                           .colors = col, .color_size = 4 })
                == SR_OK);
        const uint8_t *px = sr_framebuffer_pixels(t.fb);
        int bad = 0;
        for (int i = 0; i < GRID * GRID; i++) {
            covered += memcmp(px + 4 * i, "\xff\xff\xff", 3) != 0;
            for (int ch = 0; ch < 3; ch++) {
                bad += abs(got[i * 3 + ch] - px[i * 4 + ch]) > 1;
            }
        }
        if (bad) {
            FAILF("interpolation %s, I %s: %d channels differ", prim, is, bad);
        }
    }
    CHECK(covered > 100);   /* the triangles do cover pixels */
    rt_free(&t);
}
