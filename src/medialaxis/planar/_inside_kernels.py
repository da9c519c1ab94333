"""Compiled point-in-region test, the answers of ``shapely.contains_xy`` without GEOS calls per round.

:class:`RegionLocator` files the boundary segments of a polygonal region in
horizontal bands once; :func:`locate_points` counts, for each point, the
segments of its band that a ray towards +x crosses, with GEOS's
half-open rule (a segment counts when one end lies strictly above the
point and the other not). The side of a point against a segment is the sign
of a float determinant, trusted only where it exceeds ``1e-12`` of the sum
of its terms' magnitudes (the rounding error is below ``1e-15`` of it); a
point nearer than that to a segment's line (on the boundary, or about to
be) is answered by ``shapely.contains_xy`` itself. So every answer is
GEOS's. :func:`locate_points_reference` is the same count in NumPy over
all segments, used by the tests.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import shapely

from medialaxis._jit import njit

__all__ = ["RegionLocator", "band_segments", "locate_points", "triangle_centroid", "locate_centroids", "locate_points_reference"]

#: Trust a determinant's sign above this fraction of its terms' magnitudes.
SIGN_MARGIN = 1e-12
#: Unsure: ask GEOS.
UNSURE = 2


@njit(cache=True, nogil=True)
def band_segments(segments, n_bands):  # type: ignore[no-untyped-def]
    """``(y0, height, start, members)``: the segments' (s, 4: x1 y1 x2 y2) lowest y and height (0 and 1 without
    segments, at least 1e-300), and CSR lists of the segments meeting each of ``n_bands`` bands of that height."""
    y0, y1 = np.inf, -np.inf
    for s in range(len(segments)):
        y0 = min(y0, segments[s, 1], segments[s, 3])
        y1 = max(y1, segments[s, 1], segments[s, 3])
    if len(segments):
        height = max(y1 - y0, 1e-300)
    else:
        y0, height = 0.0, 1.0
    count = np.zeros(n_bands + 1, np.int64)
    lo = np.empty(len(segments), np.int64)
    hi = np.empty(len(segments), np.int64)
    for s in range(len(segments)):
        a, b = segments[s, 1], segments[s, 3]
        lo[s] = min(max(int((min(a, b) - y0) / height * n_bands), 0), n_bands - 1)
        hi[s] = min(max(int((max(a, b) - y0) / height * n_bands), 0), n_bands - 1)
        for k in range(lo[s], hi[s] + 1):
            count[k + 1] += 1
    for k in range(n_bands):
        count[k + 1] += count[k]
    start = count
    members = np.empty(start[-1], np.int64)
    fill = np.empty(len(start) - 1, np.int64)
    for i in range(len(fill)):
        fill[i] = start[i]
    for s in range(len(segments)):
        for k in range(lo[s], hi[s] + 1):
            members[fill[k]] = s
            fill[k] += 1
    return y0, height, start, members


@njit(cache=True, nogil=True)
def locate_points(x, y, segments, start, members, y0, height):  # type: ignore[no-untyped-def]
    """(q,) int8: 1 inside, 0 outside, ``UNSURE`` (2) within rounding of a segment's line.

    The test is written out in the loop, not called per point: a compiled
    call with array arguments costs two atomic reference counts per array.
    """
    out = np.zeros(len(x), np.int8)
    n_bands = len(start) - 1
    for i in range(len(x)):
        px, py = x[i], y[i]
        if not (py >= y0 and py <= y0 + height):
            continue
        band = min(max(int((py - y0) / height * n_bands), 0), n_bands - 1)
        crossings = 0
        unsure = False
        for m in range(start[band], start[band + 1]):
            s = members[m]
            x1, y1, x2, y2 = segments[s, 0], segments[s, 1], segments[s, 2], segments[s, 3]
            if py < min(y1, y2) or py > max(y1, y2) or max(x1, x2) < px:
                continue
            u = (x2 - x1) * (py - y1)
            v = (y2 - y1) * (px - x1)
            det = u - v
            if abs(det) <= SIGN_MARGIN * (abs(u) + abs(v)):
                unsure = True
                break
            if (y1 > py) != (y2 > py):
                left = det > 0.0
                if y2 < y1:
                    left = not left
                if left:
                    crossings += 1
        out[i] = UNSURE if unsure else crossings % 2
    return out


@njit(cache=True, nogil=True)
def points_extent(points, lo, hi):  # type: ignore[no-untyped-def]
    """The larger side of the bounding box of ``points[lo:hi]``."""
    extent = 0.0
    for k in range(2):
        low, high = np.inf, -np.inf
        for i in range(lo, hi):
            low = min(low, points[i, k])
            high = max(high, points[i, k])
        extent = max(extent, high - low)
    return extent


@njit(cache=True, nogil=True, inline="always")
def triangle_centroid(ax, ay, bx, by, cx, cy, sliver):  # type: ignore[no-untyped-def]
    """``(proper, gx, gy)``: whether the triangle is more than a sliver, and its centroid (0, 0 for a sliver)."""
    ux, uy = bx - ax, by - ay
    vx, vy = cx - ax, cy - ay
    wx, wy = ux - vx, uy - vy
    longest = np.sqrt(max(ux * ux + uy * uy, vx * vx + vy * vy, wx * wx + wy * wy))
    if abs(ux * vy - uy * vx) <= sliver * longest:
        return False, 0.0, 0.0
    return True, (ax + bx + cx) / 3.0, (ay + by + cy) / 3.0


@njit(cache=True, nogil=True)
def locate_centroids(points, simplices, sliver_fraction, segments, start, members, y0, height):  # type: ignore[no-untyped-def]
    """Where the centroid of each proper triangle lies (as :func:`locate_points`; 0 for slivers), and the centroids.

    A sliver's doubled area is at most ``sliver_fraction`` of the points'
    extent times its longest side (as :func:`medialaxis.planar._kernels.triangle_centroids`).
    """
    sliver = sliver_fraction * points_extent(points, 0, len(points))
    centroid = np.empty((len(simplices), 2))
    proper = np.empty(len(simplices), np.bool_)
    for t in range(len(simplices)):
        a, b, c = simplices[t, 0], simplices[t, 1], simplices[t, 2]
        proper[t], centroid[t, 0], centroid[t, 1] = triangle_centroid(
            points[a, 0], points[a, 1], points[b, 0], points[b, 1], points[c, 0], points[c, 1], sliver)
    where = locate_points(centroid[:, 0], centroid[:, 1], segments, start, members, y0, height)
    for t in range(len(simplices)):
        if not proper[t]:
            where[t] = 0
    return where, centroid


def locate_points_reference(x: np.ndarray, y: np.ndarray, segments: np.ndarray) -> np.ndarray:
    """NumPy version of :func:`locate_points` over all segments (for the tests)."""
    x1, y1, x2, y2 = (segments[:, k][None, :] for k in range(4))
    px, py = x[:, None], y[:, None]
    near = (py >= np.minimum(y1, y2)) & (py <= np.maximum(y1, y2)) & (np.maximum(x1, x2) >= px)
    u = (x2 - x1) * (py - y1)
    v = (y2 - y1) * (px - x1)
    det = u - v
    unsure = (near & (np.abs(det) <= SIGN_MARGIN * (np.abs(u) + np.abs(v)))).any(1)
    left = (det > 0) ^ (y2 < y1)
    crossings = (near & ((y1 > py) != (y2 > py)) & left).sum(1)
    return np.where(unsure, UNSURE, crossings % 2).astype(np.int8)


class RegionLocator:
    """The boundary segments of a polygonal ``region``, filed by bands, for :meth:`contains`."""

    def __init__(self, region: Any, segments: np.ndarray | None = None) -> None:
        """``segments``: the region's boundary segments (s, 4: x1 y1 x2 y2) ring by ring, if known already."""
        self.region = region
        if segments is None:
            parts = []
            for ring in shapely.get_rings(shapely.get_parts(region)):
                xy = shapely.get_coordinates(ring)
                parts.append(np.hstack((xy[:-1], xy[1:])))
            segments = np.concatenate(parts) if parts else np.empty((0, 4))
        self.segments = np.ascontiguousarray(segments, np.float64)
        self.y0, self.height, self.start, self.members = band_segments(self.segments, max(1, len(self.segments) // 2))

    def inner_triangles(self, points: np.ndarray, simplices: np.ndarray, sliver_fraction: float) -> np.ndarray:
        """(T,) bool: proper triangles whose centroid the region contains (see :func:`locate_centroids`)."""
        where, centroid = locate_centroids(points, simplices, sliver_fraction, self.segments, self.start,
                                           self.members, self.y0, self.height)
        inside = where == 1
        unsure = np.flatnonzero(where == UNSURE)
        if len(unsure):
            shapely.prepare(self.region)
            inside[unsure] = shapely.contains_xy(self.region, centroid[unsure, 0], centroid[unsure, 1])
        return inside

    def contains(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """(q,) bool: ``shapely.contains_xy(region, x, y)``."""
        x = np.ascontiguousarray(x, dtype=np.float64)
        y = np.ascontiguousarray(y, dtype=np.float64)
        where = locate_points(x, y, self.segments, self.start, self.members, self.y0, self.height)
        inside = where == 1
        unsure = np.flatnonzero(where == UNSURE)
        if len(unsure):
            shapely.prepare(self.region)
            inside[unsure] = shapely.contains_xy(self.region, x[unsure], y[unsure])
        return inside
