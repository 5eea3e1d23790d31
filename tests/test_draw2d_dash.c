/* test_draw2d_dash.c - sr_path_dash against dash endpoints worked out by
 * hand on lines and squares (odd lists, offsets forward, backward and
 * wrapped, closed subpaths dashed over their start), a circle's dashes
 * against its flattened length, and every argument it refuses; dashes
 * and curves within a view (sr_path_dash_in_view, sr_path_cull_curves). */
#include "softrast.h"
#include "sr_test.h"

#include <math.h>
#include <stdlib.h>

typedef struct fixture {
    sr_context *ctx;
    sr_path *in, *out;
} fixture;

static fixture open_fixture(void)
{
    fixture f = { 0 };
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &f.ctx);
    if (f.ctx) {
        sr_make_path(f.ctx, 0, &f.in);
        sr_make_path(f.ctx, 0, &f.out);
    }
    return f;
}

static void close_fixture(fixture *f)
{
    sr_destroy_path(f->ctx, f->in);
    sr_destroy_path(f->ctx, f->out);
    sr_destroy_context(f->ctx);
}

/* The dashes of out are the spans from[i] .. to[i] (first and last point
 * of each subpath), n of them, every one open. */
static void check_dashes(const sr_path *out, const sr_point2 *from, const sr_point2 *to, int n)
{
    sr_polygon2 poly = sr_path_polygon(out);
    CHECK_EQ(poly.contour_count, n);
    int at = 0;
    for (int c = 0; c < poly.contour_count && c < n; c++) {
        int k = poly.contour_counts[c];
        sr_point2 a = poly.points[at], b = poly.points[at + k - 1];
        if (fabs(a.x - from[c].x) > 1e-9 || fabs(a.y - from[c].y) > 1e-9 ||
            fabs(b.x - to[c].x) > 1e-9 || fabs(b.y - to[c].y) > 1e-9) {
            sr_test_fail(__FILE__, __LINE__, "dash %d: (%g,%g)-(%g,%g), want (%g,%g)-(%g,%g)", c,
                         a.x, a.y, b.x, b.y, from[c].x, from[c].y, to[c].x, to[c].y);
        }
        CHECK(!sr_path_subpath_closed(out, c));
        at += k;
    }
}

/* The dashes of a horizontal line 0 .. len at y = 0 are [x0[i], x1[i]]. */
static void check_line(double len, const double *dashes, int count, double offset,
                       const double *x0, const double *x1, int n)
{
    fixture f = open_fixture();
    REQUIRE(f.in && f.out);
    sr_path_move_to(f.in, 0, 0);
    sr_path_line_to(f.in, len, 0);
    CHECK_EQ(sr_path_dash(f.ctx, f.in, dashes, count, offset, f.out), SR_OK);
    sr_point2 a[16], b[16];
    for (int i = 0; i < n; i++) {
        a[i] = (sr_point2){ x0[i], 0 };
        b[i] = (sr_point2){ x1[i], 0 };
    }
    check_dashes(f.out, a, b, n);
    close_fixture(&f);
}

SR_TEST(dash_a_line_into_dashes_and_gaps)
{
    check_line(100, (double[]){ 10, 5 }, 2, 0, (double[]){ 0, 15, 30, 45, 60, 75, 90 },
               (double[]){ 10, 25, 40, 55, 70, 85, 100 }, 7);
}

SR_TEST(dash_an_odd_list_repeats_once)
{
    /* 10 means 10 10; 4 1 2 means 4 1 2 4 1 2: dash 4, gap 1, dash 2, gap 4, ... */
    check_line(50, (double[]){ 10 }, 1, 0, (double[]){ 0, 20, 40 }, (double[]){ 10, 30, 50 }, 3);
    check_line(24, (double[]){ 4, 1, 2 }, 3, 0, (double[]){ 0, 5, 11, 14, 19 },
               (double[]){ 4, 7, 12, 18, 21 }, 5);
}

SR_TEST(dash_offsets_shift_wrap_and_go_backward)
{
    static const double x0[] = { 0, 12, 27, 42 }, x1[] = { 7, 22, 37, 50 };
    check_line(50, (double[]){ 10, 5 }, 2, 3, x0, x1, 4);
    /* whole periods (15) more or less are the same offset */
    check_line(50, (double[]){ 10, 5 }, 2, 3 + 15 * 1000, x0, x1, 4);
    check_line(50, (double[]){ 10, 5 }, 2, 3 - 15 * 7, x0, x1, 4);
    /* -3: 3 before the pattern, in the gap: the first dash starts at 3 */
    check_line(50, (double[]){ 10, 5 }, 2, -3, (double[]){ 3, 18, 33, 48 },
               (double[]){ 13, 28, 43, 50 }, 4);
    /* an offset at a dash's end starts in the gap after it */
    check_line(30, (double[]){ 10, 5 }, 2, 10, (double[]){ 5, 20 }, (double[]){ 15, 30 }, 2);
}

/* The 10 x 10 square (0,0) (10,0) (10,10) (0,10), closed: perimeter 40. */
static void square(sr_path *p)
{
    sr_path_move_to(p, 0, 0);
    sr_path_line_to(p, 10, 0);
    sr_path_line_to(p, 10, 10);
    sr_path_line_to(p, 0, 10);
    sr_path_close(p);
}

SR_TEST(dash_a_closed_square_across_its_closing_point)
{
    fixture f = open_fixture();
    REQUIRE(f.in && f.out);
    square(f.in);
    CHECK_NEAR(sr_path_length(f.in), 40, 1e-12);
    /* 8 on 4 off: 0-8, 12-20, 24-32, 36-44; the last runs over the start
     * and continues into the first, one dash (0,4) (0,0) (8,0) */
    CHECK_EQ(sr_path_dash(f.ctx, f.in, (double[]){ 8, 4 }, 2, 0, f.out), SR_OK);
    check_dashes(f.out, (sr_point2[]){ { 10, 2 }, { 6, 10 }, { 0, 4 } },
                 (sr_point2[]){ { 10, 10 }, { 0, 8 }, { 8, 0 } }, 3);
    sr_polygon2 poly = sr_path_polygon(f.out);
    REQUIRE(poly.contour_count == 3);
    CHECK_EQ(poly.contour_counts[2], 3); /* through the corner (0,0) */
    CHECK_NEAR(sr_path_length(f.out), 8 + 8 + 12, 1e-12);

    /* 5 on 5 off ends on a gap: the first dash stands alone */
    sr_path_clear(f.out);
    CHECK_EQ(sr_path_dash(f.ctx, f.in, (double[]){ 5, 5 }, 2, 0, f.out), SR_OK);
    check_dashes(f.out, (sr_point2[]){ { 10, 0 }, { 10, 10 }, { 0, 10 }, { 0, 0 } },
                 (sr_point2[]){ { 10, 5 }, { 5, 10 }, { 0, 5 }, { 5, 0 } }, 4);
    close_fixture(&f);
}

SR_TEST(dash_a_circle_along_its_flattened_length)
{
    fixture f = open_fixture();
    REQUIRE(f.in && f.out);
    sr_path_move_to(f.in, 100, 50);
    sr_path_arc_to(f.in, 50, 50, 0, false, true, 0, 50);
    sr_path_arc_to(f.in, 50, 50, 0, false, true, 100, 50);
    sr_path_close(f.in);
    double len = sr_path_length(f.in);
    /* inscribed in the circle within the 0.1 px tolerance */
    CHECK(len < 2 * M_PI * 50);
    CHECK(len > 2 * M_PI * 50 * (1 - 0.1 / 50));
    /* ten dashes of a twentieth each, the pattern shifted so that one
     * runs over the start: still ten, together half the length */
    double d = len / 20;
    CHECK_EQ(sr_path_dash(f.ctx, f.in, (double[]){ d, d }, 2, d / 2, f.out), SR_OK);
    sr_polygon2 poly = sr_path_polygon(f.out);
    CHECK_EQ(poly.contour_count, 10);
    CHECK_NEAR(sr_path_length(f.out), len / 2, 1e-9);
    /* the joined one runs from half a dash before the start point (on
     * the second arc, above y = 50) to half a dash after it (below) */
    int last = poly.point_count - poly.contour_counts[poly.contour_count - 1];
    CHECK(poly.points[last].y < 50);
    CHECK(poly.points[poly.point_count - 1].y > 50);
    close_fixture(&f);
}

SR_TEST(dash_zero_length_dashes_and_all_zero_lists)
{
    fixture f = open_fixture();
    REQUIRE(f.in && f.out);
    sr_path_move_to(f.in, 0, 0);
    sr_path_line_to(f.in, 30, 0);
    /* dashes of length 0 every 10: a point each, for caps to draw */
    CHECK_EQ(sr_path_dash(f.ctx, f.in, (double[]){ 0, 10 }, 2, 0, f.out), SR_OK);
    check_dashes(f.out, (sr_point2[]){ { 0, 0 }, { 10, 0 }, { 20, 0 }, { 30, 0 } },
                 (sr_point2[]){ { 0, 0 }, { 10, 0 }, { 20, 0 }, { 30, 0 } }, 4);
    /* no list, or only zeros: the path as it is (a solid stroke) */
    sr_path_clear(f.in);
    square(f.in);
    for (int count = 0; count <= 3; count += 3) {
        sr_path_clear(f.out);
        CHECK_EQ(sr_path_dash(f.ctx, f.in, (double[]){ 0, 0, 0 }, count, 5, f.out), SR_OK);
        sr_polygon2 poly = sr_path_polygon(f.out);
        CHECK_EQ(poly.contour_count, 1);
        CHECK_EQ(poly.point_count, 4);
        CHECK(sr_path_subpath_closed(f.out, 0));
    }
    close_fixture(&f);
}

SR_TEST(dash_appends_to_what_out_holds)
{
    fixture f = open_fixture();
    REQUIRE(f.in && f.out);
    square(f.in);
    sr_path_move_to(f.out, -5, -5);
    sr_path_line_to(f.out, -1, -1);
    CHECK_EQ(sr_path_dash(f.ctx, f.in, (double[]){ 5, 5 }, 2, 0, f.out), SR_OK);
    CHECK_EQ(sr_path_polygon(f.out).contour_count, 5);
    close_fixture(&f);
}

/* sr_path_dash refuses the call with SR_INVALID_ARG and a message naming
 * `field`, leaving out empty. */
static void check_refused(fixture *f, const sr_path *in, const double *dashes, int count,
                          double offset, sr_path *out, const char *field)
{
    CHECK_EQ(sr_path_dash(f->ctx, in, dashes, count, offset, out), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f->ctx), field);
    CHECK_EQ(sr_path_polygon(f->out).point_count, 0);
}

SR_TEST(dash_refuses_bad_arguments_by_name)
{
    fixture f = open_fixture();
    REQUIRE(f.in && f.out);
    square(f.in);
    double ok[2] = { 1, 1 }, many[SR_MAX_DASHES + 1];
    for (int i = 0; i <= SR_MAX_DASHES; i++) {
        many[i] = 1;
    }
    CHECK_EQ(sr_path_dash(NULL, f.in, ok, 2, 0, f.out), SR_INVALID_ARG);
    check_refused(&f, NULL, ok, 2, 0, f.out, "path is NULL");
    check_refused(&f, f.in, ok, 2, 0, NULL, "out is NULL");
    check_refused(&f, f.in, NULL, 2, 0, f.out, "dashes is NULL");
    check_refused(&f, f.in, ok, 2, 0, f.in, "out must not be path");
    check_refused(&f, f.in, ok, -1, 0, f.out, "count");
    check_refused(&f, f.in, many, SR_MAX_DASHES + 1, 0, f.out, "count");
    check_refused(&f, f.in, (double[]){ 1, -1 }, 2, 0, f.out, "dashes[1]");
    check_refused(&f, f.in, (double[]){ NAN, 1 }, 2, 0, f.out, "dashes[0]");
    check_refused(&f, f.in, (double[]){ 1, 2, INFINITY }, 3, 0, f.out, "dashes[2]");
    check_refused(&f, f.in, ok, 2, NAN, f.out, "offset");
    check_refused(&f, f.in, ok, 2, -INFINITY, f.out, "offset");
    /* the longest list is fine, and NULL with no values */
    CHECK_EQ(sr_path_dash(f.ctx, f.in, many, SR_MAX_DASHES, 0, f.out), SR_OK);
    sr_path_clear(f.out);
    CHECK_EQ(sr_path_dash(f.ctx, f.in, NULL, 0, 0, f.out), SR_OK);
    close_fixture(&f);
}

SR_TEST(dash_too_fine_for_the_path_is_refused_before_cutting)
{
    fixture f = open_fixture();
    REQUIRE(f.in && f.out);
    sr_path_move_to(f.in, 0, 0);
    sr_path_line_to(f.in, 1e9, 0);
    /* 4e9 dashes: refused at once, not after running out of points */
    CHECK_EQ(sr_path_dash(f.ctx, f.in, (double[]){ 0.125, 0.125 }, 2, 0, f.out), SR_TOO_LARGE);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "dashes");
    CHECK_EQ(sr_path_polygon(f.out).point_count, 0);
    /* the same pattern along a short line is fine */
    sr_path_clear(f.in);
    sr_path_move_to(f.in, 0, 0);
    sr_path_line_to(f.in, 1, 0);
    /* four dashes, and the fifth begins where the line ends: a point */
    CHECK_EQ(sr_path_dash(f.ctx, f.in, (double[]){ 0.125, 0.125 }, 2, 0, f.out), SR_OK);
    check_dashes(f.out, (sr_point2[]){ { 0, 0 }, { 0.25, 0 }, { 0.5, 0 }, { 0.75, 0 }, { 1, 0 } },
                 (sr_point2[]){ { 0.125, 0 }, { 0.375, 0 }, { 0.625, 0 }, { 0.875, 0 }, { 1, 0 } },
                 5);
    close_fixture(&f);
}

SR_TEST(dash_in_view_skips_the_pattern_outside_with_its_phase)
{
    fixture f = open_fixture();
    REQUIRE(f.in && f.out);
    /* -1e4 .. 1e4 at y = 0, seen through x' = 2 x + 10 in [0, 100]: the
     * path's x in [-5, 45].  Period 15 from -1e4: at -5 the pattern is
     * (1e4 - 5) mod 15 = 5 into a 10-long dash; dashes at 5, 20, 35. */
    sr_path_move_to(f.in, -1e4, 0);
    sr_path_line_to(f.in, 1e4, 0);
    const sr_path_view view = { { 2, 0, 0, 2, 10, 0 }, 0, -1, 100, 1 };
    CHECK(fabs(sr_path_length_in_view(f.in, &view) - 50) < 1e-6);
    CHECK_EQ(sr_path_dash_in_view(f.ctx, f.in, (double[]){ 10, 5 }, 2, 0, &view, f.out), SR_OK);
    check_dashes(f.out, (sr_point2[]){ { -5, 0 }, { 5, 0 }, { 20, 0 }, { 35, 0 } },
                 (sr_point2[]){ { 0, 0 }, { 15, 0 }, { 30, 0 }, { 45, 0 } }, 4);
    /* without a view: the same as sr_path_dash */
    sr_path_clear(f.in);
    square(f.in);
    sr_path_clear(f.out);
    CHECK_EQ(sr_path_dash_in_view(f.ctx, f.in, (double[]){ 6, 4 }, 2, 3, NULL, f.out), SR_OK);
    sr_path *plain = NULL;
    REQUIRE(sr_make_path(f.ctx, 0, &plain) == SR_OK);
    CHECK_EQ(sr_path_dash(f.ctx, f.in, (double[]){ 6, 4 }, 2, 3, plain), SR_OK);
    sr_polygon2 a = sr_path_polygon(f.out), b = sr_path_polygon(plain);
    CHECK_EQ(a.point_count, b.point_count);
    for (int i = 0; i < a.point_count && i < b.point_count; i++) {
        CHECK(a.points[i].x == b.points[i].x && a.points[i].y == b.points[i].y);
    }
    sr_destroy_path(f.ctx, plain);
    /* a view with a NaN map or an empty rectangle is refused */
    const sr_path_view bad = { { NAN, 0, 0, 1, 0, 0 }, 0, 0, 1, 1 };
    const sr_path_view empty = { { 1, 0, 0, 1, 0, 0 }, 1, 0, 0, 1 };
    CHECK_EQ(sr_path_dash_in_view(f.ctx, f.in, (double[]){ 1, 1 }, 2, 0, &bad, f.out),
             SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(f.ctx), "view");
    CHECK_EQ(sr_path_cull_curves(f.in, &empty), SR_INVALID_ARG);
    CHECK_EQ(sr_path_cull_curves(NULL, &view), SR_INVALID_ARG);
    close_fixture(&f);
}

SR_TEST(curves_wholly_outside_the_view_are_lines)
{
    fixture f = open_fixture();
    REQUIRE(f.in);
    const sr_path_view view = { { 1, 0, 0, 1, 0, 0 }, 0, 0, 100, 100 };
    REQUIRE(sr_path_cull_curves(f.in, &view) == SR_OK);
    /* below the view: one point; inside it: flattened as without a view */
    sr_path_move_to(f.in, 0, 200);
    sr_path_cubic_to(f.in, 30, 300, 60, 300, 90, 200);
    CHECK_EQ(sr_path_polygon(f.in).point_count, 2);
    sr_path_move_to(f.in, 10, 10);
    sr_path_cubic_to(f.in, 30, 90, 60, 90, 90, 10);
    int with = sr_path_polygon(f.in).point_count - 2;
    sr_path_clear(f.in); /* which turns it off */
    sr_path_move_to(f.in, 0, 200);
    sr_path_cubic_to(f.in, 30, 300, 60, 300, 90, 200);
    CHECK(sr_path_polygon(f.in).point_count > 2);
    sr_path_clear(f.in);
    sr_path_move_to(f.in, 10, 10);
    sr_path_cubic_to(f.in, 30, 90, 60, 90, 90, 10);
    CHECK_EQ(sr_path_polygon(f.in).point_count, with);
    close_fixture(&f);
}

SR_TEST(arcs_far_outside_the_view_are_lines)
{
    fixture f = open_fixture();
    REQUIRE(f.in);
    const sr_path_view view = { { 1, 0, 0, 1, 0, 0 }, 0, 0, 100, 100 };
    REQUIRE(sr_path_cull_curves(f.in, &view) == SR_OK);
    /* a half circle below the view: one point; inside it: flattened as
     * without a view */
    sr_path_move_to(f.in, 0, 200);
    sr_path_arc_to(f.in, 50, 50, 0, false, true, 100, 200);
    CHECK_EQ(sr_path_polygon(f.in).point_count, 2);
    sr_path_move_to(f.in, 10, 50);
    sr_path_arc_to(f.in, 40, 30, 20, true, false, 90, 50);
    sr_polygon2 culled = sr_path_polygon(f.in);
    int with = culled.point_count - 2;
    sr_path *plain = NULL;
    REQUIRE(sr_make_path(f.ctx, 0, &plain) == SR_OK);
    sr_path_move_to(plain, 10, 50);
    sr_path_arc_to(plain, 40, 30, 20, true, false, 90, 50);
    sr_polygon2 all = sr_path_polygon(plain);
    CHECK(with > 8);
    CHECK_EQ(all.point_count, with);
    for (int i = 0; i < with && i < all.point_count; i++) {
        sr_point2 a = culled.points[i + 2], b = all.points[i];
        CHECK(a.x == b.x && a.y == b.y);
    }
    sr_destroy_path(f.ctx, plain);
    /* A circle of radius 1e9 through (50, 50), its centre to the right:
     * flattened in full its 2 x 65536 chords (the flattening's cap) would
     * stray 0.29 px from it.  Culled, the chords that reach the view stray
     * at most the tolerance and the rest are few. */
    const double r = 1e9;
    sr_path_clear(f.in);
    REQUIRE(sr_path_cull_curves(f.in, &view) == SR_OK);
    sr_path_move_to(f.in, 50, 50);
    sr_path_arc_to(f.in, r, r, 0, false, true, 2 * r + 50, 50);
    sr_path_arc_to(f.in, r, r, 0, false, true, 50, 50);
    sr_polygon2 poly = sr_path_polygon(f.in);
    CHECK(poly.point_count < 2000);
    int near = 0;
    for (int i = 0; i + 1 < poly.point_count; i++) {
        sr_point2 a = poly.points[i], b = poly.points[i + 1];
        bool beyond = (a.x < 0 && b.x < 0) || (a.x > 100 && b.x > 100) ||
                      (a.y < 0 && b.y < 0) || (a.y > 100 && b.y > 100);
        if (!beyond) { /* it may draw in the view */
            near++;
            double d = hypot(b.x - a.x, b.y - a.y);
            CHECK(d * d / (8 * r) <= 0.1);
            CHECK(fabs(hypot(a.x - (r + 50), a.y - 50) - r) < 1e-3);
        }
    }
    CHECK(near > 0);
    close_fixture(&f);
}
