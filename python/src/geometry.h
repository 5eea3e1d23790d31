/*
 * geometry.h - what render.c's geometry outputs share with visibility.c:
 * one instance's uniforms (its vertices seen from the camera, the output
 * arrays) and the per-pixel resolve from a face index to depth,
 * barycentrics, normal, position, uv, flow, IDs and mask.  No Python
 * objects: every function here runs without the GIL.
 */
#ifndef SR_PY_GEOMETRY_H
#define SR_PY_GEOMETRY_H

#include "module.h"

#include <math.h>
#include <string.h>

typedef struct geometry_uniforms {
    /* Per mesh vertex, computed once a view rather than once a triangle
     * corner (sr_py_view_vertices): the clip position, read by the vertex
     * shader, and the camera-space one, for the fragments' rays; apart,
     * so that the vertex shader's reads stay dense. */
    const float (*clip)[4];
    const double (*camera)[3];
    size_t vertices_count, faces_count;
    const void *vertices;
    bool vertices64;
    const void *faces;
    bool faces64;
    const float *normals;       /* NULL: face normals */
    double a[3][4];             /* object -> camera */
    double nm[3][3];            /* object normal -> the normal output's frame */
    double kx[3], ky[2];        /* clip x and y rows from K */
    double fx, s, cx, fy, cy;   /* K, for the rays through pixel centres */
    float near;
    /* The faces left undrawn: those of this area2 sign (sr__area2 of the
     * snapped vertices), 0 for none.  Back faces are clockwise on the
     * y-down screen (area2 > 0), unless the pose mirrors the mesh. */
    int cull_sign;
    /* Orthographic: K maps camera x, y (not x/z, y/z) to pixels, the rays
     * run along +z, and the window depth is (far - z) / (far - near). */
    bool ortho;
    float far;
    int width;
    int32_t instance_id;
    int32_t material_id;        /* the material_id output's value for this instance */
    const float *uvs;           /* (N, 2), or NULL: the uv output is NaN */
    /* position: the camera-space point taken to the output's frame */
    double to_frame[3][4];
    /* flow: camera -> the next view's camera, and that view's K and
     * projection; flow_next false (the last view) writes NaN */
    bool flow_next, flow_ortho;
    double flow_a[3][4];
    double flow_fx, flow_s, flow_cx, flow_fy, flow_cy;
    float *depth;
    int32_t *triangle_id, *instance_out, *material_out;
    float *barycentric, *normal, *position, *uv, *flow;
    npy_bool *mask;
} geometry_uniforms;

/* The geometry pass's draw state: a reversed z-buffer (cleared to 0,
 * GREATER: near / z), the faces of `cull_sign` (see geometry_uniforms)
 * culled, no color written. */
static inline sr_state sr_py_geometry_state(const sr_program *prog, int cull_sign)
{
    return (sr_state){ .program = prog, .depth_zero_to_one = true, .depth_func = SR_GREATER,
                       .cull = cull_sign ? SR_CULL_BACK : SR_CULL_NONE,
                       .front_face = cull_sign < 0 ? SR_FRONT_CW : SR_FRONT_CCW,
                       .color_mask = SR_COLOR_MASK_NONE };
}

/* Index i of the faces array (3 f + k is corner k of face f). */
static inline size_t sr_py_face_index(const geometry_uniforms *u, size_t i)
{
    return u->faces64 ? (size_t)((const int64_t *)u->faces)[i]
                      : (size_t)((const int32_t *)u->faces)[i];
}

/* Fills u's clip and camera tables for mesh vertices [lo, hi): each
 * vertex seen from the camera. */
void sr_py_view_vertices(const geometry_uniforms *u, size_t lo, size_t hi);
/* The same for the visibility pass: the camera table filled, the clip
 * positions written to `clip` (vertex lo's) and on, `stride` bytes apart;
 * for a pinhole camera in AVX2 lanes when `lanes` (the draw state's SIMD
 * level allows them), with the same values. */
void sr_py_view_vertices_to(const geometry_uniforms *u, size_t lo, size_t hi, bool lanes,
                            float *clip, size_t stride);

/* The outputs of the n pixels from p (y * width + x, along the rows)
 * where nothing is visible: each output filled over the run at once,
 * which the compiler turns into wide stores. */
static inline void sr_py_background_run(const geometry_uniforms *u, size_t p, size_t n)
{
    if (u->depth) {
        for (size_t i = 0; i < n; i++) {
            u->depth[p + i] = INFINITY;
        }
    }
    if (u->triangle_id) {
        memset(&u->triangle_id[p], 0xff, n * sizeof(int32_t));   /* -1 */
    }
    if (u->instance_out) {
        memset(&u->instance_out[p], 0xff, n * sizeof(int32_t));
    }
    if (u->barycentric) {
        memset(&u->barycentric[3 * p], 0, 3 * n * sizeof(float));
    }
    if (u->normal) {
        memset(&u->normal[3 * p], 0, 3 * n * sizeof(float));
    }
    if (u->mask) {
        memset(&u->mask[p], 0, n * sizeof(npy_bool));
    }
    if (u->material_out) {
        memset(&u->material_out[p], 0xff, n * sizeof(int32_t));
    }
    /* The points, coordinates and displacements of nothing: NaN, as 0
     * is a real value of each. */
    if (u->position) {
        for (size_t i = 0; i < 3 * n; i++) {
            u->position[3 * p + i] = NAN;
        }
    }
    if (u->uv) {
        for (size_t i = 0; i < 2 * n; i++) {
            u->uv[2 * p + i] = NAN;
        }
    }
    if (u->flow) {
        for (size_t i = 0; i < 2 * n; i++) {
            u->flow[2 * p + i] = NAN;
        }
    }
}

/* The outputs of pixel (x, y) where face `face` is visible, with
 * `window_z` its depth-buffer value there (reversed: near / z, or
 * orthographic (far - z) / (far - near)). */
void sr_py_shade_pixel(const geometry_uniforms *u, size_t face, int x, int y, float window_z);

/* The visibility-buffer pass (visibility.c): the instances' faces
 * rasterized for depth and face index alone, then each covered pixel
 * resolved by sr_py_shade_pixel: the same bytes as the general pass,
 * whose coverage and depth test it repeats with the library's own setup
 * and depth arithmetic.  Fills the instances' camera tables
 * (sr_py_view_vertices_to) and every pixel of the outputs.  *done is false,
 * the outputs unwritten and the tables maybe unfilled, when some face
 * crosses a clip plane (clipping is left to the general pass) or the pass
 * cannot draw the view. */
sr_result sr_py_visibility_pass(sr_py_render_set *set, const geometry_uniforms *u, size_t count,
                                bool *done);

#endif
