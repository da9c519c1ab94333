"""Compiled kernel of the surface sampling: greedy thinning of a sample to a local spacing.

:func:`thin_to_spacing` keeps, in a given order, each point that no point
kept before lies nearer to than the smaller of their two radii (a
variable-radius Poisson-disk selection; dart throwing in a fixed order, as
in Cook, "Stochastic sampling in computer graphics", ACM Transactions on
Graphics 5(1), 1986, doi:10.1145/7529.8927). Every point dropped lies within
its radius of a kept one, so the sample's covering radius grows by at most
the largest radius. :func:`thin_to_spacing_reference` is the pure-Python
version the tests compare it with.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from medialaxis._jit import njit

__all__ = ["thin_to_spacing", "thin_to_spacing_reference"]

_MIX = -7046029254386353131  # odd 64-bit multiplier of the cell hash (as in _rows.first_of_rows)


@njit(cache=True, nogil=True)
def _cell_hash(x, y, z, mask):  # type: ignore[no-untyped-def]
    h = np.int64(0)
    for c in (x, y, z):
        h = (h ^ c) * _MIX
        h ^= h >> 29
    return h & mask


@njit(cache=True, nogil=True)
def thin_to_spacing(points, radius, order, group):  # type: ignore[no-untyped-def]
    """Boolean mask of the points kept by greedy thinning in ``order``.

    Parameters
    ----------
    points : (n, 3) float64 ndarray
    radius : (n,) float64 ndarray
        Positive; points ``i`` and ``j`` conflict when
        ``|p_i - p_j| < min(radius_i, radius_j)``.
    order : (n,) int64 ndarray
        A permutation of ``range(n)``: the first of two conflicting points in it is kept.
    group : (n,) int64 ndarray
        Points of the same non-negative group never conflict (the
        low-discrepancy points of one face are spread already), -1: none.
    """
    n = points.shape[0]
    keep = np.zeros(n, np.bool_)
    if n == 0:
        return keep
    cell = 2.0 * radius.max()  # a ball of a radius lies in the 2 x 2 x 2 cells nearest its centre
    hb = 4
    while (1 << hb) < 2 * n:
        hb += 1
    mask = (1 << hb) - 1
    table = np.full(1 << hb, -1, np.int64)  # slot -> cell index
    coords = np.empty((n, 3), np.int64)  # cell index -> its integer coordinates
    n_cells = 0
    point_cell = np.empty(n, np.int64)
    for i in range(n):
        x = np.int64(np.floor(points[i, 0] / cell))
        y = np.int64(np.floor(points[i, 1] / cell))
        z = np.int64(np.floor(points[i, 2] / cell))
        h = _cell_hash(x, y, z, mask)
        while True:
            c = table[h]
            if c < 0:
                table[h] = n_cells
                coords[n_cells, 0], coords[n_cells, 1], coords[n_cells, 2] = x, y, z
                point_cell[i] = n_cells
                n_cells += 1
                break
            if coords[c, 0] == x and coords[c, 1] == y and coords[c, 2] == z:
                point_cell[i] = c
                break
            h = (h + 1) & mask
    head = np.full(n_cells, -1, np.int64)  # kept points of each cell, as linked lists
    nxt = np.full(n, -1, np.int64)
    for i in order:
        own = point_cell[i]
        # the neighbour along each axis on the side of the cell the point is nearer to
        sx = 1 if points[i, 0] / cell - coords[own, 0] >= 0.5 else -1
        sy = 1 if points[i, 1] / cell - coords[own, 1] >= 0.5 else -1
        sz = 1 if points[i, 2] / cell - coords[own, 2] >= 0.5 else -1
        free = True
        for corner in range(8):
            x = coords[own, 0] + (sx if corner & 1 else 0)
            y = coords[own, 1] + (sy if corner & 2 else 0)
            z = coords[own, 2] + (sz if corner & 4 else 0)
            h = _cell_hash(x, y, z, mask)
            c = table[h]
            while c >= 0 and not (coords[c, 0] == x and coords[c, 1] == y and coords[c, 2] == z):
                h = (h + 1) & mask
                c = table[h]
            if c < 0:
                continue
            j = head[c]
            while j >= 0:
                if group[i] >= 0 and group[i] == group[j]:
                    j = nxt[j]
                    continue
                r = min(radius[i], radius[j])
                d0 = points[i, 0] - points[j, 0]
                d1 = points[i, 1] - points[j, 1]
                d2 = points[i, 2] - points[j, 2]
                if d0 * d0 + d1 * d1 + d2 * d2 < r * r:
                    free = False
                    break
                j = nxt[j]
            if not free:
                break
        if free:
            keep[i] = True
            nxt[i] = head[own]
            head[own] = i
    return keep


def thin_to_spacing_reference(points: np.ndarray, radius: np.ndarray, order: np.ndarray, group: np.ndarray) -> np.ndarray:
    """:func:`thin_to_spacing` in NumPy and a k-d tree (for tests)."""
    keep = np.zeros(len(points), bool)
    if len(points) == 0:
        return keep
    tree = cKDTree(points)
    for i in order:
        near = np.asarray(tree.query_ball_point(points[i], float(radius.max())), np.int64)
        near = near[keep[near] & ((group[near] != group[i]) | (group[i] < 0))]
        gap = np.linalg.norm(points[near] - points[i], axis=1)
        keep[i] = not np.any(gap < np.minimum(radius[near], radius[i]))
    return keep
