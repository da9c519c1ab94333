"""Reading and writing :class:`MedialAxis` results.

Lossless: ``.json`` and ``.npz`` (read back by :func:`load`, including the
unpruned axis so :meth:`MedialAxis.prune` still works). Exports: ``.graphml``,
``.geojson``, ``.svg`` (axis over the shape), ``.png`` (plot coloured by
radius), ``.graphml`` (nodes with position and radius, edges with length and
radius), ``.obj`` (``v``, ``l`` for curve edges, ``f``; VTK reads the curves,
meshio's and trimesh's OBJ readers only the faces), ``.ply``, ``.vtk``, ``.vtu`` and
``.swc`` (:mod:`medialaxis.core.mesh_files`: files that meshio, trimesh,
pyvista and neuron tools open) and ``.html`` (interactive offline 3D view,
:mod:`medialaxis.core.html`; the viewer library is written beside it once).
Every file is written to a temporary name in the target folder, then renamed,
so a failure never leaves a half-written file.
"""

from __future__ import annotations

import contextlib
import contextvars
import json
import os
import re
import stat
import tempfile
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import IO, Any

import numpy as np

from medialaxis.core import mesh_files
from medialaxis.core.result import MedialAxis
from medialaxis.errors import InputFileError, InvalidInputError, UnsupportedFormatError

__all__ = [
    "LOSSLESS",
    "WRITERS",
    "atomic_write",
    "check_writable",
    "is_result_file",
    "load",
    "output_batch",
    "output_mode",
    "save",
]

FORMAT_VERSION = 1


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


#: Renames deferred by :func:`output_batch` (temporary file, target), or None outside a batch.
_BATCH: contextvars.ContextVar[list[tuple[str, Path]] | None] = contextvars.ContextVar("medialaxis_batch", default=None)


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
def atomic_write(path: str | os.PathLike[str], mode: str = "wb") -> Iterator[IO[Any]]:
    """Open a temporary file next to ``path``; rename it over ``path`` on success.

    The temporary file is created private (``tempfile.mkstemp``) and given
    the permissions of :func:`output_mode` before it is renamed, so the
    result is readable as any file the user writes would be. Inside
    :func:`output_batch` the rename waits for the end of the batch.
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
        with os.fdopen(fd, mode) as fh:
            yield fh
        batch = _BATCH.get()
        if batch is None:
            os.replace(tmp, path)
        else:
            batch.append((tmp, path))
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


# ------------------------------------------------------------- lossless
def _jsonable(value: Any) -> Any:
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_jsonable(v) for v in value]
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    return value


def _shape_wkt(ma: MedialAxis) -> str | None:
    return ma.shape.wkt if hasattr(ma.shape, "wkt") else None


def _to_dict(ma: MedialAxis) -> dict[str, Any]:
    return {
        "format": "medialaxis",
        "version": FORMAT_VERSION,
        "points": ma.points.tolist(),
        "radii": ma.radii.tolist(),
        "edges": ma.edges.tolist(),
        "faces": ma.faces.tolist(),
        # Infinite values (contacts on different rings) are kept as JSON
        # ``Infinity``, which Python's json module reads back.
        "extras": {k: {"dtype": str(v.dtype), "shape": list(v.shape), "data": v.tolist()} for k, v in ma.extras.items()},
        "metadata": _jsonable(dict(ma.metadata, dim=ma.dim)),
        "shape": _shape_wkt(ma),
        "raw": _to_dict(ma.raw) if ma.raw is not None else None,
    }


def _extra_from_json(spec: dict[str, Any]) -> np.ndarray:
    return np.asarray(spec["data"], dtype=spec["dtype"]).reshape(spec["shape"])


def _from_dict(d: dict[str, Any]) -> MedialAxis:
    if d.get("format") != "medialaxis":
        raise InputFileError("not a medialaxis result file")
    shape = None
    if d.get("shape"):
        import shapely

        shape = shapely.from_wkt(d["shape"])
    meta = d.get("metadata", {})
    for key in ("spacing", "image_shape"):
        if key in meta and isinstance(meta[key], list):
            meta[key] = tuple(meta[key])
    dim = int(meta.pop("dim", len(d["points"][0]) if d["points"] else 2))
    return MedialAxis(
        np.asarray(d["points"], np.float64).reshape(-1, dim),
        np.asarray(d["radii"], np.float64),
        np.asarray(d["edges"], np.int64).reshape(-1, 2),
        np.asarray(d["faces"], np.int64).reshape(-1, 3),
        extras={k: _extra_from_json(v) for k, v in d.get("extras", {}).items()},
        metadata=meta,
        shape=shape,
        raw=_from_dict(d["raw"]) if d.get("raw") else None,
    )


def _write_json(ma: MedialAxis, path: Path) -> None:
    d = _to_dict(ma)
    with atomic_write(path, "w") as fh:
        json.dump(d, fh)


def _npz_arrays(ma: MedialAxis, prefix: str) -> dict[str, np.ndarray]:
    meta = _jsonable(dict(ma.metadata))
    meta["dim"] = ma.dim
    out = {
        f"{prefix}points": ma.points,
        f"{prefix}radii": ma.radii,
        f"{prefix}edges": ma.edges,
        f"{prefix}faces": ma.faces,
        f"{prefix}metadata": np.asarray(json.dumps(meta)),
        f"{prefix}shape": np.asarray(_shape_wkt(ma) or ""),
    }
    for k, v in ma.extras.items():
        out[f"{prefix}extra__{k}"] = v
    if ma.raw is not None:
        out.update(_npz_arrays(ma.raw, prefix + "raw__"))
    return out


def _write_npz(ma: MedialAxis, path: Path) -> None:
    with atomic_write(path, "wb") as fh:
        np.savez_compressed(fh, format=np.asarray("medialaxis"), version=np.asarray(FORMAT_VERSION), **_npz_arrays(ma, ""))


def _from_npz(z: Any, prefix: str) -> MedialAxis:
    meta = json.loads(str(z[f"{prefix}metadata"]))
    for key in ("spacing", "image_shape"):
        if key in meta and isinstance(meta[key], list):
            meta[key] = tuple(meta[key])
    wkt = str(z[f"{prefix}shape"])
    shape = None
    if wkt:
        import shapely

        shape = shapely.from_wkt(wkt)
    extras = {k[len(prefix) + 7 :]: z[k] for k in z.files if k.startswith(f"{prefix}extra__")}
    has_raw = f"{prefix}raw__points" in z.files
    dim = int(meta.pop("dim", 2))
    return MedialAxis(
        z[f"{prefix}points"].reshape(-1, dim),
        z[f"{prefix}radii"],
        z[f"{prefix}edges"],
        z[f"{prefix}faces"],
        extras=extras,
        metadata=meta,
        shape=shape,
        raw=_from_npz(z, prefix + "raw__") if has_raw else None,
    )


#: A ``.json`` file larger than this is sniffed, not parsed, by :func:`is_result_file`.
_PARSE_JSON_BELOW = 64 << 20
_FORMAT_TAG = re.compile(rb'^\s*\{\s*"format"\s*:\s*"medialaxis"')


def is_result_file(path: str | os.PathLike[str]) -> bool:
    """Whether ``path`` is a result saved by :meth:`MedialAxis.save` (``.json`` or ``.npz``).

    A ``.npz`` is one if it holds a ``format`` array equal to
    ``"medialaxis"``; a ``.json`` if its top-level object has
    ``"format": "medialaxis"`` (GeoJSON and other JSON are not). Files that
    cannot be read are not results (their reader reports why).
    """
    path = Path(path)
    ext = path.suffix.lower()
    if ext not in LOSSLESS or not path.is_file():
        return False
    try:
        if ext == ".npz":
            with np.load(path, allow_pickle=False) as z:
                return "format" in z.files and str(z["format"]) == "medialaxis"
        if path.stat().st_size > _PARSE_JSON_BELOW:
            with open(path, "rb") as fh:  # :func:`save` writes the tag first
                return bool(_FORMAT_TAG.match(fh.read(256)))
        with open(path, "rb") as fh:
            doc = json.load(fh)
        return isinstance(doc, dict) and doc.get("format") == "medialaxis"
    except Exception:  # noqa: BLE001 - unreadable or corrupt: not a result
        return False


def _check_loaded(ma: MedialAxis, what: str) -> None:
    """Refuse a loaded result whose numbers no computation could have produced."""
    from medialaxis.core.validate import MAX_COORDINATE

    for name, values in (("points", ma.points), ("radii", ma.radii)):
        bad = ~np.isfinite(values) | (np.abs(values) > MAX_COORDINATE)
        if name == "radii":
            bad |= values < 0
        if bad.any():
            kinds = "negative, infinite or overflowing" if name == "radii" else "infinite or overflowing"
            raise InputFileError(f"{what} is corrupt: its {name} hold {kinds} values")
    for key, value in ma.extras.items():
        if value.dtype.kind not in "biuf":
            raise InputFileError(f"{what} is corrupt: its extra {key!r} holds {value.dtype} values, not numbers")
    if ma.raw is not None:
        _check_loaded(ma.raw, what + " (unpruned axis)")


def load(path: str | os.PathLike[str]) -> MedialAxis:
    """Read a result written by :meth:`MedialAxis.save` as ``.json`` or ``.npz``.

    Raises
    ------
    InputFileError
        Missing, unreadable or corrupt file.
    UnsupportedFormatError
        Any other extension.
    """
    path = Path(path)
    ext = path.suffix.lower()
    if ext not in LOSSLESS:
        raise UnsupportedFormatError(f"cannot load {ext!r}; lossless formats are {', '.join(LOSSLESS)}")
    if not path.is_file():
        raise InputFileError(f"no such file: {str(path)!r}")
    try:
        if ext == ".json":
            with open(path) as fh:
                ma = _from_dict(json.load(fh))
        else:
            with np.load(path, allow_pickle=False) as z:
                if "format" not in z.files or str(z["format"]) != "medialaxis":
                    raise InputFileError(f"{str(path)!r} is not a medialaxis result file")
                ma = _from_npz(z, "")
    except InputFileError:
        raise
    except Exception as exc:  # noqa: BLE001 - corrupt files raise many types
        raise InputFileError(f"cannot read {str(path)!r}: {type(exc).__name__}: {exc}") from exc
    _check_loaded(ma, repr(str(path)))
    return ma


# -------------------------------------------------------------- exports
def _write_graphml(ma: MedialAxis, path: Path) -> None:
    from medialaxis._optional import require

    nx = require("networkx", "networkx")
    g = nx.Graph()
    names = "xyz"
    for i, (p, r) in enumerate(zip(ma.points.tolist(), ma.radii.tolist())):
        g.add_node(i, radius=float(r), **{names[k]: float(c) for k, c in enumerate(p)})
    radii = np.asarray(ma.radii, np.float64)
    for a, b in ma._all_edges.tolist():
        length = float(np.linalg.norm(ma.points[a] - ma.points[b]))
        g.add_edge(int(a), int(b), length=length, radius=0.5 * float(radii[a] + radii[b]))
    with atomic_write(path, "wb") as fh:
        nx.write_graphml(g, fh)


def _from_image(ma: MedialAxis) -> bool:
    """A 2D result in image index order (row, column)."""
    return ma.dim == 2 and "image_shape" in ma.metadata


def _write_geojson(ma: MedialAxis, path: Path) -> None:
    """Branches as LineStrings, junctions and endpoints as Points. An image's
    axis is written with x = column and y = row (pixels times spacing, y
    downwards as in the image), as GIS tools place a raster's pixels; the
    document's ``properties["coordinates"]`` says which."""
    swap = _from_image(ma)

    def xy(points: np.ndarray) -> list[Any]:
        return (points[..., ::-1] if swap else points).tolist()

    feats = []
    for br in ma.branches():
        feats.append(
            {
                "type": "Feature",
                "geometry": {"type": "LineString", "coordinates": xy(br.points)},
                "properties": {"kind": "branch", "radii": br.radii.tolist(), "length": br.length},
            }
        )
    isolated = np.flatnonzero(ma.degree == 0)
    for kind, idx in (("junction", ma.junctions), ("endpoint", ma.endpoints), ("point", isolated)):
        for i in idx.tolist():
            feats.append(
                {
                    "type": "Feature",
                    "geometry": {"type": "Point", "coordinates": xy(ma.points[i])},
                    "properties": {"kind": kind, "radius": float(ma.radii[i]), "index": i},
                }
            )
    properties = _jsonable(dict(ma.metadata))
    properties["coordinates"] = ("x = column, y = row (image pixels times spacing, y down)" if swap
                                 else "the result's own coordinates")
    doc = {"type": "FeatureCollection", "features": feats, "properties": properties}
    with atomic_write(path, "w") as fh:
        json.dump(doc, fh)


def _display_xy(ma: MedialAxis, xy: np.ndarray) -> np.ndarray:
    """Map axis coordinates to picture (x right, y down) coordinates."""
    if "image_shape" in ma.metadata:  # (row, col): col is x, row is y (down)
        return xy[:, ::-1]
    return np.c_[xy[:, 0], -xy[:, 1]]


def _write_svg(ma: MedialAxis, path: Path) -> None:
    if ma.dim != 2:
        raise UnsupportedFormatError("SVG export is for planar axes; use .ply, .obj or .png for 3D")
    parts: list[np.ndarray] = [ma.points]
    outline: list[np.ndarray] = []
    if ma.shape is not None:
        import shapely

        for poly in shapely.get_parts(ma.shape):
            for ring in [poly.exterior, *poly.interiors]:
                outline.append(np.asarray(ring.coords))
        parts.extend(outline)
    allxy = _display_xy(ma, np.vstack(parts)) if len(np.vstack(parts)) else np.zeros((1, 2))
    lo, hi = allxy.min(0), allxy.max(0)
    size = max(float((hi - lo).max()), 1e-12)
    pad = 0.05 * size
    scale = 800.0 / (size + 2 * pad)
    w, h = ((hi - lo) + 2 * pad) * scale

    def tr(xy: np.ndarray) -> np.ndarray:
        return (_display_xy(ma, xy) - lo + pad) * scale

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w:.1f}" height="{h:.1f}" viewBox="0 0 {w:.1f} {h:.1f}">']
    if outline:
        d = " ".join("M " + " L ".join(f"{x:.2f},{y:.2f}" for x, y in tr(r)) + " Z" for r in outline)
        out.append(f'<path d="{d}" fill="#dde6f0" stroke="#445" stroke-width="1" fill-rule="evenodd"/>')
    for br in ma.branches():
        pts = " ".join(f"{x:.2f},{y:.2f}" for x, y in tr(br.points))
        out.append(f'<polyline points="{pts}" fill="none" stroke="#c0392b" stroke-width="1.5"/>')
    for i in ma.junctions.tolist():
        x, y = tr(ma.points[i : i + 1])[0]
        out.append(f'<circle cx="{x:.2f}" cy="{y:.2f}" r="3" fill="#2c3e50"/>')
    for i in ma.endpoints.tolist():
        x, y = tr(ma.points[i : i + 1])[0]
        out.append(f'<circle cx="{x:.2f}" cy="{y:.2f}" r="3" fill="#27ae60"/>')
    out.append("</svg>")
    with atomic_write(path, "w") as fh:
        fh.write("\n".join(out))


def _write_png(ma: MedialAxis, path: Path) -> None:
    from medialaxis.core.plot import plot_axis

    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    fig = plot_axis(ma)
    try:
        with atomic_write(path, "wb") as fh:
            fig.savefig(fh, format="png", dpi=120, bbox_inches="tight")
    finally:
        plt.close(fig)


def _through(write: Callable[[MedialAxis, Any], None], mode: str) -> Callable[[MedialAxis, Path], None]:
    """A writer of :mod:`medialaxis.core.mesh_files`, through an atomic file."""

    def run(ma: MedialAxis, path: Path) -> None:
        with atomic_write(path, mode) as fh:
            write(ma, fh)

    return run


def _write_obj(ma: MedialAxis, path: Path) -> None:
    pts = mesh_files.points_3d(ma)
    with atomic_write(path, "w") as fh:
        fh.write("# medialaxis result: vertices, curve edges (l) and faces (f); radii are in .ply .vtk .vtu .swc\n")
        np.savetxt(fh, pts, fmt="v %.10g %.10g %.10g")
        curves = mesh_files.curve_edges(ma)
        if len(curves):
            np.savetxt(fh, curves + 1, fmt="l %d %d")
        if len(ma.faces):
            np.savetxt(fh, ma.faces + 1, fmt="f %d %d %d")


def _write_html(ma: MedialAxis, path: Path) -> None:
    from medialaxis.core.html import write_html  # plotly view, 3D results

    write_html(ma, path)


WRITERS: dict[str, Callable[[MedialAxis, Path], None]] = {
    ".json": _write_json,
    ".npz": _write_npz,
    ".graphml": _write_graphml,
    ".geojson": _write_geojson,
    ".svg": _write_svg,
    ".png": _write_png,
    ".ply": _through(mesh_files.write_ply, "wb"),
    ".obj": _write_obj,
    ".vtk": _through(mesh_files.write_vtk, "w"),
    ".vtu": _through(mesh_files.write_vtu, "w"),
    ".swc": _through(mesh_files.write_swc, "w"),
    ".html": _write_html,
}
LOSSLESS = (".json", ".npz")


def save(ma: MedialAxis, path: str | os.PathLike[str]) -> None:
    """Write ``ma`` to ``path``; the extension picks the format (see module docstring)."""
    if not isinstance(ma, MedialAxis):
        raise InvalidInputError(f"expected a MedialAxis, got {type(ma).__name__}")
    path = Path(path)
    ext = path.suffix.lower()
    if ext not in WRITERS:
        raise UnsupportedFormatError(f"unsupported output format {ext or '(none)'!r}; choose one of {', '.join(WRITERS)}")
    WRITERS[ext](ma, path)
