"""Compiled 2D Delaunay triangulation of boundary samples (Bowyer-Watson), a fast path before Qhull.

:func:`delaunay_2d` inserts the points one after the other, in the order
given (boundary samples follow their rings, so each point lies next to the
last one and the walk that locates it is a step or two), into a
triangulation of four far corners. Each insertion removes the triangles
whose circumcircle holds the point (the cavity, grown from the triangle
that holds it) and joins the point to the cavity's boundary.

The predicates are evaluated in floating point. The caller jitters the
points (:func:`medialaxis.planar.delaunay.triangulate`), so exact
degeneracies do not occur; where rounding still makes the decisions
inconsistent (a new triangle that is not counter-clockwise, a cavity
boundary that is not one loop, a walk that does not end) the kernel gives
up and returns ``None`` from Python's side, and the caller takes SciPy's Qhull.
The reference is Qhull itself: the tests compare the triangles of both.

References
----------
.. [1] A. Bowyer, "Computing Dirichlet tessellations", The Computer Journal 24(2):162-166, 1981.
       doi:10.1093/comjnl/24.2.162
.. [2] D. F. Watson, "Computing the n-dimensional Delaunay tessellation with application to
       Voronoi polytopes", The Computer Journal 24(2):167-172, 1981. doi:10.1093/comjnl/24.2.167
.. [3] N. Amenta, S. Choi, G. Rote, "Incremental constructions con BRIO", Proc. 19th Symposium
       on Computational Geometry, 211-219, 2003. doi:10.1145/777792.777824
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit

__all__ = ["delaunay_2d", "insertion_order", "insert_points", "scratch", "corner_square", "drop_corners"]

#: Steps of the visibility walk before the kernel gives up.
MAX_WALK = 1 << 20
#: The scratch rows of :func:`insert_points`, indexed in place (a row view per
#: insertion costs two atomic reference counts: a fifth of the sampling's time).
STAMP, CAVITY, FREE, BND_A, BND_B, BND_OUT, NEW_TRI, BY_START, BY_END = range(9)


@njit(cache=True, nogil=True, inline="always")
def _orient(x, y, a, b, c):  # type: ignore[no-untyped-def]
    """Twice the signed area of ``abc`` (> 0 counter-clockwise)."""
    return (x[b] - x[a]) * (y[c] - y[a]) - (y[b] - y[a]) * (x[c] - x[a])


@njit(cache=True, nogil=True, inline="always")
def _in_circle(x, y, a, b, c, p):  # type: ignore[no-untyped-def]
    """> 0 when ``p`` lies inside the circumcircle of the counter-clockwise ``abc``."""
    adx, ady = x[a] - x[p], y[a] - y[p]
    bdx, bdy = x[b] - x[p], y[b] - y[p]
    cdx, cdy = x[c] - x[p], y[c] - y[p]
    return ((adx * adx + ady * ady) * (bdx * cdy - cdx * bdy)
            + (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy)
            + (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady))


@njit(cache=True, nogil=True, inline="always")
def _hilbert_key(x, y, bits):  # type: ignore[no-untyped-def]
    """Position of the point ``(x, y)`` of ``[0, 1]^2`` along a Hilbert curve on a ``2**bits`` grid."""
    side = (1 << bits) - 1
    px = min(max(int(x * side), 0), side)
    py = min(max(int(y * side), 0), side)
    d = 0
    s = 1 << (bits - 1)
    while s > 0:
        rx = 1 if px & s else 0
        ry = 1 if py & s else 0
        d += s * s * ((3 * rx) ^ ry)
        if ry == 0:  # the quadrant turned
            if rx == 1:
                px = side - px
                py = side - py
            px, py = py, px
        s >>= 1
    return d


@njit(cache=True, nogil=True, inline="always")
def _stable_sort_by_key(values, key, lo, hi):  # type: ignore[no-untyped-def]
    """Sort ``values[lo:hi]`` by ``key[lo:hi]`` (both reordered), ties in their order: a bottom-up merge sort."""
    n = hi - lo
    buf = np.empty((2, 2, max(n, 1)), np.int64)  # [buffer][values, keys][i]
    for i in range(n):
        buf[0, 0, i] = values[lo + i]
        buf[0, 1, i] = key[lo + i]
    src = 0
    width = 1
    while width < n:
        dst = 1 - src
        for left in range(0, n, 2 * width):
            mid, right = min(left + width, n), min(left + 2 * width, n)
            i, j = left, mid
            for m in range(left, right):
                if i < mid and (j >= right or buf[src, 1, i] <= buf[src, 1, j]):
                    buf[dst, 0, m], buf[dst, 1, m] = buf[src, 0, i], buf[src, 1, i]
                    i += 1
                else:
                    buf[dst, 0, m], buf[dst, 1, m] = buf[src, 0, j], buf[src, 1, j]
                    j += 1
        src = dst
        width *= 2
    for i in range(n):
        values[lo + i] = buf[src, 0, i]
        key[lo + i] = buf[src, 1, i]


@njit(cache=True, nogil=True)
def insertion_order(x, y, seed=12345):  # type: ignore[no-untyped-def]
    """A biased randomised insertion order of the points of ``[0, 1]^2`` (BRIO).

    The points are shuffled (a fixed seed: the order is deterministic) and
    cut into rounds that double in size; each round follows a Hilbert curve.
    Inserting samples along their ring instead makes long thin triangles
    whose cavities grow with the sample. Amenta, Choi, Rote, "Incremental
    constructions con BRIO", Proc. SoCG 2003.
    """
    n = len(x)
    order = np.arange(n)
    state = np.uint64(seed)
    for i in range(n - 1, 0, -1):  # Fisher-Yates with a 64-bit LCG
        state = state * np.uint64(6364136223846793005) + np.uint64(1442695040888963407)
        j = int((state >> np.uint64(33)) % np.uint64(i + 1))
        order[i], order[j] = order[j], order[i]
    key = np.empty(n, np.int64)
    for i in range(n):
        key[i] = _hilbert_key(x[order[i]], y[order[i]], 16)
    lo = 0
    size = 16
    while lo < n:
        hi = min(n, lo + size) if n - lo - size > size // 2 else n
        _stable_sort_by_key(order, key, lo, hi)  # np.argsort(kind="mergesort") compiles 2 s slower
        lo = hi
        size *= 2
    return order


@njit(cache=True, nogil=True)
def insert_points(x, y, tv, tn, count, order, hint, near, fresh, work, seen):  # type: ignore[no-untyped-def]
    """Insert the points ``order`` into the triangulation ``tv``/``tn`` (``count`` live slots) by Bowyer-Watson.

    Point ``order[m]`` walks from triangle ``near[hint[m]]``, or from the
    last new triangle where ``hint[m] < 0``. ``near[v]`` is kept at a live
    triangle of ``v`` for every vertex of every new triangle; ``fresh``
    marks the slots written. ``work`` holds scratch rows (:data:`STAMP` ..
    :data:`BY_END`) sized to the triangle capacity plus 3, or the point
    capacity for the last two; ``seen`` (point capacity) must hold no
    ``p + 1``. Returns ``(count, ok)``: ``ok`` False where rounding made an
    insertion inconsistent (the triangulation is then unusable). One call
    for all the points: a compiled call per point with array arguments costs
    two atomic reference counts per array.
    """
    last = 0
    for m in range(len(order)):
        p = order[m]
        t = near[hint[m]] if hint[m] >= 0 else last
        n_free = 0
        # locate: a visibility walk
        steps = 0
        while True:
            moved = False
            for k in range(3):
                a = tv[t, (k + 1) % 3]
                b = tv[t, (k + 2) % 3]
                if _orient(x, y, a, b, p) < 0.0:
                    u = tn[t, k]
                    if u < 0:
                        return count, False
                    t = u
                    moved = True
                    break
            if not moved:
                break
            steps += 1
            if steps > MAX_WALK:
                return count, False
        # the cavity, grown across edges from the triangle that holds p
        mark = p + 1
        work[STAMP, t] = mark
        work[CAVITY, 0] = t
        n_cav = 1
        n_bnd = 0
        head = 0
        while head < n_cav:
            t = work[CAVITY, head]
            head += 1
            for k in range(3):
                u = tn[t, k]
                if u >= 0 and work[STAMP, u] == mark:
                    continue
                inside = False
                if u >= 0 and work[STAMP, u] != -mark:
                    if _in_circle(x, y, tv[u, 0], tv[u, 1], tv[u, 2], p) > 0.0:
                        inside = True
                    else:
                        work[STAMP, u] = -mark
                if inside:
                    work[STAMP, u] = mark
                    work[CAVITY, n_cav] = u
                    n_cav += 1
                else:
                    work[BND_A, n_bnd] = tv[t, (k + 1) % 3]
                    work[BND_B, n_bnd] = tv[t, (k + 2) % 3]
                    work[BND_OUT, n_bnd] = u
                    n_bnd += 1
        if n_bnd != n_cav + 2:  # the boundary of a disc of c triangles has c + 2 edges
            return count, False
        # the new triangles (a, b, p), in the cavity's slots first
        for j in range(n_cav):
            work[FREE, n_free] = work[CAVITY, j]
            n_free += 1
        for j in range(n_bnd):
            a, b = work[BND_A, j], work[BND_B, j]
            if _orient(x, y, a, b, p) <= 0.0 or seen[a] == mark:
                return count, False
            seen[a] = mark
            if n_free > 0:
                n_free -= 1
                s = work[FREE, n_free]
            else:
                s = count
                count += 1
            tv[s, 0], tv[s, 1], tv[s, 2] = a, b, p
            tn[s, 2] = work[BND_OUT, j]
            work[STAMP, s] = 0
            u = work[BND_OUT, j]
            if u >= 0:
                for k in range(3):
                    if tv[u, (k + 1) % 3] == b and tv[u, (k + 2) % 3] == a:
                        tn[u, k] = s
            work[BY_START, a] = s
            work[BY_END, b] = s
            work[NEW_TRI, j] = s
        for j in range(n_bnd):
            s = work[NEW_TRI, j]
            a, b = tv[s, 0], tv[s, 1]
            if seen[b] != mark:  # the boundary is not one closed loop
                return count, False
            tn[s, 0] = work[BY_START, b]
            tn[s, 1] = work[BY_END, a]
        for j in range(n_bnd):
            s = work[NEW_TRI, j]
            fresh[s] = True
            near[tv[s, 0]] = s  # the cavity's vertices lost their triangles: each new one is at its two
            near[tv[s, 1]] = s
        last = work[NEW_TRI, 0]
        near[p] = last
    return count, True


@njit(cache=True, nogil=True)
def scratch(tri_capacity, point_capacity):  # type: ignore[no-untyped-def]
    """The scratch rows of :func:`insert_points` and a zeroed ``seen``."""
    work = np.empty((9, max(tri_capacity + 3, point_capacity)), np.int64)
    work[0, :] = 0
    return work, np.zeros(point_capacity, np.int64)


@njit(cache=True, nogil=True)
def corner_square(tv, tn, c0):  # type: ignore[no-untyped-def]
    """The two triangles of the four counter-clockwise corners ``c0 .. c0 + 3`` in slots 0 and 1."""
    tv[0, 0], tv[0, 1], tv[0, 2] = c0, c0 + 1, c0 + 2
    tv[1, 0], tv[1, 1], tv[1, 2] = c0, c0 + 2, c0 + 3
    tn[0, 1] = 1  # edge c2-c0
    tn[1, 2] = 0


@njit(cache=True, nogil=True)
def _triangulate(x, y):  # type: ignore[no-untyped-def]
    """Triangles and neighbours of ``n`` points followed by four counter-clockwise corners around them.

    Returns ``(vertices, neighbours, count, ok)``: the first ``count`` rows
    hold the triangulation (every slot alive), ``neighbours[t, k]`` is the
    triangle across the edge opposite vertex ``k`` (-1 on the outer square).
    """
    n = len(x) - 4
    cap = 2 * n + 2
    tv = np.empty((cap, 3), np.int64)
    tn = np.full((cap, 3), -1, np.int64)
    corner_square(tv, tn, n)
    count = 2
    work, seen = scratch(cap, n + 4)
    order = insertion_order(x[:n], y[:n])
    hint = np.full(n, -1, np.int64)  # each walk from the triangle made last
    count, ok = insert_points(x, y, tv, tn, count, order, hint, np.zeros(n + 4, np.int64), np.zeros(cap, np.bool_),
                              work, seen)
    if not ok:
        return tv, tn, 0, False
    return tv, tn, count, True


@njit(cache=True, nogil=True)
def drop_corners(tv, tn, count, lo, hi):  # type: ignore[no-untyped-def]
    """The triangles of the real points ``lo .. hi - 1`` (no corner), renumbered from 0, with their neighbours."""
    new_index = np.full(count, -1, np.int64)
    m = 0
    for t in range(count):
        if min(tv[t, 0], tv[t, 1], tv[t, 2]) >= lo and max(tv[t, 0], tv[t, 1], tv[t, 2]) < hi:
            new_index[t] = m
            m += 1
    simplices = np.empty((m, 3), np.int64)
    neighbors = np.empty((m, 3), np.int64)
    for t in range(count):
        j = new_index[t]
        if j < 0:
            continue
        for k in range(3):
            simplices[j, k] = tv[t, k] - lo
            u = tn[t, k]
            neighbors[j, k] = new_index[u] if u >= 0 else -1
    return simplices, neighbors, new_index


def delaunay_2d(work: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """Delaunay triangles of ``work`` (N, 2) and four far corners, without the triangles at the corners.

    Parameters
    ----------
    work : (N, 2) float ndarray
        Points inside the unit square (jittered), followed by four
        counter-clockwise corners far outside it.

    Returns
    -------
    simplices : (T, 3) int64 ndarray
        Counter-clockwise triangles of the first ``N - 4`` points.
    neighbors : (T, 3) int64 ndarray
        ``neighbors[t, k]`` shares the edge opposite vertex ``k``; -1 where
        that triangle touched a corner.

    ``None`` when rounding made the insertion inconsistent (the caller then
    takes Qhull).
    """
    x = np.ascontiguousarray(work[:, 0], dtype=np.float64)
    y = np.ascontiguousarray(work[:, 1], dtype=np.float64)
    tv, tn, count, ok = _triangulate(x, y)
    if not ok:
        return None
    simplices, neighbors, _ = drop_corners(tv, tn, count, 0, len(work) - 4)
    return simplices, neighbors
