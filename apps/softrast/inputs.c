/* inputs.c - the files a command reads (model, MTL, textures, SVG, event
 * script, font), so that no command writes an image over one of them: the
 * atomic write would replace the input with the image.  Files are compared
 * by device and inode, so another name, a symbolic link or a hard link to
 * an input is refused as well; an output that does not exist yet is not
 * an input. */
#include "cli.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

struct cli_input {
    dev_t dev;
    ino_t ino;
    const char *kind;   /* "model", "texture", ... (a string literal) */
    char *path;
    unsigned reads;     /* times read (cli_inputs_read) */
};

/* The entry of the file `st` describes, or NULL. */
static cli_input *find_file(const cli_inputs *in, const struct stat *st)
{
    for (size_t i = 0; i < in->count; i++) {
        if (in->items[i].dev == st->st_dev && in->items[i].ino == st->st_ino) {
            return &in->items[i];
        }
    }
    return NULL;
}

bool cli_inputs_add(cli_inputs *in, const char *path, const char *kind)
{
    struct stat st;
    if (!path || stat(path, &st) != 0) {
        return true;    /* nothing there to overwrite; reading it reports why */
    }
    if (find_file(in, &st)) {
        return true;
    }
    if (in->count == in->cap) {
        size_t cap = in->cap ? 2 * in->cap : 8;
        cli_input *grown = realloc(in->items, cap * sizeof *grown);
        if (!grown) {
            in->incomplete = true;
            return false;
        }
        in->items = grown;
        in->cap = cap;
    }
    char *copy = strdup(path);
    if (!copy) {
        in->incomplete = true;
        return false;
    }
    in->items[in->count++] = (cli_input){ st.st_dev, st.st_ino, kind, copy, 0 };
    return true;
}

bool cli_inputs_read(cli_inputs *in, const char *path, const char *kind)
{
    if (!cli_inputs_add(in, path, kind)) {
        return false;
    }
    struct stat st;
    cli_input *hit = path && stat(path, &st) == 0 ? find_file(in, &st) : NULL;
    if (hit) {
        hit->reads++;
    }
    return true;
}

void cli_inputs_report(const cli_inputs *in)
{
    for (size_t i = 0; i < in->count; i++) {
        const cli_input *it = &in->items[i];
        if (it->reads > 0) {
            fprintf(stderr, "softrast: read %s (%s) %u time%s\n", it->path, it->kind, it->reads,
                    it->reads == 1 ? "" : "s");
        }
    }
}

/* The input that `output` names, or NULL. */
static const cli_input *find_input(const cli_inputs *in, const char *output)
{
    struct stat st;
    if (!in || stat(output, &st) != 0) {
        return NULL;
    }
    for (size_t i = 0; i < in->count; i++) {
        if (in->items[i].dev == st.st_dev && in->items[i].ino == st.st_ino) {
            return &in->items[i];
        }
    }
    return NULL;
}

bool cli_output_is_input(const cli_inputs *in, const char *output, char *why, size_t why_size)
{
    if (!output) {
        return false;
    }
    if (in && in->incomplete) {
        snprintf(why, why_size, "out of memory listing the inputs, so '%s' may be one", output);
        return true;
    }
    const cli_input *hit = find_input(in, output);
    if (hit) {
        snprintf(why, why_size, "'%s' is the %s being read (%s); choose another output file",
                 output, hit->kind, hit->path);
    }
    return hit != NULL;
}

bool cli_check_output_name(const char *opt, const char *output)
{
    if (output && !*output) {
        cli_error("%s: the file name is empty", opt);
        return false;
    }
    if (output && (strcmp(output, "-") == 0 || strcmp(output, "--") == 0)) {
        /* opt may be "svg: -o": the option is its last word. */
        const char *name = strrchr(opt, ' ') ? strrchr(opt, ' ') + 1 : opt;
        if (output[1]) {
            cli_error("%s: '--' names no file here (it is the value of %s, not the end of the "
                      "options); name a file, ./-- for one called '--'", opt, name);
        } else {
            cli_error("%s: '-' names no file here (softrast writes nothing to standard "
                      "output); name a file, ./- for one called '-'", opt);
        }
        return false;
    }
    return true;
}

bool cli_check_output(const cli_inputs *in, const char *opt, const char *output)
{
    if (!cli_check_output_name(opt, output)) {
        return false;
    }
    char why[8400];
    if (cli_output_is_input(in, output, why, sizeof why)) {
        cli_error("%s: %s", opt, why);
        return false;
    }
    return true;
}

void cli_inputs_free(cli_inputs *in)
{
    for (size_t i = 0; i < in->count; i++) {
        free(in->items[i].path);
    }
    free(in->items);
    *in = (cli_inputs){ 0 };
}

/* A path's directory from the root, spelt plainly (no "//" or "/./"),
 * into dir; returns its last name. */
static const char *split_path(const char *path, char *dir, size_t size)
{
    const char *slash = strrchr(path, '/');
    size_t n = 0;
    if (path[0] != '/' && getcwd(dir, size - 1)) {
        n = strlen(dir);
        dir[n++] = '/';
    }
    for (const char *c = path; slash && c < slash && n + 1 < size; c++) {
        bool dot = c[0] == '.' && (c == path || c[-1] == '/') && (c[1] == '/');
        if (dot) {
            c++;        /* past "./" */
            continue;
        }
        if (*c == '/' && n > 0 && dir[n - 1] == '/') {
            continue;   /* a second '/' */
        }
        dir[n++] = *c;
    }
    if (n > 1 && dir[n - 1] == '/') {
        n--;
    }
    snprintf(dir + n, size - n, "%s", n ? "" : "/");
    return slash ? slash + 1 : path;
}

/* Two spellings of one output that does not exist yet are the same file
 * when their last names match and their directories are one directory
 * ("d/f", "./d//f", a link to d), or, not made yet, are written alike. */
bool cli_same_output(const char *a, const char *b)
{
    struct stat sa, sb;
    if (stat(a, &sa) == 0 && stat(b, &sb) == 0) {
        return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    }
    char da[4096], db[4096];
    const char *na = split_path(a, da, sizeof da), *nb = split_path(b, db, sizeof db);
    if (strcmp(na, nb) != 0) {
        return false;
    }
    if (stat(da, &sa) == 0 && stat(db, &sb) == 0) {
        return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    }
    return strcmp(da, db) == 0;
}
