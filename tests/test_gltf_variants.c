/* test_gltf_variants.c - KHR_materials_variants: the variant names on the
 * scene, each primitive's materials by variant, sr_load_desc.variant's
 * choice (a primitive the variant does not map keeps its own material),
 * one message with the JSON pointer for each malformed mapping, and
 * `softrast render --variant` by name and number, its errors and -v's
 * list. */
#include "batch_cli.h"
#include "gltf_write.h"
#include "image_compare.h"

#include "softrast_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Own materials: 0 magenta (quad 0, left), 1 yellow (quad 1, right);
 * the variants' 2 red, 3 green, 4 blue; all unlit, so that the pixels
 * show the base color. */
#define UNLIT(rgb) \
    "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[" rgb ",1]}," \
    "\"extensions\":{\"KHR_materials_unlit\":{}}}"
#define MATERIALS \
    ",\"materials\":[" UNLIT("1,0,1") "," UNLIT("1,1,0") "," UNLIT("1,0,0") "," \
    UNLIT("0,1,0") "," UNLIT("0,0,1") "]"
#define VARIANTS_USED \
    ",\"extensionsUsed\":[\"KHR_materials_unlit\",\"KHR_materials_variants\"]"
#define TWO_VARIANTS \
    ",\"extensions\":{\"KHR_materials_variants\":{\"variants\":[{\"name\":\"Red\"}," \
    "{\"name\":\"Green\"}]}}"
/* Red: quad 0 red, quad 1 blue; Green: quad 0 green, quad 1 its own. */
#define MAP0 "[{\"material\":2,\"variants\":[0]},{\"material\":3,\"variants\":[1],\"name\":\"g\"}]"
#define MAP1 "[{\"material\":4,\"variants\":[0]}]"

/* Two quads side by side in z = 0, facing +z, with `root` (the top
 * level's extensions) and each primitive's mappings (NULL: none). */
static char *variants_model(const char *root, const char *map0, const char *map1)
{
    static const gltf_quad quads[2] = { { -2.0f, -0.8f, -0.1f, 0.8f, 0 },
                                        { 0.1f, -0.8f, 2.0f, 0.8f, 1 } };
    char tail[2000];
    snprintf(tail, sizeof tail, "%s%s%s", MATERIALS, VARIANTS_USED, root);
    char *json = gltf_quads(quads, 2, tail);
    const char *const maps[2] = { map0, map1 };
    for (int q = 0; q < 2 && json; q++) {
        char from[40], to[1200];
        if (!maps[q]) {
            continue;
        }
        snprintf(from, sizeof from, "\"material\":%d}", q);
        snprintf(to, sizeof to,
                 "\"material\":%d,\"extensions\":{\"KHR_materials_variants\":{\"mappings\":%s}}}",
                 q, maps[q]);
        json = text_replaced(json, from, to);
    }
    return json;
}

static sr_result parse_variant(const char *json, int variant, sr_scene **s, sr_io_error *e)
{
    sr_load_desc desc = { .variant = variant };
    return sr_parse_gltf(sr_test_ctx(), "v.gltf", (const uint8_t *)json, strlen(json), &desc, s,
                         e);
}

SR_TEST(variant_names_and_each_primitives_materials_are_read)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    char *json = variants_model(TWO_VARIANTS, MAP0, MAP1);
    REQUIRE(json);
    /* want[v][q]: quad q's material with sr_load_desc.variant v */
    static const int want[3][2] = { { 0, 1 }, { 2, 4 }, { 3, 1 } };
    for (int v = 0; v < 3; v++) {
        sr_scene *s = NULL;
        sr_io_error e;
        sr_result r = parse_variant(json, v, &s, &e);
        if (r != SR_OK) {
            FAILF("variant %d: %s", v, e.message);
            continue;
        }
        REQUIRE(s->variant_count == 2 && s->primitive_count == 2);
        CHECK(strcmp(s->variants[0], "Red") == 0);
        CHECK(strcmp(s->variants[1], "Green") == 0);
        CHECK_EQ(s->warning_count, 0);   /* the extension is not "not read" */
        for (int q = 0; q < 2; q++) {
            const sr_scene_primitive *p = &s->primitives[q];
            CHECK_EQ(p->material, want[v][q]);
            REQUIRE(p->variant_materials);
            for (int k = 0; k < 3; k++) {
                CHECK_EQ(p->variant_materials[k], want[k][q]);
            }
        }
        sr_destroy_scene(sr_test_ctx(), s);
    }
    free(json);
}

SR_TEST(a_primitive_without_mappings_and_a_file_without_variants_keep_their_materials)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    char *json = variants_model(TWO_VARIANTS, MAP0, NULL);
    sr_scene *s = NULL;
    sr_io_error e;
    REQUIRE(json && parse_variant(json, 1, &s, &e) == SR_OK);
    CHECK_EQ(s->primitives[0].material, 2);
    CHECK_EQ(s->primitives[1].material, 1);
    CHECK(s->primitives[1].variant_materials == NULL);
    sr_destroy_scene(sr_test_ctx(), s);
    free(json);
    json = variants_model("", NULL, NULL);
    REQUIRE(json && parse_variant(json, 0, &s, &e) == SR_OK);
    CHECK_EQ(s->variant_count, 0);
    CHECK(s->variants == NULL);
    sr_destroy_scene(sr_test_ctx(), s);
    free(json);
}

SR_TEST(a_variant_the_file_does_not_have_is_an_invalid_argument)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    char *json = variants_model(TWO_VARIANTS, MAP0, MAP1);
    sr_scene *s = (sr_scene *)json;
    sr_io_error e;
    REQUIRE(json);
    CHECK_EQ(parse_variant(json, 3, &s, &e), SR_INVALID_ARG);
    CHECK(s == NULL);
    CHECK_STR_CONTAINS(e.message, "v.gltf: sr_load_desc.variant: 3, but the file has 2 variants");
    CHECK_EQ(parse_variant(json, -1, &s, &e), SR_INVALID_ARG);
    free(json);
    /* Any other format has none. */
    char path[1100];
    snprintf(path, sizeof path, "%s/variants_tri.obj", sr_test_out_dir());
    REQUIRE(write_text(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    CHECK_EQ(sr_load_scene(sr_test_ctx(), path, &(sr_load_desc){ .variant = 1 }, &s, &e),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(e.message, "sr_load_desc.variant: 1, but the file has 0 variants");
}

typedef struct bad_mapping {
    const char *root, *map0;
    const char *message;
} bad_mapping;

#define PRIM0 "v.gltf: /meshes/0/primitives/0/extensions/KHR_materials_variants"

static const bad_mapping bad_mappings[] = {
    { TWO_VARIANTS, "[{\"material\":2,\"variants\":[0]},{\"material\":3,\"variants\":[1,0]}]",
      PRIM0 "/mappings/1/variants/1: variant 0 is already mapped by mappings/0 (each variant "
      "at most once per primitive)" },
    { TWO_VARIANTS, "[{\"material\":2,\"variants\":[0,0]}]",
      PRIM0 "/mappings/0/variants/1: variant 0 is already mapped by mappings/0" },
    { TWO_VARIANTS, "[{\"material\":2,\"variants\":[2]}]",
      PRIM0 "/mappings/0/variants/0: not a variant index below 2" },
    { TWO_VARIANTS, "[{\"material\":2,\"variants\":[\"Red\"]}]",
      PRIM0 "/mappings/0/variants/0: not a variant index below 2" },
    { TWO_VARIANTS, "[{\"material\":5,\"variants\":[0]}]",
      PRIM0 "/mappings/0/material: 5 is not an index below 5" },
    { TWO_VARIANTS, "[{\"variants\":[0]}]", PRIM0 "/mappings/0/material: missing" },
    { TWO_VARIANTS, "[{\"material\":2,\"variants\":[]}]",
      PRIM0 "/mappings/0/variants: missing or empty" },
    { TWO_VARIANTS, "[{\"material\":2,\"variants\":[0],\"name\":7}]",
      PRIM0 "/mappings/0/name: not a string" },
    { TWO_VARIANTS, "{}", PRIM0 "/mappings: not an array" },
    { TWO_VARIANTS, "[7]", PRIM0 "/mappings/0: not an object" },
    { "", "[{\"material\":2,\"variants\":[0]}]",
      PRIM0 "/mappings: the document defines no variants "
      "(/extensions/KHR_materials_variants/variants)" },
    { ",\"extensions\":{\"KHR_materials_variants\":{\"variants\":[{\"name\":\"Red\"},{}]}}",
      NULL, "v.gltf: /extensions/KHR_materials_variants/variants/1/name: missing or not a "
      "string" },
    { ",\"extensions\":{\"KHR_materials_variants\":{\"variants\":{}}}", NULL,
      "v.gltf: /extensions/KHR_materials_variants/variants: not an array" },
};

SR_TEST(malformed_variants_give_one_message_with_the_json_pointer)
{
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    for (size_t i = 0; i < sizeof bad_mappings / sizeof *bad_mappings; i++) {
        const bad_mapping *b = &bad_mappings[i];
        char *json = variants_model(b->root, b->map0, NULL);
        REQUIRE(json);
        sr_scene *s = (sr_scene *)json;
        sr_io_error e = { { 0 } };
        sr_result r = parse_variant(json, 0, &s, &e);
        if (r != SR_BAD_FORMAT || s != NULL ||
            strncmp(e.message, b->message, strlen(b->message)) != 0 || strchr(e.message, '\n')) {
            FAILF("case %zu: %s (%s), want %s", i, sr_result_name(r), e.message, b->message);
        }
        free(json);
    }
    /* The mappings' own "mappings" member is required. */
    char *json = variants_model(TWO_VARIANTS, "[]", NULL);
    json = text_replaced(json, "{\"mappings\":[]}", "{}");
    REQUIRE(json);
    sr_scene *s = NULL;
    sr_io_error e;
    CHECK_EQ(parse_variant(json, 0, &s, &e), SR_BAD_FORMAT);
    CHECK_STR_CONTAINS(e.message, PRIM0 "/mappings: missing");
    free(json);
}

/* ---- softrast render --variant ------------------------------------------ */

/* The model written into the test's directory as variants.gltf. */
static bool write_model(const char *dir, char *model, size_t cap)
{
    snprintf(model, cap, "%s/variants.gltf", dir);
    char *json = variants_model(TWO_VARIANTS, MAP0, MAP1);
    bool ok = json && write_text(model, json);
    free(json);
    return ok;
}

/* Pixels of each color the model can show: [0] red, green, blue, magenta,
 * yellow (a channel over 160 or under 60 each). */
static void count_colors(const uint8_t *px, int w, int h, long counts[5])
{
    static const uint8_t colors[5][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 },
                                          { 1, 0, 1 }, { 1, 1, 0 } };
    memset(counts, 0, 5 * sizeof *counts);
    for (long i = 0; i < (long)w * h; i++) {
        for (int c = 0; c < 5; c++) {
            bool match = true;
            for (int k = 0; k < 3; k++) {
                uint8_t v = px[4 * i + k];
                match &= colors[c][k] ? v > 160 : v < 60;
            }
            counts[c] += match;
        }
    }
}

/* Renders the model with --variant (NULL: none) into dir/NAME.png at
 * 64x48 and reads it back; NULL after a failed check. */
static uint8_t *render_variant(const char *dir, const char *model, const char *variant,
                               const char *name, int *w, int *h)
{
    char out[1200];
    snprintf(out, sizeof out, "%s/%s.png", dir, name);
    run_result r;
    uint8_t *px = variant ? render_read(ARGS("render", model, "--size", "64x48", "--variant",
                                             variant, "--threads", "1", "-o", out),
                                        out, w, h, &r)
                          : render_read(ARGS("render", model, "--size", "64x48", "--threads",
                                             "1", "-o", out),
                                        out, w, h, &r);
    CHECK(!px || strstr(r.err, "warning") == NULL);
    return px;
}

SR_TEST(render_draws_the_chosen_variants_base_colors)
{
    NEED_CLI();
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    char dir[1024], model[1100];
    fresh_dir("variants", dir, sizeof dir);
    REQUIRE(write_model(dir, model, sizeof model));
    int w, h;
    long none[5], red[5], green[5], by_number[5];
    uint8_t *px = render_variant(dir, model, NULL, "none", &w, &h);
    REQUIRE(px);
    count_colors(px, w, h, none);
    free(px);
    px = render_variant(dir, model, "Red", "red", &w, &h);
    REQUIRE(px);
    count_colors(px, w, h, red);
    free(px);
    uint8_t *by_name = render_variant(dir, model, "Green", "green", &w, &h);
    REQUIRE(by_name);
    count_colors(by_name, w, h, green);
    px = render_variant(dir, model, "1", "green_by_number", &w, &h);
    REQUIRE(px);
    count_colors(px, w, h, by_number);
    CHECK(memcmp(px, by_name, 4 * (size_t)w * (size_t)h) == 0);
    free(px);
    long min = (long)w * h / 20;   /* each quad covers far more */
    /* No variant: the primitives' own magenta and yellow. */
    CHECK(none[3] > min && none[4] > min && none[0] + none[1] + none[2] == 0);
    /* Red maps both quads: red and blue. */
    CHECK(red[0] > min && red[2] > min && red[1] + red[3] + red[4] == 0);
    /* Green maps quad 0 only: green, and quad 1's own yellow. */
    CHECK(green[1] > min && green[4] > min && green[0] + green[2] + green[3] == 0);
    /* Unlit, so the pixels are the base colors but for the edges. */
    sr_test_check_image("gltf_variant_green", by_name, w, h, 2, (long)w * h / 200);
    free(by_name);
}

SR_TEST(an_unknown_variant_is_one_line_listing_the_files_variants)
{
    NEED_CLI();
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    char dir[1024], model[1100], out[1200], obj[1200];
    fresh_dir("variants_bad", dir, sizeof dir);
    REQUIRE(write_model(dir, model, sizeof model));
    snprintf(out, sizeof out, "%s/out.png", dir);
    run_result r;
    REQUIRE(run(ARGS("render", model, "--variant", "Purple", "-o", out), &r));
    CHECK_EQ(r.status, 2);
    CHECK_EQ(count_lines(r.err), 1);
    CHECK_STR_CONTAINS(r.err, "variants.gltf: --variant Purple: no such variant (the file has "
                              "0 Red, 1 Green)");
    CHECK(!file_exists(out));
    REQUIRE(run(ARGS("render", model, "--variant", "2", "-o", out), &r));
    CHECK_EQ(r.status, 2);
    CHECK_STR_CONTAINS(r.err, "--variant 2: no such variant");
    REQUIRE(run(ARGS("render", model, "-o", out, "--variant"), &r));
    CHECK_EQ(r.status, 2);
    CHECK_EQ(count_lines(r.err), 1);
    CHECK_STR_CONTAINS(r.err, "--variant: missing value");
    /* A file without variants, and a format without them. */
    char *plain = variants_model("", NULL, NULL);
    char plain_path[1200];
    snprintf(plain_path, sizeof plain_path, "%s/plain.gltf", dir);
    REQUIRE(plain && write_text(plain_path, plain));
    free(plain);
    REQUIRE(run(ARGS("render", plain_path, "--variant", "Red", "-o", out), &r));
    CHECK_EQ(r.status, 2);
    CHECK_EQ(count_lines(r.err), 1);
    CHECK_STR_CONTAINS(r.err, "plain.gltf: --variant Red: the file has no material variants");
    snprintf(obj, sizeof obj, "%s/tri.obj", dir);
    REQUIRE(write_text(obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    REQUIRE(run(ARGS("render", obj, "--variant", "Red", "-o", out), &r));
    CHECK_EQ(r.status, 2);
    CHECK_EQ(count_lines(r.err), 1);
    CHECK_STR_CONTAINS(r.err, "tri.obj: --variant Red: not a glTF file");
    CHECK(!file_exists(out));
}

SR_TEST(verbose_lists_the_variants_and_the_one_drawn)
{
    NEED_CLI();
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    char dir[1024], model[1100], out[1200];
    fresh_dir("variants_verbose", dir, sizeof dir);
    REQUIRE(write_model(dir, model, sizeof model));
    snprintf(out, sizeof out, "%s/out.png", dir);
    run_result r;
    REQUIRE(run(ARGS("render", model, "--size", "16x16", "-v", "--variant", "Green", "-o", out),
                &r));
    CHECK_EQ(r.status, 0);
    CHECK_STR_CONTAINS(r.err, "variants.gltf: material variants 0 Red, 1 Green; drawn: Green");
}

SR_TEST(a_batch_draws_every_input_with_the_variant)
{
    NEED_CLI();
    if (!sr_io_have_gltf()) {
        SKIP("softrast was built without jansson");
    }
    char dir[1024], model[1100], outdir[1200], out[1300];
    fresh_dir("variants_batch", dir, sizeof dir);
    REQUIRE(write_model(dir, model, sizeof model));
    snprintf(outdir, sizeof outdir, "%s/out", dir);
    snprintf(out, sizeof out, "%s/variants.png", outdir);
    int w, h;
    run_result r;
    uint8_t *px = render_read(ARGS("render", dir, "--output-dir", outdir, "--size", "64x48",
                                   "--variant", "Red"),
                              out, &w, &h, &r);
    REQUIRE(px);
    long counts[5];
    count_colors(px, w, h, counts);
    CHECK(counts[0] > (long)w * h / 20 && counts[2] > (long)w * h / 20);
    CHECK(counts[1] + counts[3] + counts[4] == 0);
    free(px);
}
