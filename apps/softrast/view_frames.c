/* view_frames.c - double buffering for `softrast view`: two sr_framebuffers,
 * front and back.  The render thread draws the scene into back (through
 * render_job_draw, the code `softrast render` uses), writes a requested
 * screenshot from it, then draws the overlay over it; meanwhile the main
 * thread keeps showing front.  When back is ready the thread pushes an
 * SDL event, the main thread swaps the two, copies the new front into
 * the streaming texture and presents it with vsync, so a frame is never
 * shown half drawn.  The main thread touches the job and the framebuffers
 * only while the render thread is idle. */
#ifdef SR_HAVE_VIEWER
#include "cli.h"
#include "softrast_io.h"
#include "view_sdl.h"

#include <stdio.h>
#include <string.h>
#include <time.h>

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static void draw_frame(view_frames *vf)
{
    sr_context *ctx = render_job_context(vf->job);
    vf->error[0] = vf->shot_error[0] = 0;
    vf->shot_ok = false;
    double t0 = now_ms();
    vf->result = render_job_draw(vf->job, vf->back, &vf->frame);
    double t1 = now_ms();
    vf->render_ms = t1 - t0;
    if (vf->result != SR_OK) {
        snprintf(vf->error, sizeof vf->error, "%s", render_job_error(vf->job));
        return;
    }
    /* The screenshot is the scene alone, as `softrast render` draws it. */
    if (vf->shot[0]) {
        int w = sr_framebuffer_width(vf->back), h = sr_framebuffer_height(vf->back);
        sr_io_error err;
        if (cli_write_image(vf->shot, w, h, sr_framebuffer_pixels(vf->back),
                            &(cli_image_options){ .png_level = -1,
                                                  .inputs = render_job_inputs(vf->job) },
                            &err) == SR_OK) {
            vf->shot_ok = true;
        } else {
            snprintf(vf->shot_error, sizeof vf->shot_error, "%s", err.message);
        }
    }
    double t2 = now_ms();
    if (vf->overlay && vf->font) {
        vf->info.render_ms = vf->render_ms;
        vf->info.triangles = vf->frame.triangles;
        vf->info.fragments = vf->frame.fragments;
        vf->info.title = vf->title;
        vf->info.modes = vf->modes;
        vf->result = view_overlay_draw(vf->font, ctx, vf->back, &vf->info);
        if (vf->result != SR_OK) {
            snprintf(vf->error, sizeof vf->error, "overlay: %s", sr_context_error(ctx));
        }
    }
    vf->overlay_ms = now_ms() - t2;
    if (vf->result == SR_OK && vf->window_shot[0]) {
        int w = sr_framebuffer_width(vf->back), h = sr_framebuffer_height(vf->back);
        sr_io_error err;
        if (cli_write_image(vf->window_shot, w, h, sr_framebuffer_pixels(vf->back),
                            &(cli_image_options){ .png_level = -1,
                                                  .inputs = render_job_inputs(vf->job) },
                            &err) != SR_OK) {
            vf->shot_ok = false;
            snprintf(vf->shot_error, sizeof vf->shot_error, "%s", err.message);
        }
    }
}

static void *render_thread(void *arg)
{
    view_frames *vf = arg;
    for (;;) {
        pthread_mutex_lock(&vf->mu);
        while (!vf->has_work && !vf->stop) {
            pthread_cond_wait(&vf->cv, &vf->mu);
        }
        bool stop = vf->stop;
        vf->has_work = false;
        pthread_mutex_unlock(&vf->mu);
        if (stop) {
            return NULL;
        }
        draw_frame(vf);
        SDL_Event e = { .type = vf->done_event };
        SDL_PushEvent(&e);
    }
}

bool view_frames_resize(view_frames *vf, int w, int h)
{
    view_frames_release(vf);
    sr_context *ctx = render_job_context(vf->job);
    sr_framebuffer_desc d = { .width = w, .height = h,
                              .depth_format = render_job_depth_format(vf->job) };
    if (sr_make_framebuffer(ctx, &d, &vf->front) != SR_OK ||
        sr_make_framebuffer(ctx, &d, &vf->back) != SR_OK) {
        snprintf(vf->error, sizeof vf->error, "%dx%d framebuffers: %s", w, h,
                 sr_context_error(ctx));
        view_frames_release(vf);
        return false;
    }
    return true;
}

void view_frames_release(view_frames *vf)
{
    sr_context *ctx = render_job_context(vf->job);
    sr_destroy_framebuffer(ctx, vf->front);
    sr_destroy_framebuffer(ctx, vf->back);
    vf->front = vf->back = NULL;
}

bool view_frames_start(view_frames *vf, render_job *job, view_font *font, int w, int h)
{
    vf->job = job;
    vf->font = font;
    if (!view_frames_resize(vf, w, h)) {
        return false;
    }
    pthread_mutex_init(&vf->mu, NULL);
    pthread_cond_init(&vf->cv, NULL);
    if (pthread_create(&vf->thread, NULL, render_thread, vf) != 0) {
        snprintf(vf->error, sizeof vf->error, "cannot start the render thread");
        return false;
    }
    vf->started = true;
    return true;
}

void view_frames_kick(view_frames *vf)
{
    pthread_mutex_lock(&vf->mu);
    vf->has_work = true;
    pthread_cond_signal(&vf->cv);
    pthread_mutex_unlock(&vf->mu);
}

void view_frames_swap(view_frames *vf)
{
    sr_framebuffer *t = vf->front;
    vf->front = vf->back;
    vf->back = t;
}

void view_frames_stop(view_frames *vf)
{
    if (vf->started) {
        pthread_mutex_lock(&vf->mu);
        vf->stop = true;
        pthread_cond_signal(&vf->cv);
        pthread_mutex_unlock(&vf->mu);
        pthread_join(vf->thread, NULL);
        pthread_mutex_destroy(&vf->mu);
        pthread_cond_destroy(&vf->cv);
        vf->started = false;
    }
    if (vf->job) {
        view_frames_release(vf);
    }
}
#endif /* SR_HAVE_VIEWER */
