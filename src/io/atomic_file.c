/* atomic_file.c - output files that appear whole or not at all (io stage,
 * the end of the pipeline): the image is written to a temporary file in
 * the target's directory, fsync'd, then renamed over the target, so a
 * failed write never leaves a partial file or clobbers an existing one.
 * Shared by the PNG and JPEG writers, and public as sr_write_file for
 * files encoded elsewhere (the CLI's animated WebPs). */
/* realpath() is XSI, not in the build's plain _POSIX_C_SOURCE. */
#define _XOPEN_SOURCE 700

#include "io/io_util.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* All n bytes or false with errno set: retries after EINTR, continues
 * after a short write (a full disk or RLIMIT_FSIZE takes part of a write
 * first, then fails the next one with the reason). */
bool sr__write_all(int fd, const uint8_t *p, size_t n)
{
    while (n > 0) {
        ssize_t w = write(fd, p, n);
        if (w < 0) {
            if (errno == EINTR) {
                continue;
            }
            return false;
        }
        if (w == 0) {
            errno = EIO; /* no progress and no reason: do not spin */
            return false;
        }
        p += w;
        n -= (size_t)w;
    }
    return true;
}

bool sr__write_fd(void *user, const void *data, size_t size)
{
    return sr__write_all(*(const int *)user, data, size);
}

/* The permission bits a plain fopen would give a new file: 0666 less the
 * umask.  mkstemp creates 0600, which would leave rendered images unreadable
 * to anyone else.  umask() can only be read by setting it, which races with
 * other threads creating files, so read it from /proc where there is one. */
static mode_t new_file_mode(void)
{
    /* open/read rather than fopen: no hidden allocation outside the
     * caller's allocator. */
    mode_t mask = 022;
    int fd = open("/proc/self/status", O_RDONLY);
    if (fd >= 0) {
        char buf[4096];
        size_t n = 0;
        ssize_t got;
        while (n < sizeof buf - 1 &&
               ((got = read(fd, buf + n, sizeof buf - 1 - n)) > 0 || (got < 0 && errno == EINTR))) {
            n += got > 0 ? (size_t)got : 0;
        }
        close(fd);
        buf[n] = 0;
        const char *line = strstr(buf, "\nUmask:");
        unsigned int m;
        if (line && sscanf(line + 1, "Umask: %o", &m) == 1) {
            mask = (mode_t)(m & 0777);
        }
    }
    return 0666 & ~mask;
}

/* After the rename, make the new directory entry itself durable.  Best
 * effort: the image is already complete and in place. */
static void sync_directory(const char *file_path)
{
    const char *slash = strrchr(file_path, '/');
    char dir[4096];
    if (!slash) {
        snprintf(dir, sizeof dir, ".");
    } else if (slash == file_path) {
        snprintf(dir, sizeof dir, "/");
    } else if ((size_t)(slash - file_path) < sizeof dir) {
        memcpy(dir, file_path, (size_t)(slash - file_path));
        dir[slash - file_path] = 0;
    } else {
        return;
    }
    int fd = open(dir, O_RDONLY);
    if (fd >= 0) {
        (void)fsync(fd);
        close(fd);
    }
}

static void atomic_release(sr_atomic_file *f)
{
    sr__io_free(&f->a, f->tmp);
    free(f->resolved);
    f->tmp = NULL;
    f->resolved = NULL;
    f->fd = -1;
}

sr_result sr__atomic_create(sr_atomic_file *f, const char *path, sr_allocator a,
                            sr_io_error *err)
{
    *f = (sr_atomic_file){ .path = path, .target = path, .fd = -1, .a = a };
    if (!path || !path[0]) {
        return sr__io_fail(err, SR_INVALID_ARG, "<null>", 0, "no file name given");
    }
    /* The file the image will replace.  A symbolic link is followed, so the
     * file it names is replaced rather than the link itself. */
    bool exists = false;
    struct stat st;
    if (lstat(path, &st) == 0) {
        if (S_ISLNK(st.st_mode)) {
            f->resolved = realpath(path, NULL);
            if (!f->resolved || stat(f->resolved, &st) != 0) {
                int e = errno;
                atomic_release(f);
                return sr__io_fail(err, SR_IO_ERROR, path, 0,
                                   "symbolic link to a file that cannot be reached: %s",
                                   strerror(e));
            }
            f->target = f->resolved;
        }
        if (S_ISDIR(st.st_mode)) {
            atomic_release(f);
            return sr__io_fail(err, SR_IO_ERROR, path, 0,
                               "is a directory; give a file name for the image");
        }
        if (!S_ISREG(st.st_mode)) {
            atomic_release(f);
            return sr__io_fail(err, SR_IO_ERROR, path, 0,
                               "is not a regular file; refusing to replace it");
        }
        exists = true;
    } else if (errno != ENOENT) {
        return sr__io_fail(err, SR_IO_ERROR, path, 0, "cannot examine: %s", strerror(errno));
    }

    /* "<dir>/.<base>.XXXXXX": the same directory, hence the same file
     * system, which is what makes the final rename atomic.  The leading dot
     * keeps a half-written file out of plain directory listings. */
    const char *target = f->target;
    const char *slash = strrchr(target, '/');
    size_t dir_len = slash ? (size_t)(slash - target) + 1 : 0;
    const char *base = target + dir_len;
    if (!base[0]) {
        atomic_release(f);
        return sr__io_fail(err, SR_INVALID_ARG, path, 0,
                           "names a directory (ends in '/'); give a file name for the image");
    }
    size_t tmp_size = strlen(target) + sizeof "/..XXXXXX";
    f->tmp = sr__io_alloc(&f->a, tmp_size);
    if (!f->tmp) {
        atomic_release(f);
        return sr__io_fail(err, SR_OUT_OF_MEMORY, path, 0, "out of memory");
    }
    snprintf(f->tmp, tmp_size, "%.*s.%s.XXXXXX", (int)dir_len, target, base);
    f->fd = mkstemp(f->tmp);
    if (f->fd < 0) {
        int e = errno;
        sr_result r = sr__io_fail(err, SR_IO_ERROR, path, 0, "cannot create a file in '%.*s': %s",
                                  dir_len > 1 ? (int)dir_len - 1 : (int)dir_len,
                                  dir_len ? target : ".", strerror(e));
        atomic_release(f);
        return r;
    }
    /* A replaced file keeps its permissions.  Failing to set them (some
     * file systems have none) is no reason to lose the image. */
    (void)fchmod(f->fd, exists ? (st.st_mode & 07777) : new_file_mode());
    return SR_OK;
}

void sr__atomic_discard(sr_atomic_file *f)
{
    if (f->fd >= 0) {
        close(f->fd);
        unlink(f->tmp);
    }
    atomic_release(f);
}

sr_result sr__atomic_commit(sr_atomic_file *f, sr_io_error *err)
{
    const char *path = f->path;
    sr_result result = SR_OK;
    /* The data must be on disk before the rename publishes it, or a crash
     * could leave a complete-looking name over an empty file. */
    if (fsync(f->fd) != 0) {
        result = sr__io_fail(err, SR_IO_ERROR, path, 0, "write failed: %s", strerror(errno));
        sr__atomic_discard(f);
        return result;
    }
    /* close() is not retried after EINTR: on Linux the descriptor is
     * released whatever it returns, and the data is already fsync'd. */
    int fd = f->fd;
    f->fd = -1;
    if (close(fd) != 0 && errno != EINTR) {
        result = sr__io_fail(err, SR_IO_ERROR, path, 0, "write failed on close: %s",
                             strerror(errno));
        unlink(f->tmp);
        atomic_release(f);
        return result;
    }
    if (rename(f->tmp, f->target) != 0) {
        result = sr__io_fail(err, SR_IO_ERROR, path, 0,
                             "cannot move the finished image into place: %s", strerror(errno));
        unlink(f->tmp);
        atomic_release(f);
        return result;
    }
    sync_directory(f->target);
    atomic_release(f);
    return SR_OK;
}

sr_result sr_write_file(const char *path, const void *data, size_t size, sr_io_error *err)
{
    if (err) {
        err->message[0] = '\0';
    }
    if (!data && size > 0) {
        return sr__io_fail(err, SR_INVALID_ARG, path ? path : "<null>", 0,
                           "sr_write_file: data is NULL for %zu bytes", size);
    }
    sr_atomic_file f;
    sr_result r = sr__atomic_create(&f, path, (sr_allocator){ 0 }, err);
    if (r != SR_OK) {
        return r;
    }
    if (!sr__write_all(f.fd, data, size)) {
        r = sr__io_fail(err, SR_IO_ERROR, path, 0, "write failed: %s", strerror(errno));
        sr__atomic_discard(&f);
        return r;
    }
    return sr__atomic_commit(&f, err);
}
