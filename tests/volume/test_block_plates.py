"""The chunked route's plate figures from the blocks' gaps, one block's at a time (block_plates).

Truth: ``plate_summary`` and ``nominal_thicknesses`` on all the gaps at once (what the client
computed when it gathered them), and ``np.partition`` for the selection.
"""

from __future__ import annotations

import dataclasses
import os
import tempfile

import numpy as np
import pytest

from medialaxis.errors import EmptyShapeError
from medialaxis.volume.blockwise.block_plates import block_plates, kth_smallest
from medialaxis.volume.blockwise.blocks import BlockScan
from medialaxis.volume.plates import nominal_thicknesses, plate_summary


def _scans(gaps: np.ndarray, cuts: list[int], folder: str, spilled: bool) -> list[BlockScan]:
    """Blocks holding the runs of ``gaps`` between ``cuts``, their gaps in spill files when ``spilled``
    (as :meth:`BlockScan.spill` leaves them: a file with ``gaps``, the scan's own empty)."""
    scans = []
    for part in np.split(gaps, cuts):
        scan = BlockScan(part, 1.0, None, None, 8)
        if spilled and len(part):
            handle, path = tempfile.mkstemp(suffix=".npz", dir=folder)
            os.close(handle)
            np.savez(path, gaps=part)
            scan = dataclasses.replace(scan, gaps=np.zeros(0), spilled=path)
        scans.append(scan)
    return scans


def _gaps(rng: np.random.Generator, kind: str) -> np.ndarray:
    if kind == "one plate":
        return rng.normal(8.0, 0.4, 20_001)
    if kind == "two plates":  # a rib thinner than its wall: two nominal thicknesses
        return np.concatenate([rng.normal(4.0, 0.2, 6_000), rng.normal(10.0, 0.3, 14_000)])
    # lengths on a coarse lattice: many ties, an even count
    return np.round(rng.normal(8.0, 1.0, 30_000) * 4) / 4


@pytest.mark.parametrize("kind", ["one plate", "two plates", "ties"])
@pytest.mark.parametrize("spilled", [False, True])
def test_the_blocks_give_the_figures_of_all_their_gaps(tmp_path, kind, spilled):
    rng = np.random.default_rng(7)
    gaps = _gaps(rng, kind)
    cuts = sorted(rng.choice(len(gaps), 9, replace=False).tolist()) + [len(gaps)]  # the last block is empty
    scans = _scans(gaps, cuts, str(tmp_path), spilled)
    ranges = [(3.0, np.inf), (7.5, 9.25)] + ([(8.0, 8.0)] if kind == "ties" else [])  # 8.0 alone: all ties
    for lower, upper in ranges:
        plates, nominal = block_plates(scans, lower, upper, 1.0)
        whole = plate_summary(gaps, lower, upper, 1.0)
        assert plates.value == whole.value  # bit for bit
        assert (plates.lower, plates.upper, plates.ranged) == (whole.lower, whole.upper, whole.ranged)
        np.testing.assert_array_equal(nominal, nominal_thicknesses(gaps, lower, 1.0))
    assert len(block_plates(scans, 3.0, np.inf, 1.0)[1]) == (2 if kind == "two plates" else 1)


def test_a_part_without_plates_in_range_is_refused_as_the_whole_gaps_refuse_it(tmp_path):
    gaps = np.random.default_rng(1).uniform(5.0, 9.0, 1_000)
    scans = _scans(gaps, [300, 600], str(tmp_path), True)
    with pytest.raises(EmptyShapeError) as whole:
        plate_summary(gaps, 12.0, 20.0, 1.0)
    with pytest.raises(EmptyShapeError) as blocks:
        block_plates(scans, 12.0, 20.0, 1.0)
    assert str(blocks.value) == str(whole.value)
    with pytest.raises(EmptyShapeError, match="has no plates"):
        block_plates(_scans(np.zeros(0), [], str(tmp_path), True), 2.0, np.inf, 1.0)


def test_the_kth_smallest_is_the_partitions():
    rng = np.random.default_rng(3)
    values = np.concatenate([rng.exponential(5.0, 5_000), np.full(500, 8.0), [0.0, -0.0, np.inf, 1e-300, 5e-324]])
    parts = np.array_split(rng.permutation(values), 7)
    ordered = np.sort(values)
    for k in [0, 1, 2, 250, 2_600, 2_800, len(values) - 2, len(values) - 1]:
        assert kth_smallest(lambda: iter(parts), k) == ordered[k]
    with pytest.raises(IndexError):
        kth_smallest(lambda: iter(parts), len(values))
