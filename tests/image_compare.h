/* image_compare.h - reference-image checks for image tests.
 *
 * sr_test_check_image compares an RGBA8 image with tests/ref/<name>.png.
 * A pixel differs when any channel differs by more than `channel_tol`; the
 * check fails when more than `max_bad_pixels` differ.  On failure it writes
 * <out>/<name>.actual.png and <out>/<name>.diff.png (differing pixels red on
 * a darkened copy of the reference) and reports their paths.
 * With SR_UPDATE_REFS=1 in the environment it (re)writes the reference
 * instead - look at every image it writes before committing it. */
#ifndef SR_IMAGE_COMPARE_H
#define SR_IMAGE_COMPARE_H
#include <stdbool.h>
#include <stdint.h>

bool sr_test_check_image(const char *name, const uint8_t *rgba, int w, int h,
                         int channel_tol, long max_bad_pixels);
/* The same check against `ref` in memory (w x h too), for two renders
 * that must agree: on failure <out>/<name>.actual.png and .diff.png. */
bool sr_test_compare_images(const char *name, const uint8_t *rgba, const uint8_t *ref, int w,
                            int h, int channel_tol, long max_bad_pixels);
/* An animation's render checked (w x h each): `posed` within 2 codes of
 * `hand` (the file with the pose's values written in) and of
 * tests/ref/<name>.png on all but 0.5% of the pixels (a last bit of a
 * sampled value, or another CPU's libm, can move an edge pixel), and
 * unlike `rest` (the rest pose) in more bytes than w h / rest_share. */
void sr_test_check_posed(const char *name, const uint8_t *posed, const uint8_t *hand,
                         const uint8_t *rest, int w, int h, long rest_share);
#endif
