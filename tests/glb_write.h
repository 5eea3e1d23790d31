/* glb_write.h - GLB files in memory for the glTF tests: a JSON chunk and
 * an optional BIN chunk, framed and padded as the format asks (or, for
 * the framing tests, as they ask).  Internal to tests. */
#ifndef SR_GLB_WRITE_H
#define SR_GLB_WRITE_H

#include "gltf_write.h"
#include "wbuf.h"

/* A GLB of json, its chunk declaring jn bytes and padded with pad spaces,
 * and bin (n bytes, none: no BIN chunk) padded as the format asks. */
static inline wbuf glb_framed(const char *json, uint32_t jn, size_t pad, const void *bin,
                              size_t n)
{
    wbuf b = {0};
    size_t bn = (n + 3) & ~(size_t)3;
    uint32_t head[3] = { 0x46546C67u, 2,
                         (uint32_t)(12 + 8 + strlen(json) + pad + (n ? 8 + bn : 0)) };
    uint32_t jc[2] = { jn, 0x4E4F534Au }, bc[2] = { (uint32_t)bn, 0x004E4942u };
    uint8_t le[12];
    le_copy(le, head, 3, 4);
    wb_put(&b, le, 12);
    le_copy(le, jc, 2, 4);
    wb_put(&b, le, 8);
    wb_put(&b, json, strlen(json));
    wb_put(&b, "   ", pad);
    if (n) {
        le_copy(le, bc, 2, 4);
        wb_put(&b, le, 8);
        wb_put(&b, bin, n);
        wb_put(&b, "\0\0\0", bn - n);
    }
    return b;
}

/* A GLB of json and bin, padded as the format asks. */
static inline wbuf glb(const char *json, const void *bin, size_t n)
{
    size_t jn = (strlen(json) + 3) & ~(size_t)3;
    return glb_framed(json, (uint32_t)jn, jn - strlen(json), bin, n);
}

#endif
