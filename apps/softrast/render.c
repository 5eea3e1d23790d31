/* render.c - `softrast render [MODEL] [options]`: load a model (or build the
 * teapot scene), frame it with a camera, light it, draw it with the
 * pipeline and write a PNG atomically. */
#include "cli.h"
#include "framing.h"
#include "render.h"
#include "scene.h"
#include "softrast_io.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#define PI_F 3.14159265358979f

typedef struct render_opts {
    const char *model;
    const char *output;
    bool writes_output;            /* `render`, not `view`: no input may be the output */
    const char *texture;           /* --texture FILE */
    sr_texture_filter texture_filter;
    sr_texture_wrap wrap;
    bool texture_srgb;
    int width, height;
    sr_shading shading;
    sr_cull_mode cull;
    sr_front_face front;
    bool have_eye, have_target, have_up;
    sr_vec3 eye, target, up;
    float fov_deg;
    bool ortho;
    float turn_deg;
    float near_z, far_z;           /* 0: fitted */
    sr_light lights[SR_MAX_LIGHTS];
    int light_count;
    bool have_ambient;
    sr_vec3 ambient;
    bool have_mat_color, have_specular, have_shininess;
    sr_vec3 mat_color, specular;
    float shininess;
    sr_vec3 background;
    sr_depth_format depth_format;
    sr_depth_func depth_func;
    sr_interpolation interp;
    int normals;                   /* -1 auto, 0 file, 1 smooth, 2 flat */
    int detail;
    sr_rasterizer rasterizer;
    int threads;
    int png_level;
    int jpeg_quality;              /* 0: not given */
    bool verbose;
    int lines;                     /* LINES_NONE, ... */
    float line_width, point_size;
    float offset_factor, offset_units;  /* the depth pass of the line modes */
    sr_vec3 line_color;
    bool have_line_color;
    bool smooth;
    int ssaa;                      /* 1: off; k: render k x k samples per pixel */
    int msaa;                      /* 1: off; n: n samples per pixel, shaded once */
    float opacity;                 /* of the model; 1: opaque */
    sr_resample_filter filter;
} render_opts;

/* What the line modes draw besides (or instead of) the shaded model. */
enum { LINES_NONE = 0, LINES_WIREFRAME, LINES_HIDDEN, LINES_EDGES, LINES_POINTS };

static const char *const shading_names[] = { "flat", "gouraud", "phong", "normals", "depth",
                                             "unlit", NULL };
static const sr_shading shading_values[] = { SR_SHADING_FLAT, SR_SHADING_GOURAUD, SR_SHADING_PHONG,
                                             SR_SHADING_NORMALS, SR_SHADING_DEPTH, SR_SHADING_UNLIT };
static const char *const cull_names[] = { "back", "front", "none", NULL };
static const sr_cull_mode cull_values[] = { SR_CULL_BACK, SR_CULL_FRONT, SR_CULL_NONE };
static const char *const front_names[] = { "ccw", "cw", NULL };
static const char *const depth_format_names[] = { "d16", "d24", "d32", "d32f", NULL };
static const sr_depth_format depth_format_values[] = { SR_DEPTH_D16, SR_DEPTH_D24, SR_DEPTH_D32,
                                                       SR_DEPTH_D32F };
static const char *const depth_func_names[] = { "never", "less", "equal", "lequal", "greater",
                                                "notequal", "gequal", "always", NULL };
static const char *const interp_names[] = { "perspective", "affine", NULL };
static const char *const normals_names[] = { "file", "smooth", "flat", NULL };
static const char *const raster_names[] = { "halfspace", "scanline", "barycentric", NULL };
static const char *const filter_names[] = { "nearest", "bilinear", "trilinear", NULL };
static const char *const aa_names[] = { "none", "ssaa2", "ssaa3", "ssaa4", "msaa2", "msaa4",
                                         "msaa8", "msaa16", NULL };
static const int aa_ssaa[] = { 1, 2, 3, 4, 1, 1, 1, 1 };
static const int aa_msaa[] = { 1, 1, 1, 1, 2, 4, 8, 16 };
static const char *const resample_names[] = { "box", "tent", "gaussian", "mitchell", NULL };
static const char *const wrap_names[] = { "repeat", "clamp", "mirror", NULL };

static void render_help(void)
{
    printf(
        "usage: softrast render [MODEL] [options]\n"
        "\n"
        "Render MODEL (.obj, .ply, .stl; other formats through Assimp when built\n"
        "with it) or, without MODEL, the built-in Utah teapot scene, to a PNG or\n"
        "a JPEG.\n"
        "\n"
        "output:\n"
        "  -o, --output FILE        image to write, atomically: a JPEG when FILE ends in\n"
        "                           .jpg or .jpeg, else a PNG (default softrast.png)\n"
        "  --size WxH               image size, 1..8192 each (default 1280x720)\n"
        "  --background COLOR       name, #rgb, #rrggbb, R,G,B in 0..1, or a gray level\n"
        "                           in 0..1 (default #1d2230)\n"
        "  --png-level N            zlib level 0..9 (default 1: fast, see docs)\n"
        "  --jpeg-quality N         JPEG quality 1..100 (default 90)\n"
        "shading:\n"
        "  --shading MODE           flat|gouraud|phong|normals|depth|unlit (default phong)\n"
        "  --normals MODE           file|smooth|flat: the file's normals, angle-weighted\n"
        "                           smooth ones, or one per face (default: file if the\n"
        "                           model has them, else smooth)\n"
        "  --material KEY=V,...     color=COLOR, specular=COLOR, shininess=N\n"
        "                           (default: light gray, specular 0.25, shininess 40)\n"
        "  --ambient COLOR          global ambient light (default 0.12,0.12,0.14)\n"
        "  --opacity A              the model's opacity, 0..1 (default 1); translucent\n"
        "                           surfaces are drawn after opaque ones, back to front\n"
        "  --light dir=X,Y,Z[,color=C][,intensity=I]\n"
        "  --light point=X,Y,Z[,color=C][,intensity=I]\n"
        "                           add a light in world space (repeatable, up to 8);\n"
        "                           without any, a key, fill and rim light placed\n"
        "                           relative to the camera\n"
        "textures:\n"
        "  --texture FILE           PNG or JPEG that colors the model through its texture\n"
        "                           coordinates (default: the model's own - OBJ map_Kd,\n"
        "                           glTF/FBX textures named or embedded - each material's\n"
        "                           on its own faces, or MODEL_texture.png or .jpg beside\n"
        "                           a model MODEL.obj;\n"
        "                           one of those that cannot be read is a warning)\n"
        "  --texture-filter F       nearest|bilinear|trilinear (default trilinear)\n"
        "  --wrap MODE              repeat|clamp|mirror (default repeat)\n"
        "  --texture-srgb           filter texels in linear light (sRGB-correct)\n"
        "camera:\n"
        "  --camera eye=X,Y,Z[,target=X,Y,Z][,up=X,Y,Z]\n"
        "                           (default: a three-quarter view from above that\n"
        "                           frames the model's bounding sphere)\n"
        "  --fov DEG                field of view across the smaller image side\n"
        "                           (default 35)\n"
        "  --ortho                  orthographic projection\n"
        "  --turn DEG               rotate the model about the vertical axis (default 0)\n"
        "  --near Z, --far Z        clip distances (default: fitted to the scene)\n"
        "pipeline:\n"
        "  --cull MODE              back|front|none (default back)\n"
        "  --front-face ORDER       ccw|cw (default ccw)\n"
        "  --depth-format F         d16|d24|d32|d32f (default d24)\n"
        "  --depth-func F           never|less|equal|lequal|greater|notequal|gequal|always\n"
        "                           (default less; greater and gequal clear depth to 0)\n"
        "  --projection-interp M    perspective|affine (default perspective)\n"
        "lines and points:\n"
        "  --wireframe              every edge, hidden ones too, no shading\n"
        "  --hidden-line            only the visible edges (a depth pass pushed back by\n"
        "                           polygon offset, then the edges)\n"
        "  --edges                  the shaded model with its visible edges over it\n"
        "  --points                 the visible vertices as points\n"
        "  --line-width N           1..64 pixels (default 1)\n"
        "  --point-size N           1..64 pixels (default 3)\n"
        "  --line-color COLOR       (default #e8ecf4, or #202020 on a light background)\n"
        "  --smooth                 antialiased lines and round antialiased points\n"
        "  --polygon-offset F,U     how far the depth pass of --hidden-line, --edges and\n"
        "                           --points is pushed back: factor F times the depth\n"
        "                           slope plus U depth steps (default 1,1; 0,0 shows the\n"
        "                           stitching it prevents)\n"
        "  --aa MODE                none|ssaa2|ssaa3|ssaa4: render k x k samples per pixel\n"
        "                           and filter them down; msaa2|msaa4|msaa8|msaa16: that\n"
        "                           many coverage and depth samples per pixel, shaded\n"
        "                           once, box-resolved (default none)\n"
        "  --filter F               box|tent|gaussian|mitchell, the SSAA reconstruction\n"
        "                           filter (default box)\n"
        "  --rasterizer R           halfspace|scanline|barycentric (default halfspace;\n"
        "                           all three give the same pixels)\n"
        "  --threads N              rasterizer threads (default: SR_THREADS or CPUs)\n"
        "  --detail N               teapot tessellation per patch, 1..64 (default 12)\n"
        "  -v, --verbose            print timings and counts to stderr\n"
        "  -h, --help               this help\n"
        "\n"
        "Exit status: 0 on success, 2 for bad options or a bad model file (one line\n"
        "FILE:LINE: what is wrong), 1 when rendering or writing fails.\n");
}

static bool camera_kv(void *user, const char *opt, const char *key, const char *value)
{
    render_opts *o = user;
    if (strcmp(key, "eye") == 0) {
        o->have_eye = true;
        return parse_vec3(opt, value, &o->eye);
    }
    if (strcmp(key, "target") == 0) {
        o->have_target = true;
        return parse_vec3(opt, value, &o->target);
    }
    if (strcmp(key, "up") == 0) {
        o->have_up = true;
        return parse_vec3(opt, value, &o->up);
    }
    cli_error("%s: unknown key '%s' (expected eye, target, up)", opt, key);
    return false;
}

static bool light_kv(void *user, const char *opt, const char *key, const char *value)
{
    sr_light *l = user;
    if (strcmp(key, "dir") == 0 || strcmp(key, "point") == 0) {
        if (l->type != SR_LIGHT_OFF) {
            cli_error("%s: give either dir= or point=, once", opt);
            return false;
        }
        l->type = key[0] == 'd' ? SR_LIGHT_DIRECTIONAL : SR_LIGHT_POINT;
        if (!parse_vec3(opt, value, &l->vector)) {
            return false;
        }
        if (l->type == SR_LIGHT_DIRECTIONAL && sr_vec3_length(l->vector) == 0.0f) {
            cli_error("%s: a light direction must not be zero", opt);
            return false;
        }
        return true;
    }
    if (strcmp(key, "color") == 0) {
        return parse_color(opt, value, &l->color);
    }
    if (strcmp(key, "intensity") == 0) {
        return parse_float(opt, value, 0.0f, 1000.0f, &l->intensity);
    }
    cli_error("%s: unknown key '%s' (expected dir, point, color, intensity)", opt, key);
    return false;
}

static bool material_kv(void *user, const char *opt, const char *key, const char *value)
{
    render_opts *o = user;
    if (strcmp(key, "color") == 0) {
        o->have_mat_color = true;
        return parse_color(opt, value, &o->mat_color);
    }
    if (strcmp(key, "specular") == 0) {
        o->have_specular = true;
        return parse_color(opt, value, &o->specular);
    }
    if (strcmp(key, "shininess") == 0) {
        o->have_shininess = true;
        return parse_float(opt, value, 1.0f, 10000.0f, &o->shininess);
    }
    cli_error("%s: unknown key '%s' (expected color, specular, shininess)", opt, key);
    return false;
}

/* Returns -1 to continue, else the exit status. */
static int parse_args(int argc, char **argv, render_opts *o)
{
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        char optbuf[64];
        const char *value = NULL;
        /* --opt=value as well as --opt value. */
        const char *eq = strncmp(arg, "--", 2) == 0 ? strchr(arg, '=') : NULL;
        if (eq && (size_t)(eq - arg) < sizeof optbuf) {
            memcpy(optbuf, arg, (size_t)(eq - arg));
            optbuf[eq - arg] = 0;
            value = eq + 1;
            arg = optbuf;
        }
#define IS(name) (strcmp(arg, name) == 0)
#define VALUE()                                                                     \
    do {                                                                            \
        if (!value) {                                                               \
            if (i + 1 >= argc) {                                                    \
                cli_error("%s: missing value", arg);                                \
                return EXIT_USAGE;                                                  \
            }                                                                       \
            value = argv[++i];                                                      \
        }                                                                           \
        if (!*value) {                                                              \
            cli_error("%s: empty value", arg);                                      \
            return EXIT_USAGE;                                                      \
        }                                                                           \
    } while (0)
#define CHOICE(names, dst, values)                                                  \
    do {                                                                            \
        int k_;                                                                     \
        VALUE();                                                                    \
        if (!parse_choice(arg, value, names, &k_)) {                                \
            return EXIT_USAGE;                                                      \
        }                                                                           \
        dst = values;                                                               \
    } while (0)

        if ((IS("-h") || IS("--help") || IS("-v") || IS("--verbose")) && value) {
            cli_error("%s: takes no value", arg);
            return EXIT_USAGE;
        }
        if (IS("-h") || IS("--help")) {
            render_help();
            return EXIT_OK;
        } else if (IS("-o") || IS("--output")) {
            VALUE();
            o->output = value;
        } else if (IS("--size")) {
            VALUE();
            if (!parse_size(arg, value, &o->width, &o->height)) {
                return EXIT_USAGE;
            }
        } else if (IS("--shading")) {
            CHOICE(shading_names, o->shading, shading_values[k_]);
        } else if (IS("--cull")) {
            CHOICE(cull_names, o->cull, cull_values[k_]);
        } else if (IS("--front-face")) {
            CHOICE(front_names, o->front, k_ == 0 ? SR_FRONT_CCW : SR_FRONT_CW);
        } else if (IS("--depth-format")) {
            CHOICE(depth_format_names, o->depth_format, depth_format_values[k_]);
        } else if (IS("--depth-func")) {
            CHOICE(depth_func_names, o->depth_func, (sr_depth_func)(SR_NEVER + k_));
        } else if (IS("--projection-interp")) {
            CHOICE(interp_names, o->interp, k_ == 0 ? SR_INTERP_PERSPECTIVE : SR_INTERP_AFFINE);
        } else if (IS("--normals")) {
            CHOICE(normals_names, o->normals, k_);
        } else if (IS("--rasterizer")) {
            CHOICE(raster_names, o->rasterizer, (sr_rasterizer)(SR_RASTER_HALFSPACE + k_));
        } else if (IS("--camera")) {
            VALUE();
            if (!parse_kv_list(arg, value, camera_kv, o)) {
                return EXIT_USAGE;
            }
            if (!o->have_eye) {
                cli_error("%s: eye=X,Y,Z is required", arg);
                return EXIT_USAGE;
            }
        } else if (IS("--fov")) {
            VALUE();
            if (!parse_float(arg, value, 1.0f, 170.0f, &o->fov_deg)) {
                return EXIT_USAGE;
            }
        } else if (IS("--wireframe") || IS("--hidden-line") || IS("--edges") || IS("--points")) {
            if (value) {
                cli_error("%s: takes no value", arg);
                return EXIT_USAGE;
            }
            o->lines = IS("--wireframe") ? LINES_WIREFRAME : IS("--hidden-line") ? LINES_HIDDEN
                     : IS("--edges") ? LINES_EDGES : LINES_POINTS;
        } else if (IS("--opacity")) {
            VALUE();
            if (!parse_float(arg, value, 0.0f, 1.0f, &o->opacity)) {
                return EXIT_USAGE;
            }
        } else if (IS("--aa")) {
            int aa;
            CHOICE(aa_names, aa, k_);
            o->ssaa = aa_ssaa[aa];
            o->msaa = aa_msaa[aa];
        } else if (IS("--filter")) {
            CHOICE(resample_names, o->filter, (sr_resample_filter)(SR_RESAMPLE_BOX + k_));
        } else if (IS("--texture")) {
            VALUE();
            o->texture = value;
        } else if (IS("--texture-filter")) {
            CHOICE(filter_names, o->texture_filter, (sr_texture_filter)(SR_FILTER_NEAREST + k_));
        } else if (IS("--wrap")) {
            CHOICE(wrap_names, o->wrap, (sr_texture_wrap)(SR_WRAP_REPEAT + k_));
        } else if (IS("--texture-srgb")) {
            if (value) {
                cli_error("%s: takes no value", arg);
                return EXIT_USAGE;
            }
            o->texture_srgb = true;
        } else if (IS("--smooth")) {
            if (value) {
                cli_error("%s: takes no value", arg);
                return EXIT_USAGE;
            }
            o->smooth = true;
        } else if (IS("--line-width") || IS("--point-size")) {
            VALUE();
            if (!parse_float(arg, value, 1.0f, 64.0f,
                             IS("--line-width") ? &o->line_width : &o->point_size)) {
                return EXIT_USAGE;
            }
        } else if (IS("--polygon-offset")) {
            VALUE();
            int n = 0;
            if (sscanf(value, "%f,%f%n", &o->offset_factor, &o->offset_units, &n) != 2 ||
                value[n] != 0 || !isfinite(o->offset_factor) || !isfinite(o->offset_units) ||
                fabsf(o->offset_factor) > 1e6f || fabsf(o->offset_units) > 1e6f) {
                cli_error("%s: expected FACTOR,UNITS, two numbers (got '%s')", arg, value);
                return EXIT_USAGE;
            }
        } else if (IS("--line-color")) {
            VALUE();
            o->have_line_color = true;
            if (!parse_color(arg, value, &o->line_color)) {
                return EXIT_USAGE;
            }
        } else if (IS("--ortho")) {
            if (value) {
                cli_error("%s: takes no value", arg);
                return EXIT_USAGE;
            }
            o->ortho = true;
        } else if (IS("--turn")) {
            VALUE();
            if (!parse_float(arg, value, -36000.0f, 36000.0f, &o->turn_deg)) {
                return EXIT_USAGE;
            }
        } else if (IS("--near") || IS("--far")) {
            VALUE();
            float *dst = IS("--near") ? &o->near_z : &o->far_z;
            if (!parse_float(arg, value, 1e-6f, 1e9f, dst)) {
                return EXIT_USAGE;
            }
        } else if (IS("--light")) {
            VALUE();
            if (o->light_count == SR_MAX_LIGHTS) {
                cli_error("%s: at most %d lights", arg, SR_MAX_LIGHTS);
                return EXIT_USAGE;
            }
            sr_light *l = &o->lights[o->light_count];
            if (!parse_kv_list(arg, value, light_kv, l)) {
                return EXIT_USAGE;
            }
            if (l->type == SR_LIGHT_OFF) {
                cli_error("%s: needs dir=X,Y,Z or point=X,Y,Z", arg);
                return EXIT_USAGE;
            }
            o->light_count++;
        } else if (IS("--ambient")) {
            VALUE();
            o->have_ambient = true;
            if (!parse_color(arg, value, &o->ambient)) {
                return EXIT_USAGE;
            }
        } else if (IS("--material")) {
            VALUE();
            if (!parse_kv_list(arg, value, material_kv, o)) {
                return EXIT_USAGE;
            }
        } else if (IS("--background")) {
            VALUE();
            if (!parse_color(arg, value, &o->background)) {
                return EXIT_USAGE;
            }
        } else if (IS("--png-level")) {
            VALUE();
            if (!parse_int(arg, value, 0, 9, &o->png_level)) {
                return EXIT_USAGE;
            }
        } else if (IS("--jpeg-quality")) {
            VALUE();
            if (!parse_int(arg, value, 1, 100, &o->jpeg_quality)) {
                return EXIT_USAGE;
            }
        } else if (IS("--threads")) {
            VALUE();
            if (!parse_int(arg, value, 1, 64, &o->threads)) {
                return EXIT_USAGE;
            }
        } else if (IS("--detail")) {
            VALUE();
            if (!parse_int(arg, value, 1, 64, &o->detail)) {
                return EXIT_USAGE;
            }
        } else if (IS("-v") || IS("--verbose")) {
            o->verbose = true;
        } else if (arg[0] == '-' && arg[1] != 0) {
            cli_error("%s: unknown option '%s' (try 'softrast %s --help')", argv[0], arg, argv[0]);
            return EXIT_USAGE;
        } else if (!*arg) {
            cli_error("%s: the model's file name is empty", argv[0]);
            return EXIT_USAGE;
        } else if (!o->model) {
            o->model = arg;
        } else {
            cli_error("%s: more than one model given ('%s' and '%s')", argv[0], o->model, arg);
            return EXIT_USAGE;
        }
#undef IS
#undef VALUE
#undef CHOICE
    }
    if (o->near_z > 0 && o->far_z > 0 && o->near_z >= o->far_z) {
        cli_error("--near %g must be less than --far %g", (double)o->near_z, (double)o->far_z);
        return EXIT_USAGE;
    }
    return -1;
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static int load_model(const render_opts *o, scene *s)
{
    memset(s, 0, sizeof *s);
    scene_object *ob = &s->objects[0];
    sr_io_error err;
    sr_result r = sr_load_mesh(o->model, NULL, &ob->mesh, &err);
    if (r != SR_OK) {
        fprintf(stderr, "%s\n", err.message);
        return r == SR_OUT_OF_MEMORY ? EXIT_FAILURE_RUN : EXIT_USAGE;
    }
    s->count = 1;
    ob->model = sr_mat4_identity();
    ob->frame = true;
    ob->material = (sr_material){ .diffuse = { 0.72f, 0.72f, 0.74f },
                                  .specular = { 0.25f, 0.25f, 0.25f }, .shininess = 40.0f };
    return -1;
}

/* --normals: the file's, smooth or flat.  Flat shading needs none. */
static int prepare_normals(const render_opts *o, sr_context *ctx, scene *s)
{
    for (int i = 0; i < s->count; i++) {
        sr_mesh *m = &s->objects[i].mesh;
        int mode = o->normals;
        if (mode == 0 && !m->normals && o->model && i == 0) {
            cli_error("%s: --normals file: the model has no normals (use smooth or flat)", o->model);
            return EXIT_USAGE;
        }
        if (mode == -1) {
            mode = m->normals ? 0 : 1;
        }
        if (mode == 0) {
            continue;
        }
        sr_result r = sr_mesh_compute_normals_ctx(ctx, m,
                                                  mode == 2 ? SR_NORMALS_FLAT : SR_NORMALS_SMOOTH);
        if (r != SR_OK) {
            cli_error("computing normals: %s", sr_result_text(r));
            return EXIT_FAILURE_RUN;
        }
    }
    return -1;
}

typedef struct camera {
    sr_mat4 view, proj;
    sr_camera_basis basis;
} camera;

/* The eye, target and up the options ask for: --camera, else the default
 * framing of the objects' bounding sphere. */
static void resolve_camera(const render_opts *o, const scene *s, sr_vec3 *eye, sr_vec3 *target,
                           sr_vec3 *up)
{
    sr_vec3 c;
    float r;
    scene_bounds(s, true, &c, &r);
    *target = o->have_target ? o->target : c;
    *up = o->have_up ? o->up : (sr_vec3){ 0, 1, 0 };
    *eye = o->have_eye ? o->eye : framing_default_eye(c, r, o->fov_deg * PI_F / 180.0f);
}

static bool finite_mat(const sr_mat4 *m)
{
    for (int i = 0; i < 16; i++) {
        if (!isfinite(m->m[i])) {
            return false;
        }
    }
    return true;
}

/* The camera the options and the scene ask for.  NULL, or why there is
 * none (a message naming --camera when the options are at fault): eye and
 * target in one point, or sizes or distances whose squares overflow
 * float (from about 1e19) or underflow it (below about 1e-19) - the
 * readers accept such coordinates, the framing cannot use them. */
static const char *setup_camera(const render_opts *o, const scene *s, camera *cam,
                                float *near_out, float *far_out)
{
    sr_vec3 c;
    float r;
    scene_bounds(s, true, &c, &r);
    float fov = o->fov_deg * PI_F / 180.0f;

    sr_vec3 eye, target, up;
    resolve_camera(o, s, &eye, &target, &up);
    sr_vec3 gaze = sr_vec3_sub(target, eye);
    /* Looking straight along the up vector: pick another up; one of the
     * last two is never parallel to a gaze. */
    const sr_vec3 ups[3] = { up, { 0, 0, -1 }, { 1, 0, 0 } };
    bool framed = false;
    for (int i = 0; i < 3 && !framed; i++) {
        framed = sr_camera_frame(eye, gaze, ups[i], &cam->basis);
    }
    bool user = o->have_eye || o->have_target;
    const char *range = user ? "--camera: the eye, the target or the model lies beyond the range "
                               "the framing can use (sizes and distances of about 1e-18 to 1e18)"
                             : "the model lies beyond the range the framing can use (sizes and "
                               "distances of about 1e-18 to 1e18)";
    if (!framed) {
        bool same = gaze.x == 0.0f && gaze.y == 0.0f && gaze.z == 0.0f;
        return same && user ? "--camera: eye and target are the same point" : range;
    }
    cam->view = sr_camera_matrix(&cam->basis);

    /* Near and far from every object's sphere, so the ground is kept. */
    sr_vec3 ca;
    float ra;
    scene_bounds(s, false, &ca, &ra);
    float near_z, far_z;
    framing_near_far(eye, ca, ra, &near_z, &far_z);
    far_z = o->far_z > 0 ? o->far_z : far_z;
    near_z = o->near_z > 0 ? o->near_z : near_z;
    if (near_z >= far_z) {
        far_z = near_z * 2.0f;
    }
    float aspect = (float)o->width / (float)o->height;
    if (o->ortho) {
        float half = r * 1.04f;
        float hw = aspect >= 1.0f ? half * aspect : half;
        float hh = aspect >= 1.0f ? half : half / aspect;
        cam->proj = sr_ortho(-hw, hw, -hh, hh, near_z, far_z, false);
    } else {
        cam->proj = sr_perspective(sr_fit_fovy(fov, o->width, o->height), aspect, near_z, far_z, false);
    }
    *near_out = near_z;
    *far_out = far_z;
    if (!(near_z > 0.0f) || !isfinite(far_z) || !(far_z > near_z) || !finite_mat(&cam->view) ||
        !finite_mat(&cam->proj)) {
        return range;
    }
    return NULL;
}

static bool is_file(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* Whether two paths name one existing file (links and ./ included): the
 * atomic write of the output would replace an input that is the same. */
static bool same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev &&
           sa.st_ino == sb.st_ino;
}

/* Decoded pixels px (freed here) into *out on ctx, for both texture
 * loaders; a failure names `name`.  Returns an exit status, or -1. */
static int upload_texture(const render_opts *o, sr_context *ctx, const char *name, int w, int h,
                          uint8_t *px, sr_texture **out)
{
    sr_result r = sr_make_texture(ctx, &(sr_texture_desc){ .width = w, .height = h, .pixels = px,
                                                            .srgb = o->texture_srgb },
                                  out);
    free(px);
    if (r != SR_OK) {
        cli_error("%s: %s", name, sr_context_error(ctx));
        return r == SR_OUT_OF_MEMORY ? EXIT_FAILURE_RUN : EXIT_USAGE;
    }
    return -1;
}

/* Whether the texture file `path` is -o's output, which the atomic write
 * would replace (an error, reported here). */
static bool texture_is_output(const render_opts *o, const char *path)
{
    if (path && o->writes_output && same_file(path, o->output)) {
        cli_error("-o: '%s' is the texture being read (%s); choose another output file",
                  o->output, path);
        return true;
    }
    return false;
}

/* A texture into *out, for both texture loaders: the image file `path`,
 * or else the encoded bytes data[0 .. size) a model embeds, `name` in
 * messages.  One that cannot be read is a warning when `optional` (the
 * model brought it: "drawing `what`" says what goes on without it, *out
 * stays NULL), else an error.  Returns an exit status, or -1. */
static int read_texture(const render_opts *o, sr_context *ctx, const char *path,
                        const uint8_t *data, size_t size, const char *name, bool optional,
                        const char *what, sr_texture **out)
{
    int w, h;
    uint8_t *px = NULL;
    sr_io_error err;
    sr_result rr = path ? sr_read_image(path, &w, &h, &px, &err)
                        : sr_decode_image(name, data, size, &w, &h, &px, &err);
    if (rr != SR_OK) {
        if (optional && rr != SR_OUT_OF_MEMORY) {
            cli_error("warning: %s (drawing %s)", err.message, what);
            return -1;
        }
        fprintf(stderr, "%s\n", err.message);
        return rr == SR_OUT_OF_MEMORY ? EXIT_FAILURE_RUN : EXIT_USAGE;
    }
    return upload_texture(o, ctx, path ? path : name, w, h, px, out);
}

/* Whether parts a and b take one image: the same file, or the same
 * embedded bytes (each part holds its own copy). */
static bool same_part_texture(const sr_mesh_part *a, const sr_mesh_part *b)
{
    if (a->texture_path || b->texture_path) {
        return a->texture_path && b->texture_path && strcmp(a->texture_path, b->texture_path) == 0;
    }
    return a->texture_size == b->texture_size &&
           memcmp(a->texture_data, b->texture_data, a->texture_size) == 0;
}

/* The textures of a model whose parts take different ones (sr_mesh.parts):
 * each image read or decoded once; one that is missing or unreadable is a
 * warning, and its parts are drawn without it.  Returns an exit status, or
 * -1. */
static int load_part_textures(const render_opts *o, sr_context *ctx, scene_object *ob)
{
    size_t n = ob->mesh.part_count;
    ob->part_textures = calloc(n, sizeof *ob->part_textures);
    ob->owned = calloc(n, sizeof *ob->owned);
    /* The images met so far, by the first part that takes each, with its
     * texture (NULL when unreadable): parts far outnumber images in a
     * model that switches back and forth. */
    const sr_mesh_part **seen = calloc(n, sizeof *seen);
    if (!ob->part_textures || !ob->owned || !seen) {
        free(seen);
        cli_error("render: out of memory");
        return EXIT_FAILURE_RUN;
    }
    int status = -1;
    for (size_t p = 0; p < n && status < 0; p++) {
        const sr_mesh_part *part = &ob->mesh.parts[p];
        const char *path = part->texture_path;
        bool textured = path || part->texture_data;
        size_t k = 0;
        while (textured && k < ob->owned_count && !same_part_texture(seen[k], part)) {
            k++;
        }
        if (!textured || k < ob->owned_count) {
            ob->part_textures[p] = textured ? ob->owned[k] : NULL;
            continue;
        }
        seen[k] = part;
        ob->owned_count++;
        if (texture_is_output(o, path)) {
            status = EXIT_USAGE;
            break;
        }
        char name[4200];
        snprintf(name, sizeof name, "%s (its embedded texture of part %zu)", o->model, p + 1);
        status = read_texture(o, ctx, path, part->texture_data, part->texture_size, name, true,
                              "its part of the model without it", &ob->owned[k]);
        ob->part_textures[p] = ob->owned[k];
    }
    free(seen);
    return status;
}

/* The model's texture: --texture, else the file's own (OBJ map_Kd, or an
 * image a glTF or GLB file embeds), else MODEL_texture.png or .jpg beside
 * MODEL.ext.  One the user named must be read; one the model brings that
 * is missing or unreadable is reported in a warning and the model drawn
 * without it - a preview of the geometry beats no preview.  Returns an
 * exit status, or -1. */
static int load_texture(const render_opts *o, sr_context *ctx, scene *s)
{
    if (!o->model || s->count == 0) {
        if (o->texture) {
            cli_error("--texture: the built-in scene has no texture coordinates");
            return EXIT_USAGE;
        }
        return -1;
    }
    scene_object *ob = &s->objects[0];
    if (!o->texture && ob->mesh.part_count > 0 && ob->mesh.texcoords) {
        return load_part_textures(o, ctx, ob);
    }
    char guess[4096];
    const char *path = o->texture;
    const char *named = ob->mesh.texture_path;
    bool embedded = !path && ob->mesh.texture_data;
    if (!path && !embedded && named && is_file(named)) {
        path = named;
    }
    if (!path && !embedded) {
        const char *dot = strrchr(o->model, '.'), *slash = strrchr(o->model, '/');
        size_t stem = dot && (!slash || dot > slash) ? (size_t)(dot - o->model) : strlen(o->model);
        static const char *const suffixes[] = { "_texture.png", "_texture.jpg" };
        for (size_t i = 0; i < 2 && !path; i++) {
            if (stem + strlen(suffixes[i]) < sizeof guess) {
                memcpy(guess, o->model, stem);
                strcpy(guess + stem, suffixes[i]);
                path = is_file(guess) ? guess : NULL;
            }
        }
    }
    if (!path && !embedded) {
        if (named && ob->mesh.texcoords) {
            struct stat st;
            cli_error("warning: %s: %s, named by the model's material (drawing the model "
                      "without its texture)", named,
                      stat(named, &st) != 0 ? strerror(errno) : "not a regular file");
        }
        return -1;
    }
    if (texture_is_output(o, path)) {
        return EXIT_USAGE;
    }
    if (!ob->mesh.texcoords) {
        if (o->texture) {
            cli_error("--texture: %s has no texture coordinates", o->model);
            return EXIT_USAGE;
        }
        return -1; /* a texture found by name but nothing to map it with */
    }
    char name[4200];
    snprintf(name, sizeof name, "%s (its embedded texture)", o->model);
    return read_texture(o, ctx, embedded ? NULL : path, ob->mesh.texture_data,
                        ob->mesh.texture_size, name, !o->texture, "the model without its texture",
                        &ob->texture);
}

static void free_textures(sr_context *ctx, scene *s)
{
    for (int i = 0; i < s->count; i++) {
        scene_object *ob = &s->objects[i];
        sr_destroy_texture(ctx, ob->texture);
        ob->texture = NULL;
        for (size_t k = 0; k < ob->owned_count; k++) {
            sr_destroy_texture(ctx, ob->owned[k]);
        }
        free(ob->owned);
        free(ob->part_textures);
        ob->owned = NULL;
        ob->part_textures = NULL;
        ob->owned_count = 0;
    }
}

static bool translucent(const scene_object *ob)
{
    return ob->material.opacity > 0.0f && ob->material.opacity < 1.0f;
}

typedef struct depth_key {
    float depth;
    uint32_t tri;
} depth_key;

static int farther_first(const void *a, const void *b)
{
    const depth_key *x = a, *y = b;
    if (x->depth != y->depth) {
        return x->depth > y->depth ? -1 : 1;
    }
    return x->tri < y->tri ? -1 : x->tri > y->tri;
}

/* A translucent object's triangles [first, first + n) as indices sorted
 * back to front by each triangle's centroid distance along the view
 * direction (blending is order-dependent, so transparency needs sorting);
 * malloc'd, or NULL when out of memory. */
static uint32_t *sorted_indices(const scene_object *ob, const camera *cam, size_t first,
                                size_t n)
{
    const uint32_t *indices = ob->mesh.indices + 3 * first;
    depth_key *keys = malloc(n * sizeof *keys);
    uint32_t *out = malloc(n * 3 * sizeof *out);
    if (!keys || !out) {
        free(keys);
        free(out);
        return NULL;
    }
    sr_mat4 mv = sr_mat4_mul(&cam->view, &ob->model);
    for (size_t t = 0; t < n; t++) {
        float z = 0.0f;
        for (int k = 0; k < 3; k++) {
            const float *p = &ob->mesh.positions[indices[t * 3 + k] * 3];
            z += mv.m[2] * p[0] + mv.m[6] * p[1] + mv.m[10] * p[2] + mv.m[14];
        }
        keys[t] = (depth_key){ -z, (uint32_t)t };   /* eye looks down -z: distance is -z */
    }
    qsort(keys, n, sizeof *keys, farther_first);
    for (size_t t = 0; t < n; t++) {
        memcpy(&out[t * 3], &indices[keys[t].tri * 3], 3 * sizeof *out);
    }
    free(keys);
    return out;
}

/* Opaque objects first, then translucent ones back to front with
 * source-over blending and no depth writes (they still test against the
 * opaque depth). */
static sr_result draw_scene(sr_context *ctx, sr_framebuffer *fb, sr_state *state, scene *s,
                            const camera *cam, bool keep_material, uint64_t *tris,
                            uint64_t *frags)
{
    sr_result r = SR_OK;
    for (int pass = 0; pass < 2 && r == SR_OK; pass++) {
        for (int i = 0; i < s->count && r == SR_OK; i++) {
            scene_object *ob = &s->objects[i];
            bool see_through = !keep_material && translucent(ob);
            if (see_through != (pass == 1)) {
                continue;
            }
            /* The texture colors the surface, not the line modes' plain
             * passes; a mesh whose parts take different textures is drawn
             * part by part (a translucent one sorted within each part). */
            bool by_part = !keep_material && ob->part_textures;
            size_t parts = by_part ? ob->mesh.part_count : 1;
            for (size_t p = 0; p < parts && r == SR_OK; p++) {
                size_t first = by_part ? ob->mesh.parts[p].first_triangle : 0;
                size_t count = by_part ? ob->mesh.parts[p].triangle_count
                                       : ob->mesh.triangle_count;
                sr_state st = *state;
                if (!keep_material) {
                    st.material = ob->material;
                }
                st.texture = keep_material ? NULL : by_part ? ob->part_textures[p] : ob->texture;
                const uint32_t *indices = ob->mesh.indices + 3 * first;
                uint32_t *sorted = NULL;
                if (see_through) {
                    sorted = sorted_indices(ob, cam, first, count);
                    if (!sorted) {
                        return SR_OUT_OF_MEMORY;
                    }
                    indices = sorted;
                    st.no_depth_write = true;
                    st.blend = (sr_blend){ .enabled = true, .src_rgb = SR_BLEND_SRC_ALPHA,
                                           .dst_rgb = SR_BLEND_ONE_MINUS_SRC_ALPHA,
                                           .src_alpha = SR_BLEND_ONE,
                                           .dst_alpha = SR_BLEND_ONE_MINUS_SRC_ALPHA };
                }
                r = sr_draw(ctx, fb, &st, &(sr_draw_desc){
                    .positions = ob->mesh.positions, .normals = ob->mesh.normals,
                    .colors = ob->mesh.colors, .color_size = 4,
                    .texcoords = ob->mesh.texcoords, .vertex_count = ob->mesh.vertex_count,
                    .indices = indices, .index_type = SR_INDEX_U32, .index_count = count * 3,
                    .model = &ob->model, .view = &cam->view, .projection = &cam->proj });
                free(sorted);
                sr_draw_info info = sr_last_draw_info(ctx);
                *tris += info.triangles_in;
                *frags += info.fragments;
            }
        }
    }
    return r;
}

/* The passes of each mode.  Hidden-line, edges and points first fill the
 * depth buffer with the model pushed back by polygon offset (factor 1,
 * units 1 unless --polygon-offset says otherwise), so lines on its surface win the LEQUAL test without stitching
 * or z-fighting; hidden-line and points fill with the background color. */
static sr_result draw_passes(const render_opts *o, sr_context *ctx, sr_framebuffer *fb,
                             const sr_state *base, scene *s, const camera *cam, uint64_t *tris,
                             uint64_t *frags)
{
    sr_state st = *base;
    if (o->lines == LINES_NONE) {
        return draw_scene(ctx, fb, &st, s, cam, false, tris, frags);
    }
    bool light_bg = o->background.x + o->background.y + o->background.z > 1.5f;
    sr_vec3 ink = o->have_line_color ? o->line_color
                : light_bg ? (sr_vec3){ 0.125f, 0.125f, 0.125f }
                           : (sr_vec3){ 0.91f, 0.925f, 0.957f };
    sr_material ink_material = { .diffuse = ink, .no_vertex_color = true };
    sr_result r = SR_OK;
    if (o->lines != LINES_WIREFRAME) {
        sr_state fill = st;
        fill.offset = (sr_polygon_offset){ .factor = o->offset_factor,
                                           .units = o->offset_units, .fill = true };
        if (o->lines == LINES_EDGES) {
            r = draw_scene(ctx, fb, &fill, s, cam, false, tris, frags);
        } else {
            fill.shading = SR_SHADING_UNLIT;
            fill.material = (sr_material){ .diffuse = o->background, .no_vertex_color = true };
            r = draw_scene(ctx, fb, &fill, s, cam, true, tris, frags);
        }
    }
    if (r != SR_OK) {
        return r;
    }
    sr_state lines = st;
    lines.shading = SR_SHADING_UNLIT;
    lines.material = ink_material;
    /* Supersampled, lines and points keep their width in output pixels. */
    lines.line_width = o->line_width * (float)o->ssaa;
    lines.point_size = o->point_size * (float)o->ssaa;
    lines.smooth_lines = lines.smooth_points = o->smooth;
    sr_polygon_mode mode = o->lines == LINES_POINTS ? SR_POLYGON_POINT : SR_POLYGON_LINE;
    lines.polygon_mode_front = lines.polygon_mode_back = mode;
    if (o->lines == LINES_WIREFRAME) {
        lines.cull = SR_CULL_NONE;
        lines.no_depth_test = true;
        lines.no_depth_write = true;
    } else {
        lines.depth_func = SR_LEQUAL;
    }
    return draw_scene(ctx, fb, &lines, s, cam, true, tris, frags);
}

/* ---- render jobs: what `softrast render` and `softrast view` share ------- */

struct render_job {
    render_opts o;
    scene s;
    bool have_scene;
    sr_context *ctx;
    sr_framebuffer *work;   /* the supersampled image (or one with the requested depth
                             * format) when the caller's framebuffer cannot be drawn into */
    char error[512];
};

static render_opts default_opts(void)
{
    return (render_opts){
        .output = "softrast.png", .width = 1280, .height = 720, .shading = SR_SHADING_PHONG,
        .cull = SR_CULL_BACK, .front = SR_FRONT_CCW, .fov_deg = FRAMING_FOV_DEG,
        .background = { 0x1d / 255.0f, 0x22 / 255.0f, 0x30 / 255.0f },
        .depth_format = SR_DEPTH_D24, .depth_func = SR_LESS, .interp = SR_INTERP_PERSPECTIVE,
        .normals = -1, .detail = 12, .rasterizer = SR_RASTER_HALFSPACE, .png_level = -1,
        .line_width = 1.0f, .point_size = 3.0f, .ssaa = 1, .msaa = 1, .opacity = 1.0f,
        .offset_factor = 1.0f, .offset_units = 1.0f,
    };
}

int render_job_parse(int argc, char **argv, render_job **out)
{
    *out = NULL;
    render_job *job = calloc(1, sizeof *job);
    if (!job) {
        cli_error("out of memory");
        return EXIT_FAILURE_RUN;
    }
    job->o = default_opts();
    int status = parse_args(argc, argv, &job->o);
    if (status >= 0) {
        free(job);
        return status;
    }
    *out = job;
    return -1;
}

/* The context, unless made already (cmd_render makes it first). */
static int start_context(render_job *job)
{
    if (job->ctx) {
        return -1;
    }
    sr_result r = sr_make_context(&(sr_context_desc){ .threads = job->o.threads }, &job->ctx);
    if (r != SR_OK) {
        cli_error("render: %s", sr_result_text(r));
        return EXIT_FAILURE_RUN;
    }
    return -1;
}

/* The context and the textures that live on it. */
static int make_context(render_job *job)
{
    int status = start_context(job);
    if (status >= 0) {
        return status;
    }
    return load_texture(&job->o, job->ctx, &job->s);
}

static void drop_context(render_job *job)
{
    if (job->ctx) {
        free_textures(job->ctx, &job->s);
        sr_destroy_framebuffer(job->ctx, job->work);
        sr_destroy_context(job->ctx);
    }
    job->work = NULL;
    job->ctx = NULL;
}

/* The first part of render_job_load, which needs no context: the model
 * file read, or the built-in scene made. */
static int load_objects(render_job *job)
{
    render_opts *o = &job->o;
    scene *s = &job->s;
    if (o->model) {
        int status = load_model(o, s);
        if (status >= 0) {
            return status;
        }
    } else {
        sr_result r = scene_builtin(s, o->detail);
        if (r != SR_OK) {
            cli_error("building the teapot scene: %s", sr_result_text(r));
            return EXIT_FAILURE_RUN;
        }
    }
    job->have_scene = true;
    return -1;
}

/* The rest of the scene, with the context's threads for the normals:
 * materials, turn, bounds, and a check that a camera can be made. */
static int finish_scene(render_job *job)
{
    render_opts *o = &job->o;
    scene *s = &job->s;
    int status = prepare_normals(o, job->ctx, s);
    if (status >= 0) {
        return status;
    }
    for (int i = 0; i < s->count; i++) {
        scene_object *ob = &s->objects[i];
        if (o->have_mat_color && ob->frame) {
            ob->material.diffuse = o->mat_color;
            ob->material.no_vertex_color = true;
        }
        if (o->have_specular && ob->frame) {
            ob->material.specular = o->specular;
        }
        if (o->have_shininess && ob->frame) {
            ob->material.shininess = o->shininess;
        }
        if (ob->frame && o->opacity < 1.0f) {
            /* Zero means the default (opaque) in sr_material: keep a
             * fully transparent request just above it. */
            ob->material.opacity = o->opacity > 0.0f ? o->opacity : 1e-6f;
        }
    }
    if (o->turn_deg != 0.0f) {
        /* Turn the framed objects about the vertical axis through their
         * bounding sphere's centre. */
        sr_vec3 c;
        float r;
        scene_bounds(s, true, &c, &r);
        sr_mat4 to = sr_mat4_translate(c.x, 0, c.z), from = sr_mat4_translate(-c.x, 0, -c.z);
        sr_mat4 rot = sr_mat4_rotate(o->turn_deg * PI_F / 180.0f, (sr_vec3){ 0, 1, 0 });
        sr_mat4 m = sr_mat4_mul(&rot, &from);
        m = sr_mat4_mul(&to, &m);
        for (int i = 0; i < s->count; i++) {
            if (s->objects[i].frame) {
                s->objects[i].model = sr_mat4_mul(&m, &s->objects[i].model);
            }
        }
    }
    /* The objects and their matrices are final: frame from cached bounds. */
    scene_cache_bounds(s);
    /* A camera that cannot be made is the input's fault: say so now, as a
     * usage error, rather than when drawing. */
    camera cam;
    float near_z, far_z;
    const char *why = setup_camera(o, s, &cam, &near_z, &far_z);
    if (why) {
        if (o->model && why[0] != '-') {   /* not an option's fault: name the file */
            cli_error("%s: %s", o->model, why);
        } else {
            cli_error("%s", why);
        }
        return EXIT_USAGE;
    }
    if ((long)o->width * o->ssaa > SR_MAX_FRAMEBUFFER_SIZE ||
        (long)o->height * o->ssaa > SR_MAX_FRAMEBUFFER_SIZE) {
        cli_error("--aa: ssaa%d at %dx%d needs %ldx%ld samples, more than %d a side", o->ssaa,
                  o->width, o->height, (long)o->width * o->ssaa, (long)o->height * o->ssaa,
                  SR_MAX_FRAMEBUFFER_SIZE);
        return EXIT_USAGE;
    }
    return -1;
}

int render_job_load(render_job *job)
{
    int status = start_context(job);
    if (status < 0) {
        status = load_objects(job);
    }
    if (status < 0) {
        status = finish_scene(job);
    }
    return status >= 0 ? status : make_context(job);
}

int render_job_configure(render_job *job, int argc, char **argv)
{
    render_opts o = default_opts();
    int status = parse_args(argc, argv, &o);
    if (status >= 0) {
        return status;
    }
    bool new_context = job->ctx && o.threads != job->o.threads;
    job->o = o;
    if (new_context) {
        drop_context(job);
        return make_context(job);
    }
    return -1;
}

void render_job_camera(const render_job *job, sr_vec3 *eye, sr_vec3 *target, sr_vec3 *up)
{
    resolve_camera(&job->o, &job->s, eye, target, up);
}

void render_job_bounds(const render_job *job, sr_vec3 *centre, float *radius)
{
    scene_bounds(&job->s, true, centre, radius);
}

float render_job_fov(const render_job *job)
{
    return job->o.fov_deg * PI_F / 180.0f;
}

void render_job_set_camera(render_job *job, sr_vec3 eye, sr_vec3 target, sr_vec3 up)
{
    job->o.have_eye = job->o.have_target = job->o.have_up = true;
    job->o.eye = eye;
    job->o.target = target;
    job->o.up = up;
}

sr_context *render_job_context(const render_job *job)
{
    return job->ctx;
}

sr_depth_format render_job_depth_format(const render_job *job)
{
    return job->o.ssaa > 1 || job->o.msaa > 1 ? SR_DEPTH_NONE : job->o.depth_format;
}

const char *render_job_error(const render_job *job)
{
    return job->error;
}

const char *render_job_model(const render_job *job)
{
    return job->o.model;
}

sr_result render_job_draw(render_job *job, sr_framebuffer *out, render_frame_info *info)
{
    render_opts *o = &job->o;
    sr_context *ctx = job->ctx;
    job->error[0] = 0;
    *info = (render_frame_info){ 0 };
    o->width = sr_framebuffer_width(out);
    o->height = sr_framebuffer_height(out);
    long sw = (long)o->width * o->ssaa, sh = (long)o->height * o->ssaa;
    if (sw > SR_MAX_FRAMEBUFFER_SIZE || sh > SR_MAX_FRAMEBUFFER_SIZE) {
        snprintf(job->error, sizeof job->error,
                 "ssaa%d at %dx%d needs %ldx%ld samples, more than %d a side", o->ssaa,
                 o->width, o->height, sw, sh, SR_MAX_FRAMEBUFFER_SIZE);
        return SR_TOO_LARGE;
    }

    camera cam;
    const char *why = setup_camera(o, &job->s, &cam, &info->near_z, &info->far_z);
    if (why) {
        snprintf(job->error, sizeof job->error, "%s", why);
        return SR_INVALID_ARG;
    }
    sr_state state = {
        .cull = o->cull, .front_face = o->front, .depth_func = o->depth_func,
        .shading = o->shading, .interpolation = o->interp, .rasterizer = o->rasterizer,
        .ambient = o->have_ambient ? o->ambient : (sr_vec3){ 0.12f, 0.12f, 0.14f },
        .two_sided = o->cull == SR_CULL_NONE,
        .texture_filter = o->texture_filter, .wrap_u = o->wrap, .wrap_v = o->wrap,
    };
    if (o->light_count > 0) {
        memcpy(state.lights, o->lights, sizeof o->lights);
    } else {
        framing_default_lights(&cam.basis, state.lights);
    }

    /* SSAA renders k x k samples per output pixel into the work image,
     * then filters them down into `out`; MSAA renders into a multisampled
     * work image of the output's size and resolves it. */
    sr_framebuffer *fb = out;
    sr_result r = SR_OK;
    sr_depth_format want = o->depth_format == SR_DEPTH_DEFAULT ? SR_DEPTH_D24 : o->depth_format;
    if (o->ssaa > 1 || o->msaa > 1 || sr_framebuffer_depth_format(out) != want) {
        if (job->work && (sr_framebuffer_width(job->work) != sw ||
                          sr_framebuffer_height(job->work) != sh ||
                          sr_framebuffer_samples(job->work) != o->msaa ||
                          sr_framebuffer_depth_format(job->work) != want)) {
            sr_destroy_framebuffer(ctx, job->work);
            job->work = NULL;
        }
        if (!job->work) {
            r = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = (int)sw,
                                                                .height = (int)sh,
                                                                .depth_format = want,
                                                                .samples = o->msaa },
                                    &job->work);
        }
        fb = job->work;
    }
    bool clear_to_near = o->depth_func == SR_GREATER || o->depth_func == SR_GEQUAL;
    if (r == SR_OK) {
        r = sr_clear(ctx, fb, &(sr_clear_desc){ .color = { o->background.x, o->background.y,
                                                           o->background.z, 1.0f },
                                                .depth = clear_to_near ? 0.0f : 1.0f });
    }
    if (r == SR_OK) {
        r = draw_passes(o, ctx, fb, &state, &job->s, &cam, &info->triangles, &info->fragments);
    }
    if (r == SR_OK && fb != out) {
        r = o->msaa > 1 ? sr_resolve(ctx, fb, out) : sr_downsample(ctx, fb, out, o->filter);
    }
    if (r != SR_OK) {
        snprintf(job->error, sizeof job->error, "%s", sr_context_error(ctx)[0]
                                                          ? sr_context_error(ctx)
                                                          : sr_result_text(r));
    }
    return r;
}

void render_job_free(render_job *job)
{
    if (!job) {
        return;
    }
    drop_context(job);
    if (job->have_scene) {
        scene_free(&job->s);
    }
    free(job);
}

/* sr_make_framebuffer on a thread of its own (cmd_render). */
typedef struct fb_maker {
    sr_context *ctx;
    sr_framebuffer_desc desc;
    sr_framebuffer *fb;
    sr_result result;
    char error[256];        /* sr_context_error, read before the context is used again */
    pthread_t thread;
} fb_maker;

static void *make_fb(void *arg)
{
    fb_maker *m = arg;
    m->result = sr_make_framebuffer(m->ctx, &m->desc, &m->fb);
    if (m->result != SR_OK) {
        snprintf(m->error, sizeof m->error, "%s", sr_context_error(m->ctx));
    }
    return NULL;
}

int cmd_render(int argc, char **argv)
{
    render_job *job;
    int status = render_job_parse(argc, argv, &job);
    if (status >= 0) {
        return status;
    }
    job->o.writes_output = true;
    const render_opts *o = &job->o;
    struct stat st;
    if (stat(o->output, &st) == 0 && S_ISDIR(st.st_mode)) {
        cli_error("-o: '%s' is a directory", o->output);
        render_job_free(job);
        return EXIT_USAGE;
    }
    if (o->model && same_file(o->model, o->output)) {
        cli_error("-o: '%s' is the model being read; choose another output file", o->output);
        render_job_free(job);
        return EXIT_USAGE;
    }
    bool jpeg = cli_is_jpeg_name(o->output);
    if (jpeg ? o->png_level >= 0 : o->jpeg_quality > 0) {
        cli_error(jpeg ? "--png-level: the output '%s' is a JPEG (see --jpeg-quality)"
                       : "--jpeg-quality: the output '%s' is a PNG (name it .jpg for a JPEG)",
                  o->output);
        render_job_free(job);
        return EXIT_USAGE;
    }

    double t0 = now_ms();
    /* The framebuffer is made on a thread of its own while the model
     * file is read on this one: its fresh pages (16 MB at 1920 x 1080)
     * took the kernel 2-25 ms to zero, time the reader's one core leaves
     * the other free for.  The context is used again only once the
     * framebuffer is made (finish_scene's normals, make_context's
     * textures). */
    status = start_context(job);
    if (status >= 0) {
        render_job_free(job);
        return status;
    }
    fb_maker maker = { .ctx = job->ctx,
                       .desc = { .width = o->width, .height = o->height,
                                 .depth_format = render_job_depth_format(job) } };
    bool threaded = pthread_create(&maker.thread, NULL, make_fb, &maker) == 0;
    if (!threaded) {
        make_fb(&maker);  /* no thread to spare: one after the other */
    }
    status = load_objects(job);
    /* "setup" is the wait for the framebuffer beyond the reading. */
    double t_wait = now_ms();
    if (threaded) {
        pthread_join(maker.thread, NULL);
    }
    double setup_ms = now_ms() - t_wait;
    if (status < 0) {
        status = finish_scene(job);
    }
    if (status < 0) {
        status = make_context(job);
    }
    if (status >= 0) {
        sr_destroy_framebuffer(job->ctx, maker.fb);
        render_job_free(job);
        return status;
    }
    sr_framebuffer *fb = maker.fb;
    sr_result r = maker.result;
    double t_setup = now_ms();
    render_frame_info info = { 0 };
    if (r == SR_OK) {
        r = render_job_draw(job, fb, &info);
    } else {
        snprintf(job->error, sizeof job->error, "%s", maker.error);
    }
    double t_render = now_ms();
    if (r != SR_OK) {
        cli_error("render: %s", render_job_error(job));
        sr_destroy_framebuffer(job->ctx, fb);
        render_job_free(job);
        return EXIT_FAILURE_RUN;
    }

    sr_io_error err;
    r = cli_write_image(o->output, o->width, o->height, sr_framebuffer_pixels(fb),
                        &(cli_image_options){ .png_level = o->png_level,
                                              .jpeg_quality = o->jpeg_quality,
                                              .context = job->ctx },
                        &err);
    double t_write = now_ms();
    if (o->verbose) {
        fprintf(stderr,
                "softrast: %dx%d, %llu triangles, %llu fragments, near %.4g far %.4g, %d threads\n"
                "softrast: load %.1f ms, setup %.1f ms, render %.1f ms, %s %.1f ms\n",
                o->width, o->height, (unsigned long long)info.triangles,
                (unsigned long long)info.fragments, (double)info.near_z, (double)info.far_z,
                sr_context_threads(job->ctx), t_setup - t0 - setup_ms, setup_ms, t_render - t_setup,
                jpeg ? "jpeg" : "png", t_write - t_render);
    }
    sr_destroy_framebuffer(job->ctx, fb);
    render_job_free(job);
    if (r != SR_OK) {
        fprintf(stderr, "%s\n", err.message);
        return EXIT_FAILURE_RUN;
    }
    return EXIT_OK;
}
