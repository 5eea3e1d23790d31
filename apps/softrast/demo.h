/* demo.h - `softrast demo NAME`: images that show a pipeline phenomenon
 * side by side, labelled.  Each demo lives in its own demo_NAME.c and is
 * listed in demo.c's table. */
#ifndef SR_DEMO_H
#define SR_DEMO_H

#include "softrast.h"

#include <stdint.h>

typedef struct demo_args {
    const char *output;     /* PNG path (default "demo-NAME.png") */
    int scale;              /* magnification for pixel-level demos (0: the demo's default) */
} demo_args;

/* A demo renders into a framebuffer it makes on ctx and returns it in
 * *out (the caller writes the PNG and destroys it).  The return value is
 * a CLI exit status: 0, or 1 after printing one line on failure. */
typedef int (*demo_fn)(sr_context *ctx, const demo_args *args, sr_framebuffer **out);

typedef struct demo_entry {
    const char *name;
    const char *summary;
    demo_fn run;
} demo_entry;

/* Demos register here, and demo.c's table is built from this list: one
 * line each, X(id, "name", summary), the function demo_<id> in
 * demo_<id>.c.  The id is the name as a C identifier (dashes become
 * underscores: gouraud-highlight -> demo_gouraud_highlight in
 * demo_gouraud_highlight.c). */
#define DEMO_LIST(X) \
    X(lines, "lines", "every line algorithm on a star of lines, magnified") \
    X(fill, "fill", "even-odd vs nonzero fill of a star and of holes; area and supersampled AA") \
    X(floodfill, "floodfill", "flood and boundary fill, 4- vs 8-connected, leaking through a diagonal gap") \
    X(clip, "clip", "Sutherland-Hodgman clipping: a 2D polygon edge by edge; 3D triangles in clip space") \
    X(curves, "curves", "midpoint circles and ellipses, Bezier flattening, stroke joins and caps") \
    X(gouraud_highlight, "gouraud-highlight", "a specular highlight missed (interior) and smeared (at a vertex) by Gouraud, vs Phong") \
    X(perspective, "perspective", "checkerboard and gradient interpolated in screen space (affine) vs perspective-correctly") \
    X(zfight, "zfight", "z-fighting: D16/D24/D32F depth at several far/near ratios, reversed-Z, polygon offset") \
    X(normals, "normals", "a non-uniformly scaled sphere lit with normals transformed by M vs by M^-T") \
    X(viewport, "viewport", "one scene in wide and tall viewports, stretched vs aspect ratio preserved") \
    X(aa, "aa", "a star and a turned square aliased, MSAA 4/8/16, exact area, SSAA with four filters") \
    X(painter, "painter", "the painter's algorithm vs the z-buffer: cyclic overlap and interpenetration") \
    X(orientation, "orientation", "a quad's colors interpolated by scan lines change as it turns; as two triangles they do not") \
    X(depth_range, "depth-range", "the depth range: window depths in 0,1 and 0.25,0.75, inverted, split for an overlay")

/* Each demo_<id>.c defines the function declared here. */
#define DEMO_DECLARE(id, name, summary) int demo_##id(sr_context *, const demo_args *, sr_framebuffer **);
DEMO_LIST(DEMO_DECLARE)

/* The registered demos (demo.c), terminated by a NULL name. */
extern const demo_entry demo_table[];

/* Pages made of panels (demo_paste.c).  Copy src into dst with its
 * top-left corner at (x, y), clipped to dst. */
sr_result demo_paste(sr_context *ctx, sr_framebuffer *dst, const sr_framebuffer *src, int x,
                     int y);
/* A demo's image of w x h at a magnification of scale: EXIT_OK when it
 * fits a framebuffer, else EXIT_USAGE after one line that names --scale
 * (too large a --scale is the user's to change, not a failed run). */
int demo_check_image(const char *name, int scale, int w, int h);

/* Magnify src into dst at (x, y), each pixel a scale x scale block, with
 * a one-pixel line of the RGBA8 color `grid` on each block's top and left
 * edges when grid is not NULL and scale is at least 4.  The block image
 * must lie inside dst. */
sr_result demo_magnify(sr_context *ctx, sr_framebuffer *dst, int x, int y,
                       const sr_framebuffer *src, int scale, const uint8_t *grid);

#endif
