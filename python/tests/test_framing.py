"""Cameras fitted to a scene: render() without a camera is softrast render's
default camera (fit_camera, the library's sr_fit_camera), and orbit()'s
turntable batches see the whole scene, evenly spaced."""

import math
import os
import platform
import subprocess

import numpy as np
import pytest
import softrast

import gltf_build as gb
from conftest import CLI, MODELS, load_gltf, needs_cli

BACKGROUND = (0x1d / 255, 0x22 / 255, 0x30 / 255)   # softrast render's default


def save(name, image):
    out = os.environ.get("SR_TEST_OUT")
    if out:
        softrast.write_png(os.path.join(out, name), image)


def assert_same_picture(ours, theirs):
    """The same bytes on x86-64; elsewhere, where the compiler may round
    the two programs' float arithmetic differently, within 2 codes on all
    but 0.5% of the pixels, as the other comparisons with the command."""
    if platform.machine() in ("x86_64", "AMD64"):
        assert np.array_equal(ours, theirs), f"{np.any(ours != theirs, -1).sum()} pixels differ"
    else:
        diff = np.abs(ours.astype(int) - theirs).max(-1)
        assert (diff > 2).mean() <= 0.005, f"{(diff > 2).mean():.2%} of the pixels differ"


def mat(color):
    return {"pbrMetallicRoughness": {"baseColorFactor": list(color), "metallicFactor": 0.0,
                                      "roughnessFactor": 0.6}}


def floor_and_box(tmp_path):
    """A floor and a box off its centre: a glTF file whose nodes have no
    transform, so that the command and load() frame the same floats."""
    return gb.write(tmp_path / "floor_box.gltf",
                    [(gb.quad((0, 0, 0), 4.0, "y", uv=False), 0),
                     (gb.box((0.4, 0.5, -0.4), 0.8), 1)],
                    [mat((0.8, 0.8, 0.8, 1)), mat((0.6, 0.3, 0.2, 1))])


def command(path, width, height, *args):
    """softrast render's picture of path with its default camera, RGB."""
    png = os.path.join(os.path.dirname(path), "cli.png")
    subprocess.run([CLI, "render", str(path), "--size", f"{width}x{height}", *args, "-o", png],
                   check=True, capture_output=True)
    return softrast.read_image(png)[..., :3]


def cube_mesh(lo=(-1.0, -0.5, -2.0), hi=(2.0, 1.0, 0.5)):
    lo, hi = np.asarray(lo), np.asarray(hi)
    v = np.array([[hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1],
                   hi[2] if i & 4 else lo[2]] for i in range(8)])
    f = np.array([[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
                  [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]], np.int32)
    return softrast.Mesh(v, f)


@needs_cli
@pytest.mark.parametrize("size", [(160, 120), (90, 160)])
@pytest.mark.parametrize("shading,args,kw", [
    ("pbr", ["--aa", "none"], {}),
    ("pbr", ["--aa", "msaa4"], {"antialias": "msaa4"}),
    ("unlit", ["--aa", "none", "--shading", "unlit"], {}),
])
def test_no_camera_is_the_commands_default_camera(tmp_path, size, shading, args, kw):
    # The same picture as the command's, byte for byte, where the shading
    # is the same: render() frames with the command's own sr_fit_camera.
    path = floor_and_box(tmp_path)
    width, height = size
    theirs = command(path, width, height, *args)
    ours = softrast.render(load_gltf(path), width=width, height=height, shading=shading,
                           background=BACKGROUND, outputs=("color",), **kw)["color"]
    save(f"framing_vs_cli_{shading}_{kw.get('antialias', 'none')}_{width}x{height}.png",
         np.concatenate([ours, theirs], 1))
    assert_same_picture(ours, theirs)


@needs_cli
@pytest.mark.parametrize("model", ["suzanne.obj", "cow.obj"])
def test_lit_default_camera_covers_the_commands_pixels(tmp_path, model):
    # "lit" is a headlight the command does not have: its pixels differ, but
    # the camera is the command's, so the surface covers exactly the pixels
    # the command draws (with the command's back-face culling).
    path = os.path.join(MODELS, model)
    if not os.path.exists(path):
        pytest.skip(f"{path} is missing")
    png = tmp_path / "cli.png"
    subprocess.run([CLI, "render", path, "--size", "160x120", "--aa", "none", "--shading",
                    "phong", "-o", str(png)], check=True, capture_output=True)
    theirs = softrast.read_image(png)[..., :3]
    mesh = softrast.load(path)
    out = softrast.render(mesh, width=160, height=120, cull="back", outputs=("color", "mask"))
    covered = np.any(theirs != theirs[0, 0], axis=-1)
    assert out["mask"].sum() > 1000
    assert np.array_equal(out["mask"], covered)
    # And render() without a camera is render() with fit_camera's.
    cam = softrast.fit_camera(mesh, width=160, height=120)
    again = softrast.render(mesh, camera=cam, width=160, height=120, cull="back",
                            outputs=("color", "mask"))
    assert np.array_equal(out["color"], again["color"])


@needs_cli
def test_orthographic_default_camera_is_the_commands(tmp_path):
    path = floor_and_box(tmp_path)
    theirs = command(path, 160, 120, "--aa", "none", "--ortho")
    ours = softrast.render(load_gltf(path), width=160, height=120, shading="pbr",
                           projection="orthographic", background=BACKGROUND,
                           outputs=("color",))["color"]
    save("framing_vs_cli_ortho.png", np.concatenate([ours, theirs], 1))
    assert_same_picture(ours, theirs)


def project(K, R, t, points):
    cam = points @ R.T + t
    assert np.all(cam[:, 2] > 0)
    uvw = cam @ K.T
    return uvw[:, :2] / uvw[:, 2:]


@pytest.mark.parametrize("size", [(160, 120), (90, 160)])
def test_fit_camera_fills_the_limiting_side_less_the_margin(size):
    width, height = size
    mesh = cube_mesh()
    cam = softrast.fit_camera(mesh, width=width, height=height)
    assert cam.type == "perspective" and cam.index is None
    K = cam.intrinsics(width, height)
    uv = project(K, cam.R, cam.t, np.asarray(mesh.vertices))
    # Pixel edges at -1/2 and width - 1/2: the projection's span in each
    # dimension as a fraction of the image, and its margins.
    left, right = uv[:, 0].min() + 0.5, width - 0.5 - uv[:, 0].max()
    top, bottom = uv[:, 1].min() + 0.5, height - 0.5 - uv[:, 1].max()
    margins = np.array([[left / width, right / width], [top / height, bottom / height]])
    limit = int(np.argmin(margins.min(axis=1)))
    assert np.allclose(margins[limit], 0.05, atol=1e-4)
    assert margins[1 - limit].min() >= 0.05 - 1e-4
    assert abs(margins[1 - limit][0] - margins[1 - limit][1]) < 1e-3
    # The view from the front right, above, with +y up the image.
    back = np.asarray(cam.R[2]) * -1
    assert np.allclose(back, np.array([0.62, 0.48, 1.0]) / np.linalg.norm([0.62, 0.48, 1.0]),
                       atol=1e-6)
    assert cam.R[1] @ [0, 1, 0] < 0      # OpenCV's y points down the image
    # render() without a camera draws from it, every output.
    a = softrast.render(mesh, width=width, height=height, outputs=("depth", "triangle_id"))
    b = softrast.render(mesh, camera=cam, width=width, height=height,
                        outputs=("depth", "triangle_id"))
    assert np.array_equal(a["depth"], b["depth"])
    assert np.array_equal(a["triangle_id"], b["triangle_id"])


def test_fit_camera_frames_every_instance_as_posed():
    mesh = cube_mesh((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5))
    pose = np.eye(4)
    pose[:3, 3] = (3.0, 0.0, 0.0)
    scene = softrast.Scene([mesh, (mesh, pose)])
    cam = softrast.fit_camera(scene, width=200, height=100)
    K = cam.intrinsics(200, 100)
    both = np.concatenate([np.asarray(mesh.vertices), np.asarray(mesh.vertices) + pose[:3, 3]])
    uv = project(K, cam.R, cam.t, both)
    assert uv[:, 0].min() > 0 and uv[:, 0].max() < 199 and uv[:, 1].min() > 0
    assert uv[:, 1].max() < 99
    # The right-hand cube is in the right half of the image.
    right = project(K, cam.R, cam.t, np.asarray(mesh.vertices) + pose[:3, 3])
    assert right[:, 0].mean() > 100


def world_corners(scene):
    v = np.concatenate([np.asarray(i.mesh.vertices) @ i.pose[:3, :3].T + i.pose[:3, 3]
                        for i in scene])
    lo, hi = v.min(0), v.max(0)
    return np.array([[hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1],
                      hi[2] if i & 4 else lo[2]] for i in range(8)]), (lo + hi) / 2


@pytest.mark.parametrize("size", [(96, 64), (64, 96)])
@pytest.mark.parametrize("elevation", [None, 0.0, -0.6, 1.2])
def test_orbit_sees_the_whole_box_evenly_spaced(size, elevation):
    width, height = size
    scene = softrast.Scene([cube_mesh(), (cube_mesh((0, 0, 0), (0.3, 2.5, 0.3)),
                                          np.diag([1.0, 1.0, 1.0, 1.0]))])
    n = 7
    K, R, t = softrast.orbit(scene, n, width=width, height=height, elevation=elevation)
    assert K.shape == (n, 3, 3) and R.shape == (n, 3, 3) and t.shape == (n, 3)
    corners, centre = world_corners(scene)
    eyes = np.einsum("vji,vj->vi", R, -t)           # -R^T t
    margins = []
    for k, r, tt in zip(K, R, t):
        uv = project(k, r, tt, corners)
        assert np.all(uv >= -0.5) and np.all(uv[:, 0] <= width - 0.5)
        assert np.all(uv[:, 1] <= height - 0.5)
        margins.append(min((uv[:, 0].min() + 0.5) / width, (width - 0.5 - uv[:, 0].max()) / width,
                           (uv[:, 1].min() + 0.5) / height,
                           (height - 0.5 - uv[:, 1].max()) / height))
        # Each looks at the box's centre, +y up the image.
        assert np.allclose(project(k, r, tt, centre[None]), [[(width - 1) / 2, (height - 1) / 2]])
    # The fitted distance: every corner inside less the 5% margin, one on it.
    assert min(margins) == pytest.approx(0.05, abs=1e-9)
    offsets = eyes - centre
    dist = np.linalg.norm(offsets, axis=1)
    assert np.allclose(dist, dist[0])
    el = np.arcsin(offsets[:, 1] / dist)
    want_el = math.asin(0.48 / np.linalg.norm([0.62, 0.48, 1.0])) if elevation is None \
        else elevation
    assert np.allclose(el, want_el)
    az = np.arctan2(offsets[:, 0], offsets[:, 2])
    steps = np.mod(np.diff(az), 2 * math.pi)
    assert np.allclose(steps, 2 * math.pi / n)
    if elevation is None:
        # View 0 looks from the default camera's direction.
        assert np.allclose(offsets[0] / dist[0], np.array([0.62, 0.48, 1.0]) /
                           np.linalg.norm([0.62, 0.48, 1.0]))


def test_orbit_batch_is_each_view_alone():
    mesh = cube_mesh()
    K, R, t = softrast.orbit(mesh, 5, width=64, height=48, elevation=0.4, azimuth=0.3,
                             fov_y=0.9, distance=9.0)
    outputs = ("color", "depth", "triangle_id", "normal")
    batch = softrast.render(mesh, K=K, R=R, t=t, width=64, height=48, outputs=outputs)
    for i in range(5):
        one = softrast.render(mesh, K=K[i], R=R[i], t=t[i], width=64, height=48, outputs=outputs)
        for name in outputs:
            assert batch[name][i].tobytes() == one[name].tobytes(), name
    eyes = np.einsum("vji,vj->vi", R, -t)
    corners, centre = world_corners(softrast.Scene([mesh]))
    assert np.allclose(np.linalg.norm(eyes - centre, axis=1), 9.0)
    assert K[0, 1, 1] == pytest.approx(24 / math.tan(0.45))
    # Views differ: the turntable turns.
    assert not np.array_equal(batch["triangle_id"][0], batch["triangle_id"][1])


def test_bad_arguments_name_the_argument():
    mesh = cube_mesh()
    empty = softrast.Mesh(np.zeros((0, 3), np.float32), np.zeros((0, 3), np.int32))
    kw = dict(width=32, height=32)
    for bad, exc, name in [(0, ValueError, "n"), (-3, ValueError, "n"), (2.0, TypeError, "n"),
                           (True, TypeError, "n"), ("4", TypeError, "n")]:
        with pytest.raises(exc, match=f"^{name}:"):
            softrast.orbit(mesh, bad, **kw)
    for arg, value, exc in [("elevation", float("nan"), ValueError),
                            ("elevation", math.pi / 2, ValueError),
                            ("elevation", "high", TypeError),
                            ("azimuth", float("inf"), ValueError),
                            ("fov_y", 0.0, ValueError), ("fov_y", float("nan"), ValueError),
                            ("distance", -1.0, ValueError), ("distance", float("nan"), ValueError),
                            ("width", 0, ValueError)]:
        args = dict(kw, **{arg: value})
        with pytest.raises(exc, match=arg):
            softrast.orbit(mesh, 4, **args)
    with pytest.raises(ValueError, match="^scene:"):
        softrast.orbit(empty, 4, **kw)
    with pytest.raises(TypeError, match="^scene:"):
        softrast.orbit("mesh.obj", 4, **kw)
    with pytest.raises(ValueError, match="^scene:"):
        softrast.fit_camera(empty, **kw)
    with pytest.raises(ValueError, match="^scene:"):
        softrast.render(empty, **kw)
    point = softrast.Mesh(np.ones((3, 3), np.float32), np.array([[0, 1, 2]], np.int32))
    with pytest.raises(ValueError, match="^scene:"):
        softrast.fit_camera(point, **kw)
    with pytest.raises(ValueError, match="^scene:"):
        softrast.orbit(point, 3, **kw)
    for arg, value, exc in [("fov", float("nan"), ValueError), ("fov", 4.0, ValueError),
                            ("fov", "wide", TypeError), ("projection", "fisheye", ValueError),
                            ("height", -2, ValueError)]:
        with pytest.raises(exc, match=arg):
            softrast.fit_camera(mesh, **dict(kw, **{arg: value}))
    with pytest.raises(TypeError, match="^K:"):
        softrast.render(mesh, R=np.eye(3), t=np.zeros(3), **kw)
    with pytest.raises(ValueError, match="^projection:"):
        softrast.render(mesh, projection="fisheye", **kw)
