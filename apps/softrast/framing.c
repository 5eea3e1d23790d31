/* framing.c - the default camera and lights of `softrast render`. */
#include "framing.h"

#include <math.h>

sr_vec3 framing_default_eye(sr_vec3 centre, float radius, float fov_radians)
{
    float dist = radius / sinf(fov_radians * 0.5f) * 1.04f;
    sr_vec3 dir = sr_vec3_normalize((sr_vec3){ 0.62f, 0.48f, 1.0f });
    return sr_vec3_add(centre, sr_vec3_scale(dir, dist));
}

void framing_near_far(sr_vec3 eye, sr_vec3 centre, float radius, float *near_z, float *far_z)
{
    float dc = sr_vec3_length(sr_vec3_sub(centre, eye));
    *far_z = (dc + radius) * 1.01f;
    /* Never closer than 1/1000 of far: depth precision stays usable when
     * the eye is inside the sphere. */
    *near_z = fmaxf(dc - radius, *far_z * 1e-3f) * 0.99f;
}

int framing_default_lights(const sr_camera_basis *b, sr_light *lights)
{
    struct { float u, v, w, intensity; } rig[3] = {
        { -0.55f, 0.70f, 0.45f, 0.95f },   /* key: upper left, towards the viewer */
        { 0.80f, 0.05f, 0.60f, 0.35f },    /* fill: right */
        { 0.10f, 0.55f, -0.85f, 0.45f },   /* rim: behind, above */
    };
    for (int i = 0; i < 3; i++) {
        sr_vec3 to_light = sr_vec3_add(sr_vec3_add(sr_vec3_scale(b->u, rig[i].u),
                                                   sr_vec3_scale(b->v, rig[i].v)),
                                       sr_vec3_scale(b->w, rig[i].w));
        lights[i] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL,
                                .vector = sr_vec3_scale(sr_vec3_normalize(to_light), -1.0f),
                                .color = { 1.0f, 0.98f, 0.95f },
                                .intensity = rig[i].intensity };
    }
    return 3;
}
