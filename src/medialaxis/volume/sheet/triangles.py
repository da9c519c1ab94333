"""Triangles from the Voronoi regions of the picks on the medial voxels (Michikawa and Suzuki).

A triangle joins three picks whose regions meet in one 2x2x2 block of voxels
of one sheet (plus junction voxels) and touch pairwise; four regions meeting
without diagonals (a degenerate Voronoi vertex) give two triangles across the
shorter diagonal. Junction edges are shared by the triangles of all sheets at
the line (three at a T, four at an X).
"""

from __future__ import annotations

import itertools

import numpy as np

from medialaxis.core.arrays import unique_ints
from medialaxis.volume.sheet._triangle_kernels import block_labels
from medialaxis.volume.voxel_table import VoxelTable, neighbour_rows, table_lookup

__all__ = ["region_triangles", "pair_keys", "has_keys", "block_labels_reference"]


def pair_keys(a: np.ndarray, b: np.ndarray, n: int) -> np.ndarray:
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    return lo.astype(np.int64) * n + hi


def _region_edges(neighbours: np.ndarray, label: np.ndarray, n: int, sheet: np.ndarray | None = None) -> np.ndarray:
    """Sorted unique keys of label pairs that are 6-adjacent (share a voxel face) somewhere.

    ``neighbours`` are the rows of the voxels' 26 neighbours. With ``sheet``
    (sheet of each voxel, -1 junction), only pairs in one sheet, or with a
    junction voxel, count.
    """
    keys = []
    for column in (21, 15, 13):  # the neighbours one step up along axis 0, 1, 2 (C order without the centre)
        j = neighbours[:, column].astype(np.int64)
        i = np.flatnonzero(j >= 0)
        j = j[i]
        a, b = label[i], label[j]
        touch = (a >= 0) & (b >= 0) & (a != b)
        if sheet is not None:
            sa, sb = sheet[i], sheet[j]
            touch &= (sa == sb) | (sa == -1) | (sb == -1)
        keys.append(pair_keys(a[touch], b[touch], n))
    return unique_ints(np.concatenate(keys))


def has_keys(keys: np.ndarray, query: np.ndarray) -> np.ndarray:
    pos = np.searchsorted(keys, query)
    pos = np.minimum(pos, len(keys) - 1)
    return keys[pos] == query if len(keys) else np.zeros(len(query), bool)


#: Medial voxels whose 2x2x2 blocks the reference labels at a time (bounds the memory of a large sheet).
BLOCK_BATCH = 250_000


def _block_labels(table: VoxelTable, voxels: np.ndarray, label: np.ndarray,
                  sheet: np.ndarray | None = None, neighbours: np.ndarray | None = None) -> np.ndarray:
    """Sorted labels (-1 padded) of the 2x2x2 blocks that hold three or more regions (Voronoi vertices).

    With ``sheet`` (sheet of each voxel, -1 junction), a block gives one row
    per sheet in it, with the labels of that sheet's voxels and of the
    junction voxels; blocks of junction voxels only give none. Regions of
    two sheets thus never form a triangle. Compiled
    (:func:`~medialaxis.volume.sheet._triangle_kernels.block_labels`); the same
    rows as :func:`block_labels_reference`, in another order.
    """
    use_sheet = sheet is not None
    sheets = np.asarray(sheet if use_sheet else np.zeros(0), np.int64)
    voxels = np.ascontiguousarray(voxels, np.int64)
    if neighbours is None:
        neighbours = neighbour_rows(table, voxels)
    return block_labels(neighbours, table.shape, voxels, np.asarray(label, np.int64), sheets, use_sheet)


def block_labels_reference(table: VoxelTable, voxels: np.ndarray, label: np.ndarray,
                           sheet: np.ndarray | None = None) -> np.ndarray:
    """NumPy reference of :func:`_block_labels`: the voxels are taken ``BLOCK_BATCH`` at a time, and a block
    may come once per batch."""
    out = [np.zeros((0, 8), np.int64)]
    for start in range(0, len(voxels), BLOCK_BATCH):
        labels = _batch_labels(table, voxels[start:start + BLOCK_BATCH], label, sheet)
        out.append(labels[(labels >= 0).sum(axis=1) >= 3])
    return np.concatenate(out)


def _batch_labels(table: VoxelTable, voxels: np.ndarray, label: np.ndarray, sheet: np.ndarray | None) -> np.ndarray:
    corners = np.array(list(itertools.product((0, 1), repeat=3)), np.int64)
    origins = (voxels[:, None, :] - corners[None, :, :]).reshape(-1, 3)
    shape = table.shape
    origins = origins[np.all((origins >= 0) & (origins < shape - 1), axis=1)]
    flat = unique_ints(np.ravel_multi_index(origins.T, tuple(shape)))
    origins = np.stack(np.unravel_index(flat, tuple(shape)), axis=1)
    cells = origins[:, None, :] + corners[None, :, :]
    rows = table_lookup(table, cells.reshape(-1, 3)).reshape(-1, 8)
    present = rows >= 0
    labels = np.where(present, label[rows], -1)
    if sheet is not None:
        sheets = np.where(present, sheet[rows], -2)
        real = sheets >= 0
        top = np.where(real, sheets, -1).max(axis=1)
        bottom = np.where(real, sheets, np.iinfo(sheets.dtype).max).min(axis=1)
        mixed = np.flatnonzero((top >= 0) & (top != bottom))
        # one row per (block, sheet) of the blocks that hold several sheets,
        # in block then sheet order
        block, slot = np.nonzero(real[mixed])
        pairs = np.unique(np.stack([mixed[block], sheets[mixed[block], slot]], axis=1), axis=0)
        b, one = pairs[:, 0], pairs[:, 1]
        keep = (sheets[b] == one[:, None]) | (sheets[b] == -1)
        labels = np.concatenate([labels[(top >= 0) & (top == bottom)], np.where(keep, labels[b], -1)])
    labels.sort(axis=1)
    # blank repeated labels so each row lists its distinct labels
    labels[:, 1:][labels[:, 1:] == labels[:, :-1]] = -1
    labels.sort(axis=1)
    return labels


def _split_quad(labs: np.ndarray, points: np.ndarray, edges: np.ndarray, n: int) -> list[tuple[int, int, int]]:
    """Two triangles for four regions meeting at one degenerate Voronoi vertex.

    Regions that share a voxel face are sides of the quad; the diagonals are
    the two pairs that only touch at the vertex. A diagonal that is a region
    edge elsewhere is used; otherwise the shorter diagonal.
    """
    pairings = [((0, 1), (2, 3)), ((0, 2), (1, 3)), ((0, 3), (1, 2))]

    def side(i: int, j: int) -> bool:
        return bool(has_keys(edges, pair_keys(np.array([labs[i]]), np.array([labs[j]]), n))[0])

    def length(i: int, j: int) -> float:
        return float(np.linalg.norm(points[labs[i]] - points[labs[j]]))

    sides = [sum(side(*e) for e in pairing) for pairing in pairings]
    candidates = [k for k in range(3) if sides[k] < 2] or [int(np.argmax([length(*a) + length(*b) for a, b in pairings]))]
    k = min(candidates, key=lambda c: (sides[c] == 0 and len(candidates) > 1, sum(length(*e) for e in pairings[c])))
    (a, b), (c, d) = pairings[k]
    if side(c, d) and not side(a, b):
        (a, b), (c, d) = (c, d), (a, b)
    elif side(a, b) == side(c, d) and length(c, d) < length(a, b):
        (a, b), (c, d) = (c, d), (a, b)
    la, lb, lc, ld = (int(labs[i]) for i in (a, b, c, d))
    return [(la, lb, lc), (la, lb, ld)]


def region_triangles(table: VoxelTable, voxels: np.ndarray, label: np.ndarray, points: np.ndarray,
                     sheet: np.ndarray | None = None, neighbours: np.ndarray | None = None) -> np.ndarray:
    """Sorted unique triangles ``(f, 3)`` of the regions ``label`` (pick numbers) that meet at Voronoi vertices
    (``neighbours``: the voxels' :func:`~medialaxis.volume.voxel_table.neighbour_rows`, looked up when not given).

    References
    ----------
    .. [1] T. Michikawa, H. Suzuki, "Polygonization of volumetric skeletons with junctions",
           Computer-Aided Design 45(4):822-828, 2013. doi:10.1016/j.cad.2011.06.003
    """
    n = len(points)
    if neighbours is None:
        neighbours = neighbour_rows(table, voxels)
    edges = _region_edges(neighbours, label, n, sheet)
    blocks = _block_labels(table, voxels, label, sheet, neighbours)
    distinct = (blocks >= 0).sum(axis=1)
    faces = [blocks[distinct == 3][:, -3:].astype(np.int64)]
    extra: list[tuple[int, int, int]] = []
    for row in np.unique(blocks[distinct >= 4], axis=0):
        labs = row[row >= 0]
        if len(labs) == 4:
            extra.extend(_split_quad(labs, points, edges, n))
        else:  # five or more regions at one vertex: triangles of face-adjacent triples
            for c in itertools.combinations(labs.tolist(), 3):
                ks = pair_keys(np.array([c[0], c[0], c[1]]), np.array([c[1], c[2], c[2]]), n)
                if has_keys(edges, ks).all():
                    extra.append(c)
    if extra:
        faces.append(np.array(extra, np.int64).reshape(-1, 3))
    out = np.sort(np.concatenate(faces), axis=1)
    return np.unique(out, axis=0) if len(out) else out.reshape(0, 3)
