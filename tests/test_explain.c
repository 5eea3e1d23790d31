/* test_explain.c - `softrast explain`: every algorithm's last frame shows,
 * cell for cell, the pixels the library draws for the same primitive at
 * 1x.  The frames are read back as PNGs; a cell counts as drawn when any
 * of its pixels is the frame's fill blue: the edges, marks and labels
 * drawn over the cells are black or grey, and blended over white they stay
 * grey, so blue shows only where a cell was filled. */
#include "raster_util.h"
#include "softrast_io.h"
#include "sr_test.h"

#include <stdio.h>
#include <sys/stat.h>

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

/* The cells drawn in the last frame-NNN.png of dir; its number, or 0. */
static int last_frame_cells(const char *dir, uint8_t *cells)
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
                    blue += fx < w && fy < h && is_fill_blue(px + ((size_t)fy * w + fx) * 4);
                }
            }
            cells[cy * GRID + cx] = blue > 0;
        }
    }
    free(px);
    return last;
}

static int run_explain(const char *algorithm, const char *prim_opt, const char *prim,
                       const char *dir)
{
    char grid[16], zoom[8];
    snprintf(grid, sizeof grid, "%dx%d", GRID, GRID);
    snprintf(zoom, sizeof zoom, "%d", ZOOM);
    const char *args[] = { "explain", algorithm, prim_opt, prim, "--grid", grid, "--zoom", zoom,
                           "-o", dir, NULL };
    return sr_test_run_cli(args);
}

static const char *out_dir(const char *name, char *buf, size_t n)
{
    snprintf(buf, n, "%s/explain_%s", sr_test_out_dir(), name);
    mkdir(buf, 0777);
    return buf;
}

SR_TEST(triangle_last_frame_is_what_sr_draw_covers)
{
    NEEDS_CLI();
    /* the example (ties on a top, a left and a right edge), then random
     * triangles of either winding with vertices on the half-pixel grid,
     * so that many pixel centres fall exactly on edges */
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
        char prim[256], dir[1024], name[32];
        snprintf(prim, sizeof prim, "%g,%g,%g,%g,%g,%g", v[0], v[1], v[2], v[3], v[4], v[5]);
        snprintf(name, sizeof name, "triangle_%02d", k);
        out_dir(name, dir, sizeof dir);
        REQUIRE(run_explain("triangle", "--triangle", prim, dir) == 0);
        uint8_t cells[GRID * GRID], want[GRID * GRID];
        REQUIRE(last_frame_cells(dir, cells) >= 2);
        for (int r = SR_RASTER_HALFSPACE; r <= SR_RASTER_BARYCENTRIC; r++) {
            rt_clear(&t);
            REQUIRE(rt_draw_tris(&t, v, 1, NULL, (sr_rasterizer)r) == SR_OK);
            rt_mask(&t, want);
            int diff = 0;
            for (int i = 0; i < GRID * GRID; i++) {
                diff += cells[i] != want[i];
                drawn_total += r == SR_RASTER_HALFSPACE && want[i];
            }
            if (diff) {
                FAILF("triangle %s, rasterizer %d: %d cells differ", prim, r, diff);
            }
        }
    }
    CHECK(drawn_total > 500);   /* the triangles do cover pixels */
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
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "triangle", "--zoom", "3", "-o", dir,
                                               NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "triangle", "-o", "a%s%d", NULL }), 2);
    CHECK_EQ(sr_test_run_cli((const char *[]){ "explain", "--help", NULL }), 0);
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
