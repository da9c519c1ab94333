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

__all__ = ["betti_numbers", "void_faces"]


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
    kept, of_face, face_alive = _collapse_free_faces(n_points, edges, faces)
    graph = sparse.coo_matrix((np.ones(len(kept)), (kept[:, 0], kept[:, 1])), shape=(n_points, n_points))
    b0 = int(csgraph.connected_components(graph, directed=False)[0])
    rank = len(_gf2_pivots(of_face[face_alive]))
    b2 = int(face_alive.sum()) - rank
    b1 = len(kept) - n_points + b0 - rank
    return b0, b1, b2


def void_faces(n_points: int, edges: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Faces whose removal leaves no void: one per independent 2-cycle (``b2`` of them).

    The faces left after the free-face collapses are eliminated over GF(2)
    in the given order; a face whose boundary reduces to zero closes a
    cycle of earlier faces. Removing these faces leaves ``b0`` and ``b1``
    unchanged (each removal drops a dependent row) and ``b2`` at 0.

    Examples
    --------
    >>> import numpy as np
    >>> tet = np.array([[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]])
    >>> void_faces(4, np.empty((0, 2), int), tet)
    array([3])
    """
    _, of_face, face_alive = _collapse_free_faces(n_points, edges, faces)
    rows = np.flatnonzero(face_alive)
    pivots = _gf2_pivots(of_face[rows])
    independent = np.zeros(len(rows), bool)
    independent[pivots] = True
    return rows[~independent]


def _collapse_free_faces(n_points: int, edges: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Collapse faces through free edges: the edges left, each face's edges, the faces left."""
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
    return all_edges[edge_alive], of_face, face_alive


def _gf2_pivots(rows: np.ndarray) -> list[int]:
    """Rows independent of the rows before them, over GF(2) (0/1 rows with ones at the given columns)."""
    pivots: dict[int, int] = {}
    independent = []
    for i, row in enumerate(rows):
        bits = 0
        for column in row:
            bits ^= 1 << int(column)
        while bits:
            lead = bits.bit_length() - 1
            if lead not in pivots:
                pivots[lead] = bits
                independent.append(i)
                break
            bits ^= pivots[lead]
    return independent
