/* test_attribute.c - the generic per-vertex attribute array: validated,
 * interpolated like every varying, and shown as color by
 * SR_SHADING_ATTRIBUTE (1 float gray, 2 red/green, 3 RGB, 4 RGBA). */
#include "raster_util.h"

static void draw_attr(rt_target *t, const float *generic, int size, const uint8_t **px)
{
    /* A right triangle over most of the 64x64 target, in window pixels. */
    const double xy[6] = { 0.0, 0.0, 64.0, 0.0, 0.0, 64.0 };
    float pos[9];
    for (int i = 0; i < 3; i++) {
        pos[i * 3 + 0] = rt_ndc_x(t, xy[i * 2]);
        pos[i * 3 + 1] = rt_ndc_y(t, xy[i * 2 + 1]);
        pos[i * 3 + 2] = 0.0f;
    }
    rt_clear(t);
    sr_state st = { .shading = SR_SHADING_ATTRIBUTE };
    sr_result r = sr_draw(t->ctx, t->fb, &st,
                          &(sr_draw_desc){ .positions = pos, .vertex_count = 3,
                                           .generic = generic, .generic_size = size });
    CHECK_EQ(r, SR_OK);
    *px = sr_framebuffer_pixels(t->fb);
}

SR_TEST(one_component_attribute_is_interpolated_gray)
{
    rt_target t = rt_make(64, 64, 1);
    const float g[3] = { 0.0f, 1.0f, 0.5f };
    const uint8_t *px;
    draw_attr(&t, g, 1, &px);
    /* At pixel (x, y) the attribute is x/64 * 1 + y/64 * 0.5 (affine: w = 1). */
    int checked = 0;
    for (int y = 0; y < 64; y += 7) {
        for (int x = 0; x + y < 62; x += 5) {
            double want = ((x + 0.5) / 64.0) * 1.0 + ((y + 0.5) / 64.0) * 0.5;
            const uint8_t *p = px + (y * 64 + x) * 4;
            CHECK_NEAR(p[0], want * 255.0, 1.0);
            CHECK_EQ(p[0], p[1]);
            CHECK_EQ(p[1], p[2]);
            CHECK_EQ(p[3], 255);
            checked++;
        }
    }
    CHECK(checked > 20);
    rt_free(&t);
}

SR_TEST(three_component_attribute_is_rgb)
{
    rt_target t = rt_make(64, 64, 1);
    const float g[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
    const uint8_t *px;
    draw_attr(&t, g, 3, &px);
    const uint8_t *p = px + (1 * 64 + 1) * 4;   /* near the first vertex: red */
    CHECK(p[0] > 240 && p[1] < 15 && p[2] < 15);
    rt_free(&t);
}

SR_TEST(attribute_arguments_are_validated)
{
    rt_target t = rt_make(8, 8, 1);
    float pos[9] = { 0 };
    sr_state st = { .shading = SR_SHADING_ATTRIBUTE };
    CHECK_EQ(sr_draw(t.ctx, t.fb, &st, &(sr_draw_desc){ .positions = pos, .vertex_count = 3 }),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(t.ctx), "sr_draw_desc.generic");
    const float g[3] = { 0 };
    CHECK_EQ(sr_draw(t.ctx, t.fb, &st, &(sr_draw_desc){ .positions = pos, .vertex_count = 3,
                                                        .generic = g, .generic_size = 5 }),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(t.ctx), "generic_size");
    rt_free(&t);
}
