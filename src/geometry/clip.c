/* clip.c - clipping in homogeneous clip space, before the divide (geometry
 * stage; any thread, no shared state).
 *
 * Planes (docs/raster-rules.md §4): w >= epsilon (so nothing behind or at the eye
 * reaches the divide), near, far, and the four planes of the fixed-point
 * guard band [-16384, 16384) px - never the viewport planes: the rasterizer
 * trims to the viewport exactly, so visible shared edges are untouched.
 * Sutherland-Hodgman in 4D, one plane at a time, and every intersection is
 * computed from the inside vertex towards the outside one, so two triangles
 * sharing an edge get bit-identical new vertices. */
#include "pipeline.h"

#include <math.h>

/* The planes, their order in the outcode and the band's edges are in
 * pipeline.h (SR_PLANE_*, SR_CLIP_BAND_*), shared with the vertex stage's
 * outcodes. */
#define BAND_LO SR_CLIP_BAND_LO
#define BAND_HI SR_CLIP_BAND_HI

/* Signed distance of p to a plane; inside is >= 0. */
static double plane_dist(const sr_draw_state *ds, int plane, const float pos[4])
{
    double x = pos[0], y = pos[1], z = pos[2], w = pos[3];
    switch (plane) {
    case SR_PLANE_W:      return w - SR_CLIP_W_EPSILON;
    case SR_PLANE_NEAR:   return ds->zero_to_one ? z : z + w;
    case SR_PLANE_FAR:    return w - z;
    /* x_w = ox + px x/w >= lo  <=>  px x - (lo - ox) w >= 0 (w > 0). */
    case SR_PLANE_LEFT:   return ds->vp_px * x - (BAND_LO - ds->vp_ox) * w;
    case SR_PLANE_RIGHT:  return (BAND_HI - ds->vp_ox) * w - ds->vp_px * x;
    /* y_w = oy - py y/w, y down. */
    case SR_PLANE_TOP:    return (ds->vp_oy - BAND_LO) * w - ds->vp_py * y;
    case SR_PLANE_BOTTOM: return ds->vp_py * y - (ds->vp_oy - BAND_HI) * w;
    default:           return 0.0;
    }
}

unsigned sr__clip_outcode(const sr_draw_state *ds, const float pos[4])
{
    sr_clip_planes k;
    sr__clip_planes(ds, &k);
    return sr__clip_outcode_with(&k, pos);
}

/* I = inside + t (outside - inside) for the position and every varying. */
static void intersect(const sr_clip_vertex *in, const sr_clip_vertex *out_v,
                      double d_in, double d_out, int nvary, sr_clip_vertex *res)
{
    double t = d_in / (d_in - d_out);
    for (int k = 0; k < 4; k++) {
        res->pos[k] = (float)(in->pos[k] + t * ((double)out_v->pos[k] - in->pos[k]));
    }
    for (int k = 0; k < nvary; k++) {
        res->vary[k] = (float)(in->vary[k] + t * ((double)out_v->vary[k] - in->vary[k]));
    }
}

bool sr__clip_segment(const sr_draw_state *ds, const sr_clip_vertex *a, const sr_clip_vertex *b,
                      unsigned planes, sr_clip_vertex *out_a, sr_clip_vertex *out_b)
{
    /* Parametric clipping of A + t (B - A), t in [t0, t1]. */
    double t0 = 0.0, t1 = 1.0;
    bool move_a = false, move_b = false;
    for (int p = 0; p < SR_PLANE_COUNT; p++) {
        if (!(planes & (1u << p))) {
            continue;
        }
        double da = plane_dist(ds, p, a->pos), db = plane_dist(ds, p, b->pos);
        if (da < 0.0 && db < 0.0) {
            return false;
        }
        /* An end outside a plane always moves, even when its t rounds to
         * 0 or 1; the caller discards an end that still has w <= 0. */
        if (da < 0.0) {
            t0 = fmax(t0, da / (da - db));
            move_a = true;
        } else if (db < 0.0) {
            t1 = fmin(t1, da / (da - db));
            move_b = true;
        }
    }
    if (!(t0 < t1)) {
        return false;
    }
    /* An end that moves is computed from the original A and B, the same
     * arithmetic as a polygon edge's intersection. */
    *out_a = *a;
    *out_b = *b;
    if (move_a) {
        intersect(a, b, t0, t0 - 1.0, ds->nvary, out_a);
    }
    if (move_b) {
        intersect(a, b, t1, t1 - 1.0, ds->nvary, out_b);
    }
    return true;
}

int sr__clip_polygon(const sr_draw_state *ds, const sr_clip_vertex *const in[3],
                     unsigned planes, sr_clip_vertex *out)
{
    /* Two buffers, ping-ponged plane by plane.  Each plane adds at most one
     * vertex to a convex polygon: 3 + 7 = 10 <= SR_CLIP_MAX_VERTS. */
    sr_clip_vertex buf[2][SR_CLIP_MAX_VERTS];
    const sr_clip_vertex *poly[SR_CLIP_MAX_VERTS];
    int n = 3;
    for (int i = 0; i < 3; i++) {
        poly[i] = in[i];
    }
    int which = 0;
    for (int p = 0; p < SR_PLANE_COUNT; p++) {
        if (!(planes & (1u << p))) {
            continue;
        }
        sr_clip_vertex *dst = buf[which];
        int m = 0;
        for (int i = 0; i < n; i++) {
            const sr_clip_vertex *a = poly[i];
            const sr_clip_vertex *b = poly[(i + 1) % n];
            double da = plane_dist(ds, p, a->pos);
            double db = plane_dist(ds, p, b->pos);
            bool a_in = da >= 0.0, b_in = db >= 0.0;
            if (a_in) {
                dst[m++] = *a;
            }
            if (a_in != b_in) {
                if (a_in) {
                    intersect(a, b, da, db, ds->nvary, &dst[m++]);
                } else {
                    intersect(b, a, db, da, ds->nvary, &dst[m++]);
                }
            }
        }
        n = m;
        if (n < 3) {
            return 0;
        }
        for (int i = 0; i < n; i++) {
            poly[i] = &dst[i];
        }
        which ^= 1;
    }
    for (int i = 0; i < n; i++) {
        out[i] = *poly[i];
    }
    return n;
}
