#!/usr/bin/python3
"""instanced-forest.py - writes a .glb of one small mesh (a cone "tree" on
a box "trunk", 2 primitives) placed N times by one node's
EXT_mesh_gpu_instancing, on a square grid with a random turn about +Y and
a random size per tree (fixed seed): the scene the instancing
measurements of docs/gltf.md load and render.  With --nodes, the same
trees as N plain nodes of the mesh instead (core glTF), to compare.

    tools/instanced-forest.py [--nodes] N OUT.glb
"""
import math
import random
import sys

import glb


def cone(segments, radius, y0, y1):
    pos, idx = [0.0, y1, 0.0], []
    for i in range(segments):
        a = 2 * math.pi * i / segments
        pos += [radius * math.cos(a), y0, -radius * math.sin(a)]
    for i in range(segments):
        a, b = 1 + i, 1 + (i + 1) % segments
        idx += [0, a, b]
    base = len(pos) // 3
    pos += [0.0, y0, 0.0]
    for i in range(segments):
        a, b = 1 + i, 1 + (i + 1) % segments
        idx += [base, b, a]
    return pos, idx


def box(h, y0, y1):
    pos = [x for y in (y0, y1) for (x0, z0) in ((-h, -h), (h, -h), (h, h), (-h, h))
           for x in (x0, y, z0)]
    idx = [0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6, 0, 4, 5, 0, 5, 1, 1, 5, 6, 1, 6, 2,
           2, 6, 7, 2, 7, 3, 3, 7, 4, 3, 4, 0]
    return pos, idx


def main():
    args = sys.argv[1:]
    plain = args[:1] == ["--nodes"]
    args = args[1:] if plain else args
    if len(args) != 2:
        sys.exit("usage: " + __doc__.strip().splitlines()[-1].strip())
    n, out = int(args[0]), args[1]
    rng = random.Random(7)
    side = max(1, math.ceil(math.sqrt(n)))
    buf = glb.Buffer()
    add = buf.add

    prims = []
    for (pos, idx), material in ((cone(12, 0.6, 0.4, 2.0), 0), (box(0.12, 0.0, 0.4), 1)):
        lo = [min(pos[k::3]) for k in range(3)]
        hi = [max(pos[k::3]) for k in range(3)]
        p = add("f", pos, {"componentType": 5126, "count": len(pos) // 3, "type": "VEC3",
                           "min": lo, "max": hi})
        i = add("H", idx, {"componentType": 5123, "count": len(idx), "type": "SCALAR"})
        prims.append({"attributes": {"POSITION": p}, "indices": i, "material": material})
    t, r, s = [], [], []
    for k in range(n):
        x, z = k % side, k // side
        t += [(x - side / 2) * 1.5 + rng.uniform(-0.4, 0.4), 0.0,
              (z - side / 2) * 1.5 + rng.uniform(-0.4, 0.4)]
        a = rng.uniform(0, math.pi)
        r += [0.0, math.sin(a), 0.0, math.cos(a)]
        g = rng.uniform(0.6, 1.3)
        s += [g, g * rng.uniform(0.8, 1.2), g]
    if plain:
        nodes = [{"mesh": 0, "translation": t[3 * k:3 * k + 3], "rotation": r[4 * k:4 * k + 4],
                  "scale": s[3 * k:3 * k + 3]} for k in range(n)]
    attrs = None if plain else {
        "TRANSLATION": add("f", t, {"componentType": 5126, "count": n, "type": "VEC3"}),
        "ROTATION": add("f", r, {"componentType": 5126, "count": n, "type": "VEC4"}),
        "SCALE": add("f", s, {"componentType": 5126, "count": n, "type": "VEC3"}),
    }
    if not plain:
        nodes = [{"mesh": 0, "extensions": {"EXT_mesh_gpu_instancing": {"attributes": attrs}}}]
    doc = {
        "asset": {"version": "2.0", "generator": "softrast tools/instanced-forest.py"},
        "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": [{"primitives": prims}],
        "materials": [
            {"pbrMetallicRoughness": {"baseColorFactor": [0.1, 0.45, 0.15, 1],
                                      "metallicFactor": 0, "roughnessFactor": 0.8}},
            {"pbrMetallicRoughness": {"baseColorFactor": [0.4, 0.25, 0.1, 1],
                                      "metallicFactor": 0, "roughnessFactor": 0.9}}],
    }
    if not plain:
        doc["extensionsUsed"] = doc["extensionsRequired"] = ["EXT_mesh_gpu_instancing"]
    glb.write(out, doc, buf)


if __name__ == "__main__":
    main()
