"""Faces cut along where other faces meet them, in exact rational arithmetic.

Every point of the cut is a rational point: a vertex, where an edge meets
another face's plane, where an edge crosses a coplanar face's edge, where
three faces meet. Held exactly, as integers ``(X, Y, Z, W)`` (``W > 0``,
divided by their common divisor) over one power of two, a point is the same
whichever pair of faces finds it and in each face it lies on: its
coordinates are its identity. The pieces of the faces then close up (no
T-junction where curves of the cut meet, no point found twice a hair apart)
without welding by tolerance. Every predicate is the sign of an integer
determinant; each face is cut by inserting its points into its triangle and
recovering its constraint segments by edge flips (Sloan, "A fast algorithm
for generating constrained Delaunay triangulations", Computers & Structures
47(3), 441-450, 1993, doi:10.1016/0045-7949(93)90239-A), then flipped towards
Delaunay where the flip keeps the pieces convex.

The arrangement this builds is that of Zhou, Grinspun, Zorin, Jacobson,
"Mesh arrangements for solid geometry", ACM Transactions on Graphics 35(4),
39:1-39:15, 2016 (doi:10.1145/2897824.2925901), who cut with exact
arithmetic (CGAL's) for the same reason.
"""

from __future__ import annotations

from collections import defaultdict, deque
from collections.abc import Callable
from fractions import Fraction
from math import gcd

import numpy as np

__all__ = ["ExactCut"]

Point = tuple[int, int, int, int]

#: Delaunay flips per face, at most this many times its points (the flips only improve shapes).
FLIPS_PER_POINT = 8


def _sub(a: Point, b: Point) -> tuple[int, int, int]:
    return a[0] - b[0], a[1] - b[1], a[2] - b[2]


def _cross(u: tuple[int, ...], v: tuple[int, ...]) -> tuple[int, int, int]:
    return u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]


def _dot(u: tuple[int, ...], v: tuple[int, ...]) -> int:
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]


def _canon(x: int, y: int, z: int, w: int) -> Point:
    if w < 0:
        x, y, z, w = -x, -y, -z, -w
    g = gcd(x, y, z, w)
    return x // g, y // g, z // g, w // g


def _orient2(p: tuple[int, int, int], q: tuple[int, int, int], r: tuple[int, int, int]) -> int:
    """Sign of the orientation of three homogeneous 2D points ``(x, y, w)``, ``w > 0``."""
    d = p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) + p[2] * (q[0] * r[1] - q[1] * r[0])
    return (d > 0) - (d < 0)


class ExactCut:
    """Points, constraint segments and edge points of the cut of some faces of a mesh.

    ``vertices`` are floats; the vertices of ``faces`` used are taken
    exactly, as integers over one common power of two. Point ids below
    ``len(vertices)`` are the mesh's vertices; new points follow.
    """

    def __init__(self, vertices: np.ndarray, faces: np.ndarray, used: np.ndarray) -> None:
        self.faces, self.vertices = faces, vertices
        exponent = np.frexp(vertices[vertices != 0])[1]
        self.den = 2 ** max(0, 53 - int(exponent.min())) if exponent.size else 1  # every coordinate times it: an integer
        self.points = _Points(self._vertex)
        self.ids: dict[Point, int] = {}
        for v in sorted((int(v) for v in used), reverse=True):  # coincident vertices: the lowest id
            self.ids[self.points[v]] = v
        self.next_id = len(vertices)
        self.segments: dict[int, set[tuple[int, int]]] = defaultdict(set)
        self.on_edge: dict[tuple[int, int], set[int]] = defaultdict(set)
        self.covered: dict[int, list[int]] = defaultdict(list)
        self.coplanar: set[int] = set()  # faces overlapping a coplanar face
        self._normal: dict[int, tuple[int, int, int]] = {}

    # -- points ------------------------------------------------------------

    def _vertex(self, v: int) -> Point:
        (x, a), (y, b), (z, c) = (c.as_integer_ratio() for c in self.vertices[v].tolist())
        return x * (self.den // a), y * (self.den // b), z * (self.den // c), 1

    def point_id(self, p: Point) -> int:
        p = _canon(*p)
        pid = self.ids.get(p)
        if pid is None:
            pid = self.ids[p] = self.next_id
            self.points[pid] = p
            self.next_id += 1
        return pid

    def coordinates(self, pid: int) -> np.ndarray:
        """The point as floats (correctly rounded)."""
        x, y, z, w = self.points[pid]
        return np.array([x / (w * self.den), y / (w * self.den), z / (w * self.den)])

    def normal(self, f: int) -> tuple[int, int, int]:
        n = self._normal.get(f)
        if n is None:
            a, b, c = (self.points[int(v)] for v in self.faces[f])
            n = self._normal[f] = _cross(_sub(b, a), _sub(c, a))
        return n

    def _plane_value(self, f: int, p: Point) -> int:
        """Where vertex ``p`` lies against the plane of face ``f``: its normal times ``p``'s offset (exact)."""
        return _dot(self.normal(f), _sub(p, self.points[int(self.faces[f][0])]))

    def _register(self, pid: int, f: int) -> None:
        """Note point ``pid`` (in face ``f``'s closed triangle) on the edge of ``f`` it lies inside, if any."""
        p = self.points[pid]
        corners = [int(v) for v in self.faces[f]]
        if pid in corners:
            return
        for k in range(3):
            u, v = corners[k], corners[(k + 1) % 3]
            a, b = self.points[u], self.points[v]
            d = _sub(b, a)
            rel = (p[0] - a[0] * p[3], p[1] - a[1] * p[3], p[2] - a[2] * p[3])
            if _cross(d, rel) == (0, 0, 0) and 0 < _dot(d, rel) < p[3] * _dot(d, d):
                self.on_edge[(min(u, v), max(u, v))].add(pid)
                return

    def _segment(self, p: int, q: int, into: tuple[int, ...], on: tuple[int, ...]) -> None:
        if p == q:
            return
        for f in on:
            self._register(p, f)
            self._register(q, f)
        for f in into:
            self.segments[f].add((min(p, q), max(p, q)))

    # -- pairs of faces ------------------------------------------------------

    def cut_pair(self, i: int, j: int) -> None:
        """Record where faces ``i`` and ``j`` meet: a segment, or for coplanar faces each one's edges within the other."""
        ni, nj = self.normal(i), self.normal(j)
        if ni == (0, 0, 0) or nj == (0, 0, 0):
            return  # a face of zero area: its neighbours' cuts end on its edges
        ti = [self.points[int(v)] for v in self.faces[i]]
        tj = [self.points[int(v)] for v in self.faces[j]]
        vi = [self._plane_value(j, p) for p in ti]
        vj = [self._plane_value(i, p) for p in tj]
        if vi == [0, 0, 0]:
            self._cut_coplanar(i, j)
            return
        line = _cross(ni, nj)
        axis = max(range(3), key=lambda k: abs(line[k]))

        def along(p: Point) -> Fraction:
            return Fraction(p[axis], p[3])

        ends = []
        for t, v in ((ti, vi), (tj, vj)):
            section = _section(t, v)
            if not section:
                return
            ends.append(sorted(section, key=along))
        lo = max(ends[0][0], ends[1][0], key=along)
        hi = min(ends[0][-1], ends[1][-1], key=along)
        if along(lo) < along(hi):
            self._segment(self.point_id(lo), self.point_id(hi), (i, j), (i, j))

    def _cut_coplanar(self, i: int, j: int) -> None:
        """Coplanar faces: each one's edges within the other as its segments, when they overlap."""
        drop = max(range(3), key=lambda k: abs(self.normal(i)[k]))
        pieces, overlap = [], False
        for f, g in ((i, j), (j, i)):  # the edges of g within f
            corners = [_flat(self.points[int(v)], drop) for v in self.faces[f]]
            if _orient2(*corners) < 0:
                corners.reverse()
            for k in range(3):
                a, b = self.points[int(self.faces[g][k])], self.points[int(self.faces[g][(k + 1) % 3])]
                lo, hi = Fraction(0), Fraction(1)
                for e in range(3):  # clip a + t (b - a) to each edge's inner side (Cyrus-Beck)
                    u, v = corners[e], corners[(e + 1) % 3]
                    fa, fb = _det_h(u, v, _flat(a, drop)), _det_h(u, v, _flat(b, drop))
                    if fa < 0 and fb < 0:
                        lo, hi = Fraction(1), Fraction(0)
                    elif fa < 0:
                        lo = max(lo, Fraction(fa, fa - fb))
                    elif fb < 0:
                        hi = min(hi, Fraction(fa, fa - fb))
                if lo < hi:
                    pieces.append((f, _along(a, b, lo), _along(a, b, hi)))
                    middle = _flat(_along(a, b, (lo + hi) / 2), drop)
                    overlap |= all(_orient2(corners[e], corners[(e + 1) % 3], middle) > 0 for e in range(3))
            overlap |= any(all(_orient2(corners[e], corners[(e + 1) % 3], _flat(self.points[int(c)], drop)) > 0
                               for e in range(3)) for c in self.faces[g])
        if not overlap:
            return  # they touch only
        self.coplanar.update((i, j))
        for f, p, q in pieces:
            self._segment(self.point_id(p), self.point_id(q), (f,), (i, j))
        if _dot(self.normal(i), self.normal(j)) > 0:
            self.covered[max(i, j)].append(min(i, j))  # the same surface twice: the lower face's pieces stay

    # -- one face ------------------------------------------------------------

    def triangulate(self, f: int) -> list[tuple[int, int, int]]:
        """Face ``f`` cut along its segments: triangles of point ids, oriented as the face."""
        corners = [int(v) for v in self.faces[f]]
        ring: list[int] = []
        for k in range(3):
            u, v = corners[k], corners[(k + 1) % 3]
            a, d = self.points[u], _sub(self.points[v], self.points[u])
            extra = sorted(self.on_edge.get((min(u, v), max(u, v)), ()), key=lambda p: Fraction(
                _dot(d, _sub(self.points[p], tuple(c * self.points[p][3] for c in a))), self.points[p][3]))
            ring += [u] + extra
        normal = self.normal(f)
        if normal == (0, 0, 0):  # a face of zero area with points on its edges: a fan
            return [(ring[0], ring[k], ring[k + 1]) for k in range(1, len(ring) - 1)]
        drop = max(range(3), key=lambda k: abs(normal[k]))
        xy = {p: _flat(self.points[p], drop) for p in ring}
        for s in self.segments.get(f, ()):
            for p in s:
                xy.setdefault(p, _flat(self.points[p], drop))
        for p in self._node(f, xy, drop):
            xy.setdefault(p, _flat(self.points[p], drop))
        segments = self._noded(f, xy)
        flipped = _orient2(*(xy[c] for c in corners)) < 0
        mesh = _Triangulation(xy, corners[::-1] if flipped else corners)
        for p in xy:
            if p not in corners:
                mesh.insert(p)
        for a, b in segments:
            mesh.enforce(a, b)
        mesh.improve(segments, FLIPS_PER_POINT * len(xy))
        return [t[::-1] if flipped else t for t in mesh.triangles.values()]

    def _node(self, f: int, xy: dict, drop: int) -> list[int]:
        """Points where two of face ``f``'s segments cross (where three faces meet)."""
        segs = sorted(self.segments.get(f, ()))
        found = []
        for k, (a, b) in enumerate(segs):
            for c, d in segs[k + 1:]:
                if len({a, b, c, d}) < 4:
                    continue
                oc, od = _orient2(xy[a], xy[b], xy[c]), _orient2(xy[a], xy[b], xy[d])
                if oc * od >= 0 or _orient2(xy[c], xy[d], xy[a]) * _orient2(xy[c], xy[d], xy[b]) >= 0:
                    continue
                # on the line ab: a combination of a and b that cd's line vanishes at
                sa, sb = _det_h(xy[c], xy[d], xy[a]), _det_h(xy[c], xy[d], xy[b])
                pa, pb = self.points[a], self.points[b]
                found.append(self.point_id(tuple(sa * y - sb * x for x, y in zip(pa, pb))))
        return found

    def _noded(self, f: int, xy: dict) -> set[tuple[int, int]]:
        """Face ``f``'s segments split at every point lying inside them."""
        out = set()
        for a, b in self.segments.get(f, ()):
            axis = max(range(2), key=lambda k: abs(xy[b][k] * xy[a][2] - xy[a][k] * xy[b][2]))

            def key(p: int, axis: int = axis) -> Fraction:
                return Fraction(xy[p][axis], xy[p][2])

            ka, kb = sorted((key(a), key(b)))
            inner = [p for p in xy if p != a and p != b and _orient2(xy[a], xy[b], xy[p]) == 0 and ka < key(p) < kb]
            chain = sorted([a, b, *inner], key=key)
            out.update((min(p, q), max(p, q)) for p, q in zip(chain, chain[1:]))
        return out


class _Points(dict):
    """Exact points by id; the mesh's vertices are read when first asked for."""

    def __init__(self, vertex: Callable[[int], Point]) -> None:
        super().__init__()
        self.vertex = vertex

    def __missing__(self, v: int) -> Point:
        p = self[v] = self.vertex(v)
        return p


class _Triangulation:
    """A triangulation of one face's points (exact orientations), counter-clockwise in the plane."""

    def __init__(self, xy: dict, corners: list[int]) -> None:
        self.xy = xy
        self.triangles: dict[int, tuple[int, int, int]] = {}
        self.edge: dict[tuple[int, int], int] = {}
        self.count = 0
        self._add(*corners)

    def _add(self, a: int, b: int, c: int) -> None:
        self.triangles[self.count] = (a, b, c)
        for e in ((a, b), (b, c), (c, a)):
            self.edge[e] = self.count
        self.count += 1

    def _remove(self, t: int) -> tuple[int, int, int]:
        a, b, c = self.triangles.pop(t)
        for e in ((a, b), (b, c), (c, a)):
            del self.edge[e]
        return a, b, c

    def _o(self, a: int, b: int, c: int) -> int:
        return _orient2(self.xy[a], self.xy[b], self.xy[c])

    def insert(self, p: int) -> None:
        for t, (a, b, c) in list(self.triangles.items()):
            o = (self._o(b, c, p), self._o(c, a, p), self._o(a, b, p))
            if min(o) < 0:
                continue
            if 0 not in o:
                self._remove(t)
                self._add(a, b, p), self._add(b, c, p), self._add(c, a, p)
                return
            k = o.index(0)  # on the edge opposite corner k
            w, u, v = (a, b, c)[k], (a, b, c)[(k + 1) % 3], (a, b, c)[(k + 2) % 3]
            other = self.edge.get((v, u))
            self._remove(t)
            self._add(w, u, p), self._add(w, p, v)
            if other is not None:
                x = next(c for c in self._remove(other) if c not in (u, v))
                self._add(v, p, x), self._add(p, u, x)
            return
        raise AssertionError(f"point {p} lies outside its face")

    def _crosses(self, a: int, b: int, u: int, v: int) -> bool:
        return self._o(a, b, u) * self._o(a, b, v) < 0 and self._o(u, v, a) * self._o(u, v, b) < 0

    def _flip(self, u: int, v: int) -> tuple[int, int]:
        """Flip the edge ``uv`` of triangles ``(u, v, w)`` and ``(v, u, x)`` into ``wx``."""
        w = next(c for c in self._remove(self.edge[(u, v)]) if c not in (u, v))
        x = next(c for c in self._remove(self.edge[(v, u)]) if c not in (u, v))
        self._add(u, x, w), self._add(x, v, w)
        return w, x

    def _convex(self, u: int, v: int) -> tuple[int, int] | None:
        w = next(c for c in self.triangles[self.edge[(u, v)]] if c not in (u, v))
        x = next(c for c in self.triangles[self.edge[(v, u)]] if c not in (u, v))
        return (w, x) if self._o(w, x, u) * self._o(w, x, v) < 0 else None

    def enforce(self, a: int, b: int) -> None:
        """Make the segment ``ab`` (no point inside it, crossing no other segment) an edge (Sloan 1993)."""
        if (a, b) in self.edge or (b, a) in self.edge:
            return
        queue = deque((u, v) for (u, v) in self.edge if u < v and self._crosses(a, b, u, v))
        while queue:
            u, v = queue.popleft()
            if self._convex(u, v) is None:
                queue.append((u, v))
                continue
            w, x = self._flip(u, v)
            if self._crosses(a, b, w, x):
                queue.append((w, x))

    def improve(self, fixed: set[tuple[int, int]], budget: int) -> None:
        """Flip edges that are not segments towards Delaunay (floating-point in-circle test), ``budget`` flips at most."""
        flat = {p: (x / w, y / w) for p, (x, y, w) in self.xy.items()}
        queue = deque((u, v) for (u, v) in self.edge if u < v and (v, u) in self.edge)
        while queue and budget > 0:
            u, v = queue.popleft()
            if (u, v) not in self.edge or (v, u) not in self.edge or (min(u, v), max(u, v)) in fixed:
                continue
            wx = self._convex(u, v)
            if wx is None or not _in_circle(flat[u], flat[v], flat[wx[0]], flat[wx[1]]):
                continue
            w, x = self._flip(u, v)
            budget -= 1
            queue.extend([(u, x), (x, v), (v, w), (w, u)])


def _in_circle(a: tuple, b: tuple, c: tuple, d: tuple) -> bool:
    """Whether ``d`` lies clearly inside the circle through the counter-clockwise ``a, b, c``."""
    rows = [(p[0] - d[0], p[1] - d[1]) for p in (a, b, c)]
    m = [(x, y, x * x + y * y) for x, y in rows]
    det = (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
           + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))
    scale = max(abs(v) for r in m for v in r) ** 2
    return det > 1e-9 * scale


def _flat(p: Point, drop: int) -> tuple[int, int, int]:
    """Homogeneous 2D coordinates of ``p`` with coordinate ``drop`` left out."""
    u, v = [k for k in range(3) if k != drop]
    return p[u], p[v], p[3]


def _det_h(p: tuple[int, int, int], q: tuple[int, int, int], r: tuple[int, int, int]) -> int:
    return p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) + p[2] * (q[0] * r[1] - q[1] * r[0])


def _section(t: list[Point], value: list[int]) -> list[Point]:
    """Where triangle ``t`` (vertices) meets a plane (``value``: each corner's side of it): its corners on it, its edges across it."""
    out = [_canon(*t[k]) for k in range(3) if value[k] == 0]
    for k in range(3):
        m = (k + 1) % 3
        if (value[k] > 0 > value[m]) or (value[k] < 0 < value[m]):
            p, q, sp, sq = t[k], t[m], value[k], value[m]
            out.append(_canon(q[0] * sp - p[0] * sq, q[1] * sp - p[1] * sq, q[2] * sp - p[2] * sq, sp - sq))
    return out


def _along(a: Point, b: Point, t: Fraction) -> Point:
    """``a + t (b - a)`` for vertices ``a, b`` (``w = 1``)."""
    n, d = t.numerator, t.denominator
    return a[0] * (d - n) + b[0] * n, a[1] * (d - n) + b[1] * n, a[2] * (d - n) + b[2] * n, d
