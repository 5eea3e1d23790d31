/* gltf_draco.c - KHR_draco_mesh_compression for the glTF reader (io
 * stage): a primitive whose geometry is a Draco stream is decoded once,
 * before its accessors are read, by libdraco (draco_decode.cc); each
 * accessor the stream fills is written as the accessor would store its
 * elements, and gltf_accessor.c reads those bytes with every check it
 * makes.  Without libdraco the accessors read their uncompressed fallback,
 * or the primitive is refused when they have none.  Called by gltf.c's
 * read_primitive; one document, one thread. */
#include "io/gltf.h"

#include <stdlib.h>
#include <string.h>

#ifdef SR_HAVE_DRACO
#include "io/draco_decode.h"
#endif

#define EXT_NAME "KHR_draco_mesh_compression"

/* The attributes softrast reads (gltf.c's read_primitive); a stream's
 * others (joints, weights, more coordinate sets) are left encoded. */
static const char *const read_attributes[] = { "POSITION",   "NORMAL",     "TANGENT",
                                               "TEXCOORD_0", "TEXCOORD_1", "COLOR_0" };
#define READ_COUNT (sizeof read_attributes / sizeof *read_attributes)

/* The decoded accessors of one primitive: the attributes read, then the
 * indices. */
struct gltf_draco_primitive {
    long accessor[READ_COUNT + 1];
    uint8_t *bytes[READ_COUNT + 1];
    size_t size[READ_COUNT + 1];
    size_t count;
    uint32_t *corners;           /* when the primitive has no indices accessor */
};

bool sr__gltf_have_draco(void)
{
#ifdef SR_HAVE_DRACO
    return true;
#else
    return false;
#endif
}

const uint8_t *sr__gltf_draco_accessor(const gltf_doc *d, long index, size_t *size)
{
    for (size_t i = 0; d->draco && i < d->draco->count; i++) {
        if (d->draco->accessor[i] == index) {
            *size = d->draco->size[i];
            return d->draco->bytes[i];
        }
    }
    *size = 0;
    return NULL;
}

void sr__gltf_draco_end(gltf_doc *d)
{
    struct gltf_draco_primitive *p = d->draco;
    for (size_t i = 0; p && i < p->count; i++) {
        free(p->bytes[i]);
    }
    if (p) {
        free(p->corners);
        free(p);
    }
    d->draco = NULL;
}

/* The primitive's accessor for attribute `name` (-1: none), and the
 * pointer naming it. */
static sr_result primitive_accessor(gltf_doc *d, const json_t *prim, const char *ptr,
                                    const char *name, long *index, char *aptr, size_t cap)
{
    *index = -1;
    if (name) {
        snprintf(aptr, cap, "%s/attributes/%s", ptr, name);
        json_t *attrs = json_object_get(prim, "attributes");
        char attrs_ptr[GLTF_PTR];
        snprintf(attrs_ptr, sizeof attrs_ptr, "%s/attributes", ptr);
        return sr__gltf_index(d, attrs, attrs_ptr, name, (size_t)-1 / 2, false, index);
    }
    snprintf(aptr, cap, "%s/indices", ptr);
    return sr__gltf_index(d, prim, ptr, "indices", (size_t)-1 / 2, false, index);
}

#ifdef SR_HAVE_DRACO

/* The extension's members, checked: bufferView, attributes (names of the
 * primitive's attributes, each a Draco unique id). */
static sr_result check_extension(gltf_doc *d, const json_t *prim, const json_t *ext,
                                 const char *eptr, long *view, json_t **attrs)
{
    sr_result r;
    if ((r = sr__gltf_index(d, ext, eptr, "bufferView", (size_t)-1 / 2, true, view)) != SR_OK ||
        (r = sr__gltf_object(d, ext, eptr, "attributes", attrs)) != SR_OK) {
        return r;
    }
    if (!*attrs) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/attributes: missing", eptr);
    }
    char aptr[GLTF_PTR];
    snprintf(aptr, sizeof aptr, "%s/attributes", eptr);
    const char *name;
    json_t *id;
    json_t *prim_attrs = json_object_get(prim, "attributes");
    json_object_foreach(*attrs, name, id) {
        long unused;
        if ((r = sr__gltf_index(d, *attrs, aptr, name, UINT32_MAX, true, &unused)) != SR_OK) {
            return r;
        }
        if (!json_object_get(prim_attrs, name)) {
            return sr__gltf_fail(d, SR_BAD_FORMAT,
                                 "%s/%.64s: not one of the primitive's attributes", aptr, name);
        }
    }
    return SR_OK;
}

static size_t component_bytes(int type)
{
    return type == 5126 || type == 5125 ? 4 : type >= 5122 ? 2 : 1;
}

/* Attribute `name` (NULL: the indices) of the decoded mesh into slot k,
 * as its accessor stores it; `strip`: the primitive is a triangle strip. */
static sr_result fill(gltf_doc *d, const json_t *prim, const char *ptr, const json_t *attrs,
                      const char *eptr, const char *name, const sr_draco_mesh *m, bool strip,
                      struct gltf_draco_primitive *p)
{
    long index;
    char aptr[GLTF_PTR], xptr[GLTF_PTR];
    sr_result r = primitive_accessor(d, prim, ptr, name, &index, aptr, sizeof aptr);
    if (r != SR_OK || index < 0) {
        return r;
    }
    gltf_accessor_info info;
    if ((r = sr__gltf_accessor_info(d, index, aptr, &info)) != SR_OK) {
        return r;
    }
    size_t points = sr__draco_points(m), faces = sr__draco_faces(m);
    size_t csize = component_bytes(info.component_type), bytes;
    if (info.matrix) {
        return SR_OK;   /* refused by the accessor's reader */
    }
    if (!name) {
        /* Indices: Draco's triangles' corners, in the accessor's type. */
        if (info.components != 1 || info.component_type == 5126 || info.component_type == 5120 ||
            info.component_type == 5122) {
            return SR_OK;   /* refused by sr__gltf_read_indices */
        }
        /* A strip's indices are the corners too, but its triangles are
         * not the stream's faces: it draws corners - 2 of them. */
        if (info.count != faces * 3) {
            return sr__gltf_fail(d, SR_BAD_FORMAT,
                                 "%s: accessor %ld has %zu elements, but the Draco stream (%s) "
                                 "has %zu %s (%zu corners%s)",
                                 aptr, index, info.count, eptr, faces,
                                 strip ? "faces" : "triangles", faces * 3,
                                 strip ? ", the strip's indices" : "");
        }
        if (csize < 4 && points > ((size_t)1 << (8 * csize))) {
            return sr__gltf_fail(d, SR_BAD_FORMAT,
                                 "%s: accessor %ld's componentType %d cannot index the Draco "
                                 "stream's %zu points",
                                 aptr, index, info.component_type, points);
        }
    } else {
        snprintf(xptr, sizeof xptr, "%s/attributes/%s", eptr, name);
        if (info.count != points) {
            return sr__gltf_fail(d, SR_BAD_FORMAT,
                                 "%s: the Draco stream has %zu points, but accessor %ld (%s) "
                                 "has %zu elements",
                                 xptr, points, index, aptr, info.count);
        }
    }
    if (!sr__mul_ok(info.count, csize * (size_t)info.components, &bytes)) {
        return sr__gltf_fail(d, SR_TOO_LARGE, "%s: too large", aptr);
    }
    size_t k = p->count;
    p->bytes[k] = malloc(bytes ? bytes : 1);
    if (!p->bytes[k]) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory for %zu bytes", aptr,
                             bytes);
    }
    p->accessor[k] = index;
    p->size[k] = bytes;
    p->count++;
    if (!name) {
        uint32_t *corners = malloc(faces * 3 * sizeof *corners + 1);
        if (!corners) {
            return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", aptr);
        }
        sr__draco_indices(m, corners);
        for (size_t i = 0; i < faces * 3; i++) {
            for (size_t b = 0; b < csize; b++) {
                p->bytes[k][i * csize + b] = (uint8_t)(corners[i] >> (8 * b));
            }
        }
        free(corners);
        return SR_OK;
    }
    long id;
    if ((r = sr__gltf_index(d, attrs, eptr, name, UINT32_MAX, true, &id)) != SR_OK) {
        return r;
    }
    char why[160];
    sr_draco_status s = sr__draco_attribute(m, (uint32_t)id, info.component_type,
                                            info.components, p->bytes[k], why, sizeof why);
    switch (s) {
    case SR_DRACO_OK:
        return SR_OK;
    case SR_DRACO_NO_ATTRIBUTE:
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: the Draco stream has no attribute of unique "
                             "id %ld", xptr, id);
    case SR_DRACO_MISMATCH:
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: Draco attribute %ld does not match accessor "
                             "%ld (%s): %s", xptr, id, index, aptr, why);
    case SR_DRACO_NO_MEMORY:
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", xptr);
    default:
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: Draco attribute %ld does not decode (%s)",
                             xptr, id, why);
    }
}

/* The bytes the decoded accessors will take, counted against the budget
 * before the stream is decoded: a few bytes of Draco can claim millions
 * of points. */
static sr_result charge(gltf_doc *d, const json_t *prim, const char *ptr, const char *eptr)
{
    size_t total = 0;
    for (size_t i = 0; i <= READ_COUNT; i++) {
        const char *name = i < READ_COUNT ? read_attributes[i] : NULL;
        long index;
        char aptr[GLTF_PTR];
        gltf_accessor_info info;
        sr_result r = primitive_accessor(d, prim, ptr, name, &index, aptr, sizeof aptr);
        if (r == SR_OK && index >= 0) {
            r = sr__gltf_accessor_info(d, index, aptr, &info);
        }
        if (r != SR_OK) {
            return r;
        }
        size_t bytes;
        if (index >= 0 && (!sr__mul_ok(info.count, 4 * (size_t)info.components, &bytes) ||
                           __builtin_add_overflow(total, bytes, &total))) {
            total = (size_t)-1;
        }
    }
    if (total / 4 > d->elements_left) {
        return sr__gltf_fail(d, SR_TOO_LARGE,
                             "%s: %zu bytes to decode are more than a file of this size may "
                             "decode",
                             eptr, total);
    }
    d->elements_left -= total / 4;
    return SR_OK;
}

sr_result sr__gltf_draco_begin(gltf_doc *d, const json_t *prim, const json_t *ext,
                               const char *ptr, const uint32_t **indices, size_t *index_count)
{
    *indices = NULL;
    *index_count = 0;
    char eptr[GLTF_PTR], vptr[GLTF_PTR];
    snprintf(eptr, sizeof eptr, "%s/extensions/" EXT_NAME, ptr);
    snprintf(vptr, sizeof vptr, "%s/bufferView", eptr);
    long view = -1, mode = 4;
    json_t *attrs;
    sr_result r;
    if ((r = sr__gltf_index(d, prim, ptr, "mode", 7, false, &mode)) != SR_OK ||
        (r = check_extension(d, prim, ext, eptr, &view, &attrs)) != SR_OK) {
        return r;
    }
    /* "The mode of primitive must be either TRIANGLES or TRIANGLE_STRIP
     * and the mesh data will be decoded accordingly": the stream's
     * corners, face after face, are then the primitive's indices, laid out
     * as its mode says (gltf.c's triangles_of). */
    if (mode != 4 && mode != 5) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/mode: %ld, but KHR_draco_mesh_compression allows triangles "
                             "(4) and triangle strips (5) only", ptr, mode);
    }
    if ((r = charge(d, prim, ptr, eptr)) != SR_OK) {
        return r;
    }
    const uint8_t *data;
    size_t size, stride;
    if ((r = sr__gltf_buffer_view(d, view, vptr, &data, &size, &stride)) != SR_OK) {
        return r;
    }
    sr_draco_mesh *m;
    char why[160];
    switch (sr__draco_decode(data, size, &m, why, sizeof why)) {
    case SR_DRACO_OK:
        break;
    case SR_DRACO_NOT_A_MESH:
        return sr__gltf_fail(d, SR_UNSUPPORTED,
                             "%s: the Draco stream is a point cloud, not a triangle mesh",
                             vptr);
    case SR_DRACO_NO_MEMORY:
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory decoding the Draco stream",
                             vptr);
    default:
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s: the Draco stream does not decode (corrupt or truncated; "
                             "libdraco: %s)", vptr, why[0] ? why : "no reason given");
    }
    /* A strip survives only a stream that keeps the faces and their
     * corners in order: sequential connectivity.  Edgebreaker, libdraco's
     * default, reorders both, so its corners are no strip.  The header
     * (DracoBitstream.md): "DRACO", major and minor version, encoder
     * type, encoder method (0 sequential, 1 edgebreaker); the stream
     * decoded, so its nine bytes are there. */
    if (mode == 5 && data[8] != 0) {
        sr__draco_free(m);
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/mode: 5 (a triangle strip), but the Draco stream (%s) is "
                             "edgebreaker-encoded, which reorders the triangles: a strip needs "
                             "sequential connectivity",
                             ptr, vptr);
    }
    d->draco = calloc(1, sizeof *d->draco);
    if (!d->draco) {
        sr__draco_free(m);
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", eptr);
    }
    for (size_t i = 0; r == SR_OK && i < READ_COUNT; i++) {
        if (json_object_get(attrs, read_attributes[i])) {
            r = fill(d, prim, ptr, attrs, eptr, read_attributes[i], m, mode == 5, d->draco);
        }
    }
    if (r == SR_OK && json_object_get(prim, "indices")) {
        r = fill(d, prim, ptr, attrs, eptr, NULL, m, mode == 5, d->draco);
    } else if (r == SR_OK) {
        /* No indices accessor: the stream's triangles, as they are. */
        size_t faces = sr__draco_faces(m);
        d->draco->corners = malloc(faces * 3 * sizeof *d->draco->corners + 1);
        if (!d->draco->corners) {
            r = sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", eptr);
        } else {
            sr__draco_indices(m, d->draco->corners);
            *indices = d->draco->corners;
            *index_count = faces * 3;
        }
    }
    sr__draco_free(m);
    return r;
}

#else /* !SR_HAVE_DRACO */

/* Without libdraco the primitive is read from its accessors, the
 * uncompressed copy a writer may keep, and the extension is ignored, as
 * the specification asks of a reader without it: each accessor the stream
 * would fill (all it may fill, when the extension names none) must have
 * a bufferView, since one without reads as zeros. */
sr_result sr__gltf_draco_begin(gltf_doc *d, const json_t *prim, const json_t *ext,
                               const char *ptr, const uint32_t **indices, size_t *index_count)
{
    *indices = NULL;
    *index_count = 0;
    json_t *attrs = json_object_get(ext, "attributes");
    sr_result r = SR_OK;
    for (size_t i = 0; r == SR_OK && i <= READ_COUNT; i++) {
        const char *name = i < READ_COUNT ? read_attributes[i] : NULL;
        long index;
        char aptr[GLTF_PTR];
        if (name && json_is_object(attrs) && !json_object_get(attrs, name)) {
            continue;
        }
        r = primitive_accessor(d, prim, ptr, name, &index, aptr, sizeof aptr);
        if (r != SR_OK || index < 0) {
            continue;
        }
        json_t *a = json_array_get(json_object_get(d->root, "accessors"), (size_t)index);
        if (json_is_object(a) && !json_object_get(a, "bufferView") &&
            !json_object_get(a, "sparse")) {
            r = sr__gltf_fail(d, SR_UNSUPPORTED,
                              "%s: softrast was built without libdraco, and accessor %ld holds "
                              "no uncompressed fallback",
                              aptr, index);
        }
    }
    return r;
}

#endif
