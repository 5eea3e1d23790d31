/* test_svg_limits.c - the SVG reader bounds its work (softrast_io.h,
 * docs/robustness.md): a small document that asks for millions of points,
 * a wide round-joined stroke, a dash pattern far finer than its path, or
 * fills that cover the image hundreds of times over is refused by sr_render_svg with SR_TOO_LARGE after counted
 * work within the documented budgets (no clock: the operations are
 * counted), and by `softrast svg` with one line "FILE:LINE: ..." and exit
 * status 2, without an output file; arcs whose radii square to infinity or
 * to zero render.  Needs expat. */
#include "softrast_io.h"
#include "sr_test.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static char *grow_cat(char *s, size_t *len, const char *add)
{
    size_t n = strlen(add);
    s = realloc(s, *len + n + 1);
    memcpy(s + *len, add, n + 1);
    *len += n;
    return s;
}

/* head + `piece` count times + tail, malloc'd; its length in *len. */
static char *build_svg(const char *head, const char *piece, int count, const char *tail,
                       size_t *len)
{
    *len = 0;
    char *s = grow_cat(NULL, len, head);
    for (int i = 0; i < count; i++) {
        s = grow_cat(s, len, piece);
    }
    return grow_cat(s, len, tail);
}

/* The same, written to the output dir as `name`. */
static const char *write_svg(const char *name, const char *head, const char *piece, int count,
                             const char *tail)
{
    static char path[1024];
    snprintf(path, sizeof path, "%s/%s", sr_test_out_dir(), name);
    size_t len;
    char *s = build_svg(head, piece, count, tail, &len);
    FILE *f = fopen(path, "wb");
    if (f) {
        fwrite(s, 1, len, f);
        fclose(f);
    }
    free(s);
    return f ? path : NULL;
}

/* Runs `softrast svg IN -o OUT`; exit status (-1: did not run or died),
 * stderr in err. */
static int run_svg(const char *in, const char *out, char *err, size_t cap)
{
#ifndef SR_CLI_PATH
    (void)in, (void)out, (void)err, (void)cap;
    return -1;
#else
    int p[2];
    if (pipe(p) != 0) {
        return -1;
    }
    pid_t pid = fork();
    if (pid == 0) {
        dup2(p[1], STDERR_FILENO);
        close(p[0]);
        const char *argv[24];
        if (sr_test_program_argv(SR_CLI_PATH, (const char *[]){ "svg", in, "-o", out, NULL }, argv,
                                 sizeof argv / sizeof argv[0])) {
            execv(argv[0], (char *const *)argv);
        }
        _exit(127);
    }
    close(p[1]);
    size_t n = 0;
    ssize_t got;
    while ((got = read(p[0], err + n, cap - 1 - n)) > 0 || (got < 0 && errno == EINTR)) {
        n += got > 0 ? (size_t)got : 0;
        if (n == cap - 1) {
            break;
        }
    }
    err[n] = 0;
    close(p[0]);
    int st;
    if (pid < 0 || waitpid(pid, &st, 0) < 0) {
        return -1;
    }
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
#endif
}

static bool have_svg(void)
{
    const char *in = write_svg("limits_probe.svg", "<svg width='2' height='2'/>", "", 0, "");
    char out[1100], err[4096];
    snprintf(out, sizeof out, "%s/limits_probe.png", sr_test_out_dir());
    return sr_io_have_svg() && in && run_svg(in, out, err, sizeof err) == 0;
}

/* Refused by the library: SR_TOO_LARGE with `want` in the one line, no
 * image, and the work counted until then within the budgets, which are
 * the documented ones for this document of `len` bytes and a w x h image
 * - the bound on the time taken, whatever the machine. */
static sr_svg_info expect_refused_in_library(const char *name, const char *svg, size_t len,
                                             int w, int h, const char *want)
{
    sr_svg_info info = { 0 };
    sr_context *ctx = NULL;
    if (sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "no context");
        return info;
    }
    sr_framebuffer *fb = NULL;
    sr_io_error err;
    CHECK_EQ(sr_render_svg(ctx, svg, len, &(sr_svg_desc){ .name = name }, &fb, &info, &err),
             SR_TOO_LARGE);
    CHECK(fb == NULL);
    CHECK_STR_CONTAINS(err.message, name);
    CHECK_STR_CONTAINS(err.message, want);
    CHECK_EQ(info.points_budget, SR_SVG_POINTS_BASE + (double)SR_SVG_POINTS_PER_BYTE * len);
    CHECK_EQ(info.work_budget, (double)SR_SVG_WORK_PER_PIXEL * w * h + SR_SVG_WORK_BASE);
    CHECK(info.points_used <= info.points_budget);
    CHECK(info.work_used <= info.work_budget);
    CHECK(!info.over_layer_limit);   /* work, not memory */
    printf("  %-20s %zu bytes: refused after %.0f of %.0f points, %.0f of %.0f fill work\n",
           name, len, info.points_used, info.points_budget, info.work_used, info.work_budget);
    sr_destroy_context(ctx);
    return info;
}

/* Refused by the library (above) and by the command: status 2, `want` in
 * its one line, and no output file.  Returns what the library counted. */
static sr_svg_info expect_refused(const char *name, const char *head, const char *piece,
                                  int count, const char *tail, int w, int h, const char *want)
{
    size_t len;
    char *svg = build_svg(head, piece, count, tail, &len);
    sr_svg_info info = expect_refused_in_library(name, svg, len, w, h, want);
    free(svg);
    const char *in = write_svg(name, head, piece, count, tail);
    if (!in) {
        sr_test_fail(__FILE__, __LINE__, "cannot write %s", name);
        return info;
    }
    char out[1100], err[4096];
    snprintf(out, sizeof out, "%s/%s.png", sr_test_out_dir(), name);
    unlink(out);
    CHECK_EQ(run_svg(in, out, err, sizeof err), 2);
    CHECK_STR_CONTAINS(err, name);
    CHECK_STR_CONTAINS(err, want);
    CHECK(strchr(err, '\n') == err + strlen(err) - 1); /* one line */
    struct stat st;
    CHECK(stat(out, &st) != 0);
    return info;
}

SR_TEST(svg_path_with_millions_of_flattened_points_is_refused)
{
    if (!have_svg()) {
        SKIP("SVG is not available (built without expat)");
    }
    /* 3000 arcs of radius 1e5 px: 65536 points each as flattened. */
    expect_refused("limit_points.svg", "<svg width='100' height='100'><path d='M0 0",
                   " A1e5 1e5 0 1 1 1 0 A1e5 1e5 0 1 1 0 0", 1500, "'/></svg>", 100, 100,
                   "points when flattened");
}

SR_TEST(svg_path_with_too_many_subpaths_is_refused)
{
    if (!have_svg()) {
        SKIP("SVG is not available (built without expat)");
    }
    expect_refused("limit_subpaths.svg", "<svg width='100' height='100'><path d='", "M0 0 1 1",
                   20000, "'/></svg>", 100, 100, "subpaths");
}

SR_TEST(svg_fills_covering_the_image_hundreds_of_times_are_refused)
{
    if (!have_svg()) {
        SKIP("SVG is not available (built without expat)");
    }
    sr_svg_info info =
        expect_refused("limit_coverage.svg", "<svg width='2000' height='2000'>",
                       "<rect width='2000' height='2000' fill='red'/>", 400, "</svg>", 2000,
                       2000, "pixel operations");
    /* Stopped at the budget: one more rectangle (its box and rows) would
     * have passed it. */
    CHECK(info.work_used + 2000.0 * 2000 + 4 * 2001 > info.work_budget);
    /* Edges that each cross every row: the cost is in the rows, not the box. */
    expect_refused("limit_rows.svg", "<svg width='1000' height='1000'><polygon points='",
                   "0,0 1,1000 ", 40000, "'/></svg>", 1000, 1000, "pixel operations");
}

SR_TEST(svg_wide_round_stroke_over_a_long_path_is_refused_before_outlining)
{
    if (!have_svg()) {
        SKIP("SVG is not available (built without expat)");
    }
    expect_refused("limit_stroke.svg",
                   "<svg width='100' height='100'><polyline fill='none' stroke='red' "
                   "stroke-width='5000' stroke-linejoin='round' points='",
                   "0,0 1,1 ", 5000, "'/></svg>", 100, 100, "stroke: the outline");
}

SR_TEST(svg_dash_pattern_finer_than_the_point_budget_is_refused_before_cutting)
{
    if (!have_svg()) {
        SKIP("SVG is not available (built without expat)");
    }
    /* a million dashes along one line across the image, of a 100-byte
     * document (only the dashes that can reach the image count) */
    expect_refused("limit_dash.svg",
                   "<svg width='100' height='100'><line x2='100' stroke='red' "
                   "stroke-dasharray='0.0001'/></svg>",
                   "", 0, "", 100, 100, "stroke-dasharray: a pattern of period 0.0002");
}

SR_TEST(svg_many_shapes_beyond_the_document_point_budget_are_refused)
{
    if (!have_svg()) {
        SKIP("SVG is not available (built without expat)");
    }
    /* Each circle of radius 1e5 flattens to about 2200 points, all off the
     * image (cheap to fill): only the point count stops them. */
    sr_svg_info info = expect_refused("limit_total.svg", "<svg width='100' height='100'>",
                                      "<circle cx='1.5e5' r='1e5'/>", 4000, "</svg>", 100, 100,
                                      "points in all");
    /* Stopped at the budget: one more circle, flattened then filled (about
     * 2 x 2200 points), would have passed it. */
    CHECK(info.points_used + 2 * 2300 > info.points_budget);
}

SR_TEST(svg_arcs_with_radii_that_square_out_of_range_render)
{
    if (!have_svg()) {
        SKIP("SVG is not available (built without expat)");
    }
    const char *in = write_svg(
        "arc_radii.svg",
        "<svg width='20' height='20'><path stroke='blue' fill='red' d='M10 10 A1e300 1e300 720 0 1 "
        "20 20 M1 1 A1e-300 1e-300 0 0 0 5 5 z'/>"
        "<path d='M1 1 L2 2' stroke='blue' stroke-width='1e-17' stroke-linecap='round'/></svg>",
        "", 0, "");
    REQUIRE(in);
    char out[1100], err[4096];
    snprintf(out, sizeof out, "%s/arc_radii.png", sr_test_out_dir());
    CHECK_EQ(run_svg(in, out, err, sizeof err), 0);
    CHECK_EQ(err[0], 0);
}

SR_TEST(svg_warnings_stop_after_64_names)
{
    if (!have_svg()) {
        SKIP("SVG is not available (built without expat)");
    }
    char *elems = NULL;
    size_t len = 0;
    for (int i = 0; i < 300; i++) {
        char e[64];
        snprintf(e, sizeof e, "<unknown%d/>\n", i);
        elems = grow_cat(elems, &len, e);
    }
    const char *in = write_svg("many_warnings.svg", "<svg width='4' height='4'>\n", elems, 1,
                               "</svg>\n");
    free(elems);
    REQUIRE(in);
    char out[1100], err[16384];
    snprintf(out, sizeof out, "%s/many_warnings.png", sr_test_out_dir());
    CHECK_EQ(run_svg(in, out, err, sizeof err), 0);
    int lines = 0;
    for (const char *c = err; *c; c++) {
        lines += *c == '\n';
    }
    CHECK_EQ(lines, 65);
    CHECK_STR_CONTAINS(err, "many_warnings.svg:66: warning: more unsupported names; further "
                            "warnings not shown");
}

/* The longest line in `s`, in bytes. */
static size_t longest_line(const char *s)
{
    size_t best = 0;
    while (*s) {
        size_t n = strcspn(s, "\n");
        best = n > best ? n : best;
        s += n + (s[n] != 0);
    }
    return best;
}

/* A warning or an error quotes an attribute value cut short: a
 * 100000-number tableValues or a 4097-number kernelMatrix gives one short
 * line that still names FILE:LINE and the attribute. */
SR_TEST(svg_messages_quote_huge_values_cut_short)
{
    if (!have_svg()) {
        SKIP("SVG is not available (built without expat)");
    }
    char *table = NULL, *kernel = NULL;
    size_t tlen = 0, klen = 0;
    table = grow_cat(table, &tlen, "<filter id='f'>\n<feComponentTransfer><feFuncR type='table' "
                                   "tableValues='");
    for (int i = 0; i < 100000; i++) {
        table = grow_cat(table, &tlen, i ? " 0.5" : "0.5");
    }
    table = grow_cat(table, &tlen, "'/></feComponentTransfer>\n");
    kernel = grow_cat(kernel, &klen, "<feConvolveMatrix order='64' kernelMatrix='");
    for (int i = 0; i < 4097; i++) {
        kernel = grow_cat(kernel, &klen, " 1");
    }
    kernel = grow_cat(kernel, &klen, "'/>\n</filter>\n");
    table = grow_cat(table, &tlen, kernel);
    free(kernel);
    const char *in = write_svg("huge_values.svg", "<svg width='4' height='4'>\n", table, 1,
                               "<rect width='4' height='4' filter='url(#f)'/></svg>\n");
    free(table);
    REQUIRE(in);
    static char err[65536];
    char out[1100];
    snprintf(out, sizeof out, "%s/huge_values.png", sr_test_out_dir());
    CHECK_EQ(run_svg(in, out, err, sizeof err), 0);
    CHECK(longest_line(err) < 1200); /* the path of the output dir and a short message */
    CHECK_STR_CONTAINS(err, "huge_values.svg:3: warning: unsupported tableValues '0.5 0.5 ");
    CHECK_STR_CONTAINS(err, "huge_values.svg:4: warning: unsupported feConvolveMatrix");
    CHECK_STR_CONTAINS(err, " 1 1...' skipped");

    /* An error, cut before a two-byte character it would split: "x" and
     * 29 of them fill 59 bytes, and the 30th does not fit in 60. */
    char tr[512] = "<g transform='x";
    for (int i = 0; i < 100; i++) {
        strcat(tr, "\xc3\xa9");
    }
    strcat(tr, "'/>\n");
    in = write_svg("huge_transform.svg", "<svg width='4' height='4'>\n", tr, 1, "</svg>\n");
    REQUIRE(in);
    snprintf(out, sizeof out, "%s/huge_transform.png", sr_test_out_dir());
    CHECK_EQ(run_svg(in, out, err, sizeof err), 2);
    char want[256] = "huge_transform.svg:2: transform=\"x";
    for (int i = 0; i < 29; i++) {
        strcat(want, "\xc3\xa9");
    }
    strcat(want, "...\" is malformed");
    CHECK_STR_CONTAINS(err, want);
    CHECK(longest_line(err) < 1200);
}

/* Group opacity, masks and clip paths draw into layers of the image's
 * size, nested up to 8 deep: sr_svg_desc.max_layer_bytes bounds what
 * they hold at once (6 bytes a pixel each, 4 more for a composite), and `softrast svg` gives
 * them what SR_MEMORY_LIMIT leaves, so a deeply nested drawing is
 * refused in one line instead of allocating past the limit. */
SR_TEST(svg_layers_nested_past_the_memory_left_are_refused)
{
    if (!have_svg()) {
        SKIP("built without expat or the softrast tool");
    }
    static const char head[] = "<svg xmlns='http://www.w3.org/2000/svg' width='64' height='64'>"
                               "<clipPath id='c'><rect width='50' height='50'/></clipPath>";
    static const char piece[] = "<g opacity='0.9' clip-path='url(#c)'>";
    char tail[512] = "<rect width='40' height='40' fill='red'/>";
    for (int i = 0; i < 8; i++) {
        strcat(tail, "</g>");
    }
    strcat(tail, "</svg>");
    size_t len;
    char *svg = build_svg(head, piece, 8, tail, &len);
    const uint64_t layer = 64 * 64 * 6, composite = 64 * 64 * 4;
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    sr_framebuffer *fb = NULL, *unlimited = NULL;
    sr_io_error err;
    sr_svg_info info;
    CHECK_EQ(sr_render_svg(ctx, svg, len, &(sr_svg_desc){ .name = "nested.svg",
                                                          .max_layer_bytes = 3 * layer + composite },
                           &fb, &info, &err),
             SR_TOO_LARGE);
    CHECK(fb == NULL);
    CHECK(info.over_layer_limit);   /* memory, as a caller tells it from a work budget */
    CHECK_STR_CONTAINS(err.message, "nested.svg:1: layers nested 4 deep (group opacity, masks, "
                                    "clip paths, patterns) need about 112 KiB besides the image, "
                                    "more than the 88 KiB left for them");
    /* Enough for the eight: the same pixels as without a limit. */
    CHECK_EQ(sr_render_svg(ctx, svg, len, &(sr_svg_desc){ .max_layer_bytes = 8 * layer + composite }, &fb,
                           &info, &err),
             SR_OK);
    CHECK(!info.over_layer_limit);
    CHECK_EQ(sr_render_svg(ctx, svg, len, &(sr_svg_desc){ 0 }, &unlimited, NULL, &err), SR_OK);
    if (fb && unlimited) {
        CHECK(memcmp(sr_framebuffer_pixels(fb), sr_framebuffer_pixels(unlimited),
                     64 * 64 * 4) == 0);
        CHECK(sr_framebuffer_pixels(fb)[(10 * 64 + 10) * 4 + 3] > 0); /* drawn */
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_framebuffer(ctx, unlimited);
    sr_destroy_context(ctx);
    free(svg);

    const char *in = write_svg("nested_layers.svg", head, piece, 8, tail);
    REQUIRE(in);
    char out[1100], msg[4096];
    snprintf(out, sizeof out, "%s/nested_layers.png", sr_test_out_dir());
    unlink(out);
    REQUIRE(setenv("SR_MEMORY_LIMIT", "100000", 1) == 0);
    CHECK_EQ(run_svg(in, out, msg, sizeof msg), 2);
    CHECK_STR_CONTAINS(msg, "nested_layers.svg:1: layers nested 4 deep");
    CHECK_STR_CONTAINS(msg, "more than the 98 KiB left for them");
    CHECK(strchr(msg, '\n') == msg + strlen(msg) - 1);
    struct stat st;
    CHECK(stat(out, &st) != 0);
    REQUIRE(setenv("SR_MEMORY_LIMIT", "1M", 1) == 0);
    CHECK_EQ(run_svg(in, out, msg, sizeof msg), 0);
    CHECK(stat(out, &st) == 0);
    unsetenv("SR_MEMORY_LIMIT");
}
