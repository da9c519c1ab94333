"""Compiled pairwise step of the shape distance (the axis tour), with a NumPy reference.

Signatures are packed into flat arrays (:func:`pack_tour`) so that a whole
block of pairs is scored in one ``nogil`` call: threads then run in parallel.

The cost of matching tour sample ``i`` of A with sample ``k`` of B is half
the squared Hellinger distance of their histograms plus
``|r - r'| / (r + r')``; B's cyclic sequence is aligned to A's, keeping the
order, each skipped sample of either costing ``gap``, from ``TOUR_SHIFTS``
starting offsets and within ``TOUR_BAND`` samples of the diagonal; the least
total over the pairs of versions of one group (tour, mirror image), divided by
the mean sample count, and the least over the groups (the axis; the axis
before the method's pruning; the shape closed, slits filled, charged
``CLOSING_PENALTY`` times the larger area fraction the closing changed in
either shape).
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit

__all__ = [
    "EPS", "precedes", "pack_tour", "tour_distances", "tour_match_reference", "TOUR_SHIFTS", "TOUR_BAND",
    "CLOSING_PENALTY",
]

EPS = 1e-12


# ------------------------------------------------------------- axis tour
#: Cyclic starting offsets tried when aligning two tours (every ``k // TOUR_SHIFTS``-th
#: sample), and how far (in samples) an alignment may drift from the diagonal.
#: Chosen on Kimia-99 for time at equal row: 8 shifts and a band of 16 give
#: the row of all 64 shifts without band within 1, at a quarter of the time.
TOUR_SHIFTS = 8
TOUR_BAND = 16
#: Charge on comparing the closed shapes, per unit of the larger area
#: fraction the closing changed in either shape. Without it (plain least over
#: all versions) closed octopuses, jars and lizards, whose limbs and handles
#: the closing merges, match other blobs. MPEG-7 dev (35 classes; a side
#: study on a copy of this kernel, the matrix of each pair of versions combined
#: afterwards; the axis at two prunings and the closed axis at both): no charge
#: 90.04%, 0.5 90.58%, 1 90.75%, 2 89.99%, 4 89.09%; choosing the charge on four
#: class folds and scoring the fifth picks 0.75-1 and gives 90.71%. With the
#: versions kept (the axis, the raw axis, the closed axis): 0.75 90.86%,
#: 1 90.85%, 1.5 90.39% (issue 15).
CLOSING_PENALTY = 1.0


def pack_tour(tours: list[np.ndarray], radii: list[np.ndarray], gains: list[float]) -> tuple[np.ndarray, ...]:
    """Pack per-shape tours for :func:`tour_distances`.

    ``tours[s]``: shape ``s``'s histograms ``(v, t, h)`` in ``v`` versions,
    an even number: (tour, mirror image) for each axis compared, the last
    pair the closed shape's when there are several (see :class:`~medialaxis.compare.Signature`);
    ``radii[s]``: ``(v, t)``; ``gains[s]``: the area fraction its closing changed.
    Returns ``(sqrt_histograms (v, sum t, h), radii (v, sum t),
    squared_norms (v, sum t), offsets (n+1,), gains (n,))``: square roots, so that half
    the squared Hellinger distance is ``0.5 (|a|^2 + |b|^2) - a.b``.
    """
    offsets = np.zeros(len(tours) + 1, np.int64)
    offsets[1:] = np.cumsum([t.shape[1] for t in tours])
    roots = np.ascontiguousarray(np.sqrt(np.maximum(np.concatenate(tours, axis=1), 0.0)), np.float64)
    flat_radii = np.ascontiguousarray(np.concatenate(radii, axis=1), np.float64)
    norms = np.ascontiguousarray((roots * roots).sum(axis=2))
    return roots, flat_radii, norms, offsets, np.ascontiguousarray(gains, np.float64).reshape(len(tours))


@njit(cache=True, nogil=True)
def _tour_costs(ha, ra, na2, hb, rb, nb2):  # pragma: no cover - compiled
    """``C[i, k]`` (columns repeated twice): half the squared Hellinger distance plus the relative radius difference."""
    na, nb = ha.shape[0], hb.shape[0]
    gram = ha @ np.ascontiguousarray(hb.T)
    cost = np.empty((na, 2 * nb))
    for i in range(na):
        for k in range(nb):
            x = max(0.0, 0.5 * (na2[i] + nb2[k]) - gram[i, k]) + abs(ra[i] - rb[k]) / (ra[i] + rb[k] + EPS)
            cost[i, k] = x
            cost[i, k + nb] = x
    return cost


@njit(cache=True, nogil=True)
def _cyclic_align(cost, nb, gap, stride, band, table, bound):  # pragma: no cover - compiled
    """Least order-keeping alignment of A's samples to B's started at ``0, stride, ...``.

    Each skipped sample costs ``gap``; the alignment stays within ``band``
    samples of the diagonal ``k = i nb / na``. ``table`` is ``(na + 1, nb + 1)`` scratch.
    A start is abandoned once every cell of a row reaches ``bound`` or the
    best total so far (costs are >= 0 and every alignment crosses every row),
    so the result is exact when below ``bound`` and ``inf`` when no
    alignment is.
    """
    na = cost.shape[0]
    big = np.inf
    best = bound
    for s in range(0, nb, stride):
        abandoned = False
        for k in range(nb + 1):
            table[0, k] = k * gap if k <= band else big
        for i in range(1, na + 1):
            centre = (i * nb) // na
            lo = max(1, centre - band)
            hi = min(nb, centre + band)
            left = i * gap if lo == 1 else big  # the cell to the left, kept in a register
            table[i, lo - 1] = left
            low = left
            for k in range(lo, hi + 1):
                left = min(table[i - 1, k - 1] + cost[i - 1, k - 1 + s], min(table[i - 1, k], left) + gap)
                table[i, k] = left
                low = min(low, left)
            reach = min(nb, ((i + 1) * nb) // na + band) if i < na else hi
            for k in range(hi + 1, reach + 1):
                table[i, k] = big
            if low >= best:
                abandoned = True
                break
        if not abandoned and table[na, nb] < best:
            best = table[na, nb]
    return best if best < bound else np.inf


@njit(cache=True, nogil=True)
def _tour_pair(roots, radii, norms, oa, ea, ob, eb, gap, penalty):  # pragma: no cover - compiled
    """Tour distance of shapes A (rows ``oa:ea``) and B: least over the groups of versions.

    The closed shapes' group (the last of several) is charged ``penalty``.
    """
    na, nb = ea - oa, eb - ob
    stride = max(1, nb // TOUR_SHIFTS)
    table = np.empty((na + 1, nb + 1))
    scale = 0.5 * (na + nb)
    n_groups = roots.shape[0] // 2
    best = np.inf
    # Versions come in pairs (a tour, its mirror image), one pair per group (an axis of the
    # shape or of the closed shape). Within each group, every version of A against every
    # version of B: a set that mirroring either shape leaves unchanged, so the value is exactly
    # mirror invariant.
    for version in range(2 * roots.shape[0]):
        group, va, vb = version // 4, (version // 2) % 2, version % 2
        extra = penalty if group == n_groups - 1 > 0 else 0.0  # the last pair: the closed shape
        if extra >= best:
            continue
        va += 2 * group
        vb += 2 * group
        cost = _tour_costs(roots[va, oa:ea], radii[va, oa:ea], norms[va, oa:ea],
                           roots[vb, ob:eb], radii[vb, ob:eb], norms[vb, ob:eb])
        value = _cyclic_align(cost, nb, gap, stride, TOUR_BAND, table, (best - extra) * scale) / scale + extra
        if value < best:
            best = value
    return best


@njit(cache=True, nogil=True)
def precedes(hb, rb, ha, ra):  # pragma: no cover - compiled
    """Content order of two descriptors (sample count, then radii, then histograms); False if equal."""
    if len(rb) != len(ra):
        return len(rb) < len(ra)
    for i in range(len(rb)):
        if rb[i] != ra[i]:
            return rb[i] < ra[i]
    for i in range(hb.shape[0]):
        for t in range(hb.shape[1]):
            if hb[i, t] != ha[i, t]:
                return hb[i, t] < ha[i, t]
    return False


@njit(cache=True, nogil=True)
def _tour_precedes(roots, radii, oa, ea, ob, eb):  # pragma: no cover - compiled
    """Content order of two packed tours (first version): sample count, radii, histograms; False if equal."""
    return precedes(roots[0, ob:eb], radii[0, ob:eb], roots[0, oa:ea], radii[0, oa:ea])


@njit(cache=True, nogil=True)
def tour_distances(roots, radii, norms, offsets, gains, rows, cols, gap):  # pragma: no cover - compiled
    """Tour distances of the pairs ``(rows[p], cols[p])`` of packed tours (see :func:`pack_tour`).

    Per pair: B's tour is aligned cyclically to A's (:func:`_cyclic_align`)
    for every pair of versions of the same group (the tours and their
    mirror images), the least total divided by the mean sample count, plus
    ``CLOSING_PENALTY * max(gains[a], gains[b])`` for the closed shapes' group;
    the least over the groups. Each pair is
    computed in an order fixed by the contents of the two tours, so the value
    is exactly symmetric; equal tours give exactly 0.
    """
    out = np.empty(len(rows))
    for p in range(len(rows)):
        a, b = rows[p], cols[p]
        oa, ea, ob, eb = offsets[a], offsets[a + 1], offsets[b], offsets[b + 1]
        if _tour_precedes(roots, radii, oa, ea, ob, eb):
            oa, ea, ob, eb = ob, eb, oa, ea
        elif not _tour_precedes(roots, radii, ob, eb, oa, ea):
            out[p] = 0.0  # same contents
            continue
        out[p] = _tour_pair(roots, radii, norms, oa, ea, ob, eb, gap, CLOSING_PENALTY * max(gains[a], gains[b]))
    return out


def tour_match_reference(
    tour_a: np.ndarray, radii_a: np.ndarray, tour_b: np.ndarray, radii_b: np.ndarray, gap: float,
    gain_a: float = 0.0, gain_b: float = 0.0,
) -> tuple[float, int, int, list[tuple[int, int]]]:
    """NumPy version of one :func:`tour_distances` value, with the alignment behind it.

    ``tour_a (v, t, h)``, ``radii_a (v, t)``: plain histograms and radii of
    A's tour versions (as in :func:`pack_tour`), ``gain_a`` its closing's
    area fraction; same for B. Computed in the
    order given (the compiled kernel orders each pair by content, which can
    change the last bits). Returns ``(distance, version of A, version of B,
    pairs)``: the versions whose alignment was best and the aligned sample
    pairs ``(i of A, k of B)`` in those versions.
    """
    n_versions = min(len(tour_a), len(tour_b))
    pairs_of_versions = [(g + i, g + k) for g in range(0, n_versions, 2) for i in (0, 1) for k in (0, 1)]
    penalty = CLOSING_PENALTY * max(gain_a, gain_b)
    na, nb = tour_a.shape[1], tour_b.shape[1]
    if na == nb and np.array_equal(tour_a[0], tour_b[0]) and np.array_equal(radii_a[0], radii_b[0]):
        return 0.0, 0, 0, [(i, i) for i in range(na)]
    stride = max(1, nb // TOUR_SHIFTS)
    best: tuple[float, int, int, list[tuple[int, int]]] = (np.inf, 0, 0, [])
    centre = (np.arange(na + 1) * nb) // na
    for va, vb in pairs_of_versions:
        ha, ra, hb, rb = tour_a[va], radii_a[va], tour_b[vb], radii_b[vb]
        hell = 0.5 * ((np.sqrt(ha)[:, None, :] - np.sqrt(hb)[None, :, :]) ** 2).sum(axis=2)
        cost = hell + np.abs(ra[:, None] - rb[None, :]) / (ra[:, None] + rb[None, :] + EPS)
        for s in range(0, nb, stride):
            c = np.roll(cost, -s, axis=1)
            table = np.full((na + 1, nb + 1), np.inf)
            table[0, : TOUR_BAND + 1] = np.arange(min(nb, TOUR_BAND) + 1) * gap
            for i in range(1, na + 1):
                lo, hi = max(1, centre[i] - TOUR_BAND), min(nb, centre[i] + TOUR_BAND)
                if lo == 1:
                    table[i, 0] = i * gap
                for k in range(lo, hi + 1):
                    table[i, k] = min(
                        table[i - 1, k - 1] + c[i - 1, k - 1], table[i - 1, k] + gap, table[i, k - 1] + gap
                    )
            extra = penalty if va // 2 == n_versions // 2 - 1 > 0 else 0.0
            if table[na, nb] / (0.5 * (na + nb)) + extra < best[0]:
                pairs, i, k = [], na, nb
                while i > 0 and k > 0:
                    if table[i, k] == table[i - 1, k - 1] + c[i - 1, k - 1]:
                        pairs.append((i - 1, (k - 1 + s) % nb))
                        i, k = i - 1, k - 1
                    elif table[i, k] == table[i - 1, k] + gap:
                        i -= 1
                    else:
                        k -= 1
                best = (float(table[na, nb]) / (0.5 * (na + nb)) + extra, va, vb, pairs[::-1])
    return best
