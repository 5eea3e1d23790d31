/* render_programs.c - the physically based programs of one object's parts,
 * kept while they are drawn (render_programs.h).  A program is read-only
 * once made, so drawing with one made for an earlier part of the same
 * material gives the same pixels as a new one; making it cost some 11,000
 * instructions, a good part of a small part's whole draw.  The render
 * job's thread alone. */
#include "render_programs.h"

sr_pbr *render_programs_find(const render_programs *t, size_t key)
{
    size_t slot = key % RENDER_PROGRAM_SLOTS;
    return t->program[slot] && t->key[slot] == key ? t->program[slot] : NULL;
}

void render_programs_keep(sr_context *ctx, render_programs *t, size_t key, sr_pbr *p)
{
    size_t slot = key % RENDER_PROGRAM_SLOTS;
    if (t->program[slot] != p) {
        sr_destroy_pbr_program(ctx, t->program[slot]);
    }
    t->program[slot] = p;
    t->key[slot] = key;
}

void render_programs_clear(sr_context *ctx, render_programs *t)
{
    for (size_t i = 0; i < RENDER_PROGRAM_SLOTS; i++) {
        sr_destroy_pbr_program(ctx, t->program[i]);
    }
    *t = (render_programs){ 0 };
}
