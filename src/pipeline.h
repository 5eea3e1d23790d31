/* pipeline.h - the stages of one draw call and what passes between them:
 * the vertices in clip space with their varyings (sr_clip_vertex), after
 * the vertex stage (sr_vertex_post) and after the divide and viewport
 * (sr_window_vertex), and each stage's entry points - validation, state
 * resolution, the vertex stage, clipping, setup, the rasterizers and
 * lighting.  The state they all read is draw_state.h, the set-up records
 * setup hands the rasterizers are raster/records.h.  Internal to the
 * library. */
#ifndef SR_PIPELINE_H
#define SR_PIPELINE_H

#include "softrast.h"
#include "draw_state.h"
#include "raster/fixed.h"
#include "raster/records.h"
#include "simd_types.h"
#include "target/framebuffer.h"

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

/* ---- stage entry points ---- */

/* draw_validate.c: sr_draw's arguments checked, SR_OK or the failure
 * (with its message on ctx). */
sr_result sr__draw_validate(sr_context *ctx, const sr_framebuffer *fb, const sr_state *st,
                            const sr_draw_desc *d);
/* The same without a framebuffer: the state and the draw, for what takes
 * a state to draw with later (sr_make_builtin_program). */
sr_result sr__draw_validate_state(sr_context *ctx, const sr_state *st, const sr_draw_desc *d);

/* draw_painter.c: a validated triangle-list draw with SR_VISIBILITY_PAINTER,
 * drawn back to front without a depth test. */
sr_result sr__draw_painter(sr_context *ctx, sr_framebuffer *fb, const sr_state *state,
                           const sr_draw_desc *d);

/* draw_state.c: the whole draw state resolved into ds, and its shading
 * half alone (model, varyings, texture, material, lights in eye space),
 * which the built-in programs (fragment/builtin.c) use. */
void sr__resolve_draw_state(const sr_framebuffer *fb, const sr_state *st, const sr_mat4 *view,
                            const sr_mat4 *proj, sr_simd_level simd, sr_draw_state *ds);
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
/* The smallest and largest of indices [0, count) (both 0 for none). */
void sr__index_range(sr_index_type type, const void *indices, size_t count, uint32_t *min,
                     uint32_t *max);

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
/* geometry/clip_view.c: the view-volume clipper.  P (NULL -> identity)
 * and its inverse in double; false when P is singular. */
bool sr__view_volume_matrices(const sr_mat4 *proj, double p[16], double inv[16]);
/* Clip a triangle in view space against the six planes of the view volume
 * and map the polygon back to clip space; the vertex count, < 3 when
 * nothing is left. */
int sr__clip_polygon_view(const sr_draw_state *ds, const sr_clip_vertex *const in[3],
                          sr_clip_vertex *out);
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
/* raster/polygon_offset.c: polygon offset of the triangle's plane (0 when
 * offset is off for `mode`). */
double sr__polygon_offset(const sr_draw_state *ds, const sr_window_vertex *v0,
                          const sr_window_vertex *v1, const sr_window_vertex *v2,
                          sr_polygon_mode mode);

/* raster/{triangle,scanline,barycentric}.c: the rasterizers (sr_raster_fn).
 * triangle.c's half-space loop is instanced per shading model and depth
 * mode: sr__raster_halfspace_select gives the state's instance. */
sr_raster_fn sr__raster_halfspace_select(const sr_draw_state *ds);
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
/* raster/msaa.c: the per-sample path (ds->per_sample: multisampling or
 * the stencil test), whatever the rasterizer choice; the generic loop for
 * states without a program or a vector kernel. */
void sr__raster_msaa(const sr_draw_state *ds, const sr_tri *t,
                     int rx0, int ry0, int rx1, int ry1, sr_frag_stats *st);
/* The vector kernel of the per-sample path for this state, or NULL. */
sr_raster_fn sr__raster_msaa_select(const sr_draw_state *ds);

/* fragment/shade.c: Blinn-Phong. n must be unit length. */
void sr__light(const sr_draw_state *ds, const float n[3], const float eye[3],
               const float diffuse[4], float out[4]);

#endif
