/* render_lights.c - the lights of pbr's program for `softrast render`
 * (docs/pbr.md, "Lights"): a glTF file's own (KHR_lights_punctual, read
 * by sr_load_scene), the default key, fill and rim rig or the --light
 * options, or both, as --lights chooses.  Called by render.c once a
 * frame, on the thread that draws it. */
#include "render_lights.h"

#include "softrast_io.h"

#include <string.h>

/* The glTF object: render_gltf.c merges the file into objects[0]. */
static const scene_object *file_object(const scene *s)
{
    return s->gltf && s->count > 0 && s->objects[0].part_material ? &s->objects[0] : NULL;
}

int render_lights_in_file(const scene *s)
{
    int n = 0;
    for (size_t i = 0; file_object(s) && i < s->gltf->light_count && n < SR_MAX_LIGHTS; i++) {
        n += s->gltf->lights[i].light.type != SR_LIGHT_OFF;
    }
    return n;
}

static sr_vec3 move_point(const sr_mat4 *m, sr_vec3 p)
{
    const float *a = m->m;
    return (sr_vec3){ a[0] * p.x + a[4] * p.y + a[8] * p.z + a[12],
                      a[1] * p.x + a[5] * p.y + a[9] * p.z + a[13],
                      a[2] * p.x + a[6] * p.y + a[10] * p.z + a[14] };
}

static sr_vec3 move_direction(const sr_mat4 *m, sr_vec3 d)
{
    const float *a = m->m;
    return sr_vec3_normalize((sr_vec3){ a[0] * d.x + a[4] * d.y + a[8] * d.z,
                                        a[1] * d.x + a[5] * d.y + a[9] * d.z,
                                        a[2] * d.x + a[6] * d.y + a[10] * d.z });
}

/* The file's lit lights into out (room for SR_MAX_LIGHTS), moved by the
 * object's model matrix (rotations and translations: --up, --turn), in
 * the file's order.  Returns how many. */
static int file_lights(const scene *s, sr_light *out)
{
    const scene_object *ob = file_object(s);
    int n = 0;
    for (size_t i = 0; ob && i < s->gltf->light_count && n < SR_MAX_LIGHTS; i++) {
        sr_light l = s->gltf->lights[i].light;
        if (l.type == SR_LIGHT_OFF) {
            continue;
        }
        if (l.type == SR_LIGHT_DIRECTIONAL) {
            l.vector = move_direction(&ob->model, l.vector);
        } else {
            l.vector = move_point(&ob->model, l.vector);
            if (l.type == SR_LIGHT_SPOT) {
                l.direction = move_direction(&ob->model, l.direction);
            }
        }
        out[n++] = l;
    }
    return n;
}

void render_lights_pbr(const render_opts *o, const scene *s, const sr_light rig[SR_MAX_LIGHTS],
                       bool image_light, sr_pbr_desc *lighting)
{
    /* The rig as radiance, and the hemisphere (the ambient light when no
     * environment replaces it). */
    sr_pbr_default_lighting(rig, lighting);
    if (image_light && o->light_count == 0) {
        /* The studio is the fill and the rim: of the classic rig only the
         * key light stays, for shape. */
        for (int l = 1; l < SR_MAX_LIGHTS; l++) {
            lighting->lights[l].type = SR_LIGHT_OFF;
        }
    }
    int source = o->lights_source;
    if (source == LIGHTS_AUTO) {
        source = o->light_count == 0 && render_lights_in_file(s) > 0 ? LIGHTS_FILE
                                                                     : LIGHTS_DEFAULT;
    }
    if (source == LIGHTS_DEFAULT) {
        return;
    }
    /* The file's in place of the rig, or before it (sr_pbr_scene_lights:
     * the strongest directional one first, to cast the shadow). */
    sr_light mine[SR_MAX_LIGHTS] = { 0 };
    int n = file_lights(s, mine);
    sr_pbr_scene_lights(mine, (size_t)n, source == LIGHTS_BOTH, lighting->lights);
}
