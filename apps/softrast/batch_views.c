/* batch_views.c - the views of a turntable (--views N) and the contact
 * sheet (--sheet FILE) that lays a batch's images out on one page, each
 * captioned in softrast's own 5x7 font. */
#include "batch_views.h"
#include "framing.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define PI_F 3.14159265358979f

void batch_view_camera(render_job *job, bool user_camera, int view, int views)
{
    sr_vec3 eye, target, up = { 0, 1, 0 };
    if (user_camera) {
        render_job_camera(job, &eye, &target, &up);
    } else {
        /* The bounding sphere framed from the default direction: every
         * view then shows the model at one scale, as a turntable should. */
        float r;
        render_job_bounds(job, &target, &r);
        eye = framing_default_eye(target, r, render_job_fov(job));
    }
    /* Walk round the vertical axis through the target, a step a view. */
    float a = 2.0f * PI_F * (float)view / (float)views, c = cosf(a), s = sinf(a);
    sr_vec3 d = sr_vec3_sub(eye, target);
    sr_vec3 turned = { c * d.x + s * d.z, d.y, -s * d.x + c * d.z };
    render_job_set_camera(job, sr_vec3_add(target, turned), target, up);
}

/* ---- the contact sheet --------------------------------------------------- */

/* Caption text: the 5x7 font, doubled in cells wide enough for about 26
 * doubled glyphs, in a strip one glyph high plus a margin. */
static int caption_scale(int cell_w)
{
    return cell_w >= 320 ? 2 : 1;
}

static int caption_height(int cell_w)
{
    return 12 * caption_scale(cell_w);
}

bool batch_sheet_size(int images, int columns, int w, int h, int *cols, int *rows,
                      long *sheet_w, long *sheet_h)
{
    *cols = columns > 0 ? columns : (int)ceil(sqrt((double)images));
    if (*cols < 1) {
        *cols = 1;
    }
    if (*cols > images && images > 0) {
        *cols = images;
    }
    *rows = images > 0 ? (images + *cols - 1) / *cols : 1;
    *sheet_w = (long)*cols * w;
    *sheet_h = (long)*rows * (h + caption_height(w));
    return *sheet_w <= SR_MAX_FRAMEBUFFER_SIZE && *sheet_h <= SR_MAX_FRAMEBUFFER_SIZE;
}

bool batch_sheet_columns_that_fit(int images, int w, int h, int *lo, int *hi)
{
    long most_cols = SR_MAX_FRAMEBUFFER_SIZE / w;
    long most_rows = SR_MAX_FRAMEBUFFER_SIZE / (h + caption_height(w));
    if (images < 1 || most_cols < 1 || most_rows < 1) {
        return false;
    }
    long fewest_cols = (images + most_rows - 1) / most_rows;
    long cols_used = images < most_cols ? images : most_cols; /* more would be empty */
    if (fewest_cols > cols_used) {
        return false;
    }
    *lo = (int)fewest_cols;
    *hi = (int)cols_used;
    return true;
}

sr_result batch_sheet_start(batch_sheet *sh, sr_context *ctx, int images, int columns, int w,
                            int h, sr_vec3 background, float alpha)
{
    long sw, shh;
    *sh = (batch_sheet){ .cell_w = w, .cell_h = h, .caption_h = caption_height(w) };
    if (!batch_sheet_size(images, columns, w, h, &sh->cols, &sh->rows, &sw, &shh)) {
        return SR_TOO_LARGE;
    }
    /* Light text on a dark background, dark on a light one. */
    float ink = background.x + background.y + background.z > 1.5f ? 0.1f : 0.92f;
    sh->ink = (sr_rgba){ ink, ink, ink, 1.0f };
    sr_result r = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = (int)sw,
                                                                  .height = (int)shh,
                                                                  .depth_format = SR_DEPTH_NONE },
                                      &sh->fb);
    if (r == SR_OK) {
        r = sr_clear(ctx, sh->fb, &(sr_clear_desc){ .color = { background.x, background.y,
                                                               background.z, alpha } });
    }
    return r;
}

sr_result batch_sheet_put(batch_sheet *sh, sr_context *ctx, const uint8_t *rgba,
                          const char *caption, bool failed)
{
    int col = sh->next % sh->cols, row = sh->next / sh->cols;
    int x = col * sh->cell_w, y = row * (sh->cell_h + sh->caption_h);
    sh->next++;
    sr_result r = SR_OK;
    if (rgba) {
        r = sr_write_pixels(ctx, sh->fb, x, y, sh->cell_w, sh->cell_h, rgba,
                            4 * (size_t)sh->cell_w);
    }
    /* The caption, cut to the cell's width with "..." at its end. */
    int scale = caption_scale(sh->cell_w);
    char text[256];
    snprintf(text, sizeof text, "%s", caption);
    size_t n = strlen(text);
    while (n > 3 && sr_text_width(text, scale) > sh->cell_w - 4) {
        n--;
        memcpy(text + n - 3, "...", 4);
    }
    int tw = sr_text_width(text, scale);
    sr_rgba ink = failed ? (sr_rgba){ 0.95f, 0.3f, 0.25f, 1.0f } : sh->ink;
    if (r == SR_OK) {
        r = sr_draw_text(ctx, sh->fb, x + (sh->cell_w - tw) / 2, y + sh->cell_h + 2 * scale,
                         scale, text, ink);
    }
    return r;
}

void batch_sheet_free(batch_sheet *sh, sr_context *ctx)
{
    sr_destroy_framebuffer(ctx, sh->fb);
    sh->fb = NULL;
}
