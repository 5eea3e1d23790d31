/*
 * render.h - what render.c's passes share with the metallic-roughness
 * pass (render_pbr.c): the instances and the job as render() was handed
 * them, and the helpers both color passes use.  Read by the drawing
 * thread without the GIL.
 */
#ifndef SR_PY_RENDER_H
#define SR_PY_RENDER_H

#include "module.h"

/* One instance as render() was handed it. */
typedef struct instance {
    MeshObject *mesh;
    double a[3][4], nm[3][3];
    int32_t id;
    int32_t material_id;        /* the material_id output's value */
    const float *positions;     /* for the color pass */
    const uint32_t *indices;
    PyObject *held[2];          /* the arrays they point into, for the call */
    /* How the Mesh's texture is sampled: its Material's sampler (a loaded
     * file's), else the library's defaults. */
    sr_texture_filter filter;
    sr_texture_wrap wrap_u, wrap_v;
    /* For the metallic-roughness look: the object -> world pose, the
     * Material's factors, alpha mode and flags (no textures), and the
     * loaded primitive it came from (its textures and arrays), or NULL. */
    double pose[3][4];
    sr_pbr_material factors;
    const sr_py_file_draw *src;
} instance;

typedef struct render_job {
    instance *inst;
    size_t count;
    int width, height, threads;
    double k[3][3];
    double view[3][4];          /* world -> camera [R | t], for the metallic-roughness look */
    float near;
    bool ortho;                 /* K maps camera x, y to pixels; rays along +z */
    float far;                  /* ortho: where the window depth reaches 0 */
    float background[3];
    /* color: antialiased with msaa samples a pixel, or drawn ssaa x ssaa
     * times larger and box-filtered down (at most one of them above 1) */
    int msaa, ssaa;
    bool lit;                   /* color: headlight-lit, else the colors as they are */
    bool pbr;                   /* color: the metallic-roughness program instead */
    const sr_environment *env;  /* pbr: its image-based light, or NULL (the hemisphere) */
    bool shadows;               /* pbr: the key light's shadow map */
    bool ground;                /* pbr, with shadows: the shadow catcher under the instances */
    /* pbr: softrast render's --lights: the default rig (0), the given
     * lights (1: a file's, in world space and the extension's units) or
     * both (2); `lights` holds light_count lit ones, in the file's order. */
    int lights_mode;
    sr_light lights[SR_MAX_LIGHTS];
    int light_count;
    float exposure;             /* pbr: --exposure, stops */
    sr_tonemap_op tonemap;      /* pbr: --tonemap */
    float *depth;
    int32_t *triangle_id, *instance_id, *material_id;
    float *barycentric, *normal, *position, *uv, *flow;
    double to_frame[3][4];      /* position: camera -> the output's frame */
    /* flow: camera -> the next view's camera, its K and projection;
     * without a next view (flow_next false) the flow is NaN */
    bool flow_next, flow_ortho;
    double flow_a[3][4], flow_k[3][3];
    uint8_t *color, *rgba;
    npy_bool *mask;
    bool cull_back;             /* faces seen from behind are not drawn */
    bool general;               /* geometry: the library's pipeline, not the visibility pass */
    sr_py_render_set *set;      /* what run() draws with */
    char error[512];
} render_job;

/* Whether the 3x3 part of a flips handedness (its determinant is
 * negative), turning the mesh's front faces clockwise on screen. */
bool sr_py_mirrors(const double a[3][4]);
/* The column-major matrix of rows a (the fourth row 0 0 0 1). */
void sr_py_mat_from_rows(const double a[3][4], sr_mat4 *out);
/* The mesh's texture on ctx (RGB expanded to RGBA), or NULL without one. */
sr_result sr_py_make_texture(sr_context *ctx, const MeshObject *m, sr_texture **tex);
/* The color pass of shading="pbr" (render_pbr.c) with `proj` taking
 * OpenGL's eye space to clip space; the framebuffer is cleared. */
sr_result sr_py_pbr_pass(sr_context *ctx, sr_framebuffer *fb, const render_job *j,
                         const sr_mat4 *proj);

#endif
