/* demo_zfight.c - `softrast demo zfight`: z-buffer quantization and
 * "z-fighting" (two close surfaces may quantize to the same
 * depth, and which one shows is then decided by drawing order and
 * rounding, pixel by pixel).
 *
 * Two floors, a blue one at y = 0 and an orange one GAP above it, both
 * checkered, recede from an eye one unit up to the far plane at 100.
 * The blue floor is drawn first, then the orange one with the depth test
 * LESS: where both quantize to the same depth the farther blue one stays,
 * so every blue pixel is a wrong one.  Window depth z_w = (f/(f-n))(1 -
 * n/d) (d the eye distance) spends almost all its resolution near the
 * near plane n: the depth step at distance d is about d^2 / (n 2^b), so
 * the fighting starts closer as far/near grows and as the buffer gets
 * fewer bits.
 *
 * Columns: far/near = 10^2, 10^4, 10^6 (near = 1, 0.01, 0.0001).
 * Rows (row-major panels):
 *   D16, D24, D32F - the same projection, GL's depth range; D32F is no
 *     better than D24 here, since a float has 24 significant bits and
 *     z_w crowds against 1 where floats are no finer than D24's steps;
 *   D32F reversed-Z - a projection that maps near to 1 and far to 0
 *     (depth_zero_to_one, test GREATER): z_w ~ n/d, small where d is
 *     large, exactly where floats are finest - no fighting at any ratio;
 *   D16 + polygon offset - D16 again with the blue floor pushed back by
 *     sr_state.offset (factor 1, units 1: its depth slope m plus one
 *     depth step r), the fix for coplanar decals and hidden-line outlines. */
#include "cli.h"
#include "demo.h"
#include "demo3d.h"

#include <stdint.h>
#include <stdio.h>

#define GAP 0.001f     /* height of the orange floor above the blue one */
#define FAR_Z 100.0f
#define TEX 32

static const float NEARS[3] = { 1.0f, 0.01f, 0.0001f };
static const char *const RATIOS[3] = { "10^2", "10^4", "10^6" };

typedef enum row_kind { ROW_D16, ROW_D24, ROW_D32F, ROW_REVERSED, ROW_OFFSET, ROW_COUNT } row_kind;

static sr_result make_checker(sr_context *ctx, sr_texture **out)
{
    static uint8_t px[TEX * TEX * 4];
    for (int y = 0; y < TEX; y++) {
        for (int x = 0; x < TEX; x++) {
            uint8_t v = (((x / (TEX / 2)) ^ (y / (TEX / 2))) & 1) ? 255 : 190;
            uint8_t *p = px + 4 * (y * TEX + x);
            p[0] = p[1] = p[2] = v;
            p[3] = 255;
        }
    }
    return sr_make_texture(ctx, &(sr_texture_desc){ .width = TEX, .height = TEX, .pixels = px },
                           out);
}

/* Reversed-Z: like sr_perspective with zero_to_one, but z_ndc = 1 at the
 * near plane and 0 at the far plane: z_c = (n z_e + n f) / (f - n),
 * w_c = -z_e, so z_ndc = n (f - d) / (d (f - n)) for d = -z_e. */
static sr_mat4 reversed_z(float fovy, float aspect, float n, float f)
{
    sr_mat4 p = sr_perspective(fovy, aspect, n, f, true);
    p.m[2 * 4 + 2] = n / (f - n);
    p.m[3 * 4 + 2] = n * f / (f - n);
    return p;
}

static sr_result draw_panel(sr_context *ctx, sr_framebuffer *fb, const sr_texture *checker,
                            row_kind kind, float near_z)
{
    bool reversed = kind == ROW_REVERSED;
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.07f, 0.08f, 0.1f, 1 },
                                        .depth_action = SR_ACTION_CLEAR,
                                        .depth = reversed ? 0.0f : 1.0f });
    float aspect = (float)sr_framebuffer_width(fb) / (float)sr_framebuffer_height(fb);
    sr_mat4 view = sr_look_at((sr_vec3){ 0, 1, 0 }, (sr_vec3){ 0, 0.55f, -10 },
                              (sr_vec3){ 0, 1, 0 });
    sr_mat4 proj = reversed ? reversed_z(1.0f, aspect, near_z, FAR_Z)
                            : sr_perspective(1.0f, aspect, near_z, FAR_Z, false);
    /* Each floor one big quad reaching behind the eye and past the far
     * plane: the clipper cuts it at near and far. */
    const float X = 150, Z0 = 2, Z1 = -160, U = X, V = (Z0 - Z1) / 2;
    float blue[12] = { -X, 0, Z0, X, 0, Z0, X, 0, Z1, -X, 0, Z1 };
    float orange[12];
    for (int i = 0; i < 12; i++) {
        orange[i] = i % 3 == 1 ? GAP : blue[i];
    }
    const float uv[8] = { 0, 0, U, 0, U, V, 0, V };
    const uint8_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    sr_draw_desc draw = { .positions = blue, .texcoords = uv, .vertex_count = 4,
                          .indices = idx, .index_type = SR_INDEX_U8, .index_count = 6,
                          .view = &view, .projection = &proj };
    sr_state st = {
        .shading = SR_SHADING_UNLIT,
        .texture = checker,
        .material.diffuse = { 0.25f, 0.55f, 0.95f },
        .depth_zero_to_one = reversed,
        .depth_func = reversed ? SR_GREATER : SR_LESS,
    };
    if (kind == ROW_OFFSET) {
        st.offset = (sr_polygon_offset){ .factor = 1, .units = 1, .fill = true };
    }
    sr_result r = sr_draw(ctx, fb, &st, &draw);
    if (r != SR_OK) {
        return r;
    }
    st.offset = (sr_polygon_offset){ 0 };
    st.material.diffuse = (sr_vec3){ 1.0f, 0.55f, 0.15f };
    draw.positions = orange;
    return sr_draw(ctx, fb, &st, &draw);
}

int demo_zfight(sr_context *ctx, const demo_args *args, sr_framebuffer **out)
{
    static const char *const rows[ROW_COUNT] = { "D16", "D24", "D32F", "D32F revZ",
                                                 "D16+offs" };
    static const sr_depth_format formats[ROW_COUNT] = { SR_DEPTH_D16, SR_DEPTH_D24,
                                                        SR_DEPTH_D32F, SR_DEPTH_D32F,
                                                        SR_DEPTH_D16 };
    char labels[ROW_COUNT * 3][48];
    const char *label_ptrs[ROW_COUNT * 3];
    for (int i = 0; i < ROW_COUNT * 3; i++) {
        snprintf(labels[i], sizeof labels[i], "%s f/n %s", rows[i / 3], RATIOS[i % 3]);
        label_ptrs[i] = labels[i];
    }
    demo3d d;
    int status = demo3d_begin(&d, ctx, "zfight", DEMO3D_LAYOUT_ZFIGHT, args->scale, label_ptrs,
                              ROW_COUNT * 3);
    if (status != EXIT_OK) {
        return status;
    }
    sr_texture *checker = NULL;
    if (make_checker(ctx, &checker) != SR_OK) {
        return demo3d_fail(&d);
    }
    for (int i = 0; i < ROW_COUNT * 3; i++) {
        sr_framebuffer *fb = NULL;
        if (demo3d_panel(&d, formats[i / 3], &fb) != SR_OK ||
            draw_panel(ctx, fb, checker, (row_kind)(i / 3), NEARS[i % 3]) != SR_OK) {
            sr_destroy_framebuffer(ctx, fb);
            sr_destroy_texture(ctx, checker);
            return demo3d_fail(&d);
        }
        demo3d_blit(&d, i, fb, labels[i]);
        sr_destroy_framebuffer(ctx, fb);
    }
    sr_destroy_texture(ctx, checker);
    return demo3d_finish(&d, out);
}
