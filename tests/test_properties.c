/* test_properties.c - rasterization properties at scale, fixed seeds
 * (docs/raster-rules.md §11):
 *
 *  - Watertightness, exact: random planar meshes (regular grids, jittered
 *    grids with random diagonals, fans) under random projective maps with
 *    sub-pixel offsets, snapped on the CPU and drawn through the pipeline
 *    with identity matrices.  An independent int64 reference counts, per
 *    pixel, the triangles covering it; the pipeline's coverage and its
 *    fragment count must match, every pixel is covered at most once, and
 *    every pixel whose centre is inside the snapped mesh boundary (and not
 *    on it) exactly once.  About 1.5 million triangles in a Release build.
 *  - Viewport-filling quads with random w per vertex at every angle from 0
 *    to 90 degrees, also clipped against the guard band: each pixel once.
 *  - Watertightness through the projection: 3D grids under perspective
 *    (the divide, near-plane clipping): covered pixels = fragments (no
 *    pixel twice), and every pixel well inside the projected square covered.
 *  - Closed surfaces: for a sphere seen from outside, every ray enters as
 *    often as it leaves, so the front faces (cull BACK) and the back faces
 *    (cull FRONT) cover the same pixels the same number of times.
 *  - Determinism: random scenes of triangles, lines and points in several
 *    shading and polygon modes with polygon offset give the same color and
 *    depth bytes with 1, 2, 3 and 8 threads and with every rasterizer;
 *    chunks copied in tile order, and those set up with plain stores
 *    after such a copy, give the bytes of one thread.
 *  - Translation invariance: moving the viewport by whole pixels moves the
 *    image exactly (color and depth).
 *
 * Under AddressSanitizer (the CI's second pass, a Debug build) the mesh
 * tests run a quarter of their meshes (PROP_SCALE). */
#include "context.h"
#include "raster_util.h"
#include "scratch.h"
#include "raster/fixed.h"
#include "raster/triangle_simd.h"
#include "target/framebuffer.h"

#if defined(__SANITIZE_ADDRESS__)
#define PROP_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PROP_SANITIZED 1
#endif
#endif
#ifdef PROP_SANITIZED
#define PROP_SCALE 4   /* divide the mesh counts */
#else
#define PROP_SCALE 1
#endif

/* 2 x 2 tiles; a power of two, so window <-> NDC is exact in float. */
enum { FB = 2 * SR_TILE_SIZE };

/* ---- meshes in window space (q8 integers) ------------------------------- */

typedef struct mesh2 {
    int nv, nt;
    int64_t *x, *y;    /* q8 */
    int *idx;          /* 3 per triangle */
} mesh2;

static void mesh2_alloc(mesh2 *m, int nv, int nt)
{
    m->nv = nv;
    m->nt = nt;
    m->x = malloc(sizeof(int64_t) * (size_t)nv);
    m->y = malloc(sizeof(int64_t) * (size_t)nv);
    m->idx = malloc(sizeof(int) * 3 * (size_t)nt);
}

static void mesh2_free(mesh2 *m)
{
    free(m->x);
    free(m->y);
    free(m->idx);
}

/* A projective map of the unit square: rotation, scale, sub-pixel
 * translation, then x' = (a u + b v + c) / (g u + h v + 1) with the
 * denominator kept in [0.6, 1.4]. */
typedef struct proj2 {
    double m[3][3];
} proj2;

static proj2 random_proj2(sr_rng *rng, double size_lo, double size_hi, bool perspective)
{
    double ang = sr_rng_range(rng, 0, 2 * M_PI);
    double sx = sr_rng_range(rng, size_lo, size_hi), sy = sx * sr_rng_range(rng, 0.7, 1.3);
    double cx = sr_rng_range(rng, FB * 0.25, FB * 0.75), cy = sr_rng_range(rng, FB * 0.25, FB * 0.75);
    double g = perspective ? sr_rng_range(rng, -0.4, 0.4) : 0.0;
    double h = perspective ? sr_rng_range(rng, -0.4, 0.4) : 0.0;
    double c = cos(ang), s = sin(ang);
    /* The square centred on the origin, then rotated and scaled. */
    proj2 p = { { { c * sx, -s * sy, cx - 0.5 * (c * sx - s * sy) },
                  { s * sx, c * sy, cy - 0.5 * (s * sx + c * sy) },
                  { g, h, 1.0 - 0.5 * (g + h) } } };
    return p;
}

static void apply_proj2(const proj2 *p, double u, double v, int64_t *xq, int64_t *yq)
{
    double w = p->m[2][0] * u + p->m[2][1] * v + p->m[2][2];
    double x = (p->m[0][0] * u + p->m[0][1] * v + p->m[0][2]) / w;
    double y = (p->m[1][0] * u + p->m[1][1] * v + p->m[1][2]) / w;
    *xq = (int64_t)nearbyint(x * 256.0);
    *yq = (int64_t)nearbyint(y * 256.0);
}

/* Grid of n x m cells over the unit square; jitter moves interior vertices
 * by up to `jitter` of a cell; diagonals random when `random_diag`.  With
 * jitter <= 0.15 both triangles of a cell keep at least a tenth of their
 * area whichever diagonal is chosen, so snapping never flips one. */
static void make_grid(mesh2 *me, sr_rng *rng, const proj2 *p, int n, int m, double jitter,
                      bool random_diag)
{
    mesh2_alloc(me, (n + 1) * (m + 1), 2 * n * m);
    for (int j = 0; j <= m; j++) {
        for (int i = 0; i <= n; i++) {
            double u = (double)i / n, v = (double)j / m;
            if (i > 0 && i < n) {
                u += sr_rng_range(rng, -jitter, jitter) / n;
            }
            if (j > 0 && j < m) {
                v += sr_rng_range(rng, -jitter, jitter) / m;
            }
            apply_proj2(p, u, v, &me->x[j * (n + 1) + i], &me->y[j * (n + 1) + i]);
        }
    }
    int t = 0;
    for (int j = 0; j < m; j++) {
        for (int i = 0; i < n; i++) {
            int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            bool diag = random_diag ? (sr_rng_next(rng) & 1) : ((i + j) & 1);
            int *q = &me->idx[t * 3];
            if (diag) {
                q[0] = a; q[1] = b; q[2] = d; q[3] = a; q[4] = d; q[5] = c;
            } else {
                q[0] = a; q[1] = b; q[2] = c; q[3] = b; q[4] = d; q[5] = c;
            }
            t += 2;
        }
    }
}

/* A fan around the centre of a star-shaped polygon with k rim vertices. */
static void make_fan(mesh2 *me, sr_rng *rng, const proj2 *p, int k)
{
    mesh2_alloc(me, k + 1, k);
    apply_proj2(p, 0.5, 0.5, &me->x[0], &me->y[0]);
    for (int i = 0; i < k; i++) {
        double a = 2 * M_PI * (i + sr_rng_range(rng, -0.3, 0.3)) / k;
        double r = 0.5 * sr_rng_range(rng, 0.4, 1.0);
        apply_proj2(p, 0.5 + r * cos(a), 0.5 + r * sin(a), &me->x[i + 1], &me->y[i + 1]);
        me->idx[i * 3 + 0] = 0;
        me->idx[i * 3 + 1] = 1 + i;
        me->idx[i * 3 + 2] = 1 + (i + 1) % k;
    }
}

static int64_t area2_q8(const mesh2 *m, int t)
{
    const int *q = &m->idx[t * 3];
    return ref_edge(m->x[q[0]], m->y[q[0]], m->x[q[1]], m->y[q[1]], m->x[q[2]], m->y[q[2]]);
}

/* ---- the independent reference ------------------------------------------ */

/* Per-pixel count of covering triangles (top-left rule, docs/raster-rules.md §3.2),
 * each triangle only over its bounding box. */
static void ref_count(const mesh2 *m, int *count)
{
    memset(count, 0, sizeof(int) * FB * FB);
    for (int t = 0; t < m->nt; t++) {
        int64_t x[3], y[3];
        for (int k = 0; k < 3; k++) {
            x[k] = m->x[m->idx[t * 3 + k]];
            y[k] = m->y[m->idx[t * 3 + k]];
        }
        int64_t a2 = ref_edge(x[0], y[0], x[1], y[1], x[2], y[2]);
        if (a2 == 0) {
            continue;
        }
        if (a2 < 0) {
            int64_t tx = x[1], ty = y[1];
            x[1] = x[2]; y[1] = y[2];
            x[2] = tx; y[2] = ty;
        }
        int64_t lo_x = x[0], hi_x = x[0], lo_y = y[0], hi_y = y[0];
        for (int k = 1; k < 3; k++) {
            lo_x = x[k] < lo_x ? x[k] : lo_x;
            hi_x = x[k] > hi_x ? x[k] : hi_x;
            lo_y = y[k] < lo_y ? y[k] : lo_y;
            hi_y = y[k] > hi_y ? y[k] : hi_y;
        }
        int px0 = (int)(lo_x >> 8) - 1, px1 = (int)(hi_x >> 8) + 1;
        int py0 = (int)(lo_y >> 8) - 1, py1 = (int)(hi_y >> 8) + 1;
        px0 = px0 < 0 ? 0 : px0;
        py0 = py0 < 0 ? 0 : py0;
        px1 = px1 > FB - 1 ? FB - 1 : px1;
        py1 = py1 > FB - 1 ? FB - 1 : py1;
        for (int py = py0; py <= py1; py++) {
            for (int px = px0; px <= px1; px++) {
                int64_t sx = px * 256 + 128, sy = py * 256 + 128;
                bool in = true;
                for (int i = 0; i < 3 && in; i++) {
                    int a = i, b = (i + 1) % 3;
                    int64_t dx = x[b] - x[a], dy = y[b] - y[a];
                    bool tl = dy < 0 || (dy == 0 && dx > 0);
                    in = ref_edge(x[a], y[a], x[b], y[b], sx, sy) + (tl ? 1 : 0) > 0;
                }
                count[py * FB + px] += in;
            }
        }
    }
}

static int cmp_edge(const void *a, const void *b)
{
    const int64_t *x = a, *y = b;
    return x[0] < y[0] ? -1 : x[0] > y[0] ? 1 : 0;
}

/* The winding number of the mesh boundary (edges used by one triangle,
 * directed as in it) at every pixel centre, by exact crossings along each
 * row; on_edge marks centres lying exactly on a boundary edge. */
static void boundary_winding(const mesh2 *m, int *wind, uint8_t *on_edge)
{
    int ne = m->nt * 3;
    int64_t (*e)[3] = malloc(sizeof *e * (size_t)ne);
    for (int t = 0; t < m->nt; t++) {
        for (int k = 0; k < 3; k++) {
            int a = m->idx[t * 3 + k], b = m->idx[t * 3 + (k + 1) % 3];
            int lo = a < b ? a : b, hi = a < b ? b : a;
            e[t * 3 + k][0] = (int64_t)lo * m->nv + hi;
            e[t * 3 + k][1] = a;
            e[t * 3 + k][2] = b;
        }
    }
    qsort(e, (size_t)ne, sizeof *e, cmp_edge);
    memset(wind, 0, sizeof(int) * FB * FB);
    memset(on_edge, 0, FB * FB);
    int *diff = calloc(FB + 1, sizeof(int));
    for (int py = 0; py < FB; py++) {
        memset(diff, 0, sizeof(int) * (FB + 1));
        int64_t sy = py * 256 + 128;
        for (int i = 0; i < ne;) {
            int j = i;
            while (j < ne && e[j][0] == e[i][0]) {
                j++;
            }
            if (j - i == 1) {
                int64_t xa = m->x[e[i][1]], ya = m->y[e[i][1]];
                int64_t xb = m->x[e[i][2]], yb = m->y[e[i][2]];
                if (ya == yb) {
                    if (sy == ya) { /* centres on a horizontal edge */
                        int64_t lo = xa < xb ? xa : xb, hi = xa < xb ? xb : xa;
                        for (int px = 0; px < FB; px++) {
                            int64_t sx = px * 256 + 128;
                            if (sx >= lo && sx <= hi) {
                                on_edge[py * FB + px] = 1;
                            }
                        }
                    }
                } else {
                    int dir = yb > ya ? 1 : -1;
                    int64_t y0 = ya < yb ? ya : yb, y1 = ya < yb ? yb : ya;
                    if (sy >= y0 && sy <= y1) {
                        /* crossing x = num / den, den > 0 */
                        int64_t den = yb - ya, num = xa * (yb - ya) + (sy - ya) * (xb - xa);
                        if (den < 0) {
                            den = -den;
                            num = -num;
                        }
                        int64_t r = num - 128 * den; /* centre column c: 256 c den vs r */
                        int64_t c = sr__floor_div(r, 256 * den);
                        if (r == c * 256 * den && c >= 0 && c < FB) {
                            on_edge[py * FB + c] = 1;
                        }
                        if (sy < y1) { /* half-open rows: [y0, y1) */
                            int64_t c0 = c + 1;
                            c0 = c0 < 0 ? 0 : c0;
                            if (c0 < FB) {
                                diff[c0] += dir;
                            }
                        }
                    }
                }
            }
            i = j;
        }
        int acc = 0;
        for (int px = 0; px < FB; px++) {
            acc += diff[px];
            wind[py * FB + px] = acc;
        }
    }
    free(diff);
    free(e);
}

/* ---- drawing a window-space mesh through the pipeline ------------------- */

static float ndc_of_q8(int64_t q) { return (float)((double)q / (256.0 * FB * 0.5) - 1.0); }

/* Draws the mesh (identity matrices, UNLIT white, no depth buffer) and
 * returns the fragment count; rotate picks which vertex goes first. */
static uint64_t draw_mesh2(rt_target *t, const mesh2 *m, sr_rasterizer rast, int rotate)
{
    float *pos = malloc(sizeof(float) * 3 * (size_t)m->nv);
    for (int i = 0; i < m->nv; i++) {
        pos[i * 3 + 0] = ndc_of_q8(m->x[i]);
        pos[i * 3 + 1] = -ndc_of_q8(m->y[i]);
        pos[i * 3 + 2] = 0.0f;
    }
    uint32_t *idx = malloc(sizeof(uint32_t) * 3 * (size_t)m->nt);
    for (int k = 0; k < m->nt; k++) {
        for (int j = 0; j < 3; j++) {
            idx[k * 3 + j] = (uint32_t)m->idx[k * 3 + (j + rotate) % 3];
        }
    }
    rt_clear(t);
    sr_state st = { .rasterizer = rast, .material = { .diffuse = { 1, 1, 1 } } };
    sr_result r = sr_draw(t->ctx, t->fb, &st, &(sr_draw_desc){
        .positions = pos, .vertex_count = (size_t)m->nv, .indices = idx,
        .index_type = SR_INDEX_U32, .index_count = (size_t)m->nt * 3 });
    CHECK_EQ(r, SR_OK);
    free(pos);
    free(idx);
    return sr_last_draw_info(t->ctx).fragments;
}

/* y in NDC points up, window y down: ndc_y = 1 - y / (FB/2); the
 * expression above is -(y/(FB/2) - 1), the same value exactly. */

typedef struct wt_totals {
    long meshes, triangles, pixels_checked;
} wt_totals;

/* All the exact checks for one mesh; false on the first failure. */
static bool check_mesh2(rt_target *t, const mesh2 *m, sr_rasterizer rast, int rotate,
                        int *count, int *wind, uint8_t *on_edge, uint8_t *mask,
                        wt_totals *tot)
{
    int64_t sign = 0;
    for (int k = 0; k < m->nt; k++) {
        int64_t a = area2_q8(m, k);
        if (a != 0) {
            if (sign == 0) {
                sign = a > 0 ? 1 : -1;
            }
            /* The generators keep cells large enough that snapping never
             * flips a triangle; a flip would make overlap legitimate. */
            if ((a > 0 ? 1 : -1) != sign) {
                sr_test_fail(__FILE__, __LINE__, "generator made a flipped triangle");
                return false;
            }
        }
    }
    ref_count(m, count);
    boundary_winding(m, wind, on_edge);
    uint64_t frags = draw_mesh2(t, m, rast, rotate);
    rt_mask(t, mask);
    uint64_t ref_total = 0;
    for (int i = 0; i < FB * FB; i++) {
        ref_total += (uint64_t)count[i];
        if (count[i] > 1) {
            sr_test_fail(__FILE__, __LINE__, "reference covers pixel (%d, %d) %d times",
                         i % FB, i / FB, count[i]);
            return false;
        }
        if (mask[i] != (count[i] > 0)) {
            sr_test_fail(__FILE__, __LINE__, "pixel (%d, %d): pipeline %d, reference %d (rast %d)",
                         i % FB, i / FB, mask[i], count[i], (int)rast);
            return false;
        }
        if (!on_edge[i] && count[i] != abs(wind[i])) {
            sr_test_fail(__FILE__, __LINE__, "pixel (%d, %d): covered %d times, winding %d",
                         i % FB, i / FB, count[i], wind[i]);
            return false;
        }
    }
    if (frags != ref_total) {
        sr_test_fail(__FILE__, __LINE__, "%llu fragments, reference %llu (a pixel drawn twice)",
                     (unsigned long long)frags, (unsigned long long)ref_total);
        return false;
    }
    tot->meshes++;
    tot->triangles += m->nt;
    tot->pixels_checked += FB * FB;
    return true;
}

SR_TEST(random_meshes_cover_every_inside_pixel_exactly_once)
{
    rt_target t1 = rt_make(FB, FB, 1), t2 = rt_make(FB, FB, 2);
    int *count = malloc(sizeof(int) * FB * FB), *wind = malloc(sizeof(int) * FB * FB);
    uint8_t *on_edge = malloc(FB * FB), *mask = malloc(FB * FB);
    static const sr_rasterizer rasts[3] = { SR_RASTER_HALFSPACE, SR_RASTER_SCANLINE,
                                            SR_RASTER_BARYCENTRIC };
    sr_rng rng = { 0x77a7e4719e5ULL };
    wt_totals tot = { 0 };
    const int rounds = 240 / PROP_SCALE;
    for (int r = 0; r < rounds && !sr_test_failed_now(); r++) {
        mesh2 m;
        int kind = r % 4;
        bool persp = (r / 4) % 2 == 1;
        if (kind == 0) {        /* regular grid, cells >= ~0.6 px */
            proj2 p = random_proj2(&rng, 60, 300, persp);
            int n = sr_rng_int(&rng, 16, 64), k = sr_rng_int(&rng, 16, 64);
            make_grid(&m, &rng, &p, n, k, 0.0, false);
        } else if (kind == 1) { /* random triangulation: jittered, random diagonals */
            proj2 p = random_proj2(&rng, 60, 300, persp);
            int n = sr_rng_int(&rng, 16, 64), k = sr_rng_int(&rng, 16, 64);
            make_grid(&m, &rng, &p, n, k, 0.15, true);
        } else if (kind == 2) { /* a fine grid: thousands of tiny triangles */
            proj2 p = random_proj2(&rng, 120, 220, persp);
            make_grid(&m, &rng, &p, 96, 96, 0.15, true);
        } else {                /* a fan of long thin triangles */
            proj2 p = random_proj2(&rng, 60, 400, persp);
            make_fan(&m, &rng, &p, sr_rng_int(&rng, 3, 400));
        }
        rt_target *t = (r & 1) ? &t2 : &t1;
        check_mesh2(t, &m, rasts[(r / 2) % 3], r % 3, count, wind, on_edge, mask, &tot);
        mesh2_free(&m);
    }
    /* The same meshes must add up to the promised scale in Release. */
    printf("  watertight: %ld meshes, %ld triangles, %ld pixels checked\n", tot.meshes,
           tot.triangles, tot.pixels_checked);
    if (PROP_SCALE == 1) {
        CHECK(tot.triangles >= 1000000);
    }
    free(count);
    free(wind);
    free(on_edge);
    free(mask);
    rt_free(&t1);
    rt_free(&t2);
}

/* Vertex order: rotating each triangle's vertices changes no pixel. */
SR_TEST(rotating_vertex_order_changes_no_pixel)
{
    rt_target t = rt_make(FB, FB, 2);
    uint8_t *m0 = malloc(FB * FB), *m1 = malloc(FB * FB);
    sr_rng rng = { 0x0dde12 };
    for (int r = 0; r < 24 / PROP_SCALE + 2; r++) {
        proj2 p = random_proj2(&rng, 40, 300, true);
        mesh2 m;
        make_grid(&m, &rng, &p, 24, 24, 0.15, true);
        for (int rot = 0; rot < 3; rot++) {
            draw_mesh2(&t, &m, SR_RASTER_HALFSPACE, rot);
            rt_mask(&t, rot ? m1 : m0);
            if (rot) {
                CHECK(memcmp(m0, m1, FB * FB) == 0);
            }
        }
        mesh2_free(&m);
    }
    free(m0);
    free(m1);
    rt_free(&t);
}

/* The CTS `clipped_full` case: a quad much larger than the viewport, as two
 * triangles with random w in [0.1, 4] per vertex (the projected quad is the
 * same), rotated through 0..90 degrees with sub-pixel offsets: every pixel
 * exactly once, also when the corners lie beyond the guard band and the
 * triangles are clipped against it. */
SR_TEST(viewport_filling_quads_at_every_angle_cover_each_pixel_once)
{
    rt_target t = rt_make(FB, FB, 2);
    uint8_t *mask = malloc(FB * FB);
    sr_rng rng = { 0xc1199ed };
    for (int step = 0; step <= 90 && !sr_test_failed_now(); step++) {
        for (int big = 0; big < 2; big++) {
            /* The square's inscribed circle (radius rad / sqrt 2) holds the viewport. */
            double a = step * M_PI / 180.0, rad = big ? 600.0 : 3.0; /* NDC; 600 -> 77000 px */
            double cx = sr_rng_range(&rng, -0.01, 0.01), cy = sr_rng_range(&rng, -0.01, 0.01);
            float pos[16];
            for (int k = 0; k < 4; k++) {
                double w = sr_rng_range(&rng, 0.1, 4.0);
                pos[k * 4 + 0] = (float)((cx + rad * cos(a + k * M_PI / 2)) * w);
                pos[k * 4 + 1] = (float)((cy + rad * sin(a + k * M_PI / 2)) * w);
                pos[k * 4 + 2] = 0.0f;
                pos[k * 4 + 3] = (float)w;
            }
            static const uint8_t idx[6] = { 0, 1, 2, 0, 2, 3 };
            rt_clear(&t);
            sr_state st = { .rasterizer = (sr_rasterizer)(1 + step % 3),
                            .material = { .diffuse = { 1, 1, 1 } } };
            REQUIRE(sr_draw(t.ctx, t.fb, &st, &(sr_draw_desc){
                .positions = pos, .position_size = 4, .vertex_count = 4, .indices = idx,
                .index_type = SR_INDEX_U8, .index_count = 6 }) == SR_OK);
            rt_mask(&t, mask);
            int covered = 0;
            for (int i = 0; i < FB * FB; i++) {
                covered += mask[i];
            }
            if (covered != FB * FB || sr_last_draw_info(t.ctx).fragments != (uint64_t)FB * FB) {
                sr_test_fail(__FILE__, __LINE__, "%d degrees%s: %d pixels covered, %llu fragments",
                             step, big ? " (clipped)" : "", covered,
                             (unsigned long long)sr_last_draw_info(t.ctx).fragments);
            }
            if (big) {
                CHECK(sr_last_draw_info(t.ctx).triangles_clipped > 0);
            }
        }
    }
    free(mask);
    rt_free(&t);
}

/* ---- through the projection: 3D meshes ---------------------------------- */

/* A unit square grid in the plane z = 0 (object space), n x n cells. */
static void grid3(int n, float **pos, uint32_t **idx, int *nv, int *nt)
{
    *nv = (n + 1) * (n + 1);
    *nt = 2 * n * n;
    *pos = malloc(sizeof(float) * 3 * (size_t)*nv);
    *idx = malloc(sizeof(uint32_t) * 3 * (size_t)*nt);
    for (int j = 0; j <= n; j++) {
        for (int i = 0; i <= n; i++) {
            float *p = &(*pos)[(j * (n + 1) + i) * 3];
            p[0] = (float)i / n - 0.5f;
            p[1] = (float)j / n - 0.5f;
            p[2] = 0.0f;
        }
    }
    int t = 0;
    for (int j = 0; j < n; j++) {
        for (int i = 0; i < n; i++) {
            uint32_t a = (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)n + 1, d = c + 1;
            uint32_t *q = &(*idx)[t * 3];
            q[0] = a; q[1] = b; q[2] = d; q[3] = a; q[4] = d; q[5] = c;
            t += 2;
        }
    }
}

static sr_mat4 random_rotation(sr_rng *rng, double max_tilt)
{
    sr_mat4 rz = sr_mat4_rotate((float)sr_rng_range(rng, 0, 2 * M_PI), sr_vec3_make(0, 0, 1));
    sr_vec3 axis = sr_vec3_make((float)sr_rng_range(rng, -1, 1), (float)sr_rng_range(rng, -1, 1), 0);
    if (sr_vec3_length(axis) == 0.0f) {
        axis = sr_vec3_make(1, 0, 0);
    }
    sr_mat4 tilt = sr_mat4_rotate((float)sr_rng_range(rng, -max_tilt, max_tilt), axis);
    return sr_mat4_mul(&tilt, &rz);
}

/* Window position of object point p under mvp, in double (px, y down). */
static void window_of(const sr_mat4 *mvp, const float p[3], double *x, double *y, double *w)
{
    const float *m = mvp->m;
    double c[4];
    for (int r = 0; r < 4; r++) {
        c[r] = (double)m[r] * p[0] + (double)m[4 + r] * p[1] + (double)m[8 + r] * p[2] + m[12 + r];
    }
    *w = c[3];
    *x = (c[0] / c[3] + 1.0) * FB * 0.5;
    *y = (1.0 - c[1] / c[3]) * FB * 0.5;
}

/* Signed distance from (x, y) to the inside of convex polygon q (n
 * vertices, either orientation): > 0 inside. */
static double inside_distance(const double (*q)[2], int n, double x, double y)
{
    double area = 0;
    for (int i = 0; i < n; i++) {
        int j = (i + 1) % n;
        area += q[i][0] * q[j][1] - q[j][0] * q[i][1];
    }
    double s = area > 0 ? 1.0 : -1.0, best = 1e300;
    for (int i = 0; i < n; i++) {
        int j = (i + 1) % n;
        double ex = q[j][0] - q[i][0], ey = q[j][1] - q[i][1];
        double len = sqrt(ex * ex + ey * ey);
        if (len == 0) {
            continue;
        }
        double d = s * (ex * (y - q[i][1]) - ey * (x - q[i][0])) / len;
        best = d < best ? d : best;
    }
    return best;
}

static uint64_t count_mask(const uint8_t *m, int n)
{
    uint64_t c = 0;
    for (int i = 0; i < n; i++) {
        c += m[i];
    }
    return c;
}

SR_TEST(projected_grids_are_watertight)
{
    rt_target t = rt_make(FB, FB, 2);
    uint8_t *mask = malloc(FB * FB);
    sr_rng rng = { 0xb105f00d };
    sr_mat4 proj = sr_perspective(1.0f, 1.0f, 0.1f, 100.0f, false);
    long tris = 0, clipped = 0;
    for (int r = 0; r < 160 / PROP_SCALE && !sr_test_failed_now(); r++) {
        int n = sr_rng_int(&rng, 8, 80);
        float *pos;
        uint32_t *idx;
        int nv, nt;
        grid3(n, &pos, &idx, &nv, &nt);
        /* Every fourth grid is big and tilted through the near plane (and
         * behind the eye).  Its far end stays within ~5 units, where cells
         * are still pixels wide: nearer the horizon they would become
         * slivers that snapping may legitimately fold over a neighbour. */
        bool crossing = r % 4 == 3;
        float size = crossing ? 8.0f : (float)sr_rng_range(&rng, 0.3, 3.0);
        sr_mat4 s = sr_mat4_scale(size, size, 1);
        sr_mat4 rot = random_rotation(&rng, crossing ? 1.2 : 1.0);
        sr_mat4 tr = sr_mat4_translate((float)sr_rng_range(&rng, -0.3, 0.3),
                                       (float)sr_rng_range(&rng, -0.3, 0.3),
                                       crossing ? -0.5f : (float)sr_rng_range(&rng, -4.0, -1.5));
        sr_mat4 rs = sr_mat4_mul(&rot, &s);
        sr_mat4 model = sr_mat4_mul(&tr, &rs);
        rt_clear(&t);
        sr_state st = { .rasterizer = (sr_rasterizer)(1 + r % 3),
                        .material = { .diffuse = { 1, 1, 1 } } };
        REQUIRE(sr_draw(t.ctx, t.fb, &st, &(sr_draw_desc){
            .positions = pos, .vertex_count = (size_t)nv, .indices = idx,
            .index_type = SR_INDEX_U32, .index_count = (size_t)nt * 3,
            .model = &model, .projection = &proj }) == SR_OK);
        uint64_t frags = sr_last_draw_info(t.ctx).fragments;
        clipped += crossing && sr_last_draw_info(t.ctx).triangles_clipped > 0;
        rt_mask(&t, mask);
        /* No pixel twice: every fragment landed on a pixel of its own. */
        if (frags != count_mask(mask, FB * FB)) {
            sr_test_fail(__FILE__, __LINE__, "round %d (%s, n %d): %llu fragments on %llu pixels",
                         r, crossing ? "crossing" : "in front", n, (unsigned long long)frags,
                         (unsigned long long)count_mask(mask, FB * FB));
        }
        if (!crossing) {
            /* No holes: pixels whose centre is 1 px inside the projected
             * square are covered, 1 px outside are not. */
            sr_mat4 mvp = sr_mat4_mul(&proj, &model);
            double q[4][2], w;
            const float corners[4][3] = { { -0.5f, -0.5f, 0 }, { 0.5f, -0.5f, 0 },
                                          { 0.5f, 0.5f, 0 }, { -0.5f, 0.5f, 0 } };
            bool in_front = true;
            for (int k = 0; k < 4; k++) {
                window_of(&mvp, corners[k], &q[k][0], &q[k][1], &w);
                in_front &= w > 0.2;
            }
            for (int i = 0; in_front && i < FB * FB; i++) {
                double d = inside_distance((const double (*)[2])q, 4, i % FB + 0.5, i / FB + 0.5);
                if ((d > 1.0 && !mask[i]) || (d < -1.0 && mask[i])) {
                    sr_test_fail(__FILE__, __LINE__, "round %d pixel (%d, %d): %s at %.2f px",
                                 r, i % FB, i / FB, mask[i] ? "covered" : "hole", d);
                    break;
                }
            }
        }
        tris += nt;
        free(pos);
        free(idx);
    }
    printf("  projected grids: %ld triangles, %ld grids through the near plane\n", tris, clipped);
    CHECK(clipped >= 160 / PROP_SCALE / 8); /* most crossing grids really cross */
    free(mask);
    rt_free(&t);
}

/* A UV sphere with outward counter-clockwise faces (poles as fans). */
static void sphere(int stacks, int slices, float **pos, uint32_t **idx, int *nv, int *nt)
{
    *nv = 2 + (stacks - 1) * slices;
    *nt = 2 * slices * (stacks - 1);
    *pos = malloc(sizeof(float) * 3 * (size_t)*nv);
    *idx = malloc(sizeof(uint32_t) * 3 * (size_t)*nt);
    float *p = *pos;
    p[0] = 0; p[1] = 1; p[2] = 0;         /* north pole */
    p[3] = 0; p[4] = -1; p[5] = 0;        /* south pole */
    for (int i = 1; i < stacks; i++) {
        double th = M_PI * i / stacks;
        for (int j = 0; j < slices; j++) {
            double ph = 2 * M_PI * j / slices;
            float *v = &p[(2 + (i - 1) * slices + j) * 3];
            v[0] = (float)(sin(th) * cos(ph));
            v[1] = (float)cos(th);
            v[2] = (float)(-sin(th) * sin(ph));
        }
    }
    uint32_t *q = *idx;
    int t = 0;
#define RING(i, j) (uint32_t)(2 + ((i) - 1) * slices + ((j) % slices))
    for (int j = 0; j < slices; j++) {
        q[t * 3 + 0] = 0; q[t * 3 + 1] = RING(1, j); q[t * 3 + 2] = RING(1, j + 1); t++;
        q[t * 3 + 0] = 1; q[t * 3 + 1] = RING(stacks - 1, j + 1); q[t * 3 + 2] = RING(stacks - 1, j); t++;
    }
    for (int i = 1; i < stacks - 1; i++) {
        for (int j = 0; j < slices; j++) {
            uint32_t a = RING(i, j), b = RING(i, j + 1), c = RING(i + 1, j), d = RING(i + 1, j + 1);
            q[t * 3 + 0] = a; q[t * 3 + 1] = c; q[t * 3 + 2] = d; t++;
            q[t * 3 + 0] = a; q[t * 3 + 1] = d; q[t * 3 + 2] = b; t++;
        }
    }
#undef RING
    *nt = t;
}

static int cmp_pt(const void *a, const void *b)
{
    const double *p = a, *q = b;
    return p[0] < q[0] ? -1 : p[0] > q[0] ? 1 : p[1] < q[1] ? -1 : p[1] > q[1] ? 1 : 0;
}

static double cross3(const double *o, const double *a, const double *b)
{
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/* Convex hull (monotone chain) of n points into hull; returns its size. */
static int convex_hull(double (*pts)[2], int n, double (*hull)[2])
{
    qsort(pts, (size_t)n, sizeof *pts, cmp_pt);
    int k = 0;
    for (int i = 0; i < n; i++) {
        while (k >= 2 && cross3(hull[k - 2], hull[k - 1], pts[i]) <= 0) {
            k--;
        }
        hull[k][0] = pts[i][0];
        hull[k][1] = pts[i][1];
        k++;
    }
    for (int i = n - 2, lo = k + 1; i >= 0; i--) {
        while (k >= lo && cross3(hull[k - 2], hull[k - 1], pts[i]) <= 0) {
            k--;
        }
        hull[k][0] = pts[i][0];
        hull[k][1] = pts[i][1];
        k++;
    }
    return k - 1;
}

SR_TEST(closed_spheres_cover_each_pixel_as_often_from_the_front_as_from_the_back)
{
    rt_target t = rt_make(FB, FB, 2);
    uint8_t *front = malloc(FB * FB), *back = malloc(FB * FB);
    sr_rng rng = { 0x5fe4e };
    sr_mat4 proj = sr_perspective(1.0f, 1.0f, 0.1f, 100.0f, false);
    long tris = 0;
    for (int r = 0; r < 60 / PROP_SCALE && !sr_test_failed_now(); r++) {
        float *pos;
        uint32_t *idx;
        int nv, nt;
        sphere(sr_rng_int(&rng, 3, 120), sr_rng_int(&rng, 3, 160), &pos, &idx, &nv, &nt);
        float rad = (float)sr_rng_range(&rng, 0.05, 1.2);
        sr_mat4 s = sr_mat4_scale(rad, rad * (float)sr_rng_range(&rng, 0.6, 1.4), rad);
        sr_mat4 rot = random_rotation(&rng, M_PI);
        sr_mat4 tr = sr_mat4_translate((float)sr_rng_range(&rng, -0.5, 0.5),
                                       (float)sr_rng_range(&rng, -0.5, 0.5),
                                       (float)sr_rng_range(&rng, -5.0, -2.0));
        sr_mat4 rs = sr_mat4_mul(&rot, &s);
        sr_mat4 model = sr_mat4_mul(&tr, &rs);
        uint64_t frags[2];
        for (int side = 0; side < 2; side++) {
            rt_clear(&t);
            sr_state st = { .cull = side ? SR_CULL_FRONT : SR_CULL_BACK,
                            .rasterizer = (sr_rasterizer)(1 + r % 3),
                            .material = { .diffuse = { 1, 1, 1 } } };
            REQUIRE(sr_draw(t.ctx, t.fb, &st, &(sr_draw_desc){
                .positions = pos, .vertex_count = (size_t)nv, .indices = idx,
                .index_type = SR_INDEX_U32, .index_count = (size_t)nt * 3,
                .model = &model, .projection = &proj }) == SR_OK);
            frags[side] = sr_last_draw_info(t.ctx).fragments;
            rt_mask(&t, side ? back : front);
        }
        CHECK_EQ(frags[0], frags[1]);
        CHECK(memcmp(front, back, FB * FB) == 0);
        /* No holes: every pixel 1 px inside the hull of the projected
         * vertices is covered by the front faces. */
        sr_mat4 mvp = sr_mat4_mul(&proj, &model);
        double (*pts)[2] = malloc(sizeof *pts * (size_t)nv);
        double (*hull)[2] = malloc(sizeof *hull * (size_t)(nv + 1));
        for (int i = 0; i < nv; i++) {
            double w;
            window_of(&mvp, &pos[i * 3], &pts[i][0], &pts[i][1], &w);
        }
        int nh = convex_hull(pts, nv, hull);
        for (int i = 0; i < FB * FB; i++) {
            double d = inside_distance((const double (*)[2])hull, nh, i % FB + 0.5, i / FB + 0.5);
            if ((d > 1.0 && !front[i]) || (d < -1.0 && front[i])) {
                sr_test_fail(__FILE__, __LINE__, "sphere %d pixel (%d, %d): %s at %.2f px", r,
                             i % FB, i / FB, front[i] ? "covered" : "hole", d);
                break;
            }
        }
        tris += nt;
        free(pts);
        free(hull);
        free(pos);
        free(idx);
    }
    printf("  spheres: %ld triangles, drawn twice\n", tris);
    free(front);
    free(back);
    rt_free(&t);
}

/* ---- random scenes: determinism and translation invariance -------------- */

typedef struct scene {
    int nv;
    float pos[3 * 96], nrm[3 * 96], col[4 * 96];
    sr_primitive prim;
    sr_state st;
    sr_mat4 view, proj;
} scene;

/* A batch of random primitives in a random state.  All vertices stay well
 * in front of the camera and inside the viewport (for the translation
 * test, which must not clip differently). */
static void random_scene(sr_rng *rng, int k, scene *s)
{
    memset(s, 0, sizeof *s);
    static const sr_primitive prims[] = {
        SR_PRIM_TRIANGLES, SR_PRIM_TRIANGLE_STRIP, SR_PRIM_TRIANGLE_FAN, SR_PRIM_LINES,
        SR_PRIM_LINE_STRIP, SR_PRIM_LINE_LOOP, SR_PRIM_POINTS, SR_PRIM_TRIANGLES,
    };
    s->prim = prims[k % 8];
    s->nv = 3 * sr_rng_int(rng, 4, 32);
    for (int i = 0; i < s->nv; i++) {
        s->pos[i * 3 + 0] = (float)sr_rng_range(rng, -0.9, 0.9);
        s->pos[i * 3 + 1] = (float)sr_rng_range(rng, -0.9, 0.9);
        s->pos[i * 3 + 2] = (float)sr_rng_range(rng, -0.9, 0.9);
        sr_vec3 n = sr_vec3_normalize(sr_vec3_make((float)sr_rng_range(rng, -1, 1),
                                                   (float)sr_rng_range(rng, -1, 1), 1.0f));
        s->nrm[i * 3 + 0] = n.x;
        s->nrm[i * 3 + 1] = n.y;
        s->nrm[i * 3 + 2] = n.z;
        for (int c = 0; c < 4; c++) {
            s->col[i * 4 + c] = (float)sr_rng_unit(rng);
        }
    }
    sr_state *st = &s->st;
    static const sr_shading shadings[] = { SR_SHADING_UNLIT, SR_SHADING_FLAT, SR_SHADING_GOURAUD,
                                           SR_SHADING_PHONG, SR_SHADING_NORMALS, SR_SHADING_DEPTH };
    st->shading = shadings[sr_rng_int(rng, 0, 5)];
    st->interpolation = sr_rng_int(rng, 0, 3) == 0 ? SR_INTERP_AFFINE : SR_INTERP_PERSPECTIVE;
    st->provoking = sr_rng_int(rng, 0, 1) ? SR_PROVOKING_LAST : SR_PROVOKING_FIRST;
    st->cull = (sr_cull_mode)sr_rng_int(rng, 1, 3);
    st->polygon_mode_front = (sr_polygon_mode)sr_rng_int(rng, 1, 3);
    st->polygon_mode_back = (sr_polygon_mode)sr_rng_int(rng, 1, 3);
    st->line_width = (float)sr_rng_int(rng, 1, 5);
    st->point_size = (float)sr_rng_int(rng, 1, 24) * 0.5f;
    static const sr_depth_func funcs[] = { SR_LESS, SR_LEQUAL, SR_GREATER, SR_GEQUAL,
                                           SR_NOTEQUAL, SR_ALWAYS, SR_LESS, SR_LEQUAL };
    st->depth_func = funcs[sr_rng_int(rng, 0, 7)];
    st->offset = (sr_polygon_offset){ .factor = (float)sr_rng_range(rng, -2, 2),
                                      .units = (float)sr_rng_int(rng, -4, 4),
                                      .fill = sr_rng_int(rng, 0, 1), .line = sr_rng_int(rng, 0, 1),
                                      .point = sr_rng_int(rng, 0, 1) };
    st->material.specular = (sr_vec3){ 0.5f, 0.5f, 0.5f };
    st->material.shininess = 16;
    st->ambient = (sr_vec3){ 0.2f, 0.2f, 0.2f };
    st->lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL, .vector = { 0.2f, -0.5f, -1 } };
    st->lights[1] = (sr_light){ .type = SR_LIGHT_POINT, .vector = { 1, 1, 1 },
                                .color = { 1, 0.5f, 0.2f } };
    st->two_sided = sr_rng_int(rng, 0, 1);
    s->view = sr_mat4_translate(0, 0, -3);
    s->proj = sr_rng_int(rng, 0, 1) ? sr_perspective(0.9f, 1.0f, 1.0f, 10.0f, false)
                                    : sr_ortho(-1.5f, 1.5f, -1.5f, 1.5f, 1.0f, 10.0f, false);
}

static sr_result draw_scene(sr_context *ctx, sr_framebuffer *fb, const scene *s,
                            sr_viewport vp, sr_rasterizer rast)
{
    sr_state st = s->st;
    st.viewport = vp;
    st.rasterizer = rast;
    bool greater = st.depth_func == SR_GREATER || st.depth_func == SR_GEQUAL;
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.1f, 0.2f, 0.3f, 1 },
                                        .depth_action = SR_ACTION_CLEAR,
                                        .depth = greater ? 0.0f : 1.0f });
    return sr_draw(ctx, fb, &st, &(sr_draw_desc){
        .primitive = s->prim, .positions = s->pos, .vertex_count = (size_t)s->nv,
        .normals = s->nrm, .colors = s->col, .view = &s->view, .projection = &s->proj });
}

/* The stored depth values, widened to 32 bits (resolving any pending
 * clear first), into out[width * height]. */
static void raw_depth(sr_framebuffer *fb, uint32_t *out)
{
    sr__fb_resolve(fb, SR_TILE_PENDING_DEPTH);
    for (size_t i = 0; i < (size_t)fb->width * (size_t)fb->height; i++) {
        out[i] = sr__depth_at(fb, i);
    }
}

SR_TEST(random_scenes_give_identical_bytes_for_1_2_3_8_threads_and_every_rasterizer)
{
    /* 3 x 2 tiles, the last ones partial. */
    enum { W = 2 * SR_TILE_SIZE + 22, H = SR_TILE_SIZE + 46 };
    static const int threads[] = { 1, 2, 3, 8 };
    static const sr_depth_format formats[] = { SR_DEPTH_D16, SR_DEPTH_D24, SR_DEPTH_D32,
                                               SR_DEPTH_D32F };
    sr_context *ctx[4];
    for (int i = 0; i < 4; i++) {
        REQUIRE(sr_make_context(&(sr_context_desc){ .threads = threads[i] }, &ctx[i]) == SR_OK);
    }
    uint8_t *c0 = malloc(W * H * 4);
    uint32_t *d0 = malloc(sizeof(uint32_t) * W * H), *d = malloc(sizeof(uint32_t) * W * H);
    sr_rng rng = { 0xde7e3 };
    static scene s;
    int compared = 0;
    for (int k = 0; k < 64 && !sr_test_failed_now(); k++) {
        random_scene(&rng, k, &s);
        sr_depth_format df = formats[k % 4];
        for (int v = 0; v < 6; v++) {
            int ti = v < 4 ? v : 1;                        /* threads 1, 2, 3, 8 */
            sr_rasterizer rast = v < 4 ? SR_RASTER_HALFSPACE
                                       : (v == 4 ? SR_RASTER_SCANLINE : SR_RASTER_BARYCENTRIC);
            sr_framebuffer *fb;
            REQUIRE(sr_make_framebuffer(ctx[ti], &(sr_framebuffer_desc){
                .width = W, .height = H, .depth_format = df }, &fb) == SR_OK);
            CHECK_EQ(draw_scene(ctx[ti], fb, &s, (sr_viewport){ 0 }, rast), SR_OK);
            raw_depth(fb, v == 0 ? d0 : d);
            if (v == 0) {
                memcpy(c0, sr_framebuffer_pixels(fb), W * H * 4);
            } else {
                if (memcmp(c0, sr_framebuffer_pixels(fb), W * H * 4) != 0 ||
                    memcmp(d0, d, sizeof(uint32_t) * W * H) != 0) {
                    sr_test_fail(__FILE__, __LINE__, "scene %d (prim %d, shading %d): %d threads, "
                                 "rasterizer %d differ from 1 thread", k, (int)s.prim,
                                 (int)s.st.shading, threads[ti], (int)rast);
                }
                compared++;
            }
            sr_destroy_framebuffer(ctx[ti], fb);
        }
    }
    CHECK(compared > 300);
    free(c0);
    free(d0);
    free(d);
    for (int i = 0; i < 4; i++) {
        sr_destroy_context(ctx[i]);
    }
}

/* A vertex of the kernel tests' random triangles (centre cx, cy, radius
 * r, in front of the camera at a random depth) and its normal. */
static void kernel_test_vertex(sr_rng *rng, double cx, double cy, double r, float p[3],
                               float nrm[3])
{
    p[0] = (float)(cx + sr_rng_range(rng, -r, r));
    p[1] = (float)(cy + sr_rng_range(rng, -r, r));
    p[2] = (float)sr_rng_range(rng, -1.5, 1.5);
    sr_vec3 n = sr_vec3_normalize(sr_vec3_make((float)sr_rng_range(rng, -1, 1),
                                               (float)sr_rng_range(rng, -1, 1), 1));
    memcpy(nrm, &n, sizeof(float) * 3);
}

/* The kernel tests' two images and depth words (one drawn each way) and
 * their camera, 3 units back with a perspective projection. */
typedef struct kernel_test_io {
    sr_context *ctx;                  /* two threads */
    uint8_t *c[2];
    uint32_t *d[2];
    sr_mat4 view, proj;
} kernel_test_io;

static kernel_test_io kernel_test_io_make(int w, int h)
{
    size_t n = (size_t)w * (size_t)h;
    kernel_test_io io = { NULL, { malloc(n * 4), malloc(n * 4) },
                          { malloc(sizeof(uint32_t) * n), malloc(sizeof(uint32_t) * n) },
                          sr_mat4_translate(0, 0, -3),
                          sr_perspective(0.9f, (float)w / (float)h, 1.0f, 10.0f, false) };
    if (sr_make_context(&(sr_context_desc){ .threads = 2 }, &io.ctx) != SR_OK || !io.c[0] ||
        !io.c[1] || !io.d[0] || !io.d[1]) {
        fprintf(stderr, "out of memory for a %d x %d kernel test\n", w, h);
        exit(1);
    }
    return io;
}

static void kernel_test_io_free(kernel_test_io *io)
{
    sr_destroy_context(io->ctx);
    for (int i = 0; i < 2; i++) {
        free(io->c[i]);
        free(io->d[i]);
    }
}

/* Draw into a fresh framebuffer cleared to one color and the far depth,
 * with ctx's vector level set as SR_SIMD=`simd` would set it (NULL: the
 * widest kernel); its color and raw depth words are copied out. */
static void kernel_test_draw(sr_context *ctx, int w, int h, sr_depth_format df, const char *simd,
                             const sr_state *st, const sr_draw_desc *desc, uint8_t *color,
                             uint32_t *depth)
{
    sr_simd_level level = !simd                     ? SR_SIMD_AVX512
                          : strcmp(simd, "off") == 0  ? SR_SIMD_OFF
                          : strcmp(simd, "base") == 0 ? SR_SIMD_BASE
                          : strcmp(simd, "avx2") == 0 ? SR_SIMD_AVX2
                                                      : SR_SIMD_AVX512;
    sr_simd_level cpu = sr__simd_cpu_level(), kept = ctx->simd;
    ctx->simd = level < cpu ? level : cpu;
    sr_framebuffer *fb;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = w, .height = h,
                                                            .depth_format = df }, &fb) == SR_OK);
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.1f, 0.2f, 0.3f, 1 }, .depth = 1 });
    CHECK_EQ(sr_draw(ctx, fb, st, desc), SR_OK);
    raw_depth(fb, depth);
    memcpy(color, sr_framebuffer_pixels(fb), (size_t)w * (size_t)h * 4);
    sr_destroy_framebuffer(ctx, fb);
    ctx->simd = kept;
}

/* The vector kernels (the AVX-512 build's sixteen-lane pairs of block
 * rows, the AVX2 build's eight-lane rows, the four-lane groups of both and
 * of the SSE2 build) against the scalar loop they restate, chosen by
 * SR_SIMD (the default is the widest the CPU runs): large and small triangles under
 * perspective, colors outside [0, 1] (the saturating packs), random depths
 * against D16 and D24 with depth LESS and off, in every shading model the
 * kernels cover.  The image is 203 x 141: rows and blocks end at the
 * framebuffer's edge in the middle of a group. */
SR_TEST(vector_kernels_give_the_scalar_loops_bytes)
{
    enum { W = 203, H = 141, N = 48 };
    static const char *const simd[] = { NULL, "avx2", "base", "off" };
    static const sr_shading shadings[] = { SR_SHADING_UNLIT, SR_SHADING_GOURAUD,
                                           SR_SHADING_FLAT, SR_SHADING_PHONG };
    float pos[N * 9], nrm[N * 9], col[N * 12];
    kernel_test_io io = kernel_test_io_make(W, H);
    sr_rng rng = { 0x51ad };
    int compared = 0;
    for (int k = 0; k < 32 && !sr_test_failed_now(); k++) {
        /* Every third triangle spans up to the whole view (full block
         * rows), every third is a few pixels across (the tiny stamps). */
        for (int i = 0; i < N; i++) {
            double r = i % 3 == 0 ? 1.2 : i % 3 == 1 ? 0.15 : 0.03;
            double cx = sr_rng_range(&rng, -1, 1), cy = sr_rng_range(&rng, -1, 1);
            for (int v = 0; v < 3; v++) {
                kernel_test_vertex(&rng, cx, cy, r, &pos[(i * 3 + v) * 3], &nrm[(i * 3 + v) * 3]);
                for (int c = 0; c < 4; c++) {
                    col[(i * 3 + v) * 4 + c] = (float)sr_rng_range(&rng, -0.5, 1.5);
                }
                if (k / 8 % 2) {
                    /* Channels equal at all three vertices (unlit: the
                     * color as given): the kernels pack those once per
                     * triangle. */
                    col[(i * 3 + v) * 4 + 3] = 1.0f;
                    col[(i * 3 + v) * 4 + 1] = (float)(i % 5) * 0.3f - 0.2f;
                }
            }
        }
        sr_state st = { .shading = shadings[k % 4], .cull = SR_CULL_NONE,
                        .depth_test = k % 8 >= 4 ? SR_OFF : SR_ON,
                        .depth_write = k % 8 >= 4 ? SR_OFF : SR_ON,
                        .ambient = { 0.2f, 0.2f, 0.2f },
                        .material = { .diffuse = { 1, 1, 1 }, .specular = { 0.5f, 0.5f, 0.5f },
                                      .shininess = 8 } };
        st.lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL, .vector = { 0.2f, -0.5f, -1 } };
        if (k / 4 % 2) {
            /* Phong's other branches: back faces lit on both sides, a
             * point light (a length per pixel) and an odd shininess. */
            st.two_sided = true;
            st.lights[1] = (sr_light){ .type = SR_LIGHT_POINT, .vector = { 0.5f, 1.0f, -1.0f },
                                       .color = { 0.7f, 0.4f, 0.2f } };
            st.material.shininess = 13;
        }
        sr_depth_format df = k % 16 < 8 ? SR_DEPTH_D24 : SR_DEPTH_D16;
        const sr_draw_desc desc = { .positions = pos, .vertex_count = N * 3, .normals = nrm,
                                    .colors = col, .color_size = 4, .view = &io.view,
                                    .projection = &io.proj };
        kernel_test_draw(io.ctx, W, H, df, simd[0], &st, &desc, io.c[0], io.d[0]);
        for (int v = 1; v < 4; v++) {
            kernel_test_draw(io.ctx, W, H, df, simd[v], &st, &desc, io.c[1], io.d[1]);
            if (memcmp(io.c[0], io.c[1], W * H * 4) != 0 ||
                memcmp(io.d[0], io.d[1], sizeof(uint32_t) * W * H) != 0) {
                sr_test_fail(__FILE__, __LINE__, "batch %d (shading %d, depth test %d): "
                             "SR_SIMD=%s differs from the default kernel", k,
                             (int)st.shading, st.depth_test != SR_OFF, simd[v]);
            }
            compared++;
        }
    }
    CHECK_EQ(compared, 96);
    kernel_test_io_free(&io);
}

/* The front end's sixteen-lane assembly and setup of triangle lists
 * without indices (geometry/assembly_wide.h, at the AVX-512 level) against
 * the scalar triangle() and sr__setup_tri, through SR_SIMD=off: every cull
 * mode and winding, perspective and not, D16 and D24, tiny, small and large
 * triangles, some crossing the near plane or the sides (clipped at their
 * place among the others), some of zero area, some between pixel centres,
 * some with a vertex at infinity.  Pixels, depths and the draw's counters
 * must agree. */
SR_TEST(front_end_lanes_give_the_scalar_bytes_and_counts)
{
    enum { W = 173, H = 131, N = 200 };
    static const sr_cull_mode culls[] = { SR_CULL_NONE, SR_CULL_BACK, SR_CULL_FRONT,
                                          SR_CULL_FRONT_AND_BACK };
    float pos[N * 9], nrm[N * 9], col[N * 12];
    kernel_test_io io = kernel_test_io_make(W, H);
    sr_rng rng = { 0xfe16 };
    int compared = 0;
    for (int k = 0; k < 16 && !sr_test_failed_now(); k++) {
        for (int i = 0; i < N; i++) {
            int kind = i % 7;
            double r = kind < 3 ? 0.02 : kind < 5 ? 0.12 : 1.5;
            double cx = sr_rng_range(&rng, -1.3, 1.3), cy = sr_rng_range(&rng, -1.3, 1.3);
            for (int v = 0; v < 3; v++) {
                float *p = &pos[(i * 3 + v) * 3];
                p[0] = (float)(cx + sr_rng_range(&rng, -r, r));
                p[1] = (float)(cy + sr_rng_range(&rng, -r, r));
                /* Some vertices behind the near plane (z > 2 in front of
                 * the camera at -3): those triangles are clipped. */
                p[2] = (float)sr_rng_range(&rng, -2.0, kind == 6 ? 2.6 : 1.5);
                float *n = &nrm[(i * 3 + v) * 3];
                n[0] = (float)sr_rng_range(&rng, -0.5, 0.5);
                n[1] = (float)sr_rng_range(&rng, -0.5, 0.5);
                n[2] = 1.0f;
                for (int c = 0; c < 4; c++) {
                    col[(i * 3 + v) * 4 + c] = (float)sr_rng_range(&rng, -0.2, 1.2);
                }
            }
            if (i % 23 == 0) {
                /* Zero area: the third vertex on the line through the others. */
                for (int a = 0; a < 3; a++) {
                    pos[(i * 3 + 2) * 3 + a] = 2 * pos[(i * 3 + 1) * 3 + a] - pos[i * 9 + a];
                }
            }
            if (i % 37 == 5) {
                pos[i * 9] = INFINITY; /* not finite: discarded */
            }
        }
        sr_state st = { .shading = k % 3 == 2 ? SR_SHADING_UNLIT : SR_SHADING_GOURAUD,
                        .cull = culls[k % 4], .front_face = k / 4 % 2 ? SR_FRONT_CW : SR_FRONT_CCW,
                        .depth_test = k % 8 == 7 ? SR_OFF : SR_ON,
                        .depth_write = k % 8 == 7 ? SR_OFF : SR_ON };
        sr_depth_format df = k % 16 < 8 ? SR_DEPTH_D24 : SR_DEPTH_D16;
        /* Odd batches without a projection: w = 1, so no perspective. */
        st.lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL, .vector = { 0.2f, -0.5f, -1 } };
        const sr_draw_desc desc = { .positions = pos, .vertex_count = N * 3, .normals = nrm,
                                    .colors = col, .color_size = 4, .view = k % 2 ? NULL : &io.view,
                                    .projection = k % 2 ? NULL : &io.proj };
        kernel_test_draw(io.ctx, W, H, df, NULL, &st, &desc, io.c[0], io.d[0]);
        sr_draw_info lanes = sr_last_draw_info(io.ctx);
        kernel_test_draw(io.ctx, W, H, df, "off", &st, &desc, io.c[1], io.d[1]);
        sr_draw_info scalar = sr_last_draw_info(io.ctx);
        if (memcmp(io.c[0], io.c[1], W * H * 4) != 0 ||
            memcmp(io.d[0], io.d[1], sizeof(uint32_t) * W * H) != 0) {
            sr_test_fail(__FILE__, __LINE__, "batch %d (cull %d, winding %d): the default front "
                         "end differs from SR_SIMD=off", k, (int)st.cull, (int)st.front_face);
        }
        CHECK_EQ(lanes.triangles_in, scalar.triangles_in);
        CHECK_EQ(lanes.triangles_clipped, scalar.triangles_clipped);
        CHECK_EQ(lanes.triangles_culled, scalar.triangles_culled);
        CHECK_EQ(lanes.triangles_drawn, scalar.triangles_drawn);
        CHECK_EQ(lanes.fragments, scalar.fragments);
        CHECK(st.cull == SR_CULL_FRONT_AND_BACK ? scalar.triangles_drawn == 0
                                                : scalar.triangles_drawn > 0);
        CHECK(scalar.triangles_clipped > 0 && scalar.triangles_culled > 0);
        compared++;
    }
    CHECK_EQ(compared, 16);
    kernel_test_io_free(&io);
}

/* Triangles that cover the whole view: the vector kernels walk a box a
 * triangle covers whole by rows of sixteen with no coverage test, with
 * 32-bit edge lanes when the triangle is a few times the view and double
 * lanes when it is far larger.  Against the scalar loop: a 45 x 37 view
 * (one tile; rows end mid-span), triangles from 2 to 300 times its size
 * around random points near its centre, random depths and colors, each shading
 * model the kernels cover, depth LESS and off. */
SR_TEST(vector_kernels_give_the_scalar_bytes_for_boxes_covered_whole)
{
    enum { W = 45, H = 37, N = 4 };
    static const sr_shading shadings[] = { SR_SHADING_UNLIT, SR_SHADING_GOURAUD,
                                           SR_SHADING_FLAT, SR_SHADING_PHONG };
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    float pos[N * 9], nrm[N * 9], col[N * 12];
    uint8_t c0[W * H * 4], c1[W * H * 4];
    uint32_t d0[W * H], d1[W * H];
    sr_rng rng = { 0x16c0 };
    for (int k = 0; k < 48 && !sr_test_failed_now(); k++) {
        for (int i = 0; i < N; i++) {
            /* An equilateral triangle of circumradius r (NDC) around a
             * point within 0.3 of the centre contains the view once r/2
             * (its inradius) exceeds 1.3 sqrt(2).  Up to r = 5 its edge
             * values in the view fit 32 bits. */
            double r = i % 2 ? sr_rng_range(&rng, 3.8, 5) : sr_rng_range(&rng, 100, 600);
            double cx = sr_rng_range(&rng, -0.3, 0.3), cy = sr_rng_range(&rng, -0.3, 0.3);
            double a0 = sr_rng_range(&rng, 0, 2 * M_PI);
            for (int v = 0; v < 3; v++) {
                float *p = &pos[(i * 3 + v) * 3];
                p[0] = (float)(cx + r * cos(a0 + v * 2 * M_PI / 3));
                p[1] = (float)(cy + r * sin(a0 + v * 2 * M_PI / 3));
                p[2] = (float)sr_rng_range(&rng, -0.9, 0.9);
                float *n = &nrm[(i * 3 + v) * 3];
                n[0] = (float)sr_rng_range(&rng, -0.5, 0.5);
                n[1] = (float)sr_rng_range(&rng, -0.5, 0.5);
                n[2] = 1.0f;
                for (int c = 0; c < 4; c++) {
                    col[(i * 3 + v) * 4 + c] = (float)sr_rng_range(&rng, -0.2, 1.2);
                }
            }
        }
        sr_state st = { .shading = shadings[k % 4], .cull = SR_CULL_NONE,
                        .depth_test = k % 8 >= 4 ? SR_OFF : SR_ON, .ambient = { 0.2f, 0.2f, 0.2f },
                        .material = { .diffuse = { 1, 1, 1 }, .specular = { 0.5f, 0.5f, 0.5f },
                                      .shininess = 8 } };
        st.lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL, .vector = { 0.2f, -0.5f, -1 } };
        const sr_draw_desc desc = { .positions = pos, .vertex_count = N * 3, .normals = nrm,
                                    .colors = col, .color_size = 4 };
        kernel_test_draw(ctx, W, H, SR_DEPTH_D24, NULL, &st, &desc, c0, d0);
        kernel_test_draw(ctx, W, H, SR_DEPTH_D24, "off", &st, &desc, c1, d1);
        if (memcmp(c0, c1, sizeof c0) != 0 || memcmp(d0, d1, sizeof d0) != 0) {
            sr_test_fail(__FILE__, __LINE__, "batch %d (shading %d, depth test %d): the default "
                         "kernel differs from SR_SIMD=off", k, (int)st.shading,
                         st.depth_test != SR_OFF);
        }
    }
    sr_destroy_context(ctx);
}

/* A small framebuffer's box of a huge triangle: a corner inside the
 * image and the other two vertices up to 10,000 pixels away.  The box
 * is small, so the vector kernels walk it as they walk small triangles,
 * but its edge values near the corner exceed 32 bits: a kernel that
 * judged by the box rather than by the triangle would lose them. */
SR_TEST(vector_kernels_keep_huge_triangles_exact_in_small_boxes)
{
    enum { W = 13, H = 11, N = 24 };
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 1 }, &ctx) == SR_OK);
    float pos[N * 9], col[N * 12];
    uint8_t c0[W * H * 4], c1[W * H * 4];
    uint32_t d0[W * H], d1[W * H];
    sr_rng rng = { 0xb16 };
    for (int k = 0; k < 16 && !sr_test_failed_now(); k++) {
        for (int i = 0; i < N; i++) {
            /* NDC: one pixel is 2 / 13 wide, so 1,500 is about 10,000 px. */
            double fx = sr_rng_range(&rng, -1500, 1500), fy = sr_rng_range(&rng, -1500, 1500);
            double corner[3][2] = { { sr_rng_range(&rng, -1, 1), sr_rng_range(&rng, -1, 1) },
                                    { fx, fy },
                                    { fx + sr_rng_range(&rng, -300, 300), -fy } };
            for (int v = 0; v < 3; v++) {
                float *p = &pos[(i * 3 + v) * 3];
                p[0] = (float)corner[v][0];
                p[1] = (float)corner[v][1];
                p[2] = (float)sr_rng_range(&rng, -0.9, 0.9);
                for (int c = 0; c < 4; c++) {
                    col[(i * 3 + v) * 4 + c] = (float)sr_rng_range(&rng, 0, 1);
                }
            }
        }
        sr_state st = { .shading = k % 2 ? SR_SHADING_UNLIT : SR_SHADING_FLAT,
                        .cull = SR_CULL_NONE, .depth_test = k % 4 >= 2 ? SR_OFF : SR_ON };
        const sr_draw_desc desc = { .positions = pos, .vertex_count = N * 3, .colors = col,
                                    .color_size = 4 };
        kernel_test_draw(ctx, W, H, SR_DEPTH_D24, NULL, &st, &desc, c0, d0);
        kernel_test_draw(ctx, W, H, SR_DEPTH_D24, "off", &st, &desc, c1, d1);
        if (memcmp(c0, c1, sizeof c0) != 0 || memcmp(d0, d1, sizeof d0) != 0) {
            sr_test_fail(__FILE__, __LINE__, "batch %d: the default kernel differs from SR_SIMD=off",
                         k);
        }
    }
    sr_destroy_context(ctx);
}

/* The textured vector kernel (the AVX-512 build's stamps for unlit and
 * Gouraud color modulated by a texture) against the scalar loop: random
 * triangles large and tiny under perspective, texture coordinates beyond
 * [0, 1] in every wrap mode, the three filters, an sRGB texture and a
 * linear one of odd size (a mip chain with odd levels), depth LESS and
 * off.  Elsewhere the default is the scalar loop itself, and the test
 * still holds. */
SR_TEST(textured_vector_kernel_gives_the_scalar_loops_bytes)
{
    enum { W = 203, H = 141, N = 36, TW = 37, TH = 20 };
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 2 }, &ctx) == SR_OK);
    sr_rng rng = { 0x7e47 };
    uint8_t texels[TW * TH * 4];
    for (int i = 0; i < TW * TH * 4; i++) {
        texels[i] = (uint8_t)sr_rng_int(&rng, 0, 255);
    }
    sr_texture *tex[2] = { NULL, NULL };
    for (int k = 0; k < 2; k++) {
        REQUIRE(sr_make_texture(ctx, &(sr_texture_desc){ .width = TW, .height = TH,
                                                         .pixels = texels, .srgb = k == 1 },
                                &tex[k]) == SR_OK);
    }
    float pos[N * 9], nrm[N * 9], uv[N * 6];
    uint8_t *c0 = malloc(W * H * 4), *c1 = malloc(W * H * 4);
    uint32_t *d0 = malloc(sizeof(uint32_t) * W * H), *d1 = malloc(sizeof(uint32_t) * W * H);
    sr_mat4 view = sr_mat4_translate(0, 0, -3);
    sr_mat4 proj = sr_perspective(0.9f, (float)W / H, 1.0f, 10.0f, false);
    static const sr_texture_filter filters[] = { SR_FILTER_NEAREST, SR_FILTER_BILINEAR,
                                                 SR_FILTER_TRILINEAR };
    static const sr_texture_wrap wraps[] = { SR_WRAP_REPEAT, SR_WRAP_CLAMP, SR_WRAP_MIRROR };
    int compared = 0;
    for (int k = 0; k < 24 && !sr_test_failed_now(); k++) {
        for (int i = 0; i < N; i++) {
            double r = i % 3 == 0 ? 1.2 : i % 3 == 1 ? 0.15 : 0.03;
            double cx = sr_rng_range(&rng, -1, 1), cy = sr_rng_range(&rng, -1, 1);
            for (int v = 0; v < 3; v++) {
                kernel_test_vertex(&rng, cx, cy, r, &pos[(i * 3 + v) * 3], &nrm[(i * 3 + v) * 3]);
                uv[(i * 3 + v) * 2] = (float)sr_rng_range(&rng, -1.5, 2.5);
                uv[(i * 3 + v) * 2 + 1] = (float)sr_rng_range(&rng, -1.5, 2.5);
            }
        }
        sr_state st = { .shading = k % 2 ? SR_SHADING_GOURAUD : SR_SHADING_UNLIT,
                        .cull = SR_CULL_NONE, .depth_test = k % 4 >= 2 ? SR_OFF : SR_ON,
                        .depth_write = k % 4 >= 2 ? SR_OFF : SR_ON, .texture = tex[k / 12],
                        .texture_filter = filters[k % 3], .wrap_u = wraps[k / 3 % 3],
                        .wrap_v = wraps[(k / 3 + 1) % 3],
                        .ambient = { 0.2f, 0.2f, 0.2f },
                        .material = { .diffuse = { 0.9f, 0.8f, 1.2f }, .specular = { 0.5f, 0.5f, 0.5f },
                                      .shininess = 8 } };
        st.lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL, .vector = { 0.2f, -0.5f, -1 } };
        const sr_draw_desc desc = { .positions = pos, .vertex_count = N * 3, .normals = nrm,
                                    .texcoords = uv, .view = &view, .projection = &proj };
        kernel_test_draw(ctx, W, H, SR_DEPTH_D24, NULL, &st, &desc, c0, d0);
        kernel_test_draw(ctx, W, H, SR_DEPTH_D24, "off", &st, &desc, c1, d1);
        if (memcmp(c0, c1, W * H * 4) != 0 || memcmp(d0, d1, sizeof(uint32_t) * W * H) != 0) {
            sr_test_fail(__FILE__, __LINE__, "batch %d (shading %d, filter %d, wrap %d/%d, "
                         "srgb %d): the default kernel differs from SR_SIMD=off", k,
                         (int)st.shading, (int)st.texture_filter, (int)st.wrap_u,
                         (int)st.wrap_v, k / 12);
        }
        compared++;
    }
    CHECK_EQ(compared, 24);
    free(c0);
    free(d0);
    free(c1);
    free(d1);
    sr_destroy_texture(ctx, tex[0]);
    sr_destroy_texture(ctx, tex[1]);
    sr_destroy_context(ctx);
}

/* The batch size changes how often each tile is visited, never the
 * bytes: 5,000 overlapping triangles with blending (order matters) in
 * batches of 1,024 and of the default size, on 1 and 3 threads. */
SR_TEST(batch_size_changes_no_byte)
{
    enum { W = 2 * SR_TILE_SIZE + 32, H = SR_TILE_SIZE + 56, N = 5000 }; /* 3 x 2 tiles */
    float *pos = malloc(sizeof(float) * 9 * N), *col = malloc(sizeof(float) * 12 * N);
    sr_rng rng = { 0xba7c };
    for (int i = 0; i < 3 * N; i++) {
        pos[i * 3 + 0] = (float)sr_rng_range(&rng, -1.1, 1.1);
        pos[i * 3 + 1] = (float)sr_rng_range(&rng, -1.1, 1.1);
        pos[i * 3 + 2] = (float)sr_rng_range(&rng, -0.9, 0.9);
        for (int c = 0; c < 4; c++) {
            col[i * 4 + c] = (float)sr_rng_unit(&rng);
        }
    }
    /* Nearby vertices: small triangles, so tiles see triangles of many batches. */
    for (int i = 0; i < N; i++) {
        for (int v = 1; v < 3; v++) {
            for (int a = 0; a < 2; a++) {
                pos[(i * 3 + v) * 3 + a] = pos[i * 9 + a] + (pos[(i * 3 + v) * 3 + a] * 0.1f);
            }
        }
    }
    static const int batch[] = { SR_BATCH_MIN, 0, SR_BATCH_MIN, 0 };
    static const int threads[] = { 1, 1, 3, 3 };
    uint8_t *first = malloc(W * H * 4);
    for (int v = 0; v < 4; v++) {
        sr_context *ctx;
        REQUIRE(sr_make_context(&(sr_context_desc){ .threads = threads[v],
                                                    .batch_primitives = batch[v] }, &ctx) == SR_OK);
        sr_framebuffer *fb;
        REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &fb) ==
                SR_OK);
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 }, .depth = 1 });
        sr_state st = { .shading = SR_SHADING_UNLIT,
                        .blend = { .enabled = true, .src_rgb = SR_BLEND_SRC_ALPHA,
                                   .dst_rgb = SR_BLEND_ONE_MINUS_SRC_ALPHA,
                                   .src_alpha = SR_BLEND_ONE, .dst_alpha = SR_BLEND_ZERO } };
        CHECK_EQ(sr_draw(ctx, fb, &st, &(sr_draw_desc){ .positions = pos, .vertex_count = 3 * N,
                                                         .colors = col }), SR_OK);
        if (v == 0) {
            memcpy(first, sr_framebuffer_pixels(fb), W * H * 4);
        } else {
            CHECK(memcmp(first, sr_framebuffer_pixels(fb), W * H * 4) == 0);
        }
        sr_destroy_framebuffer(ctx, fb);
        sr_destroy_context(ctx);
    }
    free(first);
    free(pos);
    free(col);
}

/* Tiny triangles, n of them from `first` on, with random colors and depth:
 * a corner in a random place and the other vertices within about 4
 * pixels of it, or (`walk`) the corners one beside the other along the
 * rows of a w x h framebuffer, the way a mesh's triangles follow each
 * other. */
static void tiny_triangles(sr_rng *rng, int first, int n, bool walk, int w, int h, float *pos,
                           float *col)
{
    for (int i = first; i < first + n; i++) {
        double cx, cy;
        if (walk) {
            int per_row = w / 5;
            cx = -1.0 + (2.0 * (i % per_row) + 1.0) * 5.0 / w;
            cy = 1.0 - (2.0 * ((i / per_row) % (h / 5)) + 1.0) * 5.0 / h;
        } else {
            cx = sr_rng_range(rng, -1.05, 1.05);
            cy = sr_rng_range(rng, -1.05, 1.05);
        }
        for (int v = 0; v < 3; v++) {
            float *p = &pos[(i * 3 + v) * 3];
            p[0] = (float)(cx + (v ? sr_rng_range(rng, -8.0 / w, 8.0 / w) : 0));
            p[1] = (float)(cy + (v ? sr_rng_range(rng, -8.0 / h, 8.0 / h) : 0));
            p[2] = (float)sr_rng_range(rng, -0.9, 0.9);
            for (int c = 0; c < 4; c++) {
                col[(i * 3 + v) * 4 + c] = (float)sr_rng_unit(rng);
            }
        }
    }
}

/* Tiny primitives scattered over many tiles: on more than one thread
 * their chunks are copied in tile order (parallel/bin.c), which must give
 * the bytes of numbered bins - those of one draw per primitive, whose
 * one-primitive chunks are never scattered.  Triangles with blending
 * (order matters), depth-tested points and, beside them, short lines,
 * each as one draw in batches of 1,024 and of the default size, on 1, 2
 * and 3 threads, and one draw per primitive on 3 threads too (each then
 * one chunk, binned over its own tiles, after draws elsewhere). */
SR_TEST(primitives_copied_in_tile_order_give_the_bytes_of_numbered_bins)
{
    /* 10 x 6 tiles: two random primitives in a row mostly start over a
     * tile apart, which makes a chunk scattered (parallel/bin.c). */
    enum { W = 10 * SR_TILE_SIZE, H = 6 * SR_TILE_SIZE, N = 6000 };
    float *pos = malloc(sizeof(float) * 9 * N), *col = malloc(sizeof(float) * 12 * N);
    REQUIRE(pos && col);
    sr_rng rng = { 0x711e };
    tiny_triangles(&rng, 0, N, false, W, H, pos, col);
    /* Points at the corners, lines from each corner to a vertex near it:
     * consecutive primitives lie apart, as consecutive triangles do. */
    uint32_t *idx = malloc(sizeof(uint32_t) * 2 * N);
    REQUIRE(idx);
    for (int i = 0; i < N; i++) {
        idx[2 * i] = (uint32_t)(3 * i);
        idx[2 * i + 1] = (uint32_t)(3 * i + 1);
    }
    uint32_t *corners = malloc(sizeof(uint32_t) * N);
    REQUIRE(corners);
    for (int i = 0; i < N; i++) {
        corners[i] = (uint32_t)(3 * i);
    }
    static const sr_primitive prims[] = { SR_PRIM_TRIANGLES, SR_PRIM_POINTS, SR_PRIM_LINES };
    /* Variants 0, the reference, and 6 draw one primitive at a time. */
    enum { VARIANTS = 7 };
    static const int batch[VARIANTS] = { 0, SR_BATCH_MIN, 0, 0, 0, SR_BATCH_MIN, 0 };
    static const int threads[VARIANTS] = { 1, 1, 1, 2, 3, 2, 3 };
    uint8_t *first = malloc(W * H * 4);
    REQUIRE(first);
    for (int k = 0; k < 3; k++) {
        bool copied = false;
        for (int v = 0; v < VARIANTS; v++) {
            bool each = v == 0 || v == 6;
            sr_context *ctx;
            REQUIRE(sr_make_context(&(sr_context_desc){ .threads = threads[v],
                                                        .batch_primitives = batch[v] },
                                    &ctx) == SR_OK);
            sr_framebuffer *fb;
            REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H },
                                        &fb) == SR_OK);
            sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 }, .depth = 1 });
            sr_state st = { .shading = SR_SHADING_UNLIT, .point_size = 2, .line_width = 1 };
            if (prims[k] == SR_PRIM_TRIANGLES) {
                st.blend = (sr_blend){ .enabled = true, .src_rgb = SR_BLEND_SRC_ALPHA,
                                             .dst_rgb = SR_BLEND_ONE_MINUS_SRC_ALPHA,
                                             .src_alpha = SR_BLEND_ONE,
                                             .dst_alpha = SR_BLEND_ZERO };
            } else {
                st.depth_func = SR_LESS;
            }
            sr_draw_desc d = { .primitive = prims[k], .positions = pos, .vertex_count = 3 * N,
                               .colors = col };
            if (prims[k] != SR_PRIM_TRIANGLES) {
                d.indices = prims[k] == SR_PRIM_LINES ? idx : corners;
                d.index_type = SR_INDEX_U32;
                d.index_count = prims[k] == SR_PRIM_LINES ? 2 * N : N;
            }
            bool copies = false;
            for (int i = 0; i < (each ? N : 1); i++) {
                sr_draw_desc one = d;
                if (each && prims[k] == SR_PRIM_TRIANGLES) {
                    one.positions = pos + 9 * i;
                    one.colors = col + 12 * i;
                    one.vertex_count = 3;
                } else if (each) {
                    size_t first_index = prims[k] == SR_PRIM_LINES ? 2 * (size_t)i : (size_t)i;
                    one.indices = (const uint32_t *)d.indices + first_index;
                    one.index_count = prims[k] == SR_PRIM_LINES ? 2 : 1;
                }
                CHECK_EQ(sr_draw(ctx, fb, &st, &one), SR_OK);
                for (int ci = 0; ci < SR_MAX_CHUNKS; ci++) {
                    copies |= ctx->scratch->chunks[ci].in_tile_order;
                }
            }
            if (each) {
                CHECK(!copies);
            }
            if (v == 0) {
                memcpy(first, sr_framebuffer_pixels(fb), W * H * 4);
            } else if (memcmp(first, sr_framebuffer_pixels(fb), W * H * 4) != 0) {
                sr_test_fail(__FILE__, __LINE__, "primitive %d: %d threads, batch %d differ from "
                             "one draw per primitive", (int)prims[k], threads[v], batch[v]);
            }
            copied |= copies;
            sr_destroy_framebuffer(ctx, fb);
            sr_destroy_context(ctx);
        }
        /* The test is of the copies: some chunk must have made them - of
         * triangles and points.  An aliased line's tiles are walked from
         * its record, not given by a box, so binning never counts a chunk
         * of lines as scattered: they keep their refs. */
        CHECK_EQ(copied, prims[k] != SR_PRIM_LINES);
    }
    free(idx);
    free(corners);
    free(first);
    free(pos);
    free(col);
}

/* A chunk copied in tile order sets its next batch up with plain stores
 * (geometry/assembly.c, sr__run_front_end), guessing that it will be copied again.  When
 * the guess is wrong - scattered triangles, then a mesh-like draw that is
 * binned by numbers - the tile jobs read the records from the writer's
 * cache.  Either way the bytes must be one thread's: scattered, walked,
 * scattered again, on 2 and 3 threads against 1, depth-tested. */
SR_TEST(plain_stores_after_a_copied_batch_give_one_threads_bytes)
{
    enum { W = 10 * SR_TILE_SIZE, H = 6 * SR_TILE_SIZE, N = 6000 };
    float *pos = malloc(sizeof(float) * 9 * 3 * N), *col = malloc(sizeof(float) * 12 * 3 * N);
    uint8_t *c0 = malloc(W * H * 4);
    uint32_t *d0 = malloc(sizeof(uint32_t) * W * H), *d1 = malloc(sizeof(uint32_t) * W * H);
    REQUIRE(pos && col && c0 && d0 && d1);
    sr_rng rng = { 0x9a1e };
    tiny_triangles(&rng, 0, N, false, W, H, pos, col);
    tiny_triangles(&rng, N, N, true, W, H, pos, col);
    tiny_triangles(&rng, 2 * N, N, false, W, H, pos, col);
    static const int threads[] = { 1, 2, 3 };
    for (int v = 0; v < 3; v++) {
        sr_context *ctx;
        REQUIRE(sr_make_context(&(sr_context_desc){ .threads = threads[v] }, &ctx) == SR_OK);
        sr_framebuffer *fb;
        REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H },
                                    &fb) == SR_OK);
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 }, .depth = 1 });
        sr_state st = { .shading = SR_SHADING_UNLIT, .depth_func = SR_LESS };
        /* Per draw, whether a chunk was copied in tile order, and whether
         * one set its records up with plain stores and was not copied. */
        bool copied[3] = { false }, guessed_wrong[3] = { false };
        for (int k = 0; k < 3; k++) {
            sr_draw_desc d = { .primitive = SR_PRIM_TRIANGLES, .positions = pos + 9 * k * N,
                               .colors = col + 12 * k * N, .vertex_count = 3 * N };
            CHECK_EQ(sr_draw(ctx, fb, &st, &d), SR_OK);
            for (int ci = 0; ci < SR_MAX_CHUNKS; ci++) {
                const sr_chunk *c = &ctx->scratch->chunks[ci];
                copied[k] |= c->in_tile_order;
                guessed_wrong[k] |= c->tri_count > 0 && !c->stream && !c->in_tile_order;
            }
        }
        raw_depth(fb, v == 0 ? d0 : d1);
        if (v == 0) {
            CHECK(!copied[0] && !copied[2]);
            memcpy(c0, sr_framebuffer_pixels(fb), W * H * 4);
        } else {
            /* The paths this test is for were taken: the scattered draws
             * were copied, and the walk after the first was set up with
             * plain stores but binned by numbers. */
            CHECK(copied[0] && !copied[1] && copied[2]);
            CHECK(guessed_wrong[1]);
            if (memcmp(c0, sr_framebuffer_pixels(fb), W * H * 4) != 0 ||
                memcmp(d0, d1, sizeof(uint32_t) * W * H) != 0) {
                sr_test_fail(__FILE__, __LINE__, "%d threads differ from 1 thread", threads[v]);
            }
        }
        sr_destroy_framebuffer(ctx, fb);
        sr_destroy_context(ctx);
    }
    free(c0);
    free(d0);
    free(d1);
    free(pos);
    free(col);
}

SR_TEST(moving_the_viewport_by_whole_pixels_moves_the_image_exactly)
{
    enum { W = 200, H = 160, VW = 96, VH = 80 };
    sr_context *ctx;
    REQUIRE(sr_make_context(&(sr_context_desc){ .threads = 2 }, &ctx) == SR_OK);
    sr_framebuffer *fa, *fb;
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                .depth_format = SR_DEPTH_D24 }, &fa) == SR_OK);
    REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                .depth_format = SR_DEPTH_D24 }, &fb) == SR_OK);
    sr_rng rng = { 0x7a4e5 };
    static scene s;
    int nonempty = 0;
    for (int k = 0; k < 48 && !sr_test_failed_now(); k++) {
        random_scene(&rng, k, &s);
        /* The scene stays inside the viewport: only whole-pixel moves. */
        s.st.point_size = s.st.point_size > 4 ? 4 : s.st.point_size;
        s.st.line_width = s.st.line_width > 2 ? 2 : s.st.line_width;
        for (int i = 0; i < s.nv * 3; i++) {
            s.pos[i] *= 0.6f;
        }
        int ax = sr_rng_int(&rng, 0, W - VW), ay = sr_rng_int(&rng, 0, H - VH);
        int bx = sr_rng_int(&rng, 0, W - VW), by = sr_rng_int(&rng, 0, H - VH);
        sr_rasterizer rast = (sr_rasterizer)(1 + k % 3);
        CHECK_EQ(draw_scene(ctx, fa, &s, (sr_viewport){ ax, ay, VW, VH }, rast), SR_OK);
        CHECK_EQ(draw_scene(ctx, fb, &s, (sr_viewport){ bx, by, VW, VH }, rast), SR_OK);
        const uint8_t *pa = sr_framebuffer_pixels(fa), *pb = sr_framebuffer_pixels(fb);
        static uint32_t da[W * H], db[W * H];
        raw_depth(fa, da);
        raw_depth(fb, db);
        nonempty += sr_last_draw_info(ctx).fragments > 0;
        for (int y = 0; y < VH; y++) {
            int x = 0;
            for (; x < VW; x++) {
                size_t ia = (size_t)(ay + y) * W + (size_t)(ax + x);
                size_t ib = (size_t)(by + y) * W + (size_t)(bx + x);
                if (memcmp(pa + ia * 4, pb + ib * 4, 4) != 0 || da[ia] != db[ib]) {
                    sr_test_fail(__FILE__, __LINE__, "scene %d: viewport pixel (%d, %d) differs "
                                 "after moving by (%d, %d)", k, x, y, bx - ax, by - ay);
                    break;
                }
            }
            if (x < VW) {
                break;
            }
        }
    }
    CHECK(nonempty > 24);
    sr_destroy_framebuffer(ctx, fa);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
}
