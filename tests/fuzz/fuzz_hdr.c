/* fuzz_hdr.c - libFuzzer target: sr_decode_hdr on arbitrary bytes.  A
 * success must be a whole picture within the limits whose every value is
 * read (so the sanitizers see any short buffer) and is a finite,
 * non-negative float; a failure must leave no pixels, a 0 x 0 size and a
 * one-line message naming the input.  scripts/fuzz.sh fuzz_hdr SECONDS. */
#include "softrast_io.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    int w = -1, h = -1;
    float *px = NULL;
    sr_io_error err;
    memset(&err, 0, sizeof err);
    sr_result r = sr_decode_hdr("fuzz.hdr", data, size, &w, &h, &px, &err);
    if (r == SR_OK) {
        if (!px || w <= 0 || h <= 0 || w > SR_HDR_MAX_SIDE || h > SR_HDR_MAX_SIDE ||
            (size_t)w * (size_t)h > SR_HDR_MAX_PIXELS) {
            abort();
        }
        for (size_t i = 0; i < 3 * (size_t)w * (size_t)h; i++) {
            if (!isfinite(px[i]) || px[i] < 0.0f) {
                abort();
            }
        }
        free(px);
        return 0;
    }
    if (px || w != 0 || h != 0 || strncmp(err.message, "fuzz.hdr: ", 10) != 0 ||
        memchr(err.message, '\n', sizeof err.message)) {
        abort();
    }
    return 0;
}
