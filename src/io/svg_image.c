/* svg_image.c - where the SVG reader's <image> elements come from: a
 * data: URI's base64 payload, or a file next to the document.  Pure
 * functions; the drawing is in svg.c. */
#include "io/io_util.h"
#include "io/svg.h"

#include <stdlib.h>
#include <string.h>

bool svg_data_uri(const char *uri, uint8_t **out, size_t *size)
{
    *out = NULL;
    *size = 0;
    if (strncmp(uri, "data:", 5) != 0) {
        return false;
    }
    const char *comma = strchr(uri, ',');
    if (!comma) {
        return false;
    }
    /* only base64 payloads: images are binary */
    const char *b64 = strstr(uri, ";base64");
    if (!b64 || b64 > comma) {
        return false;
    }
    return sr__base64_decode(comma + 1, strlen(comma + 1), out, size) && *out;
}

char *svg_image_path(const char *document, const char *href)
{
    /* A relative path inside the document's directory: no scheme, no
     * absolute path, no way up. */
    if (!href[0] || href[0] == '/' || strchr(href, ':') || strchr(href, '\\')) {
        return NULL;
    }
    for (const char *s = href; *s; s = strchr(s, '/') ? strchr(s, '/') + 1 : s + strlen(s)) {
        if (strncmp(s, "..", 2) == 0 && (s[2] == '/' || s[2] == 0)) {
            return NULL;
        }
    }
    const char *slash = strrchr(document, '/');
    size_t dir = slash ? (size_t)(slash - document + 1) : 0;
    char *path = malloc(dir + strlen(href) + 1);
    if (path) {
        memcpy(path, document, dir);
        strcpy(path + dir, href);
    }
    return path;
}
