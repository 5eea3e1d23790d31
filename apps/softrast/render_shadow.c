/* render_shadow.c - the key light's shadow map for `softrast render` and
 * the --ground shadow catcher (docs/shadows.md).  Called by render.c on
 * the thread that draws; the catcher's shaders run on the context's
 * workers and only read their uniforms and the map. */
#include "render_shadow.h"

#include <math.h>
#include <string.h>

/* A 1024-texel map: the bunny's shadows at 1080p look as they do at 2048,
 * for half the draw.  The light's size softens the shadow away from the
 * contact, as a thumbnail's ground shadow wants (docs/shadows.md). */
#define SHADOW_MAP_SIZE    1024
#define SHADOW_LIGHT_RADIUS 0.04f
/* How dark the catcher's full shadow is, and the part of the ground
 * (from its centre, in half-sides) where the shadow fades out. */
#define CATCHER_STRENGTH   0.6f
#define CATCHER_FADE_START 0.5f

static bool same_vec3(sr_vec3 a, sr_vec3 b)
{
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

sr_result render_shadow_draw(sr_context *ctx, render_shadow *sh, const scene *s,
                             sr_vec3 direction)
{
    if (!sh->map || !same_vec3(sh->direction, direction) || !same_vec3(sh->lo, s->box_min) ||
        !same_vec3(sh->hi, s->box_max)) {
        render_shadow_free(ctx, sh);
        sr_result r = sr_make_shadow_map(ctx, &(sr_shadow_desc){
            .direction = direction, .bounds_min = s->box_min, .bounds_max = s->box_max,
            .size = SHADOW_MAP_SIZE, .light_radius = SHADOW_LIGHT_RADIUS }, &sh->map);
        if (r != SR_OK) {
            sh->map = NULL;
            return r;
        }
        sh->direction = direction;
        sh->lo = s->box_min;
        sh->hi = s->box_max;
    }
    sr_result r = sr_shadow_map_clear(ctx, sh->map);
    for (int i = 0; i < s->count && r == SR_OK; i++) {
        const scene_object *ob = &s->objects[i];
        if (!ob->frame || ob->mesh.triangle_count == 0) {
            continue;
        }
        r = sr_shadow_map_draw(ctx, sh->map, &(sr_draw_desc){
            .positions = ob->mesh.positions, .vertex_count = ob->mesh.vertex_count,
            .indices = ob->mesh.indices, .index_type = SR_INDEX_U32,
            .index_count = ob->mesh.triangle_count * 3, .model = &ob->model });
    }
    return r;
}

void render_shadow_free(sr_context *ctx, render_shadow *sh)
{
    if (sh->map) {
        sr_destroy_shadow_map(ctx, sh->map);
    }
    sh->map = NULL;
}

sr_result render_ground_add(sr_context *ctx, scene *s)
{
    int n = 0;
    for (int i = 0; i < s->count; i++) {
        if (s->objects[i].frame) {
            s->objects[n++] = s->objects[i];
        } else {
            sr_destroy_mesh(ctx, &s->objects[i].mesh);
        }
    }
    s->count = n;
    if (n == SCENE_MAX_OBJECTS) {
        return SR_INVALID_ARG;
    }
    scene_object *g = &s->objects[n];
    memset(g, 0, sizeof *g);
    sr_result r = sr_make_ground_mesh(ctx, &(sr_ground_desc){ .bounds_min = s->box_min,
                                                              .bounds_max = s->box_max },
                                      &g->mesh);
    if (r != SR_OK) {
        return r;
    }
    g->model = sr_mat4_identity();
    g->catcher = true;
    s->count = n + 1;
    scene_cache_bounds(s);
    return SR_OK;
}

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
    float vis[4];
    sr_shadow_visibility4(c->map, q->varyings[0], q->varyings[3], vis);
    for (int i = 0; i < 4; i++) {
        float dx = q->varyings[6][i] - 0.5f, dy = q->varyings[7][i] - 0.5f;
        float r = 2.0f * sqrtf(dx * dx + dy * dy);      /* 0 centre, 1 the sides' midpoints */
        float fade = fminf(fmaxf((1.0f - r) / (1.0f - CATCHER_FADE_START), 0.0f), 1.0f);
        q->color[0][i] = q->color[1][i] = q->color[2][i] = 0.0f;
        q->color[3][i] = CATCHER_STRENGTH * (1.0f - vis[i]) * fade;
    }
}

sr_result render_catcher_draw(sr_context *ctx, sr_framebuffer *fb, const sr_state *base,
                              const sr_shadow_map *map, const scene_object *ground,
                              const sr_mat4 *view, const sr_mat4 *projection)
{
    catcher_uniforms u = { sr_mat4_mul(projection, view), map };
    sr_program program = { .vertex = catcher_vs, .fragment = catcher_fs, .uniforms = &u,
                           .varying_count = 8 };
    sr_state st = *base;
    st.program = &program;
    st.cull = SR_CULL_NONE;
    st.depth_write = SR_OFF;
    st.blend = (sr_blend){ .enabled = true, .src_rgb = SR_BLEND_SRC_ALPHA,
                           .dst_rgb = SR_BLEND_ONE_MINUS_SRC_ALPHA, .src_alpha = SR_BLEND_ONE,
                           .dst_alpha = SR_BLEND_ONE_MINUS_SRC_ALPHA };
    const sr_mesh *m = &ground->mesh;
    return sr_draw(ctx, fb, &st, &(sr_draw_desc){
        .positions = m->positions, .normals = m->normals, .texcoords = m->texcoords,
        .vertex_count = m->vertex_count, .indices = m->indices, .index_type = SR_INDEX_U32,
        .index_count = m->triangle_count * 3 });
}
