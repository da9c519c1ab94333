"""Endpoints of the compared axis: their order along the shape's boundary, their weights and the geodesic
distances between them (where the tour starts)."""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.sparse import csgraph

from medialaxis.compare.compared_axis import edge_lengths, terminal_protrusions
from medialaxis.compare.tour import rotation_system
from medialaxis.core import graph as _graph

__all__ = ["endpoint_order", "endpoint_weights", "path_lengths", "weighted_graph"]


def endpoint_weights(
    points: np.ndarray, radii: np.ndarray, edges: np.ndarray, ends: np.ndarray, lengths: np.ndarray
) -> np.ndarray:
    """Protrusion of the terminal branch of each endpoint (see :func:`~medialaxis.compare.compared_axis.terminal_protrusions`)."""
    out = np.full(len(ends), lengths.max() / 2 if lengths.size else 0.0)
    where = {int(e): k for k, e in enumerate(ends)}
    for chain, value in terminal_protrusions(points, radii, edges):
        k = where.get(int(chain[-1]))
        if k is not None:
            out[k] = value
    return out


def _boundary_order(points: np.ndarray, edges: np.ndarray, ends: np.ndarray) -> np.ndarray:
    """Endpoints in the order a walk around the boundary meets them.

    Walks the faces of the axis's planar embedding: arriving at node ``b``
    from ``a``, leave by the neighbour that follows ``a`` in angular order
    around ``b``. For a tree this is the walk around the boundary.
    """
    nbrs, rank = rotation_system(points, edges)
    is_end = set(int(e) for e in ends)
    seen: set[int] = set()
    out: list[int] = []
    for start in ends:
        start = int(start)
        if start in seen:
            continue
        seen.add(start)
        out.append(start)
        if not nbrs[start]:
            continue
        dart = (start, nbrs[start][0])
        first = dart
        for _ in range(4 * len(edges) + 4):
            a, b = dart
            if b in is_end and b not in seen:
                seen.add(b)
                out.append(b)
            dart = (b, nbrs[b][(rank[b][a] + 1) % len(nbrs[b])])
            if dart == first:
                break
    return np.asarray(out, np.int64)


def _diameter_ends(points: np.ndarray, edges: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """Two far-apart nodes (double sweep) when the axis has fewer than two endpoints."""
    n = len(points)
    if not len(edges):
        return np.array([0, 0], np.int64)
    graph = weighted_graph(n, edges, weights)
    d0 = csgraph.dijkstra(graph, directed=False, indices=0)
    a = int(np.argmax(np.where(np.isfinite(d0), d0, -1)))
    da = csgraph.dijkstra(graph, directed=False, indices=a)
    b = int(np.argmax(np.where(np.isfinite(da), da, -1)))
    return np.array([a, b], np.int64)


def weighted_graph(n: int, edges: np.ndarray, weights: np.ndarray) -> Any:
    from scipy import sparse

    w = np.maximum(weights, 1e-300)  # csgraph drops explicit zeros
    return sparse.coo_matrix((w, (edges[:, 0], edges[:, 1])), shape=(n, n)).tocsr()


def endpoint_order(points: np.ndarray, edges: np.ndarray) -> np.ndarray:
    """Endpoints in boundary order, or two far-apart nodes if the axis has fewer than two endpoints."""
    ends = np.flatnonzero(_graph.degree(len(points), edges) == 1)
    if len(ends) < 2:
        return _diameter_ends(points, edges, edge_lengths(points, edges) if len(edges) else np.empty(0))
    return _boundary_order(points, edges, ends)


def path_lengths(points: np.ndarray, edges: np.ndarray, ends: np.ndarray) -> np.ndarray:
    """Geodesic axis distances ``(e, e)`` between the nodes ``ends``."""
    if not len(edges):
        return np.zeros((len(ends), len(ends)))
    graph = weighted_graph(len(points), edges, edge_lengths(points, edges))
    return csgraph.dijkstra(graph, directed=False, indices=ends)[:, ends]
