/* explain_perspective.c - `softrast explain perspective`: one span of a
 * triangle whose vertices lie at different eye distances w, its colours
 * interpolated two ways.  Affine (screen-space) interpolation weights the
 * vertex values by the barycentric weights l_i of the pixel centre on the
 * screen; but the perspective divide does not preserve distances, so the
 * weights of the point on the 3D triangle are l_i / w_i, normalized:
 * interpolate a/w and 1/w linearly on the screen and divide per pixel.
 * The pipeline does the latter (SR_INTERP_AFFINE does the former). */
#include "explain.h"

#include <math.h>
#include <stdio.h>

static const sr_rgba VERTEX_COLOR[3] = { { 1, 0, 0, 1 }, { 0, 1, 0, 1 }, { 0, 0, 1, 1 } };
static const sr_rgba COVERED = { 0.90f, 0.90f, 0.90f, 1 };

typedef struct persp {
    ex_tri t;
    double w[3];
    int swap;     /* whether V1 and V2 were swapped: the colours follow */
} persp;

/* The weights of pixel (px, py)'s centre, affine or perspective-correct;
 * false when the triangle does not cover it. */
static bool weights(const persp *p, int px, int py, bool correct, double l[3])
{
    int64_t sx = (int64_t)px * 256 + 128, sy = (int64_t)py * 256 + 128;
    if (!ex_tri_covers(&p->t, sx, sy)) {
        return false;
    }
    ex_tri_weights(&p->t, sx, sy, l);
    if (correct) {
        double s = 0;
        for (int i = 0; i < 3; i++) {
            l[i] /= p->w[i];
            s += l[i];
        }
        for (int i = 0; i < 3; i++) {
            l[i] /= s;
        }
    }
    return true;
}

/* The colour of vertex i in the order ex_tri_setup left them. */
static sr_rgba vcolor(const persp *p, int i)
{
    return VERTEX_COLOR[p->swap && i ? 3 - i : i];
}

static sr_rgba blend(const persp *p, const double l[3])
{
    sr_rgba c = { 0, 0, 0, 1 };
    for (int i = 0; i < 3; i++) {
        sr_rgba v = vcolor(p, i);
        c.r += (float)(l[i] * v.r);
        c.g += (float)(l[i] * v.g);
        c.b += (float)(l[i] * v.b);
    }
    return c;
}

static void draw_tri(ex_canvas *c, const persp *p, int row)
{
    sr_point2 v[3];
    for (int i = 0; i < 3; i++) {
        v[i] = (sr_point2){ p->t.x[i] / 256.0, p->t.y[i] / 256.0 };
    }
    ex_outline(c, v, 3, true, EX_EDGE, 1.5);
    if (row >= 0) {   /* -1: no span */
        ex_segment(c, (sr_point2){ 0, row + 0.5 }, (sr_point2){ c->grid_w, row + 0.5 }, EX_HILITE,
                   1.5);
    }
    for (int i = 0; i < 3; i++) {
        char label[32];
        snprintf(label, sizeof label, "w=%g", p->w[i]);
        ex_dot(c, v[i], c->zoom >= 20 ? 5 : c->zoom * 0.25, vcolor(p, i));
        ex_label(c, v[i], label, EX_EDGE);
    }
}

/* The triangle's pixels: the span's coloured by the interpolation, the
 * weight of the green vertex printed; the others grey, or all coloured. */
static int fill(ex_canvas *c, const persp *p, int row, bool correct, bool all, double *gw,
                int *gx)
{
    int n = 0;
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            double l[3];
            if (!weights(p, x, y, correct, l)) {
                continue;
            }
            if (!all && y != row) {
                ex_cell(c, x, y, COVERED);
                continue;
            }
            sr_rgba col = blend(p, l);
            ex_cell(c, x, y, col);
            if (y == row) {
                char s[16];
                double g = col.g;
                snprintf(s, sizeof s, "%.2f", g);
                ex_cell_text(c, x, y, s + (g < 1), (sr_rgba){ 1, 1, 1, 1 });
                gx[n] = x;
                gw[n++] = g;
            }
        }
    }
    return n;
}

/* The triangle as sr_fill_gouraud's FillPoly/FillSpan fills it, read back
 * from a framebuffer of the grid's size: the incremental scan-line
 * interpolation of explain_fillpoly.c, the vertex colours stepped in
 * screen space. */
static void fill_fillspan(ex_canvas *c, const persp *p)
{
    sr_framebuffer *fb = NULL;
    sr_result r = sr_make_framebuffer(c->ctx, &(sr_framebuffer_desc){
                                                  .width = c->grid_w, .height = c->grid_h,
                                                  .depth_format = SR_DEPTH_NONE },
                                      &fb);
    sr_point2 v[3];
    sr_rgba col[3];
    for (int i = 0; i < 3; i++) {
        v[i] = (sr_point2){ p->t.x[i] / 256.0, p->t.y[i] / 256.0 };
        col[i] = vcolor(p, i);
    }
    if (r == SR_OK) {
        sr_clear(c->ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
        r = sr_fill_gouraud(c->ctx, fb, &(sr_polygon2){ v, 3, NULL, 0 }, col,
                            &(sr_gouraud_desc){ .method = SR_GOURAUD_INCREMENTAL });
    }
    if (r != SR_OK) {
        c->error = c->error ? c->error : r;
    } else {
        const uint8_t *px = sr_framebuffer_pixels(fb);
        for (int i = 0; i < c->grid_w * c->grid_h; i++) {
            const uint8_t *q = px + (size_t)i * 4;
            if (q[3]) {   /* filled: the clear left alpha 0 */
                ex_cell(c, i % c->grid_w, i / c->grid_w,
                        (sr_rgba){ q[0] / 255.0f, q[1] / 255.0f, q[2] / 255.0f, 1 });
            }
        }
    }
    sr_destroy_framebuffer(c->ctx, fb);
}

sr_result explain_perspective(ex_canvas *c, const ex_primitive *prim)
{
    persp p;
    p.swap = ex_tri_setup_at(&p.t, p.w, prim, 0);
    int row = prim->row;
    if (row < 0) {   /* the middle of the triangle */
        int64_t lo = p.t.y[0], hi = p.t.y[0];
        for (int i = 1; i < 3; i++) {
            lo = p.t.y[i] < lo ? p.t.y[i] : lo;
            hi = p.t.y[i] > hi ? p.t.y[i] : hi;
        }
        row = (int)((lo + hi) / 512);
    }
    char cap[640];
    double affine[256], correct[256];
    int xs[256];

    ex_begin(c);
    draw_tri(c, &p, row);
    snprintf(cap, sizeof cap,
             "1. A triangle whose vertices lie at eye distances w (the clip-space w before the "
             "divide), red, green and blue at the vertices. The span on scanline %d (pink): how "
             "does the colour vary along it?",
             row);
    ex_end(c, cap);

    ex_begin(c);
    int n = fill(c, &p, row, false, false, affine, xs);
    draw_tri(c, &p, row);
    ex_end(c, "2. Affine (screen-space) interpolation: each pixel centre's barycentric weights "
              "l0, l1, l2 on the screen times the vertex colours. Printed: the green weight. It "
              "steps by the same amount every pixel, as if the triangle faced the eye.");

    ex_begin(c);
    fill(c, &p, row, true, false, correct, xs);
    draw_tri(c, &p, row);
    int worst = 0;
    for (int i = 1; i < n; i++) {
        worst = fabs(correct[i] - affine[i]) > fabs(correct[worst] - affine[worst]) ? i : worst;
    }
    int len = snprintf(cap, sizeof cap,
                       "3. Perspective-correct: the weights of the 3D point are li / wi, "
                       "normalized (interpolate colour/w and 1/w on the screen, divide per "
                       "pixel). ");
    if (n == 0) {
        /* the rows that have a covered centre, to name in the caption */
        int first = -1, last = -1;
        for (int y = 0; y < c->grid_h; y++) {
            for (int x = 0; x < c->grid_w; x++) {
                if (ex_tri_covers(&p.t, (int64_t)x * 256 + 128, (int64_t)y * 256 + 128)) {
                    first = first < 0 ? y : first;
                    last = y;
                    break;
                }
            }
        }
        if (first < 0) {
            snprintf(cap + len, sizeof cap - (size_t)len,
                     "Scanline %d covers no pixel of the triangle, and no scanline of the grid "
                     "does: nothing to compare.", row);
        } else {
            snprintf(cap + len, sizeof cap - (size_t)len,
                     "Scanline %d covers no pixel of the triangle: nothing to compare (give "
                     "--row %d to %d).", row, first, last);
        }
    } else if (fabs(correct[worst] - affine[worst]) < 0.0005) {
        snprintf(cap + len, sizeof cap - (size_t)len,
                 "With every w equal the two agree: at x = %d both are %.3f. Perspective "
                 "matters only when the vertices' w differ (--w).",
                 xs[worst], correct[worst]);
    } else {
        snprintf(cap + len, sizeof cap - (size_t)len,
                 "The green weight now steps unevenly: at x = %d it is %.3f, %.3f affine.",
                 xs[worst], correct[worst], affine[worst]);
    }
    ex_end(c, cap);

    /* frames 4 and 5: the cells alone, nothing drawn over them; the one
     * --interpolation asks for last, as the library draws it */
    if (prim->interpolation == EX_INTERP_FILLSPAN) {
        ex_begin(c);
        fill(c, &p, -1, true, true, correct, xs);
        ex_end(c, "4. The whole triangle perspective-correct, what sr_draw draws for these "
                  "vertices given with their w: the near vertices' colours reach further, the "
                  "far vertex's is squeezed toward it.");
        ex_begin(c);
        fill_fillspan(c, &p);
        ex_end(c, "5. The whole triangle by FillPoly/FillSpan (explain fillpoly), as "
                  "sr_fill_gouraud draws it (SR_GOURAUD_INCREMENTAL): x and the colour step by "
                  "constant increments on the screen, so it is affine, blind to w, and wrong "
                  "under perspective like frame 2.");
        return c->error;
    }
    bool last_affine = prim->interpolation == EX_INTERP_AFFINE;
    for (int k = 0; k < 2; k++) {
        bool affine_now = last_affine ? k == 1 : k == 0;
        ex_begin(c);
        fill(c, &p, -1, !affine_now, true, affine_now ? affine : correct, xs);
        snprintf(cap, sizeof cap, "%d. The whole triangle %s%s", 4 + k,
                 affine_now ? "affine: each weight is constant along lines parallel to the "
                              "opposite edge on the screen, as if no vertex were further than "
                              "another: wrong under perspective"
                            : "perspective-correct: the near vertices' colours reach further, "
                              "the far vertex's is squeezed toward it, as the far squares of a "
                              "checkerboard shrink",
                 k == 0 ? "."
                 : affine_now ? ". What sr_draw draws with interpolation SR_INTERP_AFFINE."
                              : ". What sr_draw draws for these vertices given with their w "
                                "(the default interpolation).");
        ex_end(c, cap);
    }
    return c->error;
}
