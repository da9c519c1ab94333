"""When plain Douglas-Peucker gives what the topology-preserving simplification would.

GEOS's topology-preserving simplifier (``shapely.simplify(...,
preserve_topology=True)``) runs the Douglas-Peucker recursion and refuses a
flattening only where the new segment would cross a segment of the input or
of the output, or jump over another ring; it costs ten times plain
Douglas-Peucker on the smoothed contours of a mask. :func:`flattening_is_safe`
checks a plain result against a superset of those refusals: no output segment
meets an input segment outside the section it replaces, nor another output
segment (beyond the shared end of its neighbours), and no vertex of another
ring lies within the tolerance of it. Where every check passes, no flattening
was refused, so both give the same vertices; anything doubtful (a near
touch, a determinant within rounding, a short ring) answers False and the
caller runs the topology-preserving simplifier. :func:`flattening_is_safe_reference`
is the same test in plain Python, used by the tests.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit

__all__ = ["flattening_is_safe", "flattening_is_safe_reference"]

#: Determinants within this fraction of their terms' magnitudes are doubtful.
MARGIN = 1e-9


@njit(cache=True, nogil=True)
def _side(ax, ay, bx, by, px, py):  # type: ignore[no-untyped-def]
    """Sign of the orientation of ``p`` against ``ab``: 1, -1, or 0 when within rounding."""
    u = (bx - ax) * (py - ay)
    v = (by - ay) * (px - ax)
    if abs(u - v) <= MARGIN * (abs(u) + abs(v)) + 1e-300:
        return 0
    return 1 if u > v else -1


@njit(cache=True, nogil=True)
def _may_meet(ax, ay, bx, by, cx, cy, dx, dy):  # type: ignore[no-untyped-def]
    """Whether segments ``ab`` and ``cd`` may meet beyond an exactly shared end (True when unsure)."""
    if max(ax, bx) < min(cx, dx) or max(cx, dx) < min(ax, bx) or max(ay, by) < min(cy, dy) or max(cy, dy) < min(ay, by):
        return False
    shared_a = (ax == cx and ay == cy) or (ax == dx and ay == dy)
    shared_b = (bx == cx and by == cy) or (bx == dx and by == dy)
    if shared_a or shared_b:  # they meet only there unless cd runs back along ab
        if shared_a and shared_b:
            return True
        sx, sy = (ax, ay) if shared_a else (bx, by)  # the shared end, ab's other end, cd's other end
        ox, oy = (bx, by) if shared_a else (ax, ay)
        fx, fy = (dx, dy) if (cx == sx and cy == sy) else (cx, cy)
        if _side(ax, ay, bx, by, fx, fy) != 0:
            return False
        dot = (ox - sx) * (fx - sx) + (oy - sy) * (fy - sy)
        return dot >= -MARGIN * (abs(ox - sx) + abs(oy - sy)) * (abs(fx - sx) + abs(fy - sy))
    s1, s2 = _side(ax, ay, bx, by, cx, cy), _side(ax, ay, bx, by, dx, dy)
    s3, s4 = _side(cx, cy, dx, dy, ax, ay), _side(cx, cy, dx, dy, bx, by)
    if s1 == 0 or s2 == 0 or s3 == 0 or s4 == 0:
        return True
    return s1 != s2 and s3 != s4


@njit(cache=True, nogil=True)
def flattening_is_safe(xy, ring_start, out, kept_start, tolerance):  # type: ignore[no-untyped-def]
    """Whether no flattening of the plain result can have been refused (see the module docstring).

    Input ring ``r`` is ``xy[ring_start[r]:ring_start[r + 1]]`` (not closed),
    its simplified ring ``out[kept_start[r]:kept_start[r + 1]]`` (not
    closed), which must be input vertices in order along the ring (else False).
    """
    if len(ring_start) != len(kept_start):  # a ring collapsed
        return False
    kept = np.empty(len(out), np.int64)
    for r in range(len(ring_start) - 1):
        r0, n = ring_start[r], ring_start[r + 1] - ring_start[r]
        k0, m = kept_start[r], kept_start[r + 1] - kept_start[r]
        if m < 8 or m > n:  # short rings: GEOS keeps a ring's minimum size its own way
            return False
        i = 0
        for s in range(m):
            steps = 0
            while xy[r0 + i, 0] != out[k0 + s, 0] or xy[r0 + i, 1] != out[k0 + s, 1]:
                i = (i + 1) % n
                steps += 1
                if steps > n or (s > 0 and i == kept[k0]):
                    return False
            kept[k0 + s] = i
    reach = tolerance * (1.0 + 1e-6) + 1e-12
    # the input segments filed in a grid of about two per cell, by their boxes
    n_all = len(xy)
    owner = np.empty(n_all, np.int64)  # ring of each input segment (segment e runs from vertex e to the next)
    for r in range(len(ring_start) - 1):
        for e in range(ring_start[r], ring_start[r + 1]):
            owner[e] = r
    x0, y0, x1, y1 = np.inf, np.inf, -np.inf, -np.inf
    for e in range(n_all):
        x0, x1 = min(x0, xy[e, 0]), max(x1, xy[e, 0])
        y0, y1 = min(y0, xy[e, 1]), max(y1, xy[e, 1])
    size = max(x1 - x0, y1 - y0, 1e-300)
    g = max(1, int(np.sqrt(n_all / 2.0)))
    cell = size / g * (1.0 + 1e-9)
    count = np.zeros(g * g + 1, np.int64)
    box = np.empty((n_all, 4), np.int64)
    for e in range(n_all):
        r = owner[e]
        f = ring_start[r] + (e - ring_start[r] + 1) % (ring_start[r + 1] - ring_start[r])
        box[e, 0] = min(int((min(xy[e, 0], xy[f, 0]) - x0) / cell), g - 1)
        box[e, 1] = min(int((max(xy[e, 0], xy[f, 0]) - x0) / cell), g - 1)
        box[e, 2] = min(int((min(xy[e, 1], xy[f, 1]) - y0) / cell), g - 1)
        box[e, 3] = min(int((max(xy[e, 1], xy[f, 1]) - y0) / cell), g - 1)
        for cx in range(box[e, 0], box[e, 1] + 1):
            for cy in range(box[e, 2], box[e, 3] + 1):
                count[cx * g + cy + 1] += 1
    for c in range(g * g):
        count[c + 1] += count[c]
    fill = np.empty(g * g, np.int64)
    for c in range(g * g):
        fill[c] = count[c]
    members = np.empty(count[g * g], np.int64)
    for e in range(n_all):
        for cx in range(box[e, 0], box[e, 1] + 1):
            for cy in range(box[e, 2], box[e, 3] + 1):
                members[fill[cx * g + cy]] = e
                fill[cx * g + cy] += 1
    stamp = np.full(n_all, -1, np.int64)
    for r in range(len(ring_start) - 1):
        r0, n = ring_start[r], ring_start[r + 1] - ring_start[r]
        k0, m = kept_start[r], kept_start[r + 1] - kept_start[r]
        for s in range(m):
            i, j = kept[k0 + s], kept[k0 + (s + 1) % m]
            ax, ay, bx, by = xy[r0 + i, 0], xy[r0 + i, 1], xy[r0 + j, 0], xy[r0 + j, 1]
            length2 = (bx - ax) ** 2 + (by - ay) ** 2
            lo_x = max(int((min(ax, bx) - reach - x0) / cell), 0)
            hi_x = min(int((max(ax, bx) + reach - x0) / cell), g - 1)
            lo_y = max(int((min(ay, by) - reach - y0) / cell), 0)
            hi_y = min(int((max(ay, by) + reach - y0) / cell), g - 1)
            for cx in range(lo_x, hi_x + 1):  # input segments outside the section i..j, near the new segment
                for cy in range(lo_y, hi_y + 1):
                    for mm in range(count[cx * g + cy], count[cx * g + cy + 1]):
                        e = members[mm]
                        if stamp[e] == k0 + s:
                            continue
                        stamp[e] = k0 + s
                        q = owner[e]
                        if q == r and (e - r0 - i) % n < (j - i) % n:
                            continue
                        q0, nq = ring_start[q], ring_start[q + 1] - ring_start[q]
                        f = q0 + (e - q0 + 1) % nq
                        if _may_meet(ax, ay, bx, by, xy[e, 0], xy[e, 1], xy[f, 0], xy[f, 1]):
                            return False
                        if q != r:  # a vertex of another ring near the new segment
                            for v in (e, f):
                                px, py = xy[v, 0] - ax, xy[v, 1] - ay
                                t = min(max((px * (bx - ax) + py * (by - ay)) / max(length2, 1e-300), 0.0), 1.0)
                                if (px - t * (bx - ax)) ** 2 + (py - t * (by - ay)) ** 2 <= reach * reach:
                                    return False
            for q in range(len(kept_start) - 1):  # the other output segments
                for t2 in range(kept_start[q], kept_start[q + 1]):
                    if q == r and t2 == k0 + s:
                        continue
                    q0, mq = ring_start[q], kept_start[q + 1] - kept_start[q]
                    c = q0 + kept[t2]
                    d = q0 + kept[kept_start[q] + (t2 - kept_start[q] + 1) % mq]
                    if _may_meet(ax, ay, bx, by, xy[c, 0], xy[c, 1], xy[d, 0], xy[d, 1]):
                        return False
    return True


def flattening_is_safe_reference(
    xy: np.ndarray, ring_start: np.ndarray, out: np.ndarray, kept_start: np.ndarray, tolerance: float
) -> bool:
    """:func:`flattening_is_safe` run by the Python interpreter (for the tests)."""
    return bool(flattening_is_safe.py_func(xy, ring_start, out, kept_start, tolerance))
