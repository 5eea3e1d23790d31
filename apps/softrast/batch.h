/* batch.h - many inputs in one process, for `softrast render` (batch.c)
 * and `softrast svg` (svg_cmd.c), through batch_session.h: the input list
 * and the output names (batch_inputs.c), the share of it one shard
 * renders (batch_shard.c), and the JSON Lines log and the progress line
 * (batch_log.c). */
#ifndef SR_BATCH_H
#define SR_BATCH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Exit statuses of a batch beyond cli.h's: some inputs failed and the
 * others were rendered (or skipped), or every input failed. */
enum { EXIT_BATCH_SOME_FAILED = 3, EXIT_BATCH_ALL_FAILED = 4 };

typedef struct batch_item {
    char *input;
    char *output;   /* named by the list, else NULL until batch_name_outputs */
    char *rel;      /* the path below the directory it was found in, or NULL */
    size_t index;   /* position in the sorted list, the same in every shard */
    bool named;     /* the output is the list's, not the pattern's */
} batch_item;

/* The files a command takes from a directory: a file name's test. */
typedef bool (*batch_takes_fn)(const char *name);

typedef struct batch_list {
    batch_item *items;
    size_t count, cap;
    const char *dir, *pattern;   /* what batch_name_outputs named the outputs by */
    batch_takes_fn takes;        /* NULL: model files */
} batch_list;

/* An input path, a directory (searched for the files l->takes, hidden
 * entries skipped) or a glob pattern that names no file itself.  -1, or
 * an exit status after one line. */
int batch_add_arg(batch_list *l, const char *arg);
/* --batch LIST: one INPUT or INPUT<TAB>OUTPUT per line, "-" for standard
 * input; blank lines and lines starting with '#' are skipped. */
int batch_read_list(batch_list *l, const char *path);
/* Sort by input path, drop repeated inputs and number the rest. */
void batch_list_sort(batch_list *l);
void batch_list_free(batch_list *l);

/* Check an output name pattern (--name): false after one line. */
bool batch_check_pattern(const char *pattern);
/* Name every output without one: DIR/PATTERN with {stem}, {ext}, {rel},
 * {index} and {view} (0) filled in; then refuse two inputs with one
 * output.  -1, or an exit status after one line. */
int batch_name_outputs(batch_list *l, const char *dir, const char *pattern);
/* The output of view `view` of an input named by the pattern, in
 * out[size]; false when too long. */
bool batch_view_output(const batch_list *l, const batch_item *it, int view, char *out,
                       size_t size);

/* The share of the list this process renders. */
typedef struct batch_shard {
    int index, count;          /* 0 <= index < count */
    const char *source;        /* "--shard", "JOB_COMPLETION_INDEX", ... or NULL */
} batch_shard;

/* From --shard I/N (NULL if not given), else JOB_COMPLETION_INDEX with
 * --shard-count N, else SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT,
 * else the whole list.  -1, or an exit status after one line. */
int batch_shard_resolve(const char *shard, const char *count, batch_shard *out);
/* Whether `input` belongs to the shard: by a hash of its path, so an
 * input lands on the same shard whatever the order of the list. */
bool batch_in_shard(const char *input, const batch_shard *s);

/* One input's result, as a line of the --log file. */
typedef struct batch_record {
    const char *input, *output;
    size_t index;
    const char *status;        /* "ok", "failed" or "skipped" */
    const char *error;         /* NULL unless failed */
    uint64_t triangles;
    double load_ms, render_ms, encode_ms;
} batch_record;

/* Append the record as one JSON object and a newline, in one write. */
bool batch_log_write(int fd, const batch_record *r);

/* The progress line: on a terminal, redrawn in place on standard error. */
typedef struct batch_progress {
    bool tty, shown;
    size_t total, done, failed, skipped;
    double start_ms, drawn_ms;
} batch_progress;

void batch_progress_start(batch_progress *p, size_t total, double now_ms);
/* Redraw (at most ten times a second unless `final`). */
void batch_progress_show(batch_progress *p, double now_ms, bool final);
/* Clear the line so that an error can be printed in its place. */
void batch_progress_clear(batch_progress *p);

#endif
