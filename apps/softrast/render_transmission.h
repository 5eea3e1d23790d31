/* render_transmission.h - the image transmissive glTF materials see
 * (KHR_materials_transmission, docs/pbr.md): the opaque scene drawn
 * before them into a framebuffer of its own, made into a texture
 * (render_transmission.c; render.c draws it). */
#ifndef SR_RENDER_TRANSMISSION_H
#define SR_RENDER_TRANSMISSION_H

#include "scene.h"
#include "softrast.h"

/* Whether the PBR program lets light through material m. */
bool render_transmits(const sr_pbr_material *m);
/* Whether a part of s (a glTF scene's) has such a material. */
bool render_scene_transmits(const scene *s);
/* A width x height framebuffer (depth, one sample) cleared by `clear`,
 * for the opaque scene's draw. */
sr_result render_transmission_begin(sr_context *ctx, int width, int height,
                                    const sr_clear_desc *clear, sr_framebuffer **out);
/* Its pixels as an sRGB texture with mip levels (the roughness blur);
 * the caller still destroys the framebuffer. */
sr_result render_transmission_finish(sr_context *ctx, const sr_framebuffer *fb,
                                     sr_texture **out);

#endif
