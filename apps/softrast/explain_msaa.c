/* explain_msaa.c - `softrast explain msaa`: a triangle's coverage with
 * several samples per pixel, as a multisampled framebuffer records it.
 * The samples sit at the standard positions (sr_sample_position, all on
 * the 1/16-pixel grid); each is tested against the three edge functions
 * with the top-left rule, exactly as the pixel centre is without MSAA.
 * Shading runs once per pixel, its colour goes to the covered samples,
 * and the resolve averages each pixel's samples: (sum + n/2) / n per
 * channel, so a pixel with k of n samples covered gets k/n of the colour. */
#include "explain.h"

#include <stdio.h>

/* The sample positions in q8 from the pixel's upper-left corner. */
static void positions(int n, int64_t pos[][2])
{
    for (int s = 0; s < n; s++) {
        float x, y;
        sr_sample_position(n, s, &x, &y);
        pos[s][0] = (int64_t)(x * 256.0f);
        pos[s][1] = (int64_t)(y * 256.0f);
    }
}

static sr_point2 sample_at(int px, int py, const int64_t *pos)
{
    return (sr_point2){ px + pos[0] / 256.0, py + pos[1] / 256.0 };
}

/* One resolved channel: background `bg` and colour `fg` (bytes) over
 * k of n samples, as sr_resolve rounds it. */
static int resolved(int fg, int bg, int k, int n)
{
    return (k * fg + (n - k) * bg + n / 2) / n;
}

sr_result explain_msaa(ex_canvas *c, const ex_primitive *prim)
{
    int n = prim->samples;
    int64_t pos[16][2];
    positions(n, pos);
    ex_tri t;
    bool swapped = ex_tri_setup(&t, prim);
    double r_dot = c->zoom >= 20 ? 2.5 : 1.2;
    char cap[640];

    ex_begin(c);
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            for (int s = 0; s < n; s++) {
                ex_dot(c, sample_at(x, y, pos[s]), r_dot, EX_EDGE);
            }
        }
    }
    ex_tri_draw(c, &t, -1);
    snprintf(cap, sizeof cap,
             "1. MSAA with %d samples per pixel at the standard positions (multiples of 1/16 "
             "pixel). Coverage and depth are decided per sample; shading runs once per pixel "
             "and triangle.%s",
             n, swapped ? " (Given clockwise: V1 and V2 swapped so inside is E > 0.)" : "");
    ex_end(c, cap);

    /* per-sample coverage: every sample by the edge functions */
    ex_begin(c);
    int covered = 0, ties = 0, full = 0, partial = 0;
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            int k = 0;
            for (int s = 0; s < n; s++) {
                k += ex_tri_covers(&t, (int64_t)x * 256 + pos[s][0], (int64_t)y * 256 + pos[s][1]);
            }
            if (k > 0) {
                ex_cell(c, x, y, k == n ? EX_CELL_IN : EX_TIE);
            }
            full += k == n;
            partial += k > 0 && k < n;
        }
    }
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            for (int s = 0; s < n; s++) {
                int64_t sx = (int64_t)x * 256 + pos[s][0], sy = (int64_t)y * 256 + pos[s][1];
                bool in = ex_tri_covers(&t, sx, sy);
                bool tie = false;
                for (int i = 0; i < 3; i++) {
                    tie |= ex_tri_edge(&t, i, sx, sy) == 0;
                }
                covered += in;
                ties += tie;
                ex_dot(c, sample_at(x, y, pos[s]), in ? r_dot * 1.6 : r_dot * 0.8,
                       in ? EX_INK : EX_EDGE);
            }
        }
    }
    ex_tri_draw(c, &t, -1);
    snprintf(cap, sizeof cap,
             "2. Per-sample coverage: each sample tested against E0, E1, E2, ties (%d samples "
             "exactly on an edge) by the top-left rule. %d samples covered (large blue dots): "
             "%d pixels fully (green), %d partly (yellow).",
             ties, covered, full, partial);
    ex_end(c, cap);

    /* the resolve */
    ex_begin(c);
    const uint8_t ink[3] = { (uint8_t)(EX_INK.r * 255 + 0.5f), (uint8_t)(EX_INK.g * 255 + 0.5f),
                             (uint8_t)(EX_INK.b * 255 + 0.5f) };
    for (int y = 0; y < c->grid_h; y++) {
        for (int x = 0; x < c->grid_w; x++) {
            int k = 0;
            for (int s = 0; s < n; s++) {
                k += ex_tri_covers(&t, (int64_t)x * 256 + pos[s][0], (int64_t)y * 256 + pos[s][1]);
            }
            if (k == 0) {
                continue;
            }
            sr_rgba col = { resolved(ink[0], 255, k, n) / 255.0f,
                            resolved(ink[1], 255, k, n) / 255.0f,
                            resolved(ink[2], 255, k, n) / 255.0f, 1 };
            ex_cell(c, x, y, col);
            char frac[32];
            snprintf(frac, sizeof frac, "%d/%d", k, n);
            ex_cell_text(c, x, y, frac, k * 2 > n ? (sr_rgba){ 1, 1, 1, 1 } : EX_TEXT);
        }
    }
    ex_tri_draw(c, &t, -1);
    snprintf(cap, sizeof cap,
             "3. Resolve: each pixel the box average of its %d samples, (sum + %d/2) / %d per "
             "channel, so k covered samples give k/%d of the triangle's colour over the "
             "background: what sr_draw leaves in a %d-sample framebuffer, read back.",
             n, n, n, n, n);
    ex_end(c, cap);
    return c->error;
}
