"""CSS colors and (r, g, b[, a]) numbers as the library's RGBA in [0, 1],
for render_svg's background and the canvas's paints."""

from __future__ import annotations

from typing import Sequence, Tuple, Union

import numpy as np

from . import _softrast

Color = Union[str, Sequence[float]]


def to_rgba(value: Color, name: str) -> Tuple[float, float, float, float]:
    """value as (r, g, b, a); TypeError or ValueError naming `name`."""
    if isinstance(value, str):
        # The library's own CSS color parser, the one that reads fill and
        # stroke, so a color means the same here as in an SVG document.
        try:
            return _softrast.parse_color(value)
        except ValueError:
            raise ValueError(f"{name}: not a CSS color: {value!r}") from None
    expected = (f"{name}: expected a CSS color (str) or 3 or 4 numbers in [0, 1] "
                f"(r, g, b[, a]), got {type(value).__name__}")
    if isinstance(value, bytes):
        raise TypeError(expected)
    try:
        items = list(value)
        components = [float(c) for c in items]
    except TypeError:
        raise TypeError(expected) from None
    if any(isinstance(c, (bool, np.bool_)) for c in items):
        raise TypeError(f"{name}: expected numbers in [0, 1], got bool")  # not 0 and 1
    if len(components) not in (3, 4):
        raise ValueError(f"{name}: expected 3 or 4 numbers (r, g, b[, a]), "
                         f"got {len(components)}")
    if not all(0.0 <= c <= 1.0 for c in components):
        raise ValueError(f"{name}: components must be in [0, 1], got {tuple(components)}")
    if len(components) == 3:
        components.append(1.0)
    r, g, b, a = components
    return (r, g, b, a)
