/* pbr_clearcoat.c - KHR_materials_clearcoat's coat on the PBR program's
 * four lanes (fragment stage, pbr_layers.h): a GGX lobe with its own
 * roughness and normal over the base, weighted by the coat's Fresnel at
 * its N.V as the extension's fresnel_coat, F0 0.04 (ior 1.5):
 *   out = base (1 - clearcoat Fc) + clearcoat Fc coat,
 * coat = the lobe's D V (N.L) per light and, for ambient light, the
 * prefiltered radiance times the split sum's albedo with F = 1.  Any
 * thread; the state is the caller's. */
#include "fragment/pbr_layers.h"

void sr__coat_begin(sr__pbr_layers *x, const v4f v[3])
{
    x->cc_nvr = dot3(x->cc_n, v);
    x->cc_nv = vmax(x->cc_nvr, (v4f){ 1e-4f, 1e-4f, 1e-4f, 1e-4f });
    v4f gv2 = x->cc_nv * x->cc_nv * (1.0f - x->cc_a2) + x->cc_a2;
    x->cc_gv = gv2 * rsqrt_nr(gv2);
    v4f m = 1.0f - x->cc_nv, m2 = m * m;
    v4f fc = 0.04f + 0.96f * (m2 * m2 * m);
    x->cc_w = x->cc * fc;
    x->cc_keep = 1.0f - x->cc_w;
    for (int c = 0; c < 3; c++) {
        x->coat_sum[c] = (v4f){ 0 };
    }
}

/* The base's D V in one division (shade_lanes), on the coat's normal. */
void sr__coat_light(sr__pbr_layers *x, const v4f ld[3], v4f hs, const v4f rad[3])
{
    v4f zero = { 0 }, a2 = x->cc_a2;
    v4f nlr = dot3(x->cc_n, ld);
    v4f nl = vmax(nlr, zero);
    v4f nh = vmax((nlr + x->cc_nvr) * hs, zero);
    v4f dd = nh * nh * (a2 - 1.0f) + 1.0f;
    v4f gl2 = nl * nl * (1.0f - a2) + a2;
    v4f gl = gl2 * rsqrt_nr(gl2);
    v4f dv = a2 * 0.5f * rcp_nr(PI_F * dd * dd * (nl * x->cc_gv + x->cc_nv * gl));
    for (int c = 0; c < 3; c++) {
        x->coat_sum[c] += dv * nl * rad[c];
    }
}

void sr__coat_ambient(sr__pbr_layers *x, const v4f er[3], v4f ao)
{
    v4f sa, sb;
    split_sum(x->cc_rc, x->cc_nv, &sa, &sb);
    v4f albedo = (sa + sb) * ao;
    for (int c = 0; c < 3; c++) {
        x->coat_sum[c] += er[c] * albedo;
    }
}

/* The sheen lies on the base under the coat: the sheen's albedo scaling
 * and lobe first, then the coat over both. */
void sr__layers_finish(const sr__pbr_layers *x, v4f out[3])
{
    for (int c = 0; c < 3; c++) {
        if (x->sheen) {
            out[c] = out[c] * x->sheen_keep + x->sheen_sum[c];
        }
        if (x->coat) {
            out[c] = out[c] * x->cc_keep + x->cc_w * x->coat_sum[c];
        }
    }
}
