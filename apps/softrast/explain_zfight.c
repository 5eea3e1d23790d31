/* explain_zfight.c - `softrast explain zfight`: two nearly coplanar
 * triangles fighting in a quantized z-buffer, and the fix by polygon
 * offset.  A (a base) is drawn, then B (a decal on it) with the LESS test
 * in a 16-bit buffer: where their depths quantize to nearly the same q,
 * which one shows is decided pixel by pixel by the rounding, not by the
 * geometry.  Polygon offset adds one constant per triangle to B's depth,
 * o = factor m + units r, m = max(|dz/dx|, |dz/dy|) the slope of its plane
 * and r = 1/(2^16 - 1) the buffer's step (docs/raster-rules.md 6.4);
 * factor and units below zero pull B forward, and it wins everywhere.
 * Every q shown is the library's: read back (sr_read_depth) from a buffer
 * sr_draw drew the triangle into. */
#include "explain.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DEPTH_MAX 65535.0   /* D16: q in 0 .. 2^16 - 1 */

static const sr_rgba TRI_A = { 0.93f, 0.45f, 0.15f, 1 };
static const sr_rgba TRI_A_LIGHT = { 0.99f, 0.85f, 0.72f, 1 };
static const sr_rgba TRI_B_LIGHT = { 0.75f, 0.85f, 0.98f, 1 };

/* Triangle `first` (0: A, 3: B) of prim drawn alone, or both A then B
 * (both), into fb with a D16 buffer cleared to 1; B offset by
 * (factor, units) when `offset`.  The colour buffer: A orange, B blue. */
static sr_result draw(ex_canvas *c, const ex_primitive *prim, int first, bool both,
                      bool offset, sr_framebuffer *fb)
{
    sr_clear(c->ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 }, .depth = 1 });
    sr_result r = SR_OK;
    for (int t = both ? 0 : first / 3; t <= (both ? 1 : first / 3) && r == SR_OK; t++) {
        float pos[9];
        for (int i = 0; i < 3; i++) {
            const sr_point2 *p = &prim->pts[3 * t + i];
            pos[3 * i] = (float)(2 * p->x / c->grid_w - 1);
            pos[3 * i + 1] = (float)(1 - 2 * p->y / c->grid_h);
            pos[3 * i + 2] = (float)(2 * prim->z[3 * t + i] - 1);
        }
        sr_rgba col = t == 0 ? TRI_A : EX_INK;
        sr_state st = { .shading = SR_SHADING_UNLIT,
                        .material = { .diffuse = { col.r, col.g, col.b } } };
        if (t == 1 && offset) {
            st.offset = (sr_polygon_offset){ .factor = (float)prim->offset[0],
                                             .units = (float)prim->offset[1], .fill = true };
        }
        r = sr_draw(c->ctx, fb, &st, &(sr_draw_desc){ .positions = pos, .vertex_count = 3 });
    }
    return r;
}

/* The quantized depth of each pixel the colour buffer has (alpha > 0),
 * else -1. */
static sr_result depths(ex_canvas *c, sr_framebuffer *fb, float *tmp, int64_t *q)
{
    sr_result r = sr_read_depth(c->ctx, fb, 0, 0, c->grid_w, c->grid_h, tmp, (size_t)c->grid_w);
    const uint8_t *px = sr_framebuffer_pixels(fb);
    for (int i = 0; i < c->grid_w * c->grid_h; i++) {
        q[i] = px[4 * i + 3] ? (int64_t)llround(tmp[i] * DEPTH_MAX) : -1;
    }
    return r;
}

/* Which triangle each pixel shows: 0 none, 1 A, 2 B. */
static void owners(const ex_canvas *c, sr_framebuffer *fb, int8_t *own)
{
    const uint8_t *px = sr_framebuffer_pixels(fb);
    for (int i = 0; i < c->grid_w * c->grid_h; i++) {
        own[i] = !px[4 * i + 3] ? 0 : px[4 * i + 2] > px[4 * i] ? 2 : 1;
    }
}

static void number(ex_canvas *c, int i, int64_t q, sr_rgba color)
{
    char s[24];
    snprintf(s, sizeof s, "%lld", (long long)q);
    ex_cell_text(c, i % c->grid_w, i / c->grid_w, s, color);
}

/* The two outlines (and with labels, the vertices named); dark over the
 * result's cells, which are in the triangles' colours. */
static void outlines(ex_canvas *c, const ex_primitive *prim, bool labels, bool dark)
{
    for (int t = 0; t < 2; t++) {
        sr_rgba col = dark ? EX_EDGE : t == 0 ? TRI_A : EX_INK;
        ex_outline(c, &prim->pts[3 * t], 3, true, col, 2);
        for (int i = 0; labels && i < 3; i++) {
            char label[32];
            snprintf(label, sizeof label, "%s z=%g", t ? "B" : "A", prim->z[3 * t + i]);
            ex_label(c, prim->pts[3 * t + i], label, EX_EDGE);
            ex_dot(c, prim->pts[3 * t + i], c->zoom >= 20 ? 4 : c->zoom * 0.2, col);
        }
    }
}

/* B's depth slope m in depth-range units per pixel, from its vertices
 * snapped as the rasterizer snaps them (the library's formula). */
static double slope(const ex_primitive *prim)
{
    double x[3], y[3], z[3];
    for (int i = 0; i < 3; i++) {
        x[i] = (double)ex_snap(prim->pts[3 + i].x);
        y[i] = (double)ex_snap(prim->pts[3 + i].y);
        z[i] = prim->z[3 + i];
    }
    double dx1 = x[1] - x[0], dy1 = y[1] - y[0], dx2 = x[2] - x[0], dy2 = y[2] - y[0];
    double area2 = dx1 * dy2 - dy1 * dx2;
    if (area2 == 0) {
        return 0;
    }
    double dz1 = z[1] - z[0], dz2 = z[2] - z[0];
    double dzdx = (dz1 * dy2 - dz2 * dy1) * 256 / area2;
    double dzdy = (dx1 * dz2 - dx2 * dz1) * 256 / area2;
    return fmax(fabs(dzdx), fabs(dzdy));
}

/* A frame of B's q at each pixel it covers, tested against A's. */
static int test_frame(ex_canvas *c, const ex_primitive *prim, const int64_t *qa,
                      const int64_t *qb, int *fail_out)
{
    int n = c->grid_w * c->grid_h, pass = 0, fail = 0;
    ex_begin(c);
    for (int i = 0; i < n; i++) {
        bool passes = qb[i] >= 0 && (qa[i] < 0 || qb[i] < qa[i]);
        if (passes) {
            ex_cell(c, i % c->grid_w, i / c->grid_w, TRI_B_LIGHT);
        } else if (qa[i] >= 0) {
            ex_cell(c, i % c->grid_w, i / c->grid_w, TRI_A_LIGHT);
        }
    }
    outlines(c, prim, false, false);
    for (int i = 0; i < n; i++) {
        if (qb[i] < 0) {
            continue;
        }
        bool passes = qa[i] < 0 || qb[i] < qa[i];
        number(c, i, qb[i], passes ? EX_TEXT : EX_BAD);
        if (passes) {
            pass++;
        } else {
            ex_cross_above_text(c, i % c->grid_w, i / c->grid_w, EX_BAD);
            fail++;
        }
    }
    outlines(c, prim, true, false);
    *fail_out = fail;
    return pass;
}

/* The colour buffer after A then B, each pixel's stored q printed. */
static void result_frame(ex_canvas *c, const ex_primitive *prim, const int8_t *own,
                         const int64_t *q)
{
    ex_begin(c);
    for (int i = 0; i < c->grid_w * c->grid_h; i++) {
        if (own[i]) {
            ex_cell(c, i % c->grid_w, i / c->grid_w, own[i] == 1 ? TRI_A : EX_INK);
        }
    }
    outlines(c, prim, false, true);
    for (int i = 0; i < c->grid_w * c->grid_h; i++) {
        if (own[i]) {
            number(c, i, q[i], (sr_rgba){ 1, 1, 1, 1 });
        }
    }
    outlines(c, prim, true, true);
}

sr_result explain_zfight(ex_canvas *c, const ex_primitive *prim)
{
    int n = c->grid_w * c->grid_h;
    sr_framebuffer *fb = NULL;
    float *tmp = malloc(sizeof *tmp * (size_t)n);
    int64_t *qa = malloc(sizeof *qa * (size_t)n * 4);
    int8_t *own = malloc((size_t)n * 2);
    sr_result r = tmp && qa && own ? SR_OK : SR_OUT_OF_MEMORY;
    if (r == SR_OK) {
        r = sr_make_framebuffer(c->ctx, &(sr_framebuffer_desc){ .width = c->grid_w,
                                                                .height = c->grid_h,
                                                                .depth_format = SR_DEPTH_D16 },
                                &fb);
    }
    int64_t *qb = qa + n, *qbo = qa + 2 * n, *qres = qa + 3 * n;
    int8_t *own_o = own ? own + n : NULL;
    /* A alone, B alone, B offset alone, then A and B together twice */
    r = r == SR_OK ? draw(c, prim, 0, false, false, fb) : r;
    r = r == SR_OK ? depths(c, fb, tmp, qa) : r;
    r = r == SR_OK ? draw(c, prim, 3, false, false, fb) : r;
    r = r == SR_OK ? depths(c, fb, tmp, qb) : r;
    r = r == SR_OK ? draw(c, prim, 3, false, true, fb) : r;
    r = r == SR_OK ? depths(c, fb, tmp, qbo) : r;
    if (r != SR_OK) {
        sr_destroy_framebuffer(c->ctx, fb);
        free(tmp);
        free(qa);
        free(own);
        return c->error = r;
    }
    char cap[900];

    ex_begin(c);
    outlines(c, prim, true, false);
    ex_end(c, "1. Two nearly coplanar triangles, A (a base) then B (a decal on it), with a window "
              "depth z at each vertex. The depth buffer has 16 bits: z is quantized once, q = "
              "floor(z x 65535 + 1/2), and B is drawn where its q is LESS than the q stored.");

    ex_begin(c);
    int drawn_a = 0;
    for (int i = 0; i < n; i++) {
        if (qa[i] >= 0) {
            ex_cell(c, i % c->grid_w, i / c->grid_w, TRI_A_LIGHT);
            drawn_a++;
        }
    }
    outlines(c, prim, false, false);
    for (int i = 0; i < n; i++) {
        if (qa[i] >= 0) {
            number(c, i, qa[i], EX_TEXT);
        }
    }
    outlines(c, prim, true, false);
    snprintf(cap, sizeof cap,
             "2. A's %d pixels and their q, as sr_draw stores them: all pass against the cleared "
             "65535.", drawn_a);
    ex_end(c, cap);

    int fail, pass = test_frame(c, prim, qa, qb, &fail);
    snprintf(cap, sizeof cap,
             "3. B's q at its pixels against A's: %d pass, %d fail (crossed: q not less, equal "
             "included). The two planes are closer than the buffer resolves, so which wins is "
             "decided pixel by pixel by the rounding: z-fighting.",
             pass, fail);
    ex_end(c, cap);

    r = draw(c, prim, 0, true, false, fb);
    r = r == SR_OK ? depths(c, fb, tmp, qres) : r;
    owners(c, fb, own);
    int lost = 0;
    for (int i = 0; i < n; i++) {
        lost += qb[i] >= 0 && own[i] == 1;
    }
    result_frame(c, prim, own, qres);
    snprintf(cap, sizeof cap,
             "4. The result, what sr_draw leaves for A then B: B shows through in patches, %d of "
             "its pixels lost to A.", lost);
    ex_end(c, cap);

    double m = slope(prim), o = prim->offset[0] * m + prim->offset[1] / DEPTH_MAX;
    pass = test_frame(c, prim, qa, qbo, &fail);
    snprintf(cap, sizeof cap,
             "5. Polygon offset on B: o = factor m + units r with m = max(|dz/dx|, |dz/dy|) = "
             "%.3g, B's depth slope per pixel, and r = 1/65535, the buffer's step: o = %g x %.3g "
             "+ %g x 1/65535 = %.3g (%.3g steps), added to B's depth before the test. %d pass, "
             "%d fail.",
             m, prim->offset[0], m, prim->offset[1], o, o * DEPTH_MAX, pass, fail);
    ex_end(c, cap);

    r = r == SR_OK ? draw(c, prim, 0, true, true, fb) : r;
    r = r == SR_OK ? depths(c, fb, tmp, qres) : r;
    owners(c, fb, own_o);
    lost = 0;
    for (int i = 0; i < n; i++) {
        lost += qbo[i] >= 0 && own_o[i] == 1;
    }
    result_frame(c, prim, own_o, qres);
    snprintf(cap, sizeof cap,
             "6. The result with the offset, what sr_draw leaves with sr_state.offset = { factor "
             "%g, units %g } on B: %d of B's pixels lost to A.",
             prim->offset[0], prim->offset[1], lost);
    ex_end(c, cap);

    sr_destroy_framebuffer(c->ctx, fb);
    free(tmp);
    free(qa);
    free(own);
    return c->error != SR_OK ? c->error : r;
}
