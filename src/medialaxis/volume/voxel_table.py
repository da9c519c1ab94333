"""A hash table from voxel indices to rows: the grid of a sparse voxel set.

The medial voxels of a thin-plate part are a thin sheet in a large box: a
dense ``(Z, Y, X)`` int32 grid of their rows costs 4 bytes per voxel of the
box (4 GiB for a 1024^3 scan, and the polygonization needs three such grids),
while the sheet holds a few voxels per thousand. :class:`VoxelTable` stores
only the voxels (open addressing with linear probing, at most half full), and
the compiled kernels look neighbours up in it as they would in the grid.
Positions outside ``shape`` are absent.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from medialaxis._jit import njit

__all__ = ["VoxelTable", "voxel_table", "table_find", "table_lookup"]


class VoxelTable(NamedTuple):
    """Open-addressing table of voxel positions.

    Attributes
    ----------
    keys : (c,) int64 ndarray
        Linear index ``(z * Y + y) * X + x`` of the voxel in each slot, -1 when empty.
    rows : (c,) int64 ndarray
        Row of the voxel in each slot.
    shape : (3,) int64 ndarray
        The grid ``(Z, Y, X)``.
    """

    keys: np.ndarray
    rows: np.ndarray
    shape: np.ndarray


#: 2^64 / golden ratio (as a signed 64-bit integer): Fibonacci hashing.
_GOLDEN = np.int64(-7046029254386353131)


@njit(cache=True, nogil=True)
def _slot(key: int, mask: int) -> int:  # pragma: no cover - compiled
    h = key * _GOLDEN
    return (h ^ (h >> 29)) & mask


@njit(cache=True, nogil=True)
def _build(voxels: np.ndarray, shape: np.ndarray, capacity: int) -> tuple[np.ndarray, np.ndarray]:  # pragma: no cover
    keys = np.full(capacity, -1, np.int64)
    rows = np.zeros(capacity, np.int64)
    mask = capacity - 1
    Y, X = shape[1], shape[2]
    for i in range(voxels.shape[0]):
        key = (voxels[i, 0] * Y + voxels[i, 1]) * X + voxels[i, 2]
        s = _slot(key, mask)
        while keys[s] != -1 and keys[s] != key:
            s = (s + 1) & mask
        if keys[s] == -1:  # the first of repeated voxels keeps its row
            keys[s] = key
            rows[s] = i
    return keys, rows


@njit(cache=True, nogil=True)
def table_find(keys: np.ndarray, rows: np.ndarray, shape: np.ndarray, z: int, y: int, x: int) -> int:  # pragma: no cover
    """Row of voxel ``(z, y, x)``, or -1 (absent or outside the grid)."""
    if z < 0 or y < 0 or x < 0 or z >= shape[0] or y >= shape[1] or x >= shape[2]:
        return -1
    key = (z * shape[1] + y) * shape[2] + x
    mask = keys.shape[0] - 1
    s = _slot(key, mask)
    while keys[s] != -1:
        if keys[s] == key:
            return rows[s]
        s = (s + 1) & mask
    return -1


@njit(cache=True, nogil=True)
def _lookup(keys: np.ndarray, rows: np.ndarray, shape: np.ndarray, points: np.ndarray) -> np.ndarray:  # pragma: no cover
    out = np.empty(points.shape[0], np.int64)
    for i in range(points.shape[0]):
        out[i] = table_find(keys, rows, shape, points[i, 0], points[i, 1], points[i, 2])
    return out


def voxel_table(voxels: np.ndarray, shape: tuple[int, ...] | np.ndarray) -> VoxelTable:
    """The table of ``voxels`` ((n, 3) indices inside ``shape``); row ``i`` is ``voxels[i]``.

    Examples
    --------
    >>> import numpy as np
    >>> t = voxel_table(np.array([[1, 2, 3], [4, 5, 6]]), (8, 8, 8))
    >>> table_lookup(t, np.array([[4, 5, 6], [0, 0, 0], [9, 9, 9]])).tolist()
    [1, -1, -1]
    """
    voxels = np.ascontiguousarray(voxels, np.int64).reshape(-1, 3)
    shape_arr = np.asarray(shape, np.int64).reshape(3)
    capacity = 16
    while capacity < 2 * len(voxels):
        capacity *= 2
    keys, rows = _build(voxels, shape_arr, capacity)
    return VoxelTable(keys, rows, shape_arr)


def table_lookup(table: VoxelTable, points: np.ndarray) -> np.ndarray:
    """(k,) rows of the voxels at ``points`` ((k, 3) indices), -1 where there is none."""
    points = np.ascontiguousarray(points, np.int64).reshape(-1, 3)
    return _lookup(table.keys, table.rows, table.shape, points)
