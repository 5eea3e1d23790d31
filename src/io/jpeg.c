/* jpeg.c - JPEG images in and out (io stage), through libjpeg-turbo.  In:
 * baseline and progressive, grayscale, YCbCr/RGB and CMYK, any chroma
 * subsampling, to malloc'd RGBA8 (alpha 255).  Out: RGBA8 rows (alpha
 * dropped) to a file written atomically (atomic_file.c), as PNG is.
 * Reentrant: libjpeg's state lives on the caller's stack, and libjpeg
 * never prints or exits (our error hooks).
 *
 * Strictness: libjpeg recovers from damaged data with a warning and goes
 * on - a truncated file comes out with its missing rows gray.  A texture
 * with a gray band is a wrong picture, not a picture, so any warning
 * fails the read with libjpeg's own words; nothing partial is returned. */
#include "io/io_util.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#define MAX_READ_SIZE 16384   /* per side, as for PNG: 16384^2 RGBA8 is 1 GiB */
#define MAX_WRITE_SIZE 65500  /* per side: JPEG's own limit (libjpeg's JPEG_MAX_DIMENSION) */
/* libjpeg's working memory beyond which it fails rather than allocates.
 * A progressive image keeps every coefficient while it decodes, 2 bytes a
 * sample: 3 bytes a pixel with 4:2:0 chroma, 6 with 4:4:4, so 512 MiB
 * takes 8192 x 8192 at 4:4:4 and refuses 16000 x 16000 at 4:2:0.  With
 * the pixels (up to 1 GiB) a read stays under 2 GiB. */
#define MAX_DECODER_MEMORY ((long)1 << 29)

#ifdef SR_HAVE_JPEG

#include <jerror.h>
#include <jpeglib.h>
#include <setjmp.h>

/* The error manager: libjpeg's fields first, then where to jump and what
 * was said.  It lives in the caller of the function that calls setjmp, so
 * a longjmp leaves none of it indeterminate. */
typedef struct jpeg_status {
    struct jpeg_error_mgr pub;
    jmp_buf jump;
    sr_result code;                /* SR_OK until something fails */
    char message[JMSG_LENGTH_MAX];
    char warning[JMSG_LENGTH_MAX]; /* the first warning, "" for none */
} jpeg_status;

static void on_jpeg_error(j_common_ptr cinfo)
{
    jpeg_status *st = (jpeg_status *)cinfo->err;
    int code = cinfo->err->msg_code;
    if (code == JERR_NO_BACKING_STORE) {
        /* libjpeg's way of saying MAX_DECODER_MEMORY ran out */
        snprintf(st->message, sizeof st->message,
                 "decoding it would take more than %ld MiB of working memory",
                 MAX_DECODER_MEMORY >> 20);
        st->code = SR_TOO_LARGE;
    } else {
        (*cinfo->err->format_message)(cinfo, st->message);
        st->code = code == JERR_OUT_OF_MEMORY ? SR_OUT_OF_MEMORY : SR_BAD_FORMAT;
    }
    longjmp(st->jump, 1);
}

/* Level -1 is a warning (damaged data that libjpeg worked around); the
 * others are trace messages.  Nothing is printed. */
static void on_jpeg_message(j_common_ptr cinfo, int level)
{
    jpeg_status *st = (jpeg_status *)cinfo->err;
    if (level < 0 && st->warning[0] == 0) {
        (*cinfo->err->format_message)(cinfo, st->warning);
    }
}

/* Adobe's CMYK JPEGs store the inks inverted (255 = no ink), which is
 * what libjpeg hands back; the RGB of such a pixel is C K / 255 and so
 * on.  Others store them plainly. */
static void cmyk_row_to_rgba(const uint8_t *in, uint8_t *out, size_t w, bool inverted)
{
    for (size_t x = 0; x < w; x++) {
        unsigned k = inverted ? in[4 * x + 3] : 255u - in[4 * x + 3];
        for (int c = 0; c < 3; c++) {
            unsigned v = inverted ? in[4 * x + c] : 255u - in[4 * x + c];
            out[4 * x + c] = (uint8_t)((v * k + 127) / 255);
        }
        out[4 * x + 3] = 255;
    }
}

typedef struct jpeg_image {
    uint8_t *pixels;
    uint8_t *cmyk_row;
    int width, height;
} jpeg_image;

/* Decode into *out, or leave out->pixels NULL and say why in *st. */
static void decode_jpeg(const uint8_t *data, size_t size, jpeg_image *out, jpeg_status *st)
{
    struct jpeg_decompress_struct cinfo;
    cinfo.err = jpeg_std_error(&st->pub);
    st->pub.error_exit = on_jpeg_error;
    st->pub.emit_message = on_jpeg_message;
    if (setjmp(st->jump)) {
        jpeg_destroy_decompress(&cinfo);
        free(out->pixels);
        free(out->cmyk_row);
        out->pixels = NULL;
        out->cmyk_row = NULL;
        return;
    }
    jpeg_create_decompress(&cinfo);
    cinfo.mem->max_memory_to_use = MAX_DECODER_MEMORY;
    jpeg_mem_src(&cinfo, data, (unsigned long)size);
    jpeg_read_header(&cinfo, TRUE);

    JDIMENSION w = cinfo.image_width, h = cinfo.image_height;
    if (w > MAX_READ_SIZE || h > MAX_READ_SIZE) {
        st->code = SR_TOO_LARGE;
        snprintf(st->message, sizeof st->message, "image is %lux%lu, larger than the %dx%d limit",
                 (unsigned long)w, (unsigned long)h, MAX_READ_SIZE, MAX_READ_SIZE);
        jpeg_destroy_decompress(&cinfo);
        return;
    }
    bool cmyk = cinfo.jpeg_color_space == JCS_CMYK || cinfo.jpeg_color_space == JCS_YCCK;
    /* libjpeg-turbo writes RGBA itself from gray, RGB and YCbCr. */
    cinfo.out_color_space = cmyk ? JCS_CMYK : JCS_EXT_RGBA;
    bool inverted = cinfo.saw_Adobe_marker;
    jpeg_start_decompress(&cinfo);
    if (cinfo.output_components != 4) {
        st->code = SR_BAD_FORMAT;
        snprintf(st->message, sizeof st->message, "unsupported color space (%d components)",
                 cinfo.output_components);
        jpeg_destroy_decompress(&cinfo);
        return;
    }
    size_t stride = 4 * (size_t)w;
    out->pixels = malloc(stride * h);
    out->cmyk_row = cmyk ? malloc(stride) : NULL;
    if (!out->pixels || (cmyk && !out->cmyk_row)) {
        st->code = SR_OUT_OF_MEMORY;
        snprintf(st->message, sizeof st->message, "out of memory for a %lux%lu image",
                 (unsigned long)w, (unsigned long)h);
        longjmp(st->jump, 1);
    }
    /* Stop at the first warning: the rest would be made up. */
    while (cinfo.output_scanline < h && st->warning[0] == 0) {
        uint8_t *row = out->pixels + stride * cinfo.output_scanline;
        JSAMPROW target = cmyk ? out->cmyk_row : row;
        if (jpeg_read_scanlines(&cinfo, &target, 1) != 1) {
            break; /* only a suspending source stops early; the memory one cannot */
        }
        if (cmyk) {
            cmyk_row_to_rgba(out->cmyk_row, row, w, inverted);
        }
    }
    if (st->warning[0] == 0) {
        jpeg_finish_decompress(&cinfo); /* reads to the end marker: may warn too */
    }
    jpeg_destroy_decompress(&cinfo);
    free(out->cmyk_row);
    out->cmyk_row = NULL;
    if (st->warning[0]) {
        free(out->pixels);
        out->pixels = NULL;
        st->code = SR_BAD_FORMAT;
        return;
    }
    out->width = (int)w;
    out->height = (int)h;
}

/* Encode to a buffer libjpeg mallocs (*out, *size), or say why in *st.
 * Alpha is dropped: JPEG has none. */
static void encode_jpeg(const uint8_t *rgba, int w, int h, size_t stride, int quality,
                        unsigned char **out, unsigned long *size, jpeg_status *st)
{
    struct jpeg_compress_struct cinfo;
    cinfo.err = jpeg_std_error(&st->pub);
    st->pub.error_exit = on_jpeg_error;
    st->pub.emit_message = on_jpeg_message;
    if (setjmp(st->jump)) {
        jpeg_destroy_compress(&cinfo);
        free(*out);
        *out = NULL;
        return;
    }
    jpeg_create_compress(&cinfo);
    jpeg_mem_dest(&cinfo, out, size);
    cinfo.image_width = (JDIMENSION)w;
    cinfo.image_height = (JDIMENSION)h;
    cinfo.input_components = 4;
    cinfo.in_color_space = JCS_EXT_RGBA;
    jpeg_set_defaults(&cinfo);
    jpeg_set_quality(&cinfo, quality, TRUE);
    jpeg_start_compress(&cinfo, TRUE);
    while (cinfo.next_scanline < cinfo.image_height) {
        JSAMPROW row = (JSAMPROW)(rgba + stride * cinfo.next_scanline);
        jpeg_write_scanlines(&cinfo, &row, 1);
    }
    jpeg_finish_compress(&cinfo);
    jpeg_destroy_compress(&cinfo);
}

/* Encode, then hand the whole file to `write` at once.  When `write`
 * fails: SR_IO_ERROR with *write_failed set and no message (the caller
 * knows what the write was). */
static sr_result jpeg_run(const char *name, int w, int h, const uint8_t *rgba, size_t stride,
                          int quality, sr_write_fn write, void *user, bool *write_failed,
                          sr_io_error *err)
{
    *write_failed = false;
    unsigned char *data = NULL;
    unsigned long size = 0;
    jpeg_status status = { .code = SR_OK };
    encode_jpeg(rgba, w, h, stride, quality, &data, &size, &status);
    if (status.code != SR_OK) {
        return sr__io_fail(err, status.code, name, 0, "cannot encode JPEG: %s", status.message);
    }
    *write_failed = !write(user, data, size);
    free(data);
    return *write_failed ? SR_IO_ERROR : SR_OK;
}

bool sr_io_have_jpeg(void)
{
    return true;
}

sr_result sr_decode_jpeg(const char *name, const uint8_t *data, size_t size, int *width,
                         int *height, uint8_t **pixels, sr_io_error *err)
{
    sr_result args = sr__decode_args(&name, data, size, width, height, pixels, err);
    if (args != SR_OK) {
        return args;
    }
    if (size < 3 || data[0] != 0xFF || data[1] != 0xD8 || data[2] != 0xFF) {
        return sr__io_fail(err, SR_BAD_FORMAT, name, 0,
                           size == 0 ? "empty file, not a JPEG"
                                     : "not a JPEG file (no JPEG start-of-image marker)");
    }
    jpeg_image image = { 0 };
    jpeg_status status = { .code = SR_OK };
    decode_jpeg(data, size, &image, &status);
    if (status.code != SR_OK) {
        if (status.code == SR_BAD_FORMAT) {
            return sr__io_fail(err, SR_BAD_FORMAT, name, 0, "corrupt JPEG: %s",
                               status.warning[0] ? status.warning : status.message);
        }
        return sr__io_fail(err, status.code, name, 0, "%s", status.message);
    }
    *width = image.width;
    *height = image.height;
    *pixels = image.pixels;
    return SR_OK;
}

#else /* !SR_HAVE_JPEG */

bool sr_io_have_jpeg(void)
{
    return false;
}

sr_result sr_decode_jpeg(const char *name, const uint8_t *data, size_t size, int *width,
                         int *height, uint8_t **pixels, sr_io_error *err)
{
    (void)data;
    (void)size;
    sr__image_outputs_clear(width, height, pixels, err);
    return sr__io_fail(err, SR_UNSUPPORTED, name ? name : "<memory>", 0,
                       "cannot read JPEG (softrast was built without libjpeg; install "
                       "libjpeg-dev and rebuild)");
}

static sr_result jpeg_run(const char *name, int w, int h, const uint8_t *rgba, size_t stride,
                          int quality, sr_write_fn write, void *user, bool *write_failed,
                          sr_io_error *err)
{
    (void)w;
    (void)h;
    (void)rgba;
    (void)stride;
    (void)quality;
    (void)write;
    (void)user;
    *write_failed = false;
    return sr__io_fail(err, SR_UNSUPPORTED, name, 0,
                       "cannot write JPEG (softrast was built without libjpeg; install "
                       "libjpeg-dev and rebuild)");
}

#endif

/* The quality from desc, checked (a name for messages). */
static sr_result jpeg_settings(const char *name, int width, int height, const uint8_t *rgba,
                               size_t stride, const sr_jpeg_write_desc *desc, int *quality,
                               sr_io_error *err)
{
    sr_result checked = sr__check_image_write(name, width, height, MAX_WRITE_SIZE, rgba, stride,
                                              err);
    if (checked != SR_OK) {
        return checked;
    }
    *quality = desc && desc->quality ? desc->quality : SR_JPEG_DEFAULT_QUALITY;
    if (*quality < 1 || *quality > 100) {
        return sr__io_fail(err, SR_INVALID_ARG, name, 0,
                           "sr_jpeg_write_desc.quality %d is not in 1..100", *quality);
    }
    return SR_OK;
}

sr_result sr_encode_jpeg(sr_write_fn write, void *user, int width, int height,
                         const uint8_t *rgba, size_t stride, const sr_jpeg_write_desc *desc,
                         sr_io_error *err)
{
    const char *name = "<memory>";
    int quality;
    sr_result r = jpeg_settings(name, width, height, rgba, stride, desc, &quality, err);
    if (r != SR_OK) {
        return r;
    }
    if (!write) {
        return sr__io_fail(err, SR_INVALID_ARG, name, 0, "no write function given");
    }
    bool write_failed;
    r = jpeg_run(name, width, height, rgba, stride, quality, write, user, &write_failed, err);
    return write_failed ? sr__io_fail(err, r, name, 0, "the write function failed") : r;
}

sr_result sr_write_jpeg(const char *path, int width, int height, const uint8_t *rgba,
                        size_t stride, const sr_jpeg_write_desc *desc, sr_io_error *err)
{
    int quality;
    sr_result r = jpeg_settings(path, width, height, rgba, stride, desc, &quality, err);
    if (r != SR_OK) {
        return r;
    }
    sr_atomic_file file;
    r = sr__atomic_create(&file, path, (sr_allocator){ 0 }, err);
    if (r != SR_OK) {
        return r;
    }
    bool write_failed;
    r = jpeg_run(path, width, height, rgba, stride, quality, sr__write_fd, &file.fd,
                 &write_failed, err);
    if (r != SR_OK) {
        int e = errno;
        sr__atomic_discard(&file);
        return write_failed ? sr__io_fail(err, r, path, 0, "write failed: %s", strerror(e)) : r;
    }
    return sr__atomic_commit(&file, err);
}

sr_result sr_read_jpeg(const char *path, int *width, int *height, uint8_t **pixels,
                       sr_io_error *err)
{
    sr__image_outputs_clear(width, height, pixels, err);
    if (!path || !path[0]) {
        return sr__io_fail(err, SR_INVALID_ARG, "<null>", 0, "no file name given");
    }
    char *data;
    size_t size;
    sr_result r = sr__read_file_as(path, "a JPEG file", &data, &size, err);
    if (r != SR_OK) {
        return r;
    }
    r = sr_decode_jpeg(path, (const uint8_t *)data, size, width, height, pixels, err);
    sr__free_file(data, size);
    return r;
}
