/* explain_area.c - `softrast explain area`: unweighted area sampling, the
 * SR_LINE_AREA line of sr_draw_line, one pixel row at a time.  The line
 * is thickened to the rectangle of width w around the segment (with its
 * caps); a pixel's intensity is the area of its square the rectangle
 * covers.  The numbers come from sr_line_area_pixels, the code that draws
 * the line: each row's strip of the rectangle, its area A(x) left of each
 * pixel boundary, and each pixel's area A(x + 1) - A(x).  The frame
 * before the last shows every pixel's area as a fraction, the last the
 * line as sr_draw_line draws it. */
#include "explain.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CAP_ARC 16        /* chords per round end of the rectangle's outline */
#define OUTLINE_MAX (2 * (CAP_ARC + 1) + 4)

typedef struct area_row {
    int y, first, end;        /* its pixels [first, end) */
    sr_point2 *strip;
    int strip_count;
} area_row;

typedef struct area_line {
    sr_line_area_info *px;    /* strip pointers cleared: the rows keep them */
    int n, cap;
    area_row *rows;
    int row_count, row_cap;
    sr_result error;
} area_line;

static bool grow(void **p, int *cap, size_t size)
{
    int n = *cap ? 2 * *cap : 32;
    void *grown = realloc(*p, (size_t)n * size);
    if (!grown) {
        return false;
    }
    *p = grown;
    *cap = n;
    return true;
}

static void add_pixel(void *user, const sr_line_area_info *p)
{
    area_line *l = user;
    if (l->error != SR_OK) {
        return;
    }
    area_row *row = l->row_count ? &l->rows[l->row_count - 1] : NULL;
    if (!row || row->y != p->y) {
        sr_point2 *strip = malloc((size_t)p->strip_count * sizeof *strip);
        if (!strip || (l->row_count == l->row_cap &&
                       !grow((void **)&l->rows, &l->row_cap, sizeof *l->rows))) {
            free(strip);
            l->error = SR_OUT_OF_MEMORY;
            return;
        }
        memcpy(strip, p->strip, (size_t)p->strip_count * sizeof *strip);
        row = &l->rows[l->row_count++];
        *row = (area_row){ .y = p->y, .first = l->n, .end = l->n, .strip = strip,
                           .strip_count = p->strip_count };
    }
    if (l->n == l->cap && !grow((void **)&l->px, &l->cap, sizeof *l->px)) {
        l->error = SR_OUT_OF_MEMORY;
        return;
    }
    l->px[l->n] = *p;
    l->px[l->n].strip = NULL;
    l->n++;
    row->end = l->n;
}

static void free_line(area_line *l)
{
    for (int i = 0; i < l->row_count; i++) {
        free(l->rows[i].strip);
    }
    free(l->rows);
    free(l->px);
}

/* The opacity sr_draw_line blends a pixel with: its coverage in 8 bits. */
static double opacity(const sr_line_area_info *p)
{
    return (p->coverage >= 1.0f ? 255 : floor(p->coverage * 255.0f + 0.5f)) / 255.0;
}

/* An area short enough for a cell: ".42", "1", and "<.01" for a sliver
 * that would read ".00". */
static void area_text(char *buf, size_t size, double area)
{
    if (area < 0.005) {
        snprintf(buf, size, "<.01");
    } else {
        ex_weight_text(buf, size, area);
    }
}

static sr_rgba text_on(double c)
{
    return c > 0.8 ? (sr_rgba){ 1, 1, 1, 1 } : EX_TEXT;
}

/* The outline of the line's rectangle with its caps (for the eye only:
 * the areas are sr_line_area_pixels'); its point count, 0 for none. */
static int rectangle(const ex_primitive *prim, sr_point2 *pts)
{
    sr_point2 a = prim->pts[0], b = prim->pts[1];
    double h = 0.5 * prim->line_width, dx = b.x - a.x, dy = b.y - a.y, len = hypot(dx, dy);
    sr_line_cap cap = prim->line_cap;
    int n = 0;
    if (len == 0) {
        if (cap == SR_LINE_CAP_BUTT) {
            return 0;
        }
        dx = 1;   /* no direction: the square is axis-aligned */
        dy = 0;
    } else {
        dx /= len;
        dy /= len;
    }
    double nx = -dy, ny = dx, ext = cap == SR_LINE_CAP_SQUARE ? h : 0;
    for (int e = 0; e < 2; e++) {
        sr_point2 o = e ? b : a;
        double s = e ? 1 : -1;   /* outward along the line */
        double side = e ? 1 : -1;
        if (cap == SR_LINE_CAP_ROUND) {
            for (int i = 0; i <= CAP_ARC; i++) {
                double t = 3.14159265358979323846 * i / CAP_ARC, cs = cos(t), sn = sin(t);
                pts[n++] = (sr_point2){ o.x + h * (side * cs * nx + s * sn * dx),
                                        o.y + h * (side * cs * ny + s * sn * dy) };
            }
        } else {
            sr_point2 q = { o.x + s * ext * dx, o.y + s * ext * dy };
            pts[n++] = (sr_point2){ q.x + side * h * nx, q.y + side * h * ny };
            pts[n++] = (sr_point2){ q.x - side * h * nx, q.y - side * h * ny };
        }
    }
    return n;
}

static void draw_line(ex_canvas *c, const ex_primitive *prim)
{
    sr_point2 pts[OUTLINE_MAX];
    int n = rectangle(prim, pts);
    if (n) {
        ex_outline(c, pts, n, true, EX_TIE, 1.5);
    }
    ex_line_ab(c, prim->pts[0], prim->pts[1]);
}

static const char *cap_name(sr_line_cap cap)
{
    return cap == SR_LINE_CAP_SQUARE ? "square" : cap == SR_LINE_CAP_ROUND ? "round" : "butt";
}

/* Row r's frame: the rows before in their intensities, this row's strip
 * (pink) and each pixel's area A(x + 1) - A(x). */
static void row_frame(ex_canvas *c, const area_line *l, const ex_primitive *prim, int r,
                      int number)
{
    const area_row *row = &l->rows[r];
    ex_begin(c);
    for (int i = 0; i < row->end; i++) {
        if (l->px[i].drawn) {
            ex_cell(c, l->px[i].x, l->px[i].y, ex_ink_over_white(opacity(&l->px[i])));
        }
    }
    sr_rgba wash = EX_HILITE;
    wash.a = 0.3f;
    ex_fill(c, row->strip, row->strip_count, wash);
    ex_outline(c, row->strip, row->strip_count, true, EX_HILITE, 2);
    for (int i = row->first; i < row->end; i++) {
        char t[16];
        area_text(t, sizeof t, l->px[i].area);
        if (l->px[i].drawn) {
            ex_cell_text(c, l->px[i].x, l->px[i].y, t, text_on(opacity(&l->px[i])));
        }
    }
    draw_line(c, prim);
    char cap[900];
    int count = row->end - row->first;
    int len = snprintf(cap, sizeof cap, "%d. Row y = %d: the rectangle cut to the strip %d <= y "
                       "<= %d (pink), A(x) its area left of x; %d pixel%s, each covering "
                       "A(x + 1) - A(x) of its square. ", number, row->y, row->y, row->y + 1,
                       count, count == 1 ? "" : "s");
    int i = row->first;
    for (; i < row->end && len < (int)sizeof cap - 100; i++) {
        const sr_line_area_info *p = &l->px[i];
        len += snprintf(cap + len, sizeof cap - (size_t)len, "x = %d: %.3f - %.3f = %.3f%s%s",
                        p->x, p->right, p->left, p->area, p->drawn ? "" : " (not drawn)",
                        i + 1 < row->end ? "; " : ".");
    }
    if (i < row->end) {   /* a wide line's row outgrows the caption */
        snprintf(cap + len, sizeof cap - (size_t)len, "and %d more.", row->end - i);
    }
    ex_end(c, cap);
}

/* Every pixel's area as a fraction of its square, and their sum against
 * the rectangle's area. */
static void areas_frame(ex_canvas *c, const area_line *l, const ex_primitive *prim, int number)
{
    ex_begin(c);
    double sum = 0;
    int drawn = 0;
    for (int i = 0; i < l->n; i++) {
        const sr_line_area_info *p = &l->px[i];
        sum += p->area;
        if (p->drawn) {
            ex_cell(c, p->x, p->y, ex_ink_over_white(opacity(p)));
            drawn++;
        }
    }
    for (int i = 0; i < l->n; i++) {
        char t[16];
        area_text(t, sizeof t, l->px[i].area);
        if (l->px[i].drawn) {
            ex_cell_text(c, l->px[i].x, l->px[i].y, t, text_on(opacity(&l->px[i])));
        }
    }
    draw_line(c, prim);
    sr_point2 a = prim->pts[0], b = prim->pts[1];
    double w = prim->line_width, len = hypot(b.x - a.x, b.y - a.y);
    double whole = prim->line_cap == SR_LINE_CAP_ROUND    ? w * len + 3.14159265358979323846 * w * w / 4
                 : prim->line_cap == SR_LINE_CAP_SQUARE ? w * (len + w) : w * len;
    bool all = fabs(sum - whole) < 0.0005;
    const char *formula = prim->line_cap == SR_LINE_CAP_ROUND    ? "w |AB| + pi w^2/4"
                        : prim->line_cap == SR_LINE_CAP_SQUARE ? "w (|AB| + w)" : "w |AB|";
    char cap[700];
    snprintf(cap, sizeof cap,
             "%d. The areas: the fraction of each pixel's square the rectangle covers, %d "
             "pixels, exactly (the notes' count of a finer grid's subpixels inside only "
             "approximates them). Unweighted: equal areas give equal intensities wherever "
             "they lie in the pixel. They sum to %.3f px^2, the rectangle's area %s = %.3f%s.",
             number, drawn, sum, formula, whole, all ? "" : ", less what lies off the grid");
    ex_end(c, cap);
}

/* The last frame: the line as sr_draw_line draws it, ink over white, each
 * cell the colour of its pixel. */
static void final_frame(ex_canvas *c, const area_line *l, const ex_primitive *prim, int number)
{
    int drawn = ex_line_frame(c, prim->pts[0], prim->pts[1],
                              &(sr_line_desc){ .algorithm = SR_LINE_AREA,
                                               .width = prim->line_width,
                                               .cap = prim->line_cap });
    draw_line(c, prim);
    int covered = 0;
    for (int i = 0; i < l->n; i++) {
        covered += l->px[i].drawn;
    }
    char cap[500];
    int len = snprintf(cap, sizeof cap,
                       "%d. %d pixels: the line as sr_draw_line (SR_LINE_AREA) draws it, each "
                       "area the ink's opacity, blended in linear light, so a pixel half "
                       "covered is half as bright and the line's total intensity is its area, "
                       "at any slope.", number, drawn);
    if (covered > drawn) {   /* an opacity of 0 or 1 in 255 leaves white white */
        snprintf(cap + len, sizeof cap - (size_t)len, " The other %d covered pixel%s, so "
                 "slightly that the opacity is 0 or 1 in 255, stay%s white.", covered - drawn,
                 covered - drawn == 1 ? "" : "s", covered - drawn == 1 ? "s" : "");
    }
    ex_end(c, cap);
}

sr_result explain_area(ex_canvas *c, const ex_primitive *prim)
{
    area_line l = { 0 };
    sr_line_desc desc = { .algorithm = SR_LINE_AREA, .width = prim->line_width,
                          .cap = prim->line_cap };
    sr_result r = sr_line_area_pixels(c->ctx, c->grid_w, c->grid_h, prim->pts[0], prim->pts[1],
                                      &desc, add_pixel, &l);
    if (r == SR_OK && l.error != SR_OK) {
        r = l.error;
    }
    if (r != SR_OK) {
        free_line(&l);
        return c->error = r;
    }
    sr_point2 a = prim->pts[0], b = prim->pts[1];
    char cap[700];
    ex_begin(c);
    draw_line(c, prim);
    int len = snprintf(cap, sizeof cap,
                       "1. Unweighted area sampling (sr_draw_line's SR_LINE_AREA): the line "
                       "thickened to a rectangle of width %g around A-B (yellow, %s ends), and "
                       "each pixel shaded by the area of its square the rectangle covers, "
                       "from 0 to 1. A pixel it does not reach gets nothing. ",
                       prim->line_width, cap_name(prim->line_cap));
    if (a.x == b.x && a.y == b.y && prim->line_cap == SR_LINE_CAP_BUTT) {
        snprintf(cap + len, sizeof cap - (size_t)len, "A = B with butt ends: the rectangle has "
                 "no area and nothing is drawn.");
    } else {
        snprintf(cap + len, sizeof cap - (size_t)len, "The rectangle is cut into the pixel "
                 "rows' strips, %d on the grid, and each strip at the pixels' sides.",
                 l.row_count);
    }
    ex_end(c, cap);
    int number = 2;
    for (int i = 0; i < l.row_count && c->error == SR_OK; i++) {
        row_frame(c, &l, prim, i, number++);
    }
    if (l.n) {
        areas_frame(c, &l, prim, number++);
    }
    if (c->error == SR_OK) {
        final_frame(c, &l, prim, number);
    }
    free_line(&l);
    return c->error;
}
