/* test_svg_api.c - the SVG reader as a library call (softrast_io.h):
 * sr_render_svg_file draws the same pixels as `softrast svg` writes,
 * reports "FILE:LINE: ..." through sr_io_error with an sr_result,
 * hands warnings to the callback one line each, and checks its
 * arguments. */
#include "softrast_io.h"
#include "sr_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static sr_context *make_ctx(void)
{
    sr_context *ctx = NULL;
    if (sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) != SR_OK) {
        return NULL;
    }
    return ctx;
}

SR_TEST(render_file_draws_what_the_command_writes)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    char in[1024], out[1024];
    snprintf(in, sizeof in, "%s/data/svg/transforms.svg", sr_test_src_dir());
    snprintf(out, sizeof out, "%s/svg_api_transforms.png", sr_test_out_dir());
    REQUIRE(sr_test_run_cli((const char *[]){ "svg", in, "-o", out, "--scale", "2", NULL }) ==
            0);
    int w, h;
    uint8_t *png = NULL;
    sr_io_error err;
    REQUIRE(sr_read_png(out, NULL, &w, &h, &png, &err) == SR_OK);

    sr_context *ctx = make_ctx();
    REQUIRE(ctx);
    sr_framebuffer *fb = NULL;
    sr_svg_info info;
    CHECK_EQ(sr_render_svg_file(ctx, in, &(sr_svg_desc){ .scale = 2 }, &fb, &info, &err), SR_OK);
    REQUIRE(fb);
    CHECK_EQ(sr_framebuffer_width(fb), w);
    CHECK_EQ(sr_framebuffer_height(fb), h);
    CHECK(memcmp(sr_framebuffer_pixels(fb), png, (size_t)w * (size_t)h * 4) == 0);
    /* Work was counted, within the budgets. */
    CHECK(info.points_used > 0 && info.points_used <= info.points_budget);
    CHECK(info.work_used > 0 && info.work_used <= info.work_budget);
    CHECK_EQ(info.warnings, 0);
    sr_destroy_framebuffer(ctx, fb);
    free(png);
    sr_destroy_context(ctx);
}

SR_TEST(warnings_reach_the_callback_once_per_name)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    static const char doc[] = "<svg width='8' height='8'>\n<foreignObject/>\n<foreignObject/>\n"
                              "<rect width='4' height='4' filter='x'/>\n</svg>\n";
    sr_context *ctx = make_ctx();
    REQUIRE(ctx);
    sr_test_warnings w = { 0 };
    sr_framebuffer *fb = NULL;
    sr_svg_info info;
    sr_io_error err;
    CHECK_EQ(sr_render_svg(ctx, doc, sizeof doc - 1,
                           &(sr_svg_desc){ .name = "w.svg", .warn = sr_test_collect_warning,
                                           .warn_user = &w },
                           &fb, &info, &err),
             SR_OK);
    CHECK_EQ(w.count, 2);
    CHECK_EQ(info.warnings, 2);
    CHECK_STR_CONTAINS(w.text, "w.svg:2: warning: unsupported element 'foreignObject' skipped|");
    CHECK_STR_CONTAINS(w.text, "w.svg:4: warning: unsupported filter 'x' skipped|");
    CHECK(strchr(w.text, '\n') == NULL);
    sr_destroy_framebuffer(ctx, fb);
    /* Without a callback they are only counted. */
    CHECK_EQ(sr_render_svg(ctx, doc, sizeof doc - 1, NULL, &fb, &info, &err), SR_OK);
    CHECK_EQ(info.warnings, 2);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(failures_are_results_with_file_and_line)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_context *ctx = make_ctx();
    REQUIRE(ctx);
    sr_framebuffer *fb = (sr_framebuffer *)&fb; /* must come back NULL */
    sr_io_error err;
    static const char bad[] = "<svg width='8' height='8'>\n<circle r='1q'/>\n</svg>";
    CHECK_EQ(sr_render_svg(ctx, bad, sizeof bad - 1, &(sr_svg_desc){ .name = "bad.svg" }, &fb,
                           NULL, &err),
             SR_BAD_FORMAT);
    CHECK(fb == NULL);
    CHECK_STR_CONTAINS(err.message, "bad.svg:2: r=\"1q\" is not a length");
    static const char xml[] = "<svg width='8' height='8'>\n<g>\n</svg>";
    CHECK_EQ(sr_render_svg(ctx, xml, sizeof xml - 1, NULL, &fb, NULL, &err), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(err.message, "<svg>:3: ");
    char missing[1024];
    snprintf(missing, sizeof missing, "%s/no_such.svg", sr_test_out_dir());
    CHECK(sr_render_svg_file(ctx, missing, NULL, &fb, NULL, &err) != SR_OK);
    CHECK_STR_CONTAINS(err.message, "no_such.svg: cannot open");
    CHECK(fb == NULL);
    /* A name with a newline and an escape sequence, and a style sheet's
     * tab and newline in a quoted value: control bytes come out as '?',
     * in failures and in warnings, as the model readers write them. */
    const char *name = "a\nb\033[2J.svg";
    CHECK_EQ(sr_render_svg(ctx, bad, sizeof bad - 1, &(sr_svg_desc){ .name = name }, &fb, NULL,
                           &err),
             SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(err.message, "a?b?[2J.svg:2: ");
    static const char warned[] = "<svg width='8' height='8'><style>rect { fil\tter\n: x }"
                                 "</style><rect width='4' height='4'/></svg>";
    sr_test_warnings w = { 0 };
    CHECK_EQ(sr_render_svg(ctx, warned, sizeof warned - 1,
                           &(sr_svg_desc){ .name = name, .warn = sr_test_collect_warning,
                                           .warn_user = &w },
                           &fb, NULL, &err),
             SR_OK);
    sr_destroy_framebuffer(ctx, fb);
    CHECK(w.count >= 1);
    CHECK_STR_CONTAINS(w.text, "a?b?[2J.svg:");
    for (const char *c = w.text; *c; c++) {
        CHECK((unsigned char)*c >= 0x20 && *c != 0x7f);
    }
    sr_destroy_context(ctx);
}

/* SVG draws nothing of a zero width, height or viewBox size, and a
 * negative one is an error: a failure naming the attribute, not a blank
 * 300 x 150 image, also when the size of the image is given; an <image>
 * of such a document draws nothing in its place. */
SR_TEST(zero_and_negative_sizes_are_failures)
{
    if (!sr_io_have_svg()) {
        SKIP("built without expat");
    }
    sr_context *ctx = make_ctx();
    REQUIRE(ctx);
    static const struct {
        const char *attrs, *want;
    } cases[] = {
        { "width='0' height='10'", "z.svg:2: width=\"0\" disables rendering" },
        { "width='10' height='0mm'", "z.svg:2: height=\"0mm\" disables rendering" },
        { "viewBox='0 0 0 0'", "z.svg:2: viewBox=\"0 0 0 0\" disables rendering" },
        { "viewBox='0 0 10 0'", "z.svg:2: viewBox=\"0 0 10 0\" disables rendering" },
        { "width='0' height='10' viewBox='0 0 10 10'", "z.svg:2: width=\"0\" disables" },
        { "width='-5' height='10'", "z.svg:2: width=\"-5\" is negative" },
        { "width='10' height='-1px'", "z.svg:2: height=\"-1px\" is negative" },
        { "viewBox='0 0 -10 10'", "z.svg:2: viewBox=\"0 0 -10 10\" needs four numbers" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char doc[256];
        int n = snprintf(doc, sizeof doc, "<?xml version='1.0'?>\n<svg %s><rect width='5' "
                                          "height='5'/></svg>", cases[i].attrs);
        for (int sized = 0; sized < 2; sized++) {
            sr_framebuffer *fb = (sr_framebuffer *)&fb;
            sr_io_error err;
            sr_svg_desc d = { .name = "z.svg", .width = sized ? 16 : 0, .height = sized ? 16 : 0 };
            CHECK_EQ(sr_render_svg(ctx, doc, (size_t)n, &d, &fb, NULL, &err), SR_BAD_FORMAT);
            CHECK(fb == NULL);
            CHECK_STR_CONTAINS(err.message, cases[i].want);
        }
    }
    /* 0% is no size of the root's own: the viewBox's stands in. */
    static const char pct[] = "<svg width='0%' height='10' viewBox='0 0 20 10'/>";
    sr_framebuffer *fb = NULL;
    sr_io_error err;
    CHECK_EQ(sr_render_svg(ctx, pct, sizeof pct - 1, NULL, &fb, NULL, &err), SR_OK);
    CHECK(fb && sr_framebuffer_width(fb) == 20 && sr_framebuffer_height(fb) == 10);
    sr_destroy_framebuffer(ctx, fb);
    fb = NULL;
    /* An SVG image of zero width: nothing where it would be, red under it
     * stays. */
    static const char img[] =
        "<svg xmlns='http://www.w3.org/2000/svg' width='4' height='4'>"
        "<rect width='4' height='4' fill='red'/><image width='4' height='4' "
        "href='data:image/svg+xml,%3Csvg xmlns=%22http://www.w3.org/2000/svg%22 width=%220%22 "
        "height=%224%22%3E%3Crect width=%224%22 height=%224%22 fill=%22blue%22/%3E%3C/svg%3E'/>"
        "</svg>";
    CHECK_EQ(sr_render_svg(ctx, img, sizeof img - 1, NULL, &fb, NULL, &err), SR_OK);
    if (fb) {
        const uint8_t *px = sr_framebuffer_pixels(fb);
        CHECK_EQ(px[0], 255);
        CHECK_EQ(px[2], 0);
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(bad_arguments_are_refused)
{
    sr_context *ctx = make_ctx();
    REQUIRE(ctx);
    sr_framebuffer *fb = NULL;
    sr_io_error err;
    const char doc[] = "<svg/>";
    CHECK_EQ(sr_render_svg(NULL, doc, 6, NULL, &fb, NULL, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_render_svg(ctx, doc, 6, NULL, NULL, NULL, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_render_svg(ctx, NULL, 6, NULL, &fb, NULL, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_render_svg(ctx, doc, 6, &(sr_svg_desc){ .width = 4 }, &fb, NULL, &err),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(err.message, "sr_svg_desc");
    CHECK_EQ(sr_render_svg(ctx, doc, 6, &(sr_svg_desc){ .scale = -1 }, &fb, NULL, &err),
             SR_INVALID_ARG);
    /* A background that is not finite has no color to clear to. */
    CHECK_EQ(sr_render_svg(ctx, doc, 6, &(sr_svg_desc){ .background = { 0, NAN, 0, 1 } }, &fb,
                           NULL, &err), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(err.message, "sr_svg_desc.background is not finite");
    CHECK(fb == NULL);
    CHECK_EQ(sr_render_svg_file(ctx, NULL, NULL, &fb, NULL, &err), SR_INVALID_ARG);
    CHECK(fb == NULL);
    sr_destroy_context(ctx);
}

/* sr_io_parse_color: the reader's own color syntax, alpha included. */
SR_TEST(parse_color_reads_css_colors)
{
    sr_rgba c = { 0 };
    CHECK_EQ(sr_io_parse_color("#1e90ff", &c), SR_OK);
    CHECK(c.r == 0x1e / 255.0f && c.g == 0x90 / 255.0f && c.b == 1.0f && c.a == 1.0f);
    sr_rgba named = { 0 };
    CHECK_EQ(sr_io_parse_color(" DodgerBlue ", &named), SR_OK);
    CHECK(memcmp(&named, &c, sizeof c) == 0);
    CHECK_EQ(sr_io_parse_color("#abc8", &c), SR_OK);
    CHECK(c.r == 0xaa / 255.0f && c.g == 0xbb / 255.0f && c.b == 0xcc / 255.0f &&
          c.a == 0x88 / 255.0f);
    CHECK_EQ(sr_io_parse_color("#00ff0080", &c), SR_OK);
    CHECK(c.r == 0 && c.g == 1.0f && c.b == 0 && c.a == 0x80 / 255.0f);
    CHECK_EQ(sr_io_parse_color("rgba(255, 0, 51, 0.25)", &c), SR_OK);
    CHECK(c.r == 1.0f && c.g == 0 && c.b == 51 / 255.0f && c.a == 0.25f);
    CHECK_EQ(sr_io_parse_color("rgb(100% 50% 0%)", &c), SR_OK);
    CHECK(c.r == 1.0f && c.g == 0.5f && c.b == 0 && c.a == 1.0f);
    CHECK_EQ(sr_io_parse_color("transparent", &c), SR_OK);
    CHECK(c.r == 0 && c.g == 0 && c.b == 0 && c.a == 0);
}

SR_TEST(parse_color_refuses_what_is_not_a_color)
{
    const char *bad[] = { "", "  ", "none", "currentColor", "url(#g)", "#12", "#12345",
                          "#ggg", "rgb(1, 2)", "rgb(1, 2, 3", "notacolor", "red blue" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        sr_rgba c = { 0.5f, 0.5f, 0.5f, 0.5f };
        CHECK_EQ(sr_io_parse_color(bad[i], &c), SR_BAD_FORMAT);
        CHECK(c.r == 0.5f && c.a == 0.5f);   /* untouched */
    }
    sr_rgba c;
    CHECK_EQ(sr_io_parse_color(NULL, &c), SR_INVALID_ARG);
    CHECK_EQ(sr_io_parse_color("red", NULL), SR_INVALID_ARG);
}
