/* view.h - the pieces of `softrast view`: an orbit camera, the table of
 * pipeline modes the keys cycle through, the TrueType text of the overlay,
 * the overlay itself, the scripted input of tests, and the front/back
 * framebuffers with the thread that renders into the back one.  Only
 * view.c, view_frames.c and view_script.c see SDL; the camera and the
 * modes are plain C so the key table stays one line per mode value. */
#ifndef SR_VIEW_H
#define SR_VIEW_H

#include "render.h"
#include "softrast.h"

#include <stdbool.h>
#include <stddef.h>

/* ---- camera (view_camera.c) ---------------------------------------------- */

/* An orbit camera around a target; the state is the eye, target and up
 * that `softrast render --camera` takes, so a view can be reproduced. */
typedef struct view_camera {
    sr_vec3 eye, target, up;
    sr_vec3 home_eye, home_target, home_up;  /* R goes back here */
    sr_vec3 centre;                          /* the framed bounding sphere (F) */
    float radius, fov;                       /* fov across the smaller side, radians */
} view_camera;

void view_camera_init(view_camera *c, const render_job *job);
/* Drag by (dx, dy) window pixels: azimuth and elevation about the target. */
void view_camera_orbit(view_camera *c, float dx, float dy);
/* Move eye and target together so the point under the cursor follows it;
 * `short_side` is the smaller window dimension in pixels. */
void view_camera_pan(view_camera *c, float dx, float dy, int short_side);
/* Wheel notches: positive moves closer. */
void view_camera_zoom(view_camera *c, float notches);
void view_camera_fit(view_camera *c);
void view_camera_reset(view_camera *c);

/* ---- modes (view_modes.c) -------------------------------------------------- */

#define VIEW_MAX_CHOICES 12

/* One value of a mode: its name on screen and the `softrast render`
 * argument that selects it (NULL: no argument, the render default). */
typedef struct view_choice {
    const char *name;
    const char *arg;
} view_choice;

typedef struct view_mode {
    char key;                 /* lowercase key that cycles it (Shift: backwards) */
    const char *label;
    view_choice choices[VIEW_MAX_CHOICES];  /* ends at name == NULL */
} view_mode;

extern const view_mode view_modes[];
extern const int view_mode_count;

typedef struct view_mode_state {
    int index[32];            /* current choice per mode; -1: as the user's arguments say */
} view_mode_state;

/* The choices that the user's own render arguments select (else 0; -1
 * for a value the table does not list).  base receives the arguments
 * without those the table replaces; returns their count. */
int view_modes_init(view_mode_state *st, int argc, char *const *argv, const char **base);
/* The mode bound to `key`, or -1. */
int view_mode_for_key(char key);
void view_mode_cycle(view_mode_state *st, int mode, int step);
/* Append the arguments of the current choices to argv (room for
 * view_mode_count entries); returns the new count. */
int view_modes_args(const view_mode_state *st, const char **argv, int argc);
/* "phong, cull back, ..." for the overlay. */
void view_modes_describe(const view_mode_state *st, char *out, size_t size);

/* ---- TrueType text (view_font.c) ------------------------------------------ */

typedef struct view_font view_font;

/* Open a TrueType font at `pixel_size`; false with a one-line reason. */
bool view_font_open(const char *path, int pixel_size, view_font **out, char *why, size_t size);
void view_font_close(view_font *f);
int  view_font_line_height(const view_font *f);
int  view_font_ascent(const view_font *f);
/* Advance width of UTF-8 text in pixels. */
int  view_font_width(view_font *f, sr_context *ctx, const char *text);
/* Draw UTF-8 text with its baseline at y, starting at x.  Glyph coverage
 * is rasterized once per character and cached. */
sr_result view_font_draw(view_font *f, sr_context *ctx, sr_framebuffer *fb, int x, int y,
                         const char *text, sr_rgba color);
/* Glyphs rasterized so far (the cache's size). */
int  view_font_cached(const view_font *f);

/* ---- overlay (view_overlay.c) --------------------------------------------- */

typedef struct view_overlay_info {
    const char *title;            /* model name */
    int width, height, threads;
    double render_ms, median_ms;  /* this frame, median so far */
    double fps;                   /* presented frames per second */
    unsigned long long triangles, fragments;
    const char *modes;
    bool help;                    /* the key list */
} view_overlay_info;

sr_result view_overlay_draw(view_font *f, sr_context *ctx, sr_framebuffer *fb,
                            const view_overlay_info *info);

#endif
