/* io_util.h - shared by the model readers and the image code (src/io):
 * whole-file reading with limits, and error messages in the one form the
 * CLI prints ("FILE:LINE: what is wrong" / "FILE: byte N: what is wrong"). */
#ifndef SR_IO_UTIL_H
#define SR_IO_UTIL_H

#include "softrast_io.h"

#include <stdarg.h>
#include <stdio.h>

/* Message "name:line: ..." (line > 0), "name: byte N: ..." (sr__io_fail_at),
 * or "name: ..." (line == 0).  A name too long for sr_io_error.message
 * loses its head ("...tail:line: ..."), never the position or the reason.
 * Returns `code` so callers can `return sr__io_fail(...)`. */
sr_result sr__io_fail(sr_io_error *err, sr_result code, const char *name,
                      long line, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
sr_result sr__io_fail_at(sr_io_error *err, sr_result code, const char *name,
                         unsigned long long byte_offset, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));

/* A message without a file name ("sr_check_memory: desc is NULL") in err
 * (may be NULL) and, for a failure (code other than SR_OK), in the
 * thread's sr_last_error; returns code. */
sr_result sr__io_message(sr_io_error *err, sr_result code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* For the calls whose readers may meet a failure and carry on (a texture
 * skipped with a warning, SVG path data that ends early): the thread's
 * sr_last_error before the call, and `r` after putting it back when the
 * call succeeded, so that a success leaves it as it was. */
void sr__last_error_save(sr_io_error *saved);
sr_result sr__last_error_keep(sr_result r, const sr_io_error *saved);

/* snprintf(out, cap, fmt, ...) for the JSON pointers a reader builds for
 * the elements it walks (json_pointer.c): formats of %s, %d, %ld and %zu
 * alone, cut as snprintf cuts. */
void sr__json_pointer(char *out, size_t cap, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Open a regular file for reading: *f and its size, or a message naming
 * the file ("cannot open: ...", "is a directory, not KIND", with KIND
 * such as "a PNG file", or "not a regular file").  Never waits for
 * another process: a FIFO is refused, not read. */
sr_result sr__open_regular(const char *path, const char *kind, FILE **f,
                           unsigned long long *size, sr_io_error *err);

/* Read a whole regular file (directories, devices and files larger than
 * SR_IO_MAX_FILE_BYTES are refused with a clear message).  The buffer has
 * one extra NUL byte after `*size` bytes; release it with sr__free_file. */
sr_result sr__read_file(const char *path, char **data, size_t *size, sr_io_error *err);
/* The same for a file of another KIND ("a JPEG file"), named so in messages. */
sr_result sr__read_file_as(const char *path, const char *kind, char **data, size_t *size,
                           sr_io_error *err);
void sr__free_file(char *data, size_t size);

/* Read a whole file and hand it to a parser (the readers' sr__load_*):
 * *out is zeroed first and the buffer freed after. */
typedef sr_result (*sr_parse_fn)(const char *name, const uint8_t *data, size_t size,
                                 sr_mesh *out, sr_io_error *err);
sr_result sr__load_file_with(const char *path, sr_parse_fn parse, sr_mesh *out,
                             sr_io_error *err);

/* The image readers' outputs before anything is read: an empty message,
 * a 0 x 0 size and no pixels (each pointer may be NULL). */
void sr__image_outputs_clear(int *width, int *height, uint8_t **pixels, sr_io_error *err);
/* The same for a decoder of bytes in memory, then its arguments checked:
 * *name becomes "<memory>" when NULL; SR_INVALID_ARG with a message when
 * an output pointer is NULL, or data is NULL with size > 0. */
sr_result sr__decode_args(const char **name, const uint8_t *data, size_t size, int *width,
                          int *height, uint8_t **pixels, sr_io_error *err);

/* webp.c: a WebP image in memory as sr_decode_png decodes a PNG
 * (SR_UNSUPPORTED in a build without libwebp), and whether it can. */
sr_result sr__decode_webp(const char *name, const uint8_t *data, size_t size, int *width,
                          int *height, uint8_t **pixels, sr_io_error *err);
bool sr__io_have_webp(void);

/* The image writers' common arguments: a path, RGBA8 pixels, a size of
 * 1..max_side a side and a stride of at least 4 width bytes.  Clears the
 * message; SR_INVALID_ARG with a message naming the path otherwise. */
sr_result sr__check_image_write(const char *path, int width, int height, int max_side,
                                const uint8_t *rgba, size_t stride, sr_io_error *err);

/* An output file written atomically (atomic_file.c): create it, write to
 * fd (sr__write_all), then commit - fsync, rename over the target (the
 * file a symbolic link names), sync the directory - or discard it.  On
 * any failure nothing is left behind and an existing target keeps its
 * bytes; a replaced file keeps its permissions, a new one gets 0666 less
 * the umask.  The temporary's name comes from `a` (zero: malloc). */
typedef struct sr_atomic_file {
    const char *path;      /* as given, for messages */
    const char *target;    /* the file replaced: path, or where its link points */
    char *resolved;        /* realpath's string, or NULL */
    char *tmp;             /* "<dir>/.<base>.XXXXXX" */
    int fd;
    sr_allocator a;
} sr_atomic_file;

sr_result sr__atomic_create(sr_atomic_file *f, const char *path, sr_allocator a,
                            sr_io_error *err);
sr_result sr__atomic_commit(sr_atomic_file *f, sr_io_error *err);
void sr__atomic_discard(sr_atomic_file *f);
/* All n bytes or false with errno set (EINTR retried, short writes continued). */
bool sr__write_all(int fd, const uint8_t *p, size_t n);
/* sr__write_all as an sr_write_fn, `user` pointing to the int descriptor:
 * the encoders' callback for a file. */
bool sr__write_fd(void *user, const void *data, size_t size);

/* A block from the caller's allocator (zero: malloc/free), as every io
 * function that takes an sr_allocator uses it.  sr__io_free ignores NULL. */
void *sr__io_alloc(const sr_allocator *a, size_t size);
void sr__io_free(const sr_allocator *a, void *p);

/* Overflow-checked size arithmetic for allocations sized by input. */
static inline bool sr__mul_ok(size_t a, size_t b, size_t *out)
{
    return !__builtin_mul_overflow(a, b, out);
}

/* Bytes as people read them, "8.5 GiB", "640 MiB", into buf (memory_limit.c). */
void sr__format_bytes(uint64_t n, char *buf, size_t size);

/* Standard (or URL-safe) base64, '=' padding optional, blanks skipped:
 * *out a malloc'd block of *size bytes, or NULL (true returned) when a
 * character is not base64; false only when out of memory. */
bool sr__base64_decode(const char *s, size_t n, uint8_t **out, size_t *size);

/* sr_load_desc's pose fields checked (desc may be NULL): the pose one of
 * sr_load_pose's, a finite time.  The animation's index is the glTF
 * reader's to check, against the file's animations. */
sr_result sr__check_load_pose(const sr_load_desc *desc, const char *name, sr_io_error *err);

#endif
