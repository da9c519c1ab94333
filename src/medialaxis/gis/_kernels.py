"""Compiled per-feature steps of the GIS layers: an axis's branches as flat vertex lists.

:func:`branch_chains` is :func:`medialaxis.core.graph.branches` (its
reference in the tests) in one compiled call: the same kernels
(:func:`medialaxis.core._kernels.neighbour_lists`, then
:func:`~medialaxis.core._kernels.branch_walks`), the chains flat, ready for
``shapely.linestrings(..., indices=...)``. :func:`axis_widths_kernel` is
``axis_widths_reference`` (``tests/gis_reference.py``) with NumPy's sums
(:func:`pairwise_sum`, the pairwise summation of ``np.add.reduce``), so the
same widths to the last bit (tested).
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit
from medialaxis.core._kernels import branch_walks, neighbour_lists

__all__ = ["branch_chains", "pairwise_sum", "axis_widths_kernel"]


@njit(cache=True, nogil=True)
def branch_chains(n, edges):  # type: ignore[no-untyped-def]
    """``(nodes, part)``: every chain's nodes one after the other and the chain each belongs to."""
    indptr, nbrs, eids, deg = neighbour_lists(n, edges)
    nodes, offsets = branch_walks(indptr, nbrs, eids, deg, edges)
    part = np.empty(len(nodes), np.int64)
    for c in range(len(offsets) - 1):
        part[offsets[c]:offsets[c + 1]] = c
    return nodes, part


@njit(cache=True, nogil=True, inline="always")
def _block_sum(a, lo, n):  # type: ignore[no-untyped-def]
    """NumPy's sum of a run of at most 128 values: one by one under 8, else eight running sums."""
    if n < 8:
        res = 0.0
        for i in range(lo, lo + n):
            res += a[i]
        return res
    r0, r1, r2, r3 = a[lo], a[lo + 1], a[lo + 2], a[lo + 3]
    r4, r5, r6, r7 = a[lo + 4], a[lo + 5], a[lo + 6], a[lo + 7]
    i = 8
    while i < n - n % 8:
        r0, r1, r2, r3 = r0 + a[lo + i], r1 + a[lo + i + 1], r2 + a[lo + i + 2], r3 + a[lo + i + 3]
        r4, r5, r6, r7 = r4 + a[lo + i + 4], r5 + a[lo + i + 5], r6 + a[lo + i + 6], r7 + a[lo + i + 7]
        i += 8
    res = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
    while i < n:
        res += a[lo + i]
        i += 1
    return res


@njit(cache=True, nogil=True)
def pairwise_sum(a, lo, n):  # type: ignore[no-untyped-def]
    """``np.sum(a[lo:lo + n])`` of a contiguous float64 array, in NumPy's order (its ``pairwise_sum``: runs of
    at most 128 values summed by :func:`_block_sum`, a longer run as the sum of its two halves, the first
    half a multiple of 8). The halving is walked with a stack (numba's cache does not keep recursion)."""
    if n <= 128:
        return _block_sum(a, lo, n)
    run_lo = np.empty(128, np.int64)
    run_n = np.empty(128, np.int64)
    join = np.zeros(128, np.bool_)
    sums = np.empty(128)
    top, depth = 0, 0
    run_lo[0], run_n[0] = lo, n
    while top >= 0:
        at, size, both = run_lo[top], run_n[top], join[top]
        top -= 1
        if both:  # the two halves are summed: add them in order
            sums[depth - 2] = sums[depth - 2] + sums[depth - 1]
            depth -= 1
        elif size <= 128:
            sums[depth] = _block_sum(a, at, size)
            depth += 1
        else:
            half = size // 2
            half -= half % 8
            run_lo[top + 1], run_n[top + 1], join[top + 1] = at, size, True
            run_lo[top + 2], run_n[top + 2], join[top + 2] = at + half, size - half, False
            run_lo[top + 3], run_n[top + 3], join[top + 3] = at, half, False
            top += 3
    return sums[0]


@njit(cache=True, nogil=True)
def axis_widths_kernel(points, radii, edges):  # type: ignore[no-untyped-def]
    """Twice the smallest, the length-weighted mean (twice) and twice the largest radius (NaN without a node)."""
    n, m = len(radii), len(edges)
    if n == 0:
        return np.nan, np.nan, np.nan
    lo, hi = radii[0], radii[0]
    for i in range(n):
        lo, hi = min(lo, radii[i]), max(hi, radii[i])
    if m == 0:  # summed from a copy: the caller's read-only radii would compile pairwise_sum a second time
        return 2 * lo, 2 * (pairwise_sum(radii.copy(), 0, n) / n), 2 * hi
    length = np.empty(m)
    weighted = np.empty(m)
    for e in range(m):
        a, b = edges[e, 0], edges[e, 1]
        dx, dy = points[a, 0] - points[b, 0], points[a, 1] - points[b, 1]
        length[e] = np.sqrt(dx * dx + dy * dy)
        weighted[e] = length[e] * (radii[a] + radii[b])
    return 2 * lo, pairwise_sum(weighted, 0, m) / max(pairwise_sum(length, 0, m), 1e-300), 2 * hi
