"""Mid-surfaces of volumes larger than memory: the pipeline block by block.

The volume is cut into blocks of ``chunks`` voxels (:mod:`~medialaxis.volume.blocks`),
each read with a halo from its source (:mod:`~medialaxis.volume.sources`),
on local threads or a Dask cluster (:func:`~medialaxis.core.parallel.run_tasks`).
Passes over the blocks:

1. the iso value, when not given: exact value counts of 8 and 16-bit scans
   (or a 256-bin histogram of float scans, their class sums only without two peaks) give the ISO-50
   value the whole array gives (:func:`~medialaxis.volume.inputs.iso50_counts`, ``iso50_histogram``);
2. one read per block: the lengths of its plate-crossing pairs, its deepest
   voxel, its foreground box and its candidate medial pairs
   (:func:`~medialaxis.volume.blocks.scan_block`). The part-wide plate
   thickness then gives ``lam``, and each block's pairs give its medial
   voxels (:func:`~medialaxis.volume.blocks.finish_block`), identical to the
   in-memory route's. With a number ``thickness`` the blocks mark their
   medial voxels at once; a part with several nominal thicknesses reads each
   block again to label its plates (:func:`~medialaxis.volume.blocks.medial_block`).

The medial voxels are a thin sheet (a few per thousand voxels of a thin-plate
part); gathered, they are polygonized, their dents removed and their free
edges extended to the isosurface as one mesh
(:func:`~medialaxis.volume.stages.polygonize_stage` and the stages after
it), so the mesh has no seams at all. The extension rays read the grey
values around their ends block by block.

Memory: each running block holds its box (chunk plus halo) at about 40 bytes
per voxel plus the per-voxel arrays of its foreground. What grows with the
part is the sheet: the candidate pairs wait in a temporary folder (local
runs; in the client's memory on a cluster, about 130 bytes per marked voxel)
and the gathered medial voxels take about 100 bytes each, their
polygonization about 170 more.
"""

from __future__ import annotations

import math
import os
import shutil
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis._progress import check_cancel
from medialaxis.core.parallel import check_jobs, check_scheduler, run_tasks
from medialaxis.core.result import MedialAxis
from medialaxis.core.scene3d import Surface
from medialaxis.core.validate import check_finite, check_number
from medialaxis.errors import EmptyShapeError, InvalidInputError
from medialaxis.volume.blocks import (
    Block,
    BlockSampler,
    block_grid,
    finish_block,
    halo_voxels,
    medial_block,
    scan_block,
)
from medialaxis.volume.distance import Grid
from medialaxis.volume.inputs import (
    HISTOGRAM_BINS,
    VolumeInput,
    check_spacing,
    counted,
    iso50_counts,
    iso50_histogram,
    value_counts,
)
from medialaxis.volume.medial import DEFAULT_LAM_RATIO, MedialVoxels
from medialaxis.volume.plates import DEFAULT_MIN_THICKNESS, PlateThickness, nominal_thicknesses, plate_summary
from medialaxis.volume.sources import Source, is_zarr_folder, open_source
from medialaxis.volume.stages import (
    assemble,
    check_range,
    dents_stage,
    dropped_report,
    extension_stage,
    polygonize_stage,
    stage_metadata,
)

__all__ = ["DEFAULT_CHUNK", "CHUNKED_VOXELS", "check_chunks", "chunked_medial_voxels", "chunked_midsurface",
           "chunked_voxels", "use_chunks"]

#: Block edge (voxels) when the chunked route is taken by size.
DEFAULT_CHUNK = 256
#: Volumes of more voxels take the chunked route unless ``chunks=0``.
CHUNKED_VOXELS = 1 << 27
#: Smallest block edge: smaller blocks spend more on their halos than on their cores.
MIN_CHUNK = 16
#: Halo of the first pass (voxels), grown per block where the part is thicker.
FIRST_HALO = 8


def check_chunks(chunks: Any) -> tuple[int, int, int] | None:
    """``chunks`` as three block edges, or None (``None``: decide by size; ``0``/``False``: in memory)."""
    if chunks is None:
        return None
    if chunks is False or (isinstance(chunks, (int, np.integer)) and not isinstance(chunks, bool) and chunks == 0):
        return (0, 0, 0)
    try:
        sizes = (int(chunks),) * 3 if np.ndim(chunks) == 0 else tuple(int(c) for c in chunks)
    except (TypeError, ValueError):
        raise InvalidInputError(f"chunks must be a block size or 3 block sizes, got {chunks!r}") from None
    if isinstance(chunks, bool) or len(sizes) != 3 or min(sizes) < MIN_CHUNK:
        raise InvalidInputError(f"chunks must be one or three sizes of at least {MIN_CHUNK} voxels (or 0), got {chunks!r}")
    return sizes  # type: ignore[return-value]


def use_chunks(volume: Any, chunks: Any, scheduler: Any, raw_shape: Any = None, raw_dtype: Any = None) -> tuple[int, int, int] | None:
    """The block size when ``volume`` takes the chunked route, else None.

    Given ``chunks`` decide (0: in memory); otherwise a Dask or Zarr array or
    store, a cluster ``scheduler`` or more than :data:`CHUNKED_VOXELS` voxels take it with
    blocks of :data:`DEFAULT_CHUNK`.
    """
    sizes = check_chunks(chunks)
    if sizes is not None:
        return None if sizes == (0, 0, 0) else sizes
    if scheduler not in (None, "threads", "synchronous"):
        return (DEFAULT_CHUNK,) * 3
    module = type(volume).__module__ or ""
    if module.startswith(("dask", "zarr")):
        return (DEFAULT_CHUNK,) * 3
    shape = getattr(volume, "shape", None)
    if isinstance(volume, (str, os.PathLike)) and is_zarr_folder(Path(volume)):
        return (DEFAULT_CHUNK,) * 3  # only the block reader reads Zarr stores
    if shape is None and isinstance(volume, (str, os.PathLike)):
        try:
            shape = open_source(volume, raw_shape=raw_shape, raw_dtype=raw_dtype, header_only=True).shape
        except Exception:  # noqa: BLE001 - formats without a block reader are read whole
            return None
    if shape is not None and len(shape) == 3 and math.prod(int(s) for s in shape) > CHUNKED_VOXELS:
        return (DEFAULT_CHUNK,) * 3
    return None


def _value_counts(block: Block, source: Source) -> np.ndarray:
    values, counts = value_counts(source.read(block.region))
    return np.stack([values, counts.astype(np.float64)])


def _range(block: Block, source: Source) -> tuple[float, float]:
    grey = np.asarray(source.read(block.region), np.float32)
    if not np.all(np.isfinite(grey)):
        raise InvalidInputError(f"the volume contains NaN or infinite values (in the block at {block.lo} of {source.name})")
    return float(grey.min()), float(grey.max())


def _histogram(block: Block, source: Source, lo: float, hi: float) -> np.ndarray:
    grey = np.asarray(source.read(block.region), np.float32)
    return np.histogram(grey, bins=HISTOGRAM_BINS, range=(lo, hi))[0]


def _class_sums(block: Block, source: Source, t: float) -> np.ndarray:
    grey = np.asarray(source.read(block.region), np.float32)
    low = grey <= t
    return np.array([grey[low].sum(dtype=np.float64), low.sum(), grey[~low].sum(dtype=np.float64), (~low).sum()])


def _iso(source: Source, blocks: list[Block], iso: Any, run: Callable[..., list[Any]]) -> tuple[float, float, str]:
    """The iso value (ISO-50 when not given), the smallest grey value (NaN when not read), ``threshold_method``."""
    if iso is not None:
        return check_finite(iso, "iso"), math.nan, "given"
    if source.dtype == bool:
        return 0.5, 0.0, "mask"
    if counted(source.dtype):
        tables = run(_value_counts, blocks, source, desc="grey values")
        values, inverse = np.unique(np.concatenate([t[0] for t in tables]), return_inverse=True)
        counts = np.bincount(inverse, np.concatenate([t[1] for t in tables]))
        if len(values) == 1:
            raise EmptyShapeError(f"the volume is constant ({values[0]:g}); nothing to threshold")
        found = iso50_counts(values, counts)
        return found.value, float(values[0]), found.method
    ranges = run(_range, blocks, source, desc="grey range")
    lo, hi = min(r[0] for r in ranges), max(r[1] for r in ranges)
    if lo == hi:
        raise EmptyShapeError(f"the volume is constant ({lo}); nothing to threshold")
    hist = np.sum(run(_histogram, blocks, source, lo, hi, desc="grey histogram"), axis=0)

    def class_means(t: float) -> tuple[float, float] | None:  # Otsu's fallback only: one more pass
        sums = np.sum(run(_class_sums, blocks, source, t, desc="grey classes"), axis=0)
        return None if sums[1] == 0 or sums[3] == 0 else (sums[0] / sums[1], sums[2] / sums[3])

    found = iso50_histogram(hist, lo, hi, class_means)
    return found.value, lo, found.method


def _plates(scans: list[Any], thickness: Any, lam: Any, spacing: np.ndarray) -> tuple[PlateThickness, float | None, np.ndarray | None]:
    """Part-wide plate thickness, ``lam`` and the nominal thicknesses (None: one thickness) from the first pass."""
    unit = float(spacing.min())
    lam_value = None if lam is None else check_number(lam, "lam", positive=True)
    if thickness is None:
        lower, upper = DEFAULT_MIN_THICKNESS * unit, np.inf
    else:
        lower, upper = check_range(thickness)
    gaps = np.concatenate([s.gaps for s in scans])
    plates = plate_summary(gaps, lower, upper, unit)
    nominal = nominal_thicknesses(gaps, lower, unit)
    if len(nominal) > 1:
        return plates, lam_value, nominal
    return plates, (DEFAULT_LAM_RATIO * plates.value if lam_value is None else lam_value), None


def _gather(parts: list[Any]) -> tuple[MedialVoxels, Grid | None, int]:
    """The blocks' medial voxels in the in-memory route's order, on the crop grid of the whole foreground."""
    boxes = [(p.lo, p.hi) for p in parts if p.lo is not None]
    foreground = sum(p.foreground for p in parts)
    if not boxes:
        return parts[0].medial, None, foreground
    lo = np.min([b[0] for b in boxes], axis=0) - 1
    hi = np.max([b[1] for b in boxes], axis=0) + 1
    m = [p.medial for p in parts]
    voxels = np.concatenate([x.voxels for x in m])
    order = np.lexsort((voxels[:, 2], voxels[:, 1], voxels[:, 0]))
    medial = MedialVoxels(
        voxels=voxels[order] - lo,
        position=np.concatenate([x.position for x in m])[order],
        radius=np.concatenate([x.radius for x in m])[order],
        normal=np.concatenate([x.normal for x in m])[order],
        distance=np.concatenate([x.distance for x in m])[order],
        coherence=np.concatenate([x.coherence for x in m])[order],
        sheet_pairs=sum(x.sheet_pairs for x in m),
        dropped_gaps=np.concatenate([x.dropped_gaps for x in m]),
    )
    return medial, Grid(lo, tuple(int(s) for s in hi - lo), np.zeros(3)), foreground  # spacing set by the caller


def chunked_medial_voxels(
    volume: Any, *, chunks: tuple[int, int, int], iso: Any = None, thickness: Any = None, lam: Any = None,
    spacing: Any = None, raw_shape: Any = None, raw_dtype: Any = None, scheduler: Any = None, n_jobs: int | None = None,
    callback: Callable[[str], Any] | None = None, show_progress: bool | None = None,
) -> dict[str, Any]:
    """Passes 1-3: the medial voxels of a volume, block by block.

    Returns a state dict with ``source``, ``iso``, ``threshold_method``, ``minimum``, ``spacing``,
    ``grid``, ``medial``, ``plates``, ``thickness``, ``lam``, ``chunks`` and ``halo``.
    """
    check_scheduler(scheduler)
    check_jobs(n_jobs)
    source = open_source(volume, raw_shape=raw_shape, raw_dtype=raw_dtype)
    folders: list[str | None] = []
    try:
        spacing = check_spacing(spacing, source.spacing)
        chunks = tuple(min(int(c), int(s)) for c, s in zip(chunks, source.shape))
        limit = int(max(chunks))
        blocks = block_grid(source.shape, chunks)  # type: ignore[arg-type]

        jobs = _local_jobs(n_jobs, chunks)

        def run(fn: Callable[..., Any], items: list[Any], *args: Any, desc: str) -> list[Any]:
            check_cancel(callback, desc)
            return run_tasks(fn, items, *args, scheduler=scheduler, n_jobs=jobs, desc=desc,
                             show_progress=show_progress, callback=callback)

        iso_value, minimum, threshold_method = _iso(source, blocks, iso, run)
        unit = float(spacing.min())
        if thickness is not None and not isinstance(thickness, (tuple, list, np.ndarray)):
            value = check_number(thickness, "thickness", positive=True)
            if value < 2.0 * float(spacing.max()):
                raise InvalidInputError(
                    f"thickness={value:g} is under 2 voxels ({2 * float(spacing.max()):g}); plates that thin cannot be resolved"
                )
            lam_value = DEFAULT_LAM_RATIO * value if lam is None else check_number(lam, "lam", positive=True)
            plates, nominal = PlateThickness(value, lam_value, np.inf), None
            halo = halo_voxels(0.5 * value + float(spacing.max()), spacing, False)
            _check_halo(halo, chunks, source.shape)
            parts = run(medial_block, blocks, source, iso_value, spacing, halo, lam_value, plates, None, limit,
                        desc="medial voxels")
        else:
            first = np.full(3, min(FIRST_HALO, limit), np.int64)
            lower = DEFAULT_MIN_THICKNESS * unit if thickness is None else float(thickness[0])
            shortest = 1.5 * unit if lam is None else min(check_number(lam, "lam", positive=True), 1.5 * unit)
            # local runs keep the first pass's pairs in a temporary folder, cluster runs in memory
            spill = tempfile.mkdtemp(prefix="medialaxis-pairs-") if scheduler in (None, "threads", "synchronous") else None
            folders.append(spill)
            scans = run(scan_block, blocks, source, iso_value, spacing, first, lower, shortest, limit, spill,
                        desc="medial voxels")
            _check_foreground(sum(s.foreground for s in scans), source, iso_value)
            plates, lam_value, nominal = _plates(scans, thickness, lam, spacing)
            depth = max(s.depth for s in scans)
            halo = halo_voxels(depth, spacing, nominal is not None)
            if nominal is None:  # one thickness: the first pass's pairs give the medial voxels
                parts = [finish_block(scan, lam_value, plates, unit) for scan in scans]
            else:  # several: each block labels its plates, reading itself again
                del scans
                _check_halo(halo, chunks, source.shape)
                parts = run(medial_block, blocks, source, iso_value, spacing, halo, lam_value, plates, nominal, limit,
                            depth, desc="plate labels")
        medial, grid, foreground = _gather(parts)
        _check_foreground(foreground, source, iso_value)
        if grid is None or len(medial.voxels) == 0:
            what = f"lam={lam_value:g}" if lam_value is not None else f"plates {plates.lower:g} to {plates.upper:g} thick"
            raise EmptyShapeError(f"no medial voxel for {what}: the thickness or lam is larger than the part allows")
        grid = Grid(grid.offset, grid.shape, spacing)
        if nominal is not None:  # marks the result as judged per plate (labels live in the blocks)
            plates = PlateThickness(plates.value, plates.lower, plates.upper, np.zeros(0), ranged=True)
        return {"source": source, "iso": iso_value, "threshold_method": threshold_method, "minimum": minimum,
                "spacing": spacing, "grid": grid, "medial": medial, "plates": plates, "thickness": plates.value,
                "lam": lam_value, "chunks": chunks, "halo": halo}
    except BaseException:
        _cleanup(source)
        raise
    finally:
        for folder in folders:
            if folder:
                shutil.rmtree(folder, ignore_errors=True)


#: Bytes per voxel of a block's read box at its peak (grey, mask, index, the
#: foreground's features and pairs), measured on the ribbed panel: a 256^3
#: block peaks at about 0.7 GiB.
BLOCK_BYTES_PER_VOXEL = 40


def _local_jobs(n_jobs: int | None, chunks: tuple[int, ...]) -> int | None:
    """Threads for local blocks: ``n_jobs``, or as many CPUs as there is memory for their blocks."""
    if n_jobs is not None:
        return n_jobs
    from medialaxis.core.validate import memory_budget

    per_block = BLOCK_BYTES_PER_VOXEL * math.prod(int(c) + 16 for c in chunks)
    return max(1, min(os.cpu_count() or 1, memory_budget() // (2 * per_block)))


def _check_halo(halo: np.ndarray, chunks: tuple[int, ...], shape: tuple[int, ...]) -> None:
    """Refuse blocks smaller than their halo along an axis they cut (they would read mostly halo)."""
    small = [k for k in range(3) if chunks[k] < shape[k] and halo[k] > chunks[k]]
    if small:
        raise InvalidInputError(
            f"chunks={tuple(chunks)} is smaller than the halo of {tuple(int(h) for h in halo)} voxels that the plates "
            f"of this part need; use chunks of at least {int(max(halo[k] for k in small))} along axis {small[0]}"
        )


def _check_foreground(count: int, source: Source, iso: float) -> None:
    if count == 0:
        raise EmptyShapeError(f"no voxel is above iso={iso:g}: the volume is empty")
    if count == math.prod(source.shape):
        raise EmptyShapeError(f"every voxel is above iso={iso:g}: the volume is full, the part has no surface")


def _cleanup(source: Source) -> None:
    folder = getattr(source, "cleanup", None)
    if folder:
        shutil.rmtree(folder, ignore_errors=True)


def shell_of_source(source: Source, iso: float, spacing: np.ndarray, cells: int = 128) -> Surface | None:
    """The isosurface of a large volume at the shell's step (every ``step``-th voxel, read slice by slice)."""
    from medialaxis.volume.shell import isosurface_shell

    step = max(1, math.ceil(max(source.shape) / cells))
    Z, Y, X = source.shape
    planes = [np.asarray(source.read((slice(z, z + 1), slice(0, Y), slice(0, X))), np.float32)[0, ::step, ::step]
              for z in range(0, Z, step)]
    grey = np.stack(planes)
    mask = grey > iso
    if not mask.any():
        return None
    return isosurface_shell(VolumeInput(grey, mask, iso, spacing * step), cells=max(grey.shape))


def chunked_midsurface(volume: Any, *, chunks: tuple[int, int, int], extend: bool = True, remove_dents: bool = True,
                       density: float = 1.0, rng: Any = 0, **options: Any) -> MedialAxis:
    """The mid-surface of a volume by blocks (options of :func:`chunked_medial_voxels`)."""

    density = check_number(density, "density", positive=True)
    state = chunked_medial_voxels(volume, chunks=chunks, **options)
    source = state["source"]
    try:
        state["dropped"] = dropped_report(state["medial"], state["plates"], state["lam"])
        callback = options.get("callback")
        check_cancel(callback, "polygonize")
        polygonize_stage(state, density, rng)
        check_cancel(callback, "dents")
        dents_stage(state, remove_dents)
        if extend:
            check_cancel(callback, "extension")
            minimum = state["minimum"] if np.isfinite(state["minimum"]) else state["iso"] - 1.0
            sampler = BlockSampler(source, state["chunks"], minimum)
            extension_stage(state, sampler, state["iso"], state["spacing"], density)
        metadata = stage_metadata("midsurface", state["iso"], state["plates"], state["lam"], state["dropped"],
                                  state["spacing"], source.shape, threshold_method=state["threshold_method"])
        metadata.update({"extend": bool(extend), "remove_dents": bool(remove_dents), "density": density,
                         "chunks": list(state["chunks"]), "halo": state["halo"].tolist()})
        shell = shell_of_source(source, state["iso"], state["spacing"])
        return assemble(state, metadata, shell)[0]
    finally:
        _cleanup(source)


def chunked_voxels(volume: Any, *, chunks: tuple[int, int, int], **options: Any) -> MedialAxis:
    """The medial voxels of a volume by blocks (``method="voxels"``)."""
    from medialaxis.volume.polygonize import classify_voxels
    from medialaxis.volume.voxel_table import voxel_table

    state = chunked_medial_voxels(volume, chunks=chunks, **options)
    source = state["source"]
    try:
        medial, grid, plates = state["medial"], state["grid"], state["plates"]
        dropped = dropped_report(medial, plates, state["lam"])
        kind = classify_voxels(voxel_table(medial.voxels, grid.shape), medial.voxels)
        metadata = stage_metadata("voxels", state["iso"], plates, state["lam"], dropped, state["spacing"], source.shape,
                                  threshold_method=state["threshold_method"])
        metadata.update({"chunks": list(state["chunks"]), "halo": state["halo"].tolist()})
        return MedialAxis(
            grid.physical(medial.voxels), medial.radius,
            extras={"position": medial.position, "normal": medial.normal, "voxel_kind": kind},
            metadata=metadata, shape=shell_of_source(source, state["iso"], state["spacing"]),
        )
    finally:
        _cleanup(source)
