/* test_explain_interp.c - the three interpolation methods `softrast explain
 * interpolation` shows (apps/softrast/explain_interp_methods.c, linked in):
 * on random triangles bilinear, the plane equation and barycentric
 * coordinates cover the same pixel centres, exactly the pixels sr_draw
 * draws, and agree there within float rounding; sr_draw's 8-bit colours
 * are theirs within one step.  Fixed seeds. */
#include "explain.h"
#include "raster_util.h"
#include "sr_test.h"

#include <math.h>
#include <stdlib.h>

#define GRID 16
/* Values are in 0..1 and the grid 16 pixels wide: each method sums at most
 * a few dozen float steps (FillPoly and the plane) or mixes three weights
 * (barycentric), so they agree far inside this; a wrong step (a half-pixel
 * offset, a swapped weight) moves values by 1/16 and more. */
#define TOLERANCE 1e-4

/* A random triangle on the 1/16-pixel grid (exact through NDC in float,
 * so sr_draw snaps it where the methods do), some of it off the grid. */
static ex_primitive random_triangle(sr_rng *rng)
{
    ex_primitive p = { .kind = EX_TRIANGLE, .count = 3 };
    for (int i = 0; i < 3; i++) {
        p.pts[i].x = sr_rng_int(rng, -4 * 16, (GRID + 4) * 16) / 16.0;
        p.pts[i].y = sr_rng_int(rng, -4 * 16, (GRID + 4) * 16) / 16.0;
        p.z[i] = sr_rng_int(rng, 0, 1000) / 1000.0;
    }
    return p;
}

/* sr_draw's pixels for prim with its values as a grey colour, affine. */
static void library(rt_target *t, const ex_primitive *prim)
{
    float pos[9], col[12];
    for (int i = 0; i < 3; i++) {
        pos[3 * i] = rt_ndc_x(t, prim->pts[i].x);
        pos[3 * i + 1] = rt_ndc_y(t, prim->pts[i].y);
        pos[3 * i + 2] = 0;
        col[4 * i] = col[4 * i + 1] = col[4 * i + 2] = (float)prim->z[i];
        col[4 * i + 3] = 1;
    }
    sr_clear(t->ctx, t->fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
    sr_state st = { .shading = SR_SHADING_UNLIT, .material = { .diffuse = { 1, 1, 1 } },
                    .interpolation = SR_INTERP_AFFINE };
    REQUIRE(sr_draw(t->ctx, t->fb, &st, &(sr_draw_desc){ .positions = pos, .vertex_count = 3,
                                                         .colors = col, .color_size = 4 })
            == SR_OK);
}

SR_TEST(three_interpolation_methods_agree_on_the_library_pixels)
{
    sr_rng rng = { 7411 };
    rt_target t = rt_make(GRID, GRID, 1);
    float bil[GRID * GRID], pla[GRID * GRID], bar[GRID * GRID], lambda[3 * GRID * GRID];
    ex_interp_row rows[GRID];
    int covered = 0, triangles = 0;
    double worst = 0, worst_lib = 0;
    for (int k = 0; k < 400; k++) {
        ex_primitive prim = random_triangle(&rng);
        ex_tri tri;
        double in[3], abc[3];
        int origin[2];
        ex_tri_setup_at(&tri, in, &prim, 0);
        ex_interp_bilinear(&tri, in, GRID, GRID, bil, rows);
        ex_interp_plane(&tri, in, GRID, GRID, pla, abc, origin);
        ex_interp_barycentric(&tri, in, GRID, GRID, bar, lambda);
        library(&t, &prim);
        const uint8_t *px = sr_framebuffer_pixels(t.fb);
        int bad_cover = 0, bad_value = 0, bad_lib = 0;
        for (int i = 0; i < GRID * GRID; i++) {
            bool drawn = px[4 * i + 3] != 0;
            bad_cover += isnan(bil[i]) == drawn || isnan(pla[i]) == drawn ||
                         isnan(bar[i]) == drawn;
            if (!drawn || isnan(bil[i]) || isnan(pla[i]) || isnan(bar[i])) {
                continue;
            }
            covered++;
            double d = fmax(fabs(bil[i] - pla[i]), fmax(fabs(pla[i] - bar[i]),
                                                        fabs(bar[i] - bil[i])));
            worst = fmax(worst, d);
            bad_value += d > TOLERANCE;
            double lib = fabs(bar[i] * 255.0 - px[4 * i]);
            worst_lib = fmax(worst_lib, lib);
            bad_lib += lib > 1;
        }
        triangles += tri.area2 != 0;
        if (bad_cover || bad_value || bad_lib) {
            sr_test_fail(__FILE__, __LINE__,
                         "triangle %g,%g,%g,%g,%g,%g I %g,%g,%g: %d pixels covered unlike "
                         "sr_draw, %d apart by more than %g, %d off sr_draw's by a step",
                         prim.pts[0].x, prim.pts[0].y, prim.pts[1].x, prim.pts[1].y,
                         prim.pts[2].x, prim.pts[2].y, prim.z[0], prim.z[1], prim.z[2],
                         bad_cover, bad_value, TOLERANCE, bad_lib);
        }
    }
    CHECK(covered > 10000);   /* the triangles do cover pixels */
    CHECK(triangles > 390);
    printf("largest difference between the methods %.3g, from sr_draw %.3f of a step\n", worst,
           worst_lib);
    rt_free(&t);
}

/* The plane through the vertices takes each vertex's value there. */
SR_TEST(plane_coefficients_reproduce_the_vertex_values)
{
    sr_rng rng = { 7412 };
    for (int k = 0; k < 200; k++) {
        ex_primitive prim = random_triangle(&rng);
        ex_tri tri;
        double in[3], abc[3];
        ex_tri_setup_at(&tri, in, &prim, 0);
        if (!ex_interp_plane_coefficients(&tri, in, abc)) {
            CHECK_EQ(tri.area2, 0);
            continue;
        }
        for (int i = 0; i < 3; i++) {
            double v = abc[0] * tri.x[i] / 256.0 + abc[1] * tri.y[i] / 256.0 + abc[2];
            CHECK(fabs(v - in[i]) < 1e-9);
        }
    }
}
