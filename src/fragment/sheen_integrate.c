/* sheen_integrate.c - the directional albedo of KHR_materials_sheen's
 * BRDF with a white sheen, E(N.V, roughness) = integral over the
 * hemisphere of D V (N.L), computed (fragment stage): the extension's
 * albedo scaling takes max(sheen color) E off the base under the sheen,
 * and the ambient sheen is E times the irradiance.  The build runs it
 * once (tools/ibl_tables.c) and the library reads the result
 * (pbr_sheen.c); pure, any thread. */
#include "fragment/sheen.h"

#define STEPS_COS 128      /* along cos(theta_l) = u^2: denser at grazing */
#define STEPS_PHI 64       /* over phi in [0, pi]; the lobe is symmetric */
#define MIN_N_DOT_V 1e-4f  /* the N.V = 0 column is taken here */

void sr__sheen_table_row(int row, float out[SR__SHEEN_TABLE_SIZE])
{
    float alpha = sr__sheen_alpha((float)row / (SR__SHEEN_TABLE_SIZE - 1));
    const double pi = 3.14159265358979323846;
    for (int col = 0; col < SR__SHEEN_TABLE_SIZE; col++) {
        float nv = fmaxf((float)col / (SR__SHEEN_TABLE_SIZE - 1), MIN_N_DOT_V);
        float v[3] = { sqrtf(1.0f - nv * nv), 0.0f, nv };
        double sum = 0.0;
        for (int i = 0; i < STEPS_COS; i++) {
            double u = (i + 0.5) / STEPS_COS;
            float nl = (float)(u * u), sl = sqrtf(1.0f - nl * nl);
            for (int j = 0; j < STEPS_PHI; j++) {
                double phi = pi * (j + 0.5) / STEPS_PHI;
                float l[3] = { sl * (float)cos(phi), sl * (float)sin(phi), nl };
                float h[3] = { l[0] + v[0], l[1] + v[1], l[2] + v[2] };
                float hl = sqrtf(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
                float nh = hl > 0.0f ? h[2] / hl : 0.0f;
                /* d omega = d cos d phi, d cos = 2 u du */
                sum += (double)sr__sheen_lobe(alpha, nl, nv, nh) * 2.0 * u;
            }
        }
        /* twice the half circle of phi */
        double e = 2.0 * sum * (1.0 / STEPS_COS) * (pi / STEPS_PHI);
        out[col] = (float)(e < 1.0 ? e : 1.0);
    }
}
