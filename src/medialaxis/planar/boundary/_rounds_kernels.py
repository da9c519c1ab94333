"""Compiled: the rounds of the incremental adaptive sampling, one after the other in one call.

:func:`incremental_rounds` runs the loop of
:func:`medialaxis.planar.boundary.adaptive.sample_and_triangulate` (insert the new
samples, :func:`~medialaxis.planar.boundary._refine_kernels.insert_round`; split the
pieces, :func:`~medialaxis.planar.boundary._refine_kernels.refine_round`; grow the
arrays) with the same kernels in the same order, and comes back to Python
only for what it cannot answer: centroids the compiled inside test leaves
to GEOS, a jitter table too short, an insertion that rounding made
inconsistent, or after each round once the sample holds more than
``one_round_above`` vertices (a large shape's progress bar and Ctrl-C).
On the OpenStreetMap lakes the Python between the rounds was a tenth of
the time per lake.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit
from medialaxis.planar._delaunay_kernels import corner_square, insertion_order
from medialaxis.planar._kernels import OVER_SPLIT
from medialaxis.planar.boundary._refine_kernels import CORNERS, insert_round, refine_round

__all__ = ["DONE", "ASK_GEOS", "MORE_JITTER", "FAILED", "ROUND", "first_state", "sample_box", "incremental_rounds",
           "grown"]

#: What :func:`incremental_rounds` returns for: the sample is final ...
DONE = 0
#: ... the slots ``unsure`` need GEOS's inside test (then resume with ``inserted``) ...
ASK_GEOS = 1
#: ... the jitter table is too short for the new samples (resume with ``inserted`` and a longer one) ...
MORE_JITTER = 2
#: ... rounding made an insertion inconsistent (the triangulation is unusable) ...
FAILED = 3
#: ... a round is done and the sample is large (resume).
ROUND = 4


@njit(cache=True, nogil=True)
def first_state(first, first_arc, first_ring, first_next, lo, extent, far_corners, shaken):  # type: ignore[no-untyped-def]
    """The state :func:`incremental_rounds` starts from, for the first sample (``n`` points, ``n`` >= 3).

    Returns ``(points, arc, ring, nxt, x, y, near, tv, tn, centre, radius,
    where, memo, batch, hint)``: the samples after the :data:`CORNERS` far
    corners, their jittered coordinates ``(p - lo) / extent + shaken``, the
    two triangles of the corners, room for ``2 n + 2`` triangles, and the
    first batch in its insertion order (BRIO).
    """
    n = len(first)
    points = np.zeros((CORNERS + n, 2))
    arc = np.zeros(CORNERS + n)
    ring = np.full(CORNERS + n, -1, np.int64)
    nxt = np.full(CORNERS + n, -1, np.int64)
    x, y = np.empty(CORNERS + n), np.empty(CORNERS + n)
    for i in range(CORNERS):
        x[i], y[i] = far_corners[i, 0], far_corners[i, 1]
    for i in range(n):
        points[CORNERS + i, 0], points[CORNERS + i, 1] = first[i, 0], first[i, 1]
        arc[CORNERS + i], ring[CORNERS + i], nxt[CORNERS + i] = first_arc[i], first_ring[i], first_next[i] + CORNERS
        x[CORNERS + i] = (first[i, 0] - lo[0]) / extent + shaken[i, 0]
        y[CORNERS + i] = (first[i, 1] - lo[1]) / extent + shaken[i, 1]
    slots = 2 * n + 2
    tv = np.empty((slots, 3), np.int64)
    tn = np.full((slots, 3), -1, np.int64)
    corner_square(tv, tn, 0)
    memo = np.full((slots, 4), -1, np.int64)  # each slot's corner test, kept while its triangle stays
    batch = insertion_order(x[CORNERS:], y[CORNERS:]) + CORNERS
    return (points, arc, ring, nxt, x, y, np.zeros(CORNERS + n, np.int64), tv, tn, np.empty((slots, 2)),
            np.empty(slots), np.zeros(slots, np.int8), memo, batch, np.full(n, -1, np.int64))


@njit(cache=True, nogil=True)
def sample_box(points):  # type: ignore[no-untyped-def]
    """``(lo, extent)``: ``points.min(0)`` and ``float((points.max(0) - lo).max())``, the same numbers (NumPy's
    reductions along the rows of an (n, 2) array took 17 us a lake)."""
    lo = np.empty(2)
    extent = -np.inf
    for k in range(2):
        low, high = np.inf, -np.inf
        for i in range(len(points)):
            low = min(low, points[i, k])
            high = max(high, points[i, k])
        lo[k] = low
        extent = max(extent, high - low)
    return lo, extent


@njit(cache=True, nogil=True, inline="always")
def grown(array, rows, keep, fill):  # type: ignore[no-untyped-def]
    """``array`` (2-D) with at least ``rows`` rows (twice as many when it grows), its first ``keep`` rows kept.

    The others hold ``fill``: only ``memo``'s are read (a slot not tested yet).
    """
    if len(array) >= rows:
        return array
    out = np.empty((max(rows, 2 * len(array)), array.shape[1]), array.dtype)
    for i in range(keep):  # element by element: a slice assignment compiles its shape error's string formatting
        for j in range(array.shape[1]):
            out[i, j] = array[i, j]
    out[keep:] = fill
    return out


@njit(cache=True, nogil=True, inline="always")
def _grown_rows(array, rows, keep):  # type: ignore[no-untyped-def]
    """:func:`grown` of a 1-D array, the new rows not filled."""
    if len(array) >= rows:
        return array
    out = np.empty(max(rows, 2 * len(array)), array.dtype)
    for i in range(keep):
        out[i] = array[i]
    return out


@njit(cache=True, nogil=True)
def incremental_rounds(round_, inserted, settled, max_rounds, one_round_above, count, x, y, tv, tn, batch, hint,  # type: ignore[no-untyped-def]
                       near, points, centre, radius, where, memo, arc, ring, nxt, sliver, segments, start, members,
                       y0, height, rings_s, rings_xy, rings_start, convex, touching, ring_length, lo, extent, shaken, tolerance,
                       min_length, ratio, settled_share, over_split=OVER_SPLIT):
    """The rounds from ``round_`` on (``inserted``: its samples are in already), until one of the statuses.

    Returns ``(status, round_, settled, count, x, y, tv, tn, batch, hint,
    near, points, centre, radius, where, memo, arc, ring, nxt, unsure, gx,
    gy)``: the state to resume from, and for :data:`ASK_GEOS` the slots and
    centroids to ask about. ``over_split``: see :data:`medialaxis.planar._kernels.OVER_SPLIT`.
    """
    no_slots = np.empty(0, np.int64)
    no_xy = np.empty(0)
    while True:
        if not inserted:
            count, ok, unsure, gx, gy = insert_round(x, y, tv, tn, count, batch, hint, near, points, centre, radius,
                                                     where, sliver, segments, start, members, y0, height)
            if not ok:
                status = FAILED
                break
            inserted = True
            if len(unsure):
                return (ASK_GEOS, round_, settled, count, x, y, tv, tn, batch, hint, near, points, centre, radius,
                        where, memo, arc, ring, nxt, unsure, gx, gy)
        if settled or round_ == max_rounds - 1:
            status = DONE
            break
        m, now_settled, points, arc, ring, nxt, x, y, near, batch, hint = refine_round(
            tv, count, where, centre, radius, memo, nxt, arc, ring, points, x, y, near, rings_s, rings_xy,
            rings_start, convex, touching, ring_length, lo, extent, shaken, tolerance, min_length, ratio, settled_share,
            over_split)
        if m < 0:
            status = MORE_JITTER
            break
        settled = now_settled
        if m == 0:
            status = DONE
            break
        slots = 2 * (len(x) - CORNERS) + 2
        tv, tn, memo = grown(tv, slots, count, -1), grown(tn, slots, count, -1), grown(memo, slots, count, -1)
        centre = grown(centre, slots, count, 0.0)
        radius, where = _grown_rows(radius, slots, count), _grown_rows(where, slots, count)
        round_ += 1
        inserted = False
        if len(x) > one_round_above:
            status = ROUND
            break
    return (status, round_, settled, count, x, y, tv, tn, batch, hint, near, points, centre, radius, where, memo, arc,
            ring, nxt, no_slots, no_xy, no_xy)
