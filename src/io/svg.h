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

/* ---- numbers and separators (svg_path_data.c) ------------------------- */

/* s past blanks; past blanks, one comma and blanks. */
const char *svg_skip_ws(const char *s);
const char *svg_skip_ws_comma(const char *s);
/* An SVG number (sign, digits, fraction, exponent), no leading blanks:
 * *s moved past it; false when there is none or it is beyond double. */
bool svg_parse_number(const char **s, double *out);
/* A length: a number with an optional unit in any case, as CSS reads
 * units: px, pt, pc, in, cm, mm (96 px per inch), em and ex (half an em)
 * of `em`; blanks around.  With percent, "%" is allowed (*percent set,
 * the number returned as is). */
bool svg_parse_length(const char *s, double em, double *out, bool *percent);

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

/* ---- gradients (svg.c) ------------------------------------------------ */

/* A gradient resolved for one shape as the library's paint
 * (sr_fill_polygon_paint), with the stops and the map it points to. */
typedef struct svg_gradient {
    sr_paint paint;
    sr_gradient_stop stops[SR_MAX_GRADIENT_STOPS];
    sr_point2 focal;
    sr_affine2 transform;        /* gradient space -> pixels */
} svg_gradient;

/* ---- blending into layers (svg_fill.c) --------------------------------- */

/* Source-over of a straight-alpha color with coverage (0..1) onto an RGBA8
 * pixel, as the 2D fills blend (the color quantized to RGBA8 first). */
void svg_blend(uint8_t *d, sr_rgba c, float cov);

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

/* ---- values quoted in messages (svg_quote.c) ----------------------------- */

/* A warning or error is one line: an attribute value it quotes is cut to
 * its first SVG_QUOTE_CHARS bytes, whole UTF-8 sequences, then "...". */
#define SVG_QUOTE_CHARS 60
#define SVG_QUOTE_SIZE (SVG_QUOTE_CHARS + sizeof "...")
/* s (NULL reads as "") as it is quoted, in out (SVG_QUOTE_SIZE bytes); returns out. */
const char *svg_quote(const char *s, char out[SVG_QUOTE_SIZE]);
/* svg_quote into a buffer that lives until the end of the enclosing block:
 * printf("%s", SVG_QUOTED(value)). */
#define SVG_QUOTED(s) svg_quote((s), (char[SVG_QUOTE_SIZE]){ 0 })

/* ---- gzip-compressed documents (svg_gzip.c) ----------------------------- */

/* Whether bytes start as gzip's do (1f 8b), whatever the file's name. */
bool svg_is_gzip(const void *data, size_t size);
/* The bytes gzip-compressed data stands for, malloc'd in *out (*out_size
 * of them), refused as SR_TOO_LARGE once they pass `limit` (a gzip bomb is
 * not inflated to the end); else a result and one line in why. */
sr_result svg_gunzip(const void *data, size_t size, size_t limit, char **out, size_t *out_size,
                     char *why, size_t why_size);

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

/* ---- filter effects (svg_filter.c) ------------------------------------- */

/* The properties of a filter primitive, cascaded (svg.c). */
typedef struct svg_fe_style {
    sr_rgba flood;               /* flood-color, flood-opacity folded into its alpha */
    sr_rgba lighting;            /* lighting-color */
    bool srgb;                   /* color-interpolation-filters: sRGB (else linearRGB) */
} svg_fe_style;

/* What a filter is applied to and the reader's services it uses. */
typedef struct svg_filter_job {
    const svg_node *filter;      /* the <filter> element */
    const uint8_t *source;       /* the element's layer, RGBA8 straight alpha */
    uint8_t *pixels;             /* width x height: the result, in the same form */
    int width, height;
    int origin[2];               /* the image pixel that is the layer's (0, 0): a
                                  * layer drawn beyond the image starts left of it
                                  * or above it */
    double m[6];                 /* user space -> the layer's pixels: a b c d e f */
    double bbox[4];              /* the element's x0 y0 x1 y1 in user space (empty: x1 <= x0) */
    double vp_w, vp_h;           /* the viewport, for percentages */
    sr_rgba fill, stroke;        /* FillPaint, StrokePaint: a flat color (transparent: none,
                                  * a paint server) */
    sr_context *ctx;
    void *host;                  /* the reader's document, handed to the calls below */
    /* "FILE:LINE: warning: unsupported KIND 'NAME' skipped", at the node's line */
    void (*warn)(void *host, const svg_node *at, const char *kind, const char *name);
    /* the document's failure "FILE:LINE: msg", at the node's line */
    void (*fail)(void *host, const svg_node *at, sr_result r, const char *msg);
    svg_fe_style (*style)(void *host, const svg_node *fe);
    /* false after reporting, at primitive `at`, that `work` more pixel
     * operations pass the budget */
    bool (*budget)(void *host, const svg_node *at, double work);
    /* feImage: the element `href` names ("#id"), or the picture it names
     * fitted into rect (x y w h, user space), drawn in the filtered
     * element's user space into out (RGBA8 straight, width x height,
     * cleared; left so when nothing is drawn, warned); false after a
     * failure */
    bool (*draw)(void *host, const svg_node *at, const char *href, const double rect[4],
                 uint8_t *out);
} svg_filter_job;

/* Run the filter's primitives on the layer (SVG 1.1 filter effects, in
 * premultiplied floats over the filter region at device resolution) and
 * put the result in its place; pixels outside the region become
 * transparent.  Failures go through job->fail. */
void svg_apply_filter(const svg_filter_job *job);

/* The pixels (x0 y0 x1 y1, the layer's; beyond it where the region is)
 * that the SourceGraphic must cover for the result inside the layer:
 * the filter region, cut to the layer widened by how far the primitives
 * can move content (offsets on the side they pull from, blurs, radii; a
 * tile or a wrapped edge takes the whole region; nothing when the result
 * does not read the source), at most the layer's width and height each
 * side;
 * passes: about how many times the filter's work budget counts each
 * pixel of its region.  False when the filter draws nothing.  Reads
 * job->filter, m, bbox, vp_w, vp_h, width and height; warns as
 * svg_apply_filter would. */
bool svg_filter_extent(const svg_filter_job *job, int out[4], double *passes);

/* The most memory (bytes) the filter's float images and scratch hold at
 * once while svg_apply_filter runs on the job, and (images) how many
 * images of the filter region that is; 0 when it draws nothing. */
uint64_t svg_filter_peak(const svg_filter_job *job, int *images);

/* B(cb, cs) of a blend mode on straight colors, each channel 0..1. */
void svg_blend_mix(svg_blend_kind mode, const float b[3], const float s[3], float out[3]);

/* Values of a stroke-dasharray, at most (an odd list doubled). */
#define SVG_MAX_DASHES SR_MAX_DASHES

#endif
