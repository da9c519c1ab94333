"""Freed memory handed back to the operating system between the large stages of a computation.

A NumPy array smaller than glibc's mmap threshold (128 kB at first, raised
up to 32 MB as large blocks are freed) lives in the C heap; when it is
freed, its pages stay with the process until the heap's top is free. The
millions of tetrahedra of a Voronoi medial surface leave several hundred
megabytes so (a scanned 62k-vertex ogre: 1.06 GB resident before the inside
test, 0.81 GB after a trim), which the next stage's arrays then pile on.
"""

from __future__ import annotations

import ctypes
import functools
from typing import Any

__all__ = ["release_freed_memory"]


@functools.lru_cache(maxsize=1)
def _malloc_trim() -> Any:
    try:
        return ctypes.CDLL(None).malloc_trim  # glibc; musl, macOS and Windows have none
    except (OSError, AttributeError):
        return None


def release_freed_memory() -> None:
    """Give the C heap's free pages back to the operating system (glibc's ``malloc_trim``); elsewhere, nothing.

    Costs a walk of the heap, a few milliseconds: call it between stages, not in loops.

    Examples
    --------
    >>> release_freed_memory()
    """
    trim = _malloc_trim()
    if trim is not None:
        trim(0)
