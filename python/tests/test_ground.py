"""ground=True: softrast render's --ground shadow catcher under
shading="pbr": the key light's shadow over the background and nothing
else of the ground."""

import numpy as np
import pytest
import softrast

import gltf_build as gb
from conftest import assert_matches_command, load_gltf, needs_cli
from test_pbr_gltf import BACKGROUND, mat, save
from test_visibility import GEOMETRY


def box_scene(tmp_path, orthographic=False):
    """A box standing on nothing, and a camera looking down at it."""
    size = 1.4 if orthographic else 0.8
    return gb.write(tmp_path / "box.gltf", [(gb.box((0, 0.5, 0), 1.0), 0)],
                    [mat((0.8, 0.2, 0.1, 1))],
                    camera=((2.5, 2.6, 3.0), (0, 0.3, 0), size), orthographic=orthographic)


def test_the_shadow_darkens_the_background_and_nothing_else(tmp_path):
    scene = load_gltf(box_scene(tmp_path))
    light = (0.9, 0.9, 0.92)
    args = dict(camera=scene.cameras[0], width=96, height=72, shading="pbr", background=light,
                outputs=GEOMETRY + ("color", "rgba"))
    plain = softrast.render(scene, shadows=True, **args)
    caught = softrast.render(scene, ground=True, **args)
    assert np.array_equal(caught["color"], softrast.render(scene, ground=True, shadows=True,
                                                           **args)["color"]), "shadows on"
    save("ground.png", caught["color"])
    for name in GEOMETRY:
        assert caught[name].tobytes() == plain[name].tobytes(), name
    box = plain["mask"]
    assert np.array_equal(caught["color"][box], plain["color"][box]), "the box is as it was"
    bg = np.round(np.array(light) * 255).astype(int)
    assert (plain["color"][~box] == bg).all()
    c = caught["color"][~box].astype(int)
    dark = (c != bg).any(-1)
    assert dark.sum() > 100, "a shadow on the ground"
    assert (c[dark] < bg).all(), "only darker: black blended over"
    # Black at alpha a over the background: each channel bg (1 - a).
    a = 1 - c[dark] / bg
    assert np.abs(a - a.mean(-1, keepdims=True)).max() < 0.05
    # The key light comes from the viewer's upper left: the shadow falls to
    # the box's right.
    cols = np.nonzero(~box)[1][dark]
    assert cols.mean() > np.nonzero(box)[1].mean()
    # rgba: the background transparent, the shadow with its alpha.
    alpha = caught["rgba"][..., 3]
    assert (alpha[box] == 255).all() and (alpha[~box][~dark] == 0).all()
    assert (alpha[~box][dark] > 0).all()
    # Without shadows the ground shows nothing.
    assert np.array_equal(softrast.render(scene, ground=True, shadows=False, **args)["color"],
                          softrast.render(scene, **args)["color"])
    assert np.array_equal(softrast.render(scene, ground=True, threads=1, **args)["color"],
                          caught["color"]), "the same bytes on one thread"


def test_ground_is_checked(tmp_path):
    scene = load_gltf(box_scene(tmp_path))
    args = dict(camera=scene.cameras[0], width=8, height=8, outputs=("color",))
    with pytest.raises(ValueError, match="ground"):
        softrast.render(scene, ground=True, **args)
    for bad in ("yes", 1, None, np.array([True])):
        with pytest.raises(TypeError, match="ground"):
            softrast.render(scene, shading="pbr", ground=bad, **args)
    with pytest.raises(TypeError, match="shadows"):
        softrast.render(scene, shading="pbr", shadows="on", **args)


@needs_cli
@pytest.mark.parametrize("orthographic, aa", [(False, "none"), (True, "msaa4")])
def test_ground_matches_the_command(tmp_path, orthographic, aa):
    # softrast render --ground of the file's camera, perspective without
    # antialiasing and orthographic with MSAA.
    assert_matches_command(tmp_path, box_scene(tmp_path, orthographic),
                           f"ground_vs_cli_{orthographic}_{aa}", ["--ground", "--aa", aa],
                           shading="pbr", background=BACKGROUND, ground=True,
                           antialias=None if aa == "none" else aa)
