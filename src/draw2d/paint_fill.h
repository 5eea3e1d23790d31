/* paint_fill.h - draw2d stage, internal: fills painted with more than a
 * color.  A paint server (a linear or radial gradient, an RGBA8 image)
 * evaluated a row at a time over a polygon's covered span and blended
 * source-over in straight alpha.  Behind sr_fill_polygon_paint and
 * sr_fill_path_paint (paint_api.c) and through them the SVG reader's
 * gradients, patterns and images; the calls run on the caller's thread. */
#ifndef SR_DRAW2D_PAINT_FILL_H
#define SR_DRAW2D_PAINT_FILL_H

#include "softrast.h"

#include <stdbool.h>
#include <stdint.h>
#include <string.h>

/* A channel in [0, 1] as an 8-bit code, rounded (NaN and below 0: 0), as
 * the 2D fills quantize: every paint server packs through it. */
static inline uint8_t sr__paint_unorm8(float v)
{
    return !(v > 0.0f) ? 0 : v >= 1.0f ? 255 : (uint8_t)(v * 255.0f + 0.5f);
}

/* Source-over of the RGBA8 color s at opacity a (0 < a <= 1) onto d, in
 * straight alpha: the painted fills' blend, and the SVG reader's into its
 * layers (inline, as softrast_io reaches no internal symbol of the core). */
static inline void sr__blend_rgba8(uint8_t *d, const uint8_t *s, float a)
{
    if (d[3] == 0) {
        /* Over an empty pixel the blend below has oa = a, so a / oa = 1
         * and keep 0 exactly: the source's color at alpha a, undivided. */
        memcpy(d, s, 3);
        d[3] = sr__paint_unorm8(a);
        return;
    }
    /* Straight alpha: the destination's color counts by its alpha. */
    float da = d[3] * (1.0f / 255.0f), keep = 1.0f - a, oa = a + da * keep;
    if (d[3] < 255) {
        keep = oa > 0.0f ? da * keep / oa : 0.0f;
        a = oa > 0.0f ? a / oa : 0.0f;
    }
    for (int i = 0; i < 3; i++) {
        d[i] = sr__paint_unorm8((s[i] * a + d[i] * keep) * (1.0f / 255.0f));
    }
    d[3] = sr__paint_unorm8(oa);
}

/* ---- gradients (gradient.c) ------------------------------------------- */

/* Cells of a gradient's color table over t in [0, 1).  At 1024, a cell
 * between stops more than 0.26 apart changes a channel by less than 0.98
 * codes, so its centre's color is within half a code of each exact one
 * and the pixel within one code; the other cells (stops closer or inside
 * the cell) evaluate their pixels alone. */
#define SR__GRADIENT_LUT 1024

/* A gradient resolved for one fill: its geometry in gradient space and
 * the map from pixel coordinates into that space; the color table is
 * filled as the fill's pixels ask for it. */
typedef struct sr__gradient {
    bool radial;
    double x1, y1, x2, y2;       /* linear: the gradient vector */
    double cx, cy, r, fx, fy, fr;/* radial: end circle, focal circle */
    sr_gradient_spread spread;
    double inv[6];               /* pixel -> gradient space (a b c d e f) */
    int n_stops;                 /* >= 1 */
    /* Cell k of the table: 0 until a pixel asks for it (zeroed with the
     * stops set), then 1 when lut[k] is within half a code of every color
     * of the cell, 2 when no one color is (a stop inside, or a fast
     * change): those pixels are evaluated alone.  Cell SR__GRADIENT_LUT
     * is t >= 1. */
    uint8_t lut_state[SR__GRADIENT_LUT + 1];
    double offset[SR_MAX_GRADIENT_STOPS]; /* non-decreasing, in [0, 1] */
    sr_rgba color[SR_MAX_GRADIENT_STOPS]; /* straight alpha, opacity included */
    uint32_t lut[SR__GRADIENT_LUT + 1];   /* RGBA8 in memory order, straight alpha */
} sr__gradient;

/* A paint along a row: the straight-alpha RGBA8 colors (memory order r,
 * g, b, a) at the centres of pixels x..x+n-1 of row y.  True when they
 * depend on x alone (every row gets the same bytes at the same x).  The
 * paint is not const: it may keep tables it fills as it goes. */
typedef bool (*sr__paint_span_fn)(void *paint, int x, int y, int n, uint32_t *out);

/* A gradient (sr__gradient) as an sr__paint_span_fn. */
bool sr__gradient_span(void *g, int x, int y, int n, uint32_t *out);

/* ---- images (image_paint.c) ------------------------------------------- */

/* An RGBA8 image (straight alpha) as a paint: pixel coordinates map into
 * it by inv; sampled bilinearly, repeated (a pattern tile) or its edge
 * texels extended (an image: the fill stays inside it). */
typedef struct sr__image {
    const uint8_t *rgba;
    int w, h;
    size_t stride;               /* bytes from a row to the next, >= 4 w */
    double inv[6];               /* pixel -> image texels (a b c d e f) */
    bool repeat;
} sr__image;

/* An image (sr__image) as an sr__paint_span_fn. */
bool sr__image_span(void *image, int x, int y, int n, uint32_t *out);

/* ---- painted fills (paint_fill.c) --------------------------------------- */

/* Fill a polygon in pixel coordinates with a paint times opacity: the
 * coverage is sr_polygon_coverage's (the same pixels and weights as
 * sr_fill_polygon with that desc), the paint is evaluated over each row's
 * covered span and blended source-over in straight alpha, the color
 * quantized to RGBA8 first.  The paint is valid (the caller checked); the
 * polygon is checked here, messages naming the public call fn. */
sr_result sr__fill_paint(sr_context *ctx, const char *fn, sr_framebuffer *fb,
                         const sr_polygon2 *poly, const sr_fill_desc *desc,
                         sr__paint_span_fn span, void *paint, float opacity);

#endif
