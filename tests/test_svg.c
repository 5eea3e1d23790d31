/* test_svg.c - `softrast svg` end to end: small SVG files in tests/data/svg
 * rendered through the CLI and compared with references, crispEdges
 * against the exact pixel-centre rule, output sizing (--size, --scale,
 * viewBox letterboxing), one warning per unsupported name, and malformed
 * input: "FILE:LINE: what is wrong", exit status 2, no output file.
 * Skipped when the CLI was built without expat. */
#include "image_compare.h"
#include "softrast_io.h"
#include "sr_test.h"

#include <fcntl.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

/* Run the CLI (args after "softrast", NULL-terminated); stderr is kept in
 * err (NUL-terminated, truncated to n).  Returns the exit status. */
static int run_cli(const char *const *args, char *err, size_t n)
{
    char err_path[1024];
    snprintf(err_path, sizeof err_path, "%s/svg_stderr.txt", sr_test_out_dir());
    const char *argv[48];
    if (!sr_test_program_argv(SR_CLI_PATH, args, argv, sizeof argv / sizeof argv[0])) {
        return -1;
    }
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 2, err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid;
    int e = posix_spawn(&pid, argv[0], &fa, NULL, (char *const *)argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (e != 0) {
        return -1;
    }
    int status;
    if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status)) {
        return -1;
    }
    if (err && n) {
        err[0] = 0;
        FILE *f = fopen(err_path, "rb");
        if (f) {
            size_t got = fread(err, 1, n - 1, f);
            err[got] = 0;
            fclose(f);
        }
    }
    return WEXITSTATUS(status);
}

static bool have_svg(void)
{
    return sr_io_have_svg();
}

static const char *out_path(const char *name, char *buf, size_t n)
{
    snprintf(buf, n, "%s/%s", sr_test_out_dir(), name);
    return buf;
}

static bool write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        return false;
    }
    fputs(text, f);
    return fclose(f) == 0;
}

static uint8_t *read_png(const char *path, int *w, int *h)
{
    uint8_t *px = NULL;
    sr_io_error err;
    if (sr_read_png(path, NULL, w, h, &px, &err) != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "reading %s: %s", path, err.message);
        return NULL;
    }
    return px;
}

static void check_reference(const char *file, const char *ref, const char *const *extra)
{
    char in[1024], out[1024];
    snprintf(in, sizeof in, "%s/data/svg/%s", sr_test_src_dir(), file);
    out_path("svg_render.png", out, sizeof out);
    const char *args[16] = { "svg", in, "-o", out };
    int n = 4;
    for (int i = 0; extra[i]; i++) {
        args[n++] = extra[i];
    }
    args[n] = NULL;
    char err[1024];
    int status = run_cli(args, err, sizeof err);
    CHECK_EQ(status, 0);
    if (status != 0) {
        return;
    }
    int w, h;
    uint8_t *px = read_png(out, &w, &h);
    if (px) {
        sr_test_check_image(ref, px, w, h, 2, (long)w * h / 200);
        free(px);
    }
}

SR_TEST(svg_shapes_match_reference)
{
    if (!have_svg()) {
        SKIP("built without expat");
    }
    check_reference("shapes.svg", "svg_shapes",
                    (const char *[]){ "--scale", "2", "--background", "white", NULL });
}

SR_TEST(svg_nested_transforms_match_reference)
{
    if (!have_svg()) {
        SKIP("built without expat");
    }
    check_reference("transforms.svg", "svg_transforms", (const char *[]){ "--scale", "2", NULL });
}

SR_TEST(crisp_edges_fill_exactly_the_pixel_centres_inside)
{
    if (!have_svg()) {
        SKIP("built without expat");
    }
    char in[1024], out[1024];
    out_path("crisp.svg", in, sizeof in);
    out_path("crisp.png", out, sizeof out);
    REQUIRE(write_file(in, "<svg xmlns='http://www.w3.org/2000/svg' width='12' height='10'>\n"
                           "<rect x='2.3' y='3.7' width='5' height='4' shape-rendering='crispEdges'/>\n"
                           "</svg>\n"));
    REQUIRE(run_cli((const char *[]){ "svg", in, "-o", out, "--background", "white", NULL }, NULL, 0) == 0);
    int w, h;
    uint8_t *px = read_png(out, &w, &h);
    REQUIRE(px);
    CHECK_EQ(w, 12);
    CHECK_EQ(h, 10);
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            double cx = x + 0.5, cy = y + 0.5;
            bool in_rect = cx >= 2.3 && cx < 7.3 && cy >= 3.7 && cy < 7.7;
            CHECK_EQ(px[(y * w + x) * 4], in_rect ? 0 : 255);
        }
    }
    free(px);
}

SR_TEST(output_size_follows_size_and_scale_options)
{
    if (!have_svg()) {
        SKIP("built without expat");
    }
    char in[1024], out[1024];
    out_path("sized.svg", in, sizeof in);
    out_path("sized.png", out, sizeof out);
    /* a 10 x 10 viewBox in a 20 x 10 image: letterboxed, the square lands
     * in the middle 10 x 10 */
    REQUIRE(write_file(in, "<svg xmlns='http://www.w3.org/2000/svg' width='2in' height='1in' "
                           "viewBox='0 0 10 10'><rect width='10' height='10' fill='red' "
                           "shape-rendering='crispEdges'/></svg>"));
    int w, h;
    REQUIRE(run_cli((const char *[]){ "svg", in, "-o", out, NULL }, NULL, 0) == 0);
    uint8_t *px = read_png(out, &w, &h);
    REQUIRE(px);
    CHECK_EQ(w, 192);
    CHECK_EQ(h, 96);
    CHECK_EQ(px[(50 * w + 95) * 4 + 0], 255); /* inside the square */
    CHECK_EQ(px[(50 * w + 20) * 4 + 3], 0);   /* letterbox: transparent */
    free(px);
    REQUIRE(run_cli((const char *[]){ "svg", in, "-o", out, "--size", "40x40", NULL }, NULL, 0) == 0);
    px = read_png(out, &w, &h);
    REQUIRE(px);
    CHECK_EQ(w, 40);
    CHECK_EQ(h, 40);
    CHECK_EQ(px[(0 * w + 0) * 4 + 0], 255); /* the viewBox fills a square image */
    free(px);
    REQUIRE(run_cli((const char *[]){ "svg", in, "-o", out, "--scale", "0.5", NULL }, NULL, 0) == 0);
    px = read_png(out, &w, &h);
    REQUIRE(px);
    CHECK_EQ(w, 96);
    CHECK_EQ(h, 48);
    free(px);
    CHECK_EQ(run_cli((const char *[]){ "svg", in, "-o", out, "--size", "4x4", "--scale", "2", NULL },
                     NULL, 0), 2);
}

SR_TEST(unsupported_names_warn_once_each)
{
    if (!have_svg()) {
        SKIP("built without expat");
    }
    char in[1024], out[1024], err[4096];
    out_path("warn.svg", in, sizeof in);
    out_path("warn.png", out, sizeof out);
    REQUIRE(write_file(in, "<svg xmlns='http://www.w3.org/2000/svg' width='10' height='10'>\n"
                           "<foreignObject/>\n<foreignObject/>\n"
                           "<rect width='5' height='5' fill-paint='url(#g)'/>\n"
                           "<rect width='5' height='5' style='fill-paint: url(#g)'/>\n"
                           "<tref/>\n"
                           "</svg>\n"));
    CHECK_EQ(run_cli((const char *[]){ "svg", in, "-o", out, NULL }, err, sizeof err), 0);
    CHECK_STR_CONTAINS(err, "warn.svg:2: warning: unsupported element 'foreignObject' skipped");
    CHECK_STR_CONTAINS(err, "warn.svg:4: warning: unsupported property 'fill-paint' skipped");
    CHECK_STR_CONTAINS(err, "warn.svg:6: warning: unsupported element 'tref' skipped");
    int lines = 0;
    for (const char *p = err; *p; p++) {
        lines += *p == '\n';
    }
    CHECK_EQ(lines, 3);
    struct stat st;
    CHECK(stat(out, &st) == 0);
}

static void expect_input_error(const char *name, const char *svg, const char *want)
{
    char in[1024], out[1100], err[2048];
    out_path(name, in, sizeof in);
    snprintf(out, sizeof out, "%s.png", in);
    unlink(out);
    REQUIRE(write_file(in, svg));
    CHECK_EQ(run_cli((const char *[]){ "svg", in, "-o", out, NULL }, err, sizeof err), 2);
    CHECK_STR_CONTAINS(err, want);
    /* one line, and no output written */
    CHECK(strchr(err, '\n') == err + strlen(err) - 1);
    struct stat st;
    CHECK(stat(out, &st) != 0);
}

SR_TEST(malformed_input_is_reported_with_file_and_line)
{
    if (!have_svg()) {
        SKIP("built without expat");
    }
    expect_input_error("bad_xml.svg", "<svg width='10' height='10'>\n<rect width='5'>\n</svg>\n",
                       "bad_xml.svg:3: mismatched tag");
    expect_input_error("bad_len.svg", "<svg width='10' height='10'>\n<circle r='abc'/></svg>",
                       "bad_len.svg:2: r=\"abc\" is not a length");
    expect_input_error("bad_tr.svg",
                       "<svg width='10' height='10'>\n<g transform='rotate(1,2)'/></svg>",
                       "bad_tr.svg:2: transform=\"rotate(1,2)\" is malformed");
    expect_input_error("bad_root.svg", "<html/>", "bad_root.svg:1: the root element is <html>");
    expect_input_error("bad_size.svg", "<svg width='100000' height='10'/>", "outside 1..8192");
    /* said as such, not expat's "no element found" and "invalid token" */
    expect_input_error("empty.svg", "", "empty.svg:1: file is empty");
    /* gzip's first bytes: read as a .svgz (test_svgz.c), here a broken one */
    expect_input_error("gzip.svgz", "\x1f\x8b\x08\x08 gzip",
                       "gzip.svgz: gzip-compressed data that does not read (");
}

/* A zero width or height disables rendering in SVG: one line naming the
 * attribute and exit status 2, with --size too (as rsvg-convert), not a
 * blank image. */
SR_TEST(zero_size_is_refused_even_with_size)
{
    if (!have_svg()) {
        SKIP("built without expat");
    }
    expect_input_error("zero_w.svg", "<svg width='0' height='10'>\n<rect width='5'/></svg>",
                       "zero_w.svg:1: width=\"0\" disables rendering");
    expect_input_error("neg_h.svg", "\n<svg width='10' height='-3'/>",
                       "neg_h.svg:2: height=\"-3\" is negative");
    char in[1024], out[1100], err[2048];
    out_path("zero_vb.svg", in, sizeof in);
    snprintf(out, sizeof out, "%s.png", in);
    unlink(out);
    REQUIRE(write_file(in, "<svg viewBox='0 0 0 10'/>"));
    CHECK_EQ(run_cli((const char *[]){ "svg", in, "-o", out, "--size", "32x32", NULL }, err,
                     sizeof err),
             2);
    CHECK_STR_CONTAINS(err, "zero_vb.svg:1: viewBox=\"0 0 0 10\" disables rendering");
    CHECK(strchr(err, '\n') == err + strlen(err) - 1);
    struct stat st;
    CHECK(stat(out, &st) != 0);
}

/* Messages count lines as XML does: CR, LF and CR LF each end one, also
 * inside a tag and in UTF-16. */
SR_TEST(message_lines_count_every_line_end)
{
    if (!have_svg()) {
        SKIP("built without expat");
    }
    expect_input_error("lines_lf.svg",
                       "<svg width='10' height='10'>\n\n<rect\nwidth='1' height='1'/><g>\n"
                       "</g><circle r='abc'/></svg>",
                       "lines_lf.svg:5: r=\"abc\" is not a length");
    expect_input_error("lines_crlf.svg",
                       "<svg width='10'\r\nheight='10'>\r\n\r<rect width='1' height='1'/>\n\r"
                       "\r\n<circle\r\nr='abc'/></svg>",
                       "lines_crlf.svg:7: r=\"abc\" is not a length");
    static const char utf16[] = "\xFF\xFE<\0s\0v\0g\0>\0\r\0\n\0\r\0<\0c\0i\0r\0c\0l\0e\0"
                                " \0r\0=\0'\0x\0'\0/\0>\0<\0/\0s\0v\0g\0>\0";
    char in[1024], out[1100], err[2048];
    out_path("lines_utf16.svg", in, sizeof in);
    snprintf(out, sizeof out, "%s.png", in);
    FILE *f = fopen(in, "wb");
    REQUIRE(f);
    REQUIRE(fwrite(utf16, 1, sizeof utf16 - 1, f) == sizeof utf16 - 1);
    REQUIRE(fclose(f) == 0);
    CHECK_EQ(run_cli((const char *[]){ "svg", in, "-o", out, NULL }, err, sizeof err), 2);
    CHECK_STR_CONTAINS(err, "lines_utf16.svg:3: r=\"x\" is not a length");
}

/* Path data in error is drawn up to the error (SVG's error processing
 * for path data, tests/test_svg_syntax.c): a warning, and the image. */
SR_TEST(path_data_in_error_warns_and_draws)
{
    if (!have_svg()) {
        SKIP("built without expat");
    }
    char in[1024], out[1024], err[1024];
    out_path("bad_path.svg", in, sizeof in);
    out_path("bad_path.png", out, sizeof out);
    unlink(out);
    REQUIRE(write_file(in, "<svg width='10' height='10'>\n\n<path d='M 1 1 L 5 x'/>\n</svg>\n"));
    CHECK_EQ(run_cli((const char *[]){ "svg", in, "-o", out, NULL }, err, sizeof err), 0);
    CHECK_STR_CONTAINS(err, "bad_path.svg:3: warning: path data: expected a number at offset 10");
    struct stat st;
    CHECK(stat(out, &st) == 0);
}

SR_TEST(path_commands_all_parse_compact_forms)
{
    if (!have_svg()) {
        SKIP("built without expat");
    }
    char in[1024], out[1024], err[1024];
    out_path("compact.svg", in, sizeof in);
    out_path("compact.png", out, sizeof out);
    /* implicit repeats, no separators before signs and dots, exponents,
     * arc flags written together, every command in both cases */
    REQUIRE(write_file(in, "<svg xmlns='http://www.w3.org/2000/svg' width='40' height='40'>"
                           "<path d='M1,1L5-2.5.5.5l1e1,0h2H3v1V2c1,1,2,2,3,3C1 1 2 2 3 3"
                           "s1,1 2,2S1 1 2 2q1,1 2,2Q1 1 2 2t1,1T2 2a5,5 0 011,1A5 5 0 1 0 9 9z"
                           "m2,2 3,3 4,4Z'/></svg>"));
    CHECK_EQ(run_cli((const char *[]){ "svg", in, "-o", out, NULL }, err, sizeof err), 0);
    CHECK_EQ(strlen(err), 0);
}

SR_TEST(display_visibility_and_opacity_follow_svg)
{
    if (!have_svg()) {
        SKIP("built without expat");
    }
    char in[1024], out[1024];
    out_path("vis.svg", in, sizeof in);
    out_path("vis.png", out, sizeof out);
    /* columns 0-9: display none (with a visible child: still hidden);
     * 10-19: a hidden group with a visible child (drawn);
     * 20-29: group opacity 0.5 times fill-opacity 0.5 */
    REQUIRE(write_file(in, "<svg xmlns='http://www.w3.org/2000/svg' width='30' height='10'>"
                           "<g display='none'><rect width='10' height='10' visibility='visible'/></g>"
                           "<g visibility='hidden'><rect x='10' width='5' height='10'/>"
                           "<rect x='15' width='5' height='10' visibility='visible'/></g>"
                           "<g opacity='0.5'><rect x='20' width='10' height='10' fill='#000' "
                           "fill-opacity='0.5'/></g></svg>"));
    REQUIRE(run_cli((const char *[]){ "svg", in, "-o", out, "--background", "white", NULL }, NULL, 0) == 0);
    int w, h;
    uint8_t *px = read_png(out, &w, &h);
    REQUIRE(px);
    CHECK_EQ(px[(5 * w + 5) * 4], 255);
    CHECK_EQ(px[(5 * w + 12) * 4], 255);
    CHECK_EQ(px[(5 * w + 17) * 4], 0);
    CHECK_NEAR(px[(5 * w + 25) * 4], 191, 1); /* 25% black over white */
    free(px);
}
