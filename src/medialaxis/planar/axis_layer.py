"""The pruned axes of many polygons, the shapely work of all of them in a few vectorised calls: GIS layers.

:func:`polygon_axes` gives what :func:`medialaxis.planar.axis_arrays.polygon_axis_arrays`
gives for each polygon, bit for bit (tested), but validates, normalizes and
measures the polygons, takes their rings apart and files their boundary
segments for the inside test with one shapely call each over the whole list,
not with a dozen calls per polygon: on the OpenStreetMap lakes of
``benchmarks/bench_centerlines.py`` those calls were a fifth of the time per
lake. A polygon this path does not take as it is (invalid, empty, holding
huge coordinates, simplified first, too small a ring, a sample the compiled
rounds give up on) goes the way of :func:`polygon_axis_arrays`, which
repairs it or raises its error.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import shapely

from medialaxis.core.validate import MAX_COORDINATE, check_number
from medialaxis.planar._inside_kernels import RegionLocator
from medialaxis.planar.axis_arrays import NEAREST, AxisArrays, axis_of_sample, polygon_axis_arrays
from medialaxis.planar.boundary.adaptive import incremental_sample
from medialaxis.planar.boundary.corners import closed_ring_arrays
from medialaxis.planar.pipeline import MIN_RING_FRACTION, SIMPLIFY_ABOVE, parameters
from medialaxis.planar.reading.vectors import NEAR_DUPLICATE

__all__ = ["polygon_axes"]


def _offsets(index: np.ndarray, n: int) -> np.ndarray:
    """Where the rows of each of ``n`` groups start (``index`` sorted, groups may be empty), and the end."""
    return np.concatenate([[0], np.cumsum(np.bincount(index, minlength=n))]).astype(np.int64)


def _per_group(ufunc: Any, values: np.ndarray, start: np.ndarray, empty: Any) -> np.ndarray:
    """``ufunc.reduceat`` of ``values`` over the groups ``start[g]:start[g + 1]``, ``empty`` for an empty group."""
    out = np.full(len(start) - 1, empty, dtype=values.dtype)
    full = np.flatnonzero(start[1:] > start[:-1])
    if len(full):
        out[full] = ufunc.reduceat(values, start[:-1][full])
    return out


def _extents(xy: np.ndarray, start: np.ndarray) -> np.ndarray:
    """``float(np.ptp(xy[a:b], axis=0).max())`` of each group ``a:b`` of rows."""
    ptp = [_per_group(np.maximum, xy[:, c], start, 0.0) - _per_group(np.minimum, xy[:, c], start, 0.0) for c in (0, 1)]
    return np.maximum(*ptp)


def _merged(geoms: np.ndarray, tolerance: np.ndarray) -> np.ndarray:
    """``shapely.remove_repeated_points`` of each geometry; the geometry itself where GEOS refuses it."""
    try:
        return shapely.remove_repeated_points(geoms, tolerance)
    except shapely.errors.GEOSException:
        out = np.empty(len(geoms), dtype=object)
        for k, (g, t) in enumerate(zip(geoms, tolerance)):
            try:
                out[k] = shapely.remove_repeated_points(g, t)
            except shapely.errors.GEOSException:  # a ring that would collapse: kept as it is
                out[k] = g
        return out


def _valid_regions(geoms: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`medialaxis.planar.reading.vectors.validate_polygonal`'s region of each geometry it takes as it is, and which."""
    n = len(geoms)
    ok = np.isin(shapely.get_type_id(geoms), (3, 6)) & ~shapely.is_empty(geoms)
    ok &= shapely.get_num_coordinates(geoms) > 0
    ok[ok] &= shapely.is_valid(geoms[ok]) & (shapely.area(geoms[ok]) > 0)
    regions = np.empty(n, dtype=object)
    take = np.flatnonzero(ok)
    coords, which = shapely.get_coordinates(geoms[take], return_index=True)
    start = _offsets(which, len(take))
    finite = np.isfinite(coords).all(1)
    largest = np.abs(np.where(finite[:, None], coords, 0.0)).max(1) if len(coords) else np.empty(0)
    fine = _per_group(np.logical_and, finite, start, True) & (_per_group(np.maximum, largest, start, 0.0)
                                                              <= MAX_COORDINATE)
    extent = _extents(coords, start)[fine]  # check_coordinates passes, then validate_polygonal's extent
    ok[take[~fine]] = False
    take, counts = take[fine], np.diff(start)[fine]
    given = geoms[take]
    merged = _merged(given, NEAR_DUPLICATE * extent)
    changed = np.flatnonzero(shapely.get_num_coordinates(merged) != counts)
    if len(changed):
        m = merged[changed]
        use = shapely.is_valid(m) & ~shapely.is_empty(m) & (shapely.area(m) > 0)
        given = given.copy()
        given[changed[use]] = m[use]
    regions[take] = shapely.normalize(given)
    return regions, ok


def polygon_axes(geoms: Sequence[Any], *, lam: float | None = None, tolerance: float | None = None,
                 detour: float | None = None) -> list[AxisArrays]:
    """``[polygon_axis_arrays(g, lam=lam, tolerance=tolerance, detour=detour) for g in geoms]``.

    Parameters
    ----------
    geoms : sequence of shapely Polygon or MultiPolygon
        Other geometries go the way of :func:`polygon_axis_arrays` (which
        raises for them as it does).
    lam, tolerance, detour : float, optional
        As :func:`medialaxis.planar.pipeline.voronoi_medial_axis` takes them.

    Returns
    -------
    list of AxisArrays

    Examples
    --------
    >>> import numpy as np
    >>> from shapely.geometry import box
    >>> shapes = [box(0, 0, 4, 2), box(0, 0, 1, 5).union(box(0, 0, 5, 1))]
    >>> together = polygon_axes(shapes)
    >>> alone = [polygon_axis_arrays(g) for g in shapes]
    >>> all(np.array_equal(a, b) for one, other in zip(together, alone) for a, b in zip(one, other))
    True
    """
    geoms = np.asarray(list(geoms), dtype=object)
    n = len(geoms)
    if tolerance is not None:
        tolerance = check_number(tolerance, "tolerance")
    regions, ok = _valid_regions(geoms)
    out: list[Any] = [None] * n
    take = np.flatnonzero(ok)
    xy, which = shapely.get_coordinates(regions[take], return_index=True)
    vstart = _offsets(which, len(take))
    centre = shapely.get_coordinates(shapely.centroid(regions[take]))
    far = _per_group(np.maximum, ((xy - centre[which]) ** 2).sum(1), vstart, 0.0)
    simple = shapely.normalize(regions[take])  # simplify_rings(region, 0.0)'s region
    parts, part_of = shapely.get_parts(simple, return_index=True)
    rings, ring_part = shapely.get_rings(parts, return_index=True)
    ring_of = part_of[ring_part]
    rxy, row_ring = shapely.get_coordinates(rings, return_index=True)
    rstart = _offsets(row_ring, len(rings))
    first_ring = _offsets(ring_of, len(take))
    last = np.zeros(len(rxy), bool)  # each ring's repeated first vertex
    last[rstart[1:][rstart[1:] > rstart[:-1]] - 1] = True
    pair = np.flatnonzero(~last[:-1])  # the segments (row, row + 1) of the locator, ring by ring
    segments = np.hstack((rxy[pair], rxy[pair + 1]))
    seg_start = _offsets(row_ring[pair], len(rings))
    sizes = np.maximum(np.diff(rstart) - 1, 0)  # vertices of each ring, not repeated
    spread = _extents(rxy, rstart)
    all_full = _per_group(np.logical_and, sizes >= 3, first_ring, True)  # every ring of the feature is one of Rings'
    narrowest = _per_group(np.minimum, spread, first_ring, np.inf)
    vertices = rxy[~last]  # the rings one after the other, not closed: ring r at vstart[r]:vstart[r + 1]
    open_start = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
    diameter = 2.0 * np.sqrt(far)
    small = np.diff(vstart) <= SIMPLIFY_ABOVE
    for j, k in enumerate(take):
        axis = None
        size = float(diameter[j])
        if small[j]:
            rings = range(first_ring[j], first_ring[j + 1])
            sliced = bool(all_full[j])
            if not sliced or narrowest[j] >= MIN_RING_FRACTION * size:  # else polygon_axis_arrays raises
                axis = _one(simple[j], rings, sliced, size, rxy, rstart, vertices, open_start, sizes, spread, segments,
                            seg_start, lam, tolerance, detour)
        out[k] = polygon_axis_arrays(geoms[k], lam=lam, tolerance=tolerance, detour=detour) if axis is None else axis
    for k in np.flatnonzero(~ok):
        out[k] = polygon_axis_arrays(geoms[k], lam=lam, tolerance=tolerance, detour=detour)
    return out


def _one(region: Any, ring_ids: range, sliced: bool, size: float, rxy: np.ndarray, rstart: np.ndarray,
         vertices: np.ndarray, open_start: np.ndarray, sizes: np.ndarray, spread: np.ndarray, segments: np.ndarray,
         seg_start: np.ndarray, lam: float | None, tolerance: float | None,
         detour: float | None) -> AxisArrays | None:
    """The axis of one region (its rings ``ring_ids`` of the layer's arrays) as :func:`polygon_axis_arrays`
    computes it, or None where that function takes another way. ``sliced``: every ring has three vertices
    or more (is one of ``Rings.vertices``) and none is too small (the caller checked)."""
    tolerance, lam, detour = parameters(size, lam, tolerance, detour)
    first, end = ring_ids[0], ring_ids[-1] + 1
    if sliced:  # the usual case: slices
        xy = vertices[open_start[first]:open_start[end]]
        start = open_start[first:end + 1] - open_start[first]
    else:
        kept = [r for r in ring_ids if sizes[r] >= 3]
        if not kept or min(spread[r] for r in kept) < MIN_RING_FRACTION * size:
            return None  # polygon_axis_arrays raises
        xy = np.concatenate([rxy[rstart[r]:rstart[r + 1] - 1] for r in kept])
        start = np.concatenate([[0], np.cumsum([sizes[r] for r in kept])]).astype(np.int64)
    closed = closed_ring_arrays(xy, start)
    locator = RegionLocator(region, segments[seg_start[ring_ids[0]]:seg_start[ring_ids[-1] + 1]])
    min_length = max(tolerance, lam / 8.0)
    found = incremental_sample(region, locator, closed, tolerance, min_length, show_progress=False)
    if found is None:
        return None
    smp, tri, inside = found
    if not inside.any() or len(smp.points) <= NEAREST:
        return None
    return axis_of_sample(region, locator, closed, smp, tri, inside, tolerance, lam, detour)
