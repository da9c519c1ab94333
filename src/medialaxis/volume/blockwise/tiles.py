"""The mid-surface of a large volume meshed block by block, on the workers.

Each block's medial voxels wait in a folder (:func:`store_sheet`). A block
then meshes a *window* of the sheet, its core plus a halo of the
neighbouring blocks' voxels, with the whole route's stages
(:func:`~medialaxis.volume.sheet.polygonize.polygonize`, dents, extension), and
keeps what its core owns (:func:`mesh_block`):

* the vertices whose medial voxel is in the core (an extension vertex goes
  with the vertex it extends), named by their voxel's volume index;
* the faces whose first vertex (smallest name) is in the core.

The window decides as the whole sheet does wherever nothing outside it
reaches: the pick order hashes each voxel's index
(:func:`~medialaxis.volume.sheet.polygonize.pick_hash`), vertices are numbered in
that order, and every later stage looks a few vertices around.
:func:`~medialaxis.volume._kernels.subsample_certainty` proves the picks
near the core are the whole sheet's; where they are not, the block reads a
wider window. The pieces are joined by their vertex names
(:mod:`~medialaxis.volume.blockwise.stitch`): no seam, the same mesh as the whole
sheet gives.
"""

from __future__ import annotations

import dataclasses
import math
import threading
import time
from pathlib import Path
from typing import Any

import numpy as np

from medialaxis.errors import InvalidInputError
from medialaxis.volume.blockwise.blocks import Block, BlockSampler
from medialaxis.volume.distance import Grid
from medialaxis.volume.medial import MedialVoxels
from medialaxis.volume.plates import PlateThickness
from medialaxis.volume.sheet.polygonize import polygonize
from medialaxis.volume.sheet.stages import MedialStage, SheetMesh, dents_stage, extension_stage

__all__ = ["SheetPart", "MeshPlan", "store_sheet", "load_sheet", "mesh_block", "forget_window", "vertex_names", "name_voxels",
           "PIECE_FIELDS", "sheet_counts"]

#: Bits per axis of a vertex name (volumes up to 2^20 voxels along an axis).
AXIS_BITS = 20


def vertex_names(voxels: np.ndarray, extension: np.ndarray | bool = False) -> np.ndarray:
    """(n,) int64 names of vertices at volume indices ``voxels`` (an extension vertex: its source's voxel, odd)."""
    v = np.asarray(voxels, np.int64).reshape(-1, 3)
    packed = (v[:, 0] << (2 * AXIS_BITS)) | (v[:, 1] << AXIS_BITS) | v[:, 2]
    return packed * 2 + np.asarray(extension, np.int64)


def name_voxels(names: np.ndarray) -> np.ndarray:
    """(n, 3) volume indices of the voxels named by ``names``."""
    packed = np.asarray(names, np.int64) >> 1
    mask = (1 << AXIS_BITS) - 1
    return np.stack([packed >> (2 * AXIS_BITS), (packed >> AXIS_BITS) & mask, packed & mask], axis=1)


@dataclasses.dataclass(frozen=True)
class SheetPart:
    """What the client learns of one block's medial voxels (they stay in the folder)."""

    index: tuple[int, int, int]
    lo: np.ndarray | None
    hi: np.ndarray | None
    foreground: int
    count: int
    sheet_pairs: int
    dropped_gaps: np.ndarray
    largest_radius: float


def _sheet_path(folder: str, index: tuple[int, ...]) -> Path:
    return Path(folder) / ("sheet_{}_{}_{}.npz".format(*index))


def store_sheet(part: Any, index: tuple[int, int, int], folder: str) -> SheetPart:
    """Write a block's medial voxels (volume indices) to ``folder``; return its counts."""
    medial = part.medial
    if len(medial.voxels):
        np.savez(_sheet_path(folder, index), voxels=medial.voxels.astype(np.int32), position=medial.position,
                 radius=medial.radius, coherence=medial.coherence, normal=medial.normal,
                 distance=medial.distance)
    return SheetPart(index, part.lo, part.hi, int(part.foreground), len(medial.voxels), int(medial.sheet_pairs),
                     np.asarray(medial.dropped_gaps), float(medial.radius.max(initial=0.0)))


def load_sheet(folder: str, indices: list[tuple[int, int, int]], lo: Any = None, hi: Any = None) -> MedialVoxels:
    """The medial voxels of the blocks ``indices`` (inside ``[lo, hi)`` when given), in the volume's C order."""
    parts: dict[str, list[np.ndarray]] = {k: [] for k in ("voxels", "position", "radius", "coherence", "normal",
                                                          "distance")}
    for index in indices:
        path = _sheet_path(folder, index)
        if not path.exists():
            continue
        with np.load(path) as data:
            voxels = data["voxels"].astype(np.int64)
            keep = slice(None) if lo is None else np.all((voxels >= lo) & (voxels < hi), axis=1)
            for key in parts:
                parts[key].append(data[key][keep])
    if not parts["voxels"]:
        return MedialVoxels(np.zeros((0, 3), np.int64), np.zeros((0, 3)), np.zeros(0), np.zeros((0, 3)), np.zeros(0),
                            np.zeros(0))
    cat = {k: np.concatenate(v) for k, v in parts.items()}
    voxels = cat["voxels"].astype(np.int64)
    order = np.lexsort((voxels[:, 2], voxels[:, 1], voxels[:, 0]))
    return MedialVoxels(voxels[order], cat["position"][order], cat["radius"][order],
                        cat["normal"][order], cat["distance"][order], cat["coherence"][order])


@dataclasses.dataclass(frozen=True)
class MeshPlan:
    """What every block needs to mesh its window as the whole sheet would be meshed.

    ``crop`` is the volume index of the whole sheet's crop grid (the
    foreground box less one voxel), ``reach`` the largest sampling radius
    (physical) of any medial voxel, ``halo`` the first window's halo (voxels).
    """

    folder: str
    chunks: tuple[int, int, int]
    shape: tuple[int, int, int]
    crop: np.ndarray
    crop_hi: np.ndarray
    spacing: np.ndarray
    density: float
    seed: int
    plates: PlateThickness
    thickness: float
    lam: float | None
    iso: float
    minimum: float
    extend: bool
    remove_dents: bool
    reach: float
    halo: int
    exact: int


#: The fields of a block's mesh piece (``mesh_{i}_{j}_{k}.npz``).
PIECE_FIELDS = ("names", "order", "points", "radii", "kind", "faces")


#: The margin around a core where the window must decide as the whole sheet, in sampling radii
#: (the faces of the core's vertices, three rings of them for the dent planes), and the room
#: beyond it for the chains of greedy picks (:func:`mesh_plan_halo`).
EXACT_RADII, CHAIN_RADII = 4.0, 5.0


def mesh_plan_halo(reach: float, spacing: np.ndarray, extend_reach: float) -> tuple[int, int]:
    """(halo, exact margin) in voxels: the picks within the margin of the core must be the whole sheet's.

    The margin holds the faces of the core's vertices, their rings for the
    dent planes (three rings of faces at most two radii long) and the
    extension rays along junction lines; the halo adds room for the chains
    of the greedy picks.
    """
    unit = float(spacing.min())
    exact = int(math.ceil(max(EXACT_RADII * reach, extend_reach) / unit)) + 4
    return exact + int(math.ceil(CHAIN_RADII * reach / unit)) + 4, exact


def _neighbours(plan: MeshPlan, lo: np.ndarray, hi: np.ndarray) -> list[tuple[int, int, int]]:
    chunks = np.asarray(plan.chunks)
    first = np.maximum(lo, 0) // chunks
    last = (np.minimum(hi, plan.shape) - 1) // chunks
    return [(a, b, c) for a in range(first[0], last[0] + 1) for b in range(first[1], last[1] + 1)
            for c in range(first[2], last[2] + 1)]


#: The last window meshed in this process (dented and extended) when it was the whole sheet's crop, for
#: the next block whose window is the same: where the windows reach the crop on every side (small
#: volumes, small chunks) every block would mesh the whole sheet again. :func:`forget_window` empties it.
_LAST_WINDOW: dict[str, Any] = {}
_WINDOW_LOCK = threading.Lock()


def forget_window() -> None:
    """Drop the window kept for the next block (the end of a run)."""
    with _WINDOW_LOCK:
        _LAST_WINDOW.clear()


def mesh_block(item: tuple[Block, tuple[int, int, int]], plan: MeshPlan, source: Any) -> dict[str, Any]:
    """Mesh one block's window and write the piece its core owns; returns its counts."""
    started, cpu = time.perf_counter(), time.thread_time()
    block, index = item
    lo, hi = np.array(block.lo), np.array(block.hi)
    halo = plan.halo
    while True:
        wlo = np.maximum(lo - halo, plan.crop)
        whi = np.minimum(hi + halo, plan.crop_hi)
        key = (plan.folder, tuple(wlo.tolist()), tuple(whi.tolist()))
        with _WINDOW_LOCK:
            last = _LAST_WINDOW.get("key") == key and _LAST_WINDOW["value"]
        if last:
            medial, stage, sheet = last
        else:
            medial = load_sheet(plan.folder, _neighbours(plan, wlo, whi), wlo, whi)
            stage = sheet = None
        core = np.all((medial.voxels >= lo) & (medial.voxels < hi), axis=1)
        if not core.any():
            return {"index": index, "vertices": 0, "faces": 0, "halo": halo, "voxels": len(medial.voxels)}
        if sheet is None:
            stage, sheet = _window_mesh(medial, wlo, whi, plan)
        near = np.all((medial.voxels >= lo - plan.exact) & (medial.voxels < hi + plan.exact), axis=1)
        if sheet.mesh.certain[near].all():
            break
        if halo >= 4 * max(plan.chunks):
            raise InvalidInputError(f"the block at {block.lo} cannot mesh its sheet from a window of {halo} voxels "
                                    f"around it; use larger chunks")
        halo *= 2
    assert stage is not None and sheet is not None
    if not last:
        sheet = dents_stage(stage, sheet, plan.remove_dents)
        if plan.extend:
            sampler = BlockSampler(source, plan.chunks, plan.minimum)
            sheet = extension_stage(stage, sheet, sampler, plan.iso, plan.spacing, plan.density)
        if np.array_equal(wlo, plan.crop) and np.array_equal(whi, plan.crop_hi):  # the whole sheet: kept
            with _WINDOW_LOCK:
                _LAST_WINDOW.update(key=key, value=(medial, stage, sheet))
    piece = _owned_piece(stage, sheet, lo, hi)
    path = Path(plan.folder) / ("mesh_{}_{}_{}.npz".format(*index))
    np.savez(path, **piece)
    return {"index": index, "vertices": len(piece["names"]), "faces": len(piece["faces"]), "halo": halo,
            "voxels": len(medial.voxels), "seconds": time.perf_counter() - started,
            "cpu_seconds": time.thread_time() - cpu, "bytes": path.stat().st_size}


def _window_mesh(medial: MedialVoxels, wlo: np.ndarray, whi: np.ndarray,
                 plan: MeshPlan) -> tuple[MedialStage, SheetMesh]:
    """The medial voxels of a window ``[wlo, whi)`` of the sheet and their polygonization."""
    offset = wlo - 1
    local = dataclasses.replace(medial, voxels=medial.voxels - offset)
    grid = Grid(offset, tuple(int(s) for s in whi - wlo + 2), plan.spacing)
    width = np.ceil(plan.reach / plan.spacing).astype(np.int64) + 1
    cut_lo, cut_hi = wlo > plan.crop, whi < plan.crop_hi
    below, above = medial.voxels - wlo, whi - 1 - medial.voxels

    def within(w: np.ndarray) -> np.ndarray:
        return np.any((cut_lo & (below < w)) | (cut_hi & (above < w)), axis=1)

    # the band, and every voxel one of its voxels may remove (a box around it: a superset of the balls)
    band = (within(width), within(2 * width))
    mesh = polygonize(grid, local, density=plan.density, seed=plan.seed, band=band, shift=offset - plan.crop)
    return MedialStage(local, grid, plan.plates, plan.lam), SheetMesh.of(mesh)


def _owned_piece(stage: MedialStage, sheet: SheetMesh, lo: np.ndarray, hi: np.ndarray) -> dict[str, Any]:
    """The vertices (used by a face) and faces of the window that the core ``[lo, hi)`` owns."""
    mesh = sheet.mesh
    picks = mesh.picks
    source = np.concatenate([np.arange(len(picks)), sheet.extended_from])
    where = stage.medial.voxels[picks][source]  # window (crop) index of each vertex's voxel (an extension: its source's)
    at = where + stage.grid.offset
    names = vertex_names(at, np.arange(len(source)) >= len(picks))
    faces = sheet.faces
    used = np.zeros(len(source), bool)
    used[faces.ravel()] = True
    inside = np.all((at >= lo) & (at < hi), axis=1)
    keep = np.flatnonzero(used & inside)
    keep = keep[np.argsort(names[keep])]
    first = names[faces].min(axis=1)
    first_at = name_voxels(first)
    owned = np.all((first_at >= lo) & (first_at < hi), axis=1)
    order = mesh.order_key[source[keep]]
    return {"names": names[keep], "order": order, "points": sheet.points[keep], "radii": sheet.radii[keep],
            "kind": sheet.kind[keep], "faces": names[faces[owned]]}


def sheet_counts(parts: list[SheetPart]) -> tuple[MedialVoxels, Grid | None, int]:
    """The counts of the blocks' medial voxels and the crop grid of the whole foreground (spacing set by the caller)."""
    boxes = [(p.lo, p.hi) for p in parts if p.lo is not None]
    foreground = sum(p.foreground for p in parts)
    counts = MedialVoxels(np.zeros((0, 3), np.int64), np.zeros((0, 3)), np.zeros(0), np.zeros((0, 3)), np.zeros(0),
                          np.zeros(0), sum(p.sheet_pairs for p in parts), np.concatenate([p.dropped_gaps for p in parts]))
    if not boxes or sum(p.count for p in parts) == 0:
        return counts, None, foreground
    lo = np.min([b[0] for b in boxes], axis=0) - 1
    hi = np.max([b[1] for b in boxes], axis=0) + 1
    return counts, Grid(lo, tuple(int(s) for s in hi - lo), np.zeros(3)), foreground
