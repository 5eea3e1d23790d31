"""render(lights=...): softrast render's --lights in Python - a glTF file's
KHR_lights_punctual lights (Scene.lights), the default rig, both, or lights
made with softrast.Light - compared with the command's picture of the same
file from its camera."""

import json
import math
import os
import subprocess

import numpy as np
import pytest
import softrast

import gltf_build as gb
from conftest import load_gltf

BACKGROUND = (0x1d / 255, 0x22 / 255, 0x30 / 255)   # softrast render's default
CLI = os.environ.get("SR_CLI")
needs_cli = pytest.mark.skipif(not CLI, reason="SR_CLI (the softrast command) is not set")

# A warm sun from the upper left (its node turned so that -Z points down
# and to +x: the shadow falls right of the box), a blue point light in
# front of the box, a green spot from the left, and a dark point light
# (intensity 0).
LIGHTS = [
    {"type": "directional", "color": [1.0, 0.85, 0.7], "intensity": 1.5},
    {"type": "point", "color": [0.3, 0.5, 1.0], "intensity": 1.5, "range": 8},
    {"type": "spot", "color": [0.2, 1.0, 0.3], "intensity": 6.0,
     "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.6}},
    {"type": "point", "intensity": 0},
]


def _rotation_to(direction):
    """A unit quaternion (x, y, z, w) turning -Z onto direction."""
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    a = np.array([0.0, 0.0, -1.0])
    axis = np.cross(a, d)
    s = np.linalg.norm(axis)
    angle = math.atan2(s, float(a @ d))
    axis = axis / s if s > 0 else np.array([1.0, 0.0, 0.0])
    return (axis * math.sin(angle / 2)).tolist() + [math.cos(angle / 2)]


SUN = (0.9, -1.0, 0.2)
SPOT_AT, SPOT_TO = (-2.0, 1.5, 1.0), (0.4, -0.3, -0.2)


def lit_scene(tmp_path, lights=LIGHTS, nodes=None):
    """The floor and box of test_pbr_gltf's shadow scene with `lights`."""
    path = gb.write(tmp_path / "lit.gltf",
                    [(gb.quad((0, 0, 0), 4.0, "y", uv=False), 0), (gb.box((0, 0.6, 0), 0.8), 1)],
                    [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1],
                                               "metallicFactor": 0, "roughnessFactor": 0.6}},
                     {"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.1, 1],
                                               "metallicFactor": 0, "roughnessFactor": 0.4}}],
                    camera=((2.5, 2.2, 3.0), (0, 0.3, 0), 0.8))
    doc = json.loads(path.read_text())
    if nodes is None:
        nodes = [{"rotation": _rotation_to(SUN)},
                 {"translation": [0.3, 1.0, 1.2]},
                 {"translation": list(SPOT_AT), "rotation": _rotation_to(SPOT_TO)},
                 {"translation": [0, 3, 0]}][:len(lights)]
    doc["extensionsUsed"] = ["KHR_lights_punctual"]
    doc["extensions"] = {"KHR_lights_punctual": {"lights": lights}}
    first = len(doc["nodes"])
    for i, node in enumerate(nodes):
        node = dict(node, extensions={"KHR_lights_punctual": {"light": i}})
        doc["nodes"].append(node)
    doc["scenes"][0]["nodes"] += list(range(first, first + len(nodes)))
    path.write_text(json.dumps(doc))
    return path


def ours(scene, **kw):
    return softrast.render(scene, camera=scene.cameras[0], width=160, height=120, shading="pbr",
                           background=BACKGROUND, outputs=("color",), **kw)["color"]


def command(tmp_path, path, *args):
    png = tmp_path / "cli.png"
    subprocess.run([CLI, "render", str(path), "--camera-index", "0", "--aa", "none",
                    "--size", "160x120", *args, "-o", str(png)], check=True, capture_output=True)
    return softrast.read_image(png)[..., :3]


def assert_close(name, a, b):
    """Within 2 codes on all but 0.5% of the pixels, as test_pbr_gltf's
    comparisons with the command (the command moves the vertices by the
    nodes, render in the program); the pair to $SR_TEST_OUT/name.png."""
    out = os.environ.get("SR_TEST_OUT")
    if out:
        softrast.write_png(os.path.join(out, f"{name}.png"), np.concatenate([a, b], 1))
    diff = np.abs(a.astype(int) - b).max(-1)
    assert (diff > 2).mean() <= 0.005, f"{name}: {(diff > 2).mean():.2%} of the pixels differ"


@needs_cli
@pytest.mark.parametrize("mode", ["auto", "file", "default", "both"])
@pytest.mark.parametrize("shadows", [False, True])
def test_lights_match_the_command(tmp_path, mode, shadows):
    path = lit_scene(tmp_path)
    scene = load_gltf(path)
    a = ours(scene, lights=mode, shadows=shadows)
    b = command(tmp_path, path, "--lights", mode, "--shadows", "on" if shadows else "off")
    assert_close(f"lights_{mode}_{shadows}", a, b)


@needs_cli
def test_by_default_a_file_is_lit_by_its_own_lights(tmp_path):
    path = lit_scene(tmp_path)
    scene = load_gltf(path)
    own = ours(scene)
    assert np.array_equal(own, ours(scene, lights="file"))
    assert not np.array_equal(own, ours(scene, lights="default"))
    assert_close("lights_default_mode", own, command(tmp_path, path))


@needs_cli
def test_only_point_lights_cast_no_shadow_and_both_lets_the_key_cast_it(tmp_path):
    # No directional light in the file: no shadow with "file"; with "both"
    # the rig goes first and its key casts it, as in the command.
    path = lit_scene(tmp_path, LIGHTS[1:2], [{"translation": [0.3, 1.0, 1.2]}])
    scene = load_gltf(path)
    assert np.array_equal(ours(scene, lights="file", shadows=True),
                          ours(scene, lights="file", shadows=False))
    for mode in ("file", "both"):
        assert_close(f"lights_point_{mode}", ours(scene, lights=mode, shadows=True),
                     command(tmp_path, path, "--lights", mode, "--shadows", "on"))


def test_lights_made_in_python_light_as_the_files_do(tmp_path):
    scene = load_gltf(lit_scene(tmp_path))
    sun, point, spot, dark = scene.lights
    made = [softrast.Light.directional(SUN, color=(1.0, 0.85, 0.7), intensity=1.5),
            softrast.Light.point((0.3, 1.0, 1.2), color=(0.3, 0.5, 1.0), intensity=1.5,
                                 range=8),
            softrast.Light.spot(SPOT_AT, SPOT_TO, color=(0.2, 1.0, 0.3), intensity=6.0,
                                inner_cone=0.2, outer_cone=0.6)]
    for m, f in zip(made, (sun, point, spot)):
        assert m.type == f.type and m.node is None and f.node is not None
        assert np.allclose(m.direction if f.position is None else m.position,
                           f.direction if f.position is None else f.position, atol=1e-6)
        assert np.allclose(m.world[:3, 2], f.world[:3, 2], atol=1e-6)    # both shine down -Z
    a = ours(scene, lights="file", shadows=True)
    b = ours(scene, lights=made, shadows=True)
    diff = np.abs(a.astype(int) - b).max(-1)
    assert (diff > 1).mean() <= 0.001, "a light made in Python is a file's"
    # the file's own lights as a list, the dark one left out as the command does
    assert np.array_equal(ours(scene, lights=list(scene.lights), shadows=True), a)
    # a Scene given lights lights with them
    own = softrast.Scene(scene.instances, scene.cameras, made)
    assert np.array_equal(ours(own, shadows=True), b)
    # an empty list: the ambient light alone, darker than the file's
    assert ours(scene, lights=[]).astype(int).sum() < a.astype(int).sum()


def test_lights_are_checked(tmp_path):
    scene = load_gltf(lit_scene(tmp_path))
    with pytest.raises(ValueError, match="lights: must be"):
        ours(scene, lights="sun")
    with pytest.raises(TypeError, match=r"lights\[1\]: expected a softrast.Light"):
        ours(scene, lights=[scene.lights[0], (0, 1, 0)])
    with pytest.raises(ValueError, match="need shading='pbr'"):
        softrast.render(scene, camera=scene.cameras[0], width=8, height=8, lights="file")
    with pytest.raises(ValueError, match="outer_cone"):
        softrast.Light.spot((0, 0, 0), (0, -1, 0), outer_cone=2.0)
    with pytest.raises(ValueError, match="inner_cone"):
        softrast.Light.spot((0, 0, 0), (0, -1, 0), inner_cone=0.8, outer_cone=0.5)
    with pytest.raises(ValueError, match="direction: must not be zero"):
        softrast.Light.directional((0, 0, 0))
    with pytest.raises(ValueError, match="intensity"):
        softrast.Light.point((0, 0, 0), intensity=-1)
    with pytest.raises(ValueError, match="range"):
        softrast.Light.point((0, 0, 0), range=0)
    dark = softrast.Scene(scene.instances, scene.cameras, [scene.lights[3]])
    assert dark.lights[0].dark and dark.lights[0].type == "point"
    with pytest.warns(UserWarning, match="no lit lights"):
        ours(dark, lights="file")
    # "auto" on a scene without lit lights is the rig, without a warning
    assert np.array_equal(ours(dark), ours(dark, lights="default"))


@needs_cli
@pytest.mark.parametrize("exposure, tonemap, environment",
                         [(-1.5, "neutral", None), (1.0, "aces", None), (0.5, "none", "none")])
def test_exposure_tonemap_and_environment_match_the_command(tmp_path, exposure, tonemap,
                                                            environment):
    path = lit_scene(tmp_path)
    scene = load_gltf(path)
    a = ours(scene, exposure=exposure, tonemap=tonemap, environment=environment)
    args = ["--exposure", str(exposure), "--tonemap", tonemap]
    if environment:
        args += ["--environment", environment]
    assert_close(f"exposure_{exposure}_{tonemap}", a, command(tmp_path, path, *args))
    assert not np.array_equal(a, ours(scene))
    assert np.array_equal(ours(scene, exposure=0, tonemap="neutral"), ours(scene))


def test_exposure_and_tonemap_are_checked(tmp_path):
    scene = load_gltf(lit_scene(tmp_path))
    with pytest.raises(ValueError, match="exposure: must be in -20 .. 20"):
        ours(scene, exposure=30)
    with pytest.raises(TypeError, match="exposure: expected a number"):
        ours(scene, exposure="bright")
    with pytest.raises(ValueError, match="tonemap: must be"):
        ours(scene, tonemap="filmic")
    with pytest.raises(ValueError, match="need shading='pbr'"):
        softrast.render(scene, camera=scene.cameras[0], width=8, height=8, exposure=-1.0)
