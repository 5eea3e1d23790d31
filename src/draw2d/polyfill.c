/* polyfill.c - draw2d stage: polygon scan conversion.
 * Consumes contours of sr_point2, produces spans or coverage rows for a
 * window.  Four converters: the scan-line fill with an edge table (ET)
 * and a sorted active edge table (AET) in exact integer arithmetic, the
 * same fill with unsorted winding cells and a prefix sum (the fast one the
 * fills use; the sorted one is its reference and names span edges), the
 * signed-area accumulator for exact antialiased coverage, and n x n
 * supersampling built on the winding cells.  Runs on the caller's thread. */
#include "draw2d/polyfill.h"

#include "context.h"
#include "draw2d/paint.h"
#include "rows.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define Q8_ONE 256
#define Q8_HALF 128
#define MAX_SUPERSAMPLE 16

_Static_assert((int64_t)SR_MAX_COORD2D * MAX_SUPERSAMPLE * Q8_ONE <= ((int64_t)1 << 30),
               "q8 coordinates (supersampled) must stay within 2^30 for the ET bit budget");

/* floor(a / b) for b > 0. */
static int64_t floor_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    if ((a % b != 0) && (a < 0)) {
        q--;
    }
    return q;
}

/* ---- setup: contours -> q8 edges ------------------------------------- */

/* sr__edges_from_polygon into `local` (room for local_cap edges) when the
 * polygon fits there, else into memory from ctx; *edges is one or the other. */
static sr_result edges_into(sr_context *ctx, const char *fn, const sr_polygon2 *poly, int scale,
                            const sr__window *win, sr__edge2 *local, int local_cap,
                            sr__edge2 **edges, int *count)
{
    *edges = NULL;
    *count = 0;
    if (!poly) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: polygon is NULL", fn);
    }
    if (poly->point_count < 0 || (poly->point_count > 0 && !poly->points)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_polygon2.points is NULL or point_count < 0",
                        fn);
    }
    if (poly->contour_counts && poly->contour_count < 0) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_polygon2.contour_count < 0", fn);
    }
    int contours = poly->contour_counts ? poly->contour_count : 1;
    long long total = 0;
    for (int c = 0; c < contours; c++) {
        int n = poly->contour_counts ? poly->contour_counts[c] : poly->point_count;
        if (n < 0) {
            return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_polygon2.contour_counts[%d] < 0", fn, c);
        }
        total += n;
    }
    if (total != poly->point_count) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "%s: sr_polygon2.contour_counts sum to %lld, point_count is %d", fn,
                        total, poly->point_count);
    }
    bool huge = false;
    for (int i = 0; i < poly->point_count; i++) {
        double x = poly->points[i].x, y = poly->points[i].y;
        if (!isfinite(x) || !isfinite(y)) {
            return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_polygon2.points[%d] is not finite", fn, i);
        }
        if (fabs(x) > SR_MAX_COORD2D || fabs(y) > SR_MAX_COORD2D) {
            if (!win) {
                return sr__fail(ctx, SR_TOO_LARGE, "%s: sr_polygon2.points[%d] (%g, %g) is "
                                "beyond +-%g pixels", fn, i, x, y, SR_MAX_COORD2D);
            }
            huge = true;
        }
    }
    if (huge) {
        /* Beyond the fixed-point budget: drawn as the part of it that can
         * reach the window (guardclip.c), which fits the budget. */
        sr_polygon2 cut;
        sr_result r = sr__guard_clip(ctx, fn, poly, *win, &cut);
        if (r == SR_OK) {
            r = edges_into(ctx, fn, &cut, scale, NULL, local, local_cap, edges, count);
        }
        sr__free(ctx, (void *)cut.points);
        sr__free(ctx, (void *)cut.contour_counts);
        return r;
    }
    if (poly->point_count == 0) {
        return SR_OK;
    }
    sr__edge2 *e = poly->point_count <= local_cap
                       ? local : sr__calloc(ctx, (size_t)poly->point_count, sizeof *e);
    if (!e) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "%s: no memory for %d edges", fn,
                        poly->point_count);
    }
    int n_edges = 0, start = 0;
    for (int c = 0; c < contours; c++) {
        int n = poly->contour_counts ? poly->contour_counts[c] : poly->point_count;
        for (int k = 0; k < n; k++) {
            int ia = start + k, ib = start + (k + 1) % n;
            /* Snap to 1/256 with round-to-nearest-even (the default mode). */
            int64_t ax = (int64_t)nearbyint(poly->points[ia].x * Q8_ONE) * scale;
            int64_t ay = (int64_t)nearbyint(poly->points[ia].y * Q8_ONE) * scale;
            int64_t bx = (int64_t)nearbyint(poly->points[ib].x * Q8_ONE) * scale;
            int64_t by = (int64_t)nearbyint(poly->points[ib].y * Q8_ONE) * scale;
            if (ay == by) {
                continue; /* horizontal edges cross no scanline */
            }
            sr__edge2 *d = &e[n_edges++];
            if (ay < by) {
                *d = (sr__edge2){ ax, ay, bx, by, +1, ia, ib };
            } else {
                *d = (sr__edge2){ bx, by, ax, ay, -1, ib, ia };
            }
        }
        start += n;
    }
    *edges = e;
    *count = n_edges;
    return SR_OK;
}

sr_result sr__edges_from_polygon(sr_context *ctx, const char *fn, const sr_polygon2 *poly,
                                 int scale, sr__edge2 **edges, int *count)
{
    return edges_into(ctx, fn, poly, scale, NULL, NULL, 0, edges, count);
}

/* Shrink the window's rows to those the edges can touch (pixel rows
 * floor(y_min) .. ceil(y_max) - 1), so a small polygon in a large target
 * does not walk every scanline. */
static sr__window rows_of_edges(const sr__edge2 *edges, int count, sr__window win)
{
    int64_t lo = INT64_MAX, hi = INT64_MIN;
    for (int i = 0; i < count; i++) {
        lo = edges[i].y0 < lo ? edges[i].y0 : lo;
        hi = edges[i].y1 > hi ? edges[i].y1 : hi;
    }
    int64_t r0 = floor_div(lo, Q8_ONE), r1 = floor_div(hi + Q8_ONE - 1, Q8_ONE);
    if (r0 > win.y0) {
        win.y0 = r0 >= win.y1 ? win.y1 : (int)r0;
    }
    if (r1 < win.y1) {
        win.y1 = r1 <= win.y0 ? win.y0 : (int)r1;
    }
    return win;
}

/* Shrink *win to the edges' rows; false when nothing is left to scan. */
static bool rows_to_scan(const sr__edge2 *edges, int count, sr__window *win)
{
    if (count <= 0) {
        return false;
    }
    *win = rows_of_edges(edges, count, *win);
    return win->x0 < win->x1 && win->y0 < win->y1;
}

/* The columns the edges can touch, floor(x_min) .. floor(x_max) + 1 (a
 * piece in column c also deposits into c + 1), within the window: the
 * converters' per-row buffers and loops need no more.  Narrowing changes
 * no pixel: every deposit and crossing lands in the same absolute column,
 * and what lies left or right of the narrowed window was so of the full
 * one (a contour wholly left of it sums to zero, in the area converter's
 * exact height arithmetic as in the winding cells' integers). */
static sr__window columns_of_edges(const sr__edge2 *edges, int count, sr__window win)
{
    int64_t lo = INT64_MAX, hi = INT64_MIN;
    for (int i = 0; i < count; i++) {
        int64_t a = edges[i].x0 < edges[i].x1 ? edges[i].x0 : edges[i].x1;
        int64_t b = edges[i].x0 < edges[i].x1 ? edges[i].x1 : edges[i].x0;
        lo = a < lo ? a : lo;
        hi = b > hi ? b : hi;
    }
    int64_t c0 = floor_div(lo, Q8_ONE), c1 = floor_div(hi, Q8_ONE) + 2;
    if (c0 > win.x0) {
        win.x0 = c0 >= win.x1 ? win.x1 : (int)c0;
    }
    if (c1 < win.x1) {
        win.x1 = c1 <= win.x0 ? win.x0 : (int)c1;
    }
    return win;
}

/* ---- scan-line fill: edge table + active edge table ------------------- */

/* An edge-table entry.  At scanline y (sample height yc = 256 y + 128 in
 * q8) the edge crosses at x(yc); the first pixel whose centre is at or
 * right of it is ceil((x(yc) - 128) / 256) = ceil(N / D) with
 * N = (x0 - 128) den + (yc - y0) dx and D = 256 den (den = y1 - y0).  N
 * is kept as f D + r, 0 <= r < D, and stepped by 256 dx per scanline: the
 * integer DDA with remainder, so x never drifts.  That pixel index is the
 * sort key: two crossings in the same pixel gap bound an empty span in
 * either order, so sorting by it gives the same pixels as sorting by x. */
typedef struct et_entry {
    int64_t f, r;        /* N = f D + r */
    int64_t q, rem;      /* 256 dx = q D + rem */
    int64_t D;
    int last_row;        /* last scanline where the edge is active */
    int dir;
    int edge;            /* index into the edge array */
    int next;            /* next entry in the same ET bucket, -1 ends */
} et_entry;

static int64_t et_key(const et_entry *e)
{
    return e->f + (e->r > 0);
}

static bool fill_rule_inside(sr_fill_rule rule, int w)
{
    return rule == SR_EVENODD ? (w & 1) != 0 : w != 0;
}

/* Build the ET: bucket each edge by its first scanline in the window
 * (bucket[] has one list head per row, -1 when empty).  Active on y iff
 * y0 <= 256 y + 128 < y1 (half-open in y).  Returns the entry count. */
static int build_edge_table(const sr__edge2 *edges, int count, sr__window win, et_entry *et,
                            int *bucket)
{
    for (int y = 0; y < win.y1 - win.y0; y++) {
        bucket[y] = -1;
    }
    int n_et = 0;
    for (int i = 0; i < count; i++) {
        const sr__edge2 *s = &edges[i];
        int64_t first = floor_div(s->y0 - Q8_HALF + Q8_ONE - 1, Q8_ONE); /* ceil */
        int64_t last = floor_div(s->y1 - Q8_HALF + Q8_ONE - 1, Q8_ONE) - 1;
        if (first < win.y0) {
            first = win.y0;
        }
        if (last >= win.y1) {
            last = win.y1 - 1;
        }
        if (first > last) {
            continue;
        }
        int64_t den = s->y1 - s->y0, dx = s->x1 - s->x0;
        int64_t yc = first * Q8_ONE + Q8_HALF;
        et_entry *e = &et[n_et];
        e->D = den * Q8_ONE;
        int64_t N = (s->x0 - Q8_HALF) * den + (yc - s->y0) * dx;
        e->f = floor_div(N, e->D);
        e->r = N - e->f * e->D;
        e->q = floor_div(dx * Q8_ONE, e->D);
        e->rem = dx * Q8_ONE - e->q * e->D;
        e->last_row = (int)last;
        e->dir = s->dir;
        e->edge = i;
        int b = (int)(first - win.y0);
        e->next = bucket[b];
        bucket[b] = n_et++;
    }
    return n_et;
}

/* x(y+1) = x(y) + 1/m: the DDA step with remainder. */
static void et_step(et_entry *e)
{
    e->f += e->q;
    e->r += e->rem;
    if (e->r >= e->D) {
        e->r -= e->D;
        e->f++;
    }
}

sr_result sr__scan_edge_table(sr_context *ctx, const sr__edge2 *edges, int count,
                              sr_fill_rule rule, sr__window win, sr__span_fn fn, void *user)
{
    if (!rows_to_scan(edges, count, &win)) {
        return SR_OK;
    }
    int rows = win.y1 - win.y0;
    et_entry *et = sr__alloc(ctx, (size_t)count * sizeof *et);
    int *bucket = sr__alloc(ctx, (size_t)rows * sizeof *bucket);
    int *aet = sr__alloc(ctx, (size_t)count * sizeof *aet);
    if (!et || !bucket || !aet) {
        sr__free(ctx, et);
        sr__free(ctx, bucket);
        sr__free(ctx, aet);
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "polygon fill: no memory for the edge table");
    }
    build_edge_table(edges, count, win, et, bucket);
    int n_aet = 0;
    for (int y = win.y0; y < win.y1; y++) {
        /* Drop edges that ended, add the ET bucket of this scanline. */
        int kept = 0;
        for (int k = 0; k < n_aet; k++) {
            if (et[aet[k]].last_row >= y) {
                aet[kept++] = aet[k];
            }
        }
        n_aet = kept;
        for (int i = bucket[y - win.y0]; i >= 0; i = et[i].next) {
            aet[n_aet++] = i;
        }
        /* Insertion sort by x: between scanlines the order only changes
         * where edges cross, so this is nearly linear. */
        for (int k = 1; k < n_aet; k++) {
            int v = aet[k];
            int64_t key = et_key(&et[v]);
            int j = k - 1;
            while (j >= 0 && et_key(&et[aet[j]]) > key) {
                aet[j + 1] = aet[j];
                j--;
            }
            aet[j + 1] = v;
        }
        /* Walk the crossings left to right, accumulating the winding. */
        int w = 0;
        for (int k = 0; k + 1 < n_aet; k++) {
            const et_entry *a = &et[aet[k]], *b = &et[aet[k + 1]];
            w += a->dir;
            if (!fill_rule_inside(rule, w)) {
                continue;
            }
            int64_t xl = et_key(a), xr = et_key(b);
            if (xl < win.x0) {
                xl = win.x0;
            }
            if (xr > win.x1) {
                xr = win.x1;
            }
            if (xl < xr) {
                sr__span sp = { y, (int)xl, (int)xr, NULL, a->edge, b->edge, y + 0.5 };
                fn(user, &sp);
            }
        }
        /* Step every active edge to the next scanline. */
        for (int k = 0; k < n_aet; k++) {
            et_step(&et[aet[k]]);
        }
    }
    sr__free(ctx, et);
    sr__free(ctx, bucket);
    sr__free(ctx, aet);
    return SR_OK;
}

/* ---- scan-line fill, fast: edge table + winding cells ------------------ */

/* The same edge table and the same active edges, but the AET is never
 * sorted: each active edge adds its direction to the winding cell of its
 * first pixel (the sort key above; crossings left of the window count at
 * its first column, those right of it are dropped), and a prefix sum along
 * the row gives the winding number at every pixel centre.  A pixel's
 * winding is the sum over the crossings at or left of it whichever order
 * they come in, so the spans are those of the sorted walk, merged where
 * they touch.  Ended edges leave the active list by swap-remove, since
 * order no longer matters. */
/* The active edges of the winding-cell fill, one array per field so the
 * step over all of them is a straight vectorizable loop. */
typedef struct cell_aet {
    int64_t *f, *r, *q, *rem, *D;
    int *last_row, *dir;
    int n;
} cell_aet;

static void cell_aet_remove(cell_aet *a, int k)
{
    int m = --a->n;
    a->f[k] = a->f[m];
    a->r[k] = a->r[m];
    a->q[k] = a->q[m];
    a->rem[k] = a->rem[m];
    a->D[k] = a->D[m];
    a->last_row[k] = a->last_row[m];
    a->dir[k] = a->dir[m];
}

sr_result sr__scan_winding_cells(sr_context *ctx, const sr__edge2 *edges, int count,
                                 sr_fill_rule rule, sr__window win, sr__span_fn fn, void *user)
{
    if (!rows_to_scan(edges, count, &win)) {
        return SR_OK;
    }
    win = columns_of_edges(edges, count, win);
    if (win.x0 >= win.x1) {
        return SR_OK;
    }
    int rows = win.y1 - win.y0, w = win.x1 - win.x0;
    et_entry *et = sr__alloc(ctx, (size_t)count * sizeof *et);
    int *bucket = sr__alloc(ctx, (size_t)rows * sizeof *bucket);
    int *ends = sr__calloc(ctx, (size_t)rows, sizeof *ends);
    int64_t *wide = sr__alloc(ctx, (size_t)count * 5 * sizeof *wide);
    int *narrow = sr__alloc(ctx, (size_t)count * 2 * sizeof *narrow);
    int *cell = sr__calloc(ctx, (size_t)w, sizeof *cell);
    sr_result res = SR_OK;
    if (!et || !bucket || !ends || !wide || !narrow || !cell) {
        res = sr__fail(ctx, SR_OUT_OF_MEMORY, "polygon fill: no memory for winding cells");
        goto done;
    }
    int n_et = build_edge_table(edges, count, win, et, bucket);
    for (int i = 0; i < n_et; i++) {
        ends[et[i].last_row - win.y0]++;
    }
    size_t n = (size_t)count;
    cell_aet a = { wide, wide + n, wide + 2 * n, wide + 3 * n, wide + 4 * n, narrow, narrow + n,
                   0 };
    for (int y = win.y0; y < win.y1; y++) {
        for (int i = bucket[y - win.y0]; i >= 0; i = et[i].next) {
            int k = a.n++;
            a.f[k] = et[i].f;
            a.r[k] = et[i].r;
            a.q[k] = et[i].q;
            a.rem[k] = et[i].rem;
            a.D[k] = et[i].D;
            a.last_row[k] = et[i].last_row;
            a.dir[k] = et[i].dir;
        }
        int lo = w, hi = -1;
        for (int k = 0; k < a.n; k++) {
            int64_t c = a.f[k] + (a.r[k] > 0) - win.x0;
            c = c < 0 ? 0 : c;
            if (c < w) {
                cell[c] += a.dir[k];
                lo = (int)c < lo ? (int)c : lo;
                hi = (int)c > hi ? (int)c : hi;
            }
        }
        /* Step every active edge (the DDA with remainder, branch-free),
         * then let the edges that ended on this row go. */
        for (int k = 0; k < a.n; k++) {
            int64_t r = a.r[k] + a.rem[k];
            int64_t carry = r >= a.D[k];
            a.f[k] += a.q[k] + carry;
            a.r[k] = r - (a.D[k] & -carry);
        }
        for (int k = 0, left = ends[y - win.y0]; left > 0;) {
            if (a.last_row[k] == y) {
                cell_aet_remove(&a, k); /* look at the moved entry next */
                left--;
            } else {
                k++;
            }
        }
        /* Prefix sum over the touched cells, clearing them for the next
         * row; a span still open after the last crossing runs to the
         * window's right side (its closing crossings were dropped). */
        int wind = 0, open = -1;
        for (int c = lo; c <= hi; c++) {
            wind += cell[c];
            cell[c] = 0;
            bool in = fill_rule_inside(rule, wind);
            if (in && open < 0) {
                open = c;
            } else if (!in && open >= 0) {
                fn(user, &(sr__span){ y, win.x0 + open, win.x0 + c, NULL, -1, -1, y + 0.5 });
                open = -1;
            }
        }
        if (open >= 0) {
            fn(user, &(sr__span){ y, win.x0 + open, win.x1, NULL, -1, -1, y + 0.5 });
        }
    }
done:
    sr__free(ctx, et);
    sr__free(ctx, bucket);
    sr__free(ctx, ends);
    sr__free(ctx, wide);
    sr__free(ctx, narrow);
    sr__free(ctx, cell);
    return res;
}

/* ---- exact area coverage: signed-area accumulation -------------------- */

/* One piece of an edge inside one pixel column c of the current row, from
 * x = xa to xb, with signed height d: the pixel gets d times the part of
 * it right of the piece, the next pixel the rest (the running sum along
 * the row then integrates the winding number over each pixel). */
static void deposit_piece(double *acc, int w, int wx0, double xa, double xb, double d)
{
    double mid = 0.5 * (xa + xb);
    double cf = floor(mid);
    if (cf < wx0) {
        acc[0] += d;
        return;
    }
    if (cf >= (double)wx0 + w) {
        return;
    }
    int c = (int)cf - wx0;
    double f = mid - cf;
    acc[c] += d * (1.0 - f);
    acc[c + 1] += d * f;
}

/* deposit_piece for a piece from x to nx known to lie in window column c
 * (pixel column cf). */
static void split_piece(double *acc, int c, double cf, double x, double nx, double d)
{
    double f = 0.5 * (x + nx) - cf;
    acc[c] += d * (1.0 - f);
    acc[c + 1] += d * f;
}

/* Deposit the part of an edge between heights ya < yb (within one row),
 * x from xa to xb, split at integer x.  The walk goes from xa to xb one
 * column at a time; each piece's height is the difference of the heights
 * ya + (x - xa) dy/dx at its ends, so the pieces sum to yb - ya exactly.
 * Everything left of the window lands in acc[0] in one piece, everything
 * right of it is dropped in one piece. */
static void deposit_segment(double *acc, int w, int wx0, double xa, double ya, double xb,
                            double yb, double dir)
{
    double xmin = xa < xb ? xa : xb, xmax = xa < xb ? xb : xa;
    double right = (double)wx0 + w;
    if (xa == xb || xmax <= wx0 || xmin >= right) {
        /* One piece: within a column, wholly left (into acc[0]) or wholly
         * right (dropped) of the window. */
        deposit_piece(acc, w, wx0, xa, xb, dir * (yb - ya));
        return;
    }
    double dydx = (yb - ya) / (xb - xa);
    double x = xa, y = ya;
    if (xb > xa) {
        if (x < wx0) {
            double ny = ya + (wx0 - xa) * dydx;
            acc[0] += dir * (ny - y);
            x = wx0;
            y = ny;
        }
        /* Column cf holds the piece from x to the next integer (or xb). */
        double cf = floor(x);
        int c = (int)cf - wx0;
        while (x != xb && x < right) {
            double nx = cf + 1.0 > xb ? xb : cf + 1.0;
            double ny = nx == xb ? yb : ya + (nx - xa) * dydx;
            split_piece(acc, c, cf, x, nx, dir * (ny - y));
            x = nx;
            y = ny;
            cf += 1.0;
            c++;
        }
        return;
    }
    if (x > right) {
        /* The part right of the window is dropped. */
        y = ya + (right - xa) * dydx;
        x = right;
    }
    /* Column cf holds the piece from x down to the integer below (or xb). */
    double cf = ceil(x) - 1.0;
    int c = (int)cf - wx0;
    while (x != xb) {
        if (x <= wx0) {
            acc[0] += dir * (yb - y);
            return;
        }
        double nx = cf < xb ? xb : cf;
        double ny = nx == xb ? yb : ya + (nx - xa) * dydx;
        split_piece(acc, c, cf, x, nx, dir * (ny - y));
        x = nx;
        y = ny;
        cf -= 1.0;
        c--;
    }
}

static uint8_t coverage_byte(sr_fill_rule rule, double s)
{
    double a = fabs(s);
    if (rule == SR_EVENODD) {
        a = fmod(a, 2.0);
        if (a > 1.0) {
            a = 2.0 - a;
        }
    } else if (a > 1.0) {
        a = 1.0;
    }
    return (uint8_t)(a * 255.0 + 0.5);
}

typedef struct area_entry {
    double x0, y0, x1, y1; /* pixels, y0 < y1 */
    double dir;
    double inv;            /* dx / dy */
    int last_row;
    int next;
} area_entry;

/* A row is flat when every active edge is vertical and spans it whole:
 * its deposits then depend on nothing that changes from row to row, so two
 * flat rows with the same active edges have the same coverage (the inside
 * of a rectangle, of any shape with only vertical sides). */
static bool row_is_flat(const area_entry *et, const int *active, int n_active, int y)
{
    for (int k = 0; k < n_active; k++) {
        const area_entry *e = &et[active[k]];
        if (e->x0 != e->x1 || e->y0 > y || e->y1 < y + 1.0) {
            return false;
        }
    }
    return true;
}

/* The area converter; `fast` narrows the columns to the edges', reuses a
 * flat row's coverage for the flat rows below it, and takes a column no
 * deposit reached from its left neighbour (the running sum is unchanged
 * there), all giving the bytes the plain walk gives. */
/* A small shape's coverage rows come from the stack (bytes): the fill of
 * an icon-sized shape then allocates nothing. */
#define AREA_STACK_BYTES 4096

static sr_result scan_area(sr_context *ctx, const sr__edge2 *edges, int count, sr_fill_rule rule,
                           sr__window win, sr__span_fn fn, void *user, bool fast)
{
    if (!rows_to_scan(edges, count, &win)) {
        return SR_OK;
    }
    if (fast) {
        win = columns_of_edges(edges, count, win);
        if (win.x0 >= win.x1) {
            return SR_OK;
        }
    }
    int rows = win.y1 - win.y0, w = win.x1 - win.x0;
    /* One block for the five arrays (a fill of a small shape is mostly
     * its setup): the doubles first, then the ints, then the bytes. */
    size_t acc_size = ((size_t)w + 2) * sizeof(double);
    size_t et_size = (size_t)count * sizeof(area_entry);
    size_t ints = ((size_t)rows + (size_t)count) * sizeof(int);
    size_t total = acc_size + et_size + ints + (size_t)w + 1;
    _Alignas(double) char stack[AREA_STACK_BYTES];
    char *block = total <= sizeof stack ? stack : sr__alloc(ctx, total);
    if (!block) {
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "polygon fill: no memory for coverage rows");
    }
    double *acc = (double *)block;
    area_entry *et = (area_entry *)(block + acc_size);
    int *bucket = (int *)(block + acc_size + et_size), *active = bucket + rows;
    uint8_t *cov = (uint8_t *)(block + acc_size + et_size + ints);
    memset(acc, 0, acc_size);
    for (int y = 0; y < rows; y++) {
        bucket[y] = -1;
    }
    int n_et = 0;
    for (int i = 0; i < count; i++) {
        const sr__edge2 *s = &edges[i];
        /* Rows touched: floor(y0) .. ceil(y1) - 1 (pixel units). */
        int64_t first = floor_div(s->y0, Q8_ONE);
        int64_t last = floor_div(s->y1 + Q8_ONE - 1, Q8_ONE) - 1;
        if (first < win.y0) {
            first = win.y0;
        }
        if (last >= win.y1) {
            last = win.y1 - 1;
        }
        if (first > last) {
            continue;
        }
        area_entry *e = &et[n_et];
        e->x0 = s->x0 / 256.0;
        e->y0 = s->y0 / 256.0;
        e->x1 = s->x1 / 256.0;
        e->y1 = s->y1 / 256.0;
        e->dir = s->dir;
        e->inv = (e->x1 - e->x0) / (e->y1 - e->y0);
        e->last_row = (int)last;
        int b = (int)(first - win.y0);
        e->next = bucket[b];
        bucket[b] = n_et++;
    }
    int n_active = 0;
    /* The last row's span (span_x1 = 0 without one) and whether that row
     * was flat, for the next row to reuse. */
    int span_x0 = 0, span_x1 = 0;
    bool prev_flat = false;
    for (int y = win.y0; y < win.y1; y++) {
        int kept = 0;
        for (int k = 0; k < n_active; k++) {
            if (et[active[k]].last_row >= y) {
                active[kept++] = active[k];
            }
        }
        bool same_edges = kept == n_active && bucket[y - win.y0] < 0;
        n_active = kept;
        for (int i = bucket[y - win.y0]; i >= 0; i = et[i].next) {
            active[n_active++] = i;
        }
        if (fast) {
            bool flat = n_active > 0 && row_is_flat(et, active, n_active, y);
            if (flat && prev_flat && same_edges) {
                if (span_x1 > span_x0) {
                    fn(user, &(sr__span){ y, span_x0, span_x1, cov + (span_x0 - win.x0), -1, -1,
                                          y + 0.5 });
                }
                continue;
            }
            prev_flat = flat;
            span_x1 = span_x0;
        }
        if (n_active == 0) {
            continue;
        }
        double lo = INFINITY, hi = -INFINITY;
        for (int k = 0; k < n_active; k++) {
            const area_entry *e = &et[active[k]];
            double ya = e->y0 > y ? e->y0 : y;
            double yb = e->y1 < y + 1.0 ? e->y1 : y + 1.0;
            if (!(ya < yb)) {
                continue;
            }
            double inv = e->inv;
            double xa = (ya == e->y0) ? e->x0 : e->x0 + (ya - e->y0) * inv;
            double xb = (yb == e->y1) ? e->x1 : e->x0 + (yb - e->y0) * inv;
            deposit_segment(acc, w, win.x0, xa, ya, xb, yb, e->dir);
            double mn = xa < xb ? xa : xb, mx = xa < xb ? xb : xa;
            if (mn < lo) {
                lo = mn;
            }
            if (mx > hi) {
                hi = mx;
            }
        }
        if (!(lo <= hi)) {
            continue; /* nothing deposited in this row */
        }
        /* Only columns from the leftmost touched one to one past the
         * rightmost can be non-zero: a closed contour's row sums to 0. */
        int c0 = lo <= win.x0 ? 0 : lo >= win.x1 ? w : (int)floor(lo) - win.x0;
        int c1 = hi >= win.x1 ? w : hi < win.x0 ? 0 : (int)floor(hi) - win.x0 + 2;
        if (c1 > w) {
            c1 = w;
        }
        if (c1 < c0) {
            c1 = c0;
        }
        /* Left of c0 nothing was deposited (c0 > 0 means no edge reaches
         * the window's left side), so the running sum starts at 0. */
        double s = 0.0;
        uint8_t byte = 0;
        int first_nz = -1, last_nz = -1;
        for (int c = c0; c < c1; c++) {
            if (acc[c] != 0.0 || !fast) {
                s += acc[c];
                byte = coverage_byte(rule, s);
            }
            cov[c] = byte;
            if (byte) {
                if (first_nz < 0) {
                    first_nz = c;
                }
                last_nz = c;
            }
        }
        if (first_nz >= 0) {
            span_x0 = win.x0 + first_nz;
            span_x1 = win.x0 + last_nz + 1;
            fn(user, &(sr__span){ y, span_x0, span_x1, cov + first_nz, -1, -1, y + 0.5 });
        }
        int clear_end = c1 + 2 < w + 2 ? c1 + 2 : w + 2;
        memset(acc + c0, 0, (size_t)(clear_end - c0) * sizeof *acc);
        acc[0] = 0.0;
    }
    if (block != stack) {
        sr__free(ctx, block);
    }
    return SR_OK;
}

sr_result sr__scan_area(sr_context *ctx, const sr__edge2 *edges, int count, sr_fill_rule rule,
                        sr__window win, sr__span_fn fn, void *user)
{
    return scan_area(ctx, edges, count, rule, win, fn, user, true);
}

sr_result sr__scan_area_each_row(sr_context *ctx, const sr__edge2 *edges, int count,
                                 sr_fill_rule rule, sr__window win, sr__span_fn fn, void *user)
{
    return scan_area(ctx, edges, count, rule, win, fn, user, false);
}

/* ---- n x n supersampling over the edge-table converter ------------------ */

typedef struct ss_state {
    uint16_t *count;   /* samples hit per pixel of the current pixel row */
    uint8_t *cov;
    int n, wx0, w;
    int row;           /* pixel row being accumulated */
    int lo, hi;        /* its touched pixel columns */
    sr__span_fn fn;
    void *user;
} ss_state;

static void ss_flush(ss_state *s)
{
    if (s->hi < s->lo) {
        return;
    }
    int nn = s->n * s->n;
    for (int c = s->lo; c <= s->hi; c++) {
        s->cov[c] = (uint8_t)((s->count[c] * 255 + nn / 2) / nn);
        s->count[c] = 0;
    }
    sr__span sp = { s->row, s->wx0 + s->lo, s->wx0 + s->hi + 1, s->cov + s->lo, -1, -1,
                    s->row + 0.5 };
    s->fn(s->user, &sp);
    s->lo = s->w;
    s->hi = -1;
}

static void ss_span(void *user, const sr__span *sp)
{
    ss_state *s = user;
    int row = (int)floor_div(sp->y, s->n);
    if (row != s->row) {
        ss_flush(s);
        s->row = row;
    }
    /* Sample columns sp->x0 .. x1-1 belong to pixels floor(sx / n). */
    int c0 = (int)floor_div(sp->x0, s->n) - s->wx0;
    int c1 = (int)floor_div(sp->x1 - 1, s->n) - s->wx0;
    for (int c = c0; c <= c1; c++) {
        int64_t a = (int64_t)(c + s->wx0) * s->n, b = a + s->n;
        if (a < sp->x0) {
            a = sp->x0;
        }
        if (b > sp->x1) {
            b = sp->x1;
        }
        s->count[c] = (uint16_t)(s->count[c] + (b - a));
    }
    if (c0 < s->lo) {
        s->lo = c0;
    }
    if (c1 > s->hi) {
        s->hi = c1;
    }
}

sr_result sr__scan_supersample(sr_context *ctx, const sr__edge2 *edges, int count,
                               sr_fill_rule rule, int n, sr__window win,
                               sr__span_fn fn, void *user)
{
    if (count <= 0 || win.x0 >= win.x1 || win.y0 >= win.y1) {
        return SR_OK;
    }
    int w = win.x1 - win.x0;
    ss_state s = { sr__calloc(ctx, (size_t)w, sizeof(uint16_t)), sr__alloc(ctx, (size_t)w), n,
                   win.x0, w, win.y0, w, -1, fn, user };
    if (!s.count || !s.cov) {
        sr__free(ctx, s.count);
        sr__free(ctx, s.cov);
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "polygon fill: no memory for sample counts");
    }
    /* The winding-cell converter on the n-times finer grid (edges were built with
     * their vertices scaled by n): sample row j of pixel row y is scanline
     * n y + j; spans arrive row by row and are counted per pixel. */
    sr__window sw = { win.x0 * n, win.y0 * n, win.x1 * n, win.y1 * n };
    sr_result r = sr__scan_winding_cells(ctx, edges, count, rule, sw, ss_span, &s);
    ss_flush(&s);
    sr__free(ctx, s.count);
    sr__free(ctx, s.cov);
    return r;
}

/* ---- the public fills -------------------------------------------------- */

sr_result sr__fill_desc_defaults(sr_context *ctx, const char *fn, const sr_fill_desc *in,
                                 sr_fill_desc *out)
{
    *out = in ? *in : (sr_fill_desc){0};
    if (out->rule == SR_FILL_RULE_DEFAULT) {
        out->rule = SR_NONZERO;
    }
    if (out->rule != SR_NONZERO && out->rule != SR_EVENODD) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_fill_desc.rule %d is not a fill rule", fn,
                        (int)out->rule);
    }
    if (out->antialias == SR_AA_DEFAULT) {
        out->antialias = SR_AA_NONE;
    }
    if (out->antialias != SR_AA_NONE && out->antialias != SR_AA_AREA &&
        out->antialias != SR_AA_SUPERSAMPLE) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_fill_desc.antialias %d is not a mode", fn,
                        (int)out->antialias);
    }
    if (out->samples == 0) {
        out->samples = 4;
    }
    if (out->samples < 1 || out->samples > MAX_SUPERSAMPLE) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: sr_fill_desc.samples must be in 1..%d (got %d)",
                        fn, MAX_SUPERSAMPLE, out->samples);
    }
    return SR_OK;
}

/* Polygons of up to this many points keep their edges on the stack. */
#define LOCAL_EDGES 32

sr_result sr__rasterize_polygon(sr_context *ctx, const char *fn, const sr_polygon2 *poly,
                                const sr_fill_desc *desc, sr__window win,
                                sr__span_fn fn_span, void *user)
{
    int scale = desc->antialias == SR_AA_SUPERSAMPLE ? desc->samples : 1;
    sr__edge2 local[LOCAL_EDGES], *edges;
    int count;
    sr_result r = edges_into(ctx, fn, poly, scale, &win, local, LOCAL_EDGES, &edges, &count);
    if (r != SR_OK) {
        return r;
    }
    switch (desc->antialias) {
    case SR_AA_AREA:
        r = sr__scan_area(ctx, edges, count, desc->rule, win, fn_span, user);
        break;
    case SR_AA_SUPERSAMPLE:
        r = sr__scan_supersample(ctx, edges, count, desc->rule, scale, win, fn_span, user);
        break;
    default:
        r = sr__scan_winding_cells(ctx, edges, count, desc->rule, win, fn_span, user);
        break;
    }
    if (edges != local) {
        sr__free(ctx, edges);
    }
    return r;
}

typedef struct paint_target {
    sr__paint paint;
    sr__blend_memo memo;
    sr_framebuffer *fb;
} paint_target;

static void paint_span(void *user, const sr__span *sp)
{
    paint_target *t = user;
    uint32_t *row = t->fb->color + (size_t)sp->y * (size_t)t->fb->width;
    sr__paint_row_memo(&t->paint, &t->memo, row + sp->x0, sp->cov, sp->x1 - sp->x0);
}

sr_result sr_fill_polygon(sr_context *ctx, sr_framebuffer *fb, const sr_polygon2 *poly,
                          sr_rgba color, const sr_fill_desc *desc)
{
    static const char fn[] = "sr_fill_polygon";
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_fill_polygon: ctx is NULL");
    }
    if (!fb) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: fb is NULL", fn);
    }
    sr_fill_desc d;
    sr_result r = sr__fill_desc_defaults(ctx, fn, desc, &d);
    if (r != SR_OK) {
        return r;
    }
    paint_target t = { .fb = fb };
    if (!sr__paint_init(&t.paint, color, d.linear_light)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: color is not finite", fn);
    }
    t.paint.wide = fb->wide_stores;
    sr__blend_memo_init(&t.memo);
    sr_result r2d = sr__fb_begin_2d(ctx, fn, fb);
    if (r2d != SR_OK) {
        return r2d;
    }
    r = sr__rasterize_polygon(ctx, fn, poly, &d, (sr__window){ 0, 0, fb->width, fb->height },
                              paint_span, &t);
    if (r == SR_OK) {
        sr__ok(ctx);
    }
    return r;
}

typedef struct mask_target {
    uint8_t *mask;
    size_t stride;
    int x0, y0;
} mask_target;

static void mask_span(void *user, const sr__span *sp)
{
    mask_target *m = user;
    if (sp->x1 <= sp->x0) {
        return;
    }
    uint8_t *row = m->mask + (size_t)(sp->y - m->y0) * m->stride + (sp->x0 - m->x0);
    size_t n = (size_t)(sp->x1 - sp->x0);
    if (sp->cov) {
        memcpy(row, sp->cov, n);
    } else {
        memset(row, 255, n);
    }
}

sr_result sr_polygon_coverage(sr_context *ctx, const sr_polygon2 *poly,
                              const sr_fill_desc *desc, int x0, int y0, int w, int h,
                              uint8_t *mask, size_t stride)
{
    return sr__polygon_coverage(ctx, "sr_polygon_coverage", poly, desc, x0, y0, w, h, mask,
                                stride);
}

sr_result sr__polygon_coverage(sr_context *ctx, const char *fn, const sr_polygon2 *poly,
                               const sr_fill_desc *desc, int x0, int y0, int w, int h,
                               uint8_t *mask, size_t stride)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "%s: ctx is NULL", fn);
    }
    if (!mask) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: mask is NULL", fn);
    }
    if (w < 1 || h < 1 || w > SR_MAX_FRAMEBUFFER_SIZE || h > SR_MAX_FRAMEBUFFER_SIZE) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: window %d x %d must be 1..%d on each side", fn,
                        w, h, SR_MAX_FRAMEBUFFER_SIZE);
    }
    /* No snapped edge reaches a pixel beyond the budget: a window there
     * would come back empty where the polygon covers it. */
    if (x0 < -SR_MAX_COORD2D || y0 < -SR_MAX_COORD2D || (double)x0 + w > SR_MAX_COORD2D ||
        (double)y0 + h > SR_MAX_COORD2D) {
        return sr__fail(ctx, SR_TOO_LARGE, "%s: window (%d, %d) + %d x %d reaches beyond +-%g",
                        fn, x0, y0, w, h, SR_MAX_COORD2D);
    }
    if (stride < (size_t)w) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: stride %zu < width %d", fn, stride, w);
    }
    if (!sr__rows_fit(mask, (size_t)h, stride, (size_t)w)) {
        return sr__fail(ctx, SR_INVALID_ARG, "%s: %d rows of stride %zu run past the end of memory",
                        fn, h, stride);
    }
    sr_fill_desc d;
    sr_result r = sr__fill_desc_defaults(ctx, fn, desc, &d);
    if (r != SR_OK) {
        return r;
    }
    /* Rows without gaps between them are cleared in one call: a call per
     * row of a small shape's mask costs more than its bytes. */
    if (stride == (size_t)w) {
        memset(mask, 0, (size_t)w * (size_t)h);
    }
    for (int y = 0; y < h && stride != (size_t)w; y++) {
        memset(mask + (size_t)y * stride, 0, (size_t)w);
    }
    mask_target m = { mask, stride, x0, y0 };
    r = sr__rasterize_polygon(ctx, fn, poly, &d, (sr__window){ x0, y0, x0 + w, y0 + h },
                              mask_span, &m);
    if (r == SR_OK) {
        sr__ok(ctx);
    }
    return r;
}
