"""Cycles of the medial complex that the solid lacks, cut where they run through points that are not medial.

The dual complex of the inner Delaunay tetrahedra has the topology of their
union, and that union can gain a handle where nearly flat tetrahedra on the
surface are taken in and out by turns: a uv ellipsoid whose vertices were
moved along it by a tenth of their shortest edge packs 224 vertices into a
circle 0.014 across at each pole, and got Betti numbers (1, 4, 0) for
(1, 0, 0). The homotopy-preserving collapse then keeps each extra cycle as a
curve from the medial sheet up to the surface and back, through the
circumcentres of flat tetrahedra, thousands of units outside the solid.

When the complex has more cycles than the solid (its Betti number ``b1``
from the mesh's Euler characteristic), :func:`cut_stray_cycles` cuts such
curves: a curve edge at a point that is not a medial point (its
circumcentre outside the solid, beyond the mesh's diagonal, or nearer the
surface than its own samples by more than the sampling error allows), or
at a ball touching one side only (its four contacts within 60 degrees as
seen from its centre: the balls on the polar axis of that ellipsoid, each
over four samples of one ring), that closes a cycle of the 1-skeleton is
removed, one per extra cycle, and the curve it
opens is pulled back to the sheet (free ends removed, an elementary collapse
at a time). An edge that closes a cycle is not a bridge, so each cut lowers
``b1`` by one and leaves the components and the voids as they are; edges
between medial points are never cut.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from scipy import sparse
from scipy.sparse import csgraph

from medialaxis.mesh.medial._collapse_kernels import complement_components

__all__ = ["cut_stray_cycles", "complement_voids", "without_stray_cycles"]


def _root(parent: np.ndarray, a: int) -> int:
    while parent[a] != a:
        parent[a] = parent[parent[a]]
        a = int(parent[a])
    return a


def cut_stray_cycles(
    n_points: int, faces: np.ndarray, edges: np.ndarray, n_curve: int, stray: np.ndarray, excess: int
) -> tuple[np.ndarray, int, np.ndarray, int]:
    """Cut up to ``excess`` cycles through stray points and pull the opened curves back.

    Parameters
    ----------
    n_points : int
    faces : (k, 3) int ndarray
    edges : (m, 2) int ndarray
        Curve pieces first (``n_curve`` of them), then the sheets' border edges.
    n_curve : int
    stray : (n_points,) bool ndarray
        Points that are not medial points.
    excess : int
        Cycles to cut at most (the complex's ``b1`` less the solid's).

    Returns
    -------
    edges : (m', 2) int64 ndarray
        The edges left, curve pieces first.
    n_curve : int
    keep : (n_points,) bool ndarray
        The points left: all but those of the removed curve pieces that no
        face or other edge uses.
    n_cut : int
        Cycles cut.

    Examples
    --------
    A triangle with a loop of three curve edges through a stray point 4:

    >>> import numpy as np
    >>> faces = np.array([[0, 1, 2]])
    >>> edges = np.array([[2, 3], [3, 4], [4, 2], [0, 1]])
    >>> stray = np.array([False, False, False, False, True])
    >>> kept, n_curve, keep, n_cut = cut_stray_cycles(5, faces, edges, 3, stray, 1)
    >>> kept.tolist(), n_curve, keep.tolist(), n_cut
    ([[0, 1]], 0, [True, True, True, False, False], 1)
    """
    edges = np.asarray(edges, np.int64).reshape(-1, 2)
    keep_points = np.ones(n_points, bool)
    curve = edges[:n_curve]
    bad = np.flatnonzero(stray[curve].any(axis=1))
    if excess <= 0 or not len(bad):
        return edges, n_curve, keep_points, 0
    faces = np.asarray(faces, np.int64).reshape(-1, 3)
    good = np.ones(n_curve, bool)
    good[bad] = False
    joined = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], edges[n_curve:], curve[good]])
    graph = sparse.coo_matrix((np.ones(len(joined)), (joined[:, 0], joined[:, 1])), shape=(n_points, n_points))
    n_labels, label = csgraph.connected_components(graph, directed=False)
    parent = np.arange(n_labels)
    # edges with one stray end join first; those between two stray points are cut first
    bad = bad[np.argsort(stray[curve[bad]].sum(axis=1), kind="stable")]
    alive = np.ones(n_curve, bool)
    n_cut = 0
    opened = np.zeros(n_points, bool)
    for e in bad.tolist():
        a, b = _root(parent, int(label[curve[e, 0]])), _root(parent, int(label[curve[e, 1]]))
        if a != b:
            parent[a] = b
        elif n_cut < excess:
            alive[e] = False
            opened[curve[e]] = True
            n_cut += 1
    fixed = np.zeros(n_points, bool)  # points a face or a border edge holds
    fixed[faces.ravel()] = True
    fixed[edges[n_curve:].ravel()] = True
    still = np.zeros(n_points, bool)  # points left, though no edge holds them any more
    while True:  # free ends of the opened curves, one elementary collapse after another
        degree = np.bincount(curve[alive].ravel(), minlength=n_points)
        free = opened & ~fixed & (degree == 1)
        loose = alive & free[curve].any(axis=1)
        if not loose.any():
            break
        alive &= ~loose
        opened[curve[loose].ravel()] = True
        # a path alone collapses from both ends at once: where they meet (a point, or an edge free at
        # both ends) one point of the component is kept
        still[curve[loose & free[curve].all(axis=1), 0]] = True
        ends = np.zeros(n_points, bool)
        ends[curve[loose].ravel()] = True
        still |= ends & ~free & (np.bincount(curve[alive].ravel(), minlength=n_points) == 0)
    removed = np.zeros(n_points, bool)
    removed[curve[~alive].ravel()] = True
    still[curve[alive].ravel()] = True
    keep_points = ~removed | fixed | still
    return np.concatenate([curve[alive], edges[n_curve:]]), int(alive.sum()), keep_points, n_cut


def complement_voids(simplices: np.ndarray, neighbors: np.ndarray, facet_ij: np.ndarray) -> int:
    """``b2`` of the union of the kept Voronoi facets: the bounded components of its complement.

    By Alexander duality (a compact set in the 3-sphere has as many voids as
    its complement has components, less one), without the elimination over
    GF(2) that a complex with voids makes costly (gigabytes on a scanned ogre
    with four cavities). The complement is the union of the samples' Voronoi
    cells glued through the facets not kept: two samples are in one
    component when a chain of Delaunay edges whose facets are not kept joins
    them; the cells of the samples on the convex hull reach infinity.

    References
    ----------
    .. [1] A. Hatcher, *Algebraic Topology*, Cambridge University Press, 2002, Theorem 3.44
           (Alexander duality). ISBN 978-0-521-79540-1.

    Examples
    --------
    Four samples around a fifth one inside them, all its facets kept (its
    cell closed):

    >>> import numpy as np
    >>> from medialaxis.mesh.medial.voronoi_diagram import tetrahedralise
    >>> dt = tetrahedralise(np.array([[0, 0, 0], [4, 0, 0], [0, 4, 0], [0, 0, 4], [1, 1, 1.0]]))
    >>> complement_voids(dt.simplices, dt.neighbors, np.array([[0, 4], [1, 4], [2, 4], [3, 4]]))
    1
    >>> complement_voids(dt.simplices, dt.neighbors, np.array([[0, 4], [1, 4], [2, 4]]))
    0
    """
    simplices = np.ascontiguousarray(simplices, np.int64)
    n = int(simplices.max()) + 1
    ends = np.sort(np.asarray(facet_ij, np.int64).reshape(-1, 2), axis=1)
    ends = ends[np.argsort(ends[:, 0], kind="stable")]
    kept_ptr = np.zeros(n + 1, np.int64)
    np.cumsum(np.bincount(ends[:, 0], minlength=n), out=kept_ptr[1:])
    return int(complement_components(simplices, np.ascontiguousarray(neighbors, np.int64), kept_ptr,
                                     np.ascontiguousarray(ends[:, 1]))) - 1


def without_stray_cycles(
    used: np.ndarray, faces: np.ndarray, edges: np.ndarray, n_curve: int, stray: np.ndarray,
    solid: tuple[int, int, int], voids: Callable[[], int], chi: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, int, int]:
    """The complex over ``used`` with the cycles through ``stray`` points that the solid lacks cut.

    Looks at the Betti numbers only where the complex's Euler characteristic
    ``chi`` differs from the solid's ``(b0, b1, b2)``: ``b2`` from ``voids()``
    (:func:`complement_voids`), ``b0`` from the edges, ``b1`` from the Euler
    characteristic. Returns ``used``, ``faces``, ``edges`` (renumbered),
    ``n_curve`` and the number of cycles cut (each raises ``chi`` by one).
    """
    if chi == solid[0] - solid[1] + solid[2]:
        return used, faces, edges, n_curve, 0
    pairs = np.concatenate([np.asarray(faces, np.int64)[:, [0, 1]], np.asarray(faces, np.int64)[:, [1, 2]], edges])
    graph = sparse.coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(len(used), len(used)))
    b0 = csgraph.connected_components(graph, directed=False)[0]
    excess = b0 + voids() - chi - solid[1]
    kept, n_kept, keep, n_cut = cut_stray_cycles(len(used), faces, edges, n_curve, stray, excess)
    if not n_cut:
        return used, faces, edges, n_curve, 0
    new_index = np.cumsum(keep) - 1
    return used[keep], new_index[faces], new_index[kept], n_kept, n_cut
