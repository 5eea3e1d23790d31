/* oct_cache.c - the context's cache of prefiltered radiance maps
 * (oct_cache.h): least recently asked-for maps out, where no live program
 * reads them, growth where evicted maps are asked for again, and a
 * destroyed environment's maps out at once.  Called
 * by whoever makes and destroys the context's programs, one thread at a
 * time; the maps are the same built or shared, so the order of the calls
 * never changes a pixel. */
#include "context.h"

#include <string.h>

float *sr__oct_cache_get(sr_context *ctx, uint64_t env, uint32_t roughness)
{
    sr__oct_cache *c = &ctx->oct;
    uint64_t now = ++c->clock;
    for (int i = 0; i < c->count; i++) {
        sr__oct_entry *e = &c->entries[i];
        if (e->env == env && e->roughness == roughness) {
            e->users++;
            e->used = now;
            return e->map;
        }
    }
    return NULL;
}

/* Whether (env, roughness) was evicted not long ago (its ghost goes). */
static bool ghost_taken(sr__oct_cache *c, uint64_t env, uint32_t roughness)
{
    for (int i = 0; i < SR_OCT_CACHE_MAX; i++) {
        sr__oct_ghost *g = &c->ghosts[i];
        if (g->env == env && g->roughness == roughness) {
            *g = (sr__oct_ghost){ 0, 0 };
            return true;
        }
    }
    return false;
}

/* Room for one more entry; false where the memory is not there. */
static bool make_room(sr_context *ctx, sr__oct_cache *c)
{
    if (c->count < c->capacity) {
        return true;
    }
    int capacity = c->capacity ? 2 * c->capacity : SR_OCT_CACHE;
    capacity = capacity < SR_OCT_CACHE_MAX ? capacity : SR_OCT_CACHE_MAX;
    sr__oct_entry *entries = sr__calloc(ctx, (size_t)capacity, sizeof *entries);
    if (!entries) {
        return false;
    }
    if (c->count) {
        memcpy(entries, c->entries, (size_t)c->count * sizeof *entries);
    }
    sr__free(ctx, c->entries);
    c->entries = entries;
    c->capacity = capacity;
    return true;
}

bool sr__oct_cache_put(sr_context *ctx, uint64_t env, uint32_t roughness, float *map)
{
    sr__oct_cache *c = &ctx->oct;
    if (ctx->arena) {
        /* A fixed budget, which a cache keeping maps after their programs
         * would wear down. */
        return false;
    }
    int limit = c->limit ? c->limit : SR_OCT_CACHE;
    /* A full cache that evicted this very map: the scene draws more maps
     * in turn than it holds, and least-recently-used order would evict
     * each just before it is asked for again. */
    if (c->count >= limit && limit < SR_OCT_CACHE_MAX && ghost_taken(c, env, roughness)) {
        limit++;
    }
    c->limit = limit;
    sr__oct_entry *slot = NULL;
    if (c->count < limit && make_room(ctx, c)) {
        slot = &c->entries[c->count++];
    } else {
        /* The least recently asked-for map no live program reads. */
        for (int i = 0; i < c->count; i++) {
            sr__oct_entry *e = &c->entries[i];
            if (e->users == 0 && (!slot || e->used < slot->used)) {
                slot = e;
            }
        }
        if (!slot) {
            return false;
        }
        c->ghosts[c->ghost_next] = (sr__oct_ghost){ slot->env, slot->roughness };
        c->ghost_next = (c->ghost_next + 1) % SR_OCT_CACHE_MAX;
        sr__free(ctx, slot->map);
    }
    *slot = (sr__oct_entry){ env, roughness, 1, c->clock, map };
    return true;
}

/* Free entry i's map and move the last entry into its place. */
static void drop(sr_context *ctx, sr__oct_cache *c, int i)
{
    sr__free(ctx, c->entries[i].map);
    c->entries[i] = c->entries[--c->count];
}

void sr__oct_cache_release(sr_context *ctx, const float *map)
{
    sr__oct_cache *c = &ctx->oct;
    for (int i = 0; i < c->count; i++) {
        sr__oct_entry *e = &c->entries[i];
        if (e->map == map && e->users > 0) {
            if (--e->users == 0 && e->env == 0) {
                drop(ctx, c, i);
            }
            return;
        }
    }
}

void sr__oct_cache_forget(sr_context *ctx, uint64_t env)
{
    sr__oct_cache *c = &ctx->oct;
    for (int i = 0; i < c->count;) {
        sr__oct_entry *e = &c->entries[i];
        if (e->env != env) {
            i++;
        } else if (e->users > 0) {
            e->env = 0;
            i++;
        } else {
            drop(ctx, c, i);
        }
    }
    for (int i = 0; i < SR_OCT_CACHE_MAX; i++) {
        if (c->ghosts[i].env == env) {
            c->ghosts[i] = (sr__oct_ghost){ 0, 0 };
        }
    }
}

void sr__oct_cache_free(sr_context *ctx)
{
    sr__oct_cache *c = &ctx->oct;
    for (int i = 0; i < c->count; i++) {
        sr__free(ctx, c->entries[i].map);
    }
    sr__free(ctx, c->entries);
    *c = (sr__oct_cache){ 0 };
}
