"""Cameras in OpenCV's convention: x right, y down, z forward (the optical axis)."""

import math

import numpy as np


def _vector3(value, name):
    try:
        v = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise TypeError(f"{name}: expected 3 numbers, got {type(value).__name__}") from None
    if v.shape != (3,):
        raise ValueError(f"{name}: shape must be (3,), got {v.shape}")
    if not np.all(np.isfinite(v)):
        raise ValueError(f"{name}: contains NaN or infinity")
    return v


def look_at(eye, target, up=(0.0, 1.0, 0.0), *, fov_y=math.radians(60.0), width, height):
    """Camera intrinsics and extrinsics looking from ``eye`` at ``target``.

    Returns ``(K, R, t)``: ``K`` (3, 3) with square pixels and the principal
    point at the image centre, ``((width - 1) / 2, (height - 1) / 2)``, for the
    vertical field of view ``fov_y`` (radians); ``R`` (3, 3) and ``t`` (3,) map
    world to camera coordinates, ``x_cam = R @ x_world + t``, in OpenCV's
    frame: x right, y down, z from the eye towards the target.  ``up`` is the
    world direction that appears upwards in the image.
    """
    eye = _vector3(eye, "eye")
    target = _vector3(target, "target")
    up = _vector3(up, "up")
    if not (isinstance(width, (int, np.integer)) and isinstance(height, (int, np.integer))):
        raise TypeError("width, height: must be integers")
    if width < 1 or height < 1:
        raise ValueError(f"width, height: must be positive, got {width} x {height}")
    fov_y = float(fov_y)
    if not (0.0 < fov_y < math.pi):
        raise ValueError(f"fov_y: must be in (0, pi) radians, got {fov_y}")
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
    t = -R @ eye
    f = 0.5 * height / math.tan(0.5 * fov_y)
    K = np.array([[f, 0.0, 0.5 * (width - 1)], [0.0, f, 0.5 * (height - 1)], [0.0, 0.0, 1.0]])
    return K, R, t


# glTF's camera frame (x right, y up, looking down -z) to OpenCV's.
_GL_TO_CV = np.diag([1.0, -1.0, -1.0])


class Camera:
    """A camera of a model file (a glTF node's camera), as
    :func:`softrast.load` reads it into ``Scene.cameras``.

    Pass it to :func:`render` as ``camera=`` (a list of them renders a
    batch), or take its OpenCV parameters: ``R`` (3, 3) and ``t`` (3,),
    ``x_cam = R @ x_world + t``, and :meth:`intrinsics` for an image size.

    type: "perspective" or "orthographic" (which :func:`render` cannot
        draw: its cameras are pinholes).
    yfov: the vertical field of view in radians (perspective); the
        horizontal one follows the image's aspect, as softrast render's
        ``--camera-index`` does, whatever the file's aspectRatio.
    xmag, ymag: half the view's width and height (orthographic).
    znear, zfar: the clipping distances (zfar 0: none); ``render`` clips
        at znear unless given ``near``.
    world: (4, 4) camera-to-world matrix of its node; view: (4, 4)
        world-to-camera matrix in glTF's frame (looking down -z, scale
        and shear taken out).
    index: its index in the file's ``cameras``; node: its node.
    """

    __slots__ = ("type", "yfov", "aspect", "xmag", "ymag", "znear", "zfar", "world", "view",
                 "index", "node", "R", "t")

    def __init__(self, fields):
        self.type = fields["type"]
        for name in ("yfov", "aspect", "xmag", "ymag", "znear", "zfar"):
            setattr(self, name, float(fields[name]))
        self.world = np.asarray(fields["world"], np.float64)
        self.view = None if fields["view"] is None else np.asarray(fields["view"], np.float64)
        self.index = int(fields["camera"])
        self.node = int(fields["node"])
        self.R = None if self.view is None else _GL_TO_CV @ self.view[:3, :3]
        self.t = None if self.view is None else _GL_TO_CV @ self.view[:3, 3]

    def intrinsics(self, width, height):
        """K (3, 3) for a width x height image: square pixels, the
        principal point at the image's centre ((width - 1) / 2,
        (height - 1) / 2), the focal length from ``yfov``."""
        if self.type != "perspective":
            raise ValueError(f"camera: camera {self.index} is orthographic; render draws "
                             f"pinhole cameras only")
        if self.view is None:
            raise ValueError(f"camera: camera {self.index}'s node matrix is degenerate")
        if not (isinstance(width, (int, np.integer)) and isinstance(height, (int, np.integer))):
            raise TypeError("width, height: must be integers")
        if width < 1 or height < 1:
            raise ValueError(f"width, height: must be positive, got {width} x {height}")
        f = 0.5 * height / math.tan(0.5 * self.yfov)
        return np.array([[f, 0.0, 0.5 * (width - 1)], [0.0, f, 0.5 * (height - 1)],
                         [0.0, 0.0, 1.0]])

    def __repr__(self):
        return f"Camera(index={self.index}, node={self.node}, type={self.type!r})"
