/*
 * softrast_io.h - files in and out: model readers (OBJ, PLY, STL, and other
 * formats through Assimp when the build found it), PNG images (libpng) and
 * JPEG images (libjpeg-turbo, when the build found it).
 *
 * Errors: every function returns an sr_result and, on failure, fills an
 * sr_io_error with one line of the form "FILE:LINE: what is wrong" for text
 * files, "FILE: byte N: what is wrong" for binary ones, or "FILE: what is
 * wrong" when no position applies.  A FILE too long for the message is cut
 * from the left ("...tail/name.obj:4: ..."); the position and the reason are
 * always whole.  Nothing here prints or exits.
 */
#ifndef SOFTRAST_IO_H
#define SOFTRAST_IO_H

#include "softrast.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sr_io_error {
    char message[512];
} sr_io_error;

/* Documented limits, checked before anything is allocated from a count
 * read out of a file. */
#define SR_IO_MAX_FILE_BYTES    ((size_t)1 << 31)   /* 2 GiB */
#define SR_IO_MAX_VERTICES      ((size_t)1 << 28)
#define SR_IO_MAX_TRIANGLES     ((size_t)1 << 28)

typedef enum sr_model_format {
    SR_FORMAT_AUTO = 0,   /* from the file name's extension, then its content */
    SR_FORMAT_OBJ,
    SR_FORMAT_PLY,
    SR_FORMAT_STL,
    SR_FORMAT_ASSIMP,     /* anything else Assimp reads */
} sr_model_format;

typedef struct sr_load_desc {
    sr_model_format format;
    bool keep_file_normals_only; /* reserved; normals policy is the caller's */
} sr_load_desc;

/* Load a model file into *out (which is zeroed first).  Faces with more than
 * three vertices are triangulated.  Normals are those of the file, or NULL. */
SR_API sr_result sr_load_mesh(const char *path, const sr_load_desc *desc,
                              sr_mesh *out, sr_io_error *err);

/* The readers on a buffer already in memory (for tests and fuzzing).  `name`
 * is used in messages.  `data` need not be NUL-terminated. */
SR_API sr_result sr_parse_obj(const char *name, const char *data, size_t size,
                              sr_mesh *out, sr_io_error *err);
SR_API sr_result sr_parse_ply(const char *name, const uint8_t *data, size_t size,
                              sr_mesh *out, sr_io_error *err);
SR_API sr_result sr_parse_stl(const char *name, const uint8_t *data, size_t size,
                              sr_mesh *out, sr_io_error *err);

/* true when this build can read other formats through Assimp. */
SR_API bool sr_io_have_assimp(void);

/* PNG. */
typedef struct sr_png_write_desc {
    int compression_level;  /* zlib level; 0 -> SR_PNG_DEFAULT_LEVEL; -1 -> store */
    bool no_alpha;          /* write RGB, dropping alpha */
    sr_allocator allocator; /* zero: malloc/free.  Every block the write
                             * allocates - its own and zlib's - comes from here,
                             * on the calling thread (except realpath's when
                             * `path` is a symbolic link); NULL from alloc makes
                             * the call return SR_OUT_OF_MEMORY with nothing
                             * left behind */
    sr_context *context;    /* optional: compress on this context's threads
                             * (bands of rows at once); the file's bytes are the
                             * same with or without it.  The context must not be
                             * in use on another thread meanwhile */
} sr_png_write_desc;

#define SR_PNG_DEFAULT_LEVEL 1

/* Write RGBA8 pixels (stride in bytes) to `path` atomically: a temporary
 * file in the same directory, fsync'd, then renamed over the target, so a
 * failed write never leaves a partial file or clobbers an existing one.
 * Writes retry after EINTR (a signal handler without SA_RESTART) and carry
 * on after a short write; the first real error (ENOSPC, EFBIG, EIO) fails
 * the call with SR_IO_ERROR and removes the temporary file. */
SR_API sr_result sr_write_png(const char *path, int width, int height,
                              const uint8_t *rgba, size_t stride,
                              const sr_png_write_desc *desc, sr_io_error *err);

/* Read a PNG as RGBA8 (any bit depth, palette, gray and alpha expanded).
 * *pixels is malloc'd; free it with free(). */
SR_API sr_result sr_read_png(const char *path, int *width, int *height,
                             uint8_t **pixels, sr_io_error *err);

typedef struct sr_png_read_desc {
    sr_allocator allocator; /* zero: malloc/free.  libpng's and zlib's blocks, the
                             * row table and the pixels come from here (release
                             * *pixels with allocator.free); only stdio's FILE does
                             * not.  NULL from alloc: SR_OUT_OF_MEMORY, nothing kept */
} sr_png_read_desc;

/* sr_read_png with options (desc may be NULL: exactly sr_read_png). */
SR_API sr_result sr_read_png_desc(const char *path, const sr_png_read_desc *desc, int *width,
                                  int *height, uint8_t **pixels, sr_io_error *err);
/* sr_read_png on a file already in memory; `name` is used in messages. */
SR_API sr_result sr_decode_png(const char *name, const uint8_t *data, size_t size,
                               int *width, int *height, uint8_t **pixels, sr_io_error *err);

/* JPEG: baseline or progressive, gray, YCbCr/RGB or CMYK (Adobe's inverted
 * inks too), any chroma subsampling, read as RGBA8 with alpha 255; at
 * most 16384 pixels a side, like PNG, and SR_TOO_LARGE for a progressive
 * image whose decoding would take more than 512 MiB.  Data libjpeg would only patch
 * over with a warning (a truncated file's missing rows come out gray) is
 * an error with libjpeg's words: nothing partial is returned.  *pixels is
 * malloc'd; free it with free().  A build without libjpeg returns
 * SR_UNSUPPORTED (sr_io_have_jpeg says which). */
SR_API sr_result sr_read_jpeg(const char *path, int *width, int *height,
                              uint8_t **pixels, sr_io_error *err);
/* The same on a file already in memory; `name` is used in messages. */
SR_API sr_result sr_decode_jpeg(const char *name, const uint8_t *data, size_t size,
                                int *width, int *height, uint8_t **pixels, sr_io_error *err);
SR_API bool sr_io_have_jpeg(void);

/* Write RGBA8 pixels (stride in bytes) as a baseline JPEG with 4:2:0
 * chroma, alpha dropped, atomically as sr_write_png does (a failed write
 * leaves nothing and replaces nothing).  At most 65500 pixels a side. */
typedef struct sr_jpeg_write_desc {
    int quality;            /* 1..100; 0 -> SR_JPEG_DEFAULT_QUALITY */
} sr_jpeg_write_desc;

#define SR_JPEG_DEFAULT_QUALITY 90

SR_API sr_result sr_write_jpeg(const char *path, int width, int height,
                               const uint8_t *rgba, size_t stride,
                               const sr_jpeg_write_desc *desc, sr_io_error *err);

/* A PNG or a JPEG, told apart by the file's first bytes (not its name),
 * read as RGBA8 by sr_read_png or sr_read_jpeg. */
SR_API sr_result sr_read_image(const char *path, int *width, int *height,
                               uint8_t **pixels, sr_io_error *err);
/* The same on bytes in memory (sr_mesh.texture_data, say). */
SR_API sr_result sr_decode_image(const char *name, const uint8_t *data, size_t size,
                                 int *width, int *height, uint8_t **pixels, sr_io_error *err);

#ifdef __cplusplus
}
#endif
#endif /* SOFTRAST_IO_H */
