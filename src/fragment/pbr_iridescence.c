/* pbr_iridescence.c - KHR_materials_iridescence on the PBR program's four
 * lanes (fragment stage, pbr_layers.h): a dielectric film between air (or
 * a clear coat) and the base whose two reflections interfere, Belcour and Barla's
 * "A Practical Extension to Microfacet Theory for the Modeling of Varying
 * Iridescence" (2017) as the extension's appendix and the glTF Sample
 * Viewer write it: the Airy series to its second order, each order's
 * spectrum integrated against Gaussian fits of the CIE 1931 matching
 * functions in closed form, to linear Rec. 709.  Per lane (cosines and
 * exponentials), for iridescent materials only.  Any thread. */
#include "fragment/pbr_layers.h"

#include <math.h>

static float sq(float a)
{
    return a * a;
}

static float schlick(float f0, float cos_theta)
{
    float m = 1.0f - cos_theta, m2 = m * m;
    return f0 + (1.0f - f0) * (m2 * m2 * m);
}

/* The Fourier transform of the matching functions at an optical path
 * difference opd (nm) with the phases shift (radians, per XYZ term), as
 * linear Rec. 709: what one order of the series adds per unit
 * amplitude.  The Gaussians' centres, variances and weights are the
 * paper's fit. */
static void sensitivity(float opd, const float shift[3], float rgb[3])
{
    static const float val[3] = { 5.4856e-13f, 4.4201e-13f, 5.2481e-13f };
    static const float pos[3] = { 1.6810e+06f, 1.7953e+06f, 2.2084e+06f };
    static const float var[3] = { 4.3278e+09f, 9.3046e+09f, 6.6121e+09f };
    float phase = 2.0f * PI_F * opd * 1.0e-9f, xyz[3];
    for (int k = 0; k < 3; k++) {
        xyz[k] = val[k] * sqrtf(2.0f * PI_F * var[k]) * cosf(pos[k] * phase + shift[k]) *
                 expf(-sq(phase) * var[k]);
    }
    xyz[0] += 9.7470e-14f * sqrtf(2.0f * PI_F * 4.5282e+09f) *
              cosf(2.2399e+06f * phase + shift[0]) * expf(-4.5282e+09f * sq(phase));
    for (int k = 0; k < 3; k++) {
        xyz[k] /= 1.0685e-7f;
    }
    rgb[0] = 3.2404542f * xyz[0] - 1.5371385f * xyz[1] - 0.4985314f * xyz[2];
    rgb[1] = -0.9692660f * xyz[0] + 1.8760108f * xyz[1] + 0.0415560f * xyz[2];
    rgb[2] = 0.0556434f * xyz[0] - 0.2040259f * xyz[1] + 1.0572252f * xyz[2];
}

/* The film under a medium of index n1 above it: air (1), or a clear
 * coat (1.5). */
static void film_under(float n1, float cos1, float thickness_nm, float film_ior, const float f0[3],
                       float out[3])
{
    /* The film's index goes to the medium's above as the film vanishes,
     * so a film of no thickness is the base alone. */
    float t = clamp01(thickness_nm / 0.03f), step = t * t * (3.0f - 2.0f * t);
    float eta = n1 + (film_ior - n1) * step;
    float cos2sq = 1.0f - sq(n1 / eta) * (1.0f - sq(cos1));
    if (cos2sq < 0.0f) {
        out[0] = out[1] = out[2] = 1.0f;    /* total internal reflection */
        return;
    }
    float cos2 = sqrtf(cos2sq);
    /* Above to film: reflected R12, through both ways T121; a phase of
     * pi on reflection off the denser side. */
    float r12 = schlick(sq((eta - n1) / (eta + n1)), cos1), t121 = 1.0f - r12;
    float phi21 = eta < n1 ? 0.0f : PI_F;
    float opd = 2.0f * eta * thickness_nm * cos2;
    float r23[3], phi[3];
    for (int c = 0; c < 3; c++) {
        /* The base's index from its F0 as seen from air. */
        float s = sqrtf(min_f(max_f(f0[c], 0.0f), 0.9999f));
        float n3 = (1.0f + s) / (1.0f - s);
        r23[c] = schlick(sq((n3 - eta) / (n3 + eta)), cos2);
        phi[c] = phi21 + (n3 < eta ? PI_F : 0.0f);
    }
    float cm[3], r123[3];
    for (int c = 0; c < 3; c++) {
        float rr = min_f(max_f(r12 * r23[c], 1e-5f), 0.9999f);
        r123[c] = sqrtf(rr);
        float rs = sq(t121) * r23[c] / (1.0f - rr);
        out[c] = r12 + rs;              /* the incoherent sum, order 0 */
        cm[c] = rs - t121;
    }
    for (int m = 1; m <= 2; m++) {
        float sh[3] = { (float)m * phi[0], (float)m * phi[1], (float)m * phi[2] }, s[3];
        sensitivity((float)m * opd, sh, s);
        for (int c = 0; c < 3; c++) {
            cm[c] *= r123[c];
            out[c] += cm[c] * 2.0f * s[c];
        }
    }
    for (int c = 0; c < 3; c++) {
        out[c] = max_f(out[c], 0.0f);   /* outside the gamut */
    }
}

void sr__thin_film(float cos1, float thickness_nm, float film_ior, const float f0[3],
                   float out[3])
{
    film_under(1.0f, cos1, thickness_nm, film_ior, f0, out);
}

/* Under a clear coat the film's upper medium is the coat (ior 1.5, its
 * F0 of 0.04), not air: the extension says so.  A partial coat mixes
 * the film under it and the film under air by the coat's factor. */
static void film_coated(float coat, float cos1, float thickness_nm, float film_ior,
                        const float f0[3], float out[3])
{
    float a[3] = { 0, 0, 0 }, b[3] = { 0, 0, 0 };
    if (coat < 1.0f) {
        film_under(1.0f, cos1, thickness_nm, film_ior, f0, a);
    }
    if (coat > 0.0f) {
        film_under(1.5f, cos1, thickness_nm, film_ior, f0, b);
    }
    for (int c = 0; c < 3; c++) {
        out[c] = coat <= 0.0f ? a[c] : coat >= 1.0f ? b[c] : a[c] + (b[c] - a[c]) * coat;
    }
}

/* The film's Fresnel at N.V over the dielectric's F0 and over the
 * metal's (its base color), mixed by metallic: the extension replaces
 * the Fresnel term of each of glTF's two BRDFs, which Appendix B mixes
 * by metallic, and the film is not linear in the F0 beneath it (three.js
 * does the same; a single film over the mixed F0 colours a half-metal
 * differently).  A lane that is all one or the other computes one film. */
static void film_mix(float nv, float thick, float ior, const float f0d[3], const float base[3],
                     float metal, float coat, float out[3])
{
    float m = clamp01(metal), d[3] = { 0, 0, 0 }, k[3] = { 0, 0, 0 };
    if (m < 1.0f) {
        film_coated(coat, nv, thick, ior, f0d, d);
    }
    if (m > 0.0f) {
        film_coated(coat, nv, thick, ior, base, k);
    }
    for (int c = 0; c < 3; c++) {
        out[c] = m <= 0.0f ? d[c] : m >= 1.0f ? k[c] : d[c] + (k[c] - d[c]) * m;
    }
}

/* ir_f0 inverts Schlick's form at N.V, F = F0 + (1 - F0) (1 - N.V)^5, as
 * three.js does, so that the split sum's albedo scales the film's color. */
void sr__iridescence_begin(sr__pbr_layers *x, v4f nv, const v4f f0d[3], const v4f base[3],
                           v4f metal)
{
    for (int i = 0; i < 4; i++) {
        float fd[3] = { f0d[0][i], f0d[1][i], f0d[2][i] };
        float b[3] = { base[0][i], base[1][i], base[2][i] }, f[3];
        film_mix(nv[i], x->ir_thick[i], x->ir_ior, fd, b, metal[i],
                 x->coat ? clamp01(x->cc[i]) : 0.0f, f);
        float m = 1.0f - nv[i], m2 = m * m, m5 = m2 * m2 * m;
        for (int c = 0; c < 3; c++) {
            x->ir_f[c][i] = f[c];
            x->ir_f0[c][i] = m5 < 1.0f ? clamp01((f[c] - m5) / (1.0f - m5)) : f[c];
        }
    }
}
