/* floodfill.c - draw2d stage: region filling (flood fill and boundary
 * fill, 4- or 8-connected).  Consumes a framebuffer's pixels and a seed,
 * produces the recoloured region.  Span based with an explicit stack and
 * a visited bitmap, so a region of every pixel of an 8192 x 8192 target
 * needs no recursion and O(pixels / 8) bytes.  Caller's thread only. */
#include "context.h"
#include "draw2d/paint.h"

#include <stdlib.h>
#include <string.h>

typedef struct seed { int x, y; } seed;

typedef struct region {
    sr_framebuffer *fb;
    uint8_t *visited;      /* one bit per pixel */
    uint8_t ref[4];        /* the seed color (flood) or the boundary color */
    bool match_means_inside; /* flood: matching ref is inside; boundary: outside */
    int tol;
    seed *stack;
    size_t n, cap;
    sr_context *ctx;
} region;

static bool color_matches(const region *g, uint32_t px)
{
    uint8_t c[4];
    memcpy(c, &px, sizeof c);
    for (int i = 0; i < 4; i++) {
        int d = c[i] - g->ref[i];
        if (d > g->tol || -d > g->tol) {
            return false;
        }
    }
    return true;
}

/* inside() of the span fill: in bounds, not yet set, and part of the region. */
static bool inside(const region *g, int x, int y)
{
    if (x < 0 || y < 0 || x >= g->fb->width || y >= g->fb->height) {
        return false;
    }
    size_t i = (size_t)y * (size_t)g->fb->width + (size_t)x;
    if (g->visited[i >> 3] & (1u << (i & 7))) {
        return false;
    }
    return color_matches(g, g->fb->color[i]) == g->match_means_inside;
}

static bool push(region *g, int x, int y)
{
    if (g->n == g->cap) {
        size_t cap = g->cap ? g->cap * 2 : 1024;
        seed *s = sr__alloc(g->ctx, cap * sizeof *s);
        if (!s) {
            return false;
        }
        if (g->n) {
            memcpy(s, g->stack, g->n * sizeof *s);
        }
        sr__free(g->ctx, g->stack);
        g->stack = s;
        g->cap = cap;
    }
    g->stack[g->n++] = (seed){ x, y };
    return true;
}

static sr_result span_fill(region *g, int sx, int sy, bool conn8, uint32_t fill, size_t *count)
{
    size_t filled = 0;
    int e = conn8 ? 1 : 0;
    if (inside(g, sx, sy) && !push(g, sx, sy)) {
        return SR_OUT_OF_MEMORY;
    }
    uint32_t w = (uint32_t)g->fb->width;
    while (g->n) {
        seed s = g->stack[--g->n];
        if (!inside(g, s.x, s.y)) {
            continue;
        }
        /* Extend to the whole run l..r and set it. */
        int l = s.x, r = s.x;
        while (inside(g, l - 1, s.y)) {
            l--;
        }
        while (inside(g, r + 1, s.y)) {
            r++;
        }
        uint32_t *row = g->fb->color + (size_t)s.y * w;
        for (int x = l; x <= r; x++) {
            size_t i = (size_t)s.y * w + (size_t)x;
            g->visited[i >> 3] |= (uint8_t)(1u << (i & 7));
            row[x] = fill;
        }
        filled += (size_t)(r - l + 1);
        /* One seed per run of inside pixels in the rows above and below,
         * across l-e .. r+e (diagonal neighbours when 8-connected). */
        for (int ny = s.y - 1; ny <= s.y + 1; ny += 2) {
            int i = l - e;
            while (i <= r + e) {
                if (inside(g, i, ny)) {
                    if (!push(g, i, ny)) {
                        return SR_OUT_OF_MEMORY;
                    }
                    while (i <= r + e && inside(g, i, ny)) {
                        i++;
                    }
                } else {
                    i++;
                }
            }
        }
    }
    *count = filled;
    return SR_OK;
}

static sr_result region_fill(sr_context *ctx, const char *fn, sr_framebuffer *fb, int x, int y,
                             sr_rgba fill, const sr_rgba *boundary,
                             const sr_region_fill_desc *desc, size_t *filled)
{
    if (filled) {
        *filled = 0;
    }
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "%s: ctx is NULL", fn);
    }
    if (!fb) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: fb is NULL", fn);
    }
    sr_region_fill_desc d = desc ? *desc : (sr_region_fill_desc){0};
    if (d.connectivity == SR_CONNECT_DEFAULT) {
        d.connectivity = SR_CONNECT_4;
    }
    if (d.connectivity != SR_CONNECT_4 && d.connectivity != SR_CONNECT_8) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_region_fill_desc.connectivity %d is invalid",
                        fn, (int)d.connectivity);
    }
    if (d.tolerance < 0 || d.tolerance > 255) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "%s: sr_region_fill_desc.tolerance must be in 0..255 (got %d)", fn,
                        d.tolerance);
    }
    if (x < 0 || y < 0 || x >= fb->width || y >= fb->height) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: seed (%d, %d) is outside the %d x %d framebuffer",
                        fn, x, y, fb->width, fb->height);
    }
    sr__paint fill_paint, boundary_paint;
    if (!sr__paint_init(&fill_paint, fill, false)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: fill color is not finite", fn);
    }
    if (boundary && !sr__paint_init(&boundary_paint, *boundary, false)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: boundary color is not finite", fn);
    }
    sr_result r2d = sr__fb_begin_2d(ctx, fn, fb);
    if (r2d != SR_OK) {
        return r2d;
    }
    size_t pixels = (size_t)fb->width * (size_t)fb->height;
    region g = { .fb = fb, .tol = d.tolerance, .ctx = ctx };
    g.visited = sr__calloc(ctx, (pixels + 7) / 8, 1);
    if (!g.visited) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "%s: no memory for the visited bitmap", fn);
    }
    if (boundary) {
        memcpy(g.ref, boundary_paint.rgba, 4);
        g.match_means_inside = false;
    } else {
        uint32_t s = fb->color[(size_t)y * (size_t)fb->width + (size_t)x];
        memcpy(g.ref, &s, 4);
        g.match_means_inside = true;
    }
    size_t count = 0;
    sr_result r = span_fill(&g, x, y, d.connectivity == SR_CONNECT_8, fill_paint.packed, &count);
    sr__free(ctx, g.visited);
    sr__free(ctx, g.stack);
    if (r != SR_OK) {
        return sr__fail(ctx, r, "%s: no memory for the span stack", fn);
    }
    if (filled) {
        *filled = count;
    }
    sr__ok(ctx);
    return SR_OK;
}

sr_result sr_flood_fill(sr_context *ctx, sr_framebuffer *fb, int x, int y, sr_rgba fill,
                        const sr_region_fill_desc *desc, size_t *filled)
{
    return region_fill(ctx, "sr_flood_fill", fb, x, y, fill, NULL, desc, filled);
}

sr_result sr_boundary_fill(sr_context *ctx, sr_framebuffer *fb, int x, int y, sr_rgba fill,
                           sr_rgba boundary, const sr_region_fill_desc *desc, size_t *filled)
{
    return region_fill(ctx, "sr_boundary_fill", fb, x, y, fill, &boundary, desc, filled);
}
