"""How much memory one call's images may take, checked before they are allocated.

The library's limit, as the softrast tool's (sr_check_memory in
softrast_io.h): the environment variable SR_MEMORY_LIMIT when set (bytes,
or 512M, 8G, 1.5T), else the physical memory, or less under a ulimit.
Linux overcommits: an image larger than the machine holds is rarely
refused when allocated, and the process is killed later as its pages are
touched, so the estimate is compared first and a MemoryError (numpy's own
kind of failure to allocate) names the sizes instead.
"""

from __future__ import annotations

from . import _softrast


def check_memory(what: str, need: int, lower: str) -> None:
    """MemoryError when `what` needs more than the limit: "what needs about
    N of image memory, more than LIMIT allows: lower"; ValueError for a
    malformed SR_MEMORY_LIMIT."""
    _softrast.check_memory(what, int(need), lower)
