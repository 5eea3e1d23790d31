/* svg.h - the SVG reader (src/io), internal: the document walk and drawing
 * behind sr_render_svg (svg.c) and its colors (svg_color.c).  The public
 * entry points and limits are in softrast_io.h. */
#ifndef SR_SVG_H
#define SR_SVG_H

#include "softrast_io.h"

typedef enum svg_paint_kind {
    SVG_PAINT_INVALID = 0,   /* not a color */
    SVG_PAINT_NONE,          /* "none" */
    SVG_PAINT_COLOR,         /* *out set, alpha 1 */
    SVG_PAINT_CURRENT,       /* "currentColor": the color property */
    SVG_PAINT_URL,           /* url(#id) [fallback]: a paint server */
} svg_paint_kind;

/* A CSS color: keyword, "transparent", #rgb, #rgba, #rrggbb, #rrggbbaa,
 * rgb()/rgba() and hsl()/hsla() (commas or blanks, integers, numbers or
 * percentages, an alpha after ',' or '/'), "currentColor", url(...) or
 * "none".  *out is set for SVG_PAINT_COLOR, alpha included. */
svg_paint_kind svg_parse_color(const char *s, sr_rgba *out);

/* ---- the document tree (svg.c) ---------------------------------------- */

typedef struct svg_node {
    const char *name;            /* local name, no namespace prefix */
    const char **atts;           /* name, value, ..., NULL (as expat gave them) */
    const char *id, *cls;        /* the id and class attributes, or NULL */
    unsigned long line;          /* of the start tag */
    struct svg_node *parent, *first, *last, *next;
    char *text;                  /* character data, kept for <style> only */
    size_t text_len;
    bool active;                 /* being drawn through a use chain */
    bool foreign;                /* a prefix other than svg: (editor data) */
} svg_node;

/* ---- style sheets (svg_css.c) ----------------------------------------- */

#define SVG_CSS_MAX_COMPOUNDS 8
#define SVG_CSS_MAX_CLASSES 8
/* Matching steps for one document: beyond this it is refused. */
#define SVG_CSS_MAX_WORK 20000000L

#define SVG_CSS_MAX_ATTRS 4

/* An attribute test: [name] (op 0), [name=v], [name~=v] (a word of the
 * list), [name|=v] (v or v-...), [name^=v], [name$=v], [name*=v]. */
typedef struct svg_css_attr {
    char *name, *value;
    char op;                     /* 0, '=', '~', '|', '^', '$', '*' */
} svg_css_attr;

typedef struct svg_css_compound {
    char *type, *id;             /* NULL: any */
    char *classes[SVG_CSS_MAX_CLASSES];
    int n_classes;
    svg_css_attr attrs[SVG_CSS_MAX_ATTRS];
    int n_attrs;
    bool first_child;            /* :first-child */
    char combinator;             /* to the compound on its left: ' ', '>', '+' or '~' */
} svg_css_compound;

typedef struct svg_css_selector {
    svg_css_compound parts[SVG_CSS_MAX_COMPOUNDS]; /* left to right */
    int n;
    long specificity;            /* ids * 10000 + classes * 100 + types */
} svg_css_selector;

typedef struct svg_css_decl {
    char *name, *value;
    bool important;
} svg_css_decl;

typedef struct svg_css_rule {
    svg_css_selector selector;
    svg_css_decl *decls;
    int n_decls;
    int order;                   /* in the document, for equal specificity */
} svg_css_rule;

typedef struct svg_css_sheet {
    svg_css_rule *rules;
    int n_rules;
} svg_css_sheet;

/* Add the rules of a style sheet's text; *unsupported counts selectors
 * and at-rules skipped.  False: out of memory. */
bool svg_css_parse(svg_css_sheet *sheet, const char *text, int *unsupported);
/* Append the declarations "name: value [!important]; ..." of s..e (a
 * style attribute or a rule's block) to rule.  False: out of memory. */
bool svg_css_parse_decls(const char *s, const char *e, svg_css_rule *rule);
/* Whether the selector matches the element; *work counts the steps. */
bool svg_css_matches(const svg_css_selector *sel, const svg_node *node, long *work);
void svg_css_free_rule(svg_css_rule *rule);
void svg_css_free(svg_css_sheet *sheet);

/* ---- gradients (svg_gradient.c) --------------------------------------- */

#define SVG_MAX_STOPS 256
/* Cells of a gradient's color table over t in [0, 1).  At 1024, a cell
 * between stops more than 0.26 apart changes a channel by less than 0.98
 * codes, so its centre's color is within half a code of each exact one
 * and the pixel within one code; the other cells (stops closer or inside
 * the cell) evaluate their pixels alone. */
#define SVG_GRADIENT_LUT 1024

typedef enum svg_spread { SVG_SPREAD_PAD, SVG_SPREAD_REFLECT, SVG_SPREAD_REPEAT } svg_spread;

/* A gradient resolved for one shape: its geometry in gradient space and
 * the map from pixel coordinates into that space; the color table is
 * filled as the fill's pixels ask for it. */
typedef struct svg_gradient {
    bool radial;
    double x1, y1, x2, y2;       /* linear: the gradient vector */
    double cx, cy, r, fx, fy, fr;/* radial: end circle, focal circle */
    svg_spread spread;
    double inv[6];               /* pixel -> gradient space (a b c d e f) */
    int n_stops;                 /* >= 1 */
    /* Cell k of the table: 0 until a pixel asks for it (resolve_gradient
     * zeroes this with the stops it reads), then 1 when lut[k] is within
     * half a code of every color of the cell, 2 when no one color is (a
     * stop inside, or a fast change): those pixels are evaluated alone.
     * Cell SVG_GRADIENT_LUT is t >= 1. */
    uint8_t lut_state[SVG_GRADIENT_LUT + 1];
    double offset[SVG_MAX_STOPS];/* non-decreasing, in [0, 1] */
    sr_rgba color[SVG_MAX_STOPS];/* straight alpha, opacity included */
    uint32_t lut[SVG_GRADIENT_LUT + 1]; /* RGBA8 in memory order, straight alpha */
} svg_gradient;

/* A paint along a row: the straight-alpha RGBA8 colors (memory order r,
 * g, b, a) at the centres of pixels x..x+n-1 of row y.  True when they
 * depend on x alone (every row gets the same bytes at the same x).  The
 * paint is not const: it may keep tables it fills as it goes. */
typedef bool (*svg_span_fn)(void *paint, int x, int y, int n, uint32_t *out);

/* A gradient (svg_gradient) as an svg_span_fn. */
bool svg_gradient_span(void *g, int x, int y, int n, uint32_t *out);

/* ---- painted fills (svg_fill.c) ------------------------------------------ */

/* A channel in [0, 1] as an 8-bit code, rounded (NaN and below 0: 0), as
 * the 2D fills quantize: every paint of the reader packs through it. */
static inline uint8_t svg_unorm8(float v)
{
    return !(v > 0.0f) ? 0 : v >= 1.0f ? 255 : (uint8_t)(v * 255.0f + 0.5f);
}

/* Source-over of a straight-alpha color with coverage (0..1) onto an RGBA8
 * pixel, as the 2D fills blend (the color quantized to RGBA8 first). */
void svg_blend(uint8_t *d, sr_rgba c, float cov);

/* Fill a polygon in pixel coordinates with a paint times opacity: the
 * coverage is sr_polygon_coverage's (the same pixels and weights as
 * sr_fill_polygon with that desc), the paint is evaluated over each row's
 * covered span and blended source-over as svg_blend does. */
sr_result svg_fill_paint(sr_context *ctx, sr_framebuffer *fb, const sr_polygon2 *poly,
                         const sr_fill_desc *desc, svg_span_fn span, void *paint,
                         float opacity);

/* An RGBA8 image (straight alpha) as a paint: pixel coordinates map into
 * it by inv; sampled bilinearly, repeated (a pattern tile) or its edge
 * texels extended (an image: the fill stays inside it). */
typedef struct svg_image {
    const uint8_t *rgba;
    int w, h;
    double inv[6];               /* pixel -> image texels (a b c d e f) */
    bool repeat;
} svg_image;

/* An image (svg_image) as an svg_span_fn (svg_image_paint.c). */
bool svg_image_span(void *image, int x, int y, int n, uint32_t *out);

/* ---- image sources (svg_image.c) ---------------------------------------- */

/* The bytes of a data: URI (*out malloc'd): base64,
 * or percent-encoded text (an SVG's "data:image/svg+xml,%3Csvg..."); false
 * when uri is not one (another scheme, a bad character or escape) or out
 * of memory. */
bool svg_data_uri(const char *uri, uint8_t **out, size_t *size);

/* The file an <image> href names, relative to the directory of the
 * document's path, its "." and empty segments dropped (so that a file
 * has one name); malloc'd; NULL for what is not read: absolute paths,
 * URLs, paths that climb out with "..", or out of memory. */
char *svg_image_path(const char *document, const char *href);

/* ---- blend modes (svg_blend.c) ------------------------------------------ */

typedef enum svg_blend_kind {
    SVG_BLEND_NORMAL, SVG_BLEND_MULTIPLY, SVG_BLEND_SCREEN, SVG_BLEND_OVERLAY,
    SVG_BLEND_DARKEN, SVG_BLEND_LIGHTEN, SVG_BLEND_COLOR_DODGE, SVG_BLEND_COLOR_BURN,
    SVG_BLEND_HARD_LIGHT, SVG_BLEND_SOFT_LIGHT, SVG_BLEND_DIFFERENCE, SVG_BLEND_EXCLUSION,
    SVG_BLEND_HUE, SVG_BLEND_SATURATION, SVG_BLEND_COLOR, SVG_BLEND_LUMINOSITY,
    SVG_BLEND_COUNT
} svg_blend_kind;

/* The mode a mix-blend-mode keyword names, or -1. */
int svg_blend_mode(const char *name);

/* The color (straight alpha, src.a kept) that src takes over the RGBA8
 * backdrop under the mode: B(backdrop, src) where the backdrop is
 * opaque, src itself where it is transparent, mixed by its alpha. */
sr_rgba svg_blend_color(svg_blend_kind mode, const uint8_t backdrop[4], sr_rgba src);

/* ---- dashes (svg_dash.c) ----------------------------------------------- */

/* Values of a stroke-dasharray, at most. */
#define SVG_MAX_DASHES 32

/* The length of the flattened path, closing segments included. */
double svg_path_length(const sr_path *path);

/* Append to out the dashes of path `in`: dash[0..n) are the lengths of
 * dashes and gaps in turn (n even, each >= 0, their sum > 0), the pattern
 * starting `offset` into itself at every subpath.  The caller bounds the
 * work: about length / sum * n dashes. */
sr_result svg_dash_path(const sr_path *in, const double *dash, int n, double offset,
                        sr_path *out);

#endif
