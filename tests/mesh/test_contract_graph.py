"""The skeleton graph's cycles: incremental path lengths equal Dijkstra's after every added edge."""

from __future__ import annotations

import numpy as np
from scipy import sparse
from scipy.sparse import csgraph
from scipy.spatial import Delaunay

from medialaxis.mesh.skeleton.contract_graph import _spanning_forest_with_cycles


def _reference(pos, node_edges, n_cycles):
    """Minimum spanning forest, then the longest cycle closed n_cycles times, all distances by Dijkstra."""
    m = len(pos)
    w = np.linalg.norm(pos[node_edges[:, 0]] - pos[node_edges[:, 1]], axis=1) + 1e-12

    def adjacency(edges, weights):
        a = sparse.coo_matrix((weights, (edges[:, 0], edges[:, 1])), shape=(m, m)).tocsr()
        return (a + a.T).tocsr()

    tree = csgraph.minimum_spanning_tree(adjacency(node_edges, w)).tocoo()
    kept = np.sort(np.column_stack([tree.row, tree.col]), axis=1).astype(np.int64)
    in_tree = {tuple(e) for e in kept.tolist()}
    candidates = [i for i, e in enumerate(node_edges.tolist()) if tuple(e) not in in_tree]
    for _ in range(n_cycles):
        if not candidates:
            break
        kw = np.linalg.norm(pos[kept[:, 0]] - pos[kept[:, 1]], axis=1) + 1e-12
        dist = csgraph.dijkstra(adjacency(kept, kw))
        loop = [dist[node_edges[c, 0], node_edges[c, 1]] + w[c] for c in candidates]
        best = int(np.argmax(loop))
        kept = np.vstack([kept, node_edges[candidates[best]][None]])
        del candidates[best]
    return kept


def _cycles(n, e):
    """Independent cycles of a graph: E - V + components."""
    g = sparse.coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(n, n))
    return len(e) - n + csgraph.connected_components(g, directed=False)[0]


def test_cycles_closed_are_the_reference_ones():
    rng = np.random.default_rng(0)
    for _ in range(20):
        n = int(rng.integers(20, 300))
        pos = rng.random((n, 3))
        t = Delaunay(pos).simplices
        edges = np.unique(np.sort(np.r_[t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 3]], t[:, [0, 3]]], 1), axis=0)
        edges = edges[rng.random(len(edges)) < 0.5]
        k = int(rng.integers(0, 8))
        got = _spanning_forest_with_cycles(pos, edges, k)
        want = _reference(pos, edges, k)
        np.testing.assert_array_equal(np.sort(got, 1), np.sort(want, 1))
        assert _cycles(n, got) == min(k, _cycles(n, edges))
