/* image_compare.c - reference-image comparison with a diff image on failure. */
#include "image_compare.h"
#include "sr_test.h"
#include "softrast_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void write_or_note(const char *path, const uint8_t *px, int w, int h)
{
    sr_io_error err;
    if (sr_write_png(path, w, h, px, (size_t)w * 4, NULL, &err) != SR_OK) {
        fprintf(stderr, "  could not write %s: %s\n", err.message, path);
    } else {
        fprintf(stderr, "  wrote %s\n", path);
    }
}

bool sr_test_compare_images(const char *name, const uint8_t *rgba, const uint8_t *ref, int w,
                            int h, int channel_tol, long max_bad_pixels)
{
    char out_path[1024];
    long bad = 0;
    int worst = 0;
    uint8_t *diff = malloc((size_t)w * h * 4);
    for (long i = 0; i < (long)w * h; i++) {
        int d = 0;
        for (int c = 0; c < 4; c++) {
            int e = abs((int)rgba[i * 4 + c] - (int)ref[i * 4 + c]);
            d = e > d ? e : d;
        }
        worst = d > worst ? d : worst;
        bool is_bad = d > channel_tol;
        bad += is_bad;
        if (diff) {
            diff[i * 4 + 0] = is_bad ? 255 : ref[i * 4 + 0] / 3;
            diff[i * 4 + 1] = is_bad ? 0 : ref[i * 4 + 1] / 3;
            diff[i * 4 + 2] = is_bad ? 0 : ref[i * 4 + 2] / 3;
            diff[i * 4 + 3] = 255;
        }
    }
    bool ok = bad <= max_bad_pixels;
    if (!ok) {
        sr_test_fail(__FILE__, __LINE__,
                     "image %s: %ld pixels differ by more than %d (allowed %ld), worst %d",
                     name, bad, channel_tol, max_bad_pixels, worst);
        snprintf(out_path, sizeof out_path, "%s/%s.actual.png", sr_test_out_dir(), name);
        write_or_note(out_path, rgba, w, h);
        if (diff) {
            snprintf(out_path, sizeof out_path, "%s/%s.diff.png", sr_test_out_dir(), name);
            write_or_note(out_path, diff, w, h);
        }
    }
    free(diff);
    return ok;
}

bool sr_test_check_image(const char *name, const uint8_t *rgba, int w, int h,
                         int channel_tol, long max_bad_pixels)
{
    char ref_path[1024], out_path[1024];
    snprintf(ref_path, sizeof ref_path, "%s/ref/%s.png", sr_test_src_dir(), name);
    const char *update = getenv("SR_UPDATE_REFS");
    if (update && strcmp(update, "1") == 0) {
        write_or_note(ref_path, rgba, w, h);
        return true;
    }

    int rw = 0, rh = 0;
    uint8_t *ref = NULL;
    sr_io_error err;
    if (sr_read_png(ref_path, NULL, &rw, &rh, &ref, &err) != SR_OK) {
        sr_test_fail(__FILE__, __LINE__, "reference %s: %s", name, err.message);
        snprintf(out_path, sizeof out_path, "%s/%s.actual.png", sr_test_out_dir(), name);
        write_or_note(out_path, rgba, w, h);
        return false;
    }
    if (rw != w || rh != h) {
        sr_test_fail(__FILE__, __LINE__, "reference %s is %dx%d, image is %dx%d",
                     name, rw, rh, w, h);
        free(ref);
        return false;
    }

    bool ok = sr_test_compare_images(name, rgba, ref, w, h, channel_tol, max_bad_pixels);
    free(ref);
    return ok;
}

void sr_test_check_posed(const char *name, const uint8_t *posed, const uint8_t *hand,
                         const uint8_t *rest, int w, int h, long rest_share)
{
    char hand_name[256];
    snprintf(hand_name, sizeof hand_name, "%s_hand_posed", name);
    sr_test_compare_images(hand_name, posed, hand, w, h, 2, (long)w * h / 200);
    sr_test_check_image(name, posed, w, h, 2, (long)w * h / 200);
    long differ = 0;
    for (long i = 0; i < (long)w * h * 4; i++) {
        differ += posed[i] != rest[i];
    }
    if (differ <= (long)w * h / rest_share) {
        sr_test_fail(__FILE__, __LINE__, "%s: only %ld bytes differ from the rest pose", name,
                     differ);
    }
}
