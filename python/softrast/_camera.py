"""Cameras in OpenCV's convention: x right, y down, z forward (the optical axis)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Mapping, Optional, overload

import numpy as np
from numpy.typing import NDArray

from ._arrays import real_array

if TYPE_CHECKING:
    from .typing import CameraParameters, Projection, RealArrayLike


def _vector3(value: RealArrayLike, name: str) -> NDArray[np.float64]:
    v = real_array(value, name)
    if v.shape != (3,):
        raise ValueError(f"{name}: shape must be (3,), got {v.shape}")
    if not np.all(np.isfinite(v)):
        raise ValueError(f"{name}: contains NaN or infinity")
    return v


def _image_size(width: int, height: int) -> None:
    if not (isinstance(width, (int, np.integer)) and isinstance(height, (int, np.integer))) or \
            isinstance(width, bool) or isinstance(height, bool):
        raise TypeError("width, height: must be integers")
    if width < 1 or height < 1:
        raise ValueError(f"width, height: must be positive, got {width} x {height}")


def _number(value: float, name: str) -> float:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer,
                                                                    np.floating)):
        raise TypeError(f"{name}: expected a number, got {type(value).__name__}")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{name}: must be finite, got {value}")
    return value


def _fov_y(fov_y: float, name: str = "fov_y") -> float:
    fov_y = _number(fov_y, name)
    if not (0.0 < fov_y < math.pi):
        raise ValueError(f"{name}: must be in (0, pi) radians, got {fov_y}")
    return fov_y


def _ymag(ymag: float) -> float:
    ymag = _number(ymag, "ymag")
    if not ymag > 0.0:
        raise ValueError(f"ymag: must be positive, got {ymag}")
    return ymag


def _intrinsics(f: float, width: int, height: int) -> NDArray[np.float64]:
    """K with square pixels of focal length f and the principal point at
    the image centre."""
    return np.array([[f, 0.0, 0.5 * (width - 1)], [0.0, f, 0.5 * (height - 1)],
                     [0.0, 0.0, 1.0]])


# A perspective view (fov_y) or an orthographic one (ymag), not both.
@overload
def look_at(eye: RealArrayLike, target: RealArrayLike, up: RealArrayLike = ..., *,
            fov_y: Optional[float] = ..., ymag: None = ..., width: int,
            height: int) -> CameraParameters: ...


@overload
def look_at(eye: RealArrayLike, target: RealArrayLike, up: RealArrayLike = ..., *,
            fov_y: None = ..., ymag: float, width: int, height: int) -> CameraParameters: ...


def look_at(eye: RealArrayLike, target: RealArrayLike, up: RealArrayLike = (0.0, 1.0, 0.0), *,
            fov_y: Optional[float] = None, ymag: Optional[float] = None, width: int,
            height: int) -> CameraParameters:
    """Camera intrinsics and extrinsics looking from ``eye`` at ``target``.

    Returns ``(K, R, t)``: ``K`` (3, 3) with square pixels and the principal
    point at the image centre, ``((width - 1) / 2, (height - 1) / 2)``, for the
    vertical field of view ``fov_y`` (radians, default 60 degrees); ``R``
    (3, 3) and ``t`` (3,) map world to camera coordinates, ``x_cam = R @
    x_world + t``, in OpenCV's frame: x right, y down, z from the eye towards
    the target.  ``up`` is the world direction that appears upwards in the
    image.

    ``ymag`` instead of ``fov_y``: an orthographic view ``2 * ymag`` high (in
    the unit of the vertices, ``ymag * width / height`` half wide), whose
    ``K`` maps camera x, y straight to pixels (focal lengths in pixels per
    unit); render it with ``render(..., projection="orthographic")``.
    """
    eye_v = _vector3(eye, "eye")
    target_v = _vector3(target, "target")
    up_v = _vector3(up, "up")
    _image_size(width, height)
    if ymag is not None:
        if fov_y is not None:
            raise TypeError("fov_y, ymag: give one (perspective or orthographic), not both")
        f = 0.5 * height / _ymag(ymag)
    else:
        fov_y = math.radians(60.0) if fov_y is None else _fov_y(fov_y)
        f = 0.5 * height / math.tan(0.5 * fov_y)
    R, t = _frame(eye_v, target_v, up_v)
    return _intrinsics(f, width, height), R, t


def _frame(eye: NDArray[np.float64], target: NDArray[np.float64],
           up: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """R, t of OpenCV's camera at eye looking at target, ``up`` upwards."""
    z = target - eye
    if not np.linalg.norm(z) > 0:
        raise ValueError("eye, target: must differ")
    z = z / np.linalg.norm(z)
    x = np.cross(z, up)
    if not np.linalg.norm(x) > 1e-12:
        raise ValueError("up: must not be parallel to target - eye")
    x = x / np.linalg.norm(x)
    y = np.cross(z, x)
    R = np.stack([x, y, z])
    return R, -R @ eye


# glTF's camera frame (x right, y up, looking down -z) to OpenCV's.
_GL_TO_CV = np.diag([1.0, -1.0, -1.0])


class Camera:
    """A camera: one of a model file (a glTF node's camera), as
    :func:`softrast.load` reads it into ``Scene.cameras``, or one made by
    :meth:`Camera.perspective` or :meth:`Camera.orthographic`.

    Pass it to :func:`render` as ``camera=`` (a list of them renders a
    batch, perspective and orthographic ones mixed), or take its OpenCV
    parameters: ``R`` (3, 3) and ``t`` (3,), ``x_cam = R @ x_world + t``,
    and :meth:`intrinsics` for an image size.

    type: "perspective" or "orthographic".
    yfov: the vertical field of view in radians (perspective); the
        horizontal one follows the image's aspect, as softrast render's
        ``--camera-index`` does, whatever the file's aspectRatio.
    xmag, ymag: half the view's width and height (orthographic); the
        width drawn is ``ymag`` times the image's aspect, as softrast
        render's ``--camera-index`` does, whatever the file's xmag.
    znear, zfar: the clipping distances (zfar 0: none); ``render`` clips
        at znear unless given ``near``, and has no far plane.
    world: (4, 4) camera-to-world matrix of its node; view: (4, 4)
        world-to-camera matrix in glTF's frame (looking down -z, scale
        and shear taken out).
    index: its index in the file's ``cameras``; node: its node (None for
        a camera made here).
    """

    __slots__ = ("type", "yfov", "aspect", "xmag", "ymag", "znear", "zfar", "world", "view",
                 "index", "node", "R", "t")

    type: Projection
    yfov: float
    aspect: float
    xmag: float
    ymag: float
    znear: float
    zfar: float
    world: NDArray[np.float64]
    view: Optional[NDArray[np.float64]]
    index: Optional[int]
    node: Optional[int]
    R: Optional[NDArray[np.float64]]
    t: Optional[NDArray[np.float64]]

    def __init__(self, eye: RealArrayLike, target: RealArrayLike,
                 up: RealArrayLike = (0.0, 1.0, 0.0), *, yfov: Optional[float] = None,
                 ymag: Optional[float] = None, znear: Optional[float] = None) -> None:
        """A camera at ``eye`` looking at ``target`` (``up`` upwards in the
        image): perspective with the vertical field of view ``yfov``
        (radians, default 60 degrees) or, given ``ymag`` instead,
        orthographic (as :func:`look_at` chooses); ``znear`` defaults to
        1e-3 and 0.  :meth:`perspective` and :meth:`orthographic` say
        more."""
        if ymag is not None:
            if yfov is not None:
                raise TypeError("yfov, ymag: give one (perspective or orthographic), not both")
            near = _number(0.0 if znear is None else znear, "znear")
            if not near >= 0.0:
                raise ValueError(f"znear: must be >= 0, got {near}")
            ymag = _ymag(ymag)
            self._set(_looking(eye, target, up, near, type="orthographic", ymag=ymag, xmag=ymag))
        else:
            near = _number(1e-3 if znear is None else znear, "znear")
            if not near > 0.0:
                raise ValueError(f"znear: must be positive, got {near}")
            fov = _fov_y(math.radians(60.0) if yfov is None else yfov, "yfov")
            self._set(_looking(eye, target, up, near, type="perspective", yfov=fov))

    @classmethod
    def _from_fields(cls, fields: Mapping[str, Any]) -> Camera:
        """A camera of a model file's fields (python/src/scene_file.c)."""
        camera = cls.__new__(cls)
        camera._set(fields)
        return camera

    def _set(self, fields: Mapping[str, Any]) -> None:
        self.type = fields["type"]
        for name in ("yfov", "aspect", "xmag", "ymag", "znear", "zfar"):
            setattr(self, name, float(fields[name]))
        self.world = np.asarray(fields["world"], np.float64)
        self.view = None if fields["view"] is None else np.asarray(fields["view"], np.float64)
        self.index = None if fields["camera"] is None else int(fields["camera"])
        self.node = None if fields["node"] is None else int(fields["node"])
        self.R = None if self.view is None else _GL_TO_CV @ self.view[:3, :3]
        self.t = None if self.view is None else _GL_TO_CV @ self.view[:3, 3]

    @classmethod
    def perspective(cls, eye: RealArrayLike, target: RealArrayLike,
                    up: RealArrayLike = (0.0, 1.0, 0.0), *, yfov: float = math.radians(60.0),
                    znear: float = 1e-3) -> Camera:
        """A pinhole camera at ``eye`` looking at ``target`` (``up``
        upwards in the image) with the vertical field of view ``yfov``
        (radians), clipping at ``znear`` (> 0)."""
        return cls(eye, target, up, yfov=_fov_y(yfov, "yfov"), znear=_number(znear, "znear"))

    @classmethod
    def orthographic(cls, eye: RealArrayLike, target: RealArrayLike,
                     up: RealArrayLike = (0.0, 1.0, 0.0), *, ymag: float,
                     znear: float = 0.0) -> Camera:
        """An orthographic camera at ``eye`` looking at ``target`` (``up``
        upwards in the image): the view is ``2 * ymag`` high (in the unit
        of the vertices) and as wide as the image's aspect makes it; rays
        run parallel to the optical axis from the plane through ``eye``;
        depth is the distance along the axis from that plane, clipped at
        ``znear`` (>= 0, may be 0)."""
        return cls(eye, target, up, ymag=_ymag(ymag), znear=_number(znear, "znear"))

    def intrinsics(self, width: int, height: int) -> NDArray[np.float64]:
        """K (3, 3) for a width x height image: square pixels, the
        principal point at the image's centre ((width - 1) / 2,
        (height - 1) / 2), the focal length from ``yfov``; for an
        orthographic camera, pixels per unit from ``ymag`` (``height /
        (2 ymag)``), K then mapping camera x, y (not x/z, y/z) to
        pixels."""
        if self.view is None:
            raise ValueError(f"camera: camera {self.index}'s node matrix is degenerate")
        _image_size(width, height)
        if self.type == "orthographic":
            # (The sign of ymag is ignored, as softrast render does.)
            if not (abs(self.ymag) > 0.0 and math.isfinite(self.ymag)):
                raise ValueError(f"camera: camera {self.index}'s ymag must not be 0")
            return _intrinsics(0.5 * height / abs(self.ymag), width, height)
        return _intrinsics(0.5 * height / math.tan(0.5 * self.yfov), width, height)

    def __repr__(self) -> str:
        lens = f"yfov={self.yfov:.6g}" if self.type == "perspective" else f"ymag={self.ymag:.6g}"
        where = f"eye={_short(self.world[:3, 3])}"
        if self.R is not None:
            where += f", forward={_short(self.R[2])}"
        source = "" if self.index is None else f"index={self.index}, node={self.node}, "
        return f"Camera({source}type={self.type!r}, {lens}, znear={self.znear:.6g}, {where})"


def _looking(eye: RealArrayLike, target: RealArrayLike, up: RealArrayLike, znear: float,
             **fields: Any) -> dict[str, Any]:
    """The fields of a camera made here, not read from a file."""
    eye_v = _vector3(eye, "eye")
    R, t = _frame(eye_v, _vector3(target, "target"), _vector3(up, "up"))
    view = np.eye(4)
    view[:3, :3] = _GL_TO_CV @ R
    view[:3, 3] = _GL_TO_CV @ t
    world = np.eye(4)
    world[:3, :3] = view[:3, :3].T
    world[:3, 3] = eye_v
    base: dict[str, Any] = dict(yfov=0.0, aspect=0.0, xmag=0.0, ymag=0.0, znear=znear, zfar=0.0,
                                world=world, view=view, camera=None, node=None)
    base.update(fields)
    return base


def _short(v: NDArray[np.float64]) -> str:
    """A vector in 6 significant digits, without numpy's array(...)."""
    return "(" + ", ".join(f"{x:.6g}" for x in v) + ")"
