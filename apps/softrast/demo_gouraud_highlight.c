/* demo_gouraud_highlight.c - `softrast demo gouraud-highlight`: the two
 * flaws of Gouraud shading that follow from its convex
 * interpolation, each beside Phong shading of the same mesh.
 *
 * Gouraud lights the vertices only and interpolates their colors, so
 * every pixel is a convex combination of the vertex colors: a sharp
 * specular highlight
 *   - inside a large polygon, far from every vertex, is missed entirely
 *     (top row: a quad of 4 vertices, 2 triangles), and
 *   - at a vertex is smeared over every triangle sharing that vertex, in
 *     the triangles' shapes (bottom row: a 4 x 4 grid, the highlight on
 *     its centre vertex).
 * Phong interpolates the normals and lights every pixel, so the highlight
 * lands where it belongs, round and small, whatever the tessellation.
 * The triangles are outlined faintly, their vertices dotted.
 *
 * Panels (row-major): interior Gouraud, interior Phong, vertex Gouraud,
 * vertex Phong. */
#include "cli.h"
#include "demo.h"
#include "demo3d.h"

#include <stdint.h>
#include <stdio.h>

#define MAX_GRID 4
#define MAX_VERTS ((MAX_GRID + 1) * (MAX_GRID + 1))

/* The surface: the rectangle [-HX, HX] x [-HY, HY] of the plane z = 0,
 * normal +z, seen obliquely from EYE. */
#define HX 1.35f
#define HY 1.0f
static const sr_vec3 EYE = { 0.0f, -2.3f, 2.3f };

typedef struct mesh {
    float pos[3 * MAX_VERTS], nrm[3 * MAX_VERTS];
    uint16_t idx[6 * MAX_GRID * MAX_GRID];
    int verts, indices;
} mesh;

/* An n x n grid of quads, each split along the same diagonal into two
 * counter-clockwise triangles. */
static void make_grid(int n, mesh *m)
{
    m->verts = 0;
    for (int j = 0; j <= n; j++) {
        for (int i = 0; i <= n; i++) {
            float *p = m->pos + 3 * m->verts, *q = m->nrm + 3 * m->verts;
            p[0] = -HX + 2 * HX * i / n;
            p[1] = -HY + 2 * HY * j / n;
            p[2] = 0;
            q[0] = 0;
            q[1] = 0;
            q[2] = 1;
            m->verts++;
        }
    }
    m->indices = 0;
    for (int j = 0; j < n; j++) {
        for (int i = 0; i < n; i++) {
            uint16_t a = (uint16_t)(j * (n + 1) + i), b = (uint16_t)(a + 1);
            uint16_t c = (uint16_t)(b + n + 1), d = (uint16_t)(a + n + 1);
            uint16_t t[6] = { a, b, c, a, c, d };
            for (int k = 0; k < 6; k++) {
                m->idx[m->indices++] = t[k];
            }
        }
    }
}

/* A point light placed so that the mirror reflection of the eye in the
 * plane z = 0 passes through `spot`: the highlight's centre (where the
 * Blinn-Phong half vector equals the normal) is then exactly at spot. */
static sr_vec3 light_for_spot(sr_vec3 spot)
{
    sr_vec3 mirrored_eye = { EYE.x, EYE.y, -EYE.z };
    return sr_vec3_add(spot, sr_vec3_scale(sr_vec3_sub(spot, mirrored_eye), 0.55f));
}

static sr_result draw_panel(sr_context *ctx, sr_framebuffer *fb, const mesh *m,
                            sr_shading shading, sr_vec3 spot)
{
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.07f, 0.08f, 0.1f, 1 }, .depth = 1 });
    float aspect = (float)sr_framebuffer_width(fb) / (float)sr_framebuffer_height(fb);
    sr_mat4 view = sr_look_at(EYE, (sr_vec3){ 0, -0.08f, 0 }, (sr_vec3){ 0, 1, 0 });
    sr_mat4 proj = sr_perspective(0.72f, aspect, 0.5f, 10.0f, false);
    sr_draw_desc draw = { .positions = m->pos, .normals = m->nrm,
                          .vertex_count = (size_t)m->verts, .indices = m->idx,
                          .index_type = SR_INDEX_U16, .index_count = (size_t)m->indices,
                          .view = &view, .projection = &proj };
    sr_state lit = {
        .shading = shading,
        .ambient = { 0.12f, 0.12f, 0.12f },
        .material = { .diffuse = { 0.16f, 0.3f, 0.68f }, .specular = { 0.95f, 0.95f, 0.9f },
                      .shininess = 300 },
        .lights[0] = { .type = SR_LIGHT_POINT, .vector = light_for_spot(spot) },
    };
    sr_result r = sr_draw(ctx, fb, &lit, &draw);
    if (r != SR_OK) {
        return r;
    }
    /* The tessellation on top: outlines and vertices, translucent white. */
    sr_state wire = {
        .shading = SR_SHADING_UNLIT,
        .material = { .diffuse = { 1, 1, 1 }, .opacity = 0.3f },
        .blend = { .enabled = true, .src_rgb = SR_BLEND_SRC_ALPHA,
                   .dst_rgb = SR_BLEND_ONE_MINUS_SRC_ALPHA, .src_alpha = SR_BLEND_ONE,
                   .dst_alpha = SR_BLEND_ONE_MINUS_SRC_ALPHA },
        .depth_test = SR_OFF,
        .polygon_mode_front = SR_POLYGON_LINE,
        .polygon_mode_back = SR_POLYGON_LINE,
    };
    r = sr_draw(ctx, fb, &wire, &draw);
    if (r != SR_OK) {
        return r;
    }
    wire.polygon_mode_front = wire.polygon_mode_back = SR_POLYGON_POINT;
    wire.point_size = 5;
    wire.round_points = true;
    wire.material.opacity = 0.55f;
    draw.primitive = SR_PRIM_POINTS;
    draw.indices = NULL;
    draw.index_type = SR_INDEX_NONE;
    draw.index_count = 0;
    return sr_draw(ctx, fb, &wire, &draw);
}

int demo_gouraud_highlight(sr_context *ctx, const demo_args *args, sr_framebuffer **out)
{
    static const char *const labels[4] = {
        "interior: Gouraud", "interior: Phong", "at a vertex: Gouraud", "at a vertex: Phong",
    };
    demo3d d;
    int status = demo3d_begin(&d, ctx, "gouraud-highlight", DEMO3D_LAYOUT_GOURAUD, args->scale,
                              labels, 4);
    if (status != EXIT_OK) {
        return status;
    }
    sr_framebuffer *fb = NULL;
    if (demo3d_panel(&d, SR_DEPTH_D24, &fb) != SR_OK) {
        return demo3d_fail(&d);
    }
    mesh quad, grid;
    make_grid(1, &quad);
    make_grid(MAX_GRID, &grid);
    /* Interior: well inside the lower-right triangle, far from its
     * corners and from the diagonal.  Vertex: the grid's centre vertex,
     * shared by six triangles. */
    const sr_vec3 interior = { 0.38f, -0.3f, 0 }, vertex = { 0, 0, 0 };
    for (int i = 0; i < 4; i++) {
        sr_shading sh = i % 2 ? SR_SHADING_PHONG : SR_SHADING_GOURAUD;
        if (draw_panel(ctx, fb, i < 2 ? &quad : &grid, sh, i < 2 ? interior : vertex) != SR_OK) {
            sr_destroy_framebuffer(ctx, fb);
            return demo3d_fail(&d);
        }
        demo3d_blit(&d, i, fb, labels[i]);
    }
    sr_destroy_framebuffer(ctx, fb);
    return demo3d_finish(&d, out);
}
