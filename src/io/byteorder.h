/* Little-endian loads for the binary formats (glTF buffers and GLB
 * chunks, binary STL): assembled from bytes, so they read the file the
 * same way on a big-endian host. */
#ifndef SR_IO_BYTEORDER_H
#define SR_IO_BYTEORDER_H

#include <stdint.h>
#include <string.h>

static inline uint16_t sr__le16(const uint8_t *p)
{
    return (uint16_t)(p[0] | p[1] << 8);
}

static inline uint32_t sr__le32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static inline float sr__le_float(const uint8_t *p)
{
    uint32_t bits = sr__le32(p);
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

#endif
