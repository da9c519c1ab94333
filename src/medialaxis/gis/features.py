"""The work done for one feature of a layer: its axis, its widths, its stations.

Everything here is a plain module-level function of picklable arguments, so
that the same code runs in this process, in worker processes and on Dask
workers (:mod:`medialaxis.gis.parallel`).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from medialaxis.api import medial_axis
from medialaxis.errors import InvalidInputError
from medialaxis.gis._kernels import axis_widths_kernel, branch_chains
from medialaxis.gis.network import STATION_COLUMNS, branch_stations
from medialaxis.planar.axis_arrays import polygon_axis_arrays
from medialaxis.planar.axis_layer import polygon_axes

__all__ = ["DETOUR", "WIDTH_COLUMNS", "KINDS", "axis_widths", "branch_lines",
           "chunk_lines", "feature_axis", "chunk_axes", "run_chunk"]

#: Columns added to the layer: twice the smallest, mean (over the axis
#: length) and largest radius along each feature's axis.
WIDTH_COLUMNS = ("width_min", "width_mean", "width_max")

#: Default ``detour`` of the pruning for layers: a branch stays when the shore
#: between its contacts is at least twice as long as the gap between them (an
#: arm, a bay), not for every bend of a digitized shore line. Measured on 200
#: OSM lakes (``benchmarks/bench_centerlines.py``): the polygon default 0.028
#: keeps 31 terminal branches per lake, 0.5 keeps 17, 1.0 keeps 12 with 1.2
#: spurious ones and 95% of each lake covered by the discs of its line, where
#: pruning by ``lam`` at the mean width instead (1.3 spurious) cuts whole narrow
#: arms (83% covered, as pygeoops.centerline's defaults).
DETOUR = 1.0

#: Options the lighter path of :func:`feature_axis` takes.
LIGHT_OPTIONS = frozenset({"lam", "tolerance", "detour"})

#: What a feature's work returns: its line and widths, or its stations.
KINDS = ("lines", "stations")


def axis_widths(ma: Any) -> tuple[float, float, float]:
    """Twice the smallest, the length-weighted mean and the largest radius of an axis.

    Compiled (:func:`medialaxis.gis._kernels.axis_widths_kernel`, NumPy's
    sums in NumPy's order): the NumPy version in ``tests/gis_reference.py`` to the last bit.
    """
    points = np.ascontiguousarray(ma.points, np.float64).reshape(-1, 2)
    edges = np.ascontiguousarray(ma.edges, np.int64).reshape(-1, 2)
    low, mean, high = axis_widths_kernel(points, np.ascontiguousarray(ma.radii, np.float64), edges)
    return float(low), float(mean), float(high)


def branch_lines(ma: Any) -> Any:
    """The axis's branches as one MultiLineString: :meth:`MedialAxis.to_shapely` in two vectorised shapely calls.

    The same branches in the same order and direction
    (:func:`medialaxis.gis._kernels.branch_chains`, compiled), without a
    shapely object per branch on the way: a layer's per-feature cost.
    """
    import shapely

    nodes, part = branch_chains(len(ma.points), np.asarray(ma.edges, np.int64).reshape(-1, 2))
    if not len(nodes):
        return shapely.MultiLineString()
    return shapely.multilinestrings(shapely.linestrings(ma.points[nodes], indices=part))


def chunk_lines(axes: Sequence[Any]) -> list[Any]:
    """:func:`branch_lines` of each axis (None for None or no branch), two vectorised shapely calls in all."""
    import shapely

    coords, parts, owners = [], [], []
    n_parts = 0
    for k, ma in enumerate(axes):
        if ma is None:
            continue
        nodes, part = branch_chains(len(ma.points), np.asarray(ma.edges, np.int64).reshape(-1, 2))
        if not len(nodes):
            continue
        coords.append(ma.points[nodes])
        parts.append(part + n_parts)
        owners.append(np.full(part[-1] + 1, k))
        n_parts += part[-1] + 1
    out: list[Any] = [None] * len(axes)
    if coords:
        lines = shapely.linestrings(np.concatenate(coords), indices=np.concatenate(parts))
        owner = np.concatenate(owners)
        features = np.unique(owner)
        for k, multi in zip(features, shapely.multilinestrings(lines, indices=np.searchsorted(features, owner))):
            out[k] = multi
    return out


def _checked(index: Any, geom: Any) -> bool:
    """Whether the feature has a polygon to compute (False: empty or missing); other geometries raise."""
    if geom is None or geom.is_empty:
        return False
    if geom.geom_type not in ("Polygon", "MultiPolygon"):
        raise InvalidInputError(f"feature {index!r} is a {geom.geom_type}; centerlines needs polygons")
    return True


def feature_axis(index: Any, geom: Any, options: dict[str, Any]) -> Any:
    """The medial axis of one polygon feature (None for an empty or missing geometry).

    With no options but :data:`LIGHT_OPTIONS`, the points, radii and edges of
    the axis come from :func:`medialaxis.planar.axis_arrays.polygon_axis_arrays`
    (the same arrays, half the time of the result object on small features).
    """
    if not _checked(index, geom):
        return None
    options = {"detour": DETOUR, **options}
    if options.keys() <= LIGHT_OPTIONS:
        return polygon_axis_arrays(geom, **options)
    return medial_axis(geom, **options)


def chunk_axes(chunk: Sequence[tuple[Any, Any]], options: dict[str, Any]) -> list[Any]:
    """:func:`feature_axis` of each ``(index, geometry)``; with only :data:`LIGHT_OPTIONS`, the polygons' shapely
    work in vectorised calls (:func:`medialaxis.planar.axis_layer.polygon_axes`, the same arrays)."""
    light = {"detour": DETOUR, **options}
    if not light.keys() <= LIGHT_OPTIONS:
        return [feature_axis(index, geom, options) for index, geom in chunk]
    take = [k for k, (index, geom) in enumerate(chunk) if _checked(index, geom)]
    out: list[Any] = [None] * len(chunk)
    for k, axis in zip(take, polygon_axes([chunk[k][1] for k in take], **light)):
        out[k] = axis
    return out


def run_chunk(kind: str, chunk: Sequence[tuple[Any, Any]], options: dict[str, Any], step: float | None = None
              ) -> list[Any]:
    """The work of ``kind`` (:data:`KINDS`) for each ``(index, geometry)`` of a chunk, in order."""
    axes = chunk_axes(chunk, options)
    if kind == "lines":
        widths = [(np.nan,) * 3 if ma is None else axis_widths(ma) for ma in axes]
        return list(zip(chunk_lines(axes), widths))
    return [{name: np.empty(0) for name in STATION_COLUMNS} if ma is None else
            branch_stations(ma.points, ma.radii, ma.edges, step) for ma in axes]
