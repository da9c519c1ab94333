"""Sub-sampling polygonization of medial voxels (Michikawa and Suzuki, 2013).

1. Classify medial voxels as junction, boundary or surface by counting the
   background components around them (Malandain).
2. Pick representatives in the order junction, boundary, surface, each pick
   removing the medial voxels within its sampling radius.
3. Grow the picks' discrete Voronoi regions over the medial voxels
   (breadth-first, 26-adjacency) and connect picks whose regions touch.
4. A triangle joins three picks whose regions meet in one 2x2x2 block of
   voxels and touch pairwise; four regions meeting without diagonals (a
   degenerate Voronoi vertex) give two triangles across the shorter
   diagonal. Junction edges are shared by three or more triangles.
"""

from __future__ import annotations

import dataclasses
import itertools

import numpy as np

from medialaxis.volume import _kernels
from medialaxis.volume.distance import Features
from medialaxis.volume.medial import MedialVoxels

__all__ = ["SURFACE", "BOUNDARY", "JUNCTION", "EXTENSION", "Polygonization", "classify_voxels", "polygonize"]

#: Vertex / voxel classes.
SURFACE, BOUNDARY, JUNCTION, EXTENSION = 0, 1, 2, 3


@dataclasses.dataclass(frozen=True)
class Polygonization:
    """A triangle mesh over picked medial voxels.

    Attributes
    ----------
    picks : (v,) int64 ndarray
        Rows of the medial voxels used as vertices.
    points : (v, 3) float64 ndarray
    radii : (v,) float64 ndarray
    kind : (v,) int8 ndarray
        ``SURFACE``, ``BOUNDARY`` or ``JUNCTION``.
    faces : (f, 3) int64 ndarray
    voxel_kind : (n,) int8 ndarray
        Class of every medial voxel.
    voxel_label : (n,) int64 ndarray
        Voronoi region (vertex index) of every medial voxel.
    """

    picks: np.ndarray
    points: np.ndarray
    radii: np.ndarray
    kind: np.ndarray
    faces: np.ndarray
    voxel_kind: np.ndarray
    voxel_label: np.ndarray


def classify_voxels(occupied: np.ndarray, voxels: np.ndarray) -> np.ndarray:
    """Junction / boundary / surface class of each voxel of a thin sheet.

    Parameters
    ----------
    occupied : (z, y, x) bool ndarray
        The sheet; False on the outer layer.
    voxels : (n, 3) int64 ndarray
        Indices of the sheet voxels.

    Returns
    -------
    (n,) int8 ndarray
        ``JUNCTION`` (three or more background components around the voxel),
        ``BOUNDARY`` (at most one) or ``SURFACE`` (two).
    """
    count = _kernels.topology_class(occupied, np.ascontiguousarray(voxels, np.int64), _kernels.N26_OFFSETS,
                                    _kernels.N26_ADJ, _kernels.N26_FACE)
    kind = np.full(len(voxels), SURFACE, np.int8)
    kind[count <= 1] = BOUNDARY
    kind[count >= 3] = JUNCTION
    return kind


def _pair_keys(a: np.ndarray, b: np.ndarray, n: int) -> np.ndarray:
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    return lo.astype(np.int64) * n + hi


def _region_edges(label_grid: np.ndarray, n: int) -> np.ndarray:
    """Sorted unique keys of label pairs that are 6-adjacent somewhere."""
    keys = []
    for axis in range(3):
        lo = [slice(None)] * 3
        hi = [slice(None)] * 3
        lo[axis], hi[axis] = slice(None, -1), slice(1, None)
        a, b = label_grid[tuple(lo)], label_grid[tuple(hi)]
        touch = (a >= 0) & (b >= 0) & (a != b)
        keys.append(_pair_keys(a[touch], b[touch], n))
    return np.unique(np.concatenate(keys))


def _has(keys: np.ndarray, query: np.ndarray) -> np.ndarray:
    pos = np.searchsorted(keys, query)
    pos = np.minimum(pos, len(keys) - 1)
    return keys[pos] == query if len(keys) else np.zeros(len(query), bool)


def _block_labels(label_grid: np.ndarray, voxels: np.ndarray) -> np.ndarray:
    """Sorted labels (-1 padded) of every 2x2x2 block that holds a medial voxel."""
    corners = np.array(list(itertools.product((0, 1), repeat=3)), np.int64)
    origins = (voxels[:, None, :] - corners[None, :, :]).reshape(-1, 3)
    shape = np.array(label_grid.shape)
    origins = origins[np.all((origins >= 0) & (origins < shape - 1), axis=1)]
    flat = np.unique(np.ravel_multi_index(origins.T, label_grid.shape))
    origins = np.stack(np.unravel_index(flat, label_grid.shape), axis=1)
    cells = origins[:, None, :] + corners[None, :, :]
    labels = label_grid[cells[..., 0], cells[..., 1], cells[..., 2]]
    labels.sort(axis=1)
    # blank repeated labels so each row lists its distinct labels
    labels[:, 1:][labels[:, 1:] == labels[:, :-1]] = -1
    labels.sort(axis=1)
    return labels


def _triangles(label_grid: np.ndarray, voxels: np.ndarray, points: np.ndarray) -> np.ndarray:
    n = len(points)
    edges = _region_edges(label_grid, n)
    blocks = _block_labels(label_grid, voxels)
    distinct = (blocks >= 0).sum(axis=1)
    tri = [blocks[distinct == 3][:, -3:]]
    extra: list[tuple[int, int, int]] = []
    for row in np.unique(blocks[distinct >= 4], axis=0):
        labs = row[row >= 0]
        cliques = [c for c in itertools.combinations(labs, 3)
                   if _has(edges, _pair_keys(np.array([c[0], c[0], c[1]]), np.array([c[1], c[2], c[2]]), n)).all()]
        if len(labs) == 4 and len(cliques) != 2:
            # a degenerate Voronoi vertex: split the quad across its shorter diagonal
            best = None
            for a, b in itertools.combinations(labs, 2):
                c, d = [x for x in labs if x not in (a, b)]
                pair = [(a, b, c), (a, b, d)]
                perimeter = sum(np.linalg.norm(points[t[0]] - points[t[1]]) + np.linalg.norm(points[t[1]] - points[t[2]])
                                + np.linalg.norm(points[t[2]] - points[t[0]]) for t in pair)
                if best is None or perimeter < best[0]:
                    best = (perimeter, pair)
            assert best is not None
            cliques = best[1]
        extra.extend(cliques)
    if extra:
        tri.append(np.array(extra, np.int64).reshape(-1, 3))
    faces = np.concatenate(tri).astype(np.int64)
    if len(faces) == 0:
        return faces.reshape(0, 3)
    keys_ab = _pair_keys(faces[:, 0], faces[:, 1], n)
    keys_bc = _pair_keys(faces[:, 1], faces[:, 2], n)
    keys_ca = _pair_keys(faces[:, 2], faces[:, 0], n)
    # triangles from 3-label blocks need their three regions to touch pairwise;
    # quad splits add their diagonal, which is not a region edge
    first = len(tri[0])
    ok = np.ones(len(faces), bool)
    ok[:first] = _has(edges, keys_ab[:first]) & _has(edges, keys_bc[:first]) & _has(edges, keys_ca[:first])
    faces = np.sort(faces[ok], axis=1)
    return np.unique(faces, axis=0)


def polygonize(features: Features, medial: MedialVoxels, *, density: float = 1.0) -> Polygonization:
    """Triangle mesh of the medial voxels by sub-sampling.

    Parameters
    ----------
    features : Features
        Gives the crop grid of the medial voxels.
    medial : MedialVoxels
    density : float
        Sampling radius in units of the local radius (half thickness); smaller
        gives more vertices. The radius is at least 1.5 voxels.

    Returns
    -------
    Polygonization
    """
    shape = features.index.shape
    voxels = np.ascontiguousarray(medial.voxels, np.int64)
    n = len(voxels)
    occupied = np.zeros(shape, bool)
    occupied[tuple(voxels.T)] = True
    kind = classify_voxels(occupied, voxels)
    del occupied
    index = np.full(shape, -1, np.int32)
    index[tuple(voxels.T)] = np.arange(n, dtype=np.int32)
    priority = np.select([kind == JUNCTION, kind == BOUNDARY], [0, 1], 2)
    order = np.lexsort((np.arange(n), priority))
    radius = np.maximum(density * medial.radius, 1.5 * float(features.spacing.max()))
    picks = _kernels.greedy_subsample(index, voxels, order, radius, features.spacing)
    label = _kernels.geodesic_labels(index, voxels, picks, _kernels.OFFSETS_26)
    del index
    label_grid = np.full(shape, -1, np.int32)
    label_grid[tuple(voxels.T)] = label
    points = medial.position[picks]
    faces = _triangles(label_grid, voxels, points)
    return Polygonization(picks, points, medial.radius[picks], kind[picks], faces, kind, label)
