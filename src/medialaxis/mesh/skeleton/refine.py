"""Conforming refinement of coarse surfaces: split every edge longer than a bound.

CAD exports describe a flat face by a few long, thin triangles (a drilled
block in 72 vertices); a flow over so few vertices has nothing to contract
but the whole part, and collapses it to a point. Splitting each long edge at
its midpoint, and each triangle by the pattern of its split edges (one edge:
two triangles; two: three; three: four), keeps the mesh closed, manifold and
consistently oriented, keeps every input vertex at its index, and leaves the
surface itself unchanged.
"""

from __future__ import annotations

import numpy as np

from medialaxis.mesh.skeleton import _flow_operators as ops

__all__ = ["split_long_edges", "refine_coarse", "FINE_RATIO", "COARSE_RATIO"]

#: Passes of splitting at most (each halves the longest edges).
MAX_PASSES = 12
#: Vertices a coarse surface is refined to at most for its thickness (a
#: 10 x 10 x 0.2 CAD plate would take 75,000, and its graph stage minutes).
MAX_REFINED = 10_000
#: A surface whose edges are all shorter than its diagonal over this is fine
#: enough as it is.
FINE_RATIO = 50.0
#: A coarse surface is first split to edges of its diagonal over this, then
#: to edges no longer than its median inner-ball radius.
COARSE_RATIO = 10.0


def refine_coarse(points: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Split the long edges of a coarse closed surface (nothing to do on a fine one).

    Edges longer than the diagonal over ``COARSE_RATIO`` are split first; then
    edges longer than the median inner-ball radius (shrinking-ball poles of
    the split surface), so that every part has vertices across its thickness.
    A surface whose edges are all under the diagonal over ``FINE_RATIO`` is
    returned as it is.

    Parameters
    ----------
    points : (n, 3) float64 ndarray
    faces : (k, 3) int64 ndarray

    Returns
    -------
    points, faces
        As :func:`split_long_edges` (input vertices first, at their indices).
    """
    diag = float(np.linalg.norm(points.max(axis=0) - points.min(axis=0)))
    edges = ops.unique_edges(faces)
    if not diag > 0 or np.linalg.norm(points[edges[:, 0]] - points[edges[:, 1]], axis=1).max() <= diag / FINE_RATIO:
        return points, faces
    points, faces = split_long_edges(points, faces, diag / COARSE_RATIO)
    edges = ops.unique_edges(faces)
    mean_edge = float(np.linalg.norm(points[edges[:, 0]] - points[edges[:, 1]], axis=1).mean())
    _, radius = ops.pole_targets(points, ops.vertex_normals(points, faces), max_radius=0.5 * diag, ignore=2.0 * mean_edge)
    thickness = float(np.median(radius))
    if thickness > 0:  # a wide thin plate would take millions: its flow graph would not finish
        points, faces = split_long_edges(points, faces, thickness, max_vertices=MAX_REFINED)
    return points, faces


def split_long_edges(points: np.ndarray, faces: np.ndarray, max_length: float, *,
                     max_vertices: int = 200_000) -> tuple[np.ndarray, np.ndarray]:
    """Split edges longer than ``max_length`` until none is left.

    Parameters
    ----------
    points : (n, 3) float64 ndarray
    faces : (k, 3) int64 ndarray
    max_length : float
        Longest edge wanted (> 0).
    max_vertices : int
        Stop before a pass would give more vertices than this.

    Returns
    -------
    points : (n + m, 3) float64 ndarray
        The input points, then the new midpoints.
    faces : (k', 3) int64 ndarray

    Examples
    --------
    >>> import numpy as np
    >>> tet = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    >>> f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    >>> p, g = split_long_edges(tet, f, 0.8)
    >>> len(p), len(g)  # every edge split once: 4 + 6 vertices, 4 x 4 faces
    (10, 16)
    """
    points = np.asarray(points, np.float64)
    faces = np.asarray(faces, np.int64)
    for _ in range(MAX_PASSES):
        corners = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 3, 2)
        edges, inverse = np.unique(np.sort(corners.reshape(-1, 2), axis=1), axis=0, return_inverse=True)
        long = np.linalg.norm(points[edges[:, 0]] - points[edges[:, 1]], axis=1) > max_length
        n_new = int(long.sum())
        if n_new == 0 or len(points) + n_new > max_vertices:
            break
        middle = np.full(len(edges), -1, np.int64)
        middle[long] = len(points) + np.arange(n_new)
        points = np.concatenate([points, 0.5 * (points[edges[long, 0]] + points[edges[long, 1]])])
        faces = _split_faces(faces, middle[inverse.reshape(-1, 3)])
    return points, faces


def _split_faces(faces: np.ndarray, mid: np.ndarray) -> np.ndarray:
    """Triangles of each face ``(a, b, c)`` given the midpoints of its edges
    ``ab, bc, ca`` (``-1``: not split), in the face's orientation."""
    split = mid >= 0
    count = split.sum(axis=1)
    # roll each face so that one split edge is ab, or the one unsplit edge is ca
    first_split = np.argmax(split, axis=1)
    unsplit = np.argmin(split, axis=1)
    roll = np.where(count == 2, (unsplit + 1) % 3, np.where(count == 1, first_split, 0))
    order = (np.arange(3)[None, :] + roll[:, None]) % 3
    f = np.take_along_axis(faces, order, axis=1)
    m = np.take_along_axis(mid, order, axis=1)
    a, b, c = f.T
    m0, m1, m2 = m.T
    out = [np.stack([a, b, c], 1)[count == 0]]
    one = count == 1
    out += [np.stack([a, m0, c], 1)[one], np.stack([m0, b, c], 1)[one]]
    two = count == 2
    out += [np.stack([m0, b, m1], 1)[two], np.stack([a, m0, m1], 1)[two], np.stack([a, m1, c], 1)[two]]
    three = count == 3
    out += [np.stack(t, 1)[three] for t in ((a, m0, m2), (m0, b, m1), (m2, m1, c), (m0, m1, m2))]
    return np.concatenate(out)
