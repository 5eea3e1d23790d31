/* identity.c - the same bytes everywhere: renders a fixed set of scenes and
 * compares the SHA-256 digests of their colour, depth and stencil buffers
 * with the one committed table, tests/identity/digests.txt.
 *
 * Every build (any SR_SIMD level and thread count, GCC or clang, -O0 or
 * -O2, any CPU the library runs on) must give that table; a row that
 * differs names the scene and the buffer.  The scenes build their own
 * geometry and textures, so a clone of the repository alone runs them.
 *
 *   test_identity [TABLE]          compare (default: the source tree's table)
 *   test_identity --print          print the table this build gives
 *   test_identity --png DIR        compare, and write each scene's colour as DIR/SCENE.png
 *
 * Regenerate the table only for a deliberate change of the output, and say
 * so in the commit (docs/portability.md). */
#include "sha256.h"
#include "softrast.h"
#include "softrast_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 160
#define H 120

typedef sr_result (*scene_fn)(sr_context *ctx, sr_framebuffer **fb);

/* The sine and cosine the scenes' geometry takes, from additions,
 * multiplications and divisions alone, which IEEE 754 rounds the same
 * everywhere: libm's sinf and cosf differ in the last place between C
 * libraries (glibc's and Emscripten's musl round some of these angles
 * apart), which moves a vertex and changes a depth. */
static float exact_sin(double x)
{
    const double two_pi = 6.283185307179586;
    double r = x - two_pi * nearbyint(x / two_pi);  /* in [-pi, pi] */
    double term = r, sum = r;
    for (int k = 1; k <= 12; k++) {                 /* the Taylor series to r^25 */
        term = -term * r * r / (double)((2 * k) * (2 * k + 1));
        sum += term;
    }
    return (float)sum;
}

static float exact_cos(double x)
{
    return exact_sin(x + 1.5707963267948966);
}

static sr_result make_fb(sr_context *ctx, int samples, bool stencil, sr_framebuffer **fb)
{
    sr_result r = sr_make_framebuffer(
        ctx, &(sr_framebuffer_desc){ .width = W, .height = H, .samples = samples,
                                     .stencil = stencil },
        fb);
    if (r == SR_OK) {
        r = sr_clear(ctx, *fb, &(sr_clear_desc){ .color = { 0.1f, 0.12f, 0.15f, 1 } });
    }
    return r;
}

static sr_mat4 camera(void)
{
    return sr_look_at((sr_vec3){ 4.0f, 3.0f, 5.0f }, (sr_vec3){ 0, 0.6f, 0 },
                      (sr_vec3){ 0, 1, 0 });
}

static sr_mat4 projection(void)
{
    return sr_perspective(0.7f, (float)W / (float)H, 0.5f, 20.0f, false);
}

static void key_lights(sr_state *st)
{
    st->lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL, .vector = { -1, -1, -0.5f } };
    st->lights[1] = (sr_light){ .type = SR_LIGHT_POINT, .vector = { -2, 2, 3 },
                                .color = { 0.4f, 0.5f, 1.0f }, .intensity = 0.8f };
    st->ambient = (sr_vec3){ 0.15f, 0.15f, 0.15f };
    st->material = (sr_material){ .diffuse = { 0.8f, 0.5f, 0.3f }, .specular = { 0.6f, 0.6f, 0.6f },
                                  .shininess = 40 };
}

static sr_draw_desc mesh_draw(const sr_mesh *m, const sr_mat4 *view, const sr_mat4 *proj)
{
    return (sr_draw_desc){ .positions = m->positions, .normals = m->normals,
                           .texcoords = m->texcoords, .vertex_count = m->vertex_count,
                           .indices = m->indices, .index_type = SR_INDEX_U32,
                           .index_count = 3 * m->triangle_count, .view = view,
                           .projection = proj };
}

/* The teapot is 3 units high: half of it fills the frame. */
static sr_mat4 teapot_model(void)
{
    return sr_mat4_scale(0.5f, 0.5f, 0.5f);
}

/* The teapot, Phong-shaded, with the stencil counting every sample a
 * fragment reached (depth-failed ones too): overdraw as stencil. */
static sr_result draw_teapot(sr_context *ctx, sr_framebuffer *fb, sr_shading shading)
{
    sr_mesh m;
    sr_result r = sr_make_teapot(ctx, 6, &m);
    if (r != SR_OK) {
        return r;
    }
    sr_mat4 view = camera(), proj = projection();
    sr_state st = { .shading = shading, .cull = SR_CULL_NONE, .two_sided = true };
    key_lights(&st);
    if (sr_framebuffer_has_stencil(fb)) {
        st.stencil = (sr_stencil){ .enabled = true,
                                   .front = { .pass = SR_STENCIL_INCR,
                                              .depth_fail = SR_STENCIL_INCR } };
    }
    sr_mat4 model = teapot_model();
    sr_draw_desc d = mesh_draw(&m, &view, &proj);
    d.model = &model;
    r = sr_draw(ctx, fb, &st, &d);
    sr_destroy_mesh(ctx, &m);
    return r;
}

static sr_result teapot_phong(sr_context *ctx, sr_framebuffer **fb)
{
    sr_result r = make_fb(ctx, 1, true, fb);
    return r == SR_OK ? draw_teapot(ctx, *fb, SR_SHADING_PHONG) : r;
}

static sr_result teapot_msaa4(sr_context *ctx, sr_framebuffer **fb)
{
    sr_result r = make_fb(ctx, 4, true, fb);
    return r == SR_OK ? draw_teapot(ctx, *fb, SR_SHADING_GOURAUD) : r;
}

static sr_result teapot_msaa16(sr_context *ctx, sr_framebuffer **fb)
{
    sr_result r = make_fb(ctx, 16, false, fb);
    return r == SR_OK ? draw_teapot(ctx, *fb, SR_SHADING_PHONG) : r;
}

/* A lumpy sphere standing in for a scanned model such as the bunny: many
 * small triangles of uneven size and orientation, smooth normals. */
static sr_result make_lumpy(sr_context *ctx, sr_mesh *out)
{
    enum { SLICES = 64, STACKS = 40 };
    size_t nv = (SLICES + 1) * (STACKS + 1), nt = 2 * SLICES * STACKS;
    float *pos = malloc(nv * 3 * sizeof(float)), *uv = malloc(nv * 2 * sizeof(float));
    uint32_t *idx = malloc(nt * 3 * sizeof(uint32_t));
    sr_result r = SR_OUT_OF_MEMORY;
    if (pos && uv && idx) {
        size_t v = 0, k = 0;
        for (int j = 0; j <= STACKS; j++) {
            float th = 3.14159265f * (float)j / STACKS;
            for (int i = 0; i <= SLICES; i++, v++) {
                float ph = 6.2831853f * (float)i / SLICES;
                float rad = 1.0f + 0.12f * exact_sin(5 * ph) * exact_sin(4 * th) +
                            0.05f * exact_cos(11 * th);
                pos[3 * v] = rad * exact_sin(th) * exact_cos(ph);
                pos[3 * v + 1] = 0.8f + rad * exact_cos(th);
                pos[3 * v + 2] = -rad * exact_sin(th) * exact_sin(ph);
                uv[2 * v] = 2.0f * (float)i / SLICES;
                uv[2 * v + 1] = 1.0f - (float)j / STACKS;
            }
        }
        for (uint32_t j = 0; j < STACKS; j++) {
            for (uint32_t i = 0; i < SLICES; i++) {
                uint32_t a = j * (SLICES + 1) + i, b = a + 1, c = a + SLICES + 1, d = c + 1;
                uint32_t t[6] = { a, c, b, b, c, d };
                memcpy(&idx[k], t, sizeof t);
                k += 6;
            }
        }
        r = sr_make_mesh(ctx, &(sr_mesh){ .vertex_count = nv, .positions = pos,
                                          .texcoords = uv, .triangle_count = nt, .indices = idx },
                         out);
        if (r == SR_OK) {
            r = sr_mesh_compute_normals(ctx, out, SR_NORMALS_SMOOTH);
            if (r != SR_OK) {
                sr_destroy_mesh(ctx, out);
            }
        }
    }
    free(pos);
    free(uv);
    free(idx);
    return r;
}

/* A 64 x 64 checker with a colour ramp, so every mip level differs. */
static sr_result make_checker(sr_context *ctx, bool srgb, sr_texture **out)
{
    static uint8_t px[64 * 64 * 4];
    for (int y = 0; y < 64; y++) {
        for (int x = 0; x < 64; x++) {
            uint8_t *p = px + 4 * (y * 64 + x);
            bool on = ((x >> 3) ^ (y >> 3)) & 1;
            p[0] = (uint8_t)(on ? 230 : 4 * x);
            p[1] = (uint8_t)(on ? 220 : 4 * y);
            p[2] = (uint8_t)(on ? 60 : 255 - 3 * x);
            p[3] = 255;
        }
    }
    return sr_make_texture(ctx, &(sr_texture_desc){ .width = 64, .height = 64, .pixels = px,
                                                    .srgb = srgb },
                           out);
}

static sr_result draw_lumpy(sr_context *ctx, sr_framebuffer **fb, bool textured)
{
    sr_result r = make_fb(ctx, 1, false, fb);
    sr_mesh m;
    if (r != SR_OK || (r = make_lumpy(ctx, &m)) != SR_OK) {
        return r;
    }
    sr_texture *tex = NULL;
    if (textured) {
        r = make_checker(ctx, true, &tex);
    }
    if (r == SR_OK) {
        sr_mat4 view = camera(), proj = projection();
        sr_state st = { .shading = SR_SHADING_PHONG, .cull = SR_CULL_BACK, .texture = tex };
        key_lights(&st);
        sr_draw_desc d = mesh_draw(&m, &view, &proj);
        r = sr_draw(ctx, *fb, &st, &d);
    }
    sr_destroy_texture(ctx, tex);
    sr_destroy_mesh(ctx, &m);
    return r;
}

static sr_result lumpy_phong(sr_context *ctx, sr_framebuffer **fb)
{
    return draw_lumpy(ctx, fb, false);
}

static sr_result lumpy_textured(sr_context *ctx, sr_framebuffer **fb)
{
    return draw_lumpy(ctx, fb, true);
}

/* A spiral as a wide line strip and as smooth round points, depth-tested
 * against each other. */
static sr_result lines_points(sr_context *ctx, sr_framebuffer **fb)
{
    enum { N = 200 };
    float xyz[3 * N], rgb[3 * N];
    for (int i = 0; i < N; i++) {
        float t = (float)i / N;
        xyz[3 * i] = (0.3f + 1.2f * t) * exact_cos(18.0f * t);
        xyz[3 * i + 1] = 0.1f + 1.6f * t;
        xyz[3 * i + 2] = (0.3f + 1.2f * t) * exact_sin(18.0f * t);
        rgb[3 * i] = t;
        rgb[3 * i + 1] = 1.0f - t;
        rgb[3 * i + 2] = 0.5f;
    }
    sr_result r = make_fb(ctx, 1, false, fb);
    sr_mat4 view = camera(), proj = projection();
    sr_draw_desc d = { .primitive = SR_PRIM_LINE_STRIP, .positions = xyz, .colors = rgb,
                       .color_size = 3, .vertex_count = N, .view = &view, .projection = &proj };
    if (r == SR_OK) {
        r = sr_draw(ctx, *fb, &(sr_state){ .line_width = 3 }, &d);
    }
    if (r == SR_OK) {
        sr_mat4 shift = sr_mat4_translate(0.0f, 0.15f, 0.0f);
        d.model = &shift;
        r = sr_draw(ctx, *fb, &(sr_state){ .smooth_lines = true, .line_width = 1.5f }, &d);
    }
    if (r == SR_OK) {
        d.primitive = SR_PRIM_POINTS;
        d.model = NULL;
        r = sr_draw(ctx, *fb, &(sr_state){ .point_size = 5, .round_points = true }, &d);
    }
    if (r == SR_OK) {
        sr_mat4 shift = sr_mat4_translate(0.2f, -0.1f, 0.0f);
        d.model = &shift;
        r = sr_draw(ctx, *fb, &(sr_state){ .point_size = 3.5f, .smooth_points = true }, &d);
    }
    return r;
}

/* The 2D raster API: antialiased polygon fill, lines by three algorithms,
 * a circle and text. */
static sr_result drawing_2d(sr_context *ctx, sr_framebuffer **fb)
{
    sr_result r = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H,
                                                                    .depth_format = SR_DEPTH_NONE },
                                      fb);
    if (r == SR_OK) {
        r = sr_clear(ctx, *fb, &(sr_clear_desc){ .color = { 1, 1, 1, 1 } });
    }
    const sr_point2 star[] = { { 80, 8 }, { 95, 50 }, { 150, 50 }, { 105, 75 }, { 125, 115 },
                               { 80, 90 }, { 35, 115 }, { 55, 75 }, { 10, 50 }, { 65, 50 } };
    if (r == SR_OK) {
        r = sr_fill_polygon(ctx, *fb, &(sr_polygon2){ .points = star, .point_count = 10 },
                            (sr_rgba){ 0.9f, 0.3f, 0.1f, 0.8f },
                            &(sr_fill_desc){ .antialias = SR_AA_AREA, .linear_light = true });
    }
    const sr_line_algorithm algos[] = { SR_LINE_BRESENHAM, SR_LINE_WU, SR_LINE_AREA };
    for (int i = 0; i < 3 && r == SR_OK; i++) {
        r = sr_draw_line(ctx, *fb, (sr_point2){ 3.3, 10.0 + 30 * i }, (sr_point2){ 156.7, 40.5 + 25 * i },
                         (sr_rgba){ 0.1f, 0.2f, 0.7f, 1 },
                         &(sr_line_desc){ .algorithm = algos[i], .width = 2.5 });
    }
    if (r == SR_OK) {
        r = sr_draw_circle(ctx, *fb, 120.5, 90.0, 22.0, (sr_rgba){ 0.2f, 0.7f, 0.3f, 1 }, false);
    }
    if (r == SR_OK) {
        r = sr_draw_text(ctx, *fb, 4, 100, 2, "softrast", (sr_rgba){ 0, 0, 0, 1 });
    }
    return r;
}

/* An SVG document through softrast_io: a rounded rectangle, a stroked
 * path with curves, a dashed ellipse under a transform, opacity. */
static sr_result svg_drawing(sr_context *ctx, sr_framebuffer **fb)
{
    static const char doc[] =
        "<svg xmlns='http://www.w3.org/2000/svg' viewBox='0 0 160 120' width='160' height='120'>"
        "<rect x='5' y='5' width='150' height='110' rx='12' fill='#3070c0' fill-opacity='0.8'/>"
        "<path d='M20 100 C 40 10, 120 10, 140 100 Q 80 60 20 100 Z' fill='#ffffff' "
        "fill-opacity='0.6' stroke='#202020' stroke-width='3' stroke-linejoin='round'/>"
        "<g transform='rotate(20 80 60)'><ellipse cx='80' cy='60' rx='30' ry='12' "
        "fill='none' stroke='#c02040' stroke-width='4' stroke-dasharray='8 4'/></g>"
        "</svg>";
    if (!sr_io_have_svg()) {
        return SR_UNSUPPORTED;
    }
    sr_io_error err;
    sr_result r = sr_render_svg(ctx, doc, sizeof doc - 1, &(sr_svg_desc){ .name = "identity.svg" },
                                fb, NULL, &err);
    if (r != SR_OK) {
        fprintf(stderr, "identity: %s\n", err.message);
    }
    return r;
}

/* The teapot m drawn into fb with the metallic-roughness program d. */
static sr_result draw_pbr(sr_context *ctx, sr_framebuffer *fb, const sr_mesh *m,
                          const sr_pbr_desc *d)
{
    sr_pbr *p = NULL;
    sr_result r = sr_make_pbr_program(ctx, d, &p);
    if (r == SR_OK) {
        sr_draw_desc dd = mesh_draw(m, NULL, NULL);
        r = sr_draw(ctx, fb, &(sr_state){ .program = sr_pbr_program(p), .cull = SR_CULL_NONE },
                    &dd);
    }
    sr_destroy_pbr_program(ctx, p);
    return r;
}

/* The metallic-roughness program lit by the built-in studio environment. */
static sr_result teapot_pbr(sr_context *ctx, sr_framebuffer **fb)
{
    sr_result r = make_fb(ctx, 4, false, fb);
    sr_mesh m = { 0 };
    sr_environment *env = NULL;
    if (r == SR_OK) {
        r = sr_make_teapot(ctx, 6, &m);
    }
    if (r == SR_OK) {
        r = sr_make_environment(ctx, NULL, &env);
    }
    sr_mat4 view = camera(), proj = projection(), model = teapot_model();
    if (r == SR_OK) {
        sr_pbr_material mat = sr_pbr_default_material();
        mat.base_color[0] = 0.95f;
        mat.base_color[1] = 0.64f;
        mat.base_color[2] = 0.54f;
        mat.metallic = 1.0f;
        mat.roughness = 0.35f;
        sr_pbr_desc d = { .material = &mat, .model = &model, .view = &view, .projection = &proj,
                          .environment = env };
        d.lights[0] = (sr_light){ .type = SR_LIGHT_DIRECTIONAL, .vector = { -1, -1, -1 },
                                  .intensity = 2.0f };
        r = draw_pbr(ctx, *fb, &m, &d);
    }
    sr_destroy_environment(ctx, env);
    sr_destroy_mesh(ctx, &m);
    return r;
}

/* The program's KHR_lights_punctual falloffs: a spot light's cone edge
 * and a point light's range window cross the teapot. */
static sr_result teapot_spot(sr_context *ctx, sr_framebuffer **fb)
{
    sr_result r = make_fb(ctx, 1, false, fb);
    sr_mesh m = { 0 };
    if (r == SR_OK) {
        r = sr_make_teapot(ctx, 6, &m);
    }
    sr_mat4 view = camera(), proj = projection(), model = teapot_model();
    if (r == SR_OK) {
        sr_pbr_material mat = sr_pbr_default_material();
        mat.metallic = 0.0f;
        mat.roughness = 0.45f;
        sr_pbr_desc d = { .material = &mat, .model = &model, .view = &view, .projection = &proj };
        d.lights[0] = (sr_light){ .type = SR_LIGHT_SPOT, .vector = { 2, 3, 3 },
                                  .direction = { -2, -2.4f, -3 }, .intensity = 40.0f,
                                  .inner_cone = 0.1f, .outer_cone = 0.2f };
        d.lights[1] = (sr_light){ .type = SR_LIGHT_POINT, .vector = { 1.5f, 0.5f, 1.0f },
                                  .color = { 0.4f, 0.6f, 1.0f }, .intensity = 3.0f,
                                  .range = 2.0f };
        r = draw_pbr(ctx, *fb, &m, &d);
    }
    sr_destroy_mesh(ctx, &m);
    return r;
}

static const struct scene {
    const char *name;
    scene_fn draw;
} scenes[] = {
    { "teapot_phong", teapot_phong },   { "teapot_msaa4", teapot_msaa4 },
    { "teapot_msaa16", teapot_msaa16 }, { "lumpy_phong", lumpy_phong },
    { "lumpy_textured", lumpy_textured }, { "lines_points", lines_points },
    { "drawing_2d", drawing_2d },       { "svg_drawing", svg_drawing },
    { "teapot_pbr", teapot_pbr },       { "teapot_spot", teapot_spot },
};
#define SCENE_COUNT (sizeof scenes / sizeof scenes[0])

/* Colour, depth and stencil digests of fb; "-" for a buffer it lacks.
 * Depth is hashed as its float values' bits in little-endian order, so
 * the digest does not depend on the machine's byte order. */
static sr_result digest(sr_context *ctx, const sr_framebuffer *fb, char out[3][65])
{
    int w = sr_framebuffer_width(fb), h = sr_framebuffer_height(fb);
    size_t n = (size_t)w * (size_t)h;
    uint8_t *bytes = malloc(4 * n);
    float *depth = malloc(n * sizeof(float));
    sr_result r = bytes && depth ? SR_OK : SR_OUT_OF_MEMORY;
    sha256 s;
    if (r == SR_OK) {
        r = sr_read_pixels(ctx, fb, 0, 0, w, h, bytes, 4 * (size_t)w);
        sha256_init(&s);
        sha256_update(&s, bytes, 4 * n);
        sha256_final_hex(&s, out[0]);
    }
    strcpy(out[1], "-");
    if (r == SR_OK && sr_framebuffer_depth_format(fb) != SR_DEPTH_NONE) {
        r = sr_read_depth(ctx, fb, 0, 0, w, h, depth, (size_t)w);
        for (size_t i = 0; i < n; i++) {
            uint32_t u;
            memcpy(&u, &depth[i], 4);
            for (int b = 0; b < 4; b++) {
                bytes[4 * i + (size_t)b] = (uint8_t)(u >> (8 * b));
            }
        }
        sha256_init(&s);
        sha256_update(&s, bytes, 4 * n);
        sha256_final_hex(&s, out[1]);
    }
    strcpy(out[2], "-");
    if (r == SR_OK && sr_framebuffer_has_stencil(fb)) {
        r = sr_read_stencil(ctx, fb, 0, 0, w, h, bytes, (size_t)w);
        sha256_init(&s);
        sha256_update(&s, bytes, n);
        sha256_final_hex(&s, out[2]);
    }
    free(bytes);
    free(depth);
    return r;
}

/* The colour buffer as DIR/NAME.png, to look at a scene whose row differs. */
static sr_result write_png(sr_context *ctx, const sr_framebuffer *fb, const char *dir,
                           const char *name)
{
    int w = sr_framebuffer_width(fb), h = sr_framebuffer_height(fb);
    uint8_t *rgba = malloc(4 * (size_t)w * (size_t)h);
    char path[4096];
    snprintf(path, sizeof path, "%s/%s.png", dir, name);
    sr_result r = rgba ? sr_read_pixels(ctx, fb, 0, 0, w, h, rgba, 4 * (size_t)w)
                       : SR_OUT_OF_MEMORY;
    sr_io_error err;
    if (r == SR_OK && (r = sr_write_png(path, w, h, rgba, 4 * (size_t)w, NULL, &err)) != SR_OK) {
        fprintf(stderr, "identity: %s\n", err.message);
    }
    free(rgba);
    return r;
}

/* FIPS 180-4's examples: a wrong SHA-256 would make every table row wrong. */
static bool sha256_self_test(void)
{
    static const struct { const char *in, *hex; } cases[] = {
        { "abc", "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad" },
        { "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq",
          "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1" },
        { "", "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855" },
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        sha256 s;
        char hex[65];
        sha256_init(&s);
        sha256_update(&s, cases[i].in, strlen(cases[i].in));
        sha256_final_hex(&s, hex);
        if (strcmp(hex, cases[i].hex) != 0) {
            fprintf(stderr, "identity: SHA-256(\"%s\") = %s, expected %s\n", cases[i].in, hex,
                    cases[i].hex);
            return false;
        }
    }
    return true;
}

/* The table's row for a scene: its three digests, or false when absent. */
static bool table_row(const char *table, const char *name, char want[3][65])
{
    size_t len = strlen(name);
    for (const char *line = table; *line; line = strchr(line, '\n') ? strchr(line, '\n') + 1 : "") {
        if (strncmp(line, name, len) == 0 && line[len] == ' ') {
            return sscanf(line + len, " %64s %64s %64s", want[0], want[1], want[2]) == 3;
        }
    }
    return false;
}

static char *read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        return NULL;
    }
    char *text = NULL;
    size_t size = 0, cap = 0;
    for (;;) {
        if (size + 4096 + 1 > cap) {
            cap = 2 * cap + 4096 + 1;
            char *grown = realloc(text, cap);
            if (!grown) {
                break;
            }
            text = grown;
        }
        size_t got = fread(text + size, 1, 4096, f);
        size += got;
        if (got < 4096) {
            break;
        }
    }
    fclose(f);
    if (text) {
        text[size] = '\0';
    }
    return text;
}

int main(int argc, char **argv)
{
    bool print = argc > 1 && strcmp(argv[1], "--print") == 0;
    const char *png_dir = argc > 2 && strcmp(argv[1], "--png") == 0 ? argv[2] : NULL;
    const char *path = !print && !png_dir && argc > 1 ? argv[1] : SR_IDENTITY_TABLE;
    if (!sha256_self_test()) {
        return 1;
    }
    char *table = print ? NULL : read_text(path);
    if (!print && !table) {
        perror(path);
        return 1;
    }
    /* Threads and vector kernels from SR_THREADS and SR_SIMD (CTest runs
     * this program once per combination). */
    sr_context *ctx;
    if (sr_make_context(&(sr_context_desc){ 0 }, &ctx) != SR_OK) {
        fprintf(stderr, "identity: cannot make a context\n");
        free(table);
        return 1;
    }
    fprintf(print ? stderr : stdout, "identity: %d threads, SIMD level %d\n",
            sr_context_threads(ctx), (int)sr_context_simd(ctx));
    if (print) {
        printf("# scene colour depth stencil: SHA-256 of RGBA8 pixels, depth floats (bits,\n"
               "# little-endian) and stencil bytes; '-' where the framebuffer has none.\n"
               "# Regenerate with `test_identity --print` (docs/portability.md).\n");
    }
    int failed = 0;
    for (size_t i = 0; i < SCENE_COUNT; i++) {
        sr_framebuffer *fb = NULL;
        char got[3][65], want[3][65];
        sr_result r = scenes[i].draw(ctx, &fb);
        if (r == SR_UNSUPPORTED) {
            printf("%s: skipped (this build lacks what the scene needs)\n", scenes[i].name);
            sr_destroy_framebuffer(ctx, fb);
            continue;
        }
        if (r == SR_OK) {
            r = digest(ctx, fb, got);
        }
        if (r == SR_OK && png_dir) {
            r = write_png(ctx, fb, png_dir, scenes[i].name);
        }
        sr_destroy_framebuffer(ctx, fb);
        if (r != SR_OK) {
            fprintf(stderr, "identity: %s: %s (%s)\n", scenes[i].name, sr_result_name(r),
                    sr_context_error(ctx));
            failed++;
            continue;
        }
        if (print) {
            printf("%s %s %s %s\n", scenes[i].name, got[0], got[1], got[2]);
            continue;
        }
        if (!table_row(table, scenes[i].name, want)) {
            printf("%s: FAIL: no row in %s\n", scenes[i].name, path);
            failed++;
            continue;
        }
        static const char *const buffers[3] = { "colour", "depth", "stencil" };
        int failed_before = failed;
        for (int b = 0; b < 3; b++) {
            if (strcmp(got[b], want[b]) != 0) {
                printf("%s: FAIL: %s %s, table %s\n", scenes[i].name, buffers[b], got[b], want[b]);
                failed++;
            }
        }
        if (failed == failed_before) {
            printf("%s: ok\n", scenes[i].name);
        }
    }
    sr_destroy_context(ctx);
    free(table);
    if (!print) {
        printf("identity: %s\n", failed ? "FAILED" : "all digests match");
    }
    return failed ? 1 : 0;
}
