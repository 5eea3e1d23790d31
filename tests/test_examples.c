/* test_examples.c - the example programs of docs/shaders.md run and draw
 * what the text says: the toon teapot in a few flat bands with dark ink
 * at its rim, and the procedural checkerboard with crisp squares near the
 * camera that the quad-derivative filter fades to their average far
 * away. */
#include "sr_test.h"
#include "softrast_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#if defined(SR_EXAMPLE_TOON) && defined(SR_EXAMPLE_CHECKER)

static bool run(const char *exe, const char *out)
{
    pid_t pid = fork();
    if (pid == 0) {
        execl(exe, exe, out, (char *)NULL);
        _exit(127);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

SR_TEST(toon_example_draws_bands_and_ink)
{
    char out[512];
    snprintf(out, sizeof out, "%s/example-toon.png", sr_test_out_dir());
    REQUIRE(run(SR_EXAMPLE_TOON, out));
    int w, h;
    uint8_t *px;
    sr_io_error err;
    REQUIRE(sr_read_png(out, NULL, &w, &h, &px, &err) == SR_OK);
    /* Count the pixels of each band color (base x band), exactly. */
    static const float bands[] = { 1.0f, 0.65f, 0.35f, 0.05f };
    int count[4] = { 0, 0, 0, 0 }, background = 0, other = 0;
    for (int i = 0; i < w * h; i++) {
        const uint8_t *p = &px[i * 4];
        int hit = -1;
        for (int b = 0; b < 4; b++) {
            if (p[0] == (uint8_t)(bands[b] * 255.0f + 0.5f) &&
                p[1] == (uint8_t)(0.55f * bands[b] * 255.0f + 0.5f)) {
                hit = b;
            }
        }
        if (hit >= 0) {
            count[hit]++;
        } else if (p[0] == p[1] || (p[0] > 230 && p[1] > 230)) {
            background++;
        } else {
            other++;   /* multisampled edges between bands */
        }
    }
    for (int b = 0; b < 4; b++) {
        CHECK(count[b] > 1000);
    }
    CHECK(background > w * h / 3);
    /* Flat bands: the blended edge pixels are a small minority. */
    CHECK(other < (count[0] + count[1] + count[2] + count[3]) / 4);
    free(px);
}

SR_TEST(checker_example_is_crisp_near_and_filtered_far)
{
    char out[512];
    snprintf(out, sizeof out, "%s/example-checker.png", sr_test_out_dir());
    REQUIRE(run(SR_EXAMPLE_CHECKER, out));
    int w, h;
    uint8_t *px;
    sr_io_error err;
    REQUIRE(sr_read_png(out, NULL, &w, &h, &px, &err) == SR_OK);
    /* The bottom rows (near): mostly the two pure colors.  Just below the
     * horizon (far): mostly in between, no pure light squares. */
    int pure_near = 0, light_far = 0, mid_far = 0, n_near = 0, n_far = 0;
    for (int x = 0; x < w; x++) {
        for (int y = h - 20; y < h; y++) {
            int r = px[(y * w + x) * 4];
            pure_near += r <= 45 || r >= 230;
            n_near++;
        }
    }
    /* Find the horizon: the first row from the top that is not sky. */
    int horizon = 0;
    while (horizon < h && px[(horizon * w + w / 2) * 4 + 2] > 190) {
        horizon++;
    }
    REQUIRE(horizon > 10 && horizon < h - 40);
    for (int x = 0; x < w; x++) {
        for (int y = horizon + 1; y < horizon + 4; y++) {
            int r = px[(y * w + x) * 4];
            light_far += r >= 230;
            mid_far += r > 80 && r < 200;
            n_far++;
        }
    }
    CHECK(pure_near > n_near * 7 / 10);
    CHECK(light_far < n_far / 50);
    CHECK(mid_far > n_far * 8 / 10);
    free(px);
}

#else

SR_TEST(examples_not_built)
{
    SKIP("built with SR_BUILD_EXAMPLES=OFF");
}

#endif
