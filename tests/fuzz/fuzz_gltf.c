/* fuzz_gltf.c - libFuzzer target: sr_parse_gltf on arbitrary bytes (JSON
 * or GLB).  A parse either fails with one line, or gives a scene whose
 * every primitive's indices are in range, whose arrays hold vertex_count
 * entries (ASan checks the reads), whose materials exist and whose
 * texture slots point to the scene's own textures, and whose lights the
 * PBR program accepts; a file with animations parses again posed by
 * them, to the same draws.  Relative URIs name
 * files in the current directory: none by default.
 * scripts/fuzz.sh fuzz_gltf SECONDS. */
#include "fuzz_mesh.h"

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
    }
    for (size_t i = 0; i < s->camera_count; i++) {
        FUZZ_CHECK(s->cameras[i].type == SR_SCENE_CAMERA_PERSPECTIVE ||
                   s->cameras[i].type == SR_SCENE_CAMERA_ORTHOGRAPHIC);
    }
    /* Every light the reader places, the program takes as it is. */
    for (size_t i = 0; i < s->light_count; i++) {
        const sr_scene_light *l = &s->lights[i];
        FUZZ_CHECK(l->node >= 0 && l->light_index >= 0);
        sr_pbr_desc d = { 0 };
        d.lights[0] = l->light;
        sr_pbr *p = NULL;
        FUZZ_CHECK(sr_make_pbr_program(fuzz_context(), &d, &p) == SR_OK);
        sr_destroy_pbr_program(fuzz_context(), p);
    }
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
            FUZZ_CHECK(r == SR_OK && posed != NULL);
            FUZZ_CHECK(posed->animation == (int)a);
            FUZZ_CHECK(posed->primitive_count == s->primitive_count);
            for (size_t i = 0; i < s->primitive_count; i++) {
                FUZZ_CHECK(posed->primitives[i].node == s->primitives[i].node);
            }
            sr_destroy_scene(fuzz_context(), posed);
        }
    }
    sr_destroy_scene(fuzz_context(), s);
    return 0;
}
