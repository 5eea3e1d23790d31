/* sheen.h - KHR_materials_sheen's BRDF without its color (fragment
 * stage): Charlie's distribution (Estevez and Kulla 2017) and the
 * extension's fitted visibility, scalar, shared by the shader's lanes
 * (pbr_sheen.c) and the build's table of its directional albedo
 * (sheen_integrate.c, through tools/ibl_tables.c).  Pure; any thread. */
#ifndef SR_SHEEN_H
#define SR_SHEEN_H

#include <math.h>

/* Below it Charlie's exponent 1 / alpha passes 200 and the lobe is a
 * sliver at grazing angles that neither the table nor powf resolve. */
#define SR__SHEEN_MIN_ROUGHNESS 0.07f

/* The directional albedo E(N.V, roughness) on SR__SHEEN_TABLE_SIZE nodes
 * along each, [roughness][n_dot_v]: row `row` computed by quadrature
 * (sheen_integrate.c), the whole table by the build (ibl_tables.c). */
#define SR__SHEEN_TABLE_SIZE 32
void sr__sheen_table_row(int row, float out[SR__SHEEN_TABLE_SIZE]);
extern const float sr__sheen_builtin[SR__SHEEN_TABLE_SIZE][SR__SHEEN_TABLE_SIZE];

static inline float sr__sheen_alpha(float roughness)
{
    float r = roughness > SR__SHEEN_MIN_ROUGHNESS ? roughness : SR__SHEEN_MIN_ROUGHNESS;
    return r * r;
}

/* D(h) = (2 + 1 / alpha) sin(theta_h)^(1 / alpha) / (2 pi). */
static inline float sr__charlie_d(float alpha, float n_dot_h)
{
    float inv = 1.0f / alpha;
    float sin2 = 1.0f - n_dot_h * n_dot_h;
    sin2 = sin2 > 0.0f ? sin2 : 0.0f;
    return (2.0f + inv) * powf(sin2, 0.5f * inv) * (0.5f / 3.14159265358979f);
}

/* The extension's fit of the shadowing exponent: the coefficients at
 * alpha 0 and 1 blended by (1 - alpha)^2. */
static inline float sr__sheen_l(float x, float alpha)
{
    float t = (1.0f - alpha) * (1.0f - alpha);
    float a = 21.5473f + (25.3245f - 21.5473f) * t;
    float b = 3.82987f + (3.32435f - 3.82987f) * t;
    float c = 0.19823f + (0.16801f - 0.19823f) * t;
    float d = -1.97760f + (-1.27393f + 1.97760f) * t;
    float e = -4.32054f + (-4.85967f + 4.32054f) * t;
    return a / (1.0f + b * powf(x, c)) + d * x + e;
}

static inline float sr__sheen_lambda(float cos_theta, float alpha)
{
    return cos_theta < 0.5f ? expf(sr__sheen_l(cos_theta, alpha))
                            : expf(2.0f * sr__sheen_l(0.5f, alpha) -
                                   sr__sheen_l(1.0f - cos_theta, alpha));
}

/* D V (N.L) for N.L, N.V > 0: V = 1 / ((1 + Lambda(N.V) + Lambda(N.L))
 * 4 (N.V) (N.L)), the N.L cancelled. */
static inline float sr__sheen_lobe(float alpha, float n_dot_l, float n_dot_v, float n_dot_h)
{
    float lam = 1.0f + sr__sheen_lambda(n_dot_v, alpha) + sr__sheen_lambda(n_dot_l, alpha);
    return sr__charlie_d(alpha, n_dot_h) / (lam * 4.0f * n_dot_v);
}

#endif
