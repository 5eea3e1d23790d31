/* scene.h - the memory of an sr_scene (scene_store.c) and the readers
 * behind sr_load_scene (scene.c, gltf.c).  Internal to src/io. */
#ifndef SR_IO_SCENE_H
#define SR_IO_SCENE_H

#include "softrast_io.h"

/* An empty scene whose blocks are freed by sr_destroy_scene, or NULL. */
sr_scene *sr__scene_new(void);
/* A zeroed block the scene owns, or NULL when out of memory. */
void *sr__scene_alloc(sr_scene *scene, size_t size);
/* Hands a malloc'd block to the scene (freed with it; on failure, now). */
bool sr__scene_keep(sr_scene *scene, void *block);
/* The record sr_scene_pose poses the scene from (gltf_pose.c), freed
 * with the scene by `release`; NULL when the scene has none. */
bool sr__scene_set_posing(sr_scene *scene, void *posing, void (*release)(void *));
void *sr__scene_posing(const sr_scene *scene);
/* gltf_pose.c: the scene posed again from its record (sr_scene_pose
 * checked the arguments); the file's name, for messages. */
sr_result sr__gltf_pose(void *posing, sr_scene *scene, bool animated, int animation, float time,
                        sr_io_error *err);
const char *sr__gltf_posing_name(const void *posing);
/* Adds a texture to scene->textures, destroyed with the scene (on
 * failure, now). */
bool sr__scene_add_texture(sr_context *ctx, sr_scene *scene, sr_texture *tex);
/* Appends n zeroed entries to one of the scene's growing arrays (items of
 * `size` bytes, *count of them); the first new one, or NULL. */
void *sr__scene_grow(sr_scene *scene, void **items, size_t *count, size_t size, size_t n);
/* For sr_load_mesh (sr__parse_gltf's for_mesh), the encoded base color
 * image of material `material`, bytes the scene owns (one of its blocks,
 * the same pointer for every material showing one image):
 * sr__scene_add_source records it (false when out of memory),
 * sr__scene_source finds it (NULL: the material shows none). */
bool sr__scene_add_source(sr_scene *scene, size_t material, const uint8_t *bytes, size_t size);
const uint8_t *sr__scene_source(const sr_scene *scene, size_t material, size_t *size);
/* bounds_min/max over every primitive's world positions. */
void sr__scene_bounds(sr_scene *scene);
/* The column-major product a * b. */
void sr__mat4_mul(const float *a, const float *b, float *out);

/* gltf.c: a glTF document (JSON or GLB) into a new scene; relative URIs
 * are read from `dir` ("" for the current directory).  for_mesh: the
 * scene sr_load_mesh flattens, which shows base color images alone: no
 * texture is made, the base color images are read, checked by decoding
 * and kept encoded (sr__scene_add_source), the other slots' images are
 * not read at all (their slots stay empty). */
sr_result sr__parse_gltf(sr_context *ctx, const char *name, const char *dir, const uint8_t *data,
                         size_t size, const sr_load_desc *desc, bool for_mesh, sr_scene **out,
                         sr_io_error *err);
/* scene.c: the glTF file at path as sr_load_scene reads it, or as
 * sr_load_mesh needs it (for_mesh). */
sr_result sr__load_gltf_scene(sr_context *ctx, const char *path, const sr_load_desc *desc,
                              bool for_mesh, sr_scene **out, sr_io_error *err);

#endif
