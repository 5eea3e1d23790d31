/* test_json_pointer.c - the JSON pointers the glTF reader builds for its
 * messages (src/io/json_pointer.c) are the bytes snprintf writes for the
 * same format and arguments, cut alike at every buffer size. */
#include "sr_test.h"
#include "io/io_util.h"

#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

/* Cutting is the point: every size from none to the whole. */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wformat-truncation"
#endif

/* Fills both buffers with a marker, then both formats at every size up
 * to `n`; the bytes past the terminator must stay untouched too. */
#define SAME_AS_SNPRINTF(n, ...)                                                   \
    do {                                                                           \
        for (size_t cap = 0; cap <= (n); cap++) {                                  \
            char want[96], got[96];                                                \
            memset(want, '#', sizeof want);                                        \
            memset(got, '#', sizeof got);                                          \
            snprintf(want, cap, __VA_ARGS__);                                      \
            sr__json_pointer(got, cap, __VA_ARGS__);                               \
            if (memcmp(want, got, sizeof want) != 0) {                             \
                sr_test_fail(__FILE__, __LINE__, "size %zu: \"%.*s\", not \"%.*s\"", \
                             cap, (int)(cap ? cap - 1 : 0), got,                   \
                             (int)(cap ? cap - 1 : 0), want);                      \
            }                                                                      \
        }                                                                          \
    } while (0)

SR_TEST(pointers_are_what_snprintf_writes)
{
    SAME_AS_SNPRINTF(40, "/accessors/%ld", 12L);
    SAME_AS_SNPRINTF(40, "/accessors/%ld", 0L);
    SAME_AS_SNPRINTF(40, "%s/bufferView", "/accessors/7");
    SAME_AS_SNPRINTF(40, "/%s/%ld", "bufferViews", 1234567L);
    SAME_AS_SNPRINTF(60, "/meshes/%ld/primitives/%zu", 3L, (size_t)19);
    SAME_AS_SNPRINTF(40, "%s/%s", "/meshes/0/primitives/0/attributes", "TEXCOORD_1");
    SAME_AS_SNPRINTF(40, "%s/lights/%zu", "", (size_t)0);
    SAME_AS_SNPRINTF(40, "/nodes/%d/x", -42);
    SAME_AS_SNPRINTF(40, "%ld", LONG_MIN);
    SAME_AS_SNPRINTF(40, "%ld", LONG_MAX);
    SAME_AS_SNPRINTF(40, "%d:%d", INT_MIN, INT_MAX);
    SAME_AS_SNPRINTF(40, "%zu", SIZE_MAX);
    SAME_AS_SNPRINTF(40, "no conversion");
    SAME_AS_SNPRINTF(8, "%s", "");
}
