/* buffer.c - vertex buffers: an application's arrays copied into memory
 * the context allocates (vertex stage input).  The copy is the point: the
 * default allocator maps blocks of 4 MiB and more as 2 MiB pages
 * (alloc.c), and a draw that streams through a large array from 4 KiB
 * pages waits on a page-table walk every 4 KiB - a million triangles'
 * 96 MB of positions and colors cost the front end 15 ms a frame on one
 * thread, and three times that just after another renderer had run. */
#include "context.h"

#include <stdint.h>
#include <string.h>

struct sr_buffer {
    void *data;
    size_t size;
};

sr_result sr_make_buffer(sr_context *ctx, const void *data, size_t bytes, sr_buffer **out)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_make_buffer: ctx is NULL");
    }
    if (!out) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_make_buffer: out is NULL");
    }
    *out = NULL;
    if (bytes == 0) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_make_buffer: bytes is 0");
    }
    if (bytes > SR_BUFFER_MAX) {
        return sr__fail(ctx, SR_TOO_LARGE, "sr_make_buffer: bytes %zu exceeds the limit %zu",
                        bytes, SR_BUFFER_MAX);
    }
    sr_buffer *b = sr__calloc(ctx, 1, sizeof *b);
    void *block = b ? sr__alloc(ctx, bytes) : NULL;
    if (!block) {
        sr__free(ctx, b);
        return sr__fail(ctx, SR_OUT_OF_MEMORY, "sr_make_buffer: out of memory for %zu bytes",
                        bytes);
    }
    if (data) {
        memcpy(block, data, bytes);
    } else {
        memset(block, 0, bytes);
    }
    b->data = block;
    b->size = bytes;
    *out = b;
    sr__ok(ctx);
    return SR_OK;
}

sr_result sr_buffer_update(sr_context *ctx, sr_buffer *buf, size_t offset, const void *data,
                           size_t bytes)
{
    if (!ctx) {
        return sr__fail(NULL, SR_INVALID_ARG, "sr_buffer_update: ctx is NULL");
    }
    if (!buf || (!data && bytes > 0)) {
        return sr__fail(ctx, SR_INVALID_ARG, "sr_buffer_update: %s is NULL", buf ? "data" : "buf");
    }
    if (offset > buf->size || bytes > buf->size - offset) {
        return sr__fail(ctx, SR_INVALID_ARG,
                        "sr_buffer_update: bytes %zu at offset %zu run past the buffer's %zu",
                        bytes, offset, buf->size);
    }
    /* data may lie in the buffer itself (moving a range within it). */
    if (bytes > 0) {
        memmove((uint8_t *)buf->data + offset, data, bytes);
    }
    sr__ok(ctx);
    return SR_OK;
}

void sr_destroy_buffer(sr_context *ctx, sr_buffer *buf)
{
    if (!ctx || !buf) {
        return;
    }
    sr__free(ctx, buf->data);
    sr__free(ctx, buf);
}

void *sr_buffer_data(sr_buffer *buf)
{
    return buf ? buf->data : NULL;
}

size_t sr_buffer_size(const sr_buffer *buf)
{
    return buf ? buf->size : 0;
}
