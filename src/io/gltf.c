/*
 * gltf.c - io stage: glTF 2.0 documents (.gltf, .glb) read into an
 * sr_scene.  Consumes the JSON (parsed by jansson) and its buffers - the
 * GLB's BIN chunk, data: URIs, files beside the document; produces the
 * scene flattened for drawing: one primitive per node instance of a mesh
 * primitive with its world matrix, the cameras the nodes place, the
 * materials (gltf_material.c) and the bounds.  Any thread may call it with
 * a context of its own; jansson keeps no shared state.
 */
#include "io/byteorder.h"
#include "io/gltf.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* ---- messages ------------------------------------------------------------ */

sr_result sr__gltf_fail(gltf_doc *d, sr_result code, const char *fmt, ...)
{
    if (d->err && d->err->message[0] == 0) {
        char reason[sizeof d->err->message];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(reason, sizeof reason, fmt, ap);
        va_end(ap);
        sr__io_fail(d->err, code, d->name, 0, "%s", reason);
    }
    return code;
}

void sr__gltf_warn(gltf_doc *d, const char *fmt, ...)
{
    if (d->scene) {
        d->scene->warning_count++;
    }
    if (!d->desc || !d->desc->warn) {
        return;
    }
    char reason[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(reason, sizeof reason, fmt, ap);
    va_end(ap);
    sr_io_error line = {{0}};
    sr__io_fail(&line, SR_OK, d->name, 0, "warning: %s", reason);
    d->desc->warn(d->desc->user, line.message);
}

/* ---- JSON members -------------------------------------------------------- */

/* sr__gltf_size of the member v (NULL: absent), looked up by the caller. */
static sr_result size_member(gltf_doc *d, const json_t *v, const char *ptr, const char *key,
                             size_t lo, size_t hi, bool required, size_t *out)
{
    if (!v) {
        return required ? sr__gltf_fail(d, SR_BAD_FORMAT, "%s/%s: missing", ptr, key) : SR_OK;
    }
    /* Some writers print integers as reals ("36.0"): whole ones are taken. */
    double real = json_is_real(v) ? json_real_value(v) : 0.5;
    if (!json_is_integer(v) && !(real == floor(real) && fabs(real) < 9e15)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/%s: not an integer", ptr, key);
    }
    json_int_t i = json_is_integer(v) ? json_integer_value(v) : (json_int_t)real;
    if (i < 0 || (unsigned long long)i < lo || (unsigned long long)i > hi) {
        return sr__gltf_fail(d, i < 0 || (unsigned long long)i < lo ? SR_BAD_FORMAT : SR_TOO_LARGE,
                             "%s/%s: %lld is outside %zu..%zu", ptr, key, (long long)i, lo, hi);
    }
    *out = (size_t)i;
    return SR_OK;
}

sr_result sr__gltf_size(gltf_doc *d, const json_t *obj, const char *ptr, const char *key,
                        size_t lo, size_t hi, bool required, size_t *out)
{
    return size_member(d, json_object_get(obj, key), ptr, key, lo, hi, required, out);
}

sr_result sr__gltf_index(gltf_doc *d, const json_t *obj, const char *ptr, const char *key,
                         size_t limit, bool required, long *out)
{
    size_t v = 0;
    json_t *m = json_object_get(obj, key);
    double value = json_number_value(m);
    if (json_is_number(m) && value == floor(value) && value < 0) {
        /* Not "below LIMIT": callers that resolve the index later pass a
         * limit that means no bound yet. */
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/%s: %.0f is negative, not an index", ptr, key,
                             value);
    }
    if (json_is_number(m) && value == floor(value) && value >= (double)limit) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/%s: %.0f is not an index below %zu", ptr, key,
                             value, limit);
    }
    sr_result r = size_member(d, m, ptr, key, 0, limit - 1, required, &v);
    if (r == SR_OK && m) {
        *out = (long)v;
    }
    return r;
}

sr_result sr__gltf_number(gltf_doc *d, const json_t *obj, const char *ptr, const char *key,
                          float *out)
{
    json_t *v = json_object_get(obj, key);
    if (!v) {
        return SR_OK;
    }
    if (!json_is_number(v) || !isfinite((float)json_number_value(v))) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/%s: not a finite number", ptr, key);
    }
    *out = (float)json_number_value(v);
    return SR_OK;
}

sr_result sr__gltf_numbers(gltf_doc *d, const json_t *obj, const char *ptr, const char *key,
                           size_t n, float *out)
{
    json_t *v = json_object_get(obj, key);
    if (!v) {
        return SR_OK;
    }
    if (!json_is_array(v) || json_array_size(v) != n) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/%s: not an array of %zu numbers", ptr, key, n);
    }
    for (size_t i = 0; i < n; i++) {
        json_t *e = json_array_get(v, i);
        if (!json_is_number(e) || !isfinite((float)json_number_value(e))) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/%s/%zu: not a finite number", ptr, key, i);
        }
        out[i] = (float)json_number_value(e);
    }
    return SR_OK;
}

sr_result sr__gltf_array(gltf_doc *d, const json_t *obj, const char *ptr, const char *key,
                         json_t **out, size_t *count)
{
    json_t *v = json_object_get(obj, key);
    *out = NULL;
    *count = 0;
    if (!v) {
        return SR_OK;
    }
    if (!json_is_array(v)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/%s: not an array", ptr, key);
    }
    *out = v;
    *count = json_array_size(v);
    return SR_OK;
}

sr_result sr__gltf_object(gltf_doc *d, const json_t *obj, const char *ptr, const char *key,
                          json_t **out)
{
    json_t *v = json_object_get(obj, key);
    *out = NULL;
    if (v && !json_is_object(v)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/%s: not an object", ptr, key);
    }
    *out = v;
    return SR_OK;
}

json_t *sr__gltf_extension(const json_t *obj, const char *name)
{
    json_t *e = json_object_get(json_object_get(obj, "extensions"), name);
    return json_is_object(e) ? e : NULL;
}

/* The element `i` of root[key], which must be an object: *ptr is set to
 * "/key/i". */
static sr_result element(gltf_doc *d, const char *key, long i, const char *use, json_t **out,
                         char *ptr, size_t cap)
{
    json_t *arr;
    size_t n;
    *out = NULL;
    sr_result r = sr__gltf_array(d, d->root, "", key, &arr, &n);
    if (r != SR_OK) {
        return r;
    }
    if (i < 0 || (size_t)i >= n) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: %s %ld does not exist (%zu of them)", use, key,
                             i, n);
    }
    sr__json_pointer(ptr, cap, "/%s/%ld", key, i);
    *out = json_array_get(arr, (size_t)i);
    if (!json_is_object(*out)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: not an object", ptr);
    }
    return SR_OK;
}

/* ---- URIs and buffers ---------------------------------------------------- */

static int hex_value(char c)
{
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

/* Whether a decoded relative path names a file under the model's
 * directory: it must not be absolute (a percent-encoded "/" decodes to
 * one) nor climb above its start with "..", so that a document cannot make
 * the reader open files elsewhere. */
static bool stays_inside(const char *rel)
{
    if (rel[0] == '/') {
        return false;
    }
    long depth = 0;
    for (const char *s = rel; *s;) {
        size_t n = strcspn(s, "/");
        if (n == 2 && s[0] == '.' && s[1] == '.') {
            if (--depth < 0) {
                return false;
            }
        } else if (n > 0 && !(n == 1 && s[0] == '.')) {
            depth++;
        }
        s += n + (s[n] == '/');
    }
    return true;
}

sr_result sr__gltf_read_uri(gltf_doc *d, const char *uri, const char *ptr, char **owned,
                            size_t *size, bool *from_file)
{
    *owned = NULL;
    *from_file = false;
    if (strncmp(uri, "data:", 5) == 0) {
        const char *comma = strchr(uri, ',');
        if (!comma || comma - uri < 12 || strncmp(comma - 7, ";base64", 7) != 0) {
            return sr__gltf_fail(d, SR_UNSUPPORTED, "%s: only base64 data: URIs are read", ptr);
        }
        uint8_t *b;
        if (!sr__base64_decode(comma + 1, strlen(comma + 1), &b, size)) {
            return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
        }
        if (!b) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: invalid base64", ptr);
        }
        *owned = (char *)b;
        return SR_OK;
    }
    const char *colon = strpbrk(uri, ":/?#");
    if (uri[0] == '/' || (colon && *colon == ':')) {
        return sr__gltf_fail(d, SR_UNSUPPORTED,
                             "%s: only relative file names and data: URIs are read", ptr);
    }
    const char *dir = d->dir;
    size_t dlen = strlen(dir), ulen = strlen(uri);
    char *path = malloc(dlen + ulen + 2);
    if (!path) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
    }
    memcpy(path, dir, dlen);
    size_t o = dlen;
    for (size_t i = 0; i < ulen; i++) {
        int hi, lo;
        if (uri[i] == '%' && i + 2 < ulen && (hi = hex_value(uri[i + 1])) >= 0 &&
            (lo = hex_value(uri[i + 2])) >= 0 && (hi | lo) != 0) {
            path[o++] = (char)(hi << 4 | lo);
            i += 2;
        } else {
            path[o++] = uri[i];
        }
    }
    path[o] = 0;
    if (!stays_inside(path + dlen)) {
        free(path);
        return sr__gltf_fail(d, SR_UNSUPPORTED,
                             "%s: only file names inside the model's directory are read", ptr);
    }
    sr_io_error inner = {{0}};
    char *data;
    sr_result r = sr__read_file(path, &data, size, &inner);
    if (r == SR_OK && d->desc && d->desc->file_read) {
        d->desc->file_read(d->desc->user, path);
    }
    free(path);
    if (r != SR_OK) {
        return sr__gltf_fail(d, r, "%s: %s", ptr, inner.message);
    }
    *owned = data;
    *from_file = true;
    return SR_OK;
}

/* Buffer i's bytes, read on first use. */
static sr_result load_buffer(gltf_doc *d, long i, const char *use, gltf_buffer **out)
{
    char ptr[GLTF_PTR];
    json_t *b;
    sr_result r = element(d, "buffers", i, use, &b, ptr, sizeof ptr);
    if (r != SR_OK) {
        return r;
    }
    gltf_buffer *buf = &d->buffers[i];
    *out = buf;
    if (buf->loaded) {
        return SR_OK;
    }
    size_t length = 0;
    if ((r = sr__gltf_size(d, b, ptr, "byteLength", 1, SR_IO_MAX_FILE_BYTES, true, &length)) !=
        SR_OK) {
        return r;
    }
    json_t *uri = json_object_get(b, "uri");
    const uint8_t *data;
    size_t size;
    if (uri) {
        if (!json_is_string(uri)) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/uri: not a string", ptr);
        }
        char uptr[GLTF_PTR];
        sr__json_pointer(uptr, sizeof uptr, "%s/uri", ptr);
        if ((r = sr__gltf_read_uri(d, json_string_value(uri), uptr, &buf->owned,
                          &buf->owned_size, &buf->from_file)) != SR_OK) {
            return r;
        }
        data = (const uint8_t *)buf->owned;
        size = buf->owned_size;
        d->input_bytes += size;
        /* Data read from elsewhere earns its own decoding budget. */
        size_t more;
        if (sr__mul_ok(size, SR_SCENE_ELEMENTS_PER_BYTE, &more) &&
            !__builtin_add_overflow(d->elements_left, more, &more)) {
            d->elements_left = more;
        }
    } else if (i == 0 && d->bin) {
        data = d->bin;
        size = d->bin_size;
    } else if (sr__gltf_is_fallback_buffer(b)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s: a fallback buffer without data, read by %s (which has no "
                             "EXT_meshopt_compression)",
                             ptr, use);
    } else {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/uri: missing (and no GLB BIN chunk)", ptr);
    }
    if (length > size) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/byteLength: %zu, but only %zu bytes are there",
                             ptr, length, size);
    }
    buf->data = data;
    buf->size = length;
    buf->loaded = true;
    return SR_OK;
}

sr_result sr__gltf_buffer_bytes(gltf_doc *d, long i, const char *use, const uint8_t **data,
                                size_t *size)
{
    gltf_buffer *b;
    sr_result r = load_buffer(d, i, use, &b);
    *data = r == SR_OK ? b->data : NULL;
    *size = r == SR_OK ? b->size : 0;
    return r;
}

sr_result sr__gltf_buffer_view(gltf_doc *d, long view, const char *use, const uint8_t **data,
                               size_t *size, size_t *stride)
{
    char ptr[GLTF_PTR];
    json_t *v;
    sr_result r = element(d, "bufferViews", view, use, &v, ptr, sizeof ptr);
    if (r != SR_OK) {
        return r;
    }
    long buffer = -1;
    size_t offset = 0, length = 0;
    *stride = 0;
    if ((r = sr__gltf_index(d, v, ptr, "buffer", d->buffer_count ? d->buffer_count : 1, true,
                            &buffer)) != SR_OK ||
        (r = sr__gltf_size(d, v, ptr, "byteOffset", 0, SR_IO_MAX_FILE_BYTES, false, &offset)) !=
            SR_OK ||
        (r = sr__gltf_size(d, v, ptr, "byteLength", 1, SR_IO_MAX_FILE_BYTES, true, &length)) !=
            SR_OK ||
        (r = sr__gltf_size(d, v, ptr, "byteStride", 4, 252, false, stride)) != SR_OK) {
        return r;
    }
    json_t *meshopt = sr__gltf_extension(v, "EXT_meshopt_compression");
    if (meshopt) {
        if ((r = sr__gltf_meshopt_view(d, view, meshopt, ptr, length, *stride, data)) != SR_OK) {
            return r;
        }
        if (*data) {
            *size = length;
            return SR_OK;
        }
    }
    char bptr[GLTF_PTR];
    sr__json_pointer(bptr, sizeof bptr, "%s/buffer", ptr);
    gltf_buffer *b;
    if ((r = load_buffer(d, buffer, bptr, &b)) != SR_OK) {
        return r;
    }
    if (offset > b->size || length > b->size - offset) {
        return sr__gltf_fail(d, SR_BAD_FORMAT,
                             "%s/byteLength: bytes %zu..%zu run past the %zu bytes of buffer %ld",
                             ptr, offset, offset + length, b->size, buffer);
    }
    *data = b->data + offset;
    *size = length;
    return SR_OK;
}

/* ---- meshes -------------------------------------------------------------- */

/* A mesh's primitives decoded once, drawn by every node that uses the
 * mesh: arrays, counts and material set, world not (NULL positions:
 * skipped); beside each, what posing it per node takes. */
typedef struct gltf_mesh {
    sr_scene_primitive *prims;
    gltf_pose_source *pose;     /* count of them, malloc'd */
    size_t count;
    size_t target_count;        /* every primitive's, checked equal */
    bool decoded;
} gltf_mesh;

/* Triangles from a primitive's mode, as indices into its vertices. */
static sr_result triangles_of(gltf_doc *d, const char *ptr, long mode, const uint32_t *idx,
                              size_t n, size_t vertex_count, sr_scene_primitive *p)
{
    size_t tris;
    if (mode == 4) {
        if (n % 3 != 0) {
            return sr__gltf_fail(d, SR_BAD_FORMAT,
                                 "%s: %zu vertices do not make whole triangles", ptr, n);
        }
        tris = n / 3;
    } else {
        tris = n >= 3 ? n - 2 : 0;
    }
    for (size_t i = 0; i < n; i++) {
        uint32_t v = idx ? idx[i] : (uint32_t)i;
        if (v >= vertex_count) {
            return sr__gltf_fail(d, SR_BAD_FORMAT,
                                 "%s/indices: element %zu is %u, past the %zu vertices", ptr, i,
                                 v, vertex_count);
        }
    }
    uint32_t *out = sr__scene_alloc(d->scene, tris * 3 * sizeof *out + 1);
    if (!out) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
    }
#define IDX(k) (idx ? idx[k] : (uint32_t)(k))
    for (size_t t = 0; t < tris; t++) {
        uint32_t *o = out + 3 * t;
        if (mode == 4) {
            o[0] = IDX(3 * t), o[1] = IDX(3 * t + 1), o[2] = IDX(3 * t + 2);
        } else if (mode == 5) {
            /* Strip: every other triangle reversed to keep the winding. */
            o[0] = IDX(t), o[1] = IDX(t + 1 + t % 2), o[2] = IDX(t + 2 - t % 2);
        } else {
            o[0] = IDX(t + 1), o[1] = IDX(t + 2), o[2] = IDX(0);
        }
    }
#undef IDX
    p->indices = out;
    p->triangle_count = tris;
    return SR_OK;
}

/* One vertex attribute into the scene: `name` of the primitive's
 * attributes, checked against the vertex count. */
static sr_result attribute(gltf_doc *d, const json_t *attrs, const char *aptr, const char *name,
                           unsigned allowed, size_t vertex_count, gltf_accessor_info *info,
                           float **out)
{
    *out = NULL;
    long index = -1;
    sr_result r = sr__gltf_index(d, attrs, aptr, name, (size_t)-1 / 2, false, &index);
    if (r != SR_OK || index < 0) {
        return r;
    }
    char ptr[GLTF_PTR];
    sr__json_pointer(ptr, sizeof ptr, "%s/%s", aptr, name);
    float *f;
    if ((r = sr__gltf_read_floats(d, index, ptr, allowed, info, &f)) != SR_OK) {
        return r;
    }
    if (!sr__scene_keep(d->scene, f)) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
    }
    if (vertex_count != (size_t)-1 && info->count != vertex_count) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: accessor %ld has %zu elements, POSITION %zu",
                             ptr, index, info->count, vertex_count);
    }
    *out = f;
    return SR_OK;
}

/* glTF's v runs down the image, sr_make_texture's up. */
static void flip_v(float *uv, size_t n)
{
    for (size_t i = 0; uv && i < n; i++) {
        uv[2 * i + 1] = 1.0f - uv[2 * i + 1];
    }
}

/* A texture of the primitive's material that reads a coordinate set the
 * primitive lacks is drawn as one texel's color: said once per primitive,
 * since the file looks textured in other viewers' lists but not drawn so. */
static void check_texcoords(gltf_doc *d, const char *aptr, int material, bool has0, bool has1)
{
    const sr_pbr_material *m = &d->scene->materials[material];
    const sr_texture_slot *slots[] = { &m->base_color_texture, &m->metallic_roughness_texture,
                                       &m->normal_texture, &m->occlusion_texture,
                                       &m->emissive_texture, &m->specular_texture,
                                       &m->specular_color_texture, &m->clearcoat_texture,
                                       &m->clearcoat_roughness_texture,
                                       &m->clearcoat_normal_texture, &m->sheen_color_texture,
                                       &m->sheen_roughness_texture };
    size_t n;
    for (size_t i = 0; i < sizeof slots / sizeof *slots; i++) {
        int set = slots[i]->texcoord;
        /* for_mesh makes no textures: its base color image is a source. */
        bool textured = slots[i]->texture ||
                        (i == 0 && sr__scene_source(d->scene, (size_t)material, &n));
        if (textured && !(set == 0 ? has0 : has1)) {
            sr__gltf_warn(d, "%s: no TEXCOORD_%d, which material %d's textures read (drawn "
                          "with one color of the texture)", aptr, set, material);
            return;
        }
    }
}

/* `draco_corners`: the triangles' corners of a KHR_draco_mesh_compression
 * primitive without an indices accessor, else NULL. */
static sr_result read_arrays(gltf_doc *d, const json_t *prim, const char *ptr,
                             const uint32_t *draco_corners, size_t draco_corner_count,
                             sr_scene_primitive *p, gltf_pose_source *pose)
{
    json_t *attrs;
    long mode = 4, indices = -1, material = -1;
    sr_result r;
    if (!json_is_object(prim)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: not an object", ptr);
    }
    if ((r = sr__gltf_object(d, prim, ptr, "attributes", &attrs)) != SR_OK ||
        (r = sr__gltf_index(d, prim, ptr, "mode", 7, false, &mode)) != SR_OK ||
        (r = sr__gltf_index(d, prim, ptr, "indices", (size_t)-1 / 2, false, &indices)) != SR_OK ||
        (r = sr__gltf_index(d, prim, ptr, "material", d->scene->material_count - 1, false,
                            &material)) != SR_OK) {
        return r;
    }
    if (!attrs) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/attributes: missing", ptr);
    }
    p->material = material >= 0 ? (int)material : (int)d->scene->material_count - 1;
    if ((r = sr__gltf_primitive_variants(d, prim, ptr, p)) != SR_OK) {
        return r;
    }
    if (mode < 4) {
        sr__gltf_warn(d, "%s/mode: points and lines (mode %ld) are not drawn", ptr, mode);
        return SR_OK;
    }
    char aptr[GLTF_PTR];
    sr__json_pointer(aptr, sizeof aptr, "%s/attributes", ptr);
    if (!json_object_get(attrs, "POSITION")) {
        sr__gltf_warn(d, "%s: no POSITION, not drawn", aptr);
        return SR_OK;
    }
    gltf_accessor_info info;
    float *pos, *nrm, *tan, *uv0, *uv1, *col;
    if ((r = attribute(d, attrs, aptr, "POSITION", 1u << 3, (size_t)-1, &info, &pos)) != SR_OK) {
        return r;
    }
    size_t n = info.count;
    if ((r = attribute(d, attrs, aptr, "NORMAL", 1u << 3, n, &info, &nrm)) != SR_OK ||
        (r = attribute(d, attrs, aptr, "TANGENT", 1u << 4, n, &info, &tan)) != SR_OK ||
        (r = attribute(d, attrs, aptr, "TEXCOORD_0", 1u << 2, n, &info, &uv0)) != SR_OK ||
        (r = attribute(d, attrs, aptr, "TEXCOORD_1", 1u << 2, n, &info, &uv1)) != SR_OK ||
        (r = attribute(d, attrs, aptr, "COLOR_0", 1u << 3 | 1u << 4, n, &info, &col)) != SR_OK) {
        return r;
    }
    if (col && info.components == 3) {
        float *rgba = sr__scene_alloc(d->scene, n * 4 * sizeof *rgba);
        if (!rgba) {
            return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", aptr);
        }
        for (size_t i = 0; i < n; i++) {
            memcpy(rgba + 4 * i, col + 3 * i, 3 * sizeof *col);
            rgba[4 * i + 3] = 1;
        }
        col = rgba;
    }
    /* Skinning attributes are read only where a skin may use them, so
     * that a file without skins costs nothing more. */
    if ((r = sr__gltf_read_targets(d, prim, ptr, n, pose)) != SR_OK ||
        (json_array_size(json_object_get(d->root, "skins")) > 0 &&
         (r = sr__gltf_read_influences(d, attrs, aptr, n, pose)) != SR_OK)) {
        return r;
    }
    check_texcoords(d, aptr, p->material, uv0 != NULL, uv1 != NULL);
    flip_v(uv0, n);
    flip_v(uv1, n);
    uint32_t *idx = NULL;
    size_t count = n;
    if (draco_corners) {
        count = draco_corner_count;
        idx = malloc(count * sizeof *idx + 1);
        if (!idx) {
            return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
        }
        memcpy(idx, draco_corners, count * sizeof *idx);
    } else if (indices >= 0) {
        char iptr[GLTF_PTR];
        sr__json_pointer(iptr, sizeof iptr, "%s/indices", ptr);
        if ((r = sr__gltf_read_indices(d, indices, iptr, &info, &idx)) != SR_OK) {
            return r;
        }
        count = info.count;
    }
    r = triangles_of(d, ptr, mode, idx, count, n, p);
    free(idx);
    if (r != SR_OK) {
        return r;
    }
    p->vertex_count = n;
    p->positions = pos;
    p->normals = nrm;
    p->tangents = tan;
    p->texcoords0 = uv0;
    p->texcoords1 = uv1;
    p->colors = col;
    return SR_OK;
}

/* A primitive's arrays into p: a KHR_draco_mesh_compression one's from
 * its decoded stream (gltf_draco.c), held while its accessors are read. */
static sr_result read_primitive(gltf_doc *d, const json_t *prim, const char *ptr,
                                sr_scene_primitive *p, gltf_pose_source *pose)
{
    json_t *draco = sr__gltf_extension(prim, "KHR_draco_mesh_compression");
    const uint32_t *corners = NULL;
    size_t corner_count = 0;
    sr_result r = SR_OK;
    if (draco && json_is_object(prim)) {
        r = sr__gltf_draco_begin(d, prim, draco, ptr, &corners, &corner_count);
    }
    if (r == SR_OK) {
        r = read_arrays(d, prim, ptr, corners, corner_count, p, pose);
    }
    sr__gltf_draco_end(d);
    return r;
}

/* Mesh m's primitives, decoded on first use. */
static sr_result mesh_of(gltf_doc *d, gltf_mesh *meshes, long m, const char *use,
                         gltf_mesh **out)
{
    char ptr[GLTF_PTR];
    json_t *mesh, *prims;
    size_t n;
    sr_result r = element(d, "meshes", m, use, &mesh, ptr, sizeof ptr);
    if (r != SR_OK) {
        return r;
    }
    *out = &meshes[m];
    if (meshes[m].decoded) {
        return SR_OK;
    }
    meshes[m].decoded = true;
    if ((r = sr__gltf_array(d, mesh, ptr, "primitives", &prims, &n)) != SR_OK) {
        return r;
    }
    if (n == 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/primitives: missing or empty", ptr);
    }
    if ((r = sr__gltf_check_targets(d, mesh, ptr)) != SR_OK) {
        return r;
    }
    meshes[m].target_count = json_array_size(json_object_get(json_array_get(prims, 0), "targets"));
    meshes[m].prims = sr__scene_alloc(d->scene, n * sizeof *meshes[m].prims);
    meshes[m].pose = calloc(n, sizeof *meshes[m].pose);
    if (!meshes[m].prims || !meshes[m].pose) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
    }
    meshes[m].count = n;
    for (size_t i = 0; i < n; i++) {
        char pptr[GLTF_PTR];
        sr__json_pointer(pptr, sizeof pptr, "%s/primitives/%zu", ptr, i);
        sr_scene_primitive *p = &meshes[m].prims[i];
        p->mesh = (int)m;
        if ((r = read_primitive(d, json_array_get(prims, i), pptr, p, &meshes[m].pose[i])) !=
            SR_OK) {
            return r;
        }
    }
    return SR_OK;
}

/* ---- nodes and cameras --------------------------------------------------- */

void sr__gltf_trs(const float t[3], const float q[4], const float s[3], float m[16])
{
    /* The unit quaternion (x, y, z, w) as a rotation matrix, columns
     * scaled by s; normalized first, as viewers do with rounded files. */
    double x = q[0], y = q[1], z = q[2], w = q[3];
    double len = sqrt(x * x + y * y + z * z + w * w);
    if (len > 0) {
        x /= len, y /= len, z /= len, w /= len;
    } else {
        w = 1;
    }
    double rot[9] = {
        1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
        2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
        2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y),
    };
    for (int c = 0; c < 3; c++) {
        for (int row = 0; row < 3; row++) {
            m[c * 4 + row] = (float)(rot[c * 3 + row] * s[c]);
        }
        m[c * 4 + 3] = 0;
        m[12 + c] = t[c];
    }
    m[15] = 1;
}

/* A node's local matrix: `matrix`, or T * R * S.  glTF allows one of the
 * two (the Khronos validator's NODE_MATRIX_TRS); a node with both is drawn
 * with its matrix, after a warning, as three.js's GLTFLoader and Blender's
 * importer draw it, rather than refusing a file every viewer shows. */
static sr_result local_matrix(gltf_doc *d, const json_t *node, long index, const char *ptr,
                              bool warn, float *m)
{
    static const float identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    memcpy(m, identity, sizeof identity);
    sr_result r;
    if (json_object_get(node, "matrix")) {
        static const char *const trs[] = { "translation", "rotation", "scale" };
        for (int i = 0; warn && i < 3; i++) {
            if (json_object_get(node, trs[i])) {
                sr__gltf_warn(d, "%s: both matrix and %s (glTF allows one): the matrix is used",
                              ptr, trs[i]);
                break;
            }
        }
        r = sr__gltf_numbers(d, node, ptr, "matrix", 16, m);
        if (r == SR_OK && !sr__gltf_posing_node(d, index, m, NULL, NULL, NULL)) {
            r = sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
        }
        return r;
    }
    float t[3] = { 0, 0, 0 }, q[4] = { 0, 0, 0, 1 }, s[3] = { 1, 1, 1 };
    if ((r = sr__gltf_numbers(d, node, ptr, "translation", 3, t)) != SR_OK ||
        (r = sr__gltf_numbers(d, node, ptr, "rotation", 4, q)) != SR_OK ||
        (r = sr__gltf_numbers(d, node, ptr, "scale", 3, s)) != SR_OK) {
        return r;
    }
    if (!sr__gltf_posing_node(d, index, NULL, t, q, s)) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
    }
    /* The animation's values replace the node's own (gltf_animation.c
     * refused it for a node with a matrix). */
    const gltf_node_pose *pose = d->pose ? &d->pose[index] : NULL;
    if (pose && (pose->animated & GLTF_POSE_TRANSLATION)) {
        memcpy(t, pose->translation, sizeof t);
    }
    if (pose && (pose->animated & GLTF_POSE_ROTATION)) {
        memcpy(q, pose->rotation, sizeof q);
    }
    if (pose && (pose->animated & GLTF_POSE_SCALE)) {
        memcpy(s, pose->scale, sizeof s);
    }
    sr__gltf_trs(t, q, s, m);
    return SR_OK;
}

bool sr__gltf_mirrors(const float world[16])
{
    const float *w = world;
    double det = (double)w[0] * ((double)w[5] * w[10] - (double)w[9] * w[6]) -
                 (double)w[4] * ((double)w[1] * w[10] - (double)w[9] * w[2]) +
                 (double)w[8] * ((double)w[1] * w[6] - (double)w[5] * w[2]);
    return det < 0;
}

sr_result sr__gltf_node_world(gltf_doc *d, long node, float world[16])
{
    static const float identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    size_t n = d->node_count;
    if (!d->node_parent || node < 0 || (size_t)node >= n) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "/nodes: node %ld does not exist", node);
    }
    if (!d->node_worlds) {
        d->node_worlds = malloc(n * 16 * sizeof *d->node_worlds);
        d->node_world_known = calloc(n, 1);
        d->node_chain = malloc(n * sizeof *d->node_chain);
        if (!d->node_worlds || !d->node_world_known || !d->node_chain) {
            return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "/nodes: out of memory");
        }
    }
    /* The path up to a known world or a root (node_parents ruled out
     * cycles), then down it, each world made once. */
    size_t depth = 0;
    for (long v = node; v >= 0 && !d->node_world_known[v]; v = d->node_parent[v]) {
        d->node_chain[depth++] = v;
    }
    json_t *nodes = json_object_get(d->root, "nodes");
    while (depth > 0) {
        long v = d->node_chain[--depth], up = d->node_parent[v];
        char ptr[GLTF_PTR];
        float local[16];
        sr__json_pointer(ptr, sizeof ptr, "/nodes/%ld", v);
        sr_result r = local_matrix(d, json_array_get(nodes, (size_t)v), v, ptr, false, local);
        if (r != SR_OK) {
            return r;
        }
        sr__mat4_mul(up >= 0 ? d->node_worlds + 16 * up : identity, local,
                     d->node_worlds + 16 * v);
        d->node_world_known[v] = 1;
    }
    memcpy(world, d->node_worlds + 16 * node, 16 * sizeof *world);
    return SR_OK;
}

static sr_result read_camera(gltf_doc *d, long index, const char *use, sr_scene_camera *c)
{
    char ptr[GLTF_PTR], sub[GLTF_PTR];
    json_t *cam, *p;
    sr_result r = element(d, "cameras", index, use, &cam, ptr, sizeof ptr);
    if (r != SR_OK) {
        return r;
    }
    json_t *type = json_object_get(cam, "type");
    const char *t = json_is_string(type) ? json_string_value(type) : "";
    bool persp = strcmp(t, "perspective") == 0;
    if (!persp && strcmp(t, "orthographic") != 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/type: not perspective or orthographic", ptr);
    }
    c->type = persp ? SR_SCENE_CAMERA_PERSPECTIVE : SR_SCENE_CAMERA_ORTHOGRAPHIC;
    c->camera = (int)index;
    if ((r = sr__gltf_object(d, cam, ptr, t, &p)) != SR_OK) {
        return r;
    }
    sr__json_pointer(sub, sizeof sub, "%s/%s", ptr, t);
    if (!p) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: missing", sub);
    }
    c->znear = c->zfar = c->yfov = c->aspect = c->xmag = c->ymag = -1;
    if ((r = sr__gltf_number(d, p, sub, "znear", &c->znear)) != SR_OK ||
        (r = sr__gltf_number(d, p, sub, "zfar", &c->zfar)) != SR_OK ||
        (r = sr__gltf_number(d, p, sub, "yfov", &c->yfov)) != SR_OK ||
        (r = sr__gltf_number(d, p, sub, "aspectRatio", &c->aspect)) != SR_OK ||
        (r = sr__gltf_number(d, p, sub, "xmag", &c->xmag)) != SR_OK ||
        (r = sr__gltf_number(d, p, sub, "ymag", &c->ymag)) != SR_OK) {
        return r;
    }
    const char *bad = NULL;
    if (persp) {
        bad = c->yfov <= 0 || c->yfov >= 3.14159f ? "yfov"
            : c->znear <= 0                      ? "znear"
            : c->zfar != -1 && c->zfar <= c->znear ? "zfar"
            : c->aspect != -1 && c->aspect <= 0  ? "aspectRatio" : NULL;
        c->aspect = fmaxf(c->aspect, 0);
        c->zfar = fmaxf(c->zfar, 0);
        c->xmag = c->ymag = 0;
    } else {
        bad = c->xmag == 0 || c->xmag == -1  ? "xmag"
            : c->ymag == 0 || c->ymag == -1  ? "ymag"
            : c->znear < 0                   ? "znear"
            : c->zfar <= c->znear            ? "zfar" : NULL;
        c->yfov = c->aspect = 0;
    }
    if (bad) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "%s/%s: missing or out of range", sub, bad);
    }
    return SR_OK;
}

/* Each node's parent (-1 for roots), checking that the nodes make a
 * forest: no node a child twice, no cycle. */
static sr_result node_parents(gltf_doc *d, const json_t *nodes, size_t n, long *parent)
{
    sr_result r;
    for (size_t i = 0; i < n; i++) {
        parent[i] = -1;
    }
    for (size_t i = 0; i < n; i++) {
        char ptr[GLTF_PTR];
        json_t *node = json_array_get(nodes, i), *children;
        size_t k;
        sr__json_pointer(ptr, sizeof ptr, "/nodes/%zu", i);
        if (!json_is_object(node)) {
            return sr__gltf_fail(d, SR_BAD_FORMAT, "%s: not an object", ptr);
        }
        if ((r = sr__gltf_array(d, node, ptr, "children", &children, &k)) != SR_OK) {
            return r;
        }
        for (size_t c = 0; c < k; c++) {
            json_t *v = json_array_get(children, c);
            json_int_t ch = json_is_integer(v) ? json_integer_value(v) : -1;
            if (ch < 0 || (size_t)ch >= n) {
                return sr__gltf_fail(d, SR_BAD_FORMAT,
                                     "%s/children/%zu: not a node index below %zu", ptr, c, n);
            }
            if (parent[ch] != -1 || (size_t)ch == i) {
                return sr__gltf_fail(d, SR_BAD_FORMAT,
                                     "%s/children/%zu: node %lld already has a parent (node %ld)",
                                     ptr, c, (long long)ch, (size_t)ch == i ? (long)i : parent[ch]);
            }
            parent[ch] = (long)i;
        }
    }
    /* With one parent each, a cycle is a parent chain that comes back:
     * walk each chain once, marking nodes (1: on this walk, 2: leads to a
     * root). */
    unsigned char *mark = calloc(n ? n : 1, 1);
    if (!mark) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "/nodes: out of memory");
    }
    r = SR_OK;
    for (size_t i = 0; i < n && r == SR_OK; i++) {
        long v = (long)i;
        while (v >= 0 && mark[v] == 0) {
            mark[v] = 1;
            v = parent[v];
        }
        if (v >= 0 && mark[v] == 1) {
            r = sr__gltf_fail(d, SR_BAD_FORMAT,
                              "/nodes/%ld/children: node %ld is its own ancestor (a cycle)",
                              parent[v], v);
        }
        for (long u = (long)i; u >= 0 && mark[u] == 1; u = parent[u]) {
            mark[u] = 2;
        }
    }
    free(mark);
    return r;
}

/* Work for the depth-first walk: a node and its parent's world matrix. */
typedef struct walk_item {
    long node;
    float parent[16];
} walk_item;

/* Primitive i of mesh m as node `node_index` poses it: moved by the
 * node's morph weights (n of them), then skinned by its skin (-1: none). */
static sr_result pose_primitive(gltf_doc *d, const gltf_mesh *m, size_t i, long node_index,
                                const char *ptr, long mesh, long skin, const float *weights,
                                sr_scene_primitive *p)
{
    char pptr[GLTF_PTR], use[GLTF_PTR];
    sr__json_pointer(pptr, sizeof pptr, "/meshes/%ld/primitives/%zu", mesh, i);
    sr_result r = SR_OK;
    if (m->pose[i].target_count > 0) {
        r = sr__gltf_morph(d, &m->pose[i], weights, ptr, p);
    }
    if (r == SR_OK && skin >= 0) {
        sr__json_pointer(use, sizeof use, "/nodes/%ld/skin", node_index);
        r = sr__gltf_skin(d, skin, use, &m->pose[i], pptr, p);
    }
    return r;
}

/* Whether `copies` more instances of draws, vertices and triangles fit the
 * scene's limits (SR_SCENE_MAX_*), checked before any is made. */
static sr_result check_copies(gltf_doc *d, const char *eptr, size_t copies, size_t draws,
                              size_t vertices, size_t triangles)
{
    size_t all_draws = 0, all_vertices = 0, all_triangles = 0;
    const char *what = NULL;
    size_t limit = 0;
    if (!sr__mul_ok(copies, draws, &all_draws) ||
        all_draws > SR_SCENE_MAX_DRAWS - d->scene->primitive_count) {
        what = "primitives to draw", limit = SR_SCENE_MAX_DRAWS;
    } else if (!sr__mul_ok(copies, vertices, &all_vertices) ||
               all_vertices > SR_SCENE_MAX_DRAWN_VERTICES - d->drawn_vertices) {
        what = "vertices to draw in all", limit = SR_SCENE_MAX_DRAWN_VERTICES;
    } else if (!sr__mul_ok(copies, triangles, &all_triangles) ||
               all_triangles > SR_SCENE_MAX_DRAWN_TRIANGLES - d->drawn_triangles) {
        what = "triangles to draw in all", limit = SR_SCENE_MAX_DRAWN_TRIANGLES;
    }
    if (what) {
        return sr__gltf_fail(d, SR_TOO_LARGE,
                             "%s: %zu more instances of %zu primitives (%zu vertices, %zu "
                             "triangles): more than %zu %s",
                             eptr, copies, draws, vertices, triangles, limit, what);
    }
    d->drawn_vertices += all_vertices;
    d->drawn_triangles += all_triangles;
    return SR_OK;
}

/* Mesh `mesh` drawn by node `node_index` at `world`: one draw per
 * primitive, or with EXT_mesh_gpu_instancing (instances: instance_count
 * matrices) one per primitive and instance, primitive-major.  Each
 * primitive is posed once per node (morph weights and skins are the
 * node's); its instances share the posed arrays. */
static sr_result add_draws(gltf_doc *d, gltf_mesh *meshes, long node_index, const char *ptr,
                           long mesh, long skin, const float *world, const float *instances,
                           size_t instance_count)
{
    char use[GLTF_PTR];
    sr__json_pointer(use, sizeof use, "%s/mesh", ptr);
    gltf_mesh *m;
    sr_result r = mesh_of(d, meshes, mesh, use, &m);
    if (r != SR_OK) {
        return r;
    }
    /* Plain instances share the mesh's arrays; posed ones get their own. */
    float *weights = NULL, *rest = NULL;
    if (m->target_count > 0) {
        weights = malloc(m->target_count * sizeof *weights);
        rest = d->posing ? malloc(m->target_count * sizeof *rest) : NULL;
        r = weights && (rest || !d->posing)
                ? sr__gltf_node_weights(d, node_index, mesh, weights, m->target_count)
                : sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
        if (r == SR_OK && rest) {
            r = sr__gltf_node_rest_weights(d, node_index, mesh, rest, m->target_count);
        }
    }
    size_t first = d->scene->primitive_count;
    for (size_t i = 0; i < m->count && r == SR_OK; i++) {
        const sr_scene_primitive *g = &m->prims[i];
        if (!g->positions || g->triangle_count == 0) {
            continue;
        }
        if (d->scene->primitive_count >= SR_SCENE_MAX_DRAWS) {
            r = sr__gltf_fail(d, SR_TOO_LARGE, "%s: more than %zu primitives to draw", ptr,
                              SR_SCENE_MAX_DRAWS);
            break;
        }
        /* Instances are cheap to list but each costs its vertices to
         * bound and to draw. */
        d->drawn_vertices += g->vertex_count;
        if (d->drawn_vertices > SR_SCENE_MAX_DRAWN_VERTICES) {
            r = sr__gltf_fail(d, SR_TOO_LARGE, "%s: more than %zu vertices to draw in all", ptr,
                              SR_SCENE_MAX_DRAWN_VERTICES);
            break;
        }
        d->drawn_triangles += g->triangle_count;
        if (d->drawn_triangles > SR_SCENE_MAX_DRAWN_TRIANGLES) {
            r = sr__gltf_fail(d, SR_TOO_LARGE, "%s: more than %zu triangles to draw in all", ptr,
                              SR_SCENE_MAX_DRAWN_TRIANGLES);
            break;
        }
        sr_scene_primitive *p = sr__scene_grow(d->scene, (void **)&d->scene->primitives,
                                               &d->scene->primitive_count, sizeof *p, 1);
        if (!p) {
            r = sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
            break;
        }
        *p = *g;
        memcpy(p->world, world, sizeof p->world);
        p->node = (int)node_index;
        p->mirrored = sr__gltf_mirrors(world);
        r = pose_primitive(d, m, i, node_index, ptr, mesh, skin, weights, p);
        if (r == SR_OK && d->posing && (skin >= 0 || m->target_count > 0) &&
            !sr__gltf_posing_draw(d, d->scene->primitive_count - 1, skin, g, &m->pose[i],
                                  rest)) {
            r = sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
        }
    }
    free(weights);
    free(rest);
    size_t made = d->scene->primitive_count - first;
    if (r != SR_OK || !instances || made == 0) {
        return r;
    }
    /* The draws just made are the pattern, posed once.  Each primitive's
     * instances follow one another (primitive-major, as one instanced
     * draw call would list them), so that a renderer finds them as one
     * run of one material.  Made from the last slot back: a pattern draw
     * is read before its slot is taken, and its world (the node's, or
     * the identity of a skinned draw) stays the base until then. */
    char eptr[GLTF_PTR];
    sr__json_pointer(eptr, sizeof eptr, "%s/extensions/EXT_mesh_gpu_instancing", ptr);
    size_t vertices = 0, triangles = 0;
    for (size_t j = 0; j < made; j++) {
        vertices += d->scene->primitives[first + j].vertex_count;
        triangles += d->scene->primitives[first + j].triangle_count;
    }
    if ((r = check_copies(d, eptr, instance_count - 1, made, vertices, triangles)) != SR_OK) {
        return r;
    }
    if (instance_count > 1 &&
        !sr__scene_grow(d->scene, (void **)&d->scene->primitives, &d->scene->primitive_count,
                        sizeof *d->scene->primitives, made * (instance_count - 1))) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", eptr);
    }
    sr_scene_primitive *pattern = d->scene->primitives + first;
    for (size_t j = made; j-- > 0;) {
        const sr_scene_primitive g = pattern[j];
        for (size_t k = instance_count; k-- > 0;) {
            sr_scene_primitive *p = pattern + j * instance_count + k;
            const float *inst = instances + 16 * k;
            *p = g;
            /* A skinned pattern's mirror comes from its joints, not its
             * (identity) world: the instance's own mirror turns it. */
            p->mirrored = g.mirrored != sr__gltf_mirrors(inst);
            sr__mat4_mul(g.world, inst, p->world);
        }
    }
    d->scene->instanced_draws += made * instance_count;
    d->scene->instanced_nodes++;
    if (!sr__gltf_posing_instances(d, first, made, instance_count, instances)) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", eptr);
    }
    return SR_OK;
}

/* The scene's node trees, depth first in the order the file lists them. */
static sr_result walk_nodes(gltf_doc *d, const json_t *roots, const char *roots_ptr,
                            const long *parent, size_t node_count)
{
    json_t *nodes = json_object_get(d->root, "nodes");
    size_t mesh_count = json_array_size(json_object_get(d->root, "meshes"));
    gltf_mesh *meshes = calloc(mesh_count ? mesh_count : 1, sizeof *meshes);
    walk_item *stack = malloc((node_count ? node_count : 1) * sizeof *stack);
    unsigned char *seen = calloc(node_count ? node_count : 1, 1);
    if (!meshes || !stack || !seen) {
        free(meshes);
        free(stack);
        free(seen);
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "/nodes: out of memory");
    }
    static const float identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    sr_result r = SR_OK;
    size_t nroots = json_array_size(roots);
    /* Roots pushed last first, so the first is drawn first. */
    size_t top = 0;
    for (size_t i = nroots; i-- > 0 && r == SR_OK;) {
        json_t *v = json_array_get(roots, i);
        json_int_t n = json_is_integer(v) ? json_integer_value(v) : -1;
        if (n < 0 || (size_t)n >= node_count) {
            r = sr__gltf_fail(d, SR_BAD_FORMAT, "%s/%zu: not a node index below %zu", roots_ptr,
                              i, node_count);
        } else if (parent[n] != -1) {
            r = sr__gltf_fail(d, SR_BAD_FORMAT,
                              "%s/%zu: node %lld is not a root (node %ld's child)", roots_ptr, i,
                              (long long)n, parent[n]);
        } else if (seen[n]) {
            r = sr__gltf_fail(d, SR_BAD_FORMAT, "%s/%zu: node %lld is listed twice", roots_ptr, i,
                              (long long)n);
        } else {
            seen[n] = 1;
            stack[top].node = (long)n;
            memcpy(stack[top].parent, identity, sizeof identity);
            top++;
        }
    }
    while (r == SR_OK && top > 0) {
        walk_item it = stack[--top];
        char ptr[GLTF_PTR];
        sr__json_pointer(ptr, sizeof ptr, "/nodes/%ld", it.node);
        json_t *node = json_array_get(nodes, (size_t)it.node), *children;
        float local[16], world[16];
        long mesh = -1, camera = -1, skin = -1;
        size_t k;
        if ((r = local_matrix(d, node, it.node, ptr, true, local)) != SR_OK ||
            (r = sr__gltf_index(d, node, ptr, "mesh", (size_t)-1 / 2, false, &mesh)) != SR_OK ||
            (r = sr__gltf_index(d, node, ptr, "skin", (size_t)-1 / 2, false, &skin)) != SR_OK ||
            (r = sr__gltf_index(d, node, ptr, "camera", (size_t)-1 / 2, false, &camera)) !=
                SR_OK) {
            break;
        }
        sr__mat4_mul(it.parent, local, world);
        /* The specification's node.skin: "When defined, mesh MUST also be
         * defined"; silence would hide a file that lost its mesh. */
        if (skin >= 0 && mesh < 0) {
            r = sr__gltf_fail(d, SR_BAD_FORMAT, "%s/skin: skin %ld on a node without a mesh", ptr,
                              skin);
            break;
        }
        float *instances = NULL;
        size_t instance_count = 0;
        if ((r = sr__gltf_read_instances(d, node, ptr, mesh,
                                         SR_SCENE_MAX_DRAWS - d->scene->primitive_count,
                                         &instances, &instance_count)) != SR_OK) {
            break;
        }
        if (mesh >= 0) {
            r = add_draws(d, meshes, it.node, ptr, mesh, skin, world, instances, instance_count);
        }
        free(instances);
        if (r != SR_OK) {
            break;
        }
        if ((r = sr__gltf_place_light(d, node, ptr, it.node, world)) != SR_OK) {
            break;
        }
        if (camera >= 0) {
            sr_scene_camera *c = sr__scene_grow(d->scene, (void **)&d->scene->cameras,
                                                &d->scene->camera_count, sizeof *c, 1);
            char use[GLTF_PTR];
            sr__json_pointer(use, sizeof use, "%s/camera", ptr);
            if (!c) {
                r = sr__gltf_fail(d, SR_OUT_OF_MEMORY, "%s: out of memory", ptr);
                break;
            }
            if ((r = read_camera(d, camera, use, c)) != SR_OK) {
                break;
            }
            memcpy(c->world, world, sizeof world);
            c->node = (int)it.node;
        }
        /* node_parents checked the children; each node is pushed once. */
        sr__gltf_array(d, node, ptr, "children", &children, &k);
        for (size_t c = k; c-- > 0;) {
            stack[top].node = (long)json_integer_value(json_array_get(children, c));
            memcpy(stack[top].parent, world, sizeof world);
            top++;
        }
    }
    for (size_t m = 0; m < mesh_count; m++) {
        /* sr_scene_pose poses the draws again from the sources. */
        if (d->posing && meshes[m].pose) {
            if (!sr__gltf_posing_sources(d, meshes[m].pose, meshes[m].count) && r == SR_OK) {
                r = sr__gltf_fail(d, SR_OUT_OF_MEMORY, "/meshes/%zu: out of memory", m);
            }
            continue;
        }
        for (size_t i = 0; meshes[m].pose && i < meshes[m].count; i++) {
            sr__gltf_pose_free(&meshes[m].pose[i]);
        }
        free(meshes[m].pose);
    }
    free(meshes);
    free(stack);
    free(seen);
    return r;
}

/* The nodes of the scene to draw: `scene`, else scene 0, else (a file
 * with no scenes) every root node. */
static sr_result read_nodes(gltf_doc *d)
{
    json_t *nodes, *scenes, *roots = NULL;
    size_t node_count, scene_count;
    sr_result r;
    if ((r = sr__gltf_array(d, d->root, "", "nodes", &nodes, &node_count)) != SR_OK ||
        (r = sr__gltf_array(d, d->root, "", "scenes", &scenes, &scene_count)) != SR_OK) {
        return r;
    }
    long scene = scene_count > 0 ? 0 : -1;
    if ((r = sr__gltf_index(d, d->root, "", "scene", scene_count ? scene_count : 1, false,
                            &scene)) != SR_OK) {
        return r;
    }
    if (json_object_get(d->root, "scene") && scene_count == 0) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "/scene: given, but there are no scenes");
    }
    long *parent = malloc((node_count ? node_count : 1) * sizeof *parent);
    if (!parent) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "/nodes: out of memory");
    }
    r = node_parents(d, nodes, node_count, parent);
    char rptr[GLTF_PTR] = "/nodes";
    json_t *all = NULL;
    if (r == SR_OK && scene >= 0) {
        json_t *s = json_array_get(scenes, (size_t)scene);
        sr__json_pointer(rptr, sizeof rptr, "/scenes/%ld", scene);
        size_t n;
        if (!json_is_object(s)) {
            r = sr__gltf_fail(d, SR_BAD_FORMAT, "%s: not an object", rptr);
        } else {
            r = sr__gltf_array(d, s, rptr, "nodes", &roots, &n);
            sr__json_pointer(rptr, sizeof rptr, "/scenes/%ld/nodes", scene);
        }
    } else if (r == SR_OK) {
        all = roots = json_array();
        for (size_t i = 0; roots && i < node_count; i++) {
            if (parent[i] == -1) {
                json_array_append_new(roots, json_integer((json_int_t)i));
            }
        }
    }
    if (r == SR_OK) {
        d->node_count = node_count;
        d->node_parent = parent;
        r = walk_nodes(d, roots, rptr, parent, node_count);   /* NULL: no roots */
    }
    if (r == SR_OK) {
        r = sr__gltf_pointers_finish(d, parent, node_count);
    }
    json_decref(all);
    sr__gltf_skins_free(d);
    free(d->node_worlds);
    free(d->node_world_known);
    free(d->node_chain);
    d->node_worlds = NULL;
    d->node_world_known = NULL;
    d->node_chain = NULL;
    d->node_parent = NULL;
    free(parent);
    return r;
}

/* ---- the document ------------------------------------------------------- */

static const char *supported_extensions[] = {
    "KHR_mesh_quantization",
    "KHR_texture_transform",
    "KHR_materials_emissive_strength",
    "KHR_materials_unlit",
    "KHR_materials_ior",
    "KHR_materials_specular",
    "KHR_materials_clearcoat",
    "KHR_materials_sheen",
    "KHR_materials_anisotropy",
    "KHR_materials_iridescence",
    "KHR_materials_transmission",
    "KHR_materials_volume",
    "KHR_materials_dispersion",
    "KHR_materials_diffuse_transmission",
    "KHR_materials_pbrSpecularGlossiness",
    "KHR_lights_punctual",
    "KHR_materials_variants",
    "EXT_mesh_gpu_instancing",
    "KHR_animation_pointer",
    "KHR_node_visibility",
    "KHR_xmp_json_ld",
};

/* Extensions read when softrast was built with their decoder. */
static const struct {
    const char *name, *library;
    bool (*have)(void);
} decoded_extensions[] = {
    { "EXT_meshopt_compression", "meshoptimizer", sr__gltf_have_meshopt },
    { "KHR_draco_mesh_compression", "libdraco", sr__gltf_have_draco },
    { "EXT_texture_webp", "libwebp", sr__io_have_webp },
};

/* Whether extension `name` is read; when it is not for want of a
 * library, *library names it (else NULL). */
static bool extension_read(const char *name, const char **library)
{
    *library = NULL;
    for (size_t k = 0; name && k < sizeof supported_extensions / sizeof *supported_extensions;
         k++) {
        if (strcmp(name, supported_extensions[k]) == 0) {
            return true;
        }
    }
    for (size_t k = 0; name && k < sizeof decoded_extensions / sizeof *decoded_extensions; k++) {
        if (strcmp(name, decoded_extensions[k].name) == 0) {
            *library = decoded_extensions[k].have() ? NULL : decoded_extensions[k].library;
            return !*library;
        }
    }
    return false;
}

static sr_result check_asset(gltf_doc *d)
{
    json_t *asset;
    sr_result r = sr__gltf_object(d, d->root, "", "asset", &asset);
    if (r != SR_OK) {
        return r;
    }
    json_t *version = json_object_get(asset, "version");
    if (!asset || !json_is_string(version)) {
        return sr__gltf_fail(d, SR_BAD_FORMAT, "/asset/version: missing");
    }
    if (strncmp(json_string_value(version), "2.", 2) != 0) {
        return sr__gltf_fail(d, SR_UNSUPPORTED, "/asset/version: \"%.20s\" is not glTF 2.x",
                             json_string_value(version));
    }
    json_t *min = json_object_get(asset, "minVersion");
    if (json_is_string(min) && strcmp(json_string_value(min), "2.0") != 0) {
        return sr__gltf_fail(d, SR_UNSUPPORTED, "/asset/minVersion: \"%.20s\" is newer than 2.0",
                             json_string_value(min));
    }
    json_t *req;
    size_t n;
    if ((r = sr__gltf_array(d, d->root, "", "extensionsRequired", &req, &n)) != SR_OK) {
        return r;
    }
    for (size_t i = 0; i < n; i++) {
        const char *name = json_string_value(json_array_get(req, i));
        const char *library;
        if (!extension_read(name, &library)) {
            return sr__gltf_fail(d, SR_UNSUPPORTED,
                                 "/extensionsRequired/%zu: extension %.64s is not supported%s%s%s",
                                 i, name ? name : "(not a string)",
                                 library ? " (softrast was built without " : "",
                                 library ? library : "", library ? ")" : "");
        }
    }
    return SR_OK;
}

/* Appends ", item" (or "item" first) to list while it fits; once one does
 * not, ", ..." ends the list. */
static void list_add(char *list, size_t cap, bool *full, const char *item)
{
    size_t at = strlen(list);
    if (*full) {
        return;
    }
    if (at + strlen(item) + 8 >= cap) {
        snprintf(list + at, cap - at, ", ...");
        *full = true;
        return;
    }
    snprintf(list + at, cap - at, "%s%s", at ? ", " : "", item);
}

/* One warning naming what the file holds that the scene leaves out
 * (extensions other than the supported ones), so that a model drawn
 * without its lights, say, says why. */
static void warn_unread(gltf_doc *d)
{
    char list[400] = "", item[GLTF_PTR + 80];
    bool full = false;
    json_t *used = json_object_get(d->root, "extensionsUsed");
    for (size_t i = 0; i < json_array_size(used); i++) {
        const char *name = json_string_value(json_array_get(used, i));
        const char *library;
        if (name && !extension_read(name, &library)) {
            snprintf(item, sizeof item, "/extensionsUsed/%zu (%.64s)", i, name);
            list_add(list, sizeof list, &full, item);
        }
    }
    if (list[0]) {
        sr__gltf_warn(d, "not read, the scene is drawn without them: %s", list);
    }
}

/* Whether a whole chunk (header and data) starts at byte at. */
static bool chunk_fits(const uint8_t *data, size_t length, size_t at)
{
    return at + 8 <= length && sr__le32(data + at) <= length - at - 8;
}

/* Where the chunk after the one at byte at (of clen bytes) starts. The
 * format pads chunks to 4 bytes and counts the padding in the length; some
 * writers skip the padding, and other readers (three.js, the Khronos
 * validator) read the next chunk right after the declared length, so that
 * comes first. A writer that padded without counting the padding leaves the
 * next chunk at the 4-byte boundary instead: taken when only that one fits. */
static size_t next_chunk(const uint8_t *data, size_t length, size_t at, uint32_t clen)
{
    size_t next = at + 8 + (size_t)clen, padded = (next + 3) & ~(size_t)3;
    if (padded != next && next + 8 <= length && !chunk_fits(data, length, next) &&
        chunk_fits(data, length, padded)) {
        return padded;
    }
    return next;
}

/* The JSON and BIN chunks of a GLB. */
static sr_result read_glb(gltf_doc *d, const uint8_t *data, size_t size, const char **json,
                          size_t *json_size)
{
    if (size < 20) {
        return sr__io_fail(d->err, SR_BAD_FORMAT, d->name, 0, "GLB header cut short");
    }
    uint32_t version = sr__le32(data + 4), length = sr__le32(data + 8);
    if (version != 2) {
        return sr__io_fail(d->err, SR_UNSUPPORTED, d->name, 0, "GLB version %u, not 2", version);
    }
    if (length > size || length < 20) {
        return sr__io_fail_at(d->err, SR_BAD_FORMAT, d->name, 8,
                              "GLB length %u, but the file has %zu bytes", length, size);
    }
    *json = NULL;
    uint32_t json_len = 0;
    size_t after_json = 0;
    for (size_t at = 12; at + 8 <= length;) {
        uint32_t clen = sr__le32(data + at), type = sr__le32(data + at + 4);
        if (clen > length - at - 8) {
            /* After a JSON chunk of odd length the "chunk" read is most likely
             * JSON text or padding: its length is the cause to name. */
            if (at == after_json && json_len % 4 != 0) {
                return sr__io_fail_at(d->err, SR_BAD_FORMAT, d->name, 12,
                                      "JSON chunk length %u (not a multiple of 4) does not end "
                                      "where the next chunk starts",
                                      json_len);
            }
            return sr__io_fail_at(d->err, SR_BAD_FORMAT, d->name, at,
                                  "chunk of %u bytes runs past the end", clen);
        }
        if (at == 12) {
            if (type != 0x4E4F534Au) {
                return sr__io_fail_at(d->err, SR_BAD_FORMAT, d->name, at + 4,
                                      "the first chunk is not JSON");
            }
            *json = (const char *)data + at + 8;
            *json_size = clen;
            json_len = clen;
        } else if (type == 0x004E4942u && !d->bin) {
            d->bin = data + at + 8;
            d->bin_size = clen;
        }
        at = next_chunk(data, length, at, clen);
        after_json = after_json ? after_json : at;
    }
    if (!*json) {
        return sr__io_fail_at(d->err, SR_BAD_FORMAT, d->name, 12, "no JSON chunk");
    }
    return SR_OK;
}

/* A name ending in .glb promises the binary container. */
static bool is_glb_name(const char *name)
{
    size_t n = name ? strlen(name) : 0;
    return n >= 4 && strcasecmp(name + n - 4, ".glb") == 0;
}

static sr_result read_document(gltf_doc *d, const uint8_t *data, size_t size)
{
    const char *json = (const char *)data;
    size_t json_size = size;
    sr_result r;
    if (size == 0) {
        return sr__io_fail(d->err, SR_BAD_FORMAT, d->name, 0, "file is empty");
    }
    bool glb = size >= 4 && memcmp(data, "glTF", 4) == 0;
    if (glb && (r = read_glb(d, data, size, &json, &json_size)) != SR_OK) {
        return r;
    }
    /* Content decides, so a JSON document named .glb still reads; anything
     * else named .glb is not "invalid JSON" to the user but not a GLB. */
    size_t first = 0;
    while (first < size && (data[first] == ' ' || data[first] == '\t' || data[first] == '\r' ||
                            data[first] == '\n')) {
        first++;
    }
    if (!glb && is_glb_name(d->name) && (first == size || data[first] != '{')) {
        return sr__io_fail_at(d->err, SR_BAD_FORMAT, d->name, 0,
                              "not a GLB file (it does not start with 'glTF')");
    }
    json_error_t jerr;
    d->root = json_loadb(json, json_size, JSON_REJECT_DUPLICATES, &jerr);
    if (!d->root) {
        return sr__io_fail(d->err, SR_BAD_FORMAT, d->name, jerr.line > 0 ? jerr.line : 0,
                           "invalid JSON: %s (column %d)", jerr.text, jerr.column);
    }
    if (!json_is_object(d->root)) {
        return sr__io_fail(d->err, SR_BAD_FORMAT, d->name, 0,
                           "the document is not a JSON object");
    }
    if ((r = check_asset(d)) != SR_OK || (r = sr__gltf_read_metadata(d)) != SR_OK) {
        return r;
    }
    json_t *buffers, *images;
    if ((r = sr__gltf_array(d, d->root, "", "buffers", &buffers, &d->buffer_count)) != SR_OK ||
        (r = sr__gltf_array(d, d->root, "", "images", &images, &d->image_count)) != SR_OK) {
        return r;
    }
    d->buffers = calloc(d->buffer_count ? d->buffer_count : 1, sizeof *d->buffers);
    d->image_textures = calloc(d->image_count ? 2 * d->image_count : 1, sizeof(sr_texture *));
    d->image_sources = d->for_mesh ? calloc(d->image_count ? d->image_count : 1,
                                            sizeof *d->image_sources)
                                   : NULL;
    if (!d->buffers || !d->image_textures || (d->for_mesh && !d->image_sources)) {
        return sr__gltf_fail(d, SR_OUT_OF_MEMORY, "/buffers: out of memory");
    }
    if ((r = sr__gltf_read_materials(d)) != SR_OK || (r = sr__gltf_read_variants(d)) != SR_OK ||
        (r = sr__gltf_read_lights(d)) != SR_OK || (r = sr__gltf_read_animations(d)) != SR_OK ||
        (r = read_nodes(d)) != SR_OK) {
        return r;
    }
    sr__gltf_lights_done(d);
    sr__scene_bounds(d->scene);
    warn_unread(d);
    return sr__gltf_posing_finish(d) ? SR_OK
                                     : sr__gltf_fail(d, SR_OUT_OF_MEMORY, "/animations: out of memory");
}

sr_result sr__parse_gltf(sr_context *ctx, const char *name, const char *dir, const uint8_t *data,
                         size_t size, const sr_load_desc *desc, bool for_mesh, sr_scene **out,
                         sr_io_error *err)
{
    gltf_doc d = { .ctx = ctx, .name = name, .desc = desc, .err = err, .dir = dir,
                   .for_mesh = for_mesh };
    *out = NULL;
    d.input_bytes = size;
    d.elements_left = SR_SCENE_ELEMENTS_BASE;
    if (size < (size_t)-1 / SR_SCENE_ELEMENTS_PER_BYTE / 2) {
        d.elements_left += size * SR_SCENE_ELEMENTS_PER_BYTE;
    }
    d.scene = sr__scene_new();
    sr_result r = d.scene ? read_document(&d, data, size)
                          : sr__io_fail(err, SR_OUT_OF_MEMORY, name, 0, "out of memory");
    for (size_t i = 0; d.buffers && i < d.buffer_count; i++) {
        if (d.buffers[i].from_file) {
            sr__free_file(d.buffers[i].owned, d.buffers[i].owned_size);
        } else {
            free(d.buffers[i].owned);
        }
    }
    free(d.buffers);
    free(d.image_textures);
    free(d.image_sources);
    free(d.lights);
    sr__gltf_meshopt_free(&d);
    sr__gltf_draco_end(&d);
    json_decref(d.root);
    sr__gltf_posing_abandon(&d);
    if (d.applied_own) {
        sr__gltf_anim_free(d.applied_own);
        free(d.applied_own);
    }
    if (r != SR_OK) {
        sr_destroy_scene(ctx, d.scene);
        return r;
    }
    *out = d.scene;
    return SR_OK;
}
