/* png_none.c - io without libpng and zlib (a WebAssembly build, whose
 * toolchain has neither): PNG files are refused with SR_UNSUPPORTED, the
 * way a build without libjpeg refuses JPEG.  CMake compiles this file in
 * place of png.c and png_write.c only when it finds no libpng or zlib. */
#include "io/io_util.h"

static sr_result no_png(const char *name, sr_io_error *err)
{
    return sr__io_fail(err, SR_UNSUPPORTED, name ? name : "<memory>", 0,
                       "this build has no PNG support (install libpng-dev and zlib1g-dev "
                       "and rebuild)");
}

sr_result sr_read_png(const char *path, const sr_png_read_desc *desc, int *width,
                      int *height, uint8_t **pixels, sr_io_error *err)
{
    (void)desc;
    sr__image_outputs_clear(width, height, pixels, err);
    return no_png(path, err);
}

sr_result sr_decode_png(const char *name, const uint8_t *data, size_t size, int *width,
                        int *height, uint8_t **pixels, sr_io_error *err)
{
    (void)data;
    (void)size;
    sr__image_outputs_clear(width, height, pixels, err);
    return no_png(name, err);
}

sr_result sr_encode_png(sr_write_fn write, void *user, int width, int height,
                        const uint8_t *rgba, size_t stride, const sr_png_write_desc *desc,
                        sr_io_error *err)
{
    (void)write;
    (void)user;
    (void)width;
    (void)height;
    (void)rgba;
    (void)stride;
    (void)desc;
    return no_png(NULL, err);
}

sr_result sr_write_png(const char *path, int width, int height, const uint8_t *rgba,
                       size_t stride, const sr_png_write_desc *desc, sr_io_error *err)
{
    (void)width;
    (void)height;
    (void)rgba;
    (void)stride;
    (void)desc;
    return no_png(path, err);
}
