"""Mid-surfaces of thin-plate CT volumes (paper 002: Kumar, Michikawa, Suzuki).

Stages (each kept by :func:`volume_stages`):

1. binarize at ``iso`` (:mod:`~medialaxis.volume.inputs`);
2. sub-voxel boundary and nearest-boundary transform (:mod:`~medialaxis.volume.distance`);
3. plate thickness (:mod:`~medialaxis.volume.plates`) and medial voxels, the grid
   lambda-medial axis (:mod:`~medialaxis.volume.medial`);
4. sub-sampling polygonization (:mod:`~medialaxis.volume.polygonize`);
5. dent removal at junctions, eq. (1) (:mod:`~medialaxis.volume.dents`);
6. extension of the free edges to the isosurface (:mod:`~medialaxis.volume.extension`).

Stages 4-6 are :mod:`~medialaxis.volume.stages`, shared with the route for volumes
larger than memory (:mod:`~medialaxis.volume.chunked`), which the public functions
take by themselves for large inputs.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis._progress import Progress, check_cancel, progress
from medialaxis.core.result import MedialAxis
from medialaxis.core.validate import check_number
from medialaxis.errors import InvalidInputError
from medialaxis.volume.chunked import check_out, chunked_midsurface, use_chunks
from medialaxis.volume.distance import Features, feature_transform
from medialaxis.volume.inputs import VolumeInput, load_volume
from medialaxis.volume.medial import DEFAULT_LAM_RATIO, MedialVoxels, medial_voxels
from medialaxis.volume.ome_zarr import is_ome_zarr_out, write_in_memory
from medialaxis.volume.plates import PlateThickness, plate_thickness
from medialaxis.volume.polygonize import Polygonization
from medialaxis.volume.shell import isosurface_shell
from medialaxis.volume.stages import (
    assemble,
    check_range,
    dents_stage,
    dropped_report,
    extension_stage,
    polygonize_stage,
    stage_metadata,
)
from medialaxis.volume.stitch import write_zarr_mesh

__all__ = ["midsurface_medial_axis", "volume_stages", "VolumeStages", "iso_of", "thickness_and_lam"]


@dataclasses.dataclass(frozen=True)
class VolumeStages:
    """Every intermediate of one run (for ``--steps`` and debugging).

    Attributes
    ----------
    source : VolumeInput
    features : Features
    thickness, lam : float
        Values used (physical units).
    medial : MedialVoxels
    mesh : Polygonization
        The sub-sampled mesh before dent removal and extension.
    result : MedialAxis
    timings : dict of str to float
        Seconds per stage.
    steps : dict of str to MedialAxis
        The axis after each stage, for viewing: ``"medial_voxels"`` (points
        only), ``"polygonized"``, ``"dents_removed"`` and ``"extended"`` (the
        result).
    """

    source: VolumeInput
    features: Features
    thickness: float
    lam: float
    medial: MedialVoxels
    mesh: Polygonization
    result: MedialAxis
    timings: dict[str, float]
    steps: dict[str, MedialAxis] = dataclasses.field(default_factory=dict)


def iso_of(iso: Any, threshold: Any) -> Any:
    """The iso level given as ``iso`` or ``threshold`` (they must agree)."""
    if iso is not None and threshold is not None and float(iso) != float(threshold):
        raise InvalidInputError(f"iso={iso!r} and threshold={threshold!r} disagree; give one")
    return iso if iso is not None else threshold


def thickness_and_lam(features: Features, thickness: Any, lam: Any) -> tuple[PlateThickness, float | None]:
    """The plate thickness (one value, or per plate) and ``lam`` (``None``: per plate)."""
    deepest = 2.0 * float(features.distance.max()) + float(features.spacing.max())
    lam_value = None if lam is None else check_number(lam, "lam", positive=True)
    if thickness is None or isinstance(thickness, (tuple, list, np.ndarray)):
        lower, upper = (None, np.inf) if thickness is None else check_range(thickness)
        plates = plate_thickness(features, lower, upper)
        if lam_value is None and not plates.local:  # one plate thickness: lam as for a nominal one
            lam_value = DEFAULT_LAM_RATIO * plates.value
        return plates, lam_value
    thickness_value = check_number(thickness, "thickness", positive=True)
    if thickness_value > 2.0 * deepest:
        raise InvalidInputError(
            f"thickness={thickness_value:g} does not fit: the thickest part of the volume is about {deepest:.3g}"
        )
    if thickness_value < 2.0 * float(features.spacing.max()):
        raise InvalidInputError(
            f"thickness={thickness_value:g} is under 2 voxels ({2 * float(features.spacing.max()):g}); "
            "plates that thin cannot be resolved"
        )
    if lam_value is None:
        lam_value = DEFAULT_LAM_RATIO * thickness_value
    return PlateThickness(thickness_value, lam_value, np.inf), lam_value


def volume_stages(
    volume: Any,
    *,
    iso: float | None = None,
    threshold: float | None = None,
    thickness: float | None = None,
    lam: float | None = None,
    spacing: Any = None,
    extend: bool = True,
    remove_dents: bool = True,
    density: float = 1.0,
    rng: Any = 0,
    raw_shape: Any = None,
    raw_dtype: Any = None,
    callback: Callable[[str], Any] | None = None,
    show_progress: bool | None = None,
) -> VolumeStages:
    """Run the mid-surface pipeline and keep every stage.

    Parameters are those of :func:`midsurface_medial_axis`.

    Returns
    -------
    VolumeStages
    """
    timings: dict[str, float] = {}
    density = check_number(density, "density", positive=True)
    stages = ["binarize", "distance", "medial voxels", "polygonize", "dents", "extension"]
    state: dict[str, Any] = {}
    for step, stage in enumerate(progress(stages, desc="mid-surface", show=show_progress)):
        check_cancel(callback, Progress("midsurface", stage, step, len(stages)))
        t0 = time.perf_counter()
        if stage == "binarize":
            state["source"] = load_volume(volume, iso=iso_of(iso, threshold), spacing=spacing, raw_shape=raw_shape, raw_dtype=raw_dtype)
        elif stage == "distance":
            state["features"] = feature_transform(state["source"])
            state["plates"], state["lam"] = thickness_and_lam(state["features"], thickness, lam)
            state["thickness"] = state["plates"].value
        elif stage == "medial voxels":
            state["medial"] = medial_voxels(state["features"], state["lam"], state["plates"])
            state["dropped"] = dropped_report(state["medial"], state["plates"], state["lam"])
        elif stage == "polygonize":
            state["grid"] = state["features"]
            polygonize_stage(state, density, rng)
        elif stage == "dents":
            dents_stage(state, remove_dents)
        elif stage == "extension" and extend:
            src = state["source"]
            extension_stage(state, src.grey, src.iso, src.spacing, density)
        timings[stage] = time.perf_counter() - t0
    src = state["source"]
    metadata = stage_metadata("midsurface", src.iso, state["plates"], state["lam"], state["dropped"], src.spacing,
                              src.mask.shape, threshold_method=src.threshold_method)
    metadata.update({"extend": bool(extend), "remove_dents": bool(remove_dents), "density": density})
    t0 = time.perf_counter()
    shell = isosurface_shell(src)
    timings["shell"] = time.perf_counter() - t0
    metadata["timings"] = timings
    result, steps = assemble(state, metadata, shell)
    return VolumeStages(src, state["features"], state["thickness"], state["lam"], state["medial"], state["mesh"], result,
                        timings, steps)


def midsurface_medial_axis(
    volume: Any,
    *,
    iso: float | None = None,
    threshold: float | None = None,
    thickness: float | None = None,
    lam: float | None = None,
    spacing: Any = None,
    extend: bool = True,
    remove_dents: bool = True,
    density: float = 1.0,
    rng: Any = 0,
    raw_shape: Any = None,
    raw_dtype: Any = None,
    chunks: Any = None,
    scheduler: Any = None,
    n_jobs: int | None = None,
    callback: Callable[[str], Any] | None = None,
    show_progress: bool | None = None,
    out: Any = None,
    spill: Any = None,
) -> MedialAxis:
    """Mid-surface of a thin-plate volume as a triangle mesh with thickness.

    Implements Kumar, Michikawa and Suzuki, "Improving medial surfaces for
    reverse engineering" (paper 002): medial voxels (Prohaska and Hege),
    sub-sampling polygonization (Michikawa and Suzuki), extension of the
    shrunk free edges to the isosurface and dent removal at junctions by
    their eq. (1).

    Parameters
    ----------
    volume : (Z, Y, X) array_like, str or path
        Bool mask or grey values, or a volume file / folder (NRRD, NIfTI,
        TIFF stack, DICOM series, ``.npy``, ``.raw`` with ``raw_shape``/``raw_dtype``).
        Never modified.
    iso, threshold : float, optional
        Foreground is ``grey > iso`` (``threshold`` is the dispatcher's name
        for it). Default 0.5 for bool input, else ISO-50: half-way between
        the background and material peaks of the grey-value histogram, or
        Otsu's class means where it has not two (:func:`~medialaxis.volume.inputs.iso50`).
    thickness : float or (min, max), optional
        Plate thickness (the paper's epsilon), physical units. Omitted: every
        plate at least 2 voxels (of the finest spacing) thick is kept, each
        judged by its own thickness, measured where adjacent voxels see the
        plate's two faces (a rib thinner than its wall keeps its
        mid-surface). A ``(min, max)`` range: the same, for plates of
        thickness in the range (``max`` may be ``inf``). A number: one
        nominal thickness for the whole part, as in the paper. Plates left
        out by a number or a range are reported in ``metadata["dropped"]``
        and by a :class:`~medialaxis.MedialAxisWarning`.
    lam : float, optional
        Lambda of the grid lambda-medial axis: adjacent voxels whose nearest
        boundary points are more than ``lam`` apart are medial. Default
        ``0.75`` times the thickness (of each plate, or the nominal one),
        which keeps plates and drops the branches into convex edges.
    spacing : float or 3 floats, optional
        Voxel size per array axis (default: the file's, else 1).
    extend : bool
        Extend the free edges to the isosurface.
    remove_dents : bool
        Move junction vertices by eq. (1).
    density : float
        Vertex spacing in units of the local half thickness.
    rng : seed or numpy Generator
        Order of the sub-sampling within a class (reproducible per seed).
    raw_shape, raw_dtype : optional
        Array shape ``(Z, Y, X)`` and dtype of a ``.raw`` file.
    chunks : int or 3 ints, optional
        Block size of the chunked route (:mod:`~medialaxis.volume.chunked`),
        for volumes larger than memory: the volume is read and processed a
        block at a time, each with a halo (see below); the medial voxels of
        each block wait in a folder (``spill``). Default: blocks of 256 for a Dask or Zarr array,
        with a cluster ``scheduler``, or above 2^27 voxels (512^3); ``0``
        keeps the whole volume in memory. The medial voxels are identical to
        the in-memory route's, and so is the mesh: each block meshes a window
        of the sheet around it and keeps what it owns, vertices named by
        their voxel, so the pieces join without seams.

        The halo is chosen from the part: without a thickness, a first pass
        measures the deepest voxel ``D`` (half the thickest plate); the halo
        is ``D`` plus two voxels (the medial test of a core voxel uses its
        neighbours' nearest boundary points, which must be inside the read
        box), or ``3 D`` plus four voxels when plates of several nominal
        thicknesses are labelled; with a number ``thickness``, half of it
        plus three voxels. Every block checks that each voxel its answer
        depends on is nearer to a boundary point it read than to the sides
        of its box, and reads itself again with a doubled halo where not.
        The mesh stages read a window of the neighbouring blocks' medial
        voxels, wider where the picks near the core are not provably the
        whole sheet's (``metadata["mesh_halo"]``).
        Accepted sources: arrays, ``dask.array.Array``, Zarr arrays and
        stores, OME-Zarr images (level 0, or the level a path names),
        ``.npy`` and raw files (memory-mapped), NRRD (raw memory-mapped;
        gzip/bzip2 decompressed once to a temporary file), NIfTI, TIFF
        stacks and folders (page by page).
    scheduler : None, "threads", "synchronous", dask Client or str
        Where the blocks run: local threads (default), one thread, or a Dask
        cluster (a ``Client`` or an address such as ``"tcp://host:8786"``;
        its workers must see the input file). Implies the chunked route.
    n_jobs : int, optional
        Local worker threads of the chunked route (default: all CPUs).
    callback : callable, optional
        Called with each stage name; returning ``False`` cancels.
    show_progress : bool, optional
        Progress bar on stderr (default: when stderr is a terminal).
    out : str or path, optional
        A ``.ply`` file or a ``.zarr`` group (arrays ``vertices``, ``faces``,
        ``radii``, ``vertex_kind``) for the mesh. The chunked route streams it
        there block by block (the mesh is never whole in one process) and
        returns a result without the mesh: ``metadata["written"]``,
        ``["vertices"]`` and ``["faces"]``; in memory the result is written
        and returned. A ``.ome.zarr`` path gets an OME-Zarr image of the wall thickness on the
        mid-surface's voxels, the mesh in its group ``mesh`` (:mod:`~medialaxis.volume.ome_zarr`).
    spill : str or path, optional
        Folder for the blocks' medial voxels and mesh pieces of the chunked
        route (default: the temporary folder; on a cluster of several
        machines, a folder every worker sees).

    Returns
    -------
    MedialAxis
        ``points (n, 3)`` in index order times ``spacing``; ``faces (k, 3)``
        (non-manifold along junctions); ``edges`` the faces' edges;
        ``radii`` half the local thickness; extras ``thickness (n,)`` and
        ``vertex_kind (n,)`` (0 surface, 1 free edge, 2 junction, 3 extension).
        ``metadata``: ``iso`` and ``threshold_method`` (``"peaks"``,
        ``"otsu"``, ``"given"`` or ``"mask"``), ``thickness`` (the nominal one, or the median of the
        plates kept), ``thickness_range`` (``[min, max]``, ``None`` for no
        bound; ``None`` for a nominal thickness), ``lam`` (``None``: per
        plate) and ``dropped`` (``None``, or the ``fraction`` of the plate
        area left out and its median ``thickness``).

    Raises
    ------
    InvalidInputError
        Not a 3D array, NaN, bad ``iso``/``spacing``/``lam``/``density``, a
        thickness that does not fit the volume, a range that is not
        ``0 < min < max``.
    EmptyShapeError
        Empty or full volume, no plate in the thickness range, or nothing medial.
    InputFileError
        Unreadable or truncated file.
    Cancelled
        Interrupted, or the callback returned ``False``.

    Examples
    --------
    >>> import numpy as np, medialaxis as mx
    >>> v = np.zeros((20, 40, 40), bool); v[7:13, 5:35, 5:35] = True
    >>> ma = mx.medial_axis(v, method="midsurface")
    >>> round(float(np.median(2 * ma.radii)), 1), ma.n_components
    (6.0, 1)
    >>> bool(np.allclose(ma.points[:, 0], 9.5))
    True
    """
    sizes = use_chunks(volume, chunks, scheduler, raw_shape, raw_dtype)
    if sizes is not None:
        return chunked_midsurface(
            volume, chunks=sizes, iso=iso_of(iso, threshold), thickness=thickness, lam=lam, spacing=spacing, extend=extend,
            remove_dents=remove_dents, density=density, rng=rng, raw_shape=raw_shape, raw_dtype=raw_dtype,
            scheduler=scheduler, n_jobs=n_jobs, callback=callback, show_progress=show_progress, out=out, spill=spill,
        )
    check_out(out)
    stages = volume_stages(
        volume, iso=iso, threshold=threshold, thickness=thickness, lam=lam, spacing=spacing, extend=extend,
        remove_dents=remove_dents, density=density, rng=rng, raw_shape=raw_shape, raw_dtype=raw_dtype, callback=callback,
        show_progress=show_progress,
    )
    result = stages.result
    if out is not None:
        if is_ome_zarr_out(out):
            write_in_memory(out, stages)
        elif Path(out).suffix.lower() == ".zarr":
            write_zarr_mesh(out, result.points, result.radii, result.vertex_kind, result.faces)
        else:
            result.save(out)
    return result
