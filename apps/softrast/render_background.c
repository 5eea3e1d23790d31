/* render_background.c - the environment as the background of a render:
 * each pixel's ray from the inverse of the camera's view-projection, the
 * environment's radiance along it (sr_environment_background), then
 * exposure, tone curve and sRGB encoding (sr_tonemap) into the
 * framebuffer, before the model is drawn over it.  Called on the drawing
 * thread; the rays are looked up on threads of its own. */
#include "render_background.h"

#include <pthread.h>
#include <stdlib.h>

#define MAX_THREADS 64

typedef struct band {
    const sr_environment *env;
    sr_mat4 inv;                 /* clip -> world */
    sr_vec3 forward;             /* the camera's gaze, world space */
    float blur;
    int width, height, y0, y1;
    float *rgb;
} band;

/* The point of clip space (x, y, z, 1) in world space. */
static sr_vec3 unproject(const sr_mat4 *inv, float x, float y, float z)
{
    sr_vec4 p = sr_mat4_mul_vec4(inv, (sr_vec4){ x, y, z, 1.0f });
    return (sr_vec3){ p.x / p.w, p.y / p.w, p.z / p.w };
}

static void *look_up_band(void *arg)
{
    const band *b = arg;
    for (int y = b->y0; y < b->y1; y++) {
        /* Pixel centres; y points down the image, up in clip space. */
        float cy = 1.0f - 2.0f * ((float)y + 0.5f) / (float)b->height;
        for (int x = 0; x < b->width; x++) {
            float cx = 2.0f * ((float)x + 0.5f) / (float)b->width - 1.0f;
            /* Two points of the pixel's ray, finite for either depth
             * convention and an infinite far plane; the ray points ahead. */
            sr_vec3 d = sr_vec3_sub(unproject(&b->inv, cx, cy, 0.0f),
                                    unproject(&b->inv, cx, cy, -1.0f));
            float s = sr_vec3_dot(d, b->forward) < 0.0f ? -1.0f : 1.0f;
            float dir[3] = { s * d.x, s * d.y, s * d.z };
            sr_environment_background(b->env, dir, b->blur,
                                      &b->rgb[3 * ((size_t)y * b->width + x)]);
        }
    }
    return NULL;
}

sr_result render_background_draw(sr_context *ctx, sr_framebuffer *fb, const sr_environment *env,
                                 float blur, const sr_mat4 *view, const sr_mat4 *projection,
                                 float exposure, sr_tonemap_op tonemap, int threads)
{
    int w = sr_framebuffer_width(fb), h = sr_framebuffer_height(fb);
    sr_mat4 vp = sr_mat4_mul(projection, view), inv;
    if (!sr_mat4_invert(&vp, &inv)) {
        return SR_INVALID_ARG;
    }
    sr_vec3 forward = { -view->m[2], -view->m[6], -view->m[10] };
    float *rgb = malloc((size_t)w * h * 3 * sizeof *rgb);
    uint8_t *rgba = malloc((size_t)w * h * 4);
    if (!rgb || !rgba) {
        free(rgb);
        free(rgba);
        return SR_OUT_OF_MEMORY;
    }
    threads = threads < 1 ? 1 : threads > MAX_THREADS ? MAX_THREADS : threads;
    band bands[MAX_THREADS];
    pthread_t ids[MAX_THREADS];
    bool started[MAX_THREADS] = { false };
    for (int t = 0; t < threads; t++) {
        bands[t] = (band){ env, inv, forward, blur, w, h, h * t / threads, h * (t + 1) / threads,
                           rgb };
        /* The caller's thread takes the first band. */
        started[t] = t > 0 && pthread_create(&ids[t], NULL, look_up_band, &bands[t]) == 0;
    }
    for (int t = 0; t < threads; t++) {
        if (!started[t]) {
            look_up_band(&bands[t]);
        }
    }
    for (int t = 1; t < threads; t++) {
        if (started[t]) {
            pthread_join(ids[t], NULL);
        }
    }
    sr_result r = sr_tonemap(ctx, rgb, w, h, 0, rgba, 0,
                             &(sr_tonemap_desc){ .op = tonemap, .exposure = exposure,
                                                 .channels = 3 });
    if (r == SR_OK) {
        r = sr_write_pixels(ctx, fb, 0, 0, w, h, rgba, (size_t)w * 4);
    }
    free(rgb);
    free(rgba);
    return r;
}
