/* explain_line.c - `softrast explain bresenham` and `softrast explain dda`:
 * a line one major step at a time, as sr_draw_line draws it.  The line is
 * x-major when |dx| >= |dy| (else the roles of x and y swap: u is the
 * major axis, v the minor); each step plots one pixel.
 *   bresenham: the midpoint algorithm with endpoints on pixel centres.
 *     The decision variable d = 2 F(M), F the line's implicit equation at
 *     the midpoint M between the two candidate pixels, starts at
 *     2dv - du and grows by 2dv (step E, minor index kept) or 2(dv - du)
 *     (step NE, minor index +1); a tie (d = 0, M on the line) goes to the
 *     smaller minor index.  The end pixel is left out, so lines joined end
 *     to end draw the shared pixel once.
 *   dda: the incremental DDA: v at the first pixel centre on the major
 *     axis, then v += m per step (in fixed point with 32 fraction bits, as
 *     the library keeps it), the pixel being the one whose centre is
 *     nearest, floor(v).  Columns whose centres lie in [start, end) along
 *     the direction of travel are drawn. */
#include "explain.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

__extension__ typedef __int128 i128;

#define MAX_STEPS 512

typedef struct step {
    int x, y;
    bool drawn;             /* false: bresenham's end pixel, shown left out */
    bool has_mid;
    sr_point2 mid;          /* bresenham: the midpoint tested */
    /* > 0: a run of this many steps whose pixels are off the grid, shown
     * as one frame; x, y the last one's pixel */
    int run;
    int first, first_x, first_y;      /* the run's first step: its number, pixel */
    char first_value[48], last_value[48];   /* the value the steps' captions give */
    char caption[320];
} step;

typedef struct line_steps {
    sr_point2 a, b;         /* snapped */
    int grid_w, grid_h;
    step s[MAX_STEPS];      /* the on-grid steps of a line and at most two runs */
    int n;
    char intro[640], outro[320];
} line_steps;

static i128 floor_div128(i128 a, i128 b)
{
    i128 q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}

static i128 round_div128(i128 a, i128 b)
{
    if (b < 0) {
        a = -a;
        b = -b;
    }
    return floor_div128(2 * a + b, 2 * b);
}

static bool on_centre(int64_t q8)
{
    return ((q8 - 128) % 256 + 256) % 256 == 0;
}

/* The entry for step `number` (from 1) at pixel (x, y), whose caption
 * gives `value`; NULL when the pixel is off the grid: the step joins the
 * run of such steps before it, or starts one.  A line's pixels on the grid
 * are consecutive steps, so a line has at most a run before and one after
 * them, and its entries stay few however far its ends are. */
static step *add_step(line_steps *ls, int x, int y, int number, const char *value)
{
    bool off = x < 0 || y < 0 || x >= ls->grid_w || y >= ls->grid_h;
    step *prev = ls->n ? &ls->s[ls->n - 1] : NULL;
    if (off && prev && prev->run) {
        prev->run++;
        prev->x = x;
        prev->y = y;
        snprintf(prev->last_value, sizeof prev->last_value, "%s", value);
        return NULL;
    }
    if (ls->n == MAX_STEPS) {
        return NULL;
    }
    step *st = &ls->s[ls->n++];
    *st = (step){ .x = x, .y = y, .drawn = true };
    if (!off) {
        return st;
    }
    *st = (step){ .x = x, .y = y, .run = 1, .first = number, .first_x = x, .first_y = y };
    snprintf(st->first_value, sizeof st->first_value, "%s", value);
    snprintf(st->last_value, sizeof st->last_value, "%s", value);
    return NULL;
}

static const char *axis(bool xmaj, bool major)
{
    return xmaj == major ? "x" : "y";
}

bool ex_line_on_centres(const ex_primitive *prim)
{
    for (int i = 0; i < 2; i++) {
        if (!on_centre(ex_snap(prim->pts[i].x)) || !on_centre(ex_snap(prim->pts[i].y))) {
            return false;
        }
    }
    return true;
}

/* The midpoint algorithm on centre endpoints; false when an endpoint is
 * not on a pixel centre. */
static bool bresenham(line_steps *ls, int64_t ax, int64_t ay, int64_t bx, int64_t by)
{
    if (!on_centre(ax) || !on_centre(ay) || !on_centre(bx) || !on_centre(by)) {
        return false;
    }
    bool xmaj = llabs(bx - ax) >= llabs(by - ay);
    int64_t u0 = ((xmaj ? ax : ay) - 128) / 256, v0 = ((xmaj ? ay : ax) - 128) / 256;
    int64_t u1 = ((xmaj ? bx : by) - 128) / 256, v1 = ((xmaj ? by : bx) - 128) / 256;
    int64_t end_k = u1;
    bool reversed = u0 > u1;
    if (reversed) {   /* walk with the major coordinate increasing */
        int64_t t = u0; u0 = u1; u1 = t;
        t = v0; v0 = v1; v1 = t;
    }
    int64_t du = u1 - u0, dv = llabs(v1 - v0), s = v1 < v0 ? -1 : 1;
    int64_t d = 2 * dv - du, dE = 2 * dv, dNE = 2 * (dv - du), i = 0;
    const char *U = axis(xmaj, true), *V = axis(xmaj, false);
    snprintf(ls->intro, sizeof ls->intro,
             "1. Bresenham (midpoint) line, %s-major: d%s = %lld, d%s = %lld%s. Decision "
             "variable d = 2F(M) at the midpoint M between the two candidates: "
             "d0 = 2d%s - d%s = %lld; step E (%s+1) adds 2d%s = %lld, step NE (%s+1, %s%s1) "
             "adds 2(d%s - d%s) = %lld. Integers only.",
             U, U, (long long)du, V, (long long)dv, s < 0 ? " (minor axis mirrored)" : "",
             V, U, (long long)d, U, V, (long long)dE, U, V, s > 0 ? "+" : "-", V, U,
             (long long)dNE);
    if (reversed) {
        size_t len = strlen(ls->intro);
        snprintf(ls->intro + len, sizeof ls->intro - len,
                 " Walked from the end, so %s increases.", U);
    }
    ls->n = 0;
    for (int64_t k = u0; k <= u1; k++) {
        int64_t j = v0 + s * i;
        bool ne = s > 0 ? d > 0 : d >= 0;
        char value[48];
        snprintf(value, sizeof value, "d = %lld", (long long)d);
        step *st = add_step(ls, (int)(xmaj ? k : j), (int)(xmaj ? j : k), (int)(k - u0 + 1),
                            value);
        if (!st) {
            d += ne ? dNE : dE;
            i += ne ? 1 : 0;
            continue;
        }
        double mu = k + 1 + 0.5, mv = j + 0.5 + s * 0.5;   /* M, between the candidates */
        st->has_mid = k < u1;
        st->mid = xmaj ? (sr_point2){ mu, mv } : (sr_point2){ mv, mu };
        int len = snprintf(st->caption, sizeof st->caption, "Plot (%d, %d)%s. ", st->x, st->y,
                           k == end_k ? " - no: the end pixel is left out" : "");
        if (k < u1) {
            snprintf(st->caption + len, sizeof st->caption - (size_t)len,
                     "d = %lld%s: step %s, d %s %lld = %lld.", (long long)d,
                     d > 0 ? " > 0" : d < 0 ? " < 0" : " (M on the line: the smaller index)",
                     ne ? "NE" : "E",
                     ne ? (dNE < 0 ? "-" : "+") : "+", (long long)llabs(ne ? dNE : dE),
                     (long long)(d + (ne ? dNE : dE)));
        }
        st->drawn = k != end_k;
        if (ne) {
            i++;
            d += dNE;
        } else {
            d += dE;
        }
    }
    snprintf(ls->outro, sizeof ls->outro,
             "sr_draw_line (SR_LINE_BRESENHAM) draws exactly these pixels: one per %s "
             "column, the end pixel left out.", U);
    return true;
}

static void dda(line_steps *ls, int64_t ax, int64_t ay, int64_t bx, int64_t by)
{
    bool xmaj = llabs(bx - ax) >= llabs(by - ay);
    int64_t au = xmaj ? ax : ay, av = xmaj ? ay : ax, bu = xmaj ? bx : by, bv = xmaj ? by : bx;
    int64_t du = bu - au, dv = bv - av;
    ls->n = 0;
    const char *U = axis(xmaj, true), *V = axis(xmaj, false);
    if (du == 0) {
        snprintf(ls->intro, sizeof ls->intro, "1. The line has no length: nothing is drawn.");
        ls->outro[0] = 0;
        return;
    }
    /* centres c = 256k + 128 with a_u <= c < b_u along the travel */
    int64_t k0, k1, dir = du > 0 ? 1 : -1;
    if (du > 0) {
        k0 = (int64_t)-floor_div128(-(i128)(au - 128), 256);
        k1 = (int64_t)-floor_div128(-(i128)(bu - 128), 256) - 1;
    } else {
        k0 = (int64_t)floor_div128(au - 128, 256);
        k1 = (int64_t)floor_div128(bu - 128, 256) + 1;
    }
    i128 inc = round_div128((i128)dv * ((i128)1 << 32), du > 0 ? du : -du);
    i128 v = (i128)av * (1 << 24) + round_div128((i128)(k0 * 256 + 128 - au) * dv * (1 << 24), du);
    const double one = 4294967296.0;
    snprintf(ls->intro, sizeof ls->intro,
             "1. DDA line, %s-major, stepping %s by %s1: m = d%s/|d%s| = %.4f per step. The "
             "line's %s at the first pixel centre %s = %.1f is %.4f; then %s += m each step, "
             "the pixel being the nearest centre: floor(%s) (centres at +1/2). Drawn: centres "
             "from the start up to, not at, the end.",
             U, U, dir > 0 ? "+" : "-", V, U, (double)inc / one, V, U, (double)k0 + 0.5,
             (double)v / one, V, V);
    int number = 0;
    for (int64_t k = k0; dir > 0 ? k <= k1 : k >= k1; k += dir) {
        int64_t j = (int64_t)floor_div128(v, (i128)1 << 32);
        double vc = (double)v / one;
        char value[48];
        snprintf(value, sizeof value, "%s = %.4f", V, vc);
        step *st = add_step(ls, (int)(xmaj ? k : j), (int)(xmaj ? j : k), ++number, value);
        if (!st) {
            v += inc;
            continue;
        }
        st->has_mid = true;
        st->mid = xmaj ? (sr_point2){ k + 0.5, vc } : (sr_point2){ vc, k + 0.5 };
        snprintf(st->caption, sizeof st->caption,
                 "%s = %lld.5: %s = %.4f, floor -> plot (%d, %d). Next %s = %.4f.", U,
                 (long long)k, V, vc, st->x, st->y, V, (double)(v + inc) / one);
        v += inc;   /* per step of travel, whichever way u goes */
    }
    snprintf(ls->outro, sizeof ls->outro,
             "sr_draw_line (SR_LINE_DDA_INCREMENTAL) draws exactly these pixels: one per %s "
             "column.", U);
}

static void draw_line(ex_canvas *c, const line_steps *ls)
{
    ex_line_ab(c, ls->a, ls->b);
}

static bool in_grid(const ex_canvas *c, int x, int y)
{
    return x >= 0 && y >= 0 && x < c->grid_w && y < c->grid_h;
}

static sr_result frames(ex_canvas *c, line_steps *ls)
{
    ex_begin(c);
    draw_line(c, ls);
    ex_end(c, ls->intro);
    for (int i = 0; i < ls->n && c->error == SR_OK; i++) {
        ex_begin(c);
        for (int k = 0; k < i; k++) {
            if (ls->s[k].drawn && in_grid(c, ls->s[k].x, ls->s[k].y)) {
                ex_cell(c, ls->s[k].x, ls->s[k].y, EX_INK);
            }
        }
        const step *st = &ls->s[i];
        char cap[400];
        if (st->run) {
            draw_line(c, ls);
            if (st->run == 1) {
                snprintf(cap, sizeof cap, "%d. Step %d: pixel (%d, %d) off the grid, not shown "
                         "(%s).", i + 2, st->first, st->x, st->y, st->first_value);
            } else {
                snprintf(cap, sizeof cap, "%d. Steps %d to %d: pixels (%d, %d) to (%d, %d) off "
                         "the grid, not shown (%s first, %s last).", i + 2, st->first,
                         st->first + st->run - 1, st->first_x, st->first_y, st->x, st->y,
                         st->first_value, st->last_value);
            }
            ex_end(c, cap);
            continue;
        }
        if (st->drawn && in_grid(c, st->x, st->y)) {
            ex_cell(c, st->x, st->y, EX_CELL_IN);
        }
        draw_line(c, ls);
        if (!st->drawn && in_grid(c, st->x, st->y)) {
            ex_cross(c, st->x, st->y, EX_BAD);
        }
        if (st->has_mid) {
            ex_dot(c, st->mid, 3.5, EX_HILITE);
        }
        snprintf(cap, sizeof cap, "%d. %s", i + 2, st->caption);
        ex_end(c, cap);
    }
    ex_begin(c);
    int drawn = 0;
    for (int k = 0; k < ls->n; k++) {
        if (ls->s[k].drawn && in_grid(c, ls->s[k].x, ls->s[k].y)) {
            ex_cell(c, ls->s[k].x, ls->s[k].y, EX_INK);
            drawn++;
        }
    }
    draw_line(c, ls);
    char cap[400];
    snprintf(cap, sizeof cap, "%d. %d pixels. %s", ls->n + 2, drawn, ls->outro);
    ex_end(c, cap);
    return c->error;
}

/* Snap the line, compute its steps by `bresenham` or the DDA, draw them. */
static sr_result explain(ex_canvas *c, const ex_primitive *prim, bool midpoint)
{
    line_steps *ls = calloc(1, sizeof *ls);
    if (!ls) {
        return c->error = SR_OUT_OF_MEMORY;
    }
    int64_t q[4];
    for (int i = 0; i < 4; i++) {
        q[i] = ex_snap(i % 2 ? prim->pts[i / 2].y : prim->pts[i / 2].x);
    }
    ls->grid_w = c->grid_w;
    ls->grid_h = c->grid_h;
    ls->a = (sr_point2){ q[0] / 256.0, q[1] / 256.0 };
    ls->b = (sr_point2){ q[2] / 256.0, q[3] / 256.0 };
    sr_result r = SR_INVALID_ARG;   /* bresenham: ends not on centres */
    if (!midpoint) {
        dda(ls, q[0], q[1], q[2], q[3]);
    }
    if (!midpoint || bresenham(ls, q[0], q[1], q[2], q[3])) {
        r = frames(c, ls);
    }
    free(ls);
    return r;
}

sr_result explain_bresenham(ex_canvas *c, const ex_primitive *prim)
{
    return explain(c, prim, true);
}

sr_result explain_dda(ex_canvas *c, const ex_primitive *prim)
{
    return explain(c, prim, false);
}
