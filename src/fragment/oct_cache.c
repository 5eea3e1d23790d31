/* oct_cache.c - the context's cache of prefiltered radiance maps
 * (oct_cache.h): maps kept within a budget of bytes, the least recently
 * asked-for that no live program reads evicted (and freed) to make room,
 * except where that would thrash; a destroyed environment's maps out at
 * once.  Called by whoever makes and destroys the context's programs, one
 * thread at a time; the maps are the same built or shared, so the order
 * of the calls never changes a pixel. */
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
            c->hits++;
            return e->map;
        }
    }
    c->misses++;
    return NULL;
}

/* The ghost of (env, roughness), or -1. */
static int find_ghost(const sr__oct_cache *c, uint64_t env, uint32_t roughness)
{
    for (int i = 0; c->ghosts && i < SR_OCT_GHOSTS; i++) {
        const sr__oct_ghost *g = &c->ghosts[i];
        if (g->env == env && g->roughness == roughness) {
            return i;
        }
    }
    return -1;
}

/* Remember that (env, roughness), not held, was asked for at `asked`: in
 * its ghost `*at` where it has one, else in the ring's oldest slot (*at
 * becomes -1 if that was the slot it named).  Without the memory for the
 * ring it is forgotten, which costs reuse, never a pixel. */
static void note_ghost(sr_context *ctx, sr__oct_cache *c, int *at, uint64_t env,
                       uint32_t roughness, uint64_t asked)
{
    if (*at >= 0) {
        c->ghosts[*at].asked = asked;
        return;
    }
    if (!c->ghosts && !(c->ghosts = sr__calloc(ctx, SR_OCT_GHOSTS, sizeof *c->ghosts))) {
        return;
    }
    c->ghosts[c->ghost_next] = (sr__oct_ghost){ env, roughness, asked };
    c->ghost_next = (c->ghost_next + 1) % SR_OCT_GHOSTS;
}

/* Move the entries into room for `capacity`; false where the memory is
 * not there (they stay where they are). */
static bool resize(sr_context *ctx, sr__oct_cache *c, int capacity)
{
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

/* Free entry i's map and move the last entry into its place; the room
 * halves once a quarter of it is used. */
static void drop(sr_context *ctx, sr__oct_cache *c, int i)
{
    sr__oct_entry *e = &c->entries[i];
    c->bytes -= e->bytes;
    sr__free(ctx, e->map);
    *e = c->entries[--c->count];
    if (c->count == 0) {
        sr__free(ctx, c->entries);
        c->entries = NULL;
        c->capacity = 0;
    } else if (c->capacity > SR_OCT_ROOM_MIN && c->count <= c->capacity / 4) {
        (void)resize(ctx, c, c->capacity / 2 > SR_OCT_ROOM_MIN ? c->capacity / 2
                                                                : SR_OCT_ROOM_MIN);
    }
}

/* The least recently asked-for map no live program reads, or -1. */
static int lru_victim(const sr__oct_cache *c)
{
    int v = -1;
    for (int i = 0; i < c->count; i++) {
        const sr__oct_entry *e = &c->entries[i];
        if (e->users == 0 && (v < 0 || e->used < c->entries[v].used)) {
            v = i;
        }
    }
    return v;
}

bool sr__oct_cache_put(sr_context *ctx, uint64_t env, uint32_t roughness, float *map,
                       size_t bytes)
{
    sr__oct_cache *c = &ctx->oct;
    if (ctx->arena || bytes > c->budget) {
        /* An arena is a fixed budget, which a cache keeping maps after
         * their programs would wear down. */
        return false;
    }
    int ghost = find_ghost(c, env, roughness);
    while (c->bytes + bytes > c->budget) {
        int v = lru_victim(c);
        /* Asked for again after it went, this map is one of more than the
         * budget holds that the scene asks for in turn, if the victim was
         * asked for since this map last was: least-recently-used order
         * would then evict each map just before it is asked for again and
         * build every one.  Keeping the maps held serves them at least;
         * this one is built whenever it is asked for. */
        if (v < 0 || (ghost >= 0 && c->entries[v].used > c->ghosts[ghost].asked)) {
            note_ghost(ctx, c, &ghost, env, roughness, c->clock);
            return false;
        }
        sr__oct_entry *e = &c->entries[v];
        int none = -1;
        if (ghost >= 0 && ghost == c->ghost_next) {
            ghost = -1;   /* its slot takes the victim's key */
        }
        note_ghost(ctx, c, &none, e->env, e->roughness, e->used);
        drop(ctx, c, v);
    }
    if (c->count == c->capacity &&
        !resize(ctx, c, c->capacity ? 2 * c->capacity : SR_OCT_ROOM_MIN)) {
        return false;
    }
    c->entries[c->count++] = (sr__oct_entry){ env, roughness, 1, bytes, c->clock, map };
    c->bytes += bytes;
    if (ghost >= 0) {
        c->ghosts[ghost] = (sr__oct_ghost){ 0, 0, 0 };
    }
    return true;
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
    for (int i = 0; c->ghosts && i < SR_OCT_GHOSTS; i++) {
        if (c->ghosts[i].env == env) {
            c->ghosts[i] = (sr__oct_ghost){ 0, 0, 0 };
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
    sr__free(ctx, c->ghosts);
    size_t budget = c->budget;
    *c = (sr__oct_cache){ .budget = budget };
}
