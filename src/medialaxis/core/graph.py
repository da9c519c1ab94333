"""Graph utilities over ``(m, 2)`` edge arrays: degrees, components, branches, pruning.

All functions take the number of nodes and an integer edge array and work
with SciPy sparse matrices, so they scale to millions of edges.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy import sparse
from scipy.sparse import csgraph

__all__ = [
    "degree",
    "adjacency",
    "n_components",
    "component_labels",
    "cycle_rank",
    "branches",
    "branches_reference",
    "peel_leaves",
    "compact",
    "to_networkx",
    "sheet_edges",
]


def degree(n: int, edges: np.ndarray) -> np.ndarray:
    """(n,) int64 node degrees (a self-loop counts twice)."""
    edges = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    return np.bincount(edges.ravel(), minlength=n).astype(np.int64)


def adjacency(n: int, edges: np.ndarray) -> sparse.csr_matrix:
    """Symmetric CSR adjacency matrix; entry (i, j) is the edge index + 1."""
    edges = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    ids = np.arange(1, len(edges) + 1, dtype=np.int64)
    rows = np.concatenate([edges[:, 0], edges[:, 1]])
    cols = np.concatenate([edges[:, 1], edges[:, 0]])
    return sparse.csr_matrix((np.concatenate([ids, ids]), (rows, cols)), shape=(n, n))


def component_labels(n: int, edges: np.ndarray) -> tuple[int, np.ndarray]:
    """Connected components: ``(count, labels)``; isolated nodes count."""
    if n == 0:
        return 0, np.empty(0, np.int64)
    count, labels = csgraph.connected_components(adjacency(n, edges), directed=False)
    return int(count), labels.astype(np.int64)


def n_components(n: int, edges: np.ndarray) -> int:
    """Number of connected components (isolated nodes count)."""
    return component_labels(n, edges)[0]


def cycle_rank(n: int, edges: np.ndarray) -> int:
    """First Betti number ``m - n + c`` of the graph (duplicate edges removed)."""
    edges = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    if len(edges):
        edges = np.unique(np.sort(edges, axis=1), axis=0)
        edges = edges[edges[:, 0] != edges[:, 1]]
    return int(len(edges) - n + n_components(n, edges))


def _neighbour_lists(n: int, edges: Any) -> tuple[np.ndarray, ...]:
    """Edges, degrees and CSR neighbour lists (``indptr``, neighbour, edge id) of a multigraph.

    By sorting, not a sparse matrix: repeated edges and self-loops keep one
    entry each instead of being summed into one.
    """
    edges = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    rows = np.concatenate([edges[:, 0], edges[:, 1]])
    order = np.argsort(rows, kind="stable")
    indptr = np.searchsorted(rows[order], np.arange(n + 1)).astype(np.int64)
    nbrs = np.concatenate([edges[:, 1], edges[:, 0]])[order]
    eids = np.tile(np.arange(len(edges)), 2)[order]
    return edges, degree(n, edges), indptr, nbrs, eids


def branches(n: int, edges: np.ndarray) -> list[np.ndarray]:
    """Chains between nodes whose degree is not 2.

    Returns a list of index arrays; each edge is walked exactly once. A
    component that is a pure loop is returned once, closed (first index
    repeated last).
    """
    from medialaxis.core._kernels import (  # numba loads on first use, not with the graph helpers
        branch_walks,
        neighbour_lists,
    )

    edges = np.ascontiguousarray(np.asarray(edges, dtype=np.int64).reshape(-1, 2))
    indptr, nbrs, eids, deg = neighbour_lists(n, edges)
    nodes, offsets = branch_walks(indptr, nbrs, eids, deg, edges)
    return np.split(nodes, offsets[1:-1]) if len(offsets) > 1 else []


def branches_reference(n: int, edges: np.ndarray) -> list[np.ndarray]:
    """Pure-Python twin of :func:`branches` (the tests' reference)."""
    edges, deg, indptr, nbrs, eids = _neighbour_lists(n, edges)
    used = np.zeros(len(edges), bool)
    chains: list[np.ndarray] = []

    def walk(start: int, k: int) -> np.ndarray:
        path = [start]
        node = start
        while True:
            used[eids[k]] = True
            node = int(nbrs[k])
            path.append(node)
            if deg[node] != 2 or node == start:
                return np.asarray(path, np.int64)
            lo, hi = indptr[node], indptr[node + 1]
            nxt = [j for j in range(lo, hi) if not used[eids[j]]]
            if not nxt:
                return np.asarray(path, np.int64)
            k = nxt[0]

    for start in np.flatnonzero((deg != 2) & (deg > 0)):
        for k in range(indptr[start], indptr[start + 1]):
            if not used[eids[k]]:
                chains.append(walk(int(start), k))
    for e in np.flatnonzero(~used):
        if used[e]:
            continue
        first = int(edges[e, 0])
        k = next(j for j in range(indptr[first], indptr[first + 1]) if eids[j] == e)
        chains.append(walk(first, k))
    return chains


def peel_leaves(n: int, edges: np.ndarray, removable: np.ndarray) -> np.ndarray:
    """Topology-preserving pruning: repeatedly delete removable leaf edges.

    An edge is deleted only while one of its nodes has degree 1 (it hangs off
    the graph), so deleting it never disconnects a component or opens a cycle.
    The result keeps every non-removable edge and the removable edges that
    are needed to connect them or that lie on cycles.

    Parameters
    ----------
    n : int
        Number of nodes.
    edges : (m, 2) int ndarray
    removable : (m,) bool ndarray
        Edges that may go when they become leaves. The result does not
        depend on the order of removal (leaf peeling is confluent).

    Returns
    -------
    (m,) bool ndarray
        Mask of the edges kept.
    """
    edges = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    keep = np.ones(len(edges), bool)
    if len(edges) == 0:
        return keep
    from medialaxis.core._kernels import peel_leaves_kernel

    adj = adjacency(n, edges)
    deg = degree(n, edges)
    peel_leaves_kernel(adj.indptr, adj.indices, (adj.data - 1).astype(np.int64), deg, edges,
                       np.asarray(removable, bool), keep)
    return keep


def compact(n: int, edges: np.ndarray, keep_nodes: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Drop nodes not used by ``edges`` (unless ``keep_nodes``) and renumber.

    Returns ``(old_index_of_new, new_edges)``.
    """
    edges = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    used = np.zeros(n, bool)
    used[edges.ravel()] = True
    if keep_nodes is not None:
        used |= keep_nodes
    old = np.flatnonzero(used)
    new_of_old = np.full(n, -1, np.int64)
    new_of_old[old] = np.arange(len(old))
    return old, new_of_old[edges]


def to_networkx(points: np.ndarray, radii: np.ndarray, edges: np.ndarray) -> Any:
    """Build a :class:`networkx.Graph` with ``pos``/``radius`` nodes and ``length`` edges."""
    from medialaxis._optional import require

    nx = require("networkx", "networkx")
    g = nx.Graph()
    for i, (p, r) in enumerate(zip(points.tolist(), radii.tolist())):
        g.add_node(i, pos=tuple(p), radius=r)
    lengths = np.linalg.norm(points[edges[:, 0]] - points[edges[:, 1]], axis=1) if len(edges) else []
    for (a, b), length in zip(edges.tolist(), np.asarray(lengths).tolist()):
        g.add_edge(a, b, length=length)
    return g


def sheet_edges(faces: np.ndarray) -> np.ndarray:
    """The sides of a surface's triangles where a sheet ends (one triangle) or sheets meet (three or more).

    What every surface result lists in ``edges`` besides its curve pieces; a
    side inside a sheet (two triangles) is not one.

    >>> sheet_edges(np.array([[0, 1, 2], [0, 2, 3]])).tolist()
    [[0, 1], [0, 3], [1, 2], [2, 3]]
    """
    faces = np.asarray(faces, np.int64).reshape(-1, 3)
    sides, uses = np.unique(np.sort(faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1), axis=0, return_counts=True)
    return sides[uses != 2].reshape(-1, 2)
