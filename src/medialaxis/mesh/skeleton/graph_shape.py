"""Shaping a contracted curve skeleton: straight branches into junctions, junction balls, leaves reaching the tips."""

from __future__ import annotations

import numpy as np
from scipy import sparse

from medialaxis.core import graph as _graph

__all__ = ["branch_chains", "straighten_junction", "junction_ball", "extend_leaves"]


def branch_chains(adj: sparse.csr_matrix, deg: np.ndarray, j: int) -> list[list[int]]:
    """Node chains leaving node ``j``, each up to (and including) the next non-degree-2 node."""
    chains = []
    for start in adj.indices[adj.indptr[j] : adj.indptr[j + 1]]:
        chain, prev, cur = [int(start)], j, int(start)
        while deg[cur] == 2:
            nxt = [v for v in adj.indices[adj.indptr[cur] : adj.indptr[cur + 1]] if v != prev]
            if not nxt or nxt[0] == j:
                break
            prev, cur = cur, int(nxt[0])
            chain.append(cur)
        chains.append(chain)
    return chains


def straighten_junction(pos: np.ndarray, adj: sparse.csr_matrix, deg: np.ndarray, j: int, radius: float) -> None:
    """Move junction ``j`` to where its branches' lines meet and put the hub nodes on those lines.

    Near a junction the medial axis of a solid leaves the branches' axes (the
    hub's medial sheets); a curve skeleton continues each branch straight into
    the junction. Each branch's line is fitted to its nodes between 1.5 and 4
    radii from the junction; nodes nearer than 1.5 radii are projected on it.
    """
    fits = []
    for chain in branch_chains(adj, deg, j):
        dist = np.linalg.norm(pos[chain] - pos[j], axis=1)
        far = np.asarray(chain)[(dist >= 1.5 * radius) & (dist <= 4.0 * radius)]
        if len(far) < 2:
            continue
        mean = pos[far].mean(axis=0)
        direction = np.linalg.svd(pos[far] - mean, full_matrices=False)[2][0]
        near = np.asarray(chain)[dist < 1.5 * radius]
        fits.append((mean, direction, near))
    if len(fits) < 2:
        return
    a = np.zeros((3, 3))
    b = np.zeros(3)
    for mean, d, _near in fits:
        proj = np.eye(3) - np.outer(d, d)
        a += proj
        b += proj @ mean
    if np.linalg.cond(a) > 1e6:
        return
    x = np.linalg.solve(a, b)
    if np.linalg.norm(x - pos[j]) > 2.0 * radius:
        return
    pos[j] = x
    for mean, d, near in fits:
        if len(near):
            pos[near] = mean + ((pos[near] - mean) @ d)[:, None] * d


def junction_ball(pos: np.ndarray, edges: np.ndarray, radii: np.ndarray, protected: np.ndarray) -> np.ndarray | None:
    """Nodes inside some junction's ball and connected to it through the ball, junction first.

    Around a junction the flow leaves a small blob (the medial surface of
    the hub); those nodes are merged into the junction.
    """
    deg = _graph.degree(len(pos), edges)
    junctions = np.flatnonzero(deg >= 3)
    if len(junctions) == 0:
        return None
    adj = _graph.adjacency(len(pos), edges)
    for j in junctions:
        near = np.linalg.norm(pos - pos[j], axis=1) < radii[j]
        near &= ~protected
        near[j] = True
        # the ball's nodes reached from j through the ball (a search, not a labelling of the whole
        # graph per junction: a box with a 5e9-long spike took 30k labellings, 13 s)
        seen, todo = {int(j)}, [int(j)]
        while todo:
            u = todo.pop()
            for v in adj.indices[adj.indptr[u]:adj.indptr[u + 1]]:
                if near[v] and int(v) not in seen:
                    seen.add(int(v))
                    todo.append(int(v))
        if len(seen) > 1:
            ball = np.array(sorted(seen), np.int64)
            return np.concatenate([[j], ball[ball != j]])
    return None


def extend_leaves(
    pos: np.ndarray,
    adj: sparse.csr_matrix,
    deg: np.ndarray,
    node_of_vertex: np.ndarray,
    contracted: np.ndarray,
    protected: np.ndarray,
    top: float = 0.1,
) -> None:
    """Move each free endpoint to the far end of the contracted points it holds.

    A node sits at the mean of its group, up to half a cell short of where
    the contracted branch ends; the endpoint is put at the mean of the
    ``top`` fraction of its points that reach furthest along the branch.
    """
    leaves = np.flatnonzero((deg == 1) & ~protected)
    if len(leaves) == 0:
        return
    order = np.argsort(node_of_vertex, kind="stable")
    sorted_nodes = node_of_vertex[order]
    for leaf in leaves:
        lo, hi = np.searchsorted(sorted_nodes, [leaf, leaf + 1])
        members = order[lo:hi]
        if len(members) < 2:
            continue
        nbr = adj.indices[adj.indptr[leaf]]
        direction = pos[leaf] - pos[nbr]
        norm = np.linalg.norm(direction)
        if norm == 0:
            continue
        reach = contracted[members] @ (direction / norm)
        k = max(1, int(np.ceil(top * len(members))))
        far = members[np.argsort(reach)[-k:]]
        tip = contracted[far].mean(axis=0)
        if (tip - pos[nbr]) @ direction > norm**2:  # only ever lengthen the branch
            pos[leaf] = tip
