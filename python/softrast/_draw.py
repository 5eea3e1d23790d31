"""Canvas: 2D drawing into an (H, W, 4) uint8 RGBA array with the library's
paths, fills, strokes and paints (sr_path, sr_path_dash, sr_make_stroke_outline,
sr_fill_polygon_paint), the code its SVG reader draws with.  The paints
(colors, LinearGradient, RadialGradient, Pattern) are checked here, where
a wrong value is named; the canvas's state (its transform, its clip's
coverage and the saved states) is kept here as SVG's transform and
clip-path would give it; python/src/canvas.c draws."""

from __future__ import annotations

import math
import operator
from typing import TYPE_CHECKING, Any, Iterable, List, Optional, Sequence, Tuple, Union

import numpy as np
from numpy.typing import NDArray

from . import _softrast
from ._color import Color, to_rgba
from ._memory import check_memory
from ._softrast import Path

if TYPE_CHECKING:
    from .typing import Cap, FillRule, Join, PointsLike, RealArrayLike, Spread, Wrap

_NAMES = _softrast.draw2d_names
_IDENTITY = (1.0, 0.0, 0.0, 1.0, 0.0, 0.0)
# What the library's paint takes, as a tuple for Canvas2D (canvas.c):
# (kind, rgba, six numbers of geometry, stops, spread, image, wrap,
# transform a..f, opacity).
_PaintTuple = Tuple[int, Tuple[float, float, float, float], Tuple[float, ...],
                    Optional[NDArray[np.float64]], int, Optional[NDArray[np.uint8]], int,
                    Tuple[float, float, float, float, float, float], float]


def _name(value: str, name: str, table: str) -> int:
    names = _NAMES[table]
    if not isinstance(value, str):
        raise TypeError(f"{name}: expected one of {', '.join(map(repr, names))}, "
                        f"got {type(value).__name__}")
    if value not in names:
        raise ValueError(f"{name}: expected one of {', '.join(map(repr, names))}, got {value!r}")
    return names[value]


def _real(value: float, name: str) -> float:
    if isinstance(value, (bool, np.bool_, str, bytes)):
        raise TypeError(f"{name}: expected a number, got {type(value).__name__}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name}: expected a number, got {type(value).__name__}") from None
    if not math.isfinite(v):
        raise ValueError(f"{name}: must be finite, got {value!r}")
    return v


def _point(value: Sequence[float], name: str) -> Tuple[float, float]:
    try:
        x, y = value
    except (TypeError, ValueError):
        raise TypeError(f"{name}: expected a point (x, y), got {value!r}") from None
    return _real(x, f"{name}[0]"), _real(y, f"{name}[1]")


def _transform(value: Optional[RealArrayLike], name: str = "transform"
               ) -> Tuple[float, float, float, float, float, float]:
    """A 2x3 matrix [[a, c, e], [b, d, f]] (x' = a x + c y + e, y' = b x +
    d y + f: SVG's matrix(a b c d e f)) as (a, b, c, d, e, f)."""
    if value is None:
        return _IDENTITY
    m = np.asarray(value)
    if m.dtype.kind not in "iuf":
        raise TypeError(f"{name}: expected a 2x3 matrix of numbers, got dtype {m.dtype}")
    if m.shape != (2, 3):
        raise ValueError(f"{name}: shape must be (2, 3), [[a, c, e], [b, d, f]], got {m.shape}")
    m = m.astype(np.float64)
    if not np.all(np.isfinite(m)):
        raise ValueError(f"{name}: contains NaN or infinity")
    a, c, e = (float(v) for v in m[0])
    b, d, f = (float(v) for v in m[1])
    det = a * d - b * c
    if not (abs(det) > 1e-300) or not all(math.isfinite(v) for v in (d / det, a / det, b / det,
                                                                       c / det)):
        raise ValueError(f"{name}: the matrix is singular (determinant {det})")
    return (a, b, c, d, e, f)


def _stops(value: Sequence[Tuple[float, Color]]) -> NDArray[np.float64]:
    if isinstance(value, (str, bytes)):
        raise TypeError("stops: expected a sequence of (offset, color) pairs, "
                        f"got {type(value).__name__}")
    try:
        pairs = list(value)
    except TypeError:
        raise TypeError("stops: expected a sequence of (offset, color) pairs, "
                        f"got {type(value).__name__}") from None
    limit = _softrast.max_gradient_stops
    if not 1 <= len(pairs) <= limit:
        raise ValueError(f"stops: {len(pairs)} stops, the library takes 1..{limit}")
    out = np.empty((len(pairs), 5), np.float64)
    for i, pair in enumerate(pairs):
        try:
            offset, color = pair
        except (TypeError, ValueError):
            raise TypeError(f"stops[{i}]: expected an (offset, color) pair, got {pair!r}") from None
        o = _real(offset, f"stops[{i}] offset")
        if not 0.0 <= o <= 1.0:
            raise ValueError(f"stops[{i}] offset: must be in [0, 1], got {o}")
        if i > 0 and o < out[i - 1, 0]:
            raise ValueError(f"stops[{i}] offset: {o} is below the offset before it, "
                             f"{out[i - 1, 0]}")
        out[i, 0] = o
        out[i, 1:] = to_rgba(color, f"stops[{i}] color")
    out.flags.writeable = False  # the gradient's, as checked
    return out


def _num(v: float) -> str:
    """A coordinate as repr shows it: 2 not 2.0, 0.25 as is."""
    return f"{v:g}"


def _pt(p: Tuple[float, float]) -> str:
    return f"({_num(p[0])}, {_num(p[1])})"


def _stops_text(stops: NDArray[np.float64], spread: str) -> str:
    n = len(stops)
    return f"{n} stop{'s' if n != 1 else ''}, spread={spread!r}"


class _Immutable:
    """A paint is checked and converted once, when made: its fields are
    read-only (a changed one would not be drawn)."""

    __slots__ = ()

    def __setattr__(self, name: str, value: Any) -> None:
        if hasattr(self, "_paint"):
            raise AttributeError(f"{type(self).__name__} is immutable: make a new one")
        object.__setattr__(self, name, value)


class LinearGradient(_Immutable):
    """A linear gradient from `start` (offset 0) to `end` (offset 1), constant
    across, in paint space (``transform`` maps it to pixels).

    stops: (offset, color) pairs, offsets in [0, 1] in order (1 to 256);
    spread: beyond the ends, "pad" (the end colors), "reflect" or "repeat";
    transform: a 2x3 matrix [[a, c, e], [b, d, f]], SVG's
    ``gradientTransform="matrix(a b c d e f)"``.  As SVG's linearGradient in
    userSpaceOnUse units.
    """

    __slots__ = ("start", "end", "stops", "spread", "transform", "_paint")

    def __init__(self, start: Sequence[float], end: Sequence[float],
                 stops: Sequence[Tuple[float, Color]], *, spread: Spread = "pad",
                 transform: Optional[RealArrayLike] = None) -> None:
        self.start = _point(start, "start")
        self.end = _point(end, "end")
        self.stops = _stops(stops)
        self.spread: Spread = spread
        self.transform = _transform(transform)
        self._paint: _PaintTuple = (
            _NAMES["kind"]["linear"], (0.0, 0.0, 0.0, 0.0), (*self.start, *self.end, 0.0, 0.0),
            self.stops, _name(spread, "spread", "spread"), None, 0, self.transform, 1.0)

    def __repr__(self) -> str:
        return (f"LinearGradient(start={_pt(self.start)}, end={_pt(self.end)}, "
                f"{_stops_text(self.stops, self.spread)})")


class RadialGradient(_Immutable):
    """A radial gradient: offset 1 on the circle (`center`, `radius`), 0 on
    the focal circle (`focal`, default the center, `focal_radius`), the
    cone between them, as SVG's radialGradient (cx, cy, r, fx, fy, fr) in
    userSpaceOnUse units.  stops, spread, transform: as LinearGradient's.
    """

    __slots__ = ("center", "radius", "focal", "focal_radius", "stops", "spread", "transform",
                 "_paint")

    def __init__(self, center: Sequence[float], radius: float,
                 stops: Sequence[Tuple[float, Color]], *,
                 focal: Optional[Sequence[float]] = None, focal_radius: float = 0.0,
                 spread: Spread = "pad", transform: Optional[RealArrayLike] = None) -> None:
        self.center = _point(center, "center")
        self.radius = _real(radius, "radius")
        if not self.radius > 0:
            raise ValueError(f"radius: must be > 0, got {self.radius}")
        self.focal = self.center if focal is None else _point(focal, "focal")
        self.focal_radius = _real(focal_radius, "focal_radius")
        if not self.focal_radius >= 0:
            raise ValueError(f"focal_radius: must be >= 0, got {self.focal_radius}")
        self.stops = _stops(stops)
        self.spread: Spread = spread
        self.transform = _transform(transform)
        self._paint: _PaintTuple = (
            _NAMES["kind"]["radial"], (0.0, 0.0, 0.0, 0.0),
            (*self.center, self.radius, *self.focal, self.focal_radius), self.stops,
            _name(spread, "spread", "spread"), None, 0, self.transform, 1.0)

    def __repr__(self) -> str:
        focal = "" if self.focal == self.center else f", focal={_pt(self.focal)}"
        if self.focal_radius:
            focal += f", focal_radius={_num(self.focal_radius)}"
        return (f"RadialGradient(center={_pt(self.center)}, radius={_num(self.radius)}{focal}, "
                f"{_stops_text(self.stops, self.spread)})")


class Pattern(_Immutable):
    """An RGBA image as paint: an (H, W, 4) uint8 array, straight alpha,
    texel (i, j) covering [i, i+1) x [j, j+1) of paint space, sampled
    bilinearly at texel centres and repeated (``wrap="repeat"``) or with
    its edge texels extended (``"clamp"``); ``transform`` (2x3, as the
    gradients') maps paint space to pixels.  The array is kept, not
    copied (unless it is not C-contiguous): a change to it shows in the
    next draw.
    """

    __slots__ = ("image", "wrap", "transform", "_paint")

    def __init__(self, image: NDArray[np.uint8], *, transform: Optional[RealArrayLike] = None,
                 wrap: Wrap = "repeat") -> None:
        if not isinstance(image, np.ndarray):
            raise TypeError(f"image: expected a numpy array, got {type(image).__name__}")
        if image.dtype != np.uint8:
            raise TypeError(f"image: dtype must be uint8, got {image.dtype}")
        h, w = image.shape[:2] if image.ndim == 3 else (0, 0)
        if image.ndim != 3 or image.shape[2] != 4 or not (1 <= h <= 8192 and 1 <= w <= 8192):
            raise ValueError(f"image: shape must be (H, W, 4), 1 <= H, W <= 8192, "
                             f"got {image.shape}")
        self.image: NDArray[np.uint8] = np.ascontiguousarray(image)
        self.wrap: Wrap = wrap
        self.transform = _transform(transform)
        self._paint: _PaintTuple = (
            _NAMES["kind"]["pattern"], (0.0, 0.0, 0.0, 0.0), (0.0,) * 6, None, 0, self.image,
            _name(wrap, "wrap", "wrap"), self.transform, 1.0)

    def __repr__(self) -> str:
        h, w = self.image.shape[:2]
        return f"Pattern({w}x{h} image, wrap={self.wrap!r})"


Paint = Union[str, Sequence[float], LinearGradient, RadialGradient, Pattern]
Shape = Union[Path, "PointsLike", Sequence["PointsLike"]]


def _paint(value: Paint, opacity: float) -> _PaintTuple:
    if isinstance(value, (LinearGradient, RadialGradient, Pattern)):
        p = value._paint
    else:
        if not isinstance(value, (str, Iterable)) or isinstance(value, bytes):
            raise TypeError("paint: expected a color (a CSS color str or 3 or 4 numbers), "
                            "LinearGradient, RadialGradient or Pattern, "
                            f"got {type(value).__name__}")
        rgba = to_rgba(value, "paint")  # what is wrong with the color, named
        p = (_NAMES["kind"]["color"], rgba, (0.0,) * 6, None, 0, None, 0, _IDENTITY, 1.0)
    return (p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], opacity)


def _dashes(value: Optional[Sequence[float]]) -> Tuple[float, ...]:
    """A dash list as stroke takes it: None or lengths >= 0, at most the
    library's SR_MAX_DASHES."""
    if value is None:
        return ()
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__"):
        raise TypeError(f"dashes: expected a sequence of lengths, got {type(value).__name__}")
    limit = _softrast.max_dashes
    if len(value) > limit:
        raise ValueError(f"dashes: at most {limit} values, got {len(value)}")
    out = tuple(_real(v, f"dashes[{i}]") for i, v in enumerate(value))
    for i, v in enumerate(out):
        if v < 0:
            raise ValueError(f"dashes[{i}]: must be >= 0, got {v}")
    return out


def _opacity(value: float) -> float:
    v = _real(value, "opacity")
    if not 0.0 <= v <= 1.0:
        raise ValueError(f"opacity: must be in [0, 1], got {v}")
    return v


def _contours(shape: Any) -> List[Any]:
    """A polygon given as points, or as a list of contours (arrays or
    nested lists of (x, y)), as the list of contours Canvas2D takes."""
    if isinstance(shape, np.ndarray):
        return list(shape) if shape.ndim == 3 else [shape]
    if isinstance(shape, (list, tuple)) and shape and np.ndim(shape[0]) == 2:
        return list(shape)
    return [shape]


Matrix = Tuple[float, float, float, float, float, float]


def _mul(m: Matrix, n: Matrix) -> Matrix:
    """m * n (n applied first), term for term as the SVG reader composes
    its transforms (svg.c mat_mul), so that a drawing gives its bytes."""
    a, b, c, d, e, f = m
    return (a * n[0] + c * n[1], b * n[0] + d * n[1], a * n[2] + c * n[3],
            b * n[2] + d * n[3], a * n[4] + c * n[5] + e, b * n[4] + d * n[5] + f)


def _matrix(a: float, b: float, c: float, d: float, e: float, f: float) -> Matrix:
    """Six numbers, each checked under its name."""
    return (_real(a, "a"), _real(b, "b"), _real(c, "c"), _real(d, "d"), _real(e, "e"),
            _real(f, "f"))


def _invertible(m: Matrix, what: str) -> Matrix:
    """m, when finite with a finite inverse; a ValueError saying `what`."""
    a, b, c, d = m[:4]
    det = a * d - b * c
    if not all(math.isfinite(v) for v in m):
        raise ValueError(f"{what}: the transform would not be finite")
    if not (abs(det) > 1e-300) or not all(math.isfinite(v / det) for v in (a, b, c, d)):
        raise ValueError(f"{what}: the transform would be singular (determinant {det:g})")
    return m


class _Saved:
    """What Canvas.save returns: used in a with statement, the state is
    restored at its end."""

    __slots__ = ("_canvas", "_depth")

    def __init__(self, canvas: Canvas, depth: int) -> None:
        self._canvas = canvas
        self._depth = depth

    def __enter__(self) -> Canvas:
        return self._canvas

    def __exit__(self, *exc: object) -> None:
        saved = self._canvas._saved
        if len(saved) < self._depth:
            raise RuntimeError("restore: the state this with statement saved was restored "
                               "already")
        del saved[self._depth:]
        self._canvas.restore()


def _size(value: int, name: str) -> int:
    if isinstance(value, bool):
        raise TypeError(f"{name}: expected an int, got bool")
    try:
        n = operator.index(value)
    except TypeError:
        raise TypeError(f"{name}: expected an int, got {type(value).__name__}") from None
    if not 1 <= n <= 8192:
        raise ValueError(f"{name}: must be in 1..8192, got {n}")
    return n


class Canvas:
    """A 2D canvas over an (H, W, 4) uint8 RGBA image (straight alpha, row 0
    at the top, pixel (x, y) covering [x, x+1) x [y, y+1)), drawn with the
    library's fills and strokes in place: ``Canvas(width, height)`` makes
    a new image (MemoryError, before it is allocated, when it would take
    more than the memory limit: SR_MEMORY_LIMIT, else the physical
    memory), ``Canvas.from_array(image)`` draws into the caller's.
    Each draw blends source-over as the library's RGBA8 framebuffer does,
    so a drawing gives the bytes ``render_svg`` gives for the same SVG.

    Draws are under the canvas's state, as in cairo and HTML's canvas: a
    current transform from user space to pixels (``translate``,
    ``scale``, ``rotate``, ``transform``, ``set_transform``; SVG's
    ``transform`` attribute), which maps paths, strokes (their width and
    dashes too, as SVG strokes) and paints; and a clip (``clip``: SVG's
    ``clip-path``), which each later draw is cut by.  ``save()`` and
    ``restore()`` keep and bring back both (``with canvas.save():``).
    """

    __slots__ = ("_core", "_matrix", "_clip", "_saved")

    def __init__(self, width: int, height: int, *, background: Optional[Color] = None) -> None:
        w, h = _size(width, "width"), _size(height, "height")
        check_memory(f"Canvas: {w} x {h}", w * h * 4, "give a smaller width and height")
        image = np.zeros((h, w, 4), np.uint8)
        self._core = _softrast.Canvas2D(image)
        self._reset_state()
        if background is not None:
            self._core.clear(to_rgba(background, "background"))

    @classmethod
    def from_array(cls, image: NDArray[np.uint8]) -> Canvas:
        """A canvas drawing into `image` itself, an (H, W, 4) uint8 array,
        C-contiguous and writeable (no copy is made)."""
        canvas = cls.__new__(cls)
        canvas._core = _softrast.Canvas2D(image)
        canvas._reset_state()
        return canvas

    def _reset_state(self) -> None:
        self._matrix: Matrix = _IDENTITY
        # The clip as the coverage of the image (read-only), None for none.
        self._clip: Optional[NDArray[np.uint8]] = None
        self._saved: List[Tuple[Matrix, Optional[NDArray[np.uint8]]]] = []

    # -- the current transform ---------------------------------------------

    def get_transform(self) -> Matrix:
        """The current transform (a, b, c, d, e, f): user space to pixels,
        x' = a x + c y + e, y' = b x + d y + f (SVG's matrix(a b c d e f),
        cairo's Matrix(xx, yx, xy, yy, x0, y0), HTML's getTransform()).
        ``set_transform(*canvas.get_transform())`` puts it back."""
        return self._matrix

    def set_transform(self, a: float, b: float, c: float, d: float, e: float,
                      f: float) -> None:
        """Make (a, b, c, d, e, f) the current transform (as get_transform
        gives it), whatever it was; it must be finite and invertible."""
        self._matrix = _invertible(_matrix(a, b, c, d, e, f), "set_transform")

    def reset_transform(self) -> None:
        """Make the identity the current transform: user space is pixels."""
        self._matrix = _IDENTITY

    def transform(self, a: float, b: float, c: float, d: float, e: float, f: float) -> None:
        """Multiply the current transform by (a, b, c, d, e, f), applied
        first to what is drawn next (SVG's transform="matrix(a b c d e f)"
        on an inner group; HTML's transform(), cairo's transform())."""
        m = _invertible(_matrix(a, b, c, d, e, f), "transform")
        self._matrix = _invertible(_mul(self._matrix, m), "transform")

    def translate(self, tx: float, ty: float) -> None:
        """Move user space's origin to (tx, ty) of the current user space."""
        m = (1.0, 0.0, 0.0, 1.0, _real(tx, "tx"), _real(ty, "ty"))
        self._matrix = _invertible(_mul(self._matrix, m), "translate")

    def scale(self, sx: float, sy: Optional[float] = None) -> None:
        """Scale user space by sx along x and sy (default sx) along y;
        neither may be 0.  Strokes scale too: their width is in user
        units, as in SVG and cairo."""
        x = _real(sx, "sx")
        y = x if sy is None else _real(sy, "sy")
        if x == 0 or y == 0:
            raise ValueError(f"{'sx' if x == 0 else 'sy'}: must not be 0 (the transform would be "
                             "singular)")
        self._matrix = _invertible(_mul(self._matrix, (x, 0.0, 0.0, y, 0.0, 0.0)), "scale")

    def rotate(self, angle: float) -> None:
        """Rotate user space by `angle` radians, from +x towards +y (clockwise
        on the image, whose y points down; SVG's rotate() takes degrees)."""
        r = _real(angle, "angle")
        c, s = math.cos(r), math.sin(r)
        self._matrix = _invertible(_mul(self._matrix, (c, s, -s, c, 0.0, 0.0)), "rotate")

    # -- the clip and the saved states -------------------------------------

    def clip(self, shape: Shape, *, rule: FillRule = "nonzero", antialias: bool = True) -> None:
        """Intersect the clip with `shape` (as fill takes it) under the
        current transform, by `rule`: later draws show only inside both.
        The clip is a coverage of the image's pixels (antialiased edges
        partly in, as SVG's clip-path; antialias=False: pixel centres), so
        it stays where it was drawn when the transform changes; coverages
        multiply, rounded to 8 bits, as a clipPath with a clip-path of its
        own does."""
        if not isinstance(antialias, bool):
            raise TypeError(f"antialias: expected a bool, got {type(antialias).__name__}")
        r = _name(rule, "rule", "rule")
        cov: NDArray[np.uint8] = self._core.coverage(
            shape if isinstance(shape, Path) else _contours(shape), r, antialias, self._matrix)
        if self._clip is not None:
            cov = ((self._clip.astype(np.uint16) * cov + 127) // 255).astype(np.uint8)
        cov.flags.writeable = False  # kept by saved states as it is
        self._clip = cov

    def reset_clip(self) -> None:
        """Remove the clip: draws reach every pixel again."""
        self._clip = None

    def save(self) -> _Saved:
        """Push the current transform and clip; restore() pops them.  The
        result is a context manager: ``with canvas.save(): ...`` restores
        at the end of the block."""
        self._saved.append((self._matrix, self._clip))
        return _Saved(self, len(self._saved))

    def restore(self) -> None:
        """Bring back the transform and clip of the last save() (a
        RuntimeError without one)."""
        if not self._saved:
            raise RuntimeError("restore: no saved state (restore() without a save())")
        self._matrix, self._clip = self._saved.pop()

    @property
    def image(self) -> NDArray[np.uint8]:
        """The (H, W, 4) uint8 RGBA array drawn into."""
        image: NDArray[np.uint8] = self._core.image
        return image

    @property
    def width(self) -> int:
        """The image's width in pixels (its shape[1])."""
        return int(self._core.image.shape[1])

    @property
    def height(self) -> int:
        """The image's height in pixels (its shape[0])."""
        return int(self._core.image.shape[0])

    def __repr__(self) -> str:
        return f"Canvas({self.width}x{self.height})"

    def clear(self, color: Color = "transparent") -> None:
        """Set every pixel to `color` (a CSS color or (r, g, b[, a]) in [0,
        1]), whatever the transform and the clip."""
        self._core.clear(to_rgba(color, "color"))

    def fill(self, shape: Shape, paint: Paint, *, rule: FillRule = "nonzero",
             antialias: bool = True, opacity: float = 1.0) -> None:
        """Fill `shape` (a Path, whose subpaths are closed for the fill;
        an (N, 2) array of polygon points; or a list of such arrays, the
        contours of one polygon, holes included) with `paint`: a color (a
        CSS color str, or (r, g, b[, a]) in [0, 1]), a LinearGradient, a
        RadialGradient or a Pattern, at `opacity`.  rule: "nonzero" or
        "evenodd"; antialias: exact area coverage, or (False) pixel centres.
        The shape and the paint are in user space (the current transform
        maps them to pixels), cut by the clip.
        """
        if not isinstance(antialias, bool):
            raise TypeError(f"antialias: expected a bool, got {type(antialias).__name__}")
        p = _paint(paint, _opacity(opacity))
        r = _name(rule, "rule", "rule")
        if p[8] == 0.0:
            return  # the library reads opacity 0 as 1: nothing to draw
        self._core.fill(shape if isinstance(shape, Path) else _contours(shape), self._mapped(p), r,
                        antialias, self._matrix, self._clip)

    def stroke(self, path: Path, paint: Paint, *, width: float = 1.0, join: Join = "miter",
               cap: Cap = "butt", miter_limit: float = 4.0, antialias: bool = True,
               opacity: float = 1.0, dashes: Optional[Sequence[float]] = None,
               dash_offset: float = 0.0) -> None:
        """Stroke `path` with `paint` (as fill's): the outline of a line
        `width` user units wide along each subpath (pixels under the
        identity transform; the transform maps the outline, so a scale
        widens it, as in SVG and cairo), with joins ("miter",
        "round", "bevel"; a miter longer than miter_limit times the width
        is bevelled) and caps on open subpaths ("butt", "round",
        "square"), filled nonzero, as SVG strokes.  `dashes` (lengths of
        dashes and gaps in turn, in user units along the path, at most 32; an
        odd list repeats) strokes only the dashes, each with its caps,
        the pattern starting `dash_offset` into itself at every subpath,
        as SVG's stroke-dasharray and stroke-dashoffset.
        """
        if not isinstance(path, Path):
            raise TypeError(f"path: expected a softrast.Path, got {type(path).__name__} (a "
                            "polygon's points make one: Path().add_polygon(points))")
        if not isinstance(antialias, bool):
            raise TypeError(f"antialias: expected a bool, got {type(antialias).__name__}")
        w = _real(width, "width")
        if not 0 < w <= 262144:
            raise ValueError(f"width: must be in (0, 262144], got {w}")
        limit = _real(miter_limit, "miter_limit")
        if not limit >= 1:
            raise ValueError(f"miter_limit: must be >= 1, got {limit}")
        p = _paint(paint, _opacity(opacity))
        j, c = _name(join, "join", "join"), _name(cap, "cap", "cap")
        d, offset = _dashes(dashes), _real(dash_offset, "dash_offset")
        if p[8] == 0.0:
            return
        self._core.stroke(path, self._mapped(p), w, j, c, limit, antialias, d, offset,
                          self._matrix, self._clip)

    def _mapped(self, p: _PaintTuple) -> _PaintTuple:
        """The paint with its space under the current transform, as SVG
        maps a userSpaceOnUse gradient by the element's transform."""
        if self._matrix == _IDENTITY:
            return p
        m = _invertible(_mul(self._matrix, p[7]), "paint transform")
        return (p[0], p[1], p[2], p[3], p[4], p[5], p[6], m, p[8])
