/* explain_zbuffer.c - `softrast explain zbuffer`: two triangles through
 * the z-buffer algorithm.  Depth is linear in screen space, so at each
 * covered pixel centre it is the barycentric blend of the vertex depths,
 * the weights being the exact edge functions over twice the area.  It is
 * quantized once, q = floor(z (2^16 - 1) + 1/2) for a 16-bit buffer, and
 * the LESS test compares quantized values: a fragment is drawn only where
 * its q is smaller than the one stored, and then its q is stored. */
#include "explain.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define DEPTH_MAX 65535.0   /* a D16 buffer: q in 0 .. 2^16 - 1 */

/* The first triangle's colour; the second is drawn in the frame blue. */
static const sr_rgba TRI_A = { 0.93f, 0.45f, 0.15f, 1 };
static const sr_rgba TRI_A_LIGHT = { 0.99f, 0.85f, 0.72f, 1 };
static const sr_rgba TRI_B_LIGHT = { 0.75f, 0.85f, 0.98f, 1 };

typedef struct depth_tri {
    ex_tri t;
    double z[3];     /* in the order ex_tri_setup left the vertices */
} depth_tri;

/* The quantized depth at the centre of (px, py), or -1 when the triangle
 * does not cover it.  Weight of vertex k: the edge function of the edge
 * opposite it over twice the area (edge i runs from Vi to Vi+1). */
static int64_t depth_at(const depth_tri *d, int px, int py)
{
    int64_t sx = (int64_t)px * 256 + 128, sy = (int64_t)py * 256 + 128;
    if (!ex_tri_covers(&d->t, sx, sy)) {
        return -1;
    }
    double l[3];
    ex_tri_weights(&d->t, sx, sy, l);
    double z = (d->z[0] + l[1] * (d->z[1] - d->z[0]) + l[2] * (d->z[2] - d->z[0])) * DEPTH_MAX;
    z = z < 0 ? 0 : z > DEPTH_MAX ? DEPTH_MAX : z;
    return (int64_t)floor(z + 0.5);
}

static void vertices(const depth_tri *d, sr_point2 v[3])
{
    for (int i = 0; i < 3; i++) {
        v[i] = (sr_point2){ d->t.x[i] / 256.0, d->t.y[i] / 256.0 };
    }
}

static void draw_edges(ex_canvas *c, const depth_tri *d, sr_rgba color)
{
    sr_point2 v[3];
    vertices(d, v);
    ex_outline(c, v, 3, true, color, 2);
}

/* The vertices and their labels, drawn after the cells' numbers so the
 * labels can keep clear of them. */
static void draw_marks(ex_canvas *c, const depth_tri *d, const char *name, sr_rgba color)
{
    sr_point2 v[3];
    vertices(d, v);
    for (int i = 0; i < 3; i++) {
        char label[32];
        snprintf(label, sizeof label, "%s z=%g", name, d->z[i]);
        ex_label(c, v[i], label, EX_EDGE);   /* its ground under the dot */
        ex_dot(c, v[i], c->zoom >= 20 ? 4 : c->zoom * 0.2, color);
    }
}

static void draw_tri(ex_canvas *c, const depth_tri *d, const char *name, sr_rgba color)
{
    draw_edges(c, d, color);
    draw_marks(c, d, name, color);
}

static void number(ex_canvas *c, int x, int y, int64_t q, sr_rgba color)
{
    char s[24];
    snprintf(s, sizeof s, "%lld", (long long)q);
    ex_cell_text(c, x, y, s, color);
}

sr_result explain_zbuffer(ex_canvas *c, const ex_primitive *prim)
{
    depth_tri a, b;
    ex_tri_setup_at(&a.t, a.z, prim, 0);
    ex_tri_setup_at(&b.t, b.z, prim, 3);
    int n = c->grid_w * c->grid_h;
    int64_t *depth = malloc(sizeof *depth * (size_t)n);
    int8_t *owner = malloc((size_t)n);   /* 0 background, 1 A, 2 B */
    if (!depth || !owner) {
        free(depth);
        free(owner);
        return SR_OUT_OF_MEMORY;
    }
    for (int i = 0; i < n; i++) {
        depth[i] = (int64_t)DEPTH_MAX;
        owner[i] = 0;
    }
    char cap[640];

    ex_begin(c);
    draw_tri(c, &a, "A", TRI_A);
    draw_tri(c, &b, "B", EX_INK);
    ex_end(c, "1. Two triangles, A then B, with a window depth z at each vertex (0 near, 1 far). "
              "The depth buffer (16 bits) is cleared to the far value 65535 and the test is "
              "LESS: a fragment is drawn where its depth is less than the one stored.");

    /* A: every covered pixel passes against the cleared buffer */
    /* (In each frame the cells, then the edges, then the numbers over
     * them and the labels last, each kept readable over what is under.) */
    ex_begin(c);
    int drawn_a = 0;
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            int64_t q = depth_at(&a, x, y);
            if (q >= 0) {
                int i = y * c->grid_w + x;
                depth[i] = q;
                owner[i] = 1;
                ex_cell(c, x, y, TRI_A_LIGHT);
                drawn_a++;
            }
        }
    }
    draw_edges(c, &a, TRI_A);
    for (int i = 0; i < n; i++) {
        if (owner[i] == 1) {
            number(c, i % c->grid_w, i / c->grid_w, depth[i], EX_TEXT);
        }
    }
    draw_marks(c, &a, "A", TRI_A);
    snprintf(cap, sizeof cap,
             "2. A's %d pixels: z at each centre is the barycentric blend of the vertex "
             "depths (linear in screen space), quantized once, q = floor(z x 65535 + 1/2) "
             "(printed). All pass against 65535: colour and q are written.",
             drawn_a);
    ex_end(c, cap);

    /* B: each covered pixel tested against what A left */
    ex_begin(c);
    int pass = 0, fail = 0;
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            int i = y * c->grid_w + x;
            int64_t q = depth_at(&b, x, y);
            bool passes = q >= 0 && q < depth[i];
            if (passes) {
                ex_cell(c, x, y, TRI_B_LIGHT);
            } else if (owner[i] == 1) {
                ex_cell(c, x, y, TRI_A_LIGHT);
            }
        }
    }
    draw_edges(c, &a, TRI_A);
    draw_edges(c, &b, EX_INK);
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            int i = y * c->grid_w + x;
            int64_t q = depth_at(&b, x, y);
            if (q < 0) {
                continue;
            }
            bool passes = q < depth[i];
            number(c, x, y, q, passes ? EX_TEXT : EX_BAD);
            if (passes) {
                depth[i] = q;
                owner[i] = 2;
                pass++;
            } else {
                ex_cross_above_text(c, x, y, EX_BAD);
                fail++;
            }
        }
    }
    draw_marks(c, &a, "A", TRI_A);
    draw_marks(c, &b, "B", EX_INK);
    snprintf(cap, sizeof cap,
             "3. B's pixels with B's q, each compared with the stored one: %d pass (blue, q less: "
             "B's colour and q replace A's or the background), %d fail (crossed, q not "
             "less, equal included: the pixel keeps A). The order of drawing does not "
             "matter except on ties.",
             pass, fail);
    ex_end(c, cap);

    /* the colour buffer, with the depth buffer's values */
    ex_begin(c);
    for (int i = 0; i < n; i++) {
        if (owner[i]) {
            ex_cell(c, i % c->grid_w, i / c->grid_w, owner[i] == 1 ? TRI_A : EX_INK);
        }
    }
    draw_edges(c, &a, EX_EDGE);
    draw_edges(c, &b, EX_EDGE);
    for (int i = 0; i < n; i++) {
        if (owner[i]) {
            number(c, i % c->grid_w, i / c->grid_w, depth[i], (sr_rgba){ 1, 1, 1, 1 });
        }
    }
    draw_marks(c, &a, "A", EX_EDGE);
    draw_marks(c, &b, "B", EX_EDGE);
    ex_end(c, "4. The result: in each pixel the colour of the nearest fragment and its q in the "
              "depth buffer, what sr_draw leaves in a 16-bit depth buffer (LESS test) for A "
              "then B.");
    free(depth);
    free(owner);
    return c->error;
}
