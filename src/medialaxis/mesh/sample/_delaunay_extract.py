"""The finished Delaunay tetrahedralisation's arrays (:mod:`medialaxis.mesh.sample.delaunay`), in one pass.

The finite tetrahedra of the insertion's slots, numbered along a Z-order
(Morton) curve of their centroids, with their neighbours renumbered to match
(-1 across the hull) and the convex hull's outward triangles. The keys are
computed from the slots, sorted (:func:`~medialaxis.mesh.sample._rows.radix_argsort`,
stable: tied keys in slot order) and each array is written once, in its
final order (an extraction in slot order then a renumbering wrote the 2M
tetrahedra of the uv ellipsoid twice: 0.31 s of CPU for 0.16 s).
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit, prange
from medialaxis.mesh.sample._predicates import _FACE_OUT


@njit(cache=True, nogil=True)
def _spread16(v):  # type: ignore[no-untyped-def]
    """Bits of a 16-bit integer moved to every third position."""
    v &= 0xFFFF
    v = (v | (v << 16)) & 0x0000FF0000FF
    v = (v | (v << 8)) & 0x00F00F00F00F
    v = (v | (v << 4)) & 0x0C30C30C30C3
    v = (v | (v << 2)) & 0x249249249249
    return v


@njit(cache=True, nogil=True)
def _morton(x, y, z):  # type: ignore[no-untyped-def]
    """Morton (Z-order) code of a point of ``[-0.5, 0.5]^3`` on a 2^16 grid per axis."""
    top = (1 << 16) - 1
    code = 0
    for axis, value in enumerate((x, y, z)):
        c = min(max(int((value + 0.5) * top), 0), top)
        code |= _spread16(c) << axis
    return code


@njit(cache=True, nogil=True, parallel=True)
def _finite_keys(tet, nt, inf, Q):  # type: ignore[no-untyped-def]
    """The slots of the finite tetrahedra (in slot order), each slot's rank among them (-1: none), their keys.

    The key is the Morton code of the centroid (``Q`` in ``[-0.5, 0.5]^3``).
    """
    rank = np.empty(nt, np.int64)
    for t in prange(nt):
        finite = tet[t, 0] >= 0 and tet[t, 0] != inf and tet[t, 1] != inf and tet[t, 2] != inf and tet[t, 3] != inf
        rank[t] = 1 if finite else 0
    count = 0
    for t in range(nt):  # running count: the rank of each finite tetrahedron, -1 for the others
        if rank[t]:
            rank[t] = count
            count += 1
        else:
            rank[t] = -1
    slot = np.empty(count, np.int64)
    key = np.empty(count, np.int64)
    for t in prange(nt):
        i = rank[t]
        if i < 0:
            continue
        slot[i] = t
        a, b, c, d = tet[t, 0], tet[t, 1], tet[t, 2], tet[t, 3]
        key[i] = _morton(
            0.25 * (Q[a, 0] + Q[b, 0] + Q[c, 0] + Q[d, 0]),
            0.25 * (Q[a, 1] + Q[b, 1] + Q[c, 1] + Q[d, 1]),
            0.25 * (Q[a, 2] + Q[b, 2] + Q[c, 2] + Q[d, 2]),
        )
    return slot, rank, key


@njit(cache=True, nogil=True, parallel=True)
def _sorted_tetrahedra(tet, slot, rank, perm, keep):  # type: ignore[no-untyped-def]
    """Simplices (vertices mapped through ``keep``) and neighbours in the order ``perm`` of the ranks, and the hull.

    The hull's triangles come in rank order, then face order (outward, vertices mapped through ``keep``).
    The slots are read in order and each row written where it goes (reading them in the final order
    instead took twice as long: the rows are scattered over the slots).
    """
    n = perm.shape[0]
    final = np.empty(rank.shape[0], np.int32)  # each slot's final index, -1 if not finite
    for t in prange(rank.shape[0]):
        final[t] = -1
    for i in prange(n):
        final[slot[perm[i]]] = i
    simplices = np.empty((n, 4), np.int64)
    neighbors = np.empty((n, 4), np.int64)
    n_hull = np.zeros(n + 1, np.int64)
    for r in prange(n):
        t = slot[r]
        i = final[t]
        for k in range(4):
            simplices[i, k] = keep[tet[t, k]]
            u = final[tet[t, 4 + k] >> 2]
            neighbors[i, k] = u
            if u < 0:
                n_hull[r + 1] += 1
    for r in range(n):
        n_hull[r + 1] += n_hull[r]
    hull = np.empty((n_hull[n], 3), np.int64)
    for r in prange(n):
        h = n_hull[r]
        t = slot[r]
        for k in range(4):
            if final[tet[t, 4 + k] >> 2] < 0:
                for j in range(3):
                    hull[h, j] = keep[tet[t, _FACE_OUT[k, j]]]
                h += 1
    return simplices, neighbors, hull
