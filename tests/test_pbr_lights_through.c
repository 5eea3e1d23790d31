/* test_pbr_lights_through.c - punctual lights seen through transmissive
 * glTF materials (sr_make_pbr_program): the glass BTDF's exit path for
 * point and spot lights, a lamp split by a dispersive volume, and a
 * leaf's backlight under the key light's shadow map.  Each expectation
 * is worked out here in double from the extensions' formulas. */
#include "image_compare.h"
#include "sr_test.h"

#include "softrast.h"
#include "softrast_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 128
#define H 128
#define PI_D 3.14159265358979

/* The camera: at (0, 0, 5) looking down -z, 40 degrees vertically. */
static const double eye[3] = { 0, 0, 5 };
static const double fovy = 40.0 * PI_D / 180.0;

/* A square slab of side 8 through the origin, facing +z turned by `tilt`
 * about y: its front face is what the program draws. */
typedef struct slab {
    double tilt;
    double n[3];
} slab;

static slab make_slab(double tilt)
{
    return (slab){ .tilt = tilt, .n = { sin(tilt), 0.0, cos(tilt) } };
}

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void unit(double a[3])
{
    double l = sqrt(dot(a, a));
    for (int k = 0; k < 3; k++) {
        a[k] /= l;
    }
}

static double srgb_encode(double l)
{
    l = l < 0 ? 0 : l > 1 ? 1 : l;
    return 255.0 * (l <= 0.0031308 ? 12.92 * l : 1.055 * pow(l, 1 / 2.4) - 0.055);
}

static double srgb_decode(int code)
{
    double c = code / 255.0;
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

/* The point of the slab seen through the centre of pixel (x, y) (x may
 * be fractional), and the unit way from it to the eye. */
static void hit(const slab *s, double x, double y, double p[3], double v[3])
{
    double t = tan(fovy / 2);
    double d[3] = { ((x + 0.5) / W * 2.0 - 1.0) * t, (1.0 - (y + 0.5) / H * 2.0) * t, -1.0 };
    double k = -dot(eye, s->n) / dot(d, s->n);
    for (int i = 0; i < 3; i++) {
        p[i] = eye[i] + k * d[i];
        v[i] = -d[i];
    }
    unit(v);
}

/* GLSL's refract(-v, n, 1 / ior), unit. */
static void refract_in(const double v[3], const double n[3], double ior, double t[3])
{
    double eta = 1.0 / ior, ni = -dot(n, v), k = 1.0 - eta * eta * (1.0 - ni * ni);
    for (int i = 0; i < 3; i++) {
        t[i] = -eta * v[i] - (eta * ni + sqrt(k)) * n[i];
    }
    unit(t);
}

/* The screen x of a world point. */
static double screen_x(const double p[3])
{
    double z = eye[2] - p[2];
    return ((p[0] / z) / tan(fovy / 2) + 1.0) * 0.5 * W - 0.5;
}

/* The sample viewer's getPunctualRadianceTransmission without the base
 * color: the light l (unit, to the light) mirrored through the surface,
 * GGX D and the height-correlated visibility at alpha = roughness^2
 * (ior 1.5 keeps it), times 1 - F(V.H) with F0 0.04. */
static double btdf(const double n[3], const double v[3], const double l[3], double rough)
{
    double nl = dot(n, l), lm[3], h[3];
    for (int k = 0; k < 3; k++) {
        lm[k] = l[k] - 2.0 * nl * n[k];
        h[k] = lm[k] + v[k];
    }
    unit(h);
    double nh = dot(n, h), vh = dot(v, h), nlm = dot(n, lm), nv = dot(n, v);
    double a = rough * rough, a2 = a * a, dd = nh * nh * (a2 - 1.0) + 1.0;
    double d = a2 / (PI_D * dd * dd);
    double vis = 0.5 / (nlm * sqrt(nv * nv * (1.0 - a2) + a2) + nv * sqrt(nlm * nlm * (1.0 - a2) + a2));
    double f = 0.04 + 0.96 * pow(1.0 - vh, 5.0);
    return nl < 0.0 ? (1.0 - f) * d * vis : 0.0;
}

/* Draws the slab under desc d (its material, lights, source) into a
 * fresh black W x H framebuffer. */
static sr_framebuffer *draw_slab(const slab *s, sr_pbr_desc d)
{
    float pos[12] = { -4, -4, 0, 4, -4, 0, 4, 4, 0, -4, 4, 0 };
    float nrm[12] = { 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1 };
    float uv[8] = { 0, 0, 1, 0, 1, 1, 0, 1 };
    uint32_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    sr_mat4 model = sr_mat4_rotate((float)s->tilt, (sr_vec3){ 0, 1, 0 });
    sr_mat4 view = sr_look_at((sr_vec3){ 0, 0, 5 }, (sr_vec3){ 0, 0, 0 }, (sr_vec3){ 0, 1, 0 });
    sr_mat4 proj = sr_perspective((float)fovy, 1.0f, 0.5f, 20.0f, false);
    d.model = &model;
    d.view = &view;
    d.projection = &proj;
    d.tonemap = SR_TONEMAP_NONE;
    sr_context *ctx = sr_test_ctx();
    sr_framebuffer *fb = NULL;
    sr_pbr *p = NULL;
    if (sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &fb) != SR_OK) {
        return NULL;
    }
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    sr_result r = sr_make_pbr_program(ctx, &d, &p);
    if (r == SR_OK) {
        r = sr_draw(ctx, fb, &(sr_state){ .program = sr_pbr_program(p), .cull = SR_CULL_NONE },
                    &(sr_draw_desc){ .positions = pos, .normals = nrm, .texcoords = uv,
                                     .vertex_count = 4, .indices = idx,
                                     .index_type = SR_INDEX_U32, .index_count = 6 });
        sr_destroy_pbr_program(ctx, p);
    }
    if (r != SR_OK) {
        sr_destroy_framebuffer(ctx, fb);
        return NULL;
    }
    return fb;
}

static const uint8_t *px(const sr_framebuffer *fb, int x, int y)
{
    return sr_framebuffer_pixels(fb) + 4 * ((size_t)y * W + (size_t)x);
}

static void save(const sr_framebuffer *fb, const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s.png", sr_test_out_dir(), name);
    sr_io_error err;
    if (sr_write_png(path, W, H, sr_framebuffer_pixels(fb), 4 * W, NULL, &err) != SR_OK) {
        fprintf(stderr, "%s\n", err.message);
    }
}

/* Clear glass: white, a dielectric that lets everything through. */
static sr_pbr_material glass(float rough)
{
    sr_pbr_material m = sr_pbr_default_material();
    m.metallic = 0.0f;
    m.roughness = rough;
    m.transmission = 1.0f;
    return m;
}

/* ---- the glass BTDF's exit path for point and spot lights --------------- */

/* A point (or spot) light behind a transmissive slab, as the sample
 * viewer lights it (getPunctualRadianceTransmission after
 * getVolumeTransmissionRay): seen from where the refracted view ray
 * leaves a volume of thickness th (from the surface itself when thin),
 * its direction, inverse square and cone taken there, and the
 * transmittance attenuation^(way / distance) along that ray. */
typedef struct lamp {
    double at[3], intensity;
    const double *axis;          /* a spot's (unit), or NULL */
    double cos_inner, cos_outer;
} lamp;

static double lamp_through(const slab *s, const lamp *lp, double x, double y, double rough,
                           double th, double att, double dist)
{
    double p[3], v[3], t[3], e[3], l[3];
    hit(s, x, y, p, v);
    refract_in(v, s->n, 1.5, t);
    for (int k = 0; k < 3; k++) {
        e[k] = p[k] + t[k] * th;
        l[k] = lp->at[k] - e[k];
    }
    double d2 = dot(l, l);
    unit(l);
    double rad = lp->intensity / d2;
    if (lp->axis) {
        double c = -dot(l, lp->axis);
        double k = (c - lp->cos_outer) / (lp->cos_inner - lp->cos_outer);
        k = k < 0 ? 0 : k > 1 ? 1 : k;
        rad *= k * k;
    }
    double keep = dist > 0.0 ? pow(att, th / dist) : 1.0;
    return btdf(s->n, v, l, rough) * rad * keep;
}

/* The brightest pixel of row y by green. */
static int peak_x(const sr_framebuffer *fb, int y)
{
    int best = 0;
    for (int x = 1; x < W; x++) {
        best = px(fb, x, y)[1] > px(fb, best, y)[1] ? x : best;
    }
    return best;
}

/* A point light behind a slab turned 35 degrees shines through it: thin,
 * and as a volume 0.6 thick absorbing half over 0.3.  Every pixel of
 * the middle row and of a column through the highlight is within 2 codes
 * of the viewer's formula worked out here, and the highlight's peak lies
 * where the formula's does: the refracted ray's exit point moves it (by
 * more than 3 pixels). */
SR_TEST(point_light_through_thin_and_thick_glass)
{
    slab s = make_slab(35.0 * PI_D / 180.0);
    const double rough = 0.3;
    lamp lp = { .at = { 0.9, 0.3, -3.0 }, .intensity = 0.8 };
    sr_pbr_material m = glass((float)rough);
    sr_pbr_desc d = { .material = &m };
    d.lights[0] = (sr_light){ .type = SR_LIGHT_POINT, .vector = { 0.9f, 0.3f, -3.0f },
                              .intensity = (float)lp.intensity };
    const double th[2] = { 0.0, 1.0 };
    int peak[2], want_peak[2];
    for (int k = 0; k < 2; k++) {
        m.thickness = (float)th[k];
        m.attenuation_distance = k ? 1.0f : 0.0f;
        m.attenuation_color[0] = m.attenuation_color[1] = m.attenuation_color[2] = k ? 0.5f : 1.0f;
        sr_framebuffer *fb = draw_slab(&s, d);
        REQUIRE(fb);
        save(fb, k ? "pbr_lamp_through_volume" : "pbr_lamp_through_thin");
        int y = H / 2;
        double top = 0.0;
        want_peak[k] = 0;
        int bad = 0;
        for (int x = 0; x < W; x++) {
            double want = lamp_through(&s, &lp, x, y, rough, th[k], 0.5, k ? 1.0 : 0.0);
            if (want > top) {
                top = want;
                want_peak[k] = x;
            }
            for (int c = 0; c < 3; c++) {
                bad += fabs(px(fb, x, y)[c] - srgb_encode(want)) > 2.0;
            }
        }
        peak[k] = peak_x(fb, y);
        for (int yy = 0; yy < H; yy++) {
            double want = lamp_through(&s, &lp, peak[k], yy, rough, th[k], 0.5, k ? 1.0 : 0.0);
            bad += fabs(px(fb, peak[k], yy)[1] - srgb_encode(want)) > 2.0;
        }
        fprintf(stderr, "thickness %.1f: peak %.3f at x %d (formula x %d), %d pixels off\n", th[k],
                top, peak[k], want_peak[k], bad);
        CHECK(top > 0.2 && top < 0.95);
        CHECK_EQ(bad, 0);
        CHECK(abs(peak[k] - want_peak[k]) <= 1);
        sr_destroy_framebuffer(sr_test_ctx(), fb);
    }
    CHECK(abs(peak[1] - peak[0]) > 3);
}

/* A spot light's cone is taken where the ray leaves the volume too:
 * with its axis straight at the slab's centre and the cone's edge
 * across the highlight, the middle row matches the formula (cone
 * included) within 2 codes, thin and thick, and some of it is cut by
 * the cone (the plain point light's formula is off there). */
SR_TEST(spot_light_cone_through_glass)
{
    slab s = make_slab(35.0 * PI_D / 180.0);
    const double rough = 0.3;
    double axis[3] = { -0.9, -0.3, 8.0 };
    unit(axis);
    double inner = 0.02, outer = 0.05;
    lamp lp = { .at = { 0.9, 0.3, -3.0 }, .intensity = 0.8, .axis = axis,
                .cos_inner = cos(inner), .cos_outer = cos(outer) };
    lamp bare = lp;
    bare.axis = NULL;
    sr_pbr_material m = glass((float)rough);
    sr_pbr_desc d = { .material = &m };
    d.lights[0] = (sr_light){ .type = SR_LIGHT_SPOT, .vector = { 0.9f, 0.3f, -3.0f },
                              .direction = { (float)axis[0], (float)axis[1], (float)axis[2] },
                              .intensity = (float)lp.intensity, .inner_cone = (float)inner,
                              .outer_cone = (float)outer };
    for (int k = 0; k < 2; k++) {
        double th = k ? 1.0 : 0.0;
        m.thickness = (float)th;
        sr_framebuffer *fb = draw_slab(&s, d);
        REQUIRE(fb);
        if (k) {
            save(fb, "pbr_spot_through_volume");
        }
        int bad = 0, cut = 0;
        for (int x = 0; x < W; x++) {
            double want = lamp_through(&s, &lp, x, H / 2, rough, th, 1.0, 0.0);
            double full = lamp_through(&s, &bare, x, H / 2, rough, th, 1.0, 0.0);
            for (int c = 0; c < 3; c++) {
                bad += fabs(px(fb, x, H / 2)[c] - srgb_encode(want)) > 2.0;
            }
            cut += srgb_encode(full) - srgb_encode(want) > 10.0;
        }
        fprintf(stderr, "spot, thickness %.1f: %d pixels off, %d cut by the cone\n", th, bad, cut);
        CHECK_EQ(bad, 0);
        CHECK(cut > 5);
        sr_destroy_framebuffer(sr_test_ctx(), fb);
    }
}

/* ---- a lamp through a dispersive volume ---------------------------------- */

/* The centroid of row y's channel c above half its largest value. */
static double centroid(const sr_framebuffer *fb, int y, int c)
{
    double top = 0.0, sum = 0.0, wsum = 0.0;
    for (int x = 0; x < W; x++) {
        double v = srgb_decode(px(fb, x, y)[c]);
        top = v > top ? v : top;
    }
    for (int x = 0; x < W; x++) {
        double v = srgb_decode(px(fb, x, y)[c]);
        if (v > 0.5 * top) {
            sum += (v - 0.5 * top) * x;
            wsum += v - 0.5 * top;
        }
    }
    return wsum > 0.0 ? sum / wsum : NAN;
}

/* KHR_materials_dispersion splits a lamp seen through a volume as it
 * splits the scene behind: a light straight behind a slab turned 50
 * degrees (thickness 2, ior 1.5, dispersion 20: iors 1.25, 1.5, 1.75)
 * shows red's and blue's highlights where green's is, moved by the
 * angle between their exit points and green's seen from the eye (Snell's
 * law here), within 0.5 pixel, on either side of green and more than 2
 * pixels from it; dispersion 0 keeps the channels together.  The image
 * is held to tests/ref/pbr_dispersion_lamp.png (3 codes, 0.5% of the
 * pixels). */
SR_TEST(dispersion_splits_a_lamp_behind_glass)
{
    slab s = make_slab(50.0 * PI_D / 180.0);
    const double th = 2.0, ior = 1.5, disp = 20.0;
    sr_pbr_material m = glass(0.3f);
    m.thickness = (float)th;
    m.ior = (float)ior;
    sr_pbr_desc d = { .material = &m };
    d.lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL, .vector = { 0, 0, 1 },
                              .intensity = 0.02f };
    sr_framebuffer *plain = draw_slab(&s, d);
    m.dispersion = (float)disp;
    sr_framebuffer *fb = draw_slab(&s, d);
    REQUIRE(plain && fb);
    save(fb, "pbr_dispersion_lamp");
    sr_test_check_image("pbr_dispersion_lamp", sr_framebuffer_pixels(fb), W, H, 3, W * H / 200);
    int y = H / 2;
    double half = (ior - 1.0) / (20.0 / disp) / 2.0;
    const double iors[3] = { ior - half, ior, ior + half };
    double got[3], same[3];
    for (int c = 0; c < 3; c++) {
        got[c] = centroid(fb, y, c);
        same[c] = centroid(plain, y, c);
        REQUIRE(!isnan(got[c]) && !isnan(same[c]));
    }
    /* At green's highlight, each channel's exit point on the screen. */
    double p[3], v[3], at[3];
    hit(&s, got[1], y, p, v);
    for (int c = 0; c < 3; c++) {
        double t[3], e[3];
        refract_in(v, s.n, iors[c], t);
        for (int k = 0; k < 3; k++) {
            e[k] = p[k] + t[k] * th;
        }
        at[c] = screen_x(e);
    }
    for (int c = 0; c < 3; c += 2) {
        double want = got[1] - (at[c] - at[1]);
        fprintf(stderr, "channel %d: highlight at %.2f, green's %.2f, want %.2f\n", c, got[c],
                got[1], want);
        CHECK_NEAR(got[c], want, 0.5);
        CHECK(fabs(got[c] - got[1]) > 2.0);
        CHECK_NEAR(same[c], same[1], 0.05);
    }
    CHECK((got[0] - got[1]) * (got[2] - got[1]) < 0.0);
    sr_destroy_framebuffer(sr_test_ctx(), plain);
    sr_destroy_framebuffer(sr_test_ctx(), fb);
}

/* ---- a backlit leaf under the key light's shadow map ---------------------- */

/* A leaf: a green dielectric letting all of its diffuse light through. */
static sr_pbr_material leaf(void)
{
    sr_pbr_material m = sr_pbr_default_material();
    m.base_color[0] = 0.2f, m.base_color[1] = 0.6f, m.base_color[2] = 0.1f;
    m.metallic = 0.0f;
    m.roughness = 0.5f;
    m.double_sided = true;
    m.diffuse_transmission = 1.0f;
    m.diffuse_transmission_color[0] = 0.6f;
    m.diffuse_transmission_color[1] = 0.9f;
    m.diffuse_transmission_color[2] = 0.2f;
    return m;
}

/* The key light's shadow map along travel over the box of the leaf (the
 * slab of side 8, turned by s's tilt, drawn into it) and, with
 * `blocker`, of a square of side 0.8 at z = bz centred on x = -0.6,
 * between the light and the leaf. */
static sr_shadow_map *leaf_shadow(const slab *s, const float travel[3], bool blocker, float bz)
{
    sr_context *ctx = sr_test_ctx();
    float pos[12] = { -4, -4, 0, 4, -4, 0, 4, 4, 0, -4, 4, 0 };
    float block[12] = { -1.0f, -0.4f, bz, -0.2f, -0.4f, bz, -0.2f, 0.4f, bz, -1.0f, 0.4f, bz };
    uint32_t idx[6] = { 0, 1, 2, 0, 2, 3 };
    sr_mat4 model = sr_mat4_rotate((float)s->tilt, (sr_vec3){ 0, 1, 0 });
    sr_shadow_map *sm = NULL;
    if (sr_make_shadow_map(ctx, &(sr_shadow_desc){ .direction = { travel[0], travel[1], travel[2] },
                                                   .bounds_min = { -4, -4, -4 },
                                                   .bounds_max = { 4, 4, 4 }, .size = 512, .light_radius = 0.04f },
                           &sm) != SR_OK) {
        return NULL;
    }
    sr_draw_desc d = { .positions = pos, .model = &model, .vertex_count = 4, .indices = idx,
                       .index_type = SR_INDEX_U32, .index_count = 6 };
    bool ok = sr_shadow_map_clear(ctx, sm) == SR_OK && sr_shadow_map_draw(ctx, sm, &d) == SR_OK;
    if (ok && blocker) {
        d.positions = block;
        d.model = NULL;
        ok = sr_shadow_map_draw(ctx, sm, &d) == SR_OK;
    }
    if (!ok) {
        sr_destroy_shadow_map(ctx, sm);
        return NULL;
    }
    return sm;
}

/* KHR_materials_diffuse_transmission under the key light's shadow map:
 * a thin double-sided leaf between the light and the camera is its own
 * occluder in the map, and must not shade the light it lets through
 * (real renderers look the transmitted light's shadow up from the far
 * side of the surface).  Lit only from behind (travel (0.3, 0, 1)), the
 * leaf with the map draws the bytes it draws without one, within 1
 * code, but where another square stands between the light and the leaf:
 * there the backlight is gone (the leaf is black without ambient light).
 * Lit from the front, the leaf's own map changes no byte either, and a
 * square in front of it still shadows it. */
SR_TEST(leaf_does_not_shadow_its_own_backlight)
{
    slab s = make_slab(0.0);
    sr_pbr_material m = leaf();
    for (int front = 0; front < 2; front++) {
        float travel[3] = { 0.3f, 0.0f, front ? -1.0f : 1.0f };
        float bz = front ? 1.5f : -1.5f;
        sr_shadow_map *own = leaf_shadow(&s, travel, false, bz);
        sr_shadow_map *both = leaf_shadow(&s, travel, true, bz);
        REQUIRE(own && both);
        sr_pbr_desc d = { .material = &m };
        d.lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL,
                                  .vector = { travel[0], travel[1], travel[2] },
                                  .intensity = 1.5f };
        sr_framebuffer *fb[3];
        for (int k = 0; k < 3; k++) {
            d.shadow = k == 0 ? NULL : k == 1 ? own : both;
            fb[k] = draw_slab(&s, d);
            REQUIRE(fb[k]);
        }
        save(fb[2], front ? "pbr_leaf_shadow_front" : "pbr_leaf_shadow_back");
        /* The square's shadow on the leaf: 1.5 along the light's way
         * moves it by 1.5 * 0.3. */
        double p[3] = { -0.6 + 1.5 * 0.3, 0.0, 0.0 };
        int sx = (int)lround(screen_x(p)), sy = H / 2, lx = W - 24, ly = 20;
        int off = 0;
        for (int y = 0; y < H; y++) {
            for (int x = 0; x < W; x++) {
                for (int c = 0; c < 3; c++) {
                    off += abs(px(fb[0], x, y)[c] - px(fb[1], x, y)[c]) > 1;
                }
            }
        }
        fprintf(stderr, "%s: %d channels off with the leaf's own map; lit %d, under the square %d "
                "(no map %d)\n", front ? "front" : "back", off, px(fb[2], lx, ly)[1],
                px(fb[2], sx, sy)[1], px(fb[0], sx, sy)[1]);
        CHECK(px(fb[0], lx, ly)[1] > 20);
        CHECK_EQ(off, 0);
        CHECK_NEAR(px(fb[2], lx, ly)[1], px(fb[0], lx, ly)[1], 1.0);
        CHECK(px(fb[2], sx, sy)[1] < 3);
        for (int k = 0; k < 3; k++) {
            sr_destroy_framebuffer(sr_test_ctx(), fb[k]);
        }
        sr_destroy_shadow_map(sr_test_ctx(), own);
        sr_destroy_shadow_map(sr_test_ctx(), both);
    }
}

/* The far side's lookup goes as deep as the thickness the shading uses:
 * KHR_materials_volume's factor times its texture's G.  A leaf of
 * thickness factor 1 whose texture's G is 51 (0.2), lit from behind
 * with a square 0.5 behind it, looks the backlight's shadow up 0.2
 * behind itself, where the square is between it and the light: it draws
 * the bytes (within 1 code, a few edge pixels aside) of the untextured
 * leaf 0.2 thick, black under the square's shadow, where the leaf 1
 * thick (whose lookup lies beyond the square) stays lit.  Before, the
 * textured leaf looked up 1 deep, as the factor alone says. */
SR_TEST(a_textured_thickness_sets_the_far_side_lookup_depth)
{
    slab s = make_slab(0.0);
    float travel[3] = { 0.3f, 0.0f, 1.0f };
    sr_shadow_map *sm = leaf_shadow(&s, travel, true, -0.5f);
    REQUIRE(sm);
    const uint8_t texel[16] = { 0, 51, 0, 255, 0, 51, 0, 255, 0, 51, 0, 255, 0, 51, 0, 255 };
    sr_texture *t = NULL;
    REQUIRE(sr_make_texture(sr_test_ctx(), &(sr_texture_desc){ .width = 2, .height = 2,
                                                               .pixels = texel }, &t) == SR_OK);
    sr_pbr_material m[3] = { leaf(), leaf(), leaf() };
    m[0].thickness = 1.0f;
    m[0].thickness_texture.texture = t;
    m[1].thickness = 0.2f;
    m[2].thickness = 1.0f;
    sr_framebuffer *fb[3];
    for (int k = 0; k < 3; k++) {
        sr_pbr_desc d = { .material = &m[k], .shadow = sm };
        d.lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL,
                                  .vector = { travel[0], travel[1], travel[2] },
                                  .intensity = 1.5f };
        fb[k] = draw_slab(&s, d);
        REQUIRE(fb[k]);
    }
    save(fb[0], "pbr_leaf_shadow_thickness_texture");
    save(fb[2], "pbr_leaf_shadow_thickness_1");
    /* The square's shadow on the far side 0.2 behind the leaf: 0.3 along
     * the light's way moves it by 0.3 * 0.3. */
    double p[3] = { -0.6 + 0.3 * 0.3, 0.0, 0.0 };
    int sx = (int)lround(screen_x(p)), sy = H / 2;
    int off = 0;
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            for (int c = 0; c < 3; c++) {
                off += abs(px(fb[0], x, y)[c] - px(fb[1], x, y)[c]) > 1;
            }
        }
    }
    fprintf(stderr, "textured vs 0.2 thick: %d channels off; under the square %d, %d, 1 thick %d\n",
            off, px(fb[0], sx, sy)[1], px(fb[1], sx, sy)[1], px(fb[2], sx, sy)[1]);
    CHECK(off <= 12);
    CHECK(px(fb[1], sx, sy)[1] < 3);
    CHECK(px(fb[0], sx, sy)[1] < 3);
    CHECK(px(fb[2], sx, sy)[1] > 20);
    for (int k = 0; k < 3; k++) {
        sr_destroy_framebuffer(sr_test_ctx(), fb[k]);
    }
    sr_destroy_texture(sr_test_ctx(), t);
    sr_destroy_shadow_map(sr_test_ctx(), sm);
}
