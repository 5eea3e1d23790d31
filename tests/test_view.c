/* test_view.c - `softrast view` as a user meets it: the real executable run
 * with posix_spawn, no shell.  Without a display it must say so in one line
 * and exit 1 (not crash, not run unseen).  Under Xvfb (xvfb-run), driven by
 * a script of synthetic input events (drags, wheel, keys, a resize), its
 * screenshot must be exactly the pixels `softrast render` draws from the
 * command the viewer prints for that view: the viewer and the renderer
 * share their camera and mode code.  Tests that need Xvfb, the shared
 * models or a viewer build skip with a message when those are absent. */
#include "softrast.h"
#include "softrast_io.h"
#include "sr_test.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

extern char **environ;

#define FAILF(...) sr_test_fail(__FILE__, __LINE__, __VA_ARGS__)
#define CHILD_TIMEOUT_MS (120000 * SR_TEST_SLOWDOWN)
#define MAX_ARGS 64

typedef struct run_result {
    int status;      /* exit status, or -1 (killed, crashed, could not run) */
    int signal;      /* the signal that ended it, or 0 */
    char *out, *err; /* captured streams, NUL-terminated */
} run_result;

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        return calloc(1, 1);
    }
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = malloc((size_t)(n > 0 ? n : 0) + 1);
    size_t got = buf && n > 0 ? fread(buf, 1, (size_t)n, f) : 0;
    if (buf) {
        buf[got] = 0;
    }
    fclose(f);
    return buf;
}

static void result_free(run_result *r)
{
    free(r->out);
    free(r->err);
}

/* Run argv[0] (looked up in PATH; the built tool through a cross build's
 * emulator) with `env`, streams captured. */
static bool run(const char *const *argv, char *const *env, run_result *r)
{
    memset(r, 0, sizeof *r);
    r->status = -1;
#ifdef SR_CLI_PATH
    const char *emulated[MAX_ARGS + 16];
    if (strcmp(argv[0], SR_CLI_PATH) == 0) {
        if (!sr_test_program_argv(argv[0], argv + 1, emulated, MAX_ARGS + 16)) {
            return false;
        }
        argv = emulated;
    }
#endif
    char out_path[1100], err_path[1100];
    snprintf(out_path, sizeof out_path, "%s/view-%d.out", sr_test_out_dir(), (int)getpid());
    snprintf(err_path, sizeof err_path, "%s/view-%d.err", sr_test_out_dir(), (int)getpid());
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 1, out_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&fa, 2, err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid;
    int e = posix_spawnp(&pid, argv[0], &fa, NULL, (char *const *)argv, env);
    posix_spawn_file_actions_destroy(&fa);
    if (e != 0) {
        return false;
    }
    int status = 0;
    for (int waited = 0;; waited += 10) {
        pid_t w = waitpid(pid, &status, WNOHANG);
        if (w == pid) {
            break;
        }
        if (waited > CHILD_TIMEOUT_MS) {
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            FAILF("%s did not finish within %d s", argv[0], CHILD_TIMEOUT_MS / 1000);
            break;
        }
        nanosleep(&(struct timespec){ 0, 10000000 }, NULL);
    }
    if (WIFEXITED(status)) {
        r->status = WEXITSTATUS(status);
    } else if (WIFSIGNALED(status)) {
        r->signal = WTERMSIG(status);
    }
    r->out = slurp(out_path);
    r->err = slurp(err_path);
    unlink(out_path);
    unlink(err_path);
    return r->out && r->err;
}

/* The environment without the variables that name a display. */
static char **env_without_display(void)
{
    static char *env[512];
    int n = 0;
    for (char **e = environ; *e && n < 511; e++) {
        if (strncmp(*e, "DISPLAY=", 8) && strncmp(*e, "WAYLAND_DISPLAY=", 16) &&
            strncmp(*e, "SDL_VIDEODRIVER=", 16)) {
            env[n++] = *e;
        }
    }
    env[n] = NULL;
    return env;
}

static bool in_path(const char *prog)
{
    const char *path = getenv("PATH");
    char buf[4096];
    while (path && *path) {
        size_t n = strcspn(path, ":");
        snprintf(buf, sizeof buf, "%.*s/%s", (int)n, path, prog);
        if (access(buf, X_OK) == 0) {
            return true;
        }
        path += n + (path[n] == ':');
    }
    return false;
}

static int count_lines(const char *s)
{
    int n = 0;
    for (; *s; s++) {
        n += *s == '\n';
    }
    return n;
}

/* 1: built with the viewer, 0: without, -1: the tool is not built. */
static int viewer_built(void)
{
#ifndef SR_CLI_PATH
    return -1;
#else
    const char *argv[] = { SR_CLI_PATH, "view", "--events", "/nonexistent/events", NULL };
    run_result r;
    if (!run(argv, env_without_display(), &r)) {
        return -1;
    }
    int built = strstr(r.err, "built without SDL2") ? 0 : 1;
    result_free(&r);
    return built;
#endif
}

static const char *bunny(char *buf, size_t size)
{
    const char *dir = sr_test_models_dir();
    if (!dir) {
        return NULL;
    }
    snprintf(buf, size, "%s/stanford-bunny.obj", dir);
    return access(buf, R_OK) == 0 ? buf : NULL;
}

static bool write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        return false;
    }
    bool ok = fputs(text, f) >= 0;
    return fclose(f) == 0 && ok;
}

static uint8_t *read_image(const char *path, int *w, int *h)
{
    uint8_t *px = NULL;
    sr_io_error err;
    if (sr_read_image(path, w, h, &px, &err) != SR_OK) {
        FAILF("%s", err.message);
        return NULL;
    }
    return px;
}

/* Run `softrast view ARGS...` under xvfb-run. */
static bool run_view_xvfb(const char *const *args, run_result *r)
{
#ifdef SR_CLI_PATH
    const char *argv[MAX_ARGS];
    int n = 0;
    /* An authority file of our own: with its temporary one, xvfb-run
     * sometimes fails to remove that directory after a command that
     * exits non-zero and then exits 5 itself (2 runs in 15 here). */
    static char auth[1100];
    snprintf(auth, sizeof auth, "%s/view-xauthority", sr_test_out_dir());
    argv[n++] = "xvfb-run";
    argv[n++] = "-a";
    argv[n++] = "-f";
    argv[n++] = auth;
    argv[n++] = "-s";
    argv[n++] = "-screen 0 1024x768x24 -nolisten tcp";
    const char *view_args[MAX_ARGS];
    view_args[0] = "view";
    int k = 1;
    for (int i = 0; args[i] && k < MAX_ARGS - 1; i++) {
        view_args[k++] = args[i];
    }
    view_args[k] = NULL;
    if (!sr_test_program_argv(SR_CLI_PATH, view_args, argv + n, (size_t)(MAX_ARGS - n))) {
        FAILF("too many arguments for run_view_xvfb");
        return false;
    }
    /* In the sanitizer build, leak checking is off for the windowed
     * process only: SDL's X11 and D-Bus libraries keep blocks until exit,
     * some allocated from modules already unloaded, that LeakSanitizer
     * reports and no suppression can name.  The library and every other
     * command (the `render` runs these tests compare against included)
     * stay leak-checked. */
    static char *env[520];
    char **base = env_without_display();
    k = 0;
    for (int i = 0; base[i] && k < 510; i++) {
        if (strncmp(base[i], "LSAN_OPTIONS=", 13) != 0) {
            env[k++] = base[i];
        }
    }
    env[k++] = "LSAN_OPTIONS=detect_leaks=0";
    env[k] = NULL;
    return run(argv, env, r);
#else
    (void)args;
    (void)r;
    return false;
#endif
}

/* ---- tests ----------------------------------------------------------------- */

SR_TEST(view_without_a_display_says_so_in_one_line)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    char model[1024];
    const char *m = bunny(model, sizeof model);
    const char *argv[] = { SR_CLI_PATH, "view", m ? m : "--size", m ? "--log" : "320x240", NULL };
    run_result r;
    REQUIRE(run(argv, env_without_display(), &r));
    CHECK_EQ(r.signal, 0);
    /* A build without the viewer refuses the command as it would an
     * unknown option (2); one with it fails to open the window (1). */
    CHECK_EQ(r.status, strstr(r.err, "built without SDL2") ? 2 : 1);
    CHECK_EQ(count_lines(r.err), 1);
    CHECK_STR_CONTAINS(r.err, "softrast: view: ");
    if (!strstr(r.err, "built without SDL2")) {
        CHECK_STR_CONTAINS(r.err, "no display");
    }
    CHECK_EQ(strlen(r.out), 0);
    result_free(&r);
#endif
}

SR_TEST(view_help_matches_the_options)
{
#ifndef SR_CLI_PATH
    SKIP("the softrast tool is not part of this build");
#else
    const char *argv[] = { SR_CLI_PATH, "view", "--help", NULL };
    run_result r;
    REQUIRE(run(argv, environ, &r));
    CHECK_EQ(r.status, 0);
    CHECK_STR_CONTAINS(r.out, "usage: softrast view [MODEL]");
    const char *opts[] = { "--size", "--frames", "--screenshot", "--screenshot-overlay",
                           "--events", "--log", "--no-overlay", "--no-vsync", "--font" };
    for (size_t i = 0; i < sizeof opts / sizeof opts[0]; i++) {
        CHECK_STR_CONTAINS(r.out, opts[i]);
    }
    result_free(&r);
#endif
}

/* The options that do nothing under the shading given are said as
 * render says them, once each, and the mode table's own --filter is not
 * taken for the user's (told before the display is looked for). */
SR_TEST(view_warns_of_options_without_effect_once)
{
    if (viewer_built() != 1) {
        SKIP("softrast view is not built (needs libsdl2-dev and libfreetype-dev)");
    }
#ifdef SR_CLI_PATH
    const char *argv[] = { SR_CLI_PATH, "view", "--shading", "flat", "--exposure", "1",
                           "--detail", "2", NULL };
    run_result r;
    REQUIRE(run(argv, env_without_display(), &r));
    CHECK_EQ(r.status, 1);
    CHECK_STR_CONTAINS(r.err, "softrast: warning: --exposure has no effect with --shading flat "
                              "(it is for pbr)\n");
    const char *first = strstr(r.err, "--exposure has");
    CHECK(first && !strstr(first + 1, "--exposure has"));
    CHECK(!strstr(r.err, "--filter"));
    CHECK_STR_CONTAINS(r.err, "no display");
    CHECK_EQ(count_lines(r.err), 2);
    result_free(&r);
    const char *filtered[] = { SR_CLI_PATH, "view", "--filter", "tent", "--detail", "2", NULL };
    REQUIRE(run(filtered, env_without_display(), &r));
    CHECK_STR_CONTAINS(r.err, "softrast: warning: --filter has no effect without --aa ssaa2");
    CHECK_EQ(count_lines(r.err), 2);
    result_free(&r);
#endif
}

SR_TEST(bad_event_script_names_file_and_line)
{
    if (viewer_built() != 1) {
        SKIP("softrast view is not built (needs libsdl2-dev and libfreetype-dev)");
    }
#ifdef SR_CLI_PATH
    char path[1100];
    snprintf(path, sizeof path, "%s/view-bad-events.txt", sr_test_out_dir());
    REQUIRE(write_text(path, "# fine\nwheel 2\ndrag sideways 1 2 3 4\n"));
    const char *argv[] = { SR_CLI_PATH, "view", "--events", path, NULL };
    run_result r;
    REQUIRE(run(argv, env_without_display(), &r));
    CHECK_EQ(r.status, 2);
    CHECK_EQ(count_lines(r.err), 1);
    char want[1200];
    snprintf(want, sizeof want, "%s:3: drag: the button is left, right or middle", path);
    CHECK_STR_CONTAINS(r.err, want);
    result_free(&r);
#endif
}

/* A screenshot over one of the viewer's inputs (its event script, its
 * model, by any name) is refused before any window opens, and the input
 * keeps its bytes. */
SR_TEST(screenshot_over_an_input_is_refused)
{
    if (viewer_built() != 1) {
        SKIP("softrast view is not built (needs libsdl2-dev and libfreetype-dev)");
    }
#ifdef SR_CLI_PATH
    char events[1100], model[1100], link_path[1100], events_link[1100];
    snprintf(events, sizeof events, "%s/view-own-events.txt", sr_test_out_dir());
    snprintf(model, sizeof model, "%s/view-own-model.obj", sr_test_out_dir());
    snprintf(link_path, sizeof link_path, "%s/view-own-model-link.png", sr_test_out_dir());
    snprintf(events_link, sizeof events_link, "%s/view-own-events-link.png", sr_test_out_dir());
    const char *script = "wheel 2\nquit\n", *tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    REQUIRE(write_text(events, script));
    REQUIRE(write_text(model, tri));
    remove(link_path);
    REQUIRE(symlink(model, link_path) == 0);
    remove(events_link);
    REQUIRE(symlink(events, events_link) == 0);
    /* (named as themselves, .txt and .obj, they are no images: refused
     * for that first, test_cli.c) */
    const char *cases[][8] = {
        { SR_CLI_PATH, "view", "--events", events, "--screenshot", events_link, NULL },
        { SR_CLI_PATH, "view", model, "--screenshot-overlay", link_path, "--screenshot",
          "new.png" },
    };
    const char *needles[] = { "is the event script being read", "is the model being read" };
    for (int i = 0; i < 2; i++) {
        run_result r;
        REQUIRE(run(cases[i], env_without_display(), &r));
        CHECK_EQ(r.status, 2);
        CHECK_EQ(count_lines(r.err), 1);
        CHECK_STR_CONTAINS(r.err, needles[i]);
        result_free(&r);
    }
    char *s = slurp(events), *m = slurp(model);
    CHECK(strcmp(s, script) == 0);
    CHECK(strcmp(m, tri) == 0);
    free(s);
    free(m);
#endif
}

/* A directory read as nothing (an empty script, the viewer then waiting
 * for input); opening a FIFO waited for a writer (run() kills a child
 * that hangs); a long line came back from fgets as two, the second parsed
 * as a command under the wrong line number. */
SR_TEST(event_script_that_is_a_directory_a_fifo_or_has_a_long_line_is_refused)
{
    if (viewer_built() != 1) {
        SKIP("softrast view is not built (needs libsdl2-dev and libfreetype-dev)");
    }
#ifdef SR_CLI_PATH
    const char *out = sr_test_out_dir();
    const char *argv[] = { SR_CLI_PATH, "view", "--events", out, NULL };
    run_result r;
    REQUIRE(run(argv, env_without_display(), &r));
    CHECK_EQ(r.status, 2);
    CHECK_EQ(count_lines(r.err), 1);
    CHECK_STR_CONTAINS(r.err, "is a directory, not an event script");
    result_free(&r);

    char path[1100], want[1200];
    snprintf(path, sizeof path, "%s/view-events.fifo", out);
    unlink(path);
    REQUIRE(mkfifo(path, 0644) == 0);
    argv[3] = path;
    REQUIRE(run(argv, env_without_display(), &r));
    CHECK_EQ(r.status, 2);
    CHECK_EQ(count_lines(r.err), 1);
    snprintf(want, sizeof want, "--events: %s: not a regular file", path);
    CHECK_STR_CONTAINS(r.err, want);
    result_free(&r);
    unlink(path);

    snprintf(path, sizeof path, "%s/view-long-line.txt", out);
    static char text[6000];
    memset(text, 'x', 5000);
    text[0] = '#';
    memcpy(text + 5000, "\nquit\n", 7);
    REQUIRE(write_text(path, text));
    argv[3] = path;
    REQUIRE(run(argv, env_without_display(), &r));
    CHECK_EQ(r.status, 2);
    CHECK_EQ(count_lines(r.err), 1);
    snprintf(want, sizeof want, "%s:1: line longer than", path);
    CHECK_STR_CONTAINS(r.err, want);
    result_free(&r);
#endif
}

/* Split the printed render command into argv (the viewer quotes words with
 * spaces; the paths here have none). */
static int split_command(char *line, const char **argv, int max)
{
    int n = 0;
    for (char *tok = strtok(line, " \n"); tok && n < max - 1; tok = strtok(NULL, " \n")) {
        argv[n++] = tok;
    }
    argv[n] = NULL;
    return n;
}

SR_TEST(view_screenshot_after_scripted_input_equals_render)
{
    char model[1024];
    if (!bunny(model, sizeof model)) {
        SKIP("../shared/models (stanford-bunny.obj) is absent");
    }
    if (!in_path("xvfb-run")) {
        SKIP("xvfb-run is not installed (Debian: xvfb xauth)");
    }
    if (viewer_built() != 1) {
        SKIP("softrast view is not built (needs libsdl2-dev and libfreetype-dev)");
    }
#ifdef SR_CLI_PATH
    const char *out = sr_test_out_dir();
    char events[1100], shot[1100], again[1100], plain[1100];
    snprintf(events, sizeof events, "%s/view-events.txt", out);
    snprintf(shot, sizeof shot, "%s/view-shot.png", out);
    snprintf(again, sizeof again, "%s/view-render.png", out);
    snprintf(plain, sizeof plain, "%s/view-default.png", out);
    remove(shot);
    /* Orbit, pan and zoom through real input handling; then keys: M twice
     * (pbr -> flat -> gouraud), W three times (edges), C (no culling), A (ssaa2). */
    REQUIRE(write_text(events, "drag left 160 120 230 90\n"
                               "frames 1\n"
                               "drag right 100 100 120 110 4\n"
                               "wheel 3\n"
                               "frames 2\n"
                               "key m\nkey m\nkey w\nkey w\nkey w\nkey c\nkey a\n"));
    run_result r;
    REQUIRE(run_view_xvfb((const char *[]){ model, "--size", "320x240", "--events", events,
                                            "--screenshot", shot, NULL }, &r));
    CHECK_EQ(r.signal, 0);
    CHECK_EQ(r.status, 0);
    if (r.status != 0) {
        FAILF("view: %s", r.err);
    }
    const char *cmd = strstr(r.out, "the same image: softrast render ");
    REQUIRE(cmd);
    char line[4096];
    snprintf(line, sizeof line, "%s", cmd + strlen("the same image: softrast "));
    CHECK(strchr(line, '\'') == NULL);
    CHECK_STR_CONTAINS(line, "--shading=gouraud");
    CHECK_STR_CONTAINS(line, "--edges");
    CHECK_STR_CONTAINS(line, "--cull=none");
    CHECK_STR_CONTAINS(line, "--aa=ssaa2");
    CHECK_STR_CONTAINS(line, "--size=320x240");
    CHECK_STR_CONTAINS(line, "--camera=eye=");
    result_free(&r);

    /* The printed command, with the output renamed. */
    const char *argv[MAX_ARGS];
    int n = split_command(line, argv, MAX_ARGS);
    REQUIRE(n > 3 && strcmp(argv[n - 2], "-o") == 0);
    argv[n - 1] = again;
    CHECK_EQ(sr_test_run_cli(argv), 0);

    int w1, h1, w2, h2;
    uint8_t *a = read_image(shot, &w1, &h1), *b = read_image(again, &w2, &h2);
    REQUIRE(a && b);
    CHECK_EQ(w1, 320);
    CHECK_EQ(h1, 240);
    CHECK_EQ(w1, w2);
    CHECK_EQ(h1, h2);
    if (w1 == w2 && h1 == h2) {
        size_t diff = 0;
        for (size_t i = 0; i < (size_t)w1 * h1 * 4; i++) {
            diff += a[i] != b[i];
        }
        CHECK_EQ(diff, 0);
    }

    /* The input did move the camera: the default view is another image. */
    const char *def[] = { "render", model, "--size", "320x240", "--shading", "gouraud", "--edges",
                          "--cull", "none", "--aa", "ssaa2", "-o", plain, NULL };
    CHECK_EQ(sr_test_run_cli(def), 0);
    int w3, h3;
    uint8_t *c = read_image(plain, &w3, &h3);
    REQUIRE(c);
    if (w3 == w1 && h3 == h1) {
        CHECK(memcmp(a, c, (size_t)w1 * h1 * 4) != 0);
    }
    free(a);
    free(b);
    free(c);
#endif
}

/* A script's own screenshot then quit, with trailing comments as
 * docs/viewer.md writes them: the quit waits for the screenshot's frame. */
/* A screenshot named .jpg is a JPEG, as `softrast render -o NAME.jpg`
 * writes one (apps/softrast/image_out.c serves both). */
SR_TEST(a_jpg_screenshot_is_a_jpeg)
{
    if (!in_path("xvfb-run")) {
        SKIP("xvfb-run is not installed (Debian: xvfb xauth)");
    }
    if (viewer_built() != 1) {
        SKIP("softrast view is not built (needs libsdl2-dev and libfreetype-dev)");
    }
    if (!sr_io_have_jpeg()) {
        SKIP("this build writes no JPEG (libjpeg-dev was not found)");
    }
#ifdef SR_CLI_PATH
    char shot[1100];
    snprintf(shot, sizeof shot, "%s/view-shot.jpg", sr_test_out_dir());
    remove(shot);
    run_result r;
    REQUIRE(run_view_xvfb((const char *[]){ "--size", "96x64", "--frames", "1", "--screenshot",
                                            shot, NULL }, &r));
    CHECK_EQ(r.status, 0);
    result_free(&r);
    FILE *f = fopen(shot, "rb");
    REQUIRE(f);
    uint8_t head[3] = { 0 };
    CHECK_EQ(fread(head, 1, 3, f), 3);
    fclose(f);
    CHECK(head[0] == 0xFF && head[1] == 0xD8 && head[2] == 0xFF);
    int w, h;
    uint8_t *px = read_image(shot, &w, &h);
    REQUIRE(px);
    CHECK_EQ(w, 96);
    CHECK_EQ(h, 64);
    free(px);
#endif
}

SR_TEST(script_screenshot_then_quit_writes_the_file)
{
    if (!in_path("xvfb-run")) {
        SKIP("xvfb-run is not installed (Debian: xvfb xauth)");
    }
    if (viewer_built() != 1) {
        SKIP("softrast view is not built (needs libsdl2-dev and libfreetype-dev)");
    }
#ifdef SR_CLI_PATH
    const char *out = sr_test_out_dir();
    char events[1100], shot[1100], text[2400];
    snprintf(events, sizeof events, "%s/view-shot-quit.txt", out);
    snprintf(shot, sizeof shot, "%s/view-shot#1.png", out);
    remove(shot);
    snprintf(text, sizeof text,
             "# the built-in scene\n"
             "wheel 2              # notches\n"
             "screenshot %s   # the next frame, as PNG\n"
             "quit\n", shot);
    REQUIRE(write_text(events, text));
    run_result r;
    REQUIRE(run_view_xvfb((const char *[]){ "--size", "160x120", "--events", events, NULL }, &r));
    CHECK_EQ(r.signal, 0);
    CHECK_EQ(r.status, 0);
    if (r.status != 0) {
        FAILF("view: %s", r.err);
    }
    char wrote[1200];
    snprintf(wrote, sizeof wrote, "wrote %s;", shot);
    CHECK_STR_CONTAINS(r.out, wrote);
    result_free(&r);
    int w, h;
    uint8_t *px = read_image(shot, &w, &h);
    REQUIRE(px);
    CHECK_EQ(w, 160);
    CHECK_EQ(h, 120);
    free(px);
#endif
}

/* A screenshot the script asks for over the script itself fails like a
 * write that cannot be made (status 1, one line), and the script keeps
 * its bytes. */
SR_TEST(script_screenshot_over_the_script_is_refused)
{
    if (!in_path("xvfb-run")) {
        SKIP("xvfb-run is not installed (Debian: xvfb xauth)");
    }
    if (viewer_built() != 1) {
        SKIP("softrast view is not built (needs libsdl2-dev and libfreetype-dev)");
    }
#ifdef SR_CLI_PATH
    char events[1100], text[2400];
    snprintf(events, sizeof events, "%s/view-shot-self.txt", sr_test_out_dir());
    snprintf(text, sizeof text, "screenshot %s\nquit\n", events);
    REQUIRE(write_text(events, text));
    run_result r;
    REQUIRE(run_view_xvfb((const char *[]){ "--size", "96x64", "--events", events, NULL }, &r));
    CHECK_EQ(r.signal, 0);
    CHECK_EQ(r.status, 1);
    CHECK_EQ(count_lines(r.err), 1);
    CHECK_STR_CONTAINS(r.err, "is the event script being read");
    if (r.status != 1) {
        FAILF("view: %s", r.err);
    }
    result_free(&r);
    char *after = slurp(events);
    CHECK(strcmp(after, text) == 0);
    free(after);
#endif
}

SR_TEST(view_resizes_logs_frames_and_reports_the_median)
{
    char model[1024];
    if (!bunny(model, sizeof model)) {
        SKIP("../shared/models (stanford-bunny.obj) is absent");
    }
    if (!in_path("xvfb-run")) {
        SKIP("xvfb-run is not installed (Debian: xvfb xauth)");
    }
    if (viewer_built() != 1) {
        SKIP("softrast view is not built (needs libsdl2-dev and libfreetype-dev)");
    }
    const char *out = sr_test_out_dir();
    char events[1100], shot[1100], overlay[1100];
    snprintf(events, sizeof events, "%s/view-resize.txt", out);
    snprintf(shot, sizeof shot, "%s/view-resized.png", out);
    snprintf(overlay, sizeof overlay, "%s/view-resized-overlay.png", out);
    REQUIRE(write_text(events, "frames 1\nresize 200 150\nframes 3\nkey h\n"));
    run_result r;
    REQUIRE(run_view_xvfb((const char *[]){ model, "--size", "320x240", "--events", events,
                                            "--frames", "6", "--log", "--screenshot", shot,
                                            "--screenshot-overlay", overlay, NULL }, &r));
    CHECK_EQ(r.status, 0);
    CHECK_STR_CONTAINS(r.out, "frame 1: render ");
    CHECK_STR_CONTAINS(r.out, "frame 6: render ");
    CHECK(strstr(r.out, "frame 7:") == NULL);
    CHECK_STR_CONTAINS(r.out, "6 frames at 200x150");
    CHECK_STR_CONTAINS(r.out, "render median ");
    result_free(&r);
    int w, h;
    uint8_t *a = read_image(shot, &w, &h);
    REQUIRE(a);
    CHECK_EQ(w, 200);
    CHECK_EQ(h, 150);
    int w2, h2;
    uint8_t *b = read_image(overlay, &w2, &h2);
    REQUIRE(b);
    /* The overlay (the key list, after H) covers the top-left corner. */
    if (w2 == w && h2 == h) {
        CHECK(memcmp(a, b, (size_t)w * 40 * 4) != 0);
    }
    free(a);
    free(b);
}

/* A model after "--" whose name starts with '-': the viewer adds its
 * mode options to the render arguments before the "--", not after it
 * (where they would be operands), and prints the render command with
 * the model after "--" too. */
SR_TEST(model_after_end_of_options_is_viewed)
{
    if (!in_path("xvfb-run")) {
        SKIP("xvfb-run is not installed (Debian: xvfb xauth)");
    }
    if (viewer_built() != 1) {
        SKIP("softrast view is not built (needs libsdl2-dev and libfreetype-dev)");
    }
#ifdef SR_CLI_PATH
    char dir[1100], cwd[4096];
    snprintf(dir, sizeof dir, "%s/view-dash", sr_test_out_dir());
    mkdir(dir, 0777);
    REQUIRE(getcwd(cwd, sizeof cwd) != NULL);
    REQUIRE(chdir(dir) == 0);
    remove("shot.png");
    bool written = write_text("-a.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
    run_result r = { 0 };
    bool ran = written && run_view_xvfb((const char *[]){ "--size", "96x64", "--frames", "1",
                                                          "--screenshot", "shot.png", "--",
                                                          "-a.obj", NULL }, &r);
    struct stat st;
    bool shot = stat("shot.png", &st) == 0;
    REQUIRE(chdir(cwd) == 0);
    REQUIRE(written && ran);
    CHECK_EQ(r.status, 0);
    CHECK(shot);
    CHECK_STR_CONTAINS(r.out, " -o shot.png -- -a.obj\n");
    result_free(&r);
#endif
}
