/* clip_view.c - clipping in view (eye) space against the six planes of the
 * view volume, the selectable reference beside clip.c (geometry stage; any
 * thread, no shared state).
 *
 * The view volume of a projection P is where every clip coordinate lies in
 * [-w, w] (z in [0, w] with depth_zero_to_one).  Written in view space
 * each bound is a plane through rows of P: near is (row w + row z) . e >= 0,
 * far (row w - row z) . e >= 0, and the four sides (row w +- row x or y).
 * For a frustum these are the near and far planes z = -n, z = -f and the
 * four side planes through the eye; for an orthographic P, the box.
 *
 * The vertex stage hands over clip positions only, so a vertex's view
 * position is recovered as e = P^-1 c.  Sutherland-Hodgman clips the
 * triangle plane by plane in view space, each intersection computed from
 * the inside vertex towards the outside one (shared edges get the same
 * points), and each new vertex is projected back with P.  The original
 * vertices keep their clip positions, so a vertex moves only where it is
 * cut.  Clipping at the side planes lands new edges on the viewport's
 * edges, which the rasterizer trims to anyway (docs/clipping.md). */
#include "pipeline.h"

#include <math.h>
#include <string.h>

/* Column-major as sr_mat4: element (row r, column c) is m[4 c + r]. */
#define AT(m, r, c) ((m)[4 * (c) + (r)])

/* Gauss-Jordan with partial pivoting, in double. */
static bool invert(const double m[16], double inv[16])
{
    double a[4][8];
    for (int r = 0; r < 4; r++) {
        for (int c = 0; c < 4; c++) {
            a[r][c] = AT(m, r, c);
            a[r][c + 4] = r == c ? 1.0 : 0.0;
        }
    }
    for (int c = 0; c < 4; c++) {
        int piv = c;
        for (int r = c + 1; r < 4; r++) {
            if (fabs(a[r][c]) > fabs(a[piv][c])) {
                piv = r;
            }
        }
        if (!(fabs(a[piv][c]) > 0.0)) {
            return false;
        }
        if (piv != c) {
            double t[8];
            memcpy(t, a[c], sizeof t);
            memcpy(a[c], a[piv], sizeof t);
            memcpy(a[piv], t, sizeof t);
        }
        double d = a[c][c];
        for (int k = 0; k < 8; k++) {
            a[c][k] /= d;
        }
        for (int r = 0; r < 4; r++) {
            if (r != c && a[r][c] != 0.0) {
                double f = a[r][c];
                for (int k = 0; k < 8; k++) {
                    a[r][k] -= f * a[c][k];
                }
            }
        }
    }
    for (int r = 0; r < 4; r++) {
        for (int c = 0; c < 4; c++) {
            AT(inv, r, c) = a[r][c + 4];
        }
    }
    return true;
}

bool sr__view_volume_matrices(const sr_mat4 *proj, double p[16], double inv[16])
{
    for (int i = 0; i < 16; i++) {
        p[i] = proj ? proj->m[i] : (i % 5 == 0 ? 1.0 : 0.0);
        if (!isfinite(p[i])) {
            return false;
        }
    }
    return invert(p, inv);
}

/* A vertex during clipping: its view position beside the clip vertex. */
typedef struct view_vertex {
    double eye[4];
    sr_clip_vertex v;
} view_vertex;

/* The view-space plane of bound `plane` (0 near, 1 far, 2 left, 3 right,
 * 4 top, 5 bottom): its clip-space coefficients q over (x, y, z, w), the
 * same as clip.c's, carried to view space as q P. */
static void view_plane(const sr_draw_state *ds, int plane, double out[4])
{
    double q[4] = { 0, 0, 0, 0 };
    switch (plane) {
    case 0: q[2] = 1; q[3] = ds->zero_to_one ? 0 : 1; break;
    case 1: q[2] = -1; q[3] = 1; break;
    case 2: q[0] = ds->vp_px; q[3] = -(SR_CLIP_BAND_LO - ds->vp_ox); break;
    case 3: q[0] = -ds->vp_px; q[3] = SR_CLIP_BAND_HI - ds->vp_ox; break;
    case 4: q[1] = -ds->vp_py; q[3] = ds->vp_oy - SR_CLIP_BAND_LO; break;
    default: q[1] = ds->vp_py; q[3] = -(ds->vp_oy - SR_CLIP_BAND_HI); break;
    }
    for (int c = 0; c < 4; c++) {
        out[c] = q[0] * AT(ds->proj, 0, c) + q[1] * AT(ds->proj, 1, c) +
                 q[2] * AT(ds->proj, 2, c) + q[3] * AT(ds->proj, 3, c);
    }
}

static double dist(const double plane[4], const double e[4])
{
    return plane[0] * e[0] + plane[1] * e[1] + plane[2] * e[2] + plane[3] * e[3];
}

/* I = inside + t (outside - inside) in view space and for every varying,
 * then c = P I. */
static void intersect(const sr_draw_state *ds, const view_vertex *in, const view_vertex *out_v,
                      double d_in, double d_out, view_vertex *res)
{
    double t = d_in / (d_in - d_out);
    for (int k = 0; k < 4; k++) {
        res->eye[k] = in->eye[k] + t * (out_v->eye[k] - in->eye[k]);
    }
    for (int r = 0; r < 4; r++) {
        double c = 0.0;
        for (int k = 0; k < 4; k++) {
            c += AT(ds->proj, r, k) * res->eye[k];
        }
        res->v.pos[r] = (float)c;
    }
    for (int k = 0; k < ds->nvary; k++) {
        res->v.vary[k] =
            (float)(in->v.vary[k] + t * ((double)out_v->v.vary[k] - in->v.vary[k]));
    }
}

int sr__clip_polygon_view(const sr_draw_state *ds, const sr_clip_vertex *const in[3],
                          sr_clip_vertex *out)
{
    /* Each of the six planes adds at most one vertex: 3 + 6 <= SR_CLIP_MAX_VERTS. */
    view_vertex buf[2][SR_CLIP_MAX_VERTS];
    int n = 3;
    for (int i = 0; i < 3; i++) {
        view_vertex *a = &buf[0][i];
        a->v = *in[i];
        for (int r = 0; r < 4; r++) {
            double e = 0.0;
            for (int k = 0; k < 4; k++) {
                e += AT(ds->proj_inv, r, k) * in[i]->pos[k];
            }
            a->eye[r] = e;
        }
    }
    int which = 0;
    for (int p = 0; p < 6; p++) {
        double plane[4];
        view_plane(ds, p, plane);
        const view_vertex *src = buf[which];
        view_vertex *dst = buf[which ^ 1];
        int m = 0;
        for (int i = 0; i < n; i++) {
            const view_vertex *a = &src[i];
            const view_vertex *b = &src[(i + 1) % n];
            double da = dist(plane, a->eye), db = dist(plane, b->eye);
            bool a_in = da >= 0.0, b_in = db >= 0.0;
            if (a_in) {
                dst[m++] = *a;
            }
            if (a_in != b_in) {
                if (a_in) {
                    intersect(ds, a, b, da, db, &dst[m++]);
                } else {
                    intersect(ds, b, a, db, da, &dst[m++]);
                }
            }
        }
        n = m;
        if (n < 3) {
            return 0;
        }
        which ^= 1;
    }
    for (int i = 0; i < n; i++) {
        out[i] = buf[which][i].v;
    }
    return n;
}
