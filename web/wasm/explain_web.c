/* explain_web.c - the web pages' WebAssembly module: `softrast explain`
 * itself (explain*.c, cmd_explain) run on the arguments a page gives, its
 * frames kept in memory for the page's canvas rather than written as PNG
 * files.  This file stands in for the tool's image_out.c: cmd_explain
 * "writes" each step with cli_write_image, which here keeps a copy.  So
 * the canvas shows the bytes the native tool writes for the same
 * arguments, and an algorithm added to explain.c's table appears here
 * with no change. */
#include "explain_web.h"

#include "cli.h"
#include "explain.h"

#include <emscripten/emscripten.h>

#include <stdlib.h>
#include <string.h>

#define MAX_ARGS 64

static uint8_t **frames;
static int frame_count, frame_cap, frame_w, frame_h;
static char message[1024];

static void drop_frames(void)
{
    for (int i = 0; i < frame_count; i++) {
        free(frames[i]);
    }
    frame_count = 0;
}

sr_result cli_write_image(const char *path, int width, int height, const uint8_t *rgba,
                          const cli_image_options *opt, sr_io_error *err)
{
    (void)path;
    (void)opt;
    size_t bytes = (size_t)width * (size_t)height * 4;
    uint8_t *copy = malloc(bytes);
    if (frame_count == frame_cap) {
        int cap = frame_cap ? 2 * frame_cap : 16;
        uint8_t **grown = realloc(frames, (size_t)cap * sizeof *grown);
        if (grown) {
            frames = grown;
            frame_cap = cap;
        }
    }
    if (!copy || frame_count == frame_cap) {
        free(copy);
        snprintf(err->message, sizeof err->message, "out of memory for the frames");
        return SR_OUT_OF_MEMORY;
    }
    memcpy(copy, rgba, bytes);
    frames[frame_count++] = copy;
    frame_w = width;
    frame_h = height;
    return SR_OK;
}

EMSCRIPTEN_KEEPALIVE int web_explain(const char *args)
{
    static char buf[8192];
    char *argv[MAX_ARGS + 4];
    int argc = 0;
    drop_frames();
    argv[argc++] = "explain";
    snprintf(buf, sizeof buf, "%s", args);
    for (char *p = buf; *p && argc < MAX_ARGS;) {
        argv[argc++] = p;
        char *nl = strchr(p, '\n');
        if (!nl) {
            break;
        }
        *nl = '\0';
        p = nl + 1;
    }
    argv[argc++] = "-o";
    argv[argc++] = "frame-%d";   /* a pattern: cmd_explain makes no directory */
    argv[argc] = NULL;
    cli_capture(message, sizeof message);
    int status = cmd_explain(argc, argv);
    cli_capture(NULL, 0);
    if (status != EXIT_OK) {
        drop_frames();
    }
    return status;
}

EMSCRIPTEN_KEEPALIVE const char *web_message(void)
{
    return message;
}

EMSCRIPTEN_KEEPALIVE int web_frame_count(void)
{
    return frame_count;
}

EMSCRIPTEN_KEEPALIVE int web_frame_width(void)
{
    return frame_w;
}

EMSCRIPTEN_KEEPALIVE int web_frame_height(void)
{
    return frame_h;
}

EMSCRIPTEN_KEEPALIVE const uint8_t *web_frame(int i)
{
    return i >= 0 && i < frame_count ? frames[i] : NULL;
}

EMSCRIPTEN_KEEPALIVE int web_margin(void)
{
    return EX_MARGIN;
}

EMSCRIPTEN_KEEPALIVE const char *web_algorithm(int i)
{
    static char json[8192];
    const char *name, *summary;
    ex_primitive ex;
    int gw, gh, zoom;
    if (!explain_algorithm(i, &name, &summary, &ex, &gw, &gh, &zoom)) {
        return NULL;
    }
    /* The primitive's option is --KIND (ex_kind's order); the page makes
     * handles of its points, and of the seed, the row, the clip window
     * and the highlight where the example has them. */
    static const char *const kinds[] = { "none",     "triangle", "polygon", "line",
                                         "triangles", "circle",  "cubic",   "clip-triangle",
                                         "object" };
    const char *kind = (size_t)ex.kind < sizeof kinds / sizeof kinds[0] ? kinds[ex.kind] : "none";
    int n = snprintf(json, sizeof json, "{\"name\":\"%s\",\"kind\":\"%s\",\"summary\":\"", name,
                     kind);
    for (const char *s = summary; *s && n < (int)sizeof json - 1024; s++) {
        if (*s == '\n') {            /* the help text's wrapped lines, joined */
            while (s[1] == ' ') {
                s++;
            }
            json[n++] = ' ';
        } else if (*s != '"' && *s != '\\') {
            json[n++] = *s;
        }
    }
    n += snprintf(json + n, sizeof json - (size_t)n, "\",\"points\":[");
    for (int k = 0; k < ex.count && n < (int)sizeof json - 128; k++) {
        n += snprintf(json + n, sizeof json - (size_t)n, "%s[%.17g,%.17g]", k ? "," : "",
                      ex.pts[k].x, ex.pts[k].y);
    }
    /* each point's value: a depth, w, an intensity, the circle's radius */
    n += snprintf(json + n, sizeof json - (size_t)n, "],\"values\":[");
    for (int k = 0; k < ex.count && n < (int)sizeof json - 128; k++) {
        n += snprintf(json + n, sizeof json - (size_t)n, "%s%.17g", k ? "," : "", ex.z[k]);
    }
    n += snprintf(json + n, sizeof json - (size_t)n, "],\"clip\":[");
    for (int k = 0; k < 12 && n < (int)sizeof json - 128; k++) {
        n += snprintf(json + n, sizeof json - (size_t)n, "%s%.17g", k ? "," : "",
                      ex.clip[k / 4][k % 4]);
    }
    snprintf(json + n, sizeof json - (size_t)n,
             "],\"window\":[%.17g,%.17g,%.17g,%.17g],\"seed\":[%d,%d],\"row\":%d,"
             "\"highlight\":[%.17g,%.17g],\"grid\":[%d,%d],\"zoom\":%d}",
             ex.window[0], ex.window[1], ex.window[2], ex.window[3], ex.seed[0], ex.seed[1], ex.row,
             ex.highlight[0], ex.highlight[1], gw, gh, zoom);
    return json;
}
