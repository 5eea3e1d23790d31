/* render_shadow.c - the key light's shadow map for `softrast render` and
 * the --ground shadow catcher (docs/shadows.md; drawn by the library's
 * sr_draw_shadow_catcher).  Called by render.c on the thread that draws. */
#include "render_shadow.h"

#include <string.h>

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
            .size = SR_DEFAULT_SHADOW_SIZE,
            .light_radius = SR_DEFAULT_SHADOW_LIGHT_RADIUS }, &sh->map);
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

sr_result render_catcher_draw(sr_context *ctx, sr_framebuffer *fb, const sr_state *base,
                              const render_shadow *sh, const scene_object *ground,
                              const sr_mat4 *view, const sr_mat4 *projection)
{
    return sr_draw_shadow_catcher(ctx, fb, base, &(sr_shadow_catcher_desc){
        .ground = &ground->mesh, .map = sh->map, .direction = sh->direction,
        .bounds_min = sh->lo, .bounds_max = sh->hi, .view = view, .projection = projection });
}
