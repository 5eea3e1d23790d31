/* main.c - a program that uses an installed softrast as any other project
 * would: only the public headers and libraries.  It draws a red triangle
 * over a black 32x32 framebuffer, writes it as a PNG with softrast_io,
 * reads the file back and checks a pixel inside the triangle and one
 * outside, and parses an empty glTF document.  Exit status 0 when all
 * are right. */
#include <softrast.h>
#include <softrast_io.h>

#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: downstream OUT.png\n");
        return 2;
    }
    enum { W = 32, H = 32 };
    sr_context *ctx = NULL;
    sr_framebuffer *fb = NULL;
    if (sr_make_context(NULL, &ctx) != SR_OK ||
        sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = W, .height = H }, &fb) != SR_OK) {
        fprintf(stderr, "downstream: cannot make a context and framebuffer\n");
        return 1;
    }
    /* Clip space with the default identity matrices: the triangle covers
     * the framebuffer's lower left half, its corner (0, 0) stays black. */
    const float xyz[] = { -1, -1, 0, 1, -1, 0, -1, 1, 0 };
    const float rgba[] = { 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1 };
    sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0, 0, 0, 1 } });
    sr_result r = sr_draw(ctx, fb, &(sr_state){ 0 },
                          &(sr_draw_desc){ .positions = xyz, .colors = rgba, .vertex_count = 3 });
    if (r != SR_OK) {
        fprintf(stderr, "downstream: %s\n", sr_context_error(ctx));
        return 1;
    }
    sr_io_error err;
    int w = 0, h = 0;
    uint8_t *px = NULL;
    if (sr_write_png(argv[1], W, H, sr_framebuffer_pixels(fb), W * 4, NULL, &err) != SR_OK ||
        sr_read_png(argv[1], NULL, &w, &h, &px, &err) != SR_OK) {
        fprintf(stderr, "downstream: %s\n", err.message);
        return 1;
    }
    /* The glTF reader too: linked from the static archive it brings the
     * libraries it decodes with (libdraco's C++ among them). */
    static const char doc[] = "{\"asset\":{\"version\":\"2.0\"}}";
    sr_scene *scene = NULL;
    sr_result parsed = sr_parse_gltf(ctx, "empty.gltf", (const uint8_t *)doc, sizeof doc - 1,
                                     NULL, &scene, &err);
    if (sr_io_have_gltf() ? parsed != SR_OK : parsed != SR_UNSUPPORTED) {
        fprintf(stderr, "downstream: %s\n", err.message);
        return 1;
    }
    sr_destroy_scene(ctx, scene);
    const uint8_t *in = px + ((size_t)(H - 4) * W + 4) * 4;  /* near the lower left corner */
    const uint8_t *out = px;                                 /* the upper left corner */
    int ok = w == W && h == H && in[0] == 255 && in[1] == 0 && in[2] == 0 &&
             out[0] == 0 && out[1] == 0 && out[2] == 0;
    printf("downstream: %dx%d, inside %d,%d,%d, outside %d,%d,%d: %s\n", w, h, in[0], in[1],
           in[2], out[0], out[1], out[2], ok ? "ok" : "WRONG");
    free(px);
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
    return ok ? 0 : 1;
}
