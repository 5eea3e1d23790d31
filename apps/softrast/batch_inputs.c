/* batch_inputs.c - the inputs of a batch and the names of its outputs:
 * model paths, directories searched for model files, glob patterns the
 * shell left alone, and list files (--batch), sorted into one list whose
 * order and numbering do not depend on how it was given. */
#include "batch.h"
#include "cli.h"

#include <dirent.h>
#include <errno.h>
#include <glob.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

/* Deeper than any real library; a bound for a link loop's sake. */
#define SCAN_MAX_DEPTH 32

static bool add_item(batch_list *l, const char *input, const char *output, const char *rel)
{
    if (l->count == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 64;
        batch_item *grown = realloc(l->items, cap * sizeof *grown);
        if (!grown) {
            return false;
        }
        l->items = grown;
        l->cap = cap;
    }
    batch_item it = { strdup(input), output ? strdup(output) : NULL, rel ? strdup(rel) : NULL, 0,
                      output != NULL };
    if (!it.input || (output && !it.output) || (rel && !it.rel)) {
        free(it.input);
        free(it.output);
        free(it.rel);
        return false;
    }
    l->items[l->count++] = it;
    return true;
}

/* A name the readers take: their own formats (glTF's in every build), and
 * Assimp's when built in. */
static bool is_model_name(const char *name)
{
    static const char *const own[] = { "stl", "obj", "ply", "gltf", "glb", NULL };
    static const char *const assimp[] = { "fbx", "dae", "3ds", "off", NULL };
    const char *dot = strrchr(name, '.');
    if (!dot || dot == name) {
        return false;
    }
    for (int i = 0; own[i]; i++) {
        if (strcasecmp(dot + 1, own[i]) == 0) {
            return true;
        }
    }
    for (int i = 0; assimp[i] && sr_io_have_assimp(); i++) {
        if (strcasecmp(dot + 1, assimp[i]) == 0) {
            return true;
        }
    }
    return false;
}

/* The files l->takes under path[0, len) (path has room for PATH_MAX bytes);
 * rel_from is where the part below the searched directory starts.
 * Directories reached through a symbolic link are not entered. */
static int scan_dir(batch_list *l, char *path, size_t len, size_t rel_from, int depth)
{
    batch_takes_fn takes = l->takes ? l->takes : is_model_name;
    DIR *d = opendir(path);
    if (!d) {
        cli_error("%s: %s", path, strerror(errno));
        return EXIT_USAGE;
    }
    int status = -1;
    struct dirent *e;
    while (status < 0 && (e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.') {
            continue;   /* ., .. and hidden entries (.git, editors' backups) */
        }
        size_t n = strlen(e->d_name);
        if (len + 1 + n + 1 > 4096) {
            cli_error("%s/%s: the path is too long", path, e->d_name);
            status = EXIT_USAGE;
            break;
        }
        path[len] = '/';
        memcpy(path + len + 1, e->d_name, n + 1);
        struct stat lst, st;
        if (lstat(path, &lst) == 0 && S_ISDIR(lst.st_mode)) {
            if (depth >= SCAN_MAX_DEPTH) {
                cli_error("%s: more than %d directories deep", path, SCAN_MAX_DEPTH);
                status = EXIT_USAGE;
            } else {
                status = scan_dir(l, path, len + 1 + n, rel_from, depth + 1);
            }
        } else if (takes(e->d_name) && stat(path, &st) == 0 && S_ISREG(st.st_mode)) {
            if (!add_item(l, path, NULL, path + rel_from)) {
                cli_error("out of memory listing the inputs");
                status = EXIT_FAILURE_RUN;
            }
        }
        path[len] = '\0';
    }
    closedir(d);
    return status;
}

static int add_path(batch_list *l, const char *arg)
{
    struct stat st;
    if (stat(arg, &st) == 0 && S_ISDIR(st.st_mode)) {
        char path[4096];
        size_t len = strlen(arg);
        while (len > 1 && arg[len - 1] == '/') {
            len--;   /* "models/" and "models" give the same paths */
        }
        if (len >= sizeof path) {
            cli_error("%s: the path is too long", arg);
            return EXIT_USAGE;
        }
        memcpy(path, arg, len);
        path[len] = '\0';
        return scan_dir(l, path, len, len + 1, 0);
    }
    /* Anything else is an input: one that cannot be read fails alone. */
    if (!add_item(l, arg, NULL, NULL)) {
        cli_error("out of memory listing the inputs");
        return EXIT_FAILURE_RUN;
    }
    return -1;
}

int batch_add_arg(batch_list *l, const char *arg)
{
    struct stat st;
    if (stat(arg, &st) == 0 || !strpbrk(arg, "*?[")) {
        return add_path(l, arg);
    }
    glob_t g;
    int r = glob(arg, 0, NULL, &g);
    if (r == GLOB_NOMATCH) {
        cli_error("%s: no file matches the pattern", arg);
        return EXIT_USAGE;
    }
    if (r != 0) {
        cli_error("%s: %s", arg, r == GLOB_NOSPACE ? "out of memory" : "cannot read a directory");
        globfree(&g);
        return r == GLOB_NOSPACE ? EXIT_FAILURE_RUN : EXIT_USAGE;
    }
    int status = -1;
    for (size_t i = 0; i < g.gl_pathc && status < 0; i++) {
        status = add_path(l, g.gl_pathv[i]);
    }
    globfree(&g);
    return status;
}

int batch_read_list(batch_list *l, const char *path)
{
    bool std_in = strcmp(path, "-") == 0;
    FILE *f = std_in ? stdin : fopen(path, "r");
    struct stat st;
    if (!f || fstat(fileno(f), &st) != 0 || S_ISDIR(st.st_mode)) {
        cli_error("--batch: %s: %s", path, f ? "is a directory" : strerror(errno));
        if (f && !std_in) {
            fclose(f);
        }
        return EXIT_USAGE;
    }
    char *line = NULL;
    size_t cap = 0;
    ssize_t n;
    int status = -1;
    while (status < 0 && (n = getline(&line, &cap, f)) >= 0) {
        while (n > 0 && (line[n - 1] == '\n' || line[n - 1] == '\r')) {
            line[--n] = '\0';
        }
        if (n == 0 || line[0] == '#') {
            continue;
        }
        char *tab = strchr(line, '\t');
        if (tab) {
            *tab = '\0';
        }
        const char *out = tab && tab[1] ? tab + 1 : NULL;
        if (!line[0]) {
            cli_error("--batch: %s: a line with an output but no input", path);
            status = EXIT_USAGE;
        } else if (!add_item(l, line, out, NULL)) {
            cli_error("out of memory listing the inputs");
            status = EXIT_FAILURE_RUN;
        }
    }
    if (status < 0 && ferror(f)) {
        cli_error("--batch: %s: %s", path, strerror(errno));
        status = EXIT_USAGE;
    }
    free(line);
    if (!std_in) {
        fclose(f);
    }
    return status;
}

static int by_input(const void *a, const void *b)
{
    const batch_item *x = a, *y = b;
    return strcmp(x->input, y->input);
}

static void item_free(batch_item *it)
{
    free(it->input);
    free(it->output);
    free(it->rel);
}

void batch_list_sort(batch_list *l)
{
    if (l->count > 1) {
        qsort(l->items, l->count, sizeof *l->items, by_input);
    }
    size_t n = 0;
    for (size_t i = 0; i < l->count; i++) {
        if (n > 0 && strcmp(l->items[n - 1].input, l->items[i].input) == 0) {
            item_free(&l->items[i]);   /* the first mention (and output) wins */
            continue;
        }
        l->items[n] = l->items[i];
        l->items[n].index = n;
        n++;
    }
    l->count = n;
}

void batch_list_free(batch_list *l)
{
    for (size_t i = 0; i < l->count; i++) {
        item_free(&l->items[i]);
    }
    free(l->items);
    *l = (batch_list){ 0 };
}

/* ---- output names ------------------------------------------------------ */

static const char *const fields[] = { "stem", "ext", "rel", "index", "view", NULL };

/* The field at p ("{name}"), its index in `fields`, or -1. */
static int field_at(const char *p, size_t *len)
{
    for (int k = 0; fields[k]; k++) {
        size_t n = strlen(fields[k]);
        if (strncmp(p + 1, fields[k], n) == 0 && p[1 + n] == '}') {
            *len = n + 2;
            return k;
        }
    }
    return -1;
}

bool batch_check_pattern(const char *pattern)
{
    /* ".." would climb out of --output-dir as a leading '/' would. */
    bool up = false;
    for (const char *c = pattern; *c; c = strchr(c, '/') ? strchr(c, '/') + 1 : "") {
        up |= strncmp(c, "..", 2) == 0 && (c[2] == '/' || c[2] == '\0');
    }
    if (!*pattern || pattern[0] == '/' || up) {
        cli_error("--name: '%s': expected a file name pattern below --output-dir", pattern);
        return false;
    }
    for (const char *p = pattern; *p; p++) {
        size_t len;
        if (*p == '{' && field_at(p, &len) < 0) {
            const char *end = strchr(p, '}');
            cli_error("--name: unknown field '%.*s' (expected {stem}, {ext}, {rel}, {index} or "
                      "{view})",
                      end ? (int)(end - p + 1) : (int)strlen(p), p);
            return false;
        }
    }
    return true;
}

/* The output of `it`, DIR/PATTERN filled in, in out[size]; false when
 * too long. */
static bool fill_pattern(const batch_item *it, const char *dir, const char *pattern, int view,
                         char *out, size_t size)
{
    const char *base = strrchr(it->input, '/');
    base = base ? base + 1 : it->input;
    const char *dot = strrchr(base, '.');
    size_t stem_len = dot && dot != base ? (size_t)(dot - base) : strlen(base);
    const char *rel = it->rel ? it->rel : base;
    const char *rel_dot = strrchr(rel, '.');
    size_t rel_len = rel_dot && rel_dot > rel && rel_dot[-1] != '/' && !strchr(rel_dot, '/')
                   ? (size_t)(rel_dot - rel) : strlen(rel);
    int n = snprintf(out, size, "%s/", dir);
    for (const char *p = pattern; *p && n >= 0 && (size_t)n < size;) {
        size_t len = 1;
        int k = *p == '{' ? field_at(p, &len) : -1;
        char index[32];
        snprintf(index, sizeof index, "%zu", k == 4 ? (size_t)view : it->index);
        const char *text = k == 0 ? base : k == 1 ? (stem_len < strlen(base) ? dot + 1 : "")
                         : k == 2 ? rel : k >= 3 ? index : p;
        size_t text_len = k == 0 ? stem_len : k == 2 ? rel_len : k < 0 ? 1 : strlen(text);
        n += snprintf(out + n, size - (size_t)n, "%.*s", (int)text_len, text);
        p += len;
    }
    return n >= 0 && (size_t)n < size;
}

static int by_output(const void *a, const void *b)
{
    const batch_item *const *x = a, *const *y = b;
    return strcmp((*x)->output, (*y)->output);
}

bool batch_view_output(const batch_list *l, const batch_item *it, int view, char *out,
                       size_t size)
{
    if (it->named) {
        return snprintf(out, size, "%s", it->output) < (int)size;
    }
    return fill_pattern(it, l->dir, l->pattern, view, out, size);
}

int batch_name_outputs(batch_list *l, const char *dir, const char *pattern)
{
    char out[4096];
    l->dir = dir;
    l->pattern = pattern;
    for (size_t i = 0; i < l->count; i++) {
        batch_item *it = &l->items[i];
        if (it->output) {
            continue;
        }
        if (!fill_pattern(it, dir, pattern, 0, out, sizeof out)) {
            cli_error("%s: the output name is too long", it->input);
            return EXIT_USAGE;
        }
        if (!(it->output = strdup(out))) {
            cli_error("out of memory naming the outputs");
            return EXIT_FAILURE_RUN;
        }
    }
    /* Two inputs to one output would overwrite each other: refuse before
     * drawing anything, so that every shard refuses alike. */
    const batch_item **sorted = malloc((l->count + 1) * sizeof *sorted);
    if (!sorted) {
        cli_error("out of memory naming the outputs");
        return EXIT_FAILURE_RUN;
    }
    for (size_t i = 0; i < l->count; i++) {
        sorted[i] = &l->items[i];
    }
    qsort(sorted, l->count, sizeof *sorted, by_output);
    int status = -1;
    for (size_t i = 1; i < l->count && status < 0; i++) {
        const batch_item *a = sorted[i - 1], *b = sorted[i];
        if (strcmp(a->output, b->output) != 0) {
            continue;
        }
        if (a->named || b->named) {
            cli_error("--batch: '%s' and '%s' would both be written to '%s' (give each its "
                      "own output in the list)", a->input, b->input, b->output);
        } else {
            cli_error("--name: '%s' and '%s' would both be written to '%s' "
                      "(add {ext} or {index} to --name)", a->input, b->input, b->output);
        }
        status = EXIT_USAGE;
    }
    free(sorted);
    return status;
}
