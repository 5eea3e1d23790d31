/* gltf_lights.c - KHR_lights_punctual for the glTF reader: the document's
 * lights checked and read once (sr__gltf_read_lights), then placed by each
 * node that names one as walk_nodes meets it (sr__gltf_place_light), in
 * world space, into sr_scene.lights.  Called by gltf.c on the reading
 * thread; internal to src/io. */
#include "io/gltf.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define EXT "KHR_lights_punctual"
#define PI_F 3.14159265358979f

/* One entry of /extensions/KHR_lights_punctual/lights, as the file says
 * it with glTF's defaults filled in. */
typedef struct gltf_light {
    sr_light_type type;
    float color[3];
    float intensity;
    float range;                 /* 0: infinite */
    float inner, outer;          /* spot cone, radians */
} gltf_light;

static sr_result read_light(gltf_doc *d, const json_t *obj, const char *ptr, gltf_light *out)
{
    sr_result r;
    if (!json_is_object(obj)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: not an object", ptr);
    }
    json_t *type = json_object_get(obj, "type");
    if (!json_is_string(type)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/type: missing or not a string", ptr);
    }
    const char *t = json_string_value(type);
    out->type = strcmp(t, "directional") == 0 ? SR_LIGHT_DIRECTIONAL
              : strcmp(t, "point") == 0       ? SR_LIGHT_POINT
              : strcmp(t, "spot") == 0        ? SR_LIGHT_SPOT : SR_LIGHT_OFF;
    if (out->type == SR_LIGHT_OFF) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/type: \"%.32s\" is not directional, point or spot", ptr, t);
    }
    out->color[0] = out->color[1] = out->color[2] = 1.0f;
    out->intensity = 1.0f;
    out->range = 0.0f;
    out->inner = 0.0f;
    out->outer = PI_F / 4;
    float range = -1.0f;
    if ((r = sr__gltf_numbers(d, obj, ptr, "color", 3, out->color)) != SR_OK ||
        (r = sr__gltf_number(d, obj, ptr, "intensity", &out->intensity)) != SR_OK ||
        (r = sr__gltf_number(d, obj, ptr, "range", &range)) != SR_OK) {
        return r;
    }
    for (int c = 0; c < 3; c++) {
        if (out->color[c] < 0) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/color/%d: %g is negative", ptr, c,
                                 out->color[c]);
        }
    }
    if (out->intensity < 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/intensity: %g is negative", ptr,
                             out->intensity);
    }
    if (json_object_get(obj, "range")) {
        if (!(range > 0)) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/range: %g is not > 0", ptr, range);
        }
        /* Directional lights have no range: the extension says to ignore it. */
        out->range = out->type == SR_LIGHT_DIRECTIONAL ? 0.0f : range;
    }
    json_t *spot;
    if ((r = sr__gltf_object(d, obj, ptr, "spot", &spot)) != SR_OK) {
        return r;
    }
    if (out->type != SR_LIGHT_SPOT) {
        return SR_OK;
    }
    char sub[GLTF_PTR];
    sr__json_pointer(sub, sizeof sub, "%s/spot", ptr);
    if (!spot) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: missing", sub);
    }
    if ((r = sr__gltf_number(d, spot, sub, "innerConeAngle", &out->inner)) != SR_OK ||
        (r = sr__gltf_number(d, spot, sub, "outerConeAngle", &out->outer)) != SR_OK) {
        return r;
    }
    if (!(out->outer > 0 && out->outer <= PI_F / 2)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/outerConeAngle: %g is outside (0, pi/2]", sub,
                             out->outer);
    }
    if (!(out->inner >= 0 && out->inner < out->outer)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/innerConeAngle: %g is outside [0, outerConeAngle %g)", sub,
                             out->inner, out->outer);
    }
    return SR_OK;
}

sr_result sr__gltf_read_lights(gltf_doc *d)
{
    json_t *ext, *lights;
    size_t n;
    sr_result r;
    json_t *exts = json_object_get(d->root, "extensions");
    if (!json_is_object(exts)) {
        return SR_OK;
    }
    const char *ptr = "/extensions/" EXT;
    if ((r = sr__gltf_object(d, exts, "/extensions", EXT, &ext)) != SR_OK || !ext) {
        return r;
    }
    if ((r = sr__gltf_array(d, ext, ptr, "lights", &lights, &n)) != SR_OK) {
        return r;
    }
    if (!lights) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/lights: missing", ptr);
    }
    /* Each light costs the JSON text of an object: the count is bounded
     * by the document's size, well inside a size_t product. */
    d->lights = calloc(n ? n : 1, sizeof *d->lights);
    if (!d->lights) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s/lights: out of memory", ptr);
    }
    d->light_count = n;
    for (size_t i = 0; i < n; i++) {
        char lptr[GLTF_PTR];
        sr__json_pointer(lptr, sizeof lptr, "%s/lights/%zu", ptr, i);
        if ((r = read_light(d, json_array_get(lights, i), lptr, &d->lights[i])) != SR_OK) {
            return r;
        }
    }
    return SR_OK;
}

sr_result sr__gltf_place_light(gltf_doc *d, const json_t *node, const char *ptr, long node_index,
                               const float world[16])
{
    json_t *ext = sr__gltf_extension(node, EXT);
    long index = -1;
    sr_result r;
    char eptr[GLTF_PTR];
    sr__json_pointer(eptr, sizeof eptr, "%s/extensions/" EXT, ptr);
    if (!ext) {
        if (json_object_get(json_object_get(node, "extensions"), EXT)) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: not an object", eptr);
        }
        return SR_OK;
    }
    if ((r = sr__gltf_index(d, ext, eptr, "light", d->light_count, true, &index)) != SR_OK) {
        return r;
    }
    const gltf_light *g = &d->lights[index];
    sr_scene_light placed = { .light_index = (int)index, .node = (int)node_index,
                              .type = g->type };
    bool dark = g->intensity == 0 ||
                (g->color[0] == 0 && g->color[1] == 0 && g->color[2] == 0);
    placed.light = (sr_light){
        .type = dark ? SR_LIGHT_OFF : g->type,
        .color = { g->color[0], g->color[1], g->color[2] },
        .intensity = g->intensity,
        .range = g->range,
    };
    if (g->type == SR_LIGHT_SPOT) {
        placed.light.inner_cone = g->inner;
        placed.light.outer_cone = g->outer;
    }
    if (!sr__gltf_aim_light(&placed, world)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s: the node's matrix collapses the light's direction (its -Z)",
                             eptr);
    }
    sr_scene_light *l = sr__scene_grow(d->scene, (void **)&d->scene->lights,
                                       &d->scene->light_count, sizeof *l, 1);
    if (!l) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", eptr);
    }
    *l = placed;
    return SR_OK;
}

bool sr__gltf_aim_light(sr_scene_light *l, const float world[16])
{
    /* The light sits at the node's origin and shines down its -Z, both
     * through the whole world matrix (a scaled node moves its light but
     * the direction is normalized). */
    float pos[3], dir[3];
    for (int k = 0; k < 3; k++) {
        pos[k] = world[12 + k];
        dir[k] = -world[8 + k];
    }
    double len = sqrt((double)dir[0] * dir[0] + (double)dir[1] * dir[1] +
                      (double)dir[2] * dir[2]);
    if (l->type != SR_LIGHT_POINT && !(len > 0 && isfinite(len))) {
        return false;
    }
    for (int k = 0; k < 3 && len > 0; k++) {
        dir[k] = (float)(dir[k] / len);
    }
    memcpy(l->world, world, sizeof l->world);
    l->light.vector = l->type == SR_LIGHT_DIRECTIONAL ? (sr_vec3){ dir[0], dir[1], dir[2] }
                                                      : (sr_vec3){ pos[0], pos[1], pos[2] };
    if (l->type == SR_LIGHT_SPOT) {
        l->light.direction = (sr_vec3){ dir[0], dir[1], dir[2] };
    }
    return true;
}

void sr__gltf_lights_done(gltf_doc *d)
{
    /* The PBR program takes SR_MAX_LIGHTS: say which lit ones a program
     * that takes the first of them (softrast render) leaves out. */
    const sr_scene *s = d->scene;
    char list[300] = "";
    size_t lit = 0, at = 0;
    for (size_t i = 0; i < s->light_count; i++) {
        if (s->lights[i].light.type == SR_LIGHT_OFF || ++lit <= SR_MAX_LIGHTS) {
            continue;
        }
        if (at + 40 < sizeof list) {
            at += (size_t)snprintf(list + at, sizeof list - at, "%s/nodes/%d (light %d)",
                                   at ? ", " : "", s->lights[i].node, s->lights[i].light_index);
        } else if (at + 5 < sizeof list && strcmp(list + at - 3, "...") != 0) {
            at += (size_t)snprintf(list + at, sizeof list - at, ", ...");
        }
    }
    if (lit > SR_MAX_LIGHTS) {
        sr__gltf_warn(d,
                      "/extensions/" EXT ": %zu lights are placed and a program takes %d, "
                      "the first in node order: not drawn: %s",
                      lit, SR_MAX_LIGHTS, list);
    }
}
