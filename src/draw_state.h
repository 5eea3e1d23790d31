/* draw_state.h - sr_draw_state: sr_state, the matrices and the framebuffer
 * resolved once per draw (draw_state.c, application thread), then read
 * by every stage on every thread: the vertex stage, setup, binning, the
 * tile jobs' rasterizers and the fragment stage.  Also the rasterizers'
 * signature (sr_raster_fn), which the state names for its draw, and the
 * per-thread counters they fill.  Internal to the library. */
#ifndef SR_DRAW_STATE_H
#define SR_DRAW_STATE_H

#include "softrast.h"
#include "target/framebuffer.h"

typedef struct sr_light_eye {
    bool point;
    float vec[3];             /* point: eye-space position; directional: unit vector to the light */
    float color[3];           /* color x intensity */
} sr_light_eye;

struct sr_draw_state;
struct sr_tri;
struct sr_frag_stats;

/* A triangle rasterizer: cover the part of a set-up triangle inside the
 * pixel rectangle [rx0, rx1) x [ry0, ry1) and hand each sample to the
 * fragment stage. */
typedef void (*sr_raster_fn)(const struct sr_draw_state *ds, const struct sr_tri *t, int rx0,
                             int ry0, int rx1, int ry1, struct sr_frag_stats *st);

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
    /* SR_CLIPPER_VIEW_VOLUME: triangles are clipped in view space
     * (geometry/clip_view.c) with the projection P and its inverse,
     * column-major as sr_mat4. */
    bool view_volume;
    double proj[16], proj_inv[16];

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

    /* The context's vector level (never SR_SIMD_DEFAULT). */
    sr_simd_level simd;
    /* The one function that rasterizes this draw's triangles, chosen
     * once from the rasterizer, the per-sample path, the program and the
     * vector level (draw_state.c): the tile jobs call only it. */
    sr_raster_fn raster_tri;
    /* Gouraud vertices lit four at a time (fragment/light_lanes.h, the
     * same bytes); off with SR_SIMD=off, which keeps sr__light's loop. */
    bool light_lanes;
    /* Gouraud vertices sixteen at a time, every step of a vertex in the
     * lanes (geometry/vertex_wide.c): the AVX-512 level. */
    bool vertex_lanes16;
    /* Tile clears in 64-byte stores: the AVX-512 level. */
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
     * per-sample path (raster/msaa.c), lines and points too. */
    int samples;                      /* the framebuffer's, 1..16 */
    const int8_t (*sample_off)[2];    /* q8 offsets from the pixel centre */
    bool per_sample;
    bool stencil_test;
    sr_stencil_face stencil[2];       /* front, back: defaults resolved */
    bool alpha_to_coverage;
    /* A program (docs/shaders.md) and its varyings' interpolation. */
    const sr_program *program;
    unsigned flat_mask, noperspective_mask;
    double depth_scale;               /* 2^n - 1 for UNORM, 1 for float */
    double zq_min, zq_max;            /* depth range in buffer units */
    int tiles_x, tiles_y;
} sr_draw_state;

/* Per-thread fragment counters. */
typedef struct sr_frag_stats {
    uint64_t fragments;
    uint64_t pad[7];                  /* one cache line per thread */
} sr_frag_stats;

/* The models whose fragment color is the interpolated color varying, as
 * the vertex stage left it: what the vector kernels shade like UNLIT. */
static inline bool sr__color_varying_shading(sr_shading s)
{
    return s == SR_SHADING_UNLIT || s == SR_SHADING_GOURAUD || s == SR_SHADING_ATTRIBUTE;
}

#endif
