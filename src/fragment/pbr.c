/* pbr.c - glTF's metallic-roughness material as a program (fragment
 * stage): the vertex shader moves positions, normals and tangents to world
 * space, the fragment shader lights a 2x2 quad with Appendix B of the glTF
 * specification and writes tone-mapped, sRGB-encoded colors.
 *
 * The uniforms are resolved once (sr_make_pbr_program) and read-only
 * after, so every tile worker shades with them at once.  Per-fragment math
 * runs as loops over the quad's four lanes, one array per quantity, so the
 * compiler turns each loop into vector instructions; texture fetches and
 * the tone curve stay per lane. */
#include "context.h"
#include "fragment/environment.h"
#include "fragment/light_lanes.h"
#include "fragment/pbr_lanes.h"
#include "fragment/pbr_layers.h"
#include "fragment/pbr_transmission.h"
#include "fragment/texture.h"
#include "fragment/tonemap.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

#define MAX_EXPOSURE  64.0f

/* An octahedral map (Engelhardt and Dachsbacher; Cigolle et al. 2014):
 * directions onto the unit square through the octahedron |x|+|y|+|z| = 1,
 * the lower half folded over the upper; no trigonometry either way. */
#define OCT_SIZE 64
#define OCT_BYTES ((size_t)OCT_SIZE * OCT_SIZE * 4 * sizeof(float))   /* RGBA floats */
#define OCT_MIN_ROUGHNESS 0.35f   /* below it the map's texels blur the lobe */

static void oct_decode(float u, float v, float d[3])
{
    float px = 2.0f * u - 1.0f, py = 2.0f * v - 1.0f;
    float y = 1.0f - fabsf(px) - fabsf(py);
    if (y < 0.0f) {
        float ax = fabsf(px), ay = fabsf(py);
        px = (1.0f - ay) * (px >= 0.0f ? 1.0f : -1.0f);
        py = (1.0f - ax) * (py >= 0.0f ? 1.0f : -1.0f);
    }
    d[0] = px;
    d[1] = y;
    d[2] = py;
}

static inline v4f vabs(v4f x)
{
    return (v4f)((v4i)x & 0x7fffffff);
}

/* +1 where x >= 0, else -1. */
static inline v4f vsign(v4f x)
{
    return sr__v4_sel(x >= 0.0f, (v4f){ 1, 1, 1, 1 }, (v4f){ -1, -1, -1, -1 });
}

/* Four directions d (any length > 0) looked up bilinearly on an n x n
 * octahedral map of RGBA texels, clamped to its edge texels: the mapping
 * and the weights in vectors, one 4-float load per texel and lane. */
static inline __attribute__((always_inline)) void
oct_lookup4(const float *map, int n, const v4f d[3], v4f out[3])
{
    v4f l1 = vabs(d[0]) + vabs(d[1]) + vabs(d[2]);
    v4f s = 1.0f / vmax(l1, 1e-30f - (v4f){ 0 });
    v4f px = d[0] * s, pz = d[2] * s;               /* +y is up: fold along y */
    v4i lower = d[1] < 0.0f;
    v4f fx_ = (1.0f - vabs(pz)) * vsign(d[0]), fz_ = (1.0f - vabs(px)) * vsign(d[2]);
    px = sr__v4_sel(lower, fx_, px);
    pz = sr__v4_sel(lower, fz_, pz);
    v4f top = (v4f){ 0 } + (float)(n - 1);
    v4f fx = vmin(vmax((px * 0.5f + 0.5f) * (float)n - 0.5f, (v4f){ 0 }), top);
    v4f fy = vmin(vmax((pz * 0.5f + 0.5f) * (float)n - 0.5f, (v4f){ 0 }), top);
    v4i x0 = __builtin_convertvector(fx, v4i), y0 = __builtin_convertvector(fy, v4i);
    v4f ax = fx - __builtin_convertvector(x0, v4f), ay = fy - __builtin_convertvector(y0, v4f);
    for (int i = 0; i < 4; i++) {
        int x1 = x0[i] + 1 < n ? x0[i] + 1 : x0[i], y1 = y0[i] + 1 < n ? y0[i] + 1 : y0[i];
        v4f t00 = load(&map[4 * (y0[i] * n + x0[i])]), t10 = load(&map[4 * (y0[i] * n + x1)]);
        v4f t01 = load(&map[4 * (y1 * n + x0[i])]), t11 = load(&map[4 * (y1 * n + x1)]);
        v4f upper = t00 + (t10 - t00) * ax[i], lower_row = t01 + (t11 - t01) * ax[i];
        v4f c = upper + (lower_row - upper) * ay[i];
        out[0][i] = c[0];
        out[1][i] = c[1];
        out[2][i] = c[2];
    }
}

/* An n x n octahedral map of RGBA texels: the environment's prefiltered
 * radiance at one roughness. */
static float *oct_build(sr_context *ctx, const sr_environment *env, int n, float roughness)
{
    float *map = sr__alloc(ctx, (size_t)n * (size_t)n * 4 * sizeof(float));
    if (!map) {
        return NULL;
    }
    for (int y = 0; y < n; y++) {
        for (int x = 0; x < n; x++) {
            float d[3], *t = &map[4 * (y * n + x)];
            oct_decode(((float)x + 0.5f) / (float)n, ((float)y + 0.5f) / (float)n, d);
            sr_environment_specular(env, d, roughness, t);
            t[3] = 0.0f;
        }
    }
    return map;
}

/* oct_build's map of env at `roughness`, shared through the context's
 * cache (owned false: the context frees it), else the program's own. */
static float *oct_shared(sr_context *ctx, const sr_environment *env, float roughness,
                         bool *owned)
{
    uint32_t bits;
    memcpy(&bits, &roughness, sizeof bits);
    float *map = sr__oct_cache_get(ctx, env->serial, bits);
    *owned = false;
    if (!map) {
        map = oct_build(ctx, env, OCT_SIZE, roughness);
        *owned = !map || !sr__oct_cache_put(ctx, env->serial, bits, map, OCT_BYTES);
    }
    return map;
}

/* The irradiance polynomial's terms: 1, y, z, x, xy, yz, z^2, xz, x^2 - y^2. */
#define IRR_TERMS 9

/* sr__irradiance_eval's sum of SH basis functions times coefficients, with
 * each basis function's constant folded into its coefficient: the same
 * function, fewer operations per fragment. */
static void irr_poly(const float sh[9][3], float q[3][IRR_TERMS])
{
    for (int c = 0; c < 3; c++) {
        q[c][0] = 0.282095f * sh[0][c] - 0.315392f * sh[6][c];
        q[c][1] = 0.488603f * sh[1][c];
        q[c][2] = 0.488603f * sh[2][c];
        q[c][3] = 0.488603f * sh[3][c];
        q[c][4] = 1.092548f * sh[4][c];
        q[c][5] = 1.092548f * sh[5][c];
        q[c][6] = 3.0f * 0.315392f * sh[6][c];
        q[c][7] = 1.092548f * sh[7][c];
        q[c][8] = 0.546274f * sh[8][c];
    }
}

enum {
    SLOT_BASE, SLOT_MR, SLOT_NORMAL, SLOT_OCCLUSION, SLOT_EMISSIVE,
    /* the extensions' (pbr_layers.h) */
    SLOT_SPECULAR, SLOT_SPECULAR_COLOR, SLOT_CLEARCOAT, SLOT_CLEARCOAT_ROUGHNESS,
    SLOT_CLEARCOAT_NORMAL, SLOT_SHEEN_COLOR, SLOT_SHEEN_ROUGHNESS,
    /* transmission (R) and the volume's thickness (G) (pbr_transmission.h) */
    SLOT_TRANSMISSION, SLOT_THICKNESS,
    /* the base lobe's anisotropy and thin film (pbr_layers.h) */
    SLOT_ANISOTROPY, SLOT_IRIDESCENCE, SLOT_IRIDESCENCE_THICKNESS,
    /* diffuse transmission's share (A) and color (pbr_layers.h) */
    SLOT_DIFFUSE_TRANSMISSION, SLOT_DIFFUSE_TRANSMISSION_COLOR,
    /* KHR_materials_pbrSpecularGlossiness: RGB F0, A glossiness */
    SLOT_SPEC_GLOSS,
    SLOT_COUNT
};

/* Where each slot lives in sr_pbr_material, and its name for messages:
 * one table for every loop over the slots. */
static const struct {
    size_t offset;
    const char *name;
} slot_fields[SLOT_COUNT] = {
#define SLOT_FIELD(f) { offsetof(sr_pbr_material, f), #f }
    SLOT_FIELD(base_color_texture), SLOT_FIELD(metallic_roughness_texture),
    SLOT_FIELD(normal_texture), SLOT_FIELD(occlusion_texture), SLOT_FIELD(emissive_texture),
    SLOT_FIELD(specular_texture), SLOT_FIELD(specular_color_texture),
    SLOT_FIELD(clearcoat_texture), SLOT_FIELD(clearcoat_roughness_texture),
    SLOT_FIELD(clearcoat_normal_texture), SLOT_FIELD(sheen_color_texture),
    SLOT_FIELD(sheen_roughness_texture), SLOT_FIELD(transmission_texture),
    SLOT_FIELD(thickness_texture), SLOT_FIELD(anisotropy_texture),
    SLOT_FIELD(iridescence_texture), SLOT_FIELD(iridescence_thickness_texture),
    SLOT_FIELD(diffuse_transmission_texture), SLOT_FIELD(diffuse_transmission_color_texture),
    SLOT_FIELD(specular_glossiness_texture),
#undef SLOT_FIELD
};

static const sr_texture_slot *material_slot(const sr_pbr_material *m, int i)
{
    return (const sr_texture_slot *)((const char *)m + slot_fields[i].offset);
}

/* The diffuse lobe's weight without transmission. */
static const float opaque[4] = { 1, 1, 1, 1 };

/* Varyings 0..2 world position, 3..5 world normal; the rest as needed. */
enum { VARY_POS = 0, VARY_NORMAL = 3, VARY_FIXED = 6 };

typedef struct pbr_slot {
    const sr_texture *tex;        /* NULL: empty */
    sr_texture_filter filter;
    sr_texture_wrap wu, wv;
    int vary;                     /* varying index of its texcoords */
    /* KHR_texture_transform in sr_texture's frame (v up):
     * u' = xf[0] s + xf[1] t + xf[2], v' = xf[3] s + xf[4] t + xf[5]. */
    float xf[6];
} pbr_slot;

struct sr_pbr {
    sr_program program;
    sr_pbr_material m;
    pbr_slot slot[SLOT_COUNT];
    sr_mat4 model, view_projection;
    float normal_matrix[9];       /* row-major 3x3: inverse transpose of the model's */
    float handedness;             /* -1 when the model mirrors: the tangents' w turns */
    float eye[3];                 /* the camera's world position */
    int nlights;
    float light_vec[SR_MAX_LIGHTS][3];  /* directional: unit vector to the light; point, spot: position */
    float light_rad[SR_MAX_LIGHTS][3];
    bool light_point[SR_MAX_LIGHTS];    /* point or spot: falls off with distance */
    bool light_spot[SR_MAX_LIGHTS];
    float light_axis[SR_MAX_LIGHTS][3]; /* spot: unit vector the light points along */
    /* spot: t = cos(angle to the axis) * scale + offset, clamped to [0, 1] */
    float light_cone_scale[SR_MAX_LIGHTS], light_cone_offset[SR_MAX_LIGHTS];
    float light_inv_range2[SR_MAX_LIGHTS];  /* point, spot: 1 / range^2; 0: no range */
    bool ambient;
    float sky[3], ground[3];
    const sr_environment *environment;  /* replaces the hemisphere when set */
    /* The environment's prefiltered radiance at the material's one
     * roughness on an octahedral map (OCT_SIZE^2 RGB), or NULL: queried
     * per fragment instead. */
    float *oct;
    bool oct_owned, oct_coat_owned;   /* else the context's cache holds them */
    /* Its irradiance (E / pi) as the quadratic polynomial in the image
     * frame's (x, y, z) that its 9 SH coefficients are (irr_poly), and the
     * world -> image rotation about +Y. */
    float irr[3][IRR_TERMS];
    float env_cos, env_sin;
    /* The extensions (pbr_layers.h), resolved: whether any runs, the
     * dielectric's F0 from the ior times the specular color (unclamped)
     * and its F90 (the specular factor), the coat and the sheen, and the
     * coat's prefiltered radiance like `oct`, at its roughness. */
    bool layers, coat, sheen;
    float f0_color[3], f90;
    /* KHR_materials_pbrSpecularGlossiness: f0_color is its specular
     * color, metallic 0, roughness 1 - glossiness (pbr_fs). */
    bool sg;
    /* The base lobe's anisotropy (its direction as cos and sin of the
     * rotation) and thin film (its index), when on. */
    bool aniso, irid;
    float an_cos, an_sin;
    /* Diffuse transmission, when on, and the volume's absorption of the
     * light it lets through: -log2(attenuation color) / distance times
     * the model's mean axis length (thickness to world), 0 without. */
    bool dtrans;
    float dt_absorb[3];
    float dt_axis;                /* the model's mean axis length: thickness to world */
    float *oct_coat;
    const sr_shadow_map *shadow;        /* darkens lights[0] when set */
    float scale;                  /* 2^exposure */
    sr_tonemap_op tonemap;
    const srgb_table *srgb;
    int vary_uv[2], vary_color, vary_tangent;   /* -1: absent */
    size_t vertex_count;
    const uint8_t *tangents, *texcoords1;
    size_t tangent_stride, texcoord1_stride;
    /* KHR_materials_transmission and _volume (pbr_transmission.c). */
    bool transmits;               /* a lit material with a transmission factor */
    sr__transmission tr;
};

sr_pbr_material sr_pbr_default_material(void)
{
    sr_pbr_material m = {
        .base_color = { 1, 1, 1, 1 },
        .metallic = 1.0f,
        .roughness = 1.0f,
        .normal_scale = 1.0f,
        .occlusion_strength = 1.0f,
        .emissive_strength = 1.0f,
        .alpha_cutoff = 0.5f,
        .attenuation_color = { 1, 1, 1 },
        .diffuse_transmission_color = { 1, 1, 1 },
    };
    for (int i = 0; i < SLOT_COUNT; i++) {
        sr_texture_slot *s = (sr_texture_slot *)((char *)&m + slot_fields[i].offset);
        s->scale[0] = s->scale[1] = 1.0f;
    }
    return m;
}

/* ---- vertex shader ------------------------------------------------------ */

static void pbr_vs(const void *uniforms, const sr_vertex_input *in, float clip[4], float *vary)
{
    const sr_pbr *p = uniforms;
    const float *m = p->model.m;
    const float *pos = in->position;
    float w[4];
    for (int r = 0; r < 4; r++) {
        w[r] = m[r] * pos[0] + m[4 + r] * pos[1] + m[8 + r] * pos[2] + m[12 + r] * pos[3];
    }
    const float *vp = p->view_projection.m;
    for (int r = 0; r < 4; r++) {
        clip[r] = vp[r] * w[0] + vp[4 + r] * w[1] + vp[8 + r] * w[2] + vp[12 + r] * w[3];
    }
    float iw = w[3] != 0.0f ? 1.0f / w[3] : 1.0f;
    const float *nm = p->normal_matrix;
    for (int r = 0; r < 3; r++) {
        vary[VARY_POS + r] = w[r] * iw;
        vary[VARY_NORMAL + r] =
            nm[3 * r] * in->normal[0] + nm[3 * r + 1] * in->normal[1] +
            nm[3 * r + 2] * in->normal[2];
    }
    bool inside = in->index < p->vertex_count;
    if (p->vary_uv[0] >= 0) {
        vary[p->vary_uv[0]] = in->texcoord[0];
        vary[p->vary_uv[0] + 1] = in->texcoord[1];
    }
    if (p->vary_uv[1] >= 0) {
        const float *t = (const float *)(p->texcoords1 + in->index * p->texcoord1_stride);
        vary[p->vary_uv[1]] = inside ? t[0] : 0.0f;
        vary[p->vary_uv[1] + 1] = inside ? t[1] : 0.0f;
    }
    if (p->vary_color >= 0) {
        /* A draw without colors multiplies by white. */
        for (int c = 0; c < 4; c++) {
            vary[p->vary_color + c] = in->has_color ? in->color[c] : 1.0f;
        }
    }
    if (p->vary_tangent >= 0) {
        float t[4] = { 0, 0, 0, 1 };
        if (inside) {
            memcpy(t, p->tangents + in->index * p->tangent_stride, sizeof t);
        }
        /* Tangents lie in the surface: they move with the model matrix. */
        for (int r = 0; r < 3; r++) {
            vary[p->vary_tangent + r] = m[r] * t[0] + m[4 + r] * t[1] + m[8 + r] * t[2];
        }
        vary[p->vary_tangent + 3] = t[3] < 0.0f ? -p->handedness : p->handedness;
    }
}

/* ---- fragment shader ---------------------------------------------------- */

/* The slot's texels at the quad's fragments, [channel][lane]; the level of
 * detail from the transformed coordinates' lane differences.  Texels come
 * as sr_texture decodes them: linear light for sRGB textures. */
static void sample_slot(const pbr_slot *s, const sr_fragment_quad *q, float out[4][4],
                        float uv[2][4])
{
    const float *su = q->varyings[s->vary], *sv = q->varyings[s->vary + 1];
    for (int i = 0; i < 4; i++) {
        uv[0][i] = s->xf[0] * su[i] + s->xf[1] * sv[i] + s->xf[2];
        uv[1][i] = s->xf[3] * su[i] + s->xf[4] * sv[i] + s->xf[5];
    }
    float lod = 0.0f;
    if (s->filter == SR_FILTER_TRILINEAR) {
        lod = sr__texture_lod(s->tex, uv[0][1] - uv[0][0], uv[1][1] - uv[1][0],
                              uv[0][2] - uv[0][0], uv[1][2] - uv[1][0]);
    }
    for (int i = 0; i < 4; i++) {
        float t[4] = { 0, 0, 0, 1 };
        if (q->mask >> i & 1) {
            sr__texture_sample_linear(s->tex, s->filter, s->wu, s->wv, uv[0][i], uv[1][i], lod,
                                      t);
        }
        for (int c = 0; c < 4; c++) {
            out[c][i] = t[c];
        }
    }
}

static inline __attribute__((always_inline)) void normalize4(float a[3][4])
{
    v4f v[3];
    load3(v, a);
    v4f l2 = dot3(v, v);
    v4f s = sr__v4_sel(l2 > 0.0f, rsqrt_nr(l2), (v4f){ 0 });
    for (int k = 0; k < 3; k++) {
        store(a[k], v[k] * s);
    }
}

/* The normal map's tangent frame at each lane, T and B (the normal N is
 * already the shading side's).  From the tangent varying when the draw
 * has tangents, else from the screen-space derivatives of position and
 * the map's coordinates (the surface gradients of u and v). */
static inline __attribute__((always_inline)) void
tangent_frame(const sr_pbr *p, const sr_fragment_quad *q, float n[3][4], float uv[2][4],
              float t[3][4], float b[3][4])
{
    if (p->vary_tangent >= 0) {
        const float (*tv)[4] = &q->varyings[p->vary_tangent];
        float flip = q->front ? 1.0f : -1.0f;
        for (int i = 0; i < 4; i++) {
            /* N is flipped on back faces; T and B flip with it. */
            float tn = (tv[0][i] * n[0][i] + tv[1][i] * n[1][i] + tv[2][i] * n[2][i]) * flip;
            for (int k = 0; k < 3; k++) {
                t[k][i] = (tv[k][i] - n[k][i] * flip * tn) * flip;
            }
        }
        normalize4(t);
        for (int i = 0; i < 4; i++) {
            float w = tv[3][i] < 0.0f ? -1.0f : 1.0f;
            b[0][i] = (n[1][i] * t[2][i] - n[2][i] * t[1][i]) * w;
            b[1][i] = (n[2][i] * t[0][i] - n[0][i] * t[2][i]) * w;
            b[2][i] = (n[0][i] * t[1][i] - n[1][i] * t[0][i]) * w;
        }
        return;
    }
    float dp1[3], dp2[3];
    for (int k = 0; k < 3; k++) {
        dp1[k] = q->varyings[VARY_POS + k][1] - q->varyings[VARY_POS + k][0];
        dp2[k] = q->varyings[VARY_POS + k][2] - q->varyings[VARY_POS + k][0];
    }
    float du1 = uv[0][1] - uv[0][0], dv1 = uv[1][1] - uv[1][0];
    float du2 = uv[0][2] - uv[0][0], dv2 = uv[1][2] - uv[1][0];
    for (int i = 0; i < 4; i++) {
        float nx = n[0][i], ny = n[1][i], nz = n[2][i];
        /* dp2 x N and N x dp1: with screen y down, dp1 x dp2 points away
         * from the viewer, so the sums are minus the gradients. */
        float a[3] = { dp2[1] * nz - dp2[2] * ny, dp2[2] * nx - dp2[0] * nz,
                       dp2[0] * ny - dp2[1] * nx };
        float c[3] = { ny * dp1[2] - nz * dp1[1], nz * dp1[0] - nx * dp1[2],
                       nx * dp1[1] - ny * dp1[0] };
        float tt = 0.0f, bb = 0.0f;
        for (int k = 0; k < 3; k++) {
            t[k][i] = -(a[k] * du1 + c[k] * du2);
            b[k][i] = -(a[k] * dv1 + c[k] * dv2);
            tt += t[k][i] * t[k][i];
            bb += b[k][i] * b[k][i];
        }
        float m = max_f(tt, bb);
        float s = m > 0.0f ? 1.0f / sqrtf(m) : 0.0f;
        for (int k = 0; k < 3; k++) {
            t[k][i] *= s;
            b[k][i] *= s;
        }
    }
}

/* Radiance of the hemisphere light in direction d (world, unit). */
static void hemisphere(const sr_pbr *p, const v4f d[3], v4f out[3])
{
    v4f s = 0.5f + 0.5f * d[1];
    for (int c = 0; c < 3; c++) {
        out[c] = p->ground[c] + (p->sky[c] - p->ground[c]) * s;
    }
}

/* The environment's irradiance (E / pi) along unit normals d (world):
 * its SH polynomial at d turned into the image's frame, negative values
 * (a high-contrast image's truncated series) clamped to zero. */
static inline __attribute__((always_inline)) void
irradiance4(const sr_pbr *p, const v4f d[3], v4f out[3])
{
    v4f x = d[0] * p->env_cos - d[2] * p->env_sin, y = d[1];
    v4f z = d[0] * p->env_sin + d[2] * p->env_cos;
    v4f term[IRR_TERMS - 1] = { y, z, x, x * y, y * z, z * z, x * z, x * x - y * y };
    for (int c = 0; c < 3; c++) {
        const float *q = p->irr[c];
        v4f e = q[0] + q[1] * term[0];
        for (int k = 2; k < IRR_TERMS; k++) {
            e += q[k] * term[k - 1];
        }
        out[c] = vmax(e, (v4f){ 0 });
    }
}

/* The environment's prefiltered radiance along rr at roughness rough
 * (0..1): from the program's octahedral table when there is one (made
 * at that one roughness), else queried per fragment. */
static inline __attribute__((always_inline)) void env_radiance(const sr_pbr *p,
                                                               const float *table,
                                                               const v4f rr[3], v4f rough,
                                                               v4f er[3])
{
    if (table) {
        oct_lookup4(table, OCT_SIZE, rr, er);
        return;
    }
    sr_vec3x4 dr, e_r;
    float rl[4];
    store(dr.x, rr[0]);
    store(dr.y, rr[1]);
    store(dr.z, rr[2]);
    store(rl, rough);
    sr_environment_specular4(p->environment, &dr, rl, &e_r);
    er[0] = load(e_r.x), er[1] = load(e_r.y), er[2] = load(e_r.z);
}

/* The coat's image-based or hemisphere light: the prefiltered radiance
 * along the coat normal's reflection at the coat's roughness, from the
 * program's table where there is one, else queried. */
static void coat_ambient(const sr_pbr *p, sr__pbr_layers *x, const v4f v[3], v4f ao)
{
    v4f rr[3], er[3];
    for (int k = 0; k < 3; k++) {
        rr[k] = 2.0f * x->cc_nvr * x->cc_n[k] - v[k];
    }
    if (!p->environment) {
        hemisphere(p, rr, er);
    } else {
        env_radiance(p, p->oct_coat, rr, x->cc_rc, er);
    }
    sr__coat_ambient(x, er, ao);
}

/* Point or spot light l seen from pos: ld, its position on entry, becomes
 * the unit vector to it; returns what reaches pos of its intensity
 * (KHR_lights_punctual: over the squared distance, the range's window and
 * the spot's cone). */
static inline __attribute__((always_inline)) v4f point_falloff(const sr_pbr *p, int l,
                                                               const v4f pos[3], v4f ld[3])
{
    for (int c = 0; c < 3; c++) {
        ld[c] -= pos[c];
    }
    v4f d2 = dot3(ld, ld);
    v4f fall = sr__v4_sel(d2 > 0.0f, 1.0f / d2, (v4f){ 0 });
    v4f il = sr__v4_sqrt(fall);
    for (int c = 0; c < 3; c++) {
        ld[c] *= il;
    }
    if (p->light_inv_range2[l] > 0.0f) {
        /* The extension's window, 1 at the light and 0 from the
         * range on: clamp(1 - (d / range)^4, 0, 1)^2. */
        v4f q = d2 * p->light_inv_range2[l];
        v4f w = vclamp(1.0f - q * q, 0.0f, 1.0f);
        fall *= w * w;
    }
    if (p->light_spot[l]) {
        /* The cone by the cosine of the angle between the axis
         * and the way from the light to the point (-L). */
        v4f cd = -(ld[0] * p->light_axis[l][0] + ld[1] * p->light_axis[l][1] +
                   ld[2] * p->light_axis[l][2]);
        v4f t = vclamp(cd * p->light_cone_scale[l] + p->light_cone_offset[l], 0.0f, 1.0f);
        fall *= t * t;
    }
    return fall;
}

/* Appendix B at four lanes: the punctual lights through the
 * Cook-Torrance specular (GGX D, height-correlated Smith visibility,
 * Schlick F) and Lambert diffuse weighted by 1 - F, plus the hemisphere's
 * ambient light times the occlusion.  Radiance out, linear, unexposed.
 * diffuse_ scales the diffuse lobe (1 but where transmission takes its
 * share) and seen_, when not NULL, is the transmitted light, part of the
 * base under the layers.  x, when not NULL, carries the extensions
 * (pbr_layers.h): the dielectric's F0 and F90, and the coat and sheen
 * lobes lit by the same lights and ambient.  Inlined at two calls, one
 * with ext NULL, so that a material without the extensions runs the code
 * it ran before them. */
static inline __attribute__((always_inline)) void
shade_lanes(const sr_pbr *p, const float pos_[3][4], const float n_[3][4], const float v_[3][4],
            const float base_[4][4], const float metal_[4], const float rough_[4],
            const float ao_[4], const float shadow_[4], const float diffuse_[4],
            const float (*seen_)[4], sr__pbr_layers *ext, float out_[3][4])
{
    v4f pos[3], n[3], v[3], base[3], cdiff[3], f0[3], out[3], f90 = { 1, 1, 1, 1 };
    load3(pos, pos_);
    load3(n, n_);
    load3(v, v_);
    load3(base, base_);
    v4f mt = vclamp(load(metal_), 0.0f, 1.0f), dw = load(diffuse_), cback[3];
    for (int c = 0; c < 3; c++) {
        cdiff[c] = base[c] * (1.0f - mt) * dw;
        if (ext && ext->dtrans) {
            /* Diffuse transmission takes its share of the dielectric's
             * diffuse lobe for a Lambert lobe lit from behind, in its own
             * color (the extension's mix of diffuse BRDF and BTDF). */
            cback[c] = ext->dt_col[c] * ext->dt * (1.0f - mt) * dw;
            cdiff[c] *= 1.0f - ext->dt;
        }
        /* Metals reflect their base color, from F90 = 1 at grazing. */
        f0[c] = ext ? ext->f0[c] + (base[c] - ext->f0[c]) * mt : 0.04f + (base[c] - 0.04f) * mt;
        out[c] = (v4f){ 0 };
    }
    if (ext) {
        f90 = ext->f90 + (1.0f - ext->f90) * mt;
    }
    v4f r = vclamp(load(rough_), MIN_ROUGHNESS, 1.0f);
    v4f a2 = r * r * r * r, one_a2 = 1.0f - a2;
    v4f nv = vmax(dot3(n, v), (v4f){ 1e-4f, 1e-4f, 1e-4f, 1e-4f });
    /* The visibility term's view half is the same for every light. */
    v4f gv2 = nv * nv * one_a2 + a2;    /* >= a2 > 0 */
    v4f gv = gv2 * rsqrt_nr(gv2);
    if (ext && ext->aniso) {
        sr__aniso_begin(ext, r * r, v, nv);
    }
    if (ext && ext->irid) {
        sr__iridescence_begin(ext, vclamp(dot3(n, v), 0.0f, 1.0f), ext->f0, base, mt);
    }
    /* The split sum at N.V: the specular lobe's single-scattering albedo
     * Ess = A + B, for the lights' energy compensation and the ambient. */
    v4f rc = vclamp(load(rough_), 0.0f, 1.0f), sa, sb;
    split_sum(rc, nv, &sa, &sb);
    /* Multiple scattering under the lights (Turquin 2019, as three.js
     * does): one GGX bounce reflects Ess of what comes in, so the lobe is
     * scaled by 1 + F0 (1 / Ess - 1), which gives a white metal back all
     * the light at every roughness, as the ambient's Fdez-Aguera term
     * does for the environment. */
    v4f ms[3], inv_ess = 1.0f / vmax(sa + sb, (v4f){ 1e-3f, 1e-3f, 1e-3f, 1e-3f }) - 1.0f;
    for (int c = 0; c < 3; c++) {
        ms[c] = 1.0f + f0[c] * inv_ess;
    }
    for (int l = 0; l < p->nlights; l++) {
        v4f ld[3], rad[3], fall = { 1, 1, 1, 1 };
        for (int c = 0; c < 3; c++) {
            ld[c] = p->light_vec[l][c] - (v4f){ 0 };
            rad[c] = p->light_rad[l][c] - (v4f){ 0 };
        }
        if (l == 0) {
            /* The shadow map belongs to the key light. */
            for (int c = 0; c < 3; c++) {
                rad[c] *= load(shadow_);
            }
        }
        if (p->light_point[l]) {
            fall = point_falloff(p, l, pos, ld);
            for (int c = 0; c < 3; c++) {
                rad[c] *= fall;
            }
        }
        /* H = (L + V) / |L + V| without forming it: |L + V|^2 = 2 + 2 L.V,
         * N.H = (N.L + N.V) / |L + V|, V.H = (1 + L.V) / |L + V|. */
        v4f zero = { 0 };
        v4f nlr = dot3(n, ld), lv = dot3(ld, v);
        v4f hl = 2.0f + 2.0f * lv;
        v4f hs = sr__v4_sel(hl > 1e-12f, rsqrt_nr(vmax(hl, 1e-12f - zero)), zero);
        v4f nl = vmax(nlr, zero);
        v4f nh = vmax((nlr + dot3(n, v)) * hs, zero);
        v4f vh = vmax((1.0f + lv) * hs, zero);
        v4f x = 1.0f - vh, x2 = x * x, fw = x2 * x2 * x;
        v4f dd = nh * nh * (a2 - 1.0f) + 1.0f;
        v4f gl2 = nl * nl * one_a2 + a2;
        v4f gl = gl2 * rsqrt_nr(gl2);
        /* D times V in one division: a2 / (pi dd^2) times 0.5 / (the
         * visibility's sum), which is positive as nv > 0 and a2 > 0. */
        v4f dv = a2 * 0.5f * rcp_nr(PI_F * dd * dd * (nl * gv + nv * gl));
        if (ext && ext->aniso) {
            dv = sr__aniso_dv(ext, ld, hs, nl, nv, nh);
        }
        for (int c = 0; c < 3; c++) {
            v4f f = f0[c] + (f90 - f0[c]) * fw;
            if (ext && ext->irid) {
                /* The film's Fresnel, at N.V, mixed in by its weight. */
                f += ext->ir_w * (ext->ir_f[c] - f);
            }
            out[c] += ((1.0f - f) * cdiff[c] * (1.0f / PI_F) + f * dv * ms[c]) * rad[c] * nl;
        }
        if (ext && ext->dtrans) {
            /* The light let through from behind: the key light's has its
             * own shadow lookup, from the far side (ext->dt_shadow). */
            v4f back[3];
            for (int c = 0; c < 3; c++) {
                back[c] = p->light_rad[l][c] - (v4f){ 0 };
                if (l == 0) {
                    back[c] *= ext->dt_shadow;
                }
                if (p->light_point[l]) {
                    back[c] *= fall;
                }
            }
            sr__diffuse_btdf_light(ext, n, v, nlr, lv, f0, f90, cback, back, out);
        }
        if (ext && ext->coat) {
            sr__coat_light(ext, ld, hs, rad);
        }
        if (ext && ext->sheen) {
            sr__sheen_light(ext, nl, nv, nh, rad);
        }
    }
    if (!p->environment && !p->ambient) {
        goto done;
    }
    v4f nd = dot3(n, v), rr[3], en[3], er[3];
    for (int k = 0; k < 3; k++) {
        rr[k] = 2.0f * nd * n[k] - v[k];
    }
    v4f ao = load(ao_);
    if (ext && ext->aniso) {
        /* The stretched lobe reflects about the bent normal. */
        v4f bn[3];
        sr__aniso_bent(ext, n, v, rc, bn);
        v4f bd = dot3(bn, v);
        for (int k = 0; k < 3; k++) {
            rr[k] = 2.0f * bd * bn[k] - v[k];
        }
    }
    v4f eb[3];
    if (p->environment) {
        /* Image-based light: irradiance (E / pi) along N and the
         * prefiltered radiance along R, from tables made with the program
         * (octahedral maps) where they can be. */
        irradiance4(p, n, en);
        env_radiance(p, p->oct, rr, rc, er);
    } else {
        /* The hemisphere along N and along R. */
        hemisphere(p, n, en);
        hemisphere(p, rr, er);
    }
    if (ext && ext->dtrans) {
        /* Diffuse transmission's lobe sees the irradiance from behind. */
        v4f nb[3] = { -n[0], -n[1], -n[2] };
        if (p->environment) {
            irradiance4(p, nb, eb);
        } else {
            hemisphere(p, nb, eb);
        }
    }
    /* Multiple scattering (Fdez-Aguera 2019, as three.js and Khronos'
     * sample viewer light with an environment): a single GGX bounce
     * reflects only Ess = A + B of the light; the rest, Ems, comes back
     * after more bounces, tinted by the average Fresnel, as irradiance.
     * The diffuse takes what neither reflects, so a white furnace stays
     * white for dielectrics and metals at every roughness. */
    v4f ems = 1.0f - (sa + sb);
    for (int c = 0; c < 3; c++) {
        v4f f0c = f0[c];
        if (ext && ext->irid) {
            f0c += ext->ir_w * (ext->ir_f0[c] - f0c);
        }
        v4f fss_ess = f0c * sa + f90 * sb;
        v4f favg = f0c + (f90 - f0c) * (1.0f / 21.0f);
        v4f fms_ems = ems * fss_ess * favg / (1.0f - ems * favg);
        v4f kd = cdiff[c] * (1.0f - (fss_ess + fms_ems));
        out[c] += (fss_ess * er[c] + (fms_ems + kd) * en[c]) * ao;
        if (ext && ext->dtrans) {
            out[c] += cback[c] * (1.0f - (fss_ess + fms_ems)) * eb[c] * ao;
        }
    }
    if (ext && ext->coat) {
        coat_ambient(p, ext, v, ao);
    }
    if (ext && ext->sheen) {
        sr__sheen_ambient(ext, en, ao);
    }
done:
    if (seen_) {
        for (int c = 0; c < 3; c++) {
            out[c] += load(seen_[c]);
        }
    }
    if (ext) {
        sr__layers_finish(ext, out);
    }
    for (int c = 0; c < 3; c++) {
        store(out_[c], out[c]);
    }
}

/* KHR_materials_anisotropy's inputs: the strength (factor times the
 * texture's B) and the direction, (cos, sin) of the rotation turning the
 * texture's RG (in -1..1; (1, 0) without one), in the tangent frame of
 * the geometric normal; B = N x T.  A lane without a direction (no
 * texture coordinates to derive a frame from) is isotropic. */
static void aniso_inputs(const sr_pbr *p, const sr_fragment_quad *q, float side,
                         sr__pbr_layers *x)
{
    float tex[4][4], uv[2][4] = { { 0 } }, g[3][4], t[3][4], b[3][4];
    float dx[4], dy[4], s[4];
    for (int k = 0; k < 3; k++) {
        for (int i = 0; i < 4; i++) {
            g[k][i] = q->varyings[VARY_NORMAL + k][i] * side;
        }
    }
    normalize4(g);
    for (int i = 0; i < 4; i++) {
        dx[i] = p->an_cos;
        dy[i] = p->an_sin;
        s[i] = p->m.anisotropy_strength;
    }
    if (p->slot[SLOT_ANISOTROPY].tex) {
        sample_slot(&p->slot[SLOT_ANISOTROPY], q, tex, uv);
        for (int i = 0; i < 4; i++) {
            float u = 2.0f * tex[0][i] - 1.0f, w = 2.0f * tex[1][i] - 1.0f;
            dx[i] = p->an_cos * u - p->an_sin * w;
            dy[i] = p->an_sin * u + p->an_cos * w;
            s[i] *= tex[2][i];
        }
    } else if (p->vary_tangent < 0) {
        memcpy(uv, &q->varyings[p->vary_uv[0]], sizeof uv);
    }
    tangent_frame(p, q, g, uv, t, b);
    float tt[3][4];
    for (int k = 0; k < 3; k++) {
        for (int i = 0; i < 4; i++) {
            tt[k][i] = t[k][i] * dx[i] + b[k][i] * dy[i];
        }
    }
    normalize4(tt);
    for (int i = 0; i < 4; i++) {
        float l2t = tt[0][i] * tt[0][i] + tt[1][i] * tt[1][i] + tt[2][i] * tt[2][i];
        if (!(l2t > 0.0f)) {
            /* Isotropic here: any T across the normal does. */
            bool ax = fabsf(g[0][i]) < 0.9f;
            float a[3] = { ax ? 1.0f : 0.0f, ax ? 0.0f : 1.0f, 0.0f };
            float c[3] = { g[1][i] * a[2] - g[2][i] * a[1], g[2][i] * a[0] - g[0][i] * a[2],
                           g[0][i] * a[1] - g[1][i] * a[0] };
            float l2c = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
            float il = l2c > 0.0f ? 1.0f / sqrtf(l2c) : 0.0f;
            for (int k = 0; k < 3; k++) {
                tt[k][i] = c[k] * il;
            }
            s[i] = 0.0f;
        }
        float bb[3] = { g[1][i] * tt[2][i] - g[2][i] * tt[1][i],
                        g[2][i] * tt[0][i] - g[0][i] * tt[2][i],
                        g[0][i] * tt[1][i] - g[1][i] * tt[0][i] };
        float l2 = bb[0] * bb[0] + bb[1] * bb[1] + bb[2] * bb[2];
        float il = l2 > 0.0f ? 1.0f / sqrtf(l2) : 0.0f;
        for (int k = 0; k < 3; k++) {
            x->an_t[k][i] = tt[k][i];
            x->an_b[k][i] = bb[k] * il;
        }
        x->an_s[i] = clamp01(s[i]);
    }
    x->aniso = true;
}

/* KHR_materials_diffuse_transmission's inputs: the share (factor times
 * the texture's A) and the color (factor times the texture's RGB), the
 * color dimmed by the volume it crosses (KHR_materials_volume's
 * Beer-Lambert over the thickness, as the sample viewer does; a thin
 * wall, thickness 0, absorbs nothing). */
static void dtrans_inputs(const sr_pbr *p, const sr_fragment_quad *q, sr__pbr_layers *x)
{
    const sr_pbr_material *m = &p->m;
    float tex[4][4], uv[2][4];
    x->dtrans = true;
    x->dt_shadow = (v4f){ 1, 1, 1, 1 };
    x->dt = (v4f){ 0 } + m->diffuse_transmission;
    for (int c = 0; c < 3; c++) {
        x->dt_col[c] = (v4f){ 0 } + m->diffuse_transmission_color[c];
    }
    if (p->slot[SLOT_DIFFUSE_TRANSMISSION].tex) {
        sample_slot(&p->slot[SLOT_DIFFUSE_TRANSMISSION], q, tex, uv);
        x->dt *= load(tex[3]);
    }
    if (p->slot[SLOT_DIFFUSE_TRANSMISSION_COLOR].tex) {
        sample_slot(&p->slot[SLOT_DIFFUSE_TRANSMISSION_COLOR], q, tex, uv);
        for (int c = 0; c < 3; c++) {
            x->dt_col[c] *= load(tex[c]);
        }
    }
    x->dt = vclamp(x->dt, 0.0f, 1.0f);
    /* The thickness both the absorption and the far side's shadow
     * lookup (shade_layered) cross. */
    x->dt_thick = (v4f){ 0 } + m->thickness;
    if (m->thickness > 0.0f && p->slot[SLOT_THICKNESS].tex &&
        (m->attenuation_distance > 0.0f || p->shadow)) {
        sample_slot(&p->slot[SLOT_THICKNESS], q, tex, uv);
        x->dt_thick *= load(tex[1]);
    }
    if (m->thickness > 0.0f && m->attenuation_distance > 0.0f) {
        for (int c = 0; c < 3; c++) {
            for (int i = 0; i < 4; i++) {
                x->dt_col[c][i] *= exp2f(-p->dt_absorb[c] * x->dt_thick[i]);
            }
        }
    }
}

/* The extensions' inputs at the quad's lanes (pbr_layers.h): factors
 * times textures, the coat's normal (the geometry's, or its own map's in
 * the same tangent frame as the base's), then each layer's per-fragment
 * terms.  n is the base's shading normal, v the view direction. */
static void layer_inputs(const sr_pbr *p, const sr_fragment_quad *q, float side,
                         const float n_[3][4], const float v_[3][4], const float (*sg_f0)[4],
                         sr__pbr_layers *x)
{
    const sr_pbr_material *m = &p->m;
    float tex[4][4], uv[2][4];
    v4f v[3], n[3];
    load3(v, v_);
    load3(n, n_);
    memset(x, 0, sizeof *x);
    /* KHR_materials_specular: F0 = min(F0(ior) color, 1) specular, F90 =
     * specular; metals are left alone (shade_lanes mixes them in). */
    v4f weight = (v4f){ 0 } + p->f90, col[3];
    for (int c = 0; c < 3; c++) {
        col[c] = (v4f){ 0 } + p->f0_color[c];
    }
    if (p->slot[SLOT_SPECULAR_COLOR].tex) {
        sample_slot(&p->slot[SLOT_SPECULAR_COLOR], q, tex, uv);
        for (int c = 0; c < 3; c++) {
            col[c] *= load(tex[c]);
        }
    }
    if (p->slot[SLOT_SPECULAR].tex) {
        sample_slot(&p->slot[SLOT_SPECULAR], q, tex, uv);
        weight *= load(tex[3]);
    }
    for (int c = 0; c < 3; c++) {
        x->f0[c] = sg_f0 ? load(sg_f0[c]) : vmin(col[c], (v4f){ 1, 1, 1, 1 }) * weight;
    }
    x->f90 = weight;
    if (p->coat) {
        x->coat = true;
        x->cc = (v4f){ 0 } + m->clearcoat;
        v4f cr = (v4f){ 0 } + m->clearcoat_roughness;
        if (p->slot[SLOT_CLEARCOAT].tex) {
            sample_slot(&p->slot[SLOT_CLEARCOAT], q, tex, uv);
            x->cc *= load(tex[0]);
        }
        if (p->slot[SLOT_CLEARCOAT_ROUGHNESS].tex) {
            sample_slot(&p->slot[SLOT_CLEARCOAT_ROUGHNESS], q, tex, uv);
            cr *= load(tex[1]);
        }
        x->cc_rc = vclamp(cr, 0.0f, 1.0f);
        v4f r = vclamp(cr, MIN_ROUGHNESS, 1.0f);
        x->cc_a2 = r * r * r * r;
        float g[3][4];
        for (int k = 0; k < 3; k++) {
            for (int i = 0; i < 4; i++) {
                g[k][i] = q->varyings[VARY_NORMAL + k][i] * side;
            }
        }
        normalize4(g);
        if (p->slot[SLOT_CLEARCOAT_NORMAL].tex) {
            float t[3][4], b[3][4], s = m->clearcoat_normal_scale;
            sample_slot(&p->slot[SLOT_CLEARCOAT_NORMAL], q, tex, uv);
            tangent_frame(p, q, g, uv, t, b);
            for (int i = 0; i < 4; i++) {
                float tx = (2.0f * tex[0][i] - 1.0f) * s, ty = (2.0f * tex[1][i] - 1.0f) * s;
                float tz = 2.0f * tex[2][i] - 1.0f;
                for (int k = 0; k < 3; k++) {
                    g[k][i] = t[k][i] * tx + b[k][i] * ty + g[k][i] * tz;
                }
            }
            normalize4(g);
        }
        load3(x->cc_n, g);
        sr__coat_begin(x, v);
    }
    if (p->sheen) {
        x->sheen = true;
        x->sheen_r = (v4f){ 0 } + m->sheen_roughness;
        for (int c = 0; c < 3; c++) {
            x->sheen_col[c] = (v4f){ 0 } + m->sheen_color[c];
        }
        if (p->slot[SLOT_SHEEN_COLOR].tex) {
            sample_slot(&p->slot[SLOT_SHEEN_COLOR], q, tex, uv);
            for (int c = 0; c < 3; c++) {
                x->sheen_col[c] *= load(tex[c]);
            }
        }
        if (p->slot[SLOT_SHEEN_ROUGHNESS].tex) {
            sample_slot(&p->slot[SLOT_SHEEN_ROUGHNESS], q, tex, uv);
            x->sheen_r *= load(tex[3]);
        }
        sr__sheen_begin(x, vmax(dot3(n, v), (v4f){ 1e-4f, 1e-4f, 1e-4f, 1e-4f }));
    }
    if (p->aniso) {
        aniso_inputs(p, q, side, x);
    }
    if (p->dtrans) {
        dtrans_inputs(p, q, x);
    }
    if (p->irid) {
        x->irid = true;
        x->ir_ior = m->iridescence_ior;
        x->ir_w = (v4f){ 0 } + m->iridescence;
        x->ir_thick = (v4f){ 0 } + m->iridescence_thickness_max;
        if (p->slot[SLOT_IRIDESCENCE].tex) {
            sample_slot(&p->slot[SLOT_IRIDESCENCE], q, tex, uv);
            x->ir_w *= load(tex[0]);
        }
        if (p->slot[SLOT_IRIDESCENCE_THICKNESS].tex) {
            float lo = m->iridescence_thickness_min, hi = m->iridescence_thickness_max;
            sample_slot(&p->slot[SLOT_IRIDESCENCE_THICKNESS], q, tex, uv);
            x->ir_thick = lo + (hi - lo) * load(tex[1]);
        }
    }
}

/* The unit direction from the eye to pos + ray, for the lanes. */
static void eye_to(const sr_pbr *p, const v4f pos[3], const v4f ray[3], v4f d[3])
{
    for (int c = 0; c < 3; c++) {
        d[c] = pos[c] + ray[c] - p->eye[c];
    }
    v4f l2 = dot3(d, d);
    v4f il = sr__v4_sel(l2 > 0.0f, rsqrt_nr(vmax(l2, (v4f){ 1e-30f, 1e-30f, 1e-30f, 1e-30f })),
                        (v4f){ 0 });
    for (int c = 0; c < 3; c++) {
        d[c] *= il;
    }
}

/* x turned by the rotation that takes the unit direction a onto b
 * (Rodrigues: with k = a x b and cos = a.b, x cos + k x x + k (k.x) /
 * (1 + cos)); a and b lie a dispersion's few degrees apart, never
 * opposite. */
static void turn_onto(const v4f a[3], const v4f b[3], v4f x[3])
{
    v4f k[3] = { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                 a[0] * b[1] - a[1] * b[0] };
    v4f cs = dot3(a, b), kx = dot3(k, x);
    v4f w = sr__v4_sel(cs > -0.5f, kx * rcp_nr(vmax(1.0f + cs, (v4f){ 0.5f, 0.5f, 0.5f, 0.5f })),
                       (v4f){ 0 });
    v4f t[3] = { k[1] * x[2] - k[2] * x[1], k[2] * x[0] - k[0] * x[2],
                 k[0] * x[1] - k[1] * x[0] };
    for (int c = 0; c < 3; c++) {
        x[c] = x[c] * cs + t[c] + k[c] * w;
    }
}

/* One light's radiance towards the eye through the surface, seen from
 * exit (the ray's way out of the volume), for all three channels; turn,
 * when not NULL, is a pair of directions (from, onto) the light's
 * direction is turned by first. */
static void light_through(const sr_pbr *p, int l, const v4f exit[3], const v4f n[3],
                          const v4f v[3], v4f rough, const v4f f0[3], v4f f90,
                          const v4f (*turn)[3], v4f out[3])
{
    v4f ld[3], bt[3];
    for (int c = 0; c < 3; c++) {
        ld[c] = p->light_vec[l][c] - (v4f){ 0 };
        out[c] = p->light_rad[l][c] - (v4f){ 0 };
    }
    if (p->light_point[l]) {
        v4f fall = point_falloff(p, l, exit, ld);
        for (int c = 0; c < 3; c++) {
            out[c] *= fall;
        }
    }
    if (turn) {
        turn_onto(turn[0], turn[1], ld);
    }
    sr__transmission_btdf4(&p->tr, n, v, ld, rough, f0, f90, bt);
    for (int c = 0; c < 3; c++) {
        out[c] *= bt[c];
    }
}

/* The punctual lights' radiance through a transmissive surface at four
 * lanes (sr__transmission_btdf4), attenuated by the volume as the light
 * behind is (keep): a point or spot light is seen from where the view ray
 * leaves the volume (pos + ray), a directional one from everywhere the
 * same way.  In a dispersive volume (ray_rb: red's and blue's own ways)
 * red and blue see a point light from their own exit points, and every
 * light turned by the angle between their way from the eye and green's:
 * the angle by which they see the background beside green's, so that a
 * lamp splits into colours as the scene behind does.  The shadow map is
 * not applied: the glass itself stands between it and the key light
 * shining through. */
static void transmitted_lights(const sr_pbr *p, const float pos_[3][4], const float n_[3][4],
                               const float v_[3][4], const float rough_[4],
                               const float ray_[3][4], const float (*ray_rb)[3][4],
                               const float keep_[3][4], const float f0_[3][4], const float f90_[4],
                               float out_[3][4])
{
    v4f pos[3], exit[3], ray[3], n[3], v[3], f0[3], sum[3] = { { 0 } };
    load3(pos, pos_);
    load3(ray, ray_);
    load3(n, n_);
    load3(v, v_);
    load3(f0, f0_);
    v4f rough = load(rough_), f90 = load(f90_);
    for (int c = 0; c < 3; c++) {
        exit[c] = pos[c] + ray[c];
    }
    /* Red's and blue's exit points, and their ways from the eye turned
     * onto green's. */
    v4f side_exit[2][3], turn[2][2][3];
    if (ray_rb) {
        for (int s = 0; s < 2; s++) {
            v4f r[3];
            load3(r, ray_rb[s]);
            for (int c = 0; c < 3; c++) {
                side_exit[s][c] = pos[c] + r[c];
            }
            eye_to(p, pos, r, turn[s][0]);
            eye_to(p, pos, ray, turn[s][1]);
        }
    }
    for (int l = 0; l < p->nlights; l++) {
        v4f rad[3];
        light_through(p, l, exit, n, v, rough, f0, f90, NULL, rad);
        if (!ray_rb) {
            for (int c = 0; c < 3; c++) {
                sum[c] += rad[c];
            }
            continue;
        }
        sum[1] += rad[1];
        for (int s = 0; s < 2; s++) {
            light_through(p, l, side_exit[s], n, v, rough, f0, f90,
                          (const v4f(*)[3])turn[s], rad);
            sum[2 * s] += rad[2 * s];
        }
    }
    for (int c = 0; c < 3; c++) {
        store(out_[c], sum[c] * load(keep_[c]));
    }
}

/* KHR_materials_transmission at four lanes: kd becomes 1 - transmission
 * (the diffuse lobe's share left), seen the transmitted radiance, in the
 * dielectric's share (1 - metallic) through the base color: the light
 * behind (sr__transmission_light4) minus what the specular lobe reflects,
 * 1 - (F0 A + F90 B) with the split sum's scale and bias, plus the
 * punctual lights shining through (transmitted_lights); the dielectric's
 * F0 and F90 from x (ior and specular) or 0.04 and 1. */
static void transmission_lanes(const sr_pbr *p, const sr_fragment_quad *q,
                               const float pos[3][4], const float n[3][4], const float v[3][4],
                               const float base[4][4], const float metal[4],
                               const float rough[4], const sr__pbr_layers *x, float kd[4],
                               float seen[3][4])
{
    float tr[4], thick[4], tex[4][4], uv[2][4];
    for (int i = 0; i < 4; i++) {
        tr[i] = p->m.transmission;
        thick[i] = p->m.thickness;
    }
    if (p->slot[SLOT_TRANSMISSION].tex) {
        sample_slot(&p->slot[SLOT_TRANSMISSION], q, tex, uv);
        for (int i = 0; i < 4; i++) {
            tr[i] *= tex[0][i];
        }
    }
    if (p->slot[SLOT_THICKNESS].tex) {
        sample_slot(&p->slot[SLOT_THICKNESS], q, tex, uv);
        for (int i = 0; i < 4; i++) {
            thick[i] *= tex[1][i];
        }
    }
    float light[3][4], ray[3][4], keep[3][4], ray_rb[2][3][4], nv[4], rc[4], sa[4], sb[4];
    sr__transmission_light4(&p->tr, pos, n, v, rough, thick, q->mask, light, ray, keep,
                            p->tr.disperses ? ray_rb : NULL);
    for (int i = 0; i < 4; i++) {
        tr[i] = clamp01(tr[i]);
        kd[i] = 1.0f - tr[i];
        nv[i] = clamp01(n[0][i] * v[0][i] + n[1][i] * v[1][i] + n[2][i] * v[2][i]);
        rc[i] = clamp01(rough[i]);
    }
    sr_brdf_table4(nv, rc, sa, sb);
    float f0[3][4], f90[4];
    for (int i = 0; i < 4; i++) {
        for (int c = 0; c < 3; c++) {
            f0[c][i] = x ? x->f0[c][i] : 0.04f;
        }
        f90[i] = x ? x->f90[i] : 1.0f;
    }
    float direct[3][4] = { { 0 } };
    if (p->nlights > 0) {
        transmitted_lights(p, pos, n, v, rough, (const float(*)[4])ray,
                           p->tr.disperses ? (const float(*)[3][4])ray_rb : NULL,
                           (const float(*)[4])keep, (const float(*)[4])f0, f90, direct);
    }
    for (int i = 0; i < 4; i++) {
        float share = tr[i] * (1.0f - clamp01(metal[i]));
        for (int c = 0; c < 3; c++) {
            float es = f0[c][i] * sa[i] + f90[i] * sb[i];
            seen[c][i] = share * (1.0f - es) * base[c][i] * light[c][i] +
                         share * base[c][i] * direct[c][i];
        }
    }
}

/* shade_lanes for a material with extensions, out of pbr_fs so that the
 * plain materials' code stays as it was; keep gets what the coat lets
 * through (pbr_layers.h), for the emission. */
static __attribute__((noinline)) void shade_layered(const sr_pbr *p, const sr_fragment_quad *q,
                                                    float side, const float n[3][4],
                                                    const float v[3][4], const float pos[3][4],
                                                    const float base[4][4], const float metal[4],
                                                    const float rough[4], const float ao[4],
                                                    const float shadow[4],
                                                    const float (*sg_f0)[4], float out[3][4],
                                                    float keep[4])
{
    sr__pbr_layers x;
    layer_inputs(p, q, side, n, v, sg_f0, &x);
    if (p->dtrans && p->shadow) {
        /* The light let through from behind reaches the far side of the
         * surface first: looked up there, the thickness deep (the one the
         * absorption crosses, textured or not) and moved along the far
         * side's normal (towards a light behind), so that the surface
         * itself, which the map holds, does not shadow it, while anything
         * between it and the light still does. */
        float g[3][4], far[3][4], vis[4];
        for (int i = 0; i < 4; i++) {
            float len2 = 0.0f;
            for (int k = 0; k < 3; k++) {
                g[k][i] = -q->varyings[VARY_NORMAL + k][i] * side;
                len2 += g[k][i] * g[k][i];
            }
            float il = len2 > 0.0f ? x.dt_thick[i] * p->dt_axis / sqrtf(len2) : 0.0f;
            for (int k = 0; k < 3; k++) {
                far[k][i] = pos[k][i] + g[k][i] * il;
            }
        }
        sr_shadow_visibility4(p->shadow, &far[0][0], &g[0][0], vis);
        x.dt_shadow = load(vis);
    }
    /* The transmitted light is the base's: under the sheen and the coat. */
    float kd[4], seen[3][4];
    const float *diffuse = opaque;
    const float(*through)[4] = NULL;
    if (p->transmits) {
        transmission_lanes(p, q, pos, n, v, base, metal, rough, &x, kd, seen);
        diffuse = kd;
        through = (const float(*)[4])seen;
    }
    shade_lanes(p, pos, n, v, base, metal, rough, ao, shadow, diffuse, through, &x, out);
    store(keep, x.coat ? x.cc_keep : (v4f){ 1, 1, 1, 1 });
}

/* The tone curve at four lanes: Khronos PBR Neutral (the default) as
 * sr__tone_curve computes it, both of its branches evaluated and selected
 * so the lanes stay in vectors; the other curves per lane. */
static void tone_lanes(sr_tonemap_op op, float a[3][4])
{
    if (op != SR_TONEMAP_PBR_NEUTRAL) {
        for (int i = 0; i < 4; i++) {
            float in[3] = { a[0][i], a[1][i], a[2][i] }, o[3];
            sr__tone_curve(op, in, o);
            a[0][i] = o[0], a[1][i] = o[1], a[2][i] = o[2];
        }
        return;
    }
    const float start = 0.8f - 0.04f, desaturation = 0.15f, d = 1.0f - start;
    v4f c[3];
    for (int k = 0; k < 3; k++) {
        /* NaN and negatives are black, infinities the largest float. */
        c[k] = vclamp(load(a[k]), 0.0f, FLT_MAX);
    }
    v4f x = vmin(c[0], vmin(c[1], c[2]));
    v4f offset = sr__v4_sel(x < 0.08f, x - 6.25f * x * x, 0.04f - (v4f){ 0 });
    for (int k = 0; k < 3; k++) {
        c[k] -= offset;
    }
    v4f peak = vmax(c[0], vmax(c[1], c[2]));
    v4f new_peak = 1.0f - d * d / (peak + d - start);
    v4f g = 1.0f - 1.0f / (desaturation * (peak - new_peak) + 1.0f);
    v4f sc = new_peak / vmax(peak, start - (v4f){ 0 });
    v4i keep = peak < start;
    for (int k = 0; k < 3; k++) {
        v4f cv = c[k] * sc;
        store(a[k], sr__v4_sel(keep, c[k], cv + (new_peak - cv) * g));
    }
}

/* sr__srgb_code at four lanes: the clamp and the bucket index in vectors,
 * the two table reads per channel and lane without a branch. */
static void encode_lanes(const srgb_table *t, const float a[3][4], sr_fragment_quad *q)
{
    for (int k = 0; k < 3; k++) {
        v4f x = vclamp(load(a[k]), 0.0f, 1.0f);
        v4i bucket = (v4i)x >> SR_SRGB_BUCKET_SHIFT;
        v4f code;
        for (int i = 0; i < 4; i++) {
            int c = t->first[bucket[i]];
            /* step[255] does not exist: 1.0 and above are 255 already. */
            c += c < 255 && x[i] >= t->step[c < 255 ? c : 254];
            code[i] = (float)c;
        }
        store(q->color[k], code * (1.0f / 255.0f));
    }
}

/* KHR_materials_pbrSpecularGlossiness's BRDF inputs, as the extension
 * writes them: F0 = specular (factor times the texture's RGB), alpha =
 * (1 - glossiness)^2, that is roughness 1 - glossiness (factor times the
 * texture's A), a dielectric (metallic 0) whose diffuse color (base) is
 * weighted by 1 - max(F0). */
static void sg_inputs(const sr_pbr *p, const sr_fragment_quad *q, float base[4][4],
                      float metal[4], float rough[4], float f0[3][4])
{
    float tex[4][4], uv[2][4];
    for (int c = 0; c < 4; c++) {
        for (int i = 0; i < 4; i++) {
            tex[c][i] = 1.0f;
        }
    }
    if (p->slot[SLOT_SPEC_GLOSS].tex) {
        sample_slot(&p->slot[SLOT_SPEC_GLOSS], q, tex, uv);
    }
    for (int i = 0; i < 4; i++) {
        float top = 0.0f;
        for (int c = 0; c < 3; c++) {
            f0[c][i] = clamp01(p->f0_color[c] * tex[c][i]);
            top = max_f(top, f0[c][i]);
        }
        for (int c = 0; c < 3; c++) {
            base[c][i] *= 1.0f - top;
        }
        metal[i] = 0.0f;
        rough[i] = 1.0f - clamp01(p->m.glossiness * tex[3][i]);
    }
}

static void pbr_fs(const void *uniforms, sr_fragment_quad *q)
{
    const sr_pbr *p = uniforms;
    const sr_pbr_material *m = &p->m;
    float base[4][4], tex[4][4], uv[2][4];
    for (int c = 0; c < 4; c++) {
        for (int i = 0; i < 4; i++) {
            base[c][i] = m->base_color[c];
        }
    }
    if (p->vary_color >= 0) {
        for (int c = 0; c < 4; c++) {
            for (int i = 0; i < 4; i++) {
                base[c][i] *= q->varyings[p->vary_color + c][i];
            }
        }
    }
    if (p->slot[SLOT_BASE].tex) {
        sample_slot(&p->slot[SLOT_BASE], q, tex, uv);
        for (int c = 0; c < 4; c++) {
            for (int i = 0; i < 4; i++) {
                base[c][i] *= tex[c][i];
            }
        }
    }
    float alpha[4];
    for (int i = 0; i < 4; i++) {
        alpha[i] = m->alpha_mode == SR_ALPHA_BLEND ? clamp01(base[3][i]) : 1.0f;
    }
    if (m->alpha_mode == SR_ALPHA_MASK) {
        for (int i = 0; i < 4; i++) {
            q->discard |= base[3][i] < m->alpha_cutoff ? 1u << i : 0u;
        }
    }
    float out[3][4];
    if (m->unlit) {
        /* Unlit is the base colour as radiance: exposed and tone mapped like
         * every other surface, as glTF viewers do, so an unlit label keeps
         * its tone beside lit parts; --tonemap none shows it as it is. */
        for (int c = 0; c < 3; c++) {
            for (int i = 0; i < 4; i++) {
                out[c][i] = base[c][i] * p->scale;
            }
        }
    } else {
        float metal[4], rough[4], ao[4];
        for (int i = 0; i < 4; i++) {
            metal[i] = m->metallic;
            rough[i] = m->roughness;
            ao[i] = 1.0f;
        }
        if (p->slot[SLOT_MR].tex) {
            sample_slot(&p->slot[SLOT_MR], q, tex, uv);
            for (int i = 0; i < 4; i++) {
                rough[i] *= tex[1][i];
                metal[i] *= tex[2][i];
            }
        }
        float sg_f0[3][4];
        if (p->sg) {
            sg_inputs(p, q, base, metal, rough, sg_f0);
        }
        if (p->slot[SLOT_OCCLUSION].tex) {
            sample_slot(&p->slot[SLOT_OCCLUSION], q, tex, uv);
            for (int i = 0; i < 4; i++) {
                ao[i] = 1.0f + m->occlusion_strength * (tex[0][i] - 1.0f);
            }
        }
        float n[3][4], v[3][4];
        float side = q->front ? 1.0f : -1.0f;
        for (int k = 0; k < 3; k++) {
            for (int i = 0; i < 4; i++) {
                n[k][i] = q->varyings[VARY_NORMAL + k][i] * side;
                v[k][i] = p->eye[k] - q->varyings[VARY_POS + k][i];
            }
        }
        normalize4(n);
        normalize4(v);
        if (p->slot[SLOT_NORMAL].tex) {
            float t[3][4], b[3][4];
            sample_slot(&p->slot[SLOT_NORMAL], q, tex, uv);
            tangent_frame(p, q, n, uv, t, b);
            for (int i = 0; i < 4; i++) {
                float x = (2.0f * tex[0][i] - 1.0f) * m->normal_scale;
                float y = (2.0f * tex[1][i] - 1.0f) * m->normal_scale;
                float z = 2.0f * tex[2][i] - 1.0f;
                for (int k = 0; k < 3; k++) {
                    n[k][i] = t[k][i] * x + b[k][i] * y + n[k][i] * z;
                }
            }
            normalize4(n);
        }
        float pos[3][4], shadow[4] = { 1, 1, 1, 1 };
        memcpy(pos, &q->varyings[VARY_POS], sizeof pos);
        if (p->shadow) {
            /* The geometric normal (the interpolated vertex normal, facing
             * the shaded side), not the normal map's. */
            float g[3][4];
            for (int k = 0; k < 3; k++) {
                for (int i = 0; i < 4; i++) {
                    g[k][i] = q->varyings[VARY_NORMAL + k][i] * side;
                }
            }
            sr_shadow_visibility4(p->shadow, &pos[0][0], &g[0][0], shadow);
        }
        float coat_keep[4];
        if (p->layers) {
            shade_layered(p, q, side, (const float(*)[4])n, (const float(*)[4])v,
                          (const float(*)[4])pos, (const float(*)[4])base, metal, rough, ao,
                          shadow, p->sg ? (const float(*)[4])sg_f0 : NULL, out, coat_keep);
        } else {
            /* Transmission takes its share of the diffuse lobe (kd). */
            float kd[4], seen[3][4];
            const float *diffuse = opaque;
            const float(*through)[4] = NULL;
            if (p->transmits) {
                transmission_lanes(p, q, (const float(*)[4])pos, (const float(*)[4])n,
                                   (const float(*)[4])v, (const float(*)[4])base, metal, rough,
                                   NULL, kd, seen);
                diffuse = kd;
                through = (const float(*)[4])seen;
            }
            shade_lanes(p, (const float(*)[4])pos, (const float(*)[4])n, (const float(*)[4])v,
                        (const float(*)[4])base, metal, rough, ao, shadow, diffuse, through, NULL,
                        out);
        }
        /* Without emission (no texture, a zero factor, a strength of 0)
         * the sum would add a zero, which changes at most the sign of a
         * zero radiance: every tone curve sends both zeros to black
         * (sr__tone_curve), so the bytes are the same without the sum. */
        bool emits = m->emissive_strength != 0.0f &&
                     (p->slot[SLOT_EMISSIVE].tex || m->emissive[0] != 0.0f ||
                      m->emissive[1] != 0.0f || m->emissive[2] != 0.0f);
        if (p->slot[SLOT_EMISSIVE].tex) {
            sample_slot(&p->slot[SLOT_EMISSIVE], q, tex, uv);
        } else {
            for (int c = 0; c < 3; c++) {
                for (int i = 0; i < 4; i++) {
                    tex[c][i] = 1.0f;
                }
            }
        }
        float es = m->emissive_strength;
        if (emits && p->coat) {
            /* The coat lies over the emission too and reflects its share. */
            for (int c = 0; c < 3; c++) {
                store(tex[c], load(tex[c]) * load(coat_keep));
            }
        }
        for (int c = 0; c < 3; c++) {
            for (int i = 0; i < 4; i++) {
                out[c][i] = emits ? (out[c][i] + m->emissive[c] * es * tex[c][i]) * p->scale
                                  : out[c][i] * p->scale;
            }
        }
    }
    tone_lanes(p->tonemap, out);
    encode_lanes(p->srgb, out, q);
    for (int i = 0; i < 4; i++) {
        q->color[3][i] = alpha[i];
    }
}

/* ---- the program -------------------------------------------------------- */

static bool finite_n(const float *v, int n)
{
    for (int i = 0; i < n; i++) {
        if (!isfinite(v[i])) {
            return false;
        }
    }
    return true;
}

static sr_result check_slot(sr_context *ctx, const sr_texture_slot *s, const char *name)
{
    if (!s->texture) {
        return SR_OK;
    }
    if (s->texcoord != 0 && s->texcoord != 1) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_pbr_material.%s.texcoord %d must be 0 or 1",
                        name, s->texcoord);
    }
    if ((unsigned)s->filter > SR_FILTER_TRILINEAR || (unsigned)s->wrap_u > SR_WRAP_MIRROR ||
        (unsigned)s->wrap_v > SR_WRAP_MIRROR) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_pbr_material.%s: unknown filter or wrap mode",
                        name);
    }
    if (!finite_n(s->offset, 2) || !finite_n(s->scale, 2) || !isfinite(s->rotation)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_pbr_material.%s: transform is not finite", name);
    }
    return SR_OK;
}

/* KHR_materials_transmission and _volume: finite, a thickness and an
 * attenuation distance that are lengths (their slots are checked with
 * the others). */
static sr_result check_transmission(sr_context *ctx, const sr_pbr_material *m)
{
    if (!isfinite(m->transmission) || !finite_n(m->attenuation_color, 3) ||
        !(m->thickness >= 0.0f && m->thickness < INFINITY) ||
        !(m->attenuation_distance >= 0.0f && m->attenuation_distance < INFINITY)) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_pbr_material: transmission, thickness or attenuation is not finite "
                        "(thickness and attenuation_distance must be >= 0)");
    }
    return SR_OK;
}

static sr_result check_material(sr_context *ctx, const sr_pbr_material *m)
{
    if (!finite_n(m->base_color, 4) || !finite_n(m->emissive, 3) || !isfinite(m->metallic) ||
        !isfinite(m->roughness) || !isfinite(m->normal_scale) ||
        !isfinite(m->occlusion_strength) || !isfinite(m->emissive_strength) ||
        !isfinite(m->alpha_cutoff)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_pbr_material: a factor is not finite");
    }
    sr_result tr = check_transmission(ctx, m);
    if (tr != SR_OK) {
        return tr;
    }
    if ((unsigned)m->alpha_mode > SR_ALPHA_BLEND) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_pbr_material.alpha_mode %d is not a mode",
                        (int)m->alpha_mode);
    }
    if (!isfinite(m->ior) || !finite_n(m->specular_color, 3) || !isfinite(m->specular) ||
        !isfinite(m->clearcoat) || !isfinite(m->clearcoat_roughness) ||
        !isfinite(m->clearcoat_normal_scale) || !finite_n(m->sheen_color, 3) ||
        !isfinite(m->sheen_roughness) || !isfinite(m->anisotropy_strength) ||
        !isfinite(m->anisotropy_rotation) || !isfinite(m->iridescence) ||
        !isfinite(m->iridescence_ior) || !isfinite(m->iridescence_thickness_min) ||
        !isfinite(m->iridescence_thickness_max) || !isfinite(m->dispersion) ||
        !isfinite(m->diffuse_transmission) || !finite_n(m->diffuse_transmission_color, 3) ||
        !finite_n(m->sg_specular, 3) || !isfinite(m->glossiness)) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_pbr_material: an extension's factor is not finite");
    }
    if (m->ior != 0.0f && !(m->ior >= 1.0f)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_pbr_material.ior %g must be 0 (1.5) or >= 1",
                        (double)m->ior);
    }
    if (m->iridescence_ior != 0.0f && !(m->iridescence_ior >= 1.0f)) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_pbr_material.iridescence_ior %g must be 0 (1.3) or >= 1",
                        (double)m->iridescence_ior);
    }
    if (m->dispersion < 0.0f) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_pbr_material.dispersion %g must be >= 0",
                        (double)m->dispersion);
    }
    if (m->diffuse_transmission < 0.0f || m->diffuse_transmission > 1.0f) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_pbr_material.diffuse_transmission %g must be in 0..1",
                        (double)m->diffuse_transmission);
    }
    for (int c = 0; c < 3; c++) {
        if (m->diffuse_transmission_color[c] < 0.0f || m->diffuse_transmission_color[c] > 1.0f) {
            return sr__fail(ctx, SR_INVALID_ARG,
                            "sr_pbr_material.diffuse_transmission_color[%d] %g must be in 0..1",
                            c, (double)m->diffuse_transmission_color[c]);
        }
    }
    if (m->iridescence_thickness_min < 0.0f || m->iridescence_thickness_max < 0.0f) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_pbr_material: iridescence thicknesses must be >= 0 nm");
    }
    for (int i = 0; i < SLOT_COUNT; i++) {
        sr_result r = check_slot(ctx, material_slot(m, i), slot_fields[i].name);
        if (r != SR_OK) {
            return r;
        }
    }
    return SR_OK;
}

/* The slot's transform is already in sr_texture's frame (v up; a glTF
 * reader converts the file's, docs/gltf.md): uv' = T R S uv with R
 * counter-clockwise. */
static void resolve_slot(const sr_texture_slot *in, pbr_slot *out)
{
    out->tex = in->texture;
    out->filter = in->filter ? in->filter : SR_FILTER_TRILINEAR;
    out->wu = in->wrap_u ? in->wrap_u : SR_WRAP_REPEAT;
    out->wv = in->wrap_v ? in->wrap_v : SR_WRAP_REPEAT;
    sr__texture_slot_matrix(in, out->xf);
}

static sr_result check_desc(sr_context *ctx, const sr_pbr_desc *d)
{
    if (!(fabsf(d->exposure) <= MAX_EXPOSURE)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_pbr_desc.exposure %g is not in -64..64 EV",
                        (double)d->exposure);
    }
    if ((unsigned)d->tonemap > SR_TONEMAP_NONE) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_pbr_desc.tonemap %d is not an operator",
                        (int)d->tonemap);
    }
    if ((unsigned)d->vertex_color > SR_OFF) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_pbr_desc.vertex_color %d is not a switch",
                        (int)d->vertex_color);
    }
    if ((d->tangents || d->texcoords1) && d->vertex_count == 0) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_pbr_desc.vertex_count must be > 0 with tangents or texcoords1");
    }
    if ((d->tangent_stride && d->tangent_stride < 16) || d->tangent_stride % 4 ||
        (d->texcoord1_stride && d->texcoord1_stride < 8) || d->texcoord1_stride % 4) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_pbr_desc: strides must be multiples of 4 and hold their floats");
    }
    /* Every vertex and normal goes through them: a NaN would reach the
     * clipper as a NaN position and the lights as NaN radiance. */
    const sr_mat4 *mats[3] = { d->model, d->view, d->projection };
    static const char *const names[3] = { "model", "view", "projection" };
    for (int i = 0; i < 3; i++) {
        if (mats[i] && !finite_n(mats[i]->m, 16)) {
            return sr__fail(ctx, SR_INVALID_ARG, "sr_pbr_desc.%s has a NaN or infinite entry",
                            names[i]);
        }
    }
    if (!finite_n(&d->sky.x, 3) || !finite_n(&d->ground.x, 3) || d->sky.x < 0 || d->sky.y < 0 ||
        d->sky.z < 0 || d->ground.x < 0 || d->ground.y < 0 || d->ground.z < 0) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_pbr_desc: sky and ground must be finite and >= 0");
    }
    for (int l = 0; l < SR_MAX_LIGHTS; l++) {
        const sr_light *li = &d->lights[l];
        if ((unsigned)li->type > SR_LIGHT_SPOT) {
            return sr__fail(ctx, SR_INVALID_ARG, "sr_pbr_desc.lights[%d].type %d is not a type", l,
                            (int)li->type);
        }
        if (li->type == SR_LIGHT_OFF) {
            continue;
        }
        if (!finite_n(&li->vector.x, 3) || !finite_n(&li->color.x, 3) ||
            !isfinite(li->intensity) || !finite_n(&li->direction.x, 3) ||
            !isfinite(li->inner_cone) || !isfinite(li->outer_cone) || !isfinite(li->range)) {
            return sr__fail(ctx, SR_INVALID_ARG, "sr_pbr_desc.lights[%d] is not finite", l);
        }
        if (li->range < 0) {
            return sr__fail(ctx, SR_INVALID_ARG, "sr_pbr_desc.lights[%d].range must be >= 0", l);
        }
        if (li->type == SR_LIGHT_SPOT) {
            float outer = li->outer_cone != 0.0f ? li->outer_cone : PI_F / 4;
            if (!(li->inner_cone >= 0 && li->inner_cone < outer && outer <= PI_F / 2)) {
                return sr__fail(ctx, SR_INVALID_ARG,
                                "sr_pbr_desc.lights[%d]: cones must be 0 <= inner_cone < "
                                "outer_cone <= pi/2", l);
            }
            if (sr_vec3_length(li->direction) == 0.0f) {
                return sr__fail(ctx, SR_INVALID_ARG,
                                "sr_pbr_desc.lights[%d].direction must not be zero", l);
            }
        }
    }
    return SR_OK;
}

static void resolve_lights(const sr_pbr_desc *d, sr_pbr *p)
{
    for (int l = 0; l < SR_MAX_LIGHTS; l++) {
        const sr_light *li = &d->lights[l];
        if (li->type == SR_LIGHT_OFF) {
            continue;
        }
        int k = p->nlights++;
        sr_vec3 col = li->color;
        if (col.x == 0 && col.y == 0 && col.z == 0) {
            col = (sr_vec3){ 1, 1, 1 };
        }
        float in = li->intensity != 0.0f ? li->intensity : 1.0f;
        p->light_rad[k][0] = col.x * in;
        p->light_rad[k][1] = col.y * in;
        p->light_rad[k][2] = col.z * in;
        p->light_point[k] = li->type == SR_LIGHT_POINT || li->type == SR_LIGHT_SPOT;
        p->light_spot[k] = li->type == SR_LIGHT_SPOT;
        /* A directional light's vector is the way it travels: shading
         * wants the way back to it. */
        sr_vec3 v = p->light_point[k] ? li->vector
                                       : sr_vec3_normalize(sr_vec3_scale(li->vector, -1));
        p->light_vec[k][0] = v.x;
        p->light_vec[k][1] = v.y;
        p->light_vec[k][2] = v.z;
        if (p->light_point[k] && li->range > 0.0f) {
            double r = li->range;
            p->light_inv_range2[k] = (float)(1.0 / (r * r));
        }
        if (p->light_spot[k]) {
            sr_vec3 a = sr_vec3_normalize(li->direction);
            p->light_axis[k][0] = a.x;
            p->light_axis[k][1] = a.y;
            p->light_axis[k][2] = a.z;
            /* The extension's recommended blend, linear in the cosine and
             * squared by the shader; the 0.001 keeps a hard-edged cone
             * (inner close to outer) finite. */
            double outer = li->outer_cone != 0.0f ? li->outer_cone : PI_F / 4;
            double co = cos(outer), ci = cos(li->inner_cone);
            double scale = 1.0 / (ci - co > 0.001 ? ci - co : 0.001);
            p->light_cone_scale[k] = (float)scale;
            p->light_cone_offset[k] = (float)(-co * scale);
        }
    }
}

/* Varyings after the fixed six: the texcoord sets the slots read, vertex
 * colors, then tangents if there is room (else the derivative frame). */
static int layout_varyings(const sr_pbr_desc *d, sr_pbr *p)
{
    int n = VARY_FIXED;
    bool uses[2] = { false, false };
    bool lit = !p->m.unlit;
    for (int i = 0; i < SLOT_COUNT; i++) {
        if (p->slot[i].tex && (lit || i == SLOT_BASE)) {
            /* A slot on set 1 without texcoords1 reads set 0 (below), which
             * must then be laid out even when no slot names it. */
            int set = material_slot(&p->m, i)->texcoord;
            uses[set == 1 && !d->texcoords1 ? 0 : set] = true;
        }
    }
    /* Anisotropy's derivative frame reads set 0 when the draw has no
     * tangents. */
    uses[0] |= p->aniso;
    for (int k = 0; k < 2; k++) {
        p->vary_uv[k] = -1;
        if (uses[k] && (k == 0 || d->texcoords1)) {
            p->vary_uv[k] = n;
            n += 2;
        }
    }
    for (int i = 0; i < SLOT_COUNT; i++) {
        int set = material_slot(&p->m, i)->texcoord;
        /* A slot on a set the draw cannot give reads set 0 (zero if absent). */
        p->slot[i].vary = p->vary_uv[set] >= 0 ? p->vary_uv[set] : p->vary_uv[0];
        if (p->slot[i].vary < 0) {
            p->slot[i].tex = NULL;
        }
    }
    p->vary_color = -1;
    if (d->vertex_color != SR_OFF) {
        p->vary_color = n;
        n += 4;
    }
    p->vary_tangent = -1;
    bool maps = p->slot[SLOT_NORMAL].tex || p->slot[SLOT_CLEARCOAT_NORMAL].tex || p->aniso;
    if (lit && maps && d->tangents && n + 4 <= SR_SHADER_MAX_VARYINGS) {
        p->vary_tangent = n;
        n += 4;
    }
    return n;
}

/* In double: ior 1.5 gives 0.04f itself, the base's constant, so the
 * extension's default draws the very bytes of its absence. */
float sr__ior_f0(float ior)
{
    if (ior == 0.0f) {
        return 0.04f;
    }
    double r = ((double)ior - 1.0) / ((double)ior + 1.0);
    return (float)(r * r);
}

/* The extensions' uniforms: which layers run, the dielectric's F0 color
 * and F90 before textures; factors clamped to their ranges here, as the
 * shader clamps metallic and roughness.  A layer that cannot show (a
 * zero weight or color) is off with its textures, so such a material
 * draws the base's very bytes. */
static void resolve_layers(sr_pbr *p)
{
    sr_pbr_material *m = &p->m;
    float f0 = sr__ior_f0(m->ior);
    bool spec = m->specular_set && !m->specular_glossiness;
    for (int c = 0; c < 3; c++) {
        p->f0_color[c] = f0 * (spec ? max_f(m->specular_color[c], 0.0f) : 1.0f);
        m->sheen_color[c] = clamp01(m->sheen_color[c]);
    }
    p->f90 = spec ? clamp01(m->specular) : 1.0f;
    /* Specular-glossiness: F0 is the specular color itself (the shader
     * multiplies in the texture's RGB), F90 1. */
    p->sg = !m->unlit && m->specular_glossiness;
    if (p->sg) {
        for (int c = 0; c < 3; c++) {
            p->f0_color[c] = clamp01(m->sg_specular[c]);
        }
        m->glossiness = clamp01(m->glossiness);
    }
    m->clearcoat = clamp01(m->clearcoat);
    m->clearcoat_roughness = clamp01(m->clearcoat_roughness);
    m->sheen_roughness = clamp01(m->sheen_roughness);
    m->anisotropy_strength = clamp01(m->anisotropy_strength);
    p->an_cos = cosf(m->anisotropy_rotation);
    p->an_sin = sinf(m->anisotropy_rotation);
    m->iridescence = clamp01(m->iridescence);
    if (m->iridescence_ior == 0.0f) {
        m->iridescence_ior = 1.3f;
    }
    if (!m->iridescence_thickness_set && m->iridescence_thickness_min == 0.0f &&
        m->iridescence_thickness_max == 0.0f) {
        m->iridescence_thickness_min = 100.0f;
        m->iridescence_thickness_max = 400.0f;
    }
    /* A film 0 nm thick everywhere is no film (KHR_materials_iridescence):
     * off, rather than the formula's near miss of the base. */
    bool film = m->iridescence_thickness_max > 0.0f ||
                (p->slot[SLOT_IRIDESCENCE_THICKNESS].tex && m->iridescence_thickness_min > 0.0f);
    if (m->clearcoat_normal_scale == 0.0f) {
        m->clearcoat_normal_scale = 1.0f;
    }
    /* Unlit excludes the layers (the extensions say so). */
    p->coat = !m->unlit && m->clearcoat > 0.0f;
    p->sheen = !m->unlit &&
               (m->sheen_color[0] > 0.0f || m->sheen_color[1] > 0.0f || m->sheen_color[2] > 0.0f);
    p->aniso = !m->unlit && m->anisotropy_strength > 0.0f;
    p->irid = !m->unlit && m->iridescence > 0.0f && film;
    p->dtrans = !m->unlit && m->diffuse_transmission > 0.0f;
    p->layers = !m->unlit && (m->ior != 0.0f || spec || p->coat || p->sheen || p->aniso ||
                              p->irid || p->dtrans || p->sg);
    int off[SLOT_COUNT], count = 0;
    if (!spec) {
        off[count++] = SLOT_SPECULAR;
        off[count++] = SLOT_SPECULAR_COLOR;
    }
    if (p->sg) {
        off[count++] = SLOT_MR;
    } else {
        off[count++] = SLOT_SPEC_GLOSS;
    }
    if (!p->coat) {
        off[count++] = SLOT_CLEARCOAT;
        off[count++] = SLOT_CLEARCOAT_ROUGHNESS;
        off[count++] = SLOT_CLEARCOAT_NORMAL;
    }
    if (!p->sheen) {
        off[count++] = SLOT_SHEEN_COLOR;
        off[count++] = SLOT_SHEEN_ROUGHNESS;
    }
    if (!p->aniso) {
        off[count++] = SLOT_ANISOTROPY;
    }
    if (!p->irid) {
        off[count++] = SLOT_IRIDESCENCE;
        off[count++] = SLOT_IRIDESCENCE_THICKNESS;
    }
    if (!p->dtrans) {
        off[count++] = SLOT_DIFFUSE_TRANSMISSION;
        off[count++] = SLOT_DIFFUSE_TRANSMISSION_COLOR;
    }
    for (int i = 0; i < count; i++) {
        p->slot[off[i]].tex = NULL;
    }
}

/* The volume's absorption of diffusely transmitted light per unit of
 * the material's thickness: its rate per world unit (as
 * sr__transmission_setup's) times the model's mean axis length, the
 * thickness being in object space. */
static float mean_axis(const sr_mat4 *model)
{
    float scale = 0.0f;
    for (int a = 0; a < 3; a++) {
        const float *c = &model->m[4 * a];
        scale += sqrtf(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) * (1.0f / 3.0f);
    }
    return scale;
}

static void dtrans_absorption(sr_pbr *p)
{
    const sr_pbr_material *m = &p->m;
    float scale = mean_axis(&p->model);
    for (int c = 0; c < 3; c++) {
        float col = m->attenuation_color[c] > 1e-30f ? m->attenuation_color[c] : 1e-30f;
        float rate = -log2f(col > 1.0f ? 1.0f : col) / m->attenuation_distance * scale;
        p->dt_absorb[c] = rate < 1e30f ? rate : 1e30f;
    }
}

sr_result sr_make_pbr_program(sr_context *ctx, const sr_pbr_desc *desc, sr_pbr **out)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_make_pbr_program: ctx is NULL");
    }
    if (!desc || !out) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_make_pbr_program: %s is NULL",
                        desc ? "out" : "desc");
    }
    *out = NULL;
    sr_pbr_material mat = desc->material ? *desc->material : sr_pbr_default_material();
    sr_result r = check_desc(ctx, desc);
    if (r == SR_OK) {
        r = check_material(ctx, &mat);
    }
    if (r != SR_OK) {
        return r;
    }
    sr_pbr *p = sr__calloc(ctx, 1, sizeof *p);
    if (!p) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_make_pbr_program: out of memory");
    }
    p->m = mat;
    if (!p->m.emissive_strength_set && p->m.emissive_strength == 0.0f) {
        p->m.emissive_strength = 1.0f;
    }
    if (p->m.alpha_cutoff == 0.0f) {
        p->m.alpha_cutoff = 0.5f;
    }
    for (int i = 0; i < SLOT_COUNT; i++) {
        resolve_slot(material_slot(&mat, i), &p->slot[i]);
    }
    resolve_layers(p);
    p->model = desc->model ? *desc->model : sr_mat4_identity();
    sr_mat4 view = desc->view ? *desc->view : sr_mat4_identity();
    sr_mat4 proj = desc->projection ? *desc->projection : sr_mat4_identity();
    p->view_projection = sr_mat4_mul(&proj, &view);
    sr_mat4 nm;
    if (!sr_normal_matrix(&p->model, &nm)) {
        nm = p->model;
    }
    /* The bitangent is w N x T with N and T moved to world space; a
     * mirror turns that cross product against the mirrored B, so w turns
     * with it (the sign of the model's 3x3 determinant). */
    const float *mm = p->model.m;
    double det = (double)mm[0] * ((double)mm[5] * mm[10] - (double)mm[9] * mm[6]) -
                 (double)mm[4] * ((double)mm[1] * mm[10] - (double)mm[9] * mm[2]) +
                 (double)mm[8] * ((double)mm[1] * mm[6] - (double)mm[5] * mm[2]);
    p->handedness = det < 0 ? -1.0f : 1.0f;
    for (int r3 = 0; r3 < 3; r3++) {
        for (int c = 0; c < 3; c++) {
            p->normal_matrix[3 * r3 + c] = nm.m[4 * c + r3];
        }
    }
    sr_mat4 inv;
    if (sr_mat4_invert(&view, &inv)) {
        p->eye[0] = inv.m[12];
        p->eye[1] = inv.m[13];
        p->eye[2] = inv.m[14];
    }
    resolve_lights(desc, p);
    memcpy(p->sky, &desc->sky.x, sizeof p->sky);
    memcpy(p->ground, &desc->ground.x, sizeof p->ground);
    p->environment = desc->environment;
    p->shadow = desc->shadow;
    p->ambient = p->sky[0] + p->sky[1] + p->sky[2] + p->ground[0] + p->ground[1] + p->ground[2] > 0;
    p->scale = exp2f(desc->exposure);
    p->tonemap = desc->tonemap ? desc->tonemap : SR_TONEMAP_PBR_NEUTRAL;
    p->srgb = sr__srgb_table();
    p->vertex_count = desc->tangents || desc->texcoords1 ? desc->vertex_count : 0;
    p->tangents = (const uint8_t *)desc->tangents;
    p->tangent_stride = desc->tangent_stride ? desc->tangent_stride : 4 * sizeof(float);
    p->texcoords1 = (const uint8_t *)desc->texcoords1;
    p->texcoord1_stride = desc->texcoord1_stride ? desc->texcoord1_stride : 2 * sizeof(float);
    p->transmits = !mat.unlit && mat.transmission != 0.0f;
    if (p->dtrans && mat.thickness > 0.0f && mat.attenuation_distance > 0.0f) {
        dtrans_absorption(p);
    }
    if (p->dtrans) {
        p->dt_axis = mean_axis(&p->model);
    }
    if (!p->transmits) {
        p->slot[SLOT_TRANSMISSION].tex = NULL;
        if (!p->dtrans) {
            p->slot[SLOT_THICKNESS].tex = NULL;
        }
    } else {
        sr__transmission_setup(&mat, &p->model, &p->view_projection, desc->transmission_source,
                               desc->environment, p->scale, &p->tr);
    }
    sr_program *pr = &p->program;
    pr->vertex = pbr_vs;
    pr->fragment = pbr_fs;
    pr->uniforms = p;
    pr->varying_count = layout_varyings(desc, p);
    pr->may_discard = mat.alpha_mode == SR_ALPHA_MASK;
    /* Only the texture lookups read lane differences (level of detail,
     * the derivative tangent frame); the shadow's quad verdict equals
     * its lanes' own tests. */
    pr->independent_lanes = true;
    for (int i = 0; i < SLOT_COUNT; i++) {
        pr->independent_lanes &= !p->slot[i].tex;
    }
    pr->independent_lanes &= !(p->aniso && p->vary_tangent < 0);
    float rough = p->sg ? 1.0f - p->m.glossiness : min_f(max_f(mat.roughness, 0.0f), 1.0f);
    int rough_slot = p->sg ? SLOT_SPEC_GLOSS : SLOT_MR;
    if (p->environment && !p->m.unlit) {
        /* Irradiance from the SH, and with one roughness for every
         * fragment the prefiltered radiance tabulated once (4096 queries)
         * and read per fragment without the queries' trigonometry. */
        irr_poly(p->environment->sh, p->irr);
        p->env_cos = p->environment->cos_rot;
        p->env_sin = p->environment->sin_rot;
        bool ok = true;
        if (!p->slot[rough_slot].tex && rough >= OCT_MIN_ROUGHNESS) {
            ok &= (p->oct = oct_shared(ctx, p->environment, rough, &p->oct_owned)) != NULL;
        }
        /* The coat's one roughness likewise. */
        if (p->coat && !p->slot[SLOT_CLEARCOAT_ROUGHNESS].tex &&
            p->m.clearcoat_roughness >= OCT_MIN_ROUGHNESS) {
            ok &= (p->oct_coat = oct_shared(ctx, p->environment, p->m.clearcoat_roughness,
                                            &p->oct_coat_owned)) != NULL;
        }
        if (!ok) {
            sr_destroy_pbr_program(ctx, p);
            return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_make_pbr_program: out of memory");
        }
    }
    *out = p;
    sr__ok(ctx);
    return SR_OK;
}

const sr_program *sr_pbr_program(const sr_pbr *p)
{
    return p ? &p->program : NULL;
}

void sr_destroy_pbr_program(sr_context *ctx, sr_pbr *p)
{
    if (ctx && p) {
        if (p->oct_owned) {
            sr__free(ctx, p->oct);
        } else if (p->oct) {
            sr__oct_cache_release(ctx, p->oct);
        }
        if (p->oct_coat_owned) {
            sr__free(ctx, p->oct_coat);
        } else if (p->oct_coat) {
            sr__oct_cache_release(ctx, p->oct_coat);
        }
        sr__free(ctx, p);
    }
}
