/* test_locale.c - the text readers (OBJ, PLY, STL, SVG) read the same
 * numbers whatever locale the host program set: under de_DE.UTF-8, where
 * strtod takes ',' as the decimal point and stops at the '.' of "0.5",
 * every reader gives bit for bit what it gives under the C locale.
 * scripts/install-deps.sh generates the locale; without it the tests skip
 * and say so. */
#include "softrast_io.h"
#include "sr_test.h"

#include <locale.h>
#include <stdlib.h>
#include <string.h>

#define GERMAN "de_DE.UTF-8"

/* Numbers whose '.' strtod would stop at under GERMAN, with exponents,
 * many digits and a subnormal. */
#define X0 "0.5"
#define X1 "-1.25e-3"
#define X2 "3.14159265358979323846"
#define Y0 "2.5E+1"
#define Y1 ".75"
#define Y2 "1.1754942e-38"

static const char obj_text[] = "v " X0 " 0 0\nv " X1 " " Y1 " 0\nv " X2 " " Y0 " " Y2 "\n"
                               "f 1 2 3\n";
static const char ply_text[] = "ply\nformat ascii 1.0\nelement vertex 3\n"
                               "property float x\nproperty float y\nproperty double z\n"
                               "element face 1\nproperty list uchar int vertex_indices\n"
                               "end_header\n" X0 " 0 0\n" X1 " " Y1 " 0\n" X2 " " Y0 " " Y2 "\n"
                               "3 0 1 2\n";
static const char stl_text[] = "solid t\nfacet normal 0.0 0.0 1.0\nouter loop\n"
                               "vertex " X0 " 0 0\nvertex " X1 " " Y1 " 0\n"
                               "vertex " X2 " " Y0 " " Y2 "\nendloop\nendfacet\nendsolid t\n";

typedef sr_result (*parse_fn)(sr_context *, const char *, const uint8_t *, size_t, sr_mesh *,
                              sr_io_error *);

static sr_result parse_obj_bytes(sr_context *ctx, const char *name, const uint8_t *data,
                                 size_t size, sr_mesh *out, sr_io_error *err)
{
    return sr_parse_obj(ctx, name, (const char *)data, size, out, err);
}

/* Switch the whole process to GERMAN; false (and a skip) when the system
 * does not have it. */
static bool use_german(void)
{
    if (!setlocale(LC_ALL, GERMAN)) {
        sr_test_skip("locale " GERMAN " is not installed (scripts/install-deps.sh generates it)");
        return false;
    }
    /* The premise: here strtod stops at the '.'. */
    char *end;
    double v = strtod("0.5", &end);
    CHECK(v == 0 && *end == '.');
    return true;
}

static void same_mesh_in_both_locales(const char *name, const char *text, parse_fn parse)
{
    setlocale(LC_ALL, "C");
    sr_mesh c, de;
    sr_io_error err;
    sr_result r = parse(sr_test_ctx(), name, (const uint8_t *)text, strlen(text), &c, &err);
    CHECK_EQ(r, SR_OK);
    if (r != SR_OK) {
        fprintf(stderr, "  C locale: %s\n", err.message);
        return;
    }
    if (!use_german()) {
        sr_destroy_mesh(sr_test_ctx(), &c);
        return;
    }
    r = parse(sr_test_ctx(), name, (const uint8_t *)text, strlen(text), &de, &err);
    setlocale(LC_ALL, "C");
    CHECK_EQ(r, SR_OK);
    if (r == SR_OK) {
        CHECK_EQ(de.vertex_count, c.vertex_count);
        CHECK(de.vertex_count == 3 &&
              memcmp(de.positions, c.positions, 9 * sizeof c.positions[0]) == 0);
        /* And the numbers are the ones written, not "0" cut at the '.'. */
        CHECK(c.positions[0] == 0.5f && c.positions[4] == 0.75f && c.positions[7] == 25);
        sr_destroy_mesh(sr_test_ctx(), &de);
    } else {
        fprintf(stderr, "  %s: %s\n", GERMAN, err.message);
    }
    sr_destroy_mesh(sr_test_ctx(), &c);
}

SR_TEST(obj_reads_the_same_numbers_under_a_german_locale)
{
    same_mesh_in_both_locales("t.obj", obj_text, parse_obj_bytes);
}

SR_TEST(ply_reads_the_same_numbers_under_a_german_locale)
{
    same_mesh_in_both_locales("t.ply", ply_text, sr_parse_ply);
}

SR_TEST(stl_reads_the_same_numbers_under_a_german_locale)
{
    same_mesh_in_both_locales("t.stl", stl_text, sr_parse_stl);
}

/* An SVG whose every number has a '.': coordinates, a transform, an
 * opacity, a stroke width, rgb() percentages and a length unit. */
static const char svg_text[] =
    "<svg width='32.5' height='24.5' viewBox='0 0 16.25 12.25'>"
    "<g transform='translate(0.5 0.25) rotate(12.5) scale(1.5)'>"
    "<path d='M0.5 0.5 L9.75 1.25 L4.5 7.125 z' fill='rgb(12.5%, 50.5%, 99.5%)'"
    " fill-opacity='0.75' stroke='black' stroke-width='0.35'/>"
    "<circle cx='6.5' cy='4.5' r='2.25mm' fill='red' opacity='.5'/></g></svg>";

/* The image, or NULL (and a failure) if the render fails. */
static uint8_t *render_svg(sr_context *ctx, int *w, int *h)
{
    sr_framebuffer *fb = NULL;
    sr_io_error err;
    sr_result r = sr_render_svg(ctx, svg_text, strlen(svg_text),
                                &(sr_svg_desc){ .name = "t.svg" }, &fb, NULL, &err);
    CHECK_EQ(r, SR_OK);
    if (r != SR_OK) {
        fprintf(stderr, "  %s\n", err.message);
        return NULL;
    }
    *w = sr_framebuffer_width(fb);
    *h = sr_framebuffer_height(fb);
    size_t n = (size_t)*w * (size_t)*h * 4;
    uint8_t *px = malloc(n);
    memcpy(px, sr_framebuffer_pixels(fb), n);
    sr_destroy_framebuffer(ctx, fb);
    return px;
}

SR_TEST(svg_draws_the_same_image_under_a_german_locale)
{
    if (!sr_io_have_svg()) {
        SKIP("this build reads no SVG (no expat)");
    }
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    setlocale(LC_ALL, "C");
    int w = 0, h = 0, dw = 0, dh = 0;
    uint8_t *c = render_svg(ctx, &w, &h);
    if (c && use_german()) {
        uint8_t *de = render_svg(ctx, &dw, &dh);
        setlocale(LC_ALL, "C");
        CHECK(w == 33 && h == 25); /* 32.5 x 24.5 rounded up, not 32 x 24 */
        CHECK(de && dw == w && dh == h && memcmp(c, de, (size_t)w * (size_t)h * 4) == 0);
        free(de);
    }
    setlocale(LC_ALL, "C");
    free(c);
    sr_destroy_context(ctx);
}
