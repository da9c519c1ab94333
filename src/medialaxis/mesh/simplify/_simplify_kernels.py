"""Compiled loops of the simplification: the edge collapses and the snaps to medial candidates.

:func:`collapse` runs the edge collapses of least spherical quadric error
(Li et al., "Q-MAT: Computing medial axis transform by quadratic error
minimization", ACM TOG 35(1), 2015; Garland and Heckbert, "Surface
simplification using quadric error metrics", SIGGRAPH 1997) with a binary
heap of ``(cost, i, j, version i, version j)`` popped in the order of
Python's tuples, so the collapses are those of the loop it replaced. Each
collapsed sphere is snapped to the medial candidate of least quadric error
among its nearest in (centre, radius) (:func:`snap_one`), found by a k-d tree
(Bentley, "Multidimensional binary search trees used for associative
searching", CACM 18(9), 1975; :func:`kd_build`, :func:`kd_knn`).

A candidate counts only when it is inscribed (its centre's exact depth within
a share of its radius), asked of the signed distance in Python. The snaps
assume a candidate not yet asked is inscribed and mark it pending (state
``2``): the caller asks the pending ones in one batch and runs the loop again
when one is not (the snap's choice then stands only if the candidate it took
is inscribed: the least cost among more candidates than the inscribed ones,
reached at an inscribed one, is the least among these).
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit
from medialaxis.mesh.sample._closest_kernels import box_distance2

__all__ = ["kd_build", "kd_knn", "snap_one", "snap_many", "collapse", "optimum", "pair_costs", "span_cosines", "PENDING"]

#: ``MedialCandidates.state`` of a candidate a snap took before it was asked.
PENDING = 2


@njit(cache=True, nogil=True)
def optimum(qa, qb, qc, s1, s2, reg):  # type: ignore[no-untyped-def]
    """Sphere minimising ``s.qa.s - 2 qb.s + qc + reg |s - mid|^2`` and its quadric error (without ``reg``)."""
    mid = 0.5 * (s1 + s2)
    a = qa + reg * np.eye(4)
    b = qb + reg * mid
    s = np.linalg.solve(a, b)
    # The merged sphere stays near the two it replaces: on thin parts the quadric barely
    # constrains the radius along the axis, and an unchecked optimum balloons out of the shape.
    r_max = max(s1[3], s2[3])
    half = 0.5 * np.sqrt(np.sum((s1[:3] - s2[:3]) ** 2))
    off = np.sqrt(np.sum((s[:3] - mid[:3]) ** 2))
    if s[3] <= 0 or not np.all(np.isfinite(s)) or s[3] > 1.1 * r_max or off > half + 0.1 * r_max:
        # the cheapest of the two spheres and their midpoint (Garland and Heckbert's fallback): the
        # midpoint of a large and a small sphere alone pokes out of the thin part
        s = mid
        error = _form(s, qa, qb)
        for t in (s1, s2):
            e = _form(t, qa, qb)
            if e < error:
                s, error = t.copy(), e
    else:
        error = _form(s, qa, qb)
    return s, max(error + qc, 0.0)


@njit(cache=True, nogil=True)
def _form(s, qa, qb):  # type: ignore[no-untyped-def]
    """The quadric error ``s.qa.s - 2 qb.s`` (without the constant)."""
    return s @ qa @ s - 2.0 * (qb @ s)


@njit(cache=True, nogil=True)
def pair_costs(qa, qb, qc, spheres, reg, pairs):  # type: ignore[no-untyped-def]
    """:func:`optimum`'s error of merging each pair ``(i, j)`` of spheres."""
    out = np.empty(pairs.shape[0])
    for k in range(pairs.shape[0]):
        i, j = pairs[k, 0], pairs[k, 1]
        _, out[k] = optimum(qa[i] + qa[j], qb[i] + qb[j], qc[i] + qc[j], spheres[i], spheres[j], reg)
    return out


@njit(cache=True, nogil=True)
def _select(perm, pts, dim, lo, hi, kth):  # type: ignore[no-untyped-def]
    """Reorder ``perm[lo:hi]`` so that ``perm[kth]`` holds the point of its rank along ``dim`` (Hoare's select)."""
    left, right = lo, hi - 1
    while right > left:
        pivot = pts[perm[(left + right) // 2], dim]
        i, j = left, right
        while i <= j:
            while pts[perm[i], dim] < pivot:
                i += 1
            while pts[perm[j], dim] > pivot:
                j -= 1
            if i <= j:
                perm[i], perm[j] = perm[j], perm[i]
                i += 1
                j -= 1
        if kth <= j:
            right = j
        elif kth >= i:
            left = i
        else:
            break


@njit(cache=True, nogil=True)
def kd_build(pts, leaf=8):  # type: ignore[no-untyped-def]
    """A k-d tree of ``pts`` split at the median of the widest side: ``(perm, start, stop, child, low, high)``.

    Node ``k`` holds ``perm[start[k]:stop[k]]`` inside the box ``low[k]``..``high[k]``; its children
    are ``child[k]`` and ``child[k] + 1`` (``-1``: a leaf).
    """
    n, d = pts.shape
    perm = np.arange(n)
    cap = 4 * (n // leaf + 1)
    start, stop, child = np.zeros(cap, np.int64), np.zeros(cap, np.int64), np.full(cap, -1, np.int64)
    low, high = np.zeros((cap, d)), np.zeros((cap, d))
    stop[0] = n
    count, k = 1, 0
    while k < count:
        lo, hi = start[k], stop[k]
        for c in range(d):
            low[k, c], high[k, c] = np.inf, -np.inf
        for p in range(lo, hi):
            for c in range(d):
                v = pts[perm[p], c]
                low[k, c] = min(low[k, c], v)
                high[k, c] = max(high[k, c], v)
        if hi - lo > leaf:
            dim = int(np.argmax(high[k] - low[k]))
            mid = (lo + hi) // 2
            _select(perm, pts, dim, lo, hi, mid)
            child[k] = count
            start[count], stop[count], start[count + 1], stop[count + 1] = lo, mid, mid, hi
            count += 2
        k += 1
    return perm, start[:count], stop[:count], child[:count], low[:count], high[:count]


@njit(cache=True, nogil=True)
def kd_knn(q, k, pts, perm, start, stop, child, low, high):  # type: ignore[no-untyped-def]
    """Indices of the ``k`` points of the tree nearest ``q`` (Euclidean), nearest first."""
    k = min(k, pts.shape[0])
    best_d, best_i = np.full(k, np.inf), np.full(k, -1, np.int64)
    stack, bound = np.empty(256, np.int64), np.empty(256)
    stack[0], bound[0], top = 0, 0.0, 1
    while top:
        top -= 1
        node = stack[top]
        if bound[top] > best_d[k - 1]:
            continue
        if child[node] < 0:
            for p in range(start[node], stop[node]):
                i = perm[p]
                dist = 0.0
                for c in range(q.shape[0]):
                    dist += (pts[i, c] - q[c]) ** 2
                if dist < best_d[k - 1]:
                    m = k - 1
                    while m > 0 and best_d[m - 1] > dist:
                        best_d[m], best_i[m] = best_d[m - 1], best_i[m - 1]
                        m -= 1
                    best_d[m], best_i[m] = dist, i
            continue
        a, b = child[node], child[node] + 1
        da, db = box_distance2(q, low, high, a), box_distance2(q, low, high, b)
        if da < db:
            a, b, da, db = b, a, db, da
        stack[top], bound[top], stack[top + 1], bound[top + 1] = a, da, b, db  # nearer on top
        top += 2
    return best_i


@njit(cache=True, nogil=True)
def snap_one(s, qa, qb, cand, state, tree, k1):  # type: ignore[no-untyped-def]
    """Index of the candidate among the ``k1`` nearest ``s`` (else ``4 k1``) of least quadric error ``(qa, qb)``.

    Only candidates not known to be outside count (``state != -1``), all of them when none is left; a
    candidate taken before it was asked is marked :data:`PENDING`.
    """
    m = cand.shape[0]
    near = np.empty(0, np.int64)
    any_ok = False
    for k in (k1, 4 * k1):
        near = kd_knn(s, k, cand, *tree)
        any_ok = False
        for c in near:
            if state[c] != -1:
                any_ok = True
        if any_ok or k >= m:
            break
    best, best_cost = -1, np.inf
    for c in near:
        if any_ok and state[c] == -1:
            continue
        t = cand[c]
        cost = 0.0
        for a in range(4):
            row = 0.0
            for b in range(4):
                row += qa[a, b] * t[b]
            cost += t[a] * row
        cost -= 2.0 * (t[0] * qb[0] + t[1] * qb[1] + t[2] * qb[2] + t[3] * qb[3])
        if best < 0 or cost < best_cost:
            best, best_cost = c, cost
    if state[best] == 0:
        state[best] = PENDING
    return best


@njit(cache=True, nogil=True)
def snap_many(spheres, qa, qb, cand, state, tree, k1):  # type: ignore[no-untyped-def]
    """:func:`snap_one` of each sphere with its own quadric (the candidates' indices)."""
    out = np.empty(spheres.shape[0], np.int64)
    for i in range(spheres.shape[0]):
        out[i] = snap_one(spheres[i], qa[i], qb[i], cand, state, tree, k1)
    return out


@njit(cache=True, nogil=True)
def _less(cost, key, a, b):  # type: ignore[no-untyped-def]
    if cost[a] != cost[b]:
        return cost[a] < cost[b]
    for c in range(4):
        if key[a, c] != key[b, c]:
            return key[a, c] < key[b, c]
    return False


@njit(cache=True, nogil=True)
def _swap(cost, key, a, b):  # type: ignore[no-untyped-def]
    cost[a], cost[b] = cost[b], cost[a]
    for c in range(4):
        key[a, c], key[b, c] = key[b, c], key[a, c]


@njit(cache=True, nogil=True)
def _push(cost, key, size, value, i, j, vi, vj):  # type: ignore[no-untyped-def]
    """Push onto the heap (``cost``, ``key``) of ``size`` entries; returns the arrays (grown when full)."""
    if size == cost.shape[0]:
        grown_cost, grown_key = np.empty(2 * size + 16), np.empty((2 * size + 16, 4), np.int64)
        grown_cost[:size], grown_key[:size] = cost[:size], key[:size]
        cost, key = grown_cost, grown_key
    cost[size] = value
    key[size, 0], key[size, 1], key[size, 2], key[size, 3] = i, j, vi, vj
    at = size
    while at > 0 and _less(cost, key, at, (at - 1) // 2):
        _swap(cost, key, at, (at - 1) // 2)
        at = (at - 1) // 2
    return cost, key


@njit(cache=True, nogil=True)
def _pop(cost, key, size):  # type: ignore[no-untyped-def]
    """Move the least entry of the heap to ``size - 1`` (the heap is then ``size - 1`` long)."""
    last = size - 1
    _swap(cost, key, 0, last)
    at = 0
    while True:
        low = at
        for c in (2 * at + 1, 2 * at + 2):
            if c < last and _less(cost, key, c, low):
                low = c
        if low == at:
            break
        _swap(cost, key, at, low)
        at = low


@njit(cache=True, nogil=True)
def _drop(lists, count, v, x):  # type: ignore[no-untyped-def]
    row = lists[v]
    for p in range(count[v]):
        if row[p] == x:
            row[p] = row[count[v] - 1]
            count[v] -= 1
            return


@njit(cache=True, nogil=True)
def _add(lists, count, v, x):  # type: ignore[no-untyped-def]
    row = lists[v]
    for p in range(count[v]):
        if row[p] == x:
            return
    if count[v] == row.shape[0]:
        grown = np.empty(2 * row.shape[0] + 4, np.int64)
        grown[: count[v]] = row[: count[v]]
        lists[v] = grown
        row = grown
    row[count[v]] = x
    count[v] += 1


@njit(cache=True, nogil=True)
def collapse(spheres, qa, qb, qc, reg, edges, target, bound, snap, cand, state, tree, k1):  # type: ignore[no-untyped-def]
    """Collapse the cheapest edges until ``target`` spheres are left or the root cost passes ``bound``.

    ``edges`` (both ways not needed) are the mesh's; with ``snap`` each merged sphere is the
    :func:`snap_one` candidate. Returns ``(spheres, into)``: ``into[j]`` is the sphere ``j`` was
    merged into (``-1``: kept). The inputs are not changed (but ``state``).
    """
    spheres, qa, qb, qc = spheres.copy(), qa.copy(), qb.copy(), qc.copy()
    n = spheres.shape[0]
    degree = np.zeros(n, np.int64)
    for e in range(edges.shape[0]):
        degree[edges[e, 0]] += 1
        degree[edges[e, 1]] += 1
    lists = [np.empty(degree[v] + 2, np.int64) for v in range(n)]
    count = np.zeros(n, np.int64)
    for e in range(edges.shape[0]):
        a, b = edges[e, 0], edges[e, 1]
        if a != b:
            _add(lists, count, a, b)
            _add(lists, count, b, a)
    version, into = np.zeros(n, np.int64), np.full(n, -1, np.int64)
    cost, key = np.empty(edges.shape[0] + 16), np.empty((edges.shape[0] + 16, 4), np.int64)
    size = 0
    for i in range(n):
        for p in range(count[i]):
            j = lists[i][p]
            if i < j:
                _, c = optimum(qa[i] + qa[j], qb[i] + qb[j], qc[i] + qc[j], spheres[i], spheres[j], reg)
                cost, key = _push(cost, key, size, c, i, j, 0, 0)
                size += 1
    left = n
    while left > target and size:
        _pop(cost, key, size)
        size -= 1
        c, i, j, vi, vj = cost[size], key[size, 0], key[size, 1], key[size, 2], key[size, 3]
        if into[i] >= 0 or into[j] >= 0 or version[i] != vi or version[j] != vj:
            continue
        if np.sqrt(c) > bound:
            break
        a, b, z = qa[i] + qa[j], qb[i] + qb[j], qc[i] + qc[j]
        s, _ = optimum(a, b, z, spheres[i], spheres[j], reg)
        spheres[i] = cand[snap_one(s, a, b, cand, state, tree, k1)] if snap else s
        qa[i], qb[i], qc[i] = a, b, z
        into[j] = i
        left -= 1
        for p in range(count[j]):
            k = lists[j][p]
            _drop(lists, count, k, j)
            if k != i:
                _add(lists, count, k, i)
                _add(lists, count, i, k)
        _drop(lists, count, i, j)
        count[j] = 0
        version[i] += 1
        for p in range(count[i]):
            k = lists[i][p]
            lo, hi = min(i, k), max(i, k)
            _, c = optimum(qa[lo] + qa[hi], qb[lo] + qb[hi], qc[lo] + qc[hi], spheres[lo], spheres[hi], reg)
            cost, key = _push(cost, key, size, c, lo, hi, version[lo], version[hi])
            size += 1
    return spheres, into


@njit(cache=True, nogil=True)
def span_cosines(centres, contacts, radii, on_sphere):  # type: ignore[no-untyped-def]
    """Per sphere, the least cosine between two of its contacts seen from its centre.

    With ``on_sphere > 0`` a contact farther than ``on_sphere`` of the radius from the sphere does not
    count (cosine ``1``). The arithmetic is numpy's of ``medial_candidates._spans`` (norms, then the
    dot products of the unit vectors).
    """
    n, k = contacts.shape[0], contacts.shape[1]
    out = np.empty(n)
    u, off = np.empty((k, 3)), np.zeros(k, np.bool_)
    for s in range(n):
        for a in range(k):
            sq = 0.0
            for c in range(3):
                u[a, c] = contacts[s, a, c] - centres[s, c]
                sq += u[a, c] * u[a, c]
            d = np.sqrt(sq)
            off[a] = on_sphere > 0 and abs(d - radii[s]) > on_sphere * radii[s]
            d = max(d, 1e-300)
            for c in range(3):
                u[a, c] /= d
        least = np.inf
        for a in range(k):
            for b in range(k):
                cos = 1.0 if off[a] or off[b] else u[a, 0] * u[b, 0] + u[a, 1] * u[b, 1] + u[a, 2] * u[b, 2]
                least = min(least, cos)
        out[s] = least
    return out
