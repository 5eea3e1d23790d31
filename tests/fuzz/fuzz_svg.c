/* fuzz_svg.c - libFuzzer target: the SVG reader of `softrast svg`
 * (apps/softrast/svg.c) on arbitrary bytes, through svg_render, the same
 * entry point the command uses.  Checks, besides ASan/UBSan/LSan: either
 * an image no larger than asked for, or an exit status of 1 or 2 with one
 * non-empty line naming the document; and the work bounds of svg.h hold
 * (libFuzzer's -timeout turns a slow input into a finding).
 * scripts/fuzz.sh fuzz_svg SECONDS. */
#include "svg.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Images of at most this many pixels a side keep each input cheap; the
 * --size and --scale paths are taken by inputs whose length says so. */
#define FUZZ_MAX_SIDE 256

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void fuzz_fail(const char *what, const char *msg)
{
    fprintf(stderr, "fuzz_svg: %s: \"%s\"\n", what, msg);
    abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static sr_context *ctx;
    if (!ctx && sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) != SR_OK) {
        abort();
    }
    /* Vary the options with the input's length: the document itself stays
     * a plain SVG file, so every corpus file opens in a browser. */
    svg_options opt = { .name = "fuzz.svg", .max_side = FUZZ_MAX_SIDE,
                        .background = { 1, 1, 1, (size % 3) == 0 } };
    if (size % 5 == 1) {
        opt.size_w = 1 + (int)(size % 97);
        opt.size_h = 1 + (int)(size % 89);
    } else if (size % 5 == 2) {
        opt.scale = 0.01 + (double)(size % 7);
    }
    sr_framebuffer *fb = NULL;
    char msg[512];
    memset(msg, 'x', sizeof msg);
    int status = svg_render(ctx, (const char *)data, size, &opt, &fb, msg, sizeof msg);
    if (status == EXIT_OK) {
        if (!fb) {
            fuzz_fail("EXIT_OK without an image", "");
        }
        int w = sr_framebuffer_width(fb), h = sr_framebuffer_height(fb);
        if (w < 1 || h < 1 || w > FUZZ_MAX_SIDE || h > FUZZ_MAX_SIDE ||
            (opt.size_w && (w != opt.size_w || h != opt.size_h))) {
            fuzz_fail("image size outside what was asked", "");
        }
        sr_destroy_framebuffer(ctx, fb);
    } else {
        if (fb) {
            fuzz_fail("an image after a failure", msg);
        }
        if (status != EXIT_USAGE && status != EXIT_FAILURE_RUN) {
            fuzz_fail("unknown status", msg);
        }
        if (memchr(msg, 0, sizeof msg) == NULL || strncmp(msg, "fuzz.svg:", 9) != 0 ||
            strchr(msg, '\n') != NULL || strlen(msg) <= 10) {
            fuzz_fail("the message is not one line \"fuzz.svg:LINE: ...\"", msg);
        }
    }
    return 0;
}
