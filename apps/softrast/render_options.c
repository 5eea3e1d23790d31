/* render_options.c - the options of `softrast render` (and of the frames
 * `softrast view` draws): --help, and the parser that turns argv into a
 * render_opts, printing one line naming the option when a value is bad. */
#include "cli.h"
#include "framing.h"
#include "render_options.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* "pbr" is the metallic-roughness program; the classic models keep its
 * slot's sr_shading at Phong (per-pixel normals) for what asks. */
static const char *const shading_names[] = { "pbr", "flat", "gouraud", "phong", "normals",
                                             "depth", "unlit", NULL };
static const sr_shading shading_values[] = { SR_SHADING_PHONG, SR_SHADING_FLAT,
                                             SR_SHADING_GOURAUD, SR_SHADING_PHONG,
                                             SR_SHADING_NORMALS, SR_SHADING_DEPTH,
                                             SR_SHADING_UNLIT };
static const char *const tonemap_names[] = { "neutral", "aces", "none", NULL };
static const sr_tonemap_op tonemap_values[] = { SR_TONEMAP_PBR_NEUTRAL, SR_TONEMAP_ACES,
                                                SR_TONEMAP_NONE };
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
static const char *const clipper_names[] = { "homogeneous", "view-volume", NULL };
static const char *const filter_names[] = { "nearest", "bilinear", "trilinear", NULL };
static const char *const aa_names[] = { "none", "ssaa2", "ssaa3", "ssaa4", "msaa2", "msaa4",
                                         "msaa8", "msaa16", NULL };
static const int aa_ssaa[] = { 1, 2, 3, 4, 1, 1, 1, 1 };
static const int aa_msaa[] = { 1, 1, 1, 1, 2, 4, 8, 16 };
static const char *const resample_names[] = { "box", "tent", "gaussian", "mitchell", NULL };
static const char *const up_names[] = { "+x", "-x", "+y", "-y", "+z", "-z", NULL };
static const char *const switch_names[] = { "on", "off", NULL };
static const char *const lights_names[] = { "file", "default", "both", "auto", NULL };
static const int lights_values[] = { LIGHTS_FILE, LIGHTS_DEFAULT, LIGHTS_BOTH, LIGHTS_AUTO };
static const char *const wrap_names[] = { "repeat", "clamp", "mirror", NULL };
/* What only pbr's program reads: the classic models draw without them. */
static const char *const pbr_only[] = { "--tonemap", "--exposure", "--environment",
                                        "--environment-intensity", "--shadows", "--ground",
                                        "--lights", NULL };

/* The options that take a value: the parser takes the next argument as
 * it whatever it looks like ("-o --" takes "--" as the output's name, as
 * getopt would), and the commands that pass render options on (a batch,
 * the viewer) step over it by this same list. */
static const char *const valued_options[] = {
    "-o", "--output", "--size", "--background", "--png-level", "--jpeg-quality", "--shading",
    "--tonemap", "--exposure", "--environment", "--environment-intensity", "--shadows",
    "--normals", "--material", "--ambient", "--opacity", "--light", "--lights", "--texture",
    "--texture-filter", "--wrap", "--camera", "--fov", "--up", "--turn", "--camera-index",
    "--variant",
    "--animation", "--time",
    "--near", "--far", "--cull", "--front-face", "--depth-format", "--depth-func",
    "--projection-interp", "--depth-range", "--clipper", "--line-width", "--point-size",
    "--line-color", "--polygon-offset", "--aa", "--filter", "--rasterizer", "--threads",
    "--detail", NULL
};

bool render_opts_takes_value(const char *arg)
{
    for (int k = 0; valued_options[k]; k++) {
        if (strcmp(arg, valued_options[k]) == 0) {
            return true;
        }
    }
    return false;
}

static void render_help(void)
{
    printf(
        "usage: softrast render [MODEL] [options]\n"
        "\n"
        "Render MODEL (.obj, .ply, .stl, .gltf, .glb; other formats through Assimp\n"
        "when built with it) or, without MODEL, the built-in Utah teapot scene, to\n"
        "a PNG or a JPEG.\n"
        "\n"
        "output:\n"
        "  -o, --output FILE        image to write, atomically: a JPEG when FILE ends in\n"
        "                           .jpg or .jpeg, a PNG when it ends in .png or has no\n"
        "                           extension (another is refused; default softrast.png)\n"
        "  --size WxH               image size, 1..8192 each (default 1280x720); refused\n"
        "                           when its frames (with --aa's samples) need more\n"
        "                           memory than the machine has or SR_MEMORY_LIMIT allows\n"
        "  --background COLOR       name, #rgb, #rrggbb, R,G,B in 0..1, or a gray level\n"
        "                           in 0..1 (default #1d2230); transparent: a PNG with\n"
        "                           alpha, the model's edges blended into nothing;\n"
        "                           environment or blur: the --environment (studio or\n"
        "                           FILE.hdr) behind the model, sharp or blurred\n"
        "  --png-level N            zlib level 0..9 (default 1: fast, see docs)\n"
        "  --jpeg-quality N         JPEG quality 1..100 (default 90)\n"
        "shading:\n"
        "  --shading MODE           pbr|flat|gouraud|phong|normals|depth|unlit (default\n"
        "                           pbr: glTF's metallic-roughness model, lit by a\n"
        "                           studio environment and the key light, tone mapped;\n"
        "                           the others are the classic Blinn-Phong models)\n"
        "  --tonemap T              neutral|aces|none, pbr's tone curve: Khronos PBR\n"
        "                           Neutral, ACES filmic, or a clamp (default neutral)\n"
        "  --exposure EV            pbr's exposure in stops, -20..20 (default 0)\n"
        "  --environment E          pbr's ambient light: studio (a built-in neutral\n"
        "                           studio, prefiltered when softrast was built, and the\n"
        "                           key light; the default), FILE.hdr (an\n"
        "                           equirectangular Radiance picture, +y up, prefiltered\n"
        "                           once, and the key light) or hemisphere (a gray sky\n"
        "                           over a darker ground, with the key, fill and rim\n"
        "                           lights; also 'none')\n"
        "  --environment-intensity S  its radiance scale, 0.001..1000 (default 0.6)\n"
        "  --shadows on|off         pbr: the key light casts a shadow (a shadow map\n"
        "                           fitted to the model; default: on where a ground\n"
        "                           receives it - --ground, the teapot's floor - else\n"
        "                           off)\n"
        "  --ground                 pbr: a shadow catcher under the model: the ground\n"
        "                           shows only the model's soft shadow over the\n"
        "                           background (replaces the teapot's floor)\n"
        "  --normals MODE           file|smooth|flat: the file's normals, angle-weighted\n"
        "                           smooth ones, or one per face (default: file if the\n"
        "                           model has them, else smooth; flat on a glTF\n"
        "                           primitive without them, as glTF asks)\n"
        "  --material KEY=V,...     color=COLOR, specular=COLOR, shininess=N\n"
        "                           (default: light gray, specular 0.25, shininess 40;\n"
        "                           pbr: the color as base color, a dielectric of\n"
        "                           roughness 0.5, or 1 - sqrt(N/1000) for shininess N;\n"
        "                           an OBJ material's Ns, Pr, Pm, d, Tr and bump maps\n"
        "                           apply as docs/pbr.md says; a glTF file's own\n"
        "                           materials, which these keys override under the\n"
        "                           classic models)\n"
        "  --ambient COLOR          global ambient light (default 0.12,0.12,0.14; pbr:\n"
        "                           uniform COLOR in place of the environment)\n"
        "  --opacity A              the model's opacity, 0..1 (default 1); translucent\n"
        "                           surfaces are drawn after opaque ones, back to front\n"
        "  --light dir=X,Y,Z[,color=C][,intensity=I]\n"
        "  --light point=X,Y,Z[,color=C][,intensity=I]\n"
        "                           add a light in world space (repeatable, up to 8);\n"
        "                           without any, a key, fill and rim light placed\n"
        "                           relative to the camera\n"
        "  --lights file|default|both|auto\n"
        "                           pbr's lights: a glTF file's own (KHR_lights_punctual,\n"
        "                           its first 8, in candela and lux: see --exposure; the\n"
        "                           strongest directional one casts the shadow), the\n"
        "                           default ones (the rig above, or --light's), or the\n"
        "                           file's and then those (default auto: the file's when\n"
        "                           it has some and no --light is given, else the\n"
        "                           default ones)\n"
        "textures:\n"
        "  --texture FILE           PNG, JPEG or WebP that colors the model through its\n"
        "                           texture coordinates (default: the model's own - OBJ\n"
        "                           map_Kd, glTF/FBX textures named or embedded - each\n"
        "                           material's on its own faces, or MODEL_texture.png or\n"
        "                           .jpg beside a model MODEL.obj;\n"
        "                           one of those that cannot be read is a warning, a\n"
        "                           glTF's an error); FILE replaces them all\n"
        "  --texture-filter F       nearest|bilinear|trilinear (default trilinear)\n"
        "  --wrap MODE              repeat|clamp|mirror (default repeat); a glTF file's\n"
        "                           own textures take their sampler under every look\n"
        "  --texture-srgb           filter texels in linear light (sRGB-correct; always\n"
        "                           so under pbr)\n"
        "camera:\n"
        "  --camera eye=X,Y,Z[,target=X,Y,Z][,up=X,Y,Z]\n"
        "                           (default: a three-quarter view from above, the\n"
        "                           model filling the image to a 5%% margin on its\n"
        "                           limiting side, centred on the other)\n"
        "  --fov DEG                field of view across the smaller image side\n"
        "                           (default 35)\n"
        "  --ortho                  orthographic projection\n"
        "  --up AXIS                +x|-x|+y|-y|+z|-z: the model's up axis, turned to\n"
        "                           point up the image (default +z for .stl, as CAD\n"
        "                           and 3D printing use; +y for every other format,\n"
        "                           as glTF specifies, and the built-in teapot)\n"
        "  --turn DEG               rotate the model about the vertical axis (default 0)\n"
        "  --camera-index N         a glTF file's camera N (0 first, in node order) in\n"
        "                           place of the default camera (any --shading)\n"
        "  --variant NAME|N         a glTF file's material variant (KHR_materials_variants)\n"
        "                           by name, or by number (0 first, in the file's order);\n"
        "                           default: none, each primitive's own material; -v\n"
        "                           lists the file's variants\n"
        "  --near Z, --far Z        clip distances (default: fitted to the scene)\n"
        "animation (glTF):\n"
        "  --animation N|NAME       pose the model by the file's animation N (0 first)\n"
        "                           or the one named NAME (default: the rest pose)\n"
        "  --time SECONDS           the time into it, -1e6..1e6 (default 0); before the\n"
        "                           first key the pose is the first key's, after the\n"
        "                           last the last's\n"
        "pipeline:\n"
        "  --cull MODE              back|front|none (default back)\n"
        "  --front-face ORDER       ccw|cw (default ccw)\n"
        "  --depth-format F         d16|d24|d32|d32f (default d24)\n"
        "  --depth-func F           never|less|equal|lequal|greater|notequal|gequal|always\n"
        "                           (default less; greater and gequal clear depth to 0)\n"
        "  --projection-interp M    perspective|affine (default perspective)\n"
        "  --depth-range NEAR,FAR   window depths of the near and far planes, each\n"
        "                           clamped to [0, 1] as glDepthRange (default 0,1;\n"
        "                           NEAR > FAR inverts depth)\n"
        "  --clipper C              homogeneous|view-volume: clip triangles in clip\n"
        "                           space or against the view volume's six planes in\n"
        "                           view space (default homogeneous; view-volume needs\n"
        "                           a --shading other than pbr)\n"
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
        "                           once, box-resolved (default msaa4)\n"
        "  --filter F               box|tent|gaussian|mitchell, the SSAA reconstruction\n"
        "                           filter (default box)\n"
        "  --rasterizer R           halfspace|scanline|barycentric (default halfspace;\n"
        "                           all three give the same pixels)\n"
        "  --threads N              rasterizer threads (default: SR_THREADS or CPUs)\n"
        "  --detail N               teapot tessellation per patch, 1..64 (default 12)\n"
        "  -v, --verbose            print timings, counts and the files read to stderr\n"
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

/* A model named on the command line; -1 to go on, else the exit status. */
static int take_model(const char *cmd, const char *arg, render_opts *o)
{
    if (!*arg) {
        cli_error("%s: the model's file name is empty", cmd);
        return EXIT_USAGE;
    } else if (o->model_fn) {
        if (!o->model_fn(o->model_user, arg)) {
            return EXIT_FAILURE_RUN;
        }
    } else if (!o->model) {
        o->model = arg;
    } else {
        cli_error("%s: more than one model given ('%s' and '%s')", cmd, o->model, arg);
        return EXIT_USAGE;
    }
    return -1;
}

int render_opts_parse(int argc, char **argv, render_opts *o)
{
    bool ended = false;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        cli_arg_kind kind = cli_arg(arg, &ended);
        if (kind == CLI_ARG_END) {
            continue;
        } else if (kind == CLI_ARG_OPERAND) {
            int status = take_model(argv[0], arg, o);
            if (status >= 0) {
                return status;
            }
            continue;
        }
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
        /* The value of "--opt value", taken here for every valued option
         * (so that the list cannot miss one an option below reads). */
        if (!value && render_opts_takes_value(arg)) {
            if (i + 1 >= argc) {
                cli_error("%s: missing value", arg);
                return EXIT_USAGE;
            }
            value = argv[++i];
        }
#define IS(name) (strcmp(arg, name) == 0)
#define VALUE()                                                                     \
    do {                                                                            \
        if (!value) {                                                               \
            cli_error("%s: missing value", arg);                                    \
            return EXIT_USAGE;                                                      \
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

        for (int k = 0; pbr_only[k]; k++) {
            o->pbr_only_given |= IS(pbr_only[k]) ? 1u << k : 0;
        }
        if ((IS("-h") || IS("--help") || IS("-v") || IS("--verbose")) && value) {
            cli_error("%s: takes no value", arg);
            return EXIT_USAGE;
        }
        if (IS("-h") || IS("--help")) {
            render_help();
            return EXIT_OK;
        } else if (IS("-o") || IS("--output")) {
            VALUE();
            if (!cli_check_output_name(arg, value) || !cli_check_image_name(arg, value, true)) {
                return EXIT_USAGE;
            }
            o->output = value;
        } else if (IS("--size")) {
            VALUE();
            if (!parse_size(arg, value, &o->width, &o->height)) {
                return EXIT_USAGE;
            }
        } else if (IS("--shading")) {
            int sh;
            CHOICE(shading_names, sh, k_);
            o->shading = shading_values[sh];
            o->pbr = sh == 0;
            o->shading_name = shading_names[sh];
        } else if (IS("--tonemap")) {
            CHOICE(tonemap_names, o->tonemap, tonemap_values[k_]);
        } else if (IS("--camera-index")) {
            VALUE();
            char *end = NULL;
            long n = strtol(value, &end, 10);
            if (end == value || *end != 0 || n < 0 || n > 1000000) {
                cli_error("%s: expected a camera number from 0 (got '%s')", arg, value);
                return EXIT_USAGE;
            }
            o->camera_index = (int)n;
        } else if (IS("--variant")) {
            VALUE();
            o->variant = value;
        } else if (IS("--animation")) {
            VALUE();
            o->animation = value;
        } else if (IS("--time")) {
            VALUE();
            if (!parse_float(arg, value, -1e6f, 1e6f, &o->animation_time)) {
                return EXIT_USAGE;
            }
            o->have_time = true;
        } else if (IS("--environment")) {
            VALUE();
            o->environment = value;
        } else if (IS("--environment-intensity")) {
            VALUE();
            if (!parse_float(arg, value, 0.001f, 1000.0f, &o->environment_intensity)) {
                return EXIT_USAGE;
            }
        } else if (IS("--exposure")) {
            VALUE();
            if (!parse_float(arg, value, -20.0f, 20.0f, &o->exposure)) {
                return EXIT_USAGE;
            }
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
        } else if (IS("--clipper")) {
            CHOICE(clipper_names, o->clipper, (sr_clipper)(SR_CLIPPER_HOMOGENEOUS + k_));
        } else if (IS("--depth-range")) {
            VALUE();
            int n = 0;
            if (sscanf(value, "%f,%f%n", &o->depth_near, &o->depth_far, &n) != 2 ||
                value[n] != 0 || isnan(o->depth_near) || isnan(o->depth_far)) {
                cli_error("%s: expected NEAR,FAR, two numbers (got '%s')", arg, value);
                return EXIT_USAGE;
            }
            o->depth_range = SR_DEPTH_RANGE_SET;
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
            o->filter_given = true;
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
        } else if (IS("--up")) {
            CHOICE(up_names, o->model_up, k_);
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
            bool clear = strcmp(value, "transparent") == 0;
            o->background_env = strcmp(value, "environment") == 0 ? BACKGROUND_SHARP
                              : strcmp(value, "blur") == 0        ? BACKGROUND_BLUR
                                                                  : BACKGROUND_COLOR;
            o->background = (sr_vec3){ 0, 0, 0 };
            o->background_alpha = clear ? 0.0f : 1.0f;
            if (!clear && !o->background_env && !parse_color(arg, value, &o->background)) {
                return EXIT_USAGE;
            }
        } else if (IS("--lights")) {
            CHOICE(lights_names, o->lights_source, lights_values[k_]);
        } else if (IS("--shadows")) {
            CHOICE(switch_names, o->shadows, k_ == 0 ? 1 : 0);
        } else if (IS("--ground")) {
            if (value) {
                cli_error("%s: takes no value", arg);
                return EXIT_USAGE;
            }
            o->ground = true;
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
        } else {
            cli_error("%s: unknown option '%s' (try 'softrast %s --help')", argv[0], arg, argv[0]);
            return EXIT_USAGE;
        }
#undef IS
#undef VALUE
#undef CHOICE
    }
    if (o->clipper == SR_CLIPPER_VIEW_VOLUME && o->pbr) {
        cli_error("--clipper view-volume clips the built-in shading models' view space; "
                  "pbr's program has none (give --shading phong, or another)");
        return EXIT_USAGE;
    }
    if (o->background_env && !render_opts_image_light(o)) {
        cli_error("--background %s: shows the environment of --environment studio or FILE.hdr "
                  "under --shading pbr, without --ambient",
                  o->background_env == BACKGROUND_BLUR ? "blur" : "environment");
        return EXIT_USAGE;
    }
    if (o->have_time && !o->animation) {
        cli_error("--time: gives a time into an animation: give --animation N|NAME too");
        return EXIT_USAGE;
    }
    if (o->near_z > 0 && o->far_z > 0 && o->near_z >= o->far_z) {
        cli_error("--near %g must be less than --far %g", (double)o->near_z, (double)o->far_z);
        return EXIT_USAGE;
    }
    return -1;
}

void render_opts_warn(const render_opts *o)
{
    for (int k = 0; pbr_only[k] && !o->pbr; k++) {
        if (o->pbr_only_given & 1u << k) {
            cli_error("warning: %s has no effect with --shading %s (it is for pbr)", pbr_only[k],
                      o->shading_name);
        }
    }
    if (o->filter_given && o->ssaa <= 1) {
        cli_error("warning: --filter has no effect without --aa ssaa2, ssaa3 or ssaa4 "
                  "(it filters SSAA's samples)");
    }
}

uint64_t render_opts_frame_bytes(const render_opts *o, int width, int height)
{
    uint64_t pixels = (uint64_t)width * (uint64_t)height;
    uint64_t samples = o->ssaa > 1 ? (uint64_t)o->ssaa * (uint64_t)o->ssaa : (uint64_t)o->msaa;
    uint64_t depth = o->depth_format == SR_DEPTH_D16 ? 2 : 4;
    /* Every sample's color and depth; the resolved or filtered image;
     * the image as it is written (its straight-alpha copy, the encoder's
     * rows); SSAA's filter keeps every sample row filtered to the
     * output's width, in float RGBA (sr_downsample). */
    uint64_t filter = o->ssaa > 1 ? pixels * (uint64_t)o->ssaa * 16 : 0;
    return pixels * samples * (4 + depth) + (samples > 1 ? pixels * 4 : 0) + pixels * 4 + filter;
}

int render_opts_check_frames(const render_opts *o, const char *cmd, int width, int height,
                             int frames)
{
    return render_opts_check_memory(o, cmd, width, height, frames, 0, "", NULL);
}

int render_opts_check_memory(const render_opts *o, const char *cmd, int width, int height,
                             int frames, uint64_t more, const char *more_what, const char *lower)
{
    char aa[16] = "none";
    if (o->ssaa > 1 || o->msaa > 1) {
        snprintf(aa, sizeof aa, "%s%d", o->ssaa > 1 ? "ssaa" : "msaa",
                 o->ssaa > 1 ? o->ssaa : o->msaa);
    }
    long sw = (long)width * o->ssaa, sh = (long)height * o->ssaa;
    if (sw > SR_MAX_FRAMEBUFFER_SIZE || sh > SR_MAX_FRAMEBUFFER_SIZE) {
        cli_error("%s: --aa %s at --size %dx%d draws %ldx%ld samples, more than %d a side: "
                  "give a smaller --size or --aa", cmd, aa, width, height, sw, sh,
                  SR_MAX_FRAMEBUFFER_SIZE);
        return EXIT_USAGE;
    }
    /* thumbnail.c renders a square of its -s SIZE, with render's --aa. */
    bool thumb = strcmp(cmd, "thumbnail") == 0;
    char what[192];
    if (thumb) {
        snprintf(what, sizeof what, "thumbnail: -s %d", width);
    } else {
        snprintf(what, sizeof what, "%s: --size %dx%d with --aa %s%s%s", cmd, width, height, aa,
                 frames > 1 ? " (two frames at once)" : "", more_what);
    }
    return cli_check_memory(what,
                            render_opts_frame_bytes(o, width, height) * (uint64_t)frames + more,
                            lower  ? lower
                            : thumb ? "give a smaller -s"
                                    : "give a smaller --size or --aa");
}

bool render_opts_image_light(const render_opts *o)
{
    return o->pbr && !o->have_ambient && strcmp(o->environment, "hemisphere") != 0 &&
           strcmp(o->environment, "none") != 0;
}

render_opts render_opts_defaults(void)
{
    return (render_opts){
        .output = "softrast.png", .width = 1280, .height = 720, .shading = SR_SHADING_PHONG,
        .pbr = true, .tonemap = SR_TONEMAP_PBR_NEUTRAL, .environment = "studio",
        .environment_intensity = 0.6f, .camera_index = -1,
        .cull = SR_CULL_BACK, .front = SR_FRONT_CCW, .fov_deg = SR_FRAMING_FOV_DEG,
        .background = { 0x1d / 255.0f, 0x22 / 255.0f, 0x30 / 255.0f }, .background_alpha = 1.0f,
        .shadows = -1,
        .depth_format = SR_DEPTH_D24, .depth_func = SR_LESS, .interp = SR_INTERP_PERSPECTIVE,
        .normals = -1, .detail = 12, .rasterizer = SR_RASTER_HALFSPACE, .png_level = -1,
        .line_width = 1.0f, .point_size = 3.0f, .ssaa = 1, .msaa = 4, .opacity = 1.0f,
        .offset_factor = 1.0f, .offset_units = 1.0f, .model_up = UP_AUTO,
    };
}
