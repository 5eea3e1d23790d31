/* gltf_parse.h - glTF documents in memory read by sr_parse_gltf as
 * "t.gltf", the reader's warnings counted and the last one kept: for the
 * glTF reader's tests.  Internal to tests. */
#ifndef SR_GLTF_PARSE_H
#define SR_GLTF_PARSE_H

#include "sr_test.h"

#include "softrast_io.h"

#include <stdio.h>
#include <string.h>

typedef struct warnings {
    int count;
    char last[600];
} warnings;

static inline void on_warn(void *user, const char *message)
{
    warnings *w = user;
    w->count++;
    snprintf(w->last, sizeof w->last, "%s", message);
}

static inline sr_result parse(const char *json, warnings *w, sr_scene **s, sr_io_error *e)
{
    sr_load_desc desc = { .warn = on_warn, .user = w };
    return sr_parse_gltf(sr_test_ctx(), "t.gltf", (const uint8_t *)json, strlen(json), &desc, s,
                         e);
}

#endif
