/* pbr_transmission.h - KHR_materials_transmission and _volume for the PBR
 * program (pbr.c): the light a transmissive surface lets through, read
 * from the image of the opaque scene behind it (docs/pbr.md).  Resolved
 * once per program, read-only after: any tile worker may call it. */
#ifndef SR_PBR_TRANSMISSION_H
#define SR_PBR_TRANSMISSION_H

#include "fragment/light_lanes.h"
#include "softrast.h"

#include <stdbool.h>

typedef struct sr__transmission {
    const sr_texture *source;      /* the opaque image; NULL: the environment */
    const sr_environment *environment; /* without a source; NULL too: black */
    float eta;                     /* 1 / the material's ior: air into the volume */
    float view_projection[16];     /* column-major, world -> clip */
    float model_scale[3];          /* the model's axis lengths: thickness to world */
    float inv_exposure;            /* 2^-exposure: the source holds exposed radiance */
    float lod_scale;               /* log2 of the source's width: the roughness-1 level */
    float absorb[3];               /* -log2(attenuation color) / distance, per channel */
    bool attenuates;               /* attenuation_distance > 0 */
    float rough_scale;             /* clamp(2 ior - 2, 0, 1): the ior's share of the roughness */
    /* KHR_materials_dispersion: 1 / the ior of each of red, green and
     * blue, when the material spreads them (green's is eta). */
    bool disperses;
    float eta_rgb[3];
} sr__transmission;

/* Fills t from the material (its ior: KHR_materials_ior's, 0 the
 * default 1.5, the ior whose F0 is the base's 0.04), the program's
 * matrices, the source, the environment seen instead where there is no
 * source, and 2^exposure. */
void sr__transmission_setup(const sr_pbr_material *m, const sr_mat4 *model,
                            const sr_mat4 *view_projection, const sr_texture *source,
                            const sr_environment *environment, float exposure_scale,
                            sr__transmission *t);

/* The radiance seen through the surface at four lanes (mask: the live
 * ones): the source at the screen position of pos moved along the
 * refracted view ray by the thickness (world units, 0: straight behind),
 * at the mip level the roughness blurs it to, attenuated (Beer-Lambert)
 * along that ray.  Without a source, the environment's radiance in the
 * direction the ray leaves (refracted in a volume, straight on through
 * a thin wall), prefiltered for the roughness.  A dispersive volume
 * refracts one ray per channel, each at its own ior, and reads each
 * channel where its own ray leaves.  pos, n (unit, facing the viewer), v (unit, to the
 * eye) in world space; rough is the material's perceptual roughness.
 * ray gets the way from pos to the exit point (zero for a thin wall;
 * green's in a dispersive volume) and
 * keep the volume's transmittance along it, per channel (1 without
 * attenuation); out is already multiplied by keep.  ray_rb, when not
 * NULL, gets red's and blue's own ways in a dispersive volume (zero
 * otherwise). */
void sr__transmission_light4(const sr__transmission *t, const float pos[3][4],
                             const float n[3][4], const float v[3][4], const float rough[4],
                             const float thick[4], unsigned mask, float out[3][4],
                             float ray[3][4], float keep[3][4], float ray_rb[2][3][4]);

/* The share of a punctual light's radiance that a transmissive surface
 * sends towards the eye at four lanes, the sample viewer's BTDF
 * (getPunctualRadianceTransmission): the light mirrored through the
 * surface, a GGX lobe (D times the height-correlated visibility) about
 * the mirrored light and the view at the roughness the ior scales, times
 * 1 - F at V.H with the dielectric's f0 and f90.  l (unit, to the light),
 * n and v as for sr__transmission_light4; a light on the viewer's side
 * of the surface sends nothing through. */
void sr__transmission_btdf4(const sr__transmission *t, const v4f n[3], const v4f v[3],
                            const v4f l[3], v4f rough, const v4f f0[3], v4f f90, v4f out[3]);

#endif
