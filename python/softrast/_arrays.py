"""Numeric array arguments as float64, refusing what numpy would quietly
read as numbers: a bool array (True as 1.0) is never what a caller means
by intrinsics, a pose or a color, so it is a TypeError naming the
argument, as the C extension's arrays (python/src/mesh.c) refuse it."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray


def real_array(value: Any, name: str) -> NDArray[np.float64]:
    """value (an array, nested sequences or a number) as float64; a
    TypeError naming `name` for booleans, strings, complex numbers or
    anything else that is not real numbers."""
    try:
        a = np.asarray(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name}: expected a numeric array, got {type(value).__name__}") from None
    if a.dtype.kind == "O":
        # Python objects (Fractions, Decimals, a mix of numpy scalars)
        # that convert to float; bools among them do too, so look.
        if any(isinstance(v, (bool, np.bool_)) for v in a.flat):
            raise TypeError(f"{name}: dtype must be a real number type, got bool")
        try:
            return a.astype(np.float64)
        except (TypeError, ValueError):
            raise TypeError(f"{name}: expected a numeric array, "
                            f"got {type(value).__name__}") from None
    if a.dtype.kind not in "iuf":
        raise TypeError(f"{name}: dtype must be a real number type, got {a.dtype}")
    return a.astype(np.float64)
