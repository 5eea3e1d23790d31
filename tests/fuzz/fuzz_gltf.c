/* fuzz_gltf.c - libFuzzer target: sr_parse_gltf on arbitrary bytes (JSON
 * or GLB).  A parse either fails with one line, or gives a scene whose
 * every primitive's indices are in range, whose arrays hold vertex_count
 * entries (ASan checks the reads), whose materials exist and whose
 * texture slots point to the scene's own textures, whose lights and
 * materials the PBR program accepts and whose cameras give finite
 * matrices or none; a file with animations parses again posed by them,
 * to the same draws and to lights, materials and cameras that pass the
 * same checks (or fails as docs/gltf.md says a pose may).  Relative URIs
 * name files in the current directory: none by default.
 * scripts/fuzz.sh fuzz_gltf SECONDS. */
#include "fuzz_mesh.h"

#include <math.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static bool owned_texture(const sr_scene *s, const sr_texture *t)
{
    for (size_t i = 0; t && i < s->texture_count; i++) {
        if (s->textures[i] == t) {
            return true;
        }
    }
    return t == NULL;
}

static bool finite_mat4(const sr_mat4 *m)
{
    for (int i = 0; i < 16; i++) {
        if (!isfinite(m->m[i])) {
            return false;
        }
    }
    return true;
}

/* What softrast render takes of a scene: each light and (the first few)
 * material as a PBR program's, each camera's matrices finite when
 * sr_scene_camera_matrices gives them. */
static void check_renderable(const sr_scene *s)
{
    for (size_t i = 0; i < s->light_count; i++) {
        const sr_scene_light *l = &s->lights[i];
        FUZZ_CHECK(l->node >= 0 && l->light_index >= 0);
        sr_pbr_desc d = { 0 };
        d.lights[0] = l->light;
        sr_pbr *p = NULL;
        FUZZ_CHECK(sr_make_pbr_program(fuzz_context(), &d, &p) == SR_OK);
        sr_destroy_pbr_program(fuzz_context(), p);
    }
    for (size_t i = 0; i < s->material_count && i < 4; i++) {
        sr_pbr_desc d = { .material = &s->materials[i] };
        sr_pbr *p = NULL;
        if (sr_make_pbr_program(fuzz_context(), &d, &p) != SR_OK) {
            fprintf(stderr, "material %zu: %s\n", i, sr_context_error(fuzz_context()));
            FUZZ_CHECK(!"a material the PBR program refuses");
        }
        sr_destroy_pbr_program(fuzz_context(), p);
    }
    for (size_t i = 0; i < s->camera_count; i++) {
        FUZZ_CHECK(s->cameras[i].type == SR_SCENE_CAMERA_PERSPECTIVE ||
                   s->cameras[i].type == SR_SCENE_CAMERA_ORTHOGRAPHIC);
        sr_mat4 view, projection;
        if (sr_scene_camera_matrices(&s->cameras[i], 1.5f, &view, &projection) == SR_OK) {
            FUZZ_CHECK(finite_mat4(&view) && finite_mat4(&projection));
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    sr_scene *s = NULL;
    sr_io_error err;
    memset(&err, 0, sizeof err);
    sr_result r = sr_parse_gltf(fuzz_context(), "fuzz.gltf", data, size, NULL, &s, &err);
    if (r != SR_OK) {
        FUZZ_CHECK(r > SR_OK && r < SR_RESULT_COUNT);
        FUZZ_CHECK(s == NULL);
        FUZZ_CHECK(err.message[0] != '\0');
        FUZZ_CHECK(strchr(err.message, '\n') == NULL);
        return 0;
    }
    FUZZ_CHECK(s != NULL);
    FUZZ_CHECK(s->primitive_count <= SR_SCENE_MAX_DRAWS);
    volatile float sink = 0;
    for (size_t i = 0; i < s->primitive_count; i++) {
        const sr_scene_primitive *p = &s->primitives[i];
        FUZZ_CHECK(p->material >= 0 && (size_t)p->material < s->material_count);
        FUZZ_CHECK(p->positions != NULL && p->vertex_count > 0);
        size_t n = p->vertex_count;
        sink += p->positions[3 * n - 1];
        if (p->normals) sink += p->normals[3 * n - 1];
        if (p->tangents) sink += p->tangents[4 * n - 1];
        if (p->texcoords0) sink += p->texcoords0[2 * n - 1];
        if (p->texcoords1) sink += p->texcoords1[2 * n - 1];
        if (p->colors) sink += p->colors[4 * n - 1];
        for (size_t k = 0; k < 3 * p->triangle_count; k++) {
            FUZZ_CHECK(p->indices[k] < n);
        }
    }
    (void)sink;
    for (size_t i = 0; i < s->material_count; i++) {
        const sr_pbr_material *m = &s->materials[i];
        FUZZ_CHECK(owned_texture(s, m->base_color_texture.texture));
        FUZZ_CHECK(owned_texture(s, m->metallic_roughness_texture.texture));
        FUZZ_CHECK(owned_texture(s, m->normal_texture.texture));
        FUZZ_CHECK(owned_texture(s, m->occlusion_texture.texture));
        FUZZ_CHECK(owned_texture(s, m->emissive_texture.texture));
        FUZZ_CHECK(owned_texture(s, m->specular_glossiness_texture.texture));
    }
    check_renderable(s);
    /* A file with animations, read again posed by its first two at
     * times before, inside and after their keys: the same draws, from
     * the same nodes, with finite sampled values where the keys are. */
    for (size_t a = 0; a < s->animation_count && a < 2; a++) {
        const sr_scene_animation *anim = &s->animations[a];
        FUZZ_CHECK(anim->name != NULL && anim->channel_count > 0);
        FUZZ_CHECK(anim->duration >= 0.0f);
        const float times[3] = { -1.0f, anim->duration * 0.37f, anim->duration + 1.0f };
        for (int k = 0; k < 3; k++) {
            sr_load_desc desc = { .pose = SR_POSE_ANIMATION, .animation = (int)a,
                                  .animation_time = times[k] };
            sr_scene *posed = NULL;
            memset(&err, 0, sizeof err);
            r = sr_parse_gltf(fuzz_context(), "fuzz.gltf", data, size, &desc, &posed, &err);
            if (r != SR_OK) {
                /* docs/gltf.md: a pose may turn a light's node to nothing. */
                FUZZ_CHECK(r == SR_BAD_FORMAT && posed == NULL &&
                           strstr(err.message, "collapses the light's direction") != NULL);
                continue;
            }
            FUZZ_CHECK(posed != NULL);
            FUZZ_CHECK(posed->animation == (int)a);
            FUZZ_CHECK(posed->primitive_count == s->primitive_count);
            for (size_t i = 0; i < s->primitive_count; i++) {
                FUZZ_CHECK(posed->primitives[i].node == s->primitives[i].node);
            }
            check_renderable(posed);
            sr_destroy_scene(fuzz_context(), posed);
        }
    }
    sr_destroy_scene(fuzz_context(), s);
    return 0;
}
