/* fuzz_mesh.h - what every reader's fuzz target checks of a parsed mesh:
 * a reader either fails with a message, or returns a mesh whose indices
 * are all in range, whose arrays hold vertex_count entries (ASan checks
 * the sizes when they are read here) and whose parts, if any, cover its
 * triangles in order.  Internal to tests/fuzz. */
#ifndef SR_FUZZ_MESH_H
#define SR_FUZZ_MESH_H

#include "softrast.h"
#include "softrast_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FUZZ_CHECK(cond)                                                     \
    do {                                                                     \
        if (!(cond)) {                                                       \
            fprintf(stderr, "%s:%d: fuzz invariant failed: %s\n", __FILE__, \
                    __LINE__, #cond);                                        \
            abort();                                                         \
        }                                                                    \
    } while (0)

/* The context that owns the meshes: made once, kept for the process. */
static inline sr_context *fuzz_context(void)
{
    static sr_context *ctx;
    if (!ctx) {
        FUZZ_CHECK(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    }
    return ctx;
}

static inline void fuzz_check_mesh(sr_result r, sr_mesh *m, const sr_io_error *err)
{
    if (r != SR_OK) {
        FUZZ_CHECK(r > SR_OK && r < SR_RESULT_COUNT);
        FUZZ_CHECK(err->message[0] != '\0');
        FUZZ_CHECK(memchr(err->message, '\0', sizeof err->message) != NULL);
        FUZZ_CHECK(strchr(err->message, '\n') == NULL);
        FUZZ_CHECK(m->positions == NULL && m->indices == NULL);
        return;
    }
    FUZZ_CHECK(m->vertex_count <= SR_IO_MAX_VERTICES);
    FUZZ_CHECK(m->triangle_count <= SR_IO_MAX_TRIANGLES);
    FUZZ_CHECK(m->vertex_count == 0 || m->positions != NULL);
    FUZZ_CHECK(m->triangle_count == 0 || m->indices != NULL);
    volatile float sink = 0;
    for (size_t i = 0; i < m->vertex_count; i++) {
        sink += m->positions[i * 3 + 2];
        if (m->normals) sink += m->normals[i * 3 + 2];
        if (m->colors) sink += m->colors[i * 4 + 3];
        if (m->texcoords) sink += m->texcoords[i * 2 + 1];
    }
    (void)sink;
    for (size_t i = 0; i < m->triangle_count * 3; i++) {
        FUZZ_CHECK(m->indices[i] < m->vertex_count);
    }
    /* Parts, when there are any, cover the triangles in order, one after
     * another (each at least one triangle). */
    FUZZ_CHECK((m->parts == NULL) == (m->part_count == 0));
    for (size_t p = 0, next = 0; p < m->part_count; p++) {
        FUZZ_CHECK(m->parts[p].first_triangle == next && m->parts[p].triangle_count > 0);
        next += m->parts[p].triangle_count;
        FUZZ_CHECK(p + 1 < m->part_count || next == m->triangle_count);
    }
    if (m->vertex_count > 0 && m->triangle_count > 0) {
        sr_vec3 lo, hi;
        FUZZ_CHECK(sr_mesh_bounds(m, &lo, &hi));
        /* Computed normals replace the file's: exercises the mesh code on
         * whatever geometry the reader accepted. */
        sr_result rn = sr_mesh_compute_normals(fuzz_context(), m,
                                               (m->triangle_count & 1) ? SR_NORMALS_FLAT
                                                                       : SR_NORMALS_SMOOTH);
        FUZZ_CHECK(rn == SR_OK || rn == SR_OUT_OF_MEMORY || rn == SR_TOO_LARGE);
    }
    sr_destroy_mesh(fuzz_context(), m);
}

#endif
