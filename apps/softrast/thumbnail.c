/* thumbnail.c - `softrast thumbnail -s SIZE INPUT OUTPUT`, the freedesktop
 * thumbnailer convention (softrast.thumbnailer runs it as
 * `softrast thumbnail -s %s %i %o`): a SIZE x SIZE PNG of the model framed
 * by the default camera, in the default look.  It is a `softrast render`
 * with those options, so it loads, frames, refuses to write over its
 * input and writes atomically exactly as render does. */
#include "cli.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Freedesktop's largest thumbnail is 1024; a little room beyond it. */
#define THUMB_MAX_SIZE 4096

static void usage(FILE *f)
{
    fprintf(f,
            "usage: softrast thumbnail -s SIZE [--transparent] INPUT OUTPUT\n"
            "\n"
            "A SIZE x SIZE PNG preview of a model (OBJ, PLY, STL, glTF, GLB) for file\n"
            "managers: the model framed to fit, in the default look of 'softrast render'\n"
            "(msaa4 antialiasing).  INPUT is a path or a file:// URI.  Installed as\n"
            "share/thumbnailers/softrast.thumbnailer for GNOME and KDE.\n"
            "\n"
            "  -s, --size SIZE  the image's side in pixels (1 to %d)\n"
            "  --transparent    no background: an RGBA PNG, the model's edges blended\n"
            "                   into nothing\n"
            "  -h, --help       this text\n",
            THUMB_MAX_SIZE);
}

static int hex_digit(char c)
{
    return c >= '0' && c <= '9' ? c - '0'
         : c >= 'a' && c <= 'f' ? c - 'a' + 10
         : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
}

/* A file:// URI (host empty or "localhost") as a path, percent-decoded, in
 * `path`; anything else is taken as a path already.  false after one line
 * when the URI is not a local file's. */
static bool input_path(const char *input, char *path, size_t size)
{
    const char *scheme = "file://";
    if (strncmp(input, scheme, strlen(scheme)) != 0) {
        if (strlen(input) + 1 > size) {
            cli_error("thumbnail: the input path is too long");
            return false;
        }
        snprintf(path, size, "%s", input);
        return true;
    }
    const char *p = input + strlen(scheme);
    if (strncmp(p, "localhost/", 10) == 0) {
        p += 9;
    }
    if (*p != '/') {
        cli_error("thumbnail: '%s' is not a local file's URI (file:///PATH)", input);
        return false;
    }
    size_t n = 0;
    for (; *p; p++) {
        char c = *p;
        if (c == '%') {
            int hi = hex_digit(p[1]), lo = hi < 0 ? -1 : hex_digit(p[2]);
            if (lo < 0 || (hi == 0 && lo == 0)) {
                cli_error("thumbnail: '%s': bad percent escape", input);
                return false;
            }
            c = (char)(hi * 16 + lo);
            p += 2;
        }
        if (n + 1 >= size) {
            cli_error("thumbnail: the input path is too long");
            return false;
        }
        path[n++] = c;
    }
    path[n] = '\0';
    return true;
}

int cmd_thumbnail(int argc, char **argv)
{
    int size = 0;
    bool transparent = false;
    const char *files[2] = { NULL, NULL };
    int nfiles = 0;
    bool ended = false;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        cli_arg_kind kind = cli_arg(a, &ended);
        if (kind == CLI_ARG_END) {
            continue;
        } else if (kind == CLI_ARG_OPERAND) {
            if (nfiles == 2) {
                cli_error("thumbnail: expected INPUT OUTPUT, got a third file '%s'", a);
                return EXIT_USAGE;
            }
            files[nfiles++] = a;
            continue;
        }
        cli_opt opt;
        cli_split_option(a, &opt);
        const char *v;
        int help = cli_help_option(&opt, usage);
        if (help >= 0) {
            return help;
        }
        if (strcmp(opt.name, "-s") == 0 || strcmp(opt.name, "--size") == 0) {
            if (!(v = cli_option_value(&opt, argc, argv, &i)) ||
                !parse_int(opt.name, v, 1, THUMB_MAX_SIZE, &size)) {
                return EXIT_USAGE;
            }
        } else if (strcmp(opt.name, "--transparent") == 0) {
            if (!cli_option_flag(&opt)) {
                return EXIT_USAGE;
            }
            transparent = true;
        } else {
            cli_error("thumbnail: unknown option '%s' (try 'softrast thumbnail --help')", a);
            return EXIT_USAGE;
        }
    }
    if (size == 0 || nfiles < 2) {
        cli_error("thumbnail: usage: softrast thumbnail -s SIZE INPUT OUTPUT");
        return EXIT_USAGE;
    }
    char model[4096], output[4096], size_arg[32];
    if (!input_path(files[0], model, sizeof model)) {
        return EXIT_USAGE;
    }
    if (!cli_check_output_name("thumbnail: OUTPUT", files[1])) {
        return EXIT_USAGE;
    }
    if (strlen(files[1]) + 3 > sizeof output) {
        cli_error("thumbnail: the output path is too long");
        return EXIT_USAGE;
    }
    if (!cli_check_image_name("thumbnail: OUTPUT", files[1], false)) {
        return EXIT_USAGE;
    }
    snprintf(output, sizeof output, "%s%s", files[1][0] == '-' ? "./" : "", files[1]);
    /* Render would name its -o: say OUTPUT, the argument given here. */
    cli_inputs in = { 0 };
    cli_inputs_add(&in, model, "model");
    bool distinct = cli_check_output(&in, "thumbnail: OUTPUT", output);
    cli_inputs_free(&in);
    if (!distinct) {
        return EXIT_USAGE;
    }
    snprintf(size_arg, sizeof size_arg, "%dx%d", size, size);
    char *render_argv[10] = { "thumbnail", "-o", output, "--size", size_arg };
    int n = 5;
    if (transparent) {
        render_argv[n++] = "--background";
        render_argv[n++] = "transparent";
    }
    render_argv[n++] = "--";   /* a model named "-x.stl" is not an option */
    render_argv[n++] = model;
    return cmd_render(n, render_argv);
}
