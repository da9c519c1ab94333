"""Compiled kernels of the volume pipeline, each with a pure-Python reference.

* :func:`topology_class`: Malandain's topological classification of the
  voxels of a thin sheet by counting the background components around each
  voxel (0 isolated, 1 boundary, 2 surface, 3 or more junction).
* :func:`greedy_subsample`: pick voxels in a priority order, removing the
  not-yet-picked ones within each pick's radius (Michikawa and Suzuki).
* :func:`subsample_certainty`: which of those decisions a window of the
  sheet decides for sure (the rest of the sheet may pick voxels that reach in).
* :func:`sheet_labels`: multi-source search on the 26-connected voxels,
  the discrete Voronoi regions of the picks, kept inside sheets: growth
  never crosses from one sheet to another, and the junction voxels between
  sheets are seeds with fixed labels shared by every sheet.

The references (``*_reference``) loop in Python; the tests compare them.
"""

from __future__ import annotations

import heapq

import numpy as np

from medialaxis._jit import njit

__all__ = [
    "topology_class",
    "topology_class_reference",
    "greedy_subsample",
    "greedy_subsample_reference",
    "subsample_certainty",
    "subsample_certainty_reference",
    "sheet_labels",
    "sheet_labels_reference",
    "adjacent_gaps",
]


def _n26_tables() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Offsets of the 26-neighbourhood, their 6-adjacency and which are 6-neighbours."""
    offs = [(a, b, c) for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1) if (a, b, c) != (0, 0, 0)]
    offs_arr = np.array(offs, np.int64)
    n = len(offs)
    adj = np.full((n, 6), -1, np.int64)
    for i, o in enumerate(offs):
        k = 0
        for j, p in enumerate(offs):
            if sum(abs(x - y) for x, y in zip(o, p)) == 1:
                adj[i, k] = j
                k += 1
    face = np.array([sum(map(abs, o)) == 1 for o in offs])
    return offs_arr, adj, face


N26_OFFSETS, N26_ADJ, N26_FACE = _n26_tables()
OFFSETS_26 = np.array([(a, b, c) for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1) if (a, b, c) != (0, 0, 0)],
                      np.int64)


@njit(cache=True, nogil=True)
def topology_class(neighbours: np.ndarray, adj: np.ndarray) -> np.ndarray:  # pragma: no cover - compiled
    """Number of 6-connected background components in the 26-neighbourhood
    of each voxel (Malandain's count of background components: 2 inside a
    thin sheet, 1 on its free edge, 3 or more at a junction of sheets).

    ``neighbours`` (n, 26) are the rows of each voxel's neighbours in the
    order of ``N26_OFFSETS`` (-1: background;
    :func:`~medialaxis.volume.voxel_table.neighbour_rows`).
    """
    n = neighbours.shape[0]
    m = neighbours.shape[1]
    out = np.zeros(n, np.int64)
    bg = np.zeros(m, np.bool_)
    seen = np.zeros(m, np.bool_)
    stack = np.zeros(m, np.int64)
    for i in range(n):
        for j in range(m):
            bg[j] = neighbours[i, j] < 0
            seen[j] = False
        count = 0
        for j in range(m):
            if bg[j] and not seen[j]:
                count += 1
                top = 0
                stack[top] = j
                top += 1
                seen[j] = True
                while top > 0:
                    top -= 1
                    k = stack[top]
                    for t in range(6):
                        nb = adj[k, t]
                        if nb >= 0 and bg[nb] and not seen[nb]:
                            seen[nb] = True
                            stack[top] = nb
                            top += 1
        out[i] = count
    return out


@njit(cache=True, nogil=True)
def neighbour_components(neighbours: np.ndarray, member: np.ndarray, half: int) -> np.ndarray:  # pragma: no cover - compiled
    """Connected components of the ``member`` voxels under the first ``half`` columns of
    ``neighbours`` (rows of each voxel's neighbours, -1 none; union-find: no edge list is
    stored). Each voxel gets the smallest row of its component (non-members their own row)."""
    n = neighbours.shape[0]
    parent = np.arange(n)
    for i in range(n):
        if not member[i]:
            continue
        for t in range(half):
            j = np.int64(neighbours[i, t])
            if j < 0 or not member[j]:
                continue
            a = i
            while parent[a] != a:
                parent[a] = parent[parent[a]]
                a = parent[a]
            b = j
            while parent[b] != b:
                parent[b] = parent[parent[b]]
                b = parent[b]
            if a < b:
                parent[b] = a
            elif b < a:
                parent[a] = b
    for i in range(n):
        r = i
        while parent[r] != r:
            r = parent[r]
        parent[i] = r
    return parent


def topology_class_reference(occupied: np.ndarray, voxels: np.ndarray) -> np.ndarray:
    """Pure-Python/SciPy reference of :func:`topology_class`."""
    from scipy import ndimage

    six = ndimage.generate_binary_structure(3, 1)
    out = np.zeros(len(voxels), np.int64)
    for i, (z, y, x) in enumerate(voxels):
        patch = ~occupied[z - 1 : z + 2, y - 1 : y + 2, x - 1 : x + 2]
        patch[1, 1, 1] = False
        out[i] = ndimage.label(patch, structure=six)[1]
    return out


@njit(cache=True, nogil=True)
def _mark_ball(directory: np.ndarray, bricks: np.ndarray, shape: np.ndarray, voxels: np.ndarray, i: int, r: float,
               spacing: np.ndarray, removed: np.ndarray, maybe: np.ndarray, sure: bool) -> None:  # pragma: no cover
    """Mark the voxels within ``r`` of voxel ``i`` (not ``i``, not yet removed): ``removed`` when ``sure``,
    else ``maybe`` (those not marked so already). Rows of absent 8^3 bricks are skipped a brick at a time."""
    r2 = r * r
    z, y, x = voxels[i, 0], voxels[i, 1], voxels[i, 2]
    hz, hy, hx = int(r / spacing[0]), int(r / spacing[1]), int(r / spacing[2])
    c0, c1 = max(x - hx, 0), min(x + hx + 1, shape[2])
    for a in range(max(z - hz, 0), min(z + hz + 1, shape[0])):
        da = (a - z) * spacing[0]
        for b in range(max(y - hy, 0), min(y + hy + 1, shape[1])):
            db = (b - y) * spacing[1]
            base = ((a & 7) * 8 + (b & 7)) * 8
            c = c0
            while c < c1:
                stop = min(((c >> 3) + 1) << 3, c1)
                d = directory[a >> 3, b >> 3, c >> 3]
                if d >= 0:
                    for cc in range(c, stop):
                        j = bricks[d, base + (cc & 7)]
                        if j >= 0 and j != i and not removed[j] and (sure or not maybe[j]):
                            dc = (cc - x) * spacing[2]
                            if da * da + db * db + dc * dc <= r2:
                                if sure:
                                    removed[j] = True
                                else:
                                    maybe[j] = True
                c = stop


@njit(cache=True, nogil=True)
def greedy_subsample(directory: np.ndarray, bricks: np.ndarray, shape: np.ndarray, voxels: np.ndarray, order: np.ndarray,
                     radius: np.ndarray, spacing: np.ndarray) -> np.ndarray:  # pragma: no cover - compiled
    """Pick ``voxels[order[k]]`` unless removed; each pick removes every
    voxel within ``radius[pick]`` (physical units). The voxel table
    ``(directory, bricks, shape)`` maps grid positions to rows. Returns picked rows
    in pick order."""
    n = voxels.shape[0]
    removed = np.zeros(n, np.bool_)
    picks = np.empty(n, np.int64)
    npick = 0
    for k in range(n):
        i = order[k]
        if removed[i]:
            continue
        picks[npick] = i
        npick += 1
        removed[i] = True
        _mark_ball(directory, bricks, shape, voxels, i, radius[i], spacing, removed, removed, True)
    return picks[:npick].copy()


def greedy_subsample_reference(voxels: np.ndarray, order: np.ndarray, radius: np.ndarray,
                               spacing: np.ndarray) -> np.ndarray:
    """Pure-NumPy reference of :func:`greedy_subsample`."""
    phys = voxels * spacing
    removed = np.zeros(len(voxels), bool)
    picks = []
    for i in order:
        if removed[i]:
            continue
        picks.append(i)
        removed |= np.sum((phys - phys[i]) ** 2, axis=1) <= radius[i] ** 2
    return np.array(picks, np.int64)


@njit(cache=True, nogil=True)
def subsample_certainty(directory: np.ndarray, bricks: np.ndarray, shape: np.ndarray, voxels: np.ndarray,
                        order: np.ndarray, radius: np.ndarray, spacing: np.ndarray, band: np.ndarray,
                        near_band: np.ndarray) -> np.ndarray:  # pragma: no cover - compiled
    """Which decisions of :func:`greedy_subsample` (same arguments) a window of the sheet takes for sure.

    ``band`` marks the voxels whose own order or radius may be wrong in the
    window or that voxels outside it may remove (those near a side that cuts
    the sheet); ``near_band`` every voxel that a band voxel may remove (within
    the largest radius of one; a superset will do). A voxel is certain when
    a certain pick removes it, or when neither the band nor an uncertain
    voxel before it could.
    """
    n = voxels.shape[0]
    removed = np.zeros(n, np.bool_)  # by a certain pick
    maybe = near_band.copy()  # perhaps by an uncertain voxel
    certain = np.zeros(n, np.bool_)
    for k in range(n):
        i = order[k]
        if removed[i]:
            certain[i] = True
            continue
        sure = not (band[i] or maybe[i])
        certain[i] = sure
        _mark_ball(directory, bricks, shape, voxels, i, radius[i], spacing, removed, maybe, sure)
        if sure:
            removed[i] = True
    return certain


def subsample_certainty_reference(voxels: np.ndarray, order: np.ndarray, radius: np.ndarray, spacing: np.ndarray,
                                  band: np.ndarray, near_band: np.ndarray) -> np.ndarray:
    """Pure-NumPy reference of :func:`subsample_certainty`."""
    phys = voxels * spacing
    maybe = np.asarray(near_band, bool).copy()
    removed = np.zeros(len(voxels), bool)
    certain = np.zeros(len(voxels), bool)
    for i in order:
        if removed[i]:
            certain[i] = True
            continue
        sure = not (band[i] or maybe[i])
        certain[i] = sure
        near = np.sum((phys - phys[i]) ** 2, axis=1) <= radius[i] ** 2
        near[i] = False
        if sure:
            removed |= near
            removed[i] = True
        else:
            maybe |= near
    return certain


@njit(cache=True, nogil=True)
def sheet_labels(neighbours: np.ndarray, voxels: np.ndarray, seeds: np.ndarray, seed_label: np.ndarray,
                 sheet: np.ndarray, offs: np.ndarray, spacing: np.ndarray) -> np.ndarray:  # pragma: no cover - compiled
    """Discrete geodesic Voronoi regions of ``seeds`` that stay inside sheets.

    Regions grow in order of the Euclidean distance from a voxel to the seed
    of the neighbour it is reached from (vector propagation with a heap), so
    region borders are near the Euclidean bisectors; ties go to the lower
    seed. ``neighbours`` (n, len(offs)) holds the row of each voxel's neighbour at each of ``offs`` (-1 none). Seed ``s``
    gives its region the label ``seed_label[s]`` (several seeds may share
    one), and a region grows from
    voxel ``i`` to voxel ``j`` only when ``sheet[j] >= 0`` and ``sheet[i]``
    is ``sheet[j]`` or negative (junction voxels, ``sheet == -1``, are seeds
    and reach into every sheet). Voxels not reached get -1.
    """
    n = voxels.shape[0]
    label = np.full(n, -1, np.int64)
    owner = np.full(n, -1, np.int64)
    best = np.full(n, np.inf)
    heap = [(0.0, np.int64(0), np.int64(0))]
    heap.pop()
    for s in range(seeds.shape[0]):
        best[seeds[s]] = 0.0
        owner[seeds[s]] = s
    done = np.zeros(n, np.bool_)
    # the seeds' entries (distance 0) would pop first, in seed order: they are taken in that order
    # without the heap (most voxels are seeds when the sheets grow into the junctions' surroundings)
    k = 0
    while k < seeds.shape[0] or len(heap) > 0:
        if k < seeds.shape[0]:
            s, i = np.int64(k), np.int64(seeds[k])
            k += 1
        else:
            d, s, i = heapq.heappop(heap)
        if done[i] or owner[i] != s:
            continue
        done[i] = True
        label[i] = seed_label[s]
        src = seeds[s]
        for t in range(offs.shape[0]):
            j = np.int64(neighbours[i, t])
            if j >= 0 and not done[j] and sheet[j] >= 0 and (sheet[i] < 0 or sheet[i] == sheet[j]):
                a, b, c = voxels[i, 0] + offs[t, 0], voxels[i, 1] + offs[t, 1], voxels[i, 2] + offs[t, 2]
                dz = (a - voxels[src, 0]) * spacing[0]
                dy = (b - voxels[src, 1]) * spacing[1]
                dx = (c - voxels[src, 2]) * spacing[2]
                dj = np.sqrt(dz * dz + dy * dy + dx * dx)
                if dj < best[j] or (dj == best[j] and s < owner[j]):
                    best[j] = dj
                    owner[j] = s
                    heapq.heappush(heap, (dj, np.int64(s), np.int64(j)))
    return label


def sheet_labels_reference(voxels: np.ndarray, seeds: np.ndarray, seed_label: np.ndarray, sheet: np.ndarray,
                           spacing: np.ndarray) -> np.ndarray:
    """Pure-Python reference of :func:`sheet_labels`."""
    where = {tuple(v): i for i, v in enumerate(voxels.tolist())}
    owner = np.full(len(voxels), -1, np.int64)
    best = np.full(len(voxels), np.inf)
    done = np.zeros(len(voxels), bool)
    heap: list[tuple[float, int, int]] = []
    for s, i in enumerate(seeds):
        best[i], owner[i] = 0.0, s
        heapq.heappush(heap, (0.0, s, int(i)))
    while heap:
        _, s, i = heapq.heappop(heap)
        if done[i] or owner[i] != s:
            continue
        done[i] = True
        for off in OFFSETS_26:
            j = where.get(tuple((voxels[i] + off).tolist()))
            if j is None or done[j] or sheet[j] < 0 or not (sheet[i] < 0 or sheet[i] == sheet[j]):
                continue
            dj = float(np.linalg.norm((voxels[j] - voxels[seeds[s]]) * spacing))
            if dj < best[j] or (dj == best[j] and s < owner[j]):
                best[j], owner[j] = dj, s
                heapq.heappush(heap, (dj, s, j))
    label = np.full(len(voxels), -1, np.int64)
    label[done] = np.asarray(seed_label, np.int64)[owner[done]]
    return label


@njit(cache=True, nogil=True)
def adjacent_gaps(index: np.ndarray, feature: np.ndarray, axis: int,
                  shortest: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:  # pragma: no cover - compiled
    """Rows ``(p, q)`` of the foreground voxels 6-adjacent along ``axis`` (``index``: row of each voxel
    of the grid, -1 background) whose nearest boundary points (``feature``) are more than ``shortest``
    apart, and that distance; in the grid's C order (the reference: :func:`~medialaxis.volume.plates.pair_gaps_reference`)."""
    Z, Y, X = index.shape
    dz, dy, dx = int(axis == 0), int(axis == 1), int(axis == 2)
    size = 1024
    p, q, gap = np.empty(size, np.int64), np.empty(size, np.int64), np.empty(size)
    count = 0
    for z in range(Z - dz):
        for y in range(Y - dy):
            for x in range(X - dx):
                a = index[z, y, x]
                if a < 0:
                    continue
                b = index[z + dz, y + dy, x + dx]
                if b < 0:
                    continue
                d0 = feature[a, 0] - feature[b, 0]
                d1 = feature[a, 1] - feature[b, 1]
                d2 = feature[a, 2] - feature[b, 2]
                g = np.sqrt(d0 * d0 + d1 * d1 + d2 * d2)  # numpy's norm: the squares summed in order
                if not g > shortest:
                    continue
                if count == size:  # twice as long
                    p = np.concatenate((p, np.empty(size, np.int64)))
                    q = np.concatenate((q, np.empty(size, np.int64)))
                    gap = np.concatenate((gap, np.empty(size)))
                    size *= 2
                p[count], q[count], gap[count] = a, b, g
                count += 1
    return p[:count].copy(), q[:count].copy(), gap[:count].copy()

