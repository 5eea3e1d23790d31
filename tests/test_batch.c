/* test_batch.c - `softrast render` over many models in one process, as a
 * pipeline or a cluster's scheduler runs it: the real executable
 * (SR_CLI_PATH) with the environment a Kubernetes Indexed Job or a Slurm
 * array sets, standard input from a file, and its --log read back as
 * JSON.  Models are written by the test (STL and OBJ), with a bad one
 * among them. */
#define _XOPEN_SOURCE 700   /* posix_openpt, grantpt, unlockpt, ptsname */
#include "batch_cli.h"
#include "gltf_write.h" /* le_copy */
#include "softrast_io.h"
#include "sr_test.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

/* ---- files -------------------------------------------------------------- */

/* A binary STL of a tetrahedron stretched by s along x (4 triangles). */
static bool write_stl(const char *path, float s)
{
    const float v[4][3] = { { 0, 0, 0 }, { s, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
    const int t[4][3] = { { 0, 2, 1 }, { 0, 1, 3 }, { 0, 3, 2 }, { 1, 2, 3 } };
    uint8_t buf[84 + 4 * 50] = { 0 };
    uint32_t count = 4;
    le_copy(buf + 80, &count, 1, 4); /* binary STL is little endian on any host */
    for (int i = 0; i < 4; i++) {
        uint8_t *rec = buf + 84 + 50 * i;
        for (int k = 0; k < 3; k++) {
            le_copy(rec + 12 + 12 * k, v[t[i][k]], 3, 4);
        }
    }
    return sr_test_write_file(path, buf, sizeof buf);
}

/* An OBJ cube of side s (12 triangles). */
static bool write_obj(const char *path, float s)
{
    char text[1024];
    int n = 0;
    for (int i = 0; i < 8; i++) {
        n += snprintf(text + n, sizeof text - (size_t)n, "v %g %g %g\n", (double)(i & 1 ? s : 0),
                      (double)(i & 2 ? s : 0), (double)(i & 4 ? s : 0));
    }
    snprintf(text + n, sizeof text - (size_t)n,
             "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n");
    return write_text(path, text);
}

static bool is_stl(const char *path)
{
    return strcmp(strrchr(path, '.'), ".stl") == 0;
}

/* The batch's models in dir: good STL and OBJ files and, sorted in the
 * middle, one that is no model; their paths (as the batch names them
 * from the directory) in `paths`.  Returns the count. */
enum { MODELS = 5, BAD_MODEL = 2 };
static int write_models(const char *dir, char paths[MODELS][1200])
{
    const char *names[MODELS] = { "a_tetra.stl", "b_cube.obj", "c_bad.stl", "d_long.stl",
                                  "e_big.obj" };
    for (int i = 0; i < MODELS; i++) {
        snprintf(paths[i], 1200, "%s/%s", dir, names[i]);
        bool ok = i == BAD_MODEL ? write_text(paths[i], "solid nothing but a name\n")
                : is_stl(names[i]) ? write_stl(paths[i], 1.0f + (float)i)
                                 : write_obj(paths[i], (float)i);
        if (!ok) {
            FAILF("cannot write %s", paths[i]);
            return 0;
        }
    }
    return MODELS;
}

/* A w x h image with some pixels other than the corner's (the model). */
static bool is_thumbnail(const char *path, int w, int h)
{
    int pw, ph;
    uint8_t *px = NULL;
    sr_io_error err;
    if (sr_read_image(path, &pw, &ph, &px, &err) != SR_OK) {
        FAILF("%s: %s", path, err.message);
        return false;
    }
    size_t differ = 0;
    for (size_t i = 0; i < (size_t)pw * (size_t)ph; i++) {
        differ += memcmp(px + 4 * i, px, 3) != 0;
    }
    free(px);
    if (pw != w || ph != h || differ < (size_t)(w * h) / 50) {
        FAILF("%s: %dx%d with %zu model pixels, expected %dx%d with some", path, pw, ph, differ,
              w, h);
        return false;
    }
    return true;
}

/* ---- tests -------------------------------------------------------------- */

/* A directory of models with a bad one in the middle: every good one is
 * rendered, the bad one is one line and a failed record, the exit status
 * says some failed, and the log holds one whole record per input. */
SR_TEST(batch_renders_every_model_past_a_bad_one)
{
    NEED_CLI();
    char dir[1024], out[1024], logp[1100], paths[MODELS][1200];
    fresh_dir("models", dir, sizeof dir);
    fresh_dir("out", out, sizeof out);
    snprintf(logp, sizeof logp, "%s/../batch_log.jsonl", out);
    unlink(logp);
    REQUIRE(write_models(dir, paths) == MODELS);

    run_result r;
    REQUIRE(run(ARGS("render", dir, "--output-dir", out, "--size", "64x48", "--log", logp), &r));
    CHECK_EQ(r.status, 3);
    CHECK_EQ(count_lines(r.err), 1);
    CHECK_STR_CONTAINS(r.err, "c_bad.stl");

    record recs[16];
    int n = read_log(logp, recs, 16);
    CHECK_EQ(n, MODELS);
    for (int i = 0; i < MODELS && n == MODELS; i++) {
        const record *rec = find_record(recs, n, paths[i]);
        if (!rec) {
            FAILF("no record for %s", paths[i]);
            continue;
        }
        char want[1300];
        snprintf(want, sizeof want, "%s/%.*s.png", out, (int)(strrchr(paths[i], '.') -
                 strrchr(paths[i], '/') - 1), strrchr(paths[i], '/') + 1);
        CHECK(strcmp(rec->output, want) == 0);
        CHECK_EQ(rec->index, i);
        CHECK(rec->ms >= rec->load_ms && rec->load_ms >= 0 && rec->render_ms >= 0 &&
              rec->encode_ms >= 0);
        if (i == BAD_MODEL) {
            CHECK(strcmp(rec->status, "failed") == 0);
            CHECK(!rec->error_null && strstr(rec->error, "c_bad.stl"));
            CHECK(!file_exists(want));
        } else {
            CHECK(strcmp(rec->status, "ok") == 0);
            CHECK(rec->error_null);
            CHECK_EQ(rec->triangles, is_stl(paths[i]) ? 4 : 12);
            CHECK(is_thumbnail(want, 64, 48));
        }
    }

    /* A batch draws each model exactly as a single render does. */
    char single[1200];
    snprintf(single, sizeof single, "%s/../batch_single.png", out);
    REQUIRE(run(ARGS("render", paths[1], "-o", single, "--size", "64x48"), &r));
    CHECK_EQ(r.status, 0);
    size_t na, nb;
    char batch_png[1300];
    snprintf(batch_png, sizeof batch_png, "%s/b_cube.png", out);
    uint8_t *a = sr_test_read_file(single, &na), *b = sr_test_read_file(batch_png, &nb);
    CHECK(a && b && na == nb && memcmp(a, b, na) == 0);
    free(a);
    free(b);
}

/* The next model is read while the last is drawn (by a second job): the
 * images are byte for byte those of batches of one model each, and the
 * failures come on stderr and in the log in the order of the list. */
SR_TEST(batch_reads_ahead_without_changing_a_byte)
{
    NEED_CLI();
    enum { N = 6 };
    const char *names[N] = { "a_tetra.stl", "b_bad.stl", "c_cube.obj", "d_bad.obj",
                             "e_long.stl", "f_big.obj" };
    char dir[1024], out[1024], one[1024], logp[1100], paths[N][1200];
    fresh_dir("ahead", dir, sizeof dir);
    fresh_dir("ahead_out", out, sizeof out);
    fresh_dir("ahead_one", one, sizeof one);
    snprintf(logp, sizeof logp, "%s/../ahead_log.jsonl", out);
    unlink(logp);
    for (int i = 0; i < N; i++) {
        snprintf(paths[i], sizeof paths[i], "%s/%s", dir, names[i]);
        bool ok = strstr(names[i], "_bad.") ? write_text(paths[i], is_stl(names[i]) ? "solid nothing\n"
                                                             : "v 0 0 0\nf 1 2 3\n")
                : is_stl(names[i]) ? write_stl(paths[i], 1.0f + (float)i)
                                   : write_obj(paths[i], (float)i);
        REQUIRE(ok);
    }
    run_result r;
    REQUIRE(run(ARGS("render", dir, "--output-dir", out, "--size", "40x30", "--threads", "2",
                     "--environment", "studio", "--log", logp), &r));
    CHECK_EQ(r.status, 3);
    CHECK_EQ(count_lines(r.err), 2);
    const char *first = strstr(r.err, "b_bad.stl"), *second = strstr(r.err, "d_bad.obj");
    CHECK(first && second && first < second);

    record recs[N + 1];
    CHECK_EQ(read_log(logp, recs, N + 1), N);
    for (int i = 0; i < N; i++) {
        CHECK(strcmp(recs[i].input, paths[i]) == 0);
        bool bad = strstr(names[i], "_bad.") != NULL;
        CHECK(strcmp(recs[i].status, bad ? "failed" : "ok") == 0);
        if (bad) {
            continue;
        }
        char batch_png[1300], one_png[1300];
        snprintf(batch_png, sizeof batch_png, "%s/%.*s.png", out, (int)strcspn(names[i], "."),
                 names[i]);
        snprintf(one_png, sizeof one_png, "%s/%.*s.png", one, (int)strcspn(names[i], "."),
                 names[i]);
        REQUIRE(run(ARGS("render", paths[i], "--output-dir", one, "--size", "40x30",
                         "--threads", "2", "--environment", "studio"), &r));
        CHECK_EQ(r.status, 0);
        size_t na, nb;
        uint8_t *a = sr_test_read_file(one_png, &na), *b = sr_test_read_file(batch_png, &nb);
        if (!(a && b && na == nb && memcmp(a, b, na) == 0)) {
            FAILF("%s: the batch's image differs from a batch of that model alone", names[i]);
        }
        free(a);
        free(b);
    }

    /* The light is made once, before any input: a bad one is a bad option. */
    char hdr[1200];
    snprintf(hdr, sizeof hdr, "%s/none.hdr", dir);
    REQUIRE(run(ARGS("render", dir, "--output-dir", out, "--environment", hdr), &r));
    CHECK_EQ(r.status, 2);
    CHECK_EQ(count_lines(r.err), 1);
    CHECK_STR_CONTAINS(r.err, "none.hdr");
}

static bool same_file_state(const char *path, const struct stat *before)
{
    struct stat st;
    return stat(path, &st) == 0 && st.st_ino == before->st_ino &&
           st.st_mtim.tv_sec == before->st_mtim.tv_sec &&
           st.st_mtim.tv_nsec == before->st_mtim.tv_nsec;
}

/* --skip-existing leaves every finished image alone and renders only what
 * is missing; the exit status counts a skipped input as done. */
SR_TEST(skip_existing_renders_only_missing_outputs)
{
    NEED_CLI();
    char dir[1024], out[1024], logp[1100], paths[MODELS][1200];
    fresh_dir("skip_models", dir, sizeof dir);
    fresh_dir("skip_out", out, sizeof out);
    snprintf(logp, sizeof logp, "%s/log.jsonl", dir);
    REQUIRE(write_models(dir, paths) == MODELS);
    unlink(paths[BAD_MODEL]);

    run_result r;
    REQUIRE(run(ARGS("render", dir, "--output-dir", out, "--size", "32x32"), &r));
    REQUIRE(r.status == 0);
    char outs[MODELS][1300];
    struct stat before[MODELS];
    for (int i = 0; i < MODELS; i++) {
        snprintf(outs[i], sizeof outs[i], "%s/%.*s.png", out, (int)(strrchr(paths[i], '.') -
                 strrchr(paths[i], '/') - 1), strrchr(paths[i], '/') + 1);
        CHECK(i == BAD_MODEL || stat(outs[i], &before[i]) == 0);
    }
    unlink(outs[3]);
    REQUIRE(run(ARGS("render", dir, "--output-dir", out, "--size", "32x32", "--skip-existing",
                     "--log", logp), &r));
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.err[0], '\0');
    record recs[16];
    int n = read_log(logp, recs, 16);
    CHECK_EQ(n, MODELS - 1);
    for (int i = 0; i < MODELS && n == MODELS - 1; i++) {
        if (i == BAD_MODEL) {
            continue;
        }
        const record *rec = find_record(recs, n, paths[i]);
        CHECK(rec && strcmp(rec->status, i == 3 ? "ok" : "skipped") == 0);
        if (i != 3) {
            CHECK(same_file_state(outs[i], &before[i]));
        } else {
            CHECK(is_thumbnail(outs[i], 32, 32));
        }
    }
}

/* The exit status: 0 when all inputs were rendered, 4 when none was. */
SR_TEST(exit_status_says_all_or_none)
{
    NEED_CLI();
    char dir[1024], out[1024], bad1[1100], bad2[1100], good[1100];
    fresh_dir("status", dir, sizeof dir);
    fresh_dir("status_out", out, sizeof out);
    snprintf(bad1, sizeof bad1, "%s/x.stl", dir);
    snprintf(bad2, sizeof bad2, "%s/missing.obj", dir);
    snprintf(good, sizeof good, "%s/g.stl", dir);
    REQUIRE(write_text(bad1, "not a model\n") && write_stl(good, 1.0f));
    run_result r;
    REQUIRE(run(ARGS("render", bad1, bad2, "--output-dir", out, "--size", "16x16"), &r));
    CHECK_EQ(r.status, 4);
    CHECK_EQ(count_lines(r.err), 2);
    CHECK_STR_CONTAINS(r.err, "missing.obj");
    REQUIRE(run(ARGS("render", good, "--output-dir", out, "--size", "16x16"), &r));
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.err[0], '\0');
}

/* A glTF the reader refuses is logged with the reader's message, as an
 * OBJ's is, not a bare "failed". */
SR_TEST(a_bad_gltf_is_logged_with_the_readers_message)
{
    NEED_CLI();
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson (glTF)");
    }
    char dir[1024], out[1024], glb[1100], logp[1100];
    fresh_dir("gltf_log", dir, sizeof dir);
    fresh_dir("gltf_log_out", out, sizeof out);
    snprintf(glb, sizeof glb, "%s/cut.glb", dir);
    snprintf(logp, sizeof logp, "%s/log.jsonl", dir);
    /* A GLB header saying 600 bytes, and no more. */
    const uint32_t words[5] = { 0x46546C67u, 2, 600, 0, 0x4E4F534Au };
    uint8_t bytes[20];
    le_copy(bytes, words, 5, 4);
    REQUIRE(sr_test_write_file(glb, bytes, sizeof bytes));
    run_result r;
    REQUIRE(run(ARGS("render", glb, "--output-dir", out, "--size", "16x16", "--log", logp), &r));
    CHECK_EQ(r.status, 4);
    CHECK_EQ(count_lines(r.err), 1);
    record recs[2];
    REQUIRE(read_log(logp, recs, 2) == 1);
    CHECK(strcmp(recs[0].status, "failed") == 0);
    CHECK(!recs[0].error_null);
    CHECK_STR_CONTAINS(recs[0].error, "cut.glb: byte 8: GLB length 600, but the file has 20 bytes");
}

/* --batch: a list on standard input, with an output named on one line, a
 * comment and a blank line; a quoted glob pattern expanded by the tool. */
SR_TEST(list_on_stdin_and_glob_patterns)
{
    NEED_CLI();
    char dir[1024], out[1024], list[1100], named[1100], paths[MODELS][1200];
    fresh_dir("list", dir, sizeof dir);
    fresh_dir("list_out", out, sizeof out);
    REQUIRE(write_models(dir, paths) == MODELS);
    snprintf(list, sizeof list, "%s/list.txt", dir);
    snprintf(named, sizeof named, "%s/sub/named.png", out);
    char text[4096];
    snprintf(text, sizeof text, "# the list\n%s\n\n%s\t%s\n", paths[0], paths[1], named);
    REQUIRE(write_text(list, text));
    run_result r;
    REQUIRE(run_env(ARGS("render", "--batch", "-", "--output-dir", out, "--size", "24x24",
                         "--name", "{index}-{stem}.{ext}.png"),
                    NO_ENV, list, &r));
    CHECK_EQ(r.status, 0);
    char first[1300];
    snprintf(first, sizeof first, "%s/0-a_tetra.stl.png", out);
    CHECK(is_thumbnail(first, 24, 24));
    CHECK(is_thumbnail(named, 24, 24));

    char pattern[1100], obj_out[1300], stl_out[1300];
    snprintf(pattern, sizeof pattern, "%s/*.obj", dir);
    fresh_dir("list_out", out, sizeof out);
    REQUIRE(run(ARGS("render", pattern, "--output-dir", out, "--size", "24x24"), &r));
    CHECK_EQ(r.status, 0);
    snprintf(obj_out, sizeof obj_out, "%s/e_big.png", out);
    snprintf(stl_out, sizeof stl_out, "%s/a_tetra.png", out);
    CHECK(file_exists(obj_out) && !file_exists(stl_out));
}

/* A failed input whose name holds a newline and an escape sequence is
 * still one line on stderr, with those bytes as '?' (as the readers quote
 * names), and named once. */
SR_TEST(failed_inputs_with_control_bytes_in_their_names_are_one_line_each)
{
    NEED_CLI();
    char dir[1024], out[1024], a[1200], b[1200];
    fresh_dir("ctrl_names", dir, sizeof dir);
    fresh_dir("ctrl_out", out, sizeof out);
    snprintf(a, sizeof a, "%s/no\nfaces\033[2J.obj", dir);
    snprintf(b, sizeof b, "%s/two\nnumbers.obj", dir);
    REQUIRE(write_text(a, "# nothing to draw\n"));
    REQUIRE(write_text(b, "v 1 2\n"));
    run_result r;
    REQUIRE(run(ARGS("render", dir, "--output-dir", out, "--size", "16x16"), &r));
    CHECK_EQ(r.status, 4);
    CHECK_EQ(count_lines(r.err), 2);
    CHECK(strchr(r.err, '\033') == NULL);
    CHECK_STR_CONTAINS(r.err, "softrast: ");
    CHECK_STR_CONTAINS(r.err, "no?faces?[2J.obj: contains no faces\n");
    CHECK_STR_CONTAINS(r.err, "two?numbers.obj:1: 'v' takes");
    /* named once: the reader's message starts with the name already */
    const char *first = strstr(r.err, "no?faces");
    CHECK(first && !strstr(first + 1, "no?faces"));
}

/* Mistakes that would lose work are refused before anything is drawn. */
SR_TEST(batch_refuses_bad_options_in_one_line)
{
    NEED_CLI();
    char dir[1024], out[1024], paths[MODELS][1200], nomatch[1100], empty[1100];
    fresh_dir("refuse", dir, sizeof dir);
    fresh_dir("refuse_out", out, sizeof out);
    char stale[1100];   /* an earlier run's, where ".." would have led */
    fresh_dir("refuse_up", stale, sizeof stale);
    rmdir(stale);
    REQUIRE(write_models(dir, paths) == MODELS);
    snprintf(nomatch, sizeof nomatch, "%s/*.nothing", dir);
    snprintf(empty, sizeof empty, "%s/empty", dir);
    mkdir(empty, 0777);
    struct {
        const char *label;
        const char *const *args;
        const char *needle;
    } cases[] = {
        { "-o in a batch", ARGS("render", dir, "--output-dir", out, "-o", "x.png"), "-o" },
        { "unknown field", ARGS("render", dir, "--output-dir", out, "--name", "{nope}.png"),
          "{nope}" },
        { "absolute name", ARGS("render", dir, "--name", "/tmp/x.png"), "--name" },
        { "name above the directory",
          ARGS("render", dir, "--output-dir", out, "--name", "../batch_refuse_up/{stem}.png"),
          "below --output-dir" },
        { "one output for all", ARGS("render", dir, "--output-dir", out, "--name", "all.png"),
          "both be written" },
        { "pattern matches nothing", ARGS("render", nomatch, "--output-dir", out), "no file" },
        { "empty directory", ARGS("render", empty, "--output-dir", out), "no models" },
        { "missing list", ARGS("render", "--batch", "/nonexistent/list", "--output-dir", out),
          "--batch" },
        { "--log without value", ARGS("render", dir, "--log"), "--log" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        run_result r;
        REQUIRE(run(cases[i].args, &r));
        if (r.status != 2 || count_lines(r.err) != 1 || !strstr(r.err, cases[i].needle)) {
            FAILF("%s: status %d, stderr \"%s\" (expected 2 and one line with '%s')",
                  cases[i].label, r.status, r.err, cases[i].needle);
        }
    }
    DIR *d = opendir(out);
    int entries = 0;
    for (struct dirent *e; d && (e = readdir(d)) != NULL;) {
        entries += e->d_name[0] != '.';
    }
    if (d) {
        closedir(d);
    }
    CHECK_EQ(entries, 0);
    char up[1100];
    snprintf(up, sizeof up, "%s/../batch_refuse_up", out);
    CHECK(!file_exists(up));

    /* Outputs named like the inputs ({ext} is a model's) are no images:
     * refused before anything is drawn. */
    run_result r;
    REQUIRE(run(ARGS("render", dir, "--output-dir", dir, "--name", "{stem}.{ext}"), &r));
    CHECK_EQ(r.status, 2);
    CHECK_STR_CONTAINS(r.err, "--name: '{stem}.{ext}': softrast writes PNG or JPEG images");

    /* An output that is an input of the batch by another name (a hard
     * link named .png) fails that input, and the input keeps its bytes. */
    char alias[1300];
    snprintf(alias, sizeof alias, "%.*s.png", (int)(strrchr(paths[0], '.') - paths[0]),
             paths[0]);
    remove(alias);
    REQUIRE(link(paths[0], alias) == 0);
    size_t before_n, after_n;
    uint8_t *before = sr_test_read_file(paths[0], &before_n);
    REQUIRE(run(ARGS("render", paths[0], "--output-dir", dir, "--name", "{stem}.png"), &r));
    CHECK_EQ(r.status, 4);
    CHECK_STR_CONTAINS(r.err, "input of the batch");
    uint8_t *after = sr_test_read_file(paths[0], &after_n);
    CHECK(before && after && before_n == after_n && memcmp(before, after, before_n) == 0);
    free(before);
    free(after);

    /* A --log that is one of the models, which appending would end in
     * JSON, and a --sheet that is one are refused before anything is
     * drawn, as the outputs are (exit status 2). */
    const char *const *kinds[] = {
        ARGS("render", dir, "--output-dir", out, "--log", paths[1]),
        ARGS("render", dir, "--sheet", paths[1]),
    };
    const char *why[] = { "is an input of the batch", "softrast writes PNG or JPEG images" };
    for (int k = 0; k < 2; k++) {
        before = sr_test_read_file(paths[1], &before_n);
        REQUIRE(run(kinds[k], &r));
        CHECK_EQ(r.status, 2);
        CHECK_STR_CONTAINS(r.err, why[k]);
        CHECK_EQ(count_lines(r.err), 1);
        after = sr_test_read_file(paths[1], &after_n);
        CHECK(before && after && before_n == after_n && memcmp(before, after, before_n) == 0);
        free(before);
        free(after);
    }

    /* The same outputs named by a --batch list: the messages point to the
     * list, not to --name and its fields. */
    char list[8192], listp[1100];
    snprintf(listp, sizeof listp, "%s/batch_refuse_list.txt", sr_test_out_dir());
    snprintf(list, sizeof list, "%s\t%s\n", paths[0], alias);
    REQUIRE(write_text(listp, list));
    REQUIRE(run(ARGS("render", "--batch", listp), &r));
    CHECK_EQ(r.status, 4);
    CHECK_STR_CONTAINS(r.err, "choose another --batch output");
    remove(alias);
    snprintf(list, sizeof list, "%s\t%s/a.png\n%s\t%s/a.png\n", paths[0], out, paths[1], out);
    REQUIRE(write_text(listp, list));
    REQUIRE(run(ARGS("render", "--batch", listp), &r));
    CHECK_EQ(r.status, 2);
    CHECK_STR_CONTAINS(r.err, "--batch: ");
    CHECK(!strstr(r.err, "--name"));
}

/* ---- shards ------------------------------------------------------------- */

enum { SHARD_INPUTS = 23 };

/* A list file of SHARD_INPUTS models (in dir), in forward or reverse order. */
static bool write_shard_models(const char *dir, const char *list, bool reverse,
                               char paths[SHARD_INPUTS][1200])
{
    char text[SHARD_INPUTS * 1210] = "";
    size_t n = 0;
    for (int k = 0; k < SHARD_INPUTS; k++) {
        int i = reverse ? SHARD_INPUTS - 1 - k : k;
        snprintf(paths[i], 1200, "%s/m%02d.stl", dir, i);
        if (!write_stl(paths[i], 1.0f + 0.1f * (float)i)) {
            return false;
        }
        n += (size_t)snprintf(text + n, sizeof text - n, "%s\n", paths[i]);
    }
    return write_text(list, text);
}

/* Run `count` shards over the list, each with the environment `env_of`
 * gives it (and, when it names one, an option followed by the count),
 * then check from their logs that every
 * input was rendered exactly once.  Records which shard took each input
 * in owner[] (for comparing two runs). */
typedef void (*shard_env_fn)(int index, int count, char env[3][64], const char **extra);

static void run_shards(const char *label, const char *list, char paths[SHARD_INPUTS][1200],
                       int count, shard_env_fn env_of, int owner[SHARD_INPUTS])
{
    char out[1024], logp[1100];
    fresh_dir("shard_out", out, sizeof out);
    for (int i = 0; i < SHARD_INPUTS; i++) {
        owner[i] = -1;
    }
    for (int s = 0; s < count; s++) {
        char env[3][64] = { "", "", "" }, count_s[16];
        const char *extra = NULL;
        env_of(s, count, env, &extra);
        snprintf(count_s, sizeof count_s, "%d", count);
        snprintf(logp, sizeof logp, "%s/shard%d.jsonl", out, s);
        const char *envp[4] = { NULL, NULL, NULL, NULL };
        for (int k = 0, m = 0; k < 3; k++) {
            if (env[k][0]) {
                envp[m++] = env[k];
            }
        }
        run_result r;
        bool ran = extra ? run_env(ARGS("render", "--batch", list, "--output-dir", out, "--size",
                                        "8x8", "--aa", "none", "--log", logp, extra, count_s),
                                   envp, NULL, &r)
                         : run_env(ARGS("render", "--batch", list, "--output-dir", out, "--size",
                                        "8x8", "--aa", "none", "--log", logp),
                                   envp, NULL, &r);
        if (!ran || r.status != 0) {
            FAILF("%s: shard %d of %d: status %d: %s", label, s, count, r.status, r.err);
            return;
        }
        record recs[SHARD_INPUTS + 1];
        int n = read_log(logp, recs, SHARD_INPUTS + 1);
        for (int k = 0; k < n && k <= SHARD_INPUTS; k++) {
            int i = 0;
            while (i < SHARD_INPUTS && strcmp(paths[i], recs[k].input) != 0) {
                i++;
            }
            if (i == SHARD_INPUTS || strcmp(recs[k].status, "ok") != 0) {
                FAILF("%s: shard %d: unexpected record for %s (%s)", label, s, recs[k].input,
                      recs[k].status);
            } else if (owner[i] >= 0) {
                FAILF("%s: %s rendered by shards %d and %d of %d", label, paths[i], owner[i], s,
                      count);
            } else {
                owner[i] = s;
            }
        }
    }
    for (int i = 0; i < SHARD_INPUTS; i++) {
        if (owner[i] < 0) {
            FAILF("%s: %s rendered by none of %d shards", label, paths[i], count);
        }
    }
}

static void env_kubernetes(int index, int count, char env[3][64], const char **extra)
{
    (void)count;
    snprintf(env[0], 64, "JOB_COMPLETION_INDEX=%d", index);
    *extra = "--shard-count";
}

/* Slurm's --array=1-N numbers its tasks from 1: the index is less MIN. */
static void env_slurm(int index, int count, char env[3][64], const char **extra)
{
    *extra = NULL;
    snprintf(env[0], 64, "SLURM_ARRAY_TASK_ID=%d", index + 1);
    snprintf(env[1], 64, "SLURM_ARRAY_TASK_COUNT=%d", count);
    snprintf(env[2], 64, "SLURM_ARRAY_TASK_MIN=1");
}

SR_TEST(shards_partition_the_inputs)
{
    NEED_CLI();
    char dir[1024], list[1100], rlist[1100], paths[SHARD_INPUTS][1200];
    fresh_dir("shard_models", dir, sizeof dir);
    snprintf(list, sizeof list, "%s/list.txt", dir);
    snprintf(rlist, sizeof rlist, "%s/reversed.txt", dir);
    REQUIRE(write_shard_models(dir, rlist, true, paths));
    REQUIRE(write_shard_models(dir, list, false, paths));
    const int counts[] = { 1, 2, 3, 7 };
    for (size_t c = 0; c < sizeof counts / sizeof counts[0]; c++) {
        int n = counts[c];
        int by_k8s[SHARD_INPUTS], by_slurm[SHARD_INPUTS], reversed[SHARD_INPUTS];
        run_shards("JOB_COMPLETION_INDEX", list, paths, n, env_kubernetes, by_k8s);
        run_shards("SLURM_ARRAY_TASK_ID", list, paths, n, env_slurm, by_slurm);
        run_shards("reversed list", rlist, paths, n, env_kubernetes, reversed);
        int used[8] = { 0 };
        for (int i = 0; i < SHARD_INPUTS; i++) {
            /* The same input lands on the same shard, whatever the
             * scheduler or the order of the list. */
            CHECK_EQ(by_k8s[i], by_slurm[i]);
            CHECK_EQ(by_k8s[i], reversed[i]);
            if (by_k8s[i] >= 0) {
                used[by_k8s[i]]++;
            }
        }
        for (int s = 0; s < n && n <= 3; s++) {
            CHECK(used[s] > 0);   /* 23 inputs leave no shard of three empty */
        }
    }
}

/* --shard I/N gives the same shards as the schedulers' variables, and
 * wins over them. */
SR_TEST(shard_option_matches_the_environment)
{
    NEED_CLI();
    char dir[1024], list[1100], out[1024], logp[1100], paths[SHARD_INPUTS][1200];
    fresh_dir("shard_opt", dir, sizeof dir);
    snprintf(list, sizeof list, "%s/list.txt", dir);
    REQUIRE(write_shard_models(dir, list, false, paths));
    int by_k8s[SHARD_INPUTS];
    run_shards("JOB_COMPLETION_INDEX", list, paths, 3, env_kubernetes, by_k8s);
    for (int s = 0; s < 3; s++) {
        char shard[16];
        snprintf(shard, sizeof shard, "%d/3", s);
        fresh_dir("shard_opt_out", out, sizeof out);
        snprintf(logp, sizeof logp, "%s/log.jsonl", out);
        run_result r;
        /* A bad scheduler variable is ignored when --shard is given. */
        REQUIRE(run_env(ARGS("render", "--batch", list, "--output-dir", out, "--size", "8x8",
                             "--log", logp, "--shard", shard),
                        ENV("JOB_COMPLETION_INDEX=junk"), NULL, &r));
        CHECK_EQ(r.status, 0);
        record recs[SHARD_INPUTS + 1];
        int n = read_log(logp, recs, SHARD_INPUTS + 1);
        int want = 0;
        for (int i = 0; i < SHARD_INPUTS; i++) {
            want += by_k8s[i] == s;
            CHECK((find_record(recs, n, paths[i]) != NULL) == (by_k8s[i] == s));
        }
        CHECK_EQ(n, want);
    }
}

/* Bad shard settings, from the option or from the environment, are
 * refused with one line naming the option or the variable. */
SR_TEST(bad_shard_settings_are_refused)
{
    NEED_CLI();
    char dir[1024], out[1024], model[1100];
    fresh_dir("shard_bad", dir, sizeof dir);
    fresh_dir("shard_bad_out", out, sizeof out);
    snprintf(model, sizeof model, "%s/m.stl", dir);
    REQUIRE(write_stl(model, 1.0f));
    struct {
        const char *const *env;
        const char *shard, *count, *needle;
    } cases[] = {
        { NO_ENV, "3/3", NULL, "--shard" },
        { NO_ENV, "1", NULL, "--shard" },
        { NO_ENV, "-1/2", NULL, "--shard" },
        { NO_ENV, "0/0", NULL, "--shard" },
        { NO_ENV, "a/b", NULL, "--shard" },
        { NO_ENV, "0/2", "2", "--shard-count" },
        { NO_ENV, NULL, "2", "--shard-count" },
        { ENV("JOB_COMPLETION_INDEX=1"), NULL, NULL, "--shard-count" },
        { ENV("JOB_COMPLETION_INDEX=abc"), NULL, "4", "JOB_COMPLETION_INDEX" },
        { ENV("JOB_COMPLETION_INDEX="), NULL, "4", "JOB_COMPLETION_INDEX" },
        { ENV("JOB_COMPLETION_INDEX=4"), NULL, "4", "JOB_COMPLETION_INDEX" },
        { ENV("JOB_COMPLETION_INDEX=-1"), NULL, "4", "JOB_COMPLETION_INDEX" },
        { ENV("JOB_COMPLETION_INDEX=0"), NULL, "zero", "--shard-count" },
        { ENV("SLURM_ARRAY_TASK_ID=x", "SLURM_ARRAY_TASK_COUNT=2"), NULL, NULL,
          "SLURM_ARRAY_TASK_ID" },
        { ENV("SLURM_ARRAY_TASK_ID=1"), NULL, NULL, "SLURM_ARRAY_TASK_COUNT" },
        { ENV("SLURM_ARRAY_TASK_ID=5", "SLURM_ARRAY_TASK_COUNT=3"), NULL, NULL,
          "SLURM_ARRAY_TASK_ID 5" },
        { ENV("SLURM_ARRAY_TASK_ID=1", "SLURM_ARRAY_TASK_COUNT=0"), NULL, NULL,
          "SLURM_ARRAY_TASK_COUNT" },
        { ENV("SLURM_ARRAY_TASK_ID=3", "SLURM_ARRAY_TASK_COUNT=2", "SLURM_ARRAY_TASK_STEP=2"),
          NULL, NULL, "SLURM_ARRAY_TASK_ID 3" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const char *args[16] = { "render", model, "--output-dir", out };
        int n = 4;
        if (cases[i].shard) {
            args[n++] = "--shard";
            args[n++] = cases[i].shard;
        }
        if (cases[i].count) {
            args[n++] = "--shard-count";
            args[n++] = cases[i].count;
        }
        args[n] = NULL;
        run_result r;
        REQUIRE(run_env(args, cases[i].env, NULL, &r));
        if (r.status != 2 || count_lines(r.err) != 1 || !strstr(r.err, cases[i].needle)) {
            FAILF("case %zu (%s): status %d, stderr \"%s\" (expected 2 and one line with '%s')",
                  i, cases[i].env[0] ? cases[i].env[0] : cases[i].shard, r.status, r.err,
                  cases[i].needle);
        }
    }
    char png[1200];
    snprintf(png, sizeof png, "%s/m.png", out);
    CHECK(!file_exists(png));
}

/* A shard killed part-way (SIGKILL) leaves only whole images; rerun with
 * --skip-existing it renders what was missing and redoes nothing that was
 * finished. */
SR_TEST(killed_shard_resumes_with_skip_existing)
{
    NEED_CLI();
    char dir[1024], list[1100], out[1024], logp[1100], err[1100], paths[SHARD_INPUTS][1200];
    fresh_dir("kill", dir, sizeof dir);
    fresh_dir("kill_out", out, sizeof out);
    snprintf(list, sizeof list, "%s/list.txt", dir);
    snprintf(logp, sizeof logp, "%s/first.jsonl", dir);
    snprintf(err, sizeof err, "%s/stderr.txt", dir);
    REQUIRE(write_shard_models(dir, list, false, paths));
    /* Big, supersampled images on one thread: slow enough to be killed
     * part-way on any machine. */
    const char *const args[] = { "render", "--batch", list, "--output-dir", out, "--size",
                                 "1024x1024", "--aa", "ssaa4", "--threads", "1", "--log", logp,
                                 NULL };
    pid_t pid = start_cli(args, ENV("SLURM_ARRAY_TASK_ID=0", "SLURM_ARRAY_TASK_COUNT=1"), NULL,
                          err);
    REQUIRE(pid > 0);
    /* Kill once two records are written. */
    for (int waited = 0; waited < 60000 * SR_TEST_SLOWDOWN; waited++) {
        struct stat st;
        FILE *f = fopen(logp, "r");
        int lines = 0;
        for (int c; f && (c = fgetc(f)) != EOF;) {
            lines += c == '\n';
        }
        if (f) {
            fclose(f);
        }
        if (lines >= 2 || (stat(logp, &st) == 0 && waitpid(pid, NULL, WNOHANG) == pid)) {
            break;
        }
        struct timespec ts = { 0, 1000000 };
        nanosleep(&ts, NULL);
    }
    kill(pid, SIGKILL);
    int status = wait_status(pid);
    if (status != 128 + SIGKILL) {
        SKIP("the batch finished before it could be killed");
    }

    /* Only whole images, and a record for each. */
    record first[SHARD_INPUTS + 1];
    int nfirst = read_log(logp, first, SHARD_INPUTS + 1);
    CHECK(nfirst >= 2 && nfirst < SHARD_INPUTS);
    struct stat done[SHARD_INPUTS];
    bool had[SHARD_INPUTS];
    int nhad = 0;
    for (int i = 0; i < SHARD_INPUTS; i++) {
        char png[1300];
        snprintf(png, sizeof png, "%s/m%02d.png", out, i);
        had[i] = stat(png, &done[i]) == 0;
        nhad += had[i];
        if (had[i]) {
            CHECK(is_thumbnail(png, 1024, 1024));
        }
    }
    CHECK(nhad >= nfirst);

    snprintf(logp, sizeof logp, "%s/second.jsonl", dir);
    run_result r;
    REQUIRE(run(ARGS("render", "--batch", list, "--output-dir", out, "--size", "1024x1024",
                     "--aa", "none", "--skip-existing", "--log", logp), &r));
    CHECK_EQ(r.status, 0);
    record second[SHARD_INPUTS + 1];
    int nsecond = read_log(logp, second, SHARD_INPUTS + 1);
    CHECK_EQ(nsecond, SHARD_INPUTS);
    for (int i = 0; i < SHARD_INPUTS && nsecond == SHARD_INPUTS; i++) {
        const record *rec = find_record(second, nsecond, paths[i]);
        char png[1300];
        snprintf(png, sizeof png, "%s/m%02d.png", out, i);
        CHECK(rec && strcmp(rec->status, had[i] ? "skipped" : "ok") == 0);
        CHECK(had[i] ? same_file_state(png, &done[i]) : is_thumbnail(png, 1024, 1024));
    }
}

/* ---- views and sheets --------------------------------------------------- */

static uint8_t *read_rgba(const char *path, int *w, int *h)
{
    uint8_t *px = NULL;
    sr_io_error err;
    if (sr_read_image(path, w, h, &px, &err) != SR_OK) {
        FAILF("%s: %s", path, err.message);
        return NULL;
    }
    return px;
}

/* --views N: N images a model, {view} in their names, each a different
 * side; the same angle gives the same image whatever N. */
SR_TEST(views_render_a_turntable)
{
    NEED_CLI();
    char dir[1024], out[1024], model[1100], logp[1100];
    fresh_dir("views", dir, sizeof dir);
    fresh_dir("views_out", out, sizeof out);
    snprintf(model, sizeof model, "%s/m.stl", dir);
    snprintf(logp, sizeof logp, "%s/log.jsonl", dir);
    REQUIRE(write_stl(model, 3.0f));
    run_result r;
    REQUIRE(run(ARGS("render", model, "--views", "4", "--output-dir", out, "--size", "48x48",
                     "--log", logp), &r));
    CHECK_EQ(r.status, 0);
    record recs[8];
    CHECK_EQ(read_log(logp, recs, 8), 4);
    uint8_t *px[4] = { NULL };
    for (int v = 0; v < 4; v++) {
        char png[1200];
        snprintf(png, sizeof png, "%s/m_%d.png", out, v);
        CHECK(is_thumbnail(png, 48, 48));
        CHECK(find_record(recs, 4, model) && strcmp(recs[v].output, png) == 0);
        int w, h;
        px[v] = read_rgba(png, &w, &h);
    }
    for (int v = 1; v < 4; v++) {
        CHECK(px[0] && px[v] && memcmp(px[0], px[v], 48 * 48 * 4) != 0);
    }
    /* 180 degrees is view 2 of 4 and view 4 of 8. */
    fresh_dir("views_out", out, sizeof out);
    REQUIRE(run(ARGS("render", model, "--views", "8", "--output-dir", out, "--size", "48x48",
                     "--name", "v{view}.png"), &r));
    CHECK_EQ(r.status, 0);
    char png[1200];
    snprintf(png, sizeof png, "%s/v4.png", out);
    int w, h;
    uint8_t *half = read_rgba(png, &w, &h);
    CHECK(half && px[2] && memcmp(half, px[2], 48 * 48 * 4) == 0);
    free(half);
    for (int v = 0; v < 4; v++) {
        free(px[v]);
    }
    REQUIRE(run(ARGS("render", model, "--views", "4", "--output-dir", out, "--name", "x.png"),
                &r));
    CHECK(r.status == 2 && strstr(r.err, "{view}"));
}

/* --sheet: every image in one grid, captioned; a failed model's cell is
 * empty with its caption, and the sheet is still written. */
SR_TEST(sheet_lays_out_models_with_captions)
{
    NEED_CLI();
    char dir[1024], out[1024], sheet[1100], paths[MODELS][1200];
    fresh_dir("sheet", dir, sizeof dir);
    fresh_dir("sheet_out", out, sizeof out);
    REQUIRE(write_models(dir, paths) == MODELS);
    snprintf(sheet, sizeof sheet, "%s/sheet.png", out);
    run_result r;
    REQUIRE(run(ARGS("render", dir, "--sheet", sheet, "--size", "40x30", "--sheet-columns", "2"),
                &r));
    CHECK_EQ(r.status, 3);
    CHECK_EQ(count_lines(r.err), 1);
    int w, h;
    uint8_t *px = read_rgba(sheet, &w, &h);
    REQUIRE(px != NULL);
    /* Five cells, two a row: three rows of 30 pixels and a 12-pixel caption. */
    CHECK(w == 80 && h == 3 * 42);
    /* The first cell is the first model's image as a batch draws it alone. */
    REQUIRE(run(ARGS("render", paths[0], "--output-dir", out, "--size", "40x30"), &r));
    char single[1200];
    snprintf(single, sizeof single, "%s/a_tetra.png", out);
    int sw, sh;
    uint8_t *one = read_rgba(single, &sw, &sh);
    bool same = one != NULL;
    for (int y = 0; same && y < 30; y++) {
        same = memcmp(px + 4 * (size_t)(y * w), one + 4 * (size_t)(y * 40), 4 * 40) == 0;
    }
    CHECK(same);
    free(one);
    /* Captions: ink in every used cell's strip; the bad model's (cell 2,
     * left of row 1) is red, and its image area is background only. */
    for (int cell = 0; cell < MODELS; cell++) {
        int x0 = (cell % 2) * 40, y0 = (cell / 2) * 42;
        size_t ink = 0, red = 0, drawn = 0;
        for (int y = y0 + 30; y < y0 + 42; y++) {
            for (int x = x0; x < x0 + 40; x++) {
                const uint8_t *p = px + 4 * (size_t)(y * w + x);
                ink += memcmp(p, px, 3) != 0;
                red += p[0] > 160 && p[1] < 120;
            }
        }
        for (int y = y0; y < y0 + 30; y++) {
            for (int x = x0; x < x0 + 40; x++) {
                drawn += memcmp(px + 4 * (size_t)(y * w + x), px, 3) != 0;
            }
        }
        CHECK(ink > 10);
        CHECK((red > 0) == (cell == BAD_MODEL));
        CHECK((drawn > 0) == (cell != BAD_MODEL));
    }
    free(px);

    /* Sheets that cannot be made say what would fit: the columns that
     * keep them within 8192 pixels a side, else a smaller size. */
    REQUIRE(run(ARGS("render", dir, "--sheet", sheet, "--size", "4000x4000"), &r));
    CHECK(r.status == 2 && count_lines(r.err) == 1 &&
          strstr(r.err, "--sheet: 5 images of 4000x4000 need more than 8192 pixels a side: give "
                        "a smaller --size or fewer models"));
    REQUIRE(run(ARGS("render", paths[0], "--views", "24", "--sheet", sheet, "--size", "512x512"),
                &r));
    CHECK(r.status == 2 && count_lines(r.err) == 1 &&
          strstr(r.err, "--sheet: 24 images of 512x512, 24 a row, need more than 8192 pixels a "
                        "side: give --sheet-columns from 2 to 16"));
    REQUIRE(run(ARGS("render", dir, "--sheet", sheet, "--size", "2000x2000", "--sheet-columns",
                     "1"), &r));
    CHECK(r.status == 2 && count_lines(r.err) == 1 &&
          strstr(r.err, "1 a row, need more than 8192 pixels a side: give --sheet-columns from "
                        "2 to 4"));
    REQUIRE(run(ARGS("render", dir, "--sheet", sheet, "--skip-existing"), &r));
    CHECK(r.status == 2 && strstr(r.err, "--skip-existing"));
    REQUIRE(run(ARGS("render", dir, "--sheet-columns", "3"), &r));
    CHECK(r.status == 2 && strstr(r.err, "--sheet"));
}

/* --animate: each model's views as the frames of one animated WebP. */
SR_TEST(animate_writes_a_turntable_webp)
{
    NEED_CLI();
    char dir[1024], out[1024], model[1100], webp[1200];
    fresh_dir("anim", dir, sizeof dir);
    fresh_dir("anim_out", out, sizeof out);
    snprintf(model, sizeof model, "%s/m.obj", dir);
    REQUIRE(write_obj(model, 1.0f));
    run_result r;
    REQUIRE(run(ARGS("render", model, "--views", "5", "--animate", "{stem}.webp",
                     "--output-dir", out, "--size", "40x30"), &r));
    if (r.status == 2 && strstr(r.err, "without libwebp")) {
        SKIP("this softrast was built without libwebp");
    }
    CHECK_EQ(r.status, 0);
    snprintf(webp, sizeof webp, "%s/m.webp", out);
    size_t n = 0;
    uint8_t *bytes = sr_test_read_file(webp, &n);
    bool animated = false;
    CHECK_EQ(bytes ? count_anmf(bytes, n, &animated) : -1, 5);
    CHECK(animated);
    free(bytes);
    const struct {
        const char *const *args;
        const char *needle;
    } bad[] = {
        { ARGS("render", model, "--animate", "t.png", "--output-dir", out), ".webp" },
        { ARGS("render", model, "--animate", "t.webp", "--sheet", "s.png"), "--sheet" },
        { ARGS("render", model, "--animate", "t.webp", "--name", "x.png"), "--name" },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        REQUIRE(run(bad[i].args, &r));
        CHECK(r.status == 2 && count_lines(r.err) == 1 && strstr(r.err, bad[i].needle));
    }
}

/* On a terminal, a progress line on stderr, redrawn in place, that ends
 * with every input done and the failures counted; the failure's own line
 * is printed over a cleared line. */
SR_TEST(progress_line_on_a_terminal)
{
    NEED_CLI();
    char dir[1024], out[1024], paths[MODELS][1200];
    fresh_dir("tty", dir, sizeof dir);
    fresh_dir("tty_out", out, sizeof out);
    REQUIRE(write_models(dir, paths) == MODELS);
    int master = posix_openpt(O_RDWR | O_NOCTTY);
    if (master < 0 || grantpt(master) != 0 || unlockpt(master) != 0) {
        SKIP("no pseudo-terminal");
    }
    char slave_path[128];
    snprintf(slave_path, sizeof slave_path, "%s", ptsname(master));
    /* Held open here too, so that what the child wrote stays readable. */
    int slave = open(slave_path, O_RDWR | O_NOCTTY);
    REQUIRE(slave >= 0);
    pid_t pid = start_cli(ARGS("render", dir, "--output-dir", out, "--size", "16x16"), NO_ENV,
                          NULL, slave_path);
    REQUIRE(pid > 0);
    CHECK_EQ(wait_status(pid), 3);
    fcntl(master, F_SETFL, fcntl(master, F_GETFL) | O_NONBLOCK);
    char text[8192];
    size_t n = 0;
    for (ssize_t got; n + 1 < sizeof text &&
                      (got = read(master, text + n, sizeof text - 1 - n)) > 0;) {
        n += (size_t)got;
    }
    text[n] = '\0';
    close(slave);
    close(master);
    CHECK_STR_CONTAINS(text, "\r\033[K");
    CHECK_STR_CONTAINS(text, "5/5");
    CHECK_STR_CONTAINS(text, "1 failed");
    CHECK_STR_CONTAINS(text, "\r\033[Ksoftrast: ");
    CHECK_STR_CONTAINS(text, "c_bad.stl");
    CHECK(n > 0 && text[n - 1] == '\n');
}
