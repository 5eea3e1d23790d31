/* environment_prefilter.c - image-based light's precomputation (fragment
 * stage, docs/ibl.md): an environment image's diffuse irradiance as
 * spherical harmonics, and its radiance convolved with the GGX lobe of
 * each roughness level under the split sum's N = V = R assumption.
 * Called by sr_make_environment, and by the build for the built-in studio
 * (tools/ibl_tables.c); the levels are written by bands of rows on the
 * context's threads, each texel on its own, so the floats do not depend
 * on the thread count.
 */
#include "fragment/environment.h"

#include <assert.h>
#include <string.h>

/* ---- irradiance -------------------------------------------------------- */

/* Real spherical harmonics up to order 2 at a unit direction. */
static void sh_basis(const float d[3], float y[9])
{
    float x = d[0], yy = d[1], z = d[2];
    y[0] = 0.282095f;
    y[1] = 0.488603f * yy;
    y[2] = 0.488603f * z;
    y[3] = 0.488603f * x;
    y[4] = 1.092548f * x * yy;
    y[5] = 1.092548f * yy * z;
    y[6] = 0.315392f * (3.0f * z * z - 1.0f);
    y[7] = 1.092548f * x * z;
    y[8] = 0.546274f * (x * x - yy * yy);
}

void sr__irradiance_sh(const sr__equirect *e, float sh[9][3])
{
    double acc[9][3] = { { 0 } };
    for (int j = 0; j < e->h; j++) {
        /* the exact solid angle of a texel of this row */
        double t0 = SR__PI_D * j / e->h, t1 = SR__PI_D * (j + 1) / e->h;
        double d_omega = 2.0 * SR__PI_D / e->w * (cos(t0) - cos(t1));
        const float *p = e->rgb + (size_t)j * e->w * 3;
        for (int i = 0; i < e->w; i++) {
            float d[3], y[9];
            sr__equirect_direction(i, j, e->w, e->h, d);
            sh_basis(d, y);
            for (int k = 0; k < 9; k++) {
                for (int c = 0; c < 3; c++) {
                    acc[k][c] += d_omega * y[k] * p[3 * i + c];
                }
            }
        }
    }
    /* Ramamoorthi and Hanrahan's convolution with the clamped cosine,
     * A_l = pi, 2 pi / 3, pi / 4, then divided by pi for E / pi. */
    static const float band_scale[9] = { 1.0f,        2.0f / 3.0f, 2.0f / 3.0f,
                                         2.0f / 3.0f, 0.25f,       0.25f,
                                         0.25f,       0.25f,       0.25f };
    for (int k = 0; k < 9; k++) {
        for (int c = 0; c < 3; c++) {
            sh[k][c] = (float)acc[k][c] * band_scale[k];
        }
    }
}

/* sh_basis's terms summed, branch-free per lane: the 4-lane loop
 * vectorizes and a single lane gives the same floats. */
static inline float sh_sum(const float sh[9][3], int c, float x, float y, float z)
{
    float v = sh[0][c] * 0.282095f;
    v += sh[1][c] * (0.488603f * y);
    v += sh[2][c] * (0.488603f * z);
    v += sh[3][c] * (0.488603f * x);
    v += sh[4][c] * (1.092548f * x * y);
    v += sh[5][c] * (1.092548f * y * z);
    v += sh[6][c] * (0.315392f * (3.0f * z * z - 1.0f));
    v += sh[7][c] * (1.092548f * x * z);
    v += sh[8][c] * (0.546274f * (x * x - y * y));
    /* a high-contrast image's truncated series can dip below zero */
    return v > 0.0f ? v : 0.0f;
}

void sr__irradiance_eval(const float sh[9][3], const float d[3], float out[3])
{
    for (int c = 0; c < 3; c++) {
        out[c] = sh_sum(sh, c, d[0], d[1], d[2]);
    }
}

void sr__irradiance_eval4(const float sh[9][3], const sr_vec3x4 *d, sr_vec3x4 *out)
{
    for (int i = 0; i < 4; i++) {
        out->x[i] = sh_sum(sh, 0, d->x[i], d->y[i], d->z[i]);
    }
    for (int i = 0; i < 4; i++) {
        out->y[i] = sh_sum(sh, 1, d->x[i], d->y[i], d->z[i]);
    }
    for (int i = 0; i < 4; i++) {
        out->z[i] = sh_sum(sh, 2, d->x[i], d->y[i], d->z[i]);
    }
}

/* ---- source mips ------------------------------------------------------- */

/* dst (w/2 x h/2, at least 1) as 2 x 2 boxes of src; an odd last column or
 * row is folded into its neighbour's box by clamping. */
void sr__equirect_halve(const sr__equirect *src, sr__equirect *dst, int row0, int row1)
{
    for (int j = row0; j < row1; j++) {
        int j0 = 2 * j < src->h ? 2 * j : src->h - 1;
        int j1 = 2 * j + 1 < src->h ? 2 * j + 1 : src->h - 1;
        const float *r0 = src->rgb + (size_t)j0 * src->w * 3;
        const float *r1 = src->rgb + (size_t)j1 * src->w * 3;
        float *o = dst->rgb + (size_t)j * dst->w * 3;
        for (int i = 0; i < dst->w; i++) {
            int i0 = 2 * i < src->w ? 2 * i : src->w - 1;
            int i1 = 2 * i + 1 < src->w ? 2 * i + 1 : src->w - 1;
            for (int c = 0; c < 3; c++) {
                o[3 * i + c] = 0.25f * (r0[3 * i0 + c] + r0[3 * i1 + c] + r1[3 * i0 + c] +
                                        r1[3 * i1 + c]);
            }
        }
    }
}

/* ---- specular levels --------------------------------------------------- */

/* The GGX sample set of one level, in tangent space (N = V = +z). */
void sr__specular_samples(float roughness, int source_w, int source_h, int mips,
                          sr__spec_sample *s, int *count)
{
    /* A narrow lobe needs fewer samples: half as many, each read from a mip
     * half a level coarser. */
    int samples = roughness < 0.3f ? SR__SPEC_SAMPLES / 2 : SR__SPEC_SAMPLES;
    float alpha = roughness * roughness;
    float a2 = alpha * alpha;
    /* Karis's mip-filtered sampling: a sample stands for the solid angle
     * 1 / (n pdf); read the mip whose texels are about that size, one
     * level blurrier to hide the sample pattern. */
    float texel_omega = 4.0f * SR__PI / ((float)source_w * (float)source_h);
    int n = 0;
    for (int i = 0; i < samples; i++) {
        float h[3];
        sr__ggx_half_vector(((float)i + 0.5f) / samples, sr__radical_inverse((unsigned)i), alpha, h);
        float nl = 2.0f * h[2] * h[2] - 1.0f;
        if (nl <= 0.0f) {
            continue;
        }
        float nh = h[2];
        float q = nh * nh * (a2 - 1.0f) + 1.0f;
        float pdf = a2 / (SR__PI * q * q) / 4.0f;
        float sample_omega = 1.0f / ((float)samples * pdf + 1e-6f);
        float lod = 0.5f * log2f(sample_omega / texel_omega) + 1.0f;
        /* Every texel reads sample i from the same mip, so rounding the
         * level changes the blur a little but leaves no seams. */
        int m = (int)(lod + 0.5f);
        m = m < 0 ? 0 : (m > mips - 1 ? mips - 1 : m);
        s[n] = (sr__spec_sample){ .l = { 2.0f * h[2] * h[0], 2.0f * h[2] * h[1], nl },
                                  .weight = nl, .mip = m };
        n++;
    }
    *count = n;
}

void sr__prefilter_rows(const sr__equirect *mip, const sr__spec_sample *s, int count,
                        sr__equirect *dst, int row0, int row1)
{
    assert(dst->w <= SR__LEVEL_MAX_WIDTH);
    float sum[SR__LEVEL_MAX_WIDTH * 3];
    float wsum = 0.0f;
    for (int k = 0; k < count; k++) {
        wsum += s[k].weight;
    }
    for (int j = row0; j < row1; j++) {
        /* Texels of a row differ only by a rotation about +Y, which moves
         * every sample by the same step in u: find the samples of the
         * row's first texel and slide them along.  The frame t = up x n,
         * b = n x t turns with n (no texel centre lies on a pole). */
        float n[3];
        sr__equirect_direction(0, j, dst->w, dst->h, n);
        float tl = 1.0f / sqrtf(n[2] * n[2] + n[0] * n[0]);
        float t[3] = { n[2] * tl, 0.0f, -n[0] * tl };
        float b[3] = { n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2],
                       n[0] * t[1] - n[1] * t[0] };
        memset(sum, 0, sizeof(float) * 3 * (size_t)dst->w);
        for (int k = 0; k < count; k++) {
            const float *l = s[k].l;
            float d[3];
            for (int c = 0; c < 3; c++) {
                d[c] = t[c] * l[0] + b[c] * l[1] + n[c] * l[2];
            }
            float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            const sr__equirect *m = &mip[s[k].mip];
            float px, py;
            sr__equirect_coords(d[0] / len, d[1] / len, d[2] / len, m->w, m->h, &px, &py);
            /* sr__equirect_bilinear with the row pair fixed */
            float fy = py - 0.5f, y0f = floorf(fy), ay = fy - y0f;
            int y0 = (int)y0f, y1 = y0 + 1;
            y0 = y0 < 0 ? 0 : (y0 >= m->h ? m->h - 1 : y0);
            y1 = y1 < 0 ? 0 : (y1 >= m->h ? m->h - 1 : y1);
            const float *r0 = m->rgb + (size_t)y0 * m->w * 3, *r1 = m->rgb + (size_t)y1 * m->w * 3;
            float w0 = s[k].weight * (1.0f - ay), w1 = s[k].weight * ay;
            float step = (float)m->w / (float)dst->w;
            for (int i = 0; i < dst->w; i++) {
                /* px in [0, w) and step i < w: one wrap either way at most */
                float fx = px + step * (float)i - 0.5f;
                float x0f = floorf(fx), ax = fx - x0f;
                int x0 = (int)x0f;
                x0 = x0 < 0 ? x0 + m->w : (x0 >= m->w ? x0 - m->w : x0);
                int x1 = x0 + 1 == m->w ? 0 : x0 + 1;
                for (int c = 0; c < 3; c++) {
                    float top = r0[3 * x0 + c] + ax * (r0[3 * x1 + c] - r0[3 * x0 + c]);
                    float bot = r1[3 * x0 + c] + ax * (r1[3 * x1 + c] - r1[3 * x0 + c]);
                    sum[3 * i + c] += w0 * top + w1 * bot;
                }
            }
        }
        float *o = dst->rgb + (size_t)j * dst->w * 3;
        for (int i = 0; i < 3 * dst->w; i++) {
            o[i] = sum[i] / wsum;
        }
    }
}
