/* main.c - the softrast command-line tool: dispatches to a subcommand.
 * Each subcommand lives in its own file and is thin over the library.
 *
 * Standard output carries only text (help, version): images always go to
 * files, written atomically by sr_write_png.  SIGPIPE is ignored, so text
 * sent into a closed pipe (`softrast render --help | head -c1`) makes the
 * write fail with EPIPE instead of killing the process; main() flushes
 * stdout itself and turns any failure into exit status 1 (quietly for a
 * reader that went away, with one line for anything else, e.g. /dev/full). */
#include "cli.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

static int run(int argc, char **argv);

/* Flush stdout and report a failed write; the exit status to use. */
static int finish_stdout(int status)
{
    errno = 0;
    int e = 0;
    /* No handler in this process can interrupt a write, but a retry after
     * EINTR costs nothing (stdio keeps the unwritten bytes). */
    while (fflush(stdout) != 0) {
        e = errno;
        if (e != EINTR) {
            break;
        }
        clearerr(stdout);
        e = 0;
    }
    if (e == 0 && ferror(stdout)) {
        e = EIO; /* failed earlier, reason lost */
    }
    if (e == 0) {
        return status;
    }
    if (e != EPIPE) {
        cli_error("cannot write to standard output: %s", strerror(e));
    }
    return status != EXIT_OK ? status : EXIT_FAILURE_RUN;
}

int main(int argc, char **argv)
{
    signal(SIGPIPE, SIG_IGN);
    /* Into a pipe or file, hold all the text until finish_stdout: a help
     * text fits, so its one write(2) fails (or not) with an exact errno. */
    static char out_buf[1 << 16]; /* glibc ignores the size without a buffer */
    if (!isatty(STDOUT_FILENO)) {
        setvbuf(stdout, out_buf, _IOFBF, sizeof out_buf);
    }
    return finish_stdout(run(argc, argv));
}

static void usage(FILE *f)
{
    fprintf(f,
            "usage: softrast COMMAND [ARGS]\n"
            "\n"
            "A CPU graphics pipeline: every pixel is rasterized by softrast.\n"
            "\n"
            "commands:\n"
            "  render [MODEL] [options]   render a model file (OBJ, PLY, STL, ...) or the\n"
            "                             built-in teapot scene to a PNG; several models,\n"
            "                             a directory or --batch LIST render as a batch\n"
            "  thumbnail -s SIZE INPUT OUTPUT\n"
            "                             a SIZE x SIZE PNG preview of a model for file\n"
            "                             managers (the freedesktop thumbnailer convention)\n"
            "  info MODEL [--json]        what softrast reads in a model: draws, bounds,\n"
            "                             materials, textures, cameras, lights\n"
            "  svg INPUT.svg [options]    render an SVG drawing to a PNG with the 2D toolkit;\n"
            "                             several, a directory or --batch LIST render as\n"
            "                             a batch\n"
            "  demo NAME [options]        an image that shows a pipeline phenomenon\n"
            "                             ('softrast demo --help' lists them)\n"
            "  explain ALGORITHM [options]\n"
            "                             one primitive through one algorithm, step by\n"
            "                             step, as PNG frames, a contact sheet or a WebP\n"
            "  view [MODEL] [options]     an interactive window onto the pipeline (SDL2):\n"
            "                             orbit, zoom, and keys for every mode\n"
            "\n"
            "  softrast COMMAND --help    options of a command\n"
            "  softrast --version         version, and the optional formats built in\n");
}

static int run(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return EXIT_USAGE;
    }
    const char *cmd = argv[1];
    if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 || strcmp(cmd, "help") == 0) {
        usage(stdout);
        return EXIT_OK;
    }
    if (strcmp(cmd, "--version") == 0 || strcmp(cmd, "version") == 0) {
        printf("softrast %s\nbuilt with: %s\n", SR_VERSION_STRING, sr_io_features());
        return EXIT_OK;
    }
    if (strcmp(cmd, "render") == 0) {
        return cmd_render(argc - 1, argv + 1);
    }
    if (strcmp(cmd, "thumbnail") == 0) {
        return cmd_thumbnail(argc - 1, argv + 1);
    }
    if (strcmp(cmd, "info") == 0) {
        return cmd_info(argc - 1, argv + 1);
    }
    if (strcmp(cmd, "demo") == 0) {
        return cmd_demo(argc - 1, argv + 1);
    }
    if (strcmp(cmd, "explain") == 0) {
        return cmd_explain(argc - 1, argv + 1);
    }
    if (strcmp(cmd, "view") == 0) {
        return cmd_view(argc - 1, argv + 1);
    }
    if (strcmp(cmd, "svg") == 0) {
        return cmd_svg(argc - 1, argv + 1);
    }
    cli_error("unknown command '%s' (try 'softrast --help')", cmd);
    return EXIT_USAGE;
}
