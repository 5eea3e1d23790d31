/* svg_cmd.c - `softrast svg INPUT.svg [-o OUT.png] [--size WxH | --scale S]
 * [--background COLOR]`: the command around the library's SVG reader
 * (sr_render_svg, src/io/svg.c).  Reads the file whole (at most
 * SR_SVG_MAX_INPUT_BYTES), renders it and writes the PNG atomically.
 * Warnings go to stderr as they arise; a failure is one line
 * "FILE:LINE: what is wrong", exit status 2 for a bad document, 1 when the
 * run itself fails, and no output file. */
#include "cli.h"
#include "softrast_io.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void svg_help(FILE *f)
{
    fprintf(f, "usage: softrast svg INPUT.svg [-o OUT.png] [--size WxH | --scale S]\n"
               "                    [--background COLOR]\n\n"
               "Render an SVG 1.1 drawing (shapes, paths, transforms, fills, strokes and\n"
               "dashes, markers, style sheets, defs and use, gradients, patterns, clip paths,\n"
               "masks, group opacity, blend modes, PNG, JPEG and SVG images; no text or\n"
               "filters) with softrast's 2D toolkit; docs/draw2d.md lists what is supported.\n\n"
               "options:\n"
               "  -o, --output FILE    PNG to write, or a JPEG for a name ending .jpg/.jpeg\n"
               "                       (needs --background) (default: INPUT with .png)\n"
               "  --size WxH           output size in pixels (the viewBox is fitted in)\n"
               "  --scale S            output size = the drawing's size times S (default 1)\n"
               "  --background COLOR   opaque background (default transparent)\n");
}

/* The whole file into a malloc'd buffer; EXIT_OK, or the status after
 * printing one line. */
static int read_input(const char *input, char **data, size_t *size)
{
    /* The readers' open: a FIFO, device or directory is refused without
     * waiting for a writer. */
    FILE *fp;
    unsigned long long file_size;
    sr_io_error err;
    if (sr_open_file(input, "an SVG file", &fp, &file_size, &err) != SR_OK) {
        cli_error("svg: %s", err.message);
        return EXIT_USAGE;
    }
    size_t cap = 65536, n = 0;
    char *buf = malloc(cap);
    for (;;) {
        if (!buf) {
            fclose(fp);
            cli_error("svg: out of memory reading %s", input);
            return EXIT_FAILURE_RUN;
        }
        n += fread(buf + n, 1, cap - n, fp);
        if (ferror(fp)) {
            int e = errno;
            free(buf);
            fclose(fp);
            cli_error("svg: reading %s: %s", input, strerror(e));
            return EXIT_USAGE;
        }
        if (n < cap) {
            break; /* end of file */
        }
        if (cap > SR_SVG_MAX_INPUT_BYTES) {
            free(buf);
            fclose(fp);
            cli_error("svg: %s is larger than the %zu MiB limit", input,
                      SR_SVG_MAX_INPUT_BYTES >> 20);
            return EXIT_USAGE;
        }
        char *grown = realloc(buf, cap * 2);
        if (!grown) {
            free(buf);
        }
        buf = grown;
        cap *= 2;
    }
    fclose(fp);
    *data = buf;
    *size = n;
    return EXIT_OK;
}

/* The library's warnings, one line each on stderr as they arise. */
static void warn_stderr(void *user, const char *message)
{
    (void)user;
    fprintf(stderr, "%s\n", message);
}

int cmd_svg(int argc, char **argv)
{
    if (!sr_io_have_svg()) {
        cli_error("svg: this softrast was built without expat (install libexpat1-dev and "
                  "rebuild)");
        return EXIT_FAILURE_RUN;
    }
    const char *input = NULL, *output = NULL;
    sr_svg_desc opt = { .background = { 0, 0, 0, 0 }, .warn = warn_stderr };
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        bool has_value = i + 1 < argc;
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            svg_help(stdout);
            return EXIT_OK;
        } else if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0 || strcmp(a, "--size") == 0 ||
                   strcmp(a, "--scale") == 0 || strcmp(a, "--background") == 0) {
            if (!has_value) {
                cli_error("svg: %s: missing value", a);
                return EXIT_USAGE;
            }
            const char *v = argv[++i];
            if (a[1] == 'o' || a[2] == 'o') {
                output = v;
            } else if (strcmp(a, "--size") == 0) {
                if (!parse_size(a, v, &opt.width, &opt.height)) {
                    return EXIT_USAGE;
                }
            } else if (strcmp(a, "--scale") == 0) {
                float s;
                if (!parse_float(a, v, 0.001f, 1000.0f, &s)) {
                    return EXIT_USAGE;
                }
                opt.scale = s;
            } else {
                sr_vec3 c;
                if (!parse_color(a, v, &c)) {
                    return EXIT_USAGE;
                }
                opt.background = (sr_rgba){ c.x, c.y, c.z, 1 };
            }
        } else if (a[0] == '-' && a[1]) {
            cli_error("svg: unknown option '%s' (try 'softrast svg --help')", a);
            return EXIT_USAGE;
        } else if (!input) {
            input = a;
        } else {
            cli_error("svg: more than one input ('%s' and '%s')", input, a);
            return EXIT_USAGE;
        }
    }
    if (!input) {
        svg_help(stderr);
        return EXIT_USAGE;
    }
    if (opt.width && opt.scale > 0) {
        cli_error("svg: --size and --scale exclude each other");
        return EXIT_USAGE;
    }
    char default_out[4096];
    if (!output) {
        size_t n = strlen(input);
        if (n > 4 && strcmp(input + n - 4, ".svg") == 0) {
            n -= 4;
        }
        snprintf(default_out, sizeof default_out, "%.*s.png", (int)n, input);
        output = default_out;
    }
    if (cli_is_jpeg_name(output) && opt.background.a < 1) {
        cli_error("svg: -o: a JPEG has no transparency; give a --background for '%s'", output);
        return EXIT_USAGE;
    }
    cli_inputs inputs = { 0 };
    cli_inputs_add(&inputs, input, "SVG file");
    if (!cli_check_output(&inputs, "svg: -o", output)) {
        cli_inputs_free(&inputs);
        return EXIT_USAGE;
    }
    char *data = NULL;
    size_t size = 0;
    int status = read_input(input, &data, &size);
    if (status != EXIT_OK) {
        cli_inputs_free(&inputs);
        return status;
    }
    sr_context *ctx = NULL;
    if (sr_make_context(&(sr_context_desc){0}, &ctx) != SR_OK) {
        free(data);
        cli_inputs_free(&inputs);
        cli_error("svg: cannot create a context");
        return EXIT_FAILURE_RUN;
    }
    opt.name = input;
    sr_framebuffer *fb = NULL;
    sr_io_error err;
    sr_result r = sr_render_svg(ctx, data, size, &opt, &fb, NULL, &err);
    free(data);
    if (r != SR_OK) {
        fprintf(stderr, "%s\n", err.message);
        /* Out of memory is the run's failure; anything else the document's. */
        status = r == SR_OUT_OF_MEMORY ? EXIT_FAILURE_RUN : EXIT_USAGE;
    } else {
        int w = sr_framebuffer_width(fb), h = sr_framebuffer_height(fb);
        if (cli_write_image(output, w, h, sr_framebuffer_pixels(fb),
                            &(cli_image_options){ .png_level = -1,
                                                  .keep_alpha = opt.background.a < 1,
                                                  .inputs = &inputs },
                            &err) != SR_OK) {
            fprintf(stderr, "%s\n", err.message);
            status = EXIT_FAILURE_RUN;
        }
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
    cli_inputs_free(&inputs);
    return status;
}
