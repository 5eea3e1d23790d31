/* test_gltf_metadata.c - what a glTF file says about itself
 * (sr_scene.metadata): the asset's version, generator and copyright, the
 * KHR_xmp_json_ld packet the asset references as the file gives it and
 * its licence and authorship properties as text (tests/data/gltf); a bad
 * reference is one warning with its JSON pointer and the model is read;
 * the extension itself is read, so it is no "not read" warning. */
#include "sr_test.h"

#include "softrast_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

SR_TEST_NEEDS(sr_io_have_gltf, "softrast was built without jansson")

typedef struct warnings {
    int count;
    char last[1024];
} warnings;

static void keep_warning(void *user, const char *message)
{
    warnings *w = user;
    w->count++;
    snprintf(w->last, sizeof w->last, "%s", message);
}

/* tests/data/gltf/NAME read with its warnings into w; NULL after a
 * failed check. */
static sr_scene *load_data(sr_context *ctx, const char *name, warnings *w)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/data/gltf/%s", sr_test_src_dir(), name);
    sr_scene *s = NULL;
    sr_io_error err;
    sr_result r = sr_load_scene(ctx, path, &(sr_load_desc){ .warn = keep_warning, .user = w }, &s,
                                &err);
    if (r != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "%s: %s", name, err.message);
    }
    return s;
}

/* A property's text, or NULL when the scene does not list it. */
static const char *property(const sr_scene *s, const char *name)
{
    for (size_t i = 0; i < s->metadata.property_count; i++) {
        if (strcmp(s->metadata.properties[i].name, name) == 0) {
            return s->metadata.properties[i].value;
        }
    }
    return NULL;
}

#define CHECK_STR(a, b)                                                              \
    do {                                                                             \
        const char *sr__s = (a);                                                     \
        if (!sr__s || strcmp(sr__s, (b)) != 0)                                       \
            sr_test_fail(__FILE__, __LINE__, "%s: \"%s\", not \"%s\"", #a,           \
                         sr__s ? sr__s : "(null)", (b));                             \
    } while (0)

SR_TEST(the_asset_and_its_xmp_packet_are_read)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    warnings w = { 0 };
    sr_scene *s = load_data(ctx, "xmp_metadata.gltf", &w);
    REQUIRE(s);
    CHECK_EQ(w.count, 0); /* KHR_xmp_json_ld is read: no "not read" warning */
    const sr_scene_metadata *m = &s->metadata;
    CHECK_STR(m->version, "2.0");
    CHECK(m->min_version == NULL);
    CHECK_STR(m->generator, "tests/data/gltf (written by hand)");
    CHECK_STR(m->copyright, "2026 Ada Example, CC BY 4.0");
    CHECK_EQ(m->xmp_packet_index, 0);
    /* the packet as the file gives it, members in its order */
    CHECK_STR_CONTAINS(m->xmp_packet,
                       "{\"@context\":{\"dc\":\"http://purl.org/dc/elements/1.1/\",");
    CHECK_STR_CONTAINS(m->xmp_packet, "\"dc:subject\":{\"@set\":[\"test\",\"triangle\"]}}");
    CHECK(!strstr(m->xmp_packet, "the mesh alone")); /* packet 1 is the mesh's */
    /* listed in sr_scene_metadata's order, not the file's */
    REQUIRE(m->property_count == 5);
    CHECK_STR(m->properties[0].name, "dc:title");
    CHECK_STR(m->properties[4].name, "xmpRights:Marked");
    CHECK_STR(property(s, "dc:title"), "Corner triangle [en-us], Triangolo d'angolo [it-it]");
    CHECK_STR(property(s, "dc:creator"), "Ada Example, Bo Sample <bo@example.org>");
    CHECK_STR(property(s, "dc:rights"), "CC BY 4.0");
    CHECK_STR(property(s, "xmpRights:UsageTerms"),
              "Attribution required: \"Corner triangle\" by Ada Example");
    CHECK_STR(property(s, "xmpRights:Marked"), "true");
    CHECK(property(s, "dc:subject") == NULL);
    CHECK_EQ(s->primitive_count, 1);
    sr_destroy_scene(ctx, s);
    sr_destroy_context(ctx);
}

SR_TEST(a_reference_to_no_packet_is_a_warning_and_the_model_is_read)
{
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    warnings w = { 0 };
    sr_scene *s = load_data(ctx, "xmp_bad_packet.gltf", &w);
    REQUIRE(s);
    CHECK_EQ(w.count, 1);
    CHECK_EQ(s->warning_count, 1);
    CHECK_STR_CONTAINS(w.last, "xmp_bad_packet.gltf: warning: /asset/extensions/KHR_xmp_json_ld/"
                               "packet: 2 is not an index below 2 (/extensions/KHR_xmp_json_ld/"
                               "packets), the asset's metadata is left out");
    CHECK(s->metadata.xmp_packet == NULL);
    CHECK_EQ(s->metadata.xmp_packet_index, -1);
    CHECK_EQ(s->metadata.property_count, 0);
    CHECK_STR(s->metadata.copyright, "2026 Ada Example, CC BY 4.0"); /* the rest is kept */
    CHECK_EQ(s->primitive_count, 1);
    sr_destroy_scene(ctx, s);
    sr_destroy_context(ctx);
}

/* Each malformed piece of the metadata: its warning, and nothing else
 * lost (the triangle is drawn). */
SR_TEST(malformed_metadata_warns_with_its_pointer)
{
    static const char head[] =
        "{\"asset\":{\"version\":\"2.0\"%s},%s"
        "\"buffers\":[{\"byteLength\":36,\"uri\":\"data:application/octet-stream;base64,"
        "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA\"}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
        "\"min\":[0,0,0],\"max\":[1,1,0]}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
        "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]}";
    static const char packets[] =
        "\"extensions\":{\"KHR_xmp_json_ld\":{\"packets\":[{\"@context\":{}},7]}},";
    struct {
        const char *asset, *root, *says;
    } cases[] = {
        { ",\"extensions\":{\"KHR_xmp_json_ld\":{\"packet\":-1}}", packets,
          "/asset/extensions/KHR_xmp_json_ld/packet: -1 is not an index below 2" },
        { ",\"extensions\":{\"KHR_xmp_json_ld\":{\"packet\":0.5}}", packets,
          "/asset/extensions/KHR_xmp_json_ld/packet: not an integer" },
        { ",\"extensions\":{\"KHR_xmp_json_ld\":{}}", packets,
          "/asset/extensions/KHR_xmp_json_ld/packet: missing" },
        { ",\"extensions\":{\"KHR_xmp_json_ld\":3}", packets,
          "/asset/extensions/KHR_xmp_json_ld: not an object" },
        { ",\"extensions\":{\"KHR_xmp_json_ld\":{\"packet\":1}}", packets,
          "/extensions/KHR_xmp_json_ld/packets/1: not an object" },
        { "", "\"extensions\":{\"KHR_xmp_json_ld\":{\"packets\":{}}},",
          "/extensions/KHR_xmp_json_ld/packets: not an array" },
        { ",\"copyright\":7", "", "/asset/copyright: not a string, left out" },
    };
    sr_context *ctx = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char doc[2048];
        snprintf(doc, sizeof doc, head, cases[i].asset, cases[i].root);
        warnings w = { 0 };
        sr_scene *s = NULL;
        sr_io_error err;
        sr_result r = sr_parse_gltf(ctx, "m.gltf", (const uint8_t *)doc, strlen(doc),
                                    &(sr_load_desc){ .warn = keep_warning, .user = &w }, &s, &err);
        CHECK_EQ(r, SR_OK);
        if (r != SR_OK) {
            sr_test_fail(__FILE__, __LINE__, "case %zu: %s", i, err.message);
            continue;
        }
        CHECK_EQ(w.count, 1);
        CHECK_STR_CONTAINS(w.last, cases[i].says);
        CHECK_STR_CONTAINS(w.last, "m.gltf: warning: /");
        CHECK(s->metadata.xmp_packet == NULL);
        CHECK(s->metadata.copyright == NULL);
        CHECK_EQ(s->primitive_count, 1);
        sr_destroy_scene(ctx, s);
    }
    sr_destroy_context(ctx);
}
