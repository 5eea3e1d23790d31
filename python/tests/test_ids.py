"""triangle_id and instance_id: the C library's own coverage, OpenCV's
projection, several instances, batches, and the same bytes for any thread
count."""

import numpy as np
import pytest
import softrast
from conftest import default_camera, pixel_rays, random_triangles

W, H = 200, 150


def test_triangle_id_matches_the_library_coverage():
    """The built-in pipeline (unlit, each face's ID in its vertex colors)
    draws the same faces where the ID program says they show."""
    rng = np.random.default_rng(7)
    verts, faces = random_triangles(rng, 300)
    ids = np.repeat(np.arange(len(faces)), 3)
    colors = np.column_stack([(ids & 255) / 255.0, (ids >> 8) / 255.0, np.zeros(len(ids))])
    mesh = softrast.Mesh(verts.astype(np.float32), faces, colors=colors.astype(np.float32))
    K, R, t = default_camera(W, H)
    out = softrast.render(mesh, K=K, R=R, t=t, width=W, height=H,
                          outputs=("color", "triangle_id", "mask"), shading="unlit",
                          background=(1.0, 1.0, 1.0))
    tri, color = out["triangle_id"], out["color"].astype(np.int64)
    decoded = np.where(color[..., 2] == 255, -1, color[..., 0] + 256 * color[..., 1])
    assert (tri >= 0).mean() > 0.3, "the triangles cover a good part of the image"
    assert np.array_equal(decoded, tri)
    assert np.array_equal(out["mask"], tri >= 0)


def test_opencv_projection_lands_on_the_face():
    """Face centroids projected with OpenCV's pinhole model in numpy land on
    pixels showing that face, at the depth and barycentrics of the ray."""
    rng = np.random.default_rng(3)
    # Small separated faces, each in its own cell of a grid, so none hides another.
    gx, gy = np.meshgrid(np.linspace(-1.6, 1.6, 12), np.linspace(-1.1, 1.1, 9))
    centres = np.column_stack([gx.ravel(), gy.ravel(), rng.uniform(3.0, 4.0, gx.size)])
    # Near-equilateral, about 7 px in radius: the pixel nearest to the
    # centroid has its centre inside the face.
    phase = rng.uniform(0, 2 * np.pi, (len(centres), 1)) + np.array([0, 2, 4]) * np.pi / 3
    offsets = np.stack([np.cos(phase), np.sin(phase), rng.uniform(-0.3, 0.3, phase.shape)], -1)
    corners = centres[:, None, :] + 0.1 * offsets
    verts = corners.reshape(-1, 3)
    faces = np.arange(len(verts), dtype=np.int32).reshape(-1, 3)
    # A camera that is not at the origin: world = camera frame rotated and moved.
    angle = 0.2
    Rz = np.array([[np.cos(angle), -np.sin(angle), 0], [np.sin(angle), np.cos(angle), 0], [0, 0, 1]])
    R, t = Rz, np.array([0.1, -0.2, 0.3])
    world = (verts - t) @ R          # R @ world + t == verts
    K = np.array([[260.0, 1.5, 97.2], [0.0, 250.0, 71.6], [0.0, 0.0, 1.0]])
    out = softrast.render(softrast.Mesh(world, faces), K=K, R=R, t=t, width=W, height=H,
                          outputs=("triangle_id", "depth", "barycentric"))
    cam = (R @ world.T).T + t
    centroid = cam.reshape(-1, 3, 3).mean(axis=1)
    uvw = centroid @ K.T
    u, v = uvw[:, 0] / uvw[:, 2], uvw[:, 1] / uvw[:, 2]
    inside = (u > -0.5) & (u < W - 0.5) & (v > -0.5) & (v < H - 0.5)
    assert inside.sum() > 50
    px, py = np.rint(u[inside]).astype(int), np.rint(v[inside]).astype(int)
    assert np.array_equal(out["triangle_id"][py, px], np.flatnonzero(inside))
    rays = pixel_rays(K, W, H)[py, px]
    c = cam.reshape(-1, 3, 3)[inside]
    n = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
    z = np.einsum("ij,ij->i", n, c[:, 0]) / np.einsum("ij,ij->i", n, rays)
    assert np.allclose(out["depth"][py, px], z, rtol=4e-7, atol=0)
    hit = rays * z[:, None]
    bary = out["barycentric"][py, px].astype(np.float64)
    assert np.allclose(np.einsum("ij,ijk->ik", bary, c), hit, atol=1e-5)
    assert np.allclose(bary.sum(axis=1), 1.0, atol=1e-6)


def test_instances_poses_and_ids():
    square = softrast.Mesh(np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], np.float32),
                           np.array([[0, 1, 2], [0, 2, 3]], np.int32))
    left = np.eye(4)
    left[:3, 3] = (-1.5, 0, 6)
    right = np.eye(4)
    right[:3, 3] = (1.5, 0, 5)
    right[:3, :3] *= 0.5
    scene = softrast.Scene([(square, left, 10), softrast.Instance(square, right, 20)])
    K, R, t = default_camera(W, H)
    out = softrast.render(scene, K=K, R=R, t=t, width=W, height=H,
                          outputs=("instance_id", "depth", "triangle_id"))
    inst = out["instance_id"]
    assert set(np.unique(inst)) == {-1, 10, 20}
    assert np.all(out["depth"][inst == 10] == np.float32(6))
    assert np.all(out["depth"][inst == 20] == np.float32(5))
    assert np.all((inst == -1) == (out["triangle_id"] == -1))
    # The right square is half the size: a quarter of the pixels, to the pixel.
    ratio = (inst == 20).sum() / (inst == 10).sum()
    assert abs(ratio - 0.25 * (6 / 5) ** 2) < 0.05


def test_batch_is_the_single_views_stacked():
    rng = np.random.default_rng(11)
    verts, faces = random_triangles(rng, 100)
    mesh = softrast.Mesh(verts, faces)
    cams = [softrast.look_at(eye=e, target=(0, 0, 4), width=W, height=H)
            for e in [(0, 0, 0), (0.5, 0.2, -0.5), (-0.4, 0.1, 0.2)]]
    Ks, Rs, ts = (np.stack(x) for x in zip(*cams))
    names = ("depth", "triangle_id", "normal", "barycentric", "mask", "color", "instance_id")
    batch = softrast.render(mesh, K=Ks, R=Rs, t=ts, width=W, height=H, outputs=names)
    ext = np.concatenate([Rs, ts[:, :, None]], axis=2)
    batch_ext = softrast.render(mesh, K=Ks[0], extrinsics=ext, width=W, height=H, outputs=names)
    for name in names:
        assert batch[name].shape[0] == 3
        assert np.array_equal(batch[name], batch_ext[name])
        for b, (K, R, t) in enumerate(cams):
            one = softrast.render(mesh, K=K, R=R, t=t, width=W, height=H, outputs=(name,))
            assert np.array_equal(one[name], batch[name][b]), name


def test_same_bytes_for_any_thread_count():
    rng = np.random.default_rng(5)
    verts, faces = random_triangles(rng, 3000, size=0.5)
    normals = rng.normal(size=verts.shape)
    mesh = softrast.Mesh(verts, faces, normals=normals / np.linalg.norm(normals, axis=1)[:, None],
                         uvs=rng.uniform(0, 1, (len(verts), 2)))
    K, R, t = default_camera(400, 300)
    names = tuple(softrast.OUTPUTS)
    runs = [softrast.render(mesh, K=K, R=R, t=t, width=400, height=300, outputs=names, threads=n)
            for n in (1, 2, 3)]
    for name in names:
        assert runs[0][name].tobytes() == runs[1][name].tobytes() == runs[2][name].tobytes(), name


def test_normals_in_camera_and_world_frames():
    # A square facing +z in world space, seen by a camera looking down -z.
    square = softrast.Mesh(np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], np.float64),
                           np.array([[0, 1, 2], [0, 2, 3]], np.int64))
    K, R, t = softrast.look_at(eye=(0, 0, 3), target=(0, 0, 0), width=64, height=48)
    cam = softrast.render(square, K=K, R=R, t=t, width=64, height=48, outputs=("normal", "mask"))
    world = softrast.render(square, K=K, R=R, t=t, width=64, height=48, outputs=("normal",),
                            normal_frame="world")
    m = cam["mask"]
    assert m.any()
    assert np.allclose(world["normal"][m], [0, 0, 1])
    assert np.allclose(cam["normal"][m], R @ [0, 0, 1])     # towards the camera: -z
    assert np.all(cam["normal"][~m] == 0)


@pytest.mark.parametrize("threads", [1, 0])
def test_python_threads_render_at_once(threads):
    """With the GIL released, views rendered on several Python threads at
    once are the views rendered one after another (the float64 mesh's
    float32 copy for the color pass made by each call)."""
    import concurrent.futures
    rng = np.random.default_rng(13)
    verts, faces = random_triangles(rng, 500)
    mesh = softrast.Mesh(verts, faces)
    cams = [softrast.look_at(eye=(0.1 * i, 0, 0), target=(0, 0, 4), width=W, height=H)
            for i in range(8)]

    def view(cam):
        K, R, t = cam
        return softrast.render(mesh, K=K, R=R, t=t, width=W, height=H,
                               outputs=("depth", "triangle_id", "color"), threads=threads)
    alone = [view(c) for c in cams]
    with concurrent.futures.ThreadPoolExecutor(4) as pool:
        together = list(pool.map(view, cams))
    for a, b in zip(alone, together):
        assert all(np.array_equal(a[name], b[name]) for name in a)


def _depth_and_ids(mesh, cam, size, threads):
    K, R, t = cam
    out = softrast.render(mesh, K=K, R=R, t=t, width=size[0], height=size[1],
                          outputs=("depth", "triangle_id", "normal"), threads=threads)
    return {name: a.tobytes() for name, a in out.items()}


_FORKED = {}


def _forked_view():
    """_depth_and_ids of _FORKED's arguments, in a forked child (a Mesh
    is not pickled: the child has the parent's memory)."""
    return _depth_and_ids(*_FORKED["args"])


def test_calls_carry_nothing_over():
    """render keeps its context, framebuffer and scratch from one call for
    the next: a view rendered after others (other sizes, meshes and thread
    counts) is the same bytes as when it is the first, also in a forked
    child, which cannot use its parent's pool threads."""
    import multiprocessing
    rng = np.random.default_rng(21)
    small = softrast.Mesh(*random_triangles(rng, 200))
    big = softrast.Mesh(*random_triangles(rng, 4000, size=0.4))
    cam = softrast.look_at(eye=(0.2, 0.1, 0), target=(0, 0, 4), width=W, height=H)
    first = _depth_and_ids(small, cam, (W, H), 2)
    _depth_and_ids(big, softrast.look_at(eye=(0, 0, 0), target=(0, 0, 4), width=320, height=200),
                   (320, 200), 2)
    _depth_and_ids(big, cam, (W, H), 1)
    assert _depth_and_ids(small, cam, (W, H), 2) == first
    _FORKED["args"] = (small, cam, (W, H), 2)
    with multiprocessing.get_context("fork").Pool(1) as pool:
        child = pool.apply_async(_forked_view).get(timeout=120)
    assert child == first
