/* batch_anim.h - a turntable's views as one animated WebP (batch_anim.c,
 * libwebp's animation encoder when the build found it). */
#ifndef SR_BATCH_ANIM_H
#define SR_BATCH_ANIM_H

#include "softrast_io.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct batch_anim batch_anim;

/* Whether this build writes animated WebP. */
bool batch_anim_available(void);
/* Whether path ends in .webp (any case): an animation is written by no
 * other name, so that no viewer takes it for a PNG. */
bool batch_anim_is_webp_name(const char *path);
/* An animation of width x height frames (with an alpha channel when
 * `alpha`); NULL with the reason in why. */
batch_anim *batch_anim_start(int width, int height, bool alpha, char *why, size_t size);
/* Add a frame (RGBA8, straight alpha) shown from timestamp_ms. */
bool batch_anim_add(batch_anim *a, const uint8_t *rgba, int timestamp_ms, char *why,
                    size_t size);
/* Encode it, the last frame lasting until end_ms, and write it to path
 * atomically. */
bool batch_anim_write(batch_anim *a, const char *path, int end_ms, sr_io_error *err);
void batch_anim_free(batch_anim *a);

#endif
