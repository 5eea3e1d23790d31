/* render.c - the render job and `softrast render [MODEL] [options]`: load
 * a model (or build the teapot scene), frame it with a camera, light it,
 * draw it with the pipeline and write a PNG atomically.  The options are
 * parsed in render_options.c, the textures found and loaded in
 * render_textures.c. */
#include "cli.h"
#include "framing.h"
#include "render.h"
#include "render_background.h"
#include "render_bump.h"
#include "render_gltf.h"
#include "render_lights.h"
#include "render_options.h"
#include "render_programs.h"
#include "render_shadow.h"
#include "render_textures.h"
#include "render_transmission.h"
#include "scene.h"
#include "softrast_io.h"

#include <assert.h>
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <time.h>

#define PI_F 3.14159265358979f

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

/* sr_load_desc.file_read: the model's other files (an OBJ's MTL) are inputs. */
static void note_mtl(void *inputs, const char *path)
{
    cli_inputs_read(inputs, path, "MTL file");
}

static int load_model(const render_opts *o, sr_context *ctx, cli_inputs *inputs, scene *s)
{
    memset(s, 0, sizeof *s);
    scene_object *ob = &s->objects[0];
    sr_io_error err;
    cli_inputs_add(inputs, o->model, "model");
    if (o->variant && !render_gltf_is(o->model)) {
        cli_error("%s: --variant %s: not a glTF file (.gltf, .glb), the only kind with "
                  "material variants", o->model, o->variant);
        return EXIT_USAGE;
    }
    if (o->animation && render_gltf_is(o->model) && !sr_io_have_gltf()) {
        cli_message("%s: --animation: cannot read glTF (softrast was built without jansson; "
                    "install libjansson-dev and rebuild)", o->model);
        return EXIT_USAGE;
    }
    if (o->animation && !render_gltf_is(o->model)) {
        cli_error("--animation: only glTF files (.gltf, .glb) have animations");
        return EXIT_USAGE;
    }
    if (render_gltf_is(o->model) && (o->pbr || o->camera_index >= 0 || o->variant ||
                                     sr_io_have_gltf() || !sr_io_have_assimp())) {
        /* softrast's own glTF reader for every look (docs/gltf.md says why
         * not Assimp's, which a build may also lack): the physically
         * based look draws glTF's materials, the classic models each
         * primitive's Blinn-Phong translation of its material
         * (render_gltf_classic).  Only a build without the reader (no
         * jansson) leaves the classic models Assimp's, if it has Assimp:
         * without either, the reader's refusal names jansson. */
        return render_gltf_load(o->model, o->normals == -1, o->variant, o->verbose,
                                o->animation, o->animation_time, ctx, inputs, s);
    }
    cli_inputs_read(inputs, o->model, "model");
    sr_result r = sr_load_mesh(ctx, o->model,
                               &(sr_load_desc){ .file_read = note_mtl, .user = inputs },
                               &ob->mesh, &err);
    if (r != SR_OK) {
        cli_message("%s", err.message);
        return r == SR_OUT_OF_MEMORY ? EXIT_FAILURE_RUN : EXIT_USAGE;
    }
    s->count = 1;
    ob->model = sr_mat4_identity();
    ob->frame = true;
    ob->material = (sr_material){ .diffuse = { 0.72f, 0.72f, 0.74f },
                                  .specular = { 0.25f, 0.25f, 0.25f }, .shininess = 40.0f };
    return -1;
}

/* --normals: the file's, smooth or flat.  Flat shading needs none. */
static int prepare_normals(const render_opts *o, sr_context *ctx, scene *s)
{
    for (int i = 0; i < s->count; i++) {
        sr_mesh *m = &s->objects[i].mesh;
        int mode = o->normals;
        if (mode == 0 && !m->normals && o->model && i == 0) {
            cli_error("%s: --normals file: the model has no normals (use smooth or flat)", o->model);
            return EXIT_USAGE;
        }
        if (mode == -1) {
            mode = m->normals ? 0 : 1;
        }
        if (mode == 0) {
            continue;
        }
        sr_set_last_error(NULL);
        sr_result r = sr_mesh_compute_normals(ctx, m,
                                              mode == 2 ? SR_NORMALS_FLAT : SR_NORMALS_SMOOTH);
        if (r != SR_OK) {
            cli_error("computing normals: %s", cli_why(r));
            return EXIT_FAILURE_RUN;
        }
    }
    return -1;
}

typedef struct camera {
    sr_mat4 view, proj;
    sr_camera_basis basis;
} camera;

/* The default camera: sr_fit_camera of the framed objects in the image
 * the options ask for; false when it cannot fit them. */
static bool fit_default(const render_opts *o, const scene *s, sr_framing_info *v)
{
    sr_framing_points sets[SCENE_MAX_OBJECTS];
    int n = 0;
    for (int i = 0; i < s->count; i++) {
        const scene_object *ob = &s->objects[i];
        if (ob->frame) {
            sets[n++] = (sr_framing_points){ ob->mesh.positions, ob->mesh.vertex_count,
                                             &ob->model };
        }
    }
    return n > 0 && sr_fit_camera(NULL, &(sr_framing_desc){
                        .sets = sets, .set_count = n, .width = o->width, .height = o->height,
                        .fov = o->fov_deg * PI_F / 180.0f, .ortho = o->ortho }, v) == SR_OK;
}

/* fit_default, answered from the scene's cache when it was made for the
 * same image size, field of view and projection: a render checks the
 * camera before drawing, then makes it again to draw. */
static bool cached_fit(const render_opts *o, scene *s, sr_framing_info *v)
{
    if (!(s->fit_cached && s->fit_width == o->width && s->fit_height == o->height &&
          s->fit_fov_deg == o->fov_deg && s->fit_ortho == o->ortho)) {
        s->fit_ok = fit_default(o, s, &s->fit);
        s->fit_width = o->width;
        s->fit_height = o->height;
        s->fit_fov_deg = o->fov_deg;
        s->fit_ortho = o->ortho;
        s->fit_cached = true;
    }
    *v = s->fit;
    return s->fit_ok;
}

/* The eye, target and up the options ask for: --camera, else `fit` (the
 * default camera, or NULL when there is none), else the framing of the
 * objects' bounding sphere. */
static void resolve_camera(const render_opts *o, const scene *s, const sr_framing_info *fit,
                           sr_vec3 *eye, sr_vec3 *target, sr_vec3 *up)
{
    sr_vec3 c;
    float r;
    scene_bounds(s, true, &c, &r);
    *up = o->have_up ? o->up : (sr_vec3){ 0, 1, 0 };
    if (o->have_eye) {
        *eye = o->eye;
        *target = o->have_target ? o->target : c;
    } else if (fit) {
        *eye = fit->eye;
        *target = fit->target;
    } else {
        *eye = framing_default_eye(c, r, o->fov_deg * PI_F / 180.0f);
        *target = c;
    }
}

static bool finite_mat(const sr_mat4 *m)
{
    for (int i = 0; i < 16; i++) {
        if (!isfinite(m->m[i])) {
            return false;
        }
    }
    return true;
}

/* The camera the options and the scene ask for.  NULL, or why there is
 * none (a message naming --camera when the options are at fault): eye and
 * target in one point, or sizes or distances whose squares overflow
 * float (from about 1e19) or underflow it (below about 1e-19) - the
 * readers accept such coordinates, the framing cannot use them. */
static const char *setup_camera(const render_opts *o, scene *s, camera *cam,
                                float *near_out, float *far_out)
{
    if (o->camera_index >= 0) {
        /* The file's own camera: its matrices as glTF defines them. */
        float aspect = (float)o->width / (float)o->height;
        const char *why = render_gltf_camera(s, o->camera_index, aspect, &cam->view, &cam->proj);
        if (why) {
            return why;
        }
        const float *e = cam->view.m;
        sr_mat4 inv;
        sr_mat4_invert(&cam->view, &inv);
        cam->basis = (sr_camera_basis){ .u = { e[0], e[4], e[8] }, .v = { e[1], e[5], e[9] },
                                        .w = { e[2], e[6], e[10] },
                                        .e = { inv.m[12], inv.m[13], inv.m[14] } };
        /* The near and far planes from the projection (reported by -v). */
        const float *p = cam->proj.m;
        bool ortho = p[15] == 1.0f;
        *near_out = ortho ? (p[14] + 1.0f) / p[10] : p[14] / (p[10] - 1.0f);
        *far_out = ortho ? (p[14] - 1.0f) / p[10]
                 : p[10] != -1.0f ? p[14] / (p[10] + 1.0f) : INFINITY;
        return NULL;
    }
    sr_vec3 c;
    float r;
    scene_bounds(s, true, &c, &r);
    float fov = o->fov_deg * PI_F / 180.0f;

    sr_framing_info fit;
    bool fitted = !o->have_eye && cached_fit(o, s, &fit);
    sr_vec3 eye, target, up;
    resolve_camera(o, s, fitted ? &fit : NULL, &eye, &target, &up);
    sr_vec3 gaze = sr_vec3_sub(target, eye);
    /* Looking straight along the up vector: pick another up; one of the
     * last two is never parallel to a gaze. */
    const sr_vec3 ups[3] = { up, { 0, 0, -1 }, { 1, 0, 0 } };
    bool framed = false;
    for (int i = 0; i < 3 && !framed; i++) {
        framed = sr_camera_frame(eye, gaze, ups[i], &cam->basis);
    }
    bool user = o->have_eye || o->have_target;
    const char *range = user ? "--camera: the eye, the target or the model lies beyond the range "
                               "the framing can use (sizes and distances of about 1e-18 to 1e18)"
                             : "the model lies beyond the range the framing can use (sizes and "
                               "distances of about 1e-18 to 1e18)";
    if (!framed) {
        bool same = gaze.x == 0.0f && gaze.y == 0.0f && gaze.z == 0.0f;
        return same && user ? "--camera: eye and target are the same point" : range;
    }
    cam->view = sr_camera_matrix(&cam->basis);

    /* Near and far from every object's sphere, so the ground is kept. */
    sr_vec3 ca;
    float ra;
    scene_bounds(s, false, &ca, &ra);
    float near_z, far_z;
    framing_near_far(eye, ca, ra, &near_z, &far_z);
    far_z = o->far_z > 0 ? o->far_z : far_z;
    near_z = o->near_z > 0 ? o->near_z : near_z;
    if (near_z >= far_z) {
        far_z = near_z * 2.0f;
    }
    float aspect = (float)o->width / (float)o->height;
    if (o->ortho) {
        float half = r * 1.04f;
        float hw = fitted ? fit.half_width : aspect >= 1.0f ? half * aspect : half;
        float hh = fitted ? fit.half_height : aspect >= 1.0f ? half : half / aspect;
        cam->proj = sr_ortho(-hw, hw, -hh, hh, near_z, far_z, false);
    } else {
        cam->proj = sr_perspective(sr_fit_fovy(fov, o->width, o->height), aspect, near_z, far_z, false);
    }
    *near_out = near_z;
    *far_out = far_z;
    if (!(near_z > 0.0f) || !isfinite(far_z) || !(far_z > near_z) || !finite_mat(&cam->view) ||
        !finite_mat(&cam->proj)) {
        return range;
    }
    return NULL;
}

static bool translucent(const scene_object *ob)
{
    return ob->material.opacity > 0.0f && ob->material.opacity < 1.0f;
}

/* A translucent object's triangles [first, first + n) as indices sorted
 * back to front (sr_sort_back_to_front: blending is order-dependent, so
 * transparency needs sorting); malloc'd, or NULL on failure. */
static uint32_t *sorted_indices(sr_context *ctx, const scene_object *ob, const camera *cam,
                                size_t first, size_t n)
{
    uint32_t *out = malloc((n ? n : 1) * 3 * sizeof *out);
    sr_mat4 mv = sr_mat4_mul(&cam->view, &ob->model);
    if (out && sr_sort_back_to_front(ctx, ob->mesh.positions, ob->mesh.vertex_count,
                                     ob->mesh.indices + 3 * first, n, &mv, out) != SR_OK) {
        free(out);
        out = NULL;
    }
    return out;
}

/* The parts of ob in the order to blend them: farthest first by the mean
 * eye-space depth of their vertices (sr_mean_view_depth,
 * sr_order_back_to_front; malloc'd, or NULL on failure). */
static size_t *parts_back_to_front(sr_context *ctx, const scene_object *ob, const camera *cam)
{
    size_t n = ob->mesh.part_count;
    float *depth = malloc((n ? n : 1) * sizeof *depth);
    size_t *order = malloc((n ? n : 1) * sizeof *order);
    sr_mat4 mv = sr_mat4_mul(&cam->view, &ob->model);
    sr_result r = depth && order ? SR_OK : SR_OUT_OF_MEMORY;
    for (size_t p = 0; p < n && r == SR_OK; p++) {
        const sr_mesh_part *part = &ob->mesh.parts[p];
        r = sr_mean_view_depth(ob->mesh.positions, ob->mesh.vertex_count,
                               ob->mesh.indices + 3 * part->first_triangle, part->triangle_count,
                               &mv, &depth[p]);
    }
    if (r == SR_OK) {
        r = sr_order_back_to_front(ctx, depth, n, order);
    }
    free(depth);
    if (r != SR_OK) {
        free(order);
        order = NULL;
    }
    return order;
}

static float srgb_to_linear(float c)
{
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

static float roughness_of_shininess(float n)
{
    return 1.0f - sqrtf(fminf(fmaxf(n, 0.0f), 1000.0f) / 1000.0f);
}

/* An OBJ part's material statements (docs/pbr.md), as Blender's OBJ
 * importer maps them: Pr, else Ns as 1 - sqrt(Ns / 1000), else a black
 * Ks (no highlight) as fully rough; Pm as metallic; d or Tr below 1 as
 * BLEND; the bump map as the normal map. */
static void apply_part_look(const sr_mesh_material *l, const sr_texture *normal_map,
                            sr_pbr_material *m)
{
    if (l->has_roughness) {
        m->roughness = fminf(fmaxf(l->roughness, 0.0f), 1.0f);
    } else if (l->has_shininess) {
        m->roughness = roughness_of_shininess(l->shininess);
    } else if (l->has_specular && l->specular[0] <= 0.0f && l->specular[1] <= 0.0f &&
               l->specular[2] <= 0.0f) {
        m->roughness = 1.0f;
    }
    if (l->has_metallic) {
        m->metallic = fminf(fmaxf(l->metallic, 0.0f), 1.0f);
    }
    if (l->has_opacity && l->opacity < 1.0f) {
        m->alpha_mode = SR_ALPHA_BLEND;
        m->base_color[3] *= fmaxf(l->opacity, 0.0f);
    }
    if (normal_map) {
        m->normal_texture = (sr_texture_slot){ .texture = normal_map,
                                               .filter = SR_FILTER_TRILINEAR,
                                               .wrap_u = SR_WRAP_REPEAT,
                                               .wrap_v = SR_WRAP_REPEAT, .scale = { 1, 1 } };
    }
}

/* The physically based look of a classic material, as glTF viewers read
 * OBJ materials: its (display-space) color as the base color, white
 * under a texture or the vertex colors unless --material color= asks,
 * a dielectric of roughness 0.5, the part's own material statements
 * (`part`, may be NULL) over that, --material shininess=N (1 - sqrt(N /
 * 1000)) over those, translucent through BLEND. */
static sr_pbr_material pbr_material(const render_opts *o, const scene_object *ob,
                                    const sr_texture *tex, size_t part)
{
    sr_pbr_material m = sr_pbr_default_material();
    m.metallic = 0.0f;
    m.roughness = 0.5f;
    if (ob->mesh.parts && part < ob->mesh.part_count) {
        apply_part_look(&ob->mesh.parts[part].material,
                        ob->part_normal_maps ? ob->part_normal_maps[part] : NULL, &m);
    }
    if (o->have_shininess && ob->frame) {
        m.roughness = roughness_of_shininess(o->shininess);
    }
    bool given = o->have_mat_color && ob->frame;
    bool colored = ob->mesh.colors && ob->material.vertex_color != SR_OFF;
    for (int c = 0; c < 3 && (given || !(tex || colored)); c++) {
        m.base_color[c] = srgb_to_linear((&ob->material.diffuse.x)[c]);
    }
    m.base_color_texture = (sr_texture_slot){ .texture = tex, .filter = o->texture_filter,
                                              .wrap_u = o->wrap, .wrap_v = o->wrap,
                                              .scale = { 1, 1 } };
    if (translucent(ob)) {
        m.alpha_mode = SR_ALPHA_BLEND;
        m.base_color[3] *= ob->material.opacity;
    }
    m.double_sided = o->cull == SR_CULL_NONE;
    return m;
}

/* Whether any part of ob's mesh carries material statements (an OBJ's
 * Ks, Ns, d, Pm, Pr or bump map). */
static bool part_looks(const scene_object *ob)
{
    for (size_t p = 0; ob->mesh.parts && p < ob->mesh.part_count; p++) {
        const sr_mesh_material *l = &ob->mesh.parts[p].material;
        if (l->has_specular || l->has_shininess || l->has_opacity || l->has_metallic ||
            l->has_roughness || l->bump_path) {
            return true;
        }
    }
    return false;
}

/* What draw_scene draws: everything, or the opaque objects and the
 * shadow catcher alone (a transmission source's image). */
typedef enum scene_passes { PASSES_ALL, PASSES_OPAQUE } scene_passes;

/* Opaque objects first; then the shadow catcher and the transmissive glTF
 * parts (KHR_materials_transmission, seeing `see`: the opaque image);
 * then translucent ones back to front with source-over blending and no
 * depth writes (they still test against the opaque depth). */
static sr_result draw_scene(const render_opts *o, const sr_environment *env,
                            const sr_pbr_desc *lighting, const render_shadow *shadow,
                            sr_context *ctx, sr_framebuffer *fb, sr_state *state, scene *s,
                            const camera *cam, bool keep_material, scene_passes passes,
                            const sr_texture *see, uint64_t *tris, uint64_t *frags)
{
    bool pbr = o->pbr && !keep_material;
    sr_result r = SR_OK;
    for (int pass = 0; pass < (passes == PASSES_ALL ? 3 : 2) && r == SR_OK; pass++) {
        /* A shadow catcher after the opaque objects, whose depth hides the
         * ground behind them, and before the translucent ones. */
        for (int i = 0; i < s->count && r == SR_OK && pass == 1 && pbr && shadow; i++) {
            if (s->objects[i].catcher) {
                r = render_catcher_draw(ctx, fb, state, shadow, &s->objects[i], &cam->view,
                                        &cam->proj);
            }
        }
        for (int i = 0; i < s->count && r == SR_OK; i++) {
            scene_object *ob = &s->objects[i];
            bool gltf = ob->part_material && s->gltf;
            /* An OBJ whose materials say more than a color (part_looks) is
             * drawn part by part under pbr, each part in the pass its
             * opacity asks for, as glTF's primitives are. */
            bool looks = pbr && !gltf && part_looks(ob);
            bool per_part = gltf || looks;
            bool see_through = !keep_material && translucent(ob);
            if (ob->catcher || (!per_part && (see_through ? 2 : 0) != pass)) {
                continue;
            }
            /* The texture colors the surface, not the line modes' plain
             * passes; a mesh whose parts take different textures (or, from
             * glTF, materials) is drawn part by part (a translucent one
             * sorted within each part, glTF's BLEND parts back to front). */
            bool by_part = !keep_material && (ob->part_textures || per_part);
            size_t parts = by_part ? ob->mesh.part_count : 1;
            size_t *order = per_part && pass == 2 ? parts_back_to_front(ctx, ob, cam) : NULL;
            if (per_part && pass == 2 && !order) {
                return SR_OUT_OF_MEMORY;
            }
            /* A glTF material's program, made for its first part here. */
            render_programs programs = { 0 };
            for (size_t k = 0; k < parts && r == SR_OK; k++) {
                size_t p = order ? order[k] : k;
                const sr_pbr_material *gm =
                    gltf && !keep_material ? &s->gltf->materials[ob->part_material[p]] : NULL;
                if (gltf) {
                    see_through = gm && gm->alpha_mode == SR_ALPHA_BLEND;
                    bool transmits = pbr && gm && render_transmits(gm);
                    if ((see_through ? 2 : transmits ? 1 : 0) != pass ||
                        (transmits && passes == PASSES_OPAQUE)) {
                        continue;
                    }
                } else if (looks) {
                    const sr_mesh_material *l = &ob->mesh.parts[p].material;
                    see_through = translucent(ob) || (l->has_opacity && l->opacity < 1.0f);
                    if ((see_through ? 2 : 0) != pass) {
                        continue;
                    }
                }
                size_t first = by_part ? ob->mesh.parts[p].first_triangle : 0;
                size_t count = by_part ? ob->mesh.parts[p].triangle_count
                                       : ob->mesh.triangle_count;
                /* The glTF parts that follow with the same material and
                 * the next triangles (a primitive's EXT_mesh_gpu_instancing
                 * instances, or nodes repeating one mesh) are one draw: a
                 * draw shades only its own vertices and shares its
                 * material's program, but each still validates and
                 * resolves its state and visits its tiles, which adds up
                 * over tens of thousands of small instances.
                 * Not where the parts are sorted back to front. */
                while (gltf && !order && !see_through && k + 1 < parts &&
                       ob->part_material[k + 1] == ob->part_material[p] &&
                       ob->mesh.parts[k + 1].first_triangle == first + count &&
                       (s->gltf->primitives[k + 1].colors != NULL) ==
                           (s->gltf->primitives[p].colors != NULL)) {
                    count += ob->mesh.parts[++k].triangle_count;
                }
                sr_state st = *state;
                if (!keep_material) {
                    st.material = ob->material;
                }
                /* --texture replaces a glTF material's base color texture
                 * too, as it replaces any model's. */
                const sr_texture *given = o->texture ? ob->texture : NULL;
                st.texture = keep_material ? NULL
                           : given ? given
                           : gm ? gm->base_color_texture.texture
                           : by_part && ob->part_textures ? ob->part_textures[p] : ob->texture;
                const float *texcoords = ob->mesh.texcoords;
                if (gm && !pbr && !given) {
                    /* The base color texture where, and as, the physically
                     * based look samples it: its sampler, its coordinate
                     * set and transform (base_uv). */
                    const sr_texture_slot *bt = &gm->base_color_texture;
                    st.texture_filter = bt->filter;
                    st.wrap_u = bt->wrap_u;
                    st.wrap_v = bt->wrap_v;
                    texcoords = ob->base_uv ? ob->base_uv : texcoords;
                }
                if (gm && !pbr) {
                    /* The file's material, but what --material says wins,
                     * as it does over any other model's. */
                    st.material = render_gltf_classic(gm, s->gltf->primitives[p].colors != NULL);
                    if (o->have_mat_color) {
                        st.material.diffuse = o->mat_color;
                        st.material.vertex_color = SR_OFF;
                    }
                    if (o->have_specular) {
                        st.material.specular = o->specular;
                    }
                    if (o->have_shininess) {
                        st.material.shininess = o->shininess;
                    }
                }
                if (gm && gm->double_sided) {
                    st.cull = SR_CULL_NONE;
                    st.two_sided = true;
                }
                const uint32_t *indices = ob->mesh.indices + 3 * first;
                uint32_t *sorted = NULL;
                if (see_through) {
                    sorted = sorted_indices(ctx, ob, cam, first, count);
                    if (!sorted) {
                        free(order);
                        render_programs_clear(ctx, &programs);
                        return SR_OUT_OF_MEMORY;
                    }
                    indices = sorted;
                    st.depth_write = SR_OFF;
                    st.blend = (sr_blend){ .enabled = true, .src_rgb = SR_BLEND_SRC_ALPHA,
                                           .dst_rgb = SR_BLEND_ONE_MINUS_SRC_ALPHA,
                                           .src_alpha = SR_BLEND_ONE,
                                           .dst_alpha = SR_BLEND_ONE_MINUS_SRC_ALPHA };
                }
                sr_pbr *program = NULL;
                size_t material = gm ? (size_t)ob->part_material[p] + 1 : 0;
                if (pbr && material) {
                    program = render_programs_find(&programs, material);
                }
                if (pbr && !program) {
                    sr_pbr_material m = gm ? *gm
                                       : pbr_material(o, ob, st.texture, by_part ? p : SIZE_MAX);
                    if (gm && given) {
                        m.base_color_texture = (sr_texture_slot){
                            .texture = given, .filter = o->texture_filter, .wrap_u = o->wrap,
                            .wrap_v = o->wrap, .scale = { 1, 1 } };
                    }
                    sr_pbr_desc d = { .material = &m, .model = &ob->model, .view = &cam->view,
                                      .projection = &cam->proj, .exposure = o->exposure,
                                      .tonemap = o->tonemap,
                                      .vertex_color = ob->mesh.colors
                                                          ? ob->material.vertex_color : SR_OFF,
                                      .tangents = ob->tangents, .texcoords1 = ob->texcoords1 };
                    if (ob->tangents || ob->texcoords1) {
                        d.vertex_count = ob->mesh.vertex_count;
                    }
                    memcpy(d.lights, lighting->lights, sizeof d.lights);
                    d.sky = lighting->sky;
                    d.ground = lighting->ground;
                    if (o->have_ambient) {
                        d.sky = d.ground = o->ambient;
                    }
                    d.environment = env;
                    d.transmission_source = see;
                    d.shadow = shadow ? shadow->map : NULL;
                    r = sr_make_pbr_program(ctx, &d, &program);
                    if (r != SR_OK) {
                        free(sorted);
                        free(order);
                        render_programs_clear(ctx, &programs);
                        return r;
                    }
                    if (material) {
                        render_programs_keep(ctx, &programs, material, program);
                    }
                }
                if (program) {
                    st.program = sr_pbr_program(program);
                }
                r = sr_draw(ctx, fb, &st, &(sr_draw_desc){
                    .positions = ob->mesh.positions, .normals = ob->mesh.normals,
                    .colors = ob->mesh.colors, .color_size = 4,
                    .texcoords = texcoords, .vertex_count = ob->mesh.vertex_count,
                    .indices = indices, .index_type = SR_INDEX_U32, .index_count = count * 3,
                    .model = &ob->model, .view = &cam->view, .projection = &cam->proj });
                free(sorted);
                if (!material) {
                    sr_destroy_pbr_program(ctx, program);
                }
                sr_draw_info info = sr_last_draw_info(ctx);
                *tris += info.triangles_in;
                *frags += info.fragments;
            }
            render_programs_clear(ctx, &programs);
            free(order);
        }
    }
    return r;
}

/* The passes of each mode.  Hidden-line, edges and points first fill the
 * depth buffer with the model pushed back by polygon offset (factor 1,
 * units 1 unless --polygon-offset says otherwise), so lines on its surface win the LEQUAL test without stitching
 * or z-fighting; hidden-line and points fill with the background color. */
static sr_result draw_passes(const render_opts *o, const sr_environment *env,
                             const sr_pbr_desc *lighting, const render_shadow *shadow,
                             sr_context *ctx, sr_framebuffer *fb, const sr_state *base, scene *s,
                             const camera *cam, const sr_texture *see, uint64_t *tris,
                             uint64_t *frags)
{
    sr_state st = *base;
    if (o->lines == LINES_NONE) {
        return draw_scene(o, env, lighting, shadow, ctx, fb, &st, s, cam, false, PASSES_ALL, see,
                          tris, frags);
    }
    bool light_bg = o->background.x + o->background.y + o->background.z > 1.5f;
    sr_vec3 ink = o->have_line_color ? o->line_color
                : light_bg ? (sr_vec3){ 0.125f, 0.125f, 0.125f }
                           : (sr_vec3){ 0.91f, 0.925f, 0.957f };
    sr_material ink_material = { .diffuse = ink, .vertex_color = SR_OFF };
    sr_result r = SR_OK;
    if (o->lines != LINES_WIREFRAME) {
        sr_state fill = st;
        fill.offset = (sr_polygon_offset){ .factor = o->offset_factor,
                                           .units = o->offset_units, .fill = true };
        if (o->lines == LINES_EDGES) {
            r = draw_scene(o, env, lighting, shadow, ctx, fb, &fill, s, cam, false, PASSES_ALL,
                           see, tris, frags);
        } else {
            fill.shading = SR_SHADING_UNLIT;
            fill.material = (sr_material){ .diffuse = o->background, .vertex_color = SR_OFF };
            r = draw_scene(o, env, lighting, shadow, ctx, fb, &fill, s, cam, true, PASSES_ALL,
                           NULL, tris, frags);
        }
    }
    if (r != SR_OK) {
        return r;
    }
    sr_state lines = st;
    lines.shading = SR_SHADING_UNLIT;
    lines.material = ink_material;
    /* Supersampled, lines and points keep their width in output pixels. */
    lines.line_width = o->line_width * (float)o->ssaa;
    lines.point_size = o->point_size * (float)o->ssaa;
    lines.smooth_lines = lines.smooth_points = o->smooth;
    sr_polygon_mode mode = o->lines == LINES_POINTS ? SR_POLYGON_POINT : SR_POLYGON_LINE;
    lines.polygon_mode_front = lines.polygon_mode_back = mode;
    if (o->lines == LINES_WIREFRAME) {
        lines.cull = SR_CULL_NONE;
        lines.depth_test = SR_OFF;
        lines.depth_write = SR_OFF;
    } else {
        lines.depth_func = SR_LEQUAL;
    }
    return draw_scene(o, env, lighting, shadow, ctx, fb, &lines, s, cam, true, PASSES_ALL, NULL,
                      tris, frags);
}

/* ---- render jobs: what `softrast render` and `softrast view` share ------- */

struct render_job {
    render_opts o;
    scene s;
    bool have_scene;
    sr_context *ctx;
    /* The scene's meshes live on a context of their own, made with the
     * first options' threads: it outlives the drawing context, which a
     * change of --threads replaces. */
    sr_context *mesh_ctx;
    sr_framebuffer *work;   /* the supersampled image (or one with the requested depth
                             * format) when the caller's framebuffer cannot be drawn into */
    cli_inputs inputs;      /* the files read: model, MTL, textures */
    sr_environment *env;    /* pbr's image-based light, on mesh_ctx; NULL: the hemisphere */
    bool env_shared;        /* env is another job's (render_job_share_light) */
    render_shadow shadow;   /* the key light's map, on ctx */
    char error[512];
};

int render_job_parse(int argc, char **argv, render_job **out)
{
    *out = NULL;
    render_job *job = calloc(1, sizeof *job);
    if (!job) {
        cli_error("out of memory");
        return EXIT_FAILURE_RUN;
    }
    job->o = render_opts_defaults();
    int status = render_opts_parse(argc, argv, &job->o);
    if (status >= 0) {
        free(job);
        return status;
    }
    *out = job;
    return -1;
}

/* The contexts, unless made already (cmd_render makes them first). */
static int start_context(render_job *job)
{
    if (job->ctx) {
        return -1;
    }
    sr_set_last_error(NULL);
    sr_result r = sr_make_context(&(sr_context_desc){ .threads = job->o.threads }, &job->ctx);
    if (r == SR_OK && !job->mesh_ctx) {
        r = sr_make_context(&(sr_context_desc){ .threads = job->o.threads }, &job->mesh_ctx);
    }
    if (r != SR_OK) {
        cli_error("render: %s", cli_why(r));
        return EXIT_FAILURE_RUN;
    }
    return -1;
}

/* The context and the textures that live on it. */
static int make_context(render_job *job)
{
    int status = start_context(job);
    if (status >= 0) {
        return status;
    }
    status = render_textures_load(&job->o, job->ctx, &job->inputs, &job->s);
    return status >= 0 ? status : render_bump_load(&job->o, job->ctx, &job->inputs, &job->s);
}

static void drop_context(render_job *job)
{
    if (job->ctx) {
        render_textures_free(job->ctx, &job->s);
        render_bump_free(job->ctx, &job->s);
        render_shadow_free(job->ctx, &job->shadow);
        sr_destroy_framebuffer(job->ctx, job->work);
        sr_destroy_context(job->ctx);
    }
    job->work = NULL;
    job->ctx = NULL;
}

/* The first part of render_job_load, which needs no context: the model
 * file read, or the built-in scene made. */
static int load_objects(render_job *job)
{
    render_opts *o = &job->o;
    scene *s = &job->s;
    if (o->model) {
        int status = load_model(o, job->mesh_ctx, &job->inputs, s);
        if (status >= 0) {
            return status;
        }
        if (o->pbr && (o->lights_source == LIGHTS_FILE || o->lights_source == LIGHTS_BOTH) &&
            render_lights_in_file(s) == 0) {
            cli_error("warning: --lights %s: %s has no lights of its own (KHR_lights_punctual)",
                      o->lights_source == LIGHTS_FILE ? "file" : "both", o->model);
        }
    } else {
        sr_set_last_error(NULL);
        sr_result r = scene_builtin(job->mesh_ctx, s, o->detail);
        if (r != SR_OK) {
            cli_error("building the teapot scene: %s", cli_why(r));
            return EXIT_FAILURE_RUN;
        }
    }
    job->have_scene = true;
    return -1;
}

/* --up, or the up axis the model's format implies: +z for STL, the
 * format of CAD and 3D printing; +y for the rest (glTF specifies it, OBJ
 * and PLY from modelling tools mostly follow it) and the teapot. */
static int render_model_up(const render_opts *o)
{
    if (o->model_up != UP_AUTO) {
        return o->model_up;
    }
    const char *dot = o->model ? strrchr(o->model, '.') : NULL;
    return dot && strcasecmp(dot, ".stl") == 0 ? UP_POS_Z : UP_POS_Y;
}

/* The rest of the scene, with the context's threads for the normals:
 * materials, turn, bounds, and a check that a camera can be made. */
static int finish_scene(render_job *job)
{
    render_opts *o = &job->o;
    scene *s = &job->s;
    size_t vertices = s->objects[0].mesh.vertex_count;
    int status = prepare_normals(o, job->mesh_ctx, s);
    if (status >= 0) {
        return status;
    }
    scene_object *first = &s->objects[0];
    if (first->mesh.vertex_count != vertices) {
        /* --normals flat split the vertices: the per-vertex extras no
         * longer match (the normal maps take the derivative frame). */
        free(first->tangents);
        free(first->texcoords1);
        first->tangents = first->texcoords1 = NULL;
    }
    sr_result uv = render_gltf_base_uv(job->mesh_ctx, s, first);
    if (uv != SR_OK) {
        cli_error("%s: %s", o->model,
                  uv == SR_OUT_OF_MEMORY ? "out of memory" : sr_context_error(job->mesh_ctx));
        return EXIT_FAILURE_RUN;
    }
    if (s->gltf && !first->tangents && first->mesh.texcoords && first->mesh.normals) {
        /* Normal maps or anisotropy with a primitive that has no
         * tangents: MikkTSpace's for the whole merged mesh. */
        bool mapped = false;
        for (size_t i = 0; i < s->gltf->material_count; i++) {
            mapped |= s->gltf->materials[i].normal_texture.texture != NULL ||
                      s->gltf->materials[i].clearcoat_normal_texture.texture != NULL ||
                      s->gltf->materials[i].anisotropy_strength > 0.0f;
        }
        first->tangents = mapped ? malloc(first->mesh.vertex_count * 4 * sizeof(float)) : NULL;
        if (mapped && (!first->tangents || sr_mesh_compute_tangents(job->mesh_ctx, &first->mesh,
                                                                    first->tangents) != SR_OK)) {
            cli_error("%s: computing tangents: %s", o->model, sr_context_error(job->mesh_ctx));
            return EXIT_FAILURE_RUN;
        }
    }
    for (int i = 0; i < s->count; i++) {
        scene_object *ob = &s->objects[i];
        if (o->have_mat_color && ob->frame) {
            ob->material.diffuse = o->mat_color;
            ob->material.vertex_color = SR_OFF;
        }
        if (o->have_specular && ob->frame) {
            ob->material.specular = o->specular;
        }
        if (o->have_shininess && ob->frame) {
            ob->material.shininess = o->shininess;
        }
        if (ob->frame && o->opacity < 1.0f) {
            /* Zero means the default (opaque) in sr_material: keep a
             * fully transparent request just above it. */
            ob->material.opacity = o->opacity > 0.0f ? o->opacity : 1e-6f;
        }
    }
    int up = render_model_up(o);
    for (int i = 0; i < s->count && up != UP_POS_Y; i++) {
        if (s->objects[i].frame) {
            sr_mat4 m = framing_upright(up);
            s->objects[i].model = sr_mat4_mul(&m, &s->objects[i].model);
        }
    }
    if (o->turn_deg != 0.0f) {
        /* Turn the framed objects about the vertical axis through their
         * bounding sphere's centre. */
        sr_vec3 c;
        float r;
        scene_bounds(s, true, &c, &r);
        sr_mat4 to = sr_mat4_translate(c.x, 0, c.z), from = sr_mat4_translate(-c.x, 0, -c.z);
        sr_mat4 rot = sr_mat4_rotate(o->turn_deg * PI_F / 180.0f, (sr_vec3){ 0, 1, 0 });
        sr_mat4 m = sr_mat4_mul(&rot, &from);
        m = sr_mat4_mul(&to, &m);
        for (int i = 0; i < s->count; i++) {
            if (s->objects[i].frame) {
                s->objects[i].model = sr_mat4_mul(&m, &s->objects[i].model);
            }
        }
    }
    /* The objects and their matrices are final: frame from cached bounds. */
    scene_cache_bounds(s);
    if (o->ground && o->pbr && o->shadows != 0) {
        sr_set_last_error(NULL);
        sr_result r = render_ground_add(job->mesh_ctx, s);
        if (r != SR_OK) {
            cli_error("making the ground: %s", cli_why(r));
            return EXIT_FAILURE_RUN;
        }
    }
    /* A camera that cannot be made is the input's fault: say so now, as a
     * usage error, rather than when drawing. */
    camera cam;
    float near_z, far_z;
    const char *why = setup_camera(o, s, &cam, &near_z, &far_z);
    if (why) {
        if (o->model && why[0] != '-') {   /* not an option's fault: name the file */
            cli_error("%s: %s", o->model, why);
        } else {
            cli_error("%s", why);
        }
        return EXIT_USAGE;
    }
    if ((long)o->width * o->ssaa > SR_MAX_FRAMEBUFFER_SIZE ||
        (long)o->height * o->ssaa > SR_MAX_FRAMEBUFFER_SIZE) {
        cli_error("--aa: ssaa%d at %dx%d needs %ldx%ld samples, more than %d a side", o->ssaa,
                  o->width, o->height, (long)o->width * o->ssaa, (long)o->height * o->ssaa,
                  SR_MAX_FRAMEBUFFER_SIZE);
        return EXIT_USAGE;
    }
    return -1;
}

/* --environment: the built-in studio (the default, prefiltered at build
 * time), an equirectangular Radiance picture, or hemisphere / none (the
 * sky-and-ground hemisphere); made once a job, not once a model: a
 * batch's models all share the light. */
static int load_environment(render_job *job)
{
    const render_opts *o = &job->o;
    if (!render_opts_image_light(o)) {
        return -1;
    }
    bool file = strcmp(o->environment, "studio") != 0;
    if (file) {
        cli_inputs_add(&job->inputs, o->environment, "environment");
    }
    if (job->env) {
        return -1;
    }
    sr_environment_desc d = { .intensity = o->environment_intensity };
    float *px = NULL;
    if (file) {
        sr_io_error err;
        sr_result r = sr_read_hdr(o->environment, &d.width, &d.height, &px, &err);
        if (r != SR_OK) {
            fprintf(stderr, "%s\n", err.message);
            return r == SR_OUT_OF_MEMORY ? EXIT_FAILURE_RUN : EXIT_USAGE;
        }
        d.pixels = px;
    }
    sr_result r = sr_make_environment(job->mesh_ctx, &d, &job->env);
    free(px);
    if (r != SR_OK) {
        cli_error("%s: %s", o->environment, sr_context_error(job->mesh_ctx));
        return r == SR_OUT_OF_MEMORY ? EXIT_FAILURE_RUN : EXIT_USAGE;
    }
    return -1;
}

int render_job_prepare(render_job *job)
{
    int status = start_context(job);
    return status >= 0 ? status : load_environment(job);
}

void render_job_share_light(render_job *job, const render_job *from)
{
    assert(!job->env);
    job->env = from->env;
    job->env_shared = job->env != NULL;
}

int render_job_load(render_job *job)
{
    int status = start_context(job);
    if (status < 0) {
        status = load_objects(job);
    }
    if (status < 0) {
        status = finish_scene(job);
    }
    if (status < 0) {
        status = load_environment(job);
    }
    return status >= 0 ? status : make_context(job);
}

int render_job_reload(render_job *job, const char *model)
{
    if (job->ctx) {
        render_textures_free(job->ctx, &job->s);
        render_bump_free(job->ctx, &job->s);
    }
    if (job->have_scene) {
        scene_free(job->mesh_ctx, &job->s);
        job->have_scene = false;
    }
    cli_inputs_free(&job->inputs);
    job->o.model = model;
    return render_job_load(job);
}

int render_job_configure(render_job *job, int argc, char **argv)
{
    render_opts o = render_opts_defaults();
    int status = render_opts_parse(argc, argv, &o);
    if (status >= 0) {
        return status;
    }
    bool new_context = job->ctx && o.threads != job->o.threads;
    job->o = o;
    if (new_context) {
        drop_context(job);
        return make_context(job);
    }
    return -1;
}

void render_job_camera(const render_job *job, sr_vec3 *eye, sr_vec3 *target, sr_vec3 *up)
{
    sr_framing_info fit;
    bool fitted = !job->o.have_eye && fit_default(&job->o, &job->s, &fit);
    resolve_camera(&job->o, &job->s, fitted ? &fit : NULL, eye, target, up);
}

void render_job_bounds(const render_job *job, sr_vec3 *centre, float *radius)
{
    scene_bounds(&job->s, true, centre, radius);
}

float render_job_fov(const render_job *job)
{
    return job->o.fov_deg * PI_F / 180.0f;
}

void render_job_set_camera(render_job *job, sr_vec3 eye, sr_vec3 target, sr_vec3 up)
{
    job->o.have_eye = job->o.have_target = job->o.have_up = true;
    job->o.eye = eye;
    job->o.target = target;
    job->o.up = up;
}

bool render_job_animation(const render_job *job, float *duration)
{
    const sr_scene *g = job->have_scene ? job->s.gltf : NULL;
    if (!g || g->animation < 0) {
        return false;
    }
    *duration = g->animations[g->animation].duration;
    return true;
}

int render_job_pose(render_job *job, float seconds)
{
    sr_scene *g = job->have_scene ? job->s.gltf : NULL;
    if (!g || g->animation < 0) {
        cli_error("%s: not posed by an animation", job->o.model ? job->o.model : "the scene");
        return EXIT_USAGE;
    }
    sr_io_error err;
    sr_result r = sr_scene_pose(g, SR_POSE_ANIMATION, g->animation, seconds, &err);
    if (r != SR_OK) {
        cli_message("%s", err.message);
        return r == SR_OUT_OF_MEMORY ? EXIT_FAILURE_RUN : EXIT_USAGE;
    }
    job->o.animation_time = seconds;
    /* The job's objects made again from the posed scene, as
     * render_job_reload makes them from a reading, but the scene kept:
     * its file is not read again, nor are its inputs listed again. */
    if (job->ctx) {
        render_textures_free(job->ctx, &job->s);
        render_bump_free(job->ctx, &job->s);
    }
    job->s.gltf = NULL;
    scene_free(job->mesh_ctx, &job->s);
    job->have_scene = false;
    memset(&job->s, 0, sizeof job->s);
    const render_opts *o = &job->o;
    int status = render_gltf_build(o->model, o->normals == -1, o->variant, false, g,
                                   job->mesh_ctx, &job->s);
    if (status < 0) {
        job->have_scene = true;
        status = finish_scene(job);
    }
    return status >= 0 ? status : make_context(job);
}

int render_job_check_frames(const render_job *job, const char *cmd, int width, int height,
                            int frames)
{
    return render_opts_check_frames(&job->o, cmd, width, height, frames);
}

sr_context *render_job_context(const render_job *job)
{
    return job->ctx;
}

sr_depth_format render_job_depth_format(const render_job *job)
{
    return job->o.ssaa > 1 || job->o.msaa > 1 ? SR_DEPTH_NONE : job->o.depth_format;
}

const char *render_job_error(const render_job *job)
{
    return job->error;
}

const char *render_job_model(const render_job *job)
{
    return job->o.model;
}

cli_inputs *render_job_inputs(render_job *job)
{
    return &job->inputs;
}

/* --shadows, by default on where a ground (--ground, the teapot's
 * floor) receives them: on a model alone the shadow only falls on the
 * model, and there it was half again the CPU time of the `cli` scene
 * (docs/shadows.md). */
/* --background blur: the environment as the specular reflection of a
 * surface this rough shows it, soft but still recognisable. */
#define BACKGROUND_BLUR_ROUGHNESS 0.5f

static bool wants_shadows(const render_opts *o, const scene *s)
{
    bool ground = false;
    for (int i = 0; i < s->count; i++) {
        ground |= !s->objects[i].frame;
    }
    return o->shadows > 0 || (o->shadows < 0 && ground);
}

sr_framebuffer_desc render_job_direct_desc(const render_job *job, int width, int height)
{
    const render_opts *o = &job->o;
    bool msaa = o->msaa > 1 && o->ssaa == 1;
    return (sr_framebuffer_desc){ .width = width, .height = height,
                                  .depth_format = msaa ? o->depth_format
                                                       : render_job_depth_format(job),
                                  .samples = msaa ? o->msaa : 1 };
}

sr_result render_job_draw(render_job *job, sr_framebuffer *out, render_frame_info *info)
{
    render_opts *o = &job->o;
    sr_context *ctx = job->ctx;
    job->error[0] = 0;
    sr_set_last_error(NULL);    /* for cli_why: a frame's failure, not an older one */
    *info = (render_frame_info){ 0 };
    o->width = sr_framebuffer_width(out);
    o->height = sr_framebuffer_height(out);
    long sw = (long)o->width * o->ssaa, sh = (long)o->height * o->ssaa;
    if (sw > SR_MAX_FRAMEBUFFER_SIZE || sh > SR_MAX_FRAMEBUFFER_SIZE) {
        snprintf(job->error, sizeof job->error,
                 "ssaa%d at %dx%d needs %ldx%ld samples, more than %d a side", o->ssaa,
                 o->width, o->height, sw, sh, SR_MAX_FRAMEBUFFER_SIZE);
        return SR_TOO_LARGE;
    }

    camera cam;
    const char *why = setup_camera(o, &job->s, &cam, &info->near_z, &info->far_z);
    if (why) {
        snprintf(job->error, sizeof job->error, "%s", why);
        return SR_INVALID_ARG;
    }
    sr_state state = {
        .cull = o->cull, .front_face = o->front, .depth_func = o->depth_func,
        .shading = o->shading, .interpolation = o->interp, .rasterizer = o->rasterizer,
        .clipper = o->clipper, .depth_range = o->depth_range, .depth_near = o->depth_near,
        .depth_far = o->depth_far,
        .ambient = o->have_ambient ? o->ambient : (sr_vec3){ 0.12f, 0.12f, 0.14f },
        .two_sided = o->cull == SR_CULL_NONE,
        .texture_filter = o->texture_filter, .wrap_u = o->wrap, .wrap_v = o->wrap,
    };
    if (o->light_count > 0) {
        memcpy(state.lights, o->lights, sizeof o->lights);
    } else if (sr_default_lights(&cam.basis, state.lights) != SR_OK) {
        snprintf(job->error, sizeof job->error, "the camera's frame is degenerate");
        return SR_INVALID_ARG;
    }

    /* SSAA renders k x k samples per output pixel into the work image,
     * then filters them down into `out`; MSAA renders into `out` itself
     * when it has the samples and depth (render_job_direct_desc), else
     * into a multisampled work image of the output's size and resolves
     * it. */
    sr_framebuffer *fb = out;
    sr_result r = SR_OK;
    sr_depth_format want = o->depth_format == SR_DEPTH_DEFAULT ? SR_DEPTH_D24 : o->depth_format;
    if (o->ssaa > 1 || sr_framebuffer_samples(out) != o->msaa ||
        sr_framebuffer_depth_format(out) != want) {
        if (job->work && (sr_framebuffer_width(job->work) != sw ||
                          sr_framebuffer_height(job->work) != sh ||
                          sr_framebuffer_samples(job->work) != o->msaa ||
                          sr_framebuffer_depth_format(job->work) != want)) {
            sr_destroy_framebuffer(ctx, job->work);
            job->work = NULL;
        }
        if (!job->work) {
            r = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = (int)sw,
                                                                .height = (int)sh,
                                                                .depth_format = want,
                                                                .samples = o->msaa },
                                    &job->work);
        }
        fb = job->work;
    }
    bool clear_to_near = o->depth_func == SR_GREATER || o->depth_func == SR_GEQUAL;
    sr_clear_desc clear = { .color = { o->background.x, o->background.y, o->background.z,
                                       o->background_alpha },
                            .depth_action = SR_ACTION_CLEAR,
                            .depth = clear_to_near ? 0.0f : 1.0f };
    float blur = o->background_env == BACKGROUND_BLUR ? BACKGROUND_BLUR_ROUGHNESS : 0.0f;
    if (r == SR_OK) {
        r = sr_clear(ctx, fb, &clear);
    }
    if (r == SR_OK && o->background_env && job->env) {
        r = render_background_draw(ctx, fb, job->env, blur, &cam.view, &cam.proj, o->exposure,
                                   o->tonemap, sr_context_threads(ctx));
    }
    /* pbr's lights: the file's, the rig or both (--lights). */
    sr_pbr_desc lighting = { 0 };
    render_lights_pbr(o, &job->s, state.lights, job->env != NULL, &lighting);
    /* The key light's shadow map, before the objects that receive it. */
    const render_shadow *shadow = NULL;
    if (r == SR_OK && o->pbr && wants_shadows(o, &job->s) &&
        lighting.lights[0].type == SR_LIGHT_DIRECTIONAL) {
        r = render_shadow_draw(ctx, &job->shadow, &job->s, lighting.lights[0].vector);
        shadow = &job->shadow;
    }
    /* What transmissive parts see: the opaque scene, drawn first into an
     * image of the output's size with the exposure but no tone curve. */
    sr_texture *see = NULL;
    if (r == SR_OK && o->pbr && render_scene_transmits(&job->s)) {
        sr_framebuffer *src = NULL;
        uint64_t ignored = 0;
        render_opts lin = *o;
        lin.tonemap = SR_TONEMAP_NONE;
        r = render_transmission_begin(ctx, o->width, o->height, &clear, &src);
        if (r == SR_OK && o->background_env && job->env) {
            r = render_background_draw(ctx, src, job->env, blur, &cam.view, &cam.proj,
                                       o->exposure, SR_TONEMAP_NONE, sr_context_threads(ctx));
        }
        if (r == SR_OK) {
            r = draw_scene(&lin, job->env, &lighting, shadow, ctx, src, &state, &job->s, &cam,
                           false, PASSES_OPAQUE, NULL, &ignored, &ignored);
        }
        if (r == SR_OK) {
            r = render_transmission_finish(ctx, src, &see);
        }
        sr_destroy_framebuffer(ctx, src);
    }
    if (r == SR_OK) {
        r = draw_passes(o, job->env, &lighting, shadow, ctx, fb, &state, &job->s, &cam, see,
                        &info->triangles, &info->fragments);
    }
    sr_destroy_texture(ctx, see);
    if (r == SR_OK && fb != out) {
        r = o->msaa > 1 ? sr_resolve(ctx, fb, out) : sr_downsample(ctx, fb, out, o->filter);
    }
    if (r != SR_OK) {
        /* The thread's message covers the calls without a context too (the
         * lights' set-up). */
        snprintf(job->error, sizeof job->error, "%s", cli_why(r));
    }
    return r;
}

void render_job_free(render_job *job)
{
    if (!job) {
        return;
    }
    drop_context(job);
    if (!job->env_shared) {
        sr_destroy_environment(job->mesh_ctx, job->env);
    }
    if (job->have_scene) {
        scene_free(job->mesh_ctx, &job->s);
    }
    sr_destroy_context(job->mesh_ctx);
    cli_inputs_free(&job->inputs);
    free(job);
}

/* sr_make_framebuffer on a thread of its own (cmd_render). */
typedef struct fb_maker {
    sr_context *ctx;
    sr_framebuffer_desc desc;
    sr_framebuffer *fb;
    sr_result result;
    char error[256];        /* sr_context_error, read before the context is used again */
    pthread_t thread;
} fb_maker;

static void *make_fb(void *arg)
{
    fb_maker *m = arg;
    m->result = sr_make_framebuffer(m->ctx, &m->desc, &m->fb);
    if (m->result != SR_OK) {
        snprintf(m->error, sizeof m->error, "%s", sr_context_error(m->ctx));
    }
    return NULL;
}

int cmd_render(int argc, char **argv)
{
    int status = batch_render(argc, argv);
    if (status >= 0) {
        return status;
    }
    render_job *job;
    status = render_job_parse(argc, argv, &job);
    if (status >= 0) {
        return status;
    }
    const render_opts *o = &job->o;
    render_opts_warn(o);
    /* thumbnail.c runs this render as "thumbnail": its output is the
     * OUTPUT argument there, not an -o the user never gave. */
    const char *out_opt = strcmp(argv[0], "thumbnail") == 0 ? "thumbnail: OUTPUT" : "-o";
    struct stat st;
    if (stat(o->output, &st) == 0 && S_ISDIR(st.st_mode)) {
        cli_error("%s: '%s' is a directory", out_opt, o->output);
        render_job_free(job);
        return EXIT_USAGE;
    }
    /* The model now, before the time to read it; the rest it brings once read. */
    cli_inputs_add(&job->inputs, o->model, "model");
    if (!cli_check_output(&job->inputs, out_opt, o->output)) {
        render_job_free(job);
        return EXIT_USAGE;
    }
    bool jpeg = cli_is_jpeg_name(o->output);
    if (jpeg && o->background_alpha < 1.0f) {
        cli_error("--background transparent: the output '%s' is a JPEG, which has no alpha",
                  o->output);
        render_job_free(job);
        return EXIT_USAGE;
    }
    if (jpeg ? o->png_level >= 0 : o->jpeg_quality > 0) {
        cli_error(jpeg ? "--png-level: the output '%s' is a JPEG (see --jpeg-quality)"
                       : "--jpeg-quality: the output '%s' is a PNG (name it .jpg for a JPEG)",
                  o->output);
        render_job_free(job);
        return EXIT_USAGE;
    }

    /* Refused before anything is allocated, rather than killed for it. */
    status = render_opts_check_frames(o, argv[0], o->width, o->height, 1);
    if (status >= 0) {
        render_job_free(job);
        return status;
    }

    double t0 = now_ms();
    /* The framebuffer is made on a thread of its own while the model
     * file is read on this one: its fresh pages (with the default 4x MSAA
     * at 1920 x 1080, 66 MB of samples and the 8 MB resolved image) are
     * the kernel's to zero, time the reader's one core leaves the other
     * free for.  The reader allocates on the mesh context; the drawing
     * context is used again only once the framebuffer is made
     * (make_context's textures). */
    status = start_context(job);
    if (status >= 0) {
        render_job_free(job);
        return status;
    }
    fb_maker maker = { .ctx = job->ctx,
                       .desc = render_job_direct_desc(job, o->width, o->height) };
    bool threaded = pthread_create(&maker.thread, NULL, make_fb, &maker) == 0;
    if (!threaded) {
        make_fb(&maker);  /* no thread to spare: one after the other */
    }
    status = load_objects(job);
    /* "setup" is the wait for the framebuffer beyond the reading. */
    double t_wait = now_ms();
    if (threaded) {
        pthread_join(maker.thread, NULL);
    }
    double setup_ms = now_ms() - t_wait;
    if (status < 0) {
        status = finish_scene(job);
    }
    if (status < 0) {
        status = load_environment(job);
    }
    if (status < 0) {
        status = make_context(job);
    }
    if (status < 0 && !cli_check_output(&job->inputs, out_opt, o->output)) {
        status = EXIT_USAGE;
    }
    if (status >= 0) {
        sr_destroy_framebuffer(job->ctx, maker.fb);
        render_job_free(job);
        return status;
    }
    sr_framebuffer *fb = maker.fb;
    sr_result r = maker.result;
    double t_setup = now_ms();
    render_frame_info info = { 0 };
    if (r == SR_OK) {
        r = render_job_draw(job, fb, &info);
    } else {
        snprintf(job->error, sizeof job->error, "%s", maker.error);
    }
    double t_render = now_ms();
    if (r != SR_OK) {
        cli_error("render: %s", render_job_error(job));
        sr_destroy_framebuffer(job->ctx, fb);
        render_job_free(job);
        return EXIT_FAILURE_RUN;
    }

    sr_io_error err;
    r = cli_write_image(o->output, o->width, o->height, sr_framebuffer_pixels(fb),
                        &(cli_image_options){ .png_level = o->png_level,
                                              .jpeg_quality = o->jpeg_quality,
                                              .keep_alpha = o->background_alpha < 1.0f,
                                              .premultiplied = true,
                                              .context = job->ctx,
                                              .inputs = &job->inputs },
                        &err);
    double t_write = now_ms();
    if (o->verbose) {
        fprintf(stderr,
                "softrast: %dx%d, %llu triangles, %llu fragments, near %.4g far %.4g, %d threads\n"
                "softrast: load %.1f ms, setup %.1f ms, render %.1f ms, %s %.1f ms\n",
                o->width, o->height, (unsigned long long)info.triangles,
                (unsigned long long)info.fragments, (double)info.near_z, (double)info.far_z,
                sr_context_threads(job->ctx), t_setup - t0 - setup_ms, setup_ms, t_render - t_setup,
                jpeg ? "jpeg" : "png", t_write - t_render);
        cli_inputs_report(&job->inputs);
    }
    sr_destroy_framebuffer(job->ctx, fb);
    render_job_free(job);
    if (r != SR_OK) {
        fprintf(stderr, "%s\n", err.message);
        return EXIT_FAILURE_RUN;
    }
    return EXIT_OK;
}
