/* explain.h - `softrast explain`: one primitive through one algorithm,
 * step by step.  Each algorithm (explain_*.c) draws its steps as frames on
 * a canvas: the primitive's pixel grid magnified `zoom` times, with sample
 * points, edges and marks over it and a caption below, all drawn by the
 * library (cells and marks as polygons, captions with sr_draw_text).  The
 * last frame of every algorithm shows, cell for cell, the pixels the
 * library draws for the primitive. */
#ifndef SR_EXPLAIN_H
#define SR_EXPLAIN_H

#include "softrast.h"

#include <stdbool.h>
#include <stdint.h>

#define EX_MARGIN 16      /* frame pixels around the grid: its top-left corner */
#define EX_MAX_POINTS 64  /* vertices of a --polygon */
#define EX_MAX_FRAME_BYTES ((size_t)1 << 30)  /* all frames are kept for the sheet */

/* perspective's last frame: the whole triangle as sr_draw interpolates it
 * (SR_INTERP_PERSPECTIVE, SR_INTERP_AFFINE) or as sr_fill_gouraud's
 * FillPoly/FillSpan (SR_GOURAUD_INCREMENTAL) does in screen space. */
typedef enum ex_interp { EX_INTERP_PERSPECTIVE, EX_INTERP_AFFINE, EX_INTERP_FILLSPAN } ex_interp;

/* interpolation: which of the three ways to interpolate it shows. */
typedef enum ex_method { EX_METHOD_ALL, EX_METHOD_BILINEAR, EX_METHOD_PLANE,
                         EX_METHOD_BARYCENTRIC } ex_method;

/* transform's viewing pipeline: M_O, the camera and the projection. */
typedef struct ex_view {
    double rotate;          /* M_O: degrees about y, then */
    double translate[3];    /* a translation */
    double eye[3], target[3], up[3];
    double fov;             /* degrees: perspective's field of view, across the smaller side */
    double near_far[2];     /* distances in front of the eye */
    bool orthographic;      /* sr_ortho instead of sr_perspective */
    bool stretch;           /* aspect 1: NDC's square stretched over the viewport */
} ex_view;

/* The primitive the user gave (window coordinates, pixels, y down). */
typedef enum ex_kind { EX_NONE, EX_TRIANGLE, EX_POLYGON, EX_LINE, EX_TRIANGLES, EX_CIRCLE,
               EX_CUBIC, EX_CLIP_TRIANGLE, EX_OBJECT_TRIANGLE } ex_kind;

typedef struct ex_primitive {
    ex_kind kind;
    sr_point2 pts[EX_MAX_POINTS];
    /* a value at each vertex: --triangles' window depth (0..1), --w's eye
     * distance (perspective), --intensity's I (fillpoly); --circle's
     * radius in z[0] (its centre in pts[0]); --tolerance in z[0] (cubic) */
    double z[EX_MAX_POINTS];
    int count;
    sr_fill_rule rule;      /* polygons: SR_EVENODD or SR_NONZERO */
    double window[4];       /* clip: xmin, ymin, xmax, ymax */
    int samples;            /* msaa: samples per pixel */
    int row;                /* perspective: the scanline of the span */
    int seed[2];            /* floodfill: the seed pixel */
    double clip[3][4];      /* clip4d: the triangle in clip space, x, y, z, w */
    int connectivity;       /* floodfill: 4 or 8 */
    sr_rasterizer rasterizer;        /* triangle: the rasterizer whose steps are shown */
    ex_interp interpolation;         /* perspective: what the last frame draws */
    ex_method method;                /* interpolation: the method(s) shown */
    ex_view view;                    /* transform: object coordinates in pts (x, y) and z */
    double highlight[2];             /* gouraud: where the light's highlight peaks */
    double shininess;                /* gouraud: the Blinn-Phong exponent n */
    double offset[2];                /* zfight: B's polygon offset, factor and units */
    double line_width;               /* aaline, area: the line's width, pixels */
    sr_line_cap line_cap;            /* area: SR_LINE_AREA's ends */
} ex_primitive;

/* The frames drawn so far (RGBA8, all the same size) and the canvas the
 * next one is drawn on. */
typedef struct ex_canvas {
    sr_context *ctx;
    sr_framebuffer *fb;
    int grid_w, grid_h, zoom;
    int width, height;
    int text_scale, caption_y, caption_lines;
    int caption_needed;       /* the most lines a caption took (drawn or not) */
    int labels[16][4];        /* this frame's labels so far: x, y, w, h */
    int label_count;
    bool cell_text;           /* this frame has text in its cells (ex_cell_text) */
    uint8_t *text_cells;      /* which: grid_w x grid_h, 1 where a cell has text */
    uint8_t **frames;
    int frame_count, frame_cap;
    size_t kept_bytes;        /* of all the frames, at most EX_MAX_FRAME_BYTES */
    bool too_many;            /* ex_end refused a frame over that limit */
    sr_result error;          /* the first failure; later calls do nothing */
} ex_canvas;

/* The course's colours, shared so every algorithm reads the same way. */
extern const sr_rgba EX_BG, EX_GRID, EX_INK, EX_CELL_OUT, EX_CELL_IN, EX_TIE,
    EX_EDGE, EX_HILITE, EX_TEXT, EX_BAD;

/* A canvas for frames of grid_w x grid_h cells of zoom x zoom frame
 * pixels, with room for caption_lines lines of caption under them. */
sr_result ex_canvas_init(ex_canvas *c, sr_context *ctx, int grid_w, int grid_h, int zoom,
                         int caption_lines);
void ex_canvas_free(ex_canvas *c);

/* Start a frame: background, empty cells, grid lines. */
void ex_begin(ex_canvas *c);
void ex_cell(ex_canvas *c, int x, int y, sr_rgba color);
/* A small mark at the centre of cell (x, y): the sample point. */
void ex_sample(ex_canvas *c, int x, int y, sr_rgba color);
/* A ring around the sample point of cell (x, y). */
void ex_ring(ex_canvas *c, int x, int y, sr_rgba color);
/* A diagonal cross over cell (x, y). */
void ex_cross(ex_canvas *c, int x, int y, sr_rgba color);
/* The same cross kept above the band ex_cell_text writes in, for a cell
 * whose value it marks (over the whole cell when no text fits). */
void ex_cross_above_text(ex_canvas *c, int x, int y, sr_rgba color);
/* Text centred in cell (x, y), only when it fits; whether it was drawn. */
bool ex_cell_text(ex_canvas *c, int x, int y, const char *text, sr_rgba color);
/* Text in white on a disc of `color` filling cell (x, y), as large as
 * fits; false, drawing nothing, when it does not fit. */
bool ex_cell_badge(ex_canvas *c, int x, int y, const char *text, sr_rgba color);
/* A segment or closed outline in grid coordinates (pixels). */
void ex_segment(ex_canvas *c, sr_point2 a, sr_point2 b, sr_rgba color, double width);
void ex_outline(ex_canvas *c, const sr_point2 *pts, int n, bool closed, sr_rgba color,
                double width);
/* A polygon in grid coordinates (near the grid) filled with color, its
 * alpha blended over the frame, antialiased. */
void ex_fill(ex_canvas *c, const sr_point2 *pts, int n, sr_rgba color);
void ex_dot(ex_canvas *c, sr_point2 p, double radius, sr_rgba color);
/* A label beside a point in grid coordinates; in a frame with cell text,
 * on a light box and out of the band the cells' text is written in. */
void ex_label(ex_canvas *c, sr_point2 p, const char *text, sr_rgba color);
/* The segment a-b with its ends marked and named A and B ("A=B" when they
 * are too close for two names). */
void ex_line_ab(ex_canvas *c, sr_point2 a, sr_point2 b);
/* A weight in [0, 1] short enough for a cell: ".74" (no leading 0), "1". */
void ex_weight_text(char *buf, size_t size, double w);
/* A cell's colour for weight c: the ink over the empty cell's white with
 * opacity c, mixed in linear light as sr_draw_line mixes its antialiased
 * lines. */
sr_rgba ex_ink_over_white(double c);
/* The pixels of the grid that sr_draw_line draws for the segments
 * through pts (closed: and back to the first), 1 in mask, row by row. */
sr_result ex_polyline_pixels(ex_canvas *c, const sr_point2 *pts, int n, bool closed,
                             uint8_t *mask);
/* Start a frame with the line a-b as sr_draw_line draws it (desc) in
 * the ink over white, each cell its pixel's colour; the cells drawn
 * (not left white). */
int ex_line_frame(ex_canvas *c, sr_point2 a, sr_point2 b, const sr_line_desc *desc);
/* The caption under the grid, word-wrapped; then the frame is kept. */
void ex_end(ex_canvas *c, const char *caption);

/* The algorithms: each draws its frames; SR_OK or the first failure. */
typedef sr_result (*ex_algorithm_fn)(ex_canvas *c, const ex_primitive *prim);
sr_result explain_triangle(ex_canvas *c, const ex_primitive *prim);
sr_result explain_scanline(ex_canvas *c, const ex_primitive *prim);
sr_result explain_msaa(ex_canvas *c, const ex_primitive *prim);
sr_result explain_clip(ex_canvas *c, const ex_primitive *prim);
sr_result explain_bresenham(ex_canvas *c, const ex_primitive *prim);
sr_result explain_dda(ex_canvas *c, const ex_primitive *prim);
sr_result explain_wu(ex_canvas *c, const ex_primitive *prim);
sr_result explain_aaline(ex_canvas *c, const ex_primitive *prim);
sr_result explain_area(ex_canvas *c, const ex_primitive *prim);
sr_result explain_zbuffer(ex_canvas *c, const ex_primitive *prim);
sr_result explain_perspective(ex_canvas *c, const ex_primitive *prim);
sr_result explain_fillpoly(ex_canvas *c, const ex_primitive *prim);
sr_result explain_circle(ex_canvas *c, const ex_primitive *prim);
sr_result explain_fwdiff(ex_canvas *c, const ex_primitive *prim);
sr_result explain_floodfill(ex_canvas *c, const ex_primitive *prim);
sr_result explain_clip4d(ex_canvas *c, const ex_primitive *prim);
sr_result explain_transform(ex_canvas *c, const ex_primitive *prim);
sr_result explain_gouraud(ex_canvas *c, const ex_primitive *prim);
sr_result explain_zfight(ex_canvas *c, const ex_primitive *prim);
sr_result explain_interpolation(ex_canvas *c, const ex_primitive *prim);
/* Whether transform can show prim on a grid_w x grid_h viewport: a camera
 * frame, every vertex inside near and far; else false with why. */
bool ex_transform_check(const ex_primitive *prim, int grid_w, int grid_h, char *why,
                        size_t size);

/* Whether both ends of a line are on pixel centres (x + 1/2, y + 1/2),
 * which the midpoint algorithm's integer decision variable needs. */
bool ex_line_on_centres(const ex_primitive *prim);

/* A triangle as the pipeline sets it up (explain_triangle.c). */
typedef struct ex_tri {
    int64_t x[3], y[3];     /* snapped, q8; ordered so that inside is E > 0 */
    bool top_left[3];       /* edge i = vertex i -> vertex i+1 */
    int64_t area2;
} ex_tri;

/* Snap and order; whether two vertices were swapped (clockwise given). */
bool ex_tri_setup(ex_tri *t, const ex_primitive *prim);
/* The same for points first..first+2 of prim, with the value z[] of each
 * vertex (prim->z) kept beside it through the reordering. */
bool ex_tri_setup_at(ex_tri *t, double z[3], const ex_primitive *prim, int first);
/* The barycentric weights of the point (sx, sy) in q8: the edge function
 * of the edge opposite each vertex over twice the area. */
void ex_tri_weights(const ex_tri *t, int64_t sx, int64_t sy, double l[3]);
/* Edge function i at the point (sx, sy) in q8. */
int64_t ex_tri_edge(const ex_tri *t, int i, int64_t sx, int64_t sy);
/* Whether the point (sx, sy) in q8 is covered, ties by the top-left rule. */
bool ex_tri_covers(const ex_tri *t, int64_t sx, int64_t sy);
/* Outline, vertices and their names; edge `hilite` (or -1) stressed. */
void ex_tri_draw(ex_canvas *c, const ex_tri *t, int hilite);
/* A sample point at every pixel centre of the grid. */
void ex_tri_samples(ex_canvas *c);
/* The last frame: the covered pixels, with the caption's first words. */
void ex_tri_coverage(ex_canvas *c, const ex_tri *t, const char *lead);
/* explain_triangle_walk.c: frames 2.. of the scan-line and the
 * barycentric rasterizers (explain_triangle draws the half-space one). */
void ex_tri_scanline_steps(ex_canvas *c, const ex_tri *t);
void ex_tri_barycentric_steps(ex_canvas *c, const ex_tri *t);

/* t's vertices by y, then x: A (top), B (middle), C (bottom) in o. */
void ex_tri_order_by_y(const ex_tri *t, int o[3]);
/* An intensity 0..1 in cell (x, y): "1", ".55", in white on dark cells. */
void ex_cell_value(ex_canvas *c, int x, int y, float v);

/* explain_interp_methods.c: a vertex value in[i] at each vertex of t
 * interpolated three ways, each into I (gw x gh floats) at the pixel
 * centres t covers (ex_tri_covers), NAN at the others. */
typedef struct ex_interp_row {   /* bilinear: one scanline */
    int x0, x1;                  /* its covered pixels x0..x1-1; none when x0 = x1 */
    const char *left, *right;    /* the edges walked ("AC", "AB", "BC") */
    int fresh;                   /* bit 0: the left walk starts here, bit 1: the right */
    double xl, xr;               /* their x at the scanline centre */
    float il, ir, dI;            /* their I there, and FillSpan's step per pixel */
} ex_interp_row;
/* explain_fillpoly.c: FillPoly along the edges, FillSpan along each
 * span, at the pixels of mask (gw x gh, nonzero: covered; NULL: those t
 * covers) into I, each scanline's walk in rows[gh]. */
void ex_fillpoly_spans(const ex_tri *t, const double in[3], const uint8_t *mask, int gw, int gh,
                       float *I, ex_interp_row *rows);
/* ex_fillpoly_spans at t's pixels. */
void ex_interp_bilinear(const ex_tri *t, const double in[3], int gw, int gh, float *I,
                        ex_interp_row *rows);
/* I = a x + b y + c through the vertices (x, y in pixels) into abc;
 * false, a = b = 0, when t has no area. */
bool ex_interp_plane_coefficients(const ex_tri *t, const double in[3], double abc[3]);
/* The plane at the first centre of the covered pixels' bounding box
 * (origin: its pixel, -1 when none), stepped in float by a per pixel
 * and b per row. */
void ex_interp_plane(const ex_tri *t, const double in[3], int gw, int gh, float *I,
                     double abc[3], int origin[2]);
/* I = l0 I0 + l1 I1 + l2 I2, li the barycentric weights of each centre
 * (ex_tri_weights), kept in lambda (3 per pixel) unless it is NULL. */
void ex_interp_barycentric(const ex_tri *t, const double in[3], int gw, int gh, float *I,
                           float *lambda);

/* Snap to the 1/256-pixel grid the rasterizers use. */
int64_t ex_snap(double v);

/* Algorithm i (0, 1, ...) of `softrast explain`: its name, one-line help,
 * example primitive and default view; false past the last.  The web pages
 * (web/) list the algorithms and start from their examples with it. */
bool explain_algorithm(int i, const char **name, const char **summary, ex_primitive *example,
                       int *grid_w, int *grid_h, int *zoom);

#endif
