"""The axis tour (walk around the axis) and its compiled alignment kernel."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from medialaxis.compare import _kernels
from medialaxis.compare.tour import N_TOUR, outer_face, tour_context

# A "Y": three limbs of different lengths from node 0.
Y_POINTS = np.array([[0.0, 0.0], [3.0, 0.0], [-1.0, 2.0], [-1.5, -2.5], [1.5, 0.0]])
Y_RADII = np.array([1.0, 0.3, 0.4, 0.5, 0.7])
Y_EDGES = np.array([[0, 4], [4, 1], [0, 2], [0, 3]])


def _rotate(points, angle, mirror):
    c, s = np.cos(angle), np.sin(angle)
    out = points @ np.array([[c, -s], [s, c]]).T
    return out * np.array([1.0, -1.0]) if mirror else out


def test_a_tree_walk_runs_every_edge_once_each_way():
    darts = outer_face(Y_POINTS, Y_EDGES, np.array([1]))
    assert len(darts) == 2 * len(Y_EDGES)
    assert {tuple(d) for d in darts} == {tuple(e) for e in Y_EDGES} | {tuple(e[::-1]) for e in Y_EDGES}
    assert darts[0, 0] == 1  # starts by leaving the start node
    assert np.array_equal(darts[1:, 0], darts[:-1, 1])  # a walk


def test_the_outer_face_is_chosen_when_the_axis_has_a_cycle():
    # A square cycle with a limb outside and a short one inside (a shape with a hole).
    points = np.array([[0, 0], [4, 0], [4, 4], [0, 4], [7, 2], [1, 1]], float)
    edges = np.array([[0, 1], [1, 2], [2, 3], [3, 0], [1, 4], [0, 5]])
    for mirror in (False, True):
        pts = _rotate(points, 0.7, mirror)
        darts = outer_face(pts, edges, np.array([4]))
        nodes = set(darts.ravel().tolist())
        assert 4 in nodes and 5 not in nodes  # the outer limb is walked, the inner one is not
        assert len(darts) == 4 + 2  # the cycle once, the outer limb both ways


def test_histograms_sum_to_one_and_the_walk_goes_out_and_back():
    h, r, p = tour_context(Y_POINTS, Y_RADII, Y_EDGES, 2.0, np.array([1]), n_samples=40)
    assert h.shape == (40, 60) and np.allclose(h.sum(axis=1), 1.0) and (h >= 0).all()
    assert r.min() >= Y_RADII.min() / 2 - 1e-12 and r.max() <= Y_RADII.max() / 2 + 1e-12
    half_step = np.linalg.norm(np.diff(Y_POINTS[Y_EDGES], axis=1), axis=2).sum() * 2 / 40 / 2
    # Samples sit half a step after the start (the tip of limb 1) and half a step before coming back.
    assert np.allclose([np.linalg.norm(p[0] - Y_POINTS[1]), np.linalg.norm(p[-1] - Y_POINTS[1])], half_step)


def test_a_single_point_is_one_sample():
    h, r, p = tour_context(np.array([[2.0, 3.0]]), np.array([1.5]), np.empty((0, 2), np.int64), 3.0, np.array([0]))
    assert h.shape == (1, 60) and r.tolist() == [0.5] and p.tolist() == [[2.0, 3.0]]


@settings(max_examples=25, deadline=None)
@given(angle=st.floats(-np.pi, np.pi), scale=st.floats(0.1, 10), mirror=st.booleans(), seed=st.integers(0, 1000))
def test_invariant_under_similarity_and_renumbering(angle, scale, mirror, seed):
    """The same samples whatever the pose and numbering; a mirror image gives the mirrored walk's histograms."""
    rng = np.random.default_rng(seed)
    perm = rng.permutation(len(Y_POINTS))
    inv = np.argsort(perm)
    moved = _rotate(Y_POINTS, angle, False)[perm] * scale + rng.normal(size=2)
    edges = inv[Y_EDGES][rng.permutation(len(Y_EDGES))]
    starts = inv[[1, 2]]  # two candidates: the walk picks the same one
    base = tour_context(Y_POINTS, Y_RADII, Y_EDGES, 2.0, np.array([1, 2]))
    pose = moved * np.array([1.0, -1.0]) if mirror else moved
    got = tour_context(pose, Y_RADII[perm] * scale, edges, 2.0 * scale, starts)
    want = tour_context(Y_POINTS * np.array([1.0, -1.0]), Y_RADII, Y_EDGES, 2.0, np.array([1, 2])) if mirror else base
    assert np.allclose(got[0], want[0], atol=1e-9) and np.allclose(got[1], want[1] * 1.0, atol=1e-9)


def _random_tours(rng, n_samples, versions=2, bins=60):
    h = rng.random((versions, n_samples, bins)) ** 3
    h /= h.sum(axis=2, keepdims=True)
    return h, rng.uniform(0.05, 0.5, (versions, n_samples))


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("na, nb", [(N_TOUR, N_TOUR), (20, 33), (1, 12)])
def test_compiled_alignment_matches_reference_and_is_symmetric(seed, na, nb):
    rng = np.random.default_rng(seed)
    (ha, ra), (hb, rb) = _random_tours(rng, na), _random_tours(rng, nb)
    packed = _kernels.pack_tour([ha, hb], [ra, rb], [0.0, 0.0])
    forward = _kernels.tour_distances(*packed, np.array([0]), np.array([1]), 0.3)[0]
    backward = _kernels.tour_distances(*packed, np.array([1]), np.array([0]), 0.3)[0]
    assert forward == backward  # exactly symmetric
    ref_ab = _kernels.tour_match_reference(ha, ra, hb, rb, 0.3)[0]
    ref_ba = _kernels.tour_match_reference(hb, rb, ha, ra, 0.3)[0]
    # The kernel aligns the pair in an order fixed by content: it equals the reference in one of the two orders.
    assert any(forward == pytest.approx(ref, rel=1e-9) for ref in (ref_ab, ref_ba))
    assert forward > 0


def test_alignment_is_zero_on_itself_and_finds_a_rotated_start():
    rng = np.random.default_rng(7)
    h, r = _random_tours(rng, N_TOUR)
    shifted = np.roll(h, -16, axis=1), np.roll(r, -16, axis=1)  # the same walk started 16 samples later
    packed = _kernels.pack_tour([h, h.copy(), shifted[0]], [r, r.copy(), shifted[1]], [0.0] * 3)
    d = _kernels.tour_distances(*packed, np.array([0, 0]), np.array([1, 2]), 0.3)
    assert d[0] == 0.0 and d[1] < 1e-12
    value, va, vb, pairs = _kernels.tour_match_reference(h, r, shifted[0], shifted[1], 0.3)
    assert value < 1e-12 and (va, vb) == (0, 0) and pairs[0] == (0, N_TOUR - 16)
    # The gap bounds the cost: skipping every sample of both costs 2 * gap per mean sample.
    far = _random_tours(np.random.default_rng(8), N_TOUR)
    packed = _kernels.pack_tour([h, far[0]], [r, far[1]], [0.0, 0.0])
    assert 0 < _kernels.tour_distances(*packed, np.array([0]), np.array([1]), 0.3)[0] <= 2 * 0.3 + 1e-12


@pytest.mark.parametrize("seed", range(3))
def test_closed_versions_are_charged_their_closing_gain(seed):
    """Versions 4-5 (the closed shapes) count with CLOSING_PENALTY times the larger gain; reference agrees."""
    rng = np.random.default_rng(seed)
    (ha, ra), (hb, rb) = _random_tours(rng, N_TOUR, versions=6), _random_tours(rng, N_TOUR, versions=6)
    hb[4:], rb[4:] = ha[4:], ra[4:]  # the closed shapes are equal: that comparison costs only the charge

    def kernel(ga, gb):
        packed = _kernels.pack_tour([ha, hb], [ra, rb], [ga, gb])
        return _kernels.tour_distances(*packed, np.array([0]), np.array([1]), 0.3)[0]

    # Only the shapes as given: the least over their two groups, each aligned separately.
    alone = _kernels.tour_match_reference(ha[:4], ra[:4], hb[:4], rb[:4], 0.3)[0]
    assert min(
        _kernels.tour_match_reference(ha[g:g + 2], ra[g:g + 2], hb[g:g + 2], rb[g:g + 2], 0.3)[0] for g in (0, 2)
    ) == pytest.approx(alone, rel=1e-12)
    # The kernel aligns in an order fixed by content (see above): the other order's value may be the one.
    alone_ba = _kernels.tour_match_reference(hb[:4], rb[:4], ha[:4], ra[:4], 0.3)[0]
    kernel_alone = kernel(5.0, 0.0)
    assert any(kernel_alone == pytest.approx(ref, rel=1e-9) for ref in (alone, alone_ba)) and kernel_alone > 0.05
    for ga, gb in ((0.0, 0.01), (0.02, 0.005), (0.3, 0.1)):
        charge = _kernels.CLOSING_PENALTY * max(ga, gb)
        assert kernel(ga, gb) == pytest.approx(min(kernel_alone, charge), rel=1e-9) == kernel(gb, ga)
        value, va, vb, _ = _kernels.tour_match_reference(ha, ra, hb, rb, 0.3, ga, gb)
        assert value == pytest.approx(min(alone, charge), rel=1e-9) and (va >= 4) == (charge < alone)


def test_abandoning_hopeless_starts_keeps_the_least_alignment():
    """The row bound prunes only starts that cannot win: the value equals the one found without it."""
    rng = np.random.default_rng(11)
    for _ in range(20):
        (ha, ra), (hb, rb) = _random_tours(rng, N_TOUR, versions=1), _random_tours(rng, N_TOUR, versions=1)
        cost = _kernels._tour_costs(np.sqrt(ha[0]), ra[0], (ha[0]).sum(1), np.sqrt(hb[0]), rb[0], (hb[0]).sum(1))
        table = np.empty((N_TOUR + 1, N_TOUR + 1))
        exact = _kernels._cyclic_align(cost, N_TOUR, 0.3, 8, 16, table, np.inf)
        assert np.isfinite(exact)
        assert _kernels._cyclic_align(cost, N_TOUR, 0.3, 8, 16, table, exact * 1.000001) == exact
        assert _kernels._cyclic_align(cost, N_TOUR, 0.3, 8, 16, table, exact) == np.inf  # nothing below the bound
