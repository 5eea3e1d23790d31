/*
 * sr_test.h - the small test harness every test executable uses.
 *
 * A test is a function declared with SR_TEST(name); it registers itself and
 * tests/sr_test.c's main() runs every registered test, or only those named on
 * the command line, and closes with "N passed, N failed, N skipped".
 * CHECK* record a failure with file:line and carry on; REQUIRE* stop the
 * current test.  SKIP(msg) ends the test as skipped (e.g. no shared models).
 */
#ifndef SR_TEST_H
#define SR_TEST_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stddef.h>
#include <string.h> /* strstr in CHECK_STR_CONTAINS */

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef void (*sr_test_fn)(void);
void sr_test_register(const char *name, sr_test_fn fn);
void sr_test_fail(const char *file, int line, const char *fmt, ...);
void sr_test_skip(const char *why);
bool sr_test_failed_now(void);
/* ../shared/models, or NULL when that folder is absent. */
const char *sr_test_models_dir(void);
/* Directory the tests may write into (the build's tests/out). */
const char *sr_test_out_dir(void);
/* A one-thread context for tests that need one only to own meshes (made
 * on first use, destroyed at exit). */
struct sr_context;
struct sr_context *sr_test_ctx(void);
/* Warnings a reader hands its callback (sr_svg_desc.warn): how many, and
 * their text, each followed by '|' (cut at the buffer's end). */
typedef struct sr_test_warnings {
    int count;
    char text[2048];
} sr_test_warnings;
/* The callback; user is an sr_test_warnings. */
void sr_test_collect_warning(void *user, const char *message);
/* Source tree's tests/ directory (reference images, data). */
const char *sr_test_src_dir(void);
/* A whole file, malloc'd (free it), or NULL when it cannot be opened. */
uint8_t *sr_test_read_file(const char *path, size_t *size);
/* Write a whole file; false when it cannot be written. */
bool sr_test_write_file(const char *path, const void *data, size_t size);
/* Run the built softrast CLI with args (NULL-terminated, without the
 * program name), no shell; its exit status, or -1 if it could not run. */
int sr_test_run_cli(const char *const *args);
/* The argument vector that starts the built program `path` with args
 * (NULL-terminated, without the program name) into argv[0 .. cap - 1],
 * NULL-terminated: path and args, or in a cross build tested under an
 * emulator (SR_TEST_EMULATED: CMake's CMAKE_CROSSCOMPILING_EMULATOR, such
 * as scripts/cross-test.sh's qemu-user) the emulator's words before them,
 * since the host cannot start the target's programs itself.  Start
 * argv[0].  False when cap is too small. */
bool sr_test_program_argv(const char *path, const char *const *args, const char **argv,
                          size_t cap);
/* How many times longer than natively a started program may take: 1, or
 * under an emulator 20 (qemu-user runs softrast 10 to 20 times slower);
 * for the waits of tests that watch a program run, not for timing it. */
#ifdef SR_TEST_EMULATED
#define SR_TEST_SLOWDOWN 20
#else
#define SR_TEST_SLOWDOWN 1
#endif

#define SR_TEST(name)                                                        \
    static void name(void);                                                  \
    __attribute__((constructor)) static void name##__register(void)          \
    {                                                                        \
        sr_test_register(#name, name);                                       \
    }                                                                        \
    static void name(void)

#define CHECK(cond)                                                          \
    do {                                                                     \
        if (!(cond)) sr_test_fail(__FILE__, __LINE__, "CHECK(%s)", #cond);   \
    } while (0)

#define CHECK_EQ(a, b)                                                       \
    do {                                                                     \
        long long sr__a = (long long)(a), sr__b = (long long)(b);            \
        if (sr__a != sr__b)                                                  \
            sr_test_fail(__FILE__, __LINE__, "CHECK_EQ(%s, %s): %lld != %lld", \
                         #a, #b, sr__a, sr__b);                              \
    } while (0)

#define CHECK_NEAR(a, b, tol)                                                \
    do {                                                                     \
        double sr__a = (double)(a), sr__b = (double)(b);                     \
        if (!(sr__a - sr__b <= (tol) && sr__b - sr__a <= (tol)))             \
            sr_test_fail(__FILE__, __LINE__,                                 \
                         "CHECK_NEAR(%s, %s, %g): %.9g vs %.9g",             \
                         #a, #b, (double)(tol), sr__a, sr__b);               \
    } while (0)

#define CHECK_STR_CONTAINS(hay, needle)                                      \
    do {                                                                     \
        const char *sr__h = (hay), *sr__n = (needle);                        \
        if (!sr__h || !strstr(sr__h, sr__n))                                 \
            sr_test_fail(__FILE__, __LINE__, "\"%s\" does not contain \"%s\"", \
                         sr__h ? sr__h : "(null)", sr__n);                   \
    } while (0)

#define REQUIRE(cond)                                                        \
    do {                                                                     \
        if (!(cond)) {                                                       \
            sr_test_fail(__FILE__, __LINE__, "REQUIRE(%s)", #cond);          \
            return;                                                          \
        }                                                                    \
    } while (0)

/* Every test of a file needs what `have` says the build has (a library
 * it may be built without): SR_TEST_NEEDS(sr_io_have_gltf, "softrast was
 * built without jansson") at file scope skips each with `why` when it
 * returns false, so that the file needs no SKIP in each test. */
void sr_test_needs(bool (*have)(void), const char *why);
#define SR_TEST_NEEDS(have, why)                                             \
    __attribute__((constructor)) static void sr_test_needs__register(void)   \
    {                                                                        \
        sr_test_needs(have, why);                                            \
    }

#define SKIP(why)                                                            \
    do {                                                                     \
        sr_test_skip(why);                                                   \
        return;                                                              \
    } while (0)

/* Deterministic PRNG for property tests (xorshift64*); fixed seeds only. */
typedef struct sr_rng { uint64_t s; } sr_rng;
static inline uint64_t sr_rng_next(sr_rng *r)
{
    r->s ^= r->s >> 12;
    r->s ^= r->s << 25;
    r->s ^= r->s >> 27;
    return r->s * 2685821657736338717ULL;
}
static inline double sr_rng_unit(sr_rng *r) /* [0, 1) */
{
    return (double)(sr_rng_next(r) >> 11) * (1.0 / 9007199254740992.0);
}
static inline double sr_rng_range(sr_rng *r, double lo, double hi)
{
    return lo + (hi - lo) * sr_rng_unit(r);
}
static inline int sr_rng_int(sr_rng *r, int lo, int hi) /* [lo, hi] */
{
    return lo + (int)(sr_rng_next(r) % (uint64_t)(hi - lo + 1));
}

#endif
