/* light_rig.c - softrast render's default lighting, as data for the
 * shading models: the key, fill and rim lights placed relative to the
 * camera, and for the metallic-roughness program the same lights as
 * radiance with a sky-and-ground hemisphere.  Pure functions; any thread.
 * The command, the benchmark and the Python package all light with these,
 * so that their pictures of one model agree. */
#include "softrast.h"
#include "error.h"

#include <math.h>
#include <string.h>

static bool finite3(sr_vec3 a)
{
    return isfinite(a.x) && isfinite(a.y) && isfinite(a.z);
}

static bool unit(sr_vec3 a)
{
    return finite3(a) && fabsf(sr_vec3_length(a) - 1.0f) < 1e-3f;
}

sr_result sr_default_lights(const sr_camera_basis *basis, sr_light lights[SR_MAX_LIGHTS])
{
    if (!basis || !lights) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_default_lights: %s is NULL",
                        basis ? "lights" : "basis");
    }
    if (!unit(basis->u) || !unit(basis->v) || !unit(basis->w)) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_default_lights: basis->%s is not a unit vector",
                        !unit(basis->u) ? "u" : !unit(basis->v) ? "v" : "w");
    }
    /* Towards each light in the basis (u across, v up, w towards the
     * viewer), and its intensity. */
    static const float rig[SR_DEFAULT_LIGHT_COUNT][4] = {
        { -0.55f, 0.70f, 0.45f, 0.95f },   /* key: upper left, towards the viewer */
        { 0.80f, 0.05f, 0.60f, 0.35f },    /* fill: right */
        { 0.10f, 0.55f, -0.85f, 0.45f },   /* rim: behind, above */
    };
    memset(lights, 0, SR_MAX_LIGHTS * sizeof *lights);
    for (int i = 0; i < SR_DEFAULT_LIGHT_COUNT; i++) {
        sr_vec3 to_light = sr_vec3_add(sr_vec3_add(sr_vec3_scale(basis->u, rig[i][0]),
                                                   sr_vec3_scale(basis->v, rig[i][1])),
                                       sr_vec3_scale(basis->w, rig[i][2]));
        lights[i] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL,
                                .vector = sr_vec3_scale(sr_vec3_normalize(to_light), -1.0f),
                                .color = { 1.0f, 0.98f, 0.95f },
                                .intensity = rig[i][3] };
    }
    return SR_OK;
}

sr_result sr_pbr_default_lighting(const sr_light lights[SR_MAX_LIGHTS], sr_pbr_desc *desc)
{
    if (!lights || !desc) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_pbr_default_lighting: %s is NULL",
                        lights ? "desc" : "lights");
    }
    for (int i = 0; i < SR_MAX_LIGHTS; i++) {
        if ((unsigned)lights[i].type > SR_LIGHT_POINT) {
            return sr__fail(NULL, SR_INVALID_ARG,
                            "sr_pbr_default_lighting: lights[%d].type %d is not off, "
                            "directional or point", i, (int)lights[i].type);
        }
        if (!finite3(lights[i].vector) || !finite3(lights[i].color) ||
            !isfinite(lights[i].intensity)) {
            return sr__fail(NULL, SR_INVALID_ARG,
                            "sr_pbr_default_lighting: lights[%d].%s is not finite", i,
                            !finite3(lights[i].vector)  ? "vector"
                            : !finite3(lights[i].color) ? "color"
                                                        : "intensity");
        }
    }
    for (int i = 0; i < SR_MAX_LIGHTS; i++) {
        desc->lights[i] = lights[i];
        /* Radiance for a BRDF whose white Lambertian part is 1/pi: this
         * scale gives a surface facing the key light, encoded to sRGB,
         * about the brightness the Blinn-Phong look gives it. */
        float in = lights[i].intensity != 0.0f ? lights[i].intensity : 1.0f;
        desc->lights[i].intensity = in * SR_PBR_LIGHT_SCALE;
    }
    desc->sky = (sr_vec3){ 0.16f, 0.165f, 0.18f };
    desc->ground = (sr_vec3){ 0.05f, 0.048f, 0.045f };
    return SR_OK;
}

sr_result sr_pbr_scene_lights(const sr_light *scene_lights, size_t count, bool keep_rig,
                              sr_light lights[SR_MAX_LIGHTS])
{
    if (!lights || (count > 0 && !scene_lights)) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_pbr_scene_lights: %s is NULL",
                        lights ? "scene_lights" : "lights");
    }
    for (size_t i = 0; i < count; i++) {
        if ((unsigned)scene_lights[i].type > SR_LIGHT_SPOT) {
            return sr__fail(NULL, SR_INVALID_ARG,
                            "sr_pbr_scene_lights: scene_lights[%zu].type %d is not a light type",
                            i, (int)scene_lights[i].type);
        }
    }
    sr_light mine[SR_MAX_LIGHTS] = { 0 };
    int n = 0, key = -1;
    float key_power = -1.0f;
    for (size_t i = 0; i < count && n < SR_MAX_LIGHTS; i++) {
        const sr_light *l = &scene_lights[i];
        if (l->type == SR_LIGHT_OFF) {
            continue;
        }
        if (l->type == SR_LIGHT_DIRECTIONAL) {
            float c = fmaxf(fmaxf(l->color.x, l->color.y), l->color.z);
            if (c * l->intensity > key_power) {
                key_power = c * l->intensity;
                key = n;
            }
        }
        mine[n++] = *l;
    }
    if (key > 0) {
        sr_light k = mine[key];
        memmove(&mine[1], &mine[0], (size_t)key * sizeof *mine);
        mine[0] = k;
    }
    if (keep_rig) {
        bool rig_first = n == 0 || mine[0].type != SR_LIGHT_DIRECTIONAL;
        sr_light merged[SR_MAX_LIGHTS] = { 0 };
        int m = 0;
        for (int pass = 0; pass < 2; pass++) {
            bool take_rig = (pass == 0) == rig_first;
            for (int l = 0; l < (take_rig ? SR_MAX_LIGHTS : n) && m < SR_MAX_LIGHTS; l++) {
                const sr_light *li = take_rig ? &lights[l] : &mine[l];
                if (li->type != SR_LIGHT_OFF) {
                    merged[m++] = *li;
                }
            }
        }
        memcpy(mine, merged, sizeof mine);
    }
    memcpy(lights, mine, sizeof mine);
    return SR_OK;
}
