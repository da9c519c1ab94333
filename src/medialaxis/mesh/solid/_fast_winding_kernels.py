"""Fast generalized winding numbers: a bounding-sphere tree of the triangles with dipole far fields (numba).

Far from a cluster of triangles, the sum of their solid angles is close to
that of a dipole at the cluster's area-weighted centre whose moment is the
sum of the triangles' area-weighted normals, ``(c - q) . N / (4 pi |c - q|^3)``;
a cluster is taken whole when the query point is more than ``beta`` times
its bounding radius away, else its children are opened, down to leaves
summed exactly (:mod:`medialaxis.mesh.solid._winding_kernels`' formula). The first
order of Barill et al.'s expansion: enough to tell inside (1) from outside
(0) away from the surface, where it is used (:mod:`medialaxis.mesh.solid.contour`).

References
----------
.. [1] Barill, Dickson, Schmidt, Levin, Jacobson, "Fast winding numbers for soups and
       clouds", ACM Transactions on Graphics 37(4):43:1-43:12 (Proc. SIGGRAPH), 2018.
       doi:10.1145/3197517.3201337
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit, prange
from medialaxis.mesh.solid._winding_kernels import solid_angle

__all__ = ["WindingTree", "fast_winding_numbers"]

#: Triangles per leaf of the tree.
LEAF = 8
#: A cluster is replaced by its dipole beyond this many bounding radii.
BETA = 2.0


class WindingTree:
    """Bounding-sphere tree of ``triangles`` ``(T, 3, 3)``: leaves of at most ``LEAF`` triangles, split at the median."""

    def __init__(self, triangles: np.ndarray) -> None:
        triangles = np.ascontiguousarray(triangles, np.float64)
        centroids = triangles.mean(axis=1)
        order = np.arange(len(triangles))
        lo, hi, left, right = [], [], [], []
        stack = [(0, len(triangles), -1, 0)]  # range, parent, which child
        while stack:
            start, stop, parent, side = stack.pop()
            node = len(lo)
            lo.append(start), hi.append(stop), left.append(-1), right.append(-1)
            if parent >= 0:
                (left if side == 0 else right)[parent] = node
            if stop - start <= LEAF:
                continue
            part = order[start:stop]
            axis = int(np.argmax(np.ptp(centroids[part], axis=0)))
            mid = (stop - start) // 2
            order[start:stop] = part[np.argpartition(centroids[part, axis], mid)]
            stack.append((start + mid, stop, node, 1))
            stack.append((start, start + mid, node, 0))
        self.triangles = triangles[order]
        self.lo, self.hi = np.array(lo, np.int64), np.array(hi, np.int64)
        self.left, self.right = np.array(left, np.int64), np.array(right, np.int64)
        self.centre, self.radius, self.dipole = _node_moments(self.triangles, self.lo, self.hi)

    def __call__(self, points: np.ndarray, beta: float = BETA) -> np.ndarray:
        """Winding number of the triangles at ``points`` ``(P, 3)`` (all cores)."""
        return fast_winding_numbers(np.ascontiguousarray(points, np.float64), self.triangles, self.lo, self.hi,
                                    self.left, self.right, self.centre, self.radius, self.dipole, float(beta))


@njit(cache=True, nogil=True)
def _node_moments(triangles, lo, hi):  # type: ignore[no-untyped-def]
    """Each node's area-weighted centre, bounding radius about it, and summed area-weighted normal."""
    n = lo.shape[0]
    centre, radius, dipole = np.zeros((n, 3)), np.zeros(n), np.zeros((n, 3))
    for k in range(n):
        area = 0.0
        for t in range(lo[k], hi[k]):
            e1 = triangles[t, 1] - triangles[t, 0]
            e2 = triangles[t, 2] - triangles[t, 0]
            normal = 0.5 * np.cross(e1, e2)
            a = np.sqrt(normal @ normal)
            dipole[k] += normal
            centre[k] += a * (triangles[t, 0] + triangles[t, 1] + triangles[t, 2]) / 3.0
            area += a
        if area > 0.0:
            centre[k] /= area
        else:
            centre[k] = triangles[lo[k], 0]
        r = 0.0
        for t in range(lo[k], hi[k]):
            for c in range(3):
                d = triangles[t, c] - centre[k]
                r = max(r, np.sqrt(d @ d))
        radius[k] = r
    return centre, radius, dipole


@njit(cache=True, nogil=True, parallel=True)
def fast_winding_numbers(points, triangles, lo, hi, left, right, centre, radius, dipole, beta):  # type: ignore[no-untyped-def]
    """Winding numbers at ``points`` through the tree of :class:`WindingTree`."""
    out = np.empty(points.shape[0])
    four_pi = 4.0 * np.pi
    for p in prange(points.shape[0]):
        x, y, z = points[p, 0], points[p, 1], points[p, 2]
        stack = np.empty(128, np.int64)
        stack[0], top, total = 0, 0, 0.0
        while top >= 0:
            k = stack[top]
            top -= 1
            dx, dy, dz = centre[k, 0] - x, centre[k, 1] - y, centre[k, 2] - z
            d = np.sqrt(dx * dx + dy * dy + dz * dz)
            if d > beta * radius[k]:
                total += (dx * dipole[k, 0] + dy * dipole[k, 1] + dz * dipole[k, 2]) / (four_pi * d * d * d)
            elif left[k] < 0:
                for t in range(lo[k], hi[k]):
                    total += solid_angle(x, y, z, triangles, t) / four_pi
            else:
                stack[top + 1], stack[top + 2] = left[k], right[k]
                top += 2
        out[p] = total
    return out
