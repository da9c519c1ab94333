"""Sub-sampling polygonization of medial voxels (Michikawa and Suzuki, 2013).

1. Classify medial voxels as junction, boundary or surface by counting the
   background components around them (Malandain; :mod:`~medialaxis.volume.regions`).
2. Pick representatives in the order junction, crease, boundary, surface,
   each pick removing the medial voxels within its sampling radius.
3. Split the medial voxels into sheets that meet at the junction voxels
   (:func:`~medialaxis.volume.regions.sheet_ids`). Split the junction voxels between the junction
   picks along the lines, then grow the picks' discrete Voronoi regions
   over each sheet from its own picks and from all junction voxels
   (:func:`~medialaxis.volume._kernels.sheet_labels`): regions never cross
   from one sheet to another, and every sheet at a junction line sees the
   same chain of junction regions.
4. (:mod:`~medialaxis.volume.sheet.triangles`) A triangle joins three picks whose regions meet in one 2x2x2 block of
   voxels of one sheet (plus junction voxels) and touch pairwise; four
   regions meeting without diagonals (a degenerate Voronoi vertex) give two
   triangles across the shorter diagonal. Junction edges are shared by the
   triangles of all sheets at the line (three at a T, four at an X).
5. Repairs (:func:`~medialaxis.volume.repair.repair_faces`): folded and doubly split quads go; the
   notches a sheet leaves beside a junction line, at a line's end, and
   small holes are closed.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from medialaxis.volume import _kernels
from medialaxis.volume.distance import Features, Grid
from medialaxis.volume.medial import MedialVoxels
from medialaxis.volume.regions import BOUNDARY, EXTENSION, JUNCTION, SURFACE, classify_voxels, region_labels, sheet_ids
from medialaxis.volume.repair import repair_faces
from medialaxis.volume.sheet.triangles import region_triangles
from medialaxis.volume.voxel_table import neighbour_rows, voxel_table

__all__ = ["SURFACE", "BOUNDARY", "JUNCTION", "EXTENSION", "Polygonization", "classify_voxels", "pick_hash", "pick_seed", "polygonize"]

#: Junction picks are this many local radii apart (sparser than the sheets:
#: larger junction regions keep the regions of different sheets apart).
JUNCTION_SPACING = 1.5

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
    certain : (n,) bool ndarray or None
        With a ``band``: whether each voxel's pick decision is the whole sheet's.
    order_key : (v, 2) uint64 ndarray
        Class priority and hash of each vertex: the vertices are in the order
        of these rows (then of their voxels), whole or by blocks.
    """

    picks: np.ndarray
    points: np.ndarray
    radii: np.ndarray
    kind: np.ndarray
    faces: np.ndarray
    voxel_kind: np.ndarray
    voxel_label: np.ndarray
    certain: np.ndarray | None = None
    order_key: np.ndarray | None = None


#: Surface voxels whose pair directions disagree this much (mean direction
#: shorter than this) lie on a crease and are sampled before the others.
CREASE_COHERENCE = 0.9


def pick_seed(rng: Any) -> int:
    """The one number :func:`pick_hash` draws from ``rng`` (a seed or a numpy Generator)."""
    return int(np.random.default_rng(rng).integers(0, 2**63))


def pick_hash(voxels: np.ndarray, seed: int) -> np.ndarray:
    """(n,) uint64: the order of the voxels within a class, drawn by each voxel's index from ``seed``.

    The order of two voxels depends on them alone (a hash of their indices
    and one seed), not on which other voxels are listed: a window of the
    sheet orders its voxels as the whole sheet does (ties, which need equal
    hashes, go by row: the volume's C order).
    """
    v = np.asarray(voxels, np.int64).astype(np.uint64)
    with np.errstate(over="ignore"):
        h = np.uint64(seed) ^ (v[:, 0] * np.uint64(0x9E3779B97F4A7C15)) ^ (v[:, 1] * np.uint64(0xC2B2AE3D27D4EB4F)) \
            ^ (v[:, 2] * np.uint64(0x165667B19E3779F9))
        # splitmix64's finaliser
        h = (h ^ (h >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
        h = (h ^ (h >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
        h ^= h >> np.uint64(31)
    return h


def polygonize(features: Features | Grid, medial: MedialVoxels, *, density: float = 1.0, rng: Any = 0,
               band: tuple[np.ndarray, np.ndarray] | None = None, shift: Any = 0,
               seed: int | None = None) -> Polygonization:
    """Triangle mesh of the medial voxels by sub-sampling.

    Parameters
    ----------
    features : Features or Grid
        Gives the crop grid of the medial voxels (``shape``, ``spacing``).
    medial : MedialVoxels
    density : float
        Sampling radius in units of the local radius (half thickness); smaller
        gives more vertices. The radius is at least 1.5 voxels.
    rng : seed or numpy Generator
        Order of the picks within a class (results are reproducible for a seed).
    band : ((n,) bool ndarray, (n,) bool ndarray), optional
        For a window of a larger sheet: the voxels whose class may be wrong
        there or that voxels outside may remove (near the sides that cut the
        sheet), and the voxels a band voxel may remove. ``certain`` then says
        which picks are the whole sheet's.

    Returns
    -------
    Polygonization

    References
    ----------
    .. [1] T. Michikawa, H. Suzuki, "Polygonization of volumetric skeletons with junctions",
           Computer-Aided Design 45(4):822-828, 2013. doi:10.1016/j.cad.2011.06.003
    .. [2] G. Malandain, G. Bertrand, N. Ayache, "Topological segmentation of discrete
           surfaces", International Journal of Computer Vision 10(2):183-197, 1993.
           doi:10.1007/BF01420736
    """
    voxels = np.ascontiguousarray(medial.voxels, np.int64)
    n = len(voxels)
    table = voxel_table(voxels, features.shape)
    neighbours = neighbour_rows(table, voxels)  # looked up once for the classes, sheets and regions
    kind = classify_voxels(neighbours, voxels)
    # creases (a sheet bending sharply, pairs in two directions) come right
    # after junctions so that vertices sit on the crease line
    crease = (kind == SURFACE) & (medial.coherence < CREASE_COHERENCE)
    priority = np.select([kind == JUNCTION, crease, kind == BOUNDARY], [0, 1, 2], 3)
    # a random order within each class avoids grid-aligned picks, whose Voronoi
    # regions meet four at a time (degenerate vertices)
    hashed = pick_hash(voxels + np.asarray(shift, np.int64), pick_seed(rng) if seed is None else seed)
    order = np.lexsort((np.arange(n), hashed, priority))
    radius = np.maximum(density * medial.radius, 1.5 * float(features.spacing.max()))
    radius[kind == JUNCTION] *= JUNCTION_SPACING
    # vertices are numbered in pick order, which depends on the voxels alone:
    # the same relative order in a window of the sheet as in the whole
    picks = _kernels.greedy_subsample(*table, voxels, order, radius, features.spacing)
    certain = None
    if band is not None:
        band, near_band = band
        certain = _kernels.subsample_certainty(*table, voxels, order, radius, features.spacing,
                                               np.asarray(band, bool), np.asarray(near_band, bool))
    junction = kind == JUNCTION
    sheet = sheet_ids(neighbours, voxels, junction, features.spacing)
    label = region_labels(neighbours, voxels, picks, junction, sheet, features.spacing)
    points = medial.position[picks]
    vertex_junction = kind[picks] == JUNCTION
    faces = region_triangles(table, voxels, label, points, sheet, neighbours)
    del neighbours
    faces = faces[~vertex_junction[faces].all(axis=1)]  # junction lines carry no faces of their own
    faces = repair_faces(faces, vertex_junction, points, free=kind[picks] == BOUNDARY)
    return Polygonization(picks, points, medial.radius[picks], kind[picks], faces, kind, label, certain,
                          np.stack([priority[picks].astype(np.uint64), hashed[picks]], axis=1))
