"""Booleans given for numbers: numpy would read True as 1 and False as 0,
which is never what a bool array for intrinsics, a pose, vertices or a
color means, so every numeric array argument of the API refuses a bool
dtype (or a list of bools) with a TypeError naming the argument."""

import numpy as np
import pytest
import softrast

V = np.array([[-1, -1, 3], [1, -1, 3], [0, 1, 3]], np.float32)
F = np.array([[0, 1, 2]], np.int32)
K = np.array([[50.0, 0, 15.5], [0, 50.0, 11.5], [0, 0, 1]])
R, T = np.eye(3), np.zeros(3)
B3 = np.eye(3, dtype=bool)
MESH = softrast.Mesh(V, F)


def render(**kwargs):
    args = dict(K=K, R=R, t=T, width=32, height=24, outputs=("depth",))
    args.update(kwargs)
    softrast.render(MESH, **args)


@pytest.mark.parametrize("call, name", [
    (lambda: render(K=B3), "K"),
    (lambda: render(K=np.stack([B3, B3])), "K"),
    (lambda: render(R=B3), "R"),
    (lambda: render(t=np.zeros(3, bool)), "t"),
    (lambda: render(t=[False, False, True]), "t"),
    (lambda: render(t=np.zeros((2, 3), bool)), "t"),
    (lambda: render(R=None, t=None, extrinsics=np.eye(4, dtype=bool)), "extrinsics"),
    (lambda: render(background=(True, False, True)), "background"),
    (lambda: softrast.Mesh(V.astype(bool), F), "vertices"),
    (lambda: softrast.Mesh(V.astype(bool).tolist(), F), "vertices"),
    (lambda: softrast.Mesh(V, F.astype(bool)), "faces"),
    (lambda: softrast.Mesh(V, [[False, True, True]]), "faces"),
    (lambda: softrast.Mesh(V, F, normals=np.ones((3, 3), bool)), "normals"),
    (lambda: softrast.Mesh(V, F, normals=[[True] * 3] * 3), "normals"),
    (lambda: softrast.Mesh(V, F, colors=np.ones((3, 3), bool)), "colors"),
    (lambda: softrast.Mesh(V, F, colors=[[True] * 4] * 3), "colors"),
    (lambda: softrast.Mesh(V, F, uvs=np.ones((3, 2), bool)), "uvs"),
    (lambda: softrast.Mesh(V, F, uvs=np.zeros((3, 2)), texture=np.ones((2, 2, 3), bool)),
     "texture"),
    (lambda: softrast.Instance(MESH, pose=np.eye(4, dtype=bool)), "pose"),
    (lambda: softrast.Scene().add(MESH, pose=np.eye(4, dtype=bool).tolist()), "pose"),
    (lambda: softrast.look_at(eye=[False, False, False], target=(0, 0, 1), width=8, height=8),
     "eye"),
    (lambda: softrast.look_at(eye=(0, 0, 0), target=np.array([0, 0, 1], bool), width=8,
                              height=8), "target"),
    (lambda: softrast.look_at((0, 0, 0), (0, 0, 1), np.array([0, 1, 0], bool), width=8,
                              height=8), "up"),
    (lambda: softrast.Camera.perspective(np.array([1, 0, 0], bool), (0, 0, 0)), "eye"),
    (lambda: softrast.Camera.orthographic((1, 0, 0), (0, 0, 0), (True, False, False), ymag=1),
     "up"),
    (lambda: softrast.Material(base_color=np.ones(4, bool)), "base_color"),
    (lambda: softrast.Material(base_color=[1, 1, 1, True]), "base_color"),
    (lambda: softrast.Material(emissive=(True, False, False)), "emissive"),
    (lambda: softrast.Material(metallic=True), "metallic"),
    (lambda: softrast.Material(roughness=np.bool_(False)), "roughness"),
    (lambda: softrast.Canvas(8, 8).fill(np.array([[0, 0], [1, 0], [0, 1]], bool), "red"),
     "shape"),
    (lambda: softrast.Canvas(8, 8).fill([[0, 0], [1, 0], [0, 1]], (True, False, False)),
     "paint"),
    (lambda: softrast.Canvas(8, 8, background=np.array([1, 1, 1], bool)), "background"),
    (lambda: softrast.Path().add_polygon([[True, False], [False, True], [True, True]]),
     "points"),
    (lambda: softrast.Canvas.from_array(np.zeros((4, 4, 4), bool)), "image"),
    (lambda: softrast.Pattern(np.zeros((4, 4, 4), bool)), "image"),
    (lambda: softrast.LinearGradient((0, 0), (1, 0), [(0, "red")],
                                     transform=np.array([[1, 0, 0], [0, 1, 0]], bool)),
     "transform"),
    (lambda: softrast.LinearGradient((0, 0), (1, 0), [(0, (True, True, False))]),
     r"stops\[0\] color"),
    (lambda: softrast.write_png("never.png", np.zeros((2, 2, 4), bool)), "image"),
    (lambda: softrast.write_png("never.png", np.zeros((2, 2, 4), bool).tolist()), "image"),
    # numpy's bool scalars, which float() reads as 0 and 1, like bool
    (lambda: softrast.Path().move_to(np.bool_(True), 0), "x"),
    (lambda: softrast.Path(tolerance=np.bool_(True)), "tolerance"),
    (lambda: softrast.Canvas(8, 8).stroke(softrast.Path(), "red", width=np.bool_(True)),
     "width"),
    (lambda: softrast.Canvas(8, 8).translate(np.bool_(True), 0), "tx"),
])
def test_bool_arrays_are_refused_by_name(call, name):
    with pytest.raises(TypeError, match=f"^{name}: .*bool"):
        call()


def test_numbers_of_other_dtypes_still_work():
    # The check is of booleans only: integer arrays and lists of ints
    # are read as numbers, as before.
    softrast.render(MESH, K=K.astype(np.int64), R=R.astype(np.int8), t=[0, 0, 0], width=8,
                    height=8, outputs=("depth",))
    softrast.Instance(MESH, pose=np.eye(4, dtype=np.int32).tolist())
    softrast.Material(base_color=[1, 1, 1, 1], metallic=0)
    softrast.Mesh(V.tolist(), F.tolist())
