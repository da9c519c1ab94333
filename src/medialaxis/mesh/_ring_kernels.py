"""Compiled helpers over the rings of Delaunay edges (Voronoi facets as lists of tetrahedra).

A ring is ``ring_tets[ring_ptr[k]:ring_ptr[k + 1]]``: the tetrahedra around
one Delaunay edge in cyclic order, each sharing a triangle with the next
(the last with the first). These kernels replace NumPy passes over every
ring entry (about twelve million on a 221k-point sample), which cost more in
temporary arrays, sorts and searches than the walk that built the rings.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit, prange

__all__ = ["ring_side_ids", "csr_transpose", "ring_rises", "ring_all", "edge_order", "gather_rings"]


@njit(cache=True, nogil=True, parallel=True)
def ring_side_ids(ring_ptr, ring_tets, neighbors):  # type: ignore[no-untyped-def]
    """The triangle between each ring entry and the next, as ``4 * lo + k``.

    ``lo`` is the lower of the two tetrahedra and ``k`` the face of ``lo``
    across which the other lies (``neighbors[lo, k]``), so the same triangle
    gets the same id from every ring through it; -1 if the two are not
    neighbours (rings of one or two tetrahedra).
    """
    out = np.empty(ring_tets.shape[0], np.int64)
    for r in prange(ring_ptr.shape[0] - 1):
        start, stop = ring_ptr[r], ring_ptr[r + 1]
        for q in range(start, stop):
            a = ring_tets[q]
            b = ring_tets[q + 1] if q + 1 < stop else ring_tets[start]
            lo, hi = min(a, b), max(a, b)
            out[q] = -1
            for k in range(4):
                if neighbors[lo, k] == hi:
                    out[q] = 4 * lo + k
                    break
    return out


@njit(cache=True, nogil=True)
def csr_transpose(ptr, idx, n_cols):  # type: ignore[no-untyped-def]
    """Transpose of the incidence ``row -> idx[ptr[row]:ptr[row + 1]]``: rows of each column, ascending."""
    tptr = np.zeros(n_cols + 1, np.int64)
    for q in range(idx.shape[0]):
        tptr[idx[q] + 1] += 1
    for c in range(n_cols):
        tptr[c + 1] += tptr[c]
    fill = tptr[:-1].copy()
    rows = np.empty(idx.shape[0], np.int64)
    for r in range(ptr.shape[0] - 1):
        for q in range(ptr[r], ptr[r + 1]):
            c = idx[q]
            rows[fill[c]] = r
            fill[c] += 1
    return tptr, rows


@njit(cache=True, nogil=True, parallel=True)
def ring_rises(ring_ptr, ring_tets, flag):  # type: ignore[no-untyped-def]
    """For each ring, how many times an unflagged tetrahedron is followed by a flagged one (cyclically)."""
    n = ring_ptr.shape[0] - 1
    rises = np.zeros(n, np.int64)
    for r in prange(n):
        start, stop = ring_ptr[r], ring_ptr[r + 1]
        count = 0
        for q in range(start, stop):
            nxt = ring_tets[q + 1] if q + 1 < stop else ring_tets[start]
            if not flag[ring_tets[q]] and flag[nxt]:
                count += 1
        rises[r] = count
    return rises


@njit(cache=True, nogil=True, parallel=True)
def ring_all(ring_ptr, ring_tets, flag):  # type: ignore[no-untyped-def]
    """For each ring: does it hold a tetrahedron, and are all its tetrahedra flagged."""
    n = ring_ptr.shape[0] - 1
    out = np.zeros(n, np.bool_)
    for r in prange(n):
        if ring_ptr[r + 1] > ring_ptr[r]:
            out[r] = True
            for q in range(ring_ptr[r], ring_ptr[r + 1]):
                if not flag[ring_tets[q]]:
                    out[r] = False
                    break
    return out


@njit(cache=True, nogil=True)
def edge_order(edge_ij, n_points):  # type: ignore[no-untyped-def]
    """Order of the edges by ``(i, j)``: a counting sort on ``i``, then insertion sort within each ``i``."""
    n = edge_ij.shape[0]
    ptr = np.zeros(n_points + 1, np.int64)
    for e in range(n):
        ptr[edge_ij[e, 0] + 1] += 1
    for p in range(n_points):
        ptr[p + 1] += ptr[p]
    fill = ptr[:-1].copy()
    order = np.empty(n, np.int64)
    for e in range(n):
        i = edge_ij[e, 0]
        order[fill[i]] = e
        fill[i] += 1
    for p in range(n_points):
        for q in range(ptr[p] + 1, ptr[p + 1]):
            e = order[q]
            j = edge_ij[e, 1]
            s = q
            while s > ptr[p] and edge_ij[order[s - 1], 1] > j:
                order[s] = order[s - 1]
                s -= 1
            order[s] = e
    return order


@njit(cache=True, nogil=True, parallel=True)
def gather_rings(ring_ptr, ring_tets, rows):  # type: ignore[no-untyped-def]
    """Rings ``rows`` (in that order) as a new ``(ptr, tets)`` pair."""
    n = rows.shape[0]
    ptr = np.zeros(n + 1, np.int64)
    for k in range(n):
        ptr[k + 1] = ptr[k] + ring_ptr[rows[k] + 1] - ring_ptr[rows[k]]
    out = np.empty(ptr[n], np.int64)
    for k in prange(n):
        src = ring_ptr[rows[k]]
        for q in range(ptr[k + 1] - ptr[k]):
            out[ptr[k] + q] = ring_tets[src + q]
    return ptr, out
