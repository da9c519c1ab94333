"""Betti numbers of medial complexes (points, edges and triangles) over GF(2).

A medial complex is mostly made of sheets with free borders. Faces with a free
edge (an edge of no other face) are collapsed with that edge, one after
another as edges become free (compiled), which keeps the homotopy type and
leaves little or nothing of the sheets; what is left is counted: ``b0`` from the 1-skeleton, ``b2`` from the
rank of the boundary matrix of the faces left, ``b1`` from the Euler
characteristic.

The rank is taken over regions, not faces: a 2-cycle holds both faces of an
edge that only two faces share or neither, so the faces joined through such
edges (a region: a sheet between junction lines, a whole closed surface) are
in a cycle together. A region's boundary is the set of junction edges (three
or more faces) it meets an odd number of times, and Gaussian elimination over
GF(2) runs on those few rows and columns. On faces it kept one integer per
row as wide as the highest edge index, which ran out of memory (past 22 GB)
on the complex of a scanned ogre whose four cavities leave closed sheets of
thousands of faces.
"""

from __future__ import annotations

import numpy as np
from scipy import sparse
from scipy.sparse import csgraph

from medialaxis.core._kernels import collapse_free_faces_kernel
from medialaxis.core.arrays import unique_ints

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
    b2 = len(_closing_faces(of_face, face_alive))
    rank = int(face_alive.sum()) - b2
    b1 = len(kept) - n_points + b0 - rank
    return b0, b1, b2


def void_faces(n_points: int, edges: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Faces whose removal leaves no void: one per independent 2-cycle (``b2`` of them).

    The faces left after the free-face collapses are eliminated over GF(2)
    in the given order; a face whose boundary reduces to zero closes a
    cycle of earlier faces (it is the last face of a region, see the module
    docstring). Removing these faces leaves ``b0`` and ``b1``
    unchanged (each removal drops a dependent row) and ``b2`` at 0.

    Examples
    --------
    >>> import numpy as np
    >>> tet = np.array([[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]])
    >>> void_faces(4, np.empty((0, 2), int), tet)
    array([3])
    """
    _, of_face, face_alive = _collapse_free_faces(n_points, edges, faces)
    return _closing_faces(of_face, face_alive)


def _collapse_free_faces(n_points: int, edges: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Collapse faces through free edges: the edges left, each face's edges, the faces left."""
    faces = np.asarray(faces, np.int64).reshape(-1, 3)
    edges = np.asarray(edges, np.int64).reshape(-1, 2)
    # a triangle with a repeated point is the edge it spans: its edges count, it is never alive
    flat = (faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2]) | (faces[:, 2] == faces[:, 0])
    face_edges = np.sort(faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    spans = np.concatenate([np.sort(edges, axis=1), face_edges])
    key = unique_ints((spans[:, 0] * n_points + spans[:, 1])[spans[:, 0] != spans[:, 1]])
    all_edges = np.stack([key // n_points, key % n_points], axis=1)
    of_face = np.searchsorted(key, face_edges[:, 0] * n_points + face_edges[:, 1]).reshape(-1, 3)
    of_face[flat] = 0
    face_alive = ~flat
    edge_alive = collapse_free_faces_kernel(of_face, face_alive, len(all_edges))
    return all_edges[edge_alive], of_face, face_alive


def _closing_faces(of_face: np.ndarray, face_alive: np.ndarray) -> np.ndarray:
    """Alive faces, in increasing order, each the last face of a 2-cycle of the alive faces up to it.

    One per independent 2-cycle: the faces whose boundary rows depend on the
    rows before them. Every edge of an alive face is in two or more alive
    faces (free ones were collapsed). A cycle is a union of regions (faces
    joined through edges of two faces), so its last face is the last face
    of its last region, and that region's junction row depends on the rows
    of the regions that end before it.
    """
    rows = np.flatnonzero(face_alive)
    if not len(rows):
        return rows
    fe = of_face[rows].ravel()
    owner = np.repeat(np.arange(len(rows)), 3)
    degree = np.bincount(fe)
    two = degree[fe] == 2
    order = np.argsort(fe[two], kind="stable")
    pairs = owner[two][order].reshape(-1, 2)  # the two faces of each such edge
    graph = sparse.coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(len(rows), len(rows)))
    n_regions, region = csgraph.connected_components(graph, directed=False)
    last = np.zeros(n_regions, np.int64)
    np.maximum.at(last, region, np.arange(len(rows)))
    rank_of = np.empty(n_regions, np.int64)  # regions numbered by their last face
    rank_of[np.argsort(last)] = np.arange(n_regions)
    junction = ~two
    _, column = np.unique(fe[junction], return_inverse=True)  # junction edges numbered from 0
    width = max(int(column.max(initial=-1)) + 1, 1)
    key, times = np.unique(rank_of[region[owner[junction]]] * width + column, return_counts=True)
    key = key[times % 2 == 1]  # the junction edges each region meets an odd number of times
    start = np.searchsorted(key // width, np.arange(n_regions + 1))
    boundary = [(key[start[i]:start[i + 1]] % width).tolist() for i in range(n_regions)]
    closing = np.ones(n_regions, bool)
    closing[_gf2_pivots(boundary)] = False
    return rows[np.sort(last)[closing]]


def _gf2_pivots(rows: list[list[int]]) -> list[int]:
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
