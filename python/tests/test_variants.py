"""softrast.load(path, variant=...): a glTF file's material variants
(KHR_materials_variants) named on the scene, and the chosen variant's
base colors in the instances' materials and in the pixels, for the
colour pass and shading="pbr"."""

import json
import pickle

import numpy as np
import pytest
import softrast

import gltf_build as gb
from conftest import load_gltf


def unlit(rgb):
    return {"pbrMetallicRoughness": {"baseColorFactor": list(rgb) + [1.0]},
            "extensions": {"KHR_materials_unlit": {}}}


# Own materials: magenta (left quad), yellow (right); the variants' red,
# green, blue.  "Red" maps both quads, "Green" only the left one.
COLORS = [(1, 0, 1), (1, 1, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]


def variants_file(tmp_path):
    path = gb.write(tmp_path / "variants.gltf",
                    [(gb.quad((-0.55, 0, 0), 1.0, uv=False), 0),
                     (gb.quad((0.55, 0, 0), 1.0, uv=False), 1)],
                    [unlit(c) for c in COLORS])
    doc = json.loads(path.read_text())
    doc["extensionsUsed"] = ["KHR_materials_unlit", "KHR_materials_variants"]
    doc["extensions"] = {"KHR_materials_variants": {
        "variants": [{"name": "Red"}, {"name": "Green"}]}}
    maps = [[{"material": 2, "variants": [0]}, {"material": 3, "variants": [1]}],
            [{"material": 4, "variants": [0]}]]
    for mesh, mappings in zip(doc["meshes"], maps):
        mesh["primitives"][0]["extensions"] = {
            "KHR_materials_variants": {"mappings": mappings}}
    path.write_text(json.dumps(doc))
    return path


def halves(scene, shading):
    """The centre pixels of the left and the right quad, seen from +z."""
    K, R, t = softrast.look_at(eye=(0, 0, 3), target=(0, 0, 0), width=64, height=32, fov_y=0.7)
    color = softrast.render(scene, K=K, R=R, t=t, width=64, height=32, shading=shading,
                            outputs=("color",))["color"]
    return tuple(tuple(int(c) for c in color[16, x, :3]) for x in (24, 40))


@pytest.mark.parametrize("shading", ["unlit", "pbr"])
def test_the_chosen_variants_base_colors_are_drawn(tmp_path, shading):
    path = variants_file(tmp_path)
    want = {None: (COLORS[0], COLORS[1]), "Red": (COLORS[2], COLORS[4]),
            0: (COLORS[2], COLORS[4]), "Green": (COLORS[3], COLORS[1]),
            1: (COLORS[3], COLORS[1])}
    for variant, (left, right) in want.items():
        scene = load_gltf(path) if variant is None else softrast.load(path, variant=variant)
        assert scene.variants == ("Red", "Green")
        bases = [tuple(inst.material.base_color[:3].tolist()) for inst in scene.instances]
        assert bases == [left, right], variant
        got = halves(scene, shading)
        # pbr's tone curve keeps an unlit color's channels apart: over 200
        # where the base color has 1, under 60 where it has 0.
        for pixel, rgb in zip(got, (left, right)):
            assert all(p > 200 if c else p < 60 for p, c in zip(pixel, rgb)), (variant, got)


def test_a_pickled_scene_keeps_its_variant(tmp_path):
    scene = softrast.load(variants_file(tmp_path), variant="Green")
    again = pickle.loads(pickle.dumps(scene))
    assert again.variants == ("Red", "Green")
    assert halves(again, "pbr") == halves(scene, "pbr")


def test_unknown_variants_name_the_files_variants(tmp_path):
    path = variants_file(tmp_path)
    with pytest.raises(ValueError, match=r"variant 'Purple': no such variant "
                                         r"\(the file has \['Red', 'Green'\]\)"):
        softrast.load(path, variant="Purple")
    with pytest.raises(ValueError, match="variant 2: no such variant"):
        softrast.load(path, variant=2)
    with pytest.raises(TypeError, match="variant: expected a str, an int or None"):
        softrast.load(path, variant=True)
    plain = gb.write(tmp_path / "plain.gltf", [(gb.quad((0, 0, 0), 1.0), 0)], [unlit((1, 1, 1))])
    assert load_gltf(plain).variants == ()
    with pytest.raises(ValueError, match="the file has no material variants"):
        softrast.load(plain, variant="Red")
    obj = tmp_path / "tri.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    assert softrast.load(obj).variants == ()
    with pytest.raises(ValueError, match="the file has no material variants"):
        softrast.load(obj, variant=0)
