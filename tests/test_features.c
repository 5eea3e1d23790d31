/* test_features.c - sr_io_features names exactly what this build found:
 * the list CMake computed from its own findings (SR_TEST_FEATURES), and
 * the readers' own answers where they have one. */
#include "softrast_io.h"
#include "sr_test.h"

#include <stdbool.h>
#include <string.h>

static bool has(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = list; (p = strstr(p, name)) != NULL; p += n) {
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) {
            return true;
        }
    }
    return false;
}

SR_TEST(features_are_what_the_build_found)
{
    const char *f = sr_io_features();
    REQUIRE(f);
    printf("sr_io_features: \"%s\"\n", f);
    CHECK(strcmp(f, SR_TEST_FEATURES) == 0);
    /* Single spaces between names, none at the ends. */
    CHECK(f[0] != ' ' && strstr(f, "  ") == NULL);
    CHECK(f[0] == '\0' || f[strlen(f) - 1] != ' ');
}

SR_TEST(features_agree_with_the_readers)
{
    const char *f = sr_io_features();
    CHECK_EQ(has(f, "gltf"), sr_io_have_gltf());
    CHECK_EQ(has(f, "jpeg"), sr_io_have_jpeg());
    CHECK_EQ(has(f, "svg"), sr_io_have_svg());
    CHECK_EQ(has(f, "text"), sr_io_have_text());
    CHECK_EQ(has(f, "assimp"), sr_io_have_assimp());
    /* What needs another feature comes with it. */
    CHECK(!has(f, "svgz") || has(f, "svg"));
    CHECK(!has(f, "bidi") || has(f, "text"));
    CHECK(!has(f, "meshopt") || has(f, "gltf"));
    CHECK(!has(f, "draco") || has(f, "gltf"));
    CHECK(!has("svgz", "svg"));
}
