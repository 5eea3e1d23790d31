/* test_gltf_spec_gloss.c - the archived KHR_materials_pbrSpecularGlossiness
 * (docs/gltf.md, docs/pbr.md): its factors and textures reach
 * sr_pbr_material over the metallic-roughness values, and `softrast
 * render` draws it as the extension writes its BRDF inputs: a sphere of
 * it renders like the metallic-roughness sphere of metallic 0, roughness
 * 1 - glossiness, base color diffuse times 1 - max(specular) and
 * KHR_materials_specular's F0 equal to the specular color; a white
 * specular leaves no diffuse lobe; and a row of four spheres is compared
 * with tests/ref/gltf_spec_gloss.png. */
#include "batch_cli.h"
#include "gltf_parse.h"
#include "image_compare.h"
#include "uv_sphere.h"

#include "softrast_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

SR_TEST_NEEDS(sr_io_have_gltf, "softrast was built without jansson (glTF)")

static bool collect(void *user, const void *data, size_t size)
{
    wb_put(user, data, size);
    return true;
}

/* An n x n RGBA image as a PNG data: URI (malloc'd), texel (x, y) from
 * texel(x, y, out). */
static char *png_uri(int n, void (*texel)(int x, int y, uint8_t out[4]))
{
    uint8_t *px = malloc(4 * (size_t)n * (size_t)n);
    wbuf png = {0};
    if (px) {
        for (int y = 0; y < n; y++) {
            for (int x = 0; x < n; x++) {
                texel(x, y, &px[4 * ((size_t)y * (size_t)n + (size_t)x)]);
            }
        }
        sr_io_error e;
        sr_encode_png(collect, &png, n, n, px, 4 * (size_t)n, NULL, &e);
    }
    free(px);
    char *uri = png.n ? malloc(4 * (png.n / 3 + 1) + 32) : NULL;
    if (uri) {
        strcpy(uri, "data:image/png;base64,");
        gltf_base64(png.p, png.n, uri + strlen(uri));
    }
    free(png.p);
    return uri;
}

/* One texel everywhere: specular (sRGB codes) 200, 120, 60, glossiness
 * (linear) 153 = 0.6. */
static void uniform_texel(int x, int y, uint8_t out[4])
{
    (void)x, (void)y;
    out[0] = 200, out[1] = 120, out[2] = 60, out[3] = 153;
}

/* A checker of orange and pale blue, for the diffuse texture. */
static void checker_texel(int x, int y, uint8_t out[4])
{
    bool odd = ((x / 2) + (y / 2)) & 1;
    out[0] = odd ? 230 : 120, out[1] = odd ? 120 : 170, out[2] = odd ? 40 : 230, out[3] = 255;
}

/* Stripes across u: a shiny dark specular, then a rough bright gold. */
static void stripe_texel(int x, int y, uint8_t out[4])
{
    (void)y;
    bool gold = (x / 2) & 1;
    out[0] = gold ? 255 : 40, out[1] = gold ? 200 : 40, out[2] = gold ? 90 : 40;
    out[3] = gold ? 90 : 240;
}

/* A .gltf (malloc'd) of n unit spheres in a row along x, 2.4 apart,
 * sphere k drawn with material k of `materials` (the JSON array's
 * items), with extensionsUsed `used` and the images `images` (items of
 * the array; texture k shows image k), the geometry in a data: URI. */
static char *spheres(int n, const char *used, const char *materials, const char *images)
{
    static sphere s;
    make_sphere(&s);
    wbuf bin = {0};
    put_sphere_attributes(&bin, &s);
    size_t idx_at = bin.n;
    uint8_t *idx = malloc(s.index_count * 4);
    if (!idx) {
        free(bin.p);
        return NULL;
    }
    le_copy(idx, s.idx, s.index_count, 4);
    wb_put(&bin, idx, s.index_count * 4);
    free(idx);
    char *b64 = malloc(4 * (bin.n / 3 + 1) + 1);
    if (!b64) {
        free(bin.p);
        return NULL;
    }
    gltf_base64(bin.p, bin.n, b64);
    wbuf j = {0};
    wb_printf(&j, "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":%s,", used);
    wb_printf(&j, "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;"
                  "base64,", bin.n);
    wb_put(&j, b64, strlen(b64));
    wb_printf(&j, "\"}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":%d},"
                  "{\"buffer\":0,\"byteOffset\":%d,\"byteLength\":%d},"
                  "{\"buffer\":0,\"byteOffset\":%d,\"byteLength\":%d},"
                  "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}],",
              VERTS * 12, VERTS * 12, VERTS * 12, VERTS * 24, VERTS * 8, idx_at,
              s.index_count * 4);
    wb_printf(&j, "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":%d,"
                  "\"type\":\"VEC3\",\"min\":[-1,-1,-1],\"max\":[1,1,1]},"
                  "{\"bufferView\":1,\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\"},"
                  "{\"bufferView\":2,\"componentType\":5126,\"count\":%d,\"type\":\"VEC2\"},"
                  "{\"bufferView\":3,\"componentType\":5125,\"count\":%zu,"
                  "\"type\":\"SCALAR\"}],",
              VERTS, VERTS, VERTS, s.index_count);
    wb_printf(&j, "\"meshes\":[");
    for (int k = 0; k < n; k++) {
        wb_printf(&j, "%s{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,"
                      "\"TEXCOORD_0\":2},\"indices\":3,\"material\":%d}]}", k ? "," : "", k);
    }
    wb_printf(&j, "],\"nodes\":[");
    for (int k = 0; k < n; k++) {
        wb_printf(&j, "%s{\"mesh\":%d,\"translation\":[%g,0,0]}", k ? "," : "", k,
                  2.4 * (k - (n - 1) / 2.0));
    }
    wb_printf(&j, "],\"scenes\":[{\"nodes\":[");
    for (int k = 0; k < n; k++) {
        wb_printf(&j, "%s%d", k ? "," : "", k);
    }
    wb_printf(&j, "]}],\"scene\":0");
    if (images) {
        wb_printf(&j, ",\"images\":[");
        wb_put(&j, images, strlen(images));
        wb_printf(&j, "],\"textures\":[{\"source\":0},{\"source\":1}]");
    }
    wb_printf(&j, ",\"materials\":[");
    wb_put(&j, materials, strlen(materials));
    wb_put(&j, "]}", 3);
    free(b64);
    free(bin.p);
    return (char *)j.p;
}

#define SG_USED "[\"KHR_materials_pbrSpecularGlossiness\",\"KHR_texture_transform\"]"
#define SG(body) "{\"extensions\":{\"KHR_materials_pbrSpecularGlossiness\":{" body "}}}"

static char *two_images(void)
{
    char *a = png_uri(16, checker_texel), *b = png_uri(16, stripe_texel);
    size_t n = (a ? strlen(a) : 0) + (b ? strlen(b) : 0) + 64;
    char *out = a && b ? malloc(n) : NULL;
    if (out) {
        snprintf(out, n, "{\"uri\":\"%s\"},{\"uri\":\"%s\"}", a, b);
    }
    free(a);
    free(b);
    return out;
}

/* The factors and textures reach sr_pbr_material with the extension's
 * defaults; the metallic-roughness values beside them are not drawn;
 * factors out of 0..1 are clamped with a warning each; the extension is
 * neither named among those not read nor refused when required;
 * KHR_materials_specular, which the extension excludes, is dropped with
 * a warning. */
SR_TEST(factors_and_textures_are_read)
{
    char *images = two_images();
    REQUIRE(images);
    char *doc = spheres(
        4, SG_USED,
        "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,1,1],\"metallicFactor\":1,"
        "\"roughnessFactor\":0.1,\"baseColorTexture\":{\"index\":1},"
        "\"metallicRoughnessTexture\":{\"index\":1}},"
        "\"extensions\":{\"KHR_materials_pbrSpecularGlossiness\":{"
        "\"diffuseFactor\":[0.5,0.25,1,0.75],\"specularFactor\":[0.25,0.5,0.125],"
        "\"glossinessFactor\":0.375,\"diffuseTexture\":{\"index\":0,\"extensions\":"
        "{\"KHR_texture_transform\":{\"scale\":[2,2]}}},"
        "\"specularGlossinessTexture\":{\"index\":1,\"texCoord\":1}}}},"
        SG("") ","
        SG("\"diffuseFactor\":[2,0,0,1],\"specularFactor\":[-1,0,0],\"glossinessFactor\":3") ","
        "{\"extensions\":{\"KHR_materials_pbrSpecularGlossiness\":{},"
        "\"KHR_materials_specular\":{\"specularColorFactor\":[2,2,2]}}}",
        images);
    free(images);
    REQUIRE(doc);
    warnings w = {0};
    sr_scene *s = NULL;
    sr_io_error e;
    REQUIRE(parse(doc, &w, &s, &e) == SR_OK);
    REQUIRE(s->material_count == 5);
    const sr_pbr_material *m = &s->materials[0];
    CHECK(m->specular_glossiness);
    CHECK_EQ(m->base_color[0], 0.5f);
    CHECK_EQ(m->base_color[1], 0.25f);
    CHECK_EQ(m->base_color[2], 1.0f);
    CHECK_EQ(m->base_color[3], 0.75f);
    CHECK_EQ(m->sg_specular[0], 0.25f);
    CHECK_EQ(m->sg_specular[1], 0.5f);
    CHECK_EQ(m->sg_specular[2], 0.125f);
    CHECK_EQ(m->glossiness, 0.375f);
    /* The diffuse texture (sRGB, its transform) in the base color's slot;
     * the specular-glossiness texture on set 1, sRGB like the diffuse
     * (its A stays linear): one texture per image and color space. */
    REQUIRE(m->base_color_texture.texture != NULL);
    CHECK_EQ(m->base_color_texture.scale[0], 2.0f);
    REQUIRE(m->specular_glossiness_texture.texture != NULL);
    CHECK_EQ(m->specular_glossiness_texture.texcoord, 1);
    CHECK(m->specular_glossiness_texture.texture != m->base_color_texture.texture);
    CHECK(m->metallic_roughness_texture.texture == NULL);
    CHECK(!m->specular_set);
    /* Present but empty: white diffuse and specular, glossiness 1. */
    const sr_pbr_material *d = &s->materials[1];
    CHECK(d->specular_glossiness);
    CHECK(d->base_color[0] == 1.0f && d->base_color[3] == 1.0f);
    CHECK(d->sg_specular[0] == 1.0f && d->sg_specular[2] == 1.0f && d->glossiness == 1.0f);
    /* Clamped. */
    const sr_pbr_material *c = &s->materials[2];
    CHECK_EQ(c->base_color[0], 1.0f);
    CHECK_EQ(c->sg_specular[0], 0.0f);
    CHECK_EQ(c->glossiness, 1.0f);
    const sr_pbr_material *x = &s->materials[3];
    CHECK(x->specular_glossiness && !x->specular_set);
    /* Three clamps and the excluded extension; nothing about the
     * extension not being read. */
    CHECK_EQ(w.count, 4);
    CHECK_STR_CONTAINS(w.last, "t.gltf: warning: /materials/3/extensions/"
                               "KHR_materials_specular: not read on a material with "
                               "KHR_materials_pbrSpecularGlossiness");
    sr_destroy_scene(sr_test_ctx(), s);
    /* Required: read, not refused. */
    char *req = text_replaced(doc, "\"extensionsUsed\"", "\"extensionsRequired\":"
                              "[\"KHR_materials_pbrSpecularGlossiness\"],\"extensionsUsed\"");
    REQUIRE(req);
    w = (warnings){0};
    CHECK(parse(req, &w, &s, &e) == SR_OK);
    if (s) {
        CHECK(s->materials[0].specular_glossiness);
        sr_destroy_scene(sr_test_ctx(), s);
    }
    free(req);
}

/* The material extensions whose specifications say they must not be used
 * with KHR_materials_pbrSpecularGlossiness (their "Exclusions") are not
 * read on such a material, one warning each, while
 * KHR_materials_emissive_strength, which does not exclude it, is; and a
 * sphere of specular-glossiness with a clear coat, a sheen and a film
 * draws the bytes of the one without them. */
#define EXCLUDED                                                                     \
    "\"KHR_materials_ior\":{\"ior\":2},"                                              \
    "\"KHR_materials_clearcoat\":{\"clearcoatFactor\":1},"                            \
    "\"KHR_materials_sheen\":{\"sheenColorFactor\":[1,0,1]},"                         \
    "\"KHR_materials_transmission\":{\"transmissionFactor\":1},"                      \
    "\"KHR_materials_volume\":{\"thicknessFactor\":1,\"attenuationDistance\":1},"     \
    "\"KHR_materials_dispersion\":{\"dispersion\":1},"                                \
    "\"KHR_materials_anisotropy\":{\"anisotropyStrength\":1},"                        \
    "\"KHR_materials_iridescence\":{\"iridescenceFactor\":1},"                        \
    "\"KHR_materials_diffuse_transmission\":{\"diffuseTransmissionFactor\":1}"

SR_TEST(extensions_that_exclude_it_are_not_drawn_over_it)
{
    char *doc = spheres(1, SG_USED,
                        "{\"emissiveFactor\":[0.1,0.1,0.1],\"extensions\":{"
                        "\"KHR_materials_pbrSpecularGlossiness\":{},"
                        "\"KHR_materials_emissive_strength\":{\"emissiveStrength\":3}," EXCLUDED
                        "}}",
                        NULL);
    REQUIRE(doc);
    warnings w = {0};
    sr_scene *s = NULL;
    sr_io_error e;
    REQUIRE(parse(doc, &w, &s, &e) == SR_OK);
    free(doc);
    const sr_pbr_material *m = &s->materials[0];
    CHECK(m->specular_glossiness);
    CHECK_EQ(m->emissive_strength, 3.0f);
    CHECK_EQ(m->ior, 0.0f);
    CHECK_EQ(m->clearcoat, 0.0f);
    CHECK_EQ(m->sheen_color[0], 0.0f);
    CHECK_EQ(m->transmission, 0.0f);
    CHECK_EQ(m->thickness, 0.0f);
    CHECK_EQ(m->attenuation_distance, 0.0f);
    CHECK_EQ(m->dispersion, 0.0f);
    CHECK_EQ(m->anisotropy_strength, 0.0f);
    CHECK_EQ(m->iridescence, 0.0f);
    CHECK_EQ(m->diffuse_transmission, 0.0f);
    CHECK_EQ(w.count, 9);
    CHECK_STR_CONTAINS(w.last, "t.gltf: warning: /materials/0/extensions/"
                               "KHR_materials_diffuse_transmission: not read on a material "
                               "with KHR_materials_pbrSpecularGlossiness (the extensions "
                               "exclude each other)");
    sr_destroy_scene(sr_test_ctx(), s);
    NEED_CLI();
    char dir[1024], model[1200], out[1200];
    fresh_dir("spec_gloss_excluded", dir, sizeof dir);
    static const char *const mats[2] = {
        SG("\"diffuseFactor\":[0.6,0.3,0.1,1],\"specularFactor\":[0.1,0.1,0.1],"
           "\"glossinessFactor\":0.7"),
        "{\"extensions\":{\"KHR_materials_pbrSpecularGlossiness\":{\"diffuseFactor\":"
        "[0.6,0.3,0.1,1],\"specularFactor\":[0.1,0.1,0.1],\"glossinessFactor\":0.7},"
        "\"KHR_materials_clearcoat\":{\"clearcoatFactor\":1},"
        "\"KHR_materials_sheen\":{\"sheenColorFactor\":[0,1,1]},"
        "\"KHR_materials_iridescence\":{\"iridescenceFactor\":1}}}",
    };
    uint8_t *px[2] = { NULL, NULL };
    int w2[2], h2[2];
    for (int k = 0; k < 2; k++) {
        snprintf(model, sizeof model, "%s/excluded%d.gltf", dir, k);
        snprintf(out, sizeof out, "%s/excluded%d.png", dir, k);
        doc = spheres(1, SG_USED, mats[k], NULL);
        REQUIRE(doc && write_text(model, doc));
        free(doc);
        run_result r;
        px[k] = render_read(ARGS("render", model, "-o", out, "--size", "96x96"), out, &w2[k],
                            &h2[k], &r);
        REQUIRE(px[k]);
    }
    REQUIRE(w2[0] == w2[1] && h2[0] == h2[1]);
    CHECK(sr_test_compare_images("spec_gloss_excluded", px[0], px[1], w2[0], h2[0], 0, 0));
    free(px[0]);
    free(px[1]);
}

/* Renders the .gltf text `doc` (freed here) as dir/stem.gltf with the
 * tool; the pixels (malloc'd) or NULL after a failure. */
static uint8_t *render_doc(const char *dir, const char *stem, char *doc, int *w, int *h)
{
    char model[1200], out[1200];
    snprintf(model, sizeof model, "%s/%s.gltf", dir, stem);
    snprintf(out, sizeof out, "%s/%s.png", dir, stem);
    bool ok = doc && write_text(model, doc);
    free(doc);
    if (!ok) {
        FAILF("%s: not written", model);
        return NULL;
    }
    run_result r;
    uint8_t *px = render_read(ARGS("render", model, "-o", out, "--size", "320x96"), out, w, h,
                              &r);
    CHECK(px == NULL || strstr(r.err, "warning") == NULL);
    return px;
}

/* One specular-glossiness material and its metallic-roughness twin:
 * base color diffuse (1 - max(specular)), metallic 0, roughness
 * 1 - glossiness, and KHR_materials_specular's F0 min(0.04 color, 1) =
 * specular with color = specular / 0.04 (ior 1.5, specular 1: F90 1). */
typedef struct twin {
    float diffuse[3], specular[3], gloss;
} twin;

static void twin_json(const twin *t, wbuf *sg, wbuf *mr, bool first)
{
    const float *d = t->diffuse, *s = t->specular;
    float top = fmaxf(fmaxf(s[0], s[1]), s[2]), keep = 1.0f - top;
    wb_printf(sg, "%s{\"extensions\":{\"KHR_materials_pbrSpecularGlossiness\":{"
                  "\"diffuseFactor\":[%.9g,%.9g,%.9g,1],\"specularFactor\":[%.9g,%.9g,%.9g],"
                  "\"glossinessFactor\":%.9g}}}",
              first ? "" : ",", d[0], d[1], d[2], s[0], s[1], s[2], t->gloss);
    wb_printf(mr, "%s{\"pbrMetallicRoughness\":{\"baseColorFactor\":[%.9g,%.9g,%.9g,1],"
                  "\"metallicFactor\":0,\"roughnessFactor\":%.9g},"
                  "\"extensions\":{\"KHR_materials_specular\":{"
                  "\"specularColorFactor\":[%.9g,%.9g,%.9g]}}}",
              first ? "" : ",", d[0] * keep, d[1] * keep, d[2] * keep, 1.0f - t->gloss,
              s[0] / 0.04f, s[1] / 0.04f, s[2] / 0.04f);
}

/* Four spheres, gold (the extension's example), green plastic under a
 * blue-tinted specular, a rough one and one of black specular (F0 0:
 * the whole diffuse lobe, under Schlick's F90 1), against their
 * metallic-roughness twins: within 1 code (the twin's F0 is 0.04 times
 * specular / 0.04, a float rounding from the specular). */
SR_TEST(renders_as_metallic_roughness_with_specular)
{
    NEED_CLI();
    static const twin twins[4] = {
        { { 0, 0, 0 }, { 1.0f, 0.766f, 0.336f }, 0.9f },
        { { 0.1f, 0.6f, 0.15f }, { 0.1f, 0.2f, 0.45f }, 0.75f },
        { { 0.7f, 0.3f, 0.3f }, { 0.3f, 0.3f, 0.3f }, 0.2f },
        { { 0.8f, 0.5f, 0.1f }, { 0, 0, 0 }, 0.6f },
    };
    wbuf sg = {0}, mr = {0};
    for (int k = 0; k < 4; k++) {
        twin_json(&twins[k], &sg, &mr, k == 0);
    }
    wb_put(&sg, "", 1);
    wb_put(&mr, "", 1);
    char dir[1024];
    fresh_dir("spec_gloss_twins", dir, sizeof dir);
    int w[2], h[2];
    uint8_t *a = render_doc(dir, "spec_gloss", spheres(4, SG_USED, (char *)sg.p, NULL), &w[0],
                            &h[0]);
    uint8_t *b = render_doc(dir, "metal_rough",
                            spheres(4, "[\"KHR_materials_specular\"]", (char *)mr.p, NULL), &w[1],
                            &h[1]);
    if (a && b && w[0] == w[1] && h[0] == h[1]) {
        sr_test_compare_images("spec_gloss_twins", a, b, w[0], h[0], 1, 0);
    }
    free(a);
    free(b);
    free(sg.p);
    free(mr.p);
}

/* The specular-glossiness texture: sRGB RGB specular, linear A
 * glossiness, times the factors.  A uniform texture (specular codes 200,
 * 120, 60, glossiness 153) draws as the twin whose factors are the
 * texel's values: within 1 code. */
SR_TEST(texture_channels_are_specular_and_glossiness)
{
    NEED_CLI();
    char *tex = png_uri(4, uniform_texel);
    REQUIRE(tex);
    size_t n = 2 * strlen(tex) + 64;
    char *images = malloc(n);
    REQUIRE(images);
    snprintf(images, n, "{\"uri\":\"%s\"},{\"uri\":\"%s\"}", tex, tex);
    free(tex);
    float spec[3];
    const uint8_t code[3] = { 200, 120, 60 };
    for (int c = 0; c < 3; c++) {
        float v = code[c] / 255.0f;
        spec[c] = 0.5f * (v <= 0.04045f ? v / 12.92f : powf((v + 0.055f) / 1.055f, 2.4f));
    }
    const twin t = { { 0.2f, 0.4f, 0.8f }, { spec[0], spec[1], spec[2] }, 0.8f * 153 / 255.0f };
    wbuf sg = {0}, mr = {0};
    twin_json(&t, &sg, &mr, true);
    wb_put(&mr, "", 1);
    char sgm[512];
    snprintf(sgm, sizeof sgm,
             SG("\"diffuseFactor\":[0.2,0.4,0.8,1],\"specularFactor\":[0.5,0.5,0.5],"
                "\"glossinessFactor\":0.8,\"specularGlossinessTexture\":{\"index\":0}"));
    char dir[1024];
    fresh_dir("spec_gloss_texture", dir, sizeof dir);
    int w[2], h[2];
    uint8_t *a = render_doc(dir, "textured", spheres(1, SG_USED, sgm, images), &w[0], &h[0]);
    uint8_t *b = render_doc(dir, "factors",
                            spheres(1, "[\"KHR_materials_specular\"]", (char *)mr.p, NULL), &w[1],
                            &h[1]);
    if (a && b && w[0] == w[1] && h[0] == h[1]) {
        sr_test_compare_images("spec_gloss_texture", a, b, w[0], h[0], 1, 0);
    }
    free(a);
    free(b);
    free(images);
    free(sg.p);
    free(mr.p);
}

/* Energy: the diffuse lobe is weighted by 1 - max(specular), so under a
 * specular whose largest channel is 1 the diffuse color does not show at
 * all: red and green diffuse spheres draw the same bytes, and a black
 * one too.  (A white specular alone would not tell: its Fresnel is 1
 * everywhere, which leaves 1 - F = 0 to the diffuse anyway.) */
SR_TEST(full_specular_channel_leaves_no_diffuse)
{
    NEED_CLI();
    static const char *const colors[3] = { "1,0,0", "0,1,0", "0,0,0" };
    char dir[1024];
    fresh_dir("spec_gloss_white", dir, sizeof dir);
    uint8_t *px[3] = { NULL, NULL, NULL };
    int w[3], h[3];
    for (int k = 0; k < 3; k++) {
        char m[256], stem[16];
        snprintf(m, sizeof m,
                 SG("\"diffuseFactor\":[%s,1],\"specularFactor\":[0.2,1,0.1],"
                    "\"glossinessFactor\":0.5"), colors[k]);
        snprintf(stem, sizeof stem, "white%d", k);
        px[k] = render_doc(dir, stem, spheres(1, SG_USED, m, NULL), &w[k], &h[k]);
    }
    for (int k = 1; k < 3; k++) {
        if (px[0] && px[k] && w[0] == w[k] && h[0] == h[k]) {
            CHECK(memcmp(px[0], px[k], 4 * (size_t)w[0] * (size_t)h[0]) == 0);
        }
    }
    for (int k = 0; k < 3; k++) {
        free(px[k]);
    }
}

/* A row of four spheres: the extension's gold, red plastic, the checker
 * diffuse under stripes of shiny dark and rough gold specular (its
 * texture scaled by KHR_texture_transform), and rough blue under a warm
 * specular tint. */
SR_TEST(spheres_match_the_reference)
{
    NEED_CLI();
    char *images = two_images();
    REQUIRE(images);
    char *doc = spheres(
        4, SG_USED,
        SG("\"diffuseFactor\":[0,0,0,1],\"specularFactor\":[1,0.766,0.336],"
           "\"glossinessFactor\":0.9") ","
        SG("\"diffuseFactor\":[0.6,0.05,0.04,1],\"specularFactor\":[0.05,0.05,0.05],"
           "\"glossinessFactor\":0.8") ","
        SG("\"diffuseTexture\":{\"index\":0},\"specularGlossinessTexture\":{\"index\":1,"
           "\"extensions\":{\"KHR_texture_transform\":{\"scale\":[2,1]}}}") ","
        SG("\"diffuseFactor\":[0.1,0.2,0.6,1],\"specularFactor\":[0.4,0.25,0.1],"
           "\"glossinessFactor\":0.35"),
        images);
    free(images);
    check_model_render("spec_gloss", "spheres.gltf", doc, "360x112",
                       (const char *const[]){ "--fov", "16", "--camera", "eye=0,1.5,14,target=0,0,0",
                                              NULL },
                       "gltf_spec_gloss");
}

/* sr_make_pbr_program refuses a specular-glossiness factor that is not
 * finite, as every other factor. */
SR_TEST(program_refuses_a_glossiness_that_is_not_finite)
{
    sr_pbr_material m = sr_pbr_default_material();
    m.specular_glossiness = true;
    m.glossiness = NAN;
    sr_pbr_desc d = { .material = &m };
    sr_pbr *p = NULL;
    CHECK_EQ(sr_make_pbr_program(sr_test_ctx(), &d, &p), SR_INVALID_ARG);
    CHECK(p == NULL);
    m.glossiness = 0.5f;
    m.sg_specular[1] = INFINITY;
    CHECK_EQ(sr_make_pbr_program(sr_test_ctx(), &d, &p), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(sr_test_ctx()), "not finite");
}

/* `doc` (spheres', freed here) with one animation: the floats of
 * `keys` (2 keys a channel, at 0 and 2 s, widths[k] floats each) in a
 * second buffer, channel k on pointers[k].  Malloc'd, NULL on failure. */
static char *with_animation(char *doc, const float *keys, const int *widths,
                            const char *const *pointers, int n)
{
    static const char *const type[5] = { "", "SCALAR", "VEC2", "VEC3", "VEC4" };
    static const float times[2] = { 0, 2 };
    wbuf bin = {0}, views = {0}, acc = {0}, anim = {0};
    uint8_t le[64];
    le_copy(le, times, 2, 4);
    wb_put(&bin, le, 8);
    wb_printf(&views, ",{\"buffer\":1,\"byteLength\":8}");
    wb_printf(&acc, ",{\"bufferView\":4,\"componentType\":5126,\"count\":2,\"type\":\"SCALAR\","
                    "\"min\":[0],\"max\":[2]}");
    wb_printf(&anim, ",\"animations\":[{\"samplers\":[");
    for (int k = 0, at = 0; k < n; at += 2 * widths[k], k++) {
        le_copy(le, keys + at, 2 * (size_t)widths[k], 4);
        wb_printf(&views, ",{\"buffer\":1,\"byteOffset\":%zu,\"byteLength\":%d}", bin.n,
                  8 * widths[k]);
        wb_put(&bin, le, 8 * (size_t)widths[k]);
        wb_printf(&acc, ",{\"bufferView\":%d,\"componentType\":5126,\"count\":2,\"type\":\"%s\"}",
                  5 + k, type[widths[k]]);
        wb_printf(&anim, "%s{\"input\":4,\"output\":%d}", k ? "," : "", 5 + k);
    }
    wb_printf(&anim, "],\"channels\":[");
    for (int k = 0; k < n; k++) {
        wb_printf(&anim, "%s{\"sampler\":%d,\"target\":{\"path\":\"pointer\",\"extensions\":"
                         "{\"KHR_animation_pointer\":{\"pointer\":\"%s\"}}}}", k ? "," : "", k,
                  pointers[k]);
    }
    wb_printf(&anim, "]}]");
    char b64[256];
    gltf_base64(bin.p, bin.n, b64);
    wbuf out = {0};
    /* Spliced in before the ends of spheres' arrays of buffers, views and
     * accessors, and before the document's closing brace. */
    const char *cuts[3] = { "],\"bufferViews\"", "],\"accessors\"", "],\"meshes\"" };
    const char *from = doc;
    for (int c = 0; doc && c < 3; c++) {
        const char *at = strstr(from, cuts[c]);
        if (!at) {
            free(doc);
            doc = NULL;
            break;
        }
        wb_put(&out, from, (size_t)(at - from));
        if (c == 0) {
            wb_printf(&out, ",{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;"
                            "base64,%s\"}", bin.n, b64);
        } else {
            const wbuf *w = c == 1 ? &views : &acc;
            wb_put(&out, w->p, w->n);
        }
        from = at;
    }
    if (doc) {
        size_t len = strlen(from);
        wb_put(&out, from, len - 1);   /* without the closing brace */
        wb_put(&out, anim.p, anim.n);
        wb_put(&out, "}", 2);
    }
    free(doc);
    free(bin.p);
    free(views.p);
    free(acc.p);
    free(anim.p);
    return doc ? (char *)out.p : (free(out.p), NULL);
}

/* dir/stem.gltf, written from `doc` (freed here), rendered by the tool at
 * `time` of animation 0 (NULL: at rest) into dir/stem_<time>.png; the
 * pixels (malloc'd) or NULL after a failure. */
static uint8_t *render_at(const char *dir, const char *stem, char *doc, const char *time,
                          int *w, int *h)
{
    char model[1200], out[1200];
    snprintf(model, sizeof model, "%s/%s.gltf", dir, stem);
    snprintf(out, sizeof out, "%s/%s_%s.png", dir, stem, time ? time : "rest");
    if (doc && !write_text(model, doc)) {
        FAILF("%s: not written", model);
    }
    free(doc);
    run_result r;
    uint8_t *px = time ? render_read(ARGS("render", model, "-o", out, "--size", "160x160",
                                          "--animation", "0", "--time", time), out, w, h, &r)
                       : render_read(ARGS("render", model, "-o", out, "--size", "160x160"), out,
                                     w, h, &r);
    CHECK(px == NULL || strstr(r.err, "warning") == NULL);
    return px;
}

#define TT "/extensions/KHR_texture_transform/"
#define SG_USED_ANIMATED "[\"KHR_materials_pbrSpecularGlossiness\",\"KHR_texture_transform\"," \
                         "\"KHR_animation_pointer\"]"
#define SGP "/materials/0/extensions/KHR_materials_pbrSpecularGlossiness/"

/* The KHR_texture_transform of both textures and the three factors,
 * animated through KHR_animation_pointer from 0 to 2 s: `softrast render`
 * at 1 s draws the document with the values of 1 s written in (within a
 * code), and at rest something else.  They used to be skipped as
 * properties softrast does not animate. */
SR_TEST(texture_transforms_and_factors_animate_through_pointers)
{
    NEED_CLI();
    char dir[1024];
    fresh_dir("spec_gloss_pointer", dir, sizeof dir);
    static const float keys[] = {
        0, 1,                 /* diffuse rotation: 0.5 at 1 s */
        1, 1, 3, 2,           /* diffuse scale: (2, 1.5) */
        0, 0, 0.5f, 0.25f,    /* diffuse offset: (0.25, 0.125) */
        1, 1, 2, 3,           /* specular-glossiness scale: (1.5, 2) */
        0, 0, 0.5f, 0.5f,     /* specular-glossiness offset: (0.25, 0.25) */
        0.2f, 0.6f,           /* glossiness: 0.4 */
        1, 1, 1, 0.5f, 0.5f, 0.5f,     /* specular: (0.75, 0.75, 0.75) */
        1, 1, 1, 1, 0.5f, 1, 0, 1,     /* diffuse: (0.75, 1, 0.5, 1) */
    };
    static const int widths[] = { 1, 2, 2, 2, 2, 1, 3, 4 };
    static const char *const pointers[] = {
        SGP "diffuseTexture" TT "rotation",
        SGP "diffuseTexture" TT "scale",
        SGP "diffuseTexture" TT "offset",
        SGP "specularGlossinessTexture" TT "scale",
        SGP "specularGlossinessTexture" TT "offset",
        SGP "glossinessFactor",
        SGP "specularFactor",
        SGP "diffuseFactor",
    };
    static const char *const fmt = SG(
        "\"diffuseFactor\":%s,\"specularFactor\":%s,\"glossinessFactor\":%s,"
        "\"diffuseTexture\":{\"index\":0,\"extensions\":{\"KHR_texture_transform\":{%s}}},"
        "\"specularGlossinessTexture\":{\"index\":1,\"extensions\":{\"KHR_texture_transform\":"
        "{%s}}}");
    char rest[1024], posed[1024];
    snprintf(rest, sizeof rest, fmt, "[1,1,1,1]", "[1,1,1]", "0.2",
             "\"offset\":[0,0],\"rotation\":0,\"scale\":[1,1]", "\"offset\":[0,0],\"scale\":[1,1]");
    snprintf(posed, sizeof posed, fmt, "[0.75,1,0.5,1]", "[0.75,0.75,0.75]", "0.4",
             "\"offset\":[0.25,0.125],\"rotation\":0.5,\"scale\":[2,1.5]",
             "\"offset\":[0.25,0.25],\"scale\":[1.5,2]");
    char *images = two_images();
    REQUIRE(images);
    int n = (int)(sizeof widths / sizeof *widths);
    char *animated = with_animation(spheres(1, SG_USED_ANIMATED, rest, images), keys, widths, pointers,
                                    n);
    REQUIRE(animated);
    char *written = spheres(1, SG_USED, posed, images);
    free(images);
    int w[3], h[3];
    uint8_t *px[3];
    px[0] = render_at(dir, "animated", animated, "1", &w[0], &h[0]);
    px[1] = render_at(dir, "written", written, NULL, &w[1], &h[1]);
    px[2] = render_at(dir, "animated", NULL, NULL, &w[2], &h[2]);   /* its rest pose */
    REQUIRE(px[0] && px[1] && px[2] && w[0] == w[1] && h[0] == h[1] && w[0] == w[2] &&
            h[0] == h[2]);
    CHECK(sr_test_compare_images("spec_gloss_pointer", px[0], px[1], w[0], h[0], 1, 0));
    long differ = 0;
    for (long i = 0; i < 4L * w[0] * h[0]; i++) {
        differ += abs(px[0][i] - px[2][i]) > 8;
    }
    fprintf(stderr, "%ld channels apart from the rest pose\n", differ);
    CHECK(differ > (long)w[0] * h[0] / 10);
    for (int k = 0; k < 3; k++) {
        free(px[k]);
    }
}
#undef SG_USED_ANIMATED
#undef SGP
#undef TT
