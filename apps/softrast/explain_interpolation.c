/* explain_interpolation.c - `softrast explain interpolation`: a value
 * given at each vertex (an intensity) interpolated over the triangle's
 * pixels by the course's three methods (explain_interp_methods.c):
 * bilinear, the plane equation and barycentric coordinates, each frame
 * showing what the method stepped or solved; the last frame is sr_draw's
 * pixels for the triangle with the values as a colour attribute, in
 * screen space, and how far the methods and the library differ. */
#include "explain.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const sr_rgba VERTEX_COLOR[3] = { { 1, 0, 0, 1 }, { 0, 1, 0, 1 }, { 0, 0, 1, 1 } };

typedef struct interp {
    ex_tri t;
    double in[3];
    int name[3];           /* the number the user gave vertex i (setup may swap V1, V2) */
    float *bil, *pla, *bar, *lambda;
    ex_interp_row *rows;
    double abc[3];
    int origin[2];
    int ex, ey;            /* the covered pixel nearest the centroid, or -1 */
} interp;

static sr_rgba grey(float v)
{
    return (sr_rgba){ v, v, v, 1 };
}

static sr_point2 vertex(const interp *p, int i)
{
    return (sr_point2){ p->t.x[i] / 256.0, p->t.y[i] / 256.0 };
}

/* The outline and each vertex's name and value. */
static void draw_tri(ex_canvas *c, const interp *p)
{
    sr_point2 v[3] = { vertex(p, 0), vertex(p, 1), vertex(p, 2) };
    ex_outline(c, v, 3, true, EX_EDGE, 1.5);
    for (int i = 0; i < 3; i++) {
        char label[32];
        snprintf(label, sizeof label, "V%d I=%g", p->name[i], p->in[i]);
        ex_dot(c, v[i], c->zoom >= 20 ? 5 : c->zoom * 0.25, VERTEX_COLOR[p->name[i]]);
        ex_label(c, v[i], label, EX_EDGE);
    }
}

/* The covered cells of I in their grey, each with its value. */
static void values(ex_canvas *c, const float *I)
{
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            float v = I[y * c->grid_w + x];
            if (!isnan(v)) {
                ex_cell(c, x, y, grey(v));
                ex_cell_value(c, x, y, v);
            }
        }
    }
}

/* Each covered scanline's walk: where it crosses the edges and, with
 * `line`, the span between them (left out over the cells' values). */
static void spans(ex_canvas *c, const interp *p, bool line)
{
    for (int y = 0; y < c->grid_h; y++) {
        const ex_interp_row *r = &p->rows[y];
        if (r->x0 == r->x1) {
            continue;
        }
        sr_point2 l = { r->xl, y + 0.5 }, rt = { r->xr, y + 0.5 };
        if (line) {
            ex_segment(c, l, rt, EX_HILITE, 1.5);
        }
        ex_dot(c, l, 3, EX_INK);
        ex_dot(c, rt, 3, EX_INK);
    }
}

static void bilinear_frames(ex_canvas *c, const interp *p, const char *lead)
{
    char cap[900], inc[3][64];
    int o[3];
    ex_tri_order_by_y(&p->t, o);
    const int ends[3][2] = { { 0, 2 }, { 0, 1 }, { 1, 2 } };   /* AC, AB, BC */
    for (int e = 0; e < 3; e++) {
        int a = o[ends[e][0]], b = o[ends[e][1]];
        double dy = (p->t.y[b] - p->t.y[a]) / 256.0;
        if (dy > 0) {
            snprintf(inc[e], sizeof inc[e], "dX = %.3f, dI = %.4f",
                     (p->t.x[b] - p->t.x[a]) / 256.0 / dy, (p->in[b] - p->in[a]) / dy);
        } else {
            snprintf(inc[e], sizeof inc[e], "horizontal, never walked");
        }
    }
    int first = -1, last = -1;
    float lo = INFINITY, hi = -INFINITY;
    for (int y = 0; y < c->grid_h; y++) {
        const ex_interp_row *r = &p->rows[y];
        if (r->x0 < r->x1) {
            first = first < 0 ? y : first;
            last = y;
            if (r->x1 - r->x0 > 1) {   /* a one-pixel span steps nothing */
                lo = r->dI < lo ? r->dI : lo;
                hi = r->dI > hi ? r->dI : hi;
            }
        }
    }

    ex_begin(c);
    spans(c, p, true);
    draw_tri(c, p);
    int n = snprintf(cap, sizeof cap,
                     "%d. %s, along the edges (FillPoly, as in explain fillpoly): A, B, "
                     "C sorted by y; at each scanline centre the left and right edges' x step "
                     "by dX = 1/m and I by dI = dI/dy. AC: %s; AB: %s; BC: %s.",
                     c->frame_count + 1, lead, inc[0], inc[1], inc[2]);
    if (first >= 0) {
        const ex_interp_row *f = &p->rows[first], *l = &p->rows[last];
        snprintf(cap + n, sizeof cap - (size_t)n,
                 " Scanline %d: I_L = %.3f (%s), I_R = %.3f (%s); scanline %d: I_L = %.3f, "
                 "I_R = %.3f.",
                 first, f->il, f->left, f->ir, f->right, last, l->il, l->ir);
    }
    ex_end(c, cap);

    ex_begin(c);
    values(c, p->bil);
    spans(c, p, false);
    draw_tri(c, p);
    if (first < 0) {
        snprintf(cap, sizeof cap, "%d. Bilinear, along each span (FillSpan): no scanline "
                 "covers a pixel centre of the triangle.", c->frame_count + 1);
    } else if (lo > hi) {
        snprintf(cap, sizeof cap,
                 "%d. Bilinear, along each span (FillSpan): I at the first covered centre is "
                 "I_L + (x + 1/2 - x_L) dI with dI = (I_R - I_L) / (x_R - x_L); every span here "
                 "is one pixel, so nothing is stepped along it.", c->frame_count + 1);
    } else {
        char range[64];
        int k = snprintf(range, sizeof range, "%.5f", lo);
        char hi_text[32];
        snprintf(hi_text, sizeof hi_text, "%.5f", hi);
        if (strcmp(range, hi_text) != 0) {
            snprintf(range + k, sizeof range - (size_t)k, " to %s", hi_text);
        }
        snprintf(cap, sizeof cap,
                 "%d. Bilinear, along each span (FillSpan): I at the first covered centre is "
                 "I_L + (x + 1/2 - x_L) dI, then +dI per pixel, dI = (I_R - I_L) / (x_R - x_L) "
                 "= %s on the spans here: the same slope on every span (I over a triangle is "
                 "a plane), apart from float rounding.",
                 c->frame_count + 1, range);
    }
    ex_end(c, cap);
}

static void plane_frame(ex_canvas *c, const interp *p, const char *lead)
{
    char cap[900];
    ex_begin(c);
    values(c, p->pla);
    /* where each row of the bounding box starts: its value is the last
     * row's start plus b, whether or not the triangle covers it */
    int last_row = -1;
    for (int i = 0; i < c->grid_w * c->grid_h; i++) {
        last_row = isnan(p->pla[i]) ? last_row : i / c->grid_w;
    }
    for (int y = p->origin[1]; y >= 0 && y <= last_row; y++) {
        ex_sample(c, p->origin[0], y, EX_HILITE);
    }
    draw_tri(c, p);
    int n = snprintf(cap, sizeof cap,
                     "%d. %s I(x, y) = a x + b y + c, solved from the three "
                     "vertices (Cramer's rule, twice the area %g as the determinant): a = %.5f, "
                     "b = %.5f, c = %.4f.",
                     c->frame_count + 1, lead, (double)p->t.area2 / 65536.0, p->abc[0],
                     p->abc[1], p->abc[2]);
    if (p->origin[0] >= 0) {
        snprintf(cap + n, sizeof cap - (size_t)n,
                 " At the centre (%d.5, %d.5) I = %.4f; then +a per pixel along a row and +b "
                 "from one row's start (pink) to the next: two additions, no division, per "
                 "pixel.",
                 p->origin[0], p->origin[1],
                 p->abc[0] * (p->origin[0] + 0.5) + p->abc[1] * (p->origin[1] + 0.5) + p->abc[2]);
    }
    ex_end(c, cap);
}

static void barycentric_frames(ex_canvas *c, const interp *p, const char *lead)
{
    char cap[900], at[300] = "";
    int gw = c->grid_w;
    double l[3] = { 0, 0, 0 };   /* by the user's numbering */
    if (p->ex >= 0) {
        for (int i = 0; i < 3; i++) {
            l[p->name[i]] = p->lambda[3 * (p->ey * gw + p->ex) + i];
        }
        snprintf(at, sizeof at,
                 " At (%d.5, %d.5), ringed: l0 = %.3f, l1 = %.3f, l2 = %.3f.", p->ex, p->ey, l[0],
                 l[1], l[2]);
    }
    ex_begin(c);
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < gw; x++) {
            const float *w = p->lambda + 3 * (y * gw + x);
            if (isnan(p->bar[y * gw + x])) {
                continue;
            }
            sr_rgba col = { 0, 0, 0, 1 };
            for (int i = 0; i < 3; i++) {
                col.r += w[i] * VERTEX_COLOR[p->name[i]].r;
                col.g += w[i] * VERTEX_COLOR[p->name[i]].g;
                col.b += w[i] * VERTEX_COLOR[p->name[i]].b;
            }
            ex_cell(c, x, y, col);
        }
    }
    if (p->ex >= 0) {
        ex_ring(c, p->ex, p->ey, EX_EDGE);
    }
    draw_tri(c, p);
    snprintf(cap, sizeof cap,
             "%d. %s: at each centre P, li = Ei(P) / 2A, the edge "
             "function of the edge opposite Vi (twice the area of P and that edge) over twice "
             "the triangle's area; l0 + l1 + l2 = 1, all >= 0 inside. Red l0, green l1, blue "
             "l2.%s",
             c->frame_count + 1, lead, at);
    ex_end(c, cap);

    ex_begin(c);
    values(c, p->bar);
    draw_tri(c, p);
    double in[3];
    for (int i = 0; i < 3; i++) {
        in[p->name[i]] = p->in[i];
    }
    int n = snprintf(cap, sizeof cap,
                     "%d. Barycentric: I = l0 I0 + l1 I1 + l2 I2, the vertex values mixed by "
                     "the weights, at every covered centre on its own (nothing stepped).",
                     c->frame_count + 1);
    if (p->ex >= 0) {
        snprintf(cap + n, sizeof cap - (size_t)n,
                 " At (%d.5, %d.5): %.3f x %g + %.3f x %g + %.3f x %g = %.4f.", p->ex, p->ey,
                 l[0], in[0], l[1], in[1], l[2], in[2], p->bar[p->ey * gw + p->ex]);
    }
    ex_end(c, cap);
}

/* sr_draw's pixels for the triangle, its values as a grey colour
 * attribute, in screen space (an orthographic projection onto the grid,
 * w = 1 at every vertex), into px (RGBA8, the grid's size). */
static sr_result library_pixels(ex_canvas *c, const interp *p, uint8_t *px)
{
    sr_framebuffer *fb = NULL;
    sr_result r = sr_make_framebuffer(c->ctx, &(sr_framebuffer_desc){
                                                  .width = c->grid_w, .height = c->grid_h,
                                                  .depth_format = SR_DEPTH_NONE },
                                      &fb);
    if (r != SR_OK) {
        return r;
    }
    sr_mat4 proj = sr_ortho(0, (float)c->grid_w, (float)c->grid_h, 0, -1, 1, false);
    float pos[9], col[12];
    for (int i = 0; i < 3; i++) {
        pos[3 * i] = (float)(p->t.x[i] / 256.0);
        pos[3 * i + 1] = (float)(p->t.y[i] / 256.0);
        pos[3 * i + 2] = 0;
        for (int k = 0; k < 3; k++) {
            col[4 * i + k] = (float)p->in[i];
        }
        col[4 * i + 3] = 1;
    }
    sr_clear(c->ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
    sr_state st = { .shading = SR_SHADING_UNLIT, .material = { .diffuse = { 1, 1, 1 } },
                    .interpolation = SR_INTERP_AFFINE, .cull = SR_CULL_NONE };
    r = sr_draw(c->ctx, fb, &st, &(sr_draw_desc){ .positions = pos, .vertex_count = 3,
                                                  .colors = col, .color_size = 4,
                                                  .projection = &proj });
    if (r == SR_OK) {
        memcpy(px, sr_framebuffer_pixels(fb), (size_t)c->grid_w * c->grid_h * 4);
    }
    sr_destroy_framebuffer(c->ctx, fb);
    return r;
}

static void library_frame(ex_canvas *c, const interp *p, const uint8_t *px)
{
    int gw = c->grid_w, n = 0, cover_diff = 0;
    double methods = 0, lib = 0;
    for (int i = 0; i < gw * c->grid_h; i++) {
        bool drawn = px[4 * i + 3] != 0, ours = !isnan(p->bar[i]);
        cover_diff += drawn != ours;
        if (drawn) {
            ex_cell(c, i % gw, i / gw, grey(px[4 * i] / 255.0f));
            n++;
        }
        if (!drawn || !ours) {
            continue;
        }
        float m[3] = { p->bil[i], p->pla[i], p->bar[i] };
        for (int k = 0; k < 3; k++) {
            double d = fabs(m[k] - m[(k + 1) % 3]), dl = fabs(m[k] * 255.0 - px[4 * i]);
            methods = d > methods ? d : methods;
            lib = dl > lib ? dl : lib;
        }
    }
    char cap[900], cover[160];
    if (cover_diff) {
        snprintf(cover, sizeof cover, "%d pixels differ from those the methods covered",
                 cover_diff);
    } else {
        snprintf(cover, sizeof cover, "exactly those the three methods covered");
    }
    int len = snprintf(cap, sizeof cap,
                       "%d. The result (the cells alone): what sr_draw draws for this triangle "
                       "with the vertex values as a colour attribute, in screen space "
                       "(SR_INTERP_AFFINE): %d pixels, %s.",
                       c->frame_count + 1, n, cover);
    if (n > 0) {
        snprintf(cap + len, sizeof cap - (size_t)len,
                 " Largest difference between the three methods: %.2g (float rounding: one "
                 "plane reached three ways); between them and the library's 8-bit pixels: %.2f "
                 "of a step of 1/255 (rounding to 8 bits).",
                 methods, lib);
    }
    ex_end(c, cap);
}

sr_result explain_interpolation(ex_canvas *c, const ex_primitive *prim)
{
    interp p = { .ex = -1, .ey = -1 };
    bool swapped = ex_tri_setup_at(&p.t, p.in, prim, 0);
    for (int i = 0; i < 3; i++) {
        p.name[i] = swapped && i ? 3 - i : i;
    }
    size_t cells = (size_t)c->grid_w * (size_t)c->grid_h;
    p.bil = malloc(cells * sizeof *p.bil);
    p.pla = malloc(cells * sizeof *p.pla);
    p.bar = malloc(cells * sizeof *p.bar);
    p.lambda = malloc(3 * cells * sizeof *p.lambda);
    p.rows = malloc((size_t)c->grid_h * sizeof *p.rows);
    uint8_t *px = malloc(4 * cells);
    sr_result r = p.bil && p.pla && p.bar && p.lambda && p.rows && px ? SR_OK : SR_OUT_OF_MEMORY;
    if (r == SR_OK) {
        ex_interp_bilinear(&p.t, p.in, c->grid_w, c->grid_h, p.bil, p.rows);
        ex_interp_plane(&p.t, p.in, c->grid_w, c->grid_h, p.pla, p.abc, p.origin);
        ex_interp_barycentric(&p.t, p.in, c->grid_w, c->grid_h, p.bar, p.lambda);
        r = library_pixels(c, &p, px);
    }
    if (r != SR_OK) {
        c->error = c->error ? c->error : r;
    } else {
        double cx = (p.t.x[0] + p.t.x[1] + p.t.x[2]) / 768.0,
               cy = (p.t.y[0] + p.t.y[1] + p.t.y[2]) / 768.0, best = INFINITY;
        for (int y = 0; y < c->grid_h; y++) {
            for (int x = 0; x < c->grid_w; x++) {
                double d = hypot(x + 0.5 - cx, y + 0.5 - cy);
                if (!isnan(p.bar[y * c->grid_w + x]) && d < best) {
                    best = d;
                    p.ex = x;
                    p.ey = y;
                }
            }
        }
        char cap[900];
        static const char *const shown[] = {
            "all three", "bilinear (--method bilinear)", "the plane equation (--method plane)",
            "barycentric coordinates (--method barycentric)" };
        ex_begin(c);
        ex_tri_samples(c);
        draw_tri(c, &p);
        snprintf(cap, sizeof cap,
                 "1. A triangle with a value at each vertex, here an intensity I (a colour "
                 "channel; depth and texture coordinates are interpolated alike), snapped to "
                 "1/256 pixel. Three methods give I at each covered pixel centre, one linear "
                 "function of x and y on a triangle: bilinear (scan-line), the plane equation "
                 "and barycentric coordinates. Shown: %s.",
                 shown[prim->method]);
        ex_end(c, cap);
        bool all = prim->method == EX_METHOD_ALL;
        if (all || prim->method == EX_METHOD_BILINEAR) {
            bilinear_frames(c, &p, all ? "Method 1: bilinear" : "Bilinear");
        }
        if (all || prim->method == EX_METHOD_PLANE) {
            plane_frame(c, &p, all ? "Method 2: the plane equation" : "The plane equation");
        }
        if (all || prim->method == EX_METHOD_BARYCENTRIC) {
            barycentric_frames(c, &p, all ? "Method 3: barycentric coordinates"
                                          : "Barycentric coordinates");
        }
        ex_begin(c);
        library_frame(c, &p, px);
    }
    free(p.bil);
    free(p.pla);
    free(p.bar);
    free(p.lambda);
    free(p.rows);
    free(px);
    return c->error;
}
