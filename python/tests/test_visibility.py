"""The visibility pass (python/src/visibility.c), which draws the geometry
outputs of views that need no clipping, gives the bytes of the general
pass through the library's pipeline (the C renderer's general=True): the
same coverage, the same winner of equal depths, for any thread count."""

import functools

import numpy as np
import pytest
import softrast
from softrast import _softrast
from conftest import default_camera, random_triangles

W, H = 160, 120
GEOMETRY = ("depth", "triangle_id", "instance_id", "barycentric", "normal", "mask", "position",
            "material_id")


def render_both(scene, threads=(1, 2, 3, 0), **kw):
    """The general pass's outputs, after checking that the visibility pass
    gives exactly them on each thread count."""
    kw.setdefault("width", W)
    kw.setdefault("height", H)
    orig = _softrast.render
    _softrast.render = functools.partial(orig, general=True)
    try:
        want = softrast.render(scene, outputs=GEOMETRY, threads=1, **kw)
    finally:
        _softrast.render = orig
    for n in threads:
        got = softrast.render(scene, outputs=GEOMETRY, threads=n, **kw)
        for name in GEOMETRY:
            assert got[name].dtype == want[name].dtype
            assert got[name].tobytes() == want[name].tobytes(), (name, n)
    return want


def camera_at(eye, target=(0.0, 0.0, 4.0)):
    return dict(zip("KRt", softrast.look_at(eye=eye, target=target, up=(0.0, -1.0, 0.0),
                                            fov_y=1.0, width=W, height=H)))


def test_random_overlapping_triangles():
    rng = np.random.default_rng(11)
    verts, faces = random_triangles(rng, 400, size=0.8)
    K, R, t = default_camera(W, H)
    out = render_both(softrast.Mesh(verts.astype(np.float32), faces.astype(np.int32)),
                      K=K, R=R, t=t)
    assert (out["triangle_id"] >= 0).mean() > 0.5


def test_float64_int64_normals_and_instances():
    rng = np.random.default_rng(12)
    verts, faces = random_triangles(rng, 150)
    normals = rng.normal(size=verts.shape).astype(np.float32)
    a = softrast.Mesh(verts, faces, normals=normals)
    b = softrast.Mesh(verts.astype(np.float32), faces.astype(np.int32))
    pose = np.eye(4)
    pose[:3, 3] = (0.2, 0.1, 0.5)
    scene = [softrast.Instance(a, np.eye(4), 7), softrast.Instance(b, pose, 3),
             softrast.Instance(a, pose, 9)]
    out = render_both(scene, **camera_at((0.3, -0.2, -0.5)))
    assert set(np.unique(out["instance_id"])) == {-1, 3, 7, 9}


def test_equal_depths_keep_the_first_drawn():
    """The same face drawn twice, in one mesh and in two instances: the
    first of equal depths wins, as the depth test GREATER keeps it."""
    verts = np.array([[-1, -1, 3], [1, -1, 3], [0, 1, 3.5]], np.float32)
    faces = np.array([[0, 1, 2], [0, 1, 2], [2, 1, 0]], np.int32)
    mesh = softrast.Mesh(verts, faces)
    K, R, t = default_camera(W, H)
    out = render_both(mesh, K=K, R=R, t=t)
    assert set(np.unique(out["triangle_id"])) == {-1, 0}
    out = render_both([(mesh, np.eye(4), 5), (mesh, np.eye(4), 6)], K=K, R=R, t=t)
    assert set(np.unique(out["instance_id"])) == {-1, 5}


def test_a_dense_mesh_of_subpixel_faces():
    """Most faces cover no pixel centre, many one: the case the box test
    and the pre-setup test are for, with shared vertices."""
    n = 180
    theta, phi = np.meshgrid(np.linspace(0, np.pi, n + 1), np.linspace(0, 2 * np.pi, n + 1))
    r = 1 + 0.1 * np.sin(5 * theta) * np.cos(7 * phi)
    verts = np.stack([r * np.sin(theta) * np.cos(phi), r * np.cos(theta),
                      4 + r * np.sin(theta) * np.sin(phi)], -1).reshape(-1, 3)
    idx = np.arange((n + 1) * (n + 1)).reshape(n + 1, n + 1)
    quads = np.stack([idx[:-1, :-1], idx[1:, :-1], idx[1:, 1:], idx[:-1, 1:]], -1).reshape(-1, 4)
    faces = np.ascontiguousarray(np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]]))
    mesh = softrast.Mesh(verts.astype(np.float32), faces.astype(np.int32))
    for eye in [(0.0, 0.0, 0.0), (2.5, -1.0, 1.5), (0.5, 3.9, 4.0)]:
        out = render_both(mesh, **camera_at(eye))
        assert (out["triangle_id"] >= 0).any()


@pytest.mark.parametrize("eye", [(0.0, 0.0, 3.0), (0.0, 0.0, 4.0)])
def test_views_that_need_clipping(eye):
    """A camera among the faces: faces crossing the near plane send the
    view to the general pass, faces wholly behind it are dropped."""
    rng = np.random.default_rng(13)
    verts, faces = random_triangles(rng, 300, depth_range=(2.0, 6.0))
    out = render_both(softrast.Mesh(verts, faces), **camera_at(eye, (0.0, 0.0, 9.0)))
    assert (out["triangle_id"] >= 0).any()


def test_degenerate_offscreen_and_hidden_faces():
    """A face without area, one off the image, one behind the camera (all
    three vertices outside the near plane: dropped without clipping)."""
    rng = np.random.default_rng(14)
    verts, faces = random_triangles(rng, 100)
    verts = np.concatenate([verts, [[0, 0, 4], [0, 0, 4], [1, 1, 4], [40, 0, 4], [41, 0, 4],
                                    [40, 1, 4], [0, 0, -5], [1, 0, -5], [0, 1, -5]]])
    n = len(verts)
    faces = np.concatenate([faces, np.arange(n - 9, n).reshape(3, 3)])
    K, R, t = default_camera(W, H)
    render_both(softrast.Mesh(verts, faces), K=K, R=R, t=t)


def test_empty_scene_and_empty_mesh():
    K, R, t = default_camera(W, H)
    empty = softrast.Mesh(np.zeros((0, 3), np.float32), np.zeros((0, 3), np.int32))
    out = render_both(empty, K=K, R=R, t=t)
    assert (out["triangle_id"] == -1).all() and np.isinf(out["depth"]).all()
    out = render_both([], K=K, R=R, t=t)
    assert not out["mask"].any()


@pytest.mark.parametrize("level", ["off", "avx2"])
def test_every_simd_level(monkeypatch, level):
    """The vertices are classified sixteen at a time where the CPU has
    AVX-512, one at a time otherwise (SR_SIMD lowers the level): the
    same bytes."""
    monkeypatch.setenv("SR_SIMD", level)
    rng = np.random.default_rng(15)
    verts, faces = random_triangles(rng, 300, size=0.8)
    K, R, t = default_camera(W, H)
    render_both(softrast.Mesh(verts.astype(np.float32), faces.astype(np.int32)), K=K, R=R, t=t)


def test_cull_back_faces():
    """cull="back" leaves out the faces whose normal points away from the
    camera (clockwise on screen), turned round by a mirroring pose: in
    both passes alike, and in color too."""
    rng = np.random.default_rng(16)
    verts, faces = random_triangles(rng, 300, size=0.8)
    corners = verts[faces]
    normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    away = np.einsum("ij,ij->i", normal, corners[:, 0])   # camera at the origin
    clear = np.abs(away) > 1e-3 * np.linalg.norm(normal, axis=1) * np.linalg.norm(corners[:, 0],
                                                                                 axis=1)
    mesh = softrast.Mesh(verts, faces)
    K, R, t = default_camera(W, H)
    shown = render_both(mesh, K=K, R=R, t=t)["triangle_id"]
    assert (away[shown[shown >= 0]] > 0).any()   # back faces show without culling
    culled = render_both(mesh, K=K, R=R, t=t, cull="back")["triangle_id"]
    ids = culled[culled >= 0]
    assert ids.size and not (clear[ids] & (away[ids] > 0)).any()
    color = softrast.render(mesh, K=K, R=R, t=t, width=W, height=H, cull="back",
                            outputs=("color", "triangle_id"))
    assert np.array_equal(color["triangle_id"], culled)
    assert np.array_equal(color["color"].any(axis=2), culled >= 0)
    # Mirrored in x about the optical axis: clockwise on screen is now the
    # faces' front, and the same faces show their front to the camera.
    flip = np.diag([-1.0, 1.0, 1.0, 1.0])
    mirrored = render_both([(mesh, flip, 0)], K=K, R=R, t=t, cull="back")["triangle_id"]
    ids = mirrored[mirrored >= 0]
    assert ids.size and not (clear[ids] & (away[ids] > 0)).any()


def test_cull_back_faces_orthographic():
    """Under an orthographic camera (every ray along +z) the back faces
    are those whose normal has z > 0; the vertices take the scalar path
    there, the same bytes in both passes."""
    rng = np.random.default_rng(17)
    verts, faces = random_triangles(rng, 300, size=0.8)
    corners = verts[faces]
    normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    clear = np.abs(normal[:, 2]) > 1e-3 * np.linalg.norm(normal, axis=1)
    mesh = softrast.Mesh(verts.astype(np.float32), faces.astype(np.int32))
    cam = dict(K=np.array([[30.0, 0.0, 80.0], [0.0, 30.0, 60.0], [0.0, 0.0, 1.0]]), R=np.eye(3),
               t=np.zeros(3), projection="orthographic")
    shown = render_both(mesh, **cam)["triangle_id"]
    assert (normal[shown[shown >= 0], 2] > 0).any()
    culled = render_both(mesh, cull="back", **cam)["triangle_id"]
    ids = culled[culled >= 0]
    assert ids.size and not (clear[ids] & (normal[ids, 2] > 0)).any()


def boundary_faces(rng, width, height):
    """Faces on a 1/256-pixel grid of a camera whose pixel centres are
    the integer (u, v): sub-pixel faces with a vertex or an edge exactly
    on a centre (both windings), faces reaching past the image's border,
    faces thousands of pixels across that cover one corner centre, faces
    without area, and small random faces, in (u, v) pixels."""
    tris = []
    for u, v in rng.integers(1, (width - 1, height - 1), (60, 2)):
        for d in rng.integers(1, 129, 3) / 256:
            tris += [[(u, v), (u + d, v), (u, v + d)],            # vertex on the centre
                     [(u - d, v), (u + d, v), (u, v + d)],        # edge through it
                     [(u - d, v), (u, v - d), (u + d, v)],
                     [(u - d, v - d), (u + d, v + d), (u + d, v - d)],   # diagonal edge
                     [(u + d, v + d), (u, v), (u, v + 2 * d)]]
    for u in (0, width - 1):
        for v in rng.integers(0, height, 8):
            d = rng.integers(1, 384) / 256
            tris += [[(u - d, v), (u + d, v), (u, v + d)], [(u, v - d), (u, v + d), (u + d, v)],
                     [(u + d, v - d), (u, v + d), (u - d, v)]]
    for v in (0, height - 1):
        for u in rng.integers(0, width, 8):
            d = rng.integers(1, 384) / 256
            tris += [[(u, v - d), (u + d, v + d), (u - d, v)], [(u - d, v), (u, v), (u, v + d)]]
    for u, v in rng.integers(1, (width - 1, height - 1), (20, 2)):
        tris += [[(u, v), (u, v), (u + 1, v)], [(u, v), (u + 0.5, v), (u + 1, v)],
                 [(u, v + 0.5), (u, v + 0.5), (u, v + 0.5)]]
    # Faces thousands of pixels across whose box is one corner centre.
    for (u, v), (su, sv) in [((0, 0), (1, 1)), ((width - 1, height - 1), (-1, -1)),
                             ((width - 1, 0), (-1, 1)), ((0, height - 1), (1, -1))]:
        for t, size in zip((0, 1 / 256, 0.5) * 2, (200, 500, 3000, 7000, 10000, 14000)):
            a = (u + su * t, v + sv * t)
            b, c = (a[0], v - sv * size), (u - su * size, a[1])
            tris += [[a, b, c], [a, c, b]]
    centres = rng.integers(0, 256 * np.array([width, height]), (400, 1, 2)) / 256
    tris += list(centres + rng.integers(-300, 301, (400, 3, 2)) / 256)
    tris = np.array(tris, np.float64)
    return tris[rng.permutation(len(tris))]


@pytest.mark.parametrize("level", ["off", "avx2"])
def test_faces_at_pixel_centres_and_borders(monkeypatch, level):
    """The faces' first look (eight at a time in lanes where the CPU has
    AVX2) drops only faces that cover no pixel centre or are culled: on
    faces straddling a centre exactly, touching the border or without
    area, at depths that overlap, in meshes of sizes that are not
    multiples of 8, the bytes of the general pass."""
    monkeypatch.setenv("SR_SIMD", level)
    rng = np.random.default_rng(18)
    f = 64.0
    K = np.array([[f, 0.0, W / 2], [0.0, f, H / 2], [0.0, 0.0, 1.0]])
    uv = boundary_faces(rng, W, H)
    z = np.repeat(rng.integers(2, 6, (len(uv), 1, 1)).astype(np.float64), 3, axis=1)
    xy = (uv - K[:2, 2]) / f * z   # exact: a power-of-two focal length
    verts = np.concatenate([xy, z], axis=2).reshape(-1, 3)
    faces = np.arange(len(verts)).reshape(-1, 3)
    meshes = [softrast.Mesh(verts[:3 * m], faces[:m].astype(dtype))
              for m, dtype in [(len(faces), np.int64), (8 * (len(faces) // 8) - 3, np.int32),
                               (13, np.int32), (7, np.int64)]]
    cam = dict(K=K, R=np.eye(3), t=np.zeros(3))
    for cull in ("none", "back"):
        shown = [(render_both(mesh, cull=cull, **cam)["triangle_id"] >= 0).sum()
                 for mesh in meshes]
        assert shown[0] >= shown[1] > 0
        # Scaled about the camera: the same pixels, nearer (exactly).
        scene = [softrast.Instance(m, np.diag([s, s, s, 1.0]), i)
                 for i, (m, s) in enumerate(zip(meshes[1:], (1.0, 0.5, 0.25)))]
        out = render_both(scene, cull=cull, **cam)
        assert len(np.unique(out["instance_id"])) > 2
