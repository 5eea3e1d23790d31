/* pbr_layers.h - the lobes glTF's material extensions add to the PBR
 * program (fragment stage, docs/pbr.md): KHR_materials_clearcoat's coat
 * (pbr_clearcoat.c) and KHR_materials_sheen's sheen (pbr_sheen.c), on the
 * four lanes of a quad.  pbr.c fills the inputs per quad, calls the
 * per-light and ambient parts from its own loops and the finish last;
 * KHR_materials_ior and _specular only change the base's F0 and F90 and
 * live in pbr.c.  Any thread: the state is the caller's, on its stack. */
#ifndef SR_PBR_LAYERS_H
#define SR_PBR_LAYERS_H

#include "fragment/pbr_lanes.h"

#include <stdbool.h>

typedef struct sr__pbr_layers {
    /* ior and specular: the dielectric's Fresnel at 0 and 90 degrees. */
    v4f f0[3], f90;
    bool coat, sheen;
    /* Clearcoat: weight, roughness (0..1), alpha^2 of its GGX lobe (the
     * roughness clamped as the base's), its normal (unit, facing the
     * viewer's side), N.V (raw, and clamped above 0), the visibility's
     * view half, the layer's weight clearcoat Fresnel(N.V) and what it
     * lets through, 1 - that. */
    v4f cc, cc_rc, cc_a2, cc_n[3], cc_nvr, cc_nv, cc_gv, cc_w, cc_keep;
    v4f coat_sum[3];           /* the coat lobe's radiance, before its weight */
    /* Sheen: color and roughness (0..1), its directional albedo E(N.V)
     * and 1 - max(color) E, what the base keeps under it. */
    v4f sheen_col[3], sheen_r, sheen_e, sheen_keep;
    v4f sheen_sum[3];
} sr__pbr_layers;

/* Clearcoat.  begin: from cc, cc_a2 (set) and cc_n (set) the rest; v is
 * the view direction.  light: one light's radiance rad arriving along ld
 * (unit), hs = 1 / |L + V|.  ambient: er the prefiltered radiance along
 * the coat's reflection at its roughness, times ao. */
void sr__coat_begin(sr__pbr_layers *x, const v4f v[3]);
void sr__coat_light(sr__pbr_layers *x, const v4f ld[3], v4f hs, const v4f rad[3]);
void sr__coat_ambient(sr__pbr_layers *x, const v4f er[3], v4f ao);

/* Sheen.  begin: from sheen_col and sheen_r (set) the rest; nv the base
 * normal's N.V clamped above 0.  light: nl, nh of the base normal.
 * ambient: en the irradiance (E / pi) along the base normal. */
void sr__sheen_begin(sr__pbr_layers *x, v4f nv);
void sr__sheen_light(sr__pbr_layers *x, v4f nl, v4f nv, v4f nh, const v4f rad[3]);
void sr__sheen_ambient(sr__pbr_layers *x, const v4f en[3], v4f ao);

/* The layers over the base's radiance `out`: the sheen's albedo scaling
 * and lobe, then the coat's. */
void sr__layers_finish(const sr__pbr_layers *x, v4f out[3]);

/* KHR_materials_ior: a dielectric's reflectance at normal incidence from
 * air, ((ior - 1) / (ior + 1))^2; ior 0 (absent) is 1.5's, 0.04. */
float sr__ior_f0(float ior);

/* The sheen's directional albedo E(cos, roughness) with a white sheen:
 * bilinear in the table the build computed (sheen_integrate.c). */
float sr__sheen_albedo(float n_dot_v, float roughness);

#endif
