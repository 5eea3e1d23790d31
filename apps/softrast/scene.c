/* scene.c - the built-in scene: the Utah teapot, tessellated at run time
 * from its Bezier patches, on a checkered ground plane. */
#include "scene.h"
#include "softrast_io.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A square ground of n x n tiles in the plane y = 0, centred on the origin,
 * with alternating colors.  Each tile has its own four vertices so the
 * colors stay crisp under interpolation. */
static void free_arrays(sr_mesh *m)
{
    free(m->positions);
    free(m->normals);
    free(m->colors);
    free(m->indices);
}

/* Built in malloc'd arrays, then made a mesh on ctx. */
static sr_result make_ground(sr_context *ctx, sr_mesh *out, float half, int n)
{
    sr_mesh ground = { 0 }, *m = &ground;
    size_t verts = (size_t)n * n * 4, tris = (size_t)n * n * 2;
    m->positions = malloc(verts * 3 * sizeof(float));
    m->normals = malloc(verts * 3 * sizeof(float));
    m->colors = malloc(verts * 4 * sizeof(float));
    m->indices = malloc(tris * 3 * sizeof(uint32_t));
    if (!m->positions || !m->normals || !m->colors || !m->indices) {
        free_arrays(m);
        return SR_OUT_OF_MEMORY;
    }
    m->vertex_count = verts;
    m->triangle_count = tris;
    float step = 2.0f * half / n;
    const float light[3] = { 0.80f, 0.80f, 0.78f }, dark[3] = { 0.56f, 0.58f, 0.60f };
    size_t v = 0, t = 0;
    for (int j = 0; j < n; j++) {
        for (int i = 0; i < n; i++) {
            const float *c = ((i + j) & 1) ? dark : light;
            float x0 = -half + i * step, z0 = -half + j * step;
            float corners[4][2] = { { x0, z0 }, { x0, z0 + step }, { x0 + step, z0 + step },
                                    { x0 + step, z0 } };
            for (int k = 0; k < 4; k++) {
                float *p = &m->positions[(v + k) * 3];
                p[0] = corners[k][0];
                p[1] = 0.0f;
                p[2] = corners[k][1];
                float *nn = &m->normals[(v + k) * 3];
                nn[0] = 0.0f;
                nn[1] = 1.0f;
                nn[2] = 0.0f;
                float *cc = &m->colors[(v + k) * 4];
                cc[0] = c[0];
                cc[1] = c[1];
                cc[2] = c[2];
                cc[3] = 1.0f;
            }
            /* Counter-clockwise seen from above (+y). */
            uint32_t *ix = &m->indices[t * 3];
            ix[0] = (uint32_t)v;
            ix[1] = (uint32_t)v + 1;
            ix[2] = (uint32_t)v + 2;
            ix[3] = (uint32_t)v;
            ix[4] = (uint32_t)v + 2;
            ix[5] = (uint32_t)v + 3;
            v += 4;
            t += 2;
        }
    }
    sr_result r = sr_make_mesh(ctx, m, out);
    free_arrays(m);
    return r;
}

sr_result scene_builtin(sr_context *ctx, scene *s, int detail)
{
    memset(s, 0, sizeof *s);
    scene_object *pot = &s->objects[0];
    sr_result r = sr_make_teapot(ctx, detail, &pot->mesh);
    if (r != SR_OK) {
        return r;
    }
    pot->material = (sr_material){
        .diffuse = { 0.78f, 0.30f, 0.16f },
        .specular = { 0.55f, 0.50f, 0.45f },
        .shininess = 60.0f,
    };
    pot->model = sr_mat4_identity();
    pot->frame = true;
    s->count = 1;

    sr_vec3 lo, hi;
    sr_mesh_bounds(&pot->mesh, &lo, &hi);
    float extent = fmaxf(hi.x - lo.x, hi.z - lo.z);
    scene_object *ground = &s->objects[1];
    r = make_ground(ctx, &ground->mesh, extent * 1.6f, 12);
    if (r != SR_OK) {
        scene_free(ctx, s);
        return r;
    }
    ground->material = (sr_material){ .diffuse = { 1, 1, 1 }, .specular = { 0.08f, 0.08f, 0.08f },
                                      .shininess = 16.0f };
    ground->model = sr_mat4_translate(0.0f, lo.y, 0.0f);
    ground->frame = false;
    s->count = 2;
    return SR_OK;
}

void scene_free(sr_context *ctx, scene *s)
{
    for (int i = 0; i < s->count; i++) {
        sr_destroy_mesh(ctx, &s->objects[i].mesh);
        free(s->objects[i].part_material);
        free(s->objects[i].tangents);
        free(s->objects[i].texcoords1);
        free(s->objects[i].base_uv);
        s->objects[i].part_material = NULL;
        s->objects[i].base_uv = NULL;
        s->objects[i].tangents = s->objects[i].texcoords1 = NULL;
    }
    sr_destroy_scene(ctx, s->gltf);
    s->gltf = NULL;
    s->count = 0;
}

/* Vertex p after M_O as sr_mat4_mul_vec4 computes it (w = 1), in line:
 * a library call per vertex was two thirds of the bounds' time. */
static inline void to_world(const sr_mat4 *m, const float *p, double q[3])
{
    const float *a = m->m;
    for (int k = 0; k < 3; k++) {
        q[k] = a[k] * p[0] + a[4 + k] * p[1] + a[8 + k] * p[2] + a[12 + k] * 1.0f;
    }
}

/* The box of the transformed vertices (infinite when there are none).
 * The running bounds are never NaN, so `q < lo ? q : lo` is fmin(lo, q)
 * to the bit (a NaN q is skipped, and of two zeros the bound keeps its
 * own, as glibc's fmin does) without a call per value. */
static void world_box(const scene *s, bool framed_only, double lo[3], double hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    for (int o = 0; o < s->count; o++) {
        const scene_object *ob = &s->objects[o];
        for (size_t i = 0; i < ob->mesh.vertex_count && (ob->frame || !framed_only); i++) {
            double q[3];
            to_world(&ob->model, &ob->mesh.positions[i * 3], q);
            for (int k = 0; k < 3; k++) {
                lo[k] = q[k] < lo[k] ? q[k] : lo[k];
                hi[k] = q[k] > hi[k] ? q[k] : hi[k];
            }
        }
    }
}

/* Sphere around the transformed bounding-box centre that holds every
 * transformed vertex. */
void scene_bounds(const scene *s, bool framed_only, sr_vec3 *centre, float *radius)
{
    if (s->bounds_cached) {
        *centre = s->cached_centre[framed_only ? 0 : 1];
        *radius = s->cached_radius[framed_only ? 0 : 1];
        return;
    }
    double lo[3], hi[3];
    world_box(s, framed_only, lo, hi);
    double c[3] = { (lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2 };
    if (!isfinite(c[0])) {
        *centre = (sr_vec3){ 0, 0, 0 };
        *radius = 1.0f;
        return;
    }
    double r2 = 0.0;
    for (int o = 0; o < s->count; o++) {
        const scene_object *ob = &s->objects[o];
        for (size_t i = 0; i < ob->mesh.vertex_count && (ob->frame || !framed_only); i++) {
            double q[3];
            to_world(&ob->model, &ob->mesh.positions[i * 3], q);
            double d2 = (q[0] - c[0]) * (q[0] - c[0]) + (q[1] - c[1]) * (q[1] - c[1]) +
                        (q[2] - c[2]) * (q[2] - c[2]);
            r2 = d2 > r2 ? d2 : r2;
        }
    }
    *centre = (sr_vec3){ (float)c[0], (float)c[1], (float)c[2] };
    *radius = r2 > 0.0 ? (float)sqrt(r2) : 1.0f;
}

void scene_cache_bounds(scene *s)
{
    s->bounds_cached = false;
    s->fit_cached = false;
    scene_bounds(s, true, &s->cached_centre[0], &s->cached_radius[0]);
    bool all_framed = true;
    for (int o = 0; o < s->count; o++) {
        all_framed &= s->objects[o].frame || s->objects[o].mesh.vertex_count == 0;
    }
    if (all_framed) {   /* a model alone: both spheres are the same */
        s->cached_centre[1] = s->cached_centre[0];
        s->cached_radius[1] = s->cached_radius[0];
    } else {
        scene_bounds(s, false, &s->cached_centre[1], &s->cached_radius[1]);
    }
    double lo[3], hi[3];
    world_box(s, true, lo, hi);
    bool finite = isfinite(lo[0]) && isfinite(hi[0]);
    s->box_min = finite ? (sr_vec3){ (float)lo[0], (float)lo[1], (float)lo[2] } : s->cached_centre[0];
    s->box_max = finite ? (sr_vec3){ (float)hi[0], (float)hi[1], (float)hi[2] } : s->cached_centre[0];
    s->bounds_cached = true;
}
