/* demo.c - `softrast demo NAME [-o FILE] [--scale N]`: looks the demo up
 * in the table, runs it and writes its image atomically. */
#include "cli.h"
#include "demo.h"
#include "softrast_io.h"

#include <stdio.h>
#include <string.h>

/* Demos register here: one line each, X(id, "name", summary), the
 * function demo_<id> in demo_<id>.c.  The id is the name as a C
 * identifier (dashes become underscores: gouraud-highlight ->
 * demo_gouraud_highlight in demo_gouraud_highlight.c). */
#define DEMO_LIST(X) \
    X(lines, "lines", "every line algorithm on a star of lines, magnified") \
    X(fill, "fill", "even-odd vs nonzero fill of a star and of holes; area and supersampled AA") \
    X(floodfill, "floodfill", "flood and boundary fill, 4- vs 8-connected, leaking through a diagonal gap") \
    X(clip, "clip", "Sutherland-Hodgman clipping: a 2D polygon edge by edge; 3D triangles in clip space") \
    X(curves, "curves", "midpoint circles and ellipses, Bezier flattening, stroke joins and caps") \
    X(gouraud_highlight, "gouraud-highlight", "a specular highlight missed (interior) and smeared (at a vertex) by Gouraud, vs Phong") \
    X(perspective, "perspective", "checkerboard and gradient interpolated in screen space (affine) vs perspective-correctly") \
    X(zfight, "zfight", "z-fighting: D16/D24/D32F depth at several far/near ratios, reversed-Z, polygon offset") \
    X(normals, "normals", "a non-uniformly scaled sphere lit with normals transformed by M vs by M^-T") \
    X(viewport, "viewport", "one scene in wide and tall viewports, stretched vs aspect ratio preserved") \
    X(aa, "aa", "a star and a turned square aliased, MSAA 4/8/16, exact area, SSAA with four filters")

#define DEMO_DECLARE(id, name, summary) int demo_##id(sr_context *, const demo_args *, sr_framebuffer **);
DEMO_LIST(DEMO_DECLARE)
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
               "                      (default demo-NAME.png)\n"
               "  --scale N           magnification of pixel-level demos, 1..32\n");
}

int cmd_demo(int argc, char **argv)
{
    const char *name = NULL;
    char default_out[128];
    demo_args args = { NULL, 0 };
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            demo_help(stdout);
            return EXIT_OK;
        } else if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
            if (i + 1 >= argc) {
                cli_error("%s: missing value", a);
                return EXIT_USAGE;
            }
            args.output = argv[++i];
        } else if (strcmp(a, "--scale") == 0) {
            if (i + 1 >= argc) {
                cli_error("%s: missing value", a);
                return EXIT_USAGE;
            }
            if (!parse_int(a, argv[++i], 1, 32, &args.scale)) {
                return EXIT_USAGE;
            }
        } else if (a[0] == '-') {
            cli_error("demo: unknown option '%s' (try 'softrast demo --help')", a);
            return EXIT_USAGE;
        } else if (!name) {
            name = a;
        } else {
            cli_error("demo: more than one demo named ('%s' and '%s')", name, a);
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
    if (sr_make_context(&(sr_context_desc){0}, &ctx) != SR_OK) {
        cli_error("demo: cannot create a context");
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
