"""softrast: exact, deterministic CPU rendering of triangle meshes and SVG drawings to numpy arrays.

Depth, triangle and instance IDs, barycentric coordinates, normals, a
coverage mask and a shaded color image from one call, for OpenCV-style
cameras (intrinsics ``K``, world-to-camera ``R``, ``t``), on the CPU, with no
OpenGL.  The same inputs give the same bytes for any number of threads.

>>> import numpy as np, softrast
>>> mesh = softrast.Mesh(vertices, faces)            # or softrast.load(path)
>>> K, R, t = softrast.look_at(eye=(0, 0, 3), target=(0, 0, 0), width=640, height=480)
>>> out = softrast.render(mesh, K=K, R=R, t=t, width=640, height=480,
...                       outputs=("depth", "triangle_id"))
>>> out["depth"].shape, out["depth"].dtype
((480, 640), dtype('float32'))

SVG drawings render to RGBA arrays with :func:`render_svg`, as ``softrast
svg`` renders them:

>>> icon = softrast.render_svg("icon.svg", width=64, height=64)
>>> icon.shape, icon.dtype
((64, 64, 4), dtype('uint8'))

2D drawing into RGBA arrays, paths filled and stroked with colors,
gradients and patterns through the same code (:class:`Canvas`):

>>> canvas = softrast.Canvas(64, 64, background="white")
>>> canvas.fill(softrast.Path().move_to(8, 8).line_to(56, 8).line_to(32, 56).close(), "navy")
>>> canvas.image.shape
(64, 64, 4)

Without a camera, ``render(mesh, width=640, height=480)`` frames the mesh as
``softrast render`` does (:func:`fit_camera`); :func:`orbit` makes a batch
of cameras circling a scene.

See docs/python.md in the source tree for the conventions.
"""

from ._softrast import Mesh, Path, PathView, features, library_version, read_image, write_png
from ._camera import Camera, look_at
from ._light import Light
from ._material import Material
from ._scene import Animation, Instance, Scene, load, load_mesh
from ._framing import fit_camera, orbit
from ._render import OUTPUTS, render
from ._svg import SvgWarning, render_svg
from ._warning import SoftrastWarning
from ._draw import Canvas, LinearGradient, Pattern, RadialGradient

__version__ = library_version
__all__ = ["Camera", "Light", "Mesh", "Instance", "Material", "Scene", "load", "load_mesh",
           "Animation", "look_at",
           "fit_camera", "orbit",
           "features", "read_image", "render", "render_svg", "SoftrastWarning", "SvgWarning",
           "write_png", "OUTPUTS",
           "__version__",
           "Canvas", "Path", "PathView", "LinearGradient", "RadialGradient", "Pattern"]
