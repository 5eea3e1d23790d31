/* test_gltf_meshopt.c - glTF's EXT_meshopt_compression: a sphere written
 * plainly and compressed as gltfpack writes it (meshoptimizer's encoders,
 * linked into this test only, with the octahedral and exponential
 * filters, KHR_mesh_quantization's types and a fallback buffer without
 * data) reads as the same scene and renders the same image; malformed
 * compressed views give one line and exit 2 from `softrast render`; a
 * build without meshoptimizer refuses such a file naming the library. */
#include "batch_cli.h"
#include "glb_write.h"
#include "image_compare.h"
#include "sr_test.h"
#include "uv_sphere.h"

#include "softrast.h"
#include "softrast_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef SR_HAVE_MESHOPT_TEST
#include <meshoptimizer.h>
#endif
#ifdef SR_HAVE_WEBP_TEST
#include <webp/encode.h>
#endif

/* ---- the sphere ------------------------------------------------------------ */

/* The sphere's material, untextured; a textured look replaces it. */
#define SPHERE_LOOK                                                                  \
    "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.8,0.3,0.1,1]," \
    "\"metallicFactor\":0,\"roughnessFactor\":0.4}}]"

/* The members after the accessors: the mesh, `look` (materials and any
 * textures and images, NULL: SPHERE_LOOK), the node and the scene. */
static void put_tail(wbuf *json, const char *look)
{
    static const char mesh[] = "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,"
                               "\"NORMAL\":1,\"TEXCOORD_0\":2},\"indices\":3,\"material\":0}]}],";
    static const char scene[] =
        ",\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0}";
    wb_put(json, mesh, strlen(mesh));
    look = look ? look : SPHERE_LOOK;
    wb_put(json, look, strlen(look));
    wb_put(json, scene, sizeof scene);   /* with its NUL */
}

/* The plain file's JSON (NUL-terminated, without its opening brace when
 * `open` is false) and BIN: float positions, normals and coordinates,
 * short indices. */
static void plain_parts(const sphere *s, bool open, const char *look, wbuf *json_out,
                        wbuf *bin_out)
{
    wbuf bin = {0}, json = {0};
    uint8_t tmp[2];
    put_sphere_attributes(&bin, s);
    for (size_t i = 0; i < s->index_count; i++) {
        uint16_t v = (uint16_t)s->idx[i];
        le_copy(tmp, &v, 1, 2);
        wb_put(&bin, tmp, 2);
    }
    wb_printf(&json, "%s\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu}],",
              open ? "{" : "", bin.n);
    wb_printf(&json, "\"bufferViews\":[{\"buffer\":0,\"byteLength\":%d},", VERTS * 12);
    wb_printf(&json, "{\"buffer\":0,\"byteOffset\":%d,\"byteLength\":%d},", VERTS * 12,
              VERTS * 12);
    wb_printf(&json, "{\"buffer\":0,\"byteOffset\":%d,\"byteLength\":%d},", VERTS * 24,
              VERTS * 8);
    wb_printf(&json, "{\"buffer\":0,\"byteOffset\":%d,\"byteLength\":%zu}],", VERTS * 32,
              s->index_count * 2);
    wb_printf(&json, "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":%d,"
                     "\"type\":\"VEC3\",\"min\":[-1,-1,-1],\"max\":[1,1,1]},",
              VERTS);
    wb_printf(&json, "{\"bufferView\":1,\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\"},",
              VERTS);
    wb_printf(&json, "{\"bufferView\":2,\"componentType\":5126,\"count\":%d,\"type\":\"VEC2\"},",
              VERTS);
    wb_printf(&json, "{\"bufferView\":3,\"componentType\":5123,\"count\":%zu,"
                     "\"type\":\"SCALAR\"}],",
              s->index_count);
    put_tail(&json, look);
    *json_out = json;
    *bin_out = bin;
}

static sr_scene *parse_glb(const wbuf *b, sr_io_error *e)
{
    sr_scene *s = NULL;
    if (sr_parse_gltf(sr_test_ctx(), "t.glb", b->p, b->n, NULL, &s, e) != SR_OK) {
        return NULL;
    }
    return s;
}

#ifdef SR_HAVE_MESHOPT_TEST

static wbuf plain_glb(const sphere *s, const char *look)
{
    wbuf json, bin;
    plain_parts(s, true, look, &json, &bin);
    wbuf out = glb((const char *)json.p, bin.p, bin.n);
    free(bin.p);
    free(json.p);
    return out;
}

/* How the compressed file is written; zero: as gltfpack writes it. */
typedef struct pack_options {
    bool indices_mode;          /* INDICES of 32-bit indices, not TRIANGLES of 16-bit */
    bool used_only;             /* extensionsUsed only, a fallback of zeros with data */
    const char *look;           /* as put_tail's */
    bool webp;                  /* look requires EXT_texture_webp */
} pack_options;

typedef struct packed {
    wbuf json, bin;
    size_t stream_at[4];        /* where positions, normals, coordinates, indices start */
} packed;

static void put_stream(wbuf *bin, const uint8_t *data, size_t n)
{
    wb_put(bin, data, n);
    wb_put(bin, "\0\0\0", (4 - n % 4) % 4);
}

/* The sphere as EXT_meshopt_compression streams in the BIN chunk (buffer
 * 0) over views of the fallback buffer 1: positions float with the
 * exponential filter, normals octahedral in signed bytes, coordinates
 * normalized shorts, indices as o asks.  json is NUL-terminated. */
static packed pack(const sphere *s, pack_options o)
{
    packed p = {0};
    size_t cap = meshopt_encodeVertexBufferBound(VERTS, 12) +
                 meshopt_encodeIndexBufferBound(s->index_count, VERTS) +
                 meshopt_encodeIndexSequenceBound(s->index_count, VERTS);
    uint8_t *enc = malloc(cap);
    float *f4 = malloc(sizeof(float) * 4 * VERTS);
    uint8_t *raw = malloc(s->index_count * 4 + VERTS * 12);
    size_t off[4], len[4];

    meshopt_encodeFilterExp(raw, VERTS, 12, 23, &s->pos[0][0]);
    off[0] = p.bin.n;
    put_stream(&p.bin, enc, len[0] = meshopt_encodeVertexBuffer(enc, cap, raw, VERTS, 12));

    for (int v = 0; v < VERTS; v++) {
        memcpy(f4 + 4 * v, s->nrm[v], 12);
        f4[4 * v + 3] = 0;
    }
    meshopt_encodeFilterOct(raw, VERTS, 4, 8, f4);
    off[1] = p.bin.n;
    put_stream(&p.bin, enc, len[1] = meshopt_encodeVertexBuffer(enc, cap, raw, VERTS, 4));

    uint16_t *uv = (uint16_t *)raw;
    for (int v = 0; v < VERTS; v++) {
        uv[2 * v] = (uint16_t)lrintf(s->uv[v][0] * 65535.0f);
        uv[2 * v + 1] = (uint16_t)lrintf(s->uv[v][1] * 65535.0f);
    }
    off[2] = p.bin.n;
    put_stream(&p.bin, enc, len[2] = meshopt_encodeVertexBuffer(enc, cap, raw, VERTS, 4));

    off[3] = p.bin.n;
    len[3] = o.indices_mode ? meshopt_encodeIndexSequence(enc, cap, s->idx, s->index_count)
                            : meshopt_encodeIndexBuffer(enc, cap, s->idx, s->index_count);
    put_stream(&p.bin, enc, len[3]);
    memcpy(p.stream_at, off, sizeof off);
    size_t isize = o.indices_mode ? 4 : 2;

    size_t fallback = (size_t)VERTS * 20 + s->index_count * isize;
    const char *webp = o.webp ? ",\"EXT_texture_webp\"" : "";
    wb_printf(&p.json, "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":["
                       "\"EXT_meshopt_compression\",\"KHR_mesh_quantization\"%s],"
                       "\"extensionsRequired\":[%s\"KHR_mesh_quantization\"%s],",
              webp, o.used_only ? "" : "\"EXT_meshopt_compression\",", webp);
    wb_printf(&p.json, "\"buffers\":[{\"byteLength\":%zu},{\"byteLength\":%zu,", p.bin.n,
              fallback);
    if (o.used_only) {
        /* Zeros: a reader that took them instead would draw nothing. */
        uint8_t *zeros = calloc(1, fallback);
        char *b64 = malloc(4 * (fallback / 3 + 1) + 1);
        gltf_base64(zeros, fallback, b64);
        wb_put(&p.json, "\"uri\":\"data:application/octet-stream;base64,", 44);
        wb_put(&p.json, b64, strlen(b64));
        wb_put(&p.json, "\"}],", 4);
        free(zeros);
        free(b64);
    } else {
        wb_printf(&p.json, "%s", "\"extensions\":{\"EXT_meshopt_compression\":"
                                 "{\"fallback\":true}}}],");
    }
    static const char *const filters[] = { "EXPONENTIAL", "OCTAHEDRAL", "NONE" };
    static const int strides[] = { 12, 4, 4 };
    size_t fo = 0;
    wb_printf(&p.json, "%s", "\"bufferViews\":[");
    for (int k = 0; k < 3; k++) {
        wb_printf(&p.json, "{\"buffer\":1,\"byteOffset\":%zu,\"byteLength\":%d,"
                           "\"byteStride\":%d,\"extensions\":{\"EXT_meshopt_compression\":",
                  fo, VERTS * strides[k], strides[k]);
        wb_printf(&p.json, "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,"
                           "\"byteStride\":%d,\"count\":%d,\"mode\":\"ATTRIBUTES\","
                           "\"filter\":\"%s\"}}},",
                  off[k], len[k], strides[k], VERTS, filters[k]);
        fo += (size_t)VERTS * strides[k];
    }
    wb_printf(&p.json, "{\"buffer\":1,\"byteOffset\":%zu,\"byteLength\":%zu,"
                       "\"extensions\":{\"EXT_meshopt_compression\":",
              fo, s->index_count * isize);
    wb_printf(&p.json, "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,"
                       "\"byteStride\":%zu,\"count\":%zu,\"mode\":\"%s\"}}}],",
              off[3], len[3], isize, s->index_count, o.indices_mode ? "INDICES" : "TRIANGLES");
    wb_printf(&p.json, "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":%d,"
                       "\"type\":\"VEC3\",\"min\":[-1,-1,-1],\"max\":[1,1,1]},",
              VERTS);
    wb_printf(&p.json, "{\"bufferView\":1,\"componentType\":5120,\"normalized\":true,"
                       "\"count\":%d,\"type\":\"VEC3\"},",
              VERTS);
    wb_printf(&p.json, "{\"bufferView\":2,\"componentType\":5123,\"normalized\":true,"
                       "\"count\":%d,\"type\":\"VEC2\"},",
              VERTS);
    wb_printf(&p.json, "{\"bufferView\":3,\"componentType\":%d,\"count\":%zu,"
                       "\"type\":\"SCALAR\"}],",
              o.indices_mode ? 5125 : 5123, s->index_count);
    put_tail(&p.json, o.look);
    free(enc);
    free(f4);
    free(raw);
    return p;
}

static wbuf packed_glb(const packed *p)
{
    return glb((const char *)p->json.p, p->bin.p, p->bin.n);
}

static void packed_free(packed *p)
{
    free(p->json.p);
    free(p->bin.p);
}

/* The compressed scene equals the plain one: indices exactly, positions
 * within the 23-bit mantissa, normals within 8-bit octahedral precision,
 * coordinates within a 16-bit step. */
static void check_same_scene(const sr_scene *a, const sr_scene *b)
{
    REQUIRE(a->primitive_count == 1 && b->primitive_count == 1);
    const sr_scene_primitive *p = &a->primitives[0], *q = &b->primitives[0];
    REQUIRE(p->vertex_count == q->vertex_count && p->triangle_count == q->triangle_count);
    REQUIRE(q->normals && q->texcoords0);
    CHECK_EQ(memcmp(p->indices, q->indices, p->triangle_count * 3 * sizeof *p->indices), 0);
    double dp = 0, dn = 0, dt = 0;
    for (size_t i = 0; i < p->vertex_count * 3; i++) {
        dp = fmax(dp, fabs(p->positions[i] - q->positions[i]));
        dn = fmax(dn, fabs(p->normals[i] - q->normals[i]));
    }
    for (size_t i = 0; i < p->vertex_count * 2; i++) {
        dt = fmax(dt, fabs(p->texcoords0[i] - q->texcoords0[i]));
    }
    CHECK(dp <= 1e-6);
    CHECK(dn <= 0.02);
    CHECK(dt <= 1.0 / 65535);
}

SR_TEST(compressed_sphere_reads_as_the_plain_one)
{
    static sphere s;
    make_sphere(&s);
    wbuf plain = plain_glb(&s, NULL);
    sr_io_error e;
    sr_scene *a = parse_glb(&plain, &e);
    REQUIRE(a);
    for (int variant = 0; variant < 2; variant++) {
        /* gltfpack's layout; then INDICES of ints with the extension only
         * used and a fallback with data, which is not read. */
        packed p = pack(&s, (pack_options){ .indices_mode = variant == 1,
                                            .used_only = variant == 1 });
        wbuf packed_file = packed_glb(&p);
        CHECK(variant == 1 || packed_file.n * 2 < plain.n);
        sr_scene *b = parse_glb(&packed_file, &e);
        if (!b) {
            FAILF("variant %d: %s", variant, e.message);
        } else {
            check_same_scene(a, b);
            sr_destroy_scene(sr_test_ctx(), b);
        }
        free(packed_file.p);
        packed_free(&p);
    }
    sr_destroy_scene(sr_test_ctx(), a);
    free(plain.p);
}

SR_TEST(compressed_sphere_renders_as_the_plain_one)
{
    NEED_CLI();
    static sphere s;
    make_sphere(&s);
    wbuf plain = plain_glb(&s, NULL);
    packed p = pack(&s, (pack_options){0});
    wbuf packed_file = packed_glb(&p);
    /* 8-bit octahedral normals move the shading by a few levels (4 at
     * most, here). */
    check_same_render("meshopt_sphere", (const void *[]){ plain.p, packed_file.p },
                      (size_t[]){ plain.n, packed_file.n }, 8, 0);
    free(plain.p);
    free(packed_file.p);
    packed_free(&p);
}

#ifdef SR_HAVE_WEBP_TEST

enum { MAP_W = 256, MAP_H = 128 };

/* A map for the sphere: latitude bands, a longitude checker, a ring. */
static void make_map(uint8_t *rgba)
{
    for (int y = 0; y < MAP_H; y++) {
        for (int x = 0; x < MAP_W; x++) {
            uint8_t *p = rgba + 4 * (y * MAP_W + x);
            double band = 0.5 + 0.5 * sin(6 * M_PI * y / MAP_H);
            bool check = ((x / 16) + (y / 16)) % 2;
            double dx = x - 80.0, dy = y - 60.0, ring = fabs(sqrt(dx * dx + dy * dy) - 20);
            p[0] = (uint8_t)(ring < 3 ? 250 : 40 + 150 * band);
            p[1] = (uint8_t)(ring < 3 ? 220 : check ? 150 : 90);
            p[2] = (uint8_t)(ring < 3 ? 60 : 200 - 120 * band);
            p[3] = 255;
        }
    }
}

static char *image_look(const char *mime, const uint8_t *bytes, size_t n, bool webp)
{
    char *b64 = malloc(4 * (n / 3 + 1) + 1);
    gltf_base64(bytes, n, b64);
    size_t cap = strlen(b64) + 600;
    char *look = malloc(cap);
    snprintf(look, cap,
             "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0},"
             "\"metallicFactor\":0,\"roughnessFactor\":0.5}}],\"textures\":[{%s}],"
             "\"images\":[{\"uri\":\"data:%s;base64,%s\"}]",
             webp ? "\"extensions\":{\"EXT_texture_webp\":{\"source\":0}}" : "\"source\":0",
             mime, b64);
    free(b64);
    return look;
}

static bool collect(void *user, const void *data, size_t size)
{
    wb_put(user, data, size);
    return true;
}

/* What gltfpack -cc -tw writes: compressed geometry and a WebP texture,
 * against the plain file with the same texels in PNG. */
SR_TEST(gltfpack_style_sphere_with_a_webp_texture_renders_as_the_plain_one)
{
    NEED_CLI();
    static sphere s;
    static uint8_t map[MAP_W * MAP_H * 4];
    make_sphere(&s);
    make_map(map);
    wbuf png = {0};
    sr_io_error e;
    REQUIRE(sr_encode_png(collect, &png, MAP_W, MAP_H, map, MAP_W * 4, NULL, &e) == SR_OK);
    uint8_t *webp = NULL;
    size_t webp_n = WebPEncodeLosslessRGBA(map, MAP_W, MAP_H, MAP_W * 4, &webp);
    REQUIRE(webp_n > 0);
    char *plain_look = image_look("image/png", png.p, png.n, false);
    char *packed_look = image_look("image/webp", webp, webp_n, true);
    wbuf plain = plain_glb(&s, plain_look);
    packed p = pack(&s, (pack_options){ .look = packed_look, .webp = true });
    wbuf packed_file = packed_glb(&p);
    /* 16-bit coordinates and 8-bit normals move the shading by a level
     * or two (2 at most, here). */
    check_same_render("meshopt_webp_sphere", (const void *[]){ plain.p, packed_file.p },
                      (size_t[]){ plain.n, packed_file.n }, 8, 0);
    free(plain.p);
    free(packed_file.p);
    packed_free(&p);
    free(plain_look);
    free(packed_look);
    WebPFree(webp);
    free(png.p);
}

#endif

typedef struct bad_case {
    const char *from, *to;       /* the JSON edit, or from NULL */
    const char *from2, *to2;     /* and a second one */
    int corrupt;                 /* >= 0: the first byte of that stream is flipped */
    const char *message;
} bad_case;

SR_TEST(malformed_compressed_views_give_one_line_and_exit_2)
{
    NEED_CLI();
    static sphere s;
    make_sphere(&s);
    static const bad_case cases[] = {
        /* the position stream cut short, then its header byte corrupted */
        { "{\"buffer\":0,\"byteOffset\":0,\"byteLength\":",
          "{\"buffer\":0,\"byteOffset\":0,\"byteLength\":40,\"x\":", NULL, NULL, -1,
          "/bufferViews/0/extensions/EXT_meshopt_compression: the ATTRIBUTES stream does not "
          "decode" },
        { NULL, NULL, NULL, NULL, 0,
          "/bufferViews/0/extensions/EXT_meshopt_compression: the ATTRIBUTES stream does not "
          "decode" },
        { NULL, NULL, NULL, NULL, 3,
          "/bufferViews/3/extensions/EXT_meshopt_compression: the TRIANGLES stream does not "
          "decode" },
        /* elements times stride past the view, and past any size */
        { "\"count\":1225", "\"count\":1226", NULL, NULL, -1,
          "/bufferViews/0/extensions/EXT_meshopt_compression/count: 1226 elements of 12 "
          "bytes, but the bufferView's byteLength is 14700" },
        { "\"count\":1225", "\"count\":2147483648", NULL, NULL, -1,
          "/bufferViews/0/extensions/EXT_meshopt_compression/count: 2147483648 elements of 12 "
          "bytes" },
        { "\"filter\":\"EXPONENTIAL\"", "\"filter\":\"OCTAHEDRAL\"", NULL, NULL, -1,
          "/bufferViews/0/extensions/EXT_meshopt_compression/filter: OCTAHEDRAL needs a "
          "byteStride of 4 or 8, not 12" },
        { "\"mode\":\"TRIANGLES\"", "\"mode\":\"TRIANGLES\",\"filter\":\"OCTAHEDRAL\"", NULL,
          NULL, -1,
          "/bufferViews/3/extensions/EXT_meshopt_compression/filter: only ATTRIBUTES take a "
          "filter" },
        { "\"mode\":\"TRIANGLES\"", "\"mode\":\"TRIANGLE_STRIP\"", NULL, NULL, -1,
          "/bufferViews/3/extensions/EXT_meshopt_compression/mode: not one of ATTRIBUTES, "
          "TRIANGLES, INDICES" },
        /* a view without the extension on the fallback buffer, which has no data */
        { ",\"extensions\":{\"EXT_meshopt_compression\":{\"buffer\":0,\"byteOffset\":0,",
          ",\"x\":{\"y\":{\"buffer\":0,\"byteOffset\":0,", NULL, NULL, -1,
          "/buffers/1: a fallback buffer without data, read by /bufferViews/0/buffer" },
        { "{\"buffer\":0,\"byteOffset\":0,", "{\"buffer\":1,\"byteOffset\":0,", NULL, NULL, -1,
          "/bufferViews/0/extensions/EXT_meshopt_compression/buffer: buffer 1 is a fallback "
          "buffer" },
        { "\"extensions\":{\"EXT_meshopt_compression\":{\"buffer\":0,",
          "\"extensions\":{\"EXT_meshopt_compression\":{", NULL, NULL, -1,
          "/bufferViews/0/extensions/EXT_meshopt_compression/buffer: missing" },
        /* a view past its fallback buffer; more decoding than the file may ask */
        { "{\"buffer\":1,\"byteOffset\":0,\"byteLength\":14700,",
          "{\"buffer\":1,\"byteOffset\":90000,\"byteLength\":14700,", NULL, NULL, -1,
          "/bufferViews/0/byteLength: bytes 90000..104700 run past the" },
        { "{\"buffer\":1,\"byteOffset\":0,\"byteLength\":14700,",
          "{\"buffer\":1,\"byteOffset\":0,\"byteLength\":1200000000,",
          "\"count\":1225", "\"count\":100000000", -1,
          "/bufferViews/0/extensions/EXT_meshopt_compression/count: 1200000000 bytes to "
          "decode are more than a file of this size may decode" },
    };
    char dir[1024];
    fresh_dir("meshopt_bad", dir, sizeof dir);
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        const bad_case *c = &cases[i];
        packed p = pack(&s, (pack_options){0});
        if ((c->from && !edit_text(&p.json, c->from, c->to)) ||
            (c->from2 && !edit_text(&p.json, c->from2, c->to2))) {
            packed_free(&p);
            continue;
        }
        if (c->corrupt >= 0) {
            p.bin.p[p.stream_at[c->corrupt]] ^= 0xFF;
        }
        wbuf file = packed_glb(&p);
        check_refused(dir, i, file.p, file.n, c->message);
        free(file.p);
        packed_free(&p);
    }
}

#endif

/* Without the library a file that requires the extension is refused
 * naming it; with it, such a file reads (the fallback of a view read
 * plainly is named when it has no data, as above). */
SR_TEST(a_required_extension_is_read_or_refused_naming_the_library)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    static sphere s;
    make_sphere(&s);
    /* The plain file claiming the extension: nothing in it is compressed. */
    wbuf json = {0}, rest, bin;
    plain_parts(&s, false, NULL, &rest, &bin);
    wb_printf(&json, "%s", "{\"extensionsRequired\":[\"EXT_meshopt_compression\"],");
    wb_put(&json, rest.p, rest.n);
    wbuf file = glb((const char *)json.p, bin.p, bin.n);
    sr_io_error e;
    sr_scene *sc = parse_glb(&file, &e);
#ifdef SR_HAVE_MESHOPT_TEST
    CHECK(sc != NULL);
#else
    CHECK(sc == NULL);
    CHECK_STR_CONTAINS(e.message, "/extensionsRequired/0: extension EXT_meshopt_compression is "
                                  "not supported (softrast was built without meshoptimizer)");
#endif
    sr_destroy_scene(sr_test_ctx(), sc);
    free(json.p);
    free(rest.p);
    free(bin.p);
    free(file.p);
}
