"""softrast.load (sr_load_scene) and softrast.load_mesh (sr_load_mesh)."""

import base64
import json
import os

import numpy as np
import pytest
import softrast
from conftest import MODELS


def test_load_mesh_obj(tmp_path):
    path = tmp_path / "quad.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n")
    mesh = softrast.load_mesh(path)
    assert mesh.vertices.dtype == np.float32 and mesh.faces.dtype == np.int32
    assert mesh.faces.shape == (2, 3)
    assert np.allclose(mesh.normals, [0, 0, 1])
    assert set(map(tuple, mesh.vertices[mesh.faces].reshape(-1, 3).tolist())) == \
        {(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)}


def test_load_mesh_shared_model_with_texture():
    path = os.path.join(MODELS, "spot.obj")
    if not os.path.exists(path):
        pytest.skip(f"{path} is missing")
    loaded = softrast.load_mesh(path)
    assert len(loaded.faces) > 1000 and loaded.uvs is not None
    texture = softrast.read_image(os.path.join(MODELS, "spot_texture.png"))
    assert texture.dtype == np.uint8 and texture.ndim == 3 and texture.shape[2] == 4
    mesh = softrast.Mesh(loaded.vertices, loaded.faces, uvs=loaded.uvs, texture=texture)
    K, R, t = softrast.look_at(eye=(0, 0.5, 3), target=(0, 0.3, 0), width=64, height=64)
    out = softrast.render(mesh, K=K, R=R, t=t, width=64, height=64, outputs=("color", "mask"))
    assert out["mask"].sum() > 300
    assert out["color"][out["mask"]].std() > 5       # textured, not flat


def test_load_errors(tmp_path):
    with pytest.raises(OSError, match="missing.obj"):
        softrast.load_mesh(tmp_path / "missing.obj")
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nf 1 2 3\n")
    with pytest.raises(ValueError, match="bad.obj"):
        softrast.load_mesh(bad)
    with pytest.raises(TypeError, match="path"):
        softrast.load(3)


@pytest.mark.parametrize("read", [softrast.load, softrast.load_mesh, softrast.read_image])
def test_file_errors_are_the_oserror_subclass_of_their_cause(tmp_path, read):
    missing = tmp_path / "missing.obj"
    with pytest.raises(FileNotFoundError, match="missing.obj") as e:
        read(missing)
    assert e.value.filename == str(missing) and "cannot open" in e.value.strerror
    with pytest.raises(IsADirectoryError, match="directory"):
        read(tmp_path)
    with pytest.raises(FileNotFoundError, match=r"\\xff"):   # a name that is not UTF-8
        read(os.fsencode(tmp_path) + b"/\xff.obj")
    empty = tmp_path / "empty.obj"
    empty.write_bytes(b"")
    with pytest.raises(ValueError, match="empty.obj"):
        read(empty)


def write_gltf(path):
    """One triangle, drawn by two nodes: at the origin and moved by x + 2."""
    pos = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32).tobytes()
    idx = np.array([0, 1, 2, 0], np.uint16).tobytes()
    data = pos + idx
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0, "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0}, {"mesh": 0, "translation": [2, 0, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                        {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
    }
    path.write_text(json.dumps(doc))


def load_gltf(path):
    """softrast.load(path), the test skipped in a build that reads no glTF."""
    try:
        return softrast.load(path)
    except ValueError as e:
        if "jansson" in str(e) or "not supported" in str(e):
            pytest.skip("this build reads no glTF")
        raise


def test_load_gltf_scene(tmp_path):
    path = tmp_path / "two.gltf"
    write_gltf(path)
    scene = load_gltf(path)
    assert len(scene) == 2
    a, b = scene.instances
    assert a.mesh is b.mesh, "the primitive's arrays are shared"
    assert np.allclose(b.pose[:3, 3], [2, 0, 0]) and np.allclose(a.pose, np.eye(4))
    K, R, t = softrast.look_at(eye=(1.5, 0.5, 4), target=(1.5, 0.5, 0), width=80, height=40,
                               fov_y=0.6)
    out = softrast.render(scene, K=K, R=R, t=t, width=80, height=40, outputs=("instance_id",))
    ids = out["instance_id"]
    cols = np.nonzero(ids >= 0)[1]
    assert set(np.unique(ids)) == {-1, 0, 1}
    assert cols[ids[ids >= 0] == 0].max() < cols[ids[ids >= 0] == 1].min()


# A 2x2 lossless WebP (libwebp's WebPEncodeLosslessRGBA) of these texels:
# red, half-transparent green / blue, quarter-opaque white.
WEBP_2X2 = bytes.fromhex(
    "5249464630000000574542505650384c240000002f014000101f30ff028222ff"
    "47db7f8100218dff28c18d26424ddb062c7e938e88fec701")
WEBP_2X2_TEXELS = [[[255, 0, 0, 255], [0, 255, 0, 128]],
                   [[0, 0, 255, 255], [255, 255, 255, 64]]]


def test_read_image_reads_a_webp(tmp_path):
    path = tmp_path / "tex.webp"
    path.write_bytes(WEBP_2X2)
    try:
        image = softrast.read_image(path)
    except ValueError as e:
        if "without libwebp" in str(e):
            pytest.skip(str(e))
        raise
    assert image.dtype == np.uint8 and image.shape == (2, 2, 4)
    assert image.tolist() == WEBP_2X2_TEXELS
    assert softrast._softrast.decode_image(WEBP_2X2, "tex.webp").tolist() == WEBP_2X2_TEXELS
    path.write_bytes(WEBP_2X2[:30])     # the header, then the file ends
    with pytest.raises(ValueError, match="tex.webp"):
        softrast.read_image(path)


def test_load_exposes_a_gltf_files_lights_read_only(tmp_path):
    path = tmp_path / "lit.gltf"
    write_gltf(path)
    doc = json.loads(path.read_text())
    half = np.sqrt(0.5)
    doc["extensionsUsed"] = ["KHR_lights_punctual"]
    doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"type": "spot", "color": [1, 0.5, 0.25], "intensity": 40, "range": 9,
         "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}},
        {"type": "directional", "intensity": 3},
        {"type": "point", "intensity": 0}]}}
    doc["nodes"] += [
        {"translation": [0, 0, 2], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"rotation": [-half, 0, 0, half], "extensions": {"KHR_lights_punctual": {"light": 1}}},
        {"translation": [1, 2, 3], "extensions": {"KHR_lights_punctual": {"light": 2}}}]
    doc["scenes"][0]["nodes"] += [2, 3, 4]
    path.write_text(json.dumps(doc))
    scene = load_gltf(path)
    spot, sun, dark = scene.lights
    assert spot.type == "spot" and spot.light_index == 0 and spot.node == 2
    assert np.allclose(spot.color, [1, 0.5, 0.25]) and spot.intensity == 40
    assert np.allclose(spot.position, [0, 0, 2]) and np.allclose(spot.direction, [0, 0, -1])
    assert spot.range == 9 and np.isclose(spot.inner_cone, 0.2) and np.isclose(spot.outer_cone, 0.5)
    assert np.allclose(spot.world[:3, 3], [0, 0, 2])
    # rotated -90 degrees about x, its -Z points down -y: a sun from above
    assert sun.type == "directional" and sun.position is None and sun.range is None
    assert np.allclose(sun.direction, [0, -1, 0], atol=1e-6) and sun.inner_cone is None
    assert np.allclose(sun.color, [1, 1, 1]) and sun.intensity == 3
    # intensity 0: dark, but still the point light the file says it is
    assert dark.type == "point" and dark.node == 4 and dark.intensity == 0 and dark.dark
    assert np.allclose(dark.position, [1, 2, 3]) and not spot.dark and not sun.dark
    with pytest.raises(AttributeError):
        scene.lights = ()
    with pytest.raises(AttributeError):
        spot.intensity = 1      # type: ignore[misc]
    with pytest.raises(ValueError):
        spot.color[0] = 0
    assert "Light(light_index=0, node=2, type='spot'" in repr(spot)
    assert softrast.Scene([]).lights == ()


def write_glb(path):
    """A triangle with normals and colors, drawn by a moved and scaled node
    and by a mirroring one, as a GLB."""
    pos = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32)
    nrm = np.array([[0.6, 0, 0.8]] * 3, np.float32)
    col = np.array([[1, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 0.5]], np.float32)
    data = pos.astype("<f4").tobytes() + nrm.astype("<f4").tobytes() + col.astype("<f4").tobytes()
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0, "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0, "translation": [1, 2, 3], "scale": [2, 3, 1]},
                  {"mesh": 0, "scale": [-1, 1, 1]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "COLOR_0": 2}}]}],
        "buffers": [{"byteLength": len(data)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 72},
                        {"buffer": 0, "byteOffset": 72, "byteLength": 48}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 0, "byteOffset": 36, "componentType": 5126, "count": 3,
                       "type": "VEC3"},
                      {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC4"}],
    }
    write_glb_file(path, doc, data)


def write_glb_file(path, doc, data):
    """The GLB of a document and its binary chunk's bytes."""
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    chunks = (len(text).to_bytes(4, "little") + b"JSON" + text +
              len(data).to_bytes(4, "little") + b"BIN\0" + data)
    path.write_bytes(b"glTF" + (2).to_bytes(4, "little") +
                     (12 + len(chunks)).to_bytes(4, "little") + chunks)


def test_load_mesh_of_a_glb_is_its_scene_flattened(tmp_path):
    path = tmp_path / "two.glb"
    write_glb(path)
    scene = load_gltf(path)
    mesh = softrast.load_mesh(path)
    vertices, normals, faces = [], [], []
    for inst in scene.instances:
        m, pose = inst.mesh, inst.pose
        linear = pose[:3, :3]
        f = m.faces + sum(len(v) for v in vertices)
        if np.linalg.det(linear) < 0:
            f = f[:, [0, 2, 1]]     # mirrored: counter-clockwise again
        vertices.append(m.vertices @ linear.T + pose[:3, 3])
        n = m.normals @ np.linalg.inv(linear)
        normals.append(n / np.linalg.norm(n, axis=1, keepdims=True))
        faces.append(f)
    assert np.allclose(mesh.vertices, np.concatenate(vertices), atol=1e-6)
    assert np.allclose(mesh.normals, np.concatenate(normals), atol=1e-6)
    assert np.array_equal(mesh.faces, np.concatenate(faces))
    assert np.allclose(mesh.colors[:3, :3], scene.instances[0].mesh.colors[:, :3], atol=1e-6)
    assert np.allclose(mesh.vertices[3:], [[0, 0, 0], [-1, 0, 0], [0, 1, 0]])


def write_skinned_glb(path):
    """A strip of six vertices (rows y = 0, 1, 2) skinned to two joints:
    joint 1 sits at (0, 1, 0) turned 90 degrees about +z, row 2 follows it,
    row 1 both by half.  The skinned node's own transform (moved by 100,
    scaled by 5) is ignored; a second node draws the mesh unskinned with
    morph weight 1, its target lifting every vertex by 1 in z."""
    pos = np.array([[-0.5, 0, 0], [0.5, 0, 0], [-0.5, 1, 0], [0.5, 1, 0], [-0.5, 2, 0],
                    [0.5, 2, 0]], "<f4")
    joints = np.array([[0, 1, 0, 0]] * 4 + [[1, 0, 0, 0]] * 2, "<u2")
    weights = np.array([[1, 0, 0, 0]] * 2 + [[0.5, 0.5, 0, 0]] * 2 + [[1, 0, 0, 0]] * 2, "<f4")
    ibm = np.array([np.eye(4), np.eye(4)], "<f4")
    ibm[1, 3, 1] = -1          # column-major: the translation is the last row here
    up = np.array([[0, 0, 1]] * 6, "<f4")
    idx = np.array([0, 1, 3, 0, 3, 2, 2, 3, 5, 2, 5, 4], "<u2")
    parts = [pos.tobytes(), joints.tobytes(), weights.tobytes(), ibm.tobytes(), up.tobytes(),
             idx.tobytes()]
    views, at = [], 0
    for p in parts:
        views.append({"buffer": 0, "byteOffset": at, "byteLength": len(p)})
        at += len(p)
    h = 0.5 ** 0.5
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0, "scenes": [{"nodes": [0, 1, 3]}],
        "nodes": [{"mesh": 0, "skin": 0, "translation": [100, 0, 0], "scale": [5, 5, 5]},
                  {"children": [2]},
                  {"translation": [0, 1, 0], "rotation": [0, 0, h, h]},
                  {"mesh": 0, "weights": [1]}],
        "skins": [{"joints": [1, 2], "inverseBindMatrices": 3}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "JOINTS_0": 1, "WEIGHTS_0": 2},
                                    "indices": 5, "targets": [{"POSITION": 4}]}],
                    "weights": [0]}],
        "buffers": [{"byteLength": at}],
        "bufferViews": views,
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3",
                       "min": [-0.5, 0, 0], "max": [0.5, 2, 0]},
                      {"bufferView": 1, "componentType": 5123, "count": 6, "type": "VEC4"},
                      {"bufferView": 2, "componentType": 5126, "count": 6, "type": "VEC4"},
                      {"bufferView": 3, "componentType": 5126, "count": 2, "type": "MAT4"},
                      {"bufferView": 4, "componentType": 5126, "count": 6, "type": "VEC3"},
                      {"bufferView": 5, "componentType": 5123, "count": 12, "type": "SCALAR"}],
    }
    write_glb_file(path, doc, b"".join(parts))


def test_load_and_load_mesh_pose_skins_and_morph_targets(tmp_path):
    path = tmp_path / "skinned.glb"
    write_skinned_glb(path)
    scene = load_gltf(path)
    skinned, morphed = scene.instances
    posed = [[-0.5, 0, 0], [0.5, 0, 0], [-0.25, 0.75, 0], [0.25, 1.25, 0], [-1, 0.5, 0],
             [-1, 1.5, 0]]
    # Skinned: world-space vertices under an identity pose.
    assert np.allclose(skinned.pose, np.eye(4))
    assert np.allclose(skinned.mesh.vertices, posed, atol=1e-6)
    # Morphed by the node's weight 1 (the mesh says 0), under its node's pose.
    assert skinned.mesh is not morphed.mesh
    assert np.allclose(morphed.mesh.vertices[:, 2], 1)
    mesh = softrast.load_mesh(path)
    assert np.allclose(mesh.vertices[:6], posed, atol=1e-6)
    assert np.allclose(mesh.vertices[6:, 2], 1)


def test_load_mesh_reads_only_the_base_color_image(tmp_path):
    """load_mesh's uvs are where the base color texture is sampled (its
    KHR_texture_transform applied, as load's), and a damaged normal map,
    which load_mesh does not read, does not stop it; load refuses it."""
    from gltf_build import quad, write
    image = np.zeros((2, 2, 4), np.uint8)
    image[..., 0] = [[200, 20], [20, 200]]
    image[..., 3] = 255
    path = tmp_path / "quad.gltf"
    transform = {"KHR_texture_transform": {"offset": [0.5, 0.25], "rotation": 0.5,
                                           "scale": [2, 3]}}
    material = {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0,
                                                              "extensions": transform}}}
    write(path, [(quad((0, 0, 0), 2), 0)], [material], images=[image])
    scene = softrast.load(path)
    mesh = softrast.load_mesh(path)
    assert scene.instances[0].mesh.uvs is not None
    assert np.allclose(mesh.uvs, scene.instances[0].mesh.uvs, atol=1e-6)
    assert not np.allclose(mesh.uvs, [[0, 0], [1, 0], [1, 1], [0, 1]], atol=0.1)
    assert np.array_equal(mesh.texture, image)

    doc = json.loads(path.read_text())
    doc["images"].append({"uri": "data:image/png;base64,iVBORw0KGgoAAAANSUhEUg=="})
    doc["textures"].append({"source": 1})
    doc["materials"][0]["normalTexture"] = {"index": 1}
    path.write_text(json.dumps(doc))
    assert np.allclose(softrast.load_mesh(path).uvs, mesh.uvs)
    with pytest.raises(ValueError, match="/images/1"):
        softrast.load(path)


def test_a_zero_texture_scale_samples_the_offset(tmp_path):
    """KHR_texture_transform's scale [0, 0] collapses the coordinates onto
    the offset (the extension's), not the identity a zeroed C slot means:
    every uv load_mesh gives is glTF's (0.5, 0.25), (0.5, 0.75) in the
    library's frame (v up)."""
    from gltf_build import quad, write
    image = np.zeros((2, 2, 4), np.uint8)
    image[..., 3] = 255
    path = tmp_path / "quad.gltf"
    transform = {"KHR_texture_transform": {"offset": [0.5, 0.25], "scale": [0, 0]}}
    material = {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0,
                                                              "extensions": transform}}}
    write(path, [(quad((0, 0, 0), 2), 0)], [material], images=[image])
    mesh = softrast.load_mesh(path)
    assert np.allclose(mesh.uvs, [[0.5, 0.75]] * 4, atol=1e-6)
