/* fuzz_svg.c - libFuzzer target: the SVG reader (src/io/svg.c) on
 * arbitrary bytes, through sr_render_svg, the entry point `softrast svg`
 * uses.  Checks, besides ASan/UBSan/LSan: either an image no larger than
 * asked for, or a failure with one non-empty line naming the document; and
 * the work stays within the budgets of softrast_io.h (libFuzzer's -timeout
 * turns a slow input into a finding).  scripts/fuzz.sh fuzz_svg SECONDS. */
#include "softrast_io.h"

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
    sr_svg_desc opt = { .name = "fuzz.svg", .max_side = FUZZ_MAX_SIDE,
                        .background = { 1, 1, 1, (size % 3) == 0 } };
    if (size % 5 == 1) {
        opt.width = 1 + (int)(size % 97);
        opt.height = 1 + (int)(size % 89);
    } else if (size % 5 == 2) {
        opt.scale = 0.01 + (double)(size % 7);
    }
    sr_framebuffer *fb = NULL;
    sr_io_error err;
    memset(err.message, 'x', sizeof err.message);
    sr_svg_info info;
    sr_result r = sr_render_svg(ctx, (const char *)data, size, &opt, &fb, &info, &err);
    const char *msg = err.message;
    if (info.points_used > info.points_budget || info.work_used > info.work_budget) {
        fuzz_fail("work beyond the budgets", msg);
    }
    if (r == SR_OK) {
        if (!fb) {
            fuzz_fail("SR_OK without an image", "");
        }
        int w = sr_framebuffer_width(fb), h = sr_framebuffer_height(fb);
        if (w < 1 || h < 1 || w > FUZZ_MAX_SIDE || h > FUZZ_MAX_SIDE ||
            (opt.width && (w != opt.width || h != opt.height))) {
            fuzz_fail("image size outside what was asked", "");
        }
        sr_destroy_framebuffer(ctx, fb);
    } else {
        if (fb) {
            fuzz_fail("an image after a failure", msg);
        }
        if (r != SR_BAD_FORMAT && r != SR_TOO_LARGE && r != SR_OUT_OF_MEMORY) {
            fuzz_fail("unexpected result", msg);
        }
        if (memchr(msg, 0, sizeof err.message) == NULL || strncmp(msg, "fuzz.svg:", 9) != 0 ||
            strchr(msg, '\n') != NULL || strlen(msg) <= 10) {
            fuzz_fail("the message is not one line \"fuzz.svg:LINE: ...\"", msg);
        }
    }
    return 0;
}
