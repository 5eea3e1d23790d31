/* png_write.c - io, the end of the pipeline: framebuffer pixels to a PNG
 * file.  sr_write_png consumes RGBA8 rows (any stride) and produces a file
 * that appears whole or not at all (atomic_file.c).
 *
 * zlib compresses; the container around it - signature, IHDR, IDAT, IEND
 * and their CRCs - is a few dozen lines written here rather than through
 * libpng's writer, because libpng feeds one zlib stream a row at a time
 * on one thread, and deflate is most of a PNG's time: the 1920x1080 bunny
 * that `softrast render` writes took 19-21 ms to deflate out of libpng's
 * 24 ms.  Here the rows are cut into bands of about BAND_BYTES, each band
 * filtered and deflated on its own (a raw stream ended by a sync flush,
 * the last by the final block), on the context's threads when the caller
 * names one, and the pieces follow one another in one zlib stream, its
 * Adler-32 combined from theirs (pigz does the same).  The band size
 * depends on the row size alone, so the file has the same bytes for any
 * number of threads, or none.
 *
 * One fixed filter rather than libpng's default of trying all five on
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
 * At level 1 (the default) the deflate strategy is Z_RLE: after the UP
 * filter the data is mostly runs, and run-length matching finds them
 * without hashing.  On the 1920x1080 bunny as `softrast render` writes it
 * (level 1, UP, best of 5): default strategy 371 KB 20.6 ms, Z_RLE 343 KB
 * 19.7 ms.  Z_RLE ignores the level, so levels 2-9 keep zlib's default
 * strategy: slower, and smaller where the image has repeats further back
 * than the pixel above.  Level 0 stores the rows unfiltered. */
#include "io/io_util.h"

#include "context.h"
#include "parallel/pool.h"

#include <zlib.h>

#include <errno.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#define MAX_WRITE_SIZE 65535 /* per side, as documented */

/* Filtered bytes per band, at least one row: 24 bands for a 1920x1080 RGB
 * image.  A band ends its deflate blocks and loses the matches the next
 * would have found across the cut (a run at most, under Z_RLE): on that
 * image 24 bands made the file 0.4% smaller than one stream, from the
 * extra Huffman tables fitted to each band. */
#define BAND_BYTES ((size_t)256 * 1024)

typedef struct png_job {
    /* The image. */
    const uint8_t *rgba;
    size_t stride;
    int width, height;
    int channels;              /* 4, or 3 with SR_PNG_RGB */
    int level;                 /* zlib level, 0 = stored */
    size_t row_bytes;          /* a filtered row, its filter byte included */
    int band_rows, bands;
    /* Per band: its compressed bytes at out + b * out_cap, and the
     * Adler-32 of its filtered bytes. */
    uint8_t *out;
    size_t out_cap;
    size_t *out_len;
    uLong *adler;
    /* Per slot (one thread at a time each): a deflate stream and a row. */
    z_stream *streams;
    uint8_t *rows;
    atomic_int next_band;
    atomic_bool failed;
} png_job;

/* Row y filtered into dst: a filter-type byte, then the row's bytes minus
 * those of the row above (UP; the row above row 0 is zeros), or unfiltered
 * when stored.  RGB drops each pixel's fourth byte. */
static void filter_row(const png_job *j, int y, uint8_t *dst)
{
    const uint8_t *src = j->rgba + (size_t)y * j->stride;
    const uint8_t *up = y > 0 && j->level > 0 ? src - j->stride : NULL;
    size_t n = (size_t)j->width;
    dst[0] = up ? 2 : 0;   /* UP; row 0 under UP equals NONE, and says so */
    uint8_t *d = dst + 1;
    if (j->channels == 4) {
        if (up) {
            for (size_t i = 0; i < 4 * n; i++) {
                d[i] = (uint8_t)(src[i] - up[i]);
            }
        } else {
            memcpy(d, src, 4 * n);
        }
        return;
    }
    for (size_t x = 0; x < n; x++) {
        for (int c = 0; c < 3; c++) {
            d[3 * x + c] = (uint8_t)(src[4 * x + c] - (up ? up[4 * x + c] : 0));
        }
    }
}

static bool deflate_band(png_job *j, int band, z_stream *z, uint8_t *row)
{
    if (deflateReset(z) != Z_OK) {
        return false;
    }
    z->next_out = j->out + (size_t)band * j->out_cap;
    z->avail_out = (uInt)j->out_cap;
    uLong adler = adler32(0L, Z_NULL, 0);
    int y0 = band * j->band_rows;
    int y1 = y0 + j->band_rows < j->height ? y0 + j->band_rows : j->height;
    for (int y = y0; y < y1; y++) {
        filter_row(j, y, row);
        adler = adler32(adler, row, (uInt)j->row_bytes);
        z->next_in = row;
        z->avail_in = (uInt)j->row_bytes;
        if (deflate(z, Z_NO_FLUSH) != Z_OK || z->avail_in != 0) {
            return false;
        }
    }
    /* A sync flush ends the band on a byte boundary with no final block,
     * so the next band's blocks may follow; the last band finishes. */
    bool last = band == j->bands - 1;
    int ret = deflate(z, last ? Z_FINISH : Z_SYNC_FLUSH);
    if (ret != (last ? Z_STREAM_END : Z_OK) || z->avail_out == 0) {
        return false;   /* out of room: the bound below was wrong */
    }
    j->out_len[band] = j->out_cap - z->avail_out;
    j->adler[band] = adler;
    return true;
}

/* One slot: bands in any order, as they come; each lands in its own place. */
static void run_slot(void *arg, int slot, int thread)
{
    (void)thread;
    png_job *j = arg;
    z_stream *z = &j->streams[slot];
    uint8_t *row = j->rows + (size_t)slot * j->row_bytes;
    int band;
    while (!atomic_load_explicit(&j->failed, memory_order_relaxed) &&
           (band = atomic_fetch_add_explicit(&j->next_band, 1, memory_order_relaxed)) < j->bands) {
        if (!deflate_band(j, band, z, row)) {
            atomic_store(&j->failed, true);
        }
    }
}

/* zlib's blocks through the caller's allocator. */
static voidpf zlib_alloc(voidpf opaque, uInt items, uInt size)
{
    size_t n;
    return sr__mul_ok(items, size, &n) ? sr__io_alloc(opaque, n) : NULL;
}

static void zlib_free(voidpf opaque, voidpf p)
{
    sr__io_free(opaque, p);
}

/* ---- the container ------------------------------------------------------ */

static void put32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24);
    p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

/* Where the file's bytes go: a buffer in front of the caller's write
 * function (for a file, write(2) through sr__write_all, which retries
 * EINTR and short writes). */
typedef struct png_sink {
    sr_write_fn write;
    void *user;
    uint8_t *buf;
    size_t n, cap;
    bool failed;
} png_sink;

#define SINK_SIZE ((size_t)1 << 16)

static void sink_put(png_sink *s, const uint8_t *p, size_t len)
{
    if (s->failed) {
        return;
    }
    if (s->n + len > s->cap) {
        s->failed = !s->write(s->user, s->buf, s->n);
        s->n = 0;
        if (!s->failed && len >= s->cap) {
            s->failed = !s->write(s->user, p, len);
            return;
        }
    }
    if (!s->failed) {
        memcpy(s->buf + s->n, p, len);
        s->n += len;
    }
}

/* A chunk whose data is up to three pieces in a row (a piece may be
 * empty): length, type, data, CRC of type and data. */
static void put_chunk(png_sink *s, const char type[4], const uint8_t *const piece[3],
                      const size_t len[3])
{
    uint8_t head[8];
    put32(head, (uint32_t)(len[0] + len[1] + len[2]));
    memcpy(head + 4, type, 4);
    sink_put(s, head, 8);
    uLong crc = crc32(0L, head + 4, 4);
    for (int i = 0; i < 3; i++) {
        if (len[i] > 0) {
            sink_put(s, piece[i], len[i]);
            crc = crc32(crc, piece[i], (uInt)len[i]);
        }
    }
    uint8_t tail[4];
    put32(tail, (uint32_t)crc);
    sink_put(s, tail, 4);
}

/* Signature, IHDR, one IDAT a band (the first opening the zlib stream,
 * the last closing it with the Adler-32 of every band), IEND. */
static void put_file(png_sink *s, const png_job *j)
{
    static const uint8_t signature[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n' };
    sink_put(s, signature, 8);

    uint8_t ihdr[13];
    put32(ihdr, (uint32_t)j->width);
    put32(ihdr + 4, (uint32_t)j->height);
    ihdr[8] = 8;                            /* bits per channel */
    ihdr[9] = j->channels == 4 ? 6 : 2;     /* RGBA or RGB */
    ihdr[10] = ihdr[11] = ihdr[12] = 0;     /* deflate, adaptive filters, no interlace */
    put_chunk(s, "IHDR", (const uint8_t *const[3]){ ihdr, NULL, NULL },
              (const size_t[3]){ 13, 0, 0 });

    /* zlib header: deflate with a 32 KiB window; FLEVEL 0 ("fastest")
     * for stored data and Z_RLE, 2 (default) otherwise, as zlib writes it;
     * the check bits make the pair a multiple of 31. */
    unsigned flevel = j->level <= 1 ? 0 : 2;
    unsigned cmf = 0x78, flg = flevel << 6;
    flg += 31 - (cmf * 256 + flg) % 31;
    const uint8_t zhead[2] = { (uint8_t)cmf, (uint8_t)flg };

    uLong adler = j->adler[0];
    for (int b = 1; b < j->bands; b++) {
        z_off_t len = (z_off_t)j->band_rows * (z_off_t)j->row_bytes;
        if (b == j->bands - 1) {
            len = (z_off_t)(j->height - b * j->band_rows) * (z_off_t)j->row_bytes;
        }
        adler = adler32_combine(adler, j->adler[b], len);
    }
    uint8_t ztail[4];
    put32(ztail, (uint32_t)adler);

    for (int b = 0; b < j->bands; b++) {
        bool first = b == 0, last = b == j->bands - 1;
        put_chunk(s, "IDAT",
                  (const uint8_t *const[3]){ zhead, j->out + (size_t)b * j->out_cap, ztail },
                  (const size_t[3]){ first ? 2 : 0, j->out_len[b], last ? 4 : 0 });
    }
    put_chunk(s, "IEND", (const uint8_t *const[3]){ NULL, NULL, NULL },
              (const size_t[3]){ 0, 0, 0 });
    if (!s->failed && s->n > 0) {
        s->failed = !s->write(s->user, s->buf, s->n);
    }
}

/* ---- sr_write_png --------------------------------------------------------- */

/* Every block the encoding takes, so that one failure frees them all. */
typedef struct png_blocks {
    sr_allocator a;
    uint8_t *out, *rows, *sink;
    size_t *out_len;
    uLong *adler;
    z_stream *streams;
    int streams_ready;
} png_blocks;

static void free_blocks(png_blocks *m)
{
    for (int i = 0; i < m->streams_ready; i++) {
        deflateEnd(&m->streams[i]);
    }
    sr__io_free(&m->a, m->streams);
    sr__io_free(&m->a, m->out);
    sr__io_free(&m->a, m->rows);
    sr__io_free(&m->a, m->sink);
    sr__io_free(&m->a, m->out_len);
    sr__io_free(&m->a, m->adler);
}

/* Allocate the job's memory and start its deflate streams: false when the
 * allocator says no. */
static bool prepare(png_job *j, png_blocks *m, int slots)
{
    size_t n_bands = (size_t)j->bands;
    m->streams = sr__io_alloc(&m->a, sizeof(z_stream) * (size_t)slots);
    if (!m->streams) {
        return false;
    }
    /* Level 1 is Z_RLE (see the top); a raw stream (negative window bits),
     * since the bands' pieces share one zlib header and trailer. */
    int strategy = j->level == 1 ? Z_RLE : Z_DEFAULT_STRATEGY;
    for (int i = 0; i < slots; i++) {
        z_stream *z = &m->streams[i];
        *z = (z_stream){ .zalloc = zlib_alloc, .zfree = zlib_free, .opaque = &m->a };
        if (deflateInit2(z, j->level, Z_DEFLATED, -15, 8, strategy) != Z_OK) {
            return false;
        }
        m->streams_ready++;
    }
    /* A band's worst case, with room for the sync flush's empty stored
     * block and the final block's bits. */
    size_t band_in = (size_t)j->band_rows * j->row_bytes;
    j->out_cap = deflateBound(&m->streams[0], (uLong)band_in) + 64;
    size_t out_size, rows_size;
    if (!sr__mul_ok(j->out_cap, n_bands, &out_size) ||
        !sr__mul_ok(j->row_bytes, (size_t)slots, &rows_size)) {
        return false;
    }
    m->out = sr__io_alloc(&m->a, out_size);
    m->rows = sr__io_alloc(&m->a, rows_size);
    m->out_len = sr__io_alloc(&m->a, sizeof(size_t) * n_bands);
    m->adler = sr__io_alloc(&m->a, sizeof(uLong) * n_bands);
    m->sink = sr__io_alloc(&m->a, SINK_SIZE);
    j->out = m->out;
    j->rows = m->rows;
    j->out_len = m->out_len;
    j->adler = m->adler;
    j->streams = m->streams;
    return m->out && m->rows && m->out_len && m->adler && m->sink;
}

/* The encoding's settings from desc, checked: the job to run, its
 * allocator, the context and how many slots run it. */
static sr_result png_settings(const char *name, int width, int height, const uint8_t *rgba,
                              size_t stride, const sr_png_write_desc *desc, png_job *j,
                              png_blocks *m, int *slots, sr_io_error *err)
{
    sr_result checked = sr__check_image_write(name, width, height, MAX_WRITE_SIZE, rgba, stride,
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
        return sr__io_fail(err, SR_INVALID_ARG, name, 0,
                           "sr_png_write_desc.compression_level %d is not in -1..9", level);
    }
    *m = (png_blocks){ .a = desc ? desc->allocator : (sr_allocator){0} };
    if ((m->a.alloc == NULL) != (m->a.free == NULL)) {
        return sr__io_fail(err, SR_INVALID_ARG, name, 0,
                           "sr_png_write_desc.allocator needs both alloc and free");
    }
    if (desc && (unsigned)desc->channels > SR_PNG_RGB) {
        return sr__io_fail(err, SR_INVALID_ARG, name, 0,
                           "sr_png_write_desc.channels %d is not an sr_png_channels",
                           (int)desc->channels);
    }
    sr_context *ctx = desc ? desc->context : NULL;

    *j = (png_job){
        .rgba = rgba, .stride = stride, .width = width, .height = height,
        .channels = desc && desc->channels == SR_PNG_RGB ? 3 : 4, .level = level,
    };
    j->row_bytes = 1 + (size_t)j->channels * (size_t)width;
    j->band_rows = j->row_bytes >= BAND_BYTES ? 1 : (int)(BAND_BYTES / j->row_bytes);
    if (j->band_rows > height) {
        j->band_rows = height;
    }
    j->bands = (height + j->band_rows - 1) / j->band_rows;
    int threads = ctx ? ctx->threads : 1;
    *slots = threads < j->bands ? threads : j->bands;
    return SR_OK;
}

/* Deflate the job and hand the file's bytes to `write`; every block is
 * freed before it returns.  When `write` fails: SR_IO_ERROR with
 * *write_failed set and no message (the caller knows what the write was). */
static sr_result png_run(const char *name, png_job *j, png_blocks *m, sr_context *ctx,
                         int slots, sr_write_fn write, void *user, bool *write_failed,
                         sr_io_error *err)
{
    *write_failed = false;
    if (!prepare(j, m, slots)) {
        free_blocks(m);
        return sr__io_fail(err, SR_OUT_OF_MEMORY, name, 0, "cannot encode PNG: out of memory");
    }
    sr__pool_run(ctx && slots > 1 ? ctx->pool : NULL, run_slot, j, slots);
    if (atomic_load(&j->failed)) {
        free_blocks(m);
        return sr__io_fail(err, SR_IO_ERROR, name, 0, "cannot encode PNG: zlib failed");
    }
    png_sink sink = { .write = write, .user = user, .buf = m->sink, .cap = SINK_SIZE };
    put_file(&sink, j);
    free_blocks(m);
    *write_failed = sink.failed;
    return sink.failed ? SR_IO_ERROR : SR_OK;
}

/* Both entry points: to `write`, or (file non-NULL) to a new file at
 * `name` written atomically. */
static sr_result png_encode(const char *name, sr_atomic_file *file, sr_write_fn write,
                            void *user, int width, int height, const uint8_t *rgba,
                            size_t stride, const sr_png_write_desc *desc, sr_io_error *err)
{
    png_job j;
    png_blocks m;
    int slots = 1;
    sr_result r = png_settings(name, width, height, rgba, stride, desc, &j, &m, &slots, err);
    if (r != SR_OK) {
        return r;
    }
    if (file) {
        r = sr__atomic_create(file, name, m.a, err);
        if (r != SR_OK) {
            return r;
        }
        write = sr__write_fd;
        user = &file->fd;
    } else if (!write) {
        return sr__io_fail(err, SR_INVALID_ARG, name, 0, "no write function given");
    }
    errno = 0;  /* so that a stale errno is never reported as the cause */
    bool write_failed;
    r = png_run(name, &j, &m, desc ? desc->context : NULL, slots, write, user, &write_failed,
                err);
    int saved_errno = errno;
    if (r == SR_OK) {
        return file ? sr__atomic_commit(file, err) : SR_OK;
    }
    if (file) {
        sr__atomic_discard(file);
    }
    if (!write_failed) {
        return r;
    }
    return file ? sr__io_fail(err, r, name, 0, "write failed: %s",
                              strerror(saved_errno ? saved_errno : EIO))
                : sr__io_fail(err, r, name, 0, "the write function failed");
}

sr_result sr_encode_png(sr_write_fn write, void *user, int width, int height,
                        const uint8_t *rgba, size_t stride, const sr_png_write_desc *desc,
                        sr_io_error *err)
{
    return png_encode("<memory>", NULL, write, user, width, height, rgba, stride, desc, err);
}

sr_result sr_write_png(const char *path, int width, int height,
                       const uint8_t *rgba, size_t stride,
                       const sr_png_write_desc *desc, sr_io_error *err)
{
    sr_atomic_file file;
    return png_encode(path, &file, NULL, NULL, width, height, rgba, stride, desc, err);
}
