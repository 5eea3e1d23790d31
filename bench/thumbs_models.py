#!/usr/bin/python3
"""Write the thumbs benchmark's generated models: each OBJ given, as a
binary STL, a binary PLY and a glTF with its buffer embedded, into OUTDIR
(positions and triangles only; faces of more than three vertices split
into fans).

usage: thumbs_models.py OUTDIR MODEL.obj...
"""
import base64
import json
import os
import struct
import sys


def read_obj(path):
    verts, tris = [], []
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                verts.append(tuple(float(x) for x in parts[1:4]))
            elif parts[0] == "f":
                idx = []
                for p in parts[1:]:
                    i = int(p.split("/")[0])
                    idx.append(i - 1 if i > 0 else len(verts) + i)
                for k in range(1, len(idx) - 1):
                    tris.append((idx[0], idx[k], idx[k + 1]))
    return verts, tris


def write_stl(path, verts, tris):
    with open(path, "wb") as f:
        f.write(b"thumbs benchmark".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            a, b, c = (verts[i] for i in t)
            u = [b[k] - a[k] for k in range(3)]
            v = [c[k] - a[k] for k in range(3)]
            n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
            length = sum(x * x for x in n) ** 0.5 or 1.0
            f.write(struct.pack("<3f", *(x / length for x in n)))
            for p in (a, b, c):
                f.write(struct.pack("<3f", *p))
            f.write(b"\0\0")


def write_ply(path, verts, tris):
    with open(path, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\n"
                 "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
                 "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
                 % (len(verts), len(tris))).encode())
        for p in verts:
            f.write(struct.pack("<3f", *p))
        for t in tris:
            f.write(struct.pack("<B3i", 3, *t))


def write_gltf(path, verts, tris):
    pos = b"".join(struct.pack("<3f", *p) for p in verts)
    ind = b"".join(struct.pack("<3I", *t) for t in tris)
    lo = [min(p[k] for p in verts) for k in range(3)]
    hi = [max(p[k] for p in verts) for k in range(3)]
    data = pos + ind
    doc = {
        "asset": {"version": "2.0", "generator": "softrast thumbs benchmark"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64,"
                            + base64.b64encode(data).decode()}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(pos), "target": 34962},
            {"buffer": 0, "byteOffset": len(pos), "byteLength": len(ind), "target": 34963},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(verts), "type": "VEC3",
             "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5125, "count": 3 * len(tris), "type": "SCALAR"},
        ],
    }
    with open(path, "w") as f:
        json.dump(doc, f)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__.strip())
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for obj in sys.argv[2:]:
        stem = os.path.splitext(os.path.basename(obj))[0]
        verts, tris = read_obj(obj)
        write_stl(os.path.join(out, stem + ".stl"), verts, tris)
        write_ply(os.path.join(out, stem + ".ply"), verts, tris)
        write_gltf(os.path.join(out, stem + ".gltf"), verts, tris)


if __name__ == "__main__":
    main()
