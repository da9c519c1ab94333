"""Medial voxels into classes, sheets and the discrete Voronoi regions of the picks.

1. Classify medial voxels as junction, boundary or surface by counting the
   background components around them (Malandain).
2. Split them into sheets that meet at the junction voxels (:func:`sheet_ids`).
3. Split the junction voxels between the junction picks along the lines,
   then grow the picks' regions over each sheet from its own picks and from
   all junction voxels (:func:`~medialaxis.volume._kernels.sheet_labels`):
   regions never cross from one sheet to another, and every sheet at a
   junction line sees the same chain of junction regions.
"""

from __future__ import annotations

import numpy as np

from medialaxis.volume import _kernels
from medialaxis.volume.voxel_table import VoxelTable, neighbour_rows

__all__ = ["SURFACE", "BOUNDARY", "JUNCTION", "EXTENSION", "classify_voxels", "sheet_ids", "region_labels"]

#: Vertex / voxel classes.
SURFACE, BOUNDARY, JUNCTION, EXTENSION = 0, 1, 2, 3
#: The names of those codes, as voxel results give them (``metadata["voxel_kinds"]``).
VOXEL_KINDS = ("surface", "boundary", "junction", "extension")


def _neighbours(table: VoxelTable | np.ndarray, voxels: np.ndarray) -> np.ndarray:
    """The rows of the 26 neighbours of ``voxels`` (the table's own rows): given, or looked up in ``table``."""
    if isinstance(table, VoxelTable):
        return neighbour_rows(table, voxels)
    return table


def classify_voxels(table: VoxelTable | np.ndarray, voxels: np.ndarray) -> np.ndarray:
    """Junction / boundary / surface class of each voxel of a thin sheet.

    Parameters
    ----------
    table : VoxelTable or (n, 26) int32 ndarray
        The sheet (:func:`~medialaxis.volume.voxel_table.voxel_table`), or the
        rows of its voxels' neighbours (:func:`~medialaxis.volume.voxel_table.neighbour_rows`).
    voxels : (n, 3) int64 ndarray
        Indices of the sheet voxels (the table's rows).

    Returns
    -------
    (n,) int8 ndarray
        ``JUNCTION`` (three or more background components around the voxel),
        ``BOUNDARY`` (at most one) or ``SURFACE`` (two).

    References
    ----------
    .. [1] G. Malandain, G. Bertrand, N. Ayache, "Topological segmentation of discrete
           surfaces", International Journal of Computer Vision 10(2):183-197, 1993.
           doi:10.1007/BF01420736
    """
    count = _kernels.topology_class(_neighbours(table, voxels), _kernels.N26_ADJ)
    kind = np.full(len(voxels), SURFACE, np.int8)
    kind[count <= 1] = BOUNDARY
    kind[count >= 3] = JUNCTION
    return kind


#: Medial voxels closer than this (voxels) to a junction voxel do not join
#: sheets: near a junction the sheets touch one another diagonally.
SHEET_SEPARATION = 3.0


#: Sheets of fewer voxels are noise: their voxels join the nearest sheet.
MIN_SHEET_VOXELS = 20


def sheet_ids(table: VoxelTable | np.ndarray, voxels: np.ndarray, junction: np.ndarray, spacing: np.ndarray) -> np.ndarray:
    """Split the medial voxels into sheets that meet at junction voxels.

    Voxels farther than ``SHEET_SEPARATION`` voxels from every junction voxel
    form sheets by 26-connectivity; the voxels near the junctions then join
    the sheet they are geodesically nearest to (never through a junction
    voxel).

    Parameters
    ----------
    table : VoxelTable or (n, 26) int32 ndarray
        Row of each medial voxel, or the rows of their neighbours.
    voxels : (n, 3) int64 ndarray
    junction : (n,) bool ndarray
    spacing : (3,) float64 ndarray

    Returns
    -------
    (n,) int64 ndarray
        Sheet number, -1 for junction voxels.
    """
    from scipy.spatial import cKDTree

    n = len(voxels)
    neighbours = _neighbours(table, voxels)
    if not junction.any():
        free = np.ones(n, bool)
    else:
        near, _ = cKDTree(voxels[junction]).query(voxels, k=1, distance_upper_bound=SHEET_SEPARATION + 1e-9)
        free = ~np.isfinite(near) | (near > SHEET_SEPARATION)
    # components numbered by their smallest row (the order of scipy's connected_components)
    comp = _kernels.neighbour_components(neighbours, free, 13)
    size = np.bincount(comp[free], minlength=n)
    core = free & (size[comp] >= MIN_SHEET_VOXELS)
    if not core.any():
        return np.where(junction, -1, 0).astype(np.int64)
    _, sheet = np.unique(comp[core], return_inverse=True)
    seeds = np.flatnonzero(core)
    grow = np.where(junction, -1, 0).astype(np.int64)
    out = _kernels.sheet_labels(neighbours, voxels, seeds, sheet.astype(np.int64), grow, _kernels.OFFSETS_26, spacing)
    out[junction] = -1
    # cut off from every sheet (rare specks): one sheet of their own, numbered past the others
    out[(out < 0) & ~junction] = int(sheet.max(initial=-1)) + 1
    return out


def region_labels(table: VoxelTable | np.ndarray, voxels: np.ndarray, picks: np.ndarray, junction: np.ndarray, sheet: np.ndarray,
            spacing: np.ndarray) -> np.ndarray:
    """Vertex (pick number) of every medial voxel: Voronoi regions kept inside sheets.

    The junction voxels are first split between the junction picks along
    the junction lines; then they, with the other picks, grow regions into
    the sheets. Every sheet at a junction line thus sees the same chain of
    junction regions, and their triangles share the junction edges.
    """
    from scipy.spatial import cKDTree

    neighbours = _neighbours(table, voxels)
    on_line = np.where(junction, 0, -1).astype(np.int64)
    vertex = np.arange(len(picks), dtype=np.int64)
    at_junction = junction[picks]
    jlabel = _kernels.sheet_labels(neighbours, voxels, picks[at_junction], vertex[at_junction], on_line,
                                   _kernels.OFFSETS_26, spacing)
    lost = junction & (jlabel < 0)
    if lost.any() and at_junction.any():  # junction voxels cut off from every junction pick
        _, nearest = cKDTree(voxels[picks[at_junction]] * spacing).query(voxels[lost] * spacing, k=1)
        jlabel[lost] = vertex[at_junction][nearest]
    rows = np.flatnonzero(junction & (jlabel >= 0))
    seeds = np.concatenate([rows, picks[~at_junction]]).astype(np.int64)
    seed_label = np.concatenate([jlabel[rows], vertex[~at_junction]]).astype(np.int64)
    return _kernels.sheet_labels(neighbours, voxels, seeds, seed_label, sheet, _kernels.OFFSETS_26, spacing)
