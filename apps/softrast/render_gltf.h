/* render_gltf.h - glTF files for the render job (render_gltf.c). */
#ifndef SR_RENDER_GLTF_H
#define SR_RENDER_GLTF_H

#include "cli.h"
#include "scene.h"

#include <stdbool.h>

/* Whether path names a glTF file (.gltf or .glb), which sr_load_scene reads. */
bool render_gltf_is(const char *path);
/* Reads the file into s (one object, a part per primitive, s->gltf kept
 * for the materials and cameras) on ctx; with flat_normals, primitives
 * without normals get flat ones (glTF's rule, for the default --normals);
 * `variant` (--variant, or NULL) picks the material variant; `verbose`
 * lists the file's variants; animation (--animation, NULL: the rest pose)
 * names the file's animation to pose it by, a number or a name, at `time`
 * seconds.  Returns an exit status after one line, or -1. */
int render_gltf_load(const char *path, bool flat_normals, const char *variant, bool verbose,
                     const char *animation, float time, sr_context *ctx, cli_inputs *inputs,
                     scene *s);
/* The second half of render_gltf_load: s made from sc, a scene of path
 * read (and posed) already, which s takes (destroyed on failure).  For
 * a model posed again (sr_scene_pose) without reading it again. */
int render_gltf_build(const char *path, bool flat_normals, const char *variant, bool verbose,
                      sr_scene *sc, sr_context *ctx, scene *s);
/* ob's base_uv for the classic models, which have one set of texture
 * coordinates and no per-slot transform: each part's coordinates as the
 * physically based program samples its base color texture (its set, 0 or
 * 1, through its KHR_texture_transform), when some part's differ from
 * the texcoords; else NULL.  SR_OUT_OF_MEMORY, or the slot's
 * error (the context's message). */
sr_result render_gltf_base_uv(sr_context *ctx, const scene *s, scene_object *ob);
/* The classic models' Blinn-Phong material for glTF material m
 * (docs/pbr.md, "glTF files in softrast render"); with vertex_colors the
 * primitive's COLOR_0 is its diffuse, as an OBJ's or a PLY's is. */
sr_material render_gltf_classic(const sr_pbr_material *m, bool vertex_colors);
/* The view and projection of the file's camera `index` for `aspect`, or
 * why there is none (a message for the user). */
const char *render_gltf_camera(const scene *s, int index, float aspect, sr_mat4 *view,
                               sr_mat4 *projection);

#endif
