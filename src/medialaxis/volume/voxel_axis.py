"""The medial voxels of a volume (``method="voxels"``): the grid lambda-medial axis of
:mod:`~medialaxis.volume.medial`, each voxel classed as sheet, free edge or junction
(:mod:`~medialaxis.volume.regions`), whole or by blocks (:mod:`~medialaxis.volume.chunked`)."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

from medialaxis._progress import Progress, check_cancel
from medialaxis.core.result import MedialAxis
from medialaxis.volume.chunked import chunked_voxels, use_chunks
from medialaxis.volume.distance import feature_transform
from medialaxis.volume.inputs import load_volume
from medialaxis.volume.medial import medial_voxels
from medialaxis.volume.pipeline import iso_of, thickness_and_lam
from medialaxis.volume.regions import VOXEL_KINDS, classify_voxels
from medialaxis.volume.shell import isosurface_shell
from medialaxis.volume.stages import dropped_report, stage_metadata
from medialaxis.volume.voxel_table import voxel_table

__all__ = ["medial_voxel_axis", "STAGES"]

#: The stages the callback hears of, in order (the whole volume at once).
STAGES = ("binarize", "distance", "medial voxels", "classify")


def medial_voxel_axis(
    volume: Any,
    *,
    iso: float | None = None,
    threshold: float | None = None,
    thickness: float | None = None,
    lam: float | None = None,
    spacing: Any = None,
    raw_shape: Any = None,
    raw_dtype: Any = None,
    chunks: Any = None,
    scheduler: Any = None,
    n_jobs: int | None = None,
    callback: Callable[[Progress], Any] | None = None,
    show_progress: bool | None = None,
) -> MedialAxis:
    """The medial voxels themselves (``method="voxels"``): points and radii, no faces.

    Parameters are as :func:`~medialaxis.volume.pipeline.midsurface_medial_axis`;
    the chunked route (``chunks``, ``scheduler``) gives the same voxels.
    ``callback(Progress)`` runs before each stage (``"binarize"``,
    ``"distance"``, ``"medial voxels"``, ``"classify"``; the chunked route's
    passes and blocks); returning ``False`` cancels.

    Returns
    -------
    MedialAxis
        ``points (n, 3)``: voxel centres (index times ``spacing``); ``radii``:
        half the distance between the two nearest boundary points; extras
        ``position (n, 3)`` (sub-voxel mid-point), ``normal (n, 3)`` and
        ``voxel_kind (n,)`` (0 surface, 1 free edge, 2 junction); metadata
        as :func:`midsurface_medial_axis`.

    Examples
    --------
    >>> import numpy as np, medialaxis as mx
    >>> v = np.zeros((20, 30, 30), bool); v[7:13, 5:25, 5:25] = True
    >>> ma = mx.medial_axis(v, method="voxels")
    >>> len(ma.faces), sorted(set(ma.points[:, 0].tolist()))
    (0, [9.0])
    """
    sizes = use_chunks(volume, chunks, scheduler, raw_shape, raw_dtype)
    if sizes is not None:
        return chunked_voxels(volume, chunks=sizes, iso=iso_of(iso, threshold), thickness=thickness, lam=lam,
                              spacing=spacing, raw_shape=raw_shape, raw_dtype=raw_dtype, scheduler=scheduler,
                              n_jobs=n_jobs, callback=callback, show_progress=show_progress)
    started = time.perf_counter()

    def stage(step: int, name: str) -> None:
        check_cancel(callback, Progress("voxels", name, step, len(STAGES)))

    stage(0, STAGES[0])
    src = load_volume(volume, iso=iso_of(iso, threshold), spacing=spacing, raw_shape=raw_shape, raw_dtype=raw_dtype)
    stage(1, STAGES[1])
    features = feature_transform(src)
    plates, lam_value = thickness_and_lam(features, thickness, lam)
    stage(2, STAGES[2])
    medial = medial_voxels(features, lam_value, plates)
    dropped = dropped_report(medial, plates, lam_value)
    stage(3, STAGES[3])
    kind = classify_voxels(voxel_table(medial.voxels, features.index.shape), medial.voxels)
    metadata = stage_metadata("voxels", src.iso, plates, lam_value, dropped, src.spacing, src.mask.shape,
                              threshold_method=src.threshold_method)
    metadata.update(voxel_kinds=VOXEL_KINDS, timings={"total": time.perf_counter() - started})
    return MedialAxis(
        features.physical(medial.voxels), medial.radius,
        extras={"position": medial.position, "normal": medial.normal, "voxel_kind": kind},
        metadata=metadata, shape=isosurface_shell(src),
    )
