/* scratch.c - growing and freeing the draw scratch memory.  Vertex and
 * tile arrays grow on the application thread before a draw; chunk stores
 * may grow on the front-end workers. */
#include "scratch.h"
#include "alloc.h"

#include <string.h>

sr_scratch *sr__scratch_create(const sr_allocator *a)
{
    return sr__mem_calloc(a, 1, sizeof(sr_scratch));
}

void sr__scratch_destroy(const sr_allocator *a, sr_scratch *s)
{
    if (!s) {
        return;
    }
    sr__mem_free(a, s->post);
    sr__mem_free(a, s->vary);
    for (int i = 0; i < SR_MAX_CHUNKS; i++) {
        sr__mem_free(a, s->chunks[i].tris);
        sr__mem_free(a, s->chunks[i].tile_box);
        sr__mem_free(a, s->chunks[i].refs);
        sr__mem_free(a, s->chunks[i].ordered);
        sr__mem_free(a, s->chunks[i].bin_start);
    }
    sr__mem_free(a, s->active_tiles);
    sr__mem_free(a, s);
}

/* The first size is what is asked for, at least `least`: a one-shot
 * render (softrast render) populates every byte of its stores, so
 * doubling from a small start (a bunny chunk's 2.6 MB of records became
 * 4 MB) cost page zeroing for nothing.  Later growth doubles, so a draw
 * that keeps growing reallocates a logarithmic number of times. */
static size_t grow(size_t cap, size_t need, size_t least)
{
    if (cap == 0) {
        return need > least ? need : least;
    }
    size_t c = cap;
    while (c < need) {
        c = c > SIZE_MAX / 2 ? need : c * 2;
    }
    return c;
}

/* Make room for `need` elements of `size` bytes in the store `old` of
 * capacity *cap elements: *out is `old` when it has room, else a larger
 * block (grow, first at least `least` elements) holding old's first
 * keep_bytes, and old is freed.  false, with `old` and *cap untouched,
 * when the block cannot be had. */
static bool grow_store(const sr_allocator *a, void *old, size_t *cap, size_t need, size_t size,
                       size_t least, size_t keep_bytes, void **out)
{
    *out = old;
    if (need <= *cap) {
        return true;
    }
    size_t n = grow(*cap, need, least), bytes;
    if (__builtin_mul_overflow(n, size, &bytes)) {
        return false;
    }
    void *p = sr__mem_alloc_large(a, bytes);
    if (!p) {
        return false;
    }
    if (keep_bytes) {
        memcpy(p, old, keep_bytes);
    }
    sr__mem_free(a, old);
    *cap = n;
    *out = p;
    return true;
}

bool sr__scratch_reserve(const sr_allocator *a, sr_scratch *s, size_t count, int nvary,
                         size_t tiles, int chunks)
{
    /* Written by the vertex stage before any read: no need to zero.  The
     * varyings take the draw's count, not the most a draw can have (a
     * Phong vertex's 10 floats, not 16), and a small draw or a vertex
     * window (geometry/assembly.c) exactly its own size. */
    size_t floats;
    if (__builtin_mul_overflow(count, (size_t)nvary, &floats)) {
        return false;
    }
    void *p;
    if (!grow_store(a, s->post, &s->vert_cap, count, sizeof(sr_vertex_post), 1, 0, &p)) {
        return false;
    }
    s->post = p;
    if (!grow_store(a, s->vary, &s->vary_cap, floats, sizeof(float), 1, 0, &p)) {
        return false;
    }
    s->vary = p;
    if (tiles > s->tile_cap) {
        uint32_t *active = sr__mem_calloc(a, tiles, sizeof(uint32_t));
        if (!active) {
            return false;
        }
        sr__mem_free(a, s->active_tiles);
        s->active_tiles = active;
        for (int i = 0; i < SR_MAX_CHUNKS; i++) {
            sr__mem_free(a, s->chunks[i].bin_start);
            s->chunks[i].bin_start = NULL;
        }
        s->tile_cap = tiles;
    }
    for (int i = 0; i < chunks; i++) {
        if (!s->chunks[i].bin_start) {
            s->chunks[i].bin_start = sr__mem_calloc(a, s->tile_cap + 1, sizeof(uint32_t));
            if (!s->chunks[i].bin_start) {
                return false;
            }
        }
    }
    return true;
}

bool sr__chunk_reserve_tris(const sr_allocator *a, sr_chunk *c, size_t records, size_t size)
{
    size_t need;
    void *p;
    if (__builtin_mul_overflow(records, size, &need) ||
        !grow_store(a, c->tris, &c->tri_bytes, need, 1, 256, (size_t)c->tri_count * size, &p)) {
        return false;
    }
    c->tris = p;
    /* The tile boxes keep room for every record the store can hold, so a
     * store with room needs no second check. */
    if (!grow_store(a, c->tile_box, &c->box_cap, c->tri_bytes / size, sizeof *c->tile_box, 256,
                    (size_t)c->tri_count * sizeof *c->tile_box, &p)) {
        return false;
    }
    c->tile_box = p;
    return true;
}

bool sr__chunk_reserve_refs(const sr_allocator *a, sr_chunk *c, size_t refs)
{
    void *p;
    if (!grow_store(a, c->refs, &c->ref_cap, refs, sizeof *c->refs, 256, 0, &p)) {
        return false;
    }
    c->refs = p;
    return true;
}

bool sr__chunk_reserve_ordered(const sr_allocator *a, sr_chunk *c, size_t bytes)
{
    void *p;
    if (!grow_store(a, c->ordered, &c->ordered_bytes, bytes, 1, 256, 0, &p)) {
        return false;
    }
    c->ordered = p;
    return true;
}
