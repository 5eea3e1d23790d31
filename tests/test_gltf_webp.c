/* test_gltf_webp.c - WebP images: lossless ones (libwebp's encoder, linked
 * into this test only) decode to the exact texels, alpha included; glTF's
 * EXT_texture_webp takes its WebP over a PNG fallback and renders as the
 * same texture in PNG does, as does an OBJ's .webp map_Kd; a damaged WebP
 * is one line and exit 2; a build without libwebp refuses a file that
 * requires the extension naming the library. */
#include "batch_cli.h"
#include "gltf_write.h"
#include "image_compare.h"
#include "sr_test.h"
#include "wbuf.h"

#include "softrast.h"
#include "softrast_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef SR_HAVE_WEBP_TEST
#include <webp/decode.h>
#include <webp/encode.h>
#endif

/* A one-quad glTF (x, y in -1..1) whose material takes texture 0, with
 * `head` spliced in first (extensions lists) and `textures_images` the
 * "textures" and "images" members. */
static char *quad_model(const char *head, const char *textures_images)
{
    static const gltf_quad quad = { -1, -1, 1, 1, 0 };
    size_t cap = strlen(textures_images) + strlen(head) + 400;
    char *tail = malloc(cap);
    snprintf(tail, cap,
             "%s,%s,\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":"
             "{\"index\":0}},\"alphaMode\":\"BLEND\",\"extensions\":"
             "{\"KHR_materials_unlit\":{}}}]",
             head, textures_images);
    char *json = gltf_quads(&quad, 1, tail);
    free(tail);
    return json;
}

#ifdef SR_HAVE_WEBP_TEST

enum { TEX = 64 };

/* A checker of eight colors a side, alpha falling from 255 to 65 across:
 * every texel differs from its neighbours in some channel. */
static void make_texels(uint8_t *rgba)
{
    for (int y = 0; y < TEX; y++) {
        for (int x = 0; x < TEX; x++) {
            uint8_t *p = rgba + 4 * (y * TEX + x);
            int cell = (x / 8 + y / 8) % 2;
            p[0] = (uint8_t)(cell ? 230 : 40 + 3 * x);
            p[1] = (uint8_t)(cell ? 180 - 2 * y : 90);
            p[2] = (uint8_t)(cell ? 30 : 200);
            p[3] = (uint8_t)(255 - 3 * x);
        }
    }
}

static bool collect(void *user, const void *data, size_t size)
{
    wb_put(user, data, size);
    return true;
}

static wbuf png_of(const uint8_t *rgba, int w, int h)
{
    wbuf b = {0};
    sr_io_error e;
    if (sr_encode_png(collect, &b, w, h, rgba, (size_t)w * 4, NULL, &e) != SR_OK) {
        FAILF("%s", e.message);
    }
    return b;
}

/* "data:MIME;base64,..." of n bytes, malloc'd. */
static char *data_uri(const char *mime, const uint8_t *p, size_t n)
{
    char *b64 = malloc(4 * (n / 3 + 1) + 1);
    gltf_base64(p, n, b64);
    size_t cap = strlen(b64) + strlen(mime) + 32;
    char *uri = malloc(cap);
    snprintf(uri, cap, "data:%s;base64,%s", mime, b64);
    free(b64);
    return uri;
}

static bool write_text_file(const char *dir, const char *name, const char *text, char *path,
                            size_t cap)
{
    snprintf(path, cap, "%s/%s", dir, name);
    return sr_test_write_file(path, text, strlen(text));
}

static wbuf webp_lossless(const uint8_t *rgba, int w, int h)
{
    uint8_t *out = NULL;
    size_t n = WebPEncodeLosslessRGBA(rgba, w, h, w * 4, &out);
    wbuf b = {0};
    if (n == 0) {
        FAILF("WebPEncodeLosslessRGBA failed");
    } else {
        wb_put(&b, out, n);
    }
    WebPFree(out);
    return b;
}

SR_TEST(lossless_webp_decodes_to_the_exact_texels_alpha_included)
{
    static uint8_t texels[TEX * TEX * 4];
    make_texels(texels);
    wbuf webp = webp_lossless(texels, TEX, TEX);
    REQUIRE(webp.n > 0);
    int w = 0, h = 0;
    uint8_t *px = NULL;
    sr_io_error e;
    REQUIRE(sr_decode_image("t.webp", webp.p, webp.n, &w, &h, &px, &e) == SR_OK);
    CHECK_EQ(w, TEX);
    CHECK_EQ(h, TEX);
    CHECK_EQ(memcmp(px, texels, sizeof texels), 0);
    free(px);

    /* Lossy with alpha: the size, and colors near the texels'. */
    uint8_t *lossy = NULL;
    size_t n = WebPEncodeRGBA(texels, TEX, TEX, TEX * 4, 90, &lossy);
    REQUIRE(n > 0);
    REQUIRE(sr_decode_image("t.webp", lossy, n, &w, &h, &px, &e) == SR_OK);
    CHECK_EQ(w, TEX);
    long sum = 0;
    for (size_t i = 0; i < sizeof texels; i++) {
        sum += abs((int)px[i] - (int)texels[i]);
    }
    CHECK(sum / (long)sizeof texels < 8);
    free(px);
    WebPFree(lossy);

    /* Cut short, and damaged after its header: one message each. */
    CHECK_EQ(sr_decode_image("t.webp", webp.p, webp.n / 2, &w, &h, &px, &e), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(e.message, "t.webp: corrupt WebP");
    CHECK(px == NULL && w == 0);
    for (size_t i = 30; i < webp.n; i++) {
        webp.p[i] ^= 0x5A;
    }
    CHECK_EQ(sr_decode_image("t.webp", webp.p, webp.n, &w, &h, &px, &e), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(e.message, "t.webp: corrupt WebP");
    free(webp.p);
}

/* Renders model with the tool; the pixels, or NULL. */
static uint8_t *render(const char *model, const char *out)
{
    run_result r;
    if (!run(ARGS("render", model, "-o", out, "--size", "160x120", "--background", "#203040"),
             &r) ||
        r.status != 0 || r.err[0]) {
        FAILF("softrast render %s: status %d: %s", model, r.status, r.err);
        return NULL;
    }
    int w, h;
    uint8_t *px = NULL;
    sr_io_error e;
    if (sr_read_png(out, NULL, &w, &h, &px, &e) != SR_OK || w != 160 || h != 120) {
        FAILF("%s: %s", out, e.message);
    }
    return px;
}

SR_TEST(gltf_webp_textures_render_as_the_same_texels_in_png)
{
    NEED_CLI();
    static uint8_t texels[TEX * TEX * 4], red[TEX * TEX * 4];
    make_texels(texels);
    for (size_t i = 0; i < sizeof red; i += 4) {
        red[i] = 255, red[i + 1] = 0, red[i + 2] = 0, red[i + 3] = 255;
    }
    wbuf webp = webp_lossless(texels, TEX, TEX), png = png_of(texels, TEX, TEX),
         red_png = png_of(red, TEX, TEX);
    char *webp_uri = data_uri("image/webp", webp.p, webp.n);
    char *png_uri = data_uri("image/png", png.p, png.n);
    char *red_uri = data_uri("image/png", red_png.p, red_png.n);
    size_t cap = strlen(webp_uri) + strlen(png_uri) + strlen(red_uri) + 400;
    char *members = malloc(cap);
    char dir[1024], path[3][1100], out[3][1100];
    fresh_dir("webp_gltf", dir, sizeof dir);

    /* The texture in PNG; in WebP over a red PNG fallback; in WebP only. */
    snprintf(members, cap, "\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"%s\"}]",
             png_uri);
    char *model[3];
    model[0] = quad_model("", members);
    snprintf(members, cap,
             "\"textures\":[{\"source\":1,\"extensions\":{\"EXT_texture_webp\":{\"source\":0}}}],"
             "\"images\":[{\"uri\":\"%s\"},{\"uri\":\"%s\"}]",
             webp_uri, red_uri);
    model[1] = quad_model(",\"extensionsUsed\":[\"EXT_texture_webp\",\"KHR_materials_unlit\"]",
                          members);
    snprintf(members, cap,
             "\"textures\":[{\"extensions\":{\"EXT_texture_webp\":{\"source\":0}}}],"
             "\"images\":[{\"uri\":\"%s\",\"mimeType\":\"image/webp\"}]",
             webp_uri);
    model[2] = quad_model(",\"extensionsUsed\":[\"EXT_texture_webp\",\"KHR_materials_unlit\"],"
                          "\"extensionsRequired\":[\"EXT_texture_webp\"]",
                          members);
    uint8_t *px[3] = { NULL, NULL, NULL };
    for (int i = 0; i < 3; i++) {
        static const char *const names[] = { "png.gltf", "webp_over_png.gltf", "webp.gltf" };
        REQUIRE(write_text_file(dir, names[i], model[i], path[i], sizeof path[i]));
        snprintf(out[i], sizeof out[i], "%s/%.*s.png", dir, (int)strlen(names[i]) - 5,
                 names[i]);
        px[i] = render(path[i], out[i]);
    }
    /* In-process too: no warning, the texture in the base color slot. */
    sr_scene *s = NULL;
    sr_io_error e;
    sr_test_warnings warnings = {0};
    sr_load_desc desc = { .warn = sr_test_collect_warning, .user = &warnings };
    CHECK_EQ(sr_load_scene(sr_test_ctx(), path[2], &desc, &s, &e), SR_OK);
    CHECK_EQ(warnings.count, 0);
    if (s) {
        CHECK(s->materials[0].base_color_texture.texture != NULL);
        sr_destroy_scene(sr_test_ctx(), s);
    }
    if (px[0] && px[1] && px[2]) {
        /* The same texels through the same pipeline: the same bytes. */
        sr_test_compare_images("webp_over_png_fallback", px[1], px[0], 160, 120, 0, 0);
        sr_test_compare_images("webp_only", px[2], px[0], 160, 120, 0, 0);
    }
    for (int i = 0; i < 3; i++) {
        free(px[i]);
        free(model[i]);
    }
    free(members);
    free(webp_uri);
    free(png_uri);
    free(red_uri);
    free(webp.p);
    free(png.p);
    free(red_png.p);
}

SR_TEST(obj_map_kd_reads_a_webp_texture)
{
    NEED_CLI();
    static uint8_t texels[TEX * TEX * 4];
    make_texels(texels);
    char dir[1024], p[1100];
    fresh_dir("webp_obj", dir, sizeof dir);
    wbuf webp = webp_lossless(texels, TEX, TEX), png = png_of(texels, TEX, TEX);
    snprintf(p, sizeof p, "%s/tex.webp", dir);
    REQUIRE(sr_test_write_file(p, webp.p, webp.n));
    snprintf(p, sizeof p, "%s/tex.png", dir);
    REQUIRE(sr_test_write_file(p, png.p, png.n));
    static const char obj[] = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                              "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                              "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
    char text[400];
    snprintf(text, sizeof text, "mtllib webp.mtl\nusemtl m\n%s", obj);
    REQUIRE(write_text_file(dir, "webp.obj", text, p, sizeof p));
    snprintf(text, sizeof text, "mtllib png.mtl\nusemtl m\n%s", obj);
    REQUIRE(write_text_file(dir, "png.obj", text, p, sizeof p));
    REQUIRE(write_text_file(dir, "webp.mtl", "newmtl m\nKd 1 1 1\nmap_Kd tex.webp\n", p,
                            sizeof p));
    REQUIRE(write_text_file(dir, "png.mtl", "newmtl m\nKd 1 1 1\nmap_Kd tex.png\n", p,
                            sizeof p));
    char a[1100], b[1100], ao[1100], bo[1100];
    snprintf(a, sizeof a, "%s/png.obj", dir);
    snprintf(b, sizeof b, "%s/webp.obj", dir);
    snprintf(ao, sizeof ao, "%s/png.png", dir);
    snprintf(bo, sizeof bo, "%s/webp.png", dir);
    uint8_t *pa = render(a, ao), *pb = render(b, bo);
    if (pa && pb) {
        sr_test_compare_images("webp_obj", pb, pa, 160, 120, 0, 0);
    }
    free(pa);
    free(pb);
    free(webp.p);
    free(png.p);
}

SR_TEST(a_damaged_gltf_webp_is_one_line_and_exit_2)
{
    NEED_CLI();
    static uint8_t texels[TEX * TEX * 4];
    make_texels(texels);
    wbuf webp = webp_lossless(texels, TEX, TEX);
    char *uri = data_uri("image/webp", webp.p, webp.n / 2);
    size_t cap = strlen(uri) + 200;
    char *members = malloc(cap);
    snprintf(members, cap,
             "\"textures\":[{\"extensions\":{\"EXT_texture_webp\":{\"source\":0}}}],"
             "\"images\":[{\"uri\":\"%s\"}]",
             uri);
    char *model = quad_model(",\"extensionsRequired\":[\"EXT_texture_webp\"]", members);
    char dir[1024], path[1100], out[1100];
    fresh_dir("webp_bad", dir, sizeof dir);
    REQUIRE(write_text_file(dir, "cut.gltf", model, path, sizeof path));
    snprintf(out, sizeof out, "%s/cut.png", dir);
    run_result r;
    if (run(ARGS("render", path, "-o", out), &r)) {
        CHECK_EQ(r.status, 2);
        CHECK_EQ(count_lines(r.err), 1);
        CHECK_STR_CONTAINS(r.err, "/images/0: corrupt WebP");
        CHECK(!file_exists(out));
    }
    free(model);
    free(members);
    free(uri);
    free(webp.p);
}

#endif

/* Without libwebp a file requiring the extension is refused naming the
 * library, and WebP bytes say what is missing. */
SR_TEST(without_libwebp_webp_is_refused_naming_the_library)
{
#ifdef SR_HAVE_WEBP_TEST
    SKIP("this build reads WebP");
#else
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    char *model = quad_model(",\"extensionsRequired\":[\"EXT_texture_webp\"]",
                             "\"textures\":[{\"extensions\":{\"EXT_texture_webp\":"
                             "{\"source\":0}}}],\"images\":[{\"uri\":\"t.webp\"}]");
    sr_scene *s = NULL;
    sr_io_error e;
    CHECK_EQ(sr_parse_gltf(sr_test_ctx(), "t.gltf", (const uint8_t *)model, strlen(model), NULL,
                           &s, &e),
             SR_UNSUPPORTED);
    CHECK_STR_CONTAINS(e.message, "/extensionsRequired/0: extension EXT_texture_webp is not "
                                  "supported (softrast was built without libwebp)");
    static const uint8_t riff[16] = { 'R', 'I', 'F', 'F', 8, 0, 0, 0, 'W', 'E', 'B', 'P' };
    int w, h;
    uint8_t *px;
    CHECK_EQ(sr_decode_image("t.webp", riff, sizeof riff, &w, &h, &px, &e), SR_UNSUPPORTED);
    CHECK_STR_CONTAINS(e.message, "t.webp: a WebP image, which cannot be read (softrast was built without libwebp");
    free(model);
#endif
}
