/* svg_font.c - fonts for the SVG reader's text (src/io, softrast_io):
 * fontconfig picks the file for a family list, weight and slant;
 * HarfBuzz shapes runs of characters into glyphs (kerning, ligatures,
 * marks, right to left) in font units; FreeType reads each glyph's
 * outline unscaled and unhinted (FT_Outline_Decompose), which becomes a
 * softrast path: FreeType rasterizes nothing, the reader's own filler
 * fills the glyphs.  Faces and decomposed outlines are kept per document
 * (svg_fonts), so a drawing of many labels matches and reads each once.
 * One document per svg_fonts; documents in other threads have their own
 * FreeType library (fontconfig's matching is thread-safe). */
#include "io/svg.h"
#include "io/svg_text.h"

#ifdef SR_HAVE_SVG_TEXT

#include <fontconfig/fontconfig.h>
#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_OUTLINE_H
#include FT_TRUETYPE_TABLES_H
#include <hb-ot.h>
#include <hb.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

bool svg_text_available(void)
{
    return true;
}

/* A glyph's outline in font units: ops 'M', 'L', 'Q' (one control
 * point), 'C' (two), each followed by its points. */
typedef struct outline {
    char *ops;
    int n_ops;
    float *xy;
    int n_xy;
} outline;

struct svg_face {
    char *family;                /* the request: family list, weight, slant ("" for a file's) */
    int weight, slant;
    char *file;                  /* the font file and its face index */
    int index;
    FcFontSet *sorted;           /* fontconfig's fallbacks for the request, on first miss */
    bool sort_tried;
    FT_Face ft;
    hb_font_t *hb;
    svg_face_metrics metrics;
    outline **glyphs;            /* by glyph id, read on first use */
    int n_glyphs;
    struct svg_face *next;
};

struct svg_fonts {
    FT_Library lib;
    svg_face *faces;
};

svg_fonts *svg_fonts_make(void)
{
    svg_fonts *f = calloc(1, sizeof *f);
    if (!f) {
        return NULL;
    }
    if (FT_Init_FreeType(&f->lib) != 0) {
        free(f);
        return NULL;
    }
    return f;
}

static void free_face(svg_face *face)
{
    for (int i = 0; i < face->n_glyphs; i++) {
        if (face->glyphs[i]) {
            free(face->glyphs[i]->ops);
            free(face->glyphs[i]->xy);
            free(face->glyphs[i]);
        }
    }
    free(face->glyphs);
    if (face->hb) {
        hb_font_destroy(face->hb);
    }
    if (face->ft) {
        FT_Done_Face(face->ft);
    }
    if (face->sorted) {
        FcFontSetDestroy(face->sorted);
    }
    free(face->family);
    free(face->file);
    free(face);
}

void svg_fonts_free(svg_fonts *fonts)
{
    if (!fonts) {
        return;
    }
    while (fonts->faces) {
        svg_face *next = fonts->faces->next;
        free_face(fonts->faces);
        fonts->faces = next;
    }
    FT_Done_FreeType(fonts->lib);
    free(fonts);
}

/* Add the families of a font-family list (names quoted or not, commas
 * between) to a pattern, in order; the initial value is serif, as in
 * browsers and rsvg-convert. */
static bool add_families(FcPattern *pat, const char *list)
{
    const char *s = list;
    int added = 0;
    while (*s) {
        while (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r' || *s == ',') {
            s++;
        }
        if (!*s) {
            break;
        }
        char name[128];
        size_t n = 0;
        if (*s == '\'' || *s == '"') {
            char q = *s++;
            while (*s && *s != q) {
                if (n + 1 < sizeof name) {
                    name[n++] = *s;
                }
                s++;
            }
            if (*s) {
                s++;
            }
        } else {
            while (*s && *s != ',') {
                if (n + 1 < sizeof name) {
                    name[n++] = *s;
                }
                s++;
            }
            while (n > 0 && (name[n - 1] == ' ' || name[n - 1] == '\t' || name[n - 1] == '\n')) {
                n--;
            }
        }
        name[n] = 0;
        if (n > 0) {
            if (!FcPatternAddString(pat, FC_FAMILY, (const FcChar8 *)name)) {
                return false;
            }
            added++;
        }
    }
    return added > 0 || FcPatternAddString(pat, FC_FAMILY, (const FcChar8 *)"serif");
}

/* The pattern of a request, configured and defaulted for matching;
 * NULL when out of memory. */
static FcPattern *request_pattern(const char *family, int weight, int slant)
{
    FcPattern *pat = FcPatternCreate();
    if (!pat || !add_families(pat, family) ||
        !FcPatternAddInteger(pat, FC_WEIGHT, FcWeightFromOpenType(weight)) ||
        !FcPatternAddInteger(pat, FC_SLANT,
                             slant == SVG_SLANT_ITALIC    ? FC_SLANT_ITALIC
                             : slant == SVG_SLANT_OBLIQUE ? FC_SLANT_OBLIQUE
                                                          : FC_SLANT_ROMAN) ||
        !FcPatternAddBool(pat, FC_OUTLINE, FcTrue)) {
        if (pat) {
            FcPatternDestroy(pat);
        }
        return NULL;
    }
    FcConfigSubstitute(NULL, pat, FcMatchPattern);
    FcDefaultSubstitute(pat);
    return pat;
}

/* The file and face index fontconfig picks; false with a line in why. */
static bool match_file(const char *family, int weight, int slant, char *file, size_t file_size,
                       int *index, char *why, size_t why_size)
{
    if (!FcInit()) {
        snprintf(why, why_size, "fontconfig cannot read its configuration");
        return false;
    }
    FcPattern *pat = request_pattern(family, weight, slant);
    if (!pat) {
        snprintf(why, why_size, "out of memory");
        return false;
    }
    FcResult res = FcResultNoMatch;
    FcPattern *got = FcFontMatch(NULL, pat, &res);
    FcPatternDestroy(pat);
    FcChar8 *path = NULL;
    bool ok = got && FcPatternGetString(got, FC_FILE, 0, &path) == FcResultMatch && path &&
              strlen((const char *)path) < file_size;
    if (ok) {
        snprintf(file, file_size, "%s", (const char *)path);
        if (FcPatternGetInteger(got, FC_INDEX, 0, index) != FcResultMatch) {
            *index = 0;
        }
    } else {
        snprintf(why, why_size, "fontconfig finds no font for font-family \"%s\"",
                 SVG_QUOTED(family));
    }
    if (got) {
        FcPatternDestroy(got);
    }
    return ok;
}

/* The vertical origin of a glyph of a font without vertical metrics:
 * the middle of its advance across, the ascender above its baseline, so
 * that upright glyphs share a baseline one ascender below the top of
 * their advance, as Chromium places them (HarfBuzz's own fallback
 * centres each glyph's ink in its advance, so that the baseline jumps
 * from glyph to glyph). */
static hb_bool_t em_box_v_origin(hb_font_t *font, void *font_data, hb_codepoint_t glyph,
                                 hb_position_t *x, hb_position_t *y, void *user_data)
{
    (void)font_data;
    (void)user_data;
    hb_font_extents_t e;
    hb_font_get_h_extents(font, &e);
    *x = hb_font_get_glyph_h_advance(font, glyph) / 2;
    *y = e.ascender;
    return true;
}

static bool has_table(hb_face_t *face, hb_tag_t tag)
{
    hb_blob_t *b = hb_face_reference_table(face, tag);
    bool has = hb_blob_get_length(b) > 0;
    hb_blob_destroy(b);
    return has;
}

/* HarfBuzz's font for face hf: its own functions throughout, but for
 * the vertical origin where the face has neither VORG nor vmtx. */
static hb_font_t *make_hb_font(hb_face_t *hf)
{
    hb_font_t *font = hb_font_create(hf);
    if (has_table(hf, HB_TAG('V', 'O', 'R', 'G')) || has_table(hf, HB_TAG('v', 'm', 't', 'x'))) {
        return font;
    }
    hb_font_t *sub = hb_font_create_sub_font(font); /* forwards what it does not set */
    hb_font_destroy(font);
    hb_font_funcs_t *funcs = hb_font_funcs_create();
    hb_font_funcs_set_glyph_v_origin_func(funcs, em_box_v_origin, NULL, NULL);
    hb_font_funcs_make_immutable(funcs);
    hb_font_set_funcs(sub, funcs, NULL, NULL);
    hb_font_funcs_destroy(funcs);
    return sub;
}

static bool open_face(svg_fonts *fonts, svg_face *face, const char *file, int index, char *why,
                      size_t why_size)
{
    face->index = index;
    if (!(face->file = strdup(file))) {
        snprintf(why, why_size, "out of memory");
        return false;
    }
    if (FT_New_Face(fonts->lib, file, index, &face->ft) != 0 || !FT_IS_SCALABLE(face->ft)) {
        snprintf(why, why_size, "%s: FreeType cannot read it as an outline font", file);
        return false;
    }
    hb_blob_t *blob = hb_blob_create_from_file(file);
    hb_face_t *hf = hb_face_create(blob, (unsigned)index);
    hb_blob_destroy(blob);
    face->hb = make_hb_font(hf);
    hb_face_destroy(hf);
    if (!face->hb || hb_face_get_glyph_count(hb_font_get_face(face->hb)) == 0) {
        snprintf(why, why_size, "%s: HarfBuzz cannot read it as a font", file);
        return false;
    }
    /* Font units throughout: HarfBuzz's scale is the em, unhinted. */
    FT_Face ft = face->ft;
    int upem = ft->units_per_EM > 0 ? ft->units_per_EM : 1000;
    hb_font_set_scale(face->hb, upem, upem);
    face->n_glyphs = (int)ft->num_glyphs;
    face->glyphs = calloc((size_t)(face->n_glyphs > 0 ? face->n_glyphs : 1), sizeof *face->glyphs);
    if (!face->glyphs) {
        snprintf(why, why_size, "out of memory");
        return false;
    }
    svg_face_metrics *m = &face->metrics;
    m->upem = upem;
    m->ascender = ft->ascender;
    m->descender = ft->descender;
    m->underline_pos = ft->underline_position;
    m->underline_thick = ft->underline_thickness > 0 ? ft->underline_thickness : upem / 14.0;
    m->x_height = upem / 2.0;
    m->strike_pos = upem / 4.0;
    m->strike_thick = m->underline_thick;
    const TT_OS2 *os2 = FT_Get_Sfnt_Table(ft, FT_SFNT_OS2);
    if (os2 && os2->version != 0xFFFF) {
        if (os2->version >= 2 && os2->sxHeight > 0) {
            m->x_height = os2->sxHeight;
        }
        if (os2->yStrikeoutSize > 0) {
            m->strike_pos = os2->yStrikeoutPosition;
            m->strike_thick = os2->yStrikeoutSize;
        }
    }
    return true;
}

svg_face *svg_fonts_match(svg_fonts *fonts, const char *family, int weight, int slant,
                          char *why, size_t why_size)
{
    for (svg_face *f = fonts->faces; f; f = f->next) {
        if (f->weight == weight && f->slant == slant && strcmp(f->family, family) == 0) {
            return f;
        }
    }
    char file[4096];
    int index = 0;
    if (!match_file(family, weight, slant, file, sizeof file, &index, why, why_size)) {
        return NULL;
    }
    svg_face *face = calloc(1, sizeof *face);
    if (!face || !(face->family = strdup(family))) {
        free(face);
        snprintf(why, why_size, "out of memory");
        return NULL;
    }
    face->weight = weight;
    face->slant = slant;
    if (!open_face(fonts, face, file, index, why, why_size)) {
        free_face(face);
        return NULL;
    }
    face->next = fonts->faces;
    fonts->faces = face;
    return face;
}

/* The face of a font file, opened once: the caller's file, or a
 * fallback fontconfig lists. */
static svg_face *face_of_file(svg_fonts *fonts, const char *file, int index, char *why,
                              size_t why_size)
{
    for (svg_face *f = fonts->faces; f; f = f->next) {
        if (f->weight == 0 && f->index == index && strcmp(f->file, file) == 0) {
            return f;
        }
    }
    svg_face *face = calloc(1, sizeof *face);
    if (!face || !(face->family = strdup(""))) {
        free(face);
        snprintf(why, why_size, "out of memory");
        return NULL;
    }
    /* weight 0 matches no request: the face is found only by its file */
    if (!open_face(fonts, face, file, index, why, why_size)) {
        free_face(face);
        return NULL;
    }
    face->next = fonts->faces;
    fonts->faces = face;
    return face;
}

svg_face *svg_fonts_open_file(svg_fonts *fonts, const char *file, char *why, size_t why_size)
{
    return face_of_file(fonts, file, 0, why, why_size);
}

/* Characters that go with the one before whatever font has them: marks,
 * joiners, variation selectors and other invisible format characters, so
 * that a cluster is not split between fonts. */
static bool follows_previous(uint32_t cp)
{
    hb_unicode_general_category_t gc =
        hb_unicode_general_category(hb_unicode_funcs_get_default(), cp);
    return gc == HB_UNICODE_GENERAL_CATEGORY_NON_SPACING_MARK ||
           gc == HB_UNICODE_GENERAL_CATEGORY_ENCLOSING_MARK ||
           gc == HB_UNICODE_GENERAL_CATEGORY_SPACING_MARK ||
           gc == HB_UNICODE_GENERAL_CATEGORY_FORMAT || (cp >= 0xFE00 && cp <= 0xFE0F) ||
           (cp >= 0xE0100 && cp <= 0xE01EF);
}

svg_face *svg_fonts_cover(svg_fonts *fonts, svg_face *face, svg_face *prev, uint32_t cp,
                          bool *missing)
{
    *missing = false;
    if (prev && follows_previous(cp)) {
        return prev;
    }
    /* controls and the space are drawn by any font, as nothing or blank */
    if (cp <= 0x20 || (cp >= 0x7F && cp <= 0xA0) || FT_Get_Char_Index(face->ft, cp) != 0) {
        return face;
    }
    if (face->weight == 0) {
        *missing = true; /* a file the caller chose: no other fonts */
        return face;
    }
    if (!face->sort_tried) {
        /* fontconfig's own order for the request: the families asked for,
         * then its fallbacks for them, each adding characters (trim) */
        face->sort_tried = true;
        FcPattern *pat = request_pattern(face->family, face->weight, face->slant);
        FcResult res = FcResultNoMatch;
        if (pat) {
            face->sorted = FcFontSort(NULL, pat, FcTrue, NULL, &res);
            FcPatternDestroy(pat);
        }
    }
    for (int i = 0; face->sorted && i < face->sorted->nfont; i++) {
        FcPattern *p = face->sorted->fonts[i];
        FcCharSet *cs = NULL;
        FcChar8 *file = NULL;
        int index = 0;
        FcBool scalable = FcTrue;
        if (FcPatternGetCharSet(p, FC_CHARSET, 0, &cs) != FcResultMatch ||
            !FcCharSetHasChar(cs, cp) ||
            FcPatternGetString(p, FC_FILE, 0, &file) != FcResultMatch ||
            (FcPatternGetBool(p, FC_OUTLINE, 0, &scalable) == FcResultMatch && !scalable)) {
            continue;
        }
        if (FcPatternGetInteger(p, FC_INDEX, 0, &index) != FcResultMatch) {
            index = 0;
        }
        if (strcmp((const char *)file, face->file) == 0 && index == face->index) {
            continue; /* fontconfig's charset and the cmap disagree */
        }
        char why[64];
        svg_face *got = face_of_file(fonts, (const char *)file, index, why, sizeof why);
        if (got && FT_Get_Char_Index(got->ft, cp) != 0) {
            return got;
        }
    }
    *missing = true;
    return face;
}

const svg_face_metrics *svg_face_get_metrics(const svg_face *face)
{
    return &face->metrics;
}

int svg_face_shape(svg_face *face, const uint32_t *cps, int n, int start, int len, int dir,
                   svg_glyph **glyphs, int *cap)
{
    hb_buffer_t *buf = hb_buffer_create();
    if (!hb_buffer_allocation_successful(buf)) {
        hb_buffer_destroy(buf);
        return -1;
    }
    hb_buffer_add_codepoints(buf, cps, n, (unsigned)start, len);
    if (dir >= 0) {
        hb_buffer_set_direction(buf, dir == 2   ? HB_DIRECTION_TTB
                                     : dir == 1 ? HB_DIRECTION_RTL
                                                : HB_DIRECTION_LTR);
    }
    hb_buffer_guess_segment_properties(buf);
    /* Vertical scripts are laid out horizontally, as SVG's initial
     * writing mode says, unless asked to stand upright. */
    if (dir != 2 && HB_DIRECTION_IS_VERTICAL(hb_buffer_get_direction(buf))) {
        hb_buffer_set_direction(buf, HB_DIRECTION_LTR);
    }
    hb_shape(face->hb, buf, NULL, 0);
    unsigned count = 0;
    const hb_glyph_info_t *info = hb_buffer_get_glyph_infos(buf, &count);
    const hb_glyph_position_t *pos = hb_buffer_get_glyph_positions(buf, NULL);
    if ((int)count > *cap) {
        svg_glyph *grown = realloc(*glyphs, count * sizeof *grown);
        if (!grown) {
            hb_buffer_destroy(buf);
            return -1;
        }
        *glyphs = grown;
        *cap = (int)count;
    }
    for (unsigned i = 0; i < count; i++) {
        (*glyphs)[i] = (svg_glyph){ info[i].codepoint, (int)info[i].cluster, pos[i].x_advance,
                                    pos[i].y_advance, pos[i].x_offset, pos[i].y_offset };
    }
    hb_buffer_destroy(buf);
    return (int)count;
}

bool svg_face_turns_vertical(svg_face *face, uint32_t cp)
{
    hb_codepoint_t nominal;
    if (!hb_font_get_nominal_glyph(face->hb, cp, &nominal)) {
        return false;
    }
    hb_buffer_t *buf = hb_buffer_create();
    if (!hb_buffer_allocation_successful(buf)) {
        hb_buffer_destroy(buf);
        return false;
    }
    hb_buffer_add_codepoints(buf, &cp, 1, 0, 1);
    hb_buffer_set_direction(buf, HB_DIRECTION_TTB);
    hb_buffer_guess_segment_properties(buf);
    /* top to bottom HarfBuzz applies vert and vrt2 */
    hb_shape(face->hb, buf, NULL, 0);
    unsigned count = 0;
    const hb_glyph_info_t *info = hb_buffer_get_glyph_infos(buf, &count);
    bool turned = count == 1 && info[0].codepoint != nominal;
    hb_buffer_destroy(buf);
    return turned;
}

/* ---- outlines ---------------------------------------------------------------- */

typedef struct sink {
    outline *o;
    int cap_ops, cap_xy;
    bool failed;
} sink;

static void put(sink *s, char op, const FT_Vector *const *p, int n)
{
    outline *o = s->o;
    if (s->failed) {
        return;
    }
    if (o->n_ops + 1 > s->cap_ops) {
        int c = s->cap_ops ? 2 * s->cap_ops : 32;
        char *g = realloc(o->ops, (size_t)c);
        if (!g) {
            s->failed = true;
            return;
        }
        o->ops = g;
        s->cap_ops = c;
    }
    if (o->n_xy + 2 * n > s->cap_xy) {
        int c = s->cap_xy ? 2 * s->cap_xy : 128;
        float *g = realloc(o->xy, (size_t)c * sizeof *g);
        if (!g) {
            s->failed = true;
            return;
        }
        o->xy = g;
        s->cap_xy = c;
    }
    o->ops[o->n_ops++] = op;
    for (int i = 0; i < n; i++) {
        o->xy[o->n_xy++] = (float)p[i]->x;
        o->xy[o->n_xy++] = (float)p[i]->y;
    }
}

static int on_move(const FT_Vector *to, void *user)
{
    put(user, 'M', (const FT_Vector *[]){ to }, 1);
    return 0;
}

static int on_line(const FT_Vector *to, void *user)
{
    put(user, 'L', (const FT_Vector *[]){ to }, 1);
    return 0;
}

static int on_conic(const FT_Vector *c, const FT_Vector *to, void *user)
{
    put(user, 'Q', (const FT_Vector *[]){ c, to }, 2);
    return 0;
}

static int on_cubic(const FT_Vector *c1, const FT_Vector *c2, const FT_Vector *to, void *user)
{
    put(user, 'C', (const FT_Vector *[]){ c1, c2, to }, 3);
    return 0;
}

/* The glyph's outline in font units, read once; NULL when out of memory. */
static outline *glyph_outline(svg_face *face, unsigned id)
{
    if (id >= (unsigned)face->n_glyphs) {
        id = 0; /* .notdef */
    }
    if (face->glyphs[id]) {
        return face->glyphs[id];
    }
    outline *o = calloc(1, sizeof *o);
    if (!o) {
        return NULL;
    }
    sink s = { .o = o };
    /* Unscaled and unhinted: the outline as designed, mapped later. */
    if (FT_Load_Glyph(face->ft, id, FT_LOAD_NO_SCALE | FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP) ==
            0 &&
        face->ft->glyph->format == FT_GLYPH_FORMAT_OUTLINE) {
        FT_Outline_Funcs funcs = { on_move, on_line, on_conic, on_cubic, 0, 0 };
        FT_Outline_Decompose(&face->ft->glyph->outline, &funcs, &s);
    }
    if (!face->metrics.oriented && o->n_ops > 0 && !s.failed) {
        /* TrueType's outer contours run clockwise (y up), CFF's the other
         * way: decorations follow, so that nonzero fills their overlaps. */
        face->metrics.clockwise =
            FT_Outline_Get_Orientation(&face->ft->glyph->outline) == FT_ORIENTATION_TRUETYPE;
        face->metrics.oriented = true;
    }
    if (s.failed) {
        free(o->ops);
        free(o->xy);
        free(o);
        return NULL;
    }
    face->glyphs[id] = o;
    return o;
}

sr_result svg_face_outline(svg_fonts *fonts, svg_face *face, unsigned id, const double m[6],
                           sr_path *path)
{
    (void)fonts;
    const outline *o = glyph_outline(face, id);
    if (!o) {
        return SR_OUT_OF_MEMORY;
    }
    const float *p = o->xy;
    double x[3], y[3];
    sr_result r = SR_OK;
    bool open = false;
    for (int i = 0; i < o->n_ops && r == SR_OK; i++) {
        int n = o->ops[i] == 'Q' ? 2 : o->ops[i] == 'C' ? 3 : 1;
        for (int k = 0; k < n; k++, p += 2) {
            x[k] = m[0] * p[0] + m[2] * p[1] + m[4];
            y[k] = m[1] * p[0] + m[3] * p[1] + m[5];
        }
        switch (o->ops[i]) {
        case 'M':
            if (open) {
                r = sr_path_close(path);
            }
            if (r == SR_OK) {
                r = sr_path_move_to(path, x[0], y[0]);
            }
            open = true;
            break;
        case 'L':
            r = sr_path_line_to(path, x[0], y[0]);
            break;
        case 'Q':
            r = sr_path_quad_to(path, x[0], y[0], x[1], y[1]);
            break;
        default:
            r = sr_path_cubic_to(path, x[0], y[0], x[1], y[1], x[2], y[2]);
            break;
        }
    }
    if (open && r == SR_OK) {
        r = sr_path_close(path);
    }
    return r;
}

#else /* no fontconfig, HarfBuzz or FreeType: text is skipped */

bool svg_text_available(void)
{
    return false;
}

void svg_fonts_free(svg_fonts *fonts)
{
    (void)fonts;
}

#endif
