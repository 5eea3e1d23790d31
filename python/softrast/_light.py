"""Lights in world space: glTF's KHR_lights_punctual, as softrast.load reads
them into Scene.lights, placed by their nodes, or made with
Light.directional, Light.point and Light.spot; render(lights=...) lights a
scene with them as softrast render's --lights does."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Mapping, NamedTuple, Optional, Tuple

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from .typing import RealArrayLike

#: sr_light_type's values, as the extension names them.
_TYPES = {"directional": 1, "point": 2, "spot": 3}


def _frozen(values: Any, shape: tuple[int, ...]) -> NDArray[np.float64]:
    a = np.array(values, np.float64).reshape(shape)
    a.flags.writeable = False
    return a


def _vector(value: Any, name: str) -> NDArray[np.float64]:
    try:
        a = np.array(value, np.float64)
    except (TypeError, ValueError):
        raise TypeError(f"{name}: expected 3 numbers, got {type(value).__name__}") from None
    if a.shape != (3,):
        raise ValueError(f"{name}: shape must be (3,), got {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name}: contains NaN or infinity")
    return a


def _scalar(value: Any, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name}: expected a number, got {type(value).__name__}")
    v = float(value)
    if not math.isfinite(v):
        raise ValueError(f"{name}: must be finite, got {v}")
    return v


def _placed(kind: str, position: Optional[Any], direction: Optional[Any], color: Any,
            intensity: Any, range_: Optional[Any], inner: Optional[Any],
            outer: Optional[Any]) -> Light:
    """A Light made in Python: checked as the glTF reader checks a file's,
    its world matrix the node that would place it (at ``position``, its
    -Z down ``direction``)."""
    c = _vector(color, "color")
    if np.any(c < 0):
        raise ValueError(f"color: must not be negative, got {tuple(c)}")
    i = _scalar(intensity, "intensity")
    if i < 0:
        raise ValueError(f"intensity: must not be negative, got {i}")
    p = None if position is None else _vector(position, "position")
    d = None
    if direction is not None:
        d = _vector(direction, "direction")
        length = float(np.linalg.norm(d))
        if not length > 0:
            raise ValueError("direction: must not be zero")
        d = d / length
    r = None
    if range_ is not None:
        r = _scalar(range_, "range")
        if not r > 0:
            raise ValueError(f"range: must be above 0 (None: infinite), got {r}")
    if kind == "spot":
        inner = _scalar(inner, "inner_cone")
        outer = _scalar(outer, "outer_cone")
        if not 0 < outer <= math.pi / 2:
            raise ValueError(f"outer_cone: {outer} is outside (0, pi/2]")
        if not 0 <= inner < outer:
            raise ValueError(f"inner_cone: {inner} is outside [0, outer_cone {outer})")
    world = np.eye(4)
    if d is not None:
        # -Z down the direction, X level where it can be.
        z = -d
        x = np.cross((0.0, 1.0, 0.0), z)
        if np.linalg.norm(x) < 1e-6:
            x = np.cross((1.0, 0.0, 0.0), z)
        x /= np.linalg.norm(x)
        world[:3, 0], world[:3, 1], world[:3, 2] = x, np.cross(z, x), z
    if p is not None:
        world[:3, 3] = p
    return Light(type=kind, color=_frozen(c, (3,)), intensity=i,
                 position=None if p is None else _frozen(p, (3,)),
                 direction=None if d is None else _frozen(d, (3,)), range=r,
                 inner_cone=None if inner is None else float(inner),
                 outer_cone=None if outer is None else float(outer),
                 world=_frozen(world, (4, 4)), light_index=None, node=None)


class Light(NamedTuple):
    """A light in world space: a model file's (``Scene.lights``), or one
    made with :meth:`directional`, :meth:`point` or :meth:`spot` for
    ``render(lights=[...])`` or ``Scene(lights=...)``.

    type: "directional", "point" or "spot", as the file gives it, also
        for a dark light (:attr:`dark`: intensity 0 or a black color),
        which gives no light.
    color: (3,) linear RGB; intensity: lux (directional) or candela
        (point, spot), as the file gives them (glTF's units, which
        ``render`` takes as they are; see docs/pbr.md "Units").
    position: (3,) world position of a point or spot light, else None.
    direction: (3,) unit direction the light travels (directional) or
        the spot's axis (spot), its node's -Z; else None.
    range: the distance where a point or spot light ends (glTF's smooth
        window), None when infinite or directional.
    inner_cone, outer_cone: a spot's cone half-angles in radians (full
        light inside the inner, none outside the outer), else None.
    world: (4, 4) light-to-world matrix of its node (it shines down -Z).
    light_index: its index in the file's lights; node: its node (None
        for a light made in Python).
    """

    type: str
    color: NDArray[np.float64]
    intensity: float
    position: Optional[NDArray[np.float64]]
    direction: Optional[NDArray[np.float64]]
    range: Optional[float]
    inner_cone: Optional[float]
    outer_cone: Optional[float]
    world: NDArray[np.float64]
    light_index: Optional[int]
    node: Optional[int]

    @property
    def dark(self) -> bool:
        """Whether it gives no light: intensity 0 or a black color
        (softrast render draws it as off)."""
        return self.intensity == 0 or not np.any(self.color > 0)

    @classmethod
    def directional(cls, direction: RealArrayLike, *,
                    color: RealArrayLike = (1.0, 1.0, 1.0), intensity: float = 1.0) -> Light:
        """A light from far away travelling along ``direction`` (any
        length), of ``intensity`` lux."""
        return _placed("directional", None, direction, color, intensity, None, None, None)

    @classmethod
    def point(cls, position: RealArrayLike, *, color: RealArrayLike = (1.0, 1.0, 1.0),
              intensity: float = 1.0, range: Optional[float] = None) -> Light:
        """A light at ``position`` shining every way, of ``intensity``
        candela, ending at ``range`` (glTF's smooth window; None:
        infinite)."""
        return _placed("point", position, None, color, intensity, range, None, None)

    @classmethod
    def spot(cls, position: RealArrayLike, direction: RealArrayLike, *,
             color: RealArrayLike = (1.0, 1.0, 1.0), intensity: float = 1.0,
             range: Optional[float] = None, inner_cone: float = 0.0,
             outer_cone: float = math.pi / 4) -> Light:
        """A point light at ``position`` shining down ``direction`` in a
        cone: full inside ``inner_cone``, none outside ``outer_cone``
        (half-angles in radians, 0 <= inner < outer <= pi/2; glTF's
        defaults)."""
        return _placed("spot", position, direction, color, intensity, range, inner_cone,
                       outer_cone)

    def _program(self) -> Tuple[Any, ...]:
        """The sr_light the program takes (python/src/render.c's lights)."""
        zero = np.zeros(3)
        vector = self.direction if self.type == "directional" else self.position
        direction = self.direction if self.type == "spot" else None
        return (_TYPES[self.type], _floats(zero if vector is None else vector),
                _floats(self.color), float(self.intensity),
                _floats(zero if direction is None else direction),
                float(self.inner_cone or 0.0), float(self.outer_cone or 0.0),
                float(self.range or 0.0))

    @classmethod
    def _from_fields(cls, f: Mapping[str, Any]) -> Light:
        """A light of a model file's fields (python/src/load.c)."""
        kind = f["type"]
        local = kind in ("point", "spot")
        spot = kind == "spot"
        direction = f["direction"] if spot else f["vector"] if kind == "directional" else None
        return cls(type=kind, color=_frozen(f["color"], (3,)), intensity=float(f["intensity"]),
                   position=_frozen(f["vector"], (3,)) if local else None,
                   direction=None if direction is None else _frozen(direction, (3,)),
                   range=float(f["range"]) if local and f["range"] > 0 else None,
                   inner_cone=float(f["inner_cone"]) if spot else None,
                   outer_cone=float(f["outer_cone"]) if spot else None,
                   world=_frozen(f["world"], (4, 4)), light_index=int(f["light"]),
                   node=int(f["node"]))

    def __repr__(self) -> str:
        where = "" if self.position is None else f", position={_short(self.position)}"
        if self.direction is not None:
            where += f", direction={_short(self.direction)}"
        source = ("" if self.node is None
                  else f"light_index={self.light_index}, node={self.node}, ")
        return (f"Light({source}type={self.type!r}, color={_short(self.color)}, "
                f"intensity={self.intensity:.6g}{where}{', dark' if self.dark else ''})")


def _floats(v: NDArray[np.float64]) -> Tuple[float, float, float]:
    return (float(v[0]), float(v[1]), float(v[2]))


def _short(v: NDArray[np.float64]) -> str:
    return "(" + ", ".join(f"{x:.4g}" for x in v) + ")"
