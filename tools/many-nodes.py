#!/usr/bin/python3
"""many-nodes.py - writes a .glb of N plain nodes, each with its own small
mesh (a box of 24 vertices and 12 triangles, one primitive), on a square
grid, the materials alternating A, B, A, ...: no two consecutive parts
share a material, so nothing merges them into one draw, and each of the N
draws names 24 vertices of a loaded mesh of 24 N.  The scene of the
per-draw cost measurements in docs/performance.md.  With M materials
(--materials M, at least 2) they cycle through M roughnesses from 0.4 to
0.95 (more distinct prefiltered radiance maps than a context used to keep).

    tools/many-nodes.py N OUT.glb [--materials M]
"""
import math
import sys

import glb


def box(h):
    """A cube of half size h, 4 vertices per face for flat normals."""
    pos, nrm, idx = [], [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            n = [0.0, 0.0, 0.0]
            n[axis] = sign
            u, v = (axis + 1) % 3, (axis + 2) % 3
            base = len(pos) // 3
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis], p[u], p[v] = sign * h, a * h, b * h
                pos += p
                nrm += n
            quad = [0, 1, 2, 0, 2, 3] if sign > 0 else [0, 2, 1, 0, 3, 2]
            idx += [base + k for k in quad]
    return pos, nrm, idx


def main():
    args = sys.argv[1:]
    usage = "usage: " + __doc__.strip().splitlines()[-1].strip()
    materials = 2
    if len(args) == 4 and args[2] == "--materials":
        materials = int(args[3])
        args = args[:2]
    if len(args) != 2 or materials < 2:
        sys.exit(usage)
    n, out = int(args[0]), args[1]
    side = max(1, math.ceil(math.sqrt(n)))
    buf = glb.Buffer()
    add = buf.add

    pos, nrm, idx = box(0.4)
    meshes, nodes = [], []
    for k in range(n):
        # Each node its own accessors, as exporters write separate objects.
        p = add("f", pos, {"componentType": 5126, "count": len(pos) // 3, "type": "VEC3",
                           "min": [-0.4] * 3, "max": [0.4] * 3})
        q = add("f", nrm, {"componentType": 5126, "count": len(nrm) // 3, "type": "VEC3"})
        i = add("H", idx, {"componentType": 5123, "count": len(idx), "type": "SCALAR"})
        meshes.append({"primitives": [{"attributes": {"POSITION": p, "NORMAL": q},
                                       "indices": i, "material": k % materials}]})
        x, z = k % side, k // side
        nodes.append({"mesh": k, "translation": [(x - side / 2) * 1.2, 0.0,
                                                 (z - side / 2) * 1.2]})
    doc = {
        "asset": {"version": "2.0", "generator": "softrast tools/many-nodes.py"},
        "scene": 0, "scenes": [{"nodes": list(range(n))}],
        "nodes": nodes, "meshes": meshes,
        "materials": [
            {"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.3, 0.2, 1],
                                      "metallicFactor": 0, "roughnessFactor": 0.6}},
            {"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.8, 1],
                                      "metallicFactor": 0.5, "roughnessFactor": 0.3}}],
    }
    if materials > 2:
        doc["materials"] = [
            {"pbrMetallicRoughness": {
                "baseColorFactor": [0.2 + 0.6 * j / (materials - 1), 0.4, 0.8 - 0.6 * j / (materials - 1), 1],
                "metallicFactor": 0.5,
                "roughnessFactor": round(0.4 + 0.55 * j / (materials - 1), 4)}}
            for j in range(materials)]
    glb.write(out, doc, buf)


if __name__ == "__main__":
    main()
