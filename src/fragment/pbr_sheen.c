/* pbr_sheen.c - KHR_materials_sheen on the PBR program's four lanes
 * (fragment stage, pbr_layers.h): Charlie's lobe times the sheen color
 * per light, E(N.V) times the irradiance for ambient light, and the
 * extension's albedo scaling of the base under it, 1 - max(color) E(N.V)
 * (its per-view form).  The lobe's powers and exponentials have no lane
 * twin: they run per lane, for sheen materials only.  Any thread. */
#include "fragment/pbr_layers.h"
#include "fragment/sheen.h"

float sr__sheen_albedo(float n_dot_v, float roughness)
{
    const int n = SR__SHEEN_TABLE_SIZE;
    float fx = clamp01(n_dot_v) * (float)(n - 1), fy = clamp01(roughness) * (float)(n - 1);
    int x0 = (int)fx, y0 = (int)fy;
    x0 = x0 < n - 1 ? x0 : n - 2;
    y0 = y0 < n - 1 ? y0 : n - 2;
    float ax = fx - (float)x0, ay = fy - (float)y0;
    const float(*t)[SR__SHEEN_TABLE_SIZE] = sr__sheen_builtin;
    float top = t[y0][x0] + ax * (t[y0][x0 + 1] - t[y0][x0]);
    float bot = t[y0 + 1][x0] + ax * (t[y0 + 1][x0 + 1] - t[y0 + 1][x0]);
    return top + ay * (bot - top);
}

void sr__sheen_begin(sr__pbr_layers *x, v4f nv)
{
    v4f peak = vmax(x->sheen_col[0], vmax(x->sheen_col[1], x->sheen_col[2]));
    for (int i = 0; i < 4; i++) {
        x->sheen_e[i] = sr__sheen_albedo(nv[i], x->sheen_r[i]);
    }
    x->sheen_keep = 1.0f - peak * x->sheen_e;
    for (int c = 0; c < 3; c++) {
        x->sheen_sum[c] = (v4f){ 0 };
    }
}

void sr__sheen_light(sr__pbr_layers *x, v4f nl, v4f nv, v4f nh, const v4f rad[3])
{
    v4f s = { 0 };
    for (int i = 0; i < 4; i++) {
        if (nl[i] > 0.0f) {
            s[i] = sr__sheen_lobe(sr__sheen_alpha(x->sheen_r[i]), nl[i], nv[i], nh[i]);
        }
    }
    for (int c = 0; c < 3; c++) {
        x->sheen_sum[c] += x->sheen_col[c] * s * rad[c];
    }
}

void sr__sheen_ambient(sr__pbr_layers *x, const v4f en[3], v4f ao)
{
    for (int c = 0; c < 3; c++) {
        x->sheen_sum[c] += x->sheen_col[c] * x->sheen_e * en[c] * ao;
    }
}
