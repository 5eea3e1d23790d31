/* svg_quote.c - the SVG reader (src/io): attribute values as warnings and
 * errors quote them.  Consumes any NUL-terminated string, produces at
 * most SVG_QUOTE_CHARS of its bytes plus "..." when cut; pure, so any
 * thread may call it.  A huge tableValues or kernelMatrix still gives one
 * short line that names the file, the line and the attribute. */
#include "io/svg.h"

#include <string.h>

const char *svg_quote(const char *s, char out[SVG_QUOTE_SIZE])
{
    if (!s) {
        s = "";
    }
    size_t n = strnlen(s, SVG_QUOTE_CHARS + 1);
    if (n <= SVG_QUOTE_CHARS) {
        memcpy(out, s, n + 1);
        return out;
    }
    /* Cut before the byte at SVG_QUOTE_CHARS; back over continuation
     * bytes (10xxxxxx) so a multi-byte character is kept whole or not at
     * all.  At most 3 steps for valid UTF-8; invalid bytes stop at 4. */
    n = SVG_QUOTE_CHARS;
    for (int back = 0; back < 4 && n > 0 && ((unsigned char)s[n] & 0xC0) == 0x80; back++) {
        n--;
    }
    memcpy(out, s, n);
    memcpy(out + n, "...", sizeof "...");
    return out;
}
