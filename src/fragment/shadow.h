/* shadow.h - the shadow map shared by its maker (shadow_map.c) and its
 * lookup (shadow_lookup.c), fragment stage.  The map is a depth-only
 * D32F framebuffer drawn through sr_draw; the lookup reads its depth
 * words directly (non-negative float bits, which order like integers). */
#ifndef SR_SHADOW_H
#define SR_SHADOW_H

#include "softrast.h"

struct sr_shadow_map {
    sr_framebuffer *fb;          /* size x size, D32F, color never written */
    const uint32_t *depth;       /* fb->depth: every pending clear carried out */
    int size;
    sr_mat4 view, projection;    /* world -> light eye -> clip, depth in [0, 1] */
    /* World -> map: texel x (0 at the left edge), texel y (0 at the top),
     * window depth; rows of an affine map (the projection is orthographic). */
    float to_map[3][4];
    sr_vec3 toward_light;        /* unit, against the light's direction */
    float texel_size;            /* world units a texel spans */
    float filter_radius;         /* texels */
    float normal_offset;         /* texels */
    float offset_factor, offset_units, offset_clamp;
};

#endif
