/* svg_image.c - where the SVG reader's <image> elements come from: a
 * data: URI's base64 payload, or a file next to the document.  Pure
 * functions; the drawing is in svg.c. */
#include "io/io_util.h"
#include "io/svg.h"

#include <stdlib.h>
#include <string.h>

static int hex_digit(char c)
{
    return c >= '0' && c <= '9' ? c - '0'
           : c >= 'a' && c <= 'f' ? c - 'a' + 10
           : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
}

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
    const char *b64 = strstr(uri, ";base64");
    if (b64 && b64 < comma) {
        return sr__base64_decode(comma + 1, strlen(comma + 1), out, size) && *out;
    }
    const char *s = comma + 1;
    uint8_t *o = malloc(strlen(s) + 1);
    if (!o) {
        return false;
    }
    size_t n = 0;
    for (; *s; s++) {
        int hi, lo;
        if (*s != '%') {
            o[n++] = (uint8_t)*s;
        } else if ((hi = hex_digit(s[1])) >= 0 && (lo = hex_digit(s[2])) >= 0) {
            o[n++] = (uint8_t)(hi * 16 + lo);
            s += 2;
        } else {
            free(o);
            return false;
        }
    }
    o[n] = 0;
    *out = o;
    *size = n;
    return true;
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
    if (!path) {
        return NULL;
    }
    memcpy(path, document, dir);
    char *o = path + dir;
    for (const char *s = href; *s;) {
        size_t len = strcspn(s, "/");
        if (len > 0 && !(len == 1 && s[0] == '.')) {
            memcpy(o, s, len);
            o += len;
            if (s[len] == '/') {
                *o++ = '/';
            }
        }
        s += len + (s[len] == '/');
    }
    *o = 0;
    return path;
}
