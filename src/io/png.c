/* png.c - io: PNG files and bytes to RGBA8 pixels, through libpng (the
 * writer is png_write.c).  sr_read_png consumes any PNG and produces
 * malloc'd RGBA8.  Reentrant: all state lives on the caller's stack, and
 * libpng never prints (our error and warning hooks).
 */
/* fmemopen() with the rest of POSIX 2008. */
#define _XOPEN_SOURCE 700

#include "io/io_util.h"

#include <png.h>

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_READ_SIZE  16384    /* per side; 16384^2 RGBA8 is 1 GiB, the most we allocate */

/* ---- libpng error hooks ------------------------------------------------- */

/* What went wrong inside libpng, filled by the hooks and read after the
 * longjmp.  It lives in the caller of the function that calls setjmp, so it
 * is never one of the locals whose value a longjmp leaves indeterminate. */
typedef struct png_status {
    sr_result code;         /* SR_OK until something fails */
    int saved_errno;        /* errno when libpng gave up (write/read errors) */
    char message[200];
} png_status;

static void on_png_error(png_structp png, png_const_charp msg)
{
    png_status *st = png_get_error_ptr(png);
    st->saved_errno = errno;
    if (st->code == SR_OK) {
        st->code = SR_BAD_FORMAT;
    }
    snprintf(st->message, sizeof st->message, "%s", msg ? msg : "unknown libpng error");
    png_longjmp(png, 1);
}

/* libpng's default would print to stderr; the library never prints.
 * Warnings (a damaged ancillary chunk, say) do not stop the image. */
static void on_png_warning(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg;
}

/* The caller's allocator, for libpng (and, through libpng, zlib).  `failed`
 * tells an out-of-memory longjmp from a read error: libpng reports both
 * through the same error hook. */
typedef struct png_mem {
    sr_allocator a;
    bool failed;
} png_mem;

static void *mem_alloc(png_mem *m, size_t size)
{
    void *p = sr__io_alloc(&m->a, size);
    if (!p) {
        m->failed = true;
    }
    return p;
}

static void mem_free(png_mem *m, void *p)
{
    sr__io_free(&m->a, p);
}

static png_voidp png_mem_alloc(png_structp png, png_alloc_size_t size)
{
    return mem_alloc(png_get_mem_ptr(png), size);
}

static void png_mem_free(png_structp png, png_voidp p)
{
    mem_free(png_get_mem_ptr(png), p);
}

/* ---- reading ------------------------------------------------------------ */

typedef struct png_image_out {
    uint8_t *pixels;
    png_bytep *rows;
    int width, height;
} png_image_out;

/* The decoder proper; as with encode_png, no local changes after setjmp.
 * Whatever it allocates is hung on *out, so the longjmp path can free it. */
static void decode_png(FILE *f, png_mem *mem, png_image_out *out, png_status *st)
{
    png_structp png = png_create_read_struct_2(PNG_LIBPNG_VER_STRING, st, on_png_error,
                                               on_png_warning, mem, png_mem_alloc, png_mem_free);
    if (!png) {
        st->code = SR_OUT_OF_MEMORY;
        snprintf(st->message, sizeof st->message, "out of memory creating the PNG reader");
        return;
    }
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_read_struct(&png, NULL, NULL);
        st->code = SR_OUT_OF_MEMORY;
        snprintf(st->message, sizeof st->message, "out of memory creating the PNG reader");
        return;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, NULL);
        mem_free(mem, out->pixels);
        mem_free(mem, out->rows);
        out->pixels = NULL;
        out->rows = NULL;
        if (mem->failed) { /* libpng's "Out of memory", or zlib's failure */
            st->code = SR_OUT_OF_MEMORY;
            snprintf(st->message, sizeof st->message, "out of memory");
        }
        return;
    }
    png_init_io(png, f);
    png_set_sig_bytes(png, 8);  /* the caller has checked the signature */
    png_read_info(png, info);

    png_uint_32 w = png_get_image_width(png, info);
    png_uint_32 h = png_get_image_height(png, info);
    if (w > MAX_READ_SIZE || h > MAX_READ_SIZE) {
        png_destroy_read_struct(&png, &info, NULL);
        st->code = SR_TOO_LARGE;
        snprintf(st->message, sizeof st->message,
                 "image is %lux%lu, larger than the %dx%d limit",
                 (unsigned long)w, (unsigned long)h, MAX_READ_SIZE, MAX_READ_SIZE);
        return;
    }
    /* Every PNG to RGBA8: palette and gray below 8 bits expand to 8-bit
     * samples (and tRNS to an alpha channel), 16-bit samples drop their low
     * byte, gray becomes RGB, and an image with no alpha gets an opaque one. */
    png_set_expand(png);
    png_set_strip_16(png);
    png_set_gray_to_rgb(png);
    png_set_add_alpha(png, 0xFF, PNG_FILLER_AFTER);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    if (png_get_rowbytes(png, info) != 4 * (size_t)w) {
        png_destroy_read_struct(&png, &info, NULL);
        st->code = SR_BAD_FORMAT;
        snprintf(st->message, sizeof st->message,
                 "unsupported pixel layout (%lu bytes per row after conversion, expected %lu)",
                 (unsigned long)png_get_rowbytes(png, info), 4ul * w);
        return;
    }
    out->pixels = mem_alloc(mem, 4 * (size_t)w * h);
    out->rows = mem_alloc(mem, sizeof(png_bytep) * h);
    if (!out->pixels || !out->rows) {
        st->code = SR_OUT_OF_MEMORY;
        snprintf(st->message, sizeof st->message, "out of memory for a %lux%lu image",
                 (unsigned long)w, (unsigned long)h);
        png_destroy_read_struct(&png, &info, NULL);
        mem_free(mem, out->pixels);
        mem_free(mem, out->rows);
        out->pixels = NULL;
        out->rows = NULL;
        return;
    }
    for (png_uint_32 y = 0; y < h; y++) {
        out->rows[y] = out->pixels + 4 * (size_t)w * y;
    }
    png_read_image(png, out->rows);
    png_read_end(png, NULL);
    png_destroy_read_struct(&png, &info, NULL);
    mem_free(mem, out->rows);
    out->rows = NULL;
    out->width = (int)w;
    out->height = (int)h;
}

/* The rest of a read once the input is open as `f` (a file, or memory
 * through fmemopen): signature, decode, messages naming `name`.  Closes f. */
static sr_result read_png_stream(FILE *f, const char *name, const sr_png_read_desc *desc,
                                 int *width, int *height, uint8_t **pixels, sr_io_error *err)
{
    uint8_t sig[8];
    size_t got = fread(sig, 1, sizeof sig, f);
    if (got < sizeof sig || png_sig_cmp(sig, 0, sizeof sig) != 0) {
        bool read_error = ferror(f);
        int e = errno;
        fclose(f);
        if (read_error) {
            return sr__io_fail(err, SR_IO_ERROR, name, 0, "read error: %s", strerror(e));
        }
        if (got == 0) {
            return sr__io_fail(err, SR_BAD_FORMAT, name, 0, "empty file, not a PNG");
        }
        return sr__io_fail(err, SR_BAD_FORMAT, name, 0, "not a PNG file (no PNG signature)");
    }

    png_mem mem = { .a = desc ? desc->allocator : (sr_allocator){0} };
    if ((mem.a.alloc == NULL) != (mem.a.free == NULL)) {
        fclose(f);
        return sr__io_fail(err, SR_INVALID_ARG, name, 0,
                           "sr_png_read_desc.allocator needs both alloc and free");
    }
    png_image_out image = { 0 };
    png_status status = { .code = SR_OK };
    errno = 0;
    decode_png(f, &mem, &image, &status);
    bool read_error = ferror(f);
    bool at_end = feof(f);
    fclose(f);
    if (status.code != SR_OK) {
        if (read_error) {
            return sr__io_fail(err, SR_IO_ERROR, name, 0, "read error: %s",
                               strerror(status.saved_errno));
        }
        if (at_end && status.code == SR_BAD_FORMAT) {
            return sr__io_fail(err, SR_BAD_FORMAT, name, 0,
                               "truncated PNG: the file ends early (libpng: %s)", status.message);
        }
        if (status.code == SR_BAD_FORMAT) {
            return sr__io_fail(err, SR_BAD_FORMAT, name, 0, "corrupt PNG: %s", status.message);
        }
        return sr__io_fail(err, status.code, name, 0, "%s", status.message);
    }
    *width = image.width;
    *height = image.height;
    *pixels = image.pixels;
    return SR_OK;
}

sr_result sr_read_png(const char *path, const sr_png_read_desc *desc, int *width,
                      int *height, uint8_t **pixels, sr_io_error *err)
{
    sr__image_outputs_clear(width, height, pixels, err);
    if (!path || !path[0]) {
        return sr__io_fail(err, SR_INVALID_ARG, "<null>", 0, "no file name given");
    }
    if (!width || !height || !pixels) {
        return sr__io_fail(err, SR_INVALID_ARG, path, 0,
                           "width, height and pixels must not be NULL");
    }
    FILE *f;
    unsigned long long size;
    sr_result res = sr__open_regular(path, "a PNG file", &f, &size, err);
    if (res != SR_OK) {
        return res;
    }
    return read_png_stream(f, path, desc, width, height, pixels, err);
}

sr_result sr_decode_png(const char *name, const uint8_t *data, size_t size, int *width,
                        int *height, uint8_t **pixels, sr_io_error *err)
{
    sr_result args = sr__decode_args(&name, data, size, width, height, pixels, err);
    if (args != SR_OK) {
        return args;
    }
    if (size == 0) {
        return sr__io_fail(err, SR_BAD_FORMAT, name, 0, "empty file, not a PNG");
    }
    /* libpng reads through stdio; fmemopen makes the bytes a stream. */
    FILE *f = fmemopen((void *)data, size, "rb");
    if (!f) {
        return sr__io_fail(err, errno == ENOMEM ? SR_OUT_OF_MEMORY : SR_IO_ERROR, name, 0,
                           "cannot read from memory: %s", strerror(errno));
    }
    return read_png_stream(f, name, NULL, width, height, pixels, err);
}
