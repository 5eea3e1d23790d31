/* main.c - the softrast command-line tool: dispatches to a subcommand.
 * Each subcommand lives in its own file and is thin over the library. */
#include "cli.h"

#include <stdio.h>
#include <string.h>

static void usage(FILE *f)
{
    fprintf(f,
            "usage: softrast COMMAND [ARGS]\n"
            "\n"
            "A CPU graphics pipeline: every pixel is rasterized by softrast.\n"
            "\n"
            "commands:\n"
            "  render [MODEL] [options]   render a model file (OBJ, PLY, STL, ...) or the\n"
            "                             built-in teapot scene to a PNG\n"
            "  svg INPUT.svg [options]    render an SVG drawing to a PNG with the 2D toolkit\n"
            "  demo NAME [options]        an image that shows a pipeline phenomenon\n"
            "                             ('softrast demo --help' lists them)\n"
            "\n"
            "  softrast COMMAND --help    options of a command\n"
            "  softrast --version         version\n");
}

int main(int argc, char **argv)
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
        printf("softrast %s\n", SR_VERSION_STRING);
        return EXIT_OK;
    }
    if (strcmp(cmd, "render") == 0) {
        return cmd_render(argc - 1, argv + 1);
    }
    if (strcmp(cmd, "demo") == 0) {
        return cmd_demo(argc - 1, argv + 1);
    }
    if (strcmp(cmd, "svg") == 0) {
        return cmd_svg(argc - 1, argv + 1);
    }
    cli_error("unknown command '%s' (try 'softrast --help')", cmd);
    return EXIT_USAGE;
}
