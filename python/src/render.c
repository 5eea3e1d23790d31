/*
 * render.c - softrast._softrast.render: one camera's geometry buffers
 * (depth, triangle, instance and material IDs, barycentrics, normals,
 * positions, texture coordinates, flow to the next view, mask) and
 * color (RGB, or RGBA with a transparent background) from a list of mesh
 * instances.  The Python layer (softrast/_render.py) validates cameras and
 * poses and loops over batches; this file checks what it is handed again
 * so that no call can crash, then draws with the GIL released.
 *
 * The geometry buffers come from one sr_program per instance.  Its vertex
 * shader reads the mesh's own arrays (float32 or float64 vertices, int32
 * or int64 faces) by triangle corner, so the draw is non-indexed, three
 * corners a face: corner c of the draw is corner c % 3 of face c / 3,
 * whose index reaches the fragment shader as a flat varying.  The fragment
 * shader intersects the pixel's ray with that face for depth, barycentrics
 * and normal, and writes them for the fragments that pass the depth test;
 * fragments of one tile are shaded in draw order, so the last write to a
 * pixel is the visible surface's, the same for any thread count.  That is
 * the general pass: a view in which no face crosses a clip plane takes
 * the visibility pass instead (visibility.c), with the same bytes.  Color
 * comes from a second pass on the same projection: the built-in shading
 * (textures, vertex colors, a headlight), or the metallic-roughness
 * program lit as softrast render's default look, multisampled or
 * supersampled when asked.  A camera is a pinhole or orthographic (K
 * applied to camera x and y, rays along +z).
 */
#include "geometry.h"
#include "render.h"
#include "math/dvec3.h"
#include "simd_types.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Varyings of the geometry program: the face index, exact in a float up
 * to 2^24 faces; beyond, in two 16-bit halves (V_TRI_HI and V_TRI_LO).
 * One varying where it does makes each triangle's set-up record
 * smaller. */
enum { V_TRI = 0, V_TRI_HI = 0, V_TRI_LO = 1 };
#define ONE_VARYING_FACES ((size_t)1 << 24)

static void fetch_vertex(const geometry_uniforms *u, size_t v, double p[3])
{
    for (int k = 0; k < 3; k++) {
        p[k] = u->vertices64 ? ((const double *)u->vertices)[3 * v + k]
                             : (double)((const float *)u->vertices)[3 * v + k];
    }
}

static void to_camera(const geometry_uniforms *u, const double p[3], double c[3])
{
    for (int r = 0; r < 3; r++) {
        c[r] = u->a[r][0] * p[0] + u->a[r][1] * p[1] + u->a[r][2] * p[2] + u->a[r][3];
    }
}

/* Mesh vertex v seen from the camera: its clip and camera-space
 * positions. */
static void view_of(const geometry_uniforms *u, size_t v, float clip[4], double c[3])
{
    double p[3];
    fetch_vertex(u, v, p);
    to_camera(u, p, c);
    if (u->ortho) {
        /* Orthographic: pixel centre (u, v) is at window (u + 1/2, v + 1/2)
         * with u, v from camera x, y alone; w = 1, and a window depth
         * falling linearly from 1 at near to 0 at far (still largest
         * nearest: the depth test is GREATER). */
        clip[0] = (float)(u->kx[0] * c[0] + u->kx[1] * c[1] + u->kx[2]);
        clip[1] = (float)(u->ky[0] * c[1] + u->ky[1]);
        clip[2] = (float)(((double)u->far - c[2]) / ((double)u->far - u->near));
        clip[3] = 1.0f;
        return;
    }
    /* OpenCV's pinhole: pixel centre (u, v) is at window (u + 1/2, v + 1/2);
     * w = z; clip z = near with z in [0, w] gives z_ndc = near / z, largest
     * nearest (the depth test is GREATER), infinite far plane. */
    clip[0] = (float)(u->kx[0] * c[0] + u->kx[1] * c[1] + u->kx[2] * c[2]);
    clip[1] = (float)(u->ky[0] * c[1] + u->ky[1] * c[2]);
    clip[2] = u->near;
    clip[3] = (float)c[2];
}

#if defined(__x86_64__) && defined(__GNUC__)
#define SR_PY_VIEW_LANES 1
/* Mesh vertices [lo, hi) of type T four at a time in AVX2 lanes: view_of's
 * perspective operations in its order, lane by lane (never contracted, as
 * SR_EXACT_FP_FLAGS says), so the same values.  Returns the first vertex
 * left for view_of. */
#define VIEW_LANES(T)                                                                      \
    for (; v + 4 <= hi; v += 4) {                                                         \
        const T *s = (const T *)u->vertices + 3 * v;                                      \
        v4d p[3];                                                                         \
        for (int k = 0; k < 3; k++) {                                                     \
            p[k] = (v4d){ s[k], s[3 + k], s[6 + k], s[9 + k] };                           \
        }                                                                                 \
        v4d c[3];                                                                         \
        for (int r = 0; r < 3; r++) {                                                     \
            c[r] = u->a[r][0] * p[0] + u->a[r][1] * p[1] + u->a[r][2] * p[2] + u->a[r][3]; \
        }                                                                                 \
        v4f x = __builtin_convertvector(u->kx[0] * c[0] + u->kx[1] * c[1] + u->kx[2] * c[2], \
                                        v4f);                                             \
        v4f y = __builtin_convertvector(u->ky[0] * c[1] + u->ky[1] * c[2], v4f);          \
        v4f w = __builtin_convertvector(c[2], v4f);                                       \
        for (int i = 0; i < 4; i++) {                                                     \
            double *cam = camera[v + i];                                                  \
            cam[0] = c[0][i];                                                             \
            cam[1] = c[1][i];                                                             \
            cam[2] = c[2][i];                                                             \
            float *o = (float *)(clip + (v + i - lo) * stride);                           \
            o[0] = x[i];                                                                  \
            o[1] = y[i];                                                                  \
            o[2] = u->near;                                                               \
            o[3] = w[i];                                                                  \
        }                                                                                 \
    }

__attribute__((target("avx2"))) static size_t view_lanes(const geometry_uniforms *u, size_t lo,
                                                         size_t hi, char *clip, size_t stride)
{
    double (*camera)[3] = (double (*)[3])u->camera;
    size_t v = lo;
    if (u->vertices64) {
        VIEW_LANES(double)
    } else {
        VIEW_LANES(float)
    }
    return v;
}
#undef VIEW_LANES
#endif

void sr_py_view_vertices_to(const geometry_uniforms *u, size_t lo, size_t hi, bool lanes,
                            float *clip, size_t stride)
{
    double (*camera)[3] = (double (*)[3])u->camera;
    size_t v = lo;
#ifdef SR_PY_VIEW_LANES
    if (lanes && !u->ortho) {
        v = view_lanes(u, lo, hi, (char *)clip, stride);
    }
#else
    (void)lanes;
#endif
    for (; v < hi; v++) {
        view_of(u, v, (float *)((char *)clip + (v - lo) * stride), camera[v]);
    }
}

void sr_py_view_vertices(const geometry_uniforms *u, size_t lo, size_t hi)
{
    /* The tables are the render set's, handed out read-only to the
     * shaders. */
    sr_py_view_vertices_to(u, lo, hi, false, (float *)u->clip[lo], 4 * sizeof(float));
}

static void geometry_vertex(const void *uniforms, const sr_vertex_input *in, float clip[4],
                            float *vary)
{
    const geometry_uniforms *u = uniforms;
    size_t face = in->index / 3;
    memcpy(clip, u->clip[sr_py_face_index(u, in->index)], 4 * sizeof(float));
    if (u->faces_count <= ONE_VARYING_FACES) {
        vary[V_TRI] = (float)face;
    } else {
        vary[V_TRI_HI] = (float)(face >> 16);
        vary[V_TRI_LO] = (float)(face & 0xffff);
    }
}

/* The flow output at pixel (x, y) of camera-space point cp: where the
 * next view sees it, less the pixel; NaN for the last view and for a
 * point that is not in front of the next pinhole. */
static void flow_of(const geometry_uniforms *u, const double cp[3], int x, int y, float out[2])
{
    double q[3];
    for (int r = 0; r < 3; r++) {
        q[r] = u->flow_a[r][0] * cp[0] + u->flow_a[r][1] * cp[1] + u->flow_a[r][2] * cp[2] +
               u->flow_a[r][3];
    }
    if (!u->flow_next || (!u->flow_ortho && !(q[2] > 0.0))) {
        out[0] = out[1] = NAN;
        return;
    }
    double w = u->flow_ortho ? 1.0 : q[2];
    out[0] = (float)((u->flow_fx * q[0] + u->flow_s * q[1]) / w + u->flow_cx - x);
    out[1] = (float)(u->flow_fy * q[1] / w + u->flow_cy - y);
}

/* The visible face's outputs at pixel (x, y), from the ray through the
 * pixel's centre and the face's camera-space plane, in double: depth and
 * barycentrics are the exact intersection rounded once to float, not
 * interpolated from vertices snapped to the raster's sub-pixel grid. */
void sr_py_shade_pixel(const geometry_uniforms *u, size_t face, int x, int y, float window_z)
{
    size_t p = (size_t)y * (size_t)u->width + (size_t)x;
    size_t vi[3];
    double o[3][3], c[3][3];
    for (int k = 0; k < 3; k++) {
        vi[k] = sr_py_face_index(u, 3 * face + (size_t)k);
        memcpy(c[k], u->camera[vi[k]], sizeof c[k]);
    }
    /* The pixel centre's ray: from the eye through (d[0], d[1], 1), or,
     * orthographic, from (d[0], d[1], 0) along +z. */
    double dy = ((double)y - u->cy) / u->fy;
    double d[3] = { ((double)x - u->cx - u->s * dy) / u->fx, dy, 1.0 };
    double e1[3] = { c[1][0] - c[0][0], c[1][1] - c[0][1], c[1][2] - c[0][2] };
    double e2[3] = { c[2][0] - c[0][0], c[2][1] - c[0][1], c[2][2] - c[0][2] };
    double n[3];
    sr__dcross(e1, e2, n);
    double denom = sr__ddot(n, d), nn = sr__ddot(n, n);
    double z, lambda[3] = { 1.0 / 3, 1.0 / 3, 1.0 / 3 };
    if (u->ortho) {
        denom = n[2];
    }
    if (denom != 0.0 && nn > 0.0) {
        double w[3], t[3];
        if (u->ortho) {
            /* w = the ray's point at depth z, from corner 0. */
            w[0] = d[0] - c[0][0];
            w[1] = d[1] - c[0][1];
            z = c[0][2] - (n[0] * w[0] + n[1] * w[1]) / denom;
            w[2] = z - c[0][2];
        } else {
            z = sr__ddot(n, c[0]) / denom;
            w[0] = z * d[0] - c[0][0];
            w[1] = z * d[1] - c[0][1];
            w[2] = z * d[2] - c[0][2];
        }
        sr__dcross(w, e2, t);
        lambda[1] = sr__ddot(t, n) / nn;
        sr__dcross(e1, w, t);
        lambda[2] = sr__ddot(t, n) / nn;
        lambda[0] = 1.0 - lambda[1] - lambda[2];
    } else {
        /* Seen edge-on: no area to intersect; the raster's depth. */
        z = u->ortho ? u->far - (double)window_z * ((double)u->far - u->near)
                     : u->near / window_z;
    }
    if (u->depth) {
        u->depth[p] = (float)z;
    }
    if (u->triangle_id) {
        u->triangle_id[p] = (int32_t)face;
    }
    if (u->instance_out) {
        u->instance_out[p] = u->instance_id;
    }
    if (u->barycentric) {
        for (int k = 0; k < 3; k++) {
            u->barycentric[3 * p + k] = (float)lambda[k];
        }
    }
    if (u->normal) {
        double on[3] = { 0, 0, 0 }, fn[3];
        if (u->normals) {
            for (int k = 0; k < 3; k++) {
                for (int i = 0; i < 3; i++) {
                    on[i] += lambda[k] * u->normals[3 * vi[k] + i];
                }
            }
        } else {
            for (int k = 0; k < 3; k++) {
                fetch_vertex(u, vi[k], o[k]);
            }
            double oe1[3] = { o[1][0] - o[0][0], o[1][1] - o[0][1], o[1][2] - o[0][2] };
            double oe2[3] = { o[2][0] - o[0][0], o[2][1] - o[0][1], o[2][2] - o[0][2] };
            sr__dcross(oe1, oe2, on);
        }
        for (int r = 0; r < 3; r++) {
            fn[r] = u->nm[r][0] * on[0] + u->nm[r][1] * on[1] + u->nm[r][2] * on[2];
        }
        double len = sqrt(sr__ddot(fn, fn));
        double scale = len > 0.0 ? 1.0 / len : 0.0;
        for (int r = 0; r < 3; r++) {
            u->normal[3 * p + r] = (float)(fn[r] * scale);
        }
    }
    if (u->mask) {
        u->mask[p] = 1;
    }
    if (u->material_out) {
        u->material_out[p] = u->material_id;
    }
    if (u->uv) {
        for (int i = 0; i < 2; i++) {
            double t = u->uvs ? 0.0 : NAN;
            for (int k = 0; k < 3 && u->uvs; k++) {
                t += lambda[k] * u->uvs[2 * vi[k] + i];
            }
            u->uv[2 * p + i] = (float)t;
        }
    }
    if (u->position || u->flow) {
        /* The ray's point at depth z, in the camera frame. */
        double cp[3] = { u->ortho ? d[0] : z * d[0], u->ortho ? d[1] : z * d[1], z };
        if (u->position) {
            for (int r = 0; r < 3; r++) {
                u->position[3 * p + r] = (float)(u->to_frame[r][0] * cp[0] +
                                                 u->to_frame[r][1] * cp[1] +
                                                 u->to_frame[r][2] * cp[2] + u->to_frame[r][3]);
            }
        }
        if (u->flow) {
            flow_of(u, cp, x, y, &u->flow[2 * p]);
        }
    }
}

static void geometry_fragment(const void *uniforms, sr_fragment_quad *q)
{
    const geometry_uniforms *u = uniforms;
    for (int i = 0; i < 4; i++) {
        if (q->mask >> i & 1) {
            size_t face = u->faces_count <= ONE_VARYING_FACES
                              ? (size_t)lrintf(q->varyings[V_TRI][i])
                              : (size_t)lrintf(q->varyings[V_TRI_HI][i]) << 16 |
                                    (size_t)lrintf(q->varyings[V_TRI_LO][i]);
            sr_py_shade_pixel(u, face, q->x + (i & 1), q->y + (i >> 1), q->z[i]);
        }
    }
}

/* Every pixel of the geometry outputs as where nothing is visible. */
static void fill_outputs(const render_job *j)
{
    geometry_uniforms u = { .depth = j->depth, .triangle_id = j->triangle_id,
                            .instance_out = j->instance_id, .barycentric = j->barycentric,
                            .normal = j->normal, .mask = j->mask,
                            .material_out = j->material_id, .position = j->position,
                            .uv = j->uv, .flow = j->flow };
    sr_py_background_run(&u, 0, (size_t)j->width * (size_t)j->height);
}

static void clip_rows(const render_job *j, double kx[3], double ky[2])
{
    double w = j->width, h = j->height;
    kx[0] = 2.0 * j->k[0][0] / w;
    kx[1] = 2.0 * j->k[0][1] / w;
    kx[2] = 2.0 * (j->k[0][2] + 0.5) / w - 1.0;
    ky[0] = -2.0 * j->k[1][1] / h;
    ky[1] = 1.0 - 2.0 * (j->k[1][2] + 0.5) / h;
}

/* One instance's draw in one pass; `faces` > 0. */
typedef sr_result (*instance_draw)(sr_context *ctx, sr_framebuffer *fb, const render_job *j,
                                   const instance *in, size_t faces, const void *arg);

static sr_result draw_instances(sr_context *ctx, sr_framebuffer *fb, const render_job *j,
                                instance_draw draw, const void *arg)
{
    sr_result r = SR_OK;
    for (size_t i = 0; i < j->count && r == SR_OK; i++) {
        size_t faces = (size_t)PyArray_DIM(j->inst[i].mesh->faces, 0);
        if (faces > 0) {
            r = draw(ctx, fb, j, &j->inst[i], faces, arg);
        }
    }
    return r;
}

/* Each instance's uniforms, with room for its vertices seen from the
 * camera in the set's per-vertex tables (every instance's at once, as the
 * visibility pass resolves any of them at any pixel), filled when `view`
 * (the visibility pass fills them on its threads). */
static sr_result geometry_uniforms_of(const render_job *j, bool view, geometry_uniforms *u)
{
    size_t total = 0;
    for (size_t i = 0; i < j->count; i++) {
        total += (size_t)PyArray_DIM(j->inst[i].mesh->vertices, 0);
    }
    sr_py_render_set *set = j->set;
    size_t bytes = total * (4 * sizeof(float) + 3 * sizeof(double));
    if (set->vertices_bytes < bytes) {
        void *grown = realloc(set->vertices, bytes);
        if (!grown) {
            return SR_OUT_OF_MEMORY;
        }
        set->vertices = grown;
        set->vertices_bytes = bytes;
    }
    float (*clip)[4] = set->vertices;
    double (*camera)[3] = (double (*)[3])(clip + total);
    for (size_t i = 0; i < j->count; i++) {
        const instance *in = &j->inst[i];
        const MeshObject *m = in->mesh;
        u[i] = (geometry_uniforms){
            .vertices_count = (size_t)PyArray_DIM(m->vertices, 0),
            .faces_count = (size_t)PyArray_DIM(m->faces, 0),
            .vertices = PyArray_DATA(m->vertices),
            .vertices64 = PyArray_TYPE(m->vertices) == NPY_FLOAT64,
            .faces = PyArray_DATA(m->faces),
            .faces64 = PyArray_TYPE(m->faces) == NPY_INT64,
            .normals = m->normals ? PyArray_DATA(m->normals) : NULL,
            .fx = j->k[0][0], .s = j->k[0][1], .cx = j->k[0][2], .fy = j->k[1][1],
            .cy = j->k[1][2], .near = j->near, .ortho = j->ortho, .far = j->far,
            .cull_sign = !j->cull_back ? 0 : sr_py_mirrors(in->a) ? -1 : 1,
            .width = j->width, .instance_id = in->id,
            .depth = j->depth, .triangle_id = j->triangle_id, .instance_out = j->instance_id,
            .barycentric = j->barycentric, .normal = j->normal, .mask = j->mask,
            .material_id = in->material_id, .uvs = m->uvs ? PyArray_DATA(m->uvs) : NULL,
            .flow_next = j->flow_next, .flow_ortho = j->flow_ortho,
            .flow_fx = j->flow_k[0][0], .flow_s = j->flow_k[0][1], .flow_cx = j->flow_k[0][2],
            .flow_fy = j->flow_k[1][1], .flow_cy = j->flow_k[1][2],
            .material_out = j->material_id, .position = j->position, .uv = j->uv,
            .flow = j->flow,
        };
        memcpy(u[i].to_frame, j->to_frame, sizeof u[i].to_frame);
        memcpy(u[i].flow_a, j->flow_a, sizeof u[i].flow_a);
        memcpy(u[i].a, in->a, sizeof u[i].a);
        memcpy(u[i].nm, in->nm, sizeof u[i].nm);
        clip_rows(j, u[i].kx, u[i].ky);
        u[i].clip = (const float (*)[4])clip;
        u[i].camera = (const double (*)[3])camera;
        if (view) {
            sr_py_view_vertices(&u[i], 0, u[i].vertices_count);
        }
        clip += u[i].vertices_count;
        camera += u[i].vertices_count;
    }
    return SR_OK;
}

/* One instance through the library's pipeline; `u->faces_count` > 0. */
static sr_result geometry_draw(sr_context *ctx, sr_framebuffer *fb, const geometry_uniforms *u,
                               const MeshObject *m)
{
    size_t faces = u->faces_count;
    sr_program prog = { .vertex = geometry_vertex, .fragment = geometry_fragment,
                        .uniforms = u, .varying_count = faces <= ONE_VARYING_FACES ? 1 : 2 };
    prog.modes[V_TRI_HI] = prog.modes[V_TRI_LO] = SR_VARYING_FLAT;
    /* The shader reads the mesh itself; sr_draw still wants a position
     * array of vertex_count entries.  Overlapping ones 4 bytes apart
     * (3 * faces + 2 zeros, made with the mesh) are the smallest. */
    sr_state st = sr_py_geometry_state(&prog, u->cull_sign);
    return sr_draw(ctx, fb, &st,
                   &(sr_draw_desc){ .positions = m->zeros, .position_stride = sizeof(float),
                                    .vertex_count = 3 * faces });
}

/* The visibility pass where it can draw the view (unless the caller
 * asked for the general one), else each instance through the library's
 * pipeline: the same bytes either way. */
static sr_result geometry_pass(sr_context *ctx, sr_framebuffer *fb, const render_job *j)
{
    geometry_uniforms *u = calloc(j->count ? j->count : 1, sizeof *u);
    if (!u) {
        return SR_OUT_OF_MEMORY;
    }
    sr_result r = geometry_uniforms_of(j, j->general, u);
    bool done = false;
    if (r == SR_OK && !j->general) {
        r = sr_py_visibility_pass(j->set, u, j->count, &done);
    }
    if (r == SR_OK && !done) {
        for (size_t i = 0; i < j->count && !j->general; i++) {
            sr_py_view_vertices(&u[i], 0, u[i].vertices_count);
        }
        fill_outputs(j);
        r = sr_clear(ctx, fb, &(sr_clear_desc){ .depth_action = SR_ACTION_CLEAR, .depth = 0,
                                                 .color_action = SR_ACTION_KEEP });
        for (size_t i = 0; i < j->count && r == SR_OK; i++) {
            if (u[i].faces_count > 0) {
                r = geometry_draw(ctx, fb, &u[i], j->inst[i].mesh);
            }
        }
    }
    free(u);
    return r;
}

bool sr_py_mirrors(const double a[3][4])
{
    double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                 a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                 a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    return det < 0.0;
}

void sr_py_mat_from_rows(const double a[3][4], sr_mat4 *out)
{
    memset(out, 0, sizeof *out);
    for (int r = 0; r < 3; r++) {
        for (int c = 0; c < 4; c++) {
            out->m[c * 4 + r] = (float)a[r][c];
        }
    }
    out->m[15] = 1.0f;
}

sr_result sr_py_make_texture(sr_context *ctx, const MeshObject *m, sr_texture **tex)
{
    *tex = NULL;
    if (!m->texture) {
        return SR_OK;
    }
    int th = (int)PyArray_DIM(m->texture, 0), tw = (int)PyArray_DIM(m->texture, 1);
    const uint8_t *src = PyArray_DATA(m->texture);
    uint8_t *rgba = NULL;
    if (PyArray_DIM(m->texture, 2) == 3) {
        rgba = malloc((size_t)tw * (size_t)th * 4);
        if (!rgba) {
            return SR_OUT_OF_MEMORY;
        }
        for (size_t p = 0; p < (size_t)tw * (size_t)th; p++) {
            memcpy(rgba + 4 * p, src + 3 * p, 3);
            rgba[4 * p + 3] = 255;
        }
    }
    sr_result r = sr_make_texture(ctx, &(sr_texture_desc){ .width = tw, .height = th,
                                                           .pixels = rgba ? rgba : src, .srgb = true },
                                  tex);
    free(rgba);
    return r;
}

static sr_result color_draw(sr_context *ctx, sr_framebuffer *fb, const render_job *j,
                            const instance *in, size_t faces, const void *proj)
{
    const MeshObject *m = in->mesh;
    sr_texture *tex;
    sr_result r = sr_py_make_texture(ctx, m, &tex);
    if (r != SR_OK) {
        return r;
    }
    sr_mat4 model;
    sr_py_mat_from_rows(in->a, &model);
    sr_state st = {
        .depth_zero_to_one = true, .depth_func = SR_GREATER,
        .cull = j->cull_back ? SR_CULL_BACK : SR_CULL_NONE,
        .front_face = sr_py_mirrors(in->a) ? SR_FRONT_CW : SR_FRONT_CCW,
        .shading = !j->lit ? SR_SHADING_UNLIT : m->normals ? SR_SHADING_PHONG : SR_SHADING_FLAT,
        .two_sided = true,
        .ambient = { 0.25f, 0.25f, 0.25f }, .texture = tex, .texture_filter = in->filter,
        .wrap_u = in->wrap_u, .wrap_v = in->wrap_v,
        /* A headlight: the view is the identity, so "world" is camera space. */
        .lights = { { .type = SR_LIGHT_DIRECTIONAL, .vector = { 0, 0, 1 }, .intensity = 0.75f } },
    };
    sr_draw_desc d = {
        .vertex_count = (size_t)PyArray_DIM(m->vertices, 0),
        .positions = in->positions,
        .normals = m->normals ? PyArray_DATA(m->normals) : NULL,
        .colors = m->colors ? PyArray_DATA(m->colors) : NULL,
        .color_size = m->colors ? (int)PyArray_DIM(m->colors, 1) : 0,
        .texcoords = m->uvs ? PyArray_DATA(m->uvs) : NULL,
        .indices = in->indices, .index_type = SR_INDEX_U32, .index_count = 3 * faces,
        .model = &model, .projection = proj,
    };
    r = sr_draw(ctx, fb, &st, &d);
    sr_destroy_texture(ctx, tex);
    return r;
}

/* The color pass: into fb, or antialiased into a framebuffer of samples
 * or of k x k pixels a pixel, then resolved into fb. */
static sr_result color_pass(sr_context *ctx, sr_framebuffer *fb, const render_job *j)
{
    sr_framebuffer *work = NULL;
    sr_result r = SR_OK;
    if (j->msaa > 1 || j->ssaa > 1) {
        r = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){
            .width = j->width * j->ssaa, .height = j->height * j->ssaa,
            .depth_format = SR_DEPTH_D32F, .samples = j->msaa }, &work);
        if (r != SR_OK) {
            return r;
        }
    }
    sr_framebuffer *target = work ? work : fb;
    r = sr_clear(ctx, target, &(sr_clear_desc){
        .color = { j->background[0], j->background[1], j->background[2], j->rgba ? 0.0f : 1.0f },
        .depth_action = SR_ACTION_CLEAR, .depth = 0 });
    double kx[3], ky[2];
    clip_rows(j, kx, ky);
    /* The same clip coordinates as geometry_vertex, as a matrix. */
    sr_mat4 proj = { { 0 } };
    proj.m[0] = (float)kx[0], proj.m[4] = (float)kx[1];
    proj.m[5] = (float)ky[0];
    if (j->ortho) {
        double range = (double)j->far - j->near;
        proj.m[12] = (float)kx[2], proj.m[13] = (float)ky[1];
        proj.m[10] = (float)(-1.0 / range), proj.m[14] = (float)(j->far / range);
        proj.m[15] = 1.0f;
    } else {
        proj.m[8] = (float)kx[2], proj.m[9] = (float)ky[1];
        proj.m[14] = j->near;
        proj.m[11] = 1.0f;
    }
    if (j->pbr) {
        /* The program's view takes the world to OpenGL's eye space (y up,
         * z backward): undo the flip of y and z here. */
        for (int c = 1; c < 3; c++) {
            for (int row = 0; row < 4; row++) {
                proj.m[c * 4 + row] = -proj.m[c * 4 + row];
            }
        }
    }
    /* (Clip space does not depend on the framebuffer's size: the same
     * projection draws the larger one.) */
    if (r == SR_OK) {
        r = j->pbr ? sr_py_pbr_pass(ctx, target, j, &proj)
                   : draw_instances(ctx, target, j, color_draw, &proj);
    }
    if (r == SR_OK && work) {
        r = j->msaa > 1 ? sr_resolve(ctx, work, fb) : sr_downsample(ctx, work, fb, SR_RESAMPLE_BOX);
    }
    sr_destroy_framebuffer(ctx, work);
    if (r == SR_OK) {
        const uint8_t *px = sr_framebuffer_pixels(fb);
        size_t n = (size_t)j->width * (size_t)j->height;
        for (size_t p = 0; j->color && p < n; p++) {
            memcpy(j->color + 3 * p, px + 4 * p, 3);
        }
        if (j->rgba) {
            memcpy(j->rgba, px, 4 * n);
        }
    }
    return r;
}

/* Makes what the set lacks for j: a context, and a framebuffer of j's
 * size (replacing one of another size). */
static sr_result prepare_set(sr_py_render_set *s, const render_job *j)
{
    sr_result r = SR_OK;
    if (!s->ctx) {
        r = sr_make_context(&(sr_context_desc){ .threads = j->threads }, &s->ctx);
        if (r != SR_OK) {
            s->ctx = NULL;
            return r;
        }
        s->threads = j->threads;
    }
    if (s->fb && (s->width != j->width || s->height != j->height)) {
        sr_destroy_framebuffer(s->ctx, s->fb);
        s->fb = NULL;
    }
    if (!s->fb) {
        r = sr_make_framebuffer(s->ctx, &(sr_framebuffer_desc){ .width = j->width,
                                                                 .height = j->height,
                                                                 .depth_format = SR_DEPTH_D32F },
                                &s->fb);
        if (r != SR_OK) {
            s->fb = NULL;
            return r;
        }
        s->width = j->width;
        s->height = j->height;
    }
    return r;
}

/* Runs without the GIL: touches no Python object, only array memory. */
static void run(render_job *j, sr_py_render_set *s)
{
    j->set = s;
    sr_set_last_error(NULL);    /* a failure below names itself, not an older one */
    sr_result r = prepare_set(s, j);
    if (r != SR_OK && !s->ctx) {
        snprintf(j->error, sizeof j->error, "cannot make a context: %s", sr_py_why(r));
        return;
    }
    sr_context *ctx = s->ctx;
    sr_framebuffer *fb = s->fb;
    bool geometry = j->depth || j->triangle_id || j->instance_id || j->barycentric || j->normal ||
                    j->mask || j->material_id || j->position || j->uv || j->flow;
    if (r == SR_OK && geometry) {
        r = geometry_pass(ctx, fb, j);
    }
    if (r == SR_OK && (j->color || j->rgba)) {
        r = color_pass(ctx, fb, j);
    }
    if (r != SR_OK) {
        /* The thread's message: the context's calls and those without one
         * (the lights' set-up) alike. */
        snprintf(j->error, sizeof j->error, "%s", sr_py_why(r));
    }
}

/* An output array from the Python layer: None, or C-contiguous of the
 * given type and shape (height, width[, channels]). */
static int take_output(PyObject *obj, const char *name, int type, int height, int width, int channels,
                       void **out)
{
    *out = NULL;
    if (obj == Py_None) {
        return 0;
    }
    const int types[] = { type, -1 };
    npy_intp shape[3] = { height, width, channels };
    PyArrayObject *a = sr_py_take_array(obj, name, channels ? 3 : 2, shape, types);
    if (!a) {
        return -1;
    }
    if ((PyObject *)a != obj || !PyArray_ISWRITEABLE(a)) {
        PyErr_Format(PyExc_ValueError, "%s: array is read-only, not aligned or not in native byte order", name);
        Py_DECREF(a);
        return -1;
    }
    *out = PyArray_DATA(a);
    Py_DECREF(a);   /* the caller holds obj for the call */
    return 0;
}

static int take_matrix(PyObject *obj, const char *name, int rows, int cols, double *out)
{
    static const int types[] = { NPY_FLOAT64, -1 };
    npy_intp shape[2] = { rows, cols };
    PyArrayObject *a = sr_py_take_array(obj, name, 2, shape, types);
    if (!a) {
        return -1;
    }
    memcpy(out, PyArray_DATA(a), sizeof(double) * (size_t)(rows * cols));
    Py_DECREF(a);
    for (int i = 0; i < rows * cols; i++) {
        if (!isfinite(out[i])) {
            PyErr_Format(PyExc_ValueError, "%s: contains NaN or infinity", name);
            return -1;
        }
    }
    return 0;
}

/* An instance's look for the metallic-roughness pass: (pose (3, 4),
 * base color (4), metallic, roughness, emissive (3), emissive strength,
 * alpha mode (0 opaque, 1 mask, 2 blend), alpha cutoff, double-sided,
 * unlit, normal scale, occlusion strength, ior, specular, specular color
 * (3), clearcoat, clearcoat roughness, sheen color (3), sheen roughness,
 * (transmission, thickness, attenuation color (3), attenuation distance),
 * (anisotropy strength, rotation, iridescence, its ior, thickness min and
 * max), (dispersion, diffuse transmission, its color (3)), (specular-
 * glossiness, its specular (3), glossiness), source: None or (the loaded
 * scene's capsule, primitive index)). */
static int take_look(PyObject *look, Py_ssize_t i, instance *in)
{
    PyObject *pose, *source;
    sr_pbr_material *m = &in->factors;
    *m = sr_pbr_default_material();
    int mode, double_sided, unlit;
    float *c = m->base_color, *e = m->emissive, *sc = m->specular_color, *sh = m->sheen_color;
    float *ac = m->attenuation_color, *dc = m->diffuse_transmission_color, *sp = m->sg_specular;
    int sg;
    if (!PyTuple_Check(look) ||
        !PyArg_ParseTuple(look,
                          "O(ffff)ff(fff)fifppffff(fff)ff(fff)f(ff(fff)f)(ffffff)(ff(fff))"
                          "(p(fff)f)O",
                          &pose,
                          &c[0],
                          &c[1], &c[2], &c[3], &m->metallic, &m->roughness, &e[0], &e[1], &e[2],
                          &m->emissive_strength, &mode, &m->alpha_cutoff, &double_sided, &unlit,
                          &m->normal_scale, &m->occlusion_strength, &m->ior, &m->specular,
                          &sc[0], &sc[1], &sc[2], &m->clearcoat, &m->clearcoat_roughness,
                          &sh[0], &sh[1], &sh[2], &m->sheen_roughness, &m->transmission,
                          &m->thickness, &ac[0], &ac[1], &ac[2], &m->attenuation_distance,
                          &m->anisotropy_strength, &m->anisotropy_rotation, &m->iridescence,
                          &m->iridescence_ior, &m->iridescence_thickness_min,
                          &m->iridescence_thickness_max, &m->dispersion,
                          &m->diffuse_transmission, &dc[0], &dc[1], &dc[2], &sg, &sp[0],
                          &sp[1], &sp[2], &m->glossiness, &source)) {
        PyErr_Clear();
        PyErr_Format(PyExc_TypeError, "instances[%zd]: the look is malformed", i);
        return -1;
    }
    if (mode < 0 || mode > 2) {
        PyErr_Format(PyExc_ValueError, "instances[%zd]: alpha mode %d", i, mode);
        return -1;
    }
    m->alpha_mode = mode == 1 ? SR_ALPHA_MASK : mode == 2 ? SR_ALPHA_BLEND : SR_ALPHA_OPAQUE;
    m->double_sided = double_sided;
    m->unlit = unlit;
    m->specular_glossiness = sg;
    m->specular_set = true;   /* white 1 draws as absent */
    m->iridescence_thickness_set = true;   /* 0 nm is no film, not the default */
    m->emissive_strength_set = true;       /* 0 is no emission, not the default 1 */
    if (take_matrix(pose, "pose", 3, 4, &in->pose[0][0]) < 0) {
        return -1;
    }
    in->src = NULL;
    if (source != Py_None) {
        PyObject *capsule;
        Py_ssize_t index;
        if (!PyArg_ParseTuple(source, "On", &capsule, &index)) {
            return -1;
        }
        in->src = sr_py_file_draw_of(capsule, index);
        if (!in->src) {
            return -1;
        }
    }
    return 0;
}

static int take_instances(PyObject *seq, render_job *j)
{
    PyObject *fast = PySequence_Fast(seq, "instances: expected a sequence");
    if (!fast) {
        return -1;
    }
    Py_ssize_t n = PySequence_Fast_GET_SIZE(fast);
    j->inst = calloc(n ? (size_t)n : 1, sizeof *j->inst);
    if (!j->inst) {
        Py_DECREF(fast);
        PyErr_NoMemory();
        return -1;
    }
    j->count = (size_t)n;
    for (Py_ssize_t i = 0; i < n; i++) {
        PyObject *item = PySequence_Fast_GET_ITEM(fast, i);
        PyObject *mesh, *a, *nm, *look = Py_None;
        int id, filter = 0, wrap_u = 0, wrap_v = 0;
        instance *in = &j->inst[i];
        if (!PyTuple_Check(item) ||
            !PyArg_ParseTuple(item, "O!OOi|O(iii)", &sr_py_MeshType, &mesh, &a, &nm, &id, &look,
                              &filter, &wrap_u, &wrap_v)) {
            PyErr_Clear();
            PyErr_Format(PyExc_TypeError,
                         "instances[%zd]: expected (Mesh, (3, 4) matrix, (3, 3) matrix, int"
                         "[, look or None[, (filter, wrap_u, wrap_v)]])", i);
            goto fail;
        }
        if (filter < SR_FILTER_DEFAULT || filter > SR_FILTER_TRILINEAR ||
            wrap_u < SR_WRAP_DEFAULT || wrap_u > SR_WRAP_MIRROR ||
            wrap_v < SR_WRAP_DEFAULT || wrap_v > SR_WRAP_MIRROR) {
            PyErr_Format(PyExc_ValueError, "instances[%zd]: sampler (%d, %d, %d)", i, filter,
                         wrap_u, wrap_v);
            goto fail;
        }
        in->filter = (sr_texture_filter)filter;
        in->wrap_u = (sr_texture_wrap)wrap_u;
        in->wrap_v = (sr_texture_wrap)wrap_v;
        if (j->pbr && (look == Py_None || take_look(look, i, in) < 0)) {
            if (look == Py_None) {
                PyErr_Format(PyExc_TypeError, "instances[%zd]: pbr needs the look", i);
            }
            goto fail;
        }
        in->mesh = (MeshObject *)mesh;
        in->id = id;
        if (!in->mesh->vertices) {
            PyErr_Format(PyExc_ValueError, "instances[%zd]: the Mesh was never initialized", i);
            goto fail;
        }
        if (take_matrix(a, "pose", 3, 4, &in->a[0][0]) < 0 ||
            take_matrix(nm, "normal matrix", 3, 3, &in->nm[0][0]) < 0) {
            goto fail;
        }
        MeshObject *m = in->mesh;
        size_t faces = (size_t)PyArray_DIM(m->faces, 0);
        if (m->zeros_count < 3 * faces + 2) {
            free(m->zeros);
            m->zeros = calloc(3 * faces + 2, sizeof(float));
            m->zeros_count = m->zeros ? 3 * faces + 2 : 0;
            if (!m->zeros) {
                PyErr_NoMemory();
                goto fail;
            }
        }
        Py_ssize_t bad = sr_py_mesh_bad_face(m);
        if (bad >= 0) {
            PyErr_Format(PyExc_ValueError,
                         "instances[%zd]: faces: face %zd has an index outside [0, %zd) "
                         "(the array changed after the Mesh was made)",
                         i, bad, (Py_ssize_t)PyArray_DIM(m->vertices, 0));
            goto fail;
        }
        if ((j->color || j->rgba) &&
            sr_py_mesh_draw_arrays(m, &in->positions, &in->indices, in->held) < 0) {
            goto fail;
        }
    }
    Py_DECREF(fast);
    return 0;
fail:
    Py_DECREF(fast);
    return -1;
}

static void free_instances(render_job *j)
{
    for (size_t i = 0; j->inst && i < j->count; i++) {
        Py_CLEAR(j->inst[i].held[0]);
        Py_CLEAR(j->inst[i].held[1]);
    }
    free(j->inst);
}

/* render(materials=): None (every instance's material_id -1), or one
 * int32 a instance. */
static int take_material_ids(PyObject *materials, render_job *j)
{
    for (size_t i = 0; i < j->count; i++) {
        j->inst[i].material_id = -1;
    }
    if (materials == Py_None) {
        return 0;
    }
    PyObject *seq = PySequence_Fast(materials, "materials: expected a sequence of ints");
    if (!seq) {
        return -1;
    }
    if ((size_t)PySequence_Fast_GET_SIZE(seq) != j->count) {
        PyErr_Format(PyExc_ValueError, "materials: %zd ids for %zu instances",
                     PySequence_Fast_GET_SIZE(seq), j->count);
        Py_DECREF(seq);
        return -1;
    }
    for (size_t i = 0; i < j->count; i++) {
        long v = PyLong_AsLong(PySequence_Fast_GET_ITEM(seq, (Py_ssize_t)i));
        if (v == -1 && PyErr_Occurred()) {
            Py_DECREF(seq);
            return -1;
        }
        if (v < -1 || v > INT32_MAX) {
            PyErr_Format(PyExc_ValueError, "materials[%zu]: %ld is not an id (-1 .. 2^31 - 1)", i,
                         v);
            Py_DECREF(seq);
            return -1;
        }
        j->inst[i].material_id = (int32_t)v;
    }
    Py_DECREF(seq);
    return 0;
}

/* render(lights=): None, or a sequence of at most SR_MAX_LIGHTS tuples
 * (type, (vector), (color), intensity, (direction), inner, outer, range)
 * of lit lights in world space, which the Python layer has checked. */
static int take_lights(PyObject *lights, render_job *j)
{
    if (j->lights_mode < 0 || j->lights_mode > 2) {
        PyErr_Format(PyExc_ValueError, "lights_mode: must be 0, 1 or 2, got %d", j->lights_mode);
        return -1;
    }
    if (lights == Py_None) {
        return 0;
    }
    PyObject *seq = PySequence_Fast(lights, "lights: expected a sequence of tuples");
    if (!seq) {
        return -1;
    }
    Py_ssize_t n = PySequence_Fast_GET_SIZE(seq);
    if (n > SR_MAX_LIGHTS) {
        PyErr_Format(PyExc_ValueError, "lights: at most %d, got %zd", SR_MAX_LIGHTS, n);
        Py_DECREF(seq);
        return -1;
    }
    for (Py_ssize_t i = 0; i < n; i++) {
        sr_light *l = &j->lights[i];
        int type;
        if (!PyArg_ParseTuple(PySequence_Fast_GET_ITEM(seq, i), "i(fff)(fff)f(fff)fff", &type,
                              &l->vector.x, &l->vector.y, &l->vector.z, &l->color.x,
                              &l->color.y, &l->color.z, &l->intensity, &l->direction.x,
                              &l->direction.y, &l->direction.z, &l->inner_cone, &l->outer_cone,
                              &l->range)) {
            Py_DECREF(seq);
            return -1;
        }
        if (type < SR_LIGHT_DIRECTIONAL || type > SR_LIGHT_SPOT) {
            PyErr_Format(PyExc_ValueError, "lights[%zd]: type %d is not a light", i, type);
            Py_DECREF(seq);
            return -1;
        }
        l->type = (sr_light_type)type;
    }
    j->light_count = (int)n;
    Py_DECREF(seq);
    return 0;
}

PyObject *sr_py_render(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kwlist[] = { "instances", "K", "width", "height", "near", "threads", "depth",
                              "triangle_id", "instance_id", "barycentric", "normal", "color",
                              "mask", "background", "lit", "rgba", "pbr", "view",
                              "environment", "shadows", "general", "ortho", "far", "msaa", "ssaa",
                              "ground", "cull", "lights", "lights_mode", "exposure", "tonemap",
                              "material_id", "position", "uv", "flow", "to_frame", "materials",
                              "flow_K", "flow_Rt", "flow_ortho", NULL };
    PyObject *instances, *K, *outs[8] = { NULL, NULL, NULL, NULL, NULL, NULL, NULL, Py_None };
    PyObject *view = Py_None, *env = Py_None, *lights = Py_None;
    PyObject *more[4] = { Py_None, Py_None, Py_None, Py_None };
    PyObject *to_frame = Py_None, *materials = Py_None, *flow_k = Py_None, *flow_rt = Py_None;
    int flow_ortho = 0;
    render_job j = { .msaa = 1, .ssaa = 1 };
    int lit = 1, pbr = 0, shadows = 0, general = 0, ortho = 0, ground = 0, cull = 0;
    int tonemap = SR_TONEMAP_DEFAULT;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OOiifiOOOOOOO(fff)p|OpOOpppfiippOifiOOOOOOOOp:render",
                                     kwlist,
                                     &instances, &K, &j.width, &j.height, &j.near, &j.threads,
                                     &outs[0], &outs[1], &outs[2], &outs[3], &outs[4], &outs[5],
                                     &outs[6], &j.background[0], &j.background[1],
                                     &j.background[2], &lit, &outs[7], &pbr, &view, &env,
                                     &shadows, &general, &ortho, &j.far, &j.msaa, &j.ssaa,
                                     &ground, &cull, &lights, &j.lights_mode, &j.exposure,
                                     &tonemap, &more[0], &more[1], &more[2], &more[3],
                                     &to_frame, &materials, &flow_k, &flow_rt, &flow_ortho)) {
        return NULL;
    }
    if (!(j.exposure >= -64.0f && j.exposure <= 64.0f) || tonemap < SR_TONEMAP_DEFAULT ||
        tonemap > SR_TONEMAP_NONE) {
        PyErr_Format(PyExc_ValueError, "exposure, tonemap: %g stops (-64 .. 64), curve %d "
                     "(0 .. 3)", (double)j.exposure, tonemap);
        return NULL;
    }
    j.tonemap = (sr_tonemap_op)tonemap;
    if (take_lights(lights, &j) < 0) {
        return NULL;
    }
    j.ortho = ortho;
    j.pbr = pbr;
    j.shadows = shadows;
    j.ground = ground;
    j.cull_back = cull;
    j.general = general;
    if (pbr && take_matrix(view, "view", 3, 4, &j.view[0][0]) < 0) {
        return NULL;
    }
    if (env != Py_None && !(j.env = sr_py_environment_of(env))) {
        return NULL;
    }
    if (j.width < 1 || j.width > SR_MAX_FRAMEBUFFER_SIZE || j.height < 1 ||
        j.height > SR_MAX_FRAMEBUFFER_SIZE) {
        PyErr_Format(PyExc_ValueError, "width, height: must be in 1 .. %d, got %d x %d",
                     SR_MAX_FRAMEBUFFER_SIZE, j.width, j.height);
        return NULL;
    }
    if (!(j.ortho ? j.near >= 0.0f : j.near > 0.0f) || !isfinite(j.near)) {
        PyErr_SetString(PyExc_ValueError, j.ortho ? "near: must be a finite distance >= 0"
                                                  : "near: must be a positive finite distance");
        return NULL;
    }
    if (j.ortho && (!(j.far > j.near) || !isfinite(j.far))) {
        PyErr_SetString(PyExc_ValueError, "far: must be finite and beyond near");
        return NULL;
    }
    bool msaa_ok = j.msaa == 1 || j.msaa == 2 || j.msaa == 4 || j.msaa == 8 || j.msaa == 16;
    if (!msaa_ok || j.ssaa < 1 || j.ssaa > 4 || (j.msaa > 1 && j.ssaa > 1) ||
        (long)j.width * j.ssaa > SR_MAX_FRAMEBUFFER_SIZE ||
        (long)j.height * j.ssaa > SR_MAX_FRAMEBUFFER_SIZE) {
        PyErr_Format(PyExc_ValueError, "antialias: msaa %d, ssaa %d at %d x %d: not a mode "
                     "(msaa 1, 2, 4, 8 or 16; ssaa 1 .. 4 and the image at most %d a side)",
                     j.msaa, j.ssaa, j.width, j.height, SR_MAX_FRAMEBUFFER_SIZE);
        return NULL;
    }
    if (j.threads < 0 || j.threads > 64) {
        PyErr_Format(PyExc_ValueError, "threads: must be in 0 .. 64 (0: every CPU), got %d",
                     j.threads);
        return NULL;
    }
    j.lit = lit;
    if (take_matrix(K, "K", 3, 3, &j.k[0][0]) < 0) {
        return NULL;
    }
    int H = j.height, W = j.width;
    void *ptr[12];
    if (take_output(outs[0], "depth", NPY_FLOAT32, H, W, 0, &ptr[0]) < 0 ||
        take_output(outs[1], "triangle_id", NPY_INT32, H, W, 0, &ptr[1]) < 0 ||
        take_output(outs[2], "instance_id", NPY_INT32, H, W, 0, &ptr[2]) < 0 ||
        take_output(outs[3], "barycentric", NPY_FLOAT32, H, W, 3, &ptr[3]) < 0 ||
        take_output(outs[4], "normal", NPY_FLOAT32, H, W, 3, &ptr[4]) < 0 ||
        take_output(outs[5], "color", NPY_UINT8, H, W, 3, &ptr[5]) < 0 ||
        take_output(outs[6], "mask", NPY_BOOL, H, W, 0, &ptr[6]) < 0 ||
        take_output(outs[7], "rgba", NPY_UINT8, H, W, 4, &ptr[7]) < 0 ||
        take_output(more[0], "material_id", NPY_INT32, H, W, 0, &ptr[8]) < 0 ||
        take_output(more[1], "position", NPY_FLOAT32, H, W, 3, &ptr[9]) < 0 ||
        take_output(more[2], "uv", NPY_FLOAT32, H, W, 2, &ptr[10]) < 0 ||
        take_output(more[3], "flow", NPY_FLOAT32, H, W, 2, &ptr[11]) < 0) {
        return NULL;
    }
    for (int r = 0; r < 3; r++) {
        j.to_frame[r][r] = 1.0;     /* the camera frame unless given */
    }
    if ((to_frame != Py_None && take_matrix(to_frame, "to_frame", 3, 4, &j.to_frame[0][0]) < 0) ||
        ((flow_k == Py_None) != (flow_rt == Py_None) &&
         (PyErr_SetString(PyExc_TypeError, "flow_K, flow_Rt: give both or neither"), 1)) ||
        (flow_k != Py_None && (take_matrix(flow_k, "flow_K", 3, 3, &j.flow_k[0][0]) < 0 ||
                               take_matrix(flow_rt, "flow_Rt", 3, 4, &j.flow_a[0][0]) < 0))) {
        return NULL;
    }
    j.flow_next = flow_k != Py_None;
    j.flow_ortho = flow_ortho;
    j.depth = ptr[0], j.triangle_id = ptr[1], j.instance_id = ptr[2];
    j.barycentric = ptr[3], j.normal = ptr[4], j.color = ptr[5], j.mask = ptr[6];
    j.rgba = ptr[7];
    j.material_id = ptr[8], j.position = ptr[9], j.uv = ptr[10], j.flow = ptr[11];
    if (take_instances(instances, &j) < 0 || take_material_ids(materials, &j) < 0) {
        free_instances(&j);
        return NULL;
    }
    /* The instances' meshes and the outputs stay referenced by the
     * caller's arguments for the whole call. */
    sr_py_render_set set;
    sr_py_take_render_set(j.threads, &set);
    Py_BEGIN_ALLOW_THREADS
    run(&j, &set);
    Py_END_ALLOW_THREADS
    sr_py_give_back_render_set(&set, !j.error[0]);
    free_instances(&j);
    if (j.error[0]) {
        PyErr_SetString(PyExc_RuntimeError, j.error);
        return NULL;
    }
    Py_RETURN_NONE;
}
