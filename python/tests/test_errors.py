"""Bad arguments raise TypeError or ValueError naming the argument, and
never crash; the version and docstrings."""

import os
import re

import numpy as np
import pytest
import softrast

V = np.array([[-1, -1, 3], [1, -1, 3], [0, 1, 3]], np.float32)
F = np.array([[0, 1, 2]], np.int32)
K = np.array([[50.0, 0, 15.5], [0, 50.0, 11.5], [0, 0, 1]])
R, T = np.eye(3), np.zeros(3)


@pytest.mark.parametrize("kwargs, error, name", [
    (dict(vertices=V[:, :2]), ValueError, "vertices"),
    (dict(vertices=V.astype(np.int32)), TypeError, "vertices"),
    (dict(vertices=V.astype(np.float16)), TypeError, "vertices"),
    (dict(vertices=np.asfortranarray(np.tile(V, (1, 1)))[:, ::-1]), ValueError, "vertices"),
    (dict(vertices=np.array([[0, 0, np.nan], [1, 0, 0], [0, 1, 0]])), ValueError, "vertices"),
    (dict(vertices="not an array"), TypeError, "vertices"),
    (dict(faces=F.astype(np.float32)), TypeError, "faces"),
    (dict(faces=F.astype(np.uint8)), TypeError, "faces"),
    (dict(faces=np.array([[0, 1, 3]], np.int32)), ValueError, "faces"),
    (dict(faces=np.array([[0, -1, 2]], np.int64)), ValueError, "faces"),
    (dict(faces=np.array([[0, -1, 2]], np.int32)), ValueError, "faces"),
    (dict(faces=np.array([0, 1, 2], np.int32)), ValueError, "faces"),
    (dict(faces=np.array([[0, 1, 2, 0, 1, 2]], np.int32)[:, ::2]), ValueError, "faces"),
    (dict(normals=np.zeros((2, 3))), ValueError, "normals"),
    (dict(normals=np.full((3, 3), np.inf)), ValueError, "normals"),
    (dict(colors=np.zeros((3, 5))), ValueError, "colors"),
    (dict(uvs=np.zeros((3, 3))), ValueError, "uvs"),
    (dict(uvs=np.zeros((3, 2)), texture=np.zeros((4, 4, 3), np.float32)), TypeError, "texture"),
    (dict(uvs=np.zeros((3, 2)), texture=np.zeros((4, 4, 2), np.uint8)), ValueError, "texture"),
    (dict(texture=np.zeros((4, 4, 3), np.uint8)), ValueError, "texture"),
])
def test_bad_mesh(kwargs, error, name):
    args = dict(vertices=V, faces=F)
    args.update(kwargs)
    with pytest.raises(error, match=name):
        softrast.Mesh(**args)


MESH = softrast.Mesh(V, F)
NAN_R = np.eye(3)
NAN_R[0, 0] = np.nan


@pytest.mark.parametrize("kwargs, error, name", [
    (dict(K=np.eye(2)), ValueError, "K"),
    (dict(K=np.array([[50.0, 0, 15.5], [0, 50.0, 11.5], [0, 0, 2]])), ValueError, "K"),
    (dict(K=np.array([[-50.0, 0, 15.5], [0, 50.0, 11.5], [0, 0, 1]])), ValueError, "K"),
    (dict(K=np.full((3, 3), np.nan)), ValueError, "K"),
    (dict(K="K"), TypeError, "K"),
    (dict(R=NAN_R), ValueError, "R"),
    (dict(R=2 * np.eye(3)), ValueError, "R"),
    (dict(R=np.diag([1.0, 1.0, -1.0])), ValueError, "R"),
    (dict(R=np.eye(3)[None].repeat(2, 0), t=np.zeros((3, 3))), ValueError, "R, t"),
    (dict(t=np.array([0.0, np.nan, 0.0])), ValueError, "t"),
    (dict(t=np.zeros(4)), ValueError, "t"),
    (dict(R=None), TypeError, "R, t"),
    (dict(extrinsics=np.zeros((3, 4))), TypeError, "extrinsics"),
    (dict(width=0), ValueError, "width"),
    (dict(width=10000), ValueError, "width"),
    (dict(height=2.5), TypeError, "height"),
    (dict(outputs="depth"), TypeError, "outputs"),
    (dict(outputs=("depth", "zbuffer")), ValueError, "outputs"),
    (dict(outputs=()), ValueError, "outputs"),
    (dict(threads=-1), ValueError, "threads"),
    (dict(near=0.0), ValueError, "near"),
    (dict(near=float("nan")), ValueError, "near"),
    (dict(normal_frame="object"), ValueError, "normal_frame"),
    (dict(shading="toon"), ValueError, "shading"),
    (dict(cull="front"), ValueError, "cull"),
    (dict(background=(1, 2)), ValueError, "background"),
    (dict(scene=V), TypeError, "scene"),
    (dict(scene=[(MESH, np.full((4, 4), np.nan))]), ValueError, "pose"),
    (dict(scene=[(MESH, np.zeros((4, 4)))]), ValueError, "pose"),
    (dict(scene=[(MESH, np.eye(3))]), ValueError, "pose"),
    (dict(scene=[(MESH, None, -3)]), ValueError, "instance_id"),
    (dict(scene=[(MESH, None, "a")]), TypeError, "instance_id"),
    (dict(scene=[42]), TypeError, "instances"),
])
def test_bad_render_arguments(kwargs, error, name):
    args = dict(scene=MESH, K=K, R=R, t=T, width=32, height=24, outputs=("depth",))
    args.update(kwargs)
    scene = args.pop("scene")
    with pytest.raises(error, match=name):
        softrast.render(scene, **args)


def test_faces_changed_after_the_mesh_was_made():
    faces = F.copy()
    mesh = softrast.Mesh(V, faces)
    faces[0, 1] = 1000
    with pytest.raises(ValueError, match="faces"):
        softrast.render(mesh, K=K, R=R, t=T, width=32, height=24, outputs=("depth",))


@pytest.mark.parametrize("dtype", [np.int32, np.int64])
@pytest.mark.parametrize("bad", [-1, 3, 2**31 - 1])
def test_the_first_bad_face_of_many_is_named(dtype, bad):
    """Faces are checked a block at a time (int32 by the library's
    vectorized index maximum): the message names the first bad face."""
    faces = np.tile(F, (5000, 1)).astype(dtype)
    mesh = softrast.Mesh(V, faces)
    faces[4321, 2] = faces[4400, 0] = bad
    with pytest.raises(ValueError, match="face 4321 has an index outside"):
        softrast.render(mesh, K=K, R=R, t=T, width=32, height=24, outputs=("depth",))


def test_c_render_checks_its_output_arrays():
    from softrast import _softrast
    good = np.empty((24, 32), np.float32)
    inst = [(MESH, np.hstack([np.eye(3), np.zeros((3, 1))]), np.eye(3), 0)]
    for bad, name in [(np.empty((24, 31), np.float32), "depth"), (np.empty((24, 32)), "depth"),
                      (np.empty((32, 24), np.float32).T, "depth")]:
        with pytest.raises((TypeError, ValueError), match=name):
            _softrast.render(inst, K, 32, 24, 1e-3, 1, bad, None, None, None, None, None, None,
                             (0, 0, 0), True)
    readonly = good.copy()
    readonly.flags.writeable = False
    with pytest.raises(ValueError, match="depth"):
        _softrast.render(inst, K, 32, 24, 1e-3, 1, readonly, None, None, None, None, None, None,
                         (0, 0, 0), True)
    with pytest.raises(TypeError, match="instances"):
        _softrast.render([(MESH,)], K, 32, 24, 1e-3, 1, good, None, None, None, None, None, None,
                         (0, 0, 0), True)


def test_empty_mesh_renders_background():
    mesh = softrast.Mesh(np.zeros((0, 3)), np.zeros((0, 3), np.int64))
    out = softrast.render(mesh, K=K, R=R, t=T, width=32, height=24,
                          outputs=("depth", "triangle_id", "mask"))
    assert np.isinf(out["depth"]).all() and (out["triangle_id"] == -1).all()
    assert not out["mask"].any()


def test_mesh_is_initialized_once():
    mesh = softrast.Mesh(V, F)
    with pytest.raises(TypeError, match="Mesh"):
        mesh.__init__(V, F)
    assert mesh.vertices is V


def test_zero_copy():
    verts = V.astype(np.float64)
    faces = F.astype(np.int64)
    mesh = softrast.Mesh(verts, faces)
    assert mesh.vertices is verts and mesh.faces is faces


def test_mesh_pickles_by_value():
    import pickle
    mesh = softrast.Mesh(V, F, colors=np.ones((3, 3), np.float32))
    copy = pickle.loads(pickle.dumps(mesh))
    assert np.array_equal(copy.vertices, V) and np.array_equal(copy.faces, F)
    assert copy.normals is None and np.array_equal(copy.colors, mesh.colors)
    with pytest.raises(ValueError, match="uninitialized"):
        pickle.dumps(softrast.Mesh.__new__(softrast.Mesh))


def test_version_and_docstrings():
    cmake = open(os.path.join(os.path.dirname(__file__), "..", "..", "CMakeLists.txt")).read()
    project = re.search(r"project\(softrast\s+VERSION\s+([0-9.]+)", cmake)
    assert project and softrast.__version__ == project.group(1)
    for name in softrast.__all__:
        if name != "__version__" and name != "OUTPUTS":
            assert (getattr(softrast, name).__doc__ or "").strip(), f"{name} has no docstring"
    with pytest.raises(ValueError, match="alpha_mode"):
        softrast.Material(alpha_mode="glass")


def test_library_message_for_a_call_without_a_context():
    # The extension raises the library's message (sr_last_error) for a call
    # that had no context to hold one: here sr_make_context refusing a
    # thread count, which the public functions refuse before it.
    from softrast import _softrast
    with pytest.raises(ValueError, match=r"^environment: sr_context_desc\.threads must be in "
                                         r"0\.\.64 \(got -1\)$"):
        _softrast.make_environment("", 1.0, -1)
