#!/usr/bin/env python3
"""animated_gltf.py - a large animated glTF (GLB) for measuring how
`softrast batch --animate --animation` and `softrast render --animation`
scale with the size of the file: a grid of COLS x ROWS vertices bent by a
chain of JOINTS joints (a skin whose joints an animation turns), with a
morph target an animation weighs, its node moved by a translation
channel.  Standard library only.

    /usr/bin/python3 bench/animated_gltf.py OUT.glb [COLS ROWS [JOINTS]]

The default, 500 x 1000 vertices, writes a file of about 40 MB.
"""
import array
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
import glb  # noqa: E402  (tools/glb.py: the GLB container)


def main():
    if len(sys.argv) not in (2, 4, 5):
        sys.exit(__doc__)
    out = sys.argv[1]
    cols = int(sys.argv[2]) if len(sys.argv) > 2 else 500
    rows = int(sys.argv[3]) if len(sys.argv) > 3 else 1000
    joints = int(sys.argv[4]) if len(sys.argv) > 4 else 8
    n = cols * rows
    # The grid stands in the xy plane, 1 wide and 2 high, facing +z; joint
    # j sits at height 2 j / joints and each vertex follows the two joints
    # around it.
    pos, nrm, wts, dlt = (array.array("f") for _ in range(4))
    jnt = array.array("B")
    for r in range(rows):
        y = 2.0 * r / (rows - 1)
        f = y / 2.0 * (joints - 1)
        j0 = min(int(f), joints - 2)
        w1 = f - j0
        for c in range(cols):
            x = c / (cols - 1) - 0.5
            pos.extend((x, y, 0.0))
            nrm.extend((0.0, 0.0, 1.0))
            jnt.extend((j0, j0 + 1, 0, 0))
            wts.extend((1.0 - w1, w1, 0.0, 0.0))
            dlt.extend((0.0, 0.0, 0.2 * math.sin(8 * x) * math.sin(4 * y)))
    idx = array.array("I")
    for r in range(rows - 1):
        for c in range(cols - 1):
            a = r * cols + c
            idx.extend((a, a + 1, a + cols + 1, a, a + cols + 1, a + cols))
    # Inverse bind matrices: the joints' rest translations undone.
    ibm = array.array("f")
    for j in range(joints):
        ibm.extend((1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -2.0 * j / joints, 0, 1))
    # Four seconds at 10 keys a second: every joint sways about z, the
    # morph weight and the node's height follow.
    keys = 41
    times = array.array("f", (k / 10.0 for k in range(keys)))
    rot = array.array("f")
    for k in range(keys):
        a = 0.25 * math.sin(2 * math.pi * k / (keys - 1))
        rot.extend((0.0, 0.0, math.sin(a / 2), math.cos(a / 2)))
    weight = array.array("f", (0.5 + 0.5 * math.sin(math.pi * k / 20) for k in range(keys)))
    lift = array.array("f")
    for k in range(keys):
        lift.extend((0.0, 0.1 * math.sin(math.pi * k / 10), 0.0))
    if sys.byteorder != "little":
        for a in (pos, nrm, wts, dlt, idx, ibm, times, rot, weight, lift):
            a.byteswap()

    blob = bytearray()
    views, accessors = [], []

    def add(data, count, kind, ctype, extra=None):
        off = len(blob)
        blob.extend(data.tobytes())
        blob.extend(b"\0" * (-len(blob) % 4))
        views.append({"buffer": 0, "byteOffset": off, "byteLength": len(data) * data.itemsize})
        acc = {"bufferView": len(views) - 1, "componentType": ctype, "count": count, "type": kind}
        acc.update(extra or {})
        accessors.append(acc)
        return len(accessors) - 1

    a_pos = add(pos, n, "VEC3", 5126, {"min": [-0.5, 0, 0], "max": [0.5, 2, 0]})
    a_nrm = add(nrm, n, "VEC3", 5126)
    a_jnt = add(jnt, n, "VEC4", 5121)
    a_wts = add(wts, n, "VEC4", 5126)
    a_dlt = add(dlt, n, "VEC3", 5126, {"min": [0, 0, -0.2], "max": [0, 0, 0.2]})
    a_idx = add(idx, len(idx), "SCALAR", 5125)
    a_ibm = add(ibm, joints, "MAT4", 5126)
    a_t = add(times, keys, "SCALAR", 5126, {"min": [0], "max": [times[-1]]})
    a_rot = add(rot, keys, "VEC4", 5126)
    a_w = add(weight, keys, "SCALAR", 5126)
    a_lift = add(lift, keys, "VEC3", 5126)

    # Node 0 draws the skinned grid; nodes 1.. are the joint chain.
    nodes = [{"mesh": 0, "skin": 0}]
    for j in range(joints):
        node = {"translation": [0, 2.0 / joints if j else 0, 0]}
        if j + 1 < joints:
            node["children"] = [j + 2]
        nodes.append(node)
    channels = [{"sampler": 0, "target": {"node": j + 1, "path": "rotation"}}
                for j in range(joints)]
    channels.append({"sampler": 1, "target": {"node": 0, "path": "weights"}})
    channels.append({"sampler": 2, "target": {"node": 1, "path": "translation"}})
    doc = {
        "asset": {"version": "2.0", "generator": "softrast bench/animated_gltf.py"},
        "buffers": [{"byteLength": len(blob)}],
        "bufferViews": views,
        "accessors": accessors,
        "meshes": [{"name": "grid", "primitives": [{
            "attributes": {"POSITION": a_pos, "NORMAL": a_nrm, "JOINTS_0": a_jnt,
                           "WEIGHTS_0": a_wts},
            "indices": a_idx, "targets": [{"POSITION": a_dlt}]}], "weights": [0]}],
        "skins": [{"joints": list(range(1, joints + 1)), "inverseBindMatrices": a_ibm}],
        "nodes": nodes,
        "scenes": [{"nodes": [0, 1]}],
        "animations": [{"name": "sway", "channels": channels, "samplers": [
            {"input": a_t, "output": a_rot},
            {"input": a_t, "output": a_w},
            {"input": a_t, "output": a_lift}]}],
    }
    glb.write_chunks(out, doc, blob)

if __name__ == "__main__":
    main()
