"""Cameras fitted to a scene: softrast render's default camera, and orbits
of cameras around a scene for turntables and datasets."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, List, Optional

import numpy as np
from numpy.typing import NDArray

from . import _softrast
from ._camera import Camera, _fov_y, _frame, _image_size, _intrinsics, _number
from ._scene import Scene, as_scene

if TYPE_CHECKING:
    from .typing import CameraParameters, Projection, SceneLike

#: softrast render's default field of view across the smaller image side
#: (SR_FRAMING_FOV_DEG), radians.
DEFAULT_FOV = math.radians(_softrast.framing_fov_deg)

# The margin fit_camera and orbit keep on each side of the image, a
# fraction of its width or height (SR_FRAMING_MARGIN), and the default view
# direction, from the scene towards the eye (sr_framing_direction).
_MARGIN = _softrast.framing_margin
_DIRECTION = np.array(_softrast.framing_direction)


def _world_vertices(sc: Scene) -> List[NDArray[np.float64]]:
    """Each instance's vertices placed by its pose, float64, (N, 3) each."""
    return [np.asarray(inst.mesh.vertices, np.float64) @ inst.pose[:3, :3].T + inst.pose[:3, 3]
            for inst in sc]


def _framed(scene: SceneLike) -> Scene:
    """The scene as a Scene, with at least one vertex."""
    sc = as_scene(scene)
    if not any(len(inst.mesh.vertices) for inst in sc):
        raise ValueError("scene: has no vertices to frame")
    return sc


def fit_camera(scene: SceneLike, *, width: int, height: int, fov: Optional[float] = None,
               projection: Projection = "perspective") -> Camera:
    """softrast render's default camera for ``scene`` in a width x height image.

    The camera ``softrast render`` places when it is given none (the
    library's ``sr_fit_camera``, which the command calls too): looking
    from the front right, above (along ``-(0.62, 0.48, 1)`` normalized)
    with +y up the image, from where the scene's vertices span the image
    less 5% of its width or height on each side in the limiting dimension
    and are centred in the other; the target is the point of the line of
    sight nearest the centre of the vertices' world box.  Vertices and poses
    are taken as float32, as the command reads them.  ``render(scene,
    width=..., height=...)`` without a camera renders from it.

    fov: the field of view across the smaller image side, radians (default
        35 degrees, the command's ``--fov``); the camera's ``yfov`` is the
        vertical one that gives it.
    projection: "perspective" or "orthographic" (the command's ``--ortho``:
        the view as tight, ``ymag`` half its height, the eye where the
        perspective camera would stand).

    Returns a :class:`Camera` (``camera.intrinsics(width, height)``, ``R``,
    ``t`` give OpenCV's K, R, t), clipping at half the nearest vertex's
    distance along the axis (0 for orthographic).  The fit is for this
    image size: another aspect ratio frames differently.  Raises ValueError
    for a scene without vertices or whose vertices give no frame (all in one
    point, not finite).
    """
    sc = _framed(scene)
    _image_size(width, height)
    fov = 0.0 if fov is None else _fov_y(fov, "fov")
    if projection not in ("perspective", "orthographic"):
        raise ValueError(f"projection: must be 'perspective' or 'orthographic', "
                         f"got {projection!r}")
    ortho = projection == "orthographic"
    sets = [(np.ascontiguousarray(inst.mesh.vertices, np.float32),
             np.ascontiguousarray(inst.pose.T.reshape(16), np.float32)) for inst in sc]
    eye, target, up, fovy, _, half_h = _softrast.fit_camera(sets, width, height, fov, ortho)
    if ortho:
        return Camera.orthographic(eye, target, up, ymag=half_h)
    R, t = _frame(np.asarray(eye), np.asarray(target), np.asarray(up))
    z = min(float((v @ R[2]).min()) for v in _world_vertices(sc) if len(v)) + t[2]
    return Camera.perspective(eye, target, up, yfov=fovy, znear=0.5 * z if z > 0 else 1e-3)


def _angle(value: float, name: str, low: float, high: float) -> float:
    value = _number(value, name)
    if not low < value < high:
        raise ValueError(f"{name}: must be in ({low:.6g}, {high:.6g}) radians, got {value}")
    return value


def orbit(scene: SceneLike, n: int, *, width: int, height: int,
          elevation: Optional[float] = None, azimuth: Optional[float] = None,
          fov_y: Optional[float] = None, distance: Optional[float] = None) -> CameraParameters:
    """``n`` cameras evenly spaced on a circle around ``scene``: a turntable.

    The cameras look at the centre of the scene's world box (its
    vertices placed by their poses) from ``distance`` away, +y up the
    image, at ``elevation`` above the horizontal plane, view ``i`` at
    azimuth ``azimuth + 2 pi i / n`` (about +y, from +z towards +x:
    counter-clockwise seen from above).  The defaults start at softrast
    render's default view direction, so that view 0 looks from where
    :func:`fit_camera` does.

    n: the number of views, >= 1.
    width, height: the image size the cameras are made for.
    elevation: radians in (-pi/2, pi/2) (default 0.3873, about 22.2
        degrees, the default camera's).
    azimuth: view 0's azimuth, radians (default 0.5550, about 31.8
        degrees, the default camera's).
    fov_y: the vertical field of view, radians in (0, pi) (default: 35
        degrees across the smaller image side, as :func:`fit_camera`).
    distance: from the box's centre to each eye (default None: the least
        at which every corner of the box lies inside every view, less 5%
        of the image's width or height on each side).

    Returns ``(K, R, t)`` as :func:`look_at` does, batched: ``K`` (n, 3, 3)
    (the same for every view: square pixels, the principal point at the
    image centre), ``R`` (n, 3, 3) and ``t`` (n, 3), world to camera in
    OpenCV's frame, ``x_cam = R @ x_world + t``.  ``render(scene, K=K,
    R=R, t=t, width=width, height=height)`` renders the n views (each the
    same bytes as rendered alone); ``zip(K, R, t)`` gives them one by one.
    Raises TypeError or ValueError naming the argument that is wrong, and
    ValueError for a scene without vertices.
    """
    sc = _framed(scene)
    if not isinstance(n, (int, np.integer)) or isinstance(n, bool):
        raise TypeError(f"n: expected an int, got {type(n).__name__}")
    if n < 1:
        raise ValueError(f"n: must be >= 1, got {n}")
    _image_size(width, height)
    elevation = math.asin(_DIRECTION[1]) if elevation is None else \
        _angle(elevation, "elevation", -math.pi / 2, math.pi / 2)
    azimuth = math.atan2(_DIRECTION[0], _DIRECTION[2]) if azimuth is None else \
        _number(azimuth, "azimuth")
    if fov_y is None:
        # DEFAULT_FOV across the smaller side (sr_fit_fovy).
        ratio = min(width / height, 1.0)
        fov_y = 2.0 * math.atan(math.tan(DEFAULT_FOV / 2) / ratio)
    else:
        fov_y = _fov_y(fov_y)
    if distance is not None:
        distance = _number(distance, "distance")
        if not distance > 0:
            raise ValueError(f"distance: must be positive, got {distance}")

    placed = np.concatenate([v for v in _world_vertices(sc) if len(v)])
    lo, hi = placed.min(axis=0), placed.max(axis=0)
    if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
        raise ValueError("scene: its vertices are not all finite")
    centre = (lo + hi) / 2
    corners = np.array([[hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1],
                         hi[2] if i & 4 else lo[2]] for i in range(8)]) - centre
    angles = azimuth + 2.0 * math.pi * np.arange(n) / n
    dirs = np.column_stack([math.cos(elevation) * np.sin(angles),
                            np.full(n, math.sin(elevation)),
                            math.cos(elevation) * np.cos(angles)])
    up = np.array([0.0, 1.0, 0.0])
    # The rotations of cameras at the centre looking back along each
    # direction: a corner q sits at camera (x, y) = R q and depth d - dir q.
    rots = np.stack([_frame(np.zeros(3), -d, up)[0] for d in dirs])
    if distance is None:
        fill = 1.0 - 2.0 * _MARGIN
        tan_y = math.tan(fov_y / 2) * fill
        tan_x = math.tan(fov_y / 2) * width / height * fill
        q = np.einsum("vij,cj->vci", rots, corners)
        toward = corners @ dirs.T           # (8, n): each corner's offset towards the eye
        need = np.maximum(toward.T + np.abs(q[..., 0]) / tan_x, toward.T + np.abs(q[..., 1]) / tan_y)
        distance = float(need.max())
        if not distance > 0:
            raise ValueError("scene: its vertices are all in one point: give distance")
    eyes = centre + distance * dirs
    t = -np.einsum("vij,vj->vi", rots, eyes)
    f = 0.5 * height / math.tan(fov_y / 2)
    K = np.broadcast_to(_intrinsics(f, width, height), (n, 3, 3)).copy()
    return K, rots, t
