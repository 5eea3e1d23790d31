/* test_validation.c - API misuse and resource failure: every invalid
 * argument class returns its code and a message naming the field, a failed
 * call draws nothing, allocation failures injected at every allocation of
 * sr_make_context (1 and 2 threads), sr_make_framebuffer and sr_draw
 * (first draw and scratch growth) return SR_OUT_OF_MEMORY without leaks
 * and leave the context usable; and the result strings. */
#include "sr_test.h"
#include "softrast.h"

#include <limits.h>
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

enum { FW = 8, FH = 8 };

/* ---- fixture: a context, a cleared 8x8 framebuffer and its snapshot ---- */

typedef struct fixture {
    sr_context *ctx;
    sr_framebuffer *fb;
    uint8_t color[FW * FH * 4];
    float depth[FW * FH];
} fixture;

static void fixture_clear(fixture *f)
{
    sr_clear(f->ctx, f->fb, &(sr_clear_desc){ .color = { 0.2f, 0.4f, 0.6f, 1 },
                                             .depth_action = SR_ACTION_CLEAR, .depth = 0.75f });
    memcpy(f->color, sr_framebuffer_pixels(f->fb), sizeof f->color);
    sr_read_depth(f->ctx, f->fb, 0, 0, FW, FH, f->depth, FW);
}

static fixture fixture_make(void)
{
    fixture f;
    memset(&f, 0, sizeof f);
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &f.ctx);
    sr_make_framebuffer(f.ctx, &(sr_framebuffer_desc){ .width = FW, .height = FH }, &f.fb);
    fixture_clear(&f);
    return f;
}

static void fixture_free(fixture *f)
{
    sr_destroy_framebuffer(f->ctx, f->fb);
    sr_destroy_context(f->ctx);
}

static bool unchanged(fixture *f)
{
    float d[FW * FH];
    sr_read_depth(f->ctx, f->fb, 0, 0, FW, FH, d, FW);
    return memcmp(sr_framebuffer_pixels(f->fb), f->color, sizeof f->color) == 0 &&
           memcmp(d, f->depth, sizeof d) == 0;
}

/* One triangle covering the whole target, in front of the cleared depth. */
static const float tri_pos[9] = { -3, -3, 0, 3, -3, 0, 0, 3, 0 };
static const float tri_nrm[9] = { 0, 0, 1, 0, 0, 1, 0, 0, 1 };

static sr_state valid_state(void)
{
    return (sr_state){ .material = { .diffuse = { 1, 0, 0 } } };
}

static sr_draw_desc valid_draw(void)
{
    return (sr_draw_desc){ .positions = tri_pos, .vertex_count = 3 };
}

SR_TEST(the_valid_draw_changes_the_framebuffer)
{
    /* Otherwise "unchanged" below would prove nothing. */
    fixture f = fixture_make();
    sr_state st = valid_state();
    sr_draw_desc d = valid_draw();
    REQUIRE(sr_draw(f.ctx, f.fb, &st, &d) == SR_OK);
    CHECK(!unchanged(&f));
    CHECK_EQ(sr_last_draw_info(f.ctx).fragments, FW * FH);
    CHECK(strcmp(sr_context_error(f.ctx), "") == 0);
    fixture_free(&f);
}

/* ---- sr_draw -------------------------------------------------------------- */

typedef struct bad_draw {
    const char *needle;        /* must appear in the message */
    sr_result code;
} bad_draw;

static const float nan_f = NAN;

/* Apply invalid case i to a valid state and draw; false when i is past the
 * last case. */
static bool make_bad(int i, sr_state *st, sr_draw_desc *d, sr_mat4 *m, bad_draw *want)
{
    static const uint8_t idx8[6] = { 0, 1, 2, 2, 1, 3 };
    static const uint16_t idx16[3] = { 0, 65535, 1 };
    static const uint32_t idx32[3] = { 0, 1, 0xffffffffu };
    static const uint32_t idx32b[3] = { 3, 1, 2 };
    static const float pos3[9] = { 0 };
    /* Room for the triangle one to three bytes past a float boundary. */
    static float shifted[16];
    static uint32_t idx_bytes[4];
    const char *odd = (const char *)shifted + 1, *idx_odd = (const char *)idx_bytes + 2;
    *m = sr_mat4_identity();
    *want = (bad_draw){ NULL, SR_INVALID_ARG };
    switch (i) {
    case 0:  st->cull = (sr_cull_mode)99;                 want->needle = "sr_state.cull"; break;
    case 1:  st->cull = (sr_cull_mode)-1;                 want->needle = "sr_state.cull"; break;
    case 2:  st->front_face = (sr_front_face)7;           want->needle = "sr_state.front_face"; break;
    case 3:  st->depth_func = (sr_depth_func)9;           want->needle = "sr_state.depth_func"; break;
    case 4:  st->rasterizer = (sr_rasterizer)4;           want->needle = "sr_state.rasterizer"; break;
    case 5:  st->interpolation = (sr_interpolation)3;     want->needle = "sr_state.interpolation"; break;
    case 6:  st->provoking = (sr_provoking_vertex)3;      want->needle = "sr_state.provoking"; break;
    case 7:  st->shading = (sr_shading)(SR_SHADING_ATTRIBUTE + 1); want->needle = "sr_state.shading"; break;
    case 8:  st->shading = (sr_shading)-2;                want->needle = "sr_state.shading"; break;
    case 9:  st->lights[3].type = (sr_light_type)5;       want->needle = "sr_state.lights[3].type"; break;
    case 10: st->lights[0].type = SR_LIGHT_DIRECTIONAL;   want->needle = "sr_state.lights[0].vector"; break;
    case 11: st->lights[2] = (sr_light){ .type = SR_LIGHT_POINT, .vector = { nan_f, 0, 0 } };
             want->needle = "sr_state.lights[2]"; break;
    case 12: st->viewport = (sr_viewport){ 0, 0, -1, 8 };  want->needle = "sr_state.viewport"; break;
    case 13: st->viewport = (sr_viewport){ 0, 0, 0, 4 };   want->needle = "sr_state.viewport"; break;
    case 14: st->viewport = (sr_viewport){ -20000, 0, 8, 8 }; want->needle = "sr_state.viewport"; break;
    case 15: st->viewport = (sr_viewport){ 0, 0, 9000, 8 }; want->needle = "sr_state.viewport"; break;
    case 16: st->viewport = (sr_viewport){ 0, 16380, 8, 8 }; want->needle = "sr_state.viewport"; break;
    case 17: st->depth_far = nan_f;                        want->needle = "depth_far"; break;
    case 18: st->depth_near = -0.1f; st->depth_far = -nan_f; want->needle = "depth_far"; break;
    case 19: st->depth_near = nan_f;                       want->needle = "depth_near"; break;
    case 20: st->offset.units = nan_f;                     want->needle = "sr_state.offset"; break;
    case 21: st->offset.clamp = INFINITY;                  want->needle = "sr_state.offset"; break;
    case 22: st->material.opacity = 2;                     want->needle = "sr_state.material"; break;
    case 23: st->material.shininess = -1;                  want->needle = "sr_state.material"; break;
    case 24: st->material.diffuse.y = nan_f;               want->needle = "sr_state.material"; break;
    case 25: st->ambient.x = INFINITY;                     want->needle = "sr_state.ambient"; break;
    case 26: m->m[5] = nan_f; d->model = m;                want->needle = "sr_draw_desc.model"; break;
    case 27: m->m[12] = INFINITY; d->view = m;             want->needle = "sr_draw_desc.view"; break;
    case 28: m->m[11] = nan_f; d->projection = m;          want->needle = "sr_draw_desc.projection"; break;
    case 29: d->position_size = 2;                         want->needle = "sr_draw_desc.position_size"; break;
    case 30: d->position_size = 5;                         want->needle = "sr_draw_desc.position_size"; break;
    case 31: d->color_size = 2; d->colors = pos3;          want->needle = "sr_draw_desc.color_size"; break;
    case 32: d->primitive = (sr_primitive)9;               want->needle = "sr_draw_desc.primitive"; break;
    case 33: d->index_type = (sr_index_type)7;             want->needle = "sr_draw_desc.index_type"; break;
    case 34: d->index_type = SR_INDEX_U16; d->index_count = 3;
             want->needle = "sr_draw_desc.indices"; break;
    case 35: d->indices = idx16;                           want->needle = "sr_draw_desc.indices"; break;
    case 36: d->positions = NULL;                          want->needle = "sr_draw_desc.positions"; break;
    case 37: st->shading = SR_SHADING_GOURAUD;             want->needle = "sr_draw_desc.normals"; break;
    case 38: st->shading = SR_SHADING_PHONG;               want->needle = "sr_draw_desc.normals"; break;
    case 39: st->shading = SR_SHADING_NORMALS;             want->needle = "sr_draw_desc.normals"; break;
    /* Index out of range: the message gives the position and the value. */
    case 40: d->indices = idx8; d->index_type = SR_INDEX_U8; d->index_count = 6;
             want->needle = "indices[5] = 3"; break;
    case 41: d->indices = idx16; d->index_type = SR_INDEX_U16; d->index_count = 3;
             want->needle = "indices[1] = 65535"; break;
    case 42: d->indices = idx32; d->index_type = SR_INDEX_U32; d->index_count = 3;
             want->needle = "indices[2] = 4294967295"; break;
    case 43: d->indices = idx32b; d->index_type = SR_INDEX_U32; d->index_count = 3;
             want->needle = "indices[0] = 3"; break;
    case 44: d->vertex_count = ((size_t)1 << 28) + 1;
             *want = (bad_draw){ "sr_draw_desc.vertex_count", SR_TOO_LARGE }; break;
    /* Attributes are read as floats in place: an array and its stride
     * must be multiples of 4 bytes, indices of their size. */
    case 45: d->position_stride = 13;                      want->needle = "position_stride 13"; break;
    case 46: d->normals = tri_nrm; d->normal_stride = 6;   want->needle = "sr_draw_desc.normal_stride"; break;
    case 47: d->colors = pos3; d->color_stride = 14;       want->needle = "sr_draw_desc.color_stride"; break;
    case 48: d->texcoords = pos3; d->texcoord_stride = 9;  want->needle = "sr_draw_desc.texcoord_stride"; break;
    case 49: d->generic = pos3; d->generic_stride = 1;     want->needle = "sr_draw_desc.generic_stride"; break;
    case 50: memcpy(shifted, tri_pos, sizeof tri_pos);
             d->positions = (const float *)(const void *)odd;
             want->needle = "sr_draw_desc.positions is not 4-byte aligned"; break;
    case 51: d->colors = (const float *)(const void *)(odd + 2); want->needle = "sr_draw_desc.colors"; break;
    case 52: d->indices = idx_odd; d->index_type = SR_INDEX_U32; d->index_count = 3;
             want->needle = "sr_draw_desc.indices is not 4-byte aligned"; break;
    case 53: d->indices = idx_odd + 1; d->index_type = SR_INDEX_U16; d->index_count = 3;
             want->needle = "sr_draw_desc.indices is not 2-byte aligned"; break;
    /* A range without SR_DEPTH_RANGE_SET would be ignored: refused. */
    case 54: st->depth_range = (sr_depth_range_mode)2;      want->needle = "sr_state.depth_range 2"; break;
    case 55: st->depth_near = 0.25f;                       want->needle = "SR_DEPTH_RANGE_SET"; break;
    case 56: st->depth_far = 0.5f;                         want->needle = "SR_DEPTH_RANGE_SET"; break;
    default: return false;
    }
    return true;
}

SR_TEST(every_invalid_draw_argument_is_named_and_draws_nothing)
{
    fixture f = fixture_make();
    int cases = 0;
    for (int i = 0;; i++) {
        sr_state st = valid_state();
        sr_draw_desc d = valid_draw();
        sr_mat4 m;
        bad_draw want;
        if (!make_bad(i, &st, &d, &m, &want)) {
            break;
        }
        cases++;
        /* A success first, so a stale message cannot satisfy the check. */
        sr_state ok_st = valid_state();
        sr_draw_desc ok_d = valid_draw();
        ok_d.vertex_count = 0;
        REQUIRE(sr_draw(f.ctx, f.fb, &ok_st, &ok_d) == SR_OK);
        REQUIRE(strcmp(sr_context_error(f.ctx), "") == 0);

        sr_result r = sr_draw(f.ctx, f.fb, &st, &d);
        if (r != want.code || !strstr(sr_context_error(f.ctx), want.needle)) {
            fprintf(stderr, "case %d: %s \"%s\"\n", i, sr_result_name(r), sr_context_error(f.ctx));
        }
        CHECK_EQ(r, want.code);
        CHECK_STR_CONTAINS(sr_context_error(f.ctx), want.needle);
        CHECK(unchanged(&f));
        CHECK_EQ(sr_last_draw_info(f.ctx).fragments, 0);
        CHECK_EQ(sr_last_draw_info(f.ctx).triangles_in, 0);
    }
    CHECK_EQ(cases, 57);
    fixture_free(&f);
}

SR_TEST(null_draw_arguments_are_rejected)
{
    fixture f = fixture_make();
    sr_state st = valid_state();
    sr_draw_desc d = valid_draw();
    CHECK_EQ(sr_draw(NULL, f.fb, &st, &d), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(NULL), "NULL");
    CHECK_EQ(sr_draw(f.ctx, NULL, &st, &d), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "fb");
    CHECK_EQ(sr_draw(f.ctx, f.fb, NULL, &d), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "state");
    CHECK_EQ(sr_draw(f.ctx, f.fb, &st, NULL), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "draw");
    CHECK(unchanged(&f));
    /* Zero vertices with NULL arrays is a valid empty draw. */
    CHECK_EQ(sr_draw(f.ctx, f.fb, &st, &(sr_draw_desc){ 0 }), SR_OK);
    CHECK(strcmp(sr_context_error(f.ctx), "") == 0);
    CHECK(unchanged(&f));
    fixture_free(&f);
}

/* The valid edge of each range is accepted. */
SR_TEST(boundary_values_are_accepted)
{
    fixture f = fixture_make();
    sr_state st = valid_state();
    sr_draw_desc d = valid_draw();
    st.depth_range = SR_DEPTH_RANGE_SET;
    st.depth_near = 1.0f;
    st.depth_far = 0.0f;
    st.material.opacity = 1.0f;
    st.material.shininess = 0.0f;
    st.viewport = (sr_viewport){ -16384, -16384, 8192, 8192 };
    st.lights[7] = (sr_light){ .type = SR_LIGHT_POINT };
    CHECK_EQ(sr_draw(f.ctx, f.fb, &st, &d), SR_OK);
    d.position_size = 4;
    const float p4[12] = { -3, -3, 0, 1, 3, -3, 0, 1, 0, 3, 0, 1 };
    d.positions = p4;
    st = valid_state();
    st.shading = SR_SHADING_GOURAUD;
    d.normals = tri_nrm;
    CHECK_EQ(sr_draw(f.ctx, f.fb, &st, &d), SR_OK);
    const uint8_t idx[3] = { 2, 1, 0 };
    d.indices = idx;
    d.index_type = SR_INDEX_U8;
    d.index_count = 3;
    CHECK_EQ(sr_draw(f.ctx, f.fb, &st, &d), SR_OK);
    /* Any multiple of 4 is a stride, also one that is not a whole vertex
     * (the arrays overlap) or, for bytes, an odd address. */
    d.position_size = 3;
    d.position_stride = 16;
    d.normal_stride = 4;
    CHECK_EQ(sr_draw(f.ctx, f.fb, &st, &d), SR_OK);
    const uint8_t idx_odd[4] = { 0, 2, 1, 0 };
    d.indices = idx_odd + 1;
    CHECK_EQ(sr_draw(f.ctx, f.fb, &st, &d), SR_OK);
    fixture_free(&f);
}

/* ---- framebuffers, clear, read ------------------------------------------ */

SR_TEST(invalid_framebuffer_descs_are_named)
{
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    struct { sr_framebuffer_desc d; sr_result code; const char *needle; } cases[] = {
        { { .width = 0, .height = 8 }, SR_INVALID_ARG, "sr_framebuffer_desc.width" },
        { { .width = -5, .height = 8 }, SR_INVALID_ARG, "sr_framebuffer_desc.width" },
        { { .width = 8, .height = 0 }, SR_INVALID_ARG, "sr_framebuffer_desc.height" },
        { { .width = 8, .height = -3 }, SR_INVALID_ARG, "sr_framebuffer_desc.height" },
        { { .width = 8193, .height = 8 }, SR_TOO_LARGE, "sr_framebuffer_desc.width" },
        { { .width = 8, .height = 10000 }, SR_TOO_LARGE, "sr_framebuffer_desc.height" },
        { { .width = INT_MAX, .height = INT_MAX }, SR_TOO_LARGE, "sr_framebuffer_desc" },
        { { .width = 8, .height = 8, .depth_format = (sr_depth_format)99 }, SR_INVALID_ARG,
          "sr_framebuffer_desc.depth_format" },
        { { .width = 8, .height = 8, .depth_format = (sr_depth_format)-1 }, SR_INVALID_ARG,
          "sr_framebuffer_desc.depth_format" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        sr_framebuffer *fb = (sr_framebuffer *)&ctx; /* must be reset to NULL */
        sr_result r = sr_make_framebuffer(ctx, &cases[i].d, &fb);
        CHECK_EQ(r, cases[i].code);
        CHECK(fb == NULL);
        CHECK_STR_CONTAINS(sr_context_error(ctx), cases[i].needle);
    }
    sr_framebuffer *fb;
    CHECK_EQ(sr_make_framebuffer(NULL, &(sr_framebuffer_desc){ .width = 8, .height = 8 }, &fb), SR_INVALID_ARG);
    CHECK_EQ(sr_make_framebuffer(ctx, NULL, &fb), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "desc");
    CHECK_EQ(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 8, .height = 8 }, NULL), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "out");
    /* The limits themselves are fine (8192 x 1 is small). */
    CHECK_EQ(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 8192, .height = 1 }, &fb), SR_OK);
    CHECK(strcmp(sr_context_error(ctx), "") == 0);
    CHECK_EQ(sr_framebuffer_width(fb), 8192);
    CHECK_EQ(sr_framebuffer_depth_format(fb), SR_DEPTH_D24);
    sr_destroy_framebuffer(ctx, fb);
    CHECK_EQ(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 1, .height = 8192,
                                                             .depth_format = SR_DEPTH_NONE }, &fb), SR_OK);
    CHECK_EQ(sr_framebuffer_depth_format(fb), SR_DEPTH_NONE);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(invalid_clear_and_read_arguments_are_named)
{
    fixture f = fixture_make();
    struct { sr_clear_desc d; const char *needle; } clears[] = {
        { { .depth = 1.5f }, "sr_clear_desc.depth" },
        { { .depth = -0.1f }, "sr_clear_desc.depth" },
        { { .depth = NAN }, "sr_clear_desc.depth" },
        { { .color = { 0, 0, NAN, 1 }, .depth = 1 }, "sr_clear_desc.color[2]" },
        { { .color = { INFINITY, 0, 0, 1 }, .depth = 1 }, "sr_clear_desc.color[0]" },
    };
    for (size_t i = 0; i < sizeof clears / sizeof clears[0]; i++) {
        CHECK_EQ(sr_clear(f.ctx, f.fb, &clears[i].d), SR_INVALID_ARG);
        CHECK_STR_CONTAINS(sr_context_error(f.ctx), clears[i].needle);
        CHECK(unchanged(&f));
    }
    CHECK_EQ(sr_clear(NULL, f.fb, &(sr_clear_desc){ .depth = 1 }), SR_INVALID_ARG);
    CHECK_EQ(sr_clear(f.ctx, NULL, &(sr_clear_desc){ .depth = 1 }), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "fb");
    CHECK_EQ(sr_clear(f.ctx, f.fb, NULL), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "desc");
    CHECK(unchanged(&f));

    uint8_t px[FW * FH * 4];
    float d[FW * FH];
    const int rects[][4] = { { -1, 0, 1, 1 }, { 0, -1, 1, 1 }, { 6, 0, 4, 1 }, { 0, 7, 1, 2 },
                             { 0, 0, 0, 1 }, { 0, 0, 1, 0 }, { 8, 0, 1, 1 }, { 1, 1, INT_MAX, 1 },
                             { 0, 0, FW + 1, FH } };
    for (size_t i = 0; i < sizeof rects / sizeof rects[0]; i++) {
        const int *r = rects[i];
        CHECK_EQ(sr_read_pixels(f.ctx, f.fb, r[0], r[1], r[2], r[3], px, sizeof px), SR_INVALID_ARG);
        CHECK_STR_CONTAINS(sr_context_error(f.ctx), "sr_read_pixels: rectangle");
        CHECK_EQ(sr_read_depth(f.ctx, f.fb, r[0], r[1], r[2], r[3], d, FW * FH), SR_INVALID_ARG);
        CHECK_STR_CONTAINS(sr_context_error(f.ctx), "sr_read_depth: rectangle");
        CHECK_EQ(sr_write_pixels(f.ctx, f.fb, r[0], r[1], r[2], r[3], px, sizeof px),
                 SR_INVALID_ARG);
        CHECK_STR_CONTAINS(sr_context_error(f.ctx), "sr_write_pixels: rectangle");
    }
    /* A refused write writes nothing. */
    CHECK_EQ(sr_write_pixels(f.ctx, f.fb, 0, 0, 2, 2, px, 7), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "sr_write_pixels: stride 7");
    CHECK_EQ(sr_write_pixels(f.ctx, f.fb, 0, 0, 2, 2, NULL, 8), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "sr_write_pixels: rgba is NULL");
    CHECK_EQ(sr_write_pixels(f.ctx, NULL, 0, 0, 2, 2, px, 8), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "sr_write_pixels: fb is NULL");
    CHECK_EQ(sr_write_pixels(NULL, f.fb, 0, 0, 2, 2, px, 8), SR_INVALID_ARG);
    CHECK(unchanged(&f));
    CHECK_EQ(sr_read_pixels(f.ctx, f.fb, 0, 0, 2, 2, px, 7), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "stride");
    CHECK_EQ(sr_read_depth(f.ctx, f.fb, 0, 0, 2, 2, d, 1), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "stride");
    CHECK_EQ(sr_read_pixels(f.ctx, f.fb, 0, 0, 2, 2, NULL, 8), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "out");
    CHECK_EQ(sr_read_pixels(f.ctx, NULL, 0, 0, 2, 2, px, 8), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "fb");
    CHECK_EQ(sr_read_pixels(NULL, f.fb, 0, 0, 2, 2, px, 8), SR_INVALID_ARG);
    /* The whole framebuffer and the last pixel are fine. */
    CHECK_EQ(sr_read_pixels(f.ctx, f.fb, 0, 0, FW, FH, px, FW * 4), SR_OK);
    CHECK(memcmp(px, f.color, sizeof px) == 0);
    CHECK_EQ(sr_read_depth(f.ctx, f.fb, FW - 1, FH - 1, 1, 1, d, 1), SR_OK);
    CHECK(d[0] == f.depth[FW * FH - 1]);
    CHECK(strcmp(sr_context_error(f.ctx), "") == 0);

    sr_framebuffer *nodepth;
    REQUIRE(sr_make_framebuffer(f.ctx, &(sr_framebuffer_desc){ .width = 4, .height = 4,
                                                              .depth_format = SR_DEPTH_NONE }, &nodepth) == SR_OK);
    CHECK_EQ(sr_read_depth(f.ctx, nodepth, 0, 0, 1, 1, d, 1), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "depth buffer");
    /* Clearing depth that does not exist is not an error. */
    CHECK_EQ(sr_clear(f.ctx, nodepth, &(sr_clear_desc){ .depth = 1 }), SR_OK);
    sr_destroy_framebuffer(f.ctx, nodepth);
    fixture_free(&f);
}

/* A buffer with guard bytes on both sides: a stride that wraps the
 * address space lands its second row just before the buffer. */
typedef struct guarded {
    uint8_t before[64];
    uint8_t buf[256];
    uint8_t after[64];
} guarded;

static bool guards_intact(const guarded *g)
{
    for (size_t i = 0; i < sizeof g->before; i++) {
        if (g->before[i] != 0xa5 || g->after[i] != 0xa5) {
            return false;
        }
    }
    return true;
}

SR_TEST(strides_that_wrap_the_address_space_are_refused)
{
    fixture f = fixture_make();
    guarded g;
    memset(&g, 0xa5, sizeof g);
    /* Row 1 at buf + SIZE_MAX is buf - 1: a stride no buffer can have. */
    CHECK_EQ(sr_read_pixels(f.ctx, f.fb, 0, 0, 2, 2, g.buf, SIZE_MAX), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "sr_read_pixels: 2 rows of stride");
    CHECK_EQ(sr_read_pixels(f.ctx, f.fb, 0, 0, 2, FH, g.buf, SIZE_MAX / 4), SR_INVALID_ARG);
    CHECK_EQ(sr_write_pixels(f.ctx, f.fb, 0, 0, 2, 2, g.buf, SIZE_MAX), SR_INVALID_ARG);
    CHECK_EQ(sr_write_pixels(f.ctx, f.fb, 0, 0, 2, 2, g.buf, SIZE_MAX / 2), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "sr_write_pixels: 2 rows of stride");
    /* SIZE_MAX / 4 floats is SIZE_MAX - 3 bytes: row 1 one float before. */
    CHECK_EQ(sr_read_depth(f.ctx, f.fb, 0, 0, 2, 2, (float *)(void *)g.buf, SIZE_MAX / 4),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "sr_read_depth: 2 rows of stride");
    CHECK_EQ(sr_read_depth(f.ctx, f.fb, 0, 0, 2, 2, (float *)(void *)g.buf, SIZE_MAX / 2),
             SR_INVALID_ARG);
    CHECK(unchanged(&f));

    sr_framebuffer *st;
    REQUIRE(sr_make_framebuffer(f.ctx, &(sr_framebuffer_desc){ .width = 4, .height = 4,
                                                              .stencil = true }, &st) == SR_OK);
    CHECK_EQ(sr_read_stencil(f.ctx, st, 0, 0, 2, 2, g.buf, SIZE_MAX), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "sr_read_stencil: 2 rows of stride");
    sr_destroy_framebuffer(f.ctx, st);

    sr_texture *tex = NULL;
    CHECK_EQ(sr_make_texture(f.ctx, &(sr_texture_desc){ .width = 2, .height = 2, .pixels = g.buf,
                                                        .stride = SIZE_MAX }, &tex),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "sr_texture_desc: 2 rows of stride");
    CHECK(tex == NULL);

    const sr_point2 tri[3] = { { 0, 0 }, { 4, 0 }, { 0, 4 } };
    const sr_polygon2 poly = { .points = tri, .point_count = 3 };
    CHECK_EQ(sr_polygon_coverage(f.ctx, &poly, NULL, 0, 0, 2, 2, g.buf, SIZE_MAX),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "sr_polygon_coverage: 2 rows of stride");
    CHECK_EQ(sr_draw_coverage(f.ctx, f.fb, 0, 0, 2, 2, g.buf, SIZE_MAX,
                              (sr_rgba){ 1, 1, 1, 1 }), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "sr_draw_coverage: 2 rows of stride");
    CHECK(unchanged(&f));
    CHECK(guards_intact(&g));

    /* The largest stride that still fits is taken. */
    CHECK_EQ(sr_read_pixels(f.ctx, f.fb, 0, 0, 2, 1, g.buf, SIZE_MAX), SR_OK);
    CHECK(guards_intact(&g));
    fixture_free(&f);
}

SR_TEST(write_pixels_may_move_a_rectangle_within_the_framebuffer)
{
    fixture f = fixture_make();
    uint8_t img[FW * FH * 4], want[FW * FH * 4];
    for (size_t i = 0; i < sizeof img; i++) {
        img[i] = (uint8_t)(i * 7 + i / 32);
    }
    REQUIRE(sr_write_pixels(f.ctx, f.fb, 0, 0, FW, FH, img, FW * 4) == SR_OK);
    /* Down one row and right one column, from the framebuffer's own pixels:
     * every pixel takes the value it had before the call. */
    memcpy(want, img, sizeof want);
    for (int y = 1; y < FH; y++) {
        memcpy(want + (y * FW + 1) * 4, img + ((y - 1) * FW) * 4, (FW - 1) * 4);
    }
    const uint8_t *own = sr_framebuffer_pixels(f.fb);
    REQUIRE(sr_write_pixels(f.ctx, f.fb, 1, 1, FW - 1, FH - 1, own, FW * 4) == SR_OK);
    CHECK(memcmp(sr_framebuffer_pixels(f.fb), want, sizeof want) == 0);
    /* And back up: the other direction of overlap. */
    own = sr_framebuffer_pixels(f.fb);
    REQUIRE(sr_write_pixels(f.ctx, f.fb, 0, 0, FW - 1, FH - 1, own + (FW + 1) * 4, FW * 4) == SR_OK);
    for (int y = 0; y < FH - 1; y++) {
        CHECK(memcmp(sr_framebuffer_pixels(f.fb) + y * FW * 4, img + y * FW * 4, (FW - 1) * 4) == 0);
    }
    fixture_free(&f);
}

static void *only_alloc(size_t n, void *user)
{
    (void)user;
    return malloc(n);
}

SR_TEST(invalid_context_descs_are_rejected)
{
    sr_context *ctx = (sr_context *)&ctx;
    CHECK_EQ(sr_make_context(&(sr_context_desc){ .threads = -1 }, &ctx), SR_INVALID_ARG);
    CHECK(ctx == NULL);
    ctx = (sr_context *)&ctx;
    CHECK_EQ(sr_make_context(&(sr_context_desc){ .threads = 100000 }, &ctx), SR_INVALID_ARG);
    CHECK(ctx == NULL);
    CHECK_EQ(sr_make_context(&(sr_context_desc){ .allocator = { .alloc = only_alloc } }, &ctx), SR_INVALID_ARG);
    CHECK(ctx == NULL);
    CHECK_EQ(sr_make_context(&(sr_context_desc){ .threads = 1 }, NULL), SR_INVALID_ARG);
    static const int bad_batches[] = { -1, 1, SR_BATCH_MIN - 1, SR_BATCH_MAX + 1 };
    for (int i = 0; i < 4; i++) {
        ctx = (sr_context *)&ctx;
        CHECK_EQ(sr_make_context(&(sr_context_desc){ .batch_primitives = bad_batches[i] }, &ctx),
                 SR_INVALID_ARG);
        CHECK(ctx == NULL);
    }
    /* An arena that would run past the end of memory describes no memory. */
    static uint8_t arena[4096];
    ctx = (sr_context *)&ctx;
    CHECK_EQ(sr_make_context(&(sr_context_desc){ .arena = arena, .arena_size = SIZE_MAX }, &ctx),
             SR_INVALID_ARG);
    CHECK(ctx == NULL);
    CHECK_EQ(sr_make_context(&(sr_context_desc){ .batch_primitives = SR_BATCH_MIN }, &ctx), SR_OK);
    sr_destroy_context(ctx);
    /* NULL desc means all defaults. */
    CHECK_EQ(sr_make_context(NULL, &ctx), SR_OK);
    CHECK(sr_context_threads(ctx) >= 1);
    CHECK(strcmp(sr_context_error(ctx), "") == 0);
    sr_destroy_context(ctx);
    sr_destroy_context(NULL);
}

/* ---- result strings ------------------------------------------------------- */

SR_TEST(every_result_has_a_name_and_a_text)
{
    static const struct { sr_result r; const char *name, *text; } list[] = {
#define X(name, text) { SR_##name, "SR_" #name, text },
        SR_RESULT_LIST(X)
#undef X
    };
    CHECK_EQ(sizeof list / sizeof list[0], SR_RESULT_COUNT);
    for (int i = 0; i < SR_RESULT_COUNT; i++) {
        CHECK_EQ(list[i].r, i);
        CHECK(strcmp(sr_result_name((sr_result)i), list[i].name) == 0);
        CHECK(strcmp(sr_result_text((sr_result)i), list[i].text) == 0);
        CHECK(strlen(sr_result_text((sr_result)i)) > 0);
        for (int j = 0; j < i; j++) {
            CHECK(strcmp(sr_result_name((sr_result)i), sr_result_name((sr_result)j)) != 0);
            CHECK(strcmp(sr_result_text((sr_result)i), sr_result_text((sr_result)j)) != 0);
        }
    }
    CHECK_EQ(SR_OK, 0);
    CHECK(strcmp(sr_result_name(SR_OK), "SR_OK") == 0);
    CHECK(strcmp(sr_result_text(SR_OK), "success") == 0);
    CHECK(strcmp(sr_result_name(SR_INVALID_ARG), "SR_INVALID_ARG") == 0);
    CHECK(strcmp(sr_result_name(SR_OUT_OF_MEMORY), "SR_OUT_OF_MEMORY") == 0);
    CHECK(strcmp(sr_result_text(SR_OUT_OF_MEMORY), "allocation failed") == 0);
    CHECK(strcmp(sr_result_name(SR_TOO_LARGE), "SR_TOO_LARGE") == 0);
    CHECK(strcmp(sr_result_name(SR_UNSUPPORTED), "SR_UNSUPPORTED") == 0);
    CHECK(strcmp(sr_result_name(SR_IO_ERROR), "SR_IO_ERROR") == 0);
    CHECK(strcmp(sr_result_name(SR_BAD_FORMAT), "SR_BAD_FORMAT") == 0);
    /* Out of range values get a placeholder, not a crash. */
    CHECK(sr_result_name(SR_RESULT_COUNT) != NULL);
    CHECK(sr_result_text((sr_result)-1) != NULL);
    CHECK(strcmp(sr_result_name((sr_result)1000), sr_result_name(SR_OK)) != 0);
}

/* ---- allocation failure injection ----------------------------------------- */

/* Fails allocation number fail_at (counting from 0), or every allocation
 * from fail_at on when sticky; counts live blocks.  Thread-safe: the front
 * end may allocate from worker threads. */
typedef struct counting_alloc {
    atomic_long calls;
    atomic_long live;
    atomic_long fail_at;       /* -1: never */
    bool sticky;
} counting_alloc;

static void *ca_alloc(size_t n, void *user)
{
    counting_alloc *a = user;
    long k = atomic_fetch_add(&a->calls, 1);
    long f = atomic_load(&a->fail_at);
    if (f >= 0 && (k == f || (a->sticky && k > f))) {
        return NULL;
    }
    void *p = malloc(n);
    if (p) {
        atomic_fetch_add(&a->live, 1);
    }
    return p;
}

static void ca_free(void *p, void *user)
{
    counting_alloc *a = user;
    if (p) {
        atomic_fetch_sub(&a->live, 1);
    }
    free(p);
}

static void ca_init(counting_alloc *a, bool sticky)
{
    atomic_init(&a->calls, 0);
    atomic_init(&a->live, 0);
    atomic_init(&a->fail_at, -1);
    a->sticky = sticky;
}

/* Fail the k-th allocation from now on. */
static void ca_arm(counting_alloc *a, long k) { atomic_store(&a->fail_at, atomic_load(&a->calls) + k); }
static void ca_disarm(counting_alloc *a) { atomic_store(&a->fail_at, -1); }

static sr_context_desc ca_desc(counting_alloc *a, int threads)
{
    return (sr_context_desc){ .allocator = { ca_alloc, ca_free, a }, .threads = threads };
}

SR_TEST(context_creation_survives_every_allocation_failure)
{
    for (int sticky = 0; sticky <= 1; sticky++) {
        for (int threads = 1; threads <= 2; threads++) {
            counting_alloc a;
            ca_init(&a, sticky);
            int failures = 0;
            for (long k = 0; k < 1000; k++) {
                ca_arm(&a, k);
                sr_context *ctx = (sr_context *)&a;
                sr_result r = sr_make_context(&(sr_context_desc){ .allocator = { ca_alloc, ca_free, &a },
                                                                  .threads = threads }, &ctx);
                ca_disarm(&a);
                if (r == SR_OK) {
                    CHECK(ctx != NULL);
                    CHECK_EQ(sr_context_threads(ctx), threads);
                    sr_destroy_context(ctx);
                    break;
                }
                failures++;
                CHECK_EQ(r, SR_OUT_OF_MEMORY);
                CHECK(ctx == NULL);
                CHECK_EQ(atomic_load(&a.live), 0);
            }
            /* The context and its scratch at least; the pool with 2 threads. */
            CHECK(failures >= threads);
            CHECK_EQ(atomic_load(&a.live), 0);
        }
    }
}

SR_TEST(framebuffer_creation_survives_every_allocation_failure)
{
    const sr_depth_format fmts[] = { SR_DEPTH_D24, SR_DEPTH_NONE, SR_DEPTH_D32F };
    /* ms: multisampled with a stencil buffer, which adds the stencil and
     * the resolve buffer to the allocations. */
    for (int sticky = 0; sticky <= 1; sticky++) {
        for (int fi = 0; fi < 6; fi++) {
            bool ms = fi >= 3;
            counting_alloc a;
            ca_init(&a, sticky);
            sr_context *ctx;
            REQUIRE(sr_make_context(&(sr_context_desc){ .allocator = { ca_alloc, ca_free, &a },
                                                        .threads = 1 }, &ctx) == SR_OK);
            long base = atomic_load(&a.live);
            int failures = 0;
            for (long k = 0; k < 1000; k++) {
                sr_framebuffer *fb = (sr_framebuffer *)&a;
                ca_arm(&a, k);
                sr_result r = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 100, .height = 70,
                                                                              .depth_format = fmts[fi % 3],
                                                                              .samples = ms ? 4 : 0,
                                                                              .stencil = ms }, &fb);
                ca_disarm(&a);
                if (r == SR_OK) {
                    /* Usable: clear and read back. */
                    CHECK_EQ(sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 1, 0, 0, 1 }, .depth = 1 }), SR_OK);
                    CHECK_EQ(sr_framebuffer_pixels(fb)[(70 * 100 - 1) * 4], 255);
                    sr_destroy_framebuffer(ctx, fb);
                    break;
                }
                failures++;
                CHECK_EQ(r, SR_OUT_OF_MEMORY);
                CHECK(fb == NULL);
                CHECK_STR_CONTAINS(sr_context_error(ctx), "out of memory");
                CHECK_EQ(atomic_load(&a.live), base);
            }
            CHECK(failures >= (fmts[fi % 3] == SR_DEPTH_NONE ? 2 : 3) + (ms ? 2 : 0));
            CHECK_EQ(atomic_load(&a.live), base);
            sr_destroy_context(ctx);
            CHECK_EQ(atomic_load(&a.live), 0);
        }
    }
}

/* A grid of many colored triangles: enough vertices and triangles to make
 * the scratch memory grow. */
typedef struct mesh {
    float *pos, *col;
    uint32_t *idx;
    int nv, ni;
} mesh;

static mesh make_grid(int n)
{
    mesh m;
    m.nv = (n + 1) * (n + 1);
    m.ni = 6 * n * n;
    m.pos = malloc(sizeof(float) * 3 * (size_t)m.nv);
    m.col = malloc(sizeof(float) * 4 * (size_t)m.nv);
    m.idx = malloc(sizeof(uint32_t) * (size_t)m.ni);
    sr_rng rng = { 0x911d };
    for (int j = 0; j <= n; j++) {
        for (int i = 0; i <= n; i++) {
            int k = j * (n + 1) + i;
            m.pos[k * 3] = (float)(-1.1 + 2.2 * i / n + sr_rng_range(&rng, -0.2, 0.2) / n);
            m.pos[k * 3 + 1] = (float)(-1.1 + 2.2 * j / n + sr_rng_range(&rng, -0.2, 0.2) / n);
            m.pos[k * 3 + 2] = (float)sr_rng_range(&rng, -0.9, 0.9);
            for (int c = 0; c < 3; c++) {
                m.col[k * 4 + c] = (float)sr_rng_unit(&rng);
            }
            m.col[k * 4 + 3] = 1;
        }
    }
    int t = 0;
    for (int j = 0; j < n; j++) {
        for (int i = 0; i < n; i++) {
            uint32_t a = (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)n + 1, d = c + 1;
            const uint32_t q[6] = { a, b, d, a, d, c };
            memcpy(m.idx + t, q, sizeof q);
            t += 6;
        }
    }
    return m;
}

static void free_mesh(mesh *m)
{
    free(m->pos);
    free(m->col);
    free(m->idx);
}

enum { DW = 200, DH = 150 };

static sr_result draw_mesh(sr_context *ctx, sr_framebuffer *fb, const mesh *m)
{
    sr_state st = { .depth_func = SR_LESS };
    return sr_draw(ctx, fb, &st, &(sr_draw_desc){ .positions = m->pos, .colors = m->col,
                                                 .vertex_count = (size_t)m->nv, .indices = m->idx,
                                                 .index_type = SR_INDEX_U32, .index_count = (size_t)m->ni });
}

static void clear_target(sr_context *ctx, sr_framebuffer *fb)
{
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 }, .depth = 1 });
}

/* For k = 0, 1, 2, ...: a fresh context and framebuffer, an optional
 * warm-up draw (so the big draw has to grow scratch that already exists),
 * then the big draw with allocation k failing.  Each failure returns
 * SR_OUT_OF_MEMORY; the context then still draws the reference image, and
 * destroying everything frees every block. */
static void draw_failures(int threads, bool warm_up, bool sticky, const mesh *small, const mesh *big,
                          const uint8_t *want)
{
    int failures = 0;
    for (long k = 0; k < 10000; k++) {
        counting_alloc a;
        ca_init(&a, sticky);
        sr_context *ctx;
        sr_framebuffer *fb;
        sr_context_desc cd = ca_desc(&a, threads);
        REQUIRE(sr_make_context(&cd, &ctx) == SR_OK);
        REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = DW, .height = DH }, &fb) == SR_OK);
        if (warm_up) {
            clear_target(ctx, fb);
            REQUIRE(draw_mesh(ctx, fb, small) == SR_OK);
        }
        clear_target(ctx, fb);
        ca_arm(&a, k);
        sr_result r = draw_mesh(ctx, fb, big);
        ca_disarm(&a);
        bool done = r == SR_OK;
        if (!done) {
            failures++;
            CHECK_EQ(r, SR_OUT_OF_MEMORY);
            CHECK_STR_CONTAINS(sr_context_error(ctx), "out of memory");
            /* Still usable: the same draw now succeeds. */
            clear_target(ctx, fb);
            CHECK_EQ(draw_mesh(ctx, fb, big), SR_OK);
            CHECK(strcmp(sr_context_error(ctx), "") == 0);
        }
        CHECK(memcmp(sr_framebuffer_pixels(fb), want, (size_t)DW * DH * 4) == 0);
        sr_destroy_framebuffer(ctx, fb);
        sr_destroy_context(ctx);
        CHECK_EQ(atomic_load(&a.live), 0);
        if (done || sr_test_failed_now()) {
            break;
        }
    }
    CHECK(failures >= 1);
}

SR_TEST(draw_survives_every_allocation_failure)
{
    mesh small = make_grid(1), big = make_grid(48);
    /* The reference image, drawn with plain malloc. */
    sr_context *ctx;
    sr_framebuffer *fb;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = DW, .height = DH }, &fb) == SR_OK);
    clear_target(ctx, fb);
    REQUIRE(draw_mesh(ctx, fb, &big) == SR_OK);
    uint8_t *want = malloc((size_t)DW * DH * 4);
    memcpy(want, sr_framebuffer_pixels(fb), (size_t)DW * DH * 4);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);

    for (int threads = 1; threads <= 2; threads++) {
        for (int warm = 0; warm <= 1; warm++) {
            for (int sticky = 0; sticky <= 1; sticky++) {
                draw_failures(threads, warm, sticky, &small, &big, want);
            }
        }
    }
    free(want);
    free_mesh(&small);
    free_mesh(&big);
}
