/* draco_encode.cc - test_gltf_draco's Draco writer (draco_encode.h): the
 * mesh built as libdraco's draco::Mesh, encoded with draco::Encoder at the
 * default speed (edgebreaker, which reorders the points and the faces) or
 * with sequential connectivity (faces kept in order), then decoded
 * once to tell the writer the counts its accessors must state, as the
 * extension asks of exporters.  Internal to tests. */
#include "draco_encode.h"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>

#include <cstdlib>
#include <cstring>

namespace {

int add(draco::PointCloud &pc, draco::GeometryAttribute::Type type, const float *values,
        int components, size_t n)
{
    draco::GeometryAttribute ga;
    ga.Init(type, nullptr, static_cast<uint8_t>(components), draco::DT_FLOAT32, false,
            static_cast<int64_t>(sizeof(float)) * components, 0);
    int id = pc.AddAttribute(ga, true, static_cast<uint32_t>(n));
    draco::PointAttribute *a = pc.attribute(id);
    for (size_t i = 0; i < n; i++) {
        a->SetAttributeValue(draco::AttributeValueIndex(static_cast<uint32_t>(i)),
                             values + i * static_cast<size_t>(components));
    }
    return id;
}

} // namespace

extern "C" draco_encoded draco_encode(const float *pos, const float *nrm, const float *uv,
                                      size_t n, const uint32_t *idx, size_t faces, int bits,
                                      int point_cloud, int sequential)
{
    draco_encoded out = {};
    try {
        std::unique_ptr<draco::PointCloud> pc;
        if (point_cloud) {
            pc.reset(new draco::PointCloud);
        } else {
            draco::Mesh *m = new draco::Mesh;
            pc.reset(m);
            for (size_t f = 0; f < faces; f++) {
                m->AddFace({ draco::PointIndex(idx[3 * f]), draco::PointIndex(idx[3 * f + 1]),
                             draco::PointIndex(idx[3 * f + 2]) });
            }
        }
        pc->set_num_points(static_cast<uint32_t>(n));
        int ids[3] = { add(*pc, draco::GeometryAttribute::POSITION, pos, 3, n), -1, -1 };
        if (nrm) {
            ids[1] = add(*pc, draco::GeometryAttribute::NORMAL, nrm, 3, n);
        }
        if (uv) {
            ids[2] = add(*pc, draco::GeometryAttribute::TEX_COORD, uv, 2, n);
        }
        out.id_pos = pc->attribute(ids[0])->unique_id();
        out.id_nrm = nrm ? pc->attribute(ids[1])->unique_id() : 0;
        out.id_uv = uv ? pc->attribute(ids[2])->unique_id() : 0;
        draco::Encoder enc;
        enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, bits);
        enc.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
        enc.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
        if (sequential) {
            enc.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
        }
        draco::EncoderBuffer buf;
        draco::Status s = point_cloud
                              ? enc.EncodePointCloudToBuffer(*pc, &buf)
                              : enc.EncodeMeshToBuffer(*static_cast<draco::Mesh *>(pc.get()), &buf);
        if (!s.ok()) {
            return out;
        }
        draco::DecoderBuffer in;
        in.Init(buf.data(), buf.size());
        draco::Decoder dec;
        auto back = dec.DecodePointCloudFromBuffer(&in);
        if (!back.ok()) {
            return out;
        }
        out.points = back.value()->num_points();
        if (!point_cloud) {
            out.faces = static_cast<draco::Mesh *>(back.value().get())->num_faces();
        }
        out.data = static_cast<uint8_t *>(std::malloc(buf.size()));
        if (out.data) {
            std::memcpy(out.data, buf.data(), buf.size());
            out.size = buf.size();
        }
    } catch (...) {
        std::free(out.data);
        out.data = nullptr;
    }
    return out;
}
