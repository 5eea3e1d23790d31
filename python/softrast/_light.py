"""A model file's lights: glTF's KHR_lights_punctual, as softrast.load reads
them into Scene.lights, placed in world space by their nodes.  Read-only:
``render`` has no lights argument; it lights as docs/python.md says."""

from __future__ import annotations

from typing import Any, Mapping, NamedTuple, Optional

import numpy as np
from numpy.typing import NDArray


def _frozen(values: Any, shape: tuple[int, ...]) -> NDArray[np.float64]:
    a = np.array(values, np.float64).reshape(shape)
    a.flags.writeable = False
    return a


class Light(NamedTuple):
    """A light of a model file, in world space (``Scene.lights``).

    type: "directional", "point" or "spot", as the file gives it, also
        for a dark light (:attr:`dark`: intensity 0 or a black color),
        which gives no light.
    color: (3,) linear RGB; intensity: lux (directional) or candela
        (point, spot), as the file gives them.
    position: (3,) world position of a point or spot light, else None.
    direction: (3,) unit direction the light travels (directional) or
        the spot's axis (spot), its node's -Z; else None.
    range: the distance where a point or spot light ends (glTF's smooth
        window), None when infinite or directional.
    inner_cone, outer_cone: a spot's cone half-angles in radians (full
        light inside the inner, none outside the outer), else None.
    world: (4, 4) light-to-world matrix of its node (it shines down -Z).
    light_index: its index in the file's lights; node: its node.
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
    light_index: int
    node: int

    @property
    def dark(self) -> bool:
        """Whether it gives no light: intensity 0 or a black color
        (softrast render draws it as off)."""
        return self.intensity == 0 or not np.any(self.color > 0)

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
        return (f"Light(light_index={self.light_index}, node={self.node}, type={self.type!r}, "
                f"color={_short(self.color)}, intensity={self.intensity:.6g}{where})")


def _short(v: NDArray[np.float64]) -> str:
    return "(" + ", ".join(f"{x:.4g}" for x in v) + ")"
