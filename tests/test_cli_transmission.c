/* test_cli_transmission.c - `softrast render` of glass (KHR_materials_
 * transmission and KHR_materials_volume): three spheres in front of a
 * checker of white, red and blue squares.  The clear one shows the
 * checker magnified by the refraction offset, the frosted one blurred
 * and tinted blue, the absorbing one orange, its blue squares dark.
 * Compared with tests/ref/gltf_transmission.png within 3 codes on 0.5% of
 * the pixels (test_images.c's tolerance: libm), and the same bytes from
 * one thread and from three. */
#include "batch_cli.h"
#include "gltf_write.h"

#include "softrast_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SLICES 32
#define STACKS 16
#define GRID_X 8
#define GRID_Y 5

typedef struct bytes {
    uint8_t *p;
    size_t n;
} bytes;

static void put(bytes *b, const void *src, size_t count, size_t size)
{
    le_copy(b->p + b->n, src, count, size);
    b->n += count * size;
}

/* The leaf: a diamond 1.2 wide and 1.8 tall in z = 0.3, facing +z. */
static const float leaf_pos[12] = { 0, -0.9f, 0.3f, 0.6f, 0, 0.3f, 0, 0.9f, 0.3f, -0.6f, 0, 0.3f };

/* The model: a UV sphere of radius 0.8 (mesh k draws it with material
 * 2 + k, `glass` holding the three) at x = -1.9, 0, 1.9, and behind it at
 * z = -1.5 a GRID_X x GRID_Y checker whose squares take materials 0 and 1
 * and 5 in turn.  With `leaf`, mesh 2 is a leaf (leaf_pos) in place of the
 * third sphere. */
static char *glass_model(const char *glass, bool leaf)
{
    size_t sv = (SLICES + 1) * (STACKS + 1), si = SLICES * STACKS * 6;
    size_t cv = GRID_X * GRID_Y * 4;
    bytes b = { malloc(sv * 24 + si * 2 + cv * 24 + GRID_X * GRID_Y * 12 + 128), 0 };
    if (!b.p) {
        return NULL;
    }
    for (int j = 0; j <= STACKS; j++) {
        for (int i = 0; i <= SLICES; i++) {
            float th = 3.14159265f * (float)j / STACKS, ph = 6.2831853f * (float)i / SLICES;
            float n[3] = { sinf(th) * sinf(ph), -cosf(th), sinf(th) * cosf(ph) };
            float p[3] = { 0.8f * n[0], 0.8f * n[1], 0.8f * n[2] };
            put(&b, p, 3, 4);
        }
    }
    for (int j = 0; j <= STACKS; j++) {
        for (int i = 0; i <= SLICES; i++) {
            float th = 3.14159265f * (float)j / STACKS, ph = 6.2831853f * (float)i / SLICES;
            float n[3] = { sinf(th) * sinf(ph), -cosf(th), sinf(th) * cosf(ph) };
            put(&b, n, 3, 4);
        }
    }
    for (int j = 0; j < STACKS; j++) {
        for (int i = 0; i < SLICES; i++) {
            uint16_t a = (uint16_t)(j * (SLICES + 1) + i), c = (uint16_t)(a + SLICES + 1);
            uint16_t t[6] = { a, (uint16_t)(a + 1), (uint16_t)(c + 1), a, (uint16_t)(c + 1), c };
            put(&b, t, 6, 2);
        }
    }
    size_t checker_pos = b.n;
    const float size = 0.75f, x0 = -GRID_X * size / 2, y0 = -GRID_Y * size / 2;
    for (int y = 0; y < GRID_Y; y++) {
        for (int x = 0; x < GRID_X; x++) {
            float l = x0 + (float)x * size, r = l + size, d = y0 + (float)y * size, u = d + size;
            float q[12] = { l, d, -1.5f, r, d, -1.5f, r, u, -1.5f, l, u, -1.5f };
            put(&b, q, 12, 4);
        }
    }
    size_t checker_nrm = b.n;
    for (size_t k = 0; k < cv; k++) {
        const float z[3] = { 0, 0, 1 };
        put(&b, z, 3, 4);
    }
    /* One index list per color, squares in turn white, red, blue. */
    size_t lists[3], counts[3] = { 0, 0, 0 };
    for (int c = 0; c < 3; c++) {
        lists[c] = b.n;
        for (int k = 0; k < GRID_X * GRID_Y; k++) {
            if (k % 3 == c) {
                uint16_t v = (uint16_t)(4 * k);
                uint16_t t[6] = { v, (uint16_t)(v + 1), (uint16_t)(v + 2), v, (uint16_t)(v + 2),
                                  (uint16_t)(v + 3) };
                put(&b, t, 6, 2);
                counts[c] += 6;
            }
        }
    }
    /* The leaf's positions, normals and indices, 4-aligned after the
     * 2-byte indices: bufferViews 8..10 and accessors 8..10. */
    char views[256] = "", accessors[256] = "", mesh2[128];
    snprintf(mesh2, sizeof mesh2, "\"POSITION\":0,\"NORMAL\":1},\"indices\":2");
    if (leaf) {
        while (b.n % 4) {
            b.p[b.n++] = 0;
        }
        size_t at = b.n;
        put(&b, leaf_pos, 12, 4);
        for (int k = 0; k < 4; k++) {
            const float z[3] = { 0, 0, 1 };
            put(&b, z, 3, 4);
        }
        const uint16_t t[6] = { 0, 1, 2, 0, 2, 3 };
        put(&b, t, 6, 2);
        snprintf(views, sizeof views,
                 ",{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":48},"
                 "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":48},"
                 "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":12}",
                 at, at + 48, at + 96);
        snprintf(accessors, sizeof accessors,
                 ",{\"bufferView\":8,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
                 "\"min\":[-0.6,-0.9,0.3],\"max\":[0.6,0.9,0.3]},"
                 "{\"bufferView\":9,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
                 "{\"bufferView\":10,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}");
        snprintf(mesh2, sizeof mesh2, "\"POSITION\":8,\"NORMAL\":9},\"indices\":10");
    }
    char *b64 = malloc(4 * (b.n / 3 + 1) + 1);
    char *json = b64 ? malloc(4 * (b.n / 3 + 1) + 8192) : NULL;
    if (!json) {
        free(b.p);
        free(b64);
        return NULL;
    }
    gltf_base64(b.p, b.n, b64);
    sprintf(json,
            "{\"asset\":{\"version\":\"2.0\"},"
            "\"extensionsUsed\":[\"KHR_materials_transmission\",\"KHR_materials_volume\"%s],"
            "\"buffers\":[{\"byteLength\":%zu,"
            "\"uri\":\"data:application/octet-stream;base64,%s\"}],"
            "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":%zu},"
            "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},"
            "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},"
            "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},"
            "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},"
            "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},"
            "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},"
            "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}%s],"
            "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":%zu,"
            "\"type\":\"VEC3\","
            "\"min\":[-0.8,-0.8,-0.8],\"max\":[0.8,0.8,0.8]},"
            "{\"bufferView\":1,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\"},"
            "{\"bufferView\":2,\"componentType\":5123,\"count\":%zu,\"type\":\"SCALAR\"},"
            "{\"bufferView\":3,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\","
            "\"min\":[%g,%g,-1.5],\"max\":[%g,%g,-1.5]},"
            "{\"bufferView\":4,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\"},"
            "{\"bufferView\":5,\"componentType\":5123,\"count\":%zu,\"type\":\"SCALAR\"},"
            "{\"bufferView\":6,\"componentType\":5123,\"count\":%zu,\"type\":\"SCALAR\"},"
            "{\"bufferView\":7,\"componentType\":5123,\"count\":%zu,\"type\":\"SCALAR\"}%s],"
            "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.8,0.8,0.8,1],"
            "\"metallicFactor\":0,\"roughnessFactor\":0.8}},"
            "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.7,0.05,0.03,1],"
            "\"metallicFactor\":0,\"roughnessFactor\":0.8}},%s,"
            "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.03,0.1,0.6,1],"
            "\"metallicFactor\":0,\"roughnessFactor\":0.8}}],"
            "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1},"
            "\"indices\":2,\"material\":2}]},"
            "{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1},"
            "\"indices\":2,\"material\":3}]},"
            "{\"primitives\":[{\"attributes\":{%s,\"material\":4}]},"
            "{\"primitives\":[{\"attributes\":{\"POSITION\":3,\"NORMAL\":4},\"indices\":5,"
            "\"material\":0},{\"attributes\":{\"POSITION\":3,\"NORMAL\":4},\"indices\":6,"
            "\"material\":1},{\"attributes\":{\"POSITION\":3,\"NORMAL\":4},\"indices\":7,"
            "\"material\":5}]}],"
            "\"nodes\":[{\"mesh\":0,\"translation\":[-1.9,0,0]},{\"mesh\":1},"
            "{\"mesh\":2,\"translation\":[1.9,0,0]},{\"mesh\":3}],"
            "\"scenes\":[{\"nodes\":[0,1,2,3]}],\"scene\":0}",
            leaf ? ",\"KHR_materials_dispersion\",\"KHR_materials_diffuse_transmission\"" : "",
            b.n, b64, sv * 12, sv * 12, sv * 12, sv * 24, si * 2, checker_pos, cv * 12,
            checker_nrm, cv * 12, lists[0], counts[0] * 2, lists[1], counts[1] * 2, lists[2],
            counts[2] * 2, views, sv, sv, si, cv, (double)x0, (double)y0, (double)-x0,
            (double)-y0, cv, counts[0], counts[1], counts[2], accessors, glass, mesh2);
    free(b64);
    free(b.p);
    return json;
}

SR_TEST(glass_spheres_show_the_checker_behind_them)
{
    NEED_CLI();
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    const char *glass =
        "{\"pbrMetallicRoughness\":{\"metallicFactor\":0,\"roughnessFactor\":0},"
        "\"extensions\":{\"KHR_materials_transmission\":{\"transmissionFactor\":1},"
        "\"KHR_materials_volume\":{\"thicknessFactor\":1.6}}},"
        "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.6,0.8,1,1],\"metallicFactor\":0,"
        "\"roughnessFactor\":0.35},"
        "\"extensions\":{\"KHR_materials_transmission\":{\"transmissionFactor\":1}}},"
        "{\"pbrMetallicRoughness\":{\"metallicFactor\":0,\"roughnessFactor\":0.05},"
        "\"extensions\":{\"KHR_materials_transmission\":{\"transmissionFactor\":1},"
        "\"KHR_materials_volume\":{\"thicknessFactor\":1.6,\"attenuationColor\":[1,0.45,0.1],"
        "\"attenuationDistance\":0.8}}}";
    check_model_render("transmission", "glass.gltf", glass_model(glass, false), "240x112",
                       ARGS("--camera", "eye=0,1,7,target=0,0,0"), "gltf_transmission");
}

/* KHR_materials_dispersion and KHR_materials_diffuse_transmission: the
 * same checker behind a clear sphere (left), one of the same glass with
 * dispersion 4 at ior 1.7 (its checker edges split into red, green and
 * blue fringes), and a leaf letting a light from behind through,
 * yellow-green, against the studio environment.  Compared with
 * tests/ref/gltf_dispersion_leaf.png as the glass scene is. */
SR_TEST(dispersive_sphere_and_backlit_leaf)
{
    NEED_CLI();
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    const char *materials =
        "{\"pbrMetallicRoughness\":{\"metallicFactor\":0,\"roughnessFactor\":0},"
        "\"extensions\":{\"KHR_materials_transmission\":{\"transmissionFactor\":1},"
        "\"KHR_materials_volume\":{\"thicknessFactor\":1.6}}},"
        "{\"pbrMetallicRoughness\":{\"metallicFactor\":0,\"roughnessFactor\":0},"
        "\"extensions\":{\"KHR_materials_transmission\":{\"transmissionFactor\":1},"
        "\"KHR_materials_volume\":{\"thicknessFactor\":1.6},"
        "\"KHR_materials_ior\":{\"ior\":1.7},\"KHR_materials_dispersion\":{\"dispersion\":4}}},"
        "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.12,0.4,0.06,1],\"metallicFactor\":0,"
        "\"roughnessFactor\":0.6},\"doubleSided\":true,"
        "\"extensions\":{\"KHR_materials_diffuse_transmission\":{"
        "\"diffuseTransmissionFactor\":0.8,\"diffuseTransmissionColorFactor\":[0.6,0.9,0.2]}}}";
    check_model_render("dispersion", "prism.gltf", glass_model(materials, true), "240x112",
                       ARGS("--camera", "eye=0,1,7,target=0,0,0", "--light",
                            "dir=-0.2,-0.3,1,intensity=3"),
                       "gltf_dispersion_leaf");
}

/* The leaf alone (the scene's third node), lit from behind with the key
 * light's shadow map on: the leaf is in the map, but it does not shadow
 * the light it lets through itself (pbr.c looks that light's shadow up
 * from the far side), so `--shadows on` draws the bytes of `--shadows
 * off` within a code.  Before, the leaf's green fell from 245 to 129. */
SR_TEST(backlit_leaf_is_not_its_own_shadow)
{
    NEED_CLI();
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    const char *materials =
        "{\"pbrMetallicRoughness\":{\"metallicFactor\":0}},"
        "{\"pbrMetallicRoughness\":{\"metallicFactor\":0}},"
        "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.12,0.4,0.06,1],\"metallicFactor\":0,"
        "\"roughnessFactor\":0.6},\"doubleSided\":true,"
        "\"extensions\":{\"KHR_materials_diffuse_transmission\":{"
        "\"diffuseTransmissionFactor\":0.8,\"diffuseTransmissionColorFactor\":[0.6,0.9,0.2]}}}";
    char dir[1024], model[1100], out[2][1200];
    fresh_dir("leaf_shadow", dir, sizeof dir);
    snprintf(model, sizeof model, "%s/leaf.gltf", dir);
    char *text = text_replaced(glass_model(materials, true), "\"nodes\":[0,1,2,3]",
                               "\"nodes\":[2]");
    REQUIRE(text && write_text(model, text));
    free(text);
    uint8_t *px[2];
    int w[2], h[2];
    for (int k = 0; k < 2; k++) {
        snprintf(out[k], sizeof out[k], "%s/shadows_%s.png", dir, k ? "on" : "off");
        run_result r;
        px[k] = render_read(ARGS("render", model, "--size", "96x96", "--camera",
                                 "eye=0,1,7,target=1.9,0,0", "--light",
                                 "dir=-0.2,-0.3,1,intensity=3", "--shadows", k ? "on" : "off",
                                 "-o", out[k]),
                            out[k], &w[k], &h[k], &r);
        REQUIRE(px[k]);
    }
    REQUIRE(w[0] == w[1] && h[0] == h[1]);
    int off = 0;
    for (size_t i = 0; i < 4 * (size_t)w[0] * (size_t)h[0]; i++) {
        off += abs(px[0][i] - px[1][i]) > 1;
    }
    const uint8_t *centre = px[0] + 4 * ((size_t)h[0] / 2 * (size_t)w[0] + (size_t)w[0] / 2);
    CHECK(centre[1] > 200);          /* the leaf, lit through */
    CHECK_EQ(off, 0);
    free(px[0]);
    free(px[1]);
}
