/* texture_slot.c - a material's texture slot (sr_texture_slot): its
 * KHR_texture_transform as the 2x3 matrix the PBR program applies per
 * fragment (pbr.c), and applied to coordinate arrays for the pipelines
 * that interpolate coordinates already transformed.  Pure functions; any
 * thread. */
#include "context.h"
#include "fragment/texture.h"

#include <math.h>

void sr__texture_slot_matrix(const sr_texture_slot *slot, float xf[6])
{
    float sx = slot->scale[0], sy = slot->scale[1];
    /* A zeroed slot (a C user's) is the identity; a set scale of 0 is
     * the extension's, every coordinate on the offset's texel. */
    if (!slot->scale_set && sx == 0.0f && sy == 0.0f) {
        sx = sy = 1.0f;
    }
    float c = cosf(slot->rotation), s = sinf(slot->rotation);
    xf[0] = c * sx;
    xf[1] = -s * sy;
    xf[2] = slot->offset[0];
    xf[3] = s * sx;
    xf[4] = c * sy;
    xf[5] = slot->offset[1];
}

sr_result sr_texture_slot_uv(sr_context *ctx, const sr_texture_slot *slot, const float *uv,
                             size_t count, float *out)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_texture_slot_uv: ctx is NULL");
    }
    if (!slot || (count > 0 && (!uv || !out))) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_texture_slot_uv: %s is NULL",
                        !slot ? "slot" : !uv ? "uv" : "out");
    }
    if (!isfinite(slot->offset[0]) || !isfinite(slot->offset[1]) ||
        !isfinite(slot->scale[0]) || !isfinite(slot->scale[1]) || !isfinite(slot->rotation)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_texture_slot_uv: the transform is not finite");
    }
    float xf[6];
    sr__texture_slot_matrix(slot, xf);
    for (size_t i = 0; i < count; i++) {
        /* The order of pbr.c's sample_slot, for the same roundings. */
        float s = uv[2 * i], t = uv[2 * i + 1];
        out[2 * i] = xf[0] * s + xf[1] * t + xf[2];
        out[2 * i + 1] = xf[3] * s + xf[4] * t + xf[5];
    }
    return SR_OK;
}
