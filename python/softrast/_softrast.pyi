# The types of the C extension softrast._softrast (python/src/*.c); the
# names and positional/keyword kinds are the functions' argument parsing,
# held to the built module by tests/test_types.py (mypy's stubtest).
from typing import Any, Optional, Sequence, Tuple, Union, final

import numpy as np
from numpy.typing import NDArray

from .typing import Faces, Image, PathLike, VertexData, Vertices

library_version: str
have_svg: bool
framing_direction: Tuple[float, float, float]
framing_margin: float
framing_fov_deg: float

@final
class Mesh:
    def __init__(self, vertices: Vertices, faces: Faces, normals: Optional[VertexData] = None,
                 colors: Optional[VertexData] = None, uvs: Optional[VertexData] = None,
                 texture: Optional[Image] = None) -> None: ...
    @property
    def vertices(self) -> Union[NDArray[np.float32], NDArray[np.float64]]: ...
    @property
    def faces(self) -> Union[NDArray[np.int32], NDArray[np.int64]]: ...
    @property
    def normals(self) -> Optional[NDArray[np.float32]]: ...
    @property
    def colors(self) -> Optional[NDArray[np.float32]]: ...
    @property
    def uvs(self) -> Optional[NDArray[np.float32]]: ...
    @property
    def texture(self) -> Optional[NDArray[np.uint8]]: ...

def read_image(path: PathLike, /) -> NDArray[np.uint8]: ...
def decode_image(data: bytes, name: str, /) -> NDArray[np.uint8]: ...
def write_png(path: PathLike, image: NDArray[np.uint8], /) -> None: ...
def render_svg(path: Optional[PathLike], data: Optional[Union[bytes, bytearray, memoryview]],
               name: Optional[PathLike], width: int, height: int, scale: float,
               background: Tuple[float, float, float, float], /
               ) -> Tuple[Optional[NDArray[np.uint8]], list[str], Optional[Exception]]: ...
def parse_color(text: str, /) -> Tuple[float, float, float, float]: ...

# The package's own entry points into the library (softrast.render,
# load, load_mesh, fit_camera wrap them).
def load_mesh(path: PathLike, /) -> dict[str, Any]: ...
def load_scene(path: PathLike, /) -> dict[str, Any]: ...
def make_environment(path: PathLike, intensity: float, threads: int, /) -> object: ...
def fit_camera(sets: Sequence[Tuple[NDArray[np.float32], NDArray[np.float32]]], width: int,
               height: int, fov: float, ortho: bool, /
               ) -> Tuple[Tuple[float, float, float], Tuple[float, float, float],
                          Tuple[float, float, float], float, float, float]: ...
def render(instances: Sequence[Tuple[Any, ...]], K: NDArray[np.float64], width: int, height: int,
           near: float, threads: int, depth: Optional[NDArray[np.float32]],
           triangle_id: Optional[NDArray[np.int32]], instance_id: Optional[NDArray[np.int32]],
           barycentric: Optional[NDArray[np.float32]], normal: Optional[NDArray[np.float32]],
           color: Optional[NDArray[np.uint8]], mask: Optional[NDArray[np.bool_]],
           background: Tuple[float, float, float], lit: bool,
           rgba: Optional[NDArray[np.uint8]] = None, pbr: bool = False,
           view: Optional[NDArray[np.float64]] = None, environment: object = None,
           shadows: bool = False, general: bool = False, ortho: bool = False, far: float = 0.0,
           msaa: int = 1, ssaa: int = 1, ground: bool = False, cull: bool = False) -> None: ...
