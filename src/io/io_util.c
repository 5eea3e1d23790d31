/* io_util.c - file reading and error messages shared by the readers. */
#define _DEFAULT_SOURCE 1           /* MAP_ANONYMOUS, MAP_POPULATE */
#include "io/io_util.h"
#include "rows.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

/* A shortened name keeps at least this many bytes of its tail (the file's
 * own name, usually), even when a very long reason has to lose its end. */
#define MIN_NAME_TAIL 40
#define ELISION "..."

/* Copy `s` to dst + at, as much as fits before `cap`; the new end. */
static size_t append(char *dst, size_t at, size_t cap, const char *s)
{
    size_t n = strlen(s);
    if (n > cap - at) {
        n = cap - at;
    }
    memcpy(dst + at, s, n);
    return at + n;
}

/* The message "NAME" + `where` (":LINE: ", ": byte N: " or ": ") + the
 * reason.  The position and the reason are what the reader needs, so when
 * the whole does not fit, the name gives way from the left: "..." and its
 * tail, cut at a UTF-8 character boundary.  A failure's message is also
 * the thread's sr_last_error, err or not; a warning's (code SR_OK) is
 * err's alone. */
static void format_message(sr_io_error *err, sr_result code, const char *name,
                           const char *where, const char *fmt, va_list ap)
{
    sr_io_error own;
    if (!err) {
        if (code == SR_OK) {
            return;
        }
        err = &own;
    }
    char reason[sizeof err->message];
    vsnprintf(reason, sizeof reason, fmt, ap);
    size_t cap = sizeof err->message - 1;
    size_t fixed = strlen(where) + strlen(reason);
    size_t room = fixed < cap ? cap - fixed : 0;
    if (room < sizeof ELISION - 1 + MIN_NAME_TAIL) {
        room = sizeof ELISION - 1 + MIN_NAME_TAIL;
    }
    size_t len = strlen(name);
    const char *elision = "";
    if (len > room) {
        elision = ELISION;
        name += len - (room - (sizeof ELISION - 1));
        while (((unsigned char)*name & 0xC0) == 0x80) {
            name++;             /* not inside a multi-byte character */
        }
    }
    size_t n = append(err->message, 0, cap, elision);
    n = append(err->message, n, cap, name);
    n = append(err->message, n, cap, where);
    n = append(err->message, n, cap, reason);
    err->message[n] = 0;
    /* Names and quoted tokens come from the input: a control byte (an
     * escape sequence, a newline) would reach the user's terminal or
     * break the message's one line. */
    for (size_t i = 0; i < n; i++) {
        unsigned char c = (unsigned char)err->message[i];
        if (c < 0x20 || c == 0x7f) {
            err->message[i] = '?';
        }
    }
    if (code != SR_OK) {
        sr_set_last_error(err->message);
    }
}

sr_result sr__io_fail(sr_io_error *err, sr_result code, const char *name,
                      long line, const char *fmt, ...)
{
    char where[32];
    if (line > 0) {
        snprintf(where, sizeof where, ":%ld: ", line);
    } else {
        snprintf(where, sizeof where, ": ");
    }
    va_list ap;
    va_start(ap, fmt);
    format_message(err, code, name ? name : "<input>", where, fmt, ap);
    va_end(ap);
    return code;
}

sr_result sr__io_message(sr_io_error *err, sr_result code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    format_message(err, code, "", "", fmt, ap);
    va_end(ap);
    return code;
}

void sr__last_error_save(sr_io_error *saved)
{
    snprintf(saved->message, sizeof saved->message, "%s", sr_last_error());
}

sr_result sr__last_error_keep(sr_result r, const sr_io_error *saved)
{
    if (r == SR_OK) {
        sr_set_last_error(saved->message);
    }
    return r;
}

sr_result sr__io_fail_at(sr_io_error *err, sr_result code, const char *name,
                         unsigned long long byte_offset, const char *fmt, ...)
{
    char where[40];
    snprintf(where, sizeof where, ": byte %llu: ", byte_offset);
    va_list ap;
    va_start(ap, fmt);
    format_message(err, code, name ? name : "<input>", where, fmt, ap);
    va_end(ap);
    return code;
}

sr_result sr__load_file_with(const char *path, sr_parse_fn parse, sr_mesh *out,
                             sr_io_error *err)
{
    if (out) {
        memset(out, 0, sizeof *out);
    }
    char *data;
    size_t size;
    sr_result res = sr__read_file(path, &data, &size, err);
    if (res != SR_OK) {
        return res;
    }
    res = parse(path, (const uint8_t *)data, size, out, err);
    sr__free_file(data, size);
    return res;
}

/* Files from this size on are read into memory mapped with its pages
 * already in place: faulting in a fresh malloc'd buffer page by page made
 * up a quarter of the Stanford bunny's 22 ms first load on the
 * development VM (15.8 ms populated, medians of 12 fresh processes). */
#define SR_IO_POPULATE_BYTES ((size_t)1 << 20)

static char *alloc_file(size_t bytes)
{
#if defined(MAP_ANONYMOUS) && defined(MAP_POPULATE)
    if (bytes >= SR_IO_POPULATE_BYTES) {
        void *m = mmap(NULL, bytes, PROT_READ | PROT_WRITE,
                       MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
        return m == MAP_FAILED ? NULL : m;
    }
#endif
    return malloc(bytes);
}

void sr__free_file(char *data, size_t size)
{
    if (!data) {
        return;
    }
#if defined(MAP_ANONYMOUS) && defined(MAP_POPULATE)
    if (size + 1 >= SR_IO_POPULATE_BYTES) {
        munmap(data, size + 1);
        return;
    }
#endif
    free(data);
}

sr_result sr__open_regular(const char *path, const char *kind, FILE **f,
                           unsigned long long *size, sr_io_error *err)
{
    *f = NULL;
    *size = 0;
    if (!path || !kind) {
        return sr__io_fail(err, SR_INVALID_ARG, path ? path : "<null>", 0,
                           "no file name or kind given");
    }
    /* O_NONBLOCK: opening a FIFO for reading otherwise waits until some
     * process opens it for writing, which may be never.  The file type is
     * only known once it is open, so open without waiting, then refuse. */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        return sr__io_fail(err, SR_IO_ERROR, path, 0, "cannot open: %s", strerror(errno));
    }
    struct stat st;
    if (fstat(fd, &st) != 0) {
        int e = errno;
        close(fd);
        return sr__io_fail(err, SR_IO_ERROR, path, 0, "cannot stat: %s", strerror(e));
    }
    if (S_ISDIR(st.st_mode)) {
        close(fd);
        return sr__io_fail(err, SR_IO_ERROR, path, 0, "is a directory, not %s", kind);
    }
    /* FIFOs, sockets and devices (/dev/zero never ends) are not files to
     * read whole. */
    if (!S_ISREG(st.st_mode)) {
        close(fd);
        return sr__io_fail(err, SR_IO_ERROR, path, 0, "not a regular file");
    }
    /* Reads from a regular file do not block anyway; clear the flag so the
     * descriptor is the plain one fopen would have given. */
    int flags = fcntl(fd, F_GETFL);
    if (flags < 0 || fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) != 0) {
        int e = errno;
        close(fd);
        return sr__io_fail(err, SR_IO_ERROR, path, 0, "cannot open: %s", strerror(e));
    }
    *f = fdopen(fd, "rb");
    if (!*f) {
        int e = errno;
        close(fd);
        return sr__io_fail(err, e == ENOMEM ? SR_OUT_OF_MEMORY : SR_IO_ERROR, path, 0,
                           "cannot open: %s", strerror(e));
    }
    *size = (unsigned long long)st.st_size;
    return SR_OK;
}

sr_result sr_open_file(const char *path, const char *kind, FILE **f, unsigned long long *size,
                       sr_io_error *err)
{
    if (!f || !size) {
        if (f) {
            *f = NULL;
        }
        if (size) {
            *size = 0;
        }
        return sr__io_fail(err, SR_INVALID_ARG, path ? path : "<null>", 0,
                           "sr_open_file: %s is NULL", f ? "size" : "f");
    }
    return sr__open_regular(path, kind, f, size, err);
}

sr_result sr__read_file(const char *path, char **data, size_t *size, sr_io_error *err)
{
    return sr__read_file_as(path, "a model file", data, size, err);
}

sr_result sr__read_file_as(const char *path, const char *kind, char **data, size_t *size,
                           sr_io_error *err)
{
    *data = NULL;
    *size = 0;
    if (!path) {
        return sr__io_fail(err, SR_INVALID_ARG, "<null>", 0, "no file name given");
    }
    FILE *f;
    unsigned long long file_size;
    sr_result res = sr__open_regular(path, kind, &f, &file_size, err);
    if (res != SR_OK) {
        return res;
    }
    if (file_size > SR_IO_MAX_FILE_BYTES) {
        fclose(f);
        return sr__io_fail(err, SR_TOO_LARGE, path, 0,
                           "file is %llu bytes, larger than the %zu-byte limit",
                           file_size, (size_t)SR_IO_MAX_FILE_BYTES);
    }
    size_t n = (size_t)file_size;
    char *buf = alloc_file(n + 1);
    if (!buf) {
        fclose(f);
        return sr__io_fail(err, SR_OUT_OF_MEMORY, path, 0, "out of memory reading %zu bytes", n);
    }
    size_t got = n ? fread(buf, 1, n, f) : 0;
    int read_error = ferror(f);
    fclose(f);
    if (got != n || read_error) {
        sr__free_file(buf, n);
        return sr__io_fail(err, SR_IO_ERROR, path, 0, "read error (got %zu of %zu bytes)", got, n);
    }
    buf[n] = 0;
    *data = buf;
    *size = n;
    return SR_OK;
}

void sr__image_outputs_clear(int *width, int *height, uint8_t **pixels, sr_io_error *err)
{
    if (err) {
        err->message[0] = 0;
    }
    if (width) {
        *width = 0;
    }
    if (height) {
        *height = 0;
    }
    if (pixels) {
        *pixels = NULL;
    }
}

sr_result sr__decode_args(const char **name, const uint8_t *data, size_t size, int *width,
                          int *height, uint8_t **pixels, sr_io_error *err)
{
    sr__image_outputs_clear(width, height, pixels, err);
    if (!*name) {
        *name = "<memory>";
    }
    if (!width || !height || !pixels || (!data && size > 0)) {
        return sr__io_fail(err, SR_INVALID_ARG, *name, 0,
                           "width, height, pixels and data must not be NULL");
    }
    return SR_OK;
}

sr_result sr__check_image_write(const char *path, int width, int height, int max_side,
                                const uint8_t *rgba, size_t stride, sr_io_error *err)
{
    if (err) {
        err->message[0] = 0;
    }
    if (!path || !path[0]) {
        return sr__io_fail(err, SR_INVALID_ARG, "<null>", 0, "no file name given");
    }
    if (!rgba) {
        return sr__io_fail(err, SR_INVALID_ARG, path, 0, "no pixels given (rgba is NULL)");
    }
    if (width < 1 || width > max_side || height < 1 || height > max_side) {
        return sr__io_fail(err, SR_INVALID_ARG, path, 0,
                           "image size %dx%d is outside 1..%d on a side", width, height,
                           max_side);
    }
    if (stride < 4 * (size_t)width) {
        return sr__io_fail(err, SR_INVALID_ARG, path, 0,
                           "row stride %zu is less than 4 * width = %zu bytes", stride,
                           4 * (size_t)width);
    }
    if (!sr__rows_fit(rgba, (size_t)height, stride, 4 * (size_t)width)) {
        return sr__io_fail(err, SR_INVALID_ARG, path, 0,
                           "%d rows of stride %zu run past the end of memory", height, stride);
    }
    return SR_OK;
}

void *sr__io_alloc(const sr_allocator *a, size_t size)
{
    return a->alloc ? a->alloc(size, a->user) : malloc(size);
}

void sr__io_free(const sr_allocator *a, void *p)
{
    if (p) {
        if (a->alloc) {
            a->free(p, a->user);
        } else {
            free(p);
        }
    }
}

static int base64_value(unsigned char c)
{
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+' || c == '-') return 62;
    if (c == '/' || c == '_') return 63;
    return -1;
}

bool sr__base64_decode(const char *s, size_t n, uint8_t **out, size_t *size)
{
    while (n > 0 && (s[n - 1] == '=' || isspace((unsigned char)s[n - 1]))) {
        n--;
    }
    uint8_t *b = malloc(n / 4 * 3 + 3);
    if (!b) {
        return false;
    }
    size_t o = 0;
    uint32_t acc = 0;
    int bits = 0;
    for (size_t i = 0; i < n; i++) {
        if (isspace((unsigned char)s[i])) {
            continue;
        }
        int v = base64_value((unsigned char)s[i]);
        if (v < 0) {
            free(b);
            *out = NULL;
            return true;
        }
        acc = acc << 6 | (uint32_t)v;
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            b[o++] = (uint8_t)(acc >> bits);
        }
    }
    *out = b;
    *size = o;
    return true;
}

sr_result sr__check_load_pose(const sr_load_desc *desc, const char *name, sr_io_error *err)
{
    if (!desc) {
        return SR_OK;
    }
    if (desc->pose != SR_POSE_DEFAULT && desc->pose != SR_POSE_REST &&
        desc->pose != SR_POSE_ANIMATION) {
        return sr__io_fail(err, SR_INVALID_ARG, name, 0,
                           "sr_load_desc.pose %d is not an sr_load_pose", (int)desc->pose);
    }
    if (desc->pose == SR_POSE_ANIMATION && !isfinite(desc->animation_time)) {
        return sr__io_fail(err, SR_INVALID_ARG, name, 0,
                           "sr_load_desc.animation_time is not finite");
    }
    return SR_OK;
}
