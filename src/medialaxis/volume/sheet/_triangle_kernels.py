"""Compiled loop of the triangles step: the labels of the 2x2x2 blocks of voxels where regions meet.

:func:`block_labels` walks each 2x2x2 block of the sheet once (from the
first voxel of the block in corner order) and keeps the rows of three or
more distinct region labels, the Voronoi vertices of
:func:`~medialaxis.volume.sheet.triangles.region_triangles` (Michikawa and
Suzuki's sub-sampling polygonization). Its NumPy reference is
:func:`~medialaxis.volume.sheet.triangles.block_labels_reference`; the rows are
the same set (the order may differ, duplicates are allowed: the triangles
are made unique afterwards).
"""

from __future__ import annotations

import numpy as np

from medialaxis._jit import njit

__all__ = ["block_labels"]


@njit(cache=True, nogil=True)
def _emit(out: np.ndarray, count: int, labs: np.ndarray) -> tuple[np.ndarray, int]:  # pragma: no cover - compiled
    """Append the distinct labels of ``labs`` (8, -1 absent; sorted here in place) as a row, -1 first,
    when there are three or more."""
    for k in range(1, 8):  # insertion sort of eight
        value = labs[k]
        t = k - 1
        while t >= 0 and labs[t] > value:
            labs[t + 1] = labs[t]
            t -= 1
        labs[t + 1] = value
    distinct = 0
    for k in range(8):
        if labs[k] >= 0 and (k == 0 or labs[k] != labs[k - 1]):
            distinct += 1
    if distinct < 3:
        return out, count
    if count == out.shape[0]:
        bigger = np.full((2 * out.shape[0], 8), -1, np.int64)
        for i in range(count):  # element by element: a slice assignment compiles its shape error's string formatting
            for k in range(8):
                bigger[i, k] = out[i, k]
        out = bigger
    pos = 8 - distinct
    for k in range(8):
        if labs[k] >= 0 and (k == 0 or labs[k] != labs[k - 1]):
            out[count, pos] = labs[k]
            pos += 1
    return out, count + 1


@njit(cache=True, nogil=True)
def block_labels(neighbours: np.ndarray, shape: np.ndarray, voxels: np.ndarray, label: np.ndarray,
                 sheet: np.ndarray, use_sheet: bool) -> np.ndarray:  # pragma: no cover - compiled
    """Rows (r, 8) of sorted distinct labels (-1 padded first) of the 2x2x2 blocks holding three or more regions.

    ``neighbours`` (n, 26) are the rows of each voxel's 26 neighbours in C
    order (:func:`~medialaxis.volume.voxel_table.neighbour_rows`): the
    other corners of every block a voxel is in. With ``use_sheet``, a
    block gives one row per sheet in it (its voxels' labels and the
    junction voxels', ``sheet == -1``), and a block of junction voxels
    only gives none.
    """
    n = voxels.shape[0]
    out = np.full((max(16, n // 8), 8), -1, np.int64)
    count = np.int64(0)  # not the literal 0: _emit typed with it would compile twice
    rows = np.empty(8, np.int64)
    labs = np.empty(8, np.int64)
    for i in range(n):
        for c in range(8):
            cz, cy, cx = (c >> 2) & 1, (c >> 1) & 1, c & 1
            z, y, x = voxels[i, 0] - cz, voxels[i, 1] - cy, voxels[i, 2] - cx
            if z < 0 or y < 0 or x < 0 or z >= shape[0] - 1 or y >= shape[1] - 1 or x >= shape[2] - 1:
                continue
            owner = True  # the block is walked from its first voxel in corner order
            for k in range(8):
                if k == c:
                    rows[k] = i
                    continue
                # corner k is the neighbour at offset (corner k - corner c), column of C order without the centre
                column = (((k >> 2) & 1) - cz + 1) * 9 + (((k >> 1) & 1) - cy + 1) * 3 + ((k & 1) - cx + 1)
                rows[k] = neighbours[i, column - (column > 13)]
                if k < c and rows[k] >= 0:
                    owner = False
                    break
            if not owner:
                continue
            if not use_sheet:
                for k in range(8):
                    labs[k] = label[rows[k]] if rows[k] >= 0 else -1
                out, count = _emit(out, count, labs)
                continue
            for k in range(8):  # each sheet of the block once, from its first voxel
                if rows[k] < 0 or sheet[rows[k]] < 0:
                    continue
                s = sheet[rows[k]]
                seen = False
                for t in range(k):
                    if rows[t] >= 0 and sheet[rows[t]] == s:
                        seen = True
                        break
                if seen:
                    continue
                for t in range(8):
                    r = rows[t]
                    labs[t] = label[r] if r >= 0 and (sheet[r] == s or sheet[r] == -1) else -1
                out, count = _emit(out, count, labs)
    return out[:count].copy()
