/*
 * render_pbr.c - the color pass of render(shading="pbr"): each instance
 * drawn by the library's metallic-roughness program as softrast render
 * draws a glTF file (docs/pbr.md): in world space, lit by the default
 * rig relative to the camera (sr_default_lights, sr_pbr_default_lighting)
 * or by an environment and the key light alone, by the scene's own
 * lights instead or too (--lights: sr_pbr_scene_lights), with the key light's
 * shadow map when asked; opaque and masked instances first, then the
 * transmissive ones (KHR_materials_transmission, seeing an image of the
 * others drawn first without the tone curve, as softrast render does),
 * then blended ones farthest first, each with its triangles back to front
 * (sr_mean_view_depth, sr_sort_back_to_front) and no depth writes.  An
 * instance loaded from a glTF file draws its primitive's own arrays and
 * material, textures included; any other takes its Mesh's colors and
 * texture as the base color.  Runs without the GIL.
 */
#include "render.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* What one instance draws: its arrays, and its material's textures. */
typedef struct pbr_draw {
    sr_draw_desc d;
    const float *tangents, *texcoords1;
    bool mirrored;
    sr_mat4 model;
} pbr_draw;

static void draw_of(const instance *in, pbr_draw *out)
{
    memset(out, 0, sizeof *out);
    sr_py_mat_from_rows(in->pose, &out->model);
    bool mirrored = sr_py_mirrors(in->pose);
    if (in->src) {
        const sr_mesh *m = &in->src->mesh;
        out->d = (sr_draw_desc){ .positions = m->positions, .normals = m->normals,
                                 .colors = m->colors, .color_size = m->colors ? 4 : 0,
                                 .texcoords = m->texcoords, .vertex_count = m->vertex_count,
                                 .indices = m->indices, .index_type = SR_INDEX_U32,
                                 .index_count = 3 * m->triangle_count };
        out->tangents = in->src->tangents;
        out->texcoords1 = in->src->texcoords1;
        out->mirrored = mirrored;
        return;
    }
    const MeshObject *m = in->mesh;
    out->d = (sr_draw_desc){
        .positions = in->positions, .normals = m->normals ? PyArray_DATA(m->normals) : NULL,
        .colors = m->colors ? PyArray_DATA(m->colors) : NULL,
        .color_size = m->colors ? (int)PyArray_DIM(m->colors, 1) : 0,
        .texcoords = m->uvs ? PyArray_DATA(m->uvs) : NULL,
        .vertex_count = (size_t)PyArray_DIM(m->vertices, 0),
        .indices = in->indices, .index_type = SR_INDEX_U32,
        .index_count = 3 * (size_t)PyArray_DIM(m->faces, 0) };
    out->mirrored = mirrored;
}

/* The instance's material: a loaded primitive's (every texture) or one
 * whose base color texture is the Mesh's `tex` (with the instance's
 * sampler), with the factors, alpha mode and flags of its Material. */
static sr_pbr_material material_of(const instance *in, const sr_texture *tex)
{
    const sr_pbr_material *f = &in->factors;
    sr_pbr_material m = sr_pbr_default_material();
    if (in->src) {
        m = *in->src->material;
    } else {
        m.base_color_texture.texture = tex;
        m.base_color_texture.filter = in->filter;
        m.base_color_texture.wrap_u = in->wrap_u;
        m.base_color_texture.wrap_v = in->wrap_v;
    }
    memcpy(m.base_color, f->base_color, sizeof m.base_color);
    memcpy(m.emissive, f->emissive, sizeof m.emissive);
    m.metallic = f->metallic;
    m.roughness = f->roughness;
    m.emissive_strength = f->emissive_strength;
    m.emissive_strength_set = f->emissive_strength_set;
    m.alpha_mode = f->alpha_mode;
    m.alpha_cutoff = f->alpha_cutoff;
    m.double_sided = f->double_sided;
    m.unlit = f->unlit;
    m.normal_scale = f->normal_scale;
    m.occlusion_strength = f->occlusion_strength;
    m.ior = f->ior;
    m.specular_set = f->specular_set;
    m.specular = f->specular;
    memcpy(m.specular_color, f->specular_color, sizeof m.specular_color);
    m.clearcoat = f->clearcoat;
    m.clearcoat_roughness = f->clearcoat_roughness;
    memcpy(m.sheen_color, f->sheen_color, sizeof m.sheen_color);
    m.sheen_roughness = f->sheen_roughness;
    m.transmission = f->transmission;
    m.thickness = f->thickness;
    memcpy(m.attenuation_color, f->attenuation_color, sizeof m.attenuation_color);
    m.attenuation_distance = f->attenuation_distance;
    m.anisotropy_strength = f->anisotropy_strength;
    m.anisotropy_rotation = f->anisotropy_rotation;
    m.iridescence = f->iridescence;
    m.iridescence_ior = f->iridescence_ior;
    m.iridescence_thickness_set = f->iridescence_thickness_set;
    m.iridescence_thickness_min = f->iridescence_thickness_min;
    m.iridescence_thickness_max = f->iridescence_thickness_max;
    m.dispersion = f->dispersion;
    m.diffuse_transmission = f->diffuse_transmission;
    memcpy(m.diffuse_transmission_color, f->diffuse_transmission_color,
           sizeof m.diffuse_transmission_color);
    m.specular_glossiness = f->specular_glossiness;
    memcpy(m.sg_specular, f->sg_specular, sizeof m.sg_specular);
    m.glossiness = f->glossiness;
    return m;
}

/* The world box of every instance's drawn vertices (as softrast render
 * fits its shadow map to the model's box); false when empty. */
static bool world_box(const render_job *j, sr_vec3 *lo, sr_vec3 *hi)
{
    double l[3] = { INFINITY, INFINITY, INFINITY }, h[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (size_t i = 0; i < j->count; i++) {
        pbr_draw pd;
        draw_of(&j->inst[i], &pd);
        const double (*a)[4] = j->inst[i].pose;
        for (size_t v = 0; v < pd.d.vertex_count; v++) {
            const float *p = &pd.d.positions[3 * v];
            for (int k = 0; k < 3; k++) {
                double w = a[k][0] * p[0] + a[k][1] * p[1] + a[k][2] * p[2] + a[k][3];
                l[k] = w < l[k] ? w : l[k];
                h[k] = w > h[k] ? w : h[k];
            }
        }
    }
    *lo = (sr_vec3){ (float)l[0], (float)l[1], (float)l[2] };
    *hi = (sr_vec3){ (float)h[0], (float)h[1], (float)h[2] };
    return l[0] <= h[0];
}

static sr_result draw_shadow_map(sr_context *ctx, const render_job *j, sr_vec3 direction,
                                 sr_shadow_map **out)
{
    *out = NULL;
    sr_vec3 lo, hi;
    if (!world_box(j, &lo, &hi)) {
        return SR_OK;
    }
    sr_result r = sr_make_shadow_map(ctx, &(sr_shadow_desc){
        .direction = direction, .bounds_min = lo, .bounds_max = hi,
        .size = SR_DEFAULT_SHADOW_SIZE, .light_radius = SR_DEFAULT_SHADOW_LIGHT_RADIUS }, out);
    if (r != SR_OK) {
        *out = NULL;
        return r;
    }
    r = sr_shadow_map_clear(ctx, *out);
    for (size_t i = 0; i < j->count && r == SR_OK; i++) {
        pbr_draw pd;
        draw_of(&j->inst[i], &pd);
        if (pd.d.index_count > 0) {
            r = sr_shadow_map_draw(ctx, *out, &(sr_draw_desc){
                .positions = pd.d.positions, .vertex_count = pd.d.vertex_count,
                .indices = pd.d.indices, .index_type = SR_INDEX_U32,
                .index_count = pd.d.index_count, .model = &pd.model });
        }
    }
    return r;
}

typedef struct pass_light {
    sr_mat4 view;               /* world -> OpenGL's eye space */
    sr_light lights[SR_MAX_LIGHTS];   /* as the program takes them: the rig as radiance */
    sr_vec3 sky, ground;
    const sr_shadow_map *shadow;
} pass_light;

/* Draws one instance; transmissive ones see `see` (NULL: black), and
 * `tonemap` is the program's tone curve (NONE for the transmission
 * source). */
static sr_result draw_one(sr_context *ctx, sr_framebuffer *fb, const render_job *j,
                          const instance *in, const pass_light *pl, const sr_mat4 *proj,
                          const sr_texture *see, sr_tonemap_op tonemap)
{
    pbr_draw pd;
    draw_of(in, &pd);
    if (pd.d.index_count == 0) {
        return SR_OK;
    }
    sr_texture *tex = NULL;
    sr_result r = in->src ? SR_OK : sr_py_make_texture(ctx, in->mesh, &tex);
    if (r != SR_OK) {
        return r;
    }
    sr_pbr_material m = material_of(in, tex);
    sr_pbr_desc d = { .material = &m, .model = &pd.model, .view = &pl->view, .projection = proj,
                      .vertex_color = pd.d.colors ? SR_ON : SR_OFF, .tangents = pd.tangents,
                      .texcoords1 = pd.texcoords1, .environment = j->env, .shadow = pl->shadow,
                      .transmission_source = see, .tonemap = tonemap };
    if (pd.tangents || pd.texcoords1) {
        d.vertex_count = pd.d.vertex_count;
    }
    d.exposure = j->exposure;
    d.tonemap = j->tonemap;
    memcpy(d.lights, pl->lights, sizeof d.lights);
    d.sky = pl->sky;
    d.ground = pl->ground;
    sr_pbr *program = NULL;
    r = sr_make_pbr_program(ctx, &d, &program);
    sr_state st = {
        .depth_zero_to_one = true, .depth_func = SR_GREATER,
        .cull = m.double_sided && !j->cull_back ? SR_CULL_NONE : SR_CULL_BACK,
        .front_face = pd.mirrored ? SR_FRONT_CW : SR_FRONT_CCW,
        .two_sided = m.double_sided,
        .program = program ? sr_pbr_program(program) : NULL,
    };
    uint32_t *sorted = NULL;
    if (r == SR_OK && m.alpha_mode == SR_ALPHA_BLEND) {
        sr_mat4 mv = sr_mat4_mul(&pl->view, &pd.model);
        size_t n = pd.d.index_count / 3;
        sorted = malloc(pd.d.index_count * sizeof *sorted);
        r = sorted ? sr_sort_back_to_front(ctx, pd.d.positions, pd.d.vertex_count, pd.d.indices,
                                           n, &mv, sorted)
                   : SR_OUT_OF_MEMORY;
        pd.d.indices = sorted;
        st.depth_write = SR_OFF;
        st.blend = (sr_blend){ .enabled = true, .src_rgb = SR_BLEND_SRC_ALPHA,
                               .dst_rgb = SR_BLEND_ONE_MINUS_SRC_ALPHA,
                               .src_alpha = SR_BLEND_ONE,
                               .dst_alpha = SR_BLEND_ONE_MINUS_SRC_ALPHA };
    }
    if (r == SR_OK) {
        r = sr_draw(ctx, fb, &st, &pd.d);
    }
    free(sorted);
    sr_destroy_pbr_program(ctx, program);
    sr_destroy_texture(ctx, tex);
    return r;
}

/* softrast render's --ground: the shadow catcher under the instances'
 * world box (sr_make_ground_mesh, +y up), after the opaque instances,
 * whose depth hides the ground behind them, and before the blended
 * ones. */
static sr_result draw_ground(sr_context *ctx, sr_framebuffer *fb, const render_job *j,
                             const pass_light *pl, const sr_mat4 *proj)
{
    sr_vec3 lo, hi;
    if (!world_box(j, &lo, &hi)) {
        return SR_OK;
    }
    sr_mesh ground = { 0 };
    sr_result r = sr_make_ground_mesh(ctx, &(sr_ground_desc){ .bounds_min = lo, .bounds_max = hi },
                                      &ground);
    if (r == SR_OK) {
        sr_state st = { .depth_zero_to_one = true, .depth_func = SR_GREATER };
        r = sr_draw_shadow_catcher(ctx, fb, &st, &(sr_shadow_catcher_desc){
            .ground = &ground, .map = pl->shadow, .direction = pl->lights[0].vector,
            .bounds_min = lo, .bounds_max = hi, .view = &pl->view, .projection = proj });
    }
    sr_destroy_mesh(ctx, &ground);
    return r;
}

/* Which pass draws an instance: 0 opaque and masked, 1 transmissive,
 * 2 blended. */
static int pass_of(const instance *in)
{
    if (in->factors.alpha_mode == SR_ALPHA_BLEND) {
        return 2;
    }
    return in->factors.transmission > 0.0f && !in->factors.unlit ? 1 : 0;
}

/* The opaque instances and the ground, drawn into a framebuffer of fb's
 * size with the background and no tone curve, as the texture the
 * transmissive instances see (*out stays NULL when there are none). */
static sr_result transmission_source(sr_context *ctx, const render_job *j, const pass_light *pl,
                                     const sr_mat4 *proj, sr_texture **out)
{
    *out = NULL;
    bool any = false;
    for (size_t i = 0; i < j->count; i++) {
        any |= pass_of(&j->inst[i]) == 1;
    }
    if (!any) {
        return SR_OK;
    }
    sr_framebuffer *src = NULL;
    sr_result r = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){
        .width = j->width, .height = j->height, .depth_format = SR_DEPTH_D32F }, &src);
    if (r == SR_OK) {
        r = sr_clear(ctx, src, &(sr_clear_desc){
            .color = { j->background[0], j->background[1], j->background[2], 1.0f },
            .depth_action = SR_ACTION_CLEAR, .depth = 0 });
    }
    for (size_t i = 0; i < j->count && r == SR_OK; i++) {
        if (pass_of(&j->inst[i]) == 0) {
            r = draw_one(ctx, src, j, &j->inst[i], pl, proj, NULL, SR_TONEMAP_NONE);
        }
    }
    if (r == SR_OK && pl->shadow && j->ground) {
        r = draw_ground(ctx, src, j, pl, proj);
    }
    if (r == SR_OK) {
        r = sr_make_texture(ctx, &(sr_texture_desc){ .width = j->width, .height = j->height,
                                                     .pixels = sr_framebuffer_pixels(src),
                                                     .srgb = true },
                            out);
    }
    sr_destroy_framebuffer(ctx, src);
    return r;
}

sr_result sr_py_pbr_pass(sr_context *ctx, sr_framebuffer *fb, const render_job *j,
                         const sr_mat4 *proj)
{
    /* OpenCV's camera frame (y down, z forward) to OpenGL's eye space (y
     * up, z backward): the program's view, whose rows are the camera's
     * basis, so the rig follows the camera as softrast render's does. */
    pass_light pl = { .shadow = NULL };
    double v[3][4];
    for (int r = 0; r < 3; r++) {
        for (int c = 0; c < 4; c++) {
            v[r][c] = (r == 0 ? 1.0 : -1.0) * j->view[r][c];
        }
    }
    sr_py_mat_from_rows(v, &pl.view);
    sr_camera_basis basis = { .u = { (float)v[0][0], (float)v[0][1], (float)v[0][2] },
                              .v = { (float)v[1][0], (float)v[1][1], (float)v[1][2] },
                              .w = { (float)v[2][0], (float)v[2][1], (float)v[2][2] } };
    sr_result r = sr_default_lights(&basis, pl.lights);
    if (r == SR_OK && j->env) {
        /* The environment is the fill and the rim: the key light stays,
         * for shape. */
        for (int l = 1; l < SR_MAX_LIGHTS; l++) {
            pl.lights[l].type = SR_LIGHT_OFF;
        }
    }
    sr_pbr_desc rig = { 0 };
    if (r == SR_OK) {
        r = sr_pbr_default_lighting(pl.lights, &rig);
    }
    memcpy(pl.lights, rig.lights, sizeof pl.lights);
    pl.sky = rig.sky;
    pl.ground = rig.ground;
    if (r == SR_OK && j->lights_mode != 0) {
        /* softrast render's --lights file|both. */
        r = sr_pbr_scene_lights(j->lights, (size_t)j->light_count, j->lights_mode == 2,
                                pl.lights);
    }
    /* The map is directional: a key light that is not casts none. */
    sr_shadow_map *shadow = NULL;
    if (r == SR_OK && j->shadows && pl.lights[0].type == SR_LIGHT_DIRECTIONAL) {
        r = draw_shadow_map(ctx, j, pl.lights[0].vector, &shadow);
        pl.shadow = shadow;
    }
    /* Blended instances after the others, farthest first. */
    float *depth = malloc((j->count ? j->count : 1) * sizeof *depth);
    size_t *blended = malloc((j->count ? j->count : 1) * sizeof *blended), nb = 0;
    if ((!depth || !blended) && r == SR_OK) {
        r = SR_OUT_OF_MEMORY;
    }
    sr_texture *see = NULL;
    if (r == SR_OK) {
        r = transmission_source(ctx, j, &pl, proj, &see);
    }
    for (size_t i = 0; i < j->count && r == SR_OK; i++) {
        const instance *in = &j->inst[i];
        if (pass_of(in) == 0) {
            r = draw_one(ctx, fb, j, in, &pl, proj, NULL, SR_TONEMAP_DEFAULT);
        }
        if (pass_of(in) != 2) {
            continue;
        }
        pbr_draw pd;
        draw_of(in, &pd);
        sr_mat4 mv = sr_mat4_mul(&pl.view, &pd.model);
        blended[nb] = i;
        r = sr_mean_view_depth(pd.d.positions, pd.d.vertex_count, pd.d.indices,
                               pd.d.index_count / 3, &mv, &depth[nb]);
        nb++;
    }
    if (r == SR_OK && shadow && j->ground) {
        r = draw_ground(ctx, fb, j, &pl, proj);
    }
    for (size_t i = 0; i < j->count && r == SR_OK; i++) {
        if (pass_of(&j->inst[i]) == 1) {
            r = draw_one(ctx, fb, j, &j->inst[i], &pl, proj, see, SR_TONEMAP_DEFAULT);
        }
    }
    size_t *order = malloc((nb ? nb : 1) * sizeof *order);
    if (r == SR_OK) {
        r = order ? sr_order_back_to_front(ctx, depth, nb, order) : SR_OUT_OF_MEMORY;
    }
    for (size_t k = 0; k < nb && r == SR_OK; k++) {
        r = draw_one(ctx, fb, j, &j->inst[blended[order[k]]], &pl, proj, see,
                     SR_TONEMAP_DEFAULT);
    }
    sr_destroy_texture(ctx, see);
    free(order);
    free(depth);
    free(blended);
    sr_destroy_shadow_map(ctx, shadow);
    return r;
}
