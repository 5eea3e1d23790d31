/* demo_painter.c - `softrast demo painter`: where the painter's algorithm
 * (sr_state.visibility = SR_VISIBILITY_PAINTER: whole triangles sorted back
 * to front, drawn without a depth test) fails and the z-buffer (a depth
 * per pixel) does not.
 *
 * Top row: three long triangles ("pencils") that overlap cyclically -
 * each lies over the next at one end and under it at the other - so no
 * order of whole triangles is right: the z-buffer shows each pencil
 * over the next, the painter puts one of them on top of both.
 * Bottom row: a green triangle passing through a red one; the z-buffer
 * shows where it comes out, the painter draws one entirely over the
 * other.  Colors are darker farther away.
 *
 * Panels (row-major): cyclic z-buffer, cyclic painter's, interpenetrating
 * z-buffer, interpenetrating painter's.  Point-sampled (one sample at
 * each pixel centre). */
#include "cli.h"
#include "demo.h"
#include "demo3d.h"

#include <math.h>
#include <string.h>

typedef struct scene {
    float pos[27], rgb[27];
    int tris;
} scene;

/* Pencil i runs from a wide near end at corner i of an equilateral
 * triangle to a far tip past corner i+1. */
static void cyclic_scene(scene *s)
{
    static const float hue[3][3] = { { 0.95f, 0.3f, 0.25f }, { 0.3f, 0.85f, 0.35f },
                                     { 0.3f, 0.5f, 1.0f } };
    float corner[3][2];
    for (int i = 0; i < 3; i++) {
        float a = 1.5707963f + 2.0943951f * (float)i;
        corner[i][0] = 0.9f * cosf(a);
        corner[i][1] = 0.9f * sinf(a) - 0.2f;
    }
    for (int i = 0; i < 3; i++) {
        const float *a = corner[i], *b = corner[(i + 1) % 3];
        float dx = b[0] - a[0], dy = b[1] - a[1], len = sqrtf(dx * dx + dy * dy);
        dx /= len;
        dy /= len;
        float bx = a[0] - 0.45f * dx, by = a[1] - 0.45f * dy, hw = 0.32f;
        const float v[9] = { bx - hw * dy, by + hw * dx, -4.2f, bx + hw * dy, by - hw * dx, -4.2f,
                             b[0] + 0.7f * dx, b[1] + 0.7f * dy, -6.2f };
        memcpy(s->pos + 9 * i, v, sizeof v);
        for (int k = 0; k < 3; k++) {
            float shade = k == 2 ? 0.45f : 1.0f; /* the far tip darker */
            for (int c = 0; c < 3; c++) {
                s->rgb[9 * i + 3 * k + c] = hue[i][c] * shade;
            }
        }
    }
    s->tris = 3;
}

/* Red at distance 5; green from distance 3.6 on the left to 6.4 on the
 * right, through red. */
static void crossing_scene(scene *s)
{
    static const float pos[18] = { -1.2f, -0.95f, -5.0f, 1.2f, -0.95f, -5.0f, 0.0f, 1.0f, -5.0f,
                                   -1.6f, 0.35f, -3.6f, 1.7f, 0.6f, -6.4f, 1.7f, -0.35f, -6.4f };
    static const float rgb[18] = { 0.95f, 0.3f, 0.25f, 0.95f, 0.3f, 0.25f, 0.95f, 0.3f, 0.25f,
                                   0.4f, 1.0f, 0.45f, 0.18f, 0.45f, 0.2f, 0.18f, 0.45f, 0.2f };
    memcpy(s->pos, pos, sizeof pos);
    memcpy(s->rgb, rgb, sizeof rgb);
    s->tris = 2;
}

static sr_result draw_panel(sr_context *ctx, sr_framebuffer *fb, const scene *s,
                            sr_visibility vis)
{
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.07f, 0.08f, 0.1f, 1 }, .depth = 1 });
    float aspect = (float)sr_framebuffer_width(fb) / (float)sr_framebuffer_height(fb);
    sr_mat4 proj = sr_perspective(0.62f, aspect, 1.0f, 20.0f, false);
    sr_state st = { .visibility = vis, .cull = SR_CULL_NONE };
    return sr_draw(ctx, fb, &st,
                   &(sr_draw_desc){ .positions = s->pos, .colors = s->rgb, .color_size = 3,
                                    .vertex_count = (size_t)s->tris * 3, .projection = &proj });
}

int demo_painter(sr_context *ctx, const demo_args *args, sr_framebuffer **out)
{
    static const char *const labels[4] = {
        "cyclic overlap: z-buffer", "cyclic overlap: painter's",
        "interpenetrating: z-buffer", "interpenetrating: painter's",
    };
    demo3d d;
    int status = demo3d_begin(&d, ctx, "painter", DEMO3D_LAYOUT_PAINTER, args->scale, labels, 4);
    if (status != EXIT_OK) {
        return status;
    }
    sr_framebuffer *fb = NULL;
    if (demo3d_panel(&d, SR_DEPTH_D24, &fb) != SR_OK) {
        return demo3d_fail(&d);
    }
    scene cyclic, crossing;
    cyclic_scene(&cyclic);
    crossing_scene(&crossing);
    for (int i = 0; i < 4; i++) {
        sr_visibility vis = i % 2 ? SR_VISIBILITY_PAINTER : SR_VISIBILITY_Z_BUFFER;
        if (draw_panel(ctx, fb, i < 2 ? &cyclic : &crossing, vis) != SR_OK) {
            sr_destroy_framebuffer(ctx, fb);
            return demo3d_fail(&d);
        }
        demo3d_blit(&d, i, fb, labels[i]);
    }
    sr_destroy_framebuffer(ctx, fb);
    return demo3d_finish(&d, out);
}
