"""softrast.SoftrastWarning: what the library's readers skipped, given to
the warnings module once the reader is done (the readers run without the
GIL and hand their warnings back as lines)."""

from __future__ import annotations

import warnings
from typing import Iterable, Type


class SoftrastWarning(UserWarning):
    """What one of the library's readers skipped or left out, in the words
    the softrast tool prints: a model file's skipped texture, unsupported
    extension or bad reference (``"FILE: warning: /json/pointer: ..."``),
    an SVG element it does not draw (:class:`SvgWarning`)."""

    def __init__(self, message: str) -> None:
        # (A signature of its own: inspect finds none on Warning's.)
        super().__init__(message)


def warn_lines(lines: Iterable[str], stacklevel: int,
               category: Type[SoftrastWarning] = SoftrastWarning) -> None:
    """One warning per line; ``stacklevel`` as the caller's caller sees it
    (2: the function that calls warn_lines is the one the user called)."""
    for line in lines:
        warnings.warn(line, category, stacklevel=stacklevel + 1)
