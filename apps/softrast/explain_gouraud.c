/* explain_gouraud.c - `softrast explain gouraud`: Gouraud versus Phong
 * shading of one flat triangle lit by a point light whose specular
 * highlight falls inside it, the course's "Gouraud highlight" flaw.
 * Gouraud lights the three vertices and interpolates their intensities,
 * so every pixel is a convex combination of them: a highlight far from
 * every vertex is missed.  Phong interpolates the normal and lights every
 * pixel, and the highlight appears.
 *
 * The triangle lies in the plane z = 0 of eye space, in window
 * coordinates (an orthographic P that maps x 0..W, y 0..H onto the grid),
 * its normal N = (0, 0, 1) at every vertex; the viewer is at infinity
 * along +z; the light hangs LIGHT_HEIGHT pixels above the highlight, where
 * the half vector H equals N.  Every intensity shown is the library's:
 * the vertices' drawn as points with SR_SHADING_GOURAUD (the colour the
 * vertex stage computes), the pixels drawn by sr_draw with
 * SR_SHADING_GOURAUD and SR_SHADING_PHONG.  The material is grey, so one
 * number, 0..255, is each colour. */
#include "explain.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define LIGHT_HEIGHT 8.0f   /* pixels above the plane */
#define AMBIENT 0.2f
#define DIFFUSE 0.35f
#define SPECULAR 0.55f

static const sr_rgba LIGHT = { 0.98f, 0.75f, 0.10f, 1 };

/* The state and the projection every drawing of the triangle shares. */
static void shading_state(const ex_canvas *c, const ex_primitive *prim, sr_shading shading,
                          sr_mat4 *proj, sr_state *st)
{
    *proj = sr_ortho(0, (float)c->grid_w, (float)c->grid_h, 0, -64, 64, false);
    *st = (sr_state){
        .shading = shading,
        .ambient = { AMBIENT, AMBIENT, AMBIENT },
        .material = { .diffuse = { DIFFUSE, DIFFUSE, DIFFUSE },
                      .specular = { SPECULAR, SPECULAR, SPECULAR },
                      .shininess = (float)prim->shininess },
        .lights[0] = { .type = SR_LIGHT_POINT,
                       .vector = { (float)prim->highlight[0], (float)prim->highlight[1],
                                   LIGHT_HEIGHT } },
    };
}

/* The triangle (or, points: its three vertices as points) drawn with
 * `shading` into fb (grid size); px its pixels. */
static sr_result draw(ex_canvas *c, const ex_primitive *prim, sr_shading shading, bool points,
                      sr_framebuffer *fb)
{
    sr_mat4 proj;
    sr_state st;
    shading_state(c, prim, shading, &proj, &st);
    /* a point 2 pixels wide covers a pixel centre wherever it is */
    st.point_size = 2;
    float pos[9], nrm[9];
    for (int i = 0; i < 3; i++) {
        pos[3 * i] = (float)prim->pts[i].x;
        pos[3 * i + 1] = (float)prim->pts[i].y;
        pos[3 * i + 2] = 0;
        nrm[3 * i] = 0;
        nrm[3 * i + 1] = 0;
        nrm[3 * i + 2] = 1;
    }
    sr_clear(c->ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
    return sr_draw(c->ctx, fb, &st, &(sr_draw_desc){ .positions = pos, .normals = nrm,
                                                     .vertex_count = points ? 1 : 3,
                                                     .primitive = points ? SR_PRIM_POINTS
                                                                         : SR_PRIM_TRIANGLES,
                                                     .projection = &proj });
}

/* Vertex i's Gouraud intensity: the vertex drawn alone as a point. */
static sr_result vertex_intensity(ex_canvas *c, const ex_primitive *prim, int i,
                                  sr_framebuffer *fb, int *out)
{
    ex_primitive one = *prim;
    one.pts[0] = prim->pts[i];
    sr_result r = draw(c, &one, SR_SHADING_GOURAUD, true, fb);
    const uint8_t *px = sr_framebuffer_pixels(fb);
    *out = -1;
    for (int k = 0; r == SR_OK && k < c->grid_w * c->grid_h; k++) {
        if (px[4 * k + 3]) {
            *out = px[4 * k];
            break;
        }
    }
    return r;
}

static sr_rgba grey(int v)
{
    float f = v / 255.0f;
    return (sr_rgba){ f, f, f, 1 };
}

/* The pixels drawn (alpha > 0) as cells in their colour; with values,
 * each cell of row `row` (or every row, -1) shows its intensity. */
static void cells(ex_canvas *c, const uint8_t *px, int row, bool values)
{
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            const uint8_t *p = px + 4 * ((size_t)y * c->grid_w + x);
            if (!p[3] || (row >= 0 && y != row)) {
                continue;
            }
            ex_cell(c, x, y, grey(p[0]));
            if (values) {
                char v[8];
                snprintf(v, sizeof v, "%d", p[0]);
                ex_cell_text(c, x, y, v, p[0] > 110 ? EX_TEXT : (sr_rgba){ 1, 1, 1, 1 });
            }
        }
    }
}

/* The highest intensity of row (or of every pixel, -1), its column in
 * *at. */
static int peak(const ex_canvas *c, const uint8_t *px, int row, int *at)
{
    int best = -1;
    *at = -1;
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            const uint8_t *p = px + 4 * ((size_t)y * c->grid_w + x);
            if (p[3] && (row < 0 || y == row) && p[0] > best) {
                best = p[0];
                *at = x;
            }
        }
    }
    return best;
}

static void outline(ex_canvas *c, const ex_primitive *prim, const int *values)
{
    ex_outline(c, prim->pts, 3, true, EX_EDGE, 1.5);
    for (int i = 0; i < 3; i++) {
        char name[32];
        if (values) {
            snprintf(name, sizeof name, "V%d I=%d", i, values[i]);
        } else {
            snprintf(name, sizeof name, "V%d", i);
        }
        ex_dot(c, prim->pts[i], 4, EX_HILITE);
        ex_label(c, prim->pts[i], name, EX_TEXT);
    }
}

/* A frame: the sample points (px NULL) or the pixels of px (row `row`
 * with their values, or all of them, -1), the triangle (its vertices'
 * intensities when vi is given) and the light. */
static void begin_frame(ex_canvas *c, const ex_primitive *prim, const uint8_t *px, int row,
                        const int *vi)
{
    ex_begin(c);
    if (px) {
        cells(c, px, row, row >= 0);
    } else {
        ex_tri_samples(c);
    }
    outline(c, prim, vi);
    sr_point2 h = { prim->highlight[0], prim->highlight[1] };
    ex_dot(c, h, 6, LIGHT);
    ex_label(c, h, "light", EX_TEXT);
}

sr_result explain_gouraud(ex_canvas *c, const ex_primitive *prim)
{
    sr_framebuffer *fb = NULL, *fb_g = NULL, *fb_p = NULL;
    sr_framebuffer_desc fd = { .width = c->grid_w, .height = c->grid_h,
                               .depth_format = SR_DEPTH_NONE };
    sr_result r = sr_make_framebuffer(c->ctx, &fd, &fb);
    r = r == SR_OK ? sr_make_framebuffer(c->ctx, &fd, &fb_g) : r;
    r = r == SR_OK ? sr_make_framebuffer(c->ctx, &fd, &fb_p) : r;
    int vi[3] = { 0, 0, 0 };
    for (int i = 0; i < 3 && r == SR_OK; i++) {
        r = vertex_intensity(c, prim, i, fb, &vi[i]);
    }
    r = r == SR_OK ? draw(c, prim, SR_SHADING_GOURAUD, false, fb_g) : r;
    r = r == SR_OK ? draw(c, prim, SR_SHADING_PHONG, false, fb_p) : r;
    if (r != SR_OK) {
        sr_destroy_framebuffer(c->ctx, fb);
        sr_destroy_framebuffer(c->ctx, fb_g);
        sr_destroy_framebuffer(c->ctx, fb_p);
        return c->error = r;
    }
    const uint8_t *g = sr_framebuffer_pixels(fb_g), *p = sr_framebuffer_pixels(fb_p);
    int row = (int)floor(prim->highlight[1]);
    row = row < 0 ? 0 : row >= c->grid_h ? c->grid_h - 1 : row;
    int gx, px_, gall, pall;
    int g_row = peak(c, g, row, &gx), p_row = peak(c, p, row, &px_);
    int g_max = peak(c, g, -1, &gall), p_max = peak(c, p, -1, &pall);
    int v_max = vi[0] > vi[1] ? vi[0] : vi[1];
    v_max = vi[2] > v_max ? vi[2] : v_max;
    char cap[1200];

    /* 1. the setup and the lighting model */
    begin_frame(c, prim, NULL, -1, NULL);
    snprintf(cap, sizeof cap,
             "1. A flat triangle, the normal N = (0, 0, 1) at every vertex, lit by Blinn-Phong: "
             "I = k_a I_a + k_d max(N.L, 0) + k_s max(N.H, 0)^n with k_a I_a = %.2f x %.2f, k_d = "
             "%.2f, k_s = %.2f, n = %g; L towards a point light %g pixels above (%g, %g), the "
             "viewer along +z, H = (L + V)/|L + V|. The highlight peaks where H = N: under the "
             "light.",
             AMBIENT, DIFFUSE, DIFFUSE, SPECULAR, prim->shininess, LIGHT_HEIGHT,
             prim->highlight[0], prim->highlight[1]);
    ex_end(c, cap);

    /* 2. Gouraud: the vertex intensities */
    begin_frame(c, prim, NULL, -1, vi);
    snprintf(cap, sizeof cap,
             "2. Gouraud lights the vertices only: I = %d at V0, %d at V1, %d at V2 (of 255).",
             vi[0], vi[1], vi[2]);
    ex_end(c, cap);

    /* 3. Gouraud: the span through the highlight */
    begin_frame(c, prim, g, row, vi);
    if (g_row >= 0) {
        snprintf(cap, sizeof cap,
                 "3. Gouraud interpolates the intensities along the edges and then along each "
                 "span, here row %d under the light: each value is a convex combination of %d, "
                 "%d and %d, so none exceeds %d. The span's brightest is %d.",
                 row, vi[0], vi[1], vi[2], v_max, g_row);
    } else {
        snprintf(cap, sizeof cap,
                 "3. Gouraud interpolates the intensities along the edges and then along each "
                 "span; row %d, under the light, has no pixel of the triangle.", row);
    }
    ex_end(c, cap);

    /* 4. Gouraud: the whole triangle */
    begin_frame(c, prim, g, -1, NULL);
    snprintf(cap, sizeof cap,
             "4. Gouraud shading, the whole triangle: what sr_draw draws with "
             "SR_SHADING_GOURAUD. Brightest %d: the highlight is %s.",
             g_max, p_max > g_max + 8 ? "missed" : "no brighter than the vertices make it");
    ex_end(c, cap);

    /* 5. Phong: the same span, lit per pixel */
    begin_frame(c, prim, p, row, NULL);
    if (p_row >= 0) {
        snprintf(cap, sizeof cap,
                 "5. Phong interpolates the normal instead (renormalized) and lights every pixel: "
                 "along row %d the brightest is %d (Gouraud: %d).",
                 row, p_row, g_row);
    } else {
        snprintf(cap, sizeof cap,
                 "5. Phong interpolates the normal instead (renormalized) and lights every "
                 "pixel.");
    }
    ex_end(c, cap);

    /* 6. Phong: the whole triangle, the library's pixels */
    begin_frame(c, prim, p, -1, NULL);
    snprintf(cap, sizeof cap,
             "6. Phong shading, the whole triangle: what sr_draw draws with SR_SHADING_PHONG. "
             "Brightest %d, Gouraud's %d: %s",
             p_max, g_max, p_max > g_max + 8 ? "the highlight Gouraud missed."
                                             : "here the vertices catch the light as well.");
    ex_end(c, cap);

    sr_destroy_framebuffer(c->ctx, fb);
    sr_destroy_framebuffer(c->ctx, fb_g);
    sr_destroy_framebuffer(c->ctx, fb_p);
    return c->error;
}
