/* explain_interp_methods.c - the three ways the course interpolates a
 * vertex value I over a triangle, each computed on its own at the pixel
 * centres the triangle covers (ex_tri_covers: the library's pixels):
 * bilinear (FillPoly's edges, then FillSpan along each span), the plane
 * equation I = a x + b y + c stepped by a per pixel and b per row, and
 * the barycentric weights from the edge functions.  On a triangle they
 * are one linear function, so they differ by float rounding only; the
 * frames (explain_interpolation.c) and the tests compare them. */
#include "explain.h"

#include <math.h>

static void uncovered(float *I, int n)
{
    for (int i = 0; i < n; i++) {
        I[i] = NAN;
    }
}

static bool covers(const ex_tri *t, int x, int y)
{
    return t->area2 != 0 && ex_tri_covers(t, (int64_t)x * 256 + 128, (int64_t)y * 256 + 128);
}

void ex_interp_bilinear(const ex_tri *t, const double in[3], int gw, int gh, float *I,
                        ex_interp_row *rows)
{
    ex_fillpoly_spans(t, in, NULL, gw, gh, I, rows);   /* explain fillpoly's walk */
}

bool ex_interp_plane_coefficients(const ex_tri *t, const double in[3], double abc[3])
{
    if (t->area2 == 0) {
        abc[0] = abc[1] = 0;
        abc[2] = in[0];
        return false;
    }
    /* I = a x + b y + c through the three vertices: Cramer's rule on
     * I1 - I0 = a dx1 + b dy1, I2 - I0 = a dx2 + b dy2, whose determinant
     * is twice the area */
    double x0 = t->x[0] / 256.0, y0 = t->y[0] / 256.0;
    double dx1 = t->x[1] / 256.0 - x0, dy1 = t->y[1] / 256.0 - y0;
    double dx2 = t->x[2] / 256.0 - x0, dy2 = t->y[2] / 256.0 - y0;
    double di1 = in[1] - in[0], di2 = in[2] - in[0], det = dx1 * dy2 - dx2 * dy1;
    abc[0] = (di1 * dy2 - di2 * dy1) / det;
    abc[1] = (dx1 * di2 - dx2 * di1) / det;
    abc[2] = in[0] - abc[0] * x0 - abc[1] * y0;
    return true;
}

void ex_interp_plane(const ex_tri *t, const double in[3], int gw, int gh, float *I,
                     double abc[3], int origin[2])
{
    uncovered(I, gw * gh);
    ex_interp_plane_coefficients(t, in, abc);
    /* step from the covered pixels' top-left corner: values near the
     * triangle, where float keeps them close */
    int bx0 = gw, by0 = gh;
    for (int y = 0; y < gh; y++) {
        for (int x = 0; x < gw; x++) {
            if (covers(t, x, y)) {
                bx0 = x < bx0 ? x : bx0;
                by0 = y < by0 ? y : by0;
            }
        }
    }
    origin[0] = bx0 < gw ? bx0 : -1;
    origin[1] = by0 < gh ? by0 : -1;
    float a = (float)abc[0], b = (float)abc[1];
    float row = (float)(abc[0] * (bx0 + 0.5) + abc[1] * (by0 + 0.5) + abc[2]);
    for (int y = by0; y < gh; y++) {
        float v = row;
        for (int x = bx0; x < gw; x++) {
            if (covers(t, x, y)) {
                I[y * gw + x] = v;
            }
            v += a;
        }
        row += b;
    }
}

void ex_interp_barycentric(const ex_tri *t, const double in[3], int gw, int gh, float *I,
                           float *lambda)
{
    uncovered(I, gw * gh);
    for (int y = 0; y < gh; y++) {
        for (int x = 0; x < gw; x++) {
            if (!covers(t, x, y)) {
                continue;
            }
            double l[3];
            ex_tri_weights(t, (int64_t)x * 256 + 128, (int64_t)y * 256 + 128, l);
            I[y * gw + x] = (float)(l[0] * in[0] + l[1] * in[1] + l[2] * in[2]);
            for (int k = 0; lambda && k < 3; k++) {
                lambda[3 * (y * gw + x) + k] = (float)l[k];
            }
        }
    }
}
