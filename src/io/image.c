/* image.c - an image of any kind softrast reads (io stage): PNG, JPEG
 * or WebP, told apart by the first bytes rather than the name, so a texture
 * saved as "wood.png" in JPEG form (common in downloaded models) still
 * reads; from a file, or from memory (a texture a model file embeds). */
#include "io/io_util.h"

#include <string.h>

typedef enum image_kind { IMAGE_UNKNOWN, IMAGE_PNG, IMAGE_JPEG, IMAGE_WEBP } image_kind;

static image_kind kind_of(const uint8_t *head, size_t n)
{
    static const uint8_t png_signature[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n' };
    if (n >= sizeof png_signature && memcmp(head, png_signature, sizeof png_signature) == 0) {
        return IMAGE_PNG;
    }
    if (n >= 3 && head[0] == 0xFF && head[1] == 0xD8 && head[2] == 0xFF) {
        return IMAGE_JPEG;
    }
    /* A RIFF container whose form type is WEBP. */
    if (n >= 12 && memcmp(head, "RIFF", 4) == 0 && memcmp(head + 8, "WEBP", 4) == 0) {
        return IMAGE_WEBP;
    }
    return IMAGE_UNKNOWN;
}

static sr_result unknown_kind(const char *name, size_t n, sr_io_error *err)
{
    return sr__io_fail(err, SR_BAD_FORMAT, name, 0,
                       n == 0 ? "empty file, not an image"
                              : "neither a PNG, a JPEG nor a WebP image (by its first bytes)");
}

/* The file read once and decoded from memory, as sr_read_jpeg does: no
 * second open to learn the kind, and one path for every kind. */
sr_result sr_read_image(const char *path, int *width, int *height, uint8_t **pixels,
                        sr_io_error *err)
{
    sr__image_outputs_clear(width, height, pixels, err);
    if (!path || !path[0]) {
        return sr__io_fail(err, SR_INVALID_ARG, "<null>", 0, "no file name given");
    }
    char *data;
    size_t size;
    sr_result r = sr__read_file_as(path, "an image file", &data, &size, err);
    if (r != SR_OK) {
        return r;
    }
    r = sr_decode_image(path, (const uint8_t *)data, size, width, height, pixels, err);
    sr__free_file(data, size);
    return r;
}

sr_result sr_decode_image(const char *name, const uint8_t *data, size_t size, int *width,
                          int *height, uint8_t **pixels, sr_io_error *err)
{
    sr__image_outputs_clear(width, height, pixels, err);
    if (!name) {
        name = "<memory>";
    }
    if (!data && size > 0) {
        return sr__io_fail(err, SR_INVALID_ARG, name, 0, "data must not be NULL");
    }
    switch (kind_of(data, size)) {
    case IMAGE_PNG:  return sr_decode_png(name, data, size, width, height, pixels, err);
    case IMAGE_JPEG: return sr_decode_jpeg(name, data, size, width, height, pixels, err);
    case IMAGE_WEBP: return sr__decode_webp(name, data, size, width, height, pixels, err);
    default:         return unknown_kind(name, size, err);
    }
}
