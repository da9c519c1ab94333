"""Compiled piece state of the adaptive sampling that knows convex corners: mirrored corner samples need no refinement.

Near a convex vertex ``v`` of a polygon the medial axis is the bisector of
its two edges. Samples placed in mirrored pairs, at equal distances from
``v`` along both edges, have Delaunay triangles whose circumcentres lie on
that bisector (an isosceles trapezoid is cyclic, its centre on the axis of
symmetry; the triangle of ``v`` and its two neighbours is isosceles): they
are points of the medial axis however far apart the samples are. Their small
circumradius, which makes the rule of
:func:`medialaxis.planar.boundary.sampling.refine_arcs` split the pieces at a corner
again and again down to ``min_length``, says nothing about the sampling
error there.

:func:`corner_piece_state` is :func:`medialaxis.planar._kernels.piece_state`
with three changes:

* *corner triangles* do not count in the radius of their pieces. Each is
  checked, not assumed: its three samples lie on the two edges of one convex
  vertex, and its circumcentre lies on the inner side of both edges, projects
  inside both, and is within ``tolerance / OVER_SPLIT**2`` of their bisector (the
  bound the split rule keeps elsewhere, ``h**2 / (16 R)`` with pieces over-split);
* mirrored pieces (the pieces met walking from a convex vertex along both
  edges while the samples stay at equal distances from it) get the smaller
  radius of the two and are conforming only if both are, so they are split
  alike and stay mirrored;
* the pieces of a sample at a pinch (a vertex ``touching`` another) get the radii of the inner triangles
  at the other sample there (:mod:`medialaxis.planar.boundary._pinch_kernels`).

Samples are ``offset .. len(nxt) - 1`` (the incremental kernels keep the
far corners of the triangulation before them); ``rings_s``, ``rings_xy`` are
each closed ring's cumulative arc length and vertices, ring ``r`` at
``rings_start[r]:rings_start[r + 1]``; ``convex`` flags those vertices.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit
from medialaxis.planar._kernels import OVER_SPLIT, piece_state
from medialaxis.planar.boundary._circle_kernels import whole_circles
from medialaxis.planar.boundary._pinch_kernels import pinched_radius

__all__ = ["sample_edges", "corner_triangle", "corner_triangles", "corner_piece_state", "corner_piece_state_memo", "closed_rings",
           "ERROR_SHARE"]

#: A corner triangle's circumcentre is within this share of the tolerance of the bisector (the split rule's bound).
ERROR_SHARE = 1.0 / OVER_SPLIT**2
#: Mirrored samples go in from a corner's nearest samples, each this many times closer to the corner ...
PROGRESSION = 3.0
#: ... down to the pair ``2 * REACH * min_length`` apart (a hair above ``lam``, which is ``8 * min_length`` by
#: default: the pruned axis reaches into the corner up to that pair, as far as with dense samples), and one more.
REACH = 4.0 * (1.0 + 1e-6)


@njit(cache=True, nogil=True, inline="always")
def sample_edges(arc, ring, offset, rings_s, rings_start):  # type: ignore[no-untyped-def]
    """The edge of each sample (its first vertex, numbered in its ring) and whether the sample is that vertex."""
    n = len(arc)
    edge = np.full(n, -1, np.int64)
    at_vertex = np.zeros(n, np.bool_)
    for i in range(offset, n):
        lo = rings_start[ring[i]]
        a, b = 0, rings_start[ring[i] + 1] - lo - 1  # the last j with s[j] <= arc, by bisection
        while b - a > 1:
            mid = (a + b) // 2
            if rings_s[lo + mid] <= arc[i]:
                a = mid
            else:
                b = mid
        edge[i] = a
        at_vertex[i] = rings_s[lo + a] == arc[i]
    return edge, at_vertex


@njit(cache=True, nogil=True, inline="always")
def _touches(edge_i, at_vertex_i, v, m):  # type: ignore[no-untyped-def]
    """A sample on edge ``edge_i`` (at its first vertex: ``at_vertex_i``) lies on an edge of vertex ``v`` (ring of ``m`` vertices)."""
    d = (v - edge_i) % m
    return d == 0 or d == 1 or (at_vertex_i and d == m - 1)


def corner_triangle(a, b, c, centre_x, centre_y, edge, at_vertex, ring, rings_xy, rings_start, convex, tolerance):  # type: ignore[no-untyped-def]
    """Whether the triangle of samples ``a, b, c`` is a corner triangle (see the module docstring)."""
    return bool(corner_triangles(np.array([[a, b, c]], np.int64), np.array([0], np.int64),
                                 np.array([[centre_x, centre_y]], np.float64), edge, at_vertex, ring, rings_xy,
                                 rings_start, convex, tolerance)[0])


@njit(cache=True, nogil=True)
def corner_triangles(simplices, slots, centres, edge, at_vertex, ring, rings_xy, rings_start, convex, tolerance,  # type: ignore[no-untyped-def]
                     over_split=OVER_SPLIT):
    """Whether each triangle ``simplices[slots[j]]`` is a corner triangle (see the module docstring; its
    circumcentre within ``tolerance / over_split**2`` of the bisector).

    One call for all the triangles, the test written out in the loop: a
    compiled call per triangle with array arguments costs two atomic
    reference counts per array.
    """
    out = np.zeros(len(slots), np.bool_)
    share = 2.0 / (over_split * over_split)  # abs(d1 - d2) is the distance to the bisector times 2 half_sine
    for j in range(len(slots)):
        t = slots[j]
        a, b, c = simplices[t, 0], simplices[t, 1], simplices[t, 2]
        r = ring[a]
        if ring[b] != r or ring[c] != r:
            continue
        lo = rings_start[r]
        m = rings_start[r + 1] - lo - 1
        if m < 3:
            continue
        for step in range(3):  # the vertices sample a may belong to
            v = (edge[a] + step - 1) % m
            if not convex[lo + v] or not (_touches(edge[a], at_vertex[a], v, m) and _touches(edge[b], at_vertex[b], v, m)
                                          and _touches(edge[c], at_vertex[c], v, m)):
                continue
            px, py = rings_xy[lo + (v - 1) % m, 0], rings_xy[lo + (v - 1) % m, 1]
            vx, vy = rings_xy[lo + v, 0], rings_xy[lo + v, 1]
            nx, ny = rings_xy[lo + (v + 1) % m, 0], rings_xy[lo + (v + 1) % m, 1]
            ux, uy = vx - px, vy - py  # the edge into v
            wx, wy = nx - vx, ny - vy  # the edge out of v
            l1 = np.sqrt(ux * ux + uy * uy)
            l2 = np.sqrt(wx * wx + wy * wy)
            cx, cy = centres[t, 0] - vx, centres[t, 1] - vy
            d1 = (uy * cx - ux * cy) / l1  # distances to both edges' lines, positive on the inner (right) side
            d2 = (wy * cx - wx * cy) / l2
            f1 = -(ux * cx + uy * cy) / l1  # the feet, from v along each edge
            f2 = (wx * cx + wy * cy) / l2
            half_sine = np.sqrt(max(0.5 * (1.0 + (ux * wx + uy * wy) / (l1 * l2)), 0.0))  # sin of half the inner angle
            if (d1 >= 0.0 and d2 >= 0.0 and 0.0 <= f1 <= l1 and 0.0 <= f2 <= l2
                    and abs(d1 - d2) <= share * tolerance * half_sine):
                out[j] = True
                break
    return out


@njit(cache=True, nogil=True)
def corner_piece_state(simplices, inside, radii, centres, nxt, arc, ring, offset, rings_s, rings_xy, rings_start,
                       convex, touching, tolerance, over_split=OVER_SPLIT):  # type: ignore[no-untyped-def]
    """``(conforming, radius)`` of every piece ``(i, nxt[i])``, corner triangles left out and mirrored pieces alike;
    the pieces at vertices ``touching`` another get the radii of both (:mod:`medialaxis.planar.boundary._pinch_kernels`)."""
    memo = np.full((len(simplices), 4), -1, np.int64)
    return corner_piece_state_memo(simplices, inside, radii, centres, nxt, arc, ring, offset, rings_s, rings_xy,
                                   rings_start, convex, touching, tolerance, memo, over_split)


@njit(cache=True, nogil=True)
def corner_piece_state_memo(simplices, inside, radii, centres, nxt, arc, ring, offset, rings_s, rings_xy, rings_start,
                            convex, touching, tolerance, memo, over_split=OVER_SPLIT):  # type: ignore[no-untyped-def]
    """:func:`corner_piece_state` that keeps each slot's corner test in ``memo`` (rows ``a, b, c, corner``).

    A slot whose triangle has the same vertices, in the same order, as when
    it was tested keeps its answer: the test reads only the vertices, their
    arc positions and the circumcentre, which the vertices fix. The
    incremental rounds (:func:`medialaxis.planar.boundary._refine_kernels.refine_round`)
    so test only the triangles made since the round before.
    """
    edge, at_vertex = sample_edges(arc, ring, offset, rings_s, rings_start)
    corner = np.zeros(len(simplices), np.bool_)
    slots = np.empty(len(simplices), np.int64)
    n_tested = 0
    for t in range(len(simplices)):
        a, b, c = simplices[t, 0], simplices[t, 1], simplices[t, 2]
        if memo[t, 0] == a and memo[t, 1] == b and memo[t, 2] == c:
            corner[t] = memo[t, 3] == 1
            continue
        if inside[t] and min(a, b, c) >= offset:
            slots[n_tested] = t
            n_tested += 1
        memo[t, 0], memo[t, 1], memo[t, 2], memo[t, 3] = a, b, c, 0
    tested = corner_triangles(simplices, slots[:n_tested], centres, edge, at_vertex, ring, rings_xy, rings_start,
                              convex, tolerance, over_split)
    for j in range(n_tested):
        corner[slots[j]] = tested[j]
        memo[slots[j], 3] = 1 if tested[j] else 0
    counted = inside & ~whole_circles(corner, inside, centres, radii)
    conforming, radius = piece_state(simplices, counted, radii, nxt)
    pinched_radius(simplices, counted, radii, nxt, radius, ring, edge, at_vertex, rings_start, touching)
    _mirror_pairs(conforming, radius, nxt, arc, ring, offset, edge, at_vertex, rings_s, rings_start, convex)
    return conforming, radius


@njit(cache=True, nogil=True, inline="always")
def _mirror_pairs(conforming, radius, nxt, arc, ring, offset, edge, at_vertex, rings_s, rings_start, convex):  # type: ignore[no-untyped-def]
    """Give the mirrored pieces at each convex vertex the smaller radius and the conformity of both."""
    n = len(nxt)
    prev = np.full(n, -1, np.int64)
    for i in range(offset, n):
        prev[nxt[i]] = i
    changed = True
    while changed:  # a piece may be mirrored at both its edge's ends: until every pair agrees
        changed = _mirror_pass(conforming, radius, nxt, prev, arc, ring, offset, edge, at_vertex, rings_s,
                               rings_start, convex)


@njit(cache=True, nogil=True, inline="always")
def _mirror_pass(conforming, radius, nxt, prev, arc, ring, offset, edge, at_vertex, rings_s, rings_start, convex):  # type: ignore[no-untyped-def]
    """One pass of :func:`_mirror_pairs` over the convex vertices; whether it changed anything."""
    n = len(nxt)
    changed = False
    for i in range(offset, n):
        lo = rings_start[ring[i]]
        m = rings_start[ring[i] + 1] - lo - 1
        j = edge[i]
        if not at_vertex[i] or not convex[lo + j]:
            continue
        length = rings_s[lo + m]
        reach = min(rings_s[lo + j + 1] - rings_s[lo + j],  # the shorter of the two edges
                    rings_s[lo + j] - rings_s[lo + j - 1] if j > 0 else length - rings_s[lo + m - 1])
        p, q = i, i
        while True:
            pn, qn = nxt[p], prev[q]
            if pn == qn or pn == i or qn == i or pn == q:
                break
            out = (arc[pn] - arc[i]) % length
            back = (arc[i] - arc[qn]) % length
            if abs(out - back) > 1e-9 * length or out > reach * (1.0 + 1e-9):
                break
            low = min(radius[p], radius[qn])
            both = conforming[p] and conforming[qn]
            changed = changed or radius[p] != radius[qn] or conforming[p] != conforming[qn]
            radius[p], radius[qn] = low, low
            conforming[p], conforming[qn] = both, both
            p, q = pn, qn
    return changed


@njit(cache=True, nogil=True, inline="always")
def _gap(a, x, length):  # type: ignore[no-untyped-def]
    """Distance along the ring from arc position ``x`` to the nearest of the sorted positions ``a``."""
    k = np.searchsorted(a, x)
    after = a[k] - x if k < len(a) else a[0] + length - x
    before = x - a[k - 1] if k > 0 else x - (a[-1] - length)
    return min(after, before)


@njit(cache=True, nogil=True)
def corner_twins(a, s, xy, tolerance, min_length, ratio):  # type: ignore[no-untyped-def]
    """The twins :func:`medialaxis.planar.boundary.corners.mirrored_corner_arcs` adds on one ring, unsorted.

    ``a`` the ring's sorted arc positions (every vertex among them), ``s`` and
    ``xy`` its cumulative arc length and vertices, closed.
    """
    m = len(s) - 1
    length = s[m]
    eps = 1e-9 * length
    twins = np.empty(len(a) + 64 * m)
    count = 0
    for j in range(m):
        p = (j - 1) % m
        ix, iy = xy[j, 0] - xy[p, 0], xy[j, 1] - xy[p, 1]
        ox, oy = xy[j + 1, 0] - xy[j, 0], xy[j + 1, 1] - xy[j, 1]
        if ix * oy - iy * ox >= 0.0:
            continue  # not convex
        l_out = s[j + 1] - s[j]
        l_in = s[j] - s[j - 1] if j > 0 else length - s[m - 1]
        cos_half = np.sqrt(min(max(0.5 * (1.0 - (ix * ox + iy * oy) / max(l_in * l_out, 1e-300)), 0.0), 1.0))
        k = np.searchsorted(a, s[j] + eps)  # the first sample after the vertex, the last before it
        h_out = min((a[k] if k < len(a) else a[0] + length) - s[j], l_out)
        k_in = np.searchsorted(a, s[j] - eps) - 1
        h_in = min(s[j] - (a[k_in] if k_in >= 0 else a[-1] - length), l_in)
        h = min(h_out, h_in)
        radius = h / (2.0 * max(cos_half, 1e-300))
        target = max(min(ratio * radius, np.sqrt(16.0 * radius * tolerance)), min_length)
        if not (h > target and h > 2.0 * min_length):
            continue
        sin_half = max(np.sqrt(1.0 - cos_half * cos_half), 1e-300)
        deepest = REACH * min_length / sin_half  # where the pair is lam = 8 * min_length apart (by default)
        d = h
        while count + 6 <= len(twins):  # mirrored pairs in from the nearest samples, the last two about lam apart
            d = d / PROGRESSION if d / PROGRESSION > 1.5 * deepest else (deepest if d > deepest else deepest / PROGRESSION)
            if d < h:
                twins[count] = (s[j] + d) % length
                twins[count + 1] = (s[j] - d) % length
                count += 2
            if d < deepest:
                break
        short, sign = (l_out, -1.0) if l_out <= l_in else (l_in, 1.0)
        reach = max(l_out, l_in) - min_length
        step = 1 if sign < 0 else -1  # walk the shorter edge away from the vertex
        i = k if sign < 0 else k_in
        for _ in range(len(a) + 1):
            q = a[i % len(a)]
            d = (q - s[j]) % length if sign < 0 else (s[j] - q) % length
            if d > short - eps:
                d = short
            if d < reach:
                x = (s[j] + sign * d) % length
                if _gap(a, x, length) > min_length and x < length:
                    twins[count] = x
                    count += 1
            if d >= short:
                break
            i += step
    return twins[:count]


@njit(cache=True, nogil=True)
def closed_rings(vertices, open_start):  # type: ignore[no-untyped-def]
    """``(xy, s, start, convex)`` of :class:`medialaxis.planar.boundary.corners.RingArrays` from the rings' vertices.

    ``vertices`` holds the rings one after another, not closed, ring ``r`` at
    ``open_start[r]:open_start[r + 1]``. Each ring is closed (its first
    vertex repeated), ``s`` is its cumulative arc length as
    :attr:`medialaxis.planar.boundary.sampling.Rings.arc_lengths` computes it (the
    same numbers, tested), and a vertex is convex where the region, on the
    rings' right, turns right.
    """
    n_rings = len(open_start) - 1
    start = np.empty(n_rings + 1, np.int64)
    start[0] = 0
    for r in range(n_rings):
        start[r + 1] = start[r] + open_start[r + 1] - open_start[r] + 1
    xy = np.empty((start[-1], 2))
    s = np.empty(start[-1])
    convex = np.empty(start[-1], np.bool_)
    for r in range(n_rings):
        lo, m = start[r], open_start[r + 1] - open_start[r]
        for i in range(m):
            xy[lo + i, 0], xy[lo + i, 1] = vertices[open_start[r] + i, 0], vertices[open_start[r] + i, 1]
        xy[lo + m, 0], xy[lo + m, 1] = xy[lo, 0], xy[lo, 1]
        s[lo] = 0.0
        for i in range(m):
            dx, dy = xy[lo + i + 1, 0] - xy[lo + i, 0], xy[lo + i + 1, 1] - xy[lo + i, 1]
            s[lo + i + 1] = s[lo + i] + np.sqrt(dx * dx + dy * dy)
        for i in range(m + 1):
            before = lo + m - 1 if i == 0 else lo + i - 1  # the vertex before, not the repeat
            after = lo + 1 if i == m else lo + i + 1
            ix, iy = xy[lo + i, 0] - xy[before, 0], xy[lo + i, 1] - xy[before, 1]
            ox, oy = xy[after, 0] - xy[lo + i, 0], xy[after, 1] - xy[lo + i, 1]
            convex[lo + i] = ix * oy - iy * ox < 0
    return xy, s, start, convex
