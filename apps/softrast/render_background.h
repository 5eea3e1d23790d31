/* render_background.h - --background environment|blur: the environment
 * the camera sees behind the model (render_background.c). */
#ifndef SR_RENDER_BACKGROUND_H
#define SR_RENDER_BACKGROUND_H

#include "softrast.h"

/* Write into fb (after its clear, before the draws) the environment seen
 * through each pixel's centre by the camera (view, projection),
 * blurred as the specular level of roughness `blur` (0: sharp), through
 * the same exposure and tone curve as the model's shading.  Rows are
 * split over `threads` threads. */
sr_result render_background_draw(sr_context *ctx, sr_framebuffer *fb, const sr_environment *env,
                                 float blur, const sr_mat4 *view, const sr_mat4 *projection,
                                 float exposure, sr_tonemap_op tonemap, int threads);

#endif
