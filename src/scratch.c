/* scratch.c - growing and freeing the draw scratch memory.  Vertex and
 * tile arrays grow on the application thread before a draw; chunk stores
 * may grow on the front-end workers. */
#include "scratch.h"
#include "context.h"

#include <string.h>

sr_scratch *sr__scratch_create(sr_context *ctx)
{
    return sr__calloc(ctx, 1, sizeof(sr_scratch));
}

void sr__scratch_destroy(sr_context *ctx, sr_scratch *s)
{
    if (!s) {
        return;
    }
    sr__free(ctx, s->post);
    sr__free(ctx, s->vary);
    for (int i = 0; i < SR_MAX_CHUNKS; i++) {
        sr__free(ctx, s->chunks[i].tris);
        sr__free(ctx, s->chunks[i].tile_box);
        sr__free(ctx, s->chunks[i].refs);
        sr__free(ctx, s->chunks[i].ordered);
        sr__free(ctx, s->chunks[i].bin_start);
    }
    sr__free(ctx, s->active_tiles);
    sr__free(ctx, s);
}

/* The first size is what is asked for: a one-shot render (softrast
 * render) populates every byte of its stores, so doubling from a small
 * start (a bunny chunk's 2.6 MB of records became 4 MB) cost page
 * zeroing for nothing.  Later growth doubles, so a draw that keeps
 * growing reallocates a logarithmic number of times. */
static size_t grow(size_t cap, size_t need)
{
    if (cap == 0) {
        return need > 256 ? need : 256;
    }
    size_t c = cap;
    while (c < need) {
        c = c > SIZE_MAX / 2 ? need : c * 2;
    }
    return c;
}

bool sr__scratch_reserve(sr_context *ctx, sr_scratch *s, size_t count, size_t tiles, int chunks)
{
    if (count > s->vert_cap) {
        size_t cap = grow(s->vert_cap, count);
        /* Written by the vertex stage before any read: no need to zero. */
        size_t post_bytes, vary_bytes;
        if (__builtin_mul_overflow(cap, sizeof(sr_vertex_post), &post_bytes) ||
            __builtin_mul_overflow(cap, SR_MAX_VARYINGS * sizeof(float), &vary_bytes)) {
            return false;
        }
        sr_vertex_post *post = sr__alloc_large(ctx, post_bytes);
        float *vary = sr__alloc_large(ctx, vary_bytes);
        if (!post || !vary) {
            sr__free(ctx, post);
            sr__free(ctx, vary);
            return false;
        }
        sr__free(ctx, s->post);
        sr__free(ctx, s->vary);
        s->post = post;
        s->vary = vary;
        s->vert_cap = cap;
    }
    if (tiles > s->tile_cap) {
        uint32_t *active = sr__calloc(ctx, tiles, sizeof(uint32_t));
        if (!active) {
            return false;
        }
        sr__free(ctx, s->active_tiles);
        s->active_tiles = active;
        for (int i = 0; i < SR_MAX_CHUNKS; i++) {
            sr__free(ctx, s->chunks[i].bin_start);
            s->chunks[i].bin_start = NULL;
        }
        s->tile_cap = tiles;
    }
    for (int i = 0; i < chunks; i++) {
        if (!s->chunks[i].bin_start) {
            s->chunks[i].bin_start = sr__calloc(ctx, s->tile_cap + 1, sizeof(uint32_t));
            if (!s->chunks[i].bin_start) {
                return false;
            }
        }
    }
    return true;
}

/* The tile boxes keep room for every record the store can hold, so a
 * store with room needs no second check. */
static bool reserve_boxes(sr_context *ctx, sr_chunk *c, size_t records)
{
    if (records <= c->box_cap) {
        return true;
    }
    size_t cap = grow(c->box_cap, records), bytes;
    if (__builtin_mul_overflow(cap, sizeof(uint32_t), &bytes)) {
        return false;
    }
    uint32_t *b = sr__alloc_large(ctx, bytes);
    if (!b) {
        return false;
    }
    if (c->tri_count) {
        memcpy(b, c->tile_box, (size_t)c->tri_count * sizeof(uint32_t));
    }
    sr__free(ctx, c->tile_box);
    c->tile_box = b;
    c->box_cap = cap;
    return true;
}

bool sr__chunk_reserve_tris(sr_context *ctx, sr_chunk *c, size_t records, size_t size)
{
    size_t need;
    if (__builtin_mul_overflow(records, size, &need)) {
        return false;
    }
    if (need > c->tri_bytes) {
        size_t bytes = grow(c->tri_bytes, need);
        uint8_t *t = sr__alloc_large(ctx, bytes);
        if (!t) {
            return false;
        }
        if (c->tri_count) {
            memcpy(t, c->tris, (size_t)c->tri_count * size);
        }
        sr__free(ctx, c->tris);
        c->tris = t;
        c->tri_bytes = bytes;
    }
    return reserve_boxes(ctx, c, c->tri_bytes / size);
}

bool sr__chunk_reserve_refs(sr_context *ctx, sr_chunk *c, size_t refs)
{
    if (refs <= c->ref_cap) {
        return true;
    }
    size_t cap = grow(c->ref_cap, refs);
    size_t bytes;
    if (__builtin_mul_overflow(cap, sizeof(uint32_t), &bytes)) {
        return false;
    }
    uint32_t *r = sr__alloc_large(ctx, bytes);
    if (!r) {
        return false;
    }
    sr__free(ctx, c->refs);
    c->refs = r;
    c->ref_cap = cap;
    return true;
}

bool sr__chunk_reserve_ordered(sr_context *ctx, sr_chunk *c, size_t bytes)
{
    if (bytes <= c->ordered_bytes) {
        return true;
    }
    size_t cap = grow(c->ordered_bytes, bytes);
    uint8_t *o = sr__alloc_large(ctx, cap);
    if (!o) {
        return false;
    }
    sr__free(ctx, c->ordered);
    c->ordered = o;
    c->ordered_bytes = cap;
    return true;
}
