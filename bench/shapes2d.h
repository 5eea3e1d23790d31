/* shapes2d.h - the 2D shape benchmark modelled on Blend2D's bl_bench
 * (rectangles, polygons of 10/20/40 vertices, curves; 8 to 256 px; solid,
 * linear and radial gradient paint), softrast's SVG renderer against cairo
 * in the same run; and the icon-directory benchmark, every SVG of an icon
 * theme (a fixed subset) rendered in one process against rsvg-convert
 * started once per file. */
#ifndef SR_BENCH_SHAPES2D_H
#define SR_BENCH_SHAPES2D_H

#include "softrast.h"

/* Print the result lines; return false on failure (after a message).
 * only: NULL for all, else the --cases list (shapes, paints, sizes). */
bool bench_shapes2d(sr_context *ctx, int frames, bool compare, const char *only);
bool bench_icons(int frames);

#endif
