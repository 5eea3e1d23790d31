/* outline.h - a polyline or polygon outline stroked with round joins and
 * caps, antialiased by 4x supersampling: the look of the figures' outlines
 * in `softrast demo` and `softrast explain`.  Header-only so that every
 * build of those commands (the WebAssembly pages too) has it. */
#ifndef SOFTRAST_OUTLINE_H
#define SOFTRAST_OUTLINE_H

#include "softrast.h"

#include <stdbool.h>

/* Strokes pts[0..n) (closed: back to pts[0]), each point taken through
 * map(user, p) into the framebuffer's pixels, `width` pixels wide.
 * Fewer than two points draw nothing. */
static inline sr_result outline_stroke(sr_context *ctx, sr_framebuffer *fb, const sr_point2 *pts,
                                       int n, bool closed,
                                       sr_point2 (*map)(const void *user, sr_point2 p),
                                       const void *user, sr_rgba color, double width)
{
    if (n < 2) {
        return SR_OK;
    }
    sr_path *path = NULL;
    sr_result r = sr_make_path(ctx, 0.05, &path);
    if (r != SR_OK) {
        return r;
    }
    for (int i = 0; i < n; i++) {
        sr_point2 q = map(user, pts[i]);
        if (i == 0) {
            sr_path_move_to(path, q.x, q.y);
        } else {
            sr_path_line_to(path, q.x, q.y);
        }
    }
    if (closed) {
        sr_path_close(path);
    }
    r = sr_stroke_path(ctx, fb, path, color,
                       &(sr_stroke_desc){ .width = width, .join = SR_STROKE_JOIN_ROUND,
                                          .cap = SR_STROKE_CAP_ROUND,
                                          .antialias = SR_AA_SUPERSAMPLE, .samples = 4 });
    sr_destroy_path(ctx, path);
    return r;
}

#endif
