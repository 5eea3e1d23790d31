/* shadow_catcher.c - the shadow catcher (docs/shadows.md): a ground square
 * drawn as nothing but the shadow a shadow map casts on it, blended over
 * what the framebuffer holds.  Consumes a drawn map and a ground of
 * sr_make_ground_mesh; produces one sr_draw.  Its shaders run on the
 * context's workers and only read their uniforms and the map. */
#include "context.h"
#include "pipeline.h"

#include <math.h>
#include <string.h>

/* How dark the catcher's full shadow is, and the part of the ground (from
 * its centre, in half-sides) where the shadow fades out. */
#define CATCHER_STRENGTH   0.6f
#define CATCHER_FADE_START 0.5f

/* Texels of margin around the shadow's footprint: the widest penumbra
 * (8 texels a side) and the lookup's normal offset. */
#define FOOTPRINT_MARGIN_TEXELS 16.0f

typedef struct catcher_uniforms {
    sr_mat4 view_projection;
    const sr_shadow_map *map;
} catcher_uniforms;

/* Varyings: 0..2 world position, 3..5 world normal, 6..7 texcoord (the
 * ground's vertices are in world space). */
static void catcher_vs(const void *u, const sr_vertex_input *in, float clip[4], float *vary)
{
    const catcher_uniforms *c = u;
    sr_vec4 p = sr_mat4_mul_vec4(&c->view_projection, (sr_vec4){ in->position[0],
                                                                 in->position[1],
                                                                 in->position[2], 1.0f });
    clip[0] = p.x, clip[1] = p.y, clip[2] = p.z, clip[3] = p.w;
    for (int k = 0; k < 3; k++) {
        vary[k] = in->position[k];
        vary[3 + k] = in->normal[k];
    }
    vary[6] = in->texcoord[0], vary[7] = in->texcoord[1];
}

static void catcher_fs(const void *u, sr_fragment_quad *q)
{
    const catcher_uniforms *c = u;
    float fade[4], vis[4] = { 1, 1, 1, 1 };
    bool shown = false;
    for (int i = 0; i < 4; i++) {
        float dx = q->varyings[6][i] - 0.5f, dy = q->varyings[7][i] - 0.5f;
        float r = 2.0f * sqrtf(dx * dx + dy * dy);      /* 0 centre, 1 the sides' midpoints */
        fade[i] = fminf(fmaxf((1.0f - r) / (1.0f - CATCHER_FADE_START), 0.0f), 1.0f);
        shown |= fade[i] > 0.0f;
    }
    if (shown) {   /* the faded-out rim shows nothing: no lookup */
        sr_shadow_visibility4(c->map, q->varyings[0], q->varyings[3], vis);
    }
    for (int i = 0; i < 4; i++) {
        q->color[0][i] = q->color[1][i] = q->color[2][i] = 0.0f;
        q->color[3][i] = CATCHER_STRENGTH * (1.0f - vis[i]) * fade[i];
    }
}

/* The part of the ground square [x0, x1] x [z0, z1] at height y where the
 * map's box can cast a shadow: its eight corners carried along the light
 * onto the plane, their rectangle widened by the margin, clipped to the
 * square.  False when it is empty or the light does not come from above. */
static bool footprint(const sr_shadow_catcher_desc *d, float y, float sq[4], float out[4])
{
    sr_vec3 dir = d->direction, lo = d->bounds_min, hi = d->bounds_max;
    sr_shadow_info info;
    if (!(dir.y < 0.0f) || sr_query_shadow_map(d->map, &info) != SR_OK) {
        return false;
    }
    float r[4] = { INFINITY, INFINITY, -INFINITY, -INFINITY };   /* x0 z0 x1 z1 */
    for (int k = 0; k < 8; k++) {
        sr_vec3 c = { k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z };
        float t = (y - c.y) / dir.y;
        float px = c.x + t * dir.x, pz = c.z + t * dir.z;
        r[0] = fminf(r[0], px), r[1] = fminf(r[1], pz);
        r[2] = fmaxf(r[2], px), r[3] = fmaxf(r[3], pz);
    }
    float m = FOOTPRINT_MARGIN_TEXELS * info.texel_size;
    out[0] = fmaxf(r[0] - m, sq[0]), out[1] = fmaxf(r[1] - m, sq[1]);
    out[2] = fminf(r[2] + m, sq[2]), out[3] = fminf(r[3] + m, sq[3]);
    return out[0] < out[2] && out[1] < out[3];
}

static bool finite3(sr_vec3 v)
{
    return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

static sr_result validate(sr_context *ctx, const sr_framebuffer *fb, const sr_state *state,
                          const sr_shadow_catcher_desc *d)
{
    if (!fb || !state || !d) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_draw_shadow_catcher: fb, state and desc must not be NULL");
    }
    if (!d->ground || !d->map || !d->view || !d->projection) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_shadow_catcher_desc: ground, map, view and "
                        "projection must not be NULL");
    }
    if (d->ground->vertex_count > 0 && (!d->ground->positions || !d->ground->texcoords)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_shadow_catcher_desc.ground needs positions "
                        "and texcoords (sr_make_ground_mesh)");
    }
    if (!finite3(d->direction) || !finite3(d->bounds_min) || !finite3(d->bounds_max)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_shadow_catcher_desc: direction and bounds "
                        "must be finite");
    }
    if (!(d->bounds_min.x <= d->bounds_max.x && d->bounds_min.y <= d->bounds_max.y &&
          d->bounds_min.z <= d->bounds_max.z)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_shadow_catcher_desc: bounds_min must not "
                        "exceed bounds_max");
    }
    if (d->direction.x == 0 && d->direction.y == 0 && d->direction.z == 0) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_shadow_catcher_desc.direction must not be zero");
    }
    for (int k = 0; k < 16; k++) {
        if (!isfinite(d->view->m[k]) || !isfinite(d->projection->m[k])) {
            return sr__fail(ctx, SR_INVALID_ARG, "sr_shadow_catcher_desc.%s has a NaN or "
                            "infinite entry", isfinite(d->view->m[k]) ? "projection" : "view");
        }
    }
    /* The caller's state is checked whether or not anything is drawn, so
     * that a bad state does not pass while the light is low. */
    sr_state st = *state;
    st.program = NULL;
    return sr__draw_validate(ctx, fb, &st, &(sr_draw_desc){ .projection = d->projection });
}

sr_result sr_draw_shadow_catcher(sr_context *ctx, sr_framebuffer *fb, const sr_state *state,
                                 const sr_shadow_catcher_desc *desc)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_draw_shadow_catcher: ctx is NULL");
    }
    sr_result r = validate(ctx, fb, state, desc);
    if (r != SR_OK) {
        return r;
    }
    /* Only the footprint is drawn (the rest of the ground is lit and
     * would show nothing), with texcoords of the whole square so that it
     * fades as the whole square does.  The ground lies in y = const. */
    const sr_mesh *m = desc->ground;
    float sq[4] = { INFINITY, INFINITY, -INFINITY, -INFINITY }, fp[4];
    for (size_t i = 0; i < m->vertex_count; i++) {
        const float *p = &m->positions[3 * i];
        sq[0] = fminf(sq[0], p[0]), sq[1] = fminf(sq[1], p[2]);
        sq[2] = fmaxf(sq[2], p[0]), sq[3] = fmaxf(sq[3], p[2]);
    }
    float y = m->vertex_count ? m->positions[1] : 0.0f;
    if (!footprint(desc, y, sq, fp)) {
        return SR_OK;
    }
    float pos[12], nrm[12], uv[8];
    const int corner[4][2] = { { 0, 1 }, { 0, 3 }, { 2, 3 }, { 2, 1 } };   /* ccw from +y */
    for (int v = 0; v < 4; v++) {
        float x = fp[corner[v][0]], z = fp[corner[v][1]];
        pos[3 * v] = x, pos[3 * v + 1] = y, pos[3 * v + 2] = z;
        nrm[3 * v] = 0.0f, nrm[3 * v + 1] = 1.0f, nrm[3 * v + 2] = 0.0f;
        uv[2 * v] = (x - sq[0]) / (sq[2] - sq[0]);
        uv[2 * v + 1] = (z - sq[1]) / (sq[3] - sq[1]);
    }
    static const uint32_t quad[6] = { 0, 1, 2, 0, 2, 3 };
    catcher_uniforms u = { sr_mat4_mul(desc->projection, desc->view), desc->map };
    sr_program program = { .vertex = catcher_vs, .fragment = catcher_fs, .uniforms = &u,
                           .varying_count = 8 };
    sr_state st = *state;
    st.program = &program;
    st.cull = SR_CULL_NONE;
    st.depth_write = SR_OFF;
    st.blend = (sr_blend){ .enabled = true, .src_rgb = SR_BLEND_SRC_ALPHA,
                           .dst_rgb = SR_BLEND_ONE_MINUS_SRC_ALPHA, .src_alpha = SR_BLEND_ONE,
                           .dst_alpha = SR_BLEND_ONE_MINUS_SRC_ALPHA };
    return sr_draw(ctx, fb, &st, &(sr_draw_desc){
        .positions = pos, .normals = nrm, .texcoords = uv, .vertex_count = 4, .indices = quad,
        .index_type = SR_INDEX_U32, .index_count = 6 });
}
