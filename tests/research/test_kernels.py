"""The compiled path and context kernels (benchmarks/research) against their NumPy/SciPy references."""

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from scipy.optimize import linear_sum_assignment

from research import axis_context, path_kernels


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
    packed = path_kernels.pack(*(list(col) for col in zip(a, b)))
    got = path_kernels.pair_distances(*packed, np.array([0, 1]), np.array([1, 0]), *params)
    want = path_kernels.reference_distance(a, b, *params)
    assert np.allclose(got, want, rtol=1e-9, atol=1e-12)


@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 9), extra=st.integers(0, 4))
def test_assignment_matches_scipy(seed, n, extra):
    cost = np.random.default_rng(seed).uniform(0, 10, (n, n + extra))
    rows, cols = linear_sum_assignment(cost)
    assert np.isclose(path_kernels.assignment(cost), cost[rows, cols].sum())


def test_path_costs_reference_is_zero_on_itself():
    r, L, C, B, _ = _random_features(np.random.default_rng(1), 4)
    pc = path_kernels.path_costs_reference(r, L, C, B, r, L, C, B, 0.5, 0.2, 0.3)
    for i in range(4):
        for j in range(4):
            assert pc[i, j, i, j] == 0.0
    assert (pc >= 0).all()


def _random_context(rng, k, n_radial=5, n_angular=6):
    h = rng.uniform(0, 1, (k, n_radial * n_angular)) * (rng.uniform(size=(k, n_radial * n_angular)) < 0.6)
    h[:, 0] += 1e-3
    return h / h.sum(axis=1, keepdims=True), rng.uniform(0.02, 0.3, k)


@given(seed=st.integers(0, 2**32 - 1), ka=st.integers(1, 9), kb=st.integers(1, 9))
def test_compiled_context_matches_reference_and_is_symmetric(seed, ka, kb):
    rng = np.random.default_rng(seed)
    (ha, ra), (hb, rb) = _random_context(rng, ka), _random_context(rng, kb)
    packed = axis_context.pack_context([ha, hb], [ra, rb], 6)
    got = axis_context.context_distances(*packed, np.array([0, 1]), np.array([1, 0]))
    assert got[0] == got[1]  # exactly symmetric
    want = min(axis_context.context_distance_reference(ha, ra, hb, rb, 6), axis_context.context_distance_reference(hb, rb, ha, ra, 6))
    assert np.isclose(got[0], want, rtol=1e-9, atol=1e-12)


def test_context_is_zero_on_itself_and_mirror_reverses_angle_bins():
    ha, ra = _random_context(np.random.default_rng(3), 6)
    mirrored = ha.reshape(6, 5, 6)[:, :, ::-1].reshape(6, 30)
    packed = axis_context.pack_context([ha, mirrored[::-1]], [ra, ra[::-1]], 6)
    got = axis_context.context_distances(*packed, np.array([0, 0]), np.array([0, 1]))
    assert got[0] == 0.0 and abs(got[1]) < 1e-12
