/* view_font.c - overlay text for `softrast view`: TrueType outlines read by
 * FreeType (FT_Outline_Decompose) become softrast paths, filled by
 * softrast's own antialiased nonzero polygon filler (exact-area coverage,
 * sr_polygon_coverage) into a coverage mask per character, which is kept
 * and blended into the frame with sr_draw_coverage.  FreeType only reads
 * the font; it rasterizes nothing.  Used by the render thread only. */
#ifdef SR_HAVE_VIEWER
#include "view.h"

#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_OUTLINE_H

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define CACHE_CODEPOINTS 0x2600   /* Latin, Greek, arrows, math, box drawing */

typedef struct glyph {
    int left, top;        /* mask's top-left corner relative to pen and baseline */
    int w, h;
    int advance;          /* whole pixels: pens stay on pixels, so masks can be reused */
    uint8_t *mask;        /* w x h coverage, or NULL for blank glyphs */
} glyph;

struct view_font {
    FT_Library lib;
    FT_Face face;
    int ascent, line_height;
    glyph *cache[CACHE_CODEPOINTS];
    int cached;
};

bool view_font_open(const char *path, int pixel_size, view_font **out, char *why, size_t size)
{
    *out = NULL;
    if (access(path, R_OK) != 0) {
        snprintf(why, size, "%s: %s", path, strerror(errno));
        return false;
    }
    view_font *f = calloc(1, sizeof *f);
    if (!f) {
        snprintf(why, size, "out of memory");
        return false;
    }
    FT_Error e = FT_Init_FreeType(&f->lib);
    if (!e) {
        e = FT_New_Face(f->lib, path, 0, &f->face);
        if (e) {
            snprintf(why, size, "%s: FreeType cannot read it as a font (error %d)", path, e);
            FT_Done_FreeType(f->lib);
            free(f);
            return false;
        }
        e = FT_Set_Pixel_Sizes(f->face, 0, (FT_UInt)pixel_size);
    }
    if (e || !FT_IS_SCALABLE(f->face)) {
        snprintf(why, size, "%s: not a scalable (outline) font", path);
        view_font_close(f);
        return false;
    }
    f->ascent = (int)((f->face->size->metrics.ascender + 63) >> 6);
    f->line_height = (int)((f->face->size->metrics.height + 63) >> 6);
    *out = f;
    return true;
}

void view_font_close(view_font *f)
{
    if (!f) {
        return;
    }
    for (int i = 0; i < CACHE_CODEPOINTS; i++) {
        if (f->cache[i]) {
            free(f->cache[i]->mask);
            free(f->cache[i]);
        }
    }
    if (f->face) {
        FT_Done_Face(f->face);
    }
    if (f->lib) {
        FT_Done_FreeType(f->lib);
    }
    free(f);
}

int view_font_line_height(const view_font *f)
{
    return f->line_height;
}

int view_font_ascent(const view_font *f)
{
    return f->ascent;
}

int view_font_cached(const view_font *f)
{
    return f->cached;
}

/* ---- outline -> path ------------------------------------------------------ */

/* FreeType gives 26.6 coordinates with y up; the path wants pixels with y
 * down, relative to the mask's top-left corner (ox, oy in 26.6). */
typedef struct outline_sink {
    sr_path *path;
    FT_Pos ox, oy;
    sr_result r;
} outline_sink;

static double px_x(const outline_sink *s, FT_Pos x)
{
    return (double)(x - s->ox) / 64.0;
}

static double px_y(const outline_sink *s, FT_Pos y)
{
    return (double)(s->oy - y) / 64.0;
}

static int on_move(const FT_Vector *to, void *user)
{
    outline_sink *s = user;
    if (s->r == SR_OK) {
        s->r = sr_path_move_to(s->path, px_x(s, to->x), px_y(s, to->y));
    }
    return 0;
}

static int on_line(const FT_Vector *to, void *user)
{
    outline_sink *s = user;
    if (s->r == SR_OK) {
        s->r = sr_path_line_to(s->path, px_x(s, to->x), px_y(s, to->y));
    }
    return 0;
}

static int on_conic(const FT_Vector *c, const FT_Vector *to, void *user)
{
    outline_sink *s = user;
    if (s->r == SR_OK) {
        s->r = sr_path_quad_to(s->path, px_x(s, c->x), px_y(s, c->y), px_x(s, to->x),
                               px_y(s, to->y));
    }
    return 0;
}

static int on_cubic(const FT_Vector *c1, const FT_Vector *c2, const FT_Vector *to, void *user)
{
    outline_sink *s = user;
    if (s->r == SR_OK) {
        s->r = sr_path_cubic_to(s->path, px_x(s, c1->x), px_y(s, c1->y), px_x(s, c2->x),
                                px_y(s, c2->y), px_x(s, to->x), px_y(s, to->y));
    }
    return 0;
}

/* Rasterize one character's outline into a coverage mask. */
static glyph *make_glyph(view_font *f, sr_context *ctx, unsigned cp)
{
    glyph *g = calloc(1, sizeof *g);
    if (!g) {
        return NULL;
    }
    /* Light hinting aligns stems vertically only, keeping shapes true;
     * NO_BITMAP: always the outline, never an embedded bitmap strike. */
    if (FT_Load_Char(f->face, cp, FT_LOAD_NO_BITMAP | FT_LOAD_TARGET_LIGHT) != 0 ||
        f->face->glyph->format != FT_GLYPH_FORMAT_OUTLINE) {
        return g;   /* blank */
    }
    FT_GlyphSlot slot = f->face->glyph;
    g->advance = (int)((slot->advance.x + 32) >> 6);
    FT_BBox box;
    FT_Outline_Get_CBox(&slot->outline, &box);
    FT_Pos x0 = box.xMin & ~63, y0 = box.yMin & ~63;
    FT_Pos x1 = (box.xMax + 63) & ~63, y1 = (box.yMax + 63) & ~63;
    if (slot->outline.n_contours == 0 || x1 <= x0 || y1 <= y0) {
        return g;
    }
    g->left = (int)(x0 >> 6);
    g->top = (int)(-(y1 >> 6));
    g->w = (int)((x1 - x0) >> 6);
    g->h = (int)((y1 - y0) >> 6);
    sr_path *path = NULL;
    if (sr_make_path(ctx, 0.05, &path) != SR_OK) {
        return g;
    }
    outline_sink sink = { path, x0, y1, SR_OK };
    FT_Outline_Funcs funcs = { on_move, on_line, on_conic, on_cubic, 0, 0 };
    FT_Outline_Decompose(&slot->outline, &funcs, &sink);
    g->mask = malloc((size_t)g->w * (size_t)g->h);
    if (sink.r != SR_OK || !g->mask) {
        free(g->mask);
        g->mask = NULL;
    } else {
        sr_polygon2 poly = sr_path_polygon(path);
        sr_fill_desc fill = { .rule = SR_NONZERO, .antialias = SR_AA_AREA };
        if (sr_polygon_coverage(ctx, &poly, &fill, 0, 0, g->w, g->h, g->mask,
                                (size_t)g->w) != SR_OK) {
            free(g->mask);
            g->mask = NULL;
        }
    }
    sr_destroy_path(ctx, path);
    return g;
}

static const glyph *get_glyph(view_font *f, sr_context *ctx, unsigned cp)
{
    if (cp >= CACHE_CODEPOINTS) {
        cp = '?';
    }
    if (!f->cache[cp]) {
        f->cache[cp] = make_glyph(f, ctx, cp);
        f->cached += f->cache[cp] != NULL;
    }
    return f->cache[cp];
}

/* Next code point of UTF-8 text; malformed bytes read as '?'. */
static unsigned next_cp(const char **p)
{
    const unsigned char *s = (const unsigned char *)*p;
    unsigned c = s[0];
    int n = c < 0x80 ? 0 : (c & 0xe0) == 0xc0 ? 1 : (c & 0xf0) == 0xe0 ? 2 : (c & 0xf8) == 0xf0 ? 3 : -1;
    if (n < 0) {
        *p += 1;
        return '?';
    }
    unsigned cp = n == 0 ? c : c & (0x3fu >> n);
    for (int i = 1; i <= n; i++) {
        if ((s[i] & 0xc0) != 0x80) {
            *p += i;
            return '?';
        }
        cp = cp << 6 | (s[i] & 0x3f);
    }
    *p += n + 1;
    return cp;
}

int view_font_width(view_font *f, sr_context *ctx, const char *text)
{
    int w = 0;
    for (const char *p = text; *p;) {
        const glyph *g = get_glyph(f, ctx, next_cp(&p));
        w += g ? g->advance : 0;
    }
    return w;
}

sr_result view_font_draw(view_font *f, sr_context *ctx, sr_framebuffer *fb, int x, int y,
                         const char *text, sr_rgba color)
{
    int pen = x;
    for (const char *p = text; *p;) {
        const glyph *g = get_glyph(f, ctx, next_cp(&p));
        if (!g) {
            return SR_OUT_OF_MEMORY;
        }
        if (g->mask) {
            sr_result r = sr_draw_coverage(ctx, fb, pen + g->left, y + g->top, g->w, g->h,
                                           g->mask, (size_t)g->w, color);
            if (r != SR_OK) {
                return r;
            }
        }
        pen += g->advance;
    }
    return SR_OK;
}
#endif /* SR_HAVE_VIEWER */
