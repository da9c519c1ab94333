"""Exact signed distance to a closed mesh near its surface samples (the inside test of the Voronoi route)."""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy import sparse
from scipy.spatial import cKDTree

from medialaxis.mesh._closest_kernels import closest_on_candidates, face_spheres, pseudo_normal_sign
from medialaxis.mesh.sampling import PseudoNormals, pseudo_normals

__all__ = ["SignedDistance"]


class SignedDistance:
    """Exact signed distance to a closed mesh near a surface sample.

    Candidate faces of a query are those sharing a vertex with the faces of
    a few sample points the caller names (for a Voronoi vertex: the four
    samples of its tetrahedron, which are its nearest samples).

    Parameters
    ----------
    mesh : trimesh.Trimesh
        Closed and outward oriented.
    normals : PseudoNormals, optional
    """

    def __init__(self, mesh: Any, normals: PseudoNormals | None = None) -> None:
        self.vertices = np.asarray(mesh.vertices, np.float64)
        self.faces = np.asarray(mesh.faces, np.int64)
        self.normals = pseudo_normals(mesh) if normals is None else normals
        tri = self.vertices[self.faces]
        self.corners = tuple(np.ascontiguousarray(tri[:, k]) for k in range(3))
        self.spheres = face_spheres(*self.corners)
        nf, nv = len(self.faces), len(self.vertices)
        incidence = sparse.csr_matrix(
            (np.ones(3 * nf), (np.repeat(np.arange(nf), 3), self.faces.ravel())), shape=(nf, nv)
        )
        ring = (incidence @ incidence.T).tocsr()
        self.ring_ptr = ring.indptr.astype(np.int64)
        self.ring_idx = ring.indices.astype(np.int64)
        self._own_ptr, self._own_idx = np.arange(nf + 1), np.arange(nf)  # each face's "ring" is itself

    def query(self, points: np.ndarray, near_faces: np.ndarray, rings: bool = True) -> tuple[np.ndarray, np.ndarray]:
        """Signed distance (negative inside) and closest surface point.

        Parameters
        ----------
        points : (q, 3) float64 ndarray
        near_faces : (q, k) int64 ndarray
            Faces near each query (their vertex rings are searched).
        rings : bool
            ``False``: only ``near_faces`` themselves are searched.

        Returns
        -------
        signed : (q,) float64 ndarray
        closest : (q, 3) float64 ndarray
        """
        points = np.ascontiguousarray(points, np.float64)
        dist, closest, face, region = closest_on_candidates(
            points,
            *self.corners,
            *self.spheres,
            np.ascontiguousarray(near_faces, np.int64),
            *((self.ring_ptr, self.ring_idx) if rings else (self._own_ptr, self._own_idx)),
        )
        pn = self.normals
        signed = pseudo_normal_sign(
            points, closest, dist, face, region, self.faces, pn.face, pn.vertex, pn.edge, pn.face_edges
        )
        return signed, closest

    def exact(self, points: np.ndarray, k: int = 32, budget: int = 2_000_000) -> tuple[np.ndarray, np.ndarray]:
        """Signed distance and closest point, exact: every face that may be nearer is searched.

        The local search of :meth:`query` can stop at a face a little farther
        than the nearest one where many faces are nearly equidistant (the
        centre of a faceted cap). Here a point's first candidates are its ``k``
        faces of nearest centroid; a face beyond them is at least (``k``-th
        centroid distance - the largest centroid-to-corner distance) away, and
        when that is not below the distance found the answer is exact.
        Otherwise every face whose centroid lies within the distance found
        plus that largest reach is searched (points deep inside a finely
        faceted surface: a medial point is nearly equidistant from whole
        patches of faces), in batches of at most ``budget`` candidates.
        """
        points = np.asarray(points, np.float64).reshape(-1, 3)
        if not hasattr(self, "_centroid_tree"):
            self._centroid_tree = cKDTree(self.spheres[0])
            self._reach = float(self.spheres[1].max())
        k = min(k, len(self.faces))
        centroid_dist, near = self._centroid_tree.query(points, k, workers=-1)
        centroid_dist, near = centroid_dist.reshape(len(points), k), near.reshape(len(points), k)
        signed, closest = self.query(points, near, rings=False)
        todo = np.flatnonzero((centroid_dist[:, -1] - self._reach < np.abs(signed)) & (k < len(self.faces)))
        if not len(todo):
            return signed, closest
        found = self._centroid_tree.query_ball_point(
            points[todo], np.abs(signed[todo]) + self._reach, workers=-1, return_sorted=False
        )
        count = np.fromiter((len(f) for f in found), np.int64, len(todo))
        by_count = np.argsort(count, kind="stable")
        start = 0
        while start < len(by_count):  # similar counts together: little padding
            stop = start + 1
            while stop < len(by_count) and (stop + 1 - start) * count[by_count[stop]] <= budget:
                stop += 1
            rows = by_count[start:stop]
            width = int(count[rows[-1]])
            cand = np.empty((len(rows), width), np.int64)
            for r, q in enumerate(rows):
                cand[r, : count[q]] = found[q]
                cand[r, count[q] :] = found[q][0]  # padding repeats a candidate (searched once)
            signed[todo[rows]], closest[todo[rows]] = self.query(points[todo[rows]], cand, rings=False)
            start = stop
        return signed, closest
