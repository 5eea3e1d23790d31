/* scratch.c - growing and freeing the draw scratch memory (application
 * thread, between draws). */
#include "scratch.h"
#include "context.h"

#include <string.h>

sr_scratch *sr__scratch_create(sr_context *ctx)
{
    sr_scratch *s = sr__calloc(ctx, 1, sizeof *s);
    if (!s) {
        return NULL;
    }
    s->tris = sr__alloc(ctx, SR_BATCH_TRIS * sizeof(sr_tri));
    s->refs = sr__alloc(ctx, SR_BATCH_REFS * sizeof(uint32_t));
    if (!s->tris || !s->refs) {
        sr__scratch_destroy(ctx, s);
        return NULL;
    }
    return s;
}

void sr__scratch_destroy(sr_context *ctx, sr_scratch *s)
{
    if (!s) {
        return;
    }
    sr__free(ctx, s->verts);
    sr__free(ctx, s->tris);
    sr__free(ctx, s->refs);
    sr__free(ctx, s->bin_start);
    sr__free(ctx, s->bin_fill);
    sr__free(ctx, s->active_tiles);
    sr__free(ctx, s);
}

bool sr__scratch_reserve(sr_context *ctx, sr_scratch *s, size_t count, size_t tiles)
{
    if (count > s->vert_cap) {
        size_t cap = s->vert_cap ? s->vert_cap : 1024;
        while (cap < count) {
            cap = cap > SIZE_MAX / 2 ? count : cap * 2;
        }
        sr_clip_vertex *v = sr__calloc(ctx, cap, sizeof *v);
        if (!v) {
            return false;
        }
        sr__free(ctx, s->verts);
        s->verts = v;
        s->vert_cap = cap;
    }
    if (tiles > s->tile_cap) {
        uint32_t *start = sr__calloc(ctx, tiles + 1, sizeof(uint32_t));
        uint32_t *fill = sr__calloc(ctx, tiles, sizeof(uint32_t));
        uint32_t *active = sr__calloc(ctx, tiles, sizeof(uint32_t));
        if (!start || !fill || !active) {
            sr__free(ctx, start);
            sr__free(ctx, fill);
            sr__free(ctx, active);
            return false;
        }
        sr__free(ctx, s->bin_start);
        sr__free(ctx, s->bin_fill);
        sr__free(ctx, s->active_tiles);
        s->bin_start = start;
        s->bin_fill = fill;
        s->active_tiles = active;
        s->tile_cap = tiles;
    }
    return true;
}
