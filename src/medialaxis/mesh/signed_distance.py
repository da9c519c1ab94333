"""Exact signed distance to a closed mesh near its surface samples (the inside test of the Voronoi route)."""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy import sparse
from scipy.spatial import cKDTree

from medialaxis.mesh._closest_kernels import REGION_FACE, closest_on_candidates, face_spheres
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
        dist, closest, face, region = closest_on_candidates(
            np.ascontiguousarray(points, np.float64),
            *self.corners,
            *self.spheres,
            np.ascontiguousarray(near_faces, np.int64),
            *((self.ring_ptr, self.ring_idx) if rings else (self._own_ptr, self._own_idx)),
        )
        pn = self.normals
        normal = pn.face[face].copy()
        vert = region < 3
        normal[vert] = pn.vertex[self.faces[face[vert], region[vert]]]
        edge = (region >= 3) & (region < REGION_FACE)
        normal[edge] = pn.edge[pn.face_edges[face[edge], region[edge] - 3]]
        side = np.einsum("ij,ij->i", points - closest, normal)
        return np.where(side < 0, -dist, dist), closest

    def exact(
        self, points: np.ndarray, k: int = 32, budget: int = 2_000_000, max_k: int = 2048
    ) -> tuple[np.ndarray, np.ndarray]:
        """Signed distance and closest point, exact: every face that may be nearer is searched.

        The local search of :meth:`query` can stop at a face a little farther
        than the nearest one where many faces are nearly equidistant (the
        centre of a faceted cap). Here a point's candidates are its ``k``
        faces of nearest centroid; a face beyond them is at
        least (``k``-th centroid distance - the largest centroid-to-corner
        distance) away, and when that is not below the distance found the
        answer is exact; otherwise ``k`` grows fourfold for that point, up to
        ``max_k``: beyond it (a point on the axis of a finely faceted surface of
        revolution is nearly equidistant from whole rings of faces) the best
        of the ``max_k`` faces is kept. Points go in batches of at most
        ``budget`` candidate faces in all.
        """
        points = np.asarray(points, np.float64)
        if not hasattr(self, "_centroid_tree"):
            self._centroid_tree = cKDTree(self.spheres[0])
            self._reach = float(self.spheres[1].max())
        n_faces = len(self.faces)
        signed = np.empty(len(points))
        closest = np.empty((len(points), 3))
        todo = np.arange(len(points))
        while len(todo):
            k = min(k, n_faces)
            left = []
            for batch in np.array_split(todo, max(1, len(todo) * k // budget)):
                centroid_dist, near = self._centroid_tree.query(points[batch], k, workers=-1)
                centroid_dist, near = centroid_dist.reshape(len(batch), k), near.reshape(len(batch), k)
                s, c = self.query(points[batch], near, rings=False)
                done = (centroid_dist[:, -1] - self._reach >= np.abs(s)) | (k == n_faces) | (k >= max_k)
                signed[batch[done]], closest[batch[done]] = s[done], c[done]
                left.append(batch[~done])
            todo = np.concatenate(left)
            k *= 4
        return signed, closest
