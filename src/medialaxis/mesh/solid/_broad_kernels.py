"""Compiled broad phase of the crossing check for faces far larger than the median (slivers, long CAD faces).

A long face's bounding sphere holds the whole mesh across it: the 400 faces
running the length of a 100k-vertex capsule met every face of it, and
filtering those candidates took 40 s. Here each large face is cut into
pieces about as large as the small faces (longest-edge bisection, done by
the caller), which look up the small faces binned on a grid, as
:func:`~medialaxis.mesh.solid._intersect_kernels.near_pairs` bins them: a large
face meets only the small faces near one of its pieces. (Large faces among
themselves are few; the caller pairs them.)
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit, prange
from medialaxis.mesh.solid._intersect_kernels import _boxes_apart, _shared, grid_cells

__all__ = ["big_face_pairs"]


@njit(cache=True, nogil=True, parallel=True)
def big_face_pairs(triangles, faces, entry_centre, entry_radius, entry_face, n_small, big, piece_ptr, cell):  # type: ignore[no-untyped-def]
    """Pairs ``(b, j)`` of a large face ``b`` and a small face ``j`` that may cross it, each once.

    Parameters
    ----------
    triangles : (f, 3, 3) float64 ndarray
    faces : (f, 3) int64 ndarray
    entry_centre, entry_radius, entry_face : (e, 3), (e,), (e,) ndarray
        Bounding spheres on the grid: the small faces first (``n_small`` of
        them, the candidates), then the pieces of the large faces in the
        order of ``big`` (the queries).
    n_small : int
    big : (b,) int64 ndarray
        The large faces.
    piece_ptr : (b + 1,) int64 ndarray
        The pieces of ``big[k]`` are entries ``n_small + piece_ptr[k]`` to ``n_small + piece_ptr[k + 1]``.
    cell : float
        Grid side, at least the largest sum of a piece's and a small face's radii.

    Returns
    -------
    (m, 2) int64 ndarray
        Pairs whose spheres (a piece's and the small face's) and bounding
        boxes meet, sharing no edge.
    """
    is_query = np.zeros(entry_centre.shape[0], np.int64)
    is_query[n_small:] = 1
    order, cell_start, query_start, cell_of, around = grid_cells(entry_centre, is_query, cell)
    n_big = big.shape[0]
    count = np.zeros(n_big, np.int64)
    pairs = np.empty((0, 2), np.int64)
    for sweep in range(2):
        if sweep == 1:
            start = np.zeros(n_big + 1, np.int64)
            start[1:] = np.cumsum(count)
            pairs = np.empty((start[n_big], 2), np.int64)
        for b in prange(n_big):
            kept = _near_one(b, big[b], triangles, faces, entry_centre, entry_radius, entry_face, n_small, piece_ptr,
                             order, cell_start, query_start, cell_of, around)
            if sweep == 0:
                count[b] = kept.shape[0]
            else:
                for q in range(kept.shape[0]):
                    pairs[start[b] + q, 0] = big[b]
                    pairs[start[b] + q, 1] = kept[q]
    return pairs


@njit(cache=True, nogil=True)
def _near_one(b, f, triangles, faces, entry_centre, entry_radius, entry_face, n_small, piece_ptr, order,
              cell_start, query_start, cell_of, around):  # type: ignore[no-untyped-def]
    """The small faces that may cross large face ``f`` (``big[b]``), ascending, once each."""
    found = np.empty(64, np.int64)
    m = 0
    for e in range(n_small + piece_ptr[b], n_small + piece_ptr[b + 1]):
        c = cell_of[e]
        for a in range(27):
            other = around[c, a]
            if other < 0:
                break
            for s in range(cell_start[other], query_start[other]):
                r = order[s]
                j = entry_face[r]
                d2 = 0.0
                for k in range(3):
                    d2 += (entry_centre[e, k] - entry_centre[r, k]) ** 2
                reach = entry_radius[e] + entry_radius[r]
                if d2 > reach * reach or _boxes_apart(triangles[f], triangles[j]) or _shared(faces, f, j) >= 2:
                    continue
                if m == found.shape[0]:
                    grown = np.empty(2 * m, np.int64)
                    grown[:m] = found
                    found = grown
                found[m] = j
                m += 1
    return np.unique(found[:m])
