/* test_svgz.c - gzip-compressed SVG (.svgz) through the real executable
 * (SR_CLI_PATH) and the library: a compressed copy of a tests/data/svg
 * drawing gives the same bytes as the drawing, under any name, as an
 * <image> and in a directory batch; a truncated or corrupt one is one line
 * and exit status 2; one that inflates past the reader's size limit (a
 * gzip bomb) is refused without being inflated to the end.  The test
 * compresses with zlib; skipped without it or without expat. */
#include "batch_cli.h"
#include "softrast_io.h"
#include "sr_test.h"

#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#ifdef SR_HAVE_ZLIB_TEST
#include <zlib.h>

/* gzip `n` bytes of data (then `zeros` zero bytes, streamed) into path. */
static bool write_gzip(const char *path, const void *data, size_t n, size_t zeros)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        return false;
    }
    z_stream z;
    memset(&z, 0, sizeof z);
    bool ok = deflateInit2(&z, 9, Z_DEFLATED, 16 + MAX_WBITS, 9, Z_DEFAULT_STRATEGY) == Z_OK;
    static unsigned char zero[1 << 20], out[1 << 16];
    z.next_in = (unsigned char *)data;
    z.avail_in = (uInt)n;
    int zr = Z_OK;
    while (ok && zr != Z_STREAM_END) {
        if (z.avail_in == 0 && zeros > 0) {
            size_t k = zeros < sizeof zero ? zeros : sizeof zero;
            z.next_in = zero;
            z.avail_in = (uInt)k;
            zeros -= k;
        }
        z.next_out = out;
        z.avail_out = sizeof out;
        zr = deflate(&z, z.avail_in == 0 && zeros == 0 ? Z_FINISH : Z_NO_FLUSH);
        ok = (zr == Z_OK || zr == Z_STREAM_END || zr == Z_BUF_ERROR) &&
             fwrite(out, 1, sizeof out - z.avail_out, f) == sizeof out - z.avail_out;
    }
    deflateEnd(&z);
    return fclose(f) == 0 && ok;
}
#endif

#ifdef SR_HAVE_ZLIB_TEST
#define HAVE_ZLIB 1
#else
#define HAVE_ZLIB 0
#endif

#define NEED_SVGZ()                                                    \
    do {                                                               \
        NEED_SVG();                                                    \
        if (!HAVE_ZLIB) {                                              \
            SKIP("the test compresses with zlib, not found");          \
        }                                                              \
    } while (0)

/* dir/NAME compressed from `src` (a file); false when it cannot be. */
static bool gzip_file(const char *src, const char *dst)
{
#ifdef SR_HAVE_ZLIB_TEST
    size_t n = 0;
    uint8_t *data = sr_test_read_file(src, &n);
    bool ok = data && write_gzip(dst, data, n, 0);
    free(data);
    return ok;
#else
    (void)src, (void)dst;
    return false;
#endif
}

SR_TEST(svgz_renders_the_same_bytes_as_its_svg)
{
    NEED_SVGZ();
    char dir[1200], src[1400], plain[1400], packed[1400], odd[1400], a[1400], b[1400], c[1400];
    fresh_dir("svgz_same", dir, sizeof dir);
    const char *drawings[] = { "gradients", "layers", "dashes", "blend" };
    for (size_t i = 0; i < sizeof drawings / sizeof drawings[0]; i++) {
        snprintf(src, sizeof src, "%s/data/svg/%s.svg", sr_test_src_dir(), drawings[i]);
        snprintf(plain, sizeof plain, "%s/%s.svg", dir, drawings[i]);
        snprintf(packed, sizeof packed, "%s/%s.svgz", dir, drawings[i]);
        /* known by its first bytes, not its name */
        snprintf(odd, sizeof odd, "%s/%s-packed.svg", dir, drawings[i]);
        size_t n = 0;
        uint8_t *text = sr_test_read_file(src, &n);
        REQUIRE(text);
        bool written = sr_test_write_file(plain, text, n) && gzip_file(src, packed) &&
                       gzip_file(src, odd);
        free(text);
        REQUIRE(written);
        snprintf(a, sizeof a, "%s/%s-a.png", dir, drawings[i]);
        snprintf(b, sizeof b, "%s/%s-b.png", dir, drawings[i]);
        snprintf(c, sizeof c, "%s/%s-c.png", dir, drawings[i]);
        run_result r;
        REQUIRE(run(ARGS("svg", plain, "-o", a), &r));
        CHECK_EQ(r.status, 0);
        REQUIRE(run(ARGS("svg", packed, "-o", b), &r));
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.err[0], 0);
        REQUIRE(run(ARGS("svg", odd, "-o", c), &r));
        CHECK_EQ(r.status, 0);
        if (!same_file_bytes(a, b) || !same_file_bytes(a, c)) {
            FAILF("%s: the .svgz's image differs from the .svg's", drawings[i]);
        }
    }
    /* -o by default: the input's name with .png for .svgz */
    snprintf(packed, sizeof packed, "%s/gradients.svgz", dir);
    snprintf(b, sizeof b, "%s/gradients.png", dir);
    run_result r;
    REQUIRE(run(ARGS("svg", packed), &r));
    CHECK_EQ(r.status, 0);
    snprintf(a, sizeof a, "%s/gradients-a.png", dir);
    CHECK(same_file_bytes(a, b));
}

/* An <image> of a compressed SVG draws as the plain one does, and a
 * directory batch finds .svgz files. */
SR_TEST(svgz_as_an_image_and_in_a_directory)
{
    NEED_SVGZ();
    char dir[1200], out[1200], src[1400], p[1400], a[1400], b[1400];
    fresh_dir("svgz_image", dir, sizeof dir);
    fresh_dir("svgz_image_out", out, sizeof out);
    snprintf(src, sizeof src, "%s/data/svg/gradients.svg", sr_test_src_dir());
    snprintf(p, sizeof p, "%s/inner.svgz", dir);
    REQUIRE(gzip_file(src, p));
    snprintf(p, sizeof p, "%s/inner.svg", dir);
    size_t n = 0;
    uint8_t *text = sr_test_read_file(src, &n);
    REQUIRE(text);
    bool written = sr_test_write_file(p, text, n);
    free(text);
    REQUIRE(written);
    const char *outer = "<svg xmlns=\"http://www.w3.org/2000/svg\" "
                        "xmlns:xlink=\"http://www.w3.org/1999/xlink\" width=\"64\" height=\"48\">\n"
                        "  <image x=\"4\" y=\"2\" width=\"56\" height=\"44\" xlink:href=\"%s\"/>\n"
                        "</svg>\n";
    char doc[600];
    snprintf(doc, sizeof doc, outer, "inner.svg");
    snprintf(a, sizeof a, "%s/plain.svg", dir);
    REQUIRE(write_text(a, doc));
    snprintf(doc, sizeof doc, outer, "inner.svgz");
    snprintf(b, sizeof b, "%s/packed.svg", dir);
    REQUIRE(write_text(b, doc));
    run_result r;
    REQUIRE(run(ARGS("svg", a, b, "--output-dir", out), &r));
    CHECK_EQ(r.status, 0);
    snprintf(a, sizeof a, "%s/plain.png", out);
    snprintf(b, sizeof b, "%s/packed.png", out);
    CHECK(same_file_bytes(a, b));
    /* a directory: its .svgz files (any case) below it too */
    fresh_dir("svgz_tree", dir, sizeof dir);
    fresh_dir("svgz_tree_out", out, sizeof out);
    snprintf(p, sizeof p, "%s/sub", dir);
    REQUIRE(mkdir(p, 0777) == 0);
    const char *names[] = { "a.svgz", "sub/b.SVGZ" }, *pngs[] = { "a.png", "sub/b.png" };
    for (int i = 0; i < 2; i++) {
        snprintf(p, sizeof p, "%s/%s", dir, names[i]);
        REQUIRE(gzip_file(src, p));
    }
    REQUIRE(run(ARGS("svg", dir, "--output-dir", out), &r));
    CHECK_EQ(r.status, 0);
    for (int i = 0; i < 2; i++) {
        snprintf(p, sizeof p, "%s/%s", out, pngs[i]);
        CHECK(file_exists(p));
    }
}

/* One line, exit status 2, no image: for each damaged .svgz. */
static void expect_refused(const char *path, const char *want)
{
    char out[1400];
    snprintf(out, sizeof out, "%s.png", path);
    remove(out);
    run_result r;
    REQUIRE(run(ARGS("svg", path, "-o", out), &r));
    CHECK_EQ(r.status, 2);
    CHECK_EQ(count_lines(r.err), 1);
    CHECK_STR_CONTAINS(r.err, want);
    CHECK(!file_exists(out));
}

SR_TEST(damaged_svgz_and_gzip_bomb_are_refused_in_one_line)
{
    NEED_SVGZ();
    char dir[1200], src[1400], good[1400], p[1400];
    fresh_dir("svgz_bad", dir, sizeof dir);
    snprintf(src, sizeof src, "%s/data/svg/gradients.svg", sr_test_src_dir());
    snprintf(good, sizeof good, "%s/good.svgz", dir);
    REQUIRE(gzip_file(src, good));
    size_t n = 0;
    uint8_t *z = sr_test_read_file(good, &n);
    REQUIRE(z && n > 64);
    snprintf(p, sizeof p, "%s/truncated.svgz", dir);
    FILE *f = fopen(p, "wb");
    REQUIRE(f);
    fwrite(z, 1, n / 2, f);
    fclose(f);
    expect_refused(p, "truncated.svgz: gzip-compressed data that does not read (it ends early");
    for (size_t i = 20; i < 40; i++) {
        z[i] ^= 0x5a;
    }
    snprintf(p, sizeof p, "%s/corrupt.svgz", dir);
    f = fopen(p, "wb");
    REQUIRE(f);
    fwrite(z, 1, n, f);
    fclose(f);
    free(z);
    expect_refused(p, "corrupt.svgz: gzip-compressed data that does not read (");
#ifdef SR_HAVE_ZLIB_TEST
    /* 300 MiB of zeros after the start of a document: a few hundred KiB */
    const char *head = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"8\" height=\"8\">";
    snprintf(p, sizeof p, "%s/bomb.svgz", dir);
    REQUIRE(write_gzip(p, head, strlen(head), (size_t)300 << 20));
    expect_refused(p, "bomb.svgz: gzip-compressed: more than the 256 MiB limit once "
                      "decompressed");
#endif
}
