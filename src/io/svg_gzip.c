/* svg_gzip.c - gzip-compressed SVG (.svgz) for the SVG reader: the bytes
 * are inflated with zlib before expat reads them, no more of them than
 * the reader takes of a plain document.  Pure functions; svg.c calls them
 * for a document and for each SVG <image>. */
#include "io/svg.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef SR_HAVE_ZLIB
#include <zlib.h>
#endif

bool svg_is_gzip(const void *data, size_t size)
{
    const unsigned char *b = data;
    return size >= 2 && b[0] == 0x1f && b[1] == 0x8b;
}

#ifdef SR_HAVE_ZLIB

/* Grow *buf to hold more than `used` bytes, to at most limit + 1 (one
 * byte past the limit tells that the document is over it). */
static bool grow(unsigned char **buf, size_t *cap, size_t limit)
{
    size_t want = *cap < limit / 2 ? *cap * 2 : limit + 1;
    unsigned char *p = realloc(*buf, want);
    if (!p) {
        return false;
    }
    *buf = p;
    *cap = want;
    return true;
}

sr_result svg_gunzip(const void *data, size_t size, size_t limit, char **out, size_t *out_size,
                     char *why, size_t why_size)
{
    *out = NULL;
    *out_size = 0;
    z_stream z;
    memset(&z, 0, sizeof z);
    /* 16 + MAX_WBITS: a gzip header and trailer (CRC and length) around
     * the deflate stream, both checked. */
    if (inflateInit2(&z, 16 + MAX_WBITS) != Z_OK) {
        snprintf(why, why_size, "out of memory");
        return SR_OUT_OF_MEMORY;
    }
    size_t cap = size * 4 < 65536 ? 65536 : size * 4, used = 0;
    cap = cap > limit ? limit + 1 : cap;
    unsigned char *buf = malloc(cap);
    sr_result r = buf ? SR_OK : SR_OUT_OF_MEMORY;
    z.next_in = (unsigned char *)data;
    z.avail_in = (uInt)size;
    int zr = Z_OK;
    const char *bad = NULL;   /* what is wrong with the data, when zlib does not say */
    while (r == SR_OK) {
        if (used == cap && (cap > limit || !grow(&buf, &cap, limit))) {
            r = cap > limit ? SR_TOO_LARGE : SR_OUT_OF_MEMORY;
            break;
        }
        z.next_out = buf + used;
        z.avail_out = (uInt)(cap - used);
        zr = inflate(&z, Z_NO_FLUSH);
        used = cap - z.avail_out;
        if (zr == Z_STREAM_END) {
            /* gzip files may hold several members, read one after another
             * (as zcat does); anything else after one is not gzip. */
            if (z.avail_in == 0) {
                break;
            }
            if (!svg_is_gzip(z.next_in, z.avail_in) || inflateReset(&z) != Z_OK) {
                bad = "data after the end of the compressed stream";
                r = SR_BAD_FORMAT;
            }
        } else if (zr == Z_BUF_ERROR && used < cap) {
            bad = "it ends early: a truncated file?";   /* no input left before the end */
            r = SR_BAD_FORMAT;
        } else if (zr != Z_OK && zr != Z_BUF_ERROR) {
            r = zr == Z_MEM_ERROR ? SR_OUT_OF_MEMORY : SR_BAD_FORMAT;
        }
    }
    if (r == SR_TOO_LARGE) {
        snprintf(why, why_size, "gzip-compressed: more than the %zu MiB limit once "
                 "decompressed", limit >> 20);
    } else if (r == SR_OUT_OF_MEMORY) {
        snprintf(why, why_size, "out of memory");
    } else if (r != SR_OK) {
        snprintf(why, why_size, "gzip-compressed data that does not read (%s)",
                 bad ? bad : z.msg ? z.msg : "zlib gave no reason");
    }
    inflateEnd(&z);
    if (r != SR_OK) {
        free(buf);
        return r;
    }
    *out = (char *)buf;
    *out_size = used;
    return SR_OK;
}

#else

sr_result svg_gunzip(const void *data, size_t size, size_t limit, char **out, size_t *out_size,
                     char *why, size_t why_size)
{
    (void)data, (void)size, (void)limit;
    *out = NULL;
    *out_size = 0;
    snprintf(why, why_size, "gzip-compressed (an .svgz file), which this build cannot read "
             "(install zlib1g-dev and rebuild, or decompress it with zcat)");
    return SR_UNSUPPORTED;
}

#endif
