"""The compiled pairwise step against its NumPy/SciPy reference."""

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from scipy.optimize import linear_sum_assignment

from medialaxis.compare import _kernels


def _symmetric_paths(rng, e, s):
    x = rng.uniform(0.01, 0.3, (e, e, s))
    return (x + x.transpose(1, 0, 2)[:, :, ::-1]) / 2  # path j->i is path i->j reversed


def _symmetric(rng, e):
    x = rng.uniform(0.1, 2.0, (e, e))
    x = (x + x.T) / 2
    np.fill_diagonal(x, 0.0)
    return x


def _random_features(rng, e, s=5, b=3):
    return _symmetric_paths(rng, e, s), _symmetric(rng, e), _symmetric(rng, e), _symmetric_paths(rng, e, b), rng.uniform(0.01, 0.5, e)


@given(seed=st.integers(0, 2**32 - 1), na=st.integers(1, 7), nb=st.integers(1, 7))
def test_compiled_pair_matches_reference(seed, na, nb):
    rng = np.random.default_rng(seed)
    a, b = _random_features(rng, na), _random_features(rng, nb)
    params = tuple(rng.uniform(0, 1, 5))
    packed = _kernels.pack(*(list(col) for col in zip(a, b)))
    got = _kernels.pair_distances(*packed, np.array([0, 1]), np.array([1, 0]), *params)
    want = _kernels.reference_distance(a, b, *params)
    assert np.allclose(got, want, rtol=1e-9, atol=1e-12)


@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 9), extra=st.integers(0, 4))
def test_assignment_matches_scipy(seed, n, extra):
    cost = np.random.default_rng(seed).uniform(0, 10, (n, n + extra))
    rows, cols = linear_sum_assignment(cost)
    assert np.isclose(_kernels._assignment(cost), cost[rows, cols].sum())


def test_path_costs_reference_is_zero_on_itself():
    r, L, C, B, _ = _random_features(np.random.default_rng(1), 4)
    pc = _kernels.path_costs_reference(r, L, C, B, r, L, C, B, 0.5, 0.2, 0.3)
    for i in range(4):
        for j in range(4):
            assert pc[i, j, i, j] == 0.0
    assert (pc >= 0).all()
