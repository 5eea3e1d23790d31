/* assembly.h - primitive assembly and the rest of the front end (geometry
 * stage): what sr_draw hands each chunk of a batch, and the job that turns
 * the chunk's primitives into set-up records binned by tile
 * (geometry/assembly.c). */
#ifndef SR_ASSEMBLY_H
#define SR_ASSEMBLY_H

#include "context.h"
#include "pipeline.h"

/* Index i of a draw: its index array's entry, or i itself without one. */
static inline uint32_t sr__index_at(const sr_draw_desc *d, size_t i)
{
    switch (d->index_type) {
    case SR_INDEX_U8:  return ((const uint8_t *)d->indices)[i];
    case SR_INDEX_U16: return ((const uint16_t *)d->indices)[i];
    case SR_INDEX_U32: return ((const uint32_t *)d->indices)[i];
    default:           return (uint32_t)i;
    }
}

/* The front end of one chunk: what a worker needs to assemble, clip and
 * set up its primitives.  With `fused`, each chunk also runs the vertex
 * stage for its own primitives, a block at a time (see sr__run_front_end);
 * with a `window`, for the vertices its primitives use as it reaches
 * them. */
typedef struct sr_front_end {
    sr_context *ctx;
    const sr_draw_state *ds;
    const sr_draw_desc *d;
    size_t tri_size;
    int chunks;
    bool fused;
    bool shared;                      /* more than one thread: records are read on every core */
    size_t verts_per_prim;            /* fused: primitive p uses vertices k p .. k p + k - 1 */
    /* Not fused, and not 0: the vertices a primitive uses are transformed
     * into a window of this many (scratch.h), one thread. */
    size_t window;
    /* Neither: the whole-draw arrays hold vertices from this one on. */
    size_t vertex_base;
    const sr_mat4 *mvp, *mv, *nm;
} sr_front_end;

/* Where primitive assembly finds the vertex stage's output: post[i - base]
 * and vary + (i - base) nvary for vertex i - the whole draw's arrays
 * (base 0), a window of them, or a block of them on the stack. */
typedef struct sr_vertex_src {
    const sr_vertex_post *post;
    const float *vary;
    size_t base;
} sr_vertex_src;

/* The pool job for chunk `job` of a batch (arg: the sr_front_end): the
 * vertex stage for its own vertices when fused, then assembly, clipping,
 * culling and setup of its primitives, in order, and binning of the
 * records into tiles (parallel/bin.c). */
void sr__run_front_end(void *arg, int job, int thread);

#endif
