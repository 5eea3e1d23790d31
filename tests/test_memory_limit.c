/* test_memory_limit.c - the memory limit as a library call (softrast_io.h):
 * sr_query_memory_limit reads SR_MEMORY_LIMIT in its spellings and
 * refuses a malformed one, sr_check_memory compares an estimate with it
 * in one line naming both, and both check their arguments.  The softrast
 * tool and the Python package print these lines (test_cli.c,
 * python/tests/test_memory_limit.py). */
#include "softrast_io.h"
#include "sr_test.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define CHECK_STR_EQ(got, want)                                                                 \
    do {                                                                                       \
        const char *got_ = (got), *want_ = (want);                                             \
        if (strcmp(got_, want_) != 0)                                                          \
            sr_test_fail(__FILE__, __LINE__, "\"%s\" is not \"%s\"", got_, want_);             \
    } while (0)

SR_TEST(memory_limit_spellings_are_read)
{
    static const struct {
        const char *text;
        uint64_t bytes;
    } ok[] = { { "1048576", 1048576 }, { "1M", 1048576 }, { "1Mi", 1048576 },
               { "1MiB", 1048576 }, { "1MB", 1048576 }, { "1.5k", 1536 },
               { "0.0009765625G", 1048576 }, { "2T", (uint64_t)2 << 40 } };
    for (size_t i = 0; i < sizeof ok / sizeof ok[0]; i++) {
        REQUIRE(setenv("SR_MEMORY_LIMIT", ok[i].text, 1) == 0);
        sr_memory_limit_info info;
        CHECK_EQ(sr_query_memory_limit(&info, NULL), SR_OK);
        CHECK_EQ(info.bytes, ok[i].bytes);
        CHECK(info.from_environment);
        char source[64];
        snprintf(source, sizeof source, "SR_MEMORY_LIMIT=%s", ok[i].text);
        CHECK_STR_EQ(info.source, source);
    }
    unsetenv("SR_MEMORY_LIMIT");
}

SR_TEST(malformed_memory_limit_is_named)
{
    static const char *const bad[] = { "", "lots", "-5", "0", "8X", "8GBs", "0x100", " 8G",
                                       "inf", "nan", "1e30", "8G " };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        REQUIRE(setenv("SR_MEMORY_LIMIT", bad[i], 1) == 0);
        sr_memory_limit_info info = { .bytes = 7 };
        sr_io_error err = { { 0 } };
        CHECK_EQ(sr_query_memory_limit(&info, &err), SR_INVALID_ARG);
        CHECK_EQ(info.bytes, 7);
        char want[128];
        snprintf(want, sizeof want,
                 "SR_MEMORY_LIMIT: expected a size in bytes such as 512M or 8G (got '%s')", bad[i]);
        CHECK_STR_EQ(err.message, want);
        CHECK_EQ(sr_check_memory(&(sr_memory_check_desc){ .what = "w", .bytes = 1, .lower = "l" },
                                 &err),
                 SR_INVALID_ARG);
        CHECK_STR_EQ(err.message, want);
    }
    unsetenv("SR_MEMORY_LIMIT");
}

SR_TEST(an_estimate_beyond_the_limit_is_refused_in_one_line)
{
    REQUIRE(setenv("SR_MEMORY_LIMIT", "1M", 1) == 0);
    sr_io_error err = { { 0 } };
    sr_memory_check_desc desc = { .what = "Canvas: 512 x 512", .bytes = 1048576,
                                  .memory = "image memory", .lower = "give a smaller size" };
    CHECK_EQ(sr_check_memory(&desc, &err), SR_OK);
    desc.bytes++;
    CHECK_EQ(sr_check_memory(&desc, &err), SR_TOO_LARGE);
    CHECK_STR_EQ(err.message, "Canvas: 512 x 512 needs about 1.0 MiB of image memory, more than "
                              "SR_MEMORY_LIMIT=1M allows: give a smaller size");
    desc.memory = NULL;
    desc.bytes = (uint64_t)17 << 30;
    CHECK_EQ(sr_check_memory(&desc, &err), SR_TOO_LARGE);
    CHECK_STR_EQ(err.message, "Canvas: 512 x 512 needs about 17 GiB of memory, more than "
                              "SR_MEMORY_LIMIT=1M allows: give a smaller size");
    unsetenv("SR_MEMORY_LIMIT");
    /* Without it: the machine's memory (or a ulimit), named with the way to set another. */
    sr_memory_limit_info info;
    REQUIRE(sr_query_memory_limit(&info, NULL) == SR_OK);
    CHECK(!info.from_environment);
    CHECK(info.bytes > 0);
    if (info.bytes < UINT64_MAX) {
        desc.bytes = UINT64_MAX;
        CHECK_EQ(sr_check_memory(&desc, &err), SR_TOO_LARGE);
        char want[256];
        snprintf(want, sizeof want, "of %s (SR_MEMORY_LIMIT sets another limit): give a smaller size",
                 info.source);
        CHECK(strstr(err.message, "Canvas: 512 x 512 needs about ") == err.message);
        CHECK(strstr(err.message, want) != NULL);
    }
}

SR_TEST(memory_check_arguments_are_checked)
{
    sr_io_error err = { { 0 } };
    CHECK_EQ(sr_query_memory_limit(NULL, &err), SR_INVALID_ARG);
    CHECK_EQ(sr_check_memory(NULL, &err), SR_INVALID_ARG);
    CHECK_STR_EQ(err.message, "sr_check_memory: desc is NULL");
    CHECK_EQ(sr_check_memory(&(sr_memory_check_desc){ .what = "", .lower = "l" }, &err),
             SR_INVALID_ARG);
    CHECK_STR_EQ(err.message, "sr_check_memory: sr_memory_check_desc.what must be set");
    CHECK_EQ(sr_check_memory(&(sr_memory_check_desc){ .what = "w" }, NULL), SR_INVALID_ARG);
}
