/* render.h - a render job: the options of `softrast render`, the scene they
 * load and the context that draws it, split into parse, load and draw so
 * that `softrast view` draws its frames through exactly the code that
 * `softrast render` uses.  A view screenshot and a render with the same
 * options and camera are therefore the same pixels.  One thread at a time
 * may use a job. */
#ifndef SR_RENDER_H
#define SR_RENDER_H

#include "cli.h"
#include "softrast.h"

#include <stdint.h>

typedef struct render_job render_job;

typedef struct render_frame_info {
    uint64_t triangles;   /* assembled triangles, summed over the passes */
    uint64_t fragments;   /* samples written, summed over the passes */
    float near_z, far_z;  /* the clip distances used */
} render_frame_info;

/* Parse `softrast render` options (argv[0] names the command in messages).
 * Returns -1 with *out set, else the exit status after printing one line
 * (EXIT_OK after --help). */
int render_job_parse(int argc, char **argv, render_job **out);
/* Load the model (or build the teapot scene), prepare normals and
 * materials, make the context and the texture.  -1 or an exit status. */
int render_job_load(render_job *job);
/* Re-read the options that say how a frame is drawn (shading, culling,
 * depth function, line modes, antialiasing, threads, camera, ...); the
 * options read at load time (model, normals, material, texture, --turn)
 * keep their loaded effect.  A new thread count makes a new context:
 * framebuffers made on the old one must be destroyed first.  -1 or an
 * exit status. */
int render_job_configure(render_job *job, int argc, char **argv);
void render_job_free(render_job *job);
/* render_opts_check_frames with the job's options: -1 when `frames`
 * frames of width x height fit the memory limit, else the exit status
 * after one line. */
int render_job_check_frames(const render_job *job, const char *cmd, int width, int height,
                            int frames);
/* Make the contexts and the environment light (--environment) of a job
 * that has no model yet, so that another job can share the light:
 * render_job_load does this itself otherwise.  -1 or an exit status. */
int render_job_prepare(render_job *job);
/* Light `job` with the environment of `from` (prepared, and freed after
 * job) instead of prefiltering its own: a batch's two jobs, one reading
 * a model while the other draws, share one. */
void render_job_share_light(render_job *job, const render_job *from);
/* Load another model into a loaded job (a batch's next input), keeping
 * its contexts: the old scene, textures and inputs are dropped first.
 * -1, or an exit status after the reason was reported (cli_error). */
int render_job_reload(render_job *job, const char *model);

/* Whether the loaded model is posed by a glTF animation (--animation),
 * and that animation's duration in seconds. */
bool render_job_animation(const render_job *job, float *duration);
/* Pose the loaded model at `seconds` into the animation it is posed by
 * (what --time would set), without reading its file again
 * (sr_scene_pose): its objects are made again from the posed scene.
 * -1, or an exit status after the reason was reported (cli_error). */
int render_job_pose(render_job *job, float seconds);

/* The camera the options give: --camera, else the default framing. */
void render_job_camera(const render_job *job, sr_vec3 *eye, sr_vec3 *target, sr_vec3 *up);
/* Replace the camera (what `--camera eye=..,target=..,up=..` would set). */
void render_job_set_camera(render_job *job, sr_vec3 eye, sr_vec3 target, sr_vec3 up);
/* Bounding sphere of the framed objects, and the field of view (radians,
 * across the smaller image side). */
void render_job_bounds(const render_job *job, sr_vec3 *centre, float *radius);
float render_job_fov(const render_job *job);

sr_context *render_job_context(const render_job *job);
/* The depth format to give the framebuffer passed to render_job_draw so
 * that the job draws into it directly (otherwise it draws into its own
 * image and copies or filters it down). */
sr_depth_format render_job_depth_format(const render_job *job);

/* The framebuffer to make for render_job_draw when only its resolved
 * pixels are read (sr_framebuffer_pixels): with MSAA (and no SSAA) it is
 * multisampled with the job's samples and depth format, and the job draws
 * into it directly rather than into a work image resolved into it, which
 * saves a full-size image; otherwise it is single-sampled with
 * render_job_depth_format. */
sr_framebuffer_desc render_job_direct_desc(const render_job *job, int width, int height);

/* Draw one frame into `out` (made on the job's context; single-sampled,
 * or as render_job_direct_desc says), at out's size.  On failure
 * render_job_error says why in one line. */
sr_result render_job_draw(render_job *job, sr_framebuffer *out, render_frame_info *info);
const char *render_job_error(const render_job *job);
/* The model file, or NULL for the built-in scene. */
const char *render_job_model(const render_job *job);
/* The files read so far (model, MTL, textures), which no image the job's
 * command writes may replace; a command adds its own (an event script). */
cli_inputs *render_job_inputs(render_job *job);

#endif
