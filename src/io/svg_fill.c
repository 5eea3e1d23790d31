/* svg_fill.c - the SVG reader's blend of a color into its layers (src/io):
 * source-over in straight alpha, as the 2D fills blend.  Used by svg.c. */
#include "io/svg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Source-over of the RGBA8 color s at opacity a (0 < a <= 1) onto d. */
static void blend_rgba8(uint8_t *d, const uint8_t *s, float a)
{
    if (d[3] == 0) {
        /* Over an empty pixel the blend below has oa = a, so a / oa = 1
         * and keep 0 exactly: the source's color at alpha a, undivided. */
        memcpy(d, s, 3);
        d[3] = svg_unorm8(a);
        return;
    }
    /* Straight alpha: the destination's color counts by its alpha. */
    float da = d[3] * (1.0f / 255.0f), keep = 1.0f - a, oa = a + da * keep;
    if (d[3] < 255) {
        keep = oa > 0.0f ? da * keep / oa : 0.0f;
        a = oa > 0.0f ? a / oa : 0.0f;
    }
    for (int i = 0; i < 3; i++) {
        d[i] = svg_unorm8((s[i] * a + d[i] * keep) * (1.0f / 255.0f));
    }
    d[3] = svg_unorm8(oa);
}

void svg_blend(uint8_t *d, sr_rgba c, float cov)
{
    uint8_t s[4] = { svg_unorm8(c.r), svg_unorm8(c.g), svg_unorm8(c.b), 0 };
    float a = (c.a < 0 ? 0 : c.a > 1 ? 1 : c.a) * cov;
    if (a > 0.0f) {
        blend_rgba8(d, s, a);
    }
}
