/* batch_cli.c - running the softrast tool as a batch's caller does (its
 * environment, standard input from a file, standard error kept) and
 * reading back its --log, and two models rendered and compared: shared by
 * the batch tests and the glTF compression tests. */
#include "batch_cli.h"
#include "image_compare.h"

#include "softrast_io.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

/* Start SR_CLI_PATH with args and an environment of this process's
 * without the schedulers' variables, plus `env` ("NAME=VALUE"); stdin
 * from `in` (or /dev/null), stderr into `err_path`.  0 when not run. */
pid_t start_cli(const char *const *args, const char *const *env, const char *in,
                const char *err_path)
{
#ifdef SR_CLI_PATH
    const char *argv[80], *envp[256];
    int e = 0;
    if (!sr_test_program_argv(SR_CLI_PATH, args, argv, sizeof argv / sizeof argv[0])) {
        return 0;
    }
    for (char **p = environ; *p && e < 200; p++) {
        if (strncmp(*p, "JOB_COMPLETION_INDEX=", 21) != 0 && strncmp(*p, "SLURM_", 6) != 0) {
            envp[e++] = *p;
        }
    }
    for (int i = 0; env[i] && e < 255; i++) {
        envp[e++] = env[i];
    }
    envp[e] = NULL;
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 0, in ? in : "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 2, err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid;
    int r = posix_spawn(&pid, argv[0], &fa, NULL, (char *const *)argv, (char *const *)envp);
    posix_spawn_file_actions_destroy(&fa);
    return r == 0 ? pid : 0;
#else
    (void)args, (void)env, (void)in, (void)err_path;
    return 0;
#endif
}

int wait_status(pid_t pid)
{
    int ws;
    while (waitpid(pid, &ws, 0) < 0) {
        if (errno != EINTR) {
            return -1;
        }
    }
    return WIFEXITED(ws) ? WEXITSTATUS(ws) : WIFSIGNALED(ws) ? 128 + WTERMSIG(ws) : -1;
}

bool run_env(const char *const *args, const char *const *env, const char *in, run_result *r)
{
    char err_path[1024];
    snprintf(err_path, sizeof err_path, "%s/batch_stderr_%ld.txt", sr_test_out_dir(),
             (long)getpid());   /* the batch tests run side by side */
    r->status = -1;
    r->err[0] = '\0';
    pid_t pid = start_cli(args, env, in, err_path);
    if (!pid) {
        FAILF("cannot run %s", args[0]);
        return false;
    }
    r->status = wait_status(pid);
    FILE *f = fopen(err_path, "rb");
    size_t n = f ? fread(r->err, 1, sizeof r->err - 1, f) : 0;
    r->err[n] = '\0';
    if (f) {
        fclose(f);
    }
    return true;
}

bool run(const char *const *args, run_result *r)
{
    return run_env(args, NO_ENV, NULL, r);
}

uint8_t *render_read(const char *const *args, const char *out, int *w, int *h, run_result *r)
{
    if (!run(args, r) || r->status != 0) {
        FAILF("softrast %s %s: status %d: %s", args[0], args[1] ? args[1] : "", r->status,
              r->err);
        return NULL;
    }
    uint8_t *px = NULL;
    sr_io_error e;
    if (sr_read_png(out, NULL, w, h, &px, &e) != SR_OK) {
        FAILF("%s", e.message);
    }
    return px;
}

bool same_file_bytes(const char *a, const char *b)
{
    size_t na = 0, nb = 0;
    uint8_t *pa = sr_test_read_file(a, &na), *pb = sr_test_read_file(b, &nb);
    bool same = pa && pb && na == nb && memcmp(pa, pb, na) == 0;
    free(pa);
    free(pb);
    return same;
}

bool cli_reads_svg(void)
{
    /* The tool is built with the library's features. */
    return sr_io_have_svg();
}

int count_lines(const char *s)
{
    int n = 0;
    for (; *s; s++) {
        n += *s == '\n';
    }
    return n;
}

static void clean_dir(const char *path)
{
    DIR *d = opendir(path);
    if (d) {
        struct dirent *e;
        while ((e = readdir(d)) != NULL) {
            if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0) {
                char p[2048];
                snprintf(p, sizeof p, "%s/%s", path, e->d_name);
                struct stat st;
                if (lstat(p, &st) == 0 && S_ISDIR(st.st_mode)) {
                    clean_dir(p);
                    rmdir(p);
                } else {
                    unlink(p);
                }
            }
        }
        closedir(d);
    }
    mkdir(path, 0777);
}

const char *fresh_dir(const char *name, char *buf, size_t n)
{
    snprintf(buf, n, "%s/batch_%s", sr_test_out_dir(), name);
    clean_dir(buf);
    return buf;
}

bool write_text(const char *path, const char *text)
{
    return sr_test_write_file(path, text, strlen(text));
}
bool file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}


/* A JSON string at *p into dst (escapes decoded; \u to one '?' beyond
 * ASCII); false when it is not one. */
static bool json_string(const char **p, char *dst, size_t size)
{
    const char *s = *p;
    size_t n = 0;
    if (*s++ != '"') {
        return false;
    }
    for (; *s && *s != '"'; s++) {
        char c = *s;
        if (c == '\\') {
            s++;
            c = *s == 'n' ? '\n' : *s == 't' ? '\t' : *s == 'u' ? '?' : *s;
            if (*s == 'u') {
                for (int k = 1; k <= 4; k++) {
                    if (!strchr("0123456789abcdefABCDEF", s[k]) || !s[k]) {
                        return false;
                    }
                }
                s += 4;
            }
        } else if ((unsigned char)c < 0x20) {
            return false;
        }
        if (n + 1 < size) {
            dst[n++] = c;
        }
    }
    dst[n] = '\0';
    if (*s != '"') {
        return false;
    }
    *p = s + 1;
    return true;
}

/* One line of the log as a flat JSON object with the known keys; false
 * (after a failure naming the line) when it is not exactly that. */
static bool parse_record(const char *line, record *r)
{
    memset(r, 0, sizeof *r);
    const char *p = line;
    if (*p++ != '{') {
        FAILF("log line is not an object: %s", line);
        return false;
    }
    while (*p && *p != '}') {
        char key[32];
        if (!json_string(&p, key, sizeof key) || *p++ != ':') {
            FAILF("log line: bad key: %s", line);
            return false;
        }
        char *dst = strcmp(key, "input") == 0 ? r->input : strcmp(key, "output") == 0 ? r->output
                  : strcmp(key, "status") == 0 ? r->status : strcmp(key, "error") == 0 ? r->error
                  : NULL;
        size_t size = dst == r->status ? sizeof r->status : dst == r->error ? sizeof r->error
                                                                               : sizeof r->input;
        double *num = strcmp(key, "index") == 0       ? &r->index
                    : strcmp(key, "triangles") == 0   ? &r->triangles
                    : strcmp(key, "load_ms") == 0     ? &r->load_ms
                    : strcmp(key, "render_ms") == 0   ? &r->render_ms
                    : strcmp(key, "encode_ms") == 0   ? &r->encode_ms
                    : strcmp(key, "ms") == 0          ? &r->ms : NULL;
        if (dst == r->error && strncmp(p, "null", 4) == 0) {
            r->error_null = true;
            p += 4;
        } else if (dst) {
            if (!json_string(&p, dst, size)) {
                FAILF("log line: '%s' is not a string: %s", key, line);
                return false;
            }
        } else if (num) {
            char *end;
            *num = strtod(p, &end);
            if (end == p) {
                FAILF("log line: '%s' is not a number: %s", key, line);
                return false;
            }
            p = end;
        } else {
            FAILF("log line: unknown key '%s'", key);
            return false;
        }
        r->fields++;
        if (*p == ',') {
            p++;
        }
    }
    if (strcmp(p, "}") != 0 || r->fields != 10) {
        FAILF("log line: %d fields or text after the object: %s", r->fields, line);
        return false;
    }
    return true;
}

/* The records of a log file (at most max); -1 when it cannot be read. */
int read_log(const char *path, record *recs, int max)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        FAILF("cannot open the log %s", path);
        return -1;
    }
    char line[8192];
    int n = 0;
    while (fgets(line, sizeof line, f)) {
        size_t len = strlen(line);
        if (len == 0 || line[len - 1] != '\n') {
            FAILF("%s: a line without its newline", path);
            n = -1;
            break;
        }
        line[len - 1] = '\0';
        if (n < max && !parse_record(line, &recs[n])) {
            n = -1;
            break;
        }
        n++;
    }
    fclose(f);
    return n;
}

const record *find_record(const record *recs, int n, const char *input)
{
    for (int i = 0; i < n; i++) {
        if (strcmp(recs[i].input, input) == 0) {
            return &recs[i];
        }
    }
    return NULL;
}

/* Renders model to out with the tool; the pixels, or NULL. */
static uint8_t *render_png(const char *model, const char *out, int *w, int *h)
{
    run_result r;
    return render_read(ARGS("render", model, "-o", out, "--size", "320x240"), out, w, h, &r);
}

void check_same_render(const char *name, const void *const data[2], const size_t size[2],
                       int channel_tol, int max_pixels)
{
    char dir[1024], path[2][1100], png[2][1100];
    static const char *const stems[2] = { "plain", "packed" };
    uint8_t *px[2] = { NULL, NULL };
    int w[2] = { 0, 0 }, h[2] = { 0, 0 };
    fresh_dir(name, dir, sizeof dir);
    for (int i = 0; i < 2; i++) {
        snprintf(path[i], sizeof path[i], "%s/%s.glb", dir, stems[i]);
        snprintf(png[i], sizeof png[i], "%s/%s.png", dir, stems[i]);
        if (sr_test_write_file(path[i], data[i], size[i])) {
            px[i] = render_png(path[i], png[i], &w[i], &h[i]);
        } else {
            FAILF("cannot write %s", path[i]);
        }
    }
    if (px[0] && px[1] && w[0] == w[1] && h[0] == h[1]) {
        sr_test_compare_images(name, px[1], px[0], w[0], h[0], channel_tol, max_pixels);
    }
    free(px[0]);
    free(px[1]);
}

char *text_replaced(char *text, const char *from, const char *to)
{
    char *at = text ? strstr(text, from) : NULL;
    if (!at) {
        FAILF("'%s' not found", from);
        free(text);
        return NULL;
    }
    size_t cap = strlen(text) + strlen(to) + 1;
    char *out = malloc(cap);
    if (out) {
        snprintf(out, cap, "%.*s%s%s", (int)(at - text), text, to, at + strlen(from));
    }
    free(text);
    return out;
}

bool edit_text(wbuf *text, const char *from, const char *to)
{
    char *at = strstr((char *)text->p, from);
    if (!at) {
        FAILF("'%s' is not in the document", from);
        return false;
    }
    wbuf out = {0};
    wb_put(&out, text->p, (size_t)(at - (char *)text->p));
    wb_put(&out, to, strlen(to));
    wb_put(&out, at + strlen(from), strlen(at + strlen(from)) + 1);
    free(text->p);
    *text = out;
    return true;
}

void check_refused(const char *dir, size_t i, const void *data, size_t size,
                   const char *message)
{
    char path[1100], out[1100];
    snprintf(path, sizeof path, "%s/bad%zu.glb", dir, i);
    snprintf(out, sizeof out, "%s/bad%zu.png", dir, i);
    if (!sr_test_write_file(path, data, size)) {
        FAILF("cannot write %s", path);
        return;
    }
    run_result r;
    if (run(ARGS("render", path, "-o", out, "--size", "32x24"), &r)) {
        CHECK_EQ(r.status, 2);
        CHECK_EQ(count_lines(r.err), 1);
        CHECK_STR_CONTAINS(r.err, message);
        CHECK(!file_exists(out));
    }
}

/* One render of check_model_render's, its pixels or NULL after a failure. */
static uint8_t *render_model(const char *dir, const char *model, const char *size,
                             const char *const *extra, const char *threads, int *w, int *h)
{
    char out[1200];
    snprintf(out, sizeof out, "%s/threads_%s.png", dir, threads);
    const char *args[16] = { "render", model, "--size", size, "--aa", "none", "--threads",
                             threads, "-o", out };
    size_t n = 10;
    for (size_t i = 0; extra && extra[i] && n < 15; i++) {
        args[n++] = extra[i];
    }
    args[n] = NULL;
    run_result r;
    if (!run(args, &r) || r.status != 0) {
        FAILF("render: status %d: %s", r.status, r.err);
        return NULL;
    }
    CHECK(strstr(r.err, "warning") == NULL);
    uint8_t *px = NULL;
    sr_io_error err;
    if (sr_read_png(out, NULL, w, h, &px, &err) != SR_OK) {
        FAILF("%s", err.message);
        return NULL;
    }
    return px;
}

void check_model_render(const char *name, const char *file, char *text, const char *size,
                        const char *const *extra, const char *ref)
{
    char dir[1024], model[1100];
    fresh_dir(name, dir, sizeof dir);
    snprintf(model, sizeof model, "%s/%s", dir, file);
    bool written = text && write_text(model, text);
    free(text);
    if (!written) {
        FAILF("%s: not written", model);
        return;
    }
    int w, h, w3, h3;
    uint8_t *one = render_model(dir, model, size, extra, "1", &w, &h);
    uint8_t *three = render_model(dir, model, size, extra, "3", &w3, &h3);
    if (one && three && w == w3 && h == h3) {
        CHECK(memcmp(one, three, 4 * (size_t)w * (size_t)h) == 0);
        sr_test_check_image(ref, one, w, h, 3, (long)w * h / 200);
    } else if (one && three) {
        FAILF("%dx%d on one thread, %dx%d on three", w, h, w3, h3);
    }
    free(one);
    free(three);
}

/* How many animation frames (ANMF chunks) an extended WebP file has at
 * its top level, and whether its VP8X header flags an animation; -1 when
 * the file is not an extended WebP. */
int count_anmf(const uint8_t *p, size_t n, bool *animated)
{
    if (n < 30 || memcmp(p, "RIFF", 4) != 0 || memcmp(p + 8, "WEBPVP8X", 8) != 0) {
        return -1;
    }
    *animated = (p[20] & 0x02) != 0;   /* VP8X flags: the animation bit */
    int frames = 0;
    for (size_t at = 12; at + 8 <= n;) {
        uint32_t size = (uint32_t)p[at + 4] | (uint32_t)p[at + 5] << 8 |
                        (uint32_t)p[at + 6] << 16 | (uint32_t)p[at + 7] << 24;
        frames += memcmp(p + at, "ANMF", 4) == 0;
        at += 8 + size + (size & 1);
    }
    return frames;
}
