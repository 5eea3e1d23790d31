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

/* The registered demos (demo.c), terminated by a NULL name. */
extern const demo_entry demo_table[];

/* Pages made of panels (demo_paste.c).  Copy src into dst with its
 * top-left corner at (x, y), clipped to dst. */
sr_result demo_paste(sr_context *ctx, sr_framebuffer *dst, const sr_framebuffer *src, int x,
                     int y);
/* Magnify src into dst at (x, y), each pixel a scale x scale block, with
 * a one-pixel line of the RGBA8 color `grid` on each block's top and left
 * edges when grid is not NULL and scale is at least 4.  The block image
 * must lie inside dst. */
sr_result demo_magnify(sr_context *ctx, sr_framebuffer *dst, int x, int y,
                       const sr_framebuffer *src, int scale, const uint8_t *grid);

#endif
