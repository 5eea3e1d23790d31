"""A glTF texture's sampler (wrap and filters), KHR_texture_transform and
coordinate set as softrast.load and render draw them: the same pixels as
softrast render of the file, under every shading both have."""

import json

import numpy as np
import pytest

import gltf_build
from conftest import assert_matches_command, load_gltf, needs_cli

REPEAT, MIRRORED_REPEAT, CLAMP_TO_EDGE = 10497, 33648, 33071
NEAREST, LINEAR = 9728, 9729
W, H = 96, 96


def texels():
    """A 4 x 4 RGBA image, every texel its own colour, so that a texel
    sampled from the wrong place shows."""
    ramp = np.array([20, 90, 160, 230], np.uint8)
    img = np.empty((4, 4, 4), np.uint8)
    img[..., 0] = ramp[None, :]
    img[..., 1] = ramp[:, None]
    img[..., 2] = ramp[::-1][None, :] // 2 + ramp[::-1][:, None] // 2
    img[..., 3] = 255
    return img


# Each case: the base color texture's info, its sampler, and the quad's
# coordinate sets (glTF's uv, v down) 0 and 1.
WIDE = np.array([[-1, 2], [2, 2], [2, -1], [-1, -1]], np.float32)
UNIT = np.array([[0, 1], [1, 1], [1, 0], [0, 0]], np.float32)
CASES = {
    "mirror_clamp": ({"index": 0}, {"wrapS": MIRRORED_REPEAT, "wrapT": CLAMP_TO_EDGE,
                                    "magFilter": NEAREST}, WIDE, None),
    "mirror_clamp_linear": ({"index": 0}, {"wrapS": MIRRORED_REPEAT, "wrapT": CLAMP_TO_EDGE,
                                           "magFilter": LINEAR}, WIDE, None),
    "transform": ({"index": 0, "extensions": {"KHR_texture_transform": {
        "offset": [0.3, -0.2], "rotation": 0.4, "scale": [1.7, 0.8]}}},
        {"wrapS": REPEAT, "wrapT": MIRRORED_REPEAT, "magFilter": NEAREST}, UNIT, None),
    "texcoord1": ({"index": 0, "texCoord": 1, "extensions": {"KHR_texture_transform": {
        "offset": [0.1, 0.25], "scale": [2.0, 2.0], "texCoord": 1}}},
        {"wrapS": CLAMP_TO_EDGE, "wrapT": MIRRORED_REPEAT, "magFilter": NEAREST}, UNIT, WIDE),
    # Set 1 named but absent: set 0 is read, as the library's programs do.
    "texcoord1_absent": ({"index": 0, "texCoord": 1}, {"magFilter": NEAREST}, WIDE, None),
}


def sampled_scene(tmp_path, case):
    info, sampler, uvs, uvs1 = CASES[case]
    prim = gltf_build.quad((0, 0, 0), 2.0)
    prim["uvs"] = uvs
    if uvs1 is not None:
        prim["uvs1"] = uvs1
    material = {"pbrMetallicRoughness": {"baseColorTexture": info, "metallicFactor": 0.0,
                                         "roughnessFactor": 0.6}}
    path = gltf_build.write(tmp_path / f"{case}.gltf", [(prim, 0)], [material], [texels()],
                            camera=((0, 0, 2.6), (0, 0, 0), 0.9),
                            textures=[{"source": 0, "sampler": 0}], samplers=[sampler])
    doc = json.loads(path.read_text())
    doc["extensionsUsed"] = ["KHR_texture_transform"]
    path.write_text(json.dumps(doc))
    return path


@needs_cli
@pytest.mark.parametrize("shading", ["pbr", "unlit"])
@pytest.mark.parametrize("case", sorted(CASES))
def test_sampled_texture_matches_the_command(tmp_path, case, shading):
    assert_matches_command(tmp_path, sampled_scene(tmp_path, case), f"sampler_{case}_{shading}",
                           ["--aa", "none", "--shadows", "off", "--shading", shading,
                            "--background", "#000000"], width=W, height=H, shading=shading)


@pytest.mark.parametrize("case", sorted(CASES))
def test_loaded_material_keeps_the_sampler(tmp_path, case):
    _, sampler, _, _ = CASES[case]
    m = load_gltf(sampled_scene(tmp_path, case)).instances[0].material
    names = {REPEAT: "repeat", MIRRORED_REPEAT: "mirror", CLAMP_TO_EDGE: "clamp"}
    assert (m.wrap_u, m.wrap_v) == (names[sampler.get("wrapS", REPEAT)], names[sampler.get("wrapT", REPEAT)])
    assert m.texture_filter == ("nearest" if sampler["magFilter"] == NEAREST else "trilinear")
