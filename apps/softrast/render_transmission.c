/* render_transmission.c - the transmission source of `softrast render
 * --pbr`: the opaque objects, the background and the shadow catcher,
 * drawn with the exposure and without the tone curve (what the program
 * reads as radiance), as the texture the transmissive parts look
 * through.  Made only for scenes that have such parts: the others draw
 * as they did. */
#include "render_transmission.h"

#include "softrast_io.h"

bool render_transmits(const sr_pbr_material *m)
{
    return m->transmission > 0.0f && !m->unlit;
}

bool render_scene_transmits(const scene *s)
{
    for (int i = 0; i < s->count; i++) {
        const scene_object *ob = &s->objects[i];
        if (!ob->part_material || !s->gltf) {
            continue;
        }
        for (size_t p = 0; p < ob->mesh.part_count; p++) {
            if (render_transmits(&s->gltf->materials[ob->part_material[p]])) {
                return true;
            }
        }
    }
    return false;
}

sr_result render_transmission_begin(sr_context *ctx, int width, int height,
                                    const sr_clear_desc *clear, sr_framebuffer **out)
{
    *out = NULL;
    sr_result r = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = width,
                                                                    .height = height,
                                                                    .depth_format = SR_DEPTH_D24 },
                                      out);
    return r == SR_OK ? sr_clear(ctx, *out, clear) : r;
}

sr_result render_transmission_finish(sr_context *ctx, const sr_framebuffer *fb, sr_texture **out)
{
    return sr_make_texture(ctx, &(sr_texture_desc){ .width = sr_framebuffer_width(fb),
                                                     .height = sr_framebuffer_height(fb),
                                                     .pixels = sr_framebuffer_pixels(fb),
                                                     .srgb = true },
                           out);
}
