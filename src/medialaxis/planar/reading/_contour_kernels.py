"""Compiled iso-contours of a binary mask: marching squares and ring assembly in one pass.

:func:`mask_contours` gives the same rings, point for point and in the same
order, as ``skimage.measure.find_contours(mask.view(np.uint8), 0.5,
positive_orientation="high")`` (Lorensen and Cline's marching squares, with
the low side fully connected) on a mask with a false border: squares are
visited row by row, each crossing square gives its segments as scikit-image
orders them, and the segments are joined as its ``_assemble_contours`` joins
them (a contour is kept under the number of the first of the two it was
joined from). A point is keyed by the pixel edge it lies on, and placed on
it as scikit-image places it: at ``(0.5 - a) / (b - a)`` between the pixel
values (halfway for 0/1; a bool array whose true bytes are 255, as PIL
gives for mode "1" images, is contoured near its false pixels, as before). :func:`mask_contours_reference` is the scikit-image
route, used by the tests.
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit

__all__ = ["mask_contours", "mask_contours_reference", "contour_rings"]

#: Segments of each square case (ul + 2 ur + 4 ll + 8 lr above the level), as
#: (from, to) pairs of sides 0 top, 1 bottom, 2 left, 3 right; -1 pads.
_CASES = np.array([
    [-1, -1, -1, -1], [0, 2, -1, -1], [3, 0, -1, -1], [3, 2, -1, -1],
    [2, 1, -1, -1], [0, 1, -1, -1], [3, 0, 2, 1], [3, 1, -1, -1],
    [1, 3, -1, -1], [0, 2, 1, 3], [1, 0, -1, -1], [1, 2, -1, -1],
    [2, 3, -1, -1], [0, 3, -1, -1], [2, 0, -1, -1], [-1, -1, -1, -1],
], np.int64)


@njit(cache=True, nogil=True)
def _fraction(start, stop):  # type: ignore[no-untyped-def]
    """Where the level 0.5 lies between pixel values ``start`` and ``stop``, as scikit-image computes it."""
    if start == stop:
        return 0.0
    return (0.5 - start) / (stop - start)


@njit(cache=True, nogil=True)
def mask_contours(mask, cases):  # type: ignore[no-untyped-def]
    """Closed contours of the true pixels of ``mask`` (uint8, 2D, false border), clockwise in (row, col).

    Returns ``(points, offsets)``: ring ``k`` is ``points[offsets[k]:offsets[k + 1]]``
    (first point repeated last), (row, col) floats.
    """
    h, w = mask.shape
    # a point is keyed by its pixel edge: 2 (r w + c) the top edge of pixel (r, c), + 1 its left edge
    starts = np.empty(2 * h * w, np.int32)
    ends = np.empty(2 * h * w, np.int32)
    for i in range(2 * h * w):
        starts[i] = -1
        ends[i] = -1
    n_segments = 0  # a first pass sizes the stores: each segment adds at most two points and one contour
    for r in range(h - 1):
        for c in range(w - 1):
            case = min(mask[r, c], 1) + 2 * min(mask[r, c + 1], 1) + 4 * min(mask[r + 1, c], 1) + 8 * min(mask[r + 1, c + 1], 1)
            n_segments += (case != 0 and case != 15) + (case == 6 or case == 9)
    key = np.empty(2 * n_segments + 2, np.int64)
    nxt = np.empty(2 * n_segments + 2, np.int64)
    first = np.empty(n_segments + 1, np.int64)
    last = np.empty(n_segments + 1, np.int64)
    alive = np.zeros(n_segments + 1, np.bool_)
    n_nodes = 0
    n_contours = 0
    side = np.empty(4, np.int64)
    for r in range(h - 1):
        for c in range(w - 1):
            case = min(mask[r, c], 1) + 2 * min(mask[r, c + 1], 1) + 4 * min(mask[r + 1, c], 1) + 8 * min(mask[r + 1, c + 1], 1)
            if case == 0 or case == 15:
                continue
            side[0] = 2 * (r * w + c)  # top: (r, c + 0.5)
            side[1] = 2 * ((r + 1) * w + c)  # bottom
            side[2] = 2 * (r * w + c) + 1  # left: (r + 0.5, c)
            side[3] = 2 * (r * w + c + 1) + 1  # right
            for s in range(0, 4, 2):
                if cases[case, s] < 0:
                    break
                a = side[cases[case, s]]
                b = side[cases[case, s + 1]]
                tail = np.int64(starts[b])
                head = np.int64(ends[a])
                starts[b] = -1
                ends[a] = -1
                if tail >= 0 and head >= 0:
                    if tail == head:  # close the contour
                        key[n_nodes] = b
                        nxt[n_nodes] = -1
                        nxt[last[head]] = n_nodes
                        last[head] = n_nodes
                        n_nodes += 1
                    elif tail > head:  # append tail to head
                        nxt[last[head]] = first[tail]
                        last[head] = last[tail]
                        alive[tail] = False
                        starts[key[first[head]]] = head
                        ends[key[last[head]]] = head
                    else:  # prepend head to tail
                        nxt[last[head]] = first[tail]
                        first[tail] = first[head]
                        alive[head] = False
                        starts[key[first[tail]]] = tail
                        ends[key[last[tail]]] = tail
                elif tail < 0 and head < 0:  # a new contour
                    key[n_nodes] = a
                    nxt[n_nodes] = n_nodes + 1
                    key[n_nodes + 1] = b
                    nxt[n_nodes + 1] = -1
                    first[n_contours] = n_nodes
                    last[n_contours] = n_nodes + 1
                    alive[n_contours] = True
                    starts[a] = n_contours
                    ends[b] = n_contours
                    n_nodes += 2
                    n_contours += 1
                elif head < 0:  # prepend a to tail
                    key[n_nodes] = a
                    nxt[n_nodes] = first[tail]
                    first[tail] = n_nodes
                    starts[a] = tail
                    n_nodes += 1
                else:  # append b to head
                    key[n_nodes] = b
                    nxt[n_nodes] = -1
                    nxt[last[head]] = n_nodes
                    last[head] = n_nodes
                    ends[b] = head
                    n_nodes += 1
    n_rings = 0
    for k in range(n_contours):
        n_rings += alive[k]
    offsets = np.zeros(n_rings + 1, np.int64)
    points = np.empty((n_nodes, 2))
    m = 0
    j = 0
    for k in range(n_contours):
        if not alive[k]:
            continue
        node = first[k]
        while node >= 0:
            m += 1
            node = nxt[node]
        # reversed, as positive_orientation="high" gives them
        node = first[k]
        i = m - 1
        while node >= 0:
            pixel = key[node] // 2
            r, c = pixel // w, pixel % w
            if key[node] % 2:  # on the left edge of pixel (r, c): from (r, c) down to (r + 1, c)
                points[i, 0] = r + _fraction(float(mask[r, c]), float(mask[r + 1, c]))
                points[i, 1] = c
            else:  # on its top edge: from (r, c) right to (r, c + 1)
                points[i, 0] = r
                points[i, 1] = c + _fraction(float(mask[r, c]), float(mask[r, c + 1]))
            i -= 1
            node = nxt[node]
        j += 1
        offsets[j] = m
    return points[:m], offsets


def contour_rings(mask: np.ndarray) -> list[np.ndarray]:
    """The 0.5 iso-contours of a 2D uint8 (or bool) ``mask`` whose border is 0, as (k, 2) float (row, col) rings."""
    points, offsets = mask_contours(np.ascontiguousarray(mask, dtype=np.uint8), _CASES)
    return [points[offsets[k] : offsets[k + 1]] for k in range(len(offsets) - 1)]


def mask_contours_reference(mask: np.ndarray) -> list[np.ndarray]:
    """scikit-image's rings of the same mask (for the tests)."""
    from skimage.measure import find_contours

    return find_contours(np.ascontiguousarray(mask, dtype=np.uint8), 0.5, positive_orientation="high")
