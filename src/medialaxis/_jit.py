"""numba's ``njit`` whose on-disk cache never stops an import.

``@njit(cache=True)`` raises ``RuntimeError: cannot cache function ...: no
locator available`` at import time when neither the package's
``__pycache__`` nor the user's cache folder can be written (a system-wide
install run by a user without a writable home, a read-only container). Then
the kernels are cached in a private folder under the system's temporary
directory, and if even that cannot be written they are compiled in memory
on first use (slower start, same results).
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable
from typing import Any

import numba

__all__ = ["njit", "prange"]

prange = numba.prange


def _private_cache_dir() -> str | None:
    """A cache folder only this user can write, under the temporary directory, or None."""
    uid = os.getuid() if hasattr(os, "getuid") else "user"
    path = os.path.join(tempfile.gettempdir(), f"medialaxis-numba-cache-{uid}")
    try:
        os.makedirs(path, mode=0o700, exist_ok=True)
        st = os.stat(path)
        if hasattr(os, "getuid") and (st.st_uid != os.getuid() or st.st_mode & 0o022):
            return None  # someone else's folder, or writable by others: not safe to load code from
        with tempfile.TemporaryFile(dir=path):
            pass
    except OSError:
        return None
    return path


def njit(*args: Any, **options: Any) -> Any:
    """``numba.njit`` with the same arguments; ``cache=True`` falls back as the module says."""
    if args and callable(args[0]):
        return njit(**options)(args[0])

    def decorate(fn: Callable[..., Any]) -> Any:
        try:
            return numba.njit(*args, **options)(fn)
        except RuntimeError as exc:
            if not options.get("cache") or "cannot cache" not in str(exc):
                raise
        folder = _private_cache_dir()
        if folder is not None and not numba.config.CACHE_DIR:
            numba.config.CACHE_DIR = folder
            try:
                return numba.njit(*args, **options)(fn)
            except RuntimeError:
                pass
        return numba.njit(*args, **{**options, "cache": False})(fn)

    return decorate
