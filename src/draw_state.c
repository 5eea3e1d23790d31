/* draw_state.c - sr_state, the matrices and the framebuffer resolved into
 * the sr_draw_state every stage reads: the viewport matrix S, depth range
 * and format, culling, the shading model and its varyings, the lights in
 * eye space, and the vector kernels this CPU runs.  Application thread. */
#include "context.h"
#include "fragment/depth.h"
#include "pipeline.h"
#include "raster/triangle_simd.h"

#include <math.h>
#include <string.h>

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
    ds->use_vertex_color = m->vertex_color != SR_OFF;

    sr_mat4 e = view ? *view : sr_mat4_identity();
    for (int i = 0; i < SR_MAX_LIGHTS; i++) {
        const sr_light *l = &st->lights[i];
        if (l->type == SR_LIGHT_OFF) {
            continue;
        }
        sr_light_eye *le = &ds->lights[ds->light_count++];
        le->point = l->type == SR_LIGHT_POINT || l->type == SR_LIGHT_SPOT;
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

/* The one function that rasterizes the draw's triangles, as llvmpipe's
 * setup picks lp_rast_tri_tab[...] once per command: the per-sample path
 * (its vector kernel, the program's quads or the generic loop), else the
 * chosen rasterizer, the half-space one as its vector kernel or its
 * scalar instance for the state. */
static sr_raster_fn triangle_raster(const sr_draw_state *ds)
{
    if (ds->per_sample) {
        sr_raster_fn fast = sr__raster_msaa_select(ds);
        return fast ? fast : ds->program ? sr__raster_shader : sr__raster_msaa;
    }
    switch (ds->rasterizer) {
    case SR_RASTER_SCANLINE:    return sr__raster_scanline;
    case SR_RASTER_BARYCENTRIC: return sr__raster_barycentric;
    default: {
        sr_raster_fn fast = sr__raster_simd_select(ds);
        return fast ? fast : sr__raster_halfspace_select(ds);
    }
    }
}

void sr__resolve_draw_state(const sr_framebuffer *fb, const sr_state *st, const sr_mat4 *view,
                            const sr_mat4 *proj, sr_simd_level simd, sr_draw_state *ds)
{
    memset(ds, 0, sizeof *ds);
    ds->fb = (sr_framebuffer *)fb;

    sr_viewport vp = st->viewport;
    if (vp.width == 0) {
        vp = (sr_viewport){ 0, 0, fb->width, fb->height };
    }
    bool given = st->depth_range == SR_DEPTH_RANGE_SET;
    double dn = given ? st->depth_near : 0.0, df = given ? st->depth_far : 1.0;
    /* glDepthRange clamps both ends to [0, 1]; near > far stays allowed and
     * inverts depth. */
    dn = fmin(fmax(dn, 0.0), 1.0);
    df = fmin(fmax(df, 0.0), 1.0);
    ds->zero_to_one = st->depth_zero_to_one;
    /* The viewport matrix S, onto pixel edges (docs/raster-rules.md §1.3). */
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
    /* A band framebuffer (sr_render_bands) trims it to the rows it holds. */
    ds->rect_y0 = fb->row0 > ds->rect_y0 ? fb->row0 : ds->rect_y0;
    ds->rect_y1 = fb->row1 < ds->rect_y1 ? fb->row1 : ds->rect_y1;
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
    unsigned cm = st->color_mask == SR_COLOR_MASK_DEFAULT ? SR_COLOR_MASK_RGBA
                  : st->color_mask & SR_COLOR_MASK_RGBA;
    for (int c = 0; c < 4; c++) {
        ds->write_mask[c] = cm & (1u << c) ? 0xff : 0;
    }
    ds->blending = ds->blend.enabled || cm != SR_COLOR_MASK_RGBA;

    ds->cull = st->cull == SR_CULL_DEFAULT ? SR_CULL_NONE : st->cull;
    ds->front_ccw = st->front_face != SR_FRONT_CW;
    ds->rasterizer = st->rasterizer == SR_RASTER_DEFAULT ? SR_RASTER_HALFSPACE : st->rasterizer;
    ds->view_volume = st->clipper == SR_CLIPPER_VIEW_VOLUME;
    if (ds->view_volume) {
        sr__view_volume_matrices(proj, ds->proj, ds->proj_inv); /* validated invertible */
    }
    ds->depth_test = st->depth_test != SR_OFF && fb->depth != NULL;
    ds->depth_write = st->depth_write != SR_OFF && fb->depth != NULL;
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

    /* Multisampling and stencil take the per-sample path (raster/msaa.c). */
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
    ds->simd = simd;
    ds->light_lanes = simd != SR_SIMD_OFF;
    ds->vertex_lanes16 = simd == SR_SIMD_AVX512;
    ds->wide_stores = simd == SR_SIMD_AVX512;
    ds->triangles16 = simd == SR_SIMD_AVX512 && !ds->per_sample && ds->ninterp == 4 &&
                      ds->flat_mask == 0 && ds->shading != SR_SHADING_FLAT &&
                      ds->mode_front == SR_POLYGON_FILL && ds->mode_back == SR_POLYGON_FILL &&
                      ds->samples == 1 && !ds->offset_on;
    ds->index_avx2 = simd >= SR_SIMD_AVX2;
    ds->raster_tri = triangle_raster(ds);
}
