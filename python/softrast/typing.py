"""The types of softrast's annotations, for programs that annotate their own
code (checked with mypy; see docs/python.md, "Types")::

    from softrast.typing import OutputName, RenderOutputs

    def depth_and_ids(mesh: softrast.Mesh, ...) -> RenderOutputs: ...

The package's own modules import this one only while type checking, so
that softrast runs on Python 3.8, where numpy's scalar types cannot be
subscripted; importing it needs Python 3.9 or later.
"""

import os
from typing import Any, Literal, Optional, Sequence, Tuple, TypedDict, Union

import numpy as np
from numpy.typing import NDArray

# A CSS color str, or (r, g, b[, a]) numbers in [0, 1] (softrast.Canvas's
# paints, render_svg's background).
from ._color import Color as Color
from ._scene import Instance, Scene
from ._softrast import Mesh

#: A path as the readers take it (os.fspath).
PathLike = Union[str, bytes, os.PathLike[str], os.PathLike[bytes]]

#: What render_svg takes: a path, or the document as bytes or as a str
#: starting with "<".
SvgSource = Union[str, os.PathLike[str], os.PathLike[bytes], bytes, bytearray, memoryview]

#: Real numbers as numpy stores them.
Real = Union[np.floating[Any], np.integer[Any], np.bool_]

#: A real array or nested sequences of numbers: vectors, matrices and
#: batches of them (the camera's K, R, t, extrinsics, poses, eye, ...).
RealArrayLike = Union[NDArray[Real], float, Sequence[float], Sequence[Sequence[float]],
                      Sequence[Sequence[Sequence[float]]]]

#: Mesh's arrays: of these dtypes (anything else is a TypeError at run
#: time) or nested sequences of numbers.
Vertices = Union[NDArray[np.float32], NDArray[np.float64], Sequence[Sequence[float]]]
Faces = Union[NDArray[np.int32], NDArray[np.int64], Sequence[Sequence[int]]]
VertexData = Union[NDArray[np.float32], NDArray[np.float64], Sequence[Sequence[float]]]
Image = NDArray[np.uint8]

#: What Scene takes as an instance: a Mesh (identity pose), (mesh, pose),
#: (mesh, pose, instance_id) or an Instance.
SceneItem = Union[Mesh, Instance, Tuple[Mesh, Optional[RealArrayLike]],
                  Tuple[Mesh, Optional[RealArrayLike], Optional[int]]]
#: What render, fit_camera and orbit take as a scene.
SceneLike = Union[Mesh, Instance, Scene, Sequence[SceneItem]]

OutputName = Literal["color", "rgba", "depth", "normal", "triangle_id", "instance_id",
                     "barycentric", "mask", "position", "uv", "material_id", "flow",
                     "occlusion"]
Shading = Literal["lit", "unlit", "pbr"]
Projection = Literal["perspective", "orthographic"]
#: render's frame= (and its alias normal_frame=): the normal and position outputs' frame.
Frame = Literal["camera", "world"]
NormalFrame = Frame
Cull = Literal["none", "back"]
Antialias = Literal["none", "msaa2", "msaa4", "msaa8", "msaa16", "ssaa2", "ssaa3", "ssaa4"]
AlphaMode = Literal["opaque", "mask", "blend"]
#: Material's texture_filter and wrap_u, wrap_v, as softrast render's
#: --texture-filter and --wrap.
TextureFilter = Literal["nearest", "bilinear", "trilinear"]
TextureWrap = Literal["repeat", "clamp", "mirror"]
#: render's lights=, as softrast render's --lights (or a list of softrast.Light).
LightsMode = Literal["auto", "file", "default", "both"]
#: render's tonemap=, as softrast render's --tonemap.
Tonemap = Literal["neutral", "aces", "none"]
#: softrast.Canvas's names: fill rules, stroke joins and caps, gradient
#: spreads, pattern wraps.
FillRule = Literal["nonzero", "evenodd"]
Join = Literal["miter", "round", "bevel"]
Cap = Literal["butt", "round", "square"]
Spread = Literal["pad", "reflect", "repeat"]
Wrap = Literal["repeat", "clamp"]
#: A polygon's points: an (N, 2) real array or a sequence of (x, y).
PointsLike = Union[NDArray[Real], Sequence[Sequence[float]]]

#: K, R, t: (3, 3) intrinsics, (3, 3) rotation and (3,) translation, or
#: batches of them.
CameraParameters = Tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]


class ShardManifest(TypedDict):
    """What a task of softrast.dask.shard_tasks returns: its shard's index,
    the rows of the table it rendered and the files it wrote."""

    shard: int
    jobs: list[int]
    files: list[str]


class RenderOutputs(TypedDict, total=False):
    """What render returns: the requested outputs only, each an array with
    a leading batch dimension for a batch of cameras."""

    color: NDArray[np.uint8]
    rgba: NDArray[np.uint8]
    depth: NDArray[np.float32]
    normal: NDArray[np.float32]
    triangle_id: NDArray[np.int32]
    instance_id: NDArray[np.int32]
    barycentric: NDArray[np.float32]
    mask: NDArray[np.bool_]
    position: NDArray[np.float32]
    uv: NDArray[np.float32]
    material_id: NDArray[np.int32]
    flow: NDArray[np.float32]
    occlusion: NDArray[np.bool_]
