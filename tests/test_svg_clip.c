/* test_svg_clip.c - clip paths of the SVG reader beyond the drawings of
 * test_svg_paint (clipchild.svg): a use's clip path lies in the user
 * space its x and y move to, as SVG turns them into a translation after
 * its transform; the clip paths of a clipPath's children close cycles
 * that are refused, and chains of them are bounded in depth.  Pixels are
 * checked against what the drawing says. */
#include "softrast_io.h"
#include "sr_test.h"

#include <stdlib.h>
#include <string.h>

static sr_framebuffer *render(const char *svg, sr_result want, sr_io_error *err)
{
    sr_framebuffer *fb = NULL;
    CHECK_EQ(sr_render_svg(sr_test_ctx(), svg, strlen(svg),
                           &(sr_svg_desc){ .name = "t.svg", .background = { 1, 1, 1, 1 } }, &fb,
                           NULL, err),
             want);
    return fb;
}

static bool blue(const sr_framebuffer *fb, int x, int y)
{
    const uint8_t *p =
        sr_framebuffer_pixels(fb) + ((size_t)y * (size_t)sr_framebuffer_width(fb) + x) * 4;
    return p[0] == 0 && p[1] == 0x66 && p[2] == 0xcc;
}

SR_TEST(a_uses_clip_path_is_in_the_space_its_x_and_y_move_to)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    /* the first use covers 20..40 and its clip 0..10 of the moved space
     * (20..30); the second 40..60, its clip the left half of its box
     * (40..50); in a clipPath, a use's clip moves the same way (60..70) */
    sr_io_error err;
    sr_framebuffer *fb = render(
        "<svg xmlns='http://www.w3.org/2000/svg' width='80' height='20'>"
        "<defs><rect id='r' width='20' height='20'/>"
        "<clipPath id='c'><rect width='10' height='20'/></clipPath>"
        "<clipPath id='b' clipPathUnits='objectBoundingBox'><rect width='0.5' height='1'/>"
        "</clipPath>"
        "<clipPath id='k'><use href='#r' x='60' clip-path='url(#c)'/></clipPath></defs>"
        "<use href='#r' x='20' fill='#06c' clip-path='url(#c)'/>"
        "<use href='#r' x='40' fill='#06c' clip-path='url(#b)'/>"
        "<rect width='80' height='20' fill='#06c' clip-path='url(#k)'/></svg>",
        SR_OK, &err);
    REQUIRE(fb);
    for (int x = 0; x < 80; x++) {
        bool inside = (x >= 20 && x < 30) || (x >= 40 && x < 50) || (x >= 60 && x < 70);
        CHECK_EQ(blue(fb, x, 10), inside);
    }
    sr_destroy_framebuffer(sr_test_ctx(), fb);
}

SR_TEST(clip_paths_of_a_clip_paths_children_refuse_cycles_and_depth)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_io_error err;
    CHECK(render("<svg xmlns='http://www.w3.org/2000/svg' width='4' height='4'>"
                 "<clipPath id='a'><rect width='4' height='4' clip-path='url(#b)'/></clipPath>\n"
                 "<clipPath id='b'><rect width='4' height='4' clip-path='url(#a)'/></clipPath>\n"
                 "<rect width='4' height='4' clip-path='url(#a)'/></svg>",
                 SR_BAD_FORMAT, &err) == NULL);
    CHECK_STR_CONTAINS(err.message, "t.svg:2: clip-path: reference cycle through \"#a\"");
    /* 300 clip paths, each child clipped by the next: the chain stops at
     * the nesting bound of elements, with a message, not the stack */
    size_t cap = 300 * 100 + 200, n = 0;
    char *svg = malloc(cap);
    REQUIRE(svg);
    n += (size_t)snprintf(svg + n, cap - n,
                          "<svg xmlns='http://www.w3.org/2000/svg' width='4' height='4'>");
    for (int i = 0; i < 300; i++) {
        n += (size_t)snprintf(svg + n, cap - n,
                              "<clipPath id='c%d'><rect width='4' height='4' "
                              "clip-path='url(#c%d)'/></clipPath>",
                              i, i + 1);
    }
    snprintf(svg + n, cap - n, "<rect width='4' height='4' clip-path='url(#c0)'/></svg>");
    CHECK(render(svg, SR_BAD_FORMAT, &err) == NULL);
    CHECK_STR_CONTAINS(err.message, "clip paths nested deeper than 256");
    free(svg);
}
