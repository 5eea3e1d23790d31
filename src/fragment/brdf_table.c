/* brdf_table.c - the split-sum BRDF table of image-based light (fragment
 * stage, docs/ibl.md) looked up: bilinear between the nodes that the build
 * computed (brdf_integrate.c, through tools/ibl_tables.c).  Any thread.
 */
#include "fragment/environment.h"

#define TABLE_SIZE SR__BRDF_TABLE_SIZE

static inline float clamp01(float x)
{
    return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f;  /* NaN -> 0 */
}

static inline void lookup(float n_dot_v, float roughness, float *scale, float *bias)
{
    float fx = clamp01(n_dot_v) * (TABLE_SIZE - 1), fy = clamp01(roughness) * (TABLE_SIZE - 1);
    int x0 = (int)fx, y0 = (int)fy;
    x0 = x0 < TABLE_SIZE - 1 ? x0 : TABLE_SIZE - 2;
    y0 = y0 < TABLE_SIZE - 1 ? y0 : TABLE_SIZE - 2;
    float ax = fx - (float)x0, ay = fy - (float)y0;
    const float(*table)[TABLE_SIZE][2] = sr__brdf_builtin;
    for (int c = 0; c < 2; c++) {
        float top = table[y0][x0][c] + ax * (table[y0][x0 + 1][c] - table[y0][x0][c]);
        float bot = table[y0 + 1][x0][c] + ax * (table[y0 + 1][x0 + 1][c] - table[y0 + 1][x0][c]);
        float v = top + ay * (bot - top);
        if (c == 0) {
            *scale = v;
        } else {
            *bias = v;
        }
    }
}

void sr_brdf_table(float n_dot_v, float roughness, float out[2])
{
    if (!out) {
        return;
    }
    lookup(n_dot_v, roughness, &out[0], &out[1]);
}

void sr_brdf_table4(const float n_dot_v[4], const float roughness[4], float scale[4],
                    float bias[4])
{
    if (!n_dot_v || !roughness || !scale || !bias) {
        return;
    }
    sr__brdf_lookup4(n_dot_v, roughness, scale, bias);
}

void sr__brdf_lookup4(const float n_dot_v[4], const float roughness[4], float scale[4],
                      float bias[4])
{
    for (int i = 0; i < 4; i++) {
        lookup(n_dot_v[i], roughness[i], &scale[i], &bias[i]);
    }
}
