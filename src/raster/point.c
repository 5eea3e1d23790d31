/* point.c - points in the 3D pipeline (raster stage): setup of a point
 * into a binned record (front-end workers) and its square or disc within
 * one tile (tile workers).  A pixel is covered when its centre lies in
 * the half-open square, or strictly inside the disc, decided in exact
 * integers; multisampled, each sample decides. */
#include "fragment/msaa_ops.h"

#include <math.h>
#include <string.h>

#define H SR_SUBPIXEL_HALF
#define S SR_SUBPIXEL_ONE

static int clampi(int64_t v, int lo, int hi)
{
    return v < lo ? lo : v > hi ? hi : (int)v;
}

bool sr__setup_point(const sr_draw_state *ds, const sr_window_vertex *v, double offset,
                     bool front, int ninterp, const float flat[4], sr_point *p)
{
    /* The square's edges snap to q8: [lo, hi) on both axes. */
    int64_t half = (int64_t)nearbyint(ds->point_size * (S / 2));
    int64_t lox = v->x_q8 - half, hix = v->x_q8 + half;
    int64_t loy = v->y_q8 - half, hiy = v->y_q8 + half;
    p->h.kind = SR_KIND_POINT;
    p->cx = v->x_q8;
    p->cy = v->y_q8;
    p->half = (int32_t)half;
    p->radius2 = ds->round_points ? half * half : 0;
    p->smooth_radius = ds->smooth_points ? (float)(ds->point_size * 0.5) : 0.0f;
    /* The box of pixels that can be covered, in the way this point is
     * sampled, and only then trimmed to the draw rectangle (viewport,
     * scissor, framebuffer): it bounds the raster loop and decides the
     * tiles the point is binned into, so it must hold every pixel with a
     * covered sample, not only those whose centre is covered. */
    int64_t x0, x1, y0, y1;
    if (ds->samples > 1) {
        /* Multisampled: each sample inside the square or disc decides
         * (smooth points become discs, as GL ignores smoothing under
         * multisampling).  Samples lie inside their pixel's square, so
         * the box holds every pixel whose square meets [lo, hi) - also
         * when the square holds no pixel centre at all, or only centres
         * outside the rectangle. */
        p->radius2 = ds->round_points || ds->smooth_points ? half * half : 0;
        p->smooth_radius = 0.0f;
        x0 = sr__floor_div(lox, S);
        x1 = sr__floor_div(hix - 1, S) + 1;
        y0 = sr__floor_div(loy, S);
        y1 = sr__floor_div(hiy - 1, S) + 1;
    } else if (p->smooth_radius > 0.0f) {
        /* The ramp reaches half a pixel past the radius: the pixels whose
         * centre lies within, even when the square holds none. */
        int64_t reach = half + H;
        x0 = sr__ceil_div(v->x_q8 - reach - H, S);
        x1 = sr__floor_div(v->x_q8 + reach - H, S) + 1;
        y0 = sr__ceil_div(v->y_q8 - reach - H, S);
        y1 = sr__floor_div(v->y_q8 + reach - H, S) + 1;
    } else {
        /* A pixel is covered when its centre lies in [lo, hi) on both
         * axes (the top-left rule for a square); a disc lies inside. */
        x0 = sr__ceil_div(lox - H, S);
        x1 = sr__ceil_div(hix - H, S);
        y0 = sr__ceil_div(loy - H, S);
        y1 = sr__ceil_div(hiy - H, S);
    }
    p->h.x0 = clampi(x0, ds->rect_x0, ds->rect_x1);
    p->h.x1 = clampi(x1, ds->rect_x0, ds->rect_x1);
    p->h.y0 = clampi(y0, ds->rect_y0, ds->rect_y1);
    p->h.y1 = clampi(y1, ds->rect_y0, ds->rect_y1);
    if (p->h.x0 >= p->h.x1 || p->h.y0 >= p->h.y1) {
        return false;
    }
    p->z = (v->z + offset) * ds->depth_scale;
    p->front = front;
    p->ninterp = ninterp;
    if (ninterp > 0) {
        memcpy(p->vary, v->vary, (size_t)ninterp * sizeof(float));
    }
    if (flat) {
        memcpy(p->flat, flat, sizeof p->flat);
    }
    return true;
}

/* A multisampled point: each sample inside the half-open square
 * [c - half, c + half) or strictly inside the disc, in exact integers;
 * one depth and one shading for the pixel. */
static void raster_point_samples(const sr_draw_state *ds, const sr_point *p, int rx0, int ry0,
                                 int rx1, int ry1, sr_frag_stats *st)
{
    size_t n = (size_t)ds->samples;
    bool late = ds->program && (ds->program->writes_depth || ds->program->may_discard);
    for (int py = ry0; py < ry1; py++) {
        for (int px = rx0; px < rx1; px++) {
            size_t base = ((size_t)py * (size_t)ds->fb->width + (size_t)px) * n;
            double z = p->z;
            float c[4];
            if (late && !sr__program_shade_one(ds, p->vary, p->front, px, py, &z, c)) {
                continue;
            }
            uint32_t q = sr__quantize_depth(ds, &z);
            unsigned pass = 0;
            for (size_t s = 0; s < n; s++) {
                int64_t dx = sr__centre_q8(px) + ds->sample_off[s][0] - p->cx;
                int64_t dy = sr__centre_q8(py) + ds->sample_off[s][1] - p->cy;
                bool in = p->radius2 ? dx * dx + dy * dy < p->radius2
                                     : dx >= -p->half && dx < p->half && dy >= -p->half &&
                                           dy < p->half;
                if (in && sr__sample_test(ds, base + s, q, p->front, true)) {
                    pass |= 1u << s;
                }
            }
            if (pass) {
                if (ds->program && !late) {
                    (void)sr__program_shade_one(ds, p->vary, p->front, px, py, &z, c);
                } else if (!ds->program) {
                    sr__shade_vary(ds, p->vary, p->flat, p->front, z, 0.0f, c, ds->shading);
                }
                sr__write_samples(ds, base, pass, c, &ds->blend);
                st->fragments += (uint64_t)__builtin_popcount(pass);
            }
        }
    }
}

void sr__raster_point(const sr_draw_state *ds, const sr_point *p, int rx0, int ry0, int rx1,
                      int ry1, sr_frag_stats *st)
{
    if (ds->samples > 1) {
        raster_point_samples(ds, p, rx0, ry0, rx1, ry1, st);
        return;
    }
    for (int py = ry0; py < ry1; py++) {
        for (int px = rx0; px < rx1; px++) {
            if (p->radius2) {
                /* A disc: the pixel centre strictly inside the circle,
                 * decided in exact integers. */
                int64_t dx = sr__centre_q8(px) - p->cx, dy = sr__centre_q8(py) - p->cy;
                if (dx * dx + dy * dy >= p->radius2) {
                    continue;
                }
            }
            float coverage = 1.0f;
            if (p->smooth_radius > 0.0f) {
                /* A one-pixel ramp across the disc's edge. */
                double dx = (sr__centre_q8(px) - p->cx) / (double)S;
                double dy = (sr__centre_q8(py) - p->cy) / (double)S;
                double c = p->smooth_radius + 0.5 - sqrt(dx * dx + dy * dy);
                if (c <= 0.0) {
                    continue;
                }
                coverage = c < 1.0 ? (float)c : 1.0f;
            }
            sr__fragment_vary(ds, px, py, p->z, p->vary, p->flat, p->front, coverage, st);
        }
    }
}
