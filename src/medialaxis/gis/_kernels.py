"""Compiled per-feature steps of the GIS layers: an axis's branches as flat vertex lists.

:func:`branch_chains` is :func:`medialaxis.core.graph.branches` (its
reference in the tests) in one compiled call: the neighbour lists by a
stable counting sort (the order of ``np.argsort(kind="stable")`` on both
edge ends, so the walks, their order and their direction are the same),
then :func:`medialaxis.core._kernels.branch_walks`; the chains come back
flat, ready for ``shapely.linestrings(..., indices=...)``.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit
from medialaxis.core._kernels import branch_walks

__all__ = ["branch_chains"]


@njit(cache=True, nogil=True)
def branch_chains(n, edges):  # type: ignore[no-untyped-def]
    """``(nodes, part)``: every chain's nodes one after the other and the chain each belongs to."""
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
    nodes, offsets = branch_walks(indptr, nbrs, eids, deg, edges)
    part = np.empty(len(nodes), np.int64)
    for c in range(len(offsets) - 1):
        part[offsets[c]:offsets[c + 1]] = c
    return nodes, part
