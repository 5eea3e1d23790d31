/* png.c - io, the end of the pipeline: framebuffer pixels to PNG files and
 * back, through libpng.  sr_write_png consumes RGBA8 rows (any stride) and
 * produces a file that appears whole or not at all; sr_read_png consumes any
 * PNG and produces malloc'd RGBA8.  Reentrant: all state lives on the
 * caller's stack, and libpng never prints (our error and warning hooks).
 */
/* fmemopen() with the rest of POSIX 2008. */
#define _XOPEN_SOURCE 700

#include "io/io_util.h"

#include <png.h>
#include <zlib.h>

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_WRITE_SIZE 65535    /* per side, as documented; well inside libpng's 1000000 */
#define MAX_READ_SIZE  16384    /* per side; 16384^2 RGBA8 is 1 GiB, the most we allocate */

/* One fixed filter rather than libpng's default of trying all five on
 * every row and keeping the best, which costs 2.5x the time at level 1 for
 * a file 5% smaller.  Measured with libpng 1.6.39 / zlib level 1 on a
 * 1920x1080 shaded teapot over a flat background (what softrast writes),
 * encoding to memory, best of 7:
 *     NONE   502 KB  20.2 ms     UP     391 KB  22.3 ms
 *     SUB    430 KB  23.8 ms     PAETH  375 KB  31.6 ms     all  370 KB  57 ms
 * UP wins over SUB in both size and time: a background row is identical
 * to the row above, so UP turns it into one run of zeros that deflate
 * swallows in a few long matches, while SUB leaves a nonzero first pixel
 * and a spike at every object edge on every row.  Smooth shading varies
 * as little down a column as along a row, so inside the object they tie
 * (a 640x480 normals image: 151 KB both, 5.5 ms both).
 *
 * The deflate strategy is Z_RLE: after the UP filter the data is mostly
 * runs, and run-length matching finds them without hashing.  On the
 * 1920x1080 bunny as `softrast render` writes it (level 1, UP, best of 5):
 *     default strategy 371 KB 20.6 ms     Z_RLE 343 KB 19.7 ms
 * and stored (level 0) takes 10.9 ms for 6.2 MB: most of the remaining
 * time is libpng's row handling and checksums, not compression. */
#define WRITE_FILTER PNG_FILTER_UP
#define WRITE_STRATEGY Z_RLE

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

/* ---- writing ------------------------------------------------------------ */

typedef struct png_write_args {
    int width, height;
    const uint8_t *rgba;
    size_t stride;
    int level;              /* zlib level 0..9 */
    bool no_alpha;
} png_write_args;

/* The caller's allocator, for libpng (and, through libpng, zlib).  `failed`
 * tells an out-of-memory longjmp from a write error: libpng reports both
 * through the same error hook. */
typedef struct png_mem {
    sr_allocator a;
    bool failed;
} png_mem;

static void *mem_alloc(png_mem *m, size_t size)
{
    void *p = m->a.alloc ? m->a.alloc(size, m->a.user) : malloc(size);
    if (!p) {
        m->failed = true;
    }
    return p;
}

static void mem_free(png_mem *m, void *p)
{
    if (p) {
        if (m->a.alloc) {
            m->a.free(p, m->a.user);
        } else {
            free(p);
        }
    }
}

static png_voidp png_mem_alloc(png_structp png, png_alloc_size_t size)
{
    return mem_alloc(png_get_mem_ptr(png), size);
}

static void png_mem_free(png_structp png, png_voidp p)
{
    mem_free(png_get_mem_ptr(png), p);
}

/* Where the encoded bytes go: a buffer in front of the file descriptor,
 * written with write(2) directly rather than through stdio, whose fwrite
 * gives up on EINTR. */
typedef struct png_sink {
    int fd;
    uint8_t *buf;
    size_t n, cap;
} png_sink;

#define SINK_SIZE ((size_t)1 << 16)

static bool sink_flush(png_sink *s)
{
    bool ok = sr__write_all(s->fd, s->buf, s->n);
    s->n = 0;
    return ok;
}

static void sink_write(png_structp png, png_bytep data, size_t len)
{
    png_sink *s = png_get_io_ptr(png);
    if (s->n + len > s->cap && !sink_flush(s)) {
        png_error(png, "Write Error");
    }
    if (len >= s->cap) {
        if (!sr__write_all(s->fd, data, len)) {
            png_error(png, "Write Error");
        }
        return;
    }
    memcpy(s->buf + s->n, data, len);
    s->n += len;
}

static void sink_flush_hook(png_structp png)
{
    (void)png; /* sr_write_png flushes once, at the end */
}

/* Everything from png_create_write_struct to png_destroy_write_struct, in a
 * function of its own: nothing it declares changes after setjmp, so the
 * longjmp path may use all of it. */
static bool encode_png(png_sink *sink, png_mem *mem, const png_write_args *a, png_status *st)
{
    png_structp png = png_create_write_struct_2(PNG_LIBPNG_VER_STRING, st, on_png_error,
                                                on_png_warning, mem, png_mem_alloc,
                                                png_mem_free);
    if (!png) {
        st->code = SR_OUT_OF_MEMORY;
        snprintf(st->message, sizeof st->message, "out of memory creating the PNG writer");
        return false;
    }
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_write_struct(&png, NULL);
        st->code = SR_OUT_OF_MEMORY;
        snprintf(st->message, sizeof st->message, "out of memory creating the PNG writer");
        return false;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        if (mem->failed) { /* libpng says "Out of memory", or names zlib's failure */
            st->code = SR_OUT_OF_MEMORY;
            snprintf(st->message, sizeof st->message, "out of memory");
        }
        return false;
    }
    /* Errors from here on are the file's (a failed write: disk full, file
     * size limit) or the allocator's (mem->failed), not the data's. */
    st->code = SR_IO_ERROR;
    png_set_write_fn(png, sink, sink_write, sink_flush_hook);
    png_set_IHDR(png, info, (png_uint_32)a->width, (png_uint_32)a->height, 8,
                 a->no_alpha ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_RGB_ALPHA,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_compression_level(png, a->level);
    png_set_compression_strategy(png, WRITE_STRATEGY);
    /* Stored data gains nothing from filtering; otherwise one fixed filter
     * (see WRITE_FILTER) instead of libpng's per-row trial of all five. */
    png_set_filter(png, PNG_FILTER_TYPE_BASE, a->level == 0 ? PNG_FILTER_NONE : WRITE_FILTER);
    png_write_info(png, info);
    if (a->no_alpha) {
        /* On writing, a filler tells libpng the rows carry a fourth byte
         * that the RGB file does not: it drops it as it goes. */
        png_set_filler(png, 0, PNG_FILLER_AFTER);
    }
    /* Rows go straight from the caller's pixels, one at a time: no copy of
     * the image and no row-pointer array, and any stride works. */
    for (int y = 0; y < a->height; y++) {
        png_write_row(png, a->rgba + (size_t)y * a->stride);
    }
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    st->code = SR_OK;
    return true;
}

sr_result sr_write_png(const char *path, int width, int height,
                       const uint8_t *rgba, size_t stride,
                       const sr_png_write_desc *desc, sr_io_error *err)
{
    sr_result checked = sr__check_image_write(path, width, height, MAX_WRITE_SIZE, rgba, stride,
                                              err);
    if (checked != SR_OK) {
        return checked;
    }
    int level = desc ? desc->compression_level : 0;
    if (level == 0) {
        level = SR_PNG_DEFAULT_LEVEL;
    } else if (level == -1) {
        level = 0;
    } else if (level < 1 || level > 9) {
        return sr__io_fail(err, SR_INVALID_ARG, path, 0,
                           "sr_png_write_desc.compression_level %d is not in -1..9", level);
    }
    png_write_args args = {
        .width = width, .height = height, .rgba = rgba, .stride = stride,
        .level = level, .no_alpha = desc && desc->no_alpha,
    };

    png_mem mem = { .a = desc ? desc->allocator : (sr_allocator){0} };
    if ((mem.a.alloc == NULL) != (mem.a.free == NULL)) {
        return sr__io_fail(err, SR_INVALID_ARG, path, 0,
                           "sr_png_write_desc.allocator needs both alloc and free");
    }
    sr_atomic_file file;
    sr_result result = sr__atomic_create(&file, path, mem.a, err);
    if (result != SR_OK) {
        return result;
    }
    png_sink sink = { .fd = file.fd, .buf = mem_alloc(&mem, SINK_SIZE), .cap = SINK_SIZE };
    if (!sink.buf) {
        sr__atomic_discard(&file);
        return sr__io_fail(err, SR_OUT_OF_MEMORY, path, 0, "out of memory");
    }
    png_status status = { .code = SR_OK };
    errno = 0;  /* so that a stale errno is never reported as the cause */
    bool encoded = encode_png(&sink, &mem, &args, &status);
    if (encoded && !sink_flush(&sink)) {
        encoded = false;
        status = (png_status){ .code = SR_IO_ERROR, .saved_errno = errno };
        snprintf(status.message, sizeof status.message, "Write Error");
    }
    mem_free(&mem, sink.buf);
    if (!encoded) {
        sr__atomic_discard(&file);
        if (status.code == SR_IO_ERROR && status.saved_errno != 0) {
            return sr__io_fail(err, SR_IO_ERROR, path, 0, "write failed: %s (libpng: %s)",
                               strerror(status.saved_errno), status.message);
        }
        return sr__io_fail(err, status.code, path, 0, "cannot encode PNG: %s", status.message);
    }
    return sr__atomic_commit(&file, err);
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

sr_result sr_read_png(const char *path, int *width, int *height,
                      uint8_t **pixels, sr_io_error *err)
{
    return sr_read_png_desc(path, NULL, width, height, pixels, err);
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

sr_result sr_read_png_desc(const char *path, const sr_png_read_desc *desc, int *width,
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
