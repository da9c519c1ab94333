"""``release_freed_memory`` hands freed heap pages back: the resident size the OS reports drops (the truth)."""

from __future__ import annotations

import sys

import numpy as np
import pytest

from medialaxis.core.arrays import SparseRows
from medialaxis.core.memory import _malloc_trim, release_freed_memory


def _resident_mb() -> float:
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * 4096 / 1e6


@pytest.mark.skipif(not sys.platform.startswith("linux") or _malloc_trim() is None, reason="glibc's malloc_trim only")
def test_freed_small_arrays_leave_the_resident_set():
    blocks = [np.ones(12_000) for _ in range(2000)]  # 96 kB each: under glibc's mmap threshold, in the heap
    after = [np.ones(12_000) for _ in range(3)]  # above them: the heap's top is not free, so free() keeps the pages
    before = _resident_mb()
    del blocks
    kept = _resident_mb()
    release_freed_memory()
    assert kept - _resident_mb() > 0.5 * 2000 * 0.096, (before, kept, _resident_mb())
    assert after[0].sum() == 12_000  # what is still in use stays


def test_release_anywhere_is_harmless():
    release_freed_memory()
    release_freed_memory()


def test_sparse_rows_read_as_the_dense_array_they_stand_for():
    rng = np.random.default_rng(0)
    n, k = 1000, 3
    dense = np.full((n, k), np.nan)
    rows = SparseRows(n, k)
    for _ in range(20):  # settings over each other, read back between them
        index = rng.choice(n, rng.integers(0, 60), replace=False)
        values = rng.normal(size=(len(index), k))
        dense[index], rows[index] = values, values
        ask = rng.integers(0, n, 100)
        np.testing.assert_array_equal(rows[ask], dense[ask])
    np.testing.assert_array_equal(rows[np.arange(n)], dense)
    assert rows[np.zeros(0, np.int64)].shape == (0, k)
