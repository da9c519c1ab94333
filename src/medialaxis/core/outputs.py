"""Output files written atomically (a temporary name in the target folder, then a rename), with the umask's
permissions; a batch of outputs is kept all-or-none (:func:`output_batch`). The kind of result each method
gives (:data:`METHOD_KINDS`), so that an output that cannot hold it is refused before any work."""

from __future__ import annotations

import contextlib
import contextvars
import os
import stat
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import IO, Any

from medialaxis.errors import InputFileError

__all__ = ["KINDS", "METHOD_KINDS", "atomic_path", "atomic_write", "check_writable", "method_kind", "output_batch", "output_mode",
           "result_kind"]

#: The kinds of result: curves in the plane, curves in space, surfaces (triangles, possibly with curve
#: pieces), voxel sets (lone points).
KINDS = ("planar curves", "space curves", "surfaces", "voxel sets")

#: The kind each method gives, by (domain, method) as in :data:`medialaxis._dispatch.METHODS`.
METHOD_KINDS: dict[tuple[str, str], str] = {
    ("planar", "voronoi"): "planar curves",
    ("mesh", "flow"): "space curves",
    ("mesh", "voronoi"): "surfaces",
    ("volume", "midsurface"): "surfaces",
    ("volume", "voxels"): "voxel sets",
}


def method_kind(domain: str, method: str) -> str | None:
    """The kind of result ``method`` gives for ``domain`` inputs (one of :data:`KINDS`), None if unknown."""
    return METHOD_KINDS.get((domain, method))


def result_kind(ma: Any) -> str:
    """The kind of a :class:`~medialaxis.core.result.MedialAxis`: its method's, else what it holds."""
    meta = ma.metadata
    kind = method_kind(str(meta.get("domain")), str(meta.get("method")))
    if kind is not None:
        return kind
    if ma.dim == 2:
        return "planar curves"
    if len(ma.faces):
        return "surfaces"
    return "space curves" if len(ma.edges) else "voxel sets"

#: Renames deferred by :func:`output_batch` (temporary file, target), or None outside a batch.
_BATCH: contextvars.ContextVar[list[tuple[str, Path]] | None] = contextvars.ContextVar("medialaxis_batch", default=None)


def _umask() -> int:
    """The process umask, read without changing it where the system allows."""
    try:
        with open("/proc/self/status") as fh:
            for line in fh:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    mask = os.umask(0o022)  # elsewhere: set and restore (not atomic across threads)
    os.umask(mask)
    return mask


def output_mode(path: str | os.PathLike[str]) -> int:
    """Permission bits for a file written at ``path``.

    A file being replaced keeps its permissions; a new file gets what
    ``open(path, "w")`` would give it, ``0o666`` less the umask (``0o644``
    under the usual umask 022).
    """
    try:
        st = os.stat(path)
    except OSError:
        return 0o666 & ~_umask()
    return stat.S_IMODE(st.st_mode) if stat.S_ISREG(st.st_mode) else 0o666 & ~_umask()


@contextlib.contextmanager
def output_batch() -> Iterator[None]:
    """All the files written in the block appear together at its end, or none does.

    Inside the block :func:`atomic_write` leaves each file under its
    temporary name; when the block ends normally they are renamed into
    place, and when it raises (or is interrupted) they are deleted.

    Raises
    ------
    InputFileError
        A rename failed; the files not yet renamed are deleted.
    """
    pending: list[tuple[str, Path]] = []
    token = _BATCH.set(pending)
    try:
        yield
    except BaseException:
        _discard(pending)
        raise
    finally:
        _BATCH.reset(token)
    for k, (tmp, path) in enumerate(pending):
        try:
            os.replace(tmp, path)
        except OSError as exc:
            _discard(pending[k:])
            raise InputFileError(f"cannot write {str(path)!r}: {exc.strerror or exc}") from exc


def _discard(pending: list[tuple[str, Path]]) -> None:
    for tmp, _ in pending:
        with contextlib.suppress(OSError):
            os.unlink(tmp)


def check_writable(path: str | os.PathLike[str]) -> None:
    """Raise :class:`InputFileError` unless a file can be created at ``path`` (checked by creating one).

    ``path`` itself is not touched; a temporary file is made and removed in
    its folder.
    """
    path = Path(path)
    folder = path.parent if str(path.parent) else Path(".")
    if path.is_dir():
        raise InputFileError(f"output {str(path)!r} is a folder")
    if not folder.is_dir():
        raise InputFileError(f"output folder does not exist: {str(folder)!r}")
    try:
        with tempfile.TemporaryFile(prefix=f".{path.name}.", suffix=".check", dir=folder):
            pass
    except OSError as exc:
        raise InputFileError(f"cannot write in {str(folder)!r}: {exc.strerror or exc}") from exc


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike[str]) -> Iterator[str]:
    """A temporary file name next to ``path``, renamed over ``path`` when the block ends normally.

    For writers that open the file themselves (meshio's VTU writer takes a
    name, not an open file). The temporary file is created private
    (``tempfile.mkstemp``) and given the permissions of :func:`output_mode`
    before it is renamed, so the result is readable as any file the user
    writes would be. Inside :func:`output_batch` the rename waits for the end
    of the batch; on an error the temporary file is deleted.
    """
    path = Path(path)
    folder = path.parent if str(path.parent) else Path(".")
    if not folder.is_dir():
        raise InputFileError(f"output folder does not exist: {str(folder)!r}")
    permissions = output_mode(path)
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=folder)
    except OSError as exc:
        raise InputFileError(f"cannot write in {str(folder)!r}: {exc.strerror or exc}") from exc
    try:
        if hasattr(os, "fchmod"):
            os.fchmod(fd, permissions)
        os.close(fd)
        yield tmp
        batch = _BATCH.get()
        if batch is None:
            os.replace(tmp, path)
        else:
            batch.append((tmp, path))
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


@contextlib.contextmanager
def atomic_write(path: str | os.PathLike[str], mode: str = "wb") -> Iterator[IO[Any]]:
    """Open a temporary file next to ``path``; rename it over ``path`` on success (:func:`atomic_path`)."""
    with atomic_path(path) as tmp, open(tmp, mode) as fh:
        yield fh
