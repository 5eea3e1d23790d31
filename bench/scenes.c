/* scenes.c - builds the benchmark scenes (bench): loads the models and
 * frames and lights them with `softrast render`'s own defaults
 * (apps/softrast/framing.c), and generates the synthetic ones with a fixed
 * seed.  Runs once per scene,
 * before any frame is timed, on the main thread. */
#include "scenes.h"
#include "framing.h"
#include "softrast_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI_F 3.14159265358979f

const bench_scene_info bench_scene_list[] = {
    { "bunny",  BENCH_MESH,  "stanford-bunny.obj", 0, NULL, 0 },
    { "spot",   BENCH_MESH,  "spot.obj", 0, NULL, 0 },
    { "teapot", BENCH_MESH,  "teapot.obj", 0, NULL, 0 },
    { "small",  BENCH_SMALL, NULL, 0, NULL, 0 },
    { "fill",   BENCH_FILL,  NULL, 0, NULL, 0 },
    { "cli",    BENCH_CLI,   "stanford-bunny.obj", 0, NULL, 0 },
    { "lines",  BENCH_LINES, NULL, 0, NULL, 0 },
    { "polyfill", BENCH_POLYFILL, NULL, 0, NULL, 0 },
    { "polyfill_aa", BENCH_POLYFILL_AA, NULL, 0, NULL, 0 },
    { "shapes2d", BENCH_SHAPES2D, NULL, 0, NULL, 0 },
    { "icons", BENCH_ICONS, NULL, 0, NULL, 0 },
    { "msaa4",  BENCH_MESH,  "stanford-bunny.obj", 4, NULL, 0 },
    { "spot_tex", BENCH_MESH, "spot.obj", 0, "spot_texture.png", 0 },
    { "phong",  BENCH_MESH,  "stanford-bunny.obj", 0, NULL, BENCH_LOOK_PHONG },
    { "pbr",    BENCH_MESH,  "stanford-bunny.obj", 0, NULL, BENCH_LOOK_PBR },
    { "pbr_studio", BENCH_MESH, "stanford-bunny.obj", 0, NULL, BENCH_LOOK_PBR_STUDIO },
    { "pbr_textured", BENCH_MESH, "pbr_tiles.glb", 0, NULL, BENCH_LOOK_PBR_TEXTURED },
};
const int bench_scene_count = (int)(sizeof bench_scene_list / sizeof bench_scene_list[0]);

const bench_scene_info *bench_find_scene(const char *name)
{
    for (int i = 0; i < bench_scene_count; i++) {
        if (strcmp(bench_scene_list[i].name, name) == 0) {
            return &bench_scene_list[i];
        }
    }
    return NULL;
}

const char *bench_models_dir(void)
{
    const char *dir = getenv("SR_MODELS_DIR");
    return dir && dir[0] ? dir : SR_BENCH_MODELS_DIR;
}

/* ---- models, framed like `softrast render` ------------------------------ */

/* The bounding sphere of apps/softrast/scene.c: centred on the bounding
 * box, radius to the farthest vertex. */
static void mesh_sphere(const sr_mesh *m, sr_vec3 *centre, float *radius)
{
    sr_vec3 lo, hi;
    if (!sr_mesh_bounds(m, &lo, &hi)) {
        *centre = (sr_vec3){ 0, 0, 0 };
        *radius = 1.0f;
        return;
    }
    double c[3] = { ((double)lo.x + hi.x) / 2, ((double)lo.y + hi.y) / 2,
                    ((double)lo.z + hi.z) / 2 };
    double r2 = 0.0;
    for (size_t i = 0; i < m->vertex_count; i++) {
        const float *p = &m->positions[i * 3];
        double d[3] = { p[0] - c[0], p[1] - c[1], p[2] - c[2] };
        /* A comparison rather than fmax (both skip a NaN): GCC 12 for
         * aarch64 crashes vectorizing an fmax reduction. */
        double x = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        r2 = x > r2 ? x : r2;
    }
    *centre = (sr_vec3){ (float)c[0], (float)c[1], (float)c[2] };
    *radius = r2 > 0.0 ? (float)sqrt(r2) : 1.0f;
}

/* Frame and light the mesh exactly as `softrast render` does by default
 * (apps/softrast/framing.c). */
static void frame_mesh(bench_scene *s, sr_camera_basis *basis)
{
    sr_vec3 c;
    float r;
    mesh_sphere(&s->mesh, &c, &r);
    float fov = SR_FRAMING_FOV_DEG * PI_F / 180.0f;
    /* The bounding sphere's framing, not the CLI's tighter fit: a scene's
     * pixels stay what they were, so its figures compare across dates. */
    sr_vec3 eye = framing_default_eye(c, r, fov);
    sr_camera_frame(eye, sr_vec3_sub(c, eye), (sr_vec3){ 0, 1, 0 }, basis);
    s->view = sr_camera_matrix(basis);
    s->model = sr_mat4_identity();
    float near_z, far_z;
    framing_near_far(eye, c, r, &near_z, &far_z);
    float aspect = (float)s->width / (float)s->height;
    s->projection = sr_perspective(sr_fit_fovy(fov, s->width, s->height), aspect, near_z, far_z,
                                   false);
}

/* The one primitive of the generated glTF asset as the scene's mesh; the
 * file stays loaded (s->gltf) for its material and tangents. */
static sr_result load_gltf_mesh(bench_scene *s, const char *path, char *msg, size_t msg_size)
{
    if (!sr_io_have_gltf()) {
        /* Counted as a missing model, not a failure. */
        snprintf(msg, msg_size, "%s: this build reads no glTF (install libjansson-dev)", path);
        return SR_IO_ERROR;
    }
    sr_io_error err;
    sr_result r = sr_load_scene(s->mesh_ctx, path,
                                &(sr_load_desc){ .format = SR_FORMAT_GLTF }, &s->gltf, &err);
    if (r != SR_OK) {
        snprintf(msg, msg_size, "%s", err.message);
        return r;
    }
    const sr_scene_primitive *p = &s->gltf->primitives[0];
    static const float identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    if (s->gltf->primitive_count != 1 || memcmp(p->world, identity, sizeof identity) != 0 ||
        !p->normals || !p->texcoords0) {
        snprintf(msg, msg_size, "%s: not the asset softrast-pbr-asset writes", path);
        return SR_BAD_FORMAT;
    }
    r = sr_make_mesh(s->mesh_ctx, &(sr_mesh){
        .vertex_count = p->vertex_count, .positions = (float *)p->positions,
        .normals = (float *)p->normals, .texcoords = (float *)p->texcoords0,
        .triangle_count = p->triangle_count, .indices = (uint32_t *)p->indices }, &s->mesh);
    if (r != SR_OK) {
        snprintf(msg, msg_size, "%s: %s", path, sr_context_error(s->mesh_ctx));
    }
    return r;
}

/* `softrast render --environment studio --shadows on`'s shadow for the
 * key light, d->lights[0] (apps/softrast/render_shadow.c): a 1024-texel
 * map with a soft light over the mesh's box; the file's tangents for the
 * normal map. */
static sr_result make_gltf_shadow(bench_scene *s, sr_pbr_desc *d)
{
    sr_vec3 lo, hi;
    sr_mesh_bounds(&s->mesh, &lo, &hi);
    sr_result r = sr_make_shadow_map(s->mesh_ctx, &(sr_shadow_desc){
        .direction = s->state.lights[0].vector, .bounds_min = lo, .bounds_max = hi,
        .size = 1024, .light_radius = 0.04f }, &s->shadow);
    d->shadow = s->shadow;
    d->vertex_count = s->gltf->primitives[0].vertex_count;
    d->tangents = s->gltf->primitives[0].tangents;
    return r;
}

static sr_result make_mesh_scene(bench_scene *s, char *msg, size_t msg_size)
{
    char path[4096];
    bool gltf = s->info->look == BENCH_LOOK_PBR_TEXTURED;
    int n = snprintf(path, sizeof path, "%s/%s", gltf ? SR_BENCH_ASSET_DIR : bench_models_dir(),
                     s->info->model_file);
    if (n < 0 || (size_t)n >= sizeof path) {
        snprintf(msg, msg_size, "%s: model path too long", s->info->name);
        return SR_INVALID_ARG;
    }
    sr_io_error err;
    sr_result r = sr_make_context(&(sr_context_desc){ .threads = 1 }, &s->mesh_ctx);
    if (r != SR_OK) {
        snprintf(msg, msg_size, "%s: %s", s->info->name, sr_result_text(r));
        return r;
    }
    if (gltf) {
        r = load_gltf_mesh(s, path, msg, msg_size);
        if (r != SR_OK) {
            return r;
        }
    } else {
        r = sr_load_mesh(s->mesh_ctx, path, NULL, &s->mesh, &err);
        if (r != SR_OK) {
            snprintf(msg, msg_size, "%s", err.message);
            return r;
        }
        /* Smooth normals once, at load: the per-vertex lighting reads them. */
        r = sr_mesh_compute_normals(s->mesh_ctx, &s->mesh, SR_NORMALS_SMOOTH);
        if (r != SR_OK) {
            snprintf(msg, msg_size, "%s: computing normals: %s", path, sr_result_text(r));
            return r;
        }
    }
    if (s->info->texture_file) {
        if (!s->mesh.texcoords) {
            snprintf(msg, msg_size, "%s: no texture coordinates for %s", path,
                     s->info->texture_file);
            return SR_BAD_FORMAT;
        }
        n = snprintf(path, sizeof path, "%s/%s", bench_models_dir(), s->info->texture_file);
        if (n < 0 || (size_t)n >= sizeof path) {
            snprintf(msg, msg_size, "%s: texture path too long", s->info->name);
            return SR_INVALID_ARG;
        }
        r = sr_read_png(path, NULL, &s->texture_w, &s->texture_h, &s->texture_pixels, &err);
        if (r != SR_OK) {
            snprintf(msg, msg_size, "%s", err.message);
            return r;
        }
        s->texcoords = s->mesh.texcoords;
    }
    if (gltf) {
        s->texcoords = s->mesh.texcoords;   /* the maps' coordinates */
    }
    s->vertex_count = s->mesh.vertex_count;
    s->positions = s->mesh.positions;
    s->position_size = 3;
    s->normals = s->mesh.normals;
    /* The material color only (a file's vertex colors would need
     * GL_COLOR_MATERIAL on the GL side to match). */
    s->colors = NULL;
    s->indices = s->mesh.indices;
    s->index_count = s->mesh.triangle_count * 3;
    s->triangle_count = s->mesh.triangle_count;

    sr_camera_basis basis;
    frame_mesh(s, &basis);
    /* render.c's defaults for a model file: Gouraud asked for here instead
     * of its Phong; light gray material, back faces culled, depth LESS. */
    s->state = (sr_state){
        .cull = SR_CULL_BACK, .front_face = SR_FRONT_CCW, .depth_func = SR_LESS,
        .shading = SR_SHADING_GOURAUD,
        .material = { .diffuse = { 0.72f, 0.72f, 0.74f }, .specular = { 0.25f, 0.25f, 0.25f },
                      .shininess = 40.0f },
        .ambient = { 0.12f, 0.12f, 0.14f },
    };
    sr_default_lights(&basis, s->state.lights);
    if (s->info->look == BENCH_LOOK_PHONG) {
        s->state.shading = SR_SHADING_PHONG;
    } else if (s->info->look != BENCH_LOOK_GOURAUD) {
        /* render.c's default material: a light gray dielectric; or the
         * file's own. */
        sr_pbr_material m = sr_pbr_default_material();
        m.base_color[0] = m.base_color[1] = 0.72f;
        m.base_color[2] = 0.74f;
        m.metallic = 0.0f;
        m.roughness = 0.5f;
        if (gltf) {
            m = s->gltf->materials[s->gltf->primitives[0].material];
        }
        sr_pbr_desc d = { .material = &m, .model = &s->model, .view = &s->view,
                          .projection = &s->projection, .vertex_color = SR_OFF };
        sr_pbr_default_lighting(s->state.lights, &d);
        if (s->info->look == BENCH_LOOK_PBR_STUDIO || gltf) {
            /* The CLI's default light: the built-in studio at 0.6 and
             * the rig's key light. */
            r = sr_make_environment(s->mesh_ctx, &(sr_environment_desc){ .intensity = 0.6f },
                                    &s->env);
            if (r != SR_OK) {
                snprintf(msg, msg_size, "%s: %s", s->info->name, sr_context_error(s->mesh_ctx));
                return r;
            }
            d.environment = s->env;
            for (int l = 1; l < SR_MAX_LIGHTS; l++) {
                d.lights[l].type = SR_LIGHT_OFF;
            }
        }
        if (gltf) {
            r = make_gltf_shadow(s, &d);
            if (r != SR_OK) {
                snprintf(msg, msg_size, "%s: %s", s->info->name, sr_context_error(s->mesh_ctx));
                return r;
            }
        }
        r = sr_make_pbr_program(s->mesh_ctx, &d, &s->pbr);
        if (r != SR_OK) {
            snprintf(msg, msg_size, "%s: %s", s->info->name, sr_context_error(s->mesh_ctx));
            return r;
        }
        s->state.program = sr_pbr_program(s->pbr);
    }
    if (s->texture_pixels) {
        /* The texel multiplies the lit (Gouraud) color: GL_MODULATE. */
        s->state.texture_filter = SR_FILTER_TRILINEAR;
        s->state.wrap_u = s->state.wrap_v = SR_WRAP_REPEAT;
    }
    s->clear_color[0] = 0x1d / 255.0f;
    s->clear_color[1] = 0x22 / 255.0f;
    s->clear_color[2] = 0x30 / 255.0f;
    s->clear_color[3] = 1.0f;
    s->fragments_per_frame = (uint64_t)s->width * (uint64_t)s->height;
    return SR_OK;
}

/* ---- synthetic scenes, in NDC with identity matrices -------------------- */

/* splitmix64: a fixed seed gives the same scene on every run and machine. */
static uint64_t next_u64(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* Uniform in [lo, hi). */
static float uniform(uint64_t *state, float lo, float hi)
{
    return lo + (hi - lo) * (float)((double)(next_u64(state) >> 11) * 0x1.0p-53);
}

static sr_result alloc_synthetic(bench_scene *s, size_t vertices, char *msg, size_t msg_size)
{
    s->own_positions = malloc(vertices * 4 * sizeof(float));
    s->own_colors = malloc(vertices * 4 * sizeof(float));
    if (!s->own_positions || !s->own_colors) {
        snprintf(msg, msg_size, "%s: out of memory for %zu vertices", s->info->name, vertices);
        return SR_OUT_OF_MEMORY;
    }
    s->vertex_count = vertices;
    s->positions = s->own_positions;
    s->position_size = 4;
    s->colors = s->own_colors;
    s->model = s->view = s->projection = sr_mat4_identity();
    s->state = (sr_state){ .cull = SR_CULL_NONE, .depth_func = SR_LESS,
                           .shading = SR_SHADING_UNLIT };
    return SR_OK;
}

#define SMALL_TRIANGLES 1000000
#define SMALL_SEED      0x5eed5eedull

/* A million triangles of 2 to 10 px^2 at random places and depths, each a
 * stretched equilateral triangle (the stretch keeps the area), wholly on
 * screen so nothing is clipped. */
/* 100,000 segments 10-200 px long in random directions, each end its own
 * random color, no depth test: the line rasterizer alone. */
#define LINES_COUNT 100000
#define LINES_SEED 0x11e5

static sr_result make_lines_scene(bench_scene *s, char *msg, size_t msg_size)
{
    sr_result r = alloc_synthetic(s, (size_t)LINES_COUNT * 2, msg, msg_size);
    if (r != SR_OK) {
        return r;
    }
    s->triangle_count = LINES_COUNT;
    s->primitive = SR_PRIM_LINES;
    uint64_t rng = LINES_SEED;
    float sx = 2.0f / (float)s->width, sy = 2.0f / (float)s->height;
    for (size_t i = 0; i < LINES_COUNT; i++) {
        float len = uniform(&rng, 10.0f, 200.0f), a = uniform(&rng, 0.0f, 2.0f * PI_F);
        float cx = uniform(&rng, 0.0f, (float)s->width), cy = uniform(&rng, 0.0f, (float)s->height);
        for (int k = 0; k < 2; k++) {
            float sign = k ? 0.5f : -0.5f;
            float px = cx + sign * len * cosf(a), py = cy + sign * len * sinf(a);
            float *p = &s->own_positions[(i * 2 + k) * 4];
            p[0] = px * sx - 1.0f;
            p[1] = 1.0f - py * sy;
            p[2] = 0.0f;
            p[3] = 1.0f;
            float *c = &s->own_colors[(i * 2 + k) * 4];
            c[0] = uniform(&rng, 0.2f, 1.0f);
            c[1] = uniform(&rng, 0.2f, 1.0f);
            c[2] = uniform(&rng, 0.2f, 1.0f);
            c[3] = 1.0f;
        }
    }
    s->state.depth_test = SR_OFF;
    s->state.depth_write = SR_OFF;
    s->clear_color[0] = s->clear_color[1] = s->clear_color[2] = 0.0f;
    s->clear_color[3] = 1.0f;
    s->fragments_per_frame = (uint64_t)s->width * (uint64_t)s->height;
    return SR_OK;
}

static sr_result make_small_scene(bench_scene *s, char *msg, size_t msg_size)
{
    size_t tris = SMALL_TRIANGLES;
    sr_result r = alloc_synthetic(s, tris * 3, msg, msg_size);
    if (r != SR_OK) {
        return r;
    }
    s->triangle_count = tris;
    const float margin = 6.0f;  /* > the largest circumradius times stretch, ~4.4 px */
    if (s->width <= 2 * margin || s->height <= 2 * margin) {
        snprintf(msg, msg_size, "small: the image must be larger than %gx%g", 2 * margin,
                 2 * margin);
        return SR_INVALID_ARG;
    }
    uint64_t rng = SMALL_SEED;
    float sx = 2.0f / (float)s->width, sy = 2.0f / (float)s->height;
    for (size_t t = 0; t < tris; t++) {
        float area = uniform(&rng, 2.0f, 10.0f);
        /* Equilateral: area = 3 sqrt(3) / 4 * r^2. */
        float radius = sqrtf(area * 4.0f / (3.0f * sqrtf(3.0f)));
        float stretch = uniform(&rng, 0.6f, 1.6f);
        float theta = uniform(&rng, 0.0f, 2.0f * PI_F);
        float phi = uniform(&rng, 0.0f, 2.0f * PI_F);
        float cx = uniform(&rng, margin, (float)s->width - margin);
        float cy = uniform(&rng, margin, (float)s->height - margin);
        float z = uniform(&rng, -0.99f, 0.99f);
        float cp = cosf(phi), sp = sinf(phi);
        for (int k = 0; k < 3; k++) {
            float a = theta + (float)k * (2.0f * PI_F / 3.0f);
            float ex = radius * stretch * cosf(a), ey = radius / stretch * sinf(a);
            float px = cx + cp * ex - sp * ey, py = cy + sp * ex + cp * ey;
            float *p = &s->own_positions[(t * 3 + k) * 4];
            p[0] = px * sx - 1.0f;
            p[1] = 1.0f - py * sy;  /* pixel y points down, NDC y up */
            p[2] = z;
            p[3] = 1.0f;
            float *c = &s->own_colors[(t * 3 + k) * 4];
            c[0] = uniform(&rng, 0.0f, 1.0f);
            c[1] = uniform(&rng, 0.0f, 1.0f);
            c[2] = uniform(&rng, 0.0f, 1.0f);
            c[3] = 1.0f;
        }
    }
    s->clear_color[0] = s->clear_color[1] = s->clear_color[2] = 0.0f;
    s->clear_color[3] = 1.0f;
    s->fragments_per_frame = (uint64_t)s->width * (uint64_t)s->height;
    return SR_OK;
}

#define FILL_QUADS 100

/* 100 full-screen quads from far to near: every fragment passes LESS and
 * is shaded and written, so this measures the interpolated-color fill
 * rate.  Corner colors change per quad so the interpolation is real. */
static sr_result make_fill_scene(bench_scene *s, char *msg, size_t msg_size)
{
    sr_result r = alloc_synthetic(s, FILL_QUADS * 4, msg, msg_size);
    if (r != SR_OK) {
        return r;
    }
    uint32_t *ix = malloc(FILL_QUADS * 6 * sizeof(uint32_t));
    if (!ix) {
        snprintf(msg, msg_size, "fill: out of memory");
        return SR_OUT_OF_MEMORY;
    }
    /* Counter-clockwise in NDC (y up). */
    static const float corners[4][2] = { { -1, -1 }, { 1, -1 }, { 1, 1 }, { -1, 1 } };
    for (int q = 0; q < FILL_QUADS; q++) {
        float z = 0.99f - 1.98f * (float)q / (FILL_QUADS - 1);
        for (int k = 0; k < 4; k++) {
            float *p = &s->own_positions[(q * 4 + k) * 4];
            p[0] = corners[k][0];
            p[1] = corners[k][1];
            p[2] = z;
            p[3] = 1.0f;
            float *c = &s->own_colors[(q * 4 + k) * 4];
            float h = (float)((q * 4 + k) % 7) / 6.0f;
            c[0] = h;
            c[1] = 1.0f - h;
            c[2] = (float)(q % 10) / 9.0f;
            c[3] = 1.0f;
        }
        uint32_t b = (uint32_t)q * 4;
        uint32_t *t = &ix[q * 6];
        t[0] = b; t[1] = b + 1; t[2] = b + 2;
        t[3] = b; t[4] = b + 2; t[5] = b + 3;
    }
    s->own_indices = ix;
    s->indices = ix;
    s->index_count = FILL_QUADS * 6;
    s->triangle_count = FILL_QUADS * 2;
    s->clear_color[0] = s->clear_color[1] = s->clear_color[2] = 0.0f;
    s->clear_color[3] = 1.0f;
    s->fragments_per_frame = (uint64_t)FILL_QUADS * (uint64_t)s->width * (uint64_t)s->height;
    return SR_OK;
}

sr_result bench_scene_make(const bench_scene_info *info, int width, int height,
                           bench_scene *out, char *msg, size_t msg_size)
{
    memset(out, 0, sizeof *out);
    out->info = info;
    out->width = width;
    out->height = height;
    msg[0] = 0;
    sr_result r;
    switch (info->kind) {
    case BENCH_MESH:  r = make_mesh_scene(out, msg, msg_size); break;
    case BENCH_SMALL: r = make_small_scene(out, msg, msg_size); break;
    case BENCH_FILL:  r = make_fill_scene(out, msg, msg_size); break;
    case BENCH_LINES: r = make_lines_scene(out, msg, msg_size); break;
    default:
        snprintf(msg, msg_size, "%s: not a drawn scene", info->name);
        r = SR_INVALID_ARG;
        break;
    }
    if (r != SR_OK) {
        bench_scene_free(out);
    }
    return r;
}

void bench_scene_free(bench_scene *s)
{
    sr_destroy_pbr_program(s->mesh_ctx, s->pbr);
    sr_destroy_environment(s->mesh_ctx, s->env);
    sr_destroy_shadow_map(s->mesh_ctx, s->shadow);
    sr_destroy_scene(s->mesh_ctx, s->gltf);
    s->pbr = NULL;
    s->env = NULL;
    s->shadow = NULL;
    s->gltf = NULL;
    sr_destroy_mesh(s->mesh_ctx, &s->mesh);
    sr_destroy_context(s->mesh_ctx);
    free(s->own_positions);
    free(s->own_colors);
    free(s->own_indices);
    free(s->texture_pixels);
    s->texture_pixels = NULL;
    s->own_positions = s->own_colors = NULL;
    s->own_indices = NULL;
}
