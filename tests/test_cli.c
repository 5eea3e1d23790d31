/* test_cli.c - the softrast tool as a user meets it: the real executable
 * (SR_CLI_PATH) run with posix_spawn, no shell, stdout and stderr captured.
 *
 * Failures: every file of the malformed-input corpus (tests/data/bad,
 * listed with its expected status and message in MANIFEST.txt) and every
 * bad option must exit with the documented status and exactly one line on
 * stderr that says where the problem is, and must leave the output
 * directory as it was: no new file, no temporary, an existing image
 * untouched.  Successes: --version, a --help that lists every option,
 * images of the requested size for each mode, identical bytes from the
 * three rasterizers, every shared model in every shading mode, and an
 * atomic replacement of an existing image. */
#include "gltf_write.h"
#include "softrast.h"
#include "softrast_io.h"
#include "sr_test.h"

#ifdef SR_HAVE_JANSSON_TEST
#include <jansson.h>
#endif

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

extern char **environ;

#define FAILF(...) sr_test_fail(__FILE__, __LINE__, __VA_ARGS__)

/* A child that runs longer than this is killed and counted as a failure
 * (a reader stuck in a loop must not hang the suite). */
#define CHILD_TIMEOUT_MS (60000 * SR_TEST_SLOWDOWN)

#define MAX_ARGS 48

/* ---- helpers ------------------------------------------------------------ */

static char *read_whole(const char *path, size_t *len)
{
    *len = 0;
    FILE *f = fopen(path, "rb");
    if (!f) {
        return NULL;
    }
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap + 1);
    size_t got;
    while (buf && (got = fread(buf + n, 1, cap - n, f)) > 0) {
        n += got;
        if (n == cap) {
            char *nb = realloc(buf, 2 * cap + 1);
            if (!nb) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = nb;
            cap *= 2;
        }
    }
    fclose(f);
    if (buf) {
        buf[n] = 0;
        *len = n;
    }
    return buf;
}

static bool write_whole(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        return false;
    }
    bool ok = fwrite(data, 1, n, f) == n;
    return fclose(f) == 0 && ok;
}

static bool is_dir(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

/* Empty `path` (one level: files, and empty subdirectories such as
 * adir.obj), creating it if needed. */
static void clean_dir(const char *path)
{
    mkdir(path, 0777);
    DIR *d = opendir(path);
    if (!d) {
        return;
    }
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) {
            continue;
        }
        char p[2048];
        snprintf(p, sizeof p, "%s/%s", path, e->d_name);
        if (unlink(p) != 0) {
            rmdir(p);
        }
    }
    closedir(d);
}

/* A fresh, empty directory of this test file's own under the output dir. */
static const char *fresh_dir(const char *name, char *buf, size_t n)
{
    snprintf(buf, n, "%s/cli_%s", sr_test_out_dir(), name);
    clean_dir(buf);
    return buf;
}

/* Entries of `dir` other than . and ..; the first one's name in `first`. */
static int count_entries(const char *dir, char *first, size_t first_n)
{
    DIR *d = opendir(dir);
    if (!d) {
        return -1;
    }
    int n = 0;
    struct dirent *e;
    if (first && first_n) {
        first[0] = 0;
    }
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) {
            continue;
        }
        if (n == 0 && first) {
            snprintf(first, first_n, "%s", e->d_name);
        }
        n++;
    }
    closedir(d);
    return n;
}

/* A model small enough to draw in any test. */
#define ONE_TRIANGLE_OBJ "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n"

typedef struct cli_run {
    int status;         /* exit status; 128 + signal when killed; -1 when not run */
    char *out, *err;    /* captured stdout and stderr, NUL-terminated */
    size_t out_len, err_len;
} cli_run;

static void cli_run_free(cli_run *r)
{
    free(r->out);
    free(r->err);
    r->out = r->err = NULL;
}

/* Run SR_CLI_PATH with `args` (NULL-terminated, without the program name). */
static bool run_cli(const char *const *args, cli_run *r)
{
    memset(r, 0, sizeof *r);
    r->status = -1;
#ifdef SR_CLI_PATH
    char out_path[1024], err_path[1024];
    snprintf(out_path, sizeof out_path, "%s/cli_stdout.txt", sr_test_out_dir());
    snprintf(err_path, sizeof err_path, "%s/cli_stderr.txt", sr_test_out_dir());

    const char *argv[MAX_ARGS + 16];
    if (!sr_test_program_argv(SR_CLI_PATH, args, argv, sizeof argv / sizeof argv[0])) {
        FAILF("too many arguments for run_cli");
        return false;
    }

    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 1, out_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&fa, 2, err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid;
    int e = posix_spawn(&pid, argv[0], &fa, NULL, (char *const *)argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (e != 0) {
        FAILF("cannot run %s: %s", SR_CLI_PATH, strerror(e));
        return false;
    }
    int ws = 0;
    long waited_us = 0, step_us = 100;
    for (;;) {
        pid_t w = waitpid(pid, &ws, WNOHANG);
        if (w == pid) {
            break;
        }
        if (w < 0 && errno != EINTR) {
            FAILF("waitpid: %s", strerror(errno));
            return false;
        }
        if (waited_us > (long)CHILD_TIMEOUT_MS * 1000) {
            kill(pid, SIGKILL);
            waitpid(pid, &ws, 0);
            FAILF("%s %s ... did not finish within %d ms", SR_CLI_PATH, args[0] ? args[0] : "",
                  CHILD_TIMEOUT_MS);
            break;
        }
        struct timespec ts = { 0, step_us * 1000 };
        nanosleep(&ts, NULL);
        waited_us += step_us;
        if (step_us < 5000) {
            step_us *= 2;
        }
    }
    r->status = WIFEXITED(ws) ? WEXITSTATUS(ws) : WIFSIGNALED(ws) ? 128 + WTERMSIG(ws) : -1;
    r->out = read_whole(out_path, &r->out_len);
    r->err = read_whole(err_path, &r->err_len);
    if (!r->out || !r->err) {
        FAILF("cannot read the captured output");
        cli_run_free(r);
        return false;
    }
    return true;
#else
    (void)args;
    return false;
#endif
}

/* Exactly one non-empty line, ending in a newline, no NUL. */
static bool is_one_line(const char *s, size_t n)
{
    return n >= 2 && s[n - 1] == '\n' && s[0] != '\n' && !memchr(s, '\n', n - 1) &&
           strlen(s) == n;
}

/* The args (NULL-terminated) followed by more (NULL-terminated), into dst
 * of MAX_ARGS + 1 entries. */
static void join_args(const char **dst, const char *const *a, const char *const *b)
{
    int n = 0;
    for (int i = 0; a && a[i] && n < MAX_ARGS; i++) {
        dst[n++] = a[i];
    }
    for (int i = 0; b && b[i] && n < MAX_ARGS; i++) {
        dst[n++] = b[i];
    }
    dst[n] = NULL;
}

/* Check a failed run: its status and one line holding `needle`.  A build
 * without the library a case needs (glTF, SVG, JPEG, the viewer) refuses
 * it with one line of its own, "FILE: ... (softrast was built without
 * X...)", exit 2, before reaching what the case checks: that passes. */
static void check_failure_output(const char *label, const cli_run *r, int status,
                                 const char *needle)
{
    if (status == 2 && r->status == 2 && is_one_line(r->err, r->err_len) &&
        strstr(r->err, "(softrast was built without") && r->out_len == 0) {
        return;
    }
    if (r->status != status) {
        FAILF("%s: exit status %d, expected %d (stderr: %s)", label, r->status, status, r->err);
    }
    if (!is_one_line(r->err, r->err_len)) {
        FAILF("%s: stderr is not exactly one line:\n%s", label, r->err);
    }
    if (!strstr(r->err, needle)) {
        FAILF("%s: stderr \"%.*s\" does not contain \"%s\"", label,
              r->err_len && r->err[r->err_len - 1] == '\n' ? (int)r->err_len - 1 : (int)r->err_len,
              r->err, needle);
    }
    if (r->out_len != 0) {
        FAILF("%s: unexpected output on stdout: %s", label, r->out);
    }
}

static const unsigned char *sentinel(size_t *n)
{
    static unsigned char bytes[777];
    for (size_t i = 0; i < sizeof bytes; i++) {
        bytes[i] = (unsigned char)(i * 31 + 7);
    }
    memcpy(bytes, "not an image, must survive", 26);
    *n = sizeof bytes;
    return bytes;
}

/* `softrast render -o DIR/out.png ARGS` must fail with `status` and one
 * line holding `needle`, twice: into an empty directory, which must stay
 * empty (no image, no temporary), and over an existing out.png, which
 * must keep its bytes. */
static void expect_render_failure(const char *label, const char *const *args, int status,
                                  const char *needle)
{
    char dir[1024], out[1100];
    fresh_dir("fail", dir, sizeof dir);
    snprintf(out, sizeof out, "%s/out.png", dir);
    /* -o first, so that an option left without its value comes last. */
    const char *head[] = { "render", "-o", out, NULL };
    const char *all[MAX_ARGS + 1];
    join_args(all, head, args);

    for (int pass = 0; pass < 2; pass++) {
        clean_dir(dir);
        size_t sn;
        const unsigned char *sb = sentinel(&sn);
        if (pass == 1 && !write_whole(out, sb, sn)) {
            FAILF("%s: cannot write %s", label, out);
            return;
        }
        cli_run r;
        if (!run_cli(all, &r)) {
            FAILF("%s: the CLI did not run", label);
            return;
        }
        char what[1200];
        snprintf(what, sizeof what, "%s (%s)", label, pass ? "over an existing file" : "fresh");
        check_failure_output(what, &r, status, needle);
        cli_run_free(&r);

        char first[256];
        int n = count_entries(dir, first, sizeof first);
        if (pass == 0 && n != 0) {
            FAILF("%s: the failed run left '%s' in the output directory", what, first);
        }
        if (pass == 1) {
            size_t len;
            char *now = read_whole(out, &len);
            if (!now || len != sn || memcmp(now, sb, sn) != 0) {
                FAILF("%s: the existing output file was changed (%zu bytes now)", what, len);
            }
            free(now);
            if (n != 1) {
                FAILF("%s: %d entries in the output directory, expected only out.png", what, n);
            }
        }
    }
}

static const char *bad_dir(char *buf, size_t n)
{
    snprintf(buf, n, "%s/data/bad", sr_test_src_dir());
    return buf;
}

#define ARGS(...) ((const char *const[]){ __VA_ARGS__, NULL })

/* Whether this softrast has the svg command (it needs expat). */
static bool svg_command_built(void)
{
    return sr_io_have_svg();
}

/* ---- the malformed-input corpus ---------------------------------------- */

typedef struct manifest_entry {
    char name[256];
    int status;
    char needle[512];
} manifest_entry;

/* Reads MANIFEST.txt: NAME<TAB>STATUS<TAB>SUBSTRING per line. */
static int read_manifest(manifest_entry *out, int max)
{
    char dir[1024], path[1100];
    snprintf(path, sizeof path, "%s/MANIFEST.txt", bad_dir(dir, sizeof dir));
    size_t len;
    char *text = read_whole(path, &len);
    if (!text) {
        FAILF("cannot read %s", path);
        return -1;
    }
    int n = 0, lineno = 0;
    for (char *line = text; *line;) {
        char *nl = strchr(line, '\n');
        if (nl) {
            *nl = 0;
        }
        lineno++;
        if (line[0] && line[0] != '#') {
            char *t1 = strchr(line, '\t');
            char *t2 = t1 ? strchr(t1 + 1, '\t') : NULL;
            char *end = NULL;
            long st = t2 ? strtol(t1 + 1, &end, 10) : -1;
            if (!t2 || end != t2 || (st != 1 && st != 2) || !t2[1] || n == max ||
                (size_t)(t1 - line) >= sizeof out[n].name ||
                strlen(t2 + 1) >= sizeof out[n].needle) {
                FAILF("%s:%d: expected NAME<TAB>STATUS<TAB>SUBSTRING", path, lineno);
            } else {
                memcpy(out[n].name, line, (size_t)(t1 - line));
                out[n].name[t1 - line] = 0;
                out[n].status = (int)st;
                snprintf(out[n].needle, sizeof out[n].needle, "%s", t2 + 1);
                n++;
            }
        }
        if (!nl) {
            break;
        }
        line = nl + 1;
    }
    free(text);
    return n;
}

SR_TEST(every_bad_model_fails_with_one_line_and_writes_nothing)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    static manifest_entry cases[256];
    int n = read_manifest(cases, 256);
    REQUIRE(n >= 40);
    char dir[1024];
    bad_dir(dir, sizeof dir);
    for (int i = 0; i < n; i++) {
        char path[1400];
        snprintf(path, sizeof path, "%s/%.255s", dir, cases[i].name);
        struct stat st;
        if (stat(path, &st) != 0 || !S_ISREG(st.st_mode)) {
            FAILF("%s: listed in MANIFEST.txt but not a file in tests/data/bad", cases[i].name);
            continue;
        }
        /* The message starts with the file name (and its line or byte). */
        if (strncmp(cases[i].needle, cases[i].name, strlen(cases[i].name)) != 0) {
            FAILF("%s: MANIFEST.txt substring should start with the file name", cases[i].name);
        }
        expect_render_failure(cases[i].name, ARGS(path, "--size", "16x12"), cases[i].status,
                              cases[i].needle);
    }
}

SR_TEST(every_corpus_file_is_in_the_manifest)
{
    static manifest_entry cases[256];
    int n = read_manifest(cases, 256);
    REQUIRE(n > 0);
    char dir[1024];
    DIR *d = opendir(bad_dir(dir, sizeof dir));
    REQUIRE(d != NULL);
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.' || strcmp(e->d_name, "MANIFEST.txt") == 0) {
            continue;
        }
        bool listed = false;
        for (int i = 0; i < n && !listed; i++) {
            listed = strcmp(cases[i].name, e->d_name) == 0;
        }
        if (!listed) {
            FAILF("tests/data/bad/%s is not listed in MANIFEST.txt", e->d_name);
        }
    }
    closedir(d);
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < i; j++) {
            if (strcmp(cases[i].name, cases[j].name) == 0) {
                FAILF("%s is listed twice in MANIFEST.txt", cases[i].name);
            }
        }
    }
}

SR_TEST(directory_named_like_a_model_is_rejected)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024], path[1100];
    fresh_dir("models", dir, sizeof dir);
    snprintf(path, sizeof path, "%s/adir.obj", dir);
    REQUIRE(mkdir(path, 0777) == 0);
    expect_render_failure("adir.obj", ARGS(path, "--size", "16x12"), 2,
                          "adir.obj: is a directory, not a model file");
    /* An extension no built-in reader claims takes another path. */
    snprintf(path, sizeof path, "%s/adir.off", dir);
    REQUIRE(mkdir(path, 0777) == 0);
    expect_render_failure("adir.off", ARGS(path, "--size", "16x12"), 2, "adir.off: is a directory");
}

SR_TEST(missing_model_file_is_reported)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024], path[1100];
    fresh_dir("models", dir, sizeof dir);
    const char *names[] = { "no_such_model.obj", "no_such_model.ply", "no_such_model.stl",
                            "no_such_model.off", "no_such_model" };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        char needle[300];
        snprintf(needle, sizeof needle, "%s: cannot open", names[i]);
        expect_render_failure(names[i], ARGS(path, "--size", "16x12"), 2, needle);
    }
}

/* --environment FILE.hdr that is missing or not a Radiance picture: exit
 * 2, one line naming the file, no output. */
SR_TEST(bad_environment_file_is_reported)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024], missing[1100], junk[1100];
    fresh_dir("environments", dir, sizeof dir);
    snprintf(missing, sizeof missing, "%s/no_such.hdr", dir);
    snprintf(junk, sizeof junk, "%s/junk.hdr", dir);
    const char *text = "not a radiance picture\n";
    REQUIRE(write_whole(junk, text, strlen(text)));
    expect_render_failure("missing environment", ARGS("--size", "16x12", "--environment", missing),
                          2, "no_such.hdr: cannot open");
    expect_render_failure("junk environment", ARGS("--size", "16x12", "--environment", junk), 2,
                          "junk.hdr");
}

/* Opening a FIFO for reading waits for a writer, here forever: each input
 * the CLI reads must refuse one at once (run_cli kills a child that hangs),
 * except an MTL, which is skipped as a missing one is. */
SR_TEST(a_fifo_as_input_is_refused_without_waiting)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024], fifo[1100], fifo_obj[1100], model[1100], textured[1100], out[1100];
    fresh_dir("fifo", dir, sizeof dir);
    snprintf(fifo, sizeof fifo, "%s/f", dir);
    snprintf(fifo_obj, sizeof fifo_obj, "%s/f.obj", dir);
    REQUIRE(mkfifo(fifo, 0644) == 0);
    REQUIRE(mkfifo(fifo_obj, 0644) == 0);

    expect_render_failure("FIFO f.obj", ARGS(fifo_obj, "--size", "16x12"), 2,
                          "f.obj: not a regular file");
    expect_render_failure("FIFO f", ARGS(fifo, "--size", "16x12"), 2, "/f: not a regular file");

    static const char textured_obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                                       "f 1/1 2/2 3/3\n";
    snprintf(textured, sizeof textured, "%s/textured.obj", dir);
    REQUIRE(write_whole(textured, textured_obj, sizeof textured_obj - 1));
    expect_render_failure("--texture FIFO", ARGS(textured, "--texture", fifo, "--size", "16x12"),
                          2, "/f: not a regular file");

    static const char mtllib_obj[] = "mtllib f\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    snprintf(model, sizeof model, "%s/m.obj", dir);
    snprintf(out, sizeof out, "%s/m.png", dir);
    REQUIRE(write_whole(model, mtllib_obj, sizeof mtllib_obj - 1));
    cli_run r;
    REQUIRE(run_cli(ARGS("render", model, "-o", out, "--size", "16x12"), &r));
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.err_len, 0);
    CHECK(!is_dir(out) && access(out, F_OK) == 0);
    cli_run_free(&r);

    /* softrast svg is there only when the build found expat. */
    if (svg_command_built()) {
        snprintf(out, sizeof out, "%s/svg.png", dir);
        REQUIRE(run_cli(ARGS("svg", fifo, "-o", out), &r));
        check_failure_output("svg FIFO", &r, 2, "/f: not a regular file");
        CHECK(access(out, F_OK) != 0);
        cli_run_free(&r);
    }
}

/* Assimp's own messages (when the build has Assimp) are one line too and
 * say they come from Assimp; without it the message says how to get it.
 * glTF is read by the glTF reader under every look, whose JSON errors
 * name the line. */
SR_TEST(garbage_in_other_formats_gives_one_line)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024], path[1400], needle[300];
    bad_dir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/garbage.off", dir);
    snprintf(needle, sizeof needle, "garbage.off: %s",
             sr_io_have_assimp() ? "Assimp: " : "format not supported");
    expect_render_failure("garbage.off", ARGS(path, "--size", "16x12", "--shading", "phong"), 2,
                          needle);
    if (!sr_io_have_gltf()) {
        return;
    }
    snprintf(path, sizeof path, "%s/garbage.gltf", dir);
    expect_render_failure("garbage.gltf, pbr", ARGS(path, "--size", "16x12"), 2,
                          "garbage.gltf:1: invalid JSON");
    expect_render_failure("garbage.gltf, phong",
                          ARGS(path, "--size", "16x12", "--shading", "phong"), 2,
                          "garbage.gltf:1: invalid JSON");
}

/* A glTF reader's warning reaches stderr as the reader words it, one line
 * "FILE: warning: ...", not with a second "warning:" in front. */
SR_TEST(a_gltf_warning_is_one_line_said_once)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson (glTF)");
    }
    char dir[1024], model[1100], out[1100];
    fresh_dir("gltfwarn", dir, sizeof dir);
    snprintf(model, sizeof model, "%s/variants.gltf", dir);
    snprintf(out, sizeof out, "%s/out.png", dir);
    const gltf_quad q = { -1, -1, 1, 1, 0 };
    char *json = gltf_quads(&q, 1, ",\"materials\":[{}],"
                                   "\"extensionsUsed\":[\"KHR_texture_basisu\"]");
    REQUIRE(json && write_whole(model, json, strlen(json)));
    free(json);
    cli_run r;
    REQUIRE(run_cli(ARGS("render", model, "--size", "32x24", "-o", out), &r));
    CHECK_EQ(r.status, 0);
    CHECK(is_one_line(r.err, r.err_len));
    CHECK_STR_CONTAINS(r.err, "variants.gltf: warning: not read, the scene is drawn without them: "
                              "/extensionsUsed/0 (KHR_texture_basisu)");
    const char *first = strstr(r.err, "warning: ");
    CHECK(first && !strstr(first + 1, "warning: "));
    cli_run_free(&r);
#endif
}

#ifdef SR_CLI_PATH
/* A unit cube as a .gltf at path: with `normals`, 24 corners with the
 * faces' normals; without, its 8 corners shared and no normals. Placed
 * twice, the second time mirrored (scale -1 on x). */
static bool write_gltf_cube(const char *path, bool normals)
{
    float pos[24 * 3], nrm[24 * 3];
    uint16_t idx[36];
    size_t nv = 0;
    static const int axis_sign[6][2] = { { 0, 1 }, { 0, -1 }, { 1, 1 }, { 1, -1 }, { 2, 1 },
                                         { 2, -1 } };
    for (int f = 0; f < 6; f++) {
        int a = axis_sign[f][0], sg = axis_sign[f][1], u = (a + 1) % 3, v = (a + 2) % 3;
        static const float corner[4][2] = { { -1, -1 }, { 1, -1 }, { 1, 1 }, { -1, 1 } };
        uint16_t at[4];
        for (int c = 0; c < 4; c++) {
            float p[3];
            p[a] = (float)sg;
            p[u] = corner[c][0];
            p[v] = corner[c][1] * (float)sg;   /* counter-clockwise seen from outside */
            size_t k = nv;
            if (!normals) {   /* share the corner with the faces before */
                for (k = 0; k < nv && memcmp(&pos[3 * k], p, sizeof p) != 0; k++) {
                }
            }
            if (k == nv) {
                memcpy(&pos[3 * nv], p, sizeof p);
                float n[3] = { 0, 0, 0 };
                n[a] = (float)sg;
                memcpy(&nrm[3 * nv], n, sizeof n);
                nv++;
            }
            at[c] = (uint16_t)k;
        }
        const int order[6] = { 0, 1, 2, 0, 2, 3 };
        for (int k = 0; k < 6; k++) {
            idx[6 * f + k] = at[order[k]];
        }
    }
    size_t pos_len = 12 * nv, len = 2 * pos_len + sizeof idx;
    uint8_t bin[24 * 3 * 4 * 2 + sizeof idx];
    le_copy(bin, pos, 3 * nv, 4);
    le_copy(bin + pos_len, nrm, 3 * nv, 4);
    le_copy(bin + 2 * pos_len, idx, 36, 2);
    char b64[4 * (sizeof bin / 3 + 1) + 1], json[8192];
    gltf_base64(bin, len, b64);
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu,"
             "\"uri\":\"data:application/octet-stream;base64,%s\"}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteLength\":%zu},"
             "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},"
             "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":72}],"
             "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":%zu,"
             "\"type\":\"VEC3\",\"min\":[-1,-1,-1],\"max\":[1,1,1]},"
             "{\"bufferView\":1,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\"},"
             "{\"bufferView\":2,\"componentType\":5123,\"count\":36,\"type\":\"SCALAR\"}],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0%s},"
             "\"indices\":2}]}],"
             "\"nodes\":[{\"mesh\":0,\"translation\":[-1.5,0,0]},"
             "{\"mesh\":0,\"translation\":[1.5,0,0],\"scale\":[-1,1,1]}],"
             "\"scenes\":[{\"nodes\":[0,1]}]}",
             len, b64, pos_len, pos_len, pos_len, 2 * pos_len, nv, nv,
             normals ? ",\"NORMAL\":1" : "");
    return write_whole(path, json, strlen(json));
}
#endif

/* glTF asks for flat normals where a primitive has none: a cube of 8
 * shared corners is drawn as the same cube with its faces' normals, not
 * rounded by smooth normals; mirrored, its faces still face out. */
SR_TEST(a_gltf_primitive_without_normals_is_flat_shaded)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson (glTF)");
    }
    char dir[1024], with[1100], without[1100];
    fresh_dir("gltfflat", dir, sizeof dir);
    snprintf(with, sizeof with, "%s/with.gltf", dir);
    snprintf(without, sizeof without, "%s/without.gltf", dir);
    REQUIRE(write_gltf_cube(with, true) && write_gltf_cube(without, false));
    uint8_t *px[2] = { NULL, NULL };
    int w = 0, h = 0;
    const char *models[2] = { with, without };
    for (int i = 0; i < 2; i++) {
        char out[1200];
        snprintf(out, sizeof out, "%s/%d.png", dir, i);
        cli_run r;
        REQUIRE(run_cli(ARGS("render", models[i], "--size", "96x64", "-o", out), &r));
        CHECK_EQ(r.status, 0);
        cli_run_free(&r);
        sr_io_error err;
        REQUIRE(sr_read_png(out, NULL, &w, &h, &px[i], &err) == SR_OK);
    }
    /* Flat normals from the corners' cross product against the file's:
     * a rounding apart at most. */
    long differ = 0;
    for (long i = 0; i < 4L * w * h; i++) {
        differ += abs(px[0][i] - px[1][i]) > 2;
    }
    CHECK_EQ(differ, 0);
    free(px[0]);
    free(px[1]);
#endif
}

/* ---- option errors ------------------------------------------------------ */

typedef struct option_case {
    const char *label;
    const char *args[20];
    const char *needle;
} option_case;

static const option_case option_errors[] = {
    { "unknown option", { "--bogus" }, "unknown option '--bogus'" },
    { "unknown short option", { "-x" }, "unknown option '-x'" },
    { "size 0x10", { "--size", "0x10" }, "--size: expected WxH" },
    { "size 9000x10", { "--size", "9000x10" }, "--size: expected WxH with each from 1 to 8192" },
    { "size 10x9000", { "--size", "10x9000" }, "--size: expected WxH" },
    { "size abc", { "--size", "abc" }, "--size: expected WxH" },
    { "size 64x48junk", { "--size", "64x48junk" }, "--size: expected WxH" },
    { "size=abc", { "--size=abc" }, "--size: expected WxH" },
    { "size without value", { "--size" }, "--size: missing value" },
    { "shading bogus", { "--shading", "bogus" }, "--shading: expected one of pbr|flat|gouraud|" },
    { "tonemap bogus", { "--tonemap", "filmic" }, "--tonemap: expected one of neutral|aces|none" },
    { "exposure 30", { "--exposure", "30" }, "--exposure: expected a number" },
    { "exposure nan", { "--exposure", "nan" }, "--exposure: expected a number" },
    { "environment intensity 0", { "--environment-intensity", "0" },
      "--environment-intensity: expected a number" },
    { "fov 0", { "--fov", "0" }, "--fov: expected a number" },
    { "polygon offset one number", { "--polygon-offset", "1" },
      "--polygon-offset: expected FACTOR,UNITS" },
    { "fov 180", { "--fov", "180" }, "--fov: expected a number" },
    { "fov nan", { "--fov", "nan" }, "--fov: expected a number" },
    { "camera without eye", { "--camera", "target=0,0,0" }, "--camera: eye=X,Y,Z is required" },
    { "camera unknown key", { "--camera", "eye=1,2,3,focus=1" }, "--camera: unknown key 'focus'" },
    { "camera short eye", { "--camera", "eye=1,2" }, "--camera: expected three numbers" },
    { "camera not key=value", { "--camera", "1,2,3" }, "--camera: expected key=value" },
    { "light without dir or point", { "--light", "color=red" }, "--light: needs dir=X,Y,Z or point" },
    { "light zero direction", { "--light", "dir=0,0,0" }, "--light: a light direction must not be zero" },
    { "light dir and point", { "--light", "dir=0,1,0,point=1,1,1" }, "--light: give either dir=" },
    { "light bad intensity", { "--light", "dir=0,1,0,intensity=-1" }, "--light: expected a number" },
    { "nine lights",
      { "--light", "dir=0,1,0", "--light", "dir=0,1,0", "--light", "dir=0,1,0", "--light",
        "dir=0,1,0", "--light", "dir=0,1,0", "--light", "dir=0,1,0", "--light", "dir=0,1,0",
        "--light", "dir=0,1,0", "--light", "dir=0,1,0" },
      "--light: at most 8 lights" },
    { "background nocolor", { "--background", "nocolor" }, "--background: expected a color name" },
    { "background #12", { "--background", "#12" }, "--background: expected a color name" },
    { "background environment under the hemisphere",
      { "--environment", "hemisphere", "--background", "environment" },
      "--background environment: shows the environment of --environment studio or FILE.hdr" },
    { "background blur under phong",
      { "--environment", "studio", "--background", "blur", "--shading", "phong" },
      "--background blur: shows the environment" },
    { "shadows maybe", { "--shadows", "maybe" }, "--shadows: expected one of on|off" },
    { "lights sun", { "--lights", "sun" }, "--lights: expected one of file|default|both|auto" },
    { "ground with a value", { "--ground=yes" }, "--ground: takes no value" },
    { "ambient -1,0,0", { "--ambient", "-1,0,0" }, "--ambient: expected a color name" },
    { "material unknown key", { "--material", "gloss=1" }, "--material: unknown key 'gloss'" },
    { "material shininess 0", { "--material", "shininess=0" }, "--material: expected a number" },
    { "material bad color", { "--material", "color=nocolor" }, "--material: expected a color" },
    { "depth-format d8", { "--depth-format", "d8" }, "--depth-format: expected one of d16|d24|d32|d32f" },
    { "depth-func bogus", { "--depth-func", "sometimes" }, "--depth-func: expected one of never|" },
    { "cull bogus", { "--cull", "sideways" }, "--cull: expected one of back|front|none" },
    { "front-face bogus", { "--front-face", "up" }, "--front-face: expected one of ccw|cw" },
    { "projection-interp bogus", { "--projection-interp", "linear" }, "--projection-interp: expected one of" },
    { "rasterizer bogus", { "--rasterizer", "raytrace" }, "--rasterizer: expected one of halfspace|" },
    { "clipper bogus", { "--clipper", "guard-band" }, "--clipper: expected one of homogeneous|view-volume" },
    { "view-volume clipper under pbr", { "--clipper", "view-volume" },
      "--clipper view-volume clips the built-in shading models' view space" },
    { "depth-range one number", { "--depth-range", "0.5" }, "--depth-range: expected NEAR,FAR" },
    { "depth-range junk after", { "--depth-range", "0,1x" }, "--depth-range: expected NEAR,FAR" },
    { "depth-range nan", { "--depth-range", "nan,1" }, "--depth-range: expected NEAR,FAR" },
    { "normals bogus", { "--normals", "bent" }, "--normals: expected one of file|smooth|flat" },
    { "ortho with a value", { "--ortho=yes" }, "--ortho: takes no value" },
    { "turn huge", { "--turn", "1e9" }, "--turn: expected a number" },
    { "up sideways", { "--up", "sideways" }, "--up: expected one of +x|-x|+y|-y|+z|-z" },
    { "up without a sign", { "--up", "z" }, "--up: expected one of +x|-x|+y|-y|+z|-z" },
    { "near 0", { "--near", "0" }, "--near: expected a number" },
    { "far abc", { "--far", "abc" }, "--far: expected a number" },
    { "threads 0", { "--threads", "0" }, "--threads: expected a whole number from 1 to 64" },
    { "png-level 10", { "--png-level", "10" }, "--png-level: expected a whole number from 0 to 9" },
    { "jpeg-quality 0", { "--jpeg-quality", "0" }, "--jpeg-quality: expected a whole number from 1 to 100" },
    { "jpeg-quality for a PNG", { "--jpeg-quality", "80" }, "--jpeg-quality: the output '" },
    { "png-level for a JPEG", { "-o", "never-written.jpg", "--png-level", "3" },
      "--png-level: the output 'never-written.jpg' is a JPEG" },
    { "detail 0", { "--detail", "0" }, "--detail: expected a whole number from 1 to 64" },
    { "detail 1.5", { "--detail", "1.5" }, "--detail: expected a whole number" },
    { "two models", { "first.obj", "second.obj" }, "more than one model given ('first.obj' and 'second.obj')" },
    /* sscanf's %d wrapped 4294967297 to 1 and took signs and spaces. */
    { "size overflowing int", { "--size", "4294967297x10" }, "--size: expected WxH" },
    { "size with signs", { "--size", "+10x+10" }, "--size: expected WxH" },
    { "size with a space", { "--size", "10x 10" }, "--size: expected WxH" },
    { "color with junk after", { "--background", "1,1,1junk" }, "--background: expected a color" },
    { "color of four numbers", { "--background", "1,1,1,1" }, "--background: expected a color" },
    { "color beyond float", { "--background", "1e39,0,0" }, "--background: expected a color" },
    { "verbose with a value", { "--verbose=yes" }, "--verbose: takes no value" },
    { "help with a value", { "--help=foo" }, "--help: takes no value" },
    { "empty texture", { "--texture", "" }, "--texture: empty value" },
    { "empty model name", { "" }, "the model's file name is empty" },
    { "near beyond far", { "--near", "10", "--far", "1" }, "--near 10 must be less than --far 1" },
    /* Both sr_camera_frame attempts failed here and the basis was read
     * uninitialised. */
    { "camera eye on target", { "--camera", "eye=1,2,3,target=1,2,3" },
      "--camera: eye and target are the same point" },
    { "camera beyond float", { "--camera", "eye=1e30,0,0" },
      "--camera: the eye, the target or the model lies beyond the range" },
};

SR_TEST(bad_options_fail_with_one_line_naming_the_option)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    for (size_t i = 0; i < sizeof option_errors / sizeof option_errors[0]; i++) {
        expect_render_failure(option_errors[i].label, option_errors[i].args, 2,
                              option_errors[i].needle);
    }
}

/* A bound written as a float literal (0.001f) lies just off its decimal:
 * the documented limits themselves, typed as the help gives them, are
 * accepted, and the first value past them is not. */
SR_TEST(bounded_number_options_accept_their_documented_limits)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    char dir[1024], model[1100], out[1100], svg[1100];
    fresh_dir("limits", dir, sizeof dir);
    snprintf(model, sizeof model, "%s/tri.obj", dir);
    snprintf(out, sizeof out, "%s/tri.png", dir);
    const char *tri = ONE_TRIANGLE_OBJ;
    REQUIRE(write_whole(model, tri, strlen(tri)));
    const struct {
        const char *opt, *value;
        int status;
    } cases[] = {
        { "--environment-intensity", "0.001", 0 }, { "--environment-intensity", "1000", 0 },
        { "--environment-intensity", "0.00099", 2 }, { "--near", "1e-6", 0 },
        { "--fov", "170", 0 }, { "--exposure", "-20", 0 },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        cli_run r;
        REQUIRE(run_cli(ARGS("render", model, "--size", "16x12", cases[i].opt, cases[i].value,
                             "-o", out), &r));
        if (r.status != cases[i].status) {
            FAILF("%s %s: exit status %d, expected %d (stderr \"%s\")", cases[i].opt,
                  cases[i].value, r.status, cases[i].status, r.err);
        }
        cli_run_free(&r);
    }
    if (svg_command_built()) {
        const char *doc = "<svg xmlns='http://www.w3.org/2000/svg' width='4000' height='4000'>"
                          "<rect width='4000' height='4000'/></svg>";
        snprintf(svg, sizeof svg, "%s/square.svg", dir);
        REQUIRE(write_whole(svg, doc, strlen(doc)));
        cli_run r;
        REQUIRE(run_cli(ARGS("svg", svg, "--scale", "0.001", "-o", out), &r));
        if (r.status != 0) {
            FAILF("svg --scale 0.001: exit status %d (stderr \"%s\")", r.status, r.err);
        }
        cli_run_free(&r);
    }
#endif
}

/* Up along the gaze, then the fallback (0,0,-1) along it too: a third up
 * is tried, and the triangle is drawn (the basis was uninitialised). */
SR_TEST(camera_looking_along_both_ups_still_frames)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    char dir[1024], model[1100], out[1100];
    fresh_dir("camera", dir, sizeof dir);
    snprintf(model, sizeof model, "%s/tri.obj", dir);
    snprintf(out, sizeof out, "%s/tri.png", dir);
    const char *tri = ONE_TRIANGLE_OBJ;
    REQUIRE(write_whole(model, tri, strlen(tri)));
    const char *args[] = { "render", model, "--camera", "eye=0,0,5,target=0,0,0,up=0,0,1",
                           "--size", "64x48", "--background", "black", "--shading", "unlit",
                           "--material", "color=white", "-o", out, NULL };
    CHECK_EQ(sr_test_run_cli(args), 0);
    int w, h;
    uint8_t *px = NULL;
    sr_io_error err;
    REQUIRE(sr_read_png(out, NULL, &w, &h, &px, &err) == SR_OK);
    long lit = 0;
    for (long i = 0; i < (long)w * h; i++) {
        lit += px[4 * i] > 128;
    }
    CHECK(lit > 100);
    free(px);
#endif
}

/* Coordinates the readers accept but whose squares leave float's range:
 * one line naming the file, not an internal message or a blank image. */
SR_TEST(models_beyond_the_framing_range_are_refused_by_name)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    const char *cases[][2] = {
        { "huge.obj", "v 0 0 0\nv 1e19 0 0\nv 0 1e19 0\nf 1 2 3\n" },
        { "tiny.obj", "v 0 0 0\nv 1e-25 0 0\nv 0 1e-25 0\nf 1 2 3\n" },
    };
    char dir[1024];
    fresh_dir("range", dir, sizeof dir);
    for (int i = 0; i < 2; i++) {
        char model[1100], needle[1200];
        snprintf(model, sizeof model, "%s/%s", dir, cases[i][0]);
        REQUIRE(write_whole(model, cases[i][1], strlen(cases[i][1])));
        snprintf(needle, sizeof needle, "%s: the model lies beyond the range", model);
        const char *args[] = { model, NULL };
        expect_render_failure(cases[i][0], args, 2, needle);
    }
#endif
}

/* The files a refusal must leave as they were, with their bytes. */
typedef struct kept_file {
    const char *path;
    char *bytes;
    size_t len;
} kept_file;

static void keep_files(kept_file *k, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        k[i].bytes = read_whole(k[i].path, &k[i].len);
        REQUIRE(k[i].bytes != NULL);
    }
}

/* Each case must exit 2 with one line holding its needle, and every kept
 * file keep its bytes. */
typedef struct refusal_case {
    const char *label, *args[10], *needle;
} refusal_case;

static void expect_refusals(const refusal_case *cases, size_t n, kept_file *kept, size_t nkept)
{
    for (size_t i = 0; i < n; i++) {
        cli_run r;
        REQUIRE(run_cli(cases[i].args, &r));
        check_failure_output(cases[i].label, &r, 2, cases[i].needle);
        cli_run_free(&r);
        for (size_t k = 0; k < nkept; k++) {
            size_t len;
            char *now = read_whole(kept[k].path, &len);
            if (!now || len != kept[k].len || memcmp(now, kept[k].bytes, len) != 0) {
                FAILF("%s: %s changed", cases[i].label, kept[k].path);
            }
            free(now);
        }
    }
    for (size_t k = 0; k < nkept; k++) {
        free(kept[k].bytes);
    }
}

/* The atomic write would replace an input with the image: refused, by
 * any name for the same file (another path, a symbolic or a hard link),
 * and the inputs keep their bytes. */
SR_TEST(output_that_is_an_input_is_refused)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    char dir[1024], model[1100], mtl[1100], tex[1100], alias[1200], sym[1100], hard[1100];
    fresh_dir("same", dir, sizeof dir);
    snprintf(model, sizeof model, "%s/quad.obj", dir);
    snprintf(mtl, sizeof mtl, "%s/quad.mtl", dir);
    snprintf(tex, sizeof tex, "%s/quad_texture.png", dir);
    snprintf(sym, sizeof sym, "%s/symlink.png", dir);
    snprintf(hard, sizeof hard, "%s/hardlink.png", dir);
    /* The same file by another path: DIR/../NAME/quad_texture.png. */
    snprintf(alias, sizeof alias, "%s/../%s/quad_texture.png", dir, strrchr(dir, '/') + 1);
    const char *quad = "mtllib quad.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                       "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3 4/4\n";
    const char *mat = "newmtl m\nKd 1 1 1\n";
    REQUIRE(write_whole(model, quad, strlen(quad)));
    REQUIRE(write_whole(mtl, mat, strlen(mat)));
    const uint8_t texel[16] = { 255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 9, 9, 9, 255 };
    sr_io_error err;
    REQUIRE(sr_write_png(tex, 2, 2, texel, 8, NULL, &err) == SR_OK);
    REQUIRE(symlink("quad.obj", sym) == 0);
    REQUIRE(link(model, hard) == 0);
    kept_file kept[] = { { .path = model }, { .path = mtl }, { .path = tex } };
    keep_files(kept, 3);

    const refusal_case cases[] = {
        /* named for what they are: refused by their extension first */
        { "model as output", { "render", model, "-o", model }, "not .obj" },
        { "model through a symbolic link", { "render", model, "-o", sym },
          "is the model being read" },
        { "model through a hard link", { "render", model, "-o", hard },
          "is the model being read" },
        { "MTL as output", { "render", model, "-o", mtl }, "not .mtl" },
        { "found texture as output", { "render", model, "-o", tex }, "is the texture being read" },
        { "named texture through another path",
          { "render", model, "--texture", tex, "-o", alias }, "is the texture being read" },
        /* thumbnail's render names the argument given, not an -o */
        { "found texture as thumbnail", { "thumbnail", "-s", "16", model, tex },
          "thumbnail: OUTPUT: '" },
        { "directory as thumbnail", { "thumbnail", "-s", "16", model, dir },
          "thumbnail: OUTPUT: '" },
    };
    expect_refusals(cases, sizeof cases / sizeof cases[0], kept, 3);
#endif
}

/* `softrast svg` refuses to write its PNG over the SVG it reads, by any
 * name, and leaves the drawing as it was. */
SR_TEST(svg_output_that_is_its_input_is_refused)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    if (!svg_command_built()) {
        SKIP("this softrast was built without expat");
    }
    cli_run r;
    char dir[1024], svg[1100], sym[1100], hard[1100], plain[1100], hard_png[1100];
    fresh_dir("same_svg", dir, sizeof dir);
    snprintf(svg, sizeof svg, "%s/drawing.svg", dir);
    snprintf(sym, sizeof sym, "%s/symlink.png", dir);
    snprintf(hard, sizeof hard, "%s/hardlink.svg", dir);
    snprintf(hard_png, sizeof hard_png, "%s/hardlink.png", dir);
    /* A name with no .svg: the default output is NAME.png, not NAME. */
    snprintf(plain, sizeof plain, "%s/drawing", dir);
    const char *text = "<svg xmlns='http://www.w3.org/2000/svg' width='8' height='8'>"
                       "<rect width='4' height='4' fill='red'/></svg>";
    REQUIRE(write_whole(svg, text, strlen(text)));
    REQUIRE(symlink("drawing.svg", sym) == 0);
    REQUIRE(link(svg, hard) == 0);
    REQUIRE(link(svg, hard_png) == 0);
    kept_file kept[] = { { .path = svg } };
    keep_files(kept, 1);
    const refusal_case cases[] = {
        { "svg onto itself", { "svg", svg, "-o", svg }, "not .svg" },
        { "svg through a symbolic link", { "svg", svg, "--output", sym },
          "is the SVG file being read" },
        { "svg through a hard link", { "svg", hard, "-o", svg }, "not .svg" },
        { "svg through a hard link named .png", { "svg", svg, "-o", hard_png },
          "is the SVG file being read" },
    };
    expect_refusals(cases, sizeof cases / sizeof cases[0], kept, 1);

    /* A new output is of course fine. */
    REQUIRE(write_whole(plain, text, strlen(text)));
    REQUIRE(run_cli(ARGS("svg", plain), &r));
    CHECK_EQ(r.status, 0);
    cli_run_free(&r);
    size_t len;
    char *after = read_whole(plain, &len);
    CHECK(after && len == strlen(text) && memcmp(after, text, len) == 0);
    free(after);
    char png[1200];
    snprintf(png, sizeof png, "%s.png", plain);
    int w = 0, h = 0;
    uint8_t *px = NULL;
    sr_io_error err;
    CHECK_EQ(sr_read_png(png, NULL, &w, &h, &px, &err), SR_OK);
    CHECK(w == 8 && h == 8);
    free(px);
#endif
}

SR_TEST(unknown_command_fails_with_one_line)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    cli_run r;
    REQUIRE(run_cli(ARGS("paint"), &r));
    check_failure_output("unknown command", &r, 2, "unknown command 'paint'");
    cli_run_free(&r);

    /* No command at all: the usage goes to stderr with status 2. */
    REQUIRE(run_cli((const char *const[]){ NULL }, &r));
    CHECK_EQ(r.status, 2);
    CHECK_STR_CONTAINS(r.err, "usage: softrast");
    CHECK_EQ(r.out_len, 0);
    cli_run_free(&r);
}

SR_TEST(output_that_is_a_directory_is_refused)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024], sub[1100];
    fresh_dir("fail", dir, sizeof dir);
    snprintf(sub, sizeof sub, "%s/images", dir);
    REQUIRE(mkdir(sub, 0777) == 0);
    const char *forms[][3] = { { "-o", sub, NULL }, { "--output", sub, NULL } };
    for (size_t i = 0; i < 2; i++) {
        cli_run r;
        REQUIRE(run_cli(ARGS("render", "--size", "16x12", "--detail", "1", forms[i][0],
                             forms[i][1]), &r));
        check_failure_output("-o DIR", &r, 2, "-o: ");
        CHECK_STR_CONTAINS(r.err, "is a directory");
        cli_run_free(&r);
        CHECK_EQ(count_entries(sub, NULL, 0), 0);
        CHECK_EQ(count_entries(dir, NULL, 0), 1);
    }
}

SR_TEST(output_into_a_missing_directory_fails_cleanly)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024], out[1100];
    fresh_dir("fail", dir, sizeof dir);
    snprintf(out, sizeof out, "%s/missing/out.png", dir);
    cli_run r;
    REQUIRE(run_cli(ARGS("render", "--size", "16x12", "--detail", "1", "-o", out), &r));
    /* Writing is what fails: status 1, and the line names the file. */
    check_failure_output("-o missing/out.png", &r, 1, "missing/out.png: cannot create a file in");
    cli_run_free(&r);
    CHECK_EQ(count_entries(dir, NULL, 0), 0);
    CHECK(!is_dir(out));
}

SR_TEST(output_through_a_regular_file_fails_cleanly)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    /* Works as root too, unlike a read-only directory: a path whose
     * directory part is a regular file cannot be created (ENOTDIR). */
    char dir[1024], file[1100], out[1200];
    fresh_dir("fail", dir, sizeof dir);
    snprintf(file, sizeof file, "%s/file.png", dir);
    size_t n;
    const unsigned char *bytes = sentinel(&n);
    REQUIRE(write_whole(file, bytes, n));
    snprintf(out, sizeof out, "%s/out.png", file);
    cli_run r;
    REQUIRE(run_cli(ARGS("render", "--size", "16x12", "--detail", "1", "-o", out), &r));
    check_failure_output("-o FILE/out.png", &r, 1, "file.png/out.png: ");
    CHECK_STR_CONTAINS(r.err, "Not a directory");
    cli_run_free(&r);
    size_t got_n = 0;
    char *got = read_whole(file, &got_n);
    CHECK(got && got_n == n && memcmp(got, bytes, n) == 0);
    free(got);
    CHECK_EQ(count_entries(dir, NULL, 0), 1);
}

SR_TEST(a_write_that_fails_midway_leaves_the_old_image_and_no_temporary)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    /* A file size limit (RLIMIT_FSIZE, inherited by the child) makes the
     * image write fail after its first kilobyte with EFBIG, as a full disk
     * would; SIGXFSZ is ignored so write() returns the error instead of
     * killing the process.  The existing image must survive untouched,
     * PNG or JPEG. */
    const char *names[] = { "out.png", "out.jpg" };
    for (size_t k = 0; k < 2; k++) {
        if (k == 1 && !sr_io_have_jpeg()) {
            break;
        }
        char dir[1024], out[1100], label[200];
        fresh_dir("fail", dir, sizeof dir);
        snprintf(out, sizeof out, "%s/%s", dir, names[k]);
        snprintf(label, sizeof label, "-o %s under a 1 KiB file size limit", names[k]);
        size_t n;
        const unsigned char *bytes = sentinel(&n);
        REQUIRE(write_whole(out, bytes, n));
        struct rlimit old;
        REQUIRE(getrlimit(RLIMIT_FSIZE, &old) == 0);
        struct rlimit lim = old;
        lim.rlim_cur = 1024;
        void (*old_handler)(int) = signal(SIGXFSZ, SIG_IGN);
        REQUIRE(setrlimit(RLIMIT_FSIZE, &lim) == 0);
        cli_run r;
        bool ran = run_cli(ARGS("render", "--size", "300x200", "-o", out), &r);
        setrlimit(RLIMIT_FSIZE, &old);
        signal(SIGXFSZ, old_handler);
        REQUIRE(ran);
        check_failure_output(label, &r, 1, names[k]);
        CHECK_STR_CONTAINS(r.err, "File too large");
        cli_run_free(&r);
        size_t got_n = 0;
        char *got = read_whole(out, &got_n);
        CHECK(got && got_n == n && memcmp(got, bytes, n) == 0);
        free(got);
        CHECK_EQ(count_entries(dir, NULL, 0), 1);
    }
}

/* ---- successful runs ---------------------------------------------------- */

SR_TEST(version_prints_the_version)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    const char *forms[] = { "--version", "version" };
    for (size_t i = 0; i < 2; i++) {
        cli_run r;
        REQUIRE(run_cli(ARGS(forms[i]), &r));
        CHECK_EQ(r.status, 0);
        /* The second line names what this build reads: the library's
         * list, which test_io holds to the readers' own answers. */
        char want[512];
        snprintf(want, sizeof want, "softrast %s\nbuilt with: %s\n", SR_VERSION_STRING,
                 sr_io_features());
        CHECK(strcmp(r.out, want) == 0);
        CHECK_EQ(r.err_len, 0);
        cli_run_free(&r);
    }
    cli_run r;
    REQUIRE(run_cli(ARGS("--help"), &r));
    CHECK_EQ(r.status, 0);
    CHECK_STR_CONTAINS(r.out, "render [MODEL] [options]");
    CHECK_EQ(r.err_len, 0);
    cli_run_free(&r);
}

/* Every option parse_args accepts.  A new option must be added here, to
 * the help text, and (if it can go wrong) to option_errors. */
static const char *const value_options[] = {
    "-o", "--output", "--size", "--background", "--png-level", "--jpeg-quality", "--shading",
    "--normals",
    "--material", "--ambient", "--light", "--camera", "--fov", "--turn", "--near", "--far",
    "--cull", "--front-face", "--depth-format", "--depth-func", "--projection-interp",
    "--rasterizer", "--clipper", "--depth-range", "--threads", "--detail", "--line-width", "--point-size", "--line-color",
    "--texture", "--texture-filter", "--wrap", "--aa", "--filter", "--opacity",
    "--polygon-offset", "--up", "--tonemap", "--exposure", "--environment",
    "--environment-intensity", "--camera-index", "--variant", "--shadows", "--lights", "--batch", "--output-dir", "--name", "--log", "--shard",
    "--shard-count", "--views", "--sheet", "--sheet-columns", "--animate",
    "--animation", "--time", "--fps",
};
static const char *const flag_options[] = { "--ortho", "-v", "--verbose", "-h", "--help",
                                             "--wireframe", "--hidden-line", "--edges", "--points",
                                             "--smooth", "--texture-srgb", "--skip-existing",
                                             "--ground" };

SR_TEST(render_help_lists_every_option)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    const size_t nv = sizeof value_options / sizeof value_options[0];
    const size_t nf = sizeof flag_options / sizeof flag_options[0];
    const char *forms[] = { "--help", "-h" };
    for (size_t f = 0; f < 2; f++) {
        cli_run r;
        REQUIRE(run_cli(ARGS("render", forms[f]), &r));
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.err_len, 0);
        CHECK_STR_CONTAINS(r.out, "usage: softrast render");
        /* Options in the help: "-x" or "--word" at the start of a word. */
        const char *s = r.out;
        bool seen_v[64] = { false }, seen_f[64] = { false };
        for (size_t i = 0; s[i]; i++) {
            bool word_start = i == 0 || s[i - 1] == ' ' || s[i - 1] == '\n' || s[i - 1] == '(';
            if (!word_start || s[i] != '-') {
                continue;
            }
            size_t j = i + 1;
            if (s[j] == '-') {
                j++;
            }
            if (!(s[j] >= 'a' && s[j] <= 'z')) {
                continue;
            }
            while ((s[j] >= 'a' && s[j] <= 'z') || (s[j] >= '0' && s[j] <= '9') || s[j] == '-') {
                j++;
            }
            size_t n = j - i;
            bool known = false;
            for (size_t k = 0; k < nv; k++) {
                if (strlen(value_options[k]) == n && memcmp(value_options[k], s + i, n) == 0) {
                    seen_v[k] = known = true;
                }
            }
            for (size_t k = 0; k < nf; k++) {
                if (strlen(flag_options[k]) == n && memcmp(flag_options[k], s + i, n) == 0) {
                    seen_f[k] = known = true;
                }
            }
            if (!known) {
                FAILF("render --help mentions '%.*s', which this test does not know", (int)n, s + i);
            }
            i = j - 1;
        }
        for (size_t k = 0; k < nv; k++) {
            if (!seen_v[k]) {
                FAILF("render --help does not mention %s", value_options[k]);
            }
        }
        for (size_t k = 0; k < nf; k++) {
            if (!seen_f[k]) {
                FAILF("render --help does not mention %s", flag_options[k]);
            }
        }
        cli_run_free(&r);
    }
}

/* Each option in the list is one parse_args knows: without its value it
 * reports "OPTION: missing value", never "unknown option". */
SR_TEST(every_listed_option_is_accepted_by_the_parser)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    for (size_t k = 0; k < sizeof value_options / sizeof value_options[0]; k++) {
        char needle[64];
        snprintf(needle, sizeof needle, "%s: missing value", value_options[k]);
        expect_render_failure(value_options[k], ARGS(value_options[k]), 2, needle);
    }
}

/* Background #1d2230, as in the help. */
static bool is_background(const uint8_t *p)
{
    return p[0] == 0x1d && p[1] == 0x22 && p[2] == 0x30 && p[3] == 255;
}

/* Render into DIR/NAME with args, expect success, silence on both
 * streams, and a W x H PNG; returns the share of non-background pixels
 * (-1 on failure). */
static double render_ok(const char *label, const char *dir, const char *name,
                        const char *const *args, int w, int h)
{
    char out[1400];
    snprintf(out, sizeof out, "%s/%s", dir, name);
    const char *head[] = { "render", NULL };
    const char *tail[] = { "-o", out, NULL };
    const char *mid[MAX_ARGS + 1], *all[MAX_ARGS + 1];
    join_args(mid, head, args);
    join_args(all, mid, tail);
    cli_run r;
    if (!run_cli(all, &r)) {
        FAILF("%s: the CLI did not run", label);
        return -1;
    }
    bool ok = r.status == 0 && r.err_len == 0 && r.out_len == 0;
    if (!ok) {
        FAILF("%s: exit status %d, stdout \"%s\", stderr \"%s\"", label, r.status, r.out, r.err);
    }
    cli_run_free(&r);
    if (!ok) {
        return -1;
    }
    int pw = 0, ph = 0;
    uint8_t *px = NULL;
    sr_io_error err;
    if (sr_read_png(out, NULL, &pw, &ph, &px, &err) != SR_OK) {
        FAILF("%s: %s", label, err.message);
        return -1;
    }
    if (pw != w || ph != h) {
        FAILF("%s: image is %dx%d, expected %dx%d", label, pw, ph, w, h);
    }
    size_t lit = 0;
    for (size_t i = 0; i < (size_t)pw * ph; i++) {
        lit += !is_background(px + 4 * i);
    }
    free(px);
    return pw == w && ph == h ? (double)lit / ((double)pw * ph) : -1;
}

typedef struct silhouette {
    int x0, y0, x1, y1;     /* the non-background pixels' box, inclusive; x1 < x0 when none */
} silhouette;

/* The box of the non-background pixels of the W x H image PATH. */
static bool read_silhouette(const char *label, const char *path, silhouette *box)
{
    int w = 0, h = 0;
    uint8_t *px = NULL;
    sr_io_error err;
    if (sr_read_png(path, NULL, &w, &h, &px, &err) != SR_OK) {
        FAILF("%s: %s", label, err.message);
        return false;
    }
    *box = (silhouette){ w, h, -1, -1 };
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            if (!is_background(px + 4 * ((size_t)y * w + x))) {
                box->x0 = x < box->x0 ? x : box->x0;
                box->y0 = y < box->y0 ? y : box->y0;
                box->x1 = x > box->x1 ? x : box->x1;
                box->y1 = y > box->y1 ? y : box->y1;
            }
        }
    }
    free(px);
    return box->x1 >= box->x0;
}

/* render_ok, then the silhouette of what it drew. */
static bool render_silhouette(const char *label, const char *dir, const char *const *args, int w,
                              int h, silhouette *box)
{
    if (render_ok(label, dir, "silhouette.png", args, w, h) <= 0.0) {
        FAILF("%s: nothing drawn", label);
        return false;
    }
    char path[1200];
    snprintf(path, sizeof path, "%s/silhouette.png", dir);
    return read_silhouette(label, path, box);
}

/* A closed box from the origin to (sx, sy, sz) as an ASCII STL, faces
 * counter-clockwise seen from outside. */
static bool write_box_stl(const char *path, float sx, float sy, float sz)
{
    static const int quads[6][4] = { { 0, 1, 3, 2 }, { 4, 6, 7, 5 }, { 0, 4, 5, 1 },
                                      { 2, 3, 7, 6 }, { 0, 2, 6, 4 }, { 1, 5, 7, 3 } };
    FILE *f = fopen(path, "w");
    if (!f) {
        return false;
    }
    fprintf(f, "solid box\n");
    for (int q = 0; q < 6; q++) {
        const int tri[2][3] = { { quads[q][0], quads[q][1], quads[q][2] },
                                { quads[q][0], quads[q][2], quads[q][3] } };
        for (int t = 0; t < 2; t++) {
            fprintf(f, "facet normal 0 0 0\nouter loop\n");
            for (int k = 0; k < 3; k++) {
                int v = tri[t][k];   /* bit 2: x, bit 1: y, bit 0: z */
                fprintf(f, "vertex %g %g %g\n", (double)(v & 4 ? sx : 0), (double)(v & 2 ? sy : 0),
                        (double)(v & 1 ? sz : 0));
            }
            fprintf(f, "endloop\nendfacet\n");
        }
    }
    fprintf(f, "endsolid box\n");
    return fclose(f) == 0;
}

/* An STL stands on its +z axis unless --up says otherwise: a box four
 * times taller along z than wide stands upright (its silhouette taller
 * than wide) with +z and -z, and lies down with the four other axes. */
SR_TEST(up_turns_the_models_up_axis_upright)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024], model[1100];
    fresh_dir("up", dir, sizeof dir);
    snprintf(model, sizeof model, "%s/tall.stl", dir);
    REQUIRE(write_box_stl(model, 1.0f, 1.0f, 4.0f));
    silhouette box;
    if (render_silhouette("STL default", dir, ARGS(model, "--size", "120x120"), 120, 120, &box)) {
        CHECK(box.y1 - box.y0 > 2 * (box.x1 - box.x0));
    }
    const char *const axes[] = { "+x", "-x", "+y", "-y", "+z", "-z" };
    for (int i = 0; i < 6; i++) {
        char label[64];
        snprintf(label, sizeof label, "--up %s", axes[i]);
        if (!render_silhouette(label, dir, ARGS(model, "--size", "120x120", "--up", axes[i]), 120,
                               120, &box)) {
            continue;
        }
        int bw = box.x1 - box.x0, bh = box.y1 - box.y0;
        bool upright = axes[i][1] == 'z';
        if (upright ? !(bh > 2 * bw) : !(bw > bh)) {
            FAILF("%s: silhouette %dx%d, expected it %s", label, bw + 1, bh + 1,
                  upright ? "standing" : "lying");
        }
    }
    /* The same box as OBJ stands on +y: lying down by default. */
    char obj[1100];
    snprintf(obj, sizeof obj, "%s/tall.obj", dir);
    const char *text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 4\nv 1 0 4\nv 1 1 4\nv 0 1 4\n"
                       "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    REQUIRE(write_whole(obj, text, strlen(text)));
    if (render_silhouette("OBJ default", dir, ARGS(obj, "--size", "120x120"), 120, 120, &box)) {
        CHECK(box.x1 - box.x0 > box.y1 - box.y0);
    }
}

/* The default camera fits the model's projection, not a sphere around it:
 * for wide, square and tall images, turned or not, perspective or
 * orthographic, the silhouette reaches the 5% margin on both sides in one
 * dimension (within 2 pixels: a partly covered pixel counts) and stays
 * within the margins in the other. */
SR_TEST(default_camera_fills_the_frame_to_its_margin)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024], model[1100];
    fresh_dir("fit", dir, sizeof dir);
    snprintf(model, sizeof model, "%s/box.stl", dir);
    REQUIRE(write_box_stl(model, 1.0f, 2.0f, 0.6f));
    const int sizes[3][2] = { { 400, 100 }, { 160, 160 }, { 100, 400 } };
    const char *const turns[] = { "0", "35", "200" };
    for (int i = 0; i < 3; i++) {
        for (int t = 0; t < 3; t++) {
            for (int ortho = 0; ortho < 2; ortho++) {
                int w = sizes[i][0], h = sizes[i][1];
                char size[32], label[96];
                snprintf(size, sizeof size, "%dx%d", w, h);
                snprintf(label, sizeof label, "%s --turn %s%s", size, turns[t],
                         ortho ? " --ortho" : "");
                silhouette box;
                bool ok = render_silhouette(label, dir,
                                            ortho ? ARGS(model, "--size", size, "--turn", turns[t],
                                                         "--ortho")
                                                  : ARGS(model, "--size", size, "--turn", turns[t]),
                                            w, h, &box);
                if (!ok) {
                    continue;
                }
                /* The margin's first and last pixels inside it. */
                int mx = (int)(0.05 * w), my = (int)(0.05 * h);
                int left = box.x0 - mx, right = (w - 1 - mx) - box.x1;
                int top = box.y0 - my, bottom = (h - 1 - my) - box.y1;
                bool fills_x = abs(left) <= 2 && abs(right) <= 2;
                bool fills_y = abs(top) <= 2 && abs(bottom) <= 2;
                if (!(fills_x || fills_y) || left < -2 || right < -2 || top < -2 || bottom < -2) {
                    FAILF("%s: silhouette x %d..%d y %d..%d, the margin leaves x %d..%d y %d..%d",
                          label, box.x0, box.x1, box.y0, box.y1, mx, w - 1 - mx, my, h - 1 - my);
                }
            }
        }
    }
}

SR_TEST(render_writes_a_png_of_the_requested_size)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024];
    fresh_dir("ok", dir, sizeof dir);
    double lit = render_ok("--size 64x48", dir, "teapot.png", ARGS("--size", "64x48"), 64, 48);
    /* The teapot and its ground fill a good part of the frame. */
    CHECK(lit > 0.2);
    lit = render_ok("--size=7x3", dir, "tiny.png", ARGS("--size=7x3", "--detail", "2"), 7, 3);
    CHECK(lit >= 0);
    CHECK_EQ(count_entries(dir, NULL, 0), 2);   /* no temporaries left */
}

typedef struct mode_case {
    const char *label;
    const char *args[8];
    bool blank;         /* nothing but background is expected */
} mode_case;

static const mode_case modes[] = {
    { "shading flat", { "--shading", "flat" }, false },
    { "shading gouraud", { "--shading", "gouraud" }, false },
    { "shading phong", { "--shading", "phong" }, false },
    { "shading normals", { "--shading", "normals" }, false },
    { "shading depth", { "--shading", "depth" }, false },
    { "shading unlit", { "--shading", "unlit" }, false },
    { "depth-func never", { "--depth-func", "never" }, true },
    { "depth-func less", { "--depth-func", "less" }, false },
    { "depth-func equal", { "--depth-func", "equal" }, true },
    { "depth-func lequal", { "--depth-func", "lequal" }, false },
    { "depth-func greater", { "--depth-func", "greater" }, false },
    { "depth-func notequal", { "--depth-func", "notequal" }, false },
    { "depth-func gequal", { "--depth-func", "gequal" }, false },
    { "depth-func always", { "--depth-func", "always" }, false },
    { "depth-format d16", { "--depth-format", "d16" }, false },
    { "depth-format d24", { "--depth-format", "d24" }, false },
    { "depth-format d32", { "--depth-format", "d32" }, false },
    { "depth-format d32f", { "--depth-format", "d32f" }, false },
    { "ortho", { "--ortho" }, false },
    { "turn", { "--turn", "45" }, false },
    { "turn=-400", { "--turn=-400" }, false },
    { "camera eye", { "--camera", "eye=0,6,9" }, false },
    { "camera eye target up", { "--camera", "eye=4,3,5,target=0,1,0,up=0,1,0" }, false },
    { "camera along up", { "--camera", "eye=0,10,0,target=0,0,0" }, false },
    { "fov", { "--fov", "60" }, false },
    { "near far", { "--near", "1", "--far", "50" }, false },
    { "light dir", { "--light", "dir=-1,-1,-1" }, false },
    { "light point color intensity", { "--light", "point=3,5,4,color=#ffcc88,intensity=2" }, false },
    { "two lights", { "--light", "dir=0,-1,0", "--light", "dir=1,0,0,color=0.2,0.4,1" }, false },
    { "ambient", { "--ambient", "skyblue" }, false },
    { "material", { "--material", "color=steelblue,specular=#fff,shininess=90" }, false },
    { "background", { "--background", "#abc" }, false },
    { "projection-interp affine", { "--projection-interp", "affine" }, false },
    { "projection-interp perspective", { "--projection-interp", "perspective" }, false },
    { "rasterizer scanline", { "--rasterizer", "scanline" }, false },
    { "rasterizer barycentric", { "--rasterizer", "barycentric" }, false },
    { "cull none", { "--cull", "none" }, false },
    { "cull front", { "--cull", "front" }, false },
    { "front-face cw", { "--front-face", "cw" }, false },
    { "normals flat", { "--normals", "flat" }, false },
    { "normals smooth", { "--normals", "smooth" }, false },
    { "normals file", { "--normals", "file" }, false },
    { "png-level 0", { "--png-level", "0" }, false },
    { "png-level 9", { "--png-level", "9" }, false },
    { "threads 1", { "--threads", "1" }, false },
    { "threads 3", { "--threads", "3" }, false },
};

SR_TEST(every_mode_renders_a_png)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024];
    fresh_dir("ok", dir, sizeof dir);
    for (size_t i = 0; i < sizeof modes / sizeof modes[0]; i++) {
        const char *args[MAX_ARGS + 1];
        const char *common[] = { "--size", "48x32", "--detail", "3", NULL };
        join_args(args, common, modes[i].args);
        double lit = render_ok(modes[i].label, dir, "mode.png", args, 48, 32);
        if (lit < 0) {
            continue;
        }
        if (modes[i].blank ? lit != 0.0 : lit < 0.05) {
            FAILF("%s: %.0f%% of the pixels are not background", modes[i].label, lit * 100);
        }
    }
    CHECK_EQ(count_entries(dir, NULL, 0), 1);
}

static char *render_bytes(const char *label, const char *dir, const char *name,
                          const char *const *args, size_t *len)
{
    *len = 0;
    if (render_ok(label, dir, name, args, 96, 64) < 0) {
        return NULL;
    }
    char path[1400];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return read_whole(path, len);
}

/* The three rasterizers give the same pixels (docs/raster-rules.md §3.5), hence the
 * same PNG bytes; so do one thread and several. */
SR_TEST(rasterizers_and_thread_counts_give_identical_pngs)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024];
    fresh_dir("ok", dir, sizeof dir);
    const char *variants[][10] = {
        { "--rasterizer", "halfspace", "--threads", "1" },
        { "--rasterizer", "scanline" },
        { "--rasterizer", "barycentric" },
        { "--rasterizer", "halfspace", "--threads", "4" },
        { "--rasterizer", "scanline", "--threads", "3" },
    };
    const char *scenes[][10] = {
        { "--size", "96x64", "--detail", "6" },
        { "--size", "96x64", "--detail", "4", "--shading", "gouraud", "--cull", "none" },
    };
    for (size_t s = 0; s < 2; s++) {
        size_t ref_len = 0;
        char *ref = NULL;
        for (size_t v = 0; v < sizeof variants / sizeof variants[0]; v++) {
            const char *args[MAX_ARGS + 1];
            join_args(args, scenes[s], variants[v]);
            char label[128];
            snprintf(label, sizeof label, "scene %zu, %s %s %s %s", s, variants[v][0],
                     variants[v][1], variants[v][2] ? variants[v][2] : "",
                     variants[v][3] ? variants[v][3] : "");
            size_t len;
            char *png = render_bytes(label, dir, "r.png", args, &len);
            if (!png) {
                continue;
            }
            if (!ref) {
                ref = png;
                ref_len = len;
                continue;
            }
            if (len != ref_len || memcmp(png, ref, len) != 0) {
                FAILF("%s: PNG differs from the first variant's", label);
            }
            free(png);
        }
        free(ref);
    }
}

/* Antialiasing is on by default: 4x MSAA, byte for byte, and not the
 * aliased image of --aa none. */
SR_TEST(msaa4_is_the_default_antialiasing)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024];
    fresh_dir("aa", dir, sizeof dir);
    size_t ld, lm, ln;
    char *d = render_bytes("default", dir, "d.png", ARGS("--size", "96x64", "--detail", "4"), &ld);
    char *m = render_bytes("msaa4", dir, "m.png",
                           ARGS("--size", "96x64", "--detail", "4", "--aa", "msaa4"), &lm);
    char *n = render_bytes("none", dir, "n.png",
                           ARGS("--size", "96x64", "--detail", "4", "--aa", "none"), &ln);
    REQUIRE(d && m && n);
    CHECK(ld == lm && memcmp(d, m, ld) == 0);
    CHECK(!(ld == ln && memcmp(d, n, ld) == 0));
    free(d);
    free(m);
    free(n);
}

/* A single render draws its MSAA image straight into the multisampled
 * framebuffer it writes out (render_job_direct_desc); a batch draws into
 * a work image and resolves it into a single-sampled one.  Both must give
 * the same bytes, at every sample count, over a transparent background
 * (alpha resolved too) and with two triangles crossing in depth. */
SR_TEST(single_render_and_batch_resolve_msaa_alike)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char in[1024], out[1024], model[1100], single[1100], batched[1100];
    fresh_dir("msaa_in", in, sizeof in);
    fresh_dir("msaa_out", out, sizeof out);
    snprintf(model, sizeof model, "%s/m.obj", in);
    static const char obj[] = "v -1 -1 0\nv 1 -1 0\nv 0 1 0\n"
                              "v -1 0.5 -0.5\nv 1 0.2 0.5\nv 0.3 -1 0.2\n"
                              "f 1 2 3\nf 4 6 5\n";
    REQUIRE(write_whole(model, obj, sizeof obj - 1));
    snprintf(single, sizeof single, "%s/single.png", out);
    snprintf(batched, sizeof batched, "%s/m.png", out);
    const char *aa_modes[] = { "msaa2", "msaa4", "msaa8", "msaa16" };
    for (size_t i = 0; i < sizeof aa_modes / sizeof *aa_modes; i++) {
        cli_run r;
        REQUIRE(run_cli(ARGS("render", model, "-o", single, "--size", "96x64", "--aa", aa_modes[i],
                             "--background", "transparent"), &r));
        CHECK(r.status == 0);
        cli_run_free(&r);
        REQUIRE(run_cli(ARGS("render", in, "--output-dir", out, "--size", "96x64", "--aa",
                             aa_modes[i], "--background", "transparent"), &r));
        CHECK(r.status == 0);
        cli_run_free(&r);
        size_t ls = 0, lb = 0;
        char *a = read_whole(single, &ls), *b = read_whole(batched, &lb);
        REQUIRE(a && b);
        if (ls != lb || memcmp(a, b, ls) != 0) {
            FAILF("%s: the single render's PNG differs from the batch's", aa_modes[i]);
        }
        free(a);
        free(b);
    }
}

static bool has_model_extension(const char *name)
{
    const char *dot = strrchr(name, '.');
    return dot && (strcmp(dot, ".obj") == 0 || strcmp(dot, ".ply") == 0 ||
                   strcmp(dot, ".stl") == 0);
}

static int compare_names(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

SR_TEST(every_shared_model_renders_in_every_shading_mode)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    const char *models = sr_test_models_dir();
    if (!models) {
        SKIP("no shared models directory");
    }
    DIR *d = opendir(models);
    REQUIRE(d != NULL);
    char *names[128];
    size_t n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL && n < 128) {
        if (e->d_name[0] != '.' && has_model_extension(e->d_name)) {
            names[n++] = strdup(e->d_name);
        }
    }
    closedir(d);
    if (n == 0) {
        SKIP("no OBJ, PLY or STL files in the shared models directory");
    }
    qsort(names, n, sizeof names[0], compare_names);
    char dir[1024];
    fresh_dir("ok", dir, sizeof dir);
    const char *shadings[] = { "flat", "gouraud", "phong", "normals", "depth", "unlit" };
    for (size_t i = 0; i < n; i++) {
        char path[1400];
        snprintf(path, sizeof path, "%s/%s", models, names[i]);
        for (size_t s = 0; s < sizeof shadings / sizeof shadings[0]; s++) {
            char label[400];
            snprintf(label, sizeof label, "%s --shading %s", names[i], shadings[s]);
            double lit = render_ok(label, dir, "model.png",
                                   ARGS(path, "--size", "96x64", "--shading", shadings[s]), 96, 64);
            /* The camera frames the model: it covers part of the image. */
            if (lit >= 0 && lit < 0.03) {
                FAILF("%s: only %.1f%% of the pixels show the model", label, lit * 100);
            }
        }
        free(names[i]);
    }
    CHECK_EQ(count_entries(dir, NULL, 0), 1);
}

/* A render over an existing file replaces all of it (via a temporary and
 * a rename), keeps its permissions and leaves no temporary behind. */
SR_TEST(render_replaces_an_existing_file_atomically)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024], out[1100];
    fresh_dir("ok", dir, sizeof dir);
    snprintf(out, sizeof out, "%s/image.png", dir);
    /* Larger than the image will be, so a write in place would leave a tail. */
    size_t junk_n = 200000;
    unsigned char *junk = malloc(junk_n);
    REQUIRE(junk != NULL);
    for (size_t i = 0; i < junk_n; i++) {
        junk[i] = (unsigned char)(i * 131 + 17);
    }
    bool wrote = write_whole(out, junk, junk_n);
    free(junk);
    REQUIRE(wrote);
    REQUIRE(chmod(out, 0640) == 0);

    CHECK(render_ok("over an existing file", dir, "image.png",
                    ARGS("--size", "40x30", "--detail", "3"), 40, 30) > 0);
    struct stat st;
    REQUIRE(stat(out, &st) == 0);
    CHECK(st.st_size < 100000);
    CHECK_EQ(st.st_mode & 0777, 0640);
    char first[256];
    CHECK_EQ(count_entries(dir, first, sizeof first), 1);
    CHECK(strcmp(first, "image.png") == 0);

    /* And again over the image just written, with different content. */
    CHECK(render_ok("over its own output", dir, "image.png",
                    ARGS("--size", "24x20", "--detail", "2", "--shading", "normals"), 24, 20) > 0);
    CHECK_EQ(count_entries(dir, NULL, 0), 1);
}

SR_TEST(verbose_reports_on_stderr_and_still_renders)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024], out[1100];
    fresh_dir("ok", dir, sizeof dir);
    snprintf(out, sizeof out, "%s/v.png", dir);
    const char *forms[] = { "-v", "--verbose" };
    for (size_t i = 0; i < 2; i++) {
        cli_run r;
        REQUIRE(run_cli(ARGS("render", forms[i], "--size", "32x24", "--detail", "2", "-o", out),
                        &r));
        CHECK_EQ(r.status, 0);
        CHECK_STR_CONTAINS(r.err, "softrast: 32x24, ");
        CHECK_STR_CONTAINS(r.err, " triangles, ");
        CHECK_EQ(r.out_len, 0);
        cli_run_free(&r);
    }
    int w = 0, h = 0;
    uint8_t *px = NULL;
    sr_io_error err;
    CHECK_EQ(sr_read_png(out, NULL, &w, &h, &px, &err), SR_OK);
    CHECK_EQ(w, 32);
    CHECK_EQ(h, 24);
    free(px);
}

/* ---- textures in JPEG, and a model's own texture that cannot be read ---- */

#if defined(SR_CLI_PATH) && defined(SR_HAVE_JPEG_TEST)
#include "jpeg_encode.h"

/* A 16 x 16 JPEG of four colored squares, the first `keep` bytes of it
 * when keep > 0. */
static bool write_test_jpeg(const char *path, size_t keep)
{
    uint8_t px[16 * 16 * 3];
    for (int y = 0; y < 16; y++) {
        for (int x = 0; x < 16; x++) {
            int q = x / 8 + 2 * (y / 8);
            uint8_t *p = px + 3 * (16 * y + x);
            p[0] = (uint8_t)(q & 1 ? 230 : 20);
            p[1] = (uint8_t)(q & 2 ? 200 : 40);
            p[2] = (uint8_t)(q == 3 ? 250 : 60);
        }
    }
    size_t len;
    uint8_t *jpg = jpeg_encode(px, 16, 16, (jpeg_encoding){ JCS_RGB, 90, false, false }, &len);
    bool ok = jpg && write_whole(path, jpg, keep && keep < len ? keep : len);
    free(jpg);
    return ok;
}

/* A textured quad DIR/NAME.obj; with `map`, a material whose map_Kd is it. */
static bool write_textured_quad(const char *dir, const char *name, const char *map)
{
    char path[1200], mtl[1200];
    snprintf(path, sizeof path, "%s/%s.obj", dir, name);
    char text[600];
    snprintf(text, sizeof text,
             "%s%s%s"
             "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
             "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n",
             map ? "mtllib " : "", map ? name : "", map ? ".mtl\nusemtl m\n" : "");
    if (!write_whole(path, text, strlen(text))) {
        return false;
    }
    if (!map) {
        return true;
    }
    snprintf(mtl, sizeof mtl, "%s/%s.mtl", dir, name);
    snprintf(text, sizeof text, "newmtl m\nmap_Kd %s\n", map);
    return write_whole(mtl, text, strlen(text));
}
#endif

/* A JPEG texture - named by map_Kd or found as MODEL_texture.jpg - gives
 * the same image as its decoded pixels given as a PNG. */
SR_TEST(jpeg_textures_render_as_their_pixels_do)
{
#if !defined(SR_CLI_PATH) || !defined(SR_HAVE_JPEG_TEST)
    SKIP("needs the softrast tool and libjpeg");
#else
    char dir[1024], jpg[1100], png[1100], guessed[1100], model[1100], plain[1100];
    fresh_dir("jpeg", dir, sizeof dir);
    snprintf(jpg, sizeof jpg, "%s/tex.jpg", dir);
    snprintf(png, sizeof png, "%s/decoded.png", dir);
    snprintf(guessed, sizeof guessed, "%s/plain_texture.jpg", dir);
    snprintf(model, sizeof model, "%s/quad.obj", dir);
    snprintf(plain, sizeof plain, "%s/plain.obj", dir);
    REQUIRE(write_test_jpeg(jpg, 0));
    REQUIRE(write_test_jpeg(guessed, 0));
    REQUIRE(write_textured_quad(dir, "quad", "tex.jpg"));
    REQUIRE(write_textured_quad(dir, "plain", NULL));
    int w, h;
    uint8_t *px = NULL;
    sr_io_error err;
    REQUIRE(sr_read_jpeg(jpg, &w, &h, &px, &err) == SR_OK);
    REQUIRE(sr_write_png(png, w, h, px, 4 * (size_t)w, NULL, &err) == SR_OK);
    free(px);

    size_t la, lb, lc, ld;
    char *a = render_bytes("map_Kd tex.jpg", dir, "a.png", ARGS(model, "--size", "96x64"), &la);
    char *b = render_bytes("--texture decoded.png", dir, "b.png",
                           ARGS(model, "--texture", png, "--size", "96x64"), &lb);
    char *c = render_bytes("plain_texture.jpg", dir, "c.png", ARGS(plain, "--size", "96x64"), &lc);
    /* Without any texture (the guess moved away): a different picture. */
    char moved[1100];
    snprintf(moved, sizeof moved, "%s/elsewhere.jpg", dir);
    REQUIRE(rename(guessed, moved) == 0);
    char *d = render_bytes("untextured", dir, "d.png", ARGS(plain, "--size", "96x64"), &ld);
    REQUIRE(a && b && c && d);
    CHECK(la == lb && memcmp(a, b, la) == 0);
    CHECK(lc == lb && memcmp(c, b, lc) == 0);
    CHECK(!(ld == lb && memcmp(d, b, ld) == 0));
    free(a);
    free(b);
    free(c);
    free(d);
#endif
}

/* A texture the model brings that cannot be read costs a warning, not
 * the picture; one the user names with --texture is an error. */
SR_TEST(a_models_unreadable_texture_is_a_warning)
{
#if !defined(SR_CLI_PATH) || !defined(SR_HAVE_JPEG_TEST)
    SKIP("needs the softrast tool and libjpeg");
#else
    char dir[1024], broken[1100], model[1100], missing[1100], plain[1100], out[1100];
    fresh_dir("texwarn", dir, sizeof dir);
    snprintf(broken, sizeof broken, "%s/broken.jpg", dir);
    snprintf(model, sizeof model, "%s/quad.obj", dir);
    snprintf(missing, sizeof missing, "%s/lost.obj", dir);
    snprintf(plain, sizeof plain, "%s/plain.obj", dir);
    REQUIRE(write_test_jpeg(broken, 300)); /* cut short */
    REQUIRE(write_textured_quad(dir, "quad", "broken.jpg"));
    REQUIRE(write_textured_quad(dir, "lost", "nowhere.png"));
    REQUIRE(write_textured_quad(dir, "plain", NULL));
    size_t lp;
    char *untextured = render_bytes("untextured", dir, "p.png", ARGS(plain, "--size", "96x64"), &lp);
    REQUIRE(untextured);

    struct {
        const char *model, *needle;
    } cases[] = {
        { model, "broken.jpg: corrupt JPEG" },
        { missing, "nowhere.png: No such file or directory, named by the model's material" },
    };
    snprintf(out, sizeof out, "%s/w.png", dir);
    for (size_t i = 0; i < 2; i++) {
        cli_run r;
        REQUIRE(run_cli(ARGS("render", cases[i].model, "--size", "96x64", "-o", out), &r));
        CHECK_EQ(r.status, 0);
        CHECK(is_one_line(r.err, r.err_len));
        CHECK_STR_CONTAINS(r.err, "softrast: warning: ");
        CHECK_STR_CONTAINS(r.err, cases[i].needle);
        CHECK_STR_CONTAINS(r.err, "(drawing the model without its texture)");
        cli_run_free(&r);
        size_t lw;
        char *img = read_whole(out, &lw);
        CHECK(img && lw == lp && memcmp(img, untextured, lp) == 0);
        free(img);
    }
    free(untextured);
    expect_render_failure("--texture broken.jpg", ARGS(plain, "--texture", broken), 2,
                          "broken.jpg: corrupt JPEG");
#endif
}

#ifdef SR_CLI_PATH
/* A glTF 2.0 quad (positions, texture coordinates, indices) whose
 * material's base color texture is `image` (n bytes): as a self-contained
 * .gltf, with the geometry and the image in data URIs, or as a binary
 * .glb, with both in its BIN chunk and the image in a buffer view - the
 * two ways exporters embed a texture. */
static bool write_gltf_quad(const char *path, const uint8_t *image, size_t n, bool binary)
{
    const float pos[12] = { -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0 };
    const float uv[8] = { 0, 1, 1, 1, 1, 0, 0, 0 };
    const uint16_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    size_t bin_len = (92 + n + 3) & ~(size_t)3;
    uint8_t *bin = calloc(1, bin_len);
    char *b64buf = malloc(4 * (92 / 3 + 1) + 1), *b64img = malloc(4 * (n / 3 + 1) + 1);
    char *json = malloc(4 * (n / 3 + 1) + 4096);
    uint8_t *glb = malloc(20 + 4 * (n / 3 + 1) + 4096 + 8 + bin_len);
    bool ok = bin && b64buf && b64img && json && glb;
    if (ok) {
        le_copy(bin, pos, 12, 4); /* glTF and GLB are little endian on any host */
        le_copy(bin + 48, uv, 8, 4);
        le_copy(bin + 80, idx, 6, 2);
        memcpy(bin + 92, image, n);
        gltf_base64(bin, 92, b64buf);
        gltf_base64(image, n, b64img);
        char buffer[200], image_ref[200];
        if (binary) {
            snprintf(buffer, sizeof buffer, "{\"byteLength\":%zu}", bin_len);
            snprintf(image_ref, sizeof image_ref, "{\"bufferView\":3,\"mimeType\":\"image/png\"}");
        }
        sprintf(json,
                "{\"asset\":{\"version\":\"2.0\"},"
                "\"buffers\":[%s%s%s],"
                "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},"
                "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":32},"
                "{\"buffer\":0,\"byteOffset\":80,\"byteLength\":12},"
                "{\"buffer\":0,\"byteOffset\":92,\"byteLength\":%zu}],"
                "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,"
                "\"type\":\"VEC3\",\"min\":[-1,-1,0],\"max\":[1,1,0]},"
                "{\"bufferView\":1,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\"},"
                "{\"bufferView\":2,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}],"
                "\"images\":[%s%s%s],"
                "\"textures\":[{\"source\":0}],"
                "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],"
                "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":1},"
                "\"indices\":2,\"material\":0}]}],"
                "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0}",
                binary ? buffer : "{\"byteLength\":92,\"uri\":\"data:application/octet-stream;base64,",
                binary ? "" : b64buf, binary ? "" : "\"}", n,
                binary ? image_ref : "{\"uri\":\"data:image/png;base64,", binary ? "" : b64img,
                binary ? "" : "\"}");
        if (!binary) {
            ok = write_whole(path, json, strlen(json));
        } else {
            /* Header, then the JSON chunk padded with spaces and the BIN
             * chunk padded with zeros, each to 4 bytes. */
            uint32_t json_len = (uint32_t)((strlen(json) + 3) & ~(size_t)3);
            memset(json + strlen(json), ' ', json_len - strlen(json));
            uint32_t words[5] = { 0x46546C67u, 2, (uint32_t)(12 + 8 + json_len + 8 + bin_len),
                                  json_len, 0x4E4F534Au };
            size_t at = 0;
            le_copy(glb, words, 5, 4);
            at = 20;
            memcpy(glb + at, json, json_len);
            at += json_len;
            uint32_t bin_head[2] = { (uint32_t)bin_len, 0x004E4942u };
            le_copy(glb + at, bin_head, 2, 4);
            at += 8;
            memcpy(glb + at, bin, bin_len);
            ok = write_whole(path, glb, at + bin_len);
        }
    }
    free(bin);
    free(b64buf);
    free(b64img);
    free(json);
    free(glb);
    return ok;
}
#endif

#ifdef SR_CLI_PATH
static uint8_t *render_pixels(const char *const *args, const char *out, int *w, int *h);
#endif

/* An image a .gltf or .glb file embeds colors the model as the same
 * pixels given with --texture do; a damaged one is a warning, and the
 * model is drawn as it is without a texture. */
SR_TEST(a_gltf_files_embedded_texture_is_used)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    if (!sr_io_have_gltf()) {
        SKIP("this build reads no glTF (jansson was not found)");
    }
    char dir[1024], tex[1100], out[1100];
    fresh_dir("gltf", dir, sizeof dir);
    snprintf(tex, sizeof tex, "%s/tex.png", dir);
    uint8_t px[8 * 8 * 4];
    for (int i = 0; i < 64; i++) {
        int q = (i % 8) / 4 + 2 * (i / 32);
        uint8_t *p = px + 4 * i;
        p[0] = (uint8_t)(q & 1 ? 230 : 20);
        p[1] = (uint8_t)(q & 2 ? 200 : 40);
        p[2] = (uint8_t)(q == 3 ? 250 : 60);
        p[3] = 255;
    }
    sr_io_error err;
    REQUIRE(sr_write_png(tex, 8, 8, px, 32, NULL, &err) == SR_OK);
    char green[1100];
    snprintf(green, sizeof green, "%s/green.png", dir);
    uint8_t g4[16] = { 20, 200, 40, 255, 20, 200, 40, 255, 20, 200, 40, 255, 20, 200, 40, 255 };
    REQUIRE(sr_write_png(green, 2, 2, g4, 8, NULL, &err) == SR_OK);
    size_t n;
    char *png = read_whole(tex, &n);
    REQUIRE(png);
    const char *forms[] = { "gltf", "glb" };
    for (int binary = 0; binary < 2; binary++) {
        char model[1100], broken[1100];
        snprintf(model, sizeof model, "%s/quad.%s", dir, forms[binary]);
        snprintf(broken, sizeof broken, "%s/broken.%s", dir, forms[binary]);
        REQUIRE(write_gltf_quad(model, (const uint8_t *)png, n, binary));
        REQUIRE(write_gltf_quad(broken, (const uint8_t *)png, n / 2, binary)); /* cut short */

        size_t la, lb, lc;
        char *a = render_bytes(model, dir, "a.png", ARGS(model, "--size", "96x64"), &la);
        char *b = render_bytes(model, dir, "b.png",
                               ARGS(model, "--texture", tex, "--size", "96x64"), &lb);
        REQUIRE(a && b);
        CHECK(la == lb && memcmp(a, b, la) == 0);
        free(a);
        free(b);

        /* The glTF reader, under every look, refuses a damaged image with
         * its JSON path. */
        snprintf(out, sizeof out, "%s/c.png", dir);
        char pointer[200];
        snprintf(pointer, sizeof pointer, "broken.%s: /images/0: truncated PNG", forms[binary]);
        for (int classic = 0; classic < 2; classic++) {
            remove(out);
            cli_run r;
            REQUIRE(run_cli(ARGS("render", broken, "--size", "96x64", "--shading",
                                 classic ? "phong" : "pbr", "-o", out),
                            &r));
            CHECK_EQ(r.status, 2);
            CHECK(is_one_line(r.err, r.err_len));
            CHECK_STR_CONTAINS(r.err, pointer);
            CHECK(access(out, F_OK) != 0);
            cli_run_free(&r);
        }
        /* The classic models take the embedded image as --texture's too,
         * filtered in linear light as the reader's sRGB base color
         * textures are. */
        a = render_bytes(model, dir, "c.png", ARGS(model, "--size", "96x64", "--shading", "phong"),
                         &la);
        b = render_bytes(model, dir, "d.png",
                         ARGS(model, "--texture", tex, "--texture-srgb", "--size", "96x64",
                              "--shading", "phong"),
                         &lc);
        REQUIRE(a && b);
        CHECK(la == lc && memcmp(a, b, la) == 0);
        free(a);
        free(b);
        /* --texture replaces the file's image under every look: a plain
         * green one leaves no texel of the red and white quarters. */
        for (int classic = 0; classic < 2; classic++) {
            int w, h;
            uint8_t *img = render_pixels(ARGS("render", model, "--texture", green, "--size",
                                              "96x64", "--shading", classic ? "phong" : "pbr",
                                              "-o", out), out, &w, &h);
            REQUIRE(img);
            int greenish = 0, reddish = 0;
            for (int i = 0; i < w * h; i++) {
                const uint8_t *q = img + 4 * i;
                greenish += q[1] > q[0] + 40 && q[1] > q[2] + 40;
                reddish += q[0] > q[1] + 40;
            }
            CHECK(greenish > w * h / 8);
            CHECK_EQ(reddish, 0);
            free(img);
        }
    }
    free(png);
#endif
}

#ifdef SR_CLI_PATH
/* Two squares side by side in glTF (x -1..0 and 0..1, facing +z), each
 * with its own material, `materials` the JSON array, written to model. */
static bool write_two_material_quads(const char *model, const char *materials)
{
    const float pos[24] = { -1, -1, 0, 0, -1, 0, 0, 1, 0, -1, 1, 0,
                            0,  -1, 0, 1, -1, 0, 1, 1, 0, 0,  1, 0 };
    const uint16_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    uint8_t buf[108];
    le_copy(buf, pos, 24, 4); /* glTF buffers are little endian on any host */
    le_copy(buf + 96, idx, 6, 2);
    char b64[160], json[3000];
    gltf_base64(buf, sizeof buf, b64);
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},"
             "\"buffers\":[{\"byteLength\":108,\"uri\":\"data:application/octet-stream;base64,%s\"}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},"
             "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":48},"
             "{\"buffer\":0,\"byteOffset\":96,\"byteLength\":12}],"
             "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
             "\"min\":[-1,-1,0],\"max\":[0,1,0]},"
             "{\"bufferView\":1,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
             "\"min\":[0,-1,0],\"max\":[1,1,0]},"
             "{\"bufferView\":2,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}],"
             "\"materials\":%s,"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":2,"
             "\"material\":0},{\"attributes\":{\"POSITION\":1},\"indices\":2,\"material\":1}]}],"
             "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0}",
             b64, materials);
    return write_whole(model, json, strlen(json));
}
#endif

/* Two squares side by side in glTF, each with its own material's base
 * color factor and no texture: the colors come through as OBJ's Kd does
 * (unlit shading shows them unchanged).  The other classic models
 * translate the material (render_gltf_classic): a black base color (an
 * emissive-only material) stays black, not the classic default gray a
 * zero diffuse means, a white dielectric is lit white, and what
 * --material names wins, as over any model's material. */
SR_TEST(gltf_material_colors_color_the_model)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    if (!sr_io_have_gltf()) {
        SKIP("this build reads no glTF (jansson was not found)");
    }
    char dir[1024], model[1100], out[1100];
    fresh_dir("gltf_colors", dir, sizeof dir);
    snprintf(model, sizeof model, "%s/two.gltf", dir);
    snprintf(out, sizeof out, "%s/two.png", dir);
    REQUIRE(write_two_material_quads(model,
        "[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.9,0.1,0.05,1]}},"
        "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.05,0.2,0.9,1]}}]"));
    cli_run r;
    REQUIRE(run_cli(ARGS("render", model, "--shading", "unlit", "--camera", "eye=0,0,4",
                         "--size", "64x48", "-o", out),
                    &r));
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.err_len, 0);
    cli_run_free(&r);
    int w, h;
    uint8_t *px = NULL;
    sr_io_error err;
    REQUIRE(sr_read_png(out, NULL, &w, &h, &px, &err) == SR_OK);
    /* A pixel a quarter in from each side, on the middle row. */
    const uint8_t *left = px + 4 * ((size_t)(h / 2) * w + w / 4);
    const uint8_t *right = px + 4 * ((size_t)(h / 2) * w + 3 * w / 4);
    CHECK(abs(left[0] - 230) <= 1 && abs(left[1] - 26) <= 1 && abs(left[2] - 13) <= 1);
    CHECK(abs(right[0] - 13) <= 1 && abs(right[1] - 51) <= 1 && abs(right[2] - 230) <= 1);
    free(px);

    REQUIRE(write_two_material_quads(model,
        "[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1]},"
        "\"emissiveFactor\":[1,0.5,0]},"
        "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,1,1,1],\"metallicFactor\":0}}]"));
    const char *classic[] = { "phong", "gouraud", "flat" };
    for (int k = 0; k < 4; k++) {
        /* the three models, then phong with --material color=0,0,1 */
        px = render_pixels(ARGS("render", model, "--shading", classic[k % 3],
                                k == 3 ? "--material" : "--aa", k == 3 ? "color=0,0,1" : "none",
                                "--camera", "eye=0,0,4", "--size", "64x48", "-o", out),
                           out, &w, &h);
        REQUIRE(px);
        left = px + 4 * ((size_t)(h / 2) * w + w / 4);
        right = px + 4 * ((size_t)(h / 2) * w + 3 * w / 4);
        if (k < 3) {
            CHECK(left[0] == 0 && left[1] == 0 && left[2] == 0);
            CHECK(right[0] > 150 && right[1] > 150 && right[2] > 150);
        } else {
            CHECK(left[2] > 150 && left[0] < 60 && left[1] < 60);
            CHECK(right[2] > 150 && right[0] < 60 && right[1] < 60);
        }
        free(px);
    }
#endif
}

#ifdef SR_CLI_PATH
/* The picture both parts tests render (96 x 64, unlit, eye=0,0.5,6): a
 * row of squares at y = -0.5..0.5 - left red texels (200, 20, 10), middle
 * green (0, 255, 0) with no texture, right blue texels (10, 30, 210) - and
 * a white square above the right one, whose texture is missing.  The
 * camera looks at the model's centre, y = 0.75: the row 7/10 down the
 * image crosses the row of squares, and the white one lies in the upper
 * right quarter. */
static void check_parts_picture(const char *path)
{
    int w, h;
    uint8_t *px = NULL;
    sr_io_error err;
    REQUIRE(sr_read_png(path, NULL, &w, &h, &px, &err) == SR_OK);
    int found[3] = { 0, 0, 0 }, white = 0;
    int row = h * 7 / 10;
    for (int x = 0; x < w; x++) {
        const uint8_t *p = px + 4 * ((size_t)row * w + x);
        found[0] += p[0] == 200 && p[1] == 20 && p[2] == 10;
        found[1] += p[0] == 0 && p[1] == 255 && p[2] == 0;
        found[2] += p[0] == 10 && p[1] == 30 && p[2] == 210;
    }
    for (int y = 0; y < h / 2; y++) {
        for (int x = w / 2; x < w; x++) {
            const uint8_t *p = px + 4 * ((size_t)y * w + x);
            white += p[0] == 255 && p[1] == 255 && p[2] == 255;
        }
    }
    CHECK(found[0] > 4); /* red texels on the left square */
    CHECK(found[1] > 4); /* the middle square's own color: no texture */
    CHECK(found[2] > 8); /* blue texels across the right square */
    CHECK(white > 4);    /* its texture missing: drawn white */
    free(px);
}
#endif

/* An OBJ whose materials name different textures: each part of the
 * model takes its own (left square red, middle square no texture - its
 * material's Kd, right square blue; the fourth material's file is missing:
 * one warning, and that square drawn without a texture). */
SR_TEST(obj_parts_take_their_own_textures)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    char dir[1024], model[1100], mtl[1100], red[1100], blue[1100], out[1100];
    fresh_dir("obj_parts", dir, sizeof dir);
    snprintf(model, sizeof model, "%s/parts.obj", dir);
    snprintf(mtl, sizeof mtl, "%s/parts.mtl", dir);
    snprintf(red, sizeof red, "%s/red.png", dir);
    snprintf(blue, sizeof blue, "%s/blue.png", dir);
    snprintf(out, sizeof out, "%s/parts.png", dir);
    const char *obj = "mtllib parts.mtl\n"
                      "v -2 -0.5 0\nv -1 -0.5 0\nv -1 0.5 0\nv -2 0.5 0\n"
                      "v -0.5 -0.5 0\nv 0.5 -0.5 0\nv 0.5 0.5 0\nv -0.5 0.5 0\n"
                      "v 1 -0.5 0\nv 2 -0.5 0\nv 2 0.5 0\nv 1 0.5 0\n"
                      "v 1 1 0\nv 2 1 0\nv 2 2 0\nv 1 2 0\n"
                      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                      "usemtl red\nf 1/1 2/2 3/3 4/4\n"
                      "usemtl plain\nf 5/1 6/2 7/3 8/4\n"
                      "usemtl blue\nf 9/1 10/2 11/3 12/4\n"
                      "usemtl gone\nf 13/1 14/2 15/3 16/4\n";
    const char *mats = "newmtl red\nKd 1 1 1\nmap_Kd red.png\n"
                       "newmtl plain\nKd 0 1 0\n"
                       "newmtl blue\nKd 1 1 1\nmap_Kd blue.png\n"
                       "newmtl gone\nKd 1 1 1\nmap_Kd missing.png\n";
    REQUIRE(write_whole(model, obj, strlen(obj)));
    REQUIRE(write_whole(mtl, mats, strlen(mats)));
    const uint8_t r4[16] = { 200, 20, 10, 255, 200, 20, 10, 255, 200, 20, 10, 255, 200, 20, 10, 255 };
    const uint8_t b4[16] = { 10, 30, 210, 255, 10, 30, 210, 255, 10, 30, 210, 255, 10, 30, 210, 255 };
    sr_io_error err;
    REQUIRE(sr_write_png(red, 2, 2, r4, 8, NULL, &err) == SR_OK);
    REQUIRE(sr_write_png(blue, 2, 2, b4, 8, NULL, &err) == SR_OK);
    cli_run r;
    REQUIRE(run_cli(ARGS("render", model, "--shading", "unlit", "--camera", "eye=0,0.5,6",
                         "--texture-filter", "nearest", "--size", "96x64", "-o", out),
                    &r));
    CHECK_EQ(r.status, 0);
    CHECK_STR_CONTAINS(r.err, "warning: ");
    CHECK_STR_CONTAINS(r.err, "missing.png");
    cli_run_free(&r);
    check_parts_picture(out);

    /* --texture still colors the whole model with one image. */
    REQUIRE(run_cli(ARGS("render", model, "--shading", "unlit", "--camera", "eye=0,0.5,6",
                         "--texture", blue, "--size", "96x64", "-o", out),
                    &r));
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.err_len, 0);
    cli_run_free(&r);
    int w, h;
    uint8_t *px = NULL;
    REQUIRE(sr_read_png(out, NULL, &w, &h, &px, &err) == SR_OK);
    int blues = 0, reds = 0, row = h * 7 / 10;
    for (int x = 0; x < w; x++) {
        const uint8_t *p = px + 4 * ((size_t)row * w + x);
        blues += p[0] == 10 && p[1] == 30 && p[2] == 210;
        reds += p[0] == 200 && p[1] == 20 && p[2] == 10;
    }
    CHECK(blues > 12);
    CHECK_EQ(reds, 0);
    free(px);
#endif
}

/* A glTF whose materials take different textures (gltf_parts_model),
 * under the classic models: each part of the model takes its own - left
 * square the embedded red image, middle square its green base color,
 * right square blue.png through two materials, the fifth material's file
 * (missing.png) white.  A missing or damaged image is an error naming its
 * JSON pointer, as under the physically based look. */
SR_TEST(gltf_parts_take_their_own_textures)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    if (!sr_io_have_gltf()) {
        SKIP("this build reads no glTF (jansson was not found)");
    }
    char dir[1024], model[1100], red[1100], blue[1100], white[1100], out[1100];
    fresh_dir("gltf_parts", dir, sizeof dir);
    snprintf(model, sizeof model, "%s/parts.gltf", dir);
    snprintf(red, sizeof red, "%s/red.png", dir);
    snprintf(blue, sizeof blue, "%s/blue.png", dir);
    snprintf(white, sizeof white, "%s/missing.png", dir);
    snprintf(out, sizeof out, "%s/parts.png", dir);
    const uint8_t r4[16] = { 200, 20, 10, 255, 200, 20, 10, 255, 200, 20, 10, 255, 200, 20, 10, 255 };
    const uint8_t b4[16] = { 10, 30, 210, 255, 10, 30, 210, 255, 10, 30, 210, 255, 10, 30, 210, 255 };
    uint8_t w4[16];
    memset(w4, 255, sizeof w4);
    sr_io_error err;
    REQUIRE(sr_write_png(red, 2, 2, r4, 8, NULL, &err) == SR_OK);
    REQUIRE(sr_write_png(blue, 2, 2, b4, 8, NULL, &err) == SR_OK);
    size_t n;
    char *png = read_whole(red, &n);
    REQUIRE(png);
    char *json = gltf_parts_model((const uint8_t *)png, n);
    REQUIRE(json);
    REQUIRE(write_whole(model, json, strlen(json)));
    free(json);
    cli_run r;
    REQUIRE(run_cli(ARGS("render", model, "--shading", "unlit", "--camera", "eye=0,0.5,6",
                         "--texture-filter", "nearest", "--size", "96x64", "-o", out),
                    &r));
    CHECK_EQ(r.status, 2);
    CHECK(is_one_line(r.err, r.err_len));
    CHECK_STR_CONTAINS(r.err, "parts.gltf: /images/2");
    CHECK_STR_CONTAINS(r.err, "missing.png");
    cli_run_free(&r);

    REQUIRE(sr_write_png(white, 2, 2, w4, 8, NULL, &err) == SR_OK);
    REQUIRE(run_cli(ARGS("render", model, "--shading", "unlit", "--camera", "eye=0,0.5,6",
                         "--texture-filter", "nearest", "--size", "96x64", "-o", out),
                    &r));
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.err_len, 0);
    cli_run_free(&r);
    check_parts_picture(out);

    char broken[1100];
    snprintf(broken, sizeof broken, "%s/broken.gltf", dir);
    json = gltf_parts_model((const uint8_t *)png, n / 2);
    REQUIRE(json);
    REQUIRE(write_whole(broken, json, strlen(json)));
    free(json);
    REQUIRE(run_cli(ARGS("render", broken, "--shading", "unlit", "--camera", "eye=0,0.5,6",
                         "--size", "96x64", "-o", out),
                    &r));
    CHECK_EQ(r.status, 2);
    CHECK(is_one_line(r.err, r.err_len));
    CHECK_STR_CONTAINS(r.err, "broken.gltf: /images/0: truncated PNG");
    cli_run_free(&r);
    free(png);
#endif
}

/* -o NAME.jpg writes a JPEG of the picture the PNG holds: the same size,
 * every channel close (JPEG is lossy: the bound is the mean error), and
 * --jpeg-quality trades size for error. */
SR_TEST(a_jpg_output_name_writes_a_jpeg)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    if (!sr_io_have_jpeg()) {
        SKIP("this build writes no JPEG (libjpeg-dev was not found)");
    }
    char dir[1024], png[1100], jpg[1100], low[1100];
    fresh_dir("jpeg_out", dir, sizeof dir);
    snprintf(png, sizeof png, "%s/t.png", dir);
    snprintf(jpg, sizeof jpg, "%s/t.JPG", dir);
    snprintf(low, sizeof low, "%s/low.jpeg", dir);
    const char *const runs[][9] = {
        { "render", "--size", "160x120", "--detail", "6", "-o", png, NULL },
        { "render", "--size", "160x120", "--detail", "6", "-o", jpg, NULL },
        { "render", "--size", "160x120", "--detail", "6", "--jpeg-quality", "20", "-o", low },
    };
    for (size_t i = 0; i < 3; i++) {
        const char *args[10];
        memcpy(args, runs[i], sizeof runs[i]);
        args[9] = NULL;
        cli_run r;
        REQUIRE(run_cli(args, &r));
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.err_len, 0);
        cli_run_free(&r);
    }
    size_t jn, ln;
    char *jbytes = read_whole(jpg, &jn), *lbytes = read_whole(low, &ln);
    REQUIRE(jbytes && lbytes && jn > 3);
    CHECK((uint8_t)jbytes[0] == 0xFF && (uint8_t)jbytes[1] == 0xD8 && (uint8_t)jbytes[2] == 0xFF);
    CHECK(ln < jn); /* quality 20 is smaller than 90 */
    free(jbytes);
    free(lbytes);
    int pw, ph, jw, jh, lw, lh;
    uint8_t *p = NULL, *j = NULL, *l = NULL;
    sr_io_error err;
    REQUIRE(sr_read_png(png, NULL, &pw, &ph, &p, &err) == SR_OK);
    REQUIRE(sr_read_jpeg(jpg, &jw, &jh, &j, &err) == SR_OK);
    REQUIRE(sr_read_jpeg(low, &lw, &lh, &l, &err) == SR_OK);
    REQUIRE(pw == jw && ph == jh && pw == lw && ph == lh);
    double ej = 0, el = 0;
    for (size_t i = 0; i < 4 * (size_t)pw * ph; i++) {
        if (i % 4 != 3) {
            ej += abs((int)p[i] - (int)j[i]);
            el += abs((int)p[i] - (int)l[i]);
        }
    }
    ej /= 3.0 * pw * ph;
    el /= 3.0 * pw * ph;
    if (ej >= 4.0) { /* 2.66 levels measured at quality 90 (4:2:0 chroma) */
        FAILF("mean error %.2f", ej);
    }
    CHECK(el > ej);
    free(p);
    free(j);
    free(l);
    CHECK_EQ(count_entries(dir, NULL, 0), 3); /* no temporaries */
#endif
}

/* Every command that writes an image goes by the name: demo and svg write
 * a JPEG for NAME.jpg; svg refuses one whose background would be
 * transparent, which JPEG cannot hold. */
SR_TEST(demo_and_svg_write_a_jpeg_for_a_jpg_name)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    if (!sr_io_have_jpeg()) {
        SKIP("this build writes no JPEG (libjpeg-dev was not found)");
    }
    char dir[1024], demo[1100], svg_in[1100], svg_out[1100];
    fresh_dir("jpeg_cmds", dir, sizeof dir);
    snprintf(demo, sizeof demo, "%s/viewport.jpeg", dir);
    snprintf(svg_in, sizeof svg_in, "%s/box.svg", dir);
    snprintf(svg_out, sizeof svg_out, "%s/box.jpg", dir);
    const char *svg = "<svg xmlns='http://www.w3.org/2000/svg' width='80' height='60'>"
                      "<rect x='32' y='16' width='32' height='32' fill='#c03020'/></svg>";
    REQUIRE(write_whole(svg_in, svg, strlen(svg)));

    cli_run r;
    REQUIRE(run_cli(ARGS("demo", "viewport", "-o", demo), &r));
    CHECK_EQ(r.status, 0);
    cli_run_free(&r);
    int w, h;
    uint8_t *px = NULL;
    sr_io_error err;
    CHECK_EQ(sr_read_jpeg(demo, &w, &h, &px, &err), SR_OK);
    free(px);

    if (svg_command_built()) {
        REQUIRE(run_cli(ARGS("svg", svg_in, "-o", svg_out), &r));
        check_failure_output("svg to a JPEG without a background", &r, 2,
                             "a JPEG has no transparency; give a --background");
        cli_run_free(&r);
        CHECK_EQ(count_entries(dir, NULL, 0), 2);
        REQUIRE(run_cli(ARGS("svg", svg_in, "--background", "white", "-o", svg_out), &r));
        CHECK_EQ(r.status, 0);
        cli_run_free(&r);
        px = NULL;
        REQUIRE(sr_read_jpeg(svg_out, &w, &h, &px, &err) == SR_OK);
        REQUIRE(w == 80 && h == 60);
        /* The rectangle's middle is its red; the corner, 16 pixels from
         * it (a whole block of 4:2:0 chroma), the white. */
        const uint8_t *mid = px + 4 * (32 * 80 + 48), *corner = px;
        CHECK(abs(mid[0] - 0xc0) <= 8 && abs(mid[1] - 0x30) <= 8 && abs(mid[2] - 0x20) <= 8);
        CHECK(corner[0] >= 247 && corner[1] >= 247 && corner[2] >= 247);
        free(px);
    }
#endif
}

/* ---- softrast thumbnail ------------------------------------------------- */

/* A fresh DIR holding a unit cube as box.stl; `out` names DIR/thumb.png. */
static bool thumb_dir(const char *name, char *dir, char *model, char *out)
{
    fresh_dir(name, dir, 1024);
    snprintf(model, 1100, "%s/box.stl", dir);
    snprintf(out, 1100, "%s/thumb.png", dir);
    return write_box_stl(model, 1.0f, 1.0f, 1.0f);
}

/* The freedesktop form `softrast thumbnail -s SIZE INPUT OUTPUT`: a
 * SIZE x SIZE PNG with the model framed in its middle, from a path or a
 * file:// URI (percent-decoded). */
SR_TEST(thumbnail_frames_the_model_in_a_square_png)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024], model[1100], out[1100], uri[1300];
    REQUIRE(thumb_dir("thumb ok", dir, model, out));
    /* The directory's space is "%20" in the URI. */
    const char *space = strchr(model, ' ');
    REQUIRE(space != NULL);
    snprintf(uri, sizeof uri, "file://%.*s%%20%s", (int)(space - model), model, space + 1);
    const char *const inputs[2] = { model, uri };
    for (int i = 0; i < 2; i++) {
        const char *label = i ? "file:// URI" : "path";
        remove(out);
        cli_run r;
        REQUIRE(run_cli(ARGS("thumbnail", "-s", "128", inputs[i], out), &r));
        if (r.status != 0 || r.err_len != 0 || r.out_len != 0) {
            FAILF("%s: status %d, stderr: %s", label, r.status, r.err);
        }
        cli_run_free(&r);
        int w = 0, h = 0;
        uint8_t *px = NULL;
        sr_io_error err;
        if (sr_read_png(out, NULL, &w, &h, &px, &err) != SR_OK) {
            FAILF("%s: %s", label, err.message);
            continue;
        }
        free(px);
        CHECK(w == 128 && h == 128);
        silhouette box;
        if (!read_silhouette(label, out, &box)) {
            FAILF("%s: nothing drawn", label);
            continue;
        }
        /* Centred: the silhouette's middle within 5% of the image's. */
        double cx = 0.5 * (box.x0 + box.x1), cy = 0.5 * (box.y0 + box.y1);
        if (fabs(cx - 63.5) > 6.4 || fabs(cy - 63.5) > 6.4) {
            FAILF("%s: silhouette x %d..%d y %d..%d is not centred", label, box.x0, box.x1,
                  box.y0, box.y1);
        }
        CHECK(box.x1 - box.x0 > 64 || box.y1 - box.y0 > 64);
    }
}

/* Bad sizes, missing files and an output that is the input: status 2,
 * one line, and the input left as it was. */
SR_TEST(thumbnail_refuses_bad_input_in_one_line)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024], model[1100], out[1100], missing[1100];
    REQUIRE(thumb_dir("thumb bad", dir, model, out));
    snprintf(missing, sizeof missing, "%s/missing.stl", dir);
    size_t before = 0;
    char *kept = read_whole(model, &before);
    REQUIRE(kept != NULL);
    const struct {
        const char *label;
        const char *const *args;
        const char *needle;
    } cases[] = {
        { "-s 0", ARGS("thumbnail", "-s", "0", model, out), "-s" },
        { "-s x", ARGS("thumbnail", "-s", "x", model, out), "-s" },
        { "-s without value", ARGS("thumbnail", model, out, "-s"), "-s" },
        { "no size", ARGS("thumbnail", model, out), "usage" },
        { "no output", ARGS("thumbnail", "-s", "64", model), "usage" },
        { "no files", ARGS("thumbnail"), "usage" },
        { "missing input", ARGS("thumbnail", "-s", "64", missing, out), "missing.stl" },
        { "remote URI", ARGS("thumbnail", "-s", "64", "file://host/x.stl", out), "URI" },
        { "bad escape", ARGS("thumbnail", "-s", "64", "file:///x%2.stl", out), "escape" },
        { "output is input", ARGS("thumbnail", "-s", "64", model, model),
          "OUTPUT: '" },
        { "JPEG output", ARGS("thumbnail", "-s", "64", model, "t.jpg"), "PNG" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        cli_run r;
        REQUIRE(run_cli(cases[i].args, &r));
        check_failure_output(cases[i].label, &r, 2, cases[i].needle);
        /* The thumbnail's arguments are named, not render's options (as
         * "-o:", which a path such as /work/wt-optdeps/ does not hold). */
        if (strstr(r.err, "-o:") || strstr(r.err, "-o ")) {
            FAILF("%s: the message names -o: %s", cases[i].label, r.err);
        }
        cli_run_free(&r);
    }
    CHECK_EQ(count_entries(dir, NULL, 0), 1);
    size_t after = 0;
    char *now = read_whole(model, &after);
    CHECK(now && after == before && memcmp(now, kept, before) == 0);
    free(now);
    free(kept);
}

/* Every option thumbnail's and explain's parsers take is in their --help
 * (and so in the manual page): --size, thumbnail's long form of -s, and
 * --output, explain's of -o, were taken but not shown. */
SR_TEST(thumbnail_and_explain_help_show_every_option_they_take)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024], model[1100], out[1100];
    REQUIRE(thumb_dir("thumb help", dir, model, out));
    const struct {
        const char *command, *taken[8];
    } commands[] = {
        { "thumbnail", { "-s", "--size", "--transparent", "-h", "--help" } },
        { "explain", { "-o", "--output", "--sheet", "--webp", "--grid", "--zoom" } },
    };
    for (size_t c = 0; c < sizeof commands / sizeof commands[0]; c++) {
        cli_run r;
        REQUIRE(run_cli(ARGS(commands[c].command, "--help"), &r));
        CHECK_EQ(r.status, 0);
        for (size_t i = 0; i < 8 && commands[c].taken[i]; i++) {
            char word[32], comma[32];
            snprintf(word, sizeof word, " %s ", commands[c].taken[i]);
            snprintf(comma, sizeof comma, " %s,", commands[c].taken[i]);
            if (!strstr(r.out, word) && !strstr(r.out, comma)) {
                FAILF("%s --help does not show %s", commands[c].command, commands[c].taken[i]);
            }
        }
        cli_run_free(&r);
    }
    cli_run r;
    REQUIRE(run_cli(ARGS("thumbnail", "--size", "32", model, out), &r));
    if (r.status != 0 || r.err_len != 0) {
        FAILF("--size 32: status %d, stderr: %s", r.status, r.err);
    }
    cli_run_free(&r);
}

static bool file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* Run args (from a directory of the test's) and expect `status`. */
static void expect_status(const char *const *args, int status)
{
    cli_run r;
    if (!run_cli(args, &r)) {
        return;
    }
    if (r.status != status) {
        FAILF("softrast %s ... %s: status %d, expected %d (stderr: %s)", args[0], args[1],
              r.status, status, r.err);
    }
    cli_run_free(&r);
}

/* "--" ends the options (POSIX, getopt): every later argument is an
 * operand, so files whose names start with '-' can be given.  Every
 * command took "--" for an unknown option. */
SR_TEST(end_of_options_makes_dash_names_operands)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    char dir[1024], svg_src[1100], cwd[4096];
    fresh_dir("end of options", dir, sizeof dir);
    REQUIRE(getcwd(cwd, sizeof cwd) != NULL);
    snprintf(svg_src, sizeof svg_src, "%s/data/svg/gradients.svg", sr_test_src_dir());
    size_t svg_len = 0;
    char *svg = read_whole(svg_src, &svg_len);
    REQUIRE(svg);
    REQUIRE(chdir(dir) == 0);
    const char *tri = ONE_TRIANGLE_OBJ;
    bool written = write_whole("-a.obj", tri, strlen(tri)) && write_whole("-b.obj", tri,
                                                                          strlen(tri)) &&
                   write_whole("-d.svg", svg, svg_len);
    free(svg);
    if (written) {
        expect_status(ARGS("render", "--size", "32x24", "-o", "r.png", "--", "-a.obj"), 0);
        CHECK(file_exists("r.png"));
        /* after "--" an option's name is an operand too: a second model */
        expect_status(ARGS("render", "-o", "x.png", "--", "-a.obj", "--size", "8x8"), 2);
        CHECK(!file_exists("x.png"));
        expect_status(ARGS("render", "--size", "16x16", "--output-dir", "batch", "--", "-a.obj",
                           "-b.obj"), 0);
        CHECK(file_exists("batch/-a.png") && file_exists("batch/-b.png"));
        if (svg_command_built()) {
            expect_status(ARGS("svg", "-o", "s.png", "--", "-d.svg"), 0);
            CHECK(file_exists("s.png"));
            expect_status(ARGS("svg", "--", "-d.svg"), 0);
            CHECK(file_exists("-d.png"));
        }
        expect_status(ARGS("thumbnail", "-s", "16", "--", "-a.obj", "-t.png"), 0);
        CHECK(file_exists("-t.png"));
        expect_status(ARGS("demo", "-o", "demo.png", "--", "lines"), 0);
        CHECK(file_exists("demo.png"));
        expect_status(ARGS("explain", "dda", "--sheet", "e.png", "--"), 0);
        CHECK(file_exists("e.png"));
        expect_status(ARGS("explain", "--", "dda", "--sheet", "f.png"), 2);
        CHECK(!file_exists("f.png"));
    }
    REQUIRE(chdir(cwd) == 0);
    CHECK(written);
#endif
}

/* A build without one of the optional libraries refuses what needs it in
 * one line naming the file and the library, exit status 2, and writes
 * nothing.  Skipped in a build that has them all (CI builds one without:
 * .ci/run). */
SR_TEST(a_missing_library_is_refused_in_one_line)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    char dir[1024], gltf[1100], svg[1100], obj[1100], png[1100], jpg[1100];
    fresh_dir("missing_library", dir, sizeof dir);
    snprintf(gltf, sizeof gltf, "%s/a.gltf", dir);
    snprintf(svg, sizeof svg, "%s/a.svg", dir);
    snprintf(obj, sizeof obj, "%s/a.obj", dir);
    snprintf(png, sizeof png, "%s/out.png", dir);
    snprintf(jpg, sizeof jpg, "%s/out.jpg", dir);
    static const char doc[] = "{\"asset\":{\"version\":\"2.0\"}}";
    static const char drawing[] = "<svg xmlns='http://www.w3.org/2000/svg' width='4' "
                                   "height='4'/>";
    REQUIRE(write_whole(gltf, doc, strlen(doc)) && write_whole(svg, drawing, strlen(drawing)) &&
            write_whole(obj, ONE_TRIANGLE_OBJ, strlen(ONE_TRIANGLE_OBJ)));
    const struct {
        bool built;
        const char *const *args;
        const char *want;
    } cases[] = {
        { sr_io_have_gltf(), ARGS("render", gltf, "-o", png),
          "/a.gltf: cannot read glTF (softrast was built without jansson" },
        { sr_io_have_gltf(), ARGS("render", gltf, "--animation", "0", "-o", png),
          "/a.gltf: --animation: cannot read glTF (softrast was built without jansson" },
        /* The classic look reads glTF with Assimp when the build has it. */
        { sr_io_have_gltf() || sr_io_have_assimp(),
          ARGS("render", gltf, "--shading", "unlit", "-o", png),
          "/a.gltf: cannot read glTF (softrast was built without jansson" },
        { sr_io_have_gltf(), ARGS("info", gltf),
          "/a.gltf: cannot read glTF (softrast was built without jansson" },
        { sr_io_have_svg(), ARGS("svg", svg, "-o", png),
          "/a.svg: cannot read SVG drawings (softrast was built without expat" },
        { sr_io_have_jpeg(), ARGS("render", obj, "-o", jpg),
          "/out.jpg: cannot write JPEG (softrast was built without libjpeg" },
    };
    int run = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        if (cases[i].built) {
            continue;
        }
        cli_run r;
        REQUIRE(run_cli(cases[i].args, &r));
        if (!(r.status == 2 && is_one_line(r.err, r.err_len) && strstr(r.err, cases[i].want))) {
            FAILF("case %zu: status %d, stderr \"%s\", want one line with \"%s\"", i, r.status,
                  r.err, cases[i].want);
        }
        cli_run_free(&r);
        run++;
    }
    CHECK(!file_exists(png) && !file_exists(jpg));
    if (run == 0) {
        SKIP("this softrast was built with every optional library these cases need");
    }
#endif
}

/* An option's value is the next argument whatever it looks like (getopt):
 * "-o --" names the output "--", so "-o -- -a.obj" is not an end of the
 * options.  An output "--" (a mistaken end of options) or "-" (standard
 * output, where no image goes) is refused by every command in one line;
 * other names starting with '-' are written.  A batch and the viewer
 * passed render options on without their values, so "--" or an option's
 * name as a value was read differently there than by the render parser. */
SR_TEST(option_values_that_look_like_options_are_values)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    char dir[1024], cwd[4096];
    fresh_dir("dash values", dir, sizeof dir);
    REQUIRE(getcwd(cwd, sizeof cwd) != NULL);
    REQUIRE(chdir(dir) == 0);
    const char *tri = ONE_TRIANGLE_OBJ;
    const char *uv = "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";
    static const uint8_t texel[16] = { 255, 0, 0, 255, 255, 0, 0, 255, 255, 0, 0, 255,
                                       255, 0, 0, 255 };
    sr_io_error err;
    bool written = write_whole("-a.obj", tri, strlen(tri)) && write_whole("a.obj", tri,
                                                                          strlen(tri)) &&
                   write_whole("uv.obj", uv, strlen(uv)) && write_whole("-uv.obj", uv, strlen(uv));
    if (written) {
        static const refusal_case refused[] = {
            { "-o --", { "render", "-o", "--", "-a.obj" }, "-o: '--' names no file here" },
            { "-o -- model", { "render", "--size", "8x8", "-o", "--", "a.obj" },
              "-o: '--' names no file" },
            { "--output=-", { "render", "--output=-", "a.obj" },
              "--output: '-' names no file here" },
            { "batch -o -", { "render", "--size", "8x8", "-o", "-", "--", "a.obj", "-a.obj" },
              "-o: '-' names no file here" },
            { "--output-dir -", { "render", "--output-dir", "-", "--", "a.obj", "-a.obj" },
              "--output-dir: '-' names no file" },
            { "--log --", { "render", "--log", "--", "--", "a.obj", "-a.obj" },
              "--log: '--' names no file" },
            { "svg -o --", { "svg", "-o", "--", "x.svg" }, "-o: '--' names no file here" },
            { "demo -o -", { "demo", "lines", "-o", "-" }, "-o: '-' names no file here" },
            { "thumbnail -", { "thumbnail", "-s", "8", "--", "a.obj", "-" },
              "OUTPUT: '-' names no file" },
            { "explain --sheet --", { "explain", "dda", "--sheet", "--" },
              "--sheet: '--' names no file here" },
            { "explain -o -", { "explain", "dda", "-o", "-" }, "-o: '-' names no file here" },
            { "view --screenshot -", { "view", "--screenshot", "-", "a.obj" },
              "--screenshot: '-' names no file" },
        };
        expect_refusals(refused, sizeof refused / sizeof refused[0], NULL, 0);
        CHECK(!file_exists("--") && !file_exists("-") && !file_exists("softrast.png"));
        /* other names starting with '-' are the option's value, in one
         * render and where a batch or the viewer pass them on */
        expect_status(ARGS("render", "--size", "8x8", "-o", "-x.png", "a.obj"), 0);
        CHECK(file_exists("-x.png"));
        expect_status(ARGS("render", "--size", "8x8", "-o", "--skip-existing", "a.obj"), 0);
        CHECK(file_exists("--skip-existing"));
        /* a texture named like batch options: one render, and a batch */
        REQUIRE(sr_write_png("--output-dir", 2, 2, texel, 8, NULL, &err) == SR_OK);
        REQUIRE(sr_write_png("--log", 2, 2, texel, 8, NULL, &err) == SR_OK);
        expect_status(ARGS("render", "--size", "8x8", "--texture", "--output-dir", "-o", "t.png",
                           "uv.obj"), 0);
        CHECK(file_exists("t.png") && !file_exists("uv.png"));
        clean_dir("b");
        expect_status(ARGS("render", "--size", "8x8", "--output-dir", "b", "--texture", "--log",
                           "--", "uv.obj", "-uv.obj"), 0);
        CHECK(file_exists("b/uv.png") && file_exists("b/-uv.png"));
    }
    REQUIRE(chdir(cwd) == 0);
    CHECK(written);
#endif
}

/* "--name=value" is "--name value" in every command, as getopt_long
 * reads it; render, its batch options and view took it, while svg, demo,
 * thumbnail and explain called it an unknown option (explain: "needs a
 * value").  A flag given a value is refused by name. */
SR_TEST(every_command_takes_long_options_with_an_equals_sign)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    char dir[1024], cwd[4096], svg_src[1100];
    fresh_dir("equals", dir, sizeof dir);
    snprintf(svg_src, sizeof svg_src, "%s/data/svg/gradients.svg", sr_test_src_dir());
    REQUIRE(getcwd(cwd, sizeof cwd) != NULL);
    REQUIRE(chdir(dir) == 0);
    const char *tri = ONE_TRIANGLE_OBJ;
    bool written = write_whole("a.obj", tri, strlen(tri));
    if (written) {
        expect_status(ARGS("render", "a.obj", "--size=16x8", "--output=r.png"), 0);
        CHECK(file_exists("r.png"));
        if (svg_command_built()) {
            expect_status(ARGS("svg", svg_src, "--size=16x16", "--output=s.png",
                               "--background=white"), 0);
            CHECK(file_exists("s.png"));
        }
        expect_status(ARGS("demo", "lines", "--output=d.png", "--scale=1"), 0);
        CHECK(file_exists("d.png"));
        expect_status(ARGS("thumbnail", "--size=16", "a.obj", "t.png"), 0);
        CHECK(file_exists("t.png"));
        expect_status(ARGS("explain", "dda", "--sheet=e.png", "--line=1.5,1.5,6.5,3.5"), 0);
        CHECK(file_exists("e.png"));
        static const refusal_case refused[] = {
            { "--transparent=yes", { "thumbnail", "--transparent=yes", "a.obj", "u.png" },
              "--transparent: takes no value" },
            { "demo --help=1", { "demo", "lines", "--help=1" }, "--help: takes no value" },
            { "svg --help=1", { "svg", "--help=1" }, "--help: takes no value" },
            { "--sheet=", { "explain", "dda", "--sheet=" }, "--sheet: the file name is empty" },
            { "explain -o ''", { "explain", "dda", "-o", "" }, "-o: the file name is empty" },
            { "demo -o ''", { "demo", "lines", "-o", "" }, "-o: the file name is empty" },
            { "svg --output=", { "svg", "x.svg", "--output=" },
              "--output: the file name is empty" },
            { "thumbnail ''", { "thumbnail", "-s", "8", "a.obj", "" },
              "OUTPUT: the file name is empty" },
            { "--screenshot=", { "view", "--screenshot=", "a.obj" },
              "--screenshot: the file name is empty" },
            { "demo --output=-", { "demo", "lines", "--output=-" },
              "--output: '-' names no file here" },
        };
        expect_refusals(refused, sizeof refused / sizeof refused[0], NULL, 0);
        CHECK(!file_exists("u.png"));
    }
    REQUIRE(chdir(cwd) == 0);
    CHECK(written);
#endif
}

/* A --scale that makes a demo's image larger than a framebuffer is the
 * user's to change: one line naming --scale, exit status 2 (it was the
 * library's "sr_framebuffer_desc.width 8252 exceeds the maximum 8192",
 * exit status 1). */
SR_TEST(demo_scale_beyond_a_framebuffer_is_refused_by_name)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    static const refusal_case refused[] = {
        { "demo aa --scale 32", { "demo", "aa", "--scale", "32", "-o", "never.png" },
          "demo aa: --scale 32 makes a 8252x3588 image, over 8192 a side: give --scale 31 or "
          "less" },
        { "demo zfight --scale 14", { "demo", "zfight", "--scale", "14", "-o", "never.png" },
          "demo zfight: --scale 14 makes a " },
    };
    expect_refusals(refused, sizeof refused / sizeof refused[0], NULL, 0);
    CHECK(!file_exists("never.png"));
#endif
}

/* The sanitizers' shadow memory and an emulator need more address space
 * than an address space limit leaves. */
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define CLI_NO_AS_LIMIT 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__) || defined(SR_TEST_EMULATED)
#define CLI_NO_AS_LIMIT 1
#endif

/* Frames larger than the memory limit are refused in one line before
 * anything is allocated (exit status 2) by every command that takes a
 * size; SR_MEMORY_LIMIT sets the limit, so 8.5 GiB of 8192 x 8192 x 16
 * samples is refused here without allocating it.  Where an allocation
 * fails all the same (under a 1.5 GiB address space limit), the command
 * says "out of memory" in one line, exit status 1. */
SR_TEST(frames_beyond_the_memory_limit_are_refused_before_allocating)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    char dir[1024], a[1100], b[1100], svg[1100], svg2[1100];
    fresh_dir("memory limit", dir, sizeof dir);
    snprintf(a, sizeof a, "%s/a.obj", dir);
    snprintf(b, sizeof b, "%s/b.obj", dir);
    snprintf(svg, sizeof svg, "%s/d.svg", dir);
    snprintf(svg2, sizeof svg2, "%s/e.svg", dir);
    const char *tri = ONE_TRIANGLE_OBJ, *doc = "<svg width='10' height='10'/>";
    REQUIRE(write_whole(a, tri, strlen(tri)) && write_whole(b, tri, strlen(tri)) &&
            write_whole(svg, doc, strlen(doc)) && write_whole(svg2, doc, strlen(doc)));
    REQUIRE(setenv("SR_MEMORY_LIMIT", "1G", 1) == 0);
    expect_render_failure("msaa16 at 8192", ARGS(a, "--size", "8192x8192", "--aa", "msaa16"), 2,
                          "render: --size 8192x8192 with --aa msaa16 needs about 8.5 GiB of "
                          "frame memory, more than SR_MEMORY_LIMIT=1G allows: give a smaller "
                          "--size or --aa");
    /* SSAA's samples beyond a framebuffer's side: before the model is read */
    expect_render_failure("ssaa3 at 4096", ARGS("--size", "4096x4096", "--aa", "ssaa3"), 2,
                          "--aa ssaa3 at --size 4096x4096 draws 12288x12288 samples, more than "
                          "8192 a side");
    static const struct {
        const char *limit;
        const char *args[12];
        const char *needle;
    } refused[] = {
        { "1G", { "render", "--size", "4096x4096", "--output-dir", "OUT", "--", "A", "B" },
          "(two frames at once) and the images being written needs about 1.4 GiB" },
        /* a batch's frames fit, not with the writer's copies of its images */
        { "128M", { "render", "--size", "2048x2048", "--aa", "none", "--output-dir", "OUT", "A",
                    "B" },
          "render: --size 2048x2048 with --aa none (two frames at once) and the images being "
          "written needs about 144 MiB" },
        /* the frames fit, not with the sheet of them all */
        { "100M", { "render", "--size", "2048x2048", "--aa", "none", "--sheet", "OUT/sheet.png",
                    "A", "B" },
          "(two frames at once) and a 4096x2072 --sheet needs about 128 MiB of frame memory, "
          "more than SR_MEMORY_LIMIT=100M allows: give a smaller --size or fewer models\n" },
        { "100M", { "render", "--size", "2048x2048", "--aa", "none", "--background", "transparent",
                    "--sheet", "OUT/sheet.png", "A", "B" },
          "and a 4096x2072 --sheet needs about 161 MiB of frame memory, more than "
          "SR_MEMORY_LIMIT=100M allows: give a smaller --size or fewer models or an opaque "
          "--background\n" },
        { "256M", { "render", "--size", "2048x2048", "--aa", "ssaa4", "A", "-o", "OUT/r.png" },
          "render: --size 2048x2048 with --aa ssaa4 needs about 800 MiB" },
        { "256M", { "thumbnail", "-s", "4096", "A", "OUT/t.png" },
          "thumbnail: -s 4096 needs about 640 MiB of frame memory, more than SR_MEMORY_LIMIT=256M "
          "allows: give a smaller -s" },
        { "256M", { "svg", "--size", "8192x8192", "S", "-o", "OUT/s.png" },
          "svg: --size 8192x8192 needs about 512 MiB" },
        /* one drawing fits, not a batch's drawings and the writers' copies */
        { "64M", { "svg", "--size", "2048x2048", "--threads", "4", "--output-dir", "OUT", "S",
                   "T" },
          "svg: --size 2048x2048 with --threads 4 (2 drawings at once) needs about 80 MiB of "
          "frame memory, more than SR_MEMORY_LIMIT=64M allows: give a smaller --size or "
          "--threads" },
        /* --animate: libwebp's encoder instead of the writer's images, for one
         * model as for a batch (150M passed the writer's 144 MiB) */
        { "150M", { "render", "--size", "2048x2048", "--aa", "none", "--animate", "a.webp",
                    "--output-dir", "OUT", "A" },
          "render: --size 2048x2048 with --aa none (two frames at once) and the animation being "
          "encoded needs about 160 MiB" },
        { "150M", { "render", "--size", "2048x2048", "--aa", "none", "--animate", "{rel}.webp",
                    "--output-dir", "OUT", "A", "B" },
          "(two frames at once) and the animation being encoded needs about 160 MiB" },
        { "1G", { "view", "--size", "8192x8192", "--aa", "msaa16", "A" },
          "view: --size 8192x8192 with --aa msaa16 (two frames at once) needs about 17 GiB" },
    };
    for (size_t i = 0; i < sizeof refused / sizeof refused[0]; i++) {
        REQUIRE(setenv("SR_MEMORY_LIMIT", refused[i].limit, 1) == 0);
        const char *args[12] = { 0 };
        for (int k = 0; refused[i].args[k]; k++) {
            const char *w = refused[i].args[k];
            args[k] = strcmp(w, "A") == 0 ? a : strcmp(w, "B") == 0 ? b : strcmp(w, "S") == 0
                      ? svg : strcmp(w, "T") == 0 ? svg2 : w;
            if (strncmp(w, "OUT", 3) == 0) {
                static char paths[2][1200];
                snprintf(paths[k & 1], sizeof paths[0], "%s%s", dir, w + 3);
                args[k] = paths[k & 1];
            }
        }
        cli_run r;
        if (!run_cli(args, &r)) {
            continue;
        }
        if ((strcmp(args[0], "view") != 0 || !strstr(r.err, "built without SDL2")) &&
            !strstr(r.err, "built without libwebp")) {
            check_failure_output(refused[i].needle, &r, 2, refused[i].needle);
        }
        cli_run_free(&r);
    }
    CHECK_EQ(count_entries(dir, NULL, 0), 4);
    /* within the limit: drawn */
    REQUIRE(setenv("SR_MEMORY_LIMIT", "64M", 1) == 0);
    char out[1100];
    snprintf(out, sizeof out, "%s/small.png", dir);
    expect_status(ARGS("render", a, "--size", "64x48", "-o", out), 0);
    CHECK(file_exists(out));
    REQUIRE(setenv("SR_MEMORY_LIMIT", "lots", 1) == 0);
    expect_render_failure("bad limit", ARGS(a), 2,
                          "SR_MEMORY_LIMIT: expected a size in bytes such as 512M or 8G (got "
                          "'lots')");
#if !defined(CLI_NO_AS_LIMIT)
    REQUIRE(setenv("SR_MEMORY_LIMIT", "1T", 1) == 0);
    struct rlimit old;
    REQUIRE(getrlimit(RLIMIT_AS, &old) == 0);
    struct rlimit lim = old;
    lim.rlim_cur = (rlim_t)3 << 29;
    if (old.rlim_cur == RLIM_INFINITY || old.rlim_cur > lim.rlim_cur) {
        REQUIRE(setrlimit(RLIMIT_AS, &lim) == 0);
        expect_render_failure("out of memory", ARGS(a, "--size", "8192x8192", "--aa", "msaa16"),
                              1, "render: sr_make_framebuffer: out of memory for 8192x8192");
        setrlimit(RLIMIT_AS, &old);
    }
#endif
    unsetenv("SR_MEMORY_LIMIT");
#endif
}

/* Occurrences of `needle` in `s`. */
static int count_in(const char *s, const char *needle)
{
    int n = 0;
    for (const char *p = strstr(s, needle); p; p = strstr(p + 1, needle)) {
        n++;
    }
    return n;
}

/* An option the others make useless (pbr's with a classic --shading,
 * --filter without SSAA) is drawn without, as before, but says so in one
 * warning line, once a command (not once a batch input), status 0. */
SR_TEST(options_without_effect_warn_once)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    char dir[1024], a[1100], b[1100], out[1100];
    fresh_dir("no effect", dir, sizeof dir);
    snprintf(a, sizeof a, "%s/a.obj", dir);
    snprintf(b, sizeof b, "%s/b.obj", dir);
    snprintf(out, sizeof out, "%s/out.png", dir);
    const char *tri = ONE_TRIANGLE_OBJ;
    REQUIRE(write_whole(a, tri, strlen(tri)) && write_whole(b, tri, strlen(tri)));
    const struct {
        const char *opt, *value, *shading;
    } pbr_only[] = {
        { "--ground", NULL, "flat" }, { "--tonemap", "aces", "phong" },
        { "--exposure", "1", "gouraud" }, { "--environment", "hemisphere", "unlit" },
        { "--environment-intensity", "2", "normals" }, { "--shadows", "on", "depth" },
        { "--lights", "default", "phong" },
    };
    for (size_t i = 0; i < sizeof pbr_only / sizeof pbr_only[0]; i++) {
        const char *args[] = { "render", a, "-o", out, "--size", "32x24", "--shading",
                               pbr_only[i].shading, pbr_only[i].opt, pbr_only[i].value, NULL };
        char want[160];
        snprintf(want, sizeof want, "softrast: warning: %s has no effect with --shading %s "
                 "(it is for pbr)\n", pbr_only[i].opt, pbr_only[i].shading);
        cli_run r;
        REQUIRE(run_cli(args, &r));
        CHECK_EQ(r.status, 0);
        if (strcmp(r.err, want) != 0) {
            FAILF("%s: stderr \"%s\", expected \"%s\"", pbr_only[i].opt, r.err, want);
        }
        cli_run_free(&r);
        /* under pbr (the default) it acts: no warning */
        const char *pbr_args[] = { "render", a, "-o", out, "--size", "32x24", pbr_only[i].opt,
                                   pbr_only[i].value, NULL };
        REQUIRE(run_cli(pbr_args, &r));
        CHECK_EQ(r.status, 0);
        CHECK_EQ(r.err_len, 0);
        cli_run_free(&r);
    }
    cli_run r;
    REQUIRE(run_cli(ARGS("render", a, "-o", out, "--size", "32x24", "--filter", "tent"), &r));
    CHECK_EQ(r.status, 0);
    CHECK(is_one_line(r.err, r.err_len) && strstr(r.err, "warning: --filter has no effect"));
    cli_run_free(&r);
    REQUIRE(run_cli(ARGS("render", a, "-o", out, "--size", "32x24", "--filter", "tent", "--aa",
                         "ssaa2"), &r));
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.err_len, 0);
    cli_run_free(&r);
    /* a batch of two: each warning once */
    REQUIRE(run_cli(ARGS("render", a, b, "--output-dir", dir, "--size", "32x24", "--shading",
                         "flat", "--ground", "--filter", "mitchell"), &r));
    CHECK_EQ(r.status, 0);
    CHECK_EQ(count_in(r.err, "warning: --ground has no effect"), 1);
    CHECK_EQ(count_in(r.err, "warning: --filter has no effect"), 1);
    CHECK_EQ(count_in(r.err, "\n"), 2);
    cli_run_free(&r);
#endif
}

/* explain's messages give the value's form as its --help writes it and the
 * limit it applies: --grid said "1 to 8192" (the framebuffer's) for a
 * limit of 256, --circle "X,Y,Z" for CX,CY,R. */
SR_TEST(explain_messages_give_the_helps_forms_and_limits)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024];
    fresh_dir("explain msgs", dir, sizeof dir);
    const struct {
        const char *const *args;
        const char *needle;
    } cases[] = {
        { ARGS("explain", "triangle", "--grid", "0x0", "-o", dir), "WxH with each from 1 to 256" },
        { ARGS("explain", "triangle", "--grid", "300x4", "-o", dir), "from 1 to 256" },
        { ARGS("explain", "circle", "--circle", "1,2", "-o", dir), "numbers CX,CY,R " },
        { ARGS("explain", "perspective", "--w", "1,2", "-o", dir), "numbers W0,W1,W2, each in 0.015625..1024" },
        { ARGS("explain", "fillpoly", "--intensity", "1", "-o", dir), "numbers IA,IB,IC, each in 0..1" },
        { ARGS("explain", "clip4d", "--clip-triangle", "1,2", "-o", dir), "X,Y,Z,W,X,Y,Z,W" },
        { ARGS("explain", "clip", "--window", "1,2", "-o", dir), "XMIN,YMIN,XMAX,YMAX" },
        { ARGS("explain", "aaline", "--width", "0", "-o", dir), "--width: expected a number from 0.0625 to 64 (got '0')" },
        { ARGS("explain", "area", "--cap", "flat", "-o", dir), "--cap: expected one of butt|square|round (got 'flat')" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        cli_run r;
        REQUIRE(run_cli(cases[i].args, &r));
        check_failure_output(cases[i].args[2], &r, 2, cases[i].needle);
        cli_run_free(&r);
    }
    CHECK_EQ(count_entries(dir, NULL, 0), 0);
}

/* --transparent: an RGBA PNG whose corners are fully transparent, whose
 * middle is the opaque model, whose edges are partly covered, and whose
 * colors are those of the opaque thumbnail where the model covers all. */
SR_TEST(thumbnail_transparent_keeps_the_model_and_drops_the_background)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#endif
    char dir[1024], model[1100], out[1100], opaque[1200];
    REQUIRE(thumb_dir("thumb alpha", dir, model, out));
    snprintf(opaque, sizeof opaque, "%s/opaque.png", dir);
    cli_run r;
    REQUIRE(run_cli(ARGS("thumbnail", "-s", "64", "--transparent", model, out), &r));
    CHECK_EQ(r.status, 0);
    cli_run_free(&r);
    REQUIRE(run_cli(ARGS("thumbnail", "-s", "64", model, opaque), &r));
    CHECK_EQ(r.status, 0);
    cli_run_free(&r);
    int w, h, ow, oh;
    uint8_t *px = NULL, *opx = NULL;
    sr_io_error err;
    size_t n = 0;
    char *bytes = read_whole(out, &n);
    CHECK(bytes && n > 26 && bytes[25] == 6);   /* IHDR color type 6: RGBA */
    free(bytes);
    REQUIRE(sr_read_png(out, NULL, &w, &h, &px, &err) == SR_OK);
    REQUIRE(sr_read_png(opaque, NULL, &ow, &oh, &opx, &err) == SR_OK);
    CHECK(w == 64 && h == 64 && ow == 64 && oh == 64);
    size_t clear = 0, solid = 0, edge = 0, same = 0;
    for (size_t i = 0; i < 64 * 64; i++) {
        uint8_t a = px[4 * i + 3];
        clear += a == 0;
        edge += a > 0 && a < 255;
        if (a == 255) {
            solid++;
            same += memcmp(px + 4 * i, opx + 4 * i, 3) == 0;
        }
    }
    CHECK_EQ(px[3], 0);
    CHECK_EQ(px[4 * (32 * 64 + 32) + 3], 255);
    CHECK(clear > 64 * 64 / 10 && solid > 64 * 64 / 10 && edge > 0);
    CHECK_EQ(same, solid);
    free(px);
    free(opx);
}

/* The file managers' entry: [Thumbnailer Entry] with key=value lines, an
 * Exec that runs `softrast thumbnail -s %s %i %o`, and the MIME types of
 * STL, OBJ, PLY, glTF and GLB. */
SR_TEST(thumbnailer_file_runs_the_thumbnail_command)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/../share/thumbnailers/softrast.thumbnailer", sr_test_src_dir());
    size_t n = 0;
    char *text = read_whole(path, &n);
    REQUIRE(text != NULL);
    bool group = false, exec = false, tryexec = false, mime = false;
    int line_no = 0;
    for (char *line = strtok(text, "\n"); line; line = strtok(NULL, "\n")) {
        line_no++;
        if (line_no == 1) {
            group = strcmp(line, "[Thumbnailer Entry]") == 0;
            continue;
        }
        char *eq = strchr(line, '=');
        if (line[0] == '#') {
            continue;
        }
        if (!eq || eq == line) {
            FAILF("line %d is not key=value: %s", line_no, line);
            continue;
        }
        *eq = '\0';
        const char *value = eq + 1;
        if (strcmp(line, "Exec") == 0) {
            exec = strcmp(value, "softrast thumbnail -s %s %i %o") == 0;
        } else if (strcmp(line, "TryExec") == 0) {
            tryexec = strcmp(value, "softrast") == 0;
        } else if (strcmp(line, "MimeType") == 0) {
            mime = strstr(value, "model/stl;") && strstr(value, "model/obj;") &&
                   strstr(value, "ply;") && strstr(value, "model/gltf+json;") &&
                   strstr(value, "model/gltf-binary;");
        }
    }
    free(text);
    CHECK(group);
    CHECK(exec);
    CHECK(tryexec);
    CHECK(mime);
}

/* File managers run thumbnailers in sandboxes without a display: the tool
 * links no X11, EGL or GL library. */
SR_TEST(softrast_links_no_display_library)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    if (access("/usr/bin/ldd", X_OK) != 0) {
        SKIP("no ldd on this system");
    }
#ifdef SR_TEST_EMULATED
    SKIP("the host's ldd cannot load the target's program");
#endif
    FILE *p = popen("/usr/bin/ldd '" SR_CLI_PATH "'", "r");
    REQUIRE(p != NULL);
    char line[1024];
    int libs = 0;
    while (fgets(line, sizeof line, p)) {
        libs++;
        const char *const banned[] = { "libX11", "libEGL", "libGL", "libOSMesa", "libSDL2" };
        for (size_t i = 0; i < sizeof banned / sizeof banned[0]; i++) {
            if (strstr(line, banned[i])) {
                FAILF("softrast links %s: %s", banned[i], line);
            }
        }
    }
    CHECK_EQ(pclose(p), 0);
    CHECK(libs > 1);
#endif
}

/* ---- glTF scenes under the physically based look ------------------------ */

#ifdef SR_CLI_PATH
/* A .gltf with two unit quads facing +z: mesh 0 at z = 0 (x -1..0),
 * mesh 1 at z = 0.5 (x -0.5..0.5), materials and nodes as given
 * (`rest`: ",\"materials\":[..],\"nodes\":[..],..." up to the scenes). */
static bool write_two_quads(const char *path, const char *rest)
{
    float pos[24] = { -1, -1, 0, 0, -1, 0, 0, 1, 0, -1, 1, 0,
                      -0.5f, -1, 0.5f, 0.5f, -1, 0.5f, 0.5f, 1, 0.5f, -0.5f, 1, 0.5f };
    uint16_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    uint8_t bin[108];
    le_copy(bin, pos, 24, 4); /* glTF buffers are little endian on any host */
    le_copy(bin + 96, idx, 6, 2);
    char b64[160], json[4096];
    gltf_base64(bin, sizeof bin, b64);
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":108,"
             "\"uri\":\"data:application/octet-stream;base64,%s\"}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteLength\":48},"
             "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":48},"
             "{\"buffer\":0,\"byteOffset\":96,\"byteLength\":12}],"
             "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,"
             "\"type\":\"VEC3\",\"min\":[-1,-1,0],\"max\":[0,1,0]},"
             "{\"bufferView\":1,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
             "\"min\":[-0.5,-1,0.5],\"max\":[0.5,1,0.5]},"
             "{\"bufferView\":2,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":2,"
             "\"material\":0}]},{\"primitives\":[{\"attributes\":{\"POSITION\":1},"
             "\"indices\":2,\"material\":1}]}]%s}",
             b64, rest);
    return write_whole(path, json, strlen(json));
}

static uint8_t *render_pixels(const char *const *args, const char *out, int *w, int *h)
{
    cli_run r;
    if (!run_cli(args, &r)) {
        return NULL;
    }
    bool ok = r.status == 0;
    if (!ok) {
        FAILF("render: %s", r.err);
    }
    cli_run_free(&r);
    uint8_t *px = NULL;
    sr_io_error err;
    if (!ok || sr_read_png(out, NULL, w, h, &px, &err) != SR_OK) {
        return NULL;
    }
    return px;
}
#endif

/* Each primitive with its own material: a red and a blue quad side by
 * side; a node mirrored by a negative scale is still drawn (its winding
 * flips back), and the file's camera is --camera-index 0. */
SR_TEST(gltf_scene_draws_each_primitive_with_its_material)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson (glTF)");
    }
    char dir[1024], model[1100], out[1100];
    fresh_dir("gltf_scene", dir, sizeof dir);
    snprintf(model, sizeof model, "%s/two.gltf", dir);
    snprintf(out, sizeof out, "%s/two.png", dir);
    /* Mesh 1 moved right by 1.5 (x 1..2) and mirrored in x (x -2..-1)
     * beside mesh 0: three quads, left to right blue (mirrored), red, blue. */
    REQUIRE(write_two_quads(model,
        ",\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.8,0.02,0.02,1],"
        "\"metallicFactor\":0}},{\"pbrMetallicRoughness\":{\"baseColorFactor\":"
        "[0.02,0.02,0.8,1],\"metallicFactor\":0}}],"
        "\"nodes\":[{\"mesh\":0},{\"mesh\":1,\"translation\":[1.5,0,-0.5]},"
        "{\"mesh\":1,\"translation\":[-1.5,0,-0.5],\"scale\":[-1,1,1]},"
        "{\"camera\":0,\"translation\":[0,0,6]}],"
        "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.6,\"znear\":0.1}}],"
        "\"scenes\":[{\"nodes\":[0,1,2,3]}],\"scene\":0"));
    int w, h;
    uint8_t *px = render_pixels(ARGS("render", model, "--camera-index", "0", "--size", "120x60",
                                     "--aa", "none", "-o", out), out, &w, &h);
    REQUIRE(px);
    /* At the camera's yfov 0.6 from z = 6, x = +-1.5 lands about 23 px
     * either side of the centre. */
    const uint8_t *left = px + 4 * ((size_t)(h / 2) * w + w / 2 - 23);
    const uint8_t *mid = px + 4 * ((size_t)(h / 2) * w + w / 2 - 4);
    const uint8_t *right = px + 4 * ((size_t)(h / 2) * w + w / 2 + 23);
    CHECK(left[2] > 2 * left[0] && left[2] > 60);     /* the mirrored quad, drawn */
    CHECK(mid[0] > 2 * mid[2] && mid[0] > 60);        /* red */
    CHECK(right[2] > 2 * right[0] && right[2] > 60);  /* blue */
    free(px);
    /* The classic models look through the same camera, each primitive in
     * its base color. */
    const char *classic[] = { "phong", "gouraud", "flat" };
    for (int k = 0; k < 3; k++) {
        px = render_pixels(ARGS("render", model, "--camera-index", "0", "--shading", classic[k],
                                "--size", "120x60", "--aa", "none", "-o", out), out, &w, &h);
        REQUIRE(px);
        left = px + 4 * ((size_t)(h / 2) * w + w / 2 - 23);
        mid = px + 4 * ((size_t)(h / 2) * w + w / 2 - 4);
        right = px + 4 * ((size_t)(h / 2) * w + w / 2 + 23);
        const uint8_t *above = px + 4 * ((size_t)4 * w + w / 2 - 4);   /* background */
        CHECK(left[2] > 2 * left[0] && left[2] > 60);
        CHECK(mid[0] > 2 * mid[2] && mid[0] > 60);
        CHECK(right[2] > 2 * right[0] && right[2] > 60);
        CHECK(above[0] == 0x1d && above[1] == 0x22 && above[2] == 0x30);
        free(px);
    }
    cli_run r;
    REQUIRE(run_cli(ARGS("render", model, "--camera-index", "1", "--size", "32x16", "-o", out),
                    &r));
    CHECK_EQ(r.status, 2);
    CHECK_STR_CONTAINS(r.err, "--camera-index 1: the model has 1 camera");
    cli_run_free(&r);
    /* A camera its node scales to nothing has no frame: the message says
     * which of the camera's values (sr_scene_camera_matrices'). */
    REQUIRE(write_two_quads(model,
        ",\"materials\":[{},{}],\"nodes\":[{\"mesh\":0},{\"camera\":0,\"scale\":[0,0,0]}],"
        "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.6,\"znear\":0.1}}],"
        "\"scenes\":[{\"nodes\":[0,1]}],\"scene\":0"));
    REQUIRE(run_cli(ARGS("render", model, "--camera-index", "0", "--size", "32x16", "-o", out),
                    &r));
    CHECK(r.status != 0);
    CHECK_STR_CONTAINS(r.err, "--camera-index 0: sr_scene_camera_matrices: camera->world is "
                              "degenerate");
    cli_run_free(&r);
#endif
}

#ifdef SR_CLI_PATH
/* A square [-1, 1]^2 facing +z with texture coordinates over it, its
 * material `mtl` (the MTL's text), rendered head on at 64x64 with one
 * light coming from +x and no ambient; the centre pixel into px[0..2].
 * `ramp` (may be NULL) names a 32x32 image in dir: a height ramp up to
 * the right ("up_right"), up to the left ("up_left"), or one normal
 * tilted to the right ("tilted").  False on failure. */
static bool render_obj_square(const char *dir, const char *mtl, const char *ramp, int px[3])
{
    char obj[1100], mtl_path[1100], img[1100], out[1100];
    snprintf(obj, sizeof obj, "%s/square.obj", dir);
    snprintf(mtl_path, sizeof mtl_path, "%s/square.mtl", dir);
    snprintf(out, sizeof out, "%s/square.png", dir);
    static const char square[] =
        "mtllib square.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nusemtl m\nf 1/1/1 2/2/1 3/3/1 4/4/1\n";
    if (!write_whole(obj, square, strlen(square)) || !write_whole(mtl_path, mtl, strlen(mtl))) {
        return false;
    }
    if (ramp) {
        uint8_t texels[32 * 32 * 4];
        for (int y = 0; y < 32; y++) {
            for (int x = 0; x < 32; x++) {
                uint8_t *t = &texels[4 * (y * 32 + x)];
                uint8_t h = (uint8_t)(strcmp(ramp, "up_right") == 0 ? 8 * x : 248 - 8 * x);
                bool tilted = strcmp(ramp, "tilted") == 0;
                t[0] = tilted ? 218 : h;
                t[1] = tilted ? 128 : h;
                t[2] = tilted ? 218 : h;
                t[3] = 255;
            }
        }
        sr_io_error err;
        snprintf(img, sizeof img, "%s/%s.png", dir, ramp);
        if (sr_write_png(img, 32, 32, texels, 32 * 4, NULL, &err) != SR_OK) {
            return false;
        }
    }
    int w, h;
    uint8_t *pixels = render_pixels(ARGS("render", obj, "--camera", "eye=0,0,4,target=0,0,0",
                                         "--light", "dir=-1,0,-0.4", "--environment", "none",
                                         "--size", "64x64", "--aa", "none", "-o", out),
                                    out, &w, &h);
    if (!pixels) {
        return false;
    }
    for (int k = 0; k < 3; k++) {
        px[k] = pixels[4 * (32 * w + 32) + k];
    }
    free(pixels);
    return true;
}
#endif

/* An OBJ material's bump map is the physically based look's normal map:
 * a height map rising to the right faces its slopes away from a light on
 * the right, one rising to the left toward it; a map_Bump image that is a
 * normal map (Blender writes them there) and a `norm` map are read as
 * normal maps. */
SR_TEST(obj_bump_map_lights_from_the_right_side)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    char dir[1024];
    fresh_dir("obj_bump", dir, sizeof dir);
    int flat[3], right[3], left[3], tilted[3], norm[3];
    REQUIRE(render_obj_square(dir, "newmtl m\nKd 0.8 0.8 0.8\nNs 100\n", NULL, flat));
    REQUIRE(render_obj_square(dir,
                              "newmtl m\nKd 0.8 0.8 0.8\nNs 100\nmap_Bump -bm 10 up_right.png\n",
                              "up_right", right));
    REQUIRE(render_obj_square(dir, "newmtl m\nKd 0.8 0.8 0.8\nNs 100\nbump -bm 10 up_left.png\n",
                              "up_left", left));
    REQUIRE(render_obj_square(dir, "newmtl m\nKd 0.8 0.8 0.8\nNs 100\nmap_Bump tilted.png\n",
                              "tilted", tilted));
    REQUIRE(render_obj_square(dir, "newmtl m\nKd 0.8 0.8 0.8\nNs 100\nnorm tilted.png\n",
                              "tilted", norm));
    CHECK(flat[0] > 20);
    CHECK(right[0] + 10 < flat[0]);
    CHECK(left[0] > flat[0] + 10);
    CHECK(tilted[0] > flat[0] + 10);
    CHECK_EQ(norm[0], tilted[0]);
#endif
}

/* Pm/Pr and d/Tr of an OBJ material reach the physically based look: a
 * red metal away from its highlight is darker than red plastic (a metal
 * has no diffuse light), and d 0.3 (or Tr 0.7) lets the background
 * through. */
SR_TEST(obj_materials_map_onto_the_physically_based_look)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    char dir[1024];
    fresh_dir("obj_looks", dir, sizeof dir);
    int plastic[3], metal[3], opaque[3], clear[3], tr[3];
    REQUIRE(render_obj_square(dir, "newmtl m\nKd 1 0 0\nKs 1 1 1\nPr 0.3\n", NULL, plastic));
    REQUIRE(render_obj_square(dir, "newmtl m\nKd 1 0 0\nKs 1 1 1\nPr 0.3\nPm 1\n", NULL, metal));
    CHECK(metal[0] + 20 < plastic[0]);
    REQUIRE(render_obj_square(dir, "newmtl m\nKd 0.9 0.9 0.9\nNs 50\n", NULL, opaque));
    REQUIRE(render_obj_square(dir, "newmtl m\nKd 0.9 0.9 0.9\nNs 50\nd 0.3\n", NULL, clear));
    REQUIRE(render_obj_square(dir, "newmtl m\nKd 0.9 0.9 0.9\nNs 50\nTr 0.7\n", NULL, tr));
    /* The background is #1d2230. */
    CHECK(clear[0] > 0x1d && clear[0] < opaque[0] - 10);
    CHECK(clear[2] > 0x30 || clear[2] < opaque[2]);
    CHECK_EQ(tr[0], clear[0]);
#endif
}

/* BLEND primitives are blended back to front whatever their order in
 * the file: a half-transparent blue quad in front of a half-transparent
 * red one, listed first, leaves more blue than red where they overlap. */
SR_TEST(gltf_blend_primitives_are_sorted_back_to_front)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson (glTF)");
    }
    char dir[1024], model[1100], out[1100];
    fresh_dir("gltf_blend", dir, sizeof dir);
    snprintf(model, sizeof model, "%s/blend.gltf", dir);
    snprintf(out, sizeof out, "%s/blend.png", dir);
    /* Mesh 1 (z = 0.5, nearer the camera) is listed first. */
    REQUIRE(write_two_quads(model,
        ",\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.9,0.02,0.02,0.5],"
        "\"metallicFactor\":0},\"alphaMode\":\"BLEND\",\"extensions\":"
        "{\"KHR_materials_unlit\":{}}},{\"pbrMetallicRoughness\":{\"baseColorFactor\":"
        "[0.02,0.02,0.9,0.5],\"metallicFactor\":0},\"alphaMode\":\"BLEND\",\"extensions\":"
        "{\"KHR_materials_unlit\":{}}}],\"extensionsUsed\":[\"KHR_materials_unlit\"],"
        "\"nodes\":[{\"mesh\":1},{\"mesh\":0}],\"scenes\":[{\"nodes\":[0,1]}],\"scene\":0"));
    int w, h;
    uint8_t *px = render_pixels(ARGS("render", model, "--camera", "eye=0,0,5", "--background",
                                     "black", "--size", "80x60", "--aa", "none", "-o", out),
                                out, &w, &h);
    REQUIRE(px);
    /* x = -0.25: both quads cover it. */
    int x = w / 2 - w / 16;
    const uint8_t *both = px + 4 * ((size_t)(h / 2) * w + x);
    CHECK(both[2] > both[0] + 20);
    free(px);
#endif
}

#ifdef SR_CLI_PATH
/* The bunny over a --ground shadow catcher, on a light gray background,
 * its key light the one directional --light DIR. */
static uint8_t *render_grounded(const char *dir, const char *name, const char *light,
                                const char *shadows, int *w, int *h)
{
    char model[1100], out[1100];
    snprintf(model, sizeof model, "%s/stanford-bunny.obj", sr_test_models_dir());
    snprintf(out, sizeof out, "%s/%s.png", dir, name);
    return render_pixels(ARGS("render", model, "--ground", "--shadows", shadows, "--light", light,
                              "--background", "0.8", "--size", "160x120", "--aa", "none", "-o",
                              out),
                         out, w, h);
}

/* The bunny at 96 x 72, no antialiasing, with the options a0 a1 a2 a3,
 * into DIR/NAME.png: its pixels, or NULL after a failure. */
static uint8_t *render_small_bunny(const char *dir, const char *name, const char *a0,
                                   const char *a1, const char *a2, const char *a3, int *w, int *h)
{
    char model[1100], out[1100];
    snprintf(model, sizeof model, "%s/stanford-bunny.obj", sr_test_models_dir());
    snprintf(out, sizeof out, "%s/%s.png", dir, name);
    return render_pixels(ARGS("render", model, a0, a1, a2, a3, "--size", "96x72", "--aa", "none",
                              "-o", out),
                         out, w, h);
}

/* Over the pixels that show the background in `plain` (the same render
 * without a shadow): the summed darkening of `px` below the background
 * in the left and right halves, and how many of them `px` changed. */
static size_t shadow_sides(const uint8_t *px, const uint8_t *plain, int w, int h, uint8_t bg,
                           double *left, double *right)
{
    size_t changed = 0;
    *left = *right = 0.0;
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const uint8_t *p = px + 4 * ((size_t)y * w + x), *q = plain + 4 * ((size_t)y * w + x);
            if (q[0] != bg || q[1] != bg || q[2] != bg) {
                continue;   /* the model */
            }
            changed += memcmp(p, q, 4) != 0;
            double dark = 3.0 * bg - p[0] - p[1] - p[2];
            *(x < w / 2 ? left : right) += dark;
        }
    }
    return changed;
}
#endif

/* --ground: the catcher darkens the background only where the model's
 * shadow falls, on the side away from the key light (the light travels
 * +x, the default camera's right, or -x); --shadows off leaves every
 * ground pixel the background's bytes. */
SR_TEST(ground_shadow_falls_away_from_the_key_light)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    if (!sr_test_models_dir()) {
        SKIP("no shared models directory (the bunny)");
    }
    char dir[1024];
    fresh_dir("ground_shadow", dir, sizeof dir);
    int w, h;
    uint8_t *plain = render_grounded(dir, "off", "dir=1,-1,0", "off", &w, &h);
    uint8_t *right = render_grounded(dir, "right", "dir=1,-1,0", "on", &w, &h);
    uint8_t *left = render_grounded(dir, "left", "dir=-1,-1,0", "on", &w, &h);
    REQUIRE(plain && right && left);
    uint8_t bg = plain[0];                /* the corner: 0.8 as a byte */
    CHECK(bg == 204);
    size_t model = 0;
    for (size_t i = 0; i < (size_t)w * h; i++) {
        model += plain[4 * i] != bg;
    }
    CHECK(model > (size_t)w * h / 20 && model < (size_t)w * h / 2);   /* the bunny is there */
    double l, r;
    size_t n = shadow_sides(right, plain, w, h, bg, &l, &r);
    CHECK(n > (size_t)w * h / 50);   /* a shadow of some size */
    CHECK(r > 4.0 * l);
    CHECK(r > 60.0 * (double)n);     /* 20 levels a channel darker, on average */
    n = shadow_sides(left, plain, w, h, bg, &l, &r);
    CHECK(n > (size_t)w * h / 50);
    CHECK(l > 4.0 * r);
    CHECK(l > 60.0 * (double)n);
    /* Nothing brightens the background: the catcher only darkens. */
    for (size_t i = 0; i < (size_t)w * h; i++) {
        if (plain[4 * i] == bg) {
            CHECK(right[4 * i] <= bg && left[4 * i] <= bg);
        }
    }
    free(plain);
    free(right);
    free(left);
#endif
}

/* --background environment|blur: the studio fills the frame behind the
 * model (no pixel keeps the default color, the picture is opaque and
 * not one color); blurring changes it, but keeps it close to the sharp
 * one (the mean difference, in levels of green). */
SR_TEST(background_environment_shows_the_studio)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    if (!sr_test_models_dir()) {
        SKIP("no shared models directory (the bunny)");
    }
    char dir[1024];
    fresh_dir("background_env", dir, sizeof dir);
    const char *kinds[2] = { "environment", "blur" };
    uint8_t *px[2];
    int w = 0, h = 0;
    for (int m = 0; m < 2; m++) {
        px[m] = render_small_bunny(dir, kinds[m], "--environment", "studio", "--background",
                                   kinds[m], &w, &h);
        REQUIRE(px[m]);
    }
    size_t default_bg = 0, opaque = 0;
    int lo = 255, hi = 0;
    double diff = 0.0;
    for (size_t i = 0; i < (size_t)w * h; i++) {
        default_bg += is_background(px[0] + 4 * i);
        opaque += px[0][4 * i + 3] == 255 && px[1][4 * i + 3] == 255;
        lo = px[0][4 * i] < lo ? px[0][4 * i] : lo;
        hi = px[0][4 * i] > hi ? px[0][4 * i] : hi;
        diff += abs(px[0][4 * i + 1] - px[1][4 * i + 1]);
    }
    CHECK_EQ(default_bg, 0);
    CHECK_EQ(opaque, (size_t)w * h);
    CHECK(hi - lo > 30);
    CHECK(diff / ((double)w * h) > 0.5 && diff / ((double)w * h) < 12.0);
    free(px[0]);
    free(px[1]);
#endif
}

/* Without a ground the default draws no shadow map: the same bytes as
 * --shadows off; --shadows on darkens the model where it shadows itself. */
SR_TEST(shadows_are_off_on_a_model_alone_unless_asked)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    if (!sr_test_models_dir()) {
        SKIP("no shared models directory (the bunny)");
    }
    char dir[1024];
    fresh_dir("model_shadows", dir, sizeof dir);
    /* --turn 0 and --exposure 0 change nothing: the default. */
    const char *const set[3][2] = { { "--turn", "0" }, { "--shadows", "off" },
                                    { "--shadows", "on" } };
    const char *names[3] = { "default", "off", "on" };
    uint8_t *px[3];
    int w = 0, h = 0;
    for (int k = 0; k < 3; k++) {
        px[k] = render_small_bunny(dir, names[k], set[k][0], set[k][1], "--exposure", "0", &w, &h);
        REQUIRE(px[k]);
    }
    CHECK(memcmp(px[0], px[1], (size_t)w * h * 4) == 0);
    size_t darker = 0;
    for (size_t i = 0; i < (size_t)w * h * 4; i++) {
        CHECK(px[2][i] <= px[1][i] || i % 4 == 3);   /* a shadow only takes light away */
        darker += px[2][i] + 8 < px[1][i];
    }
    CHECK(darker > 20);
    for (int k = 0; k < 3; k++) {
        free(px[k]);
    }
#endif
}

/* --depth-range and --clipper reach sr_state: the range 1,0 inverts depth
 * (the less test then keeps the farthest surface, a different picture)
 * and, with --depth-func greater, gives the default picture back; 0,0 is
 * GL's zero-width range, not the library's {0} default; the view-volume
 * clipper gives the homogeneous clipper's pixels with the near plane
 * cutting the teapot, up to the float rounding docs/clipping.md allows. */
SR_TEST(depth_range_and_clipper_options_change_the_draw)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    char dir[1024], out[1100];
    fresh_dir("depthrange", dir, sizeof dir);
    snprintf(out, sizeof out, "%s/d.png", dir);
    const char *variants[][8] = {
        { "--cull", "none" },
        { "--cull", "none", "--depth-range", "1,0" },
        { "--cull", "none", "--depth-range", "1,0", "--depth-func", "greater" },
        { "--cull", "none", "--depth-range", "0,0" },
    };
    uint8_t *px[4] = { NULL };
    int w = 0, h = 0;
    for (int v = 0; v < 4; v++) {
        const char *base[] = { "render", "--size", "96x64", "--detail", "4", "-o", out, NULL };
        const char *args[MAX_ARGS + 1];
        join_args(args, base, variants[v]);
        px[v] = render_pixels(args, out, &w, &h);
        REQUIRE(px[v]);
    }
    size_t n = (size_t)w * h * 4;
    CHECK(memcmp(px[0], px[1], n) != 0);
    CHECK(memcmp(px[0], px[2], n) == 0);
    CHECK(memcmp(px[0], px[3], n) != 0);
    CHECK(memcmp(px[1], px[3], n) != 0);
    for (int v = 0; v < 4; v++) {
        free(px[v]);
    }

    /* The default camera with the near plane through the teapot. */
    uint8_t *clip[3];
    const char *names[3] = { "homogeneous", "view-volume", NULL };
    for (int k = 0; k < 3; k++) {
        const char *args[] = { "render", "--size", "96x64", "--detail", "4", "--shading",
                               "gouraud", "--aa", "none", "-o", out, names[k] ? "--near" : NULL,
                               "6", "--clipper", names[k], NULL };
        clip[k] = render_pixels(args, out, &w, &h);
        REQUIRE(clip[k]);
    }
    long differ = 0, cut = 0;
    for (int i = 0; i < w * h; i++) {
        differ += memcmp(clip[0] + 4 * i, clip[1] + 4 * i, 4) != 0;
        cut += memcmp(clip[0] + 4 * i, clip[2] + 4 * i, 4) != 0;
    }
    printf("clippers: %ld of %d pixels differ; the near plane changes %ld\n", differ, w * h, cut);
    CHECK(cut > w * h / 10);
    CHECK(differ * 100 <= w * h); /* at most 1% */
    for (int k = 0; k < 3; k++) {
        free(clip[k]);
    }
#endif
}

/* Every command that writes an image writes the format its name says or
 * refuses the name at once: "x.bmp" is neither given PNG bytes nor left
 * half-made, whichever command and option named it. */
SR_TEST(image_outputs_with_another_extension_are_refused)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    char dir[1024], model[1100], svg[1100], list[1100], bmp[1100], pattern[1100], outdir[1100];
    char webp[1100], jpg[1100];
    fresh_dir("extension", dir, sizeof dir);
    snprintf(webp, sizeof webp, "--output=%s/x.WEBP", dir);
    char *const paths[] = { jpg, model, svg, list, bmp, pattern, outdir };
    const char *const names[] = { "t.jpg", "tri.obj", "box.svg", "list.txt", "out.bmp",
                                  "step-%d.gif", "out" };
    for (size_t i = 0; i < sizeof paths / sizeof paths[0]; i++) {
        snprintf(paths[i], 1100, "%s/%s", dir, names[i]);
    }
    clean_dir(outdir);   /* an earlier run's, if any: made by no refused case */
    rmdir(outdir);
    const char *box = "<svg xmlns='http://www.w3.org/2000/svg' width='8' height='8'>"
                      "<rect width='4' height='4'/></svg>";
    char line[1200];
    snprintf(line, sizeof line, "%s\tdrawn.tiff\n", model);
    REQUIRE(write_whole(model, ONE_TRIANGLE_OBJ, strlen(ONE_TRIANGLE_OBJ)));
    REQUIRE(write_whole(svg, box, strlen(box)));
    REQUIRE(write_whole(list, line, strlen(line)));
    kept_file kept[] = { { .path = model } };
    keep_files(kept, 1);
    const char *png_or_jpeg = "softrast writes PNG or JPEG images, not .";
    refusal_case cases[] = {
        { "render", { "render", model, "-o", bmp }, "-o: '" },
        { "demo", { "demo", "lines", "-o", bmp }, png_or_jpeg },
        { "demo --output=", { "demo", "lines", webp }, "not .WEBP" },
        { "thumbnail", { "thumbnail", "-s", "16", model, bmp }, "written as a PNG, not .bmp" },
        { "thumbnail JPEG", { "thumbnail", "-s", "16", model, jpg }, "(name it .png)" },
        { "explain --sheet", { "explain", "zbuffer", "--sheet", bmp }, "--sheet: '" },
        { "explain -o", { "explain", "zbuffer", "-o", pattern }, "not .gif" },
        { "view --screenshot", { "view", model, "--screenshot", bmp }, "--screenshot: '" },
        { "render --name", { "render", model, "--output-dir", outdir, "--name", "{stem}.bmp" },
          "--name: '{stem}.bmp'" },
        { "render --sheet", { "render", model, "--output-dir", outdir, "--sheet", bmp },
          "--sheet: '" },
        { "svg -o", { "svg", svg, "-o", bmp }, png_or_jpeg },
        { "svg --name", { "svg", svg, svg, "--output-dir", outdir, "--name", "{stem}.bmp" },
          "--name: '" },
    };
    size_t n = sizeof cases / sizeof cases[0];
    if (!svg_command_built()) {
        n -= 2;   /* the svg cases are last */
    }
    expect_refusals(cases, n, kept, 1);
    char first[256];
    CHECK_EQ(count_entries(dir, first, sizeof first), 3);   /* the inputs only */
    /* A list's OUTPUT is known only as its line is read: that item fails,
     * drawing nothing, as one whose OUTPUT is an input does. */
    cli_run r;
    REQUIRE(run_cli(ARGS("render", "--batch", list, "--output-dir", outdir), &r));
    CHECK_EQ(r.status, 4);
    CHECK(r.err && strstr(r.err, "--batch output: 'drawn.tiff': softrast writes PNG or JPEG"));
    cli_run_free(&r);
    snprintf(line, sizeof line, "%s/drawn.tiff", outdir);
    CHECK(access(line, F_OK) != 0);
    /* The names it writes, in any case, and a name without extension (a PNG). */
    char png[1100], bare[1100];
    snprintf(png, sizeof png, "%s/upper.PNG", dir);
    snprintf(bare, sizeof bare, "%s/bare", dir);
    const char *written[] = { png, bare };
    for (int i = 0; i < 2; i++) {
        int w = 0, h = 0;
        uint8_t *px = render_pixels(ARGS("render", model, "--size", "8x8", "-o", written[i]),
                                    written[i], &w, &h);
        CHECK(px && w == 8 && h == 8);
        free(px);
    }
#endif
}

/* ---- softrast info ------------------------------------------------------- */

#ifdef SR_CLI_PATH
/* Two quads (4 vertices, 2 triangles each): mesh 0 once, mesh 1 placed
 * twice, one of them moved up by 3; a coated, a glass material (with
 * dispersion and diffuse transmission); two
 * material variants, one named with an escape byte; a camera and a point
 * light. */
static bool write_info_model(const char *path)
{
    return write_two_quads(path,
        ",\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.25,1,1],"
        "\"metallicFactor\":0.25,\"roughnessFactor\":0.75},\"doubleSided\":true,"
        "\"extensions\":{\"KHR_materials_clearcoat\":{\"clearcoatFactor\":1}}},"
        "{\"alphaMode\":\"MASK\",\"extensions\":{\"KHR_materials_transmission\":"
        "{\"transmissionFactor\":1},\"KHR_materials_dispersion\":{\"dispersion\":0.5},"
        "\"KHR_materials_diffuse_transmission\":{\"diffuseTransmissionFactor\":0.5}}}],"
        "\"extensionsUsed\":[\"KHR_materials_clearcoat\",\"KHR_materials_transmission\","
        "\"KHR_materials_dispersion\",\"KHR_materials_diffuse_transmission\","
        "\"KHR_lights_punctual\",\"KHR_materials_variants\"],"
        "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"point\","
        "\"intensity\":20,\"color\":[1,0.5,0.25],\"range\":8}]},"
        "\"KHR_materials_variants\":{\"variants\":[{\"name\":\"Red\"},"
        "{\"name\":\"Blue \\u001b[31m\"}]}},"
        "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.5,\"znear\":0.1}}],"
        "\"nodes\":[{\"mesh\":0},{\"mesh\":1},{\"mesh\":1,\"translation\":[0,3,0]},"
        "{\"camera\":0,\"translation\":[0,0,6]},"
        "{\"translation\":[0,0,2],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}],"
        "\"scenes\":[{\"nodes\":[0,1,2,3,4]}]");
}
#endif

/* What a glTF file holds, in words: instances counted, bounds in world
 * space, the materials' extensions, the camera and the light. */
SR_TEST(info_describes_a_gltf_scene)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    if (!sr_io_have_gltf()) {
        SKIP("this build reads no glTF");
    }
    char dir[1024], model[1100];
    fresh_dir("info", dir, sizeof dir);
    snprintf(model, sizeof model, "%s/scene.gltf", dir);
    REQUIRE(write_info_model(model));
    cli_run r;
    REQUIRE(run_cli(ARGS("info", model), &r));
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.err_len, 0);
    CHECK_STR_CONTAINS(r.out, "draws       3 primitives: 12 vertices, 6 triangles");
    CHECK_STR_CONTAINS(r.out, "bounds      min -1 -1 0, max 0.5 4 0.5 (size 1.5 x 5 x 0.5)");
    /* The file's two; not the default one the reader adds for
     * primitives without a material, which none is. */
    CHECK_STR_CONTAINS(r.out, "materials   2\n");
    CHECK(!strstr(r.out, "    2  "));
    CHECK_STR_CONTAINS(r.out, "0  base color 0.5 0.25 1 1, metallic 0.25, roughness 0.75, "
                              "OPAQUE, double-sided; KHR_materials_clearcoat\n");
    CHECK_STR_CONTAINS(r.out, "1  base color 1 1 1 1, metallic 1, roughness 1, MASK; "
                              "KHR_materials_transmission, KHR_materials_dispersion, "
                              "KHR_materials_diffuse_transmission\n");
    /* A name's escape byte never reaches the terminal. */
    CHECK_STR_CONTAINS(r.out, "variants    2 (--variant)\n    0  Red\n    1  Blue ?[31m\n");
    CHECK_STR_CONTAINS(r.out, "cameras     1\n    0  perspective, yfov 28.6479 degrees, aspect "
                              "the image's, znear 0.1, zfar infinite (node 3)\n");
    CHECK_STR_CONTAINS(r.out, "lights      1\n    0  point, color 1 0.5 0.25, intensity 20 "
                              "candela, range 8 (node 4)\n");
    cli_run_free(&r);

    REQUIRE(run_cli(ARGS("info", "--json", model), &r));
    CHECK_EQ(r.status, 0);
    CHECK_STR_CONTAINS(r.out, "\"primitives\": 3, \"vertices\": 12, \"triangles\": 6,");
    CHECK_STR_CONTAINS(r.out, "\"bounds\": {\"min\": [-1, -1, 0], \"max\": [0.5, 4, 0.5]}");
    CHECK_STR_CONTAINS(r.out, "\"extensions\": [\"KHR_materials_clearcoat\"]");
    CHECK_STR_CONTAINS(r.out, "{\"type\": \"perspective\", \"node\": 3, \"yfov\": 0.5, "
                              "\"aspect\": 0, \"znear\": 0.1, \"zfar\": null}");
    CHECK_STR_CONTAINS(r.out, "{\"type\": \"point\", \"node\": 4, \"color\": [1, 0.5, 0.25], "
                              "\"intensity\": 20, \"range\": 8}");
    CHECK_STR_CONTAINS(r.out, "\"variants\": [\"Red\", \"Blue \\u001b[31m\"]");
    CHECK_STR_CONTAINS(r.out, "\"warnings\": 0}\n");
    CHECK(!strstr(r.out, "\"default\""));
    cli_run_free(&r);

    /* With mesh 1 naming no material, the default is shown, after the
     * file's, as what it is. */
    size_t len = 0;
    char *json = read_whole(model, &len);
    char *cut = json ? strstr(json, ",\"material\":1") : NULL;
    REQUIRE(cut);
    memmove(cut, cut + strlen(",\"material\":1"), strlen(cut + strlen(",\"material\":1")) + 1);
    REQUIRE(write_whole(model, json, strlen(json)));
    free(json);
    REQUIRE(run_cli(ARGS("info", model), &r));
    CHECK_EQ(r.status, 0);
    CHECK_STR_CONTAINS(r.out, "materials   2, and the default for primitives without one\n");
    CHECK_STR_CONTAINS(r.out, "    2  (default) base color 1 1 1 1, metallic 1, roughness 1, "
                              "OPAQUE\n");
    cli_run_free(&r);
    REQUIRE(run_cli(ARGS("info", "--json", model), &r));
    CHECK_STR_CONTAINS(r.out, "{\"default\": true, \"base_color\": [1, 1, 1, 1], ");
    cli_run_free(&r);
#endif
}

/* The JSON is JSON: a file name with quotes, a backslash and a control
 * byte comes out escaped; the object parses. */
SR_TEST(info_json_escapes_the_file_name)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    char dir[1024], model[1100];
    fresh_dir("info_json", dir, sizeof dir);
    snprintf(model, sizeof model, "%s/a \"q\" \\ \t.stl", dir);
    REQUIRE(write_box_stl(model, 1, 2, 3));
    cli_run r;
    REQUIRE(run_cli(ARGS("info", model, "--json"), &r));
    CHECK_EQ(r.status, 0);
    CHECK_STR_CONTAINS(r.out, "/a \\\"q\\\" \\\\ \\u0009.stl\"");
    CHECK_STR_CONTAINS(r.out, "\"primitives\": 1,");
#ifdef SR_HAVE_JANSSON_TEST
    json_error_t je;
    json_t *root = json_loads(r.out, 0, &je);
    CHECK(root != NULL);
    if (root) {
        CHECK_EQ(json_integer_value(json_object_get(root, "triangles")), 12);
        CHECK(strcmp(json_string_value(json_object_get(root, "file")), model) == 0);
        json_decref(root);
    }
#endif
    cli_run_free(&r);
#endif
}

/* gltf_quads' document of one quad of material 0, with `tail`, for an
 * info test: its path under the fresh directory `name` in model. */
static char *info_quad(const char *name, const char *tail, char *model, size_t n)
{
    char dir[1024];
    fresh_dir(name, dir, sizeof dir);
    snprintf(model, n, "%s/%s.gltf", dir, name);
    const gltf_quad q = { -1, -1, 1, 1, 0 };
    return gltf_quads(&q, 1, tail);
}

/* A quad placed five times by EXT_mesh_gpu_instancing (an _ID alone:
 * five identity transforms): five draws, said to be instances. */
SR_TEST(info_counts_gpu_instances)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    if (!sr_io_have_gltf()) {
        SKIP("this build reads no glTF");
    }
    char model[1100];
    /* The quad's node instanced five times by a new accessor 3 (an _ID
     * without a bufferView: zeros). */
    char *json = info_quad("info_instances", ",\"materials\":[{}],"
                           "\"extensionsUsed\":[\"EXT_mesh_gpu_instancing\"]",
                           model, sizeof model);
    REQUIRE(json);
    const char *acc = "\"type\":\"SCALAR\"}]", *node = "{\"mesh\":0}";
    char *a = strstr(json, acc), *n = strstr(json, node);
    REQUIRE(a && n && a < n);
    size_t cap = strlen(json) + 400;
    char *text = malloc(cap);
    REQUIRE(text);
    snprintf(text, cap,
             "%.*s\"type\":\"SCALAR\"},{\"componentType\":5126,\"count\":5,\"type\":\"SCALAR\"}]"
             "%.*s{\"mesh\":0,\"extensions\":{\"EXT_mesh_gpu_instancing\":{\"attributes\":"
             "{\"_ID\":3}}}}%s",
             (int)(a - json), json, (int)(n - a - strlen(acc)), a + strlen(acc),
             n + strlen(node));
    free(json);
    REQUIRE(write_whole(model, text, strlen(text)));
    free(text);
    cli_run r;
    REQUIRE(run_cli(ARGS("info", model), &r));
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.err_len, 0);
    CHECK_STR_CONTAINS(r.out, "draws       5 primitives: 20 vertices, 10 triangles");
    CHECK_STR_CONTAINS(r.out, "  instances   5 of the draws, from EXT_mesh_gpu_instancing on "
                              "1 node\n");
    cli_run_free(&r);
    REQUIRE(run_cli(ARGS("info", "--json", model), &r));
    CHECK_EQ(r.status, 0);
    CHECK_STR_CONTAINS(r.out, "\"instanced_draws\": 5, \"instanced_nodes\": 1,");
    cli_run_free(&r);
#endif
}

/* A KHR_materials_pbrSpecularGlossiness material: info names the
 * extension and shows the diffuse, specular and glossiness it draws. */
SR_TEST(info_shows_specular_glossiness)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    if (!sr_io_have_gltf()) {
        SKIP("this build reads no glTF");
    }
    char model[1100];
    char *json = info_quad("info_spec_gloss",
                           ",\"materials\":[{\"extensions\":{"
                           "\"KHR_materials_pbrSpecularGlossiness\":{"
                           "\"diffuseFactor\":[0.5,0.25,1,1],"
                           "\"specularFactor\":[0.25,0.5,0.125],\"glossinessFactor\":0.375}}}],"
                           "\"extensionsRequired\":[\"KHR_materials_pbrSpecularGlossiness\"],"
                           "\"extensionsUsed\":[\"KHR_materials_pbrSpecularGlossiness\"]",
                           model, sizeof model);
    REQUIRE(json);
    REQUIRE(write_whole(model, json, strlen(json)));
    free(json);
    cli_run r;
    REQUIRE(run_cli(ARGS("info", model), &r));
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.err_len, 0);
    CHECK_STR_CONTAINS(r.out, "    0  diffuse 0.5 0.25 1 1, specular 0.25 0.5 0.125, glossiness "
                              "0.375, OPAQUE; KHR_materials_pbrSpecularGlossiness\n");
    cli_run_free(&r);
    REQUIRE(run_cli(ARGS("info", "--json", model), &r));
    CHECK_EQ(r.status, 0);
    CHECK_STR_CONTAINS(r.out, "\"specular\": [0.25, 0.5, 0.125], \"glossiness\": 0.375,");
    CHECK_STR_CONTAINS(r.out, "\"extensions\": [\"KHR_materials_pbrSpecularGlossiness\"]");
    cli_run_free(&r);
#endif
}

/* What a glTF file says about itself (tests/data/gltf): the asset's
 * generator and copyright and its KHR_xmp_json_ld packet, in text its
 * licence and authorship properties, in JSON the packet as given; a
 * reference to no packet is one warning line with its JSON pointer, and
 * the rest is shown. */
SR_TEST(info_shows_the_assets_copyright_and_xmp_metadata)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    if (!sr_io_have_gltf()) {
        SKIP("this build reads no glTF");
    }
    char model[1100], bad[1100];
    snprintf(model, sizeof model, "%s/data/gltf/xmp_metadata.gltf", sr_test_src_dir());
    snprintf(bad, sizeof bad, "%s/data/gltf/xmp_bad_packet.gltf", sr_test_src_dir());
    cli_run r;
    REQUIRE(run_cli(ARGS("info", model), &r));
    CHECK_EQ(r.status, 0);
    CHECK_EQ(r.err_len, 0); /* the extension is read: no "not read" warning */
    CHECK_STR_CONTAINS(r.out, "  asset       glTF 2.0\n"
                              "    generator  tests/data/gltf (written by hand)\n"
                              "    copyright  2026 Ada Example, CC BY 4.0\n"
                              "  metadata    KHR_xmp_json_ld packet 0, 5 properties shown "
                              "(--json: all)\n");
    CHECK_STR_CONTAINS(r.out, "    dc:title              Corner triangle [en-us], Triangolo "
                              "d'angolo [it-it]\n"
                              "    dc:creator            Ada Example, Bo Sample <bo@example.org>\n"
                              "    dc:rights             CC BY 4.0\n"
                              "    xmpRights:UsageTerms  Attribution required: \"Corner "
                              "triangle\" by Ada Example\n"
                              "    xmpRights:Marked      true\n");
    CHECK(!strstr(r.out, "the mesh alone")); /* packet 1, the mesh's */
    cli_run_free(&r);

    REQUIRE(run_cli(ARGS("info", "--json", model), &r));
    CHECK_EQ(r.status, 0);
    CHECK_STR_CONTAINS(r.out, "\"metadata\": {\"version\": \"2.0\", \"min_version\": null, "
                              "\"generator\": \"tests/data/gltf (written by hand)\", "
                              "\"copyright\": \"2026 Ada Example, CC BY 4.0\", "
                              "\"xmp_packet\": 0,");
#ifdef SR_HAVE_JANSSON_TEST
    json_error_t je;
    json_t *root = json_loads(r.out, 0, &je);
    CHECK(root != NULL);
    if (root) {
        json_t *xmp = json_object_get(json_object_get(root, "metadata"), "xmp");
        json_t *creators = json_object_get(json_object_get(xmp, "dc:creator"), "@list");
        CHECK_EQ(json_array_size(creators), 2);
        CHECK(strcmp(json_string_value(json_array_get(creators, 1)),
                     "Bo Sample <bo@example.org>") == 0);
        CHECK(json_is_true(json_object_get(xmp, "xmpRights:Marked")));
        CHECK(json_object_get(json_object_get(xmp, "@context"), "xmpRights") != NULL);
        json_decref(root);
    }
#endif
    cli_run_free(&r);

    REQUIRE(run_cli(ARGS("info", bad), &r));
    CHECK_EQ(r.status, 0);
    CHECK(is_one_line(r.err, r.err_len));
    CHECK_STR_CONTAINS(r.err, "xmp_bad_packet.gltf: warning: /asset/extensions/KHR_xmp_json_ld/"
                              "packet: 2 is not an index below 2");
    CHECK_STR_CONTAINS(r.out, "    copyright  2026 Ada Example, CC BY 4.0\n");
    CHECK(!strstr(r.out, "  metadata "));
    CHECK_STR_CONTAINS(r.out, "  warnings    1 (on stderr)\n");
    cli_run_free(&r);
    REQUIRE(run_cli(ARGS("info", "--json", bad), &r));
    CHECK_EQ(r.status, 0);
    CHECK_STR_CONTAINS(r.out, "\"xmp_packet\": null, \"xmp\": null},\n \"warnings\": 1}\n");
    cli_run_free(&r);

    /* Other formats have none. */
    char dir[1024], obj[1100];
    fresh_dir("info_metadata", dir, sizeof dir);
    snprintf(obj, sizeof obj, "%s/t.obj", dir);
    REQUIRE(write_whole(obj, ONE_TRIANGLE_OBJ, strlen(ONE_TRIANGLE_OBJ)));
    REQUIRE(run_cli(ARGS("info", obj), &r));
    CHECK(!strstr(r.out, "  asset "));
    cli_run_free(&r);
    REQUIRE(run_cli(ARGS("info", "--json", obj), &r));
    CHECK_STR_CONTAINS(r.out, "\"metadata\": {\"version\": null, \"min_version\": null, "
                              "\"generator\": null, \"copyright\": null, \"xmp_packet\": null, "
                              "\"xmp\": null},");
    cli_run_free(&r);
#endif
}

/* Bad uses are one line and status 2; a model the reader refuses is its
 * reader's line. */
SR_TEST(info_refuses_bad_uses_in_one_line)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    char dir[1024], bad[1100];
    fresh_dir("info_bad", dir, sizeof dir);
    snprintf(bad, sizeof bad, "%s/bad.obj", dir);
    REQUIRE(write_whole(bad, "v 0 0 0\nf 1 2 3\n", 16));
    struct {
        const char *const *args;
        const char *says;
    } cases[] = {
        { ARGS("info"), "softrast: info: give a MODEL" },
        { ARGS("info", "a.obj", "b.obj"), "one MODEL at a time" },
        { ARGS("info", "--frobnicate", "a.obj"), "unknown option '--frobnicate'" },
        { ARGS("info", "/nonexistent/x.obj"), "/nonexistent/x.obj: cannot open" },
        { ARGS("info", bad), "bad.obj:2:" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        cli_run r;
        REQUIRE(run_cli(cases[i].args, &r));
        CHECK_EQ(r.status, 2);
        CHECK_EQ(r.out_len, 0);
        CHECK(is_one_line(r.err, r.err_len));
        CHECK_STR_CONTAINS(r.err, cases[i].says);
        cli_run_free(&r);
    }
#endif
}
