/* svg_text.h - the SVG reader's text (src/io, internal): the font
 * properties a style carries (svg_text.c), fonts matched by fontconfig,
 * shaped by HarfBuzz and read by FreeType (svg_font.c), and the layout of
 * one <text> into glyph outlines as softrast paths (svg_text.c).  svg.c
 * walks the text's elements and fills the paths like any shape's.
 * Without fontconfig, HarfBuzz and FreeType (SR_HAVE_SVG_TEXT unset)
 * svg_text_available() is false and <text> is skipped with a warning. */
#ifndef SR_SVG_TEXT_H
#define SR_SVG_TEXT_H

#include "softrast.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Whether this build draws text. */
bool svg_text_available(void);

/* ---- font properties (svg_text.c) ---------------------------------------- */

enum { SVG_ANCHOR_START, SVG_ANCHOR_MIDDLE, SVG_ANCHOR_END };
enum { SVG_SLANT_NORMAL, SVG_SLANT_ITALIC, SVG_SLANT_OBLIQUE };
enum { SVG_DECO_UNDERLINE = 1, SVG_DECO_OVERLINE = 2, SVG_DECO_LINE_THROUGH = 4 };
/* dominant-baseline and alignment-baseline values that move glyphs. */
enum { SVG_BASE_AUTO, SVG_BASE_ALPHABETIC, SVG_BASE_MIDDLE, SVG_BASE_CENTRAL, SVG_BASE_HANGING,
       SVG_BASE_MATHEMATICAL, SVG_BASE_TEXT_TOP, SVG_BASE_TEXT_BOTTOM, SVG_BASE_IDEOGRAPHIC };
enum { SVG_SHIFT_LENGTH, SVG_SHIFT_SUB, SVG_SHIFT_SUPER, SVG_SHIFT_PERCENT };
enum { SVG_BIDI_NORMAL, SVG_BIDI_EMBED, SVG_BIDI_OVERRIDE };
/* How glyphs stand in vertical text: by character (text-orientation
 * mixed, glyph-orientation-vertical auto), all upright (upright, 0), all
 * turned (sideways, 90), all upright upside down (180), all turned the
 * other way (270). */
enum { SVG_ORIENT_MIXED, SVG_ORIENT_UPRIGHT, SVG_ORIENT_SIDEWAYS, SVG_ORIENT_UPSIDE_DOWN,
       SVG_ORIENT_SIDEWAYS_LEFT };
/* text-combine-upright: none, all, or digits N (the value N, 2 to 4). */
enum { SVG_COMBINE_NONE, SVG_COMBINE_ALL };

/* The text properties of a style.  All inherit except those marked. */
typedef struct svg_text_style {
    char family[128];        /* font-family as written; "" is the initial (serif) */
    double size;             /* font-size in user units */
    int weight;              /* font-weight, 1..1000 */
    unsigned char slant;     /* font-style */
    unsigned char anchor;    /* text-anchor */
    unsigned char baseline;  /* dominant-baseline */
    unsigned char align;     /* alignment-baseline (not inherited; AUTO: the dominant one) */
    unsigned char decoration;/* text-decoration bits (taken on by the descendants) */
    bool rtl;                /* direction: rtl */
    unsigned char bidi;      /* unicode-bidi (not inherited) */
    bool vertical;           /* writing-mode tb, tb-rl, vertical-rl, vertical-lr */
    unsigned char orient;    /* text-orientation, glyph-orientation-vertical */
    unsigned char combine;   /* text-combine-upright */
    double letter_spacing, word_spacing;
    unsigned char shift_kind;/* baseline-shift (not inherited) */
    double shift;            /* its length, or percentage of the font size */
    double raised;           /* the ancestors' shifts added up, up positive */
} svg_text_style;

/* The initial values. */
svg_text_style svg_text_initial(void);
/* Ready a copy of the parent's for an element's own declarations. */
void svg_text_reset_uninherited(svg_text_style *ts);
/* Apply one declaration: 1 taken, 0 not a text property, -1 a text
 * property with a value not understood (left as it was).  parent: the
 * parent's (for inherit, em and %), or NULL at the root. */
int svg_text_property(svg_text_style *ts, const svg_text_style *parent, const char *name,
                      const char *value);
/* After the cascade: add the element's own baseline shift to the
 * ancestors' (parent NULL: none). */
void svg_text_settle(svg_text_style *ts, const svg_text_style *parent);

/* ---- vertical orientation (svg_vertical.c) ------------------------------ */

/* Unicode's Vertical_Orientation (UAX #50): R turned sideways, U
 * upright, Tu upright with a vertical alternate glyph, Tr upright when
 * the font has a vertical alternate for it, else turned. */
enum { SVG_VO_R, SVG_VO_U, SVG_VO_TU, SVG_VO_TR };
/* The code points that are not R, in ascending ranges. */
typedef struct svg_vo_range {
    uint32_t first, last;
    unsigned char vo;
} svg_vo_range;
extern const svg_vo_range svg_vo_ranges[];
extern const int svg_vo_range_count;

/* ---- bidirectional text (svg_bidi.c) ------------------------------------ */

/* Whether this build reorders bidirectional text (it found FriBidi). */
bool svg_bidi_available(void);
/* The resolved embedding level of each of cps[0 .. n) (bidi control
 * characters among them) in a line of base direction rtl, into levels:
 * 0 done, 1 done without reordering (no FriBidi: every level the base's)
 * though the text mixes directions, -1 out of memory. */
int svg_bidi_levels(const uint32_t *cps, int n, bool rtl, unsigned char *levels);

/* ---- fonts (svg_font.c) ------------------------------------------------- */

typedef struct svg_fonts svg_fonts;   /* the faces one document matched */
typedef struct svg_face svg_face;

typedef struct svg_face_metrics {
    double upem;                      /* font units per em */
    double ascender, descender;       /* y up, descender negative */
    double x_height;
    double underline_pos, underline_thick;
    double strike_pos, strike_thick;  /* the top of the stroke and its size */
    bool clockwise;                   /* outer contours (y up), once a glyph is read */
    bool oriented;
} svg_face_metrics;

/* A glyph as shaped: id, the index of its first character (the cluster),
 * advance and offset in font units, y up. */
typedef struct svg_glyph {
    unsigned id;
    int cluster;
    double ax, ay, ox, oy;
} svg_glyph;

svg_fonts *svg_fonts_make(void);
void svg_fonts_free(svg_fonts *fonts);
/* The face fontconfig matches for a family list (as font-family writes
 * it), a weight and a slant, kept for the next request; NULL with a line
 * in why. */
svg_face *svg_fonts_match(svg_fonts *fonts, const char *family, int weight, int slant,
                          char *why, size_t why_size);
/* The face of a font file (its first face), kept like a match; NULL
 * with a line in why. */
svg_face *svg_fonts_open_file(svg_fonts *fonts, const char *file, char *why, size_t why_size);
/* The face that draws code point cp in a text whose element matched
 * face: face when it has the character, else the first font of
 * fontconfig's sorted list for face's request that has it (opened once).
 * Marks, joiners and other format characters go with prev, the face of
 * the character before (NULL at the start).  When no font has cp (or
 * face is a caller's file), face with *missing set: its .notdef draws. */
svg_face *svg_fonts_cover(svg_fonts *fonts, svg_face *face, svg_face *prev, uint32_t cp,
                          bool *missing);
const svg_face_metrics *svg_face_get_metrics(const svg_face *face);
/* Shape cps[start .. start+len) (the rest of cps is context) left to
 * right (dir 0), right to left (1), top to bottom (2: upright glyphs of
 * vertical text, with vertical metrics and alternates; advances and
 * offsets from the vertical origin, y_advance negative) or as its script
 * goes (-1): glyphs in visual order into *glyphs (grown as needed, *cap
 * its room); their count, or -1 when out of memory. */
int svg_face_shape(svg_face *face, const uint32_t *cps, int n, int start, int len, int dir,
                   svg_glyph **glyphs, int *cap);
/* Whether the face has a vertical alternate (OpenType vert or vrt2)
 * for code point cp: a Tr character then stands upright. */
bool svg_face_turns_vertical(svg_face *face, uint32_t cp);
/* Append glyph id's outline mapped by m (a, b, c, d, e, f: font units,
 * y up, to user units) to path. */
sr_result svg_face_outline(svg_fonts *fonts, svg_face *face, unsigned id, const double m[6],
                           sr_path *path);

/* ---- laying out one <text> (svg_text.c) ---------------------------------- */

typedef struct svg_text svg_text;

svg_text *svg_text_make(void);
void svg_text_free(svg_text *t);
/* Open an element of the text (text, tspan, a): its style and its
 * attributes x, y, dx, dy, rotate, textLength and lengthAdjust, in that
 * order (NULL when absent; lengths in user units, % of the viewport
 * vp_w x vp_h).  Its index (0, 1, ... in opening order), or -1 with a
 * line in why (out of memory, a malformed value). */
int svg_text_open(svg_text *t, const svg_text_style *ts, const char *const lists[7], double vp_w,
                  double vp_h, char *why, size_t why_size);
/* Lay the characters of element elem (just opened: its descendants take
 * it on) along a path of n points xy (x, y pairs in user units; move[i]
 * set where a subpath starts), from start_offset along it (a percentage
 * of its length when pct).  False when out of memory. */
bool svg_text_set_path(svg_text *t, int elem, const double *xy, const unsigned char *move, int n,
                       double start_offset, bool pct);
void svg_text_close(svg_text *t);
/* Character data of the open element, UTF-8; whitespace as xml:space
 * says (preserve: each blank a space; else newlines dropped, blanks
 * collapsed, leading and trailing ones of the whole text dropped).
 * visible false (visibility hidden): the characters take their place but
 * draw nothing.  False when out of memory. */
bool svg_text_chars(svg_text *t, const char *s, size_t len, bool preserve, bool visible);
/* Characters so far. */
int svg_text_length(const svg_text *t);
/* Match, shape and place every character; SR_OK or a result with a line
 * in why. */
sr_result svg_text_layout(svg_text *t, svg_fonts *fonts, char *why, size_t why_size);
/* After layout: a character that no font has (drawn as its font's
 * .notdef), or 0. */
uint32_t svg_text_missing(const svg_text *t);
/* After layout: whether a chunk mixing directions was left in logical
 * order (a build without FriBidi). */
bool svg_text_unordered(const svg_text *t);
/* The runs to draw, in order: consecutive characters of one element. */
int svg_text_runs(const svg_text *t);
/* The element (svg_text_open's index) whose paint a run takes. */
int svg_text_run_element(const svg_text *t, int run);
/* Append a run's glyphs and decorations to path (user units). */
sr_result svg_text_run_path(svg_text *t, svg_fonts *fonts, int run, sr_path *path);
/* Lay the text out with this face for every element instead of matching
 * their families (a font file the caller names). */
void svg_text_use_face(svg_text *t, svg_face *face);
/* The width the runs' pens cover, from the leftmost start to the
 * rightmost end. */
double svg_text_advance(const svg_text *t);
/* The largest font size in the text, for the caller's limits. */
double svg_text_max_size(const svg_text *t);

#endif
