/* pbr_asset.c - softrast-pbr-asset OUT.glb: writes the physically based
 * benchmark asset (bench), a tiled torus in one binary glTF with its four
 * maps as PNG - base color, metallic-roughness, a tangent-space normal map
 * and occlusion - all generated from one height field with a fixed seed,
 * so every build writes the same bytes.  The build runs it once; the
 * `pbr_textured` scene and the 150 ms CLI figure read what it wrote. */
#include "softrast_io.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI_D 3.14159265358979323846

/* The torus: major radius 1, minor 0.42, lying on y = 0 (its axis +y) and
 * tipped toward +z so the default camera sees into the hole. */
#define MAJOR_SEGMENTS 128
#define MINOR_SEGMENTS 64
#define MAJOR_RADIUS   1.0
#define MINOR_RADIUS   0.42
#define TILT_DEG       20.0

/* The maps: TILES_U x TILES_V tiles around the two circles, grooves
 * between them, a bevel on each tile's rim. */
#define MAP_SIZE       1024
#define SMALL_MAP_SIZE 512
#define TILES_U        24
#define TILES_V        8
#define GROOVE         0.05
#define BEVEL          0.10
#define NORMAL_DEPTH   6.0     /* height units a texel's slope is scaled by */
#define SEED           0x7113u

/* ---- the height field and the tiles' properties ------------------------- */

static uint32_t hash2(uint32_t x, uint32_t y)
{
    uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ SEED;
    h ^= h >> 15;
    h *= 0x2c1b3c6du;
    h ^= h >> 12;
    h *= 0x297a2d39u;
    return h ^ (h >> 15);
}

static double unit(uint32_t h)
{
    return (double)(h >> 8) / 16777216.0;
}

/* Value noise with period `cells` in both directions (the texture wraps). */
static double noise(double u, double v, int cells)
{
    double x = u * cells, y = v * cells;
    int x0 = (int)floor(x), y0 = (int)floor(y);
    double fx = x - x0, fy = y - y0;
    fx = fx * fx * (3 - 2 * fx);
    fy = fy * fy * (3 - 2 * fy);
    double c[4];
    for (int k = 0; k < 4; k++) {
        int xi = ((x0 + (k & 1)) % cells + cells) % cells;
        int yi = ((y0 + (k >> 1)) % cells + cells) % cells;
        c[k] = unit(hash2((uint32_t)xi, (uint32_t)yi + 7919u * (uint32_t)cells));
    }
    return (c[0] * (1 - fx) + c[1] * fx) * (1 - fy) + (c[2] * (1 - fx) + c[3] * fx) * fy;
}

static double smoothstep(double a, double b, double x)
{
    double t = fmin(fmax((x - a) / (b - a), 0.0), 1.0);
    return t * t * (3 - 2 * t);
}

/* At texture position (u, v) (v down the image): which tile, and the
 * distance to its nearest edge in tile units (0 on the edge, 0.5 at the
 * middle).  Rows are offset by half a tile, as bricks are laid. */
static void tile_at(double u, double v, int *tu, int *tv, double *edge)
{
    double y = v * TILES_V;
    int row = (int)floor(y);
    double x = u * TILES_U + (row & 1) * 0.5;
    int col = (int)floor(x);
    double fx = x - col, fy = y - row;
    *tu = ((col % TILES_U) + TILES_U) % TILES_U;
    *tv = ((row % TILES_V) + TILES_V) % TILES_V;
    *edge = fmin(fmin(fx, 1 - fx) * TILES_V / (double)TILES_U * 3.0, fmin(fy, 1 - fy));
}

static double height(double u, double v)
{
    int tu, tv;
    double edge;
    tile_at(u, v, &tu, &tv, &edge);
    double h = smoothstep(GROOVE, GROOVE + BEVEL, edge);
    return h * (0.92 + 0.08 * noise(u, v, 64)) + 0.03 * noise(u, v, 256);
}

/* One tile in five is metal (copper or gold), the rest glazed ceramic. */
static bool tile_metal(int tu, int tv)
{
    return hash2((uint32_t)tu, (uint32_t)tv) % 5 == 0;
}

static void tile_color(int tu, int tv, double c[3])
{
    static const double ceramic[4][3] = { { 0.80, 0.45, 0.30 }, { 0.20, 0.50, 0.55 },
                                          { 0.85, 0.80, 0.70 }, { 0.30, 0.35, 0.60 } };
    static const double metal[2][3] = { { 0.95, 0.64, 0.54 }, { 1.00, 0.78, 0.34 } };
    uint32_t h = hash2((uint32_t)tu + 1000u, (uint32_t)tv);
    const double *p = tile_metal(tu, tv) ? metal[h % 2] : ceramic[h % 4];
    memcpy(c, p, 3 * sizeof(double));
}

static uint8_t byte(double x)
{
    return (uint8_t)lround(fmin(fmax(x, 0.0), 1.0) * 255.0);
}

/* sRGB encoding of a linear value, for the base color map. */
static uint8_t srgb_byte(double x)
{
    x = fmin(fmax(x, 0.0), 1.0);
    return byte(x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1 / 2.4) - 0.055);
}

/* Fills the four maps (RGBA8, row 0 at the top). */
static void make_maps(uint8_t *base, uint8_t *normal, uint8_t *mr, uint8_t *ao)
{
    const int n = MAP_SIZE, s = SMALL_MAP_SIZE;
    for (int y = 0; y < n; y++) {
        for (int x = 0; x < n; x++) {
            double u = (x + 0.5) / n, v = (y + 0.5) / n;
            int tu, tv;
            double edge, c[3];
            tile_at(u, v, &tu, &tv, &edge);
            tile_color(tu, tv, c);
            double in = smoothstep(GROOVE * 0.5, GROOVE + BEVEL * 0.5, edge);
            double grain = 0.85 + 0.15 * noise(u, v, 128);
            uint8_t *b = &base[4 * ((size_t)y * n + x)];
            for (int k = 0; k < 3; k++) {
                b[k] = srgb_byte((c[k] * in + 0.08 * (1 - in)) * grain);
            }
            b[3] = 255;
            /* The slope in texels: +x right, +y up the image (glTF's
             * normal map convention), so dh/d(up) = -dh/d(row). */
            double dx = (height((x + 1.5) / n, v) - height((x - 0.5) / n, v)) / 2;
            double dy = -(height(u, (y + 1.5) / n) - height(u, (y - 0.5) / n)) / 2;
            double nx = -dx * NORMAL_DEPTH, ny = -dy * NORMAL_DEPTH, nz = 1.0;
            double len = sqrt(nx * nx + ny * ny + nz * nz);
            uint8_t *o = &normal[4 * ((size_t)y * n + x)];
            o[0] = byte(0.5 + 0.5 * nx / len);
            o[1] = byte(0.5 + 0.5 * ny / len);
            o[2] = byte(0.5 + 0.5 * nz / len);
            o[3] = 255;
        }
    }
    for (int y = 0; y < s; y++) {
        for (int x = 0; x < s; x++) {
            double u = (x + 0.5) / s, v = (y + 0.5) / s;
            int tu, tv;
            double edge;
            tile_at(u, v, &tu, &tv, &edge);
            double h = height(u, v);
            /* Metallic in B, roughness in G (glTF's channels). */
            bool metal = tile_metal(tu, tv) && edge > GROOVE;
            double rough = metal ? 0.22 + 0.15 * noise(u, v, 32) : 0.45 + 0.2 * noise(u, v, 32);
            if (h < 0.5) {
                rough = 0.9;
            }
            uint8_t *m = &mr[4 * ((size_t)y * s + x)];
            m[0] = 255;
            m[1] = byte(rough);
            m[2] = metal ? 255 : 0;
            m[3] = 255;
            /* Occlusion: the groove's floor sees little of the sky; the
             * average height around a texel says how deep in it lies. */
            double around = 0.0;
            for (int k = 0; k < 8; k++) {
                double a = k * PI_D / 4, r = 2.5 / s;
                around += height(u + r * cos(a), v + r * sin(a));
            }
            double depth = fmax(around / 8 - h, 0.0) + (1 - h) * 0.5;
            uint8_t *q = &ao[4 * ((size_t)y * s + x)];
            q[0] = q[1] = q[2] = byte(1.0 - 1.6 * depth);
            q[3] = 255;
        }
    }
}

/* ---- the torus ---------------------------------------------------------- */

typedef struct vertex {
    float p[3], n[3], t[4], uv[2];
} vertex;

static void tilt(double x, double y, double z, float out[3])
{
    double a = TILT_DEG * PI_D / 180, c = cos(a), s = sin(a);
    out[0] = (float)x;
    out[1] = (float)(c * y - s * z);
    out[2] = (float)(s * y + c * z);
}

/* Vertex (i, j): u = i / MAJOR_SEGMENTS around the axis, v = j /
 * MINOR_SEGMENTS around the tube (glTF's v, down the image). */
static void make_vertex(int i, int j, vertex *o)
{
    double th = 2 * PI_D * i / MAJOR_SEGMENTS, ph = 2 * PI_D * j / MINOR_SEGMENTS;
    double ring = MAJOR_RADIUS + MINOR_RADIUS * cos(ph);
    /* Axis +y: the tube's circle in the plane of the axis and the radius. */
    tilt(ring * cos(th), MINOR_RADIUS * sin(ph), -ring * sin(th), o->p);
    tilt(cos(ph) * cos(th), sin(ph), -cos(ph) * sin(th), o->n);
    /* The tangent follows +u; the bitangent cross(N, T) w must follow the
     * image's up, -v: w is chosen by that sign. */
    double t[3] = { -sin(th), 0, -cos(th) };
    double dv[3] = { -sin(ph) * cos(th), cos(ph), sin(ph) * sin(th) };   /* dP/dv */
    double n[3] = { cos(ph) * cos(th), sin(ph), -cos(ph) * sin(th) };
    double b[3] = { n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2],
                    n[0] * t[1] - n[1] * t[0] };
    double up = -(b[0] * dv[0] + b[1] * dv[1] + b[2] * dv[2]);
    tilt(t[0], t[1], t[2], o->t);
    o->t[3] = up >= 0 ? 1.0f : -1.0f;
    o->uv[0] = (float)((double)i / MAJOR_SEGMENTS);
    o->uv[1] = (float)((double)j / MINOR_SEGMENTS);
}

/* ---- the GLB ------------------------------------------------------------ */

typedef struct bytes {
    uint8_t *data;
    size_t size, cap;
} bytes;

static bool append(void *user, const void *data, size_t size)
{
    bytes *b = user;
    if (b->size + size > b->cap) {
        size_t cap = b->cap ? b->cap : 1 << 16;
        while (cap < b->size + size) {
            cap *= 2;
        }
        uint8_t *d = realloc(b->data, cap);
        if (!d) {
            return false;
        }
        b->data = d;
        b->cap = cap;
    }
    memcpy(b->data + b->size, data, size);
    b->size += size;
    return true;
}

static bool pad4(bytes *b, uint8_t fill)
{
    while (b->size % 4) {
        if (!append(b, &fill, 1)) {
            return false;
        }
    }
    return true;
}

static bool put_u32(FILE *f, uint32_t v)
{
    uint8_t le[4] = { (uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16), (uint8_t)(v >> 24) };
    return fwrite(le, 1, 4, f) == 4;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: softrast-pbr-asset OUT.glb\n");
        return 2;
    }
    const int nu = MAJOR_SEGMENTS + 1, nv = MINOR_SEGMENTS + 1;
    size_t vcount = (size_t)nu * nv, icount = (size_t)MAJOR_SEGMENTS * MINOR_SEGMENTS * 6;
    vertex *verts = malloc(vcount * sizeof *verts);
    uint32_t *idx = malloc(icount * sizeof *idx);
    size_t big = (size_t)MAP_SIZE * MAP_SIZE * 4;
    size_t small = (size_t)SMALL_MAP_SIZE * SMALL_MAP_SIZE * 4;
    uint8_t *maps[4] = { malloc(big), malloc(big), malloc(small), malloc(small) };
    bytes bin = { 0 };
    if (!verts || !idx || !maps[0] || !maps[1] || !maps[2] || !maps[3]) {
        fprintf(stderr, "softrast-pbr-asset: out of memory\n");
        return 1;
    }
    float lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (int i = 0; i < nu; i++) {
        for (int j = 0; j < nv; j++) {
            vertex *v = &verts[(size_t)i * nv + j];
            make_vertex(i, j, v);
            for (int k = 0; k < 3; k++) {
                lo[k] = fminf(lo[k], v->p[k]);
                hi[k] = fmaxf(hi[k], v->p[k]);
            }
        }
    }
    /* Counter-clockwise seen from outside: cross(dP/du, dP/dv) points
     * out, so a quad's corners go (i, j), (i+1, j), (i+1, j+1), (i, j+1). */
    size_t o = 0;
    for (int i = 0; i < MAJOR_SEGMENTS; i++) {
        for (int j = 0; j < MINOR_SEGMENTS; j++) {
            uint32_t a = (uint32_t)(i * nv + j), b = a + 1, c = a + (uint32_t)nv + 1,
                     d = a + (uint32_t)nv;
            uint32_t q[6] = { a, d, c, a, c, b };
            memcpy(&idx[o], q, sizeof q);
            o += 6;
        }
    }
    make_maps(maps[0], maps[1], maps[2], maps[3]);

    /* BIN: positions, normals, tangents, uvs (each a bufferView), indices,
     * then the four PNGs. */
    size_t view_off[9], view_len[9];
    int nviews = 0;
    static const int comp[4] = { 3, 3, 4, 2 };
    for (int a = 0; a < 4; a++) {
        view_off[nviews] = bin.size;
        for (size_t i = 0; i < vcount; i++) {
            const float *src = a == 0 ? verts[i].p : a == 1 ? verts[i].n : a == 2 ? verts[i].t
                                                                                : verts[i].uv;
            if (!append(&bin, src, (size_t)comp[a] * sizeof(float))) {
                goto oom;
            }
        }
        view_len[nviews] = bin.size - view_off[nviews];
        nviews++;
    }
    view_off[nviews] = bin.size;
    if (!append(&bin, idx, icount * sizeof *idx)) {
        goto oom;
    }
    view_len[nviews] = bin.size - view_off[nviews];
    nviews++;
    for (int m = 0; m < 4; m++) {
        int side = m < 2 ? MAP_SIZE : SMALL_MAP_SIZE;
        sr_io_error err;
        view_off[nviews] = bin.size;
        /* Occlusion and metallic-roughness carry no alpha; all are RGB. */
        if (sr_encode_png(append, &bin, side, side, maps[m], (size_t)side * 4,
                          &(sr_png_write_desc){ .compression_level = 9,
                                                .channels = SR_PNG_RGB },
                          &err) != SR_OK) {
            fprintf(stderr, "softrast-pbr-asset: %s\n", err.message);
            return 1;
        }
        view_len[nviews] = bin.size - view_off[nviews];
        nviews++;
        if (!pad4(&bin, 0)) {
            goto oom;
        }
    }

    char json[8192];
    int n = snprintf(json, sizeof json,
        "{\"asset\":{\"version\":\"2.0\",\"generator\":\"softrast-pbr-asset\"},"
        "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"name\":\"tiles\"}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,"
        "\"TANGENT\":2,\"TEXCOORD_0\":3},\"indices\":4,\"material\":0}]}],"
        "\"materials\":[{\"name\":\"tiles\",\"pbrMetallicRoughness\":{"
        "\"baseColorTexture\":{\"index\":0},\"metallicRoughnessTexture\":{\"index\":2}},"
        "\"normalTexture\":{\"index\":1},\"occlusionTexture\":{\"index\":3}}],"
        "\"textures\":[{\"source\":0,\"sampler\":0},{\"source\":1,\"sampler\":0},"
        "{\"source\":2,\"sampler\":0},{\"source\":3,\"sampler\":0}],"
        "\"samplers\":[{\"magFilter\":9729,\"minFilter\":9987,\"wrapS\":10497,\"wrapT\":10497}],"
        "\"images\":[{\"bufferView\":5,\"mimeType\":\"image/png\"},"
        "{\"bufferView\":6,\"mimeType\":\"image/png\"},"
        "{\"bufferView\":7,\"mimeType\":\"image/png\"},"
        "{\"bufferView\":8,\"mimeType\":\"image/png\"}],"
        "\"accessors\":["
        "{\"bufferView\":0,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\","
        "\"min\":[%.9g,%.9g,%.9g],\"max\":[%.9g,%.9g,%.9g]},"
        "{\"bufferView\":1,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\"},"
        "{\"bufferView\":2,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC4\"},"
        "{\"bufferView\":3,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC2\"},"
        "{\"bufferView\":4,\"componentType\":5125,\"count\":%zu,\"type\":\"SCALAR\"}],"
        "\"bufferViews\":[",
        vcount, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], vcount, vcount, vcount, icount);
    for (int v = 0; v < nviews && n > 0 && (size_t)n < sizeof json; v++) {
        n += snprintf(json + n, sizeof json - (size_t)n,
                      "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu%s}", v ? "," : "",
                      view_off[v], view_len[v],
                      v < 4 ? ",\"target\":34962" : v == 4 ? ",\"target\":34963" : "");
    }
    if (n > 0 && (size_t)n < sizeof json) {
        n += snprintf(json + n, sizeof json - (size_t)n, "],\"buffers\":[{\"byteLength\":%zu}]}",
                      bin.size);
    }
    if (n < 0 || (size_t)n >= sizeof json - 4) {
        fprintf(stderr, "softrast-pbr-asset: the JSON chunk does not fit\n");
        return 1;
    }
    while (n % 4) {
        json[n++] = ' ';
    }

    FILE *f = fopen(argv[1], "wb");
    if (!f) {
        perror(argv[1]);
        return 1;
    }
    uint32_t total = 12 + 8 + (uint32_t)n + 8 + (uint32_t)bin.size;
    bool ok = put_u32(f, 0x46546C67u) && put_u32(f, 2) && put_u32(f, total) &&
              put_u32(f, (uint32_t)n) && put_u32(f, 0x4E4F534Au) &&
              fwrite(json, 1, (size_t)n, f) == (size_t)n && put_u32(f, (uint32_t)bin.size) &&
              put_u32(f, 0x004E4942u) && fwrite(bin.data, 1, bin.size, f) == bin.size;
    if (fclose(f) != 0 || !ok) {
        fprintf(stderr, "softrast-pbr-asset: %s: write failed\n", argv[1]);
        remove(argv[1]);
        return 1;
    }
    for (int m = 0; m < 4; m++) {
        free(maps[m]);
    }
    free(verts);
    free(idx);
    free(bin.data);
    return 0;
oom:
    fprintf(stderr, "softrast-pbr-asset: out of memory\n");
    return 1;
}
