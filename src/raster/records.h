/* records.h - the contract between setup and the rasterizers: the records
 * sr_tri, sr_line and sr_point that setup (setup.c, line_setup.c, the
 * front-end threads) writes once per primitive into the bins, and the tile
 * jobs' rasterizers read back (triangle.c, scanline.c, barycentric.c,
 * msaa.c, shader.c, the vector kernels, line.c, point.c).  Plain data, no
 * pointers; the inline helpers rebuild what the records leave out.
 * Internal to the library. */
#ifndef SR_RECORDS_H
#define SR_RECORDS_H

#include "softrast.h"
#include "raster/fixed.h"

#include <stddef.h>

/* Floats carried per vertex besides the position (see vertex.c for the
 * layout of each shading model).  Phong needs 10. */
#define SR_MAX_VARYINGS 16

/* Varying layouts by shading model. */
enum {
    SR_VARY_COLOR = 0,        /* UNLIT, GOURAUD: r g b a */
    SR_VARY_FLAT_EYE = 0,     /* FLAT: eye xyz, then diffuse rgba */
    SR_VARY_FLAT_COLOR = 3,
    SR_VARY_PHONG_NORMAL = 0, /* PHONG: normal xyz, eye xyz, diffuse rgba */
    SR_VARY_PHONG_EYE = 3,
    SR_VARY_PHONG_COLOR = 6,
    SR_VARY_NORMAL = 0,       /* NORMALS: normal xyz */
    SR_VARY_DEPTH_W = 0,      /* DEPTH: clip w (eye distance under perspective) */
    SR_VARY_ATTRIBUTE = 0,    /* ATTRIBUTE: the generic attribute, padded to rgba */
};

/* What binning needs of any primitive: its kind and pixel bounding box
 * (inclusive-exclusive, already trimmed to viewport and framebuffer).
 * Every set-up record starts with it. */
typedef enum sr_prim_kind {
    SR_KIND_TRIANGLE = 0,
    SR_KIND_LINE,
    SR_KIND_POINT,
} sr_prim_kind;

typedef struct sr_prim_head {
    int16_t x0, y0, x1, y1;           /* inside the framebuffer: int16_t holds them */
    uint8_t kind;                     /* sr_prim_kind */
} sr_prim_head;
_Static_assert(SR_MAX_FRAMEBUFFER_SIZE <= INT16_MAX, "box corners must fit int16_t");

/* A triangle after setup: everything the rasterizers and the fragment stage
 * need, no pointers.  Vertices are in coverage order (area2 > 0); the
 * varyings were permuted with them.  Stored in the bins with only
 * 3 x ninterp varyings (sr__record_size), so `vary` must stay last.  Every
 * triangle drawn is written here once and read back by the tile jobs, so
 * the record holds nothing that a few integer operations rebuild: with
 * four varyings it is 128 bytes, two cache lines (sr__tri_c, sr__tri_bias,
 * sr__tri_flat). */
typedef struct sr_tri {
    sr_prim_head h;
    uint8_t ninterp;                  /* varyings stored in vary[] */
    bool front : 1;
    /* The plane's values inside the triangle stay within the depth range
     * with room for rounding, so the fragment clamp is a no-op and the
     * vector kernels skip it (the result is the same either way). */
    bool z_inside : 1;
    /* Every edge value at the pixel centres of the triangle's own bounding
     * box fits in 32 bits with room for the bias (so sr__rect_fits32 holds
     * for any box the kernels draw of it), found once at setup. */
    bool fits32 : 1;
    /* Edge i is opposite vertex i: E_i(p) = a[i] X + b[i] Y + c_i, which is
     * the unnormalized barycentric weight of vertex i.  a and b are
     * differences of q8 coordinates, below 2^23 (fixed.h), so they are kept
     * in 32 bits: widen them before multiplying.  c_i and the top-left bias
     * follow from them and vertex 0 (sr__tri_c, sr__tri_bias).  The three
     * E_i sum to area2 everywhere, so area2 = c_0 + c_1 + c_2 > 0. */
    int32_t a[3], b[3];
    int32_t x0_q8, y0_q8;             /* vertex 0, snapped */
    /* Perspective weights: q_i = e_i w_i (w_i = 1/w of vertex i, or 1 in
     * affine mode). */
    float w[3];
    /* Depth plane in buffer units (x (2^n - 1) for UNORM, [0, 1] for float):
     * z = z0 + e1 dz1 + e2 dz2, polygon offset folded into z0. */
    double z0, dz1, dz2;
    /* Varying k of vertex 0, then its differences to vertices 1 and 2:
     * vary[k], vary[n + k] = v1 - v0, vary[2n + k] = v2 - v0 (n = ninterp),
     * so an attribute is v0 + l1 d1 + l2 d2.  FLAT shading's lit color
     * follows them (sr__tri_flat). */
    float vary[3 * SR_MAX_VARYINGS + 4];
} sr_tri;
_Static_assert(offsetof(sr_tri, vary) == 80, "four varyings make a 128-byte record");

/* c_i of edge i: the line through vertices i + 1 and i + 2, both of which
 * give E_i = 0.  Edges 1 and 2 pass through vertex 0; edge 0 through
 * vertex 1 = vertex 0 + (b_2, -a_2) (edge 2 runs from vertex 0 to 1).
 * Exact in int64, as setup computed it. */
static inline int64_t sr__tri_c(const sr_tri *t, int i)
{
    int64_t x = t->x0_q8, y = t->y0_q8;
    if (i == 0) {
        x += t->b[2];
        y -= t->a[2];
    }
    return -((int64_t)t->a[i] * x + (int64_t)t->b[i] * y);
}

/* y points down.  With area2 > 0 the interior has E > 0.  A top edge is
 * horizontal and runs toward +x; a left edge runs upward (dy < 0).  Samples
 * exactly on a top or left edge are inside, on any other edge outside. */
static inline bool sr__is_top_left(int64_t dx, int64_t dy)
{
    return (dy < 0) | ((dy == 0) & (dx > 0));   /* no branches: the signs are random */
}

/* Edge i's bias: 0 for a top or left edge, -1 otherwise (covered iff
 * E_i + bias_i >= 0).  Edge i runs (dx, dy) = (b_i, -a_i). */
static inline int32_t sr__tri_bias(const sr_tri *t, int i)
{
    return (int32_t)sr__is_top_left(t->b[i], -(int64_t)t->a[i]) - 1;
}

/* A triangle's edge functions as the rasterizers use them, unpacked from
 * its record once a call: E_i(X, Y) = a[i] X + b[i] Y + c[i] at q8 point
 * (X, Y), covered iff E_i + bias[i] >= 0.  Kept on the rasterizer's
 * stack, where the compiler holds them across the framebuffer's stores
 * (which, as far as it knows, might write to the record). */
typedef struct sr_edges {
    int64_t a[3], b[3], c[3], bias[3];
} sr_edges;

static inline void sr__tri_edges(const sr_tri *t, sr_edges *e)
{
    for (int i = 0; i < 3; i++) {
        e->a[i] = t->a[i];
        e->b[i] = t->b[i];
        e->c[i] = sr__tri_c(t, i);
        e->bias[i] = sr__tri_bias(t, i);
    }
}

/* Edge i, unbiased, at q8 point (X, Y). */
static inline int64_t sr__edge_at(const sr_edges *e, int i, int64_t X, int64_t Y)
{
    return e->a[i] * X + e->b[i] * Y + e->c[i];
}

/* FLAT shading's lit color, after the varyings. */
static inline const float *sr__tri_flat(const sr_tri *t)
{
    return &t->vary[3 * t->ninterp];
}

/* Tile columns whose tile rows a line's record lists for binning (a line
 * up to 320 px long along its major axis); tile indices fit a byte. */
#define SR_LINE_BIN_COLUMNS 6
_Static_assert(SR_MAX_FRAMEBUFFER_SIZE / SR_TILE_SIZE <= 256, "tile indices must fit uint8_t");
/* A wide line's path lies up to (64 - 1)/2 px (the widest line_width)
 * below or left of the segment. */
_Static_assert(SR_GUARD_BAND_MAX + 2 <= INT16_MAX && SR_GUARD_BAND_MIN - 2 - 32 > INT16_MIN,
               "a line's pixel indices must fit int16_t");

/* A line segment after setup, drawn by the diamond-exit rule from a to b
 * (b's pixel excluded).  Depth is linear in screen space along the
 * segment; varyings are interpolated perspective-correctly by the
 * projected parameter t (docs/raster-rules.md §5.5). */
typedef struct sr_line {
    sr_prim_head h;
    int32_t xa, ya, xb, yb;           /* q8 endpoints */
    int32_t width;                    /* whole pixels across the minor axis */
    bool smooth;                      /* antialiased: coverage blended, see smooth_lines */
    float half_width;                 /* smooth: half the width, pixels */
    bool front;
    int32_t ninterp;
    double za, zb;                    /* buffer units, offset folded in */
    float wa, wb;                     /* 1/w, or 1 in affine mode */
    /* The aliased walk, set up once so that each tile only clips it
     * (line.c; unused for smooth lines).  u is the major axis, v the
     * minor; column k in [k0, k1] holds the pixel v = floor((n0 + (k - k0)
     * dn) / d), d > 0, except the end's pixel (end_u, end_v; end_u is
     * INT16_MIN when the end's pixel is not on the path).  start_extra:
     * the start's pixel (start_u, start_v) is off the path and drawn after
     * it.  Pixel indices fit int16_t inside the guard band; the fields are
     * kept small, as every record of a draw that makes lines is a line's
     * size (sr__record_size). */
    bool xmajor, start_extra;
    int16_t k0, k1, start_u, start_v, end_u, end_v;
    /* The tiles it reaches, found once in setup for binning's two passes
     * (bin.c): tile rows [bin_rows[2i], bin_rows[2i + 1]] of tile column
     * bin_tu0 + i along the major axis (empty when first > last), for
     * bin_count <= SR_LINE_BIN_COLUMNS columns; more: bin.c asks
     * sr__line_tile_rows column by column. */
    uint8_t bin_count, bin_tu0;
    uint8_t bin_rows[2 * SR_LINE_BIN_COLUMNS];
    int64_t n0, d, dn;
    float flat[4];
    float vary[2 * SR_MAX_VARYINGS];  /* endpoint a's varyings, then b's */
} sr_line;

/* A point after setup: a square [x0_q8, x1_q8) x [y0_q8, y1_q8) covering
 * the pixel centres inside it, with one depth and one set of varyings. */
typedef struct sr_point {
    sr_prim_head h;
    int32_t cx, cy;                   /* centre, q8 */
    int32_t half;                     /* half the size, q8 */
    int64_t radius2;                  /* round points: squared radius in q8^2, else 0 */
    float smooth_radius;              /* smooth points: radius in pixels, else 0 */
    double z;
    bool front;
    int32_t ninterp;
    float flat[4];
    float vary[SR_MAX_VARYINGS];
} sr_point;

/* Bytes per record in the bins: the largest of the kinds a draw makes
 * with only ninterp varyings stored (and FLAT shading's color after a
 * triangle's), rounded to 16.  A draw of filled triangles makes only
 * triangles: with four varyings, two cache lines where a line's record
 * would take three. */
static inline size_t sr__record_size(int ninterp, bool flat, bool triangles_only)
{
    size_t n = (size_t)ninterp;
    size_t t = offsetof(sr_tri, vary) + sizeof(float) * (3 * n + (flat ? 4 : 0));
    size_t s = t;
    if (!triangles_only) {
        size_t l = sizeof(sr_line) - sizeof(float) * (2 * SR_MAX_VARYINGS - 2 * n);
        size_t p = sizeof(sr_point) - sizeof(float) * (SR_MAX_VARYINGS - n);
        s = s > l ? s : l;
        s = s > p ? s : p;
    }
    return (s + 15) & ~(size_t)15;
}

#endif
