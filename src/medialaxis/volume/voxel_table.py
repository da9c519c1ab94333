"""A sparse grid from voxel indices to rows: the grid of a thin voxel set.

The medial voxels of a thin-plate part are a thin sheet in a large box: a
dense ``(Z, Y, X)`` int32 grid of their rows costs 4 bytes per voxel of the
box (4 GiB for a 1024^3 scan, and the polygonization needs three such grids),
while the sheet holds a few voxels per thousand. :class:`VoxelTable` stores
the rows in bricks of 8 x 8 x 8 voxels, only where the sheet passes, found
through a coarse directory of the box (one int32 per brick: 8 MB for
1024^3), as OpenVDB and NanoVDB store sparse volumes. A lookup reads the
directory and one brick, and a voxel's neighbours are in the same brick or
the next: the compiled kernels look them up nearly as fast as in the dense
grid. Positions outside ``shape`` are absent.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from medialaxis._jit import njit

__all__ = ["VoxelTable", "voxel_table", "table_find", "table_lookup", "neighbour_rows", "NEIGHBOURS_26"]


class VoxelTable(NamedTuple):
    """Rows of voxels in 8^3 bricks.

    Attributes
    ----------
    directory : (Z/8, Y/8, X/8) int32 ndarray
        Brick number of each 8^3 cell of the grid, -1 where no voxel is.
    bricks : (b, 512) int32 ndarray
        Row of each voxel of a brick (``(z % 8) * 64 + (y % 8) * 8 + x % 8``), -1 where none.
    shape : (3,) int64 ndarray
        The grid ``(Z, Y, X)``.
    """

    directory: np.ndarray
    bricks: np.ndarray
    shape: np.ndarray


@njit(cache=True, nogil=True)
def _build(voxels: np.ndarray, shape: np.ndarray) -> tuple[np.ndarray, np.ndarray]:  # pragma: no cover - compiled
    directory = np.full(((shape[0] + 7) >> 3, (shape[1] + 7) >> 3, (shape[2] + 7) >> 3), -1, np.int32)
    count = 0
    for i in range(voxels.shape[0]):
        a, b, c = voxels[i, 0] >> 3, voxels[i, 1] >> 3, voxels[i, 2] >> 3
        if directory[a, b, c] < 0:
            directory[a, b, c] = count
            count += 1
    bricks = np.full((count, 512), -1, np.int32)
    for i in range(voxels.shape[0]):
        z, y, x = voxels[i, 0], voxels[i, 1], voxels[i, 2]
        d = directory[z >> 3, y >> 3, x >> 3]
        k = ((z & 7) * 8 + (y & 7)) * 8 + (x & 7)
        if bricks[d, k] < 0:  # the first of repeated voxels keeps its row
            bricks[d, k] = i
    return directory, bricks


@njit(cache=True, nogil=True)
def table_find(directory: np.ndarray, bricks: np.ndarray, shape: np.ndarray, z: int, y: int, x: int) -> int:  # pragma: no cover
    """Row of voxel ``(z, y, x)``, or -1 (absent or outside the grid)."""
    if z < 0 or y < 0 or x < 0 or z >= shape[0] or y >= shape[1] or x >= shape[2]:
        return -1
    d = directory[z >> 3, y >> 3, x >> 3]
    if d < 0:
        return -1
    return bricks[d, ((z & 7) * 8 + (y & 7)) * 8 + (x & 7)]


@njit(cache=True, nogil=True)
def _lookup(directory: np.ndarray, bricks: np.ndarray, shape: np.ndarray, points: np.ndarray) -> np.ndarray:  # pragma: no cover
    out = np.empty(points.shape[0], np.int64)
    for i in range(points.shape[0]):
        out[i] = table_find(directory, bricks, shape, points[i, 0], points[i, 1], points[i, 2])
    return out


def voxel_table(voxels: np.ndarray, shape: tuple[int, ...] | np.ndarray) -> VoxelTable:
    """The table of ``voxels`` ((n, 3) indices inside ``shape``, n < 2^31); row ``i`` is ``voxels[i]``.

    Examples
    --------
    >>> import numpy as np
    >>> t = voxel_table(np.array([[1, 2, 3], [4, 5, 6]]), (8, 8, 8))
    >>> table_lookup(t, np.array([[4, 5, 6], [0, 0, 0], [9, 9, 9]])).tolist()
    [1, -1, -1]
    """
    voxels = np.ascontiguousarray(voxels, np.int64).reshape(-1, 3)
    shape_arr = np.asarray(shape, np.int64).reshape(3)
    directory, bricks = _build(voxels, shape_arr)
    return VoxelTable(directory, bricks, shape_arr)


def table_lookup(table: VoxelTable, points: np.ndarray) -> np.ndarray:
    """(k,) rows of the voxels at ``points`` ((k, 3) indices), -1 where there is none."""
    points = np.ascontiguousarray(points, np.int64).reshape(-1, 3)
    return _lookup(table.directory, table.bricks, table.shape, points)


#: The 26 neighbour offsets in C order (the first 13 precede the voxel).
NEIGHBOURS_26 = np.array([(a, b, c) for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1) if (a, b, c) != (0, 0, 0)],
                         np.int64)


@njit(cache=True, nogil=True)
def _neighbour_rows(directory: np.ndarray, bricks: np.ndarray, shape: np.ndarray, voxels: np.ndarray,
                    offs: np.ndarray) -> np.ndarray:  # pragma: no cover - compiled
    out = np.empty((voxels.shape[0], offs.shape[0]), np.int32)
    for i in range(voxels.shape[0]):
        z, y, x = voxels[i, 0], voxels[i, 1], voxels[i, 2]
        inner = 0 < (z & 7) < 7 and 0 < (y & 7) < 7 and 0 < (x & 7) < 7  # all 26 in the voxel's own brick
        d = directory[z >> 3, y >> 3, x >> 3] if inner else -1
        for t in range(offs.shape[0]):
            a, b, c = z + offs[t, 0], y + offs[t, 1], x + offs[t, 2]
            if inner:
                out[i, t] = bricks[d, ((a & 7) * 8 + (b & 7)) * 8 + (c & 7)]
            else:
                out[i, t] = table_find(directory, bricks, shape, a, b, c)
    return out


def neighbour_rows(table: VoxelTable, voxels: np.ndarray) -> np.ndarray:
    """(n, 26) int32 rows of the 26 neighbours (:data:`NEIGHBOURS_26`) of each of ``voxels``, -1 where there is none.

    Looked up once, the table serves every pass over the sheet's
    neighbourhoods (classes, sheets, regions): a lookup in the sparse
    table costs more than reading a row of this array.
    """
    voxels = np.ascontiguousarray(voxels, np.int64).reshape(-1, 3)
    return _neighbour_rows(table.directory, table.bricks, table.shape, voxels, NEIGHBOURS_26)
