/*
 * test_special_files.c - io stage: every reader entry point (sr_load_mesh by
 * extension, by content and on the way to Assimp, an OBJ's mtllib,
 * sr_read_png and sr_open_file) given a FIFO, a device or a directory
 * instead of a file.
 * Each must answer at once with "FILE: not a regular file" (or "is a
 * directory"), never wait: opening a FIFO for reading blocks until a writer
 * comes, so a reader that opens before it checks would hang here.  An alarm
 * ends a hung test with a message rather than leaving it to CTest's timeout.
 */
#include "softrast_io.h"
#include "sr_test.h"

#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Seconds any one test may take; the readers answer in microseconds. */
#define HANG_SECONDS 10

static void on_alarm(int sig)
{
    (void)sig;
    static const char msg[] = "test_special_files: a reader waited on a FIFO (no answer "
                              "within 10 s)\n";
    ssize_t ignored = write(2, msg, sizeof msg - 1);
    (void)ignored;
    _exit(1);
}

static void start_watchdog(void)
{
    signal(SIGALRM, on_alarm);
    alarm(HANG_SECONDS);
}

static void stop_watchdog(void)
{
    alarm(0);
}

/* A fresh FIFO named `name` in the output directory (nobody writes to it). */
static const char *make_fifo(const char *name)
{
    static char path[1024];
    snprintf(path, sizeof path, "%s/%s", sr_test_out_dir(), name);
    unlink(path);
    if (mkfifo(path, 0644) != 0) {
        return NULL;
    }
    return path;
}

static bool write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        return false;
    }
    bool ok = fputs(text, f) >= 0;
    return fclose(f) == 0 && ok;
}

static bool mesh_is_zero(const sr_mesh *m)
{
    static const sr_mesh zero;
    return memcmp(m, &zero, sizeof zero) == 0;
}

/* sr_load_mesh(path, format) must fail with SR_IO_ERROR and "NAME: not a
 * regular file", leaving the mesh zeroed. */
static void expect_not_regular(const char *path, sr_model_format format)
{
    sr_mesh m;
    sr_io_error err = { { 0 } };
    sr_result r =
        sr_load_mesh(sr_test_ctx(), path, &(sr_load_desc){ .format = format }, &m, &err);
    if (r != SR_IO_ERROR) {
        sr_test_fail(__FILE__, __LINE__, "%s (format %d): result %d, message \"%s\"", path,
                     (int)format, (int)r, err.message);
    }
    char want[1100];
    snprintf(want, sizeof want, "%s: not a regular file", path);
    CHECK_STR_CONTAINS(err.message, want);
    CHECK(mesh_is_zero(&m));
    if (r == SR_OK) {
        sr_destroy_mesh(sr_test_ctx(), &m);
    }
}

SR_TEST(a_fifo_named_like_each_model_format_is_refused_without_waiting)
{
    static const char *const names[] = { "fifo.obj", "fifo.ply", "fifo.stl", "fifo.off",
                                         "fifo" };
    start_watchdog();
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        const char *path = make_fifo(names[i]);
        REQUIRE(path);
        /* By extension, by content (the last two), and with the format named. */
        expect_not_regular(path, SR_FORMAT_AUTO);
        expect_not_regular(path, SR_FORMAT_OBJ);
        expect_not_regular(path, SR_FORMAT_PLY);
        expect_not_regular(path, SR_FORMAT_STL);
        expect_not_regular(path, SR_FORMAT_ASSIMP);
        unlink(path);
    }
    stop_watchdog();
}

SR_TEST(a_device_is_refused_as_a_model)
{
    start_watchdog();
    /* /dev/zero never ends and /dev/null is empty: neither is a model file. */
    expect_not_regular("/dev/zero", SR_FORMAT_AUTO);
    expect_not_regular("/dev/zero", SR_FORMAT_OBJ);
    expect_not_regular("/dev/null", SR_FORMAT_STL);
    stop_watchdog();
}

SR_TEST(an_mtllib_that_is_a_fifo_is_skipped_like_a_missing_one)
{
    start_watchdog();
    const char *fifo = make_fifo("fifo_colors.mtl");
    REQUIRE(fifo);
    char obj[1024];
    snprintf(obj, sizeof obj, "%s/fifo_mtllib.obj", sr_test_out_dir());
    REQUIRE(write_text(obj, "mtllib fifo_colors.mtl\nusemtl red\n"
                            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    sr_mesh m;
    sr_io_error err = { { 0 } };
    sr_result r = sr_load_mesh(sr_test_ctx(), obj, NULL, &m, &err);
    if (r != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "%s", err.message);
    }
    REQUIRE(r == SR_OK);
    CHECK_EQ(m.triangle_count, 1);
    CHECK(m.colors == NULL);    /* no material read, as for a missing MTL */
    sr_destroy_mesh(sr_test_ctx(), &m);
    unlink(fifo);
    stop_watchdog();
}

static sr_result read_png_plain(const char *path, int *w, int *h, uint8_t **px, sr_io_error *err)
{
    return sr_read_png(path, NULL, w, h, px, err);
}

SR_TEST(a_fifo_or_a_device_is_refused_as_an_image)
{
    start_watchdog();
    const char *fifo = make_fifo("fifo.png");
    REQUIRE(fifo);
    typedef sr_result (*read_fn)(const char *, int *, int *, uint8_t **, sr_io_error *);
    const struct {
        read_fn read;
        const char *kind;
    } readers[] = { { read_png_plain, "a PNG file" },
                    { sr_read_jpeg, "a JPEG file" },
                    { sr_read_image, "an image file" } };
    const char *paths[] = { fifo, "/dev/zero" };
    for (size_t k = 0; k < sizeof readers / sizeof readers[0]; k++) {
        for (size_t i = 0; i < sizeof paths / sizeof paths[0]; i++) {
            int w = -1, h = -1;
            uint8_t *px = (uint8_t *)&w;
            sr_io_error err = { { 0 } };
            CHECK_EQ(readers[k].read(paths[i], &w, &h, &px, &err), SR_IO_ERROR);
            char want[1100];
            snprintf(want, sizeof want, "%s: not a regular file", paths[i]);
            CHECK_STR_CONTAINS(err.message, want);
            CHECK(px == NULL);
            CHECK_EQ(w, 0);
            CHECK_EQ(h, 0);
        }
        /* A directory keeps its own message. */
        int w, h;
        uint8_t *px;
        sr_io_error err = { { 0 } };
        char want[64];
        snprintf(want, sizeof want, "is a directory, not %s", readers[k].kind);
        CHECK_EQ(readers[k].read(sr_test_out_dir(), &w, &h, &px, &err), SR_IO_ERROR);
        CHECK_STR_CONTAINS(err.message, want);
    }
    unlink(fifo);
    stop_watchdog();
}

/* sr_open_file, the readers' open for a program's own inputs: a FIFO, a
 * device and a directory refused at once, a regular file opened with its
 * size, and missing outputs refused. */
SR_TEST(open_file_takes_only_a_regular_file)
{
    start_watchdog();
    const char *fifo = make_fifo("fifo.txt");
    REQUIRE(fifo);
    const char *paths[] = { fifo, "/dev/zero", sr_test_out_dir() };
    const char *needles[] = { "not a regular file", "not a regular file",
                              "is a directory, not an event script" };
    for (size_t i = 0; i < 3; i++) {
        FILE *f = stdin;
        unsigned long long size = 7;
        sr_io_error err = { { 0 } };
        CHECK_EQ(sr_open_file(paths[i], "an event script", &f, &size, &err), SR_IO_ERROR);
        CHECK_STR_CONTAINS(err.message, paths[i]);
        CHECK_STR_CONTAINS(err.message, needles[i]);
        CHECK(f == NULL);
        CHECK_EQ(size, 0);
    }
    unlink(fifo);
    stop_watchdog();

    char path[1100];
    snprintf(path, sizeof path, "%s/open_file.txt", sr_test_out_dir());
    REQUIRE(write_text(path, "wheel 2\n"));
    FILE *f = NULL;
    unsigned long long size = 0;
    sr_io_error err;
    REQUIRE(sr_open_file(path, "an event script", &f, &size, &err) == SR_OK);
    CHECK_EQ(size, 8);
    char line[16] = { 0 };
    CHECK(f && fgets(line, sizeof line, f) && strcmp(line, "wheel 2\n") == 0);
    fclose(f);
    CHECK_EQ(sr_open_file(path, "an event script", NULL, &size, &err), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(err.message, "f is NULL");
    CHECK_EQ(sr_open_file(path, "an event script", &f, NULL, &err), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(err.message, "size is NULL");
    CHECK(f == NULL);
    CHECK_EQ(sr_open_file(NULL, "an event script", &f, &size, &err), SR_INVALID_ARG);
}
