"""One block of a large volume: the exact features and medial voxels of its core.

A block is a box of the volume (its *core*) read with a *halo* of extra
voxels on every side that is inside the volume. The feature transform of the
block (:func:`block_features`) is the in-memory one
(:func:`~medialaxis.volume.distance.feature_transform`) restricted to the
boundary points of the read box: the volume's own border is padded as the
in-memory route pads it, the sides cut through the volume are not. A voxel's
nearest boundary point is then exact whenever it is closer than any point
outside the box can be (the distance to the first voxel past that side).
:func:`scan_block` and :func:`medial_block` check this for every voxel that
their answers depend on and read the block again with a doubled halo when a
voxel fails (a part locally thicker than the halo assumed), so the results
do not depend on the chunking.

What the core's answers depend on:

* the medial test of a voxel uses its own and its six neighbours' nearest
  boundary points: the core plus one voxel;
* with plate labels (a part with several nominal thicknesses), the label of
  a boundary point comes from the pairs of voxels nearest to it (up to the
  largest distance ``D`` away) and from its neighbours 1.5 voxels around:
  a halo of about ``3 D`` plus a few voxels (:func:`halo_voxels`).
"""

from __future__ import annotations

import dataclasses
import os
import tempfile
from typing import Any

import numpy as np
from scipy.spatial import cKDTree

from medialaxis.errors import EmptyShapeError, InvalidInputError
from medialaxis.volume.distance import Features, boundary_points, nearest_boundary
from medialaxis.volume.medial import (
    MedialPairs,
    MedialVoxels,
    judge_pairs,
    medial_pairs,
    medial_voxels,
    pairs_to_voxels,
)
from medialaxis.volume.plates import (
    ANTIPODAL_COS,
    LABEL_RADIUS,
    PlateThickness,
    label_shortest,
    plate_labels,
    plate_pairs,
)

__all__ = ["Block", "block_grid", "halo_voxels", "scan_block", "finish_block", "medial_block", "BlockScan", "BlockMedial", "BlockSampler"]


@dataclasses.dataclass(frozen=True)
class Block:
    """The core ``[lo, hi)`` of one block (volume indices)."""

    lo: tuple[int, int, int]
    hi: tuple[int, int, int]

    @property
    def voxels(self) -> int:
        return int(np.prod(np.subtract(self.hi, self.lo)))

    @property
    def region(self) -> tuple[slice, slice, slice]:
        """The core as slices of the volume."""
        return tuple(slice(a, b) for a, b in zip(self.lo, self.hi))  # type: ignore[return-value]


def block_grid(shape: tuple[int, ...], chunks: tuple[int, int, int]) -> list[Block]:
    """The cores of a regular chunking of ``shape`` (C order)."""
    starts = [range(0, s, c) for s, c in zip(shape, chunks)]
    return [
        Block((a, b, c), (min(a + chunks[0], shape[0]), min(b + chunks[1], shape[1]), min(c + chunks[2], shape[2])))
        for a in starts[0] for b in starts[1] for c in starts[2]
    ]


def halo_voxels(depth: float, spacing: np.ndarray, labels: bool) -> np.ndarray:
    """Halo (voxels per axis) for a part whose voxels are at most ``depth`` from its boundary.

    Without plate labels: ``depth`` plus two voxels (the core's neighbours
    and their nearest boundary points). With labels: three times ``depth``
    plus ``LABEL_RADIUS`` and three voxels.
    """
    reach = (3.0 * depth + LABEL_RADIUS * float(spacing.max())) if labels else depth
    return np.ceil(reach / spacing).astype(np.int64) + (3 if labels else 2)


def _read(source: Any, block: Block, halo: np.ndarray, iso: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Grey values and mask of the block's read box, cropped to its foreground, padded past the volume's border.

    Returns ``(origin, mask, grey, box_hi)``: ``origin`` is the volume index of
    ``mask[0, 0, 0]``; ``box_hi`` the end of the read box.
    """
    shape = np.array(source.shape)
    lo = np.maximum(np.array(block.lo) - halo, 0)
    hi = np.minimum(np.array(block.hi) + halo, shape)
    raw = source.read(tuple(slice(int(a), int(b)) for a, b in zip(lo, hi)))
    grey = np.asarray(raw, dtype=np.float32)
    if np.dtype(raw.dtype).kind not in "biu" and not np.all(np.isfinite(grey)):  # integers are finite
        raise InvalidInputError(
            f"the volume contains NaN or infinite values (in voxels {tuple(lo)} to {tuple(hi - 1)} of {source.name})"
        )
    mask = grey > iso
    # pad with background where the box touches the volume's border (the
    # in-memory route pads its crop the same way), not where it cuts the volume
    pad = [(int(a == 0), int(b == s)) for a, b, s in zip(lo, hi, shape)]
    if any(a or b for a, b in pad):  # a block inside the volume is not copied
        mask = np.pad(mask, pad, constant_values=False)
        grey = np.pad(grey, pad, constant_values=np.nan)
    origin = lo - np.array([p[0] for p in pad])
    # crop to the foreground plus one voxel (every crossing edge is inside)
    if mask.any():
        nz = [np.flatnonzero(np.any(mask, axis=tuple(a for a in range(3) if a != k))) for k in range(3)]
        c_lo = np.array([max(n[0] - 1, 0) for n in nz])
        c_hi = np.array([min(n[-1] + 2, s) for n, s in zip(nz, mask.shape)])
        box = tuple(slice(int(a), int(b)) for a, b in zip(c_lo, c_hi))
        mask, grey, origin = mask[box], grey[box], origin + c_lo
    return origin, mask, grey, hi


def block_features(source: Any, block: Block, halo: np.ndarray, iso: float, spacing: np.ndarray,
                   *, reach: Any = 1, workers: int = 1) -> tuple[Features | None, np.ndarray, np.ndarray]:
    """Features of the voxels within ``reach`` of the block's core, from the boundary points of its read box,
    and the distance past which a voxel's answer may be wrong.

    Returns ``(features, margin, box)``: ``margin (n,)`` is, for each
    foreground voxel, the distance to the nearest side of the read box that
    cuts the volume (inf where none does); its nearest boundary point is
    exact when ``distance < margin``. ``box`` is ``(lo, hi)`` of the read box.
    ``features`` is None when the box holds no foreground.
    """
    origin, mask, grey, box_hi = _read(source, block, halo, iso)
    box_lo = np.maximum(np.array(block.lo) - halo, 0)
    if not mask.any():
        return None, np.zeros(0), np.stack([box_lo, box_hi])
    bphys = boundary_points(mask, grey, iso, origin) * spacing
    del grey
    voxels = np.argwhere(mask)
    voxels = voxels[_inside(voxels + origin, np.array(block.lo) - reach, np.array(block.hi) + reach)]
    index = np.full(mask.shape, -1, np.int32)
    index[tuple(voxels.T)] = np.arange(len(voxels), dtype=np.int32)
    del mask
    at = voxels + origin
    if len(bphys):
        distance, nearest = nearest_boundary(cKDTree(bphys), at * spacing, workers=workers)
    else:
        distance, nearest = np.full(len(at), np.inf), np.zeros(len(at), np.int64)
        bphys = np.zeros((1, 3))
    shape = np.array(source.shape)
    low_cut = np.where(box_lo > 0, (at - box_lo) * spacing, np.inf)  # a missing point is at index <= box_lo
    high_cut = np.where(box_hi < shape, (box_hi - 1 - at) * spacing, np.inf)  # ... or >= box_hi - 1
    margin = np.minimum(low_cut.min(axis=1), high_cut.min(axis=1))
    features = Features(origin, index, voxels, distance, bphys[nearest], bphys, spacing, nearest)
    return features, margin, np.stack([box_lo, box_hi])


def _inside(at: np.ndarray, lo: Any, hi: Any) -> np.ndarray:
    return np.all((at >= np.asarray(lo)) & (at < np.asarray(hi)), axis=1)


@dataclasses.dataclass(frozen=True)
class BlockScan:
    """What the first pass learns from one block.

    Attributes
    ----------
    gaps : (g,) float64 ndarray
        Lengths of the plate-crossing pairs owned by the core (lower voxel in it);
        empty once spilled (:meth:`plate_gaps` reads them).
    depth : float
        Largest distance to the boundary in the core (0 without foreground).
    lo, hi : (3,) int64 ndarray or None
        Bounding box of the core's foreground.
    halo : int
        Largest halo the block needed.
    foreground : int
        Foreground voxels in the core.
    pairs : MedialPairs or None
        The candidate medial pairs that mark a core voxel (``chosen`` numbers
        ``voxels``) or are owned by the core (``owned``; ``chosen`` -1 when
        the voxel they mark is in another block).
    voxels : (v, 3) int64 ndarray
        Volume indices of the core voxels the pairs mark.
    distance : (v,) float64 ndarray
    owned : (k,) bool ndarray
    """

    gaps: np.ndarray
    depth: float
    lo: np.ndarray | None
    hi: np.ndarray | None
    halo: int
    foreground: int = 0
    pairs: MedialPairs | None = None
    voxels: np.ndarray | None = None
    distance: np.ndarray | None = None
    owned: np.ndarray | None = None
    spilled: str | None = None

    def spill(self, folder: str) -> BlockScan:
        """The same scan with its pairs and gaps in a file of ``folder`` (the first pass of a large volume keeps
        about 130 bytes per marked voxel until lam is known: 1 GiB at 1024^3 in memory, and 8 bytes
        per plate-crossing pair: 120 MB at 2048^3)."""
        if self.pairs is None or len(self.pairs.gap) == 0:
            return self
        handle, path = tempfile.mkstemp(suffix=".npz", dir=folder)
        os.close(handle)
        arrays = {f.name: getattr(self.pairs, f.name) for f in dataclasses.fields(MedialPairs)
                  if getattr(self.pairs, f.name) is not None}
        np.savez(path, gaps=self.gaps, voxels=self.voxels, distance=self.distance, owned=self.owned, **arrays)
        return dataclasses.replace(self, gaps=np.zeros(0), pairs=None, voxels=None, distance=None, owned=None,
                                   spilled=path)

    def plate_gaps(self) -> np.ndarray:
        """``gaps``, read from the spill file when they wait there (before :meth:`restored` removes it)."""
        if self.spilled is None:
            return self.gaps
        with np.load(self.spilled) as data:
            return data["gaps"]

    def restored(self) -> BlockScan:
        """The scan with its pairs read back from its file (removed)."""
        if self.spilled is None:
            return self
        with np.load(self.spilled) as data:
            fields = {f.name: (data[f.name] if f.name in data.files else None) for f in dataclasses.fields(MedialPairs)}
            voxels, distance, owned = data["voxels"], data["distance"], data["owned"]
        os.remove(self.spilled)
        return dataclasses.replace(self, pairs=MedialPairs(**fields), voxels=voxels, distance=distance, owned=owned,
                                   spilled=None)


def _exact(features: Features, margin: np.ndarray, lo: Any, hi: Any) -> bool:
    need = _inside(features.voxels + features.offset, lo, hi)
    return bool(np.all(features.distance[need] < margin[need]))


def _grow(halo: np.ndarray, limit: int, block: Block, what: str) -> np.ndarray:
    bigger = halo * 2
    if int(bigger.max()) > limit:
        raise InvalidInputError(
            f"the block at {block.lo} needs a halo of more than {limit} voxels to find {what}: the part is thicker "
            f"there than chunks={limit} allows; use larger chunks"
        )
    return bigger


def scan_block(block: Block, source: Any, iso: float, spacing: np.ndarray, halo: np.ndarray, lower: float,
               shortest: float, limit: int, spill: str | None = None) -> BlockScan:
    """First pass: plate-crossing pair lengths, depth, foreground box and candidate medial pairs of one core.

    ``shortest`` is the shortest candidate pair (at most the ``lam`` the
    second half will use): with one nominal thickness the medial voxels come
    from these pairs (:func:`finish_block`) without reading the block again.
    With ``spill`` (a folder) the pairs wait there instead of in memory.
    """
    unit = float(spacing.min())
    lo, hi = np.array(block.lo), np.array(block.hi)
    while True:
        features, margin, _ = block_features(source, block, halo, iso, spacing)
        if features is None:
            return BlockScan(np.zeros(0), 0.0, None, None, int(halo.max()), 0)
        if _exact(features, margin, lo - 1, hi + 1):
            break
        halo = _grow(halo, limit, block, "the nearest boundary of its voxels")
    at = features.voxels + features.offset
    core = _inside(at, lo, hi)
    pairs = medial_pairs(features, min(shortest, label_shortest(lower, unit)))
    owned = core[pairs.p]
    plate = owned & (pairs.cos < -ANTIPODAL_COS) & (pairs.gap > label_shortest(lower, unit))
    gaps = pairs.gap[plate]
    marks = core[pairs.chosen]
    pairs = pairs.subset(marks | owned)
    owned, marks = owned[marks | owned], marks[marks | owned]
    rows, number = np.unique(pairs.chosen[marks], return_inverse=True)
    chosen = np.full(len(pairs.chosen), -1, np.int64)
    chosen[marks] = number
    pairs = dataclasses.replace(pairs, chosen=chosen, p=np.zeros(0, np.int64), q=np.zeros(0, np.int64))
    fg = at[core]
    depth = float(features.distance[core].max(initial=0.0))
    box = (fg.min(axis=0), fg.max(axis=0) + 1) if len(fg) else (None, None)
    scan = BlockScan(gaps, depth, box[0], box[1], int(halo.max()), int(core.sum()), pairs, at[rows],
                     features.distance[rows], owned)
    return scan if spill is None else scan.spill(spill)


def finish_block(scan: BlockScan, lam: float, plates: PlateThickness, unit: float) -> BlockMedial:
    """The medial voxels of a core from its first-pass pairs (one nominal thickness or a number)."""
    scan = scan.restored()
    if scan.pairs is None or scan.voxels is None:
        return BlockMedial(_empty(), scan.lo, scan.hi, scan.foreground)
    keep, sheet = judge_pairs(scan.pairs, lam, plates, plates.value, unit)
    sheet &= scan.owned
    keep &= scan.pairs.chosen >= 0
    found = pairs_to_voxels(scan.pairs, keep, len(scan.voxels))
    dropped = scan.pairs.gap[sheet & ~keep]
    if found is None:
        medial = dataclasses.replace(_empty(), sheet_pairs=int(sheet.sum()), dropped_gaps=dropped)
        return BlockMedial(medial, scan.lo, scan.hi, scan.foreground)
    rows, position, radius, normal, coherence = found
    medial = MedialVoxels(scan.voxels[rows], position, radius, normal, scan.distance[rows], coherence,
                          int(sheet.sum()), dropped)
    return BlockMedial(medial, scan.lo, scan.hi, scan.foreground)


@dataclasses.dataclass(frozen=True)
class BlockMedial:
    """The medial voxels of one core (volume indices) and its share of the counts."""

    medial: MedialVoxels
    lo: np.ndarray | None
    hi: np.ndarray | None
    foreground: int


def medial_block(block: Block, source: Any, iso: float, spacing: np.ndarray, halo: np.ndarray, lam: float | None,
                 plates: PlateThickness, nominal: np.ndarray | None, limit: int, depth: float = 0.0) -> BlockMedial:
    """Second pass: the medial voxels of one core, exactly as the whole volume gives them.

    ``plates`` carries the part-wide thickness figures; with ``nominal``
    (several nominal thicknesses) the block labels its own boundary points;
    ``depth`` is then the part's deepest voxel.
    """
    lo, hi = np.array(block.lo), np.array(block.hi)
    unit = float(spacing.min())
    # labels need exact features out to 2 D past the core (the pairs that
    # label the boundary points the core's voxels are nearest to)
    reach = np.ones(3, np.int64) if nominal is None else np.ceil(2.0 * depth / spacing).astype(np.int64) + 3
    while True:
        if np.any(halo <= reach):
            halo = _grow(halo, limit, block, "the pairs that label its plates")
            continue
        features, margin, _ = block_features(source, block, halo, iso, spacing, reach=reach)
        if features is None:
            return BlockMedial(_empty(), None, None, 0)
        if _exact(features, margin, lo - reach, hi + reach):
            break
        halo = _grow(halo, limit, block, "the nearest boundary of its voxels")
    at = features.voxels + features.offset
    core = _inside(at, lo, hi)
    local = plates
    if nominal is not None:
        p, q, gap = plate_pairs(features, label_shortest(plates.lower, unit))
        local = dataclasses.replace(plates, boundary=plate_labels(features, p, q, gap, nominal))
    try:
        medial = medial_voxels(features, lam, local, counted=core)
    except EmptyShapeError:  # a block without medial voxels; the part may have them elsewhere
        medial = None
    fg = at[core]
    box = (fg.min(axis=0), fg.max(axis=0) + 1) if len(fg) else (None, None)
    if medial is None:
        return BlockMedial(_empty(), box[0], box[1], int(core.sum()))
    where = medial.voxels + features.offset
    keep = _inside(where, lo, hi)
    kept = MedialVoxels(
        voxels=where[keep], position=medial.position[keep], radius=medial.radius[keep], normal=medial.normal[keep],
        distance=medial.distance[keep], coherence=medial.coherence[keep], sheet_pairs=medial.sheet_pairs,
        dropped_gaps=medial.dropped_gaps,
    )
    return BlockMedial(kept, box[0], box[1], int(core.sum()))


def _empty() -> MedialVoxels:
    return MedialVoxels(np.zeros((0, 3), np.int64), np.zeros((0, 3)), np.zeros(0), np.zeros((0, 3)), np.zeros(0),
                        np.zeros(0), 0, np.zeros(0))


class BlockSampler:
    """Trilinear grey values of a volume read block by block (for the extension rays).

    The points are grouped by the block of ``chunks`` they fall in and each
    group reads the box around its points (one voxel more on each side); the
    volume's border is padded with ``cval`` as ``scipy.ndimage.map_coordinates``
    extends an array in ``mode="constant"``.
    """

    def __init__(self, source: Any, chunks: tuple[int, int, int], minimum: float) -> None:
        self.source, self.chunks, self.minimum = source, np.asarray(chunks, np.int64), float(minimum)

    def sample(self, coords: np.ndarray, cval: float) -> np.ndarray:
        from scipy import ndimage

        coords = np.asarray(coords, np.float64).reshape(3, -1)
        out = np.full(coords.shape[1], float(cval), np.float32)  # as map_coordinates gives for a float32 volume
        shape = np.array(self.source.shape)
        base = np.floor(coords.T).astype(np.int64)
        near = np.all((base >= -1) & (base < shape), axis=1)  # farther out: cval
        keys = np.clip(base, 0, shape - 1) // self.chunks
        for key in np.unique(keys[near], axis=0):
            rows = np.flatnonzero(near & np.all(keys == key, axis=1))
            lo = np.clip(base[rows].min(axis=0), 0, shape)
            hi = np.clip(base[rows].max(axis=0) + 2, 0, shape)
            grey = np.asarray(self.source.read(tuple(slice(int(a), int(b)) for a, b in zip(lo, hi))), np.float32)
            pad = [(int(a == 0) * 2, int(b == s) * 2) for a, b, s in zip(lo, hi, shape)]
            grey = np.pad(grey, pad, constant_values=cval)
            local = coords[:, rows] - (lo - np.array([p[0] for p in pad]))[:, None]
            out[rows] = ndimage.map_coordinates(grey, local, order=1, mode="constant", cval=cval)
        return out
