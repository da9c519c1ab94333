"""First occurrences of integer rows, by hashing (``np.unique(rows, axis=0, return_index=True)`` without the sort),
and a stable argsort of non-negative integer keys by radix.

``np.unique`` with ``axis=0`` sorts the rows as structured records: 40-80 ms
for 100k rows of three int64, against about 3 ms here. The pipelines drop
duplicate samples, grid cells and collapsed triangles this way at every step.

:func:`radix_argsort` is ``np.argsort(keys, kind="stable")`` for keys ``>= 0``
(of int64, or of non-negative float64 through their bits, whose order is the
numbers' order): the Voronoi route sorts two million tetrahedra by their
Morton codes and 1.5 million facets by length, 0.21 and 0.27 s each in NumPy
(one thread).
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit

__all__ = ["first_of_rows", "radix_argsort"]

#: Bits per pass of :func:`radix_argsort`.
_DIGIT = 16


@njit(cache=True, nogil=True)
def first_of_rows(rows):  # type: ignore[no-untyped-def]
    """Indices (ascending) of the rows of ``rows`` (n, k) int64 seen first: one per distinct row."""
    n, k = rows.shape
    hb = 4
    while (1 << hb) < 2 * n:
        hb += 1
    mask = (1 << hb) - 1
    table = np.full(1 << hb, -1, np.int64)
    keep = np.empty(n, np.int64)
    count = 0
    for i in range(n):
        h = np.int64(0)
        for c in range(k):
            h = (h ^ rows[i, c]) * -7046029254386353131
            h ^= h >> 29
        h &= mask
        while True:
            j = table[h]
            if j < 0:
                table[h] = i
                keep[count] = i
                count += 1
                break
            same = True
            for c in range(k):
                if rows[j, c] != rows[i, c]:
                    same = False
                    break
            if same:
                break
            h = (h + 1) & mask
    return keep[:count]


@njit(cache=True, nogil=True)
def radix_argsort(keys):  # type: ignore[no-untyped-def]
    """``np.argsort(keys, kind="stable")`` of non-negative int64 ``keys`` (least significant digit first).

    A pass whose digit is the same for every key is skipped.

    >>> import numpy as np
    >>> radix_argsort(np.array([5, 3, 5, 0, 3], np.int64))
    array([3, 1, 4, 0, 2])
    """
    n = keys.shape[0]
    size = 1 << _DIGIT
    top = np.int64(0)
    for i in range(n):
        top |= keys[i]
    order = np.arange(n)
    key = keys.copy()
    other_order = np.empty(n, np.int64)
    other_key = np.empty(n, np.int64)
    count = np.empty(size + 1, np.int64)
    shift = 0
    while shift < 63 and (top >> shift) > 0:  # a shift of 64 or more is undefined
        count[:] = 0
        for i in range(n):
            count[((key[i] >> shift) & (size - 1)) + 1] += 1
        if count.max() < n:
            for d in range(size):
                count[d + 1] += count[d]
            for i in range(n):
                d = (key[i] >> shift) & (size - 1)
                j = count[d]
                count[d] = j + 1
                other_order[j] = order[i]
                other_key[j] = key[i]
            order, other_order = other_order, order
            key, other_key = other_key, key
        shift += _DIGIT
    return order
