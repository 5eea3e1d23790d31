"""render(): cameras and scene checked and composed here, pixels drawn in C."""

from __future__ import annotations

import os
import warnings
from typing import TYPE_CHECKING, Any, Dict, List, Optional, Sequence, Tuple, Union, cast

import numpy as np
from numpy.typing import NDArray

from . import _softrast
from ._arrays import real_array
from ._camera import Camera
from ._framing import fit_camera
from ._light import Light
from ._memory import check_memory
from ._scene import Instance, Scene, as_scene
from ._softrast import Mesh

if TYPE_CHECKING:
    from .typing import (Antialias, Cull, Frame, LightsMode, OutputName, PathLike, Projection,
                          RealArrayLike, RenderOutputs, SceneLike, Shading, Tonemap)

#: The outputs render() can return, with their per-view shape suffix and dtype.
OUTPUTS: Dict[str, Tuple[Tuple[int, ...], type]] = {
    "color": ((3,), np.uint8),
    "rgba": ((4,), np.uint8),
    "depth": ((), np.float32),
    "normal": ((3,), np.float32),
    "triangle_id": ((), np.int32),
    "instance_id": ((), np.int32),
    "barycentric": ((3,), np.float32),
    "mask": ((), np.bool_),
    "position": ((3,), np.float32),
    "uv": ((2,), np.float32),
    "material_id": ((), np.int32),
    "flow": ((2,), np.float32),
    "occlusion": ((), np.bool_),
}

#: What the occlusion output is computed from (_occlusion): drawn for it
#: when not asked for, then dropped.
_OCCLUSION_FROM: Tuple[OutputName, ...] = ("mask", "depth", "position", "flow")


def _step_towards(depth: NDArray[np.float64], iv: NDArray[np.intp], iu: NDArray[np.intp],
                  offset: NDArray[np.float64], axis: int) -> NDArray[np.float64]:
    """|depth change| from pixel (iv, iu) to its neighbour along `axis` on
    the side of `offset` (the projected point's, from the pixel centre);
    where that neighbour has no depth (the surface's outline, the image's
    edge), the change to the other neighbour, as the surface goes on; 0
    where neither has."""
    height, width = depth.shape
    size = width if axis == 1 else height
    at = iu if axis == 1 else iv
    change = []
    for side in (np.where(offset < 0, -1, 1), np.where(offset < 0, 1, -1)):
        n = at + side
        ok = (n >= 0) & (n < size)
        n = np.clip(n, 0, size - 1)
        there = depth[iv, n] if axis == 1 else depth[n, iu]
        with np.errstate(invalid="ignore"):
            d = np.abs(there - depth[iv, iu])
        change.append(np.where(ok & np.isfinite(d), d, np.nan))
    step = np.where(np.isnan(change[0]), change[1], change[0])
    return np.where(np.isnan(step), 0.0, step)


def _occlusion(out: Dict[str, NDArray[Any]], Rts: NDArray[np.float64], world: bool) -> NDArray[np.bool_]:
    """The occlusion output (render's docstring): True where a pixel's
    visible point has no flow target the next view sees.  From the
    renderer's buffers: the point (position, float32, in the world frame
    when `world`), where the next camera projects it (flow), the next
    view's depth at the pixel centre nearest that (depth)."""
    mask, depth, position, flow = (out[name] for name in _OCCLUSION_FROM)
    n, height, width = mask.shape
    occluded = mask.copy()      # the last view: no next view to see a point
    ys, xs = np.mgrid[0:height, 0:width].astype(np.float64)
    for b in range(n - 1):
        # The point in the next camera's frame, in double: its depth there.
        to_next = Rts[b + 1].copy()
        if not world:
            to_next = Rts[b + 1][:, :3] @ _inverse(Rts[b])
            to_next[:, 3] += Rts[b + 1][:, 3]
        p = position[b].astype(np.float64)
        z = p @ to_next[2, :3] + to_next[2, 3]
        with np.errstate(invalid="ignore"):
            u = np.rint(xs + flow[b, ..., 0])
            v = np.rint(ys + flow[b, ..., 1])
            # NaN flow: nothing there, or the point is behind the next camera.
            inside = mask[b] & (u >= 0) & (u < width) & (v >= 0) & (v < height)
        iu = np.where(inside, u, 0).astype(np.intp)
        iv = np.where(inside, v, 0).astype(np.intp)
        seen = depth[b + 1].astype(np.float64)
        # The nearest pixel centre is up to half a pixel from the projected
        # point along each axis: on the point's own surface the depth there
        # differs from the point's by the depth's step towards the point,
        # to the next pixel, times that fraction of a pixel, along each
        # axis.  2^-20 of the coordinates covers the float32 rounding of
        # position and depth (each within a few units in the last place,
        # 2^-24 of the value).
        du = xs + flow[b, ..., 0] - u
        dv = ys + flow[b, ..., 1] - v
        tolerance = (np.abs(du) * _step_towards(seen, iv, iu, du, 1) +
                     np.abs(dv) * _step_towards(seen, iv, iu, dv, 0) +
                     2.0 ** -20 * (np.abs(z) + np.abs(p).max(axis=-1)))
        with np.errstate(invalid="ignore"):
            hidden = seen[iv, iu] < z - tolerance
        occluded[b] = mask[b] & ~(inside & ~hidden)
    return occluded


def _float_array(value: object, name: str) -> NDArray[np.float64]:
    a = real_array(value, name)
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name}: contains NaN or infinity")
    return a


def _batched(value: object, name: str,
             shape: Tuple[int, ...]) -> Tuple[NDArray[np.float64], bool]:
    """(value as float64 with a leading batch axis, whether it had one)."""
    a = _float_array(value, name)
    if a.shape == shape:
        return a[None], False
    if a.ndim == len(shape) + 1 and a.shape[1:] == shape and a.shape[0] >= 1:
        return a, True
    want = ", ".join(map(str, shape))
    raise ValueError(f"{name}: shape must be ({want}) or (B, {want}), got {a.shape}")


def _cameras(K: object, R: object, t: object, extrinsics: object
             ) -> Tuple[NDArray[np.float64], NDArray[np.float64], bool]:
    """K (B, 3, 3) and [R | t] (B, 3, 4), and whether the result is batched."""
    Ks, k_batched = _batched(K, "K", (3, 3))
    if not np.array_equal(Ks[:, 2], np.broadcast_to([0.0, 0.0, 1.0], Ks[:, 2].shape)):
        raise ValueError("K: last row must be (0, 0, 1)")
    if np.any(Ks[:, 1, 0] != 0):
        raise ValueError("K: K[1, 0] must be 0")
    if np.any(Ks[:, 0, 0] <= 0) or np.any(Ks[:, 1, 1] <= 0):
        raise ValueError("K: focal lengths K[0, 0] and K[1, 1] must be positive")
    if extrinsics is not None:
        if R is not None or t is not None:
            raise TypeError("extrinsics: give either extrinsics or R and t, not both")
        a = _float_array(extrinsics, "extrinsics")
        if a.shape[-2:] == (4, 4):
            if not np.array_equal(a[..., 3, :], np.broadcast_to([0.0, 0.0, 0.0, 1.0], a[..., 3, :].shape)):
                raise ValueError("extrinsics: last row must be (0, 0, 0, 1)")
            a = a[..., :3, :]
        Rts, rt_batched = _batched(a, "extrinsics", (3, 4))
    else:
        if R is None or t is None:
            raise TypeError("R, t: both are required (or extrinsics)")
        Rs, r_batched = _batched(R, "R", (3, 3))
        t_arr = _float_array(t, "t")
        if t_arr.shape[-2:] == (3, 1):
            t_arr = t_arr[..., 0]
        ts, t_batched = _batched(t_arr, "t", (3,))
        if len(Rs) != len(ts) and 1 not in (len(Rs), len(ts)):
            raise ValueError(f"R, t: batch sizes differ ({len(Rs)} and {len(ts)})")
        n = max(len(Rs), len(ts))
        Rts = np.concatenate([np.broadcast_to(Rs, (n, 3, 3)), np.broadcast_to(ts, (n, 3))[..., None]],
                             axis=2)
        rt_batched = r_batched or t_batched
    rot = Rts[:, :, :3]
    err = np.abs(rot @ rot.transpose(0, 2, 1) - np.eye(3)).max()
    if err > 1e-5 or np.any(np.linalg.det(rot) < 0):
        raise ValueError("R: must be a rotation (orthonormal, determinant +1)")
    if len(Ks) != len(Rts) and 1 not in (len(Ks), len(Rts)):
        raise ValueError(f"K, R: batch sizes differ ({len(Ks)} and {len(Rts)})")
    n = max(len(Ks), len(Rts))
    return (np.broadcast_to(Ks, (n, 3, 3)), np.broadcast_to(Rts, (n, 3, 4)),
            k_batched or rt_batched)


def _outputs(outputs: Sequence[OutputName]) -> List[OutputName]:
    if isinstance(outputs, str) or not hasattr(outputs, "__iter__"):
        raise TypeError("outputs: expected a sequence of output names, e.g. ('depth',)")
    names = list(outputs)
    for name in names:
        if name not in OUTPUTS:
            raise ValueError(f"outputs: unknown output {name!r}; choose from {', '.join(OUTPUTS)}")
    if len(set(names)) != len(names):
        raise ValueError("outputs: a name is repeated")
    if not names:
        raise ValueError("outputs: asks for nothing")
    return names


def _flat(mesh: Mesh) -> Mesh:
    """The mesh with each face's corners its own vertices and the face's
    normal, as glTF shades a mesh without normals (the metallic-roughness
    program needs normals); faces keep their order."""
    corners = np.asarray(mesh.faces, np.int64).reshape(-1)
    v = np.asarray(mesh.vertices, np.float64)[corners].reshape(-1, 3, 3)
    n = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
    length = np.linalg.norm(n, axis=1, keepdims=True)
    n = np.divide(n, length, out=np.zeros_like(n), where=length > 0)

    def per_corner(a: Optional[NDArray[Any]]) -> Optional[NDArray[Any]]:
        return None if a is None else np.ascontiguousarray(np.asarray(a)[corners])

    return Mesh(np.ascontiguousarray(np.asarray(mesh.vertices)[corners]),
                np.arange(len(corners), dtype=np.int64).reshape(-1, 3),
                normals=np.repeat(n, 3, axis=0).astype(np.float32), colors=per_corner(mesh.colors),
                uvs=per_corner(mesh.uvs), texture=mesh.texture)


_ALPHA_MODES = {"opaque": 0, "mask": 1, "blend": 2}


def _look(inst: Instance) -> Tuple[Any, ...]:
    """What the metallic-roughness pass draws of an instance: its pose, its
    Material's factors, alpha mode and flags (a rough, double-sided
    dielectric without one), and the loaded primitive it came from."""
    m = inst.material
    pose = np.ascontiguousarray(inst.pose[:3, :])
    loaded = inst._source
    source = None if loaded is None or loaded[0] is None else (loaded[0].capsule, loaded[1])
    if m is None:
        return (pose, (1.0, 1.0, 1.0, 1.0), 0.0, 0.5, (0.0, 0.0, 0.0), 1.0, 0, 0.5, True, False,
                1.0, 1.0, 1.5, 1.0, (1.0, 1.0, 1.0), 0.0, 0.0, (0.0, 0.0, 0.0), 0.0,
                (0.0, 0.0, (1.0, 1.0, 1.0), 0.0), (0.0, 0.0, 0.0, 1.3, 100.0, 400.0),
                (0.0, 0.0, (1.0, 1.0, 1.0)), (False, (1.0, 1.0, 1.0), 1.0), source)
    # (A loaded instance is drawn from the file's own arrays, whose colors
    # do not have the factor its Mesh's have.)
    base = tuple(float(c) for c in m.base_color)
    return (pose, base, m.metallic, m.roughness, tuple(float(c) for c in m.emissive),
            m.emissive_strength, _ALPHA_MODES[m.alpha_mode], m.alpha_cutoff, m.double_sided,
            m.unlit, m.normal_scale, m.occlusion_strength, m.ior, m.specular,
            tuple(float(c) for c in m.specular_color), m.clearcoat, m.clearcoat_roughness,
            tuple(float(c) for c in m.sheen_color), m.sheen_roughness,
            (m.transmission, m.thickness, tuple(float(c) for c in m.attenuation_color),
             m.attenuation_distance),
            (m.anisotropy_strength, m.anisotropy_rotation, m.iridescence, m.iridescence_ior,
             m.iridescence_thickness_min, m.iridescence_thickness_max),
            (m.dispersion, m.diffuse_transmission,
             tuple(float(c) for c in m.diffuse_transmission_color)),
            (m.specular_glossiness, tuple(float(c) for c in m.sg_specular), m.glossiness),
            source)


# Prefiltered environments, by (file, its size and time, intensity): a few
# kept, as prefiltering costs far more than a view.
_ENVIRONMENTS: Dict[Tuple[Union[str, bytes], Optional[Tuple[int, int]], float], object] = {}


def _environment(environment: Optional[PathLike], intensity: float,
                 threads: int) -> Optional[object]:
    if environment is None:
        environment = "studio"
    if isinstance(environment, str) and environment in ("hemisphere", "none"):
        return None     # softrast render's --environment hemisphere (or none)
    try:
        intensity = float(intensity)
    except (TypeError, ValueError):
        raise TypeError(f"environment_intensity: expected a number, "
                        f"got {type(intensity).__name__}") from None
    if not (np.isfinite(intensity) and 0.001 <= intensity <= 1000):
        raise ValueError(f"environment_intensity: must be in 0.001 .. 1000, got {intensity}")
    key: Tuple[Union[str, bytes], Optional[Tuple[int, int]], float]
    if isinstance(environment, str) and environment == "studio":
        key = ("", None, intensity)
    elif isinstance(environment, (str, bytes, os.PathLike)):
        path = os.path.abspath(os.fspath(environment))
        try:
            st = os.stat(path)
        except OSError as e:
            raise type(e)(e.errno, f"environment: {os.fsdecode(path)}: {e.strerror}",
                          e.filename) from None
        key = (path, (st.st_size, st.st_mtime_ns), intensity)
    else:
        raise TypeError(f"environment: expected 'studio', 'hemisphere' or an .hdr file's path, "
                        f"got {type(environment).__name__}")
    if key not in _ENVIRONMENTS:
        if len(_ENVIRONMENTS) >= 4:
            _ENVIRONMENTS.pop(next(iter(_ENVIRONMENTS)))
        _ENVIRONMENTS[key] = _softrast.make_environment(key[0], intensity, threads)
    return _ENVIRONMENTS[key]


def _file_cameras(camera: Union[Camera, List[Camera], Tuple[Camera, ...]], width: int,
                  height: int) -> Tuple[NDArray[np.float64], NDArray[np.float64],
                                        NDArray[np.float64], NDArray[np.bool_], bool]:
    """K (B, 3, 3), [R | t] (B, 3, 4), near (B,), orthographic (B,) and
    whether batched, from one Camera or a list of them."""
    batched = isinstance(camera, (list, tuple))
    cams: List[Any] = list(camera) if isinstance(camera, (list, tuple)) else [camera]
    if not cams or not all(isinstance(c, Camera) for c in cams):
        raise TypeError("camera: expected a softrast.Camera (Scene.cameras) or a list of them")
    Ks = np.stack([c.intrinsics(width, height) for c in cams])
    Rts = np.stack([np.hstack([c.R, c.t[:, None]]) for c in cams])
    return (Ks, Rts, np.array([c.znear for c in cams]),
            np.array([c.type == "orthographic" for c in cams]), batched)


def _far(instances: Scene, poses: Sequence[Tuple[NDArray[np.float64], NDArray[np.float64]]],
         near: float) -> float:
    """An orthographic view's far plane (there is none to give): beyond
    every vertex's camera z, so that nothing is clipped there, and at
    least as far again from near, so that the farthest surface's window
    depth stays well above the cleared 0.  A float32 above both."""
    z_max = near
    for inst, (a, _) in zip(instances, poses):
        v = np.asarray(inst.mesh.vertices)
        if len(v):
            z_max = max(z_max, float((v @ a[2, :3]).max() + a[2, 3]))
    far = np.float32(near + 2.0 * (z_max - near) if z_max > near else near + 1.0)
    while not (far > z_max and far > np.float32(near)):
        far = np.nextafter(far, np.float32(np.inf))
    return float(far)


#: antialias modes, as softrast render's --aa: (MSAA samples, SSAA factor).
_ANTIALIAS = {"none": (1, 1), "msaa2": (2, 1), "msaa4": (4, 1), "msaa8": (8, 1),
              "msaa16": (16, 1), "ssaa2": (1, 2), "ssaa3": (1, 3), "ssaa4": (1, 4)}


def _antialias(antialias: Optional[Antialias], width: int, height: int) -> Tuple[int, int]:
    if antialias is None:
        antialias = "none"
    if not isinstance(antialias, str):
        raise TypeError(f"antialias: expected a mode name, got {type(antialias).__name__}")
    if antialias not in _ANTIALIAS:
        raise ValueError(f"antialias: unknown mode {antialias!r}; choose from "
                         f"{', '.join(_ANTIALIAS)}")
    msaa, ssaa = _ANTIALIAS[antialias]
    if max(width, height) * ssaa > 8192:
        raise ValueError(f"antialias: {antialias} at {width} x {height} draws more than 8192 "
                         f"pixels a side")
    return msaa, ssaa


def _check_memory(n: int, width: int, height: int, names: Sequence[str], msaa: int,
                  ssaa: int) -> None:
    """MemoryError before the outputs are allocated when they, with the
    frames drawn into, would pass the memory limit (_memory.py)."""
    pixels = width * height
    per_view = sum(int(np.prod(OUTPUTS[name][0], dtype=np.int64)) *
                   np.dtype(OUTPUTS[name][1]).itemsize for name in names)
    # The frame drawn into (RGBA and a float depth); antialiased color is
    # drawn into samples first, which SSAA also filters in float RGBA rows.
    frames = pixels * 8
    if (msaa > 1 or ssaa > 1) and ("color" in names or "rgba" in names):
        frames += pixels * ssaa * ssaa * msaa * 8 + (pixels * ssaa * 16 if ssaa > 1 else 0)
    aa = f"msaa{msaa}" if msaa > 1 else f"ssaa{ssaa}" if ssaa > 1 else "none"
    views = f"{n} views" if n > 1 else "1 view"
    check_memory(f"render: {views} of {width} x {height} ({', '.join(names)}; antialias {aa})",
                 n * pixels * per_view + frames,
                 "render fewer cameras at a time, a smaller size or fewer outputs")


#: softrast render's --tonemap as the extension takes it (sr_tonemap_op).
_TONEMAPS = {"neutral": 1, "aces": 2, "none": 3}

#: softrast render's --lights as the extension takes it (python/src/render.c).
_LIGHTS_MODES = {"default": 0, "file": 1, "both": 2}


def _lights(lights: Union[LightsMode, Sequence[Light], None], scene: Scene
            ) -> Tuple[int, List[Tuple[Any, ...]]]:
    """render's lights= as softrast render's --lights: the mode and the
    lights the program takes, the first 8 lit ones of the scene's (or of
    the given list, which stands for the scene's) in their order."""
    if lights is None:
        lights = "auto"
    if isinstance(lights, str):
        if lights not in ("auto", "file", "default", "both"):
            raise ValueError(f"lights: must be 'auto', 'file', 'default', 'both' or a list of "
                             f"softrast.Light, got {lights!r}")
        mode: str = lights
        given: Sequence[Light] = scene.lights
    else:
        if not isinstance(lights, (list, tuple)):
            raise TypeError(f"lights: expected 'auto', 'file', 'default', 'both' or a list of "
                            f"softrast.Light, got {type(lights).__name__}")
        for i, light in enumerate(lights):
            if not isinstance(light, Light):
                raise TypeError(f"lights[{i}]: expected a softrast.Light, "
                                f"got {type(light).__name__}")
        mode, given = "file", lights
    lit = [light for light in given if not light.dark][:8]
    if mode == "auto":
        mode = "file" if lit else "default"
    elif mode == "file" and not lit and isinstance(lights, str):
        warnings.warn("lights='file': the scene has no lit lights of its own: it is lit by the "
                      "ambient light alone", stacklevel=3)
    return _LIGHTS_MODES[mode], [light._program() for light in lit]


def _frames(frame: Optional[Frame], normal_frame: Optional[Frame]) -> Tuple[str, str]:
    """The frames of the normal and position outputs: each its own
    default (camera, world) unless frame (or its alias normal_frame)
    names one for both."""
    for value, name in ((frame, "frame"), (normal_frame, "normal_frame")):
        if value is not None and not isinstance(value, str):
            raise TypeError(f"{name}: expected 'camera', 'world' or None, "
                            f"got {type(value).__name__}")
        if value is not None and value not in ("camera", "world"):
            raise ValueError(f"{name}: must be 'camera' or 'world', got {value!r}")
    if frame is not None and normal_frame is not None and frame != normal_frame:
        raise TypeError(f"frame, normal_frame: normal_frame is another name for frame; "
                        f"give one (got {frame!r} and {normal_frame!r})")
    chosen = frame if frame is not None else normal_frame
    return (chosen or "camera", chosen or "world")


def _material_ids(sc: Scene) -> List[int]:
    """Each instance's material_id: its Material's index in
    Scene.materials (the same object), else -1."""
    index = {id(m): i for i, m in enumerate(sc.materials)}
    return [-1 if inst.material is None else index.get(id(inst.material), -1) for inst in sc]


def _inverse(Rt: NDArray[np.float64]) -> NDArray[np.float64]:
    """The (3, 4) rows of [R | t]'s inverse (the rotation as given, not
    its transpose: R is checked orthonormal only to 1e-5)."""
    return np.linalg.inv(np.vstack([Rt, [0.0, 0.0, 0.0, 1.0]]))[:3]


def _int_arg(value: int, name: str, low: int, high: int) -> int:
    if not isinstance(value, (int, np.integer)) or isinstance(value, bool):
        raise TypeError(f"{name}: expected an int, got {type(value).__name__}")
    if not low <= value <= high:
        raise ValueError(f"{name}: must be in {low} .. {high}, got {value}")
    return int(value)


def render(scene: SceneLike, *, K: Optional[RealArrayLike] = None,
           R: Optional[RealArrayLike] = None, t: Optional[RealArrayLike] = None,
           extrinsics: Optional[RealArrayLike] = None,
           camera: Union[Camera, List[Camera], Tuple[Camera, ...], None] = None, width: int,
           height: int,
           outputs: Sequence[OutputName] = ("color", "depth"), threads: int = 0,
           near: Optional[float] = None, frame: Optional[Frame] = None,
           normal_frame: Optional[Frame] = None,
           background: RealArrayLike = (0.0, 0.0, 0.0), shading: Shading = "lit",
           environment: Optional[PathLike] = None, environment_intensity: float = 0.6,
           shadows: Optional[bool] = None, ground: bool = False,
           projection: Optional[Projection] = None, antialias: Optional[Antialias] = None,
           cull: Cull = "none",
           lights: Union[LightsMode, Sequence[Light], None] = None, exposure: float = 0.0,
           tonemap: Tonemap = "neutral") -> RenderOutputs:
    """Render a scene from one camera or a batch of cameras.

    scene: a :class:`Mesh`, an :class:`Instance`, a :class:`Scene` or a list
        of them (see Scene).
    K: (3, 3) or (B, 3, 3) OpenCV intrinsics ``[[fx, s, cx], [0, fy, cy],
        [0, 0, 1]]``: pixel (u, v) has its centre at u = fx x/z + s y/z + cx,
        v = fy y/z + cy, integer u, v at pixel centres (OpenCV's convention).
    R, t: (3, 3) and (3,) (or batched) world-to-camera rotation and
        translation, ``x_cam = R @ x_world + t``, camera x right, y down,
        z forward.  Or ``extrinsics``: (3, 4)/(4, 4), or batched, ``[R | t]``.
    (no camera): without K, R, t, extrinsics and camera, softrast render's
        default camera for the image: :func:`fit_camera` (its
        ``projection`` from ``projection``).
    camera: instead of K, R, t: a :class:`Camera` of a loaded file
        (``Scene.cameras``) or of :meth:`Camera.orthographic` or
        :meth:`Camera.perspective`, or a list of them for a batch; its K
        for width x height (:meth:`Camera.intrinsics`), R, t, its type
        (perspective or orthographic) and its znear as ``near`` unless
        given.
    projection: with ``K``: "perspective" (the default, a pinhole, as
        above) or "orthographic": rays parallel to the optical axis, pixel
        (u, v) seeing u = fx x + s y + cx, v = fy y + cy (``fx``, ``fy`` in
        pixels per unit of the vertices; :func:`look_at` with ``ymag``
        makes such a ``K``), depth still camera z, clipped at ``near``
        (default 0; may be 0).  A :class:`Camera` brings its own type.
    width, height: the image size in pixels, 1 .. 8192.
    outputs: names from :data:`OUTPUTS`:

        - ``color`` (H, W, 3) uint8: vertex colors times the texture (gray
          without either; a glTF material's base color and base color
          texture, see :func:`load`), lit by a headlight
          (``shading="lit"``), as they are (``shading="unlit"``), or by
          glTF's metallic-roughness model (``shading="pbr"``: each
          instance's :class:`Material` with its alpha mode and a loaded
          file's textures, a rough dielectric without one; the lights
          ``lights`` chooses, softrast render's ambient light and tone
          curve;
          meshes without normals shaded flat, as glTF asks), over
          ``background`` (RGB in [0, 1]).
        - ``rgba`` (H, W, 4) uint8: ``color`` with alpha, straight (not
          premultiplied): the surface's alpha (vertex color alpha times
          the texture's), 0 where nothing is.  No blending: a translucent
          surface hides what is behind it.
        - ``depth`` (H, W) float32: camera-space z (distance along the
          optical axis, the unit of the vertices), ``inf`` where nothing is.
        - ``normal`` (H, W, 3) float32: unit normal in the camera frame, or
          the world frame with ``frame="world"``; interpolated vertex
          normals, else the face normal (counter-clockwise faces' front);
          zero where nothing is.
        - ``triangle_id`` (H, W) int32: the index of the visible face in its
          mesh's ``faces``, -1 where nothing is.
        - ``instance_id`` (H, W) int32: the visible instance's ID, -1 where
          nothing is.
        - ``barycentric`` (H, W, 3) float32: the perspective-correct weights
          of the visible face's three vertices (in ``faces`` order).
        - ``mask`` (H, W) bool: where a surface is.
        - ``position`` (H, W, 3) float32: the visible point, where the
          pixel centre's ray meets the visible face (computed as depth
          is), in the world frame (``frame="camera"``: the camera frame,
          whose z is ``depth``); NaN where nothing is.
        - ``uv`` (H, W, 2) float32: the visible mesh's ``uvs`` at the
          barycentrics, as the library stores them: v runs up, (0, 0) the
          texture image's bottom-left corner (a glTF file's TEXCOORD v is
          ``1 - v`` here; a loaded file's are its base color texture's
          set through its KHR_texture_transform); NaN where nothing is
          and on meshes without ``uvs``.
        - ``material_id`` (H, W) int32: the index in ``Scene.materials``
          (a loaded file's materials) of the visible instance's
          ``Instance.material``; -1 where nothing is and for instances
          whose material is not listed there (or who have none).
        - ``flow`` (H, W, 2) float32 (batches of cameras): where the next
          camera of the batch sees the visible point, less the pixel
          (optical flow of a static scene, whatever hides the point there:
          see ``occlusion``): (du, dv) in pixels; NaN where nothing is,
          where the point is not in front of the next camera, and in the
          last view (a single camera's too).
        - ``occlusion`` (H, W) bool (batches of cameras): where the
          visible point has no ``flow`` target the next camera sees (the
          occlusion mask of optical-flow datasets; ``mask & ~occlusion``
          is where flow is valid): the point is behind the next camera,
          projects outside its image (the nearest pixel centre is off
          it), or lies behind the next view's depth at that pixel centre
          by more than the depth's step to the next pixel towards the
          point times the point's offset from the centre, along each
          axis (how far apart they are on the same surface), plus 2^-20
          of the coordinates (float32 rounding).  Every point of the last
          view is occluded; False where nothing is.

        IDs, depth, barycentrics, positions, uvs, flow, occlusion and mask
        are never blended or antialiased:
        each pixel shows the surface nearest along its centre's ray (the
        first drawn of equals), sampled at the pixel centre, whatever
        ``antialias`` says.
    antialias: ``color`` and ``rgba`` only, under every ``shading``, as
        softrast render's ``--aa``: None or "none" (the default: each
        pixel sampled at its centre); "msaa2", "msaa4", "msaa8", "msaa16"
        (that many coverage and depth samples a pixel at the standard
        positions, shaded once a pixel and triangle, box-resolved);
        "ssaa2", "ssaa3", "ssaa4" (k x k samples a pixel, each shaded,
        box-filtered down; at most 8192 samples a side).  An edge pixel
        mixes the surface with the background (``rgba``: its color
        channels too, its alpha the covered part).
    cull: "none" (the default: both sides of every face are drawn) or
        "back": faces seen from behind (clockwise on screen, as their
        normal points away from the camera; counter-clockwise under a
        mirroring pose) are not drawn, in every output.  Faster, as a
        closed mesh seen from outside shows only its front faces; wrong
        for open meshes, whose back faces show, and for a camera inside a
        closed one.
    threads: rendering threads, 0 for every CPU; the result does not depend
        on it.
    frame: the frame of ``normal`` and ``position``: None (the default)
        for each its own (``normal`` the camera's, ``position`` the
        world's), or "camera" or "world" for both.  ``normal_frame`` is
        another name for it (given both, they must agree).
    near: surfaces closer than this (camera z) are clipped (default 1e-3,
        0 for an orthographic view, or the camera's znear; > 0 for a
        perspective view, >= 0 for an orthographic one); there is no far
        plane.
    shading: "lit", "unlit" or "pbr" (see ``color``).  With "pbr" the
        world's +y is up for the sky, the environment and the shadow's
        fit, as in glTF and softrast render.
    environment: "pbr" only: "studio" (the built-in neutral studio; the
        default, None, as softrast render's) or the path of an
        equirectangular Radiance ``.hdr`` file (+y up) for image-based
        light with the key light alone; "hemisphere" (or "none", as the
        command's) for the sky-and-ground
        ambient with the key, fill and rim lights.  Environments are at
        ``environment_intensity`` (default 0.6, as softrast render;
        0.001 .. 1000).  Prefiltered once and kept for later calls.
    shadows: "pbr" only: the key light casts a shadow (a 1024-texel
        shadow map fitted to every instance's box, as softrast render's
        ``--shadows on``); None (the default): on with ``ground``, else
        off, as the command's default.
    ground: "pbr" only: softrast render's ``--ground``, a shadow catcher
        under the instances (a square 4 times their world box's width,
        under its lowest point, +y up) that shows the key light's shadow
        and nothing else: black blended over the background (in ``rgba``
        the background darkened, with the shadow's alpha where the
        background is transparent), drawn after the opaque instances and
        before the blended ones; the rest of the ground is not drawn.  It is in ``color`` and ``rgba`` only, not in the geometry
        outputs; with ``shadows=False`` it shows nothing.
    lights: "pbr" only, softrast render's ``--lights``: "file" (the
        scene's own, ``Scene.lights``: a glTF file's KHR_lights_punctual,
        the first 8 that are not dark, in lux and candela as they are),
        "default" (the key, fill and rim lights placed relative to the
        camera, only the key with an environment), "both" (the scene's,
        then the default ones, 8 in all) or "auto" (the default, None:
        the scene's when it has some, else the default ones); or a list
        of :class:`Light` (``Light.directional``, ``point``, ``spot``),
        in world space, used as a file's are.  The ambient light (the
        environment or hemisphere) stays.  The shadow is cast by the
        strongest directional light of the scene's (none when it has
        only point and spot lights; the default key with "both" then).
    exposure: "pbr" only, softrast render's ``--exposure``: radiance times
        2^exposure before the tone curve, in stops, -20 .. 20 (default 0;
        a file's lights in physical units may want a negative one).
    tonemap: "pbr" only, softrast render's ``--tonemap``: "neutral"
        (Khronos PBR Neutral, the default), "aces" (ACES filmic) or
        "none" (a clamp).

    Returns a dict from each requested name to its array; with batched
    cameras every array has a leading dimension B.  The GIL is released
    while drawing.  Raises TypeError or ValueError naming the argument
    that is wrong, and MemoryError, before allocating, when the outputs
    of every camera and the frames drawn into would take more than the
    memory limit (SR_MEMORY_LIMIT, else the physical memory).
    """
    sc = as_scene(scene)
    width = _int_arg(width, "width", 1, 8192)
    height = _int_arg(height, "height", 1, 8192)
    if camera is not None:
        if not (K is None and R is None and t is None and extrinsics is None):
            raise TypeError("camera: give either camera or K with R, t or extrinsics, not both")
        if projection is not None:
            raise TypeError("projection: goes with K; a camera has its own type")
        Ks, Rts, nears, orthos, batched = _file_cameras(camera, width, height)
    elif K is None:
        if not (R is None and t is None and extrinsics is None):
            raise TypeError("K: required with R, t or extrinsics")
        # No camera: softrast render's default one.
        if projection is not None and not isinstance(projection, str):
            raise TypeError(f"projection: expected 'perspective' or 'orthographic', "
                            f"got {type(projection).__name__}")
        Ks, Rts, nears, orthos, batched = _file_cameras(
            fit_camera(sc, width=width, height=height,
                       projection="perspective" if projection is None else projection),
            width, height)
    else:
        if projection is None:
            projection = "perspective"
        if not isinstance(projection, str):
            raise TypeError(f"projection: expected 'perspective' or 'orthographic', "
                            f"got {type(projection).__name__}")
        if projection not in ("perspective", "orthographic"):
            raise ValueError(f"projection: must be 'perspective' or 'orthographic', "
                             f"got {projection!r}")
        Ks, Rts, batched = _cameras(K, R, t, extrinsics)
        orthos = np.full(len(Ks), projection == "orthographic")
        nears = np.where(orthos, 0.0, 1e-3)
    threads = _int_arg(threads, "threads", 0, 64)
    names = _outputs(outputs)
    if near is not None:
        try:
            near = float(near)
        except (TypeError, ValueError):
            raise TypeError(f"near: expected a number, got {type(near).__name__}") from None
        if not (np.isfinite(near) and (near >= 0 if orthos.all() else near > 0)):
            want = "finite number >= 0" if orthos.all() else "positive finite number"
            raise ValueError(f"near: must be a {want}, got {near}")
        nears = np.full(len(Ks), near)
    elif not np.all(np.isfinite(nears) & np.where(orthos, nears >= 0, nears > 0)):
        raise ValueError("camera: its znear must be a finite number, positive for a "
                         "perspective camera, >= 0 for an orthographic one")
    normal_in, position_in = _frames(frame, normal_frame)
    if cull not in ("none", "back"):
        raise ValueError(f"cull: must be 'none' or 'back', got {cull!r}")
    if shading not in ("lit", "unlit", "pbr"):
        raise ValueError(f"shading: must be 'lit', 'unlit' or 'pbr', got {shading!r}")
    bg = _float_array(background, "background")
    if bg.shape != (3,):
        raise ValueError(f"background: shape must be (3,), got {bg.shape}")
    bg = np.clip(bg, 0.0, 1.0)
    rgb = (float(bg[0]), float(bg[1]), float(bg[2]))
    if ((environment is not None or shadows or ground or lights is not None or exposure != 0.0
         or tonemap != "neutral") and shading != "pbr"):
        raise ValueError("environment, shadows, ground, lights, exposure, tonemap: "
                         "need shading='pbr'")
    if isinstance(exposure, bool) or not isinstance(exposure, (int, float, np.integer,
                                                                np.floating)):
        raise TypeError(f"exposure: expected a number, got {type(exposure).__name__}")
    if not -20.0 <= float(exposure) <= 20.0:
        raise ValueError(f"exposure: must be in -20 .. 20 stops, got {exposure}")
    if tonemap not in _TONEMAPS:
        raise ValueError(f"tonemap: must be 'neutral', 'aces' or 'none', got {tonemap!r}")
    lights_mode, program_lights = _lights(lights, sc) if shading == "pbr" else (0, [])
    if not isinstance(ground, (bool, np.bool_)):
        raise TypeError(f"ground: expected a bool, got {type(ground).__name__}")
    if shadows is None:
        shadows = bool(ground)
    if not isinstance(shadows, (bool, np.bool_)):
        raise TypeError(f"shadows: expected a bool or None, got {type(shadows).__name__}")
    env = _environment(environment, environment_intensity, threads) if shading == "pbr" else None
    msaa, ssaa = _antialias(antialias, width, height)

    n = len(Ks)
    asked = names
    if "occlusion" in names:
        names = [name for name in names if name != "occlusion"]
        names += [name for name in _OCCLUSION_FROM if name not in names]
    _check_memory(n, width, height, names + [name for name in asked if name not in names],
                  msaa, ssaa)
    out: Dict[str, NDArray[Any]] = {name: np.empty((n, height, width) + OUTPUTS[name][0], OUTPUTS[name][1]) for name in names}
    inv_t = [np.linalg.inv(inst.pose[:3, :3]).T for inst in sc]
    materials = _material_ids(sc) if "material_id" in out else None
    ids = [i if inst.instance_id is None else inst.instance_id for i, inst in enumerate(sc)]
    images = [name for name in ("color", "rgba") if name in out]
    # How each Mesh's texture is sampled: its Material's sampler (a loaded
    # file's), else the library's defaults.
    samplers = [(0, 0, 0) if inst.material is None else inst.material._sampler() for inst in sc]
    # The metallic-roughness look draws meshes without normals flat, from
    # copies: the geometry outputs are drawn from the meshes as given.
    pbr = shading == "pbr" and images
    passes: List[Tuple[Sequence[str], List[Mesh]]] = [(names, [inst.mesh for inst in sc])]
    looks: List[Tuple[Tuple[Any, ...]]] = []
    if pbr:
        # (A loaded instance's look brings the file's arrays, flat normals made.)
        looks = [(_look(inst),) for inst in sc]
        passes = [([name for name in names if name not in images], passes[0][1]),
                  (images, [_flat(inst.mesh) if inst.mesh.normals is None and
                            look[0][-1] is None else inst.mesh
                            for inst, look in zip(sc, looks)])]
    for b in range(n):
        Rt = Rts[b]
        poses = [(np.ascontiguousarray(Rt[:, :3] @ inst.pose[:3, :] +
                                       np.hstack([np.zeros((3, 3)), Rt[:, 3:]])),
                  np.ascontiguousarray(Rt[:, :3] @ nt if normal_in == "camera" else nt))
                 for inst, nt in zip(sc, inv_t)]
        far = _far(sc, poses, float(nears[b])) if orthos[b] else 1.0
        geometry: Dict[str, Any] = dict(materials=materials)
        if position_in == "world":
            geometry["to_frame"] = _inverse(Rt)
        if "flow" in out and b + 1 < n:
            # From this camera to the next one's: [R' | t'] [R | t]^-1.
            to_next = Rts[b + 1][:, :3] @ _inverse(Rt)
            to_next[:, 3] += Rts[b + 1][:, 3]
            geometry.update(flow_K=np.ascontiguousarray(Ks[b + 1]),
                            flow_Rt=np.ascontiguousarray(to_next), flow_ortho=bool(orthos[b + 1]))
        for wanted, meshes in passes:
            if not wanted:
                continue
            color_pbr = pbr and wanted is images
            looks_now: Sequence[Any] = ids
            if color_pbr:
                looks_now = looks
            instances = [(mesh, a, nm, iid, look[0] if color_pbr else None, sampler)
                         for mesh, (a, nm), iid, look, sampler
                         in zip(meshes, poses, ids, looks_now, samplers)]
            extra: Dict[str, Any] = dict(pbr=True, view=np.ascontiguousarray(Rt), environment=env,
                         shadows=bool(shadows), ground=bool(ground), lights=program_lights,
                         lights_mode=lights_mode, exposure=float(exposure),
                         tonemap=_TONEMAPS[tonemap]) if color_pbr else {}
            views = {name: out[name][b] if name in wanted else None for name in OUTPUTS}
            _softrast.render(instances, np.ascontiguousarray(Ks[b]), width, height,
                             float(nears[b]), threads, views["depth"], views["triangle_id"],
                             views["instance_id"], views["barycentric"], views["normal"],
                             views["color"], views["mask"], rgb, shading == "lit",
                             rgba=views["rgba"], material_id=views["material_id"],
                             position=views["position"], uv=views["uv"], flow=views["flow"],
                             ortho=bool(orthos[b]), far=far, msaa=msaa, ssaa=ssaa,
                             cull=cull == "back", **extra, **(geometry if not color_pbr else {}))
    if "occlusion" in asked:
        out["occlusion"] = _occlusion(out, Rts, position_in == "world")
        out = {name: out[name] for name in asked}
    if not batched:
        out = {name: a[0] for name, a in out.items()}
    return cast("RenderOutputs", out)
