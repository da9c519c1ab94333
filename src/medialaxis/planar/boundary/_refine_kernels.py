"""Compiled steps of the incremental adaptive sampling: new samples go into the triangulation already made.

Each round of :mod:`medialaxis.planar.boundary.adaptive` splits the boundary pieces
that are too long (:func:`split_linked`, the rule of
:func:`medialaxis.planar._kernels.split_count`), inserts only the new samples
into the Delaunay triangulation of the previous round (:func:`insert_batch`,
the Bowyer-Watson steps of :func:`medialaxis.planar._delaunay_kernels.insert_points`,
walking from a triangle at the split piece), and computes the circumcircle and the
inside test of the triangles made in that round only (:func:`fresh_triangles`).
A round thus costs what it adds, not what the sample holds: the triangles
that survive keep their circles and sides. The triangulation is the same
as one made from scratch of the same jittered points (the Delaunay
triangulation of points in general position is unique); the tests compare
both.

Vertices ``0 .. 3`` are the four far corners; sample ``i`` is vertex ``4 + i``.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit
from medialaxis.planar._delaunay_kernels import drop_corners, insert_points, insertion_order, scratch
from medialaxis.planar._inside_kernels import UNSURE, locate_points, triangle_centroid
from medialaxis.planar._kernels import OVER_SPLIT, circle_through, split_count
from medialaxis.planar.boundary._corner_kernels import corner_piece_state_memo, corner_twins

__all__ = ["CORNERS", "insert_batch", "fresh_triangles", "split_linked", "interp", "insert_round", "refine_round",
           "first_sample", "assembled"]

#: Vertices before the first sample: the far corners.
CORNERS = 4


@njit(cache=True, nogil=True, inline="always")
def insert_batch(x, y, tv, tn, count, order, hint, near):  # type: ignore[no-untyped-def]
    """Insert the vertices ``order`` into the triangulation, each walking from ``near[hint[m]]``.

    ``near[v]`` is a live triangle at vertex ``v``, kept so for every vertex
    of every new triangle (the walks from it are short: a step or two, where
    the slot a vertex got when inserted, long since reused, made 12 on
    average on the OSM lakes). Returns ``(count, fresh, ok)``: ``fresh[t]``
    marks the slots written by this batch; ``ok`` False where rounding made
    an insertion inconsistent (the triangulation is then unusable).
    """
    work, seen = scratch(len(tv), len(x))
    fresh = np.zeros(len(tv), np.bool_)
    count, ok = insert_points(x, y, tv, tn, count, order, hint, near, fresh, work, seen)
    return count, fresh, ok


@njit(cache=True, nogil=True, error_model="numpy")
def fresh_triangles(points, tv, count, fresh, centre, radius, where, sliver, segments, start, members, y0, height):  # type: ignore[no-untyped-def]
    """Circumcircle and inside test (:func:`triangle_centroid`, :func:`locate_points`) of the ``fresh`` slots.

    ``points`` are the unjittered vertices (rows of the corners unused);
    triangles at a corner are outside. Returns the slots whose answer is
    ``UNSURE`` and their centroids (the caller asks GEOS). The centroids are
    located in one call: per triangle, a compiled call with array arguments
    costs two atomic reference counts per array.
    """
    slot = np.empty(count, np.int64)
    gx = np.empty(count)
    gy = np.empty(count)
    n_proper = 0
    for t in range(count):
        if not fresh[t]:
            continue
        a, b, c = tv[t, 0], tv[t, 1], tv[t, 2]
        if min(a, b, c) < CORNERS:
            where[t] = 0
            radius[t] = np.inf
            continue
        ax, ay, bx, by, cx, cy = points[a, 0], points[a, 1], points[b, 0], points[b, 1], points[c, 0], points[c, 1]
        centre[t, 0], centre[t, 1], radius[t] = circle_through(ax, ay, bx, by, cx, cy)
        proper, x, y = triangle_centroid(ax, ay, bx, by, cx, cy, sliver)
        if not proper:
            where[t] = 0
            continue
        slot[n_proper], gx[n_proper], gy[n_proper] = t, x, y
        n_proper += 1
    located = locate_points(gx[:n_proper], gy[:n_proper], segments, start, members, y0, height)
    n_unsure = 0
    for j in range(n_proper):  # in slot order, as the slots come
        where[slot[j]] = located[j]
        if located[j] == UNSURE:
            slot[n_unsure], gx[n_unsure], gy[n_unsure] = slot[j], gx[j], gy[j]
            n_unsure += 1
    return slot[:n_unsure], gx[:n_unsure], gy[:n_unsure]


@njit(cache=True, nogil=True, inline="always")
def split_linked(arc, nxt, ring, points, ring_length, piece_radius, conforming, n, tolerance, min_length, ratio,  # type: ignore[no-untyped-def]
                 over_split=OVER_SPLIT):
    """Split the pieces ``(i, nxt[i])`` of the vertices ``CORNERS .. n - 1`` that are too long.

    The same pieces and arc positions as :func:`medialaxis.planar._kernels.split_pieces`;
    the new samples get the vertices ``n, n + 1, ...`` in order of their
    piece. Returns ``(new_arc, new_ring, piece, nxt)``: the arc position and
    ring of each new sample, the vertex its piece starts at, and ``nxt`` over
    all ``n + len(new_arc)`` vertices.
    """
    count = np.zeros(n, np.int64)
    total = 0
    for i in range(CORNERS, n):
        count[i] = split_count(points, i, nxt[i], piece_radius[i], conforming[i], tolerance, min_length, ratio,
                               over_split)
        total += max(count[i] - 1, 0)
    new_arc = np.empty(total)
    new_ring = np.empty(total, np.int64)
    piece = np.empty(total, np.int64)
    out = np.full(n + total, -1, np.int64)
    for i in range(n):
        out[i] = nxt[i]
    m = 0
    for i in range(CORNERS, n):
        k = count[i]
        if k == 0:
            continue
        r = ring[i]
        length = ring_length[r]
        start = arc[i]
        stop = arc[nxt[i]]
        if stop <= start:
            stop = stop + length
        prev = i
        for j in range(1, k):
            new_arc[m] = (start + (stop - start) * j / k) % length  # fmod: both are positive
            new_ring[m] = r
            piece[m] = i
            out[prev] = n + m
            prev = n + m
            m += 1
        out[prev] = nxt[i]
    return new_arc, new_ring, piece, out


@njit(cache=True, nogil=True, inline="always")
def interp(x, xp, fp, j):  # type: ignore[no-untyped-def]
    """``(np.interp(x, xp, fp), j)`` as NumPy computes it; ``j`` the segment found (and the guess given)."""
    if x >= xp[-1]:
        return fp[-1], j
    if x < xp[0]:
        return fp[0], j
    if not (xp[j] <= x and x < xp[j + 1]):  # the last j with xp[j] <= x, by bisection
        lo, hi = 0, len(xp)
        while lo < hi:
            mid = (lo + hi) // 2
            if x >= xp[mid]:
                lo = mid + 1
            else:
                hi = mid
        j = lo - 1
    if xp[j] == x:
        return fp[j], j
    slope = (fp[j + 1] - fp[j]) / (xp[j + 1] - xp[j])
    out = slope * (x - xp[j]) + fp[j]
    if np.isnan(out):
        out = slope * (x - xp[j + 1]) + fp[j + 1]
        if np.isnan(out) and fp[j] == fp[j + 1]:
            out = fp[j]
    return out, j


@njit(cache=True, nogil=True, inline="always")
def insert_round(x, y, tv, tn, count, order, hint, near, points, centre, radius, where, sliver, segments, start,
                 members, y0, height):  # type: ignore[no-untyped-def]
    """:func:`insert_batch`, then :func:`fresh_triangles`: ``(count, ok, unsure, gx, gy)``."""
    count, fresh, ok = insert_batch(x, y, tv, tn, count, order, hint, near)
    if not ok:
        return count, False, np.empty(0, np.int64), np.empty(0), np.empty(0)
    unsure, gx, gy = fresh_triangles(points, tv, count, fresh, centre, radius, where, sliver, segments, start,
                                     members, y0, height)
    return count, True, unsure, gx, gy


@njit(cache=True, nogil=True, inline="always")
def refine_round(tv, count, where, centre, radius, memo, nxt, arc, ring, points, x, y, near, rings_s, rings_xy, rings_start,  # type: ignore[no-untyped-def]
                 convex, touching, ring_length, lo, extent, jitter, tolerance, min_length, ratio, settled_share,
                 over_split=OVER_SPLIT):
    """The pieces' state, their splits and the new samples of one round, over the ``n = len(nxt)`` vertices.

    ``rings_s`` and ``rings_xy`` hold each closed ring's cumulative arc
    length and vertices, ring ``r`` at ``rings_start[r]:rings_start[r + 1]``,
    ``convex`` flags its convex vertices and ``touching`` those at one point (the pieces' state is
    :func:`medialaxis.planar.boundary._corner_kernels.corner_piece_state`, with the
    triangles' circumcentres ``centre``; ``memo`` keeps the corner test of
    each slot from round to round, see
    :func:`~medialaxis.planar.boundary._corner_kernels.corner_piece_state_memo`).
    New samples are placed as :func:`medialaxis.planar.boundary.sampling.sample`
    places them and jittered as :func:`medialaxis.planar.delaunay.triangulate`
    does (``(p - lo) / extent + jitter[i]``). Returns ``(m, settled, points,
    arc, ring, nxt, x, y, near, order, hint)``: ``m`` new samples (0: none to
    split; -1: ``jitter`` holds too few rows, nothing done), the arrays
    extended by them, and their insertion order (BRIO) with the vertex of
    their piece. ``over_split``: see :data:`medialaxis.planar._kernels.OVER_SPLIT`.
    """
    n = len(nxt)
    conforming, piece_radius = corner_piece_state_memo(tv[:count], where[:count] == 1, radius[:count], centre[:count],
                                                       nxt, arc, ring, CORNERS, rings_s, rings_xy, rings_start, convex,
                                                       touching, tolerance, memo, over_split)
    new_arc, new_ring, piece, nxt_out = split_linked(arc, nxt, ring, points, ring_length, piece_radius, conforming,
                                                     n, tolerance, min_length, ratio, over_split)
    m = len(new_arc)
    settled = m < settled_share * (n - CORNERS)
    for i in range(CORNERS, n):
        settled = settled and conforming[i]
    empty = np.empty(0, np.int64)
    if m == 0 or n - CORNERS + m > len(jitter):
        return (m if m == 0 else -1), settled, points, arc, ring, nxt, x, y, near, empty, empty
    points_out = np.empty((n + m, 2))
    arc_out = np.empty(n + m)
    ring_out = np.empty(n + m, np.int64)
    x_out = np.empty(n + m)
    y_out = np.empty(n + m)
    near_out = np.zeros(n + m, np.int64)
    for i in range(n):  # element by element: a slice assignment compiles its shape error's string formatting
        points_out[i, 0], points_out[i, 1] = points[i, 0], points[i, 1]
        arc_out[i], ring_out[i], x_out[i], y_out[i], near_out[i] = arc[i], ring[i], x[i], y[i], near[i]
    for i in range(m):
        arc_out[n + i], ring_out[n + i] = new_arc[i], new_ring[i]
    for i in range(m):
        r = new_ring[i]
        s = rings_s[rings_start[r] : rings_start[r + 1]]
        j = 0
        for k in range(2):
            value, j = interp(new_arc[i], s, rings_xy[rings_start[r] : rings_start[r + 1], k], j)
            points_out[n + i, k] = value
        x_out[n + i] = (points_out[n + i, 0] - lo[0]) / extent + jitter[n - CORNERS + i, 0]
        y_out[n + i] = (points_out[n + i, 1] - lo[1]) / extent + jitter[n - CORNERS + i, 1]
    order = insertion_order(x_out[n:], y_out[n:])
    return m, settled, points_out, arc_out, ring_out, nxt_out, x_out, y_out, near_out, order + n, piece[order]


@njit(cache=True, nogil=True, inline="always")
def _unique(values):  # type: ignore[no-untyped-def]
    """``np.unique(values)`` of a float array, sorted by the stable sort :func:`assembled` compiles already
    (equal values are equal whichever sort orders them; NaNs are one, as in numba's ``np.unique``)."""
    b = values[np.argsort(values, kind="mergesort")]
    out = np.empty(len(b))
    m = 0
    for i in range(len(b)):
        if i == 0 or (b[i - 1] != b[i] and not (b[i - 1] != b[i - 1] and b[i] != b[i])):
            out[m] = b[i]
            m += 1
    return out[:m]


@njit(cache=True, nogil=True)
def first_sample(rings_xy, rings_s, rings_start, max_length, tolerance, min_length, ratio):  # type: ignore[no-untyped-def]
    """The first sample of the adaptive rounds, in one call: ``(points, arc, ring, nxt)`` over all rings.

    What :func:`medialaxis.planar.boundary.sampling.sample` makes of the arcs of
    :func:`medialaxis.planar.boundary.sampling.initial_arcs` (every vertex, edges cut
    to ``max_length``) with the twins of
    :func:`medialaxis.planar.boundary.corners.mirrored_corner_arcs`, the same numbers
    (the tests compare both): ``rings_s`` and ``rings_xy`` hold each closed
    ring's cumulative arc length and vertices, ring ``r`` at
    ``rings_start[r]:rings_start[r + 1]``.
    """
    n_rings = len(rings_start) - 1
    arcs = []
    total = 0
    for r in range(n_rings):
        s = rings_s[rings_start[r] : rings_start[r + 1]]
        count = np.empty(len(s) - 1, np.int64)
        for j in range(len(s) - 1):
            count[j] = np.int64(max(1.0, np.ceil((s[j + 1] - s[j]) / max_length)))
        size = 0
        for j in range(len(count)):  # count.sum(): its axis check compiles string formatting
            size += count[j]
        a = np.empty(size)
        m = 0
        for j in range(len(s) - 1):
            seg = s[j + 1] - s[j]
            for i in range(count[j]):
                a[m] = s[j] + i / count[j] * seg
                m += 1
        twins = corner_twins(a, s, rings_xy[rings_start[r] : rings_start[r + 1]], tolerance, min_length, ratio)
        if len(twins):
            a = _unique(np.concatenate((a, twins)))
        arcs.append(a)
        total += len(a)
    points = np.empty((total, 2))
    arc = np.empty(total)
    ring = np.empty(total, np.int64)
    nxt = np.empty(total, np.int64)
    n0 = 0
    for r in range(n_rings):
        a = arcs[r]
        s = rings_s[rings_start[r] : rings_start[r + 1]]
        for k in range(2):
            fp = rings_xy[rings_start[r] : rings_start[r + 1], k]
            j = 0
            for i in range(len(a)):
                points[n0 + i, k], j = interp(a[i], s, fp, j)
        for i in range(len(a)):
            arc[n0 + i] = a[i]
            ring[n0 + i] = r
            nxt[n0 + i] = n0 + (i + 1) % len(a)
        n0 += len(a)
    return points, arc, ring, nxt


@njit(cache=True, nogil=True)
def assembled(points, arc, ring, n_rings, tv, tn, count, centre, radius, where):  # type: ignore[no-untyped-def]
    """The samples ``points``, ``arc``, ``ring`` (vertices ``CORNERS ..``) in ring and arc order, and their triangulation.

    Returns ``(points, ring, arc, nxt, simplices, neighbors, centres, radii,
    inside)``: the samples sorted as ``np.lexsort((arc, ring))`` sorts them,
    each one's follower on its ring, and the triangles without a far corner,
    renumbered (:func:`medialaxis.planar._delaunay_kernels.drop_corners`),
    with their circles and whether they are inside.
    """
    n = len(arc)
    by_arc = np.argsort(arc, kind="mergesort")  # stable; then a stable counting sort by ring: lexsort's order
    size = np.zeros(n_rings, np.int64)
    for i in range(n):
        size[ring[i]] += 1
    first = np.zeros(n_rings + 1, np.int64)
    for r in range(n_rings):
        first[r + 1] = first[r] + size[r]
    fill = first[:-1].copy()
    order = np.empty(n, np.int64)
    for i in by_arc:
        order[fill[ring[i]]] = i
        fill[ring[i]] += 1
    rank = np.empty(n, np.int64)
    points_out = np.empty((n, 2))
    ring_out = np.empty(n, np.int64)
    arc_out = np.empty(n)
    nxt = np.empty(n, np.int64)
    for m in range(n):
        i = order[m]
        rank[i] = m
        points_out[m, 0], points_out[m, 1] = points[i, 0], points[i, 1]
        ring_out[m] = ring[i]
        arc_out[m] = arc[i]
        nxt[m] = m + 1 if m + 1 < first[ring[i] + 1] else first[ring[i]]
    simplices, neighbors, row = drop_corners(tv, tn, count, CORNERS, CORNERS + n)
    m = len(simplices)
    centres = np.empty((m, 2))
    radii = np.empty(m)
    inside = np.empty(m, np.bool_)
    for t in range(count):
        j = row[t]
        if j < 0:
            continue
        for k in range(3):
            simplices[j, k] = rank[simplices[j, k]]
        centres[j, 0], centres[j, 1] = centre[t, 0], centre[t, 1]
        radii[j] = radius[t]
        inside[j] = where[t] == 1
    return points_out, ring_out, arc_out, nxt, simplices, neighbors, centres, radii, inside
