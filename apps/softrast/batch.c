/* batch.c - `softrast render` over many models in one process: several
 * MODEL arguments, directories, glob patterns or a --batch list, each
 * drawn by one render job whose contexts (and their thread pool) and
 * framebuffer serve every input in turn.  A bad input is one line on
 * stderr and one record in the log, and the batch goes on; the exit
 * status says whether all, some or none of the inputs were rendered. */
#include "batch.h"
#include "cli.h"
#include "render.h"
#include "render_options.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

typedef struct batch_opts {
    const char *list;          /* --batch LIST */
    const char *output_dir;    /* --output-dir DIR (default .) */
    const char *name;          /* --name PATTERN (default {stem}.png) */
    const char *log;           /* --log FILE.jsonl */
    const char *shard, *shard_count;
    bool skip_existing;
    bool any;                  /* a batch option was given */
    bool output;               /* -o was given */
    const char **models;       /* the MODEL arguments */
    size_t model_count, model_cap;
} batch_opts;

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static void batch_help(void)
{
    printf(
        "\n"
        "batch (several MODELs, a directory, a glob pattern or --batch):\n"
        "  softrast render MODEL|DIR|PATTERN... [--batch LIST] [options]\n"
        "                           renders every model in one process with the options\n"
        "                           above; a directory is searched (below it too) for\n"
        "                           .stl .obj .ply files (and Assimp's formats when built\n"
        "                           with it); a quoted pattern ('models/*.stl') is\n"
        "                           expanded here\n"
        "  --batch LIST             one INPUT or INPUT<TAB>OUTPUT per line; '-' reads\n"
        "                           standard input; blank and '#' lines are skipped\n"
        "  --output-dir DIR         where outputs go (default .)\n"
        "  --name PATTERN           output name below DIR (default {rel}.png): {stem}\n"
        "                           the input's name without extension, {ext} its\n"
        "                           extension, {rel} its path below the directory it was\n"
        "                           found in without extension, {index} its place in the\n"
        "                           sorted list; .jpg or .jpeg makes JPEGs\n"
        "  --skip-existing          leave outputs that exist alone (resumes a batch)\n"
        "  --log FILE.jsonl         append one JSON object per input: input, output,\n"
        "                           index, status (ok, failed, skipped), error,\n"
        "                           triangles, load_ms, render_ms, encode_ms, ms\n"
        "  --shard I/N              render shard I (from 0) of N: the inputs whose path\n"
        "                           hashes to I mod N\n"
        "  --shard-count N          the shard count for JOB_COMPLETION_INDEX\n"
        "                           (a Kubernetes Indexed Job)\n"
        "                           Without --shard, the shard is JOB_COMPLETION_INDEX of\n"
        "                           --shard-count, else SLURM_ARRAY_TASK_ID (less\n"
        "                           SLURM_ARRAY_TASK_MIN, over SLURM_ARRAY_TASK_STEP) of\n"
        "                           SLURM_ARRAY_TASK_COUNT; --shard 0/1 renders all\n"
        "\n"
        "A batch draws a progress line on a terminal and otherwise prints only one\n"
        "line per failed input.  Exit status: 0 when every input was rendered or\n"
        "skipped, 3 when some failed, 4 when all failed, 2 for bad options (nothing\n"
        "rendered), 1 when the batch could not start.\n");
}

static bool add_model(void *user, const char *path)
{
    batch_opts *b = user;
    if (b->model_count == b->model_cap) {
        size_t cap = b->model_cap ? 2 * b->model_cap : 16;
        const char **grown = realloc(b->models, cap * sizeof *grown);
        if (!grown) {
            cli_error("out of memory");
            return false;
        }
        b->models = grown;
        b->model_cap = cap;
    }
    b->models[b->model_count++] = path;
    return true;
}

/* The batch's own options out of argv into b; the rest (with argv[0])
 * into rest, for the render options' parser. */
static int split_args(int argc, char **argv, batch_opts *b, char **rest, int *rest_count)
{
    static const char *const valued[] = { "--batch", "--output-dir", "--name", "--log",
                                          "--shard", "--shard-count", NULL };
    const char **dst[] = { &b->list, &b->output_dir, &b->name, &b->log, &b->shard,
                           &b->shard_count };
    int n = 0;
    rest[n++] = argv[0];
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--skip-existing") == 0) {
            b->skip_existing = b->any = true;
            continue;
        }
        if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0 ||
            strncmp(a, "--output=", 9) == 0) {
            b->output = true;
        }
        int k = 0;
        size_t len = 0;
        for (; valued[k]; k++) {
            len = strlen(valued[k]);
            if (strncmp(a, valued[k], len) == 0 && (a[len] == '\0' || a[len] == '=')) {
                break;
            }
        }
        if (!valued[k]) {
            rest[n++] = argv[i];
            continue;
        }
        const char *value = a[len] == '=' ? a + len + 1 : i + 1 < argc ? argv[++i] : NULL;
        if (!value || !*value) {
            cli_error("%s: %s value", valued[k], value ? "empty" : "missing");
            return EXIT_USAGE;
        }
        *dst[k] = value;
        b->any = true;
    }
    rest[n] = NULL;
    *rest_count = n;
    return -1;
}

/* Whether the arguments ask for a batch rather than one render. */
static bool is_batch(const batch_opts *b)
{
    struct stat st;
    if (b->any) {
        return true;
    }
    if (b->output || b->model_count > 1) {
        return !b->output;   /* -o names one image: render says what is wrong */
    }
    /* One argument that is a directory, or a pattern no file is named. */
    const char *m = b->model_count ? b->models[0] : NULL;
    return m && ((stat(m, &st) == 0 && S_ISDIR(st.st_mode)) ||
                 (stat(m, &st) != 0 && strpbrk(m, "*?[")));
}

/* The inputs as (device, inode), sorted, so that no output replaces any
 * input of the list (not only its own) in O(log n) a check. */
typedef struct file_id {
    dev_t dev;
    ino_t ino;
} file_id;

static int by_id(const void *a, const void *b)
{
    const file_id *x = a, *y = b;
    return x->dev != y->dev ? (x->dev < y->dev ? -1 : 1)
         : x->ino != y->ino ? (x->ino < y->ino ? -1 : 1) : 0;
}

static file_id *input_ids(const batch_list *l, size_t *count)
{
    file_id *ids = malloc((l->count + 1) * sizeof *ids);
    size_t n = 0;
    for (size_t i = 0; ids && i < l->count; i++) {
        struct stat st;
        if (stat(l->items[i].input, &st) == 0) {
            ids[n++] = (file_id){ st.st_dev, st.st_ino };
        }
    }
    if (ids) {
        qsort(ids, n, sizeof *ids, by_id);
    }
    *count = n;
    return ids;
}

static bool is_listed_input(const file_id *ids, size_t n, const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        return false;
    }
    file_id key = { st.st_dev, st.st_ino };
    return bsearch(&key, ids, n, sizeof *ids, by_id) != NULL;
}

/* Make the directories above `path` (mkdir -p of its dirname); false
 * after one line. */
static bool make_parents(const char *path)
{
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", path);
    for (char *p = dir + 1; *p; p++) {
        if (*p != '/') {
            continue;
        }
        *p = '\0';
        if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
            cli_error("cannot make the directory '%s': %s", dir, strerror(errno));
            return false;
        }
        *p = '/';
    }
    return true;
}

static bool exists_whole(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0;
}

typedef struct batch_run {
    const render_opts *o;
    render_job *job;
    sr_framebuffer *fb;
    const file_id *ids;
    size_t id_count;
    char message[2048];        /* the held messages of the current input */
} batch_run;

/* Render one input to its output; its record filled in.  Any message
 * (why it failed, or a warning) is left in run->message. */
static void render_one(batch_run *run, const batch_item *it, batch_record *rec)
{
    const render_opts *o = run->o;
    double t0 = now_ms();
    rec->status = "failed";
    cli_capture(run->message, sizeof run->message);
    struct stat st;
    int status = -1;
    if (stat(it->output, &st) == 0 && S_ISDIR(st.st_mode)) {
        cli_error("'%s' is a directory", it->output);
        status = EXIT_USAGE;
    } else if (is_listed_input(run->ids, run->id_count, it->output)) {
        cli_error("'%s' is an input of the batch; choose another --name", it->output);
        status = EXIT_USAGE;
    }
    if (status < 0) {
        status = render_job_reload(run->job, it->input);
    }
    if (status < 0 && !run->fb) {
        sr_context *ctx = render_job_context(run->job);
        sr_result r = sr_make_framebuffer(
            ctx, &(sr_framebuffer_desc){ .width = o->width, .height = o->height,
                                         .depth_format = render_job_depth_format(run->job) },
            &run->fb);
        if (r != SR_OK) {
            cli_error("%s", sr_context_error(ctx)[0] ? sr_context_error(ctx) : sr_result_text(r));
            status = EXIT_FAILURE_RUN;
        }
    }
    double t1 = now_ms();
    rec->load_ms = t1 - t0;
    if (status >= 0) {
        cli_capture(NULL, 0);
        return;
    }
    render_frame_info info;
    sr_result r = render_job_draw(run->job, run->fb, &info);
    double t2 = now_ms();
    rec->render_ms = t2 - t1;
    rec->triangles = info.triangles;
    sr_io_error err;
    if (r != SR_OK) {
        cli_error("%s", render_job_error(run->job));
    } else if (!make_parents(it->output)) {
        /* make_parents said why */
    } else if (cli_write_image(it->output, o->width, o->height, sr_framebuffer_pixels(run->fb),
                               &(cli_image_options){ .png_level = o->png_level,
                                                     .jpeg_quality = o->jpeg_quality,
                                                     .keep_alpha = o->background_alpha < 1.0f,
                                                     .premultiplied = true,
                                                     .context = render_job_context(run->job),
                                                     .inputs = render_job_inputs(run->job) },
                               &err) != SR_OK) {
        cli_error("%s", err.message);
    } else {
        rec->status = "ok";
    }
    rec->encode_ms = now_ms() - t2;
    cli_capture(NULL, 0);
}

/* One line for a failed input (or a warning), naming the input unless
 * the message starts with it already ("FILE:LINE: why"). */
static void report(const char *input, const char *message)
{
    size_t n = strlen(input);
    if (strncmp(message, input, n) == 0 && message[n] == ':') {
        cli_error("%s", message);
    } else {
        cli_error("%s: %s", input, message);
    }
}

/* The inputs of the options: the MODEL arguments and the list. */
static int gather(const batch_opts *b, batch_list *l)
{
    int status = -1;
    for (size_t i = 0; i < b->model_count && status < 0; i++) {
        status = batch_add_arg(l, b->models[i]);
    }
    if (status < 0 && b->list) {
        status = batch_read_list(l, b->list);
    }
    if (status < 0 && l->count == 0) {
        cli_error("render: no models to render (a directory holds none, or the list is empty)");
        status = EXIT_USAGE;
    }
    if (status < 0) {
        batch_list_sort(l);
        status = batch_name_outputs(l, b->output_dir ? b->output_dir : ".",
                                    b->name ? b->name : "{rel}.png");
    }
    return status;
}

static int run_batch(const batch_opts *b, const render_opts *o, render_job *job)
{
    batch_shard shard;
    batch_list list = { 0 };
    int status = batch_shard_resolve(b->shard, b->shard_count, &shard);
    if (status < 0) {
        status = gather(b, &list);
    }
    int log_fd = -1;
    if (status < 0 && b->log) {
        log_fd = open(b->log, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
        if (log_fd < 0) {
            cli_error("--log: %s: %s", b->log, strerror(errno));
            status = EXIT_USAGE;
        }
    }
    batch_run run = { .o = o, .job = job };
    file_id *ids = status < 0 ? input_ids(&list, &run.id_count) : NULL;
    if (status < 0 && !ids) {
        cli_error("out of memory listing the inputs");
        status = EXIT_FAILURE_RUN;
    }
    run.ids = ids;
    size_t mine = 0;
    for (size_t i = 0; i < list.count; i++) {
        mine += batch_in_shard(list.items[i].input, &shard);
    }
    batch_progress progress;
    batch_progress_start(&progress, mine, now_ms());
    size_t ok = 0;
    for (size_t i = 0; status < 0 && i < list.count; i++) {
        const batch_item *it = &list.items[i];
        if (!batch_in_shard(it->input, &shard)) {
            continue;
        }
        batch_record rec = { .input = it->input, .output = it->output, .index = it->index };
        run.message[0] = '\0';
        if (b->skip_existing && exists_whole(it->output)) {
            rec.status = "skipped";
            progress.skipped++;
        } else {
            render_one(&run, it, &rec);
        }
        bool failed = strcmp(rec.status, "failed") == 0;
        ok += !failed;
        progress.failed += failed;
        progress.done++;
        if (run.message[0]) {
            batch_progress_clear(&progress);
            report(it->input, run.message);
        }
        rec.error = failed ? (run.message[0] ? run.message : "failed") : NULL;
        if (log_fd >= 0 && !batch_log_write(log_fd, &rec)) {
            cli_error("--log: %s: %s", b->log, strerror(errno));
            status = EXIT_FAILURE_RUN;
        }
        batch_progress_show(&progress, now_ms(), false);
    }
    if (status < 0) {
        batch_progress_show(&progress, now_ms(), true);
        status = progress.failed == 0 ? EXIT_OK
               : ok > 0 ? EXIT_BATCH_SOME_FAILED : EXIT_BATCH_ALL_FAILED;
    }
    if (log_fd >= 0 && close(log_fd) != 0 && status < EXIT_USAGE) {
        cli_error("--log: %s: %s", b->log, strerror(errno));
        status = EXIT_FAILURE_RUN;
    }
    if (run.fb) {
        sr_destroy_framebuffer(render_job_context(job), run.fb);
    }
    free(ids);
    batch_list_free(&list);
    return status;
}

int batch_render(int argc, char **argv)
{
    batch_opts b = { 0 };
    char **rest = malloc(((size_t)argc + 1) * sizeof *rest);
    if (!rest) {
        cli_error("out of memory");
        return EXIT_FAILURE_RUN;
    }
    int rest_count = 0;
    int status = split_args(argc, argv, &b, rest, &rest_count);
    render_opts o = render_opts_defaults();
    o.model_fn = add_model;
    o.model_user = &b;
    if (status < 0) {
        status = render_opts_parse(rest_count, rest, &o);
        if (status == EXIT_OK) {
            batch_help();   /* after render's --help */
        }
    }
    if (status < 0 && !is_batch(&b)) {
        free(b.models);
        free(rest);
        return -1;          /* one plain render */
    }
    if (status < 0 && b.output) {
        cli_error("-o: names one output; a batch names its outputs with --output-dir and --name");
        status = EXIT_USAGE;
    }
    if (status < 0 && b.name && !batch_check_pattern(b.name)) {
        status = EXIT_USAGE;
    }
    /* The job's options without the models, which come in the same order. */
    int n = 0;
    for (int i = 0, j = 0; i < rest_count; i++) {
        if ((size_t)j < b.model_count && rest[i] == b.models[j]) {
            j++;
        } else {
            rest[n++] = rest[i];
        }
    }
    rest[n] = NULL;
    render_job *job = NULL;
    if (status < 0) {
        status = render_job_parse(n, rest, &job);
    }
    if (status < 0) {
        status = run_batch(&b, &o, job);
    }
    render_job_free(job);
    free(b.models);
    free(rest);
    return status;
}
