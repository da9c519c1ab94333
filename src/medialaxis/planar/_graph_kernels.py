"""Compiled graph steps of the planar axis: its edges, merging close nodes, components and regrowing tips.

Each kernel replaces a few SciPy sparse-graph and ``np.unique`` calls on the
small graphs of one shape, where their set-up costs more than the work:

- :func:`merge_clusters` contracts tree-shaped clusters of short edges by
  union-find and keeps the first of each set of edges that become parallel;
  ``merge_close_nodes_reference`` in ``tests/planar/merging.py`` is the
  SciPy/NumPy version the tests compare it with.
- :func:`component_labels` labels connected components by union-find (the
  numbering differs from SciPy's; the pruning only groups by it).
- :func:`adjacency_lists` gives each node's neighbours and edge indices (CSR).
- :func:`regrow_tips_kernel` is :func:`medialaxis.planar.pruning.regrow_tips_reference`
  compiled.
- :func:`dual_edges` builds the raw axis's edges between inner triangles,
  :func:`medialaxis.planar.axis.dual_edges_reference` compiled.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit
from medialaxis.core._kernels import find_root

__all__ = ["merge_clusters", "component_labels", "adjacency_lists", "regrow_tips_kernel", "dual_edges"]


@njit(cache=True, nogil=True)
def component_labels(n, edges, use):  # type: ignore[no-untyped-def]
    """(n,) int64: a component number of each node over the edges where ``use``, numbered from 0 in node order."""
    parent = np.arange(n)
    for e in range(len(edges)):
        if use[e]:
            a, b = find_root(parent, edges[e, 0]), find_root(parent, edges[e, 1])
            if a != b:
                parent[max(a, b)] = min(a, b)
    label = np.full(n, -1, np.int64)
    count = 0
    for i in range(n):
        r = find_root(parent, i)
        if label[r] < 0:
            label[r] = count
            count += 1
        label[i] = label[r]
    return label


@njit(cache=True, nogil=True)
def _first_pairs(n, lo, hi, use):  # type: ignore[no-untyped-def]
    """(m,) bool: ``use`` entries whose pair ``(lo, hi)`` (nodes below ``n``) no earlier used entry has.

    Entries are filed by ``lo`` (a counting sort, which keeps their order)
    and a pair seen is marked on ``hi``: O(n + m), no sorting.
    """
    start = np.zeros(n + 1, np.int64)
    for e in range(len(lo)):
        if use[e]:
            start[lo[e] + 1] += 1
    for i in range(n):
        start[i + 1] += start[i]
    fill = np.empty(len(start) - 1, np.int64)
    for i in range(len(fill)):
        fill[i] = start[i]
    order = np.empty(start[n], np.int64)
    for e in range(len(lo)):
        if use[e]:
            order[fill[lo[e]]] = e
            fill[lo[e]] += 1
    seen = np.full(n, -1, np.int64)
    first = np.zeros(len(lo), np.bool_)
    for a in range(n):
        for m in range(start[a], start[a + 1]):
            e = order[m]
            if seen[hi[e]] != a:
                seen[hi[e]] = a
                first[e] = True
    return first


@njit(cache=True, nogil=True)
def merge_clusters(n, edges, short):  # type: ignore[no-untyped-def]
    """Contract the tree-shaped clusters of the ``short`` edges.

    Returns ``(cluster, kept_edges)``: the new node of each node (clusters
    numbered in the order of their smallest member) and the indices, in
    order, of the edges kept: those between two clusters, the first of
    each set of parallel ones.
    """
    m = len(edges)
    label = component_labels(n, edges, short)
    n_nodes = np.zeros(n, np.int64)
    first = np.full(n, n, np.int64)
    for i in range(n):
        n_nodes[label[i]] += 1
        first[label[i]] = min(first[label[i]], i)
    lo = np.empty(m, np.int64)
    hi = np.empty(m, np.int64)
    for e in range(m):
        lo[e] = min(edges[e, 0], edges[e, 1])
        hi[e] = max(edges[e, 0], edges[e, 1])
    distinct = _first_pairs(n, lo, hi, short)
    n_edges = np.zeros(n, np.int64)
    for e in range(m):
        if distinct[e]:
            n_edges[label[lo[e]]] += 1
    rep = np.arange(n)
    for i in range(n):
        if n_edges[label[i]] == n_nodes[label[i]] - 1:
            rep[i] = first[label[i]]
    cluster = np.full(n, -1, np.int64)
    count = 0
    for i in range(n):  # reps are their cluster's smallest member: numbered in node order
        if rep[i] == i:
            cluster[i] = count
            count += 1
    for i in range(n):
        cluster[i] = cluster[rep[i]]
    between = np.zeros(m, np.bool_)
    for e in range(m):
        a, b = rep[edges[e, 0]], rep[edges[e, 1]]
        lo[e], hi[e] = min(a, b), max(a, b)
        between[e] = a != b
    keep = _first_pairs(n, lo, hi, between)
    n_kept = 0
    for e in range(m):
        n_kept += keep[e]
    kept = np.empty(n_kept, np.int64)
    j = 0
    for e in range(m):
        if keep[e]:
            kept[j] = e
            j += 1
    return cluster, kept


@njit(cache=True, nogil=True)
def adjacency_lists(n, edges):  # type: ignore[no-untyped-def]
    """CSR ``(indptr, neighbours, edge_ids)`` of an undirected edge list (each edge listed at both ends)."""
    indptr = np.zeros(n + 1, np.int64)
    for e in range(len(edges)):
        indptr[edges[e, 0] + 1] += 1
        indptr[edges[e, 1] + 1] += 1
    for i in range(n):
        indptr[i + 1] += indptr[i]
    fill = np.empty(len(indptr) - 1, np.int64)
    for i in range(len(fill)):
        fill[i] = indptr[i]
    nbrs = np.empty(2 * len(edges), np.int64)
    eids = np.empty(2 * len(edges), np.int64)
    for e in range(len(edges)):
        for s in range(2):
            a, b = edges[e, s], edges[e, 1 - s]
            nbrs[fill[a]] = b
            eids[fill[a]] = e
            fill[a] += 1
    return indptr, nbrs, eids


@njit(cache=True, nogil=True)
def regrow_tips_kernel(indptr, nbrs, eids, edges, keep, growable):  # type: ignore[no-untyped-def]
    """New keep mask: each endpoint of the kept graph extended along the one growable edge onwards, to a fork."""
    n = len(indptr) - 1
    keep = keep.copy()
    kept_degree = np.zeros(n, np.int64)
    for e in range(len(edges)):
        if keep[e]:
            kept_degree[edges[e, 0]] += 1
            kept_degree[edges[e, 1]] += 1
    used = kept_degree > 0
    for start in range(n):
        if kept_degree[start] != 1:
            continue
        node = start
        while True:
            ways = 0
            way = -1
            for k in range(indptr[node], indptr[node + 1]):
                if growable[eids[k]] and not keep[eids[k]] and not used[nbrs[k]]:
                    ways += 1
                    way = k
            if ways != 1:
                break
            keep[eids[way]] = True
            node = nbrs[way]
            used[node] = True
    return keep


@njit(cache=True, nogil=True)
def dual_edges(simplices, neighbors, inner, points, nxt):  # type: ignore[no-untyped-def]
    """The Voronoi edges between the inner triangles ``inner`` (ascending), as :func:`medialaxis.planar.axis.dual_edges_reference`.

    Returns ``(edges, contact, diameter, adjacent)``: node pairs (positions
    in ``inner``), the two samples of each dual Delaunay edge, their
    distance, and whether they are consecutive samples.
    """
    node_of = np.full(len(simplices), -1, np.int64)
    for i in range(len(inner)):
        node_of[inner[i]] = i
    m = 0
    for t in inner:
        for k in range(3):
            u = neighbors[t, k]
            if u > t and node_of[u] >= 0:
                m += 1
    edges = np.empty((m, 2), np.int64)
    contact = np.empty((m, 2), np.int64)
    diameter = np.empty(m)
    adjacent = np.empty(m, np.bool_)
    m = 0
    for t in inner:
        for k in range(3):
            u = neighbors[t, k]
            if u > t and node_of[u] >= 0:
                a, b = simplices[t, (k + 1) % 3], simplices[t, (k + 2) % 3]
                edges[m, 0], edges[m, 1] = node_of[t], node_of[u]
                contact[m, 0], contact[m, 1] = a, b
                dx, dy = points[a, 0] - points[b, 0], points[a, 1] - points[b, 1]
                diameter[m] = np.sqrt(dx * dx + dy * dy)
                adjacent[m] = nxt[a] == b or nxt[b] == a
                m += 1
    return edges, contact, diameter, adjacent
