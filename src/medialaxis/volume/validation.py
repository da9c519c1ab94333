"""Scores of a mid-surface mesh against a known mid-surface (phantoms).

Used by the tests and ``benchmarks/bench_volume.py``. Distances are in the
units of the points given (voxels for the phantoms).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np
from scipy.spatial import cKDTree

from medialaxis.datasets import Rect

__all__ = ["distance_to_rects", "sample_triangles", "coverage", "MeshTopology", "mesh_topology"]


def distance_to_rects(points: np.ndarray, rects: Sequence[Rect]) -> np.ndarray:
    """(n,) distance of each point to the nearest rectangle.

    Examples
    --------
    >>> import numpy as np
    >>> r = Rect(np.zeros(3), np.array([0, 10.0, 0]), np.array([0, 0, 10.0]))
    >>> distance_to_rects(np.array([[2.0, 5, 5], [0, 13, 14]]), [r]).tolist()
    [2.0, 5.0]
    """
    points = np.asarray(points, np.float64).reshape(-1, 3)
    best = np.full(len(points), np.inf)
    for r in rects:
        d = points - r.origin
        lu, lv = float(r.u @ r.u), float(r.v @ r.v)
        s = np.clip(d @ r.u / lu, 0, 1)
        t = np.clip(d @ r.v / lv, 0, 1)
        nearest = r.origin + s[:, None] * r.u + t[:, None] * r.v
        best = np.minimum(best, np.linalg.norm(points - nearest, axis=1))
    return best


def sample_triangles(points: np.ndarray, faces: np.ndarray, step: float = 0.25) -> np.ndarray:
    """Points on every triangle no more than ~``step`` apart (vertices included)."""
    if len(faces) == 0:
        return np.asarray(points, np.float64).reshape(-1, 3)
    tri = np.asarray(points, np.float64)[faces]
    longest = np.linalg.norm(tri - np.roll(tri, 1, axis=1), axis=2).max(axis=1)
    out = [np.asarray(points, np.float64)]
    levels = np.maximum(np.ceil(longest / step).astype(int), 1)
    for k in np.unique(levels):
        sel = tri[levels == k]
        i, j = np.meshgrid(np.arange(k + 1), np.arange(k + 1), indexing="ij")
        keep = i + j <= k
        a, b = i[keep] / k, j[keep] / k
        w = np.stack([1 - a - b, a, b], axis=1)  # (p, 3)
        out.append(np.einsum("pk,tkd->tpd", w, sel).reshape(-1, 3))
    return np.concatenate(out)


def coverage(truth_points: np.ndarray, points: np.ndarray, faces: np.ndarray, tolerance: float = 1.0,
             step: float = 0.25) -> tuple[float, np.ndarray]:
    """Fraction of ``truth_points`` within ``tolerance`` of the mesh.

    The mesh is sampled ``step`` apart, so distances are over-estimated by at
    most ~``step / 2`` (the score is conservative).

    Returns
    -------
    fraction : float
    distance : (n,) float64 ndarray
        Distance of each truth point to the sampled mesh.
    """
    dist, _ = cKDTree(sample_triangles(points, faces, step)).query(truth_points, k=1)
    return float(np.mean(dist <= tolerance)), dist


@dataclasses.dataclass(frozen=True)
class MeshTopology:
    """Counts describing a (possibly non-manifold) triangle mesh.

    Attributes
    ----------
    vertices, edges, faces : int
        Used vertices, distinct edges, faces.
    euler : int
        ``vertices - edges + faces`` (1 for a contractible mesh).
    components : int
    boundary_edges, manifold_edges, junction_edges : int
        Edges with one, two, and three or more faces.
    """

    vertices: int
    edges: int
    faces: int
    euler: int
    components: int
    boundary_edges: int
    manifold_edges: int
    junction_edges: int


def mesh_topology(faces: np.ndarray) -> MeshTopology:
    """Topology counts of a triangle mesh given by its faces."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    faces = np.asarray(faces, np.int64).reshape(-1, 3)
    used, inverse = np.unique(faces, return_inverse=True)
    f = inverse.reshape(-1, 3)
    e = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    edges, count = np.unique(e, axis=0, return_counts=True)
    n = len(used)
    g = coo_matrix((np.ones(len(edges)), (edges[:, 0], edges[:, 1])), shape=(n, n))
    ncomp = connected_components(g, directed=False)[0] if n else 0
    return MeshTopology(n, len(edges), len(faces), n - len(edges) + len(faces), int(ncomp),
                        int((count == 1).sum()), int((count == 2).sum()), int((count >= 3).sum()))
