/* affine2.h - math: the inverse of a 2D affine map (x' = a x + c y + e,
 * y' = b x + d y + f, as m[0..5] = a b c d e f), shared by the paint
 * fills (draw2d/paint_api.c) and the SVG reader (io/svg.c). */
#ifndef SR_MATH_AFFINE2_H
#define SR_MATH_AFFINE2_H

#include <math.h>
#include <stdbool.h>

/* inv = m^-1; false when |det| <= min_det (singular for the caller) or
 * the inverse is not finite.  A map so large that its determinant or the
 * products of its translation overflow (an image zoomed 1e300 times) is
 * inverted with its linear part scaled by a power of two, exactly; other
 * maps by the plain formula, their bits as before. */
static inline bool sr__affine2_invert(const double m[6], double min_det, double inv[6])
{
    double a = m[0], b = m[1], c = m[2], d = m[3], e = m[4], f = m[5];
    double det = a * d - b * c;
    if (isfinite(det) && !(fabs(det) > min_det)) {
        return false;
    }
    bool ok = isfinite(det);
    if (ok) {
        inv[0] = d / det;
        inv[1] = -b / det;
        inv[2] = -c / det;
        inv[3] = a / det;
        inv[4] = (c * f - d * e) / det;
        inv[5] = (b * e - a * f) / det;
        for (int i = 0; i < 6; i++) {
            ok = ok && isfinite(inv[i]);
        }
    }
    if (ok) {
        return true;
    }
    int k = 0;
    (void)frexp(fmax(fmax(fabs(a), fabs(b)), fmax(fabs(c), fabs(d))), &k);
    a = ldexp(a, -k), b = ldexp(b, -k), c = ldexp(c, -k), d = ldexp(d, -k);
    double det_k = a * d - b * c;
    if (!(det_k != 0) || !isfinite(det_k)) {
        return false;
    }
    inv[0] = ldexp(d / det_k, -k);
    inv[1] = ldexp(-b / det_k, -k);
    inv[2] = ldexp(-c / det_k, -k);
    inv[3] = ldexp(a / det_k, -k);
    inv[4] = -(inv[0] * e + inv[2] * f);
    inv[5] = -(inv[1] * e + inv[3] * f);
    ok = true;
    for (int i = 0; i < 6; i++) {
        ok = ok && isfinite(inv[i]);
    }
    return ok;
}

#endif
