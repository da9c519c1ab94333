"""Triangle-triangle intersection kernel (numba) with its pure-Python reference.

Two triangles that share no vertex intersect when an edge of one crosses
the other (the non-coplanar case); each crossing is decided by signs of
orientation determinants, counted only beyond a tolerance so that
triangles that merely touch (along an edge or at a vertex, as the two sides
of a boolean union's touching edge do) do not count.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit, prange

__all__ = ["first_crossing", "first_crossing_reference", "crossing_mask", "segment_crosses_triangle", "near_pairs", "grid_cells",
           "planes_meet", "may_meet"]


@njit(cache=True, nogil=True)
def _orient(a: np.ndarray, b: np.ndarray, c: np.ndarray, d: np.ndarray) -> float:
    """Six times the signed volume of the tetrahedron (a, b, c, d)."""
    bx, by, bz = b[0] - a[0], b[1] - a[1], b[2] - a[2]
    cx, cy, cz = c[0] - a[0], c[1] - a[1], c[2] - a[2]
    dx, dy, dz = d[0] - a[0], d[1] - a[1], d[2] - a[2]
    return bx * (cy * dz - cz * dy) - by * (cx * dz - cz * dx) + bz * (cx * dy - cy * dx)


@njit(cache=True, nogil=True)
def segment_crosses_triangle(p: np.ndarray, q: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray, tol: float) -> bool:
    """Whether segment pq passes through the interior of triangle abc (strictly, beyond ``tol``)."""
    sp = _orient(a, b, c, p)
    sq = _orient(a, b, c, q)
    if not ((sp > tol and sq < -tol) or (sp < -tol and sq > tol)):
        return False
    s1 = _orient(p, q, a, b)
    s2 = _orient(p, q, b, c)
    s3 = _orient(p, q, c, a)
    return (s1 > tol and s2 > tol and s3 > tol) or (s1 < -tol and s2 < -tol and s3 < -tol)


@njit(cache=True, nogil=True)
def _crosses(t: np.ndarray, u: np.ndarray, tol: float) -> bool:
    for k in range(3):
        if segment_crosses_triangle(t[k], t[(k + 1) % 3], u[0], u[1], u[2], tol):
            return True
        if segment_crosses_triangle(u[k], u[(k + 1) % 3], t[0], t[1], t[2], tol):
            return True
    return False


@njit(cache=True, nogil=True)
def _boxes_apart(t: np.ndarray, u: np.ndarray) -> bool:
    for a in range(3):
        if max(t[0, a], t[1, a], t[2, a]) < min(u[0, a], u[1, a], u[2, a]):
            return True
        if max(u[0, a], u[1, a], u[2, a]) < min(t[0, a], t[1, a], t[2, a]):
            return True
    return False


@njit(cache=True, nogil=True)
def _shared(faces: np.ndarray, i: int, j: int) -> int:
    """How many vertices faces ``i`` and ``j`` share."""
    count = 0
    for a in range(3):
        for b in range(3):
            count += faces[i, a] == faces[j, b]
    return count


@njit(cache=True, nogil=True)
def _fold_crosses(t: np.ndarray, u: np.ndarray, ct: int, cu: int, tol: float) -> bool:
    """Whether triangles sharing one vertex (corner ``ct`` of ``t``, ``cu`` of ``u``) cross: an opposite edge through the other."""
    if segment_crosses_triangle(t[(ct + 1) % 3], t[(ct + 2) % 3], u[0], u[1], u[2], tol):
        return True
    return segment_crosses_triangle(u[(cu + 1) % 3], u[(cu + 2) % 3], t[0], t[1], t[2], tol)


@njit(cache=True, nogil=True)
def _pair_crosses(triangles: np.ndarray, faces: np.ndarray, i: int, j: int, tol: float) -> bool:
    """Whether faces ``i`` and ``j`` cross: sharing no vertex, or one (a fold through a neighbour), not an edge."""
    shared = _shared(faces, i, j)
    if shared == 0:
        return _crosses(triangles[i], triangles[j], tol)
    if shared > 1:
        return False
    for a in range(3):
        for b in range(3):
            if faces[i, a] == faces[j, b]:
                return _fold_crosses(triangles[i], triangles[j], a, b, tol)
    return False


@njit(cache=True, nogil=True)
def _cell_key(x: float, y: float, z: float) -> int:
    """One integer per grid cell (cell indices within +-2^20)."""
    return (np.int64(x) * 2097152 + np.int64(y)) * 2097152 + np.int64(z)


@njit(cache=True, nogil=True)
def grid_cells(points, is_query, cell):  # type: ignore[no-untyped-def]
    """Entries binned on a grid of side ``cell``, sorted by cell, the candidates of a cell before its queries.

    Returns the order, each occupied cell's first entry and first query, the
    cell of each entry (in the input's order) and the occupied cells around each cell.
    """
    n = points.shape[0]
    key = np.empty(n, np.int64)
    for q in range(n):
        key[q] = _cell_key(np.floor(points[q, 0] / cell), np.floor(points[q, 1] / cell), np.floor(points[q, 2] / cell))
    order = np.argsort(2 * key + is_query)  # cell keys lie within +-2^62
    sorted_key = key[order]
    heads = np.flatnonzero(np.diff(sorted_key)) + 1
    n_cells = heads.shape[0] + 1
    cell_start = np.empty(n_cells + 1, np.int64)
    cell_start[0], cell_start[n_cells] = 0, n
    cell_start[1:n_cells] = heads
    cell_key = sorted_key[cell_start[:n_cells]]
    cell_of = np.empty(n, np.int64)
    query_start = np.empty(n_cells, np.int64)
    for c in range(n_cells):
        cell_of[order[cell_start[c] : cell_start[c + 1]]] = c
        query_start[c] = cell_start[c + 1]
        for s in range(cell_start[c], cell_start[c + 1]):
            if is_query[order[s]]:
                query_start[c] = s
                break
    around = np.full((n_cells, 27), -1, np.int64)
    for c in range(n_cells):
        p = points[order[cell_start[c]]]
        gx, gy, gz = np.floor(p[0] / cell), np.floor(p[1] / cell), np.floor(p[2] / cell)
        m = 0
        for dx in range(-1, 2):
            for dy in range(-1, 2):
                for dz in range(-1, 2):
                    k = _cell_key(gx + dx, gy + dy, gz + dz)
                    r = np.searchsorted(cell_key, k)
                    if r < n_cells and cell_key[r] == k:
                        around[c, m] = r
                        m += 1
    return order, cell_start, query_start, cell_of, around


@njit(cache=True, nogil=True, parallel=True)
def near_pairs(triangles, faces, centre, radius, members, cell, one_apart=True):  # type: ignore[no-untyped-def]
    """Pairs ``(i, j)``, ``i < j``, of ``members`` that may cross: bounding spheres and boxes meet, no shared vertex.

    ``one_apart=False``: pairs sharing one vertex too (a face folded through
    a neighbour of its corner), not those sharing an edge.

    The members are binned on a grid of side ``cell`` (at least the largest
    sum of two of their radii), so each is compared with those of its own
    and the surrounding cells only, each pair of cells once; nothing is
    materialised for the many pairs of adjacent faces, which share a vertex.
    The pairs come in grid order.
    """
    n = members.shape[0]
    order, cell_start, _, _, around = grid_cells(centre[members], np.zeros(n, np.int64), cell)
    n_cells = cell_start.shape[0] - 1
    # members in cell order, their spheres copied alongside: the inner loop reads memory in sequence
    tri_id = members[order]
    sc, sr = centre[tri_id], radius[tri_id]
    count = np.zeros(n, np.int64)
    pairs = np.empty((0, 2), np.int64)
    for sweep in range(2):
        if sweep == 1:
            start = np.zeros(n + 1, np.int64)
            start[1:] = np.cumsum(count)
            pairs = np.empty((start[n], 2), np.int64)
        for c in prange(n_cells):
            for q in range(cell_start[c], cell_start[c + 1]):
                i = tri_id[q]
                found = 0
                for m in range(27):
                    other = around[c, m]
                    if other < 0:
                        break
                    if other < c:  # that pair of cells is done from the other one
                        continue
                    for r in range(q + 1 if other == c else cell_start[other], cell_start[other + 1]):
                        j = tri_id[r]
                        d2 = (sc[q, 0] - sc[r, 0]) ** 2 + (sc[q, 1] - sc[r, 1]) ** 2 + (sc[q, 2] - sc[r, 2]) ** 2
                        reach = sr[q] + sr[r]
                        if d2 > reach * reach:
                            continue
                        if _boxes_apart(triangles[i], triangles[j]) or _shared(faces, i, j) >= (1 if one_apart else 2):
                            continue
                        if sweep == 1:
                            pairs[start[q] + found, 0] = min(i, j)
                            pairs[start[q] + found, 1] = max(i, j)
                        found += 1
                if sweep == 0:
                    count[q] = found
    return pairs


@njit(cache=True, nogil=True, parallel=True)
def crossing_mask(triangles: np.ndarray, faces: np.ndarray, pairs: np.ndarray, tol: float) -> np.ndarray:
    """Whether each pair ``(i, j)`` of ``pairs`` crosses: sharing no vertex, or one and folded through (all cores)."""
    hit = np.zeros(len(pairs), np.bool_)
    for k in prange(len(pairs)):
        i, j = pairs[k, 0], pairs[k, 1]
        if _boxes_apart(triangles[i], triangles[j]):
            continue
        if _pair_crosses(triangles, faces, i, j, tol):
            hit[k] = True
    return hit


def first_crossing(triangles: np.ndarray, faces: np.ndarray, pairs: np.ndarray, tol: float) -> int:
    """Index of the first pair ``(i, j)`` of ``pairs`` whose triangles share no vertex and cross, or -1."""
    hit = np.flatnonzero(crossing_mask(triangles, faces, pairs, tol))
    return int(hit[0]) if len(hit) else -1


@njit(cache=True, nogil=True, parallel=True)
def planes_meet(triangles: np.ndarray, faces: np.ndarray, pairs: np.ndarray, tol: float) -> np.ndarray:
    """Whether each pair's triangles may meet: neither lies wholly beyond ``tol`` on one side of the other's plane.

    Pairs that share a vertex meet there: they count only where one is
    folded through the other (:func:`crossing_mask` without tolerance).
    """
    out = np.zeros(len(pairs), np.bool_)
    for k in prange(len(pairs)):
        if _shared(faces, pairs[k, 0], pairs[k, 1]):
            out[k] = _pair_crosses(triangles, faces, pairs[k, 0], pairs[k, 1], 0.0)
            continue
        meet = True
        for side in range(2):
            t = triangles[pairs[k, side]]
            u = triangles[pairs[k, 1 - side]]
            nx = (t[1, 1] - t[0, 1]) * (t[2, 2] - t[0, 2]) - (t[1, 2] - t[0, 2]) * (t[2, 1] - t[0, 1])
            ny = (t[1, 2] - t[0, 2]) * (t[2, 0] - t[0, 0]) - (t[1, 0] - t[0, 0]) * (t[2, 2] - t[0, 2])
            nz = (t[1, 0] - t[0, 0]) * (t[2, 1] - t[0, 1]) - (t[1, 1] - t[0, 1]) * (t[2, 0] - t[0, 0])
            norm = np.sqrt(nx * nx + ny * ny + nz * nz)
            if norm == 0.0:
                continue
            above = below = 0
            for m in range(3):
                d = ((u[m, 0] - t[0, 0]) * nx + (u[m, 1] - t[0, 1]) * ny + (u[m, 2] - t[0, 2]) * nz) / norm
                above += d > tol
                below += d < -tol
            if above == 3 or below == 3:
                meet = False
        out[k] = meet and not _boxes_apart(triangles[pairs[k, 0]], triangles[pairs[k, 1]])
    return out


def first_crossing_reference(triangles: np.ndarray, faces: np.ndarray, pairs: np.ndarray, tol: float) -> int:
    """Pure-Python reference of :func:`first_crossing` (for the tests)."""

    def orient(a, b, c, d):
        return float(np.dot(b - a, np.cross(c - a, d - a)))

    def seg(p, q, a, b, c):
        sp, sq = orient(a, b, c, p), orient(a, b, c, q)
        if not ((sp > tol and sq < -tol) or (sp < -tol and sq > tol)):
            return False
        s = [orient(p, q, a, b), orient(p, q, b, c), orient(p, q, c, a)]
        return all(v > tol for v in s) or all(v < -tol for v in s)

    for k, (i, j) in enumerate(pairs):
        shared = [(a, b) for a in range(3) for b in range(3) if faces[i][a] == faces[j][b]]
        t, u = triangles[i], triangles[j]
        if not shared:
            if any(seg(t[e], t[(e + 1) % 3], *u) or seg(u[e], u[(e + 1) % 3], *t) for e in range(3)):
                return k
        elif len(shared) == 1:  # a fold: the edge opposite the shared corner through the other face
            a, b = shared[0]
            if seg(t[(a + 1) % 3], t[(a + 2) % 3], *u) or seg(u[(b + 1) % 3], u[(b + 2) % 3], *t):
                return k
    return -1


@njit(cache=True, nogil=True)
def _edge_may_meet(p: np.ndarray, q: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray, tol: float) -> bool:
    """Whether segment pq may meet triangle abc: :func:`segment_crosses_triangle` with ``tol`` to spare."""
    sp = _orient(a, b, c, p)
    sq = _orient(a, b, c, q)
    if (sp > tol and sq > tol) or (sp < -tol and sq < -tol):
        return False
    s1 = _orient(p, q, a, b)
    s2 = _orient(p, q, b, c)
    s3 = _orient(p, q, c, a)
    return (s1 >= -tol and s2 >= -tol and s3 >= -tol) or (s1 <= tol and s2 <= tol and s3 <= tol)


@njit(cache=True, nogil=True, parallel=True)
def may_meet(triangles: np.ndarray, faces: np.ndarray, pairs: np.ndarray, rel: float) -> np.ndarray:
    """Whether each pair's triangles may meet (a superset of those that do, in exact arithmetic).

    Triangles that share no vertex meet where an edge of one meets the
    other; each orientation is trusted beyond ``rel`` times the cube of the
    pair's extent (floating-point error is ~1e-16 of it). Pairs that share a
    vertex as :func:`planes_meet` takes them (folded through one another).
    """
    out = np.zeros(len(pairs), np.bool_)
    for k in prange(len(pairs)):
        i, j = pairs[k, 0], pairs[k, 1]
        t, u = triangles[i], triangles[j]
        if _boxes_apart(t, u):
            continue
        if _shared(faces, i, j):
            out[k] = _pair_crosses(triangles, faces, i, j, 0.0)
            continue
        extent = 0.0
        for a in range(3):
            lo = min(t[0, a], t[1, a], t[2, a], u[0, a], u[1, a], u[2, a])
            hi = max(t[0, a], t[1, a], t[2, a], u[0, a], u[1, a], u[2, a])
            extent = max(extent, hi - lo)
        tol = rel * extent * extent * extent
        for e in range(3):
            if _edge_may_meet(t[e], t[(e + 1) % 3], u[0], u[1], u[2], tol) or \
                    _edge_may_meet(u[e], u[(e + 1) % 3], t[0], t[1], t[2], tol):
                out[k] = True
                break
    return out
