/* bands.c - a frame drawn band by band (target stage): one framebuffer
 * whose memory holds a band's rows, its pointers offset so that each
 * band's rows sit where the frame's would.  The draws see the frame's
 * coordinates unchanged, so every band gets the bytes of the whole-frame
 * render.  Called from the application thread. */
#include "target/framebuffer.h"
#include "target/pixel_format.h"
#include "context.h"
#include "fragment/depth.h"
#include "raster/fixed.h"

#include <stdint.h>
#include <string.h>

/* p moved by `rows` rows of `per_row` elements of `size` bytes, as an
 * address: the offset pointer points outside the block it came from. */
static void *shift(void *p, int rows, size_t per_row, size_t size)
{
    if (!p) {
        return NULL;
    }
    return (void *)((uintptr_t)p + (uintptr_t)((intptr_t)rows * (intptr_t)(per_row * size)));
}

/* Make fb's memory hold the rows [row0, row1) (row1 - row0 at most the
 * rows it was made with). */
static void hold_rows(sr_framebuffer *fb, int row0, int row1)
{
    int back = fb->row0 - row0;
    size_t n = (size_t)fb->width * (size_t)fb->samples;
    fb->color = shift(fb->color, back, n, sizeof *fb->color);
    fb->depth = shift(fb->depth, back, n, (size_t)sr__depth_size(fb));
    fb->stencil = shift(fb->stencil, back, n, 1);
    fb->resolved = shift(fb->resolved, back, (size_t)fb->width, sizeof *fb->resolved);
    fb->row0 = row0;
    fb->row1 = row1;
}

/* What sr_make_framebuffer leaves: every tile a pending clear to
 * transparent black, the far depth and stencil 0, nothing drawn. */
static void start_fresh(sr_framebuffer *fb)
{
    size_t tiles = (size_t)fb->tiles_x * (size_t)fb->tiles_y;
    fb->clear_color = 0;
    fb->clear_depth = fb->depth ? sr__depth_quantize(1.0, fb->depth_bits) : 0;
    fb->clear_stencil = 0;
    memset(fb->tile_pending, SR_TILE_PENDING_COLOR | (fb->depth ? SR_TILE_PENDING_DEPTH : 0) |
                             (fb->stencil ? SR_TILE_PENDING_STENCIL : 0), tiles);
    memset(fb->tile_memo, 0, tiles * sizeof *fb->tile_memo);
}

/* A framebuffer of the frame's size holding `rows` rows: made with that
 * height, then given the frame's height and tile grid. */
static sr_result make_band_framebuffer(sr_context *ctx, const sr_bands_desc *d, sr_framebuffer **out)
{
    sr_framebuffer *fb;
    sr_result r = sr_make_framebuffer(ctx, &(sr_framebuffer_desc){
        .width = d->width, .height = d->band_rows, .depth_format = d->depth_format,
        .samples = d->samples, .stencil = d->stencil }, &fb);
    if (r != SR_OK) {
        return r;
    }
    sr__free(ctx, fb->tile_pending);
    sr__free(ctx, fb->tile_memo);
    fb->height = d->height;
    fb->tiles_y = (d->height + SR_TILE_SIZE - 1) >> SR_TILE_ORDER;
    size_t tiles = (size_t)fb->tiles_x * (size_t)fb->tiles_y;
    fb->tile_pending = sr__calloc(ctx, tiles, 1);
    fb->tile_memo = sr__calloc(ctx, tiles, sizeof *fb->tile_memo);
    fb->row1 = d->band_rows;
    if (!fb->tile_pending || !fb->tile_memo) {
        sr_destroy_framebuffer(ctx, fb);
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_render_bands: out of memory");
    }
    *out = fb;
    return SR_OK;
}

static sr_result check_desc(sr_context *ctx, const sr_bands_desc *d)
{
    if (!d) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_render_bands: desc is NULL");
    }
    if (!d->draw || !d->output) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_bands_desc.%s is NULL",
                        d->draw ? "output" : "draw");
    }
    if (d->height <= 0 || d->height > SR_MAX_FRAMEBUFFER_SIZE) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_bands_desc.height must be 1 .. %d (got %d)",
                        SR_MAX_FRAMEBUFFER_SIZE, d->height);
    }
    if (d->band_rows < 1 || d->band_rows > d->height) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_bands_desc.band_rows must be 1 .. height %d (got %d)",
                        d->height, d->band_rows);
    }
    if ((unsigned)d->format > SR_PIXEL_RGB332) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_bands_desc.format %d is not a format",
                        (int)d->format);
    }
    return SR_OK;
}

sr_result sr_render_bands(sr_context *ctx, const sr_bands_desc *desc)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_render_bands: ctx is NULL");
    }
    sr_result r = check_desc(ctx, desc);
    sr_framebuffer *fb = NULL;
    if (r == SR_OK) {
        r = make_band_framebuffer(ctx, desc, &fb);
    }
    if (r != SR_OK) {
        return r;
    }
    const sr_bands_desc *d = desc;
    sr_pixel_format format = d->format == SR_PIXEL_DEFAULT ? SR_PIXEL_RGBA8 : d->format;
    for (int y = 0; y < d->height && r == SR_OK; y += d->band_rows) {
        int rows = d->height - y < d->band_rows ? d->height - y : d->band_rows;
        hold_rows(fb, y, y + rows);
        start_fresh(fb);
        sr_band band = { .y = y, .rows = rows, .width = d->width, .format = format };
        r = d->draw(ctx, fb, &band, d->user);
        if (r != SR_OK) {
            break;
        }
        /* The band's image is the band framebuffer's own memory, which
         * the next band clears: the small formats are packed over it. */
        uint8_t *image = (uint8_t *)(sr__fb_color_image(fb) + (size_t)y * (size_t)d->width);
        size_t pixels = (size_t)d->width * (size_t)rows;
        if (format != SR_PIXEL_RGBA8) {
            sr__pack_pixels(image, image, pixels, format);
        }
        band.pixels = image;
        band.stride = (size_t)d->width * sr__pixel_size(format);
        d->output(&band, d->user);
    }
    hold_rows(fb, 0, d->band_rows);
    fb->height = d->band_rows;
    sr_destroy_framebuffer(ctx, fb);
    if (r == SR_OK) {
        sr__ok(ctx);
    }
    return r;
}
