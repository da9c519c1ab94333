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
4. (:mod:`~medialaxis.volume.triangles`) A triangle joins three picks whose regions meet in one 2x2x2 block of
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
from medialaxis.volume.triangles import region_triangles
from medialaxis.volume.voxel_table import voxel_table

__all__ = ["SURFACE", "BOUNDARY", "JUNCTION", "EXTENSION", "Polygonization", "classify_voxels", "polygonize"]

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
    """

    picks: np.ndarray
    points: np.ndarray
    radii: np.ndarray
    kind: np.ndarray
    faces: np.ndarray
    voxel_kind: np.ndarray
    voxel_label: np.ndarray


#: Surface voxels whose pair directions disagree this much (mean direction
#: shorter than this) lie on a crease and are sampled before the others.
CREASE_COHERENCE = 0.9


def polygonize(features: Features | Grid, medial: MedialVoxels, *, density: float = 1.0, rng: Any = 0) -> Polygonization:
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

    Returns
    -------
    Polygonization
    """
    voxels = np.ascontiguousarray(medial.voxels, np.int64)
    n = len(voxels)
    table = voxel_table(voxels, features.shape)
    kind = classify_voxels(table, voxels)
    # creases (a sheet bending sharply, pairs in two directions) come right
    # after junctions so that vertices sit on the crease line
    crease = (kind == SURFACE) & (medial.coherence < CREASE_COHERENCE)
    priority = np.select([kind == JUNCTION, crease, kind == BOUNDARY], [0, 1, 2], 3)
    # a random order within each class avoids grid-aligned picks, whose Voronoi
    # regions meet four at a time (degenerate vertices)
    order = np.lexsort((np.random.default_rng(rng).permutation(n), priority))
    radius = np.maximum(density * medial.radius, 1.5 * float(features.spacing.max()))
    radius[kind == JUNCTION] *= JUNCTION_SPACING
    picks = _kernels.greedy_subsample(*table, voxels, order, radius, features.spacing)
    junction = kind == JUNCTION
    sheet = sheet_ids(table, voxels, junction, features.spacing)
    label = region_labels(table, voxels, picks, junction, sheet, features.spacing)
    points = medial.position[picks]
    vertex_junction = kind[picks] == JUNCTION
    faces = region_triangles(table, voxels, label, points, sheet)
    faces = faces[~vertex_junction[faces].all(axis=1)]  # junction lines carry no faces of their own
    faces = repair_faces(faces, vertex_junction, points, free=kind[picks] == BOUNDARY)
    return Polygonization(picks, points, medial.radius[picks], kind[picks], faces, kind, label)
