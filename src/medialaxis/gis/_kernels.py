"""Compiled per-feature steps of the GIS layers: an axis's branches as flat vertex lists.

:func:`branch_chains` is :func:`medialaxis.core.graph.branches` (its
reference in the tests) in one compiled call: the same kernels
(:func:`medialaxis.core._kernels.neighbour_lists`, then
:func:`~medialaxis.core._kernels.branch_walks`), the chains flat, ready for
``shapely.linestrings(..., indices=...)``.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit
from medialaxis.core._kernels import branch_walks, neighbour_lists

__all__ = ["branch_chains"]


@njit(cache=True, nogil=True)
def branch_chains(n, edges):  # type: ignore[no-untyped-def]
    """``(nodes, part)``: every chain's nodes one after the other and the chain each belongs to."""
    indptr, nbrs, eids, deg = neighbour_lists(n, edges)
    nodes, offsets = branch_walks(indptr, nbrs, eids, deg, edges)
    part = np.empty(len(nodes), np.int64)
    for c in range(len(offsets) - 1):
        part[offsets[c]:offsets[c + 1]] = c
    return nodes, part
