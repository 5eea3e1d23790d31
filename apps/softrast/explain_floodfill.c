/* explain_floodfill.c - `softrast explain floodfill`: flood fill as
 * sr_flood_fill runs it, on a picture of a polygon's outline drawn with
 * one-pixel lines.  The region is the pixels connected to the seed (4- or
 * 8-connected) that have the seed's colour.  Rather than recursing per
 * pixel, the fill keeps an explicit stack of seeds: pop one, extend it
 * left and right to the whole run of region pixels on its row, set the
 * run, then push one seed for each run of region pixels in the rows above
 * and below, across the run (one pixel further each way when 8-connected,
 * for the diagonal neighbours). */
#include "explain.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const sr_rgba BOUNDARY = { 0.25f, 0.25f, 0.28f, 1 };
static const sr_rgba RUN = { 0.55f, 0.80f, 0.55f, 1 };      /* the run just set */
static const sr_rgba SEED = { 0.85f, 0.25f, 0.55f, 1 };

typedef struct fill {
    int w, h;
    uint8_t *line;      /* the picture: 1 where the outline was drawn */
    uint8_t *set;       /* filled so far */
    uint8_t want;       /* the seed's colour */
    int (*stack)[2];
    int n, cap;
} fill;

static bool inside(const fill *f, int x, int y)
{
    return x >= 0 && y >= 0 && x < f->w && y < f->h && !f->set[y * f->w + x] &&
           f->line[y * f->w + x] == f->want;
}

static bool push(fill *f, int x, int y)
{
    if (f->n == f->cap) {
        int cap = f->cap ? 2 * f->cap : 64;
        void *s = realloc(f->stack, sizeof *f->stack * (size_t)cap);
        if (!s) {
            return false;
        }
        f->stack = s;
        f->cap = cap;
    }
    f->stack[f->n][0] = x;
    f->stack[f->n][1] = y;
    f->n++;
    return true;
}

/* The picture, the filled pixels (the last run lighter) and the stack. */
static void draw(ex_canvas *c, const fill *f, int run_y, int l, int r)
{
    ex_begin(c);
    for (int y = 0; y < f->h; y++) {
        for (int x = 0; x < f->w; x++) {
            if (f->set[y * f->w + x]) {
                ex_cell(c, x, y, y == run_y && x >= l && x <= r ? RUN : EX_INK);
            } else if (f->line[y * f->w + x]) {
                ex_cell(c, x, y, BOUNDARY);
            }
        }
    }
    for (int i = 0; i < f->n; i++) {
        char s[16];
        snprintf(s, sizeof s, "%d", i + 1);
        /* the number large on a disc; a ring alone where it cannot fit */
        if (!ex_cell_badge(c, f->stack[i][0], f->stack[i][1], s, SEED)) {
            ex_ring(c, f->stack[i][0], f->stack[i][1], SEED);
        }
    }
}

sr_result explain_floodfill(ex_canvas *c, const ex_primitive *prim)
{
    fill f = { .w = c->grid_w, .h = c->grid_h };
    f.line = calloc((size_t)f.w * (size_t)f.h, 1);
    f.set = calloc((size_t)f.w * (size_t)f.h, 1);
    sr_result res = f.line && f.set ? ex_polyline_pixels(c, prim->pts, prim->count, true, f.line)
                                    : SR_OUT_OF_MEMORY;
    int sx = prim->seed[0], sy = prim->seed[1];
    bool conn8 = prim->connectivity == 8;
    int e = conn8 ? 1 : 0;
    char cap[700];
    if (res == SR_OK && (sx >= f.w || sy >= f.h)) {
        res = SR_INVALID_ARG;   /* the caller checks; kept safe */
    }
    if (res == SR_OK) {
        f.want = f.line[sy * f.w + sx];
        res = push(&f, sx, sy) ? SR_OK : SR_OUT_OF_MEMORY;
    }
    if (res == SR_OK) {
        draw(c, &f, -1, 0, -1);
        snprintf(cap, sizeof cap,
                 "1. A polygon's outline drawn with one-pixel lines, and a seed at (%d, %d). "
                 "Flood fill recolours the %d-connected region of pixels with the seed's colour "
                 "(%s). No recursion per pixel: a stack of seeds (numbered discs), here just the "
                 "first.",
                 sx, sy, conn8 ? 8 : 4, f.want ? "the outline's" : "the background");
        ex_end(c, cap);
    }
    int stale = 0;
    while (res == SR_OK && f.n > 0 && c->error == SR_OK) {
        f.n--;
        int x = f.stack[f.n][0], y = f.stack[f.n][1];
        if (!inside(&f, x, y)) {
            stale++;   /* set by a run since it was pushed */
            continue;
        }
        int l = x, r = x;
        while (inside(&f, l - 1, y)) {
            l--;
        }
        while (inside(&f, r + 1, y)) {
            r++;
        }
        memset(f.set + y * f.w + l, 1, (size_t)(r - l + 1));
        int pushed = 0;
        for (int ny = y - 1; ny <= y + 1 && res == SR_OK; ny += 2) {
            int i = l - e;
            while (i <= r + e) {
                if (inside(&f, i, ny)) {
                    res = push(&f, i, ny) ? res : SR_OUT_OF_MEMORY;
                    pushed++;
                    while (i <= r + e && inside(&f, i, ny)) {
                        i++;
                    }
                } else {
                    i++;
                }
            }
        }
        draw(c, &f, y, l, r);
        snprintf(cap, sizeof cap,
                 "%d. Pop (%d, %d)%s; extend it left and right to the run %d..%d on row %d and "
                 "set it (green). Scan rows %d and %d across %d..%d%s: %d new seed%s pushed, one "
                 "per run of region pixels. Stack: %d.",
                 c->frame_count + 1, x, y, stale ? " (the seeds popped before it were already "
                                                   "filled: skipped)" : "",
                 l, r, y, y - 1, y + 1, l - e, r + e, conn8 ? " (one further each way: the "
                                                               "diagonals)" : "",
                 pushed, pushed == 1 ? "" : "s", f.n);
        ex_end(c, cap);
        stale = 0;
    }
    if (res == SR_OK) {
        int total = 0;
        for (int i = 0; i < f.w * f.h; i++) {
            total += f.set[i];
        }
        draw(c, &f, -1, 0, -1);
        snprintf(cap, sizeof cap,
                 "%d. The stack is empty: %d pixels filled, run by run in the order shown, what "
                 "sr_flood_fill recolours %d-connected. %s",
                 c->frame_count + 1, total, conn8 ? 8 : 4,
                 conn8 ? "8-connected, the fill slips between the diagonal steps of a one-pixel "
                         "line: try --connectivity 4."
                       : "4-connected, a one-pixel line stops it even where it steps "
                         "diagonally: try --connectivity 8.");
        ex_end(c, cap);
    }
    free(f.line);
    free(f.set);
    free(f.stack);
    return res != SR_OK ? res : c->error;
}
