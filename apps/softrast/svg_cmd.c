/* svg_cmd.c - `softrast svg INPUT.svg [-o OUT.png] [--size WxH | --scale S]
 * [--background COLOR]`: the command around the library's SVG reader
 * (sr_render_svg, src/io/svg.c).  Reads the file whole (at most
 * SR_SVG_MAX_INPUT_BYTES), renders it and writes the PNG atomically.
 * Warnings go to stderr as they arise; a failure is one line
 * "FILE:LINE: what is wrong", exit status 2 for a bad document, 1 when the
 * run itself fails, and no output file.  Several inputs, a directory or
 * --batch make a batch (batch_session.c): --threads threads draw
 * drawings side by side, each slot of the batch with a context of its
 * own, while SVG_WRITERS threads write the ones before. */
#include "batch_session.h"
#include "cli.h"
#include "softrast_io.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static void svg_help(FILE *f)
{
    fprintf(f, "usage: softrast svg INPUT.svg [-o OUT.png] [--size WxH | --scale S]\n"
               "                    [--background COLOR]\n\n"
               "Render an SVG 1.1 drawing (shapes, paths, transforms, fills, strokes and\n"
               "dashes, markers, style sheets, defs and use, gradients, patterns, clip paths,\n"
               "masks, group opacity, blend modes, filter effects, PNG, JPEG and SVG images,\n"
               "text in builds with fontconfig, HarfBuzz and FreeType) with softrast's 2D\n"
               "toolkit; docs/draw2d.md lists what is supported.\n"
               "A gzip-compressed drawing (.svgz, known by its first bytes) reads as well.\n\n"
               "options:\n"
               "  -o, --output FILE    PNG to write, or a JPEG for a name ending .jpg/.jpeg\n"
               "                       (needs --background); another extension is refused\n"
               "                       (default: INPUT with .png)\n"
               "  --size WxH           output size in pixels (the viewBox is fitted in);\n"
               "                       refused when the drawings in hand (a batch's\n"
               "                       --threads at once, the images being written) need\n"
               "                       more memory than the machine has or SR_MEMORY_LIMIT\n"
               "                       allows\n"
               "  --scale S            output size = the drawing's size times S (default 1)\n"
               "  --background COLOR   opaque background (default transparent)\n"
               "  --threads N          drawings drawn at once in a batch (default: SR_THREADS\n"
               "                       or CPUs)\n"
               "\n"
               "batch (several INPUTs, a directory, a glob pattern or --batch):\n"
               "  softrast svg INPUT.svg|DIR|PATTERN... [--batch LIST] [options]\n"
               "                           renders every drawing in one process with the\n"
               "                           options above; a directory is searched (below it\n"
               "                           too) for .svg and .svgz files; a quoted pattern\n"
               "                           ('icons/*.svg') is expanded here\n");
    batch_help_options(f);
    batch_help_status(f);
}

/* The whole file into a malloc'd buffer; EXIT_OK, or the status with
 * why in why[size]. */
static int read_input(const char *input, char **data, size_t *size, char *why, size_t why_size)
{
    /* The readers' open: a FIFO, device or directory is refused without
     * waiting for a writer. */
    FILE *fp;
    unsigned long long file_size;
    sr_io_error err;
    if (sr_open_file(input, "an SVG file", &fp, &file_size, &err) != SR_OK) {
        snprintf(why, why_size, "%s", err.message);
        return EXIT_USAGE;
    }
    size_t cap = 65536, n = 0;
    char *buf = malloc(cap);
    int status = EXIT_OK;
    for (;;) {
        if (!buf) {
            snprintf(why, why_size, "out of memory reading %s", input);
            status = EXIT_FAILURE_RUN;
            break;
        }
        n += fread(buf + n, 1, cap - n, fp);
        if (ferror(fp)) {
            snprintf(why, why_size, "reading %s: %s", input, strerror(errno));
            status = EXIT_USAGE;
            break;
        }
        if (n < cap) {
            break; /* end of file */
        }
        if (cap > SR_SVG_MAX_INPUT_BYTES) {
            snprintf(why, why_size, "%s is larger than the %zu MiB limit", input,
                     SR_SVG_MAX_INPUT_BYTES >> 20);
            status = EXIT_USAGE;
            break;
        }
        char *grown = realloc(buf, cap * 2);
        if (!grown) {
            free(buf);
        }
        buf = grown;
        cap *= 2;
    }
    fclose(fp);
    if (status != EXIT_OK) {
        free(buf);
        return status;
    }
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

/* The command line: the drawing's options, the inputs, and a batch's
 * options. */
typedef struct svg_args {
    sr_svg_desc desc;
    const char *output;        /* -o */
    const char *const *inputs; /* argv's, moved to its front */
    size_t count;
    int threads;               /* --threads, or 0 */
    batch_common batch;
} svg_args;

/* -1, or an exit status (EXIT_OK after --help) after one line.  The
 * inputs are moved to argv[1..], over arguments already read. */
static int parse_args(int argc, char **argv, svg_args *a)
{
    a->inputs = (const char *const *)argv + 1;
    bool ended = false;
    for (int i = 1; i < argc; i++) {
        const char *s = argv[i];
        cli_arg_kind kind = cli_arg(s, &ended);
        if (kind == CLI_ARG_END) {
            continue;
        } else if (kind == CLI_ARG_OPERAND) {
            argv[1 + a->count++] = argv[i];
            continue;
        }
        int taken = batch_take_option(&a->batch, argc, argv, &i);
        if (taken == 1) {
            continue;
        } else if (taken != 0) {
            return taken;
        }
        cli_opt opt;
        cli_split_option(s, &opt);
        s = opt.name;
        int help = cli_help_option(&opt, svg_help);
        if (help >= 0) {
            return help;
        } else if (strcmp(s, "-o") == 0 || strcmp(s, "--output") == 0 || strcmp(s, "--size") == 0 ||
                   strcmp(s, "--scale") == 0 || strcmp(s, "--background") == 0 ||
                   strcmp(s, "--threads") == 0) {
            const char *v = cli_option_value(&opt, argc, argv, &i);
            if (!v) {
                return EXIT_USAGE;
            }
            if (s[1] == 'o' || s[2] == 'o') {
                a->output = v;
                if (!cli_check_output_name(s, v) || !cli_check_image_name(s, v, true)) {
                    return EXIT_USAGE;
                }
            } else if (strcmp(s, "--size") == 0) {
                if (!parse_size(s, v, &a->desc.width, &a->desc.height)) {
                    return EXIT_USAGE;
                }
            } else if (strcmp(s, "--threads") == 0) {
                if (!parse_int(s, v, 1, BATCH_DRAW_MAX_THREADS, &a->threads)) {
                    return EXIT_USAGE;
                }
            } else if (strcmp(s, "--scale") == 0) {
                float f;
                if (!parse_float(s, v, 0.001f, 1000.0f, &f)) {
                    return EXIT_USAGE;
                }
                a->desc.scale = f;
            } else {
                sr_vec3 c;
                if (!parse_color(s, v, &c)) {
                    return EXIT_USAGE;
                }
                a->desc.background = (sr_rgba){ c.x, c.y, c.z, 1 };
            }
        } else {
            cli_error("svg: unknown option '%s' (try 'softrast svg --help')", argv[i]);
            return EXIT_USAGE;
        }
    }
    if (a->count == 0 && !a->batch.list) {
        svg_help(stderr);
        return EXIT_USAGE;
    }
    if (a->desc.width && a->desc.scale > 0) {
        cli_error("svg: --size and --scale exclude each other");
        return EXIT_USAGE;
    }
    return -1;
}

/* Writer threads: a drawing takes far less time than the fsync of its
 * image, and a file system takes several at once. */
#define SVG_WRITERS 4

/* Whether --size's drawings fit the memory limit: -1, or EXIT_USAGE after
 * one line.  One drawing takes its RGBA and the image as it is written.
 * A batch of `inputs` drawn by `threads` threads holds the drawings in
 * hand (batch_draw.c: two slots a thread, finished ones waiting only
 * while below BATCH_DRAW_MAX_BYTES), the writer's copies (batch_writer.c:
 * one a thread and one more, each kept for the next image) and one more
 * image of working memory for the drawing and the encoders.  A size
 * that comes from the document is the library's to refuse (max_side).
 * What the limit leaves is shared by the drawings drawn at once for
 * their layers (group opacity, masks, clip paths: desc->max_layer_bytes),
 * which only the document says how deep they nest. */
static int check_size(const svg_args *a, size_t inputs, int threads, sr_svg_desc *desc)
{
    uint64_t image = (uint64_t)a->desc.width * (uint64_t)a->desc.height * 4, need = 0;
    uint64_t t = inputs == 0 ? 1 : (uint64_t)threads < inputs ? (uint64_t)threads : inputs;
    char what[128];
    int n = snprintf(what, sizeof what, "svg: --size %dx%d", a->desc.width, a->desc.height);
    const char *lower = "give a smaller --size";
    if (image && inputs == 0) {
        need = 2 * image;
    } else if (image) {
        uint64_t drawings = t + BATCH_DRAW_MAX_BYTES / image;
        drawings = drawings < 2 * t ? drawings : 2 * t;
        drawings = drawings < inputs ? drawings : inputs;
        uint64_t written = inputs < SVG_WRITERS + 1 ? inputs : SVG_WRITERS + 1;
        snprintf(what + n, sizeof what - (size_t)n, " with --threads %d (%d drawings at once)",
                 threads, (int)drawings);
        need = (drawings + written + 1) * image;
        lower = "give a smaller --size or --threads";
    }
    if (image) {
        int status = cli_check_memory(what, need, lower);
        if (status >= 0) {
            return status;
        }
    }
    sr_memory_limit_info limit;
    sr_io_error err;
    if (sr_query_memory_limit(&limit, &err) != SR_OK) {
        cli_error("%s", err.message);
        return EXIT_USAGE;
    }
    uint64_t left = (limit.bytes - need) / t;
    desc->max_layer_bytes = left > 0 ? left : 1;  /* 0 would mean no limit */
    return -1;
}

/* The length of name's .svg or .svgz (gzip-compressed) ending, any case;
 * 0 for another name. */
static size_t svg_suffix(const char *name)
{
    const char *dot = strrchr(name, '.');
    return dot && dot != name && (strcasecmp(dot, ".svg") == 0 || strcasecmp(dot, ".svgz") == 0)
               ? strlen(dot) : 0;
}

static int render_one(svg_args *a)
{
    const char *input = a->inputs[0], *output = a->output;
    sr_svg_desc opt = a->desc;
    char default_out[4096];
    if (!output) {
        size_t n = strlen(input) - svg_suffix(input);
        snprintf(default_out, sizeof default_out, "%.*s.png", (int)n, input);
        output = default_out;
    }
    if (cli_is_jpeg_name(output) && opt.background.a < 1) {
        cli_error("svg: -o: a JPEG has no transparency; give a --background for '%s'", output);
        return EXIT_USAGE;
    }
    int status = check_size(a, 0, 1, &opt);
    if (status >= 0) {
        return status;
    }
    cli_inputs inputs = { 0 };
    cli_inputs_add(&inputs, input, "SVG file");
    if (!cli_check_output(&inputs, "svg: -o", output)) {
        cli_inputs_free(&inputs);
        return EXIT_USAGE;
    }
    char *data = NULL, why[1024];
    size_t size = 0;
    status = read_input(input, &data, &size, why, sizeof why);
    if (status != EXIT_OK) {
        cli_inputs_free(&inputs);
        cli_error("svg: %s", why);
        return status;
    }
    sr_context *ctx = NULL;
    sr_set_last_error(NULL);
    sr_result made = sr_make_context(&(sr_context_desc){ .threads = a->threads }, &ctx);
    if (made != SR_OK) {
        free(data);
        cli_inputs_free(&inputs);
        cli_error("svg: cannot create a context: %s", cli_why(made));
        return EXIT_FAILURE_RUN;
    }
    opt.name = input;
    opt.warn = warn_stderr;
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

/* ---- a batch ------------------------------------------------------------ */

/* A slot of the batch: a drawing thread draws with its context, which
 * draws on that thread alone (the 2D toolkit fills on the caller's). */
typedef struct svg_slot {
    sr_context *ctx;           /* made at the slot's first drawing */
    sr_framebuffer *fb;        /* its drawing, until released */
} svg_slot;

/* What every drawing of a batch is rendered with. */
typedef struct svg_batch {
    sr_svg_desc desc;
    svg_slot *slots;
    int slot_count;
} svg_batch;

/* The warnings of one drawing, held for one line after it. */
typedef struct held_warnings {
    char *buf;
    size_t size;
} held_warnings;

static void warn_held(void *user, const char *message)
{
    held_warnings *h = user;
    size_t n = strlen(h->buf);
    if (n + 1 < h->size) {
        snprintf(h->buf + n, h->size - n, "%s%s", n ? "; " : "", message);
    }
}

static bool is_svg_name(const char *name)
{
    return svg_suffix(name) > 0;
}

/* batch_draw_fn: read and render one drawing, on a drawing thread. */
static bool draw_one(void *user, int slot, const batch_item *it, batch_picture *pic,
                     batch_record *rec, char *message, size_t size)
{
    const svg_batch *sb = user;
    svg_slot *sl = &sb->slots[slot];
    if (!sl->ctx) {
        sr_set_last_error(NULL);
        sr_result made = sr_make_context(&(sr_context_desc){ .threads = 1 }, &sl->ctx);
        if (made != SR_OK) {
            snprintf(message, size, "cannot create a context: %s", cli_why(made));
            return false;
        }
    }
    if (cli_is_jpeg_name(it->output) && sb->desc.background.a < 1) {
        snprintf(message, size, "'%s': a JPEG has no transparency; give a --background",
                 it->output);
        return false;
    }
    double t0 = batch_now_ms();
    char *data = NULL;
    size_t bytes = 0;
    if (read_input(it->input, &data, &bytes, message, size) != EXIT_OK) {
        return false;
    }
    double t1 = batch_now_ms();
    held_warnings held = { message, size };
    sr_svg_desc d = sb->desc;
    d.name = it->input;
    d.warn = warn_held;
    d.warn_user = &held;
    sr_io_error err;
    sr_result r = sr_render_svg(sl->ctx, data, bytes, &d, &sl->fb, NULL, &err);
    free(data);
    rec->load_ms = t1 - t0;
    rec->render_ms = batch_now_ms() - t1;
    if (r != SR_OK) {
        snprintf(message, size, "%s", err.message);
        return false;
    }
    *pic = (batch_picture){ .rgba = sr_framebuffer_pixels(sl->fb),
                            .width = sr_framebuffer_width(sl->fb),
                            .height = sr_framebuffer_height(sl->fb),
                            .image = { .png_level = -1, .keep_alpha = d.background.a < 1 } };
    return true;
}

/* batch_release_fn: the slot's drawing is in the writer's hands. */
static void release_one(void *user, int slot)
{
    svg_slot *sl = &((svg_batch *)user)->slots[slot];
    sr_destroy_framebuffer(sl->ctx, sl->fb);
    sl->fb = NULL;
}

/* --threads, or the library's default for a context (SR_THREADS, else
 * the CPUs), as `softrast render` takes it. */
static int drawing_threads(int asked)
{
    sr_context *probe = NULL;
    if (asked > 0 || sr_make_context(&(sr_context_desc){0}, &probe) != SR_OK) {
        return asked > 0 ? asked : 1;
    }
    int n = sr_context_threads(probe);
    sr_destroy_context(probe);
    return n;
}

static int render_batch(svg_args *a)
{
    const batch_common *c = &a->batch;
    if (a->output) {
        cli_error("-o: names one output; a batch names its outputs with --output-dir and --name");
        return EXIT_USAGE;
    }
    if (c->name &&
        (!batch_check_pattern(c->name) || !cli_check_image_name("--name", c->name, true))) {
        return EXIT_USAGE;
    }
    if (c->name && cli_is_jpeg_name(c->name) && a->desc.background.a < 1) {
        cli_error("--name: '%s' names JPEGs, which have no transparency; give a --background",
                  c->name);
        return EXIT_USAGE;
    }
    batch_session s;
    batch_drawer drawer = { .draw = draw_one, .release = release_one,
                            .threads = drawing_threads(a->threads) };
    svg_batch sb = { .desc = a->desc, .slot_count = batch_draw_slots(drawer.threads) };
    drawer.user = &sb;
    int status = batch_session_gather(&s, c, a->inputs, a->count, is_svg_name,
                                      "svg: no SVG files");
    if (status < 0) {
        status = check_size(a, batch_session_mine(&s), drawer.threads, &sb.desc);
    }
    if (status < 0) {
        status = batch_session_name(&s, "{rel}.png");
    }
    if (status < 0) {
        status = batch_session_open(&s);
    }
    if (status < 0 && !(sb.slots = calloc((size_t)sb.slot_count, sizeof *sb.slots))) {
        cli_error("svg: out of memory");
        status = EXIT_FAILURE_RUN;
    }
    if (status < 0) {
        batch_session_begin(&s, batch_session_mine(&s), SVG_WRITERS);
        batch_session_each(&s, &drawer);
        status = batch_session_end(&s);
    }
    for (int i = 0; sb.slots && i < sb.slot_count; i++) {
        sr_destroy_framebuffer(sb.slots[i].ctx, sb.slots[i].fb);
        sr_destroy_context(sb.slots[i].ctx);
    }
    free(sb.slots);
    return batch_session_close(&s, status);
}

int cmd_svg(int argc, char **argv)
{
    svg_args a = { .desc = { .background = { 0, 0, 0, 0 } } };
    int status = parse_args(argc, argv, &a);
    /* After the arguments, so that --help still answers (the manual page
     * and the completions are made from it) and the line names a file. */
    if (status < 0 && !sr_io_have_svg()) {
        cli_message("%s: cannot read SVG drawings (softrast was built without expat; install "
                    "libexpat1-dev and rebuild)", a.count > 0 ? a.inputs[0] : "softrast svg");
        return EXIT_USAGE;
    }
    if (status < 0) {
        status = batch_asked(&a.batch, a.inputs, a.count) ? render_batch(&a) : render_one(&a);
    }
    return status;
}
