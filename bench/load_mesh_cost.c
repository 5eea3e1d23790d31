/* load_mesh_cost.c - softrast-load-mesh-cost [ROUNDS [SIZE]]: what loading
 * a textured glTF costs.  Writes a binary glTF (a quad whose material has
 * the five core maps - base color, metallic-roughness, normal, occlusion,
 * emissive - each a SIZE x SIZE PNG, 2048 by default, of a fixed
 * pattern) to a temporary file, then reads it ROUNDS times (default 9)
 * with sr_load_mesh, which hands on the base color image alone, and with
 * sr_load_scene, which makes every texture; prints the median CPU time of
 * each (docs/gltf.md quotes the figures). */
#include "softrast_io.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define MAPS 5

typedef struct bytes {
    uint8_t *p;
    size_t n, cap;
} bytes;

static bool put(void *user, const void *data, size_t size)
{
    bytes *b = user;
    if (b->n + size > b->cap) {
        size_t cap = b->cap ? 2 * b->cap : 1 << 16;
        while (cap < b->n + size) {
            cap *= 2;
        }
        uint8_t *p = realloc(b->p, cap);
        if (!p) {
            return false;
        }
        b->p = p;
        b->cap = cap;
    }
    memcpy(b->p + b->n, data, size);
    b->n += size;
    return true;
}

static void put_u32(bytes *b, uint32_t v)
{
    uint8_t le[4] = { (uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16), (uint8_t)(v >> 24) };
    put(b, le, 4);
}

/* Map k: gradients with a little hashed grain, so that it compresses as
 * a photographed texture does rather than as a flat color. */
static bool encode_map(int k, int size, bytes *png)
{
    uint8_t *rgba = malloc((size_t)size * size * 4);
    if (!rgba) {
        return false;
    }
    for (int y = 0; y < size; y++) {
        for (int x = 0; x < size; x++) {
            uint32_t h = (uint32_t)x * 0x8da6b343u ^ (uint32_t)y * 0xd8163841u ^ (uint32_t)k;
            h ^= h >> 13;
            h *= 0x5bd1e995u;
            uint8_t *p = rgba + 4 * ((size_t)y * size + x);
            p[0] = (uint8_t)(x * 255 / size + (h & 15));
            p[1] = (uint8_t)(y * 255 / size + (h >> 8 & 15));
            p[2] = (uint8_t)(40 * k + (h >> 16 & 31));
            p[3] = 255;
        }
    }
    sr_io_error err;
    sr_result r = sr_encode_png(put, png, size, size, rgba, (size_t)size * 4, NULL, &err);
    free(rgba);
    return r == SR_OK;
}

/* The GLB: BIN = the quad's positions, uvs and indices, then the maps. */
static bool write_glb(const char *path, int size)
{
    static const float pos[12] = { -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0 };
    static const float uv[8] = { 0, 1, 1, 1, 1, 0, 0, 0 };
    static const uint16_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    bytes bin = { 0 };
    put(&bin, pos, sizeof pos);   /* little-endian hosts: the bench's */
    put(&bin, uv, sizeof uv);
    put(&bin, idx, sizeof idx);
    size_t offset[MAPS], length[MAPS];
    for (int k = 0; k < MAPS; k++) {
        while (bin.n % 4) {
            put(&bin, "", 1);
        }
        offset[k] = bin.n;
        if (!encode_map(k, size, &bin)) {
            free(bin.p);
            return false;
        }
        length[k] = bin.n - offset[k];
    }
    while (bin.n % 4) {
        put(&bin, "", 1);
    }
    char json[4096];
    int n = snprintf(json, sizeof json,
        "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},"
        "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":32},"
        "{\"buffer\":0,\"byteOffset\":80,\"byteLength\":12}",
        bin.n);
    for (int k = 0; k < MAPS; k++) {
        n += snprintf(json + n, sizeof json - (size_t)n,
                      ",{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}", offset[k],
                      length[k]);
    }
    n += snprintf(json + n, sizeof json - (size_t)n,
        "],\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,"
        "\"type\":\"VEC3\",\"min\":[-1,-1,0],\"max\":[1,1,0]},"
        "{\"bufferView\":1,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\"},"
        "{\"bufferView\":2,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}],"
        "\"images\":[");
    for (int k = 0; k < MAPS; k++) {
        n += snprintf(json + n, sizeof json - (size_t)n,
                      "%s{\"bufferView\":%d,\"mimeType\":\"image/png\"}", k ? "," : "", 3 + k);
    }
    n += snprintf(json + n, sizeof json - (size_t)n,
        "],\"textures\":[{\"source\":0},{\"source\":1},{\"source\":2},{\"source\":3},"
        "{\"source\":4}],"
        "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0},"
        "\"metallicRoughnessTexture\":{\"index\":1}},\"normalTexture\":{\"index\":2},"
        "\"occlusionTexture\":{\"index\":3},\"emissiveTexture\":{\"index\":4},"
        "\"emissiveFactor\":[1,1,1]}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":1},"
        "\"indices\":2,\"material\":0}]}],"
        "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0}");
    while (n % 4) {
        json[n++] = ' ';
    }
    FILE *f = fopen(path, "wb");
    bool ok = f != NULL;
    if (ok) {
        bytes head = { 0 };
        put(&head, "glTF", 4);
        put_u32(&head, 2);
        put_u32(&head, (uint32_t)(12 + 8 + (size_t)n + 8 + bin.n));
        put_u32(&head, (uint32_t)n);
        put(&head, "JSON", 4);
        ok = head.p && fwrite(head.p, 1, head.n, f) == head.n &&
             fwrite(json, 1, (size_t)n, f) == (size_t)n;
        free(head.p);
        bytes mid = { 0 };
        put_u32(&mid, (uint32_t)bin.n);
        put(&mid, "BIN", 4);   /* with its NUL: "BIN\0" */
        ok = ok && mid.p && fwrite(mid.p, 1, mid.n, f) == mid.n &&
             fwrite(bin.p, 1, bin.n, f) == bin.n;
        free(mid.p);
        ok = fclose(f) == 0 && ok;
    }
    free(bin.p);
    return ok;
}

static double cpu_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    int rounds = argc > 1 ? atoi(argv[1]) : 9, size = argc > 2 ? atoi(argv[2]) : 2048;
    if (rounds < 1 || rounds > 1000 || size < 1 || size > 8192) {
        fprintf(stderr, "usage: softrast-load-mesh-cost [ROUNDS (1..1000) [SIZE (1..8192)]]\n");
        return 2;
    }
    const char *tmp = getenv("TMPDIR");
    char path[4096];
    snprintf(path, sizeof path, "%s/softrast-load-mesh-cost-%ld.glb", tmp && *tmp ? tmp : "/tmp",
             (long)getpid());
    if (!write_glb(path, size)) {
        fprintf(stderr, "softrast-load-mesh-cost: cannot write %s\n", path);
        return 1;
    }
    sr_context *ctx;
    if (sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) != SR_OK) {
        remove(path);
        return 1;
    }
    double *mesh_ms = calloc((size_t)rounds, sizeof *mesh_ms);
    double *scene_ms = calloc((size_t)rounds, sizeof *scene_ms);
    int status = mesh_ms && scene_ms ? 0 : 1;
    for (int i = 0; i < rounds && status == 0; i++) {
        sr_io_error err;
        sr_mesh m;
        double t0 = cpu_ms();
        sr_result r = sr_load_mesh(ctx, path, NULL, &m, &err);
        double t1 = cpu_ms();
        sr_scene *s = NULL;
        sr_result q = r == SR_OK ? sr_load_scene(ctx, path, NULL, &s, &err) : r;
        double t2 = cpu_ms();
        if (r != SR_OK || q != SR_OK) {
            fprintf(stderr, "softrast-load-mesh-cost: %s\n", err.message);
            status = 1;
        }
        sr_destroy_mesh(ctx, &m);
        sr_destroy_scene(ctx, s);
        mesh_ms[i] = t1 - t0;
        scene_ms[i] = t2 - t1;
    }
    if (status == 0) {
        qsort(mesh_ms, (size_t)rounds, sizeof *mesh_ms, by_value);
        qsort(scene_ms, (size_t)rounds, sizeof *scene_ms, by_value);
        printf("maps=%d size=%d rounds=%d sr_load_mesh_ms=%.1f sr_load_scene_ms=%.1f\n", MAPS,
               size, rounds, mesh_ms[rounds / 2], scene_ms[rounds / 2]);
    }
    free(mesh_ms);
    free(scene_ms);
    sr_destroy_context(ctx);
    remove(path);
    return status;
}
