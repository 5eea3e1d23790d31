"""A mirrored node (its world matrix's determinant negative) draws what
the same surface drawn without mirroring draws: a normal-mapped quad
whose mesh is mirrored in x (winding reversed to keep its front, tangents
pointing along -x with handedness -1, as a mirroring exporter writes
them) placed by a node that mirrors it back lies exactly where the plain
quad lies, with the same texture coordinates, so every pixel must match:
front faces (culling, two-sided lighting) and the normal map's tangent
frame (the file's tangents, or the renderer's own) turn with the mirror.
Through softrast.render and through the softrast command."""

import base64
import json
import os
import subprocess

import numpy as np
import pytest
import softrast

import gltf_build as gb
from conftest import load_gltf

CLI = os.environ.get("SR_CLI")


def write(path, mirrored, tangents):
    q = gb.quad((0, 0, 0), 1.6)
    pos, idx = q["positions"].copy(), q["indices"].copy()
    tan = np.tile(np.array([1, 0, 0, 1], np.float32), (4, 1))
    node = {"mesh": 0}
    if mirrored:
        pos[:, 0] *= -1
        idx = idx.reshape(-1, 3)[:, ::-1].reshape(-1).copy()
        tan = np.tile(np.array([-1, 0, 0, -1], np.float32), (4, 1))
        node["matrix"] = [-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
    arrays = [(pos, "VEC3"), (q["normals"], "VEC3"), (q["uvs"], "VEC2"), (idx, "SCALAR")]
    if tangents:
        arrays.append((tan, "VEC4"))
    data, views, accessors = b"", [], []
    for a, kind in arrays:
        a = np.ascontiguousarray(a)
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": a.nbytes})
        data += a.tobytes() + b"\0" * (-a.nbytes % 4)
        accessors.append({"bufferView": len(views) - 1, "count": len(a), "type": kind,
                          "componentType": 5123 if a.dtype == np.uint16 else 5126})
    accessors[0]["min"], accessors[0]["max"] = pos.min(0).tolist(), pos.max(0).tolist()
    attrs = {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}
    if tangents:
        attrs["TANGENT"] = 4
    # A normal map leaning toward +v (green) at the top half, toward +u
    # (red) at the bottom: a flipped tangent or bitangent shows.
    nmap = np.zeros((16, 16, 4), np.uint8)
    nmap[:8] = (128, 230, 170, 255)
    nmap[8:] = (230, 128, 170, 255)
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [node],
           "meshes": [{"primitives": [{"attributes": attrs, "indices": 3, "material": 0}]}],
           "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1],
                                                   "metallicFactor": 0.0,
                                                   "roughnessFactor": 0.5},
                          "normalTexture": {"index": 0}}],
           "textures": [{"source": 0}], "images": [{"uri": gb.png_uri(nmap)}],
           "accessors": accessors, "bufferViews": views,
           "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," +
                        base64.b64encode(data).decode()}]}
    with open(path, "w") as f:
        json.dump(doc, f)
    return path


def differ(a, b):
    return int(np.abs(a.astype(int) - b.astype(int)).max())


@pytest.mark.parametrize("tangents", [True, False], ids=["file tangents", "generated"])
def test_mirrored_node_draws_the_unmirrored_surface(tmp_path, tangents):
    plain = load_gltf(write(tmp_path / "plain.gltf", False, tangents))
    mirrored = load_gltf(write(tmp_path / "mirrored.gltf", True, tangents))
    K, R, t = softrast.look_at(eye=(0.6, 0.8, 3), target=(0, 0, 0), width=64, height=64,
                               fov_y=0.8)
    images = [softrast.render(s, K=K, R=R, t=t, width=64, height=64, shading="pbr",
                              outputs=("color",))["color"] for s in (plain, mirrored)]
    drawn = np.any(images[0] != images[0][0, 0], axis=-1).sum()
    assert drawn > 1000
    assert differ(*images) <= 1


@pytest.mark.skipif(not CLI, reason="SR_CLI (the softrast command) is not set")
@pytest.mark.parametrize("tangents", [True, False], ids=["file tangents", "generated"])
def test_mirrored_node_draws_the_unmirrored_surface_in_the_command(tmp_path, tangents):
    images = []
    for name, mirrored in (("plain", False), ("mirrored", True)):
        path = write(tmp_path / f"{name}.gltf", mirrored, tangents)
        out = tmp_path / f"{name}.png"
        subprocess.run([CLI, "render", str(path), "--size", "64x64", "--aa", "none",
                        "--camera", "eye=0.6,0.8,3", "-o", str(out)], check=True,
                       capture_output=True)
        images.append(softrast.read_image(str(out)))
    assert differ(*images) <= 1
