"""The radix argsort of the Voronoi route equals NumPy's stable argsort (the truth here)."""

import numpy as np
import pytest

from medialaxis.mesh.sample._rows import radix_argsort


@pytest.mark.parametrize("high", [1, 7, 1 << 16, 1 << 48, 1 << 62])
def test_integer_keys_with_ties_sort_as_numpy_stable(high):
    keys = np.random.default_rng(high).integers(0, high, 50_000)
    assert np.array_equal(radix_argsort(keys), np.argsort(keys, kind="stable"))


def test_non_negative_floats_sort_by_their_bits():
    rng = np.random.default_rng(1)
    lengths = np.concatenate([rng.random(20_000) * 10.0 ** rng.integers(-12, 6, 20_000), [0.0, 0.0, 1e-300, 5e300]])
    lengths[rng.integers(0, len(lengths), 2000)] = 0.5  # ties
    assert np.array_equal(radix_argsort(lengths.view(np.int64)), np.argsort(lengths, kind="stable"))


@pytest.mark.parametrize("keys", [[], [3], [0, 0, 0], [2, 1, 0], [(1 << 62) + 1, 1 << 62, 0]])
def test_small_inputs(keys):
    keys = np.array(keys, np.int64)
    assert np.array_equal(radix_argsort(keys), np.argsort(keys, kind="stable"))
