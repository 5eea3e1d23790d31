/* svg.h - `softrast svg`, internal: the pieces of the SVG reader shared
 * between svg.c (document walk and drawing) and svg_color.c. */
#ifndef SR_SVG_H
#define SR_SVG_H

#include "softrast.h"

typedef enum svg_paint_kind {
    SVG_PAINT_INVALID = 0,   /* not a color */
    SVG_PAINT_NONE,          /* "none" */
    SVG_PAINT_COLOR,         /* *out set, alpha 1 */
    SVG_PAINT_UNSUPPORTED,   /* url(...) paint servers, currentColor */
} svg_paint_kind;

/* An SVG 1.1 color: keyword, #rgb, #rrggbb, rgb(r, g, b) (integers or
 * percentages) or "none". */
svg_paint_kind svg_parse_color(const char *s, sr_rgba *out);

#endif
