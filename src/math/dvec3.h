/* dvec3.h - cross and dot products of three doubles, for the code that
 * works in double where float would lose the answer: surface normals of
 * small or thin patches and triangles (geometry), and the Python
 * package's ray-plane intersections.  Header-only; any thread.  Internal
 * to the library and its Python extension. */
#ifndef SR_MATH_DVEC3_H
#define SR_MATH_DVEC3_H

static inline void sr__dcross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static inline double sr__ddot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

#endif
