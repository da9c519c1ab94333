"""Compiled kernels of the incremental Delaunay tetrahedralisation (:mod:`medialaxis.mesh.sample.delaunay`).

The first tetrahedron and the insertion of points (Bowyer-Watson), on the
layout of :mod:`medialaxis.mesh.sample._predicates`; point location is in
:mod:`medialaxis.mesh.sample._delaunay_locate`.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit
from medialaxis.mesh.sample._delaunay_locate import _scan, _walk, prefetch
from medialaxis.mesh.sample._predicates import _FACE_OUT, _GRID, _OTHER, _conflict, _inf_pos, _orient, _visible

#: Insertions of a point, each moved further at random, before it is given up.
MAX_ATTEMPTS = 16
_OK, _COLLINEAR, _COPLANAR = 0, 1, 2


# ----------------------------------------------------------------------------
# the triangulation
# ----------------------------------------------------------------------------

#: Indices of the kernel's scalar state.
_NT, _NFREE, _LAST, _STAMP, _HSTAMP, _RNG = 0, 1, 2, 3, 4, 5
#: Statistics: points given up, extra moves, tetrahedra taken out of a cavity, walk steps (unused).
_DROPPED, _MOVED, _SHRUNK = 0, 1, 2
#: Why :func:`_insert` returned.
_DONE, _GROW_TETS, _GROW_BUFFERS, _GROW_HASH = 0, 1, 2, 3


@njit(cache=True, nogil=True)
def _initial(P, order, tet, inf):  # type: ignore[no-untyped-def]
    """First tetrahedron (four non-coplanar points) and its four infinite neighbours.

    Returns ``(status, a, b, c, d)``.
    """
    m = order.shape[0]
    a = order[0]
    b = -1
    ux = uy = uz = uu = 0.0
    for i in range(1, m):
        b = order[i]
        ux, uy, uz = P[b, 0] - P[a, 0], P[b, 1] - P[a, 1], P[b, 2] - P[a, 2]
        uu = ux * ux + uy * uy + uz * uz
        if uu > 0.0:
            break
    c = -1
    for i in range(1, m):
        q = order[i]
        vx, vy, vz = P[q, 0] - P[a, 0], P[q, 1] - P[a, 1], P[q, 2] - P[a, 2]
        cx, cy, cz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
        if cx * cx + cy * cy + cz * cz > 1e-20 * uu * (vx * vx + vy * vy + vz * vz):
            c = q
            break
    if c < 0:
        return _COLLINEAR, a, b, c, -1
    d = -1
    for i in range(1, m):
        q = order[i]
        if _orient(P, a, b, c, q) != 0:
            d = q
            break
    if d < 0:
        return _COPLANAR, a, b, c, d
    if _orient(P, a, b, c, d) < 0:
        b, c = c, b
    tet[0, 0], tet[0, 1], tet[0, 2], tet[0, 3] = a, b, c, d
    for k in range(4):
        for j in range(3):
            tet[1 + k, j] = tet[0, _FACE_OUT[k, j]]
        tet[1 + k, 3] = inf
    # neighbours of the five tetrahedra, by brute force
    for t in range(5):
        for k in range(4):
            for u in range(5):
                if u == t:
                    continue
                shared = 0
                for j in range(4):
                    if j == k:
                        continue
                    x = tet[t, j]
                    if x == tet[u, 0] or x == tet[u, 1] or x == tet[u, 2] or x == tet[u, 3]:
                        shared += 1
                if shared == 3:
                    for ku in range(4):
                        y = tet[u, ku]
                        if y != tet[t, 0] and y != tet[t, 1] and y != tet[t, 2] and y != tet[t, 3]:
                            tet[t, 4 + k] = 4 * u + ku
    return _OK, a, b, c, d


@njit(cache=True, nogil=True)
def _insert(P, order, start, jog, tet, cap, mark, free, cav, bf, htab, state, stats):  # type: ignore[no-untyped-def]
    """Insert ``P[order[start:]]`` into the triangulation ``tet`` (Bowyer-Watson; see the module docstring).

    Every array is given (and grown by the caller): nothing is allocated here.

    Parameters
    ----------
    P : (m + 1, 3) float64 ndarray
        Joggled points; the last row stands for the vertex at infinity.
        Points that need it are moved further, in place.
    order : (m,) int64 ndarray
    start : int
    jog : float
        Joggle size: the first extra move of a point is at most ``2 * jog`` per coordinate.
    tet : (n, 8) int32 ndarray
        Vertices (``tet[t, 0] == -1``: free slot) and neighbours (``4 * tet + face``).
    cap : int
        Slots the insertion may use, at most ``n``: it returns ``_GROW_TETS`` when a cavity would need
        more. The caller doubles ``cap`` (and the arrays only when ``n`` is reached): the point is then
        walked to again, with the random state moved on, so the results depend on ``cap``, not on ``n``.
    mark : (n,) int32 ndarray
        Cavity stamps.
    free : (n,) int32 ndarray
        Free slots (a stack).
    cav : (b,) int32 ndarray
    bf : (b, 6) int32 ndarray
        Cavity and boundary faces (face, outside neighbour, new tetrahedron's vertices).
    htab : (2 ** h, 4) int64 ndarray
        Hash table of the boundary edges: stamp, key, value (one row, one cache line per probe).
    state : (6,) int64 ndarray
        Slots used, free slots, last tetrahedron created, stamps, random state.
    stats : (3,) int64 ndarray

    Returns
    -------
    next : int
        First point of ``order`` not inserted yet.
    why : int
        ``_DONE``, or which arrays to grow before calling again from ``next``.
    """
    m = P.shape[0] - 1
    inf = m
    nbuf = cav.shape[0]
    hmask = htab.shape[0] - 1
    nt = state[_NT]
    nfree = state[_NFREE]
    last = state[_LAST]
    stamp = state[_STAMP]
    hst = state[_HSTAMP]
    rng = state[_RNG : _RNG + 1]
    why = _DONE
    ii = start
    while ii < order.shape[0]:
        p = order[ii]
        if p < 0:  # already in the first tetrahedron
            ii += 1
            continue
        done = False
        for attempt in range(MAX_ATTEMPTS):
            if attempt > 0:
                # move p a little further at random and try again
                scale = jog * (2.0**attempt)
                for j in range(3):
                    rng[0] = rng[0] * 6364136223846793005 + 1442695040888963407
                    u01 = ((rng[0] >> 11) & ((1 << 52) - 1)) / float(1 << 52)
                    P[p, j] = np.rint((P[p, j] + scale * (2.0 * u01 - 1.0)) * _GRID) / _GRID
                stats[_MOVED] += 1
            if stamp > (1 << 30):
                mark[:] = 0
                stamp = 0
            stamp += 2
            s_out = stamp - 1
            s_in = stamp

            # ---- locate
            t = last
            ip = _inf_pos(tet, t, inf)
            if ip >= 0:
                t = tet[t, 4 + ip] >> 2
            root = _walk(P, tet, t, p, inf, rng)
            if root < 0:
                root = _scan(P, tet, nt, p, inf)
                if root < 0:
                    continue
            if _conflict(P, tet, root, p, inf) <= 0:
                continue

            # ---- cavity: tetrahedra strictly in conflict, grown from root
            cav[0] = root
            nc = 1
            tie = False
            mark[root] = s_in
            head = 0
            full = False
            while head < nc:
                t = cav[head]
                head += 1
                for k in range(4):
                    u = tet[t, 4 + k] >> 2
                    if mark[u] >= s_out:
                        continue
                    c = _conflict(P, tet, u, p, inf)
                    if c > 0:
                        if nc == nbuf:
                            full = True
                            break
                        for kk in range(4):  # read when u's turn comes: fetch them meanwhile
                            w = tet[u, 4 + kk] >> 2
                            prefetch(tet, w)
                            prefetch(mark, w)
                        mark[u] = s_in
                        cav[nc] = u
                        nc += 1
                    else:
                        tie |= c == 0
                        mark[u] = s_out
                if full:
                    break
            if full:
                why = _GROW_BUFFERS
                break

            # ---- every boundary face must be strictly visible from p. Exact Delaunay promises it when the
            # triangulation is Delaunay (no point moved further, no cavity shrunk so far) and no boundary
            # neighbour is tied (p on its circumsphere or its hull plane): a tetrahedron whose circumsphere
            # holds p strictly, across a locally Delaunay face from one whose sphere leaves it strictly out,
            # sees p strictly on its side of that face (the two balls differ only there). Otherwise every
            # face is checked: a tie or an earlier repair can break that promise. (Checking always cost 13%
            # of the insertion on the uv ellipsoid's 221k samples, and never failed there.)
            ok = True
            changed = tie or stats[_MOVED] > 0 or stats[_SHRUNK] > 0
            while changed and ok:
                changed = False
                for i in range(nc):
                    t = cav[i]
                    if mark[t] != s_in:
                        continue
                    for k in range(4):
                        u = tet[t, 4 + k] >> 2
                        if mark[u] == s_in:
                            continue
                        if not _visible(P, tet, t, k, p, inf):
                            if t == root or _inf_pos(tet, t, inf) >= 0:
                                ok = False
                            else:
                                mark[t] = s_out
                                stats[_SHRUNK] += 1
                                changed = True
                            break
                    if not ok:
                        break
            if not ok:
                continue

            # ---- boundary faces
            nbf = 0
            ncav = 0
            for i in range(nc):
                t = cav[i]
                if mark[t] != s_in:
                    continue
                ncav += 1
                for k in range(4):
                    o = tet[t, 4 + k]
                    if mark[o >> 2] == s_in:
                        continue
                    if nbf == nbuf:
                        full = True
                        break
                    bf[nbf, 0] = k
                    bf[nbf, 1] = o
                    for j in range(4):
                        bf[nbf, 2 + j] = tet[t, j]
                    bf[nbf, 2 + k] = p
                    nbf += 1
                if full:
                    break
            if full:
                why = _GROW_BUFFERS
                break
            if nbf > ncav + nfree + cap - nt:
                why = _GROW_TETS
                break
            if 6 * nbf > hmask + 1:
                why = _GROW_HASH
                break

            # ---- replace the cavity by the new tetrahedra
            for i in range(nc):
                t = cav[i]
                if mark[t] != s_in:
                    continue
                tet[t, 0] = -1
                free[nfree] = t
                nfree += 1
            for j in range(nbf):
                if nfree > 0:
                    nfree -= 1
                    t = free[nfree]
                else:
                    t = nt
                    nt += 1
                cav[j] = t  # the cavity list is no longer needed: it now holds the new tetrahedra
                for q in range(4):
                    tet[t, q] = bf[j, 2 + q]
                mark[t] = 0
                k = bf[j, 0]
                o = bf[j, 1]
                tet[t, 4 + k] = o
                tet[o >> 2, 4 + (o & 3)] = 4 * t + k
            # faces through p: matched by the boundary edge they contain
            hst += 1
            for j in range(nbf):
                t = cav[j]
                k = bf[j, 0]
                for q in range(4):
                    if q == k:
                        continue
                    x = np.int64(tet[t, _OTHER[q, k, 0]])
                    y = np.int64(tet[t, _OTHER[q, k, 1]])
                    if x > y:
                        x, y = y, x
                    key = x * (m + 1) + y
                    h = key * -7046029254386353131
                    h = (h ^ (h >> 29)) & hmask
                    while True:
                        if htab[h, 0] != hst:
                            htab[h, 0] = hst
                            htab[h, 1] = key
                            htab[h, 2] = 4 * t + q
                            break
                        if htab[h, 1] == key:
                            o = htab[h, 2]
                            tet[t, 4 + q] = o
                            tet[o >> 2, 4 + (o & 3)] = 4 * t + q
                            break
                        h = (h + 1) & hmask
            last = cav[0]
            done = True
            break
        if why != _DONE:
            break
        if not done:
            stats[_DROPPED] += 1
        ii += 1
    state[_NT] = nt
    state[_NFREE] = nfree
    state[_LAST] = last
    state[_STAMP] = stamp
    state[_HSTAMP] = hst
    return ii, why
