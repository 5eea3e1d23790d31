/* view_overlay.c - the overlay of `softrast view`: a translucent panel with
 * the frame time, the counts the library reports (sr_last_draw_info,
 * summed over the passes), the active modes and, on H, the key list.
 * Drawn into the back framebuffer after the scene (and after a screenshot
 * is taken) with softrast's 2D toolkit: the panel is a path filled with
 * exact-area antialiasing, the text TrueType glyphs from view_font.c. */
#ifdef SR_HAVE_VIEWER
#include "view.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#define PAD 10
#define MAX_LINES 48

static const sr_rgba panel_color = { 0.06f, 0.07f, 0.10f, 0.72f };
static const sr_rgba text_color = { 0.93f, 0.94f, 0.96f, 1.0f };
static const sr_rgba dim_color = { 0.62f, 0.68f, 0.78f, 1.0f };

/* A rounded rectangle, filled with exact-area coverage. */
static sr_result panel(sr_context *ctx, sr_framebuffer *fb, double x, double y, double w,
                       double h)
{
    const double r = 6.0;
    sr_path *p;
    sr_result res = sr_make_path(ctx, 0.1, &p);
    if (res != SR_OK) {
        return res;
    }
    sr_path_move_to(p, x + r, y);
    sr_path_line_to(p, x + w - r, y);
    sr_path_arc_to(p, r, r, 0, false, true, x + w, y + r);
    sr_path_line_to(p, x + w, y + h - r);
    sr_path_arc_to(p, r, r, 0, false, true, x + w - r, y + h);
    sr_path_line_to(p, x + r, y + h);
    sr_path_arc_to(p, r, r, 0, false, true, x, y + h - r);
    sr_path_line_to(p, x, y + r);
    sr_path_arc_to(p, r, r, 0, false, true, x + r, y);
    sr_path_close(p);
    res = sr_fill_path(ctx, fb, p, panel_color,
                       &(sr_fill_desc){ .rule = SR_NONZERO, .antialias = SR_AA_AREA });
    sr_destroy_path(ctx, p);
    return res;
}

typedef struct text_block {
    char lines[MAX_LINES][160];
    bool dim[MAX_LINES];
    int count;
} text_block;

static void add(text_block *b, bool dim, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static void add(text_block *b, bool dim, const char *fmt, ...)
{
    if (b->count == MAX_LINES) {
        return;
    }
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(b->lines[b->count], sizeof b->lines[0], fmt, ap);
    va_end(ap);
    b->dim[b->count++] = dim;
}

/* src into dst (n bytes), cut short where it does not fit. */
static void copy_cut(char *dst, size_t n, const char *src)
{
    size_t k = strlen(src);
    k = k < n ? k : n - 1;
    memcpy(dst, src, k);
    dst[k] = 0;
}

/* Split "a, b, c, ..." into lines no wider than max_w pixels. */
static void add_wrapped(text_block *b, view_font *f, sr_context *ctx, const char *text, int max_w)
{
    char line[330] = "";
    const char *p = text;
    while (*p) {
        const char *comma = strstr(p, ", ");
        size_t n = comma ? (size_t)(comma - p) + 1 : strlen(p);
        char piece[160];
        snprintf(piece, sizeof piece, "%.*s", (int)n, p);
        char trial[sizeof line + sizeof piece];
        snprintf(trial, sizeof trial, "%s%s%s", line, line[0] ? " " : "", piece);
        if (line[0] && view_font_width(f, ctx, trial) > max_w) {
            add(b, false, "%s", line);
            copy_cut(line, sizeof line, piece);
        } else {
            copy_cut(line, sizeof line, trial);
        }
        p += n;
        while (*p == ' ') {
            p++;
        }
    }
    if (line[0]) {
        add(b, false, "%s", line);
    }
}

static void add_help(text_block *b)
{
    add(b, true, "keys");
    add(b, false, "left drag orbit \xc2\xb7 right/middle drag pan \xc2\xb7 wheel zoom");
    add(b, false, "R reset \xc2\xb7 F fit \xc2\xb7 S screenshot \xc2\xb7 Enter print render command");
    add(b, false, "Tab overlay \xc2\xb7 H this list \xc2\xb7 Q/Esc quit \xc2\xb7 Shift+key cycles back");
    for (int m = 0; m < view_mode_count; m++) {
        char values[160] = "";
        size_t len = 0;
        for (int c = 0; c < VIEW_MAX_CHOICES && view_modes[m].choices[c].name; c++) {
            int n = snprintf(values + len, sizeof values - len, "%s%s", c ? " / " : "",
                             view_modes[m].choices[c].name);
            len += n > 0 && (size_t)n < sizeof values - len ? (size_t)n : 0;
        }
        add(b, false, "%c  %s: %s", view_modes[m].key - 'a' + 'A', view_modes[m].label, values);
    }
}

sr_result view_overlay_draw(view_font *f, sr_context *ctx, sr_framebuffer *fb,
                            const view_overlay_info *in)
{
    int fb_w = sr_framebuffer_width(fb);
    int max_w = fb_w - 4 * PAD > 200 ? fb_w - 4 * PAD : 200;
    if (max_w > 620) {
        max_w = 620;
    }
    text_block b = { .count = 0 };
    add(&b, true, "%s  %d\xc3\x97%d", in->title, in->width, in->height);
    char fps[32] = "\xe2\x80\x93";   /* an en dash until two frames have been shown */
    if (in->fps > 0) {
        snprintf(fps, sizeof fps, "%.0f", in->fps);
    }
    add(&b, false, "render %.2f ms (median %.2f) \xc2\xb7 %s fps shown", in->render_ms,
        in->median_ms > 0 ? in->median_ms : in->render_ms, fps);
    add(&b, false, "%llu triangles \xc2\xb7 %llu fragments \xc2\xb7 %d threads", in->triangles,
        in->fragments, in->threads);
    add_wrapped(&b, f, ctx, in->modes, max_w);
    if (in->help) {
        add_help(&b);
    } else {
        add(&b, true, "H: keys");
    }
    int lh = view_font_line_height(f), w = 0;
    for (int i = 0; i < b.count; i++) {
        int lw = view_font_width(f, ctx, b.lines[i]);
        w = lw > w ? lw : w;
    }
    sr_result r = panel(ctx, fb, PAD, PAD, w + 2 * PAD, b.count * lh + 2 * PAD - 4);
    int y = 2 * PAD + view_font_ascent(f) - 2;
    for (int i = 0; i < b.count && r == SR_OK; i++, y += lh) {
        r = view_font_draw(f, ctx, fb, 2 * PAD, y, b.lines[i], b.dim[i] ? dim_color : text_color);
    }
    return r;
}
#endif /* SR_HAVE_VIEWER */
