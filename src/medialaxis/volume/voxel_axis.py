"""The medial voxels of a volume (``method="voxels"``): the grid lambda-medial axis of
:mod:`~medialaxis.volume.medial`, each voxel classed as sheet, free edge or junction
(:mod:`~medialaxis.volume.regions`), whole or by blocks (:mod:`~medialaxis.volume.blockwise.chunked`)."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

from medialaxis._progress import Progress, StageClock
from medialaxis.core.options import make_options, takes_options
from medialaxis.core.result import MedialAxis
from medialaxis.volume.blockwise.chunked import chunked_voxels, use_chunks
from medialaxis.volume.options import VoxelOptions
from medialaxis.volume.pipeline import block_options, medial_stages
from medialaxis.volume.regions import VOXEL_KINDS, classify_voxels
from medialaxis.volume.sheet.stages import stage_metadata
from medialaxis.volume.shell import isosurface_shell
from medialaxis.volume.voxel_table import voxel_table

__all__ = ["medial_voxel_axis", "STAGES"]

#: The stages the callback hears of, in order (the whole volume at once).
STAGES = ("binarize", "distance", "medial voxels", "classify")


@takes_options(VoxelOptions)
def medial_voxel_axis(
    volume: Any, options: VoxelOptions | None = None, *, callback: Callable[[Progress], Any] | None = None,
    **kwargs: Any,
) -> MedialAxis:
    """The medial voxels themselves (``method="voxels"``): points and radii, no faces.

    The chunked route (``chunks``, ``scheduler``) gives the same voxels.

    Parameters
    ----------
    volume : (Z, Y, X) array_like, str or path
        As :func:`~medialaxis.volume.pipeline.midsurface_medial_axis` takes it.
    callback : callable, optional
        ``callback(Progress)`` before each stage (``"binarize"``,
        ``"distance"``, ``"medial voxels"``, ``"classify"``; the chunked
        route's passes and blocks); returning ``False`` cancels.
    {options}

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
    opts = make_options(VoxelOptions, options, kwargs, "medial_voxel_axis")
    sizes = use_chunks(volume, opts.chunks, opts.scheduler, opts.raw_shape, opts.raw_dtype)
    if sizes is not None:
        return chunked_voxels(volume, chunks=sizes, callback=callback, **block_options(opts))
    started = time.perf_counter()
    clock = StageClock("voxels", STAGES, callback, opts.show_progress)
    src, stage, dropped = medial_stages(volume, opts, clock)
    medial, features = stage.medial, stage.grid
    with clock("classify"):
        kind = classify_voxels(voxel_table(medial.voxels, features.index.shape), medial.voxels)
    metadata = stage_metadata("voxels", src.iso, stage.plates, stage.lam, dropped, src.spacing, src.mask.shape,
                              threshold_method=src.threshold_method)
    metadata.update(voxel_kinds=VOXEL_KINDS, timings=dict(clock.timings, total=time.perf_counter() - started))
    return MedialAxis(
        features.physical(medial.voxels), medial.radius,
        extras={"position": medial.position, "normal": medial.normal, "voxel_kind": kind},
        metadata=metadata, shape=isosurface_shell(src),
    )
