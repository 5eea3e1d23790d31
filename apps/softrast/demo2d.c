/* demo2d.c - the magnified, labelled panel grid the 2D toolkit demos
 * share (see demo2d.h). */
#include "demo2d.h"

#include "cli.h"
#include "demo.h"
#include "outline.h"

#include <string.h>

#define GAP 12      /* output pixels between cells */
#define LABEL_H 28  /* output pixels above each cell for its label */

static int cell_w(const demo2d *d) { return d->panel_w * d->scale; }
static int cell_h(const demo2d *d) { return d->panel_h * d->scale; }

static void cell_origin(const demo2d *d, int index, int *ox, int *oy)
{
    *ox = GAP + (index % d->cols) * (cell_w(d) + GAP);
    *oy = GAP + (index / d->cols) * (cell_h(d) + LABEL_H + GAP) + LABEL_H;
}

int demo2d_begin(demo2d *d, sr_context *ctx, const char *name, int cols, int rows,
                 int panel_w, int panel_h, int scale)
{
    *d = (demo2d){ ctx, name, NULL, NULL, panel_w, panel_h, scale, cols, rows, SR_OK };
    int w = cols * cell_w(d) + (cols + 1) * GAP;
    int h = rows * (cell_h(d) + LABEL_H) + (rows + 1) * GAP;
    if (demo_check_image(name, scale, w, h) != EXIT_OK) {
        return EXIT_USAGE;
    }
    if (sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = w, .height = h,
                                                         .depth_format = SR_DEPTH_NONE }, &d->out) != SR_OK ||
        sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = panel_w, .height = panel_h,
                                                         .depth_format = SR_DEPTH_NONE }, &d->panel) != SR_OK) {
        return demo2d_fail(d);
    }
    sr_clear(ctx, d->out, &(sr_clear_desc){ .color = { 0.93f, 0.93f, 0.93f, 1 } });
    return EXIT_OK;
}

void demo2d_clear_panel(demo2d *d, sr_rgba bg)
{
    sr_clear(d->ctx, d->panel, &(sr_clear_desc){ .color = { bg.r, bg.g, bg.b, bg.a } });
}

void demo2d_blit(demo2d *d, int index, const char *label)
{
    int ox, oy;
    cell_origin(d, index, &ox, &oy);
    /* The labels: one size for the whole demo (twice the font when cells
     * are wide enough for 18 characters), cut short if still too long. */
    char text[96];
    strncpy(text, label, sizeof text - 1);
    text[sizeof text - 1] = 0;
    int ts = cell_w(d) >= sr_text_width("123456789012345678", 2) ? 2 : 1;
    while (sr_text_width(text, ts) > cell_w(d) && strlen(text) > 1) {
        text[strlen(text) - 1] = 0;
    }
    sr_draw_text(d->ctx, d->out, ox, oy - 8 * ts - 6, ts, text, (sr_rgba){ 0.1f, 0.1f, 0.12f, 1 });
    /* each pixel a scale x scale block, a grid line on its top and left
     * edges when blocks are large enough to spare it */
    static const uint8_t grid[4] = { 60, 64, 72, 255 };
    if (d->error == SR_OK) {
        d->error = demo_magnify(d->ctx, d->out, ox, oy, d->panel, d->scale, grid);
    }
}

sr_point2 demo2d_map(const demo2d *d, int index, sr_point2 p)
{
    int ox, oy;
    cell_origin(d, index, &ox, &oy);
    return (sr_point2){ ox + p.x * d->scale, oy + p.y * d->scale };
}

/* demo2d_map for outline_stroke: the demo and the panel's index. */
typedef struct panel {
    const demo2d *d;
    int index;
} panel;

static sr_point2 panel_map(const void *user, sr_point2 p)
{
    const panel *at = user;
    return demo2d_map(at->d, at->index, p);
}

void demo2d_outline(demo2d *d, int index, const sr_point2 *pts, int n, bool closed,
                    sr_rgba color, double width_px)
{
    outline_stroke(d->ctx, d->out, pts, n, closed, panel_map, &(panel){ d, index }, color,
                   width_px);
}

void demo2d_dot(demo2d *d, int index, sr_point2 p, double radius_px, sr_rgba color)
{
    sr_point2 q = demo2d_map(d, index, p);
    sr_path *path = NULL;
    if (sr_make_path(d->ctx, 0.05, &path) != SR_OK) {
        return;
    }
    sr_path_move_to(path, q.x - radius_px, q.y);
    sr_path_arc_to(path, radius_px, radius_px, 0, false, true, q.x + radius_px, q.y);
    sr_path_arc_to(path, radius_px, radius_px, 0, false, true, q.x - radius_px, q.y);
    sr_path_close(path);
    sr_fill_path(d->ctx, d->out, path, color, &(sr_fill_desc){ .antialias = SR_AA_AREA });
    sr_destroy_path(d->ctx, path);
}

int demo2d_finish(demo2d *d, sr_framebuffer **out)
{
    if (d->error != SR_OK) {
        return demo2d_fail(d);
    }
    sr_destroy_framebuffer(d->ctx, d->panel);
    d->panel = NULL;
    *out = d->out;
    d->out = NULL;
    return EXIT_OK;
}

int demo2d_fail(demo2d *d)
{
    /* A blit that ran out of memory before reaching the context left it
     * no message. */
    const char *why = sr_context_error(d->ctx);
    cli_error("demo %s: %s", d->name, why[0] ? why : sr_result_text(d->error));
    sr_destroy_framebuffer(d->ctx, d->panel);
    sr_destroy_framebuffer(d->ctx, d->out);
    d->panel = d->out = NULL;
    return EXIT_FAILURE_RUN;
}
