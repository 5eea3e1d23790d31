/* render_bump.h - the bump and normal maps of a model's materials under
 * `softrast render`'s physically based look (render_bump.c). */
#ifndef SR_RENDER_BUMP_H
#define SR_RENDER_BUMP_H

#include "cli.h"
#include "render_options.h"
#include "scene.h"

/* Each part's normal map onto ctx (s->objects[0].part_normal_maps), from
 * the bump map its material names (sr_mesh_material.bump_path): a height
 * map turned into a tangent-space normal map, or a normal map read as it
 * is (`norm`, or a map_Bump image whose texels are a normal map's).  A
 * file that cannot be read is a warning.  Returns an exit status, or -1. */
int render_bump_load(const render_opts *o, sr_context *ctx, cli_inputs *inputs, scene *s);
/* The normal maps of render_bump_load, destroyed on ctx. */
void render_bump_free(sr_context *ctx, scene *s);

/* A tangent-space normal map (RGBA8, +x right, +y up the image, glTF's
 * convention) from the height map `height` (its RGB mean, 0..1) of w x h
 * texels, wrapped at the edges as a repeating texture is: central
 * differences, a height change of `scale` between neighbouring texels
 * tilting the normal by 45 degrees.  Written over `height`. */
void render_bump_to_normals(uint8_t *height, int w, int h, float scale);
/* Whether an image's texels look like a tangent-space normal map's rather
 * than a height map's: nearly all of them unit vectors pointing out of the
 * surface, most of them not gray. */
bool render_bump_is_normal_map(const uint8_t *rgba, int w, int h);

#endif
