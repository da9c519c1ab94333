"""Mid-surfaces of volumes larger than memory: the pipeline block by block.

The volume is cut into blocks of ``chunks`` voxels (:mod:`~medialaxis.volume.blockwise.blocks`),
each read with a halo from its source (:mod:`~medialaxis.volume.files.sources`),
on local threads or a Dask cluster (:func:`~medialaxis.core.parallel.run_tasks`).
Passes over the blocks:

1. the iso value, when not given: exact value counts of 8 and 16-bit scans
   (or a 256-bin histogram of float scans, their class sums only without two peaks) give the ISO-50
   value the whole array gives (:func:`~medialaxis.volume.inputs.iso50_counts`, ``iso50_histogram``);
2. one read per block: the lengths of its plate-crossing pairs, its deepest
   voxel, its foreground box and its candidate medial pairs
   (:func:`~medialaxis.volume.blockwise.blocks.scan_block`). The part-wide plate
   thickness then gives ``lam``, and each block's pairs give its medial
   voxels (:func:`~medialaxis.volume.blockwise.blocks.finish_block`), identical to the
   in-memory route's. With a number ``thickness`` the blocks mark their
   medial voxels at once; a part with several nominal thicknesses reads each
   block again to label its plates (:func:`~medialaxis.volume.blockwise.blocks.medial_block`).

Each block's medial voxels are written to a folder (the temporary folder, or
``spill=``, which every worker must see), never gathered: each block then
meshes a window of the sheet on the workers (:func:`~medialaxis.volume.blockwise.tiles.mesh_block`:
polygonization, dents, extension, as the whole route), and the pieces are
joined by their vertex names (:mod:`~medialaxis.volume.blockwise.stitch`) into the
mesh the whole sheet gives, or streamed to a PLY file (``out=``). The
extension rays read the grey values around their ends block by block.

Memory: each running block holds its box (chunk plus halo) at about 40 bytes
per voxel plus the per-voxel arrays of its foreground, and then its window of
the sheet; the client holds the blocks' counts (their pair lengths one block at a time:
:mod:`~medialaxis.volume.blockwise.block_plates`), one plane of the shell, and without ``out=`` the mesh.
"""

from __future__ import annotations

import dataclasses
import math
import os
import shutil
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis._progress import Progress, check_cancel, stage_callback
from medialaxis.core.parallel import check_jobs, check_scheduler, run_tasks
from medialaxis.core.result import MedialAxis
from medialaxis.core.validate import check_number
from medialaxis.errors import EmptyShapeError, InvalidInputError
from medialaxis.volume.blockwise.block_iso import block_iso
from medialaxis.volume.blockwise.block_plates import block_plates
from medialaxis.volume.blockwise.blocks import block_grid, finish_block, halo_voxels, medial_block, scan_block
from medialaxis.volume.blockwise.stitch import check_streamed, join_pieces
from medialaxis.volume.blockwise.tiles import (
    MeshPlan,
    SheetPart,
    forget_window,
    load_sheet,
    mesh_block,
    mesh_plan_halo,
    sheet_counts,
    store_sheet,
)
from medialaxis.volume.distance import Grid
from medialaxis.volume.files.ome_zarr import stream_out
from medialaxis.volume.files.sources import Source, is_zarr_folder, open_source
from medialaxis.volume.inputs import check_spacing
from medialaxis.volume.medial import DEFAULT_LAM_RATIO, MedialVoxels
from medialaxis.volume.plates import DEFAULT_MIN_THICKNESS, PlateThickness
from medialaxis.volume.sheet.polygonize import JUNCTION_SPACING, pick_seed
from medialaxis.volume.sheet.stages import check_range, dropped_report, mesh_result, stage_metadata
from medialaxis.volume.shell import shell_of_source

__all__ = ["DEFAULT_CHUNK", "CHUNKED_VOXELS", "check_chunks", "check_out", "chunked_medial_voxels", "chunked_midsurface",
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


def _plates(scans: list[Any], thickness: Any, lam: Any, spacing: np.ndarray) -> tuple[PlateThickness, float | None, np.ndarray | None]:
    """Part-wide plate thickness, ``lam`` and the nominal thicknesses (None: one thickness) from the first pass."""
    unit = float(spacing.min())
    lam_value = None if lam is None else check_number(lam, "lam", positive=True)
    if thickness is None:
        lower, upper = DEFAULT_MIN_THICKNESS * unit, np.inf
    else:
        lower, upper = check_range(thickness)
    plates, nominal = block_plates(scans, lower, upper, unit)  # one block's gaps in memory at a time
    if len(nominal) > 1:
        return plates, lam_value, nominal
    return plates, (DEFAULT_LAM_RATIO * plates.value if lam_value is None else lam_value), None


def _stored(item: tuple[Any, tuple[int, int, int]], folder: str, fn: Callable[..., Any], *args: Any) -> SheetPart:
    """``fn(item[0], *args)``'s medial voxels written to ``folder`` (a worker's task): the sheet stays out of the client."""
    return store_sheet(fn(item[0], *args), item[1], folder)


@dataclasses.dataclass(frozen=True)
class BlockVoxels:
    """What the medial-voxel passes leave: the source, the levels and plates found, the blocks' voxels on disk.

    ``medial`` holds the counts only (the voxels wait in the folder, one
    file per block of ``items``); ``parts`` describe each block's share;
    ``run`` runs tasks where the blocks ran (threads or the cluster).
    """

    source: Source
    iso: float
    threshold_method: str
    minimum: float
    spacing: np.ndarray
    grid: Grid
    medial: MedialVoxels
    plates: PlateThickness
    lam: float | None
    chunks: tuple[int, int, int]
    halo: np.ndarray
    parts: list[SheetPart]
    items: list[Any]
    run: Callable[..., list[Any]]

    @property
    def thickness(self) -> float:
        return float(self.plates.value)


def chunked_medial_voxels(
    volume: Any, *, chunks: tuple[int, int, int], iso: Any = None, thickness: Any = None, lam: Any = None,
    spacing: Any = None, raw_shape: Any = None, raw_dtype: Any = None, scheduler: Any = None, n_jobs: int | None = None,
    callback: Callable[[Progress], Any] | None = None, show_progress: bool | None = None, folder: str,
    method: str = "midsurface",
) -> BlockVoxels:
    """Passes 1-3: the medial voxels of a volume, block by block, each block's written to ``folder``."""
    check_scheduler(scheduler)
    check_jobs(n_jobs)
    source = open_source(volume, raw_shape=raw_shape, raw_dtype=raw_dtype)
    try:
        spacing = check_spacing(spacing, source.spacing)
        chunks = tuple(min(int(c), int(s)) for c, s in zip(chunks, source.shape))
        limit = int(max(chunks))
        blocks = block_grid(source.shape, chunks)  # type: ignore[arg-type]
        items = [(b, tuple(int(lo) // int(c) for lo, c in zip(b.lo, chunks))) for b in blocks]

        jobs = _local_jobs(n_jobs, chunks)

        heard = stage_callback(callback, method)  # the passes and their blocks

        def run(fn: Callable[..., Any], items: list[Any], *args: Any, desc: str) -> list[Any]:
            check_cancel(heard, desc)
            return run_tasks(fn, items, *args, scheduler=scheduler, n_jobs=jobs, desc=desc,
                             show_progress=show_progress, callback=heard)

        iso_value, minimum, threshold_method = block_iso(source, blocks, iso, run)
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
            parts = run(_stored, items, folder, medial_block, source, iso_value, spacing, halo, lam_value, plates, None,
                        limit, desc="medial voxels")
        else:
            first = np.full(3, min(FIRST_HALO, limit), np.int64)
            lower = DEFAULT_MIN_THICKNESS * unit if thickness is None else float(thickness[0])
            shortest = 1.5 * unit if lam is None else min(check_number(lam, "lam", positive=True), 1.5 * unit)
            # the first pass's pairs wait in the folder, not in the client
            scans = run(scan_block, blocks, source, iso_value, spacing, first, lower, shortest, limit, folder,
                        desc="medial voxels")
            _check_foreground(sum(s.foreground for s in scans), source, iso_value)
            plates, lam_value, nominal = _plates(scans, thickness, lam, spacing)
            depth = max(s.depth for s in scans)
            halo = halo_voxels(depth, spacing, nominal is not None)
            if nominal is None:  # one thickness: the first pass's pairs give the medial voxels
                parts = run(_stored, [(scan, i) for scan, (_, i) in zip(scans, items)], folder, finish_block,
                            lam_value, plates, unit, desc="medial voxels")
            else:  # several: each block labels its plates, reading itself again
                del scans
                _check_halo(halo, chunks, source.shape)
                parts = run(_stored, items, folder, medial_block, source, iso_value, spacing, halo, lam_value, plates,
                            nominal, limit, depth, desc="plate labels")
        medial, grid, foreground = sheet_counts(parts)
        _check_foreground(foreground, source, iso_value)
        if grid is None:
            what = f"lam={lam_value:g}" if lam_value is not None else f"plates {plates.lower:g} to {plates.upper:g} thick"
            raise EmptyShapeError(f"no medial voxel for {what}: the thickness or lam is larger than the part allows")
        grid = Grid(grid.offset, grid.shape, spacing)
        if nominal is not None:  # marks the result as judged per plate (labels live in the blocks)
            plates = PlateThickness(plates.value, plates.lower, plates.upper, np.zeros(0), ranged=True)
        return BlockVoxels(source, iso_value, threshold_method, minimum, spacing, grid, medial, plates, lam_value,
                           chunks, halo, parts, items, run)  # type: ignore[arg-type]
    except BaseException:
        _cleanup(source)
        raise


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


def _decompressed(source: Source) -> int | None:
    """Bytes of the temporary file a compressed scan (NRRD, ``.nii.gz``) was decompressed to once, or None."""
    return getattr(source, "decompressed", None)


def _cleanup(source: Source) -> None:
    folder = getattr(source, "cleanup", None)
    if folder:
        shutil.rmtree(folder, ignore_errors=True)


def check_out(out: Any) -> None:
    """``out`` is None or a ``.ply`` or ``.zarr`` path (the formats the mesh streams to)."""
    if out is not None:
        check_streamed(out)


def _sheet_folder(spill: Any) -> str:
    """A new folder for the blocks' sheets and meshes, in ``spill`` (a folder every worker sees) or the temp folder."""
    if spill is not None and not Path(spill).is_dir():
        raise InvalidInputError(f"spill must be an existing folder (that every worker sees), got {str(spill)!r}")
    return tempfile.mkdtemp(prefix="medialaxis-sheet-", dir=None if spill is None else str(spill))


def _mesh_plan(state: BlockVoxels, folder: str, density: float, rng: Any, extend: bool, remove_dents: bool) -> MeshPlan:
    spacing, plates, grid = state.spacing, state.plates, state.grid
    largest = max(p.largest_radius for p in state.parts)
    reach = max(density * largest, 1.5 * float(spacing.max())) * JUNCTION_SPACING
    plate = 2.0 * largest if plates.local else float(state.thickness)
    extend_reach = 1.5 * plate + 2.0 * density * (largest if plates.local else 0.5 * float(state.thickness))
    halo, exact = mesh_plan_halo(reach, spacing, extend_reach)
    minimum = state.minimum if np.isfinite(state.minimum) else state.iso - 1.0
    return MeshPlan(folder, tuple(state.chunks), tuple(state.source.shape), grid.offset,
                    grid.offset + np.array(grid.shape), spacing, density, pick_seed(rng),
                    plates, float(state.thickness), state.lam, float(state.iso), float(minimum), bool(extend),
                    bool(remove_dents), float(reach), int(halo), int(exact))


def chunked_midsurface(volume: Any, *, chunks: tuple[int, int, int], extend: bool = True, remove_dents: bool = True,
                       density: float = 1.0, rng: Any = 0, out: Any = None, spill: Any = None,
                       **options: Any) -> MedialAxis:
    """The mid-surface of a volume by blocks (options of :func:`chunked_medial_voxels`).

    Each block meshes a window of the sheet on the workers
    (:func:`~medialaxis.volume.blockwise.tiles.mesh_block`); the pieces are joined by
    their vertex names (:mod:`~medialaxis.volume.blockwise.stitch`), or with ``out``
    (a ``.ply`` path or a ``.zarr`` group) streamed there block by block, and the result
    then holds no mesh (``metadata["written"]``, ``["vertices"]``, ``["faces"]``).
    """
    density = check_number(density, "density", positive=True)
    check_out(out)
    folder = _sheet_folder(spill)
    source = None
    try:
        started = time.perf_counter()
        state = chunked_medial_voxels(volume, chunks=chunks, folder=folder, **options)
        source = state.source
        medial_seconds = time.perf_counter() - started
        dropped = dropped_report(state.medial, state.plates, state.lam)
        plan = _mesh_plan(state, folder, density, rng, extend, remove_dents)
        items = [item for item, part in zip(state.items, state.parts) if part.count]
        counts = state.run(mesh_block, items, plan, source, desc="mesh")
        metadata = stage_metadata("midsurface", state.iso, state.plates, state.lam, dropped,
                                  state.spacing, source.shape, threshold_method=state.threshold_method)
        metadata.update({"extend": bool(extend), "remove_dents": bool(remove_dents), "density": density,
                         "chunks": list(state.chunks), "halo": state.halo.tolist(),
                         "mesh_halo": max(c["halo"] for c in counts), "decompressed": _decompressed(source),
                         "blocks": _block_figures(state, counts, folder),
                         "timings": _block_timings(counts, medial_seconds, time.perf_counter() - started)})
        shell = shell_of_source(source, state.iso, state.spacing)
        if out is not None:
            vertices, faces = stream_out(out, folder, counts, state.chunks, [i for _, i in state.items], source,
                                         state.spacing)
            metadata.update({"written": str(out), "vertices": vertices, "faces": faces})
            return MedialAxis(np.zeros((0, 3)), np.zeros(0), metadata=metadata, shape=shell)
        points, radii, kind, faces = join_pieces(folder, [c["index"] for c in counts if c["vertices"] or c["faces"]])
        return mesh_result(points, radii, kind, faces, metadata, shell)
    finally:
        forget_window()
        if source is not None:
            _cleanup(source)
        shutil.rmtree(folder, ignore_errors=True)


def _block_figures(state: BlockVoxels, counts: list[dict[str, Any]], folder: str) -> dict[str, int]:
    """Sizes per block (for planning a cluster): blocks, bytes of the sheets and pieces, medial voxels."""
    sheets = sum(f.stat().st_size for f in Path(folder).glob("sheet_*.npz"))
    return {"blocks": len(state.items), "sheet_blocks": len(counts), "sheet_bytes": sheets,
            "piece_bytes": int(sum(c["bytes"] for c in counts)), "medial_voxels": int(sum(p.count for p in state.parts))}


def _block_timings(counts: list[dict[str, Any]], medial_seconds: float, seconds: float) -> dict[str, float]:
    """Seconds of the two passes (wall clock), and the mesh pass's blocks summed (wall clock and CPU)."""
    return {"medial": medial_seconds, "mesh": seconds - medial_seconds,
            "mesh_blocks": float(sum(c["seconds"] for c in counts)),
            "mesh_blocks_cpu": float(sum(c["cpu_seconds"] for c in counts)), "total": seconds}


def chunked_voxels(volume: Any, *, chunks: tuple[int, int, int], spill: Any = None, **options: Any) -> MedialAxis:
    """The medial voxels of a volume by blocks (``method="voxels"``)."""
    from medialaxis.volume.regions import VOXEL_KINDS
    from medialaxis.volume.sheet.polygonize import classify_voxels
    from medialaxis.volume.voxel_table import voxel_table

    folder = _sheet_folder(spill)
    source = None
    try:
        state = chunked_medial_voxels(volume, chunks=chunks, folder=folder, method="voxels", **options)
        source = state.source
        grid, plates = state.grid, state.plates
        medial = load_sheet(folder, [i for _, i in state.items])
        medial = MedialVoxels(medial.voxels - grid.offset, medial.position, medial.radius, medial.normal,
                              medial.distance, medial.coherence)
        dropped = dropped_report(state.medial, plates, state.lam)
        kind = classify_voxels(voxel_table(medial.voxels, grid.shape), medial.voxels)
        metadata = stage_metadata("voxels", state.iso, plates, state.lam, dropped, state.spacing, source.shape,
                                  threshold_method=state.threshold_method)
        metadata.update({"chunks": list(state.chunks), "halo": state.halo.tolist(), "decompressed": _decompressed(source),
                         "voxel_kinds": VOXEL_KINDS})
        return MedialAxis(
            grid.physical(medial.voxels), medial.radius,
            extras={"position": medial.position, "normal": medial.normal, "voxel_kind": kind},
            metadata=metadata, shape=shell_of_source(source, state.iso, state.spacing),
        )
    finally:
        if source is not None:
            _cleanup(source)
        shutil.rmtree(folder, ignore_errors=True)
