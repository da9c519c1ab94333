"""The compiled pairwise step against its NumPy/SciPy reference."""

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from scipy.optimize import linear_sum_assignment

from medialaxis.compare import _kernels


def _random_signature(rng, e, s):
    radii = rng.uniform(0.01, 0.3, (e, e, s))
    radii = (radii + radii.transpose(1, 0, 2)[:, :, ::-1]) / 2  # path j->i is path i->j reversed
    lengths = rng.uniform(0.1, 2.0, (e, e))
    lengths = (lengths + lengths.T) / 2
    np.fill_diagonal(lengths, 0.0)
    return radii, lengths, rng.uniform(0.01, 0.5, e)


@given(seed=st.integers(0, 2**32 - 1), na=st.integers(1, 7), nb=st.integers(1, 7))
def test_compiled_pair_matches_reference(seed, na, nb):
    rng = np.random.default_rng(seed)
    a = _random_signature(rng, na, 5)
    b = _random_signature(rng, nb, 5)
    params = (rng.uniform(0, 1), rng.uniform(0, 1), rng.uniform(0, 2))
    packed = _kernels.pack([a[0], b[0]], [a[1], b[1]], [a[2], b[2]])
    got = _kernels.pair_distances(*packed, np.array([0, 1]), np.array([1, 0]), *params)
    want = _kernels.reference_distance(*a, *b, *params)
    assert np.allclose(got, want, rtol=1e-9, atol=1e-12)


@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 9), extra=st.integers(0, 4))
def test_assignment_matches_scipy(seed, n, extra):
    cost = np.random.default_rng(seed).uniform(0, 10, (n, n + extra))
    rows, cols = linear_sum_assignment(cost)
    assert np.isclose(_kernels._assignment(cost), cost[rows, cols].sum())


def test_path_costs_reference_is_zero_on_itself():
    rng = np.random.default_rng(1)
    r, L, _ = _random_signature(rng, 4, 6)
    pc = _kernels.path_costs_reference(r, L, r, L, 0.5)
    for i in range(4):
        for j in range(4):
            assert pc[i, j, i, j] == 0.0
    assert (pc >= 0).all()
