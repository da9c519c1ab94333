"""The 3D Delaunay tetrahedralisation of a surface sample and its Voronoi facets.

Step 2 of Algorithm 5 (paper 001). The Voronoi vertices are the circumcentres
of the Delaunay tetrahedra; the Voronoi facet dual to a Delaunay edge ``(i, j)``
is the polygon of the circumcentres of the tetrahedra around that edge, in
cyclic order around it (found by walking across shared faces). Every point of that facet is equidistant from
samples ``i`` and ``j`` and closer to them than to any other sample, so its
contact set contains both: its diameter is at least ``|p_i - p_j|``.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from medialaxis.mesh._voronoi_kernels import all_edge_rings
from medialaxis.mesh.delaunay import delaunay_tetrahedra

__all__ = ["Tetrahedralisation", "tetrahedralise", "circumspheres", "edge_rings", "TET_EDGES"]

#: Local vertex pairs of the six edges of a tetrahedron, and the two other vertices.
TET_EDGES = np.array([(0, 1, 2, 3), (0, 2, 1, 3), (0, 3, 1, 2), (1, 2, 0, 3), (1, 3, 0, 2), (2, 3, 0, 1)], np.int64)


@dataclasses.dataclass(frozen=True)
class Tetrahedralisation:
    """Delaunay tetrahedra of a point set with their circumspheres.

    Attributes
    ----------
    points : (p, 3) float64 ndarray
    simplices : (t, 4) int64 ndarray
    centres : (t, 3) float64 ndarray
        Circumcentres (Voronoi vertices); see :func:`circumspheres` for flat tetrahedra.
    radii : (t,) float64 ndarray
        Circumradii (``inf`` where undefined).
    longest : (t,) float64 ndarray
        Longest edge of each tetrahedron.
    neighbors : (t, 4) int64 ndarray
        Tetrahedron opposite each vertex (-1 on the hull).
    """

    points: np.ndarray
    simplices: np.ndarray
    centres: np.ndarray
    radii: np.ndarray
    longest: np.ndarray
    neighbors: np.ndarray


def circumspheres(points: np.ndarray, simplices: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Circumcentres ``(t, 3)`` and circumradii ``(t,)`` of tetrahedra.

    Flat tetrahedra (zero volume) get the circumcentre of their first three
    points (on the line of Voronoi vertices they span); fully degenerate
    ones get ``nan`` centres and ``inf`` radii.
    """
    a = points[simplices[:, 0]]
    u = points[simplices[:, 1]] - a
    v = points[simplices[:, 2]] - a
    w = points[simplices[:, 3]] - a
    vw, wu, uv = np.cross(v, w), np.cross(w, u), np.cross(u, v)
    det = 2.0 * np.einsum("ij,ij->i", u, vw)
    num = (u * u).sum(1)[:, None] * vw + (v * v).sum(1)[:, None] * wu + (w * w).sum(1)[:, None] * uv
    scale = np.maximum(np.abs(u).max(1), np.abs(w).max(1)) ** 3
    flat = np.abs(det) <= 1e-12 * np.maximum(scale, 1e-300)
    with np.errstate(divide="ignore", invalid="ignore"):
        offset = num / det[:, None]
    if flat.any():
        # Co-planar (co-circular) points: the Voronoi vertex lies on the line
        # through their circle's centre; take that centre.
        uf, vf = u[flat], v[flat]
        n = np.cross(uf, vf)
        nn = np.maximum((n * n).sum(1), 1e-300)[:, None]
        offset[flat] = (np.cross(n, uf) * (vf * vf).sum(1)[:, None] + np.cross(vf, n) * (uf * uf).sum(1)[:, None]) / (
            2.0 * nn
        )
        degenerate = flat & ~np.all(np.isfinite(offset), axis=1)
        offset[degenerate] = np.nan
    radii = np.linalg.norm(offset, axis=1)
    radii[~np.isfinite(radii)] = np.inf
    return a + offset, radii


def tetrahedralise(points: np.ndarray) -> Tetrahedralisation:
    """Delaunay tetrahedralisation with circumspheres and neighbours.

    The tetrahedra come from :func:`~medialaxis.mesh.delaunay.delaunay_tetrahedra`
    (compiled Bowyer-Watson insertion with exact predicates on a joggled
    copy of the points: samples of planes and spheres are highly degenerate);
    the circumspheres are computed from the exact points. 139k samples of a
    100k-vertex bumpy torus take about 0.9 s; SciPy's Qhull (``QJ``, Morton
    order) took 5.5-7.7 s for the same triangulation (``benchmarks/bench_delaunay.py``).

    Raises
    ------
    ComputationError
        Fewer than 5 distinct points, or all of them coplanar.
    """
    points = np.ascontiguousarray(points, np.float64)
    simplices, neighbors, _ = delaunay_tetrahedra(points)
    centres, radii = circumspheres(points, simplices)
    p = points[simplices]
    longest = np.zeros(len(simplices))
    for i, j, _, _ in TET_EDGES:
        longest = np.maximum(longest, np.linalg.norm(p[:, i] - p[:, j], axis=1))
    return Tetrahedralisation(points, simplices, centres, radii, longest, neighbors)


def edge_rings(
    dt: Tetrahedralisation, tets: np.ndarray, min_length: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Voronoi facets dual to the Delaunay edges of ``tets`` at least ``min_length`` long.

    Parameters
    ----------
    dt : Tetrahedralisation
    tets : (s,) int64 ndarray
        The tetrahedra to consider. A facet is returned when the tetrahedron
        of lowest index around its edge is in ``tets``: every facet of an
        edge at least ``min_length`` long when ``tets`` holds all tetrahedra
        with such an edge.
    min_length : float

    Returns
    -------
    edge_ij : (e, 2) int64 ndarray
        Sample indices of each bounded facet's Delaunay edge (hull edges are dropped).
    ring_ptr : (e + 1,) int64 ndarray
    ring_tets : (r,) int64 ndarray
        Tetrahedra of facet ``k`` in angular order around its edge:
        ``ring_tets[ring_ptr[k]:ring_ptr[k + 1]]``.
    length : (e,) float64 ndarray
        Length of each facet's Delaunay edge (the contact-set lower bound).
    """
    tets = np.sort(np.asarray(tets, np.int64))
    edge_ij, ring_ptr, ring, length = all_edge_rings(dt.simplices, dt.neighbors, dt.points, tets, float(min_length))
    # in the order of the edges (the facets of a sample come together: output files compress better)
    order = np.argsort(edge_ij[:, 0] * len(dt.points) + edge_ij[:, 1])
    counts = np.diff(ring_ptr)[order]
    new_ptr = np.r_[0, np.cumsum(counts)].astype(np.int64)
    rows = np.repeat(ring_ptr[:-1][order] - new_ptr[:-1], counts) + np.arange(new_ptr[-1])
    return edge_ij[order], new_ptr, ring[rows], length[order]

