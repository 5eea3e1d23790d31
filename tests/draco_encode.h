/* draco_encode.h - test_gltf_draco's writer: a triangle mesh (or its
 * points alone) encoded with libdraco's encoder (draco_encode.cc, C++
 * behind this C header), standing in for the exporters that write
 * KHR_draco_mesh_compression.  Internal to tests. */
#ifndef SR_TEST_DRACO_ENCODE_H
#define SR_TEST_DRACO_ENCODE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct draco_encoded {
    uint8_t *data;              /* the stream (free it), NULL on failure */
    size_t size;
    uint32_t id_pos, id_nrm, id_uv;  /* the attributes' unique ids */
    size_t points, faces;       /* what the stream decodes to */
} draco_encoded;

/* n points of positions, normals and coordinates (NULL: none), `faces`
 * triangles of idx; `bits` quantize positions (normals 10 bits,
 * coordinates 12).  point_cloud: the points alone, without triangles;
 * sequential: sequential connectivity, which keeps the faces and their
 * corners in order (a strip's), instead of edgebreaker. */
draco_encoded draco_encode(const float *pos, const float *nrm, const float *uv, size_t n,
                           const uint32_t *idx, size_t faces, int bits, int point_cloud,
                           int sequential);

#ifdef __cplusplus
}
#endif

#endif
