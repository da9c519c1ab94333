"""Geometric predicates of the Delaunay tetrahedralisation: exact orient3d and insphere, and on tetrahedra.

J. R. Shewchuk's predicates ("Adaptive precision floating-point arithmetic
and fast robust geometric predicates", 1997): evaluated in floating point
with his error bound (``errboundA`` times the permanent), and exactly on
floating-point expansions when the bound does not settle the sign. The
points must lie on a grid of step ``2**-GRID_BITS`` inside (-1, 1)
(:mod:`medialaxis.mesh.sample.delaunay` rounds them so), which makes every
coordinate difference exact.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit

#: The points (in a box of side 1 centred on 0) lie on multiples of 2**-GRID_BITS, so that
#: coordinate differences are exact (the exact predicates rely on it).
GRID_BITS = 50
_GRID = float(2**GRID_BITS)
_EPS = 2.0**-53
_O3D_ERR = (7.0 + 56.0 * _EPS) * _EPS
_ISP_ERR = (16.0 + 224.0 * _EPS) * _EPS


# ----------------------------------------------------------------------------
# exact arithmetic (J. R. Shewchuk's floating-point expansions), for the rare
# predicates the error bound does not settle. The points lie on a grid of
# step 2**-GRID_BITS inside (-1, 1), so every coordinate difference is exact.
# ----------------------------------------------------------------------------

_SPLITTER = 134217729.0  # 2**27 + 1


@njit(cache=True, nogil=True, inline="always")
def _two_sum(a, b):  # type: ignore[no-untyped-def]
    x = a + b
    bv = x - a
    av = x - bv
    return x, (a - av) + (b - bv)


@njit(cache=True, nogil=True, inline="always")
def _two_product(a, b):  # type: ignore[no-untyped-def]
    x = a * b
    c = _SPLITTER * a
    ahi = c - (c - a)
    alo = a - ahi
    c = _SPLITTER * b
    bhi = c - (c - b)
    blo = b - bhi
    err = x - ahi * bhi
    err -= alo * bhi
    err -= ahi * blo
    return x, alo * blo - err


@njit(cache=True, nogil=True)
def _expansion_sum(e, ne, f, nf, h):  # type: ignore[no-untyped-def]
    """``h = e + f`` (fast_expansion_sum_zeroelim); returns the length of ``h`` (at least 1)."""
    ie = 0
    jf = 0
    if (f[0] > e[0]) == (f[0] > -e[0]):
        q = e[0]
        ie = 1
    else:
        q = f[0]
        jf = 1
    nh = 0
    while ie < ne and jf < nf:
        if (f[jf] > e[ie]) == (f[jf] > -e[ie]):
            q, hh = _two_sum(q, e[ie])
            ie += 1
        else:
            q, hh = _two_sum(q, f[jf])
            jf += 1
        if hh != 0.0:
            h[nh] = hh
            nh += 1
    while ie < ne:
        q, hh = _two_sum(q, e[ie])
        ie += 1
        if hh != 0.0:
            h[nh] = hh
            nh += 1
    while jf < nf:
        q, hh = _two_sum(q, f[jf])
        jf += 1
        if hh != 0.0:
            h[nh] = hh
            nh += 1
    if q != 0.0 or nh == 0:
        h[nh] = q
        nh += 1
    return nh


@njit(cache=True, nogil=True)
def _scale_expansion(e, ne, b, h):  # type: ignore[no-untyped-def]
    """``h = b * e`` (scale_expansion_zeroelim); returns the length of ``h`` (at least 1)."""
    q, hh = _two_product(e[0], b)
    nh = 0
    if hh != 0.0:
        h[nh] = hh
        nh += 1
    for i in range(1, ne):
        p1, p0 = _two_product(e[i], b)
        s, hh = _two_sum(q, p0)
        if hh != 0.0:
            h[nh] = hh
            nh += 1
        q = p1 + s
        hh = s - (q - p1)
        if hh != 0.0:
            h[nh] = hh
            nh += 1
    if q != 0.0 or nh == 0:
        h[nh] = q
        nh += 1
    return nh


@njit(cache=True, nogil=True)
def _minor2(a, b, c, d, h):  # type: ignore[no-untyped-def]
    """``h = a * b - c * d`` exactly; returns its length."""
    x1, y1 = _two_product(a, b)
    x2, y2 = _two_product(c, d)
    e = np.empty(2)
    f = np.empty(2)
    e[0], e[1] = y1, x1
    f[0], f[1] = -y2, -x2
    return _expansion_sum(e, 2, f, 2, h)


@njit(cache=True, nogil=True)
def _minor3(x0, y0, z0, x1, y1, z1, x2, y2, z2, h):  # type: ignore[no-untyped-def]
    """``h = det[[x0, y0, z0], [x1, y1, z1], [x2, y2, z2]]`` exactly; returns its length."""
    m = np.empty(4)
    s = np.empty(8)
    t = np.empty(8)
    acc = np.empty(16)
    nm = _minor2(y1, z2, z1, y2, m)
    ns = _scale_expansion(m, nm, x0, s)
    nm = _minor2(z1, x2, x1, z2, m)
    nt = _scale_expansion(m, nm, y0, t)
    na = _expansion_sum(s, ns, t, nt, acc)
    nm = _minor2(x1, y2, y1, x2, m)
    ns = _scale_expansion(m, nm, z0, s)
    return _expansion_sum(acc, na, s, ns, h)


@njit(cache=True, nogil=True)
def _orient_exact(P, i0, i1, i2, i3):  # type: ignore[no-untyped-def]
    """Exact sign of ``det[p1 - p0, p2 - p0, p3 - p0]`` (the differences are exact on the grid)."""
    h = np.empty(24)
    n = _minor3(
        P[i1, 0] - P[i0, 0], P[i1, 1] - P[i0, 1], P[i1, 2] - P[i0, 2],
        P[i2, 0] - P[i0, 0], P[i2, 1] - P[i0, 1], P[i2, 2] - P[i0, 2],
        P[i3, 0] - P[i0, 0], P[i3, 1] - P[i0, 1], P[i3, 2] - P[i0, 2],
        h,
    )  # fmt: skip
    top = h[n - 1]
    return 1 if top > 0.0 else (-1 if top < 0.0 else 0)


@njit(cache=True, nogil=True)
def _insphere_exact(P, a, b, c, d, e):  # type: ignore[no-untyped-def]
    """Exact :func:`_insphere`: the lifted 4 x 4 determinant of ``a - e, b - e, c - e, d - e``."""
    q = np.empty((4, 3))
    for r, i in enumerate((a, b, c, d)):
        for j in range(3):
            q[r, j] = P[i, j] - P[e, j]
    acc = np.empty(1152)
    tmp = np.empty(1152)
    nacc = 1
    acc[0] = 0.0
    minor = np.empty(24)
    lift = np.empty(6)
    part = np.empty(2)
    two = np.empty(2)
    four = np.empty(4)
    scaled = np.empty(48)
    prod = np.empty(288)
    ptmp = np.empty(288)
    for r in range(4):
        # cofactor of the lift of row r: (-1) ** (r + 3) * det of the other rows' coordinates
        o0, o1, o2 = (1, 2, 3) if r == 0 else ((0, 2, 3) if r == 1 else ((0, 1, 3) if r == 2 else (0, 1, 2)))
        nmin = _minor3(q[o0, 0], q[o0, 1], q[o0, 2], q[o1, 0], q[o1, 1], q[o1, 2], q[o2, 0], q[o2, 1], q[o2, 2], minor)
        if r % 2 == 0:
            for i in range(nmin):
                minor[i] = -minor[i]
        # lift of row r: x * x + y * y + z * z
        x1, y1 = _two_product(q[r, 0], q[r, 0])
        x2, y2 = _two_product(q[r, 1], q[r, 1])
        part[0], part[1] = y1, x1
        two[0], two[1] = y2, x2
        nf = _expansion_sum(part, 2, two, 2, four)
        x3, y3 = _two_product(q[r, 2], q[r, 2])
        two[0], two[1] = y3, x3
        nl = _expansion_sum(four, nf, two, 2, lift)
        # lift * minor
        nprod = 1
        prod[0] = 0.0
        for k in range(nl):
            ns = _scale_expansion(minor, nmin, lift[k], scaled)
            nt = _expansion_sum(prod, nprod, scaled, ns, ptmp)
            prod[:nt] = ptmp[:nt]
            nprod = nt
        nt = _expansion_sum(acc, nacc, prod, nprod, tmp)
        acc[:nt] = tmp[:nt]
        nacc = nt
    top = acc[nacc - 1]
    # acc is the 4 x 4 determinant of rows (q, lift); positive means outside for a positive abcd
    return -1 if top > 0.0 else (1 if top < 0.0 else 0)


# ----------------------------------------------------------------------------
# predicates
# ----------------------------------------------------------------------------


@njit(cache=True, nogil=True, inline="always")
def _orient_raw(P, i0, i1, i2, i3):  # type: ignore[no-untyped-def]
    """``det[p1 - p0, p2 - p0, p3 - p0]`` in floating point and a bound on its rounding error."""
    # Shewchuk's orient3d(a, b, c, d) = det[a - d, b - d, c - d] = -det[b - a, c - a, d - a]
    dx, dy, dz = P[i3, 0], P[i3, 1], P[i3, 2]
    adx, ady, adz = P[i0, 0] - dx, P[i0, 1] - dy, P[i0, 2] - dz
    bdx, bdy, bdz = P[i1, 0] - dx, P[i1, 1] - dy, P[i1, 2] - dz
    cdx, cdy, cdz = P[i2, 0] - dx, P[i2, 1] - dy, P[i2, 2] - dz
    bdxcdy = bdx * cdy
    cdxbdy = cdx * bdy
    cdxady = cdx * ady
    adxcdy = adx * cdy
    adxbdy = adx * bdy
    bdxady = bdx * ady
    det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady)
    permanent = (
        (abs(bdxcdy) + abs(cdxbdy)) * abs(adz)
        + (abs(cdxady) + abs(adxcdy)) * abs(bdz)
        + (abs(adxbdy) + abs(bdxady)) * abs(cdz)
    )
    return -det, _O3D_ERR * permanent


@njit(cache=True, nogil=True, inline="always")
def _orient(P, i0, i1, i2, i3):  # type: ignore[no-untyped-def]
    """Exact sign of ``det[p1 - p0, p2 - p0, p3 - p0]``: +1, -1 or 0.

    Floating point with Shewchuk's error bound, exact arithmetic when the
    bound does not settle the sign.
    """
    det, err = _orient_raw(P, i0, i1, i2, i3)
    if det > err:
        return 1
    if -det > err:
        return -1
    return _orient_exact(P, i0, i1, i2, i3)


@njit(cache=True, nogil=True, inline="always")
def _insphere(P, a, b, c, d, e):  # type: ignore[no-untyped-def]
    """For a positively oriented ``abcd``: +1 if ``e`` is inside its circumsphere, -1 outside, 0 on it (exact)."""
    ex, ey, ez = P[e, 0], P[e, 1], P[e, 2]
    aex, aey, aez = P[a, 0] - ex, P[a, 1] - ey, P[a, 2] - ez
    bex, bey, bez = P[b, 0] - ex, P[b, 1] - ey, P[b, 2] - ez
    cex, cey, cez = P[c, 0] - ex, P[c, 1] - ey, P[c, 2] - ez
    dex, dey, dez = P[d, 0] - ex, P[d, 1] - ey, P[d, 2] - ez
    aexbey = aex * bey
    bexaey = bex * aey
    ab = aexbey - bexaey
    bexcey = bex * cey
    cexbey = cex * bey
    bc = bexcey - cexbey
    cexdey = cex * dey
    dexcey = dex * cey
    cd = cexdey - dexcey
    dexaey = dex * aey
    aexdey = aex * dey
    da = dexaey - aexdey
    aexcey = aex * cey
    cexaey = cex * aey
    ac = aexcey - cexaey
    bexdey = bex * dey
    dexbey = dex * bey
    bd = bexdey - dexbey
    abc = aez * bc - bez * ac + cez * ab
    bcd = bez * cd - cez * bd + dez * bc
    cda = cez * da + dez * ac + aez * cd
    dab = dez * ab + aez * bd + bez * da
    alift = aex * aex + aey * aey + aez * aez
    blift = bex * bex + bey * bey + bez * bez
    clift = cex * cex + cey * cey + cez * cez
    dlift = dex * dex + dey * dey + dez * dez
    det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd)
    # a cheaper bound first: every |coordinate difference| is at most big, so the permanent is at most
    # 72 big**5 (4 lifts of at most 3 big**2, times 6 products of at most big**3); 80 covers its rounding
    big = max(
        max(max(abs(aex), abs(aey)), max(abs(aez), abs(bex))),
        max(max(abs(bey), abs(bez)), max(abs(cex), abs(cey))),
        max(max(abs(cez), abs(dex)), max(abs(dey), abs(dez))),
    )
    big2 = big * big
    coarse = (80.0 * _ISP_ERR) * (big2 * big2 * big)
    if det < -coarse:
        return 1
    if det > coarse:
        return -1
    aezp, bezp, cezp, dezp = abs(aez), abs(bez), abs(cez), abs(dez)
    aexbeyp, bexaeyp, bexceyp, cexbeyp = abs(aexbey), abs(bexaey), abs(bexcey), abs(cexbey)
    cexdeyp, dexceyp, dexaeyp, aexdeyp = abs(cexdey), abs(dexcey), abs(dexaey), abs(aexdey)
    aexceyp, cexaeyp, bexdeyp, dexbeyp = abs(aexcey), abs(cexaey), abs(bexdey), abs(dexbey)
    permanent = (
        ((cexdeyp + dexceyp) * bezp + (dexbeyp + bexdeyp) * cezp + (bexceyp + cexbeyp) * dezp) * alift
        + ((dexaeyp + aexdeyp) * cezp + (aexceyp + cexaeyp) * dezp + (cexdeyp + dexceyp) * aezp) * blift
        + ((aexbeyp + bexaeyp) * dezp + (bexdeyp + dexbeyp) * aezp + (dexaeyp + aexdeyp) * bezp) * clift
        + ((bexceyp + cexbeyp) * aezp + (cexaeyp + aexceyp) * bezp + (aexbeyp + bexaeyp) * cezp) * dlift
    )
    err = _ISP_ERR * permanent
    # Shewchuk's insphere is positive inside for his positive orientation, which is our negative one.
    if det < -err:
        return 1
    if det > err:
        return -1
    return _insphere_exact(P, a, b, c, d, e)


# ----------------------------------------------------------------------------
# predicates on the tetrahedra: (cap, 8) int32 rows, four vertices then four
# neighbours as 4 * tet + face; the vertex at infinity is index ``inf``
# ----------------------------------------------------------------------------

#: Vertices of the face opposite vertex k, ordered so that its normal points out of the tetrahedron.
_FACE_OUT = np.array([[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]], np.int64)
#: _OTHER[q, k]: the two local vertices other than q and k (q != k).
_OTHER = np.array(
    [
        [[-1, -1], [2, 3], [1, 3], [1, 2]],
        [[2, 3], [-1, -1], [0, 3], [0, 2]],
        [[1, 3], [0, 3], [-1, -1], [0, 1]],
        [[1, 2], [0, 2], [0, 1], [-1, -1]],
    ],
    np.int64,
)


@njit(cache=True, nogil=True, inline="always")
def _orient_sub(P, tet, t, k, p):  # type: ignore[no-untyped-def]
    """Orientation (exact sign) of tetrahedron ``t`` with its vertex ``k`` replaced by point ``p``."""
    v0, v1, v2, v3 = tet[t, 0], tet[t, 1], tet[t, 2], tet[t, 3]
    if k == 0:
        v0 = p
    elif k == 1:
        v1 = p
    elif k == 2:
        v2 = p
    else:
        v3 = p
    return _orient(P, v0, v1, v2, v3)


@njit(cache=True, nogil=True, inline="always")
def _inf_pos(tet, t, inf):  # type: ignore[no-untyped-def]
    """Local index of the infinite vertex in tetrahedron ``t``, or -1."""
    if tet[t, 3] == inf:
        return 3
    if tet[t, 2] == inf:
        return 2
    if tet[t, 1] == inf:
        return 1
    if tet[t, 0] == inf:
        return 0
    return -1


@njit(cache=True, nogil=True, inline="always")
def _conflict(P, tet, t, p, inf):  # type: ignore[no-untyped-def]
    """+1 when ``p`` is strictly inside the circumsphere of ``t`` (strictly beyond its hull face if
    infinite), -1 when strictly outside (strictly inside the hull face's half-space), 0 on it (a tie)."""
    ip = _inf_pos(tet, t, inf)
    if ip >= 0:
        return _orient_sub(P, tet, t, ip, p)
    return _insphere(P, tet[t, 0], tet[t, 1], tet[t, 2], tet[t, 3], p)


@njit(cache=True, nogil=True, inline="always")
def _visible(P, tet, t, k, p, inf):  # type: ignore[no-untyped-def]
    """True when the tetrahedron ``t`` with vertex ``k`` replaced by ``p`` is positively oriented (not flat).

    For an infinite result, the far vertex of the neighbour across face ``k``
    is put in place of the infinite vertex and must be strictly on the
    inner side of the new hull triangle.
    """
    v0, v1, v2, v3 = tet[t, 0], tet[t, 1], tet[t, 2], tet[t, 3]
    if k == 0:
        v0 = p
    elif k == 1:
        v1 = p
    elif k == 2:
        v2 = p
    else:
        v3 = p
    if v0 != inf and v1 != inf and v2 != inf and v3 != inf:
        return _orient(P, v0, v1, v2, v3) > 0
    o = tet[t, 4 + k]
    d = tet[o >> 2, o & 3]
    if v0 == inf:
        v0 = d
    elif v1 == inf:
        v1 = d
    elif v2 == inf:
        v2 = d
    else:
        v3 = d
    return _orient(P, v0, v1, v2, v3) < 0
