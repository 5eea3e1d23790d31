/* pathcull.h - internal: the check sr_path_view arguments share
 * (path.c, dash.c). */
#ifndef SR_DRAW2D_PATHCULL_H
#define SR_DRAW2D_PATHCULL_H

#include "softrast.h"

#include <math.h>
#include <stdbool.h>

/* A finite map and a rectangle that is not empty (NaN fails). */
static inline bool sr__path_view_valid(const sr_path_view *v)
{
    bool ok = v->x0 <= v->x1 && v->y0 <= v->y1;
    for (int i = 0; i < 6; i++) {
        ok = ok && isfinite(v->m[i]);
    }
    return ok;
}

#endif
