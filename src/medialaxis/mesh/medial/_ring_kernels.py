"""Compiled helpers over the rings of Delaunay edges (Voronoi facets as lists of tetrahedra).

A ring is ``ring_tets[ring_ptr[k]:ring_ptr[k + 1]]``: the tetrahedra around
one Delaunay edge in cyclic order, each sharing a triangle with the next
(the last with the first); :func:`all_edge_rings` walks them. The other
kernels replace NumPy passes over every ring entry (about twelve million on
a 221k-point sample), which cost more in temporary arrays, sorts and
searches than the walk that built the rings.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit, prange

__all__ = [
    "all_edge_rings",
    "ring_side_ids",
    "ring_side_slots",
    "csr_transpose",
    "ring_all",
    "ring_max",
    "edge_order",
    "gather_rings",
    "flagged_sides",
    "odd_sides",
]


@njit(cache=True, nogil=True, inline="always")
def _side_after(neighbors, ring_tets, start, stop, q):  # type: ignore[no-untyped-def]
    """The id ``4 * lo + k`` of the triangle between ring entry ``q`` and the next (see :func:`ring_side_ids`)."""
    a = ring_tets[q]
    b = ring_tets[q + 1] if q + 1 < stop else ring_tets[start]
    lo, hi = min(a, b), max(a, b)
    for k in range(4):
        if neighbors[lo, k] == hi:
            return 4 * lo + k
    return -1


@njit(cache=True, nogil=True, parallel=True)
def ring_side_ids(ring_ptr, ring_tets, neighbors):  # type: ignore[no-untyped-def]
    """The triangle between each ring entry and the next, as ``4 * lo + k``.

    ``lo`` is the lower of the two tetrahedra and ``k`` the face of ``lo``
    across which the other lies (``neighbors[lo, k]``), so the same triangle
    gets the same id from every ring through it; -1 if the two are not
    neighbours (rings of one or two tetrahedra). Int32: ``4 * t`` fits it for any tetrahedralisation
    that fits in memory (:func:`~medialaxis.mesh.medial.voronoi_diagram.edge_rings` checks).
    """
    out = np.empty(ring_tets.shape[0], np.int32)
    for r in prange(ring_ptr.shape[0] - 1):
        start, stop = ring_ptr[r], ring_ptr[r + 1]
        for q in range(start, stop):
            out[q] = _side_after(neighbors, ring_tets, start, stop, q)
    return out


@njit(cache=True, nogil=True, parallel=True)
def ring_side_slots(ring_ptr, ring_tets, neighbors, slot):  # type: ignore[no-untyped-def]
    """``slot[ring_side_ids(ring_ptr, ring_tets, neighbors)]`` in one pass, -1 where there is no triangle.

    The ids themselves (a ring-sized array) are never made: the medial
    complex needs them only for the few rings that survive its collapses.
    """
    out = np.empty(ring_tets.shape[0], slot.dtype)
    for r in prange(ring_ptr.shape[0] - 1):
        start, stop = ring_ptr[r], ring_ptr[r + 1]
        for q in range(start, stop):
            side = _side_after(neighbors, ring_tets, start, stop, q)
            out[q] = slot[side] if side >= 0 else -1
    return out


@njit(cache=True, nogil=True)
def csr_transpose(ptr, idx, n_cols):  # type: ignore[no-untyped-def]
    """Transpose of the incidence ``row -> idx[ptr[row]:ptr[row + 1]]``: rows of each column, ascending.

    The pointers and rows come in the dtype of ``idx`` (int32 ring entries give int32 ones: there are fewer
    rows than entries, and the entries number less than ``2**31``).
    """
    tptr = np.zeros(n_cols + 1, idx.dtype)
    for q in range(idx.shape[0]):
        tptr[idx[q] + 1] += 1
    for c in range(n_cols):
        tptr[c + 1] += tptr[c]
    fill = tptr[:-1].copy()
    rows = np.empty(idx.shape[0], idx.dtype)
    for r in range(ptr.shape[0] - 1):
        for q in range(ptr[r], ptr[r + 1]):
            c = idx[q]
            rows[fill[c]] = r
            fill[c] += 1
    return tptr, rows


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
    """Rings ``rows`` (in that order) as a new ``(ptr, tets)`` pair, the tetrahedra in the dtype given."""
    n = rows.shape[0]
    ptr = np.zeros(n + 1, np.int64)
    for k in range(n):
        ptr[k + 1] = ptr[k] + ring_ptr[rows[k] + 1] - ring_ptr[rows[k]]
    out = np.empty(ptr[n], ring_tets.dtype)
    for k in prange(n):
        src = ring_ptr[rows[k]]
        for q in range(ptr[k + 1] - ptr[k]):
            out[ptr[k] + q] = ring_tets[src + q]
    return ptr, out


@njit(cache=True, nogil=True, parallel=True)
def ring_max(ring_ptr, ring_tets, values):  # type: ignore[no-untyped-def]
    """Largest ``values`` of each ring's tetrahedra (``-inf`` for an empty ring)."""
    n = ring_ptr.shape[0] - 1
    out = np.full(n, -np.inf)
    for r in prange(n):
        for q in range(ring_ptr[r], ring_ptr[r + 1]):
            out[r] = max(out[r], values[ring_tets[q]])
    return out


@njit(cache=True, nogil=True, parallel=True)
def flagged_sides(neighbors, flag):  # type: ignore[no-untyped-def]
    """Triangles shared by two flagged tetrahedra, numbered by their id ``4 * lo + k`` (see :func:`ring_side_ids`).

    Returns
    -------
    slot : (4 t,) int32 ndarray
        Number of each triangle id, -1 where the triangle is not such a side.
    ends : (s, 2) int32 ndarray
        The two tetrahedra of each side, the lower first.
    """
    n = neighbors.shape[0]
    n_blocks = max(1, min(n, 256))
    count = np.zeros(n_blocks + 1, np.int64)
    for b in prange(n_blocks):
        c = 0
        for t in range(b * n // n_blocks, (b + 1) * n // n_blocks):
            if flag[t]:
                for k in range(4):
                    u = neighbors[t, k]
                    if u > t and flag[u]:
                        c += 1
        count[b + 1] = c
    for b in range(n_blocks):
        count[b + 1] += count[b]
    slot = np.empty(4 * n, np.int32)
    ends = np.empty((count[n_blocks], 2), np.int32)
    for b in prange(n_blocks):
        c = count[b]
        for t in range(b * n // n_blocks, (b + 1) * n // n_blocks):
            for k in range(4):
                u = neighbors[t, k]
                if flag[t] and u > t and flag[u]:
                    slot[4 * t + k] = c
                    ends[c, 0], ends[c, 1] = t, u
                    c += 1
                else:
                    slot[4 * t + k] = -1
    return slot, ends


@njit(cache=True, nogil=True)
def odd_sides(side_id, n_ids):  # type: ignore[no-untyped-def]
    """Ids in ``[0, n_ids)`` met neither zero times nor twice in ``side_id``, ascending (-1 entries are no triangle)."""
    seen = np.zeros(n_ids, np.uint8)  # a triangle lies on three Delaunay edges: at most three rings
    for q in range(side_id.shape[0]):
        if side_id[q] >= 0:
            seen[side_id[q]] += 1
    n = 0
    for i in range(n_ids):
        if seen[i] != 0 and seen[i] != 2:
            n += 1
    out = np.empty(n, np.int64)
    n = 0
    for i in range(n_ids):
        if seen[i] != 0 and seen[i] != 2:
            out[n] = i
            n += 1
    return out


@njit(cache=True, nogil=True)
def _walk_ring(simplices, neighbors, t, i, j, lowest, out, pos):  # type: ignore[no-untyped-def]
    """Walk the tetrahedra around edge ``(i, j)`` from ``t`` across shared faces.

    Returns the ring's size, or 0 when the walk meets the hull (-1) or a
    tetrahedron below ``lowest`` (the ring then belongs to another start),
    or does not close within 4096 steps. With ``out``, the ring is written
    at ``out[pos:]``.
    """
    came = -1
    for c in range(4):
        v = simplices[t, c]
        if v != i and v != j:
            came = v
            break
    start = t
    size = 0
    while True:
        if out.shape[0] > 0:
            out[pos + size] = t
        size += 1
        nxt = -1
        other = -1
        for c in range(4):
            v = simplices[t, c]
            if v == came:
                nxt = neighbors[t, c]
            elif v != i and v != j:
                other = v
        if nxt < lowest or size > 4096:  # the hull (-1), or a ring already owned
            return 0
        if nxt == start:
            return size
        came = other
        t = nxt


@njit(cache=True, nogil=True, parallel=True)
def all_edge_rings(simplices, neighbors, points, tets, every, min_length):  # type: ignore[no-untyped-def]
    """The tetrahedra around every bounded Delaunay edge of ``tets``, in cyclic order.

    Each edge at least ``min_length`` long is walked from every tetrahedron
    of ``tets`` holding it, and kept by the one of lowest index in its ring
    (so each edge comes once, and only if its whole ring is in ``tets``
    when ``tets`` is sorted and holds every tetrahedron with such an edge).
    ``every``: all tetrahedra, ``tets`` unread (no index array of millions).
    Edges on the convex hull (whose Voronoi facets are unbounded) are left out.

    Returns
    -------
    edge_ij : (e, 2) int64 ndarray
        Sample indices of each edge, ``i < j``, ascending (the facets of a
        sample come together: output files compress better).
    ring_ptr : (e + 1,) int64 ndarray
    ring : (r,) int32 ndarray
        Tetrahedra of edge ``k`` at ``ring[ring_ptr[k]:ring_ptr[k + 1]]`` (int32: the ring entries, about
        six per tetrahedron, are the largest arrays of the medial complex).
    length : (e,) float64 ndarray
    """
    n = simplices.shape[0] if every else tets.shape[0]
    size = np.zeros(6 * n, np.int16)  # a ring closes within 4096 steps
    none = np.zeros(0, np.int64)
    for q in prange(n):
        t = np.int64(q) if every else tets[q]
        for a in range(3):
            for b in range(a + 1, 4):
                # the two tetrahedra next to t around the edge (across its faces through it) are in
                # t's own row: if one is lower or the hull, the walk would stop there (0.91 -> 0.69 s
                # on the uv ellipsoid's 2M tetrahedra, one thread; the same rings)
                c1 = 0 if a > 0 else (2 if b == 1 else 1)
                c2 = 6 - a - b - c1
                if neighbors[t, c1] < t or neighbors[t, c2] < t:
                    continue
                i, j = simplices[t, a], simplices[t, b]
                if min_length > 0.0:
                    d0 = points[i, 0] - points[j, 0]
                    d1 = points[i, 1] - points[j, 1]
                    d2 = points[i, 2] - points[j, 2]
                    if d0 * d0 + d1 * d1 + d2 * d2 < min_length * min_length:
                        continue
                size[6 * q + a * (7 - a) // 2 + b - a - 1] = _walk_ring(simplices, neighbors, t, i, j, t, none, 0)
    m = 0
    for q in range(size.shape[0]):
        m += size[q] > 0
    owned = np.empty(m, np.int32)  # slots 6 q + e (edge_rings keeps 6 t under 2**31); int32 at the peak below
    m = 0
    for q in range(size.shape[0]):
        if size[q] > 0:
            owned[m] = q
            m += 1
    edge_ij = np.empty((m, 2), np.int64)
    for k in prange(m):
        i, j = _slot_edge(simplices, tets, every, owned[k])
        edge_ij[k, 0], edge_ij[k, 1] = min(i, j), max(i, j)
    # written in the order of the edges, so no copy reorders them, walked in the order of the
    # tetrahedra, which keeps them in the cache (0.2 s of 1.07 on the uv ellipsoid, one thread)
    order = edge_order(edge_ij, points.shape[0])  # edge_ij dies here: the walks read each edge from its slot again
    rank = np.empty(m, np.int32)
    ring_ptr = np.zeros(m + 1, np.int64)
    for k in range(m):
        rank[order[k]] = k
        ring_ptr[k + 1] = ring_ptr[k] + size[owned[order[k]]]
    ring = np.empty(ring_ptr[-1], np.int32)
    sorted_ij = np.empty((m, 2), np.int64)
    length = np.empty(m, np.float64)
    for k in prange(m):
        t = np.int64(owned[k] // 6) if every else tets[owned[k] // 6]
        i, j = _slot_edge(simplices, tets, every, owned[k])
        i, j = min(i, j), max(i, j)
        _walk_ring(simplices, neighbors, t, i, j, t, ring, ring_ptr[rank[k]])
        sorted_ij[rank[k], 0], sorted_ij[rank[k], 1] = i, j
        d0, d1, d2 = points[i, 0] - points[j, 0], points[i, 1] - points[j, 1], points[i, 2] - points[j, 2]
        length[rank[k]] = np.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
    return sorted_ij, ring_ptr, ring, length


@njit(cache=True, nogil=True, inline="always")
def _slot_edge(simplices, tets, every, slot):  # type: ignore[no-untyped-def]
    """The edge ``(i, j)`` (unordered) of slot ``6 q + e`` of :func:`all_edge_rings`: edge ``e`` of tetrahedron ``tets[q]``."""
    t, e = np.int64(slot // 6) if every else tets[slot // 6], slot % 6
    a = 0 if e < 3 else (1 if e < 5 else 2)
    b = e - (a * (7 - a) // 2) + a + 1
    return simplices[t, a], simplices[t, b]
