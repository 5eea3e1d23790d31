/* shadow.h - the shadow map shared by its maker (shadow_map.c) and its
 * lookup (shadow_lookup.c), fragment stage.  The map is the depth of a
 * D24 framebuffer drawn through sr_draw; the lookup reads its depth words
 * directly (k for the depth k / (2^24 - 1)). */
#ifndef SR_SHADOW_H
#define SR_SHADOW_H

#include "softrast.h"

/* The lookup first compares against the nearest and farthest depth of the
 * 8x8-texel blocks its filter box touches: a point nearer than every
 * texel there is lit, farther than every one in shadow, and only points
 * in a penumbra read the texels one by one. */
#define SR_SHADOW_BLOCK_ORDER 3
#define SR_SHADOW_BLOCK_SIZE (1 << SR_SHADOW_BLOCK_ORDER)
/* The widest filter: half-width in texels. */
#define SR_SHADOW_MAX_RADIUS 8.0f

struct sr_shadow_map {
    sr_framebuffer *fb;          /* size x size, D24; its color is never read */
    const uint32_t *depth;       /* fb->depth: every pending clear carried out */
    int size;
    int blocks;                  /* blocks a side: size / SR_SHADOW_BLOCK_SIZE, rounded up */
    uint32_t *block_min, *block_max;  /* per block, row-major: its texels' extremes */
    sr_mat4 view, projection;    /* world -> light eye -> clip, depth in [0, 1] */
    /* World -> map: texel x (0 at the left edge), texel y (0 at the top),
     * window depth; rows of an affine map (the projection is orthographic). */
    float to_map[3][4];
    sr_vec3 toward_light;        /* unit, against the light's direction */
    float texel_size;            /* world units a texel spans */
    float filter_radius;         /* texels */
    float normal_offset;         /* texels */
    float light_tan;             /* tan of the light's angular radius; 0: fixed filter */
    float depth_extent;          /* world units from window depth 0 to 1 */
    float offset_factor, offset_units, offset_clamp;
};

#endif
