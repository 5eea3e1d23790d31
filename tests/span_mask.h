/* span_mask.h - tests' helper: draws the spans a scan converter hands out
 * (sr__span) into a byte mask of its window, the coverage or 255 without
 * one, counting what a converter must never do: write a pixel twice, or
 * leave the window.  Header-only; each test executable includes it once. */
#ifndef SR_TEST_SPAN_MASK_H
#define SR_TEST_SPAN_MASK_H

#include "draw2d/polyfill.h"

#include <stddef.h>

typedef struct mask_out {
    uint8_t *px;          /* (x1 - x0) * (y1 - y0) bytes, zeroed by the caller */
    sr__window win;
    long overlaps, outside;
    long with_cov;        /* spans that carried coverage */
} mask_out;

static void mark_span(void *user, const sr__span *sp)
{
    mask_out *m = user;
    if (sp->y < m->win.y0 || sp->y >= m->win.y1 || sp->x0 < m->win.x0 || sp->x1 > m->win.x1 ||
        sp->x0 >= sp->x1) {
        m->outside++;
        return;
    }
    m->with_cov += sp->cov != NULL;
    int w = m->win.x1 - m->win.x0;
    uint8_t *row = m->px + (size_t)(sp->y - m->win.y0) * (size_t)w - m->win.x0;
    for (int x = sp->x0; x < sp->x1; x++) {
        m->overlaps += row[x] != 0;
        row[x] = sp->cov ? sp->cov[x - sp->x0] : 255;
    }
}

#endif
