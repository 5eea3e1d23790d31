/* sr_test.c - the runner behind sr_test.h: registry, failure records, main(). */
#include "sr_test.h"
#include "softrast.h"

#include <spawn.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#ifdef SR_TEST_EMULATED
#include "sr_test_emulator.h" /* SR_TEST_EMULATOR_WORDS, written by tests/CMakeLists.txt */
#endif

extern char **environ;

#define MAX_TESTS 1024

static struct { const char *name; sr_test_fn fn; } tests[MAX_TESTS];
static int test_count;
static int current_failures;
static const char *current_skip;
static bool (*file_has)(void);      /* SR_TEST_NEEDS */
static const char *file_lacks;

void sr_test_register(const char *name, sr_test_fn fn)
{
    if (test_count < MAX_TESTS) {
        tests[test_count].name = name;
        tests[test_count].fn = fn;
        test_count++;
    }
}

void sr_test_fail(const char *file, int line, const char *fmt, ...)
{
    va_list ap;
    /* Print the first few failures of a test; a property test may fail
     * thousands of times and one screenful says enough. */
    if (current_failures < 20) {
        fprintf(stderr, "%s:%d: ", file, line);
        va_start(ap, fmt);
        vfprintf(stderr, fmt, ap);
        va_end(ap);
        fputc('\n', stderr);
    }
    current_failures++;
}

void sr_test_skip(const char *why) { current_skip = why; }

void sr_test_needs(bool (*have)(void), const char *why)
{
    file_has = have;
    file_lacks = why;
}
bool sr_test_failed_now(void) { return current_failures > 0; }

static bool is_dir(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

const char *sr_test_models_dir(void)
{
    const char *env = getenv("SR_MODELS_DIR");
    if (env && is_dir(env)) {
        return env;
    }
    return is_dir(SR_SHARED_MODELS_DIR) ? SR_SHARED_MODELS_DIR : NULL;
}

const char *sr_test_out_dir(void)
{
    mkdir(SR_TEST_OUT_DIR, 0777);
    return SR_TEST_OUT_DIR;
}

static sr_context *test_ctx;

static void destroy_test_context(void)
{
    sr_destroy_context(test_ctx);
}

void sr_test_collect_warning(void *user, const char *message)
{
    sr_test_warnings *w = user;
    w->count++;
    size_t n = strlen(w->text);
    snprintf(w->text + n, sizeof w->text - n, "%s|", message);
}

sr_context *sr_test_ctx(void)
{
    if (!test_ctx) {
        if (sr_make_context(&(sr_context_desc){ .threads = 1 }, &test_ctx) != SR_OK) {
            fprintf(stderr, "sr_test_ctx: no context\n");
            exit(1);
        }
        atexit(destroy_test_context);
    }
    return test_ctx;
}

const char *sr_test_src_dir(void) { return SR_TEST_SRC_DIR; }

uint8_t *sr_test_read_file(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        return NULL;
    }
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    uint8_t *buf = malloc(n > 0 ? (size_t)n : 1);
    *size = buf ? fread(buf, 1, (size_t)n, f) : 0;
    fclose(f);
    return buf;
}

bool sr_test_write_file(const char *path, const void *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        return false;
    }
    bool ok = fwrite(data, 1, size, f) == size;
    return fclose(f) == 0 && ok;
}

bool sr_test_program_argv(const char *path, const char *const *args, const char **argv,
                          size_t cap)
{
    size_t n = 0;
#ifdef SR_TEST_EMULATED
    static const char *const emulator[] = { SR_TEST_EMULATOR_WORDS };
    for (size_t i = 0; i < sizeof emulator / sizeof emulator[0]; i++) {
        if (n + 1 >= cap) {
            return false;
        }
        argv[n++] = emulator[i];
    }
#endif
    if (n + 1 >= cap) {
        return false;
    }
    argv[n++] = path;
    for (size_t i = 0; args[i]; i++) {
        if (n + 1 >= cap) {
            return false;
        }
        argv[n++] = args[i];
    }
    argv[n] = NULL;
    return true;
}

int sr_test_run_cli(const char *const *args)
{
#ifdef SR_CLI_PATH
    const char *argv[80];
    if (!sr_test_program_argv(SR_CLI_PATH, args, argv, sizeof argv / sizeof argv[0])) {
        return -1;
    }
    pid_t pid;
    if (posix_spawn(&pid, argv[0], NULL, NULL, (char *const *)argv, environ) != 0) {
        return -1;
    }
    int status;
    if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status)) {
        return -1;
    }
    return WEXITSTATUS(status);
#else
    (void)args;
    return -1;
#endif
}

int main(int argc, char **argv)
{
    int passed = 0, failed = 0, skipped = 0;
    for (int i = 0; i < test_count; i++) {
        if (argc > 1) {
            bool wanted = false;
            for (int a = 1; a < argc; a++) {
                wanted |= strcmp(argv[a], tests[i].name) == 0;
            }
            if (!wanted) {
                continue;
            }
        }
        current_failures = 0;
        current_skip = NULL;
        if (file_has && !file_has()) {
            current_skip = file_lacks;
        } else {
            tests[i].fn();
        }
        if (current_failures) {
            printf("FAIL %s (%d failed checks)\n", tests[i].name, current_failures);
            failed++;
        } else if (current_skip) {
            printf("SKIP %s: %s\n", tests[i].name, current_skip);
            skipped++;
        } else {
            printf("ok   %s\n", tests[i].name);
            passed++;
        }
        fflush(stdout);
    }
    printf("%d passed, %d failed, %d skipped\n", passed, failed, skipped);
    return failed ? 1 : 0;
}
