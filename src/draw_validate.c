/* draw_validate.c - the checks sr_draw makes before anything is drawn:
 * every pointer, count, size and value its arguments carry, each failure
 * named by its field (sr_context_error).  Application thread. */
#include "context.h"
#include "pipeline.h"

#include <math.h>

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

/* The vertex stage reads each attribute as floats in place and assembly
 * reads indices as their type, so, as GL asks of attribute offsets and
 * strides, an array's address and stride must be multiples of its
 * element's size: a misaligned read is undefined in C and faults on some
 * processors. */
static sr_result check_alignment(sr_context *ctx, const sr_draw_desc *d)
{
    const struct {
        const float *base;
        size_t stride;
        const char *base_name, *stride_name;
    } arrays[] = {
        { d->positions, d->position_stride, "positions", "position_stride" },
        { d->normals, d->normal_stride, "normals", "normal_stride" },
        { d->colors, d->color_stride, "colors", "color_stride" },
        { d->texcoords, d->texcoord_stride, "texcoords", "texcoord_stride" },
        { d->generic, d->generic_stride, "generic", "generic_stride" },
    };
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++) {
        if (!arrays[i].base) {
            continue;
        }
        if ((uintptr_t)arrays[i].base % sizeof(float) != 0) {
            return sr__fail(ctx, SR_INVALID_ARG, "sr_draw_desc.%s is not 4-byte aligned",
                            arrays[i].base_name);
        }
        if (arrays[i].stride % sizeof(float) != 0) {
            return sr__fail(ctx, SR_INVALID_ARG, "sr_draw_desc.%s %zu is not a multiple of 4",
                            arrays[i].stride_name, arrays[i].stride);
        }
    }
    size_t index_size = d->index_type == SR_INDEX_U32 ? 4 : d->index_type == SR_INDEX_U16 ? 2 : 1;
    if (d->indices && (uintptr_t)d->indices % index_size != 0) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_draw_desc.indices is not %zu-byte aligned",
                        index_size);
    }
    return SR_OK;
}

sr_result sr__draw_validate(sr_context *ctx, const sr_framebuffer *fb, const sr_state *st,
                           const sr_draw_desc *d)
{
    if (!fb) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_draw: fb is NULL");
    }
    return sr__draw_validate_state(ctx, st, d);
}

sr_result sr__draw_validate_state(sr_context *ctx, const sr_state *st, const sr_draw_desc *d)
{
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
    sr_result aligned = check_alignment(ctx, d);
    if (aligned != SR_OK) {
        return aligned;
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
    if ((unsigned)st->depth_test > SR_OFF || (unsigned)st->depth_write > SR_OFF ||
        (unsigned)st->material.vertex_color > SR_OFF) {
        const char *field = (unsigned)st->depth_test > SR_OFF    ? "depth_test"
                            : (unsigned)st->depth_write > SR_OFF ? "depth_write"
                                                                 : "material.vertex_color";
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.%s is not an sr_switch", field);
    }
    if ((unsigned)st->color_mask > SR_COLOR_MASK_NONE ||
        (st->color_mask & SR_COLOR_MASK_NONE && st->color_mask != SR_COLOR_MASK_NONE)) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_state.color_mask 0x%x is not a set of SR_COLOR_MASK_R/G/B/A bits "
                        "or SR_COLOR_MASK_NONE", (unsigned)st->color_mask);
    }
    if ((unsigned)st->depth_func > SR_ALWAYS) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.depth_func %d is not a depth function",
                        (int)st->depth_func);
    }
    if ((unsigned)st->rasterizer > SR_RASTER_BARYCENTRIC) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.rasterizer %d is not a rasterizer",
                        (int)st->rasterizer);
    }
    if ((unsigned)st->clipper > SR_CLIPPER_VIEW_VOLUME) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.clipper %d is not a clipper", (int)st->clipper);
    }
    if (st->clipper == SR_CLIPPER_VIEW_VOLUME) {
        /* A program's vertex shader writes clip space only: there is no
         * view space to clip in. */
        if (st->program) {
            return sr__fail(ctx, SR_INVALID_ARG,
                            "sr_state.clipper SR_CLIPPER_VIEW_VOLUME needs the built-in shading "
                            "models' view space; a program writes clip space only");
        }
        double p[16], inv[16];
        if (!sr__view_volume_matrices(d->projection, p, inv)) {
            return sr__fail(ctx, SR_INVALID_ARG,
                            "sr_state.clipper SR_CLIPPER_VIEW_VOLUME needs an invertible "
                            "sr_draw_desc.projection");
        }
    }
    if ((unsigned)st->visibility > SR_VISIBILITY_PAINTER) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.visibility %d is not a visibility method",
                        (int)st->visibility);
    }
    if (st->visibility == SR_VISIBILITY_PAINTER) {
        /* The sort reads eye-space depth, which only the built-in
         * shading models have, and sorts whole triangles of a list. */
        if (st->program) {
            return sr__fail(ctx, SR_INVALID_ARG,
                            "sr_state.visibility SR_VISIBILITY_PAINTER needs the built-in shading "
                            "models' eye space; a program writes clip space only");
        }
        if (d->primitive != SR_PRIM_DEFAULT && d->primitive != SR_PRIM_TRIANGLES) {
            return sr__fail(ctx, SR_INVALID_ARG,
                            "sr_state.visibility SR_VISIBILITY_PAINTER sorts triangle lists only "
                            "(sr_draw_desc.primitive %d)", (int)d->primitive);
        }
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
    /* Out-of-range values are clamped to [0, 1] when the state is resolved,
     * as glDepthRange does; NaN has no place in that range to go to. */
    if (isnan(st->depth_near) || isnan(st->depth_far)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.depth_near/depth_far must not be NaN");
    }
    if ((unsigned)st->depth_range > SR_DEPTH_RANGE_SET) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_state.depth_range %d is not a depth range mode",
                        (int)st->depth_range);
    }
    /* A range given without SR_DEPTH_RANGE_SET would be silently ignored. */
    if (st->depth_range == SR_DEPTH_RANGE_DEFAULT &&
        (st->depth_near != 0.0f || st->depth_far != 0.0f)) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_state.depth_near/depth_far are set but sr_state.depth_range is "
                        "SR_DEPTH_RANGE_DEFAULT ([0, 1]): set it to SR_DEPTH_RANGE_SET");
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
        if ((unsigned)l->type > SR_LIGHT_SPOT) {
            return sr__fail(ctx, SR_INVALID_ARG, "sr_state.lights[%d].type %d is not a light type",
                            i, (int)l->type);
        }
        /* The classic models have no falloff to window nor cone to
         * shape: drawing such a light as a plain point would mislead. */
        if (!st->program && l->type != SR_LIGHT_OFF &&
            (l->type == SR_LIGHT_SPOT || l->range != 0.0f)) {
            return sr__fail(ctx, SR_INVALID_ARG,
                            "sr_state.lights[%d]: spot lights and range are the PBR program's "
                            "(sr_pbr_desc), not the classic shading's", i);
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
