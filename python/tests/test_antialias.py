"""antialias=: the color outputs multisampled or supersampled under every
shading, as softrast render's --aa; the geometry outputs untouched."""

import numpy as np
import pytest
import softrast

from conftest import assert_matches_command, default_camera, needs_cli
from test_pbr_gltf import BACKGROUND, materials_scene
from test_visibility import GEOMETRY

W, H = 96, 72
MODES = ("msaa2", "msaa4", "msaa8", "msaa16", "ssaa2", "ssaa3", "ssaa4")


def scene(count=14):
    """Overlapping equilateral triangles (no slivers: every part of a face
    is near a pixel centre it covers) of one color each, facing the
    camera."""
    rng = np.random.default_rng(31)
    centres = np.column_stack([rng.uniform(-1.5, 1.5, count), rng.uniform(-1.0, 1.0, count),
                               rng.uniform(3.0, 6.0, count)])
    angles = rng.uniform(0, 2 * np.pi, (count, 1)) + np.array([0, 2, 4]) * np.pi / 3
    radius = rng.uniform(0.4, 0.9, (count, 1))
    corners = centres[:, None, :] + np.stack([radius * np.cos(angles), radius * np.sin(angles),
                                              np.zeros_like(angles)], axis=-1)
    colors = np.repeat(rng.uniform(0.2, 1.0, (count, 3)), 3, axis=0).astype(np.float32)
    return softrast.Mesh(corners.reshape(-1, 3), np.arange(3 * count).reshape(-1, 3),
                         colors=colors)


def args(**kw):
    K, R, t = default_camera(W, H)
    return dict(K=K, R=R, t=t, width=W, height=H, background=(0.0, 0.0, 0.5), **kw)


def uniform(ids, r):
    """Where the (2 r + 1)^2 neighbourhood of a pixel holds its own ID alone."""
    pad = np.pad(ids, r, mode="edge")
    same = np.ones_like(ids, bool)
    for dy in range(2 * r + 1):
        for dx in range(2 * r + 1):
            same &= pad[dy:dy + ids.shape[0], dx:dx + ids.shape[1]] == ids
    return same


@pytest.mark.parametrize("shading", ["lit", "unlit", "pbr"])
@pytest.mark.parametrize("mode", MODES)
def test_edges_blend_and_geometry_stays(shading, mode):
    mesh = scene()
    outputs = GEOMETRY + ("color", "rgba")
    sharp = softrast.render(mesh, outputs=outputs, **args(shading=shading))
    smooth = softrast.render(mesh, outputs=outputs, antialias=mode, **args(shading=shading))
    for name in GEOMETRY:
        assert smooth[name].tobytes() == sharp[name].tobytes(), name
    assert np.array_equal(smooth["color"], smooth["rgba"][..., :3])
    tri = sharp["triangle_id"]
    # Away from the edges: pixels whose 5 x 5 neighbourhood shows one face
    # (or nothing); on them: pixels next to another face (or nothing).
    same, edge = uniform(tri, 2), ~uniform(tri, 1)
    alpha = smooth["rgba"][..., 3]
    assert (alpha[same & (tri < 0)] == 0).all() and (alpha[same & (tri >= 0)] == 255).all()
    partial = (alpha > 0) & (alpha < 255)
    assert partial.sum() > 40 and not (partial & same).any(), "partly covered: edge pixels only"
    assert (alpha[~sharp["mask"] & edge] > 0).mean() > 0.1, "coverage past the centre samples"
    changed = np.abs(smooth["color"].astype(int) - sharp["color"]).max(-1) > 2
    assert changed[edge].mean() > 0.2
    if shading == "unlit" or mode.startswith("msaa"):
        # Shaded once a pixel (MSAA) or with a constant color: away from
        # the edges nothing changes.
        assert np.array_equal(smooth["color"][same], sharp["color"][same])
    else:
        assert (~changed[same]).mean() > 0.95
    assert softrast.render(mesh, outputs=("color",), antialias=mode, threads=1,
                           **args(shading=shading))["color"].tobytes() == smooth["color"].tobytes()


def test_batches_and_default():
    mesh = scene()
    cams = [softrast.look_at(eye=e, target=(0, 0, 4), up=(0, -1, 0), fov_y=1.0, width=W,
                             height=H) for e in ((0, 0, 0), (0.3, 0.1, 0))]
    Rs, ts = np.stack([c[1] for c in cams]), np.stack([c[2] for c in cams])
    kw = dict(K=cams[0][0], width=W, height=H, outputs=("color",), antialias="msaa4")
    batch = softrast.render(mesh, R=Rs, t=ts, **kw)["color"]
    for b in range(2):
        assert np.array_equal(batch[b], softrast.render(mesh, R=Rs[b], t=ts[b], **kw)["color"])
    plain = softrast.render(mesh, **args(outputs=("color",)))["color"]
    for none in (None, "none"):
        assert np.array_equal(softrast.render(mesh, antialias=none,
                                              **args(outputs=("color",)))["color"], plain)


def test_antialias_is_checked():
    mesh = scene()
    for bad, error in (("msaa3", ValueError), ("MSAA4", ValueError), ("", ValueError),
                       (4, TypeError), (True, TypeError), (("msaa4",), TypeError)):
        with pytest.raises(error, match="antialias"):
            softrast.render(mesh, antialias=bad, **args())
    K, R, t = default_camera(4000, 8)
    with pytest.raises(ValueError, match="antialias"):
        softrast.render(mesh, K=K, R=R, t=t, width=4000, height=8, antialias="ssaa3")
    assert softrast.render(mesh, K=K, R=R, t=t, width=4000, height=8, antialias="ssaa2",
                           outputs=("color",))["color"].shape == (8, 4000, 3)


@needs_cli
@pytest.mark.parametrize("mode", ["msaa4", "ssaa2"])
def test_pbr_matches_the_commands_aa(tmp_path, mode):
    # The command's picture of a file's camera with the same --aa, as
    # test_pbr_gltf compares them without antialiasing.
    assert_matches_command(tmp_path, materials_scene(tmp_path), f"aa_vs_cli_{mode}",
                           ["--aa", mode, "--shadows", "off"], shading="pbr",
                           background=BACKGROUND, antialias=mode)
