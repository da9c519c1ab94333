"""Compiled: corner triangles whose circle another inside triangle shares count as that one does.

Co-circular samples (a regular sample of a strip, a square arm's end)
have several Delaunay triangulations; :func:`whole_circles` decides for the
whole circle (see :func:`_whole_circles`, its reference), for
:func:`medialaxis.planar.boundary._corner_kernels.corner_piece_state`.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit

__all__ = ["whole_circles"]


@njit(cache=True, nogil=True)
def _whole_circles(corner, inside, centres, radii):  # type: ignore[no-untyped-def]
    """``corner`` where every inside triangle sharing the circle is a corner triangle too.

    Co-circular samples (a regular sample of a strip, a square arm's end)
    have several Delaunay triangulations, and which one a triangulation picks
    turns on rounding: on a shape and its turned copy the same circle can be
    split into a corner triangle and a triangle that reaches another edge, or
    the other way. Deciding for the whole circle keeps the sampling, and so
    the axis, the same under rotations, mirrors and where a ring starts.
    """
    rows = np.flatnonzero(inside)
    order = rows[np.argsort(centres[rows, 0])]
    out = corner.copy()
    for i in range(len(order)):
        t = order[i]
        eps = 1e-9 * (radii[t] + abs(centres[t, 0]) + abs(centres[t, 1]))
        for j in range(i + 1, len(order)):
            u = order[j]
            if centres[u, 0] - centres[t, 0] > eps:
                break
            if (abs(centres[u, 1] - centres[t, 1]) <= eps and abs(radii[u] - radii[t]) <= eps
                    and not (corner[t] and corner[u])):
                out[t] = False
                out[u] = False
    return out


@njit(cache=True, nogil=True, inline="always")
def whole_circles(corner, inside, centres, radii):  # type: ignore[no-untyped-def]
    """:func:`_whole_circles` (its reference) without sorting every inside triangle.

    Only a corner triangle can change, and only by an inside triangle that is
    not one whose circle the sort would compare with it: their centres' ``x``
    lie within the ``eps`` of the one first in ``x``, which is below twice
    the corner's own (the two circles agree to ``eps``). One pass over the
    inside triangles finds, among the few corner triangles sorted by ``x``,
    those near each; each pair is then decided as the sorted scan decides
    it. Equal ``x`` in such a pair, whose order the sort would pick and that
    the order would decide, or a centre that is not finite: the sorted scan
    itself.
    """
    rows = np.flatnonzero(inside)
    out = corner.copy()
    n_corner = 0
    for t in rows:
        n_corner += corner[t]
    if len(rows) < 2 or n_corner == 0:
        return out  # the sorted scan changes corner triangles only
    corners = np.empty(n_corner, np.int64)
    j = 0
    reach = 0.0
    for t in rows:
        if corner[t]:
            corners[j] = t
            j += 1
            reach = max(reach, 2e-9 * (radii[t] + abs(centres[t, 0]) + abs(centres[t, 1])))
    corners = corners[np.argsort(centres[corners, 0])]
    xs = centres[corners, 0]
    for m in range(n_corner):
        if not np.isfinite(xs[m]):
            return _whole_circles(corner, inside, centres, radii)  # as the pass below would on meeting it
    scale = n_corner / (xs[-1] - xs[0]) if xs[-1] > xs[0] else 0.0
    scale = scale if np.isfinite(scale) else 0.0
    starts = _bucket_starts(xs, scale)
    for u in rows:
        if not (np.isfinite(centres[u, 0]) and np.isfinite(centres[u, 1]) and np.isfinite(radii[u])):
            return _whole_circles(corner, inside, centres, radii)
        if corner[u]:
            continue
        low = centres[u, 0] - reach
        if low > xs[-1] or centres[u, 0] + reach < xs[0]:
            continue
        begin = starts[_bucket(low, xs[0], scale, n_corner)]
        while xs[begin] < low:  # np.searchsorted(xs, low): the bucket's corners below low skipped
            begin += 1
        for m in range(begin, n_corner):
            c = corners[m]
            if centres[c, 0] > centres[u, 0] + reach:
                break
            first = _same_circle(c, u, centres, radii) if centres[c, 0] < centres[u, 0] else \
                _same_circle(u, c, centres, radii)
            if centres[u, 0] == centres[c, 0] and first != _same_circle(c, u, centres, radii):
                return _whole_circles(corner, inside, centres, radii)  # the sort's order decides
            if first:
                out[c] = False
    return out


@njit(cache=True, nogil=True, inline="always")
def _bucket(x, low, scale, n):  # type: ignore[no-untyped-def]
    """The bucket of ``x`` among ``n`` of width ``1 / scale`` from ``low``, clipped: never lower for a larger ``x``."""
    return int(min(max((x - low) * scale, 0.0), n - 1.0))


@njit(cache=True, nogil=True, inline="always")
def _bucket_starts(xs, scale):  # type: ignore[no-untyped-def]
    """For each bucket of :func:`_bucket` over the sorted finite ``xs``, the first ``xs`` in it or a later one: every
    one before lies below each ``x`` of that bucket (the bucket never decreases with ``x``), so a search for ``x``
    starts there instead of bisecting."""
    n = len(xs)
    first = np.full(n + 1, n, np.int64)
    for m in range(n - 1, -1, -1):
        first[_bucket(xs[m], xs[0], scale, n)] = m
    for b in range(n - 1, -1, -1):
        first[b] = min(first[b], first[b + 1])
    return first


@njit(cache=True, nogil=True, inline="always")
def _same_circle(t, u, centres, radii):  # type: ignore[no-untyped-def]
    """Whether the sorted scan of :func:`_whole_circles` finds ``u``'s circle ``t``'s, ``t`` coming first."""
    eps = 1e-9 * (radii[t] + abs(centres[t, 0]) + abs(centres[t, 1]))
    return (centres[u, 0] - centres[t, 0] <= eps and abs(centres[u, 1] - centres[t, 1]) <= eps
            and abs(radii[u] - radii[t]) <= eps)
