/* svg_text.c - the SVG reader's text (src/io, softrast_io): the font
 * properties of a style, and the layout of one <text>.  svg.c opens the
 * text's elements in document order with their cascaded styles and
 * character data; here the whitespace is collapsed, x, y, dx, dy and
 * rotate are given to the characters, the text is cut into chunks (a new
 * one at each absolute x or y) and runs of one element, each run shaped
 * with its face (svg_font.c), chunks moved by text-anchor, and each run's
 * glyphs and decorations appended to a path in user units for svg.c to
 * fill and stroke with the run's paint.  One document's thread. */
#include "io/svg_text.h"
#include "io/svg.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* font-size: medium, as rsvg-convert and resvg take it; the keywords
 * step by 1.2. */
#define MEDIUM_SIZE 12.0

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

svg_text_style svg_text_initial(void)
{
    return (svg_text_style){ .size = MEDIUM_SIZE, .weight = 400 };
}

void svg_text_reset_uninherited(svg_text_style *ts)
{
    ts->align = SVG_BASE_AUTO;
    ts->bidi = SVG_BIDI_NORMAL;
    ts->shift_kind = SVG_SHIFT_LENGTH;
    ts->shift = 0;
}

void svg_text_settle(svg_text_style *ts, const svg_text_style *parent)
{
    double own = ts->shift_kind == SVG_SHIFT_SUB       ? -0.2 * ts->size
                 : ts->shift_kind == SVG_SHIFT_SUPER   ? 0.4 * ts->size
                 : ts->shift_kind == SVG_SHIFT_PERCENT ? ts->shift / 100 * ts->size
                                                       : ts->shift;
    ts->raised = (parent ? parent->raised : 0) + own;
}

static int keyword(const char *v, const char *const *words)
{
    for (int i = 0; words[i]; i++) {
        if (strcmp(v, words[i]) == 0) {
            return i;
        }
    }
    return -1;
}

static bool font_size(svg_text_style *ts, double parent, const char *v)
{
    static const char *const sizes[] = { "xx-small", "x-small", "small", "medium", "large",
                                         "x-large", "xx-large", NULL };
    int k = keyword(v, sizes);
    if (k >= 0) {
        ts->size = MEDIUM_SIZE * pow(1.2, k - 3);
        return true;
    }
    if (strcmp(v, "larger") == 0 || strcmp(v, "smaller") == 0) {
        ts->size = v[0] == 'l' ? parent * 1.2 : parent / 1.2;
        return true;
    }
    double d;
    bool pct;
    if (!svg_parse_length(v, parent, &d, &pct) || d < 0 || !isfinite(d)) {
        return false;
    }
    ts->size = pct ? parent * d / 100 : d;
    return true;
}

static bool font_weight(svg_text_style *ts, int parent, const char *v)
{
    if (strcmp(v, "normal") == 0) {
        ts->weight = 400;
    } else if (strcmp(v, "bold") == 0) {
        ts->weight = 700;
    } else if (strcmp(v, "bolder") == 0) {
        ts->weight = parent < 350 ? 400 : parent < 550 ? 700 : 900;
    } else if (strcmp(v, "lighter") == 0) {
        ts->weight = parent < 550 ? 100 : parent < 750 ? 400 : 700;
    } else {
        const char *s = v;
        double d;
        if (!svg_parse_number(&s, &d) || *svg_skip_ws(s) || d < 1 || d > 1000) {
            return false;
        }
        ts->weight = (int)d;
    }
    return true;
}

static bool font_style(svg_text_style *ts, const char *v)
{
    int k = keyword(v, (const char *const[]){ "normal", "italic", "oblique", NULL });
    if (k < 0) {
        return false;
    }
    ts->slant = (unsigned char)k;
    return true;
}

static bool set_family(svg_text_style *ts, const char *v)
{
    size_t n = strlen(v);
    if (n == 0 || n >= sizeof ts->family) {
        return false;
    }
    memcpy(ts->family, v, n + 1);
    return true;
}

/* The font shorthand: [style] [weight] size[/line-height] family; the
 * variant and stretch words are taken and ignored. */
static bool font_shorthand(svg_text_style *ts, const svg_text_style *parent, const char *v)
{
    svg_text_style t = *ts;
    t.slant = SVG_SLANT_NORMAL;
    t.weight = 400;
    const char *s = v;
    for (;;) {
        s = svg_skip_ws(s);
        const char *e = s;
        while (*e && *e != ' ' && *e != '\t' && *e != '\n') {
            e++;
        }
        char word[64];
        if (e == s || (size_t)(e - s) >= sizeof word) {
            return false;
        }
        memcpy(word, s, (size_t)(e - s));
        word[e - s] = 0;
        char *slash = strchr(word, '/');
        if (slash) {
            *slash = 0;
        }
        if (font_style(&t, word) || font_weight(&t, parent ? parent->weight : 400, word) ||
            strcmp(word, "small-caps") == 0 || strstr(word, "condensed") ||
            strstr(word, "expanded")) {
            s = e;
            continue;
        }
        if (!font_size(&t, parent ? parent->size : MEDIUM_SIZE, word)) {
            return false;
        }
        s = svg_skip_ws(e);
        if (slash) { /* line-height: no lines here */
            while (*s && *s != ' ') {
                s++;
            }
            s = svg_skip_ws(s);
        }
        if (!set_family(&t, s)) {
            return false;
        }
        *ts = t;
        return true;
    }
}

static int baseline_value(const char *v)
{
    static const struct { const char *name; int value; } names[] = {
        { "auto", SVG_BASE_AUTO }, { "baseline", SVG_BASE_ALPHABETIC },
        { "alphabetic", SVG_BASE_ALPHABETIC }, { "middle", SVG_BASE_MIDDLE },
        { "central", SVG_BASE_CENTRAL }, { "hanging", SVG_BASE_HANGING },
        { "mathematical", SVG_BASE_MATHEMATICAL }, { "text-top", SVG_BASE_TEXT_TOP },
        { "text-before-edge", SVG_BASE_TEXT_TOP }, { "before-edge", SVG_BASE_TEXT_TOP },
        { "text-bottom", SVG_BASE_TEXT_BOTTOM }, { "text-after-edge", SVG_BASE_TEXT_BOTTOM },
        { "after-edge", SVG_BASE_TEXT_BOTTOM }, { "ideographic", SVG_BASE_IDEOGRAPHIC },
        { "use-script", SVG_BASE_AUTO }, { "no-change", SVG_BASE_AUTO },
        { "reset-size", SVG_BASE_AUTO },
    };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        if (strcmp(v, names[i].name) == 0) {
            return names[i].value;
        }
    }
    return -1;
}

static bool decoration(svg_text_style *ts, const char *v)
{
    unsigned char bits = 0;
    for (const char *s = svg_skip_ws(v); *s; s = svg_skip_ws(s)) {
        const char *e = s;
        while (*e && *e != ' ' && *e != '\t' && *e != '\n') {
            e++;
        }
        size_t n = (size_t)(e - s);
        if (n == 9 && strncmp(s, "underline", n) == 0) {
            bits |= SVG_DECO_UNDERLINE;
        } else if (n == 8 && strncmp(s, "overline", n) == 0) {
            bits |= SVG_DECO_OVERLINE;
        } else if (n == 12 && strncmp(s, "line-through", n) == 0) {
            bits |= SVG_DECO_LINE_THROUGH;
        } else if (!(n == 4 && (strncmp(s, "none", n) == 0 || strncmp(s, "blink", n) == 0))) {
            return false;
        }
        s = e;
    }
    /* the decorations of the ancestors stay: they are drawn through
     * the descendants' text as well */
    ts->decoration |= bits;
    return true;
}

static bool spacing(double *out, double em, const char *v)
{
    if (strcmp(v, "normal") == 0) {
        *out = 0;
        return true;
    }
    double d;
    bool pct;
    if (!svg_parse_length(v, em, &d, &pct) || !isfinite(d)) {
        return false;
    }
    *out = pct ? d / 100 * em : d;
    return true;
}

/* text-combine-upright: none | all | digits [2-4] (CSS Writing Modes 3
 * and 4; digits alone is digits 2). */
static bool combine_upright(svg_text_style *ts, const char *v)
{
    if (strcmp(v, "none") == 0 || strcmp(v, "all") == 0) {
        ts->combine = v[0] == 'a' ? SVG_COMBINE_ALL : SVG_COMBINE_NONE;
        return true;
    }
    if (strncmp(v, "digits", 6) != 0) {
        return false;
    }
    const char *s = svg_skip_ws(v + 6);
    double d = 2;
    if (*s && (s == v + 6 || !svg_parse_number(&s, &d) || *svg_skip_ws(s))) {
        return false;
    }
    if (!(d == 2 || d == 3 || d == 4)) {
        return false;
    }
    ts->combine = (unsigned char)d;
    return true;
}

int svg_text_property(svg_text_style *ts, const svg_text_style *parent, const char *name,
                      const char *v)
{
    static const char *const names[] = {
        "font-family", "font-size", "font-weight", "font-style", "text-anchor",
        "dominant-baseline", "alignment-baseline", "text-decoration", "letter-spacing",
        "word-spacing", "baseline-shift", "direction", "font", "unicode-bidi", "writing-mode",
        "glyph-orientation-vertical", "text-orientation", "text-combine-upright", NULL,
    };
    int k = keyword(name, names);
    if (k < 0) {
        return 0;
    }
    svg_text_style initial = svg_text_initial();
    const svg_text_style *p = parent ? parent : &initial;
    if (strcmp(v, "inherit") == 0) {
        const svg_text_style one = *p;
        switch (k) {
        case 0: memcpy(ts->family, one.family, sizeof ts->family); break;
        case 1: ts->size = one.size; break;
        case 2: ts->weight = one.weight; break;
        case 3: ts->slant = one.slant; break;
        case 4: ts->anchor = one.anchor; break;
        case 5: ts->baseline = one.baseline; break;
        case 6: ts->align = one.align; break;
        case 7: ts->decoration = one.decoration; break;
        case 8: ts->letter_spacing = one.letter_spacing; break;
        case 9: ts->word_spacing = one.word_spacing; break;
        case 10: ts->shift_kind = one.shift_kind; ts->shift = one.shift; break;
        case 11: ts->rtl = one.rtl; break;
        case 13: ts->bidi = one.bidi; break;
        case 14: ts->vertical = one.vertical; break;
        case 15:
        case 16: ts->orient = one.orient; break;
        case 17: ts->combine = one.combine; break;
        default: break;
        }
        return 1;
    }
    bool ok = false;
    int b;
    switch (k) {
    case 0: ok = set_family(ts, v); break;
    case 1: ok = font_size(ts, p->size, v); break;
    case 2: ok = font_weight(ts, p->weight, v); break;
    case 3: ok = font_style(ts, v); break;
    case 4:
        b = keyword(v, (const char *const[]){ "start", "middle", "end", NULL });
        ok = b >= 0;
        ts->anchor = ok ? (unsigned char)b : ts->anchor;
        break;
    case 5:
    case 6:
        b = baseline_value(v);
        ok = b >= 0;
        if (ok && k == 5) {
            ts->baseline = (unsigned char)b;
        } else if (ok) {
            ts->align = (unsigned char)b;
        }
        break;
    case 7: ok = decoration(ts, v); break;
    case 8: ok = spacing(&ts->letter_spacing, ts->size, v); break;
    case 9: ok = spacing(&ts->word_spacing, ts->size, v); break;
    case 10:
        if (strcmp(v, "baseline") == 0 || strcmp(v, "sub") == 0 || strcmp(v, "super") == 0) {
            ts->shift_kind = v[0] == 'b'        ? SVG_SHIFT_LENGTH
                             : strcmp(v, "sub") == 0 ? SVG_SHIFT_SUB
                                                     : SVG_SHIFT_SUPER;
            ts->shift = 0;
            ok = true;
        } else {
            double d;
            bool pct;
            ok = svg_parse_length(v, ts->size, &d, &pct) && isfinite(d);
            if (ok) {
                ts->shift_kind = pct ? SVG_SHIFT_PERCENT : SVG_SHIFT_LENGTH;
                ts->shift = d;
            }
        }
        break;
    case 11:
        b = keyword(v, (const char *const[]){ "ltr", "rtl", NULL });
        ok = b >= 0;
        ts->rtl = ok ? b == 1 : ts->rtl;
        break;
    case 12: ok = font_shorthand(ts, parent, v); break;
    case 13:
        b = keyword(v, (const char *const[]){ "normal", "embed", "bidi-override", NULL });
        ok = b >= 0;
        ts->bidi = ok ? (unsigned char)b : ts->bidi;
        break;
    case 14:
        b = keyword(v, (const char *const[]){ "lr-tb", "lr", "rl-tb", "rl", "horizontal-tb",
                                              "tb-rl", "tb", "vertical-rl", "vertical-lr",
                                              NULL });
        ok = b >= 0;
        ts->vertical = ok ? b >= 5 : ts->vertical;
        break;
    case 15:
        b = keyword(v, (const char *const[]){ "auto", "0", "0deg", "90", "90deg", "180",
                                              "180deg", "270", "270deg", NULL });
        ok = b >= 0;
        if (ok) {
            static const unsigned char orients[] = {
                SVG_ORIENT_MIXED,       SVG_ORIENT_UPRIGHT,      SVG_ORIENT_UPRIGHT,
                SVG_ORIENT_SIDEWAYS,    SVG_ORIENT_SIDEWAYS,     SVG_ORIENT_UPSIDE_DOWN,
                SVG_ORIENT_UPSIDE_DOWN, SVG_ORIENT_SIDEWAYS_LEFT, SVG_ORIENT_SIDEWAYS_LEFT,
            };
            ts->orient = orients[b];
        }
        break;
    case 16:
        /* sideways-right is CSS Writing Modes 3's old name for sideways */
        b = keyword(v, (const char *const[]){ "mixed", "upright", "sideways", "sideways-right",
                                              NULL });
        ok = b >= 0;
        if (ok) {
            ts->orient = b == 0 ? SVG_ORIENT_MIXED : b == 1 ? SVG_ORIENT_UPRIGHT
                                                            : SVG_ORIENT_SIDEWAYS;
        }
        break;
    case 17: ok = combine_upright(ts, v); break;
    default: ok = true; break;
    }
    return ok ? 1 : -1;
}

#ifdef SR_HAVE_SVG_TEXT

/* ---- one <text> ------------------------------------------------------------ */

enum { LIST_X, LIST_Y, LIST_DX, LIST_DY, LIST_ROTATE, N_LISTS };

typedef struct tchar {
    uint32_t cp;
    int elem;
    svg_face *face;              /* the element's, or a fallback that has the character */
    bool visible;
    double pos[N_LISTS];         /* NAN where no list gives one */
    double advance;              /* the pen's move over its cluster (first character) */
    double extra;                /* textLength's spacing after it */
    bool starts;                 /* a cluster starts here (while its run is placed) */
    bool collapsible;            /* a space xml:space does not preserve */
    bool upright;                /* stands upright in vertical text, with vertical metrics */
    int combine;                 /* its text-combine-upright unit: its first character + 1, or 0 */
} tchar;

typedef struct telem {
    svg_text_style ts;
    double *list[N_LISTS];
    int n[N_LISTS];
    int first, end;              /* its characters, descendants' included */
    int parent;
    svg_face *face;
    double text_length;          /* textLength, or 0 */
    bool stretch;                /* lengthAdjust="spacingAndGlyphs" */
    double sx;                   /* its glyphs' and advances' horizontal scale */
    int path;                    /* the textPath it is in (t->paths), or -1 */
} telem;

/* A textPath's path, flattened in the text's user space. */
typedef struct tpath {
    double *xy;                  /* its points, x and y */
    double *at;                  /* the distance along the path to each point */
    unsigned char *move;         /* a subpath starts at the point: no segment to it */
    int n;
    double start;                /* startOffset in user units */
} tpath;

/* Nested unicode-bidi embeddings followed, within FriBidi's 125 levels. */
#define MAX_EMBED 60

/* Glyphs of one path at most (SR_SVG_MAX_SUBPATHS bounds a path's
 * contours; a glyph has a few). */
#define MAX_RUN_GLYPHS 1024

/* A run placed: the glyphs of one element's characters in one chunk. */
typedef struct trun {
    int elem;
    svg_face *face;
    int path;                    /* the textPath its glyphs are bent along, or -1 */
    int glyph0, n_glyphs;        /* in t->placed */
    double x0, x1, y;            /* pen at its start and end, its baseline */
} trun;

typedef struct tglyph {
    unsigned id;
    bool visible;
    double mid;                  /* the middle of its cluster's advance, x before bending */
    double m[6];                 /* font units to user units */
} tglyph;

struct svg_text {
    tchar *chars;
    int n_chars, cap_chars;
    telem *elems;
    int n_elems, cap_elems;
    int open;                    /* the element characters go to, or -1 */
    svg_face *face;              /* every element's, when the caller chose it */
    trun *runs;
    int n_runs, cap_runs;
    tglyph *placed;
    int n_placed, cap_placed;
    uint32_t missing;            /* a character no font has, or 0 */
    bool unordered;              /* mixed directions left in logical order */
    bool vertical;               /* laid out top to bottom (the text element's writing-mode) */
    unsigned char *levels;       /* each character's bidi level, per chunk */
    uint32_t *bidi_in;           /* a chunk's characters and bidi controls */
    int *bidi_at;                /* where each character is among them */
    int cap_bidi;
    tpath *paths;
    int n_paths, cap_paths;
};

svg_text *svg_text_make(void)
{
    svg_text *t = calloc(1, sizeof *t);
    if (t) {
        t->open = -1;
    }
    return t;
}

void svg_text_free(svg_text *t)
{
    if (!t) {
        return;
    }
    for (int e = 0; e < t->n_elems; e++) {
        for (int k = 0; k < N_LISTS; k++) {
            free(t->elems[e].list[k]);
        }
    }
    free(t->elems);
    free(t->chars);
    free(t->runs);
    free(t->placed);
    free(t->levels);
    free(t->bidi_in);
    free(t->bidi_at);
    for (int i = 0; i < t->n_paths; i++) {
        free(t->paths[i].xy);
        free(t->paths[i].at);
        free(t->paths[i].move);
    }
    free(t->paths);
    free(t);
}

static bool grow(void **p, int *cap, int need, size_t size)
{
    if (need <= *cap) {
        return true;
    }
    int c = *cap ? *cap : 16;
    while (c < need) {
        if (c > (1 << 28)) {
            return false;
        }
        c *= 2;
    }
    void *g = realloc(*p, (size_t)c * size);
    if (!g) {
        return false;
    }
    *p = g;
    *cap = c;
    return true;
}

/* A list of lengths (x, y, dx, dy) or numbers (rotate), blanks or commas
 * between. */
static bool parse_list(const char *v, bool angles, double em, double ref, double **out, int *n)
{
    int cap = 0;
    *out = NULL;
    *n = 0;
    const char *s = svg_skip_ws(v);
    while (*s) {
        const char *e = s;
        while (*e && *e != ',' && *e != ' ' && *e != '\t' && *e != '\n' && *e != '\r') {
            e++;
        }
        char item[64];
        if ((size_t)(e - s) >= sizeof item) {
            return false;
        }
        memcpy(item, s, (size_t)(e - s));
        item[e - s] = 0;
        double d;
        bool pct = false;
        if (angles) {
            const char *p = item;
            if (!svg_parse_number(&p, &d) || *p) {
                return false;
            }
        } else if (!svg_parse_length(item, em, &d, &pct)) {
            return false;
        }
        if (!isfinite(d) || !grow((void **)out, &cap, *n + 1, sizeof **out)) {
            return false;
        }
        (*out)[(*n)++] = pct ? d / 100 * ref : d;
        s = svg_skip_ws_comma(e);
    }
    return true;
}

int svg_text_open(svg_text *t, const svg_text_style *ts, const char *const lists[7], double vp_w,
                  double vp_h, char *why, size_t why_size)
{
    static const char *const names[N_LISTS] = { "x", "y", "dx", "dy", "rotate" };
    if (!grow((void **)&t->elems, &t->cap_elems, t->n_elems + 1, sizeof *t->elems)) {
        snprintf(why, why_size, "out of memory");
        return -1;
    }
    telem *e = &t->elems[t->n_elems];
    *e = (telem){ .ts = *ts, .first = t->n_chars, .end = t->n_chars, .parent = t->open, .sx = 1,
                  .path = t->open >= 0 ? t->elems[t->open].path : -1 };
    bool pct = false;
    if (lists[5] && (!svg_parse_length(lists[5], ts->size, &e->text_length, &pct) ||
                     !isfinite(e->text_length) || e->text_length < 0)) {
        snprintf(why, why_size, "textLength=\"%s\" is not a length",
                 SVG_QUOTED(lists[5]));
        return -1;
    }
    e->text_length *= pct ? vp_w / 100 : 1;
    e->stretch = lists[6] && strcmp(lists[6], "spacingAndGlyphs") == 0;
    for (int k = 0; k < N_LISTS; k++) {
        double ref = k == LIST_X || k == LIST_DX ? vp_w : vp_h;
        if (lists[k] && !parse_list(lists[k], k == LIST_ROTATE, ts->size, ref, &e->list[k],
                                    &e->n[k])) {
            for (int j = 0; j <= k; j++) {
                free(e->list[j]);
            }
            snprintf(why, why_size, "%s=\"%s\" is not a list of %s", names[k],
                     SVG_QUOTED(lists[k]),
                     k == LIST_ROTATE ? "numbers" : "lengths");
            return -1;
        }
    }
    t->open = t->n_elems;
    return t->n_elems++;
}

bool svg_text_set_path(svg_text *t, int elem, const double *xy, const unsigned char *move, int n,
                       double start_offset, bool pct)
{
    if (!grow((void **)&t->paths, &t->cap_paths, t->n_paths + 1, sizeof *t->paths)) {
        return false;
    }
    tpath *p = &t->paths[t->n_paths];
    *p = (tpath){ malloc((size_t)(n > 0 ? n : 1) * 2 * sizeof *p->xy),
                  malloc((size_t)(n > 0 ? n : 1) * sizeof *p->at),
                  malloc((size_t)(n > 0 ? n : 1)), n, 0 };
    if (!p->xy || !p->at || !p->move) {
        free(p->xy);
        free(p->at);
        free(p->move);
        return false;
    }
    double len = 0;
    for (int i = 0; i < n; i++) {
        p->xy[2 * i] = xy[2 * i];
        p->xy[2 * i + 1] = xy[2 * i + 1];
        p->move[i] = i == 0 || move[i];
        if (!p->move[i]) {
            len += hypot(xy[2 * i] - xy[2 * i - 2], xy[2 * i + 1] - xy[2 * i - 1]);
        }
        p->at[i] = len;
    }
    p->start = pct ? start_offset / 100 * len : start_offset;
    t->elems[elem].path = t->n_paths++;
    return true;
}

void svg_text_close(svg_text *t)
{
    if (t->open >= 0) {
        t->elems[t->open].end = t->n_chars;
        t->open = t->elems[t->open].parent;
    }
}

static bool add_char(svg_text *t, uint32_t cp, bool visible, bool collapsible)
{
    if (!grow((void **)&t->chars, &t->cap_chars, t->n_chars + 1, sizeof *t->chars)) {
        return false;
    }
    t->chars[t->n_chars++] = (tchar){ cp, t->open, NULL, visible,
                                      { NAN, NAN, NAN, NAN, NAN }, 0, 0, false,
                                      collapsible, false, 0 };
    return true;
}

/* The next code point of UTF-8 (expat gives well-formed text). */
static uint32_t next_cp(const unsigned char **p, const unsigned char *end)
{
    const unsigned char *s = *p;
    uint32_t c = *s++;
    int more = c >= 0xF0 ? 3 : c >= 0xE0 ? 2 : c >= 0xC0 ? 1 : 0;
    c &= more == 3 ? 0x07 : more == 2 ? 0x0F : more == 1 ? 0x1F : 0x7F;
    for (; more > 0 && s < end; more--) {
        c = (c << 6) | (*s++ & 0x3F);
    }
    *p = s;
    return c;
}

bool svg_text_chars(svg_text *t, const char *s, size_t len, bool preserve, bool visible)
{
    const unsigned char *p = (const unsigned char *)s, *end = p + len;
    while (p < end) {
        uint32_t c = next_cp(&p, end);
        if (c == '\n' || c == '\r' || c == '\t') {
            /* SVG 1.1: newlines removed unless preserved, tabs spaces */
            if (!preserve && c != '\t') {
                continue;
            }
            c = ' ';
        }
        /* a run of spaces is one, and leading ones go (the trailing one
         * goes at layout), unless preserved; a space belongs to the
         * element it is written in */
        if (c == ' ' && !preserve && (t->n_chars == 0 || t->chars[t->n_chars - 1].cp == ' ')) {
            continue;
        }
        if (!add_char(t, c, visible, c == ' ' && !preserve)) {
            return false;
        }
    }
    return true;
}

double svg_text_advance(const svg_text *t)
{
    double lo = INFINITY, hi = -INFINITY;
    for (int r = 0; r < t->n_runs; r++) {
        lo = fmin(lo, fmin(t->runs[r].x0, t->runs[r].x1));
        hi = fmax(hi, fmax(t->runs[r].x0, t->runs[r].x1));
    }
    return hi > lo ? hi - lo : 0;
}

void svg_text_use_face(svg_text *t, svg_face *face)
{
    t->face = face;
}

int svg_text_length(const svg_text *t)
{
    return t->n_chars;
}

double svg_text_max_size(const svg_text *t)
{
    double m = 0;
    for (int e = 0; e < t->n_elems; e++) {
        m = fmax(m, t->elems[e].ts.size);
    }
    return m;
}

int svg_text_runs(const svg_text *t)
{
    return t->n_runs;
}

int svg_text_run_element(const svg_text *t, int run)
{
    return t->runs[run].elem;
}

uint32_t svg_text_missing(const svg_text *t)
{
    return t->missing;
}

bool svg_text_unordered(const svg_text *t)
{
    return t->unordered;
}

/* The Vertical_Orientation of cp: a binary search of the ranges. */
static int vertical_orientation(uint32_t cp)
{
    int lo = 0, hi = svg_vo_range_count - 1;
    while (lo <= hi) {
        int mid = (lo + hi) / 2;
        if (cp < svg_vo_ranges[mid].first) {
            hi = mid - 1;
        } else if (cp > svg_vo_ranges[mid].last) {
            lo = mid + 1;
        } else {
            return svg_vo_ranges[mid].vo;
        }
    }
    return SVG_VO_R;
}

/* Whether character c of a vertical text stands upright: as its
 * element's text-orientation (or glyph-orientation-vertical) says, and
 * with mixed (auto) by its Vertical_Orientation, a Tr character only
 * where its face has a vertical alternate for it (CSS Writing Modes 3,
 * 5.1).  On a textPath too: the line is bent onto the path with its
 * glyphs, upright ones included. */
static bool stands_upright(const svg_text *t, const tchar *c)
{
    const telem *el = &t->elems[c->elem];
    if (el->ts.orient == SVG_ORIENT_SIDEWAYS || el->ts.orient == SVG_ORIENT_SIDEWAYS_LEFT) {
        return false;
    }
    if (el->ts.orient == SVG_ORIENT_UPRIGHT || el->ts.orient == SVG_ORIENT_UPSIDE_DOWN) {
        return true;
    }
    switch (vertical_orientation(c->cp)) {
    case SVG_VO_U:
    case SVG_VO_TU: return true;
    case SVG_VO_TR: return svg_face_turns_vertical(c->face, c->cp);
    default: return false;
    }
}

/* Vertical text is laid out as a horizontal line along its y, across
 * -x, then turned a quarter clockwise: y's and dy's lists go along the
 * line, x's and dx's across it. */
static void turn_lists(svg_text *t)
{
    for (int i = 0; i < t->n_chars; i++) {
        double *p = t->chars[i].pos;
        double x = p[LIST_X], dx = p[LIST_DX];
        p[LIST_X] = p[LIST_Y];
        p[LIST_Y] = -x;
        p[LIST_DX] = p[LIST_DY];
        p[LIST_DY] = -dx;
        t->chars[i].upright = stands_upright(t, &t->chars[i]);
    }
}

/* Turn the glyphs laid out for a vertical text a quarter clockwise: (u,
 * v) of the line to (-v, u); glyphs bent onto a textPath are placed
 * already. */
static void turn_glyphs(svg_text *t)
{
    for (int r = 0; r < t->n_runs; r++) {
        if (t->runs[r].path >= 0) {
            continue;
        }
        for (int i = 0; i < t->runs[r].n_glyphs; i++) {
            double *m = t->placed[t->runs[r].glyph0 + i].m, n[6];
            memcpy(n, m, sizeof n);
            m[0] = -n[1], m[1] = n[0];
            m[2] = -n[3], m[3] = n[2];
            m[4] = -n[5], m[5] = n[4];
        }
    }
}

/* Whether characters a and b (a before b) are in one chunk: no absolute
 * position at b, one textPath. */
static bool same_chunk(const svg_text *t, int a, int b)
{
    return isnan(t->chars[b].pos[LIST_X]) && isnan(t->chars[b].pos[LIST_Y]) &&
           t->elems[t->chars[a].elem].path == t->elems[t->chars[b].elem].path;
}

/* The text-combine-upright units of a vertical text (CSS Writing Modes 3
 * 9.1, 4 for digits): a run of characters of elements with all, however
 * long (it is squeezed into one em), or a run of ASCII digits of elements
 * with digits N that is at most N long, within a chunk. */
static void mark_combined(svg_text *t)
{
    for (int i = 0; i < t->n_chars;) {
        int mode = t->elems[t->chars[i].elem].ts.combine;
        bool digit = t->chars[i].cp >= '0' && t->chars[i].cp <= '9';
        if (mode == SVG_COMBINE_NONE || (mode != SVG_COMBINE_ALL && !digit)) {
            i++;
            continue;
        }
        int e = i + 1;
        for (; e < t->n_chars && same_chunk(t, i, e); e++) {
            int m = t->elems[t->chars[e].elem].ts.combine;
            uint32_t cp = t->chars[e].cp;
            if (mode == SVG_COMBINE_ALL ? m != SVG_COMBINE_ALL
                                        : m < 2 || cp < '0' || cp > '9') {
                break;
            }
        }
        for (int k = i; k < e && (mode == SVG_COMBINE_ALL || e - i <= mode); k++) {
            t->chars[k].combine = i + 1;
        }
        i = e;
    }
}

/* Give each character the x, y, dx, dy and rotate of the innermost
 * element that has one for it (elements open outer first). */
static void assign_lists(svg_text *t)
{
    for (int e = 0; e < t->n_elems; e++) {
        const telem *el = &t->elems[e];
        int end = el->end < t->n_chars ? el->end : t->n_chars;
        for (int k = 0; k < N_LISTS; k++) {
            for (int i = 0; i < el->n[k] && el->first + i < end; i++) {
                t->chars[el->first + i].pos[k] = el->list[k][i];
            }
            /* rotate: the last value holds for the rest of the element */
            if (k == LIST_ROTATE && el->n[k] > 0) {
                for (int c = el->first + el->n[k]; c < end; c++) {
                    t->chars[c].pos[k] = el->list[k][el->n[k] - 1];
                }
            }
        }
    }
}

/* How far the glyphs of an element sit below its baseline position. */
static double baseline_offset(const telem *el)
{
    const svg_face_metrics *m = svg_face_get_metrics(el->face);
    double s = el->ts.size / m->upem;
    int b = el->ts.align != SVG_BASE_AUTO ? el->ts.align : el->ts.baseline;
    if (b == SVG_BASE_AUTO && el->ts.vertical) {
        b = SVG_BASE_CENTRAL; /* vertical text centres its glyphs on the line */
    }
    double down = 0;
    switch (b) {
    case SVG_BASE_MIDDLE: down = m->x_height / 2 * s; break;
    case SVG_BASE_CENTRAL: down = (m->ascender + m->descender) / 2 * s; break;
    case SVG_BASE_HANGING: down = 0.8 * m->ascender * s; break;
    case SVG_BASE_MATHEMATICAL: down = 0.5 * m->ascender * s; break;
    case SVG_BASE_TEXT_TOP: down = m->ascender * s; break;
    case SVG_BASE_TEXT_BOTTOM:
    case SVG_BASE_IDEOGRAPHIC: down = m->descender * s; break;
    default: break;
    }
    return down - el->ts.raised;
}

static bool add_run(svg_text *t, trun r)
{
    if (!grow((void **)&t->runs, &t->cap_runs, t->n_runs + 1, sizeof *t->runs)) {
        return false;
    }
    t->runs[t->n_runs++] = r;
    return true;
}

/* Shape characters [s, e) of one element and place their glyphs from the
 * pen on; the pen moves on. */
static sr_result place_run(svg_text *t, const uint32_t *cps, int s, int e, int dir,
                           double pen[2], svg_glyph **glyphs, int *cap)
{
    telem *el = &t->elems[t->chars[s].elem];
    svg_face *face = t->chars[s].face;
    const svg_face_metrics *m = svg_face_get_metrics(face);
    double scale = el->ts.size / m->upem, sx = el->sx;
    int n = svg_face_shape(face, cps, t->n_chars, s, e - s, dir, glyphs, cap);
    if (n < 0 || !grow((void **)&t->placed, &t->cap_placed, t->n_placed + n,
                       sizeof *t->placed)) {
        return SR_OUT_OF_MEMORY;
    }
    trun run = { t->chars[s].elem, face, el->path, t->n_placed, n, pen[0], pen[0], pen[1] };
    double down = baseline_offset(el);
    bool up = t->chars[s].upright;
    /* upright glyphs are centred on the line by their vertical origin:
     * they move off it only as far as the baseline does from central */
    double up_down = down - (m->ascender + m->descender) / 2 * scale;
    /* glyph-orientation-vertical 180 and 270: each cluster turned half
     * round about the middle of its advance on the central baseline, as
     * it stands before rotate turns it about the pen */
    bool flip = el->ts.vertical && (el->ts.orient == SVG_ORIENT_UPSIDE_DOWN ||
                                    el->ts.orient == SVG_ORIENT_SIDEWAYS_LEFT);
    double flip_at[2] = { 0, 0 };
    const svg_glyph *g = *glyphs;
    for (int k = s; k < e; k++) {
        t->chars[k].starts = false;
    }
    for (int i = 0; i < n; i++) {
        if (g[i].cluster >= s && g[i].cluster < e) {
            t->chars[g[i].cluster].starts = true;
        }
    }
    double cluster_x = pen[0];
    int cluster_glyph = t->n_placed;
    for (int i = 0; i < n; i++) {
        int c = g[i].cluster;
        bool first = i == 0 || g[i - 1].cluster != c;
        /* the characters of the cluster: up to the next cluster above */
        int c_end = c + 1;
        while (c_end < e && !t->chars[c_end].starts) {
            c_end++;
        }
        if (first && i > 0 && t->n_placed - run.glyph0 >= MAX_RUN_GLYPHS) {
            /* a long run is drawn in pieces: a path holds so many subpaths */
            run.n_glyphs = t->n_placed - run.glyph0;
            run.x1 = pen[0];
            if (!add_run(t, run)) {
                return SR_OUT_OF_MEMORY;
            }
            run.glyph0 = t->n_placed;
            run.x0 = pen[0];
        }
        if (first) {
            for (int k = c; k < c_end; k++) {
                if (!isnan(t->chars[k].pos[LIST_DX])) {
                    pen[0] += t->chars[k].pos[LIST_DX];
                }
                if (!isnan(t->chars[k].pos[LIST_DY])) {
                    pen[1] += t->chars[k].pos[LIST_DY];
                }
            }
            if (i == 0) {
                run.x0 = pen[0];
                run.y = pen[1] + down;
            }
            cluster_x = pen[0];
            cluster_glyph = t->n_placed;
        }
        double rot = t->chars[c].pos[LIST_ROTATE];
        double a = isnan(rot) ? 0 : rot * (M_PI / 180);
        double co = cos(a), si = sin(a);
        if (first && flip) {
            double adv = 0;
            for (int q = i; q < n && g[q].cluster == c; q++) {
                adv += up ? -g[q].ay * scale * sx : g[q].ax * scale * sx;
            }
            double du = adv / 2, dv = up ? 0 : up_down - down;
            flip_at[0] = pen[0] + co * du - si * dv;
            flip_at[1] = pen[1] + (up ? up_down : down) + si * du + co * dv;
        }
        if (up) {
            /* upright: the glyph as it stands after the quarter turn
             * (textLength stretching it down the line), its offset from
             * the pen (the vertical origin) turned by rotate, all turned
             * back a quarter here; the pen goes down by the vertical
             * advance */
            double f[4] = { scale * co, scale * si * sx, scale * si, -scale * co * sx };
            double dx = g[i].ox * scale, dy = -g[i].oy * scale * sx;
            double u = pen[0] + si * dx + co * dy, v = pen[1] + up_down - (co * dx - si * dy);
            t->placed[t->n_placed++] = (tglyph){ g[i].id, t->chars[c].visible, 0,
                                                 { f[1], -f[0], f[3], -f[2], u, v } };
            pen[0] -= g[i].ay * scale * sx;
            pen[1] -= g[i].ax * scale;
        } else {
            double ox = pen[0] + g[i].ox * scale * sx, oy = pen[1] + down - g[i].oy * scale;
            t->placed[t->n_placed++] = (tglyph){
                g[i].id, t->chars[c].visible, 0,
                { scale * sx * co, scale * sx * si, scale * si, -scale * co, ox, oy } };
            pen[0] += g[i].ax * scale * sx;
            pen[1] -= g[i].ay * scale;
        }
        bool last = i + 1 == n || g[i + 1].cluster != c;
        if (last) {
            /* on a path the cluster turns about its middle */
            for (int j = cluster_glyph; j < t->n_placed; j++) {
                double *gm = t->placed[j].m;
                t->placed[j].mid = (cluster_x + pen[0]) / 2;
                for (int q = 0; flip && q < 4; q++) {
                    gm[q] = -gm[q];
                }
                if (flip) {
                    gm[4] = 2 * flip_at[0] - gm[4];
                    gm[5] = 2 * flip_at[1] - gm[5];
                }
            }
            for (int k = c; k < c_end; k++) {
                pen[0] += el->ts.letter_spacing * sx;
                if (t->chars[k].cp == ' ') {
                    pen[0] += el->ts.word_spacing * sx;
                }
            }
            t->chars[c].advance = pen[0] - cluster_x;
            for (int k = c; k < c_end; k++) {
                pen[0] += t->chars[k].extra;
            }
        }
    }
    run.n_glyphs = t->n_placed - run.glyph0;
    run.x1 = pen[0];
    return add_run(t, run) ? SR_OK : SR_OUT_OF_MEMORY;
}

/* Place runs seg[k .. j) (start, end pairs) of one text-combine-upright
 * unit as one upright glyph (CSS Writing Modes 3, 9.1.1): shaped left to
 * right, squeezed across the line to one em where wider, centred on the
 * line and in an em square down it (its baseline as far below the
 * square's middle as the central baseline is below the alphabetic), the
 * pen going down one em.  The em, its place and its spacing are the
 * first character's element's; the dx and dy of all its characters move
 * it.  It is one typographic character: the rotate of its first
 * character turns it about its vertical origin (the top of the square,
 * on the line), as an upright glyph turns. */
static sr_result place_combined(svg_text *t, const uint32_t *cps, const int *seg, int k, int j,
                                double pen[2], svg_glyph **glyphs, int *cap)
{
    int first = seg[2 * k];
    const telem *head = &t->elems[t->chars[first].elem];
    const svg_face_metrics *hm = svg_face_get_metrics(t->chars[first].face);
    double em = head->ts.size, sx = head->sx, hs = em / hm->upem;
    double width = 0;
    for (int q = k; q < j; q++) {
        int s = seg[2 * q], e = seg[2 * q + 1];
        svg_face *face = t->chars[s].face;
        double scale = t->elems[t->chars[s].elem].ts.size / svg_face_get_metrics(face)->upem;
        int n = svg_face_shape(face, cps, t->n_chars, s, e - s, 0, glyphs, cap);
        if (n < 0) {
            return SR_OUT_OF_MEMORY;
        }
        for (int i = 0; i < n; i++) {
            width += (*glyphs)[i].ax * scale;
        }
    }
    double squeeze = width > em ? em / width : 1;
    for (int q = k; q < j; q++) {
        for (int c = seg[2 * q]; c < seg[2 * q + 1]; c++) {
            pen[0] += isnan(t->chars[c].pos[LIST_DX]) ? 0 : t->chars[c].pos[LIST_DX];
            pen[1] += isnan(t->chars[c].pos[LIST_DY]) ? 0 : t->chars[c].pos[LIST_DY];
        }
    }
    double start = pen[0];
    /* the square's middle: along the line, and across it where upright
     * glyphs' vertical origins go */
    double mu = start + em * sx / 2;
    double mv = pen[1] + baseline_offset(head) - (hm->ascender + hm->descender) / 2 * hs;
    double base = (hm->ascender + hm->descender) / 2 * hs, x = -width * squeeze / 2;
    double rot = t->chars[first].pos[LIST_ROTATE];
    double a = isnan(rot) ? 0 : rot * (M_PI / 180), co = cos(a), si = sin(a);
    for (int q = k; q < j; q++) {
        int s = seg[2 * q], e = seg[2 * q + 1];
        svg_face *face = t->chars[s].face;
        const telem *el = &t->elems[t->chars[s].elem];
        double scale = el->ts.size / svg_face_get_metrics(face)->upem;
        int n = svg_face_shape(face, cps, t->n_chars, s, e - s, 0, glyphs, cap);
        if (n < 0 || !grow((void **)&t->placed, &t->cap_placed, t->n_placed + n,
                           sizeof *t->placed)) {
            return SR_OUT_OF_MEMORY;
        }
        /* the decorations go along the whole square, with the first run */
        trun run = { t->chars[s].elem, face, el->path, t->n_placed, n, start,
                     q == k ? start + em * sx : start, pen[1] + baseline_offset(el) };
        const svg_glyph *g = *glyphs;
        for (int i = 0; i < n; i++) {
            if (t->n_placed - run.glyph0 >= MAX_RUN_GLYPHS) {
                /* a long unit is drawn in pieces, as a long run is */
                run.n_glyphs = t->n_placed - run.glyph0;
                if (!add_run(t, run)) {
                    return SR_OUT_OF_MEMORY;
                }
                run.glyph0 = t->n_placed;
                run.x1 = start;
            }
            /* (across, down) in the upright square from its middle, to
             * the line's (along, across), turned about (start, mv) */
            double across = x + g[i].ox * scale * squeeze, down = base - g[i].oy * scale;
            double u = mu + down * sx - start, v = -across;
            t->placed[t->n_placed++] = (tglyph){
                g[i].id, t->chars[g[i].cluster].visible, mu,
                { scale * squeeze * si, -scale * squeeze * co, -scale * sx * co,
                  -scale * sx * si, start + co * u - si * v, mv + si * u + co * v } };
            x += g[i].ax * scale * squeeze;
        }
        run.n_glyphs = t->n_placed - run.glyph0;
        if (!add_run(t, run)) {
            return SR_OUT_OF_MEMORY;
        }
    }
    pen[0] = start + em * sx + head->ts.letter_spacing * sx;
    t->chars[first].advance = pen[0] - start;
    for (int q = k; q < j; q++) {
        for (int c = seg[2 * q]; c < seg[2 * q + 1]; c++) {
            pen[0] += t->chars[c].extra;
        }
    }
    return SR_OK;
}

/* The elements with unicode-bidi embed or bidi-override that character
 * i is in, outermost first, into chain; their count.  Past MAX_EMBED the
 * innermost are left out, so that every character of an element sees
 * the same outer ones. */
static int embeddings(const svg_text *t, int i, int chain[MAX_EMBED])
{
    int all = 0;
    for (int e = t->chars[i].elem; e >= 0; e = t->elems[e].parent) {
        all += t->elems[e].ts.bidi != SVG_BIDI_NORMAL;
    }
    int n = all < MAX_EMBED ? all : MAX_EMBED, k = all;
    for (int e = t->chars[i].elem; e >= 0; e = t->elems[e].parent) {
        if (t->elems[e].ts.bidi != SVG_BIDI_NORMAL && --k < n) {
            chain[k] = e;
        }
    }
    return n;
}

/* The bidi level of each character of chunk [c, end) into t->levels, its
 * base direction rtl: the elements' unicode-bidi become the embedding and
 * override controls around their characters (as CSS maps them), which
 * FriBidi reads.  False when out of memory. */
static bool chunk_levels(svg_text *t, int c, int end, bool rtl)
{
    int need = (end - c) + 2 * t->n_elems;
    if (need > t->cap_bidi) {
        unsigned char *l = realloc(t->levels, (size_t)need);
        t->levels = l ? l : t->levels;
        uint32_t *in = realloc(t->bidi_in, (size_t)need * sizeof *in);
        t->bidi_in = in ? in : t->bidi_in;
        int *at = realloc(t->bidi_at, (size_t)need * sizeof *at);
        t->bidi_at = at ? at : t->bidi_at;
        if (!l || !in || !at) {
            return false;
        }
        t->cap_bidi = need;
    }
    int open[MAX_EMBED], depth = 0, m = 0;
    for (int i = c; i < end; i++) {
        int chain[MAX_EMBED];
        int n = embeddings(t, i, chain), same = 0;
        while (same < n && same < depth && chain[same] == open[same]) {
            same++;
        }
        for (; depth > same; depth--) {
            t->bidi_in[m++] = 0x202C; /* PDF */
        }
        for (; depth < n; depth++) {
            const svg_text_style *ts = &t->elems[chain[depth]].ts;
            open[depth] = chain[depth];
            /* LRE, RLE, LRO, RLO */
            t->bidi_in[m++] = ts->bidi == SVG_BIDI_EMBED ? (ts->rtl ? 0x202B : 0x202A)
                                                         : (ts->rtl ? 0x202E : 0x202D);
        }
        t->bidi_at[i - c] = m;
        t->bidi_in[m++] = t->chars[i].cp;
    }
    assert(m <= need); /* each element opens and closes once in a chunk */
    int got = svg_bidi_levels(t->bidi_in, m, rtl, t->levels);
    if (got < 0) {
        return false;
    }
    t->unordered = t->unordered || got == 1;
    /* the characters' levels, in place (each at or after its own index) */
    for (int i = 0; i < end - c; i++) {
        t->levels[i] = t->levels[t->bidi_at[i]];
    }
    return true;
}

/* Place chunk [c, end) from the pen on, its base direction rtl: runs of
 * one element, face and bidi level, each shaped in its level's direction
 * and placed in visual order (rule L2: from the highest level down to
 * the lowest odd one, reverse every sequence of runs at that level or
 * above). */
static sr_result place_chunk(svg_text *t, const uint32_t *cps, int c, int end, bool rtl,
                             double pen[2], svg_glyph **glyphs, int *cap)
{
    if (!chunk_levels(t, c, end, rtl)) {
        return SR_OUT_OF_MEMORY;
    }
    const unsigned char *lv = t->levels;
    /* at most one run per character: [start, end) pairs */
    int *seg = malloc((size_t)(end - c) * 2 * sizeof *seg);
    if (!seg) {
        return SR_OUT_OF_MEMORY;
    }
    int n_segs = 0, top = 0, low_odd = 255;
    for (int s = c; s < end; n_segs++) {
        int e = s + 1;
        while (e < end && t->chars[e].elem == t->chars[s].elem &&
               t->chars[e].face == t->chars[s].face && lv[e - c] == lv[s - c] &&
               t->chars[e].upright == t->chars[s].upright &&
               t->chars[e].combine == t->chars[s].combine) {
            e++;
        }
        seg[2 * n_segs] = s;
        seg[2 * n_segs + 1] = e;
        top = lv[s - c] > top ? lv[s - c] : top;
        if ((lv[s - c] & 1) && lv[s - c] < low_odd) {
            low_odd = lv[s - c];
        }
        s = e;
    }
    for (int level = top; level >= low_odd && level > 0; level--) {
        for (int k = 0; k < n_segs;) {
            if (lv[seg[2 * k] - c] < level) {
                k++;
                continue;
            }
            int j = k;
            while (j < n_segs && lv[seg[2 * j] - c] >= level) {
                j++;
            }
            for (int a = k, b = j - 1; a < b; a++, b--) {
                int s0 = seg[2 * a], e0 = seg[2 * a + 1];
                seg[2 * a] = seg[2 * b], seg[2 * a + 1] = seg[2 * b + 1];
                seg[2 * b] = s0, seg[2 * b + 1] = e0;
            }
            k = j;
        }
    }
    sr_result r = SR_OK;
    bool bidi = svg_bidi_available();
    for (int k = 0; k < n_segs && r == SR_OK; k++) {
        int s = seg[2 * k], e = seg[2 * k + 1];
        if (t->chars[s].combine) {
            int j = k + 1;
            while (j < n_segs && t->chars[seg[2 * j]].combine == t->chars[s].combine) {
                j++;
            }
            r = place_combined(t, cps, seg, k, j, pen, glyphs, cap);
            k = j - 1;
            continue;
        }
        /* without FriBidi each run goes as its script does, or right to
         * left where direction says so */
        int dir = bidi ? lv[s - c] & 1 : t->elems[t->chars[s].elem].ts.rtl ? 1 : -1;
        if (t->chars[s].upright) {
            dir = 2; /* top to bottom */
        }
        r = place_run(t, cps, s, e, dir, pen, glyphs, cap);
    }
    free(seg);
    return r;
}

/* Move the glyphs and runs of a chunk by dx. */
static void shift_chunk(svg_text *t, int run0, double dx)
{
    for (int r = run0; r < t->n_runs; r++) {
        trun *run = &t->runs[r];
        run->x0 += dx;
        run->x1 += dx;
        for (int i = 0; i < run->n_glyphs; i++) {
            t->placed[run->glyph0 + i].m[4] += dx;
            t->placed[run->glyph0 + i].mid += dx;
        }
    }
}

/* The point at distance s along path p and the angle of its tangent
 * there; false when s is off the path (before it, beyond its end). */
static bool path_at(const tpath *p, double s, double *x, double *y, double *angle)
{
    if (p->n < 2 || !(s >= 0 && s <= p->at[p->n - 1])) {
        return false;
    }
    int lo = 1, hi = p->n - 1;
    while (lo < hi) { /* the first point at s or beyond */
        int mid = (lo + hi) / 2;
        if (p->at[mid] < s) {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    while (lo < p->n && p->move[lo]) {
        lo++; /* the segment after a subpath's start */
    }
    if (lo == p->n) {
        return false;
    }
    const double *a = &p->xy[2 * (lo - 1)], *b = &p->xy[2 * lo];
    double len = p->at[lo] - p->at[lo - 1];
    double u = len > 0 ? (s - p->at[lo - 1]) / len : 0;
    *x = a[0] + (b[0] - a[0]) * u;
    *y = a[1] + (b[1] - a[1]) * u;
    *angle = atan2(b[1] - a[1], b[0] - a[0]);
    return true;
}

/* The pen at the end of path p. */
static void path_end(const tpath *p, double pen[2])
{
    if (p->n > 0) {
        pen[0] = p->xy[2 * (p->n - 1)];
        pen[1] = p->xy[2 * (p->n - 1) + 1];
    }
}

/* Bend the glyphs of a chunk laid out along x onto path p (SVG 1.1
 * 10.13.3): each cluster's middle goes to the point that far along the
 * path, the glyphs turned to the tangent there, dy lifting them off it;
 * a cluster whose middle is off the path is not drawn. */
static void bend_chunk(svg_text *t, int run0, const tpath *p)
{
    for (int r = run0; r < t->n_runs; r++) {
        for (int i = 0; i < t->runs[r].n_glyphs; i++) {
            tglyph *g = &t->placed[t->runs[r].glyph0 + i];
            double px, py, a;
            if (!path_at(p, g->mid, &px, &py, &a)) {
                g->visible = false;
                continue;
            }
            double co = cos(a), si = sin(a), m[6];
            memcpy(m, g->m, sizeof m);
            g->m[0] = co * m[0] - si * m[1];
            g->m[1] = si * m[0] + co * m[1];
            g->m[2] = co * m[2] - si * m[3];
            g->m[3] = si * m[2] + co * m[3];
            g->m[4] = px + co * (m[4] - g->mid) - si * m[5];
            g->m[5] = py + si * (m[4] - g->mid) + co * m[5];
        }
    }
}

/* Place every character: chunks from each absolute x or y, runs of one
 * element in them, text-anchor per chunk. */
static sr_result place_all(svg_text *t, const uint32_t *cps, svg_glyph **glyphs, int *cap)
{
    double pen[2] = { 0, 0 };
    sr_result r = SR_OK;
    t->n_runs = t->n_placed = 0;
    for (int c = 0; c < t->n_chars && r == SR_OK;) {
        /* a textPath's characters are chunks of their own, laid out along
         * x from its startOffset, then bent onto the path */
        int path = t->elems[t->chars[c].elem].path;
        int end = c + 1;
        while (end < t->n_chars && same_chunk(t, c, end)) {
            end++;
        }
        int before = c > 0 ? t->elems[t->chars[c - 1].elem].path : -1;
        if (path >= 0 && before != path) {
            pen[0] = t->paths[path].start;
            pen[1] = 0;
        } else if (path < 0 && before >= 0) {
            path_end(&t->paths[before], pen); /* text after a textPath goes on from its end */
        }
        if (!isnan(t->chars[c].pos[LIST_X])) {
            pen[0] = t->chars[c].pos[LIST_X];
        }
        if (!isnan(t->chars[c].pos[LIST_Y]) && path < 0) {
            pen[1] = t->chars[c].pos[LIST_Y];
        }
        const telem *head = &t->elems[t->chars[c].elem];
        double start = pen[0];
        int run0 = t->n_runs;
        r = place_chunk(t, cps, c, end, head->ts.rtl, pen, glyphs, cap);
        /* text-anchor of the chunk's first character; right to left,
         * start is the right end */
        double width = pen[0] - start;
        int anchor = head->ts.anchor;
        if (head->ts.rtl && anchor != SVG_ANCHOR_MIDDLE) {
            anchor = anchor == SVG_ANCHOR_START ? SVG_ANCHOR_END : SVG_ANCHOR_START;
        }
        double dx = anchor == SVG_ANCHOR_MIDDLE ? -width / 2
                    : anchor == SVG_ANCHOR_END  ? -width
                                                : 0;
        if (dx != 0 && r == SR_OK) {
            shift_chunk(t, run0, dx);
            pen[0] += dx;
        }
        if (path >= 0 && r == SR_OK) {
            bend_chunk(t, run0, &t->paths[path]);
        }
        c = end;
    }
    return r;
}

/* textLength: spread the difference between an element's advance and
 * its textLength over the gaps between its characters, or (lengthAdjust
 * spacingAndGlyphs) stretch its glyphs and advances; false when no
 * element asks for it. */
static bool fit_lengths(svg_text *t)
{
    bool any = false;
    for (int e = 0; e < t->n_elems; e++) {
        telem *el = &t->elems[e];
        int end = el->end < t->n_chars ? el->end : t->n_chars;
        if (el->text_length <= 0 || end <= el->first) {
            continue;
        }
        double natural = 0;
        for (int c = el->first; c < end; c++) {
            natural += t->chars[c].advance;
        }
        if (!(natural > 0)) {
            continue;
        }
        any = true;
        if (el->stretch) {
            for (int d = 0; d < t->n_elems; d++) {
                if (t->elems[d].first >= el->first && t->elems[d].end <= el->end) {
                    t->elems[d].sx *= el->text_length / natural;
                }
            }
        } else if (end - el->first > 1) {
            double gap = (el->text_length - natural) / (end - el->first - 1);
            for (int c = el->first; c + 1 < end; c++) {
                t->chars[c].extra += gap;
            }
        }
    }
    return any;
}

sr_result svg_text_layout(svg_text *t, svg_fonts *fonts, char *why, size_t why_size)
{
    while (t->n_chars > 0 && t->chars[t->n_chars - 1].collapsible) {
        t->n_chars--; /* the text's trailing space */
    }
    for (int e = 0; e < t->n_elems; e++) {
        telem *el = &t->elems[e];
        el->face = t->face ? t->face
                           : svg_fonts_match(fonts, el->ts.family[0] ? el->ts.family : "serif",
                                             el->ts.weight, el->ts.slant, why, why_size);
        if (!el->face) {
            return SR_BAD_FORMAT;
        }
    }
    /* each character's face: the element's, or the first fallback that
     * has it; a run is cut where the face changes */
    t->missing = 0;
    t->unordered = false;
    for (int i = 0; i < t->n_chars; i++) {
        tchar *c = &t->chars[i];
        svg_face *prev = i > 0 && t->chars[i - 1].elem == c->elem ? t->chars[i - 1].face : NULL;
        bool missing = false;
        c->face = svg_fonts_cover(fonts, t->elems[c->elem].face, prev, c->cp, &missing);
        if (missing && !t->missing) {
            t->missing = c->cp;
        }
    }
    assign_lists(t);
    /* SVG 1.1 takes writing-mode from the text element alone */
    t->vertical = t->n_elems > 0 && t->elems[0].ts.vertical;
    for (int e = 0; e < t->n_elems; e++) {
        t->elems[e].ts.vertical = t->vertical;
    }
    for (int i = 0; i < t->n_chars; i++) {
        t->chars[i].upright = false;
        t->chars[i].combine = 0;
    }
    if (t->vertical) {
        turn_lists(t);
        mark_combined(t);
    }
    uint32_t *cps = malloc((size_t)(t->n_chars ? t->n_chars : 1) * sizeof *cps);
    if (!cps) {
        snprintf(why, why_size, "out of memory");
        return SR_OUT_OF_MEMORY;
    }
    for (int i = 0; i < t->n_chars; i++) {
        cps[i] = t->chars[i].cp;
    }
    svg_glyph *glyphs = NULL;
    int cap = 0;
    sr_result r = place_all(t, cps, &glyphs, &cap);
    if (r == SR_OK && fit_lengths(t)) {
        r = place_all(t, cps, &glyphs, &cap); /* again, with the lengths fitted */
    }
    if (r == SR_OK && t->vertical) {
        turn_glyphs(t);
    }
    free(glyphs);
    free(cps);
    if (r != SR_OK) {
        snprintf(why, why_size, "out of memory");
    }
    return r;
}

/* A decoration's band, top y to bottom y (y down), from x0 to x1, wound
 * as the face's outer contours are. */
static sr_result add_band(sr_path *path, double x0, double x1, double top, double bottom,
                          bool clockwise, bool turn)
{
    double xs[4] = { x0, x1, x1, x0 }, ys[4] = { top, top, bottom, bottom };
    for (int k = 0; turn && k < 4; k++) { /* vertical text's quarter turn */
        double x = xs[k];
        xs[k] = -ys[k];
        ys[k] = x;
    }
    sr_result r = SR_OK;
    for (int k = 0; k < 4 && r == SR_OK; k++) {
        int i = clockwise ? k : (4 - k) % 4;
        r = k == 0 ? sr_path_move_to(path, xs[i], ys[i]) : sr_path_line_to(path, xs[i], ys[i]);
    }
    return r == SR_OK ? sr_path_close(path) : r;
}

sr_result svg_text_run_path(svg_text *t, svg_fonts *fonts, int run, sr_path *path)
{
    const trun *rn = &t->runs[run];
    const telem *el = &t->elems[rn->elem];
    sr_result r = SR_OK;
    for (int i = 0; i < rn->n_glyphs && r == SR_OK; i++) {
        const tglyph *g = &t->placed[rn->glyph0 + i];
        if (g->visible) {
            r = svg_face_outline(fonts, rn->face, g->id, g->m, path);
        }
    }
    unsigned deco = el->ts.decoration;
    /* no decorations along a path */
    if (r != SR_OK || !deco || rn->x1 <= rn->x0 || rn->path >= 0) {
        return r;
    }
    const svg_face_metrics *m = svg_face_get_metrics(el->face);
    double s = el->ts.size / m->upem, y = rn->y;
    if (deco & SVG_DECO_UNDERLINE) {
        double mid = y - m->underline_pos * s, h = m->underline_thick * s / 2;
        r = add_band(path, rn->x0, rn->x1, mid - h, mid + h, m->clockwise, t->vertical);
    }
    if (r == SR_OK && (deco & SVG_DECO_OVERLINE)) {
        double mid = y - m->ascender * s, h = m->underline_thick * s / 2;
        r = add_band(path, rn->x0, rn->x1, mid - h, mid + h, m->clockwise, t->vertical);
    }
    if (r == SR_OK && (deco & SVG_DECO_LINE_THROUGH)) {
        double top = y - m->strike_pos * s;
        r = add_band(path, rn->x0, rn->x1, top, top + m->strike_thick * s, m->clockwise,
                     t->vertical);
    }
    return r;
}

#endif
