/* webp.c - WebP images in (io stage), through libwebp's decoder: lossy
 * and lossless, with or without alpha, to malloc'd RGBA8 (alpha 255 where
 * the image has none).  glTF's EXT_texture_webp and any texture
 * sr_decode_image meets (an OBJ's map_Kd) come here.  An animation is
 * refused: a texture is one picture.  Reentrant: libwebp keeps no state
 * between calls. */
#include "io/io_util.h"

#include <stdlib.h>

#ifdef SR_HAVE_WEBP_DECODE

#include <webp/decode.h>

bool sr__io_have_webp(void)
{
    return true;
}

static const char *status_text(VP8StatusCode s)
{
    switch (s) {
    case VP8_STATUS_OUT_OF_MEMORY:       return "out of memory";
    case VP8_STATUS_UNSUPPORTED_FEATURE: return "a feature libwebp does not decode";
    case VP8_STATUS_NOT_ENOUGH_DATA:     return "truncated";
    default:                             return "damaged data";
    }
}

sr_result sr__decode_webp(const char *name, const uint8_t *data, size_t size, int *width,
                          int *height, uint8_t **pixels, sr_io_error *err)
{
    sr_result args = sr__decode_args(&name, data, size, width, height, pixels, err);
    if (args != SR_OK) {
        return args;
    }
    WebPBitstreamFeatures f;
    VP8StatusCode s = WebPGetFeatures(data, size, &f);
    if (s != VP8_STATUS_OK) {
        return sr__io_fail(err, s == VP8_STATUS_OUT_OF_MEMORY ? SR_OUT_OF_MEMORY : SR_BAD_FORMAT,
                           name, 0, "corrupt WebP: %s", status_text(s));
    }
    if (f.has_animation) {
        return sr__io_fail(err, SR_UNSUPPORTED, name, 0,
                           "an animated WebP, not one picture (a texture takes one)");
    }
    /* WebP's own limit is 16383 a side: RGBA8 at most 1 GiB, as for PNG. */
    size_t stride = (size_t)f.width * 4, n = stride * (size_t)f.height;
    uint8_t *out = f.width > 0 && f.height > 0 ? malloc(n) : NULL;
    if (!out) {
        return sr__io_fail(err, SR_OUT_OF_MEMORY, name, 0, "out of memory for a %dx%d WebP",
                           f.width, f.height);
    }
    if (!WebPDecodeRGBAInto(data, size, out, n, (int)stride)) {
        free(out);
        return sr__io_fail(err, SR_BAD_FORMAT, name, 0,
                           "corrupt WebP: its %dx%d picture does not decode (truncated or "
                           "damaged data)",
                           f.width, f.height);
    }
    *width = f.width;
    *height = f.height;
    *pixels = out;
    return SR_OK;
}

#else /* !SR_HAVE_WEBP_DECODE */

bool sr__io_have_webp(void)
{
    return false;
}

sr_result sr__decode_webp(const char *name, const uint8_t *data, size_t size, int *width,
                          int *height, uint8_t **pixels, sr_io_error *err)
{
    sr_result args = sr__decode_args(&name, data, size, width, height, pixels, err);
    if (args != SR_OK) {
        return args;
    }
    return sr__io_fail(err, SR_UNSUPPORTED, name, 0,
                       "a WebP image, which cannot be read (softrast was built without "
                       "libwebp; install libwebp-dev and rebuild)");
}

#endif
