/* batch.c - `softrast render` over many models in one process: several
 * MODEL arguments, directories, glob patterns or a --batch list, each
 * read by one render job while the one before it is drawn by another
 * (batch_reader.c) and written while the one after it is drawn
 * (batch_writer.c); the two jobs' contexts (and their thread pools) and
 * framebuffers serve every input in turn.  A bad input is one line on
 * stderr and one record in the log, and the batch goes on; the exit
 * status says whether all, some or none of the inputs were rendered. */
#include "batch.h"
#include "batch_anim.h"
#include "batch_reader.h"
#include "batch_session.h"
#include "batch_views.h"
#include "batch_writer.h"
#include "cli.h"
#include "render.h"
#include "render_options.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

typedef struct batch_opts {
    batch_common c;            /* --name's default: {rel}.png, {rel}_{view}.png */
    const char *views_arg, *sheet, *columns_arg;  /* --views N, --sheet FILE, --sheet-columns N */
    const char *animate;       /* --animate PATTERN: each model's views as an animated WebP */
    const char *fps_arg;       /* --fps N: --animate's frames a second with --animation */
    int views, columns, fps;
    char **job_argv;           /* the render options, for render_job_configure */
    int job_argc;
    bool any;                  /* a batch option was given */
    bool output;               /* -o was given */
    const char **models;       /* the MODEL arguments */
    size_t model_count, model_cap;
} batch_opts;

static void batch_help(void)
{
    printf(
        "\n"
        "batch (several MODELs, a directory, a glob pattern or --batch):\n"
        "  softrast render MODEL|DIR|PATTERN... [--batch LIST] [options]\n"
        "                           renders every model in one process with the options\n"
        "                           above; a directory is searched (below it too) for\n"
        "                           .stl .obj .ply .gltf .glb files (and Assimp's formats\n"
        "                           when built with it); a quoted pattern\n"
        "                           ('models/*.stl') is expanded here\n");
    batch_help_options(stdout);
    printf(
        "  --views N                N views round each model, 360/N degrees apart about\n"
        "                           the vertical axis (a turntable), each its own image:\n"
        "                           {view} in --name (default {rel}_{view}.png)\n"
        "  --sheet FILE             one contact sheet of every image instead, each\n"
        "                           captioned with its model's name (and view's angle)\n"
        "  --sheet-columns N        images a row (default: one model's views a row, or\n"
        "                           about square); the sheet is held whole, so its\n"
        "                           memory counts against --size's limit\n"
        "  --animate PATTERN        each model's views as one animated WebP, a turn in\n"
        "                           3 s, named like --name (e.g. turn.webp, {rel}.webp;\n"
        "                           --views defaults to 24); with --animation, the glTF\n"
        "                           animation played instead, from --time (default 0)\n"
        "                           to its end, in the first frame's camera\n"
        "  --fps N                  --animate --animation's frames a second, 1..120\n"
        "                           (default 24)\n");
    batch_help_status(stdout);
}

static bool add_model(void *user, const char *path)
{
    batch_opts *b = user;
    if (b->model_count == b->model_cap) {
        size_t cap = b->model_cap ? 2 * b->model_cap : 16;
        const char **grown = realloc(b->models, cap * sizeof *grown);
        if (!grown) {
            cli_error("out of memory");
            return false;
        }
        b->models = grown;
        b->model_cap = cap;
    }
    b->models[b->model_count++] = path;
    return true;
}

/* The batch's own options out of argv into b; the rest (with argv[0])
 * into rest, for the render options' parser. */
static int split_args(int argc, char **argv, batch_opts *b, char **rest, int *rest_count)
{
    static const char *const valued[] = { "--views", "--sheet", "--sheet-columns", "--animate",
                                          "--fps", NULL };
    const char **dst[] = { &b->views_arg, &b->sheet, &b->columns_arg, &b->animate, &b->fps_arg };
    int n = 0;
    bool ended = false;
    rest[n++] = argv[0];
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (cli_arg(a, &ended) != CLI_ARG_OPTION) {
            rest[n++] = argv[i];   /* the models and "--", for the render options */
            continue;
        }
        int taken = batch_take_option(&b->c, argc, argv, &i);
        if (taken != 0) {
            b->any = true;
            if (taken != 1) {
                return taken;
            }
            continue;
        }
        if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0 ||
            strncmp(a, "--output=", 9) == 0) {
            b->output = true;
        }
        int k = 0;
        size_t len = 0;
        for (; valued[k]; k++) {
            len = strlen(valued[k]);
            if (strncmp(a, valued[k], len) == 0 && (a[len] == '\0' || a[len] == '=')) {
                break;
            }
        }
        if (!valued[k]) {
            rest[n++] = argv[i];
            /* A render option's value goes with it, even one that looks
             * like an option or is "--" (as the render parser takes it). */
            if (render_opts_takes_value(a) && i + 1 < argc) {
                rest[n++] = argv[++i];
            }
            continue;
        }
        const char *value = a[len] == '=' ? a + len + 1 : i + 1 < argc ? argv[++i] : NULL;
        if (!value || !*value) {
            cli_error("%s: %s value", valued[k], value ? "empty" : "missing");
            return EXIT_USAGE;
        }
        *dst[k] = value;
        b->any = true;
    }
    rest[n] = NULL;
    *rest_count = n;
    return -1;
}

typedef struct batch_run {
    const batch_opts *b;
    const render_opts *o;
    batch_session s;           /* the list, the writer, the log and the progress */
    const batch_list *list;    /* s's */
    render_job *jobs[2];       /* one reads the next input while the other draws */
    render_job *job;           /* the input's (one of jobs), and its framebuffer */
    sr_framebuffer *fb;
    batch_reader reader;
    sr_context *sheet_ctx;     /* --sheet's: the jobs' contexts are busy reading */
    batch_sheet sheet;         /* --sheet: made on the job's context at its first cell */
    int sheet_images;
    char message[2048];        /* the held messages of the input being drawn */
} batch_run;

/* batch_want_fn: with --skip-existing, an input whose every output
 * exists is not read. */
static bool wants_reading(void *user, const batch_item *it)
{
    const batch_run *run = user;
    const batch_opts *b = run->b;
    if (!b->c.skip_existing || b->sheet) {
        return true;
    }
    if (b->animate) {
        return !batch_exists_whole(it->output);
    }
    char output[4096];
    for (int v = 0; v < b->views; v++) {
        if (!batch_view_output(run->list, it, v, output, sizeof output) ||
            !batch_exists_whole(output)) {
            return true;
        }
    }
    return false;
}

/* Draw view `view` of the loaded input `it` into run->fb, for `output`
 * (NULL on a sheet); false when it failed (why in run->message). */
static bool draw_view(batch_run *run, const batch_item *it, const char *output, int view,
                      batch_record *rec)
{
    double t0 = batch_now_ms();
    run->message[0] = '\0';
    cli_capture(run->message, sizeof run->message);
    /* what named the output, for the user to change */
    const char *namer = it->named ? "--batch output" : "--name";
    /* A list's OUTPUT (or a name ending in {ext}) is known only now. */
    bool ok = !output || ((run->b->animate || cli_check_image_name(namer, output, true)) &&
                          batch_session_output_ok(&run->s, output, namer) &&
                          /* the model's own other files (MTL, textures) */
                          cli_check_output(render_job_inputs(run->job),
                                           it->named ? "--batch" : "--name", output));
    if (ok && run->b->views > 1) {
        batch_view_camera(run->job, run->o->have_eye, view, run->b->views);
    }
    render_frame_info info;
    if (ok && render_job_draw(run->job, run->fb, &info) == SR_OK) {
        rec->triangles = info.triangles;
    } else if (ok) {
        cli_error("%s", render_job_error(run->job));
        ok = false;
    }
    cli_capture(NULL, 0);
    rec->render_ms = batch_now_ms() - t0;
    return ok;
}

/* A sheet cell's caption: the model's file name, and the view's angle. */
static void caption_of(const batch_run *run, const batch_item *it, int view, char *out,
                       size_t size)
{
    const char *base = strrchr(it->input, '/');
    base = base ? base + 1 : it->input;
    if (run->b->views > 1) {
        int views = run->b->views;
        snprintf(out, size, "%s %ddeg", base, (360 * view + views / 2) / views);
    } else {
        snprintf(out, size, "%s", base);
    }
}

/* The inputs of the options: the MODEL arguments and the list, and
 * their outputs' names. */
static int gather(batch_run *run)
{
    const batch_opts *b = run->b;
    batch_list *l = &run->s.list;
    int status = batch_session_gather(&run->s, &b->c, b->models, b->model_count, NULL,
                                      "render: no models");
    for (size_t i = 0; status < 0 && i < l->count && b->views > 1 && !b->sheet && !b->animate;
         i++) {
        if (l->items[i].output) {
            cli_error("--views: the list names one output for '%s'; views are named by --name",
                      l->items[i].input);
            status = EXIT_USAGE;
        }
    }
    if (status < 0 && !b->sheet) {   /* a sheet is the one output */
        status = batch_session_name(&run->s, b->animate ? b->animate
                                             : b->views > 1 ? "{rel}_{view}.png" : "{rel}.png");
    }
    return status;
}

/* Fill the sheet's next cell, making the sheet first; false after the
 * reason is in run->message. */
static bool sheet_put(batch_run *run, const batch_item *it, int view, const uint8_t *rgba)
{
    sr_context *ctx = run->sheet_ctx;
    sr_result r = ctx ? SR_OK : SR_INVALID_ARG;
    if (r == SR_OK && !run->sheet.fb) {
        r = batch_sheet_start(&run->sheet, ctx, run->sheet_images, run->b->columns,
                              run->o->width, run->o->height, run->o->background,
                              run->o->background_alpha);
    }
    char caption[512];
    caption_of(run, it, view, caption, sizeof caption);
    if (r == SR_OK) {
        r = batch_sheet_put(&run->sheet, ctx, rgba, caption, rgba == NULL);
    }
    if (r != SR_OK) {
        snprintf(run->message, sizeof run->message, "--sheet: %s",
                 ctx && sr_context_error(ctx)[0] ? sr_context_error(ctx) : sr_result_text(r));
    }
    return r == SR_OK;
}

/* --animate --animation: the loaded model posed again at time t, without
 * reading it again, in the camera its first pose framed; false with why
 * in run->message. */
static bool pose_at(batch_run *run, float t)
{
    sr_vec3 eye, target, up;
    render_job_camera(run->job, &eye, &target, &up);
    run->message[0] = '\0';
    cli_capture(run->message, sizeof run->message);
    int status = render_job_pose(run->job, t);
    cli_capture(NULL, 0);
    if (status >= 0) {
        return false;
    }
    run->message[0] = '\0';   /* its warnings were the first pose's */
    render_job_set_camera(run->job, eye, target, up);
    return true;
}

/* --animate: one model's views as the frames of one WebP, or with
 * --animation the frames of its animation, 1/fps s apart from --time to
 * its end. */
static void animate_one(batch_run *run, const batch_read *rd)
{
    const batch_item *it = rd->item;
    const render_opts *o = run->o;
    int views = run->b->views, frame_ms = 3000 / views > 20 ? 3000 / views : 20;
    int fps = run->b->fps;
    float start = o->animation_time, duration = 0.0f;
    batch_record rec = { .input = it->input, .output = it->output, .index = it->index,
                         .status = "failed", .load_ms = rd->load_ms };
    if (!rd->wanted) {
        rec.status = "skipped";
        batch_session_done(&run->s, &rec, NULL);
        return;
    }
    bool ok = rd->loaded;
    if (ok && run->message[0]) {
        batch_session_report(&run->s, it->input, run->message);   /* a warning */
    }
    bool playing = ok && o->animation && render_job_animation(run->job, &duration);
    if (playing) {
        /* Frames at start + k / fps up to the end, the end itself when it
         * falls on one (a thousandth of a frame's rounding allowed). */
        double span = duration > start ? ((double)duration - start) * fps : 0.0;
        views = span < 100000.0 ? (int)floor(span + 1e-3) + 1 : 100001;
        if (views > 100000) {
            snprintf(run->message, sizeof run->message,
                     "--animate: %.6g s at --fps %d is more than 100000 frames",
                     (double)duration - start, fps);
            ok = playing = false;
        }
    }
    bool alpha = o->background_alpha < 1.0f;
    batch_anim *anim = ok ? batch_anim_start(o->width, o->height, alpha, run->message,
                                             sizeof run->message) : NULL;
    ok = anim != NULL;
    double render_ms = 0.0, t0 = batch_now_ms();
    size_t pixels = (size_t)o->width * (size_t)o->height;
    for (int v = 0; v < views && ok; v++) {
        int stamp = playing ? (int)lround(v * 1000.0 / fps) : v * frame_ms;
        if (playing && v > 0 && !pose_at(run, start + (float)v / (float)fps)) {
            ok = false;
            break;
        }
        ok = draw_view(run, it, v == 0 ? it->output : NULL, v, &rec);
        render_ms += rec.render_ms;
        uint8_t *straight = ok && alpha ? cli_straight_alpha(sr_framebuffer_pixels(run->fb),
                                                             pixels) : NULL;
        if (ok && alpha && !straight) {
            snprintf(run->message, sizeof run->message, "out of memory");
            ok = false;
        }
        ok = ok && batch_anim_add(anim, straight ? straight : sr_framebuffer_pixels(run->fb),
                                  stamp, run->message, sizeof run->message);
        free(straight);
    }
    sr_io_error err;
    if (ok && !(cli_make_parents(it->output, &err) &&
                batch_anim_write(anim, it->output,
                                 playing ? (int)lround(views * 1000.0 / fps) : views * frame_ms,
                                 &err))) {
        snprintf(run->message, sizeof run->message, "%s", err.message);
        ok = false;
    }
    batch_anim_free(anim);
    rec.render_ms = render_ms;
    rec.encode_ms = batch_now_ms() - t0 - render_ms;
    rec.status = ok ? "ok" : "failed";
    batch_session_done(&run->s, &rec, ok ? NULL : run->message);
}

/* Render the shard's inputs in list order as the reader hands them
 * over, each image handed to the writer (or put on the sheet) while the
 * next is drawn. */
static void render_all(batch_run *run)
{
    const batch_list *list = run->list;
    const render_opts *o = run->o;
    const batch_opts *b = run->b;
    const cli_image_options image = { .png_level = o->png_level,
                                       .jpeg_quality = o->jpeg_quality,
                                       .keep_alpha = o->background_alpha < 1.0f,
                                       .premultiplied = true };
    char output[4096];
    for (batch_read *rd; (rd = batch_reader_next(&run->reader)) != NULL;) {
        const batch_item *it = rd->item;
        run->job = rd->job;
        run->fb = rd->fb;
        snprintf(run->message, sizeof run->message, "%s", rd->message);
        if (b->animate) {
            animate_one(run, rd);
            continue;
        }
        batch_record rec = { .input = it->input, .output = b->sheet ? b->sheet : it->output,
                             .index = it->index, .status = "failed", .load_ms = rd->load_ms };
        bool loaded = rd->loaded;
        if (loaded && run->message[0]) {
            batch_writer_wait(&run->s.writer);
            batch_session_report(&run->s, it->input, run->message);   /* a warning */
        }
        for (int v = 0; v < b->views; v++) {
            if (!b->sheet && !batch_view_output(list, it, v, output, sizeof output)) {
                snprintf(output, sizeof output, "%s", it->output);   /* view 0's, checked */
            }
            rec.output = b->sheet ? b->sheet : output;
            bool skip = !b->sheet && b->c.skip_existing && batch_exists_whole(output);
            if (skip || (rd->wanted && !loaded)) {
                rec.status = skip ? "skipped" : "failed";
                batch_writer_wait(&run->s.writer);
                if (b->sheet) {
                    sheet_put(run, it, v, NULL);
                }
                batch_session_done(&run->s, &rec, skip || v > 0 ? NULL : run->message);
                continue;
            }
            rec.status = "failed";
            bool drawn = draw_view(run, it, b->sheet ? NULL : output, v, &rec);
            if (drawn && b->sheet) {
                rec.status = sheet_put(run, it, v, sr_framebuffer_pixels(run->fb)) ? "ok"
                                                                                    : "failed";
            } else if (drawn && batch_writer_put(&run->s.writer, &rec, o->width, o->height,
                                                 sr_framebuffer_pixels(run->fb), &image)) {
                rec.load_ms = 0.0;   /* a model is read once for all its views */
                continue;
            } else if (drawn) {
                snprintf(run->message, sizeof run->message, "out of memory");
            }
            batch_writer_wait(&run->s.writer);
            batch_session_done(&run->s, &rec, run->message);
            rec.load_ms = 0.0;
        }
    }
    batch_writer_wait(&run->s.writer);
}

/* Write the sheet (after every input); false after one line. */
static bool write_sheet(batch_run *run)
{
    const render_opts *o = run->o;
    const char *path = run->b->sheet;
    sr_io_error err;
    if (!batch_session_output_ok(&run->s, path, "--sheet")) {
        return false;
    }
    sr_framebuffer *fb = run->sheet.fb;
    if (cli_write_image(path, sr_framebuffer_width(fb), sr_framebuffer_height(fb),
                        sr_framebuffer_pixels(fb),
                        &(cli_image_options){ .png_level = o->png_level,
                                              .jpeg_quality = o->jpeg_quality,
                                              .keep_alpha = o->background_alpha < 1.0f,
                                              .premultiplied = true,
                                              .context = run->sheet_ctx },
                        &err) != SR_OK) {
        cli_error("--sheet: %s", err.message);
        return false;
    }
    return true;
}

static int run_batch(const batch_opts *b, const render_opts *o, render_job *job)
{
    batch_run run = { .b = b, .o = o, .jobs = { job } };
    run.list = &run.s.list;
    int status = gather(&run);
    if (status < 0) {
        status = batch_session_open(&run.s);
    }
    /* The sheet would replace an input after the whole batch was drawn. */
    if (status < 0 && b->sheet && !batch_session_output_ok(&run.s, b->sheet, "--sheet")) {
        status = EXIT_USAGE;
    }
    if (status < 0) {
        size_t mine = batch_session_mine(&run.s);
        run.sheet_images = (int)(mine * (size_t)b->views);
        int cols, rows;
        long sw, sh;
        if (b->sheet && (mine > (size_t)SR_MAX_FRAMEBUFFER_SIZE ||
                         !batch_sheet_size(run.sheet_images, b->columns, o->width, o->height,
                                           &cols, &rows, &sw, &sh))) {
            int lo, hi;
            char fix[96];
            snprintf(fix, sizeof fix, "give a smaller --size or fewer models%s",
                     b->views > 1 ? " or --views" : "");
            if (mine <= (size_t)SR_MAX_FRAMEBUFFER_SIZE &&
                batch_sheet_columns_that_fit(run.sheet_images, o->width, o->height, &lo, &hi)) {
                snprintf(fix, sizeof fix, lo == hi ? "give --sheet-columns %d" :
                         "give --sheet-columns from %d to %d", lo, hi);
            }
            char at[48] = "";
            if (b->columns) {
                snprintf(at, sizeof at, ", %d a row,", b->columns);
            }
            cli_error("--sheet: %zu images of %dx%d%s need more than %d pixels a side: %s",
                      mine * (size_t)b->views, o->width, o->height, at, SR_MAX_FRAMEBUFFER_SIZE,
                      fix);
            status = EXIT_USAGE;
        } else if (b->sheet) {
            /* The sheet is held whole beside the two frames, and written
             * from a straight-alpha copy when it is transparent.  Its
             * pixels are --size times the images, whatever --aa is. */
            char more[64], lower[96];
            snprintf(more, sizeof more, " and a %ldx%ld --sheet", sw, sh);
            bool transparent = o->background_alpha < 1.0f;
            snprintf(lower, sizeof lower, "give a smaller --size or fewer models%s%s",
                     b->views > 1 ? " or --views" : "",
                     transparent ? " or an opaque --background" : "");
            uint64_t copies = transparent ? 2 : 1;
            status = render_opts_check_memory(o, "render", o->width, o->height, 2,
                                              copies * 4 * (uint64_t)sw * (uint64_t)sh, more,
                                              lower);
        }
    }
    /* The second job, which reads while the first draws, shares its light. */
    if (status < 0) {
        status = render_job_prepare(job);
    }
    if (status < 0) {
        status = render_job_parse(b->job_argc, b->job_argv, &run.jobs[1]);
    }
    if (status < 0) {
        render_job_share_light(run.jobs[1], job);
    }
    if (status < 0 && b->sheet) {
        sr_set_last_error(NULL);
        sr_result r = sr_make_context(&(sr_context_desc){ .threads = o->threads }, &run.sheet_ctx);
        if (r != SR_OK) {
            cli_error("--sheet: %s", cli_why(r));
            status = EXIT_FAILURE_RUN;
        }
    }
    if (status < 0) {
        size_t records = b->animate ? 1 : (size_t)b->views;   /* a model's */
        /* A played animation moves the first frame's camera into the
         * options (pose_at): the next model starts from the options again. */
        bool playing = b->animate && o->animation;
        batch_session_begin(&run.s, batch_session_mine(&run.s) * records, 1);
        batch_reader_start(&run.reader, run.list, &run.s.shard, wants_reading, &run, run.jobs,
                           b->job_argc, b->views > 1 || playing ? b->job_argv : NULL, o->width,
                           o->height);
        render_all(&run);
        status = batch_session_end(&run.s);
        batch_reader_stop(&run.reader);
        if (run.sheet.fb && !write_sheet(&run)) {
            status = EXIT_FAILURE_RUN;
        }
    }
    if (run.sheet.fb) {
        batch_sheet_free(&run.sheet, run.sheet_ctx);
    }
    sr_destroy_context(run.sheet_ctx);
    render_job_free(run.jobs[1]);   /* before the first, whose light it shares */
    return batch_session_close(&run.s, status);
}

/* --views, --sheet and --sheet-columns, and how they go with the other
 * options; -1 or an exit status after one line. */
static int check_views(batch_opts *b, const render_opts *o)
{
    b->views = 1;
    if (b->views_arg && !parse_int("--views", b->views_arg, 1, 360, &b->views)) {
        return EXIT_USAGE;
    }
    if (b->columns_arg && !parse_int("--sheet-columns", b->columns_arg, 1, 1000, &b->columns)) {
        return EXIT_USAGE;
    }
    b->fps = 24;
    if (b->fps_arg && !(b->animate && o->animation)) {
        cli_error("--fps: the frame rate of --animate with --animation: give both");
        return EXIT_USAGE;
    }
    if (b->fps_arg && !parse_int("--fps", b->fps_arg, 1, 120, &b->fps)) {
        return EXIT_USAGE;
    }
    if (b->columns_arg && !b->sheet) {
        cli_error("--sheet-columns: needs --sheet FILE");
        return EXIT_USAGE;
    }
    if (!b->columns && b->sheet && b->views > 1) {
        b->columns = b->views;   /* a model's views a row */
    }
    if (b->sheet && b->c.skip_existing) {
        cli_error("--skip-existing: a sheet is drawn whole each time (nothing to resume)");
        return EXIT_USAGE;
    }
    const char *named = b->sheet ? b->sheet : b->c.name;
    if (named && !cli_check_image_name(b->sheet ? "--sheet" : "--name", named, true)) {
        return EXIT_USAGE;
    }
    if (named && cli_is_jpeg_name(named) && o->background_alpha < 1.0f) {
        cli_error("--background transparent: '%s' names JPEGs, which have no alpha", named);
        return EXIT_USAGE;
    }
    if (b->animate) {
        if (b->sheet || b->c.name) {
            cli_error("--animate: names the outputs itself (not with %s)",
                      b->sheet ? "--sheet" : "--name");
            return EXIT_USAGE;
        }
        if (!batch_anim_is_webp_name(b->animate)) {
            cli_error("--animate: '%s': an animation is a WebP (name it .webp)", b->animate);
            return EXIT_USAGE;
        }
        if (!batch_check_pattern(b->animate)) {
            return EXIT_USAGE;
        }
        if (o->animation && b->views_arg) {
            cli_error("--views: not with --animation (--animate plays the animation, in one "
                      "view)");
            return EXIT_USAGE;
        }
        if (!b->views_arg && !o->animation) {
            b->views = 24;
        }
        char why[256];
        batch_anim *probe = batch_anim_start(1, 1, false, why, sizeof why);
        if (!probe) {
            cli_message("%s: %s", b->animate, why);
            return EXIT_USAGE;
        }
        batch_anim_free(probe);
    }
    const char *name = b->c.name;
    if (!b->sheet && !b->animate && b->views > 1 && name && !strstr(name, "{view}")) {
        cli_error("--name: '%s' needs {view} to name %d views apart", name, b->views);
        return EXIT_USAGE;
    }
    return -1;
}

int batch_render(int argc, char **argv)
{
    batch_opts b = { 0 };
    char **rest = malloc(((size_t)argc + 1) * sizeof *rest);
    if (!rest) {
        cli_error("out of memory");
        return EXIT_FAILURE_RUN;
    }
    int rest_count = 0;
    int status = split_args(argc, argv, &b, rest, &rest_count);
    render_opts o = render_opts_defaults();
    o.model_fn = add_model;
    o.model_user = &b;
    if (status < 0) {
        status = render_opts_parse(rest_count, rest, &o);
        if (status == EXIT_OK) {
            batch_help();   /* after render's --help */
        }
    }
    /* -o names one image: render says what is wrong with the rest. */
    bool batch = b.any || (!b.output && batch_asked(&b.c, b.models, b.model_count));
    if (status < 0 && !batch) {
        free(b.models);
        free(rest);
        return -1;          /* one plain render */
    }
    if (status < 0 && b.output) {
        cli_error("-o: names one output; a batch names its outputs with --output-dir and --name");
        status = EXIT_USAGE;
    }
    if (status < 0 && b.c.name && !batch_check_pattern(b.c.name)) {
        status = EXIT_USAGE;
    }
    if (status < 0) {
        status = check_views(&b, &o);
    }
    if (status < 0) {
        render_opts_warn(&o);   /* once, not once an input */
        /* One input is read into a frame while the last is drawn in the
         * other; the writer keeps its copies of the last two images
         * (batch_writer.c, one thread), and one more image's worth goes
         * to writing them (a transparent one's straight alpha, the
         * encoder).  --threads draws one frame on more threads, not more
         * frames.  A sheet is counted once its size is known
         * (run_batch).  --animate writes no images: libwebp's animation
         * encoder holds about four of its own (its canvases and the
         * frame it encodes, docs/batch.md), and a transparent frame's
         * straight-alpha copy one more. */
        uint64_t image = 4 * (uint64_t)o.width * (uint64_t)o.height;
        uint64_t images = b.sheet     ? 0
                          : b.animate ? (o.background_alpha < 1.0f ? 5 : 4) * image
                                      : 3 * image;
        status = render_opts_check_memory(&o, argv[0], o.width, o.height, 2, images,
                                          b.sheet     ? ""
                                          : b.animate ? " and the animation being encoded"
                                                      : " and the images being written",
                                          NULL);
    }
    /* The job's options without the models, which come in the same order. */
    int n = 0;
    for (int i = 0, j = 0; i < rest_count; i++) {
        if ((size_t)j < b.model_count && rest[i] == b.models[j]) {
            j++;
        } else {
            rest[n++] = rest[i];
        }
    }
    rest[n] = NULL;
    b.job_argv = rest;
    b.job_argc = n;
    render_job *job = NULL;
    if (status < 0) {
        status = render_job_parse(n, rest, &job);
    }
    if (status < 0) {
        status = run_batch(&b, &o, job);
    }
    render_job_free(job);
    free(b.models);
    free(rest);
    return status;
}
