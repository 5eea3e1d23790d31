/* test_svg_span.c - the paints along a row (src/draw2d/paint_fill.h) the
 * SVG reader paints with: gradients through their color table stay within one code of the
 * gradient evaluated exactly at each pixel (here, from the formulas of
 * SVG) on random linear and radial gradients with every spread method,
 * close and coincident stops and transparent ones; a paint that says it
 * depends on x alone gives every row the same bytes; an image drawn
 * texel for pixel gives its texels, and any other map the bilinear
 * filter's colors within one code; a painted fill leaves each pixel as
 * svg_blend leaves it (its copies and integer blends are no shortcut, nor
 * a paint of y written straight into the result). */
#include "draw2d/paint_fill.h"
#include "io/svg.h"
#include "sr_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static uint64_t rng = 0x9e3779b97f4a7c15ULL;

static double unit(void)
{
    rng ^= rng >> 12;
    rng ^= rng << 25;
    rng ^= rng >> 27;
    return (double)((rng * 2685821657736338717ULL) >> 11) / 9007199254740992.0;
}

static uint8_t unorm8(double v)
{
    return !(v > 0) ? 0 : v >= 1 ? 255 : (uint8_t)(v * 255 + 0.5);
}

/* ---- gradients --------------------------------------------------------------------- */

/* t at pixel centre (px, py) straight from SVG's definitions; false where
 * a radial gradient does not reach.  *edge: too close to where it stops
 * reaching for a rounding difference not to matter. */
static bool exact_t(const sr__gradient *g, double px, double py, double *t, bool *edge)
{
    const double *m = g->inv;
    double x = m[0] * px + m[2] * py + m[4], y = m[1] * px + m[3] * py + m[5];
    *edge = false;
    if (!g->radial) {
        double dx = g->x2 - g->x1, dy = g->y2 - g->y1, len2 = dx * dx + dy * dy;
        *t = len2 > 0 ? ((x - g->x1) * dx + (y - g->y1) * dy) / len2 : 0;
        return true;
    }
    double cdx = g->cx - g->fx, cdy = g->cy - g->fy, dr = g->r - g->fr;
    double pdx = x - g->fx, pdy = y - g->fy;
    double a = cdx * cdx + cdy * cdy - dr * dr, b = pdx * cdx + pdy * cdy + g->fr * dr;
    double c = pdx * pdx + pdy * pdy - g->fr * g->fr, disc = b * b - a * c;
    *edge = fabs(disc) < 1e-6 * (b * b + fabs(a * c)) + 1e-12;
    if (disc < 0) {
        return false;
    }
    double t0 = (b + sqrt(disc)) / a, t1 = (b - sqrt(disc)) / a;
    double hi = fmax(t0, t1), lo = fmin(t0, t1);
    *edge = *edge || fabs(g->fr + hi * dr) < 1e-6 || fabs(g->fr + lo * dr) < 1e-6;
    *t = g->fr + hi * dr >= 0 ? hi : lo;
    return g->fr + *t * dr >= 0;
}

static double spread_t(sr_gradient_spread s, double t)
{
    if (s == SR_SPREAD_REPEAT) {
        return t - floor(t);
    }
    if (s == SR_SPREAD_REFLECT) {
        double u = fmod(fabs(t), 2);
        return u > 1 ? 2 - u : u;
    }
    return t < 0 ? 0 : t > 1 ? 1 : t;
}

/* The color of a spread t: flat outside the stops, linear between. */
static void exact_color(const sr__gradient *g, double t, uint8_t out[4])
{
    sr_rgba c = g->color[g->n_stops - 1];
    if (t <= g->offset[0]) {
        c = g->color[0];
    } else {
        for (int i = 1; i < g->n_stops; i++) {
            if (t < g->offset[i]) {
                double u = (t - g->offset[i - 1]) / (g->offset[i] - g->offset[i - 1]);
                sr_rgba a = g->color[i - 1], b = g->color[i];
                c = (sr_rgba){ (float)(a.r + (b.r - a.r) * u), (float)(a.g + (b.g - a.g) * u),
                               (float)(a.b + (b.b - a.b) * u), (float)(a.a + (b.a - a.a) * u) };
                break;
            }
        }
    }
    out[0] = unorm8(c.r);
    out[1] = unorm8(c.g);
    out[2] = unorm8(c.b);
    out[3] = unorm8(c.a);
}

/* Whether t is within a hair of a place where the color jumps: a stop
 * shared by two offsets, or (repeat) a whole number. */
static bool near_jump(const sr__gradient *g, double t)
{
    for (int i = 1; i < g->n_stops; i++) {
        if (g->offset[i] == g->offset[i - 1] && fabs(t - g->offset[i]) < 1e-9) {
            return true;
        }
    }
    return g->spread == SR_SPREAD_REPEAT && fabs(t - floor(t + 0.5)) < 1e-9;
}

static void random_gradient(sr__gradient *g, bool close_stops)
{
    memset(g, 0, sizeof *g);
    g->radial = unit() < 0.5;
    g->spread = (sr_gradient_spread)(int)(unit() * 3);
    g->n_stops = 1 + (int)(unit() * 5);
    for (int i = 0; i < g->n_stops; i++) {
        g->offset[i] = unit();
        g->color[i] = (sr_rgba){ (float)unit(), (float)unit(), (float)unit(),
                                 unit() < 0.6 ? 1.0f : (float)unit() };
    }
    for (int i = 1; i < g->n_stops; i++) { /* sorted; some coincide */
        for (int j = i; j > 0 && g->offset[j] < g->offset[j - 1]; j--) {
            double s = g->offset[j];
            g->offset[j] = g->offset[j - 1];
            g->offset[j - 1] = s;
        }
    }
    if (g->n_stops > 2 && unit() < 0.3) {
        g->offset[2] = g->offset[1];
    }
    if (!close_stops) { /* two stops far apart: the table serves them */
        g->n_stops = 2;
        g->offset[0] = 0.1 * unit();
        g->offset[1] = 0.6 + 0.4 * unit();
    }
    double s = 20 + 200 * unit(), r = unit() * 6.283;
    double sx = s * (0.5 + unit()), sy = s * (0.5 + unit());
    /* pixels -> gradient space: scaled, turned (or not) and moved */
    double c = unit() < 0.5 ? 1 : cos(r), n = c == 1 ? 0 : sin(r);
    double inv[6] = { c / sx, -n / sy, n / sx, c / sy, -unit() * 2, -unit() * 2 };
    memcpy(g->inv, inv, sizeof inv);
    g->x1 = unit() - 0.5;
    g->y1 = unit() - 0.5;
    g->x2 = g->x1 + unit() * 2 - 1;
    g->y2 = unit() < 0.3 ? g->y1 : g->y1 + unit() * 2 - 1;
    g->cx = unit();
    g->cy = unit();
    g->r = 0.05 + unit();
    g->fx = g->cx + (unit() - 0.5) * g->r;
    g->fy = g->cy + (unit() - 0.5) * g->r;
    g->fr = unit() < 0.5 ? 0 : unit() * g->r;
}

SR_TEST(gradient_spans_are_within_one_code_of_the_exact_colors)
{
    static sr__gradient g;
    uint32_t row[300];
    long compared = 0, skipped = 0, worst = 0, tabled = 0;
    for (int n = 0; n < 600; n++) {
        random_gradient(&g, n % 3 != 0);
        for (int k = 0; k < 8; k++) {
            int x0 = (int)(unit() * 400) - 50, y = (int)(unit() * 400) - 50;
            int len = 1 + (int)(unit() * 299);
            sr__gradient_span(&g, x0, y, len, row);
            for (int i = 0; i < len; i++) {
                double t;
                bool edge, on = exact_t(&g, x0 + i + 0.5, y + 0.5, &t, &edge);
                uint8_t want[4] = { 0, 0, 0, 0 }, got[4];
                memcpy(got, &row[i], 4);
                if (edge || (on && (!isfinite(t) || near_jump(&g, spread_t(g.spread, t)) ||
                                    near_jump(&g, t)))) {
                    skipped++;
                    continue;
                }
                if (on) {
                    exact_color(&g, spread_t(g.spread, t), want);
                }
                for (int c = 0; c < 4; c++) {
                    long d = labs((long)got[c] - want[c]);
                    worst = d > worst ? d : worst;
                }
                compared++;
            }
        }
        for (int c = 0; c <= SR__GRADIENT_LUT; c++) {
            tabled += g.lut_state[c] == 1;
        }
    }
    CHECK(worst <= 1);
    /* The hairs left out are few, and the table did serve pixels. */
    CHECK(compared > 600L * 8 * 100);
    CHECK(skipped * 100 < compared);
    CHECK(tabled > 600L * 50);
}

SR_TEST(a_gradient_of_x_alone_paints_every_row_alike)
{
    static sr__gradient g;
    uint32_t a[200], b[200];
    int of_x = 0;
    for (int n = 0; n < 300; n++) {
        random_gradient(&g, true);
        /* a linear gradient along an axis of its box, as objectBoundingBox gives */
        if (n % 2 == 0) {
            g.radial = false;
            g.inv[1] = g.inv[2] = 0;
            g.y2 = g.y1;
        }
        if (sr__gradient_span(&g, 3, 7, 200, a)) {
            of_x++;
            sr__gradient_span(&g, 3, 7 + 1 + (int)(unit() * 500), 200, b);
            CHECK(memcmp(a, b, sizeof a) == 0);
        }
    }
    CHECK(of_x >= 150);
}

/* ---- images ------------------------------------------------------------------------ */

static void make_image(sr__image *im, uint8_t *rgba, int w, int h, bool repeat)
{
    for (int i = 0; i < w * h * 4; i++) {
        rgba[i] = (uint8_t)(unit() * 256);
    }
    for (int i = 0; i < w * h; i += 5) {
        rgba[i * 4 + 3] = i % 2 ? 255 : 0; /* opaque and transparent texels among the rest */
    }
    *im = (sr__image){ .rgba = rgba, .w = w, .h = h, .stride = (size_t)w * 4, .repeat = repeat };
}

static long wrap(long i, long n, bool repeat)
{
    return repeat ? ((i % n) + n) % n : i < 0 ? 0 : i >= n ? n - 1 : i;
}

SR_TEST(an_image_drawn_texel_for_pixel_gives_its_texels)
{
    uint8_t rgba[13 * 9 * 4];
    uint32_t row[100];
    for (int n = 0; n < 200; n++) {
        sr__image im;
        make_image(&im, rgba, 13, 9, n % 2 == 0);
        int ox = (int)(unit() * 60) - 30, oy = (int)(unit() * 60) - 30;
        double inv[6] = { 1, 0, 0, 1, ox, oy };
        memcpy(im.inv, inv, sizeof inv);
        int x0 = (int)(unit() * 80) - 40, y = (int)(unit() * 80) - 40;
        int len = n % 4 < 2 ? 100 : 1 + (int)(unit() * 30); /* shorter than a tile's row too */
        sr__image_span(&im, x0, y, len, row);
        for (int i = 0; i < len; i++) {
            const uint8_t *t = rgba + (wrap(y + oy, 9, im.repeat) * 13 +
                                       wrap(x0 + i + ox, 13, im.repeat)) * 4;
            uint8_t want[4] = { 0, 0, 0, 0 };
            if (t[3] > 0) {
                memcpy(want, t, 4);
            }
            CHECK(memcmp(&row[i], want, 4) == 0);
        }
    }
}

SR_TEST(an_image_under_any_other_map_is_filtered_bilinearly)
{
    uint8_t rgba[7 * 11 * 4];
    uint32_t row[64];
    long worst = 0;
    for (int n = 0; n < 200; n++) {
        sr__image im;
        make_image(&im, rgba, 7, 11, n % 2 == 1);
        double s = 0.2 + unit() * 2, r = unit() * 6.283;
        double inv[6] = { s * cos(r), s * sin(r), -s * sin(r), s * cos(r), unit() * 9, unit() * 9 };
        memcpy(im.inv, inv, sizeof inv);
        int x0 = (int)(unit() * 40) - 20, y = (int)(unit() * 40) - 20;
        sr__image_span(&im, x0, y, 64, row);
        for (int i = 0; i < 64; i++) {
            double px = x0 + i + 0.5, py = y + 0.5;
            double u = inv[0] * px + inv[2] * py + inv[4] - 0.5;
            double v = inv[1] * px + inv[3] * py + inv[5] - 0.5;
            double fu = u - floor(u), fv = v - floor(v), o[4] = { 0, 0, 0, 0 };
            for (int k = 0; k < 4; k++) {
                long ti = wrap((long)floor(u) + k % 2, 7, im.repeat);
                long tj = wrap((long)floor(v) + k / 2, 11, im.repeat);
                const uint8_t *t = rgba + (tj * 7 + ti) * 4;
                double wgt = (k % 2 ? fu : 1 - fu) * (k / 2 ? fv : 1 - fv), a = t[3] / 255.0;
                for (int c = 0; c < 3; c++) {
                    o[c] += wgt * a * t[c] / 255.0;
                }
                o[3] += wgt * a;
            }
            uint8_t want[4] = { 0, 0, 0, 0 }, got[4];
            if (o[3] > 1e-6) {
                for (int c = 0; c < 3; c++) {
                    want[c] = unorm8(o[c] / o[3]);
                }
                want[3] = unorm8(o[3]);
            } else if (o[3] > 0) {
                continue; /* a color of almost nothing: the rounding decides */
            }
            memcpy(got, &row[i], 4);
            for (int c = 0; c < 4; c++) {
                long d = labs((long)got[c] - want[c]);
                worst = d > worst ? d : worst;
            }
        }
    }
    CHECK(worst <= 1);
}

/* ---- fills ------------------------------------------------------------------------- */

/* The straight-alpha blend written out in full (the divisions by the
 * result's alpha and all): what svg_blend gives over an empty pixel. */
SR_TEST(svg_blend_over_an_empty_pixel_is_the_full_blend)
{
    long differ = 0;
    for (int n = 0; n < 20000; n++) {
        sr_rgba c = { (float)unit(), (float)unit(), (float)unit(), (float)unit() };
        float cov = n % 4 == 0 ? 1.0f : (float)unit();
        uint8_t d[4] = { (uint8_t)(unit() * 256), (uint8_t)(unit() * 256),
                         (uint8_t)(unit() * 256), 0 };
        uint8_t want[4], s[3] = { sr__paint_unorm8(c.r), sr__paint_unorm8(c.g), sr__paint_unorm8(c.b) };
        memcpy(want, d, 4);
        float a = c.a * cov;
        if (a > 0.0f) {
            float da = 0.0f, keep = 1.0f - a, oa = a + da * keep;
            keep = oa > 0.0f ? da * keep / oa : 0.0f;
            float w = oa > 0.0f ? a / oa : 0.0f;
            for (int i = 0; i < 3; i++) {
                want[i] = sr__paint_unorm8((s[i] * w + d[i] * keep) * (1.0f / 255.0f));
            }
            want[3] = sr__paint_unorm8(oa);
        }
        svg_blend(d, c, cov);
        differ += memcmp(d, want, 4) != 0;
    }
    CHECK_EQ(differ, 0);
}

SR_TEST(a_painted_fill_blends_each_pixel_as_svg_blend_does)
{
    enum { W = 64, H = 48 };
    sr_context *ctx = sr_test_ctx();
    static uint8_t before[W * H * 4], want[W * H * 4], mask[W * H], rgba[16 * 16 * 4];
    for (int n = 0; n < 40; n++) {
        sr_framebuffer *fb = NULL;
        REQUIRE(sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                                                   .depth_format = SR_DEPTH_NONE },
                                    &fb) == SR_OK);
        /* a background opaque in most rows, see-through or empty in others */
        for (int i = 0; i < W * H; i++) {
            for (int c = 0; c < 4; c++) {
                before[i * 4 + c] = (uint8_t)(unit() * 256);
            }
            int row = i / W;
            before[i * 4 + 3] = row % 4 == 0 ? 0 : row % 4 == 1 ? before[i * 4 + 3] : 255;
        }
        REQUIRE(sr_write_pixels(ctx, fb, 0, 0, W, H, before, W * 4) == SR_OK);
        sr__image im;
        make_image(&im, rgba, 16, 16, true);
        for (int i = 0; i < 16 * 16; i++) { /* mostly opaque, as a tile usually is */
            rgba[i * 4 + 3] = i % 7 == 0 ? rgba[i * 4 + 3] : 255;
        }
        double inv[6] = { 1, 0, 0, 1, (int)(unit() * 16), (int)(unit() * 16) };
        memcpy(im.inv, inv, sizeof inv);
        sr_point2 pts[9];
        for (int k = 0; k < 9; k++) { /* a star, partly off the framebuffer */
            double a = k * 2.0 * 3.14159265 * 4 / 9, r = 10 + unit() * 30;
            pts[k] = (sr_point2){ 30 + r * cos(a) + unit() * 8, 24 + r * sin(a) };
        }
        sr_polygon2 poly = { pts, 9, NULL, 0 };
        sr_fill_desc desc = { .rule = n % 2 ? SR_NONZERO : SR_EVENODD, .antialias = SR_AA_AREA };
        float opacity = n % 3 == 0 ? 0.6f : 1.0f;
        REQUIRE(sr_polygon_coverage(ctx, &poly, &desc, 0, 0, W, H, mask, W) == SR_OK);
        memcpy(want, before, sizeof want);
        for (int y = 0; y < H; y++) {
            uint32_t paint[W];
            sr__image_span(&im, 0, y, W, paint);
            for (int x = 0; x < W; x++) {
                uint8_t s[4];
                memcpy(s, &paint[x], 4);
                sr_rgba c = { s[0] / 255.0f, s[1] / 255.0f, s[2] / 255.0f,
                              s[3] * (1.0f / 255.0f) * opacity };
                svg_blend(want + (y * W + x) * 4, c, (float)mask[y * W + x] * (1.0f / 255.0f));
            }
        }
        REQUIRE(sr__fill_paint(ctx, "test", fb, &poly, &desc, sr__image_span, &im, opacity) ==
                SR_OK);
        CHECK(memcmp(sr_framebuffer_pixels(fb), want, sizeof want) == 0);
        sr_destroy_framebuffer(ctx, fb);
    }
}
