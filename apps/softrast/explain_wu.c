/* explain_wu.c - `softrast explain wu`: Xiaolin Wu's antialiased line one
 * major step at a time, with the numbers sr_draw_line uses: the steps come
 * from sr_line_steps, the same code that draws SR_LINE_WU lines.  The line
 * is x-major when |dx| >= |dy| (else y is the major axis); per column the
 * intersection with the column's centre line falls between two pixel
 * centres, and those two pixels get 1 - f and f, f its distance past the
 * first one's centre, times the column's weight: 1, or at an end the part
 * of the column the segment covers (the gap).  The last frame is the
 * line as sr_draw_line draws it. */
#include "explain.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_STEPS 512

typedef struct wu_step {
    sr_line_step_info s;
    /* > 0: a run of this many steps with no pixel on the grid, shown as
     * one frame; s the last one */
    int run;
    int first_major;
} wu_step;

typedef struct wu_line {
    sr_point2 a, b;
    int grid_w, grid_h;
    wu_step st[MAX_STEPS];
    int n;
    int steps;                /* all the steps, runs counted one by one */
    sr_result error;
} wu_line;

static bool on_grid(const wu_line *w, int x, int y)
{
    return x >= 0 && y >= 0 && x < w->grid_w && y < w->grid_h;
}

/* Steps whose two pixels are off the grid join the run before them. */
static void add_step(void *user, const sr_line_step_info *s)
{
    wu_line *w = user;
    w->steps++;
    bool off = !on_grid(w, s->x[0], s->y[0]) && !on_grid(w, s->x[1], s->y[1]);
    wu_step *prev = w->n ? &w->st[w->n - 1] : NULL;
    if (off && prev && prev->run) {
        prev->run++;
        prev->s = *s;
        return;
    }
    if (w->n == MAX_STEPS) {
        w->error = SR_TOO_LARGE;
        return;
    }
    w->st[w->n++] = (wu_step){ .s = *s, .run = off, .first_major = s->major };
}

static sr_rgba text_on(double c)
{
    return c > 0.8 ? (sr_rgba){ 1, 1, 1, 1 } : EX_TEXT;
}

/* The pixels steps [0, upto) drew, in their weights. */
static void draw_pixels(ex_canvas *c, const wu_line *w, int upto)
{
    for (int i = 0; i < upto; i++) {
        const sr_line_step_info *s = &w->st[i].s;
        for (int k = 0; k < 2 && !w->st[i].run; k++) {
            if (s->drawn[k] && on_grid(w, s->x[k], s->y[k])) {
                ex_cell(c, s->x[k], s->y[k], ex_ink_over_white(s->coverage[k]));
            }
        }
    }
}

static void draw_line(ex_canvas *c, const wu_line *w)
{
    ex_line_ab(c, w->a, w->b);
}

static const char *axis(bool y_major, bool major)
{
    return y_major == major ? "y" : "x";
}

/* Step i's frame: the earlier pixels, this column's centre line and its
 * intersection with the line, the two pixels and their weights. */
static void step_frame(ex_canvas *c, const wu_line *w, int i, int number)
{
    const wu_step *ws = &w->st[i];
    const sr_line_step_info *s = &ws->s;
    const char *U = axis(s->y_major, true), *V = axis(s->y_major, false);
    const char *col = s->y_major ? "row" : "column";
    char cap[600];
    ex_begin(c);
    draw_pixels(c, w, i);
    if (ws->run) {
        draw_line(c, w);
        if (ws->run == 1) {
            snprintf(cap, sizeof cap, "%d. %s %s = %d: both pixels off the grid, not "
                     "shown (intersection %s = %.4f).", number, s->y_major ? "Row" : "Column", U,
                     s->major, V, s->intersection);
        } else {
            snprintf(cap, sizeof cap, "%d. %ss %s = %d to %d: %d steps whose pixels are off "
                     "the grid, not shown.", number, s->y_major ? "Row" : "Column", U,
                     ws->first_major, s->major, ws->run);
            int skipped = s->major - ws->first_major + 1 - ws->run;
            if (skipped > 0) {
                size_t len = strlen(cap);
                snprintf(cap + len, sizeof cap - len, " The %d %ss between are not visited: "
                         "they cannot reach the framebuffer (each %s is computed from the "
                         "first end, so none depends on the ones before).", skipped, col, col);
            }
        }
        ex_end(c, cap);
        return;
    }
    char wt[2][16];
    for (int k = 0; k < 2; k++) {
        ex_weight_text(wt[k], sizeof wt[k], s->coverage[k]);
        if (!on_grid(w, s->x[k], s->y[k])) {
            continue;
        }
        if (s->drawn[k]) {
            ex_cell(c, s->x[k], s->y[k], ex_ink_over_white(s->coverage[k]));
        } else {
            ex_cross(c, s->x[k], s->y[k], EX_BAD);
        }
    }
    /* the column's centre line across the grid */
    double centre = s->major + 0.5, span = s->y_major ? w->grid_w : w->grid_h;
    sr_point2 p0 = s->y_major ? (sr_point2){ 0, centre } : (sr_point2){ centre, 0 };
    sr_point2 p1 = s->y_major ? (sr_point2){ span, centre } : (sr_point2){ centre, span };
    ex_segment(c, p0, p1, EX_HILITE, 1.0);
    /* a line within one column: its intersection is taken at its middle */
    double along = !(s->first_end && s->last_end) ? centre
                   : s->y_major ? (w->a.y + w->b.y) / 2 : (w->a.x + w->b.x) / 2;
    ex_dot(c, s->y_major ? (sr_point2){ s->intersection, along }
                         : (sr_point2){ along, s->intersection }, 3.5, EX_HILITE);
    /* the weights over the marks, the line (and its labels, kept out of
     * the weights' band) over them */
    for (int k = 0; k < 2; k++) {
        if (s->drawn[k]) {
            ex_cell_text(c, s->x[k], s->y[k], wt[k], text_on(s->coverage[k]));
        }
    }
    draw_line(c, w);
    double lo = (s->y_major ? s->x[0] : s->y[0]) + 0.5;
    double f = s->intersection - lo;
    int len;
    if (s->first_end && s->last_end) {
        len = snprintf(cap, sizeof cap,
                       "%d. The whole line lies in %s %s = %d: its weight is its length "
                       "along %s, %.4f, and the intersection %s = %.4f is taken at the line's "
                       "middle. ", number, col, U, s->major, U, s->weight, V, s->intersection);
    } else if (s->first_end || s->last_end) {
        len = snprintf(cap, sizeof cap,
                       "%d. %s end, %s %s = %d: the line covers %.4f of the %s (the "
                       "gap), so both weights are scaled by it. At the centre %s = %d.5 the "
                       "line is at %s = %.4f. ", number, s->first_end ? "First" : "Last", col,
                       U, s->major, s->weight, col, U, s->major, V, s->intersection);
    } else {
        len = snprintf(cap, sizeof cap,
                       "%d. %s %s = %d: intersection %s = %.4f at the centre %s = %d.5 (the "
                       "previous one + gradient %.4f). ", number, s->y_major ? "Row" : "Column", U, s->major, V,
                       s->intersection, U, s->major, s->gradient);
    }
    snprintf(cap + len, sizeof cap - (size_t)len,
             "It lies between the centres %s = %.1f and %.1f, f = %.4f past the first: (%d, %d) "
             "gets %s(1 - f) = %.4f%s, (%d, %d) gets %sf = %.4f%s.", V, lo, lo + 1, f, s->x[0],
             s->y[0], s->weight < 1 ? "gap x " : "", s->coverage[0],
             s->drawn[0] ? "" : " (not drawn)", s->x[1], s->y[1],
             s->weight < 1 ? "gap x " : "", s->coverage[1], s->drawn[1] ? "" : " (not drawn)");
    ex_end(c, cap);
}

/* The last frame: the line as sr_draw_line draws it, ink over white, each
 * cell the colour of its pixel. */
static void final_frame(ex_canvas *c, const wu_line *w, int number)
{
    int drawn = ex_line_frame(c, w->a, w->b, &(sr_line_desc){ .algorithm = SR_LINE_WU });
    draw_line(c, w);
    char cap[400];
    snprintf(cap, sizeof cap,
             "%d. %d pixels: the line as sr_draw_line (SR_LINE_WU) draws it, each weight the "
             "ink's opacity, blended in linear light. A column's two weights sum to its "
             "weight, so the line's total intensity is its extent along the major axis.",
             number, drawn);
    ex_end(c, cap);
}

sr_result explain_wu(ex_canvas *c, const ex_primitive *prim)
{
    wu_line *w = calloc(1, sizeof *w);
    if (!w) {
        return c->error = SR_OUT_OF_MEMORY;
    }
    w->a = prim->pts[0];
    w->b = prim->pts[1];
    w->grid_w = c->grid_w;
    w->grid_h = c->grid_h;
    sr_result r = sr_line_steps(c->ctx, c->grid_w, c->grid_h, w->a, w->b,
                                &(sr_line_desc){ .algorithm = SR_LINE_WU }, add_step, w);
    if (r == SR_OK && w->error != SR_OK) {
        r = w->error;
    }
    if (r != SR_OK) {
        free(w);
        return c->error = r;
    }
    double dx = w->b.x - w->a.x, dy = w->b.y - w->a.y;
    bool y_major = fabs(dy) > fabs(dx);
    const char *U = axis(y_major, true), *V = axis(y_major, false);
    const char *col = y_major ? "row" : "column";
    char cap[600];
    ex_begin(c);
    draw_line(c, w);
    if (dx == 0 && dy == 0) {
        snprintf(cap, sizeof cap, "1. Xiaolin Wu's line: A = B, the line has no length and "
                 "nothing is drawn.");
    } else {
        double g = y_major ? dx / dy : dy / dx;
        snprintf(cap, sizeof cap,
                 "1. Xiaolin Wu's antialiased line, %s-major (|d%s| %s |d%s|): one step per %s, "
                 "from the smaller %s. Gradient d%s/d%s = %.4f. In each %s the line crosses "
                 "the centre line between two pixel centres; each of the two pixels gets a "
                 "weight by its closeness, 1 - f and f. The end %ss are weighted by the part "
                 "of the %s the line covers (the gap).",
                 U, U, y_major ? ">" : ">=", V, col, U, V, U, g, col, col, col);
    }
    ex_end(c, cap);
    int number = 2;
    for (int i = 0; i < w->n && c->error == SR_OK; i++) {
        step_frame(c, w, i, number++);
    }
    if (c->error == SR_OK) {
        final_frame(c, w, number);
    }
    free(w);
    return c->error;
}
