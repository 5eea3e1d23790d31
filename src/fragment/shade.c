/* shade.c - Blinn-Phong lighting, shared by the vertex stage (Gouraud:
 * lighting per vertex), the front end (flat: once per triangle) and the
 * fragment stage (Phong: per pixel).  Any thread; reads only. */
#include "pipeline.h"

#include <math.h>

/* x^s for the specular term.  Shininess is nearly always a whole number;
 * then exponentiation by squaring (at most 2 log2 s multiplies) replaces
 * powf, which was a fifth of Phong's per-pixel cost.  Either way the value
 * depends only on (x, s), so every rasterizer computes the same bytes. */
static float specular_power(float x, float s, int si)
{
    if (si < 0) {
        return powf(x, s);
    }
    float r = 1.0f;
    while (si) {
        if (si & 1) {
            r *= x;
        }
        x *= x;
        si >>= 1;
    }
    return r;
}

/* color = ambient + sum over lights of light * (kd max(0, n.l)
 *                                              + ks max(0, n.h)^shininess),
 * h = normalize(l + v), v towards the eye.  The specular term is dropped
 * when the light is behind the surface (n.l <= 0) so no highlight shows
 * through. */
void sr__light(const sr_draw_state *ds, const float n[3], const float eye[3],
               const float diffuse[4], float out[4])
{
    float r = ds->ambient[0] * diffuse[0];
    float g = ds->ambient[1] * diffuse[1];
    float b = ds->ambient[2] * diffuse[2];

    float v[3] = { 0.0f, 0.0f, 1.0f };
    if (ds->local_viewer) {
        float len = sqrtf(eye[0] * eye[0] + eye[1] * eye[1] + eye[2] * eye[2]);
        if (len > 0.0f) {
            v[0] = -eye[0] / len;
            v[1] = -eye[1] / len;
            v[2] = -eye[2] / len;
        }
    }
    for (int i = 0; i < ds->light_count; i++) {
        const sr_light_eye *lt = &ds->lights[i];
        float l[3];
        if (lt->point) {
            l[0] = lt->vec[0] - eye[0];
            l[1] = lt->vec[1] - eye[1];
            l[2] = lt->vec[2] - eye[2];
            float len = sqrtf(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
            if (!(len > 0.0f)) {
                continue;
            }
            l[0] /= len;
            l[1] /= len;
            l[2] /= len;
        } else {
            l[0] = lt->vec[0];
            l[1] = lt->vec[1];
            l[2] = lt->vec[2];
        }
        float ndotl = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
        if (ndotl <= 0.0f) {
            continue;
        }
        float kd = ndotl;
        r += lt->color[0] * diffuse[0] * kd;
        g += lt->color[1] * diffuse[1] * kd;
        b += lt->color[2] * diffuse[2] * kd;
        if (ds->specular[0] > 0.0f || ds->specular[1] > 0.0f || ds->specular[2] > 0.0f) {
            float h[3] = { l[0] + v[0], l[1] + v[1], l[2] + v[2] };
            float hl = sqrtf(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
            if (hl > 0.0f) {
                float ndoth = (n[0] * h[0] + n[1] * h[1] + n[2] * h[2]) / hl;
                if (ndoth > 0.0f) {
                    float s = specular_power(ndoth, ds->shininess, ds->shininess_int);
                    r += lt->color[0] * ds->specular[0] * s;
                    g += lt->color[1] * ds->specular[1] * s;
                    b += lt->color[2] * ds->specular[2] * s;
                }
            }
        }
    }
    out[0] = r;
    out[1] = g;
    out[2] = b;
    out[3] = diffuse[3];
}
