// hello.c - the smallest complete softrast program: one triangle with a
// color at each corner, written as a binary PPM.  softrast.h carries this
// file's code (from the first #include on) as its "Use" example, and
// tests/test_examples.c checks that the two are the same and runs it.
#include <softrast.h>

#include <stdio.h>

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "hello.ppm";
    enum { W = 64, H = 48 };
    sr_context *ctx;
    if (sr_make_context(&(sr_context_desc){0}, &ctx) != SR_OK) {
        return 1;
    }
    sr_framebuffer *fb = NULL;
    sr_framebuffer_desc fb_desc = { .width = W, .height = H };  // depth D24 by default
    sr_result r = sr_make_framebuffer(ctx, &fb_desc, &fb);
    if (r == SR_OK) {
        // Color to dark gray; depth to the far value, ready for the LESS test.
        sr_clear(ctx, fb, &(sr_clear_desc){ .color = { 0.1f, 0.1f, 0.1f, 1 } });
        const float xyz[] = { -0.8f, -0.8f, 0, 0.8f, -0.8f, 0, 0, 0.8f, 0 };
        const float rgb[] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
        // A zeroed state draws unlit, depth-tested, every channel written.
        r = sr_draw(ctx, fb, &(sr_state){0},
                    &(sr_draw_desc){ .positions = xyz, .vertex_count = 3,
                                     .colors = rgb, .color_size = 3 });
    }
    if (r == SR_OK) {
        const uint8_t *rgba = sr_framebuffer_pixels(fb);  // row 0 at the top
        FILE *f = fopen(path, "wb");
        if (f) {
            fprintf(f, "P6\n%d %d\n255\n", W, H);
            for (int i = 0; i < W * H; i++) {
                fwrite(rgba + 4 * i, 1, 3, f);
            }
        }
        if (!f || fclose(f) != 0) {
            perror(path);
            r = SR_IO_ERROR;
        }
    } else {
        fprintf(stderr, "hello: %s\n", sr_context_error(ctx));
    }
    sr_destroy_framebuffer(ctx, fb);
    sr_destroy_context(ctx);
    return r == SR_OK ? 0 : 1;
}
