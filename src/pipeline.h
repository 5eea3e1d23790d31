/* pipeline.h - the data that flows down the pipeline inside one draw call:
 * the resolved state (sr_draw_state), vertices in clip space with their
 * varyings (sr_clip_vertex), and triangles after setup (sr_tri), which is
 * all the rasterizers ever see.  Internal to the library. */
#ifndef SR_PIPELINE_H
#define SR_PIPELINE_H

#include "softrast.h"
#include "raster/fixed.h"
#include "target/framebuffer.h"

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

typedef struct sr_light_eye {
    bool point;
    float vec[3];             /* point: eye-space position; directional: unit vector to the light */
    float color[3];           /* color x intensity */
} sr_light_eye;

struct sr_tri;
struct sr_frag_stats;

/* How the fragment stage treats depth: no buffer or nothing to do; the
 * common LESS with writes on; anything else. */
typedef enum sr_depth_mode {
    SR_DEPTH_MODE_OFF = 0,
    SR_DEPTH_MODE_LESS,
    SR_DEPTH_MODE_GENERIC,
} sr_depth_mode;

/* sr_state with every default resolved and every vector in eye space. */
typedef struct sr_draw_state {
    sr_framebuffer *fb;

    /* Viewport S: x_w = ox + px x_ndc, y_w = oy - py y_ndc (y down),
     * z_w = zs z_ndc + zb.  Pixel rect = viewport ∩ framebuffer. */
    double vp_ox, vp_oy, vp_px, vp_py, vp_zs, vp_zb;
    double depth_min, depth_max;      /* min/max of the depth range */
    bool zero_to_one;
    int rect_x0, rect_y0, rect_x1, rect_y1; /* inclusive-exclusive pixels */

    sr_cull_mode cull;
    bool front_ccw;
    sr_rasterizer rasterizer;

    bool depth_test, depth_write;
    sr_depth_func depth_func;
    sr_depth_mode depth_mode;
    int depth_bits;                   /* 16, 24, 32, 0 = float */
    sr_polygon_mode mode_front, mode_back;
    int line_width;
    double point_size;
    bool round_points;
    bool smooth_lines, smooth_points;
    double smooth_width;              /* line_width as given, for smooth lines */
    bool offset_line, offset_point;
    bool offset_on;
    double offset_factor, offset_units, offset_clamp;

    sr_shading shading;
    bool perspective;                 /* perspective-correct varyings */
    bool provoking_last;
    bool two_sided;
    bool local_viewer;                /* perspective projection: view vector = -eye */
    int nvary;                        /* varyings written by the vertex stage */
    /* Texturing: the texture, its sampling, and where u, v sit among the
     * varyings (-1 without a texture). */
    const sr_texture *texture;
    sr_texture_filter texture_filter;
    sr_texture_wrap wrap_u, wrap_v;
    int uv_index;
    /* DEPTH shading under perspective: gray = (w - near) * depth_vis_scale. */
    bool depth_vis_linear;
    float depth_vis_near, depth_vis_scale;
    int ninterp;                      /* varyings interpolated across a triangle */

    float ambient[3];                 /* material ambient x global ambient */
    float diffuse[4];                 /* material diffuse, opacity as alpha */
    float specular[3];
    float shininess;
    int shininess_int;                /* shininess if a whole number <= 4096, else -1 */
    bool use_vertex_color;
    int light_count;
    sr_light_eye lights[SR_MAX_LIGHTS];

    /* The half-space kernel chosen for this state (triangle_simd.c), or
     * NULL for the scalar instances. */
    void (*raster_fast)(const struct sr_draw_state *, const struct sr_tri *, int, int, int, int,
                        struct sr_frag_stats *);
    /* Gouraud vertices lit four at a time (fragment/light_lanes.h, the
     * same bytes); off with SR_SIMD=off, which keeps sr__light's loop. */
    bool light_lanes;
    /* Gouraud vertices sixteen at a time, every step of a vertex in the
     * lanes (geometry/vertex_wide.c): the AVX-512 level. */
    bool vertex_lanes16;
    /* Tile clears in 64-byte stores: the AVX-512 level of sr__simd_level. */
    bool wide_stores;
    /* Triangle lists without indices assembled and set up sixteen at a
     * time (geometry/assembly_wide.h): the AVX-512 level, in the states
     * it covers (filled, four varyings, no flat ones, one sample, no
     * polygon offset). */
    bool triangles16;
    /* The index range check in AVX2 (geometry/index_max.c): the AVX2
     * level or above. */
    bool index_avx2;
    bool blending;                    /* blend or color mask active: the generic color write */
    sr_blend blend;                   /* factors and ops resolved */
    uint8_t write_mask[4];            /* 0xff: channel written; 0: kept */
    /* Multisampling and stencil: with either, triangles take the
     * per-sample path (raster/sample.c), lines and points too. */
    int samples;                      /* the framebuffer's, 1..16 */
    const int8_t (*sample_off)[2];    /* q8 offsets from the pixel centre */
    bool per_sample;
    bool stencil_test;
    sr_stencil_face stencil[2];       /* front, back: defaults resolved */
    bool alpha_to_coverage;
    /* A program (docs/shaders.md) and its varyings' interpolation. */
    const sr_program *program;
    unsigned flat_mask, noperspective_mask;
    /* The per-sample path's vector kernel for this state, or NULL. */
    void (*sample_fast)(const struct sr_draw_state *, const struct sr_tri *, int, int, int, int,
                        struct sr_frag_stats *);
    double depth_scale;               /* 2^n - 1 for UNORM, 1 for float */
    double zq_min, zq_max;            /* depth range in buffer units */
    int tiles_x, tiles_y;
} sr_draw_state;

/* A vertex after the vertex stage, in homogeneous clip space. */
typedef struct sr_clip_vertex {
    float pos[4];
    float vary[SR_MAX_VARYINGS];
} sr_clip_vertex;

/* A vertex after the divide and viewport, ready for setup. */
typedef struct sr_window_vertex {
    int32_t x_q8, y_q8;               /* snapped window position */
    double z;                         /* window depth, before offset */
    float inv_w;
    const float *vary;
} sr_window_vertex;

/* What the vertex stage keeps per vertex besides its varyings: the clip
 * position with its outcode and, for vertices inside every clip plane, the
 * window position - computed once per vertex (the post-transform cache),
 * not once per triangle corner. */
typedef struct sr_vertex_post {
    float pos[4];
    unsigned outcode;                 /* SR_OUTCODE_NONFINITE for NaN/Inf */
    int32_t x_q8, y_q8;
    float inv_w;
    double z;
} sr_vertex_post;

#define SR_OUTCODE_NONFINITE 0x80000000u

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

/* Per-thread fragment counters. */
typedef struct sr_frag_stats {
    uint64_t fragments;
    uint64_t pad[7];                  /* one cache line per thread */
} sr_frag_stats;

/* ---- stage entry points ---- */

/* draw_validate.c: sr_draw's arguments checked, SR_OK or the failure
 * (with its message on ctx). */
sr_result sr__draw_validate(sr_context *ctx, const sr_framebuffer *fb, const sr_state *st,
                            const sr_draw_desc *d);

/* draw_state.c: the whole draw state resolved into ds, and its shading
 * half alone (model, varyings, texture, material, lights in eye space),
 * which the built-in programs (fragment/builtin.c) use. */
void sr__resolve_draw_state(const sr_framebuffer *fb, const sr_state *st, const sr_mat4 *view,
                            const sr_mat4 *proj, sr_draw_state *ds);
void sr__resolve_shading(const sr_state *st, const sr_mat4 *view, const sr_mat4 *proj,
                         sr_draw_state *ds);

/* Bytes from one vertex's element of an attribute array to the next: the
 * draw's stride, or tightly packed `components` floats when it is 0. */
static inline size_t sr__attr_step(size_t stride, size_t components)
{
    return stride ? stride : components * sizeof(float);
}

/* geometry/vertex.c: vertices [first, first + count) into post[0 .. count)
 * and their varyings into vary[] (ds->nvary floats each): post and vary
 * point at vertex `first`'s entries. */
void sr__vertex_stage(const sr_draw_state *ds, const sr_draw_desc *d,
                      const sr_mat4 *mvp, const sr_mat4 *mv, const sr_mat4 *nm,
                      size_t first, size_t count, sr_vertex_post *post, float *vary);

/* geometry/index_max.c: the largest of indices [begin, end) of `type`
 * (0 for an empty range or SR_INDEX_NONE); `avx2` only where
 * ds->index_avx2 says the CPU has it. */
uint32_t sr__index_max(sr_index_type type, const void *indices, size_t begin, size_t end,
                       bool avx2);

/* geometry/vertex_wide.c: sr__vertex_stage for GOURAUD with whole-number
 * shininess, sixteen vertices at a time; the same bytes.
 * AVX-512: call only where ds->vertex_lanes16 says the CPU has it.  false,
 * having written nothing, for any other state (a vertex program) or an
 * array whose stride is too long for the gathers' 32-bit offsets. */
bool sr__vertex_stage16(const sr_draw_state *ds, const sr_draw_desc *d, const sr_mat4 *mvp,
                        const sr_mat4 *mv, const sr_mat4 *nm, size_t first, size_t count,
                        sr_vertex_post *post, float *vary);
/* The classification of post[0 .. count) (outcode, window position),
 * sixteen at a time: vertex.c's classify in lanes, the same values.
 * AVX-512: call only where ds->vertex_lanes16 says the CPU has it.  false,
 * having written nothing, in a build without the AVX-512 code, as
 * sr__vertex_stage16. */
bool sr__classify16(const sr_draw_state *ds, sr_vertex_post *post, size_t count);
/* geometry/vertex.c: one vertex of a built-in model (clip position and
 * varyings), shared by the vertex stage and the built-in programs. */
void sr__vertex_shade(const sr_draw_state *ds, const float obj[4], const float *normal,
                      const float *color, const float *texcoord, const float *generic,
                      const sr_mat4 *mvp, const sr_mat4 *mv, const sr_mat4 *nm, float clip[4],
                      float *vary);
/* Flat shading's color from the three vertices' varyings (eye position
 * and color); `pv` is the provoking vertex's varyings. */
void sr__flat_color(const sr_draw_state *ds, const float *v0, const float *v1,
                    const float *v2, const float *pv, float out[4]);

/* geometry/clip.c: outcodes, and Sutherland-Hodgman in 4D.  Returns the
 * number of polygon vertices written to out (0 if nothing is left). */
#define SR_CLIP_MAX_VERTS 16
unsigned sr__clip_outcode(const sr_draw_state *ds, const float pos[4]);

/* The clip planes (docs/raster-rules.md §4, see clip.c), as bits of an outcode. */
enum {
    SR_PLANE_W = 0,
    SR_PLANE_NEAR,
    SR_PLANE_FAR,
    SR_PLANE_LEFT,
    SR_PLANE_RIGHT,
    SR_PLANE_TOP,
    SR_PLANE_BOTTOM,
    SR_PLANE_COUNT
};

/* Smallest w let through: tiny, so it never cuts geometry the near plane
 * keeps, but it excludes w = 0 exactly, where the divide would give NaN. */
#define SR_CLIP_W_EPSILON 1e-30

/* Band edges one pixel inside the fixed-point limit, so a vertex rounded
 * onto a band plane still snaps inside the range. */
#define SR_CLIP_BAND_LO ((double)SR_GUARD_BAND_MIN + 1.0)
#define SR_CLIP_BAND_HI ((double)SR_GUARD_BAND_MAX - 1.0)

/* The state's plane coefficients, formed once per block of vertices rather
 * than once per vertex: x_w = ox + px x/w >= lo <=> px x - (lo - ox) w >= 0
 * (w > 0), and likewise for the other band planes (y down). */
typedef struct sr_clip_planes {
    bool zero_to_one;
    double px, py;
    double left_w, right_w, top_w, bottom_w;
} sr_clip_planes;

static inline void sr__clip_planes(const sr_draw_state *ds, sr_clip_planes *k)
{
    k->zero_to_one = ds->zero_to_one;
    k->px = ds->vp_px;
    k->py = ds->vp_py;
    k->left_w = SR_CLIP_BAND_LO - ds->vp_ox;
    k->right_w = SR_CLIP_BAND_HI - ds->vp_ox;
    k->top_w = ds->vp_oy - SR_CLIP_BAND_LO;
    k->bottom_w = ds->vp_oy - SR_CLIP_BAND_HI;
}

/* Bit p set when pos is outside plane p (inside is distance >= 0; NaN is
 * outside). */
static inline unsigned sr__clip_outcode_with(const sr_clip_planes *k, const float pos[4])
{
    double x = pos[0], y = pos[1], z = pos[2], w = pos[3];
    double near = k->zero_to_one ? z : z + w;
    unsigned code = 0;
    code |= (unsigned)!(w - SR_CLIP_W_EPSILON >= 0.0) << SR_PLANE_W;
    code |= (unsigned)!(near >= 0.0) << SR_PLANE_NEAR;
    code |= (unsigned)!(w - z >= 0.0) << SR_PLANE_FAR;
    code |= (unsigned)!(k->px * x - k->left_w * w >= 0.0) << SR_PLANE_LEFT;
    code |= (unsigned)!(k->right_w * w - k->px * x >= 0.0) << SR_PLANE_RIGHT;
    code |= (unsigned)!(k->top_w * w - k->py * y >= 0.0) << SR_PLANE_TOP;
    code |= (unsigned)!(k->py * y - k->bottom_w * w >= 0.0) << SR_PLANE_BOTTOM;
    return code;
}
int sr__clip_polygon(const sr_draw_state *ds, const sr_clip_vertex *const in[3],
                     unsigned planes, sr_clip_vertex *out);
/* Clip segment ab to the planes; false when nothing is left. */
bool sr__clip_segment(const sr_draw_state *ds, const sr_clip_vertex *a, const sr_clip_vertex *b,
                      unsigned planes, sr_clip_vertex *out_a, sr_clip_vertex *out_b);

/* raster/setup.c (the divide and snap are inline: the vertex stage runs
 * them once per vertex). */
/* Clamp to the fixed-point range (clipping already keeps vertices inside
 * the guard band; the clamp only absorbs rounding at the band's edge), then
 * round to nearest even.  Adding and subtracting 1.5 x 2^52 rounds any
 * |s| < 2^51 to an integer in the default rounding mode, exactly as
 * nearbyint would, without the library call baseline x86-64 makes for it
 * (two per vertex). */
static inline int32_t sr__snap_q8(double v)
{
    const double lim = (double)SR_GUARD_BAND_MAX * SR_SUBPIXEL_ONE;
    const double magic = 6755399441055744.0; /* 1.5 x 2^52 */
    double s = v * SR_SUBPIXEL_ONE;
    s = s > lim ? lim : s;
    s = s < -lim ? -lim : s;
    s = (s + magic) - magic;
    return (int32_t)s;
}

/* Divide by w, apply the viewport S and snap to q8 (round to nearest even).
 * One fixed operation order (docs/raster-rules.md §1.4), in double, one rounding
 * at the snap: the same clip position always gives the same q8 value. */
static inline void sr__project(const sr_draw_state *ds, const float pos[4], int32_t *x_q8,
                               int32_t *y_q8, double *z, float *inv_w)
{
    double iw = 1.0 / pos[3];
    double xn = pos[0] * iw, yn = pos[1] * iw, zn = pos[2] * iw;
    *x_q8 = sr__snap_q8(ds->vp_ox + ds->vp_px * xn);
    *y_q8 = sr__snap_q8(ds->vp_oy - ds->vp_py * yn);
    *z = ds->vp_zs * zn + ds->vp_zb;
    *inv_w = (float)iw;
}
void sr__window_vertex(const sr_draw_state *ds, const sr_clip_vertex *v, sr_window_vertex *out);
/* Twice the signed area of the snapped triangle, E_01(v2), exact. */
static inline int64_t sr__area2(const sr_window_vertex *v0, const sr_window_vertex *v1,
                                const sr_window_vertex *v2)
{
    return (int64_t)(v1->x_q8 - v0->x_q8) * (v2->y_q8 - v0->y_q8) -
           (int64_t)(v1->y_q8 - v0->y_q8) * (v2->x_q8 - v0->x_q8);
}
/* Returns true when the triangle produced samples-to-be (not culled, not
 * zero area, bbox non-empty).  `front` is the facing to use. */
bool sr__setup_triangle(const sr_draw_state *ds, const sr_window_vertex *v0,
                        const sr_window_vertex *v1, const sr_window_vertex *v2,
                        bool front, int ninterp, const float flat[4], sr_tri *t);
/* The same with a given depth offset in depth-range units (NaN: the
 * fill's polygon offset, as sr__setup_triangle). */
bool sr__setup_triangle_offset(const sr_draw_state *ds, const sr_window_vertex *v0,
                               const sr_window_vertex *v1, const sr_window_vertex *v2,
                               double offset, bool front, int ninterp, const float flat[4],
                               sr_tri *t);

/* raster/line.c: set up a segment or a point (false when nothing can be
 * drawn), and rasterize them within a pixel rectangle. */
bool sr__setup_line(const sr_draw_state *ds, const sr_window_vertex *a, const sr_window_vertex *b,
                    double offset, bool front, int ninterp, const float flat[4], sr_line *l);
bool sr__setup_point(const sr_draw_state *ds, const sr_window_vertex *v, double offset,
                     bool front, int ninterp, const float flat[4], sr_point *p);
void sr__raster_line(const sr_draw_state *ds, const sr_line *l, int rx0, int ry0, int rx1,
                     int ry1, sr_frag_stats *st);
void sr__raster_point(const sr_draw_state *ds, const sr_point *p, int rx0, int ry0, int rx1,
                      int ry1, sr_frag_stats *st);
/* raster/line.c: the minor-axis pixels [*v0, *v1] that an aliased line's
 * pixels (wide runs included) take in its columns [u0, u1]; false when
 * none.  Tile binning reaches only these. */
bool sr__line_span(const sr_line *l, int u0, int u1, int *v0, int *v1);
/* The line's tile columns [*tu0, *tu1] along its major axis (none when
 * *tu0 > *tu1), and the tile rows [*tv0, *tv1] that its pixels reach in
 * tile column tu (false when none), all within its bounding box. */
void sr__line_tile_columns(const sr_line *l, int *tu0, int *tu1);
bool sr__line_tile_rows(const sr_line *l, int tu, int *tv0, int *tv1);
/* Polygon offset of the triangle's plane (0 when offset is off for `mode`). */
double sr__polygon_offset(const sr_draw_state *ds, const sr_window_vertex *v0,
                          const sr_window_vertex *v1, const sr_window_vertex *v2,
                          sr_polygon_mode mode);

/* raster/{triangle,scanline,barycentric}.c: cover the part of t inside the
 * pixel rectangle [rx0, rx1) x [ry0, ry1) and hand each sample to the
 * fragment stage. */
void sr__raster_halfspace(const sr_draw_state *ds, const sr_tri *t,
                          int rx0, int ry0, int rx1, int ry1, sr_frag_stats *st);
void sr__raster_scanline(const sr_draw_state *ds, const sr_tri *t,
                         int rx0, int ry0, int rx1, int ry1, sr_frag_stats *st);
void sr__raster_barycentric(const sr_draw_state *ds, const sr_tri *t,
                            int rx0, int ry0, int rx1, int ry1, sr_frag_stats *st);
/* raster/shader.c: triangles through a program's fragment shader, by 2x2
 * quads; and one line or point fragment through it (false: discarded).
 * *z is in buffer units, replaced when the program writes depth. */
void sr__raster_shader(const sr_draw_state *ds, const sr_tri *t,
                       int rx0, int ry0, int rx1, int ry1, sr_frag_stats *st);
bool sr__program_shade_one(const sr_draw_state *ds, const float *v, bool front, int px, int py,
                           double *z, float c[4]);
/* raster/sample.c: the per-sample path (ds->per_sample: multisampling or
 * the stencil test), whatever the rasterizer choice. */
void sr__raster_sample(const sr_draw_state *ds, const sr_tri *t,
                       int rx0, int ry0, int rx1, int ry1, sr_frag_stats *st);
/* raster/triangle_simd.c: which vector builds run - AVX-512 or AVX2 when
 * the CPU has it, the baseline build, or none; SR_SIMD=off|base|avx2 in the
 * environment caps it. */
typedef enum sr_simd_level {
    SR_SIMD_OFF = 0, SR_SIMD_BASE, SR_SIMD_AVX2, SR_SIMD_AVX512
} sr_simd_level;
sr_simd_level sr__simd_level(void);
/* What the AVX-512 level needs of the CPU (sr__simd_level checks each of
 * them): the target of every function built for that level. */
#define SR_TARGET_AVX512 __attribute__((target("avx2,avx512f,avx512dq,avx512bw,avx512vl,popcnt")))
/* The models whose fragment color is the interpolated color varying, as
 * the vertex stage left it: what the vector kernels shade like UNLIT. */
static inline bool sr__color_varying_shading(sr_shading s)
{
    return s == SR_SHADING_UNLIT || s == SR_SHADING_GOURAUD || s == SR_SHADING_ATTRIBUTE;
}
/* The vector kernel of the per-sample path for this state, or NULL. */
typedef void (*sr_raster_fn)(const sr_draw_state *, const sr_tri *, int, int, int, int,
                             sr_frag_stats *);
sr_raster_fn sr__raster_sample_select(const sr_draw_state *ds);

/* fragment/shade.c: Blinn-Phong. n must be unit length. */
void sr__light(const sr_draw_state *ds, const float n[3], const float eye[3],
               const float diffuse[4], float out[4]);

#endif
