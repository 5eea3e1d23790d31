/* demo.c - `softrast demo NAME [-o FILE] [--scale N]`: looks the demo up
 * in the table, runs it and writes its image atomically. */
#include "cli.h"
#include "demo.h"
#include "softrast_io.h"

#include <stdio.h>
#include <string.h>

#define DEMO_ENTRY(id, name, summary) { name, summary, demo_##id },
const demo_entry demo_table[] = {
    DEMO_LIST(DEMO_ENTRY)
    { NULL, NULL, NULL },
};

static void demo_help(FILE *f)
{
    fprintf(f, "usage: softrast demo NAME [-o FILE] [--scale N]\n\n"
               "Render an image that shows one phenomenon of the pipeline, labelled.\n\n"
               "demos:\n");
    for (const demo_entry *d = demo_table; d->name; d++) {
        fprintf(f, "  %-20s %s\n", d->name, d->summary);
    }
    fprintf(f, "\noptions:\n"
               "  -o, --output FILE   PNG to write, or a JPEG for a name ending .jpg/.jpeg\n"
               "                      (another extension is refused; default demo-NAME.png)\n"
               "  --scale N           magnification of pixel-level demos, 1..32 (less\n"
               "                      for a demo whose image would pass 8192 a side)\n");
}

int demo_check_image(const char *name, int scale, int w, int h)
{
    if (w <= SR_MAX_FRAMEBUFFER_SIZE && h <= SR_MAX_FRAMEBUFFER_SIZE) {
        return EXIT_OK;
    }
    cli_error("demo %s: --scale %d makes a %dx%d image, over %d a side: give a smaller "
              "--scale", name, scale, w, h, SR_MAX_FRAMEBUFFER_SIZE);
    return EXIT_USAGE;
}

int cmd_demo(int argc, char **argv)
{
    const char *name = NULL;
    char default_out[128];
    demo_args args = { NULL, 0 };
    bool ended = false;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        cli_arg_kind kind = cli_arg(a, &ended);
        if (kind == CLI_ARG_END) {
            continue;
        } else if (kind == CLI_ARG_OPERAND) {
            if (name) {
                cli_error("demo: more than one demo named ('%s' and '%s')", name, a);
                return EXIT_USAGE;
            }
            name = a;
            continue;
        }
        cli_opt opt;
        cli_split_option(a, &opt);
        const char *v;
        int help = cli_help_option(&opt, demo_help);
        if (help >= 0) {
            return help;
        } else if (strcmp(opt.name, "-o") == 0 || strcmp(opt.name, "--output") == 0) {
            if (!(v = cli_option_value(&opt, argc, argv, &i)) ||
                !cli_check_output_name(opt.name, v) || !cli_check_image_name(opt.name, v, true)) {
                return EXIT_USAGE;
            }
            args.output = v;
        } else if (strcmp(opt.name, "--scale") == 0) {
            if (!(v = cli_option_value(&opt, argc, argv, &i)) ||
                !parse_int(opt.name, v, 1, 32, &args.scale)) {
                return EXIT_USAGE;
            }
        } else {
            cli_error("demo: unknown option '%s' (try 'softrast demo --help')", a);
            return EXIT_USAGE;
        }
    }
    if (!name) {
        demo_help(stderr);
        return EXIT_USAGE;
    }
    const demo_entry *d = demo_table;
    while (d->name && strcmp(d->name, name) != 0) {
        d++;
    }
    if (!d->name) {
        cli_error("demo: unknown demo '%s' (try 'softrast demo --help')", name);
        return EXIT_USAGE;
    }
    if (!args.output) {
        snprintf(default_out, sizeof default_out, "demo-%s.png", name);
        args.output = default_out;
    }

    sr_context *ctx = NULL;
    sr_set_last_error(NULL);
    sr_result made = sr_make_context(&(sr_context_desc){0}, &ctx);
    if (made != SR_OK) {
        cli_error("demo: cannot create a context: %s", cli_why(made));
        return EXIT_FAILURE_RUN;
    }
    sr_framebuffer *fb = NULL;
    int status = d->run(ctx, &args, &fb);
    if (status == EXIT_OK && fb) {
        sr_io_error err;
        int w = sr_framebuffer_width(fb), h = sr_framebuffer_height(fb);
        if (cli_write_image(args.output, w, h, sr_framebuffer_pixels(fb),
                            &(cli_image_options){ .png_level = -1 }, &err) != SR_OK) {
            fprintf(stderr, "%s\n", err.message);
            status = EXIT_FAILURE_RUN;
        }
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
    return status;
}
