/* svg.c - the SVG reader (src/io, softrast_io): renders a subset of SVG
 * 1.1, held in memory or in a file, with the 2D toolkit (sr_render_svg,
 * softrast_io.h); `softrast svg` (apps/softrast/svg_cmd.c) is the command
 * around it.
 *
 * The document is read with expat in one pass: the root <svg> fixes the
 * image size and the viewBox mapping, then every shape is drawn as its
 * start tag arrives, with the transform and style inherited down a stack.
 * Shapes become paths in user units (flattened finely enough for the
 * current scale), then the fill polygon or the stroke outline is mapped
 * to pixels and filled: antialiased by exact area coverage, or aliased by
 * the edge-table fill under shape-rendering="crispEdges".
 *
 * Supported: svg (width, height, viewBox, preserveAspectRatio), g, path
 * (every command), rect (rx, ry), circle, ellipse, line, polyline,
 * polygon; transform (matrix, translate, scale, rotate, skewX, skewY);
 * fill, stroke, fill-opacity, stroke-opacity, opacity, fill-rule,
 * stroke-width, stroke-linejoin, stroke-linecap, stroke-miterlimit,
 * shape-rendering, display="none", as attributes or in style="...".
 * Group opacity multiplies into the children's opacities (exact unless
 * children overlap).  Anything else is skipped with one warning per name.
 * Malformed XML, path data or numbers, and drawings beyond the limits of
 * softrast_io.h (bounded work): one line "NAME:LINE: what is wrong" in the
 * sr_io_error and no image.  Warnings go to the caller's callback.
 * One document per call; nothing global, so calls may run in parallel on
 * different contexts. */
#include "io/svg.h"
#include "io/io_util.h"
#include "io/number.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#ifdef SR_HAVE_EXPAT

#include <expat.h>

#define MAX_DEPTH 256
#define MAX_WARNED 64

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

typedef struct style {
    bool has_fill, has_stroke;
    sr_rgba fill, stroke;
    double fill_opacity, stroke_opacity, opacity;
    sr_fill_rule fill_rule;
    double stroke_width;
    sr_stroke_join join;
    sr_stroke_cap cap;
    double miter_limit;
    bool crisp;
    bool display_none;       /* display="none" here or on an ancestor */
    bool invisible;          /* visibility (inherited, children may undo it) */
} style;

typedef struct frame {
    mat2d m;
    style st;
} frame;

typedef struct svg_doc {
    const char *file;        /* name in messages */
    const sr_svg_desc *opt;
    XML_Parser parser;
    sr_context *ctx;
    sr_framebuffer *fb;
    frame stack[MAX_DEPTH];
    int depth;
    int skip;                /* > 0: inside a skipped subtree, its depth */
    bool seen_root;
    sr_result status;        /* SR_OK until something fails */
    char *msg;               /* the failure's line goes here */
    size_t msg_size;
    char *warned[MAX_WARNED];
    int n_warned;
    bool warnings_capped;    /* "further warnings not shown" was said */
    int warnings;            /* given so far */
    unsigned long line;      /* of the element being handled */
    /* Bounded work (softrast_io.h): what the document has used so far. */
    double points_used, points_budget;
    double work_used, work_budget;
} svg_doc;

/* ---- messages -------------------------------------------------------------- */

static void svg_fail(svg_doc *doc, sr_result status, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Record the first failure as "FILE:LINE: ..." and stop the parser. */
static void svg_fail(svg_doc *doc, sr_result status, const char *fmt, ...)
{
    if (doc->status != SR_OK) {
        return;
    }
    int n = snprintf(doc->msg, doc->msg_size, "%s:%lu: ", doc->file, doc->line);
    if (n >= 0 && (size_t)n < doc->msg_size) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(doc->msg + n, doc->msg_size - (size_t)n, fmt, ap);
        va_end(ap);
    }
    /* One line, whatever the document put into the quoted text. */
    for (char *c = doc->msg; c && *c; c++) {
        if (*c == '\n' || *c == '\r') {
            *c = ' ';
        }
    }
    doc->status = status;
    XML_StopParser(doc->parser, XML_FALSE);
}

/* A library call failed: out of memory is the run's failure, anything
 * else (a non-finite or out-of-range coordinate) the document's. */
static void lib_fail(svg_doc *doc, sr_result r)
{
    svg_fail(doc, r == SR_OUT_OF_MEMORY ? SR_OUT_OF_MEMORY : SR_BAD_FORMAT, "%s",
             sr_context_error(doc->ctx));
}

/* "FILE:LINE: warning: unsupported KIND 'NAME' skipped", once per name.
 * After MAX_WARNED different names, one last line says the rest are not
 * shown: a document of a million unknown elements gets 65 lines, not a
 * million. */
static void warn_once(svg_doc *doc, const char *kind, const char *name)
{
    if (doc->warnings_capped) {
        return;
    }
    char key[128];
    snprintf(key, sizeof key, "%s %s", kind, name);
    for (int i = 0; i < doc->n_warned; i++) {
        if (strcmp(doc->warned[i], key) == 0) {
            return;
        }
    }
    char line[8192]; /* a file name of PATH_MAX and a quoted value whole */
    if (doc->n_warned == MAX_WARNED) {
        snprintf(line, sizeof line,
                 "%s:%lu: warning: more unsupported names; further warnings not shown",
                 doc->file, doc->line);
        doc->warnings_capped = true;
    } else {
        doc->warned[doc->n_warned] = strdup(key);
        if (doc->warned[doc->n_warned]) {
            doc->n_warned++;
        }
        snprintf(line, sizeof line, "%s:%lu: warning: unsupported %s '%s' skipped", doc->file,
                 doc->line, kind, name);
    }
    doc->warnings++;
    if (doc->opt->warn) {
        doc->opt->warn(doc->opt->warn_user, line);
    }
}

/* ---- numbers, lengths, lists ----------------------------------------------------- */

static const char *skip_ws(const char *s)
{
    while (isspace((unsigned char)*s)) {
        s++;
    }
    return s;
}

static const char *skip_ws_comma(const char *s)
{
    s = skip_ws(s);
    if (*s == ',') {
        s = skip_ws(s + 1);
    }
    return s;
}

/* An SVG number (sign, digits, fraction, exponent), no leading blanks. */
static bool parse_number(const char **s, double *out)
{
    const char *e = *s + strnlen(*s, 64);
    size_t n = sr__scan_decimal(*s, e);
    if (n == 0 || n == 64 || sr__parse_double(*s, *s + n, out) != SR_NUM_OK) {
        return false;
    }
    *s += n;
    return true;
}

/* A length: number with an optional absolute unit; 96 px per inch.
 * *percent is set (and the number returned as is) for "%". */
static bool parse_length(const char *s, double *out, bool *percent)
{
    s = skip_ws(s);
    if (!parse_number(&s, out)) {
        return false;
    }
    static const struct { const char *unit; double px; } units[] = {
        { "px", 1 }, { "pt", 96.0 / 72 }, { "pc", 16 }, { "in", 96 }, { "cm", 96 / 2.54 },
        { "mm", 96 / 25.4 },
    };
    if (percent) {
        *percent = false;
    }
    s = skip_ws(s);
    if (*s == 0) {
        return true;
    }
    if (*s == '%' && percent) {
        *percent = true;
        return *skip_ws(s + 1) == 0;
    }
    for (size_t i = 0; i < sizeof units / sizeof units[0]; i++) {
        size_t n = strlen(units[i].unit);
        if (strncmp(s, units[i].unit, n) == 0 && *skip_ws(s + n) == 0) {
            *out *= units[i].px;
            return true;
        }
    }
    return false;
}

/* A length attribute of a shape; false after reporting a malformed one. */
static bool length_attr(svg_doc *doc, const char *name, const char *value, double *out)
{
    if (!value) {
        *out = 0;
        return true;
    }
    bool pct = false;
    if (!parse_length(value, out, &pct)) {
        svg_fail(doc, SR_BAD_FORMAT, "%s=\"%s\" is not a length", name, value);
        return false;
    }
    if (pct) {
        warn_once(doc, "length unit", "%");
        *out = 0;
    }
    return true;
}

static const char *attr(const char **atts, const char *name)
{
    for (int i = 0; atts[i]; i += 2) {
        if (strcmp(atts[i], name) == 0) {
            return atts[i + 1];
        }
    }
    return NULL;
}

/* ---- transforms ------------------------------------------------------------- */

static bool parse_transform(const char *s, mat2d *out)
{
    mat2d m = IDENTITY;
    s = skip_ws(s);
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
        s = skip_ws(s);
        if (*s++ != '(') {
            return false;
        }
        double v[6];
        int n = 0;
        s = skip_ws(s);
        while (*s != ')') {
            if (n == 6 || !parse_number(&s, &v[n])) {
                return false;
            }
            n++;
            s = skip_ws_comma(s);
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
        s = skip_ws_comma(s);
    }
    *out = m;
    return true;
}

/* ---- style properties --------------------------------------------------------- */

static bool parse_unit_number(const char *v, double *out)
{
    v = skip_ws(v);
    return parse_number(&v, out) && *skip_ws(v) == 0;
}

static double clamp01(double v)
{
    return v < 0 ? 0 : v > 1 ? 1 : v;
}

/* Properties this reader knows it does not support. */
static const char *const unsupported_props[] = {
    "stroke-dasharray", "stroke-dashoffset", "clip-path", "clip-rule", "mask", "filter",
    "marker", "marker-start", "marker-mid", "marker-end", "font", "font-family", "font-size",
    "font-weight", "font-style", "text-anchor", "color", "stop-color", "stop-opacity",
    "fill-paint", "paint-order", "vector-effect", "image-rendering", "color-interpolation",
    "mix-blend-mode", "isolation", NULL,
};

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
    if (strcmp(v, "inherit") == 0) {
        return true; /* the parent's value is already there */
    }
    double num;
    if (strcmp(name, "fill") == 0 || strcmp(name, "stroke") == 0) {
        bool fill = name[0] == 'f';
        sr_rgba c;
        switch (svg_parse_color(v, &c)) {
        case SVG_PAINT_NONE:
            *(fill ? &st->has_fill : &st->has_stroke) = false;
            break;
        case SVG_PAINT_COLOR:
            *(fill ? &st->has_fill : &st->has_stroke) = true;
            *(fill ? &st->fill : &st->stroke) = c;
            break;
        case SVG_PAINT_UNSUPPORTED:
            warn_once(doc, "paint", v);
            *(fill ? &st->has_fill : &st->has_stroke) = false;
            break;
        default:
            warn_once(doc, "color", v);
            break;
        }
    } else if (strcmp(name, "fill-opacity") == 0 || strcmp(name, "stroke-opacity") == 0 ||
               strcmp(name, "opacity") == 0) {
        if (!parse_unit_number(v, &num)) {
            warn_once(doc, name, v);
        } else if (name[0] == 'o') {
            st->opacity *= clamp01(num);
        } else {
            *(name[0] == 'f' ? &st->fill_opacity : &st->stroke_opacity) = clamp01(num);
        }
    } else if (strcmp(name, "fill-rule") == 0) {
        if (strcmp(v, "nonzero") == 0 || strcmp(v, "evenodd") == 0) {
            st->fill_rule = v[0] == 'n' ? SR_NONZERO : SR_EVENODD;
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

/* style="name: value; ...", applied after the presentation attributes. */
static void apply_style_attr(svg_doc *doc, style *st, const char *s)
{
    char buf[2048];
    snprintf(buf, sizeof buf, "%s", s);
    char *save = NULL;
    for (char *decl = strtok_r(buf, ";", &save); decl; decl = strtok_r(NULL, ";", &save)) {
        char *colon = strchr(decl, ':');
        if (!colon) {
            continue;
        }
        *colon = 0;
        char *name = decl;
        while (isspace((unsigned char)*name)) {
            name++;
        }
        char *end = name + strlen(name);
        while (end > name && isspace((unsigned char)end[-1])) {
            *--end = 0;
        }
        if (!apply_property(doc, st, name, colon + 1)) {
            warn_once(doc, "property", name);
        }
    }
}

/* ---- path data ----------------------------------------------------------------- */

typedef struct path_build {
    sr_path *path;
    double cx, cy;        /* current point */
    double sx, sy;        /* subpath start */
    double ctrl_x, ctrl_y;/* last control point (for S and T) */
    char last;            /* last command, upper case */
    bool started;
} path_build;

/* One path command with its numbers; the library's result. */
static sr_result path_command(path_build *b, char cmd, const double *a)
{
    bool rel = islower((unsigned char)cmd) != 0;
    char up = (char)toupper((unsigned char)cmd);
    double ox = rel ? b->cx : 0, oy = rel ? b->cy : 0;
    sr_result r = SR_OK;
    switch (up) {
    case 'M':
        b->cx = b->sx = a[0] + ox;
        b->cy = b->sy = a[1] + oy;
        r = sr_path_move_to(b->path, b->cx, b->cy);
        b->started = true;
        break;
    case 'L':
        b->cx = a[0] + ox;
        b->cy = a[1] + oy;
        r = sr_path_line_to(b->path, b->cx, b->cy);
        break;
    case 'H':
        b->cx = a[0] + ox;
        r = sr_path_line_to(b->path, b->cx, b->cy);
        break;
    case 'V':
        b->cy = a[0] + oy;
        r = sr_path_line_to(b->path, b->cx, b->cy);
        break;
    case 'C':
    case 'S': {
        double x1, y1, x2, y2, x, y;
        if (up == 'C') {
            x1 = a[0] + ox, y1 = a[1] + oy, x2 = a[2] + ox, y2 = a[3] + oy;
            x = a[4] + ox, y = a[5] + oy;
        } else { /* first control point: the reflection of the previous one */
            bool prev = b->last == 'C' || b->last == 'S';
            x1 = prev ? 2 * b->cx - b->ctrl_x : b->cx;
            y1 = prev ? 2 * b->cy - b->ctrl_y : b->cy;
            x2 = a[0] + ox, y2 = a[1] + oy, x = a[2] + ox, y = a[3] + oy;
        }
        r = sr_path_cubic_to(b->path, x1, y1, x2, y2, x, y);
        b->ctrl_x = x2;
        b->ctrl_y = y2;
        b->cx = x;
        b->cy = y;
        break;
    }
    case 'Q':
    case 'T': {
        double x1, y1, x, y;
        if (up == 'Q') {
            x1 = a[0] + ox, y1 = a[1] + oy, x = a[2] + ox, y = a[3] + oy;
        } else {
            bool prev = b->last == 'Q' || b->last == 'T';
            x1 = prev ? 2 * b->cx - b->ctrl_x : b->cx;
            y1 = prev ? 2 * b->cy - b->ctrl_y : b->cy;
            x = a[0] + ox, y = a[1] + oy;
        }
        r = sr_path_quad_to(b->path, x1, y1, x, y);
        b->ctrl_x = x1;
        b->ctrl_y = y1;
        b->cx = x;
        b->cy = y;
        break;
    }
    case 'A':
        r = sr_path_arc_to(b->path, a[0], a[1], a[2], a[3] != 0, a[4] != 0, a[5] + ox,
                           a[6] + oy);
        b->cx = a[5] + ox;
        b->cy = a[6] + oy;
        break;
    case 'Z':
        r = sr_path_close(b->path);
        b->cx = b->sx;
        b->cy = b->sy;
        break;
    }
    b->last = up;
    return r;
}

static int args_for(char up)
{
    switch (up) {
    case 'M': case 'L': case 'T': return 2;
    case 'H': case 'V': return 1;
    case 'C': return 6;
    case 'S': case 'Q': return 4;
    case 'A': return 7;
    default: return 0;
    }
}

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

/* Parse d="..." into the path; false after reporting an error. */
static bool parse_path_data(svg_doc *doc, const char *d, sr_path *path)
{
    path_build b = { .path = path };
    const char *s = skip_ws(d);
    char cmd = 0;
    while (*s) {
        if (isalpha((unsigned char)*s)) {
            cmd = *s++;
            if (!args_for((char)toupper((unsigned char)cmd)) && toupper((unsigned char)cmd) != 'Z') {
                svg_fail(doc, SR_BAD_FORMAT, "path data: unknown command '%c' at offset %ld", cmd,
                         (long)(s - 1 - d));
                return false;
            }
            if (!b.started && toupper((unsigned char)cmd) != 'M') {
                svg_fail(doc, SR_BAD_FORMAT, "path data must start with a moveto (offset %ld)",
                         (long)(s - 1 - d));
                return false;
            }
            if (toupper((unsigned char)cmd) == 'Z') {
                sr_result r = path_command(&b, cmd, NULL);
                if (r != SR_OK) {
                    lib_fail(doc, r);
                    return false;
                }
                s = skip_ws_comma(s);
                continue;
            }
        } else if (!cmd || toupper((unsigned char)cmd) == 'Z') {
            svg_fail(doc, SR_BAD_FORMAT, "path data: expected a command at offset %ld",
                     (long)(s - d));
            return false;
        }
        /* One set of arguments (commands repeat implicitly). */
        char up = (char)toupper((unsigned char)cmd);
        double a[7];
        int n = args_for(up);
        for (int i = 0; i < n; i++) {
            s = skip_ws(s);
            if (up == 'A' && (i == 3 || i == 4)) { /* flags: a single 0 or 1 */
                if (*s != '0' && *s != '1') {
                    svg_fail(doc, SR_BAD_FORMAT, "path data: arc flag must be 0 or 1 at offset %ld",
                             (long)(s - d));
                    return false;
                }
                a[i] = *s++ - '0';
            } else if (!parse_number(&s, &a[i])) {
                svg_fail(doc, SR_BAD_FORMAT, "path data: expected a number at offset %ld",
                         (long)(s - d));
                return false;
            }
            s = skip_ws_comma(s);
        }
        sr_result r = path_command(&b, cmd, a);
        if (r != SR_OK) {
            lib_fail(doc, r);
            return false;
        }
        if (!path_within_limits(doc, path, "path data", (long)(s - d))) {
            return false;
        }
        /* After a moveto, further pairs are linetos. */
        if (up == 'M') {
            cmd = cmd == 'M' ? 'L' : 'l';
        }
    }
    return true;
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

/* Map a polygon to pixels and fill it, within the document's budget. */
static void fill_mapped(svg_doc *doc, sr_polygon2 poly, mat2d m, sr_rgba color,
                        sr_fill_rule rule, bool crisp)
{
    if (poly.point_count == 0) {
        return;
    }
    if (!points_within_budget(doc, poly.point_count)) {
        return;
    }
    doc->points_used += poly.point_count;
    sr_point2 *pts = malloc((size_t)poly.point_count * sizeof *pts);
    if (!pts) {
        svg_fail(doc, SR_OUT_OF_MEMORY, "out of memory");
        return;
    }
    for (int i = 0; i < poly.point_count; i++) {
        pts[i] = mat_apply(m, poly.points[i]);
    }
    int w = sr_framebuffer_width(doc->fb), h = sr_framebuffer_height(doc->fb);
    double work = fill_work(pts, &poly, w, h);
    if (doc->work_used + work > doc->work_budget) {
        free(pts);
        svg_fail(doc, SR_TOO_LARGE,
                 "the drawing costs more than %.0f pixel operations, the limit for a %dx%d "
                 "image (%d per pixel + %d)",
                 doc->work_budget, w, h, SR_SVG_WORK_PER_PIXEL, SR_SVG_WORK_BASE);
        return;
    }
    doc->work_used += work;
    poly.points = pts;
    sr_result r = sr_fill_polygon(doc->ctx, doc->fb, &poly, color,
                                  &(sr_fill_desc){ .rule = rule,
                                                   .antialias = crisp ? SR_AA_NONE : SR_AA_AREA });
    free(pts);
    if (r != SR_OK) {
        lib_fail(doc, r);
    }
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

static void draw_path(svg_doc *doc, const frame *f, sr_path *path, double tol, bool fillable)
{
    const style *st = &f->st;
    if (st->display_none || st->invisible) {
        return;
    }
    if (fillable && st->has_fill && st->fill_opacity * st->opacity > 0) {
        sr_rgba c = st->fill;
        c.a = (float)(st->fill_opacity * st->opacity);
        fill_mapped(doc, sr_path_polygon(path), f->m, c, st->fill_rule, st->crisp);
    }
    if (st->has_stroke && st->stroke_width > 0 && st->stroke_opacity * st->opacity > 0 &&
        doc->status == SR_OK) {
        sr_polygon2 poly = sr_path_polygon(path);
        double est = stroke_points(&poly, st, tol);
        if (doc->points_used + est > doc->points_budget) {
            svg_fail(doc, SR_TOO_LARGE,
                     "stroke: the outline of stroke-width %g over %d points would need about "
                     "%.0f points, beyond the drawing's %.0f (%d + %d per byte of the document)",
                     st->stroke_width, poly.point_count, est, doc->points_budget,
                     SR_SVG_POINTS_BASE, SR_SVG_POINTS_PER_BYTE);
            return;
        }
        sr_polygon2 outline;
        sr_result r = sr_make_stroke_outline(doc->ctx, path,
                                        &(sr_stroke_desc){ .width = st->stroke_width,
                                                           .join = st->join, .cap = st->cap,
                                                           .miter_limit = st->miter_limit },
                                        &outline);
        if (r != SR_OK) {
            lib_fail(doc, r);
            return;
        }
        sr_rgba c = st->stroke;
        c.a = (float)(st->stroke_opacity * st->opacity);
        fill_mapped(doc, outline, f->m, c, SR_NONZERO, st->crisp);
        sr_destroy_stroke_outline(doc->ctx, &outline);
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
static bool shape_path(svg_doc *doc, const char *name, const char **atts, sr_path *p,
                       bool *fillable)
{
    *fillable = true;
    double v[6];
    if (strcmp(name, "path") == 0) {
        const char *d = attr(atts, "d");
        return d && parse_path_data(doc, d, p);
    }
    if (strcmp(name, "rect") == 0) {
        const char *rx_s = attr(atts, "rx"), *ry_s = attr(atts, "ry");
        if (!length_attr(doc, "x", attr(atts, "x"), &v[0]) ||
            !length_attr(doc, "y", attr(atts, "y"), &v[1]) ||
            !length_attr(doc, "width", attr(atts, "width"), &v[2]) ||
            !length_attr(doc, "height", attr(atts, "height"), &v[3]) ||
            !length_attr(doc, "rx", rx_s, &v[4]) || !length_attr(doc, "ry", ry_s, &v[5])) {
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
        if (!length_attr(doc, "cx", attr(atts, "cx"), &v[0]) ||
            !length_attr(doc, "cy", attr(atts, "cy"), &v[1])) {
            return false;
        }
        if (circle) {
            if (!length_attr(doc, "r", attr(atts, "r"), &v[2])) {
                return false;
            }
            v[3] = v[2];
        } else if (!length_attr(doc, "rx", attr(atts, "rx"), &v[2]) ||
                   !length_attr(doc, "ry", attr(atts, "ry"), &v[3])) {
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
        if (!length_attr(doc, "x1", attr(atts, "x1"), &v[0]) ||
            !length_attr(doc, "y1", attr(atts, "y1"), &v[1]) ||
            !length_attr(doc, "x2", attr(atts, "x2"), &v[2]) ||
            !length_attr(doc, "y2", attr(atts, "y2"), &v[3])) {
            return false;
        }
        return path_ok(doc, sr_path_move_to(p, v[0], v[1])) &&
               path_ok(doc, sr_path_line_to(p, v[2], v[3]));
    }
    /* polyline, polygon */
    const char *pts = attr(atts, "points");
    if (!pts) {
        return false;
    }
    const char *s = skip_ws(pts);
    int n = 0;
    while (*s) {
        double x, y;
        if (!parse_number(&s, &x) || !parse_number((s = skip_ws_comma(s), &s), &y)) {
            svg_fail(doc, SR_BAD_FORMAT, "%s: points: expected a coordinate pair at offset %ld",
                     name, (long)(s - pts));
            return false;
        }
        s = skip_ws_comma(s);
        if (!path_ok(doc, n++ == 0 ? sr_path_move_to(p, x, y) : sr_path_line_to(p, x, y)) ||
            !path_within_limits(doc, p, name, (long)(s - pts))) {
            return false;
        }
    }
    if (strcmp(name, "polygon") == 0 && !path_ok(doc, sr_path_close(p))) {
        return false;
    }
    return n > 0;
}

/* ---- the root element --------------------------------------------------------------- */

static bool parse_viewbox(const char *s, double vb[4])
{
    s = skip_ws(s);
    for (int i = 0; i < 4; i++) {
        if (!parse_number(&s, &vb[i])) {
            return false;
        }
        s = skip_ws_comma(s);
    }
    return *s == 0 && vb[2] > 0 && vb[3] > 0;
}

/* preserveAspectRatio: align x, y in {0, 0.5, 1} (-1: none), slice. */
static bool parse_aspect(const char *s, double *ax, double *ay, bool *slice)
{
    *ax = *ay = 0.5;
    *slice = false;
    if (!s) {
        return true;
    }
    s = skip_ws(s);
    if (strncmp(s, "defer", 5) == 0) {
        s = skip_ws(s + 5);
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
    s = skip_ws(s);
    if (strncmp(s, "slice", 5) == 0) {
        *slice = true;
        s += 5;
    } else if (strncmp(s, "meet", 4) == 0) {
        s += 4;
    }
    return *skip_ws(s) == 0;
}

static bool root_element(svg_doc *doc, const char **atts, frame *f)
{
    double vb[4];
    const char *vbs = attr(atts, "viewBox");
    bool have_vb = vbs && parse_viewbox(vbs, vb);
    if (vbs && !have_vb) {
        svg_fail(doc, SR_BAD_FORMAT, "viewBox=\"%s\" needs four numbers with width, height > 0", vbs);
        return false;
    }
    double w = 0, h = 0;
    bool wp = false, hp = false;
    const char *ws = attr(atts, "width"), *hs = attr(atts, "height");
    if (ws && !parse_length(ws, &w, &wp)) {
        svg_fail(doc, SR_BAD_FORMAT, "width=\"%s\" is not a length", ws);
        return false;
    }
    if (hs && !parse_length(hs, &h, &hp)) {
        svg_fail(doc, SR_BAD_FORMAT, "height=\"%s\" is not a length", hs);
        return false;
    }
    /* Intrinsic size: width/height, else the viewBox's, else 300 x 150. */
    if (!ws || wp || w <= 0) {
        w = have_vb ? vb[2] : 300;
    }
    if (!hs || hp || h <= 0) {
        h = have_vb ? vb[3] : 150;
    }
    if (!have_vb) {
        vb[0] = vb[1] = 0;
        vb[2] = w;
        vb[3] = h;
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
    double ax, ay;
    bool slice;
    const char *par = attr(atts, "preserveAspectRatio");
    if (!parse_aspect(par, &ax, &ay, &slice)) {
        warn_once(doc, "preserveAspectRatio", par);
        ax = ay = 0.5;
        slice = false;
    }
    /* The viewBox onto the whole image. */
    double sx = out_w / vb[2], sy = out_h / vb[3];
    if (ax >= 0) {
        sx = sy = slice ? fmax(sx, sy) : fmin(sx, sy);
    }
    double tx = -vb[0] * sx, ty = -vb[1] * sy;
    if (ax >= 0) {
        tx += (out_w - vb[2] * sx) * ax;
        ty += (out_h - vb[3] * sy) * ay;
    }
    f->m = (mat2d){ sx, 0, 0, sy, tx, ty };
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

static void XMLCALL on_start(void *user, const XML_Char *qname, const XML_Char **atts)
{
    svg_doc *doc = user;
    if (doc->status != SR_OK) {
        return;
    }
    doc->line = XML_GetCurrentLineNumber(doc->parser);
    if (doc->skip) {
        doc->skip++;
        return;
    }
    const char *name = local_name(qname);
    if (doc->depth + 1 >= MAX_DEPTH) {
        svg_fail(doc, SR_BAD_FORMAT, "elements nested deeper than %d", MAX_DEPTH);
        return;
    }
    frame f = doc->stack[doc->depth];
    if (!doc->seen_root) {
        if (strcmp(name, "svg") != 0) {
            svg_fail(doc, SR_BAD_FORMAT, "the root element is <%s>, not <svg>", name);
            return;
        }
        doc->seen_root = true;
        if (!root_element(doc, atts, &f)) {
            return;
        }
    } else if (strcmp(name, "svg") == 0) {
        warn_once(doc, "element", "svg (nested; drawn as a group)");
    } else if (strcmp(name, "title") == 0 || strcmp(name, "desc") == 0 ||
               strcmp(name, "metadata") == 0) {
        doc->skip = 1; /* no rendering: skipped silently */
        return;
    } else if (strcmp(name, "g") != 0 && !is_shape(name)) {
        warn_once(doc, "element", name);
        doc->skip = 1;
        return;
    }
    /* Style: presentation attributes, then style="" over them. */
    f.st.opacity = doc->stack[doc->depth].st.opacity;
    for (int i = 0; atts[i]; i += 2) {
        if (strcmp(atts[i], "style") != 0 && strcmp(atts[i], "transform") != 0) {
            apply_property(doc, &f.st, atts[i], atts[i + 1]);
        }
    }
    const char *style_attr = attr(atts, "style");
    if (style_attr) {
        apply_style_attr(doc, &f.st, style_attr);
    }
    const char *tr = attr(atts, "transform");
    if (tr) {
        mat2d t;
        if (!parse_transform(tr, &t)) {
            svg_fail(doc, SR_BAD_FORMAT, "transform=\"%s\" is malformed", tr);
            return;
        }
        f.m = mat_mul(f.m, t);
    }
    doc->stack[++doc->depth] = f;
    if (is_shape(name) && !f.st.display_none && !f.st.invisible) {
        /* Flatten in user units finely enough for the pixels: the
         * tolerance shrinks with the transform's scale. */
        double scale = matrix_scale(f.m);
        double tol = scale > 0 ? 0.1 / scale : 0.1;
        if (!(tol > 0) || !isfinite(tol)) {
            return; /* a singular transform: nothing visible */
        }
        sr_path *p = NULL;
        sr_result r = sr_make_path(doc->ctx, tol, &p);
        if (r != SR_OK) {
            lib_fail(doc, r);
            return;
        }
        bool fillable;
        /* Flattening is work too, drawn or not (fill="none"). */
        if (shape_path(doc, name, atts, p, &fillable) && doc->status == SR_OK &&
            points_within_budget(doc, sr_path_polygon(p).point_count)) {
            doc->points_used += sr_path_polygon(p).point_count;
            draw_path(doc, &f, p, tol, fillable);
        }
        sr_destroy_path(doc->ctx, p);
    }
}

static void XMLCALL on_end(void *user, const XML_Char *name)
{
    (void)name;
    svg_doc *doc = user;
    if (doc->skip) {
        doc->skip--;
        return;
    }
    if (doc->depth > 0) {
        doc->depth--;
    }
}

/* ---- the entry point -------------------------------------------------------------- */

static sr_result render(sr_context *ctx, const char *data, size_t size, const sr_svg_desc *opt,
                        sr_framebuffer **out, sr_svg_info *info, char *msg, size_t msg_size)
{
    const char *name = opt->name ? opt->name : "<svg>";
    if (size > SR_SVG_MAX_INPUT_BYTES) {
        snprintf(msg, msg_size, "%s: the document is %zu bytes, more than the %zu MiB limit", name,
                 size, SR_SVG_MAX_INPUT_BYTES >> 20);
        return SR_TOO_LARGE;
    }
    svg_doc *doc = calloc(1, sizeof *doc); /* the frame stack is 40 KB: not on the stack */
    if (!doc) {
        snprintf(msg, msg_size, "%s: out of memory", name);
        return SR_OUT_OF_MEMORY;
    }
    doc->file = name;
    doc->opt = opt;
    doc->ctx = ctx;
    doc->status = SR_OK;
    doc->msg = msg;
    doc->msg_size = msg_size;
    doc->points_budget = SR_SVG_POINTS_BASE + (double)SR_SVG_POINTS_PER_BYTE * (double)size;
    doc->parser = XML_ParserCreate(NULL);
    if (!doc->parser) {
        free(doc);
        snprintf(msg, msg_size, "%s: out of memory", name);
        return SR_OUT_OF_MEMORY;
    }
    /* Initial style (SVG defaults): fill black, no stroke, width 1. */
    doc->stack[0] = (frame){ IDENTITY,
                             { true, false, { 0, 0, 0, 1 }, { 0, 0, 0, 1 }, 1, 1, 1, SR_NONZERO, 1,
                               SR_STROKE_JOIN_MITER, SR_STROKE_CAP_BUTT, 4, false, false,
                               false } };
    XML_SetUserData(doc->parser, doc);
    XML_SetElementHandler(doc->parser, on_start, on_end);
    /* XML_Parse takes an int length: feed the buffer in pieces. */
    const size_t piece = (size_t)1 << 20;
    size_t at = 0;
    do {
        size_t n = size - at < piece ? size - at : piece;
        bool last = at + n == size;
        if (XML_Parse(doc->parser, data ? data + at : "", (int)n, last) == XML_STATUS_ERROR) {
            if (doc->status == SR_OK) {
                snprintf(msg, msg_size, "%s:%lu: %s", name,
                         (unsigned long)XML_GetCurrentLineNumber(doc->parser),
                         XML_ErrorString(XML_GetErrorCode(doc->parser)));
                doc->status = SR_BAD_FORMAT;
            }
            break;
        }
        at += n;
    } while (at < size && doc->status == SR_OK);
    if (doc->status == SR_OK && !doc->fb) {
        snprintf(msg, msg_size, "%s:1: no <svg> element", name);
        doc->status = SR_BAD_FORMAT;
    }
    sr_result status = doc->status;
    if (status == SR_OK) {
        *out = doc->fb;
    } else {
        sr_destroy_framebuffer(ctx, doc->fb);
    }
    *info = (sr_svg_info){ .points_used = doc->points_used, .points_budget = doc->points_budget,
                           .work_used = doc->work_used, .work_budget = doc->work_budget,
                           .warnings = doc->warnings };
    for (int i = 0; i < doc->n_warned; i++) {
        free(doc->warned[i]);
    }
    XML_ParserFree(doc->parser);
    free(doc);
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
    snprintf(msg, msg_size, "%s: this build reads no SVG (install libexpat1-dev and rebuild)",
             opt->name ? opt->name : "<svg>");
    return SR_UNSUPPORTED;
}

bool sr_io_have_svg(void)
{
    return false;
}

#endif /* SR_HAVE_EXPAT */

sr_result sr_render_svg(sr_context *ctx, const char *data, size_t size, const sr_svg_desc *desc,
                        sr_framebuffer **out, sr_svg_info *info, sr_io_error *err)
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
    return render(ctx, data, size, desc, out, info, err->message, sizeof err->message);
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

