"""Depth against analytic depth: planes exactly (float32 rounding), spheres
within the tessellation's sagitta."""

import numpy as np
import softrast
from conftest import pixel_rays, ray_plane_depth

W, H = 160, 120


def camera(rng):
    """A camera with a skewed, off-centre, non-square K and a random pose."""
    K = np.array([[150.0, 0.7, 83.3], [0.0, 140.0, 57.9], [0.0, 0.0, 1.0]])
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    angle = 0.3
    c, s = np.cos(angle), np.sin(angle)
    X = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    R = np.eye(3) + s * X + (1 - c) * X @ X
    t = rng.uniform(-0.5, 0.5, 3)
    return K, R, t


def test_plane_depth_is_exact_to_float32():
    rng = np.random.default_rng(1)
    K, R, t = camera(rng)
    # A large tilted quad, given in camera space and moved to world space.
    cam = np.array([[-9.0, -7.0, 3.0], [9.0, -7.0, 5.0], [9.0, 7.0, 8.0], [-9.0, 7.0, 6.0]])
    world = (cam - t) @ R
    mesh = softrast.Mesh(world, np.array([[0, 1, 2], [0, 2, 3]], np.int32))
    out = softrast.render(mesh, K=K, R=R, t=t, width=W, height=H,
                          outputs=("depth", "triangle_id", "mask"))
    depth = out["depth"]
    assert depth.dtype == np.float32 and depth.shape == (H, W)
    assert out["mask"].all(), "the quad covers the image"
    want = ray_plane_depth(pixel_rays(K, W, H), *cam[:3])
    rel = np.abs(depth.astype(np.float64) - want) / want
    # float32 rounding only: a few units in the last place.
    assert rel.max() < 4 * np.finfo(np.float32).eps, rel.max()


def icosphere(subdivisions):
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t),
         (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
         (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    verts = [np.array(p, float) / np.linalg.norm(p) for p in v]
    for _ in range(subdivisions):
        cache, faces = {}, []

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                m = verts[a] + verts[b]
                verts.append(m / np.linalg.norm(m))
                cache[key] = len(verts) - 1
            return cache[key]
        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            faces += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = faces
    return np.array(verts), np.array(f, np.int64)


def largest_sagitta(verts, faces, radius):
    """How far below a sphere of the radius its inscribed mesh's faces
    reach: the deepest point of a face is its circumcentre, circumradius
    abc / 4A."""
    p = verts[faces] * radius
    a, b, c = (np.linalg.norm(p[:, i] - p[:, (i + 1) % 3], axis=1) for i in range(3))
    area = 0.5 * np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1)
    circum = (a * b * c / (4 * area)).max()
    return radius - np.sqrt(radius ** 2 - circum ** 2)


def test_sphere_depth():
    verts, faces = icosphere(4)
    radius, centre = 1.5, np.array([0.2, -0.1, 5.0])
    mesh = softrast.Mesh(verts * radius + centre, faces)
    K = np.array([[200.0, 0, (W - 1) / 2], [0, 200.0, (H - 1) / 2], [0, 0, 1]])
    out = softrast.render(mesh, K=K, R=np.eye(3), t=np.zeros(3), width=W, height=H,
                          outputs=("depth", "triangle_id"))
    depth, tri = out["depth"], out["triangle_id"]
    rays = pixel_rays(K, W, H)
    # The sphere: |z d - c|^2 = r^2, the nearer root.
    a = (rays * rays).sum(-1)
    b = -2 * rays @ centre
    c = centre @ centre - radius ** 2
    disc = b * b - 4 * a * c
    hit = disc > 0
    sphere = np.where(hit, (-b - np.sqrt(np.maximum(disc, 0))) / (2 * a), np.inf)
    covered = tri >= 0
    # Inside the outline by a pixel both agree on coverage ...
    inner = disc > 4 * a * 0.03 ** 2 * 4
    assert covered[inner].all()
    assert not covered[~hit].any()
    # ... the mesh lies inside the sphere, behind it along the ray by no more
    # than the sagitta over the cosine of the ray's angle with the normal
    # (where the ray is not grazing, and the sphere's curvature is small
    # over the distance).
    sagitta = largest_sagitta(verts, faces, radius)
    steep = covered & hit
    normal = (sphere[steep][:, None] * rays[steep] - centre) / radius
    cos = np.abs(np.einsum("ij,ij->i", normal, rays[steep])) / np.linalg.norm(rays[steep], axis=1)
    d = depth[steep].astype(np.float64) - sphere[steep]
    assert d.min() > -1e-6 * sphere[steep].max(), d.min()
    facing = cos > 0.5
    assert facing.sum() > 1000
    assert (d[facing] <= sagitta / cos[facing]).all(), (d[facing] / (sagitta / cos[facing])).max()
    # And each pixel's depth is the plane of the triangle it names.
    p = verts[faces[tri[covered]]] * radius + centre
    want = np.einsum("ij,ij->i", np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), p[:, 0]) / \
        np.einsum("ij,ij->i", rays[covered], np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]))
    rel = np.abs(depth[covered] - want) / want
    assert rel.max() < 4 * np.finfo(np.float32).eps, rel.max()
    assert np.isinf(depth[~covered]).all()
