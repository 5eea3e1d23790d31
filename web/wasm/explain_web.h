/* explain_web.h - what the web pages' WebAssembly module exports to their
 * JavaScript (web/explain.js), all through ccall. */
#ifndef SR_EXPLAIN_WEB_H
#define SR_EXPLAIN_WEB_H

#include <stdint.h>

/* Run `softrast explain ALGORITHM OPTIONS...` (args: the words after
 * "explain", separated by '\n'); the tool's exit status, 0 when the
 * frames are ready.
 * A failure's message is web_message(). */
int web_explain(const char *args);
const char *web_message(void);
int web_frame_count(void);
int web_frame_width(void);
int web_frame_height(void);
/* Step i's RGBA8 pixels, web_frame_width() x web_frame_height(); NULL
 * past the last. */
const uint8_t *web_frame(int i);
/* The frame pixels around the grid: cell x starts at margin + zoom * x. */
int web_margin(void);
/* Algorithm i of the table as JSON text (name, summary, primitive kind,
 * example points, clip window, grid and zoom), or NULL past the last. */
const char *web_algorithm(int i);

#endif
