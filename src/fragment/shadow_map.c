/* shadow_map.c - the shadow map of a directional light (fragment stage's
 * input, drawn by the whole pipeline): fits the light's orthographic view
 * to a world-space box, and draws occluders into the depth of a D24
 * framebuffer through sr_draw with slope-scaled polygon offset.  The
 * lookup is in shadow_lookup.c.  One thread at a time per map, as a
 * framebuffer. */
#include "context.h"
#include "fragment/shadow.h"
#include "target/framebuffer.h"

#include <math.h>
#include <string.h>

#define DEFAULT_SIZE          2048
#define MIN_SIZE              16
#define DEFAULT_FACTOR        1.5f
#define DEFAULT_UNITS         2.0f
#define DEFAULT_FILTER_RADIUS 1.5f
#define MIN_FILTER_RADIUS     0.5f
#define MAX_FILTER_RADIUS     SR_SHADOW_MAX_RADIUS
#define MAX_LIGHT_RADIUS      0.5f
#define DEFAULT_NORMAL_OFFSET 1.0f
#define MAX_NORMAL_OFFSET     64.0f
/* The polygon offset's slope term is capped at this many texels' worth of
 * depth: a triangle seen edge-on by the light has an unbounded slope, and
 * an unbounded offset would let light through thin walls. */
#define OFFSET_CLAMP_TEXELS   8.0

static bool finite3(sr_vec3 v)
{
    return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

static sr_result validate(sr_context *ctx, const sr_shadow_desc *d)
{
    if (!finite3(d->direction) || sr_vec3_length(d->direction) <= 0.0f ||
        !isfinite(sr_vec3_length(d->direction))) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_shadow_desc.direction must be finite and not zero (got %g, %g, %g)",
                        d->direction.x, d->direction.y, d->direction.z);
    }
    if (!finite3(d->bounds_min) || !finite3(d->bounds_max)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_shadow_desc.bounds_min and bounds_max must be finite");
    }
    if (d->bounds_min.x > d->bounds_max.x || d->bounds_min.y > d->bounds_max.y ||
        d->bounds_min.z > d->bounds_max.z) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_shadow_desc.bounds_min must be <= bounds_max");
    }
    /* The box's extent must stay finite when squared below. */
    if (sr_vec3_length(sr_vec3_sub(d->bounds_max, d->bounds_min)) > 1e18f ||
        sr_vec3_length(d->bounds_max) > 1e18f || sr_vec3_length(d->bounds_min) > 1e18f) {
        return sr__fail(ctx, SR_TOO_LARGE, "sr_shadow_desc bounds exceed 1e18");
    }
    if (d->size != 0 && (d->size < MIN_SIZE || d->size > SR_MAX_FRAMEBUFFER_SIZE)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_shadow_desc.size must be 0 or %d .. %d (got %d)",
                        MIN_SIZE, SR_MAX_FRAMEBUFFER_SIZE, d->size);
    }
    if (!isfinite(d->offset_factor) || !isfinite(d->offset_units) ||
        fabsf(d->offset_factor) > 1e6f || fabsf(d->offset_units) > 1e6f) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_shadow_desc.offset_factor and offset_units must be finite, |x| <= 1e6");
    }
    if (d->filter_radius != 0.0f &&
        !(d->filter_radius >= MIN_FILTER_RADIUS && d->filter_radius <= MAX_FILTER_RADIUS)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_shadow_desc.filter_radius must be 0 or %g .. %g (got %g)",
                        MIN_FILTER_RADIUS, MAX_FILTER_RADIUS, d->filter_radius);
    }
    if (!(d->normal_offset >= 0.0f && d->normal_offset <= MAX_NORMAL_OFFSET)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_shadow_desc.normal_offset must be 0 .. %g (got %g)",
                        MAX_NORMAL_OFFSET, d->normal_offset);
    }
    if (!(d->light_radius >= 0.0f && d->light_radius <= MAX_LIGHT_RADIUS)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_shadow_desc.light_radius must be 0 .. %g (got %g)",
                        MAX_LIGHT_RADIUS, d->light_radius);
    }
    return SR_OK;
}

/* The light's view looking along dir from the box's centre, and an
 * orthographic projection whose square covers the box's outline with a
 * margin of `margin` texels of `size` on every side and whose depth range
 * covers the box with a little room at both ends. */
static void fit(sr_shadow_map *sm, sr_vec3 dir, sr_vec3 lo, sr_vec3 hi, float margin)
{
    sr_vec3 c = sr_vec3_scale(sr_vec3_add(lo, hi), 0.5f);
    /* Any up that is not parallel to the light. */
    sr_vec3 up = fabsf(dir.y) < 0.9f ? (sr_vec3){ 0, 1, 0 } : (sr_vec3){ 0, 0, 1 };
    sr_camera_basis b;
    bool ok = sr_camera_frame(c, dir, up, &b);
    (void)ok;
    sr_mat4 view = sr_camera_matrix(&b);
    float x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    float z0 = INFINITY, z1 = -INFINITY;
    for (int i = 0; i < 8; i++) {
        sr_vec4 p = { i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z, 1.0f };
        sr_vec4 e = sr_mat4_mul_vec4(&view, p);
        x0 = fminf(x0, e.x), x1 = fmaxf(x1, e.x);
        y0 = fminf(y0, e.y), y1 = fmaxf(y1, e.y);
        z0 = fminf(z0, e.z), z1 = fmaxf(z1, e.z);
    }
    float diag = sr_vec3_length(sr_vec3_sub(hi, lo));
    float mag = fmaxf(fmaxf(fabsf(c.x), fabsf(c.y)), fmaxf(fabsf(c.z), 1.0f));
    /* A box of no extent (one point) still gets a map of some size. */
    float side = fmaxf(fmaxf(x1 - x0, y1 - y0), fmaxf(1e-3f * diag, 1e-5f * mag));
    side *= (float)sm->size / ((float)sm->size - 2.0f * margin);
    float cx = 0.5f * (x0 + x1), cy = 0.5f * (y0 + y1);
    float pad = fmaxf(0.01f * diag, 1e-5f * mag);
    /* The eye looks down -w: distances in front are -z. */
    float near_z = -z1 - pad, far_z = -z0 + pad;
    sm->view = view;
    sm->projection = sr_ortho(cx - 0.5f * side, cx + 0.5f * side, cy - 0.5f * side, cy + 0.5f * side,
                              near_z, far_z, true);
    sm->texel_size = side / (float)sm->size;
    sm->toward_light = sr_vec3_scale(dir, -1.0f);
    sr_mat4 m = sr_mat4_mul(&sm->projection, &sm->view);
    float half = 0.5f * (float)sm->size;
    for (int k = 0; k < 4; k++) {
        /* Texel x = (x_ndc + 1) size / 2; y = (1 - y_ndc) size / 2 (row 0
         * at the top, as the viewport matrix puts it); depth = z_ndc. */
        sm->to_map[0][k] = half * m.m[k * 4 + 0] + (k == 3 ? half : 0.0f);
        sm->to_map[1][k] = -half * m.m[k * 4 + 1] + (k == 3 ? half : 0.0f);
        sm->to_map[2][k] = m.m[k * 4 + 2];
    }
    /* A texel's step in depth: lateral world units over the depth range. */
    sm->depth_extent = far_z - near_z;
    double texel_depth = (double)sm->texel_size / ((double)far_z - (double)near_z);
    sm->offset_clamp = (float)(OFFSET_CLAMP_TEXELS * texel_depth);
}

/* Recompute the extremes of the blocks [bx0, bx1) x [by0, by1). */
static void update_blocks(sr_shadow_map *sm, int bx0, int by0, int bx1, int by1)
{
    int size = sm->size;
    for (int by = by0; by < by1; by++) {
        int y0 = by << SR_SHADOW_BLOCK_ORDER;
        int y1 = y0 + SR_SHADOW_BLOCK_SIZE < size ? y0 + SR_SHADOW_BLOCK_SIZE : size;
        for (int bx = bx0; bx < bx1; bx++) {
            int x0 = bx << SR_SHADOW_BLOCK_ORDER;
            int x1 = x0 + SR_SHADOW_BLOCK_SIZE < size ? x0 + SR_SHADOW_BLOCK_SIZE : size;
            uint32_t lo = UINT32_MAX, hi = 0;
            for (int y = y0; y < y1; y++) {
                const uint32_t *row = sm->depth + (size_t)y * (size_t)size;
                for (int x = x0; x < x1; x++) {
                    lo = row[x] < lo ? row[x] : lo;
                    hi = row[x] > hi ? row[x] : hi;
                }
            }
            sm->block_min[(size_t)by * sm->blocks + bx] = lo;
            sm->block_max[(size_t)by * sm->blocks + bx] = hi;
        }
    }
}

/* The blocks a draw can have touched: its vertices' texel rectangle
 * (every vertex, referenced or not), a texel wider on each side for the
 * rasterizer's rounding; every block when a position is not finite or
 * w is not 1 (4-component positions, a model matrix that is not
 * affine). */
static void draw_block_rect(const sr_shadow_map *sm, const sr_draw_desc *d, int rect[4])
{
    rect[0] = rect[1] = 0;
    rect[2] = rect[3] = sm->blocks;
    sr_mat4 model = d->model ? *d->model : sr_mat4_identity();
    if (d->position_size == 4 || model.m[3] != 0.0f || model.m[7] != 0.0f || model.m[11] != 0.0f ||
        model.m[15] != 1.0f) {
        return;
    }
    float m[2][4];
    for (int r = 0; r < 2; r++) {
        for (int k = 0; k < 4; k++) {
            m[r][k] = sm->to_map[r][0] * model.m[k * 4 + 0] + sm->to_map[r][1] * model.m[k * 4 + 1] +
                      sm->to_map[r][2] * model.m[k * 4 + 2] + (k == 3 ? sm->to_map[r][3] : 0.0f);
        }
    }
    size_t stride = d->position_stride ? d->position_stride : 3 * sizeof(float);
    float u0 = INFINITY, u1 = -INFINITY, v0 = INFINITY, v1 = -INFINITY;
    for (size_t i = 0; i < d->vertex_count; i++) {
        const float *p = (const float *)((const char *)d->positions + i * stride);
        float u = m[0][0] * p[0] + m[0][1] * p[1] + m[0][2] * p[2] + m[0][3];
        float v = m[1][0] * p[0] + m[1][1] * p[1] + m[1][2] * p[2] + m[1][3];
        if (!(isfinite(u) && isfinite(v))) {
            return;
        }
        u0 = u < u0 ? u : u0, u1 = u > u1 ? u : u1;
        v0 = v < v0 ? v : v0, v1 = v > v1 ? v : v1;
    }
    float lim = (float)sm->size;
    if (!(u0 <= u1) || u1 < -1.0f || v1 < -1.0f || u0 > lim + 1.0f || v0 > lim + 1.0f) {
        rect[2] = rect[3] = 0;   /* nothing on the map */
        return;
    }
    u0 = u0 - 1.0f > 0.0f ? u0 - 1.0f : 0.0f, v0 = v0 - 1.0f > 0.0f ? v0 - 1.0f : 0.0f;
    u1 = u1 + 1.0f < lim ? u1 + 1.0f : lim, v1 = v1 + 1.0f < lim ? v1 + 1.0f : lim;
    rect[0] = (int)u0 >> SR_SHADOW_BLOCK_ORDER;
    rect[1] = (int)v0 >> SR_SHADOW_BLOCK_ORDER;
    rect[2] = ((int)u1 >> SR_SHADOW_BLOCK_ORDER) + 1;
    rect[3] = ((int)v1 >> SR_SHADOW_BLOCK_ORDER) + 1;
    rect[2] = rect[2] < sm->blocks ? rect[2] : sm->blocks;
    rect[3] = rect[3] < sm->blocks ? rect[3] : sm->blocks;
}

sr_result sr_make_shadow_map(sr_context *ctx, const sr_shadow_desc *desc, sr_shadow_map **out)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_make_shadow_map: ctx is NULL");
    }
    if (!desc || !out) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_make_shadow_map: desc and out must not be NULL");
    }
    *out = NULL;
    sr_result r = validate(ctx, desc);
    if (r != SR_OK) {
        return r;
    }
    sr_shadow_map *sm = sr__calloc(ctx, 1, sizeof *sm);
    if (!sm) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_make_shadow_map: out of memory");
    }
    sm->size = desc->size ? desc->size : DEFAULT_SIZE;
    sm->filter_radius = desc->filter_radius != 0.0f ? desc->filter_radius : DEFAULT_FILTER_RADIUS;
    sm->normal_offset = desc->normal_offset != 0.0f ? desc->normal_offset : DEFAULT_NORMAL_OFFSET;
    sm->offset_factor = desc->offset_factor != 0.0f ? desc->offset_factor : DEFAULT_FACTOR;
    sm->offset_units = desc->offset_units != 0.0f ? desc->offset_units : DEFAULT_UNITS;
    sm->light_tan = tanf(desc->light_radius);
    /* The filter reads up to radius + 1 texels around the point: keep
     * that inside the map for every point of the box. */
    fit(sm, sr_vec3_normalize(desc->direction), desc->bounds_min, desc->bounds_max,
        sm->filter_radius + 2.0f);
    sm->blocks = (sm->size + SR_SHADOW_BLOCK_SIZE - 1) >> SR_SHADOW_BLOCK_ORDER;
    size_t nb = (size_t)sm->blocks * (size_t)sm->blocks;
    sm->block_min = sr__calloc(ctx, nb, sizeof *sm->block_min);
    sm->block_max = sr__calloc(ctx, nb, sizeof *sm->block_max);
    r = sm->block_min && sm->block_max
        ? sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = sm->size, .height = sm->size,
                                                          .depth_format = SR_DEPTH_D24 }, &sm->fb)
        : sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_make_shadow_map: out of memory");
    if (r == SR_OK) {
        r = sr_shadow_map_clear(ctx, sm);
    }
    if (r != SR_OK) {
        sr_destroy_shadow_map(ctx, sm);
        return r;
    }
    *out = sm;
    sr__ok(ctx);
    return SR_OK;
}

void sr_destroy_shadow_map(sr_context *ctx, sr_shadow_map *sm)
{
    if (!ctx || !sm) {
        return;
    }
    sr_destroy_framebuffer(ctx, sm->fb);
    sr__free(ctx, sm->block_min);
    sr__free(ctx, sm->block_max);
    sr__free(ctx, sm);
}

sr_result sr_shadow_map_clear(sr_context *ctx, sr_shadow_map *sm)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_shadow_map_clear: ctx is NULL");
    }
    if (!sm) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_shadow_map_clear: sm must not be NULL");
    }
    /* Color is never read: only depth goes back to the far value. */
    sr_result r = sr_clear(ctx, sm->fb, &(sr_clear_desc){ .color_action = SR_ACTION_KEEP });
    if (r != SR_OK) {
        return r;
    }
    /* Lookups read depth words directly, from any thread: no clear may
     * stay pending. */
    sr__fb_resolve(sm->fb, SR_TILE_PENDING_DEPTH);
    sm->depth = sm->fb->depth;     /* D24: uint32 words */
    size_t nb = (size_t)sm->blocks * (size_t)sm->blocks;
    for (size_t i = 0; i < nb; i++) {
        sm->block_min[i] = sm->block_max[i] = sm->fb->clear_depth;
    }
    return SR_OK;
}

sr_result sr_shadow_map_draw(sr_context *ctx, sr_shadow_map *sm, const sr_draw_desc *draw)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_shadow_map_draw: ctx is NULL");
    }
    if (!sm || !draw) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_shadow_map_draw: sm and draw must not be NULL");
    }
    sr_draw_desc d = *draw;
    d.normals = NULL, d.normal_stride = 0;
    d.colors = NULL, d.color_stride = 0, d.color_size = 0;
    d.texcoords = NULL, d.texcoord_stride = 0;
    d.generic = NULL, d.generic_stride = 0, d.generic_size = 0;
    d.view = &sm->view;
    d.projection = &sm->projection;
    /* Both faces: a mesh's winding need not be consistent for its shadow
     * to be whole (STL and scans often are not).  Color is written though
     * never read: a color mask or a float depth buffer would leave the
     * vector kernels for the scalar path, 4x slower (docs/shadows.md). */
    sr_state st = {
        .cull = SR_CULL_NONE,
        .depth_zero_to_one = true,
        .offset = { .factor = sm->offset_factor, .units = sm->offset_units,
                    .clamp = sm->offset_clamp, .fill = true },
    };
    sr_result r = sr_draw(ctx, sm->fb, &st, &d);
    int rect[4] = { 0, 0, sm->blocks, sm->blocks };
    if (r == SR_OK) {
        draw_block_rect(sm, &d, rect);
    } else if (r == SR_INVALID_ARG) {
        return r;   /* refused before anything was drawn */
    }
    /* Other failures (out of memory) may come after some tiles were
     * drawn: every block is taken again. */
    update_blocks(sm, rect[0], rect[1], rect[2], rect[3]);
    return r;
}

sr_result sr_query_shadow_map(const sr_shadow_map *sm, sr_shadow_info *out)
{
    if (!sm || !out) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_query_shadow_map: %s is NULL", sm ? "out" : "sm");
    }
    *out = (sr_shadow_info){
        .view = sm->view, .projection = sm->projection, .size = sm->size,
        .texel_size = sm->texel_size, .filter_radius = sm->filter_radius,
        .normal_offset = sm->normal_offset,
    };
    return SR_OK;
}
