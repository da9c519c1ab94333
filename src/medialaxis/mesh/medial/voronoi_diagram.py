"""The 3D Delaunay tetrahedralisation of a surface sample and its Voronoi facets.

Step 2 of Algorithm 5 of Boissonnat, Wormser and Yvinec ("Curved Voronoi
diagrams", section 2.7; docs/references.md). The Voronoi vertices are the circumcentres
of the Delaunay tetrahedra; the Voronoi facet dual to a Delaunay edge ``(i, j)``
is the polygon of the circumcentres of the tetrahedra around that edge, in
cyclic order around it (found by walking across shared faces). Every point of that facet is equidistant from
samples ``i`` and ``j`` and closer to them than to any other sample, so its
contact set contains both: its diameter is at least ``|p_i - p_j|``.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from medialaxis.errors import ResourceLimitError
from medialaxis.mesh.medial._ring_kernels import all_edge_rings
from medialaxis.mesh.medial._voronoi_kernels import tet_geometry
from medialaxis.mesh.sample.delaunay import delaunay_tetrahedra

__all__ = ["Tetrahedralisation", "tetrahedralise", "edge_rings"]


@dataclasses.dataclass(frozen=True)
class Tetrahedralisation:
    """Delaunay tetrahedra of a point set with their circumspheres.

    Attributes
    ----------
    points : (p, 3) float64 ndarray
    simplices : (t, 4) int64 ndarray
    centres : (t, 3) float64 ndarray
        Circumcentres (Voronoi vertices); see
        :func:`~medialaxis.mesh.medial._voronoi_kernels.tet_geometry` for flat tetrahedra.
    radii : (t,) float64 ndarray
        Circumradii (``inf`` where undefined).
    longest : (t,) float64 ndarray
        Longest edge of each tetrahedron.
    volume : (t,) float64 ndarray
        Volume of each tetrahedron.
    neighbors : (t, 4) int64 ndarray
        Tetrahedron opposite each vertex (-1 on the hull).
    """

    points: np.ndarray
    simplices: np.ndarray
    centres: np.ndarray
    radii: np.ndarray
    longest: np.ndarray
    volume: np.ndarray
    neighbors: np.ndarray


def tetrahedralise(points: np.ndarray) -> Tetrahedralisation:
    """Delaunay tetrahedralisation with circumspheres and neighbours.

    The tetrahedra come from :func:`~medialaxis.mesh.sample.delaunay.delaunay_tetrahedra`
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
    centres, radii, longest, volume = tet_geometry(points, simplices)
    return Tetrahedralisation(points, simplices, centres, radii, longest, volume, neighbors)


def edge_rings(
    dt: Tetrahedralisation, tets: np.ndarray | None, min_length: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Voronoi facets dual to the Delaunay edges of ``tets`` at least ``min_length`` long.

    Parameters
    ----------
    dt : Tetrahedralisation
    tets : (s,) int64 ndarray or None
        The tetrahedra to consider (None: all). A facet is returned when the tetrahedron
        of lowest index around its edge is in ``tets``: every facet of an
        edge at least ``min_length`` long when ``tets`` holds all tetrahedra
        with such an edge.
    min_length : float

    Returns
    -------
    edge_ij : (e, 2) int64 ndarray
        Sample indices of each bounded facet's Delaunay edge (hull edges are dropped), ascending.
    ring_ptr : (e + 1,) int64 ndarray
    ring_tets : (r,) int32 ndarray
        Tetrahedra of facet ``k`` in angular order around its edge:
        ``ring_tets[ring_ptr[k]:ring_ptr[k + 1]]``.
    length : (e,) float64 ndarray
        Length of each facet's Delaunay edge (the contact-set lower bound).
    """
    if len(dt.simplices) >= 2**28:  # the ring kernels' int32: triangles 4 * t + k, and 6 t ring entries
        raise ResourceLimitError(f"{len(dt.simplices):,} tetrahedra: at most {2**28 - 1:,} are supported")
    every = tets is None
    tets = np.zeros(0, np.int64) if tets is None else np.asarray(tets, np.int64)
    if len(tets) > 1 and not bool((tets[1:] > tets[:-1]).all()):  # flatnonzero's are in order: no sorted copy
        tets = np.sort(tets, kind="stable")
    return all_edge_rings(dt.simplices, dt.neighbors, dt.points, tets, every, float(min_length))  # type: ignore[no-any-return]

