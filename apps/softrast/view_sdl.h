/* view_sdl.h - the parts of `softrast view` that touch SDL: the scripted
 * input of tests (view_script.c) and the front and back framebuffers with
 * the thread that renders into the back one (view_frames.c).  SDL opens
 * the window, delivers input and shows our pixels; it draws nothing. */
#ifndef SR_VIEW_SDL_H
#define SR_VIEW_SDL_H

#include "view.h"

#include <SDL.h>
#include <pthread.h>

/* ---- scripted input (view_script.c) ---------------------------------------- */

typedef struct view_script view_script;

/* Read and check a script; -1, or an exit status after one line
 * "FILE:LINE: what is wrong". */
int  view_script_load(const char *path, view_script **out);
void view_script_free(view_script *s);
/* Push the events of the commands up to the next `frames N` as SDL events
 * (the same path as real input) and return N, or 0 at the end. */
int  view_script_advance(view_script *s, SDL_Window *win, Uint32 screenshot_event);

/* ---- front and back framebuffers (view_frames.c) -------------------------- */

typedef struct view_frames {
    render_job *job;
    view_font *font;              /* NULL: no overlay text */
    sr_framebuffer *front, *back; /* front is shown while back is drawn */
    Uint32 done_event;            /* pushed when a frame is ready */

    pthread_t thread;
    pthread_mutex_t mu;
    pthread_cond_t cv;
    bool has_work, stop, started;

    /* The request, written by the main thread before view_frames_kick. */
    bool overlay;
    view_overlay_info info;
    char title[256], modes[1024];
    char shot[4096];              /* screenshot path, or "" */
    char window_shot[4096];       /* the same frame with its overlay, or "" */

    /* The result, read by the main thread after done_event. */
    sr_result result;
    char error[640];
    render_frame_info frame;
    double render_ms, overlay_ms;
    bool shot_ok;
    char shot_error[640];
} view_frames;

/* Make both framebuffers at w x h and start the render thread. */
bool view_frames_start(view_frames *vf, render_job *job, view_font *font, int w, int h);
/* Re-make both framebuffers (the render thread must be idle); false
 * with vf->error set. */
bool view_frames_resize(view_frames *vf, int w, int h);
void view_frames_release(view_frames *vf);   /* destroy the framebuffers only */
/* Render the request into back on the render thread; done_event follows. */
void view_frames_kick(view_frames *vf);
/* After done_event: the back buffer becomes the one shown. */
void view_frames_swap(view_frames *vf);
void view_frames_stop(view_frames *vf);

#endif
