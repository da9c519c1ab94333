"""Reading and writing :class:`MedialAxis` results.

Lossless: ``.json`` and ``.npz`` (:mod:`~medialaxis.core.lossless`, read back
by :func:`load`, including the unpruned axis so :meth:`MedialAxis.prune`
still works). Exports: ``.graphml``,
``.geojson``, ``.svg`` (axis over the shape), ``.png`` (plot coloured by
radius), ``.graphml`` (nodes with position and radius, edges with length and
radius), ``.obj`` (``v``, ``l`` for curve edges, ``f``; VTK reads the curves,
meshio's and trimesh's OBJ readers only the faces), ``.ply``, ``.vtk``, ``.vtu`` and
``.swc`` (:mod:`medialaxis.core.mesh_files`: files that meshio, trimesh,
pyvista and neuron tools open) and ``.html`` (interactive offline 3D view,
:mod:`medialaxis.core.html`; the viewer library is written beside it once).
Every file is written to a temporary name in the target folder, then renamed,
so a failure never leaves a half-written file (:mod:`~medialaxis.core.outputs`).
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis.core import mesh_files
from medialaxis.core.lossless import LOSSLESS, is_result_file, load, write_json, write_npz
from medialaxis.core.lossless import jsonable as _jsonable
from medialaxis.core.outputs import atomic_write, check_writable, output_batch, output_mode
from medialaxis.core.result import MedialAxis
from medialaxis.errors import InvalidInputError, UnsupportedFormatError

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
    import matplotlib

    from medialaxis.core.plot import plot_axis

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
    ".json": write_json,
    ".npz": write_npz,
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


def save(ma: MedialAxis, path: str | os.PathLike[str]) -> None:
    """Write ``ma`` to ``path``; the extension picks the format (see module docstring)."""
    if not isinstance(ma, MedialAxis):
        raise InvalidInputError(f"expected a MedialAxis, got {type(ma).__name__}")
    path = Path(path)
    ext = path.suffix.lower()
    if ext not in WRITERS:
        raise UnsupportedFormatError(f"unsupported output format {ext or '(none)'!r}; choose one of {', '.join(WRITERS)}")
    WRITERS[ext](ma, path)
