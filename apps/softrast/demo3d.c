/* demo3d.c - the labelled panel grid and the shared geometry of the 3D
 * pipeline demos (see demo3d.h). */
#include "demo3d.h"

#include "cli.h"
#include "demo.h"

#include <math.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static const sr_rgba PAGE = { 0.93f, 0.93f, 0.93f, 1 };
static const sr_rgba LABEL = { 0.1f, 0.1f, 0.12f, 1 };

int demo3d_begin(demo3d *d, sr_context *ctx, const char *name, demo3d_layout layout,
                 int scale, const char *const *labels, int count)
{
    *d = (demo3d){ ctx, name, NULL, layout, scale > 0 ? scale : 1, 2, SR_OK };
    /* One label size for the whole image: twice the font when every label
     * fits its cell at that size. */
    for (int i = 0; i < count; i++) {
        if (sr_text_width(labels[i], 2) > layout.cell_w * d->scale) {
            d->label_scale = 1;
        }
    }
    int w = demo3d_grid_width(layout, d->scale), h = demo3d_grid_height(layout, d->scale);
    if (demo_check_image(name, d->scale, w, h) != EXIT_OK) {
        return EXIT_USAGE;
    }
    if (sr_make_framebuffer(ctx, &(sr_framebuffer_desc){ .width = w, .height = h,
                                                         .depth_format = SR_DEPTH_NONE },
                            &d->out) != SR_OK) {
        return demo3d_fail(d);
    }
    sr_clear(ctx, d->out, &(sr_clear_desc){ .color = { PAGE.r, PAGE.g, PAGE.b, 1 } });
    return EXIT_OK;
}

sr_result demo3d_panel(demo3d *d, sr_depth_format depth, sr_framebuffer **out)
{
    return sr_make_framebuffer(d->ctx, &(sr_framebuffer_desc){ .width = d->layout.cell_w,
                                                               .height = d->layout.cell_h,
                                                               .depth_format = depth },
                               out);
}

void demo3d_blit(demo3d *d, int index, const sr_framebuffer *panel, const char *label)
{
    if (!panel || sr_framebuffer_width(panel) != d->layout.cell_w ||
        sr_framebuffer_height(panel) != d->layout.cell_h) {
        return;
    }
    int ox, oy;
    demo3d_cell_origin(d->layout, d->scale, 0, index, &ox, &oy);
    int cw = d->layout.cell_w * d->scale;
    char text[96];
    strncpy(text, label, sizeof text - 1);
    text[sizeof text - 1] = 0;
    while (sr_text_width(text, d->label_scale) > cw && strlen(text) > 1) {
        text[strlen(text) - 1] = 0;
    }
    sr_draw_text(d->ctx, d->out, ox, oy - 8 * d->label_scale - 6, d->label_scale, text, LABEL);
    if (d->error == SR_OK) {
        d->error = demo_magnify(d->ctx, d->out, ox, oy, panel, d->scale, NULL);
    }
}

int demo3d_finish(demo3d *d, sr_framebuffer **out)
{
    if (d->error != SR_OK) {
        return demo3d_fail(d);
    }
    *out = d->out;
    d->out = NULL;
    return EXIT_OK;
}

int demo3d_fail(demo3d *d)
{
    /* A blit that ran out of memory before reaching the context left it
     * no message. */
    const char *why = sr_context_error(d->ctx);
    cli_error("demo %s: %s", d->name, why[0] ? why : sr_result_text(d->error));
    sr_destroy_framebuffer(d->ctx, d->out);
    d->out = NULL;
    return EXIT_FAILURE_RUN;
}

void demo3d_sphere(int stacks, int slices, float *pos, float *nrm, uint32_t *idx)
{
    int k = 0;
    for (int i = 0; i <= stacks; i++) {
        double phi = M_PI * i / stacks; /* from the north pole */
        for (int j = 0; j <= slices; j++) {
            double theta = 2.0 * M_PI * j / slices;
            float p[3] = { (float)(sin(phi) * sin(theta)), (float)cos(phi),
                           (float)(sin(phi) * cos(theta)) };
            memcpy(pos + 3 * k, p, sizeof p);
            memcpy(nrm + 3 * k, p, sizeof p);
            k++;
        }
    }
    k = 0;
    for (int i = 0; i < stacks; i++) {
        for (int j = 0; j < slices; j++) {
            uint32_t a = (uint32_t)(i * (slices + 1) + j), b = a + (uint32_t)(slices + 1);
            /* a is above b; theta grows towards +x seen from +z, so
             * a, b, b+1 winds counter-clockwise from outside */
            uint32_t q[6] = { a, b, b + 1, a, b + 1, a + 1 };
            memcpy(idx + k, q, sizeof q);
            k += 6;
        }
    }
}

bool demo3d_project(const sr_mat4 *proj, const sr_mat4 *view, float x0, float y0, float w,
                    float h, sr_vec3 p, sr_point2 *out)
{
    sr_mat4 pv = sr_mat4_mul(proj, view);
    sr_vec4 c = sr_mat4_mul_vec4(&pv, (sr_vec4){ p.x, p.y, p.z, 1 });
    if (!(c.w > 0)) {
        return false;
    }
    /* divide by w, then S: NDC -1..1 onto the viewport's pixel edges, y down */
    out->x = x0 + (c.x / c.w + 1.0) * 0.5 * w;
    out->y = y0 + (1.0 - c.y / c.w) * 0.5 * h;
    return true;
}
