/* gltf_meshopt.c - EXT_meshopt_compression for the glTF reader (io stage):
 * a bufferView whose bytes are stored compressed in another buffer is
 * decoded once with meshoptimizer into memory the document owns, and the
 * accessors read it like any other bufferView.  Without meshoptimizer the
 * view reads its uncompressed fallback, or says that it has none.
 * Called by gltf.c's sr__gltf_buffer_view; one document, one thread. */
#include "io/gltf.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

#ifdef SR_HAVE_MESHOPT
#include <meshoptimizer.h>
#endif

#define EXT_NAME "EXT_meshopt_compression"

/* The bytes decoded for one bufferView, kept until the document is done. */
struct gltf_decoded_view {
    uint8_t *data;     /* NULL: not decoded yet */
    size_t size;
};

bool sr__gltf_have_meshopt(void)
{
#ifdef SR_HAVE_MESHOPT
    return true;
#else
    return false;
#endif
}

bool sr__gltf_is_fallback_buffer(const json_t *buffer)
{
    return json_is_true(json_object_get(sr__gltf_extension(buffer, EXT_NAME), "fallback"));
}

void sr__gltf_meshopt_free(gltf_doc *d)
{
    for (size_t i = 0; d->decoded && i < d->decoded_count; i++) {
        free(d->decoded[i].data);
    }
    free(d->decoded);
    d->decoded = NULL;
    d->decoded_count = 0;
}

#ifdef SR_HAVE_MESHOPT

typedef enum meshopt_mode { MODE_ATTRIBUTES, MODE_TRIANGLES, MODE_INDICES } meshopt_mode;
typedef enum meshopt_filter { FILTER_NONE, FILTER_OCTAHEDRAL, FILTER_QUATERNION,
                              FILTER_EXPONENTIAL } meshopt_filter;

/* The string member key of ext as one of names (its index in *out); an
 * absent optional member leaves *out as it is. */
static sr_result enum_member(gltf_doc *d, const json_t *ext, const char *eptr, const char *key,
                             const char *const *names, int n, bool required, int *out)
{
    json_t *v = json_object_get(ext, key);
    if (!v) {
        return required ? sr__gltf_fail(d, SR_BAD_FORMAT, "%s/%s: missing", eptr, key) : SR_OK;
    }
    for (int i = 0; json_is_string(v) && i < n; i++) {
        if (strcmp(json_string_value(v), names[i]) == 0) {
            *out = i;
            return SR_OK;
        }
    }
    return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/%s: not one of %s, %s, %s%s%s", eptr, key,
                         names[0], names[1], names[2], n > 3 ? ", " : "", n > 3 ? names[3] : "");
}

/* The extension's layout checked against the specification's rules and
 * against the parent view (`length` bytes, `parent_stride` or 0). */
static sr_result check_layout(gltf_doc *d, const char *eptr, int mode, int filter, size_t stride,
                              size_t count, size_t length, size_t parent_stride)
{
    size_t decoded;
    if (!sr__mul_ok(stride, count, &decoded) || decoded != length) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/count: %zu elements of %zu bytes, but the bufferView's "
                             "byteLength is %zu",
                             eptr, count, stride, length);
    }
    if (parent_stride != 0 && parent_stride != stride) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/byteStride: %zu, but the bufferView's byteStride is %zu", eptr,
                             stride, parent_stride);
    }
    if (mode == MODE_ATTRIBUTES && stride % 4 != 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/byteStride: %zu, but ATTRIBUTES needs a multiple of 4", eptr,
                             stride);
    }
    if (mode != MODE_ATTRIBUTES) {
        if (stride != 2 && stride != 4) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/byteStride: %zu, but %s needs 2 or 4",
                                 eptr, stride, mode == MODE_TRIANGLES ? "TRIANGLES" : "INDICES");
        }
        if (filter != FILTER_NONE) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/filter: only ATTRIBUTES take a filter",
                                 eptr);
        }
    }
    if (mode == MODE_TRIANGLES && count % 3 != 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/count: %zu, but TRIANGLES needs a multiple of 3", eptr, count);
    }
    if ((filter == FILTER_OCTAHEDRAL && stride != 4 && stride != 8) ||
        (filter == FILTER_QUATERNION && stride != 8) ||
        (filter == FILTER_EXPONENTIAL && stride % 4 != 0)) {
        static const char *const need[] = { "", "4 or 8", "8", "a multiple of 4" };
        static const char *const names[] = { "", "OCTAHEDRAL", "QUATERNION", "EXPONENTIAL" };
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/filter: %s needs a byteStride of %s, not %zu",
                             eptr, names[filter], need[filter], stride);
    }
    return SR_OK;
}

static bool host_is_little_endian(void)
{
    const uint16_t one = 1;
    uint8_t first;
    memcpy(&first, &one, 1);
    return first == 1;
}

/* Reverses the bytes of each `unit`-byte value of p[0..n). */
static void swap_units(uint8_t *p, size_t n, size_t unit)
{
    for (size_t i = 0; unit > 1 && i + unit <= n; i += unit) {
        for (size_t a = i, b = i + unit - 1; a < b; a++, b--) {
            uint8_t t = p[a];
            p[a] = p[b];
            p[b] = t;
        }
    }
}

/* The compressed stream decoded into out (count * stride bytes, glTF's
 * little-endian order) and its filter applied; the decoder's result, 0 on
 * success.  The index decoders write, and the filters read and write,
 * values in the host's order: a big-endian host swaps around them. */
static int decode(int mode, int filter, uint8_t *out, size_t count, size_t stride,
                  const uint8_t *src, size_t n)
{
    int rc;
    switch (mode) {
    case MODE_ATTRIBUTES: rc = meshopt_decodeVertexBuffer(out, count, stride, src, n); break;
    case MODE_TRIANGLES:  rc = meshopt_decodeIndexBuffer(out, count, stride, src, n); break;
    default:              rc = meshopt_decodeIndexSequence(out, count, stride, src, n); break;
    }
    if (rc != 0) {
        return rc;
    }
    bool swap = !host_is_little_endian();
    if (mode != MODE_ATTRIBUTES) {
        if (swap) {
            swap_units(out, count * stride, stride);
        }
        return 0;
    }
    /* OCTAHEDRAL of 4 bytes holds bytes, of 8 and QUATERNION shorts,
     * EXPONENTIAL 32-bit words, before and after. */
    size_t unit = filter == FILTER_EXPONENTIAL ? 4 : filter == FILTER_NONE || stride == 4 ? 1 : 2;
    if (swap) {
        swap_units(out, count * stride, unit);
    }
    switch (filter) {
    case FILTER_OCTAHEDRAL:  meshopt_decodeFilterOct(out, count, stride); break;
    case FILTER_QUATERNION:  meshopt_decodeFilterQuat(out, count, stride); break;
    case FILTER_EXPONENTIAL: meshopt_decodeFilterExp(out, count, stride); break;
    default: break;
    }
    if (swap) {
        swap_units(out, count * stride, unit);
    }
    return 0;
}

sr_result sr__gltf_meshopt_view(gltf_doc *d, long view, const json_t *ext, const char *ptr,
                                size_t length, size_t parent_stride, const uint8_t **data)
{
    *data = NULL;
    if (!d->decoded) {
        size_t n = json_array_size(json_object_get(d->root, "bufferViews"));
        d->decoded = calloc(n ? n : 1, sizeof *d->decoded);
        if (!d->decoded) {
            return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
        }
        d->decoded_count = n;
    }
    assert((size_t)view < d->decoded_count);   /* the caller found the view */
    struct gltf_decoded_view *slot = &d->decoded[view];
    if (slot->data) {
        *data = slot->data;
        return SR_OK;
    }
    char eptr[GLTF_PTR];
    snprintf(eptr, sizeof eptr, "%s/extensions/" EXT_NAME, ptr);
    static const char *const modes[] = { "ATTRIBUTES", "TRIANGLES", "INDICES" };
    static const char *const filters[] = { "NONE", "OCTAHEDRAL", "QUATERNION", "EXPONENTIAL" };
    long buffer = -1;
    size_t offset = 0, n = 0, stride = 0, count = 0;
    int mode = 0, filter = FILTER_NONE;
    sr_result r;
    if ((r = sr__gltf_index(d, ext, eptr, "buffer", d->buffer_count ? d->buffer_count : 1,
                            true, &buffer)) != SR_OK ||
        (r = sr__gltf_size(d, ext, eptr, "byteOffset", 0, SR_IO_MAX_FILE_BYTES, false,
                           &offset)) != SR_OK ||
        (r = sr__gltf_size(d, ext, eptr, "byteLength", 1, SR_IO_MAX_FILE_BYTES, true, &n)) !=
            SR_OK ||
        (r = sr__gltf_size(d, ext, eptr, "byteStride", 1, 256, true, &stride)) != SR_OK ||
        (r = sr__gltf_size(d, ext, eptr, "count", 1, SR_IO_MAX_FILE_BYTES, true, &count)) !=
            SR_OK ||
        (r = enum_member(d, ext, eptr, "mode", modes, 3, true, &mode)) != SR_OK ||
        (r = enum_member(d, ext, eptr, "filter", filters, 4, false, &filter)) != SR_OK ||
        (r = check_layout(d, eptr, mode, filter, stride, count, length, parent_stride)) !=
            SR_OK) {
        return r;
    }
    /* A stream decodes to at most some 64 times its size (two header
     * bits per 16 bytes); the budget that bounds accessors bounds this
     * too, so a small file cannot ask for gigabytes. */
    if (length / 4 > d->elements_left) {
        return sr__gltf_fail(d, SR_TOO_LARGE,
                             "%s/count: %zu bytes to decode are more than a file of this size "
                             "may decode",
                             eptr, length);
    }
    /* The parent view lies in its (fallback) buffer, as any view must,
     * though that buffer's bytes are never read here. */
    json_t *parent = json_array_get(json_object_get(d->root, "bufferViews"), (size_t)view);
    long fallback = -1;
    size_t parent_offset = 0, fallback_length = 0;
    char fptr[GLTF_PTR];
    if ((r = sr__gltf_index(d, parent, ptr, "buffer", d->buffer_count ? d->buffer_count : 1,
                            true, &fallback)) != SR_OK ||
        (r = sr__gltf_size(d, parent, ptr, "byteOffset", 0, SR_IO_MAX_FILE_BYTES, false,
                           &parent_offset)) != SR_OK) {
        return r;
    }
    snprintf(fptr, sizeof fptr, "/buffers/%ld", fallback);
    json_t *fb = json_array_get(json_object_get(d->root, "buffers"), (size_t)fallback);
    if (!json_is_object(fb)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: not an object", fptr);
    }
    if ((r = sr__gltf_size(d, fb, fptr, "byteLength", 1, SR_IO_MAX_FILE_BYTES, true,
                           &fallback_length)) != SR_OK) {
        return r;
    }
    if (parent_offset > fallback_length || length > fallback_length - parent_offset) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/byteLength: bytes %zu..%zu run past the %zu bytes of buffer %ld",
                             ptr, parent_offset, parent_offset + length, fallback_length,
                             fallback);
    }
    char bptr[GLTF_PTR];
    snprintf(bptr, sizeof bptr, "%s/buffer", eptr);
    json_t *b = json_array_get(json_object_get(d->root, "buffers"), (size_t)buffer);
    if (sr__gltf_is_fallback_buffer(b)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s: buffer %ld is a fallback buffer, not compressed data", bptr,
                             buffer);
    }
    const uint8_t *bytes;
    size_t size;
    if ((r = sr__gltf_buffer_bytes(d, buffer, bptr, &bytes, &size)) != SR_OK) {
        return r;
    }
    if (offset > size || n > size - offset) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/byteLength: bytes %zu..%zu run past the %zu bytes of buffer %ld",
                             eptr, offset, offset + n, size, buffer);
    }
    uint8_t *out = malloc(length);
    if (!out) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory for %zu bytes", eptr,
                             length);
    }
    d->elements_left -= length / 4;
    int rc = decode(mode, filter, out, count, stride, bytes + offset, n);
    if (rc != 0) {
        free(out);
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s: the %s stream does not decode (corrupt or truncated; "
                             "meshoptimizer error %d)",
                             eptr, modes[mode], rc);
    }
    slot->data = out;
    slot->size = length;
    *data = out;
    return SR_OK;
}

#else /* !SR_HAVE_MESHOPT */

/* Whether buffer i holds bytes a plain bufferView can read: a URI, or the
 * GLB's BIN chunk for buffer 0. */
static bool buffer_has_data(const gltf_doc *d, long i)
{
    json_t *b = json_array_get(json_object_get(d->root, "buffers"), (size_t)i);
    return json_object_get(b, "uri") || (i == 0 && d->bin);
}

sr_result sr__gltf_meshopt_view(gltf_doc *d, long view, const json_t *ext, const char *ptr,
                                size_t length, size_t parent_stride, const uint8_t **data)
{
    (void)view;
    (void)ext;
    (void)length;
    (void)parent_stride;
    *data = NULL;
    long buffer = -1;
    json_t *v = json_array_get(json_object_get(d->root, "bufferViews"), (size_t)view);
    sr_result r = sr__gltf_index(d, v, ptr, "buffer", d->buffer_count ? d->buffer_count : 1,
                                 true, &buffer);
    if (r != SR_OK) {
        return r;
    }
    if (!buffer_has_data(d, buffer)) {
        return sr__gltf_fail(d, SR_UNSUPPORTED,
                             "%s/extensions/" EXT_NAME ": softrast was built without "
                             "meshoptimizer, and buffer %ld holds no uncompressed fallback",
                             ptr, buffer);
    }
    return SR_OK;   /* the fallback's bytes, read by the caller */
}

#endif
