/* newell.c - geometry stage: the normal of a polygon by Newell's method.
 * Consumes the corners of a polygon in 3D (any number >= 3, planar or not);
 * produces its unnormalized normal.  Reentrant: any thread may call it.
 *
 * Each component of the sum is twice the signed area of the polygon's
 * projection on one axis plane (the trapezoid rule over its edges), so the
 * vector is twice the polygon's area vector: for a planar polygon it is
 * normal to the plane with length 2 * area, and it points to the side from
 * which the corners run counter-clockwise.  For a non-planar polygon it is
 * the normal of the plane whose projection areas it keeps, a best fit that
 * no single cross product of two edges gives.
 */
#include "softrast.h"
#include "error.h"
#include "geometry/newell.h"

#include <math.h>
sr_result sr_newell_normal(const sr_vec3 *points, int count, sr_vec3 *out)
{
    if (!out) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_newell_normal: out is NULL");
    }
    *out = (sr_vec3){ 0, 0, 0 };
    if (!points) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_newell_normal: points is NULL");
    }
    if (count < 3) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_newell_normal: count %d is less than 3", count);
    }
    for (int i = 0; i < count; i++) {
        if (!isfinite(points[i].x) || !isfinite(points[i].y) || !isfinite(points[i].z)) {
            return sr__fail(NULL, SR_INVALID_ARG, "sr_newell_normal: points[%d] is not finite", i);
        }
    }
    /* Relative to the first corner, in doubles: a small polygon far from the
     * origin would otherwise lose the digits its area lives in. */
    const sr_vec3 o = points[0];
    double n[3] = { 0, 0, 0 }, a[3] = { 0, 0, 0 };
    for (int i = 1; i <= count; i++) {
        /* The closing edge returns to the first corner, the origin here. */
        const sr_vec3 q = i < count ? points[i] : o;
        double b[3] = { (double)q.x - o.x, (double)q.y - o.y, (double)q.z - o.z };
        sr__newell_add(n, a, b);
        a[0] = b[0];
        a[1] = b[1];
        a[2] = b[2];
    }
    sr_vec3 r = { (float)n[0], (float)n[1], (float)n[2] };
    if (!isfinite(r.x) || !isfinite(r.y) || !isfinite(r.z)) {
        return sr__fail(NULL, SR_TOO_LARGE,
                        "sr_newell_normal: the points are so far apart that the normal "
                        "overflows float");
    }
    *out = r;
    return SR_OK;
}
