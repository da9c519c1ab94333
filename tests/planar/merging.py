"""The planar axis's merging of close Voronoi nodes, alone and as SciPy/NumPy (test helpers).

The library merges clusters inside its compiled pruning
(:func:`medialaxis.planar._axis_kernels.merged_nodes`, which also keeps a
cluster whose mean would leave the shape); these two give the plain merge:
:func:`merge_close_nodes` through the same union-find kernel
(:func:`medialaxis.planar._graph_kernels.merge_clusters`) and
:func:`merge_close_nodes_reference` with SciPy's connected components, which
the tests hold it to.
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from medialaxis.planar._graph_kernels import merge_clusters


def merge_close_nodes(points: np.ndarray, edges: np.ndarray, min_length: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Contract tree-shaped clusters of edges shorter than ``min_length``.

    Co-circular samples produce coincident Voronoi vertices (the centre of a
    disc, the mid-line of a rectangle); each cluster becomes one node, placed
    by the caller (at the cluster's mean, which does not depend on how the
    triangulation broke the ties). Clusters that contain a cycle are left
    alone so no hole is lost.

    Returns
    -------
    cluster : (n,) int ndarray
        New node of each old node (clusters numbered by their first member).
    edges : (m', 2) int ndarray
        Remaining edges between clusters, without self-loops or duplicates.
    kept_edges : (m',) int ndarray
        Old index of each remaining edge (for its attributes).
    """
    edges = np.ascontiguousarray(edges, dtype=np.int64).reshape(-1, 2)
    length = np.linalg.norm(points[edges[:, 0]] - points[edges[:, 1]], axis=1)
    cluster, kept_edges = merge_clusters(len(points), edges, length < min_length)
    return cluster, cluster[edges[kept_edges]].reshape(-1, 2), kept_edges


def merge_close_nodes_reference(
    points: np.ndarray, edges: np.ndarray, min_length: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """SciPy/NumPy version of :func:`merge_close_nodes` (SciPy's connected components)."""
    n = len(points)
    rep = np.arange(n)
    if len(edges):
        length = np.linalg.norm(points[edges[:, 0]] - points[edges[:, 1]], axis=1)
        short = edges[length < min_length]
        if len(short):
            adj = coo_matrix((np.ones(len(short)), (short[:, 0], short[:, 1])), shape=(n, n))
            _, label = connected_components(adj, directed=False)
            uniq = np.unique(np.sort(short, 1), axis=0)
            n_nodes = np.bincount(label, minlength=label.max() + 1)
            n_edges = np.bincount(label[uniq[:, 0]], minlength=len(n_nodes))
            tree = n_edges == n_nodes - 1
            first = np.full(len(n_nodes), n, np.int64)
            np.minimum.at(first, label, np.arange(n))
            rep = np.where(tree[label], first[label], np.arange(n))
    new = np.sort(rep[edges], axis=1) if len(edges) else np.empty((0, 2), np.int64)
    candidates = np.flatnonzero(new[:, 0] != new[:, 1])
    _, first_edge = np.unique(new[candidates], axis=0, return_index=True)
    kept_edges = np.sort(candidates[first_edge])
    _, cluster = np.unique(rep, return_inverse=True)
    return cluster.reshape(-1), cluster[edges[kept_edges]].reshape(-1, 2), kept_edges


