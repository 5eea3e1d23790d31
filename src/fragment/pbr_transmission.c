/* pbr_transmission.c - fragment stage: the transmitted light of
 * KHR_materials_transmission and KHR_materials_volume, as real-time
 * renderers approximate it (Khronos' sample viewer, three.js, Filament):
 * the opaque scene drawn first is looked up at the screen position where
 * the refracted view ray leaves the volume, blurred by a mip level that
 * grows with the roughness.  Read-only state; called by tile workers. */
#include "fragment/pbr_transmission.h"
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
    t->eta = 1.0f / (m->ior != 0.0f ? m->ior : 1.5f);
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

void sr__transmission_light4(const sr__transmission *t, const float pos[3][4],
                             const float n[3][4], const float v[3][4], const float rough[4],
                             const float thick[4], unsigned mask, float out[3][4])
{
    for (int i = 0; i < 4; i++) {
        float light[3] = { 0, 0, 0 };
        float length = 0.0f;
        if ((mask >> i & 1) && (t->source || t->environment)) {
            float vi[3] = { v[0][i], v[1][i], v[2][i] }, ni[3] = { n[0][i], n[1][i], n[2][i] };
            float pi[3] = { pos[0][i], pos[1][i], pos[2][i] };
            float dir[3], step[3];
            refract_view(vi, ni, t->eta, dir);
            float th = thick[i] > 0.0f ? thick[i] : 0.0f, len2 = 0.0f;
            for (int c = 0; c < 3; c++) {
                step[c] = dir[c] * th * t->model_scale[c];
                len2 += step[c] * step[c];
            }
            length = sqrtf(len2);
            float r = rough[i] < 0.0f ? 0.0f : rough[i] > 1.0f ? 1.0f : rough[i];
            if (t->source) {
                float u, tv, texel[4];
                exit_uv(t, pi, step, &u, &tv);
                sr__texture_sample_linear(t->source, SR_FILTER_TRILINEAR, SR_WRAP_CLAMP,
                                          SR_WRAP_CLAMP, u, tv, t->lod_scale * r, texel);
                for (int c = 0; c < 3; c++) {
                    light[c] = texel[c] * t->inv_exposure;
                }
            } else {
                /* A thin wall bends the ray in and back out: it leaves
                 * parallel to the view ray. */
                const float straight[3] = { -vi[0], -vi[1], -vi[2] };
                sr_environment_specular(t->environment, th > 0.0f ? dir : straight, r, light);
            }
        }
        for (int c = 0; c < 3; c++) {
            if (t->attenuates && length > 0.0f) {
                /* Beer-Lambert: attenuation_color^(length / distance). */
                light[c] *= exp2f(-t->absorb[c] * length);
            }
            out[c][i] = light[c];
        }
    }
}
