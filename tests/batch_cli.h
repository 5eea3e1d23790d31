/* batch_cli.h - the softrast tool run as a batch's caller runs it, and
 * its --log read back (batch_cli.c), for the batch tests. */
#ifndef SR_TEST_BATCH_CLI_H
#define SR_TEST_BATCH_CLI_H

#include "sr_test.h"
#include "wbuf.h"

#include <stdbool.h>
#include <stddef.h>
#include <sys/types.h>

#define FAILF(...) sr_test_fail(__FILE__, __LINE__, __VA_ARGS__)
#define ARGS(...) ((const char *const[]){ __VA_ARGS__, NULL })
#define ENV(...) ((const char *const[]){ __VA_ARGS__, NULL })
#define NO_ENV ((const char *const[]){ NULL })

#ifdef SR_CLI_PATH
#define NEED_CLI() ((void)0)
#else
#define NEED_CLI() SKIP("the softrast tool is not part of this build")
#endif

/* Whether the tool reads SVG (was built with expat). */
bool cli_reads_svg(void);
#define NEED_SVG()                                                     \
    do {                                                               \
        NEED_CLI();                                                    \
        if (!cli_reads_svg()) {                                        \
            SKIP("softrast was built without expat");                  \
        }                                                              \
    } while (0)

typedef struct run_result {
    int status;         /* exit status, 128 + signal when killed, -1 when not run */
    char err[8192];     /* stderr, NUL-terminated (cut at the buffer's size) */
} run_result;

/* One record of a --log file: the fields a pipeline reads. */
typedef struct record {
    char input[1200], output[1200], status[16], error[1024];
    bool error_null;
    double index, triangles, load_ms, render_ms, encode_ms, ms;
    int fields;
} record;

/* Start SR_CLI_PATH with args and an environment of this process's
 * without the schedulers' variables, plus `env` ("NAME=VALUE"); stdin
 * from `in` (or /dev/null), stderr into `err_path`.  0 when not run. */
pid_t start_cli(const char *const *args, const char *const *env, const char *in,
                const char *err_path);
/* Its exit status: 128 + signal when killed, -1 when lost. */
int wait_status(pid_t pid);
/* Run it to the end, stderr into r->err; false (after a failure) when
 * it could not be started. */
bool run_env(const char *const *args, const char *const *env, const char *in, run_result *r);
bool run(const char *const *args, run_result *r);
int count_lines(const char *s);
/* Runs the tool with args, which write the PNG `out`, and reads that back
 * (malloc'd RGBA8, *w by *h; r the run); NULL after a failed check when
 * the run fails or the image does not read. */
uint8_t *render_read(const char *const *args, const char *out, int *w, int *h, run_result *r);

/* Writes two model files (data[0] the reference, data[1] the one under
 * test; .glb) into batch_`name`, renders both with the tool at 320x240 and
 * checks the second image against the first: `channel_tol` at most, but
 * for `max_pixels` pixels. */
void check_same_render(const char *name, const void *const data[2], const size_t size[2],
                       int channel_tol, int max_pixels);

/* Writes `text` (a malloc'd model file, freed here; NULL: out of
 * memory) as `file` into batch_`name`, renders it with `softrast render
 * MODEL --size SIZE --aa none` and the options `extra` (up to five;
 * NULL-terminated), on 1 and on 3 threads, and checks: no warning, the
 * same bytes, and within 3 codes of tests/ref/REF.png on all but 0.5% of
 * the pixels (test_images.c's tolerance: libm). */
void check_model_render(const char *name, const char *file, char *text, const char *size,
                        const char *const *extra, const char *ref);

/* text (malloc'd, freed here) with its first `from` replaced by `to`,
 * malloc'd; NULL (after a failure) when text is NULL or lacks from. */
char *text_replaced(char *text, const char *from, const char *to);

/* Replaces the first `from` in the NUL-terminated text with `to`; false
 * (after a failure) when absent. */
bool edit_text(wbuf *text, const char *from, const char *to);

/* Writes the model file (`.glb`) into dir as badI.glb and checks that
 * `softrast render` refuses it: exit status 2, one line on stderr that
 * contains `message`, no image written. */
void check_refused(const char *dir, size_t i, const void *data, size_t size,
                   const char *message);

/* An empty directory sr_test_out_dir()/batch_NAME, in buf. */
const char *fresh_dir(const char *name, char *buf, size_t n);
bool write_text(const char *path, const char *text);
bool file_exists(const char *path);
/* Whether two files hold the same bytes (false when one cannot be read). */
bool same_file_bytes(const char *a, const char *b);

/* The records of a log file (at most max, each checked to hold the ten
 * fields); -1 when it cannot be read or a line is not a record. */
int read_log(const char *path, record *recs, int max);
const record *find_record(const record *recs, int n, const char *input);

/* How many animation frames (ANMF chunks) an extended WebP file has at
 * its top level, and whether its VP8X header flags an animation; -1 when
 * the file is not an extended WebP. */
int count_anmf(const uint8_t *p, size_t n, bool *animated);

#endif
