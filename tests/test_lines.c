/* test_lines.c - draw2d stage, 2D lines (src/draw2d/line*.c): the
 * midpoint/Bresenham line against an independent implementation of the
 * diamond-exit closed form (docs/raster-rules.md §7.1), order independence, the
 * octants, the DDA variants against it (differences counted), clipping
 * invariance with both clippers, Wu's intensity, exact area coverage
 * against supersampling, wide lines, and argument validation.
 * Fixed seeds throughout. */
#include "sr_test.h"
#include "softrast.h"
#include "draw2d/line.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef __SIZEOF_INT128__
__extension__ typedef __int128 i128;
#else
/* 32-bit targets: the reference's products of two q8 coordinates fit 64
 * bits while the lines stay in BIG (below 2^21 q8 a coordinate). */
typedef int64_t i128;
#endif

/* ---- pixel sets ------------------------------------------------------------------ */

typedef struct pix { int x, y; float c; } pix;
typedef struct pixset { int n, cap; pix *p; } pixset;

static void collect(void *user, int x, int y, float c)
{
    pixset *s = user;
    if (s->n == s->cap) {
        s->cap = s->cap ? 2 * s->cap : 256;
        s->p = realloc(s->p, (size_t)s->cap * sizeof *s->p);
    }
    s->p[s->n++] = (pix){ x, y, c };
}

static int pix_cmp(const void *a, const void *b)
{
    const pix *p = a, *q = b;
    if (p->y != q->y) {
        return p->y < q->y ? -1 : 1;
    }
    return (p->x > q->x) - (p->x < q->x);
}

static void sort_set(pixset *s)
{
    if (s->n) {
        qsort(s->p, (size_t)s->n, sizeof *s->p, pix_cmp);
    }
}

static bool has_duplicates(pixset *s)
{
    sort_set(s);
    for (int i = 1; i < s->n; i++) {
        if (s->p[i].x == s->p[i - 1].x && s->p[i].y == s->p[i - 1].y) {
            return true;
        }
    }
    return false;
}

static bool same_set(pixset *a, pixset *b)
{
    sort_set(a);
    sort_set(b);
    if (a->n != b->n) {
        return false;
    }
    for (int i = 0; i < a->n; i++) {
        if (a->p[i].x != b->p[i].x || a->p[i].y != b->p[i].y) {
            return false;
        }
    }
    return true;
}

static bool contains(const pixset *s, int x, int y)
{
    for (int i = 0; i < s->n; i++) {
        if (s->p[i].x == x && s->p[i].y == y) {
            return true;
        }
    }
    return false;
}

static void remove_pixel(pixset *s, int x, int y)
{
    for (int i = 0; i < s->n; i++) {
        if (s->p[i].x == x && s->p[i].y == y) {
            s->p[i] = s->p[--s->n];
            return;
        }
    }
}

static void keep_inside(pixset *s, sr__irect r)
{
    int n = 0;
    for (int i = 0; i < s->n; i++) {
        if (s->p[i].x >= r.x0 && s->p[i].x < r.x1 && s->p[i].y >= r.y0 && s->p[i].y < r.y1) {
            s->p[n++] = s->p[i];
        }
    }
    s->n = n;
}

static const sr__irect BIG = { -4096, -4096, 4096, 4096 };

/* ---- the independent reference: docs/raster-rules.md §7.1 written out literally ------------ */

static i128 ref_ceil_div(i128 a, i128 b)   /* b > 0 */
{
    i128 q = a / b;
    return (a % b != 0 && a > 0) ? q + 1 : q;
}
static i128 ref_floor_div(i128 a, i128 b)
{
    i128 q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}

static bool ref_in_diamond(int64_t px, int64_t py, int64_t qx, int64_t qy, bool xmaj)
{
    int64_t dx = px - (256 * qx + 128), dy = py - (256 * qy + 128);
    int64_t d = (dx < 0 ? -dx : dx) + (dy < 0 ? -dy : dy);
    return d < 128 || (d == 128 && (dy > 0 || (!xmaj && dx == 128 && dy == 0)));
}

/* candidates(p): the <= 4 pixels whose closed squares contain p. */
static int ref_candidates(int64_t px, int64_t py, int64_t q[4][2])
{
    int64_t xs[2], ys[2];
    int nx = 0, ny = 0;
    xs[nx++] = (int64_t)ref_floor_div(px, 256);
    if (px % 256 == 0) {
        xs[nx++] = px / 256 - 1;
    }
    ys[ny++] = (int64_t)ref_floor_div(py, 256);
    if (py % 256 == 0) {
        ys[ny++] = py / 256 - 1;
    }
    int n = 0;
    for (int i = 0; i < nx; i++) {
        for (int j = 0; j < ny; j++) {
            q[n][0] = xs[i];
            q[n][1] = ys[j];
            n++;
        }
    }
    return n;
}

static void ref_pixels(const sr__line_q8 *l, pixset *out)
{
    out->n = 0;
    if (l->ax == l->bx && l->ay == l->by) {
        return;
    }
    int64_t dx = l->bx - l->ax, dy = l->by - l->ay;
    bool xmaj = llabs(dx) >= llabs(dy);
    int64_t pau = xmaj ? l->ax : l->ay, pav = xmaj ? l->ay : l->ax;
    int64_t pbu = xmaj ? l->bx : l->by, pbv = xmaj ? l->by : l->bx;
    int64_t umin = pau < pbu ? pau : pbu, umax = pau < pbu ? pbu : pau;
    for (int64_t k = (int64_t)ref_ceil_div(umin - 128, 256); 256 * k + 128 <= umax; k++) {
        int64_t c = 256 * k + 128;
        i128 num = (i128)pav * (pbu - pau) + (i128)(c - pau) * (pbv - pav);
        i128 den = pbu - pau;
        if (den < 0) {
            num = -num;
            den = -den;
        }
        int64_t j = (int64_t)ref_ceil_div(num, den * 256) - 1;
        collect(out, (int)(xmaj ? k : j), (int)(xmaj ? j : k), 1.0f);
    }
    int64_t q[4][2];
    int n = ref_candidates(l->ax, l->ay, q);
    for (int i = 0; i < n; i++) {
        if (ref_in_diamond(l->ax, l->ay, q[i][0], q[i][1], xmaj) &&
            !contains(out, (int)q[i][0], (int)q[i][1])) {
            collect(out, (int)q[i][0], (int)q[i][1], 1.0f);
        }
    }
    n = ref_candidates(l->bx, l->by, q);
    for (int i = 0; i < n; i++) {
        if (ref_in_diamond(l->bx, l->by, q[i][0], q[i][1], xmaj)) {
            remove_pixel(out, (int)q[i][0], (int)q[i][1]);
        }
    }
}

/* The pixel whose diamond owns p (x, y); false if none. */
static bool ref_owner(int64_t px, int64_t py, bool xmaj, int *x, int *y)
{
    int64_t q[4][2];
    int n = ref_candidates(px, py, q);
    for (int i = 0; i < n; i++) {
        if (ref_in_diamond(px, py, q[i][0], q[i][1], xmaj)) {
            *x = (int)q[i][0];
            *y = (int)q[i][1];
            return true;
        }
    }
    return false;
}

static sr__line_q8 random_q8(sr_rng *rng, int lo, int hi)
{
    sr__line_q8 l;
    l.ax = sr_rng_int(rng, lo * 256, hi * 256);
    l.ay = sr_rng_int(rng, lo * 256, hi * 256);
    l.bx = sr_rng_int(rng, lo * 256, hi * 256);
    l.by = sr_rng_int(rng, lo * 256, hi * 256);
    /* A third of the lines at 45 degrees or axis-aligned: tie-rich cases. */
    switch (sr_rng_int(rng, 0, 8)) {
    case 0: l.by = l.ay + (l.bx - l.ax); break;
    case 1: l.by = l.ay - (l.bx - l.ax); break;
    case 2: l.by = l.ay; break;
    default: break;
    }
    return l;
}

static sr__line_q8 random_centres(sr_rng *rng, int lo, int hi)
{
    return (sr__line_q8){ 256 * sr_rng_int(rng, lo, hi) + 128, 256 * sr_rng_int(rng, lo, hi) + 128,
                          256 * sr_rng_int(rng, lo, hi) + 128, 256 * sr_rng_int(rng, lo, hi) + 128 };
}

static void bresenham(const sr__line_q8 *l, sr__irect clip, sr_line_clipper clipper,
                      bool closed_form_only, pixset *out)
{
    out->n = 0;
    sr__line_bresenham(l, clip, clipper, closed_form_only, collect, out);
}

/* ---- Bresenham / closed form --------------------------------------------------------- */

SR_TEST(closed_form_matches_independent_reference_on_100000_subpixel_segments)
{
    sr_rng rng = { 0x11e5 };
    pixset a = { 0 }, r = { 0 };
    int bad = 0;
    for (int i = 0; i < 100000 && bad < 5; i++) {
        sr__line_q8 l = random_q8(&rng, -8, 40);
        bresenham(&l, BIG, SR_LINE_CLIP_LIANG_BARSKY, true, &a);
        ref_pixels(&l, &r);
        CHECK(!has_duplicates(&a));
        if (!same_set(&a, &r)) {
            sr_test_fail(__FILE__, __LINE__, "line %d (%lld,%lld)->(%lld,%lld) q8: %d vs %d pixels",
                         i, (long long)l.ax, (long long)l.ay, (long long)l.bx, (long long)l.by,
                         a.n, r.n);
            bad++;
        }
    }
    free(a.p);
    free(r.p);
}

SR_TEST(integer_fast_path_matches_closed_form)
{
    sr_rng rng = { 0xb7e5 };
    pixset a = { 0 }, b = { 0 };
    for (int i = 0; i < 50000; i++) {
        sr__line_q8 l = random_centres(&rng, -10, 60);
        if (i % 3 == 0) {
            l.by = l.ay + (l.bx - l.ax) * (i % 2 ? 1 : -1);   /* diagonals */
        }
        a.n = 0;
        REQUIRE(sr__line_bresenham_centres(&l, BIG, SR_LINE_CLIP_LIANG_BARSKY, collect, &a));
        bresenham(&l, BIG, SR_LINE_CLIP_LIANG_BARSKY, true, &b);
        if (!same_set(&a, &b)) {
            sr_test_fail(__FILE__, __LINE__, "line %d differs", i);
            break;
        }
        /* Clipped entry into the fast path (state computed mid-line). */
        sr__irect r = { sr_rng_int(&rng, -5, 30), sr_rng_int(&rng, -5, 30), 0, 0 };
        r.x1 = r.x0 + sr_rng_int(&rng, 1, 30);
        r.y1 = r.y0 + sr_rng_int(&rng, 1, 30);
        a.n = 0;
        sr__line_bresenham_centres(&l, r, SR_LINE_CLIP_COHEN_SUTHERLAND, collect, &a);
        keep_inside(&b, r);
        if (!same_set(&a, &b)) {
            sr_test_fail(__FILE__, __LINE__, "clipped line %d differs", i);
            break;
        }
    }
    sr__line_q8 sub = { 10, 128, 2000, 300 };
    CHECK(!sr__line_bresenham_centres(&sub, BIG, SR_LINE_CLIP_LIANG_BARSKY, collect, &a));
    free(a.p);
    free(b.p);
}

/* P->Q and Q->P: the same pixels, except that each direction includes
 * its start's pixel (the one whose diamond owns the start point) and
 * leaves out its end's. */
SR_TEST(pixels_are_independent_of_direction_apart_from_the_end_pixel)
{
    sr_rng rng = { 0x0dd };
    pixset f = { 0 }, g = { 0 };
    for (int i = 0; i < 20000; i++) {
        sr__line_q8 l = i % 2 ? random_q8(&rng, -4, 30) : random_centres(&rng, -4, 30);
        sr__line_q8 rev = { l.bx, l.by, l.ax, l.ay };
        bresenham(&l, BIG, SR_LINE_CLIP_LIANG_BARSKY, false, &f);
        bresenham(&rev, BIG, SR_LINE_CLIP_LIANG_BARSKY, false, &g);
        bool xmaj = llabs(l.bx - l.ax) >= llabs(l.by - l.ay);
        int px, py, qx, qy;
        bool hp = ref_owner(l.ax, l.ay, xmaj, &px, &py), hq = ref_owner(l.bx, l.by, xmaj, &qx, &qy);
        if (hq) {
            CHECK(!contains(&f, qx, qy));
        }
        if (hp) {
            CHECK(!contains(&g, px, py));
            if (!(hq && px == qx && py == qy)) {
                CHECK(contains(&f, px, py));
            }
            remove_pixel(&f, px, py);
        }
        if (hq) {
            remove_pixel(&g, qx, qy);
        }
        if (!same_set(&f, &g)) {
            sr_test_fail(__FILE__, __LINE__, "line %d: direction changes the pixels", i);
            break;
        }
    }
    free(f.p);
    free(g.p);
}

/* Endpoints on pixel centres in each of the eight octants, plus the
 * axes and diagonals: one pixel per major step, 8-connected, from the
 * start pixel up to (not including) the end pixel. */
SR_TEST(every_octant_draws_a_connected_half_open_line)
{
    const int dirs[][2] = { { 9, 4 }, { 4, 9 }, { -4, 9 }, { -9, 4 }, { -9, -4 }, { -4, -9 },
                            { 4, -9 }, { 9, -4 }, { 9, 0 }, { 0, 9 }, { -9, 0 }, { 0, -9 },
                            { 9, 9 }, { -9, 9 }, { -9, -9 }, { 9, -9 } };
    pixset s = { 0 };
    for (int d = 0; d < 16; d++) {
        int x0 = 20, y0 = 20, x1 = 20 + dirs[d][0], y1 = 20 + dirs[d][1];
        sr__line_q8 l = { 256 * x0 + 128, 256 * y0 + 128, 256 * x1 + 128, 256 * y1 + 128 };
        s.n = 0;
        sr__line_bresenham(&l, BIG, SR_LINE_CLIP_LIANG_BARSKY, false, collect, &s);
        CHECK_EQ(s.n, 9);
        CHECK(contains(&s, x0, y0));
        CHECK(!contains(&s, x1, y1));
        bool xmaj = abs(dirs[d][0]) >= abs(dirs[d][1]);
        /* Walk from the start: each major step has exactly one pixel,
         * adjacent to the previous one. */
        int su = (xmaj ? dirs[d][0] : dirs[d][1]) > 0 ? 1 : -1;
        int pu = xmaj ? x0 : y0, pv = xmaj ? y0 : x0;
        for (int step = 1; step < 9; step++) {
            int u = (xmaj ? x0 : y0) + su * step, found = 0, v = 0;
            for (int i = 0; i < s.n; i++) {
                if ((xmaj ? s.p[i].x : s.p[i].y) == u) {
                    found++;
                    v = xmaj ? s.p[i].y : s.p[i].x;
                }
            }
            CHECK_EQ(found, 1);
            CHECK(abs(v - pv) <= 1 && abs(u - pu) == 1);
            pu = u;
            pv = v;
        }
    }
    free(s.p);
}

/* Worked example (docs/lines.md): (0,0) -> (8,3) with endpoints on pixel
 * centres.  d starts at 2dy - dx = -2 and moves by 2dy = 6 (E) or
 * 2(dy - dx) = -10 (NE): -2 E, 4 NE, -6 E, 0 E (tie: the line passes
 * through the midpoint; the smaller y wins), 6 NE, -4 E, 2 NE. */
SR_TEST(worked_example_0_0_to_8_3)
{
    const int want[8][2] = { { 0, 0 }, { 1, 0 }, { 2, 1 }, { 3, 1 }, { 4, 1 }, { 5, 2 }, { 6, 2 },
                             { 7, 3 } };
    sr__line_q8 l = { 128, 128, 8 * 256 + 128, 3 * 256 + 128 };
    pixset s = { 0 };
    sr__line_bresenham(&l, BIG, SR_LINE_CLIP_LIANG_BARSKY, false, collect, &s);
    CHECK_EQ(s.n, 8);
    for (int i = 0; i < 8; i++) {
        CHECK(contains(&s, want[i][0], want[i][1]));
    }
    /* Drawn the other way, (8,3) -> (0,0) keeps (8,3), drops (0,0) and
     * the tie at x = 4 still goes to y = 1. */
    sr__line_q8 rev = { l.bx, l.by, l.ax, l.ay };
    s.n = 0;
    sr__line_bresenham(&rev, BIG, SR_LINE_CLIP_LIANG_BARSKY, false, collect, &s);
    CHECK(contains(&s, 8, 3) && !contains(&s, 0, 0) && contains(&s, 4, 1));
    free(s.p);
}

/* ---- DDA against Bresenham --------------------------------------------------------- */

/* Is v(c) = num / (den 256) an exact integer at major index k?  (A tie:
 * the line passes exactly through the boundary between two pixels.) */
static bool exact_tie(const sr__line_q8 *l, int64_t k)
{
    bool xmaj = llabs(l->bx - l->ax) >= llabs(l->by - l->ay);
    int64_t au = xmaj ? l->ax : l->ay, av = xmaj ? l->ay : l->ax;
    int64_t bu = xmaj ? l->bx : l->by, bv = xmaj ? l->by : l->bx;
    i128 num = (i128)av * (bu - au) + (i128)(256 * k + 128 - au) * (bv - av);
    i128 den = (i128)(bu - au) * 256;
    return num % den == 0;
}

typedef struct dda_stats { long lines, lines_differing, ties, rounding; } dda_stats;

/* Compare per major step strictly inside the line (away from the end
 * columns, where the closed form's diamond rules apply). */
static void compare_dda(const sr__line_q8 *l, bool incremental, dda_stats *st, pixset *d,
                        pixset *b)
{
    d->n = 0;
    sr__line_dda(l, incremental, BIG, SR_LINE_CLIP_LIANG_BARSKY, collect, d);
    bresenham(l, BIG, SR_LINE_CLIP_LIANG_BARSKY, true, b);
    bool xmaj = llabs(l->bx - l->ax) >= llabs(l->by - l->ay);
    int64_t au = xmaj ? l->ax : l->ay, bu = xmaj ? l->bx : l->by;
    int64_t kmin = (au < bu ? au : bu) / 256 + 2, kmax = (au < bu ? bu : au) / 256 - 2;
    bool differs = false;
    for (int i = 0; i < d->n; i++) {
        int k = xmaj ? d->p[i].x : d->p[i].y;
        if (k < kmin || k > kmax) {
            continue;
        }
        if (!contains(b, d->p[i].x, d->p[i].y)) {
            differs = true;
            if (exact_tie(l, k)) {
                st->ties++;
            } else {
                st->rounding++;
            }
        }
    }
    st->lines++;
    st->lines_differing += differs;
}

SR_TEST(dda_differs_from_bresenham_only_at_exact_ties_and_by_rounding)
{
    sr_rng rng = { 0xdda };
    pixset d = { 0 }, b = { 0 };
    dda_stats naive_c = { 0 }, inc_c = { 0 }, naive_s = { 0 }, inc_s = { 0 };
    for (int i = 0; i < 20000; i++) {
        sr__line_q8 c = random_centres(&rng, 0, 100);
        sr__line_q8 s = random_q8(&rng, 0, 100);
        compare_dda(&c, false, &naive_c, &d, &b);
        compare_dda(&c, true, &inc_c, &d, &b);
        compare_dda(&s, false, &naive_s, &d, &b);
        compare_dda(&s, true, &inc_s, &d, &b);
        /* With endpoints on centres the DDA's half-open column range is
         * Bresenham's exactly: only the rows can differ. */
        d.n = 0;
        sr__line_dda(&c, false, BIG, SR_LINE_CLIP_LIANG_BARSKY, collect, &d);
        bresenham(&c, BIG, SR_LINE_CLIP_LIANG_BARSKY, false, &b);
        CHECK_EQ(d.n, b.n);
    }
    printf("DDA vs Bresenham, 20000 lines each, interior steps (differing lines, tie pixels, "
           "rounding pixels):\n"
           "  naive, centres:       %ld %ld %ld\n  incremental, centres: %ld %ld %ld\n"
           "  naive, 1/256:         %ld %ld %ld\n  incremental, 1/256:   %ld %ld %ld\n",
           naive_c.lines_differing, naive_c.ties, naive_c.rounding, inc_c.lines_differing,
           inc_c.ties, inc_c.rounding, naive_s.lines_differing, naive_s.ties, naive_s.rounding,
           inc_s.lines_differing, inc_s.ties, inc_s.rounding);
    /* Short lines: a non-tie v(c) is at least 1/(256 * 2^16) from an
     * integer, far above double rounding; the fixed-point DDA's error
     * (2^-33 per step) stays below it too. */
    CHECK_EQ(naive_c.rounding + naive_s.rounding, 0);
    CHECK_EQ(inc_c.rounding + inc_s.rounding, 0);
    CHECK(naive_c.ties > 0 && naive_s.ties > 0);

    /* Long lines (up to 2^20 px): rounding starts to show in the DDAs. */
    dda_stats naive_l = { 0 }, inc_l = { 0 };
    for (int i = 0; i < 300; i++) {
        sr__line_q8 l = { sr_rng_int(&rng, 0, 1 << 28), sr_rng_int(&rng, 0, 1 << 28),
                          sr_rng_int(&rng, 0, 1 << 28), sr_rng_int(&rng, 0, 1 << 28) };
        /* Visit a 2000-step window in the middle of the line. */
        bool xmaj = llabs(l.bx - l.ax) >= llabs(l.by - l.ay);
        int64_t mu = ((xmaj ? l.ax + l.bx : l.ay + l.by) / 2) / 256;
        int64_t mv = ((xmaj ? l.ay + l.by : l.ax + l.bx) / 2) / 256;
        sr__irect r = xmaj ? (sr__irect){ (int)mu - 1000, -8192 - (1 << 20), (int)mu + 1000, (1 << 21) }
                           : (sr__irect){ -8192 - (1 << 20), (int)mu - 1000, (1 << 21), (int)mu + 1000 };
        (void)mv;
        for (int inc = 0; inc < 2; inc++) {
            dda_stats *st = inc ? &inc_l : &naive_l;
            d.n = 0;
            b.n = 0;
            sr__line_dda(&l, inc, r, SR_LINE_CLIP_LIANG_BARSKY, collect, &d);
            sr__line_bresenham(&l, r, SR_LINE_CLIP_LIANG_BARSKY, true, collect, &b);
            bool differs = false;
            for (int p = 0; p < d.n; p++) {
                if (!contains(&b, d.p[p].x, d.p[p].y)) {
                    differs = true;
                    int k = xmaj ? d.p[p].x : d.p[p].y;
                    if (exact_tie(&l, k)) {
                        st->ties++;
                    } else {
                        st->rounding++;
                    }
                }
            }
            st->lines++;
            st->lines_differing += differs;
        }
    }
    printf("  long lines (300, 2000-step window): naive %ld %ld %ld, incremental %ld %ld %ld\n",
           naive_l.lines_differing, naive_l.ties, naive_l.rounding, inc_l.lines_differing,
           inc_l.ties, inc_l.rounding);
    /* Bound: at most one pixel in a thousand. */
    CHECK(naive_l.rounding + naive_l.ties <= 300 * 2000 / 1000);
    CHECK(inc_l.rounding + inc_l.ties <= 300 * 2000 / 1000);
    free(d.p);
    free(b.p);
}

/* ---- clipping ------------------------------------------------------------------------ */

typedef void (*aliased_fn)(const sr__line_q8 *l, sr__irect clip, sr_line_clipper c, pixset *out);

static void run_bres(const sr__line_q8 *l, sr__irect clip, sr_line_clipper c, pixset *o)
{
    sr__line_bresenham(l, clip, c, false, collect, o);
}
static void run_dda_naive(const sr__line_q8 *l, sr__irect clip, sr_line_clipper c, pixset *o)
{
    sr__line_dda(l, false, clip, c, collect, o);
}
static void run_dda_inc(const sr__line_q8 *l, sr__irect clip, sr_line_clipper c, pixset *o)
{
    sr__line_dda(l, true, clip, c, collect, o);
}
static void run_wide3_round(const sr__line_q8 *l, sr__irect clip, sr_line_clipper c, pixset *o)
{
    sr__line_wide(l, 3, SR_LINE_CAP_ROUND, clip, c, collect, o);
}
static void run_wide4_square(const sr__line_q8 *l, sr__irect clip, sr_line_clipper c, pixset *o)
{
    sr__line_wide(l, 4, SR_LINE_CAP_SQUARE, clip, c, collect, o);
}

SR_TEST(clipped_lines_draw_exactly_the_unclipped_pixels_inside_the_rectangle)
{
    const aliased_fn fns[] = { run_bres, run_dda_naive, run_dda_inc, run_wide3_round,
                               run_wide4_square };
    const char *names[] = { "bresenham", "dda naive", "dda incremental", "wide 3 round",
                            "wide 4 square" };
    const sr_line_clipper clippers[2] = { SR_LINE_CLIP_COHEN_SUTHERLAND,
                                          SR_LINE_CLIP_LIANG_BARSKY };
    sr_rng rng = { 0xc11b };
    pixset ref = { 0 }, got = { 0 };
    long compared = 0, visible_pixels = 0;
    for (int i = 0; i < 6000; i++) {
        sr__line_q8 l = random_q8(&rng, -300, 400);
        sr__irect r = { sr_rng_int(&rng, 0, 80), sr_rng_int(&rng, 0, 80), 0, 0 };
        r.x1 = r.x0 + sr_rng_int(&rng, 1, 48);
        r.y1 = r.y0 + sr_rng_int(&rng, 1, 48);
        for (int f = 0; f < 5; f++) {
            ref.n = 0;
            fns[f](&l, BIG, SR__LINE_CLIP_NONE, &ref);     /* every step from the start */
            keep_inside(&ref, r);
            for (int c = 0; c < 2; c++) {
                got.n = 0;
                fns[f](&l, r, clippers[c], &got);
                compared++;
                visible_pixels += got.n;
                if (has_duplicates(&got) || !same_set(&got, &ref)) {
                    sr_test_fail(__FILE__, __LINE__, "%s, clipper %d, line %d: %d vs %d pixels",
                                 names[f], c, i, got.n, ref.n);
                    i = 1 << 30;
                    break;
                }
            }
        }
    }
    printf("clipping: %ld clipped lines compared, %ld visible pixels\n", compared, visible_pixels);
    free(ref.p);
    free(got.p);
}

/* Endpoints at +-1e9: only the visible steps are visited (the test would
 * take hours otherwise) and the pixels are those of the line evaluated
 * at every column of the rectangle. */
SR_TEST(huge_lines_cost_their_visible_length_and_keep_their_pixels)
{
    sr_rng rng = { 0x1e9 };
    pixset ref = { 0 }, got = { 0 };
    for (int i = 0; i < 400; i++) {
        sr_point2 a = { sr_rng_range(&rng, -1e9, 1e9), sr_rng_range(&rng, -1e9, 1e9) };
        /* Through a random point of the 200x200 rectangle. */
        double px = sr_rng_range(&rng, 0, 200), py = sr_rng_range(&rng, 0, 200);
        sr_point2 b = { px + (px - a.x), py + (py - a.y) };
        sr__line_q8 l = { sr__line_snap_q8(a.x), sr__line_snap_q8(a.y), sr__line_snap_q8(b.x),
                          sr__line_snap_q8(b.y) };
        sr__irect r = { 0, 0, 200, 200 };
        ref.n = 0;
        sr__line_bresenham(&l, r, SR__LINE_CLIP_NONE, true, collect, &ref);
        for (int c = 0; c < 2; c++) {
            got.n = 0;
            sr__line_bresenham(&l, r, c ? SR_LINE_CLIP_LIANG_BARSKY : SR_LINE_CLIP_COHEN_SUTHERLAND,
                               false, collect, &got);
            CHECK(ref.n > 0);
            if (!same_set(&got, &ref)) {
                sr_test_fail(__FILE__, __LINE__, "huge line %d clipper %d differs", i, c);
                i = 1 << 30;
                break;
            }
        }
        /* The same line with endpoints on pixel centres: the integer
         * midpoint loop enters mid-line with d computed in 128 bits. */
        sr__line_q8 lc = { 256 * (int64_t)ref_floor_div(l.ax, 256) + 128,
                           256 * (int64_t)ref_floor_div(l.ay, 256) + 128,
                           256 * (int64_t)ref_floor_div(l.bx, 256) + 128,
                           256 * (int64_t)ref_floor_div(l.by, 256) + 128 };
        ref.n = 0;
        got.n = 0;
        sr__line_bresenham(&lc, r, SR__LINE_CLIP_NONE, true, collect, &ref);
        CHECK(sr__line_bresenham_centres(&lc, r, SR_LINE_CLIP_LIANG_BARSKY, collect, &got));
        CHECK(same_set(&got, &ref));
        for (int inc = 0; inc < 2; inc++) {
            ref.n = 0;
            got.n = 0;
            sr__line_dda(&l, inc, r, SR__LINE_CLIP_NONE, collect, &ref);
            sr__line_dda(&l, inc, r, SR_LINE_CLIP_LIANG_BARSKY, collect, &got);
            CHECK(same_set(&got, &ref));
        }
    }
    /* Through the public call, both clippers, every algorithm. */
    sr_context *ctx = NULL;
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ 0 }, &ctx) == SR_OK);
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 64, .height = 64 }, &fb) == SR_OK);
    for (int alg = SR_LINE_DDA_NAIVE; alg <= SR_LINE_WIDE; alg++) {
        for (int c = SR_LINE_CLIP_COHEN_SUTHERLAND; c <= SR_LINE_CLIP_LIANG_BARSKY; c++) {
            sr_line_desc d = { .algorithm = (sr_line_algorithm)alg, .width = 3,
                               .cap = SR_LINE_CAP_ROUND, .clipper = (sr_line_clipper)c };
            CHECK_EQ(sr_draw_line(ctx, fb, (sr_point2){ -1e9, -1e9 + 7 }, (sr_point2){ 1e9, 1e9 + 7 },
                                  (sr_rgba){ 1, 1, 1, 1 }, &d), SR_OK);
        }
    }
    const uint8_t *px = sr_framebuffer_pixels(fb);
    CHECK(px[4 * (40 * 64 + 33)] == 255);   /* the line y = x + 7 passes (33.5, 40.5) */
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
    free(ref.p);
    free(got.p);
}

SR_TEST(clippers_agree_and_keep_points_on_the_line)
{
    sr_rng rng = { 0xc5b };
    sr_point2 rmin = { 10, 20 }, rmax = { 90, 70 };
    for (int i = 0; i < 20000; i++) {
        sr_point2 a = { sr_rng_range(&rng, -100, 200), sr_rng_range(&rng, -100, 200) };
        sr_point2 b = { sr_rng_range(&rng, -100, 200), sr_rng_range(&rng, -100, 200) };
        sr_point2 a1 = a, b1 = b, a2 = a, b2 = b;
        bool v1 = sr_clip_line_cohen_sutherland(rmin, rmax, &a1, &b1);
        bool v2 = sr_clip_line_liang_barsky(rmin, rmax, &a2, &b2);
        /* They may disagree only for lines grazing a corner. */
        if (v1 != v2) {
            sr_point2 v = v1 ? a1 : a2, w = v1 ? b1 : b2;
            CHECK(hypot(v.x - w.x, v.y - w.y) < 1e-9);
            continue;
        }
        if (!v1) {
            continue;
        }
        CHECK(hypot(a1.x - a2.x, a1.y - a2.y) < 1e-9 && hypot(b1.x - b2.x, b1.y - b2.y) < 1e-9);
        for (int k = 0; k < 2; k++) {
            sr_point2 p = k ? b1 : a1;
            CHECK(p.x >= rmin.x - 1e-9 && p.x <= rmax.x + 1e-9 && p.y >= rmin.y - 1e-9 &&
                  p.y <= rmax.y + 1e-9);
            double cross = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
            CHECK(fabs(cross) < 1e-8 * (1 + hypot(b.x - a.x, b.y - a.y)) * 300);
        }
    }
    sr_point2 n1 = { NAN, 0 }, n2 = { 5, 5 };
    CHECK(!sr_clip_line_liang_barsky(rmin, rmax, &n1, &n2));
    CHECK(!sr_clip_line_cohen_sutherland(rmin, rmax, &n1, &n2));
    sr_point2 i1 = { -INFINITY, 30 }, i2 = { 50, 30 };
    CHECK(!sr_clip_line_liang_barsky(rmin, rmax, &i1, &i2));
    /* Finite ends so far apart that b - a overflows: a visible part that
     * is finite and inside the rectangle (at this scale a double's t
     * resolves only to ~1e292 along the line, so no closer than that). */
    const double big = 1e308;
    struct { sr_point2 rmin, rmax, a, b; } far[] = {
        { { 0, 0 }, { 3, 3 }, { -big, -big }, { big, big } },
        { { 0, 0 }, { 3, 3 }, { -DBL_MAX, 1 }, { DBL_MAX, 1 } },
        { { -1, -DBL_MAX }, { 1, DBL_MAX }, { -DBL_MAX, 1 }, { DBL_MAX, 1 } },
    };
    for (size_t i = 0; i < sizeof far / sizeof far[0]; i++) {
        for (int c = 0; c < 2; c++) {
            sr_point2 a = far[i].a, b = far[i].b;
            bool v = c ? sr_clip_line_cohen_sutherland(far[i].rmin, far[i].rmax, &a, &b)
                       : sr_clip_line_liang_barsky(far[i].rmin, far[i].rmax, &a, &b);
            CHECK(v);
            for (int k = 0; k < 2; k++) {
                sr_point2 p = k ? b : a;
                CHECK(p.x >= far[i].rmin.x && p.x <= far[i].rmax.x && p.y >= far[i].rmin.y &&
                      p.y <= far[i].rmax.y);
                CHECK(i == 0 || p.y == 1);
            }
        }
    }
}

/* ---- Wu ------------------------------------------------------------------------------ */

static double total_coverage(const pixset *s)
{
    double t = 0;
    for (int i = 0; i < s->n; i++) {
        t += s->p[i].c;
    }
    return t;
}

/* Each column's two weights sum to 1, so a Wu line's total intensity is
 * its extent along the major axis (= its length for axis-aligned lines;
 * 1/cos of the angle dimmer per unit length on diagonals, the known
 * weakness of Wu's lines: brightness depends on the slope). */
SR_TEST(wu_total_intensity_equals_major_length_within_one_percent)
{
    sr_rng rng = { 0x3u };
    pixset s = { 0 };
    sr__irect big = { 0, 0, 2048, 2048 };
    for (int i = 0; i < 200; i++) {
        sr_point2 a = { sr_rng_range(&rng, 10, 2038), sr_rng_range(&rng, 10, 2038) };
        sr_point2 b = { sr_rng_range(&rng, 10, 2038), sr_rng_range(&rng, 10, 2038) };
        double major = fmax(fabs(b.x - a.x), fabs(b.y - a.y));
        if (major < 200) {
            continue;
        }
        s.n = 0;
        sr__line_wu(a, b, big, SR_LINE_CLIP_LIANG_BARSKY, collect, &s);
        CHECK(!has_duplicates(&s));
        CHECK_NEAR(total_coverage(&s) / major, 1.0, 0.01);
    }
    /* Horizontal: total intensity = length. */
    s.n = 0;
    sr__line_wu((sr_point2){ 10.25, 40.3 }, (sr_point2){ 1510.25, 40.3 }, big,
                SR_LINE_CLIP_LIANG_BARSKY, collect, &s);
    CHECK_NEAR(total_coverage(&s), 1500.0, 15.0);

    /* Through the framebuffer, white on black, in linear light. */
    sr_context *ctx = NULL;
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ 0 }, &ctx) == SR_OK);
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 1024, .height = 256 }, &fb) == SR_OK);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    sr_point2 a = { 12.3, 30.6 }, b = { 1000.9, 220.2 };
    REQUIRE(sr_draw_line(ctx, fb, a, b, (sr_rgba){ 1, 1, 1, 1 },
                         &(sr_line_desc){ .algorithm = SR_LINE_WU }) == SR_OK);
    const uint8_t *px = sr_framebuffer_pixels(fb);
    double sum = 0;
    for (int i = 0; i < 1024 * 256; i++) {
        double c = px[4 * i] / 255.0;
        sum += c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
    }
    CHECK_NEAR(sum / (b.x - a.x), 1.0, 0.01);
    printf("Wu through the framebuffer: intensity %.2f, major length %.2f, length %.2f\n", sum,
           b.x - a.x, hypot(b.x - a.x, b.y - a.y));
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
    free(s.p);
}

/* ---- exact area coverage ------------------------------------------------------------- */

/* Supersampled coverage of the width-w rectangle around a->b (butt
 * caps) in pixel (x, y): n x n samples at sub-cell centres. */
static double supersampled(sr_point2 a, sr_point2 b, double w, int x, int y, int n)
{
    double dx = b.x - a.x, dy = b.y - a.y, len = hypot(dx, dy);
    dx /= len;
    dy /= len;
    int inside = 0;
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++) {
            double px = x + (j + 0.5) / n - a.x, py = y + (i + 0.5) / n - a.y;
            double along = px * dx + py * dy, across = -px * dy + py * dx;
            inside += along >= 0 && along <= len && fabs(across) <= 0.5 * w;
        }
    }
    return (double)inside / ((double)n * n);
}

SR_TEST(area_lines_match_a_supersampled_reference)
{
    sr_rng rng = { 0xa4ea };
    pixset s = { 0 };
    sr__irect r = { 0, 0, 40, 40 };
    double worst = 0;
    long pixels = 0;
    for (int i = 0; i < 40; i++) {
        sr_point2 a = { sr_rng_range(&rng, 4, 36), sr_rng_range(&rng, 4, 36) };
        sr_point2 b = { sr_rng_range(&rng, 4, 36), sr_rng_range(&rng, 4, 36) };
        double w = sr_rng_range(&rng, 0.3, 4.0);
        s.n = 0;
        sr__line_area(a, b, w, SR_LINE_CAP_BUTT, r, SR_LINE_CLIP_LIANG_BARSKY, collect, &s);
        CHECK(!has_duplicates(&s));
        /* The total is the rectangle's area. */
        CHECK_NEAR(total_coverage(&s), w * hypot(b.x - a.x, b.y - a.y), 1e-3);
        /* 256 x 256 samples per pixel on the pixels drawn and their
         * neighbours (which must be empty where not drawn). */
        for (int y = 0; y < 40; y++) {
            for (int x = 0; x < 40; x++) {
                double c = 0;
                bool drawn = false;
                for (int k = 0; k < s.n; k++) {
                    if (s.p[k].x == x && s.p[k].y == y) {
                        c = s.p[k].c;
                        drawn = true;
                    }
                }
                bool near = drawn;
                for (int k = 0; k < s.n && !near; k++) {
                    near = abs(s.p[k].x - x) <= 1 && abs(s.p[k].y - y) <= 1;
                }
                if (!near) {
                    continue;
                }
                double ref = supersampled(a, b, w, x, y, 256);
                worst = fmax(worst, fabs(c - ref));
                pixels++;
                CHECK_NEAR(c, ref, 1.0 / 255.0);
            }
        }
    }
    printf("area lines: %ld pixels vs 256x256 supersampling, worst difference %.5f\n", pixels,
           worst);
    free(s.p);
}

SR_TEST(area_line_caps_add_the_expected_area)
{
    sr__irect r = { 0, 0, 64, 64 };
    pixset s = { 0 };
    sr_point2 a = { 10.3, 20.7 }, b = { 50.1, 33.9 };
    double len = hypot(b.x - a.x, b.y - a.y), w = 5.0;
    sr__line_area(a, b, w, SR_LINE_CAP_SQUARE, r, SR_LINE_CLIP_LIANG_BARSKY, collect, &s);
    CHECK_NEAR(total_coverage(&s), w * (len + w), 1e-3);
    s.n = 0;
    sr__line_area(a, b, w, SR_LINE_CAP_ROUND, r, SR_LINE_CLIP_LIANG_BARSKY, collect, &s);
    CHECK_NEAR(total_coverage(&s), w * len + M_PI * w * w / 4, 0.01);
    free(s.p);
}

/* ---- wide aliased lines -------------------------------------------------------------- */

SR_TEST(wide_lines_have_w_pixels_in_every_column)
{
    sr_rng rng = { 0x1de };
    pixset s = { 0 }, thin = { 0 };
    for (int i = 0; i < 3000; i++) {
        sr__line_q8 l = random_q8(&rng, 10, 90);
        int w = sr_rng_int(&rng, 1, 9);
        s.n = 0;
        sr__line_wide(&l, w, SR_LINE_CAP_BUTT, BIG, SR_LINE_CLIP_LIANG_BARSKY, collect, &s);
        CHECK(!has_duplicates(&s));
        /* The thin line offset by -(w-1)/2 gives the first pixel of each run. */
        bool xmaj = llabs(l.bx - l.ax) >= llabs(l.by - l.ay);
        sr__line_q8 off = l;
        if (xmaj) {
            off.ay -= (w - 1) * 128;
            off.by -= (w - 1) * 128;
        } else {
            off.ax -= (w - 1) * 128;
            off.bx -= (w - 1) * 128;
        }
        bresenham(&off, BIG, SR_LINE_CLIP_LIANG_BARSKY, true, &thin);
        CHECK_EQ(s.n, thin.n * w);
        for (int p = 0; p < thin.n && !sr_test_failed_now(); p++) {
            for (int k = 0; k < w; k++) {
                CHECK(contains(&s, thin.p[p].x + (xmaj ? 0 : k), thin.p[p].y + (xmaj ? k : 0)));
            }
        }
        /* Caps draw every pixel once. */
        for (int cap = SR_LINE_CAP_SQUARE; cap <= SR_LINE_CAP_ROUND; cap++) {
            s.n = 0;
            sr__line_wide(&l, w, (sr_line_cap)cap, BIG, SR_LINE_CLIP_LIANG_BARSKY, collect, &s);
            CHECK(!has_duplicates(&s));
            CHECK(s.n >= thin.n * w);
        }
        if (sr_test_failed_now()) {
            break;
        }
    }
    free(s.p);
    free(thin.p);
}

/* ---- antialiased lines under clipping ------------------------------------------------- */

static float coverage_at(const pixset *s, int x, int y)
{
    for (int i = 0; i < s->n; i++) {
        if (s->p[i].x == x && s->p[i].y == y) {
            return s->p[i].c;
        }
    }
    return 0.0f;
}

/* Wu evaluates each column from the first end, so clipping changes
 * nothing; the area line's polygon is built from the clipped segment,
 * which moves its far ends but not its pixels inside (within rounding). */
SR_TEST(antialiased_lines_are_unchanged_by_clipping)
{
    sr_rng rng = { 0xaac1 };
    pixset ref = { 0 }, got = { 0 };
    double worst_area = 0;
    for (int i = 0; i < 3000; i++) {
        sr_point2 a = { sr_rng_range(&rng, -300, 400), sr_rng_range(&rng, -300, 400) };
        sr_point2 b = { sr_rng_range(&rng, -300, 400), sr_rng_range(&rng, -300, 400) };
        sr__irect r = { sr_rng_int(&rng, 0, 80), sr_rng_int(&rng, 0, 80), 0, 0 };
        r.x1 = r.x0 + sr_rng_int(&rng, 1, 48);
        r.y1 = r.y0 + sr_rng_int(&rng, 1, 48);
        double w = sr_rng_range(&rng, 0.5, 5);
        sr_line_cap cap = (sr_line_cap)sr_rng_int(&rng, 1, 3);
        for (int c = 0; c < 2; c++) {
            sr_line_clipper clipper = c ? SR_LINE_CLIP_LIANG_BARSKY : SR_LINE_CLIP_COHEN_SUTHERLAND;
            ref.n = got.n = 0;
            sr__line_wu(a, b, r, SR__LINE_CLIP_NONE, collect, &ref);
            sr__line_wu(a, b, r, clipper, collect, &got);
            CHECK(same_set(&got, &ref));
            for (int k = 0; k < got.n; k++) {
                CHECK(got.p[k].c == coverage_at(&ref, got.p[k].x, got.p[k].y));
            }
            ref.n = got.n = 0;
            sr__line_area(a, b, w, cap, r, SR__LINE_CLIP_NONE, collect, &ref);
            sr__line_area(a, b, w, cap, r, clipper, collect, &got);
            for (int k = 0; k < ref.n; k++) {
                double d = fabs(ref.p[k].c - coverage_at(&got, ref.p[k].x, ref.p[k].y));
                worst_area = fmax(worst_area, d);
            }
            for (int k = 0; k < got.n; k++) {
                double d = fabs(got.p[k].c - coverage_at(&ref, got.p[k].x, got.p[k].y));
                worst_area = fmax(worst_area, d);
            }
        }
        if (sr_test_failed_now()) {
            break;
        }
    }
    printf("area lines, clipped vs unclipped: worst coverage difference %.3g\n", worst_area);
    CHECK(worst_area < 1e-6);
    free(ref.p);
    free(got.p);
}

/* ---- through the public call ----------------------------------------------------------- */

SR_TEST(draw_line_validates_its_arguments)
{
    sr_context *ctx = NULL;
    sr_framebuffer *fb = NULL;
    REQUIRE(sr_make_context(&(sr_context_desc){ 0 }, &ctx) == SR_OK);
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = 16, .height = 16 }, &fb) == SR_OK);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    sr_rgba white = { 1, 1, 1, 1 };
    sr_point2 a = { 1, 1 }, b = { 14, 9 };
    CHECK_EQ(sr_draw_line(NULL, fb, a, b, white, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_draw_line(ctx, NULL, a, b, white, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_draw_line(ctx, fb, (sr_point2){ NAN, 1 }, b, white, NULL), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "a.x");
    CHECK_EQ(sr_draw_line(ctx, fb, a, (sr_point2){ 3, INFINITY }, white, NULL), SR_INVALID_ARG);
    CHECK_STR_CONTAINS(sr_context_error(ctx), "b.y");
    CHECK_EQ(sr_draw_line(ctx, fb, a, (sr_point2){ 3e12, 0 }, white, NULL), SR_TOO_LARGE);
    CHECK_EQ(sr_draw_line(ctx, fb, a, b, (sr_rgba){ NAN, 0, 0, 1 }, NULL), SR_INVALID_ARG);
    CHECK_EQ(sr_draw_line(ctx, fb, a, b, white, &(sr_line_desc){ .algorithm = 42 }), SR_INVALID_ARG);
    CHECK_EQ(sr_draw_line(ctx, fb, a, b, white, &(sr_line_desc){ .cap = 9 }), SR_INVALID_ARG);
    CHECK_EQ(sr_draw_line(ctx, fb, a, b, white, &(sr_line_desc){ .clipper = 7 }), SR_INVALID_ARG);
    CHECK_EQ(sr_draw_line(ctx, fb, a, b, white, &(sr_line_desc){ .width = -1 }), SR_INVALID_ARG);
    CHECK_EQ(sr_draw_line(ctx, fb, a, b, white, &(sr_line_desc){ .width = NAN }), SR_INVALID_ARG);
    CHECK_EQ(sr_draw_line(ctx, fb, a, b, white,
                          &(sr_line_desc){ .algorithm = SR_LINE_WIDE, .width = 5000 }),
             SR_INVALID_ARG);
    const uint8_t *px = sr_framebuffer_pixels(fb);
    for (int i = 0; i < 16 * 16; i++) {
        CHECK_EQ(px[4 * i], 0);   /* nothing drawn by a failed call */
    }
    /* Degenerate lines draw nothing and succeed. */
    for (int alg = SR_LINE_DDA_NAIVE; alg <= SR_LINE_WIDE; alg++) {
        CHECK_EQ(sr_draw_line(ctx, fb, a, a, white, &(sr_line_desc){ .algorithm = alg }), SR_OK);
    }
    px = sr_framebuffer_pixels(fb);
    for (int i = 0; i < 16 * 16; i++) {
        CHECK_EQ(px[4 * i], 0);
    }
    /* The default draws the Bresenham pixels. */
    CHECK_EQ(sr_draw_line(ctx, fb, (sr_point2){ 0.5, 0.5 }, (sr_point2){ 8.5, 3.5 }, white, NULL),
             SR_OK);
    px = sr_framebuffer_pixels(fb);
    CHECK_EQ(px[4 * (1 * 16 + 4)], 255);
    CHECK_EQ(px[4 * (2 * 16 + 4)], 0);
    CHECK_EQ(px[4 * (3 * 16 + 8)], 0);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}

SR_TEST(every_algorithm_draws_each_pixel_once)
{
    sr_rng rng = { 0x0e };
    pixset s = { 0 };
    sr__irect r = { 0, 0, 50, 50 };
    for (int i = 0; i < 3000; i++) {
        sr_point2 a = { sr_rng_range(&rng, -20, 70), sr_rng_range(&rng, -20, 70) };
        sr_point2 b = { sr_rng_range(&rng, -20, 70), sr_rng_range(&rng, -20, 70) };
        s.n = 0;
        sr__line_wu(a, b, r, SR_LINE_CLIP_COHEN_SUTHERLAND, collect, &s);
        CHECK(!has_duplicates(&s));
        s.n = 0;
        sr__line_area(a, b, sr_rng_range(&rng, 0.2, 6), (sr_line_cap)sr_rng_int(&rng, 1, 3), r,
                      SR_LINE_CLIP_COHEN_SUTHERLAND, collect, &s);
        CHECK(!has_duplicates(&s));
        for (int k = 0; k < s.n; k++) {
            CHECK(s.p[k].x >= 0 && s.p[k].x < 50 && s.p[k].y >= 0 && s.p[k].y < 50);
            CHECK(s.p[k].c > 0 && s.p[k].c <= 1);
        }
        if (sr_test_failed_now()) {
            break;
        }
    }
    free(s.p);
}
