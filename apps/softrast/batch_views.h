/* batch_views.h - turntable views and the contact sheet of a batch
 * (batch_views.c). */
#ifndef SR_BATCH_VIEWS_H
#define SR_BATCH_VIEWS_H

#include "render.h"
#include "softrast.h"

#include <stdbool.h>

/* Set the job's camera to view `view` of `views` round the model: the
 * default camera (or the user's --camera) turned about the vertical axis
 * through its target by 360 * view / views degrees. */
void batch_view_camera(render_job *job, bool user_camera, int view, int views);

/* A grid of images, `cols` a row, each with a caption strip beneath. */
typedef struct batch_sheet {
    sr_framebuffer *fb;
    int cols, rows, cell_w, cell_h, caption_h;
    int next;                  /* the next cell to fill */
    sr_rgba ink;
} batch_sheet;

/* The grid for `images` cells of w x h (columns 0: about square); false
 * when the sheet would be wider or taller than SR_MAX_FRAMEBUFFER_SIZE. */
bool batch_sheet_size(int images, int columns, int w, int h, int *cols, int *rows,
                      long *sheet_w, long *sheet_h);
/* The --sheet-columns that make such a sheet fit, from *lo to *hi; false
 * when none does (the cells are too many or too large for any grid). */
bool batch_sheet_columns_that_fit(int images, int w, int h, int *lo, int *hi);
sr_result batch_sheet_start(batch_sheet *sh, sr_context *ctx, int images, int columns, int w,
                            int h, sr_vec3 background, float alpha);
/* Fill the next cell with rgba (w x h; NULL leaves the background) and
 * caption it (in red when failed). */
sr_result batch_sheet_put(batch_sheet *sh, sr_context *ctx, const uint8_t *rgba,
                          const char *caption, bool failed);
void batch_sheet_free(batch_sheet *sh, sr_context *ctx);

#endif
