"""EXT_mesh_gpu_instancing through softrast.load: a box one node places
three times (turned and moved per instance) is three instances sharing
one Mesh, each posed at the node's world matrix times its transform, each
numbered by its position in the scene (instance_id None)."""

import base64
import json

import numpy as np

import gltf_build as gb
from conftest import load_gltf


def quat_y(angle):
    return [0.0, np.sin(angle / 2), 0.0, np.cos(angle / 2)]


def write(path):
    gb.write(path, [(gb.box((0, 0, 0), 0.5), 0)],
             [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.4, 0.2, 1]}}])
    with open(path) as f:
        doc = json.load(f)
    t = np.array([[-1.5, 0, 0], [0, 0, 0], [1.5, 0.5, 0]], np.float32)
    r = np.array([quat_y(0), quat_y(0.5), quat_y(1.0)], np.float32)
    data = t.tobytes() + r.tobytes()
    raw = base64.b64decode(doc["buffers"][0]["uri"].split(",", 1)[1])
    at = len(raw)
    raw += data
    doc["buffers"][0] = {"byteLength": len(raw), "uri": "data:application/octet-stream;base64," +
                         base64.b64encode(raw).decode()}
    doc["bufferViews"] += [{"buffer": 0, "byteOffset": at, "byteLength": t.nbytes},
                           {"buffer": 0, "byteOffset": at + t.nbytes, "byteLength": r.nbytes}]
    n = len(doc["accessors"])
    doc["accessors"] += [{"bufferView": len(doc["bufferViews"]) - 2, "componentType": 5126,
                          "count": 3, "type": "VEC3"},
                         {"bufferView": len(doc["bufferViews"]) - 1, "componentType": 5126,
                          "count": 3, "type": "VEC4"}]
    doc["nodes"][0]["translation"] = [0.0, 0.0, -4.0]
    doc["nodes"][0]["extensions"] = {"EXT_mesh_gpu_instancing": {
        "attributes": {"TRANSLATION": n, "ROTATION": n + 1}}}
    doc["extensionsUsed"] = ["EXT_mesh_gpu_instancing"]
    with open(path, "w") as f:
        json.dump(doc, f)
    return t, r


def test_instances_share_the_mesh_and_take_node_world_times_trs(tmp_path):
    path = str(tmp_path / "instanced.gltf")
    t, r = write(path)
    scene = load_gltf(path)
    assert len(scene.instances) == 3
    assert all(inst.mesh is scene.instances[0].mesh for inst in scene.instances)
    for k, inst in enumerate(scene.instances):
        a = 0.5 * k
        want = np.eye(4)
        want[:3, :3] = [[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]]
        want[:3, 3] = t[k] + np.array([0, 0, -4.0])
        np.testing.assert_allclose(np.asarray(inst.pose), want, atol=1e-6)
    # No ID of their own: the render numbers them by position, 0, 1, 2.
    assert all(inst.instance_id is None for inst in scene.instances)
