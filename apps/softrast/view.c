/* view.c - `softrast view [MODEL] [options]`: an interactive window onto the
 * pipeline.  SDL2 opens the window, delivers input and presents our pixels
 * as a streaming texture; every pixel is rendered by softrast, through the
 * same render job as `softrast render` (render.c), so a screenshot equals
 * `softrast render` with the printed options.  This file holds the options,
 * the event loop and what each input does; view_frames.c the double
 * buffering, view_overlay.c and view_font.c the overlay. */
#include "cli.h"
#include "render.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define VIEW_DEFAULT_FONT "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"

static void view_help(void)
{
    printf(
        "usage: softrast view [MODEL] [options] [render options]\n"
        "\n"
        "Open a window onto the pipeline: MODEL (or the built-in teapot scene)\n"
        "drawn by softrast, every pixel, and shown through SDL2.  Any option of\n"
        "'softrast render' sets the starting modes and camera (see its --help).\n"
        "\n"
        "options:\n"
        "  --size WxH               window size (default 1280x720)\n"
        "  --frames N               draw N frames without waiting for input, then quit\n"
        "  --screenshot FILE        write the frame as PNG (a JPEG for FILE.jpg or .jpeg;\n"
        "                           another extension is refused),\n"
        "                           atomically, then quit: after --frames N frames, else\n"
        "                           after the --events script has played, else after\n"
        "                           the first frame\n"
        "  --screenshot-overlay FILE\n"
        "                           also write that frame with the overlay over it\n"
        "  --events FILE            play scripted input (drag, wheel, key, resize,\n"
        "                           frames, screenshot, quit; docs/viewer.md)\n"
        "  --log                    print each frame's render time to stdout and the\n"
        "                           median at exit\n"
        "  --no-overlay             start with the overlay hidden (Tab shows it)\n"
        "  --no-vsync               present without waiting for the display refresh\n"
        "  --font FILE              TrueType font of the overlay (default DejaVu Sans)\n"
        "  -h, --help               this help\n"
        "\n"
        "mouse: left drag orbits, right or middle drag pans, the wheel zooms.\n"
        "keys:  R reset camera, F fit, S screenshot, Enter print the equivalent\n"
        "       'softrast render' command, Tab overlay, H key list, Q or Esc quit;\n"
        "       M shading, W lines, L smooth lines, P polygon offset, C culling,\n"
        "       V front face, D depth function, B depth format, A antialiasing,\n"
        "       Y SSAA filter, T texture filter, U texture wrap, I interpolation,\n"
        "       O projection, X rasterizer, N threads (Shift+key cycles back).\n"
        "\n"
        "Screenshots hold the scene without the overlay.  Exit status: 0, 2 for bad\n"
        "options or input, 1 when no window can be opened or rendering fails.\n");
}

#ifndef SR_HAVE_VIEWER

/* The lean `softrast` binary: the window is softrast-view's (CMakeLists.txt
 * says why), run from the directory this executable is in, with the same
 * arguments. */
int cmd_view(int argc, char **argv)
{
    bool ended = false;
    for (int i = 1; i < argc && cli_arg(argv[i], &ended) != CLI_ARG_END; i++) {
        if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) {
            view_help();
            return EXIT_OK;
        }
    }
    char self[4096];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 32);
    if (n > 0) {
        self[n] = 0;
        char *slash = strrchr(self, '/');
        if (slash) {
            strcpy(slash + 1, "softrast-view");
            if (access(self, X_OK) == 0) {
                /* argv[0] is "view" here: softrast-view gets "view" as its
                 * command, then the options. */
                char **args = calloc((size_t)argc + 2, sizeof *args);
                if (args) {
                    args[0] = self;
                    for (int i = 0; i < argc; i++) {
                        args[i + 1] = argv[i];
                    }
                    fflush(stdout);
                    execv(self, args);
                    cli_error("view: cannot run %s: %s", self, strerror(errno));
                    free(args);
                    return EXIT_FAILURE_RUN;
                }
            }
        }
    }
    cli_error("view: cannot open a window (softrast was built without SDL2 and FreeType; "
              "install libsdl2-dev and libfreetype-dev, then run cmake again)");
    return EXIT_USAGE;
}

#else /* SR_HAVE_VIEWER */

#include "render_options.h"
#include "view_sdl.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define MAX_ARGS 256

typedef struct view_opts {
    int width, height;
    int frames;               /* 0: until closed */
    const char *screenshot;
    const char *window_shot;  /* --screenshot-overlay */
    const char *events;
    const char *font;
    bool log, no_overlay, no_vsync;
    int argc;                 /* the render arguments, argv[0] = "view" */
    const char *argv[MAX_ARGS];
    int operand_count;        /* the arguments after "--", which follow the */
    const char *operands[16]; /* mode table's options in the render arguments */
} view_opts;

typedef struct viewer {
    view_opts o;
    render_job *job;
    view_camera cam;
    view_mode_state modes;
    const char *model;        /* the model file, or NULL for the teapot scene */
    int base_argc;            /* render arguments the mode table does not replace */
    const char *base[MAX_ARGS];
    bool modes_changed;

    SDL_Window *win;
    SDL_Renderer *ren;
    SDL_Texture *tex;
    int tex_w, tex_h;
    view_frames vf;
    view_font *font;
    view_script *script;
    Uint32 ev_done, ev_shot;

    bool rendering, dirty, overlay, help, quit;
    int status;
    int drag_button;          /* SDL button held, or 0 */
    long frames_kicked, frames_done;
    int script_wait;          /* frames to wait before the script goes on */
    bool final_shot;          /* the --screenshot frame has been asked for */
    bool script_pushed;       /* events were just pushed: handle them before a frame starts */
    char pending_shot[4096];
    int shot_counter;

    double *times;            /* render ms per frame */
    size_t ntimes, cap_times;
    double present_t[16];     /* the last presents, for the fps figure */
    int npresent;
} viewer;

/* Returns -1 to go on, else the exit status. */
static int parse_view_args(int argc, char **argv, view_opts *o)
{
    o->argv[o->argc++] = "view";
    bool ended = false;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i], *value = NULL;
        if (cli_arg(arg, &ended) == CLI_ARG_END) {
            continue;
        } else if (ended) {
            if (o->operand_count == (int)(sizeof o->operands / sizeof o->operands[0])) {
                cli_error("view: too many arguments");
                return EXIT_USAGE;
            }
            o->operands[o->operand_count++] = arg;
            continue;
        }
        char name[64];
        const char *eq = strncmp(arg, "--", 2) == 0 ? strchr(arg, '=') : NULL;
        if (eq && (size_t)(eq - arg) < sizeof name) {
            memcpy(name, arg, (size_t)(eq - arg));
            name[eq - arg] = 0;
            value = eq + 1;
        } else {
            snprintf(name, sizeof name, "%s", arg);
        }
        bool takes_value = strcmp(name, "--size") == 0 || strcmp(name, "--frames") == 0 ||
                           strcmp(name, "--screenshot") == 0 || strcmp(name, "--events") == 0 ||
                           strcmp(name, "--screenshot-overlay") == 0 ||
                           strcmp(name, "--font") == 0;
        if (takes_value && !value) {
            if (i + 1 >= argc) {
                cli_error("%s: missing value", name);
                return EXIT_USAGE;
            }
            value = argv[++i];
        }
        if (strcmp(name, "-h") == 0 || strcmp(name, "--help") == 0) {
            view_help();
            return EXIT_OK;
        } else if (strcmp(name, "--size") == 0) {
            if (!parse_size(name, value, &o->width, &o->height)) {
                return EXIT_USAGE;
            }
        } else if (strcmp(name, "--frames") == 0) {
            if (!parse_int(name, value, 1, 10000000, &o->frames)) {
                return EXIT_USAGE;
            }
        } else if (strcmp(name, "--screenshot") == 0 ||
                   strcmp(name, "--screenshot-overlay") == 0) {
            if (!cli_check_output_name(name, value) || !cli_check_image_name(name, value, true)) {
                return EXIT_USAGE;
            }
            *(name[12] ? &o->window_shot : &o->screenshot) = value;
        } else if (strcmp(name, "--events") == 0) {
            o->events = value;
        } else if (strcmp(name, "--font") == 0) {
            o->font = value;
        } else if (strcmp(name, "--log") == 0) {
            o->log = true;
        } else if (strcmp(name, "--no-overlay") == 0) {
            o->no_overlay = true;
        } else if (strcmp(name, "--no-vsync") == 0) {
            o->no_vsync = true;
        } else if (strcmp(name, "-o") == 0 || strcmp(name, "--output") == 0 ||
                   strcmp(name, "--png-level") == 0 || strcmp(name, "--jpeg-quality") == 0 ||
                   strcmp(name, "-v") == 0 ||
                   strcmp(name, "--verbose") == 0) {
            cli_error("view: %s is a 'softrast render' option (use --screenshot FILE, --log)",
                      name);
            return EXIT_USAGE;
        } else if (o->argc < MAX_ARGS - 65) {
            o->argv[o->argc++] = argv[i];   /* a render option: render_options.c parses it */
            /* with its value, even one that looks like an option or is "--" */
            if (!value && render_opts_takes_value(name) && i + 1 < argc) {
                o->argv[o->argc++] = argv[++i];
            }
        } else {
            cli_error("view: too many arguments");
            return EXIT_USAGE;
        }
    }
    return -1;
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(const double *v, size_t n)
{
    if (n == 0) {
        return 0.0;
    }
    double *s = malloc(n * sizeof *s);
    if (!s) {
        return v[n - 1];
    }
    memcpy(s, v, n * sizeof *s);
    qsort(s, n, sizeof *s, cmp_double);
    double m = n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
    free(s);
    return m;
}

/* The operands given after "--", after argv[0..n-1] and a "--". */
static int operand_args(const viewer *v, const char **argv, int n)
{
    if (v->o.operand_count > 0) {
        argv[n++] = "--";
        for (int i = 0; i < v->o.operand_count; i++) {
            argv[n++] = v->o.operands[i];
        }
    }
    return n;
}

/* The render options of the current modes: the user's, then the table's. */
static int option_args(const viewer *v, const char **argv)
{
    int n = 0;
    for (int i = 0; i < v->base_argc; i++) {
        argv[n++] = v->base[i];
    }
    return view_modes_args(&v->modes, argv, n);
}

/* The render arguments of the current modes: the options, then the
 * operands given after "--". */
static int current_args(const viewer *v, const char **argv)
{
    return operand_args(v, argv, option_args(v, argv));
}

/* Shell quoting for the printed command: plain words stay bare. */
static void put_word(FILE *f, const char *s)
{
    bool plain = *s != 0;
    for (const char *p = s; *p; p++) {
        plain &= strchr("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
                        "-_=.,/+:@%", *p) != NULL;
    }
    if (plain) {
        fprintf(f, " %s", s);
        return;
    }
    fputs(" '", f);
    for (const char *p = s; *p; p++) {
        if (*p == '\'') {
            fputs("'\\''", f);
        } else {
            fputc(*p, f);
        }
    }
    fputc('\'', f);
}

/* The `softrast render` command that draws what the window shows (without
 * the overlay), to `output`. */
static void print_render_command(const viewer *v, FILE *f, const char *output)
{
    const char *argv[MAX_ARGS];
    int n = option_args(v, argv);
    fputs("softrast render", f);
    for (int i = 1; i < n; i++) {
        put_word(f, argv[i]);
    }
    char cam[400];
    /* %.9g prints a float so that reading it back gives the same float. */
    snprintf(cam, sizeof cam,
             "--camera=eye=%.9g,%.9g,%.9g,target=%.9g,%.9g,%.9g,up=%.9g,%.9g,%.9g",
             (double)v->cam.eye.x, (double)v->cam.eye.y, (double)v->cam.eye.z,
             (double)v->cam.target.x, (double)v->cam.target.y, (double)v->cam.target.z,
             (double)v->cam.up.x, (double)v->cam.up.y, (double)v->cam.up.z);
    put_word(f, cam);
    char size[40];
    snprintf(size, sizeof size, "--size=%dx%d", sr_framebuffer_width(v->vf.front),
             sr_framebuffer_height(v->vf.front));
    put_word(f, size);
    fputs(" -o", f);
    put_word(f, output);
    const char *operands[MAX_ARGS];
    int m = operand_args(v, operands, 0);
    for (int i = 0; i < m; i++) {
        put_word(f, operands[i]);
    }
    fputc('\n', f);
    fflush(f);
}

static bool exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

static void request_screenshot(viewer *v, const char *path)
{
    snprintf(v->pending_shot, sizeof v->pending_shot, "%s", path);
    v->dirty = true;
}

static void key_down(viewer *v, const SDL_KeyboardEvent *k)
{
    SDL_Keycode key = k->keysym.sym;
    bool shift = (k->keysym.mod & KMOD_SHIFT) != 0;
    v->dirty = true;
    switch (key) {
    case SDLK_ESCAPE:
    case SDLK_q:
        v->quit = true;
        return;
    case SDLK_r:
        view_camera_reset(&v->cam);
        return;
    case SDLK_f:
        view_camera_fit(&v->cam);
        return;
    case SDLK_h:
        v->help = !v->help;
        v->overlay = true;
        return;
    case SDLK_TAB:
        v->overlay = !v->overlay;
        return;
    case SDLK_s: {
        char name[64];
        do {
            snprintf(name, sizeof name, "softrast-view-%03d.png", ++v->shot_counter);
        } while (exists(name) && v->shot_counter < 999);
        request_screenshot(v, name);
        return;
    }
    case SDLK_RETURN:
    case SDLK_KP_ENTER:
        print_render_command(v, stdout, "softrast.png");
        return;
    default:
        break;
    }
    if (key >= 'a' && key <= 'z') {
        int m = view_mode_for_key((char)key);
        if (m >= 0) {
            view_mode_cycle(&v->modes, m, shift ? -1 : 1);
            v->modes_changed = true;
        }
    }
}

static void handle_event(viewer *v, const SDL_Event *e);

/* Make the job draw with the current modes.  A new thread count means a
 * new context, so the framebuffers on the old one go first. */
static bool apply_modes(viewer *v)
{
    const char *argv[MAX_ARGS];
    int n = current_args(v, argv);
    int w = sr_framebuffer_width(v->vf.front), h = sr_framebuffer_height(v->vf.front);
    view_frames_release(&v->vf);
    int status = render_job_configure(v->job, n, (char **)argv);
    if (status >= 0) {
        v->status = status == EXIT_OK ? EXIT_FAILURE_RUN : status;
        return false;
    }
    if (!view_frames_resize(&v->vf, w, h)) {
        cli_error("view: %s", v->vf.error);
        v->status = EXIT_FAILURE_RUN;
        return false;
    }
    v->modes_changed = false;
    return true;
}

static bool make_texture(viewer *v, int w, int h)
{
    if (v->tex) {
        SDL_DestroyTexture(v->tex);
    }
    v->tex = SDL_CreateTexture(v->ren, SDL_PIXELFORMAT_RGBA32, SDL_TEXTUREACCESS_STREAMING, w, h);
    v->tex_w = w;
    v->tex_h = h;
    if (!v->tex) {
        cli_error("view: cannot make a %dx%d texture: %s", w, h, SDL_GetError());
        v->status = EXIT_FAILURE_RUN;
        return false;
    }
    return true;
}

/* Start drawing the next frame into back (the render thread is idle). */
static void kick(viewer *v)
{
    int w, h;
    if (SDL_GetRendererOutputSize(v->ren, &w, &h) != 0 || w < 1 || h < 1) {
        SDL_GetWindowSize(v->win, &w, &h);
    }
    w = w < 1 ? 1 : w > SR_MAX_FRAMEBUFFER_SIZE ? SR_MAX_FRAMEBUFFER_SIZE : w;
    h = h < 1 ? 1 : h > SR_MAX_FRAMEBUFFER_SIZE ? SR_MAX_FRAMEBUFFER_SIZE : h;
    if (v->modes_changed && !apply_modes(v)) {
        v->quit = true;
        return;
    }
    /* Window resized: new framebuffers at the new size. */
    if (w != sr_framebuffer_width(v->vf.back) || h != sr_framebuffer_height(v->vf.back)) {
        if (!view_frames_resize(&v->vf, w, h)) {
            cli_error("view: %s", v->vf.error);
            v->status = EXIT_FAILURE_RUN;
            v->quit = true;
            return;
        }
    }
    render_job_set_camera(v->job, v->cam.eye, v->cam.target, v->cam.up);
    v->frames_kicked++;
    bool last = v->o.frames > 0 && v->frames_kicked >= v->o.frames;
    if (last && v->o.screenshot) {
        request_screenshot(v, v->o.screenshot);
    }
    view_frames *vf = &v->vf;
    snprintf(vf->shot, sizeof vf->shot, "%s", v->pending_shot);
    snprintf(vf->window_shot, sizeof vf->window_shot, "%s",
             v->o.window_shot && v->o.screenshot && strcmp(v->pending_shot, v->o.screenshot) == 0
                 ? v->o.window_shot : "");
    v->pending_shot[0] = 0;
    vf->overlay = v->overlay;
    const char *slash = v->model ? strrchr(v->model, '/') : NULL;
    snprintf(vf->title, sizeof vf->title, "%s",
             v->model ? (slash ? slash + 1 : v->model) : "teapot scene");
    view_modes_describe(&v->modes, vf->modes, sizeof vf->modes);
    vf->info = (view_overlay_info){
        .width = w, .height = h, .threads = sr_context_threads(render_job_context(v->job)),
        .median_ms = median(v->times, v->ntimes), .help = v->help,
    };
    if (v->npresent >= 2) {
        int a = v->npresent > 16 ? v->npresent % 16 : 0, b = (v->npresent - 1) % 16;
        int count = v->npresent > 16 ? 15 : v->npresent - 1;
        double span = v->present_t[b] - v->present_t[a];
        vf->info.fps = span > 0 ? count * 1000.0 / span : 0.0;
    }
    v->dirty = false;
    v->rendering = true;
    view_frames_kick(vf);
}

static void present(viewer *v)
{
    SDL_RenderClear(v->ren);
    if (v->tex) {
        SDL_RenderCopy(v->ren, v->tex, NULL, NULL);
    }
    SDL_RenderPresent(v->ren);
    v->present_t[v->npresent % 16] = now_ms();
    v->npresent++;
}

/* The render thread finished back: show it. */
static void frame_done(viewer *v)
{
    view_frames *vf = &v->vf;
    v->rendering = false;
    if (vf->result != SR_OK) {
        cli_error("view: %s", vf->error);
        v->status = EXIT_FAILURE_RUN;
        v->quit = true;
        return;
    }
    view_frames_swap(vf);
    v->frames_done++;
    if (v->ntimes == v->cap_times) {
        size_t cap = v->cap_times ? 2 * v->cap_times : 1024;
        double *t = realloc(v->times, cap * sizeof *t);
        if (t) {
            v->times = t;
            v->cap_times = cap;
        }
    }
    if (v->ntimes < v->cap_times) {
        v->times[v->ntimes++] = vf->render_ms;
    }
    if (v->o.log) {
        printf("frame %ld: render %.2f ms, overlay %.2f ms, %dx%d, %llu triangles, "
               "%llu fragments\n", v->frames_done, vf->render_ms, vf->overlay_ms,
               sr_framebuffer_width(vf->front), sr_framebuffer_height(vf->front),
               (unsigned long long)vf->frame.triangles, (unsigned long long)vf->frame.fragments);
    }
    if (vf->shot[0]) {
        if (vf->shot_ok) {
            printf("softrast view: wrote %s; the same image: ", vf->shot);
            print_render_command(v, stdout, vf->shot);
        } else {
            fprintf(stderr, "%s\n", vf->shot_error);
            v->status = EXIT_FAILURE_RUN;
        }
        /* --screenshot without --frames: quit once the script's input shows. */
        if (v->o.screenshot && strcmp(vf->shot, v->o.screenshot) == 0 && v->o.frames == 0) {
            v->quit = true;
        }
    }
    int w = sr_framebuffer_width(vf->front), h = sr_framebuffer_height(vf->front);
    if ((w != v->tex_w || h != v->tex_h) && !make_texture(v, w, h)) {
        v->quit = true;
        return;
    }
    SDL_UpdateTexture(v->tex, NULL, sr_framebuffer_pixels(vf->front), w * 4);
    if (v->o.frames > 0 && v->frames_done >= v->o.frames) {
        v->quit = true;
    }
    /* The script goes on once its frames are drawn; the events it pushes
     * are handled before the next frame starts. */
    if (v->script && v->script_wait > 0 && --v->script_wait == 0) {
        v->script_wait = view_script_advance(v->script, v->win, v->ev_shot);
        v->script_pushed = true;
    }
    /* --screenshot without --frames: the next frame, which shows all the
     * script's input (its events are handled before that frame starts). */
    if (v->o.screenshot && v->o.frames == 0 && !v->final_shot && !v->quit &&
        (!v->script || v->script_wait == 0)) {
        request_screenshot(v, v->o.screenshot);
        v->final_shot = true;
    }
}

static void handle_event(viewer *v, const SDL_Event *e)
{
    if (e->type == v->ev_done) {
        frame_done(v);
        return;
    }
    if (e->type == v->ev_shot) {
        request_screenshot(v, e->user.data1);
        free(e->user.data1);
        return;
    }
    switch (e->type) {
    case SDL_QUIT:
        v->quit = true;
        break;
    case SDL_KEYDOWN:
        key_down(v, &e->key);
        break;
    case SDL_MOUSEBUTTONDOWN:
        if (!v->drag_button) {
            v->drag_button = e->button.button;
        }
        break;
    case SDL_MOUSEBUTTONUP:
        if (e->button.button == v->drag_button) {
            v->drag_button = 0;
        }
        break;
    case SDL_MOUSEMOTION:
        if (v->drag_button == SDL_BUTTON_LEFT) {
            view_camera_orbit(&v->cam, (float)e->motion.xrel, (float)e->motion.yrel);
            v->dirty = true;
        } else if (v->drag_button == SDL_BUTTON_RIGHT || v->drag_button == SDL_BUTTON_MIDDLE) {
            int w = sr_framebuffer_width(v->vf.front), h = sr_framebuffer_height(v->vf.front);
            int ww, wh;
            SDL_GetWindowSize(v->win, &ww, &wh);
            /* Motion is in window units; the framebuffer may be larger (HiDPI). */
            float sx = ww > 0 ? (float)w / (float)ww : 1.0f;
            view_camera_pan(&v->cam, (float)e->motion.xrel * sx, (float)e->motion.yrel * sx,
                            w < h ? w : h);
            v->dirty = true;
        }
        break;
    case SDL_MOUSEWHEEL: {
        int y = e->wheel.direction == SDL_MOUSEWHEEL_FLIPPED ? -e->wheel.y : e->wheel.y;
        view_camera_zoom(&v->cam, (float)y);
        v->dirty = true;
        break;
    }
    case SDL_WINDOWEVENT:
        if (e->window.event == SDL_WINDOWEVENT_SIZE_CHANGED ||
            e->window.event == SDL_WINDOWEVENT_EXPOSED) {
            v->dirty = true;
        }
        break;
    default:
        break;
    }
}

static void loop(viewer *v)
{
    if (v->script) {
        v->script_wait = view_script_advance(v->script, v->win, v->ev_shot);
        v->script_pushed = true;
    }
    if (v->o.screenshot && v->o.frames == 0 && (!v->script || v->script_wait == 0)) {
        request_screenshot(v, v->o.screenshot);   /* the first frame shows it all */
        v->final_shot = true;
    }
    v->dirty = true;
    while (!v->quit) {
        SDL_Event e;
        bool continuous = v->o.frames > 0 || (v->script && v->script_wait > 0);
        /* Block for input or a finished frame, unless a frame should start. */
        bool start_now = !v->rendering && (v->dirty || continuous);
        int got = start_now ? SDL_PollEvent(&e) : SDL_WaitEvent(&e);
        bool presented = false;
        while (got) {
            handle_event(v, &e);
            if (e.type == v->ev_done) {
                presented = true;
            }
            got = SDL_PollEvent(&e);
        }
        if (v->quit) {
            break;
        }
        continuous = v->o.frames > 0 || (v->script && v->script_wait > 0);
        /* SDL ends a round of polling at a sentinel, so events the script
         * pushed during this round arrive in the next one: wait for them. */
        bool hold = v->script_pushed;
        v->script_pushed = false;
        if (hold) {
            v->dirty = true;
        } else if (!v->rendering && (v->dirty || continuous)) {
            kick(v);   /* the next frame renders while this one is presented */
        }
        if (presented) {
            present(v);
        }
    }
    /* Let a frame in flight finish before anything it uses goes away. */
    while (v->rendering) {
        SDL_Event e;
        if (!SDL_WaitEvent(&e)) {
            break;
        }
        if (e.type == v->ev_done) {
            v->rendering = false;
        } else if (e.type == v->ev_shot) {
            free(e.user.data1);
        }
    }
}

/* render's warnings of options that have no effect, said once at the
 * start as render says them: of the user's own options, since the mode
 * table's always name an SSAA filter (and the keys may change the
 * shading later, when the warning no longer holds).  Those options parse,
 * as the job's did with them. */
static void warn_no_effect(const viewer *v)
{
    const char *argv[MAX_ARGS];
    int n = operand_args(v, argv, v->o.argc);
    memcpy(argv, v->o.argv, (size_t)v->o.argc * sizeof *argv);
    render_opts o = render_opts_defaults();
    char held[512];
    cli_capture(held, sizeof held);
    int status = render_opts_parse(n, (char **)argv, &o);
    cli_capture(NULL, 0);
    if (status < 0) {
        render_opts_warn(&o);
    }
}

int cmd_view(int argc, char **argv)
{
    viewer *v = calloc(1, sizeof *v);
    if (!v) {
        cli_error("view: out of memory");
        return EXIT_FAILURE_RUN;
    }
    v->o.width = 1280;
    v->o.height = 720;
    int status = parse_view_args(argc, argv, &v->o);
    if (status >= 0) {
        free(v);
        return status;
    }
    if (v->o.window_shot && !v->o.screenshot) {
        cli_error("view: --screenshot-overlay needs --screenshot FILE too");
        free(v);
        return EXIT_USAGE;
    }
    v->base_argc = view_modes_init(&v->modes, v->o.argc, (char *const *)v->o.argv, v->base);
    v->overlay = !v->o.no_overlay;

    /* Options, the model and the script first: their errors do not need a
     * display. */
    const char *args[MAX_ARGS];
    int n = current_args(v, args);
    status = render_job_parse(n, (char **)args, &v->job);
    if (status < 0) {
        warn_no_effect(v);
        /* Two frames: one drawn while the other is shown. */
        status = render_job_check_frames(v->job, "view", v->o.width, v->o.height, 2);
    }
    if (status < 0) {
        status = render_job_load(v->job);
    }
    if (status < 0 && v->o.events) {
        status = view_script_load(v->o.events, &v->script);
    }
    const char *font = v->o.font ? v->o.font : VIEW_DEFAULT_FONT;
    char why[600];
    if (status < 0 && !view_font_open(font, 14, &v->font, why, sizeof why)) {
        if (v->o.font) {
            cli_error("view: --font: %s", why);
            status = EXIT_USAGE;
        } else {
            /* The window is still worth having: say once why it has no text. */
            cli_error("view: no overlay text: %s (install fonts-dejavu-core)", why);
        }
    }
    if (status < 0) {
        /* Screenshots never replace an input, whether named here or by
         * the script (view_frames.c checks those as it writes them). */
        cli_inputs *inputs = render_job_inputs(v->job);
        cli_inputs_add(inputs, v->o.events, "event script");
        cli_inputs_add(inputs, font, "font");
        if (!cli_check_output(inputs, "view: --screenshot", v->o.screenshot) ||
            !cli_check_output(inputs, "view: --screenshot-overlay", v->o.window_shot)) {
            status = EXIT_USAGE;
        }
    }
    if (status >= 0) {
        goto done;
    }
    view_camera_init(&v->cam, v->job);
    v->model = render_job_model(v->job);

    /* With no display SDL would fall back to its invisible offscreen
     * driver and run unseen: ask for a real display unless the user named
     * a driver (SDL_VIDEODRIVER=offscreen does run headless, on purpose). */
    const char *driver = getenv("SDL_VIDEODRIVER"), *disp = getenv("DISPLAY"),
               *wl = getenv("WAYLAND_DISPLAY");
    bool have_x = disp && *disp, have_wl = wl && *wl;
    if (!driver || !*driver) {
        if (!have_x && !have_wl) {
            cli_error("view: no display to open a window on (DISPLAY and WAYLAND_DISPLAY are "
                      "not set; run it in a desktop session, or under xvfb-run)");
            status = EXIT_FAILURE_RUN;
            goto done;
        }
        SDL_SetHint(SDL_HINT_VIDEODRIVER, have_x && have_wl ? "x11,wayland"
                                          : have_x           ? "x11" : "wayland");
    }
    if (SDL_Init(SDL_INIT_VIDEO | SDL_INIT_EVENTS) != 0) {
        cli_error("view: cannot open a window%s%s: %s", have_x ? " on DISPLAY=" : "",
                  have_x ? disp : "", SDL_GetError());
        status = EXIT_FAILURE_RUN;
        goto done;
    }
    v->win = SDL_CreateWindow("softrast view", SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED,
                              v->o.width, v->o.height, SDL_WINDOW_RESIZABLE);
    if (v->win) {
        /* Vsync'd present: the swap to a new frame happens between refreshes. */
        Uint32 flags = v->o.no_vsync ? 0 : SDL_RENDERER_PRESENTVSYNC;
        v->ren = SDL_CreateRenderer(v->win, -1, flags);
        if (!v->ren && flags) {
            v->ren = SDL_CreateRenderer(v->win, -1, 0);
        }
    }
    if (!v->win || !v->ren) {
        cli_error("view: cannot open a window: %s", SDL_GetError());
        status = EXIT_FAILURE_RUN;
        goto done;
    }
    v->ev_done = SDL_RegisterEvents(2);
    v->ev_shot = v->ev_done + 1;
    v->vf.done_event = v->ev_done;
    int w, h;
    if (SDL_GetRendererOutputSize(v->ren, &w, &h) != 0 || w < 1 || h < 1) {
        w = v->o.width;
        h = v->o.height;
    }
    if (!view_frames_start(&v->vf, v->job, v->font, w, h)) {
        cli_error("view: %s", v->vf.error);
        status = EXIT_FAILURE_RUN;
        goto done;
    }
    v->status = EXIT_OK;
    loop(v);
    status = v->status;
    if (v->o.log && v->ntimes > 0) {
        double lo = v->times[0], hi = v->times[0];
        for (size_t i = 0; i < v->ntimes; i++) {
            lo = fmin(lo, v->times[i]);
            hi = fmax(hi, v->times[i]);
        }
        printf("softrast view: %zu frame%s at %dx%d, %d threads: render median %.2f ms "
               "(min %.2f, max %.2f)\n", v->ntimes, v->ntimes == 1 ? "" : "s",
               sr_framebuffer_width(v->vf.front),
               sr_framebuffer_height(v->vf.front),
               sr_context_threads(render_job_context(v->job)), median(v->times, v->ntimes), lo,
               hi);
    }

done:
    view_frames_stop(&v->vf);
    if (v->tex) {
        SDL_DestroyTexture(v->tex);
    }
    if (v->ren) {
        SDL_DestroyRenderer(v->ren);
    }
    if (v->win) {
        SDL_DestroyWindow(v->win);
    }
    if (SDL_WasInit(0)) {
        SDL_Quit();
    }
    view_font_close(v->font);
    view_script_free(v->script);
    render_job_free(v->job);
    free(v->times);
    free(v);
    return status;
}

#endif /* SR_HAVE_VIEWER */
