"""render_svg: SVG drawings to RGBA arrays with the library's SVG reader,
the one behind ``softrast svg``."""

from __future__ import annotations

import errno
import math
import operator
import os
from typing import TYPE_CHECKING, Optional, SupportsFloat, Tuple, Union

import numpy as np
from numpy.typing import NDArray

from . import _softrast
from ._color import Color, to_rgba
from ._memory import check_memory
from ._warning import SoftrastWarning, warn_lines

if TYPE_CHECKING:
    from .typing import SvgSource


class SvgWarning(SoftrastWarning):
    """What the SVG reader skipped: an unsupported element, property or
    image source, given once per name and render as
    ``"NAME:LINE: warning: unsupported element 'foreignObject' skipped"``."""

    def __init__(self, message: str) -> None:
        super().__init__(message)


def _size(value: int, name: str) -> int:
    try:
        if isinstance(value, bool):
            raise TypeError
        n = operator.index(value)
    except TypeError:
        raise TypeError(f"{name}: expected an int, got {type(value).__name__}") from None
    if n < 1:
        raise ValueError(f"{name}: must be >= 1, got {n}")
    # Past the C int the library would refuse it anyway: say so here.
    return min(n, 2**31 - 1)


def _background(value: Optional[Color]) -> Tuple[float, float, float, float]:
    return (0.0, 0.0, 0.0, 0.0) if value is None else to_rgba(value, "background")


def _is_document(text: str) -> bool:
    # An SVG document starts with '<' (an XML declaration, a comment or
    # the svg element), possibly after a byte order mark and white space;
    # a file name does not.
    return text.lstrip("\ufeff \t\r\n").startswith("<")


def _document_name(resources_dir: Union[str, os.PathLike[str]]) -> str:
    # The reader reads a document's images from the directory of its
    # name, as it does for a file: a name in resources_dir does that
    # for a document in memory, and messages name "DIR/<svg>".
    if isinstance(resources_dir, bytes) or not isinstance(resources_dir, (str, os.PathLike)):
        raise TypeError("resources_dir: expected a directory (str or os.PathLike), "
                        f"got {type(resources_dir).__name__}")
    directory = os.fspath(resources_dir)
    if not isinstance(directory, str):
        raise TypeError("resources_dir: expected a str path, got bytes")
    if not os.path.isdir(directory):
        raise NotADirectoryError(errno.ENOTDIR, "resources_dir: not a directory", directory)
    return os.path.join(directory, "<svg>")


def render_svg(source: SvgSource, *, width: Optional[int] = None, height: Optional[int] = None,
               scale: Optional[float] = None,
               background: Optional[Color] = None,
               resources_dir: Optional[Union[str, os.PathLike[str]]] = None
               ) -> NDArray[np.uint8]:
    """Render an SVG drawing to an ``(H, W, 4)`` uint8 RGBA array.

    The drawing is rendered by softrast's SVG reader, exactly as
    ``softrast svg`` renders it: the same options give the same pixels as
    the command's PNG.

    Parameters
    ----------
    source : str, os.PathLike or a bytes-like object (bytes, memoryview, ...)
        The path of an SVG file, or the document itself: bytes-like
        objects always, a ``str`` when it starts with ``<`` (after white
        space), as every SVG document does.  ``<image>`` elements with a
        relative path are read from the file's directory (never above it);
        for a document given in memory, from ``resources_dir``, and without
        it relative paths are not read (each is skipped with a
        :class:`SvgWarning`); ``data:`` URIs work in all cases.
    width, height : int, optional
        The image size in pixels, given together; the drawing's viewBox is
        fitted in, as with ``softrast svg --size WxH``.
    scale : float, optional
        The image is the drawing's own size times ``scale`` (default 1),
        as with ``--scale``; excludes ``width`` and ``height``.
    background : str or sequence of 3 or 4 floats in [0, 1], optional
        The color the image is cleared to before drawing: a CSS color as
        SVG reads one (``"navy"``, ``"#rgb"``, ``"#rgba"``, ``"#rrggbb"``,
        ``"#rrggbbaa"``, ``"rgb(0, 0, 128)"``, ``"rgba(0, 0, 128, 0.5)"``,
        ``hsl()``, ``"transparent"``), or numbers: ``(r, g, b)`` is opaque,
        as ``--background`` is; ``(r, g, b, a)`` may be translucent.
        Default: transparent.
    resources_dir : str or os.PathLike, optional
        For a document given in memory: the directory its ``<image>``
        elements' relative paths are read from (never above it), as they
        are from a file's own directory; messages then name the document
        ``RESOURCES_DIR/<svg>``.  resvg's option of the same name.  Not
        for a path: a file's images are read from its directory.

    Returns
    -------
    numpy.ndarray
        ``(H, W, 4)`` uint8, row 0 at the top, RGBA with straight (not
        premultiplied) alpha, as the library's framebuffer holds it and
        as the command's PNG stores it.

    Raises
    ------
    ValueError
        A malformed document, a reference cycle, a root with a zero or
        negative width, height or viewBox size (SVG draws nothing of it,
        whatever ``width`` and ``height`` ask for), an image side outside
        1..8192 (SR_MAX_FRAMEBUFFER_SIZE) or work past the reader's
        budgets, with the library's message ``"NAME:LINE: what is wrong"``
        (NAME is the path as given, or ``<svg>`` for a document in
        memory); or a bad argument value, such as a ``background`` that is
        not a color.
    TypeError
        An argument of the wrong type, named in the message.
    MemoryError
        A ``width`` and ``height`` whose image would take more than the
        memory limit (SR_MEMORY_LIMIT, else the physical memory), before
        it is allocated; or layers (group opacity, masks, clip paths,
        patterns) nested deeper than what the limit leaves after the
        image holds, with the reader's ``"NAME:LINE: layers nested ..."``.
    OSError
        The file cannot be read (FileNotFoundError when it does not exist),
        with the path as ``filename``; NotADirectoryError when
        ``resources_dir`` is not a directory.

    Warnings
    --------
    What the reader skips (text, filters and other unsupported elements,
    properties, unreadable images) is reported once per name and render
    as a :class:`SvgWarning`, through the :mod:`warnings` module, also
    when the render then fails: the warnings first, then the exception.

    The render runs on the calling thread with the GIL released: Python
    threads render several drawings at once.
    """
    path: Optional[Union[str, os.PathLike[str], os.PathLike[bytes]]] = None
    data: Optional[Union[bytes, bytearray, memoryview]] = None
    if isinstance(source, (bytes, bytearray)):
        data = source
    elif isinstance(source, str) and _is_document(source):
        data = source.encode("utf-8")
    elif isinstance(source, (str, os.PathLike)):
        path = source
    else:
        # Any other bytes-like object (an mmap, a uint8 array), its bytes
        # in order whatever its layout.
        try:
            data = memoryview(source).tobytes()
        except TypeError:
            raise TypeError("source: expected a path (str or os.PathLike) or the document "
                            f"(bytes or str), got {type(source).__name__}") from None
    if (width is None) != (height is None):
        raise ValueError("width and height: give both or neither")
    if width is not None and scale is not None:
        raise ValueError("scale: excludes width and height")
    w = h = 0
    if width is not None and height is not None:
        w, h = _size(width, "width"), _size(height, "height")
        # The drawing's RGBA and the image returned.  A side past 8192, and
        # a size that comes from the document (or scale), is the library's
        # to refuse (a ValueError).
        if max(w, h) <= 8192:
            check_memory(f"render_svg: {w} x {h}", w * h * 8, "give a smaller width and height")
    s = 0.0
    if scale is not None:
        if isinstance(scale, (bool, str, bytes)) or not isinstance(scale, SupportsFloat):
            raise TypeError(f"scale: expected a number, got {type(scale).__name__}")
        s = float(scale)
        if not (s > 0 and math.isfinite(s)):
            raise ValueError(f"scale: must be a finite number > 0, got {scale}")
    name: Optional[str] = None
    if resources_dir is not None:
        if path is not None:
            raise ValueError("resources_dir: only for a document in memory; a file's images "
                             "are read from its own directory")
        name = _document_name(resources_dir)
    image, lines, error = _softrast.render_svg(path, data, name, w, h, s,
                                               _background(background))
    warn_lines(lines, 2, SvgWarning)
    if error is not None:
        raise error
    assert image is not None
    return image
