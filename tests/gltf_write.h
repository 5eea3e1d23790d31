/* gltf_write.h - glTF 2.0 files for the tests of the Assimp reader and of
 * the CLI: base64, and a model of textured quads, one mesh primitive
 * each.  Internal to tests. */
#ifndef SR_GLTF_WRITE_H
#define SR_GLTF_WRITE_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Standard base64 of n bytes into dst (room for 4 ceil(n / 3) + 1). */
static inline void gltf_base64(const uint8_t *src, size_t n, char *dst)
{
    static const char abc[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    size_t o = 0;
    for (size_t i = 0; i < n; i += 3) {
        uint32_t v = (uint32_t)src[i] << 16 | (i + 1 < n ? (uint32_t)src[i + 1] << 8 : 0) |
                     (i + 2 < n ? src[i + 2] : 0);
        dst[o++] = abc[v >> 18 & 63];
        dst[o++] = abc[v >> 12 & 63];
        dst[o++] = i + 1 < n ? abc[v >> 6 & 63] : '=';
        dst[o++] = i + 2 < n ? abc[v & 63] : '=';
    }
    dst[o] = 0;
}

/* One quad of gltf_quads: the rectangle [x0, x1] x [y0, y1] at z = 0,
 * texture coordinates 0..1 across it, and the material it takes. */
/* Copies count elements of `size` bytes from src, in the host's byte order,
 * to dst in little-endian order: the byte order of glTF buffers, GLB
 * chunks and binary STL, whatever machine runs the tests. */
static inline void le_copy(void *dst, const void *src, size_t count, size_t size)
{
    const uint16_t one = 1;
    uint8_t little;
    memcpy(&little, &one, 1);
    const uint8_t *s = src;
    uint8_t *d = dst;
    for (size_t i = 0; i < count; i++, s += size, d += size) {
        for (size_t k = 0; k < size; k++) {
            d[k] = little ? s[k] : s[size - 1 - k];
        }
    }
}

/* Appends count little-endian items of `size` bytes at buf + *n, padded
 * to 4 bytes (glTF aligns accessors so); returns their offset. */
static inline size_t gltf_put(uint8_t *buf, size_t *n, const void *src, size_t count,
                              size_t size)
{
    size_t at = *n;
    le_copy(buf + at, src, count, size);
    *n = (at + count * size + 3) & ~(size_t)3;
    return at;
}

typedef struct gltf_quad {
    float x0, y0, x1, y1;
    int material;
} gltf_quad;

/* A .gltf of n quads, primitive q of its one mesh drawing quad q, with
 * the geometry in a data URI; `tail` is the rest of the top-level object
 * (",\"materials\":[...]" and any images and textures), spliced in as is.
 * A malloc'd string, or NULL when out of memory. */
static inline char *gltf_quads(const gltf_quad *quads, size_t n, const char *tail)
{
    static const uint16_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    size_t bin_len = 80 * n + 12;
    uint8_t *bin = malloc(bin_len);
    char *b64 = malloc(4 * (bin_len / 3 + 1) + 1);
    size_t cap = 4 * (bin_len / 3 + 1) + 600 * n + strlen(tail) + 1000;
    char *json = malloc(cap);
    if (!bin || !b64 || !json) {
        free(bin);
        free(b64);
        free(json);
        return NULL;
    }
    for (size_t q = 0; q < n; q++) {
        const gltf_quad *g = &quads[q];
        float pos[12] = { g->x0, g->y0, 0, g->x1, g->y0, 0, g->x1, g->y1, 0, g->x0, g->y1, 0 };
        float uv[8] = { 0, 1, 1, 1, 1, 0, 0, 0 };
        le_copy(bin + 80 * q, pos, 12, 4);
        le_copy(bin + 80 * q + 48, uv, 8, 4);
    }
    le_copy(bin + 80 * n, idx, 6, 2);
    gltf_base64(bin, bin_len, b64);
    size_t at = (size_t)snprintf(json, cap,
                                 "{\"asset\":{\"version\":\"2.0\"},"
                                 "\"buffers\":[{\"byteLength\":%zu,"
                                 "\"uri\":\"data:application/octet-stream;base64,%s\"}],"
                                 "\"bufferViews\":[",
                                 bin_len, b64);
    for (size_t q = 0; q < n; q++) {
        at += (size_t)snprintf(json + at, cap - at,
                               "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":48},"
                               "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":32},",
                               80 * q, 80 * q + 48);
    }
    at += (size_t)snprintf(json + at, cap - at,
                           "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":12}],\"accessors\":[",
                           80 * n);
    for (size_t q = 0; q < n; q++) {
        const gltf_quad *g = &quads[q];
        at += (size_t)snprintf(json + at, cap - at,
                               "{\"bufferView\":%zu,\"componentType\":5126,\"count\":4,"
                               "\"type\":\"VEC3\",\"min\":[%g,%g,0],\"max\":[%g,%g,0]},"
                               "{\"bufferView\":%zu,\"componentType\":5126,\"count\":4,"
                               "\"type\":\"VEC2\"},",
                               2 * q, g->x0, g->y0, g->x1, g->y1, 2 * q + 1);
    }
    at += (size_t)snprintf(json + at, cap - at,
                           "{\"bufferView\":%zu,\"componentType\":5123,\"count\":6,"
                           "\"type\":\"SCALAR\"}],\"meshes\":[{\"primitives\":[",
                           2 * n);
    for (size_t q = 0; q < n; q++) {
        at += (size_t)snprintf(json + at, cap - at,
                               "%s{\"attributes\":{\"POSITION\":%zu,\"TEXCOORD_0\":%zu},"
                               "\"indices\":%zu,\"material\":%d}",
                               q ? "," : "", 2 * q, 2 * q + 1, 2 * n, quads[q].material);
    }
    snprintf(json + at, cap - at,
             "]}],\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0%s}", tail);
    free(bin);
    free(b64);
    return json;
}

/* The model of the parts tests (test_mesh, test_cli): five quads whose
 * materials take, in order, the embedded image `png` (n bytes, a data
 * URI), no texture but a green base color, the file blue.png, blue.png
 * again through a material of its own, and missing.png.  Quads 0-3 lie
 * in a row at y = -0.5..0.5 (x = -2..-1, -0.5..0.5, 1..1.5, 1.5..2), quad
 * 4 above the last two (x = 1..2, y = 1..2), as the OBJ parts test's
 * four squares.  A malloc'd string, or NULL when out of memory. */
static inline char *gltf_parts_model(const uint8_t *png, size_t n)
{
    static const gltf_quad quads[5] = {
        { -2.0f, -0.5f, -1.0f, 0.5f, 0 }, { -0.5f, -0.5f, 0.5f, 0.5f, 1 },
        { 1.0f, -0.5f, 1.5f, 0.5f, 2 },   { 1.5f, -0.5f, 2.0f, 0.5f, 3 },
        { 1.0f, 1.0f, 2.0f, 2.0f, 4 },
    };
    char *b64 = malloc(4 * (n / 3 + 1) + 1);
    char *tail = malloc(4 * (n / 3 + 1) + 1000);
    char *json = NULL;
    if (b64 && tail) {
        gltf_base64(png, n, b64);
        sprintf(tail,
                ",\"images\":[{\"uri\":\"data:image/png;base64,%s\"},{\"uri\":\"blue.png\"},"
                "{\"uri\":\"missing.png\"}],"
                "\"textures\":[{\"source\":0},{\"source\":1},{\"source\":1},{\"source\":2}],"
                "\"materials\":["
                "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}},"
                "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,1,0,1]}},"
                "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":1}}},"
                "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":2}}},"
                "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":3}}}]",
                b64);
        json = gltf_quads(quads, 5, tail);
    }
    free(b64);
    free(tail);
    return json;
}

#endif
