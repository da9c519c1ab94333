"""Compiled kernels of the compact medial complex (:mod:`medialaxis.mesh.medial.compact`).

Per round of collapses: the neighbour lists and triangle apexes of the
complex (:func:`structure`), the link condition (:func:`link_ok`), the cost
of each merge (:func:`costs`; the feature moves of those taken: :func:`moves`) and the greedy choice of collapses kept apart
(:func:`select`).
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit, prange

__all__ = ["structure", "link_ok", "select", "feature_lines", "costs", "moves", "lattice", "lattice_steps"]


@njit(cache=True, nogil=True)
def structure(n, edges, faces):  # pragma: no cover - compiled
    """Neighbour lists and triangle apexes of a complex, in one pass over its sorted edges.

    ``edges`` (m, 2) are sorted by ``(u, v)`` with ``u < v``. Returns the
    CSR adjacency ``ptr, idx`` (each list ascending: the lower neighbours
    come in edge order, then the higher ones), the edge of each entry
    ``eid`` and, per edge, the apexes of the triangles on it
    (``apex[apex_ptr[e]:apex_ptr[e + 1]]``). The entries are int32 (points and edges number
    fewer than ``2**31``: :func:`~medialaxis.mesh.medial.compact.compact_complex` checks).
    """
    m = edges.shape[0]
    ptr = np.zeros(n + 1, np.int64)
    for e in range(m):
        ptr[edges[e, 0] + 1] += 1
        ptr[edges[e, 1] + 1] += 1
    for v in range(n):
        ptr[v + 1] += ptr[v]
    fill = ptr[:-1].copy()
    idx = np.empty(2 * m, np.int32)  # int32: among a round's largest arrays (a 98k-vertex plate's peak 2.28 -> 2.18 GB)
    eid = np.empty(2 * m, np.int32)
    for e in range(m):  # lower neighbours w of u, for edges (w, u): w ascending
        u = edges[e, 1]
        idx[fill[u]] = edges[e, 0]
        eid[fill[u]] = e
        fill[u] += 1
    for e in range(m):  # then the higher ones
        u = edges[e, 0]
        idx[fill[u]] = edges[e, 1]
        eid[fill[u]] = e
        fill[u] += 1
    owner = np.empty(3 * faces.shape[0], np.int32)
    apex_ptr = np.zeros(m + 1, np.int64)
    for f in range(faces.shape[0]):
        for k in range(3):
            a, b = faces[f, k], faces[f, (k + 1) % 3]
            u, v = min(a, b), max(a, b)
            lo = ptr[u]
            hi = ptr[u + 1]
            while lo < hi:  # v's position in u's (ascending) list
                mid = (lo + hi) // 2
                if idx[mid] < v:
                    lo = mid + 1
                else:
                    hi = mid
            owner[3 * f + k] = eid[lo]  # its edge
    for r in range(owner.shape[0]):
        apex_ptr[owner[r] + 1] += 1
    for e in range(m):
        apex_ptr[e + 1] += apex_ptr[e]
    fill = apex_ptr[:-1].copy()
    apex = np.empty(owner.shape[0], np.int32)
    for f in range(faces.shape[0]):
        for k in range(3):
            e = owner[3 * f + k]
            apex[fill[e]] = faces[f, (k + 2) % 3]
            fill[e] += 1
    return ptr, idx, eid, apex_ptr, apex


@njit(cache=True, nogil=True)
def _has(ptr, idx, a, b):  # pragma: no cover - compiled
    lo, hi = ptr[a], ptr[a + 1]
    while lo < hi:
        mid = (lo + hi) // 2
        if idx[mid] < b:
            lo = mid + 1
        else:
            hi = mid
    return lo < ptr[a + 1] and idx[lo] == b


@njit(cache=True, nogil=True)
def link_ok(edges, ptr, idx, apex_ptr, apex):  # pragma: no cover - compiled
    """Link condition of each edge: common neighbours == apexes of its triangles, no two apexes joined."""
    out = np.zeros(len(edges), np.bool_)
    for e in range(len(edges)):
        u, v = edges[e, 0], edges[e, 1]
        i, j = ptr[u], ptr[v]
        common = 0
        while i < ptr[u + 1] and j < ptr[v + 1]:
            if idx[i] == idx[j]:
                common += 1
                i += 1
                j += 1
            elif idx[i] < idx[j]:
                i += 1
            else:
                j += 1
        t0, t1 = apex_ptr[e], apex_ptr[e + 1]
        ok = common == t1 - t0
        if ok and t1 - t0 >= 2:
            for a in range(t0, t1):
                for b in range(a + 1, t1):
                    if _has(ptr, idx, apex[a], apex[b]):
                        ok = False
        out[e] = ok
    return out


@njit(cache=True, nogil=True)
def select(order, src, dst, ptr, idx, n, apart):  # pragma: no cover - compiled
    """Greedy choice of collapses ``src -> dst`` (in ``order``), kept apart by ``apart``.

    ``0``: no two share a vertex (a matching); ``1``: no two meet in the
    closed neighbourhood of the vertex removed; ``2``: in the closed
    neighbourhoods of both endpoints (the link conditions tested before the
    round stay true).
    """
    marked = np.zeros(n, np.bool_)
    chosen = np.zeros(len(src), np.bool_)
    for k in order:
        a, b = src[k], dst[k]
        if marked[a] or marked[b]:
            continue
        free = True
        for v in (a, b):
            if apart == 0 or (apart == 1 and v == b):
                continue
            for p in range(ptr[v], ptr[v + 1]):
                if marked[idx[p]]:
                    free = False
                    break
        if not free:
            continue
        chosen[k] = True
        marked[a] = True
        marked[b] = True
        for v in (a, b):
            if apart == 0 or (apart == 1 and v == b):
                continue
            for p in range(ptr[v], ptr[v + 1]):
                marked[idx[p]] = True
    return chosen


@njit(cache=True, nogil=True)
def _segment_distance2(s, p, a, b, dims=4):  # pragma: no cover - compiled
    """Squared distance from sphere ``p`` to the segment between spheres ``a`` and ``b``.

    In (x, y, z, r), or between the centres only with ``dims=3``.
    """
    ab = 0.0
    ap = 0.0
    for k in range(dims):
        ab += (s[b, k] - s[a, k]) ** 2
        ap += (s[p, k] - s[a, k]) * (s[b, k] - s[a, k])
    t = min(max(ap / max(ab, 1e-300), 0.0), 1.0)
    d = 0.0
    for k in range(dims):
        d += (s[p, k] - s[a, k] - t * (s[b, k] - s[a, k])) ** 2
    return d


@njit(cache=True, nogil=True)
def _triangle_distance2(s, p, a, b, c):  # pragma: no cover - compiled
    """Squared distance from sphere ``p`` to the triangle of spheres ``a, b, c``, in (x, y, z, r)."""
    d00 = d01 = d11 = d20 = d21 = 0.0
    for k in range(4):
        e0, e1, v = s[b, k] - s[a, k], s[c, k] - s[a, k], s[p, k] - s[a, k]
        d00 += e0 * e0
        d01 += e0 * e1
        d11 += e1 * e1
        d20 += v * e0
        d21 += v * e1
    den = d00 * d11 - d01 * d01
    if den > 1e-12 * d00 * d11:
        u = (d11 * d20 - d01 * d21) / den
        w = (d00 * d21 - d01 * d20) / den
        if u >= 0.0 and w >= 0.0 and u + w <= 1.0:
            d = 0.0
            for k in range(4):
                d += (s[p, k] - s[a, k] - u * (s[b, k] - s[a, k]) - w * (s[c, k] - s[a, k])) ** 2
            return d
    return min(_segment_distance2(s, p, a, b), min(_segment_distance2(s, p, b, c), _segment_distance2(s, p, c, a)))


@njit(cache=True, nogil=True)
def _slab_distance(j, i, spheres, ptr, idx, eid, apex_ptr, apex, enough):  # pragma: no cover - compiled
    """Distance in (centre, radius) from sphere ``j`` to the edges and triangles its merge into ``i`` makes.

    The spheres interpolated over those stand for ``j`` after the merge: a
    merge whose new edges would run from a large sphere straight to a small
    one (a body's centre to a finger's root) is costed by how far ``j``
    lies from them, not only by the tangent planes ``i`` keeps. The search
    stops at a distance of at most ``enough`` (then some distance between
    the true one and ``enough`` is returned, and ``True``).
    """
    best = np.inf
    for q in range(ptr[j], ptr[j + 1]):
        k = idx[q]
        if k == i:
            continue
        best = min(best, _segment_distance2(spheres, j, i, k))
        if np.sqrt(best) <= enough:  # the triangles on edge jk hold segment ik: they can only be nearer
            return np.sqrt(best), True
        e = eid[q]
        for r in range(apex_ptr[e], apex_ptr[e + 1]):
            if apex[r] != i:
                best = min(best, _triangle_distance2(spheres, j, i, k, apex[r]))
        if np.sqrt(best) <= enough:
            return np.sqrt(best), True
    if best == np.inf:  # i is its only neighbour
        best = 0.0
        for k in range(4):
            best += (spheres[j, k] - spheres[i, k]) ** 2
    return np.sqrt(best), False


@njit(cache=True, nogil=True, inline="always")
def _cheap_terms(j, i, spheres, qa, qb, qc, count, moved, lines):  # pragma: no cover - compiled
    """The terms of merging ``j`` into ``i`` other than the slab distance: ``(sqem, rest)`` (the module docstring's (a), (b))."""
    quad = qc[j]
    for a in range(4):
        quad -= 2.0 * qb[j, a] * spheres[i, a]
        for b in range(4):
            quad += spheres[i, a] * qa[j, a, b] * spheres[i, b]
    sqem = np.sqrt(max(quad, 0.0) / count[j])
    degree, first, second = lines
    shift = 0.0
    if degree[j] != 0:
        far = -1
        if degree[j] == 2 and first[j] == i:
            far = second[j]
        elif degree[j] == 2 and second[j] == i:
            far = first[j]
        if far < 0:  # off its line: the distance moved
            for a in range(3):
                shift += (spheres[j, a] - spheres[i, a]) ** 2
        else:  # along its line: the distance to the segment that replaces it
            shift = _segment_distance2(spheres, j, i, far, 3)
    return sqem, max(moved[j], np.sqrt(shift))  # shift is 0 for a vertex off every feature


@njit(cache=True, nogil=True)
def _merge_cost(j, i, spheres, qa, qb, qc, count, moved, lines, star, exact):  # pragma: no cover - compiled
    """Cost of merging ``j`` into ``i`` and the feature move it makes (see the module docstring).

    The cost is ``max(sqem, move)``, the move ``max(rest, slab)`` with
    ``rest`` the feature terms. The slab search stops once below ``rest``
    (the move is then ``rest``) or, without ``exact``, below the other
    terms, which fixes the cost but may leave the move unknown: then the
    move returned is NaN (:func:`moves` gives it). 1.44 -> 0.67 s CPU for
    the first round of the uv ellipsoid's 1.2M edges, one thread.
    """
    sqem, rest = _cheap_terms(j, i, spheres, qa, qb, qc, count, moved, lines)
    return _with_slab(j, i, sqem, rest, spheres, star, exact)


@njit(cache=True, nogil=True)
def _with_slab(j, i, sqem, rest, spheres, star, exact):  # pragma: no cover - compiled
    """:func:`_merge_cost` given its cheap terms ``sqem`` and ``rest``."""
    ptr, idx, eid, apex_ptr, apex = star
    slab, stopped = _slab_distance(j, i, spheres, ptr, idx, eid, apex_ptr, apex, rest if exact else max(sqem, rest))
    move = max(rest, slab)
    if stopped and slab > rest:
        return max(sqem, move), np.nan  # the move lies between rest and slab
    return max(sqem, move), move


@njit(cache=True, nogil=True)
def feature_lines(edges, feature, n):  # pragma: no cover - compiled
    """Per vertex: how many feature edges it has, and the other ends of the first two."""
    degree = np.zeros(n, np.int64)
    first = np.full(n, -1, np.int64)
    second = np.full(n, -1, np.int64)
    for e in range(edges.shape[0]):
        if feature[e]:
            for s in range(2):
                u, w = edges[e, s], edges[e, 1 - s]
                if degree[u] == 0:
                    first[u] = w
                elif degree[u] == 1:
                    second[u] = w
                degree[u] += 1
    return degree, first, second


@njit(cache=True, nogil=True, parallel=True)
def costs(edges, cand, spheres, qa, qb, qc, count, moved, lines, star, name):  # pragma: no cover - compiled
    """Cheaper direction of merging each candidate edge: ``src -> dst``, its cost and its feature move.

    Features are the edges not shared by exactly two triangles; ``lines`` are
    :func:`feature_lines` of them (a vertex with two lies on a line; ties go
    to merging the end of lower ``name`` into the other). The direction whose terms
    other than the slab distance are lower is costed first, and the other
    only if those terms do not already make it dearer. The move is NaN where
    the slab search stopped before fixing it (:func:`moves` gives those).
    """
    m = cand.shape[0]
    src = np.empty(m, np.int64)
    dst = np.empty(m, np.int64)
    cost = np.empty(m)
    move = np.empty(m)
    for k in prange(m):
        u, v = edges[cand[k], 0], edges[cand[k], 1]
        if name[u] > name[v]:
            u, v = v, u
        s_uv, r_uv = _cheap_terms(u, v, spheres, qa, qb, qc, count, moved, lines)
        s_vu, r_vu = _cheap_terms(v, u, spheres, qa, qb, qc, count, moved, lines)
        c_uv = c_vu = np.inf
        m_uv = m_vu = np.nan
        if max(s_uv, r_uv) <= max(s_vu, r_vu):
            c_uv, m_uv = _with_slab(u, v, s_uv, r_uv, spheres, star, False)
            if max(s_vu, r_vu) < c_uv:  # else c_vu >= c_uv
                c_vu, m_vu = _with_slab(v, u, s_vu, r_vu, spheres, star, False)
        else:
            c_vu, m_vu = _with_slab(v, u, s_vu, r_vu, spheres, star, False)
            if max(s_uv, r_uv) <= c_vu:  # else c_uv > c_vu
                c_uv, m_uv = _with_slab(u, v, s_uv, r_uv, spheres, star, False)
        if c_uv <= c_vu:
            src[k], dst[k], cost[k], move[k] = u, v, c_uv, m_uv
        else:
            src[k], dst[k], cost[k], move[k] = v, u, c_vu, m_vu
    return src, dst, cost, move


@njit(cache=True, nogil=True, parallel=True)
def moves(src, dst, spheres, qa, qb, qc, count, moved, lines, star):  # pragma: no cover - compiled
    """Feature move (see the module docstring) of each merge ``src -> dst``, on the complex of :func:`costs`."""
    out = np.empty(src.shape[0])
    for k in prange(src.shape[0]):
        out[k] = _merge_cost(src[k], dst[k], spheres, qa, qb, qc, count, moved, lines, star, True)[1]
    return out


@njit(cache=True, nogil=True)
def lattice_steps(spheres, a, b, c, spacing):  # pragma: no cover - compiled
    """Steps of :func:`lattice` along the longest side of triangle ``a, b, c`` (edge: ``c == b``); it has samples from 2 on."""
    longest = 0.0
    for u, v in ((a, b), (b, c), (c, a)):
        d = 0.0
        for k in range(4):
            d += (spheres[u, k] - spheres[v, k]) ** 2
        longest = max(longest, d)
    return int(np.ceil(np.sqrt(longest) / spacing))


@njit(cache=True, nogil=True)
def _lattice(spheres, prims, balls, spacing, tolerance, out, owner):  # pragma: no cover - compiled
    """Fill ``out`` and ``owner`` (if not empty) with :func:`lattice`'s samples; returns their count."""
    count = 0
    s = np.empty(4)
    for p in range(prims.shape[0]):
        a, b, c = prims[p, 0], prims[p, 1], prims[p, 2]
        steps = lattice_steps(spheres, a, b, c, spacing)
        for u in range(steps + 1):
            for w in range(1 if b == c else steps - u + 1):  # an edge (b == c): w = 0 only
                if (u == 0 and w == 0) or u == steps or w == steps:  # the corners
                    continue
                t, v = u / steps, w / steps
                for k in range(4):
                    s[k] = (1.0 - t - v) * spheres[a, k] + t * spheres[b, k] + v * spheres[c, k]
                bound = s[3]  # the balls hold no surface point: d(x) >= r_q - |x - x_q|
                for m in range(balls.shape[1]):
                    q = balls[p, m]
                    d = 0.0
                    for k in range(3):
                        d += (s[k] - spheres[q, k]) ** 2
                    bound = min(bound, s[3] - spheres[q, 3] + np.sqrt(d))
                if bound <= tolerance:
                    continue
                if out.shape[0] > 0:
                    out[count] = s
                    owner[count] = p
                count += 1
    return count


@njit(cache=True, nogil=True)
def lattice(spheres, prims, balls, spacing, tolerance):  # pragma: no cover - compiled
    """Spheres interpolated over triangles ``prims`` (edges: ``(a, b, b)``) about ``spacing`` apart.

    Corners are left out, and so are the spheres that cannot reach more than
    ``tolerance`` out of a surface that the balls ``balls[p]`` (p, m) of each
    primitive do not cross (a ball ``(x, r)`` reaches ``r - d(x)`` out, and
    ``d(x) >= r_q - |x - x_q|``). Returns the samples (q, 4) and the
    primitive each comes from.
    """
    count = _lattice(spheres, prims, balls, spacing, tolerance, np.empty((0, 4)), np.empty(0, np.int64))
    out = np.empty((count, 4))
    owner = np.empty(count, np.int64)
    _lattice(spheres, prims, balls, spacing, tolerance, out, owner)
    return out, owner
