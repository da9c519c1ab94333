"""Regions painted by closed rings and stroked lines, as drawings define them.

Drawings (SVG, DXF) describe a region by its boundary rings and a fill rule
rather than by a valid polygon: rings may cross themselves and each other, and
a hole is whatever the rule leaves unpainted. :func:`fill_rings` turns such
rings into a valid shapely region under the rule; :func:`stroke_region` turns
stroked lines into the region the stroke paints.

The fill is exact up to floating point: the rings' linework is noded and
polygonized into faces, and each face is kept by the winding number of an
interior point (nonzero: any winding; evenodd: odd winding), as SVG 1.1
section 11.3 ("Fill Properties") defines the rules.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Literal

import numpy as np
import shapely
from shapely.geometry import LinearRing, LineString, MultiLineString, Polygon

__all__ = ["FILL_RULES", "fill_rings", "winding_numbers", "stroke_region"]

FILL_RULES = ("nonzero", "evenodd")

#: Points times edges per block of the explicit winding-number sum.
_WINDING_BLOCK = 4_000_000


def _without_repeats(points: np.ndarray) -> np.ndarray:
    """The polyline without consecutive repeated points."""
    points = np.asarray(points, dtype=np.float64)
    return points[np.r_[True, np.any(points[1:] != points[:-1], axis=1)]]


def _closed(ring: np.ndarray) -> np.ndarray | None:
    """The ring without repeated consecutive points, or None if it encloses nothing."""
    ring = _without_repeats(ring)
    if len(ring) > 1 and np.array_equal(ring[0], ring[-1]):
        ring = ring[:-1]
    if len(ring) < 3:
        return None
    return ring


def winding_numbers(points: np.ndarray, ring: np.ndarray) -> np.ndarray:
    """Winding number of a closed ring around each point (Sunday's crossing rule).

    Parameters
    ----------
    points : (m, 2) float ndarray
    ring : (n, 2) float ndarray
        Vertices of a closed polyline (the last joins the first).

    Returns
    -------
    (m,) int ndarray
        Positive for counter-clockwise turns in a y-up frame.

    References
    ----------
    .. [1] D. Sunday, "Inclusion of a point in a polygon", geomalgorithms.com, 2001.
    .. [2] K. Hormann, A. Agathos, "The point in polygon problem for arbitrary polygons",
           Computational Geometry 20(3):131-144, 2001. doi:10.1016/S0925-7721(01)00012-8 (the
           crossing rule with orientation).

    Examples
    --------
    >>> square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    >>> winding_numbers(np.array([[0.5, 0.5], [2.0, 0.5]]), square).tolist()
    [1, 0]
    """
    points = np.asarray(points, dtype=np.float64)
    a = np.asarray(ring, dtype=np.float64)
    b = np.roll(a, -1, axis=0)
    total = np.zeros(len(points), dtype=np.int64)
    step = max(1, _WINDING_BLOCK // max(len(a), 1))
    for lo in range(0, len(points), step):
        p = points[lo : lo + step, None, :]
        left = (b[:, 0] - a[:, 0]) * (p[..., 1] - a[:, 1]) - (p[..., 0] - a[:, 0]) * (b[:, 1] - a[:, 1])
        up = (a[:, 1] <= p[..., 1]) & (b[:, 1] > p[..., 1]) & (left > 0)
        down = (a[:, 1] > p[..., 1]) & (b[:, 1] <= p[..., 1]) & (left < 0)
        total[lo : lo + step] = up.sum(1) - down.sum(1)
    return total


def fill_rings(rings: Sequence[np.ndarray], rule: Literal["nonzero", "evenodd"] = "nonzero") -> Any:
    """The region a set of closed rings paints under a fill rule.

    Parameters
    ----------
    rings : sequence of (n, 2) float ndarrays
        Closed polylines (the last point joins the first), in any
        orientation; they may cross themselves and one another.
    rule : {"nonzero", "evenodd"}
        ``"nonzero"`` (SVG's default) paints every point the rings wind
        around; ``"evenodd"`` paints the points they wind around an odd
        number of times.

    Returns
    -------
    shapely Polygon or MultiPolygon
        Valid; empty if the rings enclose nothing.

    Examples
    --------
    Two nested squares of the same orientation: nonzero paints the inner one,
    evenodd leaves a hole.

    >>> outer = np.array([[0, 0], [4, 0], [4, 4], [0, 4]], float)
    >>> inner = np.array([[1, 1], [3, 1], [3, 3], [1, 3]], float)
    >>> fill_rings([outer, inner], "nonzero").area, fill_rings([outer, inner], "evenodd").area
    (16.0, 12.0)
    """
    if rule not in FILL_RULES:
        raise ValueError(f"fill rule must be one of {FILL_RULES}, got {rule!r}")
    closed = [r for r in (_closed(r) for r in rings) if r is not None]
    if not closed:
        return Polygon()
    if len(closed) == 1:
        ring = LinearRing(closed[0])
        if ring.is_simple:
            poly = Polygon(ring)
            return poly if poly.area > 0 else Polygon()
    lines = MultiLineString([np.vstack([r, r[:1]]) for r in closed])
    faces = [f for f in shapely.get_parts(shapely.polygonize(shapely.get_parts(shapely.node(lines)))) if f.area > 0]
    if not faces:
        return Polygon()
    inner = np.array([f.point_on_surface().coords[0] for f in faces])
    winding = np.zeros(len(faces), dtype=np.int64)
    for r in closed:
        ring = LinearRing(r)
        if ring.is_simple:
            # A simple ring winds once around its inside, in its orientation.
            sign = 1 if ring.is_ccw else -1
            winding += sign * shapely.contains_xy(Polygon(ring), inner[:, 0], inner[:, 1])
        else:
            winding += winding_numbers(inner, r)
    keep = winding != 0 if rule == "nonzero" else (winding % 2) == 1
    kept = [f for f, k in zip(faces, keep) if k]
    if not kept:
        return Polygon()
    # Faces of one noding share edges exactly: a coverage union merges them cheaply.
    region = shapely.coverage_union_all(kept)
    if not region.is_valid:
        region = shapely.make_valid(shapely.union_all(kept))
    return region


def _mitres(points: np.ndarray, closed: bool, half: float, limit: float) -> list[Any]:
    """The mitre corners (beyond the bevel) of a polyline's joins whose mitre ratio is within ``limit``.

    At a join whose segments turn by the angle ``phi`` between their outer
    normals ``n1`` and ``n2``, the mitre tip lies at ``half * (n1 + n2) /
    (1 + n1.n2)`` from the vertex and the mitre ratio (SVG's
    ``stroke-miterlimit``) is ``1 / cos(phi / 2)``.
    """
    if closed:
        if np.array_equal(points[0], points[-1]):
            points = points[:-1]
        prev, vert, nxt = np.roll(points, 1, axis=0), points, np.roll(points, -1, axis=0)
    else:
        prev, vert, nxt = points[:-2], points[1:-1], points[2:]
    if len(vert) == 0:
        return []
    u = vert - prev
    v = nxt - vert
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    turn = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]
    side = np.where(turn > 0, 1.0, -1.0)[:, None]  # the outer side is right of a left turn
    n1 = side * np.c_[u[:, 1], -u[:, 0]]
    n2 = side * np.c_[v[:, 1], -v[:, 0]]
    cos_phi = (n1 * n2).sum(1)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = 1.0 / np.sqrt((1.0 + cos_phi) / 2.0)
    keep = (np.abs(turn) > 1e-12) & (cos_phi > -1.0 + 1e-12) & (ratio <= limit)
    out = []
    for p, a, b, c in zip(vert[keep], n1[keep], n2[keep], cos_phi[keep]):
        tip = p + half * (a + b) / (1.0 + c)
        out.append(Polygon([p, p + half * a, tip, p + half * b]))
    return out


_CAPS = {"butt": "flat", "round": "round", "square": "square"}
_JOINS = {"miter": "mitre", "miter-clip": "mitre", "arcs": "mitre", "round": "round", "bevel": "bevel"}


def stroke_region(
    lines: Sequence[tuple[np.ndarray, bool]],
    width: float,
    *,
    cap: str = "butt",
    join: str = "miter",
    miter_limit: float = 4.0,
    quad_segs: int = 16,
) -> Any:
    """The region a stroke of ``width`` paints along polylines.

    Parameters
    ----------
    lines : sequence of ((n, 2) float ndarray, bool)
        Each polyline with whether it is closed (a closed one has joins at
        its first point and no caps).
    width : float
        Stroke width, in the polylines' units.
    cap : {"butt", "round", "square"}
        SVG ``stroke-linecap``.
    join : {"miter", "round", "bevel"}
        SVG ``stroke-linejoin`` (``miter-clip`` and ``arcs`` are drawn as
        ``miter``).
    miter_limit : float
        SVG ``stroke-miterlimit``: a miter longer than ``miter_limit * width``
        is bevelled.
    quad_segs : int
        Segments per quarter circle of round caps and joins.

    Returns
    -------
    shapely Polygon or MultiPolygon
        Empty if nothing is painted.

    Examples
    --------
    >>> line = np.array([[0.0, 0.0], [10.0, 0.0]])
    >>> stroke_region([(line, False)], 2.0).area
    20.0
    """
    if width <= 0 or not lines:
        return Polygon()
    parts = []
    for points, closed in lines:
        points = _without_repeats(points)
        if len(points) < 2:
            if cap in ("round", "square") and len(points) == 1:  # a zero-length subpath paints a cap only
                dot = shapely.Point(points[0]).buffer(width / 2, quad_segs=quad_segs, cap_style=_CAPS[cap])
                parts.append(dot)
            continue
        if closed and not np.array_equal(points[0], points[-1]):
            points = np.vstack([points, points[:1]])
        geom = LinearRing(points) if closed and len(points) >= 4 else LineString(points)
        style = _JOINS.get(join, "mitre")
        # GEOS cuts a mitre over the limit at the limit; SVG bevels it: bevel everywhere, then add the
        # mitres within the limit.
        parts.append(
            geom.buffer(
                width / 2,
                quad_segs=quad_segs,
                cap_style=_CAPS.get(cap, "flat"),
                join_style="bevel" if style == "mitre" else style,
            )
        )
        if style == "mitre":
            parts.extend(_mitres(points, closed, width / 2, max(float(miter_limit), 1.0)))
    parts = [p for p in parts if not p.is_empty]
    return shapely.union_all(parts) if parts else Polygon()
