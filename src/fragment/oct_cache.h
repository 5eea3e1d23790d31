/* oct_cache.h - the context's cache of the pbr programs' prefiltered
 * radiance maps (fragment/pbr.c builds them), keyed on an environment's
 * serial and a roughness, within a budget of bytes
 * (sr_context_desc.radiance_cache_bytes).  Called by whoever makes and
 * destroys a context's programs and environments, one thread at a time.
 * Internal to the library. */
#ifndef SR_OCT_CACHE_H
#define SR_OCT_CACHE_H

#include "softrast.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* A map of the environment with this serial (0: destroyed while a program
 * read the map, which goes when the last such program does) at this
 * roughness (its float's bits), its size, the live programs reading it
 * (it is not evicted while they do), and when it was last asked for (the
 * cache's clock then). */
typedef struct sr__oct_entry {
    uint64_t env;
    uint32_t roughness;
    int users;
    size_t bytes;
    uint64_t used;
    float *map;
} sr__oct_entry;

/* The key of a map the cache does not hold (evicted, or turned away), and
 * when it was last asked for. */
typedef struct sr__oct_ghost {
    uint64_t env;
    uint32_t roughness;
    uint64_t asked;
} sr__oct_ghost;

/* The keys remembered: a scene that draws in turn up to this many maps
 * more than the budget holds is recognised, and thrashes no more. */
#define SR_OCT_GHOSTS 1024
/* The fewest entries the cache keeps room for once it has any. */
#define SR_OCT_ROOM_MIN 8

typedef struct sr__oct_cache {
    sr__oct_entry *entries;   /* count hold maps, room for capacity */
    int count, capacity;
    size_t bytes;             /* the maps' sizes summed: at most budget */
    size_t budget;            /* sr_context_desc.radiance_cache_bytes, resolved */
    uint64_t clock;           /* counts the look-ups: the LRU order */
    sr__oct_ghost *ghosts;    /* a ring of SR_OCT_GHOSTS, made at the first miss */
    int ghost_next;
    uint64_t hits, misses;    /* look-ups that found a map, and that did not */
} sr__oct_cache;

/* The cached map of (env, roughness), now read by one more program, or
 * NULL (then build it and offer it to sr__oct_cache_put). */
float *sr__oct_cache_get(sr_context *ctx, uint64_t env, uint32_t roughness);
/* Keep `map` (`bytes` long), just built for the look-up that missed it
 * and read by one program, for (env, roughness); false: the cache did not
 * take it, the caller frees it. */
bool sr__oct_cache_put(sr_context *ctx, uint64_t env, uint32_t roughness, float *map,
                       size_t bytes);
/* A program no longer reads the cached map `map`. */
void sr__oct_cache_release(sr_context *ctx, const float *map);
/* The environment with this serial is destroyed: its maps go now, or
 * where live programs read one, when the last of them is destroyed. */
void sr__oct_cache_forget(sr_context *ctx, uint64_t env);
/* Free every map and the cache's memory (sr_destroy_context). */
void sr__oct_cache_free(sr_context *ctx);

#endif
