"""render()'s occlusion output: where a pixel's visible point has no flow
target the next camera sees (hidden there, off its image, or behind it),
against scenes whose occluded pixels are known exactly."""

import numpy as np
import softrast
from test_depth import icosphere

W, H = 64, 48
K = np.array([[40.0, 0.0, 31.5], [0.0, 40.0, 23.5], [0.0, 0.0, 1.0]])
# The front square's and the back one's extents (x, y) and depth: their
# edges project between pixel centres, so no pixel is a tie.
FRONT = (0.23, 1.07, -0.53, 0.47, 2.0)
BACK = (-3.37, 1.41, -0.97, 0.93, 4.0)
SHIFT = 0.4     # the second camera's centre: x = 0.4


def square(x0, x1, y0, y1, z):
    v = np.array([[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]])
    return softrast.Mesh(v, np.array([[0, 1, 2], [0, 2, 3]]))


def covers(sq, x, y, centre_x):
    """Whether square `sq` covers the pixel centres (x, y) of the camera
    at (centre_x, 0, 0) looking down +z with K (its ray met with the
    square's plane)."""
    x0, x1, y0, y1, z = sq
    wx = (x - K[0, 2]) * z / K[0, 0] + centre_x
    wy = (y - K[1, 2]) * z / K[1, 1]
    return (wx > x0) & (wx < x1) & (wy > y0) & (wy < y1)


def sliding_squares(projection="perspective"):
    scene = [square(*FRONT), square(*BACK)]
    ts = np.array([[0.0, 0.0, 0.0], [-SHIFT, 0.0, 0.0]])
    return softrast.render(scene, K=K, R=np.eye(3), t=ts, width=W, height=H,
                           projection=projection,
                           outputs=("occlusion", "mask", "depth", "flow"))


def test_a_square_sliding_behind_another_is_occluded_where_it_goes_behind():
    """The camera moves 0.4 to the right: the back square (depth 4) moves
    4 pixels left, the front one (depth 2) 8.  A point of the back square
    is occluded where its pixel 4 to the left is covered by the front
    square in the second view, or off that image; one of the front square
    only off the image.  Exact: no pixel is a tie."""
    out = sliding_squares()
    occ = out["occlusion"]
    assert occ.dtype == np.bool_ and occ.shape == (2, H, W)
    y, x = np.mgrid[0:H, 0:W].astype(np.float64)
    front = covers(FRONT, x, y, 0.0)
    back = covers(BACK, x, y, 0.0) & ~front
    assert np.array_equal(out["mask"][0], front | back)
    assert np.allclose(out["flow"][0][back], [-4.0, 0.0], atol=1e-4)
    assert np.allclose(out["flow"][0][front], [-8.0, 0.0], atol=1e-4)
    behind = back & covers(FRONT, x - 4.0, y, SHIFT)
    off = (back & (x - 4.0 < 0)) | (front & (x - 8.0 < 0))
    want = behind | off
    assert behind.sum() > 50 and off.sum() > 20 and (back & ~want).sum() > 100
    assert np.array_equal(occ[0], want), np.argwhere(occ[0] != want)[:10]
    # The last view has no next one: everything it sees is occluded.
    assert np.array_equal(occ[1], out["mask"][1])


def test_orthographic_cameras_move_both_squares_alike():
    """Under an orthographic projection both squares move 16 pixels: no
    point goes behind another, only off the image."""
    out = sliding_squares("orthographic")
    m = out["mask"][0]
    y, x = np.mgrid[0:H, 0:W]
    assert np.allclose(out["flow"][0][m], [-K[0, 0] * SHIFT, 0.0], atol=1e-4)
    assert np.array_equal(out["occlusion"][0], m & (x - 16 < 0))


def test_a_camera_that_does_not_move_occludes_nothing():
    """The same view twice: every point is seen again where it was, at its
    own depth, on a curved surface too (the depth tolerance holds the
    float32 rounding of position and depth)."""
    v, f = icosphere(3)
    rng = np.random.default_rng(3)
    v = v * rng.uniform(0.5, 1.5, size=3)
    t = np.array([0.1, -0.2, 2.5])
    R = np.eye(3)
    out = softrast.render(softrast.Mesh(v, f), K=K, R=np.stack([R, R]), t=np.stack([t, t]),
                          width=W, height=H, outputs=("occlusion", "mask"))
    assert out["mask"][0].sum() > 300
    assert not out["occlusion"][0].any()


def test_a_small_turn_occludes_only_points_the_sphere_turns_away():
    """A sphere turned a little about its centre: a point is occluded only
    near the outline, where the turn takes it to the back or the grazing
    surface's depth is too steep for the half-pixel tolerance."""
    v, f = icosphere(4)
    angle = 0.15
    c, s = np.cos(angle), np.sin(angle)
    turn = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
    centre = np.array([0.0, 0.0, 4.0])
    Rs = np.stack([np.eye(3), turn])
    ts = np.stack([centre, centre])     # the sphere turns about its centre
    out = softrast.render(softrast.Mesh(v, f), K=K, R=Rs, t=ts, width=W, height=H,
                          outputs=("occlusion", "mask", "position"),
                          frame="world")
    m, occ = out["mask"][0], out["occlusion"][0]
    assert occ.any() and (m & ~occ).sum() > 0.8 * m.sum()
    # Facing the second camera or not: its eye is at -turn^T centre.
    eye = -turn.T @ centre
    p = out["position"][0].astype(np.float64)
    normal = p / np.linalg.norm(p, axis=-1, keepdims=True)
    facing = np.einsum("hwk,hwk->hw", normal, eye - p)
    # Occluded points are seen at a grazing angle from the second camera
    # (more than 65 degrees from their normal): turned away, or beside
    # the outline, where the depth changes faster than linearly across a
    # pixel; the points that face it are all seen.
    cosine = facing / np.where(m, np.linalg.norm(eye - p, axis=-1), 1.0)
    assert (cosine[occ] < 0.42).all() and not occ[m & (cosine > 0.5)].any()
    assert occ.sum() < 0.1 * m.sum()


def test_behind_the_next_camera_is_occluded():
    quad = np.array([[-1.0, -1.0, 2.0], [1.0, -1.0, 2.0], [1.0, 1.0, 2.0], [-1.0, 1.0, 2.0]])
    mesh = softrast.Mesh(quad, np.array([[0, 1, 2], [0, 2, 3]]))
    out = softrast.render(mesh, K=K, R=np.eye(3), t=np.array([[0.0, 0.0, 0.0], [0.0, 0.0, -3.0]]),
                          width=W, height=H, outputs=("occlusion", "mask"))
    assert out["mask"][0].any()
    assert np.array_equal(out["occlusion"][0], out["mask"][0])


def test_only_the_outputs_asked_for_are_returned():
    """What occlusion is computed from is drawn for it and dropped; a
    single camera's occlusion is its mask (no next view)."""
    mesh = square(*FRONT)
    R, t = np.eye(3), np.zeros(3)
    one = softrast.render(mesh, K=K, R=R, t=t, width=W, height=H, outputs=("occlusion",))
    assert set(one) == {"occlusion"} and one["occlusion"].shape == (H, W)
    mask = softrast.render(mesh, K=K, R=R, t=t, width=W, height=H, outputs=("mask",))["mask"]
    assert np.array_equal(one["occlusion"], mask)
    both = softrast.render(mesh, K=K, R=R, t=t, width=W, height=H, outputs=("depth", "occlusion"),
                           frame="camera")
    assert list(both) == ["depth", "occlusion"]
