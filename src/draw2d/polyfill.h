/* polyfill.h - draw2d stage, internal: the polygon scan converters shared
 * by the fills, the Gouraud polygons, the strokes and the curves.
 * Setup (sr__edges_from_polygon) validates and snaps float vertices to
 * 24.8 fixed point ("q8") edges; the scan converters see only those
 * integer edges and hand out spans or coverage rows through a callback.
 * Single-threaded: the caller's thread runs everything. */
#ifndef SR_DRAW2D_POLYFILL_H
#define SR_DRAW2D_POLYFILL_H

#include "softrast.h"

#include <stdint.h>

/* An edge in q8 (1/256 pixel), oriented so y0 < y1; dir is +1 when the
 * contour runs that way (downwards) and -1 when it ran upwards.  v0 and
 * v1 are the indices of the polygon vertices at (x0, y0) and (x1, y1).
 * Horizontal edges never appear: they cross no scanline.
 * Bit budget: |coordinate| <= SR_MAX_COORD2D * 16 (supersampling) =
 * 2^22 px = 2^30 q8, so every product in the edge-table arithmetic,
 * (q8 x) * (q8 dy) and (q8 dy) * (q8 dx), stays below 2^62. */
typedef struct sr__edge2 {
    int64_t x0, y0, x1, y1;
    int dir;
    int v0, v1;
} sr__edge2;

/* What a scan converter hands out: pixels x0..x1-1 of row y, with
 * coverage cov[x - x0] (0..255), or full coverage when cov is NULL.  The
 * edge-table converter also names the two active edges that bound the
 * span (edge_l, edge_r, indices into the edge array; -1 otherwise) and
 * the scanline's sample height yc (pixel units, y + 1/2). */
typedef struct sr__span {
    int y, x0, x1;
    const uint8_t *cov;
    int edge_l, edge_r;
    double yc;
} sr__span;

typedef void (*sr__span_fn)(void *user, const sr__span *span);

/* Validate a polygon and build its edges, vertices scaled by `scale`
 * (1, or n for n x n supersampling) before snapping.  `fn` names the
 * public call in messages.  *edges is allocated on ctx (free with
 * sr__free); *count may be 0. */
sr_result sr__edges_from_polygon(sr_context *ctx, const char *fn, const sr_polygon2 *poly,
                                 int scale, sr__edge2 **edges, int *count);

/* The window every converter is clipped to: [x0, x1) x [y0, y1) pixels. */
typedef struct sr__window { int x0, y0, x1, y1; } sr__window;

/* Scan-line fill with an edge table and an active edge table (point
 * sampling at pixel centres, docs/raster-rules.md §10.2). */
sr_result sr__scan_edge_table(sr_context *ctx, const sr__edge2 *edges, int count,
                              sr_fill_rule rule, sr__window win, sr__span_fn fn, void *user);
/* The same pixels from the same edge table without sorting the AET: each
 * crossing adds its direction to a winding cell per pixel and a prefix
 * sum along the row gives the winding at each pixel centre.  Touching
 * spans come merged and name no edges (edge_l = edge_r = -1).  The fills
 * use it; sr__scan_edge_table is the reference it is tested against. */
sr_result sr__scan_winding_cells(sr_context *ctx, const sr__edge2 *edges, int count,
                                 sr_fill_rule rule, sr__window win, sr__span_fn fn, void *user);
/* Clipping scratch (polyclip.c): the points in a, b the room a stage
 * writes into; capacities in points. */
typedef struct sr__clip_scratch {
    sr_point2 *a, *b;
    long long cap_a, cap_b;
} sr__clip_scratch;
/* Make *buf hold at least `need` points (its contents need not survive). */
bool sr__clip_reserve(sr_context *ctx, sr_point2 **buf, long long *cap, long long need);
/* One Sutherland-Hodgman stage on s->a (*n points, replaced) against the
 * half-plane sign * (x or y, by axis 0 or 1, - bound) >= 0; false when
 * out of memory. */
bool sr__clip_axis_stage(sr_context *ctx, sr__clip_scratch *s, int axis, double bound,
                         double sign, int *n);
/* A validated polygon of finite points cut, contour by contour, to the
 * window grown by a guard margin and kept within SR_MAX_COORD2D: inside
 * that rectangle every point keeps its winding number.  out->points and
 * out->contour_counts are allocated on ctx (guardclip.c). */
sr_result sr__guard_clip(sr_context *ctx, const char *fn, const sr_polygon2 *poly,
                         sr__window win, sr_polygon2 *out);
/* Exact area coverage by signed-area accumulation (docs/raster-rules.md §10.3).
 * It works only on the columns the edges reach and computes a row with
 * only vertical edges once for the rows below it that have the same ones
 * (a rectangle's inside). */
sr_result sr__scan_area(sr_context *ctx, const sr__edge2 *edges, int count, sr_fill_rule rule,
                        sr__window win, sr__span_fn fn, void *user);
/* The same coverage, every row and column of the window walked: the
 * reference sr__scan_area is tested against. */
sr_result sr__scan_area_each_row(sr_context *ctx, const sr__edge2 *edges, int count,
                                 sr_fill_rule rule, sr__window win, sr__span_fn fn, void *user);
/* n x n supersampling: edges built with scale n; samples at
 * (x + (i + 1/2)/n, y + (j + 1/2)/n). */
sr_result sr__scan_supersample(sr_context *ctx, const sr__edge2 *edges, int count,
                               sr_fill_rule rule, int n, sr__window win,
                               sr__span_fn fn, void *user);

/* sr_polygon_coverage, its messages naming the public call fn. */
sr_result sr__polygon_coverage(sr_context *ctx, const char *fn, const sr_polygon2 *poly,
                               const sr_fill_desc *desc, int x0, int y0, int w, int h,
                               uint8_t *mask, size_t stride);
/* Resolve a fill desc (NULL allowed) to its defaults, validating it. */
sr_result sr__fill_desc_defaults(sr_context *ctx, const char *fn, const sr_fill_desc *in,
                                 sr_fill_desc *out);
/* Run the converter the desc selects over a polygon. */
sr_result sr__rasterize_polygon(sr_context *ctx, const char *fn, const sr_polygon2 *poly,
                                const sr_fill_desc *desc, sr__window win,
                                sr__span_fn fn_span, void *user);

/* True when every component of the n colors is finite (gouraud.c). */
bool sr__colors_finite(const sr_rgba *c, int n);

#endif
