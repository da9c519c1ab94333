"""Betti numbers of medial complexes (points, edges and triangles) over GF(2).

A medial complex is mostly made of sheets with free borders. Faces with a free
edge (an edge of no other face) are collapsed with that edge, round after
round, which keeps the homotopy type and leaves little or nothing of the
sheets; what is left is counted: ``b0`` from the 1-skeleton, ``b2`` from the
rank of the boundary matrix of the faces left (Gaussian elimination over
GF(2)), ``b1`` from the Euler characteristic.
"""

from __future__ import annotations

import numpy as np
from scipy import sparse
from scipy.sparse import csgraph

__all__ = ["betti_numbers"]


def betti_numbers(n_points: int, edges: np.ndarray, faces: np.ndarray) -> tuple[int, int, int]:
    """``(b0, b1, b2)`` of the complex of ``n_points`` points, ``edges`` and triangular ``faces``.

    Parameters
    ----------
    n_points : int
        Points (isolated ones are components).
    edges : (m, 2) int array_like
        Edges besides those of the faces (may repeat them).
    faces : (k, 3) int array_like

    Returns
    -------
    tuple of 3 int

    Examples
    --------
    >>> import numpy as np
    >>> tet = np.array([[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]])
    >>> betti_numbers(4, np.empty((0, 2), int), tet)  # a sphere
    (1, 0, 1)
    >>> betti_numbers(4, np.empty((0, 2), int), tet[:3])  # a disc
    (1, 0, 0)
    >>> betti_numbers(3, [[0, 1], [1, 2], [2, 0]], np.empty((0, 3), int))  # a circle
    (1, 1, 0)
    """
    faces = np.asarray(faces, np.int64).reshape(-1, 3)
    edges = np.asarray(edges, np.int64).reshape(-1, 2)
    face_edges = np.sort(faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    all_edges = np.unique(np.concatenate([np.sort(edges, axis=1), face_edges]), axis=0)
    all_edges = all_edges[all_edges[:, 0] != all_edges[:, 1]]
    key = all_edges[:, 0] * n_points + all_edges[:, 1]
    of_face = np.searchsorted(key, face_edges[:, 0] * n_points + face_edges[:, 1]).reshape(-1, 3)
    face_alive = np.ones(len(faces), bool)
    edge_alive = np.ones(len(all_edges), bool)
    while True:
        count = np.bincount(of_face[face_alive].ravel(), minlength=len(all_edges))
        free = (count == 1) & edge_alive
        collapsing = face_alive & free[of_face].any(axis=1)
        if not collapsing.any():
            break
        # a free edge belongs to one face only: all these collapses are independent
        rows = np.flatnonzero(collapsing)
        face_alive[rows] = False
        edge_alive[of_face[rows, np.argmax(free[of_face[rows]], axis=1)]] = False
    kept = all_edges[edge_alive]
    graph = sparse.coo_matrix((np.ones(len(kept)), (kept[:, 0], kept[:, 1])), shape=(n_points, n_points))
    b0 = int(csgraph.connected_components(graph, directed=False)[0])
    rank = _gf2_rank(of_face[face_alive])
    b2 = int(face_alive.sum()) - rank
    b1 = len(kept) - n_points + b0 - rank
    return b0, b1, b2


def _gf2_rank(rows: np.ndarray) -> int:
    """Rank over GF(2) of the 0/1 rows with ones at the given columns (3 per row)."""
    pivots: dict[int, int] = {}
    rank = 0
    for row in rows:
        bits = 0
        for column in row:
            bits ^= 1 << int(column)
        while bits:
            lead = bits.bit_length() - 1
            if lead not in pivots:
                pivots[lead] = bits
                rank += 1
                break
            bits ^= pivots[lead]
    return rank
