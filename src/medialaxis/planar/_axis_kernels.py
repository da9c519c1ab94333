"""Compiled: the pruned axis from the inner Delaunay triangles in one call, the per-feature work of GIS layers.

:func:`pruned_axis` computes what :func:`medialaxis.planar.axis.raw_axis`
(after :func:`~medialaxis.planar.axis.axis_positions`), the merging of
coincident Voronoi vertices of :mod:`medialaxis.planar.pipeline` and
:func:`medialaxis.planar.pruning.prune_graph` compute, with the same kernels
(:func:`~medialaxis.planar._graph_kernels.dual_edges`,
:func:`~medialaxis.planar._distance_kernels.delaunay_distance`,
:func:`~medialaxis.planar._graph_kernels.merge_clusters`, the leaf peeling and
the regrowing of tips) and the same arithmetic (NumPy's elementwise
operations, ``np.bincount``'s sums in index order, ``np.lexsort``'s first
node of largest radius), without the Python between them. The tests compare
it with :func:`medialaxis.planar.pipeline.voronoi_medial_axis` bit for bit.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit
from medialaxis.core._kernels import peel_leaves_kernel
from medialaxis.planar._distance_kernels import delaunay_distance, site_neighbours
from medialaxis.planar._graph_kernels import (
    adjacency_lists,
    component_labels,
    dual_edges,
    merge_clusters,
    regrow_tips_kernel,
)
from medialaxis.planar._inside_kernels import locate_points
from medialaxis.planar.boundary._pinch_kernels import pinch_arcs

__all__ = ["inner_centres", "contact_arcs", "merged_nodes", "pruned_graph", "kept_edges", "selected_nodes",
           "pruned_axis"]


@njit(cache=True, nogil=True)
def inner_centres(centres, inside, segments, start, members, y0, height):  # type: ignore[no-untyped-def]
    """``(inner, pos, all_in)``: the inside triangles, their circumcentres, and whether the region holds them all.

    :func:`medialaxis.planar.axis.axis_positions` where no circumcentre needs
    moving (``all_in``; else, or where the compiled inside test is unsure,
    the caller takes that function).
    """
    inner = np.flatnonzero(inside)
    pos = np.empty((len(inner), 2))
    for i in range(len(inner)):
        pos[i, 0], pos[i, 1] = centres[inner[i], 0], centres[inner[i], 1]
    where = locate_points(pos[:, 0], pos[:, 1], segments, start, members, y0, height)
    all_in = True
    for i in range(len(inner)):
        all_in = all_in and where[i] == 1
    return inner, pos, all_in


@njit(cache=True, nogil=True)
def contact_arcs(contact, arc, ring, ring_length):  # type: ignore[no-untyped-def]
    """:meth:`medialaxis.planar.boundary.sampling.BoundarySample.arc_between` of each contact pair (inf across rings)."""
    out = np.empty(len(contact))
    for e in range(len(contact)):
        a, b = contact[e, 0], contact[e, 1]
        if ring[a] == ring[b]:
            d = abs(arc[a] - arc[b])
            out[e] = min(d, ring_length[ring[a]] - d)
        else:
            out[e] = np.inf
    return out


@njit(cache=True, nogil=True)
def _means(pos, cluster):  # type: ignore[no-untyped-def]
    """``(points, count)``: each cluster's mean point (``np.bincount``'s sums, in index order) and size."""
    n = 0
    for i in range(len(cluster)):  # cluster.max() + 1: NumPy's max compiles an iterator and a take
        n = max(n, cluster[i] + 1)
    count = np.zeros(n, np.int64)
    sums = np.zeros((n, 2))
    for i in range(len(pos)):
        c = cluster[i]
        count[c] += 1
        sums[c, 0] += pos[i, 0]
        sums[c, 1] += pos[i, 1]
    points = np.empty((n, 2))
    for c in range(n):
        points[c, 0] = sums[c, 0] / count[c]
        points[c, 1] = sums[c, 1] / count[c]
    return points, count


@njit(cache=True, nogil=True)
def merged_nodes(pos, reach, edges, tolerance, segments, start, members, y0, height):  # type: ignore[no-untyped-def]
    """Clusters of edges shorter than ``tolerance`` contracted to their mean point, as far as it stays inside.

    As ``merge_close_nodes`` of ``tests/planar/merging.py``, except that a
    cluster is left alone (its nodes and edges kept) where the region
    (``segments`` ... ``height``: its
    :class:`~medialaxis.planar._inside_kernels.RegionLocator`) does not surely
    hold its mean point, or where that point lies outside the ball of one of
    its members (centre ``pos``, radius ``reach``): a cluster strung along the
    bend of a thin part has its mean outside the part, or a straight edge
    from it leaving the part (tested on a V-shaped strip). Coincident Voronoi
    vertices, which the merging is for, lie well inside each other's balls.

    Returns ``(cluster, kept, points, count)``: each node's cluster, the edges
    kept, each cluster's point and its size.
    """
    short = np.empty(len(edges), np.bool_)
    for e in range(len(edges)):
        dx = pos[edges[e, 0], 0] - pos[edges[e, 1], 0]
        dy = pos[edges[e, 0], 1] - pos[edges[e, 1], 1]
        short[e] = np.sqrt(dx * dx + dy * dy) < tolerance
    cluster, kept = merge_clusters(len(pos), edges, short)
    points, count = _means(pos, cluster)
    loose = count > 1
    for i in range(len(pos)):  # outside a member's ball
        c = cluster[i]
        if loose[c]:
            dx, dy = pos[i, 0] - points[c, 0], pos[i, 1] - points[c, 1]
            loose[c] = dx * dx + dy * dy < reach[i] * reach[i]
    merged = np.flatnonzero(loose)
    where = locate_points(points[merged, 0], points[merged, 1], segments, start, members, y0, height)
    bad = np.zeros(len(count), np.bool_)
    for c in range(len(count)):
        bad[c] = count[c] > 1 and not loose[c]
    for j in range(len(merged)):
        bad[merged[j]] = where[j] != 1
    if not bad.any():
        return cluster, kept, points, count
    for e in range(len(edges)):
        short[e] = short[e] and not bad[cluster[edges[e, 0]]]
    cluster, kept = merge_clusters(len(pos), edges, short)
    points, count = _means(pos, cluster)
    return cluster, kept, points, count


@njit(cache=True, nogil=True)
def pruned_graph(radii, edges, diameter, arc, adjacent, lam, detour, regrow_detour):  # type: ignore[no-untyped-def]
    """:func:`medialaxis.planar.pruning.prune_graph`: ``(kept_node_ids, kept_edges_renumbered)``."""
    keep, label, lonely = kept_edges(len(radii), edges, diameter, arc, adjacent, lam, detour, regrow_detour)
    return selected_nodes(radii, edges, keep, label, lonely)


@njit(cache=True, nogil=True)
def kept_edges(n, edges, diameter, arc, adjacent, lam, detour, regrow_detour):  # type: ignore[no-untyped-def]
    """The pruning of :func:`pruned_graph` before the radii: ``(keep, label, lonely)``, the edges kept, each
    node's component and the components left without an edge (which keep their node of largest radius)."""
    m = len(edges)
    removable = np.empty(m, np.bool_)
    growable = np.empty(m, np.bool_)
    for e in range(m):
        excess = arc[e] - diameter[e]
        removable[e] = not ((diameter[e] >= lam) and (excess >= detour * diameter[e]) and (excess >= 2.0 * lam))
        growable[e] = (diameter[e] >= lam) and not adjacent[e] and (excess >= regrow_detour * detour * diameter[e])
    keep = np.ones(m, np.bool_)
    if m:
        indptr, nbrs, eids = adjacency_lists(n, edges)
        peel_leaves_kernel(indptr, nbrs, eids, np.diff(indptr), edges, removable, keep)
        if keep.any():
            keep = regrow_tips_kernel(indptr, nbrs, eids, edges, keep, growable)
    label = component_labels(n, edges, np.ones(m, np.bool_)) if n else np.zeros(0, np.int64)
    n_comp = label.max() + 1 if n else 0
    lonely = np.ones(n_comp, np.bool_)
    for e in range(m):
        if keep[e]:
            lonely[label[edges[e, 0]]] = False
            lonely[label[edges[e, 1]]] = False
    return keep, label, lonely


@njit(cache=True, nogil=True)
def selected_nodes(radii, edges, keep, label, lonely):  # type: ignore[no-untyped-def]
    """``(kept_node_ids, kept_edges_renumbered)`` of :func:`pruned_graph` from :func:`kept_edges`; ``radii`` are
    read only in the ``lonely`` components (the first node of largest radius of each stays)."""
    n, m = len(label), len(edges)
    used = np.zeros(n, np.bool_)
    best = np.full(len(lonely), -1, np.int64)
    for i in range(n):
        c = label[i]
        if lonely[c] and (best[c] < 0 or radii[i] > radii[best[c]]):
            best[c] = i
    for c in range(len(lonely)):
        if best[c] >= 0:
            used[best[c]] = True
    n_kept = 0
    for e in range(m):
        if keep[e]:
            used[edges[e, 0]] = True
            used[edges[e, 1]] = True
            n_kept += 1
    old = np.flatnonzero(used)
    new_of_old = np.full(n, -1, np.int64)
    for j in range(len(old)):
        new_of_old[old[j]] = j
    out = np.empty((n_kept, 2), np.int64)
    j = 0
    for e in range(m):
        if keep[e]:
            out[j, 0], out[j, 1] = new_of_old[edges[e, 0]], new_of_old[edges[e, 1]]
            j += 1
    return old, out


@njit(cache=True, nogil=True)
def pruned_axis(pos, simplices, neighbors, inner, tri_points, tri_radii, points, nxt, arc, ring,  # type: ignore[no-untyped-def]
                ring_length, rings_s, rings_start, touching, tolerance, lam, detour, regrow_detour, k, segments, start,
                members, y0, height):
    """``(points, radii, edges)`` of the pruned axis whose raw nodes sit at ``pos`` in the triangles ``inner``.

    ``points``, ``nxt``, ``arc``, ``ring``, ``ring_length`` describe
    the boundary sample (more than ``k`` samples; radii from the pieces at
    the ``k`` nearest), ``rings_s``, ``rings_start``, ``touching`` the rings'
    arc lengths and pinches (:func:`~medialaxis.planar.boundary._pinch_kernels.pinch_arcs`), ``tri_points`` and ``tri_radii`` the triangulation's
    vertices and circumradii (a node's ball in :func:`merged_nodes`),
    ``segments`` ... ``height`` the region's compiled inside test. The nearest
    samples of a node are found along the triangulation's edges (``simplices``,
    ``neighbors``) from a vertex of one of its triangles. A node's
    radius is the distance at its point (a merged node's at its mean point,
    a single one's at its own), so only the nodes the pruning keeps, and
    those of components left without an edge, are measured.
    """
    edges, contact, diameter, adjacent = dual_edges(simplices, neighbors, inner, tri_points, nxt)
    prv = np.empty_like(nxt)  # BoundarySample.prev
    for i in range(len(nxt)):
        prv[nxt[i]] = i
    contact_arc = contact_arcs(contact, arc, ring, ring_length)
    pinch_arcs(contact_arc, contact, arc, ring, ring_length, rings_s, rings_start, touching)
    reach = np.empty(len(inner))
    for i in range(len(inner)):
        reach[i] = tri_radii[inner[i]]
    cluster, kept, node_points, count = merged_nodes(pos, reach, edges, tolerance, segments, start, members, y0, height)
    node_edges = np.empty((len(kept), 2), np.int64)
    for j in range(len(kept)):
        node_edges[j, 0], node_edges[j, 1] = cluster[edges[kept[j], 0]], cluster[edges[kept[j], 1]]
    n = len(count)
    keep, label, lonely = kept_edges(n, node_edges, diameter[kept], contact_arc[kept], adjacent[kept], lam, detour,
                                     regrow_detour)
    wanted = np.zeros(n, np.bool_)
    for i in range(n):
        wanted[i] = lonely[label[i]]
    for e in range(len(node_edges)):
        if keep[e]:
            wanted[node_edges[e, 0]] = True
            wanted[node_edges[e, 1]] = True
    measured = np.flatnonzero(wanted)
    seed = np.empty(n, np.int64)  # a vertex of a member's triangle: the walk to the nearest samples starts there
    for i in range(len(inner)):
        seed[cluster[i]] = simplices[inner[i], 0]
    indptr, nbrs = site_neighbours(len(points), simplices, neighbors)
    node_radii = np.full(n, np.nan)
    node_radii[measured] = delaunay_distance(node_points[measured], seed[measured], points, nxt, prv, k, indptr, nbrs)
    old, out = selected_nodes(node_radii, node_edges, keep, label, lonely)
    return node_points[old], node_radii[old], out
