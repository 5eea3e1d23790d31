/* svg.h - `softrast svg`, internal: the SVG reader (svg.c: document walk
 * and drawing, from a buffer in memory), its colors (svg_color.c), and the
 * command around them (svg_cmd.c: options, the file, the PNG).  The fuzz
 * target tests/fuzz/fuzz_svg.c drives svg_render directly. */
#ifndef SR_SVG_H
#define SR_SVG_H

#include "cli.h"
#include "softrast.h"

#include <stddef.h>
#include <stdio.h>

typedef enum svg_paint_kind {
    SVG_PAINT_INVALID = 0,   /* not a color */
    SVG_PAINT_NONE,          /* "none" */
    SVG_PAINT_COLOR,         /* *out set, alpha 1 */
    SVG_PAINT_UNSUPPORTED,   /* url(...) paint servers, currentColor */
} svg_paint_kind;

/* An SVG 1.1 color: keyword, #rgb, #rrggbb, rgb(r, g, b) (integers or
 * percentages) or "none". */
svg_paint_kind svg_parse_color(const char *s, sr_rgba *out);

/* Documented limits (docs/robustness.md, "Bounded work").  They keep the
 * cost of a drawing proportional to the size of the document and of the
 * image it asks for, so a few hundred bytes cannot make the renderer spin
 * for seconds or allocate gigabytes.  Every path command flattens to at
 * most 65537 points (src/draw2d/curves.c), so counting points after each
 * command stops a path within one command of its limit. */
#define SVG_MAX_INPUT_BYTES   ((size_t)256 << 20) /* the document itself */
#define SVG_MAX_PATH_POINTS   (1 << 20)   /* flattened points of one shape */
#define SVG_MAX_SUBPATHS      (1 << 14)   /* subpaths (moveto) of one shape */
/* Points handled in all - flattened paths, stroke outlines (estimated
 * before they are built), polygons filled - may reach SVG_POINTS_BASE plus
 * SVG_POINTS_PER_BYTE per byte of the document.  Filling costs about a
 * microsecond per point. */
#define SVG_POINTS_BASE       (1 << 19)
#define SVG_POINTS_PER_BYTE   16
/* Fill work: the pixels of every filled polygon's bounding box (clipped to
 * the image) plus the image rows each of its edges crosses, summed over
 * the document, may reach SVG_WORK_PER_PIXEL times the image's pixel count
 * plus SVG_WORK_BASE. */
#define SVG_WORK_PER_PIXEL    16
#define SVG_WORK_BASE         (1 << 24)

typedef struct svg_options {
    const char *name;        /* the document's name in messages; NULL -> "<svg>" */
    int size_w, size_h;      /* --size: the output size, or 0 */
    double scale;            /* --scale: output = intrinsic size * scale; 0 -> 1 */
    sr_rgba background;      /* cleared to before drawing */
    int max_side;            /* largest image side; 0 -> SR_MAX_FRAMEBUFFER_SIZE */
    FILE *warnings;          /* "NAME:LINE: warning: ..." lines; NULL: none */
} svg_options;

/* Parse and render an SVG document held in memory (data need not be
 * NUL-terminated; at most SVG_MAX_INPUT_BYTES).  Returns EXIT_OK with a new
 * framebuffer on ctx in *out (sr_destroy_framebuffer it), or EXIT_USAGE for
 * a bad document or option / EXIT_FAILURE_RUN for out of memory, with *out
 * NULL and one line "NAME:LINE: what is wrong" in msg (no newline). */
int svg_render(sr_context *ctx, const char *data, size_t size, const svg_options *opt,
               sr_framebuffer **out, char *msg, size_t msg_size);

#endif
