/* text_path.c - sr_text_path (src/io, softrast_io): one line of text as
 * glyph outlines in a caller's sr_path, through the SVG reader's text
 * layout (svg_text.c) and fonts (svg_font.c): fontconfig matches the
 * family, HarfBuzz shapes, FreeType reads the outlines.  Each call makes
 * and frees its own fonts, so calls may run in parallel. */
#include "io/io_util.h"
#include "io/svg_text.h"
#include "softrast_io.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Whether s is well-formed UTF-8 (no overlong forms, surrogates or code
 * points beyond U+10FFFF); *chars counts its characters. */
static bool valid_utf8(const unsigned char *s, size_t *chars)
{
    *chars = 0;
    while (*s) {
        unsigned c = *s;
        int more = c < 0x80 ? 0 : (c & 0xE0) == 0xC0 ? 1 : (c & 0xF0) == 0xE0 ? 2
                 : (c & 0xF8) == 0xF0 ? 3 : -1;
        if (more < 0) {
            return false;
        }
        unsigned cp = more == 0 ? c : c & (0x3Fu >> more);
        for (int i = 1; i <= more; i++) {
            if ((s[i] & 0xC0) != 0x80) {
                return false;
            }
            cp = (cp << 6) | (s[i] & 0x3F);
        }
        static const unsigned least[4] = { 0, 0x80, 0x800, 0x10000 };
        if (cp < least[more] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) {
            return false;
        }
        s += more + 1;
        ++*chars;
    }
    return true;
}

static sr_result fail(sr_io_error *err, sr_result r, const char *msg)
{
    return sr__io_message(err, r, "sr_text_path: %.480s", msg);
}

bool sr_io_have_text(void)
{
    return svg_text_available();
}

sr_result sr_text_path(const char *utf8, const sr_text_desc *desc, sr_path *path,
                       double *advance, sr_io_error *err)
{
    if (advance) {
        *advance = 0;
    }
    if (err) {
        err->message[0] = 0;
    }
    sr_text_desc d = desc ? *desc : (sr_text_desc){ 0 };
    d.size = d.size == 0 ? 16 : d.size;
    d.weight = d.weight == 0 ? 400 : d.weight;
    size_t chars = 0;
    if (!utf8 || !path) {
        return fail(err, SR_INVALID_ARG, "utf8 and path must not be NULL");
    }
    if (!(d.size > 0 && d.size <= SR_MAX_COORD2D)) {
        return fail(err, SR_INVALID_ARG, "sr_text_desc.size must be in (0, SR_MAX_COORD2D]");
    }
    if (d.weight < 1 || d.weight > 1000) {
        return fail(err, SR_INVALID_ARG, "sr_text_desc.weight must be 1..1000");
    }
    if ((int)d.anchor < SR_TEXT_ANCHOR_DEFAULT || d.anchor > SR_TEXT_ANCHOR_END) {
        return fail(err, SR_INVALID_ARG, "sr_text_desc.anchor is not an sr_text_anchor");
    }
    if (!isfinite(d.x) || !isfinite(d.y) || fabs(d.x) > SR_MAX_COORD2D ||
        fabs(d.y) > SR_MAX_COORD2D) {
        return fail(err, SR_INVALID_ARG, "sr_text_desc.x and .y must be within SR_MAX_COORD2D");
    }
    if (!valid_utf8((const unsigned char *)utf8, &chars)) {
        return fail(err, SR_INVALID_ARG, "utf8 is not well-formed UTF-8");
    }
    if (chars > SR_TEXT_MAX_CHARS) {
        return fail(err, SR_TOO_LARGE, "more than SR_TEXT_MAX_CHARS characters");
    }
#ifndef SR_HAVE_SVG_TEXT
    return fail(err, SR_UNSUPPORTED, "built without fontconfig, HarfBuzz and FreeType (no text)");
#else
    svg_text_style ts = svg_text_initial();
    const char *family = d.family && *d.family ? d.family : "sans-serif";
    if (strlen(family) >= sizeof ts.family) {
        return fail(err, SR_INVALID_ARG, "sr_text_desc.family is longer than 127 bytes");
    }
    memcpy(ts.family, family, strlen(family) + 1);
    ts.size = d.size;
    ts.weight = d.weight;
    ts.slant = d.italic ? SVG_SLANT_ITALIC : SVG_SLANT_NORMAL;
    ts.anchor = d.anchor == SR_TEXT_ANCHOR_MIDDLE ? SVG_ANCHOR_MIDDLE
                : d.anchor == SR_TEXT_ANCHOR_END  ? SVG_ANCHOR_END
                                                  : SVG_ANCHOR_START;
    ts.rtl = d.rtl;
    char x[64], y[64], why[512];
    snprintf(x, sizeof x, "%.17g", d.x);
    snprintf(y, sizeof y, "%.17g", d.y);
    const char *lists[7] = { x, y, NULL, NULL, NULL, NULL, NULL };
    svg_fonts *fonts = svg_fonts_make();
    svg_text *t = svg_text_make();
    sr_result r = fonts && t ? SR_OK : SR_OUT_OF_MEMORY;
    snprintf(why, sizeof why, "out of memory");
    if (r == SR_OK && svg_text_open(t, &ts, lists, 0, 0, why, sizeof why) < 0) {
        r = SR_OUT_OF_MEMORY;
    }
    if (r == SR_OK && !svg_text_chars(t, utf8, strlen(utf8), true, true)) {
        r = SR_OUT_OF_MEMORY;
    }
    if (r == SR_OK && d.font_file) {
        svg_face *face = svg_fonts_open_file(fonts, d.font_file, why, sizeof why);
        if (!face) {
            r = strstr(why, "memory") ? SR_OUT_OF_MEMORY : SR_BAD_FORMAT;
        }
        svg_text_use_face(t, face);
    }
    if (r == SR_OK) {
        svg_text_close(t);
        r = svg_text_length(t) > 0 ? svg_text_layout(t, fonts, why, sizeof why) : SR_OK;
    }
    for (int i = 0; r == SR_OK && i < svg_text_runs(t); i++) {
        r = svg_text_run_path(t, fonts, i, path);
        if (r != SR_OK) {
            snprintf(why, sizeof why, "%s", sr_result_text(r));
        }
    }
    if (r == SR_OK && advance) {
        *advance = svg_text_advance(t);
    }
    svg_text_free(t);
    svg_fonts_free(fonts);
    return r == SR_OK ? SR_OK : fail(err, r, why);
#endif
}
