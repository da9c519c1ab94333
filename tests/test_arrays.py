"""``unique_ints`` against ``np.unique`` (the truth: NumPy's own answer, however slow)."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from medialaxis.core.arrays import unique_ints


@given(arrays(np.int64, st.tuples(st.integers(0, 40), st.integers(1, 3)), elements=st.integers(-50, 50)))
def test_unique_ints_is_numpys_unique(values):
    for nearly_sorted in (False, True):  # the hint picks the sort, never the answer
        out = unique_ints(values, nearly_sorted=nearly_sorted)
        assert out.dtype == values.dtype
        np.testing.assert_array_equal(out, np.unique(values))


def test_unique_ints_of_nothing_and_of_large_keys():
    assert unique_ints(np.zeros(0, np.int64)).shape == (0,)
    keys = np.random.default_rng(0).integers(0, 2**62, 10_000)
    np.testing.assert_array_equal(unique_ints(np.r_[keys, keys[::3]]), np.unique(keys))


def test_unique_ints_of_keys_nearly_in_order():
    rng = np.random.default_rng(1)
    keys = np.sort(rng.integers(0, 2**40, 20_000))
    keys[rng.integers(0, len(keys), 200)] = rng.integers(0, 2**40, 200)  # a few out of place, as after merges
    np.testing.assert_array_equal(unique_ints(keys, nearly_sorted=True), np.unique(keys))
