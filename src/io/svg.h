/* svg.h - the SVG reader (src/io), internal: the document walk and drawing
 * behind sr_render_svg (svg.c) and its colors (svg_color.c).  The public
 * entry points and limits are in softrast_io.h. */
#ifndef SR_SVG_H
#define SR_SVG_H

#include "softrast_io.h"

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
