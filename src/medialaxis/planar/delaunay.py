"""Delaunay triangulation of boundary samples and its Voronoi (circumcentre) data.

The samples, scaled to the unit square and jittered by a deterministic
``1e-9`` of the extent (points on a closed curve are nearly co-circular; the
jitter removes the degeneracy), are triangulated inside four far corners by
the compiled Bowyer-Watson kernel of :mod:`medialaxis.planar._delaunay_kernels`
(about 0.4 microseconds a point, against 2 to 10 for SciPy's Qhull here).
Where rounding makes the kernel's decisions inconsistent it gives up and
SciPy's Qhull (BSD licence, always available with SciPy) triangulates
instead. The adaptive sampling keeps the point count to what the axis
needs, so even million-vertex polygons reach the triangulation with a few
ten thousand points.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from scipy.spatial import Delaunay, QhullError

from medialaxis.errors import ComputationError
from medialaxis.planar._delaunay_kernels import delaunay_2d
from medialaxis.planar._kernels import circumcircles_kernel

__all__ = ["Triangulation", "triangulate", "edge_keys", "jitter"]

#: Far corners (counter-clockwise) around the unit square of the scaled
#: samples: the hull is a big square, so collinear boundary samples are never
#: hull points (Qhull would join them by zero-area slivers).
FAR_CORNERS = np.array([[-10.0, -10.0], [11.0, -10.0], [11.0, 11.0], [-10.0, 11.0]])


@dataclasses.dataclass(frozen=True)
class Triangulation:
    """Triangles of a Delaunay triangulation with their circumcircles.

    Attributes
    ----------
    points : (N, 2) float ndarray
        The (unjittered) sample points.
    simplices : (T, 3) int ndarray
    neighbors : (T, 3) int ndarray
        ``neighbors[t, k]`` shares the edge opposite vertex ``k``; -1 on the hull.
    centers : (T, 2) float ndarray
        Circumcentres (the Voronoi vertices).
    radii : (T,) float ndarray
        Circumradii.
    """

    points: np.ndarray
    simplices: np.ndarray
    neighbors: np.ndarray
    centers: np.ndarray
    radii: np.ndarray


def edge_keys(a: np.ndarray, b: np.ndarray, n: int) -> np.ndarray:
    """Order-independent integer key of the edges ``(a, b)`` over ``n`` points."""
    lo = np.minimum(a, b).astype(np.int64)
    hi = np.maximum(a, b).astype(np.int64)
    return lo * n + hi


def circumcircles(p: np.ndarray, simplices: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Circumcentres and radii of triangles (computed relative to the first vertex).

    The pipeline runs its compiled twin, :func:`medialaxis.planar._kernels.circumcircles_kernel`.
    """
    a = p[simplices[:, 0]]
    b = p[simplices[:, 1]] - a
    c = p[simplices[:, 2]] - a
    d = 2.0 * (b[:, 0] * c[:, 1] - b[:, 1] * c[:, 0])
    b2 = (b**2).sum(1)
    c2 = (c**2).sum(1)
    with np.errstate(divide="ignore", invalid="ignore"):
        ux = (c[:, 1] * b2 - b[:, 1] * c2) / d
        uy = (b[:, 0] * c2 - c[:, 0] * b2) / d
    centre = np.c_[ux, uy]
    radius = np.hypot(ux, uy)
    flat = ~np.isfinite(radius)
    if flat.any():  # collinear: use the midpoint of the longest side
        tri = p[simplices[flat]]
        sides = np.stack([tri[:, 1] - tri[:, 2], tri[:, 2] - tri[:, 0], tri[:, 0] - tri[:, 1]], 1)
        k = np.argmax((sides**2).sum(2), axis=1)
        rows = np.arange(len(k))
        mid = 0.5 * (tri[rows, (k + 1) % 3] + tri[rows, (k + 2) % 3]) - a[flat]
        centre[flat] = mid
        radius[flat] = 0.5 * np.sqrt((sides[rows, k] ** 2).sum(1))
    return centre + a, radius


def _qhull(work: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Triangles and neighbours of ``work`` by SciPy's Qhull, without those at the far corners."""
    try:
        tri = Delaunay(np.vstack([work, FAR_CORNERS]))
    except QhullError as exc:
        raise ComputationError(f"Delaunay triangulation failed: {str(exc).splitlines()[0]}") from exc
    simplices = tri.simplices.astype(np.int64)
    neighbors = tri.neighbors.astype(np.int64)
    real = (simplices < len(work)).all(axis=1)
    new_index = np.full(len(simplices), -1, np.int64)
    new_index[real] = np.arange(int(real.sum()))
    simplices = simplices[real]
    neighbors = neighbors[real]
    return simplices, np.where(neighbors >= 0, new_index[neighbors], -1)


#: The jitter of seed 0, first rows (a generator's first draws do not depend on how many follow).
_JITTER: list[np.ndarray] = [np.empty((0, 2))]


def jitter(n: int, seed: int = 0) -> np.ndarray:
    """``np.random.default_rng(seed).uniform(-1e-9, 1e-9, (n, 2))``, kept for seed 0."""
    if seed != 0:
        return np.random.default_rng(seed).uniform(-1e-9, 1e-9, (n, 2))
    if len(_JITTER[0]) < n:
        _JITTER[0] = np.random.default_rng(0).uniform(-1e-9, 1e-9, (max(n, 2 * len(_JITTER[0]), 4096), 2))
    return _JITTER[0][:n]


def triangulate(points: np.ndarray, *, seed: int = 0) -> Triangulation:
    """Delaunay triangulation of ``points`` (jittered by 1e-9 of their extent).

    Triangles touching the four helper points far outside are dropped.

    References
    ----------
    .. [1] A. Bowyer, "Computing Dirichlet tessellations", The Computer Journal 24(2):162-166,
           1981. doi:10.1093/comjnl/24.2.162
    .. [2] D. F. Watson, "Computing the n-dimensional Delaunay tessellation with application to
           Voronoi polytopes", The Computer Journal 24(2):167-172, 1981.
           doi:10.1093/comjnl/24.2.167
    .. [3] N. Amenta, S. Choi, G. Rote, "Incremental constructions con BRIO", Proc. 19th
           Symposium on Computational Geometry, 211-219, 2003. doi:10.1145/777792.777824
    """
    if len(points) < 3:
        raise ComputationError(f"need at least 3 boundary samples, got {len(points)}")
    lo = points.min(0)
    extent = float((points.max(0) - lo).max())
    if extent <= 0:
        raise ComputationError("all boundary samples coincide")
    work = (points - lo) / extent + jitter(len(points), seed)
    found = delaunay_2d(np.vstack([work, FAR_CORNERS]))
    simplices, neighbors = found if found is not None else _qhull(work)
    centers, radii = circumcircles_kernel(np.ascontiguousarray(points, dtype=np.float64), simplices)
    return Triangulation(points, simplices, neighbors, centers, radii)
