"""numba's ``njit`` whose on-disk cache never stops an import.

``@njit(cache=True)`` raises ``RuntimeError: cannot cache function ...: no
locator available`` at import time when neither the package's
``__pycache__`` nor the user's cache folder can be written (a system-wide
install run by a user without a writable home, a read-only container). Then
the kernels are cached in a private folder under the system's temporary
directory, and if even that cannot be written they are compiled in memory
on first use (slower start, same results).

:func:`announce_compiling` says so on a terminal when a method is about to
compile its kernels (the first call after an install, unless
``medialaxis warmup`` ran).

:class:`Beside` runs a function on a second thread while the caller runs a
serial kernel, where numba's threading layer lets two threads launch
parallel kernels at once; its errors reach the caller as raised (running
out of memory as a :class:`~medialaxis.errors.ResourceLimitError`).
"""

from __future__ import annotations

import os
import sys
import tempfile
import threading
from collections.abc import Callable
from typing import Any

import numba
import numpy as np

from medialaxis.errors import ResourceLimitError

__all__ = ["njit", "prange", "Beside", "concurrent_kernels", "is_compiled", "announce_compiling"]

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


#: Set by ``medialaxis warmup``, which compiles on purpose and says so itself.
QUIET = False


def is_compiled(kernel: Any) -> bool:
    """Whether numba has machine code for ``kernel`` in this process or in its disk cache.

    Uses numba's cache index file (``<module>.<function>-<line>.py311.nbi``):
    False also where no index can be found (a kernel compiled in memory only).
    """
    if getattr(kernel, "signatures", None):
        return True
    index = getattr(getattr(getattr(kernel, "_cache", None), "_cache_file", None), "_index_path", None)
    return isinstance(index, str) and os.path.exists(index)


def announce_compiling(kernel: Any, what: str, stream: Any = None) -> bool:
    """One line on ``stream`` (stderr), when it is a terminal, if ``kernel`` is not compiled yet; whether it was said.

    ``kernel`` is one that every call of the method compiles, so that the
    user learns why the first call after an install is slow (numba compiles
    on first use; about a minute for a mesh method on two cores).
    """
    stream = sys.stderr if stream is None else stream
    if QUIET or is_compiled(kernel) or not getattr(stream, "isatty", lambda: False)():
        return False
    stream.write(f"medialaxis: compiling the {what} kernels on this first call (once: they are cached on disk; "
                 "`medialaxis warmup` compiles every method's ahead)\n")
    stream.flush()
    return True


@njit(parallel=True, cache=True)
def _touch(n: int) -> int:  # pragma: no cover - compiled
    total = 0
    for i in prange(n):
        total += i
    return total


def concurrent_kernels() -> bool:
    """Whether two threads may run parallel kernels at once: numba's ``omp`` and ``tbb`` layers allow it,
    ``workqueue`` aborts the process."""
    _touch(np.int64(2))  # the layer is chosen at the first parallel launch
    return numba.threading_layer() in ("omp", "tbb")


class Beside:
    """``fn(*args)`` on a daemon thread, or at once when :func:`concurrent_kernels` says no.

    :meth:`result` waits for it and returns its value or raises its
    exception; running out of memory there raises a
    :class:`~medialaxis.errors.ResourceLimitError` naming the function (a
    ``MemoryError`` of its own; the MemoryError raised is its cause). Meant for work that overlaps a long serial kernel of the
    caller (the Delaunay insertion), on the core that kernel leaves idle:
    its own parallel kernels run on one thread. Where no thread can be
    started (a memory limit leaves no room for its stack) the work is done at once.
    """

    def __init__(self, fn: Callable[..., Any], *args: Any) -> None:
        self._name = getattr(fn, "__name__", repr(fn))
        self._value: Any = None
        self._error: BaseException | None = None
        self._thread: threading.Thread | None = None
        if concurrent_kernels():
            thread = threading.Thread(target=self._run, args=(fn, args, True), daemon=True)
            try:
                thread.start()
            except (RuntimeError, MemoryError):  # "can't start new thread"
                pass
            else:
                self._thread = thread
                return
        self._run(fn, args, False)

    def _run(self, fn: Callable[..., Any], args: tuple[Any, ...], on_thread: bool) -> None:
        try:
            if on_thread:
                numba.set_num_threads(1)  # per thread: leave the other cores to the caller
            self._value = fn(*args)
        except BaseException as exc:  # handed to the caller by result()
            self._error = exc

    def result(self) -> Any:
        if self._thread is not None:
            self._thread.join()
        error = self._error
        if isinstance(error, MemoryError) and not isinstance(error, ResourceLimitError):
            detail = f": {error}" if str(error) else ""
            raise ResourceLimitError(f"out of memory in {self._name}{detail}") from error
        if error is not None:
            raise error
        return self._value
