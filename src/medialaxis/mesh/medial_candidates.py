"""Medial candidates for the simplification: spheres of the medial complex that touch two sides.

A sphere of the Voronoi medial complex carries its contacts (the four
samples of its Delaunay tetrahedron, on its sphere). When they span 90
degrees or more as seen from its centre, the sphere touches the surface on
two sides: it stands for the medial axis, not for a patch of one side. The
simplification (:mod:`medialaxis.mesh.qmat`, ``mode="medial"``) keeps only
such spheres.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from medialaxis.core.result import MedialAxis

__all__ = ["MedialCandidates", "SPAN", "SNAP"]

#: Contacts spanning at least this many degrees from the centre make a sphere a candidate (the
#: independent test asks 90 of the surface within 2% of the radius, which spans a little more than
#: the four contacts; at 90 the sheets of a box reaching its right-angled edges fell out).
SPAN = 80.0

#: Candidates a collapsed sphere is snapped among (nearest in centre and radius).
SNAP = 16


class MedialCandidates:
    """Medial candidates: the spheres of the medial complex whose contacts span at least ``SPAN``.

    From ``ma`` and the complex it was made from (``ma.raw``: the full
    complex under the compact one), each sphere with its contacts (the
    samples of its Delaunay tetrahedron, on its sphere). One whose contacts
    span 90 degrees or more as seen from its centre touches two sides of the
    surface: it stands for the medial axis. Collapsed spheres are replaced by
    the candidate nearby of least quadric error (:meth:`snap`); spheres
    added where the surface is farthest out are the candidate balls
    reaching nearest to it (:meth:`cover`).
    """

    def __init__(self, ma: MedialAxis) -> None:
        sources = [m for m in (ma, ma.raw) if m is not None and m.dim == 3 and "contacts" in m.extras]
        centres = np.concatenate([m.points for m in sources]) if sources else np.zeros((0, 3))
        radii = np.concatenate([m.radii for m in sources]) if sources else np.zeros(0)
        contacts = np.concatenate([np.asarray(m.extras["contacts"]) for m in sources]) if sources else np.zeros((0, 4, 3))
        u = contacts - centres[:, None, :]
        u /= np.maximum(np.linalg.norm(u, axis=2, keepdims=True), 1e-300)
        ok = (np.einsum("nid,njd->nij", u, u).min(axis=(1, 2)) <= np.cos(np.radians(SPAN))) & (radii > 0)
        self.spheres = np.c_[centres, radii][ok]
        self.tree = cKDTree(self.spheres) if len(self.spheres) else None
        touch = contacts[ok]
        self.contact_tree = cKDTree(touch.reshape(-1, 3)) if len(self.spheres) else None
        self.per = touch.shape[1]

    def snap(self, s: np.ndarray, qa: np.ndarray, qb: np.ndarray) -> np.ndarray:
        """The candidate among the ``SNAP`` nearest ``s`` in (centre, radius) of least quadric error."""
        if self.tree is None:
            return s
        _, near = self.tree.query(s, k=min(SNAP, len(self.spheres)))
        t = self.spheres[np.atleast_1d(near)]
        cost = np.einsum("ki,ij,kj->k", t, qa, t) - 2.0 * t @ qb
        return t[int(np.argmin(cost))].copy()

    def cover(self, x: np.ndarray) -> tuple[np.ndarray, float]:
        """The candidate ball reaching nearest to ``x`` among those touching the surface near it."""
        if self.tree is None:
            return x, 0.0
        _, near = self.contact_tree.query(x, k=min(4 * SNAP, len(self.spheres) * self.per))
        t = self.spheres[np.unique(np.atleast_1d(near) // self.per)]
        best = int(np.argmin(np.linalg.norm(t[:, :3] - x, axis=1) - t[:, 3]))
        return t[best, :3].copy(), float(t[best, 3])
