"""softrast.load(path, animation=..., time=...): a glTF file posed by one
of its animations at a time, the file's animations listed on the Scene,
and the arguments checked."""

import base64
import json
import math
import pickle

import numpy as np
import pytest
import softrast

from conftest import load_gltf


def float_accessors(arrays, kinds):
    """The asset, buffer, views and accessors of a document whose
    accessor i holds arrays[i] (float32) as kinds[i] (type, count)."""
    data, views, accessors = b"", [], []
    for a, (kind, count) in zip(arrays, kinds):
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": a.nbytes})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5126,
                          "count": count, "type": kind})
        data += a.astype("<f4").tobytes()
    return {"asset": {"version": "2.0"},
            "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64,"
                         + base64.b64encode(data).decode()}],
            "bufferViews": views, "accessors": accessors}


def write_animated(path):
    """A triangle on node 0, moved by "slide" (LINEAR translation,
    (0, 0, 0) at 0 s to (4, 2, 0) at 2 s) and turned by "turn" (LINEAR
    rotation, identity at 0 s to 90 degrees about +z at 1 s)."""
    h = math.sqrt(0.5)
    arrays = [np.array([0, 0, 0, 1, 0, 0, 0, 1, 0], np.float32),
              np.array([0, 2], np.float32),
              np.array([0, 0, 0, 4, 2, 0], np.float32),
              np.array([0, 1], np.float32),
              np.array([0, 0, 0, 1, 0, 0, h, h], np.float32)]
    kinds = [("VEC3", 3), ("SCALAR", 2), ("VEC3", 2), ("SCALAR", 2), ("VEC4", 2)]
    doc = {
        **float_accessors(arrays, kinds),
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "nodes": [{"mesh": 0, "translation": [9, 9, 9]}],
        "scenes": [{"nodes": [0]}],
        "animations": [
            {"name": "slide", "samplers": [{"input": 1, "output": 2}],
             "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}]},
            {"name": "turn", "samplers": [{"input": 3, "output": 4}],
             "channels": [{"sampler": 0, "target": {"node": 0, "path": "rotation"}}]},
        ],
    }
    path.write_text(json.dumps(doc))
    return path


def world(scene):
    return np.asarray(scene.instances[0].pose, np.float64)


def test_the_animations_are_listed_and_the_rest_pose_is_the_default(tmp_path):
    path = write_animated(tmp_path / "a.gltf")
    scene = load_gltf(path)
    assert scene.animations == [softrast.Animation("slide", 1, 2.0),
                                softrast.Animation("turn", 1, 1.0)]
    assert scene.animation is None and scene.time == 0.0
    assert world(scene)[:3, 3] == pytest.approx([9, 9, 9])


@pytest.mark.parametrize("time, where", [(0.5, (1, 0.5, 0)), (1.0, (2, 1, 0)),
                                         (-1.0, (0, 0, 0)), (5.0, (4, 2, 0))])
def test_a_translation_is_sampled_and_clamped(tmp_path, time, where):
    path = write_animated(tmp_path / "a.gltf")
    scene = load_gltf(path) and softrast.load(path, animation="slide", time=time)
    assert scene.animation == 0 and scene.time == time
    assert world(scene)[:3, 3] == pytest.approx(where, abs=1e-6)
    # The same pose by index.
    assert world(softrast.load(path, animation=0, time=time)) == pytest.approx(world(scene))


def test_a_name_reads_the_file_once(tmp_path, monkeypatch):
    path = write_animated(tmp_path / "a.gltf")
    load_gltf(path)
    import softrast._scene as scene_module
    reads = []
    real = scene_module._softrast.load_scene

    def counting(*args):
        reads.append(args)
        return real(*args)

    monkeypatch.setattr(scene_module._softrast, "load_scene", counting)
    scene = softrast.load(path, animation="slide", time=1.0)
    assert len(reads) == 1
    assert scene.animation == 0 and scene.time == 1.0
    assert world(scene) == pytest.approx(world(softrast.load(path, animation=0, time=1.0)))


def test_a_rotation_is_slerped(tmp_path):
    path = write_animated(tmp_path / "a.gltf")
    load_gltf(path)
    scene = softrast.load(path, animation=1, time=0.5)
    m = world(scene)
    h = math.sqrt(0.5)
    assert m[:3, 0] == pytest.approx([h, h, 0], abs=1e-6)   # x turned 45 degrees
    assert m[:3, 3] == pytest.approx([9, 9, 9])             # translation its own


def test_a_posed_scene_pickles_in_its_pose(tmp_path):
    path = write_animated(tmp_path / "a.gltf")
    load_gltf(path)
    scene = softrast.load(path, animation="slide", time=1.0)
    source = scene.instances[0]._source[0]
    again = pickle.loads(pickle.dumps(source))
    assert again.pose == (0, 1.0)


def test_bad_arguments_are_refused(tmp_path):
    path = write_animated(tmp_path / "a.gltf")
    load_gltf(path)
    with pytest.raises(ValueError, match="has no animation named 'walk'.*'slide', 'turn'"):
        softrast.load(path, animation="walk")
    with pytest.raises(ValueError, match="sr_load_desc.animation 2 is not an animation of the "
                                         "file \\(it has 2\\)"):
        softrast.load(path, animation=2)
    with pytest.raises(ValueError, match="animation: -1 is not an index"):
        softrast.load(path, animation=-1)
    with pytest.raises(TypeError, match="animation: expected an index or a name"):
        softrast.load(path, animation=1.5)
    with pytest.raises(TypeError, match="animation: expected an index or a name"):
        softrast.load(path, animation=True)
    with pytest.raises(ValueError, match="time: nan is not finite"):
        softrast.load(path, animation=0, time=float("nan"))
    with pytest.raises(ValueError, match="time: a time into an animation: give animation too"):
        softrast.load(path, time=1.0)
    obj = tmp_path / "t.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    with pytest.raises(ValueError, match="only glTF files have"):
        softrast.load(obj, animation=0)
    assert softrast.load(obj).animations == []


# ---- Scene.pose: posed again without reading the file ---------------------

def write_morphed(path):
    """A triangle (with normals: the physically based look draws the
    library's arrays) whose morph target lifts vertex 2 by (0, 1, 0), weighed
    0 at 0 s and 1 at 2 s ("lift", LINEAR), its node turned by "turn" as
    write_animated's; a camera looking at it down -z."""
    arrays = [np.array([0, 0, 0, 1, 0, 0, 0, 1, 0], np.float32),
              np.array([0, 0, 0, 0, 0, 0, 0, 1, 0], np.float32),
              np.array([0, 2], np.float32), np.array([0, 1], np.float32),
              np.array([0, 1], np.float32),
              np.array([0, 0, 0, 1, 0, 0, math.sqrt(0.5), math.sqrt(0.5)], np.float32),
              np.array([0, 0, 1, 0, 0, 1, 0, 0, 1], np.float32)]
    kinds = [("VEC3", 3), ("VEC3", 3), ("SCALAR", 2), ("SCALAR", 2), ("SCALAR", 2), ("VEC4", 2),
             ("VEC3", 3)]
    doc = {
        **float_accessors(arrays, kinds),
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 6},
                                    "targets": [{"POSITION": 1}]}],
                    "weights": [0]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.1}}],
        "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0.5, 0.75, 3]}],
        "scenes": [{"nodes": [0, 1]}],
        "animations": [
            {"name": "lift", "samplers": [{"input": 2, "output": 3}],
             "channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}}]},
            {"name": "turn", "samplers": [{"input": 4, "output": 5}],
             "channels": [{"sampler": 0, "target": {"node": 0, "path": "rotation"}}]},
        ],
    }
    path.write_text(json.dumps(doc))
    return path


def same_scene(a, b):
    """The instances' matrices and arrays, bit for bit."""
    assert len(a.instances) == len(b.instances)
    for x, y in zip(a.instances, b.instances):
        assert np.array_equal(np.asarray(x.pose), np.asarray(y.pose))
        assert np.array_equal(x.mesh.vertices, y.mesh.vertices)
        assert np.array_equal(x.mesh.faces, y.mesh.faces)
    assert [c.world.tolist() for c in a.cameras] == [c.world.tolist() for c in b.cameras]
    assert (a.animation, a.time, a.animations) == (b.animation, b.time, b.animations)


@pytest.mark.parametrize("animation, time", [(0, 0.5), ("lift", 2.0), (1, 0.25),
                                             ("turn", 3.0), (None, 0.0)])
def test_pose_is_load_in_that_pose_without_the_file(tmp_path, animation, time):
    path = write_morphed(tmp_path / "m.gltf")
    rest = load_gltf(path)
    read = softrast.load(path, animation=animation, time=time)
    path.unlink()   # posing again reads nothing
    posed = rest.pose(animation=animation, time=time)
    same_scene(posed, read)
    # The scene posed from is left as it was, and poses again.
    assert rest.animation is None
    assert rest.instances[0].mesh.vertices[2].tolist() == [0, 1, 0]
    same_scene(posed.pose(animation=animation, time=time), read)


def test_a_scene_keeps_its_pose_when_another_is_made(tmp_path):
    """The physically based look draws the library's arrays: an earlier
    pose draws the same after later ones."""
    path = write_morphed(tmp_path / "m.gltf")
    rest = load_gltf(path)

    def image(scene):
        return softrast.render(scene, camera=scene.cameras[0], width=32, height=32,
                               shading="pbr", outputs=("color",))["color"]

    half = rest.pose(animation="lift", time=1.0)
    drawn = image(half)
    assert drawn.any()
    full = rest.pose(animation="lift", time=2.0)
    rest.pose(animation="turn", time=1.0)
    assert np.array_equal(image(half), drawn)
    assert np.array_equal(image(full), image(softrast.load(path, animation="lift", time=2.0)))
    assert not np.array_equal(image(full), drawn)


def test_pose_refuses_bad_arguments(tmp_path):
    path = write_morphed(tmp_path / "m.gltf")
    rest = load_gltf(path)
    with pytest.raises(ValueError, match="has no animation named 'walk'.*'lift', 'turn'"):
        rest.pose(animation="walk")
    with pytest.raises(ValueError, match="animation 2 is not an animation of the scene "
                                         "\\(it has 2\\)"):
        rest.pose(animation=2)
    with pytest.raises(ValueError, match="animation: -1 is not an index"):
        rest.pose(animation=-1)
    with pytest.raises(TypeError, match="animation: expected an index or a name"):
        rest.pose(animation=True)
    with pytest.raises(ValueError, match="time: inf is not finite"):
        rest.pose(animation=0, time=float("inf"))
    with pytest.raises(ValueError, match="time: a time into an animation: give animation too"):
        rest.pose(time=1.0)
    with pytest.raises(ValueError, match="not read from a glTF file"):
        softrast.Scene().pose()


def write_pointer(path):
    """Two quads facing +z under a camera: material 0's base color red at
    0 s to blue at 2 s (KHR_animation_pointer), and node 1's quad (green)
    hidden from 1 s (KHR_node_visibility, STEP)."""
    quad = np.array([-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, -1, 0, 1, 1, 0, -1, 1, 0], np.float32)
    arrays = [quad, np.array([0, 2], np.float32), np.array([1, 0, 0, 1, 0, 0, 1, 1], np.float32),
              np.array([0, 1], np.float32)]
    doc = float_accessors(arrays, [("VEC3", 6), ("SCALAR", 2), ("VEC4", 2), ("SCALAR", 2)])
    shown = bytes([1, 0, 0, 0])
    data = base64.b64decode(doc["buffers"][0]["uri"].split(",")[1]) + shown
    doc["buffers"][0] = {"byteLength": len(data), "uri": "data:application/octet-stream;base64,"
                         + base64.b64encode(data).decode()}
    doc["bufferViews"].append({"buffer": 0, "byteOffset": len(data) - 4, "byteLength": 2})
    doc["accessors"].append({"bufferView": 4, "componentType": 5121, "count": 2,
                             "type": "SCALAR"})

    def pointer(sampler, target):
        return {"sampler": sampler, "target": {"path": "pointer", "extensions": {
            "KHR_animation_pointer": {"pointer": target}}}}
    doc.update({
        "extensionsUsed": ["KHR_animation_pointer", "KHR_node_visibility"],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1]}},
                      {"pbrMetallicRoughness": {"baseColorFactor": [0, 1, 0, 1]}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]},
                   {"primitives": [{"attributes": {"POSITION": 0}, "material": 1}]}],
        "cameras": [{"type": "orthographic", "orthographic": {"xmag": 3, "ymag": 3,
                                                                "znear": 0.1, "zfar": 10}}],
        "nodes": [{"mesh": 0, "translation": [-1.5, 0, 0]},
                  {"mesh": 1, "translation": [1.5, 0, 0],
                   "extensions": {"KHR_node_visibility": {"visible": True}}},
                  {"camera": 0, "translation": [0, 0, 5]}],
        "scenes": [{"nodes": [0, 1, 2]}],
        "animations": [{"name": "fade", "samplers": [
            {"input": 1, "output": 2},
            {"input": 3, "output": 4, "interpolation": "STEP"}],
            "channels": [pointer(0, "/materials/0/pbrMetallicRoughness/baseColorFactor"),
                         pointer(1, "/nodes/1/extensions/KHR_node_visibility/visible")]}],
    })
    path.write_text(json.dumps(doc))
    return path


def test_pointer_animated_materials_and_visibility_pose_each_scene(tmp_path):
    """A pose's materials and hidden nodes are its own: an earlier pose
    (and the rest) draws the same after later ones, and pose() gives what
    load() in that pose gives."""
    path = write_pointer(tmp_path / "p.gltf")
    rest = load_gltf(path)

    def image(scene):
        return softrast.render(scene, camera=scene.cameras[0], width=48, height=24,
                               shading="pbr", outputs=("color",))["color"]

    before = image(rest)
    late = rest.pose(animation="fade", time=1.5)
    read = softrast.load(path, animation="fade", time=1.5)
    assert late.materials[0].base_color == pytest.approx([0.25, 0, 0.75, 1])
    assert read.materials[0].base_color == pytest.approx([0.25, 0, 0.75, 1])
    assert rest.materials[0].base_color == pytest.approx([1, 0, 0, 1])
    assert len(late.instances[1].mesh.faces) == 0 and len(rest.instances[1].mesh.faces) == 2
    drawn = image(late)
    assert np.array_equal(drawn, image(read))
    assert np.array_equal(image(rest), before)
    # The left quad turned blue, the right one is gone.
    assert drawn[12, 18, 2] > drawn[12, 18, 0] and before[12, 18, 0] > before[12, 18, 2]
    assert before[12, 30].any() and not drawn[12, 30].any()
    rest.pose(animation="fade", time=0.0)
    assert np.array_equal(image(late), drawn)


def write_spec_gloss(path, animated, offset=(0.0, 0.0), diffuse=(1.0, 1.0, 1.0, 1.0)):
    """A textured quad of KHR_materials_pbrSpecularGlossiness under a
    camera, its diffuse texture's KHR_texture_transform at `offset` and
    its diffuseFactor `diffuse`; `animated`: both keyed by
    KHR_animation_pointer, offset (0, 0) to (0.5, 0.25) and diffuse white
    to (0.5, 1, 0, 1) over 2 s."""
    from gltf_build import quad, write
    checker = np.zeros((8, 8, 4), np.uint8)
    checker[..., 3] = 255
    checker[(np.arange(8)[:, None] // 2 + np.arange(8)[None, :] // 2) % 2 == 1, :3] = 255
    sg = {"diffuseFactor": list(diffuse), "specularFactor": [0.1, 0.1, 0.1],
          "glossinessFactor": 0.5,
          "diffuseTexture": {"index": 0, "extensions": {"KHR_texture_transform": {
              "offset": list(offset)}}}}
    write(path, [(quad((0, 0, 0), 2.0), 0)],
          [{"extensions": {"KHR_materials_pbrSpecularGlossiness": sg}}], images=[checker],
          camera=((0, 0, 3), (0, 0, 0), 1.2))
    doc = json.loads(path.read_text())
    doc["extensionsUsed"] = ["KHR_materials_pbrSpecularGlossiness", "KHR_texture_transform",
                             "KHR_animation_pointer"]
    if animated:
        keys = [np.array([0, 2], np.float32), np.array([0, 0, 0.5, 0.25], np.float32),
                np.array([1, 1, 1, 1, 0.5, 1, 0, 1], np.float32)]
        data = base64.b64decode(doc["buffers"][0]["uri"].split(",")[1])
        for a, kind in zip(keys, ["SCALAR", "VEC2", "VEC4"]):
            doc["bufferViews"].append({"buffer": 0, "byteOffset": len(data),
                                       "byteLength": a.nbytes})
            doc["accessors"].append({"bufferView": len(doc["bufferViews"]) - 1,
                                     "componentType": 5126, "count": 2, "type": kind})
            data += a.astype("<f4").tobytes()
        doc["buffers"][0] = {"byteLength": len(data), "uri": "data:application/octet-stream;"
                             "base64," + base64.b64encode(data).decode()}
        n = len(doc["accessors"])
        sgp = "/materials/0/extensions/KHR_materials_pbrSpecularGlossiness/"
        doc["animations"] = [{"name": "shift", "samplers": [
            {"input": n - 3, "output": n - 2}, {"input": n - 3, "output": n - 1}],
            "channels": [
                {"sampler": 0, "target": {"path": "pointer", "extensions": {
                    "KHR_animation_pointer": {"pointer": sgp + "diffuseTexture/extensions/"
                                              "KHR_texture_transform/offset"}}}},
                {"sampler": 1, "target": {"path": "pointer", "extensions": {
                    "KHR_animation_pointer": {"pointer": sgp + "diffuseFactor"}}}}]}]
    path.write_text(json.dumps(doc))
    return path


def test_a_specular_glossiness_texture_transform_animates(tmp_path):
    """A specular-glossiness material's diffuse texture offset and diffuse
    factor, animated by pointer, draw at 1 s what the file with 1 s's
    values written in draws (they used to be skipped), loaded posed and
    posed again."""
    animated = write_spec_gloss(tmp_path / "a.gltf", True)
    written = write_spec_gloss(tmp_path / "w.gltf", False, (0.25, 0.125), (0.75, 1, 0.5, 1))

    def image(scene):
        return softrast.render(scene, camera=scene.cameras[0], width=48, height=48,
                               shading="pbr", outputs=("color",))["color"]

    want = image(load_gltf(written))
    rest = load_gltf(animated)
    assert np.array_equal(image(softrast.load(animated, animation="shift", time=1.0)), want)
    assert np.array_equal(image(rest.pose(animation="shift", time=1.0)), want)
    assert (np.abs(image(rest).astype(int) - want.astype(int)) > 8).sum() > 48 * 48 // 10
