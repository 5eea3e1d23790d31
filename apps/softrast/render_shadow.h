/* render_shadow.h - the key light's shadow under `softrast render`
 * (docs/shadows.md): a shadow map fitted to the framed objects' box and
 * drawn from them every frame, and the ground of --ground, a shadow
 * catcher that shows only the shadow over the background. */
#ifndef SR_RENDER_SHADOW_H
#define SR_RENDER_SHADOW_H

#include "scene.h"
#include "softrast.h"

typedef struct render_shadow {
    sr_shadow_map *map;     /* on the drawing context, or NULL */
    sr_vec3 direction;      /* the light it was fitted for */
    sr_vec3 lo, hi;         /* the box it was fitted to */
} render_shadow;

/* Fit the map (again, when the light or the box moved) and draw every
 * triangle of the framed objects into it as occluders; `direction` is the
 * way the key light travels.  Needs scene_cache_bounds. */
sr_result render_shadow_draw(sr_context *ctx, render_shadow *sh, const scene *s,
                             sr_vec3 direction);
void render_shadow_free(sr_context *ctx, render_shadow *sh);

/* Put a catcher ground (made on ctx) under the framed objects in place of
 * any object they do not frame (the teapot's checkered ground), and
 * cache the bounds again.  Needs scene_cache_bounds. */
sr_result render_ground_add(sr_context *ctx, scene *s);

/* Draw a catcher (a ground of render_ground_add) with sh's drawn map:
 * black with alpha strength x (1 - visibility) x a fade over the outer
 * half of the square, blended source-over with depth writes off, so where
 * the ground is lit the background keeps its bytes.  Draw it after the
 * opaque objects (their depth hides the ground behind them, unshaded). */
sr_result render_catcher_draw(sr_context *ctx, sr_framebuffer *fb, const sr_state *base,
                              const render_shadow *sh, const scene_object *ground,
                              const sr_mat4 *view, const sr_mat4 *projection);

#endif
