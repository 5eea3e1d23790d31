/* render_options.h - the options of a render job (render_options.c parses
 * them; render.c and render_textures.c act on them). */
#ifndef SR_RENDER_OPTIONS_H
#define SR_RENDER_OPTIONS_H

#include "softrast.h"

#include <stdbool.h>
#include <stdint.h>

typedef struct render_opts {
    const char *model;
    const char *output;
    const char *texture;           /* --texture FILE */
    sr_texture_filter texture_filter;
    sr_texture_wrap wrap;
    bool texture_srgb;
    int width, height;
    sr_shading shading;            /* the classic model, or Phong under pbr */
    bool pbr;                      /* --shading pbr: the metallic-roughness program */
    sr_tonemap_op tonemap;         /* pbr's tone curve */
    float exposure;                /* pbr's exposure, EV */
    const char *environment;       /* "studio", "hemisphere" or an .hdr file */
    float environment_intensity;
    int camera_index;              /* --camera-index: a glTF camera, or -1 */
    const char *variant;           /* --variant: a glTF material variant's name or
                                    * number, or NULL */
    const char *animation;         /* --animation N|NAME: a glTF animation, or NULL */
    float animation_time;          /* --time SECONDS into it */
    bool have_time;
    sr_cull_mode cull;
    sr_front_face front;
    bool have_eye, have_target, have_up;
    sr_vec3 eye, target, up;
    float fov_deg;
    bool ortho;
    float turn_deg;
    int model_up;                  /* --up: UP_AUTO, or UP_POS_X ... UP_NEG_Z */
    float near_z, far_z;           /* 0: fitted */
    sr_light lights[SR_MAX_LIGHTS];
    int light_count;
    int lights_source;             /* --lights: LIGHTS_AUTO, ... */
    bool have_ambient;
    sr_vec3 ambient;
    bool have_mat_color, have_specular, have_shininess;
    sr_vec3 mat_color, specular;
    float shininess;
    sr_vec3 background;
    float background_alpha;        /* 1, or 0 for --background transparent */
    int background_env;            /* BACKGROUND_COLOR, or the environment shown */
    int shadows;                   /* pbr: the key light's shadow map: 1 on, 0 off,
                                    * -1 on when a ground receives it */
    bool ground;                   /* a shadow catcher under the model */
    sr_depth_format depth_format;
    sr_depth_func depth_func;
    sr_interpolation interp;
    int normals;                   /* -1 auto, 0 file, 1 smooth, 2 flat */
    int detail;
    sr_rasterizer rasterizer;
    sr_clipper clipper;
    sr_depth_range_mode depth_range;   /* SR_DEPTH_RANGE_SET after --depth-range */
    float depth_near, depth_far;
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
    /* For render_opts_warn: the --shading named (NULL: pbr, the default),
     * the pbr-only options given (bits in the order of render_options.c's
     * pbr_only) and whether --filter was given. */
    const char *shading_name;
    unsigned pbr_only_given;
    bool filter_given;
    /* When set, each model named is passed to model_fn (a batch's list)
     * instead of being o->model; false from it stops the parse. */
    bool (*model_fn)(void *user, const char *path);
    void *model_user;
} render_opts;

/* The model's up axis (--up), in the order of its names +x -x +y -y +z -z;
 * UP_AUTO: by the model file's format (render_model_up). */
enum { UP_AUTO = -1, UP_POS_X = 0, UP_NEG_X, UP_POS_Y, UP_NEG_Y, UP_POS_Z, UP_NEG_Z };

/* --background environment|blur: the environment itself, or blurred. */
enum { BACKGROUND_COLOR = 0, BACKGROUND_SHARP, BACKGROUND_BLUR };

/* The lights --lights names for pbr (LIGHTS_AUTO: the file's when it has
 * some and no --light is given, else the default ones; render_lights.c). */
enum { LIGHTS_AUTO = 0, LIGHTS_FILE, LIGHTS_DEFAULT, LIGHTS_BOTH };

/* What the line modes draw besides (or instead of) the shaded model. */
enum { LINES_NONE = 0, LINES_WIREFRAME, LINES_HIDDEN, LINES_EDGES, LINES_POINTS };

/* The defaults: what `softrast render` draws with no options. */
render_opts render_opts_defaults(void);
/* Parse argv (argv[0] names the command in messages) into *o, which holds
 * the defaults.  Returns -1 to continue, else the exit status (EXIT_OK
 * after --help). */
int render_opts_parse(int argc, char **argv, render_opts *o);

/* Whether the render option arg ("--size", not "--size=WxH") takes the
 * next argument as its value, whatever that looks like. */
bool render_opts_takes_value(const char *arg);

/* One warning line for each option given that the others make useless
 * (--ground without pbr, --filter without SSAA).  The caller calls it once
 * a command, not once a batch input; the exit status is not changed. */
void render_opts_warn(const render_opts *o);

/* The memory one frame of width x height takes with these options: its
 * samples' color and depth, the resolved image and the image written. */
uint64_t render_opts_frame_bytes(const render_opts *o, int width, int height);
/* Before any frame is made: -1 when `frames` frames of width x height
 * fit the memory limit (cli_memory_limit) and the samples fit a
 * framebuffer, else EXIT_USAGE after one line that starts with cmd and
 * says how to ask for less. */
int render_opts_check_frames(const render_opts *o, const char *cmd, int width, int height,
                             int frames);
/* The same with `more` bytes besides the frames (a batch's images being
 * written, its contact sheet), which more_what ("" or " and ...") names
 * after the frames in the line; `lower` ("give ...") says what asks for
 * less when it is not the frames' --size or --aa (NULL: those). */
int render_opts_check_memory(const render_opts *o, const char *cmd, int width, int height,
                             int frames, uint64_t more, const char *more_what, const char *lower);

/* The options ask for an environment's image-based light (studio or an
 * .hdr file, under pbr, without --ambient) rather than the hemisphere. */
bool render_opts_image_light(const render_opts *o);

#endif
