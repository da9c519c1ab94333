"""Compiled kernels of the planar pipeline: the per-round triangle tests and the distance to the boundary.

:func:`triangle_centroids` finds the triangles that are not jitter slivers
and their centroids (for the inside test); :func:`piece_state` tells, for
each boundary piece, whether it is a Delaunay edge and the smallest
circumradius of its inner triangles (the adaptive sampling's test).
:func:`piece_state_reference` is the NumPy version of the latter, used by
the tests; :func:`medialaxis.planar.axis.proper_triangles` is the NumPy
version of the former.

:func:`nearest_piece_distance` takes, for each query point, the boundary
pieces (segments from a sample to the next one on its ring) that start or
end at its nearest samples, and returns the distance to the closest of
them; :func:`nearest_piece_distance_reference` is the NumPy version, used
by the tests.

:func:`circumcircles_kernel` is :func:`medialaxis.planar.delaunay.circumcircles`
(the reference) compiled, with the same operations in the same order;
likewise :func:`split_pieces` is the loop of
:func:`medialaxis.planar.boundary.sampling.refine_arcs_reference` over all rings at
once (``np.mod`` as NumPy evaluates it).
"""

from __future__ import annotations

import math

import numpy as np

from medialaxis._jit import njit
from medialaxis.planar._distance_kernels import nearest_in_grid, piece_distance, sample_grid

__all__ = ["nearest_piece_distance", "nearest_piece_distance_reference", "triangle_centroids", "piece_state",
           "piece_state_reference", "circumcircles_kernel", "circle_through", "split_pieces", "split_count",
           "nearest_samples", "nearest_with_ties", "OVER_SPLIT", "DRAWING_OVER_SPLIT"]

#: A piece too long for the split rule is cut into pieces this many times shorter than the rule asks (``ceil(OVER_SPLIT
#: * h / target)`` of them), so the radii, which shrink as the sample gets denser, rarely need another round, and a
#: Voronoi vertex lies within ``tolerance / OVER_SPLIT**2`` of the axis. 1.75 rather than 2: 10% less time per lake
#: on the tuning half of ``benchmarks/bench_centerlines.py`` (546 nodes a lake instead of 610), the same spurious
#: branches, coverage and inside share (1.5: 14% less, one spurious branch more; 1.25: lost circumcentres outside
#: that a test of the planar arrays needs).
OVER_SPLIT = 1.75
#: Drawings (SVG, DXF) keep 2: their strokes' widths are asked to 0.1% (a stroked frame's median radius came out
#: 0.107% off its 3.0 with 1.75, tests/test_drawings_cli.py), a polygon's or an image's axis to its tolerance.
DRAWING_OVER_SPLIT = 2.0


@njit(cache=True, nogil=True)
def triangle_centroids(points, simplices, sliver):  # type: ignore[no-untyped-def]
    """(T,) bool: triangles whose doubled area exceeds ``sliver`` times their longest side; their centroids.

    Returns ``(proper, centroids)``, ``centroids`` (P, 2) of the proper
    triangles in order.
    """
    n = len(simplices)
    proper = np.zeros(n, np.bool_)
    cx = np.empty(n)
    cy = np.empty(n)
    m = 0
    for t in range(n):
        a, b, c = simplices[t, 0], simplices[t, 1], simplices[t, 2]
        ux, uy = points[b, 0] - points[a, 0], points[b, 1] - points[a, 1]
        vx, vy = points[c, 0] - points[a, 0], points[c, 1] - points[a, 1]
        twice_area = abs(ux * vy - uy * vx)
        wx, wy = ux - vx, uy - vy
        longest = np.sqrt(max(ux * ux + uy * uy, vx * vx + vy * vy, wx * wx + wy * wy))
        if twice_area > sliver * longest:
            proper[t] = True
            cx[m] = (points[a, 0] + points[b, 0] + points[c, 0]) / 3.0
            cy[m] = (points[a, 1] + points[b, 1] + points[c, 1]) / 3.0
            m += 1
    out = np.empty((m, 2))
    for i in range(m):  # element by element: a slice assignment compiles its shape error's string formatting
        out[i, 0], out[i, 1] = cx[i], cy[i]
    return proper, out


@njit(cache=True, nogil=True)
def piece_state(simplices, inside, radii, nxt):  # type: ignore[no-untyped-def]
    """For each boundary piece ``(i, nxt[i])``: is it a Delaunay edge, and the least radius of its inner triangles.

    Returns ``(conforming, radius)``; ``radius`` is inf where no inner
    triangle has the piece.
    """
    n = len(nxt)
    conforming = np.zeros(n, np.bool_)
    radius = np.full(n, np.inf)
    for t in range(len(simplices)):
        for k in range(3):
            a = simplices[t, (k + 1) % 3]
            b = simplices[t, (k + 2) % 3]
            if nxt[a] == b:
                i = a
            elif nxt[b] == a:
                i = b
            else:
                continue
            conforming[i] = True
            if inside[t]:
                radius[i] = min(radius[i], radii[t])
    return conforming, radius


def piece_state_reference(
    simplices: np.ndarray, inside: np.ndarray, radii: np.ndarray, nxt: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """NumPy version of :func:`piece_state` (for the tests): edges and pieces matched by sorted keys."""
    n = len(nxt)
    s = simplices
    keys = np.concatenate([np.minimum(s[:, i], s[:, j]) * n + np.maximum(s[:, i], s[:, j])
                           for i, j in ((1, 2), (2, 0), (0, 1))])
    owner = np.tile(np.arange(len(s)), 3)
    order = np.argsort(keys, kind="stable")
    keys, owner = keys[order], owner[order]
    piece = np.minimum(np.arange(n), nxt) * n + np.maximum(np.arange(n), nxt)
    lo = np.searchsorted(keys, piece, "left")
    hi = np.searchsorted(keys, piece, "right")
    radius = np.full(n, np.inf)
    for off in (0, 1):  # an edge has at most two triangles
        j = lo + off
        has = j < hi
        t = owner[np.minimum(j, len(owner) - 1)]
        use = has & inside[t]
        radius[use] = np.minimum(radius[use], radii[t[use]])
    return hi > lo, radius


@njit(cache=True, nogil=True)
def nearest_piece_distance(query, points, nxt, prv, near):  # type: ignore[no-untyped-def]
    """Distance from each ``query`` (q, 2) to the pieces at its samples ``near`` (q, k).

    The pieces are ``(j, nxt[j])`` and ``(prv[j], j)`` for each ``j`` in
    ``near[i]``: the segments that meet at the sample ``j``.
    """
    out = np.empty(len(query))
    for i in range(len(query)):
        best = np.inf
        for m in range(near.shape[1]):
            best = min(best, piece_distance(points, nxt, prv, near[i, m], query[i, 0], query[i, 1]))
        out[i] = best
    return out


def nearest_piece_distance_reference(
    query: np.ndarray, points: np.ndarray, nxt: np.ndarray, prv: np.ndarray, near: np.ndarray
) -> np.ndarray:
    """NumPy version of :func:`nearest_piece_distance` (for the tests)."""
    best = np.full(len(query), np.inf)
    for start in (near, prv[near]):
        a = points[start]
        ab = points[nxt[start]] - a
        q = query[:, None, :]
        denom = np.maximum((ab**2).sum(-1), 1e-300)
        t = np.clip(((q - a) * ab).sum(-1) / denom, 0.0, 1.0)
        d = np.linalg.norm(q - (a + t[..., None] * ab), axis=-1)
        best = np.minimum(best, d.min(axis=1))
    return best


@njit(cache=True, nogil=True, error_model="numpy", inline="always")
def circle_through(ax, ay, px, py, qx, qy):  # type: ignore[no-untyped-def]
    """Circumcentre ``(x, y)`` and radius of the triangle ``a, p, q`` (see :func:`circumcircles_kernel`).

    Scalars, not rows of an array: the loops that call it per triangle make
    no reference counts for it.
    """
    bx, by = px - ax, py - ay
    cx, cy = qx - ax, qy - ay
    d = 2.0 * (bx * cy - by * cx)
    b2 = bx * bx + by * by
    c2 = cx * cx + cy * cy
    ux = (cy * b2 - by * c2) / d
    uy = (bx * c2 - cx * b2) / d
    r = math.hypot(ux, uy)
    if not np.isfinite(r):
        xs, ys = (ax, px, qx), (ay, py, qy)
        best, longest = 0, -1.0
        for s in range(3):  # side s is opposite corner s
            e, f = (s + 1) % 3, (s + 2) % 3
            sx, sy = xs[e] - xs[f], ys[e] - ys[f]
            if sx * sx + sy * sy > longest:
                best, longest = s, sx * sx + sy * sy
        e, f = (best + 1) % 3, (best + 2) % 3
        ux = 0.5 * (xs[e] + xs[f]) - ax
        uy = 0.5 * (ys[e] + ys[f]) - ay
        r = 0.5 * np.sqrt(longest)
    return ux + ax, uy + ay, r


@njit(cache=True, nogil=True, error_model="numpy")
def circumcircles_kernel(p, simplices):  # type: ignore[no-untyped-def]
    """Circumcentres (T, 2) and radii (T,), operation for operation as :func:`medialaxis.planar.delaunay.circumcircles`.

    Collinear triangles (no finite circle) get the midpoint of their longest side and half its length.
    """
    n = len(simplices)
    centre = np.empty((n, 2))
    radius = np.empty(n)
    for t in range(n):
        i, j, k = simplices[t, 0], simplices[t, 1], simplices[t, 2]
        centre[t, 0], centre[t, 1], radius[t] = circle_through(p[i, 0], p[i, 1], p[j, 0], p[j, 1], p[k, 0], p[k, 1])
    return centre, radius


@njit(cache=True, nogil=True)
def _insertion_sort(values, lo, hi):  # type: ignore[no-untyped-def]
    """Sort ``values[lo:hi]`` in place: linear on the nearly sorted arcs (only a wrapped piece moves)."""
    for i in range(lo + 1, hi):
        v = values[i]
        j = i - 1
        while j >= lo and values[j] > v:
            values[j + 1] = values[j]
            j -= 1
        values[j + 1] = v


@njit(cache=True, nogil=True, inline="always")
def split_count(points, i, j, radius, conforming, tolerance, min_length, ratio, over_split):  # type: ignore[no-untyped-def]
    """Into how many parts the piece from sample ``i`` to ``j`` is cut (0: kept), as :func:`split_pieces` decides
    (``over_split``: :data:`OVER_SPLIT` or a caller's own)."""
    dx = points[j, 0] - points[i, 0]
    dy = points[j, 1] - points[i, 1]
    h = np.sqrt(dx * dx + dy * dy)
    target = max(min(ratio * radius, np.sqrt(16.0 * radius * tolerance)), min_length)
    if ((h > target) or not conforming) and h > 2.0 * min_length:
        return int(min(max(np.ceil(over_split * h / target), 2.0), 64.0))
    return 0


@njit(cache=True, nogil=True)
def split_pieces(arcs, a_offsets, points, nxt, ring_length, piece_radius, conforming, tolerance, min_length, ratio,  # type: ignore[no-untyped-def]
                 over_split=OVER_SPLIT):
    """The refinement of :func:`medialaxis.planar.boundary.sampling.refine_arcs` on concatenated arcs.

    Returns ``(new_arcs, new_offsets)``; ``new_offsets[0] == -1`` when no piece is split.
    """
    n = len(arcs)
    count = np.zeros(n, np.int64)
    any_split = False
    for i in range(n):
        count[i] = split_count(points, i, nxt[i], piece_radius[i], conforming[i], tolerance, min_length, ratio,
                               over_split)
        any_split = any_split or count[i] > 0
    new_offsets = np.zeros(len(a_offsets), np.int64)
    if not any_split:
        new_offsets[0] = -1
        return arcs, new_offsets
    total = n
    for i in range(n):
        total += max(count[i] - 1, 0)
    out = np.empty(total)
    m = 0
    for r in range(len(a_offsets) - 1):
        start_m = m
        length = ring_length[r]
        for i in range(a_offsets[r], a_offsets[r + 1]):
            out[m] = arcs[i]
            m += 1
            k = count[i]
            if k == 0:
                continue
            start = arcs[i]
            stop = arcs[nxt[i]]
            if stop <= start:
                stop = stop + length
            for j in range(1, k):
                out[m] = (start + (stop - start) * j / k) % length  # fmod: both are positive
                m += 1
        _insertion_sort(out, start_m, m)
        new_offsets[r + 1] = m
    return out, new_offsets


@njit(cache=True, nogil=True)
def nearest_samples(query, points, k):  # type: ignore[no-untyped-def]
    """The ``k`` nearest ``points`` (N > k) of each query, by a grid of about two points per cell.

    Returns ``(near, sure)``: ``near`` (q, k) indices; ``sure[i]`` is False
    where the k-th and the next distance agree to 1e-9, so which ``k`` are
    nearest depends on rounding (the caller takes every tied one there,
    :func:`nearest_with_ties`). Where sure, ``near[i]`` holds the same set as
    ``cKDTree.query(..., k)``.
    """
    x0, y0, cell, g, start, members = sample_grid(points)
    return nearest_in_grid(query, points, k, x0, y0, cell, g, start, members)


@njit(cache=True, nogil=True, inline="always")
def _d2(points, p, qx, qy):  # type: ignore[no-untyped-def]
    return (points[p, 0] - qx) ** 2 + (points[p, 1] - qy) ** 2


@njit(cache=True, nogil=True)
def nearest_with_ties(query, points, k):  # type: ignore[no-untyped-def]
    """The ``k`` nearest ``points`` of each query and every point tied with the ``k``-th (to 2e-9), by brute force.

    Returns ``near`` (q, w): each row's points first, then its nearest one
    repeated. Where the ``k``-th and the next distance agree to rounding,
    which ``k`` a search returns depends on the rounding; all of them do not.
    For the few queries :func:`nearest_samples` is unsure of.
    """
    n = len(points)
    kth = np.empty(len(query))
    closest = np.zeros(len(query), np.int64)
    taken = np.zeros(len(query), np.int64)
    best = np.empty(k)
    for q in range(len(query)):
        qx, qy = query[q, 0], query[q, 1]
        found = 0
        for p in range(n):
            d = _d2(points, p, qx, qy)
            if d < _d2(points, closest[q], qx, qy):
                closest[q] = p
            if found < k or d < best[k - 1]:  # the k smallest so far, sorted
                j = min(found, k - 1)
                while j > 0 and best[j - 1] > d:
                    best[j] = best[j - 1]
                    j -= 1
                best[j] = d
                found = min(found + 1, k)
        kth[q] = best[k - 1] * (1.0 + 2e-9)
        for p in range(n):
            taken[q] += _d2(points, p, qx, qy) <= kth[q]
    width = taken.max() if len(query) else 0
    near = np.empty((len(query), width), np.int64)
    for q in range(len(query)):
        m = 0
        for p in range(n):
            if _d2(points, p, query[q, 0], query[q, 1]) <= kth[q]:
                near[q, m] = p
                m += 1
        for j in range(m, width):
            near[q, j] = closest[q]
    return near

