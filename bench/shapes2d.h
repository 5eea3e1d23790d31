/* shapes2d.h - the 2D shape benchmark modelled on Blend2D's bl_bench
 * (rectangles, polygons of 10/20/40 vertices, curves; 8 to 256 px; solid,
 * linear and radial gradient, pattern paint), softrast's SVG renderer and
 * its paint API (sr_fill_path_paint) against cairo in the same run; and the icon-directory benchmark, every SVG of an icon
 * theme (a fixed subset) rendered in one process against rsvg-convert
 * started once per file. */
#ifndef SR_BENCH_SHAPES2D_H
#define SR_BENCH_SHAPES2D_H

#include "softrast.h"

/* Print the result lines; return false on failure (after a message). */
/* The paints of a comma-separated list of names as a bit set (bit k:
 * paint k of solid, linear, radial, pattern); 0 after a message when a
 * name is unknown or the list empty. */
unsigned bench_shapes2d_paints(const char *list);
/* The same for shapes (rect, poly10, poly20, poly40, curves) and sizes
 * (8, 16, 32, 64, 128, 256, in pixels). */
unsigned bench_shapes2d_shapes(const char *list);
unsigned bench_shapes2d_sizes(const char *list);
/* The cases to run: each a list as above, or NULL for all. */
typedef struct shapes2d_cases {
    const char *paints, *shapes, *sizes;
} shapes2d_cases;
bool bench_shapes2d(sr_context *ctx, int frames, bool compare, const shapes2d_cases *only);
bool bench_icons(int frames);

#endif
