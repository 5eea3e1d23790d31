/*
 * gltf_accessor.c - io stage: glTF accessors decoded to plain arrays.
 * Consumes an accessor of the document (its bufferView, byteStride,
 * component type, normalization, sparse substitution); produces floats for
 * vertex attributes or uint32 for indices.  Every offset is checked
 * against the view and the buffer before a byte is read.  Called by the
 * thread reading the document.
 */
#include "io/byteorder.h"
#include "io/gltf.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Bytes of one component, or 0 for an unknown componentType. */
static size_t component_size(long type)
{
    switch (type) {
    case 5120: case 5121: return 1;   /* BYTE, UNSIGNED_BYTE */
    case 5122: case 5123: return 2;   /* SHORT, UNSIGNED_SHORT */
    case 5125: case 5126: return 4;   /* UNSIGNED_INT, FLOAT */
    default:              return 0;
    }
}

/* Components of an accessor type, and its matrix rows (0 for vectors). */
static int type_components(const char *type, int *rows)
{
    static const struct { const char *name; int n, rows; } types[] = {
        { "SCALAR", 1, 0 }, { "VEC2", 2, 0 }, { "VEC3", 3, 0 }, { "VEC4", 4, 0 },
        { "MAT2", 4, 2 },   { "MAT3", 9, 3 }, { "MAT4", 16, 4 },
    };
    for (size_t i = 0; i < sizeof types / sizeof types[0]; i++) {
        if (strcmp(type, types[i].name) == 0) {
            *rows = types[i].rows;
            return types[i].n;
        }
    }
    return 0;
}

/* One component as a double: normalized integers mapped as the glTF
 * specification's table does (signed ones clamped at -1). */
static double read_component(const uint8_t *p, long type, bool normalized)
{
    switch (type) {
    case 5120: {
        int8_t v = (int8_t)p[0];
        return normalized ? fmax(v / 127.0, -1.0) : v;
    }
    case 5121:
        return normalized ? p[0] / 255.0 : p[0];
    case 5122: {
        int16_t v = (int16_t)sr__le16(p);
        return normalized ? fmax(v / 32767.0, -1.0) : v;
    }
    case 5123: {
        uint16_t v = sr__le16(p);
        return normalized ? v / 65535.0 : v;
    }
    case 5125:
        return sr__le32(p);
    default:
        return sr__le_float(p);
    }
}

/* Where an accessor's elements are: a validated layout. */
typedef struct layout {
    const uint8_t *base;   /* element 0, or NULL: all zeros */
    size_t stride;         /* bytes from one element to the next */
    size_t column_stride;  /* bytes from one matrix column to the next */
    int rows;              /* matrix rows, 0 for vectors */
} layout;

/* The byte of component c of an element (matrix columns are padded to 4
 * bytes, as the specification lays out MAT2/MAT3 of bytes and shorts). */
static size_t component_offset(const layout *l, size_t csize, int c)
{
    if (l->rows == 0) {
        return (size_t)c * csize;
    }
    return (size_t)(c / l->rows) * l->column_stride + (size_t)(c % l->rows) * csize;
}

/* Element size and column stride of `n` components of `csize` bytes. */
static size_t element_size(int n, int rows, size_t csize, size_t *column_stride)
{
    if (rows == 0) {
        *column_stride = 0;
        return (size_t)n * csize;
    }
    *column_stride = ((size_t)rows * csize + 3) & ~(size_t)3;
    return *column_stride * (size_t)(n / rows);
}

/* Check that `count` elements of `esize` bytes at `offset`, `stride` apart,
 * fit in a view of `size` bytes. */
static bool fits(size_t offset, size_t stride, size_t count, size_t esize, size_t size)
{
    if (offset > size || count == 0) {
        return count == 0 && offset <= size;
    }
    size_t span;
    if (!sr__mul_ok(stride, count - 1, &span) || __builtin_add_overflow(span, esize, &span) ||
        __builtin_add_overflow(span, offset, &span)) {
        return false;
    }
    return span <= size;
}

/* The accessor's description (its JSON `a`, pointer aptr) with its
 * bufferView, byteOffset and matrix rows, nothing read. */
static sr_result describe(gltf_doc *d, long index, const char *use, gltf_accessor_info *info,
                          json_t **a_out, long *view, size_t *offset, int *rows, char *aptr,
                          size_t aptr_cap)
{
    json_t *accessors;
    size_t n;
    sr_result r = sr__gltf_array(d, d->root, "", "accessors", &accessors, &n);
    if (r != SR_OK) {
        return r;
    }
    if (index < 0 || (size_t)index >= n) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: accessor %ld does not exist (%zu accessors)",
                             use, index, n);
    }
    sr__json_pointer(aptr, aptr_cap, "/accessors/%ld", index);
    json_t *a = json_array_get(accessors, (size_t)index);
    if (!json_is_object(a)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: not an object", aptr);
    }
    long ctype = 0;
    *view = -1;
    *offset = 0;
    *a_out = a;
    memset(info, 0, sizeof *info);
    if ((r = sr__gltf_index(d, a, aptr, "componentType", 5127, true, &ctype)) != SR_OK ||
        (r = sr__gltf_size(d, a, aptr, "count", 1, SR_IO_MAX_VERTICES * 3, true, &info->count)) !=
            SR_OK ||
        (r = sr__gltf_index(d, a, aptr, "bufferView", (size_t)-1 / 2, false, view)) != SR_OK ||
        (r = sr__gltf_size(d, a, aptr, "byteOffset", 0, SR_IO_MAX_FILE_BYTES, false, offset)) !=
            SR_OK) {
        return r;
    }
    size_t csize = component_size(ctype);
    if (csize == 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/componentType: %ld is not a component type",
                             aptr, ctype);
    }
    json_t *type = json_object_get(a, "type");
    *rows = 0;
    info->components = json_is_string(type) ? type_components(json_string_value(type), rows) : 0;
    if (info->components == 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/type: expected SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3 or MAT4",
                             aptr);
    }
    info->component_type = (int)ctype;
    info->matrix = *rows != 0;
    json_t *norm = json_object_get(a, "normalized");
    if (norm && !json_is_boolean(norm)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/normalized: not true or false", aptr);
    }
    info->normalized = json_is_true(norm);
    if (info->normalized && csize == 4) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/normalized: only byte and short components are normalized",
                             aptr);
    }
    if (*offset % csize != 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/byteOffset: %zu is not a multiple of the component size %zu",
                             aptr, *offset, csize);
    }
    return SR_OK;
}

sr_result sr__gltf_accessor_info(gltf_doc *d, long index, const char *use,
                                 gltf_accessor_info *info)
{
    char aptr[GLTF_PTR];
    json_t *a;
    long view;
    size_t offset;
    int rows;
    return describe(d, index, use, info, &a, &view, &offset, &rows, aptr, sizeof aptr);
}

/* The accessor's dense part, and its description; sparse left to the
 * caller (*sparse, or NULL).  An accessor of the Draco primitive being
 * read takes the decoded bytes, without its bufferView or sparse part, as
 * the extension asks. */
static sr_result open_accessor(gltf_doc *d, long index, const char *use, gltf_accessor_info *info,
                               layout *l, json_t **sparse, char *aptr, size_t aptr_cap)
{
    json_t *a;
    long view;
    size_t offset;
    int rows;
    *sparse = NULL;
    sr_result r = describe(d, index, use, info, &a, &view, &offset, &rows, aptr, aptr_cap);
    if (r != SR_OK) {
        return r;
    }
    size_t csize = component_size(info->component_type);
    /* Every element decoded counts against the budget, data or not. */
    size_t elements;
    if (!sr__mul_ok(info->count, (size_t)info->components, &elements) ||
        elements > d->elements_left) {
        return sr__gltf_fail(d, SR_TOO_LARGE,
                             "%s/count: %zu elements of %d components are more than a file "
                             "of this size may decode",
                             aptr, info->count, info->components);
    }
    d->elements_left -= elements;

    size_t esize = element_size(info->components, rows, csize, &l->column_stride);
    l->rows = rows;
    l->base = NULL;
    l->stride = esize;
    size_t decoded_size;
    const uint8_t *decoded = sr__gltf_draco_accessor(d, index, &decoded_size);
    if (decoded) {
        /* gltf_draco.c wrote count elements of esize bytes. */
        if (!fits(0, esize, info->count, esize, decoded_size)) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/count: %zu elements, but the Draco "
                                 "stream decodes %zu bytes", aptr, info->count, decoded_size);
        }
        l->base = decoded;
        return SR_OK;
    }
    if (view >= 0) {
        char vptr[GLTF_PTR];
        sr__json_pointer(vptr, sizeof vptr, "%s/bufferView", aptr);
        const uint8_t *data;
        size_t size, stride;
        if ((r = sr__gltf_buffer_view(d, view, vptr, &data, &size, &stride)) != SR_OK) {
            return r;
        }
        if (stride != 0) {
            if (stride < esize) {
                return sr__gltf_fail(d, SR_BAD_FORMAT,
                                     "/bufferViews/%ld/byteStride: %zu is less than the %zu "
                                     "bytes of an element of accessor %ld",
                                     view, stride, esize, index);
            }
            l->stride = stride;
        }
        if (!fits(offset, l->stride, info->count, esize, size)) {
            return sr__gltf_fail(d, SR_BAD_FORMAT,
                                 "%s/count: %zu elements of %zu bytes, %zu apart, from byte %zu "
                                 "run past the %zu bytes of bufferView %ld",
                                 aptr, info->count, esize, l->stride, offset, size, view);
        }
        l->base = data + offset;
    } else if (offset != 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/byteOffset: given without a bufferView",
                             aptr);
    }
    *sparse = json_object_get(a, "sparse");
    if (*sparse && !json_is_object(*sparse)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/sparse: not an object", aptr);
    }
    return SR_OK;
}

/* Element i's components into out[0..n), as doubles. */
static void read_element(const layout *l, const gltf_accessor_info *info, size_t i, double *out)
{
    size_t csize = component_size(info->component_type);
    if (!l->base) {
        for (int c = 0; c < info->components; c++) {
            out[c] = 0;
        }
        return;
    }
    const uint8_t *e = l->base + i * l->stride;
    for (int c = 0; c < info->components; c++) {
        out[c] = read_component(e + component_offset(l, csize, c), info->component_type,
                                info->normalized);
    }
}

/* Where decoded elements go: floats or uint32 (n components each). */
typedef struct sink {
    float *f;
    uint32_t *u;
} sink;

static void store(sink *s, size_t at, const double *v, int n)
{
    for (int c = 0; c < n; c++) {
        if (s->f) {
            s->f[at * (size_t)n + (size_t)c] = (float)v[c];
        } else {
            s->u[at] = (uint32_t)v[0];
        }
    }
}

/* The sparse substitution of accessor `aptr` into s. */
static sr_result apply_sparse(gltf_doc *d, const json_t *sparse, const char *aptr,
                              const gltf_accessor_info *info, const layout *dense, sink *s)
{
    char ptr[GLTF_PTR], iptr[GLTF_PTR], vptr[GLTF_PTR];
    sr__json_pointer(ptr, sizeof ptr, "%s/sparse", aptr);
    sr__json_pointer(iptr, sizeof iptr, "%s/indices", ptr);
    sr__json_pointer(vptr, sizeof vptr, "%s/values", ptr);
    size_t count = 0;
    json_t *indices, *values;
    sr_result r;
    if ((r = sr__gltf_size(d, sparse, ptr, "count", 1, info->count, true, &count)) != SR_OK ||
        (r = sr__gltf_object(d, sparse, ptr, "indices", &indices)) != SR_OK ||
        (r = sr__gltf_object(d, sparse, ptr, "values", &values)) != SR_OK) {
        return r;
    }
    if (!indices || !values) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: needs indices and values", ptr);
    }
    long iview = -1, vview = -1, itype = 0;
    size_t ioff = 0, voff = 0;
    if ((r = sr__gltf_index(d, indices, iptr, "bufferView", (size_t)-1 / 2, true, &iview)) !=
            SR_OK ||
        (r = sr__gltf_index(d, indices, iptr, "componentType", 5126, true, &itype)) != SR_OK ||
        (r = sr__gltf_size(d, indices, iptr, "byteOffset", 0, SR_IO_MAX_FILE_BYTES, false,
                           &ioff)) != SR_OK ||
        (r = sr__gltf_index(d, values, vptr, "bufferView", (size_t)-1 / 2, true, &vview)) !=
            SR_OK ||
        (r = sr__gltf_size(d, values, vptr, "byteOffset", 0, SR_IO_MAX_FILE_BYTES, false,
                           &voff)) != SR_OK) {
        return r;
    }
    if (itype != 5121 && itype != 5123 && itype != 5125) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/componentType: %ld is not an unsigned byte, short or int", iptr,
                             itype);
    }
    char bptr[GLTF_PTR];
    const uint8_t *idata, *vdata;
    size_t isize, vsize, unused;
    sr__json_pointer(bptr, sizeof bptr, "%s/bufferView", iptr);
    if ((r = sr__gltf_buffer_view(d, iview, bptr, &idata, &isize, &unused)) != SR_OK) {
        return r;
    }
    sr__json_pointer(bptr, sizeof bptr, "%s/bufferView", vptr);
    if ((r = sr__gltf_buffer_view(d, vview, bptr, &vdata, &vsize, &unused)) != SR_OK) {
        return r;
    }
    size_t isz = component_size(itype);
    layout vl = *dense;
    size_t esize = element_size(info->components, dense->rows,
                                component_size(info->component_type), &vl.column_stride);
    vl.stride = esize;   /* sparse values are tightly packed */
    if (!fits(ioff, isz, count, isz, isize)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/count: %zu indices from byte %zu run past the %zu bytes of "
                             "bufferView %ld", ptr, count, ioff, isize, iview);
    }
    if (!fits(voff, esize, count, esize, vsize)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/count: %zu values from byte %zu run past the %zu bytes of "
                             "bufferView %ld", ptr, count, voff, vsize, vview);
    }
    vl.base = vdata + voff;
    double v[16], last = -1;
    for (size_t k = 0; k < count; k++) {
        double at = read_component(idata + ioff + k * isz, itype, false);
        if (at >= (double)info->count) {
            return sr__gltf_fail(d, SR_BAD_FORMAT,
                                 "%s: index %zu is %.0f, past the accessor's %zu elements", iptr,
                                 k, at, info->count);
        }
        /* The specification asks for strictly increasing indices: a
         * repeated one would make the value depend on the reader. */
        if (at <= last) {
            return sr__gltf_fail(d, SR_BAD_FORMAT,
                                 "%s: index %zu is %.0f, not above index %zu (%.0f): sparse "
                                 "indices must strictly increase", iptr, k, at, k - 1, last);
        }
        last = at;
        read_element(&vl, info, k, v);
        store(s, (size_t)at, v, s->f ? info->components : 1);
    }
    return SR_OK;
}

/* An accessor opened for decoding: its dense part, its sparse part (or
 * NULL), its pointer, and the element budget before it was charged. */
typedef struct opened {
    layout l;
    json_t *sparse;
    char aptr[GLTF_PTR];
    size_t budget;
} opened;

/* Refuses an opened accessor's type: the budget is charged by decoding
 * alone. */
static sr_result refuse(gltf_doc *d, const opened *o, sr_result r)
{
    d->elements_left = o->budget;
    return r;
}

/* Opens accessor `index` once, for the caller's checks of its type and
 * then the decoding: describing it (its members, its bufferView's, the
 * pointers of their messages) cost as much as decoding a small one. */
static sr_result open_once(gltf_doc *d, long index, const char *ptr, gltf_accessor_info *info,
                           opened *o)
{
    o->budget = d->elements_left;
    sr_result r = open_accessor(d, index, ptr, info, &o->l, &o->sparse, o->aptr, sizeof o->aptr);
    return r == SR_OK ? r : refuse(d, o, r);
}

/* Decode the opened accessor into s (allocated here, count * n entries). */
static sr_result decode(gltf_doc *d, const opened *o, const gltf_accessor_info *info, sink *s,
                        bool as_float)
{
    const char *aptr = o->aptr;
    sr_result r = SR_OK;
    size_t n = as_float ? (size_t)info->components : 1, bytes;
    if (!sr__mul_ok(info->count, n * 4, &bytes)) {
        return sr__gltf_fail(d, SR_TOO_LARGE, "%s/count: too large", aptr);
    }
    void *block = malloc(bytes);
    if (!block) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory (%zu bytes)", aptr, bytes);
    }
    if (as_float) {
        s->f = block;
    } else {
        s->u = block;
    }
    const layout *l = &o->l;
    if (as_float && info->component_type == 5126 && l->rows == 0 && l->base) {
        /* Float vectors, the common vertex attribute, as they are: the
         * general path's round trip through double gives the same
         * floats at several times the cost. */
        for (size_t i = 0; i < info->count; i++) {
            const uint8_t *e = l->base + i * l->stride;
            for (size_t c = 0; c < n; c++) {
                s->f[i * n + c] = sr__le_float(e + 4 * c);
            }
        }
    } else if (!as_float && info->component_type == 5123 && l->base) {
        for (size_t i = 0; i < info->count; i++) {
            s->u[i] = sr__le16(l->base + i * l->stride);
        }
    } else if (!as_float && info->component_type == 5125 && l->base) {
        for (size_t i = 0; i < info->count; i++) {
            s->u[i] = sr__le32(l->base + i * l->stride);
        }
    } else {
        double v[16];
        for (size_t i = 0; i < info->count; i++) {
            read_element(l, info, i, v);
            store(s, i, v, (int)n);
        }
    }
    if (o->sparse) {
        r = apply_sparse(d, o->sparse, aptr, info, &o->l, s);
    }
    if (r == SR_OK && as_float && info->component_type == 5126) {
        for (size_t i = 0; i < info->count * n; i++) {
            if (!isfinite(s->f[i])) {
                r = sr__gltf_fail(d, SR_BAD_FORMAT, "%s: element %zu is not finite", aptr,
                                  i / n);
                break;
            }
        }
    }
    if (r != SR_OK) {
        free(block);
        s->f = NULL;
        s->u = NULL;
    }
    return r;
}

sr_result sr__gltf_read_floats(gltf_doc *d, long index, const char *ptr, unsigned allowed,
                               gltf_accessor_info *info, float **out)
{
    sink s = {0};
    opened o;
    *out = NULL;
    sr_result r = open_once(d, index, ptr, info, &o);
    if (r != SR_OK) {
        return r;
    }
    if (info->matrix) {
        return refuse(d, &o, sr__gltf_fail(d, SR_BAD_FORMAT,
                                           "%s: accessor %ld holds matrices, not vectors", ptr,
                                           index));
    }
    if (!(allowed & (1u << info->components))) {
        return refuse(d, &o, sr__gltf_fail(d, SR_BAD_FORMAT,
                                           "%s: accessor %ld has %d components per element, "
                                           "not what this attribute takes",
                                           ptr, index, info->components));
    }
    if (info->component_type == 5125) {
        return refuse(d, &o, sr__gltf_fail(d, SR_BAD_FORMAT,
                                           "%s: accessor %ld has unsigned int components, "
                                           "which no vertex attribute takes",
                                           ptr, index));
    }
    r = decode(d, &o, info, &s, true);
    *out = s.f;
    return r;
}

sr_result sr__gltf_read_indices(gltf_doc *d, long index, const char *ptr,
                                gltf_accessor_info *info, uint32_t **out)
{
    sink s = {0};
    opened o;
    *out = NULL;
    sr_result r = open_once(d, index, ptr, info, &o);
    if (r != SR_OK) {
        return r;
    }
    if (info->components != 1 || info->normalized ||
        (info->component_type != 5121 && info->component_type != 5123 &&
         info->component_type != 5125)) {
        return refuse(d, &o, sr__gltf_fail(d, SR_BAD_FORMAT,
                                           "%s: accessor %ld is not a SCALAR of unsigned bytes, "
                                           "shorts or ints",
                                           ptr, index));
    }
    r = decode(d, &o, info, &s, false);
    *out = s.u;
    return r;
}

sr_result sr__gltf_read_mat4(gltf_doc *d, long index, const char *ptr, gltf_accessor_info *info,
                             float **out)
{
    sink s = {0};
    opened o;
    *out = NULL;
    sr_result r = open_once(d, index, ptr, info, &o);
    if (r != SR_OK) {
        return r;
    }
    if (!info->matrix || info->components != 16 || info->component_type != 5126) {
        return refuse(d, &o, sr__gltf_fail(d, SR_BAD_FORMAT,
                                           "%s: accessor %ld is not a MAT4 of floats", ptr,
                                           index));
    }
    r = decode(d, &o, info, &s, true);
    *out = s.f;
    return r;
}
