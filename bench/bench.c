/* bench.c - softrast-bench (bench): times the scenes of scenes.c through
 * softrast and, with --compare, through Mesa llvmpipe (gl_compare.c) in the
 * same run, frame by frame in alternation, and prints one machine-readable
 * line per result.  One context and one framebuffer serve every frame.
 * Timing: CLOCK_MONOTONIC around whole frames (clear, draw, finish); the
 * figure is the median over --frames frames after WARMUP_FRAMES. */
#include "gl_compare.h"
#include "scenes.h"
#include "polyfill.h"
#include "shapes2d.h"
#include "softrast_io.h"

#include <errno.h>
#include <fcntl.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define WARMUP_FRAMES 3
#define DEFAULT_FRAMES 30
#define MAX_FRAMES 100000

typedef struct bench_opts {
    const char *scenes[64];
    int scene_count;
    int threads;             /* 0: the library's default */
    int width, height;
    int frames;
    bool compare;
    bool gl_default_malloc;  /* leave glibc's thresholds as they are (see keep_gl_memory) */
    const char *save_dir;
    shapes2d_cases cases;    /* shapes2d: the paints, shapes, sizes to time (NULL: all) */
} bench_opts;

typedef struct bench_run {
    const bench_opts *o;
    sr_context *ctx;
    sr_framebuffer *fb;
    sr_framebuffer *ms_fb;   /* multisampled scenes draw here, then resolve into fb */
    int threads;             /* what the context really uses */
    gl_renderer *gl;         /* NULL until a --compare scene needs it */
    bool gl_failed;
    double *sr_ms, *gl_ms;   /* --frames entries each */
    int failures;
} bench_run;

static void usage(FILE *f)
{
    fprintf(f,
        "usage: softrast-bench [SCENE...] [--threads N] [--size WxH] [--frames N]\n"
        "                      [--compare] [--gl-default-malloc] [--save-images DIR]\n"
        "                      [--paint LIST] [--shape LIST] [--shape-size LIST]\n"
        "\n"
        "Times each SCENE (all of them when none is given).  The first line says\n"
        "when and where:  date=YYYY-MM-DDTHH:MM:SSZ cpu=MODEL (the rest of the line);\n"
        "then one line per result:\n"
        "         scene=S renderer=R size=WxH threads=N frames=F median_ms=...\n"
        "         min_ms=... mtri_s=... mpix_s=...\n"
        "mtri_s is triangles per frame / median seconds / 1e6; mpix_s is framebuffer\n"
        "pixels per frame (fill: 100 x W x H fragments) / median seconds / 1e6.\n"
        "A frame is clear, draw (and resolve) until its pixels can be read, on both\n"
        "renderers (softrast: sr_framebuffer_pixels; llvmpipe: glFinish).\n"
        "\n"
        "scenes:\n"
        "  bunny, spot, teapot  the model (from $SR_MODELS_DIR, else %s),\n"
        "                       framed like `softrast render`, Gouraud, depth LESS\n"
        "  spot_tex             spot with spot_texture.png modulating the Gouraud color,\n"
        "                       trilinear (llvmpipe: GL_LINEAR_MIPMAP_LINEAR, GL_MODULATE)\n"
        "  small                1,000,000 random triangles of 2-10 px^2, vertex colors\n"
        "  fill                 100 full-screen quads back to front, vertex colors\n"
        "  cli                  the whole `softrast render bunny` process\n"
        "  lines                100,000 random segments 10-200 px long\n"
        "  msaa4                the bunny with 4x MSAA, resolved every frame (llvmpipe:\n"
        "                       a 4-sample FBO blitted to the buffer)\n"
        "  polyfill, polyfill_aa  a 10,000-edge 2D polygon, aliased and antialiased\n"
        "  shapes2d             Blend2D bl_bench-like batches: rect, poly10/20/40, curves;\n"
        "                       8-256 px; solid, linear, radial, pattern paint; softrast\n"
        "                       renders each batch as SVG and through its API\n"
        "                       (sr_fill_path_paint; --compare: cairo draws it too);\n"
        "                       --frames counts at most 5 per case\n"
        "  icons                every 16th SVG of $SR_BENCH_ICONS (default %s),\n"
        "                       each rendered and written as PNG in this process, then by\n"
        "                       `softrast svg` and `rsvg-convert` one process per file;\n"
        "                       files per second and ratios (--frames: passes, at most 3)\n"
        "  phong                the bunny, Blinn-Phong per pixel (llvmpipe: Gouraud)\n"
        "  pbr                  the bunny through the metallic-roughness program under\n"
        "                       --environment hemisphere (softrast only)\n"
        "  pbr_studio           the same under the built-in studio, the CLI's default look\n"
        "  pbr_textured         a tiled torus from a generated .glb (softrast-pbr-asset):\n"
        "                       its base color, metallic-roughness, normal and occlusion\n"
        "                       maps, the studio environment and the key light's shadow\n"
        "                       map, drawn every frame (softrast only)\n"
        "\n"
        "options:\n"
        "  --threads N          rasterizer threads (default: SR_THREADS or CPUs);\n"
        "                       llvmpipe gets the same through LP_NUM_THREADS\n"
        "  --size WxH           framebuffer size (default 1920x1080)\n"
        "  --frames N           timed frames per scene after %d warm-up (default %d)\n"
        "  --compare            also render through Mesa llvmpipe (OSMesa), alternating\n"
        "                       frame by frame, and print a line with\n"
        "                       ratio=llvmpipe_ms/softrast_ms (> 1: softrast is faster)\n"
        "                       and differ_pct, the percentage of pixels where a channel\n"
        "                       differs by more than 16/255 in the last frames\n"
        "  --gl-default-malloc  with --compare, leave glibc's malloc thresholds alone:\n"
        "                       llvmpipe then hands its per-frame memory back to the\n"
        "                       kernel and faults it in again every frame (see docs)\n"
        "  --save-images DIR    write DIR/SCENE-RENDERER.png (the last frame)\n"
        "  --paint LIST         shapes2d: only these paints, comma-separated (solid,\n"
        "                       linear, radial, pattern); the batches stay the same\n"        "  --shape LIST         shapes2d: only these shapes (rect, poly10, poly20,\n"
        "                       poly40, curves)\n"
        "  --shape-size LIST    shapes2d: only these sizes (8, 16, 32, 64, 128, 256)\n"
        "  --version            print the version\n"
        "  -h, --help           this help\n"
        "\n"
        "Options take their value as the next word or after '=' (--size=640x480).\n"
        "A --size whose frames (the scenes' and, with --compare, llvmpipe's) need more\n"
        "memory than the machine has or SR_MEMORY_LIMIT allows is refused.\n"
        "Exit status: 0, 1 when a scene or the run fails, 2 for bad options.\n",
        SR_BENCH_MODELS_DIR, SR_BENCH_ICONS_DIR, WARMUP_FRAMES, DEFAULT_FRAMES);
}

static bool parse_int(const char *opt, const char *s, int lo, int hi, int *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno || end == s || *end || v < lo || v > hi) {
        fprintf(stderr, "softrast-bench: %s: '%s' is not an integer in %d..%d\n", opt, s, lo, hi);
        return false;
    }
    *out = (int)v;
    return true;
}

static bool parse_size(const char *opt, const char *s, int *w, int *h)
{
    char *end;
    errno = 0;
    long a = strtol(s, &end, 10);
    if (errno || end == s || (*end != 'x' && *end != 'X')) {
        goto bad;
    }
    const char *t = end + 1;
    long b = strtol(t, &end, 10);
    if (errno || end == t || *end || a < 1 || b < 1 || a > SR_MAX_FRAMEBUFFER_SIZE ||
        b > SR_MAX_FRAMEBUFFER_SIZE) {
        goto bad;
    }
    *w = (int)a;
    *h = (int)b;
    return true;
bad:
    fprintf(stderr, "softrast-bench: %s: '%s' is not WxH with each in 1..%d\n", opt, s,
            SR_MAX_FRAMEBUFFER_SIZE);
    return false;
}

/* A SCENE argument into o; false after one line. */
static bool take_scene(bench_opts *o, const char *a)
{
    if (!bench_find_scene(a)) {
        fprintf(stderr, "softrast-bench: unknown scene '%s' (expected", a);
        for (int k = 0; k < bench_scene_count; k++) {
            fprintf(stderr, " %s", bench_scene_list[k].name);
        }
        fprintf(stderr, ")\n");
        return false;
    }
    if (o->scene_count == (int)(sizeof o->scenes / sizeof o->scenes[0])) {
        fprintf(stderr, "softrast-bench: too many scenes\n");
        return false;
    }
    o->scenes[o->scene_count++] = a;
    return true;
}

/* Returns -1 to go on, else the exit status. */
static int parse_args(int argc, char **argv, bench_opts *o)
{
    bool ended = false;   /* after "--", as every softrast command takes it */
    for (int i = 1; i < argc; i++) {
        /* "--name=value" is "--name value", as in every softrast command. */
        char name[32];
        const char *a = argv[i], *eq = strncmp(a, "--", 2) == 0 ? strchr(a, '=') : NULL;
        if (!ended && eq && (size_t)(eq - a) < sizeof name) {
            memcpy(name, a, (size_t)(eq - a));
            name[eq - a] = '\0';
            a = name;
        } else {
            eq = NULL;
        }
        bool has_value = eq || i + 1 < argc;
        bool valued = strcmp(a, "--threads") == 0 || strcmp(a, "--size") == 0 ||
                      strcmp(a, "--frames") == 0 || strcmp(a, "--save-images") == 0 ||
                      strcmp(a, "--paint") == 0 || strcmp(a, "--shape") == 0 ||
                      strcmp(a, "--shape-size") == 0;
        bool flag = strcmp(a, "--compare") == 0 || strcmp(a, "--gl-default-malloc") == 0 ||
                    strcmp(a, "--help") == 0 || strcmp(a, "--version") == 0;
        if (eq && flag) {
            fprintf(stderr, "softrast-bench: %s: takes no value\n", a);
            return 2;
        }
        if (eq && !valued) {
            a = argv[i];   /* unknown: named whole below */
        }
        if (!ended && strcmp(a, "--") == 0) {
            ended = true;
            continue;
        } else if (ended) {
            if (!take_scene(o, a)) {
                return 2;
            }
        } else if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            usage(stdout);
            return 0;
        } else if (strcmp(a, "--version") == 0) {
            printf("softrast-bench %s\n", SR_VERSION_STRING);
            return 0;
        } else if (strcmp(a, "--compare") == 0) {
            o->compare = true;
        } else if (strcmp(a, "--gl-default-malloc") == 0) {
            o->gl_default_malloc = true;
        } else if (valued) {
            if (!has_value) {
                fprintf(stderr, "softrast-bench: %s: missing value\n", a);
                return 2;
            }
            const char *v = eq ? eq + 1 : argv[++i];
            bool ok = true;
            if (strcmp(a, "--threads") == 0) {
                ok = parse_int(a, v, 1, 64, &o->threads);
            } else if (strcmp(a, "--size") == 0) {
                ok = parse_size(a, v, &o->width, &o->height);
            } else if (strcmp(a, "--frames") == 0) {
                ok = parse_int(a, v, 1, MAX_FRAMES, &o->frames);
            } else if (strcmp(a, "--paint") == 0) {
                o->cases.paints = v;
                ok = bench_shapes2d_paints(v) != 0;
            } else if (strcmp(a, "--shape") == 0) {
                o->cases.shapes = v;
                ok = bench_shapes2d_shapes(v) != 0;
            } else if (strcmp(a, "--shape-size") == 0) {
                o->cases.sizes = v;
                ok = bench_shapes2d_sizes(v) != 0;
            } else {
                o->save_dir = v;
            }
            if (!ok) {
                return 2;
            }
        } else if (a[0] == '-') {
            fprintf(stderr, "softrast-bench: unknown option '%s' (try --help)\n", a);
            return 2;
        } else if (!take_scene(o, a)) {
            return 2;
        }
    }
    return -1;
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec / 1e6;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Sorts v. */
static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2.0;
}

static void print_result(const bench_run *run, const char *scene, const char *renderer,
                         double *ms, uint64_t triangles, uint64_t fragments)
{
    const bench_opts *o = run->o;
    double med = median(ms, o->frames);
    double s = med / 1e3;
    printf("scene=%s renderer=%s size=%dx%d threads=%d frames=%d median_ms=%.3f min_ms=%.3f "
           "mtri_s=%.4g mpix_s=%.4g\n",
           scene, renderer, o->width, o->height, run->threads, o->frames, med, ms[0],
           (double)triangles / s / 1e6, (double)fragments / s / 1e6);
    fflush(stdout);
}

static bool ensure_dir(const char *dir)
{
    if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "softrast-bench: --save-images: cannot create '%s': %s\n", dir,
                strerror(errno));
        return false;
    }
    return true;
}

static void save_image(const bench_run *run, const char *scene, const char *renderer,
                       const uint8_t *rgba)
{
    const bench_opts *o = run->o;
    char path[PATH_MAX];
    int n = snprintf(path, sizeof path, "%s/%s-%s.png", o->save_dir, scene, renderer);
    if (n < 0 || (size_t)n >= sizeof path) {
        fprintf(stderr, "softrast-bench: --save-images: path too long\n");
        return;
    }
    sr_io_error err;
    if (sr_write_png(path, o->width, o->height, rgba, (size_t)o->width * 4,
                     &(sr_png_write_desc){ .channels = SR_PNG_RGB }, &err) != SR_OK) {
        fprintf(stderr, "softrast-bench: %s\n", err.message);
    }
}

/* Percentage of pixels where some RGB channel differs by more than 16. */
static double differ_pct(const uint8_t *a, const uint8_t *b, size_t pixels)
{
    size_t differ = 0;
    for (size_t i = 0; i < pixels; i++) {
        for (int k = 0; k < 3; k++) {
            if (abs((int)a[i * 4 + k] - (int)b[i * 4 + k]) > 16) {
                differ++;
                break;
            }
        }
    }
    return pixels ? 100.0 * (double)differ / (double)pixels : 0.0;
}

static bool need_gl(bench_run *run)
{
    if (run->gl) {
        return true;
    }
    if (run->gl_failed) {
        return false;
    }
    char msg[256];
    if (!gl_make(run->o->width, run->o->height, run->threads, &run->gl, msg, sizeof msg)) {
        fprintf(stderr, "softrast-bench: --compare: llvmpipe skipped: %s\n", msg);
        run->gl_failed = true;
        return false;
    }
    if (!strstr(gl_renderer_name(run->gl), "llvmpipe")) {
        fprintf(stderr, "softrast-bench: --compare: note: OSMesa renders with '%s', not llvmpipe\n",
                gl_renderer_name(run->gl));
    }
    return true;
}

/* One frame into run->fb; a multisampled scene draws into run->ms_fb and
 * resolves into run->fb, as the GL side blits its multisampled FBO. */
static sr_result sr_frame(bench_run *run, const bench_scene *s)
{
    const float *c = s->clear_color;
    sr_framebuffer *fb = s->info->samples > 1 ? run->ms_fb : run->fb;
    sr_result r = SR_OK;
    if (s->shadow) {
        /* The key light's shadow map, drawn every frame as the CLI does. */
        r = sr_shadow_map_clear(run->ctx, s->shadow);
        if (r == SR_OK) {
            r = sr_shadow_map_draw(run->ctx, s->shadow, &(sr_draw_desc){
                .positions = s->positions, .vertex_count = s->vertex_count,
                .indices = s->indices, .index_type = SR_INDEX_U32,
                .index_count = s->index_count, .model = &s->model });
        }
    }
    if (r == SR_OK) {
        r = sr_clear(run->ctx, fb,
                     &(sr_clear_desc){ .color = { c[0], c[1], c[2], c[3] }, .depth = 1.0f });
    }
    if (r != SR_OK) {
        return r;
    }
    r = sr_draw(run->ctx, fb, &s->state, &(sr_draw_desc){
        .primitive = s->primitive, .positions = s->positions, .position_size = s->position_size,
        .normals = s->normals, .colors = s->colors, .color_size = 4,
        .texcoords = s->texcoords, .vertex_count = s->vertex_count,
        .indices = s->indices, .index_type = s->indices ? SR_INDEX_U32 : SR_INDEX_NONE,
        .index_count = s->index_count,
        .model = &s->model, .view = &s->view, .projection = &s->projection });
    if (r == SR_OK && fb != run->fb) {
        r = sr_resolve(run->ctx, fb, run->fb);
    }
    /* The frame is done when its pixels can be read, as GL's is after
     * glFinish: reading carries out the clears of the tiles nobody drew. */
    if (r == SR_OK) {
        sr_framebuffer_pixels(run->fb);
    }
    return r;
}

/* What softrast keeps of a scene on its context, made before timing as
 * GL makes its vertex buffer objects and texture in gl_prepare: the
 * arrays copied into vertex buffers (sr_make_buffer) and the texture. */
typedef struct sr_uploads {
    sr_buffer *buf[5];
    sr_texture *tex;
} sr_uploads;

/* Copies an array of `bytes` into a buffer and points *array at it. */
static sr_result upload_array(sr_context *ctx, const void **array, size_t bytes, sr_buffer **b)
{
    if (!*array || bytes == 0) {
        return SR_OK;
    }
    sr_result r = sr_make_buffer(ctx, *array, bytes, b);
    if (r == SR_OK) {
        *array = sr_buffer_data(*b);
    }
    return r;
}

/* The scene's arrays are pointed at the buffers, which GL's uploads read
 * as well (the same values). */
static sr_result upload_scene(sr_context *ctx, bench_scene *s, sr_uploads *up)
{
    *up = (sr_uploads){ { NULL }, NULL };
    size_t n = s->vertex_count;
    const void *arrays[5] = { s->positions, s->normals, s->colors, s->texcoords, s->indices };
    size_t bytes[5] = { n * (size_t)s->position_size * sizeof(float), n * 3 * sizeof(float),
                        n * 4 * sizeof(float), n * 2 * sizeof(float),
                        s->index_count * sizeof(uint32_t) };
    for (int i = 0; i < 5; i++) {
        sr_result r = upload_array(ctx, &arrays[i], bytes[i], &up->buf[i]);
        if (r != SR_OK) {
            return r;
        }
    }
    s->positions = arrays[0];
    s->normals = arrays[1];
    s->colors = arrays[2];
    s->texcoords = arrays[3];
    s->indices = arrays[4];
    if (s->texture_pixels) {
        sr_result r = sr_make_texture(ctx, &(sr_texture_desc){ .width = s->texture_w,
                                                               .height = s->texture_h,
                                                               .pixels = s->texture_pixels },
                                      &up->tex);
        if (r != SR_OK) {
            return r;
        }
        s->state.texture = up->tex;
    }
    return SR_OK;
}

static void free_uploads(sr_context *ctx, sr_uploads *up)
{
    for (int i = 0; i < 5; i++) {
        sr_destroy_buffer(ctx, up->buf[i]);
    }
    sr_destroy_texture(ctx, up->tex);
}

/* softrast's side of a scene, untimed: the uploads, and for a
 * multisampled scene its framebuffer. */
static sr_result sr_prepare(bench_run *run, bench_scene *s, sr_uploads *up)
{
    sr_result r = upload_scene(run->ctx, s, up);
    if (r != SR_OK || s->info->samples <= 1) {
        return r;
    }
    sr_destroy_framebuffer(run->ctx, run->ms_fb);
    run->ms_fb = NULL;
    return sr_make_framebuffer(run->ctx, &(sr_framebuffer_desc){ .width = run->o->width,
                                                                .height = run->o->height,
                                                                .depth_format = SR_DEPTH_D24,
                                                                .samples = s->info->samples },
                               &run->ms_fb);
}

/* softrast failed on scene s: say so, count it, free the scene. */
static void sr_failed(bench_run *run, bench_scene *s, sr_uploads *up)
{
    fprintf(stderr, "softrast-bench: %s: %s\n", s->info->name, sr_context_error(run->ctx));
    printf("scene=%s renderer=softrast skipped=error\n", s->info->name);
    run->failures++;
    free_uploads(run->ctx, up);
    bench_scene_free(s);
}

static void run_drawn_scene(bench_run *run, const bench_scene_info *info)
{
    const bench_opts *o = run->o;
    bench_scene s;
    char msg[600];
    sr_result r = bench_scene_make(info, o->width, o->height, &s, msg, sizeof msg);
    if (r != SR_OK) {
        bool missing = info->kind == BENCH_MESH && r == SR_IO_ERROR;
        fprintf(stderr, "softrast-bench: %s: skipped: %s\n", info->name, msg);
        printf("scene=%s skipped=%s\n", info->name, missing ? "missing-model" : "error");
        fflush(stdout);
        if (!missing) {
            run->failures++;
        }
        return;
    }

    sr_uploads up;
    if (sr_prepare(run, &s, &up) != SR_OK) {
        sr_failed(run, &s, &up);
        return;
    }

    /* llvmpipe draws the fixed-function models only. */
    bool compare = o->compare && !s.state.program && need_gl(run);
    if (compare && !gl_prepare(run->gl, &s, msg, sizeof msg)) {
        fprintf(stderr, "softrast-bench: %s: llvmpipe skipped: %s\n", info->name, msg);
        compare = false;
    }

    /* Alternate the renderers frame by frame so that both see the same
     * machine noise (other processes, clock changes). */
    for (int f = 0; f < WARMUP_FRAMES + o->frames; f++) {
        double t0 = now_ms();
        r = sr_frame(run, &s);
        double t1 = now_ms();
        if (r != SR_OK) {
            if (compare) {
                gl_unprepare(run->gl);
            }
            sr_failed(run, &s, &up);
            return;
        }
        if (compare) {
            double t2 = now_ms();
            gl_frame(run->gl, &s);
            double t3 = now_ms();
            if (f >= WARMUP_FRAMES) {
                run->gl_ms[f - WARMUP_FRAMES] = t3 - t2;
            }
            if (f == 0 && !gl_check(run->gl, msg, sizeof msg)) {
                fprintf(stderr, "softrast-bench: %s: llvmpipe skipped: %s\n", info->name, msg);
                gl_unprepare(run->gl);
                compare = false;
            }
        }
        if (f >= WARMUP_FRAMES) {
            run->sr_ms[f - WARMUP_FRAMES] = t1 - t0;
        }
    }

    print_result(run, info->name, "softrast", run->sr_ms, s.triangle_count, s.fragments_per_frame);
    if (compare) {
        print_result(run, info->name, "llvmpipe", run->gl_ms, s.triangle_count,
                     s.fragments_per_frame);
        /* print_result sorted both arrays: medians are in the middle. */
        double sr_med = median(run->sr_ms, o->frames), gl_med = median(run->gl_ms, o->frames);
        printf("scene=%s size=%dx%d threads=%d ratio=%.3f differ_pct=%.2f\n", info->name,
               o->width, o->height, run->threads, gl_med / sr_med,
               differ_pct(sr_framebuffer_pixels(run->fb), gl_pixels(run->gl),
                          (size_t)o->width * (size_t)o->height));
        fflush(stdout);
    }
    if (o->save_dir) {
        save_image(run, info->name, "softrast", sr_framebuffer_pixels(run->fb));
        if (compare) {
            save_image(run, info->name, "llvmpipe", gl_pixels(run->gl));
        }
    }
    if (compare) {
        gl_unprepare(run->gl);
    }
    free_uploads(run->ctx, &up);
    bench_scene_free(&s);
}

/* ---- cli: the whole `softrast render` process ---------------------------- */

/* fork, exec, wait.  The child's stdout goes to /dev/null; its stderr is
 * kept so a failure explains itself.  Returns the exit status, or -1. */
static int run_process(char *const argv[])
{
    pid_t pid = fork();
    if (pid < 0) {
        fprintf(stderr, "softrast-bench: fork: %s\n", strerror(errno));
        return -1;
    }
    if (pid == 0) {
        int devnull = open("/dev/null", O_WRONLY);
        if (devnull >= 0) {
            dup2(devnull, STDOUT_FILENO);
            close(devnull);
        }
        execv(argv[0], argv);
        fprintf(stderr, "softrast-bench: cannot run %s: %s\n", argv[0], strerror(errno));
        _exit(127);
    }
    int status;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) {
            fprintf(stderr, "softrast-bench: waitpid: %s\n", strerror(errno));
            return -1;
        }
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

static void run_cli_scene(bench_run *run, const bench_scene_info *info)
{
    const bench_opts *o = run->o;
#ifndef SR_BENCH_CLI_PATH
    fprintf(stderr, "softrast-bench: cli: skipped: this build has no softrast CLI target\n");
    printf("scene=%s skipped=no-cli\n", info->name);
    (void)o;
    return;
#else
    const char *cli = SR_BENCH_CLI_PATH;
    if (access(cli, X_OK) != 0) {
        fprintf(stderr, "softrast-bench: cli: skipped: %s: %s (build target softrast_cli)\n", cli,
                strerror(errno));
        printf("scene=%s skipped=no-cli\n", info->name);
        return;
    }
    char model[PATH_MAX];
    snprintf(model, sizeof model, "%s/%s", bench_models_dir(), info->model_file);
    /* The triangle count, for mtri_s (untimed). */
    sr_mesh mesh;
    sr_io_error err;
    sr_context *mesh_ctx;
    if (sr_make_context(&(sr_context_desc){ .threads = 1 }, &mesh_ctx) != SR_OK) {
        fprintf(stderr, "softrast-bench: cli: skipped: no context\n");
        return;
    }
    if (sr_load_mesh(mesh_ctx, model, NULL, &mesh, &err) != SR_OK) {
        fprintf(stderr, "softrast-bench: cli: skipped: %s\n", err.message);
        printf("scene=%s skipped=missing-model\n", info->name);
        sr_destroy_context(mesh_ctx);
        return;
    }
    uint64_t triangles = mesh.triangle_count;
    sr_destroy_mesh(mesh_ctx, &mesh);
    sr_destroy_context(mesh_ctx);

    const char *tmp = getenv("TMPDIR");
    char dir[PATH_MAX], out[PATH_MAX + 16], size[32], threads[16];
    snprintf(dir, sizeof dir, "%s/softrast-bench-XXXXXX", tmp && tmp[0] ? tmp : "/tmp");
    if (!mkdtemp(dir)) {
        fprintf(stderr, "softrast-bench: cli: mkdtemp: %s\n", strerror(errno));
        printf("scene=%s skipped=error\n", info->name);
        run->failures++;
        return;
    }
    snprintf(out, sizeof out, "%s/out.png", dir);
    snprintf(size, sizeof size, "%dx%d", o->width, o->height);
    snprintf(threads, sizeof threads, "%d", run->threads);
    char *argv[] = { (char *)cli, "render", model, "--size", size, "-o", out,
                     "--threads", threads, NULL };

    bool ok = true;
    for (int f = 0; f < WARMUP_FRAMES + o->frames && ok; f++) {
        double t0 = now_ms();
        int status = run_process(argv);
        double t1 = now_ms();
        if (status != 0) {
            fprintf(stderr, "softrast-bench: cli: '%s render %s ...' exited with %d\n", cli, model,
                    status);
            ok = false;
        } else if (f >= WARMUP_FRAMES) {
            run->sr_ms[f - WARMUP_FRAMES] = t1 - t0;
        }
    }
    if (ok) {
        print_result(run, info->name, "softrast", run->sr_ms, triangles,
                     (uint64_t)o->width * (uint64_t)o->height);
        if (o->save_dir) {
            char saved[PATH_MAX];
            snprintf(saved, sizeof saved, "%s/%s-softrast.png", o->save_dir, info->name);
            argv[6] = saved;
            run_process(argv);
        }
    } else {
        printf("scene=%s skipped=error\n", info->name);
        run->failures++;
    }
    unlink(out);
    rmdir(dir);
#endif
}

/* The date (UTC) and the CPU model of the run: the ratios hold for this
 * machine on this day, so they travel with them. */
static void print_run_header(void)
{
    char date[32] = "unknown", cpu[256] = "unknown", line[512];
    time_t t = time(NULL);
    struct tm tm;
    if (gmtime_r(&t, &tm)) {
        strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", &tm);
    }
    FILE *f = fopen("/proc/cpuinfo", "r");
    while (f && fgets(line, sizeof line, f)) {
        const char *colon = strchr(line, ':');
        if (colon && strncmp(line, "model name", 10) == 0) {
            snprintf(cpu, sizeof cpu, "%s", colon + 1 + (colon[1] == ' '));
            cpu[strcspn(cpu, "\n")] = '\0';
            break;
        }
    }
    if (f) {
        fclose(f);
    }
    printf("date=%s cpu=%s\n", date, cpu);
    fflush(stdout);
}

/* llvmpipe at its best.  It frees its per-frame memory (bins, scene
 * data) at the end of every frame, glibc gives large blocks back to the
 * kernel, and the next frame faults them in again: on the development
 * machine the bunny took llvmpipe 36-40 ms that way, and 13-15 ms once a
 * scene before it (small) had raised glibc's dynamic mmap threshold, so its
 * time depended on the order of the scenes.  Fixed thresholds keep that
 * memory in the process for every scene (softrast is unaffected: its
 * large blocks are mapped by its own allocator). */
static void keep_gl_memory(void)
{
#ifdef __GLIBC__
    mallopt(M_MMAP_THRESHOLD, 32 << 20);    /* glibc's largest */
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

/* Whether the frames of --size fit the memory limit (sr_check_memory): a
 * frame of color and D24 depth, a multisampled scene's frame of its
 * samples, and under --compare llvmpipe's the same and its pixels read
 * back; 2 after one line when they do not, else -1.  The cli scene's
 * process checks its own. */
static int check_memory(const bench_opts *o)
{
    int samples = 0;
    for (int i = 0; i < o->scene_count; i++) {
        const bench_scene_info *info = bench_find_scene(o->scenes[i]);
        if (info && info->samples > samples) {
            samples = info->samples;
        }
    }
    uint64_t per_pixel = 8 + (samples > 1 ? 8 * (uint64_t)samples : 0);
    if (o->compare) {
        per_pixel = 2 * per_pixel + 4;
    }
    char what[96];
    snprintf(what, sizeof what, "softrast-bench: --size %dx%d%s%s", o->width, o->height,
             samples > 1 ? " with a multisampled scene" : "", o->compare ? " and --compare" : "");
    sr_io_error err;
    sr_result r = sr_check_memory(
        &(sr_memory_check_desc){ .what = what,
                                 .bytes = per_pixel * (uint64_t)o->width * (uint64_t)o->height,
                                 .memory = "frame memory", .lower = "give a smaller --size" },
        &err);
    if (r != SR_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 2;
    }
    return -1;
}

int main(int argc, char **argv)
{
    bench_opts o = { .width = 1920, .height = 1080, .frames = DEFAULT_FRAMES };
    int status = parse_args(argc, argv, &o);
    if (status >= 0) {
        return status;
    }
    if (o.scene_count == 0) {
        for (int i = 0; i < bench_scene_count; i++) {
            o.scenes[o.scene_count++] = bench_scene_list[i].name;
        }
    }
    if (o.save_dir && !ensure_dir(o.save_dir)) {
        return 1;
    }
    if (o.compare && !gl_available()) {
        fprintf(stderr, "softrast-bench: --compare: this build has no OSMesa (install "
                        "libosmesa6-dev and re-run cmake); comparison skipped\n");
        o.compare = false;
    }
    status = check_memory(&o);
    if (status >= 0) {
        return status;
    }
    if (o.compare && !o.gl_default_malloc) {
        keep_gl_memory();
    }

    bench_run run = { .o = &o };
    run.sr_ms = calloc((size_t)o.frames, sizeof(double));
    run.gl_ms = calloc((size_t)o.frames, sizeof(double));
    sr_result r = run.sr_ms && run.gl_ms ? SR_OK : SR_OUT_OF_MEMORY;
    if (r == SR_OK) {
        r = sr_make_context(&(sr_context_desc){ .threads = o.threads }, &run.ctx);
    }
    if (r == SR_OK) {
        r = sr_make_framebuffer(run.ctx, &(sr_framebuffer_desc){ .width = o.width,
                                                                 .height = o.height,
                                                                 .depth_format = SR_DEPTH_D24 },
                                &run.fb);
    }
    if (r != SR_OK) {
        fprintf(stderr, "softrast-bench: %s\n", run.ctx ? sr_context_error(run.ctx)
                                                        : sr_result_text(r));
        sr_destroy_context(run.ctx);
        free(run.sr_ms);
        free(run.gl_ms);
        return 1;
    }
    run.threads = sr_context_threads(run.ctx);
    print_run_header();

    for (int i = 0; i < o.scene_count; i++) {
        const bench_scene_info *info = bench_find_scene(o.scenes[i]);
        switch (info->kind) {
        case BENCH_CLI:
            run_cli_scene(&run, info);
            break;
        case BENCH_POLYFILL:
        case BENCH_POLYFILL_AA:
            if (!bench_polyfill(run.ctx, run.threads, o.frames, o.compare,
                                info->kind == BENCH_POLYFILL_AA, info->name)) {
                run.failures++;
            }
            break;
        case BENCH_SHAPES2D:
            run.failures += !bench_shapes2d(run.ctx, o.frames, o.compare, &o.cases);
            break;
        case BENCH_ICONS:
            run.failures += !bench_icons(o.frames);
            break;
        default:
            run_drawn_scene(&run, info);
            break;
        }
    }

    gl_destroy(run.gl);
    sr_destroy_framebuffer(run.ctx, run.fb);
    sr_destroy_framebuffer(run.ctx, run.ms_fb);
    sr_destroy_context(run.ctx);
    free(run.sr_ms);
    free(run.gl_ms);
    return run.failures ? 1 : 0;
}
