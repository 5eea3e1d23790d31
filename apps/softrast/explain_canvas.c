/* explain_canvas.c - the magnified pixel grid `softrast explain` draws its
 * steps on (see explain.h): cells are aliased rectangles, marks and edges
 * antialiased paths, captions the library's 5x7 font. */
#include "explain.h"
#include "outline.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MIN_TEXT_WIDTH 420  /* frame pixels: room for a caption line at scale 2 */

const sr_rgba EX_BG = { 0.97f, 0.97f, 0.96f, 1 };
const sr_rgba EX_GRID = { 0.72f, 0.74f, 0.78f, 1 };
const sr_rgba EX_CELL_OUT = { 1, 1, 1, 1 };
const sr_rgba EX_CELL_IN = { 0.55f, 0.80f, 0.55f, 1 };
const sr_rgba EX_INK = { 0.20f, 0.45f, 0.85f, 1 };
const sr_rgba EX_TIE = { 0.98f, 0.80f, 0.20f, 1 };
const sr_rgba EX_EDGE = { 0.10f, 0.10f, 0.12f, 1 };
const sr_rgba EX_HILITE = { 0.85f, 0.25f, 0.55f, 1 };
const sr_rgba EX_TEXT = { 0.10f, 0.10f, 0.12f, 1 };
const sr_rgba EX_BAD = { 0.85f, 0.15f, 0.10f, 1 };

int64_t ex_snap(double v)
{
    return (int64_t)nearbyint(v * 256.0);
}

sr_result ex_canvas_init(ex_canvas *c, sr_context *ctx, int grid_w, int grid_h, int zoom,
                         int caption_lines)
{
    *c = (ex_canvas){ .ctx = ctx, .grid_w = grid_w, .grid_h = grid_h, .zoom = zoom };
    int gw = grid_w * zoom;
    c->text_scale = gw >= MIN_TEXT_WIDTH ? 2 : 1;
    c->width = 2 * EX_MARGIN + (gw > MIN_TEXT_WIDTH / 2 * c->text_scale
                                    ? gw : MIN_TEXT_WIDTH / 2 * c->text_scale);
    c->caption_y = EX_MARGIN + grid_h * zoom + EX_MARGIN;
    c->caption_lines = caption_lines;
    c->height = c->caption_y + caption_lines * 10 * c->text_scale + EX_MARGIN;
    c->text_cells = calloc((size_t)grid_w * (size_t)grid_h, 1);
    if (!c->text_cells) {
        return c->error = SR_OUT_OF_MEMORY;
    }
    c->error = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = c->width,
                                                                .height = c->height,
                                                                .depth_format = SR_DEPTH_NONE },
                                   &c->fb);
    return c->error;
}

void ex_canvas_free(ex_canvas *c)
{
    for (int i = 0; i < c->frame_count; i++) {
        free(c->frames[i]);
    }
    free(c->frames);
    sr_destroy_framebuffer(c->ctx, c->fb);
    free(c->text_cells);
    *c = (ex_canvas){ 0 };
}

static void keep(ex_canvas *c, sr_result r)
{
    if (c->error == SR_OK) {
        c->error = r;
    }
}

/* An aliased rectangle in frame pixels (integer corners: exactly its
 * pixels). */
static void rect(ex_canvas *c, int x, int y, int w, int h, sr_rgba color)
{
    if (c->error != SR_OK) {
        return;
    }
    sr_point2 p[4] = { { x, y }, { x + w, y }, { x + w, y + h }, { x, y + h } };
    keep(c, sr_fill_polygon(c->ctx, c->fb, &(sr_polygon2){ p, 4, NULL, 0 }, color, NULL));
}

static sr_point2 to_frame(const ex_canvas *c, sr_point2 p)
{
    return (sr_point2){ EX_MARGIN + p.x * c->zoom, EX_MARGIN + p.y * c->zoom };
}

void ex_begin(ex_canvas *c)
{
    if (c->error != SR_OK) {
        return;
    }
    c->label_count = 0;
    c->cell_text = false;
    memset(c->text_cells, 0, (size_t)c->grid_w * (size_t)c->grid_h);
    keep(c, sr_clear(c->ctx, c->fb, &(sr_clear_desc){ .color = { EX_BG.r, EX_BG.g, EX_BG.b, 1 } }));
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            ex_cell(c, x, y, EX_CELL_OUT);
        }
    }
}

/* Whether cell (x, y) is on the grid: a step may name a pixel off it (a
 * line's end beyond the grid), which has nothing to show. */
static bool on_grid(const ex_canvas *c, int x, int y)
{
    return x >= 0 && y >= 0 && x < c->grid_w && y < c->grid_h;
}

void ex_cell(ex_canvas *c, int x, int y, sr_rgba color)
{
    if (!on_grid(c, x, y)) {
        return;
    }
    /* the cell without its one-pixel grid line on the top and left, which
     * the background shows through (and one past the last row/column) */
    int line = c->zoom >= 6 ? 1 : 0;
    rect(c, EX_MARGIN + x * c->zoom + line, EX_MARGIN + y * c->zoom + line, c->zoom - line,
         c->zoom - line, color);
    if (line && x == c->grid_w - 1) {
        rect(c, EX_MARGIN + (x + 1) * c->zoom, EX_MARGIN + y * c->zoom, 1, c->zoom + 1, EX_GRID);
    }
    if (line && y == c->grid_h - 1) {
        rect(c, EX_MARGIN + x * c->zoom, EX_MARGIN + (y + 1) * c->zoom, c->zoom + 1, 1, EX_GRID);
    }
    if (line) {
        rect(c, EX_MARGIN + x * c->zoom, EX_MARGIN + y * c->zoom, c->zoom, 1, EX_GRID);
        rect(c, EX_MARGIN + x * c->zoom, EX_MARGIN + y * c->zoom, 1, c->zoom, EX_GRID);
    }
}

static void path_fill(ex_canvas *c, sr_path *path, sr_rgba color)
{
    keep(c, sr_fill_path(c->ctx, c->fb, path, color, &(sr_fill_desc){ .antialias = SR_AA_AREA }));
}

static void circle(ex_canvas *c, sr_point2 q, double r, sr_rgba color, double ring)
{
    double pad = r + ring + 1;   /* a circle off the frame is left out */
    if (q.x < -pad || q.y < -pad || q.x > c->width + pad || q.y > c->height + pad) {
        return;
    }
    sr_path *path = NULL;
    if (c->error != SR_OK || (c->error = sr_make_path(c->ctx, 0.05, &path)) != SR_OK) {
        return;
    }
    sr_path_move_to(path, q.x - r, q.y);
    sr_path_arc_to(path, r, r, 0, false, true, q.x + r, q.y);
    sr_path_arc_to(path, r, r, 0, false, true, q.x - r, q.y);
    sr_path_close(path);
    if (ring > 0) {
        keep(c, sr_stroke_path(c->ctx, c->fb, path, color,
                               &(sr_stroke_desc){ .width = ring, .antialias = SR_AA_SUPERSAMPLE,
                                                  .samples = 4 }));
    } else {
        path_fill(c, path, color);
    }
    sr_destroy_path(c->ctx, path);
}

static sr_point2 cell_centre(const ex_canvas *c, int x, int y)
{
    return to_frame(c, (sr_point2){ x + 0.5, y + 0.5 });
}

void ex_sample(ex_canvas *c, int x, int y, sr_rgba color)
{
    circle(c, cell_centre(c, x, y), c->zoom >= 16 ? 2.5 : 1.2, color, 0);
}

void ex_ring(ex_canvas *c, int x, int y, sr_rgba color)
{
    circle(c, cell_centre(c, x, y), c->zoom * 0.32, color, c->zoom >= 16 ? 2.5 : 1.5);
}

void ex_cross(ex_canvas *c, int x, int y, sr_rgba color)
{
    double k = 0.22;
    ex_segment(c, (sr_point2){ x + k, y + k }, (sr_point2){ x + 1 - k, y + 1 - k }, color, 2.5);
    ex_segment(c, (sr_point2){ x + 1 - k, y + k }, (sr_point2){ x + k, y + 1 - k }, color, 2.5);
}

/* Cell text is written from TEXT_BAND frame pixels above a cell's bottom:
 * one 7-pixel row of the font under the sample point, and a pixel's gap. */
#define TEXT_BAND 10

void ex_cross_above_text(ex_canvas *c, int x, int y, sr_rgba color)
{
    if (c->zoom < 20) {
        ex_cross(c, x, y, color);
        return;
    }
    /* a square cross between the cell's top and its text band */
    double top = y + 0.12, bottom = y + 1 - (TEXT_BAND + 2.0) / c->zoom;
    double half = (bottom - top) / 2, mid = x + 0.5;
    ex_segment(c, (sr_point2){ mid - half, top }, (sr_point2){ mid + half, bottom }, color, 2.5);
    ex_segment(c, (sr_point2){ mid + half, top }, (sr_point2){ mid - half, bottom }, color, 2.5);
}

bool ex_cell_text(ex_canvas *c, int x, int y, const char *text, sr_rgba color)
{
    int w = sr_text_width(text, 1);
    if (!on_grid(c, x, y) || w > c->zoom - 3 || c->zoom < 20 || c->error != SR_OK) {
        return false;
    }
    int px = EX_MARGIN + x * c->zoom + (c->zoom - w + 1) / 2;
    int py = EX_MARGIN + y * c->zoom + c->zoom - (TEXT_BAND - 1);   /* under the sample point */
    keep(c, sr_draw_text(c->ctx, c->fb, px, py, 1, text, color));
    c->cell_text = true;
    c->text_cells[y * c->grid_w + x] = 1;
    return true;
}

bool ex_cell_badge(ex_canvas *c, int x, int y, const char *text, sr_rgba color)
{
    double r = c->zoom * 0.42;
    int s = 2;
    /* the text's box inside the disc: its half-diagonal within r - 1 */
    while (s > 0 && hypot(sr_text_width(text, s) / 2.0, 3.5 * s) > r - 1) {
        s--;
    }
    if (!on_grid(c, x, y) || s == 0 || c->zoom < 20 || c->error != SR_OK) {
        return false;
    }
    sr_point2 q = cell_centre(c, x, y);
    circle(c, q, r, color, 0);
    int w = sr_text_width(text, s);
    keep(c, sr_draw_text(c->ctx, c->fb, (int)floor(q.x - w / 2.0 + 0.5),
                         (int)floor(q.y - 3.5 * s + 0.5), s, text, (sr_rgba){ 1, 1, 1, 1 }));
    return true;
}

static sr_point2 frame_map(const void *c, sr_point2 p)
{
    return to_frame(c, p);
}

void ex_outline(ex_canvas *c, const sr_point2 *pts, int n, bool closed, sr_rgba color,
                double width)
{
    if (c->error != SR_OK) {
        return;
    }
    /* A vertex far off the grid (coordinates reach 16384 pixels, times the
     * zoom) lies beyond the 2D filler's fixed-point range: the fill cuts
     * the outline to a guard band around the frame (docs/raster-rules.md
     * §2.2), so it is drawn whole like any other. */
    keep(c, outline_stroke(c->ctx, c->fb, pts, n, closed, frame_map, c, color, width));
}

void ex_fill(ex_canvas *c, const sr_point2 *pts, int n, sr_rgba color)
{
    if (c->error != SR_OK || n < 3) {
        return;
    }
    sr_point2 *q = malloc((size_t)n * sizeof *q);
    if (!q) {
        keep(c, SR_OUT_OF_MEMORY);
        return;
    }
    for (int i = 0; i < n; i++) {
        q[i] = to_frame(c, pts[i]);
    }
    keep(c, sr_fill_polygon(c->ctx, c->fb, &(sr_polygon2){ q, n, NULL, 0 }, color,
                            &(sr_fill_desc){ .antialias = SR_AA_AREA }));
    free(q);
}

void ex_segment(ex_canvas *c, sr_point2 a, sr_point2 b, sr_rgba color, double width)
{
    ex_outline(c, (sr_point2[2]){ a, b }, 2, false, color, width);
}

void ex_dot(ex_canvas *c, sr_point2 p, double radius, sr_rgba color)
{
    circle(c, to_frame(c, p), radius, color, 0);
}

/* Whether row `row` has cell text in a column under frame x .. x + w. */
static bool row_has_text(const ex_canvas *c, int row, int x, int w)
{
    if (row < 0 || row >= c->grid_h) {
        return false;
    }
    int first = (x - EX_MARGIN) / c->zoom, last = (x + w - 1 - EX_MARGIN) / c->zoom;
    first = first < 0 ? 0 : first;
    last = last >= c->grid_w ? c->grid_w - 1 : last;
    for (int col = first; col <= last; col++) {
        if (c->text_cells[row * c->grid_w + col]) {
            return true;
        }
    }
    return false;
}

/* y for a label at x, y of w x h frame pixels, moved (up, or down when
 * `down`) out of the band cell text is written in where a cell under it
 * has some, when the room between two bands holds the label. */
static int clear_of_cell_text(const ex_canvas *c, int x, int y, int w, int h, bool down)
{
    if (!c->cell_text || h + 2 > c->zoom - TEXT_BAND || y + h <= EX_MARGIN) {
        return y;
    }
    int row = (y + h - EX_MARGIN) / c->zoom;   /* the row of the label's bottom */
    int top = EX_MARGIN + row * c->zoom, band = top + c->zoom - TEXT_BAND;
    if (y + h >= band && row_has_text(c, row, x, w)) {
        return down ? top + c->zoom + 1 : band - h - 1;
    }
    if (y < top && row_has_text(c, row - 1, x, w)) {
        /* its top in the band of the row above */
        return down ? top + 1 : top - TEXT_BAND - h - 1;
    }
    return y;
}

void ex_label(ex_canvas *c, sr_point2 p, const char *text, sr_rgba color)
{
    if (c->error != SR_OK) {
        return;
    }
    sr_point2 q = to_frame(c, p);
    int s = c->text_scale;
    int x = (int)q.x + 5, y = (int)q.y - 8 * s - 3;
    /* kept inside the frame, above the caption: a vertex beyond the grid's
     * bottom (clip4d's divide of a w <= 0 vertex) would write over it */
    int w = sr_text_width(text, s);
    x = x + w > c->width - 2 ? c->width - 2 - w : x;
    x = x < 2 ? 2 : x;
    int bottom = c->caption_y - EX_MARGIN / 2 - 8 * s;
    y = y > bottom ? bottom : y;
    y = y < 2 ? 2 : y;
    int h = 7 * s;
    y = clear_of_cell_text(c, x, y, w, h, false);
    /* a label on one drawn before in this frame (two vertices at one
     * point, a name beside a vertex's) goes below it, so both read */
    for (int tries = 0; tries < 16; tries++) {
        bool moved = false;
        for (int i = 0; i < c->label_count && !moved; i++) {
            const int *b = c->labels[i];
            if (x < b[0] + b[2] + s && b[0] < x + w + s && y < b[1] + b[3] + s &&
                b[1] < y + h + s && b[1] + b[3] + 2 * s <= bottom) {
                y = clear_of_cell_text(c, x, b[1] + b[3] + 2 * s, w, h, true);
                moved = true;
            }
        }
        if (!moved) {
            break;
        }
    }
    if (c->label_count < (int)(sizeof c->labels / sizeof c->labels[0])) {
        int *b = c->labels[c->label_count++];
        b[0] = x, b[1] = y, b[2] = w, b[3] = h;
    }
    if (c->cell_text) {
        /* over coloured cells and edges the text needs a ground of its own */
        rect(c, x - s, y - s, w + 2 * s, h + 2 * s, (sr_rgba){ EX_BG.r, EX_BG.g, EX_BG.b, 0.85f });
    }
    keep(c, sr_draw_text(c->ctx, c->fb, x, y, s, text, color));
}

/* Draw `text` wrapped at spaces (and at '\n') into the caption lines, on
 * a band cleared first: an edge to a vertex beyond the grid's bottom
 * (clip4d's divide of a w <= 0 vertex) would cross the words. */
static void caption(ex_canvas *c, const char *text)
{
    int band = c->caption_y - EX_MARGIN / 2;
    rect(c, 0, band, c->width, c->height - band, EX_BG);
    int s = c->text_scale;
    int max_chars = (c->width - 2 * EX_MARGIN) / (6 * s);
    int line = 0;
    const char *p = text;
    while (*p && c->error == SR_OK) {
        int n = 0, cut = -1;
        while (p[n] && p[n] != '\n' && n < max_chars) {
            if (p[n] == ' ') {
                cut = n;
            }
            n++;
        }
        if (p[n] && p[n] != '\n' && p[n] != ' ' && cut > 0) {
            n = cut;   /* break at the last space that fits */
        }
        if (line < c->caption_lines) {
            char buf[256];
            int k = n < (int)sizeof buf - 1 ? n : (int)sizeof buf - 1;
            memcpy(buf, p, (size_t)k);
            buf[k] = 0;
            keep(c, sr_draw_text(c->ctx, c->fb, EX_MARGIN, c->caption_y + line * 10 * s, s, buf,
                                 EX_TEXT));
        }
        p += n;
        while (*p == ' ' || *p == '\n') {
            p++;
        }
        line++;
    }
    /* the lines past the room are counted, not drawn: the caller runs the
     * steps again on a taller canvas */
    c->caption_needed = line > c->caption_needed ? line : c->caption_needed;
}

void ex_end(ex_canvas *c, const char *text)
{
    caption(c, text);
    if (c->error != SR_OK) {
        return;
    }
    if (c->frame_count == c->frame_cap) {
        int cap = c->frame_cap ? c->frame_cap * 2 : 16;
        uint8_t **f = realloc(c->frames, sizeof *f * (size_t)cap);
        if (!f) {
            c->error = SR_OUT_OF_MEMORY;
            return;
        }
        c->frames = f;
        c->frame_cap = cap;
    }
    size_t size = (size_t)c->width * (size_t)c->height * 4;
    if (c->kept_bytes + size > EX_MAX_FRAME_BYTES) {
        c->too_many = true;
        c->error = SR_TOO_LARGE;
        return;
    }
    c->kept_bytes += size;
    uint8_t *px = malloc(size);
    if (!px) {
        c->error = SR_OUT_OF_MEMORY;
        return;
    }
    memcpy(px, sr_framebuffer_pixels(c->fb), size);
    c->frames[c->frame_count++] = px;
}

sr_result ex_polyline_pixels(ex_canvas *c, const sr_point2 *pts, int n, bool closed,
                             uint8_t *mask)
{
    sr_framebuffer *fb = NULL;
    sr_result r = sr_make_framebuffer(c->ctx, &(sr_framebuffer_desc){ .width = c->grid_w,
                                                                       .height = c->grid_h,
                                                                       .depth_format = SR_DEPTH_NONE },
                                      &fb);
    if (r != SR_OK) {
        return r;
    }
    r = sr_clear(c->ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
    int segments = closed ? n : n - 1;
    for (int i = 0; i < segments && r == SR_OK; i++) {
        r = sr_draw_line(c->ctx, fb, pts[i], pts[(i + 1) % n], (sr_rgba){ 1, 1, 1, 1 }, NULL);
    }
    const uint8_t *px = sr_framebuffer_pixels(fb);
    for (int i = 0; i < c->grid_w * c->grid_h; i++) {
        mask[i] = px[i * 4] != 0;
    }
    sr_destroy_framebuffer(c->ctx, fb);
    return r;
}

void ex_line_ab(ex_canvas *c, sr_point2 a, sr_point2 b)
{
    ex_segment(c, a, b, EX_EDGE, 1.5);
    double r = c->zoom >= 20 ? 3.5 : c->zoom * 0.18;
    ex_dot(c, a, r, EX_EDGE);
    ex_dot(c, b, r, EX_EDGE);
    /* ends closer than a label's width (a zero-length line) share one
     * name: two would be drawn over each other */
    double gap = fmax(fabs(b.x - a.x), fabs(b.y - a.y)) * c->zoom;
    if (gap < sr_text_width("A", c->text_scale) + 6) {
        ex_label(c, a, "A=B", EX_EDGE);
    } else {
        ex_label(c, a, "A", EX_EDGE);
        ex_label(c, b, "B", EX_EDGE);
    }
}

void ex_weight_text(char *buf, size_t size, double w)
{
    if (w >= 0.995) {
        snprintf(buf, size, "1");
        return;
    }
    char t[16];
    snprintf(t, sizeof t, "%.2f", w);
    snprintf(buf, size, "%s", t[0] == '0' ? t + 1 : t);
}

static double srgb_to_linear(double c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

sr_rgba ex_ink_over_white(double c)
{
    const float ink[3] = { EX_INK.r, EX_INK.g, EX_INK.b };
    float out[3];
    for (int i = 0; i < 3; i++) {
        out[i] = sr_srgb_encode8((float)(c * srgb_to_linear(ink[i]) + (1.0 - c))) / 255.0f;
    }
    return (sr_rgba){ out[0], out[1], out[2], 1 };
}

int ex_line_frame(ex_canvas *c, sr_point2 a, sr_point2 b, const sr_line_desc *desc)
{
    sr_framebuffer *fb = NULL;
    keep(c, sr_make_framebuffer(c->ctx, &(sr_framebuffer_desc){ .width = c->grid_w,
                                                                 .height = c->grid_h,
                                                                 .depth_format = SR_DEPTH_NONE },
                                &fb));
    if (c->error != SR_OK) {
        return 0;
    }
    sr_clear(c->ctx, fb, &(sr_clear_desc){ .color = { 1, 1, 1, 1 } });   /* EX_CELL_OUT */
    keep(c, sr_draw_line(c->ctx, fb, a, b, EX_INK, desc));
    ex_begin(c);
    const uint8_t *px = sr_framebuffer_pixels(fb);
    int drawn = 0;
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            const uint8_t *p = px + 4 * ((size_t)y * c->grid_w + x);
            if (p[0] == 255 && p[1] == 255 && p[2] == 255) {
                continue;
            }
            ex_cell(c, x, y, (sr_rgba){ p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f, 1 });
            drawn++;
        }
    }
    sr_destroy_framebuffer(c->ctx, fb);
    return drawn;
}
