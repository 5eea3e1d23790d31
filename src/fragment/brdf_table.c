/* brdf_table.c - the split-sum BRDF table of image-based light (fragment
 * stage, docs/ibl.md): for each (N.V, roughness) the directional albedo
 * of the GGX specular BRDF with the height-correlated Smith visibility, as
 * a scale and a bias of F0 (Schlick's Fresnel).  Computed once a process,
 * by GGX importance sampling over a Hammersley set; read by any thread
 * once made.
 */
#include "context.h"
#include "fragment/environment.h"

#include <pthread.h>
#include <stdatomic.h>

#define TABLE_SIZE    32            /* nodes along N.V and along roughness */
#define TABLE_SAMPLES 512           /* Hammersley points per node */
#define MIN_N_DOT_V   1e-4f         /* the N.V = 0 column is taken here */

static float table[TABLE_SIZE][TABLE_SIZE][2];  /* [roughness][n_dot_v] */
static atomic_int table_ready;
static pthread_mutex_t table_lock = PTHREAD_MUTEX_INITIALIZER;

/* One row of the table (one roughness): the estimator is
 *   sum over H ~ D(H) (N.H) of  F(V.H) Vis(N.L, N.V) 4 (N.L) (V.H) / (N.H)
 * divided by the count, with F split into F0 (1 - Fc) + Fc. */
static void table_row(void *arg, int row, int thread)
{
    (void)arg;
    (void)thread;
    float roughness = (float)row / (TABLE_SIZE - 1);
    float alpha = roughness * roughness;
    float a2 = alpha * alpha;
    /* the half vectors depend on the roughness only */
    float h[TABLE_SAMPLES][3];
    for (unsigned i = 0; i < TABLE_SAMPLES; i++) {
        sr__ggx_half_vector(((float)i + 0.5f) / TABLE_SAMPLES, sr__radical_inverse(i), alpha, h[i]);
    }
    for (int col = 0; col < TABLE_SIZE; col++) {
        float nv = fmaxf((float)col / (TABLE_SIZE - 1), MIN_N_DOT_V);
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
        table[row][col][0] = fs;
        table[row][col][1] = fb;
    }
}

void sr__brdf_table_init(sr_context *ctx)
{
    if (atomic_load_explicit(&table_ready, memory_order_acquire)) {
        return;
    }
    pthread_mutex_lock(&table_lock);
    if (!atomic_load_explicit(&table_ready, memory_order_relaxed)) {
        sr_run_jobs(ctx, table_row, NULL, TABLE_SIZE);
        atomic_store_explicit(&table_ready, 1, memory_order_release);
    }
    pthread_mutex_unlock(&table_lock);
}

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
    sr__brdf_table_init(NULL);
    lookup(n_dot_v, roughness, &out[0], &out[1]);
}

void sr_brdf_table4(const float n_dot_v[4], const float roughness[4], float scale[4],
                    float bias[4])
{
    if (!n_dot_v || !roughness || !scale || !bias) {
        return;
    }
    sr__brdf_table_init(NULL);
    for (int i = 0; i < 4; i++) {
        lookup(n_dot_v[i], roughness[i], &scale[i], &bias[i]);
    }
}
