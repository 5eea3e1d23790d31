/* render_textures.h - the textures of a render job (render_textures.c). */
#ifndef SR_RENDER_TEXTURES_H
#define SR_RENDER_TEXTURES_H

#include "cli.h"
#include "render_options.h"
#include "scene.h"

/* The model's texture, or its parts' textures, onto ctx (s->objects[0]);
 * the files read are added to `inputs`.  Returns an exit status, or -1. */
int render_textures_load(const render_opts *o, sr_context *ctx, cli_inputs *inputs, scene *s);
/* Every texture render_textures_load made on ctx. */
void render_textures_free(sr_context *ctx, scene *s);

#endif
