/* explain_aaline.c - `softrast explain aaline`: softrast's own antialiased
 * line, the 3D pipeline's smooth lines (sr_state.smooth_lines), one
 * major-axis column at a time.  The pixels and numbers come from
 * sr_smooth_line_pixels, the walk the rasterizer shades: every pixel
 * whose centre lies within the reach (half the width plus half a pixel)
 * of the segment, its coverage the reach less that distance, at most 1 -
 * a one-pixel ramp across the edge, round ends where the nearest point is
 * an end.  The width is --width's.  The last frame is every pixel with its
 * coverage as the ink's alpha over white, as sr_draw blends it. */
#include "explain.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CAPSULE_ARC 12   /* chords per round end of the reach's outline */

typedef struct aa_line {
    sr_point2 a, b;           /* snapped to 1/256 px, as sr_draw snaps them */
    sr_line_pixel_info *px;
    int n, cap;
    sr_result error;
} aa_line;

static void add_pixel(void *user, const sr_line_pixel_info *p)
{
    aa_line *l = user;
    if (l->n == l->cap) {
        int cap = l->cap ? 2 * l->cap : 64;
        sr_line_pixel_info *grown = realloc(l->px, (size_t)cap * sizeof *grown);
        if (!grown) {
            l->error = SR_OUT_OF_MEMORY;
            return;
        }
        l->px = grown;
        l->cap = cap;
    }
    l->px[l->n++] = *p;
}

/* The ink over white with alpha c, per 8-bit channel: sr_draw's blend. */
static sr_rgba coverage_colour(double c)
{
    const float ink[3] = { EX_INK.r, EX_INK.g, EX_INK.b };
    float out[3];
    for (int i = 0; i < 3; i++) {
        double v = ink[i] * c + (1.0 - c);
        out[i] = (float)floor(v * 255.0 + 0.5) / 255.0f;
    }
    return (sr_rgba){ out[0], out[1], out[2], 1 };
}

/* The outline of the points within `reach` of the segment: two sides and
 * two half circles. */
static void draw_reach(ex_canvas *c, const aa_line *l, double reach)
{
    double dx = l->b.x - l->a.x, dy = l->b.y - l->a.y, len = hypot(dx, dy);
    if (len == 0) {
        return;
    }
    double ux = dx / len, uy = dy / len, nx = -uy, ny = ux;
    sr_point2 pts[2 * (CAPSULE_ARC + 1)];
    int n = 0;
    for (int e = 0; e < 2; e++) {
        sr_point2 o = e ? l->b : l->a;
        double sx = e ? 1 : -1;   /* the half circle bulges away from the segment */
        for (int i = 0; i <= CAPSULE_ARC; i++) {
            double t = 3.14159265358979323846 * i / CAPSULE_ARC;
            double cs = cos(t), sn = sin(t);
            /* from +n (e = 1: -n) round through the end's outward direction */
            double px = (e ? -nx : nx) * cs + sx * ux * sn, py = (e ? -ny : ny) * cs + sx * uy * sn;
            pts[n++] = (sr_point2){ o.x + reach * px, o.y + reach * py };
        }
    }
    ex_outline(c, pts, n, true, EX_TIE, 1.5);
}

static void draw_line(ex_canvas *c, const aa_line *l, double reach)
{
    draw_reach(c, l, reach);
    ex_line_ab(c, l->a, l->b);
}

static sr_point2 nearest(const aa_line *l, double t)
{
    return (sr_point2){ l->a.x + t * (l->b.x - l->a.x), l->a.y + t * (l->b.y - l->a.y) };
}

/* The frame of the column holding pixels [first, end). */
static void column_frame(ex_canvas *c, const aa_line *l, int first, int end, int number)
{
    const sr_line_pixel_info *p0 = &l->px[first];
    const char *U = p0->y_major ? "y" : "x", *V = p0->y_major ? "x" : "y";
    ex_begin(c);
    for (int i = 0; i < end; i++) {
        ex_cell(c, l->px[i].x, l->px[i].y, coverage_colour(l->px[i].coverage));
    }
    for (int i = first; i < end; i++) {
        const sr_line_pixel_info *p = &l->px[i];
        sr_point2 centre = { p->x + 0.5, p->y + 0.5 };
        ex_segment(c, centre, nearest(l, p->t), EX_HILITE, 1.0);
        ex_dot(c, centre, 2.5, EX_HILITE);
    }
    for (int i = first; i < end; i++) {
        char t[16];
        ex_weight_text(t, sizeof t, l->px[i].coverage);
        ex_cell_text(c, l->px[i].x, l->px[i].y, t,
                     l->px[i].coverage > 0.8 ? (sr_rgba){ 1, 1, 1, 1 } : EX_TEXT);
    }
    draw_line(c, l, p0->reach);
    char cap[900];
    int len = snprintf(cap, sizeof cap, "%d. %s %s = %d: %d pixel%s within the reach %g, coverage = reach - d. ", number,
                       p0->y_major ? "Row" : "Column", U, p0->major, end - first,
                       end - first == 1 ? "" : "s", p0->reach);
    int i = first;
    for (; i < end && len < (int)sizeof cap - 80; i++) {
        const sr_line_pixel_info *p = &l->px[i];
        const char *where = p->t <= 0 ? " (end A)" : p->t >= 1 ? " (end B)" : "";
        len += snprintf(cap + len, sizeof cap - (size_t)len, "%s = %d: d = %.3f%s, coverage %.3f%s%s",
                        V, p0->y_major ? p->x : p->y, p->distance, where, p->reach - p->distance,
                        p->reach - p->distance > 1 ? " -> 1" : "", i + 1 < end ? "; " : ".");
    }
    if (i < end) {   /* a wide line's column outgrows the caption */
        snprintf(cap + len, sizeof cap - (size_t)len, "and %d more.", end - i);
    }
    ex_end(c, cap);
}

sr_result explain_aaline(ex_canvas *c, const ex_primitive *prim)
{
    aa_line l = { 0 };
    for (int i = 0; i < 2; i++) {
        sr_point2 p = prim->pts[i];
        sr_point2 q = { ex_snap(p.x) / 256.0, ex_snap(p.y) / 256.0 };
        *(i ? &l.b : &l.a) = q;
    }
    sr_result r = sr_smooth_line_pixels(c->ctx, c->grid_w, c->grid_h, prim->pts[0],
                                        prim->pts[1], prim->line_width, add_pixel, &l);
    if (r == SR_OK && l.error != SR_OK) {
        r = l.error;
    }
    if (r != SR_OK) {
        free(l.px);
        return c->error = r;
    }
    /* half the width as sr_draw takes it: sr_state.line_width is a float */
    double reach = (double)(float)((double)(float)prim->line_width * 0.5) + 0.5;
    double dx = l.b.x - l.a.x, dy = l.b.y - l.a.y;
    bool y_major = fabs(dy) > fabs(dx);
    char cap[600];
    ex_begin(c);
    draw_line(c, &l, reach);
    if (dx == 0 && dy == 0) {
        snprintf(cap, sizeof cap, "1. softrast's antialiased line: A = B, the line has no "
                 "length and nothing is drawn.");
    } else {
        snprintf(cap, sizeof cap,
                 "1. softrast's antialiased line (sr_draw's smooth lines), width %g: a pixel "
                 "whose centre lies within the reach w/2 + 1/2 = %g of the segment (yellow) "
                 "gets the coverage reach - d, d the distance from its centre to the nearest "
                 "point of the segment, at most 1: a one-pixel ramp across each edge, round "
                 "past the ends. %s-major: walked %s by %s.", prim->line_width, reach,
                 y_major ? "y" : "x", y_major ? "row" : "column", y_major ? "row" : "column");
    }
    ex_end(c, cap);
    int number = 2;
    for (int i = 0; i < l.n && c->error == SR_OK;) {
        int end = i + 1;
        while (end < l.n && l.px[end].major == l.px[i].major) {
            end++;
        }
        column_frame(c, &l, i, end, number++);
        i = end;
    }
    ex_begin(c);
    for (int i = 0; i < l.n; i++) {
        ex_cell(c, l.px[i].x, l.px[i].y, coverage_colour(l.px[i].coverage));
    }
    draw_line(c, &l, reach);
    snprintf(cap, sizeof cap,
             "%d. %d pixels: the line as sr_draw draws it with smooth_lines, each coverage the "
             "alpha of the ink blended over the background. Depth is written only where the "
             "coverage is 1.", number, l.n);
    ex_end(c, cap);
    free(l.px);
    return c->error;
}
