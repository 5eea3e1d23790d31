/* svg_color.c - the SVG reader (src/io): CSS colors (CSS Color 3 and the
 * blank-separated forms of level 4): the 147 keywords, transparent, hex with
 * or without alpha, rgb()/rgba(), hsl()/hsla().  Pure parsing; used by svg.c
 * and, as sr_io_parse_color, by programs that take a color as SVG does. */
#include "io/svg.h"
#include "io/io_util.h"
#include "io/number.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

typedef struct named_color { const char *name; unsigned rgb; } named_color;

/* Sorted by name for bsearch. */
static const named_color svg_named[] = {
    { "aliceblue", 0xf0f8ff }, { "antiquewhite", 0xfaebd7 }, { "aqua", 0x00ffff },
    { "aquamarine", 0x7fffd4 }, { "azure", 0xf0ffff }, { "beige", 0xf5f5dc },
    { "bisque", 0xffe4c4 }, { "black", 0x000000 }, { "blanchedalmond", 0xffebcd },
    { "blue", 0x0000ff }, { "blueviolet", 0x8a2be2 }, { "brown", 0xa52a2a },
    { "burlywood", 0xdeb887 }, { "cadetblue", 0x5f9ea0 }, { "chartreuse", 0x7fff00 },
    { "chocolate", 0xd2691e }, { "coral", 0xff7f50 }, { "cornflowerblue", 0x6495ed },
    { "cornsilk", 0xfff8dc }, { "crimson", 0xdc143c }, { "cyan", 0x00ffff },
    { "darkblue", 0x00008b }, { "darkcyan", 0x008b8b }, { "darkgoldenrod", 0xb8860b },
    { "darkgray", 0xa9a9a9 }, { "darkgreen", 0x006400 }, { "darkgrey", 0xa9a9a9 },
    { "darkkhaki", 0xbdb76b }, { "darkmagenta", 0x8b008b }, { "darkolivegreen", 0x556b2f },
    { "darkorange", 0xff8c00 }, { "darkorchid", 0x9932cc }, { "darkred", 0x8b0000 },
    { "darksalmon", 0xe9967a }, { "darkseagreen", 0x8fbc8f }, { "darkslateblue", 0x483d8b },
    { "darkslategray", 0x2f4f4f }, { "darkslategrey", 0x2f4f4f }, { "darkturquoise", 0x00ced1 },
    { "darkviolet", 0x9400d3 }, { "deeppink", 0xff1493 }, { "deepskyblue", 0x00bfff },
    { "dimgray", 0x696969 }, { "dimgrey", 0x696969 }, { "dodgerblue", 0x1e90ff },
    { "firebrick", 0xb22222 }, { "floralwhite", 0xfffaf0 }, { "forestgreen", 0x228b22 },
    { "fuchsia", 0xff00ff }, { "gainsboro", 0xdcdcdc }, { "ghostwhite", 0xf8f8ff },
    { "gold", 0xffd700 }, { "goldenrod", 0xdaa520 }, { "gray", 0x808080 },
    { "green", 0x008000 }, { "greenyellow", 0xadff2f }, { "grey", 0x808080 },
    { "honeydew", 0xf0fff0 }, { "hotpink", 0xff69b4 }, { "indianred", 0xcd5c5c },
    { "indigo", 0x4b0082 }, { "ivory", 0xfffff0 }, { "khaki", 0xf0e68c },
    { "lavender", 0xe6e6fa }, { "lavenderblush", 0xfff0f5 }, { "lawngreen", 0x7cfc00 },
    { "lemonchiffon", 0xfffacd }, { "lightblue", 0xadd8e6 }, { "lightcoral", 0xf08080 },
    { "lightcyan", 0xe0ffff }, { "lightgoldenrodyellow", 0xfafad2 }, { "lightgray", 0xd3d3d3 },
    { "lightgreen", 0x90ee90 }, { "lightgrey", 0xd3d3d3 }, { "lightpink", 0xffb6c1 },
    { "lightsalmon", 0xffa07a }, { "lightseagreen", 0x20b2aa }, { "lightskyblue", 0x87cefa },
    { "lightslategray", 0x778899 }, { "lightslategrey", 0x778899 }, { "lightsteelblue", 0xb0c4de },
    { "lightyellow", 0xffffe0 }, { "lime", 0x00ff00 }, { "limegreen", 0x32cd32 },
    { "linen", 0xfaf0e6 }, { "magenta", 0xff00ff }, { "maroon", 0x800000 },
    { "mediumaquamarine", 0x66cdaa }, { "mediumblue", 0x0000cd }, { "mediumorchid", 0xba55d3 },
    { "mediumpurple", 0x9370db }, { "mediumseagreen", 0x3cb371 }, { "mediumslateblue", 0x7b68ee },
    { "mediumspringgreen", 0x00fa9a }, { "mediumturquoise", 0x48d1cc }, { "mediumvioletred", 0xc71585 },
    { "midnightblue", 0x191970 }, { "mintcream", 0xf5fffa }, { "mistyrose", 0xffe4e1 },
    { "moccasin", 0xffe4b5 }, { "navajowhite", 0xffdead }, { "navy", 0x000080 },
    { "oldlace", 0xfdf5e6 }, { "olive", 0x808000 }, { "olivedrab", 0x6b8e23 },
    { "orange", 0xffa500 }, { "orangered", 0xff4500 }, { "orchid", 0xda70d6 },
    { "palegoldenrod", 0xeee8aa }, { "palegreen", 0x98fb98 }, { "paleturquoise", 0xafeeee },
    { "palevioletred", 0xdb7093 }, { "papayawhip", 0xffefd5 }, { "peachpuff", 0xffdab9 },
    { "peru", 0xcd853f }, { "pink", 0xffc0cb }, { "plum", 0xdda0dd },
    { "powderblue", 0xb0e0e6 }, { "purple", 0x800080 }, { "red", 0xff0000 },
    { "rosybrown", 0xbc8f8f }, { "royalblue", 0x4169e1 }, { "saddlebrown", 0x8b4513 },
    { "salmon", 0xfa8072 }, { "sandybrown", 0xf4a460 }, { "seagreen", 0x2e8b57 },
    { "seashell", 0xfff5ee }, { "sienna", 0xa0522d }, { "silver", 0xc0c0c0 },
    { "skyblue", 0x87ceeb }, { "slateblue", 0x6a5acd }, { "slategray", 0x708090 },
    { "slategrey", 0x708090 }, { "snow", 0xfffafa }, { "springgreen", 0x00ff7f },
    { "steelblue", 0x4682b4 }, { "tan", 0xd2b48c }, { "teal", 0x008080 },
    { "thistle", 0xd8bfd8 }, { "tomato", 0xff6347 }, { "turquoise", 0x40e0d0 },
    { "violet", 0xee82ee }, { "wheat", 0xf5deb3 }, { "white", 0xffffff },
    { "whitesmoke", 0xf5f5f5 }, { "yellow", 0xffff00 }, { "yellowgreen", 0x9acd32 },
};

static int cmp_name(const void *key, const void *elem)
{
    return strcasecmp((const char *)key, ((const named_color *)elem)->name);
}

static sr_rgba rgb24(unsigned v)
{
    return (sr_rgba){ ((v >> 16) & 255) / 255.0f, ((v >> 8) & 255) / 255.0f, (v & 255) / 255.0f,
                      1.0f };
}

/* One number of a color function, with '%' noted; blanks skipped after. */
static bool color_number(const char **s, double *v, bool *pct)
{
    while (isspace((unsigned char)**s)) {
        (*s)++;
    }
    const char *e = *s + strlen(*s);
    size_t n = sr__scan_decimal(*s, e);
    /* 1e999 overflows to infinity, clamped later like any large value. */
    if (n == 0 || sr__parse_double(*s, *s + n, v) == SR_NUM_MALFORMED) {
        return false;
    }
    *s += n;
    *pct = **s == '%';
    if (*pct) {
        (*s)++;
    } else if (strncasecmp(*s, "deg", 3) == 0) { /* hue units: deg only */
        *s += 3;
    }
    while (isspace((unsigned char)**s)) {
        (*s)++;
    }
    return true;
}

static float clamp_unit(double v)
{
    return (float)(v < 0 ? 0 : v > 1 ? 1 : v);
}

/* HSL to RGB (CSS Color 3). */
static float hue_channel(double m1, double m2, double h)
{
    h -= floor(h);
    if (h * 6 < 1) {
        return (float)(m1 + (m2 - m1) * h * 6);
    }
    if (h * 2 < 1) {
        return (float)m2;
    }
    if (h * 3 < 2) {
        return (float)(m1 + (m2 - m1) * (2.0 / 3 - h) * 6);
    }
    return (float)m1;
}

/* rgb(), rgba(), hsl(), hsla() after the '(' : three numbers and an
 * optional alpha, separated by commas, or by blanks with '/' before alpha. */
static bool color_function(const char *p, bool hsl, sr_rgba *out)
{
    double v[4] = { 0, 0, 0, 1 };
    bool pct[4] = { false, false, false, false };
    int n = 0;
    bool commas = false;
    for (;;) {
        if (n == 4 || !color_number(&p, &v[n], &pct[n])) {
            return false;
        }
        n++;
        if (*p == ')') {
            break;
        }
        if (*p == ',' && (n == 1 || commas)) {
            commas = true;
            p++;
        } else if (*p == '/' && !commas && n == 3) {
            p++;
        } else if (commas || n >= 3) {
            return false;
        }
    }
    if ((n != 3 && n != 4) || p[1] != 0) {
        return false;
    }
    float a = clamp_unit(pct[3] ? v[3] / 100 : v[3]);
    if (hsl) {
        double h = v[0] / 360, sat = clamp_unit(v[1] / 100), l = clamp_unit(v[2] / 100);
        double m2 = l <= 0.5 ? l * (sat + 1) : l + sat - l * sat, m1 = l * 2 - m2;
        *out = (sr_rgba){ hue_channel(m1, m2, h + 1.0 / 3), hue_channel(m1, m2, h),
                          hue_channel(m1, m2, h - 1.0 / 3), a };
        return true;
    }
    float c[3];
    for (int i = 0; i < 3; i++) {
        c[i] = clamp_unit(pct[i] ? v[i] / 100 : v[i] / 255);
    }
    *out = (sr_rgba){ c[0], c[1], c[2], a };
    return true;
}

svg_paint_kind svg_parse_color(const char *s, sr_rgba *out)
{
    while (isspace((unsigned char)*s)) {
        s++;
    }
    size_t n = strlen(s);
    while (n > 0 && isspace((unsigned char)s[n - 1])) {
        n--;
    }
    if (n >= 4 && strncasecmp(s, "url(", 4) == 0) {
        return SVG_PAINT_URL;
    }
    char buf[96];
    if (n == 0 || n >= sizeof buf) {
        return SVG_PAINT_INVALID;
    }
    memcpy(buf, s, n);
    buf[n] = 0;
    if (strcasecmp(buf, "none") == 0) {
        return SVG_PAINT_NONE;
    }
    if (strcasecmp(buf, "currentColor") == 0) {
        return SVG_PAINT_CURRENT;
    }
    if (strcasecmp(buf, "transparent") == 0) {
        *out = (sr_rgba){ 0, 0, 0, 0 };
        return SVG_PAINT_COLOR;
    }
    if (buf[0] == '#') {
        unsigned d[8] = { 0 };
        if (n != 4 && n != 5 && n != 7 && n != 9) {
            return SVG_PAINT_INVALID;
        }
        for (size_t i = 1; i < n; i++) {
            if (!isxdigit((unsigned char)buf[i])) {
                return SVG_PAINT_INVALID;
            }
            d[i - 1] = (unsigned)(isdigit((unsigned char)buf[i]) ? buf[i] - '0'
                                                                 : (tolower((unsigned char)buf[i]) - 'a' + 10));
        }
        float c[4] = { 0, 0, 0, 1 };
        if (n == 4 || n == 5) { /* #rgb, #rgba */
            for (size_t i = 0; i + 1 < n; i++) {
                c[i] = (float)(d[i] * 17) / 255.0f;
            }
        } else { /* #rrggbb, #rrggbbaa */
            for (size_t i = 0; 2 * i + 1 < n; i++) {
                c[i] = (float)(d[2 * i] * 16 + d[2 * i + 1]) / 255.0f;
            }
        }
        *out = (sr_rgba){ c[0], c[1], c[2], c[3] };
        return SVG_PAINT_COLOR;
    }
    static const struct { const char *prefix; bool hsl; } fns[] = {
        { "rgb(", false }, { "rgba(", false }, { "hsl(", true }, { "hsla(", true },
    };
    for (size_t i = 0; i < sizeof fns / sizeof fns[0]; i++) {
        size_t k = strlen(fns[i].prefix);
        if (strncasecmp(buf, fns[i].prefix, k) == 0) {
            return color_function(buf + k, fns[i].hsl, out) ? SVG_PAINT_COLOR : SVG_PAINT_INVALID;
        }
    }
    const named_color *nc = bsearch(buf, svg_named, sizeof svg_named / sizeof svg_named[0],
                                    sizeof svg_named[0], cmp_name);
    if (!nc) {
        return SVG_PAINT_INVALID;
    }
    *out = rgb24(nc->rgb);
    return SVG_PAINT_COLOR;
}

sr_result sr_io_parse_color(const char *text, sr_rgba *out)
{
    if (!text || !out) {
        return sr__io_message(NULL, SR_INVALID_ARG, "sr_io_parse_color: %s is NULL",
                              text ? "out" : "text");
    }
    sr_rgba c;
    if (svg_parse_color(text, &c) != SVG_PAINT_COLOR) {
        return sr__io_message(NULL, SR_BAD_FORMAT, "sr_io_parse_color: '%.100s' is not a color",
                              text);
    }
    *out = c;
    return SR_OK;
}
