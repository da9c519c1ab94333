"""Endpoints of the compared axis: their order along the shape's boundary, their weights, and the geodesic
paths between them (radius functions, lengths, bends) that the skeleton-path term compares."""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.sparse import csgraph

from medialaxis.compare.compared_axis import edge_lengths, terminal_protrusions
from medialaxis.compare.tour import rotation_system
from medialaxis.core import graph as _graph

__all__ = ["endpoint_order", "endpoint_weights", "endpoint_paths", "path_lengths", "weighted_graph"]


def endpoint_weights(
    points: np.ndarray, radii: np.ndarray, edges: np.ndarray, ends: np.ndarray, lengths: np.ndarray
) -> np.ndarray:
    """Protrusion of the terminal branch of each endpoint (see :func:`_terminal_protrusions`)."""
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


def endpoint_paths(
    points: np.ndarray, radii: np.ndarray, edges: np.ndarray, ends: np.ndarray, n_samples: int, n_bend: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Radius functions, lengths and bend profiles of the geodesic paths between endpoints.

    Returns ``(radii (e, e, n_samples), lengths (e, e), bends (e, e, n_bend))``;
    the bend profile is the distance from the chord's midpoint of the path
    points at ``n_bend`` interior arc-length fractions ``k / (n_bend + 1)``.
    """
    e = len(ends)
    out_r = np.zeros((e, e, n_samples))
    out_l = np.zeros((e, e))
    out_b = np.zeros((e, e, n_bend))
    if not len(edges):
        out_r[:] = radii[ends[0]]
        return out_r, out_l, out_b
    n = len(points)
    weights = edge_lengths(points, edges)
    dist, pred = csgraph.dijkstra(weighted_graph(n, edges, weights), directed=False, indices=ends, return_predecessors=True)
    t = np.linspace(0.0, 1.0, n_samples)
    tb = np.arange(1, n_bend + 1) / (n_bend + 1)
    for i in range(e):
        for j in range(e):
            if i == j:
                out_r[i, j] = radii[ends[i]]
                continue
            if j < i:
                out_r[i, j] = out_r[j, i][::-1]
                out_l[i, j] = out_l[j, i]
                out_b[i, j] = out_b[j, i][::-1]
                continue
            path = [int(ends[j])]
            while path[-1] != ends[i]:
                path.append(int(pred[i, path[-1]]))
            path.reverse()
            p = points[path]
            arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])
            total = arc[-1]
            out_l[i, j] = total
            if total > 0:
                out_r[i, j] = np.interp(t * total, arc, radii[path])
                along = np.column_stack([np.interp(tb * total, arc, p[:, 0]), np.interp(tb * total, arc, p[:, 1])])
                out_b[i, j] = np.linalg.norm(along - (p[0] + p[-1]) / 2, axis=1)
            else:
                out_r[i, j] = radii[path[0]]
    return out_r, out_l, out_b


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
