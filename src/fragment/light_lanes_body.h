/* light_lanes_body.h - sr__light (shade.c) on the lanes of a vector, the
 * body of light_lanes.h written once for every lane count: the includer
 * names the vector types (SR_LL_F float lanes, SR_LL_I their comparison
 * masks), the lane select and correctly rounded square root (SR_LL_SEL,
 * SR_LL_SQRT), the function (SR_LL_NAME) and its target attribute
 * (SR_LL_TARGET), and the body undefines them at its end.  No include
 * guard: included once per width.
 *
 * Exactness: each lane performs the scalar function's operations in the
 * same order (no FMA: the build uses -ffp-contract=off), and where the
 * scalar code skips a light (`continue`) the lane keeps its sums through
 * a select, with the same comparisons, NaN included: the scalar code goes
 * on when n.l is NaN (it tests n.l <= 0), so the lanes test !(n.l <= 0).
 * Whole-number shininess only (ds->shininess_int >= 0): powf has no
 * lane-exact vector twin. */

/* out = sr__light(ds, n, eye, dif) lane by lane; n, eye and dif are the
 * lanes' components (x, y, z; r, g, b, a). */
static inline __attribute__((always_inline)) SR_LL_TARGET void
SR_LL_NAME(const sr_draw_state *ds, const SR_LL_F n[3], const SR_LL_F eye[3], const SR_LL_F dif[4],
           SR_LL_F out[4])
{
    const SR_LL_F zero = { 0 };
    SR_LL_F r = ds->ambient[0] * dif[0], g = ds->ambient[1] * dif[1], b = ds->ambient[2] * dif[2];
    SR_LL_F v[3] = { zero, zero, zero + 1.0f };
    if (ds->local_viewer) {
        SR_LL_F len = SR_LL_SQRT(eye[0] * eye[0] + eye[1] * eye[1] + eye[2] * eye[2]);
        SR_LL_I ok = len > zero;
        for (int k = 0; k < 3; k++) {
            v[k] = SR_LL_SEL(ok, -eye[k] / len, v[k]);
        }
    }
    bool spec = ds->specular[0] > 0.0f || ds->specular[1] > 0.0f || ds->specular[2] > 0.0f;
    for (int i = 0; i < ds->light_count; i++) {
        const sr_light_eye *lt = &ds->lights[i];
        SR_LL_F l[3];
        SR_LL_I use = (SR_LL_I){ 0 } - 1;
        if (lt->point) {
            for (int k = 0; k < 3; k++) {
                l[k] = lt->vec[k] - eye[k];
            }
            SR_LL_F len = SR_LL_SQRT(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
            use = len > zero;
            for (int k = 0; k < 3; k++) {
                l[k] = l[k] / len;
            }
        } else {
            for (int k = 0; k < 3; k++) {
                l[k] = zero + lt->vec[k];
            }
        }
        SR_LL_F ndotl = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
        use &= ~(ndotl <= zero);
        SR_LL_F kd = ndotl;
        r = SR_LL_SEL(use, r + lt->color[0] * dif[0] * kd, r);
        g = SR_LL_SEL(use, g + lt->color[1] * dif[1] * kd, g);
        b = SR_LL_SEL(use, b + lt->color[2] * dif[2] * kd, b);
        if (spec) {
            SR_LL_F h[3] = { l[0] + v[0], l[1] + v[1], l[2] + v[2] };
            SR_LL_F hl = SR_LL_SQRT(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
            SR_LL_I hs = use & (hl > zero);
            SR_LL_F ndoth = (n[0] * h[0] + n[1] * h[1] + n[2] * h[2]) / hl;
            hs &= ndoth > zero;
            SR_LL_F x = ndoth, p = zero + 1.0f;
            for (int e = ds->shininess_int; e; e >>= 1) {
                if (e & 1) {
                    p *= x;
                }
                x *= x;
            }
            r = SR_LL_SEL(hs, r + lt->color[0] * ds->specular[0] * p, r);
            g = SR_LL_SEL(hs, g + lt->color[1] * ds->specular[1] * p, g);
            b = SR_LL_SEL(hs, b + lt->color[2] * ds->specular[2] * p, b);
        }
    }
    out[0] = r;
    out[1] = g;
    out[2] = b;
    out[3] = dif[3];
}

#undef SR_LL_F
#undef SR_LL_I
#undef SR_LL_SEL
#undef SR_LL_SQRT
#undef SR_LL_NAME
#undef SR_LL_TARGET
