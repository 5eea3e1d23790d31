/* demo_clip3d.c - the 3D half of `softrast demo clip`: triangles that
 * cross the near plane and the sides of the view volume, clipped in
 * homogeneous clip space (before the divide by w, where the view volume
 * is -w <= x, y, z <= w and nothing behind the eye can wrap around).
 *
 * Panels (row-major):
 *   the scene, drawn normally: a ground grid running under the eye and
 *     past the far plane, a wall sticking out of the left side, a large
 *     triangle with one corner behind the eye;
 *   softrast's own clip (sr_state polygon mode line, which outlines each
 *     polygon after clipping): the library clips only against near and
 *     far (and a guard band far outside the image) - the sides of the
 *     view volume are left to the rasterizer, which trims to the viewport
 *     exactly, so shared edges keep their original vertices;
 *   the textbook clip against all six planes, done here in the demo by
 *     Sutherland-Hodgman in 4D, one plane at a time: original edges
 *     yellow, edges the clipper created (on a clip plane) red;
 *   the view frustum from above (x right, -z up) with the same polygons,
 *     originals grey, the clipped parts as in the third panel. */
#include "cli.h"
#include "demo.h"
#include "demo3d.h"

#include <stdint.h>
#include <stdio.h>

#define NEAR_Z 1.0f
#define FAR_Z 9.0f
#define FOVY 0.9f
#define MAX_POLY 12

static const sr_vec3 EYE = { 0, 1.4f, 2.2f };
static const sr_vec3 TARGET = { 0, 0.5f, -3 };
static const sr_rgba ORIGINAL = { 1.0f, 0.85f, 0.3f, 1 };
static const sr_rgba CREATED = { 1.0f, 0.22f, 0.18f, 1 };
static const sr_rgba FAINT = { 0.55f, 0.57f, 0.62f, 1 };

/* The scene as a triangle list: position and color per vertex. */
#define GRID 3
#define NTRI (2 * GRID * GRID + 2 + 1)
static float pos[3 * 3 * NTRI], col[3 * 3 * NTRI];
static int ntri;

static void add_tri(const float a[3], const float b[3], const float c[3], const float rgb[3])
{
    const float *v[3] = { a, b, c };
    for (int k = 0; k < 3; k++) {
        for (int i = 0; i < 3; i++) {
            pos[9 * ntri + 3 * k + i] = v[k][i];
            col[9 * ntri + 3 * k + i] = rgb[i];
        }
    }
    ntri++;
}

static void build_scene(void)
{
    ntri = 0;
    /* ground: x in [-6, 6], z in [3, -10], a checker of two greens */
    for (int j = 0; j < GRID; j++) {
        for (int i = 0; i < GRID; i++) {
            float x0 = -6 + 4.0f * i, x1 = x0 + 4, z0 = 3 - 13.0f * j / GRID,
                  z1 = 3 - 13.0f * (j + 1) / GRID;
            float a[3] = { x0, 0, z0 }, b[3] = { x1, 0, z0 }, c[3] = { x1, 0, z1 },
                  d[3] = { x0, 0, z1 };
            float g[3] = { 0.25f, 0.5f, 0.3f }, h[3] = { 0.35f, 0.62f, 0.38f };
            const float *rgb = (i + j) % 2 ? g : h;
            add_tri(a, b, c, rgb);
            add_tri(a, c, d, rgb);
        }
    }
    /* a wall crossing the left side of the view volume */
    float w0[3] = { -3.6f, 0, -2.6f }, w1[3] = { -0.9f, 0, -4.4f }, w2[3] = { -0.9f, 2.0f, -4.4f },
          w3[3] = { -3.6f, 2.0f, -2.6f }, wc[3] = { 0.35f, 0.45f, 0.85f };
    add_tri(w0, w1, w2, wc);
    add_tri(w0, w2, w3, wc);
    /* a large triangle with one corner behind the eye (z > eye z) */
    float t0[3] = { 1.3f, 0.05f, 3.2f }, t1[3] = { 3.2f, 0.05f, -5.2f }, t2[3] = { 0.4f, 2.4f, -3.6f },
          tc[3] = { 0.9f, 0.5f, 0.25f };
    add_tri(t0, t1, t2, tc);
}

/* A polygon vertex in clip space, with its world position carried along
 * (for the top view) and whether the edge to the next vertex lies on a
 * clip plane. */
typedef struct cvert {
    double c[4];
    double world[3];
    bool created_edge;
} cvert;

/* Signed distance to plane p (0..5: x >= -w, x <= w, y >= -w, y <= w,
 * z >= -w, z <= w); inside is >= 0. */
static double dist(const cvert *v, int p)
{
    double s = (p & 1) ? -1.0 : 1.0;
    return v->c[3] + s * v->c[p / 2];
}

static cvert lerp(const cvert *a, const cvert *b, double t)
{
    cvert r = *a;
    for (int k = 0; k < 4; k++) {
        r.c[k] = a->c[k] + t * (b->c[k] - a->c[k]);
    }
    for (int k = 0; k < 3; k++) {
        r.world[k] = a->world[k] + t * (b->world[k] - a->world[k]);
    }
    return r;
}

/* Sutherland-Hodgman against one plane: the four cases per edge prev->cur
 * (both in: cur; in->out: the intersection; both out: nothing; out->in:
 * the intersection, then cur).  The exit intersection starts an edge
 * along the plane, so it is marked; the entry intersection lies on the
 * original edge prev->cur and keeps prev's mark. */
static int clip_plane(const cvert *in, int n, int p, cvert *out)
{
    int m = 0;
    for (int i = 0; i < n; i++) {
        const cvert *prev = &in[(i + n - 1) % n], *cur = &in[i];
        double dp = dist(prev, p), dc = dist(cur, p);
        if (dc >= 0) {
            if (dp < 0 && m < MAX_POLY) {
                cvert e = lerp(cur, prev, dc / (dc - dp)); /* from the inside vertex */
                e.created_edge = prev->created_edge;
                out[m++] = e;
            }
            if (m < MAX_POLY) {
                out[m++] = *cur;
            }
        } else if (dp >= 0 && m < MAX_POLY) {
            cvert x = lerp(prev, cur, dp / (dp - dc));
            x.created_edge = true;
            out[m++] = x;
        }
    }
    return m;
}

static int clip_triangle(const sr_mat4 *pv, int t, cvert *poly)
{
    cvert tmp[MAX_POLY];
    for (int k = 0; k < 3; k++) {
        const float *p = pos + 9 * t + 3 * k;
        sr_vec4 c = sr_mat4_mul_vec4(pv, (sr_vec4){ p[0], p[1], p[2], 1 });
        poly[k] = (cvert){ { c.x, c.y, c.z, c.w }, { p[0], p[1], p[2] }, false };
    }
    int n = 3;
    for (int p = 0; p < 6 && n > 0; p++) {
        n = clip_plane(poly, n, p, tmp);
        for (int i = 0; i < n; i++) {
            poly[i] = tmp[i];
        }
    }
    return n;
}

static void line(sr_context *ctx, sr_framebuffer *fb, sr_point2 a, sr_point2 b, sr_rgba c,
                 double width)
{
    sr_draw_line(ctx, fb, a, b, c, &(sr_line_desc){ .algorithm = SR_LINE_AREA, .width = width,
                                                    .cap = SR_LINE_CAP_ROUND });
}

/* The third panel draws into a viewport inset from the panel's edges, so
 * the edges the clipper creates on the side planes show on the margin. */
#define INSET 24

static sr_viewport inset_viewport(int w, int h)
{
    return (sr_viewport){ INSET, INSET * h / w, w - 2 * INSET, h - 2 * (INSET * h / w) };
}

/* Window position of a clip-space vertex: divide by w, then S. */
static sr_point2 to_window(const cvert *v, sr_viewport vp)
{
    return (sr_point2){ vp.x + (v->c[0] / v->c[3] + 1) * 0.5 * vp.width,
                        vp.y + (1 - v->c[1] / v->c[3]) * 0.5 * vp.height };
}

/* Top view: world (x, z) onto the panel, the eye near the bottom. */
static sr_point2 top(const double *world, int w, int h)
{
    double s = h / 14.5;
    return (sr_point2){ w * 0.5 + world[0] * s, h - 8 + (world[2] - 3.6) * s };
}

static sr_result draw_frustum_top(sr_context *ctx, sr_framebuffer *fb, const sr_mat4 *pv)
{
    int w = sr_framebuffer_width(fb), h = sr_framebuffer_height(fb);
    sr_mat4 inv;
    if (!sr_mat4_invert(pv, &inv)) {
        return SR_INVALID_ARG;
    }
    /* the 8 corners of the view volume, NDC -> world */
    double corner[8][3];
    for (int i = 0; i < 8; i++) {
        sr_vec4 c = sr_mat4_mul_vec4(&inv, (sr_vec4){ (i & 1) ? 1.0f : -1.0f,
                                                      (i & 2) ? 1.0f : -1.0f,
                                                      (i & 4) ? 1.0f : -1.0f, 1 });
        corner[i][0] = c.x / c.w;
        corner[i][1] = c.y / c.w;
        corner[i][2] = c.z / c.w;
    }
    const sr_rgba edge = { 0.7f, 0.75f, 0.85f, 1 };
    for (int i = 0; i < 8; i++) {
        for (int b = 1; b < 8; b <<= 1) {
            if (!(i & b)) {
                line(ctx, fb, top(corner[i], w, h), top(corner[i | b], w, h), edge, 1.0);
            }
        }
    }
    double eye[3] = { EYE.x, EYE.y, EYE.z };
    sr_point2 e = top(eye, w, h);
    sr_draw_circle(ctx, fb, e.x, e.y, 3, (sr_rgba){ 1, 1, 1, 1 }, true);
    sr_draw_text(ctx, fb, (int)e.x + 6, (int)e.y - 4, 1, "eye", (sr_rgba){ 1, 1, 1, 1 });
    return SR_OK;
}

int demo_clip3d_section(sr_context *ctx, sr_framebuffer **out)
{
    static const char *const labels[4] = {
        "3D scene", "softrast: near/far only", "6 planes: new edges red", "the frustum from above",
    };
    demo3d d;
    int status = demo3d_begin(&d, ctx, "clip", DEMO3D_LAYOUT_CLIP, 1, labels, 4);
    if (status != EXIT_OK) {
        return status;
    }
    sr_framebuffer *fb = NULL;
    if (demo3d_panel(&d, SR_DEPTH_D24, &fb) != SR_OK) {
        return demo3d_fail(&d);
    }
    build_scene();
    int w = sr_framebuffer_width(fb), h = sr_framebuffer_height(fb);
    sr_mat4 view = sr_look_at(EYE, TARGET, (sr_vec3){ 0, 1, 0 });
    sr_mat4 proj = sr_perspective(FOVY, (float)w / (float)h, NEAR_Z, FAR_Z, false);
    sr_mat4 pv = sr_mat4_mul(&proj, &view);
    sr_draw_desc draw = { .positions = pos, .colors = col, .color_size = 3,
                          .vertex_count = (size_t)(3 * ntri), .view = &view,
                          .projection = &proj };
    const sr_clear_desc clear = { .color = { 0.07f, 0.08f, 0.1f, 1 }, .depth = 1 };
    sr_result r = SR_OK;
    for (int cell = 0; cell < 4 && r == SR_OK; cell++) {
        sr_clear(ctx, fb, &clear);
        if (cell == 0) {
            r = sr_draw(ctx, fb, &(sr_state){ .shading = SR_SHADING_UNLIT }, &draw);
        } else if (cell == 2) {
            sr_viewport vp = inset_viewport(w, h);
            sr_point2 rect[4] = { { vp.x, vp.y }, { vp.x + vp.width, vp.y },
                                  { vp.x + vp.width, vp.y + vp.height },
                                  { vp.x, vp.y + vp.height } };
            sr_fill_polygon(ctx, fb, &(sr_polygon2){ rect, 4, NULL, 0 },
                            (sr_rgba){ 0.16f, 0.17f, 0.2f, 1 }, NULL);
            r = sr_draw(ctx, fb, &(sr_state){ .shading = SR_SHADING_UNLIT, .viewport = vp },
                        &draw);
        } else if (cell == 1) {
            r = sr_draw(ctx, fb, &(sr_state){ .shading = SR_SHADING_UNLIT,
                                              .polygon_mode_front = SR_POLYGON_LINE,
                                              .polygon_mode_back = SR_POLYGON_LINE,
                                              .depth_test = SR_OFF },
                        &draw);
        } else {
            r = draw_frustum_top(ctx, fb, &pv);
        }
        if (cell >= 2) {
            for (int t = 0; t < ntri && r == SR_OK; t++) {
                cvert poly[MAX_POLY];
                int n = clip_triangle(&pv, t, poly);
                if (cell == 3) {
                    const float *p = pos + 9 * t;
                    double a[3] = { p[0], p[1], p[2] }, b[3] = { p[3], p[4], p[5] },
                           c[3] = { p[6], p[7], p[8] };
                    line(ctx, fb, top(a, w, h), top(b, w, h), FAINT, 0.8);
                    line(ctx, fb, top(b, w, h), top(c, w, h), FAINT, 0.8);
                    line(ctx, fb, top(c, w, h), top(a, w, h), FAINT, 0.8);
                }
                for (int i = 0; i < n; i++) {
                    const cvert *a = &poly[i], *b = &poly[(i + 1) % n];
                    sr_point2 pa = cell == 2 ? to_window(a, inset_viewport(w, h)) : top(a->world, w, h);
                    sr_point2 pb = cell == 2 ? to_window(b, inset_viewport(w, h)) : top(b->world, w, h);
                    line(ctx, fb, pa, pb, a->created_edge ? CREATED : ORIGINAL,
                         a->created_edge ? 2.0 : 1.2);
                }
            }
        }
        if (r == SR_OK) {
            demo3d_blit(&d, cell, fb, labels[cell]);
        }
    }
    sr_destroy_framebuffer(ctx, fb);
    if (r != SR_OK) {
        return demo3d_fail(&d);
    }
    return demo3d_finish(&d, out);
}
