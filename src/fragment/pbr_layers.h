/* pbr_layers.h - the lobes glTF's material extensions add to the PBR
 * program (fragment stage, docs/pbr.md): KHR_materials_clearcoat's coat
 * (pbr_clearcoat.c), KHR_materials_sheen's sheen (pbr_sheen.c), and the
 * base lobe's changes, KHR_materials_anisotropy's stretched highlight
 * (pbr_anisotropy.c) and KHR_materials_iridescence's thin-film Fresnel
 * (pbr_iridescence.c), on the four lanes of a quad.  pbr.c fills the inputs per quad, calls the
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
    bool aniso, irid;
    /* Anisotropy: strength (0..1), the stretch's direction T and B = N x T
     * (unit, world), the GGX alphas along them, T.V, B.V and the
     * visibility's view half (without N.L). */
    v4f an_s, an_t[3], an_b[3], an_at, an_ab, an_tv, an_bv, an_gv;
    /* Iridescence: weight, film thickness (nm), the film's index, and
     * from begin the film's Fresnel at N.V and the F0 that gives it in
     * Schlick's form (for the split sum). */
    v4f ir_w, ir_thick;
    float ir_ior;
    v4f ir_f[3], ir_f0[3];
    /* Diffuse transmission: its share of the diffuse lobe (0..1), the
     * color of the light it lets through (after the volume's absorption),
     * the volume's thickness (object space: the factor times the
     * texture's G) and the key light's visibility from the surface's far
     * side. */
    bool dtrans;
    v4f dt, dt_col[3], dt_thick, dt_shadow;
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

/* Anisotropy.  begin: from an_s, an_t and an_b (set) and the base's
 * alpha (roughness squared) the rest.  dv: D times V of the anisotropic
 * GGX lobe for one light along ld (hs = 1 / |L + V|, nl, nv, nh of the
 * base normal).  bent: the normal whose reflection the image-based light
 * reads, bent towards B by the stretch (rc the roughness in 0..1). */
void sr__aniso_begin(sr__pbr_layers *x, v4f alpha, const v4f v[3], v4f nv);
v4f sr__aniso_dv(const sr__pbr_layers *x, const v4f ld[3], v4f hs, v4f nl, v4f nv, v4f nh);
void sr__aniso_bent(const sr__pbr_layers *x, const v4f n[3], const v4f v[3], v4f rc,
                    v4f out[3]);

/* Iridescence.  begin: from ir_thick and ir_ior (set), N.V in 0..1, the
 * dielectric's F0, the base color (the metal's F0) and metallic the
 * film's ir_f and ir_f0: one film over each F0, mixed by metallic, the
 * film under the coat (its ior 1.5 above it, not air's) by the coat's factor. */
void sr__iridescence_begin(sr__pbr_layers *x, v4f nv, const v4f f0d[3], const v4f base[3],
                           v4f metal);

/* Diffuse transmission: one light's radiance rad arriving from behind
 * the surface (nlr = N.L < 0 and lv = L.V of its unit vector L) through the Lambert BTDF
 * of color cback (the lobe's color, share and dielectric weight), times
 * 1 - F where the light leaves towards the viewer: Schlick's F (f0, f90)
 * at V.H of the light mirrored through the surface, with the thin film's
 * Fresnel at N.V mixed in by its weight where x has a film (the
 * reflected diffuse's F, so that the film weighs the specular layer
 * against both of the base's lobes).  Added to out. */
void sr__diffuse_btdf_light(const sr__pbr_layers *x, const v4f n[3], const v4f v[3], v4f nlr,
                            v4f lv, const v4f f0[3], v4f f90, const v4f cback[3],
                            const v4f rad[3], v4f out[3]);

/* The thin film's reflectance (Belcour and Barla 2017) at the cosine
 * cos1 of the view to the normal, over a base of Fresnel f0 (RGB), for a
 * film thickness_nm thick of index film_ior between air and the base. */
void sr__thin_film(float cos1, float thickness_nm, float film_ior, const float f0[3],
                   float out[3]);

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
