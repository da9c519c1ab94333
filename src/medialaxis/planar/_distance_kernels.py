"""Compiled distance from points to the sampled boundary: a grid of the samples, ties with the k-th nearest taken.

:func:`sample_grid` buckets the samples into a square grid of about two per
cell; :func:`medialaxis.planar._kernels.nearest_samples` searches it for the
``k`` nearest. :func:`boundary_distance_kernel` is what
:func:`medialaxis.planar.axis.boundary_distance` computes: the distance to
the pieces at the ``k`` nearest samples, and where the ``k``-th and the next
distance agree to rounding (samples mirrored about a corner's bisector are
equidistant from its axis points), at every sample tied with the ``k``-th,
found in the grid instead of by the brute force of
:func:`medialaxis.planar._kernels.nearest_with_ties` (its reference in the tests).

:func:`delaunay_distance` is the same distance with the ``k`` nearest found
along the edges of the samples' Delaunay triangulation (:func:`site_neighbours`)
instead of in the grid: the ``i``-th nearest sample of any point is a Delaunay
neighbour of one of the ``i - 1`` nearer ones (shrink the disc about the point
through the ``i``-th towards it until it meets one of them: that disc is empty,
so the two are Delaunay neighbours), so a best-first walk from the nearest sample
meets them in order, and every sample within a distance forms a connected
set with the nearest. The grid visits every cell within the ``k``-th
distance, most of them empty where the point lies far from the boundary (the
middle of a lake); the walk reads a few dozen samples.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit

__all__ = ["sample_grid", "nearest_in_grid", "piece_distance", "boundary_distance_kernel", "grid_distance",
           "site_neighbours", "delaunay_distance"]


@njit(cache=True, nogil=True)
def sample_grid(points):  # type: ignore[no-untyped-def]
    """``(x0, y0, cell, g, start, members)``: the samples of cell ``ix * g + iy`` are ``members[start[c]:start[c + 1]]``."""
    n = len(points)
    x0, y0, x1, y1 = np.inf, np.inf, -np.inf, -np.inf
    for i in range(n):
        x0, x1 = min(x0, points[i, 0]), max(x1, points[i, 0])
        y0, y1 = min(y0, points[i, 1]), max(y1, points[i, 1])
    g = max(1, int(np.sqrt(n / 2.0)))
    cell = max(x1 - x0, y1 - y0, 1e-300) / g * (1.0 + 1e-9)
    start = np.zeros(g * g + 1, np.int64)
    home = np.empty(n, np.int64)
    for i in range(n):
        home[i] = min(int((points[i, 0] - x0) / cell), g - 1) * g + min(int((points[i, 1] - y0) / cell), g - 1)
        start[home[i] + 1] += 1
    for c in range(g * g):
        start[c + 1] += start[c]
    fill = start[:-1].copy()
    members = np.empty(n, np.int64)
    for i in range(n):
        members[fill[home[i]]] = i
        fill[home[i]] += 1
    return x0, y0, cell, g, start, members


@njit(cache=True, nogil=True, inline="always")
def _scan_cell(c, xs, ys, qx, qy, k, start, members, best_d, best_i, found):  # type: ignore[no-untyped-def]
    """Merge the samples of cell ``c`` (coordinates ``xs``, ``ys`` in cell order) into the sorted ``k + 1`` nearest so far; the new count found."""
    for m in range(start[c], start[c + 1]):
        d = (xs[m] - qx) ** 2 + (ys[m] - qy) ** 2
        if found == k + 1 and d >= best_d[k]:
            continue
        j = min(found, k)
        while j > 0 and best_d[j - 1] > d:
            best_d[j] = best_d[j - 1]
            best_i[j] = best_i[j - 1]
            j -= 1
        best_d[j] = d
        best_i[j] = members[m]
        found = min(found + 1, k + 1)
    return found


@njit(cache=True, nogil=True)
def nearest_in_grid(query, points, k, x0, y0, cell, g, start, members):  # type: ignore[no-untyped-def]
    """:func:`medialaxis.planar._kernels.nearest_samples` in the grid of :func:`sample_grid`, nearest first.

    The cells are visited ring by ring around the query's cell (only the
    ring's own cells, not the square it bounds) until no unseen sample can
    be nearer than the ``k + 1``-th found. ``sure`` is False where the
    ``k``-th and the next distance agree to rounding: which of the tied
    samples is listed then turns on the order of the visit.
    """
    xs, ys = np.empty(len(members)), np.empty(len(members))  # the samples in cell order: scans read memory in a row
    for m in range(len(members)):
        xs[m], ys[m] = points[members[m], 0], points[members[m], 1]
    near = np.empty((len(query), k), np.int64)
    sure = np.ones(len(query), np.bool_)
    best_d = np.empty(k + 1)
    best_i = np.empty(k + 1, np.int64)
    for q in range(len(query)):
        qx, qy = query[q, 0], query[q, 1]
        cx = min(max(int(np.floor((qx - x0) / cell)), 0), g - 1)
        cy = min(max(int(np.floor((qy - y0) / cell)), 0), g - 1)
        found = 0
        r = 0
        while True:
            lo_x, hi_x = max(cx - r, 0), min(cx + r, g - 1)
            if r == 0:
                found = _scan_cell(cx * g + cy, xs, ys, qx, qy, k, start, members, best_d, best_i, found)
            else:
                for iy in (cy - r, cy + r):  # the ring's bottom and top rows of cells, corners included
                    if 0 <= iy < g:
                        for ix in range(lo_x, hi_x + 1):
                            found = _scan_cell(ix * g + iy, xs, ys, qx, qy, k, start, members, best_d, best_i,
                                               found)
                for ix in (cx - r, cx + r):  # its left and right columns between them
                    if 0 <= ix < g:
                        for iy in range(max(cy - r + 1, 0), min(cy + r - 1, g - 1) + 1):
                            found = _scan_cell(ix * g + iy, xs, ys, qx, qy, k, start, members, best_d, best_i,
                                               found)
            covered = cx - r <= 0 and cy - r <= 0 and cx + r >= g - 1 and cy + r >= g - 1
            # any point not yet seen lies beyond the visited block of cells
            bound = min(qx - (x0 + (cx - r) * cell), x0 + (cx + r + 1) * cell - qx,
                        qy - (y0 + (cy - r) * cell), y0 + (cy + r + 1) * cell - qy)
            if covered or (found == k + 1 and bound > 0 and best_d[k] < bound * bound * (1.0 - 1e-9)):
                break
            r += 1
        for j in range(k):
            near[q, j] = best_i[j]
        sure[q] = best_d[k] - best_d[k - 1] > 1e-9 * best_d[k]
    return near, sure


@njit(cache=True, nogil=True, inline="always")
def piece_distance(points, nxt, prv, j, qx, qy):  # type: ignore[no-untyped-def]
    """Distance from ``(qx, qy)`` to the two pieces that meet at sample ``j``."""
    best = np.inf
    for begin in (j, prv[j]):
        ax, ay = points[begin, 0], points[begin, 1]
        bx, by = points[nxt[begin], 0] - ax, points[nxt[begin], 1] - ay
        px, py = qx - ax, qy - ay
        t = min(max((px * bx + py * by) / max(bx * bx + by * by, 1e-300), 0.0), 1.0)
        dx, dy = px - t * bx, py - t * by
        best = min(best, np.sqrt(dx * dx + dy * dy))
    return best


@njit(cache=True, nogil=True, inline="always")
def _squared_piece_distance(points, nxt, begin, qx, qy):  # type: ignore[no-untyped-def]
    """The square of the distance from ``(qx, qy)`` to the piece ``(begin, nxt[begin])``, as :func:`piece_distance`."""
    ax, ay = points[begin, 0], points[begin, 1]
    bx, by = points[nxt[begin], 0] - ax, points[nxt[begin], 1] - ay
    px, py = qx - ax, qy - ay
    t = min(max((px * bx + py * by) / max(bx * bx + by * by, 1e-300), 0.0), 1.0)
    dx, dy = px - t * bx, py - t * by
    return dx * dx + dy * dy


@njit(cache=True, nogil=True)
def boundary_distance_kernel(query, points, nxt, prv, k):  # type: ignore[no-untyped-def]
    """Distance from each query to the pieces at its ``k`` nearest samples (N > k) and at every one tied with the k-th."""
    x0, y0, cell, g, start, members = sample_grid(points)
    return grid_distance(query, points, nxt, prv, k, x0, y0, cell, g, start, members)


@njit(cache=True, nogil=True, inline="always")
def _sure_distance(near, k, points, nxt, prv, qx, qy):  # type: ignore[no-untyped-def]
    """Distance to the pieces at the ``k`` samples ``near``: each piece once, the root of the least square (sqrt
    is monotone, exact)."""
    least = np.inf
    for m in range(k):
        j = near[m]
        least = min(least, _squared_piece_distance(points, nxt, j, qx, qy))
        shared = False
        for other in range(k):
            shared = shared or near[other] == prv[j]
        if not shared:
            least = min(least, _squared_piece_distance(points, nxt, prv[j], qx, qy))
    return np.sqrt(least)


@njit(cache=True, nogil=True, inline="always")
def grid_distance(query, points, nxt, prv, k, x0, y0, cell, g, start, members):  # type: ignore[no-untyped-def]
    """:func:`boundary_distance_kernel` in the grid of :func:`sample_grid` made already."""
    near, sure = nearest_in_grid(query, points, k, x0, y0, cell, g, start, members)
    out = np.empty(len(query))
    for q in range(len(query)):
        qx, qy = query[q, 0], query[q, 1]
        best = np.inf
        if sure[q]:
            out[q] = _sure_distance(near[q], k, points, nxt, prv, qx, qy)
            continue
        far = near[q, k - 1]  # every sample within the k-th distance (to 2e-9), from the cells that reach it
        kth = ((points[far, 0] - qx) ** 2 + (points[far, 1] - qy) ** 2) * (1.0 + 2e-9)
        reach = np.sqrt(kth) * (1.0 + 1e-9)
        lo_x = min(max(int(np.floor((qx - reach - x0) / cell)), 0), g - 1)
        hi_x = min(max(int(np.floor((qx + reach - x0) / cell)), 0), g - 1)
        lo_y = min(max(int(np.floor((qy - reach - y0) / cell)), 0), g - 1)
        hi_y = min(max(int(np.floor((qy + reach - y0) / cell)), 0), g - 1)
        for ix in range(lo_x, hi_x + 1):
            for iy in range(lo_y, hi_y + 1):
                for m in range(start[ix * g + iy], start[ix * g + iy + 1]):
                    p = members[m]
                    if (points[p, 0] - qx) ** 2 + (points[p, 1] - qy) ** 2 <= kth:
                        best = min(best, piece_distance(points, nxt, prv, p, qx, qy))
        out[q] = best
    return out


@njit(cache=True, nogil=True)
def site_neighbours(n, simplices, neighbors):  # type: ignore[no-untyped-def]
    """``(indptr, nbrs)``: the Delaunay neighbours of sample ``i`` are ``nbrs[indptr[i]:indptr[i + 1]]``.

    ``neighbors[t, j]`` is the triangle across the edge opposite vertex ``j``
    (-1: none), so that each edge is listed once per direction.
    """
    degree = np.zeros(n + 1, np.int64)
    for t in range(len(simplices)):
        for j in range(3):
            u = neighbors[t, j]
            if u < 0 or u > t:
                degree[simplices[t, (j + 1) % 3] + 1] += 1
                degree[simplices[t, (j + 2) % 3] + 1] += 1
    for i in range(n):
        degree[i + 1] += degree[i]
    fill = degree[:-1].copy()
    nbrs = np.empty(degree[n], np.int64)
    for t in range(len(simplices)):
        for j in range(3):
            u = neighbors[t, j]
            if u < 0 or u > t:
                a, b = simplices[t, (j + 1) % 3], simplices[t, (j + 2) % 3]
                nbrs[fill[a]] = b
                fill[a] += 1
                nbrs[fill[b]] = a
                fill[b] += 1
    return degree, nbrs


@njit(cache=True, nogil=True)
def delaunay_distance(query, seed, points, nxt, prv, k, indptr, nbrs):  # type: ignore[no-untyped-def]
    """:func:`boundary_distance_kernel` with the nearest samples found along the Delaunay edges ``indptr``,
    ``nbrs`` (:func:`site_neighbours`) from the sample ``seed[q]`` of each query (any sample; one near it walks
    least). The same distances, bit for bit: the same samples (the ``k`` nearest, or every one within the
    ``k``-th distance where that and the next agree to rounding), the same arithmetic."""
    n = len(points)
    seen = np.full(n, -1, np.int64)
    heap_i = np.empty(n, np.int64)  # the walk's frontier: samples next to those taken, unsorted (each once)
    heap_d = np.empty(n)
    taken = np.empty(n, np.int64)
    taken_d = np.empty(n)
    out = np.empty(len(query))
    for q in range(len(query)):
        qx, qy = query[q, 0], query[q, 1]
        s = seed[q]
        ds = (points[s, 0] - qx) ** 2 + (points[s, 1] - qy) ** 2
        while True:  # down to the nearest sample: one Delaunay neighbour of any other is nearer
            step, dstep = s, ds
            for m in range(indptr[s], indptr[s + 1]):
                v = nbrs[m]
                d = (points[v, 0] - qx) ** 2 + (points[v, 1] - qy) ** 2
                nearer = d < dstep
                step = v if nearer else step
                dstep = d if nearer else dstep
            if step == s:
                break
            s, ds = step, dstep
        seen[s] = q
        heap_i[0], heap_d[0] = s, ds
        front, count, limit = 1, 0, np.inf
        while front:
            best, d = 0, heap_d[0]
            for m in range(1, front):  # the nearest of the frontier (no branch: the test is a coin toss)
                nearer = heap_d[m] < d
                best = m if nearer else best
                d = heap_d[m] if nearer else d
            v = heap_i[best]
            if count > k and d > limit:
                break  # every sample left is farther
            front -= 1
            heap_i[best], heap_d[best] = heap_i[front], heap_d[front]
            taken[count], taken_d[count] = v, d
            count += 1
            if count == k + 1:
                if taken_d[k] - taken_d[k - 1] > 1e-9 * taken_d[k]:
                    break  # the k nearest, surely
                limit = taken_d[k - 1] * (1.0 + 2e-9)  # a tie: every sample within the k-th distance
            for m in range(indptr[v], indptr[v + 1]):
                w = nbrs[m]
                if seen[w] == q:
                    continue
                seen[w] = q
                heap_i[front] = w
                heap_d[front] = (points[w, 0] - qx) ** 2 + (points[w, 1] - qy) ** 2
                front += 1
        if count == k + 1 and limit == np.inf:
            out[q] = _sure_distance(taken, k, points, nxt, prv, qx, qy)
            continue
        best_d = np.inf
        for m in range(count):
            if taken_d[m] <= limit or count <= k:
                best_d = min(best_d, piece_distance(points, nxt, prv, taken[m], qx, qy))
        out[q] = best_d
    return out

