"""Skeleton paths and the previous default distance (benchmarks/research) on shapes with known axes."""

import numpy as np
import pytest
from shapely.geometry import Point, Polygon, box

import medialaxis as mx
from research.path_similarity import match_endpoints, path_signature, previous_default, term_matrices

T_SHAPE = Polygon([(0, 0), (10, 0), (10, 2), (6, 2), (6, 8), (4, 8), (4, 2), (0, 2)])
CROSS = box(0, 4, 12, 6).union(box(5, 0, 7, 10))


def test_t_shape_paths_have_the_limb_lengths_and_half_width():
    sig = path_signature(mx.medial_axis(T_SHAPE), prune=0.1)
    # Everything is divided by the signature's scale; the arm tips (1, 1) and (9, 1) are 8 apart,
    # which gives the unit back. Path lengths: 8 between the arms; an arm tip to the stem tip
    # (5, 7): 4 + 6 less the corner cut at the junction (5, 5/4), about 10.
    unit = 8.0 / sig.chords.max()
    L = sig.lengths * unit
    assert np.allclose(L, L.T)
    assert np.allclose(np.sort(L[np.triu_indices(3, 1)]), [8, 10, 10], atol=0.3)
    # Radius a quarter of the way from one arm tip to the other: the half-width 1.
    arms = np.flatnonzero(np.isclose(sig.chords, sig.chords.max()).any(axis=1))
    assert sig.radii[arms[0], arms[1], sig.radii.shape[2] // 4] * unit == pytest.approx(1.0, abs=0.03)
    assert np.allclose(sig.radii, sig.radii.transpose(1, 0, 2)[:, :, ::-1])  # path j->i is i->j reversed


def test_disc_paths_have_no_length():
    sig = path_signature(mx.medial_axis(Point(0, 0).buffer(3, 64)))
    assert np.all(sig.lengths == 0) and sig.radii.shape[:2] == (2, 2)


def test_match_endpoints_of_itself_is_identity_and_previous_default_is_a_distance():
    sigs = [path_signature(mx.medial_axis(g)) for g in (CROSS, T_SHAPE, CROSS)]
    d, pairs = match_endpoints(sigs[0], sigs[0])
    assert d == 0.0 and pairs == [(i, i) for i in range(len(sigs[0].weights))]
    terms = term_matrices(sigs, n_jobs=2)
    D = previous_default(terms)
    assert np.array_equal(D, D.T) and np.all(np.diag(D) == 0) and D[0, 2] == 0.0 and D[0, 1] > 0.05
    assert terms["paths"][0, 1] == pytest.approx(match_endpoints(sigs[0], sigs[1])[0], rel=1e-9)
