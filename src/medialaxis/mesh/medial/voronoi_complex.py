"""The medial complex: Voronoi facets inside the solid, lambda-filtered, topology kept.

Step 3 of Algorithm 5 of Boissonnat, Wormser, Yvinec ("Curved Voronoi diagrams", section 2.7;
docs/references.md) removes the Voronoi facets whose contact set is narrower than lambda.
Done literally (``topology="lambda"``) the result carries the sampling noise as small holes
and islands where the contact width crosses lambda. ``topology="preserve"`` (the default) starts
instead from the dual complex ``D`` of the inner Delaunay tetrahedra
(vertices: tetrahedra whose circumcentre is inside; edges: triangles shared
by two of them; facets: Delaunay edges all of whose tetrahedra are inside).
``D`` is homotopy equivalent to the union of the inner tetrahedra, which
approximates the solid, when that union is a 3-manifold: flat tetrahedra on
the surface, whose centroids fall a hair inside or outside, can pinch it
along an edge or at a point and add cycles that the solid does not have, so
the inner set is first unpinched at its points (:func:`unpinch`), and the
Voronoi cells of samples buried inside it, 3-cells ``D`` lacks, are opened
(:func:`open_cells`). ``D`` is then collapsed: facets narrower than lambda
are removed, shortest first, only through a free side (an elementary
collapse), then dangling curve pieces are removed. Every facet of at least
lambda stays; the facets narrower than lambda that remain are those needed
to keep the homotopy type (filling holes of the lambda set) and are counted
in ``metadata["n_filling_faces"]``.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Literal

import numpy as np
from scipy import sparse

from medialaxis._jit import Beside
from medialaxis.errors import InvalidInputError
from medialaxis.mesh.medial._collapse_kernels import (
    collapse_facets,
    collapse_free_sides,
    lost_components,
    spanning_forest_edges,
)
from medialaxis.mesh.medial._ring_kernels import (
    flagged_sides,
    gather_rings,
    odd_sides,
    ring_all,
    ring_max,
    ring_side_ids,
    ring_side_slots,
)
from medialaxis.mesh.medial.inner_set import CAVITY_SHARE, unpinch
from medialaxis.mesh.medial.voronoi_diagram import Tetrahedralisation, edge_rings
from medialaxis.mesh.sample._rows import radix_argsort

__all__ = ["MedialComplex", "medial_complex", "fan_triangles", "unpinch", "open_cells", "euler_characteristic", "TOPOLOGY_MODES"]

TOPOLOGY_MODES = ("preserve", "lambda")
#: A facet narrower than lambda spans a thin part when its contact points
#: are at least this many sampling spacings apart ...
THIN_SPACINGS = 2.5
#: ... and its Delaunay edge is at least this many times the largest
#: circumradius of its Voronoi vertices: 2 sin(70 deg), contact points 140
#: degrees or more apart (a plate: 180; a fin into a right-angled edge: 90).
THIN_SPAN = 1.88
@dataclasses.dataclass(frozen=True)
class MedialComplex:
    """A medial complex over Delaunay tetrahedra (its points are their circumcentres).

    Attributes
    ----------
    tets : (n,) int64 ndarray
        Tetrahedron of each point.
    faces : (k, 3) int64 ndarray
        Triangles over the points (fans of the kept facets).
    face_length : (k,) float64 ndarray
        Delaunay edge length (contact-set width) of each triangle's facet.
    face_certified : (k,) bool ndarray
        The facet is at least lambda wide and all its vertices are inside
        (a facet of Algorithm 5); the others are kept for topology only.
    face_thin : (k,) bool ndarray
        The facet spans a thin part (kept whatever lambda; ``THIN_SPACINGS``).
    edges : (m, 2) int64 ndarray
        Curve pieces (no facet), then facet sides on the surface boundary or
        where three or more facets meet.
    n_curve_edges : int
        How many of ``edges`` are curve pieces (they come first).
    facet_ij : (f, 2) int64 ndarray
        Delaunay edge (sample pair) of each kept facet.
    """

    tets: np.ndarray
    faces: np.ndarray
    face_length: np.ndarray
    face_certified: np.ndarray
    face_thin: np.ndarray
    edges: np.ndarray
    n_curve_edges: int
    facet_ij: np.ndarray


def euler_characteristic(n_points: int, faces: np.ndarray, edges: np.ndarray | None = None) -> int:
    """Euler characteristic ``V - E + F`` of a simplicial 2-complex.

    ``E`` counts the distinct edges of the triangles and of ``edges``.
    """
    f = np.asarray(faces, np.int64).reshape(-1, 3)
    e = np.asarray(edges if edges is not None else np.empty((0, 2)), np.int64).reshape(-1, 2)
    u = np.concatenate([f[:, 0], f[:, 1], f[:, 2], e[:, 0]])
    v = np.concatenate([f[:, 1], f[:, 2], f[:, 0], e[:, 1]])
    n = max(int(n_points), int(max(u.max(), v.max())) + 1 if len(u) else 1)
    n_edges = sparse.csr_matrix((np.ones(len(u), bool), (np.minimum(u, v), np.maximum(u, v))), shape=(n, n)).nnz  # 0.2 -> 0.06 s
    return int(n_points - n_edges + len(f))


def fan_triangles(ring_ptr: np.ndarray, ring_tets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Fan triangulation of each ring polygon from its first vertex.

    Returns
    -------
    tris : (k, 3) int64 ndarray
    owner : (k,) int64 ndarray
        Ring of each triangle.
    """
    counts = np.diff(ring_ptr)
    n_tri = np.maximum(counts - 2, 0)
    owner = np.repeat(np.arange(len(counts)), n_tri)
    step = np.arange(n_tri.sum()) - np.repeat(np.cumsum(n_tri) - n_tri, n_tri)
    base = ring_ptr[owner]
    return np.c_[ring_tets[base], ring_tets[base + step + 1], ring_tets[base + step + 2]], owner


def _select(ring_ptr: np.ndarray, ring_tets: np.ndarray, keep: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return gather_rings(ring_ptr, ring_tets, np.flatnonzero(keep))


def open_cells(
    dt: Tetrahedralisation, inner: np.ndarray, edge_ij: np.ndarray, facet: np.ndarray, length: np.ndarray
) -> np.ndarray:
    """Facets to drop so that the Voronoi cells of samples buried in the inner set are open.

    The dual complex holds the 0-, 1- and 2-cells dual to the inner
    tetrahedra, the triangles and the edges inside their union. A sample
    point inside the union (every triangle at it is shared by two inner
    tetrahedra: a flat stack on the surface, or a thin part sampled too
    coarsely, covered its sample) is dual to a 3-cell, its Voronoi cell,
    which the complex lacks: the cell's facets then bound a void that the
    solid does not have. Collapsing each such 3-cell through one facet puts
    it back, keeping the union's homotopy type: a spanning forest over the
    buried points, grown from the points on the union's boundary along the
    facets, shortest Delaunay edge first (Kruskal); the facet of each tree
    edge is dropped.

    Parameters
    ----------
    dt : Tetrahedralisation
    inner : (t,) bool ndarray
    edge_ij : (e, 2) int64 ndarray
        Delaunay edge of each facet.
    facet : (e,) bool ndarray
        Facets of the complex (every tetrahedron around the edge inner).
    length : (e,) float64 ndarray
        Delaunay edge lengths.

    Returns
    -------
    (e,) bool ndarray
        The facets to drop.
    """
    n = len(dt.points)
    simplices, neighbors = dt.simplices, dt.neighbors
    on_border = np.zeros(n, bool)
    covered = np.zeros(n, bool)
    for k in range(4):  # a column at a time: no copy of the inner tetrahedra's corners (87 MB on a scanned ogre)
        covered[simplices[inner, k]] = True
        opposite = neighbors[:, k]
        open_side = np.flatnonzero(inner & ((opposite < 0) | ~inner[np.maximum(opposite, 0)]))
        for j in range(4):
            if j != k:
                on_border[simplices[open_side, j]] = True
    drop = np.zeros(len(edge_ij), bool)
    buried = covered & ~on_border
    if not buried.any():
        return drop
    candidates = np.flatnonzero(facet & (buried[edge_ij[:, 0]] | buried[edge_ij[:, 1]]))
    candidates = candidates[np.argsort(length[candidates], kind="stable")]
    parent = np.where(buried, np.arange(n), n)  # n: the border, one set
    parent = np.append(parent, n)
    spanning_forest_edges(parent, edge_ij, candidates, drop)  # the border (n) stays a root
    return drop


def _last_points(root: np.ndarray, dt: Tetrahedralisation, centre_inside: Callable[[np.ndarray], np.ndarray],
                 spacing: np.ndarray | None) -> np.ndarray:
    """One tetrahedron for each component of the inner union that the collapse left no facet or curve of.

    A part narrower than lambda everywhere (a small separate piece of an
    assembly: 5 of 14 on a scanned beast) collapses to a point, which is
    kept: the tetrahedron of the largest ball among those whose centre is a
    medial point inside, else the largest one. A component the sampling
    does not resolve is not kept: one whose longest edge is shorter than the
    sampling ``spacing`` at its points (8 tetrahedra 0.044 across between
    the nested shells of a scanned orc sampled 0.07 apart), or, as for
    cavities (``CAVITY_SHARE``), one holding at most that share of its
    longest edge cubed (slivers).
    """
    tets = np.flatnonzero(root >= 0)
    if not len(tets):
        return tets
    volume = np.zeros(len(root))
    reach = np.zeros(len(root))
    np.add.at(volume, root[tets], dt.volume[tets])
    np.maximum.at(reach, root[tets], dt.longest[tets])
    resolved = volume > CAVITY_SHARE * reach**3
    if spacing is not None:
        local = np.zeros(len(root))
        np.maximum.at(local, root[tets], spacing[dt.simplices[tets]].max(axis=1))
        resolved &= reach >= local
    tets = tets[resolved[root[tets]]]
    if not len(tets):
        return tets
    score = np.where(centre_inside(tets), dt.radii[tets], -1.0 / (1.0 + dt.volume[tets]))
    order = np.lexsort((-score, root[tets]))
    first = np.r_[True, root[tets[order]][1:] != root[tets[order]][:-1]]
    return tets[order[first]]


def _distinct(values: np.ndarray, n: int) -> np.ndarray:
    """``unique_ints(values)`` for values in ``[0, n)``, by a flag array (no sort of the millions of ring entries)."""
    flag = np.zeros(n, bool)
    flag[values] = True
    return np.flatnonzero(flag)


def _by_ends(ends: np.ndarray, n: int) -> np.ndarray:
    """Rows of ``ends`` (pairs of tetrahedra), each ascending, sorted by their first then second tetrahedron."""
    ends = np.sort(np.asarray(ends, np.int64), axis=1)
    return ends[np.argsort(ends[:, 0] * n + ends[:, 1])]


def medial_complex(
    dt: Tetrahedralisation,
    inner: np.ndarray,
    centre_inside: Callable[[np.ndarray], np.ndarray],
    lam: float,
    topology: Literal["preserve", "lambda"] = "preserve",
    spacing: np.ndarray | None = None,
    thick_pockets: Callable[[np.ndarray], None] | None = None,
) -> MedialComplex:
    """Build the medial complex from inner tetrahedra (see the module docstring).

    Parameters
    ----------
    dt : Tetrahedralisation
    inner : (t,) bool ndarray
        Tetrahedra whose centroid lies strictly inside the solid (their
        union is the solid, up to the sampling); used by ``"preserve"``.
    centre_inside : callable
        ``centre_inside(tets)``: bool ndarray, for the given tetrahedra,
        whether their circumcentre (Voronoi vertex) is a medial point inside
        the solid. Called only for the tetrahedra that matter (those of
        facets at least ``lam`` wide, or spanning a thin part; all those with
        an edge of at least ``lam`` for ``"lambda"``): the test is an exact
        closest-point query, and most tetrahedra need none.
    lam : float
        Smallest contact-set width (Delaunay edge length) of a kept facet.
    topology : {"preserve", "lambda"}
    spacing : (p,) float64 ndarray, optional
        Sampling spacing at each sample point. When given, a facet narrower
        than ``lam`` is kept as well if it spans a thin part: its contact
        points are at least ``THIN_SPACINGS`` spacings apart and nearly
        opposite as seen from its Voronoi vertices (Delaunay edge at least
        ``THIN_SPAN`` times the largest circumradius around it, an angle
        of about 140 degrees or more). Sheets of plates thinner than
        ``lam`` keep their balls; the spikes of the sampling noise (adjacent
        samples) and the fins into convex edges (contacts about 90 degrees
        apart) do not pass.
    thick_pockets : callable, optional
        Called with the thick pockets :func:`unpinch` fills
        (``inner_set.POCKET_FLAT``), if any: air the sample may not resolve.

    Returns
    -------
    MedialComplex
    """
    if topology not in TOPOLOGY_MODES:
        raise InvalidInputError(f"topology must be one of {TOPOLOGY_MODES}, got {topology!r}")
    n_tets = len(dt.simplices)
    medial = np.zeros(n_tets, bool)
    if topology == "lambda":
        tets = np.flatnonzero(dt.longest >= lam)
        medial[tets] = centre_inside(tets)
        edge_ij, ring_ptr, ring_tets, length = edge_rings(dt, tets, lam)
    else:  # the serial unpinching runs beside the parallel ring walks, which need none of it (0.3 s on the uv ellipsoid)
        thick = np.zeros(n_tets, bool)
        unpinched = Beside(unpinch, dt, inner, thick)
        edge_ij, ring_ptr, ring_tets, length = edge_rings(dt, None, 0.0)
        inner = unpinched.result() if len(ring_tets) else inner  # no inner edge: nothing to unpinch
        if thick_pockets is not None and thick.any():
            thick_pockets(np.flatnonzero(thick))
    member = medial if topology == "lambda" else inner
    keep = ring_all(ring_ptr, ring_tets, member) & (np.diff(ring_ptr) >= 3)
    if topology != "lambda":
        keep &= ~open_cells(dt, inner, edge_ij, keep, length)
    ring_ptr, ring_tets = _select(ring_ptr, ring_tets, keep)
    length, edge_ij = length[keep], edge_ij[keep]
    wide, thin = length >= lam, np.zeros(len(length), bool)
    if spacing is not None:
        local = np.maximum(spacing[edge_ij[:, 0]], spacing[edge_ij[:, 1]])
        ball = ring_max(ring_ptr, ring_tets, dt.radii)
        thin = (length >= THIN_SPACINGS * local) & (length >= THIN_SPAN * ball)
        wide |= thin
    curve = np.empty((0, 2), np.int64)
    if topology == "preserve":  # the exact queries run beside the work on the sides, which needs none of them
        tets = _distinct(ring_tets[np.repeat(wide, np.diff(ring_ptr))], n_tets)
        asked = Beside(centre_inside, tets)
        # Sides of D: triangles shared by two inner tetrahedra, as 4 * tet + face (the lower tetrahedron's face).
        slot, side_ends = flagged_sides(dt.neighbors, inner)
        facet_sides = ring_side_slots(ring_ptr, ring_tets, dt.neighbors, slot)  # the side after each ring entry
        n_sides = len(side_ends)
        # facets numbered by collapse order (length, then index): the collapse then reads them
        # nearly in sequence (1.7 -> 1.1 s on 1.5M facets); the result is the same
        by_length = radix_argsort(length.view(np.int64))  # stable; lengths >= 0 sort as their bits (0.15 -> 0.07 s)
        fptr, fsides = gather_rings(ring_ptr, facet_sides, by_length)
        del slot
        medial[tets] = asked.result()
    certified = wide & ring_all(ring_ptr, ring_tets, medial)
    if topology == "preserve":
        alive_sorted, side_alive = collapse_facets(fptr, fsides, n_sides, length[by_length], certified[by_length])
        del fptr, fsides  # ring-sized: freed before the next ones are made
        facet_alive = np.empty_like(alive_sorted)
        facet_alive[by_length] = alive_sorted
        side_used = np.zeros(n_sides, bool)
        side_used[facet_sides[np.repeat(facet_alive, np.diff(ring_ptr))]] = True
        del facet_sides
        side_alive = collapse_free_sides(side_alive, side_used, side_ends, n_tets)
        curve = _by_ends(side_ends[side_alive & ~side_used], n_tets)
        alive = facet_alive
    else:
        alive = certified
    ring_ptr, ring_tets = _select(ring_ptr, ring_tets, alive)
    side_id = ring_side_ids(ring_ptr, ring_tets, dt.neighbors)  # the triangle after each ring entry
    alone = np.zeros(0, np.int64)
    if topology == "preserve":  # the inner union's components the collapse emptied
        kept = np.zeros(n_tets, bool)
        kept[ring_tets] = True
        kept[curve.ravel()] = True
        alone = _last_points(lost_components(inner, side_ends, kept), dt, centre_inside, spacing)
    length, certified, thin = length[alive], certified[alive], thin[alive]
    tris, owner = fan_triangles(ring_ptr, ring_tets)
    border_ids = odd_sides(side_id, 4 * n_tets)
    border = _by_ends(np.c_[border_ids // 4, dt.neighbors.ravel()[border_ids]], n_tets)
    used = _distinct(np.concatenate([ring_tets, curve.ravel(), alone]), n_tets)
    new_index = np.full(n_tets, -1, np.int64)
    new_index[used] = np.arange(len(used))
    edges = new_index[np.concatenate([curve, border]).astype(np.int64)].reshape(-1, 2)
    return MedialComplex(used, new_index[tris].reshape(-1, 3), length[owner], certified[owner], thin[owner], edges,
                         len(curve), edge_ij[alive])
