/* draco_decode.cc - io stage: a KHR_draco_mesh_compression stream decoded
 * with libdraco (whose API is C++ only) into the plain arrays of
 * draco_decode.h, for gltf_draco.c.  The library's one C++ file: nothing
 * but C types cross its entry points, and no exception leaves them (an
 * allocation that throws is SR_DRACO_NO_MEMORY).  Any thread, one mesh per
 * caller. */
#include "io/draco_decode.h"

#include <draco/compression/decode.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <new>

struct sr_draco_mesh {
    std::unique_ptr<draco::Mesh> mesh;
};

namespace {

void say(char *why, size_t cap, const char *text)
{
    if (cap > 0) {
        std::snprintf(why, cap, "%s", text);
    }
}

/* Little-endian bytes of v, whatever the host's order. */
template <typename T> void put_le(uint8_t *out, T v)
{
    typename std::conditional<sizeof(T) == 4, uint32_t,
                              typename std::conditional<sizeof(T) == 2, uint16_t, uint8_t>::type>::
        type u;
    static_assert(sizeof u == sizeof v, "one word");
    std::memcpy(&u, &v, sizeof u);
    for (size_t i = 0; i < sizeof u; i++) {
        out[i] = static_cast<uint8_t>(u >> (8 * i));
    }
}

/* The glTF componentType Draco stores as `type`, or 0. */
int gltf_type_of(draco::DataType type)
{
    switch (type) {
    case draco::DT_INT8:    return 5120;
    case draco::DT_UINT8:   return 5121;
    case draco::DT_INT16:   return 5122;
    case draco::DT_UINT16:  return 5123;
    case draco::DT_UINT32:  return 5125;
    case draco::DT_FLOAT32: return 5126;
    default:                return 0;
    }
}

/* Component c of value v of the attribute as a float: a normalized
 * integer mapped as glTF's table maps it (signed ones clamped at -1). */
template <typename T> float component(const draco::PointAttribute &a, draco::AttributeValueIndex v,
                                      int c)
{
    T x;
    std::memcpy(&x, a.GetAddress(v) + static_cast<size_t>(c) * sizeof(T), sizeof x);
    if (std::is_integral<T>::value && a.normalized()) {
        double f = static_cast<double>(x) / static_cast<double>(std::numeric_limits<T>::max());
        return static_cast<float>(std::fmax(f, -1.0));
    }
    return static_cast<float>(x);
}

float component_of(const draco::PointAttribute &a, draco::AttributeValueIndex v, int c)
{
    switch (a.data_type()) {
    case draco::DT_INT8:    return component<int8_t>(a, v, c);
    case draco::DT_UINT8:   return component<uint8_t>(a, v, c);
    case draco::DT_INT16:   return component<int16_t>(a, v, c);
    case draco::DT_UINT16:  return component<uint16_t>(a, v, c);
    case draco::DT_INT32:   return component<int32_t>(a, v, c);
    case draco::DT_UINT32:  return component<uint32_t>(a, v, c);
    case draco::DT_FLOAT32: return component<float>(a, v, c);
    case draco::DT_FLOAT64: return component<double>(a, v, c);
    default:                return std::numeric_limits<float>::quiet_NaN();
    }
}

template <typename T> void copy_raw(const draco::PointAttribute &a, draco::AttributeValueIndex v,
                                    int components, uint8_t *out)
{
    for (int c = 0; c < components; c++) {
        T x;
        std::memcpy(&x, a.GetAddress(v) + static_cast<size_t>(c) * sizeof(T), sizeof x);
        put_le(out + static_cast<size_t>(c) * sizeof(T), x);
    }
}

const char *type_name(draco::DataType type)
{
    static const char *const names[] = { "invalid", "int8",  "uint8",   "int16",
                                         "uint16",  "int32", "uint32",  "int64",
                                         "uint64",  "float32", "float64", "bool" };
    return type >= 0 && type < draco::DT_TYPES_COUNT ? names[type] : "unknown";
}

sr_draco_status attribute(const draco::Mesh &mesh, uint32_t id, int ctype, int components,
                          uint8_t *out, char *why, size_t cap)
{
    const draco::PointAttribute *a = mesh.GetAttributeByUniqueId(id);
    if (!a) {
        return SR_DRACO_NO_ATTRIBUTE;
    }
    if (a->num_components() != components) {
        std::snprintf(why, cap, "it has %d components per point, the accessor %d",
                      a->num_components(), components);
        return SR_DRACO_MISMATCH;
    }
    int stored = gltf_type_of(a->data_type());
    if (ctype != 5126 && stored != ctype) {
        std::snprintf(why, cap, "it holds %s values, which componentType %d does not take",
                      type_name(a->data_type()), ctype);
        return SR_DRACO_MISMATCH;
    }
    if (ctype == 5126 && stored == 0 && a->data_type() != draco::DT_INT32 &&
        a->data_type() != draco::DT_FLOAT64) {
        std::snprintf(why, cap, "it holds %s values, which no accessor takes",
                      type_name(a->data_type()));
        return SR_DRACO_MISMATCH;
    }
    size_t csize = ctype == 5126 || ctype == 5125 ? 4 : ctype >= 5122 ? 2 : 1;
    size_t esize = csize * static_cast<size_t>(components);
    size_t points = mesh.num_points();
    for (size_t i = 0; i < points; i++) {
        draco::AttributeValueIndex v = a->mapped_index(draco::PointIndex(static_cast<uint32_t>(i)));
        if (v.value() >= a->size()) {
            say(why, cap, "a point maps past the attribute's values");
            return SR_DRACO_CORRUPT;
        }
        uint8_t *e = out + i * esize;
        if (ctype == 5126) {
            for (int c = 0; c < components; c++) {
                put_le(e + 4 * static_cast<size_t>(c), component_of(*a, v, c));
            }
            continue;
        }
        switch (ctype) {
        case 5120: copy_raw<int8_t>(*a, v, components, e); break;
        case 5121: copy_raw<uint8_t>(*a, v, components, e); break;
        case 5122: copy_raw<int16_t>(*a, v, components, e); break;
        case 5123: copy_raw<uint16_t>(*a, v, components, e); break;
        default:   copy_raw<uint32_t>(*a, v, components, e); break;
        }
    }
    return SR_DRACO_OK;
}

} // namespace

extern "C" sr_draco_status sr__draco_decode(const uint8_t *data, size_t size,
                                            sr_draco_mesh **out, char *why, size_t cap)
{
    *out = nullptr;
    say(why, cap, "");
    try {
        draco::DecoderBuffer buffer;
        buffer.Init(reinterpret_cast<const char *>(data), size);
        auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
        if (!type.ok()) {
            say(why, cap, type.status().error_msg());
            return SR_DRACO_CORRUPT;
        }
        if (type.value() != draco::TRIANGULAR_MESH) {
            return SR_DRACO_NOT_A_MESH;
        }
        draco::Decoder decoder;
        auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
        if (!decoded.ok()) {
            say(why, cap, decoded.status().error_msg());
            return SR_DRACO_CORRUPT;
        }
        std::unique_ptr<sr_draco_mesh> m(new sr_draco_mesh);
        m->mesh = std::move(decoded).value();
        if (!m->mesh) {
            say(why, cap, "no mesh");
            return SR_DRACO_CORRUPT;
        }
        /* Every corner names a point: checked once here, so that the
         * indices are a plain copy. */
        const draco::Mesh &mesh = *m->mesh;
        for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f) {
            for (int k = 0; k < 3; k++) {
                if (mesh.face(f)[k].value() >= mesh.num_points()) {
                    say(why, cap, "a triangle's corner is past the points");
                    return SR_DRACO_CORRUPT;
                }
            }
        }
        *out = m.release();
        return SR_DRACO_OK;
    } catch (const std::bad_alloc &) {
        return SR_DRACO_NO_MEMORY;
    } catch (...) {
        say(why, cap, "libdraco failed");
        return SR_DRACO_CORRUPT;
    }
}

extern "C" void sr__draco_free(sr_draco_mesh *m)
{
    delete m;
}

extern "C" size_t sr__draco_points(const sr_draco_mesh *m)
{
    return m->mesh->num_points();
}

extern "C" size_t sr__draco_faces(const sr_draco_mesh *m)
{
    return m->mesh->num_faces();
}

extern "C" void sr__draco_indices(const sr_draco_mesh *m, uint32_t *out)
{
    const draco::Mesh &mesh = *m->mesh;
    for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f) {
        for (int k = 0; k < 3; k++) {
            out[3 * static_cast<size_t>(f.value()) + static_cast<size_t>(k)] =
                mesh.face(f)[k].value();
        }
    }
}

extern "C" sr_draco_status sr__draco_attribute(const sr_draco_mesh *m, uint32_t id,
                                               int component_type, int components, uint8_t *out,
                                               char *why, size_t cap)
{
    say(why, cap, "");
    try {
        return attribute(*m->mesh, id, component_type, components, out, why, cap);
    } catch (...) {
        return SR_DRACO_NO_MEMORY;
    }
}
