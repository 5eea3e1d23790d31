/* test_svg_batch.c - `softrast svg` over many drawings in one process:
 * the real executable (SR_CLI_PATH) given several files, a directory
 * tree or a --batch list (from standard input too), its images compared
 * byte for byte with one `softrast svg` per file, and its --log read
 * back.  Drawings are tests/data/svg's and small ones written by the
 * test, with a broken one among them.  Skipped when the CLI was built
 * without expat. */
#include "batch_cli.h"
#include "sr_test.h"

#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* A small drawing: a square of `color` on a 16 x 16 canvas. */
static bool write_svg(const char *path, const char *color)
{
    char text[512];
    snprintf(text, sizeof text,
             "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"16\" height=\"16\">\n"
             "  <rect x=\"2\" y=\"3\" width=\"11\" height=\"9\" fill=\"%s\"/>\n"
             "</svg>\n", color);
    return write_text(path, text);
}

/* A drawing that ends in the middle of an element: line 2 is bad. */
static bool write_broken_svg(const char *path)
{
    return write_text(path, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"16\" height=\"16\">\n"
                            "  <rect x=\"2\" y=\n");
}

/* Three drawings in dir, the middle one broken; their paths. */
enum { DRAWINGS = 3, BROKEN = 1 };
static bool write_drawings(const char *dir, char paths[DRAWINGS][1200])
{
    const char *names[DRAWINGS] = { "a_red.svg", "b_broken.svg", "c_blue.svg" };
    for (int i = 0; i < DRAWINGS; i++) {
        snprintf(paths[i], 1200, "%s/%s", dir, names[i]);
        bool ok = i == BROKEN ? write_broken_svg(paths[i])
                              : write_svg(paths[i], i == 0 ? "#c03" : "navy");
        if (!ok) {
            FAILF("cannot write %s", paths[i]);
            return false;
        }
    }
    return true;
}

/* The drawing thread counts the batch tests run: one, and more than one
 * drawing at a time, also more than the slots' inputs. */
enum { THREAD_RUNS = 3 };
static const char *const thread_counts[THREAD_RUNS] = { "1", "2", "4" };

/* Every drawing of tests/data/svg, as a directory given whole: each
 * image the batch writes is the same bytes as the one `softrast svg IN
 * -o OUT` writes, at two sizes, with the default thread count (by
 * SR_THREADS too) and with 1, 2 and 4 drawing threads; the drawings that
 * fail alone fail in the batch too, and the exit status says some
 * failed. */
SR_TEST(batch_of_test_drawings_matches_one_process_per_file)
{
    NEED_SVG();
    char src[1024], out[1200], out1[1200], single[1200], outs[THREAD_RUNS][1200];
    snprintf(src, sizeof src, "%s/data/svg", sr_test_src_dir());
    fresh_dir("svg_each", out, sizeof out);
    fresh_dir("svg_each_t1", out1, sizeof out1);
    fresh_dir("svg_single", single, sizeof single);
    char log[1300];
    snprintf(log, sizeof log, "%s/run.jsonl", out);
    run_result r;
    REQUIRE(run(ARGS("svg", src, "--output-dir", out, "--scale", "2", "--log", log), &r));
    int batch_status = r.status;
    /* Several threads draw and write the images; the records still come
     * in the order of the list. */
    record recs[64];
    int logged = read_log(log, recs, 64);
    for (int i = 0; i < logged && i < 64; i++) {
        CHECK_EQ((int)recs[i].index, i);
    }
    REQUIRE(run_env(ARGS("svg", src, "--output-dir", out1, "--scale", "2"), ENV("SR_THREADS=1"),
                    NULL, &r));
    CHECK_EQ(r.status, batch_status);
    for (int t = 0; t < THREAD_RUNS; t++) {
        char name[64];
        snprintf(name, sizeof name, "svg_each_threads%s", thread_counts[t]);
        fresh_dir(name, outs[t], sizeof outs[t]);
        REQUIRE(run(ARGS("svg", src, "--output-dir", outs[t], "--scale", "2", "--threads",
                         thread_counts[t]), &r));
        CHECK_EQ(r.status, batch_status);
    }
    DIR *d = opendir(src);
    REQUIRE(d);
    int compared = 0, failed = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        size_t n = strlen(e->d_name);
        if (n < 5 || strcmp(e->d_name + n - 4, ".svg") != 0) {
            continue;
        }
        char in[2048], want[2048], got[2048], got1[2048];
        snprintf(in, sizeof in, "%s/%s", src, e->d_name);
        snprintf(want, sizeof want, "%s/%.*s.png", single, (int)n - 4, e->d_name);
        snprintf(got, sizeof got, "%s/%.*s.png", out, (int)n - 4, e->d_name);
        snprintf(got1, sizeof got1, "%s/%.*s.png", out1, (int)n - 4, e->d_name);
        run_result one;
        REQUIRE(run(ARGS("svg", in, "-o", want, "--scale", "2"), &one));
        if (one.status != 0) {
            CHECK(!file_exists(got));   /* a drawing that fails alone fails here too */
            failed++;
            continue;
        }
        if (!same_file_bytes(want, got) || !same_file_bytes(want, got1)) {
            FAILF("%s: the batch's image is not the single run's", e->d_name);
        }
        for (int t = 0; t < THREAD_RUNS; t++) {
            char got_t[4096];
            snprintf(got_t, sizeof got_t, "%s/%.*s.png", outs[t], (int)n - 4, e->d_name);
            if (!same_file_bytes(want, got_t)) {
                FAILF("%s: the batch's image on %s threads is not the single run's",
                      e->d_name, thread_counts[t]);
            }
        }
        compared++;
    }
    closedir(d);
    CHECK(compared >= 20);
    CHECK_EQ(logged, compared + failed);
    CHECK_EQ(batch_status, failed ? 3 : 0);
    /* And at a fixed size, by a list on standard input. */
    char list[1200], sized[1200], one_in[1200], one_out[1200], want[1300];
    snprintf(list, sizeof list, "%s/svg_list.txt", sr_test_out_dir());
    snprintf(one_in, sizeof one_in, "%s/gradients.svg", src);
    snprintf(one_out, sizeof one_out, "%s/gradients.png", fresh_dir("svg_sized", sized,
                                                                    sizeof sized));
    char text[3000];
    snprintf(text, sizeof text, "%s/shapes.svg\n%s\n", src, one_in);
    REQUIRE(write_text(list, text));
    REQUIRE(run_env(ARGS("svg", "--batch", "-", "--output-dir", sized, "--size", "40x30",
                         "--background", "white"), NO_ENV, list, &r));
    CHECK_EQ(r.status, 0);
    snprintf(want, sizeof want, "%s/gradients_single.png", single);
    REQUIRE(run(ARGS("svg", one_in, "-o", want, "--size", "40x30", "--background", "white"),
                &r));
    CHECK(same_file_bytes(want, one_out));
}

/* A list with failures between its drawings, on 1, 2 and 4 drawing
 * threads: the same lines on stderr in the order of the list (a bad
 * drawing, a missing file, a drawing's warnings, an output that is a
 * directory), the same log records in that order, the skipped output left
 * alone, each image the same bytes as one `softrast svg` of it, exit
 * status 3 on every thread count. */
enum { MIXED = 12 };
typedef enum mixed_kind { GOOD, BROKEN_FILE, MISSING, WARNED, OUTPUT_DIR, SKIPPED } mixed_kind;
static const struct {
    const char *name;
    mixed_kind kind;
} mixed[MIXED] = {
    { "00_red.svg", GOOD },      { "01_broken.svg", BROKEN_FILE }, { "02_gone.svg", MISSING },
    { "03_text.svg", WARNED },   { "04_blue.svg", OUTPUT_DIR },    { "05_green.svg", GOOD },
    { "06_bad.svg", BROKEN_FILE }, { "07_navy.svg", GOOD },        { "08_kept.svg", SKIPPED },
    { "09_teal.svg", GOOD },     { "10_gray.svg", GOOD },          { "11_gone.svg", MISSING },
};

static bool write_mixed(const char *dir, char *list, size_t size)
{
    static const char *const colors[] = { "#c03", "navy", "teal", "gray", "olive", "purple" };
    size_t used = 0;
    for (int i = 0; i < MIXED; i++) {
        char path[1300];
        snprintf(path, sizeof path, "%s/%s", dir, mixed[i].name);
        bool ok = true;
        if (mixed[i].kind == BROKEN_FILE) {
            ok = write_broken_svg(path);
        } else if (mixed[i].kind == WARNED) {
            ok = write_text(path, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"16\" "
                                  "height=\"16\">\n  <foreignObject width=\"1\" height=\"9\"/>\n"
                                  "  <rect width=\"5\" height=\"5\"/>\n</svg>\n");
        } else if (mixed[i].kind != MISSING) {
            ok = write_svg(path, colors[i % 6]);
        }
        if (!ok) {
            FAILF("cannot write %s", path);
            return false;
        }
        /* The blue drawing's output is the drawings' directory. */
        int n = mixed[i].kind == OUTPUT_DIR
                    ? snprintf(list + used, size - used, "%s\t%s\n", path, dir)
                    : snprintf(list + used, size - used, "%s\n", path);
        if (n < 0 || (size_t)n >= size - used) {
            return false;
        }
        used += (size_t)n;
    }
    return used < size;
}

SR_TEST(failures_between_drawings_report_in_list_order_on_any_thread_count)
{
    NEED_SVG();
    char dir[1200], single[1200], list[1300], text[MIXED * 1400];
    fresh_dir("svg_mixed", dir, sizeof dir);
    fresh_dir("svg_mixed_single", single, sizeof single);
    REQUIRE(write_mixed(dir, text, sizeof text));
    snprintf(list, sizeof list, "%s/list.txt", single);
    REQUIRE(write_text(list, text));
    char first_err[8192] = "";
    for (int t = 0; t < THREAD_RUNS; t++) {
        char name[64], out[1200], log[1300], kept[1300];
        snprintf(name, sizeof name, "svg_mixed_threads%s", thread_counts[t]);
        fresh_dir(name, out, sizeof out);
        snprintf(log, sizeof log, "%s/run.jsonl", out);
        snprintf(kept, sizeof kept, "%s/08_kept.png", out);
        REQUIRE(write_text(kept, "kept"));
        run_result r;
        REQUIRE(run(ARGS("svg", "--batch", list, "--output-dir", out, "--skip-existing",
                         "--log", log, "--threads", thread_counts[t]), &r));
        CHECK_EQ(r.status, 3);
        CHECK_EQ(count_lines(r.err), 6);
        if (t == 0) {
            snprintf(first_err, sizeof first_err, "%s", r.err);
        } else {
            CHECK(strcmp(r.err, first_err) == 0);   /* the same lines, the same order */
        }
        /* Each failure's line after the one before it. */
        const char *at = r.err;
        for (int i = 0; i < MIXED; i++) {
            if (mixed[i].kind == GOOD || mixed[i].kind == SKIPPED) {
                continue;
            }
            const char *line = strstr(at, mixed[i].name);
            CHECK(line != NULL);
            at = line ? line : at;
        }
        CHECK_STR_CONTAINS(r.err, "01_broken.svg:2:");
        CHECK_STR_CONTAINS(r.err, "03_text.svg:2: warning");
        CHECK_STR_CONTAINS(r.err, "is a directory");
        record recs[MIXED + 1];
        REQUIRE(read_log(log, recs, MIXED + 1) == MIXED);
        for (int i = 0; i < MIXED; i++) {
            mixed_kind k = mixed[i].kind;
            const char *want = k == GOOD || k == WARNED ? "ok"
                             : k == SKIPPED ? "skipped" : "failed";
            CHECK_EQ((int)recs[i].index, i);
            CHECK_STR_CONTAINS(recs[i].input, mixed[i].name);
            CHECK(strcmp(recs[i].status, want) == 0);
            if (strcmp(want, "ok") != 0) {
                continue;
            }
            char in[1300], one[1400];
            snprintf(in, sizeof in, "%s/%s", dir, mixed[i].name);
            snprintf(one, sizeof one, "%s/%.*s.png", single, (int)strlen(mixed[i].name) - 4,
                     mixed[i].name);
            if (t == 0) {
                REQUIRE(run(ARGS("svg", in, "-o", one), &r));
                CHECK_EQ(r.status, 0);
            }
            if (!same_file_bytes(one, recs[i].output)) {
                FAILF("%s on %s threads: not the single run's image", mixed[i].name,
                      thread_counts[t]);
            }
        }
        size_t n = 0;
        char *k = (char *)sr_test_read_file(kept, &n);
        CHECK(k && n == 4);
        free(k);
    }
}

/* A broken drawing in the middle: one line naming it, a failed record
 * with the reader's message, the others written, exit status 3; all
 * broken: 4. */
SR_TEST(broken_drawing_fails_alone)
{
    NEED_SVG();
    char dir[1200], out[1200], log[1300], paths[DRAWINGS][1200];
    fresh_dir("svg_broken", dir, sizeof dir);
    fresh_dir("svg_broken_out", out, sizeof out);
    REQUIRE(write_drawings(dir, paths));
    snprintf(log, sizeof log, "%s/run.jsonl", out);
    run_result r;
    REQUIRE(run(ARGS("svg", paths[0], paths[1], paths[2], "--output-dir", out, "--log", log),
                &r));
    CHECK_EQ(r.status, 3);
    CHECK_EQ(count_lines(r.err), 1);
    CHECK_STR_CONTAINS(r.err, "b_broken.svg:");
    record recs[8];
    int n = read_log(log, recs, 8);
    REQUIRE(n == DRAWINGS);
    for (int i = 0; i < DRAWINGS; i++) {
        const record *rec = find_record(recs, n, paths[i]);
        REQUIRE(rec);
        CHECK_EQ((int)rec->index, i);
        CHECK(strcmp(rec->status, i == BROKEN ? "failed" : "ok") == 0);
        CHECK(rec->error_null == (i != BROKEN));
        CHECK(file_exists(rec->output) == (i != BROKEN));
    }
    CHECK_STR_CONTAINS(recs[BROKEN].error, "b_broken.svg:2:");
    REQUIRE(run(ARGS("svg", paths[BROKEN], paths[BROKEN], "--output-dir", out), &r));
    CHECK_EQ(r.status, 4);
    /* -o names one output: refused in a batch, before anything is read. */
    REQUIRE(run(ARGS("svg", paths[0], paths[2], "-o", log), &r));
    CHECK_EQ(r.status, 2);
    CHECK_STR_CONTAINS(r.err, "-o");
}

/* --skip-existing leaves an output that exists alone (even one that is
 * not what the drawing gives) and writes the missing ones. */
SR_TEST(skip_existing_writes_only_missing_images)
{
    NEED_SVG();
    char dir[1200], out[1200], log[1300], a_png[1300], c_png[1300], paths[DRAWINGS][1200];
    fresh_dir("svg_skip", dir, sizeof dir);
    fresh_dir("svg_skip_out", out, sizeof out);
    REQUIRE(write_drawings(dir, paths));
    snprintf(a_png, sizeof a_png, "%s/a_red.png", out);
    snprintf(c_png, sizeof c_png, "%s/c_blue.png", out);
    snprintf(log, sizeof log, "%s/run.jsonl", dir);
    REQUIRE(write_text(a_png, "not an image, but there"));
    run_result r;
    REQUIRE(run(ARGS("svg", dir, "--output-dir", out, "--skip-existing", "--log", log), &r));
    CHECK_EQ(r.status, 3);
    size_t n = 0;
    char *kept = (char *)sr_test_read_file(a_png, &n);
    CHECK(kept && n == 23 && memcmp(kept, "not an image", 12) == 0);
    free(kept);
    CHECK(file_exists(c_png));
    record recs[8];
    REQUIRE(read_log(log, recs, 8) == DRAWINGS);
    CHECK(strcmp(find_record(recs, DRAWINGS, paths[0])->status, "skipped") == 0);
    CHECK(strcmp(find_record(recs, DRAWINGS, paths[2])->status, "ok") == 0);
}

/* An output that is an input of the batch (by a list's INPUT<TAB>OUTPUT
 * or --name) fails that input and leaves the file alone. */
SR_TEST(output_over_an_input_is_refused)
{
    NEED_SVG();
    char dir[1200], list[1300], text[5000], paths[DRAWINGS][1200];
    fresh_dir("svg_over", dir, sizeof dir);
    REQUIRE(write_drawings(dir, paths));
    size_t before = 0, before0 = 0;
    free(sr_test_read_file(paths[2], &before));
    free(sr_test_read_file(paths[0], &before0));
    snprintf(list, sizeof list, "%s/list.txt", dir);
    /* the third drawing by another name, one an image may have */
    char alias[1300];
    snprintf(alias, sizeof alias, "%s/alias.png", dir);
    REQUIRE(link(paths[2], alias) == 0);
    snprintf(text, sizeof text, "%s\t%s\n%s\t%s/c.png\n", paths[0], alias, paths[2], dir);
    REQUIRE(write_text(list, text));
    run_result r;
    REQUIRE(run(ARGS("svg", "--batch", list), &r));
    CHECK_EQ(r.status, 3);
    CHECK_STR_CONTAINS(r.err, "input of the batch");
    size_t after = 0;
    free(sr_test_read_file(paths[2], &after));
    CHECK_EQ(after, before);
    /* --name '{rel}.svg' in the inputs' own directory would name each
     * drawing as itself: no image's name, refused before any is drawn. */
    REQUIRE(run(ARGS("svg", paths[0], "--output-dir", dir, "--name", "{rel}.svg"), &r));
    CHECK_EQ(r.status, 2);
    CHECK_STR_CONTAINS(r.err, "not .svg");
    free(sr_test_read_file(paths[0], &after));
    CHECK_EQ(after, before0);
}

/* A directory is searched below it: .svg in any case, hidden entries and
 * other files left out, each image at its drawing's path below the
 * directory; a list on standard input names the same. */
SR_TEST(directory_is_searched_below_it)
{
    NEED_SVG();
    char dir[1200], out[1200], out2[1200], p[2048];
    fresh_dir("svg_tree", dir, sizeof dir);
    fresh_dir("svg_tree_out", out, sizeof out);
    fresh_dir("svg_tree_out2", out2, sizeof out2);
    const char *subdirs[] = { "apps", "apps/scalable", ".hidden" };
    for (int i = 0; i < 3; i++) {
        snprintf(p, sizeof p, "%s/%s", dir, subdirs[i]);
        REQUIRE(mkdir(p, 0777) == 0);
    }
    const char *files[] = { "top.svg", "apps/scalable/deep.SVG", "apps/mid.svg",
                            ".hidden/no.svg", "apps/notes.txt" };
    for (int i = 0; i < 5; i++) {
        snprintf(p, sizeof p, "%s/%s", dir, files[i]);
        REQUIRE(write_svg(p, "green"));
    }
    char log[1300];
    snprintf(log, sizeof log, "%s/run.jsonl", out2);
    run_result r;
    REQUIRE(run(ARGS("svg", dir, "--output-dir", out), &r));
    CHECK_EQ(r.status, 0);
    const char *want[] = { "top.png", "apps/scalable/deep.png", "apps/mid.png" };
    for (int i = 0; i < 3; i++) {
        snprintf(p, sizeof p, "%s/%s", out, want[i]);
        CHECK(file_exists(p));
    }
    snprintf(p, sizeof p, "%s/.hidden/no.png", out);
    CHECK(!file_exists(p));
    snprintf(p, sizeof p, "%s/apps/notes.png", out);
    CHECK(!file_exists(p));
    /* --batch - reads the list from standard input. */
    char list[1300], text[3000];
    snprintf(list, sizeof list, "%s/list.txt", out2);
    snprintf(text, sizeof text, "# two drawings\n%s/top.svg\n\n%s/apps/mid.svg\n", dir, dir);
    REQUIRE(write_text(list, text));
    REQUIRE(run_env(ARGS("svg", "--batch", "-", "--output-dir", out2, "--log", log), NO_ENV,
                    list, &r));
    CHECK_EQ(r.status, 0);
    record recs[4];
    CHECK_EQ(read_log(log, recs, 4), 2);
    char a[2048], b[2048];
    snprintf(a, sizeof a, "%s/top.png", out);
    snprintf(b, sizeof b, "%s/top.png", out2);
    CHECK(same_file_bytes(a, b));
    snprintf(b, sizeof b, "%s/mid.png", out2);   /* a listed file's {rel} is its name */
    CHECK(file_exists(b));
}
