/* demo2d.h - shared by the 2D toolkit demos (fill, floodfill, clip): each
 * demo draws small scenes into a panel-sized framebuffer, which is
 * magnified into one cell of a labelled grid so the pixels show, and may
 * draw vector overlays (outlines, vertices) on top in output pixels. */
#ifndef SR_DEMO2D_H
#define SR_DEMO2D_H

#include "softrast.h"

#include <stdbool.h>

typedef struct demo2d {
    sr_context *ctx;
    const char *name;          /* for error messages */
    sr_framebuffer *out;       /* the whole image */
    sr_framebuffer *panel;     /* panel_w x panel_h, drawn by the demo */
    int panel_w, panel_h, scale, cols, rows;
    sr_result error;           /* of the first blit that failed: finish reports it */
} demo2d;

/* Make the output and the panel; 0 or an exit status after one line. */
int  demo2d_begin(demo2d *d, sr_context *ctx, const char *name, int cols, int rows,
                  int panel_w, int panel_h, int scale);
void demo2d_clear_panel(demo2d *d, sr_rgba bg);
/* Magnify the panel into cell `index` (row-major) under `label`. */
void demo2d_blit(demo2d *d, int index, const char *label);
/* Panel coordinates (pixel units) -> output coordinates of cell `index`. */
sr_point2 demo2d_map(const demo2d *d, int index, sr_point2 p);
/* Vector overlays in cell `index`, given in panel coordinates. */
void demo2d_outline(demo2d *d, int index, const sr_point2 *pts, int n, bool closed,
                    sr_rgba color, double width_px);
void demo2d_dot(demo2d *d, int index, sr_point2 p, double radius_px, sr_rgba color);
/* Hand the image over (*out) and free the panel; returns EXIT_OK, or
 * demo2d_fail's status when a blit failed. */
int  demo2d_finish(demo2d *d, sr_framebuffer **out);
/* Report sr_context_error, free everything; returns EXIT_FAILURE_RUN. */
int  demo2d_fail(demo2d *d);

#endif
