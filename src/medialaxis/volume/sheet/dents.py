"""Dent removal at junctions (Kumar, Michikawa and Suzuki, eq. 1).

The inscribed balls at a junction are larger than the plates' half
thickness, so the medial surface dips there. Each junction vertex
``x_i`` moves to the minimiser of

    E(x) = sum_j <n_ij, x - p_ij>^2 + ||x_i - x||^2,

where ``f_j`` are the faces near ``x_i`` (incident to its one-ring) that
hold no junction vertex, with unit normals ``n_ij`` and centroids ``p_ij``:
the quadratic error to the neighbouring planes (Garland and Heckbert) plus a
proximity term that makes the solution unique. Setting the gradient to zero
gives the 3x3 system ``(I + sum n n^T) x = x_i + sum n n^T p``.
"""

from __future__ import annotations

import numpy as np
from scipy import sparse

__all__ = ["remove_dents", "face_normals", "bent_vertices"]


def face_normals(points: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """(f, 3) unit normals (zero for degenerate faces)."""
    tri = points[faces]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    norm = np.linalg.norm(n, axis=1, keepdims=True)
    return np.divide(n, norm, out=np.zeros_like(n), where=norm > 0)


def remove_dents(points: np.ndarray, faces: np.ndarray, junction: np.ndarray,
                 excluded: np.ndarray | None = None, rings: int = 1) -> np.ndarray:
    """New positions of the junction vertices by minimising eq. (1).

    Parameters
    ----------
    points : (v, 3) float64 ndarray
    faces : (f, 3) int64 ndarray
    junction : (v,) bool ndarray
        Which vertices move (the paper's junction vertices).
    excluded : (v,) bool ndarray, optional
        Vertices whose faces are not used as planes (default: ``junction``).
        The pipeline also moves free-edge vertices this way, using planes of
        faces with neither junction nor free-edge vertices.
    rings : int
        Planes come from the faces touching the vertex's ``rings``-ring
        (1: the paper's neighbourhood; 2 reaches past a row of excluded
        vertices, as at the corner where a junction line meets a free edge).

    Returns
    -------
    (v, 3) float64 ndarray
        A copy of ``points`` with the junction vertices moved; vertices with
        no usable neighbouring face stay.

    References
    ----------
    .. [1] V. Kumar, T. Michikawa, H. Suzuki, "Improving medial surfaces for reverse
           engineering" (venue, year and DOI unconfirmed: docs/references.md).
    .. [2] M. Garland, P. S. Heckbert, "Surface simplification using quadric error metrics",
           Proc. SIGGRAPH 97, 209-216, 1997. doi:10.1145/258734.258849

    Examples
    --------
    >>> import numpy as np
    >>> pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [0.5, 0.5, 0.3]], float)
    >>> f = np.array([[0, 1, 2], [1, 3, 2], [0, 1, 4]])
    >>> remove_dents(pts, f, np.array([0, 0, 0, 0, 1], bool))[4].round(3).tolist()
    [0.5, 0.5, 0.1]
    """
    points = np.asarray(points, np.float64)
    out = points.copy()
    faces = np.asarray(faces, np.int64)
    junction = np.asarray(junction, bool)
    if len(faces) == 0 or not junction.any():
        return out
    nv, nf = len(points), len(faces)
    incidence = sparse.csr_matrix((np.ones(3 * nf), (faces.ravel(), np.repeat(np.arange(nf), 3))), shape=(nv, nf))
    ring = (incidence @ incidence.T).tocsr()  # vertex -> vertices sharing a face (incl. itself)
    rows = np.flatnonzero(junction)
    reach = ring[rows]
    for _ in range(rings - 1):
        reach = reach @ ring
    near = (reach @ incidence).tocoo()  # junction vertex -> faces touching its one-ring
    clean = ~(junction if excluded is None else np.asarray(excluded, bool))[faces].any(axis=1)
    keep = clean[near.col]
    owner, face = rows[near.row[keep]], near.col[keep]
    normal = face_normals(points, faces)[face]
    centroid = points[faces[face]].mean(axis=1)
    nnT = normal[:, :, None] * normal[:, None, :]
    A = np.zeros((nv, 3, 3))
    b = np.zeros((nv, 3))
    np.add.at(A, owner, nnT)
    np.add.at(b, owner, np.einsum("kij,kj->ki", nnT, centroid))
    A[rows] += np.eye(3)
    b[rows] += points[rows]
    out[rows] = np.linalg.solve(A[rows], b[rows][:, :, None])[:, :, 0]
    return out


def bent_vertices(points: np.ndarray, faces: np.ndarray, share: float = 0.1) -> np.ndarray:
    """Vertices where the mesh bends: the normals of their faces span two directions.

    Parameters
    ----------
    points : (v, 3) float64 ndarray
    faces : (f, 3) int64 ndarray
    share : float
        Smallest share of the second eigenvalue of the scatter ``sum n n^T``
        of the unit normals of a vertex's faces (0 on a flat sheet, 0.5 where
        two perpendicular sheets meet in equal parts).

    Returns
    -------
    (v,) bool ndarray

    Examples
    --------
    >>> import numpy as np
    >>> pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
    >>> bent_vertices(pts, np.array([[0, 1, 2], [0, 1, 3]])).tolist()
    [True, True, False, False]
    """
    normals = face_normals(points, faces)
    scatter = np.zeros((len(points), 3, 3))
    nnT = normals[:, :, None] * normals[:, None, :]
    for corner in range(3):
        np.add.at(scatter, faces[:, corner], nnT)
    value = np.linalg.eigvalsh(scatter)  # ascending
    total = value.sum(axis=1)
    return np.divide(value[:, 1], total, out=np.zeros(len(points)), where=total > 0) > share
