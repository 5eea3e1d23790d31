/* pbr_transmission.c - fragment stage: the transmitted light of
 * KHR_materials_transmission and KHR_materials_volume, as real-time
 * renderers approximate it (Khronos' sample viewer, three.js, Filament):
 * the opaque scene drawn first is looked up at the screen position where
 * the refracted view ray leaves the volume, blurred by a mip level that
 * grows with the roughness.  Read-only state; called by tile workers. */
#include "fragment/pbr_transmission.h"
#include "fragment/pbr_lanes.h"
#include "fragment/texture.h"

#include <math.h>
#include <string.h>

void sr__transmission_setup(const sr_pbr_material *m, const sr_mat4 *model,
                            const sr_mat4 *view_projection, const sr_texture *source,
                            const sr_environment *environment, float exposure_scale,
                            sr__transmission *t)
{
    memset(t, 0, sizeof *t);
    t->source = source;
    t->environment = source ? NULL : environment;
    float ior = m->ior != 0.0f ? m->ior : 1.5f;
    t->eta = 1.0f / ior;
    /* The sample viewer's applyIorToRoughness: an ior of 1 bends no
     * light, so its microfacets spread none; 1.5 and above the full
     * roughness. */
    t->rough_scale = clamp01(2.0f * ior - 2.0f);
    /* KHR_materials_dispersion's per-channel iors: its dispersion is
     * 20 / the Abbe number V = (n_d - 1) / (n_F - n_C), and red and blue
     * lie half the spread n_F - n_C below and above green's n_d (the
     * extension's implementation notes; three.js and the sample viewer
     * alike), red clamped to 1 where the spread would take it below. */
    t->disperses = m->dispersion > 0.0f && m->thickness > 0.0f;
    if (t->disperses) {
        float half = (ior - 1.0f) * 0.025f * m->dispersion;
        float lo = ior - half, hi = ior + half;
        t->eta_rgb[0] = 1.0f / (lo > 1.0f ? lo : 1.0f);
        t->eta_rgb[1] = t->eta;
        t->eta_rgb[2] = 1.0f / hi;
    }
    memcpy(t->view_projection, view_projection->m, sizeof t->view_projection);
    for (int a = 0; a < 3; a++) {
        const float *c = &model->m[4 * a];
        t->model_scale[a] = sqrtf(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    }
    t->inv_exposure = 1.0f / exposure_scale;
    t->lod_scale = source ? log2f((float)source->width[0]) : 0.0f;
    t->attenuates = m->attenuation_distance > 0.0f;
    for (int c = 0; t->attenuates && c < 3; c++) {
        /* A black channel absorbs everything past the surface: a large
         * finite rate keeps 0 * rate (no distance) at zero, not NaN. */
        float col = m->attenuation_color[c] > 1e-30f ? m->attenuation_color[c] : 1e-30f;
        float rate = -log2f(col > 1.0f ? 1.0f : col) / m->attenuation_distance;
        t->absorb[c] = rate < 1e30f ? rate : 1e30f;
    }
}

/* x within [-1, 2], NaN to 0. */
static float clamp_uv(float x)
{
    return x >= -1.0f ? (x <= 2.0f ? x : 2.0f) : (x < -1.0f ? -1.0f : 0.0f);
}

/* refract(-v, n, eta) of GLSL, normalized; zero past the critical angle
 * (which eta = 1 / ior <= 1 never reaches from outside). */
static void refract_view(const float v[3], const float n[3], float eta, float out[3])
{
    float ni = -(n[0] * v[0] + n[1] * v[1] + n[2] * v[2]);
    float k = 1.0f - eta * eta * (1.0f - ni * ni);
    if (k < 0.0f) {
        out[0] = out[1] = out[2] = 0.0f;
        return;
    }
    float s = eta * ni + sqrtf(k);
    float len2 = 0.0f;
    for (int c = 0; c < 3; c++) {
        out[c] = -eta * v[c] - s * n[c];
        len2 += out[c] * out[c];
    }
    float il = len2 > 0.0f ? 1.0f / sqrtf(len2) : 0.0f;
    for (int c = 0; c < 3; c++) {
        out[c] *= il;
    }
}

/* Where the view ray leaves: the source's uv at the exit point (pos
 * moved by step) through the view-projection. */
static void exit_uv(const sr__transmission *t, const float pos[3], const float step[3],
                    float *u, float *v)
{
    const float *vp = t->view_projection;
    float clip[4];
    for (int r = 0; r < 4; r++) {
        clip[r] = vp[r] * (pos[0] + step[0]) + vp[4 + r] * (pos[1] + step[1]) +
                  vp[8 + r] * (pos[2] + step[2]) + vp[12 + r];
    }
    /* Behind the eye the exit point has no screen position: the
     * surface's own pixel instead. */
    if (!(clip[3] > 0.0f)) {
        for (int r = 0; r < 4; r++) {
            clip[r] = vp[r] * pos[0] + vp[4 + r] * pos[1] + vp[8 + r] * pos[2] + vp[12 + r];
        }
    }
    float iw = clip[3] != 0.0f ? 1.0f / clip[3] : 0.0f;
    /* NDC to sr_texture's uv: both have y (v) up.  Clamped, as the
     * lookup clamps to the edge anyway: a point near the eye plane would
     * give coordinates no texel index can hold. */
    *u = clamp_uv(clip[0] * iw * 0.5f + 0.5f);
    *v = clamp_uv(clip[1] * iw * 0.5f + 0.5f);
}

/* One channel's (or, without dispersion, every channel's) ray through
 * the volume at eta: the way to its exit point, its length and the light
 * seen there. */
static void trace_ray(const sr__transmission *t, const float pi[3], const float vi[3],
                      const float ni[3], float eta, float th, float r, float step[3],
                      float *length, float light[3])
{
    float dir[3];
    refract_view(vi, ni, eta, dir);
    float len2 = 0.0f;
    for (int c = 0; c < 3; c++) {
        step[c] = dir[c] * th * t->model_scale[c];
        len2 += step[c] * step[c];
    }
    *length = sqrtf(len2);
    if (t->source) {
        float u, tv, texel[4];
        exit_uv(t, pi, step, &u, &tv);
        sr__texture_sample_linear(t->source, SR_FILTER_TRILINEAR, SR_WRAP_CLAMP, SR_WRAP_CLAMP,
                                  u, tv, t->lod_scale * r, texel);
        for (int c = 0; c < 3; c++) {
            light[c] = texel[c] * t->inv_exposure;
        }
    } else if (t->environment) {
        /* A thin wall bends the ray in and back out: it leaves
         * parallel to the view ray. */
        const float straight[3] = { -vi[0], -vi[1], -vi[2] };
        sr_environment_specular(t->environment, th > 0.0f ? dir : straight, r, light);
    }
}

void sr__transmission_light4(const sr__transmission *t, const float pos[3][4],
                             const float n[3][4], const float v[3][4], const float rough[4],
                             const float thick[4], unsigned mask, float out[3][4],
                             float ray[3][4], float keep[3][4], float ray_rb[2][3][4])
{
    for (int i = 0; i < 4; i++) {
        float light[3] = { 0, 0, 0 }, step[3] = { 0, 0, 0 };
        float length[3] = { 0, 0, 0 }, side[2][3] = { { 0, 0, 0 }, { 0, 0, 0 } };
        /* The ray is needed without anything to see along it too: the
         * punctual lights shine through the same volume. */
        if (mask >> i & 1) {
            float vi[3] = { v[0][i], v[1][i], v[2][i] }, ni[3] = { n[0][i], n[1][i], n[2][i] };
            float pi[3] = { pos[0][i], pos[1][i], pos[2][i] };
            float th = thick[i] > 0.0f ? thick[i] : 0.0f;
            float r = rough[i] < 0.0f ? 0.0f : rough[i] > 1.0f ? 1.0f : rough[i];
            trace_ray(t, pi, vi, ni, t->eta, th, r, step, &length[1], light);
            length[0] = length[2] = length[1];
            if (t->disperses) {
                /* Red and blue along their own rays; green's is the one
                 * traced above. */
                for (int c = 0; c < 3; c += 2) {
                    float s[3], l[3] = { 0, 0, 0 };
                    trace_ray(t, pi, vi, ni, t->eta_rgb[c], th, r, s, &length[c], l);
                    light[c] = l[c];
                    memcpy(side[c / 2], s, sizeof s);
                }
            }
        }
        for (int c = 0; c < 3; c++) {
            float k = 1.0f;
            if (t->attenuates && length[c] > 0.0f) {
                /* Beer-Lambert: attenuation_color^(length / distance). */
                k = exp2f(-t->absorb[c] * length[c]);
                light[c] *= k;
            }
            out[c][i] = light[c];
            ray[c][i] = step[c];
            keep[c][i] = k;
            if (ray_rb) {
                ray_rb[0][c][i] = side[0][c];
                ray_rb[1][c][i] = side[1][c];
            }
        }
    }
}

void sr__transmission_btdf4(const sr__transmission *t, const v4f n[3], const v4f v[3],
                            const v4f l[3], v4f rough, const v4f f0[3], v4f f90, v4f out[3])
{
    v4f zero = { 0 };
    v4f r = vclamp(rough, 0.0f, 1.0f);
    /* GGX's alpha (the perceptual roughness squared) scaled by the ior,
     * kept off zero, where D would be a spike of 0 / 0. */
    v4f a = vmax(r * r * t->rough_scale, MIN_ROUGHNESS * MIN_ROUGHNESS - zero);
    v4f a2 = a * a;
    v4f nl = dot3(n, l), lm[3], h[3];
    for (int k = 0; k < 3; k++) {
        /* The light mirrored to the viewer's side: l - 2 (N.L) N. */
        lm[k] = l[k] - 2.0f * nl * n[k];
        h[k] = lm[k] + v[k];
    }
    v4f hl2 = dot3(h, h);
    v4f hs = sr__v4_sel(hl2 > 1e-12f, rsqrt_nr(vmax(hl2, 1e-12f - zero)), zero);
    v4f nh = vclamp(dot3(n, h) * hs, 0.0f, 1.0f), vh = vclamp(dot3(v, h) * hs, 0.0f, 1.0f);
    v4f nlm = vclamp(-nl, 0.0f, 1.0f), nv = vclamp(dot3(n, v), 0.0f, 1.0f);
    v4f dd = nh * nh * (a2 - 1.0f) + 1.0f;
    v4f gv = nlm * sr__v4_sqrt(nv * nv * (1.0f - a2) + a2);
    v4f gl = nv * sr__v4_sqrt(nlm * nlm * (1.0f - a2) + a2);
    v4f g = gv + gl;
    v4f dvis = a2 * 0.5f * rcp_nr(sr__v4_sel(g > 0.0f, PI_F * dd * dd * g, (v4f){ 1, 1, 1, 1 }));
    /* The viewer's BTDF has no cosine: without this a light grazing the
     * front of the surface would shine through it. */
    dvis = sr__v4_sel((g > 0.0f) & (nl < 0.0f), dvis, zero);
    v4f x = 1.0f - vh, x2 = x * x, fw = x2 * x2 * x;
    for (int c = 0; c < 3; c++) {
        out[c] = (1.0f - (f0[c] + (f90 - f0[c]) * fw)) * dvis;
    }
}
