"""Orthographic views: rays parallel to the optical axis, pixel (u, v)
seeing u = fx x + s y + cx, v = fy y + cy, depth still camera z.  Depth of
planes and spheres against their analytic depth, a vertex's projection
against the face the pixel shows, every output on both geometry passes,
batches, cameras made with Camera.orthographic and read from glTF files,
and the color against softrast render's picture of a file's orthographic
camera."""

import numpy as np
import pytest
import softrast

import gltf_build as gb
from conftest import assert_matches_command, load_gltf, needs_cli, random_triangles
from test_depth import camera, icosphere, largest_sagitta
from test_visibility import GEOMETRY, render_both

W, H = 160, 120
EPS32 = np.finfo(np.float32).eps


def pixel_points(K, width=W, height=H):
    """(H, W, 2) camera x, y of the orthographic rays through the pixel centres."""
    u, v = np.meshgrid(np.arange(width, dtype=np.float64), np.arange(height, dtype=np.float64))
    y = (v - K[1, 2]) / K[1, 1]
    return np.stack([(u - K[0, 2] - K[0, 1] * y) / K[0, 0], y], axis=-1)


def plane_depth(xy, p0, p1, p2):
    """Camera z of the plane through p0, p1, p2 above each (x, y)."""
    n = np.cross(p1 - p0, p2 - p0)
    return p0[2] - ((xy - p0[:2]) @ n[:2]) / n[2]


def ortho_K(fx=15.0, fy=14.0, s=0.7, cx=83.3, cy=57.9):
    """Skewed, off-centre, non-square: pixels per unit."""
    return np.array([[fx, s, cx], [0.0, fy, cy], [0.0, 0.0, 1.0]])


def test_plane_depth_is_exact_to_float32():
    rng = np.random.default_rng(21)
    _, R, t = camera(rng)
    K = ortho_K()
    cam = np.array([[-9.0, -7.0, 3.0], [9.0, -7.0, 5.0], [9.0, 7.0, 8.0], [-9.0, 7.0, 6.0]])
    world = (cam - t) @ R
    mesh = softrast.Mesh(world, np.array([[0, 1, 2], [0, 2, 3]], np.int32))
    out = render_both(mesh, K=K, R=R, t=t, projection="orthographic")
    depth = out["depth"]
    assert depth.dtype == np.float32 and depth.shape == (H, W)
    assert out["mask"].all(), "the quad covers the image"
    xy = pixel_points(K)
    want = plane_depth(xy, *cam[:3])
    rel = np.abs(depth.astype(np.float64) - want) / want
    assert rel.max() < 4 * EPS32, rel.max()
    # The barycentrics give back the point: (x, y) of the pixel's ray, z its depth.
    tri = out["triangle_id"]
    corners = cam[np.array([[0, 1, 2], [0, 2, 3]])[tri]]
    point = np.einsum("hwk,hwkc->hwc", out["barycentric"].astype(np.float64), corners)
    assert np.abs(point[..., :2] - xy).max() < 1e-5
    assert np.abs(point[..., 2] - want).max() < 1e-5
    # The normal: the face's, in the camera frame, towards which it runs
    # counter-clockwise.
    n = np.cross(cam[1] - cam[0], cam[2] - cam[0])
    assert np.abs(out["normal"] - n / np.linalg.norm(n)).max() < 1e-6


def test_depth_is_camera_z_whatever_the_distance():
    # The same plane seen from 10 and from 1000 units along the axis: the
    # same pixels (no perspective), depths 990 apart.
    quad = np.array([[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.5], [-1.0, 1.0, 0.5]])
    mesh = softrast.Mesh(quad, np.array([[0, 1, 2], [0, 2, 3]], np.int32))
    K = np.array([[40.0, 0, (W - 1) / 2], [0, 40.0, (H - 1) / 2], [0, 0, 1]])
    a, b = (softrast.render(mesh, K=K, R=np.eye(3), t=(0, 0, d), width=W, height=H,
                            projection="orthographic", outputs=("depth", "triangle_id"))
            for d in (10.0, 1000.0))
    assert np.array_equal(a["triangle_id"], b["triangle_id"])
    hit = a["triangle_id"] >= 0
    assert hit.sum() == 80 * 80, "2 units across at 40 pixels a unit"
    assert np.allclose(b["depth"][hit] - a["depth"][hit], 990.0, rtol=0, atol=1e-3)
    assert a["depth"][hit].min() >= 10.0 and a["depth"][hit].max() <= 10.5


def test_sphere_depth():
    verts, faces = icosphere(4)
    radius, centre = 1.5, np.array([0.2, -0.1, 5.0])
    mesh = softrast.Mesh(verts * radius + centre, faces)
    K = np.array([[40.0, 0, (W - 1) / 2], [0, 40.0, (H - 1) / 2], [0, 0, 1]])
    out = render_both(mesh, K=K, R=np.eye(3), t=np.zeros(3), projection="orthographic")
    depth, tri = out["depth"], out["triangle_id"]
    xy = pixel_points(K)
    # The sphere along +z from (x, y, 0): z = cz - sqrt(r^2 - rho^2).
    rho2 = ((xy - centre[:2]) ** 2).sum(-1)
    hit = rho2 < radius ** 2
    sphere = np.where(hit, centre[2] - np.sqrt(np.maximum(radius ** 2 - rho2, 0)), np.inf)
    covered = tri >= 0
    # Coverage agrees a pixel inside the outline, and nothing outside it.
    assert covered[rho2 < (radius - 0.05) ** 2].all()
    assert not covered[~hit].any()
    # The mesh lies inside the sphere: behind it along the ray by at most
    # the sagitta over the cosine of the ray's angle with the normal
    # (the ray being +z, the cosine is the normal's z).
    sagitta = largest_sagitta(verts, faces, radius)
    both = covered & hit
    cos = (centre[2] - sphere[both]) / radius
    d = depth[both].astype(np.float64) - sphere[both]
    assert d.min() > -1e-6 * centre[2], d.min()
    facing = cos > 0.5
    assert facing.sum() > 3000
    assert (d[facing] <= sagitta / cos[facing]).all()
    # Each pixel's depth is the plane of the face it names, to float32 rounding.
    q = verts[faces[tri[covered]]] * radius + centre
    n = np.cross(q[:, 1] - q[:, 0], q[:, 2] - q[:, 0])
    want = q[:, 0, 2] - np.einsum("ij,ij->i", xy[covered] - q[:, 0, :2], n[:, :2]) / n[:, 2]
    rel = np.abs(depth[covered] - want) / want
    assert rel.max() < 4 * EPS32, rel.max()
    assert np.isinf(depth[~covered]).all()
    # The normals of a sphere (face normals, no vertex normals given) face
    # the camera: -z.
    assert (out["normal"][covered][:, 2] < 0).all()


def project(K, p):
    """OpenCV's orthographic projection in numpy: (..., 3) camera points to (..., 2) pixels."""
    return np.stack([K[0, 0] * p[..., 0] + K[0, 1] * p[..., 1] + K[0, 2],
                     K[1, 1] * p[..., 1] + K[1, 2]], axis=-1)


def test_projected_vertex_lands_on_its_face():
    # Random triangles, world to camera by a random pose, projected in
    # numpy: the pixel nearest each face's projected centroid, where its
    # centre lies inside the projected face, shows that face or a nearer
    # one; and every pixel's visible point (its barycentrics' mix of the
    # corners) projects onto the pixel's centre.
    rng = np.random.default_rng(22)
    verts, faces = random_triangles(rng, 60, size=0.3)
    _, R, t = camera(rng)
    K = ortho_K(fx=30.0, fy=32.0, s=1.5, cx=80.2, cy=60.1)
    world = (verts - t) @ R
    out = softrast.render(softrast.Mesh(world, faces), K=K, R=R, t=t, width=W, height=H,
                          projection="orthographic", outputs=("triangle_id", "depth", "barycentric"))
    cam = world @ R.T + t
    corners = project(K, cam[faces])                       # (M, 3, 2)
    centre = np.rint(corners.mean(1))
    xy = pixel_points(K)
    checked = 0
    for f in range(len(faces)):
        px, py = int(centre[f, 0]), int(centre[f, 1])
        if not (0 <= px < W and 0 <= py < H):
            continue
        a, b, c = corners[f]
        edges = [np.cross(q - p, centre[f] - p) for p, q in ((a, b), (b, c), (c, a))]
        if not (all(e > 1e-3 for e in edges) or all(e < -1e-3 for e in edges)):
            continue
        shown = out["triangle_id"][py, px]
        mine = plane_depth(xy[py, px], *cam[faces[f]])
        if shown == f:
            checked += 1
            assert abs(out["depth"][py, px] - mine) <= 4 * EPS32 * mine
        else:
            assert shown >= 0 and out["depth"][py, px] <= mine, "a nearer face hides it"
    assert checked > 25
    hit = out["triangle_id"] >= 0
    point = np.einsum("nk,nkc->nc", out["barycentric"][hit].astype(np.float64),
                      cam[faces[out["triangle_id"][hit]]])
    v, u = np.nonzero(hit)
    assert np.abs(project(K, point) - np.column_stack([u, v])).max() < 1e-3


def test_batches_and_every_output():
    rng = np.random.default_rng(23)
    verts, faces = random_triangles(rng, 120, size=0.5)
    normals = rng.normal(size=verts.shape).astype(np.float32)
    mesh = softrast.Mesh(verts, faces, normals=normals,
                         colors=rng.uniform(size=(len(verts), 3)).astype(np.float32))
    pose = np.eye(4)
    pose[:3, 3] = (0.3, -0.2, 0.4)
    scene = [softrast.Instance(mesh, np.eye(4), 5), softrast.Instance(mesh, pose, 8)]
    Ks = np.stack([ortho_K(), ortho_K(fx=25.0, fy=25.0, s=0.0, cx=79.5, cy=59.5)])
    Rs = np.stack([camera(rng)[1] for _ in range(2)])
    ts = np.array([[0.0, 0.0, 2.0], [0.1, 0.0, 3.0]])
    outputs = GEOMETRY + ("color", "rgba")
    batch = softrast.render(scene, K=Ks, R=Rs, t=ts, width=W, height=H, outputs=outputs,
                            projection="orthographic")
    for b in range(2):
        alone = softrast.render(scene, K=Ks[b], R=Rs[b], t=ts[b], width=W, height=H,
                                outputs=outputs, projection="orthographic", threads=1)
        for name in outputs:
            assert batch[name].shape == (2,) + alone[name].shape
            assert batch[name][b].tobytes() == alone[name].tobytes(), (name, b)
        render_both(scene, K=Ks[b], R=Rs[b], t=ts[b], projection="orthographic")
        ids = alone["instance_id"]
        assert set(np.unique(ids)) == {-1, 5, 8}
        assert np.array_equal(alone["mask"], ids >= 0)
        assert np.array_equal(alone["mask"], alone["rgba"][..., 3] > 0)
        # The color pass draws exactly the faces triangle_id names.
        assert np.array_equal(alone["mask"], alone["color"].any(-1))


def test_near_clips():
    quad = np.array([[-1.0, -1.0, 1.0], [1.0, -1.0, 1.0], [1.0, 1.0, 3.0], [-1.0, 1.0, 3.0]])
    mesh = softrast.Mesh(quad, np.array([[0, 1, 2], [0, 2, 3]], np.int32))
    K = np.array([[40.0, 0, (W - 1) / 2], [0, 40.0, (H - 1) / 2], [0, 0, 1]])
    args = dict(K=K, R=np.eye(3), t=np.zeros(3), width=W, height=H, projection="orthographic",
                outputs=("depth", "color"))
    full = softrast.render(mesh, **args)["depth"]
    cut = softrast.render(mesh, near=2.0, **args)
    hit = np.isfinite(full)
    assert hit.sum() == 80 * 80
    vis = np.isfinite(cut["depth"])
    assert not (vis & ~hit).any() and vis[hit & (full > 2.0 + 1e-3)].all()
    assert (full[vis] >= 2.0 - 1e-3).all()
    assert np.array_equal(cut["depth"][vis], full[vis]), "the face's own depth, not the cut's"
    assert 0.4 < vis.sum() / hit.sum() < 0.6
    assert np.array_equal(cut["color"].any(-1), vis)
    render_both(mesh, near=2.0, **{k: v for k, v in args.items() if k != "outputs"})
    # Behind the camera's plane nothing shows; at the default near 0 the
    # whole quad does, wherever the camera's plane is.
    behind = softrast.render(mesh, **dict(args, t=(0, 0, -5)))["depth"]
    assert np.isinf(behind).all()


def test_look_at_and_camera_orthographic():
    K, R, t = softrast.look_at((0, 0, 5), (0, 0, 0), ymag=2.0, width=W, height=H)
    assert K[0, 0] == K[1, 1] == H / 4.0 and K[0, 2] == (W - 1) / 2
    cam = softrast.Camera.orthographic((0, 0, 5), (0, 0, 0), ymag=2.0)
    assert cam.type == "orthographic" and cam.index is None and cam.znear == 0.0
    assert np.allclose(cam.R, R) and np.allclose(cam.t, t)
    assert np.array_equal(cam.intrinsics(W, H), K)
    quad = np.array([[-3.0, -3.0, 0.0], [3.0, -3.0, 0.0], [3.0, 3.0, 0.0], [-3.0, 3.0, 0.0]])
    mesh = softrast.Mesh(quad, np.array([[0, 1, 2], [0, 2, 3]], np.int32))
    a = softrast.render(mesh, camera=cam, width=W, height=H, outputs=("depth",))["depth"]
    b = softrast.render(mesh, K=K, R=R, t=t, width=W, height=H, projection="orthographic",
                        outputs=("depth",))["depth"]
    assert np.array_equal(a, b) and np.all(a == 5.0)
    # A batch of a perspective and an orthographic camera.
    persp = softrast.Camera.perspective((0, 0, 5), (0, 0, 0), yfov=0.5)
    both = softrast.render(mesh, camera=[persp, cam], width=W, height=H, outputs=("depth",))
    assert np.array_equal(both["depth"][1], a)
    Kp, Rp, tp = softrast.look_at((0, 0, 5), (0, 0, 0), fov_y=0.5, width=W, height=H)
    assert np.array_equal(both["depth"][0], softrast.render(
        mesh, K=Kp, R=Rp, t=tp, width=W, height=H, outputs=("depth",))["depth"])


def test_orthographic_arguments_are_checked():
    mesh = softrast.Mesh(np.eye(3), np.array([[0, 1, 2]]))
    args = dict(K=np.eye(3), R=np.eye(3), t=(0, 0, 1), width=8, height=8)
    with pytest.raises(ValueError, match="projection"):
        softrast.render(mesh, projection="fisheye", **args)
    with pytest.raises(TypeError, match="projection"):
        softrast.render(mesh, projection=1, **args)
    with pytest.raises(ValueError, match="near"):
        softrast.render(mesh, projection="orthographic", near=-1.0, **args)
    with pytest.raises(ValueError, match="near"):
        softrast.render(mesh, projection="orthographic", near=float("nan"), **args)
    with pytest.raises(ValueError, match="near"):
        softrast.render(mesh, near=0.0, **args)
    cam = softrast.Camera.orthographic((0, 0, 5), (0, 0, 0), ymag=1.0)
    with pytest.raises(TypeError, match="projection"):
        softrast.render(mesh, camera=cam, projection="orthographic", width=8, height=8)
    for bad, error in ((0.0, ValueError), (-1.0, ValueError), (float("nan"), ValueError),
                       (float("inf"), ValueError), ("1", TypeError), (None, TypeError),
                       (True, TypeError), ([1.0], TypeError)):
        with pytest.raises(error, match="ymag"):
            softrast.Camera.orthographic((0, 0, 5), (0, 0, 0), ymag=bad)
        if bad is not None:
            with pytest.raises(error, match="ymag"):
                softrast.look_at((0, 0, 5), (0, 0, 0), ymag=bad, width=8, height=8)
    with pytest.raises(TypeError, match="ymag"):
        softrast.look_at((0, 0, 5), (0, 0, 0), fov_y=1.0, ymag=1.0, width=8, height=8)
    for bad in (-1.0, float("nan")):
        with pytest.raises(ValueError, match="znear"):
            softrast.Camera.orthographic((0, 0, 5), (0, 0, 0), ymag=1.0, znear=bad)
    with pytest.raises(ValueError, match="znear"):
        softrast.Camera.perspective((0, 0, 5), (0, 0, 0), znear=0.0)
    with pytest.raises(ValueError, match="eye"):
        softrast.Camera.orthographic((0, float("nan"), 5), (0, 0, 0), ymag=1.0)
    with pytest.raises(ValueError, match="eye, target"):
        softrast.Camera.orthographic((0, 0, 0), (0, 0, 0), ymag=1.0)
    with pytest.raises(ValueError, match="target"):
        softrast.Camera.orthographic((0, 0, 5), (0, 0), ymag=1.0)


def ortho_scene(tmp_path):
    return gb.write(tmp_path / "ortho.gltf",
                    [(gb.quad((0, 0, 0), 4.0, "y", uv=False), 0), (gb.box((0, 0.6, 0), 0.8), 1)],
                    [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1]}},
                     {"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.1, 1]}}],
                    camera=((2.5, 2.2, 3.0), (0, 0.3, 0), 1.6), orthographic=True)


def test_gltf_orthographic_camera(tmp_path):
    scene = load_gltf(ortho_scene(tmp_path))
    assert len(scene.cameras) == 1
    cam = scene.cameras[0]
    assert cam.type == "orthographic" and cam.index == 0
    assert cam.ymag == pytest.approx(1.6) and cam.znear == pytest.approx(0.05)
    K = cam.intrinsics(W, H)
    assert K[1, 1] == pytest.approx(H / 3.2) and K[0, 0] == K[1, 1]
    assert np.allclose(cam.R @ np.array([2.5, 2.2, 3.0]) + cam.t, 0, atol=1e-5)
    out = render_both(scene, camera=cam)
    # The box's top face (y = 1.0, world normal +y) is a plane: its depth
    # is the distance from the camera's plane along the axis.
    axis = cam.R[2]
    top = (out["instance_id"] == 1) & (np.abs(out["normal"] @ (cam.R @ [0, 1, 0]) - 1) < 1e-5)
    assert top.sum() > 50
    xy = pixel_points(K)[top]
    # Points of the top face: camera (x, y, z) back to the world, y = 1.0.
    world = (np.column_stack([xy, out["depth"][top]]) - cam.t) @ cam.R
    assert np.abs(world[:, 1] - 1.0).max() < 1e-5
    assert axis[1] < 0, "looking down"


@needs_cli
@pytest.mark.parametrize("shading", ["pbr", "unlit"])
def test_gltf_orthographic_camera_matches_the_command(tmp_path, shading):
    # The command's --camera-index picture of a file's orthographic camera,
    # as test_pbr_gltf compares them for perspective cameras.
    assert_matches_command(tmp_path, ortho_scene(tmp_path), f"ortho_vs_cli_{shading}",
                           ["--aa", "none", "--shadows", "off", "--shading", shading,
                            "--background", "#000000"], width=W, height=H, shading=shading)
