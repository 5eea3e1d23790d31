/* test_clip.c - clipping in homogeneous clip space: near/far planes under a
 * perspective camera against an analytic ray-cast reference, nothing from
 * behind the eye, the guard band with huge triangles, attributes at clip
 * points (through the internal sr__clip_polygon), watertight shared edges
 * after clipping, NaN/Inf positions and w <= 0 vertices.  Fixed seeds. */
#include "sr_test.h"
#include "softrast.h"
#include "pipeline.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- a small scene: color-only framebuffer, one thread ---------------- */

typedef struct scene {
    sr_context *ctx;
    sr_framebuffer *fb;
    int w, h;
    sr_viewport vp;
    sr_rasterizer rast;
} scene;

static scene scene_make(int w, int h)
{
    scene s = { NULL, NULL, w, h, { 0, 0, 0, 0 }, SR_RASTER_DEFAULT };
    sr_make_context(&(sr_context_desc){ .threads = 1 }, &s.ctx);
    sr_make_framebuffer(s.ctx, &(sr_framebuffer_desc){ .width = w, .height = h,
                                                      .depth_format = SR_DEPTH_NONE }, &s.fb);
    return s;
}

static void scene_free(scene *s)
{
    sr_destroy_framebuffer(s->ctx, s->fb);
    sr_destroy_context(s->ctx);
}

static void scene_clear(scene *s)
{
    sr_clear(s->ctx, s->fb, &(sr_clear_desc){ .color = { 0, 0, 0, 0 } });
}

/* Draw triangles (position_size 3 or 4) with white UNLIT color. */
static sr_result scene_draw(scene *s, const float *pos, int size, int ntri, const sr_mat4 *proj)
{
    sr_state st = { .viewport = s->vp, .rasterizer = s->rast,
                    .material = { .diffuse = { 1, 1, 1 } } };
    return sr_draw(s->ctx, s->fb, &st,
                   &(sr_draw_desc){ .positions = pos, .position_size = size,
                                    .vertex_count = (size_t)ntri * 3, .projection = proj });
}

static void scene_mask(const scene *s, uint8_t *mask)
{
    const uint8_t *px = sr_framebuffer_pixels(s->fb);
    for (int i = 0; i < s->w * s->h; i++) {
        mask[i] = px[i * 4] != 0;
    }
}

static int count_set(const uint8_t *m, int n)
{
    int c = 0;
    for (int i = 0; i < n; i++) {
        c += m[i] != 0;
    }
    return c;
}

/* ---- analytic reference: ray casting through pixel sample points ------ */

/* A symmetric frustum with half-extent k*n at the near plane. */
typedef struct camera { double k, n, f; } camera;

static sr_mat4 camera_proj(camera c)
{
    return sr_frustum((float)(-c.k * c.n), (float)(c.k * c.n), (float)(-c.k * c.n),
                      (float)(c.k * c.n), (float)c.n, (float)c.f, false);
}

/* Does the ray through window point (x, y) (pixels, y down) hit triangle
 * (eye space) at a distance in [n, f]? */
static bool ray_hits(camera c, int w, int h, double x, double y, const float tri[9])
{
    double xn = x / (w * 0.5) - 1.0, yn = 1.0 - y / (h * 0.5);
    double d[3] = { xn * c.k, yn * c.k, -1.0 };  /* point at eye depth 1 */
    double p0[3] = { tri[0], tri[1], tri[2] };
    double e1[3] = { tri[3] - p0[0], tri[4] - p0[1], tri[5] - p0[2] };
    double e2[3] = { tri[6] - p0[0], tri[7] - p0[1], tri[8] - p0[2] };
    /* Moeller-Trumbore with the ray origin at the eye. */
    double pv[3] = { d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2], d[0] * e2[1] - d[1] * e2[0] };
    double det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
    if (fabs(det) < 1e-300) {
        return false;
    }
    double tv[3] = { -p0[0], -p0[1], -p0[2] };
    double u = (tv[0] * pv[0] + tv[1] * pv[1] + tv[2] * pv[2]) / det;
    double qv[3] = { tv[1] * e1[2] - tv[2] * e1[1], tv[2] * e1[0] - tv[0] * e1[2], tv[0] * e1[1] - tv[1] * e1[0] };
    double v = (d[0] * qv[0] + d[1] * qv[1] + d[2] * qv[2]) / det;
    double s = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det; /* eye depth */
    return u >= 0 && v >= 0 && u + v <= 1 && s >= c.n && s <= c.f;
}

/* Reference coverage of a union of eye-space triangles: 1 inside, 0
 * outside, 2 where sample points within 0.05 px of the centre disagree
 * (too close to an edge to call, given snapping to 1/256 px). */
static void ref_cover_union(camera c, int w, int h, const float *tris, int ntri, uint8_t *ref)
{
    static const double off[5][2] = { { 0, 0 }, { 0.05, 0.05 }, { -0.05, 0.05 }, { 0.05, -0.05 }, { -0.05, -0.05 } };
    for (int py = 0; py < h; py++) {
        for (int px = 0; px < w; px++) {
            int inside = 0;
            for (int k = 0; k < 5; k++) {
                bool hit = false;
                for (int t = 0; t < ntri && !hit; t++) {
                    hit = ray_hits(c, w, h, px + 0.5 + off[k][0], py + 0.5 + off[k][1], tris + t * 9);
                }
                inside += hit;
            }
            ref[py * w + px] = inside == 5 ? 1 : inside == 0 ? 0 : 2;
        }
    }
}

/* Compare a mask with a reference; returns mismatches on decided pixels. */
static int compare_ref(const uint8_t *mask, const uint8_t *ref, int n, int *undecided)
{
    int bad = 0, und = 0;
    for (int i = 0; i < n; i++) {
        if (ref[i] == 2) {
            und++;
        } else {
            bad += mask[i] != ref[i];
        }
    }
    if (undecided) {
        *undecided = und;
    }
    return bad;
}

/* ---- near and far planes through the public pipeline ----------------- */

enum { W = 64, H = 64 };

/* A ground triangle on y = -0.5 from behind the eye (z = +2) to z = -60:
 * with n = 1 the near plane cuts it on screen at y_ndc = -0.5, and only
 * the part in front may be drawn; nothing may appear above the horizon
 * (which a divide by a negative w would put there). */
static void check_ground(camera c, const char *what, int min_drawn)
{
    const float tri[9] = { -3, -0.5f, 2, 3, -0.5f, 2, 0, -0.5f, -60 };
    scene s = scene_make(W, H);
    sr_mat4 p = camera_proj(c);
    static uint8_t mask[W * H], ref[W * H];
    for (int r = SR_RASTER_HALFSPACE; r <= SR_RASTER_BARYCENTRIC; r++) {
        s.rast = (sr_rasterizer)r;
        scene_clear(&s);
        REQUIRE(scene_draw(&s, tri, 3, 1, &p) == SR_OK);
        CHECK_EQ(sr_last_draw_info(s.ctx).triangles_clipped, 1);
        scene_mask(&s, mask);
        ref_cover_union(c, W, H, tri, 1, ref);
        int und;
        int bad = compare_ref(mask, ref, W * H, &und);
        if (bad) {
            fprintf(stderr, "%s: %d mismatches\n", what, bad);
        }
        CHECK_EQ(bad, 0);
        CHECK(und < W * H / 20);
        CHECK(count_set(mask, W * H) >= min_drawn);
        /* Above the horizon (rows 0 .. H/2 - 1): nothing. */
        CHECK_EQ(count_set(mask, W * H / 2), 0);
    }
    scene_free(&s);
}

SR_TEST(triangle_crossing_the_near_plane_draws_only_the_part_in_front)
{
    check_ground((camera){ 1.0, 1.0, 1000.0 }, "near", 300);
    /* The near cut is visible: rows below y_ndc = -0.5 are empty. */
    scene s = scene_make(W, H);
    sr_mat4 p = camera_proj((camera){ 1.0, 1.0, 1000.0 });
    const float tri[9] = { -3, -0.5f, 2, 3, -0.5f, 2, 0, -0.5f, -60 };
    scene_clear(&s);
    REQUIRE(scene_draw(&s, tri, 3, 1, &p) == SR_OK);
    uint8_t mask[W * H];
    scene_mask(&s, mask);
    CHECK_EQ(count_set(mask + W * (H * 3 / 4), W * H / 4), 0);
    CHECK(count_set(mask + W * (H * 3 / 4 - 1), W) > 0);
    scene_free(&s);
}

SR_TEST(triangle_crossing_the_far_plane_draws_only_the_part_before_it)
{
    /* Far at 20: the cut is at y_ndc = -0.5/20 = -0.025. */
    check_ground((camera){ 1.0, 0.25, 20.0 }, "far", 100);
    check_ground((camera){ 1.0, 1.0, 20.0 }, "near+far", 100);
    check_ground((camera){ 0.5, 1.0, 10.0 }, "near+far narrow", 100);
}

SR_TEST(triangle_entirely_behind_the_eye_draws_nothing)
{
    scene s = scene_make(W, H);
    sr_mat4 p = camera_proj((camera){ 1.0, 1.0, 100.0 });
    /* Behind (z > 0), including one exactly at the eye and one between
     * the eye and the near plane. */
    const float tris[][9] = {
        { -3, -0.5f, 2, 3, -0.5f, 2, 0, 1, 9 },
        { -1, -1, 0.5f, 1, -1, 0.5f, 0, 1, 0.5f },
        { 0, 0, 0, 1, -1, 3, -1, -1, 3 },
        { -1, -1, -0.5f, 1, -1, -0.5f, 0, 1, -0.5f },
    };
    for (int i = 0; i < 4; i++) {
        scene_clear(&s);
        REQUIRE(scene_draw(&s, tris[i], 3, 1, &p) == SR_OK);
        uint8_t mask[W * H];
        scene_mask(&s, mask);
        CHECK_EQ(count_set(mask, W * H), 0);
        CHECK_EQ(sr_last_draw_info(s.ctx).triangles_drawn, 0);
        CHECK_EQ(sr_last_draw_info(s.ctx).fragments, 0);
    }
    scene_free(&s);
}

/* ---- the guard band: huge triangles ------------------------------------ */

SR_TEST(huge_triangle_covering_the_viewport_fills_every_pixel)
{
    const int sizes[][2] = { { 64, 64 }, { 100, 37 }, { 1, 1 }, { 300, 7 } };
    const double ws[] = { 1.0, 1e-3, 1e3, 0.125 };
    for (int i = 0; i < 4; i++) {
        scene s = scene_make(sizes[i][0], sizes[i][1]);
        for (int k = 0; k < 4; k++) {
            float w = (float)ws[k];
            const float pos[12] = { -1e6f * w, -1e6f * w, 0, w, 1e6f * w, -1e6f * w, 0, w,
                                    0, 1e6f * w, 0, w };
            for (int r = SR_RASTER_HALFSPACE; r <= SR_RASTER_BARYCENTRIC; r++) {
                s.rast = (sr_rasterizer)r;
                scene_clear(&s);
                REQUIRE(scene_draw(&s, pos, 4, 1, NULL) == SR_OK);
                uint8_t *mask = malloc((size_t)s.w * s.h);
                scene_mask(&s, mask);
                CHECK_EQ(count_set(mask, s.w * s.h), s.w * s.h);
                free(mask);
                CHECK_EQ(sr_last_draw_info(s.ctx).triangles_clipped, 1);
            }
        }
        scene_free(&s);
    }
    /* With an offset viewport: exactly the viewport's pixels. */
    scene s = scene_make(64, 64);
    s.vp = (sr_viewport){ 5, 3, 50, 20 };
    const float pos[12] = { -1e6f, -1e6f, 0, 1, 1e6f, -1e6f, 0, 1, 0, 1e6f, 0, 1 };
    scene_clear(&s);
    REQUIRE(scene_draw(&s, pos, 4, 1, NULL) == SR_OK);
    uint8_t mask[64 * 64];
    scene_mask(&s, mask);
    int bad = 0;
    for (int y = 0; y < 64; y++) {
        for (int x = 0; x < 64; x++) {
            bad += mask[y * 64 + x] != (x >= 5 && x < 55 && y >= 3 && y < 23);
        }
    }
    CHECK_EQ(bad, 0);
    scene_free(&s);
}

/* A huge triangle whose long edge crosses the screen: the pixels below the
 * edge's line are covered, exactly as an unclipped triangle would cover
 * them (decided pixels, more than 0.05 px from the line). */
SR_TEST(huge_triangle_edge_across_the_screen_matches_the_unclipped_line)
{
    sr_rng rng = { 0x9a4d };
    scene s = scene_make(W, H);
    uint8_t mask[W * H];
    for (int it = 0; it < 40; it++) {
        double slope = sr_rng_range(&rng, -0.9, 0.9), icpt = sr_rng_range(&rng, -0.5, 0.5);
        float w = (float)(it % 2 ? sr_rng_range(&rng, 0.01, 100) : 1.0);
        float pos[12] = { -1e6f, (float)(-1e6 * slope + icpt), 0, 1,
                          1e6f, (float)(1e6 * slope + icpt), 0, 1,
                          0, -1e6f, 0, 1 };
        if (it % 4 == 3) {          /* reverse the winding */
            float tmp[4];
            memcpy(tmp, pos, sizeof tmp);
            memcpy(pos, pos + 4, sizeof tmp);
            memcpy(pos + 4, tmp, sizeof tmp);
        }
        for (int k = 0; k < 12; k++) {
            pos[k] *= w;
        }
        s.rast = (sr_rasterizer)(SR_RASTER_HALFSPACE + it % 3);
        scene_clear(&s);
        REQUIRE(scene_draw(&s, pos, 4, 1, NULL) == SR_OK);
        scene_mask(&s, mask);
        /* The line through the two float vertices, in NDC. */
        double x1 = (double)pos[0] / pos[3], y1 = (double)pos[1] / pos[3];
        double x2 = (double)pos[4] / pos[7], y2 = (double)pos[5] / pos[7];
        if (x1 > x2) {
            double t = x1; x1 = x2; x2 = t;
            t = y1; y1 = y2; y2 = t;
        }
        int bad = 0, drawn = 0;
        for (int py = 0; py < H; py++) {
            for (int px = 0; px < W; px++) {
                double xn = (px + 0.5) / (W / 2.0) - 1, yn = 1 - (py + 0.5) / (H / 2.0);
                double line_y = y1 + (y2 - y1) * (xn - x1) / (x2 - x1);
                double dist_px = (line_y - yn) * (H / 2.0);   /* vertical distance */
                if (fabs(dist_px) < 0.05) {
                    continue;
                }
                bad += mask[py * W + px] != (dist_px > 0);
                drawn += mask[py * W + px];
            }
        }
        CHECK_EQ(bad, 0);
        CHECK(drawn > 0 || icpt + fabs(slope) < -1);
    }
    scene_free(&s);
}

/* ---- attributes at clip points (internal clipper) ---------------------- */

static sr_draw_state make_ds(int w, int h, int nvary, bool zero_to_one)
{
    sr_draw_state ds;
    memset(&ds, 0, sizeof ds);
    ds.vp_px = w * 0.5;
    ds.vp_py = h * 0.5;
    ds.vp_ox = w * 0.5;
    ds.vp_oy = h * 0.5;
    ds.zero_to_one = zero_to_one;
    ds.vp_zs = zero_to_one ? 1.0 : 0.5;
    ds.vp_zb = zero_to_one ? 0.0 : 0.5;
    ds.depth_max = 1.0;
    ds.rect_x1 = w;
    ds.rect_y1 = h;
    ds.nvary = nvary;
    ds.ninterp = nvary;
    ds.perspective = true;
    ds.shading = SR_SHADING_UNLIT;
    return ds;
}

static sr_clip_vertex cv(float x, float y, float z, float w, float r, float g, float b, float a)
{
    sr_clip_vertex v;
    memset(&v, 0, sizeof v);
    v.pos[0] = x;
    v.pos[1] = y;
    v.pos[2] = z;
    v.pos[3] = w;
    v.vary[0] = r;
    v.vary[1] = g;
    v.vary[2] = b;
    v.vary[3] = a;
    return v;
}

/* Clip with the planes the triangle's outcodes name, as sr_draw does. */
static int clip3(const sr_draw_state *ds, const sr_clip_vertex *a, const sr_clip_vertex *b,
                 const sr_clip_vertex *c, sr_clip_vertex *out)
{
    const sr_clip_vertex *in[3] = { a, b, c };
    unsigned planes = sr__clip_outcode(ds, a->pos) | sr__clip_outcode(ds, b->pos) |
                      sr__clip_outcode(ds, c->pos);
    return sr__clip_polygon(ds, in, planes, out);
}

static bool same_vertex(const sr_clip_vertex *a, const sr_clip_vertex *b, int nvary)
{
    return memcmp(a->pos, b->pos, sizeof a->pos) == 0 &&
           memcmp(a->vary, b->vary, (size_t)nvary * sizeof(float)) == 0;
}

SR_TEST(clip_point_colors_are_the_lerp_at_the_clip_parameter)
{
    sr_rng rng = { 0xc011 };
    for (int z01 = 0; z01 <= 1; z01++) {
        sr_draw_state ds = make_ds(W, H, 4, z01);
        for (int it = 0; it < 2000; it++) {
            /* Edge a -> b crosses the near plane: a in front, b behind. */
            float wa = (float)sr_rng_range(&rng, 0.5, 4), wb = (float)sr_rng_range(&rng, 0.5, 4);
            float za = (float)(wa * sr_rng_range(&rng, z01 ? 0.1 : -0.9, 0.9));
            float zb = (float)(-wb * sr_rng_range(&rng, z01 ? 0.1 : 1.1, 3));
            sr_clip_vertex a = cv((float)sr_rng_range(&rng, -0.5, 0.5) * wa, (float)sr_rng_range(&rng, -0.5, 0.5) * wa,
                                  za, wa, (float)sr_rng_unit(&rng), (float)sr_rng_unit(&rng),
                                  (float)sr_rng_unit(&rng), 1);
            sr_clip_vertex b = cv((float)sr_rng_range(&rng, -0.5, 0.5) * wb, (float)sr_rng_range(&rng, -0.5, 0.5) * wb,
                                  zb, wb, (float)sr_rng_unit(&rng), (float)sr_rng_unit(&rng),
                                  (float)sr_rng_unit(&rng), 0);
            /* A third vertex in front, so a quad survives. */
            sr_clip_vertex c = cv(0.3f * wa, -0.4f * wa, za, wa, 0.5f, 0.5f, 0.5f, 0.5f);
            double da = z01 ? a.pos[2] : (double)a.pos[2] + a.pos[3];
            double db = z01 ? b.pos[2] : (double)b.pos[2] + b.pos[3];
            REQUIRE(da > 0 && db < 0);
            double t = da / (da - db);

            sr_clip_vertex out[SR_CLIP_MAX_VERTS];
            int n = clip3(&ds, &a, &b, &c, out);
            REQUIRE(n == 4);
            /* The new vertex on edge a-b follows a in the output order. */
            int found = 0;
            for (int i = 0; i < n; i++) {
                if (same_vertex(&out[i], &a, 4) || same_vertex(&out[i], &c, 4)) {
                    continue;
                }
                found++;
                double d = z01 ? out[i].pos[2] : (double)out[i].pos[2] + out[i].pos[3];
                CHECK_NEAR(d, 0, 1e-6 * (fabs(za) + wa + fabs(zb) + wb));
                if (fabs(out[i].pos[0] - (a.pos[0] + t * (b.pos[0] - a.pos[0]))) < 1e-5 &&
                    fabs(out[i].pos[3] - (a.pos[3] + t * (b.pos[3] - a.pos[3]))) < 1e-5) {
                    for (int k = 0; k < 4; k++) {
                        CHECK_NEAR(out[i].vary[k], a.vary[k] + t * (b.vary[k] - a.vary[k]), 1e-6);
                    }
                    for (int k = 0; k < 4; k++) {
                        CHECK_NEAR(out[i].pos[k], a.pos[k] + t * (b.pos[k] - a.pos[k]), 1e-6 * 4);
                    }
                    found += 100;
                }
            }
            CHECK_EQ(found, 102); /* two new vertices, one of them on a-b */
        }
    }
}

/* The intersection is computed from the inside vertex, so the same edge
 * clipped as part of two different triangles, in either direction, gives
 * bit-identical points. */
SR_TEST(clip_points_are_independent_of_edge_direction_and_triangle)
{
    sr_rng rng = { 0xd17 };
    sr_draw_state ds = make_ds(W, H, 4, false);
    int checked = 0;
    for (int it = 0; it < 2000; it++) {
        sr_clip_vertex a = cv((float)sr_rng_range(&rng, -3, 3), (float)sr_rng_range(&rng, -3, 3),
                              (float)sr_rng_range(&rng, -1, 1), (float)sr_rng_range(&rng, 1, 2),
                              (float)sr_rng_unit(&rng), 0, 0, 1);
        /* b behind the near plane and far outside the guard band. */
        sr_clip_vertex b = cv((float)sr_rng_range(&rng, -1e5, 1e5), (float)sr_rng_range(&rng, -1e5, 1e5),
                              (float)sr_rng_range(&rng, -5, -2), (float)sr_rng_range(&rng, -1, 1),
                              (float)sr_rng_unit(&rng), 1, 0, 1);
        sr_clip_vertex c = cv((float)sr_rng_range(&rng, -1, 1), (float)sr_rng_range(&rng, -1, 1), 0, 1, 0, 0, 1, 1);
        sr_clip_vertex d = cv((float)sr_rng_range(&rng, -1, 1), (float)sr_rng_range(&rng, -1, 1), 0.5f, 1, 0, 1, 1, 1);
        sr_clip_vertex o1[SR_CLIP_MAX_VERTS], o2[SR_CLIP_MAX_VERTS];
        /* Triangle (a, b, c) and triangle (b, a, d): edge a-b reversed. */
        int n1 = clip3(&ds, &a, &b, &c, o1);
        int n2 = clip3(&ds, &b, &a, &d, o2);
        if (n1 < 3 || n2 < 3) {
            continue;
        }
        /* Every vertex of the first polygon that lies on segment a-b (the
         * new ones) also appears, bit for bit, in the second polygon when
         * both clip with the same planes. */
        unsigned p1 = sr__clip_outcode(&ds, a.pos) | sr__clip_outcode(&ds, b.pos) | sr__clip_outcode(&ds, c.pos);
        unsigned p2 = sr__clip_outcode(&ds, a.pos) | sr__clip_outcode(&ds, b.pos) | sr__clip_outcode(&ds, d.pos);
        if (p1 != p2) {
            continue;
        }
        for (int i = 0; i < n1; i++) {
            /* On a-b: collinear in the xy-w projection is hard to test
             * exactly, so use the red varying, which is 0 at c and d. */
            if (o1[i].vary[2] != 0.0f || same_vertex(&o1[i], &a, 4)) {
                continue;
            }
            bool found = false;
            for (int j = 0; j < n2 && !found; j++) {
                found = same_vertex(&o1[i], &o2[j], 4);
            }
            CHECK(found);
            checked++;
        }
    }
    CHECK(checked > 500);
}

/* ---- watertight shared edges after clipping ---------------------------- */

/* Draw each triangle alone into a cleared framebuffer and sum the masks. */
static void count_cover(scene *s, const float *tris, int ntri, const sr_mat4 *proj, int *count)
{
    uint8_t *m = malloc((size_t)s->w * s->h);
    memset(count, 0, sizeof(int) * (size_t)s->w * s->h);
    for (int t = 0; t < ntri; t++) {
        scene_clear(s);
        scene_draw(s, tris + t * 9, 3, 1, proj);
        scene_mask(s, m);
        for (int i = 0; i < s->w * s->h; i++) {
            count[i] += m[i];
        }
    }
    free(m);
}

static void check_watertight(scene *s, camera c, const float *tris, int ntri, int min_inside)
{
    sr_mat4 p = camera_proj(c);
    int *count = malloc(sizeof(int) * (size_t)s->w * s->h);
    uint8_t *ref = malloc((size_t)s->w * s->h);
    count_cover(s, tris, ntri, &p, count);
    ref_cover_union(c, s->w, s->h, tris, ntri, ref);
    int twice = 0, holes = 0, outside = 0, inside = 0;
    for (int i = 0; i < s->w * s->h; i++) {
        twice += count[i] > 1;
        if (ref[i] == 1) {
            inside++;
            holes += count[i] != 1;
        } else if (ref[i] == 0) {
            outside += count[i] != 0;
        }
    }
    CHECK_EQ(twice, 0);
    CHECK_EQ(holes, 0);
    CHECK_EQ(outside, 0);
    CHECK(inside >= min_inside);
    free(count);
    free(ref);
}

/* A ground quad from behind the eye to z = -30 and +-2000 wide (far past
 * the guard band at the near plane), split along either diagonal. */
SR_TEST(clipped_quad_shares_its_diagonal_exactly_once)
{
    scene s = scene_make(W, H);
    camera c = { 1.0, 1.0, 100.0 };
    const float q[4][3] = { { -2000, -0.5f, 3 }, { 2000, -0.5f, 3 }, { 2000, -0.5f, -30 }, { -2000, -0.5f, -30 } };
    for (int diag = 0; diag < 2; diag++) {
        int i0 = diag, i1 = diag + 1, i2 = diag + 2, i3 = (diag + 3) % 4;
        float tris[18];
        memcpy(tris + 0, q[i0], 12);
        memcpy(tris + 3, q[i1], 12);
        memcpy(tris + 6, q[i2], 12);
        memcpy(tris + 9, q[i0], 12);
        memcpy(tris + 12, q[i2], 12);
        memcpy(tris + 15, q[i3], 12);
        for (int r = SR_RASTER_HALFSPACE; r <= SR_RASTER_BARYCENTRIC; r++) {
            s.rast = (sr_rasterizer)r;
            check_watertight(&s, c, tris, 2, 800);
        }
    }
    /* A tilted quad so the diagonal is steep on screen. */
    const float t[4][3] = { { -1, -3, 2 }, { 0.5f, -3, -40 }, { 0.3f, 5, -40 }, { -1, 5, 2 } };
    float tris[18];
    memcpy(tris + 0, t[0], 12);
    memcpy(tris + 3, t[1], 12);
    memcpy(tris + 6, t[2], 12);
    memcpy(tris + 9, t[0], 12);
    memcpy(tris + 12, t[2], 12);
    memcpy(tris + 15, t[3], 12);
    s.rast = SR_RASTER_HALFSPACE;
    check_watertight(&s, c, tris, 2, 200);
    scene_free(&s);
}

/* A grid mesh on the ground, unevenly spaced, reaching behind the eye and
 * thousands of units to the sides: every pixel of the ground once. */
SR_TEST(clipped_grid_mesh_is_watertight)
{
    const float xs[] = { -3000, -20, -6, -2.25f, 0.3f, 2.5f, 7, 25.5f, 3000 };
    const float zs[] = { 4, 0.5f, -1.5f, -3, -6.1f, -11, -19, -40 };
    enum { NX = 9, NZ = 8 };
    const float heights[] = { -0.5f, -2.0f };
    scene s = scene_make(W, H);
    for (int hi = 0; hi < 2; hi++) {
        float *tris = malloc(sizeof(float) * 18 * (NX - 1) * (NZ - 1));
        int n = 0;
        for (int j = 0; j + 1 < NZ; j++) {
            for (int i = 0; i + 1 < NX; i++) {
                float p00[3] = { xs[i], heights[hi], zs[j] }, p10[3] = { xs[i + 1], heights[hi], zs[j] };
                float p01[3] = { xs[i], heights[hi], zs[j + 1] }, p11[3] = { xs[i + 1], heights[hi], zs[j + 1] };
                const float *order[6];
                if ((i + j) % 2) {
                    const float *o[6] = { p00, p10, p11, p00, p11, p01 };
                    memcpy(order, o, sizeof o);
                } else {
                    const float *o[6] = { p00, p10, p01, p10, p11, p01 };
                    memcpy(order, o, sizeof o);
                }
                for (int k = 0; k < 6; k++) {
                    memcpy(tris + n * 9 + k * 3, order[k], 12);
                }
                n += 2;
            }
        }
        check_watertight(&s, (camera){ 1.0, 1.0, 100.0 }, tris, n, 1000);
        /* A wider field of view and a far plane inside the mesh. */
        check_watertight(&s, (camera){ 2.0, 0.5, 15.0 }, tris, n, 500);
        free(tris);
    }
    scene_free(&s);
}

/* ---- NaN, Inf, w = 0 and w < 0 ----------------------------------------- */

SR_TEST(nan_and_inf_positions_discard_only_their_triangle)
{
    const float good[2][12] = {
        { -0.9f, -0.9f, 0, 1, 0.5f, -0.9f, 0, 1, -0.9f, 0.5f, 0, 1 },
        { 0.9f, 0.9f, 0, 1, -0.2f, 0.9f, 0, 1, 0.9f, -0.2f, 0, 1 },
    };
    const float bad_vals[] = { NAN, INFINITY, -INFINITY };
    scene s = scene_make(W, H);
    static uint8_t want[W * H * 4];
    scene_clear(&s);
    REQUIRE(scene_draw(&s, &good[0][0], 4, 2, NULL) == SR_OK);
    memcpy(want, sr_framebuffer_pixels(s.fb), sizeof want);
    REQUIRE(count_set(want, W * H * 4) > 0);
    for (int v = 0; v < 3; v++) {
        for (int comp = 0; comp < 4; comp++) {
            /* Bad, good, bad (a big triangle that would cover everything), good. */
            float pos[4][12];
            const float big[12] = { -5, -5, 0, 1, 5, -5, 0, 1, 0, 5, 0, 1 };
            memcpy(pos[0], big, sizeof big);
            memcpy(pos[1], good[0], sizeof big);
            memcpy(pos[2], big, sizeof big);
            memcpy(pos[3], good[1], sizeof big);
            pos[0][comp] = bad_vals[v];
            pos[2][8 + comp] = bad_vals[v];
            scene_clear(&s);
            REQUIRE(scene_draw(&s, &pos[0][0], 4, 4, NULL) == SR_OK);
            CHECK(memcmp(sr_framebuffer_pixels(s.fb), want, sizeof want) == 0);
            sr_draw_info info = sr_last_draw_info(s.ctx);
            CHECK_EQ(info.triangles_in, 4);
            CHECK_EQ(info.triangles_drawn, 2);
        }
    }
    scene_free(&s);
}

/* Clip-space triangles with w = 0 and w < 0 vertices, drawn with identity
 * matrices, against their analytic footprints in NDC (projective
 * geometry: only the part with w > 0 is visible). */
typedef bool (*ndc_region)(double x, double y);

/* v2 = (0, 1, 0, 0) is the point at infinity up the y axis: the triangle
 * is the half-strip |x| <= 0.5, y >= -0.5. */
static bool strip_region(double x, double y) { return fabs(x) < 0.5 && y > -0.5; }
/* v2 = (0, -1, 0, -1) = -(0, 1, 0, 1): only the "external" part is in
 * front: below y = -0.5 and below the lines through (0, 1) and v0, v1. */
static bool external_region(double x, double y) { return y < -0.5 && y < 1 - 3 * fabs(x); }

static void check_region(scene *s, const float pos[12], ndc_region inside, int min_drawn)
{
    uint8_t *mask = malloc((size_t)s->w * s->h);
    for (int r = SR_RASTER_HALFSPACE; r <= SR_RASTER_BARYCENTRIC; r++) {
        s->rast = (sr_rasterizer)r;
        scene_clear(s);
        REQUIRE(scene_draw(s, pos, 4, 1, NULL) == SR_OK);
        scene_mask(s, mask);
        int bad = 0, undecided = 0;
        for (int py = 0; py < s->h; py++) {
            for (int px = 0; px < s->w; px++) {
                static const double off[5][2] = { { 0, 0 }, { 0.05, 0.05 }, { -0.05, 0.05 },
                                                  { 0.05, -0.05 }, { -0.05, -0.05 } };
                int votes = 0;
                for (int k = 0; k < 5; k++) {
                    double xn = (px + 0.5 + off[k][0]) / (s->w * 0.5) - 1;
                    double yn = 1 - (py + 0.5 + off[k][1]) / (s->h * 0.5);
                    votes += inside(xn, yn);
                }
                if (votes != 0 && votes != 5) {
                    undecided++;
                    continue;
                }
                bad += mask[py * s->w + px] != (votes == 5);
            }
        }
        CHECK_EQ(bad, 0);
        CHECK(undecided < s->w * s->h / 10);
        CHECK(count_set(mask, s->w * s->h) >= min_drawn);
    }
    free(mask);
}

SR_TEST(w_zero_vertex_is_a_point_at_infinity)
{
    scene s = scene_make(W, H);
    const float strip[12] = { -0.5f, -0.5f, 0, 1, 0.5f, -0.5f, 0, 1, 0, 1, 0, 0 };
    check_region(&s, strip, strip_region, 900);
    /* Scaling a vertex by a positive factor changes nothing. */
    const float strip2[12] = { -1, -1, 0, 2, 0.125f, -0.125f, 0, 0.25f, 0, 7, 0, 0 };
    check_region(&s, strip2, strip_region, 900);
    scene_free(&s);
}

SR_TEST(w_negative_vertex_draws_the_external_part)
{
    scene s = scene_make(W, H);
    const float ext[12] = { -0.5f, -0.5f, 0, 1, 0.5f, -0.5f, 0, 1, 0, -1, 0, -1 };
    check_region(&s, ext, external_region, 200);
    /* All three w < 0 (each vertex the negation of an on-screen one): the
     * clip volume needs w > 0, so nothing is drawn. */
    const float neg[12] = { 0.5f, 0.5f, 0, -1, -0.5f, 0.5f, 0, -1, 0, -1, 0, -1 };
    uint8_t mask[W * H];
    scene_clear(&s);
    REQUIRE(scene_draw(&s, neg, 4, 1, NULL) == SR_OK);
    scene_mask(&s, mask);
    CHECK_EQ(count_set(mask, W * H), 0);
    scene_free(&s);
}

/* Degenerate homogeneous input: a vertex at the clip-space origin
 * (0, 0, 0, 0), and an edge through it (v and -v).  The divide must never
 * see w = 0 (0/0 = NaN would reach the fixed-point snap and overflow int32
 * edge math - UBSan catches it): the projection of these triangles has no
 * area, so nothing is drawn. */
SR_TEST(clip_space_origin_vertex_draws_nothing)
{
    scene s = scene_make(W, H);
    const float cases[][12] = {
        { -0.5f, -0.5f, 0, 1, 0.5f, -0.5f, 0, 1, 0, 0, 0, 0 },
        { 0, 0, 0, 1, 0, 0, 0, -1, 0.5f, 0.5f, 0, 1 },
        { 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 },
        { 0.25f, 0.25f, 0, 1, -0.25f, -0.25f, 0, -1, 0.5f, -0.5f, 0, 1 },
    };
    uint8_t mask[W * H];
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        scene_clear(&s);
        REQUIRE(scene_draw(&s, cases[i], 4, 1, NULL) == SR_OK);
        scene_mask(&s, mask);
        CHECK_EQ(count_set(mask, W * H), 0);
        CHECK_EQ(sr_last_draw_info(s.ctx).triangles_drawn, 0);
    }
    scene_free(&s);
}
