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
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit

__all__ = ["sample_grid", "nearest_in_grid", "piece_distance", "boundary_distance_kernel", "grid_distance"]


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


@njit(cache=True, nogil=True)
def grid_distance(query, points, nxt, prv, k, x0, y0, cell, g, start, members):  # type: ignore[no-untyped-def]
    """:func:`boundary_distance_kernel` in the grid of :func:`sample_grid` made already."""
    near, sure = nearest_in_grid(query, points, k, x0, y0, cell, g, start, members)
    out = np.empty(len(query))
    for q in range(len(query)):
        qx, qy = query[q, 0], query[q, 1]
        best = np.inf
        if sure[q]:  # each piece at the k samples once; the root of the least square (sqrt is monotone, exact)
            least = np.inf
            for m in range(k):
                j = near[q, m]
                least = min(least, _squared_piece_distance(points, nxt, j, qx, qy))
                shared = False
                for other in range(k):
                    shared = shared or near[q, other] == prv[j]
                if not shared:
                    least = min(least, _squared_piece_distance(points, nxt, prv[j], qx, qy))
            out[q] = np.sqrt(least)
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
