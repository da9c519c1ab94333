"""Reading and writing :class:`MedialAxis` results.

Lossless: ``.json`` and ``.npz`` (:mod:`~medialaxis.core.lossless`, read back
by :func:`load`, including the unpruned axis so :meth:`MedialAxis.prune`
still works). Exports: ``.geojson``, ``.svg`` (axis over the shape),
``.png`` (plot coloured by radius), ``.graphml`` (nodes with position and
radius, edges with length and radius), ``.obj`` (``v``, ``l`` for curve
edges, ``f``; VTK reads the curves, meshio's and trimesh's OBJ readers only
the faces), ``.ply``, ``.vtk``, ``.vtu`` and ``.swc``
(:mod:`medialaxis.core.export.mesh_files`: files that meshio, trimesh, pyvista and
neuron tools open) and ``.html`` (interactive offline view, 2D or 3D,
:mod:`medialaxis.core.export.html`; the viewer library is written beside it once).
A 2D result is written in its source's frame, with the same (x, y) in every
format (:mod:`medialaxis.core.frames`). A format that cannot hold the kind of
result (:data:`HOLDS`) is refused before anything is written. Every file is
written to a temporary name in the target folder, then renamed, so a failure
never leaves a half-written file (:mod:`~medialaxis.core.outputs`).
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis.core.export import mesh_files
from medialaxis.core.formats import FORMATS, entry_point, format_of, suffix_of, writer_missing
from medialaxis.core.frames import coordinates_note, plane_xy, y_down
from medialaxis.core.lossless import LOSSLESS, is_result_file, load
from medialaxis.core.lossless import jsonable as _jsonable
from medialaxis.core.outputs import atomic_path, atomic_write, check_writable, output_batch, output_mode, result_kind
from medialaxis.core.result import MedialAxis
from medialaxis.errors import InvalidInputError, MissingDependencyError, UnsupportedFormatError

__all__ = [
    "HOLDS",
    "LOSSLESS",
    "WRITERS",
    "atomic_write",
    "check_kind",
    "check_writable",
    "kind_refusal",
    "is_result_file",
    "load",
    "output_batch",
    "output_mode",
    "save",
]



# -------------------------------------------------------------- exports
def write_graphml(ma: MedialAxis, path: Path) -> None:
    """Nodes with x, y (as GeoJSON writes them: x = column, y = row for an image), z in 3D and radius."""
    from medialaxis._optional import require

    nx = require("networkx", "networkx")
    g = nx.Graph()
    points = plane_xy(ma, ma.points) if ma.dim == 2 else ma.points
    if ma.dim == 2:
        g.graph["coordinates"] = coordinates_note(ma)
    for i, (p, r) in enumerate(zip(points.tolist(), ma.radii.tolist())):
        g.add_node(i, radius=float(r), **{"xyz"[k]: float(c) for k, c in enumerate(p)})
    radii = np.asarray(ma.radii, np.float64)
    for a, b in ma._all_edges.tolist():
        length = float(np.linalg.norm(ma.points[a] - ma.points[b]))
        g.add_edge(int(a), int(b), length=length, radius=0.5 * float(radii[a] + radii[b]))
    with atomic_write(path, "wb") as fh:
        nx.write_graphml(g, fh)


def write_geojson(ma: MedialAxis, path: Path) -> None:
    """Branches as LineStrings, junctions and endpoints as Points. An image's
    axis is written with x = column and y = row (pixels times spacing, y
    downwards as in the image), as GIS tools place a raster's pixels; the
    document's ``properties["coordinates"]`` says which."""

    def xy(points: np.ndarray) -> list[Any]:
        return (plane_xy(ma, points) if ma.dim == 2 else points).tolist()

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
    properties["coordinates"] = coordinates_note(ma) if ma.dim == 2 else "the result's own coordinates"
    doc = {"type": "FeatureCollection", "features": feats, "properties": properties}
    with atomic_write(path, "w") as fh:
        json.dump(doc, fh)


def write_svg(ma: MedialAxis, path: Path) -> None:
    """The axis over the shape, in the source's frame (:func:`medialaxis.core.frames.svg_frame`)."""
    from medialaxis.core.frames import svg_document

    if ma.dim != 2:
        raise UnsupportedFormatError("SVG export is for planar axes; use .ply, .obj or .png for 3D")
    with atomic_write(path, "w") as fh:
        fh.write(svg_document(ma, coordinates_note(ma)))


def write_png(ma: MedialAxis, path: Path) -> None:
    import matplotlib

    from medialaxis.core.export.plot import plot_axis

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    fig = plot_axis(ma)
    if ma.dim == 2 and y_down(ma):  # an SVG drawing's y points down, as an image's (plot_axis turns those)
        for ax in fig.axes[:1]:
            if not ax.yaxis_inverted():
                ax.invert_yaxis()
    try:
        with atomic_write(path, "wb") as fh:
            fig.savefig(fh, format="png", dpi=120, bbox_inches="tight")
    finally:
        plt.close(fig)


def _through(write: Callable[[MedialAxis, Any], None], mode: str) -> Callable[[MedialAxis, Path], None]:
    """A writer of :mod:`medialaxis.core.export.mesh_files`, through an atomic file."""

    def run(ma: MedialAxis, path: Path) -> None:
        with atomic_write(path, mode) as fh:
            write(ma, fh)

    run.__name__ = write.__name__
    return run


write_ply = _through(mesh_files.write_ply, "wb")
write_swc = _through(mesh_files.write_swc, "w")


def write_vtk(ma: MedialAxis, path: Path) -> None:
    with atomic_path(path) as tmp:  # meshio opens the file itself
        mesh_files.write_vtk(ma, tmp)


def write_vtu(ma: MedialAxis, path: Path) -> None:
    with atomic_path(path) as tmp:
        mesh_files.write_vtu(ma, tmp)


def write_obj(ma: MedialAxis, path: Path) -> None:
    pts = mesh_files.points_3d(ma)
    with atomic_write(path, "w") as fh:
        fh.write("# medialaxis result: vertices, curve edges (l) and faces (f); radii are in .ply .vtk .vtu .swc\n")
        np.savetxt(fh, pts, fmt="v %.10g %.10g %.10g")
        curves = mesh_files.curve_edges(ma)
        if len(curves):
            np.savetxt(fh, curves + 1, fmt="l %d %d")
        if len(ma.faces):
            np.savetxt(fh, ma.faces + 1, fmt="f %d %d %d")


def write_html(ma: MedialAxis, path: Path) -> None:
    from medialaxis.core.export import html  # plotly view

    html.write_html(ma, path)


def _lazy(entry: str) -> Callable[..., None]:
    """The writer named by ``entry`` (``"module:function"``), imported when first called."""

    def write(ma: MedialAxis, path: Path, **kwargs: Any) -> None:
        entry_point(entry)(ma, path, **kwargs)

    return write


#: The writer of each output suffix (:data:`medialaxis.core.formats.FORMATS`), in registry order.
WRITERS: dict[str, Callable[..., None]] = {s: _lazy(f.writer) for f in FORMATS if f.writer for s in f.suffixes}

#: What each format holds, and the kinds of result (:data:`~medialaxis.core.outputs.KINDS`) that fit.
HOLDS: dict[str, tuple[str, frozenset[str]]] = {s: f.holds for f in FORMATS if f.holds for s in f.suffixes}


def kind_refusal(path: str | os.PathLike[str], kind: str | None) -> str | None:
    """Why a file at ``path`` cannot hold a result of ``kind`` (one of :data:`KINDS`); None when it can.

    >>> kind_refusal("t.swc", "surfaces")
    'SWC holds curve skeletons, not surfaces: write .json, .npz, .graphml, .png, .ply, .obj, .vtk, .vtu or .html'
    """
    ext = suffix_of(path)
    fmt = format_of(path)
    if kind is None or fmt is None or ext not in HOLDS or kind in HOLDS[ext][1]:
        return None
    fits = [e for e, (_, kinds) in HOLDS.items() if kind in kinds]
    name = fmt.name
    return f"{name} holds {HOLDS[ext][0]}, not {kind}: write {', '.join(fits[:-1])} or {fits[-1]}"


def check_kind(ma: MedialAxis, path: str | os.PathLike[str]) -> None:
    """Raise :class:`UnsupportedFormatError` unless ``path``'s format holds ``ma``'s kind of result."""
    reason = kind_refusal(path, result_kind(ma))
    if reason is not None:
        raise UnsupportedFormatError(f"{str(path)!r}: {reason}")


def save(ma: MedialAxis, path: str | os.PathLike[str], *, timings: bool = False) -> None:
    """Write ``ma`` to ``path``; the extension picks the format (see module docstring).

    ``timings=True`` keeps the wall-clock ``metadata["timings"]`` in a
    lossless file (``.json``, ``.npz``); it is left out by default.

    Raises
    ------
    UnsupportedFormatError
        An unknown extension, or a format that cannot hold this kind of result (:data:`HOLDS`);
        nothing is written.
    """
    if not isinstance(ma, MedialAxis):
        raise InvalidInputError(f"expected a MedialAxis, got {type(ma).__name__}")
    path = Path(path)
    ext = suffix_of(path)
    if ext not in WRITERS:
        raise UnsupportedFormatError(f"unsupported output format {ext or '(none)'!r}; choose one of {', '.join(WRITERS)}")
    check_kind(ma, path)
    missing = writer_missing(ext)
    if missing is not None:
        raise MissingDependencyError(missing)
    if timings and ext in LOSSLESS:
        WRITERS[ext](ma, path, timings=True)  # type: ignore[call-arg]
    else:
        WRITERS[ext](ma, path)
