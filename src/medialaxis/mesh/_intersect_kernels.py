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

__all__ = ["first_crossing", "first_crossing_reference", "segment_crosses_triangle"]


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


@njit(cache=True, nogil=True, parallel=True)
def first_crossing(triangles: np.ndarray, faces: np.ndarray, pairs: np.ndarray, tol: float) -> int:
    """Index of the first pair ``(i, j)`` of ``pairs`` whose triangles share no vertex and cross, or -1.

    Pairs whose bounding boxes are apart are skipped at once; the others
    are tested on all cores.
    """
    hit = np.zeros(len(pairs), np.bool_)
    for k in prange(len(pairs)):
        i, j = pairs[k, 0], pairs[k, 1]
        if _boxes_apart(triangles[i], triangles[j]):
            continue
        share = False
        for a in range(3):
            for b in range(3):
                if faces[i, a] == faces[j, b]:
                    share = True
        if not share and _crosses(triangles[i], triangles[j], tol):
            hit[k] = True
    for k in range(len(pairs)):
        if hit[k]:
            return k
    return -1


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
        if set(faces[i].tolist()) & set(faces[j].tolist()):
            continue
        t, u = triangles[i], triangles[j]
        for e in range(3):
            if seg(t[e], t[(e + 1) % 3], *u) or seg(u[e], u[(e + 1) % 3], *t):
                return k
    return -1
