"""The pruned axis of a polygon as plain arrays: the lighter path of GIS layers, one feature at a time.

:func:`polygon_axis_arrays` returns the points, radii and edges of
:func:`medialaxis.planar.pipeline.voronoi_medial_axis` bit for bit (tested),
without the result object, its unpruned axis and metadata, and with
everything after the sampling in one compiled call
(:func:`medialaxis.planar._axis_kernels.pruned_axis`). On the OpenStreetMap
lakes of ``benchmarks/bench_centerlines.py`` the Python between the compiled
steps was a third of the time per lake.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from medialaxis.planar._axis_kernels import inner_centres, pruned_axis
from medialaxis.planar._inside_kernels import RegionLocator
from medialaxis.planar.axis import axis_positions
from medialaxis.planar.boundary.corners import RingArrays, ring_arrays
from medialaxis.planar.boundary.sampling import BoundarySample
from medialaxis.planar.delaunay import Triangulation
from medialaxis.planar.options import PlanarOptions
from medialaxis.planar.pipeline import _load, sampled, voronoi_medial_axis
from medialaxis.planar.pruning import REGROW_DETOUR

__all__ = ["AxisArrays", "polygon_axis_arrays", "axis_of_sample", "NEAREST"]

#: The radius of a node comes from the boundary pieces at its nearest samples,
#: as :func:`medialaxis.planar.axis.boundary_distance` takes them.
NEAREST = 8


class AxisArrays(NamedTuple):
    """The pruned axis: ``points`` (n, 2), ``radii`` (n,), ``edges`` (m, 2) int."""

    points: np.ndarray
    radii: np.ndarray
    edges: np.ndarray


def polygon_axis_arrays(shape: Any, *, lam: float | None = None, tolerance: float | None = None,
                        detour: float | None = None) -> AxisArrays:
    """Points, radii and edges of ``voronoi_medial_axis(shape, lam=..., tolerance=..., detour=...)``.

    Parameters
    ----------
    shape : shapely Polygon or MultiPolygon, or any planar input
        Inputs other than polygons (and samples of at most :data:`NEAREST`
        points) go the whole way of the pipeline.
    lam, tolerance, detour : float, optional
        As :func:`medialaxis.planar.pipeline.voronoi_medial_axis` takes them.

    Returns
    -------
    AxisArrays

    Raises
    ------
    InvalidInputError, EmptyShapeError, ComputationError
        As :func:`~medialaxis.planar.pipeline.voronoi_medial_axis` does.

    Examples
    --------
    >>> import numpy as np
    >>> from shapely.geometry import box
    >>> axis = polygon_axis_arrays(box(0, 0, 4, 2))
    >>> ma = voronoi_medial_axis(box(0, 0, 4, 2))
    >>> all(np.array_equal(a, b) for a, b in zip(axis, (ma.points, ma.radii, ma.edges)))
    True
    >>> len(axis.edges) == len(axis.points) - 1  # a tree: the rectangle's axis with its four corner arms
    True
    """
    src = _load(shape, PlanarOptions(tolerance=tolerance))
    if src.is_raster or src.labels is not None or src.drawing is not None:
        return _whole_way(shape, lam, tolerance, detour)
    given = lam, tolerance, detour
    tolerance, lam, detour, rings, smp, tri, inside = sampled(src, lam=lam, tolerance=tolerance, detour=detour,
                                                             boundary="contour")
    if len(smp.points) <= NEAREST:
        return _whole_way(shape, *given)
    return axis_of_sample(rings.region, rings.locator, ring_arrays(rings), smp, tri, inside, tolerance, lam, detour)


def axis_of_sample(region: Any, locator: RegionLocator, closed: RingArrays, smp: BoundarySample, tri: Triangulation,
                   inside: np.ndarray, tolerance: float, lam: float, detour: float) -> AxisArrays:
    """The pruned axis of a sample (more than :data:`NEAREST` points) of ``region`` (its rings ``closed``), its
    triangulation and inner triangles."""
    inner, pos, all_in = inner_centres(tri.centers, inside, locator.segments, locator.start, locator.members,
                                       locator.y0, locator.height)
    if not all_in:  # circumcentres to move, or an inside test for GEOS
        inner, pos = axis_positions(tri, inside, region, locator)
    points, radii, edges = pruned_axis(
        pos, tri.simplices, tri.neighbors, inner.astype(np.int64), np.ascontiguousarray(tri.points, np.float64),
        np.asarray(tri.radii, np.float64), np.ascontiguousarray(smp.points, np.float64), np.asarray(smp.next, np.int64),
        np.asarray(smp.arc, np.float64), np.asarray(smp.ring, np.int64), np.asarray(smp.ring_length, np.float64),
        closed.s, closed.start, closed.touching, float(tolerance), float(lam), float(detour), REGROW_DETOUR, NEAREST, locator.segments, locator.start,
        locator.members, locator.y0, locator.height)
    return AxisArrays(points, radii, edges)


def _whole_way(shape: Any, lam: float | None, tolerance: float | None, detour: float | None) -> AxisArrays:
    """The axis by the pipeline's own steps (inputs the compiled path does not take)."""
    ma = voronoi_medial_axis(shape, lam=lam, tolerance=tolerance, detour=detour)
    return AxisArrays(ma.points, ma.radii, ma.edges)
