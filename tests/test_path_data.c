/* test_path_data.c - sr_io_parse_path_data: every command of SVG path
 * data, absolute and relative, against the same path built call by call
 * (the same points, exactly); implicit repeats, compact arc flags, the
 * offset and message of each kind of error with the path kept up to it,
 * numbers at and beyond double's range, and the per-command callback. */
#include "softrast_io.h"
#include "sr_test.h"

#include <math.h>
#include <string.h>

static sr_path *new_path(void)
{
    sr_path *p = NULL;
    sr_make_path(sr_test_ctx(), 0, &p);
    return p;
}

/* Whether a and b flatten to the same points, contours and closings. */
static bool same_path(const sr_path *a, const sr_path *b)
{
    sr_polygon2 pa = sr_path_polygon(a), pb = sr_path_polygon(b);
    if (pa.point_count != pb.point_count || pa.contour_count != pb.contour_count) {
        return false;
    }
    if (pa.point_count == 0) {
        return true; /* no arrays to compare (they may be NULL) */
    }
    if (memcmp(pa.points, pb.points, (size_t)pa.point_count * sizeof *pa.points) != 0 ||
        memcmp(pa.contour_counts, pb.contour_counts,
               (size_t)pa.contour_count * sizeof *pa.contour_counts) != 0) {
        return false;
    }
    for (int c = 0; c < pa.contour_count; c++) {
        if (sr_path_subpath_closed(a, c) != sr_path_subpath_closed(b, c)) {
            return false;
        }
    }
    return true;
}

/* d parses without error into the path `want` holds; want is freed. */
static void check_parses_as(const char *d, sr_path *want, int line)
{
    sr_path *got = new_path();
    long offset = 0;
    sr_io_error err;
    sr_result r = sr_io_parse_path_data(d, got, NULL, &offset, &err);
    if (r != SR_OK || offset != -1 || !same_path(got, want)) {
        sr_test_fail(__FILE__, line, "\"%s\": %s (%s), offset %ld, %s", d, sr_result_name(r),
                     err.message, offset, same_path(got, want) ? "same path" : "another path");
    }
    sr_destroy_path(sr_test_ctx(), got);
    sr_destroy_path(sr_test_ctx(), want);
}

/* One of every command, as calls. */
static sr_path *every_command(void)
{
    sr_path *p = new_path();
    sr_path_move_to(p, 10, 20);
    sr_path_line_to(p, 30, 40);
    sr_path_line_to(p, 50, 40);                  /* H */
    sr_path_line_to(p, 50, 60);                  /* V */
    sr_path_cubic_to(p, 60, 70, 80, 70, 90, 60);
    sr_path_cubic_to(p, 100, 50, 110, 50, 120, 60); /* S: (100,50) reflects (80,70) */
    sr_path_quad_to(p, 130, 80, 140, 60);
    sr_path_quad_to(p, 150, 40, 160, 60);        /* T: (150,40) reflects (130,80) */
    sr_path_arc_to(p, 20, 10, 30, true, false, 170, 90);
    sr_path_close(p);
    return p;
}

SR_TEST(path_data_absolute_commands)
{
    check_parses_as("M10 20 L30 40 H50 V60 C60 70 80 70 90 60 S110 50 120 60 Q130 80 140 60 "
                    "T160 60 A20 10 30 1 0 170 90 Z", every_command(), __LINE__);
}

SR_TEST(path_data_relative_commands)
{
    /* the same, every point relative to the one before */
    sr_path *p = every_command();
    /* after z the current point is the subpath's start: m is from there */
    sr_path_move_to(p, 15, 25);
    sr_path_line_to(p, 15, 35);
    check_parses_as("m10 20 l20 20 h20 v20 c10 10 30 10 40 0 s20 -10 30 0 q10 20 20 0 t20 0 "
                    "a20 10 30 1 0 10 30 z m5 5 v10", p, __LINE__);
}

SR_TEST(path_data_implicit_repeats_and_compact_numbers)
{
    /* pairs after M are L, after m are l; each command repeats */
    sr_path *p = new_path();
    sr_path_move_to(p, 0, 0);
    sr_path_line_to(p, 10, 0);
    sr_path_line_to(p, 10, 10);
    sr_path_move_to(p, 20, 20);
    sr_path_line_to(p, 25, 20);
    sr_path_line_to(p, 5, 20);
    sr_path_line_to(p, 5, 20);
    sr_path_line_to(p, 25, 20);
    sr_path_line_to(p, 25, 30);
    check_parses_as("M0 0 10 0 10 10m10 10 5 0h-20-0+20v10", p, __LINE__);
    /* no separators where the grammar needs none: signs, dots, arc flags */
    p = new_path();
    sr_path_move_to(p, 0.5, -0.25);
    sr_path_line_to(p, 0.75, 0.5);
    sr_path_arc_to(p, 5, 5, 0, false, true, 10.75, 0.5);
    sr_path_arc_to(p, 5, 5, 0, true, false, 20.75, 0.5);
    check_parses_as("M.5-.25L.75.5a5,5,0,0,1,10,0a5 5 0 1010 0", p, __LINE__);
    /* blanks and commas anywhere between numbers, around commands */
    p = new_path();
    sr_path_move_to(p, 1, 2);
    sr_path_line_to(p, 3e2, 4E-1);
    check_parses_as(" \t\nM 1 , 2\r\nL3e2,4E-1 \n", p, __LINE__);
    /* empty data is an empty path */
    check_parses_as("", new_path(), __LINE__);
}

/* d stops at byte `offset` with `message`; the path holds what `want` does. */
static void check_error(const char *d, long offset, const char *message, sr_path *want,
                        int line)
{
    sr_path *got = new_path();
    long at = 0;
    sr_io_error err;
    sr_result r = sr_io_parse_path_data(d, got, NULL, &at, &err);
    if (r != SR_BAD_FORMAT || at != offset || strcmp(err.message, message) != 0 ||
        !same_path(got, want)) {
        sr_test_fail(__FILE__, line, "\"%s\": %s at %ld (%s), want %ld (%s)%s", d,
                     sr_result_name(r), at, err.message, offset, message,
                     same_path(got, want) ? "" : ", another path");
    }
    sr_destroy_path(sr_test_ctx(), got);
    sr_destroy_path(sr_test_ctx(), want);
}

static sr_path *moved_to(double x, double y)
{
    sr_path *p = new_path();
    sr_path_move_to(p, x, y);
    return p;
}

SR_TEST(path_data_errors_keep_the_path_up_to_them)
{
    /* a set of numbers cut short draws nothing of its command */
    check_error("M 10 10 L 20 x", 13, "path data: expected a number at offset 13",
                moved_to(10, 10), __LINE__);
    check_error("M0 0 X 1", 5, "path data: unknown command 'X' at offset 5", moved_to(0, 0),
                __LINE__);
    check_error("L0 0", 0, "path data: no moveto first at offset 0", new_path(), __LINE__);
    check_error("  10 10", 2, "path data: expected a command at offset 2", new_path(),
                __LINE__);
    sr_path *closed = moved_to(0, 0);
    sr_path_line_to(closed, 5, 0);
    sr_path_close(closed);
    check_error("M0 0 5 0z 7", 10, "path data: expected a command at offset 10", closed,
                __LINE__);
    check_error("M0 0a5 5 0 2 1 10 0", 11, "path data: arc flag not 0 or 1 at offset 11",
                moved_to(0, 0), __LINE__);
    sr_path *line = moved_to(0, 0);
    sr_path_line_to(line, 1, 1);
    check_error("M0 0 L1 1 2", 11, "path data: expected a number at offset 11", line, __LINE__);
}

SR_TEST(path_data_numbers_at_and_past_the_double_range)
{
    sr_path *p = moved_to(1e308, -1.7976931348623157e308);
    check_parses_as("M1e308-1.7976931348623157e308", p, __LINE__);
    /* beyond double, or written as a word: an error in the data */
    check_error("M0 0L1e309 0", 5, "path data: expected a number at offset 5",
                moved_to(0, 0), __LINE__);
    check_error("M0 0L0 inf", 7, "path data: expected a number at offset 7", moved_to(0, 0),
                __LINE__);
    /* 80 digits: longer than any number the reader takes */
    char d[128] = "M0 0L";
    for (int i = 0; i < 80; i++) {
        strcat(d, "1");
    }
    strcat(d, " 0");
    check_error(d, 5, "path data: expected a number at offset 5", moved_to(0, 0), __LINE__);
    /* finite numbers whose relative sum is not: the path refuses the point */
    sr_path *got = new_path();
    long at = 0;
    sr_io_error err;
    CHECK_EQ(sr_io_parse_path_data("M1e308 0 l1e308 0", got, NULL, &at, &err), SR_INVALID_ARG);
    CHECK_EQ(at, 9);
    CHECK_STR_CONTAINS(sr_context_error(sr_test_ctx()), "not finite");
    CHECK_EQ(sr_path_polygon(got).point_count, 1);
    sr_destroy_path(sr_test_ctx(), got);
}

typedef struct seen {
    char letters[32];
    long offsets[32];
    int n, stop_at;
} seen;

static sr_result record(void *user, char letter, long offset)
{
    seen *s = user;
    s->letters[s->n] = letter;
    s->offsets[s->n] = offset;
    return ++s->n == s->stop_at ? SR_TOO_LARGE : SR_OK;
}

SR_TEST(path_data_calls_back_after_every_command)
{
    sr_path *p = new_path();
    seen s = { .stop_at = 0 };
    sr_io_path_data_desc desc = { .command = record, .user = &s };
    long at = 0;
    CHECK_EQ(sr_io_parse_path_data("m1 1 2 2 H5 z", p, &desc, &at, NULL), SR_OK);
    CHECK_EQ(s.n, 4);
    CHECK(memcmp(s.letters, "mlHz", 4) == 0);
    CHECK_EQ(s.offsets[0], 5);
    CHECK_EQ(s.offsets[1], 9);
    CHECK_EQ(s.offsets[2], 12);
    CHECK_EQ(s.offsets[3], 13);
    /* a result other than SR_OK stops there and is returned */
    sr_path_clear(p);
    s = (seen){ .stop_at = 2 };
    sr_io_error err;
    CHECK_EQ(sr_io_parse_path_data("M0 0 L1 1 L2 2", p, &desc, &at, &err), SR_TOO_LARGE);
    CHECK_EQ(s.n, 2);
    CHECK_EQ(at, 5);
    CHECK_EQ(sr_path_polygon(p).point_count, 2);
    CHECK_STR_CONTAINS(err.message, "at offset 5");
    sr_destroy_path(sr_test_ctx(), p);
}

SR_TEST(path_data_refuses_null)
{
    sr_path *p = new_path();
    sr_io_error err;
    long at = 0;
    CHECK_EQ(sr_io_parse_path_data(NULL, p, NULL, &at, &err), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(err.message, "d is NULL");
    CHECK_EQ(sr_io_parse_path_data("M0 0", NULL, NULL, NULL, &err), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(err.message, "path is NULL");
    CHECK_EQ(sr_io_parse_path_data("M0 0", p, NULL, NULL, NULL), SR_OK);
    sr_destroy_path(sr_test_ctx(), p);
}
