/* test_interp.c - attribute interpolation: perspective-correct varyings
 * against a ray-cast reference through the internal setup and fragment
 * helpers (the public API only carries 8-bit colors), affine mode differing
 * from it, screen-linear depth, the provoking vertex of flat shading for
 * lists, strips and fans (docs/raster-rules.md §5.4), and Gouraud vs Phong on a
 * highlight inside a big quad.  Fixed seeds. */
#include "sr_test.h"
#include "softrast.h"
#include "pipeline.h"
#include "fragment/fragment.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- the internal route: clip vertices -> setup -> bary/interp -------- */

enum { W = 128, H = 128 };

static sr_draw_state make_ds(bool perspective)
{
    sr_draw_state ds;
    memset(&ds, 0, sizeof ds);
    ds.vp_px = W * 0.5;
    ds.vp_py = H * 0.5;
    ds.vp_ox = W * 0.5;
    ds.vp_oy = H * 0.5;
    ds.vp_zs = 0.5;                   /* GL depth: z_w = z_ndc / 2 + 1/2 */
    ds.vp_zb = 0.5;
    ds.depth_min = 0.0;
    ds.depth_max = 1.0;
    ds.depth_scale = 1.0;             /* depth plane in [0, 1] units */
    ds.zq_min = 0.0;
    ds.zq_max = 1.0;
    ds.rect_x1 = W;
    ds.rect_y1 = H;
    ds.perspective = perspective;
    ds.shading = SR_SHADING_UNLIT;
    ds.nvary = 2;
    ds.ninterp = 2;
    return ds;
}

/* The projection: sr_frustum(-n, n, -n, n, n, f), so x_c = x_e, y_c = y_e
 * and w_c = -z_e exactly, and NDC x = x_e / -z_e. */
static const double PN = 0.5, PF = 100.0;

/* An eye-space point given by its NDC (x, y) and its distance s = -z_e. */
typedef struct eye_pt { double xn, yn, s; } eye_pt;

static void eye_xyz(eye_pt p, double out[3])
{
    out[0] = p.xn * p.s;
    out[1] = p.yn * p.s;
    out[2] = -p.s;
}

/* A linear attribute field over eye space: f(p) = g . p + g0. */
typedef struct field { double g[3], g0; } field;

static double field_at(const field *f, const double p[3])
{
    return f->g[0] * p[0] + f->g[1] * p[1] + f->g[2] * p[2] + f->g0;
}

static sr_clip_vertex clip_vertex(eye_pt p, const field f[2])
{
    sr_clip_vertex v;
    memset(&v, 0, sizeof v);
    double e[3];
    eye_xyz(p, e);
    double a = -(PF + PN) / (PF - PN), b = -2 * PF * PN / (PF - PN);
    v.pos[0] = (float)e[0];
    v.pos[1] = (float)e[1];
    v.pos[2] = (float)(a * e[2] + b);
    v.pos[3] = (float)p.s;
    v.vary[0] = (float)field_at(&f[0], e);
    v.vary[1] = (float)field_at(&f[1], e);
    return v;
}

/* Where the ray through window point (x, y) meets the plane through the
 * three eye points: returns the eye-space hit. */
static void ray_plane(double x, double y, const double p[3][3], double hit[3])
{
    double d[3] = { x / (W * 0.5) - 1.0, 1.0 - y / (H * 0.5), -1.0 };
    double e1[3] = { p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2] };
    double e2[3] = { p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2] };
    double n[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0] };
    double s = (n[0] * p[0][0] + n[1] * p[0][1] + n[2] * p[0][2]) / (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]);
    hit[0] = s * d[0];
    hit[1] = s * d[1];
    hit[2] = s * d[2];
}

typedef struct interp_stats {
    int pixels;
    double max_err;        /* perspective mode vs the reference */
    double max_depth_err;
} interp_stats;

/* Set up the triangle and compare every covered pixel centre with the
 * analytic value.  With perspective = false, max_err is the affine error. */
static void check_triangle(const eye_pt v[3], const field f[2], bool perspective, interp_stats *st)
{
    sr_draw_state ds = make_ds(perspective);
    sr_clip_vertex cv[3];
    sr_window_vertex wv[3];
    double e[3][3];
    for (int i = 0; i < 3; i++) {
        cv[i] = clip_vertex(v[i], f);
        sr__window_vertex(&ds, &cv[i], &wv[i]);
        eye_xyz(v[i], e[i]);
        /* The chosen points snap exactly: no snapping error to allow for. */
        REQUIRE(wv[i].x_q8 == (int32_t)llround((v[i].xn + 1) * W * 0.5 * 256));
        REQUIRE(wv[i].y_q8 == (int32_t)llround((1 - v[i].yn) * H * 0.5 * 256));
    }
    sr_tri *t = calloc(1, sizeof *t);
    if (!sr__setup_triangle(&ds, &wv[0], &wv[1], &wv[2], true, 2, NULL, t)) {
        free(t);
        return;
    }
    double a = -(PF + PN) / (PF - PN), b = -2 * PF * PN / (PF - PN);
    for (int py = t->h.y0; py < t->h.y1; py++) {
        for (int px = t->h.x0; px < t->h.x1; px++) {
            int64_t X = 256 * (int64_t)px + 128, Y = 256 * (int64_t)py + 128;
            int64_t ev[3];
            bool in = true;
            for (int i = 0; i < 3; i++) {
                ev[i] = t->a[i] * X + t->b[i] * Y + sr__tri_c(t, i);
                in &= ev[i] + sr__tri_bias(t, i) >= 0;
            }
            if (!in) {
                continue;
            }
            float l[3];
            sr__bary(&ds, t, ev[0], ev[1], ev[2], l);
            double hit[3];
            ray_plane(px + 0.5, py + 0.5, e, hit);
            for (int k = 0; k < 2; k++) {
                double got = sr__interp(t, l, k), want = field_at(&f[k], hit);
                st->max_err = fmax(st->max_err, fabs(got - want));
            }
            /* Window depth is linear in screen space and equals the depth
             * of the hit point. */
            double zw = 0.5 * ((a * hit[2] + b) / -hit[2]) + 0.5;
            st->max_depth_err = fmax(st->max_depth_err, fabs(sr__tri_depth(t, ev[1], ev[2]) - zw));
            st->pixels++;
        }
    }
    free(t);
}

/* A floor from z = -1 to z = -16 (distances that are powers of two, so the
 * corners project exactly onto the 1/256 grid) with texture coordinates
 * u = (x + 4)/8 across and v = (-z - 1)/15 into the distance. */
SR_TEST(perspective_correct_texcoords_on_a_receding_floor)
{
    const eye_pt c[4] = { { -4, -1, 1 }, { 4, -1, 1 }, { 0.25, -1.0 / 16, 16 }, { -0.25, -1.0 / 16, 16 } };
    const field f[2] = { { { 1.0 / 8, 0, 0 }, 0.5 }, { { 0, 0, -1.0 / 15 }, -1.0 / 15 } };
    const eye_pt t0[3] = { c[0], c[1], c[2] }, t1[3] = { c[0], c[2], c[3] };
    interp_stats persp = { 0 }, affine = { 0 };
    check_triangle(t0, f, true, &persp);
    check_triangle(t1, f, true, &persp);
    check_triangle(t0, f, false, &affine);
    check_triangle(t1, f, false, &affine);
    CHECK(persp.pixels > 3000);
    CHECK_EQ(affine.pixels, persp.pixels);
    CHECK(persp.max_err <= 1e-4);
    CHECK(persp.max_depth_err <= 1e-6);
    /* Screen-linear interpolation is visibly wrong under perspective. */
    CHECK(affine.max_err > 0.01);
    if (persp.max_err > 1e-4 || !(affine.max_err > 0.01)) {
        fprintf(stderr, "floor: perspective err %g, affine err %g\n", persp.max_err, affine.max_err);
    }
}

/* Random triangles at random distances, with random linear fields. */
SR_TEST(perspective_correct_attributes_on_random_triangles)
{
    sr_rng rng = { 0x1e7e };
    interp_stats persp = { 0 }, affine = { 0 };
    int tilted = 0;
    for (int it = 0; it < 300; it++) {
        eye_pt v[3];
        for (int i = 0; i < 3; i++) {
            /* Window positions on the 1/256 grid, within +-1.5 viewports. */
            double xq = sr_rng_int(&rng, -64 * 256, 192 * 256) / 256.0;
            double yq = sr_rng_int(&rng, -64 * 256, 192 * 256) / 256.0;
            v[i].xn = xq / (W * 0.5) - 1;
            v[i].yn = 1 - yq / (H * 0.5);
            v[i].s = ldexp(1.0, sr_rng_int(&rng, -1, 5));   /* 0.5 .. 32 */
        }
        field f[2];
        for (int k = 0; k < 2; k++) {
            for (int j = 0; j < 3; j++) {
                f[k].g[j] = sr_rng_range(&rng, -0.2, 0.2);
            }
            f[k].g0 = sr_rng_range(&rng, -1, 1);
        }
        /* Keep the values O(1) over the triangle. */
        double e[3], mx = 0;
        for (int i = 0; i < 3; i++) {
            eye_xyz(v[i], e);
            mx = fmax(mx, fmax(fabs(field_at(&f[0], e)), fabs(field_at(&f[1], e))));
        }
        if (mx > 4) {
            continue;
        }
        tilted += v[0].s != v[1].s || v[1].s != v[2].s;
        check_triangle(v, f, true, &persp);
        check_triangle(v, f, false, &affine);
    }
    CHECK(persp.pixels > 50000);
    CHECK(tilted > 100);
    CHECK(persp.max_err <= 1e-4);
    CHECK(persp.max_depth_err <= 1e-6);
    CHECK(affine.max_err > 0.01);
    if (persp.max_err > 1e-4) {
        fprintf(stderr, "random: perspective err %g\n", persp.max_err);
    }
}

/* Triangles parallel to the screen (equal w): both modes agree. */
SR_TEST(affine_equals_perspective_when_w_is_constant)
{
    const eye_pt v[3] = { { -0.75, -0.5, 4 }, { 0.5, -0.625, 4 }, { 0.125, 0.875, 4 } };
    const field f[2] = { { { 0.3, -0.1, 0.2 }, 0.1 }, { { -0.2, 0.25, 0 }, 0.4 } };
    interp_stats p = { 0 }, a = { 0 };
    check_triangle(v, f, true, &p);
    check_triangle(v, f, false, &a);
    CHECK(p.pixels > 1000);
    CHECK(p.max_err <= 1e-5);
    CHECK(a.max_err <= 1e-5);
}

/* ---- flat shading and the provoking vertex (public API) ---------------- */

typedef struct fbuf {
    sr_context *ctx;
    sr_framebuffer *fb;
} fbuf;

static fbuf fbuf_make(int w, int h)
{
    fbuf f = { NULL, NULL };
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &f.ctx);
    sr_make_framebuffer(f.ctx, &(sr_framebuffer_desc){ .width = w, .height = h }, &f.fb);
    sr_clear(f.ctx, f.fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 }, .depth = 1 });
    return f;
}

static void fbuf_free(fbuf *f)
{
    sr_destroy_framebuffer(f->ctx, f->fb);
    sr_destroy_context(f->ctx);
}

enum { FW = 64, FH = 64 };

/* Vertex k's color: exact in 8 bits after scaling, and distinct. */
static void vertex_color(int k, float c[4])
{
    c[0] = (float)((k + 1) % 8) / 8.0f;
    c[1] = (float)((7 * k + 3) % 8) / 8.0f;
    c[2] = (float)(k / 8 + 1) / 4.0f;
    c[3] = 1.0f;
}

static uint8_t u8(float v) { return (uint8_t)(v * 255.0f + 0.5f); }

/* The pixel containing NDC point (x, y). */
static const uint8_t *pixel_at(const fbuf *f, double x, double y)
{
    int px = (int)floor((x + 1) * FW / 2), py = (int)floor((1 - y) * FH / 2);
    return sr_framebuffer_pixels(f->fb) + (py * FW + px) * 4;
}

static bool pixel_is(const uint8_t *p, const float c[4])
{
    return p[0] == u8(c[0]) && p[1] == u8(c[1]) && p[2] == u8(c[2]);
}

/* Flat, no lights, ambient 1: the color is the provoking vertex's. */
static sr_state flat_state(sr_provoking_vertex pv)
{
    return (sr_state){ .shading = SR_SHADING_FLAT, .provoking = pv, .ambient = { 1, 1, 1 },
                       .material = { .diffuse = { 1, 1, 1 } } };
}

/* Draw (optionally indexed) and check each triangle's centroid pixel. */
static void check_provoking(sr_primitive prim, const float (*xy)[2], int nverts,
                            const uint16_t *indices, int nidx, const int (*tri)[3],
                            const int *want_first, const int *want_last, int ntri)
{
    float *pos = malloc(sizeof(float) * 3 * (size_t)nverts), *col = malloc(sizeof(float) * 4 * (size_t)nverts);
    for (int k = 0; k < nverts; k++) {
        pos[k * 3] = xy[k][0];
        pos[k * 3 + 1] = xy[k][1];
        pos[k * 3 + 2] = 0;
        vertex_color(k, col + k * 4);
    }
    for (int mode = 0; mode < 2; mode++) {
        fbuf f = fbuf_make(FW, FH);
        sr_state st = flat_state(mode ? SR_PROVOKING_LAST : SR_PROVOKING_DEFAULT);
        sr_draw_desc d = { .primitive = prim, .positions = pos, .vertex_count = (size_t)nverts,
                           .colors = col, .indices = indices,
                           .index_type = indices ? SR_INDEX_U16 : SR_INDEX_NONE,
                           .index_count = (size_t)nidx };
        REQUIRE(sr_draw(f.ctx, f.fb, &st, &d) == SR_OK);
        CHECK_EQ(sr_last_draw_info(f.ctx).triangles_drawn, ntri);
        for (int i = 0; i < ntri; i++) {
            double cx = 0, cy = 0;
            for (int j = 0; j < 3; j++) {
                cx += xy[tri[i][j]][0] / 3.0;
                cy += xy[tri[i][j]][1] / 3.0;
            }
            float want[4];
            vertex_color(mode ? want_last[i] : want_first[i], want);
            const uint8_t *p = pixel_at(&f, cx, cy);
            if (!pixel_is(p, want)) {
                fprintf(stderr, "prim %d tri %d mode %s: got %d %d %d, want vertex %d\n", (int)prim, i,
                        mode ? "last" : "first", p[0], p[1], p[2], mode ? want_last[i] : want_first[i]);
            }
            CHECK(pixel_is(p, want));
        }
        fbuf_free(&f);
    }
    free(pos);
    free(col);
}

SR_TEST(flat_shading_uses_the_provoking_vertex_of_triangle_lists)
{
    const float xy[9][2] = { { -0.9f, -0.9f }, { -0.1f, -0.9f }, { -0.5f, -0.1f },
                             { 0.1f, 0.1f }, { 0.9f, 0.1f }, { 0.5f, 0.9f },
                             { -0.9f, 0.9f }, { -0.9f, 0.1f }, { -0.1f, 0.5f } };
    const int tri[3][3] = { { 0, 1, 2 }, { 3, 4, 5 }, { 6, 7, 8 } };
    const int first[3] = { 0, 3, 6 }, last[3] = { 2, 5, 8 };  /* 3i and 3i + 2 */
    check_provoking(SR_PRIM_TRIANGLES, xy, 9, NULL, 0, tri, first, last, 3);
    /* Indexed: the provoking vertex is the one the index list names. */
    const uint16_t idx[6] = { 8, 6, 7, 2, 0, 1 };
    const int itri[2][3] = { { 8, 6, 7 }, { 2, 0, 1 } };
    const int ifirst[2] = { 8, 2 }, ilast[2] = { 7, 1 };
    check_provoking(SR_PRIM_TRIANGLES, xy, 9, idx, 6, itri, ifirst, ilast, 2);
}

/* Strip triangle i is (v_i, v_i+1, v_i+2): first -> v_i, last -> v_i+2
 * (GL Table 13.2), whatever the winding swap of odd triangles. */
SR_TEST(flat_shading_uses_the_provoking_vertex_of_strips)
{
    const float xy[7][2] = { { -0.9f, 0.8f }, { -0.9f, -0.8f }, { -0.3f, 0.8f }, { -0.3f, -0.8f },
                             { 0.3f, 0.8f }, { 0.3f, -0.8f }, { 0.9f, 0.8f } };
    int tri[5][3], first[5], last[5];
    for (int i = 0; i < 5; i++) {
        tri[i][0] = i;
        tri[i][1] = i + 1;
        tri[i][2] = i + 2;
        first[i] = i;
        last[i] = i + 2;
    }
    check_provoking(SR_PRIM_TRIANGLE_STRIP, xy, 7, NULL, 0, tri, first, last, 5);
    /* The same strip through reversed indices. */
    const uint16_t idx[7] = { 6, 5, 4, 3, 2, 1, 0 };
    int rtri[5][3], rfirst[5], rlast[5];
    for (int i = 0; i < 5; i++) {
        rtri[i][0] = idx[i];
        rtri[i][1] = idx[i + 1];
        rtri[i][2] = idx[i + 2];
        rfirst[i] = idx[i];
        rlast[i] = idx[i + 2];
    }
    check_provoking(SR_PRIM_TRIANGLE_STRIP, xy, 7, idx, 7, rtri, rfirst, rlast, 5);
}

/* Fan triangle i is (v_0, v_i+1, v_i+2): first -> v_i+1 (not the hub),
 * last -> v_i+2. */
SR_TEST(flat_shading_uses_the_provoking_vertex_of_fans)
{
    float xy[7][2] = { { 0.05f, -0.05f } };
    for (int k = 1; k < 7; k++) {
        double a = (k - 1) * 50.0 * M_PI / 180.0 + 0.2;
        xy[k][0] = (float)(0.9 * cos(a));
        xy[k][1] = (float)(0.9 * sin(a));
    }
    int tri[5][3], first[5], last[5];
    for (int i = 0; i < 5; i++) {
        tri[i][0] = 0;
        tri[i][1] = i + 1;
        tri[i][2] = i + 2;
        first[i] = i + 1;
        last[i] = i + 2;
    }
    check_provoking(SR_PRIM_TRIANGLE_FAN, (const float (*)[2])xy, 7, NULL, 0, tri, first, last, 5);
}

/* A flat triangle cut by the near plane becomes a fan of several; every
 * pixel keeps the provoking vertex's color. */
SR_TEST(flat_color_survives_clipping)
{
    /* v2 is in front of the near plane (clip z < -w). */
    const float pos[12] = { -0.9f, -0.9f, 0, 1, 0.9f, -0.9f, 0, 1, 0, 0.9f, -3, 1 };
    float col[12];
    for (int k = 0; k < 3; k++) {
        vertex_color(k, col + k * 4);
    }
    for (int mode = 0; mode < 2; mode++) {
        fbuf f = fbuf_make(FW, FH);
        sr_state st = flat_state(mode ? SR_PROVOKING_LAST : SR_PROVOKING_FIRST);
        REQUIRE(sr_draw(f.ctx, f.fb, &st, &(sr_draw_desc){ .positions = pos, .position_size = 4,
                                                          .vertex_count = 3, .colors = col }) == SR_OK);
        CHECK_EQ(sr_last_draw_info(f.ctx).triangles_clipped, 1);
        CHECK(sr_last_draw_info(f.ctx).triangles_drawn >= 2);
        float want[4];
        vertex_color(mode ? 2 : 0, want);
        const uint8_t *px = sr_framebuffer_pixels(f.fb);
        int drawn = 0, bad = 0;
        for (int i = 0; i < FW * FH; i++) {
            if (px[i * 4 + 3] != 0) {
                drawn++;
                bad += !pixel_is(px + i * 4, want);
            }
        }
        CHECK(drawn > 500);
        CHECK_EQ(bad, 0);
        fbuf_free(&f);
    }
}

/* ---- Gouraud vs Phong ---------------------------------------------------- */

/* A quad at z = -2 filling the view (90 degree frustum), normals +z, a
 * point light just in front of its centre and a sharp highlight there.
 * `n` x `n` cells. */
static int highlight_max(sr_shading shading, int n, int *max_x, int *max_y, uint8_t *centre)
{
    fbuf f = fbuf_make(FW, FH);
    int nv = (n + 1) * (n + 1);
    float *pos = malloc(sizeof(float) * 3 * (size_t)nv), *nrm = malloc(sizeof(float) * 3 * (size_t)nv);
    uint32_t *idx = malloc(sizeof(uint32_t) * 6 * (size_t)n * n);
    for (int j = 0; j <= n; j++) {
        for (int i = 0; i <= n; i++) {
            int k = j * (n + 1) + i;
            pos[k * 3] = -2.0f + 4.0f * i / n;
            pos[k * 3 + 1] = -2.0f + 4.0f * j / n;
            pos[k * 3 + 2] = -2.0f;
            nrm[k * 3] = 0;
            nrm[k * 3 + 1] = 0;
            nrm[k * 3 + 2] = 1;
        }
    }
    int m = 0;
    for (int j = 0; j < n; j++) {
        for (int i = 0; i < n; i++) {
            uint32_t a = (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)n + 1, d = c + 1;
            const uint32_t q[6] = { a, b, d, a, d, c };
            memcpy(idx + m, q, sizeof q);
            m += 6;
        }
    }
    sr_mat4 proj = sr_frustum(-1, 1, -1, 1, 1, 10, false);
    sr_state st = { .shading = shading,
                    .material = { .diffuse = { 0.2f, 0.2f, 0.2f }, .specular = { 1, 1, 1 }, .shininess = 50 },
                    .lights = { { .type = SR_LIGHT_POINT, .vector = { 0, 0, -1 } } } };
    sr_result r = sr_draw(f.ctx, f.fb, &st, &(sr_draw_desc){ .positions = pos, .normals = nrm,
                                                            .vertex_count = (size_t)nv, .indices = idx,
                                                            .index_type = SR_INDEX_U32, .index_count = (size_t)m,
                                                            .projection = &proj });
    CHECK_EQ(r, SR_OK);
    const uint8_t *px = sr_framebuffer_pixels(f.fb);
    int best = -1;
    for (int y = 0; y < FH; y++) {
        for (int x = 0; x < FW; x++) {
            int v = px[(y * FW + x) * 4];
            if (v > best) {
                best = v;
                *max_x = x;
                *max_y = y;
            }
        }
    }
    memcpy(centre, px + ((FH / 2) * FW + FW / 2) * 4, 4);
    free(pos);
    free(nrm);
    free(idx);
    fbuf_free(&f);
    return best;
}

SR_TEST(phong_shows_an_interior_highlight_that_gouraud_misses)
{
    int px, py, gx, gy;
    uint8_t pc[4], gc[4];
    int phong = highlight_max(SR_SHADING_PHONG, 1, &px, &py, pc);
    int gouraud = highlight_max(SR_SHADING_GOURAUD, 1, &gx, &gy, gc);
    /* Phong: the highlight saturates near the centre. */
    CHECK(phong >= 250);
    CHECK(abs(px - FW / 2) <= 3 && abs(py - FH / 2) <= 3);
    CHECK(pc[0] >= 250);
    /* Gouraud with only the 4 corner vertices: lit at the corners only by
     * the dim diffuse term, so nothing bright anywhere. */
    CHECK(gouraud < 40);
    CHECK(gc[0] < 40);
    CHECK(pc[0] - gc[0] > 200);
    /* It is a sampling problem: Gouraud on a fine grid finds it again. */
    int fine = highlight_max(SR_SHADING_GOURAUD, 16, &gx, &gy, gc);
    CHECK(fine > 200);
    CHECK(abs(gx - FW / 2) <= 4 && abs(gy - FH / 2) <= 4);
}
