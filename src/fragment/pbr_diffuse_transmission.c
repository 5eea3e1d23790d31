/* pbr_diffuse_transmission.c - KHR_materials_diffuse_transmission on the
 * PBR program's four lanes (fragment stage, pbr_layers.h): the Lambert
 * BTDF that lets a punctual light behind a thin or dense surface through
 * to the viewer.  pbr.c splits the diffuse lobe and does the image-based
 * part (the irradiance along -N) itself.  Any thread. */
#include "fragment/pbr_layers.h"

void sr__diffuse_btdf_light(const sr__pbr_layers *x, const v4f n[3], const v4f v[3], v4f nlr,
                            v4f lv, const v4f f0[3], v4f f90, const v4f cback[3],
                            const v4f rad[3], v4f out[3])
{
    v4f zero = { 0 };
    /* Lambert about -N: only a light behind the surface shines through. */
    v4f nb = vmax(-nlr, zero);
    /* The light leaves towards the viewer as if it came from its mirror
     * image through the surface, lm = L - 2 (N.L) N: that side's Fresnel,
     * at V.H of lm (|lm + V|^2 = 2 + 2 lm.V), is what the surface keeps
     * from passing.  A light straight behind, seen straight on, has H = N
     * where L + V itself would be zero. */
    v4f lmv = lv - 2.0f * nlr * dot3(n, v);
    v4f hl = 2.0f + 2.0f * lmv;
    v4f hs = sr__v4_sel(hl > 1e-12f, rsqrt_nr(vmax(hl, 1e-12f - zero)), zero);
    v4f vh = vclamp((1.0f + lmv) * hs, 0.0f, 1.0f);
    v4f w = 1.0f - vh, w2 = w * w, fw = w2 * w2 * w;
    for (int c = 0; c < 3; c++) {
        v4f f = f0[c] + (f90 - f0[c]) * fw;
        if (x->irid) {
            /* KHR_materials_iridescence replaces the Fresnel of the
             * dielectric's fresnel_mix, whose base the extension's BTDF
             * is part of (KHR_materials_diffuse_transmission). */
            f += x->ir_w * (x->ir_f[c] - f);
        }
        out[c] += (1.0f - f) * cback[c] * (1.0f / PI_F) * rad[c] * nb;
    }
}
