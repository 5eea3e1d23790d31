/* render_programs.h - the physically based programs of one object's parts
 * (render.c's draw_scene), kept while its parts are drawn: the parts of a
 * glTF object that share a material share one program. */
#ifndef SR_RENDER_PROGRAMS_H
#define SR_RENDER_PROGRAMS_H

#include "softrast.h"

#include <stddef.h>

/* Programs kept at most: a program pins its prefiltered radiance maps in
 * the context's cache (fragment/oct_cache.c), which evicts only maps no
 * live program reads; 32 stay within the embedded profile's budget of 32
 * maps, which a larger table could fill with pinned maps. */
#define RENDER_PROGRAM_SLOTS 32

/* Programs by key (a glTF material's number), key % RENDER_PROGRAM_SLOTS
 * a slot; zero is empty. */
typedef struct render_programs {
    sr_pbr *program[RENDER_PROGRAM_SLOTS];
    size_t key[RENDER_PROGRAM_SLOTS];
} render_programs;

/* The program kept for key, or NULL. */
sr_pbr *render_programs_find(const render_programs *t, size_t key);

/* Keeps p for key, destroying the program its slot held. */
void render_programs_keep(sr_context *ctx, render_programs *t, size_t key, sr_pbr *p);

/* Destroys every program kept; t is empty after. */
void render_programs_clear(sr_context *ctx, render_programs *t);

#endif
