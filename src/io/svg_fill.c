/* svg_fill.c - the SVG reader's blend of a color into its layers (src/io):
 * source-over in straight alpha, as the 2D fills blend.  Used by svg.c. */
#include "io/svg.h"

#include "draw2d/paint_fill.h"

void svg_blend(uint8_t *d, sr_rgba c, float cov)
{
    uint8_t s[4] = { sr__paint_unorm8(c.r), sr__paint_unorm8(c.g), sr__paint_unorm8(c.b), 0 };
    float a = (c.a < 0 ? 0 : c.a > 1 ? 1 : c.a) * cov;
    if (a > 0.0f) {
        sr__blend_rgba8(d, s, a);
    }
}
