/* framebuffer.h - render target storage (target stage).  Color is RGBA8 in
 * memory order r, g, b, a, row-major from the top row.  Depth of every
 * format is kept as its *quantized* value, so one unsigned compare serves
 * all formats: D16/D24/D32 store k for k/(2^n - 1), D32F stores the bits
 * of a non-negative float, which order like integers.  D16 keeps each
 * value in a uint16, the others in a uint32 (depth16); the rasterizers
 * widen what they load to 32 bits and compare there, so the width of the
 * storage never changes a result. */
#ifndef SR_FRAMEBUFFER_H
#define SR_FRAMEBUFFER_H

#include "softrast.h"

/* A clear does not touch memory: it records the value and marks every
 * tile (SR_TILE_SIZE square) pending.  The thread that next rasterizes a
 * tile clears it first, while the tile is about to be in its cache
 * anyway; reading pixels out resolves the tiles nobody drew. */
#define SR_TILE_PENDING_COLOR 1u
#define SR_TILE_PENDING_DEPTH 2u
#define SR_TILE_PENDING_STENCIL 4u
#define SR_TILE_PENDING_ALL 7u
/* Not a pending clear but what the last one left: the tile's color memory
 * holds clear_color in every sample, written by a read-out and not drawn
 * on since.  A clear to the same color leaves such a tile alone, so the
 * background of a frame redrawn with the same clear is written once, not
 * once a frame.  Anything that writes color drops the flag. */
#define SR_TILE_CLEAN_COLOR 8u
/* The tile's base for a component: outside the tile's drawn rectangle
 * (sr_tile_memo) the component still holds what the tile's last whole
 * clear of it wrote, the memo's value.  A clear to that same value then
 * writes only the drawn rectangle: a mesh redrawn each frame over one
 * background clears the boxes of what it drew, not whole tiles (for
 * spot, a third fewer bytes).  Anything that writes a component outside
 * the tile jobs, which keep the rectangle, drops its flag. */
#define SR_TILE_BASE_COLOR 16u
#define SR_TILE_BASE_DEPTH 32u
#define SR_TILE_BASE_STENCIL 64u
#define SR_TILE_BASE_ALL 112u
/* What a tile knows of its color from clears alone (clean, base): a write
 * of color anywhere but the tile jobs drops both. */
#define SR_TILE_COLOR_FROM_CLEARS (SR_TILE_CLEAN_COLOR | SR_TILE_BASE_COLOR)

/* Per tile: its base values and the rectangle drawn on since (in pixels
 * from the tile's corner, empty when x0 >= x1), the union of the boxes
 * the tile jobs gave the rasterizers there. */
typedef struct sr_tile_memo {
    uint32_t color, depth, stencil;
    uint8_t x0, y0, x1, y1;         /* up to SR_TILE_SIZE = 128 */
} sr_tile_memo;

/* Multisampled storage keeps a pixel's samples side by side: sample s of
 * pixel (x, y) is element (y * width + x) * samples + s of color, depth
 * and stencil.  With one sample this is the plain image, so every
 * single-sample path indexes exactly as before; with n, one pixel's
 * samples share a cache line and the per-pixel shading result is written
 * to them together. */
struct sr_framebuffer {
    int width, height;
    /* The rows [row0, row1) are in memory: all of them, except in a band
     * framebuffer (sr_render_bands), whose pointers below are offset so
     * that row y is still at y * width, and whose draws and clears stop at
     * the band's edges. */
    int row0, row1;
    int samples;                    /* 1, 2, 4, 8, 16 */
    bool wide_stores;               /* its context's level is AVX-512: clears in 64-byte stores */
    sr_depth_format depth_format;   /* resolved: never SR_DEPTH_DEFAULT */
    int depth_bits;                 /* 16, 24, 32; 0 for D32F */
    uint32_t *color;
    void *depth;                    /* NULL with SR_DEPTH_NONE; sr__depth_at */
    /* D16: depth samples are uint16, else uint32.  A bool, which no store
     * of depth or color words may alias: the compiler keeps it in a
     * register across a kernel's stores instead of reloading it. */
    bool depth16;
    uint8_t *stencil;               /* NULL without a stencil buffer */
    uint32_t *resolved;             /* samples > 1: the box-filtered image read out */
    int tiles_x, tiles_y;
    uint8_t *tile_pending;          /* SR_TILE_PENDING_* per tile */
    sr_tile_memo *tile_memo;        /* per tile */
    uint32_t clear_color;           /* packed RGBA8 of the last clear */
    uint32_t clear_depth;           /* quantized depth of the last clear */
    uint8_t clear_stencil;
};

/* Whether fb holds only some of its rows (a band of sr_render_bands):
 * what would touch every row refuses it. */
static inline bool sr__fb_is_band(const sr_framebuffer *fb)
{
    return fb->row0 != 0 || fb->row1 != fb->height;
}

/* Bytes a depth sample of fb takes. */
static inline int sr__depth_size(const sr_framebuffer *fb)
{
    return fb->depth16 ? 2 : 4;
}

/* Depth sample i of fb (which has depth), widened to 32 bits, and its
 * store: where the scalar paths meet the storage width. */
static inline uint32_t sr__depth_at(const sr_framebuffer *fb, size_t i)
{
    if (fb->depth16) {
        return ((const uint16_t *)fb->depth)[i];
    }
    return ((const uint32_t *)fb->depth)[i];
}

static inline void sr__depth_put(sr_framebuffer *fb, size_t i, uint32_t q)
{
    if (fb->depth16) {
        ((uint16_t *)fb->depth)[i] = (uint16_t)q;
    } else {
        ((uint32_t *)fb->depth)[i] = q;
    }
}

/* The standard positions as q8 offsets from the pixel centre, x then y
 * (docs/raster-rules.md §9.1: 16 x the D3D offset in 1/16 px, -128..112).  NULL
 * for a count that is not 1, 2, 4, 8 or 16. */
const int8_t (*sr__sample_offsets(int samples))[2];

/* Before drawing on a tile (tile = ty * tiles_x + tx): carry out its
 * pending clears, in 64-byte stores if `wide` (the draw's
 * sr_draw_state.wide_stores); the tile is no longer clean. */
void sr__tile_resolve(sr_framebuffer *fb, int tile, bool wide);
/* After drawing on a tile: the rasterizers were given the pixels
 * [x0, x1) x [y0, y1) of it (framebuffer coordinates, inside the tile). */
void sr__tile_drawn(sr_framebuffer *fb, int tile, int x0, int y0, int x1, int y1);
/* Before reading: carry out every pending clear of the given components.
 * The tiles whose color this writes become clean. */
void sr__fb_resolve(sr_framebuffer *fb, unsigned components);
/* The single-sampled RGBA8 image of fb, pending clears carried out
 * (multisampled: resolved into fb->resolved); row y at y * width. */
const uint32_t *sr__fb_color_image(const sr_framebuffer *fb);
/* Before writing color anywhere outside the tile jobs: carry out the
 * pending color clears and drop every tile's clean flag. */
void sr__fb_begin_write(sr_framebuffer *fb);
/* Before a 2D drawing function touches fb: the 2D toolkit draws into
 * single-sampled images only (SR_INVALID_ARG naming `fn` otherwise);
 * carries out the pending color clears. */
sr_result sr__fb_begin_2d(sr_context *ctx, const char *fn, sr_framebuffer *fb);

#endif
