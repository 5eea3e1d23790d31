/* readers.h - the per-format model readers behind sr_load_mesh (src/io).
 * Each takes a file path, fills *out (zeroed on failure, nothing leaked)
 * and reports problems through sr_io_error in the forms of io_util.h.
 * The readers grow their arrays with realloc, so the meshes they fill are
 * malloc'd; load.c copies them onto the caller's context.
 * Shared by load.c and the readers; not part of the public API. */
#ifndef SR_IO_READERS_H
#define SR_IO_READERS_H

#include "softrast_io.h"

/* obj.c: also reads the MTL files named by mtllib, relative to the OBJ's
 * directory (a missing MTL is ignored), each reported to desc->file_read
 * (desc may be NULL). */
sr_result sr__load_obj(const char *path, const sr_load_desc *desc, sr_mesh *out,
                       sr_io_error *err);
/* ply.c */
sr_result sr__load_ply(const char *path, sr_mesh *out, sr_io_error *err);
/* stl.c */
sr_result sr__load_stl(const char *path, sr_mesh *out, sr_io_error *err);
/* assimp.c: every other format Assimp reads; SR_UNSUPPORTED with an
 * install hint when the build has no Assimp. */
sr_result sr__load_assimp(const char *path, sr_mesh *out, sr_io_error *err);
/* load_gltf.c: the default scene of sr_load_scene's glTF reader as one
 * mesh in world space (needs jansson: see sr_io_have_gltf). */
sr_result sr__load_gltf_mesh(sr_context *ctx, const char *path, const sr_load_desc *desc,
                             sr_mesh *out, sr_io_error *err);
/* true when the build has Assimp's headers and the library opens. */
bool sr__assimp_available(void);

/* The readers on memory (behind sr_parse_obj, sr_parse_ply, sr_parse_stl). */
sr_result sr__parse_obj(const char *name, const char *data, size_t size, sr_mesh *out,
                        sr_io_error *err);
sr_result sr__parse_ply(const char *name, const uint8_t *data, size_t size, sr_mesh *out,
                        sr_io_error *err);
sr_result sr__parse_stl(const char *name, const uint8_t *data, size_t size, sr_mesh *out,
                        sr_io_error *err);

/* Frees a mesh whose arrays a reader malloc'd, and zeroes it. */
void sr__free_malloc_mesh(sr_mesh *mesh);
/* A malloc'd mesh of verts vertices and tris triangles with the arrays
 * asked for (uninitialized); false, *m zeroed, when out of memory. */
bool sr__alloc_malloc_mesh(sr_mesh *m, size_t verts, size_t tris, bool normals, bool colors,
                           bool texcoords);

#endif /* SR_IO_READERS_H */
