/* newell.h - geometry stage: one edge's term of Newell's polygon normal,
 * shared by the public sr_newell_normal and the OBJ reader's triangulation
 * (which keeps its corners as doubles relative to the first one). */
#ifndef SR_GEOMETRY_NEWELL_H
#define SR_GEOMETRY_NEWELL_H

/* Adds the term of edge a -> b:
 *   ((y_a - y_b)(z_a + z_b), (z_a - z_b)(x_a + x_b), (x_a - x_b)(y_a + y_b)),
 * twice the signed area the edge sweeps to each axis plane. */
static inline void sr__newell_add(double n[3], const double a[3], const double b[3])
{
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
}

#endif
