/* explain_scanline.c - `softrast explain scanline`: the scan-line polygon
 * fill as sr_fill_polygon runs it.  Vertices are snapped to 1/256 pixel;
 * every non-horizontal edge goes into the edge table (ET), bucketed by the
 * first scanline whose sample height y + 1/2 it crosses (an edge is active
 * while ymin <= y + 1/2 < ymax, half-open, so a vertex shared by two edges
 * is crossed once).  On each scanline the active edge table (AET) takes
 * the new bucket, drops the edges that ended and is sorted by x; walking
 * its crossings left to right counts parity (even-odd) or winding
 * (nonzero), and the pixels whose centres lie between an inside pair of
 * crossings form a span.  The crossings are exact: the first pixel at or
 * right of crossing x is ceil(x - 1/2), computed in integers. */
#include "explain.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

typedef struct edge {
    int64_t x0, y0, x1, y1;   /* q8, y0 < y1 */
    int dir;                  /* +1 when the contour runs down, -1 up */
    int first, last;          /* the scanlines it is active on */
    int id;                   /* its number in the polygon: e<id> runs V<id> -> V<id+1> */
} edge;

static int64_t floor_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}

static int64_t ceil_div(int64_t a, int64_t b)
{
    return -floor_div(-a, b);
}

/* The crossing of edge e with scanline y: its x (pixels) and the first
 * pixel whose centre is at or right of it. */
static double cross_x(const edge *e, int y)
{
    double yc = y * 256.0 + 128;
    return (e->x0 + (yc - e->y0) * (double)(e->x1 - e->x0) / (double)(e->y1 - e->y0)) / 256.0;
}

static int64_t cross_pixel(const edge *e, int y)
{
    int64_t den = e->y1 - e->y0, yc = (int64_t)y * 256 + 128;
    return ceil_div((e->x0 - 128) * den + (yc - e->y0) * (e->x1 - e->x0), 256 * den);
}

static bool inside(sr_fill_rule rule, int w)
{
    return rule == SR_EVENODD ? (w & 1) != 0 : w != 0;
}

typedef struct scan {
    edge e[EX_MAX_POINTS];
    int n;                    /* edges that cross a scanline */
    int horizontal;           /* edges dropped: they cross no scanline */
    int y0, y1;               /* scanlines with active edges: [y0, y1] */
    sr_point2 v[EX_MAX_POINTS];
    int nv;
    uint8_t *filled;          /* grid_w x grid_h, the spans so far */
} scan;

static void build(scan *s, const ex_primitive *prim)
{
    s->n = s->horizontal = 0;
    s->nv = prim->count;
    s->y0 = 1 << 30;
    s->y1 = -(1 << 30);
    for (int i = 0; i < prim->count; i++) {
        int j = (i + 1) % prim->count;
        int64_t ax = ex_snap(prim->pts[i].x), ay = ex_snap(prim->pts[i].y);
        int64_t bx = ex_snap(prim->pts[j].x), by = ex_snap(prim->pts[j].y);
        s->v[i] = (sr_point2){ ax / 256.0, ay / 256.0 };
        if (ay == by) {
            s->horizontal++;
            continue;
        }
        edge e = ay < by ? (edge){ ax, ay, bx, by, +1, 0, 0, i } : (edge){ bx, by, ax, ay, -1, 0, 0, i };
        e.first = (int)ceil_div(e.y0 - 128, 256);
        e.last = (int)ceil_div(e.y1 - 128, 256) - 1;
        if (e.first > e.last) {
            s->horizontal++;   /* between two sample heights: crosses none either */
            continue;
        }
        s->y0 = e.first < s->y0 ? e.first : s->y0;
        s->y1 = e.last > s->y1 ? e.last : s->y1;
        s->e[s->n++] = e;
    }
}

static void draw_polygon(ex_canvas *c, const scan *s, bool names)
{
    ex_outline(c, s->v, s->nv, true, EX_EDGE, 1.5);
    for (int i = 0; i < s->nv && names; i++) {
        char name[16];
        snprintf(name, sizeof name, "V%d", i);
        ex_dot(c, s->v[i], c->zoom >= 20 ? 3.5 : c->zoom * 0.18, EX_EDGE);
        ex_label(c, s->v[i], name, EX_EDGE);
    }
}

static void draw_filled(ex_canvas *c, const scan *s, sr_rgba color)
{
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            if (s->filled[y * c->grid_w + x]) {
                ex_cell(c, x, y, color);
            }
        }
    }
}

/* Append to buf (size n) as snprintf would, never past its end. */
__attribute__((format(printf, 3, 4)))
static void add(char *buf, size_t n, const char *fmt, ...)
{
    size_t len = strlen(buf);
    if (len + 1 >= n) {
        return;
    }
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf + len, n - len, fmt, ap);
    va_end(ap);
}

static const char *rule_name(sr_fill_rule rule)
{
    return rule == SR_EVENODD ? "even-odd (parity)" : "nonzero (winding)";
}

/* Frame 2: the edge table, one line per edge in bucket order. */
static void edge_table_frame(ex_canvas *c, const scan *s)
{
    ex_begin(c);
    draw_polygon(c, s, true);
    char cap[4096] = "";
    add(cap, sizeof cap,
        "2. Edge table: each edge bucketed at its first scanline (active while "
        "ymin <= y+1/2 < ymax). Dropped: %d edge%s that cross%s no scanline (horizontal, or between two "
        "scanlines' samples).\n",
        s->horizontal, s->horizontal == 1 ? "" : "s", s->horizontal == 1 ? "es" : "");
    for (int y = s->y0; y <= s->y1; y++) {
        for (int i = 0; i < s->n; i++) {
            const edge *e = &s->e[i];
            if (e->first != y) {
                continue;
            }
            double x = cross_x(e, y);
            ex_dot(c, (sr_point2){ x, y + 0.5 }, 3, EX_HILITE);
            /* the name at the edge's middle: at the first crossing it
             * would sit on the name of the vertex the edge starts at */
            char name[8];
            snprintf(name, sizeof name, "e%d", e->id);
            ex_label(c, (sr_point2){ (e->x0 + e->x1) / 512.0, (e->y0 + e->y1) / 512.0 }, name,
                     EX_HILITE);
            add(cap, sizeof cap, "y=%d: e%d x=%.2f 1/m=%+.3f to y=%d, %s\n", y, e->id, x,
                (double)(e->x1 - e->x0) / (double)(e->y1 - e->y0), e->last,
                e->dir > 0 ? "down" : "up");
        }
    }
    ex_end(c, cap);
}

/* One scanline: the AET, its crossings and the spans. */
static void scanline_frame(ex_canvas *c, scan *s, int y, sr_fill_rule rule, int step)
{
    int aet[EX_MAX_POINTS], n = 0;
    for (int i = 0; i < s->n; i++) {
        if (s->e[i].first <= y && y <= s->e[i].last) {
            aet[n++] = i;
        }
    }
    for (int k = 1; k < n; k++) {   /* sorted by crossing pixel, then x */
        int v = aet[k], j = k - 1;
        while (j >= 0 && (cross_pixel(&s->e[aet[j]], y) > cross_pixel(&s->e[v], y) ||
                          (cross_pixel(&s->e[aet[j]], y) == cross_pixel(&s->e[v], y) &&
                           cross_x(&s->e[aet[j]], y) > cross_x(&s->e[v], y)))) {
            aet[j + 1] = aet[j];
            j--;
        }
        aet[j + 1] = v;
    }
    char cap[4096] = "";
    add(cap, sizeof cap, "%d. Scanline y=%d (samples at y=%.1f).", step, y, y + 0.5);
    bool added = false;
    for (int i = 0; i < s->n; i++) {
        if (s->e[i].first == y) {
            add(cap, sizeof cap, "%s e%d", added ? "," : " From the ET:", s->e[i].id);
            added = true;
        }
    }
    add(cap, sizeof cap, "%s", added ? "." : "");
    bool dropped = false;
    for (int i = 0; i < s->n; i++) {
        if (s->e[i].last == y - 1) {
            add(cap, sizeof cap, "%s e%d", dropped ? "," : " Ended:", s->e[i].id);
            dropped = true;
        }
    }
    add(cap, sizeof cap, "%s\nAET by x:", dropped ? "." : "");
    int w = 0, span_pixels = 0;
    ex_begin(c);
    draw_filled(c, s, EX_INK);
    for (int k = 0; k < n; k++) {
        const edge *e = &s->e[aet[k]];
        w += rule == SR_EVENODD ? 1 : e->dir;
        add(cap, sizeof cap, " e%d %.2f (%s%d)", e->id, cross_x(e, y),
            rule == SR_EVENODD ? "count " : "w ", w);
        if (k + 1 < n && inside(rule, w)) {
            int64_t xl = cross_pixel(e, y), xr = cross_pixel(&s->e[aet[k + 1]], y);
            for (int64_t x = xl; x < xr; x++) {
                if (x >= 0 && x < c->grid_w && y >= 0 && y < c->grid_h) {
                    s->filled[y * c->grid_w + x] = 1;
                    ex_cell(c, (int)x, y, EX_CELL_IN);
                }
                span_pixels++;
            }
            if (xl < xr) {
                add(cap, sizeof cap, " [span %lld..%lld]", (long long)xl, (long long)xr - 1);
            }
        }
    }
    draw_polygon(c, s, false);
    for (int k = 0; k < n;) {
        /* crossings closer than a label's width share one ("1,2"): two
         * labels would run together into "12" */
        sr_point2 p = { cross_x(&s->e[aet[k]], y), y + 0.5 };
        char label[64];
        int len = snprintf(label, sizeof label, "%d", k + 1);
        ex_dot(c, p, 3, EX_HILITE);
        int next = k + 1;
        while (next < n && len < (int)sizeof label - 8) {
            double x = cross_x(&s->e[aet[next]], y);
            if ((x - p.x) * c->zoom > sr_text_width(label, c->text_scale) + 8) {
                break;
            }
            ex_dot(c, (sr_point2){ x, y + 0.5 }, 3, EX_HILITE);
            len += snprintf(label + len, sizeof label - (size_t)len, ",%d", next + 1);
            next++;
        }
        ex_label(c, p, label, EX_HILITE);
        k = next;
    }
    add(cap, sizeof cap,
        "\n%s: inside after an %s crossing count. %d pixel%s whose centre%s between "
        "an inside pair of crossings.",
        rule_name(rule), rule == SR_EVENODD ? "odd" : "nonzero", span_pixels,
        span_pixels == 1 ? "" : "s", span_pixels == 1 ? " lies" : "s lie");
    ex_end(c, cap);
}

/* Whether scanline y has something on the grid: a crossing near it (its
 * dot and label) or the grid's row inside, which with no crossing on it is
 * all inside or all outside, as its first pixel is. */
static bool row_shown(const ex_canvas *c, const scan *s, int y, sr_fill_rule rule)
{
    int w = 0;
    for (int i = 0; i < s->n; i++) {
        const edge *e = &s->e[i];
        if (e->first > y || y > e->last) {
            continue;
        }
        double x = cross_x(e, y);
        if (x >= -1 && x <= c->grid_w + 1) {
            return true;
        }
        if (cross_pixel(e, y) <= 0) {
            w += rule == SR_EVENODD ? 1 : e->dir;
        }
    }
    return inside(rule, w);
}

/* Scanlines first..last, whose crossings and spans are off the grid, as
 * one frame; the edges that join or leave the AET on them are named, so
 * the next scanline's AET reads on from the one before. */
static void off_rows_frame(ex_canvas *c, scan *s, int first, int last, int step)
{
    char cap[1024] = "";
    if (first == last) {
        add(cap, sizeof cap, "%d. Scanline y=%d: its crossings and spans are off the grid, not "
            "shown.", step, first);
    } else {
        add(cap, sizeof cap, "%d. Scanlines y=%d to %d: their crossings and spans are off the "
            "grid, not shown.", step, first, last);
    }
    bool any = false;
    for (int i = 0; i < s->n; i++) {
        if (s->e[i].first >= first && s->e[i].first <= last) {
            add(cap, sizeof cap, "%s e%d", any ? "," : " From the ET:", s->e[i].id);
            any = true;
        }
    }
    add(cap, sizeof cap, "%s", any ? "." : "");
    any = false;
    for (int i = 0; i < s->n; i++) {
        if (s->e[i].last >= first - 1 && s->e[i].last < last) {
            add(cap, sizeof cap, "%s e%d", any ? "," : " Ended:", s->e[i].id);
            any = true;
        }
    }
    add(cap, sizeof cap, "%s", any ? "." : "");
    ex_begin(c);
    draw_filled(c, s, EX_INK);
    draw_polygon(c, s, false);
    ex_end(c, cap);
}

sr_result explain_scanline(ex_canvas *c, const ex_primitive *prim)
{
    scan s;
    build(&s, prim);
    uint8_t filled[256 * 256];
    memset(filled, 0, sizeof filled);
    s.filled = filled;

    ex_begin(c);
    draw_polygon(c, &s, true);
    char cap[1024];
    snprintf(cap, sizeof cap,
             "1. The polygon, %d vertices snapped to 1/256 pixel; edge ei runs from Vi to "
             "the next vertex. A pixel is filled when its centre is inside under the %s "
             "rule. The scan-line fill visits the scanlines top to bottom.",
             prim->count, rule_name(prim->rule));
    ex_end(c, cap);
    edge_table_frame(c, &s);

    int step = 3;
    int first = s.y0 < 0 ? 0 : s.y0, last = s.y1 >= c->grid_h ? c->grid_h - 1 : s.y1;
    int off = first;   /* the first of the scanlines off the grid before y */
    for (int y = first; y <= last + 1 && c->error == SR_OK; y++) {
        bool shown = y > last || row_shown(c, &s, y, prim->rule);
        if (shown && off < y) {
            off_rows_frame(c, &s, off, y - 1, step++);
        }
        if (!shown) {
            continue;
        }
        if (y <= last) {
            scanline_frame(c, &s, y, prim->rule, step++);
        }
        off = y + 1;
    }

    ex_begin(c);
    int total = 0;
    for (int i = 0; i < c->grid_w * c->grid_h; i++) {
        total += filled[i];
    }
    draw_filled(c, &s, EX_INK);
    draw_polygon(c, &s, true);
    snprintf(cap, sizeof cap,
             "%d. Filled: %d pixels, exactly those sr_fill_polygon draws for this polygon "
             "under the %s rule (aliased).",
             step, total, rule_name(prim->rule));
    ex_end(c, cap);
    return c->error;
}
