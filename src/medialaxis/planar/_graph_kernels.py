"""Compiled graph steps of the planar axis: merging close nodes, components and regrowing tips.

Each kernel replaces a few SciPy sparse-graph and ``np.unique`` calls on the
small graphs of one shape, where their set-up costs more than the work:

- :func:`merge_clusters` contracts tree-shaped clusters of short edges by
  union-find and keeps the first of each set of edges that become parallel;
  :func:`medialaxis.planar.pruning.merge_close_nodes_reference` is the
  SciPy/NumPy version, used by the tests.
- :func:`component_labels` labels connected components by union-find (the
  numbering differs from SciPy's; the pruning only groups by it).
- :func:`adjacency_lists` gives each node's neighbours and edge indices (CSR).
- :func:`regrow_tips_kernel` is :func:`medialaxis.planar.pruning.regrow_tips_reference`
  compiled.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit

__all__ = ["merge_clusters", "component_labels", "adjacency_lists", "regrow_tips_kernel"]


@njit(cache=True, nogil=True)
def _root(parent, i):  # type: ignore[no-untyped-def]
    while parent[i] != i:
        parent[i] = parent[parent[i]]
        i = parent[i]
    return i


@njit(cache=True, nogil=True)
def component_labels(n, edges, use):  # type: ignore[no-untyped-def]
    """(n,) int64: a component number of each node over the edges where ``use``, numbered from 0 in node order."""
    parent = np.arange(n)
    for e in range(len(edges)):
        if use[e]:
            a, b = _root(parent, edges[e, 0]), _root(parent, edges[e, 1])
            if a != b:
                parent[max(a, b)] = min(a, b)
    label = np.full(n, -1, np.int64)
    count = 0
    for i in range(n):
        r = _root(parent, i)
        if label[r] < 0:
            label[r] = count
            count += 1
        label[i] = label[r]
    return label


@njit(cache=True, nogil=True)
def merge_clusters(n, edges, short):  # type: ignore[no-untyped-def]
    """Contract the tree-shaped clusters of the ``short`` edges.

    Returns ``(cluster, kept_edges)``: the new node of each node (clusters
    numbered in the order of their smallest member) and the indices, in
    order, of the edges kept: those between two clusters, the first of
    each set of parallel ones.
    """
    label = component_labels(n, edges, short)
    n_nodes = np.zeros(n, np.int64)
    first = np.full(n, n, np.int64)
    for i in range(n):
        n_nodes[label[i]] += 1
        first[label[i]] = min(first[label[i]], i)
    # distinct short edges per cluster
    idx = np.flatnonzero(short)
    keys = np.empty(len(idx), np.int64)
    for m in range(len(idx)):
        a, b = edges[idx[m], 0], edges[idx[m], 1]
        keys[m] = min(a, b) * n + max(a, b)
    keys.sort()
    n_edges = np.zeros(n, np.int64)
    for m in range(len(keys)):
        if m == 0 or keys[m] != keys[m - 1]:
            n_edges[label[keys[m] // n]] += 1
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
    pair = np.empty(len(edges), np.int64)
    for e in range(len(edges)):
        a, b = rep[edges[e, 0]], rep[edges[e, 1]]
        pair[e] = -1 if a == b else min(a, b) * n + max(a, b)
    order = np.argsort(pair, kind="mergesort")
    keep = np.zeros(len(edges), np.bool_)
    for m in range(len(order)):
        e = order[m]
        if pair[e] >= 0 and (m == 0 or pair[order[m - 1]] != pair[e]):
            keep[e] = True
    return cluster, np.flatnonzero(keep)


@njit(cache=True, nogil=True)
def adjacency_lists(n, edges):  # type: ignore[no-untyped-def]
    """CSR ``(indptr, neighbours, edge_ids)`` of an undirected edge list (each edge listed at both ends)."""
    indptr = np.zeros(n + 1, np.int64)
    for e in range(len(edges)):
        indptr[edges[e, 0] + 1] += 1
        indptr[edges[e, 1] + 1] += 1
    indptr = np.cumsum(indptr)
    fill = indptr[:-1].copy()
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
