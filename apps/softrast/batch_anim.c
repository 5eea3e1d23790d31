/* batch_anim.c - a turntable as an animated WebP (--animate): the views
 * of one model as the frames of one file, encoded by libwebp's animation
 * encoder (libwebpmux) and written atomically like every other output.
 * Built only when libwebp was found (SR_HAVE_WEBP); otherwise
 * batch_anim_start says how to get it. */
#include "batch_anim.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#ifdef SR_HAVE_WEBP
#include <webp/encode.h>
#include <webp/mux.h>

struct batch_anim {
    WebPAnimEncoder *enc;
    WebPConfig config;
    int width, height;
    bool alpha;
};

batch_anim *batch_anim_start(int width, int height, bool alpha, char *why, size_t size)
{
    batch_anim *a = calloc(1, sizeof *a);
    WebPAnimEncoderOptions opts;
    if (!a || !WebPAnimEncoderOptionsInit(&opts) || !WebPConfigInit(&a->config)) {
        snprintf(why, size, "--animate: %s", a ? "libwebp's version does not match" : "out of memory");
        free(a);
        return NULL;
    }
    /* Lossy at quality 80: shaded surfaces, not line art; a loop forever. */
    a->config.quality = 80.0f;
    a->config.method = 4;
    opts.anim_params.loop_count = 0;
    a->enc = WebPAnimEncoderNew(width, height, &opts);
    if (!a->enc) {
        snprintf(why, size, "--animate: out of memory");
        free(a);
        return NULL;
    }
    a->width = width;
    a->height = height;
    a->alpha = alpha;
    return a;
}

bool batch_anim_add(batch_anim *a, const uint8_t *rgba, int timestamp_ms, char *why,
                    size_t size)
{
    WebPPicture pic;
    if (!WebPPictureInit(&pic)) {
        snprintf(why, size, "--animate: libwebp's version does not match");
        return false;
    }
    pic.use_argb = 1;
    pic.width = a->width;
    pic.height = a->height;
    int stride = 4 * a->width;
    bool ok = a->alpha ? WebPPictureImportRGBA(&pic, rgba, stride)
                       : WebPPictureImportRGBX(&pic, rgba, stride);
    ok = ok && WebPAnimEncoderAdd(a->enc, &pic, timestamp_ms, &a->config);
    if (!ok) {
        snprintf(why, size, "--animate: %s", WebPAnimEncoderGetError(a->enc)[0]
                                                 ? WebPAnimEncoderGetError(a->enc)
                                                 : "out of memory");
    }
    WebPPictureFree(&pic);
    return ok;
}

bool batch_anim_write(batch_anim *a, const char *path, int end_ms, sr_io_error *err)
{
    WebPData data;
    WebPDataInit(&data);
    if (!WebPAnimEncoderAdd(a->enc, NULL, end_ms, NULL) ||
        !WebPAnimEncoderAssemble(a->enc, &data)) {
        snprintf(err->message, sizeof err->message, "%s: %s", path,
                 WebPAnimEncoderGetError(a->enc));
        return false;
    }
    bool ok = sr_write_file(path, data.bytes, data.size, err) == SR_OK;
    WebPDataClear(&data);
    return ok;
}

void batch_anim_free(batch_anim *a)
{
    if (a) {
        WebPAnimEncoderDelete(a->enc);
        free(a);
    }
}

#else

struct batch_anim {
    int unused;
};

batch_anim *batch_anim_start(int width, int height, bool alpha, char *why, size_t size)
{
    (void)width, (void)height, (void)alpha;
    snprintf(why, size, "cannot write animated WebP (softrast was built without libwebp; "
                        "install libwebp-dev and rebuild)");
    return NULL;
}

bool batch_anim_add(batch_anim *a, const uint8_t *rgba, int timestamp_ms, char *why,
                    size_t size)
{
    (void)a, (void)rgba, (void)timestamp_ms, (void)why, (void)size;
    return false;
}

bool batch_anim_write(batch_anim *a, const char *path, int end_ms, sr_io_error *err)
{
    (void)a, (void)path, (void)end_ms, (void)err;
    return false;
}

void batch_anim_free(batch_anim *a)
{
    (void)a;
}

#endif

bool batch_anim_available(void)
{
#ifdef SR_HAVE_WEBP
    return true;
#else
    return false;
#endif
}

bool batch_anim_is_webp_name(const char *path)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    return dot && !(slash && dot < slash) && strcasecmp(dot, ".webp") == 0;
}
