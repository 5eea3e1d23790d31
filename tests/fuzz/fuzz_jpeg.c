/* fuzz_jpeg.c - libFuzzer target: sr_decode_jpeg on arbitrary bytes.  A
 * success must be a whole opaque picture within the limits (every pixel
 * is read, so the sanitizers see any short buffer); a failure must leave
 * no pixels, a 0 x 0 size and a message naming the input.
 * scripts/fuzz.sh fuzz_jpeg SECONDS. */
#include "softrast_io.h"

#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    int w = -1, h = -1;
    uint8_t *px = NULL;
    sr_io_error err;
    memset(&err, 0, sizeof err);
    sr_result r = sr_decode_jpeg("fuzz.jpg", data, size, &w, &h, &px, &err);
    if (r == SR_OK) {
        if (!px || w <= 0 || h <= 0 || w > 16384 || h > 16384) {
            abort();
        }
        for (size_t i = 0; i < (size_t)w * (size_t)h; i++) {
            if (px[4 * i + 3] != 255) {
                abort();
            }
        }
        free(px);
        return 0;
    }
    if (px || w != 0 || h != 0 || strncmp(err.message, "fuzz.jpg: ", 10) != 0 ||
        memchr(err.message, '\n', sizeof err.message)) {
        abort();
    }
    return 0;
}
