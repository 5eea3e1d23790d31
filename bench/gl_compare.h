/* gl_compare.h - the reference renderer for `softrast-bench --compare`:
 * Mesa llvmpipe through OSMesa and legacy fixed-function OpenGL, drawing a
 * bench_scene with the same matrices, vertex arrays, lights and material.
 * Built with SR_HAVE_OSMESA; without it every call reports unavailability.
 * Main thread only (one GL context per process). */
#ifndef SR_BENCH_GL_COMPARE_H
#define SR_BENCH_GL_COMPARE_H

#include "scenes.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct gl_renderer gl_renderer;

/* false when this build has no OSMesa. */
bool gl_available(void);

/* Create the context and an RGBA8 buffer of width x height.  llvmpipe reads
 * LP_NUM_THREADS once, when the first context is created: `threads` is put
 * there first.  On failure writes one line to msg. */
bool gl_make(int width, int height, int threads, gl_renderer **out, char *msg, size_t msg_size);
void gl_destroy(gl_renderer *g);

/* The GL_RENDERER string, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)". */
const char *gl_renderer_name(const gl_renderer *g);

/* Set up state and upload the scene's arrays (untimed).  The scene must
 * outlive its frames. */
bool gl_prepare(gl_renderer *g, const bench_scene *s, char *msg, size_t msg_size);
/* One frame: clear, draw, glFinish, so the image is complete on return. */
void gl_frame(gl_renderer *g, const bench_scene *s);
/* Release what gl_prepare uploaded. */
void gl_unprepare(gl_renderer *g);
/* The last frame, RGBA8, row 0 at the top, stride 4 * width.  false with a
 * message if GL reported an error. */
bool gl_check(gl_renderer *g, char *msg, size_t msg_size);
const uint8_t *gl_pixels(const gl_renderer *g);

#endif
