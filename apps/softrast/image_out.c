/* image_out.c - the tool's image files: a JPEG when the name ends in .jpg
 * or .jpeg (any case), else a PNG, for every command that writes one
 * (render, demo, svg, the viewer's screenshots).  Both are written
 * atomically by the io library, never over one of the command's inputs. */
#include "cli.h"
#include "softrast_io.h"

#include <string.h>
#include <strings.h>

bool cli_is_jpeg_name(const char *path)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    if (!dot || (slash && dot < slash)) {
        return false;
    }
    return strcasecmp(dot, ".jpg") == 0 || strcasecmp(dot, ".jpeg") == 0;
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
    int level = opt->png_level < 0 ? 0 : (opt->png_level == 0 ? -1 : opt->png_level);
    return sr_write_png(path, width, height, rgba, stride,
                        &(sr_png_write_desc){ .compression_level = level,
                                              .channels = opt->keep_alpha ? SR_PNG_RGBA : SR_PNG_RGB,
                                              .context = opt->context },
                        err);
}
