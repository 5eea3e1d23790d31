/* render_lights.h - the lights of pbr's program for a render job
 * (render_lights.c): the model's own, the default rig, or both. */
#ifndef SR_RENDER_LIGHTS_H
#define SR_RENDER_LIGHTS_H

#include "render_options.h"
#include "scene.h"

#include <stdbool.h>

/* The lit lights of the glTF file s was read from (KHR_lights_punctual),
 * at most SR_MAX_LIGHTS, the first in node order; 0 for other models. */
int render_lights_in_file(const scene *s);

/* Sets lighting's lights, sky and ground for pbr's program: the classic
 * lights `rig` (the key, fill and rim rig, or --light's) as
 * sr_pbr_default_lighting makes them radiance, only the key of the rig
 * when an image-based light (image_light) is the fill; the file's lights
 * as they are (candela and lux are radiance), moved with the model (its
 * --up and --turn); or both, the file's first.  lights[0] is the one
 * whose shadow the map shows when it is directional: with the file's
 * lights, the strongest of their directional lights. */
void render_lights_pbr(const render_opts *o, const scene *s, const sr_light rig[SR_MAX_LIGHTS],
                       bool image_light, sr_pbr_desc *lighting);

#endif
