"""A small glTF 2.0 writer for the tests: quads and boxes with materials,
images, a camera, written as one .gltf file with data: URIs."""

import base64
import json

import numpy as np

import softrast


def png_uri(image):
    """A data: URI of an (H, W, 4) uint8 image as PNG."""
    import os
    import tempfile
    fd, path = tempfile.mkstemp(suffix=".png")
    os.close(fd)
    try:
        softrast.write_png(path, image)
        with open(path, "rb") as f:
            data = f.read()
    finally:
        os.unlink(path)
    return "data:image/png;base64," + base64.b64encode(data).decode()


def quad(centre, size, normal_axis="z", uv=True):
    """A square facing +normal_axis: positions, normals, glTF uvs (v down), indices."""
    c = np.asarray(centre, np.float32)
    h = size / 2.0
    if normal_axis == "z":
        p = [[-h, -h, 0], [h, -h, 0], [h, h, 0], [-h, h, 0]]
        n = [0, 0, 1]
    else:   # "y": a floor
        p = [[-h, 0, h], [h, 0, h], [h, 0, -h], [-h, 0, -h]]
        n = [0, 1, 0]
    prim = {"positions": np.asarray(p, np.float32) + c,
            "normals": np.tile(np.asarray(n, np.float32), (4, 1)),
            "indices": np.array([0, 1, 2, 0, 2, 3], np.uint16)}
    if uv:
        prim["uvs"] = np.array([[0, 1], [1, 1], [1, 0], [0, 0]], np.float32)
    return prim


def box(centre, size):
    """A closed cube, a face's 4 vertices each with the face's normal."""
    c = np.asarray(centre, np.float32)
    h = size / 2.0
    pos, nrm, idx = [], [], []
    for axis in range(3):
        for sign in (1.0, -1.0):
            n = np.zeros(3, np.float32)
            n[axis] = sign
            u = np.roll(n, 1) if sign > 0 else np.roll(n, 2) * 1
            u = np.abs(u)
            v = np.cross(n, u)
            base = len(pos)
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                pos.append(c + h * (n + a * u + b * v))
                nrm.append(n)
            idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return {"positions": np.asarray(pos, np.float32), "normals": np.asarray(nrm, np.float32),
            "indices": np.asarray(idx, np.uint16)}


def write(path, prims, materials, images=(), camera=None, orthographic=False, textures=None,
          samplers=()):
    """prims: list of (primitive dict, material index); camera: (eye,
    target, yfov) or None, (eye, target, ymag) when orthographic.  Each
    primitive is a node of its own.  textures: the file's texture list
    (default: one an image, without a sampler); samplers: its samplers."""
    data = b""
    views, accessors, meshes, nodes = [], [], [], []

    def add(array, kind, target_count=None):
        nonlocal data
        a = np.ascontiguousarray(array)
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": a.nbytes})
        data += a.tobytes() + b"\0" * (-a.nbytes % 4)
        acc = {"bufferView": len(views) - 1, "count": len(a), "type": kind,
               "componentType": 5123 if a.dtype == np.uint16 else 5126}
        if kind == "VEC3" and target_count == "minmax":
            acc["min"] = a.min(0).tolist()
            acc["max"] = a.max(0).tolist()
        accessors.append(acc)
        return len(accessors) - 1

    for prim, material in prims:
        attrs = {"POSITION": add(prim["positions"], "VEC3", "minmax"),
                 "NORMAL": add(prim["normals"], "VEC3")}
        if "uvs" in prim:
            attrs["TEXCOORD_0"] = add(prim["uvs"], "VEC2")
        if "uvs1" in prim:
            attrs["TEXCOORD_1"] = add(prim["uvs1"], "VEC2")
        p = {"attributes": attrs, "indices": add(prim["indices"], "SCALAR"), "material": material}
        meshes.append({"primitives": [p]})
        nodes.append({"mesh": len(meshes) - 1})
    doc = {"asset": {"version": "2.0"}, "scene": 0, "meshes": meshes, "materials": list(materials),
           "accessors": accessors, "bufferViews": views,
           "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," +
                        base64.b64encode(data).decode()}]}
    if images:
        doc["images"] = [{"uri": png_uri(im)} for im in images]
        doc["textures"] = textures if textures is not None else \
            [{"source": i} for i in range(len(images))]
    if samplers:
        doc["samplers"] = list(samplers)
    if camera is not None:
        eye, target, size = camera
        K, R, t = softrast.look_at(eye, target, width=2, height=2)
        # OpenCV's camera (x right, y down, z forward) to glTF's (y up, -z forward).
        to_world = R.T @ np.diag([1.0, -1.0, -1.0])
        m = np.eye(4)
        m[:3, :3] = to_world
        m[:3, 3] = eye
        if orthographic:
            doc["cameras"] = [{"type": "orthographic", "orthographic": {
                "xmag": size, "ymag": size, "znear": 0.05, "zfar": 100.0}}]
        else:
            doc["cameras"] = [{"type": "perspective",
                               "perspective": {"yfov": size, "znear": 0.05, "zfar": 100.0}}]
        nodes.append({"camera": 0, "matrix": m.T.reshape(-1).tolist()})
    doc["nodes"] = nodes
    doc["scenes"] = [{"nodes": list(range(len(nodes)))}]
    with open(path, "w") as f:
        json.dump(doc, f)
    return path
