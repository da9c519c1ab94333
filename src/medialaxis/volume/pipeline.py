"""Mid-surfaces of thin-plate CT volumes (Kumar, Michikawa and Suzuki; docs/references.md).

Stages (each kept by :func:`volume_stages`):

1. binarize at ``iso`` (:mod:`~medialaxis.volume.inputs`);
2. sub-voxel boundary and nearest-boundary transform (:mod:`~medialaxis.volume.distance`);
3. plate thickness (:mod:`~medialaxis.volume.plates`) and medial voxels, the grid
   lambda-medial axis (:mod:`~medialaxis.volume.medial`);
4. sub-sampling polygonization (:mod:`~medialaxis.volume.sheet.polygonize`);
5. dent removal at junctions, eq. (1) (:mod:`~medialaxis.volume.sheet.dents`);
6. extension of the free edges to the isosurface (:mod:`~medialaxis.volume.sheet.extension`).

Stages 4-6 are :mod:`~medialaxis.volume.sheet.stages`, shared with the route for volumes
larger than memory (:mod:`~medialaxis.volume.blockwise.chunked`), which the public functions
take by themselves for large inputs.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis._progress import Progress, StageClock
from medialaxis.core.options import make_options, takes_options
from medialaxis.core.result import MedialAxis
from medialaxis.core.validate import check_number
from medialaxis.errors import InvalidInputError
from medialaxis.volume.blockwise.chunked import check_out, chunked_midsurface, use_chunks
from medialaxis.volume.blockwise.stitch import write_zarr_mesh
from medialaxis.volume.distance import Features, feature_transform
from medialaxis.volume.files.ome_zarr import is_ome_zarr_out, write_in_memory
from medialaxis.volume.inputs import VolumeInput, load_volume
from medialaxis.volume.medial import DEFAULT_LAM_RATIO, MedialVoxels, medial_voxels
from medialaxis.volume.options import MidsurfaceOptions, VoxelOptions
from medialaxis.volume.plates import PlateThickness, plate_thickness
from medialaxis.volume.sheet.polygonize import Polygonization
from medialaxis.volume.sheet.stages import (
    MedialStage,
    assemble,
    check_range,
    dents_stage,
    dropped_report,
    extension_stage,
    polygonize_stage,
    stage_metadata,
)
from medialaxis.volume.shell import isosurface_shell

__all__ = ["midsurface_medial_axis", "volume_stages", "VolumeStages", "iso_of", "thickness_and_lam", "medial_stages",
           "block_options", "STAGES"]

#: The stages the callback hears of, in order (the whole volume in memory).
STAGES = ("binarize", "distance", "medial voxels", "polygonize", "dents", "extension")


@dataclasses.dataclass(frozen=True)
class VolumeStages:
    """Every intermediate of one run (for ``--steps`` and debugging).

    Attributes
    ----------
    source : VolumeInput
    features : Features
    thickness : float
        The nominal plate thickness, or the median of the plates kept (physical units).
    lam : float or None
        The lambda used (physical units); None: each plate's own.
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
    lam: float | None
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


def block_options(opts: VoxelOptions) -> dict[str, Any]:
    """The keywords of the chunked route for ``opts``: ``iso`` from ``iso`` or ``threshold``, the rest as given
    (the block size is decided apart, by :func:`~medialaxis.volume.blockwise.chunked.use_chunks`)."""
    given = {k: v for k, v in vars(opts).items() if k not in ("iso", "threshold", "chunks")}
    return dict(given, iso=iso_of(opts.iso, opts.threshold))


def medial_stages(volume: Any, opts: VoxelOptions, clock: StageClock) -> tuple[VolumeInput, MedialStage, Any]:
    """The stages both volume methods share, whole in memory: binarize, distance, medial voxels.

    Returns the loaded volume, its medial voxels with their grid, plates and
    lambda, and what the medial test left out (:func:`dropped_report`).
    """
    with clock("binarize"):
        src = load_volume(volume, iso=iso_of(opts.iso, opts.threshold), spacing=opts.spacing, raw_shape=opts.raw_shape,
                          raw_dtype=opts.raw_dtype)
    with clock("distance"):
        features = feature_transform(src)
        plates, lam = thickness_and_lam(features, opts.thickness, opts.lam)
    with clock("medial voxels"):
        medial = medial_voxels(features, lam, plates)
        dropped = dropped_report(medial, plates, lam)
    return src, MedialStage(medial, features, plates, lam), dropped


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


@takes_options(MidsurfaceOptions)
def volume_stages(
    volume: Any, options: MidsurfaceOptions | None = None, *, callback: Callable[[Progress], Any] | None = None,
    **kwargs: Any,
) -> VolumeStages:
    """Run the mid-surface pipeline on the whole volume in memory and keep every stage.

    The options of the chunked route (``chunks``, ``scheduler``, ``n_jobs``,
    ``spill``) and ``out`` do not apply.

    Parameters
    ----------
    volume : (Z, Y, X) array_like, str or path
        As :func:`midsurface_medial_axis` takes it.
    callback : callable, optional
        As :func:`midsurface_medial_axis` calls it.
    {options}

    Returns
    -------
    VolumeStages
    """
    opts = make_options(MidsurfaceOptions, options, kwargs, "volume_stages")
    chunked = [k for k in ("chunks", "scheduler", "n_jobs", "out", "spill") if getattr(opts, k) is not None]
    if chunked:
        raise InvalidInputError(f"the stages are kept whole in memory: {', '.join(chunked)} do not apply")
    density = check_number(opts.density, "density", positive=True)
    clock = StageClock("midsurface", STAGES, callback, opts.show_progress, desc="mid-surface")
    src, stage, dropped = medial_stages(volume, opts, clock)
    with clock("polygonize"):
        sheet = polygonize_stage(stage, density, opts.rng)
    with clock("dents"):
        sheet = dents_stage(stage, sheet, opts.remove_dents)
    with clock("extension"):
        if opts.extend:
            sheet = extension_stage(stage, sheet, src.grey, src.iso, src.spacing, density)
    metadata = stage_metadata("midsurface", src.iso, stage.plates, stage.lam, dropped, src.spacing, src.mask.shape,
                              threshold_method=src.threshold_method)
    metadata.update({"extend": bool(opts.extend), "remove_dents": bool(opts.remove_dents), "density": density})
    timings = clock.timings
    t0 = time.perf_counter()
    shell = isosurface_shell(src)
    timings["shell"] = time.perf_counter() - t0
    metadata["timings"] = timings
    result, steps = assemble(stage, sheet, metadata, shell)
    return VolumeStages(src, stage.grid, stage.thickness, stage.lam, stage.medial, sheet.mesh, result, timings, steps)


@takes_options(MidsurfaceOptions)
def midsurface_medial_axis(
    volume: Any, options: MidsurfaceOptions | None = None, *, callback: Callable[[Progress], Any] | None = None,
    **kwargs: Any,
) -> MedialAxis:
    """Mid-surface of a thin-plate volume as a triangle mesh with thickness.

    Implements Kumar, Michikawa and Suzuki, "Improving medial surfaces for
    reverse engineering" [1]_: medial voxels (Prohaska and Hege [2]_),
    sub-sampling polygonization (Michikawa and Suzuki), extension of the
    shrunk free edges to the isosurface and dent removal at junctions by
    their eq. (1).

    Parameters
    ----------
    volume : (Z, Y, X) array_like, str or path
        Bool mask or grey values, or a volume file / folder (NRRD, NIfTI,
        TIFF stack, DICOM series, ``.npy``, ``.raw`` with ``raw_shape``/``raw_dtype``).
        Never modified.
    callback : callable, optional
        ``callback(Progress)`` before each stage (``"binarize"``,
        ``"distance"``, ``"medial voxels"``, ``"polygonize"``, ``"dents"``,
        ``"extension"``; the chunked route's passes and blocks); returning
        ``False`` cancels.
    {options}
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

    References
    ----------
    .. [1] V. Kumar, T. Michikawa, H. Suzuki, "Improving medial surfaces for reverse
           engineering" (venue, year and DOI unconfirmed: docs/references.md).
    .. [2] S. Prohaska, H.-C. Hege, "Fast visualization of plane-like structures in voxel
           data", Proc. IEEE Visualization 2002, 29-36, 2002. doi:10.1109/VISUAL.2002.1183753
    .. [3] T. Michikawa, H. Suzuki, "Polygonization of volumetric skeletons with junctions",
           Computer-Aided Design 45(4):822-828, 2013. doi:10.1016/j.cad.2011.06.003

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
    opts = make_options(MidsurfaceOptions, options, kwargs, "midsurface_medial_axis")
    sizes = use_chunks(volume, opts.chunks, opts.scheduler, opts.raw_shape, opts.raw_dtype)
    if sizes is not None:
        return chunked_midsurface(volume, chunks=sizes, callback=callback, **block_options(opts))
    check_out(opts.out)
    stages = volume_stages(volume, dataclasses.replace(opts, out=None, spill=None, chunks=None, scheduler=None,
                                                       n_jobs=None), callback=callback)
    out = opts.out
    result = stages.result
    if out is not None:
        if is_ome_zarr_out(out):
            write_in_memory(out, stages)
        elif Path(out).suffix.lower() == ".zarr":
            write_zarr_mesh(out, result.points, result.radii, result.vertex_kind, result.faces)
        else:
            result.save(out)
    return result
