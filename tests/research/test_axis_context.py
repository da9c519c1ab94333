"""Axis context: a continuous, similarity-invariant description of the axis around its samples."""

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from research.axis_context import N_ANGULAR, axis_context, context_distance_reference

# A "Y": three branches of different lengths and radii, one junction.
POINTS = np.array([[0.0, 0.0], [1.0, 0.2], [2.0, 0.1], [-0.8, 0.9], [-1.5, 1.8], [-0.5, -1.2], [-0.6, -2.5]])
RADII = np.array([0.5, 0.35, 0.1, 0.3, 0.12, 0.4, 0.2])
EDGES = np.array([[0, 1], [1, 2], [0, 3], [3, 4], [0, 5], [5, 6]])


def _distance(a, b):
    return context_distance_reference(a[0], a[1], b[0], b[1], N_ANGULAR)


def test_histograms_are_distributions_and_inputs_untouched():
    points, radii, edges = POINTS.copy(), RADII.copy(), EDGES.copy()
    hist, sample_radii = axis_context(points, radii, edges, 2.0)
    assert np.allclose(hist.sum(axis=1), 1.0) and (hist >= 0).all()
    assert (sample_radii > 0).all() and sample_radii.max() <= RADII.max() / 2.0
    assert np.array_equal(points, POINTS) and np.array_equal(radii, RADII) and np.array_equal(edges, EDGES)


@given(
    angle=st.floats(0, 2 * np.pi), scale=st.floats(0.2, 5.0), mirror=st.booleans(),
    shift=st.tuples(st.floats(-50, 50), st.floats(-50, 50)), seed=st.integers(0, 1000),
)
def test_invariant_under_similarity_and_renumbering(angle, scale, mirror, shift, seed):
    base = axis_context(POINTS, RADII, EDGES, 1.0)
    c, s = np.cos(angle), np.sin(angle)
    rot = np.array([[c, -s], [s, c]]) @ (np.diag([1.0, -1.0]) if mirror else np.eye(2))
    perm = np.random.default_rng(seed).permutation(len(POINTS))
    inverse = np.argsort(perm)
    points = (POINTS @ rot.T * scale + np.array(shift))[perm]
    edges = inverse[EDGES][np.random.default_rng(seed + 1).permutation(len(EDGES))]
    moved = axis_context(points, RADII[perm] * scale, edges, scale)
    assert len(moved[0]) == len(base[0])
    assert _distance(base, moved) < 1e-9  # the mirrored bins are tried too


def test_a_different_axis_is_farther():
    base = axis_context(POINTS, RADII, EDGES, 1.0)
    thinner = axis_context(POINTS, RADII * 0.5, EDGES, 1.0)
    bent = POINTS.copy()
    bent[[4, 6]] = bent[[6, 4]]
    assert _distance(base, thinner) > 0.1 and _distance(base, axis_context(bent, RADII, EDGES, 1.0)) > 0.01


def test_a_single_point_axis_is_a_disc():
    hist, radii = axis_context(np.array([[3.0, 4.0]]), np.array([2.0]), np.empty((0, 2), np.int64), 4.0)
    assert hist.shape == (1, 30) and np.isclose(hist.sum(), 1.0) and radii.tolist() == [0.5]
