"""render()'s dataset outputs: position (the ray's exact point on the
visible face, world or camera frame), uv (the mesh's texture coordinates
at the exact barycentrics), material_id (the visible instance's material
in Scene.materials) and flow (the visible point's displacement into the
next camera of a batch), against analytic values and numpy projections."""

import functools
import json
import pickle

import numpy as np
import pytest
import softrast
from softrast import _softrast
from conftest import load_gltf, pixel_rays, random_triangles, ray_plane_depth
from test_depth import camera, icosphere, largest_sagitta
from test_load import write_skinned_glb
import gltf_build

W, H = 160, 120
EPS = np.finfo(np.float32).eps


def within_float32(got, want, ulps=2):
    """got (float32) is want (float64) rounded, to a few units in the last
    place of the largest coordinate of each point (a coordinate near 0 of
    a point far from the origin carries the point's absolute error)."""
    scale = np.abs(want).max(axis=-1, keepdims=True)
    err = np.abs(got.astype(np.float64) - want)
    assert (err <= ulps * EPS * scale).all(), (err / scale).max() / EPS


def tilted_quad(rng):
    """A camera and a large tilted quad covering its image, the quad's
    corners in camera and world space."""
    K, R, t = camera(rng)
    cam = np.array([[-9.0, -7.0, 3.0], [9.0, -7.0, 5.0], [9.0, 7.0, 8.0], [-9.0, 7.0, 6.0]])
    world = (cam - t) @ R
    return K, R, t, cam, world


def test_plane_position_is_exact_to_float32_in_both_frames():
    rng = np.random.default_rng(1)
    K, R, t, cam, world = tilted_quad(rng)
    mesh = softrast.Mesh(world, np.array([[0, 1, 2], [0, 2, 3]], np.int32))
    rays = pixel_rays(K, W, H)
    want_cam = ray_plane_depth(rays, *cam[:3])[..., None] * rays
    want_world = (want_cam - t) @ R
    out = softrast.render(mesh, K=K, R=R, t=t, width=W, height=H, outputs=("position", "depth"))
    assert out["position"].dtype == np.float32 and out["position"].shape == (H, W, 3)
    within_float32(out["position"], want_world)
    cam_out = softrast.render(mesh, K=K, R=R, t=t, width=W, height=H, frame="camera",
                              outputs=("position", "depth"))
    within_float32(cam_out["position"], want_cam)
    # Camera z is the depth output, the same float.
    assert cam_out["position"][..., 2].tobytes() == cam_out["depth"].tobytes()
    # normal_frame is another name for frame.
    alias = softrast.render(mesh, K=K, R=R, t=t, width=W, height=H, normal_frame="camera",
                            outputs=("position",))
    assert alias["position"].tobytes() == cam_out["position"].tobytes()


def test_sphere_position_lies_on_the_visible_face_and_the_sphere():
    verts, faces = icosphere(4)
    radius, centre = 1.5, np.array([0.2, -0.1, 5.0])
    K = np.array([[140.0, 0.0, 80.0], [0.0, 140.0, 60.0], [0.0, 0.0, 1.0]])
    pose = np.eye(4)
    pose[:3, :3] *= radius
    pose[:3, 3] = centre
    scene = softrast.Scene([(softrast.Mesh(verts, faces), pose)])
    out = softrast.render(scene, K=K, R=np.eye(3), t=np.zeros(3), width=W, height=H,
                          outputs=("position", "triangle_id", "mask"), cull="back")
    m = out["mask"]
    p = out["position"][m].astype(np.float64)
    assert m.sum() > 3000 and np.isnan(out["position"][~m]).all()
    r = np.linalg.norm(p - centre, axis=1)
    assert r.max() <= radius * (1 + 4 * EPS) + 8 * EPS
    assert r.min() >= radius - largest_sagitta(verts, faces, radius) - 8 * EPS * 6
    # On the plane of the face triangle_id names, to float32 rounding.
    corners = verts[faces[out["triangle_id"][m]]] * radius + centre
    n = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    off = np.abs(((p - corners[:, 0]) * n).sum(1))
    assert off.max() < 4 * EPS * np.abs(p).max(), off.max()


def project(points, K, R, t):
    """Pixel coordinates (..., 2) of world points under OpenCV's pinhole."""
    c = points @ R.T + t
    uvw = c @ K.T
    return uvw[..., :2] / uvw[..., 2:]


def batch_of_cameras(rng, n):
    Ks = np.array([[[150.0, 0.4, 81.0], [0.0, 145.0, 59.5], [0.0, 0.0, 1.0]]] * n)
    Rs, ts = [], []
    for _ in range(n):
        K, R, t = camera(rng)
        Rs.append(R)
        ts.append(t * 0.2)
    return Ks, np.array(Rs), np.array(ts)


def test_position_projects_to_the_pixel_centres_of_a_batch():
    rng = np.random.default_rng(5)
    verts, faces = random_triangles(rng, 300, size=0.8)
    Ks, Rs, ts = batch_of_cameras(rng, 3)
    out = softrast.render(softrast.Mesh(verts, faces), K=Ks, R=Rs, t=ts, width=W, height=H,
                          outputs=("position", "mask"))
    assert out["position"].shape == (3, H, W, 3)
    grid = np.stack(np.meshgrid(np.arange(W), np.arange(H)), -1).astype(np.float64)
    for b in range(3):
        m = out["mask"][b]
        assert m.mean() > 0.3
        px = project(out["position"][b][m].astype(np.float64), Ks[b], Rs[b], ts[b])
        assert np.abs(px - grid[m]).max() < 1e-3


def test_uv_of_a_textured_quad_is_the_analytic_mapping():
    rng = np.random.default_rng(2)
    K, R, t, cam, world = tilted_quad(rng)
    # uv = affine in the quad's own coordinates: corner i at uvs[i].
    uvs = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 1.5], [0.0, 1.5]], np.float32)
    mesh = softrast.Mesh(world, np.array([[0, 1, 2], [0, 2, 3]], np.int32), uvs=uvs)
    out = softrast.render(mesh, K=K, R=R, t=t, width=W, height=H,
                          outputs=("uv", "position", "triangle_id"))
    assert out["uv"].dtype == np.float32 and out["uv"].shape == (H, W, 2)
    rays = pixel_rays(K, W, H)
    p = ray_plane_depth(rays, *cam[:3])[..., None] * rays
    # The quad is planar: its point in the basis of edges 0->1 and 0->3.
    e1, e3 = cam[1] - cam[0], cam[3] - cam[0]
    basis = np.stack([e1, e3], 1)
    a, *_ = np.linalg.lstsq(basis, (p - cam[0]).reshape(-1, 3).T, rcond=None)
    want = np.stack([2.0 * a[0], 1.5 * a[1]], -1).reshape(H, W, 2)
    assert np.abs(out["uv"] - want).max() < 8 * EPS * 2.0


def test_uv_is_nan_on_meshes_without_uvs():
    quad = np.array([[-1.0, -1.0, 4.0], [1.0, -1.0, 4.0], [1.0, 1.0, 4.0], [-1.0, 1.0, 4.0]])
    faces = np.array([[0, 1, 2], [0, 2, 3]])
    with_uv = softrast.Mesh(quad, faces, uvs=np.zeros((4, 2), np.float32))
    bare = softrast.Mesh(quad + [0.0, 0.0, -1.0], faces)
    K = np.array([[40.0, 0.0, 15.5], [0.0, 40.0, 15.5], [0.0, 0.0, 1.0]])
    kw = dict(K=K, R=np.eye(3), t=np.zeros(3), width=32, height=32)
    out = softrast.render([with_uv, bare], outputs=("uv", "instance_id"), **kw)
    assert (out["instance_id"] == 1).any()
    assert np.isnan(out["uv"][out["instance_id"] != 0]).all()
    assert not np.isnan(out["uv"][out["instance_id"] == 0]).any()
    # Every output of a scene without uvs (softrast.OUTPUTS) is no error.
    alone = softrast.render(bare, outputs=tuple(softrast.OUTPUTS), **kw)
    assert alone["mask"].any() and np.isnan(alone["uv"]).all()


def write_two_materials(path):
    """Three quads side by side in a glTF file: materials 1, 0, 1 (not the
    instance order), with a camera looking at them along -z."""
    prims = [(gltf_build.quad((-1.1, 0.0, 0.0), 1.0), 1),
             (gltf_build.quad((0.0, 0.0, 0.0), 1.0), 0),
             (gltf_build.quad((1.1, 0.0, 0.0), 1.0), 1)]
    materials = [{"pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1]}},
                 {"pbrMetallicRoughness": {"baseColorFactor": [0, 0, 1, 1]}}]
    return gltf_build.write(path, prims, materials, camera=((0.0, 0.0, 4.0), (0.0, 0.0, 0.0), 0.9))


def test_material_id_of_a_two_material_gltf(tmp_path):
    scene = load_gltf(write_two_materials(tmp_path / "two.gltf"))
    assert len(scene.materials) == 2
    assert [scene.materials.index(i.material) for i in scene] == [1, 0, 1]
    cam = scene.cameras[0]
    out = softrast.render(scene, camera=cam, width=W, height=H, cull="back",
                          outputs=("material_id", "instance_id", "color"), antialias="msaa4")
    mid, iid = out["material_id"], out["instance_id"]
    assert mid.dtype == np.int32 and mid.shape == (H, W)
    assert ((mid == -1) == (iid == -1)).all() and (iid == -1).any()
    for inst, want in enumerate((1, 0, 1)):
        assert (iid == inst).sum() > 500
        assert (mid[iid == inst] == want).all()
    # Never blended: the same bytes without antialiasing, nor color.
    plain = softrast.render(scene, camera=cam, width=W, height=H, outputs=("material_id",))
    assert plain["material_id"].tobytes() == mid.tobytes()
    # A pickled scene (a Dask task's) keeps which material is which.
    thawed = pickle.loads(pickle.dumps(scene))
    same = softrast.render(thawed, camera=thawed.cameras[0], width=W, height=H,
                           outputs=("material_id",))
    assert same["material_id"].tobytes() == mid.tobytes()
    # An instance whose Material is not in Scene.materials is -1.
    scene.instances[1].material = softrast.Material()
    again = softrast.render(scene, camera=cam, width=W, height=H, outputs=("material_id",))
    assert (again["material_id"][iid == 1] == -1).all()


def test_a_primitive_without_a_material_is_minus_one(tmp_path):
    """glTF's default material (of a primitive that names none) is no
    index of the file's /materials."""
    path = write_two_materials(tmp_path / "two.gltf")
    doc = json.loads(path.read_text())
    del doc["meshes"][0]["primitives"][0]["material"]
    path.write_text(json.dumps(doc))
    scene = load_gltf(path)
    assert len(scene.materials) == 2 and scene.instances[0].material not in scene.materials
    out = softrast.render(scene, camera=scene.cameras[0], width=W, height=H,
                          outputs=("material_id", "instance_id"))
    iid = out["instance_id"]
    assert (iid == 0).any() and (out["material_id"][iid == 0] == -1).all()
    assert (out["material_id"][iid == 1] == 0).all()


def test_uv_of_a_gltf_quad_runs_v_up(tmp_path):
    """glTF's TEXCOORD_0 has v down; the library stores 1 - v (v up, (0, 0)
    the image's bottom-left), and uv is what it stores."""
    scene = load_gltf(write_two_materials(tmp_path / "two.gltf"))
    out = softrast.render(scene, camera=scene.cameras[0], width=W, height=H,
                          outputs=("uv", "position", "instance_id"))
    m = out["instance_id"] == 1          # the quad centred at the origin, 1 wide
    p = out["position"][m].astype(np.float64)
    want = p[:, :2] + 0.5                # u along +x, v along +y (up)
    assert np.abs(out["uv"][m] - want).max() < 1e-5


def test_position_of_a_skinned_and_morphed_gltf_is_the_posed_surface(tmp_path):
    path = tmp_path / "skinned.glb"
    write_skinned_glb(path)
    scene = load_gltf(path)
    K, R, t = softrast.look_at(eye=(0.0, 1.0, 6.0), target=(0.0, 1.0, 0.0), fov_y=0.9,
                               width=W, height=H)
    out = softrast.render(scene, K=K, R=R, t=t, width=W, height=H,
                          outputs=("position", "triangle_id", "instance_id", "barycentric"))
    seen = 0
    for i, inst in enumerate(scene):
        m = out["instance_id"] == i
        seen += m.sum()
        v = np.asarray(inst.mesh.vertices, np.float64) @ inst.pose[:3, :3].T + inst.pose[:3, 3]
        corners = v[np.asarray(inst.mesh.faces)[out["triangle_id"][m]]]
        want = (out["barycentric"][m][..., None] * corners).sum(1)
        assert np.abs(out["position"][m] - want).max() < 1e-5
    assert seen > 1000
    # The morphed instance is the one in front (z = 1).
    assert np.allclose(out["position"][out["instance_id"] == 1][:, 2], 1.0, atol=1e-6)


def test_flow_is_the_next_cameras_projection():
    rng = np.random.default_rng(7)
    verts, faces = random_triangles(rng, 300, size=0.8)
    Ks, Rs, ts = batch_of_cameras(rng, 3)
    out = softrast.render(softrast.Mesh(verts, faces), K=Ks, R=Rs, t=ts, width=W, height=H,
                          outputs=("flow", "position", "mask"))
    flow = out["flow"]
    assert flow.dtype == np.float32 and flow.shape == (3, H, W, 2)
    grid = np.stack(np.meshgrid(np.arange(W), np.arange(H)), -1).astype(np.float64)
    for b in range(2):
        m = out["mask"][b]
        want = project(out["position"][b][m].astype(np.float64), Ks[b + 1], Rs[b + 1],
                       ts[b + 1]) - grid[m]
        assert np.abs(flow[b][m] - want).max() < 1e-3
        assert np.abs(want).max() > 1.0, "the cameras move"
        assert np.isnan(flow[b][~m]).all()
    assert np.isnan(flow[2]).all(), "the last view has no next one"
    # One camera: the last view of a batch of one.
    single = softrast.render(softrast.Mesh(verts, faces), K=Ks[0], R=Rs[0], t=ts[0], width=W,
                             height=H, outputs=("flow",))
    assert single["flow"].shape == (H, W, 2) and np.isnan(single["flow"]).all()


def test_flow_of_orthographic_cameras():
    rng = np.random.default_rng(8)
    verts, faces = random_triangles(rng, 100, size=0.8)
    K = np.array([[40.0, 0.0, 79.5], [0.0, 40.0, 59.5], [0.0, 0.0, 1.0]])
    ts = np.array([[0.0, 0.0, 0.0], [0.25, -0.1, 0.0]])
    out = softrast.render(softrast.Mesh(verts, faces), K=K, R=np.eye(3), t=ts, width=W, height=H,
                          projection="orthographic", outputs=("flow", "mask"))
    m = out["mask"][0]
    assert np.allclose(out["flow"][0][m], [40.0 * 0.25, -40.0 * 0.1], atol=1e-4)


def test_flow_is_nan_behind_the_next_camera():
    quad = np.array([[-1.0, -1.0, 2.0], [1.0, -1.0, 2.0], [1.0, 1.0, 2.0], [-1.0, 1.0, 2.0]])
    mesh = softrast.Mesh(quad, np.array([[0, 1, 2], [0, 2, 3]]))
    K = np.array([[20.0, 0.0, 15.5], [0.0, 20.0, 15.5], [0.0, 0.0, 1.0]])
    # The second camera sits beyond the quad, looking the same way.
    out = softrast.render(mesh, K=K, R=np.eye(3), t=np.array([[0.0, 0.0, 0.0], [0.0, 0.0, -3.0]]),
                          width=32, height=32, outputs=("flow", "mask"))
    assert out["mask"][0].any() and np.isnan(out["flow"][0]).all()


ALL = ("position", "uv", "material_id", "flow", "depth", "triangle_id")


@pytest.mark.parametrize("eye", [(0.3, -0.2, 3.0), (0.0, 0.0, 0.3)])
def test_same_bytes_on_every_thread_count_and_both_passes(tmp_path, eye):
    """Threads 1, 2, 3 and every CPU, and the general pass (which a view
    whose faces cross the near plane takes, the second eye's) against the
    visibility pass."""
    scene = load_gltf(write_two_materials(tmp_path / "two.gltf"))
    rng = np.random.default_rng(9)
    verts, faces = random_triangles(rng, 200, depth_range=(-1.0, 1.0), size=0.5)
    scene.add(softrast.Mesh(verts, faces, uvs=rng.uniform(0, 1, (len(verts), 2))))
    Ks, Rs, ts = [], [], []
    for dx in (0.0, 0.2):
        K, R, t = softrast.look_at(eye=(eye[0] + dx, eye[1], eye[2]), target=(0.0, 0.0, 0.0),
                                   fov_y=1.0, width=W, height=H)
        Ks.append(K)
        Rs.append(R)
        ts.append(t)
    kw = dict(K=np.array(Ks), R=np.array(Rs), t=np.array(ts), width=W, height=H, outputs=ALL)
    orig = _softrast.render
    _softrast.render = functools.partial(orig, general=True)
    try:
        want = softrast.render(scene, threads=1, **kw)
    finally:
        _softrast.render = orig
    assert (want["material_id"] >= 0).any() and not np.isnan(want["flow"][0]).all()
    for n in (1, 2, 3, 0):
        got = softrast.render(scene, threads=n, **kw)
        for name in ALL:
            assert got[name].tobytes() == want[name].tobytes(), (name, n)


def test_bad_arguments_are_named():
    mesh = softrast.Mesh(np.array([[0.0, 0.0, 2.0], [1.0, 0.0, 2.0], [0.0, 1.0, 2.0]]),
                         np.array([[0, 1, 2]]))
    kw = dict(K=np.array([[10.0, 0.0, 4.0], [0.0, 10.0, 4.0], [0.0, 0.0, 1.0]]), R=np.eye(3),
              t=np.zeros(3), width=8, height=8, outputs=("position",))
    with pytest.raises(ValueError, match="frame: must be 'camera' or 'world'"):
        softrast.render(mesh, frame="body", **kw)
    with pytest.raises(TypeError, match="frame: expected"):
        softrast.render(mesh, frame=1, **kw)
    with pytest.raises(ValueError, match="normal_frame: must be"):
        softrast.render(mesh, normal_frame="object", **kw)
    with pytest.raises(TypeError, match="frame, normal_frame"):
        softrast.render(mesh, frame="camera", normal_frame="world", **kw)
    with pytest.raises(TypeError, match=r"materials\[0\]: expected a softrast.Material"):
        softrast.Scene([mesh], materials=["red"])
    with pytest.raises(ValueError, match="unknown output 'positions'"):
        softrast.render(mesh, **{**kw, "outputs": ("positions",)})


def test_the_memory_estimate_counts_the_new_outputs(monkeypatch):
    mesh = softrast.Mesh(np.array([[0.0, 0.0, 2.0], [1.0, 0.0, 2.0], [0.0, 1.0, 2.0]]),
                         np.array([[0, 1, 2]]), uvs=np.zeros((3, 2), np.float32))
    kw = dict(K=np.array([[10.0, 0.0, 16.0], [0.0, 10.0, 16.0], [0.0, 0.0, 1.0]]),
              R=np.eye(3), t=np.zeros(3), width=32, height=32,
              outputs=("position", "uv", "material_id", "flow"))
    # 12 + 8 + 4 + 8 bytes a pixel, and the frame drawn into (8 a pixel).
    need = 32 * 32 * (12 + 8 + 4 + 8) + 32 * 32 * 8
    monkeypatch.setenv("SR_MEMORY_LIMIT", str(need))
    softrast.render(mesh, **kw)
    monkeypatch.setenv("SR_MEMORY_LIMIT", str(need - 1))
    with pytest.raises(MemoryError, match="position, uv, material_id, flow"):
        softrast.render(mesh, **kw)
