/* draco_decode.h - the C side of draco_decode.cc, the one C++ file of the
 * library: a Draco stream (glTF's KHR_draco_mesh_compression) decoded by
 * libdraco into plain arrays, a triangle list and each attribute's values
 * written as a glTF accessor stores them.  Nothing C++ crosses this header
 * (no exception escapes it).  Internal to src/io; any thread, one mesh per
 * caller. */
#ifndef SR_IO_DRACO_DECODE_H
#define SR_IO_DRACO_DECODE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sr_draco_mesh sr_draco_mesh;

typedef enum sr_draco_status {
    SR_DRACO_OK = 0,
    SR_DRACO_CORRUPT,        /* the stream does not decode (why: libdraco's reason) */
    SR_DRACO_NOT_A_MESH,     /* a point cloud, not triangles */
    SR_DRACO_NO_MEMORY,
    SR_DRACO_NO_ATTRIBUTE,   /* no attribute of that unique id */
    SR_DRACO_MISMATCH,       /* the attribute is not what the accessor says (why) */
} sr_draco_status;

/* The stream data[0..size) decoded into *out (sr__draco_free it); on
 * failure *out is NULL and why (cap bytes) says what is wrong. */
sr_draco_status sr__draco_decode(const uint8_t *data, size_t size, sr_draco_mesh **out,
                                 char *why, size_t cap);
void sr__draco_free(sr_draco_mesh *m);

/* Points (the vertices every attribute has) and triangles. */
size_t sr__draco_points(const sr_draco_mesh *m);
size_t sr__draco_faces(const sr_draco_mesh *m);

/* The triangles' corners, 3 per face, into out (each below the points). */
void sr__draco_indices(const sr_draco_mesh *m, uint32_t *out);

/* The attribute of unique id `id`, one element of `components` values per
 * point, written into out (points * components components) as a glTF
 * accessor of componentType `component_type` holds them: little-endian,
 * tightly packed.  FLOAT takes any of Draco's types (its normalized
 * integers mapped as glTF maps them); an integer type takes only the same
 * Draco type.  why says what differs on SR_DRACO_MISMATCH. */
sr_draco_status sr__draco_attribute(const sr_draco_mesh *m, uint32_t id, int component_type,
                                    int components, uint8_t *out, char *why, size_t cap);

#ifdef __cplusplus
}
#endif

#endif
