"""The iso value of a volume read block by block (the chunked route's first pass).

Exact value counts of 8 and 16-bit scans (or a 256-bin histogram of float
scans, their class sums only without two peaks) give the ISO-50 value the
whole array gives (:func:`~medialaxis.volume.inputs.iso50_counts`,
``iso50_histogram``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from medialaxis.core.validate import check_finite
from medialaxis.errors import EmptyShapeError, InvalidInputError
from medialaxis.volume.blockwise.blocks import Block
from medialaxis.volume.files.sources import Source
from medialaxis.volume.inputs import HISTOGRAM_BINS, counted, iso50_counts, iso50_histogram, value_counts

__all__ = ["block_iso"]


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


def block_iso(source: Source, blocks: list[Block], iso: Any, run: Callable[..., list[Any]]) -> tuple[float, float, str]:
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
