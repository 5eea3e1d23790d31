/* test_cli_gltf_texture.c - `softrast render` of a glTF base color
 * texture under the classic shading models: the texture must land where
 * the physically based program samples it, whatever the file's sampler
 * (mirrored repeat, clamp to edge, nearest texels), KHR_texture_transform
 * and coordinate set.  A quad whose texture coordinates run past 0..1
 * is drawn with --shading unlit and with the physically based look of
 * the same file (KHR_materials_unlit, no tone curve: the texels' own
 * codes), and the two images must agree within a code. */
#include "batch_cli.h"
#include "gltf_write.h"
#include "image_compare.h"

#include "softrast_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

SR_TEST_NEEDS(sr_io_have_gltf, "this build reads no glTF (jansson was not found)")

/* A 4 x 4 texture of 16 colors far apart (one texel from its neighbours
 * by at least 60 codes in some channel), nearest-filtered below. */
static bool write_texture(const char *path)
{
    uint8_t px[4 * 4 * 4];
    for (int i = 0; i < 16; i++) {
        px[4 * i + 0] = (uint8_t)(20 + 70 * (i & 3));
        px[4 * i + 1] = (uint8_t)(20 + 70 * (i >> 2));
        px[4 * i + 2] = (uint8_t)(i & 1 ? 230 : 40);
        px[4 * i + 3] = 255;
    }
    sr_io_error err;
    return sr_write_png(path, 4, 4, px, 16, NULL, &err) == SR_OK;
}

/* A square of side 2 at z = 0 facing +z, with TEXCOORD_0 running from
 * -0.75 to 1.75 across it (two and a half texture widths) and a skewed
 * TEXCOORD_1; its one material is `material` (JSON), its one sampler
 * `sampler`, its texture the file tex.png beside it. */
static bool write_quad(const char *path, const char *material, const char *sampler)
{
    const float pos[12] = { -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0 };
    const float uv0[8] = { -0.75f, 1.75f, 1.75f, 1.75f, 1.75f, -0.75f, -0.75f, -0.75f };
    const float uv1[8] = { 0.1f, 0.9f, 0.6f, 0.8f, 0.7f, 0.3f, 0.2f, 0.2f };
    const uint16_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    uint8_t buf[124];
    le_copy(buf, pos, 12, 4);
    le_copy(buf + 48, uv0, 8, 4);
    le_copy(buf + 80, uv1, 8, 4);
    le_copy(buf + 112, idx, 6, 2);
    char b64[200], json[4000];
    gltf_base64(buf, sizeof buf, b64);
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},"
             "\"extensionsUsed\":[\"KHR_materials_unlit\",\"KHR_texture_transform\"],"
             "\"buffers\":[{\"byteLength\":124,"
             "\"uri\":\"data:application/octet-stream;base64,%s\"}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},"
             "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":32},"
             "{\"buffer\":0,\"byteOffset\":80,\"byteLength\":32},"
             "{\"buffer\":0,\"byteOffset\":112,\"byteLength\":12}],"
             "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,"
             "\"type\":\"VEC3\",\"min\":[-1,-1,0],\"max\":[1,1,0]},"
             "{\"bufferView\":1,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\"},"
             "{\"bufferView\":2,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\"},"
             "{\"bufferView\":3,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}],"
             "\"images\":[{\"uri\":\"tex.png\"}],"
             "\"samplers\":[%s],\"textures\":[{\"source\":0,\"sampler\":0}],"
             "\"materials\":[%s],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":1,"
             "\"TEXCOORD_1\":2},\"indices\":3,\"material\":0}]}],"
             "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0}",
             b64, sampler, material);
    return write_text(path, json);
}

static uint8_t *render_png(const char *model, const char *shading, const char *normals,
                           const char *out, int *w, int *h)
{
    run_result r;
    /* normals NULL: the default (flat normals split in the glTF merge) */
    if (!run(ARGS("render", model, "--shading", shading, normals ? "--normals" : "--aa",
                  normals ? normals : "none", "--tonemap", "none", "--size", "96x96", "--aa",
                  "none", "--camera",
                  "eye=0,0,2.6,target=0,0,0", "-o", out),
             &r)) {
        return NULL;
    }
    if (r.status != 0) {
        FAILF("render --shading %s: %s", shading, r.err);
        return NULL;
    }
    uint8_t *px = NULL;
    sr_io_error err;
    return sr_read_png(out, NULL, w, h, &px, &err) == SR_OK ? px : NULL;
}

#define NEAREST "\"magFilter\":9728,\"minFilter\":9728"
#define UNLIT "\"extensions\":{\"KHR_materials_unlit\":{}}"

SR_TEST(classic_shading_samples_the_base_texture_where_pbr_does)
{
    NEED_CLI();
    static const struct {
        const char *name, *sampler, *texture_info, *normals;
    } cases[] = {
        { "mirror", "{" NEAREST ",\"wrapS\":33648,\"wrapT\":33648}", "{\"index\":0}", NULL },
        { "clamp", "{" NEAREST ",\"wrapS\":33071,\"wrapT\":33071}", "{\"index\":0}", NULL },
        { "mirror_clamp", "{" NEAREST ",\"wrapS\":33648,\"wrapT\":33071}", "{\"index\":0}", NULL },
        { "transform", "{" NEAREST "}",
          "{\"index\":0,\"extensions\":{\"KHR_texture_transform\":{\"offset\":[0.3,-0.2],"
          "\"rotation\":0.7,\"scale\":[1.5,0.8]}}}", NULL },
        { "texcoord1", "{" NEAREST ",\"wrapS\":33648}", "{\"index\":0,\"texCoord\":1}",
          NULL },
        /* The extension's texCoord overrides the textureInfo's. */
        { "transform_texcoord1", "{" NEAREST ",\"wrapT\":33648}",
          "{\"index\":0,\"extensions\":{\"KHR_texture_transform\":{\"rotation\":-0.4,"
          "\"scale\":[3,2],\"texCoord\":1}}}", NULL },
        /* Split vertices drop set 1: both looks read the slot from set 0,
         * the transform still applied. */
        { "transform_texcoord1_flat", "{" NEAREST ",\"wrapT\":33648}",
          "{\"index\":0,\"extensions\":{\"KHR_texture_transform\":{\"rotation\":-0.4,"
          "\"scale\":[3,2],\"texCoord\":1}}}", "flat" },
    };
    char dir[1024], tex[1100], model[1100], out[1100];
    fresh_dir("gltf_texture", dir, sizeof dir);
    snprintf(tex, sizeof tex, "%s/tex.png", dir);
    REQUIRE(write_texture(tex));
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char material[600];
        snprintf(material, sizeof material, "{\"pbrMetallicRoughness\":{\"baseColorTexture\":%s},"
                 UNLIT "}", cases[k].texture_info);
        snprintf(model, sizeof model, "%s/%s.gltf", dir, cases[k].name);
        REQUIRE(write_quad(model, material, cases[k].sampler));
        int w, h, w2, h2;
        snprintf(out, sizeof out, "%s/%s_pbr.png", dir, cases[k].name);
        uint8_t *pbr = render_png(model, "pbr", cases[k].normals, out, &w, &h);
        snprintf(out, sizeof out, "%s/%s_unlit.png", dir, cases[k].name);
        uint8_t *unlit = render_png(model, "unlit", cases[k].normals, out, &w2, &h2);
        REQUIRE(pbr && unlit && w == w2 && h == h2);
        /* The quad covers most of the image in many texels, so that a
         * texel misplaced anywhere shows. */
        int colors = 0;
        uint32_t seen[16] = { 0 };
        for (int i = 0; i < w * h && colors < 16; i++) {
            uint32_t c = (uint32_t)pbr[4 * i] << 16 | (uint32_t)pbr[4 * i + 1] << 8 |
                         pbr[4 * i + 2];
            int j = 0;
            while (j < colors && seen[j] != c) {
                j++;
            }
            if (j == colors) {
                seen[colors++] = c;
            }
        }
        CHECK(colors >= 5);
        /* Within a code (the sRGB round trip of the physically based
         * look); a few pixels on texel edges may fall on either side, as
         * the classic models transform the corners' coordinates and pbr
         * each fragment's. */
        char name[200];
        snprintf(name, sizeof name, "gltf_texture_%s", cases[k].name);
        CHECK(sr_test_compare_images(name, unlit, pbr, w, h, 1, w * h / 200));
        free(pbr);
        free(unlit);
    }
}

/* KHR_texture_transform's scale of 0 is the extension's (every coordinate
 * on the texel at the offset), not the zeroed slot's identity: the quad
 * drawn in one texel's color, with the physically based look and the
 * classic one.  glTF's (0.375, 0.625) from the top left is texel 9 of
 * write_texture's (column 1, row 2). */
SR_TEST(a_zero_texture_scale_draws_the_texel_at_the_offset)
{
    NEED_CLI();
    char dir[1024], tex[1100], model[1100], out[1100];
    fresh_dir("gltf_texture_zero_scale", dir, sizeof dir);
    snprintf(tex, sizeof tex, "%s/tex.png", dir);
    REQUIRE(write_texture(tex));
    snprintf(model, sizeof model, "%s/zero.gltf", dir);
    REQUIRE(write_quad(model, "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0,"
                              "\"extensions\":{\"KHR_texture_transform\":{\"offset\":[0.375,"
                              "0.625],\"scale\":[0,0]}}}}," UNLIT "}",
                       "{" NEAREST "}"));
    static const char *const shading[2] = { "pbr", "unlit" };
    const uint8_t want[3] = { 90, 160, 230 };
    for (int k = 0; k < 2; k++) {
        int w, h;
        snprintf(out, sizeof out, "%s/zero_%s.png", dir, shading[k]);
        uint8_t *px = render_png(model, shading[k], NULL, out, &w, &h);
        REQUIRE(px);
        /* The middle half of the image is well inside the quad. */
        int off = 0;
        for (int y = h / 4; y < 3 * h / 4; y++) {
            for (int x = w / 4; x < 3 * w / 4; x++) {
                const uint8_t *p = px + 4 * ((size_t)y * (size_t)w + (size_t)x);
                for (int c = 0; c < 3; c++) {
                    off += abs(p[c] - want[c]) > 1;
                }
            }
        }
        CHECK_EQ(off, 0);
        free(px);
    }
}
