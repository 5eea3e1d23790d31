/* image.c - an image file of either kind softrast reads (io stage): PNG
 * or JPEG, told apart by the file's first bytes rather than its name, so
 * a texture saved as "wood.png" in JPEG form (common in downloaded
 * models) still reads. */
#include "io/io_util.h"

#include <errno.h>
#include <string.h>

static const uint8_t png_signature[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n' };

sr_result sr_read_image(const char *path, int *width, int *height, uint8_t **pixels,
                        sr_io_error *err)
{
    sr__image_outputs_clear(width, height, pixels, err);
    if (!path || !path[0]) {
        return sr__io_fail(err, SR_INVALID_ARG, "<null>", 0, "no file name given");
    }
    FILE *f;
    unsigned long long size;
    sr_result r = sr__open_regular(path, "an image file", &f, &size, err);
    if (r != SR_OK) {
        return r;
    }
    uint8_t head[8];
    size_t got = fread(head, 1, sizeof head, f);
    bool read_error = ferror(f);
    int e = errno;
    fclose(f);
    if (read_error) {
        return sr__io_fail(err, SR_IO_ERROR, path, 0, "read error: %s", strerror(e));
    }
    if (got == sizeof head && memcmp(head, png_signature, sizeof head) == 0) {
        return sr_read_png(path, width, height, pixels, err);
    }
    if (got >= 3 && head[0] == 0xFF && head[1] == 0xD8 && head[2] == 0xFF) {
        return sr_read_jpeg(path, width, height, pixels, err);
    }
    return sr__io_fail(err, SR_BAD_FORMAT, path, 0,
                       got == 0 ? "empty file, not an image"
                                : "neither a PNG nor a JPEG image (by its first bytes)");
}
