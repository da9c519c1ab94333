"""Compiled pairwise step of the skeleton-path distance, with NumPy references.

Signatures are packed into flat arrays (see :func:`pack`) so that a whole
block of pairs is scored in one ``nogil`` call: threads then run in parallel.

Per pair (Bai and Latecki, TPAMI 2008):

1. path cost between path ``(i, j)`` of shape A and path ``(k, l)`` of B:
   ``mean_t (r_t - r'_t)**2 / (r_t + r'_t) + alpha * (L - L')**2 / (L + L')``;
2. endpoint cost ``C[i, k]``: the paths leaving ``i`` (in boundary order)
   aligned to those leaving ``k`` by dynamic programming that keeps the order
   and may skip a path at cost ``skip``;
3. the endpoints matched one-to-one (Hungarian); each unmatched endpoint costs
   ``unmatched``; both boundary orientations of B are tried (mirror
   invariance) and the smaller total, divided by the larger endpoint count,
   is the distance.
"""

from __future__ import annotations

import numpy as np
from numba import njit
from scipy.optimize import linear_sum_assignment

__all__ = ["pack", "pair_distances", "reference_distance", "path_costs_reference", "EPS"]

EPS = 1e-12


def pack(radii: list[np.ndarray], lengths: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Pack per-shape ``(e, e, s)`` radii and ``(e, e)`` lengths into flat arrays.

    Returns ``(flat_radii (sum e*e, s), flat_lengths (sum e*e,), offsets (n+1,), counts (n,))``.
    """
    counts = np.array([len(L) for L in lengths], np.int64)
    offsets = np.zeros(len(counts) + 1, np.int64)
    offsets[1:] = np.cumsum(counts * counts)
    n_samples = radii[0].shape[2] if radii else 1
    flat_r = np.concatenate([r.reshape(-1, n_samples) for r in radii]) if radii else np.zeros((0, 1))
    flat_l = np.concatenate([L.reshape(-1) for L in lengths]) if lengths else np.zeros(0)
    return np.ascontiguousarray(flat_r, np.float64), np.ascontiguousarray(flat_l, np.float64), offsets, counts


# --------------------------------------------------------------- compiled
@njit(cache=True, nogil=True)
def _path_costs(ra, la, na, rb, lb, nb, alpha):  # pragma: no cover - compiled
    s = ra.shape[1]
    out = np.zeros((na * na, nb * nb))
    for p in range(na * na):
        for q in range(nb * nb):
            acc = 0.0
            for t in range(s):
                x = ra[p, t]
                y = rb[q, t]
                acc += (x - y) * (x - y) / (x + y + EPS)
            x = la[p]
            y = lb[q]
            out[p, q] = acc / s + alpha * (x - y) * (x - y) / (x + y + EPS)
    return out


@njit(cache=True, nogil=True)
def _align(pc, i, k, na, nb, reverse, skip, table):  # pragma: no cover - compiled
    """Order-keeping alignment of the paths leaving endpoint i (A) and k (B)."""
    m = na - 1
    n = nb - 1
    for a in range(m + 1):
        table[a, 0] = a * skip
    for b in range(n + 1):
        table[0, b] = b * skip
    for a in range(1, m + 1):
        j = (i + a) % na
        for b in range(1, n + 1):
            if reverse:
                l = (k - b) % nb
            else:
                l = (k + b) % nb
            best = table[a - 1, b - 1] + pc[i * na + j, k * nb + l]
            alt = table[a - 1, b] + skip
            if alt < best:
                best = alt
            alt = table[a, b - 1] + skip
            if alt < best:
                best = alt
            table[a, b] = best
    return table[m, n]


@njit(cache=True, nogil=True)
def _assignment(cost):  # pragma: no cover - compiled
    """Minimum total of a one-to-one assignment of the rows of ``cost`` (rows <= cols).

    Shortest augmenting paths with potentials (Kuhn-Munkres, O(n^2 m)).
    """
    n, m = cost.shape
    inf = np.inf
    u = np.zeros(n + 1)
    v = np.zeros(m + 1)
    match = np.zeros(m + 1, np.int64)  # match[j] = row (1-based) assigned to column j
    way = np.zeros(m + 1, np.int64)
    minv = np.empty(m + 1)
    used = np.empty(m + 1, np.bool_)
    for i in range(1, n + 1):
        match[0] = i
        j0 = 0
        minv[:] = inf
        used[:] = False
        while True:
            used[j0] = True
            i0 = match[j0]
            delta = inf
            j1 = 0
            for j in range(1, m + 1):
                if not used[j]:
                    cur = cost[i0 - 1, j - 1] - u[i0] - v[j]
                    if cur < minv[j]:
                        minv[j] = cur
                        way[j] = j0
                    if minv[j] < delta:
                        delta = minv[j]
                        j1 = j
            for j in range(m + 1):
                if used[j]:
                    u[match[j]] += delta
                    v[j] -= delta
                else:
                    minv[j] -= delta
            j0 = j1
            if match[j0] == 0:
                break
        while True:
            j1 = way[j0]
            match[j0] = match[j1]
            j0 = j1
            if j0 == 0:
                break
    total = 0.0
    for j in range(1, m + 1):
        if match[j] != 0:
            total += cost[match[j] - 1, j - 1]
    return total


@njit(cache=True, nogil=True)
def _pair(ra, la, na, rb, lb, nb, alpha, skip, unmatched):  # pragma: no cover - compiled
    pc = _path_costs(ra, la, na, rb, lb, nb, alpha)
    table = np.empty((na, nb))
    best = np.inf
    for reverse in (False, True):
        if na <= nb:
            c = np.empty((na, nb))
            for i in range(na):
                for k in range(nb):
                    c[i, k] = _align(pc, i, k, na, nb, reverse, skip, table)
        else:
            c = np.empty((nb, na))
            for i in range(na):
                for k in range(nb):
                    c[k, i] = _align(pc, i, k, na, nb, reverse, skip, table)
        total = _assignment(c)
        if total < best:
            best = total
    return (best + unmatched * abs(na - nb)) / max(na, nb)


@njit(cache=True, nogil=True)
def pair_distances(flat_r, flat_l, offsets, counts, rows, cols, alpha, skip, unmatched):  # pragma: no cover
    """Distances of the pairs ``(rows[p], cols[p])`` of packed signatures; returns ``(p,)``."""
    out = np.empty(len(rows))
    for p in range(len(rows)):
        a = rows[p]
        b = cols[p]
        na = counts[a]
        nb = counts[b]
        ra = flat_r[offsets[a]:offsets[a + 1]]
        la = flat_l[offsets[a]:offsets[a + 1]]
        rb = flat_r[offsets[b]:offsets[b + 1]]
        lb = flat_l[offsets[b]:offsets[b + 1]]
        out[p] = _pair(ra, la, na, rb, lb, nb, alpha, skip, unmatched)
    return out


# -------------------------------------------------------------- references
def path_costs_reference(
    ra: np.ndarray, la: np.ndarray, rb: np.ndarray, lb: np.ndarray, alpha: float
) -> np.ndarray:
    """NumPy path cost tensor ``(na, na, nb, nb)`` of two signatures."""
    x = ra[:, :, None, None, :]
    y = rb[None, None, :, :, :]
    radius = ((x - y) ** 2 / (x + y + EPS)).mean(axis=-1)
    lx = la[:, :, None, None]
    ly = lb[None, None, :, :]
    return radius + alpha * (lx - ly) ** 2 / (lx + ly + EPS)


def _align_reference(seq_costs: np.ndarray, skip: float) -> float:
    m, n = seq_costs.shape
    table = np.zeros((m + 1, n + 1))
    table[:, 0] = np.arange(m + 1) * skip
    table[0, :] = np.arange(n + 1) * skip
    for a in range(1, m + 1):
        for b in range(1, n + 1):
            table[a, b] = min(table[a - 1, b - 1] + seq_costs[a - 1, b - 1], table[a - 1, b] + skip, table[a, b - 1] + skip)
    return float(table[m, n])


def reference_distance(
    ra: np.ndarray, la: np.ndarray, rb: np.ndarray, lb: np.ndarray, alpha: float, skip: float, unmatched: float
) -> float:
    """Pure NumPy/SciPy version of the compiled pair distance (used by the tests)."""
    na, nb = len(la), len(lb)
    pc = path_costs_reference(ra, la, rb, lb, alpha)
    best = np.inf
    for reverse in (False, True):
        c = np.empty((na, nb))
        for i in range(na):
            seq_a = np.array([(i + a) % na for a in range(1, na)], np.int64)
            for k in range(nb):
                seq_b = np.array([((k - b) if reverse else (k + b)) % nb for b in range(1, nb)], np.int64)
                c[i, k] = _align_reference(pc[i, seq_a, k][:, seq_b], skip)
        rows, cols = linear_sum_assignment(c)
        best = min(best, float(c[rows, cols].sum()))
    return (best + unmatched * abs(na - nb)) / max(na, nb)
