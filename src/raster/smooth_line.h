/* smooth_line.h - raster stage, internal: the walk of an antialiased line
 * of the 3D pipeline (sr_state.smooth_lines) over a rectangle of pixels.
 * Consumes the segment in q8 and half its width; produces each pixel
 * within reach with its projection t and coverage through a callback.
 * sr__raster_line (line.c, tile workers) shades those pixels;
 * sr_smooth_line_pixels hands them to a program (softrast explain), so
 * both see the same pixels and numbers.  Pure: any thread may call it. */
#ifndef SR_RASTER_SMOOTH_LINE_H
#define SR_RASTER_SMOOTH_LINE_H

#include "softrast.h"

#include <math.h>
#include <stdint.h>

/* Every pixel of [rx0, rx1) x [ry0, ry1) whose centre lies within half
 * the width plus half a pixel of the segment, with coverage falling
 * linearly over the last pixel (a box filter across the edge); round
 * ends come from clamping the projection to the segment.  Walks, per
 * major-axis column, only the rows the line can reach.  Inline, so the
 * rasterizer's callback is inlined into the loop. */
static inline __attribute__((always_inline)) void
sr__smooth_line_walk(int64_t xa_q8, int64_t ya_q8, int64_t xb_q8, int64_t yb_q8,
                     float half_width, int rx0, int ry0, int rx1, int ry1,
                     void (*fn)(void *, const sr_line_pixel_info *), void *user)
{
    const double S = 256.0;
    double ax = xa_q8 / S, ay = ya_q8 / S;
    double dx = (xb_q8 - xa_q8) / S, dy = (yb_q8 - ya_q8) / S;
    double len2 = dx * dx + dy * dy;
    bool xmajor = fabs(dx) >= fabs(dy);
    double reach = half_width + 0.5;
    int k0 = xmajor ? rx0 : ry0, k1 = xmajor ? rx1 : ry1;
    for (int k = k0; k < k1; k++) {
        /* The band of minor rows within reach at this column's centre. */
        double c = k + 0.5;
        double t_c = xmajor ? (dx != 0.0 ? (c - ax) / dx : 0.0) : (dy != 0.0 ? (c - ay) / dy : 0.0);
        t_c = t_c < 0.0 ? 0.0 : t_c > 1.0 ? 1.0 : t_c;
        double minor = xmajor ? ay + t_c * dy : ax + t_c * dx;
        double slope = xmajor ? (dx != 0.0 ? fabs(dy / dx) : 0.0) : (dy != 0.0 ? fabs(dx / dy) : 0.0);
        double span = reach * sqrt(1.0 + slope * slope) + 1.0;
        int j0 = (int)floor(minor - span), j1 = (int)ceil(minor + span);
        int lo = xmajor ? ry0 : rx0, hi = xmajor ? ry1 : rx1;
        j0 = j0 > lo ? j0 : lo;
        j1 = j1 < hi ? j1 : hi;
        for (int j = j0; j < j1; j++) {
            int px = xmajor ? k : j, py = xmajor ? j : k;
            double cx = px + 0.5 - ax, cy = py + 0.5 - ay;
            double t = len2 > 0.0 ? (cx * dx + cy * dy) / len2 : 0.0;
            t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
            double ex = cx - t * dx, ey = cy - t * dy;
            double dist = sqrt(ex * ex + ey * ey);
            double cov = reach - dist;
            if (cov <= 0.0) {
                continue;
            }
            sr_line_pixel_info p = { .y_major = !xmajor, .x = px, .y = py, .major = k, .t = t,
                                     .distance = dist, .reach = reach,
                                     .coverage = cov < 1.0 ? (float)cov : 1.0f };
            fn(user, &p);
        }
    }
}

#endif
