"""Compiled graph kernels (numba) with pure-Python references used by the tests."""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit

__all__ = ["peel_leaves_kernel", "peel_leaves_reference", "find_root", "branch_walks", "collapse_free_faces_kernel"]


@njit(cache=True, nogil=True)
def find_root(parent, i):  # type: ignore[no-untyped-def]
    """Root of ``i`` in a union-find forest ``parent``, halving the path on the way."""
    while parent[i] != i:
        parent[i] = parent[parent[i]]
        i = parent[i]
    return i


def peel_leaves_reference(indptr, nbrs, eids, deg, edges, removable, keep) -> None:
    """Pure-Python twin of :func:`peel_leaves_kernel` (same arguments, same effect)."""
    deg = deg.copy()
    stack = [i for i in range(len(deg)) if deg[i] == 1]
    while stack:
        node = stack.pop()
        if deg[node] != 1:
            continue
        for k in range(indptr[node], indptr[node + 1]):
            e = eids[k]
            if keep[e]:
                break
        else:
            continue
        if not removable[e]:
            continue
        keep[e] = False
        other = edges[e, 0] if edges[e, 1] == node else edges[e, 1]
        deg[node] -= 1
        deg[other] -= 1
        if deg[other] == 1:
            stack.append(other)


@njit(cache=True, nogil=True)
def peel_leaves_kernel(indptr, nbrs, eids, deg, edges, removable, keep):  # pragma: no cover - compiled
    """Delete removable edges hanging off degree-1 nodes until none is left.

    ``keep`` is updated in place. ``deg`` is copied. Runs in O(n + m).
    """
    deg = deg.copy()
    stack = np.empty(len(deg) + len(edges) + 1, np.int64)
    top = 0
    for i in range(len(deg)):
        if deg[i] == 1:
            stack[top] = i
            top += 1
    while top > 0:
        top -= 1
        node = stack[top]
        if deg[node] != 1:
            continue
        e = -1
        for k in range(indptr[node], indptr[node + 1]):
            if keep[eids[k]]:
                e = eids[k]
                break
        if e < 0 or not removable[e]:
            continue
        keep[e] = False
        other = edges[e, 0] if edges[e, 1] == node else edges[e, 1]
        deg[node] -= 1
        deg[other] -= 1
        if deg[other] == 1:
            stack[top] = other
            top += 1


@njit(cache=True, nogil=True)
def branch_walks(indptr, nbrs, eids, deg, edges):  # type: ignore[no-untyped-def]
    """Compiled walk of :func:`medialaxis.core.graph.branches`: chains as flat nodes and offsets."""
    m = edges.shape[0]
    used = np.zeros(m, np.bool_)
    nodes = np.empty(2 * m + 1, np.int64)
    offsets = np.zeros(m + 1, np.int64)
    n_nodes, n_chains = 0, 0
    n = deg.shape[0]
    for phase in range(2):
        for item in range(n if phase == 0 else m):
            if phase == 0:
                if deg[item] == 2 or deg[item] == 0:
                    continue
                start = item
                lo, hi = indptr[start], indptr[start + 1]
            else:
                if used[item]:
                    continue
                start = edges[item, 0]
                lo, hi = indptr[start], indptr[start + 1]
            for k0 in range(lo, hi):
                if used[eids[k0]] or (phase == 1 and eids[k0] != item):
                    continue
                k = k0
                nodes[n_nodes] = start
                n_nodes += 1
                while True:
                    used[eids[k]] = True
                    node = nbrs[k]
                    nodes[n_nodes] = node
                    n_nodes += 1
                    if deg[node] != 2 or node == start:
                        break
                    nxt = -1
                    for j in range(indptr[node], indptr[node + 1]):
                        if not used[eids[j]]:
                            nxt = j
                            break
                    if nxt < 0:
                        break
                    k = nxt
                n_chains += 1
                offsets[n_chains] = n_nodes
                if phase == 1:
                    break
    return nodes[:n_nodes], offsets[: n_chains + 1]


@njit(cache=True, nogil=True)
def neighbour_lists(n, edges):  # type: ignore[no-untyped-def]
    """CSR ``(indptr, neighbours, edge ids)`` and degrees of a multigraph by a counting sort.

    The order of a stable sort of both edge ends (at each node, the edges
    it is the first end of, in edge order, then those it is the second end
    of), as :func:`medialaxis.core.graph.branches_reference` builds them with
    ``np.argsort``: each edge listed at both ends, a self-loop twice.
    """
    m = edges.shape[0]
    indptr = np.zeros(n + 1, np.int64)
    for side in range(2):
        for e in range(m):
            indptr[edges[e, side] + 1] += 1
    for i in range(n):
        indptr[i + 1] += indptr[i]
    deg = np.empty(n, np.int64)
    for i in range(n):
        deg[i] = indptr[i + 1] - indptr[i]
    fill = indptr[:-1].copy()
    nbrs = np.empty(2 * m, np.int64)
    eids = np.empty(2 * m, np.int64)
    for side in range(2):  # first ends, then second ends, each in edge order: a stable sort of both
        for e in range(m):
            a = edges[e, side]
            nbrs[fill[a]] = edges[e, 1 - side]
            eids[fill[a]] = e
            fill[a] += 1
    return indptr, nbrs, eids, deg


@njit(cache=True, nogil=True)
def collapse_free_faces_kernel(of_face, face_alive, n_edges):  # type: ignore[no-untyped-def]
    """Remove faces through free edges (an edge of one alive face) until none is left; in place.

    ``of_face`` is ``(k, 3)``, the edge index of each face side; ``face_alive``
    flags the faces taking part. A stack of free edges replaces rounds over
    all faces (a sheet of a million faces collapses from its border inwards,
    one ring of faces a round). Which faces are left does not depend on the
    order: a face with a free edge keeps it until the face goes. Returns the
    ``(n_edges,)`` flags of the edges left (those collapsed through are not).
    """
    count = np.zeros(n_edges, np.int64)
    for f in range(of_face.shape[0]):
        if face_alive[f]:
            for j in range(3):
                count[of_face[f, j]] += 1
    ptr = np.zeros(n_edges + 1, np.int64)  # the alive faces of each edge
    for e in range(n_edges):
        ptr[e + 1] = ptr[e] + count[e]
    fill = ptr[:-1].copy()
    faces_of = np.empty(ptr[n_edges], np.int64)
    for f in range(of_face.shape[0]):
        if face_alive[f]:
            for j in range(3):
                e = of_face[f, j]
                faces_of[fill[e]] = f
                fill[e] += 1
    edge_alive = np.ones(n_edges, np.bool_)
    stack = np.empty(n_edges + 3 * of_face.shape[0], np.int64)
    top = 0
    for e in range(n_edges):
        if count[e] == 1:
            stack[top] = e
            top += 1
    while top > 0:
        top -= 1
        e = stack[top]
        if count[e] != 1 or not edge_alive[e]:
            continue
        f = -1
        for k in range(ptr[e], ptr[e + 1]):
            if face_alive[faces_of[k]]:
                f = faces_of[k]
                break
        face_alive[f] = False
        edge_alive[e] = False
        for j in range(3):
            other = of_face[f, j]
            count[other] -= 1
            if count[other] == 1 and edge_alive[other]:
                stack[top] = other
                top += 1
    return edge_alive
