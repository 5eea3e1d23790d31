/* brdf_integrate.c - the split-sum BRDF table of image-based light
 * (fragment stage, docs/ibl.md), computed: for each (N.V, roughness) the
 * directional albedo of the GGX specular BRDF with the height-correlated
 * Smith visibility, as a scale and a bias of F0 (Schlick's Fresnel), by GGX
 * importance sampling over a Hammersley set.  The build runs it once
 * (tools/ibl_tables.c) and the library reads the result (brdf_table.c);
 * pure, any thread.
 */
#include "fragment/environment.h"

#define TABLE_SAMPLES 512           /* Hammersley points per node */
#define MIN_N_DOT_V   1e-4f         /* the N.V = 0 column is taken here */

/* The estimator is
 *   sum over H ~ D(H) (N.H) of  F(V.H) Vis(N.L, N.V) 4 (N.L) (V.H) / (N.H)
 * divided by the count, with F split into F0 (1 - Fc) + Fc. */
void sr__brdf_table_row(int row, float out[SR__BRDF_TABLE_SIZE][2])
{
    float roughness = (float)row / (SR__BRDF_TABLE_SIZE - 1);
    float alpha = roughness * roughness;
    float a2 = alpha * alpha;
    /* the half vectors depend on the roughness only */
    float h[TABLE_SAMPLES][3];
    for (unsigned i = 0; i < TABLE_SAMPLES; i++) {
        sr__ggx_half_vector(((float)i + 0.5f) / TABLE_SAMPLES, sr__radical_inverse(i), alpha, h[i]);
    }
    for (int col = 0; col < SR__BRDF_TABLE_SIZE; col++) {
        float nv = fmaxf((float)col / (SR__BRDF_TABLE_SIZE - 1), MIN_N_DOT_V);
        float v[3] = { sqrtf(1.0f - nv * nv), 0.0f, nv };
        float vis_v = sqrtf(nv * nv * (1.0f - a2) + a2);
        double scale = 0.0, bias = 0.0;
        for (unsigned i = 0; i < TABLE_SAMPLES; i++) {
            float vh = v[0] * h[i][0] + v[2] * h[i][2];
            float nl = 2.0f * vh * h[i][2] - v[2];
            if (nl <= 0.0f || vh <= 0.0f) {
                continue;
            }
            float nh = h[i][2];
            float vis = 0.5f / (nl * vis_v + nv * sqrtf(nl * nl * (1.0f - a2) + a2));
            float g = vis * 4.0f * nl * vh / nh;
            float m = 1.0f - vh, m2 = m * m;
            float fc = m2 * m2 * m;
            scale += (1.0f - fc) * g;
            bias += fc * g;
        }
        scale /= TABLE_SAMPLES;
        bias /= TABLE_SAMPLES;
        /* Single scattering loses energy; the sampled sum can only overshoot
         * 1 by the estimate's own error. */
        double sum = scale + bias;
        if (sum > 1.0) {
            scale /= sum;
            bias /= sum;
        }
        float fs = (float)scale, fb = (float)bias;
        while (fs + fb > 1.0f) {
            fs = nextafterf(fs, 0.0f);
        }
        out[col][0] = fs;
        out[col][1] = fb;
    }
}
