/* image_out.c - the tool's image files: a JPEG when the name ends in .jpg
 * or .jpeg (any case), else a PNG, for every command that writes one
 * (render, demo, svg, the viewer's screenshots; image_name.c refuses any
 * other extension before the work).  Both are written atomically by the
 * io library, never over one of the command's inputs. */
#include "cli.h"
#include "softrast_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

uint8_t *cli_straight_alpha(const uint8_t *rgba, size_t pixels)
{
    uint8_t *out = malloc(4 * pixels);
    for (size_t i = 0; out && i < pixels; i++) {
        const uint8_t *p = rgba + 4 * i;
        unsigned a = p[3];
        for (int c = 0; c < 3; c++) {
            unsigned v = a == 0 ? 0 : a == 255 ? p[c] : (p[c] * 255u + a / 2) / a;
            out[4 * i + c] = (uint8_t)(v > 255 ? 255 : v);
        }
        out[4 * i + 3] = (uint8_t)a;
    }
    return out;
}

sr_result cli_write_image(const char *path, int width, int height, const uint8_t *rgba,
                          const cli_image_options *opt, sr_io_error *err)
{
    size_t stride = 4 * (size_t)width;
    if (cli_output_is_input(opt->inputs, path, err->message, sizeof err->message)) {
        return SR_INVALID_ARG;
    }
    if (cli_is_jpeg_name(path)) {
        return sr_write_jpeg(path, width, height, rgba, stride,
                             &(sr_jpeg_write_desc){ .quality = opt->jpeg_quality }, err);
    }
    uint8_t *straight = NULL;
    if (opt->keep_alpha && opt->premultiplied) {
        straight = cli_straight_alpha(rgba, (size_t)width * (size_t)height);
        if (!straight) {
            snprintf(err->message, sizeof err->message, "%s: out of memory", path);
            return SR_OUT_OF_MEMORY;
        }
    }
    int level = opt->png_level < 0 ? 0 : (opt->png_level == 0 ? -1 : opt->png_level);
    sr_result r = sr_write_png(path, width, height, straight ? straight : rgba, stride,
                               &(sr_png_write_desc){ .compression_level = level,
                                                     .channels = opt->keep_alpha ? SR_PNG_RGBA
                                                                                 : SR_PNG_RGB,
                                                     .context = opt->context },
                               err);
    free(straight);
    return r;
}
