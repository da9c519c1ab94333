"""The stages of the mid-surface pipeline after the medial voxels, shared by the in-memory and chunked routes.

Each stage reads the medial voxels (:class:`MedialStage`) and returns the mesh as it leaves it
(:class:`SheetMesh`, frozen):

1. :func:`polygonize_stage`: sub-sampling polygonization (:mod:`~medialaxis.volume.sheet.polygonize`);
2. :func:`dents_stage`: free edges, junction dents and creases by eq. (1) (:mod:`~medialaxis.volume.sheet.dents`);
3. :func:`extension_stage`: free edges extended to the isosurface (:mod:`~medialaxis.volume.sheet.extension`);
4. :func:`assemble`: the :class:`~medialaxis.core.result.MedialAxis` and the axis after each stage.
"""

from __future__ import annotations

import dataclasses
import warnings
from typing import Any

import numpy as np

from medialaxis.core.graph import sheet_edges
from medialaxis.core.result import MedialAxis
from medialaxis.errors import EmptyShapeError, InvalidInputError, MedialAxisWarning
from medialaxis.volume.medial import MedialVoxels
from medialaxis.volume.plates import TUBE_ROUTE, PlateThickness
from medialaxis.volume.sheet.dents import bent_vertices
from medialaxis.volume.sheet.dents import remove_dents as _remove_dents
from medialaxis.volume.sheet.extension import extend_mesh
from medialaxis.volume.sheet.polygonize import (
    BOUNDARY,
    CREASE_COHERENCE,
    EXTENSION,
    JUNCTION,
    SURFACE,
    Polygonization,
    polygonize,
)

__all__ = ["MedialStage", "SheetMesh", "polygonize_stage", "dents_stage", "extension_stage", "assemble", "mesh_result", "stage_metadata", "dropped_report",
           "thickness_range", "check_range"]


#: Passes of eq. (1) for free-edge vertices: each pass keeps 1 / (1 + k) of
#: the offset from the planes of the k faces beside the vertex.
FREE_EDGE_PASSES = 3


#: Passes of eq. (1) for crease vertices.
CREASE_PASSES = 2


#: Free-edge vertices take planes from faces this many rings away: beside
#: the end of a junction line their one-ring holds no clean face.
FREE_EDGE_RINGS = 2


#: Warn when the medial test leaves out at least this fraction of the pairs
#: that see both faces of a plate (a plate outside the thickness asked for).
DROPPED_WARNING = 0.01


@dataclasses.dataclass(frozen=True)
class MedialStage:
    """The medial voxels and what the mesh stages read of them.

    Attributes
    ----------
    medial : MedialVoxels
        On ``grid`` (a whole volume's, or a block's window).
    grid : Features or Grid
        Its ``offset``, ``shape``, ``spacing`` and ``physical()``.
    plates : PlateThickness
    lam : float or None
        ``None``: each plate's own.
    """

    medial: MedialVoxels
    grid: Any
    plates: PlateThickness
    lam: float | None

    @property
    def thickness(self) -> float:
        """The nominal plate thickness, or the median of the plates kept."""
        return float(self.plates.value)


@dataclasses.dataclass(frozen=True)
class SheetMesh:
    """The mid-surface mesh as a stage leaves it.

    Attributes
    ----------
    mesh : Polygonization
        The polygonization the stages started from.
    points, faces, radii, kind : ndarray
        The mesh now (``kind``: the polygonization's vertex classes, and ``EXTENSION``).
    dented_points : ndarray or None
        The points after the dent stage (for ``VolumeStages.steps``).
    extended_from : (e,) int ndarray
        The vertex each extension vertex was extended from.
    """

    mesh: Polygonization
    points: np.ndarray
    faces: np.ndarray
    radii: np.ndarray
    kind: np.ndarray
    dented_points: np.ndarray | None = None
    extended_from: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0, np.int64))

    @classmethod
    def of(cls, mesh: Polygonization) -> SheetMesh:
        """The mesh as the polygonization made it."""
        return cls(mesh, mesh.points, mesh.faces, mesh.radii, mesh.kind)


def check_range(thickness: Any) -> tuple[float, float]:
    try:
        lo, hi = (float(v) for v in thickness)
    except (TypeError, ValueError):
        raise InvalidInputError(f"thickness must be a number or a (min, max) pair, got {thickness!r}") from None
    if not (np.isfinite(lo) and lo > 0 and hi > lo) or np.isnan(hi):
        raise InvalidInputError(f"thickness range must be 0 < min < max (max may be inf), got {thickness!r}")
    return lo, hi


def thickness_range(plates: PlateThickness) -> list[float | None] | None:
    """The thickness bounds for metadata (``None`` for no upper bound: JSON has no infinity)."""
    if not plates.ranged:
        return None
    return [plates.lower, plates.upper if np.isfinite(plates.upper) else None]


def dropped_report(medial: MedialVoxels, plates: PlateThickness, lam: float | None) -> dict[str, float] | None:
    """What the medial test left out of the plates (metadata), with a warning when it matters."""
    gaps = medial.dropped_gaps
    if medial.sheet_pairs == 0 or len(gaps) == 0:
        return None
    fraction = len(gaps) / medial.sheet_pairs
    info = {"fraction": float(fraction), "thickness": float(np.median(gaps))}
    if fraction >= DROPPED_WARNING:
        if plates.ranged:
            rule = f"thickness range {plates.lower:g} to {plates.upper:g}" + (f" or lam={lam:g}" if lam is not None else "")
        else:
            rule = f"thickness={plates.value:g} (lam={lam:g})"
        warnings.warn(
            f"plates about {info['thickness']:.3g} thick ({fraction:.0%} of the plate area) are left out of the "
            f"mid-surface by {rule}; omit thickness or give a (min, max) range to keep them",
            MedialAxisWarning, stacklevel=4,
        )
    return info


def stage_metadata(method: str, iso: float, plates: PlateThickness, lam: float | None, dropped: Any,
                   spacing: np.ndarray, shape: tuple[int, ...], *, threshold_method: str) -> dict[str, Any]:
    """The metadata every volume result carries (``midsurface`` and ``voxels``, in memory or by blocks)."""
    return {
        "method": method,
        "domain": "volume",
        "iso": iso,
        "threshold_method": threshold_method,
        "thickness": plates.value,
        "thickness_range": thickness_range(plates),
        "lam": lam,
        "dropped": dropped,
        "spacing": np.asarray(spacing).tolist(),
        "image_shape": list(shape),
    }


def polygonize_stage(stage: MedialStage, density: float, rng: Any) -> SheetMesh:
    """Sub-sampling polygonization of the medial voxels."""
    return SheetMesh.of(polygonize(stage.grid, stage.medial, density=density, rng=rng))


def dents_stage(stage: MedialStage, sheet: SheetMesh, remove_dents: bool) -> SheetMesh:
    """Free edges, dents at junctions and creases put on the planes of the faces beside them (eq. 1)."""
    kind, faces = sheet.kind, sheet.faces
    special = (kind == JUNCTION) | (kind == BOUNDARY)
    # free-edge vertices mix in boundary points of the end face: put them
    # on the planes of the interior faces next to them (eq. 1 as well)
    moved = sheet.points
    for _ in range(FREE_EDGE_PASSES):
        moved = _remove_dents(moved, faces, kind == BOUNDARY, special, rings=FREE_EDGE_RINGS)
    if remove_dents:
        moved = _remove_dents(moved, faces, kind == JUNCTION, special)
        # creases (a sheet bending sharply) are rounded like dents: put
        # them on the planes of the faces on either side
        crease = (kind == SURFACE) & (stage.medial.coherence[sheet.mesh.picks] < CREASE_COHERENCE)
        crease |= (kind == SURFACE) & bent_vertices(moved, faces)
        for _ in range(CREASE_PASSES):
            moved = _remove_dents(moved, faces, crease, special | crease, rings=2)
    return dataclasses.replace(sheet, points=moved, dented_points=moved)


def extension_stage(stage: MedialStage, sheet: SheetMesh, grey: Any, iso: float, spacing: np.ndarray,
                    density: float) -> SheetMesh:
    """Free edges extended to the isosurface (``grey``: an array, or a sampler with ``sample`` and ``minimum``)."""
    local = stage.plates.local
    # each free edge reaches as far as its own plate's thickness allows
    plate = 2.0 * sheet.radii if local else stage.thickness
    # the sampling radius: each vertex's own, or half the part's plate thickness (known before the mesh,
    # so that a block of the mesh extends its edges as the whole mesh does)
    sample_radius = density * (sheet.radii if local else 0.5 * stage.thickness)
    points, faces, source = extend_mesh(
        sheet.points, sheet.faces, grey, iso, spacing,
        max_length=1.5 * plate + 2.0 * sample_radius,
        free=sheet.kind == BOUNDARY, junction=sheet.kind == JUNCTION,
        probe=0.5 * plate + 2.0 * float(spacing.max()), chord=plate,
    )
    return dataclasses.replace(
        sheet, points=points, faces=faces, extended_from=source, radii=np.concatenate([sheet.radii, sheet.radii[source]]),
        kind=np.concatenate([sheet.kind, np.full(len(source), EXTENSION, np.int8)]))


def mesh_result(points: np.ndarray, radii: np.ndarray, kind: np.ndarray, faces: np.ndarray, metadata: dict[str, Any],
                shell: Any) -> MedialAxis:
    """The mid-surface result; faces in the order of their rows (vertices are in pick order), so that
    the order does not depend on how the mesh was built, whole or by blocks.

    Raises :class:`~medialaxis.errors.EmptyShapeError` when no triangle is
    left: a rod's or a tube's plate-crossing pairs run across its width, but
    they make a line, not a sheet.
    """
    if len(faces) == 0:
        raise EmptyShapeError(
            f"no mid-surface: the {len(points)} medial points found make no sheet (rods, tubes and blobs have no "
            f"plates); {TUBE_ROUTE}")
    faces = faces[np.lexsort(faces.T[::-1])]
    return MedialAxis(points, radii, sheet_edges(faces), faces, extras={"thickness": 2.0 * radii, "vertex_kind": kind},
                      metadata=metadata, shape=shell)


def assemble(stage: MedialStage, sheet: SheetMesh, metadata: dict[str, Any],
             shell: Any) -> tuple[MedialAxis, dict[str, MedialAxis]]:
    """The result and the axis after each stage (``VolumeStages.steps``)."""
    points, faces, radii, kind = sheet.points, sheet.faces, sheet.radii, sheet.kind
    if len(faces):
        # a lone medial voxel (a noisy corner) is a vertex without a face: not part of the mid-surface
        used = np.zeros(len(points), bool)
        used[faces.ravel()] = True
        if not used.all():
            faces = (np.cumsum(used) - 1)[faces]
            points, radii, kind = points[used], radii[used], kind[used]
    result = mesh_result(points, radii, kind, faces, metadata, shell)
    mesh, medial, grid = sheet.mesh, stage.medial, stage.grid
    voxel_meta = dict(metadata, method="voxels")
    dented = sheet.points if sheet.dented_points is None else sheet.dented_points
    steps = {
        "medial_voxels": MedialAxis(grid.physical(medial.voxels), medial.radius, metadata=voxel_meta, shape=shell),
        "polygonized": MedialAxis(mesh.points, mesh.radii, faces=mesh.faces, metadata=metadata,
                                  extras={"vertex_kind": mesh.kind}, shape=shell),
        "dents_removed": MedialAxis(dented, mesh.radii, faces=mesh.faces, metadata=metadata,
                                    extras={"vertex_kind": mesh.kind}, shape=shell),
        "extended": result,
    }
    return result, steps
