/* svg.c - the SVG reader (src/io, softrast_io): renders a subset of SVG
 * 1.1, held in memory or in a file, with the 2D toolkit (sr_render_svg,
 * softrast_io.h); `softrast svg` (apps/softrast/svg_cmd.c) is the command
 * around it.
 *
 * The document is read with expat into a tree (so that ids, defs and
 * <style> sheets anywhere apply everywhere); the root <svg> fixes the
 * image size and the viewBox mapping, then the tree is drawn depth first
 * with the transform and the cascaded style (presentation attributes,
 * sheets by specificity, style="", !important) inherited down.  Shapes
 * become paths in user units (flattened finely enough for the current
 * scale), then the fill polygon or the stroke outline is mapped to pixels
 * and filled: antialiased by exact area coverage, or aliased by the
 * edge-table fill under shape-rendering="crispEdges"; a gradient paints
 * after the same coverage (sr_fill_polygon_paint).
 *
 * Supported: see the table in docs/draw2d.md.  Group opacity and clip
 * paths draw the element into a layer of its own, composited after.
 * Anything else is skipped with one warning per name.
 * Malformed XML or numbers, and drawings beyond the limits of
 * softrast_io.h (bounded work): one line "NAME:LINE: what is wrong" in the
 * sr_io_error and no image; path data in error is drawn up to the error,
 * as SVG asks, with a warning.  Warnings go to the caller's callback.
 * One document per call; nothing global, so calls may run in parallel on
 * different contexts. */
#include "io/svg.h"
#include "io/io_util.h"
#include "io/svg_text.h"
#include "io/number.h"
#include "math/affine2.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#ifdef SR_HAVE_EXPAT

#include <expat.h>

#define MAX_DEPTH 256
#define MAX_WARNED 64
#define MAX_WINDOWS 8
/* Layers (group opacity, clip paths) nested deeper than this fold their
 * opacity into the shapes and draw unclipped, with a warning: each layer
 * is a whole image of memory. */
#define MAX_LAYERS 8

/* x' = a x + c y + e, y' = b x + d y + f (SVG's matrix(a b c d e f)). */
typedef struct mat2d { double a, b, c, d, e, f; } mat2d;

static const mat2d IDENTITY = { 1, 0, 0, 1, 0, 0 };

static mat2d mat_mul(mat2d m, mat2d n) /* m * n: n applied first */
{
    return (mat2d){ m.a * n.a + m.c * n.b, m.b * n.a + m.d * n.b,
                    m.a * n.c + m.c * n.d, m.b * n.c + m.d * n.d,
                    m.a * n.e + m.c * n.f + m.e, m.b * n.e + m.d * n.f + m.f };
}

static sr_point2 mat_apply(mat2d m, sr_point2 p)
{
    return (sr_point2){ m.a * p.x + m.c * p.y + m.e, m.b * p.x + m.d * p.y + m.f };
}

/* A fill or stroke: none, a color, currentColor or a paint server. */
typedef struct paint {
    svg_paint_kind kind;
    sr_rgba color;               /* SVG_PAINT_COLOR; a server's fallback */
    bool has_fallback;           /* url(#id) followed by a color */
    const svg_node *server;      /* SVG_PAINT_URL */
} paint;

typedef struct style {
    paint fill, stroke;
    sr_rgba color;               /* the color property, for currentColor */
    sr_rgba stop_color;          /* of a gradient stop (not inherited) */
    double stop_opacity;
    double fill_opacity, stroke_opacity;
    double opacity;              /* the ancestors' opacities folded into shapes */
    double own_opacity;          /* this element's opacity (not inherited) */
    const svg_node *clip;        /* clip-path (not inherited), or NULL */
    const svg_node *mask;        /* mask (not inherited), or NULL */
    bool mask_alpha;             /* mask-type: alpha (of a mask element) */
    sr_fill_rule clip_rule;
    sr_fill_rule fill_rule;
    double stroke_width;
    sr_stroke_join join;
    sr_stroke_cap cap;
    double miter_limit;
    double dash[SVG_MAX_DASHES]; /* stroke-dasharray, even count; 0: solid */
    int n_dash;
    unsigned dash_pct;           /* bit i: dash[i] is a percentage */
    double dash_offset;
    bool dash_offset_pct;
    bool non_scaling;            /* vector-effect: non-scaling-stroke (not inherited) */
    double origin[2];            /* transform-origin (not inherited) */
    svg_blend_kind blend;        /* mix-blend-mode (not inherited) */
    bool isolate;                /* isolation: isolate (not inherited) */
    bool overflow_visible;       /* overflow: visible or auto (not inherited; markers, svg) */
    unsigned origin_pct;         /* bit i: origin[i] is a fraction of the viewport */
    const svg_node *marker[3];   /* marker-start, -mid, -end, or NULL */
    unsigned char paint_order[3];/* PAINT_FILL, PAINT_STROKE, PAINT_MARKERS in turn */
    bool crisp;
    bool display_none;       /* display="none" here or on an ancestor */
    bool invisible;          /* visibility (inherited, children may undo it) */
    const svg_node *filter;  /* filter: url(#id) (not inherited), or NULL */
    bool filter_missing;     /* filter names no <filter>: the element is not drawn */
    sr_rgba flood_color;     /* flood-color (not inherited) */
    sr_rgba lighting_color;  /* lighting-color (not inherited) */
    double flood_opacity;    /* flood-opacity (not inherited) */
    bool filters_srgb;       /* color-interpolation-filters: sRGB (else linearRGB) */
    svg_text_style text;     /* font and text properties (svg_text.h) */
} style;

enum { PAINT_FILL, PAINT_STROKE, PAINT_MARKERS };

/* A vertex of a path for markers: its point in the flattened polygon and
 * its subpath; 'M' starts a subpath, 'Z' closes one (at its first point),
 * 'L' ends any other command. */
typedef struct svg_vertex {
    int at, contour;
    char kind;
} svg_vertex;

typedef struct frame {
    mat2d m;
    style st;
    double vp_w, vp_h;           /* the viewport, for percentages */
} frame;

/* An id and its element, in a table sorted by id. */
typedef struct id_entry {
    const char *id;
    svg_node *node;
} id_entry;

typedef struct svg_doc {
    const char *file;        /* name in messages */
    const char *base;        /* the path image files are read next to, or NULL */
    unsigned long pinned_line; /* nonzero: the line messages name (an SVG image from a
                                * data: URI, whose own lines are not the file's) */
    struct svg_doc *outer;   /* the document whose <image> this one is, or NULL */
    int nesting;             /* documents outside this one */
    const sr_svg_desc *opt;
    XML_Parser parser;
    sr_context *ctx;
    sr_framebuffer *fb;
    svg_node *root;
    svg_node *open;          /* the element being read */
    int depth;               /* of the element being read */
    size_t nodes;            /* read so far */
    id_entry *ids;           /* sorted by id after reading */
    size_t n_ids;
    svg_css_sheet sheet;
    long match_work;         /* selector matching steps so far */
    int draw_depth;          /* elements drawn inside each other, uses included */
    int layers;              /* layers open (group opacity, clip paths) */
    uint64_t layer_bytes;    /* what they hold (layer_cost), against opt->max_layer_bytes */
    bool over_layer_limit;   /* a layer failed the render for max_layer_bytes */
    mat2d root_m;            /* the outermost viewport's user space to pixels */
    sr_point2 windows[MAX_WINDOWS][4]; /* markers' viewports in pixels: fills clip to them */
    int n_windows;
    const style *inherit_from; /* the parent's style while an element cascades */
    style initial;           /* the initial style, for mask content */
    sr_result status;        /* SR_OK until something fails */
    char *msg;               /* the failure's line goes here */
    size_t msg_size;
    char *warned[MAX_WARNED];
    int n_warned;
    bool warnings_capped;    /* "further warnings not shown" was said */
    int warnings;            /* given so far */
    unsigned long line;      /* of the element being handled */
    /* Lines counted here, up to byte line_at of `text` (the document's
     * bytes; NULL when expat counts them: UTF-16 input). */
    const char *text;
    bool text_has_cr;        /* a CR anywhere in text: the scan looks at every byte */
    size_t text_size, line_at;
    unsigned long lines_before;
    sr_path *spare_path;     /* a cleared shape path kept for the next shape, or NULL */
    double spare_tol;        /* the flattening tolerance it was made with */
    double cull_reach;       /* sr_path_cull_curves for the shape drawn; < 0: off */
    svg_vertex *verts;       /* of the path being read, when want_verts */
    int n_verts, cap_verts;
    bool want_verts;
    /* Bounded work (softrast_io.h): what the document has used so far. */
    double points_used, points_budget;
    double work_used, work_budget;
    /* The last pattern tile drawn and what it was drawn from: the next
     * fill with the same pattern, map and size reuses its pixels. */
    sr_framebuffer *tile;
    const svg_node *tile_pattern;
    mat2d tile_m;
    double tile_vp[2];
    /* The last gradient resolved for a shape (malloc'd) and its element:
     * the next shape painted with the same element keeps its stops. */
    svg_gradient *grad;
    const svg_node *grad_server;
    const struct frame *filter_frame; /* of the filter being run (feImage draws in it) */
    int filter_size[2];      /* the size of its layer */
    svg_fonts *fonts;        /* the faces the text matched, made on first use */
    const sr_polygon2 *paint_box; /* what paints measure instead of the shape (a whole
                                   * text, drawn a run at a time), or NULL */
} svg_doc;

/* ---- messages -------------------------------------------------------------- */

static unsigned long msg_line(const svg_doc *doc)
{
    return doc->pinned_line ? doc->pinned_line : doc->line;
}

static void svg_fail(svg_doc *doc, sr_result status, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Control bytes in a message as '?', as the model readers write them: the
 * file's name and the quoted text are the input's, and a newline or an
 * escape sequence would break the one line or reach the terminal. */
static void one_line(char *s)
{
    for (unsigned char *c = (unsigned char *)s; *c; c++) {
        if (*c < 0x20 || *c == 0x7f) {
            *c = '?';
        }
    }
}

/* Record the first failure as "FILE:LINE: ..." and stop the parser. */
static void svg_fail(svg_doc *doc, sr_result status, const char *fmt, ...)
{
    if (doc->status != SR_OK) {
        return;
    }
    int n = snprintf(doc->msg, doc->msg_size, "%s:%lu: ", doc->file, msg_line(doc));
    if (n >= 0 && (size_t)n < doc->msg_size) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(doc->msg + n, doc->msg_size - (size_t)n, fmt, ap);
        va_end(ap);
    }
    if (doc->msg) {
        one_line(doc->msg);
    }
    doc->status = status;
    if (doc->parser) {
        XML_StopParser(doc->parser, XML_FALSE);
    }
}

/* A library call failed: out of memory is the run's failure, anything
 * else (a non-finite or out-of-range coordinate) the document's. */
static void lib_fail(svg_doc *doc, sr_result r)
{
    svg_fail(doc, r == SR_OUT_OF_MEMORY ? SR_OUT_OF_MEMORY : SR_BAD_FORMAT, "%s",
             sr_context_error(doc->ctx));
}

/* "FILE:LINE: warning: TEXT", once per key.  After MAX_WARNED different
 * keys, one last line says the rest are not shown: a document of a
 * million unknown elements gets 65 lines, not a million. */
static void warn_keyed(svg_doc *doc, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static void warn_keyed(svg_doc *doc, const char *key, const char *fmt, ...)
{
    /* an SVG image's warnings count once for the whole drawing */
    svg_doc *top = doc;
    while (top->outer) {
        top = top->outer;
    }
    const char *file = doc->file;
    unsigned long at = msg_line(doc);
    doc = top;
    if (doc->warnings_capped) {
        return;
    }
    for (int i = 0; i < doc->n_warned; i++) {
        if (strcmp(doc->warned[i], key) == 0) {
            return;
        }
    }
    char line[8192]; /* a file name of PATH_MAX and the message */
    if (doc->n_warned == MAX_WARNED) {
        snprintf(line, sizeof line,
                 "%s:%lu: warning: more unsupported names; further warnings not shown",
                 file, at);
        doc->warnings_capped = true;
    } else {
        doc->warned[doc->n_warned] = strdup(key);
        if (doc->warned[doc->n_warned]) {
            doc->n_warned++;
        }
        int n = snprintf(line, sizeof line, "%s:%lu: warning: ", file, at);
        if (n >= 0 && (size_t)n < sizeof line) {
            va_list ap;
            va_start(ap, fmt);
            vsnprintf(line + n, sizeof line - (size_t)n, fmt, ap);
            va_end(ap);
        }
    }
    doc->warnings++;
    one_line(line);
    if (doc->opt->warn) {
        doc->opt->warn(doc->opt->warn_user, line);
    }
}

/* "FILE:LINE: warning: unsupported KIND 'NAME' skipped", once per name. */
static void warn_once(svg_doc *doc, const char *kind, const char *name)
{
    char key[128];
    snprintf(key, sizeof key, "%.60s %.60s", kind, name);
    warn_keyed(doc, key, "unsupported %s '%s' skipped", kind, SVG_QUOTED(name));
}

/* ---- numbers, lengths, lists ----------------------------------------------------- */

/* A length of geometry (svg_parse_length; SVG 2 reads presentation
 * attributes as CSS too: 20PX, 1In): em and ex of a 16 px font, as
 * before text was drawn (font-size is read for text only). */
static bool parse_length(const char *s, double *out, bool *percent)
{
    return svg_parse_length(s, 16, out, percent);
}

/* A length attribute of a shape; false after reporting a malformed one.
 * Percentages are of the viewport's width (x, width, cx, rx, x1, x2), its
 * height (y, ...) or its normalized diagonal (r and the rest). */
static bool length_attr(svg_doc *doc, const frame *f, const char *name, const char *value,
                        double *out)
{
    if (!value) {
        *out = 0;
        return true;
    }
    bool pct = false;
    if (!parse_length(value, out, &pct)) {
        svg_fail(doc, SR_BAD_FORMAT, "%s=\"%s\" is not a length", name, SVG_QUOTED(value));
        return false;
    }
    if (pct) {
        double ref = sqrt((f->vp_w * f->vp_w + f->vp_h * f->vp_h) / 2);
        if (name[0] == 'x' || strcmp(name, "width") == 0 || strcmp(name, "cx") == 0 ||
            strcmp(name, "rx") == 0) {
            ref = f->vp_w;
        } else if (name[0] == 'y' || strcmp(name, "height") == 0 || strcmp(name, "cy") == 0 ||
                   strcmp(name, "ry") == 0) {
            ref = f->vp_h;
        }
        *out *= ref / 100;
    }
    return true;
}

static const char *attr(const char **atts, const char *name)
{
    /* the first letters differ for most attributes: no call for those */
    for (int i = 0; atts[i]; i += 2) {
        if (atts[i][0] == name[0] && strcmp(atts[i], name) == 0) {
            return atts[i + 1];
        }
    }
    return NULL;
}

/* ---- transforms ------------------------------------------------------------- */

static bool parse_transform(const char *s, mat2d *out)
{
    mat2d m = IDENTITY;
    s = svg_skip_ws(s);
    while (*s) {
        static const char *names[] = { "matrix", "translate", "scale", "rotate", "skewX", "skewY" };
        int which = -1;
        for (int i = 0; i < 6; i++) {
            size_t n = strlen(names[i]);
            if (strncmp(s, names[i], n) == 0) {
                which = i;
                s += n;
                break;
            }
        }
        if (which < 0) {
            return false;
        }
        s = svg_skip_ws(s);
        if (*s++ != '(') {
            return false;
        }
        double v[6];
        int n = 0;
        s = svg_skip_ws(s);
        while (*s != ')') {
            if (n == 6 || !svg_parse_number(&s, &v[n])) {
                return false;
            }
            n++;
            s = svg_skip_ws_comma(s);
        }
        s++;
        mat2d t = IDENTITY;
        switch (which) {
        case 0:
            if (n != 6) {
                return false;
            }
            t = (mat2d){ v[0], v[1], v[2], v[3], v[4], v[5] };
            break;
        case 1:
            if (n != 1 && n != 2) {
                return false;
            }
            t.e = v[0];
            t.f = n == 2 ? v[1] : 0;
            break;
        case 2:
            if (n != 1 && n != 2) {
                return false;
            }
            t.a = v[0];
            t.d = n == 2 ? v[1] : v[0];
            break;
        case 3: {
            if (n != 1 && n != 3) {
                return false;
            }
            double r = v[0] * M_PI / 180, c = cos(r), si = sin(r);
            t = (mat2d){ c, si, -si, c, 0, 0 };
            if (n == 3) { /* rotate about (cx, cy) */
                mat2d to = { 1, 0, 0, 1, v[1], v[2] }, back = { 1, 0, 0, 1, -v[1], -v[2] };
                t = mat_mul(mat_mul(to, t), back);
            }
            break;
        }
        case 4:
            if (n != 1) {
                return false;
            }
            t.c = tan(v[0] * M_PI / 180);
            break;
        default:
            if (n != 1) {
                return false;
            }
            t.b = tan(v[0] * M_PI / 180);
            break;
        }
        m = mat_mul(m, t);
        s = svg_skip_ws_comma(s);
    }
    *out = m;
    return true;
}

/* ---- style properties --------------------------------------------------------- */

static bool parse_unit_number(const char *v, double *out)
{
    v = svg_skip_ws(v);
    return svg_parse_number(&v, out) && *svg_skip_ws(v) == 0;
}

static double clamp01(double v)
{
    return v < 0 ? 0 : v > 1 ? 1 : v;
}

/* Properties this reader knows it does not support. */
static const char *const unsupported_props[] = {
    "fill-paint", NULL,
};

/* Properties that change nothing this reader draws (rendering hints,
 * filter and text settings), taken silently; and properties whose value
 * here is their initial one, which the reader does already. */
static const char *const no_effect_props[] = {
    "image-rendering", "color-interpolation", "color-rendering",
    "text-rendering", "enable-background", "solid-color", "solid-opacity",
    "font", "letter-spacing", "word-spacing", "line-height", "writing-mode", "direction",
    "baseline-shift", "dominant-baseline", "alignment-baseline", "white-space", "inline-size",
    "shape-padding", "shape-margin", "shape-inside", "block-progression",
    "clip",
    /* removed by SVG 2, and ignored by Chromium, rsvg-convert and resvg:
     * drawn as they draw it (docs/draw2d.md) */
    "glyph-orientation-horizontal", NULL,
};

static const struct { const char *name, *value; } initial_values[] = {
    { "filter", "none" },

};

static svg_node *find_id(const svg_doc *doc, const char *id);

/* The target of "#id" (an href) or "url(#id)" (a paint, a clip), the
 * rest of the value after it in *rest; NULL when there is none. */
static svg_node *reference(const svg_doc *doc, const char *v, const char **rest)
{
    v = svg_skip_ws(v);
    bool url = strncmp(v, "url(", 4) == 0;
    if (url) {
        v = svg_skip_ws(v + 4);
        if (*v == '\'' || *v == '"') {
            v++;
        }
    }
    if (*v != '#') {
        return NULL;
    }
    v++;
    char id[256];
    size_t n = 0;
    while (v[n] && n + 1 < sizeof id &&
           (url ? v[n] != ')' && v[n] != '\'' && v[n] != '"' && !isspace((unsigned char)v[n])
                : !isspace((unsigned char)v[n]))) {
        id[n] = v[n];
        n++;
    }
    id[n] = 0;
    v += n;
    if (url) {
        while (*v && *v != ')') {
            v++;
        }
        v += *v == ')';
    }
    if (rest) {
        *rest = svg_skip_ws(v);
    }
    return find_id(doc, id);
}

static bool is_gradient(const svg_node *n)
{
    return n && (strcmp(n->name, "linearGradient") == 0 || strcmp(n->name, "radialGradient") == 0);
}

/* fill or stroke: a color, none, currentColor or url(#id) [fallback]. */
static void parse_paint(svg_doc *doc, paint *p, const char *v)
{
    sr_rgba c;
    switch (svg_parse_color(v, &c)) {
    case SVG_PAINT_NONE:
        *p = (paint){ .kind = SVG_PAINT_NONE };
        break;
    case SVG_PAINT_COLOR:
        *p = (paint){ .kind = SVG_PAINT_COLOR, .color = c };
        break;
    case SVG_PAINT_CURRENT:
        *p = (paint){ .kind = SVG_PAINT_CURRENT };
        break;
    case SVG_PAINT_URL: {
        const char *rest = "";
        svg_node *server = reference(doc, v, &rest);
        paint fallback = { .kind = SVG_PAINT_NONE };
        if (*rest) {
            svg_paint_kind k = svg_parse_color(rest, &c);
            fallback = (paint){ .kind = k == SVG_PAINT_COLOR || k == SVG_PAINT_CURRENT ? k
                                                                                 : SVG_PAINT_NONE,
                                .color = c };
        }
        if (is_gradient(server) || (server && strcmp(server->name, "pattern") == 0)) {
            *p = (paint){ .kind = SVG_PAINT_URL, .server = server,
                          .has_fallback = fallback.kind == SVG_PAINT_COLOR, .color = fallback.color };
        } else {
            if (server) {
                warn_once(doc, "paint server", server->name);
            }
            *p = fallback; /* a missing server: the fallback, else none */
        }
        break;
    }
    default:
        warn_once(doc, "color", v);
        break;
    }
}

/* stroke-dasharray: none, or lengths and percentages separated by commas
 * or blanks, repeated once when their count is odd; false when malformed
 * or negative (the declaration is then ignored). */
static bool parse_dasharray(const char *v, style *st)
{
    if (strcmp(v, "none") == 0) {
        st->n_dash = 0;
        return true;
    }
    double d[SVG_MAX_DASHES];
    unsigned pct_bits = 0;
    int n = 0;
    double sum = 0;
    const char *s = svg_skip_ws(v);
    while (*s) {
        const char *e = s;
        while (*e && *e != ',' && !isspace((unsigned char)*e)) {
            e++;
        }
        char item[64];
        bool pct;
        if (n == SVG_MAX_DASHES / 2 || (size_t)(e - s) >= sizeof item) {
            return false;
        }
        memcpy(item, s, (size_t)(e - s));
        item[e - s] = 0;
        if (!parse_length(item, &d[n], &pct) || !(d[n] >= 0) || !isfinite(d[n])) {
            return false;
        }
        pct_bits |= pct ? 1u << n : 0;
        sum += d[n++];
        s = svg_skip_ws_comma(e);
    }
    if (n == 0) {
        return false;
    }
    int total = n % 2 ? 2 * n : n;
    for (int i = 0; i < total; i++) {
        st->dash[i] = d[i % n];
        if (pct_bits & 1u << (i % n)) {
            pct_bits |= 1u << i;
        }
    }
    st->n_dash = sum > 0 ? total : 0; /* all zero: a solid stroke */
    st->dash_pct = pct_bits;
    return true;
}

/* transform-origin: one or two of a length, a percentage (of the
 * viewport), left, center, right, top, bottom (a third value, the z
 * offset, must be 0); false when malformed. */
static bool parse_origin(const char *v, style *st)
{
    double o[2] = { 0.5, 0.5 };
    unsigned pct = 3;
    int n = 0, axis_of[2] = { -1, -1 };
    const char *s = svg_skip_ws(v);
    while (*s && n < 3) {
        size_t len = strcspn(s, " \t\r\n");
        char item[64];
        if (len >= sizeof item) {
            return false;
        }
        memcpy(item, s, len);
        item[len] = 0;
        s = svg_skip_ws(s + len);
        static const struct { const char *word; int axis; double at; } words[] = {
            { "left", 0, 0 }, { "right", 0, 1 }, { "top", 1, 0 }, { "bottom", 1, 1 },
            { "center", -1, 0.5 },
        };
        int axis = n; /* a length: x first, then y */
        double at;
        bool is_pct = true, word = false;
        for (size_t i = 0; i < sizeof words / sizeof words[0]; i++) {
            if (strcmp(item, words[i].word) == 0) {
                axis = words[i].axis < 0 ? (n == 1 && axis_of[0] == 1 ? 0 : n) : words[i].axis;
                at = words[i].at;
                word = true;
            }
        }
        if (!word) {
            if (n == 2) { /* the z offset: only 0 means anything here */
                return parse_length(item, &at, NULL) && at == 0;
            }
            if (!parse_length(item, &at, &is_pct)) {
                return false;
            }
            at = is_pct ? at / 100 : at;
        }
        if (n == 2 || axis > 1 || (axis_of[0] == axis && n == 1)) {
            return false;
        }
        o[axis] = at;
        pct = is_pct ? pct | 1u << axis : pct & ~(1u << axis);
        axis_of[n++] = axis;
    }
    if (n == 0 || *s) {
        return false;
    }
    memcpy(st->origin, o, sizeof o);
    st->origin_pct = pct;
    return true;
}

/* paint-order: normal, or some of fill, stroke, markers (the missing ones
 * follow in that order); false when malformed. */
static bool parse_paint_order(const char *v, style *st)
{
    static const char *const names[3] = { "fill", "stroke", "markers" };
    unsigned char order[3];
    int n = 0;
    unsigned seen = 0;
    const char *s = svg_skip_ws(v);
    if (strcmp(s, "normal") == 0) {
        s += 6;
    }
    while (*s) {
        int k = -1;
        for (int i = 0; i < 3; i++) {
            size_t len = strlen(names[i]);
            if (strncmp(s, names[i], len) == 0 &&
                (s[len] == 0 || isspace((unsigned char)s[len]))) {
                k = i;
                s = svg_skip_ws(s + len);
                break;
            }
        }
        if (k < 0 || seen & 1u << k) {
            return false;
        }
        seen |= 1u << k;
        order[n++] = (unsigned char)k;
    }
    for (int i = 0; i < 3; i++) {
        if (!(seen & 1u << i)) {
            order[n++] = (unsigned char)i;
        }
    }
    memcpy(st->paint_order, order, sizeof order);
    return true;
}

/* A color property (stop-color, flood-color): a color or currentColor. */
static void color_property(svg_doc *doc, const style *st, const char *name, const char *v,
                           sr_rgba *out)
{
    sr_rgba c;
    svg_paint_kind k = svg_parse_color(v, &c);
    if (k == SVG_PAINT_COLOR || k == SVG_PAINT_CURRENT) {
        *out = k == SVG_PAINT_COLOR ? c : st->color;
    } else {
        warn_once(doc, name, v);
    }
}

/* An opacity property (stop-opacity, flood-opacity), clamped to 0..1. */
static void unit_property(svg_doc *doc, const char *name, const char *v, double *out)
{
    double num;
    if (parse_unit_number(v, &num)) {
        *out = clamp01(num);
    } else {
        warn_once(doc, name, v);
    }
}

/* filter, flood-color, flood-opacity, lighting-color,
 * color-interpolation-filters. */
static void filter_property(svg_doc *doc, style *st, const char *name, const char *v)
{
    if (strcmp(name, "filter") == 0) {
        svg_node *fl = strcmp(v, "none") == 0 ? NULL : reference(doc, v, NULL);
        st->filter = fl && strcmp(fl->name, "filter") == 0 ? fl : NULL;
        st->filter_missing = false;
        if (!st->filter && strncmp(svg_skip_ws(v), "url(", 4) == 0) {
            /* SVG 1.1 and resvg: not drawn (rsvg-convert draws it unfiltered) */
            warn_once(doc, "filter reference (element not drawn)", v);
            st->filter_missing = true;
        } else if (!st->filter && strcmp(v, "none") != 0) {
            warn_once(doc, "filter", v); /* CSS filter functions: drawn unfiltered */
        }
    } else if (strcmp(name, "flood-color") == 0) {
        color_property(doc, st, name, v, &st->flood_color);
    } else if (strcmp(name, "lighting-color") == 0) {
        color_property(doc, st, name, v, &st->lighting_color);
    } else if (strcmp(name, "flood-opacity") == 0) {
        unit_property(doc, name, v, &st->flood_opacity);
    } else if (strcmp(v, "sRGB") == 0 || strcmp(v, "linearRGB") == 0 || strcmp(v, "auto") == 0) {
        st->filters_srgb = v[0] == 's';
    } else {
        warn_once(doc, name, v);
    }
}

/* Apply one property to a style.  Returns false only when the property
 * name is not a presentation property at all (so shapes may consume it). */
static bool apply_property(svg_doc *doc, style *st, const char *name, const char *value)
{
    while (isspace((unsigned char)*value)) {
        value++;
    }
    char v[256];
    size_t n = strlen(value);
    while (n > 0 && isspace((unsigned char)value[n - 1])) {
        n--;
    }
    if (n >= sizeof v) {
        n = sizeof v - 1;
    }
    memcpy(v, value, n);
    v[n] = 0;
    /* a text property's malformed value is ignored, as CSS does */
    if (svg_text_property(&st->text, doc->inherit_from ? &doc->inherit_from->text : NULL, name,
                          v) != 0) {
        return true;
    }
    if (strcmp(v, "inherit") == 0) {
        /* An inherited property has the parent's value already; the others
         * take it from the parent's style, when there is a parent. */
        const style *p = doc->inherit_from;
        if (!p) {
            return true;
        }
        if (strcmp(name, "opacity") == 0) {
            st->own_opacity = p->own_opacity;
        } else if (strcmp(name, "clip-path") == 0) {
            st->clip = p->clip;
        } else if (strcmp(name, "mask") == 0) {
            st->mask = p->mask;
        } else if (strcmp(name, "mask-type") == 0) {
            st->mask_alpha = p->mask_alpha;
        } else if (strcmp(name, "stop-color") == 0) {
            st->stop_color = p->stop_color;
        } else if (strcmp(name, "stop-opacity") == 0) {
            st->stop_opacity = p->stop_opacity;
        } else if (strcmp(name, "filter") == 0) {
            st->filter = p->filter;
            st->filter_missing = p->filter_missing;
        } else if (strcmp(name, "flood-color") == 0) {
            st->flood_color = p->flood_color;
        } else if (strcmp(name, "flood-opacity") == 0) {
            st->flood_opacity = p->flood_opacity;
        } else if (strcmp(name, "lighting-color") == 0) {
            st->lighting_color = p->lighting_color;
        }
        return true;
    }
    double num;
    if (strcmp(name, "fill") == 0 || strcmp(name, "stroke") == 0) {
        parse_paint(doc, name[0] == 'f' ? &st->fill : &st->stroke, v);
    } else if (strcmp(name, "stop-color") == 0) {
        color_property(doc, st, name, v, &st->stop_color);
    } else if (strcmp(name, "stop-opacity") == 0) {
        unit_property(doc, name, v, &st->stop_opacity);
    } else if (strcmp(name, "color") == 0) {
        sr_rgba c;
        svg_paint_kind k = svg_parse_color(v, &c);
        if (k == SVG_PAINT_COLOR) {
            st->color = c;
        } else if (k != SVG_PAINT_CURRENT) { /* color: currentColor keeps the parent's */
            warn_once(doc, "color", v);
        }
    } else if (strcmp(name, "fill-opacity") == 0 || strcmp(name, "stroke-opacity") == 0 ||
               strcmp(name, "opacity") == 0) {
        if (!parse_unit_number(v, &num)) {
            warn_once(doc, name, v);
        } else if (name[0] == 'o') {
            st->own_opacity = clamp01(num);
        } else {
            *(name[0] == 'f' ? &st->fill_opacity : &st->stroke_opacity) = clamp01(num);
        }
    } else if (strcmp(name, "clip-path") == 0 || strcmp(name, "mask") == 0) {
        bool clip = name[0] == 'c';
        svg_node *c = strcmp(v, "none") == 0 ? NULL : reference(doc, v, NULL);
        if (c && strcmp(c->name, clip ? "clipPath" : "mask") != 0) {
            warn_once(doc, name, v);
            c = NULL;
        }
        /* a missing clip path or mask: drawn without, as rsvg-convert does */
        *(clip ? &st->clip : &st->mask) = c;
    } else if (strcmp(name, "mask-type") == 0) {
        st->mask_alpha = strcmp(v, "alpha") == 0;
    } else if (strcmp(name, "filter") == 0 || strcmp(name, "flood-color") == 0 ||
               strcmp(name, "flood-opacity") == 0 || strcmp(name, "lighting-color") == 0 ||
               strcmp(name, "color-interpolation-filters") == 0) {
        filter_property(doc, st, name, v);
    } else if (strcmp(name, "fill-rule") == 0 || strcmp(name, "clip-rule") == 0) {
        if (strcmp(v, "nonzero") == 0 || strcmp(v, "evenodd") == 0) {
            *(name[0] == 'f' ? &st->fill_rule : &st->clip_rule) =
                v[0] == 'n' ? SR_NONZERO : SR_EVENODD;
        } else {
            warn_once(doc, "fill-rule", v);
        }
    } else if (strcmp(name, "stroke-width") == 0) {
        bool pct;
        if (!parse_length(v, &num, &pct) || pct || num < 0) {
            warn_once(doc, "stroke-width", v);
        } else {
            st->stroke_width = num;
        }
    } else if (strncmp(name, "marker", 6) == 0 &&
               (name[6] == 0 || strcmp(name + 6, "-start") == 0 ||
                strcmp(name + 6, "-mid") == 0 || strcmp(name + 6, "-end") == 0)) {
        svg_node *m = strcmp(v, "none") == 0 ? NULL : reference(doc, v, NULL);
        if (m && strcmp(m->name, "marker") != 0) {
            warn_once(doc, name, v);
            m = NULL;
        }
        /* "marker" sets all three; a missing marker draws nothing */
        int which = name[6] == 0 ? -1 : name[7] == 's' ? 0 : name[7] == 'm' ? 1 : 2;
        for (int i = 0; i < 3; i++) {
            if (which < 0 || which == i) {
                st->marker[i] = m;
            }
        }
    } else if (strcmp(name, "mix-blend-mode") == 0) {
        int mode = svg_blend_mode(v);
        if (mode < 0) {
            warn_once(doc, "mix-blend-mode", v);
        } else {
            st->blend = (svg_blend_kind)mode;
        }
    } else if (strcmp(name, "overflow") == 0) {
        st->overflow_visible = strcmp(v, "visible") == 0 || strcmp(v, "auto") == 0;
    } else if (strcmp(name, "isolation") == 0) {
        if (strcmp(v, "auto") == 0 || strcmp(v, "isolate") == 0) {
            st->isolate = v[0] == 'i';
        } else {
            warn_once(doc, "isolation", v);
        }
    } else if (strcmp(name, "transform-origin") == 0) {
        if (!parse_origin(v, st)) {
            warn_once(doc, "transform-origin", v);
        }
    } else if (strcmp(name, "vector-effect") == 0) {
        if (strcmp(v, "none") == 0 || strcmp(v, "non-scaling-stroke") == 0) {
            st->non_scaling = strcmp(v, "non-scaling-stroke") == 0;
        } else {
            warn_once(doc, "vector-effect", v);
        }
    } else if (strcmp(name, "paint-order") == 0) {
        if (!parse_paint_order(v, st)) {
            warn_once(doc, "paint-order", v);
        }
    } else if (strcmp(name, "stroke-dasharray") == 0) {
        if (!parse_dasharray(v, st)) {
            warn_once(doc, "stroke-dasharray", v);
        }
    } else if (strcmp(name, "stroke-dashoffset") == 0) {
        bool pct;
        if (!parse_length(v, &num, &pct) || !isfinite(num)) {
            warn_once(doc, "stroke-dashoffset", v);
        } else {
            st->dash_offset = num;
            st->dash_offset_pct = pct;
        }
    } else if (strcmp(name, "stroke-linejoin") == 0) {
        if (strcmp(v, "miter") == 0) {
            st->join = SR_STROKE_JOIN_MITER;
        } else if (strcmp(v, "round") == 0) {
            st->join = SR_STROKE_JOIN_ROUND;
        } else if (strcmp(v, "bevel") == 0) {
            st->join = SR_STROKE_JOIN_BEVEL;
        } else {
            warn_once(doc, "stroke-linejoin", v);
        }
    } else if (strcmp(name, "stroke-linecap") == 0) {
        if (strcmp(v, "butt") == 0) {
            st->cap = SR_STROKE_CAP_BUTT;
        } else if (strcmp(v, "round") == 0) {
            st->cap = SR_STROKE_CAP_ROUND;
        } else if (strcmp(v, "square") == 0) {
            st->cap = SR_STROKE_CAP_SQUARE;
        } else {
            warn_once(doc, "stroke-linecap", v);
        }
    } else if (strcmp(name, "stroke-miterlimit") == 0) {
        if (!parse_unit_number(v, &num) || num < 1) {
            warn_once(doc, "stroke-miterlimit", v);
        } else {
            st->miter_limit = num;
        }
    } else if (strcmp(name, "shape-rendering") == 0) {
        st->crisp = strcmp(v, "crispEdges") == 0;
    } else if (strcmp(name, "display") == 0) {
        st->display_none = st->display_none || strcmp(v, "none") == 0;
    } else if (strcmp(name, "visibility") == 0) {
        st->invisible = strcmp(v, "hidden") == 0 || strcmp(v, "collapse") == 0;
    } else {
        for (size_t i = 0; i < sizeof initial_values / sizeof initial_values[0]; i++) {
            if (strcmp(name, initial_values[i].name) == 0 &&
                strcmp(v, initial_values[i].value) == 0) {
                return true;
            }
        }
        for (int i = 0; no_effect_props[i]; i++) {
            if (strcmp(name, no_effect_props[i]) == 0) {
                return true;
            }
        }
        /* Text and font settings (no text is drawn), editors' private
         * properties (Inkscape's filter-*, -inkscape-*, ...). */
        static const char *const quiet_prefixes[] = { "text-", "font-", "filter-", "-", NULL };
        for (int i = 0; quiet_prefixes[i]; i++) {
            if (strncmp(name, quiet_prefixes[i], strlen(quiet_prefixes[i])) == 0) {
                return true;
            }
        }
        for (int i = 0; unsupported_props[i]; i++) {
            if (strcmp(name, unsupported_props[i]) == 0) {
                warn_once(doc, "property", name);
                return true;
            }
        }
        return false;
    }
    return true;
}

/* ---- path data ----------------------------------------------------------------- */

/* The document's point budget (svg.h): false after reporting that `more`
 * points on top of those used would pass it. */
static bool points_within_budget(svg_doc *doc, double more)
{
    if (doc->points_used + more > doc->points_budget) {
        svg_fail(doc, SR_TOO_LARGE,
                 "the drawing needs more than %.0f points in all (%d + %d per byte of the "
                 "document)",
                 doc->points_budget, SR_SVG_POINTS_BASE, SR_SVG_POINTS_PER_BYTE);
        return false;
    }
    return true;
}

/* The per-shape limits of svg.h, checked after every command (each adds
 * at most 65537 points); false after reporting which was passed. */
static bool path_within_limits(svg_doc *doc, const sr_path *path, const char *what, long offset)
{
    sr_polygon2 poly = sr_path_polygon(path);
    if (poly.point_count > SR_SVG_MAX_PATH_POINTS) {
        svg_fail(doc, SR_TOO_LARGE,
                 "%s: more than %d points when flattened at this scale (offset %ld)", what,
                 SR_SVG_MAX_PATH_POINTS, offset);
        return false;
    }
    if (poly.contour_count > SR_SVG_MAX_SUBPATHS) {
        svg_fail(doc, SR_TOO_LARGE, "%s: more than %d subpaths (offset %ld)", what,
                 SR_SVG_MAX_SUBPATHS, offset);
        return false;
    }
    return points_within_budget(doc, poly.point_count);
}

/* Record the vertex a command just ended on, when markers want them:
 * the path's last point ('M', 'L') or its last subpath's first ('Z'). */
static bool add_vertex(svg_doc *doc, const sr_path *path, char kind)
{
    if (!doc->want_verts) {
        return true;
    }
    sr_polygon2 poly = sr_path_polygon(path);
    if (poly.contour_count == 0) {
        return true;
    }
    if (doc->n_verts == doc->cap_verts) {
        int cap = doc->cap_verts ? 2 * doc->cap_verts : 64;
        svg_vertex *v = realloc(doc->verts, (size_t)cap * sizeof *v);
        if (!v) {
            svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
            return false;
        }
        doc->verts = v;
        doc->cap_verts = cap;
    }
    int c = poly.contour_count - 1;
    doc->verts[doc->n_verts++] = (svg_vertex){
        .at = kind == 'Z' ? poly.point_count - poly.contour_counts[c] : poly.point_count - 1,
        .contour = c, .kind = kind };
    return true;
}

/* An error in path data or a points list: SVG draws the path up to the
 * last command (point) before it and drops the rest (SVG 1.1 F.2 and
 * SVG 2's path error handling), so the path built so far stands and the
 * error is a warning ("WHAT: DETAIL at offset N"), once per element and
 * place. */
static void path_data_error(svg_doc *doc, const char *what, long offset, const char *message)
{
    char key[128];
    snprintf(key, sizeof key, "%s error %lu:%ld %s", what, msg_line(doc), offset, doc->file);
    warn_keyed(doc, key, "%s; drawn up to there", message);
}

/* After each command of path data: its vertex for markers, the shape's
 * limits.  A failure is reported here and stops the parse. */
typedef struct path_data_check {
    svg_doc *doc;
    const sr_path *path;
    bool failed;
} path_data_check;

static sr_result check_path_command(void *user, char letter, long offset)
{
    path_data_check *c = user;
    char up = (char)toupper((unsigned char)letter);
    c->failed = !add_vertex(c->doc, c->path, up == 'Z' || up == 'M' ? up : 'L') ||
                (up != 'Z' && !path_within_limits(c->doc, c->path, "path data", offset));
    return c->failed ? SR_TOO_LARGE : SR_OK;
}

/* Parse d="..." into the path: false after reporting a failure (a
 * coordinate the library refuses, a limit passed); an error in the data
 * itself ends the path there with a warning. */
static bool parse_path_data(svg_doc *doc, const char *d, sr_path *path)
{
    path_data_check check = { .doc = doc, .path = path };
    long offset;
    sr_io_error err;
    sr_result r = sr_io_parse_path_data(
        d, path, &(sr_io_path_data_desc){ .command = check_path_command, .user = &check },
        &offset, &err);
    if (r == SR_BAD_FORMAT) {
        path_data_error(doc, "path data", offset, err.message);
        return true;
    }
    if (r != SR_OK && !check.failed) {
        lib_fail(doc, r);
    }
    return r == SR_OK;
}

/* ---- shapes ------------------------------------------------------------------- */

static double matrix_scale(mat2d m)
{
    return sqrt(fabs(m.a * m.d - m.b * m.c));
}

/* y clamped to the image rows [0, h], NaN to 0 (the fill rejects it). */
static double clamp_rows(double y, int h)
{
    return y > 0 ? (y < h ? y : h) : 0;
}

/* What filling the mapped polygon costs (svg.h): its bounding box clipped
 * to the image, plus the rows each edge crosses - the aliased and the
 * area fill both visit every active edge on every row it spans. */
static double fill_work(const sr_point2 *pts, const sr_polygon2 *poly, int w, int h)
{
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY, rows = 0;
    int start = 0;
    int contours = poly->contour_counts ? poly->contour_count : 1;
    for (int c = 0; c < contours; c++) {
        int n = poly->contour_counts ? poly->contour_counts[c] : poly->point_count;
        for (int i = 0; i < n; i++) {
            sr_point2 p = pts[start + i], q = pts[start + (i + 1) % n];
            x0 = fmin(x0, p.x);
            x1 = fmax(x1, p.x);
            y0 = fmin(y0, p.y);
            y1 = fmax(y1, p.y);
            rows += fabs(clamp_rows(q.y, h) - clamp_rows(p.y, h)) + 1;
        }
        start += n;
    }
    double bw = fmin(x1, w) - fmax(x0, 0), bh = fmin(y1, h) - fmax(y0, 0);
    return rows + (bw > 0 && bh > 0 ? bw * bh : 0);
}

/* The document's pixel work (svg.h): false after reporting that `work`
 * more would pass it. */
static bool work_within_budget(svg_doc *doc, double work)
{
    if (doc->work_used + work > doc->work_budget) {
        int w = sr_framebuffer_width(doc->fb), h = sr_framebuffer_height(doc->fb);
        svg_fail(doc, SR_TOO_LARGE,
                 "the drawing costs more than %.0f pixel operations, the limit for a %dx%d "
                 "image (%d per pixel + %d)",
                 doc->work_budget, w, h, SR_SVG_WORK_PER_PIXEL, SR_SVG_WORK_BASE);
        return false;
    }
    doc->work_used += work;
    return true;
}

/* The polygon mapped to pixels (a new array in *pts), its points and
 * pixel work counted; false after reporting a failure. */
static bool map_polygon(svg_doc *doc, sr_polygon2 poly, mat2d m, sr_point2 **pts)
{
    if (!points_within_budget(doc, poly.point_count)) {
        return false;
    }
    doc->points_used += poly.point_count;
    *pts = malloc((size_t)poly.point_count * sizeof **pts);
    if (!*pts) {
        svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
        return false;
    }
    for (int i = 0; i < poly.point_count; i++) {
        (*pts)[i] = mat_apply(m, poly.points[i]);
    }
    int w = sr_framebuffer_width(doc->fb), h = sr_framebuffer_height(doc->fb);
    if (!work_within_budget(doc, fill_work(*pts, &poly, w, h))) {
        free(*pts);
        return false;
    }
    return true;
}

/* Map a polygon to pixels and fill it with a color, or with a paint
 * server's colors (at, server: color.a is then the opacity), within the document's budget. */
/* Clip each contour of the polygon in pixels (its points pts, replaced)
 * to the window, Sutherland-Hodgman: inside a convex window every point
 * keeps its winding number, so either fill rule gives the same inside.
 * *counts is the new contours' sizes (malloc'd); false after reporting a
 * failure. */
static bool clip_to_window(svg_doc *doc, sr_polygon2 *poly, sr_point2 **pts, int **counts,
                           const sr_point2 window[4])
{
    int nc = poly->contour_counts ? poly->contour_count : 1;
    int cap = poly->point_count * 2 + 8 * nc, n = 0;
    sr_point2 *out = malloc((size_t)cap * sizeof *out);
    int *oc = malloc((size_t)nc * sizeof *oc);
    sr_result r = out && oc ? SR_OK : SR_OUT_OF_MEMORY;
    for (int c = 0, at = 0; r == SR_OK && c < nc; c++) {
        int count = poly->contour_counts ? poly->contour_counts[c] : poly->point_count, got;
        r = sr_clip_polygon_convex(doc->ctx, *pts + at, count, window, 4, NULL, out + n, cap - n,
                                   &got);
        if (r == SR_TOO_LARGE) { /* room for got more points, then again */
            sr_point2 *more = realloc(out, (size_t)(cap + got) * sizeof *out);
            r = more ? SR_OK : SR_OUT_OF_MEMORY;
            out = more ? more : out;
            cap += got;
            c--;
            continue;
        }
        oc[c] = got;
        n += got;
        at += count;
    }
    if (r != SR_OK) {
        free(out);
        free(oc);
        lib_fail(doc, r);
        return false;
    }
    free(*pts);
    free(*counts);
    *pts = out;
    *counts = oc;
    *poly = (sr_polygon2){ out, n, oc, nc };
    return true;
}

/* Fill a user-space polygon mapped by m with a color, or with a paint
 * server at the opacity color.a when server is not NULL. */
static void fill_mapped(svg_doc *doc, sr_polygon2 poly, mat2d m, sr_rgba color,
                        const sr_paint *server, sr_fill_rule rule, bool crisp)
{
    if (server && !(color.a > 0)) {
        return; /* a paint at opacity 0 leaves every pixel as it is */
    }
    sr_point2 *pts;
    int *counts = NULL;
    if (poly.point_count == 0 || !map_polygon(doc, poly, m, &pts)) {
        return;
    }
    poly.points = pts;
    for (int i = 0; i < doc->n_windows; i++) {
        if (!clip_to_window(doc, &poly, &pts, &counts, doc->windows[i])) {
            free(pts);
            return;
        }
    }
    sr_fill_desc desc = { .rule = rule, .antialias = crisp ? SR_AA_NONE : SR_AA_AREA };
    sr_result r;
    if (server) {
        sr_paint p = *server;
        p.opacity = color.a < 1 ? color.a : 1;
        r = sr_fill_polygon_paint(doc->ctx, doc->fb, &poly, &p, &desc);
    } else {
        r = sr_fill_polygon(doc->ctx, doc->fb, &poly, color, &desc);
    }
    free(pts);
    free(counts);
    if (r != SR_OK) {
        lib_fail(doc, r);
    }
}

static void apply_cascade(svg_doc *doc, const svg_node *node, style *st);

/* ---- gradients ------------------------------------------------------------------- */

/* Gradients inheriting through href: how long a chain may be. */
#define MAX_HREF_CHAIN 16

static const char *href_of(const svg_node *n)
{
    const char *h = attr(n->atts, "href");
    return h ? h : attr(n->atts, "xlink:href");
}

/* An attribute of a gradient (a pattern), else of the gradients (the
 * patterns) it names by href. */
/* The element of g's href chain (gradients with gradients, patterns with
 * patterns) that has the attribute, or NULL. */
static const svg_node *grad_defining(const svg_doc *doc, const svg_node *g, const char *name)
{
    for (int i = 0; g && i < MAX_HREF_CHAIN; i++) {
        if (attr(g->atts, name)) {
            return g;
        }
        const char *h = href_of(g);
        const svg_node *next = h ? reference(doc, h, NULL) : NULL;
        g = next && (is_gradient(g) ? is_gradient(next) : strcmp(next->name, g->name) == 0)
                ? next : NULL;
    }
    return NULL;
}

static const char *grad_attr(const svg_doc *doc, const svg_node *g, const char *name)
{
    const svg_node *def = grad_defining(doc, g, name);
    return def ? attr(def->atts, name) : NULL;
}

/* t about the transform-origin in st: the origin moved to 0, t, moved
 * back (lengths in the units t applies in, percentages of the viewport). */
static mat2d about_origin(mat2d t, const style *st, const frame *f)
{
    double ox = st->origin[0] * (st->origin_pct & 1 ? f->vp_w : 1);
    double oy = st->origin[1] * (st->origin_pct & 2 ? f->vp_h : 1);
    return mat_mul(mat_mul((mat2d){ 1, 0, 0, 1, ox, oy }, t), (mat2d){ 1, 0, 0, 1, -ox, -oy });
}

/* A paint server's gradientTransform or patternTransform (`name`), from
 * the element of its href chain that has it, about that element's
 * transform-origin (SVG 2: both are the transform property); the
 * identity when there is none or it is malformed (warned). */
static mat2d server_transform(svg_doc *doc, const svg_node *server, const char *name,
                              const frame *f)
{
    const svg_node *def = grad_defining(doc, server, name);
    mat2d t = IDENTITY;
    if (!def) {
        return t;
    }
    const char *tr = attr(def->atts, name);
    if (!parse_transform(tr, &t)) {
        warn_once(doc, name, tr);
        return IDENTITY;
    }
    style st = doc->initial;
    apply_cascade(doc, def, &st);
    return about_origin(t, &st, f);
}

/* A gradient coordinate: a number, or a percentage of ref (1 for
 * objectBoundingBox); def when absent or malformed. */
static double grad_coord(svg_doc *doc, const svg_node *g, const char *name, double ref, double def)
{
    const char *v = grad_attr(doc, g, name);
    double x;
    bool pct;
    if (!v) {
        return def;
    }
    if (!parse_length(v, &x, &pct)) {
        warn_once(doc, name, v);
        return def;
    }
    return pct ? x * ref / 100 : x;
}

static bool mat_invert(mat2d m, mat2d *out)
{
    const double f[6] = { m.a, m.b, m.c, m.d, m.e, m.f };
    double inv[6];
    for (int i = 0; i < 6; i++) {
        if (!isfinite(f[i])) {
            return false;
        }
    }
    if (!sr__affine2_invert(f, 1e-12, inv)) {
        return false;
    }
    *out = (mat2d){ inv[0], inv[1], inv[2], inv[3], inv[4], inv[5] };
    return true;
}

/* The stops of the first gradient of the href chain that has any. */
/* The style the content of a marker, pattern or gradient starts from: the
 * initial one cascaded down that element's own ancestors (not the
 * shape's), each level's properties that are not inherited reset and
 * `inherit` taken from its parent; display ignored. */
static style ancestor_style(svg_doc *doc, const svg_node *m)
{
    const svg_node *chain[MAX_DEPTH];
    int n = 0;
    for (const svg_node *a = m; a && n < MAX_DEPTH; a = a->parent) {
        chain[n++] = a;
    }
    style st = doc->initial;
    const style *outer = doc->inherit_from;
    while (n-- > 0 && doc->status == SR_OK) {
        style parent = st;
        st.own_opacity = 1;
        st.clip = st.mask = NULL;
        st.overflow_visible = false;
        st.stop_color = doc->initial.stop_color;
        st.stop_opacity = doc->initial.stop_opacity;
        st.filter = NULL;
        st.filter_missing = false;
        st.flood_color = doc->initial.flood_color;
        st.flood_opacity = doc->initial.flood_opacity;
        st.lighting_color = doc->initial.lighting_color;
        doc->inherit_from = &parent;
        apply_cascade(doc, chain[n], &st);
    }
    doc->inherit_from = outer;
    st.display_none = false;
    st.opacity = 1;
    return st;
}

static void gradient_stops(svg_doc *doc, const svg_node *g, svg_gradient *out)
{
    int n = 0;
    for (int i = 0; g && i < MAX_HREF_CHAIN && n == 0; i++) {
        /* the stops inherit from the gradient and its ancestors, not from
         * the shape painted: color (for currentColor), and stop-color and
         * stop-opacity for inherit */
        style gs = ancestor_style(doc, g);
        for (const svg_node *c = g->first; c; c = c->next) {
            if (strcmp(c->name, "stop") != 0 || n == SR_MAX_GRADIENT_STOPS) {
                continue;
            }
            style s = gs;
            s.stop_color = doc->initial.stop_color;
            s.stop_opacity = doc->initial.stop_opacity;
            const style *outer = doc->inherit_from;
            doc->inherit_from = &gs;
            apply_cascade(doc, c, &s);
            doc->inherit_from = outer;
            double off = 0;
            bool pct;
            const char *o = attr(c->atts, "offset");
            if (o && !parse_length(o, &off, &pct)) {
                warn_once(doc, "offset", o);
            } else if (o && pct) {
                off /= 100;
            }
            off = clamp01(off);
            int k = n++;
            sr_gradient_stop *st = &out->stops[k];
            /* each offset at least the one before it */
            st->offset = k > 0 && off < st[-1].offset ? st[-1].offset : off;
            st->color = s.stop_color;
            st->color.a *= (float)s.stop_opacity;
        }
        const char *h = href_of(g);
        g = h ? reference(doc, h, NULL) : NULL;
        g = is_gradient(g) ? g : NULL;
    }
    out->paint.stop_count = n;
}

/* The bounding box x0, y0, x1, y1 of the points; false when it is empty
 * (no area: objectBoundingBox units have nothing to map onto). */
static bool bounding_box(sr_polygon2 shape, double b[4])
{
    b[0] = b[1] = INFINITY;
    b[2] = b[3] = -INFINITY;
    for (int i = 0; i < shape.point_count; i++) {
        b[0] = fmin(b[0], shape.points[i].x);
        b[2] = fmax(b[2], shape.points[i].x);
        b[1] = fmin(b[1], shape.points[i].y);
        b[3] = fmax(b[3], shape.points[i].y);
    }
    return b[2] > b[0] && b[3] > b[1];
}

/* The gradient `server` for a shape whose user-space geometry is `shape`
 * under the frame; false when it paints nothing (no stops, an empty
 * bounding box, a singular transform). */
static bool resolve_gradient(svg_doc *doc, const svg_node *server, const frame *f,
                             sr_polygon2 shape, svg_gradient *g)
{
    /* The stops depend on the element and its ancestors alone: doc->grad
     * keeps them for the next shape (style sheets count their matching
     * work per cascade: not then). */
    if (!(g == doc->grad && server == doc->grad_server && doc->sheet.n_rules == 0)) {
        gradient_stops(doc, server, g);
        doc->grad_server = g == doc->grad && doc->status == SR_OK ? server : NULL;
    }
    int n_stops = g->paint.stop_count;
    if (n_stops == 0) {
        return false;
    }
    const char *units = grad_attr(doc, server, "gradientUnits");
    bool bbox = !units || strcmp(units, "userSpaceOnUse") != 0;
    mat2d to_user = IDENTITY;
    double rw = 1, rh = 1;
    if (bbox) {
        double b[4];
        if (!bounding_box(shape, b)) {
            return false;
        }
        to_user = (mat2d){ b[2] - b[0], 0, 0, b[3] - b[1], b[0], b[1] };
    } else {
        rw = f->vp_w;
        rh = f->vp_h;
    }
    double rd = sqrt((rw * rw + rh * rh) / 2);
    mat2d gt = server_transform(doc, server, "gradientTransform", f), inv;
    mat2d t = mat_mul(f->m, mat_mul(to_user, gt));
    if (!mat_invert(t, &inv)) {
        return false;
    }
    g->transform = (sr_affine2){ t.a, t.b, t.c, t.d, t.e, t.f };
    const char *sp = grad_attr(doc, server, "spreadMethod");
    bool radial = strcmp(server->name, "radialGradient") == 0;
    g->paint = (sr_paint){
        .kind = radial ? SR_PAINT_RADIAL_GRADIENT : SR_PAINT_LINEAR_GRADIENT,
        .stops = g->stops,
        .stop_count = n_stops,
        .spread = sp && strcmp(sp, "reflect") == 0  ? SR_SPREAD_REFLECT
                  : sp && strcmp(sp, "repeat") == 0 ? SR_SPREAD_REPEAT
                                                    : SR_SPREAD_PAD,
        .transform = &g->transform,
    };
    sr_paint *p = &g->paint;
    if (!radial) {
        p->x1 = grad_coord(doc, server, "x1", rw, 0);
        p->y1 = grad_coord(doc, server, "y1", rh, 0);
        p->x2 = grad_coord(doc, server, "x2", rw, rw);
        p->y2 = grad_coord(doc, server, "y2", rh, 0);
        return true;
    }
    p->cx = grad_coord(doc, server, "cx", rw, rw / 2);
    p->cy = grad_coord(doc, server, "cy", rh, rh / 2);
    p->r = grad_coord(doc, server, "r", rd, rd / 2);
    g->focal.x = grad_coord(doc, server, "fx", rw, p->cx);
    g->focal.y = grad_coord(doc, server, "fy", rh, p->cy);
    p->focal = &g->focal;
    p->fr = grad_coord(doc, server, "fr", rd, 0);
    /* r = 0: the area is painted with the last stop; a negative fr is an
     * error of the document: nothing */
    return p->r > 0 && p->fr >= 0;
}

/* Points of a round join or cap: as add_disc in src/draw2d/path.c (the
 * chord of a circle of radius hw within tol, 8..4096 points). */
static double disc_points(double hw, double tol)
{
    double a = tol >= hw ? M_PI / 2 : 2 * acos(1 - tol / hw);
    if (!(a > 0)) {
        a = 2 * sqrt(2 * (tol / hw));
    }
    double n = a > 0 ? ceil(2 * M_PI / a) : 4096;
    return n < 8 ? 8 : n > 4096 ? 4096 : n;
}

/* An upper bound on the stroke outline's points, computed before it is
 * built: a quadrilateral per segment, a join piece per vertex, two caps per
 * subpath.  A wide round-joined stroke would otherwise turn each of a
 * million path points into thousands of outline points. */
static double stroke_points(const sr_polygon2 *poly, const style *st, double tol)
{
    double hw = st->stroke_width / 2, disc = disc_points(hw, tol);
    double join = st->join == SR_STROKE_JOIN_ROUND ? disc : 4;
    double cap = st->cap == SR_STROKE_CAP_ROUND ? disc : 4;
    return (double)poly->point_count * (4 + join) + 2.0 * poly->contour_count * cap;
}

static bool paint_pattern(svg_doc *doc, svg_node *pat, const frame *f, sr_polygon2 poly,
                          sr_polygon2 geometry, double opacity, sr_fill_rule rule);

/* Fill a user-space polygon with a paint at an opacity; a gradient's
 * bounding box is the shape's geometry (the fill's path, for a stroke). */
static void paint_polygon_as(svg_doc *doc, const frame *f, sr_polygon2 poly,
                             sr_polygon2 geometry, const paint *p, double opacity,
                             sr_fill_rule rule);

static void paint_polygon(svg_doc *doc, const frame *f, sr_polygon2 poly, sr_polygon2 geometry,
                          const paint *p, double opacity, sr_fill_rule rule)
{
    /* a pattern's content inside measures its own shapes */
    const sr_polygon2 *box = doc->paint_box;
    doc->paint_box = NULL;
    paint_polygon_as(doc, f, poly, box ? *box : geometry, p, opacity, rule);
    doc->paint_box = box;
}

static void paint_polygon_as(svg_doc *doc, const frame *f, sr_polygon2 poly,
                             sr_polygon2 geometry, const paint *p, double opacity,
                             sr_fill_rule rule)
{
    sr_rgba c = p->kind == SVG_PAINT_CURRENT ? f->st.color : p->color;
    if (p->kind == SVG_PAINT_URL && !is_gradient(p->server)) {
        if (paint_pattern(doc, (svg_node *)p->server, f, poly, geometry, opacity, rule) ||
            !p->has_fallback || doc->status != SR_OK) {
            return;
        }
    } else if (p->kind == SVG_PAINT_URL) {
        if (!doc->grad && !(doc->grad = malloc(sizeof *doc->grad))) {
            svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
            return;
        }
        if (resolve_gradient(doc, p->server, f, geometry, doc->grad)) {
            fill_mapped(doc, poly, f->m, (sr_rgba){ 0, 0, 0, (float)opacity }, &doc->grad->paint,
                        rule, f->st.crisp);
            return;
        }
        if (!p->has_fallback || doc->status != SR_OK) {
            return;
        }
    }
    c.a *= (float)opacity;
    if (c.a > 0) {
        fill_mapped(doc, poly, f->m, c, NULL, rule, f->st.crisp);
    }
}

/* How far a stroke drawn through m reaches from its path, in device
 * pixels, and a pixel more: the half width times the most a miter or a
 * square cap reaches past it. */
static double stroke_reach(const style *st, mat2d m)
{
    /* the largest stretch of m, bounded above */
    double stretch = fabs(m.a) + fabs(m.b) + fabs(m.c) + fabs(m.d);
    return st->stroke_width / 2 * stretch * fmax(st->miter_limit, 1.4142135623730951) + 1;
}

/* The dashes of the path as a new path (stroke-dasharray, its lengths
 * in user units, percentages of the viewport's normalized diagonal);
 * NULL after reporting a failure.  A pattern so fine that its dashes
 * would pass the drawing's point budget is refused before it is cut. */
static sr_path *dash_path(svg_doc *doc, const frame *f, const sr_path *path, mat2d m,
                          double tol)
{
    const style *st = &f->st;
    double diag = sqrt((f->vp_w * f->vp_w + f->vp_h * f->vp_h) / 2), dash[SVG_MAX_DASHES];
    double period = 0;
    for (int i = 0; i < st->n_dash; i++) {
        dash[i] = st->dash[i] * (st->dash_pct & 1u << i ? diag / 100 : 1);
        period += dash[i];
    }
    double offset = st->dash_offset * (st->dash_offset_pct ? diag / 100 : 1);
    /* only the dashes that can reach the target's pixels (m maps path to
     * it): a dash outside them draws none, one cut there the same ones */
    double reach = stroke_reach(st, m);
    const sr_path_view view = { { m.a, m.b, m.c, m.d, m.e, m.f }, -reach, -reach,
                                sr_framebuffer_width(doc->fb) + reach,
                                sr_framebuffer_height(doc->fb) + reach };
    const sr_path_view *within = isfinite(reach) ? &view : NULL;
    sr_polygon2 poly = sr_path_polygon(path);
    double pieces = sr_path_length_in_view(path, within) / period * st->n_dash + poly.contour_count;
    double est = poly.point_count + 2 * pieces;
    if (!(period > 0) || !isfinite(est) || doc->points_used + est > doc->points_budget) {
        svg_fail(doc, SR_TOO_LARGE,
                 "stroke-dasharray: a pattern of period %g along this path makes about %.0f "
                 "dashes, beyond the drawing's %.0f points (%d + %d per byte of the document)",
                 period, pieces, doc->points_budget, SR_SVG_POINTS_BASE, SR_SVG_POINTS_PER_BYTE);
        return NULL;
    }
    doc->points_used += est;
    sr_path *out = NULL;
    sr_result r = sr_make_path(doc->ctx, tol, &out);
    if (r == SR_OK) {
        r = sr_path_dash_in_view(doc->ctx, path, dash, st->n_dash, offset, within, out);
    }
    if (r != SR_OK) {
        sr_destroy_path(doc->ctx, out);
        lib_fail(doc, r);
        return NULL;
    }
    return out;
}

/* The path mapped by m into a new path (flattened points as lines, the
 * closed subpaths closed); NULL after reporting a failure. */
static sr_path *mapped_path(svg_doc *doc, const sr_path *path, mat2d m)
{
    sr_polygon2 poly = sr_path_polygon(path);
    sr_path *out = NULL;
    sr_result r = sr_make_path(doc->ctx, 0.1, &out);
    for (int c = 0, at = 0; r == SR_OK && c < poly.contour_count; at += poly.contour_counts[c++]) {
        for (int i = 0; r == SR_OK && i < poly.contour_counts[c]; i++) {
            sr_point2 p = mat_apply(m, poly.points[at + i]);
            r = i == 0 ? sr_path_move_to(out, p.x, p.y) : sr_path_line_to(out, p.x, p.y);
        }
        if (r == SR_OK && sr_path_subpath_closed(path, c)) {
            r = sr_path_close(out);
        }
    }
    if (r != SR_OK) {
        sr_destroy_path(doc->ctx, out);
        lib_fail(doc, r);
        return NULL;
    }
    return out;
}

/* The stroke of a path: its outline (of the dashes, if any) filled with
 * the stroke's paint.  Under vector-effect="non-scaling-stroke" the
 * outline is made in the outermost viewport's coordinates (widths and
 * dashes in its units, whatever the transforms between) and mapped back. */
static void draw_stroke(svg_doc *doc, const frame *f, const sr_path *path, double tol)
{
    const style *st = &f->st;
    sr_path *host = NULL;
    mat2d back = IDENTITY;
    if (st->non_scaling) {
        mat2d to_host;
        if (!mat_invert(doc->root_m, &to_host) || !mat_invert(mat_mul(to_host, f->m), &back) ||
            !(host = mapped_path(doc, path, mat_mul(to_host, f->m)))) {
            return;
        }
        tol = 0.1 / matrix_scale(doc->root_m);
    }
    const sr_path *source = host ? host : path;
    sr_path *dashed =
        st->n_dash > 0 ? dash_path(doc, f, source, host ? doc->root_m : f->m, tol) : NULL;
    const sr_path *stroked = dashed ? dashed : source;
    sr_polygon2 poly = sr_path_polygon(stroked);
    double est = stroke_points(&poly, st, tol);
    if (st->n_dash > 0 && !dashed) {
        /* reported by dash_path */
    } else if (doc->points_used + est > doc->points_budget) {
        svg_fail(doc, SR_TOO_LARGE,
                 "stroke: the outline of stroke-width %g over %d points would need about "
                 "%.0f points, beyond the drawing's %.0f (%d + %d per byte of the document)",
                 st->stroke_width, poly.point_count, est, doc->points_budget,
                 SR_SVG_POINTS_BASE, SR_SVG_POINTS_PER_BYTE);
    } else {
        sr_polygon2 outline;
        sr_result r = sr_make_stroke_outline(doc->ctx, stroked,
                                             &(sr_stroke_desc){ .width = st->stroke_width,
                                                                .join = st->join, .cap = st->cap,
                                                                .miter_limit = st->miter_limit },
                                             &outline);
        if (r != SR_OK) {
            lib_fail(doc, r);
        } else {
            /* the outline is ours (made above): mapped back in place */
            sr_point2 *pts = (sr_point2 *)outline.points;
            for (int i = 0; host && i < outline.point_count; i++) {
                pts[i] = mat_apply(back, pts[i]);
            }
            paint_polygon(doc, f, outline, sr_path_polygon(path), &st->stroke,
                          st->stroke_opacity * st->opacity, SR_NONZERO);
            sr_destroy_stroke_outline(doc->ctx, &outline);
        }
    }
    sr_destroy_path(doc->ctx, dashed);
    sr_destroy_path(doc->ctx, host);
}

/* The fill (what: PAINT_FILL) or the stroke (PAINT_STROKE) of a path. */
static void draw_path(svg_doc *doc, const frame *f, sr_path *path, double tol, bool fillable,
                      int what)
{
    const style *st = &f->st;
    if (st->display_none || st->invisible || doc->status != SR_OK) {
        return;
    }
    if (what == PAINT_FILL) {
        if (fillable && st->fill.kind != SVG_PAINT_NONE && st->fill_opacity * st->opacity > 0) {
            paint_polygon(doc, f, sr_path_polygon(path), sr_path_polygon(path), &st->fill,
                          st->fill_opacity * st->opacity, st->fill_rule);
        }
    } else if (st->stroke.kind != SVG_PAINT_NONE && st->stroke_width > 0 &&
               st->stroke_opacity * st->opacity > 0) {
        draw_stroke(doc, f, path, tol);
    }
}

/* A path call inside a basic shape: false (and reported) on failure. */
static bool path_ok(svg_doc *doc, sr_result r)
{
    if (r != SR_OK) {
        lib_fail(doc, r);
        return false;
    }
    return true;
}

/* Build the path of a basic shape (false: nothing to draw or an error). */
static bool shape_path(svg_doc *doc, const frame *f, const char *name, const char **atts,
                       sr_path *p, bool *fillable)
{
    *fillable = true;
    double v[6];
    if (strcmp(name, "path") == 0) {
        const char *d = attr(atts, "d");
        return d && parse_path_data(doc, d, p);
    }
    if (strcmp(name, "rect") == 0) {
        const char *rx_s = attr(atts, "rx"), *ry_s = attr(atts, "ry");
        if (!length_attr(doc, f, "x", attr(atts, "x"), &v[0]) ||
            !length_attr(doc, f, "y", attr(atts, "y"), &v[1]) ||
            !length_attr(doc, f, "width", attr(atts, "width"), &v[2]) ||
            !length_attr(doc, f, "height", attr(atts, "height"), &v[3]) ||
            !length_attr(doc, f, "rx", rx_s, &v[4]) || !length_attr(doc, f, "ry", ry_s, &v[5])) {
            return false;
        }
        if (v[2] < 0 || v[3] < 0 || v[4] < 0 || v[5] < 0) {
            svg_fail(doc, SR_BAD_FORMAT, "rect: negative width, height, rx or ry");
            return false;
        }
        if (v[2] == 0 || v[3] == 0) {
            return false;
        }
        double x = v[0], y = v[1], w = v[2], h = v[3];
        double rx = rx_s ? v[4] : v[5], ry = ry_s ? v[5] : v[4]; /* one sets both */
        rx = fmin(rx, w / 2);
        ry = fmin(ry, h / 2);
        /* Each call is checked: x + w may overflow to infinity. */
        bool ok;
        if (rx > 0 && ry > 0) {
            ok = path_ok(doc, sr_path_move_to(p, x + rx, y)) &&
                 path_ok(doc, sr_path_line_to(p, x + w - rx, y)) &&
                 path_ok(doc, sr_path_arc_to(p, rx, ry, 0, false, true, x + w, y + ry)) &&
                 path_ok(doc, sr_path_line_to(p, x + w, y + h - ry)) &&
                 path_ok(doc, sr_path_arc_to(p, rx, ry, 0, false, true, x + w - rx, y + h)) &&
                 path_ok(doc, sr_path_line_to(p, x + rx, y + h)) &&
                 path_ok(doc, sr_path_arc_to(p, rx, ry, 0, false, true, x, y + h - ry)) &&
                 path_ok(doc, sr_path_line_to(p, x, y + ry)) &&
                 path_ok(doc, sr_path_arc_to(p, rx, ry, 0, false, true, x + rx, y));
        } else {
            ok = path_ok(doc, sr_path_move_to(p, x, y)) &&
                 path_ok(doc, sr_path_line_to(p, x + w, y)) &&
                 path_ok(doc, sr_path_line_to(p, x + w, y + h)) &&
                 path_ok(doc, sr_path_line_to(p, x, y + h));
        }
        return ok && path_ok(doc, sr_path_close(p));
    }
    if (strcmp(name, "circle") == 0 || strcmp(name, "ellipse") == 0) {
        bool circle = name[0] == 'c';
        if (!length_attr(doc, f, "cx", attr(atts, "cx"), &v[0]) ||
            !length_attr(doc, f, "cy", attr(atts, "cy"), &v[1])) {
            return false;
        }
        if (circle) {
            if (!length_attr(doc, f, "r", attr(atts, "r"), &v[2])) {
                return false;
            }
            v[3] = v[2];
        } else if (!length_attr(doc, f, "rx", attr(atts, "rx"), &v[2]) ||
                   !length_attr(doc, f, "ry", attr(atts, "ry"), &v[3])) {
            return false;
        }
        if (v[2] < 0 || v[3] < 0) {
            svg_fail(doc, SR_BAD_FORMAT, "%s: negative radius", name);
            return false;
        }
        if (v[2] == 0 || v[3] == 0) {
            return false;
        }
        return path_ok(doc, sr_path_move_to(p, v[0] + v[2], v[1])) &&
               path_ok(doc, sr_path_arc_to(p, v[2], v[3], 0, false, true, v[0] - v[2], v[1])) &&
               path_ok(doc, sr_path_arc_to(p, v[2], v[3], 0, false, true, v[0] + v[2], v[1])) &&
               path_ok(doc, sr_path_close(p));
    }
    if (strcmp(name, "line") == 0) {
        *fillable = false;
        if (!length_attr(doc, f, "x1", attr(atts, "x1"), &v[0]) ||
            !length_attr(doc, f, "y1", attr(atts, "y1"), &v[1]) ||
            !length_attr(doc, f, "x2", attr(atts, "x2"), &v[2]) ||
            !length_attr(doc, f, "y2", attr(atts, "y2"), &v[3])) {
            return false;
        }
        return path_ok(doc, sr_path_move_to(p, v[0], v[1])) && add_vertex(doc, p, 'M') &&
               path_ok(doc, sr_path_line_to(p, v[2], v[3])) && add_vertex(doc, p, 'L');
    }
    /* polyline, polygon */
    const char *pts = attr(atts, "points");
    if (!pts) {
        return false;
    }
    const char *s = svg_skip_ws(pts);
    int n = 0;
    while (*s) {
        double x, y;
        if (!svg_parse_number(&s, &x) || !svg_parse_number((s = svg_skip_ws_comma(s), &s), &y)) {
            char message[160];
            snprintf(message, sizeof message, "%s: points: expected a coordinate pair at offset %ld",
                     name, (long)(s - pts));
            path_data_error(doc, name, (long)(s - pts), message);
            break;
        }
        s = svg_skip_ws_comma(s);
        bool first = n++ == 0;
        if (!path_ok(doc, first ? sr_path_move_to(p, x, y) : sr_path_line_to(p, x, y)) ||
            !add_vertex(doc, p, first ? 'M' : 'L') ||
            !path_within_limits(doc, p, name, (long)(s - pts))) {
            return false;
        }
    }
    if (strcmp(name, "polygon") == 0 &&
        (!path_ok(doc, sr_path_close(p)) || (n > 0 && !add_vertex(doc, p, 'Z')))) {
        return false;
    }
    return n > 0;
}

/* ---- the root element --------------------------------------------------------------- */

/* viewBox's four numbers, whatever their values. */
static bool parse_viewbox_numbers(const char *s, double vb[4])
{
    s = svg_skip_ws(s);
    for (int i = 0; i < 4; i++) {
        if (!svg_parse_number(&s, &vb[i])) {
            return false;
        }
        s = svg_skip_ws_comma(s);
    }
    return *s == 0;
}

static bool parse_viewbox(const char *s, double vb[4])
{
    return parse_viewbox_numbers(s, vb) && vb[2] > 0 && vb[3] > 0;
}

/* preserveAspectRatio: align x, y in {0, 0.5, 1} (-1: none), slice. */
static bool parse_aspect(const char *s, double *ax, double *ay, bool *slice)
{
    *ax = *ay = 0.5;
    *slice = false;
    if (!s) {
        return true;
    }
    s = svg_skip_ws(s);
    if (strncmp(s, "defer", 5) == 0) {
        s = svg_skip_ws(s + 5);
    }
    if (strncmp(s, "none", 4) == 0) {
        *ax = *ay = -1;
        s += 4;
    } else {
        static const char *al[3] = { "Min", "Mid", "Max" };
        int fx = -1, fy = -1;
        for (int i = 0; i < 3; i++) {
            for (int j = 0; j < 3; j++) {
                char want[16];
                snprintf(want, sizeof want, "x%sY%s", al[i], al[j]);
                if (strncmp(s, want, 8) == 0) {
                    fx = i;
                    fy = j;
                }
            }
        }
        if (fx < 0) {
            return false;
        }
        *ax = fx / 2.0;
        *ay = fy / 2.0;
        s += 8;
    }
    s = svg_skip_ws(s);
    if (strncmp(s, "slice", 5) == 0) {
        *slice = true;
        s += 5;
    } else if (strncmp(s, "meet", 4) == 0) {
        s += 4;
    }
    return *svg_skip_ws(s) == 0;
}

/* The viewBox vb onto the viewport (x, y, w, h) as preserveAspectRatio
 * of the element says. */
static mat2d viewbox_matrix(svg_doc *doc, const char **atts, const double vb[4], double x,
                            double y, double w, double h)
{
    double ax, ay;
    bool slice;
    const char *par = attr(atts, "preserveAspectRatio");
    if (!parse_aspect(par, &ax, &ay, &slice)) {
        warn_once(doc, "preserveAspectRatio", par);
        ax = ay = 0.5;
        slice = false;
    }
    double sx = w / vb[2], sy = h / vb[3];
    if (ax >= 0) {
        sx = sy = slice ? fmax(sx, sy) : fmin(sx, sy);
    }
    double tx = x - vb[0] * sx, ty = y - vb[1] * sy;
    if (ax >= 0) {
        tx += (w - vb[2] * sx) * ax;
        ty += (h - vb[3] * sy) * ay;
    }
    return (mat2d){ sx, 0, 0, sy, tx, ty };
}

/* A root svg's viewBox (its width and height when it has none) and its
 * intrinsic size: width and height, else the viewBox's, else 300 x 150.
 * False after reporting a malformed one, a negative size (an error in
 * SVG) or a zero one: SVG draws nothing for a zero width, height or
 * viewBox size, and an image of nothing, of any size, would hide that
 * (rsvg-convert refuses such a document, whatever size it is asked for).
 * The document of an <image> with a zero size is no error: false, and
 * nothing reported, draws nothing in its place. */
static bool intrinsic_size(svg_doc *doc, const char **atts, bool image, double vb[4],
                           double *pw, double *ph)
{
    const char *vbs = attr(atts, "viewBox");
    bool have_vb = vbs && parse_viewbox(vbs, vb);
    if (vbs && !have_vb) {
        bool zero = parse_viewbox_numbers(vbs, vb) && vb[2] >= 0 && vb[3] >= 0;
        if (zero && image) {
            return false;
        }
        svg_fail(doc, SR_BAD_FORMAT,
                 zero ? "viewBox=\"%s\" disables rendering (SVG draws nothing of a zero %s)"
                      : "viewBox=\"%s\" needs four numbers with width, height > 0",
                 SVG_QUOTED(vbs), zero && vb[2] == 0 ? "width" : "height");
        return false;
    }
    double w = 0, h = 0;
    bool wp = false, hp = false;
    const char *ws = attr(atts, "width"), *hs = attr(atts, "height");
    if (ws && !parse_length(ws, &w, &wp)) {
        svg_fail(doc, SR_BAD_FORMAT, "width=\"%s\" is not a length", SVG_QUOTED(ws));
        return false;
    }
    if (hs && !parse_length(hs, &h, &hp)) {
        svg_fail(doc, SR_BAD_FORMAT, "height=\"%s\" is not a length", SVG_QUOTED(hs));
        return false;
    }
    /* A percentage of the root's viewport is no size of its own: the
     * viewBox's stands in (0% as well, as rsvg-convert reads it). */
    for (int k = 0; k < 2; k++) {
        const char *s = k ? hs : ws;
        double v = k ? h : w;
        if (s && (v < 0 || (v == 0 && !(k ? hp : wp)))) {
            if (v == 0 && image) {
                return false;
            }
            const char *name = k ? "height" : "width";
            if (v < 0) {
                svg_fail(doc, SR_BAD_FORMAT, "%s=\"%s\" is negative, an error in SVG", name,
                         SVG_QUOTED(s));
            } else {
                svg_fail(doc, SR_BAD_FORMAT,
                         "%s=\"%s\" disables rendering (SVG draws nothing of a zero %s)", name,
                         SVG_QUOTED(s), name);
            }
            return false;
        }
    }
    if (!ws || wp) {
        w = have_vb ? vb[2] : 300;
    }
    if (!hs || hp) {
        h = have_vb ? vb[3] : 150;
    }
    if (!have_vb) {
        vb[0] = vb[1] = 0;
        vb[2] = w;
        vb[3] = h;
    }
    *pw = w;
    *ph = h;
    return true;
}

static bool root_element(svg_doc *doc, const char **atts, frame *f)
{
    double vb[4], w, h;
    if (!intrinsic_size(doc, atts, false, vb, &w, &h)) {
        return false;
    }
    const sr_svg_desc *opt = doc->opt;
    int max_side = opt->max_side > 0 && opt->max_side < SR_MAX_FRAMEBUFFER_SIZE
                       ? opt->max_side : SR_MAX_FRAMEBUFFER_SIZE;
    int out_w, out_h;
    if (opt->width) {
        out_w = opt->width;
        out_h = opt->height;
        if (out_w < 1 || out_h < 1 || out_w > max_side || out_h > max_side) {
            svg_fail(doc, SR_BAD_FORMAT, "image size %d x %d is outside 1..%d", out_w, out_h,
                     max_side);
            return false;
        }
    } else {
        double s = opt->scale > 0 ? opt->scale : 1;
        double ow = ceil(w * s - 1e-9), oh = ceil(h * s - 1e-9);
        if (!(ow >= 1 && oh >= 1 && ow <= max_side && oh <= max_side)) {
            svg_fail(doc, SR_BAD_FORMAT, "image size %.0f x %.0f is outside 1..%d (use --size)", ow,
                     oh, max_side);
            return false;
        }
        out_w = (int)ow;
        out_h = (int)oh;
    }
    /* The viewBox onto the whole image. */
    f->m = viewbox_matrix(doc, atts, vb, 0, 0, out_w, out_h);
    f->vp_w = vb[2];
    f->vp_h = vb[3];
    sr_result r = sr_make_framebuffer(doc->ctx, &(sr_framebuffer_desc){
                                          .width = out_w, .height = out_h,
                                          .depth_format = SR_DEPTH_NONE }, &doc->fb);
    if (r != SR_OK) {
        lib_fail(doc, r);
        return false;
    }
    doc->work_budget = (double)SR_SVG_WORK_PER_PIXEL * out_w * out_h + SR_SVG_WORK_BASE;
    sr_rgba bg = opt->background;
    sr_clear(doc->ctx, doc->fb, &(sr_clear_desc){ .color = { bg.r, bg.g, bg.b, bg.a } });
    return true;
}

/* ---- expat handlers ---------------------------------------------------------------- */

static const char *local_name(const char *name)
{
    const char *c = strrchr(name, ':');
    return c ? c + 1 : name;
}

static bool is_shape(const char *n)
{
    static const char *shapes[] = { "path", "rect", "circle", "ellipse", "line", "polyline",
                                    "polygon", NULL };
    for (int i = 0; shapes[i]; i++) {
        if (strcmp(n, shapes[i]) == 0) {
            return true;
        }
    }
    return false;
}

/* ---- reading the tree -------------------------------------------------------------- */

/* Whether an element's character data is text to draw: that of text,
 * tspan and textPath, and of an a inside a text. */
static bool holds_text(const svg_node *n)
{
    if (!svg_text_available()) {
        return false;
    }
    if (strcmp(n->name, "a") == 0) {
        return n->parent && holds_text(n->parent);
    }
    return strcmp(n->name, "text") == 0 || strcmp(n->name, "tspan") == 0 ||
           strcmp(n->name, "textPath") == 0;
}

/* One allocation per element: the node, its attribute array and strings. */
static svg_node *make_node(const char *name, const char **atts)
{
    size_t n = 0, bytes = strlen(name) + 1;
    for (; atts[n]; n++) {
        bytes += strlen(atts[n]) + 1;
    }
    size_t head = sizeof(svg_node) + (n + 1) * sizeof(char *);
    svg_node *node = calloc(1, head + bytes);
    if (!node) {
        return NULL;
    }
    const char **a = (const char **)(node + 1);
    char *str = (char *)node + head;
    node->name = strcpy(str, name);
    str += strlen(name) + 1;
    for (size_t i = 0; i < n; i++) {
        a[i] = strcpy(str, atts[i]);
        str += strlen(atts[i]) + 1;
    }
    a[n] = NULL;
    node->atts = a;
    node->id = attr(a, "id");
    node->cls = attr(a, "class");
    return node;
}

static void free_tree(svg_node *n)
{
    while (n) {
        svg_node *next = n->next;
        free_tree(n->first);
        free(n->text);
        free(n);
        n = next;
    }
}

/* The line of the event expat is reporting.  Expat's own count walks
 * every byte since its last report through its tokenizer, about a
 * thousand instructions for a one-line element; this counts the same
 * line ends (CR, LF, CR LF) in the bytes, with memchr when the document
 * has no CR. */
static unsigned long event_line(svg_doc *doc)
{
    XML_Index at = XML_GetCurrentByteIndex(doc->parser);
    if (!doc->text || at < 0 || (size_t)at < doc->line_at || (size_t)at > doc->text_size) {
        return XML_GetCurrentLineNumber(doc->parser);
    }
    const char *p = doc->text + doc->line_at, *end = doc->text + at;
    unsigned long lines = doc->lines_before;
    if (!doc->text_has_cr) { /* the usual case: only LF ends lines */
        for (const char *q; p < end && (q = memchr(p, '\n', (size_t)(end - p))); p = q + 1) {
            lines++;
        }
        p = end;
    }
    for (; p < end; p++) {
        if (*p == '\n') {
            lines++;
        } else if (*p == '\r') {
            lines++;
            p += p + 1 < end && p[1] == '\n';
        }
    }
    doc->line_at = (size_t)at;
    doc->lines_before = lines;
    return lines + 1;
}

static void XMLCALL on_start(void *user, const XML_Char *qname, const XML_Char **atts)
{
    svg_doc *doc = user;
    if (doc->status != SR_OK) {
        return;
    }
    doc->line = event_line(doc);
    const char *name = local_name(qname);
    if (doc->depth + 1 >= MAX_DEPTH) {
        svg_fail(doc, SR_BAD_FORMAT, "elements nested deeper than %d", MAX_DEPTH);
        return;
    }
    if (!doc->root && strcmp(name, "svg") != 0) {
        svg_fail(doc, SR_BAD_FORMAT, "the root element is <%s>, not <svg>",
                 SVG_QUOTED(name));
        return;
    }
    /* Each element is a point of the budget: a document of empty
     * elements is bounded like one of points. */
    if (!points_within_budget(doc, 1)) {
        return;
    }
    doc->points_used++;
    svg_node *node = make_node(name, atts);
    if (!node) {
        svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
        return;
    }
    node->line = doc->line;
    node->foreign = name != qname && strncmp(qname, "svg:", 4) != 0;
    node->parent = doc->open;
    if (!doc->root) {
        doc->root = node;
    } else if (doc->open->last) {
        doc->open->last = doc->open->last->next = node;
    } else {
        doc->open->first = doc->open->last = node;
    }
    doc->open = node;
    doc->depth++;
    doc->nodes++;
}

static void XMLCALL on_end(void *user, const XML_Char *name)
{
    (void)name;
    svg_doc *doc = user;
    if (doc->open) {
        doc->open = doc->open->parent;
        doc->depth--;
    }
}

/* Character data is kept for <style> (the sheets are read after the
 * whole document) and for text, where it goes in nodes named "#text"
 * between the elements, in order. */
static void XMLCALL on_text(void *user, const XML_Char *s, int len)
{
    svg_doc *doc = user;
    svg_node *n = doc->open;
    if (doc->status != SR_OK || !n || len <= 0) {
        return;
    }
    if (holds_text(n)) {
        if (!n->last || strcmp(n->last->name, "#text") != 0) {
            svg_node *chars = make_node("#text", (const char *[]){ NULL });
            if (!chars || !points_within_budget(doc, 1)) {
                if (!chars) {
                    svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
                }
                free(chars);
                return;
            }
            doc->points_used++;
            chars->line = event_line(doc);
            chars->parent = n;
            if (n->last) {
                n->last = n->last->next = chars;
            } else {
                n->first = n->last = chars;
            }
            doc->nodes++;
        }
        n = n->last;
    } else if (strcmp(n->name, "style") != 0) {
        return;
    }
    char *grown = realloc(n->text, n->text_len + (size_t)len + 1);
    if (!grown) {
        svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
        return;
    }
    memcpy(grown + n->text_len, s, (size_t)len);
    n->text_len += (size_t)len;
    grown[n->text_len] = 0;
    n->text = grown;
}

/* ---- ids and style sheets ------------------------------------------------------------ */

static int cmp_id(const void *a, const void *b)
{
    const id_entry *x = a, *y = b;
    int c = strcmp(x->id, y->id);
    /* the first in document order wins: ties keep their order */
    return c ? c : (x->node->line > y->node->line) - (x->node->line < y->node->line);
}

static void collect(svg_doc *doc, svg_node *n, size_t *k)
{
    for (; n; n = n->next) {
        if (n->id && doc->ids) {
            doc->ids[(*k)++] = (id_entry){ n->id, n };
        }
        if (strcmp(n->name, "style") == 0 && n->text) {
            const char *type = attr(n->atts, "type");
            if (type && *type && strcmp(type, "text/css") != 0) {
                warn_once(doc, "style type", type);
            } else {
                int unsupported = 0;
                if (!svg_css_parse(&doc->sheet, n->text, &unsupported)) {
                    svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
                    return;
                }
                if (unsupported) {
                    doc->line = n->line;
                    warn_once(doc, "CSS", "selectors or at-rules");
                }
            }
        }
        collect(doc, n->first, k);
    }
}

/* The id table and the style sheets, once the tree is read. */
static bool index_document(svg_doc *doc)
{
    doc->ids = calloc(doc->nodes ? doc->nodes : 1, sizeof *doc->ids);
    if (!doc->ids) {
        svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
        return false;
    }
    size_t k = 0;
    collect(doc, doc->root, &k);
    doc->n_ids = k;
    qsort(doc->ids, k, sizeof *doc->ids, cmp_id);
    return doc->status == SR_OK;
}

static svg_node *find_id(const svg_doc *doc, const char *id)
{
    size_t lo = 0, hi = doc->n_ids;
    while (lo < hi) { /* the first entry not below id */
        size_t mid = (lo + hi) / 2;
        if (strcmp(doc->ids[mid].id, id) < 0) {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    return lo < doc->n_ids && strcmp(doc->ids[lo].id, id) == 0 ? doc->ids[lo].node : NULL;
}

/* A declaration with where it comes from, for the cascade. */
typedef struct cascaded {
    const svg_css_decl *decl;
    long rank;               /* origin and importance, then specificity */
    int order;
} cascaded;

static int cmp_cascaded(const void *a, const void *b)
{
    const cascaded *x = a, *y = b;
    if (x->rank != y->rank) {
        return x->rank < y->rank ? -1 : 1;
    }
    return (x->order > y->order) - (x->order < y->order);
}

/* Ranks: presentation attributes, then sheet rules by specificity, then
 * the style attribute; !important sheet rules above all of those, and
 * !important in the style attribute above everything. */
#define RANK_SHEET 1L
#define RANK_STYLE_ATTR (1L << 40)
#define RANK_IMPORTANT (1L << 41)

/* Attributes that are certainly no property: no property's name has
 * fewer than three letters (x, y, r, d, cx, rx, x1, fx, ...), and the
 * other geometry a shape carries on every element.  Skipping them spares
 * apply_property's walk through every name it knows. */
static bool is_geometry_attribute(const char *a)
{
    return a[0] == 0 || a[1] == 0 || a[2] == 0 || strcmp(a, "width") == 0 ||
           strcmp(a, "height") == 0 || strcmp(a, "points") == 0;
}

/* style, transform, class, id and marker: attributes the cascade reads
 * otherwise or not at all (the marker shorthand is a property of sheets
 * and style="", not a presentation attribute). */
static bool is_structure_attribute(const char *a)
{
    switch (a[0]) {
    case 's':
        return strcmp(a, "style") == 0;
    case 't':
        return strcmp(a, "transform") == 0;
    case 'c':
        return strcmp(a, "class") == 0;
    case 'i':
        return strcmp(a, "id") == 0;
    case 'm':
        return strcmp(a, "marker") == 0;
    default:
        return false;
    }
}

/* The element's own declarations in cascade order, applied to st. */
static void apply_cascade(svg_doc *doc, const svg_node *node, style *st)
{
    for (int i = 0; node->atts[i]; i += 2) {
        const char *a = node->atts[i];
        if (!is_geometry_attribute(a) && !is_structure_attribute(a)) {
            apply_property(doc, st, a, node->atts[i + 1]);
        }
    }
    svg_css_rule inline_rule = { 0 };
    const char *style_attr = attr(node->atts, "style");
    if (style_attr && !svg_css_parse_decls(style_attr, style_attr + strlen(style_attr),
                                           &inline_rule)) {
        svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
    }
    size_t n = (size_t)inline_rule.n_decls, cap = n;
    cascaded *list = NULL;
    for (int r = 0; r < doc->sheet.n_rules; r++) {
        const svg_css_rule *rule = &doc->sheet.rules[r];
        if (!svg_css_matches(&rule->selector, node, &doc->match_work)) {
            continue;
        }
        cap += (size_t)rule->n_decls;
    }
    if (doc->match_work > SVG_CSS_MAX_WORK) {
        svg_fail(doc, SR_TOO_LARGE, "style sheets: matching selectors takes more than %ld steps",
                 SVG_CSS_MAX_WORK);
    }
    if (doc->status != SR_OK || cap == 0) {
        svg_css_free_rule(&inline_rule);
        return;
    }
    list = malloc(cap * sizeof *list);
    if (!list) {
        svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
        svg_css_free_rule(&inline_rule);
        return;
    }
    size_t k = 0;
    long unused = 0;
    for (int r = 0; r < doc->sheet.n_rules && k < cap; r++) {
        const svg_css_rule *rule = &doc->sheet.rules[r];
        if (rule->n_decls == 0 || !svg_css_matches(&rule->selector, node, &unused)) {
            continue;
        }
        for (int d = 0; d < rule->n_decls && k < cap; d++) {
            long rank = RANK_SHEET + rule->selector.specificity +
                        (rule->decls[d].important ? RANK_IMPORTANT : 0);
            list[k++] = (cascaded){ &rule->decls[d], rank, rule->order * 1000 + d };
        }
    }
    for (int d = 0; d < inline_rule.n_decls && k < cap; d++) {
        long rank = RANK_STYLE_ATTR + (inline_rule.decls[d].important ? 2 * RANK_IMPORTANT : 0);
        list[k++] = (cascaded){ &inline_rule.decls[d], rank, d };
    }
    qsort(list, k, sizeof *list, cmp_cascaded);
    for (size_t i = 0; i < k; i++) {
        if (!apply_property(doc, st, list[i].decl->name, list[i].decl->value)) {
            warn_once(doc, "property", list[i].decl->name);
        }
    }
    free(list);
    svg_css_free_rule(&inline_rule);
}

/* ---- drawing the tree ---------------------------------------------------------------- */

static bool is_named(const svg_node *n, const char *const *names)
{
    for (int i = 0; names[i]; i++) {
        if (strcmp(n->name, names[i]) == 0) {
            return true;
        }
    }
    return false;
}

/* Elements that draw nothing where they stand: definitions, metadata. */
static const char *const not_drawn[] = { "defs", "title", "desc", "metadata", "style",
                                         "linearGradient", "radialGradient", "stop", "symbol",
                                         "clipPath", "mask", "script", "marker", "pattern",
                                         "filter", NULL };

/* The language conditional processing tests against. */
#define SVG_LANGUAGE "en"

/* Whether `tag` (up to a comma or a blank) names SVG_LANGUAGE or one of
 * its regional forms ("en", "en-GB"), case aside. */
static bool language_matches(const char *tag, size_t n)
{
    size_t k = strlen(SVG_LANGUAGE);
    return n >= k && strncasecmp(tag, SVG_LANGUAGE, k) == 0 && (n == k || tag[k] == '-');
}

/* The SVG 1.1 feature strings (its appendix A) of what the reader draws
 * (text in feature_supported): not SVG fonts, foreignObject, colour
 * profiles, enable-background, the clip property or the dynamic features. */
static const char *const features[] = {
    "BasicClip", "BasicFilter", "BasicGraphicsAttribute", "BasicPaintAttribute",
    "BasicStructure", "Clip", "ConditionalProcessing", "CoreAttribute", "Filter", "Gradient",
    "Image", "Marker", "Mask", "OpacityAttribute", "Pattern", "Shape", "Structure", "Style",
    "XlinkAttribute", NULL,
};

/* Whether the feature string of n bytes is one of features[]. */
static bool feature_supported(const char *f, size_t n)
{
    static const char prefix[] = "http://www.w3.org/TR/SVG11/feature#";
    size_t k = sizeof prefix - 1;
    if (n <= k || strncmp(f, prefix, k) != 0) {
        return false;
    }
    for (int i = 0; features[i]; i++) {
        if (strlen(features[i]) == n - k && strncmp(f + k, features[i], n - k) == 0) {
            return true;
        }
    }
    /* text, in a build that draws it */
    return svg_text_available() && ((n - k == 9 && strncmp(f + k, "BasicText", 9) == 0) ||
                                     (n - k == 4 && strncmp(f + k, "Text", 4) == 0));
}

/* The conditional processing attributes: systemLanguage (a comma list of
 * language tags, one of which must match), requiredExtensions (none is
 * supported, so any list fails) and requiredFeatures (a list of feature
 * strings, all of which must be supported; SVG 2 drops the attribute,
 * but SVG 1.1 drawings use it to offer a fallback for what a renderer
 * lacks, such as text).  An empty list fails, as SVG 1.1 says. */
static bool conditions_hold(const svg_node *node)
{
    const char *ext = attr(node->atts, "requiredExtensions");
    if (ext) {
        return false;
    }
    const char *feat = attr(node->atts, "requiredFeatures");
    if (feat) {
        const char *s = svg_skip_ws(feat);
        if (!*s) {
            return false;
        }
        for (; *s; s = svg_skip_ws(s)) {
            size_t n = strcspn(s, " \t\r\n");
            if (!feature_supported(s, n)) {
                return false;
            }
            s += n;
        }
    }
    const char *lang = attr(node->atts, "systemLanguage");
    if (!lang) {
        return true;
    }
    for (const char *s = svg_skip_ws(lang); *s; s = svg_skip_ws_comma(s)) {
        size_t n = strcspn(s, ", \t\r\n");
        if (language_matches(s, n)) {
            return true;
        }
        s += n;
    }
    return false;
}

static void draw_node(svg_doc *doc, svg_node *node, const frame *parent);
static void draw_content(svg_doc *doc, svg_node *node, frame *fp, bool shape, bool use);

static void draw_children(svg_doc *doc, svg_node *node, const frame *f)
{
    for (svg_node *c = node->first; c && doc->status == SR_OK; c = c->next) {
        draw_node(doc, c, f);
    }
}

/* Done with a path shape_at_scale made (NULL allowed): the next shape
 * reuses it, cleared, when it is flattened with the same tolerance (the
 * usual case: siblings share a transform), which saves the path's
 * allocations per element.  A path of many points is freed rather than
 * kept, so one large shape does not hold its memory to the end. */
#define SPARE_PATH_MAX_POINTS 4096

static void release_shape_path(svg_doc *doc, sr_path *p, double tol)
{
    if (!p) {
        return;
    }
    if (doc->spare_path || sr_path_polygon(p).point_count > SPARE_PATH_MAX_POINTS) {
        sr_destroy_path(doc->ctx, p);
        return;
    }
    sr_path_clear(p);
    doc->spare_path = p;
    doc->spare_tol = tol;
}

/* Curves of path p (through m to device pixels) that lie beyond the
 * budget's square grown by reach (cull_reach; < 0: none) drawn as lines:
 * the square holds every guard band (sr_fill_polygon). */
static void cull_beyond_budget(sr_path *p, mat2d m, double reach)
{
    const double b = SR_MAX_COORD2D + reach;
    const sr_path_view view = { { m.a, m.b, m.c, m.d, m.e, m.f }, -b, -b, b, b };
    sr_path_cull_curves(p, reach >= 0 && isfinite(b) ? &view : NULL);
}

/* The shape's path in user units, flattened finely enough for the
 * frame's scale (*tol); NULL when there is nothing to draw or after a
 * failure.  Flattening is work too, drawn or not (fill="none"). */
static sr_path *shape_at_scale(svg_doc *doc, const svg_node *node, const frame *f, double *tol,
                               bool *fillable)
{
    double scale = matrix_scale(f->m);
    *tol = scale > 0 ? 0.1 / scale : 0.1;
    if (!(*tol > 0) || !isfinite(*tol)) {
        return NULL; /* a singular transform: nothing visible */
    }
    sr_path *p = NULL;
    if (doc->spare_path && doc->spare_tol == *tol) {
        p = doc->spare_path;
        doc->spare_path = NULL;
    } else {
        sr_result r = sr_make_path(doc->ctx, *tol, &p);
        if (r != SR_OK) {
            lib_fail(doc, r);
            return NULL;
        }
    }
    cull_beyond_budget(p, f->m, doc->cull_reach);
    if (shape_path(doc, f, node->name, node->atts, p, fillable) && doc->status == SR_OK &&
        points_within_budget(doc, sr_path_polygon(p).point_count)) {
        doc->points_used += sr_path_polygon(p).point_count;
        return p;
    }
    release_shape_path(doc, p, *tol);
    return NULL;
}

/* ---- markers ----------------------------------------------------------------------- */


/* An angle: a number of degrees, or with deg, rad, grad or turn (in any
 * case, as CSS reads units). */
static bool parse_angle(const char *v, double *deg)
{
    static const struct { const char *unit; double deg; } units[] = {
        { "deg", 1 }, { "grad", 0.9 }, { "rad", 180 / M_PI }, { "turn", 360 }, { "", 1 },
    };
    const char *s = svg_skip_ws(v);
    if (!svg_parse_number(&s, deg)) {
        return false;
    }
    for (size_t i = 0; i < sizeof units / sizeof units[0]; i++) {
        size_t n = strlen(units[i].unit);
        if (strncasecmp(s, units[i].unit, n) == 0 && *svg_skip_ws(s + n) == 0) {
            *deg *= units[i].deg;
            return true;
        }
    }
    return false;
}

/* One marker at user-space point p; `angle` (radians) is the path's
 * direction there, for orient="auto". */
static void draw_marker(svg_doc *doc, const frame *f, svg_node *m, sr_point2 p, double angle,
                        bool start)
{
    doc->line = m->line;
    if (m->active) {
        svg_fail(doc, SR_BAD_FORMAT, "marker: reference cycle through \"#%s\"",
                 SVG_QUOTED(m->id));
        return;
    }
    if (!points_within_budget(doc, 1)) {
        return;
    }
    doc->points_used++;
    const char *orient = attr(m->atts, "orient");
    double a = 0, deg;
    if (orient && strcmp(orient, "auto") == 0) {
        a = angle;
    } else if (orient && strcmp(orient, "auto-start-reverse") == 0) {
        a = start ? angle + M_PI : angle;
    } else if (orient && parse_angle(orient, &deg)) {
        a = deg * M_PI / 180;
    } else if (orient) {
        warn_once(doc, "orient", orient);
    }
    double mw = 3, mh = 3, rx = 0, ry = 0, vb[4];
    const char *mws = attr(m->atts, "markerWidth"), *mhs = attr(m->atts, "markerHeight");
    if ((mws && !length_attr(doc, f, "width", mws, &mw)) ||
        (mhs && !length_attr(doc, f, "height", mhs, &mh)) ||
        !length_attr(doc, f, "x", attr(m->atts, "refX"), &rx) ||
        !length_attr(doc, f, "y", attr(m->atts, "refY"), &ry) || !(mw > 0 && mh > 0)) {
        return;
    }
    const char *units = attr(m->atts, "markerUnits");
    double sw = units && strcmp(units, "userSpaceOnUse") == 0 ? 1 : f->st.stroke_width;
    double c = cos(a), si = sin(a);
    mat2d place = mat_mul(mat_mul((mat2d){ 1, 0, 0, 1, p.x, p.y }, (mat2d){ c, si, -si, c, 0, 0 }),
                          (mat2d){ sw, 0, 0, sw, 0, 0 });
    frame mf = { .st = ancestor_style(doc, m), .vp_w = mw, .vp_h = mh };
    mat2d content = IDENTITY;
    const char *vbs = attr(m->atts, "viewBox");
    if (vbs && parse_viewbox(vbs, vb)) {
        content = viewbox_matrix(doc, m->atts, vb, 0, 0, mw, mh);
        mf.vp_w = vb[2];
        mf.vp_h = vb[3];
    }
    /* refX, refY (content units) land on the vertex */
    sr_point2 ref = mat_apply(content, (sr_point2){ rx, ry });
    content = mat_mul((mat2d){ 1, 0, 0, 1, -ref.x, -ref.y }, content);
    mf.m = mat_mul(mat_mul(f->m, place), content);
    if (doc->status != SR_OK || !(sw > 0)) {
        return;
    }
    /* Unless overflow is visible, what the marker draws is cut to its
     * viewport: the fills of its content clip to it in pixels. */
    bool clip = !mf.st.overflow_visible && doc->n_windows < MAX_WINDOWS;
    mat2d to_px = mat_mul(f->m, place);
    if (clip && !(fabs(to_px.a * to_px.d - to_px.b * to_px.c) > 1e-12)) {
        return; /* a viewport of no area in pixels shows nothing */
    }
    if (clip) {
        sr_point2 *w = doc->windows[doc->n_windows++];
        w[0] = mat_apply(to_px, (sr_point2){ -ref.x, -ref.y });
        w[1] = mat_apply(to_px, (sr_point2){ -ref.x + mw, -ref.y });
        w[2] = mat_apply(to_px, (sr_point2){ -ref.x + mw, -ref.y + mh });
        w[3] = mat_apply(to_px, (sr_point2){ -ref.x, -ref.y + mh });
    }
    m->active = true;
    draw_children(doc, m, &mf);
    m->active = false;
    doc->n_windows -= clip;
}

/* The direction into (dir -1) or out of (dir 1) vertex v of the path,
 * false when the subpath has no other point; a closed subpath wraps. */
static bool vertex_direction(const sr_polygon2 *poly, int start, int count, bool closed,
                             const svg_vertex *v, int dir, double *angle)
{
    sr_point2 p = poly->points[v->at];
    int i = v->at - start;
    if (v->kind == 'Z') {
        i = dir < 0 ? count : 0; /* in: the closing segment; out: the first one */
    }
    for (int k = 1; k < count; k++) {
        int j = i + dir * k;
        if (j < 0 || j >= count) {
            if (!closed) {
                return false;
            }
            j = (j + count) % count;
        }
        sr_point2 q = poly->points[start + j];
        if (q.x != p.x || q.y != p.y) {
            *angle = dir < 0 ? atan2(p.y - q.y, p.x - q.x) : atan2(q.y - p.y, q.x - p.x);
            return true;
        }
    }
    return false;
}

/* marker-start on the first vertex, marker-end on the last, marker-mid
 * on the others, each turned along the path's direction there (the
 * bisector where a segment comes in and one goes out). */
static void draw_markers(svg_doc *doc, const frame *f, const sr_path *path, const svg_vertex *v,
                         int n)
{
    sr_polygon2 poly = sr_path_polygon(path);
    int contour = -1, start = 0;
    for (int i = 0; i < n && doc->status == SR_OK; i++) {
        while (contour < v[i].contour) {
            start += contour >= 0 ? poly.contour_counts[contour] : 0;
            contour++;
        }
        int which = i == 0 ? 0 : i == n - 1 ? 2 : 1;
        if (!f->st.marker[which]) {
            continue;
        }
        int count = poly.contour_counts[contour];
        bool closed = sr_path_subpath_closed(path, contour);
        double in = 0, out = 0;
        bool has_in = vertex_direction(&poly, start, count, closed, &v[i], -1, &in);
        bool has_out = vertex_direction(&poly, start, count, closed, &v[i], 1, &out);
        double angle = has_in ? in : out;
        if (has_in && has_out) {
            double d = remainder(out - in, 2 * M_PI);
            angle = in + d / 2;
        }
        draw_marker(doc, f, (svg_node *)f->st.marker[which], poly.points[v[i].at], angle,
                    which == 0);
    }
}

/* Whether paint p is laid out on the bounding box of what it paints
 * (objectBoundingBox units), which moves when curves far off are drawn
 * as lines.  Gradients and patterns in user space do not move. */
static bool paint_on_box(const svg_doc *doc, const paint *p)
{
    if (p->kind != SVG_PAINT_URL) {
        return false;
    }
    if (is_gradient(p->server)) {
        const char *units = grad_attr(doc, p->server, "gradientUnits");
        return !units || strcmp(units, "userSpaceOnUse") != 0;
    }
    const char *units = grad_attr(doc, p->server, "patternUnits");
    const char *content = grad_attr(doc, p->server, "patternContentUnits");
    return !units || strcmp(units, "userSpaceOnUse") != 0 ||
           (content && strcmp(content, "objectBoundingBox") == 0);
}

/* How far past the fixed-point budget, in device pixels, a curve of the
 * shape drawn under f must lie to be drawn as a line (sr_path_cull_curves): its
 * stroke's half width times the most a miter or square cap reaches, and
 * a pixel.  -1 (never) when the flattened points are measured as well as
 * drawn: markers (their angles), dashes (the length along the path) and
 * paints laid out on the bounding box. */
static double cull_reach(const svg_doc *doc, const frame *f)
{
    const style *st = &f->st;
    if (doc->want_verts || st->n_dash > 0 || paint_on_box(doc, &st->fill) ||
        paint_on_box(doc, &st->stroke)) {
        return -1;
    }
    if (st->stroke.kind == SVG_PAINT_NONE || !(st->stroke_width > 0)) {
        return 1;
    }
    return stroke_reach(st, st->non_scaling ? doc->root_m : f->m);
}

static void draw_shape(svg_doc *doc, const svg_node *node, const frame *f)
{
    double tol;
    bool fillable;
    static const char *const markable[] = { "path", "line", "polyline", "polygon", NULL };
    doc->want_verts = (f->st.marker[0] || f->st.marker[1] || f->st.marker[2]) &&
                      is_named(node, markable);
    doc->n_verts = 0;
    doc->cull_reach = cull_reach(doc, f);
    sr_path *p = shape_at_scale(doc, node, f, &tol, &fillable);
    doc->cull_reach = -1;
    /* the vertices are this shape's: markers draw paths of their own */
    svg_vertex *verts = doc->verts;
    int n_verts = doc->n_verts;
    doc->verts = NULL;
    doc->n_verts = doc->cap_verts = 0;
    doc->want_verts = false;
    for (int i = 0; p && i < 3 && doc->status == SR_OK; i++) {
        if (f->st.paint_order[i] == PAINT_MARKERS) {
            draw_markers(doc, f, p, verts, n_verts);
        } else {
            draw_path(doc, f, p, tol, fillable, f->st.paint_order[i]);
        }
    }
    free(verts);
    release_shape_path(doc, p, tol);
}

/* ---- text ------------------------------------------------------------------------- */

#ifdef SR_HAVE_SVG_TEXT

/* Font sizes beyond this many pixels are refused: a glyph's curves would
 * pass the flattening's 2^16 steps before its tolerance.  Below it, the
 * curves far off the image are drawn as lines (cull_beyond_budget). */
#define MAX_FONT_PIXELS 1e8

/* The frames of a text's elements, by svg_text_open's index. */
typedef struct text_walk {
    svg_text *t;
    frame *frames;
    int cap;
    double tol;                  /* flattening tolerance in user units */
} text_walk;

/* The path a textPath names (a path or, as SVG 2 allows, a basic shape),
 * its own transform applied, flattened for the text of element elem
 * (svg_text_open's index).  False with a warning when it names none; a
 * failure is reported. */
static bool text_path_of(svg_doc *doc, text_walk *w, const svg_node *tp, const frame *f,
                         int elem)
{
    const char *h = href_of(tp);
    const svg_node *target = h ? reference(doc, h, NULL) : NULL;
    sr_path *p = NULL;
    bool fillable, ok = false;
    mat2d m = IDENTITY;
    const char *tr = target ? attr(target->atts, "transform") : NULL;
    if (!target || !is_shape(target->name) || (tr && !parse_transform(tr, &m))) {
        warn_keyed(doc, "textPath href", "textPath: href=\"%s\" names no path; its text skipped",
                   SVG_QUOTED(h));
        return false;
    }
    if (sr_make_path(doc->ctx, w->tol / fmax(matrix_scale(m), 1e-9), &p) != SR_OK) {
        svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
        return false;
    }
    /* the flattened path's points count as a shape's do */
    if (shape_path(doc, f, target->name, target->atts, p, &fillable) && doc->status == SR_OK &&
        points_within_budget(doc, sr_path_polygon(p).point_count)) {
        sr_polygon2 poly = sr_path_polygon(p);
        doc->points_used += poly.point_count;
        int n = 0, cap = poly.point_count + poly.contour_count;
        double *xy = malloc((size_t)(cap > 0 ? cap : 1) * 2 * sizeof *xy);
        unsigned char *move = malloc((size_t)(cap > 0 ? cap : 1));
        for (int c = 0, k = 0; xy && move && c < poly.contour_count; c++) {
            int count = poly.contour_counts ? poly.contour_counts[c] : poly.point_count;
            /* a closed subpath goes back to its start */
            int last = count + (sr_path_subpath_closed(p, c) && count > 1);
            for (int i = 0; i < last; i++) {
                sr_point2 q = mat_apply(m, poly.points[k + i % count]);
                if (i > 0 && q.x == xy[2 * (n - 1)] && q.y == xy[2 * (n - 1) + 1]) {
                    continue; /* no segment of no length: it has no tangent */
                }
                xy[2 * n] = q.x;
                xy[2 * n + 1] = q.y;
                move[n++] = i == 0;
            }
            k += count;
        }
        const char *so = attr(tp->atts, "startOffset");
        double start = 0;
        bool pct = false;
        if (so && !svg_parse_length(so, f->st.text.size, &start, &pct)) {
            warn_keyed(doc, "textPath startOffset", "textPath: startOffset=\"%s\" is not a "
                       "length; 0 taken", SVG_QUOTED(so));
            start = 0, pct = false;
        }
        ok = xy && move && svg_text_set_path(w->t, elem, xy, move, n, start, pct);
        if (!ok) {
            svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
        }
        free(xy);
        free(move);
    }
    sr_destroy_path(doc->ctx, p);
    return ok;
}

/* The character data of node's descendants in document order into the
 * text: what a tref draws (SVG 1.1 10.6, the referenced element's
 * flattened text content).  Nesting beyond depth is left out. */
static void tref_chars(svg_doc *doc, text_walk *w, const svg_node *node, bool preserve,
                       bool visible, int depth)
{
    for (const svg_node *c = node->first; c && doc->status == SR_OK; c = c->next) {
        if (strcmp(c->name, "#text") == 0) {
            if (!svg_text_chars(w->t, c->text ? c->text : "", c->text_len, preserve, visible)) {
                svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
            }
        } else if (depth > 0) {
            tref_chars(doc, w, c, preserve, visible, depth - 1);
        }
    }
}

/* Open a text element (its frame cascaded), add its characters and its
 * tspans' in order, close it. */
static void text_element(svg_doc *doc, text_walk *w, const svg_node *node, const frame *f,
                         bool preserve)
{
    const char *space = attr(node->atts, "xml:space");
    if (space) {
        preserve = strcmp(space, "preserve") == 0;
    }
    const char *lists[7] = { attr(node->atts, "x"), attr(node->atts, "y"),
                             attr(node->atts, "dx"), attr(node->atts, "dy"),
                             attr(node->atts, "rotate"), attr(node->atts, "textLength"),
                             attr(node->atts, "lengthAdjust") };
    char why[160];
    doc->line = node->line;
    int i = svg_text_open(w->t, &f->st.text, lists, f->vp_w, f->vp_h, why, sizeof why);
    if (i < 0) {
        svg_fail(doc, strstr(why, "memory") ? SR_OUT_OF_MEMORY : SR_BAD_FORMAT, "%s", why);
        return;
    }
    if (i >= w->cap) {
        int cap = w->cap ? 2 * w->cap : 8;
        frame *grown = realloc(w->frames, (size_t)cap * sizeof *grown);
        if (!grown) {
            svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
            return;
        }
        w->frames = grown;
        w->cap = cap;
    }
    w->frames[i] = *f;
    if (strcmp(node->name, "textPath") == 0 && !text_path_of(doc, w, node, f, i)) {
        svg_text_close(w->t);
        return;
    }
    if (strcmp(node->name, "tref") == 0) {
        const char *h = href_of(node);
        const svg_node *target = h ? reference(doc, h, NULL) : NULL;
        if (target) {
            tref_chars(doc, w, target, preserve, !f->st.invisible, 32);
        } else {
            warn_keyed(doc, "tref href", "tref: href=\"%s\" names no element of the document; "
                       "skipped", SVG_QUOTED(h));
        }
        svg_text_close(w->t);
        return;
    }
    for (const svg_node *c = node->first; c && doc->status == SR_OK; c = c->next) {
        if (strcmp(c->name, "#text") == 0) {
            if (!svg_text_chars(w->t, c->text ? c->text : "", c->text_len, preserve,
                                !f->st.invisible)) {
                svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
            }
        } else if ((strcmp(c->name, "tspan") == 0 || strcmp(c->name, "a") == 0 ||
                    strcmp(c->name, "tref") == 0 ||
                    (strcmp(c->name, "textPath") == 0 && strcmp(node->name, "text") == 0)) &&
                   conditions_hold(c)) {
            const char *method = strcmp(c->name, "textPath") == 0 ? attr(c->atts, "method") : NULL;
            const char *side = strcmp(c->name, "textPath") == 0 ? attr(c->atts, "side") : NULL;
            if (method && strcmp(method, "stretch") == 0) {
                warn_keyed(doc, "textPath method", "textPath: method=\"stretch\" drawn as "
                           "\"align\"");
            }
            if (side && strcmp(side, "right") == 0) {
                warn_keyed(doc, "textPath side", "textPath: side=\"right\" drawn as \"left\"");
            }
            frame cf = *f;
            cf.st.own_opacity = 1;
            svg_text_reset_uninherited(&cf.st.text);
            doc->line = c->line;
            doc->inherit_from = &f->st;
            apply_cascade(doc, c, &cf.st);
            doc->inherit_from = NULL;
            svg_text_settle(&cf.st.text, &f->st.text);
            cf.st.opacity *= cf.st.own_opacity;
            if (!cf.st.display_none) {
                text_element(doc, w, c, &cf, preserve);
            }
        } else if (!c->foreign && !is_named(c, not_drawn)) {
            doc->line = c->line;
            warn_once(doc, "element", c->name);
        }
    }
    svg_text_close(w->t);
}

/* Fill and stroke each run of a laid out text with its element's paint,
 * as the path of a shape. */
static void draw_text_runs(svg_doc *doc, text_walk *w, double tol)
{
    int n = svg_text_runs(w->t);
    sr_path **paths = calloc((size_t)(n > 0 ? n : 1), sizeof *paths);
    if (!paths) {
        svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
        return;
    }
    /* every run's outline first: objectBoundingBox paints measure the
     * whole text, as they would a path */
    double box[4] = { INFINITY, INFINITY, -INFINITY, -INFINITY };
    bool cull = true; /* unless a run's paint measures that box */
    for (int r = 0; r < n; r++) {
        const frame *rf = &w->frames[svg_text_run_element(w->t, r)];
        cull = cull && cull_reach(doc, rf) >= 0;
    }
    for (int r = 0; r < n && doc->status == SR_OK; r++) {
        sr_result res = sr_make_path(doc->ctx, tol, &paths[r]);
        if (res == SR_OK) {
            const frame *rf = &w->frames[svg_text_run_element(w->t, r)];
            cull_beyond_budget(paths[r], rf->m, cull ? cull_reach(doc, rf) : -1);
            res = svg_text_run_path(w->t, doc->fonts, r, paths[r]);
        }
        if (res != SR_OK) {
            lib_fail(doc, res);
        } else if (path_within_limits(doc, paths[r], "text", 0)) {
            doc->points_used += sr_path_polygon(paths[r]).point_count;
            double b[4];
            if (bounding_box(sr_path_polygon(paths[r]), b)) {
                box[0] = fmin(box[0], b[0]), box[1] = fmin(box[1], b[1]);
                box[2] = fmax(box[2], b[2]), box[3] = fmax(box[3], b[3]);
            }
        }
    }
    sr_point2 corners[4] = { { box[0], box[1] }, { box[2], box[1] }, { box[2], box[3] },
                             { box[0], box[3] } };
    int four = 4;
    sr_polygon2 whole = { .points = corners, .point_count = 4, .contour_counts = &four,
                          .contour_count = 1 };
    for (int r = 0; r < n && doc->status == SR_OK; r++) {
        frame rf = w->frames[svg_text_run_element(w->t, r)];
        rf.st.fill_rule = SR_NONZERO; /* glyph outlines are made for nonzero */
        doc->paint_box = box[0] <= box[2] ? &whole : NULL;
        for (int i = 0; i < 3 && doc->status == SR_OK; i++) {
            if (rf.st.paint_order[i] != PAINT_MARKERS) {
                draw_path(doc, &rf, paths[r], tol, true, rf.st.paint_order[i]);
            }
        }
        doc->paint_box = NULL;
    }
    for (int r = 0; r < n; r++) {
        sr_destroy_path(doc->ctx, paths[r]);
    }
    free(paths);
}

/* Read text element node's characters under frame f into a walk, with
 * the scale of f and the flattening tolerance for it.  False when nothing
 * is visible (a singular transform) or after reporting a failure. */
static bool text_start(svg_doc *doc, const svg_node *node, const frame *f, double *scale,
                       double *tol, text_walk *w)
{
    *scale = matrix_scale(f->m);
    *tol = *scale > 0 ? 0.1 / *scale : 0.1;
    if (!(*tol > 0) || !isfinite(*tol)) {
        return false;
    }
    if (!doc->fonts && !(doc->fonts = svg_fonts_make())) {
        svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
        return false;
    }
    *w = (text_walk){ .t = svg_text_make(), .tol = *tol };
    if (!w->t) {
        svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
        return false;
    }
    text_element(doc, w, node, f, false);
    return true;
}

/* Lay out the text a walk read at the drawing's scale, within the
 * budgets (each character a point of it, drawn or not), warning what it
 * draws differently; false when there is nothing to draw or after
 * reporting a failure. */
static bool text_laid_out(svg_doc *doc, const svg_node *node, text_walk *w, double scale)
{
    doc->line = node->line;
    if (doc->status != SR_OK || !points_within_budget(doc, svg_text_length(w->t))) {
        return false;
    }
    doc->points_used += svg_text_length(w->t);
    double px = svg_text_max_size(w->t) * scale;
    char why[256];
    sr_result r;
    if (px > MAX_FONT_PIXELS) {
        svg_fail(doc, SR_TOO_LARGE, "text: a font-size of %.6g pixels (beyond %.0f)", px,
                 MAX_FONT_PIXELS);
        return false;
    }
    if (svg_text_length(w->t) == 0) {
        return false; /* nothing to lay out */
    }
    if ((r = svg_text_layout(w->t, doc->fonts, why, sizeof why)) == SR_BAD_FORMAT) {
        warn_keyed(doc, "text font", "text skipped: %s", why);
        return false;
    }
    if (r != SR_OK) {
        svg_fail(doc, r, "%s", why);
        return false;
    }
    uint32_t cp = svg_text_missing(w->t);
    if (cp) {
        warn_keyed(doc, "text glyph",
                   "text: no font has U+%04X; drawn as its font's missing-glyph box",
                   (unsigned)cp);
    }
    if (svg_text_unordered(w->t)) {
        warn_keyed(doc, "text bidi",
                   "text: right-to-left and left-to-right text left in logical order "
                   "(built without FriBidi)");
    }
    return true;
}

static void draw_text(svg_doc *doc, const svg_node *node, const frame *f)
{
    double scale, tol;
    text_walk w;
    if (!text_start(doc, node, f, &scale, &tol, &w)) {
        return;
    }
    if (text_laid_out(doc, node, &w, scale)) {
        draw_text_runs(doc, &w, tol);
    }
    free(w.frames);
    svg_text_free(w.t);
}

/* The coverage of a text that is a child of a clipPath (or a shape a use
 * in one names) under frame f into cov: the union of its glyph areas,
 * each glyph filled by the nonzero rule its outline is drawn for, as
 * when the text is filled; characters made hidden add nothing.  False
 * when it covers nothing or after reporting a failure. */
static bool clip_text(svg_doc *doc, const svg_node *node, const frame *f, uint8_t *cov)
{
    double scale, tol;
    text_walk w;
    if (f->st.display_none || f->st.invisible || !text_start(doc, node, f, &scale, &tol, &w)) {
        return false;
    }
    int width = sr_framebuffer_width(doc->fb), height = sr_framebuffer_height(doc->fb);
    size_t n_px = (size_t)width * (size_t)height;
    bool drawn = false;
    uint8_t *run_cov = NULL;
    if (text_laid_out(doc, node, &w, scale) &&
        work_within_budget(doc, (double)n_px * svg_text_runs(w.t))) {
        run_cov = malloc(n_px);
        if (!run_cov) {
            svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
        } else {
            memset(cov, 0, n_px);
            drawn = true;
        }
    }
    int runs = drawn ? svg_text_runs(w.t) : 0;
    for (int r = 0; r < runs && doc->status == SR_OK; r++) {
        sr_path *p = NULL;
        sr_result res = sr_make_path(doc->ctx, tol, &p);
        if (res == SR_OK) {
            cull_beyond_budget(p, f->m, 1);
            res = svg_text_run_path(w.t, doc->fonts, r, p);
        }
        sr_point2 *pts;
        sr_polygon2 poly;
        if (res != SR_OK) {
            lib_fail(doc, res);
        } else if (path_within_limits(doc, p, "text", 0) &&
                   (poly = sr_path_polygon(p)).point_count > 0 &&
                   map_polygon(doc, poly, f->m, &pts)) {
            doc->points_used += poly.point_count;
            poly.points = pts;
            sr_fill_desc desc = { .rule = SR_NONZERO,
                                  .antialias = f->st.crisp ? SR_AA_NONE : SR_AA_AREA };
            res = sr_polygon_coverage(doc->ctx, &poly, &desc, 0, 0, width, height, run_cov,
                                      (size_t)width);
            free(pts);
            if (res != SR_OK) {
                lib_fail(doc, res);
            }
            /* runs are separate paths: their union, a + b - ab */
            for (size_t i = 0; res == SR_OK && i < n_px; i++) {
                unsigned a = cov[i], b = run_cov[i];
                cov[i] = (uint8_t)(a + b - (a * b + 127) / 255);
            }
        }
        sr_destroy_path(doc->ctx, p);
    }
    free(run_cov);
    free(w.frames);
    svg_text_free(w.t);
    return drawn && doc->status == SR_OK;
}

static void box_point(double b[4], sr_point2 q);

/* Add the outlines of text element node, laid out as draw_text lays it
 * out under frame f, to b[4] through m, for bbox_add: a filter, clip or
 * mask in objectBoundingBox units measures a text by its glyphs.  Text
 * that draw_text would refuse or skip adds nothing; drawing reports it. */
static void text_bbox_add(svg_doc *doc, const svg_node *node, const frame *f, mat2d m,
                          double b[4])
{
    double scale, tol;
    text_walk w;
    if (!text_start(doc, node, f, &scale, &tol, &w)) {
        return;
    }
    char why[256];
    if (doc->status == SR_OK && svg_text_length(w.t) > 0 &&
        doc->points_used + svg_text_length(w.t) <= doc->points_budget &&
        svg_text_max_size(w.t) * scale <= MAX_FONT_PIXELS &&
        svg_text_layout(w.t, doc->fonts, why, sizeof why) == SR_OK) {
        int n = svg_text_runs(w.t);
        for (int r = 0; r < n && doc->status == SR_OK; r++) {
            sr_path *p = NULL;
            if (sr_make_path(doc->ctx, tol, &p) != SR_OK) {
                svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
                break;
            }
            if (svg_text_run_path(w.t, doc->fonts, r, p) == SR_OK) {
                sr_polygon2 poly = sr_path_polygon(p);
                for (int i = 0; i < poly.point_count; i++) {
                    box_point(b, mat_apply(m, poly.points[i]));
                }
            }
            sr_destroy_path(doc->ctx, p);
        }
    }
    free(w.frames);
    svg_text_free(w.t);
}
#else
static void draw_text(svg_doc *doc, const svg_node *node, const frame *f)
{
    (void)doc, (void)node, (void)f; /* not reached: holds_text and draw_node skip text */
}

static bool clip_text(svg_doc *doc, const svg_node *node, const frame *f, uint8_t *cov)
{
    (void)doc, (void)node, (void)f, (void)cov; /* not reached: clip_mask skips text */
    return false;
}

static void text_bbox_add(svg_doc *doc, const svg_node *node, const frame *f, mat2d m,
                          double b[4])
{
    (void)doc, (void)node, (void)f, (void)m, (void)b; /* text is not drawn */
}
#endif

/* ---- images -------------------------------------------------------------------------- */

/* An image's viewport x, y, width, height in r; a width or height that
 * is missing or "auto" (the picture's own, known once it is read) is -1.
 * False after reporting a malformed length. */
static bool image_rect(svg_doc *doc, const svg_node *node, const frame *f, double r[4])
{
    const char *ws = attr(node->atts, "width"), *hs = attr(node->atts, "height");
    r[2] = r[3] = -1;
    return length_attr(doc, f, "x", attr(node->atts, "x"), &r[0]) &&
           length_attr(doc, f, "y", attr(node->atts, "y"), &r[1]) &&
           (!ws || strcmp(ws, "auto") == 0 || length_attr(doc, f, "width", ws, &r[2])) &&
           (!hs || strcmp(hs, "auto") == 0 || length_attr(doc, f, "height", hs, &r[3]));
}

/* SVG images inside SVG images, at most: each is drawn in a layer of its
 * own, and this leaves one of the MAX_LAYERS for the outer document. */
#define MAX_NESTED_IMAGES (MAX_LAYERS - 1)

static bool read_document(svg_doc *doc, const char *data, size_t size);
static void free_document(svg_doc *doc);
static style initial_style(void);
static uint8_t *rect_coverage(svg_doc *doc, const double r[4], const frame *f);
static sr_framebuffer *open_layer(svg_doc *doc);
static void close_layer(svg_doc *doc, sr_framebuffer *under);
static void composite_layer(svg_doc *doc, sr_framebuffer *layer, const uint8_t *mask,
                            double opacity, svg_blend_kind mode);

/* The image's viewport for a picture of intrinsic size iw x ih: a
 * missing size is the picture's; one side given, the other keeps its
 * proportions.  False after reporting a malformed length. */
static bool image_viewport(svg_doc *doc, const svg_node *node, const frame *f, double iw,
                           double ih, double r[4])
{
    if (!image_rect(doc, node, f, r)) {
        return false;
    }
    double w = r[2], h = r[3];
    r[2] = w >= 0 ? w : h >= 0 ? h * iw / ih : iw;
    r[3] = h >= 0 ? h : w >= 0 ? r[2] * ih / iw : ih;
    return true;
}

/* Draw the SVG document `in` (read) as the content of an <image>: its
 * viewBox fitted into the image's viewport by the image's
 * preserveAspectRatio, in a layer clipped to that viewport and
 * composited at the image's opacity.  Its styles, ids and sheets are its
 * own; its work counts against the drawing's budgets. */
static void draw_document_image(svg_doc *doc, svg_doc *in, const svg_node *node,
                                const frame *f)
{
    double vb[4], iw, ih, vp[4];
    in->line = in->root->line;
    if (!intrinsic_size(in, in->root->atts, true, vb, &iw, &ih) ||
        !image_viewport(doc, node, f, iw, ih, vp) || !(vp[2] > 0 && vp[3] > 0)) {
        return;
    }
    if (doc->layers == MAX_LAYERS) {
        warn_once(doc, "nesting of layers", "beyond 8 (an SVG image skipped)");
        return;
    }
    uint8_t *clip = rect_coverage(doc, vp, f);
    sr_framebuffer *under = doc->fb, *top = clip ? open_layer(doc) : NULL;
    if (top) {
        frame cf = { .m = mat_mul(f->m, viewbox_matrix(doc, node->atts, vb, vp[0], vp[1], vp[2],
                                                       vp[3])),
                     .st = initial_style(), .vp_w = vb[2], .vp_h = vb[3] };
        in->fb = top;
        in->layers = doc->layers;
        in->layer_bytes = doc->layer_bytes;
        /* inside a marker, the document is cut to its viewport too */
        in->n_windows = doc->n_windows;
        memcpy(in->windows, doc->windows, sizeof in->windows);
        in->initial = cf.st;
        in->root_m = cf.m;
        in->points_used = doc->points_used;
        in->work_used = doc->work_used;
        draw_node(in, in->root, &cf);
        doc->points_used = in->points_used;
        doc->points_budget = in->points_budget; /* grown by its own SVG images */
        doc->work_used = in->work_used;
        close_layer(doc, under);
        if (in->status != SR_OK) {
            doc->status = in->status; /* the message is written */
        } else {
            composite_layer(doc, top, clip, f->st.opacity, SVG_BLEND_NORMAL);
        }
        sr_destroy_framebuffer(doc->ctx, top);
    }
    free(clip);
}

/* The document's bytes: data..size, or the bytes a gzip-compressed one
 * (.svgz) inflates to, in *plain for the caller to free (else NULL), no
 * more than a plain document may have.  SR_OK, else a result and why. */
static sr_result document_bytes(const char **data, size_t *size, char **plain, char *why,
                                size_t why_size)
{
    *plain = NULL;
    if (!svg_is_gzip(*data, *size)) {
        return SR_OK;
    }
    sr_result r = svg_gunzip(*data, *size, SR_SVG_MAX_INPUT_BYTES, plain, size, why, why_size);
    if (r == SR_OK) {
        *data = *plain;
    }
    return r;
}

/* An <image> of an SVG document (data..size; path: the file it came
 * from, NULL for a data: URI).  A file that is being drawn already - a
 * document including itself, directly or through others - is refused. */
static void draw_svg_image(svg_doc *doc, const svg_node *node, const frame *f, const char *data,
                           size_t size, const char *path, const char *href)
{
    for (const svg_doc *d = doc; d && path; d = d->outer) {
        if (d->base && strcmp(d->base, path) == 0) {
            svg_fail(doc, SR_BAD_FORMAT, "image: reference cycle through \"%s\"", SVG_QUOTED(href));
            return;
        }
    }
    if (doc->nesting + 1 > MAX_NESTED_IMAGES) {
        svg_fail(doc, SR_BAD_FORMAT, "image: SVG images nested deeper than %d",
                 MAX_NESTED_IMAGES);
        return;
    }
    char *plain, why[256];
    sr_result r = document_bytes(&data, &size, &plain, why, sizeof why);
    if (r != SR_OK) {
        svg_fail(doc, r, "image \"%s\": %s", SVG_QUOTED(href), why);
        return;
    }
    /* Reading costs its bytes of the pixel work, so that an image drawn
     * again and again cannot be read without bound; its elements and
     * points have the allowance its bytes would have inline. */
    svg_doc *in = work_within_budget(doc, (double)size) ? calloc(1, sizeof *in) : NULL;
    if (!in) {
        if (doc->status == SR_OK) {
            svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
        }
        free(plain);
        return;
    }
    in->cull_reach = -1;
    in->file = path ? path : doc->file;
    in->pinned_line = path ? 0 : msg_line(doc);
    in->base = path ? path : doc->base;
    in->outer = doc;
    in->nesting = doc->nesting + 1;
    in->opt = doc->opt;
    in->ctx = doc->ctx;
    in->fb = doc->fb;
    in->status = SR_OK;
    in->msg = doc->msg;
    in->msg_size = doc->msg_size;
    in->points_used = doc->points_used;
    doc->points_budget += (double)SR_SVG_POINTS_PER_BYTE * (double)size;
    in->points_budget = doc->points_budget;
    in->work_budget = doc->work_budget;
    in->work_used = doc->work_used;
    if (read_document(in, data, size)) {
        doc->points_used = in->points_used;
        draw_document_image(doc, in, node, f);
    } else {
        doc->status = in->status;
    }
    if (in->status != SR_OK) {
        doc->status = in->status;
    }
    free_document(in);
    free(in);
    free(plain);
}

/* Whether bytes hold XML (an SVG) rather than a PNG or a JPEG: '<'
 * first, after an optional byte-order mark and white space. */
static bool looks_like_xml(const uint8_t *b, size_t n)
{
    size_t i = n >= 3 && b[0] == 0xEF && b[1] == 0xBB && b[2] == 0xBF ? 3 : 0;
    while (i < n && isspace(b[i])) {
        i++;
    }
    return i < n && b[i] == '<';
}

/* <image>: a PNG, a JPEG or an SVG document, from a data: URI or a file
 * next to the document, fitted into its viewport (x, y, width, height;
 * a missing size is the picture's own) as preserveAspectRatio says; a
 * picture is sampled bilinearly, an SVG drawn as vector content.  What
 * does not read is skipped with a warning. */
static void draw_image(svg_doc *doc, const svg_node *node, const frame *f)
{
    const char *href = href_of(node);
    if (!href || f->st.invisible) {
        return;
    }
    sr_io_error err;
    int iw = 0, ih = 0;
    uint8_t *px = NULL, *bytes = NULL;
    size_t n = 0;
    char *path = NULL, *file = NULL;
    sr_result r = SR_BAD_FORMAT;
    if (strncmp(href, "data:", 5) == 0) {
        if (!svg_data_uri(href, &bytes, &n)) {
            bytes = NULL;
        }
    } else if (doc->base && (path = svg_image_path(doc->base, href)) != NULL &&
               sr__read_file_as(path, "an image file", &file, &n, &err) == SR_OK) {
        bytes = (uint8_t *)file;
    }
    if (bytes && (looks_like_xml(bytes, n) || svg_is_gzip(bytes, n))) {
        draw_svg_image(doc, node, f, (const char *)bytes, n, path, href);
        r = SR_OK;
    } else if (bytes) {
        r = sr_decode_image(path ? path : doc->file, bytes, n, &iw, &ih, &px, &err);
    }
    if (file) {
        sr__free_file(file, n);
    } else {
        free(bytes);
    }
    free(path);
    if (r != SR_OK) {
        warn_once(doc, "image source (not a readable PNG, JPEG or SVG next to the document)",
                  href);
    }
    double vp[4];
    if (px && image_viewport(doc, node, f, iw, ih, vp) &&
        work_within_budget(doc, (double)iw * ih)) {
        double x = vp[0], y = vp[1], w = vp[2], h = vp[3];
        double vb[4] = { 0, 0, iw, ih };
        mat2d fit = viewbox_matrix(doc, node->atts, vb, x, y, w, h), inv;
        /* drawn where the picture and its viewport meet */
        double x0 = fmax(x, fit.e), y0 = fmax(y, fit.f);
        double x1 = fmin(x + w, fit.e + iw * fit.a), y1 = fmin(y + h, fit.f + ih * fit.d);
        mat2d t = mat_mul(f->m, fit);
        if (x1 > x0 && y1 > y0 && mat_invert(t, &inv)) {
            sr_affine2 to_px = { t.a, t.b, t.c, t.d, t.e, t.f };
            sr_paint im = { .kind = SR_PAINT_PATTERN, .image = px, .image_width = iw,
                            .image_height = ih, .image_wrap = SR_WRAP_CLAMP, .transform = &to_px };
            sr_point2 corners[4] = { { x0, y0 }, { x1, y0 }, { x1, y1 }, { x0, y1 } };
            fill_mapped(doc, (sr_polygon2){ corners, 4, NULL, 0 }, f->m,
                        (sr_rgba){ 0, 0, 0, (float)f->st.opacity }, &im, SR_NONZERO, f->st.crisp);
        }
    }
    free(px);
}

/* ---- clipping and layers ------------------------------------------------------------- */

/* The coverage of one clip shape, with its clip-rule, into cov (the
 * image's size); false when it covers nothing or after a failure. */
static bool clip_shape(svg_doc *doc, const svg_node *shape, const frame *f, uint8_t *cov)
{
    int w = sr_framebuffer_width(doc->fb), h = sr_framebuffer_height(doc->fb);
    double tol = 0;
    bool fillable, drawn = false;
    sr_path *p = f->st.display_none || f->st.invisible
                     ? NULL : shape_at_scale(doc, shape, f, &tol, &fillable);
    sr_point2 *pts;
    sr_polygon2 poly;
    if (p && fillable && (poly = sr_path_polygon(p)).point_count > 0 &&
        map_polygon(doc, poly, f->m, &pts)) {
        poly.points = pts;
        sr_fill_desc desc = { .rule = f->st.clip_rule,
                              .antialias = f->st.crisp ? SR_AA_NONE : SR_AA_AREA };
        sr_result r = sr_polygon_coverage(doc->ctx, &poly, &desc, 0, 0, w, h, cov, (size_t)w);
        free(pts);
        if (r != SR_OK) {
            lib_fail(doc, r);
        }
        drawn = r == SR_OK;
    }
    release_shape_path(doc, p, tol);
    return drawn;
}

/* A use's x and y as the translation SVG appends to its transform: its
 * clip path, mask and bounding box are in the moved user space.  False
 * after reporting a malformed one. */
static bool use_offset(svg_doc *doc, const svg_node *use, const frame *f, mat2d *out)
{
    double x = 0, y = 0;
    if (!length_attr(doc, f, "x", attr(use->atts, "x"), &x) ||
        !length_attr(doc, f, "y", attr(use->atts, "y"), &y)) {
        return false;
    }
    *out = (mat2d){ 1, 0, 0, 1, x, y };
    return true;
}

/* Grow the box b[4] = x0, y0, x1, y1 to hold q.  Comparisons, which skip a
 * NaN as fmin/fmax do: GCC 12 for aarch64 crashes vectorizing a loop of
 * fmin/fmax reductions. */
static void box_point(double b[4], sr_point2 q)
{
    b[0] = q.x < b[0] ? q.x : b[0];
    b[1] = q.y < b[1] ? q.y : b[1];
    b[2] = q.x > b[2] ? q.x : b[2];
    b[3] = q.y > b[3] ? q.y : b[3];
}

/* Add the bounding box of element n (its geometry, without strokes) to
 * b[4] = x0, y0, x1, y1, where m maps n's coordinates (its transform
 * applied) into the box's space. */
static void bbox_add(svg_doc *doc, svg_node *n, const frame *f, mat2d m, double b[4])
{
    if (n->active || doc->status != SR_OK || doc->draw_depth + 1 >= MAX_DEPTH) {
        return; /* drawing refuses the cycle or the depth itself */
    }
    const char *disp = attr(n->atts, "display");
    if (disp && strcmp(disp, "none") == 0) {
        return;
    }
    frame tf = *f;
    tf.m = mat_mul(f->m, m);
    doc->draw_depth++;
    n->active = true;
    double r[4];
    if (strcmp(n->name, "image") == 0 && image_rect(doc, n, f, r) && r[2] > 0 && r[3] > 0) {
        for (int i = 0; i < 4; i++) { /* its viewport's corners */
            sr_point2 q = mat_apply(m, (sr_point2){ r[0] + r[2] * (i % 2), r[1] + r[3] * (i / 2) });
            box_point(b, q);
        }
    } else if (strcmp(n->name, "text") == 0) {
        text_bbox_add(doc, n, &tf, m, b);
    } else if (is_shape(n->name)) {
        double tol;
        bool fillable;
        sr_path *p = shape_at_scale(doc, n, &tf, &tol, &fillable);
        if (p) {
            sr_polygon2 poly = sr_path_polygon(p);
            for (int i = 0; i < poly.point_count; i++) {
                sr_point2 q = mat_apply(m, poly.points[i]);
                box_point(b, q);
            }
            release_shape_path(doc, p, tol);
        }
    } else {
        /* m holds a use's own x and y (use_offset), as it holds its
         * transform */
        bool use = strcmp(n->name, "use") == 0;
        svg_node *c = use ? (href_of(n) ? reference(doc, href_of(n), NULL) : NULL) : n->first;
        for (; c && doc->status == SR_OK; c = use ? NULL : c->next) {
            mat2d t = IDENTITY, o;
            const char *tr = attr(c->atts, "transform");
            if (tr && !parse_transform(tr, &t)) {
                continue;
            }
            if (strcmp(c->name, "use") == 0 && !use && use_offset(doc, c, f, &o)) {
                t = mat_mul(t, o);
            }
            if (is_shape(c->name) || !is_named(c, not_drawn)) {
                /* the child's own style, which a text's font depends on */
                frame cf = *f;
                unsigned long line = doc->line;
                svg_text_reset_uninherited(&cf.st.text);
                doc->line = c->line;
                doc->inherit_from = &f->st;
                apply_cascade(doc, c, &cf.st);
                doc->inherit_from = NULL;
                doc->line = line;
                svg_text_settle(&cf.st.text, &f->st.text);
                bbox_add(doc, c, &cf, mat_mul(m, t), b);
            }
        }
    }
    n->active = false;
    doc->draw_depth--;
}

/* a[i] *= b[i] / 255 over the image (b NULL: nothing to do). */
static void multiply_coverage(uint8_t *a, const uint8_t *b, const svg_doc *doc)
{
    size_t n = (size_t)sr_framebuffer_width(doc->fb) * (size_t)sr_framebuffer_height(doc->fb);
    for (size_t i = 0; b && i < n; i++) {
        a[i] = (uint8_t)((a[i] * b[i] + 127) / 255);
    }
}

/* A nested svg's viewport: x, y, width, height (100% when not given) in
 * the parent's user space. False when it is empty (nothing drawn). */
static bool viewport_rect(svg_doc *doc, const svg_node *node, const frame *f, double r[4])
{
    r[2] = f->vp_w;
    r[3] = f->vp_h;
    const char *ws = attr(node->atts, "width"), *hs = attr(node->atts, "height");
    return length_attr(doc, f, "x", attr(node->atts, "x"), &r[0]) &&
           length_attr(doc, f, "y", attr(node->atts, "y"), &r[1]) &&
           (!ws || length_attr(doc, f, "width", ws, &r[2])) &&
           (!hs || length_attr(doc, f, "height", hs, &r[3])) && r[2] > 0 && r[3] > 0;
}

/* The frame inside a nested svg: its viewBox onto its viewport. */
static frame viewport_frame(svg_doc *doc, const svg_node *node, const frame *f)
{
    frame in = *f;
    double r[4], vb[4];
    if (!viewport_rect(doc, node, f, r)) {
        return in;
    }
    const char *vbs = attr(node->atts, "viewBox");
    if (vbs && parse_viewbox(vbs, vb)) {
        in.m = mat_mul(f->m, viewbox_matrix(doc, node->atts, vb, r[0], r[1], r[2], r[3]));
        in.vp_w = vb[2];
        in.vp_h = vb[3];
    } else {
        in.m = mat_mul(f->m, (mat2d){ 1, 0, 0, 1, r[0], r[1] });
        in.vp_w = r[2];
        in.vp_h = r[3];
    }
    return in;
}

/* The coverage of the rectangle x, y, width, height = r in f's user
 * space; NULL after a failure. */
static uint8_t *rect_coverage(svg_doc *doc, const double r[4], const frame *f)
{
    int w = sr_framebuffer_width(doc->fb), h = sr_framebuffer_height(doc->fb);
    sr_point2 corners[4] = { { r[0], r[1] }, { r[0] + r[2], r[1] },
                             { r[0] + r[2], r[1] + r[3] }, { r[0], r[1] + r[3] } };
    sr_point2 *pts;
    sr_polygon2 poly = { corners, 4, NULL, 0 };
    uint8_t *cov = malloc((size_t)w * (size_t)h);
    if (!cov) {
        svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
        return NULL;
    }
    if (!map_polygon(doc, poly, f->m, &pts)) {
        free(cov);
        return NULL;
    }
    poly.points = pts;
    sr_result res = sr_polygon_coverage(doc->ctx, &poly,
                                        &(sr_fill_desc){ .antialias = f->st.crisp ? SR_AA_NONE
                                                                                  : SR_AA_AREA },
                                        0, 0, w, h, cov, (size_t)w);
    free(pts);
    if (res != SR_OK) {
        lib_fail(doc, res);
        free(cov);
        return NULL;
    }
    return cov;
}

/* The coverage of a clipPath for an element drawn under frame f: its
 * shapes (and uses of shapes) with their clip-rule, each cut by its own
 * clip-path, in the element's user space, then cut by the clipPath's
 * own clip-path; NULL after a failure (a cycle, nesting deeper than
 * MAX_DEPTH, a budget passed). */
static uint8_t *clip_mask(svg_doc *doc, svg_node *clip, svg_node *node, const frame *f)
{
    if (clip->active) {
        svg_fail(doc, SR_BAD_FORMAT, "clip-path: reference cycle through \"#%s\"",
                 SVG_QUOTED(clip->id));
        return NULL;
    }
    if (doc->draw_depth + 1 >= MAX_DEPTH) {
        svg_fail(doc, SR_BAD_FORMAT, "clip paths nested deeper than %d", MAX_DEPTH);
        return NULL;
    }
    frame cf = *f;
    const char *units = attr(clip->atts, "clipPathUnits");
    if (units && strcmp(units, "objectBoundingBox") == 0) {
        /* the clip's unit square onto the element's bounding box */
        double b[4] = { INFINITY, INFINITY, -INFINITY, -INFINITY };
        bool was = node->active;
        node->active = false;
        bbox_add(doc, node, f, IDENTITY, b);
        node->active = was;
        cf.m = mat_mul(f->m, (mat2d){ b[2] - b[0], 0, 0, b[3] - b[1], b[0], b[1] });
        if (!(b[2] > b[0] && b[3] > b[1])) {
            cf.m = (mat2d){ 0, 0, 0, 0, 0, 0 }; /* no box: nothing is inside */
        }
    }
    int w = sr_framebuffer_width(doc->fb), h = sr_framebuffer_height(doc->fb);
    if (!work_within_budget(doc, (double)w * h)) {
        return NULL;
    }
    uint8_t *mask = calloc((size_t)w * (size_t)h, 2);
    if (!mask) {
        svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
        return NULL;
    }
    uint8_t *cov = mask + (size_t)w * (size_t)h; /* a child's coverage */
    cf.st.own_opacity = 1;
    cf.st.clip = NULL;
    apply_cascade(doc, clip, &cf.st);
    const char *tr = attr(clip->atts, "transform");
    mat2d t;
    if (tr && parse_transform(tr, &t)) {
        cf.m = mat_mul(cf.m, t);
    }
    clip->active = true;
    doc->draw_depth++;
    for (svg_node *c = clip->first; c && doc->status == SR_OK; c = c->next) {
        /* Each child is cut by its own clip-path, and a use also by its
         * shape's, each in the user space of its element, before the
         * union: a + b - ab. */
        svg_node *shape = c, *cut_node[2] = { c, NULL };
        frame sf = cf, cut_frame[2];
        sf.st.clip = NULL;
        doc->line = c->line;
        apply_cascade(doc, c, &sf.st);
        tr = attr(c->atts, "transform");
        if (tr && parse_transform(tr, &t)) {
            sf.m = mat_mul(sf.m, t);
        }
        cut_frame[0] = sf;
        if (strcmp(c->name, "use") == 0) {
            const char *href = href_of(c);
            shape = href ? reference(doc, href, NULL) : NULL;
            if (!shape || !use_offset(doc, c, &sf, &t)) {
                continue;
            }
            sf.m = mat_mul(sf.m, t);
            cut_frame[0] = sf;
            sf.st.clip = NULL;
            apply_cascade(doc, shape, &sf.st);
            tr = attr(shape->atts, "transform");
            if (tr && parse_transform(tr, &t)) {
                sf.m = mat_mul(sf.m, t);
            }
            cut_node[1] = shape;
            cut_frame[1] = sf;
        }
        bool text = strcmp(shape->name, "text") == 0 && svg_text_available();
        if (text ? !clip_text(doc, shape, &sf, cov)
                 : !is_shape(shape->name) || !clip_shape(doc, shape, &sf, cov)) {
            continue;
        }
        for (int k = 0; k < 2 && doc->status == SR_OK; k++) {
            if (cut_node[k] && cut_frame[k].st.clip) {
                uint8_t *cut = clip_mask(doc, (svg_node *)cut_frame[k].st.clip, cut_node[k],
                                         &cut_frame[k]);
                multiply_coverage(cov, cut, doc);
                free(cut);
            }
        }
        for (size_t i = 0; i < (size_t)w * (size_t)h; i++) {
            unsigned a = mask[i], b = cov[i];
            mask[i] = (uint8_t)(a + b - (a * b + 127) / 255);
        }
    }
    /* A clip path clipped in turn: the two coverages multiply. */
    if (cf.st.clip && doc->status == SR_OK) {
        uint8_t *outer = clip_mask(doc, (svg_node *)cf.st.clip, node, f);
        multiply_coverage(mask, outer, doc);
        free(outer);
    }
    clip->active = false;
    doc->draw_depth--;
    if (doc->status != SR_OK) {
        free(mask);
        return NULL;
    }
    return mask;
}

/* Composite a layer over the image through a mask (or none) at an
 * opacity: straight-alpha source-over, as the fills blend. */
/* Composite a layer whose (0, 0) lies at the image's pixel at[0], at[1]
 * (it covers the whole image). */
static void composite_layer_at(svg_doc *doc, sr_framebuffer *layer, const int at[2],
                               const uint8_t *mask, double opacity, svg_blend_kind mode)
{
    int w = sr_framebuffer_width(doc->fb), h = sr_framebuffer_height(doc->fb);
    int lw = sr_framebuffer_width(layer);
    if (!work_within_budget(doc, (double)w * h)) {
        return;
    }
    size_t n = (size_t)w * (size_t)h;
    uint8_t *px = malloc(n * 4);
    if (!px) {
        svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
        return;
    }
    sr_result r = sr_read_pixels(doc->ctx, doc->fb, 0, 0, w, h, px, (size_t)w * 4);
    const uint8_t *src = sr_framebuffer_pixels(layer);
    for (int y = 0; r == SR_OK && y < h; y++) {
        /* the layer covers the image: at[0] and at[1] are 0 or below */
        const uint8_t *row = src + ((size_t)(y - at[1]) * (size_t)lw + (size_t)-at[0]) * 4;
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            const uint8_t *l = row + (size_t)x * 4;
            if (l[3] == 0 || (mask && mask[i] == 0)) {
                continue;
            }
            sr_rgba c = { l[0] / 255.0f, l[1] / 255.0f, l[2] / 255.0f,
                          (float)(l[3] / 255.0 * opacity) };
            if (mode != SVG_BLEND_NORMAL) {
                c = svg_blend_color(mode, px + i * 4, c);
            }
            svg_blend(px + i * 4, c, mask ? mask[i] / 255.0f : 1.0f);
        }
    }
    if (r == SR_OK) {
        r = sr_write_pixels(doc->ctx, doc->fb, 0, 0, w, h, px, (size_t)w * 4);
    }
    free(px);
    if (r != SR_OK) {
        lib_fail(doc, r);
    }
}

static void composite_layer(svg_doc *doc, sr_framebuffer *layer, const uint8_t *mask,
                            double opacity, svg_blend_kind mode)
{
    composite_layer_at(doc, layer, (const int[2]){ 0, 0 }, mask, opacity, mode);
}

/* What a w x h layer holds while open: its RGBA and the coverages of the
 * clip path or mask it is composited through (docs/robustness.md has the
 * peak sizes measured). */
static uint64_t layer_cost(int w, int h)
{
    return (uint64_t)w * (uint64_t)h * 6;
}

/* A new transparent layer the size of the image, drawn into from now
 * until close_layer; NULL after reporting a failure. */
/* A transparent w x h image drawn into instead of the current one. */
static sr_framebuffer *open_layer_sized(svg_doc *doc, int w, int h)
{
    /* and while the innermost closes, composite_layer's copy of the image */
    uint64_t need = doc->layer_bytes + layer_cost(w, h), limit = doc->opt->max_layer_bytes;
    uint64_t peak = need + (uint64_t)w * (uint64_t)h * 4;
    if (limit && peak > limit) {
        char a[32], b[32];
        doc->over_layer_limit = true;
        sr__format_bytes(peak, a, sizeof a);
        sr__format_bytes(limit, b, sizeof b);
        svg_fail(doc, SR_TOO_LARGE,
                 "layers nested %d deep (group opacity, masks, clip paths, patterns) need "
                 "about %s besides the image, more than the %s left for them: draw it smaller",
                 doc->layers + 1, a, b);
        return NULL;
    }
    sr_framebuffer *top = NULL;
    sr_result r = sr_make_framebuffer(doc->ctx,
                                      &(sr_framebuffer_desc){ .width = w, .height = h,
                                                              .depth_format = SR_DEPTH_NONE },
                                      &top);
    if (r != SR_OK) {
        lib_fail(doc, r);
        return NULL;
    }
    sr_clear(doc->ctx, top, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
    doc->fb = top;
    doc->layers++;
    doc->layer_bytes = need;
    return top;
}

static sr_framebuffer *open_layer(svg_doc *doc)
{
    return open_layer_sized(doc, sr_framebuffer_width(doc->fb), sr_framebuffer_height(doc->fb));
}

static void close_layer(svg_doc *doc, sr_framebuffer *under)
{
    doc->layers--;
    doc->layer_bytes -= layer_cost(sr_framebuffer_width(doc->fb), sr_framebuffer_height(doc->fb));
    doc->fb = under;
}

/* ---- patterns ------------------------------------------------------------------------ */

/* Pixels of a pattern tile, at most (beyond: drawn at a lower resolution). */
#define MAX_TILE_PIXELS (4L << 20)

/* Fill poly (user space of f) with the pattern: its tile drawn once into an
 * image at about the device resolution, then repeated.  False when the
 * pattern paints nothing (an empty tile, a singular transform) and the
 * fallback color should be used; failures are reported. */
/* Draw a pattern's content (under tf, whose style is set here) into a
 * new tw x th tile, kept as doc->tile; NULL when it paints nothing (over
 * budget, too deeply nested, a failure). */
static sr_framebuffer *draw_tile(svg_doc *doc, svg_node *pat, const svg_node *content,
                                 frame *tf, int tw, int th)
{
    if (!work_within_budget(doc, (double)tw * th)) {
        return NULL;
    }
    if (doc->layers == MAX_LAYERS) {
        warn_once(doc, "nesting of layers", "beyond 8 (opacity folded, clip and mask ignored)");
        return NULL;
    }
    sr_framebuffer *under = doc->fb, *tile = open_layer_sized(doc, tw, th);
    if (!tile) {
        return NULL;
    }
    tf->st = ancestor_style(doc, pat);
    int windows = doc->n_windows; /* the tile has pixels of its own */
    doc->n_windows = 0;
    if (content) {
        pat->active = true;
        ((svg_node *)content)->active = true;
        draw_children(doc, (svg_node *)content, tf);
        ((svg_node *)content)->active = false;
        pat->active = false;
    }
    doc->n_windows = windows;
    close_layer(doc, under);
    if (doc->status != SR_OK) {
        sr_destroy_framebuffer(doc->ctx, tile);
        return NULL;
    }
    /* The content may have drawn tiles of its own: this one replaces them. */
    sr_destroy_framebuffer(doc->ctx, doc->tile);
    doc->tile = tile;
    doc->tile_pattern = pat;
    doc->tile_m = tf->m;
    doc->tile_vp[0] = tf->vp_w;
    doc->tile_vp[1] = tf->vp_h;
    return tile;
}

static bool paint_pattern(svg_doc *doc, svg_node *pat, const frame *f, sr_polygon2 poly,
                          sr_polygon2 geometry, double opacity, sr_fill_rule rule)
{
    doc->line = pat->line;
    const svg_node *g = pat, *content = NULL;
    for (int i = 0; g; i++) {
        if (i == MAX_HREF_CHAIN) {
            svg_fail(doc, SR_BAD_FORMAT, "pattern: href chain through \"#%s\" is a cycle or "
                     "longer than %d", SVG_QUOTED(pat->id), MAX_HREF_CHAIN);
            return true;
        }
        content = !content && g->first ? g : content;
        const char *h = href_of(g);
        g = h ? reference(doc, h, NULL) : NULL;
        g = g && strcmp(g->name, "pattern") == 0 ? g : NULL;
    }
    if (pat->active || (content && content->active)) {
        svg_fail(doc, SR_BAD_FORMAT, "pattern: reference cycle through \"#%s\"",
                 SVG_QUOTED(pat->id));
        return true;
    }
    double b[4];
    bool have_box = bounding_box(geometry, b);
    const char *units = grad_attr(doc, pat, "patternUnits");
    bool bbox_units = !units || strcmp(units, "userSpaceOnUse") != 0;
    if (bbox_units && !have_box) {
        return false;
    }
    double rw = bbox_units ? 1 : f->vp_w, rh = bbox_units ? 1 : f->vp_h;
    double x = grad_coord(doc, pat, "x", rw, 0), y = grad_coord(doc, pat, "y", rh, 0);
    double w = grad_coord(doc, pat, "width", rw, 0), h = grad_coord(doc, pat, "height", rh, 0);
    if (bbox_units) {
        x = b[0] + x * (b[2] - b[0]);
        y = b[1] + y * (b[3] - b[1]);
        w *= b[2] - b[0];
        h *= b[3] - b[1];
    }
    if (!(w > 0 && h > 0) || !isfinite(w * h)) {
        return false; /* an empty tile: the fallback color, if any, paints */
    }
    /* the content's units onto the tile, its top left at the origin */
    mat2d cm = IDENTITY;
    double vb[4];
    const char *vbs = grad_attr(doc, pat, "viewBox");
    const char *cu = grad_attr(doc, pat, "patternContentUnits");
    if (vbs && parse_viewbox(vbs, vb)) {
        const svg_node *with_vb = pat;
        while (!attr(with_vb->atts, "viewBox")) { /* preserveAspectRatio of the same element */
            with_vb = reference(doc, href_of(with_vb), NULL);
        }
        cm = viewbox_matrix(doc, with_vb->atts, vb, 0, 0, w, h);
    } else if (cu && strcmp(cu, "objectBoundingBox") == 0 && have_box) {
        cm = (mat2d){ b[2] - b[0], 0, 0, b[3] - b[1], 0, 0 };
    }
    mat2d pm = mat_mul(f->m, server_transform(doc, pat, "patternTransform", f));
    /* The tile at the device's scale along each of its axes. */
    double sx = hypot(pm.a, pm.b), sy = hypot(pm.c, pm.d), tw = w * sx, th = h * sy;
    if (!(tw > 0 && th > 0) || !isfinite(tw * th)) {
        return false;
    }
    double k = tw * th > MAX_TILE_PIXELS ? sqrt(MAX_TILE_PIXELS / (tw * th)) : 1;
    tw = fmin(fmax(ceil(tw * k - 1e-9), 1), SR_MAX_FRAMEBUFFER_SIZE);
    th = fmin(fmax(ceil(th * k - 1e-9), 1), SR_MAX_FRAMEBUFFER_SIZE);
    mat2d to_tile = { tw / w, 0, 0, th / h, 0, 0 }, inv;
    if (!mat_invert(pm, &inv)) {
        return doc->status != SR_OK;
    }
    frame tf = { .m = mat_mul(to_tile, cm), .vp_w = f->vp_w, .vp_h = f->vp_h };
    sr_framebuffer *tile = doc->tile;
    bool same = tile && doc->tile_pattern == pat && sr_framebuffer_width(tile) == (int)tw &&
                sr_framebuffer_height(tile) == (int)th && doc->tile_vp[0] == f->vp_w &&
                doc->tile_vp[1] == f->vp_h && memcmp(&doc->tile_m, &tf.m, sizeof tf.m) == 0;
    if (!same) {
        tile = draw_tile(doc, pat, content, &tf, (int)tw, (int)th);
        if (!tile) {
            return doc->status != SR_OK;
        }
    }
    /* tile texels -> pattern space -> pixels */
    mat2d t = mat_mul(mat_mul(pm, (mat2d){ 1, 0, 0, 1, x, y }), (mat2d){ w / tw, 0, 0, h / th, 0, 0 });
    sr_affine2 to_px = { t.a, t.b, t.c, t.d, t.e, t.f };
    sr_paint im = { .kind = SR_PAINT_PATTERN, .image = sr_framebuffer_pixels(tile),
                    .image_width = (int)tw, .image_height = (int)th, .transform = &to_px };
    if (doc->status == SR_OK && mat_invert(t, &inv)) {
        fill_mapped(doc, poly, f->m, (sr_rgba){ 0, 0, 0, (float)opacity }, &im, rule,
                    f->st.crisp);
    }
    return true;
}

static void draw_children(svg_doc *doc, svg_node *node, const frame *f);

/* A <mask> for element `node` drawn under frame f: its content drawn in
 * a layer (in the element's user space, or its bounding box's for
 * maskContentUnits="objectBoundingBox"), then per pixel its luminance
 * times its alpha (mask-type="alpha": the alpha alone), inside the mask
 * region only, multiplied into `into` (NULL: all 255).  Returns the
 * coverage, or NULL (into freed) after a failure. */
static uint8_t *mask_coverage(svg_doc *doc, svg_node *m, svg_node *node, const frame *f,
                              uint8_t *into)
{
    int w = sr_framebuffer_width(doc->fb), h = sr_framebuffer_height(doc->fb);
    size_t n = (size_t)w * (size_t)h;
    if (m->active) {
        svg_fail(doc, SR_BAD_FORMAT, "mask: reference cycle through \"#%s\"",
                 SVG_QUOTED(m->id));
    }
    /* The element's bounding box, for the units that need it. */
    const char *units = attr(m->atts, "maskUnits"), *cunits = attr(m->atts, "maskContentUnits");
    bool region_bbox = !units || strcmp(units, "userSpaceOnUse") != 0;
    bool content_bbox = cunits && strcmp(cunits, "objectBoundingBox") == 0;
    double b[4] = { INFINITY, INFINITY, -INFINITY, -INFINITY };
    if (region_bbox || content_bbox) {
        bool was = node->active;
        node->active = false;
        bbox_add(doc, node, f, IDENTITY, b);
        node->active = was;
    }
    bool have_box = b[2] > b[0] && b[3] > b[1];
    double r[4] = { -0.1, -0.1, 1.2, 1.2 };
    static const char *const names[4] = { "x", "y", "width", "height" };
    for (int i = 0; i < 4; i++) {
        const char *v = attr(m->atts, names[i]);
        double x;
        bool pct;
        if (v && parse_length(v, &x, &pct)) {
            r[i] = pct ? x / 100 : x;
        } else if (v) {
            warn_once(doc, names[i], v);
        }
        if (!region_bbox && (!v || pct)) {
            r[i] = r[i] * (i % 2 ? f->vp_h : f->vp_w); /* percentages of the viewport */
        }
    }
    if (region_bbox) {
        r[0] = b[0] + r[0] * (b[2] - b[0]);
        r[1] = b[1] + r[1] * (b[3] - b[1]);
        r[2] *= b[2] - b[0];
        r[3] *= b[3] - b[1];
    }
    bool empty = !(r[2] > 0 && r[3] > 0) || ((region_bbox || content_bbox) && !have_box);
    uint8_t *cov = into ? into : malloc(n);
    if (!cov || doc->status != SR_OK || !work_within_budget(doc, (double)n)) {
        if (!cov) {
            svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
        }
        free(cov);
        return NULL;
    }
    if (!into) {
        memset(cov, 255, n);
    }
    if (empty) { /* nothing of the element shows */
        memset(cov, 0, n);
        return cov;
    }
    frame mf = { .m = f->m, .st = ancestor_style(doc, m), .vp_w = f->vp_w, .vp_h = f->vp_h };
    uint8_t *region = rect_coverage(doc, r, &mf);
    if (content_bbox) {
        mf.m = mat_mul(f->m, (mat2d){ b[2] - b[0], 0, 0, b[3] - b[1], b[0], b[1] });
    }
    const char *type = attr(m->atts, "mask-type");
    bool alpha = (type && strcmp(type, "alpha") == 0) || mf.st.mask_alpha;
    sr_framebuffer *under = doc->fb, *layer = region ? open_layer(doc) : NULL;
    if (layer) {
        m->active = true;
        draw_children(doc, m, &mf);
        m->active = false;
        close_layer(doc, under);
        const uint8_t *px = sr_framebuffer_pixels(layer);
        for (size_t i = 0; i < n; i++) {
            const uint8_t *p = px + i * 4;
            double v = p[3] / 255.0 * region[i] / 255.0;
            if (!alpha) { /* luminance of the sRGB values (CSS Masking) */
                v *= (0.2125 * p[0] + 0.7154 * p[1] + 0.0721 * p[2]) / 255.0;
            }
            cov[i] = (uint8_t)(cov[i] * v + 0.5);
        }
        sr_destroy_framebuffer(doc->ctx, layer);
    }
    free(region);
    if (doc->status != SR_OK) {
        free(cov);
        return NULL;
    }
    return cov;
}

/* A symbol drawn by a use: its viewBox onto the use's width and height
 * (100% of the viewport when not given), its children as a group. */
static void draw_symbol(svg_doc *doc, svg_node *use, svg_node *symbol, frame *f)
{
    doc->line = symbol->line;
    frame sf = *f;
    apply_cascade(doc, symbol, &sf.st);
    double vb[4], w = f->vp_w, h = f->vp_h;
    const char *ws = attr(use->atts, "width"), *hs = attr(use->atts, "height");
    if ((ws && !length_attr(doc, f, "width", ws, &w)) ||
        (hs && !length_attr(doc, f, "height", hs, &h)) || doc->status != SR_OK ||
        sf.st.display_none) {
        return;
    }
    const char *vbs = attr(symbol->atts, "viewBox");
    if (vbs && parse_viewbox(vbs, vb) && w > 0 && h > 0) {
        sf.m = mat_mul(sf.m, viewbox_matrix(doc, symbol->atts, vb, 0, 0, w, h));
        sf.vp_w = vb[2];
        sf.vp_h = vb[3];
    }
    symbol->active = true;
    draw_children(doc, symbol, &sf);
    symbol->active = false;
}

/* <use href="#id">: the element drawn as a child of the use (its frame
 * moved by x and y already, draw_node); a reference back into the chain
 * being drawn is refused. */
static void draw_use(svg_doc *doc, svg_node *node, frame *f)
{
    const char *href = attr(node->atts, "href");
    if (!href) {
        href = attr(node->atts, "xlink:href");
    }
    if (!href) {
        return;
    }
    svg_node *target = reference(doc, href, NULL);
    if (!target) {
        warn_once(doc, "use of a missing element", href);
        return;
    }
    if (target->active || target == node) {
        svg_fail(doc, SR_BAD_FORMAT, "use: reference cycle through \"%s\"", SVG_QUOTED(href));
        return;
    }
    node->active = true;
    if (strcmp(target->name, "symbol") == 0) {
        draw_symbol(doc, node, target, f);
    } else {
        draw_node(doc, target, f);
    }
    node->active = false;
}

/* ---- filters (svg_filter.c runs them) --------------------------------------------- */

static void filter_warn(void *host, const svg_node *at, const char *kind, const char *name)
{
    svg_doc *doc = host;
    unsigned long line = doc->line;
    doc->line = at->line;
    warn_once(doc, kind, name);
    doc->line = line;
}

static void filter_fail(void *host, const svg_node *at, sr_result r, const char *msg)
{
    svg_doc *doc = host;
    doc->line = at->line;
    svg_fail(doc, r, "%s", msg);
}

static svg_fe_style filter_style(void *host, const svg_node *fe)
{
    style st = ancestor_style(host, fe);
    sr_rgba c = st.flood_color;
    c.a = (float)(c.a * st.flood_opacity);
    return (svg_fe_style){ .flood = c, .lighting = st.lighting_color, .srgb = st.filters_srgb };
}

static bool filter_budget(void *host, const svg_node *at, double work)
{
    svg_doc *doc = host;
    doc->line = at->line;
    return work_within_budget(doc, work);
}

static void draw_node(svg_doc *doc, svg_node *node, const frame *parent);

/* feImage href="#id": the element drawn as a use of it would be, in the
 * filtered element's user space; a reference back into what is being
 * drawn (the filtered element, the filter) is a cycle, refused. */
static bool filter_draw(void *host, const svg_node *at, const char *href, const double rect[4],
                        uint8_t *out)
{
    svg_doc *doc = host;
    const frame *f = doc->filter_frame;
    /* a picture: drawn as an <image> of the same href on the rectangle */
    char box[4][32];
    for (int i = 0; i < 4; i++) {
        snprintf(box[i], sizeof box[i], "%.17g", rect[i]);
    }
    const char *par = attr(at->atts, "preserveAspectRatio");
    const char *atts[] = { "href", href, "x", box[0], "y", box[1], "width", box[2],
                           "height", box[3], "preserveAspectRatio", par ? par : "xMidYMid",
                           NULL };
    svg_node picture = { .name = "image", .atts = atts, .line = at->line };
    svg_node *el = href[0] == '#' ? reference(doc, href, NULL) : &picture;
    if (!el || !f) {
        filter_warn(doc, at, "feImage reference (transparent black)", href);
        return true;
    }
    doc->line = at->line;
    if (el->active) {
        svg_fail(doc, SR_BAD_FORMAT, "feImage: reference cycle through \"%s\"",
                 SVG_QUOTED(href));
        return false;
    }
    if (doc->layers == MAX_LAYERS) {
        filter_warn(doc, at, "nesting of layers", "beyond 8 (feImage skipped)");
        return true;
    }
    frame ef = { .m = f->m, .st = el->parent ? ancestor_style(doc, el->parent) : doc->initial,
                 .vp_w = f->vp_w, .vp_h = f->vp_h };
    sr_framebuffer *under = doc->fb, *top = open_layer_sized(doc, doc->filter_size[0],
                                                             doc->filter_size[1]);
    if (!top) {
        return false;
    }
    if (el == &picture) {
        draw_image(doc, el, &ef);
    } else {
        draw_node(doc, el, &ef);
    }
    close_layer(doc, under);
    int w = sr_framebuffer_width(top), h = sr_framebuffer_height(top);
    memcpy(out, sr_framebuffer_pixels(top), (size_t)w * (size_t)h * 4);
    sr_destroy_framebuffer(doc->ctx, top);
    return doc->status == SR_OK;
}

/* The filter job of an element's filter (f: its frame, box: its bounding
 * box in that user space) on a w x h layer whose (0, 0) is the image's
 * pixel origin; px: the layer's pixels, or NULL to plan. */
static svg_filter_job filter_job(svg_doc *doc, const frame *f, const double box[4], int w, int h,
                                 const int origin[2], uint8_t *px)
{
    sr_rgba paints[2] = { { 0, 0, 0, 0 }, { 0, 0, 0, 0 } };
    const paint *pp[2] = { &f->st.fill, &f->st.stroke };
    for (int i = 0; i < 2; i++) {
        if (pp[i]->kind == SVG_PAINT_COLOR || pp[i]->kind == SVG_PAINT_CURRENT) {
            paints[i] = pp[i]->kind == SVG_PAINT_COLOR ? pp[i]->color : f->st.color;
            paints[i].a *= (float)(i ? f->st.stroke_opacity : f->st.fill_opacity);
        }
    }
    return (svg_filter_job){ .filter = f->st.filter, .pixels = px, .fill = paints[0],
                             .stroke = paints[1], .width = w, .height = h,
                             .origin = { origin[0], origin[1] },
                             .m = { f->m.a, f->m.b, f->m.c, f->m.d, f->m.e, f->m.f },
                             .bbox = { box[0], box[1], box[2], box[3] },
                             .vp_w = f->vp_w, .vp_h = f->vp_h, .ctx = doc->ctx, .host = doc,
                             .warn = filter_warn, .fail = filter_fail, .style = filter_style,
                             .budget = filter_budget, .draw = filter_draw };
}

/* What running the filter on a w x h layer holds besides the image and
 * the layers open below it: the layer itself (closed but not yet
 * composited), the result in RGBA8 and the filter's images. */
static uint64_t filter_cost(const svg_filter_job *job, int *images)
{
    uint64_t w = (uint64_t)job->width, h = (uint64_t)job->height;
    return layer_cost(job->width, job->height) + w * h * 4 + svg_filter_peak(job, images);
}

/* The element's filter on its layer (f: its frame, drawn into the layer
 * whose (0, 0) is the image's pixel origin; box: its bounding box in
 * that user space). */
static void apply_filter(svg_doc *doc, sr_framebuffer *layer, const frame *f, const double box[4],
                         const int origin[2])
{
    int w = sr_framebuffer_width(layer), h = sr_framebuffer_height(layer);
    if (!work_within_budget(doc, (double)w * h)) {
        return;
    }
    svg_node *filter = (svg_node *)f->st.filter;
    if (filter->active) {
        svg_fail(doc, SR_BAD_FORMAT, "filter: reference cycle through \"#%s\"",
                 SVG_QUOTED(filter->id));
        return;
    }
    svg_filter_job job = filter_job(doc, f, box, w, h, origin, NULL);
    /* its float images count against the layers' memory, as a layer
     * would, and feImage's layers count them in turn */
    int images;
    uint64_t cost = filter_cost(&job, &images), limit = doc->opt->max_layer_bytes;
    if (doc->status != SR_OK) {
        return;
    }
    if (limit && doc->layer_bytes + cost > limit) {
        char a[32], b[32];
        doc->over_layer_limit = true;
        sr__format_bytes(doc->layer_bytes + cost, a, sizeof a);
        sr__format_bytes(limit, b, sizeof b);
        svg_fail(doc, SR_TOO_LARGE,
                 "filter \"#%s\": its results and the layers open (%d float images of the "
                 "filter region at once) need about %s besides the image, more than the %s "
                 "left for them: draw it smaller",
                 filter->id ? filter->id : "", images, a, b);
        return;
    }
    size_t bytes = (size_t)w * (size_t)h * 4;
    uint8_t *px = malloc(bytes);
    if (!px) {
        svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
        return;
    }
    job.source = sr_framebuffer_pixels(layer);
    job.pixels = px;
    unsigned long line = doc->line;
    const frame *outer = doc->filter_frame;
    int outer_size[2] = { doc->filter_size[0], doc->filter_size[1] };
    doc->filter_frame = f;
    doc->filter_size[0] = w;
    doc->filter_size[1] = h;
    doc->layer_bytes += cost;
    filter->active = true;
    svg_apply_filter(&job);
    filter->active = false;
    doc->layer_bytes -= cost;
    doc->filter_frame = outer;
    doc->filter_size[0] = outer_size[0];
    doc->filter_size[1] = outer_size[1];
    doc->line = line;
    if (doc->status == SR_OK) {
        sr_result r = sr_write_pixels(doc->ctx, layer, 0, 0, w, h, px, (size_t)w * 4);
        if (r != SR_OK) {
            lib_fail(doc, r);
        }
    }
    free(px);
}

/* The pixels (x0 y0 x1 y1 of the current image) the layer of an element
 * with a filter covers: the image, and beyond it what the filter can
 * move into it (an feOffset of content drawn outside), as the filter
 * region allows and the memory left for layers, the work budget and the
 * largest framebuffer hold (else the image alone, warned once). */
static void filter_layer_rect(svg_doc *doc, const frame *f, const double box[4], int out[4])
{
    int w = sr_framebuffer_width(doc->fb), h = sr_framebuffer_height(doc->fb);
    const int zero[2] = { 0, 0 };
    int ext[4];
    double passes;
    out[0] = out[1] = 0;
    out[2] = w;
    out[3] = h;
    svg_filter_job job = filter_job(doc, f, box, w, h, zero, NULL);
    if (!svg_filter_extent(&job, ext, &passes) || doc->status != SR_OK ||
        (ext[0] >= 0 && ext[1] >= 0 && ext[2] <= w && ext[3] <= h)) {
        return;
    }
    int r[4] = { ext[0] < 0 ? ext[0] : 0, ext[1] < 0 ? ext[1] : 0, ext[2] > w ? ext[2] : w,
                 ext[3] > h ? ext[3] : h };
    frame moved = *f;
    moved.m.e -= r[0];
    moved.m.f -= r[1];
    int images;
    job = filter_job(doc, &moved, box, r[2] - r[0], r[3] - r[1], r, NULL);
    uint64_t cost = filter_cost(&job, &images), limit = doc->opt->max_layer_bytes;
    /* the larger layer is filtered and composited; its region's pixels
     * are counted for every pass */
    double more = ((double)(r[2] - r[0]) * (r[3] - r[1]) - (double)w * h) * (1 + passes);
    double base = doc->work_used + (double)w * h * (2 + passes);
    const char *why = NULL;
    if (limit && doc->layer_bytes + cost > limit) {
        why = "the memory left for layers";
    } else if (base + more > doc->work_budget) {
        if (base > doc->work_budget) {
            return; /* refused for its work either way */
        }
        why = "the work budget";
    } else if (r[2] - r[0] > SR_MAX_FRAMEBUFFER_SIZE || r[3] - r[1] > SR_MAX_FRAMEBUFFER_SIZE) {
        why = "the largest layer";
    }
    if (why) {
        char key[96];
        snprintf(key, sizeof key, "filter region beyond the image: %s", why);
        warn_keyed(doc, key,
                   "filter region beyond the image: its source drawn up to the image's edges, "
                   "as %s holds no more", why);
        return;
    }
    memcpy(out, r, sizeof r);
}

static void draw_node(svg_doc *doc, svg_node *node, const frame *parent)
{
    doc->line = node->line;
    if (doc->draw_depth + 1 >= MAX_DEPTH) {
        svg_fail(doc, SR_BAD_FORMAT, "elements and uses nested deeper than %d", MAX_DEPTH);
        return;
    }
    bool group = strcmp(node->name, "g") == 0 || strcmp(node->name, "a") == 0 ||
                 strcmp(node->name, "switch") == 0;
    bool image = strcmp(node->name, "image") == 0;
    bool text = strcmp(node->name, "text") == 0 && svg_text_available();
    bool shape = is_shape(node->name) || image, use = strcmp(node->name, "use") == 0;
    bool nested = strcmp(node->name, "svg") == 0 && node != doc->root;
    if (nested) {
        group = true;
    } else if (!group && !shape && !use && !text && node != doc->root) {
        if (!is_named(node, not_drawn) && !node->foreign) {
            warn_once(doc, "element", node->name);
        }
        return;
    }
    if (!conditions_hold(node)) {
        return;
    }
    /* Uses and nested elements are visited again and again: each visit is
     * a point of the budget, so a tree of uses cannot grow without bound. */
    if (!points_within_budget(doc, 1)) {
        return;
    }
    doc->points_used++;
    frame f = *parent;
    f.st.own_opacity = 1;
    f.st.clip = f.st.mask = NULL;
    f.st.non_scaling = false;
    f.st.origin[0] = f.st.origin[1] = 0;
    f.st.origin_pct = 0;
    f.st.blend = SVG_BLEND_NORMAL;
    f.st.isolate = false;
    f.st.overflow_visible = false;
    f.st.filter = NULL;
    f.st.filter_missing = false;
    f.st.flood_color = doc->initial.flood_color;
    f.st.flood_opacity = doc->initial.flood_opacity;
    f.st.lighting_color = doc->initial.lighting_color;
    svg_text_reset_uninherited(&f.st.text);
    doc->inherit_from = &parent->st;
    apply_cascade(doc, node, &f.st);
    doc->inherit_from = NULL;
    svg_text_settle(&f.st.text, &parent->st.text);
    if (doc->status != SR_OK || f.st.display_none || f.st.filter_missing) {
        return;
    }
    const char *tr = attr(node->atts, "transform");
    if (tr) {
        mat2d t;
        if (!parse_transform(tr, &t)) {
            svg_fail(doc, SR_BAD_FORMAT, "transform=\"%s\" is malformed", SVG_QUOTED(tr));
            return;
        }
        f.m = mat_mul(f.m, about_origin(t, &f.st, &f));
    }
    mat2d moved;
    if (use) {
        if (!use_offset(doc, node, &f, &moved)) {
            return;
        }
        f.m = mat_mul(f.m, moved);
    }
    /* A nested svg: a new viewport, which clips what it holds unless
     * its overflow is visible; one of no area shows nothing. */
    uint8_t *viewport = NULL;
    if (nested) {
        double r[4];
        if (!viewport_rect(doc, node, &f, r) ||
            (!f.st.overflow_visible && !(viewport = rect_coverage(doc, r, &f)))) {
            return;
        }
    }
    /* A group's opacity and any clip path apply to the element drawn
     * whole in a layer of its own; a lone shape's opacity folds into its
     * fill and stroke. */
    bool layer = viewport || f.st.clip || f.st.mask || (f.st.own_opacity < 1 && !shape) ||
                 f.st.blend != SVG_BLEND_NORMAL || f.st.isolate || f.st.filter;
    if (layer && doc->layers == MAX_LAYERS) {
        warn_once(doc, "nesting of layers",
                  "beyond 8 (opacity folded, clip, mask and filter ignored)");
        layer = false;
    }
    if (!layer) {
        free(viewport); /* no layer left: the viewport maps, but does not clip */
        if (nested) {
            f = viewport_frame(doc, node, &f);
        }
        f.st.opacity *= f.st.own_opacity;
        if (f.st.opacity <= 0) {
            return;
        }
        draw_content(doc, node, &f, shape, use);
        return;
    }
    /* the filter's bounding box and user space: the element's, outside a
     * nested svg's viewport */
    double fbox[4] = { INFINITY, INFINITY, -INFINITY, -INFINITY };
    frame ff = f;
    if (f.st.filter) {
        bbox_add(doc, node, &f, IDENTITY, fbox);
    }
    /* a filter can bring in what lies beyond the image: its layer is
     * drawn that much larger, moved by `lr`'s corner */
    int lr[4] = { 0, 0, sr_framebuffer_width(doc->fb), sr_framebuffer_height(doc->fb) };
    if (f.st.filter) {
        filter_layer_rect(doc, &f, fbox, lr);
        ff.m.e -= lr[0];
        ff.m.f -= lr[1];
    }
    uint8_t *mask = f.st.clip ? clip_mask(doc, (svg_node *)f.st.clip, node, &f) : NULL;
    if (f.st.mask && doc->status == SR_OK) {
        mask = mask_coverage(doc, (svg_node *)f.st.mask, node, &f, mask);
    }
    if (viewport) {
        multiply_coverage(viewport, mask, doc);
        free(mask);
        mask = viewport;
    }
    if (nested) {
        f = viewport_frame(doc, node, &f);
    }
    f.m.e -= lr[0];
    f.m.f -= lr[1];
    sr_framebuffer *under = doc->fb,
                   *top = doc->status == SR_OK ? open_layer_sized(doc, lr[2] - lr[0], lr[3] - lr[1])
                                               : NULL;
    if (top) {
        draw_content(doc, node, &f, shape, use);
        close_layer(doc, under);
        if (f.st.filter && doc->status == SR_OK) {
            apply_filter(doc, top, &ff, fbox, lr);
        }
        if (doc->status == SR_OK) {
            composite_layer_at(doc, top, lr, mask, f.st.own_opacity, f.st.blend);
        }
        sr_destroy_framebuffer(doc->ctx, top);
    }
    free(mask);
}

/* The element itself, its frame set: a shape, a use or the children. */
static void draw_content(svg_doc *doc, svg_node *node, frame *fp, bool shape, bool use)
{
    frame f = *fp;
    doc->draw_depth++;
    node->active = true;
    if (strcmp(node->name, "image") == 0) {
        draw_image(doc, node, &f);
    } else if (shape) {
        if (!f.st.invisible) {
            draw_shape(doc, node, &f);
        }
    } else if (use) {
        draw_use(doc, node, &f);
    } else if (strcmp(node->name, "text") == 0) {
        draw_text(doc, node, &f);
    } else if (strcmp(node->name, "switch") == 0) {
        /* the first drawable child whose conditions hold */
        for (svg_node *c = node->first; c; c = c->next) {
            if ((is_shape(c->name) || !is_named(c, not_drawn)) && !c->foreign &&
                conditions_hold(c)) {
                draw_node(doc, c, &f);
                break;
            }
        }
    } else {
        draw_children(doc, node, &f);
    }
    node->active = false;
    doc->draw_depth--;
}

/* ---- the entry point -------------------------------------------------------------- */

/* Read the tree, the ids and the style sheets of data; false after a
 * failure (reported in doc->msg). */
static bool read_document(svg_doc *doc, const char *data, size_t size)
{
    doc->parser = XML_ParserCreate(NULL);
    if (!doc->parser) {
        svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
        return false;
    }
    XML_SetUserData(doc->parser, doc);
    XML_SetElementHandler(doc->parser, on_start, on_end);
    XML_SetCharacterDataHandler(doc->parser, on_text);
    const unsigned char *u = (const unsigned char *)data;
    /* expat would say "not well-formed (invalid token)". */
    if (size == 0) {
        doc->line = 1;
        svg_fail(doc, SR_BAD_FORMAT, "file is empty");
        return false;
    }
    /* In UTF-16 (a NUL among the first bytes, or its byte-order mark) a
     * line end is not one byte: expat counts the lines then. */
    bool utf16 = size >= 2 && (!u[0] || !u[1] || (u[0] == 0xFE && u[1] == 0xFF) ||
                               (u[0] == 0xFF && u[1] == 0xFE));
    doc->text = data && !utf16 ? data : NULL;
    doc->text_has_cr = doc->text && memchr(data, '\r', size) != NULL;
    doc->text_size = size;
    doc->line_at = 0;
    doc->lines_before = 0;
    /* XML_Parse takes an int length: feed the buffer in pieces. */
    const size_t piece = (size_t)1 << 20;
    size_t at = 0;
    do {
        size_t n = size - at < piece ? size - at : piece;
        bool last = at + n == size;
        if (XML_Parse(doc->parser, data ? data + at : "", (int)n, last) == XML_STATUS_ERROR) {
            if (doc->status == SR_OK) {
                doc->line = XML_GetCurrentLineNumber(doc->parser);
                svg_fail(doc, SR_BAD_FORMAT, "%s", XML_ErrorString(XML_GetErrorCode(doc->parser)));
            }
            break;
        }
        at += n;
    } while (at < size && doc->status == SR_OK);
    if (doc->status == SR_OK && !doc->root) {
        doc->line = 1;
        svg_fail(doc, SR_BAD_FORMAT, "no <svg> element");
    }
    return doc->status == SR_OK && index_document(doc);
}

/* What read_document and the drawing allocated, the image aside. */
static void free_document(svg_doc *doc)
{
    for (int i = 0; i < doc->n_warned; i++) {
        free(doc->warned[i]);
    }
    if (doc->parser) {
        XML_ParserFree(doc->parser);
    }
    free_tree(doc->root);
    free(doc->ids);
    free(doc->verts);
    sr_destroy_path(doc->ctx, doc->spare_path);
    svg_css_free(&doc->sheet);
    sr_destroy_framebuffer(doc->ctx, doc->tile);
    free(doc->grad);
    svg_fonts_free(doc->fonts);
}

/* The initial style (SVG's defaults): fill black, no stroke, width 1. */
static style initial_style(void)
{
    return (style){ .fill = { .kind = SVG_PAINT_COLOR, .color = { 0, 0, 0, 1 } },
                    .stroke = { .kind = SVG_PAINT_NONE },
                    .color = { 0, 0, 0, 1 }, .stop_color = { 0, 0, 0, 1 }, .stop_opacity = 1,
                    .fill_opacity = 1, .stroke_opacity = 1, .opacity = 1,
                    .own_opacity = 1, .clip_rule = SR_NONZERO,
                    .fill_rule = SR_NONZERO, .stroke_width = 1,
                    .join = SR_STROKE_JOIN_MITER, .cap = SR_STROKE_CAP_BUTT,
                    .miter_limit = 4, .flood_color = { 0, 0, 0, 1 }, .flood_opacity = 1,
                    .lighting_color = { 1, 1, 1, 1 },
                    .paint_order = { PAINT_FILL, PAINT_STROKE, PAINT_MARKERS },
                    .text = svg_text_initial() };
}

static sr_result render(sr_context *ctx, const char *data, size_t size, const sr_svg_desc *opt,
                        sr_framebuffer **out, sr_svg_info *info, char *msg, size_t msg_size)
{
    const char *name = opt->name ? opt->name : "<svg>";
    if (size > SR_SVG_MAX_INPUT_BYTES) {
        snprintf(msg, msg_size, "%s: the document is %zu bytes, more than the %zu MiB limit", name,
                 size, SR_SVG_MAX_INPUT_BYTES >> 20);
        return SR_TOO_LARGE;
    }
    /* .svgz: the budgets below follow the document's own bytes. */
    char *plain, why[256];
    sr_result r = document_bytes(&data, &size, &plain, why, sizeof why);
    if (r != SR_OK) {
        snprintf(msg, msg_size, "%s: %s", name, why);
        return r;
    }
    svg_doc *doc = calloc(1, sizeof *doc);
    if (!doc) {
        free(plain);
        snprintf(msg, msg_size, "%s: out of memory", name);
        return SR_OUT_OF_MEMORY;
    }
    doc->file = name;
    doc->base = opt->name;
    doc->opt = opt;
    doc->ctx = ctx;
    doc->status = SR_OK;
    doc->msg = msg;
    doc->msg_size = msg_size;
    doc->points_budget = SR_SVG_POINTS_BASE + (double)SR_SVG_POINTS_PER_BYTE * (double)size;
    doc->cull_reach = -1;
    if (read_document(doc, data, size)) {
        frame f = { .m = IDENTITY, .st = initial_style() };
        doc->line = doc->root->line;
        doc->initial = f.st;
        if (root_element(doc, doc->root->atts, &f)) {
            doc->root_m = f.m;
            draw_node(doc, doc->root, &f);
        }
    }
    sr_result status = doc->status;
    if (status == SR_OK) {
        *out = doc->fb;
    } else {
        sr_destroy_framebuffer(ctx, doc->fb);
    }
    *info = (sr_svg_info){ .points_used = doc->points_used, .points_budget = doc->points_budget,
                           .work_used = doc->work_used, .work_budget = doc->work_budget,
                           .warnings = doc->warnings,
                           .over_layer_limit = doc->over_layer_limit };
    free_document(doc);
    free(doc);
    free(plain);
    return status;
}

bool sr_io_have_svg(void)
{
    return true;
}

#else /* !SR_HAVE_EXPAT */

static sr_result render(sr_context *ctx, const char *data, size_t size, const sr_svg_desc *opt,
                        sr_framebuffer **out, sr_svg_info *info, char *msg, size_t msg_size)
{
    (void)ctx, (void)data, (void)size, (void)out, (void)info;
    snprintf(msg, msg_size, "%s: cannot read SVG (softrast was built without expat; install "
             "libexpat1-dev and rebuild)",
             opt->name ? opt->name : "<svg>");
    return SR_UNSUPPORTED;
}

bool sr_io_have_svg(void)
{
    return false;
}

#endif /* SR_HAVE_EXPAT */

static sr_result render_svg(sr_context *ctx, const char *data, size_t size,
                            const sr_svg_desc *desc, sr_framebuffer **out, sr_svg_info *info,
                            sr_io_error *err)
{
    sr_io_error scratch;
    if (!err) {
        err = &scratch;
    }
    err->message[0] = 0;
    sr_svg_info ignored;
    if (!info) {
        info = &ignored;
    }
    *info = (sr_svg_info){ 0 };
    if (out) {
        *out = NULL;
    }
    sr_svg_desc none = { 0 };
    if (!desc) {
        desc = &none;
    }
    const char *name = desc->name ? desc->name : "<svg>";
    if (!ctx || !out || (!data && size > 0)) {
        return sr__io_fail(err, SR_INVALID_ARG, name, 0,
                           "sr_render_svg: ctx and out are required, and data when size > 0");
    }
    if (desc->width < 0 || desc->height < 0 || (desc->width > 0) != (desc->height > 0) ||
        !(desc->scale >= 0) || desc->max_side < 0) {
        return sr__io_fail(err, SR_INVALID_ARG, name, 0,
                           "sr_svg_desc: width and height are both 0 or both > 0, scale and "
                           "max_side >= 0");
    }
    sr_rgba bg = desc->background;
    if (!isfinite(bg.r) || !isfinite(bg.g) || !isfinite(bg.b) || !isfinite(bg.a)) {
        return sr__io_fail(err, SR_INVALID_ARG, name, 0, "sr_svg_desc.background is not finite");
    }
    sr_result r = render(ctx, data, size, desc, out, info, err->message, sizeof err->message);
    if (r != SR_OK && err->message[0]) {
        sr_set_last_error(err->message);
    }
    return r;
}

sr_result sr_render_svg(sr_context *ctx, const char *data, size_t size, const sr_svg_desc *desc,
                        sr_framebuffer **out, sr_svg_info *info, sr_io_error *err)
{
    sr_io_error saved;
    sr__last_error_save(&saved);
    return sr__last_error_keep(render_svg(ctx, data, size, desc, out, info, err), &saved);
}

sr_result sr_render_svg_file(sr_context *ctx, const char *path, const sr_svg_desc *desc,
                             sr_framebuffer **out, sr_svg_info *info, sr_io_error *err)
{
    if (out) {
        *out = NULL;
    }
    if (info) {
        *info = (sr_svg_info){ 0 };
    }
    if (!path) {
        return sr__io_fail(err, SR_INVALID_ARG, "<null>", 0, "no file name given");
    }
    char *data = NULL;
    size_t size = 0;
    sr_result r = sr__read_file_as(path, "an SVG file", &data, &size, err);
    if (r != SR_OK) {
        return r;
    }
    sr_svg_desc named = desc ? *desc : (sr_svg_desc){ 0 };
    if (!named.name) {
        named.name = path;
    }
    r = sr_render_svg(ctx, data, size, &named, out, info, err);
    sr__free_file(data, size);
    return r;
}

