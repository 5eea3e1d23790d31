"""How much memory one call's images may take, checked before they are allocated.

The same limit as the softrast tool's (apps/softrast/memory_limit.c): the
environment variable SR_MEMORY_LIMIT when set (bytes, or 512M, 8G, 1.5T),
else the physical memory, or less under a ulimit.  Linux overcommits: an
image larger than the machine holds is rarely refused when allocated, and
the process is killed later as its pages are touched, so the estimate is
compared first and a MemoryError (numpy's own kind of failure to allocate)
names the sizes instead.
"""

from __future__ import annotations

import os
import re
from typing import Tuple

_UNITS = "KMGT"


def _parse_bytes(text: str) -> int:
    m = re.fullmatch(r"\s*([0-9]*\.?[0-9]+(?:[eE][+-]?[0-9]+)?)\s*(?:([KMGTkmgt])(i?)(B?))?\s*",
                     text)
    value = float(m.group(1)) if m else 0.0
    if not m or not value > 0 or value >= 18e18:
        raise ValueError(f"SR_MEMORY_LIMIT: expected a size in bytes such as 512M or 8G "
                         f"(got {text!r})")
    if m.group(2):
        value *= 1024 ** (_UNITS.index(m.group(2).upper()) + 1)
    return int(value)


def memory_limit() -> Tuple[int, str]:
    """(the most bytes a call's images may take, what sets it)."""
    env = os.environ.get("SR_MEMORY_LIMIT")
    if env is not None:
        return _parse_bytes(env), f"SR_MEMORY_LIMIT={env}"
    limit, what = 2**64, "the physical memory"
    try:
        limit = os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (AttributeError, ValueError, OSError):
        pass
    try:
        import resource
    except ImportError:   # not on every platform
        return limit, what
    for name, said in (("RLIMIT_AS", "the address space limit (ulimit -v)"),
                       ("RLIMIT_DATA", "the data size limit (ulimit -d)")):
        soft = resource.getrlimit(getattr(resource, name))[0] if hasattr(resource, name) else -1
        if soft != resource.RLIM_INFINITY and 0 <= soft < limit:
            limit, what = soft, said
    return limit, what


def format_bytes(n: int) -> str:
    """Bytes as people read them: "8.5 GiB", "640 MiB"."""
    v, unit = float(n), "bytes"
    for u in ("KiB", "MiB", "GiB", "TiB"):
        if v < 1024:
            break
        v, unit = v / 1024, u
    return f"{v:.1f} {unit}" if v < 10 and unit != "bytes" else f"{v:.0f} {unit}"


def check_memory(what: str, need: int, lower: str) -> None:
    """MemoryError when `what` needs more than the limit: "what needs about
    N, more than LIMIT allows: lower"."""
    limit, source = memory_limit()
    if need <= limit:
        return
    if source.startswith("SR_MEMORY_LIMIT"):
        allows = f"more than {source} allows"
    else:
        allows = (f"more than the {format_bytes(limit)} of {source} "
                  f"(SR_MEMORY_LIMIT sets another limit)")
    raise MemoryError(f"{what} needs about {format_bytes(need)} of image memory, {allows}: "
                      f"{lower}")
