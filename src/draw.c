/* draw.c - sr_draw, the pipeline's driver: validate, resolve the state,
 * run the vertex stage, assemble primitives, clip, set up, bin into tiles
 * and rasterize.  Application thread; the tile back end fans out to the
 * context's pool. */
#include "context.h"
#include "parallel/bin.h"
#include "scratch.h"
#include "fragment/depth.h"
#include "raster/triangle_simd.h"
#include "raster/setup_tri.h"

#include <math.h>
#include <string.h>

#define SR_MAX_DRAW_VERTICES ((size_t)1 << 28)

static bool finite_vec3(sr_vec3 v)
{
    return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

static bool finite_mat(const sr_mat4 *m)
{
    for (int i = 0; m && i < 16; i++) {
        if (!isfinite(m->m[i])) {
            return false;
        }
    }
    return true;
}

static sr_result validate(sr_context *ctx, const sr_framebuffer *fb, const sr_state *st,
                          const sr_draw_desc *d)
{
    if (!fb) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_draw: fb is NULL");
    }
    if (!st) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_draw: state is NULL");
    }
    if (!d) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_draw: draw is NULL");
    }
    if ((unsigned)d->primitive > SR_PRIM_POINTS) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_draw_desc.primitive %d is not a primitive type",
                        (int)d->primitive);
    }
    if (d->vertex_count > SR_MAX_DRAW_VERTICES) {
        return sr__fail(ctx, SR_TOO_LARGE, "sr_draw_desc.vertex_count %zu exceeds the limit %zu",
                        d->vertex_count, SR_MAX_DRAW_VERTICES);
    }
    if (d->vertex_count > 0 && !d->positions) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_draw_desc.positions is NULL");
    }
    if (d->position_size != 0 && d->position_size != 3 && d->position_size != 4) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_draw_desc.position_size must be 3 or 4 (got %d)",
                        d->position_size);
    }
    if (d->color_size != 0 && d->color_size != 3 && d->color_size != 4) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_draw_desc.color_size must be 3 or 4 (got %d)",
                        d->color_size);
    }
    if ((unsigned)d->index_type > SR_INDEX_U32) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_draw_desc.index_type %d is not an index type",
                        (int)d->index_type);
    }
    if (d->index_type != SR_INDEX_NONE && d->index_count > 0 && !d->indices) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_draw_desc.indices is NULL but index_count is %zu",
                        d->index_count);
    }
    if (d->index_type == SR_INDEX_NONE && d->indices) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_draw_desc.indices given with index_type SR_INDEX_NONE");
    }
    if (!finite_mat(d->model) || !finite_mat(d->view) || !finite_mat(d->projection)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_draw_desc.%s has a NaN or infinite entry",
                        !finite_mat(d->model) ? "model" : !finite_mat(d->view) ? "view" : "projection");
    }
    sr_shading sh = st->shading == SR_SHADING_DEFAULT ? SR_SHADING_UNLIT : st->shading;
    if ((unsigned)st->shading > SR_SHADING_ATTRIBUTE) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.shading %d is not a shading model",
                        (int)st->shading);
    }
    if (d->generic_size < 0 || d->generic_size > 4) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_draw_desc.generic_size must be 1..4 (got %d)",
                        d->generic_size);
    }
    const sr_program *pr = st->program;
    if (pr) {
        if (!pr->vertex || !pr->fragment) {
            return sr__fail(ctx, SR_INVALID_ARG, "sr_program.%s is NULL",
                            pr->vertex ? "fragment" : "vertex");
        }
        if (pr->varying_count < 0 || pr->varying_count > SR_SHADER_MAX_VARYINGS) {
            return sr__fail(ctx, SR_INVALID_ARG, "sr_program.varying_count must be 0..%d (got %d)",
                            SR_SHADER_MAX_VARYINGS, pr->varying_count);
        }
        for (int k = 0; k < pr->varying_count; k++) {
            if ((unsigned)pr->modes[k] > SR_VARYING_FLAT) {
                return sr__fail(ctx, SR_INVALID_ARG, "sr_program.modes[%d] %d is not a mode", k,
                                (int)pr->modes[k]);
            }
        }
        /* The program reads what it wants: the shading model's needs below
         * do not apply. */
        sh = SR_SHADING_UNLIT;
    }
    if (sh == SR_SHADING_ATTRIBUTE && !d->generic && d->vertex_count > 0) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_draw_desc.generic is NULL but SR_SHADING_ATTRIBUTE shows it");
    }
    if ((sh == SR_SHADING_GOURAUD || sh == SR_SHADING_PHONG || sh == SR_SHADING_NORMALS) &&
        !d->normals && d->vertex_count > 0) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_draw_desc.normals is NULL but the shading model needs vertex normals");
    }
    if ((unsigned)st->polygon_mode_front > SR_POLYGON_POINT ||
        (unsigned)st->polygon_mode_back > SR_POLYGON_POINT) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.polygon_mode_%s %d is not a polygon mode",
                        (unsigned)st->polygon_mode_front > SR_POLYGON_POINT ? "front" : "back",
                        (int)((unsigned)st->polygon_mode_front > SR_POLYGON_POINT
                                  ? st->polygon_mode_front : st->polygon_mode_back));
    }
    if (!(st->line_width >= 0.0f && st->line_width <= 64.0f)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.line_width must be in [0, 64] (got %g)",
                        (double)st->line_width);
    }
    if (!(st->point_size >= 0.0f && st->point_size <= 1024.0f)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.point_size must be in [0, 1024] (got %g)",
                        (double)st->point_size);
    }
    if ((unsigned)st->texture_filter > SR_FILTER_TRILINEAR || (unsigned)st->wrap_u > SR_WRAP_MIRROR ||
        (unsigned)st->wrap_v > SR_WRAP_MIRROR) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_state.texture_filter, wrap_u or wrap_v is not a valid value");
    }
    if (st->texture && !pr && !d->texcoords && d->vertex_count > 0 &&
        (sh == SR_SHADING_UNLIT || sh == SR_SHADING_GOURAUD || sh == SR_SHADING_FLAT ||
         sh == SR_SHADING_PHONG)) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_draw_desc.texcoords is NULL but sr_state.texture is set");
    }
    const sr_blend *bl = &st->blend;
    if ((unsigned)bl->src_rgb > SR_BLEND_SRC_ALPHA_SATURATE ||
        (unsigned)bl->dst_rgb > SR_BLEND_SRC_ALPHA_SATURATE ||
        (unsigned)bl->src_alpha > SR_BLEND_SRC_ALPHA_SATURATE ||
        (unsigned)bl->dst_alpha > SR_BLEND_SRC_ALPHA_SATURATE ||
        (unsigned)bl->op_rgb > SR_BLEND_MAX || (unsigned)bl->op_alpha > SR_BLEND_MAX) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.blend: a factor or op is not valid");
    }
    for (int i = 0; i < 4; i++) {
        if (!isfinite(bl->constant[i])) {
            return sr__fail(ctx, SR_INVALID_ARG, "sr_state.blend.constant[%d] is not finite", i);
        }
    }
    const sr_stencil_face *sf[2] = { &st->stencil.front, &st->stencil.back };
    for (int i = 0; i < 2; i++) {
        if ((unsigned)sf[i]->func > SR_ALWAYS || (unsigned)sf[i]->fail > SR_STENCIL_DECR_WRAP ||
            (unsigned)sf[i]->depth_fail > SR_STENCIL_DECR_WRAP ||
            (unsigned)sf[i]->pass > SR_STENCIL_DECR_WRAP) {
            return sr__fail(ctx, SR_INVALID_ARG,
                            "sr_state.stencil.%s: a function or operation is not valid",
                            i ? "back" : "front");
        }
    }
    if (st->scissor.enabled && (st->scissor.width < 0 || st->scissor.height < 0)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.scissor: width and height must be >= 0");
    }
    if ((unsigned)st->cull > SR_CULL_FRONT_AND_BACK) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.cull %d is not a cull mode", (int)st->cull);
    }
    if ((unsigned)st->front_face > SR_FRONT_CW) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.front_face %d is not valid", (int)st->front_face);
    }
    if ((unsigned)st->depth_func > SR_ALWAYS) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.depth_func %d is not a depth function",
                        (int)st->depth_func);
    }
    if ((unsigned)st->rasterizer > SR_RASTER_BARYCENTRIC) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.rasterizer %d is not a rasterizer",
                        (int)st->rasterizer);
    }
    if ((unsigned)st->interpolation > SR_INTERP_AFFINE) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.interpolation %d is not valid",
                        (int)st->interpolation);
    }
    if ((unsigned)st->provoking > SR_PROVOKING_LAST) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.provoking %d is not valid", (int)st->provoking);
    }
    const sr_viewport *vp = &st->viewport;
    if (vp->width < 0 || vp->height < 0 || (vp->width == 0) != (vp->height == 0)) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_state.viewport: width and height must both be > 0, or both 0 for the whole framebuffer");
    }
    /* x > MAX - width rather than x + width > MAX, which overflows for x
     * near INT_MAX (width is within [0, 8192] by then). */
    if (vp->width > SR_MAX_FRAMEBUFFER_SIZE || vp->height > SR_MAX_FRAMEBUFFER_SIZE ||
        vp->x < SR_GUARD_BAND_MIN || vp->y < SR_GUARD_BAND_MIN ||
        vp->x > SR_GUARD_BAND_MAX - vp->width || vp->y > SR_GUARD_BAND_MAX - vp->height) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_state.viewport (%d, %d, %d x %d) is outside the supported range",
                        vp->x, vp->y, vp->width, vp->height);
    }
    if (!(st->depth_near >= 0.0f && st->depth_near <= 1.0f && st->depth_far >= 0.0f &&
          st->depth_far <= 1.0f)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.depth_near/depth_far must be in [0, 1]");
    }
    if (!isfinite(st->offset.factor) || !isfinite(st->offset.units) || !isfinite(st->offset.clamp)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.offset: factor, units and clamp must be finite");
    }
    const sr_material *m = &st->material;
    if (!finite_vec3(m->ambient) || !finite_vec3(m->diffuse) || !finite_vec3(m->specular) ||
        !isfinite(m->shininess) || m->shininess < 0.0f || !(m->opacity >= 0.0f && m->opacity <= 1.0f)) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_state.material: colors must be finite, shininess >= 0, opacity in [0, 1]");
    }
    if (!finite_vec3(st->ambient)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.ambient must be finite");
    }
    for (int i = 0; i < SR_MAX_LIGHTS; i++) {
        const sr_light *l = &st->lights[i];
        if ((unsigned)l->type > SR_LIGHT_POINT) {
            return sr__fail(ctx, SR_INVALID_ARG, "sr_state.lights[%d].type %d is not a light type",
                            i, (int)l->type);
        }
        if (l->type != SR_LIGHT_OFF && (!finite_vec3(l->vector) || !finite_vec3(l->color) ||
                                        !isfinite(l->intensity))) {
            return sr__fail(ctx, SR_INVALID_ARG, "sr_state.lights[%d]: values must be finite", i);
        }
        if (l->type == SR_LIGHT_DIRECTIONAL && sr_vec3_length(l->vector) == 0.0f) {
            return sr__fail(ctx, SR_INVALID_ARG, "sr_state.lights[%d].vector: a direction must not be zero", i);
        }
    }
    return SR_OK;
}

/* The shading half of the resolved state: the model, its varyings, the
 * texture, the material and the lights in eye space.  Shared with the
 * built-in programs (fragment/builtin.c), which need nothing else. */
void sr__resolve_shading(const sr_state *st, const sr_mat4 *view, const sr_mat4 *proj,
                         sr_draw_state *ds)
{
    ds->zero_to_one = st->depth_zero_to_one;
    ds->shading = st->shading == SR_SHADING_DEFAULT ? SR_SHADING_UNLIT : st->shading;
    ds->perspective = st->interpolation != SR_INTERP_AFFINE;
    ds->provoking_last = st->provoking == SR_PROVOKING_LAST;
    ds->two_sided = st->two_sided;
    /* A perspective projection has a bottom row (0, 0, -1, 0): the viewer
     * sits at the eye-space origin.  Otherwise the view vector is +z. */
    ds->local_viewer = proj && (proj->m[3] != 0.0f || proj->m[7] != 0.0f || proj->m[11] != 0.0f);

    switch (ds->shading) {
    case SR_SHADING_UNLIT:
    case SR_SHADING_GOURAUD: ds->nvary = 4; ds->ninterp = 4; break;
    case SR_SHADING_FLAT:    ds->nvary = 7; ds->ninterp = 0; break;
    case SR_SHADING_PHONG:   ds->nvary = 10; ds->ninterp = 10; break;
    case SR_SHADING_NORMALS: ds->nvary = 3; ds->ninterp = 3; break;
    case SR_SHADING_ATTRIBUTE: ds->nvary = 4; ds->ninterp = 4; break;
    default:                 ds->nvary = 1; ds->ninterp = 1; break;
    }
    /* A texture adds u, v after the model's own varyings; flat shading then
     * interpolates its (otherwise constant) layout too, to reach them. */
    ds->uv_index = -1;
    bool textured_model = ds->shading == SR_SHADING_UNLIT || ds->shading == SR_SHADING_GOURAUD ||
                          ds->shading == SR_SHADING_FLAT || ds->shading == SR_SHADING_PHONG;
    if (st->texture && textured_model) {
        ds->texture = st->texture;
        ds->texture_filter = st->texture_filter == SR_FILTER_DEFAULT ? SR_FILTER_TRILINEAR
                                                                     : st->texture_filter;
        ds->wrap_u = st->wrap_u == SR_WRAP_DEFAULT ? SR_WRAP_REPEAT : st->wrap_u;
        ds->wrap_v = st->wrap_v == SR_WRAP_DEFAULT ? SR_WRAP_REPEAT : st->wrap_v;
        ds->uv_index = ds->nvary;
        ds->nvary += 2;
        ds->ninterp = ds->nvary;
    }
    /* Linear depth for the DEPTH view: under a projection with w = -z_eye,
     * z_ndc = P23 / d - P22 at eye distance d, so the near and far planes
     * (z_ndc = -1 or 0, and +1) lie at d = P23 / (z_ndc + P22). */
    if (ds->shading == SR_SHADING_DEPTH && proj && proj->m[11] == -1.0f && proj->m[3] == 0.0f &&
        proj->m[7] == 0.0f && proj->m[15] == 0.0f) {
        double p22 = proj->m[10], p23 = proj->m[14];
        double dn = p23 / ((ds->zero_to_one ? 0.0 : -1.0) + p22), dfar = p23 / (1.0 + p22);
        if (isfinite(dn) && isfinite(dfar) && dn > 0.0 && dfar > dn) {
            ds->depth_vis_linear = true;
            ds->depth_vis_near = (float)dn;
            ds->depth_vis_scale = (float)(1.0 / (dfar - dn));
        }
    }

    const sr_material *m = &st->material;
    sr_vec3 kd = (m->diffuse.x == 0 && m->diffuse.y == 0 && m->diffuse.z == 0)
                     ? (sr_vec3){ 0.8f, 0.8f, 0.8f } : m->diffuse;
    ds->diffuse[0] = kd.x;
    ds->diffuse[1] = kd.y;
    ds->diffuse[2] = kd.z;
    ds->diffuse[3] = m->opacity == 0.0f ? 1.0f : m->opacity;
    /* Ambient reflectance defaults to the diffuse color: ambient light
     * then tints the surface the way it looks lit. */
    bool ka_zero = m->ambient.x == 0 && m->ambient.y == 0 && m->ambient.z == 0;
    ds->ambient[0] = st->ambient.x * (ka_zero ? 1.0f : m->ambient.x / kd.x);
    ds->ambient[1] = st->ambient.y * (ka_zero ? 1.0f : m->ambient.y / kd.y);
    ds->ambient[2] = st->ambient.z * (ka_zero ? 1.0f : m->ambient.z / kd.z);
    ds->specular[0] = m->specular.x;
    ds->specular[1] = m->specular.y;
    ds->specular[2] = m->specular.z;
    ds->shininess = m->shininess == 0.0f ? 32.0f : m->shininess;
    ds->shininess_int = (ds->shininess == floorf(ds->shininess) && ds->shininess <= 4096.0f)
                            ? (int)ds->shininess : -1;
    ds->use_vertex_color = !m->no_vertex_color;

    sr_mat4 e = view ? *view : sr_mat4_identity();
    for (int i = 0; i < SR_MAX_LIGHTS; i++) {
        const sr_light *l = &st->lights[i];
        if (l->type == SR_LIGHT_OFF) {
            continue;
        }
        sr_light_eye *le = &ds->lights[ds->light_count++];
        le->point = l->type == SR_LIGHT_POINT;
        sr_vec4 v;
        if (le->point) {
            v = sr_mat4_mul_vec4(&e, (sr_vec4){ l->vector.x, l->vector.y, l->vector.z, 1.0f });
        } else {
            /* The vector to the light is the negated travel direction. */
            v = sr_mat4_mul_vec4(&e, (sr_vec4){ -l->vector.x, -l->vector.y, -l->vector.z, 0.0f });
            sr_vec3 n = sr_vec3_normalize((sr_vec3){ v.x, v.y, v.z });
            v = (sr_vec4){ n.x, n.y, n.z, 0.0f };
        }
        le->vec[0] = v.x;
        le->vec[1] = v.y;
        le->vec[2] = v.z;
        bool white = l->color.x == 0 && l->color.y == 0 && l->color.z == 0;
        float intensity = l->intensity == 0.0f ? 1.0f : l->intensity;
        le->color[0] = (white ? 1.0f : l->color.x) * intensity;
        le->color[1] = (white ? 1.0f : l->color.y) * intensity;
        le->color[2] = (white ? 1.0f : l->color.z) * intensity;
    }
}

static void resolve_state(const sr_framebuffer *fb, const sr_state *st, const sr_mat4 *view,
                          const sr_mat4 *proj, sr_draw_state *ds)
{
    memset(ds, 0, sizeof *ds);
    ds->fb = (sr_framebuffer *)fb;

    sr_viewport vp = st->viewport;
    if (vp.width == 0) {
        vp = (sr_viewport){ 0, 0, fb->width, fb->height };
    }
    double dn = st->depth_near, df = st->depth_far;
    if (dn == 0.0 && df == 0.0) {
        df = 1.0;
    }
    ds->zero_to_one = st->depth_zero_to_one;
    /* The viewport matrix S, onto pixel edges (RASTER_RULES 1.2). */
    ds->vp_px = vp.width * 0.5;
    ds->vp_py = vp.height * 0.5;
    ds->vp_ox = vp.x + vp.width * 0.5;
    ds->vp_oy = vp.y + vp.height * 0.5;
    if (ds->zero_to_one) {
        ds->vp_zs = df - dn;
        ds->vp_zb = dn;
    } else {
        ds->vp_zs = (df - dn) * 0.5;
        ds->vp_zb = (df + dn) * 0.5;
    }
    ds->depth_min = fmin(dn, df);
    ds->depth_max = fmax(dn, df);
    ds->depth_scale = fb->depth_bits ? (double)((fb->depth_bits == 32) ? 0xffffffffu
                                                : ((1u << fb->depth_bits) - 1u)) : 1.0;
    ds->zq_min = ds->depth_min * ds->depth_scale;
    ds->zq_max = ds->depth_max * ds->depth_scale;
    ds->tiles_x = fb->tiles_x;
    ds->tiles_y = fb->tiles_y;
    ds->rect_x0 = vp.x > 0 ? vp.x : 0;
    ds->rect_y0 = vp.y > 0 ? vp.y : 0;
    ds->rect_x1 = vp.x + vp.width < fb->width ? vp.x + vp.width : fb->width;
    ds->rect_y1 = vp.y + vp.height < fb->height ? vp.y + vp.height : fb->height;
    if (st->scissor.enabled) {
        /* The scissor trims the rectangle every primitive is bounded by. */
        const sr_scissor *sc = &st->scissor;
        long sx1 = (long)sc->x + sc->width, sy1 = (long)sc->y + sc->height;
        ds->rect_x0 = sc->x > ds->rect_x0 ? sc->x : ds->rect_x0;
        ds->rect_y0 = sc->y > ds->rect_y0 ? sc->y : ds->rect_y0;
        ds->rect_x1 = sx1 < ds->rect_x1 ? (int)sx1 : ds->rect_x1;
        ds->rect_y1 = sy1 < ds->rect_y1 ? (int)sy1 : ds->rect_y1;
    }
    ds->blend = st->blend;
    if (ds->blend.enabled) {
        sr_blend *b = &ds->blend;
        b->src_rgb = b->src_rgb == SR_BLEND_FACTOR_DEFAULT ? SR_BLEND_ONE : b->src_rgb;
        b->src_alpha = b->src_alpha == SR_BLEND_FACTOR_DEFAULT ? SR_BLEND_ONE : b->src_alpha;
        b->dst_rgb = b->dst_rgb == SR_BLEND_FACTOR_DEFAULT ? SR_BLEND_ZERO : b->dst_rgb;
        b->dst_alpha = b->dst_alpha == SR_BLEND_FACTOR_DEFAULT ? SR_BLEND_ZERO : b->dst_alpha;
        b->op_rgb = b->op_rgb == SR_BLEND_OP_DEFAULT ? SR_BLEND_ADD : b->op_rgb;
        b->op_alpha = b->op_alpha == SR_BLEND_OP_DEFAULT ? SR_BLEND_ADD : b->op_alpha;
    }
    const sr_color_mask *cm = &st->color_mask;
    ds->write_mask[0] = cm->no_red ? 0 : 0xff;
    ds->write_mask[1] = cm->no_green ? 0 : 0xff;
    ds->write_mask[2] = cm->no_blue ? 0 : 0xff;
    ds->write_mask[3] = cm->no_alpha ? 0 : 0xff;
    ds->blending = ds->blend.enabled || cm->no_red || cm->no_green || cm->no_blue || cm->no_alpha;

    ds->cull = st->cull == SR_CULL_DEFAULT ? SR_CULL_NONE : st->cull;
    ds->front_ccw = st->front_face != SR_FRONT_CW;
    ds->rasterizer = st->rasterizer == SR_RASTER_DEFAULT ? SR_RASTER_HALFSPACE : st->rasterizer;
    ds->depth_test = !st->no_depth_test && fb->depth != NULL;
    ds->depth_write = !st->no_depth_write && fb->depth != NULL;
    ds->depth_func = st->depth_func == SR_DEPTH_FUNC_DEFAULT ? SR_LESS : st->depth_func;
    ds->depth_bits = fb->depth_bits;
    if (!fb->depth || (!ds->depth_test && !ds->depth_write)) {
        ds->depth_mode = SR_DEPTH_MODE_OFF;
    } else if (ds->depth_test && ds->depth_write && ds->depth_func == SR_LESS) {
        ds->depth_mode = SR_DEPTH_MODE_LESS;
    } else {
        ds->depth_mode = SR_DEPTH_MODE_GENERIC;
    }
    ds->offset_on = st->offset.fill;
    ds->offset_line = st->offset.line;
    ds->offset_point = st->offset.point;
    ds->mode_front = st->polygon_mode_front == SR_POLYGON_DEFAULT ? SR_POLYGON_FILL
                                                                  : st->polygon_mode_front;
    ds->mode_back = st->polygon_mode_back == SR_POLYGON_DEFAULT ? SR_POLYGON_FILL
                                                                : st->polygon_mode_back;
    ds->line_width = st->line_width == 0.0f ? 1 : (int)lroundf(st->line_width);
    ds->line_width = ds->line_width < 1 ? 1 : ds->line_width;
    ds->point_size = st->point_size == 0.0f ? 1.0 : st->point_size;
    ds->round_points = st->round_points;
    ds->smooth_lines = st->smooth_lines;
    ds->smooth_points = st->smooth_points;
    ds->smooth_width = st->line_width == 0.0f ? 1.0 : st->line_width;
    ds->offset_factor = st->offset.factor;
    ds->offset_units = st->offset.units;
    ds->offset_clamp = st->offset.clamp;

    sr__resolve_shading(st, view, proj, ds);

    /* Multisampling and stencil take the per-sample path (raster/sample.c). */
    ds->samples = fb->samples;
    ds->sample_off = sr__sample_offsets(fb->samples);
    ds->stencil_test = st->stencil.enabled && fb->stencil != NULL;
    for (int i = 0; i < 2; i++) {
        sr_stencil_face f = (i == 1 && st->stencil.separate) ? st->stencil.back : st->stencil.front;
        f.func = f.func == SR_DEPTH_FUNC_DEFAULT ? SR_ALWAYS : f.func;
        if (!f.masked) {
            f.read_mask = f.write_mask = 0xff;
        }
        ds->stencil[i] = f;
    }
    ds->alpha_to_coverage = st->alpha_to_coverage && fb->samples > 1;
    ds->per_sample = fb->samples > 1 || ds->stencil_test;
    if (st->program) {
        /* The program owns the varyings; the built-in models' state is
         * unused.  Fragment shaders run on the per-sample path's quads. */
        const sr_program *pr = st->program;
        ds->program = pr;
        ds->shading = SR_SHADING_UNLIT;
        ds->nvary = ds->ninterp = pr->varying_count;
        ds->texture = NULL;
        ds->uv_index = -1;
        ds->depth_vis_linear = false;
        for (int k = 0; k < pr->varying_count; k++) {
            ds->flat_mask |= pr->modes[k] == SR_VARYING_FLAT ? 1u << k : 0u;
            ds->noperspective_mask |= pr->modes[k] == SR_VARYING_NOPERSPECTIVE ? 1u << k : 0u;
        }
        ds->per_sample = true;
    }
    ds->raster_fast = ds->per_sample ? NULL : sr__raster_simd_select(ds);
    sr_simd_level simd = sr__simd_level();
    ds->light_lanes = simd != SR_SIMD_OFF;
    ds->vertex_lanes16 = simd == SR_SIMD_AVX512;
    ds->wide_stores = simd == SR_SIMD_AVX512;
    ds->index_avx2 = simd >= SR_SIMD_AVX2;
    ds->sample_fast = ds->per_sample ? sr__raster_sample_select(ds) : NULL;
}

static uint32_t index_at(const sr_draw_desc *d, size_t i)
{
    switch (d->index_type) {
    case SR_INDEX_U8:  return ((const uint8_t *)d->indices)[i];
    case SR_INDEX_U16: return ((const uint16_t *)d->indices)[i];
    case SR_INDEX_U32: return ((const uint32_t *)d->indices)[i];
    default:           return (uint32_t)i;
    }
}

/* The largest of indices [begin, end) of an indexed draw
 * (geometry/index_max.c).  Run by the vertex stage's jobs, each over its
 * share: the indices come from memory, and one pass over the bunny's
 * 208,353 on the application thread alone took 3% of a two-thread frame. */
static uint32_t max_index(const sr_draw_state *ds, const sr_draw_desc *d, size_t begin,
                          size_t end)
{
    return sr__index_max(d->index_type, d->indices, begin, end, ds->index_avx2);
}

/* Indices out of range are an error before anything is drawn: given the
 * largest index, name the first one out of range. */
static sr_result check_indices(sr_context *ctx, const sr_draw_desc *d, uint32_t max)
{
    if (d->index_type == SR_INDEX_NONE || d->index_count == 0 || max < d->vertex_count) {
        return SR_OK;
    }
    for (size_t i = 0; i < d->index_count; i++) {
        uint32_t ix = index_at(d, i);
        if (ix >= d->vertex_count) {
            return sr__fail(ctx, SR_INVALID_ARG,
                            "sr_draw_desc.indices[%zu] = %u is out of range (vertex_count %zu)",
                            i, ix, d->vertex_count);
        }
    }
    return SR_OK;
}

static bool is_culled(const sr_draw_state *ds, bool front)
{
    switch (ds->cull) {
    case SR_CULL_BACK:           return !front;
    case SR_CULL_FRONT:          return front;
    case SR_CULL_FRONT_AND_BACK: return true;
    default:                     return false;
    }
}

/* On the y-down framebuffer, a triangle that is counter-clockwise on
 * screen has a negative snapped area2 (RASTER_RULES 2.7). */
static bool facing_front(const sr_draw_state *ds, int64_t area2)
{
    return ds->front_ccw ? area2 < 0 : area2 > 0;
}

/* The front end of one chunk: what a worker needs to assemble, clip and
 * set up its primitives.  With `fused`, each chunk also runs the vertex
 * stage for its own primitives, a block at a time (see run_front_end). */
typedef struct front_end {
    sr_context *ctx;
    const sr_draw_state *ds;
    const sr_draw_desc *d;
    size_t tri_size;
    int chunks;
    bool fused;
    bool shared;                      /* more than one thread: records are read on every core */
    size_t verts_per_prim;            /* fused: primitive p uses vertices k p .. k p + k - 1 */
    const sr_mat4 *mvp, *mv, *nm;
} front_end;

/* Where primitive assembly finds the vertex stage's output: post[i - base]
 * and vary + (i - base) nvary for vertex i - the whole draw's arrays
 * (base 0), or a block of them on the stack. */
typedef struct vertex_src {
    const sr_vertex_post *post;
    const float *vary;
    size_t base;
} vertex_src;

/* The next free record of chunk c, or NULL when out of memory.  The store
 * was sized for the chunk up front, so it nearly always has room. */
static inline void *next_record(const front_end *fe, sr_chunk *c)
{
    size_t at = (size_t)c->tri_count * fe->tri_size;
    if (at + fe->tri_size > c->tri_bytes &&
        !sr__chunk_reserve_tris(fe->ctx, c, (size_t)c->tri_count + 1, fe->tri_size)) {
        c->out_of_memory = true;
        return NULL;
    }
    return c->tris + at;
}

/* Record number tri_count of chunk c is complete: note its tiles. */
static inline void keep_record(sr_chunk *c, const sr_prim_head *h)
{
    c->tile_box[c->tri_count++] = sr__tile_box(h);
}

/* Room for any kind of record set up off to the side (sr__record_size). */
typedef union record_buf {
    sr_tri tri;
    sr_line line;
    sr_point point;
} record_buf;

/* A filled triangle; area2 = sr__area2(w0, w1, w2). */
static inline __attribute__((always_inline)) void emit(const front_end *fe, sr_chunk *c, const sr_window_vertex *w0,
                 const sr_window_vertex *w1, const sr_window_vertex *w2, int64_t area2,
                 bool front, const float flat[4])
{
    if (area2 == 0) {
        return; /* setup would find nothing to draw */
    }
    sr_tri *rec = next_record(fe, c);
    if (!rec) {
        return;
    }
    /* Set up in place, or on the stack and then streamed to its place;
     * four varyings (unlit, Gouraud, attribute) is the common case,
     * unrolled. */
    record_buf buf;
    sr_tri *t = c->stream ? &buf.tri : rec;
    const sr_draw_state *ds = fe->ds;
    bool drawn = ds->ninterp == 4
                     ? sr__setup_tri(ds, w0, w1, w2, area2, NAN, front, 4, flat, t)
                     : sr__setup_tri(ds, w0, w1, w2, area2, NAN, front, ds->ninterp, flat, t);
    if (drawn) {
        if (c->stream) {
            sr__stream_record(rec, t, fe->tri_size);
        }
        keep_record(c, &t->h);
        c->info.triangles_drawn++;
    }
}

/* A multisampled line is the rectangle of its width centred on the
 * segment (Vulkan's strict lines, Direct3D's MSAA lines), drawn as two
 * triangles sampled like any other: each corner carries its end's depth,
 * 1/w and varyings. */
static void emit_line_quad(const front_end *fe, sr_chunk *c, const sr_window_vertex *a,
                           const sr_window_vertex *b, double offset, bool front,
                           const float flat[4])
{
    const sr_draw_state *ds = fe->ds;
    double dx = (double)b->x_q8 - a->x_q8, dy = (double)b->y_q8 - a->y_q8;
    double len = sqrt(dx * dx + dy * dy);
    if (len == 0.0) {
        return;
    }
    double half = (ds->smooth_lines ? ds->smooth_width : ds->line_width) * 0.5;
    double nx = -dy / len * half * SR_SUBPIXEL_ONE, ny = dx / len * half * SR_SUBPIXEL_ONE;
    int32_t ox = (int32_t)nearbyint(nx), oy = (int32_t)nearbyint(ny);
    sr_window_vertex q[4] = { *a, *a, *b, *b };
    q[0].x_q8 += ox, q[0].y_q8 += oy;
    q[1].x_q8 -= ox, q[1].y_q8 -= oy;
    q[2].x_q8 -= ox, q[2].y_q8 -= oy;
    q[3].x_q8 += ox, q[3].y_q8 += oy;
    for (int i = 0; i < 2; i++) {
        sr_tri *t = next_record(fe, c);
        if (t && sr__setup_triangle_offset(ds, &q[0], &q[1 + i], &q[2 + i], offset, front,
                                           ds->ninterp, flat, t)) {
            keep_record(c, &t->h);
        }
    }
}

static void emit_line(const front_end *fe, sr_chunk *c, const sr_window_vertex *a,
                      const sr_window_vertex *b, double offset, bool front, const float flat[4])
{
    if (fe->ds->samples > 1) {
        emit_line_quad(fe, c, a, b, offset, front, flat);
        return;
    }
    sr_line *l = next_record(fe, c);
    if (l && sr__setup_line(fe->ds, a, b, offset, front, fe->ds->ninterp, flat, l)) {
        keep_record(c, &l->h);
    }
}

static void emit_point(const front_end *fe, sr_chunk *c, const sr_window_vertex *v,
                       double offset, bool front, const float flat[4])
{
    sr_point *p = next_record(fe, c);
    if (p && sr__setup_point(fe->ds, v, offset, front, fe->ds->ninterp, flat, p)) {
        keep_record(c, &p->h);
    }
}

/* glPolygonMode: a clipped, culled polygon w[0..n-1] drawn as its outline
 * (each edge half-open, so every corner is drawn once) or its corners,
 * with the polygon offset of its plane when enabled for that mode. */
static void polygon_outline(const front_end *fe, sr_chunk *c, const sr_window_vertex *w, int n,
                            sr_polygon_mode mode, bool front, const float flat[4])
{
    double offset = sr__polygon_offset(fe->ds, &w[0], &w[1], &w[2], mode);
    for (int i = 0; i < n; i++) {
        if (mode == SR_POLYGON_LINE) {
            emit_line(fe, c, &w[i], &w[(i + 1) % n], offset, front, flat);
        } else {
            emit_point(fe, c, &w[i], offset, front, flat);
        }
    }
}

static void clip_vertex(const sr_draw_state *ds, const sr_vertex_post *p, const float *vary,
                        sr_clip_vertex *out)
{
    memcpy(out->pos, p->pos, sizeof out->pos);
    memcpy(out->vary, vary, (size_t)ds->nvary * sizeof(float));
}

/* A program's flat varyings take the provoking vertex's values: give each
 * vertex a copy with them in place (clipping then interpolates between
 * equal values, which leaves them exact), or the vertex's own varyings
 * when there are none. */
static const float *flat_varyings(const sr_draw_state *ds, const float *a, const float *pv,
                                  float *buf)
{
    if (!ds->flat_mask || a == pv) {
        return a;
    }
    memcpy(buf, a, (size_t)ds->nvary * sizeof(float));
    for (unsigned m = ds->flat_mask; m; m &= m - 1) {
        int k = __builtin_ctz(m);
        buf[k] = pv[k];
    }
    return buf;
}

/* A triangle with a vertex outside some clip plane (but not all three
 * outside one): clip, then fan the polygon back into triangles.  Facing
 * comes from the whole polygon's snapped area so the fan is culled as
 * one.  Out of line, so the common case above keeps a small frame. */
static __attribute__((noinline)) void clipped_triangle(const front_end *fe, sr_chunk *c,
                                                       const sr_vertex_post *p0,
                                                       const sr_vertex_post *p1,
                                                       const sr_vertex_post *p2, const float *a0,
                                                       const float *a1, const float *a2,
                                                       const float *pva)
{
    const sr_draw_state *ds = fe->ds;
    unsigned c0 = p0->outcode, c1 = p1->outcode, c2 = p2->outcode;
    float flat[4] = { 0, 0, 0, 1 };
    bool need_flat = ds->shading == SR_SHADING_FLAT;
    c->info.triangles_clipped++;
    if (need_flat) {
        sr__flat_color(ds, a0, a1, a2, pva, flat);
    }
    sr_clip_vertex v[3];
    clip_vertex(ds, p0, a0, &v[0]);
    clip_vertex(ds, p1, a1, &v[1]);
    clip_vertex(ds, p2, a2, &v[2]);
    const sr_clip_vertex *in[3] = { &v[0], &v[1], &v[2] };
    sr_clip_vertex poly[SR_CLIP_MAX_VERTS];
    int n = sr__clip_polygon(ds, in, (c0 | c1 | c2), poly);
    if (n < 3) {
        c->info.triangles_culled++;
        return;
    }
    sr_window_vertex w[SR_CLIP_MAX_VERTS];
    for (int i = 0; i < n; i++) {
        /* The one point with w = 0 that passes every plane is the clip-space
         * origin (the band planes force x = y = 0, near/far z = 0), e.g. the
         * midpoint of an edge from v to -v.  A polygon through it has
         * linearly dependent vertices, so no area; the divide would give
         * 0/0 = NaN.  Discard (RASTER_RULES 3.4). */
        if (!(poly[i].pos[3] > 0.0f)) {
            c->info.triangles_culled++;
            return;
        }
        sr__window_vertex(ds, &poly[i], &w[i]);
    }
    int64_t area2 = 0;
    for (int i = 1; i + 1 < n; i++) {
        area2 += sr__area2(&w[0], &w[i], &w[i + 1]);
    }
    bool front = facing_front(ds, area2);
    if (area2 == 0 || is_culled(ds, front)) {
        c->info.triangles_culled++;
        return;
    }
    sr_polygon_mode mode = front ? ds->mode_front : ds->mode_back;
    if (mode != SR_POLYGON_FILL) {
        polygon_outline(fe, c, w, n, mode, front, flat);
        return;
    }
    for (int i = 1; i + 1 < n; i++) {
        emit(fe, c, &w[0], &w[i], &w[i + 1], sr__area2(&w[0], &w[i], &w[i + 1]), front, flat);
    }
}

static void triangle(const front_end *fe, sr_chunk *c, const vertex_src *vs, uint32_t i0,
                     uint32_t i1, uint32_t i2, uint32_t pv)
{
    const sr_draw_state *ds = fe->ds;
    size_t b = vs->base;
    const sr_vertex_post *p0 = &vs->post[i0 - b], *p1 = &vs->post[i1 - b], *p2 = &vs->post[i2 - b];
    size_t nv = (size_t)ds->nvary;
    const float *a0 = vs->vary + (i0 - b) * nv, *a1 = vs->vary + (i1 - b) * nv;
    const float *a2 = vs->vary + (i2 - b) * nv;
    float fb0[SR_MAX_VARYINGS], fb1[SR_MAX_VARYINGS], fb2[SR_MAX_VARYINGS];
    const float *pva = vs->vary + (pv - b) * nv;
    if (ds->flat_mask) {
        a0 = flat_varyings(ds, a0, pva, fb0);
        a1 = flat_varyings(ds, a1, pva, fb1);
        a2 = flat_varyings(ds, a2, pva, fb2);
    }
    c->info.triangles_in++;

    unsigned c0 = p0->outcode, c1 = p1->outcode, c2 = p2->outcode;
    if ((c0 | c1 | c2) & SR_OUTCODE_NONFINITE) {
        c->info.triangles_culled++;
        return; /* NaN or infinite positions discard the primitive */
    }
    if (c0 & c1 & c2) {
        c->info.triangles_culled++;
        return; /* all three outside one plane */
    }
    if ((c0 | c1 | c2) != 0) {
        clipped_triangle(fe, c, p0, p1, p2, a0, a1, a2, pva);
        return;
    }

    /* Inside every plane: the window positions are the vertex stage's. */
    sr_window_vertex w[3] = {
        { p0->x_q8, p0->y_q8, p0->z, p0->inv_w, a0 },
        { p1->x_q8, p1->y_q8, p1->z, p1->inv_w, a1 },
        { p2->x_q8, p2->y_q8, p2->z, p2->inv_w, a2 },
    };
    int64_t area2 = sr__area2(&w[0], &w[1], &w[2]);
    bool front = facing_front(ds, area2);
    if (area2 == 0 || is_culled(ds, front)) {
        c->info.triangles_culled++;
        return;
    }
    float flat[4] = { 0, 0, 0, 1 };
    if (ds->shading == SR_SHADING_FLAT) {
        sr__flat_color(ds, a0, a1, a2, pva, flat);
    }
    sr_polygon_mode mode = front ? ds->mode_front : ds->mode_back;
    if (mode == SR_POLYGON_FILL) {
        emit(fe, c, &w[0], &w[1], &w[2], area2, front, flat);
    } else {
        polygon_outline(fe, c, w, 3, mode, front, flat);
    }
}

/* A window vertex straight from the post-transform cache. */
static sr_window_vertex cached_window(const sr_vertex_post *p, const float *vary)
{
    return (sr_window_vertex){ p->x_q8, p->y_q8, p->z, p->inv_w, vary };
}

/* Flat shading of a line or point: the provoking vertex's own color. */
static const float *provoking_color(const sr_draw_state *ds, const float *pv)
{
    return ds->shading == SR_SHADING_FLAT ? &pv[SR_VARY_FLAT_COLOR] : NULL;
}

static void segment(const front_end *fe, sr_chunk *c, const vertex_src *vs, uint32_t i0,
                    uint32_t i1, uint32_t pv)
{
    const sr_draw_state *ds = fe->ds;
    size_t b = vs->base;
    const sr_vertex_post *p0 = &vs->post[i0 - b], *p1 = &vs->post[i1 - b];
    size_t nv = (size_t)ds->nvary;
    const float *a0 = vs->vary + (i0 - b) * nv, *a1 = vs->vary + (i1 - b) * nv;
    const float *pva = vs->vary + (pv - b) * nv;
    const float *flat = provoking_color(ds, pva);
    float fb0[SR_MAX_VARYINGS], fb1[SR_MAX_VARYINGS];
    a0 = flat_varyings(ds, a0, pva, fb0);
    a1 = flat_varyings(ds, a1, pva, fb1);
    unsigned c0 = p0->outcode, c1 = p1->outcode;
    if (((c0 | c1) & SR_OUTCODE_NONFINITE) || (c0 & c1)) {
        return;
    }
    if ((c0 | c1) == 0) {
        sr_window_vertex w0 = cached_window(p0, a0), w1 = cached_window(p1, a1);
        emit_line(fe, c, &w0, &w1, 0.0, true, flat);
        return;
    }
    sr_clip_vertex v0, v1, o0, o1;
    clip_vertex(ds, p0, a0, &v0);
    clip_vertex(ds, p1, a1, &v1);
    if (!sr__clip_segment(ds, &v0, &v1, c0 | c1, &o0, &o1)) {
        return;
    }
    /* As for polygons: an end that rounding left at w <= 0 (the clip-space
     * origin, or t rounded to the outside end) cannot be divided. */
    if (!(o0.pos[3] > 0.0f) || !(o1.pos[3] > 0.0f)) {
        return;
    }
    sr_window_vertex w0, w1;
    sr__window_vertex(ds, &o0, &w0);
    sr__window_vertex(ds, &o1, &w1);
    emit_line(fe, c, &w0, &w1, 0.0, true, flat);
}

/* A point is drawn when its vertex is inside every plane (RASTER_RULES 7). */
static void point(const front_end *fe, sr_chunk *c, const vertex_src *vs, uint32_t i)
{
    const sr_draw_state *ds = fe->ds;
    const sr_vertex_post *p = &vs->post[i - vs->base];
    if (p->outcode != 0) {
        return;
    }
    const float *a = vs->vary + (i - vs->base) * (size_t)ds->nvary;
    sr_window_vertex w = cached_window(p, a);
    emit_point(fe, c, &w, 0.0, true, provoking_color(ds, a));
}

/* Primitive p of the draw, with the provoking vertex of RASTER_RULES 4.2. */
static void primitive(const front_end *fe, sr_chunk *c, const vertex_src *vs, size_t p)
{
    const sr_draw_desc *d = fe->d;
    bool last = fe->ds->provoking_last;
    switch (d->primitive) {
    case SR_PRIM_TRIANGLE_STRIP: {
        uint32_t a = index_at(d, p), b = index_at(d, p + 1), e = index_at(d, p + 2);
        uint32_t pv = last ? e : a;
        /* Odd triangles swap their first two vertices to keep winding. */
        if (p & 1) {
            triangle(fe, c, vs, b, a, e, pv);
        } else {
            triangle(fe, c, vs, a, b, e, pv);
        }
        break;
    }
    case SR_PRIM_TRIANGLE_FAN: {
        uint32_t a = index_at(d, 0), b = index_at(d, p + 1), e = index_at(d, p + 2);
        triangle(fe, c, vs, a, b, e, last ? e : b);
        break;
    }
    case SR_PRIM_LINES: {
        uint32_t a = index_at(d, 2 * p), b = index_at(d, 2 * p + 1);
        segment(fe, c, vs, a, b, last ? b : a);
        break;
    }
    case SR_PRIM_LINE_STRIP:
    case SR_PRIM_LINE_LOOP: {
        /* A loop's last segment closes back to the first vertex. */
        size_t n = d->index_type == SR_INDEX_NONE ? d->vertex_count : d->index_count;
        uint32_t a = index_at(d, p), b = index_at(d, (p + 1) % n);
        segment(fe, c, vs, a, b, last ? b : a);
        break;
    }
    case SR_PRIM_POINTS:
        point(fe, c, vs, index_at(d, p));
        break;
    default: {
        uint32_t a = index_at(d, 3 * p), b = index_at(d, 3 * p + 1), e = index_at(d, 3 * p + 2);
        triangle(fe, c, vs, a, b, e, last ? e : a);
        break;
    }
    }
}

/* Vertices per block of the fused vertex stage: a multiple of 2 and 3,
 * small enough for the block's positions and varyings to stay in L1. */
#define FUSED_BLOCK_VERTS 192

/* How many triangles ahead an indexed list's vertices are prefetched. */
#define SR_PREFETCH_TRIS 8

static void run_front_end(void *arg, int job, int thread)
{
    (void)thread;
    const front_end *fe = arg;
    sr_chunk *c = &fe->ctx->scratch->chunks[job];
    c->tri_count = 0;
    /* Records go out by streaming stores when more than one thread draws
     * (scratch.h), except in a chunk that was copied in tile order the
     * batch before (parallel/bin.c).  Its records are only read back by
     * that copy, on the thread that wrote them, so plain stores leave
     * them in this core's cache for it (small 64.7 -> 63.0 and 62.8 ->
     * 61.8 ms on two threads).  Whether this batch's chunk is copied too
     * is only known once it is binned; where it is not, the tile jobs
     * read the records from this core's cache instead: the same bytes,
     * only slower. */
    c->stream = fe->shared && !c->in_tile_order;
    /* One triangle per primitive is the common case; size for it once so
     * the store is not regrown (and copied) mid-chunk. */
    if (!sr__chunk_reserve_tris(fe->ctx, c, c->prim_end - c->prim_begin + 16, fe->tri_size)) {
        /* No records: the bins must say so rather than keep the last
         * batch's, whose records may no longer be there. */
        c->out_of_memory = true;
        sr__bin_chunk(fe->ctx, fe->ds, c, fe->tri_size, fe->shared);
        return;
    }
    if (fe->fused) {
        /* The vertex stage for this chunk's own vertices, a block at a
         * time into buffers that stay in the L1 cache while the block's
         * primitives are assembled: a draw without indices uses each
         * vertex once, so the whole-draw arrays would only be written
         * out to memory and read back. */
        sr_vertex_post post[FUSED_BLOCK_VERTS];
        float vary[FUSED_BLOCK_VERTS * SR_MAX_VARYINGS];
        size_t k = fe->verts_per_prim, per_block = FUSED_BLOCK_VERTS / k;
        for (size_t p = c->prim_begin; p < c->prim_end && !c->out_of_memory; p += per_block) {
            size_t end = c->prim_end - p < per_block ? c->prim_end : p + per_block;
            sr__vertex_stage(fe->ds, fe->d, fe->mvp, fe->mv, fe->nm, k * p, k * (end - p), post,
                             vary);
            vertex_src vs = { post, vary, k * p };
            if (k == 3) {
                /* primitive()'s triangle list without indices. */
                bool last = fe->ds->provoking_last;
                for (size_t q = p; q < end && !c->out_of_memory; q++) {
                    uint32_t a = (uint32_t)(3 * q);
                    triangle(fe, c, &vs, a, a + 1, a + 2, last ? a + 2 : a);
                }
                continue;
            }
            for (size_t q = p; q < end && !c->out_of_memory; q++) {
                primitive(fe, c, &vs, q);
            }
        }
    } else {
        const sr_scratch *s = fe->ctx->scratch;
        vertex_src vs = { s->post, s->vary, 0 };
        const sr_draw_desc *d = fe->d;
        bool list = d->primitive == SR_PRIM_DEFAULT || d->primitive == SR_PRIM_TRIANGLES;
        size_t nv = (size_t)fe->ds->nvary;
        for (size_t p = c->prim_begin; p < c->prim_end && !c->out_of_memory; p++) {
            if (list && p + SR_PREFETCH_TRIS < c->prim_end) {
                /* An indexed mesh's vertices are gathered: ask for those
                 * of a triangle a few ahead, so its post-transform
                 * vertices (48 bytes, often across two lines) and
                 * varyings arrive while this one is set up. */
                for (size_t k = 0; k < 3; k++) {
                    uint32_t i = index_at(d, 3 * (p + SR_PREFETCH_TRIS) + k);
                    const char *v = (const char *)&s->post[i];
                    __builtin_prefetch(v);
                    __builtin_prefetch(v + sizeof(sr_vertex_post) - 1);
                    __builtin_prefetch(&s->vary[i * nv]);
                }
            }
            primitive(fe, c, &vs, p);
        }
    }
    if (c->stream) {
        sr__stream_fence();
    }
    if (!sr__bin_chunk(fe->ctx, fe->ds, c, fe->tri_size, fe->shared)) {
        c->out_of_memory = true;
    }
}

typedef struct vertex_job {
    const sr_draw_state *ds;
    const sr_draw_desc *d;
    const sr_mat4 *mvp, *mv, *nm;
    sr_scratch *s;
    size_t per_job, jobs;
    uint32_t max_index[SR_MAX_THREADS]; /* per thread, over its jobs' shares of the indices */
} vertex_job;

static void run_vertex_stage(void *arg, int job, int thread)
{
    vertex_job *vj = arg;
    const sr_draw_desc *d = vj->d;
    size_t first = (size_t)job * vj->per_job;
    size_t count = d->vertex_count - first < vj->per_job ? d->vertex_count - first : vj->per_job;
    sr__vertex_stage(vj->ds, d, vj->mvp, vj->mv, vj->nm, first, count, vj->s->post + first,
                     vj->s->vary + first * (size_t)vj->ds->nvary);
    /* The vertex stage reads no index, so the check can wait for it. */
    uint32_t m = max_index(vj->ds, d, d->index_count * (size_t)job / vj->jobs,
                           d->index_count * ((size_t)job + 1) / vj->jobs);
    vj->max_index[thread] = m > vj->max_index[thread] ? m : vj->max_index[thread];
}

/* Cut primitives [begin, end) into the chunks: one equal share per thread
 * (the pool runs share t's chunks on thread t first), each share cut
 * into chunks of decreasing size, 4 : 3 : 2 : 1, so that what a thread that
 * is done early takes from the end of another's share is small - the
 * cost of a mesh's triangles varies along it (the bunny's first half,
 * mostly facing the camera, takes 1.7 times its second half to set up). */
static void split_batch(sr_scratch *s, size_t begin, size_t end, int threads, int chunks)
{
    _Static_assert(SR_CHUNKS_PER_THREAD == 4, "the weights below are for four chunks");
    static const unsigned quarters[] = { 0, 4, 7, 9, 10 }, whole[] = { 0, 10 };
    int per_thread = chunks / threads; /* 1 (one thread) or SR_CHUNKS_PER_THREAD */
    const unsigned *cum = per_thread == 1 ? whole : quarters;
    size_t n = end - begin;
    for (int ci = 0; ci < chunks; ci++) {
        size_t t = (size_t)(ci / per_thread), k = (size_t)(ci % per_thread);
        size_t lo = begin + n * t / (size_t)threads, hi = begin + n * (t + 1) / (size_t)threads;
        s->chunks[ci].prim_begin = lo + (hi - lo) * cum[k] / 10;
        s->chunks[ci].prim_end = lo + (hi - lo) * cum[k + 1] / 10;
    }
}

sr_result sr_draw(sr_context *ctx, sr_framebuffer *fb, const sr_state *state,
                  const sr_draw_desc *d)
{
    if (!ctx) {
        return SR_INVALID_ARG;
    }
    memset(&ctx->last_draw, 0, sizeof ctx->last_draw);
    sr_result r = validate(ctx, fb, state, d);
    if (r != SR_OK) {
        return r;
    }
    size_t count = d->index_type == SR_INDEX_NONE ? d->vertex_count : d->index_count;

    sr_draw_state ds;
    resolve_state(fb, state, d->view, d->projection, &ds);

    size_t prims = 0;
    switch (d->primitive) {
    case SR_PRIM_TRIANGLE_STRIP:
    case SR_PRIM_TRIANGLE_FAN: prims = count >= 3 ? count - 2 : 0; break;
    case SR_PRIM_LINES:        prims = count / 2; break;
    case SR_PRIM_LINE_STRIP:   prims = count >= 2 ? count - 1 : 0; break;
    case SR_PRIM_LINE_LOOP:    prims = count >= 3 ? count : (count == 2 ? 1 : 0); break;
    case SR_PRIM_POINTS:       prims = count; break;
    default:                   prims = count / 3; break;
    }
    /* Without indices, lists of triangles, lines or points use each vertex
     * once: the front end's chunks run the vertex stage for their own
     * primitives (run_front_end) and the whole-draw arrays are not used. */
    size_t verts_per_prim = 0;
    if (d->index_type == SR_INDEX_NONE) {
        switch (d->primitive) {
        case SR_PRIM_DEFAULT:
        case SR_PRIM_TRIANGLES: verts_per_prim = 3; break;
        case SR_PRIM_LINES:     verts_per_prim = 2; break;
        case SR_PRIM_POINTS:    verts_per_prim = 1; break;
        default:                break;
        }
    }
    bool fused = verts_per_prim != 0;
    /* More chunks than threads evens out uneven clipping and culling: the
     * bunny's first quarter of triangles takes four times as long to set up
     * as its last (culled backs), and with two chunks a thread the pool's
     * stealing could not even that out. */
    int chunks = ctx->threads == 1 ? 1 : ctx->threads * SR_CHUNKS_PER_THREAD;
    sr_scratch *s = ctx->scratch;
    if (!sr__scratch_reserve(ctx, s, fused ? 0 : d->vertex_count,
                             (size_t)ds.tiles_x * ds.tiles_y, chunks)) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_draw: out of memory for %zu vertices",
                        d->vertex_count);
    }
    sr__ok(ctx);
    if (prims == 0 || ds.rect_x0 >= ds.rect_x1 || ds.rect_y0 >= ds.rect_y1 ||
        d->vertex_count == 0) {
        /* Nothing to draw, but the indices are still checked. */
        return check_indices(ctx, d, max_index(&ds, d, 0, d->index_count));
    }

    /* M = P E M_O, and the normal matrix from E M_O. */
    sr_mat4 mo = d->model ? *d->model : sr_mat4_identity();
    sr_mat4 e = d->view ? *d->view : sr_mat4_identity();
    sr_mat4 p = d->projection ? *d->projection : sr_mat4_identity();
    sr_mat4 mv = sr_mat4_mul(&e, &mo);
    sr_mat4 mvp = sr_mat4_mul(&p, &mv);
    sr_mat4 nm;
    if (!sr_normal_matrix(&mv, &nm)) {
        nm = mv; /* singular model-view (a flattening scale): best effort */
    }
    if (!fused) {
        /* Blocks of at most 4096 vertices, a multiple of the thread count
         * of them: the pool gives each thread a contiguous share of the
         * blocks, as it does the front end's chunks, and a mesh's
         * triangles mostly use vertices near their own place in the
         * order, so a chunk mostly reads vertices its own core shaded.
         * Up to 8 blocks a thread as long as each has 256 vertices, so
         * that a caller whose workers are still waking takes over the
         * blocks of theirs they have not started. */
        size_t threads = (size_t)ctx->threads;
        size_t jobs = (d->vertex_count + 4095) / 4096;
        size_t fine = d->vertex_count / 256 < threads * 8 ? d->vertex_count / 256 : threads * 8;
        jobs = jobs > fine ? jobs : fine;
        jobs = (jobs + threads - 1) / threads * threads;
        vertex_job vj = { &ds, d, &mvp, &mv, &nm, s, (d->vertex_count + jobs - 1) / jobs, 0, { 0 } };
        vj.jobs = (d->vertex_count + vj.per_job - 1) / vj.per_job;
        sr__pool_run(ctx->pool, run_vertex_stage, &vj, (int)vj.jobs);
        uint32_t m = 0;
        for (int t = 0; t < ctx->threads; t++) {
            m = vj.max_index[t] > m ? vj.max_index[t] : m;
        }
        sr_result ri = check_indices(ctx, d, m);
        if (ri != SR_OK) {
            return ri;
        }
    }

    memset(s->stats, 0, sizeof s->stats);
    /* Filled triangles only: records of a triangle's size (sr__record_size). */
    bool triangle_prims = d->primitive == SR_PRIM_DEFAULT || d->primitive == SR_PRIM_TRIANGLES ||
                          d->primitive == SR_PRIM_TRIANGLE_STRIP ||
                          d->primitive == SR_PRIM_TRIANGLE_FAN;
    bool triangles_only = triangle_prims && ds.mode_front == SR_POLYGON_FILL &&
                          ds.mode_back == SR_POLYGON_FILL;
    size_t record_size =
        sr__record_size(ds.ninterp, ds.shading == SR_SHADING_FLAT, triangles_only);
    front_end fe = { ctx, &ds, d, record_size, chunks, fused, ctx->threads > 1,
                     verts_per_prim, &mvp, &mv, &nm };
    bool oom = false;
    /* Equal batches of at most the context's batch size, so no batch is a
     * sliver. */
    size_t batches = (prims + ctx->batch_prims - 1) / ctx->batch_prims;
    size_t batch_size = (prims + batches - 1) / batches;
    for (size_t begin = 0; begin < prims && !oom; begin += batch_size) {
        size_t end = prims - begin < batch_size ? prims : begin + batch_size;
        split_batch(s, begin, end, ctx->threads, chunks);
        sr__pool_run(ctx->pool, run_front_end, &fe, chunks);
        sr__bin_rasterize(ctx, &ds, chunks, fe.tri_size);
        for (int ci = 0; ci < chunks; ci++) {
            sr_chunk *c = &s->chunks[ci];
            sr_draw_info *in = &c->info;
            ctx->last_draw.triangles_in += in->triangles_in;
            ctx->last_draw.triangles_clipped += in->triangles_clipped;
            ctx->last_draw.triangles_culled += in->triangles_culled;
            ctx->last_draw.triangles_drawn += in->triangles_drawn;
            memset(in, 0, sizeof *in);
            oom |= c->out_of_memory;
            c->out_of_memory = false;
        }
    }
    for (int i = 0; i < SR_MAX_THREADS; i++) {
        ctx->last_draw.fragments += s->stats[i].fragments;
    }
    if (oom) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY,
                        "sr_draw: out of memory while setting up triangles (the draw is incomplete)");
    }
    return SR_OK;
}
