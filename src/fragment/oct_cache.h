/* oct_cache.h - the context's cache of the pbr programs' prefiltered
 * radiance maps (fragment/pbr.c builds them), keyed on an environment's
 * serial and a roughness.  Called by whoever makes and destroys a
 * context's programs and environments, one thread at a time.  Internal to
 * the library. */
#ifndef SR_OCT_CACHE_H
#define SR_OCT_CACHE_H

#include "softrast.h"

#include <stdbool.h>
#include <stdint.h>

/* A map of the environment with this serial (0: destroyed while a program
 * read the map, which goes when the last such program does) at this
 * roughness (its float's bits), the live programs reading it (it is not
 * evicted while they do), and when it was last asked for (the cache's
 * clock then). */
typedef struct sr__oct_entry {
    uint64_t env;
    uint32_t roughness;
    int users;
    uint64_t used;
    float *map;
} sr__oct_entry;

/* The key of an evicted map.  Asked for again, it says the maps drawn in
 * turn outnumber the cache's: it grows instead of evicting another. */
typedef struct sr__oct_ghost {
    uint64_t env;
    uint32_t roughness;
} sr__oct_ghost;

/* Maps are 64 KiB, allocated as they are first needed.  A cache keeps up
 * to SR_OCT_CACHE of them, and one more for each evicted map asked for
 * again, up to SR_OCT_CACHE_MAX (16 MiB): room for the distinct
 * roughnesses of a scene's materials, drawn again every frame, where a
 * stream of maps never asked for twice leaves it at SR_OCT_CACHE. */
#define SR_OCT_CACHE 32
#define SR_OCT_CACHE_MAX 256

typedef struct sr__oct_cache {
    sr__oct_entry *entries;   /* count hold maps, room for capacity */
    int count, capacity;
    int limit;                /* the maps it may keep (0: SR_OCT_CACHE) */
    uint64_t clock;           /* counts the look-ups: the LRU order */
    sr__oct_ghost ghosts[SR_OCT_CACHE_MAX];   /* a ring of the evicted keys */
    int ghost_next;
} sr__oct_cache;

/* The cached map of (env, roughness), now read by one more program, or
 * NULL (then build it and offer it to sr__oct_cache_put). */
float *sr__oct_cache_get(sr_context *ctx, uint64_t env, uint32_t roughness);
/* Keep `map`, just built and read by one program, for (env, roughness);
 * false: the cache did not take it, the caller frees it. */
bool sr__oct_cache_put(sr_context *ctx, uint64_t env, uint32_t roughness, float *map);
/* A program no longer reads the cached map `map`. */
void sr__oct_cache_release(sr_context *ctx, const float *map);
/* The environment with this serial is destroyed: its maps go now, or
 * where live programs read one, when the last of them is destroyed. */
void sr__oct_cache_forget(sr_context *ctx, uint64_t env);
/* Free every map and the cache's memory (sr_destroy_context). */
void sr__oct_cache_free(sr_context *ctx);

#endif
