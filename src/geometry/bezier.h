/* bezier.h - geometry stage, built-in surfaces: internals of bezier.c that
 * the tests use.  Consumes one bicubic Bezier patch (16 control points,
 * [u][v] row-major, xyz); produces a point and its two partial derivatives.
 * Pure functions, callable from any thread. */
#ifndef SR_GEOMETRY_BEZIER_H
#define SR_GEOMETRY_BEZIER_H

/* Direct evaluation with the cubic Bernstein polynomials
 * B0 = (1-t)^3, B1 = 3t(1-t)^2, B2 = 3t^2(1-t), B3 = t^3 (in double
 * precision), at parameters (u, v) in [0, 1]:
 *   pos = sum_ij B_i(u) B_j(v) cp[4i+j],  du = dpos/du,  dv = dpos/dv.
 * This is the slow, obviously correct reference the forward-difference
 * tessellator is tested against; it is also its fallback at points where
 * du x dv vanishes.  Any of pos, du, dv may be NULL. */
void sr__bezier_eval_direct(const float cp[16][3], float u, float v,
                            float pos[3], float du[3], float dv[3]);

#endif
