/* batch_session.c - the part of a batch that does not depend on what its
 * inputs are: the batch options, the sorted input list and its outputs'
 * names, the inputs' identities (no output replaces one), the writer
 * thread, the log and the progress line, and the exit status.  Called
 * from the batch's own thread; batch_session_done also from the
 * writer's, one call at a time; batch_session_output_ok and
 * batch_exists_whole also from the drawing threads (batch_draw.c), which
 * only read the session. */
#include "batch_session.h"
#include "cli.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

double batch_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

void batch_help_options(FILE *f)
{
    fprintf(f,
        "  --batch LIST             one INPUT or INPUT<TAB>OUTPUT per line; '-' reads\n"
        "                           standard input; blank and '#' lines are skipped\n"
        "  --output-dir DIR         where outputs go (default .)\n"
        "  --name PATTERN           output name below DIR (default {rel}.png): {stem}\n"
        "                           the input's name without extension, {ext} its\n"
        "                           extension, {rel} its path below the directory it was\n"
        "                           found in without extension, {index} its place in the\n"
        "                           sorted list; .jpg or .jpeg makes JPEGs, .png or no\n"
        "                           extension PNGs (another is refused)\n"
        "  --skip-existing          leave outputs that exist alone (resumes a batch)\n"
        "  --log FILE.jsonl         append one JSON object per input: input, output,\n"
        "                           index, status (ok, failed, skipped), error,\n"
        "                           triangles, load_ms, render_ms, encode_ms, ms\n"
        "  --shard I/N              render shard I (from 0) of N: the inputs whose path\n"
        "                           hashes to I mod N\n"
        "  --shard-count N          the shard count for JOB_COMPLETION_INDEX (a\n"
        "                           Kubernetes Indexed Job); without --shard, the shard\n"
        "                           is JOB_COMPLETION_INDEX of --shard-count, else\n"
        "                           SLURM_ARRAY_TASK_ID (less SLURM_ARRAY_TASK_MIN, over\n"
        "                           SLURM_ARRAY_TASK_STEP) of SLURM_ARRAY_TASK_COUNT;\n"
        "                           --shard 0/1 renders all\n");
}

void batch_help_status(FILE *f)
{
    fprintf(f,
        "\n"
        "A batch draws a progress line on a terminal and otherwise prints only one\n"
        "line per failed input.  Exit status: 0 when every input was rendered or\n"
        "skipped, 3 when some failed, 4 when all failed, 2 for bad options (nothing\n"
        "rendered), 1 when the batch could not start.\n");
}

int batch_take_option(batch_common *c, int argc, char **argv, int *i)
{
    static const char *const valued[] = { "--batch", "--output-dir", "--name", "--log",
                                          "--shard", "--shard-count", NULL };
    const char **dst[] = { &c->list, &c->output_dir, &c->name, &c->log, &c->shard,
                           &c->shard_count };
    const char *a = argv[*i];
    if (strcmp(a, "--skip-existing") == 0) {
        c->skip_existing = c->any = true;
        return 1;
    }
    for (int k = 0; valued[k]; k++) {
        size_t len = strlen(valued[k]);
        if (strncmp(a, valued[k], len) != 0 || (a[len] != '\0' && a[len] != '=')) {
            continue;
        }
        const char *value = a[len] == '=' ? a + len + 1 : *i + 1 < argc ? argv[++*i] : NULL;
        if (!value || !*value) {
            cli_error("%s: %s value", valued[k], value ? "empty" : "missing");
            return EXIT_USAGE;
        }
        *dst[k] = value;
        c->any = true;
        return 1;
    }
    return 0;
}

bool batch_asked(const batch_common *c, const char *const *args, size_t count)
{
    struct stat st;
    if (c->any || count > 1) {
        return true;
    }
    const char *a = count ? args[0] : NULL;
    return a && ((stat(a, &st) == 0 && S_ISDIR(st.st_mode)) ||
                 (stat(a, &st) != 0 && strpbrk(a, "*?[")));
}

int batch_session_gather(batch_session *s, const batch_common *c, const char *const *args,
                         size_t count, batch_takes_fn takes, const char *none)
{
    *s = (batch_session){ .opts = c, .list = { .takes = takes }, .log_fd = -1 };
    int status = batch_shard_resolve(c->shard, c->shard_count, &s->shard);
    for (size_t i = 0; i < count && status < 0; i++) {
        status = batch_add_arg(&s->list, args[i]);
    }
    if (status < 0 && c->list) {
        status = batch_read_list(&s->list, c->list);
    }
    if (status < 0 && s->list.count == 0) {
        cli_error("%s to render (a directory holds none, or the list is empty)", none);
        status = EXIT_USAGE;
    }
    if (status < 0) {
        batch_list_sort(&s->list);
    }
    return status;
}

int batch_session_name(batch_session *s, const char *default_name)
{
    const batch_common *c = s->opts;
    return batch_name_outputs(&s->list, c->output_dir ? c->output_dir : ".",
                              c->name ? c->name : default_name);
}

static int by_id(const void *a, const void *b)
{
    const batch_file_id *x = a, *y = b;
    return x->dev != y->dev ? (x->dev < y->dev ? -1 : 1)
         : x->ino != y->ino ? (x->ino < y->ino ? -1 : 1) : 0;
}

/* The inputs as (device, inode), sorted, so that no output replaces any
 * input of the list (not only its own) in O(log n) a check. */
static batch_file_id *input_ids(const batch_list *l, size_t *count)
{
    batch_file_id *ids = malloc((l->count + 1) * sizeof *ids);
    size_t n = 0;
    for (size_t i = 0; ids && i < l->count; i++) {
        struct stat st;
        if (stat(l->items[i].input, &st) == 0) {
            ids[n++] = (batch_file_id){ st.st_dev, st.st_ino };
        }
    }
    if (ids) {
        qsort(ids, n, sizeof *ids, by_id);
    }
    *count = n;
    return ids;
}

static bool is_input(const batch_session *s, const struct stat *st)
{
    batch_file_id key = { st->st_dev, st->st_ino };
    return bsearch(&key, s->ids, s->id_count, sizeof *s->ids, by_id) != NULL;
}

int batch_session_open(batch_session *s)
{
    s->ids = input_ids(&s->list, &s->id_count);
    if (!s->ids) {
        cli_error("out of memory listing the inputs");
        return EXIT_FAILURE_RUN;
    }
    const char *log = s->opts->log;
    if (!cli_check_output_name("--log", log) ||
        !cli_check_output_name("--output-dir", s->opts->output_dir)) {
        return EXIT_USAGE;
    }
    struct stat st;
    /* The log is appended to: one of the inputs (by any name) would be
     * left with JSON at its end. */
    if (log && stat(log, &st) == 0 && is_input(s, &st)) {
        cli_error("--log: '%s' is an input of the batch; choose another log file", log);
        return EXIT_USAGE;
    }
    if (log) {
        s->log_fd = open(log, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
        if (s->log_fd < 0) {
            cli_error("--log: %s: %s", log, strerror(errno));
            return EXIT_USAGE;
        }
    }
    return -1;
}

size_t batch_session_mine(const batch_session *s)
{
    size_t mine = 0;
    for (size_t i = 0; i < s->list.count; i++) {
        mine += batch_in_shard(s->list.items[i].input, &s->shard);
    }
    return mine;
}

void batch_session_begin(batch_session *s, size_t records, int writers)
{
    batch_progress_start(&s->progress, records, batch_now_ms());
    batch_writer_start(&s->writer, writers, batch_session_done, s);
    s->running = true;
}

int batch_session_end(batch_session *s)
{
    batch_writer_stop(&s->writer);
    s->running = false;
    batch_progress_show(&s->progress, batch_now_ms(), true);
    return s->progress.failed == 0 ? EXIT_OK
         : s->ok > 0 ? EXIT_BATCH_SOME_FAILED : EXIT_BATCH_ALL_FAILED;
}

int batch_session_close(batch_session *s, int status)
{
    if (s->running) {
        batch_session_end(s);
    }
    if (s->log_fd >= 0 && close(s->log_fd) != 0 && s->log_errno == 0) {
        s->log_errno = errno;
    }
    if (s->log_errno != 0) {
        cli_error("--log: %s: %s", s->opts->log, strerror(s->log_errno));
        status = EXIT_FAILURE_RUN;
    }
    free(s->ids);
    batch_list_free(&s->list);
    s->ids = NULL;
    s->log_fd = -1;
    return status;
}

bool batch_session_output_ok(const batch_session *s, const char *output, const char *opt)
{
    struct stat st;
    if (stat(output, &st) != 0) {
        return true;
    }
    if (S_ISDIR(st.st_mode)) {
        cli_error("'%s' is a directory", output);
        return false;
    }
    if (is_input(s, &st)) {
        cli_error("'%s' is an input of the batch; choose another %s", output, opt);
        return false;
    }
    return true;
}

bool batch_exists_whole(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0;
}

/* Printed directly: the writer's thread calls this while the batch may
 * be holding its own messages (cli_capture). */
void batch_session_report(batch_session *s, const char *input, const char *message)
{
    batch_progress_clear(&s->progress);
    char name[4096], line[8192];
    snprintf(name, sizeof name, "%s", input);
    cli_one_line(name);   /* as the readers quote it in their messages */
    size_t n = strlen(name);
    bool named = strncmp(message, name, n) == 0 && message[n] == ':';
    snprintf(line, sizeof line, "%s%s%s", named ? "" : name, named ? "" : ": ", message);
    cli_one_line(line);
    fprintf(stderr, "softrast: %s\n", line);
}

void batch_session_done(void *user, batch_record *rec, const char *message)
{
    batch_session *s = user;
    bool failed = strcmp(rec->status, "failed") == 0;
    s->ok += !failed;
    s->progress.failed += failed;
    s->progress.skipped += strcmp(rec->status, "skipped") == 0;
    s->progress.done++;
    if (message && *message) {
        batch_session_report(s, rec->input, message);
    }
    rec->error = failed ? (message && *message ? message : "failed") : NULL;
    if (s->log_fd >= 0 && s->log_errno == 0 && !batch_log_write(s->log_fd, rec)) {
        s->log_errno = errno ? errno : EIO;
    }
    batch_progress_show(&s->progress, batch_now_ms(), false);
}
