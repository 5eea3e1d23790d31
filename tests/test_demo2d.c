/* test_demo2d.c - `softrast demo fill`, `demo floodfill`, `demo clip` and
 * `demo curves` end to end: the CLI renders each 2D toolkit demo at --scale 4 and the
 * image is compared with tests/ref/demo_NAME.png.
 *
 * Tolerance: a channel may be off by 2 and at most 0.5% of the pixels may
 * differ; on one machine the output is bit-exact, the slack absorbs libm
 * differences (cos, sin, acos) in the vector overlays. */
#include "image_compare.h"
#include "softrast_io.h"
#include "sr_test.h"

#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

extern char **environ;

/* Run the CLI with args (NULL-terminated, after "softrast"); exit status. */
static int run_cli(const char *const *args)
{
    const char *argv[32];
    int n = 0;
    argv[n++] = SR_CLI_PATH;
    for (int i = 0; args[i] && n < 31; i++) {
        argv[n++] = args[i];
    }
    argv[n] = NULL;
    pid_t pid;
    if (posix_spawn(&pid, SR_CLI_PATH, NULL, NULL, (char *const *)argv, environ) != 0) {
        return -1;
    }
    int status;
    if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status)) {
        return -1;
    }
    return WEXITSTATUS(status);
}

static void check_demo(const char *demo)
{
    char out[1024], name[64];
    snprintf(name, sizeof name, "demo_%s", demo);
    snprintf(out, sizeof out, "%s/%s.png", sr_test_out_dir(), name);
    int status = run_cli((const char *[]){ "demo", demo, "--scale", "4", "-o", out, NULL });
    CHECK_EQ(status, 0);
    if (status != 0) {
        return;
    }
    int w, h;
    uint8_t *px = NULL;
    sr_io_error err;
    if (sr_read_png(out, &w, &h, &px, &err) != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "reading %s: %s", out, err.message);
        return;
    }
    sr_test_check_image(name, px, w, h, 2, (long)w * h / 200);
    free(px);
}

SR_TEST(demo_fill_matches_reference) { check_demo("fill"); }
SR_TEST(demo_floodfill_matches_reference) { check_demo("floodfill"); }
SR_TEST(demo_clip_matches_reference) { check_demo("clip"); }
SR_TEST(demo_curves_matches_reference) { check_demo("curves"); }
