/* image_name.c - which image format an output name asks for: JPEG for
 * .jpg or .jpeg (any case), PNG for .png or no extension; any other
 * extension is refused before the work.  Apart from image_out.c so that
 * the explain pages, which write frames their own way, check names the
 * same way as the tool. */
#include "cli.h"

#include <string.h>
#include <strings.h>

/* The extension of path's last name, from its dot; NULL if it has none
 * (a leading dot, as in ".hidden", starts a name, not an extension). */
static const char *extension(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *name = slash ? slash + 1 : path;
    const char *dot = strrchr(name, '.');
    return dot && dot > name ? dot : NULL;
}

bool cli_is_jpeg_name(const char *path)
{
    const char *dot = extension(path);
    return dot && (strcasecmp(dot, ".jpg") == 0 || strcasecmp(dot, ".jpeg") == 0);
}

bool cli_check_image_name(const char *opt, const char *path, bool jpeg_ok)
{
    const char *dot = extension(path);
    if (jpeg_ok && cli_is_jpeg_name(path) && !sr_io_have_jpeg()) {
        cli_message("%s: cannot write JPEG (softrast was built without libjpeg; install "
                    "libjpeg-dev and rebuild)", path);
        return false;
    }
    if (!dot || strcasecmp(dot, ".png") == 0 || (jpeg_ok && cli_is_jpeg_name(path))) {
        return true;
    }
    if (jpeg_ok) {
        cli_error("%s: '%s': softrast writes PNG or JPEG images, not %s (name it .png, .jpg "
                  "or .jpeg)", opt, path, dot);
    } else {
        cli_error("%s: '%s': this is written as a PNG, not %s (name it .png)", opt, path, dot);
    }
    return false;
}
