/* uv_sphere.h - the glTF compression tests' model: a unit sphere of
 * latitude rings with normals and texture coordinates, the seam's
 * vertices doubled.  Internal to tests. */
#ifndef SR_TEST_UV_SPHERE_H
#define SR_TEST_UV_SPHERE_H

#include "gltf_write.h"
#include "wbuf.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

enum { STACKS = 24, SLICES = 48, VERTS = (STACKS + 1) * (SLICES + 1) };

typedef struct sphere {
    float pos[VERTS][3], nrm[VERTS][3], uv[VERTS][2];
    uint32_t idx[STACKS * SLICES * 6];
    size_t index_count;
} sphere;

/* A unit sphere of latitude rings, poles without degenerate triangles,
 * counter-clockwise seen from outside. */
static inline void make_sphere(sphere *s)
{
    for (int i = 0; i <= STACKS; i++) {
        for (int j = 0; j <= SLICES; j++) {
            int v = i * (SLICES + 1) + j;
            double th = M_PI * i / STACKS, ph = 2 * M_PI * j / SLICES;
            float p[3] = { (float)(sin(th) * cos(ph)), (float)cos(th),
                           (float)(-sin(th) * sin(ph)) };
            memcpy(s->pos[v], p, sizeof p);
            memcpy(s->nrm[v], p, sizeof p);
            s->uv[v][0] = (float)j / SLICES;
            s->uv[v][1] = (float)i / STACKS;
        }
    }
    size_t n = 0;
    for (uint32_t i = 0; i < STACKS; i++) {
        for (uint32_t j = 0; j < SLICES; j++) {
            uint32_t a = i * (SLICES + 1) + j, b = a + SLICES + 1;
            if (i != 0) {
                s->idx[n++] = a, s->idx[n++] = b, s->idx[n++] = a + 1;
            }
            if (i != STACKS - 1) {
                s->idx[n++] = a + 1, s->idx[n++] = b, s->idx[n++] = b + 1;
            }
        }
    }
    s->index_count = n;
}

/* The sphere's float positions, normals and coordinates appended to b,
 * little-endian, as a glTF buffer holds them. */
static inline void put_sphere_attributes(wbuf *b, const sphere *s)
{
    uint8_t tmp[VERTS * 12];
    le_copy(tmp, s->pos, VERTS * 3, 4);
    wb_put(b, tmp, VERTS * 12);
    le_copy(tmp, s->nrm, VERTS * 3, 4);
    wb_put(b, tmp, VERTS * 12);
    le_copy(tmp, s->uv, VERTS * 2, 4);
    wb_put(b, tmp, VERTS * 8);
}

#endif
