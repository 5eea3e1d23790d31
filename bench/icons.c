/* icons.c - the icon-directory benchmark (bench): every 16th regular SVG
 * file (sorted by path, symlinks skipped) under an icon theme, rendered at
 * its own size and written as a PNG three ways: by softrast's library in
 * this one process (sr_render_svg_file and the PNG encoder, the calls
 * `softrast svg` makes), by `softrast svg` started once per file, and by
 * `rsvg-convert` started once per file.  Prints files per second for each
 * and their ratios to rsvg-convert.  Main thread; child processes write to
 * a temporary directory, their output to /dev/null. */
#define _XOPEN_SOURCE 700
#include "shapes2d.h"

#include "softrast_io.h"

#include <fcntl.h>
#include <ftw.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

extern char **environ;

#define STRIDE 16
#define MAX_PASSES 3

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec / 1e9;
}

/* The file list nftw fills (nftw takes no user pointer). */
static struct { char **path; size_t n, cap; bool oom; } found;

static int collect(const char *path, const struct stat *st, int type, struct FTW *ftw)
{
    (void)ftw;
    size_t len = strlen(path);
    if (type != FTW_F || !S_ISREG(st->st_mode) || len < 4 || strcmp(path + len - 4, ".svg")) {
        return 0;
    }
    if (found.n == found.cap) {
        size_t cap = found.cap ? found.cap * 2 : 1024;
        char **p = realloc(found.path, cap * sizeof *p);
        if (!p) {
            found.oom = true;
            return 1;
        }
        found.path = p;
        found.cap = cap;
    }
    found.path[found.n] = strdup(path);
    found.oom |= !found.path[found.n];
    return found.oom ? 1 : (found.n++, 0);
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Run argv with stdout and stderr to /dev/null; its exit status, or -1
 * when it could not be started. */
static int run_quiet(char *const argv[])
{
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
    pid_t pid;
    int rc = posix_spawnp(&pid, argv[0], &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) {
        return -1;
    }
    int status;
    if (waitpid(pid, &status, 0) < 0) {
        return -1;
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

static bool write_file(void *user, const void *data, size_t size)
{
    return fwrite(data, 1, size, user) == size;
}

/* One file in this process: render, encode, write. */
static bool render_inproc(sr_context *ctx, const char *svg, const char *png)
{
    sr_framebuffer *fb = NULL;
    sr_io_error err;
    if (sr_render_svg_file(ctx, svg, &(sr_svg_desc){ 0 }, &fb, NULL, &err) != SR_OK) {
        return false;
    }
    FILE *f = fopen(png, "wb");
    bool ok = f && sr_encode_png(write_file, f, sr_framebuffer_width(fb),
                                 sr_framebuffer_height(fb), sr_framebuffer_pixels(fb),
                                 (size_t)sr_framebuffer_width(fb) * 4, NULL, &err) == SR_OK;
    ok = f && fclose(f) == 0 && ok;
    sr_destroy_framebuffer(ctx, fb);
    return ok;
}

enum { R_INPROC, R_CLI, R_RSVG, R_COUNT };
static const char *const renderer_names[R_COUNT] = { "softrast_inproc", "softrast_svg",
                                                     "rsvg-convert" };

/* One pass of renderer r over the files; its seconds, or -1 when the
 * renderer cannot run at all.  *failed counts files it did not render. */
static double pass(int r, sr_context *ctx, char **files, size_t n, const char *png, int *failed)
{
    *failed = 0;
    double t0 = now_s();
    for (size_t i = 0; i < n; i++) {
        int rc;
        if (r == R_INPROC) {
            rc = render_inproc(ctx, files[i], png) ? 0 : 1;
        } else {
#ifdef SR_BENCH_CLI_PATH
            char *cli[] = { SR_BENCH_CLI_PATH, "svg", files[i], "-o", (char *)png, NULL };
#else
            char *cli[] = { NULL };
#endif
            char *rsvg[] = { "rsvg-convert", "-o", (char *)png, files[i], NULL };
            char *const *argv = r == R_CLI ? cli : rsvg;
            if (!argv[0]) {
                return -1;
            }
            rc = run_quiet(argv);
            if (rc < 0 && i == 0) {
                return -1;
            }
        }
        *failed += rc != 0;
    }
    return now_s() - t0;
}

bool bench_icons(int frames)
{
    const char *dir = getenv("SR_BENCH_ICONS");
    dir = dir && dir[0] ? dir : SR_BENCH_ICONS_DIR;
    /* Without expat: skipped as without the theme, naming the library. */
    if (!sr_io_have_svg()) {
        fprintf(stderr, "softrast-bench: icons: skipped: softrast was built without expat "
                        "(install libexpat1-dev and rebuild)\n");
        printf("scene=icons skipped=no-svg\n");
        fflush(stdout);
        return true;
    }
    /* No theme there: skipped, as a scene without its model is (Debian's
     * breeze-icon-theme holds the default one, scripts/install-deps.sh). */
    struct stat st;
    if (stat(dir, &st) != 0) {
        fprintf(stderr, "softrast-bench: icons: skipped: no icon theme at %s (install "
                        "breeze-icon-theme, or set SR_BENCH_ICONS to a directory of SVG files)\n",
                dir);
        printf("scene=icons skipped=missing-icons\n");
        fflush(stdout);
        return true;
    }
    found.n = 0;
    if (nftw(dir, collect, 32, FTW_PHYS) != 0 || found.oom || found.n == 0) {
        fprintf(stderr, "softrast-bench: icons: no SVG files under %s%s\n", dir,
                found.oom ? " (out of memory)" : "");
        return false;
    }
    qsort(found.path, found.n, sizeof *found.path, cmp_str);
    size_t n = 0;
    for (size_t i = 0; i < found.n; i++) {
        if (i % STRIDE == 0) {
            found.path[n++] = found.path[i];
        } else {
            free(found.path[i]);
        }
    }
    char tmp[] = "/tmp/softrast-bench-icons-XXXXXX";
    sr_context *ctx = NULL;
    bool ok = mkdtemp(tmp) && sr_make_context(&(sr_context_desc){ 0 }, &ctx) == SR_OK;
    if (!ok) {
        fprintf(stderr, "softrast-bench: icons: cannot make a temporary directory or context\n");
    }
    char png[sizeof tmp + 16];
    snprintf(png, sizeof png, "%s/out.png", tmp);
    int passes = frames < 1 ? 1 : frames > MAX_PASSES ? MAX_PASSES : frames;
    double fps[R_COUNT] = { 0 };
    for (int r = 0; ok && r < R_COUNT; r++) {
        double s[MAX_PASSES];
        int failed = 0;
        bool runs = true;
        for (int p = 0; p < passes && runs; p++) {
            s[p] = pass(r, ctx, found.path, n, png, &failed);
            runs = s[p] >= 0;
        }
        if (!runs) {
            fprintf(stderr, "softrast-bench: icons: %s cannot be started; skipped\n",
                    renderer_names[r]);
            continue;
        }
        qsort(s, (size_t)passes, sizeof *s, cmp_double);
        fps[r] = n / s[passes / 2];
        printf("scene=icons renderer=%s dir=%s files=%zu failed=%d passes=%d median_s=%.3f "
               "files_per_s=%.1f\n",
               renderer_names[r], dir, n, failed, passes, s[passes / 2], fps[r]);
        fflush(stdout);
    }
    if (ok && fps[R_RSVG] > 0) {
        printf("scene=icons files=%zu ratio_inproc=%.3f ratio_svg=%.3f\n", n,
               fps[R_INPROC] / fps[R_RSVG], fps[R_CLI] / fps[R_RSVG]);
    }
    unlink(png);
    rmdir(tmp);
    sr_destroy_context(ctx);
    for (size_t i = 0; i < n; i++) {
        free(found.path[i]);
    }
    free(found.path);
    found.path = NULL;
    found.cap = found.n = 0;
    return ok;
}
