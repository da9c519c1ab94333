"""Topology-preserving lambda pruning of the inner Voronoi axis.

A plain lambda cut (drop every Voronoi edge whose contact set is narrower than
``lam``, Algorithm 5 of Boissonnat, Wormser and Yvinec, "Curved Voronoi diagrams",
section 2.7) cuts the axis at necks narrower than ``lam`` and opens cycles, and on
raster silhouettes it keeps or drops noise branches depending on the rotation. Here an
edge is *significant* when

* its contact diameter is at least ``lam`` (the lambda-medial axis), and
* the boundary between its two contacts detours: the arc length between them
  exceeds their distance by at least ``detour`` times that distance and by at
  least ``2 * lam``. Contacts on different rings (around a hole) have an
  infinite arc.

The second test is scale invariant: a bump of height ``e`` between contacts
``c`` apart adds only about ``8 e**2 / (3 c)`` of arc, so pixel noise on a wide
part is dropped however large its contact diameter grows, while a real
protrusion (a leg, a corner) adds arc of the order of its length.

Insignificant edges are then removed only while they hang off the graph
(leaf peeling, :func:`medialaxis.core.graph.peel_leaves`), so the result
keeps the homotopy type of the raw axis: one component per connected shape,
one cycle per hole, and necks narrower than ``lam`` stay connected.

The detour test decides which branches exist; ``lam`` alone decides how far
they reach: from each endpoint the branch regrows along the raw axis (up to
the first fork) while the contact diameter stays
at least ``lam``, the contacts are not consecutive samples (the Voronoi
edge dual to a boundary piece runs to the boundary, not along the axis) and
the boundary still detours by a tenth of ``detour`` (boundary noise does not)
(:func:`regrow_tips`). Regrowing only extends trees, so it
changes neither the topology nor the number of endpoints.
"""

from __future__ import annotations

import numpy as np

from medialaxis.core._kernels import peel_leaves_kernel
from medialaxis.core.graph import compact
from medialaxis.planar._graph_kernels import adjacency_lists, component_labels, regrow_tips_kernel

__all__ = ["significant_edges", "regrow_tips", "prune_graph", "regrow_tips_reference"]

#: Regrowing needs a boundary detour of at least this fraction of ``detour``.
REGROW_DETOUR = 0.1


def significant_edges(contact_diameter: np.ndarray, contact_arc: np.ndarray, lam: float, detour: float) -> np.ndarray:
    """(m,) bool: edges kept by the lambda and detour tests (see module docstring)."""
    excess = contact_arc - contact_diameter
    return (contact_diameter >= lam) & (excess >= detour * contact_diameter) & (excess >= 2.0 * lam)


def regrow_tips(n: int, edges: np.ndarray, keep: np.ndarray, growable: np.ndarray) -> np.ndarray:
    """Extend every endpoint of the kept graph along ``growable`` removed edges (see :func:`regrow_tips_reference`)."""
    if not keep.any():
        return keep.copy()
    edges = np.ascontiguousarray(edges, dtype=np.int64).reshape(-1, 2)
    indptr, nbrs, eids = adjacency_lists(n, edges)
    return regrow_tips_kernel(indptr, nbrs, eids, edges, keep, np.asarray(growable, bool))


def regrow_tips_reference(n: int, edges: np.ndarray, keep: np.ndarray, growable: np.ndarray) -> np.ndarray:
    """Extend every endpoint of the kept graph along ``growable`` removed edges.

    A tip grows while exactly one growable edge leads on to a node not yet in
    the kept graph; at a fork it stops, since neither side is significant
    and picking one would depend on round-off (a mirror-symmetric shape
    would lose its symmetry). Growing only extends trees, so it creates no
    cycle or junction. Returns the new keep mask.
    """
    from medialaxis.core.graph import adjacency, degree

    keep = keep.copy()
    if not keep.any():
        return keep
    adj = adjacency(n, edges)
    indptr, nbrs, eids = adj.indptr, adj.indices, adj.data - 1
    used = degree(n, edges[keep]) > 0
    for start in np.flatnonzero(degree(n, edges[keep]) == 1):
        node = int(start)
        while True:
            ways = [k for k in range(indptr[node], indptr[node + 1])
                    if growable[eids[k]] and not keep[eids[k]] and not used[nbrs[k]]]
            if len(ways) != 1:
                break
            keep[eids[ways[0]]] = True
            node = int(nbrs[ways[0]])
            used[node] = True
    return keep


def prune_graph(
    radii: np.ndarray,
    edges: np.ndarray,
    contact_diameter: np.ndarray,
    contact_arc: np.ndarray,
    adjacent_contacts: np.ndarray,
    lam: float,
    detour: float,
) -> tuple[np.ndarray, np.ndarray]:
    """Peel insignificant leaf edges; return ``(kept_node_ids, kept_edges_renumbered)``.

    A component whose edges all go keeps its node of largest radius (a disc
    or a regular polygon keeps its centre).

    References
    ----------
    .. [1] J.-D. Boissonnat, C. Wormser, M. Yvinec, "Curved Voronoi diagrams", in J.-D.
           Boissonnat, M. Teillaud (eds.), Effective Computational Geometry for Curves and
           Surfaces, Springer, 67-116, 2006, section 2.7 (medial axis, Algorithm 5).
           https://hal.archives-ouvertes.fr/hal-00488446
    .. [2] F. Chazal, A. Lieutier, "The lambda-medial axis", Graphical Models, 2005.
           doi:10.1016/j.gmod.2005.01.002
    """
    n = len(radii)
    edges = np.ascontiguousarray(edges, dtype=np.int64).reshape(-1, 2)
    removable = ~significant_edges(contact_diameter, contact_arc, lam, detour)
    keep = np.ones(len(edges), bool)
    if len(edges):  # medialaxis.core.graph.peel_leaves, on lists built here
        indptr, nbrs, eids = adjacency_lists(n, edges)
        peel_leaves_kernel(indptr, nbrs, eids, np.diff(indptr), edges, removable, keep)
    excess = contact_arc - contact_diameter
    growable = (contact_diameter >= lam) & ~adjacent_contacts & (excess >= REGROW_DETOUR * detour * contact_diameter)
    keep = regrow_tips(n, edges, keep, growable)
    kept = edges[keep]
    keep_nodes = np.zeros(n, bool)
    if n:
        # Components with no edge left keep one node so no shape loses its axis.
        label = component_labels(n, edges, np.ones(len(edges), np.bool_))
        n_comp = int(label.max()) + 1
        has_edge = np.zeros(n_comp, bool)
        has_edge[label[kept.ravel()]] = True
        if not has_edge.all():  # the node of largest radius of each component left without an edge
            best = np.full(n_comp, -1, np.int64)
            order = np.lexsort((-radii, label))
            first = np.r_[True, label[order][1:] != label[order][:-1]]
            best[label[order][first]] = order[first]
            lonely = best[~has_edge]
            keep_nodes[lonely[lonely >= 0]] = True
    return compact(n, kept, keep_nodes)
