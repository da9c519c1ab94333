"""Compiled skeleton-path term (Bai and Latecki, TPAMI 2008), with NumPy references; moved out of the package.

Per pair:

1. path cost between path ``(i, j)`` of shape A and path ``(k, l)`` of B, with
   ``chi(x, y) = (x - y)**2 / (x + y)``:
   ``mean_t chi(r_t, r'_t) + alpha chi(L, L') + beta chi(C, C') + gamma mean_k chi(b_k, b'_k)``
   (radius function ``r``, path length ``L``, chord ``C``, bend profile ``b``;
   Bai and Latecki use the first two terms);
2. endpoint cost ``C[i, k]``: the paths leaving ``i`` (in boundary order)
   aligned to those leaving ``k`` by dynamic programming that keeps the order
   and may skip a path at cost ``skip``;
3. the endpoints matched one-to-one (Hungarian); each unmatched endpoint costs
   ``unmatched``; both boundary orientations of B are tried (mirror
   invariance) and the smaller total, divided by the mean endpoint count
   ``(na + nb) / 2``, is the distance (the larger count, used before, let a
   shape with many endpoints look close to one with few: -13 on the
   Kimia-99 row).

Measured on MPEG-7 (35 dev classes, not the Kimia-99 set it was tuned on):
the tour alone 87.59%, with 0.1 paths 87.64%, with 0.3 paths 87.65%: the
term does not earn its cost there (it is most of the pair time when on), so
it left the package (issue 17); see :mod:`research`.

:func:`assignment` (compiled Hungarian) serves this term and the axis
context (:mod:`research.axis_context`).
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import linear_sum_assignment

from medialaxis._jit import njit
from medialaxis.compare._kernels import EPS

__all__ = [
    "FORBIDDEN", "assignment", "pack", "pair_distances", "reference_distance", "reference_match",
    "path_costs_reference",
]

#: Cost of a forbidden assignment (finite so the potentials stay finite).
FORBIDDEN = 1e12


@njit(cache=True, nogil=True)
def assignment(cost):  # pragma: no cover - compiled
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


Packed = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, int]


def pack(
    radii: list[np.ndarray],
    lengths: list[np.ndarray],
    chords: list[np.ndarray],
    bends: list[np.ndarray],
    weights: list[np.ndarray],
) -> Packed:
    """Pack per-shape path features into flat arrays for :func:`pair_distances`.

    Per shape: radii ``(e, e, s)``, lengths and chords ``(e, e)``, bends
    ``(e, e, b)``, weights ``(e,)``. Returns ``(profiles (sum e*e, s + b),
    scalars (sum e*e, 2), offsets (n+1,), flat_weights (sum e,),
    weight_offsets (n+1,), counts (n,), s)``.
    """
    counts = np.array([len(L) for L in lengths], np.int64)
    offsets = np.zeros(len(counts) + 1, np.int64)
    offsets[1:] = np.cumsum(counts * counts)
    w_offsets = np.zeros(len(counts) + 1, np.int64)
    w_offsets[1:] = np.cumsum(counts)
    n_samples = radii[0].shape[2]
    n_bend = bends[0].shape[2]
    profiles = np.concatenate(
        [np.concatenate([r.reshape(-1, n_samples), b.reshape(-1, n_bend)], axis=1) for r, b in zip(radii, bends)]
    )
    scalars = np.concatenate([np.column_stack([L.reshape(-1), C.reshape(-1)]) for L, C in zip(lengths, chords)])
    flat_w = np.concatenate([np.reshape(w, -1) for w in weights])
    return (
        np.ascontiguousarray(profiles, np.float64),
        np.ascontiguousarray(scalars, np.float64),
        offsets,
        np.ascontiguousarray(flat_w, np.float64),
        w_offsets,
        counts,
        int(n_samples),
    )


@njit(cache=True, nogil=True)
def _chi(x, y):  # pragma: no cover - compiled
    return (x - y) * (x - y) / (x + y + EPS)


@njit(cache=True, nogil=True)
def _path_costs(pa, sa, na, pb, sb, nb, n_radius, alpha, beta, gamma):  # pragma: no cover - compiled
    n_cols = pa.shape[1]
    n_bend = n_cols - n_radius
    out = np.zeros((na * na, nb * nb))
    for p in range(na * na):
        for q in range(nb * nb):
            radius = 0.0
            for t in range(n_radius):
                radius += _chi(pa[p, t], pb[q, t])
            bend = 0.0
            for t in range(n_radius, n_cols):
                bend += _chi(pa[p, t], pb[q, t])
            cost = radius / n_radius + alpha * _chi(sa[p, 0], sb[q, 0]) + beta * _chi(sa[p, 1], sb[q, 1])
            if n_bend > 0:
                cost += gamma * bend / n_bend
            out[p, q] = cost
    return out


@njit(cache=True, nogil=True)
def _align(pc, i, k, na, nb, wa, wb, reverse, skip, table):  # pragma: no cover - compiled
    """Order-keeping alignment of the paths leaving endpoint i (A) and k (B).

    Skipping the path to endpoint j costs ``skip * w[j]``.
    """
    m = na - 1
    n = nb - 1
    table[0, 0] = 0.0
    for a in range(1, m + 1):
        table[a, 0] = table[a - 1, 0] + skip * wa[(i + a) % na]
    for b in range(1, n + 1):
        col = (k - b) % nb if reverse else (k + b) % nb
        table[0, b] = table[0, b - 1] + skip * wb[col]
    for a in range(1, m + 1):
        j = (i + a) % na
        skip_a = skip * wa[j]
        for b in range(1, n + 1):
            if reverse:
                col = (k - b) % nb
            else:
                col = (k + b) % nb
            best = table[a - 1, b - 1] + pc[i * na + j, k * nb + col]
            alt = table[a - 1, b] + skip_a
            if alt < best:
                best = alt
            alt = table[a, b - 1] + skip * wb[col]
            if alt < best:
                best = alt
            table[a, b] = best
    return table[m, n]


@njit(cache=True, nogil=True)
def _pair(pa, sa, wa, na, pb, sb, wb, nb, n_radius, alpha, beta, gamma, skip, unmatched):  # pragma: no cover
    pc = _path_costs(pa, sa, na, pb, sb, nb, n_radius, alpha, beta, gamma)
    table = np.empty((na, nb))
    size = na + nb
    # Augmented assignment: endpoint i of A may go to its own dummy column
    # (cost unmatched * wa[i]), endpoint k of B to its own dummy row.
    c = np.full((size, size), FORBIDDEN)
    c[na:, nb:] = 0.0
    for i in range(na):
        c[i, nb + i] = unmatched * wa[i]
    for k in range(nb):
        c[na + k, k] = unmatched * wb[k]
    best = np.inf
    for reverse in (False, True):
        for i in range(na):
            for k in range(nb):
                c[i, k] = _align(pc, i, k, na, nb, wa, wb, reverse, skip, table)
        total = assignment(c)
        if total < best:
            best = total
    return best / (0.5 * (na + nb))


@njit(cache=True, nogil=True)
def pair_distances(
    profiles, scalars, offsets, flat_w, w_offsets, counts, n_radius, rows, cols, alpha, beta, gamma, skip, unmatched
):  # pragma: no cover - compiled
    """Distances of the pairs ``(rows[p], cols[p])`` of packed signatures; returns ``(p,)``."""
    out = np.empty(len(rows))
    for p in range(len(rows)):
        a = rows[p]
        b = cols[p]
        out[p] = _pair(
            profiles[offsets[a]:offsets[a + 1]], scalars[offsets[a]:offsets[a + 1]], flat_w[w_offsets[a]:w_offsets[a + 1]],
            counts[a],
            profiles[offsets[b]:offsets[b + 1]], scalars[offsets[b]:offsets[b + 1]], flat_w[w_offsets[b]:w_offsets[b + 1]],
            counts[b],
            n_radius, alpha, beta, gamma, skip, unmatched,
        )
    return out


def _chi_reference(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    return (x - y) ** 2 / (x + y + EPS)


def path_costs_reference(
    ra: np.ndarray, la: np.ndarray, ca: np.ndarray, ba: np.ndarray,
    rb: np.ndarray, lb: np.ndarray, cb: np.ndarray, bb: np.ndarray,
    alpha: float, beta: float, gamma: float,
) -> np.ndarray:
    """NumPy path cost tensor ``(na, na, nb, nb)`` of two signatures."""
    def cross(x: np.ndarray, y: np.ndarray) -> np.ndarray:
        return _chi_reference(x[:, :, None, None, ...], y[None, None, ...])

    cost = cross(ra, rb).mean(axis=-1) + alpha * cross(la, lb) + beta * cross(ca, cb)
    if ba.shape[-1]:
        cost = cost + gamma * cross(ba, bb).mean(axis=-1)
    return cost


def _align_reference(seq_costs: np.ndarray, skip_a: np.ndarray, skip_b: np.ndarray) -> float:
    m, n = seq_costs.shape
    table = np.zeros((m + 1, n + 1))
    table[1:, 0] = np.cumsum(skip_a)
    table[0, 1:] = np.cumsum(skip_b)
    for a in range(1, m + 1):
        for b in range(1, n + 1):
            table[a, b] = min(
                table[a - 1, b - 1] + seq_costs[a - 1, b - 1],
                table[a - 1, b] + skip_a[a - 1],
                table[a, b - 1] + skip_b[b - 1],
            )
    return float(table[m, n])


def reference_distance(a: tuple[np.ndarray, ...], b: tuple[np.ndarray, ...], *params: float) -> float:
    """Pure NumPy/SciPy version of the compiled pair distance (used by the tests).

    ``a`` and ``b`` are ``(radii, lengths, chords, bends, weights)``; ``params``
    are ``alpha, beta, gamma, skip, unmatched``.
    """
    return reference_match(a, b, *params)[0]


def reference_match(
    a: tuple[np.ndarray, ...], b: tuple[np.ndarray, ...],
    alpha: float, beta: float, gamma: float, skip: float, unmatched: float,
) -> tuple[float, list[tuple[int, int]]]:
    """The pair distance and the endpoint pairs ``(i of A, k of B)`` it matched."""
    ra, la, ca, ba, wa = a
    rb, lb, cb, bb, wb = b
    na, nb = len(la), len(lb)
    pc = path_costs_reference(ra, la, ca, ba, rb, lb, cb, bb, alpha, beta, gamma)
    best = np.inf
    pairs: list[tuple[int, int]] = []
    for reverse in (False, True):
        c = np.full((na + nb, na + nb), FORBIDDEN)
        c[na:, nb:] = 0.0
        c[np.arange(na), nb + np.arange(na)] = unmatched * wa
        c[na + np.arange(nb), np.arange(nb)] = unmatched * wb
        for i in range(na):
            seq_a = np.array([(i + s) % na for s in range(1, na)], np.int64)
            for k in range(nb):
                seq_b = np.array([((k - s) if reverse else (k + s)) % nb for s in range(1, nb)], np.int64)
                c[i, k] = _align_reference(pc[i, seq_a, k][:, seq_b], skip * wa[seq_a], skip * wb[seq_b])
        rows, cols = linear_sum_assignment(c)
        total = float(c[rows, cols].sum())
        if total < best:
            best = total
            pairs = [(int(i), int(k)) for i, k in zip(rows, cols) if i < na and k < nb]
    return best / (0.5 * (na + nb)), pairs
